//! The rod in time (issue 32): Rothe's method — the equations of motion discretized in time
//! first, every time step a boundary-value problem in the arc length solved by the crate `bvp`'s
//! Lobatto collocation (mesh adapted to its tolerance at every step).
//!
//! The rod's equations of docs/model.md ("The rod in time") with the translational inertia
//! `μ(s)` of module `inertia` and, as an option (`rotary_inertia` = `g0`, default 0), the
//! rotary inertia `j = g0²/b`, at the new time level:
//!
//! ```text
//!     x' = cos φ,  y' = sin φ,  φ' = κ0 + b m,  m' = Gx sin φ − Gy cos φ + j φ_tt,  G' = μ r_tt
//!     x(0) = y(0) = 0,  θ = φ(0) − π/2 = c_s (m(0) + M − c θ_t),  m(1) = 0,  G(1) = 0
//! ```
//!
//! (`c_s` the support's compliance `1/k`, `c` its damper: the viscoelastic foot, `c = 0` is the
//! static model's support; `M` a moment applied to the support). Damping of the rod itself
//! (options, default 0): Kelvin–Voigt, `φ' = κ0 + b m − γ_i κ_t`, and external,
//! `G' = μ (r_tt + γ_e r_t)`, their rates by the trapezoidal rule (docs/model.md). Time: the Newmark average-acceleration rule (trapezoidal rule on
//! `(r, r_t)`: `r_tt = 4/Δt² (r − r̂)`, `r̂ = rⁿ + Δt vⁿ + Δt²/4 aⁿ`, and
//! `vⁿ⁺¹ = vⁿ + Δt/2 (aⁿ + aⁿ⁺¹)`; the foot angle's rate likewise). Its properties: implicit,
//! A-stable, second order, no numerical damping (the linearized rod's energy is conserved
//! exactly; its periods lengthen by `(ωΔt)²/12`), and the constraints (inextensibility, the
//! clamp) hold exactly at every step because each step solves the rod's own equations. The
//! history `r̂` is carried on a uniform grid in `s` and interpolated by cubic Lagrange
//! polynomials. Fixed steps: the error is set by `dt` (second order, so Richardson
//! extrapolation between `dt` and `dt/2` is fourth order). With `time_tol` (default off) the
//! steps adapt to a local error estimate (module `timestep`: Zienkiewicz and Xie's estimate of
//! Newmark's rule, accepted or rejected per step; the scheme stays second order and, for the
//! linearized undamped rod, keeps the energy exactly at every step whatever its length). Each step's Newton iteration starts
//! from the last two solutions extrapolated in time, `2zⁿ − zⁿ⁻¹` at fixed steps and the
//! shape's `zⁿ + (τ/h)(zⁿ − zⁿ⁻¹)` at adaptive ones (`τ` the step tried, `h` the last one;
//! module `rothe`): one iteration per step where the last solution alone took two, the same
//! equations to the same tolerance.
//!
//! Starts from the rest shape (`m ≡ 0`, an equilibrium) with a velocity field `v0(s)`
//! (inextensible: `v0' ⟂ e`; clamped: `v0'(0) = 0`) and `a⁰ = 0`, which is exact for the
//! linearized rod and `O(|v0|²)` off for the nonlinear one; a moment stepped onto the foot at
//! `t = 0` has a nonzero `a⁰` (an inconsistent `a⁰` leaves a velocity error `Δt/2·δa` for good).
//! (A consistent `a⁰` from short Taylor steps of the same BVP was tried: its `1/ε²` amplifies
//! the collocation's tolerance, 1 % of `a` at `ε = Δt/8`.) Released from the equilibrium under
//! a tip force, the interior is in balance and `a⁰ = 0` is consistent, but the trapezoidal rule
//! sees the mean of the force before and after the jump in the first step, which loses energy
//! (1.0 % at 50 steps per period); from then on the energy is kept. At large amplitudes it is
//! not: the nonlinear rod's energy grows from period to period under this rule (×1.95 a period
//! from a first-mode tip velocity 0.3). [`TimeScheme::EnergyMomentum`] (fixed steps only; the
//! default of `free` with fixed steps since 2026-12-04, Newmark's rule staying that of adaptive
//! steps and of `drag`) takes the step's mean force and moment and the moment's balance on the
//! chord of the slopes instead, and keeps the energy at every step whatever the amplitude, the
//! release's first step included; on the linearized rod it is Newmark's rule (docs/model.md,
//! "The energy of a large oscillation").
//!
//! [`drag`]: the foot dragged at a speed with the tip on a flat surface under Coulomb friction,
//! stick, slip and lift-off located in time (its own docs). `free` and `drag` share the step
//! and its history (module `rothe`); `drag` takes steps of any length (its events shorten them)
//! with the positions' history from the last step's solution and the internal force scaled by
//! the step (`Settings::short_steps` there), `free` its fixed steps as before.

use crate::rothe::{check_damping, rest_guess, Foot, Rothe, Settings, TipBc};
use crate::timestep::check_time_tol;
use crate::{Rod, VibrissaError};
use serde::Serialize;

pub use crate::dyndrag::{
    drag, parse_foot_table, read_foot_table, ContactState, DragEventKind, DragSample, DragStats,
    DynDragEvent, DynDragOptions, DynDragResult, DynDragStop, EnergyBalance, SideChange,
    SideSample, TipAlso, Whisk, IMPACT_STEPS,
};
pub use crate::rothe::{DynSample, DynStats};
pub use crate::timestep::{TimeStepControl, TIME_TOL_RANGE};

