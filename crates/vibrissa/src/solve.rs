//! Single solves: the rod shape for a given force angle and tip condition.

use crate::model::{Ends, General, HomotopyFamily, Profile, RodBvp, Uniform};
use crate::{Model, VibrissaError};
use bvp::{
    continuation::{Continuation, ContinuationOptions},
    Bvp, BvpError, BvpSolver, Collocation, CollocationOptions, Guess, Integrator, NewtonOptions,
    Scheme, Shooting, ShootingOptions, Solution, Stats,
};
use elastica::{Branch, Elastica};
use serde::{Deserialize, Serialize};
use std::f64::consts::{FRAC_PI_2, PI};
use std::fmt;
use std::str::FromStr;

/// Numerical method.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Method {
    /// Single shooting (adaptive Runge–Kutta unless `rk4_steps` is set).
    #[default]
    Shooting,
    /// Multiple shooting with `segments` segments.
    MultipleShooting,
    /// Lobatto IIIA collocation, order 4.
    #[serde(rename = "collocation")]
    Collocation4,
    /// Lobatto IIIA collocation, order 6.
    #[serde(rename = "collocation6")]
    Collocation6,
    /// Closed forms (crate `elastica`); only for the paper's scene.
    Analytic,
}

impl Method {
    /// All methods.
    pub const ALL: [Method; 5] = [
        Method::Shooting,
        Method::MultipleShooting,
        Method::Collocation4,
        Method::Collocation6,
        Method::Analytic,
    ];
    /// The command-line name.
    pub fn name(self) -> &'static str {
        match self {
            Method::Shooting => "shooting",
            Method::MultipleShooting => "multiple-shooting",
            Method::Collocation4 => "collocation",
            Method::Collocation6 => "collocation6",
            Method::Analytic => "analytic",
        }
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Method {
    type Err = VibrissaError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Method::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| VibrissaError::InvalidName {
                name: "method",
                value: s.to_string(),
                valid: "shooting, multiple-shooting, collocation, collocation6, analytic",
            })
    }
}

/// Solver settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SolverConfig {
    /// Method. Default shooting.
    pub method: Method,
    /// Tolerance (Newton residual; integrator / collocation tolerance). Default 1e-10.
    pub tol: f64,
    /// Segments of multiple shooting. Default 8.
    pub segments: usize,
    /// `Some(n)`: fixed-step RK4 with `n` steps instead of the adaptive integrator.
    pub rk4_steps: Option<usize>,
}

impl Default for SolverConfig {
    fn default() -> Self {
        SolverConfig {
            method: Method::Shooting,
            tol: 1e-10,
            segments: 8,
            rk4_steps: None,
        }
    }
}

impl SolverConfig {
    /// Checks the values: `tol ∈ [1e-15, 1e-2]`, `segments ∈ [1, 10000]`, `rk4_steps ≥ 1`.
    pub fn validate(&self) -> Result<(), VibrissaError> {
        if !(self.tol >= 1e-15 && self.tol <= 1e-2) {
            return Err(VibrissaError::range("tol", self.tol, "[1e-15, 1e-2]"));
        }
        if !(1..=10_000).contains(&self.segments) {
            return Err(VibrissaError::range(
                "segments",
                self.segments as f64,
                "[1, 10000]",
            ));
        }
        if let Some(n) = self.rk4_steps {
            if !(1..=10_000_000).contains(&n) {
                return Err(VibrissaError::range("rk4_steps", n as f64, "[1, 1e7]"));
            }
        }
        Ok(())
    }
}

/// A BVP solver built from a [`SolverConfig`]; keeps its work buffers across solves.
#[derive(Clone, Debug)]
#[allow(clippy::large_enum_variant)] // one per solve or scan, never in bulk
pub(crate) enum Engine {
    Shoot(Shooting),
    Coll(Collocation),
}

