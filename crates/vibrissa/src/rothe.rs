//! The Rothe step of the rod in time, shared by `dynamics::free` and `dynamics::drag` (issue 32):
//! one time step of Newmark's average-acceleration rule as a boundary-value problem in the arc
//! length, solved by crate `bvp`'s Lobatto collocation, and the history of positions,
//! velocities and accelerations on a uniform grid in `s` (module `dynamics` states the
//! equations and the scheme's properties).
//!
//! A step is tried first ([`Rothe::trial`]: the BVP solved for a step `τ`, nothing of the state
//! changed) and then taken ([`Rothe::commit`]), so a driver can locate an event inside a step by
//! trying steps of several lengths (`dynamics::drag`). The step length may change from step to
//! step (the rule is written for any `τ`). The foot and the tip take their conditions per
//! step: the foot at a given place, the tip free under a force, stuck at a point, or sliding
//! along the surface's line or curve ([`Track`]) under Coulomb friction.

use crate::inertia::mass_density;
use crate::parts::Stiffness;
use crate::profile::{General, Profile};
use crate::surface::{disk_on_curve, Texture};
use crate::{Rod, VibrissaError};
use bvp::{
    Bvp, BvpError, BvpSolver, Collocation, CollocationOptions, Dims, ErrorControl, Guess, Solution,
};
use serde::Serialize;
use std::f64::consts::FRAC_PI_2;
use std::sync::Arc;

/// The rod at one time.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct DynSample {
    /// Time.
    pub t: f64,
    /// Tip position, x.
    pub tip_x: f64,
    /// Tip position, y.
    pub tip_y: f64,
    /// Tip velocity, x.
    pub tip_vx: f64,
    /// Tip velocity, y.
    pub tip_vy: f64,
    /// Rotation of the foot `θ = φ(0) − π/2` (0 on a clamp).
    pub theta: f64,
    /// `m(0)`.
    pub m_base: f64,
    /// Internal force at the foot `G(0)`, x (the contact force, in the static case).
    pub gx_base: f64,
    /// Internal force at the foot, y.
    pub gy_base: f64,
    /// Kinetic energy `½∫μ|r_t|²` (with rotary inertia plus `½∫ j φ_t²`).
    pub kinetic: f64,
    /// Elastic energy `½∫b m² + θ²/(2 c_s)` (with internal damping `½∫(κ − κ0)²/b + θ²/(2 c_s)`).
    pub elastic: f64,
    /// Energy taken by the foot's damper so far, `∫ c θ_t² dt` (by the midpoint rule of the
    /// time steps: the scheme's own energy identity).
    pub dissipated: f64,
    /// Energy taken by the rod's internal (Kelvin–Voigt) damping so far,
    /// `∫ γ_i ∫ κ_t²/b ds dt` (midpoint rule of the steps, Simpson's rule on the grid).
    pub internal_damping: f64,
    /// Energy taken by the external viscous damping so far, `∫ γ_e ∫ μ |r_t|² ds dt` (likewise).
    pub external_damping: f64,
}

/// Work done.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct DynStats {
    /// Time steps.
    pub steps: usize,
    /// Newton iterations of the steps' collocation solves.
    pub newton_iterations: usize,
    /// Largest mesh of a step's collocation.
    pub max_nodes: usize,
    /// Steps the local error estimate rejected (with `time_tol`; not written while 0, so
    /// fixed steps serialize as before).
    #[serde(skip_serializing_if = "is_zero")]
    pub rejected_steps: usize,
}

/// `serde`'s test for [`DynStats::rejected_steps`].
pub(crate) fn is_zero(n: &usize) -> bool {
    *n == 0
}

/// The line or curve `y = h(x)` the tip touches in a drag: the line through `p` with the slope
/// `slope` (a flat surface: slope 0), or a surface's height profile; or the path of the centre
/// of a disk of radius `r` that touches a height profile from below (the profile's parallel
/// curve at the distance `r`: a round tip's end on a curved surface).
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Track {
    Line {
        p: [f64; 2],
        slope: f64,
    },
    Curve(std::sync::Arc<crate::surface::Height>),
    Offset {
        h: std::sync::Arc<crate::surface::Height>,
        r: f64,
    },
}

impl Track {
    /// `(h, h', h'')` at `x`. On a disk's path, at the centre `X` whose disk touches the
    /// profile at `x_c` (`X = x_c + r h'/w`, `w = √(1 + h'²)`): `Y = h − r/w`, `Y' = h'` (the
    /// path is parallel to the profile) and `Y'' = h''/(1 + r h''/w³)`, all at `x_c`.
    pub fn jet(&self, x: f64) -> (f64, f64, f64) {
        match self {
            Track::Line { p, slope } => (p[1] + slope * (x - p[0]), *slope, 0.0),
            Track::Curve(h) => h.jet(x),
            Track::Offset { h, r } => {
                let (y, hp, hpp) = h.jet(touch_of(h, *r, x));
                let w = (1.0 + hp * hp).sqrt();
                (y - r / w, hp, hpp / (1.0 + r * hpp / (w * w * w)))
            }
        }
    }

    /// Whether the track is the flat line `y = const` (its normal is `y`, its tangent `x`).
    pub fn flat(&self) -> bool {
        matches!(self, Track::Line { slope, .. } if *slope == 0.0)
    }
}

/// Where a disk of radius `r` centred at lab `x` touches the profile `h` from below: the `x_c`
/// with `x_c + r h'(x_c)/w(x_c) = x`, by the static drag's [`disk_on_curve`] (Newton kept in
/// the bracket `[x − r, x + r]`). NaN where the disk has no single contact point (it is wider
/// than a concave part of the profile is round, which the surface refuses for a round tip):
/// a step then fails as non-finite instead of going on from an unconverged contact point.
fn touch_of(h: &crate::surface::Height, r: f64, x: f64) -> f64 {
    disk_on_curve(h, r, x, 1.0).map_or(f64::NAN, |dk| dk.xc)
}

/// The line `y = 0`, the track a state starts with.
const FLAT: Track = Track::Line {
    p: [0.0, 0.0],
    slope: 0.0,
};

/// The tip's conditions in a step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum TipBc {
    /// A given force `G(1)` on the tip (`[0, 0]`: free).
    Force([f64; 2]),
    /// The tip held at a point: `r(1)` given.
    Stuck([f64; 2]),
    /// The tip on the track `y = h(x)` ([`Rothe::track`]), sliding: with the track's unit
    /// tangent `t = (1, h')/w` and normal `n = (−h', 1)/w`, `w = √(1 + h'²)`, the tangential
    /// force `G·t = ratio·G·n` (`ratio = dir·μk`: with the normal force `N = −G·n`, friction
    /// `T = −G·t = dir·μk·N` against the slide in direction `dir`; on a flat track
    /// `Gx(1) = ratio·Gy(1)`).
    Sliding { ratio: f64 },
    /// The tip on the track, sliding in direction `dir` with the kinetic friction
    /// `μk(|v_t|)` of the friction table ([`Rothe::friction_table`]): `G·t = dir·μk·G·n`, the
    /// tip's velocity along the track at the step's end by the trapezoidal rule,
    /// `v = 2/Δt (r(1) − rⁿ) − ṙⁿ`, `v_t = v·t` (`ẋ(1)` on a flat track).
    SlidingRate { dir: f64 },
    /// The tip on the track, sliding in direction `dir` with the kinetic friction `μk(x(1))`
    /// of the surface's friction texture ([`Rothe::texture`], continuous along x):
    /// `G·t = dir·μk(x(1))·G·n`.
    SlidingOn { dir: f64 },
    /// A round tip ([`Rothe::tip_radius`] `r > 0`: a rigid disk centred at the rod's end) stuck
    /// on a line track: it rolls without slipping, `w·x(1) − r·φ(1) = a` (`w = √(1 + h'²)`;
    /// the contact point's arc length along the line less the disk's turn), its centre on the
    /// track (the line lowered by `r` along its normal).
    Rolling { a: f64 },
    /// A side of the rod on the track at an inner point `s_c` (an unknown of the step), the rod
    /// tangent to the track there and free beyond it, rolling without slip: the contact's arc
    /// length along the track less `sign·s_c` stays at `a` (the contact's material point at
    /// rest; `sign = ±1` as the rod's tangent at the contact runs with or against the track's).
    /// The step is solved on the two pieces `[0, s_c]` and `[s_c, 1]` ([`Split`]).
    SideRolling { a: f64, sign: f64 },
    /// A side of the rod on the track at an inner point `s_c`, tangent to it, the rod free
    /// beyond it, sliding: its contact force `F` (the jump of the internal force) meets
    /// `F·t = ratio·F·n` as a sliding tip's `G(1)` does ([`TipBc::Sliding`]).
    SideSliding { ratio: f64 },
    /// Two contacts at once: a side on the track as [`TipBc::SideRolling`] or
    /// [`TipBc::SideSliding`] (`side`), and the tip on it as well, stuck at a point or sliding
    /// along the track (`end`). Solved as a [`Split`] whose outer piece ends on the tip's
    /// condition instead of a free end.
    SideAndTip { side: SideHold, end: EndHold },
}

/// The tip's condition beside a side's ([`TipBc::SideAndTip`]): a point tip stuck at a point
/// ([`TipBc::Stuck`]) or sliding on the track under `T = ratio·N` ([`TipBc::Sliding`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum EndHold {
    Stuck([f64; 2]),
    Sliding { ratio: f64 },
}

impl EndHold {
    /// The tip's own condition.
    fn tip_bc(self) -> TipBc {
        match self {
            EndHold::Stuck(p) => TipBc::Stuck(p),
            EndHold::Sliding { ratio } => TipBc::Sliding { ratio },
        }
    }
}

/// The arc length along `track` at lab `x` (a line: `w·x`, `w = √(1 + h'²)`; a profile: its
/// `σ(x)`), with `dσ/dx`.
pub(crate) fn track_arc(track: &Track, x: f64) -> (f64, f64) {
    match track {
        Track::Curve(h) => h.sigma(x),
        _ => {
            let hp = track.jet(x).1;
            let w = (1.0 + hp * hp).sqrt();
            (w * x, w)
        }
    }
}

/// A side contact's state at the end of a step: where it touches (`s`), the rod's state there
/// `(x, y, φ, m)`, and the contact force on the rod `F = G(s_c⁻) − G(s_c⁺)` (the jump of the
/// internal force across the contact).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct SideAt {
    /// The contact's arc length `s_c`.
    pub s: f64,
    /// `(x, y, φ, m)` at `s_c`.
    pub z: [f64; 4],
    /// The contact force on the rod.
    pub force: [f64; 2],
}

/// The x of the point where a disk of radius `r` centred at `x` on a line `track` (the surface
/// lowered by `r`) touches the surface: `x − r sin β` (`x` itself for a point tip).
pub(crate) fn contact_x(track: &Track, r: f64, x: f64) -> f64 {
    if r == 0.0 {
        return x;
    }
    if let Track::Offset { h, r } = track {
        return touch_of(h, *r, x);
    }
    let hp = track.jet(x).1;
    x - r * hp / (1.0 + hp * hp).sqrt()
}

/// A disk's rolling invariant `s(x(1)) − r·φ(1)`, the end `z = [x, y, φ, …]`: the arc length
/// `s` of its centre's path less the disk's turn (rolling without slip, the contact's material
/// point at rest, moves the centre along its path by `r` per unit turn). On a line `track`
/// `s = w·x` (`w = √(1 + h'²)`); on a disk's path under a profile `s = σ(x_c) + r·atan h'(x_c)`
/// (`σ` the profile's arc length, `x_c` where the disk touches: `ds = (w + r h''/w²) dx_c`),
/// whose slope in `x(1)` is `w` too.
pub(crate) fn rolling_invariant(track: &Track, r: f64, z: &[f64]) -> f64 {
    if let Track::Offset { h, r } = track {
        let xc = touch_of(h, *r, z[0]);
        return h.sigma(xc).0 + r * h.jet(xc).1.atan() - r * z[2];
    }
    let hp = track.jet(z[0]).1;
    (1.0 + hp * hp).sqrt() * z[0] - r * z[2]
}

/// Kinetic friction `μk(v)` of a table of `(v, μk)` points (speeds increasing): piecewise
/// linear, constant beyond its ends; with its slope `dμk/dv`.
pub(crate) fn mu_k_of(table: &[[f64; 2]], v: f64) -> (f64, f64) {
    let (first, last) = (table[0], table[table.len() - 1]);
    if v <= first[0] {
        return (first[1], 0.0);
    }
    if v >= last[0] {
        return (last[1], 0.0);
    }
    let k = table
        .partition_point(|p| p[0] <= v)
        .clamp(1, table.len() - 1);
    let (a, b) = (table[k - 1], table[k]);
    let slope = (b[1] - a[1]) / (b[0] - a[0]);
    (a[1] + slope * (v - a[0]), slope)
}