/// Options of [`free`].
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DynamicsOptions {
    /// Time step (normalized time), in `(0, 1]`.
    pub dt: f64,
    /// End time, in `(0, 1e6]`.
    pub t_end: f64,
    /// Damper of the foot's support `c` (moment per angular velocity), `≥ 0`. Default 0.
    pub foot_damping: f64,
    /// The rod's internal (Kelvin–Voigt) damping `γ_i`, in `[0, 1e6]`: the bending moment
    /// `m = ((κ − κ0) + γ_i κ_t)/b` (a material whose stress is `E(ε + γ_i ε_t)`; every mode of
    /// the linearized rod decays at `γ_i ω²/2`). Default 0.
    pub internal_damping: f64,
    /// External viscous damping `γ_e`, in `[0, 1e6]`: a distributed force `−γ_e μ(s) r_t`
    /// (every mode decays at `γ_e/2`). Default 0.
    pub external_damping: f64,
    /// Rotary inertia: the radius of gyration of the foot's cross-section over the length
    /// `g0 = r(0)/(2L)`, in `[0, 0.1]` (`limits::ROTARY_INERTIA`, as `ModeOptions`'): the rod's
    /// slopes carry the inertia `j = g0²/b` per length (a cone's `μ g²`, module `inertia`), the
    /// moment balance `m' = G × e + j φ_tt`, and the kinetic energy `½∫ j φ_t²` besides
    /// `½∫ μ |r_t|²`. Default 0 (none: the Euler–Bernoulli rod).
    pub rotary_inertia: f64,
    /// A moment `M` applied to the foot's support from `t = 0` on (a step; the follicle's
    /// muscles): the support carries `m(0) + M = kθ + cθ_t`. Finite. Default 0 (no effect
    /// on a clamp).
    pub foot_moment: f64,
    /// A tip force `(fx, fy)` (a dead load) holding the rod in its static state before
    /// `t = 0`, released then: the start is that equilibrium at rest (the interior is in
    /// balance, so `a⁰ = 0` is the consistent start; only the tip's force jumps). Finite.
    /// Default `[0, 0]`: the rest shape.
    pub release_force: [f64; 2],
    /// Intervals of the history grid in `s`, even, in `[20, 100000]`. Default 200.
    pub grid: usize,
    /// Tolerance of each step's collocation, in `[1e-13, 1e-4]`. Default 1e-10.
    pub tol: f64,
    /// Collocation scheme of the steps. Default Lobatto IIIA of order 6.
    #[serde(skip)]
    pub scheme: bvp::Scheme,
    /// Adaptive time steps: the tolerance of each step's local error estimate in the positions
    /// (rod lengths; module `timestep`: `Δt³/12 · max_s |r_ttt|`), in `[1e-14, 1e-1]`;
    /// `dt` is then the first step, a step over the tolerance is tried again shorter, and the
    /// samples are at the steps taken. `None`: fixed steps `dt`. Default `None`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub time_tol: Option<f64>,
    /// The bounds of the adaptive steps' controller (used with `time_tol` only; checked then).
    /// Default [`TimeStepControl::default`].
    pub step_control: TimeStepControl,
    /// The time discretization. `None` (the default): the energy–momentum step with fixed
    /// steps (it keeps the energy of a large motion, where Newmark's rule lets it grow), and
    /// Newmark's rule with adaptive ones (`time_tol`; the energy–momentum step has none);
    /// [`DynamicsOptions::scheme_in_use`] says which.
    pub time_scheme: Option<TimeScheme>,
}

/// How [`free`] steps in time.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum TimeScheme {
    /// Newmark's average-acceleration rule (the trapezoidal rule on `(r, r_t)`): second order,
    /// no numerical damping, the linearized rod's energy kept exactly at every step; the
    /// nonlinear rod's energy grows at large amplitudes (docs/model.md, "The energy of a large
    /// oscillation"). The scheme of adaptive steps and of the drag.
    Newmark,
    /// The energy–momentum step: the step's mean force and moment, the moment's balance on the
    /// chord of the slopes (`rothe::Settings::energy_momentum`): second order, no numerical
    /// damping, the energy kept at every step whatever the amplitude (the support's spring and
    /// damper at the step's mean turn and rate, the rod's dampers at its mean curvature rate
    /// and velocity, so each takes its share exactly). Fixed steps only; the samples' base
    /// force and moment are the step's means. The default of fixed steps.
    EnergyMomentum,
}

impl Default for DynamicsOptions {
    fn default() -> Self {
        DynamicsOptions {
            dt: 0.01,
            t_end: 1.0,
            foot_damping: 0.0,
            internal_damping: 0.0,
            external_damping: 0.0,
            rotary_inertia: 0.0,
            foot_moment: 0.0,
            release_force: [0.0, 0.0],
            grid: 200,
            tol: 1e-10,
            scheme: bvp::Scheme::Lobatto6,
            time_tol: None,
            step_control: TimeStepControl::default(),
            time_scheme: None,
        }
    }
}

impl DynamicsOptions {
    /// Checks every value; the error names it and its valid range.
    pub fn validate(&self) -> Result<(), VibrissaError> {
        let bad = |name: &str, v: f64, r: &str| Err(VibrissaError::range(name, v, r));
        if !(self.dt > 0.0 && self.dt <= 1.0) {
            return bad("dt", self.dt, "(0, 1]");
        }
        if !(self.t_end > 0.0 && self.t_end <= 1e6) {
            return bad("t_end", self.t_end, "(0, 1e6]");
        }
        if !(self.foot_damping >= 0.0 && self.foot_damping.is_finite()) {
            return bad("foot_damping", self.foot_damping, "[0, inf)");
        }
        check_damping(self.internal_damping, self.external_damping)?;
        crate::limits::ROTARY_INERTIA.check("rotary_inertia", self.rotary_inertia)?;
        for (i, f) in self.release_force.iter().enumerate() {
            if !f.is_finite() {
                return bad(["release_force.x", "release_force.y"][i], *f, "finite");
            }
        }
        if !self.foot_moment.is_finite() {
            return bad("foot_moment", self.foot_moment, "finite");
        }
        if !(20..=100_000).contains(&self.grid) || self.grid % 2 == 1 {
            return bad("grid", self.grid as f64, "[20, 100000], even");
        }
        if !(self.tol >= 1e-13 && self.tol <= 1e-4) {
            return bad("tol", self.tol, "[1e-13, 1e-4]");
        }
        if self.time_scheme == Some(TimeScheme::EnergyMomentum) {
            if let Some(t) = self.time_tol {
                return bad(
                    "time_tol",
                    t,
                    "none (fixed steps) with the energy-momentum time scheme",
                );
            }
        }
        check_time_tol(self.time_tol, &self.step_control)
    }

    /// The time scheme [`free`] steps with: `time_scheme` where given, else the
    /// energy–momentum step with fixed steps and Newmark's rule with adaptive ones.
    pub fn scheme_in_use(&self) -> TimeScheme {
        match (self.time_scheme, self.time_tol) {
            (Some(s), _) => s,
            (None, None) => TimeScheme::EnergyMomentum,
            (None, Some(_)) => TimeScheme::Newmark,
        }
    }
}

/// The time series of [`free`].
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DynamicsResult {
    /// The samples, one per step (the start included).
    pub samples: Vec<DynSample>,
    /// Work done.
    pub stats: DynStats,
}

/// β₁ of the uniform clamped–free rod, `ω₁ = β₁²` (Blevins, *Formulas for natural frequency
/// and mode shape*, 1979, table 8-1).
pub const CLAMPED_FREE_BETA1: f64 = 1.87510406871196;

/// The first mode of the uniform clamped–free rod (Blevins, table 8-1) as a velocity field
/// across the rod, `amp` at the tip: a start for [`free`] whose motion is that mode with the
/// frequency `β₁²` (the sample the tests, the example `free_oscillation` and the bench
/// `dynamics` share).
pub fn first_mode_velocity(amp: f64) -> impl Fn(f64) -> [f64; 2] {
    let b = CLAMPED_FREE_BETA1;
    let sigma = (b.cosh() + b.cos()) / (b.sinh() + b.sin());
    let w = move |s: f64| (b * s).cosh() - (b * s).cos() - sigma * ((b * s).sinh() - (b * s).sin());
    let w1 = w(1.0);
    move |s| [amp * w(s) / w1, 0.0]
}