impl Engine {
    pub(crate) fn new(cfg: &SolverConfig) -> Result<Engine, VibrissaError> {
        cfg.validate()?;
        let newton = NewtonOptions {
            max_iter: 30,
            tol: cfg.tol,
            ..NewtonOptions::default()
        };
        let wrap = |e: BvpError| VibrissaError::solver("solver options", e);
        let integrator = match cfg.rk4_steps {
            Some(steps) => Integrator::Rk4 { steps },
            None => Integrator::Adaptive {
                rtol: cfg.tol,
                atol: cfg.tol,
            },
        };
        Ok(match cfg.method {
            Method::Shooting | Method::MultipleShooting | Method::Analytic => {
                let segments = if cfg.method == Method::MultipleShooting {
                    cfg.segments
                } else {
                    1
                };
                Engine::Shoot(
                    Shooting::new(ShootingOptions {
                        integrator,
                        segments,
                        newton,
                        // a smooth rod needs a few hundred steps at most; more means a Newton
                        // iterate far off (huge f), better rejected fast
                        max_steps: 1500,
                        ..ShootingOptions::default()
                    })
                    .map_err(wrap)?,
                )
            }
            Method::Collocation4 | Method::Collocation6 => {
                let scheme = if cfg.method == Method::Collocation4 {
                    Scheme::Lobatto4
                } else {
                    Scheme::Lobatto6
                };
                Engine::Coll(
                    Collocation::new(CollocationOptions {
                        scheme,
                        tol: cfg.tol,
                        bc_tol: cfg.tol,
                        max_nodes: 20_000,
                        newton,
                        ..CollocationOptions::default()
                    })
                    .map_err(wrap)?,
                )
            }
        })
    }
}

impl BvpSolver for Engine {
    fn solve<B: Bvp + ?Sized>(&mut self, p: &B, g: &Guess) -> Result<Solution, BvpError> {
        match self {
            Engine::Shoot(s) => s.solve(p, g),
            Engine::Coll(c) => c.solve(p, g),
        }
    }
}

impl BvpSolver for &mut Engine {
    fn solve<B: Bvp + ?Sized>(&mut self, p: &B, g: &Guess) -> Result<Solution, BvpError> {
        (**self).solve(p, g)
    }
}

/// The tip condition of a solve.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Target {
    /// Tip slope `φ(1)`; unknown `f`.
    Phi1(f64),
    /// Tip height `y(1)`; unknown `f`.
    Eta(f64),
    /// Tip position; unknowns `f` and `α` (the given `α` is only the start of the search).
    Tip {
        /// Tip x.
        x1: f64,
        /// Tip y.
        y1: f64,
    },
}

/// Which solution family to look for.
#[derive(Clone, Debug, PartialEq, Default)]
pub enum BranchChoice {
    /// No flex point, right-handed (`κ ≤ 0`): the paper's section 2.1.1.
    #[default]
    Convex,
    /// One flex point (`κ > 0` before it): the paper's section 2.1.2.
    Flex,
    /// Start from this shape (no branch check).
    Guess(Box<Shape>),
}

impl BranchChoice {
    fn name(&self) -> &'static str {
        match self {
            BranchChoice::Convex => "convex",
            BranchChoice::Flex => "one flex",
            BranchChoice::Guess(_) => "guess",
        }
    }
}

/// One sample of a shape.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ShapePoint {
    /// Arc length.
    pub s: f64,
    /// x.
    pub x: f64,
    /// y.
    pub y: f64,
    /// Slope φ.
    pub phi: f64,
    /// Curvature `κ = κ0 + b·m`.
    pub kappa: f64,
    /// Internal moment `m`.
    pub m: f64,
}

#[derive(Clone, Debug, PartialEq)]
pub(crate) enum ShapeData {
    Numeric { sol: Solution, profile: General },
    Analytic(Elastica),
}

/// A solved rod.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Shape {
    /// Force angle α.
    pub alpha: f64,
    /// Force magnitude f.
    pub f: f64,
    /// `f·sin α`.
    pub fx: f64,
    /// `−f·cos α`.
    pub fy: f64,
    /// Tip slope φ(1).
    pub phi1: f64,
    /// Tip x.
    pub x1: f64,
    /// Tip y.
    pub y1: f64,
    /// `m(0)`, the internal moment at the foot (the paper's clamp moment is `m0 = −m(0)`).
    pub m_base: f64,
    /// Slope at the foot φ(0) (π/2 unless the support is compliant).
    pub phi0: f64,
    /// Number of flex points (sign changes of κ on `[0, 1)`).
    pub flex: usize,
    /// Arc length of the first flex point.
    pub s_flex: Option<f64>,
    /// Maximum of `y(s)` over the rod.
    pub y_max: f64,
    /// Max-norm of the final residual.
    pub residual: f64,
    /// Solver statistics.
    pub stats: Stats,
    #[serde(skip)]
    pub(crate) data: ShapeData,
}

