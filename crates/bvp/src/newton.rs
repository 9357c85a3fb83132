//! Damped Newton iteration shared by the solvers.
//!
//! # Method
//!
//! Solve `R(u) = 0` for `u ∈ Rᴺ`. Each iteration solves the linearized system `J(u) Δu = −R(u)`
//! (the linear algebra is the caller's: [`NewtonSystem::solve_linearized`], dense LU for shooting,
//! sparse for collocation) and takes `u ← u + λ Δu` with a backtracking line search on the merit
//! function `φ(u) = ½ ‖R(u)‖₂²` (Armijo rule):
//!
//! ```text
//!     accept λ if  φ(u + λΔu) ≤ (1 − 2σλ) φ(u),        σ = 1e-4
//! ```
//!
//! which is the Armijo condition `φ(u+λΔu) ≤ φ(u) + σλ φ'(u)[Δu]` with `φ'(u)[Δu] = −2φ(u)` for an
//! exact Newton direction. Trial `λ` starts at 1 every iteration (so the full step, and quadratic
//! convergence, is always tried); on failure the next trial minimizes the quadratic model of
//! `φ(λ)` through `φ(0)`, `φ'(0)` and the failed value, safeguarded to `[0.1 λ, 0.5 λ]`. A trial
//! whose residual is NaN/∞ (e.g. the step left the domain of the right-hand side) is treated as a
//! failed trial and `λ` is quartered. This is the plain residual-based (not Deuflhard's
//! affine-invariant) damping: it is cheap and adequate when the unknowns are reasonably scaled.
//!
//! # Scaling
//!
//! A system may scale its rows ([`NewtonSystem::residual_scale`]): every norm below is then of
//! `R_i / w_i`, with `w` refreshed at each accepted iterate and held fixed during its line
//! search (so `φ` is a fixed quadratic merit function per iteration and the Armijo test above
//! holds for the Newton direction). Collocation scales its rows (units of `z'`) by
//! `1 + max |F|` over the interval, so a layer where `|z'| ~ 1e6` is judged relative to its size
//! instead of against an absolute residual rounding cannot reach; shooting does not scale.
//!
//! # Termination
//!
//! - converged: `‖R(u)‖∞ ≤ tol` (checked at the start too, so an exact guess costs no iteration);
//! - converged at the precision floor: `‖R(u)‖∞ ≤ step_residual_tol` and either the Newton step
//!   satisfies `‖Δu‖∞ ≤ step_tol · (1 + ‖u‖∞)`, or (scaled rows only) the full step no longer
//!   decreases `φ` (rounding, not stagnation);
//! - [`BvpError::Stalled`]: `λ` fell below `min_damping` without an acceptable decrease while the
//!   residual is above `step_residual_tol` (real stagnation; the message names the options);
//! - [`BvpError::MaxIterations`]: `max_iter` linearizations without convergence;
//! - [`BvpError::SingularJacobian`], [`BvpError::NonFinite`]: reported by the system (or a
//!   non-finite Newton step / initial residual, detected here).
//!
//! Statistics: `newton_iters` (linearizations) and `residual` (final `‖R‖∞`) are updated here; the
//! system updates the evaluation counters and `factorizations` through the `&mut Stats` it gets.
//! Errors returned by the system may carry placeholder statistics: the driver replaces them (and
//! the iteration number) with the current ones, see [`attach`].

use crate::{BvpError, Stats};

/// Armijo constant `σ` of the sufficient-decrease test.
const ARMIJO: f64 = 1e-4;

/// Options of the damped Newton iteration.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct NewtonOptions {
    /// Maximum Newton iterations. Default 50.
    pub max_iter: usize,
    /// Convergence: max-norm of the residual below `tol`. Default 1e-10.
    pub tol: f64,
    /// Convergence: max-norm of the step below `step_tol · (1 + |u|)`. Default 1e-12.
    pub step_tol: f64,
    /// Smallest damping factor of the line search before declaring a stall. Default 1e-6.
    pub min_damping: f64,
    /// Precision floor: at or below this (scaled) residual max-norm, a negligible step or (scaled
    /// rows) a full step that cannot decrease the residual counts as convergence; above it, a
    /// line search that fails is [`BvpError::Stalled`]. Default 1e-8.
    pub step_residual_tol: f64,
    /// Damping strategy. Default [`Damping::Armijo`]; collocation uses
    /// [`Damping::AffineInvariant`] when the system supports it (see [`crate::collocation`]).
    pub damping: Damping,
}

