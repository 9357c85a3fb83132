//! Lobatto IIIA collocation with residual control and mesh adaptation.
//!
//! # Discretization
//!
//! On a mesh `a = s_0 < … < s_N = b` (`h_i = s_{i+1} − s_i`) the solution is approximated by a C¹
//! piecewise polynomial `S` that satisfies the ODE exactly at the Lobatto points
//! `s_i + c_j h_i` of each interval (collocation), and the boundary conditions:
//!
//! ```text
//!     Lobatto4 (bvp4c / solve_bvp):  c = 0, 1/2, 1                S cubic   on each interval
//!     Lobatto6 (Lobatto IIIA s = 4): c = 0, (5 − √5)/10, (5 + √5)/10, 1   S quartic on each interval
//! ```
//!
//! Writing `Y_j ≈ S(s_i + c_j h_i)` and `f_j = F(s_i + c_j h_i, Y_j, p)`, the collocation equations
//! are the Lobatto IIIA Runge–Kutta equations, with `a_rj = ∫_0^{c_r} L_j` (`L_j` the Lagrange
//! basis on the `c`):
//!
//! ```text
//!     (Y_r − Y_0) / h_i − Σ_j a_rj f_j = 0,      r = 1 … q,    Y_0 = z_i,  Y_q = z_{i+1}.
//! ```
//!
//! Lobatto4: the midpoint is eliminated explicitly (Hermite–Simpson),
//! `Y_1 = (z_i + z_{i+1})/2 − h_i (f_2 − f_0)/8`, leaving one block of `n` equations per interval:
//! `(z_{i+1} − z_i)/h_i − (f_0 + 4 f_1 + f_2)/6 = 0`. Unknowns: `z` at the nodes and `p`.
//! Lobatto6: the two internal stages are unknowns of the global system (`3n` equations and
//! unknowns per interval), so every equation stays local to one interval.
//! The `n + k` boundary conditions `g(z_0, z_N, p) = 0` close the square system. Its Jacobian
//! (from [`Bvp::rhs_jacobian`] or forward differences, [`crate::fd`], with the columns of `∂F/∂z`
//! grouped by its learned sparsity) is block-sparse: each interval
//! couples only its own unknowns, the right node and `p`; it is factorized by a structured
//! (almost block diagonal) LU with partial pivoting, interval by interval (`collocation::abd`).
//! Damped Newton is [`crate::newton::Newton`].
//!
//! Orders at the nodes: 4 (Lobatto4) and 6 (Lobatto6, superconvergence of Gauss–Lobatto
//! collocation); `S` itself is accurate to `O(h⁴)` resp. `O(h⁵)` between nodes.
//!
//! # Error control (Kierzenka & Shampine, as in bvp4c / solve_bvp)
//!
//! The residual `r(s) = S'(s) − F(s, S(s), p)` is scaled componentwise by `1 + |F(s, S(s), p)|`
//! and its RMS over each interval is estimated by 5-point Lobatto quadrature (`r` vanishes at the
//! interval ends, so three evaluations per interval):
//!
//! ```text
//!     ρ_i = sqrt( Σ_q w_q ‖r(s_i + t_q h_i) / (1 + |F|)‖₂² ),  t = ½ ∓ ½√(3/7), ½;  w = 49/180, 16/45, 49/180
//! ```
//!
//! A solve is accepted when `max ρ_i ≤ tol` and `max |g| ≤ bc_tol`. Otherwise the mesh is
//! adapted: an interval with `ρ_i > tol` gets one node (`ρ_i < 100 tol`) or two (else); two
//! adjacent intervals with `ρ < tol/100` are merged (the residual grows by `2³` resp. `2⁴`, still
//! far below `tol`); the current `S` interpolates the new starting values. After acceptance the
//! mesh is also coarsened (up to 8 times) while that removes at least 10 % of the nodes, and the
//! coarse solution is kept only if it still meets `tol`. Newton failures: see below.
//!
//! # Dense output, and the check of what is returned
//!
//! The returned [`Solution`] holds the mesh nodes, `z` and `dz = F(s_i, z_i, p)` there.
//! Lobatto4 returns its collocation polynomial itself, the cubic Hermite interpolant of `z`,
//! `dz` ([`crate::Dense::Hermite`], as bvp4c and `solve_bvp` do): the residual its error control
//! measures is that of the returned interpolant (`Solution::residuals` reproduces the estimate),
//! and scipy's residual assertions hold on it. Between nodes it is less accurate than at them
//! (within 10·tol on the test set, up to 50× its nodal error). Lobatto6 returns on each interval
//! the quintic Hermite interpolant of `z`, `dz` and `z'' = d/ds F(s, z(s), p)` at its two ends,
//! each `z''` a one-sided difference of `F` along the tangent `(1, F)` *into* the interval
//! ([`crate::Dense::QuinticIntervals`], order 6; its quartic collocation polynomial is of order
//! 5 between nodes). `F` is evaluated only inside `[a, b]` and never across a node, so a kink of
//! `F` at a node or at an end of the interval costs no accuracy (a central difference across the
//! node did: 3.6e-5 at tol 1e-8 on `y'' = −|y|`, `y(0) = 0`, `tests/interpolant.rs`).
//!
//! Before a solution is returned, the residual of the returned interpolant is measured at the
//! interior Lobatto points of every interval (the formula of `ρ_i` above, as scipy checks its
//! cubic; for Lobatto4 it is `ρ_i` itself): if it exceeds `tol` anywhere, those intervals are
//! refined and the solve goes on (at the node limit: [`BvpError::Inaccurate`]), except where the
//! returned object is the collocation polynomial (Lobatto6 returns its quartic on an interval
//! where the quintic misses `tol`) and the miss is the rounding floor of the nodal values (more
//! than `tol/2` above the polynomial's `ρ_i`): refinement raises that floor (∝ ε/h), so such a
//! solution is returned with its check as the estimate.
//! `stats.error_estimate` is its maximum, the residual of the object returned. A quintic for
//! Lobatto4 was tried: its residual is dominated by the derivative of the global error, which
//! local refinement does not reduce (Cash–Mazzia 5 and 11 at ε = 1e-4, tol 1e-8, ran into the
//! node limit).

