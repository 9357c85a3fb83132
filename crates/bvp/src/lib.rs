//! Two-point boundary-value problems: shooting, multiple shooting, collocation and continuation.
//!
//! # The problem
//!
//! Find `z: [a, b] → Rⁿ` and unknown parameters `p ∈ Rᵏ` with
//!
//! ```text
//!     z'(s) = F(s, z(s), p)          s ∈ [a, b]
//!     g(z(a), z(b), p) = 0           n + k conditions (two-point, non-separated allowed)
//! ```
//!
//! A problem is a type implementing [`Bvp`] (or closures assembled by [`from_fns`]); it knows
//! nothing of solvers. Analytic Jacobians (`∂F/∂z`, `∂F/∂p`, and those of `g`, all row-major with
//! the names of [`Bvp`]) are optional: without them the solvers use finite differences.
//!
//! # Solvers
//!
//! Each solver takes a problem, an initial [`Guess`] and its own options struct (with `Default`,
//! documented defaults, and `validate()` called by the constructor):
//!
//! - [`Shooting`]: single (`segments = 1`) and multiple shooting; Jacobians from the variational
//!   equations; fixed-step RK4 or an adaptive embedded pair.
//! - [`Collocation`]: Lobatto IIIA collocation of order 4 (the `bvp4c` / `solve_bvp` scheme) and 6,
//!   residual control, mesh refinement and coarsening, Newton systems by a structured
//!   (almost block diagonal) LU.
//! - [`continuation`]: natural-parameter and pseudo-arclength continuation of a [`ParamBvp`] family,
//!   with fold detection and location.
//!
//! Problems with a handful of states can be written with arrays instead of slices
//! ([`fixed::FixedBvp`], or [`fixed::SimpleBvp`] without parameters, wrapped in
//! [`fixed::Fixed`]).
//!
//! All solvers return a [`Solution`] (mesh values, dense evaluation of the method's order
//! ([`Dense`]), parameters, [`Stats`]) or a
//! [`BvpError`] that says why the solve failed and carries the statistics gathered so far.
//!
//! [`multipoint`] solves problems with interfaces at interior points ([`multipoint::MultipointBvp`],
//! conditions across the interfaces, `F` per region) with any solver, and returns one solution
//! per region.
//!
//! [`extend`]: a guess on another interval from a solution (`Guess::extended`, as MATLAB's
//! `bvpinit(sol, [a b])`; `Guess::rescaled`), and continuation in the interval's right end
//! ([`IntervalFamily`]).
//!
//! [`solve_by_continuation`] ([`path`]) solves a hard member of a [`ParamBvp`] family by walking
//! the parameter from an easy value, with any solver.
//!
//! [`samples`] holds problems with known answers, shared by tests, benches and examples;
//! [`testset`] the Cash–Mazzia BVP test set (28 singularly perturbed and nonlinear problems, exact
//! solutions where they exist), run in full by `cargo run --release -p bvp --example testset`.
//!
//! With the feature `ode_solvers`, the module `odes` adapts right-hand sides written as
//! `ode_solvers::System` and offers single shooting through `ode_solvers`' Dop853 as a baseline.
#![warn(missing_docs)]

mod error;
mod problem;
mod rk;
mod singular;
mod solution;
mod stats;

pub mod collocation;
pub mod complex;
pub mod continuation;
pub mod extend;
pub mod fd;
pub mod fixed;
pub mod linalg;
pub mod multipoint;
pub mod newton;
#[cfg(feature = "ode_solvers")]
pub mod odes;
pub mod path;
pub mod samples;
pub mod shooting;
pub mod tableau;
pub mod testset;

pub use collocation::{Collocation, CollocationOptions, ErrorControl, Progress, Scheme};
pub use continuation::{BranchPoint, Continuation, ContinuationOptions, Fold, FoldKind, ParamBvp};
pub use error::{BvpError, Check, Status};
pub use extend::IntervalFamily;
pub use newton::{Damping, NewtonOptions};
pub use path::{solve_by_continuation, solve_member, PathOptions, PathSolution, Scale};
pub use problem::{from_fns, Bvp, Dims, FnBvp, SingularTerm};
pub use shooting::{Integrator, Shooting, ShootingOptions};
pub use solution::{Dense, Guess, Solution};
pub use stats::Stats;

/// A BVP solver: takes a problem and an initial guess, returns a converged solution or says why not.
///
/// Implementations keep their work buffers between calls, so repeated solves (continuation) do not
/// allocate in their inner loops.
pub trait BvpSolver {
    /// Solves `problem` starting from `guess`.
    fn solve<P: Bvp + ?Sized>(&mut self, problem: &P, guess: &Guess) -> Result<Solution, BvpError>;

    /// The accuracy the solver checks its solutions against, if it has one (collocation: `tol`;
    /// shooting: [`ShootingOptions::accuracy_tol`]). Default `None`.
    fn tolerance(&self) -> Option<f64> {
        None
    }

    /// Sets that accuracy (`0 < tol < 1`; used by [`solve_by_continuation`] for the members on
    /// the way, see [`PathOptions::intermediate_tol`]). Default: ignored.
    fn set_tolerance(&mut self, _tol: f64) {}

    /// Whether the members solved from now on are steps of a walk towards another member
    /// (`true`; set by [`solve_by_continuation`] while it walks) or results (`false`). Returns
    /// whether the solver checks a result more than a step, so that the walk's last member is to
    /// be solved again as a result (collocation with [`ErrorControl::Confirmed`]: no guard on the
    /// way). Default: ignored, `false`.
    fn set_walking(&mut self, _walking: bool) -> bool {
        false
    }
}

impl<S: BvpSolver + ?Sized> BvpSolver for &mut S {
    fn solve<P: Bvp + ?Sized>(&mut self, problem: &P, guess: &Guess) -> Result<Solution, BvpError> {
        (**self).solve(problem, guess)
    }
    fn tolerance(&self) -> Option<f64> {
        (**self).tolerance()
    }
    fn set_tolerance(&mut self, tol: f64) {
        (**self).set_tolerance(tol)
    }
    fn set_walking(&mut self, walking: bool) -> bool {
        (**self).set_walking(walking)
    }
}

/// The examples of the crate's README.md, run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
