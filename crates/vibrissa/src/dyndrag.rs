//! The dynamic drag (issue 32): the foot moves along x at speed `v` (or along a time table, its
//! support turned by the table's angle and a whisk) while the tip touches the surface
//! `y = h(x)` (written here for the flat `y = η`; on an inclined line or a height profile the
//! same with `N = −G·n`, `T = −G·t` along the surface's normal and tangent at the tip, and the
//! slide's velocity along the tangent: [`crate::rothe::TipBc`]) with Coulomb friction, the rod
//! followed in time by the Rothe step of
//! `dynamics::free` (module `rothe`: Newmark's average acceleration in time, Lobatto
//! collocation in s).
//!
//! ```text
//!     foot:      x(0) = d(t),  y(0) = 0,  φ(0) = π/2 − θ_w(t) + θ (θ the support's own
//!                rotation: its spring and damper as in `free`, 0 on a clamp)
//!     stuck:     x(1) = X_a,  y(1) = η,  m(1) = 0            while |T| < μs N
//!     slipping:  y(1) = η,  m(1) = 0,  T = dir·μk·N           while dir·ẋ(1) > 0
//!     N = −Gy(1) (the surface pushes down on the rod),  T = −Gx(1)  (μ = T/N as in the static
//!     model: T > 0 holds the tip back against the drag in +x)
//! ```
//!
//! Events, each located inside the step where it happens by Brent's method (argmin) on the
//! step's length, every function value a step solved anew, to `event_tol` in time (one within
//! the shortest step `max(1e-3 dt, 1e-5, 0.1 √tol)` of a step's start is placed at that
//! step's end):
//! **slip** where `|T|` reaches `μs N` (the tip then slides in the direction `dir = sign T` it
//! is pushed), **stick** where the sliding tip's velocity `dir·ẋ(1)` falls to zero (the tip
//! then sticks where it is; if it needs more than `μs N` there, it slips at once, and if that
//! slip moves it the other way, it sticks at once; if it needs a pull at once, it slips at
//! once the way it is pushed where that slide is consistent (it pushes, and the tip
//! accelerates that way), else lifts off at once where the free tip accelerates away from the
//! surface; a fourth event at the same instant would repeat the second, and a pull at once
//! that no other state resolves, or a slip or lift-off within the shortest step after a
//! stick, is not the rod's either: a stick the time step does not resolve, see below),
//! **lift-off** where `N` falls to zero (the drag ends there, or with
//! `flight` the tip flies free until **touchdown**, where its gap to the surface closes: a
//! plastic impact, after which the tip slides or sticks on; its first steps are taken by
//! backward Euler, see [`IMPACT_STEPS`]; docs/model.md), **side contact** where a point of the rod
//! other than the tip reaches the surface or the rod's end turns into it (where the rod's end
//! lies down a side then rolls and slides on, and where its contact returns to the tip,
//! **to_tip**, the tip takes it over; where another point touches beside the tip, or the free
//! tip beyond a side touches down beside it, the two contacts go on together, each sticking,
//! slipping and lifting off by its own law, until one lifts off or they meet at the tip; two
//! stuck contacts, which would trap the rod between them, and a third contact end the drag by
//! name; a round tip, a friction texture or a table of μk end it at a side contact), **patch**
//! where a sliding tip crosses a boundary of the surface's friction patches (it slides on with the next patch's μk, after a restart). A
//! friction texture gives μs at the stuck tip's place and μk at the sliding tip's (a table's
//! at `x(1)`). A round tip (a disk of radius `r` at the rod's end) has its centre on the line
//! lowered by `r` (on a profile's parallel curve at the distance `r`), rolls while it sticks
//! (the arc length of its centre's path less `r·φ(1)` held: `w·x(1) − r·φ(1)` on a line), slips
//! at the contact point's material velocity `v·t − r·φ̇(1)`, and carries `m(1) = r·T` while it
//! touches. With `mu_k_table` the kinetic friction
//! depends on the slip velocity at the step's end, `T = dir·μk(|ẋ(1)|)·N` (a disk's: its
//! contact point's). A sticking tip's velocity and acceleration at the tip are set to zero:
//! the velocity is zero to the event's tolerance, and the acceleration of a continuous rod
//! jumps at the point that sticks only (the force holding it rises like `√t` from the moment
//! it sticks), which Newmark's history would otherwise carry on as an alternating spurious
//! acceleration of the tip.
//! After each slip and stick the scheme is restarted: the history's accelerations and the end
//! forces are replaced by ones consistent with the new condition (`Rothe::restart`, two steps of
//! [`restart_step`] on a copy), since the holding force jumps there and the trapezoidal rule
//! would carry half the jump on as a mode alternating from step to step (docs/model.md). What
//! is left of that mode in the held tip's force (it grows during a stuck phase) does not enter
//! the motion, so after the first event the stuck tip's tests (slip and lift-off) take the held
//! force without it
//! ([`Drive::held_force`]: the step's end, its start and the last step's start combined).
//!
//! A stick or a stuck step the time step does not resolve (the tip's force leaving the friction
//! cone at once, or jumping within the shortest step: the scheme's, where the steps before were
//! too coarse for the rod's motion) is, with fixed steps, first taken again: the drag goes back
//! to its state after the last event before that instant (the states after its last
//! [`CHECKPOINTS`] events are kept), steps from there at half the step until `dt` past the
//! instant that failed, and goes on at `dt`; up to [`DynDragOptions::refinements`] halvings (3:
//! `dt/8`), counted in [`DragStats::refinements`]. A slip placed beyond the friction cone (by
//! more than 1e-6 of `μs N`: the held force jumped within the shortest step, or at a step's
//! end) is taken again so too while a halving is left; if those refinements end in a stop, the
//! drag goes on from that slip as it would without them. Only where the shortest of them does
//! not resolve it either does the drag stop, `UnresolvedStick` or `UnresolvedStep`. A step the
//! collocation does not solve (outside such refinements) is taken again so too; where the
//! shortest steps fail as well, the drag's error is the first failure's.
//! A slip's search that ends on a held force inside the cone (by more than 1e-6 of `μs N`) has
//! met a jump of the step's solutions, not a crossing of the slip's test: a stuck step the
//! time step does not resolve too (`UnresolvedStep`, taken again so where a halving is left). With
//! `time_tol` the controller's steps are kept as they are (no refinement).
//!
//! The start: the rod pressed onto the surface (the static state with the force normal to it,
//! the start of `vibrissa::drag`), at rest, the tip stuck. The foot's speed rises smoothly
//! from 0 to `v` over the time `ramp`: `ḋ = v·(10u³ − 15u⁴ + 6u⁵)`, `u = t/ramp`, so its
//! acceleration and jerk are zero at both ends of the ramp (`d = v·ramp·(u⁴(5/2 − 3u + u²))`
//! on the ramp, `v·ramp/2 + v(t − ramp)` after it). A sudden start at speed `v` would ring the
//! stuck rod at its own frequencies with an amplitude proportional to `v`, which the slow limit
//! `v → 0` could not shed (the rod has no damping but the foot's damper).
//!
//! Energy, by the scheme's own identity (the trapezoidal rule of Newmark's rule on every force
//! at the boundary): the foot's work `W = Σ −(Gx(0)ⁿ + Gx(0)ⁿ⁺¹)/2 (dⁿ⁺¹ − dⁿ)` plus, where the
//! support turns, `Σ (m(0)ⁿ + m(0)ⁿ⁺¹)/2 (θ_wⁿ⁺¹ − θ_wⁿ)` (`δE = m(0) δθ_w` for the rod and
//! its spring at rest), the work friction
//! takes `D_f = Σ −(Gx(1)ⁿ + Gx(1)ⁿ⁺¹)/2 (x(1)ⁿ⁺¹ − x(1)ⁿ)` (zero while stuck), the damper's
//! `D_c` as in `free`, and the rod's internal and external damping's `D_i`, `D_e` (module
//! `dynamics`); `W = ΔK + ΔE + D_f + D_c + D_i + D_e`, exact for a linear rod, to the time
//! scheme's error for this one.

use crate::config::SolverConfig;
use crate::rothe::{
    check_damping, EndHold, Foot, Rothe, Settings, SideAt, SideHold, TipBc, Track, Trial,
};
use crate::shape::BranchChoice;
use crate::solve::{solve, Target};
use crate::surface::Texture;
use crate::timestep::{check_time_tol, TimeStepControl};
use crate::{Rod, Surface, VibrissaError};
use bvp::Guess;
use serde::Serialize;
use std::fmt;
use std::sync::Arc;

/// Options of [`drag`].
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DynDragOptions {
    /// The foot's speed `v` along +x after the ramp (rod lengths per time unit), in
    /// `(0, 100]`. Default 0.01.
    pub speed: f64,
    /// Duration of the smooth start of the foot's speed from 0 to `v`, in `[0, 1e6]` (0: the
    /// foot moves at `v` from `t = 0`). Default 2 (about 1.1 periods of the free rod's first
    /// mode, 13 of the stuck paper's rod's).
    pub ramp: f64,
    /// Foot displacement where the drag ends, in `(0, 1000]`. Default 0.03 (past the paper's
    /// rod's first slip at 0.0210).
    pub d_max: f64,
    /// Static friction coefficient μs, in `[0, 100]`. Default 0.5 (the paper's). A surface
    /// with a friction texture ([`Surface::texture`]) replaces it and `mu_k`.
    pub mu_s: f64,
    /// Kinetic friction coefficient `μk ∈ [0, μs)`. Default 0.3.
    pub mu_k: f64,
    /// Kinetic friction depending on the slip velocity: points `(|v|, μk)`, speeds `≥ 0`
    /// strictly increasing, each `μk ∈ [0, μs)`; `μk(|v|)` piecewise linear between them and
    /// constant beyond the ends. When not empty it replaces `mu_k`. Default empty.
    pub mu_k_table: Vec<[f64; 2]>,
    /// Time step, in `(0, 1]`. Default 0.01.
    pub dt: f64,
    /// Tolerance in time of the events' places, in `[1e-14, 1e-3]`. Default 1e-10.
    pub event_tol: f64,
    /// Damper of the foot's support `c`, `≥ 0`. Default 0.
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
    /// Intervals of the history grid in `s`, even, in `[20, 100000]`. Default 200.
    pub grid: usize,
    /// Tolerance of each step's collocation, in `[1e-13, 1e-4]`. Default 1e-10.
    pub tol: f64,
    /// Collocation scheme of the steps. Default Lobatto IIIA of order 6.
    #[serde(skip)]
    pub scheme: bvp::Scheme,
    /// Most events before the drag stops (every kind, patches crossed too), in `[1, 1e6]`.
    /// Default 10000.
    pub max_events: usize,
    /// Halvings of `dt` the drag tries, from the state after its last event, where its steps do
    /// not resolve a stick or a stuck step, place a slip beyond the friction cone, or give a
    /// step the collocation does not solve (module docs), in `[0, 10]`; 0: such a stick or step
    /// ends the drag by name (a step not solved: with its error) at once. Fixed steps only (not
    /// with `time_tol`). Default 3 (down to `dt/8`).
    pub refinements: u32,
    /// After a lift-off the tip flies (free tip) until it touches the surface again: the event
    /// `touchdown`, located like the others on the tip's gap `η − y(1)`, a plastic impact (the
    /// tip's velocity normal to the surface set to zero, the kinetic energy this takes booked
    /// as `impact`), after which the tip slides or sticks on the surface again, the first
    /// [`IMPACT_STEPS`] steps by backward Euler (their energy loss booked with the impact;
    /// docs/model.md). `false`: lift-off ends the drag (stop `lift_off`). Default `false`.
    pub flight: bool,
    /// Adaptive time steps: the tolerance of each step's local error estimate in the positions
    /// (rod lengths; module `timestep` of `dynamics::free`), in `[1e-14, 1e-1]`; `dt` is then
    /// the first step, a step over the tolerance is tried again shorter, and each accepted
    /// step proposes the next one (events still shorten a step to their place, and the
    /// restart's steps and the shortest step stay those of `dt`). `None`: fixed steps `dt`.
    /// Default `None`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub time_tol: Option<f64>,
    /// The bounds of the adaptive steps' controller (used with `time_tol` only; checked then).
    /// Default [`TimeStepControl::default`].
    pub step_control: TimeStepControl,
    /// The foot's path by a time table instead of `speed` and `ramp`: rows `(t, d, θ_w)`, the
    /// time, the foot's displacement along x and the turn of its support (rad, clockwise as
    /// the static whisk's foot angle: the clamp holds the foot's slope at `π/2 − θ_w`). `t`
    /// strictly increasing from the first row `(0, 0, 0)` (the pressed start at rest), with
    /// [`limits::FOOT_TABLE_ROWS`](crate::limits::FOOT_TABLE_ROWS) rows, `θ_w` in
    /// [`limits::THETA`](crate::limits::THETA); each column is the natural cubic spline
    /// through its values (C²: the foot's acceleration is continuous, so the table itself
    /// gives the rod no impulse; a table whose first slope is not zero starts the foot at that
    /// speed at once, as `ramp` 0 does). The drag ends at the table's last time (`d_max`,
    /// `speed` and `ramp` are not used; stop [`DynDragStop::TableEnd`]). `d` may fall as well
    /// as rise (the foot drawn back). Default empty: `speed` and `ramp`.
    pub foot_table: Vec<[f64; 3]>,
    /// Whisking: the foot's support turns by `θ_w(t) = A (1 − cos 2πft)/2` on top of the foot's
    /// path (and of a table's `θ_w`): from the rest angle to `A` and back every `1/f` time
    /// units, starting at rest. Default `None`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub whisk: Option<Whisk>,
}

/// A whisking turn of the foot's support, `θ_w(t) = A (1 − cos 2πft)/2`
/// ([`DynDragOptions::whisk`]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Whisk {
    /// The largest turn `A` (rad, clockwise; negative turns the other way), in `(−π/2, π/2)`
    /// ([`limits::THETA`](crate::limits::THETA)).
    pub amplitude: f64,
    /// Whisks per time unit `f`, in `(0, 1000]`
    /// ([`limits::WHISK_FREQUENCY`](crate::limits::WHISK_FREQUENCY); a rat's 5–12 Hz in the
    /// preset's time unit: `vibrissa::inertia`).
    pub frequency: f64,
}

impl Whisk {
    /// `θ_w(t)`.
    pub fn turn_at(&self, t: f64) -> f64 {
        0.5 * self.amplitude * (1.0 - (std::f64::consts::TAU * self.frequency * t).cos())
    }
}

impl Default for DynDragOptions {
    fn default() -> Self {
        DynDragOptions {
            speed: 0.01,
            ramp: 2.0,
            d_max: 0.03,
            mu_s: 0.5,
            mu_k: 0.3,
            mu_k_table: vec![],
            dt: 0.01,
            event_tol: 1e-10,
            foot_damping: 0.0,
            internal_damping: 0.0,
            external_damping: 0.0,
            rotary_inertia: 0.0,
            grid: 200,
            tol: 1e-10,
            scheme: bvp::Scheme::Lobatto6,
            max_events: 10_000,
            refinements: 3,
            flight: false,
            time_tol: None,
            step_control: TimeStepControl::default(),
            foot_table: vec![],
            whisk: None,
        }
    }
}

/// Most time steps of a drag (`t_end/dt`).
pub const MAX_STEPS: f64 = 1e7;

impl DynDragOptions {
    /// Checks every value; the error names it and its valid range.
    pub fn validate(&self) -> Result<(), VibrissaError> {
        use crate::limits;
        let bad = |name: &str, v: f64, r: &str| Err(VibrissaError::range(name, v, r));
        if !(self.speed > 0.0 && self.speed <= 100.0) {
            return bad("speed", self.speed, "(0, 100]");
        }
        if !(self.ramp >= 0.0 && self.ramp <= 1e6) {
            return bad("ramp", self.ramp, "[0, 1e6]");
        }
        limits::DRAG_D_MAX.check("d_max", self.d_max)?;
        limits::MU_S.check("mu_s", self.mu_s)?;
        limits::kinetic_friction(self.mu_s).check("mu_k", self.mu_k)?;
        let mut last = f64::NEG_INFINITY;
        for p in &self.mu_k_table {
            if !(p[0] >= 0.0 && p[0].is_finite() && p[0] > last) {
                return bad(
                    "mu_k_table speed",
                    p[0],
                    "[0, inf), strictly increasing along the table",
                );
            }
            last = p[0];
            limits::kinetic_friction(self.mu_s).check("mu_k_table mu_k", p[1])?;
        }
        if !(self.dt > 0.0 && self.dt <= 1.0) {
            return bad("dt", self.dt, "(0, 1]");
        }
        if !(self.event_tol >= 1e-14 && self.event_tol <= 1e-3) {
            return bad("event_tol", self.event_tol, "[1e-14, 1e-3]");
        }
        if !(self.foot_damping >= 0.0 && self.foot_damping.is_finite()) {
            return bad("foot_damping", self.foot_damping, "[0, inf)");
        }
        check_damping(self.internal_damping, self.external_damping)?;
        crate::limits::ROTARY_INERTIA.check("rotary_inertia", self.rotary_inertia)?;
        if !(20..=100_000).contains(&self.grid) || self.grid % 2 == 1 {
            return bad("grid", self.grid as f64, "[20, 100000], even");
        }
        if !(self.tol >= 1e-13 && self.tol <= 1e-4) {
            return bad("tol", self.tol, "[1e-13, 1e-4]");
        }
        limits::MAX_SLIPS.check_count("max_events", self.max_events)?;
        if self.refinements > 10 {
            return bad("refinements", f64::from(self.refinements), "[0, 10]");
        }
        check_time_tol(self.time_tol, &self.step_control)?;
        check_foot_table(&self.foot_table)?;
        if let Some(w) = self.whisk {
            limits::THETA.check("whisk amplitude", w.amplitude)?;
            limits::WHISK_FREQUENCY.check("whisk frequency", w.frequency)?;
        }
        let steps = self.t_end() / self.dt;
        if steps > MAX_STEPS {
            let (name, hint) = if self.foot_table.is_empty() {
                ("d_max/(speed dt)", "raise speed or dt, or lower d_max")
            } else {
                (
                    "the foot table's last time/dt",
                    "raise dt or end the table sooner",
                )
            };
            return Err(VibrissaError::range(
                name,
                steps,
                format!("at most {MAX_STEPS:e} time steps: {hint}"),
            ));
        }
        Ok(())
    }

    /// The foot's displacement along x at time `t`: the smooth start, then speed `v`; or the
    /// spline of `foot_table` (made anew on every call, O(rows); the drag makes it once).
    pub fn foot_at(&self, t: f64) -> f64 {
        if !self.foot_table.is_empty() {
            return FootPath::new(self).at(t).place[0];
        }
        self.ramp_at(t)
    }

    /// The turn `θ_w` of the foot's support at time `t` (the table's and the whisk's; the
    /// table's spline made anew on every call, as [`DynDragOptions::foot_at`]).
    pub fn turn_at(&self, t: f64) -> f64 {
        FootPath::new(self).at(t).turn
    }

    /// The smooth start, then speed `v`.
    fn ramp_at(&self, t: f64) -> f64 {
        let (v, tr) = (self.speed, self.ramp);
        if t >= tr {
            v * tr / 2.0 + v * (t - tr)
        } else {
            let u = t / tr;
            v * tr * u.powi(4) * (2.5 - 3.0 * u + u * u)
        }
    }

    /// The time at which the drag ends: where the foot reaches `d_max`, or the foot table's
    /// last time.
    pub fn t_end(&self) -> f64 {
        if let Some(last) = self.foot_table.last() {
            return last[0];
        }
        let (v, tr) = (self.speed, self.ramp);
        if self.d_max >= v * tr / 2.0 {
            return tr + (self.d_max - v * tr / 2.0) / v;
        }
        // on the ramp: d is increasing in t, bisection to rounding
        let (mut lo, mut hi) = (0.0, tr);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if self.ramp_at(mid) < self.d_max {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        hi
    }
}

/// Checks a foot table ([`DynDragOptions::foot_table`]); the error names the row.
fn check_foot_table(rows: &[[f64; 3]]) -> Result<(), VibrissaError> {
    if rows.is_empty() {
        return Ok(());
    }
    let bad = |reason: String| {
        Err(VibrissaError::InvalidTable {
            name: "foot".into(),
            reason,
        })
    };
    let count = crate::limits::FOOT_TABLE_ROWS;
    if !count.contains_count(rows.len()) {
        return bad(format!(
            "{} rows: a foot table needs {}",
            rows.len(),
            count.text(6)
        ));
    }
    if rows[0] != [0.0, 0.0, 0.0] {
        return bad(format!(
            "its first row is (t, d, theta) = ({}, {}, {}): it must be (0, 0, 0), the pressed \
             start at rest",
            rows[0][0], rows[0][1], rows[0][2]
        ));
    }
    for (i, r) in rows.iter().enumerate() {
        if !r.iter().all(|v| v.is_finite()) || r[1].abs() > 1000.0 {
            return bad(format!(
                "row {i}: (t, d, theta) = ({}, {}, {}) (finite, |d| <= 1000)",
                r[0], r[1], r[2]
            ));
        }
        if !crate::limits::THETA.contains(r[2]) {
            return bad(format!(
                "row {i}: theta = {} rad is not in {} (the foot turned clockwise, within a \
                 quarter turn)",
                r[2],
                crate::limits::THETA.text(6)
            ));
        }
        if i > 0 && r[0] <= rows[i - 1][0] {
            return bad(format!(
                "row {i}: t = {} is not after t = {} of the row before: t must increase \
                 strictly",
                r[0],
                rows[i - 1][0]
            ));
        }
    }
    Ok(())
}

/// The rows of a foot table's text ([`DynDragOptions::foot_table`]): one row a line, `t, d` or
/// `t, d, theta` (a missing `theta` is 0), separated by a comma, a semicolon, tabs or spaces;
/// `#` starts a comment; a first line that is not numbers is a header. The rows stay in the
/// file's order (`DynDragOptions::validate` checks them). The error names the line.
pub fn parse_foot_table(text: &str) -> Result<Vec<[f64; 3]>, VibrissaError> {
    let mut rows = Vec::new();
    let mut header = false;
    for (i, line, nums) in crate::measured::numeric_lines(text) {
        match nums {
            Some(v) if v.len() == 2 || v.len() == 3 => {
                rows.push([v[0], v[1], v.get(2).copied().unwrap_or(0.0)]);
            }
            None if rows.is_empty() && !header => header = true,
            _ => {
                return Err(VibrissaError::InvalidTable {
                    name: "foot".into(),
                    reason: format!(
                        "line {}: '{line}' is not two or three numbers t, d[, theta] (one row a \
                         line)",
                        i + 1
                    ),
                })
            }
        }
    }
    Ok(rows)
}

/// [`parse_foot_table`] of a file.
pub fn read_foot_table(path: &std::path::Path) -> Result<Vec<[f64; 3]>, VibrissaError> {
    let text = std::fs::read_to_string(path).map_err(|e| VibrissaError::InvalidTable {
        name: "foot".into(),
        reason: format!("cannot read {}: {e}", path.display()),
    })?;
    parse_foot_table(&text).map_err(|e| match e {
        VibrissaError::InvalidTable { name, reason } => VibrissaError::InvalidTable {
            name,
            reason: format!("{}: {reason}", path.display()),
        },
        e => e,
    })
}

/// The foot's place and turn in time ([`DynDragOptions::foot_table`], `speed` and `ramp`,
/// [`DynDragOptions::whisk`]).
#[derive(Clone)]
struct FootPath<'o> {
    o: &'o DynDragOptions,
    /// The table's times, and per column (d, θ_w) the values and the spline's second
    /// derivatives.
    t: Vec<f64>,
    cols: [(Vec<f64>, Vec<f64>); 2],
}