/// The rod of `rod` (its taper, rest curvature, support spring), released at rest in its rest
/// shape (or in its equilibrium under `opts.release_force`, removed at `t = 0`) with the
/// velocity `v0(s) = (vx, vy)`, followed to `opts.t_end` with free tip.
pub fn free(
    rod: &Rod,
    v0: &dyn Fn(f64) -> [f64; 2],
    opts: &DynamicsOptions,
) -> Result<DynamicsResult, VibrissaError> {
    opts.validate()?;
    let energy_momentum = opts.scheme_in_use() == TimeScheme::EnergyMomentum;
    let settings = Settings {
        grid: opts.grid,
        tol: opts.tol,
        scheme: opts.scheme,
        damping: opts.foot_damping,
        internal_damping: opts.internal_damping,
        external_damping: opts.external_damping,
        rotary_inertia: opts.rotary_inertia,
        // adaptive steps may be short: the history and the forces' scale of `drag`; the
        // energy–momentum step takes `rⁿ`, `φⁿ`, `φⁿ'` from the last solution itself
        short_steps: opts.time_tol.is_some() || energy_momentum,
        predict: true,
        remesh: false,
        energy_momentum,
    };
    let grid = Rothe::grid_of(&settings);
    let rest = rest_guess(&rod.profile(1.0), &grid);
    // the start solved once (the static problem: no inertia), the rest shape as its guess
    let mut rothe = Rothe::at_rest(
        rod,
        &settings,
        &rest,
        [0.0, 0.0],
        TipBc::Force(opts.release_force),
    )?;
    rothe.set_velocity(v0)?;
    let dt = opts.dt;
    let mut samples = vec![rothe.sample(0.0)];
    if let Some(tol) = opts.time_tol {
        adaptive(&mut rothe, opts, tol, &mut samples)?;
        return Ok(DynamicsResult {
            samples,
            stats: rothe.stats,
        });
    }
    let steps = (opts.t_end / dt).round().max(1.0) as usize;
    for n in 0..steps {
        let trial = rothe
            .trial(
                dt,
                Foot::at([0.0, 0.0]),
                TipBc::Force([0.0, 0.0]),
                opts.foot_moment,
            )
            .map_err(|e| {
                VibrissaError::solver(
                    format!("time step {} (t = {})", n + 1, (n + 1) as f64 * dt),
                    *e,
                )
            })?;
        rothe.commit(trial);
        samples.push(rothe.sample((n + 1) as f64 * dt));
    }
    Ok(DynamicsResult {
        samples,
        stats: rothe.stats,
    })
}