/// How the Newton step is damped (see the module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub enum Damping {
    /// Backtracking on the (scaled) residual norm with the Armijo rule.
    #[default]
    Armijo,
    /// Deuflhard's error-oriented, affine-invariant damping (NLEQ-ERR): a trial is accepted
    /// when the simplified Newton correction `Δ̄u = −J(u)⁻¹R(u + λΔu)` (same factorization)
    /// satisfies the monotonicity test `‖Δ̄u‖ ≤ (1 − λ/4)‖Δu‖` in the norm weighted by
    /// `1 + |u_i|`; `λ` is predicted from the previous step's contraction and corrected from
    /// the failed trial. Invariant under rescaling of the equations, so badly scaled residual
    /// rows (layers) do not steer the step. Falls back to `Armijo` for systems that cannot
    /// re-solve with their factorization ([`NewtonSystem::resolve`]).
    AffineInvariant,
}

impl Default for NewtonOptions {
    fn default() -> Self {
        NewtonOptions {
            max_iter: 50,
            tol: 1e-10,
            step_tol: 1e-12,
            min_damping: 1e-6,
            step_residual_tol: 1e-8,
            damping: Damping::Armijo,
        }
    }
}

impl NewtonOptions {
    /// Checks the ranges: `max_iter ≥ 1`, `tol > 0`, `step_tol ≥ 0`, `0 < min_damping ≤ 1`,
    /// `step_residual_tol ≥ 0` (all finite).
    pub fn validate(&self) -> Result<(), BvpError> {
        if self.max_iter < 1 {
            return Err(invalid("newton.max_iter", self.max_iter, "must be >= 1"));
        }
        if !(self.tol > 0.0 && self.tol.is_finite()) {
            return Err(invalid("newton.tol", self.tol, "must be finite and > 0"));
        }
        if !(self.step_tol >= 0.0 && self.step_tol.is_finite()) {
            return Err(invalid(
                "newton.step_tol",
                self.step_tol,
                "must be finite and >= 0",
            ));
        }
        if !(self.min_damping > 0.0 && self.min_damping <= 1.0) {
            return Err(invalid(
                "newton.min_damping",
                self.min_damping,
                "must be in (0, 1]",
            ));
        }
        if !(self.step_residual_tol >= 0.0 && self.step_residual_tol.is_finite()) {
            return Err(invalid(
                "newton.step_residual_tol",
                self.step_residual_tol,
                "must be finite and >= 0",
            ));
        }
        Ok(())
    }
}

fn invalid(name: &'static str, value: impl std::fmt::Display, reason: &'static str) -> BvpError {
    BvpError::InvalidOption {
        name,
        value: value.to_string(),
        reason,
    }
}

/// A nonlinear system `R(u) = 0` as seen by [`Newton`].
///
/// Implementations own the Jacobian and its factorization; they may cache work between the calls
/// (e.g. shooting integrates the variational equations during `residual` and reuses them in
/// `solve_linearized` when `u` is unchanged).
pub trait NewtonSystem {
    /// Writes `R(u)` into `r`; counts evaluations in `stats`. Return
    /// [`BvpError::NonFinite`] if a NaN/∞ appears where its location is known (else the driver
    /// detects non-finite `r` itself).
    fn residual(&mut self, u: &[f64], r: &mut [f64], stats: &mut Stats) -> Result<(), BvpError>;

    /// Forms `J(u)` (`r = R(u)` was the last residual evaluated at this `u`), factorizes it and
    /// writes the Newton step `du = −J⁻¹ r`. Counts `factorizations`. Return
    /// [`BvpError::SingularJacobian`] (see [`singular`]) when the matrix is singular.
    fn solve_linearized(
        &mut self,
        u: &[f64],
        r: &[f64],
        du: &mut [f64],
        stats: &mut Stats,
    ) -> Result<(), BvpError>;

    /// Scales `w_i > 0` of the residual rows at `u`, whose residual was the last one evaluated:
    /// convergence, the precision floor and the line search then use `r_i / w_i` (e.g. a
    /// collocation row in units of `z'` divided by `1 + |F|`, so that layers with `|z'| ~ 1e6`
    /// are judged relative to their size). Return `false` (the default) for unscaled rows.
    fn residual_scale(&mut self, _u: &[f64], _w: &mut [f64]) -> bool {
        false
    }