/// The internal force's unknowns (4, 5) of `guess`, values and slopes, times `r` (a change of
/// their scale `gs`, see [`Settings::short_steps`]).
fn scale_forces(guess: &mut Guess, r: f64) {
    if r == 1.0 {
        return;
    }
    for zi in guess.z.chunks_mut(6) {
        zi[4] *= r;
        zi[5] *= r;
    }
    for zi in guess.dz.iter_mut().flat_map(|d| d.chunks_mut(6)) {
        zi[4] *= r;
        zi[5] *= r;
    }
}

/// Cubic Hermite interpolation of values `v` and derivatives `d` on the uniform grid
/// (`v.len() − 1` intervals on `[0, 1]`): continuous with its first derivative.
fn interp(v: &[f64], d: &[f64], s: f64) -> f64 {
    let n = v.len() - 1;
    let h = 1.0 / n as f64;
    let u = (s * n as f64).clamp(0.0, n as f64);
    let i = (u.floor() as usize).min(n - 1);
    let t = u - i as f64;
    let (t2, t3) = (t * t, t * t * t);
    (2.0 * t3 - 3.0 * t2 + 1.0) * v[i]
        + (t3 - 2.0 * t2 + t) * h * d[i]
        + (-2.0 * t3 + 3.0 * t2) * v[i + 1]
        + (t3 - t2) * h * d[i + 1]
}

/// Cubic Lagrange interpolation of values `v` on the uniform grid (`v.len() − 1 ≥ 3`
/// intervals on `[0, 1]`; the four nodes around `s`, shifted inwards at the ends).
fn lagrange(v: &[f64], s: f64) -> f64 {
    let n = v.len() - 1;
    let u = (s * n as f64).clamp(0.0, n as f64);
    let i = (u.floor() as usize).clamp(1, n - 2);
    let t = u - i as f64;
    let (a, b, c, d) = (v[i - 1], v[i], v[i + 1], v[i + 2]);
    -t * (t - 1.0) * (t - 2.0) / 6.0 * a + (t + 1.0) * (t - 1.0) * (t - 2.0) / 2.0 * b
        - (t + 1.0) * t * (t - 2.0) / 2.0 * c
        + (t + 1.0) * t * (t - 1.0) / 6.0 * d
}

/// `sin(Δ/2)/(Δ/2)` and its derivative in `Δ/2` (series below 1e-4).
fn sinc_half(delta: f64) -> (f64, f64) {
    let u = 0.5 * delta;
    if u.abs() < 1e-4 {
        (1.0 - u * u / 6.0, -u / 3.0)
    } else {
        let (su, cu) = u.sin_cos();
        (su / u, (u * cu - su) / (u * u))
    }
}

/// `v0''(s)` by finite differences of step 1e-3 of fourth order: central inside, one-sided
/// (six points) within two steps of an end.
fn second_derivative(v0: &dyn Fn(f64) -> [f64; 2], s: f64) -> [f64; 2] {
    let h = 1e-3;
    let at = |k: f64| v0(s + k * h);
    if s >= 2.0 * h && s <= 1.0 - 2.0 * h {
        let f = [at(-2.0), at(-1.0), at(0.0), at(1.0), at(2.0)];
        let w = [-1.0, 16.0, -30.0, 16.0, -1.0];
        return [0, 1].map(|c| (0..5).map(|k| w[k] * f[k][c]).sum::<f64>() / (12.0 * h * h));
    }
    let sign = if s < 0.5 { 1.0 } else { -1.0 };
    let w = [45.0, -154.0, 214.0, -156.0, 61.0, -10.0];
    let f: Vec<[f64; 2]> = (0..6).map(|k| at(sign * k as f64)).collect();
    [0, 1].map(|c| (0..6).map(|k| w[k] * f[k][c]).sum::<f64>() / (12.0 * h * h))
}

/// One time step's boundary-value problem.
struct Step<'a> {
    profile: &'a General,
    stiffness: &'a Stiffness,
    /// `4/Δt²`.
    k_acc: f64,
    /// The unknowns 4, 5 are `G/gs` (see [`Settings::short_steps`]).
    gs: f64,
    /// Kelvin–Voigt damping: `1 + 2γ_i/Δt` and `q = γ_i (2/Δt κⁿ + κ_tⁿ)` on the grid, so that
    /// `φ' = (κ0 + b m + q)/(1 + 2γ_i/Δt)` (`None`: no internal damping, `φ' = κ0 + b m`).
    kv: Option<(f64, &'a [f64])>,
    /// Rotary inertia: `g0²·4/Δt²` and `φ̂` (or `φ̂ − φⁿ` with `base`) on the grid, so that
    /// `m' = G × e + j φ_tt` with `j = g0²/b`, `φ_tt = 4/Δt² (φ − φ̂)` (`None`: no rotary
    /// inertia).
    rot: Option<(f64, &'a [f64])>,
    /// The positions `rⁿ` as the last step's solution (then `hat_*` hold `r̂ − rⁿ`), or `None`
    /// (`hat_*` hold `r̂`).
    base: Option<&'a Solution>,
    /// `r̂` (or `r̂ − rⁿ`) on the grid.
    hat_x: &'a [f64],
    hat_y: &'a [f64],
    /// `dr̂/ds` on the grid.
    hat_xs: &'a [f64],
    hat_ys: &'a [f64],
    compliance: f64,
    /// `c·(2/Δt)`, and `c·(−2/Δt θⁿ − θ_tⁿ)`: `c θ_t = damp_k θ + damp_0`.
    damp_k: f64,
    damp_0: f64,
    /// The moment applied to the support.
    moment: f64,
    /// The foot's place and the support's turn `θ_w` (the clamp's direction `π/2 − θ_w`).
    foot: Foot,
    /// The tip's conditions.
    tip: TipBc,
    /// The track of a sliding tip.
    track: &'a Track,
    /// The friction table of [`TipBc::SlidingRate`], the tip's `(xⁿ, ẋⁿ, yⁿ, ẏⁿ, φⁿ, φ̇ⁿ)` and
    /// `2/Δt`.
    table: &'a [[f64; 2]],
    tip_then: [f64; 6],
    /// The tip's rates `q_t = two_tau (q − qⁿ) − then_rate q_tⁿ` (2/Δt and 1 by the
    /// trapezoidal rule, 1/Δt and 0 by backward Euler).
    two_tau: f64,
    then_rate: f64,
    /// The friction texture of [`TipBc::SlidingOn`].
    texture: Option<&'a Texture>,
    /// The tip's radius `r` (a disk on a line track): while it touches, `m(1) = r·T`.
    radius: f64,
    /// `(a, K)` of [`Rothe::disk_held`].
    held: (f64, f64),
    /// [`Settings::energy_momentum`] (with `base`: the last solution, `φⁿ` and `φⁿ'`).
    emm: bool,
    /// With `emm`, the support's turn `θⁿ`: its spring carries the step's mean turn, `m̄(0) + M
    /// = k (θⁿ + θⁿ⁺¹)/2 + c (θⁿ⁺¹ − θⁿ)/Δt` (`damp_k`, `damp_0` then `c/Δt`, `−c θⁿ/Δt`).
    theta_then: f64,
    /// With `emm`, `γ_i/Δt`: the Kelvin–Voigt moment at the step's mean curvature and mean
    /// rate, `b m̄ = (κⁿ + κⁿ⁺¹)/2 − κ0 + γ_i (κⁿ⁺¹ − κⁿ)/Δt`.
    emm_kv: f64,
}

impl Step<'_> {
    /// Whether a round tip touches the track (stuck or sliding): its moment condition is
    /// `m(1) = r·T` then, `m(1) = 0` otherwise.
    fn disk_touches(&self) -> bool {
        self.radius > 0.0 && !matches!(self.tip, TipBc::Force(_) | TipBc::Stuck(_))
    }

    /// `μk` of the friction texture where the tip touches (its end at `x(1)`; a disk's contact
    /// point) and `dμk/dx` (without a texture: no friction, which [`TipBc::SlidingOn`] is not
    /// built with).
    fn place_friction(&self, x1: f64) -> (f64, f64) {
        let xc = contact_x(self.track, self.radius, x1);
        self.texture.map_or((0.0, 0.0), |t| t.kinetic_slope(xc))
    }

    /// `μk` at the slip velocity at the step's end (the tip's end `zb`, the track's slope `hp`
    /// there) and `dμk/dx(1)`, `dμk/dy(1)`, `dμk/dφ(1)` (the tangent's own change left out:
    /// Newton's matrix only). A disk's slip velocity is its contact's material point's,
    /// `v·t − r φ̇(1)`, with `φ̇(1)` by the trapezoidal rule as the end's velocity.
    fn rate_friction(&self, zb: &[f64], hp: f64) -> (f64, [f64; 3]) {
        let (x1, y1) = (zb[0], zb[1]);
        let vx = self.two_tau * (x1 - self.tip_then[0]) - self.then_rate * self.tip_then[1];
        let spin = if self.radius > 0.0 {
            self.radius
                * (self.two_tau * (zb[2] - self.tip_then[4]) - self.then_rate * self.tip_then[5])
        } else {
            0.0
        };
        if hp == 0.0 {
            let v = vx - spin;
            let (mk, slope) = mu_k_of(self.table, v.abs());
            let dv = slope * v.signum() * self.two_tau;
            return (mk, [dv, 0.0, -dv * self.radius]);
        }
        let vy = self.two_tau * (y1 - self.tip_then[2]) - self.then_rate * self.tip_then[3];
        let w = (1.0 + hp * hp).sqrt();
        let v = (vx + hp * vy) / w - spin;
        let (mk, slope) = mu_k_of(self.table, v.abs());
        let dv = slope * v.signum() * self.two_tau / w;
        (mk, [dv, dv * hp, -dv * w * self.radius])
    }
}