impl Shape {
    /// `n ≥ 2` samples uniformly in `s ∈ [0, 1]` (fewer than 2 are taken as 2).
    pub fn samples(&self, n: usize) -> Vec<ShapePoint> {
        let n = n.max(2);
        (0..n)
            .map(|i| self.point_at(i as f64 / (n - 1) as f64))
            .collect()
    }

    /// The point at arc length `s` (clamped to `[0, 1]`).
    pub fn point_at(&self, s: f64) -> ShapePoint {
        let s = s.clamp(0.0, 1.0);
        match &self.data {
            ShapeData::Numeric { sol, profile } => {
                let mut z = [0.0; 4];
                sol.eval(s, &mut z);
                ShapePoint {
                    s,
                    x: z[0],
                    y: z[1],
                    phi: z[2],
                    kappa: profile.kappa(s, z[3]),
                    m: z[3],
                }
            }
            ShapeData::Analytic(e) => match e.point_at(s) {
                Ok(p) => ShapePoint {
                    s,
                    x: p.x,
                    y: p.y,
                    phi: p.phi,
                    kappa: p.kappa,
                    m: p.kappa,
                },
                Err(_) => ShapePoint {
                    s,
                    x: f64::NAN,
                    y: f64::NAN,
                    phi: f64::NAN,
                    kappa: f64::NAN,
                    m: f64::NAN,
                },
            },
        }
    }

    /// The underlying BVP solution (numerical methods only).
    pub fn solution(&self) -> Option<&Solution> {
        match &self.data {
            ShapeData::Numeric { sol, .. } => Some(sol),
            ShapeData::Analytic(_) => None,
        }
    }

    /// A BVP guess from this shape with parameters `params`.
    pub(crate) fn guess(&self, params: Vec<f64>) -> Guess {
        match &self.data {
            ShapeData::Numeric { sol, .. } => {
                let mut g = Guess::from(sol);
                g.params = params;
                g
            }
            ShapeData::Analytic(e) => elastica_guess(e, params),
        }
    }
}

/// Samples of the closed-form rod as a BVP guess (with derivatives, so interpolation is Hermite).
pub(crate) fn elastica_guess(e: &Elastica, params: Vec<f64>) -> Guess {
    let nodes = 41;
    let mesh: Vec<f64> = (0..nodes).map(|i| i as f64 / (nodes - 1) as f64).collect();
    let mut z = Vec::with_capacity(4 * nodes);
    let mut dz = Vec::with_capacity(4 * nodes);
    for &s in &mesh {
        // point_at only fails for s outside [0, 1]
        let p = e.point_at(s).unwrap_or(elastica::ShapePoint {
            s,
            x: 0.0,
            y: s,
            phi: FRAC_PI_2,
            kappa: 0.0,
        });
        z.extend_from_slice(&[p.x, p.y, p.phi, p.kappa]);
        dz.extend_from_slice(&[
            p.phi.cos(),
            p.phi.sin(),
            p.kappa,
            e.f * (p.phi - e.alpha).cos(),
        ]);
    }
    Guess {
        n: 4,
        mesh,
        z,
        dz: Some(dz),
        params,
    }
}