    /// Solves `J du = −r` with the factorization of the last [`NewtonSystem::solve_linearized`]
    /// (for [`Damping::AffineInvariant`]); `Ok(false)` (the default) if not supported.
    fn resolve(&mut self, _r: &[f64], _du: &mut [f64]) -> Result<bool, BvpError> {
        Ok(false)
    }
}

/// A [`BvpError::SingularJacobian`] with placeholder statistics (filled in by the driver).
pub fn singular() -> BvpError {
    BvpError::SingularJacobian {
        iteration: 0,
        stats: Stats::default(),
    }
}

/// A [`BvpError::NonFinite`] with placeholder statistics (filled in by the driver).
pub fn non_finite(location: &'static str, s: f64) -> BvpError {
    BvpError::NonFinite {
        location,
        s,
        stats: Stats::default(),
    }
}

/// Replaces the statistics carried by `err` with `stats` and, for iteration-numbered variants,
/// the iteration with `iteration`.
pub fn attach(mut err: BvpError, iteration: usize, stats: &Stats) -> BvpError {
    match &mut err {
        BvpError::SingularJacobian {
            iteration: it,
            stats: st,
        }
        | BvpError::Stalled {
            iteration: it,
            stats: st,
            ..
        } => {
            *it = iteration;
            *st = stats.clone();
        }
        BvpError::MaxIterations { stats: st, .. }
        | BvpError::NonFinite { stats: st, .. }
        | BvpError::MeshLimit { stats: st, .. }
        | BvpError::StepSizeTooSmall { stats: st, .. }
        | BvpError::Inaccurate { stats: st, .. } => *st = stats.clone(),
        // Input errors carry no statistics; wrapped errors (continuation) keep their own.
        _ => {}
    }
    err
}

/// Damped Newton driver with its work vectors (reuse it to avoid allocation between solves).
#[derive(Clone, Debug, Default)]
pub struct Newton {
    r: Vec<f64>,
    du: Vec<f64>,
    ut: Vec<f64>,
    rt: Vec<f64>,
    w: Vec<f64>,
    /// Affine-invariant damping: the simplified correction of the trial and its predecessor's
    /// values for the next prediction.
    dbar: Vec<f64>,
    iterations: usize,
}

/// RMS norm of `(a_i − c b_i) / (1 + |u_i|)`.
fn wdiff(a: &[f64], b: &[f64], c: f64, u: &[f64]) -> f64 {
    let s: f64 = a
        .iter()
        .zip(b)
        .zip(u)
        .map(|((x, y), w)| {
            let v = (x - c * y) / (1.0 + w.abs());
            v * v
        })
        .sum();
    (s / a.len().max(1) as f64).sqrt()
}

/// RMS norm of `x_i / (1 + |u_i|)`.
fn wnorm(x: &[f64], u: &[f64]) -> f64 {
    wdiff(x, x, 0.0, u)
}

fn max_norm(x: &[f64]) -> f64 {
    x.iter().fold(0.0_f64, |m, v| m.max(v.abs()))
}

/// Scaled max-norm and merit `½ Σ (r_i / w_i)²`.
fn scaled(r: &[f64], w: &[f64]) -> (f64, f64) {
    let (mut f, mut phi) = (0.0_f64, 0.0);
    for (x, s) in r.iter().zip(w) {
        let v = x / s;
        f = f.max(v.abs());
        phi += v * v;
    }
    (f, 0.5 * phi)
}

fn all_finite(x: &[f64]) -> bool {
    x.iter().all(|v| v.is_finite())
}

impl Newton {
    /// A driver with empty buffers (sized on first use).
    pub fn new() -> Self {
        Self::default()
    }

    /// The residual at the returned `u` (valid after [`Newton::solve`] returned `Ok`, and after
    /// most failures: it is the last accepted iterate's residual).
    pub fn residual(&self) -> &[f64] {
        &self.r
    }

    /// Newton iterations of the last solve.
    pub fn iterations(&self) -> usize {
        self.iterations
    }

    /// Refreshes the row scales at `u` (its residual was the last evaluated); true if scaled.
    fn rescale<S: NewtonSystem + ?Sized>(&mut self, sys: &mut S, u: &[f64]) -> bool {
        if sys.residual_scale(u, &mut self.w) {
            for w in &mut self.w {
                if !(*w > 0.0 && w.is_finite()) {
                    *w = 1.0;
                }
            }
            true
        } else {
            false
        }
    }