//! # The guard of residual control
//!
//! The residual bounds the error only through the conditioning of the problem (a periodic
//! epidemic model at tol 1e-4: Lobatto4's residual 8.5e-5, its error 5.2e-3). With
//! [`ErrorControl::Guarded`] a solution that passed the checks above also gets a cheap estimate
//! of its true error (`collocation::guard`): deferred correction, `e ≈ J⁻¹ R_H(u_h)` with the
//! factored Newton matrix `J` and `R_H` the integral over every interval of the residual of a
//! Hermite interpolant of higher order (quintic with `z''` for Lobatto4, septic with `z''`,
//! `z'''` for Lobatto6, derivatives from one-sided differences of `F` inside the interval), plus
//! the distance of the returned interpolant from it between nodes; 7 (Lobatto4) or 9
//! (Lobatto6) evaluations of `F` per interval and one back-substitution
//! ([`Collocation::guard_error`]). Where it exceeds `tol`, the solve continues as with
//! [`ErrorControl::Error`] (below), whose estimate then decides. The estimate is asymptotic: in
//! layers resolved by few nodes (Lobatto6's superconvergence at the nodes, or Lobatto4 on the
//! fourth-order Cash–Mazzia 104) it can exceed the true error by orders of magnitude
//! (Cash–Mazzia 6 at ε = 1e-4, tol 1e-4, Lobatto6: 1.0e-3 against 3.7e-8), which costs error
//! control's reference solves and, at the node limit, the solve; on the epidemic model it
//! underestimates Lobatto6's error (1.6e-4 for 9.5e-4) but still exceeds `tol`. So it is not
//! the default.
//!
//! # Confirmed alarms
//!
//! [`ErrorControl::Confirmed`] runs the guard on every accepted mesh too, but measures errors
//! relative to the solution's scale, `|e_c| / (1 + max_i |z_{i,c}|)` (as the Cash–Mazzia study
//! does, `examples/testset.rs`), not pointwise: Cash–Mazzia 104 at ε = 1e-3, tol 1e-4, Lobatto4
//! has a pointwise error of 3.9e-3 in `y'''` at `x = 1` (where `|y'''| ≈ 6`, 6e12 at `x = 0`),
//! which the pointwise guard found (3.8e-3) and error control could not remove within the
//! node limit; relative to the scale it is 1.1e-6. An alarm (estimate above `tol`) on a
//! solution that is not a coarsening of an accepted one is confirmed before it is acted on: the
//! solution is compared with the reference of error control (below; one Newton solve on the
//! same mesh for Lobatto4, on the halved mesh for Lobatto6), in the same scale. Above `tol`:
//! the solve continues under error control from that estimate, first by a Newton solve on the
//! same mesh to a lower threshold (an error that is Newton's goes without refinement) and an
//! estimate again. Else the alarm was false (on
//! the Cash–Mazzia set: Lobatto6's guard in layers, up to 1.0e-2 for a reference estimate of
//! 9.6e-7) and the solution is returned as accepted, without coarsening further. The steps of
//! a walk by [`crate::solve_by_continuation`] skip the guard ([`BvpSolver::set_walking`]); its
//! last member is solved again with it. The default control. Figures: [`ErrorControl::Confirmed`].
//!
//! # Error control mode
//!
//! With [`ErrorControl::Error`] (as bvp5c) a solution that met the residual control is also
//! compared with a reference of higher accuracy: Lobatto6 solved on the same mesh from it
//! (Lobatto4), or Lobatto6 on the halved mesh (Lobatto6). The estimate
//! `e_i = max |S_c − R_c| / (1 + |R_c|)` over the ends and the three interior points of interval
//! `i` is the error of `S` to a relative `O(h)` (resp. `1/64`): asymptotically correct, not a
//! bound. If `max e_i > tol`, the residual tolerance is multiplied by
//! `clamp(tol / (2 max e_i), 1e-3, 1/2)` (the error is the residual propagated by the problem's
//! Green's function) and the mesh refined where the residual exceeds it or `e_i > tol`.
//! `stats.error_estimate` is `max e_i`; coarsening after acceptance is off. An estimate above
//! `tol` that is more than half the one the last refinement was made for is a floor that
//! refinement does not lower (rounding, in a problem that amplifies it): the solve ends at once
//! with [`BvpError::Inaccurate`] (the estimate, `tol`, the statistics), not at `max_nodes`.
//!
//! # Lobatto6 from a poor guess
//!
//! When Lobatto6's damped Newton and the homotopy fail on the first mesh of a guess without
//! slopes (not one made from a solution), Lobatto4 is solved from the same guess at
//! `max(tol, 1e-3)` (a cheap attempt: at most 6 mesh passes and 500 nodes, no homotopy) and
//! Lobatto6 restarts on its mesh from its solution
//! (Lobatto6's Newton has the smaller region of convergence: Falkner–Skan from the bvp4c
//! tutorial's guess). If Lobatto4 fails too, Lobatto6 goes on refining as below.
//!
//! # Newton thresholds and failures
//!
//! Collocation rows are divided by `h_i` (units of `z'`) and scaled by `1 + max |F_c|` over their
//! interval ([`crate::newton::NewtonSystem::residual_scale`]), boundary rows are as given; Newton
//! stops when the scaled max-norm is at most `min(newton.tol, tol / 20, bc_tol)` (or at the
//! rounding floor `newton.step_residual_tol`, see [`NewtonOptions`]), so that the algebraic
//! error is negligible against the residual control. That floor's test (a full step that no
//! longer lowers the scaled residual) cannot tell rounding from a step too long for the
//! nonlinearity of a nearly singular problem; when Newton stops there with the residual met but
//! the boundary conditions not (`max |g| > bc_tol`, which refinement cannot help), it goes on
//! once from its iterate on the same mesh with the floor capped at `bc_tol`, and only then
//! reports [`BvpError::Stalled`]. A Newton failure (stall or iteration limit,
//! not NaN/∞) is answered, up to 8 times, by refining where the unconverged iterate's residual
//! exceeds `tol` (bisecting if nowhere) and restarting from that iterate, as `solve_bvp` does: a
//! coarse mesh that cannot resolve a layer often has no nearby discrete solution at all.
//!
//! # Conditioning check
//!
//! At acceptance, `A ≈ ‖J⁻¹ diag(w)‖∞` (two solves with the last LU, or with `J` formed at the
//! solution when Newton accepted it without factorizing on that mesh; `w` the row scales) bounds
//! how far scaled residuals of size 1 can move the discrete solution. With `r` this solution's
//! own residual size (the largest estimated defect `≤ tol`, and the boundary residual), if `A·r`
//! exceeds `1 + ‖u‖∞`, no digit of the solution is certain: the mesh is bisected (twice at
//! most; the defect falls like `h^order`) and then [`BvpError::SingularJacobian`] is reported.
//! This catches problems without a solution, on which residual control alone "converges" to a
//! discrete solution of huge amplitude (as `solve_bvp` does), and nearly singular ones (their
//! `A` grows under refinement). It is `r`, not `tol`: well-posed layer problems have `A ~ 1/ε`
//! through `y'` on every mesh, so a hypothetical residual at `tol` would flag them at `tol ~ ε`.

// Index loops mirror the formulas (several arrays indexed alike).
#![allow(clippy::needless_range_loop)]

mod abd;
mod guard;
mod run;
mod tableau;

use crate::fd::{bc_jacobian_or_fd, rhs_jacobian_or_fd, FdScheme, FdScratch};
use crate::newton::{attach, non_finite, singular, Newton, NewtonSystem};
use crate::singular::Regular;
use crate::solution::locate;
use crate::{Bvp, BvpError, BvpSolver, Dims, Guess, NewtonOptions, Solution, Stats};
use abd::{AbdSystem, Layout};
use run::{Ctx, Next, Run};
use tableau::{Tableau, EST_T, EST_W, MAXC};

/// Collocation scheme.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub enum Scheme {
    /// 3-point Lobatto IIIA, order 4 (the `bvp4c` / `solve_bvp` scheme).
    Lobatto4,
    /// 4-point Lobatto IIIA, order 6.
    Lobatto6,
}

impl Scheme {
    /// Order of convergence at the mesh nodes (4 or 6).
    pub fn order(self) -> usize {
        match self {
            Scheme::Lobatto4 => 4,
            Scheme::Lobatto6 => 6,
        }
    }
}