impl<'o> FootPath<'o> {
    fn new(o: &'o DynDragOptions) -> Self {
        let t: Vec<f64> = o.foot_table.iter().map(|r| r[0]).collect();
        let col = |k: usize| {
            let v: Vec<f64> = o.foot_table.iter().map(|r| r[k]).collect();
            let m = crate::spline::natural_moments(&t, &v);
            (v, m)
        };
        let cols = [col(1), col(2)];
        FootPath { o, t, cols }
    }

    /// Whether the table's spline starts the foot or its turn with a speed (at `t = 0`).
    fn starts_moving(&self) -> bool {
        !self.t.is_empty()
            && self
                .cols
                .iter()
                .any(|(v, m)| crate::spline::jet(&self.t, v, m, 0.0).1 != 0.0)
    }

    /// The foot at time `t`.
    fn at(&self, t: f64) -> Foot {
        let whisk = self.o.whisk.map_or(0.0, |w| w.turn_at(t));
        if self.t.is_empty() {
            return Foot {
                place: [self.o.ramp_at(t), 0.0],
                turn: whisk,
            };
        }
        let [(d, dm), (th, thm)] = &self.cols;
        let d = crate::spline::jet(&self.t, d, dm, t).0;
        let turn = crate::spline::jet(&self.t, th, thm, t).0;
        Foot {
            place: [d, 0.0],
            turn: turn + whisk,
        }
    }
}

/// The tip's contact.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ContactState {
    /// The tip sticks where it is.
    Stuck,
    /// The tip slides towards +x.
    SlidingForward,
    /// The tip slides towards −x.
    SlidingBack,
    /// The tip flies, off the surface (with `DynDragOptions::flight`).
    Flying,
    /// A side of the rod touches the surface and rolls on it without slip, the tip free: the
    /// rod's end lay down on the surface and the contact moved inwards (docs/model.md, "A side
    /// in time").
    SideStuck,
    /// A side of the rod slides on the surface towards +x, the tip free.
    SideSlidingForward,
    /// A side of the rod slides on the surface towards −x, the tip free.
    SideSlidingBack,
}

impl ContactState {
    /// `stuck`, `sliding_forward`, `sliding_back`, `flying`, `side_stuck`,
    /// `side_sliding_forward`, `side_sliding_back`.
    pub fn name(self) -> &'static str {
        match self {
            ContactState::Stuck => "stuck",
            ContactState::SlidingForward => "sliding_forward",
            ContactState::SlidingBack => "sliding_back",
            ContactState::Flying => "flying",
            ContactState::SideStuck => "side_stuck",
            ContactState::SideSlidingForward => "side_sliding_forward",
            ContactState::SideSlidingBack => "side_sliding_back",
        }
    }
    fn dir(self) -> f64 {
        match self {
            ContactState::Stuck | ContactState::Flying | ContactState::SideStuck => 0.0,
            ContactState::SlidingForward | ContactState::SideSlidingForward => 1.0,
            ContactState::SlidingBack | ContactState::SideSlidingBack => -1.0,
        }
    }
    /// The state that slides the way `dir` (its sign) from this one: the tip's, or a side's.
    fn sliding(self, dir: f64) -> ContactState {
        match (self.side(), dir >= 0.0) {
            (false, true) => ContactState::SlidingForward,
            (false, false) => ContactState::SlidingBack,
            (true, true) => ContactState::SideSlidingForward,
            (true, false) => ContactState::SideSlidingBack,
        }
    }
    /// Whether a side of the rod touches the surface (the tip free).
    pub fn side(self) -> bool {
        matches!(
            self,
            ContactState::SideStuck
                | ContactState::SideSlidingForward
                | ContactState::SideSlidingBack
        )
    }
}

/// What happened at an event.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum DragEventKind {
    /// The stuck tip starts to slide (`|T| = μs N`).
    Slip,
    /// The sliding tip stops and sticks (its velocity along the surface zero).
    Stick,
    /// The normal force falls to zero: the drag ends (or the tip flies, with
    /// `DynDragOptions::flight`).
    LiftOff,
    /// The flying tip reaches the surface again (a plastic impact).
    Touchdown,
    /// A point of the rod other than its tip reaches the surface. Beside a point tip (stuck or
    /// sliding, uniform friction): where the rod's end lies down the contact moves inwards, a
    /// side that rolls or slides on the surface ([`ContactState::side`]); elsewhere on the rod
    /// the point is a side sliding the way it moves beside the tip (two contacts at once:
    /// [`DynDragEvent::tip_also`]). Else the drag ends there.
    SideContact,
    /// A side's contact reaches the tip (within `1e-4` of it, or half its deepest distance from
    /// the tip where that is nearer; its approach located in time): the tip touches again, stuck where the side rolled, sliding the same way where it slid
    /// (the contact's force carried over).
    ToTip,
    /// The sliding tip crosses a boundary of the friction texture's patches: it slides on with
    /// the next patch's μk (the row: the state at the boundary, its forces the last patch's).
    Patch,
}

impl DragEventKind {
    /// `slip`, `stick`, `lift_off`, `touchdown`, `side_contact`, `to_tip`, `patch`.
    pub fn name(self) -> &'static str {
        match self {
            DragEventKind::Slip => "slip",
            DragEventKind::Stick => "stick",
            DragEventKind::LiftOff => "lift_off",
            DragEventKind::Touchdown => "touchdown",
            DragEventKind::SideContact => "side_contact",
            DragEventKind::ToTip => "to_tip",
            DragEventKind::Patch => "patch",
        }
    }
}

/// One event of a dynamic drag, at the state where it is located.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct DynDragEvent {
    /// What happened.
    pub kind: DragEventKind,
    /// Time.
    pub t: f64,
    /// Foot displacement.
    pub d: f64,
    /// The tip's x.
    pub tip_x: f64,
    /// The tip's velocity along x.
    pub tip_vx: f64,
    /// Normal force `N`: the tip's force at the event's state; at a slip the held force its
    /// test takes (after the first event: without the time rule's alternating mode, so
    /// `|T| = μs N` to the event's location; docs/model.md, "The slip test on the held force").
    pub normal: f64,
    /// Tangential force `T` (friction on the tip, + against +x), taken as `normal` is.
    pub tangential: f64,
    /// The contact from here on.
    pub state: ContactState,
    /// Where a side touches (`state` a side's): the tip's contact on the surface as well from
    /// here on (stuck or sliding: two contacts at once), `None` (and left out of JSON) where the
    /// tip is free. At an event of the tip's own (its slip, stick or lift-off beside the side)
    /// `normal` and `tangential` are the tip's.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tip_also: Option<ContactState>,
}

/// The rod at one time of a dynamic drag.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct DragSample {
    /// Time.
    pub t: f64,
    /// Foot displacement.
    pub d: f64,
    /// The turn `θ_w` of the foot's support ([`DynDragOptions::foot_table`],
    /// [`DynDragOptions::whisk`]; 0 without them).
    pub theta: f64,
    /// Tip x.
    pub tip_x: f64,
    /// Tip y.
    pub tip_y: f64,
    /// Tip velocity, x.
    pub tip_vx: f64,
    /// Tip velocity, y.
    pub tip_vy: f64,
    /// The rod end's turning rate `φ̇(1)` (a round tip's spin: its contact point's material
    /// velocity along the surface is the end's less `r·φ̇(1)`). Not serialized.
    #[serde(skip)]
    pub tip_spin: f64,
    /// The tip's contact over the step that ended here.
    pub state: ContactState,
    /// Normal force `N = −Gy(1)` (after the first event without the time rule's alternating
    /// mode: [`DragSample::step_end_forces`]).
    pub normal: f64,
    /// Tangential force `T = −Gx(1)` (`μ = T/N`), as `normal`.
    pub tangential: f64,
    /// The force the rod exerts on its support, x (`Gx(0)`; the static drag's `fx`).
    pub fx: f64,
    /// The force on the support, y.
    pub fy: f64,
    /// The forces at the support and the tip, `G(0)` and `G(1)`, as the step's end left them:
    /// with the time rule's mode that alternates from step to step, which `normal`,
    /// `tangential`, `fx` and `fy` leave out after the first event (docs/model.md, "The
    /// samples' forces"). Not serialized.
    #[serde(skip)]
    pub step_end_forces: [[f64; 2]; 2],
    /// `m(0)`.
    pub m_base: f64,
    /// Kinetic energy.
    pub kinetic: f64,
    /// Elastic energy.
    pub elastic: f64,
    /// The foot's work so far: its support's force along the foot's path and, where the
    /// support turns, its moment on the turn.
    pub foot_work: f64,
    /// Energy friction took so far.
    pub friction: f64,
    /// Energy the foot's damper took so far.
    pub damper: f64,
    /// Energy the rod's internal (Kelvin–Voigt) damping took so far.
    pub internal_damping: f64,
    /// Energy the external viscous damping took so far.
    pub external_damping: f64,
    /// Kinetic energy the touchdowns' impacts took so far.
    pub impact: f64,
    /// Where a side touches the surface (a side's state, [`ContactState::side`]; `normal` and
    /// `tangential` are then its forces). `None` (and left out of JSON) otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub side: Option<SideSample>,
    /// Where a side touches and the tip as well (two contacts at once): the tip's contact.
    /// `None` (and left out of JSON) otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tip_also: Option<TipAlso>,
}

/// The tip's contact beside a side's at a sample (two contacts at once).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct TipAlso {
    /// The tip's state: stuck, or sliding.
    pub state: ContactState,
    /// Its normal force `N` (the step's end force).
    pub normal: f64,
    /// Its tangential force `T`.
    pub tangential: f64,
}

/// Where a side of the rod touches the surface at a sample.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SideSample {
    /// The contact's arc length.
    pub s: f64,
    /// Its lab x.
    pub x: f64,
    /// Its height.
    pub y: f64,
}

/// Why a dynamic drag ended.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case", tag = "reason")]
pub enum DynDragStop {
    /// The foot reached `d_max`.
    DMax,
    /// The foot table's last time was reached ([`DynDragOptions::foot_table`]).
    TableEnd,
    /// The normal force fell to zero at displacement `d`.
    LiftOff {
        /// Where.
        d: f64,
    },
    /// `max_events` events happened.
    MaxEvents,
    /// The time step does not resolve a stick (time `t`, displacement `d`): right after it the
    /// stuck tip needs the force (`normal`, `tangential`), a pull that no slide or lift-off at
    /// once can take the place of, or beyond μs N where a slip at once then moves the tip the
    /// other way and it sticks again at once (events would cycle at one instant), or it slips
    /// or lifts off within the shortest step. The scheme's, not the rod's: its steps before the
    /// stick were too coarse for the motion. The drag has taken the steps to it again at
    /// `dt/2`, `dt/4` and `dt/8` (module docs); a shorter `dt` still may resolve it (not always:
    /// docs/model.md, "A stick the time step does not resolve").
    UnresolvedStick {
        /// When.
        t: f64,
        /// Where.
        d: f64,
        /// The normal force the stuck tip needs.
        normal: f64,
        /// The tangential force the stuck tip needs.
        tangential: f64,
    },
    /// The time step does not resolve the stuck rod at time `t`, displacement `d`: within the
    /// shortest step the stuck tip's force would jump from `(N, T) = before` to (`normal`,
    /// `tangential`), where the rod's changes continuously (the time rule's alternating mode,
    /// grown during the stuck phase, in the state's velocities, or a force that changes faster
    /// than the step follows: a rod on a very soft support, docs/model.md); or the event's
    /// search within the step is not solved by the collocation (`normal`, `tangential` then at
    /// the step's end). As for `UnresolvedStick`, the drag has taken the steps to it again at
    /// `dt/2` … `dt/8` first (where one of those steps is not solved, this stop stands).
    UnresolvedStep {
        /// When.
        t: f64,
        /// Where.
        d: f64,
        /// `(N, T)` at the step's start.
        before: [f64; 2],
        /// The normal force within the shortest step.
        normal: f64,
        /// The tangential force within the shortest step.
        tangential: f64,
    },
    /// A point of the rod other than its tip reached the surface at time `t`, displacement `d`:
    /// the point at arc length `s`, lab `x` (on a corrugation's crest, say, or the rod's end
    /// turning into the surface as `s → 1`) where the dynamic drag does not follow a side (it
    /// does beside a point tip on the surface, of uniform friction); the quasi-static drag
    /// (`vibrissa::drag`) follows such contacts.
    SideContact {
        /// When.
        t: f64,
        /// Where.
        d: f64,
        /// The rod's point that touches (arc length).
        s: f64,
        /// Its lab x.
        x: f64,
    },
    /// A side and the tip on the surface at once whose step the collocation does not solve, at
    /// any step down to the shortest nor after the refinements (time `t`, displacement `d`):
    /// the rod between the side's contact at arc length `s` and the tip lies within `gap` of
    /// the surface (the largest distance of the last solution's nodes between them below it):
    /// where that is small against `1 − s`, a contact along a stretch rather than at two
    /// points, which the dynamic drag's point contacts do not follow (the quasi-static drag
    /// does: its `stretch` states). Seen before the side's test took the rod's highest point
    /// between nodes (`gap` 1.3e-6 over 0.0052); no drag of the grids ends so since.
    Stretch {
        /// When.
        t: f64,
        /// Where.
        d: f64,
        /// The side's contact's arc length.
        s: f64,
        /// The largest distance of the rod below the surface between the two contacts.
        gap: f64,
    },
    /// A side on the surface ([`ContactState::side`]) changes its contact at time `t`,
    /// displacement `d` in a way the dynamic drag does not follow (`change`): the contact at
    /// arc length `s`, lab `x`, its forces there (`normal`, `tangential`). (A contact that
    /// returns to the tip is followed, [`DragEventKind::ToTip`], and so is the tip on the surface
    /// beside a side, [`DynDragEvent::tip_also`].)
    SideChange {
        /// What changes.
        change: SideChange,
        /// When.
        t: f64,
        /// Where.
        d: f64,
        /// The contact's arc length.
        s: f64,
        /// Its lab x.
        x: f64,
        /// Its normal force.
        normal: f64,
        /// Its tangential force.
        tangential: f64,
    },
}

/// How a side contact in time changes where the dynamic drag stops ([`DynDragStop::SideChange`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SideChange {
    /// It needs more than μs N again at an instant that has had its share of events (a stick
    /// and a slip at once, repeated).
    Slip,
    /// Its normal force falls to zero at such an instant.
    LiftOff,
    /// Its contact comes within 1e-4 of the tip at such an instant (elsewhere the tip takes
    /// the contact over, [`DragEventKind::ToTip`]).
    AtTip,
    /// Another point of the rod reaches the surface (the tip free beyond the side: a point
    /// other than the tip, which touches down beside the side instead).
    SecondContact,
    /// A third point of the rod reaches the surface beside the side and the tip (or the end
    /// lies down beside the side).
    ThirdContact,
    /// It sticks beside the stuck tip, or the tip sticks beside it: the two stuck contacts would
    /// trap the rod between them (its chord less its length held by two no-slip conditions, a
    /// pair of tangential forces that only friction bounds, large where the segment is short;
    /// the steps of such a pair were singular to working precision where tried; docs/model.md,
    /// "Two contacts that do not slip trap the rod").
    Trapped,
}

impl SideChange {
    /// `slip`, `lift_off`, `at_tip`, `second_contact`, `third_contact`, `trapped`.
    pub fn name(self) -> &'static str {
        match self {
            SideChange::Slip => "slip",
            SideChange::LiftOff => "lift_off",
            SideChange::AtTip => "at_tip",
            SideChange::SecondContact => "second_contact",
            SideChange::ThirdContact => "third_contact",
            SideChange::Trapped => "trapped",
        }
    }
}

impl fmt::Display for DynDragStop {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            DynDragStop::DMax => write!(f, "d_max"),
            DynDragStop::TableEnd => write!(f, "the foot table's end"),
            DynDragStop::LiftOff { d } => write!(f, "lift-off at d = {d}"),
            DynDragStop::MaxEvents => write!(f, "max_events"),
            DynDragStop::UnresolvedStick {
                t,
                d,
                normal,
                tangential,
            } => write!(
                f,
                "the time step does not resolve the stick at t = {t}, d = {d}: right after it \
                 the stuck tip needs N = {normal}, T = {tangential} (a pull, or beyond mu_s N), \
                 which the rod cannot need so soon after a stick, and no slide or lift-off \
                 takes its place (a shorter dt may resolve it)"
            ),
            DynDragStop::UnresolvedStep {
                t,
                d,
                before,
                normal,
                tangential,
            } => write!(
                f,
                "the time step does not resolve the stuck rod at t = {t}, d = {d}: within the \
                 shortest step the event's search can solve, the stuck tip's force would jump \
                 from N = {}, T = {} to N = {normal}, T = {tangential}, where the rod's changes \
                 continuously (the time rule's alternating mode, grown while the tip was stuck, \
                 or a force faster than the step; a shorter dt may resolve it)",
                before[0], before[1]
            ),
            DynDragStop::SideContact { t, d, x, .. } if self.at_end() => write!(
                f,
                "the rod's end lies down on the surface at t = {t}, d = {d} (x = {x}; a side \
                 touches next to the tip): the dynamic drag follows a side only beside a point \
                 tip on the surface, of uniform friction (the quasi-static drag follows side \
                 contacts)"
            ),
            DynDragStop::SideContact { t, d, s, x } => write!(
                f,
                "a side of the rod reaches the surface at t = {t}, d = {d} (the point s = {s} at \
                 x = {x}): the dynamic drag follows a side only beside a point tip on the \
                 surface, of uniform friction (the quasi-static drag follows side contacts)"
            ),
            DynDragStop::Stretch { t, d, s, gap } => write!(
                f,
                "the side at s = {s} and the tip on the surface do not resolve at t = {t}, \
                 d = {d} (no step of the two contacts solves, nor shorter ones): the rod between \
                 them, {len:e} long, lies within {gap:e} of the surface (where that is small \
                 against its length, a contact along a stretch, which the dynamic drag's point \
                 contacts do not follow; the quasi-static drag does)",
                len = 1.0 - s
            ),
            DynDragStop::SideChange {
                change,
                t,
                d,
                s,
                x,
                normal,
                tangential,
            } => {
                let what = match change {
                    SideChange::Slip => "needs more than mu_s N and would slip",
                    SideChange::LiftOff => "lifts off",
                    SideChange::AtTip => "reaches the tip (within 1e-4)",
                    SideChange::SecondContact => "is joined by another point on the surface",
                    SideChange::ThirdContact => {
                        "and the tip are joined by a third point on the surface"
                    }
                    SideChange::Trapped => {
                        "and the tip would both stick, trapping the rod between them (a pair of \
                         tangential forces only friction bounds)"
                    }
                };
                write!(
                    f,
                    "the side on the surface {what} at t = {t}, d = {d} (s = {s}, x = {x}, \
                     N = {normal}, T = {tangential}): the dynamic drag follows one side that \
                     rolls, slides or lifts off, with the tip beside it or not (the quasi-static \
                     drag follows the rest)"
                )
            }
        }
    }
}

impl DynDragStop {
    /// Whether a side contact is the rod's end lying down (`s = 1`).
    fn at_end(&self) -> bool {
        matches!(self, DynDragStop::SideContact { s, .. } if *s == 1.0)
    }
}

/// Work done.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct DragStats {
    /// Time steps taken.
    pub steps: usize,
    /// Steps solved (taken, and tried while locating events; a step tried again from the same
    /// state with the same length is not solved again).
    pub solves: usize,
    /// Newton iterations of all solves.
    pub newton_iterations: usize,
    /// Largest collocation mesh.
    pub max_nodes: usize,
    /// The collocation mesh of the last step taken (nodes; not serialized).
    #[serde(skip)]
    pub mesh_nodes: usize,
    /// Slips.
    pub slips: usize,
    /// Sticks.
    pub sticks: usize,
    /// Restarts of the scheme after a slip or a stick (module docs).
    pub restarts: usize,
    /// Steps the local error estimate rejected (with `time_tol`; not written while 0, so fixed
    /// steps serialize and print as before).
    #[serde(skip_serializing_if = "crate::rothe::is_zero")]
    pub rejected_steps: usize,
    /// Times the drag went back to its last event and took the steps to a stick or a stuck
    /// step its steps did not resolve again at half the step (module docs; not written while
    /// 0). The steps, slips, sticks and restarts are those of the drag returned; the solves,
    /// Newton iterations and the largest mesh count the steps gone back over too.
    #[serde(skip_serializing_if = "crate::rothe::is_zero")]
    pub refinements: usize,
}