    /// One affine-invariant damped step from `u` (the Newton step is in `self.du`, `R(u)` in
    /// `self.r`, scaled max-norm `f`): `Ok(None)` if the system cannot re-solve (use Armijo),
    /// `Ok(Some(true))` at the rounding floor, `Ok(Some(false))` after an accepted step (`u`,
    /// `self.r` updated).
    #[allow(clippy::too_many_arguments)]
    fn affine_step<S: NewtonSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        u: &mut [f64],
        opts: &NewtonOptions,
        it: usize,
        f: f64,
        small_step: bool,
        prev: &mut Option<(f64, f64)>,
        stats: &mut Stats,
    ) -> Result<Option<bool>, BvpError> {
        let ndu = wnorm(&self.du, u);
        // Prediction from the last step (`self.dbar` still holds its simplified correction
        // Δ̄u = −J(u_prev)⁻¹R(u)): λ = min(1, ‖Δu_prev‖‖Δ̄u‖ / (‖Δ̄u − Δu‖‖Δu‖) · λ_prev).
        let mut lambda = match *prev {
            Some((lp, ndu_prev)) => {
                let ndbar = wnorm(&self.dbar, u);
                let diff = wdiff(&self.dbar, &self.du, 1.0, u);
                if diff > 0.0 && ndu > 0.0 {
                    (ndu_prev * ndbar / (diff * ndu) * lp).min(1.0)
                } else {
                    1.0
                }
            }
            None => 1.0,
        }
        .max(opts.min_damping);
        let mut reduced = false;
        loop {
            for ((t, &x), &d) in self.ut.iter_mut().zip(u.iter()).zip(&self.du) {
                *t = x + lambda * d;
            }
            let trial = sys.residual(&self.ut, &mut self.rt, stats);
            let finite = match trial {
                Ok(()) => all_finite(&self.rt),
                Err(BvpError::NonFinite { .. }) | Err(BvpError::StepSizeTooSmall { .. }) => false,
                Err(e) => return Err(attach(e, it, stats)),
            };
            let mut next = 0.25 * lambda;
            if finite {
                if !sys.resolve(&self.rt, &mut self.dbar)? {
                    return Ok(None);
                }
                if !all_finite(&self.dbar) {
                    return Err(attach(non_finite("newton step", f64::NAN), it, stats));
                }
                let ndbar = wnorm(&self.dbar, u);
                // ‖Δ̄u − (1 − λ)Δu‖: the nonlinearity seen along the step.
                let diff = wdiff(&self.dbar, &self.du, 1.0 - lambda, u);
                if ndbar <= (1.0 - 0.25 * lambda) * ndu || ndbar == 0.0 {
                    *prev = Some((lambda, ndu));
                    u.copy_from_slice(&self.ut);
                    std::mem::swap(&mut self.r, &mut self.rt);
                    return Ok(Some(false));
                }
                if f <= opts.step_residual_tol && (small_step || lambda == 1.0) {
                    return Ok(Some(true));
                }
                let mu = if diff > 0.0 {
                    0.5 * ndu * lambda * lambda / diff
                } else {
                    0.5 * lambda
                };
                next = mu.min(0.5 * lambda);
            }
            if reduced && next >= lambda {
                next = 0.5 * lambda;
            }
            reduced = true;
            if next < opts.min_damping {
                return Err(attach(
                    BvpError::Stalled {
                        iteration: it,
                        residual: f,
                        stats: Stats::default(),
                    },
                    it,
                    stats,
                ));
            }
            lambda = next;
        }
    }

    /// Runs damped Newton on `sys` from `u` (overwritten by the solution, or by the last accepted
    /// iterate on failure). The residual vector has the length of `u` (square systems).
    pub fn solve<S: NewtonSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        u: &mut [f64],
        opts: &NewtonOptions,
        stats: &mut Stats,
    ) -> Result<(), BvpError> {
        let m = u.len();
        for v in [
            &mut self.r,
            &mut self.du,
            &mut self.ut,
            &mut self.rt,
            &mut self.dbar,
        ] {
            v.clear();
            v.resize(m, 0.0);
        }
        self.w.clear();
        self.w.resize(m, 1.0);
        self.iterations = 0;

        sys.residual(u, &mut self.r, stats)
            .map_err(|e| attach(e, 0, stats))?;
        if !all_finite(&self.r) {
            return Err(attach(non_finite("residual", f64::NAN), 0, stats));
        }
        let rows_scaled = self.rescale(sys, u);
        let (mut f, mut phi) = scaled(&self.r, &self.w);
        stats.residual = f;
        if f <= opts.tol {
            return Ok(());
        }

        // Affine-invariant damping: (λ, ‖Δu‖, ‖Δ̄u − Δu‖-based prediction) of the last step.
        let mut prev: Option<(f64, f64)> = None;
        let mut affine = opts.damping == Damping::AffineInvariant;
        for it in 1..=opts.max_iter {
            self.iterations = it;
            stats.newton_iters += 1;
            sys.solve_linearized(u, &self.r, &mut self.du, stats)
                .map_err(|e| attach(e, it, stats))?;
            if !all_finite(&self.du) {
                return Err(attach(non_finite("newton step", f64::NAN), it, stats));
            }
            let small_step = max_norm(&self.du) <= opts.step_tol * (1.0 + max_norm(u));

            if affine {
                match self.affine_step(sys, u, opts, it, f, small_step, &mut prev, stats)? {
                    Some(true) => return Ok(()),
                    Some(false) => {
                        self.rescale(sys, u);
                        (f, phi) = scaled(&self.r, &self.w);
                        stats.residual = f;
                        if f <= opts.tol || (small_step && f <= opts.step_residual_tol) {
                            return Ok(());
                        }
                        continue;
                    }
                    // The system cannot re-solve: Armijo from here on.
                    None => affine = false,
                }
            }

            // Backtracking line search.
            let mut lambda = 1.0_f64;
            let mut last_err: Option<BvpError> = None;
            let (ft, phit) = loop {
                for ((t, &x), &d) in self.ut.iter_mut().zip(u.iter()).zip(&self.du) {
                    *t = x + lambda * d;
                }
                let trial = sys.residual(&self.ut, &mut self.rt, stats);
                let ok = match trial {
                    Ok(()) if all_finite(&self.rt) => true,
                    Ok(()) => {
                        last_err = Some(non_finite("residual", f64::NAN));
                        false
                    }
                    Err(e @ BvpError::NonFinite { .. })
                    | Err(e @ BvpError::StepSizeTooSmall { .. }) => {
                        last_err = Some(e);
                        false
                    }
                    Err(e) => return Err(attach(e, it, stats)),
                };
                let next = if ok {
                    let (ftrial, phit) = scaled(&self.rt, &self.w);
                    if phit <= (1.0 - 2.0 * ARMIJO * lambda) * phi {
                        break (ftrial, phit);
                    }
                    if f <= opts.step_residual_tol && (small_step || (rows_scaled && lambda == 1.0))
                    {
                        // At the rounding floor: the step is negligible, or (rows scaled to
                        // their size, so f is relative) the full step cannot decrease φ any more.
                        return Ok(());
                    }
                    let denom = phit - phi + 2.0 * phi * lambda;
                    let lq = if denom > 0.0 {
                        phi * lambda * lambda / denom
                    } else {
                        0.5 * lambda
                    };
                    lq.clamp(0.1 * lambda, 0.5 * lambda)
                } else {
                    0.25 * lambda
                };
                if next < opts.min_damping {
                    return Err(match last_err.take() {
                        Some(e) if !ok => attach(e, it, stats),
                        _ => attach(
                            BvpError::Stalled {
                                iteration: it,
                                residual: f,
                                stats: Stats::default(),
                            },
                            it,
                            stats,
                        ),
                    });
                }
                lambda = next;
            };

            u.copy_from_slice(&self.ut);
            std::mem::swap(&mut self.r, &mut self.rt);
            (f, phi) = (ft, phit);
            if self.rescale(sys, u) {
                (f, phi) = scaled(&self.r, &self.w);
            }
            stats.residual = f;
            if f <= opts.tol || (small_step && f <= opts.step_residual_tol) {
                return Ok(());
            }
        }
        Err(BvpError::MaxIterations {
            max_iter: opts.max_iter,
            residual: f,
            stats: stats.clone(),
        })
    }
}