/// What the error control of [`Collocation`] holds to `tol` (see the module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub enum ErrorControl {
    /// The scaled RMS residual of the returned interpolant per interval (bvp4c, scipy's
    /// `solve_bvp`). The error is that residual propagated by the problem: at most its size
    /// times the conditioning of the problem, which can be large (a periodic epidemic model at
    /// tol 1e-4: residual 8.5e-5, error 5.2e-3). The default until issue 34's fourth round
    /// (now [`ErrorControl::Confirmed`]).
    Residual,
    /// The residual as above, guarded: the true error of a solution that met the residual is
    /// also estimated cheaply (deferred correction with the factored Newton matrix, see the
    /// module docs; [`Collocation::guard_error`]), and where that estimate exceeds `tol` the
    /// solve goes on as with [`ErrorControl::Error`] (whose estimate then decides). The
    /// epidemic model at tol 1e-4: error 1.9e-5 (Lobatto4), 9.5e-6 (Lobatto6). Not the default:
    /// the estimate is asymptotic, and in layers resolved by few nodes it exceeds the true error
    /// by orders of magnitude (Cash–Mazzia 104 at ε = 1e-3, tol 1e-4: 3.8e-3 for an error of
    /// 6.9e-7, after which error control ran into the node limit), which cost 2 of 343
    /// Lobatto4 successes on the test set (7 with continuation) and made continuation 2.4×
    /// slower. [`ErrorControl::Confirmed`] checks its alarms first.
    Guarded,
    /// Residual control whose successes are also within `tol` in their error. The default. The
    /// residual as above; then the guard of [`ErrorControl::Guarded`] (with errors relative
    /// to the solution's scale, `|S_c − y_c| / (1 + max |y_c|)` with the max over the nodes);
    /// an alarm (estimate above `tol`) is confirmed before it is acted on, by the reference of
    /// [`ErrorControl::Error`] (one more Newton solve; same scale). Confirmed (that estimate
    /// above `tol` too): the solve goes on under error control — first once more on the same mesh
    /// with Newton's threshold lowered (to a tenth of the residual it stopped at, times the
    /// factor the error missed by), since part of the error can be Newton's, then refining —
    /// and `stats.error_estimate` is its estimate. Not confirmed: the solution is returned as
    /// residual control accepted it (no further coarsening; `stats.error_estimate` its
    /// residual).
    /// [`Collocation::guard_error`] and [`Collocation::confirmation`] report both estimates.
    /// Steps of a walk by [`crate::solve_by_continuation`] are solved under `Residual`, and its
    /// last member again under this control ([`BvpSolver::set_walking`]).
    ///
    /// Measured. The periodic epidemic model at tol 1e-4 (error against an independent
    /// reference on 2001 points, `tests/periodic.rs`): Lobatto4 1.9e-5 (guard 3.2e-3,
    /// confirmed by 6.3e-3; `Residual`: 5.2e-3), Lobatto6 9.5e-6 (guard 1.5e-4, reference
    /// 9.3e-6 on the first accepted mesh, returned without coarsening; `Residual`: 9.5e-4);
    /// `tests/periodic.rs` checks every success of the default options at tol 1e-3…1e-8. The
    /// Cash–Mazzia study with every collocation case run under this control (the default) and
    /// `Residual` back to back in one sitting (`cargo run --release -p bvp --example testset --
    /// --residual`, all 32 problems, 384 cases per method, `data/bvp_testset/default_control`):
    /// the same converged counts (Lobatto4 343, Lobatto6 352, each with continuation 371, 372),
    /// all within 10·tol of the exact solutions; the guard fired on 1 Lobatto4 success,
    /// confirmed (problem 9 at ε = 1e-4, tol 1e-4: error 1.95e-4 → 1.7e-5, 281 → 457 nodes),
    /// and on 11 Lobatto6 successes (13 with continuation), none confirmed (reference estimates
    /// at most 0.09·tol); total times +2.1 % (Lobatto4, 24.87 s against 24.37 s), +5.1 %
    /// (Lobatto6, 53.77 / 51.15 s), +1.3 % and +2.8 % (each with continuation, 56.70 / 55.99 s
    /// and 83.61 / 81.37 s). Scaled, not pointwise: in the layer of Cash–Mazzia 104 at ε = 1e-3
    /// (`y = 1/(ε + x)`, `z = (y, …, y''')`), Lobatto4 at tol 1e-4 has a pointwise relative
    /// error of 3.9e-3 in `y'''` at `x = 1` (where `|y'''| ≈ 6` against 6e12 at `x = 0`; the
    /// pointwise guard of `Guarded` said 3.8e-3, and error control then ran into the node
    /// limit), but 1.1e-6 relative to the scale.
    ///
    /// The default since issue 34's fourth round (on the figures above).
    ///
    /// Newton's error. In the rod dynamics of the `vibrissa` crate (collocation at tol 1e-10
    /// every time step) the confirmed alarms (6.4e-9, 5.6e-9, 4.7e-9 at three successive steps)
    /// were Newton's error, not the mesh's: Newton stops at a scaled residual of `tol/20`, the
    /// positions are then 3e-12 off, and the step's equations (`G' = μ·4/Δt²·(r − r̂)`) carry
    /// that into the internal force times 3100. Refining the mesh with a lower residual tolerance
    /// removed it (2.4e-14 after one pass) but grew the mesh at every step until the node limit;
    /// the re-solve on the same mesh removes it without refinement. That crate's dynamics keeps
    /// `Residual`: the guard raises false alarms there at nearly every step (its differences of
    /// `F` meet `F`'s rounding, amplified by `4/Δt²`), which cost 4× the time.
    #[default]
    Confirmed,
    /// The residual as above, and then the true error of the returned solution, estimated
    /// against a more accurate reference (Lobatto4: Lobatto6 on the same mesh; Lobatto6:
    /// Lobatto6 on the halved mesh), componentwise `|S − R| / (1 + |R|)` at the nodes and three
    /// interior points of every interval, must meet `tol`; while it does not, the residual
    /// tolerance is lowered and the mesh refined. As bvp5c, which controls the true error. The
    /// estimate is asymptotically correct (the reference's error is `O(h)` resp. `1/64` of it),
    /// not a bound; `stats.error_estimate` is it. Costs one more Newton solve per accepted mesh,
    /// and the meshes a tighter residual needs. An estimate above `tol` that is more than half
    /// the one the last refinement was made for (a floor: rounding, or an error the estimate does
    /// not see falling) ends the solve at once with [`BvpError::Inaccurate`] (the estimate and
    /// `tol`), instead of refining to `max_nodes`; also under `Guarded` and `Confirmed` after a
    /// confirmed alarm.
    Error,
}

/// Options of [`Collocation`].
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct CollocationOptions {
    /// Scheme. Default `Lobatto4`.
    pub scheme: Scheme,
    /// Tolerance on the scaled RMS ODE residual per interval (see the module docs). Default 1e-6.
    /// Valid: `0 < tol < 1`; below about 1e-12 rounding in the residual estimate can make it
    /// unattainable (the mesh then grows to `max_nodes`).
    pub tol: f64,
    /// Tolerance on the boundary conditions (max-norm). Default `None`: the same as `tol` (as in
    /// scipy's `solve_bvp`). Valid: `> 0`.
    pub bc_tol: Option<f64>,
    /// Cap on mesh nodes. Default 10 000. Valid: `>= 3`. A refinement beyond it, or a guess mesh
    /// with more nodes, is reported as [`BvpError::MeshLimit`].
    pub max_nodes: usize,
    /// Cap on mesh passes (Newton solves on successive meshes). Default 50. Valid: `>= 1`.
    /// Exceeding it is reported as [`BvpError::MeshLimit`] with `needed` = the current node count.
    pub max_mesh_passes: usize,
    /// Adapt the mesh. Default `true`. With `false` the problem is solved once on the guess mesh
    /// (or the default 11-node mesh) and returned without checking `tol` — for convergence
    /// studies; the residual estimate is still reported in `stats.error_estimate`.
    pub adapt: bool,
    /// Merge intervals whose residual is below `tol / 100` (also after acceptance). Default `true`.
    pub coarsen: bool,
    /// Newton options. `max_iter`, `step_tol`, `min_damping`, `step_residual_tol` apply as given;
    /// the residual threshold is `min(newton.tol, tol / 20, bc_tol)`.
    pub newton: NewtonOptions,
    /// What the error control holds to `tol` ([`ErrorControl`]). Default
    /// [`ErrorControl::Confirmed`]: the residual, and the estimated true error where a cheap
    /// guard raises an alarm that a reference confirms (was `Residual`). Coarsening after
    /// acceptance is off with `Error` (and with `Confirmed` after an alarm of the guard).
    pub control: ErrorControl,
    /// Globalization: when damped Newton fails on the first mesh, solve the Newton homotopy
    /// `R(u) − τ R(u₀) = 0` from `τ = 1` to `0` on that mesh (see [`crate::newton::homotopy`])
    /// before refining. Default `true`.
    pub homotopy: bool,
}

impl Default for CollocationOptions {
    fn default() -> Self {
        CollocationOptions {
            scheme: Scheme::Lobatto4,
            tol: 1e-6,
            bc_tol: None,
            max_nodes: 10_000,
            max_mesh_passes: 50,
            adapt: true,
            coarsen: true,
            newton: NewtonOptions::default(),
            control: ErrorControl::Confirmed,
            homotopy: true,
        }
    }
}

fn invalid(name: &'static str, value: impl std::fmt::Display, reason: &'static str) -> BvpError {
    BvpError::InvalidOption {
        name,
        value: value.to_string(),
        reason,
    }
}

impl CollocationOptions {
    /// The boundary-condition tolerance in effect: `bc_tol`, or `tol` when unset.
    pub fn bc_tol(&self) -> f64 {
        self.bc_tol.unwrap_or(self.tol)
    }

