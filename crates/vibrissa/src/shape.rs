//! A solved rod ([`Shape`]): its summary numbers, samples, and the branch it is on.
//!
//! Sampling works on the cubic Hermite interpolant of the solution's nodes (positions, slope and
//! moment with their derivatives), as per-interval polynomials searched from a hint, so that the
//! 129-sample scans for flex points, load reversals and the highest point cost a few hundred
//! operations per rod whatever its profile.

pub use crate::kind::ShapeKind;
use crate::profile::{General, Profile};
pub use crate::sampling::Clearance;
use crate::sampling::{clearance, extrema, flex_and_reversals};
use bvp::{Solution, Stats};
use elastica::Elastica;
use serde::Serialize;
use std::f64::consts::{FRAC_PI_2, PI};
use std::fmt;

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
    /// Number of flex points (sign changes of the curvature κ on `[0, 1)`).
    pub flex: usize,
    /// Number of sign changes of the bending moment `m(s)` on `[0, 1)` (load reversals): the
    /// branch of the rod. Equals `flex` for the straight uniform rod (κ = m).
    pub load_reversals: usize,
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

    /// How the rod lies against the surface line through its tip inclined by `beta` (0: the
    /// horizontal surface at height `y1`); [`Clearance::penetrates`] tells whether it crosses it.
    pub fn clearance(&self, beta: f64) -> Clearance {
        match &self.data {
            ShapeData::Numeric { sol, .. } => clearance(sol, beta),
            ShapeData::Analytic(e) => {
                let (sb, cb) = beta.sin_cos();
                let h = |x: f64, y: f64| -sb * (x - e.x1) + cb * (y - e.y1);
                let mut best = (h(0.0, 0.0), 0.0);
                // the closed form has no interpolant to maximize on: dense samples
                for p in e.shape(1025).unwrap_or_default() {
                    if p.s < 1.0 && h(p.x, p.y) > best.0 {
                        best = (h(p.x, p.y), p.s);
                    }
                }
                Clearance {
                    height: best.0,
                    s: best.1,
                    tip_approach: (e.phi1 - beta).sin(),
                }
            }
        }
    }

    /// The underlying BVP solution (numerical methods only).
    pub fn solution(&self) -> Option<&Solution> {
        match &self.data {
            ShapeData::Numeric { sol, .. } => Some(sol),
            ShapeData::Analytic(_) => None,
        }
    }
}

/// Which solution family a solve asks for. Branches are told apart by the sign changes of the
/// bending moment `m(s)` (the load), which for the straight uniform rod is the paper's flex count
/// (κ = m) and for any other rod does not depend on its rest curvature or stiffness.
#[derive(Clone, Debug, PartialEq, Default)]
pub enum BranchChoice {
    /// No load reversal: the paper's convex family (§2.1.1) and, for any other rod, the solution
    /// continuously connected to it through the homotopy from the uniform straight rod.
    #[default]
    Convex,
    /// One load reversal: the paper's one-flex family (§2.1.2) and its homotopy continuation.
    Flex,
    /// Whatever the solver converges to from the convex start; [`Shape::kind`] says what it is.
    Any,
    /// Start from this shape (no branch check).
    Guess(Box<Shape>),
}

impl BranchChoice {
    /// The branches that have a name (every one but a guess).
    pub const NAMED: [BranchChoice; 3] =
        [BranchChoice::Convex, BranchChoice::Flex, BranchChoice::Any];
    /// The name on the command line and in Python (`guess` for a given shape).
    pub fn name(&self) -> &'static str {
        match self {
            BranchChoice::Convex => "convex",
            BranchChoice::Flex => "flex",
            BranchChoice::Any => "any",
            BranchChoice::Guess(_) => "guess",
        }
    }
    /// What the branch is, in one line (the program's `--help` lists it).
    pub fn help(&self) -> &'static str {
        match self {
            BranchChoice::Convex => "no load reversal: the bending moment m(s) keeps its sign (the paper's convex rod)",
            BranchChoice::Flex => "one load reversal: m(s) changes sign once (the paper's one-flex rod)",
            BranchChoice::Any => "whatever the solution connected to the uniform rod's convex one is (see load_reversals)",
            BranchChoice::Guess(_) => "start from the given shape (no branch check)",
        }
    }
    /// Load reversals the branch must have (`None`: no requirement).
    pub fn load_reversals(&self) -> Option<usize> {
        match self {
            BranchChoice::Convex => Some(0),
            BranchChoice::Flex => Some(1),
            BranchChoice::Any | BranchChoice::Guess(_) => None,
        }
    }
}

impl std::str::FromStr for BranchChoice {
    type Err = crate::VibrissaError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        BranchChoice::NAMED
            .into_iter()
            .find(|b| b.name() == s)
            .ok_or_else(|| crate::VibrissaError::InvalidName {
                name: "branch",
                value: s.to_string(),
                valid: "convex, flex, any",
            })
    }
}

impl fmt::Display for BranchChoice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            BranchChoice::Convex => "convex (no load reversal)",
            BranchChoice::Flex => "flex (one load reversal)",
            BranchChoice::Any => "any",
            BranchChoice::Guess(_) => "the given shape",
        })
    }
}

impl Shape {
    /// What this rod is (see [`ShapeKind`]).
    pub fn kind(&self) -> ShapeKind {
        if !(self.f.is_finite() && self.alpha.is_finite()) {
            return ShapeKind::NonFinite;
        }
        let (lo, hi) = self
            .samples(129)
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                (a.min(p.phi), b.max(p.phi))
            });
        if hi - lo > 2.0 * PI {
            ShapeKind::Looping
        } else if self.f < 0.0 {
            ShapeKind::Pulled
        } else {
            ShapeKind::Regular {
                load_reversals: self.load_reversals,
            }
        }
    }

    /// True when this rod is on `branch`.
    pub fn is_on(&self, branch: &BranchChoice) -> bool {
        match (branch.load_reversals(), self.kind()) {
            (Some(n), ShapeKind::Regular { load_reversals }) => n == load_reversals,
            (Some(_), _) => false,
            (None, _) => true,
        }
    }
}

/// Builds a [`Shape`] from a converged solution with `params = [f]` (α given) or `[f, α]`.
pub(crate) fn shape_from(sol: Solution, alpha: f64, profile: General) -> Shape {
    let (f, alpha) = if sol.params.len() >= 2 {
        (sol.params[0], sol.params[1])
    } else {
        (sol.params[0], alpha)
    };
    let (za, zb) = (sol.left(), sol.right());
    let (m_base, phi0, phi1, x1, y1) = (za[3], za[2], zb[2], zb[0], zb[1]);
    let (flex, s_flex, load_reversals) = if profile.is_uniform() {
        flex_and_reversals(&sol, &crate::profile::Uniform)
    } else {
        flex_and_reversals(&sol, &profile)
    };
    let y_max = extrema(&sol, 0.0, 1.0).max;
    Shape {
        alpha,
        f,
        fx: f * alpha.sin(),
        fy: -f * alpha.cos(),
        phi1,
        x1,
        y1,
        m_base,
        phi0,
        flex,
        s_flex,
        load_reversals,
        y_max,
        residual: sol.stats.residual,
        stats: sol.stats.clone(),
        data: ShapeData::Numeric { sol, profile },
    }
}

/// The closed-form rod as a [`Shape`].
pub(crate) fn shape_from_elastica(e: Elastica) -> Shape {
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
        load_reversals: flex,
        y_max: e.y_max(),
        residual: 0.0,
        stats: Stats::default(),
        data: ShapeData::Analytic(e),
    }
}