impl fmt::Display for DragStats {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} steps, {} solves, {} Newton iterations, largest mesh {}; {} slips, {} sticks, {} restarts",
            self.steps,
            self.solves,
            self.newton_iterations,
            self.max_nodes,
            self.slips,
            self.sticks,
            self.restarts
        )?;
        if self.rejected_steps > 0 {
            write!(f, "; {} steps rejected", self.rejected_steps)?;
        }
        if self.refinements > 0 {
            write!(f, "; {} refinements", self.refinements)?;
        }
        Ok(())
    }
}

/// Result of [`drag`].
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DynDragResult {
    /// One sample per step taken (the start included).
    pub samples: Vec<DragSample>,
    /// The events in order.
    pub events: Vec<DynDragEvent>,
    /// Why it ended.
    pub stop: DynDragStop,
    /// Work done.
    pub stats: DragStats,
}

/// The energy balance between two samples of a drag ([`DragSample::balance_to`]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct EnergyBalance {
    /// The elastic energy released, `E(from) − E(to)`.
    pub released: f64,
    /// The foot's work.
    pub work: f64,
    /// The work friction took.
    pub friction: f64,
    /// The work the dampers took: the support's, the rod's internal and external.
    pub damping: f64,
    /// `work − (ΔK + ΔE + friction + impacts + damping)`: zero but for the time scheme's
    /// error.
    pub imbalance: f64,
}

impl DragSample {
    /// The energy balance from this sample to a `later` one.
    pub fn balance_to(&self, later: &DragSample) -> EnergyBalance {
        let (a, b) = (self, later);
        let work = b.foot_work - a.foot_work;
        let friction = b.friction - a.friction;
        let damping = (b.internal_damping - a.internal_damping)
            + (b.external_damping - a.external_damping)
            + (b.damper - a.damper);
        let rest = (b.kinetic - a.kinetic)
            + (b.elastic - a.elastic)
            + friction
            + (b.impact - a.impact)
            + damping;
        EnergyBalance {
            released: a.elastic - b.elastic,
            work,
            friction,
            damping,
            imbalance: work - rest,
        }
    }
}

impl DynDragResult {
    /// The first slip's foot displacement.
    pub fn first_slip(&self) -> Option<f64> {
        self.first_slip_event().map(|e| e.d)
    }

    /// The first slip's event.
    pub fn first_slip_event(&self) -> Option<&DynDragEvent> {
        self.events.iter().find(|e| e.kind == DragEventKind::Slip)
    }

    /// The first slip's event and the stick that ends it (`None` where the drag ends first).
    pub fn first_slip_and_stick(&self) -> Option<(&DynDragEvent, &DynDragEvent)> {
        let slip = self.first_slip_event()?;
        let stick = self
            .events
            .iter()
            .find(|e| e.kind == DragEventKind::Stick && e.t > slip.t)?;
        Some((slip, stick))
    }

    /// The energy balance from the sample at time `from` to the one at `to` (`None` where
    /// either is not a sample's time; an event's `t` is one).
    pub fn balance(&self, from: f64, to: f64) -> Option<EnergyBalance> {
        let at = |t: f64| self.samples.iter().find(|p| p.t == t);
        Some(at(from)?.balance_to(at(to)?))
    }

    /// [`DynDragResult::balance`] from the first slip to the stick that ends it.
    pub fn first_slip_balance(&self) -> Option<EnergyBalance> {
        let (slip, stick) = self.first_slip_and_stick()?;
        self.balance(slip.t, stick.t)
    }
}

impl fmt::Display for DynDragResult {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.first_slip() {
            Some(d) => write!(f, "first slip at d = {d}; ")?,
            None => write!(f, "no slip; ")?,
        }
        write!(f, "stopped: {}; {}", self.stop, self.stats)
    }
}

/// The pressed start: the static rod with its tip at height η and the force normal to the
/// surface (the start of `vibrissa::drag`), as a guess on `grid` for the Rothe state.
fn pressed(rod: &Rod, eta: f64, grid: &[f64]) -> Result<(Guess, [f64; 2]), VibrissaError> {
    let shape = solve(
        rod,
        0.0,
        Target::Eta(eta),
        &BranchChoice::Convex,
        &SolverConfig::default(),
    )?;
    let pts: Vec<_> = grid.iter().map(|&s| shape.point_at(s)).collect();
    if let Some(p) = pts[..pts.len() - 1].iter().find(|p| p.y > eta) {
        return Err(VibrissaError::NoStart {
            reason: format!(
                "the pressed rod crosses the surface at s = {} (y = {} > eta = {eta}): the \
                 dynamic drag has the tip alone on the surface",
                p.s, p.y
            ),
        });
    }
    let (fx, fy) = (shape.fx, shape.fy);
    let mut k = 0;
    let guess = Guess::from_fn(6, grid.to_vec(), vec![], |_, z| {
        let p = &pts[k];
        k += 1;
        z.copy_from_slice(&[p.x, p.y, p.phi, p.m, fx, fy]);
    });
    Ok((guess, [shape.x1, eta]))
}

/// The pressed start on a surface that is not flat (inclined, or a height profile): the start
/// of `vibrissa::drag` there (the rod pressed onto the line, or onto the profile's trend and
/// the profile grown, the tip's force normal to the surface), as a guess on `grid`, the tip's
/// place and the track the tip then touches. A start with a side on the surface is refused:
/// the dynamic drag has the tip alone on it.
fn pressed_on(
    rod: &Rod,
    surface: &Surface,
    grid: &[f64],
) -> Result<(Guess, [f64; 2], Track), VibrissaError> {
    let cfg = SolverConfig::default();
    let (start, set, p0) = if rod.has_uniform_profile() {
        let (s, set, p0) = crate::ground::start(
            rod,
            &crate::profile::Uniform,
            surface,
            cfg.start,
            cfg.start_tol(),
        )?;
        (s.pt, set, p0)
    } else {
        let (s, set, p0) =
            crate::ground::start(rod, &rod.profile(1.0), surface, cfg.start, cfg.start_tol())?;
        (s.pt, set, p0)
    };
    surface.check_on(p0[0])?;
    if !set.tip_only() {
        return Err(VibrissaError::NoStart {
            reason: format!(
                "the pressed rod touches the surface with {} (the dynamic drag has the tip \
                 alone on the surface)",
                set.label()
            ),
        });
    }
    let track = match surface.profile_shared() {
        Some(h) => Track::Curve(h),
        None => Track::Line {
            p: p0,
            slope: surface.angle().tan(),
        },
    };
    let sol = &start.sol;
    let (f, alpha) = (sol.params[0], sol.params[1]);
    let (fx, fy) = (f * alpha.sin(), -f * alpha.cos());
    let guess = Guess::from_fn(6, grid.to_vec(), vec![], |s, z| {
        let mut r = [0.0; 4];
        sol.eval(s, &mut r);
        z.copy_from_slice(&[r[0], r[1], r[2], r[3], fx, fy]);
    });
    Ok((guess, p0, track))
}

/// The shortest step the events make, `max(1e-3 dt, 1e-5, 0.1 √tol)` (the last counts above
/// tol 1e-8 only): with `G` scaled by `4/Δt²`, the rounding of the positions still enters the
/// moment's equation as `4/Δt² · ε`, which the collocation's residual control cannot meet at
/// tol 1e-10 below a few 1e-6 (measured: a step of 2.4e-6 ran into the mesh limit of 10⁴
/// nodes, 3.5e-5 did not), and the step's end forces carry the positions' error times `4/Δt²`:
/// `0.1 √tol` keeps `4 tol/Δt²` at most 400, as 1e-5 does at tol 1e-8, where the drags read
/// their forces well (at tol 1e-6 a step of 5e-5, `4 tol/Δt²` = 1600, read a slip at N = −480
/// where N ≈ 5; `√tol` itself, 1e-4 at tol 1e-8, placed events up to 1e-4 late and read a
/// lift-off at N = −0.086 in a drag at dt 0.00125 that runs through ten slips with 1e-5). An
/// event closer than this to a step's start is placed at this step's end.
fn shortest_step(dt: f64, tol: f64) -> f64 {
    (1e-3 * dt).max(1e-5).max(0.1 * tol.sqrt())
}

/// The length `δ` of the two steps that restart the scheme after a slip or a stick:
/// `min(tol^(1/3), dt/4)`. The restart's accelerations carry the steps' position error
/// magnified by `4/δ²` (about `4 tol/δ²`) and are those of the time `1.5 δ` later; `δ = tol^(1/3)`
/// makes both about `tol^(1/3)` (4.6e-4 at the default tol 1e-10; `δ` = 1e-5 gave accelerations
/// off by O(1) there).
fn restart_step(o: &DynDragOptions) -> f64 {
    o.tol.cbrt().min(0.25 * o.dt)
}

/// The weights `[a, ½, c]` of [`Drive::held_force`] on the held force at the ends of the step
/// being tried (`τ` long) and of the last one (`h` long): `a = (τ + h/2)/(τ + h)`,
/// `c = −τ/(2(τ + h))`.
fn held_weights(tau: f64, h: f64) -> [f64; 3] {
    [(tau + 0.5 * h) / (tau + h), 0.5, -0.5 * tau / (tau + h)]
}

/// The weight `w(τ) = (τh/2 + h²/2 − τ²)/(τ h (τ + h))` of a velocity mismatch's term `A` in
/// the held force ([`held_weights`]) of a step of length `tau`, the last two of length `h`.
///
/// Why: the trapezoidal rule keeps the rod's velocities only as consistent with its
/// constraints (the held tip, inextensibility) as each step's solve, and it does not damp what
/// they miss (the rule's alternating mode): over a long stuck phase the mismatch grows, each
/// step adding about its position error `2/τ` times (the paper's rod at dt 0.0025, tol 1e-10:
/// `|A|` from 6.8e-6 to 3.8e-5 over ten slips; over a corrugation at dt 0.02, tol 1e-8: to 5.0e-3).
/// A step of length `τ` from such a state puts `A/τ` into the held tip's force (the step's
/// positions meet the constraint, so its accelerations take up `4ε/τ`), and the last two steps'
/// forces hold `∓A/h`: the held weights give `A·w(τ)`, zero at `τ = h` (a full step), `1/(2τ)`
/// as `τ → 0`, where an event search looks.
fn mismatch_weight(tau: f64, h: f64) -> f64 {
    (0.5 * tau * h + 0.5 * h * h - tau * tau) / (tau * h * (tau + h))
}

/// The weight `1/τ − 1/h` of a velocity mismatch's term `A` in the end force itself of a step
/// of length `tau` from a state whose last step was `h` long: the step's positions meet the
/// constraint, so its accelerations take up the mismatch as `A/τ` ([`mismatch_weight`]); less
/// its value at a full step, so that a full step's force is left as the rule gives it.
///
/// Why: before the drag's first event the held forces are not formed (the start is at rest and
/// the rule's alternating mode is not excited, so the end forces are the rod's), but the
/// velocities miss the stuck tip's condition by what each step's solve leaves (measured: `A`
/// = −2.1e-7 for the paper's rod at v 0.1, dt 0.005 before its first slip, +7.2e-7 on a compliant
/// support, `c_s` = 1, against N = 5.37 and 1.73), and the first slip's search reads the force
/// at steps down to 1e-5: on the compliant support at dt 0.005 it placed the slip at
/// T/N = 0.5231, and with the support's damper (0.2 to 2) at dt 0.01 it stopped as
/// `unresolved_step` before any slip.
fn end_mismatch_weight(tau: f64, h: f64) -> f64 {
    1.0 / tau - 1.0 / h
}

/// The steps after a touchdown taken by backward Euler instead of the trapezoidal rule
/// (`Rothe::euler_steps` in the crate's Rothe step).
///
/// Why: the Euler–Bernoulli rod's contact force after a point impact is singular, like
/// `t^(-1/2)`, and the trapezoidal rule answers it with end forces of alternating sign:
/// measured on the precurved rod that flies and touches down (tests/dynamic_drag.rs, program
/// defaults grid 200, tol 1e-10, dt 0.005) N = 8.5, −19.5, −15.4, −77.6 at the steps after the
/// impact and a slip's restart, with lift-offs and touchdowns 1e-5 apart (without the restart
/// −0.68, then −2.9: docs/model.md, "Flight and touchdown"). With two backward-Euler steps (L-stable:
/// what a step cannot resolve is damped, not rung) N = 2.14, 0.90, then by the trapezoidal
/// rule 0.39, 0.18, 0.12 … down to a lift-off where N falls to zero; with one, N = 2.14, 0.15,
/// 0.12, 0.28, 0.05, 0.07, −0.01 (still ringing; three steps give 2.14, 0.90, 0.52, 0.26, 0.12
/// and take 2.33e-3 for two's 2.03e-3).
/// Their energy loss (first order: `½∫μ|Δv|²` and more a step) is booked with the impact:
/// 2.0e-3, 1.3e-3, 8.6e-4 of a kinetic energy of 0.105–0.107 at dt 0.005, 0.0025, 0.00125 (like
/// `√dt`; in the continuum a plastic impact of a massless point takes nothing).
pub const IMPACT_STEPS: usize = 2;

/// The most events at one instant (without a step between them): a stick, the slip at once
/// of a tip that needs more than μs N, and its stick at once where it slides neither way.
const MAX_INSTANT_EVENTS: usize = 3;

/// Which of a step's event functions: `[lift-off, the contact's own, a side's contact, a
/// friction patch's boundary, and the tip's lift-off and own where a side touches as well]`
/// (a side's: its contact's lift-off and own, another point's, its contact reaching the tip).
const LIFT: usize = 0;
const PHASE: usize = 1;
const SIDE: usize = 2;
const EDGE: usize = 3;
const TIP_LIFT: usize = 4;
const TIP_PHASE: usize = 5;
/// The number of event functions.
const EVENTS: usize = 6;

/// States of a drag saved at its last events (time, samples and events then, the state without
/// them), to go back to where a stick or a stuck step the time step does not resolve is taken
/// again with shorter steps. A clone of the drag does not copy them.
struct Checkpoints<'r, 'o>(Vec<(f64, usize, usize, Box<Drive<'r, 'o>>)>);

impl Clone for Checkpoints<'_, '_> {
    fn clone(&self) -> Self {
        Checkpoints(Vec::new())
    }
}

/// Checkpoints kept (the events before the one a refinement goes back from).
const CHECKPOINTS: usize = 4;

/// How far inside the tip the first side step after the rod's end lay down seeks its contact
/// (`s_c = 1 − SIDE_START` at Newton's start).
const SIDE_START: f64 = 1e-3;

/// How near the tip a side's contact has reached it when the tip takes the contact over
/// ([`Drive::side_to_tip`]). Why not at the tip itself: a step past the tip has no solution
/// in the side's equations (nor in their continuation past it), and near an inflection of the
/// surface the contact reaches the tip like `√(t* − t)` (a grazing: on the corrugation 0.02
/// sin(2πx/0.2) at v 0.05, `1 − s_c ≈ 0.019 √(t* − t)`), so the steps that approach it
/// shorten without end. The hand-over leaves the rod's end turned into the surface by about
/// `κ_h SIDE_AT_TIP` (κ_h the surface's curvature there) and the tip off it by `κ_h
/// SIDE_AT_TIP²/2` (6e-9 at κ_h 1.2): with 1e-3 (until 2026-12-04 the place of a named
/// stop) that turn, 1.1e-3, outlasted the first steps and put the end's points on the surface
/// at once (s = 0.99958); with 1e-4 the end turns away within a step (measured: the 12 drags
/// of the dynamic grid over that corrugation; every approach to 1e-4 solved, 1e-6 failed at
/// v 0.01, dt 0.01 on a mesh limit).
const SIDE_AT_TIP: f64 = 1e-4;

/// How near the tip a side's contact that races towards it is handed over at once where its
/// steps fail ([`Drive::grazes_tip`]). Why: where the rod's end grazes the surface the contact
/// reaches the tip like `√(t* − t)` and its steps may cease to solve before `1 − SIDE_AT_TIP`
/// (measured over the corrugation 0.01 sin(2πx/0.1) at v 0.05: from 1.64e-4 every step down to
/// the shortest, 1e-5, failed, and the drag ended in a solver error after its refinements, 100
/// s). The hand-over then leaves the end turned into the surface by about `κ_h (1 − s_c)`,
/// which the test of its lying down again allows for (`tip_turn0`).
const SIDE_GRAZE: f64 = 1e-3;

/// The rod next to a side's contact that its other-contact test leaves out
/// ([`Drive::side_gap`]): it touches the surface to second order there, its height the
/// collocation's error.
const SIDE_NEAR: f64 = 1e-3;

/// The driver of a dynamic drag.
#[derive(Clone)]
struct Drive<'r, 'o> {
    o: &'o DynDragOptions,
    /// The fixed step (`o.dt`, halved from the last checkpoint where a stick or a stuck step was
    /// not resolved, until `refined_until`).
    dt: f64,
    refined_until: Option<f64>,
    checkpoints: Checkpoints<'r, 'o>,
    /// Where a slip beyond the friction cone began the refinements under way: the state then
    /// (its checkpoints alongside), to go on from as without them if they end in a stop; and
    /// the flag that then accepts that slip.
    cone_origin: Checkpoints<'r, 'o>,
    cone_checkpoints: Checkpoints<'r, 'o>,
    accept_cone: bool,
    /// The drag at the stop that began the refinements under way (the latest such stop, at
    /// most one), and that stop: what the drag returns if a step of the refinements is one the
    /// collocation does not solve.
    stop_origin: Checkpoints<'r, 'o>,
    stop_kept: Option<DynDragStop>,
    path: FootPath<'o>,
    rothe: Rothe<'r>,
    /// The surface the tip touches (as the rod's steps see it: `rothe.track` is the same).
    track: Track,
    t: f64,
    d: f64,
    /// The support's turn `θ_w`.
    turn: f64,
    state: ContactState,
    /// The stuck tip's x.
    anchor: f64,
    /// The surface's friction texture (it replaces `o.mu_s`, `o.mu_k`), if any.
    texture: Option<Arc<Texture>>,
    /// The sliding tip's μk where the texture does not change it along the slide (uniform
    /// friction, or the patch the tip slides on).
    mu_k_now: f64,
    /// The next boundary of the texture's patches ahead of the sliding tip.
    edge: Option<f64>,
    /// The tip's radius `r` (a disk centred at the rod's end; 0: a point tip). With `r > 0`
    /// `track` is the line its centre runs on (the surface lowered by `r` along its normal),
    /// `surface` the surface itself.
    radius: f64,
    /// The surface (the sides' clearance): `track` itself for a point tip.
    surface: Track,
    /// The stuck disk's rolling invariant `w·x(1) − r·φ(1)` ([`TipBc::Rolling`]), or the
    /// rolling side's ([`TipBc::SideRolling`]).
    roll: f64,
    /// The rolling side's sign ([`TipBc::SideRolling`]).
    side_sign: f64,
    /// A side's `s_c` at the last step's start and that step's length, where both ends were a
    /// side's ([`Drive::side_step`]).
    side_before: Option<(f64, f64)>,
    /// The side's contact's smallest `s_c` since it formed (at the tip; 1 before its first
    /// step): the contact returns to the tip ([`Drive::side_to_tip`]) where it comes within
    /// [`Drive::at_tip_room`] of it.
    side_min: f64,
    /// From a side's hand-over to the tip ([`Drive::side_to_tip`]) until the end has turned
    /// away from the surface: how far the end was turned into it at the hand-over (about `κ_h
    /// SIDE_AT_TIP`). Meanwhile the end lies down again only where it turns in further than
    /// that, and the rod within `SIDE_NEAR` of the tip is left out of the test of other points
    /// on the surface. `None`: the tests as they are.
    tip_turn0: Option<f64>,
    /// While a side touches (`state` a side's): the tip on the surface as well, stuck at
    /// `anchor` or sliding (two contacts at once; docs/model.md, "Two contacts in time"), or
    /// `None`, the tip free.
    also_tip: Option<ContactState>,
    /// The step after a slip began (the tip's velocity zero at its start).
    fresh_slip: bool,
    /// The event function of that slip's motion: `PHASE`, or `TIP_PHASE` for the tip's beside
    /// a side.
    slip_slot: usize,
    /// The tip touched down at the present instant (no step taken since): its contact force
    /// there is the flight's zero, not the impact's, which pushes.
    landed: bool,
    /// The forces at the support and the contact (`G(0)`, and the tip's `G(1)` or a side's
    /// contact force) at the last step's start, that step's length and the contact's x at its
    /// start, while the contact's condition has not changed since ([`Drive::held_ends`],
    /// [`Drive::held_contact`]).
    ends_before: Option<([[f64; 2]; 2], f64, f64)>,
    /// [`Drive::held_force`] of the last step taken while the tip is stuck (its tests; `None`
    /// where it was not formed).
    held_now: Option<[f64; 2]>,
    /// [`Drive::held_ends`] of the last step taken (its sample; `None` where it was not formed).
    ends_now: Option<[[f64; 2]; 2]>,
    /// [`Drive::held_contact`] of the last step taken (its sample's `N`, `T`).
    contact_now: Option<(f64, f64)>,
    /// A contact of a pair lets go at once ([`Drive::lets_go_at_once`]): its event's forces
    /// are zero.
    let_go: bool,
    /// The velocity mismatch's term `A` in the held forces (support, tip) of the steps tried
    /// from the present state, where [`Drive::deflate`] found one ([`mismatch_weight`]).
    mismatch: Option<[[f64; 2]; 2]>,
    /// Where that term is in the end forces themselves (before the first event, where the
    /// held forces are not formed): the last step's length `h` of its weight
    /// ([`end_mismatch_weight`]).
    mismatch_end: Option<f64>,
    /// The length of the last step taken (0 before the first).
    last_tau: f64,
    foot_work: f64,
    friction: f64,
    impact: f64,
    samples: Vec<DragSample>,
    events: Vec<DynDragEvent>,
    stats: DragStats,
    /// The steps tried from the present state (since the last step taken or event), by length.
    tried: Vec<(f64, Trial)>,
    /// Events since the last step taken (at the present instant).
    instant_events: usize,
}