impl Bvp for Step<'_> {
    fn dims(&self) -> Dims {
        Dims { n: 6, k: 0 }
    }
    fn interval(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn rhs(&self, s: f64, z: &[f64], _p: &[f64], dz: &mut [f64]) {
        let (sp, cp) = z[2].sin_cos();
        let mu = mass_density(self.stiffness, s);
        dz[0] = cp;
        dz[1] = sp;
        dz[2] = match self.kv {
            None => self.profile.k0(s) + self.profile.b(s) * z[3],
            Some((c, q)) => (self.profile.k0(s) + self.profile.b(s) * z[3] + lagrange(q, s)) / c,
        };
        dz[3] = self.gs * (z[4] * sp - z[5] * cp);
        let mut r0 = [0.0; 6];
        if let Some(b) = self.base {
            b.eval(s, &mut r0);
        }
        if self.emm {
            let mut d0 = [0.0; 6];
            if let Some(b) = self.base {
                b.eval_derivative(s, &mut d0);
            }
            let g = self.emm_kv;
            dz[2] = (self.profile.k0(s) + self.profile.b(s) * z[3] - (0.5 - g) * d0[2]) / (0.5 + g);
            let (f, _) = sinc_half(z[2] - r0[2]);
            let (sm, cm) = (0.5 * (z[2] + r0[2])).sin_cos();
            dz[3] = self.gs * f * (z[4] * sm - z[5] * cm);
        }
        if let Some((jk, phi_hat)) = self.rot {
            dz[3] += jk / self.profile.b(s) * (z[2] - r0[2] - lagrange(phi_hat, s));
        }
        let k = self.k_acc / self.gs;
        dz[4] = mu * k * (z[0] - r0[0] - interp(self.hat_x, self.hat_xs, s));
        dz[5] = mu * k * (z[1] - r0[1] - interp(self.hat_y, self.hat_ys, s));
    }
    fn rhs_jacobian(
        &self,
        s: f64,
        z: &[f64],
        _p: &[f64],
        dfdz: &mut [f64],
        _dfdp: &mut [f64],
    ) -> bool {
        let (sp, cp) = z[2].sin_cos();
        let mk = mass_density(self.stiffness, s) * (self.k_acc / self.gs);
        dfdz[..36].fill(0.0);
        dfdz[2] = -sp;
        dfdz[6 + 2] = cp;
        dfdz[12 + 3] = match self.kv {
            None => self.profile.b(s),
            Some((c, _)) => self.profile.b(s) / c,
        };
        dfdz[18 + 2] = self.gs * (z[4] * cp + z[5] * sp);
        if let Some((jk, _)) = self.rot {
            dfdz[18 + 2] += jk / self.profile.b(s);
        }
        dfdz[18 + 4] = self.gs * sp;
        dfdz[18 + 5] = -self.gs * cp;
        if self.emm {
            let mut r0 = [0.0; 6];
            if let Some(b) = self.base {
                b.eval(s, &mut r0);
            }
            dfdz[12 + 3] = self.profile.b(s) / (0.5 + self.emm_kv);
            let (f, df) = sinc_half(z[2] - r0[2]);
            let (sm, cm) = (0.5 * (z[2] + r0[2])).sin_cos();
            let (a, da) = (z[4] * sm - z[5] * cm, z[4] * cm + z[5] * sm);
            dfdz[18 + 2] = self.gs * 0.5 * (df * a + f * da);
            if let Some((jk, _)) = self.rot {
                dfdz[18 + 2] += jk / self.profile.b(s);
            }
            dfdz[18 + 4] = self.gs * f * sm;
            dfdz[18 + 5] = -self.gs * f * cm;
        }
        dfdz[24] = mk;
        dfdz[30 + 1] = mk;
        true
    }
    fn bc_jacobian(
        &self,
        _za: &[f64],
        zb: &[f64],
        _p: &[f64],
        dga: &mut [f64],
        dgb: &mut [f64],
        _dgp: &mut [f64],
    ) -> bool {
        dga[..36].fill(0.0);
        dgb[..36].fill(0.0);
        dga[0] = 1.0;
        dga[6 + 1] = 1.0;
        dga[12 + 2] = if self.emm { 0.5 } else { 1.0 } + self.compliance * self.damp_k;
        dga[12 + 3] = -self.compliance;
        dgb[18 + 3] = 1.0;
        if self.disk_touches() {
            // `m(1) − r·T`, `T = −gs (z4 + h' z5)/w` (a line: h' constant)
            let (hp, _) = self.slope_at(zb[0]);
            let w = (1.0 + hp * hp).sqrt();
            let ra = self.radius * self.held.0;
            dgb[18 + 4] = ra * self.gs / w;
            dgb[18 + 5] = ra * self.gs * hp / w;
        }
        match self.tip {
            // (a side step's tip: [`Split`] solves it with the outer piece's own condition)
            TipBc::Force(_)
            | TipBc::SideRolling { .. }
            | TipBc::SideSliding { .. }
            | TipBc::SideAndTip { .. } => {
                dgb[24 + 4] = self.gs;
                dgb[30 + 5] = self.gs;
            }
            TipBc::Stuck(_) => {
                dgb[24] = 1.0;
                dgb[30 + 1] = 1.0;
            }
            TipBc::Sliding { ratio } => self.sliding_jacobian(zb, ratio, [0.0, 0.0], dgb),
            TipBc::SlidingRate { dir } => {
                let (hp, _) = self.slope_at(zb[0]);
                let (mk, dmk) = self.rate_friction(zb, hp);
                // `res = G·t' − dir·μk·G·n'` (t', n' the unnormalized tangent and normal)
                let gn = zb[5] - hp * zb[4];
                self.sliding_jacobian(zb, dir * mk, [-dir * dmk[0] * gn, -dir * dmk[1] * gn], dgb);
                dgb[30 + 2] = -dir * dmk[2] * gn;
            }
            TipBc::SlidingOn { dir } => {
                let (hp, _) = self.slope_at(zb[0]);
                let (mk, dmk) = self.place_friction(zb[0]);
                let gn = zb[5] - hp * zb[4];
                self.sliding_jacobian(zb, dir * mk, [-dir * dmk * gn, 0.0], dgb);
            }
            TipBc::Rolling { .. } => {
                let (hp, _) = self.slope_at(zb[0]);
                dgb[24] = (1.0 + hp * hp).sqrt();
                dgb[24 + 2] = -self.radius;
                dgb[30] = -hp;
                dgb[30 + 1] = 1.0;
            }
        }
        true
    }
    fn bc(&self, za: &[f64], zb: &[f64], _p: &[f64], res: &mut [f64]) {
        // the support's own rotation: the foot's slope against the turned clamp's direction
        let theta = za[2] - FRAC_PI_2 + self.foot.turn;
        res[0] = za[0] - self.foot.place[0];
        res[1] = za[1] - self.foot.place[1];
        let spring = if self.emm {
            0.5 * (theta + self.theta_then)
        } else {
            theta
        };
        res[2] =
            spring - self.compliance * (za[3] + self.moment - self.damp_k * theta - self.damp_0);
        res[3] = zb[3];
        if self.disk_touches() {
            let (_, hp, _) = self.track.jet(zb[0]);
            let w = (1.0 + hp * hp).sqrt();
            let (a, known) = self.held;
            res[3] = zb[3] + self.radius * (a * self.gs * (zb[4] + hp * zb[5]) / w - known);
        }
        match self.tip {
            TipBc::Force(f) => {
                res[4] = self.gs * zb[4] - f[0];
                res[5] = self.gs * zb[5] - f[1];
            }
            TipBc::SideRolling { .. } | TipBc::SideSliding { .. } | TipBc::SideAndTip { .. } => {
                res[4] = self.gs * zb[4];
                res[5] = self.gs * zb[5];
            }
            TipBc::Stuck(p) => {
                res[4] = zb[0] - p[0];
                res[5] = zb[1] - p[1];
            }
            TipBc::Sliding { ratio } => self.sliding_res(zb, ratio, res),
            TipBc::SlidingRate { dir } => {
                let (hp, _) = self.slope_at(zb[0]);
                let (mk, _) = self.rate_friction(zb, hp);
                self.sliding_res(zb, dir * mk, res);
            }
            TipBc::SlidingOn { dir } => {
                let (mk, _) = self.place_friction(zb[0]);
                self.sliding_res(zb, dir * mk, res);
            }
            TipBc::Rolling { a } => {
                res[4] = rolling_invariant(self.track, self.radius, zb) - a;
                res[5] = zb[1] - self.track.jet(zb[0]).0;
            }
        }
    }
}

impl Step<'_> {
    /// The track's slope `h'` and `h''` at `x`.
    fn slope_at(&self, x: f64) -> (f64, f64) {
        let (_, hp, hpp) = self.track.jet(x);
        (hp, hpp)
    }

    /// The sliding tip's two conditions: on the track, `y(1) − h(x(1)) = 0`, and the
    /// friction `G·t' − ratio·G·n' = 0` with `t' = (1, h')`, `n' = (−h', 1)` (`w`, common to
    /// both, divided out).
    fn sliding_res(&self, zb: &[f64], ratio: f64, res: &mut [f64]) {
        let (h, hp, _) = self.track.jet(zb[0]);
        res[4] = zb[1] - h;
        res[5] = if hp == 0.0 {
            zb[4] - ratio * zb[5]
        } else {
            zb[4] + hp * zb[5] - ratio * (zb[5] - hp * zb[4])
        };
    }

    /// The derivatives of [`Step::sliding_res`] (`extra`: those of the ratio's own dependence
    /// on `x(1)`, `y(1)` in the friction row).
    fn sliding_jacobian(&self, zb: &[f64], ratio: f64, extra: [f64; 2], dgb: &mut [f64]) {
        let (hp, hpp) = self.slope_at(zb[0]);
        dgb[24] = -hp;
        dgb[24 + 1] = 1.0;
        dgb[30] = hpp * (zb[5] + ratio * zb[4]) + extra[0];
        dgb[30 + 1] = extra[1];
        dgb[30 + 4] = 1.0 + ratio * hp;
        dgb[30 + 5] = hp - ratio;
    }
}

/// A step with a side contact ([`TipBc::SideRolling`], [`TipBc::SideSliding`]) at the unknown
/// `s_c = p[0]`: the rod's two pieces on `σ ∈ [0, 1]`, the inner one from the foot
/// (`s = s_c σ`), the outer one from the tip inwards (`s = 1 − (1 − s_c) σ`), so that they meet at `σ = 1` and every condition
/// is at an end: the foot's three and the free tip's three (`m = 0`, `G = 0`) at `σ = 0`; at
/// `σ = 1` the pieces' `x, y, φ, m` equal, the rod on the track and tangent to it
/// (`h'(x) cos φ − sin φ = 0`: a smooth rod touching from one side), and the contact's hold.
/// The internal force jumps across the contact by the contact force, `F = G(s_c⁻) − G(s_c⁺)`.
struct Split<'s, 'a> {
    /// The step, its tip free.
    step: &'s Step<'a>,
    /// How the side holds.
    hold: SideHold,
}

/// How a side holds on the surface: [`TipBc::SideRolling`]'s and [`TipBc::SideSliding`]'s
/// values, the side conditions a [`Split`] is built with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum SideHold {
    /// Rolling without slip: the arc along the surface less `sign·s_c` is `a`.
    Rolling { a: f64, sign: f64 },
    /// Sliding: `T = ratio·N`.
    Sliding { ratio: f64 },
}

impl SideHold {
    /// The side's hold of the tip condition `tip` and the condition of the tip beyond it (free,
    /// or [`TipBc::SideAndTip`]'s), `None` for a tip's condition alone.
    fn of(tip: TipBc) -> Option<(SideHold, TipBc)> {
        let free = TipBc::Force([0.0, 0.0]);
        match tip {
            TipBc::SideRolling { a, sign } => Some((SideHold::Rolling { a, sign }, free)),
            TipBc::SideSliding { ratio } => Some((SideHold::Sliding { ratio }, free)),
            TipBc::SideAndTip { side, end } => Some((side, end.tip_bc())),
            _ => None,
        }
    }
}