/// The Newton homotopy `R(u) − τ R(u₀) = 0` of a system, solved at `τ` (see [`homotopy`]).
struct Shifted<'a, S: ?Sized> {
    sys: &'a mut S,
    r0: &'a [f64],
    tau: f64,
    /// `R(u)` unshifted (the system's contract for `solve_linearized`) and `−J⁻¹ r0`.
    full: Vec<f64>,
    d0: Vec<f64>,
}

impl<S: NewtonSystem + ?Sized> NewtonSystem for Shifted<'_, S> {
    fn residual(&mut self, u: &[f64], r: &mut [f64], stats: &mut Stats) -> Result<(), BvpError> {
        self.sys.residual(u, r, stats)?;
        for (x, r0) in r.iter_mut().zip(self.r0) {
            *x -= self.tau * r0;
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
        for ((f, x), r0) in self.full.iter_mut().zip(r).zip(self.r0) {
            *f = x + self.tau * r0;
        }
        self.sys.solve_linearized(u, &self.full, du, stats)?;
        if !self.sys.resolve(self.r0, &mut self.d0)? {
            return Err(singular());
        }
        for (d, d0) in du.iter_mut().zip(&self.d0) {
            *d -= self.tau * d0;
        }
        Ok(())
    }

    fn residual_scale(&mut self, u: &[f64], w: &mut [f64]) -> bool {
        self.sys.residual_scale(u, w)
    }

    fn resolve(&mut self, r: &[f64], du: &mut [f64]) -> Result<bool, BvpError> {
        self.sys.resolve(r, du)
    }
}

