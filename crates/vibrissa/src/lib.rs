//! The vibrissa model: an elastic rod with optional taper, rest curvature and compliant support,
//! pressed with its tip on a surface, and the quasi-static stiction scan of the foot dragged while
//! dry friction holds the tip. One engine for every rod; the closed forms of crate `elastica`
//! (uniform clamped rod) are the cross-check. `docs/model.md` in the repository states the model,
//! its conventions and sources in full.
//!
//! # The math (normalized units: length L, force EI/L², moment EI/L with EI at the foot)
//!
//! State `z = (x, y, φ, m)` along the arc length `s ∈ [0, 1]` from the foot:
//!
//! ```text
//!     x' = cos φ,   y' = sin φ,   φ' = κ0(s) + b(s)·m,   m' = f·cos(φ − α)
//!     x(0) = y(0) = 0,   φ(0) = π/2 + c·m(0),   m(1) = 0,   plus the tip conditions
//! ```
//!
//! `b` is the reciprocal bending stiffness (taper ratio ρ: `b = (1 − (1 − ρ)s)⁻⁴`; tables are
//! piecewise linear), `κ0` the rest curvature, `c` the compliance of the rotational spring at the
//! foot (0: clamp). The tip force on the rod is `F = (f sin α, −f cos α)`: α = 0 points straight
//! down, α < 0 rotates it clockwise. Tip conditions ([`Target`]): slope `φ(1)` or height `y(1)`
//! at a given α (unknown f), or the tip position (unknowns f and α).
//!
//! Contact with the surface line of inclination β through the contact point (tangent
//! `t = −(cos β, sin β)`, normal `n = (−sin β, cos β)`): normal force `N = f cos(α − β) ≥ 0`,
//! signed friction ratio `μ = F·t/N = tan(β − α)` (`tan(−α)` on the flat surface); the tip sticks
//! while `|μ| ≤ μ0`. `m_base = m(0)`; the paper's clamp moment is `m0 = −m(0)`.
//!
//! # The engine
//!
//! Every rod is solved by the rod's own shooter (module `shooter`): DOP853 weights on a mesh that
//! grades itself until the embedded error estimate meets the tolerance, the sensitivities
//! `∂z/∂(m(0), f, α)` carried on the same stages (exact Newton Jacobians), monomorphized over the
//! [`profile::Profile`] so that the uniform rod folds `b ≡ 1`, `κ0 ≡ 0` away and any other rod
//! reads its `b`, `κ0` from a table at the stage abscissae. Newton is damped for single solves and
//! a chord iteration in the scan; families of rods (the homotopy from the uniform straight rod to
//! any rod, folds in `d`) are followed by pseudo-arclength continuation on the same shooter.
//! Multiple shooting and Lobatto collocation of crate `bvp` ([`Method`]) run through the same scan
//! driver; their points get exact tangents from the shooter.
//!
//! Branches ([`BranchChoice`], [`ShapeKind`]) are told apart by the sign changes of the bending
//! moment `m(s)` (load reversals), which for the straight uniform rod is the paper's flex count.
//! A solve starts from the uniform clamped rod's closed form and follows the homotopy in the
//! amplitude `t ∈ [0, 1]` of the rod's deviations (taper, rest curvature, compliance), so the
//! answer is the solution continuously connected to the uniform rod's branch.
//!
//! The scan ([`scan()`]): start at α = β, `y(1) = η`, tip at `(x*, η)`; the foot moves right by
//! `d`, the tip sticks at `(x* − d, η)` relative to the foot. One march in `d` predicts each point
//! by the Hermite polynomial through the last points and their tangents, corrects it, and locates
//! every event inside the step where it happens — slip (`|μ| = μ0`, either sign), lift-off
//! (`N = 0`), penetration (the rod above the surface line), a fold in `d` (snap-through) — by
//! Brent's method (`elastica::roots`) on that polynomial refined by Newton with solves; the event that
//! ends the scan is its last point ([`Event`]). The measurable range of μ0 is the first monotone
//! stretch of `|μ(d)|` ([`RangeEnd`]); [`infer`] maps a slip displacement back to μ0.
//!
//! # Main items
//!
//! [`Rod`] (built by [`Rod::builder`] or from a [`Scene`] file), [`Surface`] → [`solve()`] →
//! [`Shape`] ([`Shape::samples`], [`Shape::clearance`]), or [`scan()`] / [`scan_at`] →
//! [`ScanResult`] of [`ScanPoint`]s; [`SolverConfig`], [`ScanOptions`]; errors:
//! [`VibrissaError`].
#![warn(missing_docs)]

// Modules import downward only (tests/layering.rs checks it): kind, parts, search → profile,
// error → limits → config, rod → scene; equations → shooter → rodsolve → arclength → chain;
// sampling → shape → report → watch → stepper (the step contract) → events, fold, record → own,
// generic → march (the driver) → engine (the one way in) → start, ground → scan, drag, peg, solve;
// the surface's shapes: gauss (quadrature) → grating, sines, surface, chain; limits → measured →
// surface → chain.
mod analytic;
mod arclength;
mod chain;
mod config;
mod contacts;
mod control;
pub mod drag;
pub mod dynamics;
mod dyndrag;
mod engine;
pub mod equations;
mod error;
mod events;
pub mod fit;
mod fold;
mod gauss;
mod generic;
mod grating;
mod ground;
pub mod inertia;
mod kind;
pub mod limits;
mod march;
mod measured;
pub mod modes;
mod own;
mod parts;
pub mod peg;
pub mod profile;
pub mod quasistatic;
mod record;
pub mod report;
mod rod;
mod rodsolve;
mod rothe;
mod sampling;
pub mod scan;
pub mod scene;
mod search;
mod shape;
mod shooter;
mod sines;
mod sode;
pub mod solve;
pub mod spectrum;
mod spline;
mod start;
mod stepper;
pub mod surface;
mod timestep;
mod watch;

pub use config::Cancel;
pub use drag::{drag, DragOptions, DragResult, FootMotion};
pub use error::VibrissaError;
pub use fit::{fit, FitOptions, FitResult, Trace, TraceSlip};
pub use peg::{locate, solve_peg, whisk, PegPoint, WhiskOptions, WhiskResult};
pub use report::{
    ContactLabel, ContactModel, Event, Inference, RangeEnd, ScanOptions, ScanPoint, ScanResult,
    StopReason,
};
pub use rod::{
    Rod, RodBuilder, Surface, Units, MAX_B, MAX_COMPLIANCE, MAX_PRECURVATURE, MAX_SURFACE_ANGLE,
    MIN_B, MIN_TAPER,
};
pub use scan::{infer, scan, scan_at};
pub use scene::{Physical, Precurvature, Scene, Stiffness};
pub use shape::{BranchChoice, Clearance, Shape, ShapeKind, ShapePoint};
pub use solve::{solve, Method, SolverConfig, StartKind, Target};

/// The examples of the crate's README.md, run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