impl Bvp for Split<'_, '_> {
    fn dims(&self) -> Dims {
        Dims { n: 12, k: 1 }
    }
    fn interval(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn rhs(&self, u: f64, z: &[f64], p: &[f64], dz: &mut [f64]) {
        let sc = p[0];
        self.step.rhs(sc * u, &z[..6], &[], &mut dz[..6]);
        self.step
            .rhs(1.0 - (1.0 - sc) * u, &z[6..], &[], &mut dz[6..]);
        dz[..6].iter_mut().for_each(|d| *d *= sc);
        dz[6..].iter_mut().for_each(|d| *d *= sc - 1.0);
    }
    fn rhs_jacobian(
        &self,
        u: f64,
        z: &[f64],
        p: &[f64],
        dfdz: &mut [f64],
        dfdp: &mut [f64],
    ) -> bool {
        let sc = p[0];
        dfdz[..144].fill(0.0);
        let mut j = [0.0; 36];
        // each piece: its own block, scaled by `ds/dσ`; the column of `s_c`: `F + (dσ s)'
        // ∂F/∂s` with `∂F/∂s` (the profile's, the history's) by central differences
        for (piece, s, scale, moves) in [(0, sc * u, sc, u), (1, 1.0 - (1.0 - sc) * u, sc - 1.0, u)]
        {
            let zp = &z[6 * piece..6 * piece + 6];
            self.step.rhs_jacobian(s, zp, &[], &mut j, &mut []);
            for r in 0..6 {
                for c in 0..6 {
                    dfdz[(6 * piece + r) * 12 + 6 * piece + c] = scale * j[r * 6 + c];
                }
            }
            let h = 1e-6;
            let (mut f, mut fp, mut fm) = ([0.0; 6], [0.0; 6], [0.0; 6]);
            self.step.rhs(s, zp, &[], &mut f);
            self.step.rhs(s + h, zp, &[], &mut fp);
            self.step.rhs(s - h, zp, &[], &mut fm);
            for r in 0..6 {
                dfdp[6 * piece + r] = f[r] + scale * moves * (fp[r] - fm[r]) / (2.0 * h);
            }
        }
        true
    }
    fn bc(&self, za: &[f64], zb: &[f64], p: &[f64], res: &mut [f64]) {
        self.step.bc(&za[..6], &za[6..], &[], &mut res[..6]);
        for k in 0..4 {
            res[6 + k] = zb[k] - zb[6 + k];
        }
        let (x, y, phi) = (zb[0], zb[1], zb[2]);
        let (h, hp, _) = self.step.track.jet(x);
        let (sp, cp) = phi.sin_cos();
        res[10] = hp * cp - sp;
        match self.hold {
            SideHold::Sliding { ratio } => {
                // (the contact as a sliding tip: its state and the jump of the force)
                let zc = [x, y, phi, zb[3], zb[4] - zb[10], zb[5] - zb[11]];
                let mut r = [0.0; 6];
                self.step.sliding_res(&zc, ratio, &mut r);
                res[11] = r[4];
                res[12] = r[5];
            }
            SideHold::Rolling { a, sign } => {
                res[11] = y - h;
                res[12] = track_arc(self.step.track, x).0 - sign * p[0] - a;
            }
        }
    }
}

/// Solves a step's problem `step` (the tip's condition `tip`; a side's as a [`Split`] on the
/// side solver) from `guess`, or first from a predicted start where there is one (a predicted
/// start that Newton cannot take falls back to `guess`): the solution on the rod's `s`, a side
/// step's own, and (with `remesh`) the residual per interval.
#[allow(clippy::type_complexity)]
fn solve_step(
    solver: &mut StepSolver,
    step: Step<'_>,
    tip: TipBc,
    (guess, predicted): (Guess, Option<Guess>),
    remesh: bool,
) -> Result<(Solution, Option<Solution>, Vec<f64>), Box<BvpError>> {
    if let Some((hold, end)) = SideHold::of(tip) {
        // (the tip beyond a side, free or on the surface too: its conditions are the outer
        // piece's)
        let outer = Step { tip: end, ..step };
        let raw = solver.side.solve(&Split { step: &outer, hold }, &guess)?;
        return Ok((merged(&raw), Some(raw), vec![]));
    }
    let sol = match predicted {
        Some(start) => match solver.armijo.solve(&step, &start) {
            Ok(sol) => sol,
            Err(_) => solver.solve(&step, &guess)?,
        },
        None => solver.solve(&step, &guess)?,
    };
    let rho = if remesh { sol.residuals(&step) } else { vec![] };
    Ok((sol, None, rho))
}

/// A side step's solution on the rod's `s`: the inner piece's nodes, then the outer piece's
/// from the contact to the tip (the contact's node twice, once for each side of the jump of
/// the internal force; the solution's search picks the piece of positive length), slopes and
/// second derivatives scaled by `dσ/ds`.
fn merged(raw: &Solution) -> Solution {
    // (a contact past the tip, `s_c > 1`, which Newton may reach: its outer piece on the rod
    // is the tip alone, its slopes and curvatures left at 0)
    let sc = raw.params[0].min(1.0);
    let over = |v: f64, l: f64| if l != 0.0 { v / l } else { 0.0 };
    let nodes = raw.len();
    let (mut mesh, mut z, mut dz) = (vec![], vec![], vec![]);
    for i in 0..nodes {
        mesh.push(sc * raw.mesh[i]);
        z.extend_from_slice(&raw.node(i)[..6]);
        dz.extend(raw.dz[12 * i..12 * i + 6].iter().map(|d| d / sc));
    }
    for i in (0..nodes).rev() {
        mesh.push(1.0 - (1.0 - sc) * raw.mesh[i]);
        z.extend_from_slice(&raw.node(i)[6..]);
        dz.extend(
            raw.dz[12 * i + 6..12 * i + 12]
                .iter()
                .map(|d| over(*d, sc - 1.0)),
        );
    }
    let dense = match &raw.dense {
        bvp::Dense::QuinticIntervals { d2z } => {
            let (a, b) = (sc * sc, (1.0 - sc) * (1.0 - sc));
            let mut out = vec![];
            for i in 0..nodes - 1 {
                let q = &d2z[24 * i..24 * i + 24];
                out.extend(q[..6].iter().map(|v| v / a));
                out.extend(q[12..18].iter().map(|v| v / a));
            }
            out.extend([0.0; 12]);
            for i in (0..nodes - 1).rev() {
                let q = &d2z[24 * i..24 * i + 24];
                out.extend(q[18..24].iter().map(|v| over(*v, b)));
                out.extend(q[6..12].iter().map(|v| over(*v, b)));
            }
            bvp::Dense::QuinticIntervals { d2z: out }
        }
        _ => bvp::Dense::Hermite,
    };
    Solution {
        n: 6,
        mesh,
        z,
        dz,
        params: vec![],
        status: raw.status,
        stats: raw.stats.clone(),
        dense,
    }
}

/// The contact of a side step's own solution (its forces `gs·(z4, z5)`).
fn side_of(raw: &Solution, gs: f64) -> SideAt {
    let zb = raw.right();
    SideAt {
        s: raw.params[0],
        z: [zb[0], zb[1], zb[2], zb[3]],
        force: [gs * (zb[4] - zb[10]), gs * (zb[5] - zb[11])],
    }
}

/// Where the foot is at a step's end: its place and the turn `θ_w` of its support (clockwise,
/// as the static whisk's foot angle: the clamp holds the foot's slope at `π/2 − θ_w`, a
/// compliant support at `π/2 − θ_w + θ` with `θ` its own rotation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Foot {
    /// The foot's place `(x(0), y(0))`.
    pub place: [f64; 2],
    /// The support's turn `θ_w`.
    pub turn: f64,
}

impl Foot {
    /// The foot at `place`, its support not turned.
    pub fn at(place: [f64; 2]) -> Foot {
        Foot { place, turn: 0.0 }
    }
}

/// Settings of the Rothe steps.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Settings {
    /// Intervals of the history grid (even).
    pub grid: usize,
    /// Collocation tolerance.
    pub tol: f64,
    /// Collocation scheme.
    pub scheme: bvp::Scheme,
    /// The foot's damper `c`.
    pub damping: f64,
    /// The rod's internal (Kelvin–Voigt) damping `γ_i`: `b m = (κ − κ0) + γ_i κ_t`.
    pub internal_damping: f64,
    /// External viscous damping `γ_e`: a distributed force `−γ_e μ r_t`.
    pub external_damping: f64,
    /// The rotary inertia's radius of gyration at the foot `g0` (module `inertia`: the rotary
    /// inertia per length `j = g0²/b`; 0: none).
    pub rotary_inertia: f64,
    /// Steps of any length, short ones too (`true`, `dynamics::drag`, whose events shorten
    /// steps), or as `dynamics::free` (`false`). With `true`: (1) `r̂ = rⁿ + (Δt vⁿ + Δt²/4 aⁿ)`
    /// with `rⁿ` the last step's solution itself and only the bracket interpolated on the grid
    /// (its interpolation error enters the acceleration with `4/Δt` and 1, not `4/Δt²`);
    /// (2) the unknowns of the internal force are `H = G/(4/Δt²)`, so `H' = μ(r − r̂)` and
    /// `m' = (4/Δt²) H × e`: the collocation's residual control scales each equation by its own
    /// size, and with `G` itself an error `δr` of the positions (rounding, at the least) makes a
    /// residual `4/Δt² δr` in `G' = μ r_tt` that a short step cannot meet (Δt = 1.3e-3 at tol
    /// 1e-10 ran into the mesh limit of 10⁴ nodes), while with `H` it is `δr`.
    pub short_steps: bool,
    /// Start each step's Newton iteration from the last two solutions extrapolated linearly in
    /// time when both have the same mesh (at its nodes, values and slopes): `2zⁿ − zⁿ⁻¹` when
    /// the step tried is as long as the last one (`dynamics::free`'s fixed steps), else
    /// `zⁿ + (τ/h)(zⁿ − zⁿ⁻¹)` (`τ` the step tried, `h` the last one: adaptive steps) in the
    /// shape `(x, y, φ)` only, `m` and `G` taken from the last solution (they carry the
    /// rule's mode that alternates from step to step, which the extrapolation would amplify:
    /// measured, extrapolating them too took more Newton iterations than no extrapolation at
    /// `time_tol` 1e-10, docs/performance.md); else from the last solution. The start of
    /// Newton only: the step solves the same equations to the same tolerance (one Newton
    /// iteration per step where the last solution needed two). `dynamics::free` only: `drag`
    /// starts from the last solution (with adaptive steps the extrapolation saved 11 to 16 %
    /// of its Newton iterations and no CPU time that could be measured; not adopted).
    pub predict: bool,
    /// Each step starts from a coarser mesh than the last solution's where that solution's
    /// residual allows ([`coarser`]: never below the history's grid; `dynamics::drag`), or
    /// from the last solution's mesh (`false`, `dynamics::free`). Why: the collocation refines a
    /// step's mesh where the residual exceeds `tol` but does not coarsen it (coarsening is off,
    /// [`Rothe::at_rest`]), so the nodes added for one step (an event's short steps, the rod's
    /// shape at one time) stayed for the rest of a drag: the paper's rod's ten-slip drag (dt
    /// 0.01, grid 100, tol 1e-8) grew from 101 nodes to 220, and the LU factorization of every
    /// Newton iteration costs in proportion (docs/performance.md, "The dynamic drag against
    /// PyElastica").
    pub remesh: bool,
    /// The energy–momentum step instead of Newmark's rule (`dynamics::free` only; fixed steps):
    /// over a step of length `τ` the internal force and
    /// moment are the step's means `Ḡ`, `m̄`, the balance of momentum `μ (vⁿ⁺¹ − vⁿ)/τ = Ḡ'`
    /// with `(rⁿ⁺¹ − rⁿ)/τ = (vⁿ + vⁿ⁺¹)/2`, the curvature's mean `(φⁿ' + φⁿ⁺¹')/2 = κ0 + b m̄`
    /// and the moment's balance on the chord of the slopes, `m̄' = −sinc(Δφ/2) e⊥(φ̄)·Ḡ`
    /// (`Δφ = φⁿ⁺¹ − φⁿ`, `φ̄` their mean): `e(φⁿ⁺¹) − e(φⁿ) = 2 sin(Δφ/2) e⊥(φ̄)`, so the work of
    /// `Ḡ` on the change of the tangents is the work of `m̄` on the change of the curvature, and
    /// the step keeps `½∫μ|v|² + ½∫ b m²` exactly (up to the collocation's error) whatever the
    /// amplitude, where the trapezoidal rule's energy grows at large ones (docs/model.md, "The
    /// energy of a large oscillation"). Needs [`Settings::short_steps`] (`rⁿ`, `φⁿ` and `φⁿ'`
    /// from the last step's solution itself).
    pub energy_momentum: bool,
}

#[cfg(test)]
impl Settings {
    /// The plain steps the crate's tests build a `Rothe` with: Lobatto6 on `grid` intervals at
    /// `tol`, Newmark's rule, no damper, damping or rotary inertia, the forces unscaled, each
    /// step started from the last solution on its own mesh.
    pub fn plain(grid: usize, tol: f64) -> Settings {
        Settings {
            grid,
            tol,
            scheme: bvp::Scheme::Lobatto6,
            damping: 0.0,
            internal_damping: 0.0,
            external_damping: 0.0,
            rotary_inertia: 0.0,
            short_steps: false,
            predict: false,
            remesh: false,
            energy_momentum: false,
        }
    }
}

/// A step solved but not taken.
#[derive(Clone)]
pub(crate) struct Trial {
    /// The step's length.
    pub tau: f64,
    /// The rule's `ca/Δt²` of the step (`a = k_acc (r − r̂)`: 4/Δt² by the trapezoidal rule,
    /// 2/Δt² the energy–momentum step's mean, 1/Δt² backward Euler).
    k_acc: f64,
    /// Solved by backward Euler ([`Rothe::euler_steps`]), not the trapezoidal rule.
    pub euler: bool,
    /// The support's turn at the step's end.
    turn: f64,
    /// `G = gs·(z[4], z[5])` in `sol`.
    gs: f64,
    /// The solution at the step's end.
    pub sol: Solution,
    /// `r̂` of the step on the grid (x, y and their s-derivatives), and `φ̂`.
    hat: [Vec<f64>; 5],
    /// Positions (x, y, cos φ, sin φ) and `φ` on the grid at the step's end.
    next: [Vec<f64>; 5],
    /// `m` on the grid at the step's end.
    m: Vec<f64>,
    /// `κ = φ'` on the grid at the step's end.
    kappa: Vec<f64>,
    /// With [`Settings::remesh`]: the step's collocation residual per mesh interval of `sol`
    /// (else empty).
    rho: Vec<f64>,
    /// A side step's own solution on its two pieces ([`Split`]; `sol` is it on the rod's `s`).
    split: Option<Solution>,
    /// A side step's contact.
    pub side: Option<SideAt>,
}

impl Trial {
    /// The contact's force on the rod and its x at the step's end: a side's, else the tip's
    /// `G(1)` at its end's x.
    pub fn contact(&self) -> ([f64; 2], f64) {
        match &self.side {
            Some(c) => (c.force, c.z[0]),
            None => (self.force(1), self.sol.right()[0]),
        }
    }

    /// The internal force `G` at the foot (`end` 0) or the tip (`end` 1) of the trial.
    pub fn force(&self, end: usize) -> [f64; 2] {
        let z = if end == 0 {
            self.sol.left()
        } else {
            self.sol.right()
        };
        [self.gs * z[4], self.gs * z[5]]
    }
}