/// A circular-arc guess (used where the closed form has no solution, e.g. `α < −π/4`): the slope
/// goes linearly from π/2 to the target tip slope (or 0.5 for a height target), `m` decreases
/// linearly to 0, and `f` balances the base moment with a lever of half the rod.
fn arc_guess(alpha: f64, target: &Target) -> Option<Guess> {
    let phi1 = match *target {
        Target::Phi1(p) => p,
        Target::Eta(_) => 0.5,
        Target::Tip { .. } => return None,
    };
    let turn = phi1 - FRAC_PI_2;
    let m0 = 2.0 * turn;
    let f = (m0.abs() / 0.5).max(0.5);
    let nodes = 41;
    let mesh: Vec<f64> = (0..nodes).map(|i| i as f64 / (nodes - 1) as f64).collect();
    let mut g = Guess::from_fn(4, mesh, vec![f], |s, z| {
        // φ(s) = π/2 + turn·(2s − s²) has φ' = 2 turn (1 − s) = m(s)
        let phi = FRAC_PI_2 + turn * (2.0 * s - s * s);
        // positions by the midpoint rule on 64 sub-steps
        let (mut x, mut y) = (0.0, 0.0);
        let k = 64;
        for j in 0..k {
            let t = s * (j as f64 + 0.5) / k as f64;
            let p = FRAC_PI_2 + turn * (2.0 * t - t * t);
            x += p.cos() * s / k as f64;
            y += p.sin() * s / k as f64;
        }
        z.copy_from_slice(&[x, y, phi, m0 * (1.0 - s)]);
    });
    let _ = alpha;
    g.dz = None;
    Some(g)
}

/// Number of sign changes of `κ` on `[0, 1)` and the first one's arc length.
fn flex_points(sol: &Solution, profile: &General, uniform: bool) -> (usize, Option<f64>) {
    let kap = |s: f64| -> f64 {
        let mut z = [0.0; 4];
        sol.eval(s, &mut z);
        if uniform {
            z[3]
        } else {
            profile.kappa(s, z[3])
        }
    };
    const N: usize = 128;
    // the tip moment vanishes, so κ(1) = κ0(1); stop short of the tip
    let scale = (0..=N)
        .map(|i| kap(i as f64 / N as f64).abs())
        .fold(0.0, f64::max);
    let eps = 1e-9 * scale.max(1e-300);
    let mut count = 0;
    let mut first = None;
    let mut prev: Option<(f64, f64)> = None;
    for i in 0..N {
        let s = i as f64 / N as f64;
        let k = kap(s);
        if k.abs() <= eps {
            continue;
        }
        if let Some((sp, kp)) = prev {
            if kp.signum() != k.signum() {
                count += 1;
                if first.is_none() {
                    let (mut a, mut b, ka) = (sp, s, kp);
                    for _ in 0..60 {
                        let c = 0.5 * (a + b);
                        if (kap(c) > 0.0) == (ka > 0.0) {
                            a = c;
                        } else {
                            b = c;
                        }
                    }
                    first = Some(0.5 * (a + b));
                }
            }
        }
        prev = Some((s, k));
    }
    (count, first)
}

/// Extrema of `h(s) = cx·x(s) + cy·y(s)` along a solution (cubic Hermite between nodes).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Extrema {
    /// Maximum over `[0, 1]`.
    pub max: f64,
    /// Largest interior local maximum (`s < 1`), `-inf` if none.
    pub interior: f64,
    /// Its arc length.
    pub s_interior: f64,
}

pub(crate) fn extrema(sol: &Solution, cx: f64, cy: f64) -> Extrema {
    let n = sol.n;
    let len = sol.mesh.len();
    let h = |i: usize| cx * sol.z[i * n] + cy * sol.z[i * n + 1];
    let dh = |i: usize| cx * sol.dz[i * n] + cy * sol.dz[i * n + 1];
    let mut out = Extrema {
        max: f64::NEG_INFINITY,
        interior: f64::NEG_INFINITY,
        s_interior: f64::NAN,
    };
    for i in 0..len {
        out.max = out.max.max(h(i));
    }
    for i in 0..len.saturating_sub(1) {
        let (s0, s1) = (sol.mesh[i], sol.mesh[i + 1]);
        let w = s1 - s0;
        let (y0, y1) = (h(i), h(i + 1));
        let (d0, d1) = (dh(i) * w, dh(i + 1) * w);
        if !(d0 > 0.0 && d1 <= 0.0) {
            continue;
        }
        // Hermite cubic p(t); p'(t) = a t² + b t + c
        let a = 6.0 * y0 + 3.0 * d0 - 6.0 * y1 + 3.0 * d1;
        let b = -6.0 * y0 - 4.0 * d0 + 6.0 * y1 - 2.0 * d1;
        let c = d0;
        let t = if d1 == 0.0 {
            1.0
        } else if a.abs() <= 1e-14 * (b.abs() + c.abs()) {
            -c / b
        } else {
            let disc = (b * b - 4.0 * a * c).max(0.0).sqrt();
            let q = -0.5 * (b + b.signum() * disc);
            let (r1, r2) = (q / a, c / q);
            if (0.0..=1.0).contains(&r1) {
                r1
            } else {
                r2
            }
        };
        if !(0.0..=1.0).contains(&t) {
            continue;
        }
        let (t2, t3) = (t * t, t * t * t);
        let y = (2.0 * t3 - 3.0 * t2 + 1.0) * y0
            + (t3 - 2.0 * t2 + t) * d0
            + (-2.0 * t3 + 3.0 * t2) * y1
            + (t3 - t2) * d1;
        out.max = out.max.max(y);
        let s = s0 + t * w;
        if s < 1.0 - 1e-9 && y > out.interior {
            out.interior = y;
            out.s_interior = s;
        }
    }
    out
}