    /// Checks the ranges documented on the fields (and [`NewtonOptions::validate`]).
    pub fn validate(&self) -> Result<(), BvpError> {
        if !(self.tol > 0.0 && self.tol < 1.0) {
            return Err(invalid("tol", self.tol, "must be in (0, 1)"));
        }
        if let Some(bc_tol) = self.bc_tol {
            if !(bc_tol > 0.0 && bc_tol.is_finite()) {
                return Err(invalid("bc_tol", bc_tol, "must be finite and > 0"));
            }
        }
        if self.max_nodes < 3 {
            return Err(invalid("max_nodes", self.max_nodes, "must be >= 3"));
        }
        if self.max_mesh_passes < 1 {
            return Err(invalid(
                "max_mesh_passes",
                self.max_mesh_passes,
                "must be >= 1",
            ));
        }
        self.newton.validate()
    }
}

/// One mesh pass of a collocation solve, as reported to the observer of
/// [`Collocation::solve_observed`].
#[derive(Clone, Copy, Debug)]
pub struct Progress<'a> {
    /// Mesh pass (1 for the first Newton solve).
    pub pass: usize,
    /// The mesh of this pass.
    pub mesh: &'a [f64],
    /// Newton iterations of the whole solve so far.
    pub newton_iters: usize,
    /// Whether Newton converged on this mesh (else the solver refines and retries, or fails).
    pub newton_converged: bool,
    /// Newton's final scaled residual on this mesh.
    pub residual: f64,
    /// Scaled RMS collocation residual of each interval (the error control's `ρ_i`; empty when
    /// Newton did not converge): where the mesh is refined next.
    pub residuals: &'a [f64],
}

/// Nodes of the default mesh when the guess has fewer than 3.
const DEFAULT_NODES: usize = 11;
/// Newton failures answered by refining the mesh (from the unconverged iterate) before one is
/// reported.
const MAX_RETRIES: usize = 8;
/// Bisections of a mesh whose solution failed the conditioning check before it is reported.
const MAX_ILL_REFINES: usize = 2;
/// Coarsening attempts after acceptance.
const MAX_COARSEN: usize = 8;

/// Collocation solver (keeps its work buffers, including those of the LU, between solves).
#[derive(Clone, Debug)]
pub struct Collocation {
    opts: CollocationOptions,
    tab: Tableau,
    work: Work,
    newton: Newton,
    /// The guard's estimate in the last solve ([`Collocation::guard_error`]).
    guard: Option<f64>,
    /// The estimate that checked the guard's alarm ([`Collocation::confirmation`]).
    confirmed: Option<f64>,
    /// Solving steps of a walk ([`BvpSolver::set_walking`]): no guard.
    walking: bool,
}

impl Collocation {
    /// Creates a solver; validates the options.
    pub fn new(opts: CollocationOptions) -> Result<Self, BvpError> {
        opts.validate()?;
        Ok(Collocation {
            tab: Tableau::new(opts.scheme),
            opts,
            work: Work::default(),
            newton: Newton::new(),
            guard: None,
            confirmed: None,
            walking: false,
        })
    }

    /// With [`ErrorControl::Guarded`] or [`ErrorControl::Confirmed`]: the guard's estimate of
    /// the true error in the last solve
    /// (componentwise `|S − y| / (1 + |S|)`, max over the nodes and three interior points of
    /// every interval), of the returned solution if it met `tol`; else the estimate that
    /// exceeded `tol`, after which the solve went on under error control (the returned
    /// `stats.error_estimate` is that control's estimate). `None` in the other modes, or where
    /// it could not be formed.
    pub fn guard_error(&self) -> Option<f64> {
        self.guard
    }

    /// With [`ErrorControl::Confirmed`]: the estimate against the reference of
    /// [`ErrorControl::Error`] that checked the guard's alarm in the last solve (componentwise
    /// `|S − R| / (1 + |R|)`, max over the nodes and three interior points of every interval;
    /// `∞` if the reference solve failed). At most `tol`: the alarm was false and the solution
    /// returned as residual control accepted it; above: the solve went on under error control.
    /// `None` if the guard raised no alarm (or in the other modes).
    pub fn confirmation(&self) -> Option<f64> {
        self.confirmed
    }

    /// The options.
    pub fn options(&self) -> &CollocationOptions {
        &self.opts
    }

    /// [`BvpSolver::solve`] reporting each mesh pass to `observer` (the library prints nothing;
    /// `cargo run --release -p bvp --example progress` prints what scipy's `verbose=2` shows).
    pub fn solve_observed<P: Bvp + ?Sized>(
        &mut self,
        problem: &P,
        guess: &Guess,
        observer: &mut dyn FnMut(&Progress<'_>),
    ) -> Result<Solution, BvpError> {
        let reg = Regular::new(problem)?;
        // A regularized singular problem changes form at s = 0: no learned pattern there.
        self.work.fd.learn_sparsity(reg.is_none());
        match reg {
            Some(reg) => self.solve_plain(&reg, guess, observer),
            None => self.solve_plain(problem, guess, observer),
        }
    }

    /// Times this solver's linear-algebra work buffers had to grow (a Newton system larger than
    /// any before); meshes no larger than one already seen reuse them without allocating.
    pub fn symbolic_factorizations(&self) -> usize {
        self.work.sys.buffer_growths
    }
}

/// Work buffers of one solver.
#[derive(Clone, Debug)]
struct Work {
    sys: AbdSystem,
    fd: FdScratch,
    /// `u` at which `ypts`/`fpts` were computed.
    u_at: Vec<f64>,
    ypts: Vec<f64>,
    fpts: Vec<f64>,
    jz: Vec<f64>,
    jp: Vec<f64>,
    ga: Vec<f64>,
    gb: Vec<f64>,
    gp: Vec<f64>,
    g: Vec<f64>,
    tmp: Vec<f64>,
    tmp2: Vec<f64>,
    fe: Vec<f64>,
    /// Nonzero columns of a row of `∂F/∂z` (Lobatto4's condensation).
    nz: Vec<usize>,
}

impl Default for Work {
    fn default() -> Self {
        Work {
            sys: AbdSystem::new(),
            fd: FdScratch::with_scheme(Dims { n: 0, k: 0 }, FdScheme::Forward),
            u_at: Vec::new(),
            ypts: Vec::new(),
            fpts: Vec::new(),
            jz: Vec::new(),
            jp: Vec::new(),
            ga: Vec::new(),
            gb: Vec::new(),
            gp: Vec::new(),
            g: Vec::new(),
            tmp: Vec::new(),
            tmp2: Vec::new(),
            fe: Vec::new(),
            nz: Vec::new(),
        }
    }
}

fn resize(v: &mut Vec<f64>, len: usize) {
    v.clear();
    v.resize(len, 0.0);
}

/// The discretized problem on one mesh, as a [`NewtonSystem`].
struct Disc<'a, P: ?Sized> {
    prob: &'a P,
    tab: &'a Tableau,
    mesh: &'a [f64],
    lay: Layout,
    w: &'a mut Work,
    /// Last NaN/∞ met in a residual evaluation (also in rejected Newton trials).
    non_finite: Option<(&'static str, f64)>,
    /// The Newton matrix was factorized on this mesh (its LU is usable for estimates).
    factored: bool,
}

impl<'a, P: Bvp + ?Sized> Disc<'a, P> {
    fn new(prob: &'a P, tab: &'a Tableau, mesh: &'a [f64], w: &'a mut Work) -> Self {
        let Dims { n, k } = prob.dims();
        let stride = if tab.internal { tab.q * n } else { n };
        let lay = Layout {
            nodes: mesh.len(),
            n,
            k,
            stride,
        };
        let npts = tab.q * (mesh.len() - 1) + 1;
        resize(&mut w.ypts, npts * n);
        resize(&mut w.fpts, npts * n);
        // The points of one interval (see `linearize`).
        resize(&mut w.jz, (tab.q + 1) * n * n);
        resize(&mut w.jp, (tab.q + 1) * n * k);
        resize(&mut w.ga, (n + k) * n);
        resize(&mut w.gb, (n + k) * n);
        resize(&mut w.gp, (n + k) * k);
        resize(&mut w.g, n + k);
        resize(&mut w.tmp, n);
        resize(&mut w.tmp2, n);
        resize(&mut w.fe, n);
        w.fd.resize(Dims { n, k });
        w.u_at.clear();
        Disc {
            prob,
            tab,
            mesh,
            lay,
            w,
            non_finite: None,
            factored: false,
        }
    }

    fn npts(&self) -> usize {
        self.tab.q * self.lay.intervals() + 1
    }