/// The rod's state in time: the last solution and the history on the grid.
#[derive(Clone)]
pub(crate) struct Rothe<'r> {
    profile: General,
    stiffness: &'r Stiffness,
    cs: f64,
    damping: f64,
    short_steps: bool,
    /// [`Settings::predict`], and the solution before `sol` with the length of the step
    /// between them and its forces' scale `gs`.
    predict: bool,
    previous: Option<(f64, f64, Solution)>,
    /// [`Settings::remesh`], the collocation's `tol`, and the nodes of `sol` the next step
    /// starts from (`None`: all of them).
    remesh: bool,
    tol: f64,
    start_nodes: Option<Vec<usize>>,
    ng: usize,
    grid: Vec<f64>,
    mu: Vec<f64>,
    bvec: Vec<f64>,
    /// `κ0` on the grid.
    k0vec: Vec<f64>,
    /// `γ_i`, `γ_e`.
    gi: f64,
    ge: f64,
    solver: StepSolver,
    /// The solution at the present time.
    pub sol: Solution,
    /// Per component (x, y): position and its s-derivative (`e = (cos φ, sin φ)`); velocity and
    /// acceleration likewise (the recursions are linear, so the derivatives follow the same
    /// rule); and the slope `φ`, its rate and acceleration (rotary inertia).
    pos: [Vec<f64>; 5],
    vel: [Vec<f64>; 5],
    acc: [Vec<f64>; 5],
    /// `g0²` of [`Settings::rotary_inertia`].
    g0sq: f64,
    /// The accelerations `(a_x, a_y)` on the grid before the last step and that step's length,
    /// while the history has not been changed since (the local error estimate,
    /// [`Rothe::local_error`]).
    acc_before: Option<([Vec<f64>; 2], f64)>,
    m: Vec<f64>,
    /// Curvature `κ = φ'` and its rate on the grid.
    kappa: Vec<f64>,
    kappa_t: Vec<f64>,
    /// `G = gs·(z[4], z[5])` in `sol`.
    gs: f64,
    /// Foot rotation and its rate.
    pub theta: f64,
    theta_t: f64,
    /// Energy the foot's damper took so far.
    pub dissipated: f64,
    /// Energy the internal and the external damping took so far.
    internal_dissipated: f64,
    external_dissipated: f64,
    /// The forces at the foot and the tip (`G(0)`, `G(1)`) now, where a [`Rothe::restart`]
    /// made them differ from `sol`'s (until the next step is taken).
    after: Option<[[f64; 2]; 2]>,
    /// Work done.
    pub stats: DynStats,
    /// Steps still to take by backward Euler instead of the trapezoidal rule (default 0).
    ///
    /// Why: where the tip touches down the Euler–Bernoulli rod's contact force is singular,
    /// like `t^(-1/2)` (the rod next to the tip, still moving into the surface, is stopped by
    /// it), and the trapezoidal rule, which does not damp, answers it with end forces of
    /// alternating sign (−0.68 then −2.9, spurious lift-offs within 1e-5: docs/model.md,
    /// "Flight and touchdown"). Backward Euler (`vⁿ⁺¹ = (rⁿ⁺¹ − rⁿ)/Δt`,
    /// `aⁿ⁺¹ = (vⁿ⁺¹ − vⁿ)/Δt`) damps what its step cannot resolve (L-stable), at the cost of
    /// first order and of an energy loss of its own (`½∫μ|Δv|²` and more a step), which the
    /// drag books with the impact.
    pub euler_steps: usize,
    /// The kinetic friction's table `(|v|, μk)` of [`TipBc::SlidingRate`] (empty: not used).
    pub friction_table: Vec<[f64; 2]>,
    /// The track of [`TipBc::Sliding`] and [`TipBc::SlidingRate`] (default: the line `y = 0`).
    pub track: Track,
    /// The surface's friction texture of [`TipBc::SlidingOn`] (`None`: not used).
    pub texture: Option<Arc<Texture>>,
    /// The tip's radius: a rigid disk at the rod's end, its centre on [`Rothe::track`] (the
    /// surface line lowered by `r`), `m(1) = r·T` while it touches (default 0: a point tip).
    pub tip_radius: f64,
    /// The disk's moment condition `m(1) = r·(a·T + K)` of the next trial: `T` the step's end
    /// tangential force, `a`, `K` its weight and the known part of a combination of it with
    /// the last two steps' that cancels the rule's alternating mode (default `(1, 0)`: the end
    /// force itself).
    pub disk_held: (f64, f64),
    /// [`Settings::energy_momentum`].
    emm: bool,
    /// The last step's own solution where it was a side step ([`Split`]).
    split: Option<Solution>,
    /// The side contact now (the last step's, a side step).
    pub side: Option<SideAt>,
    /// Where a side that has just formed is first sought (`s_c` of the first side step's
    /// start; default 1).
    pub side_guess: f64,
}

/// The rest shape's guess on the grid (`m ≡ 0`, `G ≡ 0`): the midpoint rule on a fine subgrid
/// (the guess only; collocation makes it exact).
pub(crate) fn rest_guess(profile: &General, grid: &[f64]) -> Guess {
    let ng = grid.len() - 1;
    let mut rest = Guess::from_fn(6, grid.to_vec(), vec![], |_, z| z.fill(0.0));
    let (mut x, mut y, mut phi) = (0.0, 0.0, FRAC_PI_2);
    let h = 1.0 / ng as f64;
    let sub = 20;
    for (zi, &s0) in rest.z.chunks_mut(6).zip(grid) {
        zi[0] = x;
        zi[1] = y;
        zi[2] = phi;
        for k in 0..sub {
            let s = s0 + (k as f64 + 0.5) * h / sub as f64;
            let pm = phi + 0.5 * profile.k0(s) * h / sub as f64;
            x += pm.cos() * h / sub as f64;
            y += pm.sin() * h / sub as f64;
            phi += profile.k0(s) * h / sub as f64;
        }
    }
    rest
}

/// A step's collocation, Newton damped by Armijo's rule on the residual, and Deuflhard's
/// affine-invariant damping where that fails.
///
/// Why the second: a stuck tip on a very compliant support (`c_s` ≳ 20) makes the rod a nearly
/// straight strut between the foot and the tip, whose axial force the rod's inertia lets jump
/// within a step (from N = 0.02 to 0.12 for a foot moved by 3e-10 at `c_s` = 50). The Newton
/// step is then right in direction but the product of the force's and the angle's changes in
/// `m' = G × e` is 200 times the residual it removes, so the residual norm's line search accepts
/// only 1 % of a step at a time, stalls, and refinement cannot help (the mesh grows to its
/// limit). The affine-invariant test judges a step by the Newton correction it leaves, which
/// does not see the rows' scales, and converges in a few steps. It is tried only after the
/// first has failed, so every step the first solves is solved as before, bit for bit.
#[derive(Clone)]
struct StepSolver {
    armijo: Collocation,
    affine: Collocation,
    /// A side step's ([`Split`]): no homotopy, at most [`SIDE_MAX_NODES`] nodes. Why: a side
    /// step fails where its contact would pass the tip within it (no solution), and the
    /// default's homotopy and refinement to 10⁴ nodes took 8 s over that one failure (the
    /// corrugation 0.02 sin(2πx/0.2) at v 0.05, dt 0.02, whose drag then took the step again
    /// shorter); the drag shortens such a step.
    side: Collocation,
}

/// The largest mesh of a side step's collocation ([`StepSolver::side`]; side steps at the
/// program's defaults end on up to 2583 nodes).
const SIDE_MAX_NODES: usize = 4000;

impl StepSolver {
    fn new(opts: CollocationOptions) -> Result<Self, VibrissaError> {
        let options = |e| VibrissaError::solver("dynamics options", e);
        let affine = CollocationOptions {
            newton: bvp::NewtonOptions {
                damping: bvp::Damping::AffineInvariant,
                ..opts.newton.clone()
            },
            ..opts.clone()
        };
        let side = CollocationOptions {
            homotopy: false,
            max_nodes: SIDE_MAX_NODES,
            ..opts.clone()
        };
        Ok(StepSolver {
            armijo: Collocation::new(opts).map_err(options)?,
            affine: Collocation::new(affine).map_err(options)?,
            side: Collocation::new(side).map_err(options)?,
        })
    }

    /// Solves by the first; where it fails, by the second from the same guess; where both fail,
    /// the first one's error.
    fn solve<P: Bvp + ?Sized>(
        &mut self,
        problem: &P,
        guess: &Guess,
    ) -> Result<Solution, Box<BvpError>> {
        self.armijo.solve(problem, guess).or_else(|first| {
            self.affine
                .solve(problem, guess)
                .map_err(|_| Box::new(first))
        })
    }
}

impl<'r> Rothe<'r> {
    /// The uniform grid of `settings.grid` intervals.
    pub fn grid_of(settings: &Settings) -> Vec<f64> {
        let ng = settings.grid;
        (0..=ng).map(|i| i as f64 / ng as f64).collect()
    }

    /// The state at rest in the static equilibrium with the foot at `foot` and the tip's
    /// condition `tip` (solved once, from `guess`; no inertia).
    pub fn at_rest(
        rod: &'r Rod,
        settings: &Settings,
        guess: &Guess,
        foot: [f64; 2],
        tip: TipBc,
    ) -> Result<Self, VibrissaError> {
        let profile = rod.profile(1.0);
        let stiffness = rod.stiffness();
        let ng = settings.grid;
        let grid = Self::grid_of(settings);
        let mu: Vec<f64> = grid.iter().map(|&s| mass_density(stiffness, s)).collect();
        let bvec: Vec<f64> = grid.iter().map(|&s| profile.b(s)).collect();
        let k0vec: Vec<f64> = grid.iter().map(|&s| profile.k0(s)).collect();
        let mut solver = StepSolver::new(CollocationOptions {
            tol: settings.tol,
            scheme: settings.scheme,
            coarsen: false,
            // Residual control, not bvp's default (`Confirmed`): the guard raises a false alarm
            // at nearly every step (2e-9 to 8e-9 at tol 1e-10; F of the internal force is
            // `μ·4/Δt²·(y − ŷ)` with y ≈ 1, whose rounding its differences amplify), and the
            // alarms the reference confirms (110 of 294 in this module's tests) are Newton's
            // error in the internal force (δy ≈ 3e-12 at a scaled residual of 5e-12, times
            // μ·4/Δt² = 3100), which a re-solve on the same mesh removes; with them the tests
            // pass but take 4× the CPU time. The steps' accuracy is checked against closed
            // forms in the tests of `dynamics` and `dyndrag`.
            control: ErrorControl::Residual,
            ..CollocationOptions::default()
        })?;
        let zeros = vec![0.0; ng + 1];
        let flat = FLAT;
        let statics = Step {
            profile: &profile,
            stiffness,
            k_acc: 0.0,
            gs: 1.0,
            kv: None,
            rot: None,
            base: None,
            hat_x: &zeros,
            hat_y: &zeros,
            hat_xs: &zeros,
            hat_ys: &zeros,
            compliance: rod.support_compliance(),
            damp_k: 0.0,
            damp_0: 0.0,
            moment: 0.0,
            foot: Foot::at(foot),
            tip,
            track: &flat,
            table: &[],
            tip_then: [0.0; 6],
            two_tau: 0.0,
            then_rate: 1.0,
            texture: None,
            radius: 0.0,
            held: (1.0, 0.0),
            emm: false,
            theta_then: 0.0,
            emm_kv: 0.0,
        };
        let sol = solver
            .solve(&statics, guess)
            .map_err(|e| VibrissaError::solver("the starting equilibrium", *e))?;
        let zero = || vec![0.0; ng + 1];
        let mut me = Rothe {
            cs: rod.support_compliance(),
            damping: settings.damping,
            short_steps: settings.short_steps,
            predict: settings.predict,
            previous: None,
            remesh: settings.remesh,
            tol: settings.tol,
            start_nodes: None,
            gs: 1.0,
            ng,
            mu,
            bvec,
            k0vec,
            gi: settings.internal_damping,
            ge: settings.external_damping,
            solver,
            theta: sol.left()[2] - FRAC_PI_2,
            sol,
            pos: [zero(), zero(), zero(), zero(), zero()],
            vel: [zero(), zero(), zero(), zero(), zero()],
            acc: [zero(), zero(), zero(), zero(), zero()],
            g0sq: settings.rotary_inertia * settings.rotary_inertia,
            acc_before: None,
            m: zero(),
            kappa: zero(),
            kappa_t: zero(),
            theta_t: 0.0,
            dissipated: 0.0,
            internal_dissipated: 0.0,
            external_dissipated: 0.0,
            after: None,
            stats: DynStats::default(),
            euler_steps: 0,
            friction_table: vec![],
            texture: None,
            tip_radius: 0.0,
            disk_held: (1.0, 0.0),
            emm: settings.energy_momentum,
            split: None,
            side: None,
            side_guess: 1.0,
            track: FLAT,
            grid,
            profile,
            stiffness,
        };
        let (mut pos, mut m) = (std::mem::take(&mut me.pos), std::mem::take(&mut me.m));
        me.sample_grid(&me.sol, &mut pos, &mut m);
        // at rest: κ = κ0 + b m, κ_t = 0
        me.kappa = (0..=ng).map(|i| me.k0vec[i] + me.bvec[i] * m[i]).collect();
        (me.pos, me.m) = (pos, m);
        Ok(me)
    }