/// `N = −G·n`, `T = −G·t` of the tip's force `G(1)` on a track of slope `hp` (unit normal
/// `n = (−h', 1)/w`, tangent `t = (1, h')/w`, `w = √(1 + h'²)`): on a flat one `N = −Gy(1)`,
/// `T = −Gx(1)`.
fn contact_forces(g: [f64; 2], hp: f64) -> (f64, f64) {
    if hp == 0.0 {
        return (-g[1], -g[0]);
    }
    let w = (1.0 + hp * hp).sqrt();
    ((hp * g[0] - g[1]) / w, -(g[0] + hp * g[1]) / w)
}

/// The tip's force `G(1)` of the normal and tangential forces `N`, `T` on a track of slope `hp`
/// (the inverse of [`contact_forces`]): `G = −N n − T t`, `t = (n_y, −n_x)`.
fn tip_force(normal: f64, tangential: f64, hp: f64) -> [f64; 2] {
    let n = unit_normal(hp);
    [
        -normal * n[0] - tangential * n[1],
        -normal * n[1] + tangential * n[0],
    ]
}

/// The unit normal `(−h', 1)/w` of a track of slope `hp`.
fn unit_normal(hp: f64) -> [f64; 2] {
    let w = (1.0 + hp * hp).sqrt();
    [-hp / w, 1.0 / w]
}

/// The velocity `v` along the unit tangent `(1, h')/w` of a track of slope `hp` (`v[0]` on a
/// flat one).
fn along(hp: f64, v: [f64; 2]) -> f64 {
    if hp == 0.0 {
        return v[0];
    }
    (v[0] + hp * v[1]) / (1.0 + hp * hp).sqrt()
}