/// Steps of [`homotopy`] before it gives up.
const HOMOTOPY_STEPS: usize = 200;
/// Newton iterations of an easy [`homotopy`] step (the next one is twice as long).
const HOMOTOPY_EASY: usize = 5;
/// Smallest step in `τ` of [`homotopy`].
const HOMOTOPY_MIN_STEP: f64 = 1e-3;

/// Globalization without a parameter: the Newton homotopy `R(u) − τ R(u₀) = 0` from `τ = 1`
/// (solved by `u₀`, the given `u`) to `τ = 0` (the system), each step a damped Newton solve
/// (`opts`, at most 10 iterations) from the secant predictor; a failed step halves `Δτ`, an
/// easy one (≤ 5 iterations) doubles it. The system must support
/// [`NewtonSystem::resolve`]. On failure `u` is the last point reached and the error the last
/// step's.
pub fn homotopy<S: NewtonSystem + ?Sized>(
    newton: &mut Newton,
    sys: &mut S,
    u: &mut [f64],
    opts: &NewtonOptions,
    stats: &mut Stats,
) -> Result<(), BvpError> {
    let m = u.len();
    let mut r0 = vec![0.0; m];
    sys.residual(u, &mut r0, stats)?;
    let step_opts = NewtonOptions {
        max_iter: opts.max_iter.min(10),
        ..opts.clone()
    };
    let mut shifted = Shifted {
        sys,
        r0: &r0,
        tau: 1.0,
        full: vec![0.0; m],
        d0: vec![0.0; m],
    };
    let (mut tau, mut dt) = (1.0_f64, 0.25_f64);
    // Last accepted point and the secant to it from the one before (predictor).
    let mut last = u.to_vec();
    let mut secant = vec![0.0; m];
    let mut last_dt = 0.0_f64;
    for _ in 0..HOMOTOPY_STEPS {
        let t = if tau - dt < 0.5 * dt { 0.0 } else { tau - dt };
        shifted.tau = t;
        if last_dt > 0.0 {
            let c = (tau - t) / last_dt;
            for ((x, l), d) in u.iter_mut().zip(&last).zip(&secant) {
                *x = l + c * d;
            }
        }
        let before = stats.newton_iters;
        let res = if t == 0.0 {
            newton.solve(shifted.sys, u, opts, stats)
        } else {
            newton.solve(&mut shifted, u, &step_opts, stats)
        };
        match res {
            Ok(()) => {
                if t == 0.0 {
                    return Ok(());
                }
                for ((d, x), l) in secant.iter_mut().zip(u.iter()).zip(&last) {
                    *d = x - l;
                }
                last.copy_from_slice(u);
                last_dt = tau - t;
                tau = t;
                if stats.newton_iters - before <= HOMOTOPY_EASY {
                    dt *= 2.0;
                }
            }
            Err(e) => {
                u.copy_from_slice(&last);
                dt *= 0.5;
                if dt < HOMOTOPY_MIN_STEP {
                    return Err(e);
                }
            }
        }
    }
    Err(BvpError::MaxIterations {
        max_iter: HOMOTOPY_STEPS,
        residual: stats.residual,
        stats: stats.clone(),
    })
}