    /// Positions (x, y, cos φ, sin φ) and `m` of `sol` on the grid.
    fn sample_grid(&self, sol: &Solution, pos: &mut [Vec<f64>; 5], m: &mut [f64]) {
        let mut out = [0.0; 6];
        for (i, &s) in self.grid.iter().enumerate() {
            sol.eval(s, &mut out);
            let (sp, cp) = out[2].sin_cos();
            pos[0][i] = out[0];
            pos[1][i] = out[1];
            pos[2][i] = cp;
            pos[3][i] = sp;
            pos[4][i] = out[2];
            m[i] = out[3];
        }
    }

    /// Sets the velocity field to `v0(s) = (vx, vy)` (its s-derivative by fourth-order central
    /// differences, one-sided near the ends).
    pub fn set_velocity(&mut self, v0: &dyn Fn(f64) -> [f64; 2]) -> Result<(), VibrissaError> {
        let hd = 1e-3;
        for (i, &s) in self.grid.iter().enumerate() {
            let v = v0(s);
            let sc = s.clamp(2.0 * hd, 1.0 - 2.0 * hd);
            let (p1, m1, p2, m2) = (
                v0(sc + hd),
                v0(sc - hd),
                v0(sc + 2.0 * hd),
                v0(sc - 2.0 * hd),
            );
            for c in 0..2 {
                self.vel[c][i] = v[c];
                let d = (8.0 * (p1[c] - m1[c]) - (p2[c] - m2[c])) / (12.0 * hd);
                // (s near an end: the derivative at the clamped point, corrected to first order)
                let d2 = (p1[c] - 2.0 * v0(sc)[c] + m1[c]) / (hd * hd);
                self.vel[2 + c][i] = d + d2 * (s - sc);
            }
            if !(v[0].is_finite() && v[1].is_finite()) {
                return Err(VibrissaError::range("v0", v[0] + v[1], "finite"));
            }
            // `φ_t = e⊥·(r_s)_t` (`r_s = e`)
            self.vel[4][i] = -self.pos[3][i] * self.vel[2][i] + self.pos[2][i] * self.vel[3][i];
        }
        if self.ge > 0.0 {
            // the damping force's share of the start's acceleration, `a⁰ = −γ_e v0` (consistent
            // for the linearized rod at rest: no elastic force, so the rest of `a⁰` is zero)
            for q in 0..5 {
                for i in 0..=self.ng {
                    self.acc[q][i] = -self.ge * self.vel[q][i];
                }
            }
        }
        if self.gi > 0.0 {
            // the curvature's rate of the start, `κ_t = e⊥·v0'' − κ e·v0'` (the history of the
            // Kelvin–Voigt moment: an inconsistent one would stay as an undamped alternation)
            for (i, &s) in self.grid.iter().enumerate() {
                let (cp, sp) = (self.pos[2][i], self.pos[3][i]);
                let vss = second_derivative(v0, s);
                let along = cp * self.vel[2][i] + sp * self.vel[3][i];
                self.kappa_t[i] = -sp * vss[0] + cp * vss[1] - self.kappa[i] * along;
            }
        }
        Ok(())
    }

    /// The tip's x velocity and acceleration set to zero at the grid's last node (a tip that
    /// sticks: its velocity is zero there to the event's tolerance, and its acceleration jumps
    /// to zero; the rest of the rod's acceleration is continuous at the moment it sticks).
    pub fn hold_tip_x(&mut self) {
        self.vel[0][self.ng] = 0.0;
        self.acc[0][self.ng] = 0.0;
        self.acc_before = None;
    }

    /// The tip's y velocity and acceleration set to zero at the grid's last node (a plastic
    /// impact on the surface `y = η`: see `dynamics::drag`).
    pub fn hold_tip_y(&mut self) {
        self.vel[1][self.ng] = 0.0;
        self.acc[1][self.ng] = 0.0;
        self.acc_before = None;
    }

    /// The tip's velocity and acceleration along the unit normal `n` removed at the grid's last
    /// node (a plastic impact on a track of that normal there; [`Rothe::hold_tip_y`] on a flat
    /// one).
    pub fn hold_tip_normal(&mut self, n: [f64; 2]) {
        let i = self.ng;
        for q in [&mut self.vel, &mut self.acc] {
            let along = q[0][i] * n[0] + q[1][i] * n[1];
            q[0][i] -= along * n[0];
            q[1][i] -= along * n[1];
        }
        self.acc_before = None;
    }

    /// Solves the step of length `tau` with the foot at `foot`, the tip's condition `tip` and the
    /// moment `moment` on the support; the state is left as it is.
    pub fn trial(
        &mut self,
        tau: f64,
        foot: Foot,
        tip: TipBc,
        moment: f64,
    ) -> Result<Trial, Box<BvpError>> {
        let ng = self.ng;
        let zero = || vec![0.0; ng + 1];
        let mut hat = [zero(), zero(), zero(), zero(), zero()];
        let mut bracket = [zero(), zero(), zero(), zero(), zero()];
        // the rule's coefficients: `r̂ = rⁿ + Δt vⁿ + ch Δt² aⁿ`, `a = (ca/Δt²)(r − r̂)`, and a
        // rate `q_t = (rv/Δt)(q − qⁿ) − sv q_tⁿ` (trapezoidal: ¼, 4, 2, 1; backward Euler: 0, 1,
        // 1, 0)
        let euler = self.euler_steps > 0;
        // (the energy–momentum step: `Ḡ' = μ (2/Δt²)(r − rⁿ − Δt vⁿ)`, the mean force)
        let (ch, ca, rv, sv) = if euler {
            (0.0, 1.0, 1.0, 0.0)
        } else if self.emm {
            (0.0, 2.0, 2.0, 1.0)
        } else {
            (0.25, 4.0, 2.0, 1.0)
        };
        for (q, (h, b)) in hat.iter_mut().zip(bracket.iter_mut()).enumerate() {
            for (i, (hi, bi)) in h.iter_mut().zip(b.iter_mut()).enumerate() {
                *hi = self.pos[q][i] + tau * self.vel[q][i] + ch * tau * tau * self.acc[q][i];
                *bi = tau * self.vel[q][i] + ch * tau * tau * self.acc[q][i];
            }
        }
        let k_acc = ca / (tau * tau);
        let gs = if self.short_steps { k_acc } else { 1.0 };
        let (base, mut interp_of) = if self.short_steps {
            (Some(&self.sol), bracket)
        } else {
            (None, hat.clone())
        };
        // external damping: `r_tt + γ_e r_t = k (r − r̂')` with `k = 4/Δt² + 2γ_e/Δt` and
        // `r̂' = (4/Δt² r̂ + γ_e (2/Δt rⁿ + vⁿ))/k` (`r_t` by the trapezoidal rule; by backward
        // Euler `k = 1/Δt² + γ_e/Δt`, `r̂' = (r̂/Δt² + γ_e rⁿ/Δt)/k`)
        // (the energy–momentum step: the dampers at the step's mean rates, `(r − rⁿ)/Δt`)
        let rates = if self.emm && !euler {
            (1.0, 0.0)
        } else {
            (rv, sv)
        };
        let k_step = self.damped_history(tau, k_acc, rates, &mut interp_of);
        // Kelvin–Voigt: `κ_t = 2/Δt (κ − κⁿ) − κ_tⁿ` in `κ − κ0 + γ_i κ_t = b m`
        let kv_c = 1.0 + rv * self.gi / tau;
        let kv_q: Vec<f64> = if self.gi > 0.0 {
            (0..=ng)
                .map(|i| self.gi * (rv / tau * self.kappa[i] + sv * self.kappa_t[i]))
                .collect()
        } else {
            vec![]
        };
        let c = self.damping;
        let step = Step {
            profile: &self.profile,
            stiffness: self.stiffness,
            k_acc: k_step,
            gs,
            kv: (self.gi > 0.0 && !self.emm).then_some((kv_c, kv_q.as_slice())),
            rot: (self.g0sq > 0.0).then_some((self.g0sq * k_acc, interp_of[4].as_slice())),
            base,
            hat_x: &interp_of[0],
            hat_y: &interp_of[1],
            hat_xs: &interp_of[2],
            hat_ys: &interp_of[3],
            compliance: self.cs,
            // (the foot's rate as the external damping's: the energy–momentum step's mean
            // `(θⁿ⁺¹ − θⁿ)/Δt`)
            damp_k: c * rates.0 / tau,
            damp_0: c * (-rates.0 / tau * self.theta - rates.1 * self.theta_t),
            moment,
            foot,
            tip,
            track: &self.track,
            table: &self.friction_table,
            tip_then: [
                self.pos[0][ng],
                self.vel[0][ng],
                self.pos[1][ng],
                self.vel[1][ng],
                self.pos[4][ng],
                self.vel[4][ng],
            ],
            two_tau: rv / tau,
            then_rate: sv,
            texture: self.texture.as_deref(),
            radius: self.tip_radius,
            held: self.disk_held,
            emm: self.emm,
            theta_then: self.theta,
            emm_kv: if self.emm { self.gi / tau } else { 0.0 },
        };
        let side = SideHold::of(tip).is_some();
        let mut guess = if side {
            self.split_start(matches!(tip, TipBc::SideAndTip { .. }))
        } else {
            self.start()
        };
        scale_forces(&mut guess, self.gs / gs);
        let predicted = if side {
            None
        } else {
            self.predicted(tau, &guess)
        };
        let (sol, split, rho) =
            solve_step(&mut self.solver, step, tip, (guess, predicted), self.remesh)?;
        self.stats.newton_iterations += sol.stats.newton_iters;
        // (a side step's collocation mesh is its own: the merged one has each node twice)
        let nodes = split.as_ref().map_or(sol.len(), Solution::len);
        self.stats.max_nodes = self.stats.max_nodes.max(nodes);
        let side = split.as_ref().map(|raw| side_of(raw, gs));
        let mut next = [zero(), zero(), zero(), zero(), zero()];
        let mut m = zero();
        self.sample_grid(&sol, &mut next, &mut m);
        let kappa = self.end_curvature(&sol, &mut m, (kv_c, &kv_q), euler);
        Ok(Trial {
            tau,
            k_acc,
            euler,
            turn: foot.turn,
            gs,
            sol,
            hat,
            next,
            m,
            kappa,
            rho,
            split,
            side,
        })
    }

    /// The start of a side step's collocation ([`Split`]): the last side step's solution, or,
    /// where the side has just formed, the whole rod's last solution cut at
    /// [`Rothe::side_guess`] (the outer piece's internal force less the tip's, which the
    /// contact now carries; with the tip on the surface as well, `keep_tip`, as it is: the tip
    /// goes on carrying it, the new contact none yet).
    fn split_start(&self, keep_tip: bool) -> Guess {
        if let Some(raw) = &self.split {
            return Guess::from(raw);
        }
        let sc = self.side_guess;
        let tip = self.sol.right();
        let (g4, g5) = if keep_tip {
            (0.0, 0.0)
        } else {
            (tip[4], tip[5])
        };
        let mut mesh: Vec<f64> = self.sol.mesh.clone();
        mesh.dedup();
        let mut z = Vec::with_capacity(12 * mesh.len());
        let (mut inner, mut outer) = ([0.0; 6], [0.0; 6]);
        for &u in &mesh {
            self.sol.eval(sc * u, &mut inner);
            self.sol.eval(1.0 - (1.0 - sc) * u, &mut outer);
            outer[4] -= g4;
            outer[5] -= g5;
            z.extend_from_slice(&inner);
            z.extend_from_slice(&outer);
        }
        Guess {
            n: 12,
            mesh,
            z,
            dz: None,
            params: vec![sc],
        }
    }

    /// External damping in the step's history (`interp_of`, the positions' four rows): the
    /// force `−γ_e μ r_t` with `r_t = (rv/Δt)(r − rⁿ) − sv vⁿ` (`rates = (rv, sv)`) folded into
    /// `k (r − r̂')`; returns `k` (`k_acc` without damping).
    fn damped_history(
        &self,
        tau: f64,
        k_acc: f64,
        (rv, sv): (f64, f64),
        interp_of: &mut [Vec<f64>; 5],
    ) -> f64 {
        if self.ge <= 0.0 {
            return k_acc;
        }
        let k = k_acc + rv * self.ge / tau;
        // (the positions only: the damping force has no moment on the rotation)
        for (q, h) in interp_of.iter_mut().enumerate().take(4) {
            for (i, hi) in h.iter_mut().enumerate() {
                let from = if self.short_steps {
                    self.ge * sv * self.vel[q][i]
                } else {
                    self.ge * (rv / tau * self.pos[q][i] + sv * self.vel[q][i])
                };
                *hi = (k_acc * *hi + from) / k;
            }
        }
        k
    }