/// Builds a [`Shape`] from a converged solution.
pub(crate) fn shape_from<Pr: Profile>(sol: Solution, rod: &RodBvp<Pr>, profile: General) -> Shape {
    let (f, alpha) = if sol.params.len() >= 2 {
        (sol.params[0], sol.params[1])
    } else {
        (sol.params[0], rod.alpha)
    };
    let za = sol.left().to_vec();
    let zb = sol.right().to_vec();
    let (flex, s_flex) = flex_points(&sol, &profile, Pr::UNIFORM);
    let y_max = extrema(&sol, 0.0, 1.0).max;
    Shape {
        alpha,
        f,
        fx: f * alpha.sin(),
        fy: -f * alpha.cos(),
        phi1: zb[2],
        x1: zb[0],
        y1: zb[1],
        m_base: za[3],
        phi0: za[2],
        flex,
        s_flex,
        y_max,
        residual: sol.stats.residual,
        stats: sol.stats.clone(),
        data: ShapeData::Numeric { sol, profile },
    }
}

fn shape_from_elastica(e: Elastica) -> Shape {
    let flex = e.flex_count();
    Shape {
        alpha: e.alpha,
        f: e.f,
        fx: e.fx(),
        fy: e.fy(),
        phi1: e.phi1,
        x1: e.x1,
        y1: e.y1,
        m_base: e.m_base,
        phi0: FRAC_PI_2,
        flex,
        s_flex: if flex > 0 { e.s_b } else { None },
        y_max: e.y_max(),
        residual: 0.0,
        stats: Stats::default(),
        data: ShapeData::Analytic(e),
    }
}

/// Checks that a shape is on the requested branch.
pub(crate) fn check_branch(shape: &Shape, branch: &BranchChoice) -> Result<(), VibrissaError> {
    let (phi_min, phi_max) = shape
        .samples(129)
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p.phi), b.max(p.phi))
        });
    let found = if !(shape.f.is_finite() && shape.alpha.is_finite()) {
        "a non-finite solution".to_string()
    } else if phi_max - phi_min > 2.0 * PI {
        format!("a looping rod (slope range {:.3} rad)", phi_max - phi_min)
    } else if shape.f < 0.0 {
        format!("a rod pulled at the tip (f = {:.6} < 0)", shape.f)
    } else {
        match (shape.flex, shape.phi1 > shape.phi0) {
            (0, false) => "convex".to_string(),
            (0, true) => "convex, mirrored (left-handed)".to_string(),
            (1, _) => "one flex".to_string(),
            (n, _) => format!("{n} flex points"),
        }
    };
    // The paper's convex family is right-handed for α ∈ [−π/4, 0]; below −π/4 the load bends the
    // rod to the left (e.g. the horizontal tip load), and a left-handed convex rod is the answer.
    let mirrored_ok = shape.alpha < -std::f64::consts::FRAC_PI_4 - 1e-12;
    let ok = match branch {
        BranchChoice::Convex => {
            found == "convex" || (mirrored_ok && found == "convex, mirrored (left-handed)")
        }
        BranchChoice::Flex => found == "one flex",
        BranchChoice::Guess(_) => !found.starts_with("a ") || found.starts_with("a looping"),
    };
    if ok {
        Ok(())
    } else {
        Err(VibrissaError::WrongBranch {
            requested: branch.name().to_string(),
            found,
        })
    }
}