impl<'r> Drive<'r, '_> {
    fn bc(&self) -> TipBc {
        match self.state {
            ContactState::Stuck if self.radius > 0.0 => TipBc::Rolling { a: self.roll },
            ContactState::Stuck => TipBc::Stuck([self.anchor, self.track.jet(self.anchor).0]),
            ContactState::Flying => TipBc::Force([0.0, 0.0]),
            s if s.side() && self.also_tip.is_some() => TipBc::SideAndTip {
                side: self.side_hold(),
                end: self.end_hold(),
            },
            ContactState::SideStuck => TipBc::SideRolling {
                a: self.roll,
                sign: self.side_sign,
            },
            s if s.side() => TipBc::SideSliding {
                ratio: s.dir() * self.o.mu_k,
            },
            s if !self.o.mu_k_table.is_empty() => TipBc::SlidingRate { dir: s.dir() },
            s if self.varies_along() => TipBc::SlidingOn { dir: s.dir() },
            s => TipBc::Sliding {
                ratio: s.dir() * self.mu_k_now,
            },
        }
    }

    /// How the side holds (`state` a side's).
    fn side_hold(&self) -> SideHold {
        match self.state {
            ContactState::SideStuck => SideHold::Rolling {
                a: self.roll,
                sign: self.side_sign,
            },
            s => SideHold::Sliding {
                ratio: s.dir() * self.o.mu_k,
            },
        }
    }

    /// How the tip holds beside a side ([`Drive::also_tip`]; stuck where it is not sliding).
    fn end_hold(&self) -> EndHold {
        match self.also_tip.map_or(0.0, ContactState::dir) {
            0.0 => EndHold::Stuck([self.anchor, self.track.jet(self.anchor).0]),
            dir => EndHold::Sliding {
                ratio: dir * self.o.mu_k,
            },
        }
    }

    /// The disk's moment condition's `(a, K)` for a step of length `tau`: the tangential force
    /// combined over this step's end and the last two steps' as [`Drive::held_force`] combines
    /// the stuck tip's, `a Tⁿ⁺¹ + ½ Tⁿ + c Tⁿ⁻¹` (`K` the last two terms), since `m(1) = r·T`
    /// would carry the rule's alternating mode of the multiplier `T` into the rod's motion; the
    /// end force itself (`(1, 0)`) without the last step under the same condition.
    fn disk_held(&self, tau: f64) -> (f64, f64) {
        if self.radius == 0.0 {
            return (1.0, 0.0);
        }
        let Some((g_prev, h, x_prev)) = self.ends_before else {
            return (1.0, 0.0);
        };
        let [a, _, c] = held_weights(tau, h);
        let tn = self
            .forces(self.rothe.force(1), self.rothe.sol.right()[0])
            .1;
        let tp = self.forces(g_prev[1], x_prev).1;
        (a, 0.5 * tn + c * tp)
    }

    /// Whether μk changes continuously along the slide (a friction table along x).
    fn varies_along(&self) -> bool {
        self.texture
            .as_ref()
            .is_some_and(|t| t.continuous() && t.uniform_mu_k().is_none())
    }

    /// The x of the point where the tip touches, its end (a disk's centre) at `x`: `x` for a
    /// point tip, `x − r sin β` for a disk on a line of slope `tan β`.
    fn contact_x(&self, x: f64) -> f64 {
        crate::rothe::contact_x(&self.track, self.radius, x)
    }

    /// The stuck disk's rolling invariant of the state `z` at the tip (`[x, y, φ, …]`).
    fn rolling_of(&self, z: &[f64]) -> f64 {
        crate::rothe::rolling_invariant(&self.track, self.radius, z)
    }

    /// The velocity along the surface of the tip's material point that touches it: the end's
    /// velocity `v` along the tangent, less `r·φ̇(1)` for a disk turning at `spin`.
    fn slip_rate(&self, x: f64, v: [f64; 2], spin: f64) -> f64 {
        let vt = along(self.track.jet(x).1, v);
        if self.radius == 0.0 {
            vt
        } else {
            vt - self.radius * spin
        }
    }

    /// `(μs, μk)` at lab `x` (at a patch boundary, the patch on the side `side`).
    fn coefficients(&self, x: f64, side: f64) -> (f64, f64) {
        match &self.texture {
            Some(t) => t.at(x, side),
            None => (self.o.mu_s, self.o.mu_k),
        }
    }

    /// The sliding tip's μk (at rest, with a table of speeds), its end at `x`.
    fn mu_k_at(&self, x: f64) -> f64 {
        if !self.o.mu_k_table.is_empty() {
            crate::rothe::mu_k_of(&self.o.mu_k_table, 0.0).0
        } else if self.varies_along() {
            self.coefficients(self.contact_x(x), self.state.dir()).1
        } else {
            self.mu_k_now
        }
    }

    /// A slide begins (a slip or a touchdown) or crosses a patch's boundary at `x`: its μk is
    /// the patch's ahead of the tip, and its next boundary the one after.
    fn enter_slide(&mut self, x: f64) {
        let dir = self.state.dir();
        self.mu_k_now = self.coefficients(x, dir).1;
        self.edge = self.texture.as_ref().and_then(|t| t.next_boundary(x, dir));
    }

    /// The edge event function: `dir·(x − x_b)` of a tip sliding towards the next patch
    /// boundary `x_b`, at `x` (`−1`: none ahead, or not sliding).
    fn edge_gap(&self, x: f64) -> f64 {
        match (self.state.dir(), self.edge) {
            (dir @ (1.0 | -1.0), Some(xb)) => dir * (self.contact_x(x) - xb),
            _ => -1.0,
        }
    }

    /// The step of length `tau` from the present time, solved.
    fn try_step(&mut self, tau: f64) -> Result<Trial, VibrissaError> {
        if let Some((_, tr)) = self.tried.iter().find(|(t, _)| *t == tau) {
            return Ok(tr.clone());
        }
        let foot = self.path.at(self.t + tau);
        self.stats.solves += 1;
        let bc = self.bc();
        self.rothe.disk_held = self.disk_held(tau);
        let tr = self.rothe.trial(tau, foot, bc, 0.0).map_err(|e| {
            // (a foot at full speed from t = 0 is an impulse on the rod at rest: its
            // acceleration is infinite there, which no step resolves; v 0.2 failed, 0.05 not)
            let impulse = if self.t >= self.o.dt {
                String::new()
            } else if self.path.starts_moving() {
                "; the foot table's spline starts the foot moving at once (its slope at t = 0 is \
                 not 0), an impulse on the rod at rest: rows that start it smoothly resolve it"
                    .to_string()
            } else if self.o.ramp == 0.0 {
                format!(
                    "; the foot starts at speed {} at once (ramp 0), an impulse on the rod at \
                     rest: a ramp > 0 resolves it",
                    self.o.speed
                )
            } else {
                String::new()
            };
            VibrissaError::solver(
                format!(
                    "dynamic drag: the step from t = {} by {tau} ({}){impulse}",
                    self.t,
                    self.state.name()
                ),
                *e,
            )
        })?;
        self.tried.push((tau, tr.clone()));
        Ok(tr)
    }

    /// The tip's normal and tangential force of the tip's force `g` with the tip at `x`.
    fn forces(&self, g: [f64; 2], x: f64) -> (f64, f64) {
        contact_forces(g, self.track.jet(x).1)
    }

    /// The event functions (`< 0` while the contact holds): `−N`, and `|T| − μs N` (stuck) or
    /// `−dir·v_t` (sliding, `v_t` the tip's velocity `v` along the surface), from the forces and
    /// the tip's velocity; flying: none, and the tip's height over the surface `y(1) − h(x(1))`
    /// (minus the gap), the tip at `r`.
    fn events_of(&self, n: f64, t: f64, v: [f64; 2], spin: f64, r: [f64; 2]) -> [f64; 2] {
        let phase = match self.state {
            ContactState::Stuck => {
                t.abs() - self.coefficients(self.contact_x(self.anchor), t.signum()).0 * n
            }
            ContactState::Flying => return [-1.0, r[1] - self.track.jet(r[0]).0],
            s => -s.dir() * self.slip_rate(r[0], v, spin),
        };
        [-n, phase]
    }

    fn events_after(&self, tr: &Trial) -> [f64; EVENTS] {
        if let Some(side) = &tr.side {
            let (n, t) = self
                .held_contact(tr)
                .unwrap_or_else(|| self.forces(side.force, side.z[0]));
            let v = self.rothe.velocity_at(tr, side.s);
            let mut g = self.side_events(n, t, side, v, &tr.sol);
            let r = [tr.sol.right()[0], tr.sol.right()[1]];
            [g[TIP_LIFT], g[TIP_PHASE]] =
                self.tip_beside(tr.force(1), r, self.rothe.tip_velocity(tr));
            return g;
        }
        let r = [tr.sol.right()[0], tr.sol.right()[1]];
        let (n, t) = self.forces(tr.force(1), r[0]);
        let spin = self.rothe.tip_rate(tr, 4);
        let g = self.events_of(n, t, self.rothe.tip_velocity(tr), spin, r);
        let held = (self.state == ContactState::Stuck).then(|| self.held_force(tr));
        let contact = self.sliding_lift().then(|| self.held_contact(tr)).flatten();
        let [lift, phase] = self.held_test(g, held, contact, r);
        [
            lift,
            phase,
            self.side_gap(&tr.sol).0,
            self.edge_gap(r[0]),
            -1.0,
            -1.0,
        ]
    }

    /// The tip's event functions beside a side ([`Drive::also_tip`]; `−1` where the tip is
    /// free): `−N` and `|T| − μs N` (stuck) or `−dir·v_t` (sliding), of its force `g`, its end at
    /// `r` moving at `v`.
    fn tip_beside(&self, g: [f64; 2], r: [f64; 2], v: [f64; 2]) -> [f64; 2] {
        let Some(tip) = self.also_tip else {
            return [-1.0, -1.0];
        };
        let (n, t) = self.forces(g, r[0]);
        let phase = match tip.dir() {
            0.0 => t.abs() - self.o.mu_s * n,
            dir => -dir * along(self.track.jet(r[0]).1, v),
        };
        [-n, phase]
    }

    /// The event functions of a side on the surface (`< 0` while it holds as it does), its
    /// forces `n`, `t`, its material point's velocity `v`: `−N`, `|T| − μs N` (rolling) or
    /// `−dir·v_t` (sliding), the height of the rod's other points over the surface
    /// ([`Drive::side_gap`]) and `s_c − (1 − room)` (the contact reaches the tip: [`Drive::at_tip_room`]).
    fn side_events(
        &self,
        n: f64,
        t: f64,
        side: &SideAt,
        v: [f64; 2],
        sol: &bvp::Solution,
    ) -> [f64; EVENTS] {
        let phase = match self.state {
            ContactState::SideStuck => t.abs() - self.o.mu_s * n,
            // (sliding: its material point's velocity along the surface reverses)
            s => -s.dir() * along(self.track.jet(side.z[0]).1, v),
        };
        [
            -n,
            phase,
            self.side_gap(sol).0,
            side.s - (1.0 - self.at_tip_room()),
            -1.0,
            -1.0,
        ]
    }

    /// How near the tip the side's contact hands the contact over to it: `SIDE_AT_TIP`, or half
    /// the way from the tip to the contact's deepest place where that is nearer (a side that
    /// formed and turns back before it is `2·SIDE_AT_TIP` deep: the end lay down for a moment;
    /// measured on a foot started at once over the corrugation 0.02 sin(2πx/0.2), its side
    /// reached 1.1e-4 from the tip, went back to 7e-6, and its steps then failed, the contact
    /// having no place beyond the tip). 0 before the side's first step.
    fn at_tip_room(&self) -> f64 {
        SIDE_AT_TIP.min(0.5 * (1.0 - self.side_min))
    }

    /// The contact's force now and its x: the side's where one touches, else the tip's.
    fn contact_force_now(&self) -> ([f64; 2], f64) {
        match &self.rothe.side {
            Some(c) => (c.force, c.z[0]),
            None => (self.rothe.force(1), self.rothe.sol.right()[0]),
        }
    }

    /// Whether the rod's end that lies down on the surface (a side contact at `s = 1`) goes on
    /// as a side on it ([`ContactState::side`]): from a stuck or sliding point tip on a line or
    /// a height profile of uniform friction (else the drag stops there, as before).
    fn may_roll(&self, s: f64) -> bool {
        s == 1.0 && self.may_side()
    }

    /// Whether a side may touch beside the point tip (stuck or sliding, or free beyond a side
    /// that touches) on a line or a height profile of uniform friction: the scenes the sides in
    /// time are built for.
    fn may_side(&self) -> bool {
        self.state != ContactState::Flying
            && self.radius == 0.0
            && self.texture.is_none()
            && self.o.mu_k_table.is_empty()
            && matches!(self.track, Track::Line { .. } | Track::Curve(_))
    }

    /// The rod's end lies down on the surface: from here the contact is a side at `s_c < 1`
    /// rolling without slip (its rolling invariant that of the tip now, `s_c = 1`) where the
    /// tip was stuck, else sliding as the tip did.
    fn enter_side(&mut self) {
        let z = self.rothe.sol.right();
        let hp = self.track.jet(z[0]).1;
        let (sp, cp) = z[2].sin_cos();
        self.side_sign = if cp + hp * sp >= 0.0 { 1.0 } else { -1.0 };
        self.roll = crate::rothe::track_arc(&self.track, z[0]).0 - self.side_sign;
        self.rothe.side_guess = 1.0 - SIDE_START;
        self.side_min = 1.0;
        let dir = self.state.dir();
        self.state = if dir == 0.0 {
            ContactState::SideStuck
        } else {
            ContactState::SideStuck.sliding(dir)
        };
    }

    /// A point of the rod at `s < 1` touches the surface beside the tip (stuck or sliding): from
    /// here two contacts, the tip's as it was and a side's at `s_c` near `s` (the rod tangent to
    /// the surface there), sliding the way its material point moves along the surface. The
    /// point reaches the surface with a velocity normal to it that the contact stops: a plastic
    /// impact, taken by backward Euler as a touchdown's ([`IMPACT_STEPS`]; the energy it takes
    /// booked with `impact`).
    fn enter_pair(&mut self, s: f64) {
        let z = self.rothe.sol.at(s);
        let hp = self.track.jet(z[0]).1;
        let (sp, cp) = z[2].sin_cos();
        self.side_sign = if cp + hp * sp >= 0.0 { 1.0 } else { -1.0 };
        self.roll = crate::rothe::track_arc(&self.track, z[0]).0 - self.side_sign * s;
        self.rothe.side_guess = s;
        self.side_min = 1.0;
        self.side_before = None;
        let v = along(hp, self.rothe.velocity_now(s));
        self.also_tip = Some(self.state);
        // (sliding: a side at rest beside a stuck tip would trap the rod, `Drive::traps`; at rest
        // beside a sliding one, its first step's stick finds it)
        self.state = ContactState::SideStuck.sliding(v);
        self.rothe.euler_steps = IMPACT_STEPS;
    }

    /// A side's event `which`: it slips (rolling, `|T| = μs N`: it slides the way `T` pushes
    /// it, after the restart the tip's slip takes), sticks (sliding, its velocity along the
    /// surface zero: it rolls from here), lifts off (the rod flies, with `flight`; else the
    /// drag ends; beside the tip, the tip holds on alone), hands the contact over to the tip
    /// where it reaches the tip ([`Drive::side_to_tip`]; beside the tip, the two meet); the free
    /// tip touches down beside it (a pair from here); the tip's own events beside it
    /// ([`Drive::tip_event_beside`]). The drag stops by name ([`DynDragStop::SideChange`])
    /// where another point reaches the surface, and where a contact would stick beside a stuck
    /// one ([`Drive::traps`]).
    fn apply_side(&mut self, which: usize) -> Option<DynDragStop> {
        let tip_event = which == TIP_LIFT || which == TIP_PHASE;
        if self.instant_events == MAX_INSTANT_EVENTS && tip_event {
            return Some(self.unresolved(self.rothe.force(1)));
        }
        // (another point on the surface: the free tip touches down beside the side, else the
        // drag stops there)
        let lands = which == SIDE
            && self.also_tip.is_none()
            && self.side_gap(&self.rothe.sol).1 == 1.0
            && self.may_side();
        if (which == SIDE && !lands) || self.instant_events == MAX_INSTANT_EVENTS {
            return Some(self.side_stop(self.side_change(which)));
        }
        if self.traps(which) {
            return Some(self.side_stop(SideChange::Trapped));
        }
        let (normal, tangential) = if std::mem::take(&mut self.let_go) {
            (0.0, 0.0)
        } else if tip_event {
            self.forces(self.rothe.force(1), self.rothe.sol.right()[0])
        } else {
            self.contact_now.take().unwrap_or_else(|| {
                let (f, x) = self.contact_force_now();
                self.forces(f, x)
            })
        };
        self.mismatch = None;
        self.mismatch_end = None;
        self.tried.clear();
        self.ends_before = None;
        self.ends_now = None;
        self.held_now = None;
        let kind = if lands {
            let tip = self.land_tip();
            self.also_tip = Some(tip);
            DragEventKind::Touchdown
        } else if tip_event {
            self.tip_event_beside(which)
        } else if which == EDGE && self.also_tip.is_some() {
            // (the side's contact meets the tip's: one contact, the tip's)
            self.side_leaves(true);
            DragEventKind::ToTip
        } else if which == EDGE {
            self.side_to_tip();
            DragEventKind::ToTip
        } else if which == LIFT && self.also_tip.is_some() {
            // (the side lets go, the tip holds on)
            self.side_leaves(false);
            DragEventKind::LiftOff
        } else if which == LIFT {
            if !self.o.flight {
                self.push_event(DragEventKind::LiftOff, normal, tangential);
                return Some(DynDragStop::LiftOff { d: self.d });
            }
            self.state = ContactState::Flying;
            self.rothe.euler_steps = 0;
            DragEventKind::LiftOff
        } else if self.state == ContactState::SideStuck {
            self.state = self.state.sliding(tangential);
            self.fresh_slip = true;
            self.slip_slot = PHASE;
            self.stats.slips += 1;
            self.restart(false);
            DragEventKind::Slip
        } else {
            self.state = ContactState::SideStuck;
            self.fresh_slip = false;
            if let Some(c) = self.rothe.side {
                self.roll = crate::rothe::track_arc(&self.track, c.z[0]).0 - self.side_sign * c.s;
            }
            self.stats.sticks += 1;
            self.restart(false);
            DragEventKind::Stick
        };
        self.push_event(kind, normal, tangential);
        self.instant_events += 1;
        (self.events.len() >= self.o.max_events).then_some(DynDragStop::MaxEvents)
    }

    /// The event a pair meets first (its slot and place), given the first one found from the
    /// whole step's end (`which` at `at`, searched from `lo`): every event function at the end
    /// of the step to `at` decides, not only those the whole step's end had met; one met there
    /// is searched before `at`, and within the shortest step (where the steps resolve no
    /// order) the first met in the order lift-off (the side's, the tip's), slip or stick,
    /// contact, hand-over. Elsewhere `(which, at)`.
    ///
    /// Why: in an impact's first steps a contact's `N` may pass below zero and back within
    /// the step. Measured with Kelvin–Voigt damping 0.01 over 0.02 sin(2πx/0.2) (v 0.01, grid
    /// 100, tol 1e-8), a side arriving beside the stuck tip: the tip's slip was found 1e-5
    /// after it with the tip's `N` at −0.62 (dt 0.01; −7.0 at dt 0.02, 2.3e-5 after it),
    /// its lift-off unseen by the whole step's end.
    fn first_met(
        &mut self,
        (which, at): (usize, f64),
        lo: f64,
        shortest: f64,
    ) -> Result<(usize, f64), VibrissaError> {
        const ORDER: [usize; EVENTS] = [LIFT, TIP_LIFT, PHASE, TIP_PHASE, SIDE, EDGE];
        let (mut which, mut at) = (which, at);
        if !self.state.side() || self.also_tip.is_none() {
            return Ok((which, at));
        }
        for _ in 0..EVENTS {
            let tr = self.try_step(at.max(shortest))?;
            let g = self.events_after(&tr);
            let in_order = ORDER.into_iter().find(|&w| g[w] >= 0.0).unwrap_or(which);
            if at <= shortest {
                return Ok((in_order, at));
            }
            let Some(w) = ORDER.into_iter().find(|&w| w != which && g[w] >= 0.0) else {
                break;
            };
            let a = self.locate(w, lo, at)?;
            // (found at the same place: the two are met at once)
            if a >= at - self.o.event_tol {
                return Ok((in_order, at));
            }
            (which, at) = (w, a);
        }
        Ok((which, at))
    }

    /// Whether event `which`, located at `at` in a step whose shortest is `shortest`, is one
    /// contact of a pair letting go at once: a lift-off (the side's or the tip's) within the
    /// step's shortest step (typically the first of the impact by which the other contact
    /// arrived, [`Drive::enter_pair`], [`Drive::land_tip`]). It is then applied at the step's
    /// start, its forces zero, without that step: the step held the contact with a pull (the
    /// impulse it would need is tensile), which a contact does not give, and below the
    /// shortest step the steps do not resolve where `N` passes zero.
    ///
    /// Why: measured with Kelvin–Voigt damping 0.01 over 0.02 sin(2πx/0.2) (v 0.05, dt 0.01,
    /// grid 100, tol 1e-8), the side arriving beside the sliding tip left the tip's lift-off at
    /// the first step of 1e-5 with N = −11.6 (−9.2 at dt 0.02, −11.7 at dt 0.005): a row of a
    /// tensile contact, and its pull taken into the rod's motion.
    fn lets_go_at_once(&self, which: usize, at: f64, shortest: f64) -> bool {
        (which == LIFT || which == TIP_LIFT)
            && self.state.side()
            && self.also_tip.is_some()
            && at <= shortest
    }

    /// The tip's own event beside a side (`which`: `TIP_LIFT` or `TIP_PHASE`): it lifts off
    /// (the side holds on, the tip free beyond it), or slips the way its force pushes it
    /// (stuck), or sticks where it is (sliding); the scheme restarts as at the tip's own.
    fn tip_event_beside(&mut self, which: usize) -> DragEventKind {
        let tip = self.also_tip.unwrap_or(ContactState::Stuck);
        let kind = if which == TIP_LIFT {
            self.also_tip = None;
            DragEventKind::LiftOff
        } else if tip == ContactState::Stuck {
            let (_, t) = self.forces(self.rothe.force(1), self.rothe.sol.right()[0]);
            self.also_tip = Some(tip.sliding(t));
            self.fresh_slip = true;
            self.slip_slot = TIP_PHASE;
            self.stats.slips += 1;
            DragEventKind::Slip
        } else {
            self.also_tip = Some(ContactState::Stuck);
            self.anchor = self.rothe.sol.right()[0];
            self.rothe.hold_tip_x();
            if !self.track.flat() {
                self.rothe.hold_tip_y();
            }
            self.stats.sticks += 1;
            DragEventKind::Stick
        };
        self.restart(false);
        kind
    }

    /// The side lets go while the tip holds on (it lifts off, or its contact meets the tip's,
    /// `merge`): the tip's contact alone from here, stuck or sliding as it was, and the scheme
    /// restarts. After a merge the end lies on the surface: its lying down again counts only a
    /// turn beyond the present one (`tip_turn0`, as after [`Drive::side_to_tip`]).
    fn side_leaves(&mut self, merge: bool) {
        let tip = self.also_tip.take().unwrap_or(ContactState::Stuck);
        let z = self.rothe.sol.right().to_vec();
        self.rothe.leave_side();
        self.state = tip;
        if tip.dir() != 0.0 {
            self.enter_slide(self.contact_x(z[0]));
        }
        if merge {
            self.tip_turn0 = Some(self.turn_in(&z));
        }
        self.side_before = None;
        self.restart(false);
    }

    /// The side's contact has reached the tip (within [`Drive::at_tip_room`]): the tip takes it
    /// over, stuck at its place where the side rolled, sliding the same way where it slid, and
    /// the scheme restarts as at a stick (its contact force now the tip's). The tip's velocity
    /// is made the contact's (zero along the surface where it sticks, along it where it slides;
    /// the tip moved at the contact's velocity plus the rod's turn times that room): the
    /// kinetic energy this takes is booked with `impact`. The test of the end lying down again
    /// waits until it has turned away from the surface (`tip_turn0`).
    fn side_to_tip(&mut self) {
        let dir = self.state.dir();
        let z = self.rothe.sol.right().to_vec();
        let (x, hp) = (z[0], self.track.jet(z[0]).1);
        let before = self.rothe.sample(self.t).kinetic;
        self.rothe.leave_side();
        if dir == 0.0 {
            self.state = ContactState::Stuck;
            self.anchor = x;
            self.rothe.hold_tip_x();
            self.rothe.hold_tip_y();
        } else {
            self.state = ContactState::Stuck.sliding(dir);
            self.enter_slide(self.contact_x(x));
            self.rothe.hold_tip_normal(unit_normal(hp));
        }
        let after = self.rothe.sample(self.t).kinetic;
        self.impact += before - after;
        self.tip_turn0 = Some(self.turn_in(&z));
        self.side_before = None;
        self.restart(false);
    }

    /// The step `tau`, shortened where a side's contact, moving towards the tip at the rate of
    /// the last step, would cover more than half its way to `1 − room/2` within it (`room`
    /// [`Drive::at_tip_room`]): to the step that covers half (no shorter than `shortest`), so
    /// that the contact's event at `1 − room` is found in a step that solves (past the tip the
    /// step's equations have no solution: a rod tangent to the surface at its free end grazes
    /// it).
    fn side_step(&self, tau: f64, shortest: f64) -> f64 {
        let Some((s, rate)) = self.side_rate() else {
            return tau;
        };
        // (a contact at rest or moving inwards, or a rate that is not a number: as it is)
        if rate.is_nan() || rate <= 0.0 {
            return tau;
        }
        // (half the room at the present rate: the contact speeds up as it nears the tip, where
        // its rate grows without bound as the rod grazes the surface)
        let reach = 0.5 * (1.0 - 0.5 * self.at_tip_room() - s) / rate;
        if reach < tau {
            reach.max(shortest).min(tau)
        } else {
            tau
        }
    }

    /// What a contact that has just stuck (a restart under way) does at once: a side's
    /// ([`Drive::side_at_once`]); a tip that needs more than μs N at once slips at once (only a
    /// restart changes the forces a step's end left inside the limits), one that needs a pull
    /// at once slips or lifts off at once where Coulomb's law allows it
    /// ([`Drive::unstick_at_once`]), else is a stick the step does not resolve.
    /// `Some(Some(stop))` where the drag ends, `Some(None)` where an event was applied, `None`
    /// where nothing happens at once.
    fn changes_at_once(&mut self) -> Option<Option<DynDragStop>> {
        if let Some(r) = self.side_at_once() {
            return Some(r);
        }
        if self.state != ContactState::Stuck || !self.rothe.restarted() {
            return None;
        }
        let now = self.events_now();
        if now[LIFT] >= 0.0 {
            return Some(
                self.unstick_at_once()
                    .unwrap_or_else(|| Some(self.unresolved(self.rothe.force(1)))),
            );
        }
        (now[PHASE] >= 0.0).then(|| self.apply(PHASE))
    }

    /// A side that has just stuck (a restart under way), or the tip stuck beside it, and needs
    /// more than μs N, or a pull, at once: it slips or lifts at once, within the events an
    /// instant may have. `Some(Some(stop))` where the drag ends, `Some(None)` where an event was
    /// applied, `None` where nothing happens at once.
    fn side_at_once(&mut self) -> Option<Option<DynDragStop>> {
        if !self.state.side() || !self.rothe.restarted() {
            return None;
        }
        let now = self.events_now();
        let side = (self.state == ContactState::SideStuck).then_some([LIFT, PHASE]);
        let tip = (self.also_tip == Some(ContactState::Stuck)).then_some([TIP_LIFT, TIP_PHASE]);
        let which = [side, tip]
            .into_iter()
            .flatten()
            .flatten()
            .find(|&w| now[w] >= 0.0)?;
        Some(self.apply(which))
    }

    /// The step of length `tau` from the present state, a side's shortened by
    /// [`Drive::side_step`] and, where it fails, by [`Drive::side_shorter`]: its length and
    /// trial.
    fn step_from_here(&mut self, tau: f64, tau_min: f64) -> Result<(f64, Trial), VibrissaError> {
        let tau = self.side_step(tau, tau_min);
        match self.try_step(tau) {
            Ok(tr) => Ok((tau, tr)),
            Err(e) => self.side_shorter(tau, tau_min).ok_or(e),
        }
    }

    /// Whether the side's contact, within [`SIDE_GRAZE`] of the tip, moved towards it over the
    /// last step: where its steps then fail (at every length down to the shortest), the tip
    /// takes the contact over at once ([`Drive::side_to_tip`]) rather than at `1 − room`.
    fn grazes_tip(&self) -> bool {
        self.state.side()
            && self
                .side_rate()
                .is_some_and(|(s, rate)| s > 1.0 - SIDE_GRAZE && rate > 0.0)
    }

    /// Whether event `which` sticks a contact beside a stuck one: the sliding side beside the
    /// stuck tip, or the sliding tip beside the rolling side ([`SideChange::Trapped`]).
    fn traps(&self, which: usize) -> bool {
        match which {
            PHASE => self.state.dir() != 0.0 && self.also_tip == Some(ContactState::Stuck),
            TIP_PHASE => {
                self.state == ContactState::SideStuck
                    && self.also_tip.is_some_and(|t| t.dir() != 0.0)
            }
            _ => false,
        }
    }

    /// The side's contact `s_c` now and the rate it moved at over the last step (towards the
    /// tip where positive), where both ends of that step were a side's.
    fn side_rate(&self) -> Option<(f64, f64)> {
        let (Some(c), Some((s_prev, h))) = (&self.rothe.side, self.side_before) else {
            return None;
        };
        Some((c.s, (c.s - s_prev) / h))
    }

    /// A side's step that failed (`tau`), taken at `tau/2`, `tau/4`, … (no shorter than
    /// `shortest`, four halvings at most): the first that solves, with its length; `None` for a
    /// tip's step or where none solves. Why: a side's contact speeds up as it nears the tip and a
    /// step that would carry it past the tip has no solution (see [`Drive::side_step`]).
    fn side_shorter(&mut self, tau: f64, shortest: f64) -> Option<(f64, Trial)> {
        if !self.state.side() {
            return None;
        }
        let mut t = tau;
        for _ in 0..4 {
            t *= 0.5;
            if t < shortest {
                return None;
            }
            if let Ok(tr) = self.try_step(t) {
                return Some((t, tr));
            }
        }
        None
    }

    /// The side's change by event `which` where the drag does not follow it.
    fn side_change(&self, which: usize) -> SideChange {
        match which {
            LIFT => SideChange::LiftOff,
            PHASE => SideChange::Slip,
            SIDE if self.also_tip.is_some() => SideChange::ThirdContact,
            SIDE => SideChange::SecondContact,
            _ => SideChange::AtTip,
        }
    }

    /// The stop where the side changes its contact by `change`.
    fn side_stop(&self, change: SideChange) -> DynDragStop {
        let (s, x, (normal, tangential)) = match &self.rothe.side {
            Some(side) => (
                side.s,
                side.z[0],
                self.contact_now
                    .unwrap_or_else(|| self.forces(side.force, side.z[0])),
            ),
            None => {
                let x = self.rothe.sol.right()[0];
                (1.0, x, self.forces(self.rothe.force(1), x))
            }
        };
        DynDragStop::SideChange {
            change,
            t: self.t,
            d: self.d,
            s,
            x,
            normal,
            tangential,
        }
    }

    /// How far the rod's end at the state `z` at `s = 1` (`[x, y, φ, …]`) turns into the
    /// surface, `h'(x) cos φ − sin φ` (`< 0`: away from it).
    fn turn_in(&self, z: &[f64]) -> f64 {
        let (sp, cp) = z[2].sin_cos();
        self.track.jet(z[0]).1 * cp - sp
    }

    /// The largest height of the rod's points over the surface, `max (y − h(x))` over the
    /// solution's nodes but its ends (`< 0` while only the tip touches: the foot is below the
    /// surface, the tip on it), with its node's `s` and `x`; and, while the tip touches, how
    /// far its end turns into the surface, `h'(x) cos φ − sin φ` at `s = 1` (the height over
    /// the surface of the points just before a touching tip falls like `(1 − s)` times it:
    /// where it reaches 0 the rod's end lies down on the surface, as the quasi-static drag's
    /// touchdown of a side at the tip), also beside a side; while a side touches and the tip is
    /// free, the tip's height over the surface (its node's `s` 1: the tip touches down beside
    /// the side) where the contact is more than `SIDE_NEAR` from it.
    fn side_gap(&self, sol: &bvp::Solution) -> (f64, f64, f64) {
        let mut worst = (f64::NEG_INFINITY, f64::NAN, f64::NAN);
        let tip_on = !self.state.side() || self.also_tip.is_some();
        if self.state != ContactState::Flying && tip_on && self.radius == 0.0 {
            // (a disk meets the surface at any angle: its end does not turn into it)
            let z = sol.right();
            let turn = self.turn_in(z) - self.tip_turn0.map_or(0.0, |t0| t0.max(0.0));
            worst = (turn, 1.0, z[0]);
        }
        // (a side step's contact: its node twice; the rod next to it, within `SIDE_NEAR`,
        // touches the surface to second order there, its height the collocation's error)
        let contact = sol.mesh.windows(2).find(|w| w[0] == w[1]).map(|w| w[0]);
        // (after a side's hand-over to the tip, until its end turns away: the end next to the
        // tip, off the surface by `κ_h SIDE_AT_TIP²/2` at most)
        let end = if self.tip_turn0.is_none() || self.state.side() {
            1.0
        } else {
            1.0 - SIDE_NEAR
        };
        let away = |s: f64| !contact.is_some_and(|sc| (s - sc).abs() < SIDE_NEAR) && s <= end;
        let last = sol.len().saturating_sub(1);
        let mut node = None;
        for i in 1..last {
            if !away(sol.mesh[i]) {
                continue;
            }
            let z = sol.node(i);
            let gap = z[1] - self.surface.jet(z[0]).0;
            if gap > worst.0 || gap.is_nan() {
                worst = (gap, sol.mesh[i], z[0]);
                node = Some(i);
            }
        }
        if let Some(i) = node.filter(|_| worst.0.is_finite()) {
            worst = self.highest_between(sol, i, &away).unwrap_or(worst);
        }
        if !tip_on && contact.is_some_and(|sc| 1.0 - sc > SIDE_NEAR) {
            let z = sol.right();
            let gap = z[1] - self.surface.jet(z[0]).0;
            if gap > worst.0 || gap.is_nan() {
                worst = (gap, 1.0, z[0]);
            }
        }
        worst
    }

    /// The rod's largest height over the surface between the nodes on either side of node `i`
    /// of `sol` (next to the tip to `1 − SIDE_NEAR`: the tip's height is its condition, and the
    /// end's turn tests the rod next to it; within the points `away` admits), by Brent's
    /// maximum on the solution's dense output: `(gap, s, x)`, `None` where the search fails or
    /// finds less than the node's.
    ///
    /// Why: the rod and the surface curve differently, so between nodes `h` apart the rod's
    /// highest point is above the highest node's by up to `|κ − κ_h| h²/8`: over 0.01
    /// sin(2πx/0.1) (κ_h up to 39) on 100 intervals 5e-4, so a point reached the surface that
    /// deep before the nodes saw it, and the contact that formed there had to push the rod out
    /// by that within a step (forces of hundreds where the rod's are a few).
    fn highest_between(
        &self,
        sol: &bvp::Solution,
        i: usize,
        away: &dyn Fn(f64) -> bool,
    ) -> Option<(f64, f64, f64)> {
        let last = sol.len() - 1;
        let mut lo = sol.mesh[i - 1];
        // (next to the tip: to `SIDE_NEAR` from it, where the end's turn takes over)
        let mut hi = if i + 1 < last {
            sol.mesh[i + 1]
        } else {
            1.0 - SIDE_NEAR
        };
        // (keep to the points admitted: shrink towards the node)
        let si = sol.mesh[i];
        while !away(lo) && lo < si {
            lo = 0.5 * (lo + si);
        }
        while !away(hi) && hi > si {
            hi = 0.5 * (hi + si);
        }
        if hi <= lo || hi.is_nan() || lo.is_nan() {
            return None;
        }
        let height = |s: f64| -> (f64, f64) {
            let z = sol.at(s);
            (z[1] - self.surface.jet(z[0]).0, z[0])
        };
        let mut f = |s: f64| -> Result<f64, std::convert::Infallible> { Ok(height(s).0) };
        let (s, _) = crate::search::maximize(&mut f, lo, hi, 1e-9).ok()?;
        let (gap, x) = height(s);
        let node = height(si).0;
        (gap >= node).then_some((gap, s, x))
    }

    /// The event functions `g` with the stuck tip's tests (slip and lift-off) taken on the held
    /// force `held` ([`Drive::held_force`]) where there is one, and a sliding tip's lift-off on
    /// the held contact force `contact` ([`Drive::held_contact`], see [`Drive::sliding_lift`])
    /// where there is one, the tip at `r`. (The stuck tip's lift-off too: the rule's mode
    /// reaches ±1.4 in the stuck paper's rod's N = 4 at dt 0.02 after a few slips, and a whisk
    /// drawn back, where N falls, read a lift-off at N = −0.18 where the held force had N = 2.3.)
    fn held_test(
        &self,
        g: [f64; 2],
        held: Option<[f64; 2]>,
        contact: Option<(f64, f64)>,
        r: [f64; 2],
    ) -> [f64; 2] {
        match (self.state, held, contact) {
            (ContactState::Stuck, Some(held), _) => {
                let (n, t) = self.forces(held, r[0]);
                self.events_of(n, t, [0.0, 0.0], 0.0, r)
            }
            (s, _, Some((n, _))) if s.dir() != 0.0 => [-n, g[1]],
            _ => g,
        }
    }

    /// The stuck tip's force at the end of the trial `tr` for the slip's test, without the
    /// trapezoidal rule's alternating mode: `a Gⁿ⁺¹ + ½ Gⁿ + c Gⁿ⁻¹` with
    /// `a = (τ + h/2)/(τ + h)`, `c = −τ/(2(τ + h))` (`τ` this step, `h` the last).
    ///
    /// Why: the held tip's force is a multiplier of the rod's constraints, and the rule leaves
    /// in it a mode `e, −e, e, …` that changes sign every step whatever its length and does not
    /// enter the motion (the momentum takes the forces' mean over each step). Excited at every
    /// slip and stick, it grew during a stuck phase, about linearly in time, to ±0.04 in T/N at
    /// dt 0.01, 0.005 and 0.0025 alike (docs/model.md), so it, not the rod,
    /// decided which crest of the stuck rod's ringing reached μs N. The weights sum to 1, are
    /// exact for a force linear in time, and cancel the mode (`a − ½ + c = 0`). Without the
    /// last step under the same condition (after a slip, a stick or the start) the force at
    /// the step's end itself. The weights ([`held_weights`]) hold for steps of any lengths
    /// (adaptive steps, and steps an event shortened): the mode keeps its size whatever the
    /// steps, since the momentum takes the mean of each step's two end forces.
    fn held_force(&self, tr: &Trial) -> [f64; 2] {
        self.held_ends(tr).map_or_else(|| tr.force(1), |g| g[1])
    }

    /// The forces at both ends, the support's and the contact's (the tip's, or a side's), at
    /// the end of the trial `tr` without the rule's alternating mode, as [`Drive::held_force`]
    /// forms the tip's (`None` without the last step under the same condition; before the
    /// first event the end forces less the velocity mismatch's term where [`Drive::deflate`]
    /// found one, else `None`). The support's force is a multiplier too (of the foot's place)
    /// and carries the same mode: ±0.5 in the paper's rod's `fy ≈ −4` at dt 0.02 after a few
    /// slips, sliding or stuck. The rows report these.
    fn held_ends(&self, tr: &Trial) -> Option<[[f64; 2]; 2]> {
        let Some((g_prev, h, _)) = self.ends_before else {
            // (before the first event: the end forces, less the velocity mismatch's term where
            // [`Drive::deflate`] found one)
            let (m, h) = (self.mismatch?, self.mismatch_end?);
            let w = end_mismatch_weight(tr.tau, h);
            return Some([0, 1].map(|e| {
                let g = tr.force(e);
                [0, 1].map(|k| g[k] - m[e][k] * w)
            }));
        };
        let [a, b, c] = held_weights(tr.tau, h);
        let (m, w) = (
            self.mismatch.unwrap_or_default(),
            mismatch_weight(tr.tau, h),
        );
        Some([0, 1].map(|e| {
            // (the contact's, as `ends_before` holds it: the tip's, or a side's)
            let (g1, g0) = if e == 0 {
                (tr.force(0), self.rothe.force(0))
            } else {
                (tr.contact().0, self.contact_force_now().0)
            };
            [0, 1].map(|k| a * g1[k] + b * g0[k] + c * g_prev[e][k] - m[e][k] * w)
        }))
    }

    /// Takes the velocity mismatch's term out of the held forces of the steps tried from the
    /// present state: `held(τ) − held_now = Ġ τ + A w(τ)` ([`mismatch_weight`]) fitted to the
    /// shortest step `short` and the full step `tr`, and kept where the step between them
    /// (their geometric mean) lies on it to a tenth of the tip's force (the bound of
    /// [`Drive::jumped`]); otherwise none is taken out.
    ///
    /// Why: the event search of a stuck tip reads its held force at steps down to `short`,
    /// where the term `A/(2τ)` outgrows the force: at the paper's rod (dt 0.0025, default tol)
    /// 1.18 of 5.2 at τ = 1e-5. The search put a slip there, and the drag stopped as
    /// `unresolved_step` after three slips where dt 0.01 went through ten: the finer the step,
    /// the sooner. Without the term the same drags reach d_max through ten slips at dt 0.01,
    /// 0.005 and 0.0025 (docs/model.md). Before the first event, where the held forces are not
    /// formed, the same fit on the end forces themselves ([`end_mismatch_weight`]).
    fn deflate(&mut self, tr: &Trial, short: f64) {
        self.mismatch = None;
        self.mismatch_end = None;
        // (before the first event the end forces themselves: see [`end_mismatch_weight`])
        let plain = self.ends_before.is_none() && self.events.is_empty() && self.last_tau > 0.0;
        let (now, h) = match (self.ends_now, self.ends_before) {
            (Some(now), Some((_, h, _))) => (now, h),
            _ if plain => (
                self.ends_now
                    .unwrap_or([self.rothe.force(0), self.rothe.force(1)]),
                self.last_tau,
            ),
            _ => return,
        };
        let weight = if plain {
            end_mismatch_weight
        } else {
            mismatch_weight
        };
        let ends = |me: &Self, t: &Trial| {
            if plain {
                Some([t.force(0), t.force(1)])
            } else {
                me.held_ends(t)
            }
        };
        let mid = (short * tr.tau).sqrt();
        if mid <= short || mid >= tr.tau {
            return;
        }
        // (a step these two lengths do not solve leaves the search as it was: the test is
        // the search's own, not a condition of the drag)
        let Ok(ts) = self.try_step(short) else {
            return;
        };
        let (Some(es), Some(ef)) = (ends(self, &ts), ends(self, tr)) else {
            return;
        };
        let (ws, wf) = (weight(short, h), weight(tr.tau, h));
        let det = short * wf - tr.tau * ws;
        let mut rate = [[0.0; 2]; 2];
        let mut term = [[0.0; 2]; 2];
        for e in 0..2 {
            for k in 0..2 {
                let (ds, df) = (es[e][k] - now[e][k], ef[e][k] - now[e][k]);
                term[e][k] = (short * df - tr.tau * ds) / det;
                rate[e][k] = (ds * wf - df * ws) / det;
            }
        }
        let Some(em) = self.try_step(mid).ok().and_then(|tm| ends(self, &tm)) else {
            return;
        };
        let wm = weight(mid, h);
        let miss = |k: usize| em[1][k] - term[1][k] * wm - now[1][k] - rate[1][k] * mid;
        let fits = miss(0).hypot(miss(1)) <= 0.1 * now[1][0].hypot(now[1][1]);
        if fits {
            self.mismatch = Some(term);
            self.mismatch_end = plain.then_some(h);
        }
    }

    /// The tip's `N` and `T` at the end of the trial `tr` without the rule's alternating mode:
    /// the weights of [`Drive::held_ends`] on the three forces' `N` and `T`, each taken along the
    /// surface's normal where the tip then was (the same as the held force's `N`, `T` on a flat
    /// surface; on a curve a sliding tip's `|T| = μk N` holds in each, and so in the
    /// combination, not in the combined force read at one place).
    fn held_contact(&self, tr: &Trial) -> Option<(f64, f64)> {
        if self.state == ContactState::Flying {
            // (a free tip has no contact force: the last contact step's end force, which the
            // combination would carry into the first steps of a flight, is not its)
            return Some((0.0, 0.0));
        }
        let Some((g_prev, h, x_prev)) = self.ends_before else {
            // (a side's contact force as the step's end left it)
            return tr.side.map(|c| self.forces(c.force, c.z[0]));
        };
        let [a, b, c] = held_weights(tr.tau, h);
        // (the contact's: the tip's, or a side's where one touches, the one before it formed
        // the tip's)
        let ((g1, x1), (g0, x0)) = (tr.contact(), self.contact_force_now());
        let nt = [
            self.forces(g1, x1),
            self.forces(g0, x0),
            self.forces(g_prev[1], x_prev),
        ];
        let w = mismatch_weight(tr.tau, h);
        let (mn, mt) = self.mismatch.map_or((0.0, 0.0), |m| self.forces(m[1], x1));
        let normal = a * nt[0].0 + b * nt[1].0 + c * nt[2].0 - mn * w;
        if self.varies_along() && self.state.dir() != 0.0 {
            // (μk changes along the slide: each force meets its own place's, the combination
            // none; the slide's law at the step's end, on the combined N)
            return Some((normal, self.state.dir() * self.mu_k_at(x1) * normal));
        }
        Some((normal, a * nt[0].1 + b * nt[1].1 + c * nt[2].1 - mt * w))
    }

    /// Whether the lift-off's test takes the held contact force ([`Drive::held_contact`]):
    /// a sliding tip's (a stuck tip's takes the held force, [`Drive::held_test`]).
    ///
    /// Why: the sliding tip's normal force carries the rule's alternating mode too, and after
    /// a touchdown it decided the lift-off: on the precurved rod that flies (tests/dynamic_drag.rs,
    /// dt 0.0025) the end force's N reached zero where the held N was 0.062, the tip flew
    /// 1e-5, 2.5e-9 into the surface, touched down again and lifted off at N = 0.064.
    fn sliding_lift(&self) -> bool {
        self.state.dir() != 0.0
    }

    fn events_now(&self) -> [f64; EVENTS] {
        if self.state.side() {
            return match &self.rothe.side {
                Some(side) => {
                    let (n, t) = self
                        .contact_now
                        .unwrap_or_else(|| self.forces(side.force, side.z[0]));
                    let v = self.rothe.velocity_now(side.s);
                    let mut g = self.side_events(n, t, side, v, &self.rothe.sol);
                    [g[TIP_LIFT], g[TIP_PHASE]] = self.tip_beside_now();
                    g
                }
                // (a side that has just formed beside the tip: its force rises from zero, and the
                // tip's force, as the last step left it, carries the rule's alternating mode its
                // held force had removed: the first step's end decides, as after a touchdown)
                None if self.also_tip.is_some() => [-1.0; EVENTS],
                // (the side has just formed at the tip: it moves inwards)
                None => {
                    let x = self.rothe.sol.right()[0];
                    let (n, t) = self.forces(self.rothe.force(1), x);
                    [-n, t.abs() - self.o.mu_s * n, -1.0, -1.0, -1.0, -1.0]
                }
            };
        }
        let p = self.rothe.sample(self.t);
        let r = [p.tip_x, p.tip_y];
        let (n, t) = self.forces(self.rothe.force(1), r[0]);
        let g = self.events_of(n, t, [p.tip_vx, p.tip_vy], self.rothe.tip_spin(), r);
        let contact = self.contact_now.filter(|_| self.sliding_lift());
        let [mut lift, phase] = self.held_test(g, self.held_now, contact, r);
        if self.landed {
            // (the impact's force at `t⁺` is compressive, like `t^(-1/2)`: a lift-off in the
            // first step after a touchdown is where its N falls to zero, not at its start,
            // where the flight's N = 0 would place it: measured, a lift-off at N = 6.1)
            lift = -1.0;
        }
        [
            lift,
            phase,
            self.side_gap(&self.rothe.sol).0,
            self.edge_gap(r[0]),
            -1.0,
            -1.0,
        ]
    }

    /// [`Drive::tip_beside`] now (a tip that has just touched down beside the side: no
    /// lift-off at once, its impact's force pushes).
    fn tip_beside_now(&self) -> [f64; 2] {
        if self.also_tip.is_none() {
            // (the tip free: no event of its own; not the sample's energies for nothing)
            return [-1.0, -1.0];
        }
        let p = self.rothe.sample(self.t);
        let [lift, phase] = self.tip_beside(
            self.rothe.force(1),
            [p.tip_x, p.tip_y],
            [p.tip_vx, p.tip_vy],
        );
        [if self.landed { -1.0 } else { lift }, phase]
    }

    /// Takes the step: the energies by the step's rule (the trapezoidal rule's, backward
    /// Euler's in an impact's steps), a sample.
    fn take(&mut self, tr: Trial) {
        self.landed = false;
        // (a slip beyond the cone accepted after its refinements is the step taken next)
        self.accept_cone = false;
        let euler = tr.euler;
        let energy_before =
            self.samples.last().filter(|_| euler).map(|p| {
                p.kinetic + p.elastic + p.damper + p.internal_damping + p.external_damping
            });
        self.tried.clear();
        self.instant_events = 0;
        let (g0, g1, x1, y1, d_old, turn_old, m0) = (
            self.rothe.force(0),
            self.rothe.force(1),
            self.rothe.sol.right()[0],
            self.rothe.sol.right()[1],
            self.d,
            self.turn,
            self.rothe.sol.left()[3],
        );
        // (after a restart the end's moment is the restarted force's `r·T`, not the last
        // solution's: the tip's condition changed there)
        let m1 =
            if self.radius > 0.0 && self.rothe.restarted() && self.state != ContactState::Flying {
                self.radius * self.forces(g1, x1).1
            } else {
                self.rothe.sol.right()[3]
            };
        let phi1 = self.rothe.sol.right()[2];
        let tau = tr.tau;
        let ends = self.held_ends(&tr);
        let contact = self.held_contact(&tr);
        self.mismatch = None;
        self.mismatch_end = None;
        self.last_tau = tau;
        let held = ends
            .filter(|_| self.state == ContactState::Stuck)
            .map(|g| g[1]);
        // (the contact's force at the step's start: a side's, where one touches)
        let (gc, xc) = self.contact_force_now();
        self.side_before = match (&self.rothe.side, &tr.side) {
            (Some(c0), Some(_)) => Some((c0.s, tr.tau)),
            _ => None,
        };
        if let Some(c) = tr.side {
            self.side_min = self.side_min.min(c.s);
        }
        if self.tip_turn0.is_some()
            && (self.state.side()
                || self.state == ContactState::Flying
                || self.turn_in(tr.sol.right()) < 0.0)
        {
            // (the end turned away from the surface, or another contact now)
            self.tip_turn0 = None;
        }

        // a sliding side's friction: the contact force's work on its material point, by the
        // trapezoidal rule (`½τ (F⁰·v⁰ + F¹·v¹)`; the point moves along the rod). At the step's
        // start of a side that has just formed, its force is the tip's `G(1)` where the end lay
        // down (the contact was the tip's), zero beside the tip (a new contact); until
        // 2026-12-04 that first step's friction was left out of the balance (1.7e-4 of a slide
        // over 0.01 sin(2πx/0.1)).
        let side_work = match (&tr.side, &self.rothe.side) {
            (Some(c1), c0) if self.state.dir() != 0.0 => {
                let (f0, v0) = match c0 {
                    Some(c0) => (c0.force, self.rothe.velocity_now(c0.s)),
                    None if self.also_tip.is_none() => {
                        (self.rothe.force(1), self.rothe.velocity_now(1.0))
                    }
                    None => ([0.0, 0.0], [0.0, 0.0]),
                };
                let v1 = self.rothe.velocity_at(&tr, c1.s);
                let dot = |f: [f64; 2], v: [f64; 2]| f[0] * v[0] + f[1] * v[1];
                // (an impact's backward-Euler step: the force and velocity at its end)
                let w0 = if euler { 0.0 } else { 0.5 };
                tr.tau * (w0 * dot(f0, v0) + (1.0 - w0) * dot(c1.force, v1))
            }
            _ => 0.0,
        };
        self.rothe.commit(tr);
        // (the drag's start is consistent and smooth: no mode to remove before the first event;
        // the velocity mismatch's term then comes out of the end forces, `end_mismatch_weight`)
        // (nor after an impact's backward-Euler step: the held force's weights cancel the
        // trapezoidal rule's mode and need its three forces; measured, a round tip's held force
        // across the switch back read a lift-off at N = −0.41, 1e-5 after the impact's steps)
        // (two contacts at once: the end forces as they are, the combination holds one contact's)
        let pair = self.also_tip.is_some();
        self.ends_before =
            (!self.events.is_empty() && !euler && !pair).then_some(([g0, gc], tau, xc));
        self.held_now = held;
        self.ends_now = ends;
        self.contact_now = contact;
        self.t += tau;
        let foot = self.path.at(self.t);
        (self.d, self.turn) = (foot.place[0], foot.turn);
        let (h0, h1) = (self.rothe.force(0), self.rothe.force(1));
        // the support's force along the foot's path, and its moment `m(0)` on the turn (the
        // clamp holds the slope `π/2 − θ_w`: `δE = m(0) δθ_w` for the rod and its spring)
        // (by the step's rule: the trapezoidal rule's identity takes each force's mean over the
        // step, backward Euler's the force at the step's end)
        let (w0, w1) = if euler { (0.0, 1.0) } else { (0.5, 0.5) };
        let (work_before, friction_before) = (self.foot_work, self.friction);
        self.foot_work += -(w0 * g0[0] + w1 * h0[0]) * (self.d - d_old)
            + (w0 * m0 + w1 * self.rothe.sol.left()[3]) * (self.turn - turn_old);
        // (the work of the tip's force on a moving tip: friction, the normal force's part zero
        // to the step's error on a curve, exactly zero on a flat surface, which keeps to x)
        let x1_new = self.rothe.sol.right()[0];
        // (a side's contact: its work is `side_work`, none while it rolls; the tip beyond it is
        // free, and the stuck tip's force where the side formed did none)
        let free_tip = self.state.side() && self.also_tip.is_none();
        self.friction -= side_work;
        if !free_tip {
            self.friction += -(w0 * g1[0] + w1 * h1[0]) * (x1_new - x1);
        }
        if !self.track.flat() && !free_tip {
            self.friction += -(w0 * g1[1] + w1 * h1[1]) * (self.rothe.sol.right()[1] - y1);
        }
        if self.radius > 0.0 {
            // (a disk: the end's moment `m(1) = r·T` on its turn as well, so that friction
            // takes the contact force's work on the material point that touches, and a disk
            // that rolls gives none)
            let z = self.rothe.sol.right();
            self.friction -= (w0 * m1 + w1 * z[3]) * (z[2] - phi1);
        }
        if let Some(before) = energy_before {
            // an impact's backward-Euler step takes energy of its own (`½∫μ|Δv|²` and more):
            // booked with the impact, as what the step's work leaves over
            let p = self.rothe.sample(self.t);
            let after =
                p.kinetic + p.elastic + p.dissipated + p.internal_damping + p.external_damping;
            self.impact += (self.foot_work - work_before)
                - (self.friction - friction_before)
                - (after - before);
        }
        self.stats.steps += 1;
        self.samples.push(self.sample());
    }

    /// The present state as a sample: the forces without the rule's alternating mode where
    /// [`Drive::held_ends`] formed them, else those of the step's end.
    fn sample(&self) -> DragSample {
        let p = self.rothe.sample(self.t);
        let end = [[p.gx_base, p.gy_base], self.rothe.force(1)];
        let ends = self.ends_now.unwrap_or(end);
        let (normal, tangential) = self
            .contact_now
            .unwrap_or_else(|| self.forces(ends[1], p.tip_x));
        DragSample {
            t: self.t,
            d: self.d,
            theta: self.turn,
            tip_x: p.tip_x,
            tip_y: p.tip_y,
            tip_vx: p.tip_vx,
            tip_vy: p.tip_vy,
            tip_spin: self.rothe.tip_spin(),
            state: self.state,
            normal,
            tangential,
            fx: ends[0][0],
            fy: ends[0][1],
            step_end_forces: end,
            m_base: p.m_base,
            kinetic: p.kinetic,
            elastic: p.elastic,
            foot_work: self.foot_work,
            friction: self.friction,
            damper: p.dissipated,
            internal_damping: p.internal_damping,
            external_damping: p.external_damping,
            impact: self.impact,
            side: self
                .rothe
                .side
                .filter(|_| self.state.side())
                .map(|c| SideSample {
                    s: c.s,
                    x: c.z[0],
                    y: c.z[1],
                }),
            tip_also: self.also_tip.filter(|_| self.state.side()).map(|state| {
                let (normal, tangential) = self.forces(self.rothe.force(1), p.tip_x);
                TipAlso {
                    state,
                    normal,
                    tangential,
                }
            }),
        }
    }

    /// Where event function `which` reaches zero in `(lo, hi]` (`< 0` at `lo`, `≥ 0` at `hi`; 0
    /// where it is met already at the step's start, `lo` 0):
    /// Brent's method on the step's length (no step shorter than [`shortest_step`] tried: the
    /// function is constant below it).
    fn locate(&mut self, which: usize, lo: f64, hi: f64) -> Result<f64, VibrissaError> {
        let tol = self.o.event_tol;
        let mut now = self.events_now()[which];
        let shortest = shortest_step(self.o.dt, self.o.tol).min(hi);
        // (where `now` holds: the step's start, or the shortest step below)
        let mut known = 0.0;
        let mut lo = lo;
        if lo == 0.0 && now >= 0.0 {
            // (met already at the step's start by the forces as an event's restart estimated
            // them, a condition no step before tested: at once where the shortest step meets it
            // too, placed there as an event within it; else the step's own crossing after it)
            let tr = self.try_step(shortest)?;
            now = self.events_after(&tr)[which];
            if now >= 0.0 || shortest >= hi {
                return Ok(0.0);
            }
            (lo, known) = (shortest, shortest);
        }
        let mut f = |tau: f64| -> Result<f64, VibrissaError> {
            if tau <= known {
                return Ok(now);
            }
            let tr = self.try_step(tau.max(shortest))?;
            Ok(self.events_after(&tr)[which])
        };
        let found = crate::search::root(&mut f, lo, hi, tol);
        match found {
            Ok(at) => Ok(at),
            Err(crate::search::RootError::Caller(e)) => Err(e),
            // (a lower end above the start, a slip's where its tip moves ([`Drive::slip_start`]),
            // that this event function has passed already: it is met before that end, and
            // searched from the step's start up to it)
            Err(crate::search::RootError::NoBracket { a, fa, .. })
                if a > 0.0 && known == 0.0 && fa >= 0.0 =>
            {
                self.locate(which, 0.0, a)
            }
            Err(other) => Err(VibrissaError::NoConvergence {
                what: format!("locating the dynamic drag's event after t = {}", self.t),
                reason: other.to_string(),
            }),
        }
    }

    /// The contact changes after event `which`; `Some(stop)` where the drag ends.
    fn apply(&mut self, which: usize) -> Option<DynDragStop> {
        if self.state.side() {
            return self.apply_side(which);
        }
        self.mismatch = None;
        self.mismatch_end = None;
        // a stick, a slip at once and a stick at once can share an instant; a fourth event
        // there would repeat the second from the same state, and so on without end
        if self.instant_events == MAX_INSTANT_EVENTS {
            // (the stuck tip's force that slipped it at once, not the state's now: after a
            // slip at once that finds no motion it is the slide's, inside the cone)
            return Some(
                self.unresolved_at_once()
                    .unwrap_or_else(|| self.unresolved(self.rothe.force(1))),
            );
        }
        self.tried.clear();
        self.ends_before = None;
        self.ends_now = None;
        // (an event's forces as its test takes them: a stuck tip's the held force, without the
        // rule's alternating mode, where there is one, so a slip's row has |T| = μs N and a
        // lift-off's N = 0 to the event's location; a sliding tip's lift-off the held contact
        // force, its other tests the end force)
        let lifted = self
            .contact_now
            .take()
            .filter(|_| which == LIFT && self.sliding_lift());
        let stuck = self.state == ContactState::Stuck;
        let held = self.held_now.take().filter(|_| stuck);
        let (normal, tangential) = lifted.unwrap_or_else(|| {
            self.forces(
                held.unwrap_or_else(|| self.rothe.force(1)),
                self.rothe.sol.right()[0],
            )
        });
        // (the point that reached the surface: found once, for the side or the stop)
        let point = (which == SIDE).then(|| self.side_gap(&self.rothe.sol));
        let kind = if let Some((_, s, _)) = point {
            if self.may_roll(s) {
                self.enter_side();
            } else if s < 1.0 && self.may_side() {
                self.enter_pair(s);
            }
            DragEventKind::SideContact
        } else if which == EDGE {
            let xb = self.edge.unwrap_or(self.rothe.sol.right()[0]);
            self.enter_slide(xb);
            DragEventKind::Patch
        } else if which == LIFT {
            if self.o.flight {
                self.state = ContactState::Flying;
            }
            // (a lift-off within an impact's steps ends them: the force they damp is gone)
            self.rothe.euler_steps = 0;
            DragEventKind::LiftOff
        } else if self.state == ContactState::Flying {
            self.touchdown();
            DragEventKind::Touchdown
        } else if self.state == ContactState::Stuck {
            self.state = self.state.sliding(tangential);
            self.fresh_slip = true;
            self.slip_slot = PHASE;
            self.stats.slips += 1;
            self.enter_slide(self.contact_x(self.anchor));
            DragEventKind::Slip
        } else {
            self.state = ContactState::Stuck;
            self.fresh_slip = false;
            self.anchor = self.rothe.sol.right()[0];
            self.roll = self.rolling_of(self.rothe.sol.right());
            if self.radius == 0.0 {
                self.rothe.hold_tip_x();
                if !self.track.flat() {
                    // (on a sloped track the tip moved along it in y too)
                    self.rothe.hold_tip_y();
                }
            }
            self.stats.sticks += 1;
            DragEventKind::Stick
        };
        if matches!(
            kind,
            DragEventKind::Slip | DragEventKind::Stick | DragEventKind::Patch
        ) {
            // (at a patch's boundary the tip's friction jumps as at a slip; a disk's end moves
            // at every event, rolling or sliding on: the restart then extrapolates back)
            self.restart(kind == DragEventKind::Patch || self.radius > 0.0);
        }
        self.push_event(kind, normal, tangential);
        if kind == DragEventKind::LiftOff && !self.o.flight {
            return Some(DynDragStop::LiftOff { d: self.d });
        }
        if let Some((_, s, x)) = point.filter(|_| !self.state.side()) {
            return Some(DynDragStop::SideContact {
                t: self.t,
                d: self.d,
                s,
                x,
            });
        }
        if kind != DragEventKind::Patch {
            // (a boundary crossed is not a change of the contact's state)
            self.instant_events += 1;
        }
        (self.events.len() >= self.o.max_events).then_some(DynDragStop::MaxEvents)
    }

    /// The stop at a stick the time step does not resolve, with the force the stuck tip needs
    /// (the tip's force `g`, as [`contact_forces`] reads it). The rod's held force starts from the sliding one at a stick
    /// and changes continuously (like `√t`): a tip that needs a pull or more than μs N at once,
    /// or within the shortest step, is the scheme's, its steps too coarse for the motion
    /// before the stick.
    fn unresolved(&self, g: [f64; 2]) -> DynDragStop {
        let (normal, tangential) = self.forces(g, self.rothe.sol.right()[0]);
        DynDragStop::UnresolvedStick {
            t: self.t,
            d: self.d,
            normal,
            tangential,
        }
    }

    /// A point tip that has just stuck (at this instant) but whose held force is a pull at once:
    /// the contact cannot hold it, and Coulomb's law asks which other state is consistent at
    /// this instant, each tried by the restart under its condition: a slide the way the held
    /// force pushes the tip (consistent where its contact force pushes, `N ≥ 0`, and the tip
    /// accelerates that way), else a lift-off (where the free tip accelerates away from the
    /// surface). `Some(None)`: the tip slips or flies on from here (the event recorded with the
    /// new state's force); `Some(Some(stop))`: it lifts off and the drag ends there (without
    /// `flight`); `None`: neither is consistent (or the instant has had its share of events),
    /// and the stick is one the time step does not resolve (every state restored).
    ///
    /// Why: a stick changes the tip's condition, and the inextensible rod's force at the tip
    /// jumps at once (docs/model.md, "The restart after a slip or a stick"). A whisk turned back
    /// while the tip slides (`--whisk 0.2,3 --speed 0.1`) sticks at N = 0.29, and the held tip
    /// needs N = −2.7, T = −3.7 at once; sliding back it is pushed (N = 0.16, T = −μk N) and
    /// accelerates backwards (−3.8): the tip reverses at once instead of sticking.
    fn unstick_at_once(&mut self) -> Option<Option<DynDragStop>> {
        let just_stuck = self
            .events
            .last()
            .is_some_and(|e| e.kind == DragEventKind::Stick && e.t == self.t);
        if !just_stuck
            || self.radius > 0.0
            || self.instant_events == 0
            || self.instant_events >= MAX_INSTANT_EVENTS
        {
            return None;
        }
        let (_, t_held) = self.forces(self.rothe.force(1), self.rothe.sol.right()[0]);
        let saved = (self.rothe.clone(), self.state, self.mu_k_now, self.edge);
        let restarts = self.stats.restarts;
        let x = self.rothe.sol.right()[0];
        let (_, hp, _) = self.track.jet(x);
        // a slide the way the held force pushes the tip
        self.state = if t_held >= 0.0 {
            ContactState::SlidingForward
        } else {
            ContactState::SlidingBack
        };
        self.enter_slide(self.contact_x(self.anchor));
        self.restart(false);
        let (n, t) = self.forces(self.rothe.force(1), x);
        let a = self.rothe.tip_acceleration();
        if self.stats.restarts > restarts && n >= 0.0 && self.state.dir() * along(hp, a) > 0.0 {
            self.fresh_slip = true;
            self.slip_slot = PHASE;
            self.stats.slips += 1;
            self.record_at_once(DragEventKind::Slip, n, t);
            return Some(None);
        }
        (self.rothe, self.state, self.mu_k_now, self.edge) = saved.clone();
        self.stats.restarts = restarts;
        // a lift-off: the free tip must accelerate away from the surface (whose normal
        // `unit_normal` points away from the rod: a flying tip's gap `y − h` is negative)
        let delta = restart_step(self.o);
        let feet: Vec<Foot> = (1..=2)
            .map(|k| self.path.at(self.t + k as f64 * delta))
            .collect();
        self.stats.solves += feet.len();
        let free = self
            .rothe
            .restart(delta, &feet, TipBc::Force([0.0, 0.0]), 0.0)
            .is_ok();
        let a = self.rothe.tip_acceleration();
        let nrm = unit_normal(hp);
        if free && a[0] * nrm[0] + a[1] * nrm[1] < 0.0 {
            self.stats.restarts += 1;
            self.state = if self.o.flight {
                ContactState::Flying
            } else {
                ContactState::Stuck
            };
            self.rothe.euler_steps = 0;
            self.record_at_once(DragEventKind::LiftOff, 0.0, 0.0);
            if !self.o.flight {
                return Some(Some(DynDragStop::LiftOff { d: self.d }));
            }
            return Some(None);
        }
        (self.rothe, self.state, self.mu_k_now, self.edge) = saved;
        None
    }

    /// Records an event of [`Drive::unstick_at_once`] at the present instant with the new
    /// state's force `(normal, tangential)`, one more event at this instant.
    fn record_at_once(&mut self, kind: DragEventKind, normal: f64, tangential: f64) {
        self.push_event(kind, normal, tangential);
        self.instant_events += 1;
    }

    /// Records event `kind` at the present time with the tip's force `(normal, tangential)`
    /// and the contact's state after it.
    fn push_event(&mut self, kind: DragEventKind, normal: f64, tangential: f64) {
        let p = self.rothe.sample(self.t);
        self.events.push(DynDragEvent {
            kind,
            t: self.t,
            d: self.d,
            tip_x: p.tip_x,
            tip_vx: p.tip_vx,
            normal,
            tangential,
            state: self.state,
            tip_also: self.also_tip.filter(|_| self.state.side()),
        });
    }

    /// The slip at once after a stick at the present instant (no step taken since), if the
    /// tip stuck and then slipped at once: the stuck tip then needed more than μs N at once.
    fn slid_at_once(&self) -> Option<DynDragEvent> {
        let n = self.events.len();
        (self.instant_events >= 2 && n >= 2)
            .then(|| (self.events[n - 2], self.events[n - 1]))
            .filter(|(a, b)| a.kind == DragEventKind::Stick && b.kind == DragEventKind::Slip)
            .map(|(_, b)| b)
    }

    /// `UnresolvedStick` at a slip at once after a stick ([`Drive::slid_at_once`]), with the
    /// force the stuck tip needed then.
    fn unresolved_at_once(&self) -> Option<DynDragStop> {
        self.slid_at_once().map(|e| DynDragStop::UnresolvedStick {
            t: self.t,
            d: self.d,
            normal: e.normal,
            tangential: e.tangential,
        })
    }

    /// `UnresolvedStep` where the stuck tip's held force at the end of `tr` is beyond the
    /// friction cone (`|T| > μs N` by more than `1e-6` of it).
    fn beyond_cone(&self, tr: &Trial) -> Option<DynDragStop> {
        let (normal, tangential, limit) = self.held_and_limit(tr);
        if tangential.abs() <= limit * (1.0 + 1e-6) {
            return None;
        }
        Some(self.unresolved_step(normal, tangential))
    }

    /// `UnresolvedStep` where a slip's search ended on a state whose held force is inside the
    /// friction cone (`|T| < μs N` by more than 1e-6 of it): the slip's test did not cross zero
    /// there but jumped, so the step's solutions are not continuous in its length and the step
    /// does not resolve the rod's motion. Seen on a support of compliance 50 at dt 0.01: two
    /// trials 2e-9 apart in time solved to N = 0.049, T/N = 0.492 and N = 0.095, T/N = 0.684
    /// (the first Newton's iterate accepted at its precision floor, the second converged by the
    /// affine-invariant damping, rothe.rs `StepSolver`). As any unresolved step, it is taken
    /// again with shorter steps where a refinement is left.
    fn inside_cone(&self, tr: &Trial) -> Option<DynDragStop> {
        let (normal, tangential, limit) = self.held_and_limit(tr);
        if tangential.abs() >= limit * (1.0 - 1e-6) {
            return None;
        }
        Some(self.unresolved_step(normal, tangential))
    }

    /// The stuck tip's held force at the end of `tr`, `(N, T)`, and its static limit `μs N`
    /// (μs the texture's where the tip is, for the way it is pushed).
    fn held_and_limit(&self, tr: &Trial) -> (f64, f64, f64) {
        let x = tr.sol.right()[0];
        let (normal, tangential) = self.forces(self.held_force(tr), x);
        let mu_s = self.coefficients(self.contact_x(x), tangential.signum()).0;
        (normal, tangential, mu_s * normal)
    }

    /// `UnresolvedStep` here: the stuck tip's force `(normal, tangential)` within the step
    /// against its held force at the step's start.
    fn unresolved_step(&self, normal: f64, tangential: f64) -> DynDragStop {
        let before = self.held_now.unwrap_or_else(|| self.rothe.force(1));
        let (n0, t0) = self.forces(before, self.rothe.sol.right()[0]);
        DynDragStop::UnresolvedStep {
            t: self.t,
            d: self.d,
            before: [n0, t0],
            normal,
            tangential,
        }
    }

    /// The stop where a stuck tip's event lands within the shortest step and its held force
    /// there is far from the one the step starts with (by more than a tenth of it): a force
    /// that changes continuously moves by `Ġ·τ` in such a step. Seen over a corrugation at
    /// dt 0.02 (v 0.01): after two stuck phases the trials from one state needed 6 to 55
    /// Newton iterations and their held force grew like `1/τ` as the step shortened (from
    /// |G| = 4.3 to 14 at τ = 2e-5), so the search put a slip there at T/N = 1.52, and a later
    /// one at N = −15.7, a pull. The state's velocities there do not fit the stuck tip's
    /// condition to the step's accuracy (the time rule's mode grown in the stuck phase); a
    /// shorter `dt` resolves it (dt 0.01 reaches d_max with 11 slips). Since that mismatch's
    /// `1/τ` term is taken out of the search ([`Drive::deflate`]) the same drag goes on
    /// through six slips; the stop is left for a jump the term does not account for.
    fn jumped(&self, tr: &Trial) -> Option<DynDragStop> {
        let before = self.held_now.unwrap_or_else(|| self.rothe.force(1));
        let after = self.held_force(tr);
        let jump = (after[0] - before[0]).hypot(after[1] - before[1]);
        if jump <= 0.1 * before[0].hypot(before[1]) {
            return None;
        }
        let (normal, tangential) = self.forces(after, self.rothe.sol.right()[0]);
        Some(self.unresolved_step(normal, tangential))
    }

    /// The rod's accelerations and end forces made consistent with the tip's new condition
    /// after a slip, a stick or a patch crossed (`Rothe::restart`, two steps of [`restart_step`]
    /// on a copy, three where the tip `moving` slides on).
    /// Where those steps are not solved the drag goes on from the history as it is (counted:
    /// `stats.restarts` falls short of the slips and sticks).
    fn restart(&mut self, moving: bool) {
        let delta = restart_step(self.o);
        // (three probe steps where the tip moves on: their values extrapolated back to the
        // event's instant, see `Rothe::restart`)
        let feet: Vec<Foot> = (1..=if moving { 3 } else { 2 })
            .map(|k| self.path.at(self.t + k as f64 * delta))
            .collect();
        self.stats.solves += feet.len();
        self.rothe.disk_held = (1.0, 0.0);
        if self.rothe.restart(delta, &feet, self.bc(), 0.0).is_err() {
            return;
        }
        self.stats.restarts += 1;
        if let Some(tip) = self
            .also_tip
            .filter(|t| t.dir() != 0.0 && !self.track.flat())
        {
            // (a tip sliding beside a side on a curve: its force as a sliding tip's below)
            let x = self.rothe.sol.right()[0];
            let hp = self.track.jet(x).1;
            let (n, _) = contact_forces(self.rothe.force(1), hp);
            self.rothe
                .set_restart_tip_force(tip_force(n, tip.dir() * self.o.mu_k * n, hp));
        }
        let (dir, side) = (self.state.dir(), self.state.side());
        if dir == 0.0 || (self.track.flat() && !side) {
            return;
        }
        // the restart's contact force is the mean of two probe steps' whose contact stood where
        // the surface's normal differs: on a curve it meets the slide's friction only to O(δ)
        // (5e-6 N at tol 1e-8 over a corrugation). Its normal part is kept, its tangential part
        // set to the slide's `T = dir·μk N` (μk at rest for a table; a side's, on any track,
        // its contact moving along the rod between the probes)
        let (g, x) = self.contact_force_now();
        let hp = self.track.jet(x).1;
        let (n, _) = contact_forces(g, hp);
        let mu_k = if side { self.o.mu_k } else { self.mu_k_at(x) };
        let held = tip_force(n, dir * mu_k * n, hp);
        if !side {
            self.rothe.set_restart_tip_force(held);
        } else if let Some(c) = self.rothe.side.as_mut() {
            // (a side's contact force is its own, not the free tip's)
            c.force = held;
        }
    }

    /// The plastic impact of the tip on the surface: its velocity (and acceleration) normal to
    /// the surface set to zero at the tip's node, the kinetic energy this takes booked as
    /// `impact` (the event's sample is the state after the impact); the contact from here on
    /// slides the way the tip moves along the surface (sticks, if it does not move).
    fn touchdown(&mut self) {
        self.state = self.land_tip();
        self.enter_slide(self.contact_x(self.rothe.sol.right()[0]));
    }

    /// The tip's plastic impact ([`Drive::touchdown`]) and the tip's state after it: sliding
    /// the way it moves along the surface, stuck (at `anchor`) if it does not.
    fn land_tip(&mut self) -> ContactState {
        let before = self.rothe.sample(self.t);
        let (_, hp, _) = self.track.jet(before.tip_x);
        if self.track.flat() {
            self.rothe.hold_tip_y();
        } else {
            self.rothe.hold_tip_normal(unit_normal(hp));
        }
        let before = before.kinetic;
        let after = self.rothe.sample(self.t);
        self.impact += before - after.kinetic;
        self.rothe.euler_steps = IMPACT_STEPS;
        self.landed = true;
        if let Some(last) = self.samples.last_mut() {
            // (on a sloped surface the impact changes both components)
            last.tip_vx = after.tip_vx;
            last.tip_vy = after.tip_vy;
            last.kinetic = after.kinetic;
            last.impact = self.impact;
        }
        let v = self.slip_rate(
            after.tip_x,
            [after.tip_vx, after.tip_vy],
            self.rothe.tip_spin(),
        );
        if v > 0.0 {
            ContactState::SlidingForward
        } else if v < 0.0 {
            ContactState::SlidingBack
        } else {
            self.anchor = after.tip_x;
            self.roll = self.rolling_of(self.rothe.sol.right());
            ContactState::Stuck
        }
    }

    /// The stop of two contacts whose steps do not solve ([`DynDragStop::Stretch`]): the rod's
    /// largest distance below the surface over the last solution's nodes between the side's
    /// contact and the tip.
    fn stretch(&self) -> DynDragStop {
        let sc = self.rothe.side.map_or(self.rothe.side_guess, |c| c.s);
        let sol = &self.rothe.sol;
        let gap = (0..sol.len())
            .filter(|&i| sol.mesh[i] >= sc)
            .map(|i| {
                let z = sol.node(i);
                self.surface.jet(z[0]).0 - z[1]
            })
            .fold(0.0, f64::max);
        DynDragStop::Stretch {
            t: self.t,
            d: self.d,
            s: sc,
            gap,
        }
    }

    /// A lower end of the search in a step that starts a slip (the velocity zero at the start):
    /// the longest of `τ/2, τ/4, …` (down to `tau_min`) where the tip moves the way it slides.
    /// `None`: it does not move that way at all.
    fn slip_start(&mut self, tau: f64, tau_min: f64) -> Result<Option<f64>, VibrissaError> {
        let mut lo = tau;
        while lo > tau_min {
            lo = (0.5 * lo).max(tau_min);
            let tr = self.try_step(lo)?;
            if self.events_after(&tr)[self.slip_slot] < 0.0 {
                return Ok(Some(lo));
            }
        }
        Ok(None)
    }

    /// The drag to its end: [`Drive::march`], where a slip at once after a stick
    /// ([`Drive::slid_at_once`]) is followed by a step that is not solved, the stick the step
    /// does not resolve ([`DynDragStop::UnresolvedStick`], with the slip's force).
    ///
    /// Why: the force of such a slip, outside the friction cone at once, is the scheme's, not
    /// the rod's ([`Drive::unresolved`]), and so is the failure of the step after it, not a
    /// failure of the drag: measured on a whisk drawn back after a touchdown (`vibrissa
    /// dynamics drag --whisk -0.3,2 --speed 0.05 --d-max 0.1 --flight`, dt 0.01) the tip stuck
    /// at N = 16.6, slipped at once at N = 49.5, T/N = 3.04, and the first step of the slip
    /// stalled Newton; at dt 0.005 the same instant ends as `unresolved_stick` by a stick at
    /// once after the slip. (A step that fails from a stick alone stays a solver error: at grid
    /// 200, tol 1e-8 the same drag's stuck step after the touchdown reaches the Newton limit on
    /// 5401 nodes while its force, N = 16.6, T/N = −0.3, is within the cone.)
    fn run(&mut self) -> Result<DynDragStop, VibrissaError> {
        // the step the collocation did not solve that began the refinements under way, if one
        // did: the drag's error where they do not get past it
        let mut failure: Option<VibrissaError> = None;
        loop {
            let stop = match self.run_once() {
                Ok(stop) => stop,
                // a step of the refinements that the collocation does not solve: they were an
                // attempt at what the step did not resolve, and end as if in a stop (begun by a
                // slip beyond the cone, the drag goes on from that slip; else the stop that
                // began them stands)
                Err(e @ VibrissaError::Solver { .. }) => {
                    if self.back_to_cone_origin() {
                        continue;
                    }
                    if let Some(stop) = self.back_to_stop_origin() {
                        return Ok(stop);
                    }
                    match self.after_failure(e, failure.take()) {
                        Ok(first) => {
                            failure = Some(first);
                            continue;
                        }
                        // (two contacts whose steps do not solve: a stretch on the surface)
                        Err(_) if self.also_tip.is_some() => return Ok(self.stretch()),
                        Err(first) => return Err(first),
                    }
                }
                Err(e) => return Err(e),
            };
            let t_stop = match stop {
                DynDragStop::UnresolvedStick { t, .. } | DynDragStop::UnresolvedStep { t, .. } => t,
                s => return Ok(s),
            };
            if self.refined_dt().is_some() {
                self.save_stop_origin(stop);
            }
            let refined = match self.refined_dt() {
                Some(dt) if self.back_to_checkpoint(t_stop) => Some(dt),
                _ => None,
            };
            let Some(dt) = refined else {
                // refinements begun by a slip beyond the cone that end in a stop: the drag goes
                // on from that slip as it would without them
                if self.back_to_cone_origin() {
                    continue;
                }
                return Ok(stop);
            };
            self.dt = dt;
            self.refined_until = Some(t_stop + self.o.dt);
        }
    }

    /// A step the collocation does not solve (`e`, outside refinements begun by a stop or by a
    /// slip beyond the cone) is taken again as a stop the step does not resolve: from the last
    /// checkpoint before it at half the step, until `dt` past it, where a halving is left. `Ok`
    /// with the failure that began the refinements (`first`, else `e`) when it goes back; `Err`
    /// with it when no halving or checkpoint is left.
    ///
    /// Why: a Newton that fails on a step of the fixed length `dt` is, like an unresolved stick,
    /// the scheme's where `dt` is too coarse for the rod's motion, and shorter steps are the
    /// remedy the error advised. Measured on the paper's rod at dt 0.0625, grid 20, tol 1e-6,
    /// v 0.05 (`vibrissa dynamics drag --speed 0.05 --d-max 0.4 --dt 0.0625 --grid 20 --tol
    /// 1e-6`): the first step after the slip at t = 7.1387 stalled Newton
    /// (residual 2.3e3 on 1967 nodes) and the drag failed; from the last event at dt/2 it goes
    /// on through the tenth slip.
    fn after_failure(
        &mut self,
        e: VibrissaError,
        first: Option<VibrissaError>,
    ) -> Result<VibrissaError, VibrissaError> {
        let first = match first {
            Some(f) if self.refined_until.is_some() => f,
            _ => e,
        };
        let t = self.t;
        match self.refined_dt() {
            Some(dt) if self.back_to_checkpoint(t) => {
                self.dt = dt;
                self.refined_until = Some(t + self.o.dt);
                Ok(first)
            }
            _ => Err(first),
        }
    }

    /// The step of a refinement from here (half the present one), if one is left (fixed steps,
    /// down to `dt / 2^refinements`).
    fn refined_dt(&self) -> Option<f64> {
        let dt = if self.refined_until.is_some() {
            self.dt
        } else {
            self.o.dt
        } / 2.0;
        (self.o.time_tol.is_none()
            && dt >= self.o.dt / 2f64.powi(self.o.refinements as i32) * (1.0 - 1e-9))
            .then_some(dt)
    }

    /// The present state without its samples and events (a checkpoint's), with their lengths.
    fn snapshot(&mut self) -> (usize, usize, Box<Self>) {
        let samples = std::mem::take(&mut self.samples);
        let events = std::mem::take(&mut self.events);
        let state = Box::new(self.clone());
        let lengths = (samples.len(), events.len());
        self.samples = samples;
        self.events = events;
        (lengths.0, lengths.1, state)
    }

    /// Puts a [`Drive::snapshot`] back: its state, the samples and events cut to its lengths,
    /// the work counters (solves, refinements, the rod's) kept as they are now.
    fn restore(&mut self, state: Self, ns: usize, ne: usize) {
        let mut samples = std::mem::take(&mut self.samples);
        let mut events = std::mem::take(&mut self.events);
        let (stats, rstats) = (self.stats, self.rothe.stats);
        *self = state;
        samples.truncate(ns);
        events.truncate(ne);
        self.samples = samples;
        self.events = events;
        self.stats.solves = stats.solves;
        self.stats.refinements = stats.refinements;
        self.rothe.stats = rstats;
    }

    /// Saves the present state as a checkpoint (after an event).
    fn save_checkpoint(&mut self) {
        let (ns, ne, state) = self.snapshot();
        if self.checkpoints.0.len() == CHECKPOINTS {
            self.checkpoints.0.remove(0);
        }
        self.checkpoints.0.push((self.t, ns, ne, state));
    }

    /// Goes back to [`Drive::cone_origin`] with its checkpoints, at `dt`, to accept the slip
    /// beyond the cone there; `false` if there is none.
    fn back_to_cone_origin(&mut self) -> bool {
        let Some((t, ns, ne, origin)) = self.cone_origin.0.pop() else {
            return false;
        };
        let cps = std::mem::take(&mut self.cone_checkpoints.0);
        self.restore(*origin, ns, ne);
        self.checkpoints.0 = cps;
        self.accept_cone = true;
        debug_assert!(self.t == t);
        true
    }

    /// Saves the present state, ended by `stop`, as [`Drive::stop_origin`] (in place of an
    /// earlier one: the shorter steps' stop is the one kept).
    fn save_stop_origin(&mut self, stop: DynDragStop) {
        let (ns, ne, origin) = self.snapshot();
        self.stop_origin.0.clear();
        self.stop_origin.0.push((self.t, ns, ne, origin));
        self.stop_kept = Some(stop);
    }

    /// Goes back to [`Drive::stop_origin`], if there is one: its stop.
    fn back_to_stop_origin(&mut self) -> Option<DynDragStop> {
        let stop = self.stop_kept?;
        let (_, ns, ne, origin) = self.stop_origin.0.pop()?;
        self.restore(*origin, ns, ne);
        Some(stop)
    }

    /// Saves the present state as [`Drive::cone_origin`] (a slip beyond the cone in the step
    /// from here), with a copy of its checkpoints, unless refinements are under way.
    fn save_cone_origin(&mut self) {
        if !self.cone_origin.0.is_empty() {
            return;
        }
        let (ns, ne, origin) = self.snapshot();
        self.cone_checkpoints.0 = self
            .checkpoints
            .0
            .iter()
            .map(|(t, a, b, d)| (*t, *a, *b, d.clone()))
            .collect();
        self.cone_origin.0.push((self.t, ns, ne, origin));
    }

    /// Goes back to the last checkpoint before `t` (its samples and events kept, the work since
    /// counted); `false` if there is none.
    fn back_to_checkpoint(&mut self, t: f64) -> bool {
        let mut cps = std::mem::take(&mut self.checkpoints.0);
        while cps.last().is_some_and(|c| c.0 >= t) {
            cps.pop();
        }
        let Some((_, ns, ne, cp)) = cps.last() else {
            return false;
        };
        let (ns, ne, state) = (*ns, *ne, (**cp).clone());
        let origin = std::mem::take(&mut self.cone_origin.0);
        let origin_cps = std::mem::take(&mut self.cone_checkpoints.0);
        let (stop_origin, stop_kept) = (std::mem::take(&mut self.stop_origin.0), self.stop_kept);
        self.restore(state, ns, ne);
        self.stats.refinements += 1;
        self.checkpoints.0 = cps;
        self.cone_origin.0 = origin;
        self.cone_checkpoints.0 = origin_cps;
        (self.stop_origin.0, self.stop_kept) = (stop_origin, stop_kept);
        true
    }

    fn run_once(&mut self) -> Result<DynDragStop, VibrissaError> {
        match self.march() {
            Err(err @ VibrissaError::Solver { .. }) => self.unresolved_at_once().ok_or(err),
            r => r,
        }
    }

    /// At a step's start: refinements past their window end (the step back to `dt`, the
    /// states they kept to go back to forgotten), and with fixed steps the state after a new
    /// event is kept as a checkpoint.
    fn before_step(&mut self) {
        if self.refined_until.is_some_and(|t| self.t >= t) {
            self.dt = self.o.dt;
            self.refined_until = None;
            self.cone_origin.0.clear();
            self.cone_checkpoints.0.clear();
            self.stop_origin.0.clear();
            self.stop_kept = None;
        }
        if self.o.time_tol.is_none()
            && self
                .checkpoints
                .0
                .last()
                .is_none_or(|c| self.events.len() > c.2)
        {
            self.save_checkpoint();
        }
    }

    /// The stop where the stuck tip's event `which`, located at `at` (the step `tr` taken to
    /// it), is the scheme's rather than the rod's: a slip or lift-off within the shortest step
    /// right after a stick ([`Drive::unresolved`]), a held force that jumped within it
    /// ([`Drive::jumped`]), a slip beyond the friction cone while a refinement is left
    /// ([`Drive::beyond_cone`]) or inside it ([`Drive::inside_cone`]). `None`: the event is
    /// the rod's.
    fn stuck_event_stop(
        &mut self,
        tr: &Trial,
        which: usize,
        at: f64,
        shortest: f64,
    ) -> Option<DynDragStop> {
        if self.instant_events > 0 && at <= shortest {
            // right after its stick the tip needs to slip or lift within the shortest
            // step: its force has left the friction cone at once, which the rod's does
            // not (see `unresolved`)
            return Some(self.unresolved(self.held_force(tr)));
        }
        if at <= shortest {
            if let Some(stop) = self.jumped(tr) {
                return Some(stop);
            }
        }
        if which == PHASE
            && !std::mem::take(&mut self.accept_cone)
            && self.refined_dt().is_some()
            && self.checkpoints.0.iter().any(|c| c.0 < self.t)
        {
            // a slip placed beyond the friction cone (the held force jumped within the
            // shortest step by less than `jumped` names, or at the step's end, where the
            // velocity mismatch's term is not taken out): taken again with shorter steps
            // where a refinement and a state to go back to are left
            if let Some(stop) = self.beyond_cone(tr) {
                self.save_cone_origin();
                return Some(stop);
            }
        }
        if which == PHASE {
            return self.inside_cone(tr);
        }
        None
    }

    /// The drag's steps and events to its end.
    fn march(&mut self) -> Result<DynDragStop, VibrissaError> {
        let t_end = self.o.t_end();
        let dt = self.o.dt;
        let tau_min = shortest_step(dt, self.o.tol);
        let ctl = self.o.step_control;
        // the step to try (fixed steps: `dt`; with `time_tol`: the controller's proposal)
        let mut h = if self.o.time_tol.is_some() {
            ctl.first(dt)
        } else {
            dt
        };
        loop {
            self.before_step();
            if t_end - self.t <= 1e-12 * t_end.max(1.0) {
                return Ok(if self.o.foot_table.is_empty() {
                    DynDragStop::DMax
                } else {
                    DynDragStop::TableEnd
                });
            }
            match self.changes_at_once() {
                Some(Some(stop)) => return Ok(stop),
                Some(None) => continue,
                None => {}
            }
            if self.o.time_tol.is_none() {
                h = self.dt;
            }
            // (a remainder shorter than the shortest step joins the last step: alone, its
            // `4/τ²` would magnify the positions' rounding past what the collocation meets)
            let left = t_end - self.t;
            let tau = if left <= h + tau_min { left } else { h };
            let (tau, tr) = match self.step_from_here(tau, tau_min) {
                Ok(step) => step,
                // (a side whose contact races to the tip: handed over at once)
                Err(_) if self.grazes_tip() => match self.apply_side(EDGE) {
                    Some(stop) => return Ok(stop),
                    None => continue,
                },
                Err(e) => return Err(e),
            };
            if let Some(tol) = self.o.time_tol {
                let rejected;
                (rejected, h) = ctl.judge(self.t, tau, self.rothe.local_error(&tr), tol)?;
                if rejected {
                    self.stats.rejected_steps += 1;
                    continue;
                }
            }
            let mut g1 = self.events_after(&tr);
            if g1.iter().all(|&g| g < 0.0) {
                self.take(tr);
                self.fresh_slip = false;
                continue;
            }
            // (the shortest step the searches within this step try)
            let shortest = tau_min.min(tau);
            if self.state == ContactState::Stuck {
                // (the held force's velocity mismatch out of the search's shorter steps)
                self.deflate(&tr, shortest);
                g1 = self.events_after(&tr);
                if g1.iter().all(|&g| g < 0.0) {
                    self.take(tr);
                    self.fresh_slip = false;
                    continue;
                }
            }
            // the lower end of the search: the step's start (or where a slip's tip moves)
            let mut lo = 0.0;
            if self.fresh_slip && g1[self.slip_slot] >= 0.0 {
                match self.slip_start(tau, shortest)? {
                    Some(l) => lo = l,
                    None => {
                        // no motion the way of the slip: it sticks at once
                        if let Some(stop) = self.apply(self.slip_slot) {
                            return Ok(stop);
                        }
                        continue;
                    }
                }
            }
            let mut first: Option<(f64, usize)> = None;
            let mut graze = false;
            for which in [LIFT, PHASE, SIDE, EDGE, TIP_LIFT, TIP_PHASE] {
                if g1[which] >= 0.0 {
                    let at = match self.locate(which, lo, tau) {
                        Ok(at) => at,
                        // (a search the collocation cannot finish within a stuck step: the step
                        // does not resolve the rod, and is taken again with shorter steps)
                        Err(VibrissaError::Solver { .. }) if self.state == ContactState::Stuck => {
                            let (n, t) = self.forces(self.held_force(&tr), tr.sol.right()[0]);
                            return Ok(self.unresolved_step(n, t));
                        }
                        // (a side whose contact races to the tip: handed over at once)
                        Err(_) if self.grazes_tip() => {
                            graze = true;
                            break;
                        }
                        Err(e) => return Err(e),
                    };
                    // (events within the shortest step are simultaneous, the step resolves no
                    // order among them: the first in the list's, a lift-off before a slip)
                    if first.is_none_or(|(t, _)| at.max(shortest) < t.max(shortest)) {
                        first = Some((at, which));
                    }
                }
            }
            if graze {
                match self.apply_side(EDGE) {
                    Some(stop) => return Ok(stop),
                    None => continue,
                }
            }
            let Some((at, which)) = first else {
                return Err(VibrissaError::NoConvergence {
                    what: format!("the dynamic drag's step from t = {}", self.t),
                    reason: format!("its event functions are not numbers: {g1:?}"),
                });
            };
            let (which, at) = self.first_met((which, at), lo, shortest)?;
            if self.lets_go_at_once(which, at, shortest) {
                self.let_go = true;
                if let Some(stop) = self.apply(which) {
                    return Ok(stop);
                }
                continue;
            }
            let tr = self.try_step(at.max(shortest))?;
            if self.state == ContactState::Stuck {
                if let Some(stop) = self.stuck_event_stop(&tr, which, at, shortest) {
                    return Ok(stop);
                }
            }
            self.take(tr);
            self.fresh_slip = false;
            if let Some(stop) = self.apply(which) {
                return Ok(stop);
            }
        }
    }
}