    /// The curvature `κ` on the grid at the end of the step solved as `sol` (`m` its moment
    /// there: with the energy–momentum step the elastic moment `(κ − κ0)/b` replaces the mean
    /// the solution holds). Newmark: `κ = κ0 + b m`, with Kelvin–Voigt damping
    /// `(κ0 + b m + q)/c` (`kv = (c, q)`).
    fn end_curvature(
        &self,
        sol: &Solution,
        m: &mut [f64],
        (kv_c, kv_q): (f64, &[f64]),
        euler: bool,
    ) -> Vec<f64> {
        if self.emm && !euler {
            // the step's unknown is the mean moment: the new curvature is the solution's own
            // `φ'` (exact at the mesh's nodes, the grid's among them)
            let mut d = [0.0; 6];
            return (0..=self.ng)
                .map(|i| {
                    sol.eval_derivative(self.grid[i], &mut d);
                    m[i] = (d[2] - self.k0vec[i]) / self.bvec[i];
                    d[2]
                })
                .collect();
        }
        (0..=self.ng)
            .map(|i| {
                let elastic = self.k0vec[i] + self.bvec[i] * m[i];
                if self.gi > 0.0 {
                    (elastic + kv_q[i]) / kv_c
                } else {
                    elastic
                }
            })
            .collect()
    }

    /// The start of the next step's collocation: the last solution on its mesh, or (with
    /// [`Settings::remesh`]) on the nodes [`coarser`] kept of it (the solution's own values and
    /// slopes there); after a side step's solution ([`merged`], each node twice), on the
    /// history grid's nodes.
    ///
    /// Why the grid's nodes after a side: the merged mesh has none of them (its pieces' nodes
    /// are `s_c σ` and `1 − (1 − s_c) σ`) and half its nodes crowd the outer piece, a few
    /// thousandths long where the side's contact reached the tip; the step's history is
    /// interpolated on the grid with kinks at its nodes ([`coarser`]). Measured with
    /// Kelvin–Voigt damping (whose history `q` is a cubic Lagrange interpolant, its slope
    /// jumping at the grid's nodes): over 0.02 sin(2πx/0.2), γ_i 0.01, v 0.05, the tip's first
    /// step after the side handed the contact over (on 681 nodes, 678 of them in the last
    /// thousandth) stalled Newton on every doubled mesh to 5441 nodes and at every shorter
    /// step (a solver error after 60 s); from the grid's nodes it solves and the drag reaches
    /// its end.
    fn start(&self) -> Guess {
        if self.sol.mesh.windows(2).any(|w| w[0] == w[1]) {
            return self.on_grid(&self.sol);
        }
        let Some(keep) = &self.start_nodes else {
            return Guess::from(&self.sol);
        };
        let n = self.sol.n;
        let pick = |v: &[f64]| -> Vec<f64> {
            keep.iter()
                .flat_map(|&i| v[i * n..(i + 1) * n].iter().copied())
                .collect()
        };
        Guess {
            n,
            mesh: keep.iter().map(|&i| self.sol.mesh[i]).collect(),
            z: pick(&self.sol.z),
            dz: Some(pick(&self.sol.dz)),
            params: self.sol.params.clone(),
        }
    }

    /// `sol` on the history grid's nodes: its values and slopes there.
    fn on_grid(&self, sol: &Solution) -> Guess {
        let (n, ng) = (sol.n, self.ng);
        let mesh: Vec<f64> = (0..=ng).map(|i| i as f64 / ng as f64).collect();
        let (mut z, mut dz) = (vec![0.0; n * (ng + 1)], vec![0.0; n * (ng + 1)]);
        for (i, &u) in mesh.iter().enumerate() {
            sol.eval(u, &mut z[i * n..(i + 1) * n]);
            sol.eval_derivative(u, &mut dz[i * n..(i + 1) * n]);
        }
        Guess {
            n,
            mesh,
            z,
            dz: Some(dz),
            params: sol.params.clone(),
        }
    }

    /// The start of a step of length `tau` extrapolated from the last two solutions (see
    /// [`Settings::predict`]) from `guess` (the last solution, forces scaled for the step), if
    /// it and the solution before have the same mesh: `2zⁿ − zⁿ⁻¹` if the last step was as long and the two
    /// solutions' forces have the same scale (the fixed steps' expression, kept as it was),
    /// else `zⁿ + (τ/h)(zⁿ − zⁿ⁻¹)` in the shape `(x, y, φ)` with `m` and `G` the last
    /// solution's.
    fn predicted(&self, tau: f64, guess: &Guess) -> Option<Guess> {
        let (last, prev_gs, prev) = self.previous.as_ref()?;
        // (`zⁿ` and `zⁿ⁻¹` on the same nodes; the unknowns per node are the same)
        if prev.mesh != guess.mesh {
            return None;
        }
        let mut start = guess.clone();
        if *last == tau && *prev_gs == self.gs {
            for (z, p) in start.z.iter_mut().zip(&prev.z) {
                *z += *z - p;
            }
            if let Some(dz) = start.dz.as_mut() {
                for (d, p) in dz.iter_mut().zip(&prev.dz) {
                    *d += *d - p;
                }
            }
            return Some(start);
        }
        // (the unknowns 0, 1, 2 are x, y, φ: no forces' scale)
        let r = tau / last;
        let shape = |z: &mut [f64], p: &[f64]| {
            for (zi, pi) in z.chunks_mut(6).zip(p.chunks(6)) {
                for (a, b) in zi[..3].iter_mut().zip(&pi[..3]) {
                    *a += r * (*a - b);
                }
            }
        };
        shape(&mut start.z, &prev.z);
        if let Some(dz) = start.dz.as_mut() {
            shape(dz, &prev.dz);
        }
        Some(start)
    }

    /// The internal force `G` at the foot (`end` 0) or the tip (`end` 1) now.
    pub fn force(&self, end: usize) -> [f64; 2] {
        if let Some(f) = self.after {
            return f[end];
        }
        let z = if end == 0 {
            self.sol.left()
        } else {
            self.sol.right()
        };
        [self.gs * z[4], self.gs * z[5]]
    }

    /// The local error estimate of the trial step in the positions (module `timestep`):
    /// `Δt³/12 · max_i |r_ttt(s_i)|` over the history grid, `|·|` the Euclidean length of
    /// `(x_ttt, y_ttt)`, with `r_ttt = (aⁿ⁺¹ − aⁿ⁻¹)/(Δt + h)` (`h` the last step) where the
    /// history holds `aⁿ⁻¹`, else `(aⁿ⁺¹ − aⁿ)/Δt` (infinite where it is not a number).
    pub fn local_error(&self, tr: &Trial) -> f64 {
        if tr.euler {
            // (an impact's steps are taken at the length the drag gives them, not controlled:
            // the estimate below is the trapezoidal rule's)
            return 0.0;
        }
        let k = 4.0 / (tr.tau * tr.tau);
        let (before, span) = match &self.acc_before {
            Some((a, h)) => ([&a[0], &a[1]], tr.tau + h),
            None => ([&self.acc[0], &self.acc[1]], tr.tau),
        };
        let da = |q: usize, i: usize| k * (tr.next[q][i] - tr.hat[q][i]) - before[q][i];
        let mut worst = 0.0f64;
        for i in 0..=self.ng {
            let d = da(0, i).hypot(da(1, i));
            // (a value that is not a number rejects the step)
            worst = if d.is_nan() {
                f64::INFINITY
            } else {
                worst.max(d)
            };
        }
        tr.tau.powi(3) / 12.0 * worst / span
    }

    /// The tip's velocity at the end of the trial step.
    pub fn tip_velocity(&self, tr: &Trial) -> [f64; 2] {
        [self.tip_rate(tr, 0), self.tip_rate(tr, 1)]
    }

    /// The rate of history quantity `q` (0 x, 1 y, 4 φ) at the tip at the end of the trial `tr`.
    pub fn tip_rate(&self, tr: &Trial, q: usize) -> f64 {
        let i = self.ng;
        if tr.euler {
            return (tr.next[q][i] - self.pos[q][i]) / tr.tau;
        }
        let k = 4.0 / (tr.tau * tr.tau);
        let a1 = k * (tr.next[q][i] - tr.hat[q][i]);
        self.vel[q][i] + 0.5 * tr.tau * (self.acc[q][i] + a1)
    }

    /// The material velocity `(ẋ, ẏ)` at arc length `s` at the end of the trial `tr` (Newmark's
    /// `vⁿ + τ/2 (aⁿ + a)`, `a = (4/τ²)(r − r̂)`, the history interpolated on the grid; backward
    /// Euler's `(r − rⁿ)/τ`): a side's contact point's.
    pub fn velocity_at(&self, tr: &Trial, s: f64) -> [f64; 2] {
        let r = tr.sol.at(s);
        [0, 1].map(|q| {
            let at = |v: &[Vec<f64>; 5]| interp(&v[q], &v[q + 2], s);
            if tr.euler {
                return (r[q] - at(&self.pos)) / tr.tau;
            }
            let a1 = 4.0 / (tr.tau * tr.tau) * (r[q] - interp(&tr.hat[q], &tr.hat[q + 2], s));
            at(&self.vel) + 0.5 * tr.tau * (at(&self.acc) + a1)
        })
    }

    /// The material velocity at arc length `s` now.
    pub fn velocity_now(&self, s: f64) -> [f64; 2] {
        [0, 1].map(|q| interp(&self.vel[q], &self.vel[q + 2], s))
    }

    /// The tip's acceleration `(ẍ(1), ÿ(1))` now.
    pub fn tip_acceleration(&self) -> [f64; 2] {
        [self.acc[0][self.ng], self.acc[1][self.ng]]
    }

    /// The tip's turning rate `φ̇(1)` now.
    pub fn tip_spin(&self) -> f64 {
        self.vel[4][self.ng]
    }

    /// The accelerations and end forces made consistent with a tip condition that has just
    /// changed, from two short steps of length `δ` under the new condition, taken on a copy.
    ///
    /// Why: the forces of an inextensible rod jump where its tip's condition changes (the
    /// internal force carries a change at once along the rod), and the trapezoidal rule answers
    /// a jump of a force with an undamped mode alternating from step to step at half the jump,
    /// whatever the step: at a stick of the paper's rod the tip's T/N alternated by ±0.34 to
    /// ±0.36 at dt 0.01 … 0.0025 (±0.23 with internal damping 0.01), and that mode, not the
    /// rod, decided where the tip slipped next. Over two short steps a held quantity's
    /// acceleration goes `2a_c − aⁿ`, `aⁿ` (and its force likewise) and a free one's `a_c`,
    /// `a_c` (`a_c` the consistent one, to O(δ)): their mean is `a_c` either way. The positions
    /// and velocities stay as they are.
    ///
    /// With three feet (three steps) the values are extrapolated back to the restart's instant,
    /// `1.25 a₁ + 0.5 a₂ − 0.75 a₃` (exact for a linear change, the mode cancelled): the mean of
    /// two is that of the time `1.5 δ` later, which costs no work where the tip is at rest
    /// (a slip, a stick) but `O(τ δ)` of the energy balance where it moves on (a sliding tip
    /// that crosses into another friction patch, a round tip's end at any event).
    pub fn restart(
        &mut self,
        delta: f64,
        feet: &[Foot],
        tip: TipBc,
        moment: f64,
    ) -> Result<(), Box<BvpError>> {
        let mut probe = self.clone();
        // each probe step's end accelerations (the five quantities on the grid) and end forces
        let mut acc: Vec<Vec<Vec<f64>>> = vec![];
        let mut ends: Vec<[[f64; 2]; 2]> = vec![];
        let mut sides: Vec<Option<SideAt>> = vec![];
        for (j, &foot) in feet.iter().enumerate() {
            let tr = probe.trial(delta, foot, tip, moment)?;
            // (an impact's backward-Euler steps, if any are left, restart by their own rule:
            // each probe by the rule it was solved with, as the probes' commits use up the steps)
            let k = if tr.euler { 1.0 } else { 4.0 } / (delta * delta);
            acc.push(
                (0..5)
                    .map(|q| {
                        (0..=self.ng)
                            .map(|i| k * (tr.next[q][i] - tr.hat[q][i]))
                            .collect()
                    })
                    .collect(),
            );
            ends.push([tr.force(0), tr.force(1)]);
            sides.push(tr.side);
            if j + 1 < feet.len() {
                probe.commit(tr);
            }
        }
        let combine = |v: [f64; 3]| match feet.len() {
            3 => 1.25 * v[0] + 0.5 * v[1] - 0.75 * v[2],
            _ => 0.5 * (v[0] + v[1]),
        };
        let at = |j: usize, q: usize, i: usize| acc.get(j).map_or(0.0, |a| a[q][i]);
        for q in 0..5 {
            for i in 0..=self.ng {
                self.acc[q][i] = combine([at(0, q, i), at(1, q, i), at(2, q, i)]);
            }
        }
        let end = |e: usize, c: usize| {
            let f = |j: usize| ends.get(j).map_or(0.0, |g| g[e][c]);
            combine([f(0), f(1), f(2)])
        };
        self.after = Some([[end(0, 0), end(0, 1)], [end(1, 0), end(1, 1)]]);
        if let (Some(now), true) = (self.side.as_mut(), sides.iter().all(Option::is_some)) {
            // (a side's contact force likewise: its place stays the present one)
            let f =
                |j: usize, c: usize| sides.get(j).copied().flatten().map_or(0.0, |q| q.force[c]);
            now.force = [0, 1].map(|c| combine([f(0, c), f(1, c), f(2, c)]));
        }
        self.previous = None;
        self.acc_before = None;
        self.stats.newton_iterations = probe.stats.newton_iterations;
        self.stats.max_nodes = probe.stats.max_nodes;
        Ok(())
    }