    /// Interval and abscissa index of point `pt` (the last point is the right end of the last interval).
    fn point(&self, pt: usize) -> (usize, usize) {
        let q = self.tab.q;
        if pt == self.npts() - 1 {
            (self.lay.intervals() - 1, q)
        } else {
            (pt / q, pt % q)
        }
    }

    fn abscissa(&self, i: usize, j: usize) -> f64 {
        let h = self.mesh[i + 1] - self.mesh[i];
        if j == self.tab.q {
            self.mesh[i + 1]
        } else {
            self.mesh[i] + self.tab.c[j] * h
        }
    }

    /// Offset in `u` of the unknowns of point `pt`, if it is stored there.
    fn stored(&self, pt: usize) -> Option<usize> {
        let q = self.tab.q;
        let n = self.lay.n;
        if self.tab.internal {
            Some(pt * n)
        } else if pt % q == 0 {
            Some(pt / q * n)
        } else {
            None
        }
    }

    /// Values and right-hand sides at all points for the unknowns `u`.
    fn eval_points(&mut self, u: &[f64], stats: &mut Stats) -> Result<(), BvpError> {
        let (n, k) = (self.lay.n, self.lay.k);
        let p = &u[self.lay.pcol()..self.lay.pcol() + k];
        for pt in 0..self.npts() {
            if let Some(off) = self.stored(pt) {
                let (i, j) = self.point(pt);
                let s = self.abscissa(i, j);
                self.w.ypts[pt * n..(pt + 1) * n].copy_from_slice(&u[off..off + n]);
                self.rhs_at(pt, s, p, stats)?;
            }
        }
        if !self.tab.internal {
            // Hermite–Simpson midpoint from the node values and slopes.
            for i in 0..self.lay.intervals() {
                let h = self.mesh[i + 1] - self.mesh[i];
                let (p0, pm, p1) = (2 * i, 2 * i + 1, 2 * i + 2);
                for c in 0..n {
                    self.w.ypts[pm * n + c] = 0.5
                        * (self.w.ypts[p0 * n + c] + self.w.ypts[p1 * n + c])
                        - h / 8.0 * (self.w.fpts[p1 * n + c] - self.w.fpts[p0 * n + c]);
                }
                let s = self.abscissa(i, 1);
                self.rhs_at(pm, s, p, stats)?;
            }
        }
        self.w.u_at.clear();
        self.w.u_at.extend_from_slice(u);
        Ok(())
    }

    fn rhs_at(&mut self, pt: usize, s: f64, p: &[f64], stats: &mut Stats) -> Result<(), BvpError> {
        let n = self.lay.n;
        let (y, f) = (
            &self.w.ypts[pt * n..(pt + 1) * n],
            &mut self.w.fpts[pt * n..(pt + 1) * n],
        );
        self.prob.rhs(s, y, p, f);
        stats.rhs_evals += 1;
        if f.iter().all(|v| v.is_finite()) {
            Ok(())
        } else {
            self.non_finite = Some(("rhs", s));
            Err(non_finite("rhs", s))
        }
    }

    fn ensure_points(&mut self, u: &[f64], stats: &mut Stats) -> Result<(), BvpError> {
        if self.w.u_at.as_slice() != u {
            self.eval_points(u, stats)?;
        }
        Ok(())
    }

    /// Rows of interval `i` use abscissae `r ∈ rows()`; row block `r - first`.
    fn row_range(&self) -> std::ops::RangeInclusive<usize> {
        if self.tab.internal {
            1..=self.tab.q
        } else {
            self.tab.q..=self.tab.q
        }
    }

    /// Max |BC residual| and max scaled RMS residual per interval (into `rms`).
    fn estimate(
        &mut self,
        u: &[f64],
        rms: &mut Vec<f64>,
        stats: &mut Stats,
    ) -> Result<(), BvpError> {
        self.ensure_points(u, stats)?;
        let (n, k, q) = (self.lay.n, self.lay.k, self.tab.q);
        let p = &u[self.lay.pcol()..self.lay.pcol() + k];
        rms.clear();
        let mut wi = [[0.0; MAXC]; 3];
        let mut wd = [[0.0; MAXC]; 3];
        for t in 0..3 {
            self.tab.weights(EST_T[t], &mut wi[t], &mut wd[t]);
        }
        for i in 0..self.lay.intervals() {
            let h = self.mesh[i + 1] - self.mesh[i];
            let mut sum = 0.0;
            for t in 0..3 {
                let (sv, dv) = (&mut self.w.tmp, &mut self.w.tmp2);
                for c in 0..n {
                    let mut si = self.w.ypts[q * i * n + c];
                    let mut di = 0.0;
                    for j in 0..=q {
                        let fj = self.w.fpts[(q * i + j) * n + c];
                        si += h * wi[t][j] * fj;
                        di += wd[t][j] * fj;
                    }
                    sv[c] = si;
                    dv[c] = di;
                }
                let s = self.mesh[i] + EST_T[t] * h;
                let f = &mut self.w.fe;
                self.prob.rhs(s, sv, p, f);
                stats.rhs_evals += 1;
                let mut ss = 0.0;
                for c in 0..n {
                    let r = (dv[c] - f[c]) / (1.0 + f[c].abs());
                    ss += r * r;
                }
                if !ss.is_finite() {
                    return Err(non_finite("rhs", s));
                }
                sum += EST_W[t] * ss;
            }
            rms.push(sum.sqrt());
        }
        Ok(())
    }

    /// Max |g| at `u` (points must be current).
    fn bc_residual(&mut self, u: &[f64], stats: &mut Stats) -> f64 {
        let (n, k) = (self.lay.n, self.lay.k);
        let last = self.npts() - 1;
        let p = &u[self.lay.pcol()..self.lay.pcol() + k];
        self.prob.bc(
            &self.w.ypts[..n],
            &self.w.ypts[last * n..(last + 1) * n],
            p,
            &mut self.w.g[..n + k],
        );
        stats.bc_evals += 1;
        self.w.g[..n + k]
            .iter()
            .fold(0.0, |m: f64, v| m.max(v.abs()))
    }

    /// Estimate of `‖J⁻¹ diag(w)‖∞` (`w` the Newton row scales): how much a scaled residual of
    /// size 1 can move the discrete solution. Two solves with the last LU on this mesh (`J(u)`
    /// formed and factorized here if Newton accepted `u` without a factorization on this mesh),
    /// right-hand sides `w` and `(−1)ⁱ w`.
    fn amplification(&mut self, u: &[f64], stats: &mut Stats) -> Result<f64, BvpError> {
        self.ensure_points(u, stats)?;
        if !self.factored {
            // The boundary Jacobian's finite differences need g(u) as their base values.
            self.bc_residual(u, stats);
            self.linearize(u, stats)?;
        }
        let dim = self.lay.dim();
        let mut w = vec![1.0; dim];
        self.residual_scale(u, &mut w);
        let mut best = 0.0_f64;
        for sign in [1.0, -1.0] {
            let mut x: Vec<f64> = w
                .iter()
                .enumerate()
                .map(|(i, wi)| if i % 2 == 0 { *wi } else { sign * wi })
                .collect();
            self.w.sys.solve(&mut x).map_err(|_| singular())?;
            best = best.max(x.iter().fold(0.0_f64, |m, v| m.max(v.abs())));
        }
        Ok(best)
    }