fn check_alpha(alpha: f64) -> Result<(), VibrissaError> {
    if !(alpha.is_finite() && (-PI..=PI).contains(&alpha)) {
        return Err(VibrissaError::range("alpha", alpha, "[-pi, pi]"));
    }
    Ok(())
}

fn check_target(target: &Target) -> Result<(), VibrissaError> {
    match *target {
        Target::Phi1(p) => {
            if !(p.is_finite() && (-PI..=PI).contains(&p)) {
                return Err(VibrissaError::range("phi1", p, "[-pi, pi]"));
            }
        }
        Target::Eta(e) => {
            if !(e.is_finite() && e > -1.0 && e < 1.0) {
                return Err(VibrissaError::range("eta", e, "(-1, 1)"));
            }
        }
        Target::Tip { x1, y1 } => {
            if !(x1.is_finite() && y1.is_finite() && x1 * x1 + y1 * y1 < 1.0) {
                return Err(VibrissaError::range(
                    "tip distance sqrt(x1² + y1²)",
                    (x1 * x1 + y1 * y1).sqrt(),
                    "[0, 1) (the rod has length 1)",
                ));
            }
        }
    }
    Ok(())
}

fn elastica_branch(branch: &BranchChoice) -> Branch {
    match branch {
        BranchChoice::Flex => Branch::OneFlex,
        _ => Branch::Convex,
    }
}

/// The closed-form rod for `(alpha, target)` on `branch` (tip targets excluded).
fn closed_form(alpha: f64, target: &Target, branch: Branch) -> Result<Elastica, VibrissaError> {
    let ctx = format!("closed form at alpha = {alpha}, {target:?}");
    match *target {
        Target::Phi1(p) => Elastica::new(branch, alpha, p),
        Target::Eta(e) => elastica::solve_eta(branch, alpha, e),
        Target::Tip { .. } => unreachable_tip(),
    }
    .map_err(|e| VibrissaError::elastica(ctx, e))
}

fn unreachable_tip() -> Result<Elastica, elastica::ElasticaError> {
    Err(elastica::ElasticaError::IllConditioned {
        what: "closed-form tip target",
        name: "target",
        value: f64::NAN,
        reason: "a tip-position target has no direct closed form",
    })
}

/// Solves `rod` from `guess`, wrapping the error with `context`.
pub(crate) fn run<B: Bvp + ?Sized>(
    engine: &mut Engine,
    rod: &B,
    guess: &Guess,
    context: impl FnOnce() -> String,
) -> Result<Solution, VibrissaError> {
    engine
        .solve(rod, guess)
        .map_err(|e| VibrissaError::solver(context(), e))
}

/// [`run`] for a rod, through the fast single-shape path (uniform clamped rod, single shooting;
/// `crate::fast::solve_rod`) when it applies and converges.
fn run_rod<Pr: Profile>(
    engine: &mut Engine,
    rod: &RodBvp<Pr>,
    guess: &Guess,
    context: impl FnOnce() -> String,
) -> Result<Solution, VibrissaError> {
    if let Some(tol) = crate::fast::single_shooting_tol(engine) {
        if let Some(sol) = crate::fast::solve_rod(rod, guess, tol) {
            return Ok(sol);
        }
    }
    run(engine, rod, guess, context)
}

/// Solves for the rod with force angle `alpha` (fixed for φ1 / η targets, the start for a tip
/// target) and the tip condition `target`, on the requested branch.
///
/// Start guesses: the closed form (crate `elastica`) of the uniform clamped rod; for other scenes
/// a homotopy from it in the amplitude `t ∈ [0, 1]` of taper, pre-curvature and compliance (see
/// the crate docs). A converged solution on another branch is an error
/// ([`VibrissaError::WrongBranch`]), never an answer.
pub fn solve(
    model: &Model,
    alpha: f64,
    target: Target,
    branch: &BranchChoice,
    cfg: &SolverConfig,
) -> Result<Shape, VibrissaError> {
    cfg.validate()?;
    check_alpha(alpha)?;
    check_target(&target)?;
    if cfg.method == Method::Analytic {
        return solve_analytic(model, alpha, target, branch);
    }
    let mut engine = Engine::new(cfg)?;
    let shape = if model.has_uniform_profile() && model.scene().support_compliance == 0.0 {
        solve_with(model, Uniform, &mut engine, alpha, target, branch)?
    } else {
        solve_with(
            model,
            model.profile(1.0),
            &mut engine,
            alpha,
            target,
            branch,
        )?
    };
    check_branch(&shape, branch)?;
    Ok(shape)
}