    /// The side's contact handed back to the tip: the state is the whole rod's (the last side
    /// step's solution on `s`), the next steps the tip's.
    pub fn leave_side(&mut self) {
        self.side = None;
        self.split = None;
    }

    /// Replaces the tip's force a [`Rothe::restart`] set (no effect without one).
    pub fn set_restart_tip_force(&mut self, g: [f64; 2]) {
        if let Some(f) = self.after.as_mut() {
            f[1] = g;
        }
    }

    /// Whether a [`Rothe::restart`] set the end forces since the last step was taken.
    pub fn restarted(&self) -> bool {
        self.after.is_some()
    }

    /// Takes the trial step.
    pub fn commit(&mut self, tr: Trial) {
        self.after = None;
        let euler = tr.euler;
        self.euler_steps = self.euler_steps.saturating_sub(usize::from(euler));
        // (the energy–momentum step: `vⁿ⁺¹ = vⁿ + τ ā` with the mean `ā = 2/τ² (rⁿ⁺¹ − rⁿ − τ vⁿ)`)
        let emm = self.emm && !euler;
        let (tau, k_acc) = (tr.tau, tr.k_acc);
        let old_vel = (self.ge > 0.0).then(|| [self.vel[0].clone(), self.vel[1].clone()]);
        self.acc_before = Some(([self.acc[0].clone(), self.acc[1].clone()], tau));
        let mut next = tr.next;
        for (q, nq) in next.iter().enumerate() {
            let (v, a) = (&mut self.vel[q], &mut self.acc[q]);
            for (i, (vi, ai)) in v.iter_mut().zip(a.iter_mut()).enumerate() {
                let a1 = k_acc * (nq[i] - tr.hat[q][i]);
                *vi += if euler || emm {
                    tau * a1
                } else {
                    0.5 * tau * (*ai + a1)
                };
                *ai = a1;
            }
        }
        if let Some(old) = old_vel {
            // the scheme's identity: the force `−γ_e μ r_t` takes `Δt γ_e ∫ μ |v_mid|²`
            // (backward Euler: `Δt γ_e ∫ μ |vⁿ⁺¹|²`)
            let (vel, mu) = (&self.vel, &self.mu);
            let w_old = if euler { 0.0 } else { 0.5 };
            let mid2 = |i: usize| {
                let (x, y) = (
                    w_old * old[0][i] + (1.0 - w_old) * vel[0][i],
                    w_old * old[1][i] + (1.0 - w_old) * vel[1][i],
                );
                mu[i] * (x * x + y * y)
            };
            self.external_dissipated += tau * self.ge * self.simpson(&mid2);
        }
        if self.gi > 0.0 {
            // `κ_t` by the trapezoidal rule; the moment `γ_i κ_t/b` takes `Δt γ_i ∫ κ_t,mid²/b`
            let kt1: Vec<f64> = (0..=self.ng)
                .map(|i| {
                    if euler {
                        (tr.kappa[i] - self.kappa[i]) / tau
                    } else {
                        2.0 / tau * (tr.kappa[i] - self.kappa[i]) - self.kappa_t[i]
                    }
                })
                .collect();
            let (kt0, bv) = (&self.kappa_t, &self.bvec);
            let w_old = if euler { 0.0 } else { 0.5 };
            let mid2 = |i: usize| {
                let k = w_old * kt0[i] + (1.0 - w_old) * kt1[i];
                k * k / bv[i]
            };
            self.internal_dissipated += tau * self.gi * self.simpson(&mid2);
            self.kappa_t = kt1;
        }
        self.kappa = tr.kappa;
        std::mem::swap(&mut self.pos, &mut next);
        self.m = tr.m;
        self.start_nodes = coarser(&tr.rho, &tr.sol.mesh, self.ng, self.tol);
        self.split = tr.split;
        self.side = tr.side;
        let last = std::mem::replace(&mut self.sol, tr.sol);
        if self.predict {
            self.previous = Some((tau, self.gs, last));
        }
        self.gs = tr.gs;
        self.stats.steps += 1;
        let theta1 = self.sol.left()[2] - FRAC_PI_2 + tr.turn;
        let (theta_t1, mid) = if euler {
            let rate = (theta1 - self.theta) / tau;
            (rate, rate)
        } else {
            let rate = 2.0 / tau * (theta1 - self.theta) - self.theta_t;
            (rate, 0.5 * (self.theta_t + rate))
        };
        // the scheme's own energy identity: the damper takes Δt c ((θ_tⁿ + θ_tⁿ⁺¹)/2)² per step
        // (backward Euler: Δt c (θ_tⁿ⁺¹)²)
        self.dissipated += tau * self.damping * mid * mid;
        (self.theta, self.theta_t) = (theta1, theta_t1);
    }

    /// Simpson's rule on the grid (an even number of intervals).
    fn simpson(&self, f: &dyn Fn(usize) -> f64) -> f64 {
        let (ng, h) = (self.ng, 1.0 / self.ng as f64);
        (0..=ng)
            .map(|i| {
                f(i) * h / 3.0
                    * if i == 0 || i == ng {
                        1.0
                    } else if i % 2 == 1 {
                        4.0
                    } else {
                        2.0
                    }
            })
            .sum()
    }

    /// The present state as a sample at time `t`.
    pub fn sample(&self, t: f64) -> DynSample {
        let (vel, mu, bv, m) = (&self.vel, &self.mu, &self.bvec, &self.m);
        let mut kinetic =
            0.5 * self.simpson(&|i| mu[i] * (vel[0][i] * vel[0][i] + vel[1][i] * vel[1][i]));
        if self.g0sq > 0.0 {
            // the rotation's, `½∫ j φ_t²`, `j = g0²/b`
            kinetic += 0.5 * self.g0sq * self.simpson(&|i| vel[4][i] * vel[4][i] / bv[i]);
        }
        let mut elastic = if self.gi > 0.0 {
            // `½∫ (κ − κ0)²/b`: the moment is no longer the elastic one alone
            let (k, k0) = (&self.kappa, &self.k0vec);
            0.5 * self.simpson(&|i| (k[i] - k0[i]).powi(2) / bv[i])
        } else {
            0.5 * self.simpson(&|i| bv[i] * m[i] * m[i])
        };
        if self.cs > 0.0 {
            elastic += 0.5 * self.theta * self.theta / self.cs;
        }
        let (l, r) = (self.sol.left(), self.sol.right());
        DynSample {
            t,
            tip_x: r[0],
            tip_y: r[1],
            tip_vx: vel[0][self.ng],
            tip_vy: vel[1][self.ng],
            theta: self.theta,
            m_base: l[3],
            gx_base: self.gs * l[4],
            gy_base: self.gs * l[5],
            kinetic,
            elastic,
            dissipated: self.dissipated,
            internal_damping: self.internal_dissipated,
            external_damping: self.external_dissipated,
        }
    }
}

/// The nodes of `mesh` kept when adjacent intervals whose residuals `rho` (per interval) are
/// both below `tol/100` are merged in pairs (the collocation's own rule for merging: the
/// residual of Lobatto6 grows by about `2⁴` on an interval twice as long), except across a node
/// of the history's grid of `ng` intervals: the step's equations interpolate the history on that
/// grid by cubic Hermite pieces, whose second derivative jumps at its nodes, and an interval
/// across one loses the collocation's order (merged across grid nodes the residual of the paper's
/// rod's drag rose above `tol` at every step and the mesh was refined back). A mesh of more than
/// twice the grid's nodes is brought back to the grid's nodes alone: near the rounding floor of
/// the residual (tol 1e-10) nothing is below `tol/100`, and the nodes an event's short step
/// needed (up to 2662 at grid 200) stayed for the rest of the drag (2253 nodes at its end).
/// `None` where nothing is merged (or `rho` is empty).
fn coarser(rho: &[f64], mesh: &[f64], ng: usize, tol: f64) -> Option<Vec<usize>> {
    let low = tol / 100.0;
    let on_grid = |s: f64| {
        let u = s * ng as f64;
        (u - u.round()).abs() < 1e-9 * ng as f64
    };
    if !rho.is_empty() && mesh.len() > 2 * (ng + 1) {
        return Some((0..mesh.len()).filter(|&i| on_grid(mesh[i])).collect());
    }
    let mut keep = Vec::with_capacity(rho.len() + 1);
    keep.push(0);
    let mut i = 0;
    while i < rho.len() {
        if i + 1 < rho.len() && rho[i] < low && rho[i + 1] < low && !on_grid(mesh[i + 1]) {
            i += 2;
        } else {
            i += 1;
        }
        keep.push(i);
    }
    (keep.len() < rho.len() + 1).then_some(keep)
}

/// The rod's damping of `DynamicsOptions` and `DynDragOptions`: Kelvin–Voigt `γ_i` and
/// external `γ_e`, each in `[0, 1e6]`.
pub(crate) fn check_damping(internal: f64, external: f64) -> Result<(), VibrissaError> {
    for (name, v) in [
        ("internal_damping", internal),
        ("external_damping", external),
    ] {
        if !(0.0..=1e6).contains(&v) {
            return Err(VibrissaError::range(name, v, "[0, 1e6]"));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::coarser;

    /// A drag's step refined on the history grid of 4 intervals (nodes 0, ¼, ½, ¾, 1) with
    /// nodes added at ⅛, 3/16, 5/8: the intervals below `tol/100` merge in pairs, never
    /// across a grid node, and a mesh with nothing to merge is kept as it is.
    #[test]
    fn coarser_merges_below_the_tolerance_inside_grid_cells() {
        let tol = 1e-8;
        let mesh = [0.0, 0.125, 0.1875, 0.25, 0.5, 0.625, 0.75, 1.0];
        let low = 1e-11;
        // 0–⅛ and ⅛–3/16 merge (⅛ is not a grid node); 3/16–¼ and ¼–½ do not (¼ is one);
        // ½–⅝ and ⅝–¾ merge; ¾–1 stays
        let rho = [low, low, low, low, low, low, low];
        assert_eq!(coarser(&rho, &mesh, 4, tol), Some(vec![0, 2, 3, 4, 6, 7]));
        // one interval at tol/10 keeps its neighbour's node
        let rho = [low, 1e-9, low, low, low, low, low];
        assert_eq!(
            coarser(&rho, &mesh, 4, tol),
            Some(vec![0, 1, 2, 3, 4, 6, 7])
        );
        // the grid itself, or nothing below tol/100: nothing to merge
        assert_eq!(
            coarser(&[low; 4], &[0.0, 0.25, 0.5, 0.75, 1.0], 4, tol),
            None
        );
        assert_eq!(coarser(&[2e-10; 7], &mesh, 4, tol), None);
        assert_eq!(coarser(&[], &mesh, 4, tol), None);
        // more than twice the grid's nodes: the grid's alone, whatever the residual
        let fine: Vec<f64> = (0..=16).map(|i| i as f64 / 16.0).collect();
        assert_eq!(
            coarser(&[2e-10; 16], &fine, 4, tol),
            Some(vec![0, 4, 8, 12, 16])
        );
        assert_eq!(coarser(&[], &fine, 4, tol), None);
    }
}