    /// `z'' = d/ds F(s, z(s), p)` at both ends of every interval, each from inside its
    /// interval ([`Dense::QuinticIntervals`]): along the solution's tangent `(1, F)`,
    /// `g(δ) = F(s ± δ, z ± δ F, p)` has `g'(0) = z''` exactly (the tangent's `O(δ²)` departure
    /// from the solution enters only `g''`), and the one-sided second-order difference
    /// `(−3 g(0) + 4 g(δ) − g(2δ)) / 2δ` with `δ = ∛ε · h` has a relative error `O(ε^⅔)`, far
    /// below the 6th-order nodal accuracy once multiplied by `h²` in the quintic. `F` is never
    /// evaluated outside `[a, b]` or across a node: a central difference there averaged the two
    /// sides of a kink of `F` at a node (or read `F` outside the interval at its ends), which cost
    /// the interpolant 3 800× the tolerance on `y'' = −|y|`, `y(0) = 0`.
    fn second_derivatives(
        &mut self,
        p: &[f64],
        z: &[f64],
        dz: &[f64],
        stats: &mut Stats,
    ) -> Vec<f64> {
        let n = self.lay.n;
        let m = self.mesh;
        let mut d2 = vec![0.0; 2 * n * (m.len() - 1)];
        let (mut g1, mut g2) = (vec![0.0; n], vec![0.0; n]);
        for i in 0..m.len() - 1 {
            let d = f64::EPSILON.cbrt() * (m[i + 1] - m[i]);
            for (end, node, sign) in [(0, i, 1.0), (1, i + 1, -1.0)] {
                let (zi, fi) = (&z[node * n..(node + 1) * n], &dz[node * n..(node + 1) * n]);
                for (step, g) in [(d, &mut g1), (2.0 * d, &mut g2)] {
                    let tmp = &mut self.w.tmp;
                    for c in 0..n {
                        tmp[c] = zi[c] + sign * step * fi[c];
                    }
                    self.prob.rhs(m[node] + sign * step, tmp, p, g);
                }
                stats.rhs_evals += 2;
                let out = &mut d2[(2 * i + end) * n..(2 * i + end + 1) * n];
                for c in 0..n {
                    let v = sign * (-3.0 * fi[c] + 4.0 * g1[c] - g2[c]) / (2.0 * d);
                    // NaN/∞ inside the interval (F undefined there): fall back to 0, i.e.
                    // the quintic degrades to a Hermite-like interpolant there.
                    out[c] = if v.is_finite() { v } else { 0.0 };
                }
            }
        }
        d2
    }

    /// The second derivatives of the collocation polynomial at both ends of interval `i`
    /// (points current) into `out` (`2n`: left end, right end): with them the quintic Hermite of
    /// [`Dense::QuinticIntervals`] is that polynomial itself (it reproduces degree ≤ 5).
    fn collocation_second_derivatives(&self, i: usize, out: &mut [f64]) {
        let (n, q) = (self.lay.n, self.tab.q);
        let h = self.mesh[i + 1] - self.mesh[i];
        for (end, t) in [(0, 0.0), (1, 1.0)] {
            let mut sec = [0.0; MAXC];
            self.tab.second(t, &mut sec);
            for c in 0..n {
                let mut v = 0.0;
                for j in 0..=q {
                    v += sec[j] * self.w.fpts[(q * i + j) * n + c];
                }
                out[end * n + c] = v / h;
            }
        }
    }

    /// Nodal values and slopes (node-major) of the current points.
    fn nodal(&self) -> (Vec<f64>, Vec<f64>) {
        let (n, q) = (self.lay.n, self.tab.q);
        let mut z = Vec::with_capacity(self.lay.nodes * n);
        let mut dz = Vec::with_capacity(self.lay.nodes * n);
        for i in 0..self.lay.nodes {
            z.extend_from_slice(&self.w.ypts[q * i * n..(q * i + 1) * n]);
            dz.extend_from_slice(&self.w.fpts[q * i * n..(q * i + 1) * n]);
        }
        (z, dz)
    }
}

impl<P: Bvp + ?Sized> NewtonSystem for Disc<'_, P> {
    fn residual_scale(&mut self, u: &[f64], w: &mut [f64]) -> bool {
        if self.w.u_at.as_slice() != u {
            return false;
        }
        // Collocation rows of interval i, component c: 1 + max |F_c| over the interval's points
        // (the rows are in units of z'); boundary rows as given.
        let (n, q) = (self.lay.n, self.tab.q);
        let per = self.lay.stride / n;
        for i in 0..self.lay.intervals() {
            for c in 0..n {
                let mut m = 0.0_f64;
                for j in 0..=q {
                    m = m.max(self.w.fpts[(q * i + j) * n + c].abs());
                }
                for r in 0..per {
                    w[i * self.lay.stride + r * n + c] = 1.0 + m;
                }
            }
        }
        let b = self.lay.bcrow();
        w[b..].fill(1.0);
        true
    }

    fn residual(&mut self, u: &[f64], r: &mut [f64], stats: &mut Stats) -> Result<(), BvpError> {
        self.eval_points(u, stats)?;
        let (n, k, q) = (self.lay.n, self.lay.k, self.tab.q);
        let first = *self.row_range().start();
        for i in 0..self.lay.intervals() {
            let h = self.mesh[i + 1] - self.mesh[i];
            let y0 = q * i * n;
            for rr in self.row_range() {
                let row0 = i * self.lay.stride + (rr - first) * n;
                let yr = (q * i + rr) * n;
                for c in 0..n {
                    let mut v = (self.w.ypts[yr + c] - self.w.ypts[y0 + c]) / h;
                    for j in 0..=q {
                        v -= self.tab.a[rr][j] * self.w.fpts[(q * i + j) * n + c];
                    }
                    r[row0 + c] = v;
                }
            }
        }
        let b = self.lay.bcrow();
        let last = self.npts() - 1;
        let p = &u[self.lay.pcol()..self.lay.pcol() + k];
        self.prob.bc(
            &self.w.ypts[..n],
            &self.w.ypts[last * n..(last + 1) * n],
            p,
            &mut r[b..b + n + k],
        );
        stats.bc_evals += 1;
        if r[b..b + n + k].iter().any(|v| !v.is_finite()) {
            self.non_finite = Some(("bc", f64::NAN));
            return Err(non_finite("bc", f64::NAN));
        }
        Ok(())
    }

    fn solve_linearized(
        &mut self,
        u: &[f64],
        r: &[f64],
        du: &mut [f64],
        stats: &mut Stats,
    ) -> Result<(), BvpError> {
        self.ensure_points(u, stats)?;
        // `r = R(u)` (the trait's contract): its boundary rows are g(u).
        let b = self.lay.bcrow();
        self.w.g[..r.len() - b].copy_from_slice(&r[b..]);
        self.linearize(u, stats)?;
        for (d, v) in du.iter_mut().zip(r) {
            *d = -v;
        }
        self.w.sys.solve(du).map_err(|_| singular())
    }

    fn resolve(&mut self, r: &[f64], du: &mut [f64]) -> Result<bool, BvpError> {
        if !self.factored {
            return Ok(false);
        }
        for (d, v) in du.iter_mut().zip(r) {
            *d = -v;
        }
        self.w.sys.solve(du).map_err(|_| singular())?;
        Ok(true)
    }
}