fn solve_analytic(
    model: &Model,
    alpha: f64,
    target: Target,
    branch: &BranchChoice,
) -> Result<Shape, VibrissaError> {
    if !model.is_paper_scene() {
        return Err(VibrissaError::MethodUnavailable {
            method: "analytic".into(),
            reason: "closed forms exist only for the paper's scene (uniform, straight, clamped rod, horizontal surface)".into(),
        });
    }
    if matches!(target, Target::Tip { .. }) {
        return Err(VibrissaError::MethodUnavailable {
            method: "analytic".into(),
            reason: "a tip-position target needs a numerical method".into(),
        });
    }
    let e = closed_form(alpha, &target, elastica_branch(branch))?;
    Ok(shape_from_elastica(e))
}

fn ends_of(target: Target) -> Ends {
    match target {
        Target::Phi1(phi1) => Ends::Phi1 { phi1 },
        Target::Eta(eta) => Ends::Eta { eta },
        Target::Tip { x1, y1 } => Ends::Tip { x1, y1 },
    }
}

/// Core of [`solve`] for one profile type.
pub(crate) fn solve_with<Pr: Profile>(
    model: &Model,
    profile: Pr,
    engine: &mut Engine,
    alpha: f64,
    target: Target,
    branch: &BranchChoice,
) -> Result<Shape, VibrissaError> {
    let c = model.scene().support_compliance;
    if let Target::Tip { x1, y1 } = target {
        return solve_tip(model, profile, engine, alpha, x1, y1, branch);
    }
    let rod = RodBvp {
        profile: profile.clone(),
        compliance: c,
        alpha,
        ends: ends_of(target),
    };
    if let BranchChoice::Guess(g) = branch {
        let guess = g.guess(vec![g.f]);
        let sol = run_rod(engine, &rod, &guess, || {
            format!("solve at alpha = {alpha}, {target:?} from the given shape")
        })?;
        return Ok(shape_from(sol, &rod, model.profile(1.0)));
    }
    // the closed form of the uniform clamped rod where it exists, else a circular arc
    let guess = match closed_form(alpha, &target, elastica_branch(branch)) {
        Ok(e) => {
            // the fast single-shape path needs only (m(0), f) of the closed form, not its samples
            if let (true, Some(tol)) = (
                Pr::UNIFORM && c == 0.0,
                crate::fast::single_shooting_tol(engine),
            ) {
                let g = Guess::constant(0.0, 1.0, 2, &[0.0, 0.0, FRAC_PI_2, e.m_base], vec![e.f]);
                if let Some(sol) = crate::fast::solve_rod(&rod, &g, tol) {
                    return Ok(shape_from(sol, &rod, model.profile(1.0)));
                }
            }
            elastica_guess(&e, vec![e.f])
        }
        Err(err) => match arc_guess(alpha, &target) {
            Some(g) => g,
            None => return Err(err),
        },
    };
    if Pr::UNIFORM && c == 0.0 {
        let sol = run_rod(engine, &rod, &guess, || {
            format!("solve at alpha = {alpha}, {target:?}")
        })?;
        return Ok(shape_from(sol, &rod, model.profile(1.0)));
    }
    let family = HomotopyFamily {
        profile: model.profile(1.0),
        compliance: c,
        alpha,
        ends: ends_of(target),
    };
    let sol = homotopy(engine, &family, &guess)?;
    Ok(shape_from(sol, &rod, model.profile(1.0)))
}

/// A rough "solution" made of a guess (for continuation starts, which correct it first).
pub(crate) fn guess_as_solution(g: &Guess) -> Solution {
    let dz = g.dz.clone().unwrap_or_else(|| vec![0.0; g.z.len()]);
    Solution {
        n: g.n,
        mesh: g.mesh.clone(),
        z: g.z.clone(),
        dz,
        params: g.params.clone(),
        status: bvp::Status::Converged,
        stats: Stats::default(),
    }
}

