//! The vibrissa model: an elastic rod with optional taper, pre-curvature and compliant support,
//! pressed with its tip on a surface, and the quasi-static stiction scan (paper §3), solved with
//! the generic BVP crate `bvp` and cross-checked against the closed forms of crate `elastica`.
//!
//! # The math (normalized units: length L, force EI/L², moment EI/L at the base)
//!
//! State `z = (x, y, φ, m)` along the arc length `s ∈ [0, 1]` from the foot:
//!
//! ```text
//!     x' = cos φ,   y' = sin φ,   φ' = κ0(s) + b(s)·m,   m' = f·cos(φ − α)
//!     x(0) = y(0) = 0,   φ(0) = π/2 + c·m(0),   m(1) = 0,   plus the tip condition(s)
//! ```
//!
//! `b` is the reciprocal bending stiffness (taper ratio ρ: `b = (1 − (1 − ρ)s)^(−4)`; tables are
//! piecewise linear), `κ0` the rest curvature, `c` the compliance of the rotational spring at the
//! foot (0: clamp). The tip force on the rod is `F = (f sin α, −f cos α)`: α = 0 points straight
//! down, α < 0 rotates it clockwise (friction to −x).
//!
//! Tip conditions ([`Target`]): slope `φ(1) = φ1` or height `y(1) = η` with α given (unknown f),
//! or the tip position (unknowns α and f).
//!
//! Uniform rod: `κ = m` and the first integral `½κ² = f·[sin(φ − α) − sin(φ1 − α)]` holds
//! (design.md writes `2f`; that factor contradicts the paper's (2.6) — checked in the tests).
//!
//! # Sign conventions
//!
//! * `m_base` = `m(0)`, the internal moment at the foot: negative for the convex (right-handed)
//!   rod. The paper's clamp moment is `m0 = −m(0)`.
//! * Convex branch: no flex point, `κ ≤ 0` (for α ≥ −π/4; below, the load bends the rod to the
//!   left and a left-handed convex rod is accepted). One-flex branch: `κ > 0` before the flex
//!   point, `< 0` after it (paper §2.1.2).
//! * Friction ratio `μ = tan(β − α)` with β the surface angle (`tan(−α)` on the horizontal
//!   surface). Derivation: the surface line through the contact point has tangent
//!   `t = (cos β, sin β)` and upward normal `n = (−sin β, cos β)`; `F·t = f sin(α − β)`,
//!   `F·n = −f cos(α − β)`, so `|F·t / F·n| = |tan(β − α)|`, and the scan starts at `α = β`
//!   (force along the normal). "Above the surface" means `(p − c)·n > 0` for the contact point c.
//!
//! # Solves ([`solve()`])
//!
//! The BVP is solved by shooting, multiple shooting or Lobatto collocation ([`Method`]). The
//! right-hand side is generic over a [`model::Profile`]: the paper's uniform straight rod uses
//! the zero-sized [`model::Uniform`] (b ≡ 1, κ0 ≡ 0 folded away at compile time), every other
//! scene [`model::General`]; the choice is made once per solve or scan. Analytic Jacobians
//! `∂F/∂z`, `∂F/∂p`, `∂g` are provided (checked against finite differences by proptest).
//!
//! Start guesses: the closed form of the uniform clamped rod (crate `elastica`; a circular arc
//! outside its domain, e.g. α < −π/4). Other scenes start there too and follow a homotopy in the
//! amplitude `t ∈ [0, 1]` of the scene's deviations — taper ratio `1 − t(1 − ρ)`, table `b^t`,
//! pre-curvature `t·κ0`, compliance `t·c` — by the pseudo-arclength continuation of crate `bvp`
//! ([`model::HomotopyFamily`]) from t = 0 to t = 1. A converged solution on another branch than
//! the requested one (flex count, handedness, loops, f < 0) is a
//! [`VibrissaError::WrongBranch`], never an answer.
//!
//! # The scan ([`scan()`])
//!
//! Start: α = β, `y(1) = η`, convex; its tip `x1*`. The foot moves right by `d`; the tip sticks at
//! `(x1* − d, η)` relative to the foot. The family in `λ = d` ([`model::ScanFamily`], unknowns
//! f, α) is stepped from output point to output point in d, each step warm-started by a quadratic
//! extrapolation of the last three points; where a natural step fails (near a fold in d) the
//! pseudo-arclength continuation of crate `bvp` takes over, so the birth of the flex point (κ(0)
//! changes sign), the maximum of μ and the folds in φ1 and α need no special cases. μ_max by
//! Brent's maximizer on μ(d) (solver accuracy, not the grid maximum); slip (μ = μ0) and penetration
//! (checked at the start, at every point and between points) located by Brent's root finder; a
//! fold in d (snap-through) and solver failures end the scan with a [`StopReason`]. The paper's
//! scene with single shooting runs a specialized fixed-size path (module `fast`: unknowns
//! (m(0), f, α), DOP853 steps on a 16-component system with sensitivities, tangent predictor) that
//! hands over to the generic scan on anything unusual; both are tested against the closed forms.
//! [`infer`] maps a slip displacement `d0 ∈ [0, d at μ_max]` back to μ0.
//!
//! # Main items
//!
//! [`Scene`] (with [`Scene::validate`]) → [`Model`] ([`Model::units`] for N, N·m, mm) →
//! [`solve()`] → [`Shape`] ([`Shape::samples`]) or [`scan()`] / [`scan_at`] → [`ScanResult`] of
//! [`ScanPoint`]s; [`SolverConfig`], [`ScanOptions`]; errors: [`VibrissaError`].
#![warn(missing_docs)]

// Modules import downward only: scene, profile → equations → shooter → rodsolve → shape →
// model → solve → stepper/march (report) → scan → analytic.
mod analytic;
mod arclength;
pub mod equations;
mod error;
mod march;
pub mod profile;
pub mod report;
mod rod;
mod rodsolve;
pub mod scan;
pub mod scene;
mod search;
mod shape;
mod shooter;
pub mod solve;
mod stepper;

pub use error::VibrissaError;
pub use report::{Event, Inference, RangeEnd, ScanOptions, ScanPoint, ScanResult, StopReason};
pub use rod::{
    Rod, RodBuilder, Surface, Units, MAX_B, MAX_COMPLIANCE, MAX_PRECURVATURE, MAX_SURFACE_ANGLE,
    MIN_B, MIN_TAPER,
};
pub use scan::{infer, scan, scan_at};
pub use scene::{Physical, Precurvature, Scene, Stiffness};
pub use shape::{BranchChoice, Clearance, Shape, ShapeKind, ShapePoint};
pub use solve::{solve, Method, SolverConfig, Target};