impl<'a, P: Bvp + ?Sized> Disc<'a, P> {
    /// Forms the Newton matrix `J(u)` in the ABD blocks and factorizes it. The points must be
    /// current at `u` and `w.g` must hold `g(u)` (the base values of the boundary Jacobian's
    /// finite differences; a wrong base shifts every column of it by `(g(u) − base)/δ`).
    fn linearize(&mut self, u: &[f64], stats: &mut Stats) -> Result<(), BvpError> {
        let (n, k, q) = (self.lay.n, self.lay.k, self.tab.q);
        let pc = self.lay.pcol();
        let p = &u[pc..pc + k];
        let (nn, nk) = (n * n, n * k);
        // The LU is replaced from here on, even if a Jacobian below fails.
        self.factored = false;
        self.w.sys.prepare(self.lay).map_err(|_| singular())?;
        let rows = self.row_range();
        let last = self.npts() - 1;
        let internal = self.tab.internal;
        let a = self.tab.a;
        let lay = self.lay;
        let w = &mut *self.w;
        for i in 0..lay.intervals() {
            // Jacobians of F at the interval's points, in slots 0..=q (the left end's is the
            // last interval's right end): one interval's, not every point's (`n²` doubles
            // each, mostly zeros for a large system, that a fresh solver pays in page faults).
            if i > 0 {
                w.jz.copy_within(q * nn..(q + 1) * nn, 0);
                w.jp.copy_within(q * nk..(q + 1) * nk, 0);
            }
            for j in usize::from(i > 0)..=q {
                let pt = q * i + j;
                let s = if j == q {
                    self.mesh[i + 1]
                } else {
                    self.mesh[i] + self.tab.c[j] * (self.mesh[i + 1] - self.mesh[i])
                };
                rhs_jacobian_or_fd(
                    self.prob,
                    s,
                    &w.ypts[pt * n..(pt + 1) * n],
                    p,
                    Some(&w.fpts[pt * n..(pt + 1) * n]),
                    &mut w.jz[j * nn..(j + 1) * nn],
                    &mut w.jp[j * nk..(j + 1) * nk],
                    &mut w.fd,
                    stats,
                )?;
            }
            let h = self.mesh[i + 1] - self.mesh[i];
            // Rows in order (abscissa `rr`, then component `c`), as `push_row` expects.
            for rr in rows.clone() {
                for c in 0..n {
                    let out = w.sys.row_mut();
                    out.fill(0.0);
                    if internal {
                        // ∂/∂Y_j = (δ_rj − δ_0j) I / h − a_rj J_j; ∂/∂p = −Σ a_rj Jp_j.
                        for j in 0..=q {
                            let jz = &w.jz[j * nn + c * n..j * nn + (c + 1) * n];
                            for (d, v) in jz.iter().enumerate() {
                                out[j * n + d] -= a[rr][j] * v;
                            }
                            let jp = &w.jp[j * nk + c * k..j * nk + (c + 1) * k];
                            for (e, v) in jp.iter().enumerate() {
                                out[lay.stride + n + e] -= a[rr][j] * v;
                            }
                        }
                        out[c] -= 1.0 / h;
                        out[rr * n + c] += 1.0 / h;
                    } else {
                        // Condensed midpoint: Y_1 = (z0 + z1)/2 − h (f2 − f0)/8.
                        // Slots of the left end, the midpoint and the right end.
                        let (p0, pm, p1) = (0, 1, 2);
                        let jm = &w.jz[pm * nn + c * n..pm * nn + (c + 1) * n];
                        let (b0, b1, b2) = (a[2][0], a[2][1], a[2][2]);
                        // Row c of Jm · (I/2 ± h/8 J_{0,2}), by rows of J_{0,2} and skipping the
                        // zeros of Jm: O(n · nonzeros of the row) instead of O(n²).
                        let (m0, m1) = (&mut w.tmp[..n], &mut w.tmp2[..n]);
                        for d in 0..n {
                            m0[d] = 0.5 * jm[d];
                            m1[d] = 0.5 * jm[d];
                        }
                        w.nz.clear();
                        w.nz.extend((0..n).filter(|&e| jm[e] != 0.0));
                        for &e in &w.nz {
                            let t = jm[e] * h / 8.0;
                            if t != 0.0 {
                                let j0 = &w.jz[p0 * nn + e * n..p0 * nn + (e + 1) * n];
                                let j2 = &w.jz[p1 * nn + e * n..p1 * nn + (e + 1) * n];
                                for d in 0..n {
                                    m0[d] += t * j0[d];
                                    m1[d] -= t * j2[d];
                                }
                            }
                        }
                        for d in 0..n {
                            out[d] = -b0 * w.jz[p0 * nn + c * n + d] - b1 * m0[d];
                            out[n + d] = -b2 * w.jz[p1 * nn + c * n + d] - b1 * m1[d];
                        }
                        out[c] -= 1.0 / h;
                        out[n + c] += 1.0 / h;
                        for e in 0..k {
                            let mut dm = w.jp[pm * nk + c * k + e];
                            // Zeros of Jm add nothing: O(nonzeros) per entry, not O(n).
                            for &d in &w.nz {
                                dm -= jm[d] * h / 8.0
                                    * (w.jp[p1 * nk + d * k + e] - w.jp[p0 * nk + d * k + e]);
                            }
                            out[2 * n + e] = -b0 * w.jp[p0 * nk + c * k + e]
                                - b2 * w.jp[p1 * nk + c * k + e]
                                - b1 * dm;
                        }
                    }
                    w.sys.push_row();
                }
            }
        }
        // Boundary block.
        let m = n + k;
        bc_jacobian_or_fd(
            self.prob,
            &w.ypts[..n],
            &w.ypts[last * n..(last + 1) * n],
            p,
            Some(&w.g[..m]),
            &mut w.ga,
            &mut w.gb,
            &mut w.gp,
            &mut w.fd,
            stats,
        )?;
        let bw = 2 * n + k;
        for rb in 0..m {
            let row = &mut w.sys.bc[rb * bw..(rb + 1) * bw];
            row[..n].copy_from_slice(&w.ga[rb * n..(rb + 1) * n]);
            row[n..2 * n].copy_from_slice(&w.gb[rb * n..(rb + 1) * n]);
            row[2 * n..].copy_from_slice(&w.gp[rb * k..(rb + 1) * k]);
        }
        stats.factorizations += 1;
        w.sys.factor().map_err(|_| singular())?;
        self.factored = true;
        Ok(())
    }
}

/// A converged discrete solution kept to interpolate starting values on a new mesh.
struct Snapshot {
    mesh: Vec<f64>,
    ypts: Vec<f64>,
    fpts: Vec<f64>,
    params: Vec<f64>,
}

impl Snapshot {
    /// The unknowns on `mesh` interpolated from this solution (its collocation polynomials).
    fn fill(&self, tab: &Tableau, dims: Dims, mesh: &[f64], u: &mut Vec<f64>) {
        fill_unknowns(
            tab,
            mesh,
            dims,
            &self.params,
            |s, o| self.eval(tab, dims.n, s, o),
            u,
        );
    }

    /// Evaluates the collocation polynomial `S` at `s`.
    fn eval(&self, tab: &Tableau, n: usize, s: f64, out: &mut [f64]) {
        let q = tab.q;
        let last = self.mesh.len() - 1;
        if s >= self.mesh[last] {
            out.copy_from_slice(&self.ypts[q * last * n..(q * last + 1) * n]);
            return;
        }
        let i = locate(&self.mesh, s);
        let h = self.mesh[i + 1] - self.mesh[i];
        let t = ((s - self.mesh[i]) / h).clamp(0.0, 1.0);
        let mut wi = [0.0; MAXC];
        tab.weights(t, &mut wi, &mut [0.0; MAXC]);
        for c in 0..n {
            let mut v = self.ypts[q * i * n + c];
            for (j, wj) in wi.iter().enumerate().take(q + 1) {
                v += h * wj * self.fpts[(q * i + j) * n + c];
            }
            out[c] = v;
        }
    }
}

/// Fills the unknowns for `mesh` from `src(s, out)` and the parameters.
fn fill_unknowns(
    tab: &Tableau,
    mesh: &[f64],
    dims: Dims,
    params: &[f64],
    mut src: impl FnMut(f64, &mut [f64]),
    u: &mut Vec<f64>,
) {
    let n = dims.n;
    let per = if tab.internal { tab.q } else { 1 };
    let nint = mesh.len() - 1;
    u.clear();
    u.resize(nint * per * n + n + dims.k, 0.0);
    for i in 0..nint {
        let h = mesh[i + 1] - mesh[i];
        for j in 0..per {
            let off = (i * per + j) * n;
            src(mesh[i] + tab.c[j] * h, &mut u[off..off + n]);
        }
    }
    let off = nint * per * n;
    src(mesh[nint], &mut u[off..off + n]);
    u[off + n..].copy_from_slice(params);
}

fn uniform(a: f64, b: f64, nodes: usize) -> Vec<f64> {
    (0..nodes)
        .map(|i| {
            if i == nodes - 1 {
                b
            } else {
                a + (b - a) * i as f64 / (nodes - 1) as f64
            }
        })
        .collect()
}

fn bisect(mesh: &[f64]) -> Vec<f64> {
    let mut out = Vec::with_capacity(2 * mesh.len() - 1);
    for w in mesh.windows(2) {
        out.push(w[0]);
        out.push(0.5 * (w[0] + w[1]));
    }
    out.push(mesh[mesh.len() - 1]);
    out
}