/// Convenience: damped Newton with a temporary [`Newton`] (allocates its work vectors).
pub fn newton<S: NewtonSystem + ?Sized>(
    sys: &mut S,
    u: &mut [f64],
    opts: &NewtonOptions,
    stats: &mut Stats,
) -> Result<(), BvpError> {
    Newton::new().solve(sys, u, opts, stats)
}

/// A [`NewtonSystem`] from two closures with a dense Jacobian and [`crate::linalg`] LU; handy for
/// small algebraic systems (and tests). `jac(u, j)` writes the row-major `N × N` Jacobian.
pub struct DenseSystem<R, J> {
    /// Residual closure `res(u, r)`.
    pub res: R,
    /// Jacobian closure `jac(u, j)`.
    pub jac: J,
    lu: crate::linalg::DenseLu,
}

impl<R, J> DenseSystem<R, J>
where
    R: FnMut(&[f64], &mut [f64]),
    J: FnMut(&[f64], &mut [f64]),
{
    /// Wraps the closures for systems of size `n`.
    pub fn new(n: usize, res: R, jac: J) -> Self {
        DenseSystem {
            res,
            jac,
            lu: crate::linalg::DenseLu::new(n),
        }
    }
}

impl<R, J> NewtonSystem for DenseSystem<R, J>
where
    R: FnMut(&[f64], &mut [f64]),
    J: FnMut(&[f64], &mut [f64]),
{
    fn residual(&mut self, u: &[f64], r: &mut [f64], _stats: &mut Stats) -> Result<(), BvpError> {
        (self.res)(u, r);
        Ok(())
    }

    fn solve_linearized(
        &mut self,
        u: &[f64],
        r: &[f64],
        du: &mut [f64],
        stats: &mut Stats,
    ) -> Result<(), BvpError> {
        if self.lu.n() != u.len() {
            self.lu.resize(u.len());
        }
        (self.jac)(u, self.lu.matrix_mut());
        stats.factorizations += 1;
        self.lu.factor().map_err(|_| singular())?;
        for (d, v) in du.iter_mut().zip(r) {
            *d = -v;
        }
        self.lu.solve(du);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rosenbrock_like_system_converges() {
        // R(u) = (10 (u1 − u0²), 1 − u0): root (1, 1); full steps overshoot from far away.
        let mut sys = DenseSystem::new(
            2,
            |u: &[f64], r: &mut [f64]| {
                r[0] = 10.0 * (u[1] - u[0] * u[0]);
                r[1] = 1.0 - u[0];
            },
            |u: &[f64], j: &mut [f64]| {
                j.copy_from_slice(&[-20.0 * u[0], 10.0, -1.0, 0.0]);
            },
        );
        let mut u = [-1.2, 1.0];
        let mut stats = Stats::default();
        newton(&mut sys, &mut u, &NewtonOptions::default(), &mut stats).unwrap();
        assert!((u[0] - 1.0).abs() < 1e-12 && (u[1] - 1.0).abs() < 1e-12);
        assert!(stats.newton_iters <= 25, "{stats}");
        assert!(stats.residual <= 1e-10);
    }

    #[test]
    fn no_root_stalls_or_singular() {
        // u² + 1 = 0 has no real root.
        let mut sys = DenseSystem::new(
            1,
            |u: &[f64], r: &mut [f64]| r[0] = u[0] * u[0] + 1.0,
            |u: &[f64], j: &mut [f64]| j[0] = 2.0 * u[0],
        );
        let mut u = [0.7];
        let mut stats = Stats::default();
        let e = newton(&mut sys, &mut u, &NewtonOptions::default(), &mut stats).unwrap_err();
        assert!(matches!(
            e,
            BvpError::Stalled { .. }
                | BvpError::SingularJacobian { .. }
                | BvpError::MaxIterations { .. }
        ));
        assert!(e.stats().unwrap().newton_iters >= 1);
    }

    #[test]
    fn validate_rejects_bad_options() {
        let o = NewtonOptions {
            tol: 0.0,
            ..Default::default()
        };
        assert!(matches!(
            o.validate(),
            Err(BvpError::InvalidOption {
                name: "newton.tol",
                ..
            })
        ));
    }
}