/// [`free`]'s steps with `time_tol` (module `timestep`): from `dt`, each step accepted when its
/// local error estimate is within `tol`, the next one proposed by `opts.step_control`; the
/// steps end on `t_end` (a rest shorter than two steps is halved), a sample after each.
fn adaptive(
    rothe: &mut Rothe,
    opts: &DynamicsOptions,
    tol: f64,
    samples: &mut Vec<DynSample>,
) -> Result<(), VibrissaError> {
    let c = &opts.step_control;
    let (t_end, mut t) = (opts.t_end, 0.0);
    let mut h = c.first(opts.dt);
    while t_end - t > 1e-12 * t_end.max(1.0) {
        let rest = t_end - t;
        let tau = if rest <= h {
            rest
        } else if rest < 2.0 * h {
            0.5 * rest
        } else {
            h
        };
        let trial = rothe
            .trial(
                tau,
                Foot::at([0.0, 0.0]),
                TipBc::Force([0.0, 0.0]),
                opts.foot_moment,
            )
            .map_err(|e| {
                VibrissaError::solver(format!("the time step from t = {t} by {tau}"), *e)
            })?;
        let rejected;
        (rejected, h) = c.judge(t, tau, rothe.local_error(&trial), tol)?;
        if rejected {
            rothe.stats.rejected_steps += 1;
            continue;
        }
        rothe.commit(trial);
        t = if tau == rest { t_end } else { t + tau };
        samples.push(rothe.sample(t));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Newmark's discrete frequency `ω_h` of `x_{n+1} + x_{n−1} = 2 cos(ω_h Δt) x_n` read off
    /// the tip's samples near the peak, mapped back by the scheme's exact dispersion
    /// `tan(ω_h Δt/2) = ω Δt/2` of the linear oscillator.
    fn frequency_of(r: &DynamicsResult, dt: f64, k: usize) -> f64 {
        let x: Vec<f64> = r.samples.iter().map(|p| p.tip_x).collect();
        let wh = ((x[k + 1] + x[k - 1]) / (2.0 * x[k])).acos() / dt;
        2.0 / dt * (wh * dt / 2.0).tan()
    }

    /// A backward-Euler step (`Rothe::euler_steps`, the impact's steps of `dynamics::drag`)
    /// from the rest shape with a small velocity in the first mode's shape keeps that mode and
    /// takes its energy as the linear oscillator's: `x₁ = Δt v₁`, `v₁ = v₀ − Δt ω² x₁`, so
    /// `E₁ = E₀/(1 + ω²Δt²)` (ω = β₁², β₁ = 1.87510406871196): measured 9.3e-11 and 2.2e-11
    /// relative at Δt = 0.1 and 0.02 (ratios 0.8900, 0.9951; bound 1e-7), where the trapezoidal
    /// step keeps `E₀`. The tip's velocity after it is `v₀/(1 + ω²Δt²)`.
    #[test]
    fn a_backward_euler_step_damps_the_mode_as_the_oscillator() {
        let w1 = CLAMPED_FREE_BETA1.powi(2);
        let settings = Settings::plain(200, 1e-10);
        let rod = Rod::uniform();
        let grid = Rothe::grid_of(&settings);
        let rest = rest_guess(&rod.profile(1.0), &grid);
        for dt in [0.1, 0.02] {
            let mut rothe =
                Rothe::at_rest(&rod, &settings, &rest, [0.0, 0.0], TipBc::Force([0.0, 0.0]))
                    .unwrap();
            rothe.set_velocity(&first_mode_velocity(1e-4)).unwrap();
            let e0 = rothe.sample(0.0).kinetic;
            rothe.euler_steps = 1;
            let free_tip = TipBc::Force([0.0, 0.0]);
            let tr = rothe
                .trial(dt, Foot::at([0.0, 0.0]), free_tip, 0.0)
                .unwrap();
            assert!(tr.euler);
            rothe.commit(tr);
            assert_eq!(rothe.euler_steps, 0);
            let p = rothe.sample(dt);
            let want = 1.0 / (1.0 + w1 * w1 * dt * dt);
            let ratio = (p.kinetic + p.elastic) / e0;
            eprintln!(
                "dt {dt}: energy ratio {ratio}, oscillator {want}, tip vx {}",
                p.tip_vx
            );
            assert!((ratio / want - 1.0).abs() < 1e-7, "{ratio} {want}");
            assert!(
                (p.tip_vx / (1e-4 * want) - 1.0).abs() < 1e-6,
                "{}",
                p.tip_vx
            );
            // the next step is the trapezoidal rule's again: it keeps the energy
            let tr = rothe
                .trial(dt, Foot::at([0.0, 0.0]), free_tip, 0.0)
                .unwrap();
            assert!(!tr.euler);
            rothe.commit(tr);
            let q = rothe.sample(2.0 * dt);
            let after = (q.kinetic + q.elastic) / e0;
            assert!((after / ratio - 1.0).abs() < 1e-7, "{after} {ratio}");
        }
    }

    /// A small velocity in the first mode's shape: the tip's motion has the first frequency
    /// β₁² (β₁ = 1.87510406871196, Blevins table 8-1) up to the time scheme's known dispersion
    /// (measured: 1.2e-9 relative at 50 steps per period), and the undamped scheme keeps the
    /// energy (measured drift 2.7e-9 over a period).
    #[test]
    fn small_oscillation_has_the_first_frequency_and_keeps_its_energy() {
        let w1 = CLAMPED_FREE_BETA1.powi(2);
        let period = 2.0 * std::f64::consts::PI / w1;
        let o = DynamicsOptions {
            dt: period / 50.0,
            t_end: period,
            ..DynamicsOptions::default()
        };
        let r = free(&Rod::uniform(), &first_mode_velocity(1e-4), &o).unwrap();
        assert_eq!(r.samples.len(), 51);
        let w = frequency_of(&r, o.dt, 12);
        assert!((w / w1 - 1.0).abs() < 1e-8, "omega {w}");
        let e0 = r.samples[0].kinetic;
        assert!((e0 - 0.5 * 1e-8 * 0.25).abs() < 1e-12, "{e0}");
        let worst = r.samples.iter().fold(0.0f64, |w, p| {
            w.max(((p.kinetic + p.elastic) / e0 - 1.0).abs())
        });
        eprintln!("omega error {:e}, energy drift {worst:e}", w / w1 - 1.0);
        for p in &r.samples {
            let e = p.kinetic + p.elastic;
            assert!((e / e0 - 1.0).abs() < 1e-7, "t = {}: {e} against {e0}", p.t);
        }
        // after a period the tip is back (x = A sin(ω_h t): ω_h t = 2 atan(π/50)·50 ≠ 2π)
        let wh = 2.0 / o.dt * (w1 * o.dt / 2.0).atan();
        let amp = r.samples[12].tip_x / (wh * 12.0 * o.dt).sin();
        let last = r.samples.last().unwrap();
        let want = amp * (wh * 50.0 * o.dt).sin();
        assert!(
            (last.tip_x - want).abs() < 1e-8 * amp,
            "{} {want}",
            last.tip_x
        );
    }

    /// The largest relative change of the energy `kinetic + elastic` over the samples of a free,
    /// undamped run.
    fn energy_drift(r: &DynamicsResult) -> f64 {
        let e0 = r.samples[0].kinetic + r.samples[0].elastic;
        r.samples.iter().fold(0.0f64, |w, p| {
            w.max(((p.kinetic + p.elastic) / e0 - 1.0).abs())
        })
    }

    /// Over 100 periods of a small first-mode oscillation (tip velocity 1e-3, 25 steps per
    /// period, grid 50, tol 1e-8: 2500 steps) the undamped scheme keeps the energy: measured
    /// 3.0e-6 of it at worst (a walk of the steps' collocation error, signs changing: −5e-8,
    /// +2.6e-7, −1.0e-7, +3.0e-6 at periods 1, 10, 50, 100); asserted 2e-5. The energy is
    /// 1.25e-7, so that is 4e-13 absolute, while the tolerance allows each step an error of
    /// 1e-8 in positions of size 1 (`cargo run --release -p vibrissa --example
    /// free_oscillation -- --energy 1e-3,100,25,50,1e-8`).
    #[test]
    fn a_small_oscillation_keeps_its_energy_over_a_hundred_periods() {
        let r = first_mode_run(TimeScheme::Newmark, 1e-3, 100.0, 25.0, 50, 1e-8);
        assert_eq!(r.samples.len(), 2501);
        let drift = energy_drift(&r);
        eprintln!("energy drift over 100 periods {drift:e}");
        assert!(drift < 2e-5, "{drift:e}");
    }

    /// Open with Newmark's rule (the default of fixed steps until 2026-12-04; still the scheme
    /// of adaptive steps and of the drag; docs/model.md, "The energy of a large oscillation"): from a large first-mode velocity (tip 0.3, tip amplitude about 0.085) the
    /// energy does not stay: it grows by about 1.95 times a period (1.3e-5, 5.8e-5, 1.5e-4, …
    /// 7.6e-2 at periods 1, 2, 3, … 12 at 50 steps per period; the same rate at 100 steps and
    /// at grid 200, tol 1e-10), and the step of period 13 does not converge. Asserted what the
    /// energy–momentum step keeps (the tests below): 1e-6 of the energy over 100 periods.
    #[test]
    #[ignore = "open failure of Newmark's rule: the energy of a large oscillation grows (docs/model.md)"]
    fn a_large_oscillation_keeps_its_energy_over_a_hundred_periods() {
        let r = first_mode_run(TimeScheme::Newmark, 0.3, 100.0, 50.0, 50, 1e-8);
        let drift = energy_drift(&r);
        assert!(drift < 1e-6, "{drift:e}");
    }

    /// A first-mode oscillation of the uniform rod from tip velocity `amp` over `periods`
    /// periods of `n` steps by `time_scheme` on `grid` intervals at collocation `tol`.
    fn first_mode_run(
        time_scheme: TimeScheme,
        amp: f64,
        periods: f64,
        n: f64,
        grid: usize,
        tol: f64,
    ) -> DynamicsResult {
        let period = 2.0 * std::f64::consts::PI / CLAMPED_FREE_BETA1.powi(2);
        let o = DynamicsOptions {
            dt: period / n,
            t_end: periods * period,
            grid,
            tol,
            time_scheme: Some(time_scheme),
            ..DynamicsOptions::default()
        };
        free(&Rod::uniform(), &first_mode_velocity(amp), &o).unwrap()
    }

    /// [`first_mode_run`] by the energy–momentum step.
    fn energy_momentum(amp: f64, periods: f64, n: f64, grid: usize, tol: f64) -> DynamicsResult {
        first_mode_run(TimeScheme::EnergyMomentum, amp, periods, n, grid, tol)
    }

    /// The energy–momentum step keeps the energy of the large oscillation that Newmark's rule
    /// does not (tip velocity 0.3, 25 steps per period, grid 50, tol 1e-8): over 20 periods
    /// measured 2.7e-6 of it at worst, a steady loss of 1.4e-7 a period that falls as the
    /// fourth power of the history grid's interval (the slow test below); Newmark's rule at
    /// the same settings is 8.7e-2 off after 10 periods. Asserted 1e-5.
    #[test]
    fn the_energy_momentum_step_keeps_the_energy_of_a_large_oscillation() {
        let r = energy_momentum(0.3, 20.0, 25.0, 50, 1e-8);
        let drift = energy_drift(&r);
        eprintln!("energy drift over 20 periods {drift:e}");
        assert!(drift < 1e-5, "{drift:e}");
    }

    /// The issue's check over 100 periods from the large first-mode velocity (tip 0.3), 25 steps
    /// per period, tol 1e-10: the energy's worst error 1.35e-5, 8.5e-7, 5.3e-8 on grids of 50,
    /// 100, 200 intervals (16 times less at each halving: the history's cubic interpolation in
    /// s, fourth order). Asserted on grid 100: 2e-6, and the fall to grid 200 at least 10 times.
    #[test]
    #[ignore = "slow: 5000 steps, about 30 s in debug; the default guard is the 20-period test"]
    fn the_energy_momentum_step_keeps_the_energy_over_a_hundred_periods() {
        let d100 = energy_drift(&energy_momentum(0.3, 100.0, 25.0, 100, 1e-10));
        let d200 = energy_drift(&energy_momentum(0.3, 100.0, 25.0, 200, 1e-10));
        eprintln!("energy drift over 100 periods: grid 100 {d100:e}, grid 200 {d200:e}");
        assert!(d100 < 2e-6, "{d100:e}");
        assert!(d200 < 0.1 * d100, "{d200:e} {d100:e}");
    }

    /// A tapered (0.5), pre-curved (κ0 = 1) rod released from a large tip force (0.5, 0), dt
    /// 0.02, grid 50, tol 1e-8: Newmark's rule fails at step 104 (t = 2.08: Newton's limit on
    /// 5970 nodes, 15 s of CPU in a release build; `vibrissa dynamics free --taper 0.5
    /// --precurvature 1 --release-fx 0.5 --dt 0.02 --t-end 3 --grid 50 --tol 1e-8`), the
    /// energy–momentum step follows it to t = 3 (0.9 s) with the energy within 3.7e-4 of the
    /// stored one (alternating from step to step: the release rings modes the grid of 50
    /// intervals resolves poorly; the first step 5.3e-7). Asserted: to t = 3, within 1e-3.
    #[test]
    fn the_energy_momentum_step_follows_a_large_release_of_a_tapered_curved_rod() {
        let rod = Rod::builder()
            .taper(0.5)
            .precurvature(1.0, 0.0)
            .build()
            .unwrap();
        let o = DynamicsOptions {
            dt: 0.02,
            t_end: 3.0,
            grid: 50,
            tol: 1e-8,
            release_force: [0.5, 0.0],
            time_scheme: Some(TimeScheme::EnergyMomentum),
            ..DynamicsOptions::default()
        };
        let r = free(&rod, &|_| [0.0, 0.0], &o).unwrap();
        assert_eq!(r.samples.len(), 151);
        let e0 = r.samples[0].elastic;
        for p in &r.samples {
            let e = p.kinetic + p.elastic;
            assert!((e / e0 - 1.0).abs() < 1e-3, "t = {}: {e} against {e0}", p.t);
        }
    }

    /// For the linearized rod the energy–momentum step is Newmark's (the mean force of the
    /// step is the mean of the end forces when the moment's balance is linear), so its
    /// frequency through Newmark's dispersion is β₁² (measured: the period errors of both
    /// schemes 5.2242e-3, 1.3132e-3, 3.2880e-4 at 25, 50, 100 steps per period): at 50 steps
    /// per period from tip velocity 1e-4, within 1e-8.
    #[test]
    fn the_energy_momentum_step_has_newmark_s_dispersion() {
        let w1 = CLAMPED_FREE_BETA1.powi(2);
        let period = 2.0 * std::f64::consts::PI / w1;
        let r = energy_momentum(1e-4, 1.0, 50.0, 200, 1e-10);
        let w = frequency_of(&r, period / 50.0, 12);
        assert!((w / w1 - 1.0).abs() < 1e-8, "omega {w}");
        assert!(energy_drift(&r) < 1e-7, "{}", energy_drift(&r));
    }

    /// The energy–momentum step takes fixed steps only: `time_tol` is refused by name.
    #[test]
    fn the_energy_momentum_step_refuses_adaptive_steps() {
        let o = DynamicsOptions {
            time_scheme: Some(TimeScheme::EnergyMomentum),
            time_tol: Some(1e-8),
            ..DynamicsOptions::default()
        };
        let e = free(&Rod::uniform(), &|_| [0.0, 0.0], &o).unwrap_err();
        assert!(e.to_string().contains("energy-momentum"), "{e}");
        assert!(e.to_string().contains("time_tol"), "{e}");
    }

    /// The three dampers with the energy–momentum step (the rod's at the step's mean curvature
    /// rate and mean velocity, the foot's at its mean rate; settings of
    /// `damping_takes_the_lost_energy`): what the rod loses is what they take, from the first
    /// step on (the step needs no start acceleration, so nothing is missing at t = 0; Newmark's
    /// first step loses 3.2e-3 more). Measured: 9.0e-10 over ten periods while the dampers take
    /// 90 %. Asserted 3e-8, as for Newmark's from step 1.
    #[test]
    fn the_energy_momentum_step_books_every_damper() {
        let w1 = CLAMPED_FREE_BETA1.powi(2);
        let period = 2.0 * std::f64::consts::PI / w1;
        let rod = Rod::builder().support_compliance(0.5).build().unwrap();
        let o = DynamicsOptions {
            dt: period / 25.0,
            t_end: 10.0 * period,
            foot_damping: 0.05,
            internal_damping: 0.02 / w1,
            external_damping: 0.05,
            time_scheme: Some(TimeScheme::EnergyMomentum),
            ..DynamicsOptions::default()
        };
        let r = free(&rod, &first_mode_velocity(1e-3), &o).unwrap();
        let total = |p: &DynSample| {
            p.kinetic + p.elastic + p.dissipated + p.internal_damping + p.external_damping
        };
        let e0 = total(&r.samples[0]);
        let worst = r
            .samples
            .iter()
            .fold(0.0f64, |w, p| w.max((total(p) / e0 - 1.0).abs()));
        let last = r.samples.last().unwrap();
        eprintln!(
            "energy balance {worst:e}, left {:e}",
            (last.kinetic + last.elastic) / e0
        );
        assert!(worst < 3e-8, "{worst:e}");
        assert!(last.kinetic + last.elastic < 0.2 * e0, "{last:?}");
    }

    /// For the linear(ized) rod the energy–momentum step with damping is Newmark's rule too (the
    /// trapezoidal rule and the midpoint rule agree on a linear system): the first mode's damped
    /// roots pass `damped_mode`'s checks (mapped roots within 2e-8, raw errors falling 3.9–4.1
    /// times with Δt, Richardson within 3e-5) for both dampings.
    #[test]
    fn the_energy_momentum_step_damps_the_first_mode_as_newmark() {
        let w1 = CLAMPED_FREE_BETA1.powi(2);
        let ge = 0.2;
        damped_mode(
            &DynamicsOptions {
                external_damping: ge,
                time_scheme: Some(TimeScheme::EnergyMomentum),
                ..DynamicsOptions::default()
            },
            [ge / 2.0, (w1 * w1 - ge * ge / 4.0).sqrt()],
        );
        let gi = 0.1 / w1;
        damped_mode(
            &DynamicsOptions {
                internal_damping: gi,
                time_scheme: Some(TimeScheme::EnergyMomentum),
                ..DynamicsOptions::default()
            },
            [
                gi * w1 * w1 / 2.0,
                w1 * (1.0 - (gi * w1 / 2.0).powi(2)).sqrt(),
            ],
        );
    }

    /// Rotary inertia with the energy–momentum step: the Rayleigh beam's first frequency
    /// (g0 = 0.05, ω₁ = 3.49574816) to 1e-8 and its energy to 1e-7 over a period, as with
    /// Newmark's rule (`rotary_inertia_has_the_rayleigh_beam_s_frequency`). Measured 8.9e-10
    /// and 1.5e-9.
    #[test]
    fn the_energy_momentum_step_has_the_rayleigh_beam_s_frequency() {
        let g0 = 0.05;
        let (w1, v0) = rayleigh_first_mode(g0, 1e-4);
        let period = 2.0 * std::f64::consts::PI / w1;
        let o = DynamicsOptions {
            dt: period / 50.0,
            t_end: period,
            rotary_inertia: g0,
            time_scheme: Some(TimeScheme::EnergyMomentum),
            ..DynamicsOptions::default()
        };
        let r = free(&Rod::uniform(), &v0, &o).unwrap();
        let w = frequency_of(&r, o.dt, 12);
        let drift = energy_drift(&r);
        eprintln!("omega error {:e}, energy drift {drift:e}", w / w1 - 1.0);
        assert!((w / w1 - 1.0).abs() < 1e-8, "omega {w} against {w1}");
        assert!(drift < 1e-7, "{drift:e}");
    }

    /// The first mode of the uniform clamped–free Rayleigh beam (Euler–Bernoulli with rotary
    /// inertia `j = g0²`): `w'''' + jλ w'' − λ w = 0`, `w(0) = w'(0) = 0`, `w''(1) = 0`,
    /// `w'''(1) + jλ w'(1) = 0` (the linearized rod of module `modes` about the straight rod),
    /// `w = cosh as − cos bs + C (sinh as − (a/b) sin bs)` with `a², −b²` the roots of
    /// `r⁴ + jλ r² − λ = 0`: its `λ = ω₁²` by bisection on the free end's shear condition
    /// (from below the Euler–Bernoulli `β₁⁴`), and the shape as a velocity field, `amp` at the
    /// tip.
    fn rayleigh_first_mode(g0: f64, amp: f64) -> (f64, impl Fn(f64) -> [f64; 2]) {
        let j = g0 * g0;
        let parts = move |lam: f64| {
            let root = (j * j * lam * lam + 4.0 * lam).sqrt();
            let (a, b) = (
                (0.5 * (root - j * lam)).sqrt(),
                (0.5 * (root + j * lam)).sqrt(),
            );
            let c = -(a * a * a.cosh() + b * b * b.cos()) / (a * a * a.sinh() + a * b * b.sin());
            (a, b, c)
        };
        let shear = |lam: f64| {
            let (a, b, c) = parts(lam);
            let d1 = a * a.sinh() + b * b.sin() + c * (a * a.cosh() - a * b.cos());
            let d3 = a.powi(3) * a.sinh() - b.powi(3) * b.sin()
                + c * (a.powi(3) * a.cosh() + a * b * b * b.cos());
            d3 + j * lam * d1
        };
        let (mut lo, mut hi) = (0.8 * CLAMPED_FREE_BETA1.powi(4), CLAMPED_FREE_BETA1.powi(4));
        assert!(shear(lo) * shear(hi) < 0.0);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if shear(lo) * shear(mid) <= 0.0 {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        let lam = 0.5 * (lo + hi);
        let (a, b, c) = parts(lam);
        let w = move |s: f64| {
            (a * s).cosh() - (b * s).cos() + c * ((a * s).sinh() - a / b * (b * s).sin())
        };
        let w1 = w(1.0);
        (lam.sqrt(), move |s: f64| [amp * w(s) / w1, 0.0])
    }

    /// With rotary inertia (g0 = 0.05) a small velocity in the first mode's shape of the
    /// Rayleigh beam (closed form above: ω₁ = 3.49574816, 0.58 % below Euler–Bernoulli's
    /// 3.51601527; `vibrissa modes --rotary-inertia 0.05` gives the same to 7e-13) oscillates at
    /// that frequency, and the energy with the rotation's share `½∫ j φ_t²` is kept. Measured
    /// (50 steps per period, grid 200, tol 1e-10, 2026-11-29): frequency off by 1.4e-9, energy
    /// drift 3.2e-9 over the period; the same start without rotary inertia oscillates 6.4e-3
    /// off. Bounds as the Euler–Bernoulli test's: frequency 1e-8, energy 1e-7.
    #[test]
    fn rotary_inertia_has_the_rayleigh_beam_s_frequency() {
        let g0 = 0.05;
        let (w1, v0) = rayleigh_first_mode(g0, 1e-4);
        let period = 2.0 * std::f64::consts::PI / w1;
        let o = DynamicsOptions {
            dt: period / 50.0,
            t_end: period,
            rotary_inertia: g0,
            ..DynamicsOptions::default()
        };
        let r = free(&Rod::uniform(), &v0, &o).unwrap();
        let w = frequency_of(&r, o.dt, 12);
        let e0 = r.samples[0].kinetic;
        let worst = r.samples.iter().fold(0.0f64, |w, p| {
            w.max(((p.kinetic + p.elastic) / e0 - 1.0).abs())
        });
        eprintln!(
            "rayleigh omega {w1}, euler-bernoulli {}, omega error {:e}, energy drift {worst:e}",
            CLAMPED_FREE_BETA1.powi(2),
            w / w1 - 1.0
        );
        let plain = free(
            &Rod::uniform(),
            &v0,
            &DynamicsOptions {
                rotary_inertia: 0.0,
                ..o.clone()
            },
        )
        .unwrap();
        let off = frequency_of(&plain, o.dt, 12) / w1 - 1.0;
        eprintln!("without rotary inertia: omega error {off:e}");
        assert!((w / w1 - 1.0).abs() < 1e-8, "omega {w} against {w1}");
        assert!(worst < 1e-7, "{worst:e}");
        assert!(off > 1e-3, "{off:e}");
    }

    /// The viscoelastic foot (spring `k = 1/c_s = 2`, damper `c = 0.3`): the energy the rod
    /// loses is the damper's, step by step (the scheme's identity; spatial error aside), by
    /// Newmark's rule and by the energy–momentum step (its spring at the step's mean turn, its
    /// damper at the mean rate). Measured: balance to 2.7e-9 while the damper takes 59 % of
    /// the energy in 2 time units (Newmark's).
    #[test]
    fn foot_damper_takes_the_lost_energy() {
        for time_scheme in [TimeScheme::Newmark, TimeScheme::EnergyMomentum] {
            foot_damper_balance(time_scheme);
        }
    }

    fn foot_damper_balance(time_scheme: TimeScheme) {
        let rod = Rod::builder().support_compliance(0.5).build().unwrap();
        let o = DynamicsOptions {
            dt: 0.05,
            t_end: 2.0,
            foot_damping: 0.3,
            time_scheme: Some(time_scheme),
            ..DynamicsOptions::default()
        };
        let r = free(&rod, &first_mode_velocity(1e-3), &o).unwrap();
        let e0 = r.samples[0].kinetic + r.samples[0].elastic;
        let last = r.samples.last().unwrap();
        assert!(last.dissipated > 0.05 * e0, "{last:?}");
        let worst = r.samples.iter().fold(0.0f64, |w, p| {
            w.max(((p.kinetic + p.elastic + p.dissipated) / e0 - 1.0).abs())
        });
        eprintln!(
            "{time_scheme:?}: energy balance {worst:e}, damper took {:e} of {e0:e}",
            last.dissipated
        );
        for p in &r.samples {
            let e = p.kinetic + p.elastic + p.dissipated;
            assert!((e / e0 - 1.0).abs() < 1e-7, "t = {}: {e} against {e0}", p.t);
        }
    }

    /// A step moment on the viscoelastic foot (`k = 1`, `c = 10`, `M = 1e-3`): the rod turns
    /// by `θ → M/k`, creeping with the time constant `c/k` of the Kelvin–Voigt support; the
    /// rod's rotary inertia about the foot (`∫μs² = 1/3`) makes it the slow root of
    /// `θ_tt/3 + cθ_t + kθ = M`: τ = 9.96655. Read off `ln(M/k − θ)` between t = 5 and 15
    /// (measured: 9.96522, 1.3e-4 from the rigid rod's, 3.5e-3 from c/k). The start lags the
    /// closed forms by O(Δt) (`a⁰ = 0` where the step moment accelerates the rod at once;
    /// measured 7.3e-3 of M/k at Δt = 0.1, 5.0e-3 at 0.05, 3.8e-3 at 0.025), which shifts the
    /// curve in time but leaves τ. The same by the energy–momentum step.
    #[test]
    fn step_moment_creeps_with_the_support_time_constant() {
        for time_scheme in [TimeScheme::Newmark, TimeScheme::EnergyMomentum] {
            step_moment_creep(time_scheme);
        }
    }

    fn step_moment_creep(time_scheme: TimeScheme) {
        let (k, c, m) = (1.0, 10.0, 1e-3);
        let rod = Rod::builder().support_compliance(1.0 / k).build().unwrap();
        let o = DynamicsOptions {
            dt: 0.1,
            t_end: 15.0,
            foot_damping: c,
            foot_moment: m,
            time_scheme: Some(time_scheme),
            ..DynamicsOptions::default()
        };
        let r = free(&rod, &|_| [0.0, 0.0], &o).unwrap();
        let i3 = 1.0 / 3.0;
        let r1 = (-c + (c * c - 4.0 * i3 * k).sqrt()) / (2.0 * i3);
        let at = |t: f64| {
            let p = r.samples.iter().find(|p| (p.t - t).abs() < 1e-9).unwrap();
            m / k - p.theta
        };
        let tau = 10.0 / (at(5.0) / at(15.0)).ln();
        eprintln!(
            "{time_scheme:?}: tau {tau}, rigid rod {}, c/k {}",
            -1.0 / r1,
            c / k
        );
        assert!((tau * -r1 - 1.0).abs() < 1e-3, "tau {tau}");
        assert!((tau / (c / k) - 1.0).abs() < 1e-2, "tau {tau}");
        let worst = r.samples.iter().fold(0.0f64, |w, p| {
            w.max((p.theta - m / k * (1.0 - (-p.t * k / c).exp())).abs() / (m / k))
        });
        assert!(worst < 1.1e-2, "{worst}");
    }

    /// Released from the equilibrium under a small transverse tip force F = 1e-4 (the slip's
    /// "bang" in miniature): the elastic energy at the start is the cantilever's `F²L³/(6EI)`
    /// (Clapeyron: half the work `F·δ`, `δ = FL³/(3EI)`; measured 1.7e-9 from it), and from the
    /// first step on the undamped rod keeps its energy (measured 7.7e-9 over a period at 50
    /// steps per period). With Newmark's rule the first step itself loses 1.0 % of it: the
    /// trapezoidal rule sees the mean of the force before and after the release, as if the tip
    /// were let go over one step (a limitation of that scheme at a jump, see the module docs).
    /// The default scheme of fixed steps, the energy–momentum step, keeps it from the start
    /// (measured: the first step 4.2e-10 off, then alternating from step to step within
    /// 1.5e-7, the modes the release rings; 2.5e-16 of energy, at the collocation's tolerance
    /// on moments of 1e-4); asserted 3e-7.
    #[test]
    fn release_from_a_tip_load_keeps_the_stored_energy() {
        let f = 1e-4;
        let period = 2.0 * std::f64::consts::PI / CLAMPED_FREE_BETA1.powi(2);
        let o = DynamicsOptions {
            dt: period / 50.0,
            t_end: period,
            release_force: [f, 0.0],
            ..DynamicsOptions::default()
        };
        let d = free(&Rod::uniform(), &|_| [0.0, 0.0], &o).unwrap();
        let e0 = d.samples[0].elastic;
        let worst = d.samples.iter().fold(0.0f64, |w, p| {
            w.max(((p.kinetic + p.elastic) / e0 - 1.0).abs())
        });
        eprintln!("default scheme: energy within {worst:e} of the stored one");
        assert!(worst < 3e-7, "{worst:e}");
        let o = DynamicsOptions {
            time_scheme: Some(TimeScheme::Newmark),
            ..o
        };
        let r = free(&Rod::uniform(), &|_| [0.0, 0.0], &o).unwrap();
        let s0 = &r.samples[0];
        assert!((s0.tip_x - f / 3.0).abs() < 1e-9 * f, "{}", s0.tip_x);
        assert_eq!(s0, &d.samples[0]);
        let e0 = s0.elastic;
        assert!((e0 / (f * f / 6.0) - 1.0).abs() < 1e-7, "{e0}");
        let e1 = r.samples[1].kinetic + r.samples[1].elastic;
        let lost = 1.0 - e1 / e0;
        assert!(lost > 0.0 && lost < 0.02, "first step {lost}");
        for p in &r.samples[1..] {
            let e = p.kinetic + p.elastic;
            assert!((e / e1 - 1.0).abs() < 1e-7, "t = {}: {e} against {e1}", p.t);
        }
        // the tip swings to the other side
        let min = r
            .samples
            .iter()
            .map(|p| p.tip_x)
            .fold(f64::INFINITY, f64::min);
        assert!(min < -0.9 * f / 3.0, "{min}");
    }

    /// The root `z` of the tip's recurrence `x_{n+1} = p x_n − q x_{n−1}` (least squares over
    /// the samples from step 1 on: the step from the start may be inconsistent), as
    /// `(raw, mapped)`: the raw discrete rate and frequency `(−ln|z|/Δt, arg z/Δt)`, and the
    /// continuous root `λ = 2/Δt (z − 1)/(z + 1)` the trapezoidal rule maps to `z` (exact for a
    /// linear system), as `(−Re λ, Im λ)`.
    fn damped_root(r: &DynamicsResult, dt: f64) -> ([f64; 2], [f64; 2]) {
        let x: Vec<f64> = r.samples.iter().map(|p| p.tip_x).collect();
        let (mut a11, mut a12, mut a22, mut b1, mut b2) = (0.0, 0.0, 0.0, 0.0, 0.0);
        for n in 2..x.len() - 1 {
            let (u, w, y) = (x[n], -x[n - 1], x[n + 1]);
            a11 += u * u;
            a12 += u * w;
            a22 += w * w;
            b1 += u * y;
            b2 += w * y;
        }
        let det = a11 * a22 - a12 * a12;
        let (p, q) = ((b1 * a22 - b2 * a12) / det, (a11 * b2 - a12 * b1) / det);
        let (zr, zi) = (0.5 * p, (q - 0.25 * p * p).sqrt());
        let raw = [-0.5 * q.ln() / dt, zi.atan2(zr) / dt];
        let den = (zr + 1.0).powi(2) + zi * zi;
        let mapped = [-2.0 / dt * (q - 1.0) / den, 2.0 / dt * 2.0 * zi / den];
        (raw, mapped)
    }

    /// The first mode's damped root against its closed form `[rate, frequency]`, at two steps
    /// (`period/40`, `period/80`, three periods from a tip velocity 1e-4): the trapezoidal map
    /// back is exact for the linearized rod, so its error is the rest (collocation, history
    /// grid, the `O(A²)` nonlinearity); the raw root's error is Newmark's, second order in Δt,
    /// and Richardson's pair removes it. Asserted: the mapped roots within 2e-8 (relative), the
    /// raw errors' ratio between the steps within [3.9, 4.1], Richardson's within 3e-5.
    fn damped_mode(opts: &DynamicsOptions, want: [f64; 2]) {
        let period = 2.0 * std::f64::consts::PI / CLAMPED_FREE_BETA1.powi(2);
        let run = |steps: f64| {
            let o = DynamicsOptions {
                dt: period / steps,
                t_end: 3.0 * period,
                ..opts.clone()
            };
            let r = free(&Rod::uniform(), &first_mode_velocity(1e-4), &o).unwrap();
            damped_root(&r, o.dt)
        };
        let ((raw1, map1), (raw2, map2)) = (run(40.0), run(80.0));
        let rel = |a: [f64; 2]| [0, 1].map(|k| a[k] / want[k] - 1.0);
        let rich = [0, 1].map(|k| (4.0 * raw2[k] - raw1[k]) / 3.0);
        let e = [rel(map1), rel(map2), rel(raw1), rel(raw2)];
        let er = rel(rich);
        eprintln!(
            "want {want:?}: mapped {map1:?} {map2:?} errors {:?} {:?}; raw errors {:?} {:?} \
             (ratio {:?}); Richardson {er:?}",
            e[0],
            e[1],
            e[2],
            e[3],
            [0, 1].map(|k| e[2][k] / e[3][k])
        );
        for k in 0..2 {
            assert!(e[0][k].abs() < 2e-8 && e[1][k].abs() < 2e-8, "{e:?}");
            let ratio = e[2][k] / e[3][k];
            assert!((3.9..4.1).contains(&ratio), "{e:?}");
            assert!(er[k].abs() < 3e-5, "{er:?}");
        }
    }

    /// External damping `γ_e = 0.2` on the uniform clamped–free rod: the first mode decays at
    /// `γ_e/2` with the frequency `sqrt(ω₁² − γ_e²/4)` (ω₁ = β₁², β₁ = 1.87510406871196).
    /// Measured: mapped roots 7.7e-11, 2.6e-10 from the closed form (rate; frequency 8.9e-10,
    /// 3.5e-9); raw −6.1e-3, −1.5e-3 (rate, ratio 3.98); Richardson −9.4e-6, −1.9e-6.
    #[test]
    fn external_damping_decays_the_first_mode_at_half_gamma() {
        let (ge, w1) = (0.2, CLAMPED_FREE_BETA1.powi(2));
        let want = [ge / 2.0, (w1 * w1 - ge * ge / 4.0).sqrt()];
        let o = DynamicsOptions {
            external_damping: ge,
            ..DynamicsOptions::default()
        };
        damped_mode(&o, want);
    }

    /// Kelvin–Voigt damping `γ_i` with `γ_i ω₁/2 = 0.05` on the uniform clamped–free rod: the
    /// first mode decays at `γ_i ω₁²/2` with the frequency `ω₁ sqrt(1 − (γ_i ω₁/2)²)`.
    /// Measured: mapped roots 1.0e-10, 1.9e-10 (rate; frequency 9.2e-10, 3.5e-9); raw −6.1e-3,
    /// −1.5e-3 (rate, ratio 3.98); Richardson −9.3e-6, −1.8e-6.
    #[test]
    fn internal_damping_decays_the_first_mode_at_gamma_omega_squared() {
        let w1 = CLAMPED_FREE_BETA1.powi(2);
        let gi = 0.1 / w1;
        let want = [
            gi * w1 * w1 / 2.0,
            w1 * (1.0 - (gi * w1 / 2.0).powi(2)).sqrt(),
        ];
        let o = DynamicsOptions {
            internal_damping: gi,
            ..DynamicsOptions::default()
        };
        damped_mode(&o, want);
    }

    /// Both dampings and the foot's damper over ten periods (25 steps each): the energy the rod
    /// loses is what the three dampers take, step by step (the scheme's identity; Simpson's
    /// rule on the grid aside). Measured: balance to 8.1e-9 from step 1 on, while the dampers
    /// take 90 % of it. The first step loses 3.2e-3 more: the start's acceleration `a⁰` lacks
    /// the Kelvin–Voigt moment's share (its velocity error `Δt/2·δa` stays; the external
    /// damping's share `−γ_e v0` is set).
    #[test]
    fn damping_takes_the_lost_energy() {
        let w1 = CLAMPED_FREE_BETA1.powi(2);
        let period = 2.0 * std::f64::consts::PI / w1;
        let rod = Rod::builder().support_compliance(0.5).build().unwrap();
        let o = DynamicsOptions {
            dt: period / 25.0,
            t_end: 10.0 * period,
            foot_damping: 0.05,
            internal_damping: 0.02 / w1,
            external_damping: 0.05,
            ..DynamicsOptions::default()
        };
        let r = free(&rod, &first_mode_velocity(1e-3), &o).unwrap();
        let s1 = &r.samples[1];
        let total = |p: &DynSample| {
            p.kinetic + p.elastic + p.dissipated + p.internal_damping + p.external_damping
        };
        let e1 = total(s1);
        let last = r.samples.last().unwrap();
        let worst = r.samples[1..]
            .iter()
            .fold(0.0f64, |w, p| w.max((total(p) / e1 - 1.0).abs()));
        let first = total(s1) / total(&r.samples[0]) - 1.0;
        eprintln!(
            "energy balance {worst:e} from step 1; first step {first:e}; left {:e}, foot {:e}, \
             internal {:e}, external {:e} of {e1:e}",
            last.kinetic + last.elastic,
            last.dissipated,
            last.internal_damping,
            last.external_damping
        );
        assert!(worst < 3e-8, "{worst:e}");
        assert!(first.abs() < 1e-2, "{first:e}");
        for taken in [
            last.dissipated,
            last.internal_damping,
            last.external_damping,
        ] {
            assert!(taken > 0.05 * e1, "{last:?}");
        }
        assert!(last.kinetic + last.elastic < 0.2 * e1, "{last:?}");
    }

    /// Options out of range are refused.
    #[test]
    fn options_are_checked() {
        let o = DynamicsOptions {
            dt: 0.0,
            ..DynamicsOptions::default()
        };
        assert!(matches!(
            free(&Rod::uniform(), &first_mode_velocity(1e-3), &o),
            Err(VibrissaError::OutOfRange { .. })
        ));
    }
}