/// The combinations of rod, surface and options [`drag`] refuses: a friction texture with
/// `mu_k_table`, a round tip without internal damping.
fn refuse_parts(rod: &Rod, surface: &Surface, opts: &DynDragOptions) -> Result<(), VibrissaError> {
    if surface.texture_shared().is_some() && !opts.mu_k_table.is_empty() {
        return Err(VibrissaError::NotImplemented(
            "kinetic friction depending on the slip velocity (mu_k_table) on a surface with a \
             friction texture",
        ));
    }
    if rod.tip_radius() != 0.0 && opts.internal_damping == 0.0 {
        // (the sliding disk's `m(1) = r·μk·N` puts the contact's multiplier into the bending
        // at the end, a non-conservative end condition: undamped, the rod's short waves grow
        // and `N` rang by ±0.5 to ±1.2 from step to step, Newton failing near a stick at
        // dt 0.005 and 0.01; γ_i = 1e-4 damps them, docs/model.md)
        return Err(VibrissaError::range(
            "internal damping",
            0.0,
            "above 0 with a round tip (tip radius > 0): its friction moment makes the undamped \
             rod's short waves unstable; e.g. 1e-4",
        ));
    }
    Ok(())
}

/// Drags the foot of `rod` along +x at speed `opts.speed` (after the smooth start) with the tip
/// on `surface` (a line, inclined or not, or a height profile) and Coulomb friction
/// `opts.mu_s`, `opts.mu_k`, from the pressed start at rest to `opts.d_max`, in time (see the
/// module docs of `dynamics`). A round tip (`rod.tip_radius() > 0`) rolls while it sticks
/// (its centre on the line lowered by `r`, or on a profile's parallel curve at the distance
/// `r`) and carries the moment `m(1) = r·T` while it touches; it needs
/// `opts.internal_damping > 0` (docs/model.md, "A round tip in time").
/// Errors: invalid input (a round tip without internal damping among them), `mu_k_table` with
/// a friction texture, no start (or one with a side on the surface), a step the collocation
/// does not solve.
pub fn drag(
    rod: &Rod,
    surface: &Surface,
    opts: &DynDragOptions,
) -> Result<DynDragResult, VibrissaError> {
    opts.validate()?;
    refuse_parts(rod, surface, opts)?;
    let texture = surface.texture_shared();
    let radius = rod.tip_radius();
    let settings = Settings {
        grid: opts.grid,
        tol: opts.tol,
        scheme: opts.scheme,
        damping: opts.foot_damping,
        internal_damping: opts.internal_damping,
        external_damping: opts.external_damping,
        rotary_inertia: opts.rotary_inertia,
        short_steps: true,
        // the last solution as Newton's start, at fixed and adaptive steps (the extrapolated
        // start of `free`, tried with adaptive steps: fewer Newton iterations, no CPU time
        // saved that could be measured; docs/performance.md)
        predict: false,
        remesh: true,
        energy_momentum: false,
    };
    let grid = Rothe::grid_of(&settings);
    let (guess, tip, track) =
        if surface.angle() == 0.0 && surface.profile().is_none() && radius == 0.0 {
            let eta = surface.eta();
            let (guess, tip) = pressed(rod, eta, &grid)?;
            let flat = Track::Line {
                p: [0.0, eta],
                slope: 0.0,
            };
            (guess, tip, flat)
        } else {
            pressed_on(rod, surface, &grid)?
        };
    // (a disk's centre, the rod's end, runs on the line lowered by r, or on the parallel curve
    // at the distance r under a profile: the track of the tip's conditions; the surface itself
    // for the sides)
    let surface_track = track.clone();
    let (tip, track) = if radius > 0.0 {
        let n = guess.z.len() / 6 - 1;
        let centre = [guess.z[6 * n], guess.z[6 * n + 1]];
        let path = match track {
            Track::Line { slope, .. } => Track::Line { p: centre, slope },
            Track::Curve(h) | Track::Offset { h, .. } => Track::Offset { h, r: radius },
        };
        (centre, path)
    } else {
        (tip, track)
    };
    let mut rothe = Rothe::at_rest(rod, &settings, &guess, [0.0, 0.0], TipBc::Stuck(tip))?;
    rothe.tip_radius = radius;
    rothe.friction_table = opts.mu_k_table.clone();
    rothe.track = track.clone();
    rothe.texture = texture.clone();
    let mut drive = Drive {
        o: opts,
        dt: opts.dt,
        refined_until: None,
        checkpoints: Checkpoints(Vec::new()),
        cone_origin: Checkpoints(Vec::new()),
        cone_checkpoints: Checkpoints(Vec::new()),
        accept_cone: false,
        stop_origin: Checkpoints(Vec::new()),
        stop_kept: None,
        path: FootPath::new(opts),
        rothe,
        track,
        t: 0.0,
        d: 0.0,
        turn: 0.0,
        state: ContactState::Stuck,
        anchor: tip[0],
        texture,
        mu_k_now: opts.mu_k,
        edge: None,
        radius,
        surface: surface_track,
        roll: 0.0,
        side_sign: 1.0,
        side_before: None,
        side_min: 1.0,
        tip_turn0: None,
        also_tip: None,
        fresh_slip: false,
        slip_slot: PHASE,
        landed: false,
        ends_before: None,
        held_now: None,
        ends_now: None,
        mismatch: None,
        mismatch_end: None,
        last_tau: 0.0,
        contact_now: None,
        let_go: false,
        foot_work: 0.0,
        friction: 0.0,
        impact: 0.0,
        samples: vec![],
        events: vec![],
        stats: DragStats::default(),
        tried: vec![],
        instant_events: 0,
    };
    let end = drive.rothe.sol.right().to_vec();
    drive.roll = drive.rolling_of(&end);
    drive.samples.push(drive.sample());
    let stop = if drive.events_now()[PHASE] >= 0.0 {
        // the start needs more than μs (μs = 0): it slips at once
        drive.apply(PHASE).unwrap_or(DynDragStop::DMax)
    } else {
        DynDragStop::DMax
    };
    let stop = match stop {
        DynDragStop::DMax => drive.run()?,
        s => s,
    };
    let r = &drive.rothe.stats;
    let stats = DragStats {
        newton_iterations: r.newton_iterations,
        max_nodes: r.max_nodes,
        mesh_nodes: drive.rothe.sol.len(),
        ..drive.stats
    };
    Ok(DynDragResult {
        samples: drive.samples,
        events: drive.events,
        stop,
        stats,
    })
}