/// Pseudo-arclength continuation (crate `bvp`) in the homotopy amplitude `t` from 0 (uniform
/// clamped rod, started from the closed form) to 1 (the scene).
pub(crate) fn homotopy(
    engine: &mut Engine,
    family: &HomotopyFamily,
    guess: &Guess,
) -> Result<Solution, VibrissaError> {
    let opts = ContinuationOptions {
        ds: 0.25,
        ds_min: 1e-6,
        ds_max: 2.0,
        max_steps: 400,
        lambda_min: -0.5,
        lambda_max: 1.0,
        detect_folds: false,
        ..ContinuationOptions::default()
    };
    let wrap = |e: BvpError, t: f64| {
        VibrissaError::solver(
            format!("homotopy from the uniform clamped rod (t = {t:.6} of 1)"),
            e,
        )
    };
    let mut cont = Continuation::new(family, engine, guess_as_solution(guess), 0.0, opts)
        .map_err(|e| wrap(e, 0.0))?;
    let mut stats = Stats::default();
    let mut t = 0.0;
    for item in cont.by_ref() {
        let bp = item.map_err(|e| wrap(e, t))?;
        stats.accumulate(&bp.stats);
        t = bp.lambda;
        if bp.on_bound && bp.lambda >= 1.0 {
            let mut sol = bp.solution;
            sol.stats = Stats {
                residual: sol.stats.residual,
                nodes: sol.stats.nodes,
                error_estimate: sol.stats.error_estimate,
                ..stats
            };
            return Ok(sol);
        }
        if bp.lambda < -0.25 {
            break;
        }
    }
    Err(VibrissaError::NoConvergence {
        what: "homotopy from the uniform clamped rod".into(),
        reason: format!("the branch did not reach t = 1 (last t = {t})"),
    })
}

/// Tip target: solve for `y(1) = y1` at the given `alpha`, then continue the tip x to `x1` with
/// `(f, α)` unknown.
fn solve_tip<Pr: Profile>(
    model: &Model,
    profile: Pr,
    engine: &mut Engine,
    alpha: f64,
    x1: f64,
    y1: f64,
    branch: &BranchChoice,
) -> Result<Shape, VibrissaError> {
    let c = model.scene().support_compliance;
    let rod = RodBvp {
        profile: profile.clone(),
        compliance: c,
        alpha,
        ends: Ends::Tip { x1, y1 },
    };
    let start = match branch {
        BranchChoice::Guess(g) => {
            let sol = run(engine, &rod, &g.guess(vec![g.f, g.alpha]), || {
                format!("tip ({x1}, {y1}) from the given shape")
            })?;
            return Ok(shape_from(sol, &rod, model.profile(1.0)));
        }
        _ => solve_with(
            model,
            profile.clone(),
            engine,
            alpha,
            Target::Eta(y1),
            branch,
        )?,
    };
    let mut sol = start
        .solution()
        .cloned()
        .ok_or(VibrissaError::NotImplemented("analytic tip"))?;
    sol.params = vec![start.f, start.alpha];
    let mut x = start.x1;
    let mut dx = (x1 - x).clamp(-0.05, 0.05);
    let mut stats = start.stats.clone();
    while (x1 - x).abs() > 0.0 {
        let xn = if (x1 - x).abs() <= dx.abs() {
            x1
        } else {
            x + dx
        };
        let r = RodBvp {
            ends: Ends::Tip { x1: xn, y1 },
            ..rod.clone()
        };
        match engine.solve(&r, &Guess::from(&sol)) {
            Ok(s) => {
                stats.accumulate(&s.stats);
                sol = s;
                x = xn;
                if sol.stats.newton_iters <= 4 {
                    dx *= 1.5;
                }
            }
            Err(e) => {
                dx *= 0.5;
                if dx.abs() < 1e-6 {
                    return Err(VibrissaError::solver(
                        format!("continuation of the tip x towards {x1} stalled at x = {x}"),
                        e,
                    ));
                }
            }
        }
    }
    let residual = sol.stats.residual;
    sol.stats = Stats { residual, ..stats };
    Ok(shape_from(sol, &rod, model.profile(1.0)))
}