/// New mesh from the interval residuals: split where `rms > tol`, merge pairs below `tol/100`
/// (if `merge`), keep the rest.
fn adapt_mesh(mesh: &[f64], rms: &[f64], tol: f64, refine: bool, merge: bool) -> Vec<f64> {
    let low = tol / 100.0;
    let mut out = Vec::with_capacity(mesh.len() + 8);
    let nint = rms.len();
    let mut i = 0;
    while i < nint {
        let (s0, s1) = (mesh[i], mesh[i + 1]);
        out.push(s0);
        if merge && i + 1 < nint && rms[i] < low && rms[i + 1] < low {
            i += 2; // drop node i + 1
            continue;
        }
        if refine && rms[i] > tol {
            if rms[i] < 100.0 * tol {
                out.push(0.5 * (s0 + s1));
            } else {
                out.push(s0 + (s1 - s0) / 3.0);
                out.push(s0 + 2.0 * (s1 - s0) / 3.0);
            }
        }
        i += 1;
    }
    out.push(mesh[nint]);
    if out.len() < 3 {
        out = vec![mesh[0], 0.5 * (mesh[0] + mesh[nint]), mesh[nint]];
    }
    out
}

impl Collocation {
    /// The starting mesh: the guess mesh if it has ≥ 3 nodes (validated: strictly increasing,
    /// spanning `[a, b]`), else the uniform default.
    fn initial_mesh(&self, guess: &Guess, a: f64, b: f64) -> Vec<f64> {
        let m = &guess.mesh;
        if m.len() >= 3 {
            let mut mesh = m.clone();
            mesh[0] = a;
            let last = mesh.len() - 1;
            mesh[last] = b;
            mesh
        } else {
            uniform(a, b, DEFAULT_NODES)
        }
    }
}

impl BvpSolver for Collocation {
    fn tolerance(&self) -> Option<f64> {
        Some(self.opts.tol)
    }

    /// Sets `tol` (values outside `(0, 1)` are ignored).
    fn set_tolerance(&mut self, tol: f64) {
        if tol > 0.0 && tol < 1.0 {
            self.opts.tol = tol;
        }
    }

    fn solve<P: Bvp + ?Sized>(&mut self, problem: &P, guess: &Guess) -> Result<Solution, BvpError> {
        self.solve_observed(problem, guess, &mut |_| {})
    }

    /// With [`ErrorControl::Confirmed`], steps of a walk are solved under
    /// [`ErrorControl::Residual`] (the guard and its confirmation are for results: on the
    /// Cash–Mazzia set they made continuation 1.6× (Lobatto4) and 4.8× (Lobatto6) slower on 5
    /// problems), and the walk's last member is to be solved again (returns `true`).
    fn set_walking(&mut self, walking: bool) -> bool {
        self.walking = walking;
        self.opts.control == ErrorControl::Confirmed
    }
}

impl Collocation {
    /// [`BvpSolver::solve`] of a problem without a singular term: mesh passes ([`run::Run`])
    /// until one returns.
    fn solve_plain<P: Bvp + ?Sized>(
        &mut self,
        problem: &P,
        guess: &Guess,
        observer: &mut dyn FnMut(&Progress<'_>),
    ) -> Result<Solution, BvpError> {
        guess.validate(problem.dims(), problem.interval())?;
        let (a, b) = problem.interval();
        let mut opts = self.opts.clone();
        if self.walking && opts.control == ErrorControl::Confirmed {
            opts.control = ErrorControl::Residual;
        }
        let mut nopts = opts.newton.clone();
        nopts.tol = nopts.tol.min(opts.tol / 20.0).min(opts.bc_tol());
        let mesh = self.initial_mesh(guess, a, b);
        let cx = Ctx {
            opts: &opts,
            nopts,
            tab: &self.tab,
            dims: problem.dims(),
            guess,
        };
        self.guard = None;
        self.confirmed = None;
        let mut run = Run::start(&cx, mesh)?;
        loop {
            self.guard = run.guard;
            self.confirmed = run.confirmed;
            if run.stats.mesh_passes >= opts.max_mesh_passes {
                return run.out_of_passes(&cx);
            }
            run.stats.mesh_passes += 1;
            let mesh = std::mem::take(&mut run.mesh);
            run.stats.nodes = mesh.len();
            let mut disc = Disc::new(problem, &self.tab, &mesh, &mut self.work);
            let next = match run.newton(&cx, &mut self.newton, &mut disc) {
                Err(e) => {
                    observer(&Progress {
                        pass: run.stats.mesh_passes,
                        mesh: &mesh,
                        newton_iters: run.stats.newton_iters,
                        newton_converged: false,
                        residual: run.stats.residual,
                        residuals: &[],
                    });
                    run.after_failure(&cx, &mut disc, &mesh, e)
                }
                Ok(()) => run.after_newton(&cx, &mut disc, &mesh, observer),
            };
            if run.mesh.is_empty() {
                run.mesh = mesh;
            }
            if let Next::Done(result) = next {
                self.guard = run.guard;
                self.confirmed = run.confirmed;
                return result;
            }
        }
    }
}

fn snapshot<P: Bvp + ?Sized>(disc: &Disc<'_, P>, mesh: &[f64], u: &[f64]) -> Snapshot {
    Snapshot {
        mesh: mesh.to_vec(),
        ypts: disc.w.ypts.clone(),
        fpts: disc.w.fpts.clone(),
        params: u[disc.lay.pcol()..].to_vec(),
    }
}

/// `sol` with the work counters of the whole solve (its own accuracy figures kept).
fn with_total_stats(mut sol: Solution, stats: &Stats) -> Solution {
    let mut total = stats.clone();
    total.nodes = sol.mesh.len();
    total.error_estimate = sol.stats.error_estimate;
    total.residual = sol.stats.residual;
    sol.stats = total;
    sol
}

fn attach_stats(e: BvpError, stats: &Stats) -> BvpError {
    let it = match &e {
        BvpError::SingularJacobian { iteration, .. } | BvpError::Stalled { iteration, .. } => {
            *iteration
        }
        _ => stats.newton_iters,
    };
    attach(e, it, stats)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::samples::{FiniteDifferences, Parabola};

    /// The conditioning estimate on the exact discrete solution of [`Parabola`] (6 nodes, as
    /// after coarsening), from a `Disc` that has (`factor_first`) or has not factorized there.
    fn amplification(scheme: Scheme, prob: &impl Bvp, factor_first: bool) -> f64 {
        let tab = Tableau::new(scheme);
        let exact = Parabola { end: 1.0 };
        let mesh = uniform(0.0, 1.0, 6);
        let mut u = Vec::new();
        let src = |s: f64, z: &mut [f64]| z.copy_from_slice(&exact.exact(s));
        fill_unknowns(&tab, &mesh, prob.dims(), &[exact.parameter()], src, &mut u);
        let mut work = Work::default();
        let mut disc = Disc::new(prob, &tab, &mesh, &mut work);
        let mut stats = Stats::default();
        let mut r = vec![0.0; u.len()];
        disc.residual(&u, &mut r, &mut stats).unwrap();
        assert!(norm_max(&r) < 1e-13, "not the discrete solution");
        if factor_first {
            let mut du = vec![0.0; u.len()];
            disc.solve_linearized(&u, &r, &mut du, &mut stats).unwrap();
            assert!(norm_max(&du) < 1e-13);
        }
        disc.amplification(&u, &mut stats)
            .unwrap_or_else(|e| panic!("{scheme:?} factorized {factor_first}: {e}"))
    }

    fn norm_max(v: &[f64]) -> f64 {
        v.iter().fold(0.0, |m, x| m.max(x.abs()))
    }

    #[test]
    fn amplification_uses_the_jacobian_at_the_solution_whether_or_not_newton_factorized() {
        // Reference: analytic Jacobians, factorized by a Newton step first. Forward differences
        // (step √ε) must agree to about √ε on every path; a boundary Jacobian differenced
        // against the wrong base values is off by ~1/√ε in every entry (it was: 15.3 and 16.4
        // against 9.4 and 9.9, and singular on the continuation test's coarsened mesh).
        let analytic = Parabola { end: 1.0 };
        let fd = FiniteDifferences(analytic);
        for scheme in [Scheme::Lobatto4, Scheme::Lobatto6] {
            let reference = amplification(scheme, &analytic, true);
            for (a, what) in [
                (
                    amplification(scheme, &analytic, false),
                    "analytic, unfactorized",
                ),
                (amplification(scheme, &fd, true), "differences, factorized"),
                (
                    amplification(scheme, &fd, false),
                    "differences, unfactorized",
                ),
            ] {
                assert!(
                    (a - reference).abs() <= 1e-6 * reference,
                    "{scheme:?} {what}: {a} vs {reference}"
                );
            }
        }
    }
}