#[cfg(test)]
mod tests {
    use super::{held_weights, mismatch_weight};

    /// [`mismatch_weight`] is the weight the held force gives a velocity mismatch's `1/τ`
    /// term (and the alternating mode it left in the last two steps' forces).
    #[test]
    fn a_velocity_mismatch_enters_the_held_force_by_its_weight() {
        // a mismatch `ε` of the velocities with the held tip adds `A/τ` to the force of a step
        // of length τ and alternates: `−A/h`, `+A/h` in the last two (of length h)
        let (a_term, s) = (2.5e-5, |t: f64| 4.0 - 3.0 * t);
        for (tau, h) in [
            (1e-5, 0.0025),
            (3e-4, 0.0025),
            (0.0025, 0.0025),
            (0.004, 0.01),
        ] {
            let [a, b, c] = held_weights(tau, h);
            let held =
                a * (s(tau) + a_term / tau) + b * (s(0.0) - a_term / h) + c * (s(-h) + a_term / h);
            let w = mismatch_weight(tau, h);
            assert!(
                (held - s(tau) - a_term * w).abs() < 1e-12,
                "{tau} {h}: {held}"
            );
        }
        // none at a full step (the held weights cancel the mode), `1/(2τ)` for a short one
        assert!(mismatch_weight(0.01, 0.01).abs() < 1e-12);
        let w = mismatch_weight(1e-6, 0.01);
        assert!((w * 2e-6 - 1.0).abs() < 1e-3, "{w}");
    }

    /// The held force's weights for steps of unequal length (τ the step tried, h the last):
    /// they sum to 1, give a force linear in time its value at the tried step's end, and cancel
    /// a mode `e, −e, e` of the three forces (to rounding).
    #[test]
    fn held_weights_fit_unequal_steps() {
        for (tau, h) in [(0.01, 0.01), (0.003, 0.01), (0.02, 1e-5), (1e-5, 0.5)] {
            let [a, b, c] = held_weights(tau, h);
            assert!((a + b + c - 1.0).abs() < 1e-15, "{tau} {h}");
            // G(t) = 2 + 3t with t = τ at the step's end, 0 at its start, −h before
            let g = |t: f64| 2.0 + 3.0 * t;
            let held = a * g(tau) + b * g(0.0) + c * g(-h);
            assert!((held - g(tau)).abs() < 1e-14, "{tau} {h}: {held}");
            assert!((a - b + c).abs() < 1e-15, "{tau} {h}");
        }
    }

    /// The viscoelastic support's quasi-static limit is the static model's compliant support:
    /// from the pressed start at rest (support compliance 1, damper c = 0.5), one step so long
    /// (τ = 1e12) that the rod's inertia (`4/τ²`) and the damper's moment (`c·2/τ·Δθ`) vanish,
    /// the foot moved by d = 0.0008 and the tip stuck (this support's rod slips at d 0.001), lands on the quasi-static drag's state at
    /// the same d: the rod's shooter (`crate::drag`, tol 1e-10), an independent solver of the
    /// static model with the compliant support `θ = c_s m(0)`. Measured (2026-12-05): N, the
    /// base's x force and m(0) within 1.4e-12, 1.3e-12 and 2.8e-14, the tip's place within
    /// 3.4e-15 (collocation at tol 1e-12 on 200 intervals against the shooter at 1e-10);
    /// bounds 1e-10 (the issue's), the tip's 1e-12.
    #[test]
    fn a_viscoelastic_support_s_slow_limit_is_the_compliant_support() {
        use crate::rothe::{Foot, Rothe, Settings, TipBc};
        let rod = crate::Rod::builder()
            .support_compliance(1.0)
            .build()
            .unwrap();
        let settings = Settings {
            damping: 0.5,
            ..Settings::plain(200, 1e-12)
        };
        let grid = Rothe::grid_of(&settings);
        let (guess, tip) = super::pressed(&rod, 0.75, &grid).unwrap();
        let mut rothe =
            Rothe::at_rest(&rod, &settings, &guess, [0.0, 0.0], TipBc::Stuck(tip)).unwrap();
        let d = 0.0008;
        let tau = 1e12;
        let tr = rothe
            .trial(tau, Foot::at([d, 0.0]), TipBc::Stuck(tip), 0.0)
            .unwrap();
        rothe.commit(tr);
        let p = rothe.sample(tau);
        let qs = crate::drag(
            &rod,
            &crate::Surface::flat(0.75).unwrap(),
            &crate::DragOptions {
                mu_s: Some(0.5),
                mu_k: Some(0.3),
                d_max: d,
                ..crate::DragOptions::default()
            },
        )
        .unwrap();
        let row = qs.rows.last().unwrap();
        assert!((row.d - d).abs() < 1e-15, "{}", row.d);
        let dn = (-p.gy_base - row.normal).abs();
        let dfx = (p.gx_base - row.fx).abs();
        let dm = (p.m_base - row.m_base).abs();
        let dx = (p.tip_x - row.x_tip).abs().max((p.tip_y - row.y_tip).abs());
        eprintln!(
            "N {dn:e}, fx {dfx:e}, m(0) {dm:e}, tip {dx:e}; theta {}",
            p.theta
        );
        assert!(
            dn < 1e-10 && dfx < 1e-10 && dm < 1e-10 && dx < 1e-12,
            "{dn} {dfx} {dm} {dx}"
        );
        assert!(p.theta.abs() > 0.1, "the support turns: {}", p.theta);
    }
}
