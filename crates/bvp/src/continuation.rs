//! Natural-parameter and pseudo-arclength continuation in one scalar parameter, with fold
//! detection and location.
//!
//! # The family
//!
//! A [`ParamBvp`] is a family of two-point BVPs in a scalar `λ`:
//!
//! ```text
//!     z'(s) = F(s, z, p; λ),      g(z(a), z(b), p; λ) = 0      (n + k conditions)
//! ```
//!
//! Its solutions form curves ("branches") in the space of `(z(·), p, λ)`. [`Continuation`] traces a
//! branch from a start solution, one [`BranchPoint`] per iterator item, so callers can stop on
//! their own conditions.
//!
//! # Reduction to ordinary BVPs
//!
//! Every corrector is an ordinary [`Bvp`] solve by any [`BvpSolver`] (shooting or collocation):
//!
//! - [`Member`] freezes `λ`: the family member at `λ`. Used by natural continuation, by
//!   [`Continuation::point_at`] and to land exactly on a `λ` bound.
//! - [`Arclength`] makes `λ` an extra unknown parameter (`k + 1` unknowns, `n + k + 1` conditions)
//!   and appends the pseudo-arclength condition
//!
//!   ```text
//!       ⟨τ, v − v_pred⟩_θ = 0,     v = (z(a), z(b), p, λ) ∈ R^(2n+k+1),
//!       ⟨x, y⟩_θ = Σ_{i<2n+k} x_i y_i + θ x_λ y_λ,
//!   ```
//!
//!   with `τ` a unit tangent (in the `θ`-norm) and `v_pred = v_cur + ds·τ` the predicted point.
//!
//! The boundary coordinates `v` are what shooting iterates on, so the extra condition is free for
//! shooting and a single extra row for collocation. The tangent in `v` coordinates is well defined
//! everywhere on a regular branch, folds included: a nonzero tangent `(δz(·), δp, δλ)` of the
//! branch satisfies the linearised ODE `δz' = F_z δz + F_p δp + F_λ δλ`, an initial-value problem
//! in `(δz(a), δp, δλ)`; if that triple vanished, `δz ≡ 0`, so `(δz(a), δp, δλ) ≠ 0`. At a fold
//! `δλ = 0` but `(δz(a), δp) ≠ 0`, and the bordered system (branch Jacobian plus the row `τᵀ`) is
//! nonsingular as long as `τ` is not orthogonal to the true tangent — which a secant over a step
//! shorter than the radius of curvature guarantees. The same holds for the discrete one-step
//! maps of shooting and collocation.
//!
//! # Steps
//!
//! - Arclength `σ` is accumulated as the `θ`-norm of the chord between successive points in `v`
//!   coordinates (the step length `ds`).
//! - Predictor: secant extrapolation of the whole previous solution, node by node on the newest
//!   mesh (the older solution is evaluated on it when the meshes differ), of `p` and of `λ`:
//!   `x_pred = x_cur + c·(x_cur − x_prev)`, `c = ds / |v_cur − v_prev|_θ`. The derivatives of the
//!   guess are `F` at the predicted values, so the guess interpolates as cubic Hermite.
//! - The first step of pseudo-arclength continuation is a natural step `λ0 → λ0 ± ds` (which needs
//!   no tangent); from then on the secant through the last two points is the tangent.
//! - Natural continuation steps `λ` by `±ds` and corrects with `λ` fixed; its predictor is the
//!   secant in `λ`. It cannot pass a fold: there the solves fail, the step shrinks to `ds_min` and
//!   the iterator returns [`BvpError::Fold`] with the fold's estimated `λ` when the last three
//!   points show `λ` turning back just ahead (the extremum of the quadratic `λ(σ)` through them;
//!   whatever the corrector's error: a stall, NaN/∞ past the fold), else
//!   [`BvpError::Continuation`] with the solver's error and, when Newton failed to converge
//!   (stall, iteration limit, singular matrix), a "fold?" hint (none for non-finite values,
//!   integration or mesh limits).
//! - Step control: a step is rejected (and `ds` halved) if the corrector fails or if the angle
//!   between the new and the previous secant exceeds `max_angle` (so a step cannot jump to
//!   another part of the branch); at `ds = ds_min` the angle test is waived and a corrector
//!   failure ends the continuation with the solver's error. After an accepted step,
//!   `ds ← clamp(ds · clamp(target_iters / iters, 1/2, 2), ds_min, ds_max)` (no growth after a
//!   rejection), with `iters` the corrector's Newton iterations less one per further mesh pass
//!   of an adaptive solver (each pass on a refined mesh costs at least one, whatever the step).
//! - Bounds: a step that leaves `[lambda_min, lambda_max]` is replaced by a solve at the bound
//!   (guess interpolated linearly in `λ` between the last two points); that point is the last.
//!
//! # Folds
//!
//! A fold (limit point in `λ`) shows as a sign change of the `λ` increments of successive steps:
//! with points `A, B, C`, `λ_B` is extreme among the three. It is located by Brent's minimisation
//! of `∓λ(t)` along the chord parameter `t = ⟨τ_c, v − v_A⟩_θ`, `τ_c = (v_C − v_A)/|v_C − v_A|_θ`
//! (near a fold the chord is nearly parallel to the tangent there, so `t` parametrises the
//! branch), each evaluation being an [`Arclength`] solve with `τ = τ_c`. Near the fold
//! `λ(t) ≈ λ* − K (t − t*)²`, so the search stops when `K δt² ≤ fold_tol / 4`, with `K` from the
//! parabola through `A, B, C`. The fold is reported with the point `C` (it lies between `A` and
//! `C`; its `sigma` says where), and continuation goes on past it.
//!
//! # Example
//!
//! Trace Bratu `u'' + λeᵘ = 0`, `u(0) = u(1) = 0` from λ = 0.1 through its fold, stopping on a
//! caller's condition (here `u(½) > 4.5`, on the upper branch below λ = 1), and sample the branch
//! at λ = 1:
//!
//! ```
//! use bvp::continuation::{Continuation, ContinuationOptions, Member};
//! use bvp::{samples::BratuFamily, BvpSolver, Guess, Shooting, ShootingOptions};
//!
//! let mut solver = Shooting::new(ShootingOptions::default())?;
//! let guess = Guess::constant(0.0, 1.0, 11, &[0.0, 0.0], vec![]);
//! let start = solver.solve(&Member::new(&BratuFamily, 0.1), &guess)?;
//! let opts = ContinuationOptions { lambda_min: 0.1, ..Default::default() };
//! let mut cont = Continuation::new(&BratuFamily, solver, start, 0.1, opts)?;
//! let mut fold = None;
//! while let Some(point) = cont.next() {
//!     let point = point?;
//!     if let Some(f) = point.fold {
//!         fold = Some(f.lambda);
//!     }
//!     if point.solution.at(0.5)[0] > 4.5 {
//!         break;
//!     }
//! }
//! assert!((fold.unwrap() - 3.513830719125).abs() < 1e-8);
//! let upper = cont.point_at(1.0)?; // warm-started from the latest points: upper branch
//! assert!(upper.left()[1] > 10.0);
//! # Ok::<(), bvp::BvpError>(())
//! ```
//!
//! # Choices and limitations
//!
//! - The start must be a regular point (not a fold): the first pseudo-arclength step is natural.
//! - `σ` and `ds` are measured in `(z(a), z(b), p, √θ·λ)`; rescale with `θ` when `λ` and the
//!   boundary values have very different magnitudes.
//! - Branch points (bifurcations) are not detected; the secant predictor usually continues
//!   straight through a simple branch point.
//! - A fold is located only if the three points around it are on a smooth, gently curved piece of
//!   the branch (the angle limit sees to that); otherwise it is reported with `located = false`.
//! - The last `history` points (solutions included) are kept for [`Continuation::point_at`].

use crate::{Bvp, BvpError, BvpSolver, Dims, Guess, Solution, Stats, Status};
use argmin::core::{CostFunction, Executor, State as _, TerminationReason, TerminationStatus};
use argmin::solver::brent::BrentOpt;
use std::cell::RefCell;
use std::collections::VecDeque;

/// The likely cause of a corrector failure at `ds_min`, for [`BvpError::Continuation`]: a fold
/// only where the corrector's Newton failed to converge (natural continuation cannot pass one);
/// non-finite values, integration or mesh limits and inaccurate solutions are their own cause.
fn failure_hint(method: Method, e: &BvpError) -> &'static str {
    match (method, e.status()) {
        (Method::Natural, Status::Stalled | Status::MaxIterations) => {
            " (fold? natural continuation cannot pass a fold in lambda; use PseudoArclength)"
        }
        (Method::Natural, Status::SingularJacobian) => {
            " (a singular member of the family, or a fold: natural continuation cannot pass a \
             fold in lambda; try PseudoArclength)"
        }
        _ => "",
    }
}

/// A family of BVPs in one scalar parameter `λ`: `z' = F(s, z, p; λ)`, `g(z(a), z(b), p; λ) = 0`.
///
/// Matrix layouts are those of [`crate::Bvp`]; the extra `λ` columns are vectors:
/// `dfdl[i] = ∂F_i/∂λ` (length `n`), `dgl[i] = ∂g_i/∂λ` (length `n + k`).
pub trait ParamBvp {
    /// Number of states and unknown parameters (λ excluded).
    fn dims(&self) -> Dims;
    /// The interval `[a, b]`.
    fn interval(&self) -> (f64, f64);
    /// Right-hand side at parameter `lambda`.
    fn rhs(&self, s: f64, z: &[f64], p: &[f64], lambda: f64, dz: &mut [f64]);
    /// Boundary residual at parameter `lambda`.
    fn bc(&self, za: &[f64], zb: &[f64], p: &[f64], lambda: f64, res: &mut [f64]);
    /// Analytic `∂F/∂z` (n×n), `∂F/∂p` (n×k) and `∂F/∂λ` (n); `false` if not provided (default).
    #[allow(clippy::too_many_arguments)]
    fn rhs_jacobian(
        &self,
        _s: f64,
        _z: &[f64],
        _p: &[f64],
        _lambda: f64,
        _dfdz: &mut [f64],
        _dfdp: &mut [f64],
        _dfdl: &mut [f64],
    ) -> bool {
        false
    }
    /// Analytic Jacobians of `g` with respect to `z(a)`, `z(b)`, `p` and `λ`; `false` if not
    /// provided (default).
    #[allow(clippy::too_many_arguments)]
    fn bc_jacobian(
        &self,
        _za: &[f64],
        _zb: &[f64],
        _p: &[f64],
        _lambda: f64,
        _dga: &mut [f64],
        _dgb: &mut [f64],
        _dgp: &mut [f64],
        _dgl: &mut [f64],
    ) -> bool {
        false
    }
}

impl<T: ParamBvp + ?Sized> ParamBvp for &T {
    fn dims(&self) -> Dims {
        (**self).dims()
    }
    fn interval(&self) -> (f64, f64) {
        (**self).interval()
    }
    fn rhs(&self, s: f64, z: &[f64], p: &[f64], lambda: f64, dz: &mut [f64]) {
        (**self).rhs(s, z, p, lambda, dz)
    }
    fn bc(&self, za: &[f64], zb: &[f64], p: &[f64], lambda: f64, res: &mut [f64]) {
        (**self).bc(za, zb, p, lambda, res)
    }
    fn rhs_jacobian(
        &self,
        s: f64,
        z: &[f64],
        p: &[f64],
        lambda: f64,
        dfdz: &mut [f64],
        dfdp: &mut [f64],
        dfdl: &mut [f64],
    ) -> bool {
        (**self).rhs_jacobian(s, z, p, lambda, dfdz, dfdp, dfdl)
    }
    fn bc_jacobian(
        &self,
        za: &[f64],
        zb: &[f64],
        p: &[f64],
        lambda: f64,
        dga: &mut [f64],
        dgb: &mut [f64],
        dgp: &mut [f64],
        dgl: &mut [f64],
    ) -> bool {
        (**self).bc_jacobian(za, zb, p, lambda, dga, dgb, dgp, dgl)
    }
}

/// The member of a family at a fixed `λ`, as an ordinary [`Bvp`].
#[derive(Debug)]
pub struct Member<'a, P: ParamBvp + ?Sized> {
    family: &'a P,
    lambda: f64,
    // ∂F/∂λ and ∂g/∂λ are computed by the family but not needed here; buffers avoid allocation.
    dfdl: RefCell<Vec<f64>>,
    dgl: RefCell<Vec<f64>>,
}

impl<'a, P: ParamBvp + ?Sized> Member<'a, P> {
    /// The member of `family` at `lambda`.
    pub fn new(family: &'a P, lambda: f64) -> Self {
        let Dims { n, k } = family.dims();
        Member {
            family,
            lambda,
            dfdl: RefCell::new(vec![0.0; n]),
            dgl: RefCell::new(vec![0.0; n + k]),
        }
    }

    /// The parameter value.
    pub fn lambda(&self) -> f64 {
        self.lambda
    }
}

impl<P: ParamBvp + ?Sized> Bvp for Member<'_, P> {
    fn dims(&self) -> Dims {
        self.family.dims()
    }
    fn interval(&self) -> (f64, f64) {
        self.family.interval()
    }
    fn rhs(&self, s: f64, z: &[f64], p: &[f64], dz: &mut [f64]) {
        self.family.rhs(s, z, p, self.lambda, dz)
    }
    fn bc(&self, za: &[f64], zb: &[f64], p: &[f64], res: &mut [f64]) {
        self.family.bc(za, zb, p, self.lambda, res)
    }
    fn rhs_jacobian(
        &self,
        s: f64,
        z: &[f64],
        p: &[f64],
        dfdz: &mut [f64],
        dfdp: &mut [f64],
    ) -> bool {
        let mut dfdl = self.dfdl.borrow_mut();
        self.family
            .rhs_jacobian(s, z, p, self.lambda, dfdz, dfdp, &mut dfdl)
    }
    fn bc_jacobian(
        &self,
        za: &[f64],
        zb: &[f64],
        p: &[f64],
        dga: &mut [f64],
        dgb: &mut [f64],
        dgp: &mut [f64],
    ) -> bool {
        let mut dgl = self.dgl.borrow_mut();
        self.family
            .bc_jacobian(za, zb, p, self.lambda, dga, dgb, dgp, &mut dgl)
    }
}

/// A family built from a function that makes the member problem at each `λ`: the bridge from
/// any [`Bvp`] (a struct with the parameter as a field, an array problem wrapped in
/// [`crate::fixed::Fixed`], closures from [`crate::from_fns`]) to [`ParamBvp`], for
/// [`crate::solve_by_continuation`] and [`Continuation`]. Made by [`family`].
///
/// `make` is called for every evaluation (it should be cheap: build a small struct). The
/// dimensions and interval are those of `make(0.0)` and must not depend on `λ`. The Jacobians in
/// `z` and `p` are the member's own (finite differences where it has none); `∂F/∂λ` and `∂g/∂λ`
/// are central differences with step `1e-6 · (1 + |λ|)` (error `O(1e-12)` relative).
pub struct FnFamily<F> {
    make: F,
    scratch: RefCell<[Vec<f64>; 2]>,
}

impl<F> std::fmt::Debug for FnFamily<F> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("FnFamily")
    }
}

/// The family whose member at `λ` is `make(λ)`: see [`FnFamily`].
///
/// ```
/// use bvp::continuation::family;
/// use bvp::samples::Bratu;
/// use bvp::{solve_by_continuation, BvpSolver, PathOptions, Shooting, ShootingOptions};
///
/// // Bratu's problem is a struct with its parameter as a field: walk λ from 0.5 to 3.
/// let fam = family(|lambda| Bratu { lambda });
/// let mut solver = Shooting::new(ShootingOptions::default())?;
/// let guess = Bratu { lambda: 0.5 }.guess();
/// let res = solve_by_continuation(&fam, &mut solver, &guess, 0.5, 3.0, &PathOptions::default())?;
/// assert_eq!(*res.path.last().unwrap(), 3.0);
/// # Ok::<(), bvp::BvpError>(())
/// ```
pub fn family<B: Bvp, F: Fn(f64) -> B>(make: F) -> FnFamily<F> {
    FnFamily {
        make,
        scratch: RefCell::new([Vec::new(), Vec::new()]),
    }
}

impl<B: Bvp, F: Fn(f64) -> B> FnFamily<F> {
    /// `out = ∂/∂λ eval(member)` by a central difference in `λ`.
    fn d_lambda(&self, lambda: f64, out: &mut [f64], eval: impl Fn(&B, &mut [f64])) {
        let h = 1e-6 * (1.0 + lambda.abs());
        let mut sc = self.scratch.borrow_mut();
        let [a, b] = &mut *sc;
        a.resize(out.len(), 0.0);
        b.resize(out.len(), 0.0);
        eval(&(self.make)(lambda + h), a);
        eval(&(self.make)(lambda - h), b);
        for ((d, x), y) in out.iter_mut().zip(a.iter()).zip(b.iter()) {
            *d = (x - y) / (2.0 * h);
        }
    }
}

impl<B: Bvp, F: Fn(f64) -> B> ParamBvp for FnFamily<F> {
    fn dims(&self) -> Dims {
        (self.make)(0.0).dims()
    }
    fn interval(&self) -> (f64, f64) {
        (self.make)(0.0).interval()
    }
    fn rhs(&self, s: f64, z: &[f64], p: &[f64], lambda: f64, dz: &mut [f64]) {
        (self.make)(lambda).rhs(s, z, p, dz)
    }
    fn bc(&self, za: &[f64], zb: &[f64], p: &[f64], lambda: f64, res: &mut [f64]) {
        (self.make)(lambda).bc(za, zb, p, res)
    }
    fn rhs_jacobian(
        &self,
        s: f64,
        z: &[f64],
        p: &[f64],
        lambda: f64,
        dfdz: &mut [f64],
        dfdp: &mut [f64],
        dfdl: &mut [f64],
    ) -> bool {
        if !(self.make)(lambda).rhs_jacobian(s, z, p, dfdz, dfdp) {
            return false;
        }
        self.d_lambda(lambda, dfdl, |m, out| m.rhs(s, z, p, out));
        true
    }
    fn bc_jacobian(
        &self,
        za: &[f64],
        zb: &[f64],
        p: &[f64],
        lambda: f64,
        dga: &mut [f64],
        dgb: &mut [f64],
        dgp: &mut [f64],
        dgl: &mut [f64],
    ) -> bool {
        if !(self.make)(lambda).bc_jacobian(za, zb, p, dga, dgb, dgp) {
            return false;
        }
        self.d_lambda(lambda, dgl, |m, out| m.bc(za, zb, p, out));
        true
    }
}

#[derive(Debug)]
struct ArcScratch {
    dfdp: Vec<f64>,
    dfdl: Vec<f64>,
    dgp: Vec<f64>,
    dgl: Vec<f64>,
}

/// The pseudo-arclength corrector as an ordinary [`Bvp`]: unknown parameters `(p, λ)` (`λ` last),
/// conditions `g(z(a), z(b), p; λ) = 0` followed by `⟨τ, v − v_pred⟩_θ = 0` with
/// `v = (z(a), z(b), p, λ)` (see the [module docs](self)).
#[derive(Debug)]
pub struct Arclength<'a, P: ParamBvp + ?Sized> {
    family: &'a P,
    n: usize,
    k: usize,
    tangent: Vec<f64>,
    anchor: Vec<f64>,
    theta: f64,
    scratch: RefCell<ArcScratch>,
}

impl<'a, P: ParamBvp + ?Sized> Arclength<'a, P> {
    /// The extended problem with tangent `tangent` and predicted point `anchor`, both of length
    /// `2n + k + 1` in the coordinates `(z(a), z(b), p, λ)`, and `λ` weight `theta`.
    pub fn new(
        family: &'a P,
        tangent: Vec<f64>,
        anchor: Vec<f64>,
        theta: f64,
    ) -> Result<Self, BvpError> {
        let Dims { n, k } = family.dims();
        let m = 2 * n + k + 1;
        for (what, got) in [("tangent", tangent.len()), ("anchor", anchor.len())] {
            if got != m {
                return Err(BvpError::Dimension {
                    what,
                    got,
                    expected: m,
                });
            }
        }
        Ok(Arclength {
            family,
            n,
            k,
            tangent,
            anchor,
            theta,
            scratch: RefCell::new(ArcScratch {
                dfdp: vec![0.0; n * k],
                dfdl: vec![0.0; n],
                dgp: vec![0.0; (n + k) * k],
                dgl: vec![0.0; n + k],
            }),
        })
    }
}

impl<P: ParamBvp + ?Sized> Bvp for Arclength<'_, P> {
    fn dims(&self) -> Dims {
        Dims {
            n: self.n,
            k: self.k + 1,
        }
    }
    fn interval(&self) -> (f64, f64) {
        self.family.interval()
    }
    fn rhs(&self, s: f64, z: &[f64], p: &[f64], dz: &mut [f64]) {
        self.family.rhs(s, z, &p[..self.k], p[self.k], dz)
    }
    fn bc(&self, za: &[f64], zb: &[f64], p: &[f64], res: &mut [f64]) {
        let (n, k) = (self.n, self.k);
        self.family.bc(za, zb, &p[..k], p[k], &mut res[..n + k]);
        let (t, v0) = (&self.tangent, &self.anchor);
        let mut r = 0.0;
        for j in 0..n {
            r += t[j] * (za[j] - v0[j]) + t[n + j] * (zb[j] - v0[n + j]);
        }
        for j in 0..k {
            r += t[2 * n + j] * (p[j] - v0[2 * n + j]);
        }
        let l = 2 * n + k;
        r += self.theta * t[l] * (p[k] - v0[l]);
        res[n + k] = r;
    }
    fn rhs_jacobian(
        &self,
        s: f64,
        z: &[f64],
        p: &[f64],
        dfdz: &mut [f64],
        dfdp: &mut [f64],
    ) -> bool {
        let (n, k) = (self.n, self.k);
        let mut sc = self.scratch.borrow_mut();
        let ArcScratch { dfdp: fp, dfdl, .. } = &mut *sc;
        if !self
            .family
            .rhs_jacobian(s, z, &p[..k], p[k], dfdz, fp, dfdl)
        {
            return false;
        }
        for i in 0..n {
            dfdp[i * (k + 1)..i * (k + 1) + k].copy_from_slice(&fp[i * k..(i + 1) * k]);
            dfdp[i * (k + 1) + k] = dfdl[i];
        }
        true
    }
    fn bc_jacobian(
        &self,
        za: &[f64],
        zb: &[f64],
        p: &[f64],
        dga: &mut [f64],
        dgb: &mut [f64],
        dgp: &mut [f64],
    ) -> bool {
        let (n, k) = (self.n, self.k);
        let mut sc = self.scratch.borrow_mut();
        let ArcScratch { dgp: gp, dgl, .. } = &mut *sc;
        if !self.family.bc_jacobian(
            za,
            zb,
            &p[..k],
            p[k],
            &mut dga[..(n + k) * n],
            &mut dgb[..(n + k) * n],
            gp,
            dgl,
        ) {
            return false;
        }
        for i in 0..n + k {
            dgp[i * (k + 1)..i * (k + 1) + k].copy_from_slice(&gp[i * k..(i + 1) * k]);
            dgp[i * (k + 1) + k] = dgl[i];
        }
        let t = &self.tangent;
        let last = n + k;
        dga[last * n..(last + 1) * n].copy_from_slice(&t[..n]);
        dgb[last * n..(last + 1) * n].copy_from_slice(&t[n..2 * n]);
        dgp[last * (k + 1)..last * (k + 1) + k].copy_from_slice(&t[2 * n..2 * n + k]);
        dgp[last * (k + 1) + k] = self.theta * t[2 * n + k];
        true
    }
}

/// Continuation method.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub enum Method {
    /// Step `λ`, correct with `λ` fixed. Stops at folds (with an error).
    Natural,
    /// Pseudo-arclength: step along the branch, correct on the hyperplane normal to the secant.
    /// Passes folds and locates them.
    PseudoArclength,
}

/// Options of [`Continuation`].
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ContinuationOptions {
    /// Method. Default [`Method::PseudoArclength`].
    pub method: Method,
    /// Initial step: arclength in the `θ`-norm of `(z(a), z(b), p, λ)`, or the `λ` step for
    /// natural continuation (and the first, natural step of pseudo-arclength). Default 0.05.
    pub ds: f64,
    /// Smallest step; a corrector failure at this step ends the continuation. Default 1e-6.
    pub ds_min: f64,
    /// Largest step. Default 0.5.
    pub ds_max: f64,
    /// Maximum number of steps (points after the start). Default 1000.
    pub max_steps: usize,
    /// Lower `λ` bound; continuation ends on the bound when the branch leaves it. Default −∞.
    pub lambda_min: f64,
    /// Upper `λ` bound. Default +∞.
    pub lambda_max: f64,
    /// Initial direction in `λ`: `+1.0` or `-1.0`. Default `+1.0`.
    pub direction: f64,
    /// Newton iterations per corrector aimed at by the step control (≥ 1). Default 4.
    pub target_iters: usize,
    /// Largest angle (radians) between successive secants in an accepted step, in `(0, π)`.
    /// Default 0.3.
    pub max_angle: f64,
    /// Detect and locate folds (pseudo-arclength only). Default true.
    pub detect_folds: bool,
    /// Tolerance on `λ` at a located fold. Default 1e-10.
    pub fold_tol: f64,
    /// Weight `θ > 0` of `λ` in the arclength norm. Default 1.
    pub theta: f64,
    /// Branch points kept for warm starts of [`Continuation::point_at`] (≥ 3). Default 64.
    pub history: usize,
}

impl Default for ContinuationOptions {
    fn default() -> Self {
        ContinuationOptions {
            method: Method::PseudoArclength,
            ds: 0.05,
            ds_min: 1e-6,
            ds_max: 0.5,
            max_steps: 1000,
            lambda_min: f64::NEG_INFINITY,
            lambda_max: f64::INFINITY,
            direction: 1.0,
            target_iters: 4,
            max_angle: 0.3,
            detect_folds: true,
            fold_tol: 1e-10,
            theta: 1.0,
            history: 64,
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

impl ContinuationOptions {
    /// Checks every option against its valid range.
    pub fn validate(&self) -> Result<(), BvpError> {
        let pos = |x: f64| x.is_finite() && x > 0.0;
        if !pos(self.ds_min) {
            return Err(invalid("ds_min", self.ds_min, "finite and > 0"));
        }
        if !pos(self.ds_max) || self.ds_max < self.ds_min {
            return Err(invalid("ds_max", self.ds_max, "finite and >= ds_min"));
        }
        if !pos(self.ds) || self.ds < self.ds_min || self.ds > self.ds_max {
            return Err(invalid("ds", self.ds, "in [ds_min, ds_max]"));
        }
        if self.max_steps == 0 {
            return Err(invalid("max_steps", self.max_steps, ">= 1"));
        }
        if self.lambda_min.is_nan()
            || self.lambda_max.is_nan()
            || self.lambda_min >= self.lambda_max
        {
            return Err(invalid(
                "lambda_min",
                format!("{} (lambda_max = {})", self.lambda_min, self.lambda_max),
                "lambda_min < lambda_max, not NaN",
            ));
        }
        if self.direction != 1.0 && self.direction != -1.0 {
            return Err(invalid("direction", self.direction, "+1.0 or -1.0"));
        }
        if self.target_iters == 0 {
            return Err(invalid("target_iters", self.target_iters, ">= 1"));
        }
        if !(self.max_angle > 0.0 && self.max_angle < std::f64::consts::PI) {
            return Err(invalid("max_angle", self.max_angle, "in (0, pi)"));
        }
        if !pos(self.fold_tol) {
            return Err(invalid("fold_tol", self.fold_tol, "finite and > 0"));
        }
        if !pos(self.theta) {
            return Err(invalid("theta", self.theta, "finite and > 0"));
        }
        if self.history < 3 {
            return Err(invalid("history", self.history, ">= 3"));
        }
        Ok(())
    }
}

/// Whether a fold is a maximum or a minimum of `λ` along the branch.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub enum FoldKind {
    /// `λ` has a local maximum (the branch turns back towards smaller `λ`).
    Max,
    /// `λ` has a local minimum.
    Min,
}

/// A fold (limit point in `λ`) located on the branch.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Fold {
    /// `λ` at the fold.
    pub lambda: f64,
    /// Arclength at the fold (approximately: measured along the chord of the bracketing points).
    pub sigma: f64,
    /// Maximum or minimum.
    pub kind: FoldKind,
    /// The solution at the fold (parameters `p` only, `λ` excluded).
    pub solution: Solution,
    /// True if located to `fold_tol`; false if the search failed and the best point found so far
    /// (possibly a branch point) is reported.
    pub located: bool,
    /// Corrector solves spent locating it.
    pub evaluations: usize,
}

/// One point of the branch, as yielded by [`Continuation`].
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct BranchPoint {
    /// Index: 0 for the (corrected) start, then 1, 2, …
    pub step: usize,
    /// Parameter value.
    pub lambda: f64,
    /// The solution (parameters `p` only, `λ` excluded).
    pub solution: Solution,
    /// Arclength from the start (sum of chords in the `θ`-norm).
    pub sigma: f64,
    /// Step length that led here: the arclength target `ds` (for natural continuation and the
    /// first pseudo-arclength step, `|Δλ|`); 0 for the start.
    pub ds: f64,
    /// Estimated `dλ/dσ` here (derivative of the parabola through the last three points, or the
    /// secant after the first step; NaN at the start).
    pub dlambda_dsigma: f64,
    /// A fold located between the point before the previous one and this one.
    pub fold: Option<Fold>,
    /// True if this point lies exactly on a `λ` bound (then it is the last).
    pub on_bound: bool,
    /// Solver work for this point: all attempts, rejected ones and fold location included.
    pub stats: Stats,
}

#[derive(Clone, Debug)]
struct Node {
    lambda: f64,
    sigma: f64,
    v: Vec<f64>,
    sol: Solution,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum State {
    Start,
    Running,
    Done,
}

/// Continuation of a branch of a [`ParamBvp`] family with a [`BvpSolver`]; an iterator over
/// [`BranchPoint`]s (see the [module docs](self)).
///
/// The first item is the start solution corrected at `λ0`. The iterator ends after an error
/// (yielded once), after the point on a `λ` bound, or after `max_steps` steps.
pub struct Continuation<'a, P: ParamBvp + ?Sized, S: BvpSolver> {
    family: &'a P,
    solver: S,
    opts: ContinuationOptions,
    lambda0: f64,
    start: Option<Solution>,
    state: State,
    history: VecDeque<Node>,
    ds: f64,
    step: usize,
}

impl<P: ParamBvp + ?Sized, S: BvpSolver> std::fmt::Debug for Continuation<'_, P, S> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Continuation")
            .field("opts", &self.opts)
            .field("lambda0", &self.lambda0)
            .field("state", &self.state)
            .field("step", &self.step)
            .field("ds", &self.ds)
            .field("kept_points", &self.history.len())
            .finish_non_exhaustive()
    }
}

/// The Newton iterations of a corrector solve that measure the predictor: those of the first
/// mesh pass. An adaptive solver's later passes start from the converged solution interpolated to
/// the refined mesh and need at least one iteration each whatever the step; counted, they would
/// hold the step length down (at tol 1e-8 Lobatto4 spends 4–5 per step on 3 000 nodes).
fn corrector_iters(stats: &Stats) -> usize {
    stats
        .newton_iters
        .saturating_sub(stats.mesh_passes.saturating_sub(1))
        .max(1)
}

/// Unknowns and step length of one corrector attempt.
struct Attempt {
    lambda: f64,
    sol: Solution,
    iters: usize,
}

impl<'a, P: ParamBvp + ?Sized, S: BvpSolver> Continuation<'a, P, S> {
    /// Sets up continuation of `family` from `start` (a solution, or a rough approximation, at
    /// `lambda0`) with `solver`. Validates the options and that `lambda0` is within the bounds.
    pub fn new(
        family: &'a P,
        solver: S,
        start: Solution,
        lambda0: f64,
        opts: ContinuationOptions,
    ) -> Result<Self, BvpError> {
        opts.validate()?;
        if !(lambda0 >= opts.lambda_min && lambda0 <= opts.lambda_max) {
            return Err(invalid(
                "lambda0",
                lambda0,
                "in [lambda_min, lambda_max] and not NaN",
            ));
        }
        let Dims { n, k } = family.dims();
        if start.n != n {
            return Err(BvpError::Dimension {
                what: "start solution states",
                got: start.n,
                expected: n,
            });
        }
        if start.params.len() != k {
            return Err(BvpError::Dimension {
                what: "start solution parameters",
                got: start.params.len(),
                expected: k,
            });
        }
        if start.mesh.is_empty() || start.z.len() != n * start.mesh.len() {
            return Err(BvpError::Dimension {
                what: "start solution values",
                got: start.z.len(),
                expected: n * start.mesh.len().max(1),
            });
        }
        Ok(Continuation {
            family,
            ds: opts.ds,
            solver,
            opts,
            lambda0,
            start: Some(start),
            state: State::Start,
            history: VecDeque::new(),
            step: 0,
        })
    }

    /// The options.
    pub fn options(&self) -> &ContinuationOptions {
        &self.opts
    }

    /// The solver (e.g. to change its options between steps).
    pub fn solver_mut(&mut self) -> &mut S {
        &mut self.solver
    }

    /// Gives the solver back.
    pub fn into_solver(self) -> S {
        self.solver
    }

    /// The step length the next step will try first.
    pub fn next_ds(&self) -> f64 {
        self.ds
    }

    /// The solution at exactly `lambda` (corrector with `λ` fixed), warm-started from the branch:
    /// by linear interpolation in `λ` between the most recent pair of successive kept points
    /// that brackets `lambda`, else from the kept point nearest in `λ` (the most recent on ties).
    /// Before the first item, the start solution is the guess.
    ///
    /// Meant for output on a caller's `λ` grid: call it after each item for the grid values
    /// passed by the last step. Does not change the continuation state.
    pub fn point_at(&mut self, lambda: f64) -> Result<Solution, BvpError> {
        if !lambda.is_finite() {
            return Err(invalid("lambda", lambda, "finite"));
        }
        let guess = if self.history.is_empty() {
            match &self.start {
                Some(s) => Guess::from(s),
                None => return Err(invalid("lambda", lambda, "continuation has no points")),
            }
        } else {
            let h = &self.history;
            let bracket = (1..h.len()).rev().find(|&i| {
                let (l0, l1) = (h[i - 1].lambda, h[i].lambda);
                (l0.min(l1)..=l0.max(l1)).contains(&lambda) && l0 != l1
            });
            match bracket {
                Some(i) => {
                    let (x, y) = (&h[i - 1], &h[i]);
                    let w = (lambda - x.lambda) / (y.lambda - x.lambda);
                    let (nearer, far, wn) = if w >= 0.5 { (y, x, w) } else { (x, y, 1.0 - w) };
                    blend(
                        self.family,
                        (&nearer.sol, nearer.lambda, wn),
                        (&far.sol, far.lambda, 1.0 - wn),
                        false,
                    )
                    .0
                }
                None => {
                    let mut best = h.len() - 1;
                    for i in (0..h.len()).rev() {
                        if (h[i].lambda - lambda).abs() < (h[best].lambda - lambda).abs() {
                            best = i;
                        }
                    }
                    Guess::from(&h[best].sol)
                }
            }
        };
        self.solver.solve(&Member::new(self.family, lambda), &guess)
    }

    fn v_of(&self, sol: &Solution, lambda: f64) -> Vec<f64> {
        let k = self.family.dims().k;
        let mut v = Vec::with_capacity(2 * sol.n + k + 1);
        v.extend_from_slice(sol.left());
        v.extend_from_slice(sol.right());
        v.extend_from_slice(&sol.params[..k]);
        v.push(lambda);
        v
    }

    fn push(&mut self, node: Node) {
        if self.history.len() == self.opts.history {
            self.history.pop_front();
        }
        self.history.push_back(node);
    }

    fn start_point(&mut self) -> Result<BranchPoint, BvpError> {
        let start = self
            .start
            .take()
            .ok_or_else(|| invalid("start", "none", "present"))?;
        let guess = Guess::from(&start);
        self.start = Some(start);
        let sol = self
            .solver
            .solve(&Member::new(self.family, self.lambda0), &guess)
            .map_err(|e| BvpError::Continuation {
                step: 0,
                lambda: self.lambda0,
                ds: 0.0,
                hint: " (correcting the start solution)",
                source: Box::new(e),
            })?;
        let v = self.v_of(&sol, self.lambda0);
        let stats = sol.stats.clone();
        self.push(Node {
            lambda: self.lambda0,
            sigma: 0.0,
            v,
            sol: sol.clone(),
        });
        Ok(BranchPoint {
            step: 0,
            lambda: self.lambda0,
            solution: sol,
            sigma: 0.0,
            ds: 0.0,
            dlambda_dsigma: f64::NAN,
            fold: None,
            on_bound: false,
            stats,
        })
    }

    /// One natural step of length `ds` in `λ` (clipped to the bounds).
    fn natural_attempt(&mut self, ds: f64) -> Result<Attempt, BvpError> {
        let h = &self.history;
        let cur = &h[h.len() - 1];
        let dir = if h.len() >= 2 {
            (cur.lambda - h[h.len() - 2].lambda).signum()
        } else {
            self.opts.direction
        };
        let dir = if dir == 0.0 { self.opts.direction } else { dir };
        let lambda = (cur.lambda + dir * ds).clamp(self.opts.lambda_min, self.opts.lambda_max);
        let guess = if h.len() >= 2 && h[h.len() - 2].lambda != cur.lambda {
            let prev = &h[h.len() - 2];
            let c = (lambda - cur.lambda) / (cur.lambda - prev.lambda);
            blend(
                self.family,
                (&cur.sol, cur.lambda, 1.0 + c),
                (&prev.sol, prev.lambda, -c),
                false,
            )
            .0
        } else {
            Guess::from(&cur.sol)
        };
        let sol = self
            .solver
            .solve(&Member::new(self.family, lambda), &guess)?;
        Ok(Attempt {
            lambda,
            iters: corrector_iters(&sol.stats),
            sol,
        })
    }

    /// One pseudo-arclength step of length `ds` along the secant of the last two points.
    fn arclength_attempt(&mut self, ds: f64) -> Result<Attempt, BvpError> {
        let h = &self.history;
        let (prev, cur) = (&h[h.len() - 2], &h[h.len() - 1]);
        let theta = self.opts.theta;
        let mut tau: Vec<f64> = cur.v.iter().zip(&prev.v).map(|(a, b)| a - b).collect();
        let norm = wnorm(&tau, theta);
        if !(norm > 0.0 && norm.is_finite()) {
            return Err(BvpError::Dimension {
                what: "secant of the last two points (zero length)",
                got: 0,
                expected: 1,
            });
        }
        tau.iter_mut().for_each(|t| *t /= norm);
        let anchor: Vec<f64> = cur.v.iter().zip(&tau).map(|(v, t)| v + ds * t).collect();
        let c = ds / norm;
        let (guess, _) = blend(
            self.family,
            (&cur.sol, cur.lambda, 1.0 + c),
            (&prev.sol, prev.lambda, -c),
            true,
        );
        let problem = Arclength::new(self.family, tau, anchor, theta)?;
        let mut sol = self.solver.solve(&problem, &guess)?;
        let lambda = sol.params.pop().unwrap_or(f64::NAN);
        Ok(Attempt {
            lambda,
            iters: corrector_iters(&sol.stats),
            sol,
        })
    }

    fn wrap(&self, e: BvpError, ds: f64) -> BvpError {
        if let (Method::Natural, Some(fold)) = (self.opts.method, self.fold_ahead()) {
            return BvpError::Fold {
                step: self.step + 1,
                lambda: self.history.back().map_or(self.lambda0, |n| n.lambda),
                fold,
                source: Box::new(e),
            };
        }
        BvpError::Continuation {
            step: self.step + 1,
            lambda: self.history.back().map_or(self.lambda0, |n| n.lambda),
            ds,
            hint: failure_hint(self.opts.method, &e),
            source: Box::new(e),
        }
    }

    /// A fold ahead of the last three points `A, B, C`, by the quadratic `λ(σ)` through them
    /// (`σ` the arclength): concave in the direction of travel, with its extremum `σ*` beyond `B`
    /// and within twice the span `σ_C − σ_A` of `C` (a nearly straight path has its extremum far
    /// away and is no fold). Returns `λ(σ*)`.
    fn fold_ahead(&self) -> Option<f64> {
        let h = &self.history;
        if h.len() < 3 {
            return None;
        }
        let (a, b, c) = (&h[h.len() - 3], &h[h.len() - 2], &h[h.len() - 1]);
        let (sa, sb, sc) = (a.sigma, b.sigma, c.sigma);
        if !(sa < sb && sb < sc) {
            return None;
        }
        let f_ab = (b.lambda - a.lambda) / (sb - sa);
        let f_bc = (c.lambda - b.lambda) / (sc - sb);
        let f_abc = (f_bc - f_ab) / (sc - sa);
        let dir = (c.lambda - b.lambda).signum();
        if f_abc * dir >= 0.0 || f_abc.is_nan() {
            return None;
        }
        let star = 0.5 * (sa + sb) - f_ab / (2.0 * f_abc);
        if !(star >= sb && star - sc <= 2.0 * (sc - sa)) {
            return None;
        }
        Some(a.lambda + f_ab * (star - sa) + f_abc * (star - sa) * (star - sb))
    }

    fn advance(&mut self) -> Result<Option<BranchPoint>, BvpError> {
        if self.step >= self.opts.max_steps {
            return Ok(None);
        }
        let (lmin, lmax) = (self.opts.lambda_min, self.opts.lambda_max);
        {
            // Already on a bound and heading out: nothing more to do.
            let cur = self.history.back().map_or(self.lambda0, |n| n.lambda);
            if self.history.len() == 1
                && ((cur >= lmax && self.opts.direction > 0.0)
                    || (cur <= lmin && self.opts.direction < 0.0))
            {
                return Ok(None);
            }
        }
        let natural = self.opts.method == Method::Natural || self.history.len() < 2;
        let cos_max = self.opts.max_angle.cos();
        let theta = self.opts.theta;
        let mut stats = Stats::default();
        let mut ds = self.ds;
        let mut rejected = false;
        let (att, secant_new) = loop {
            let res = if natural {
                self.natural_attempt(ds)
            } else {
                self.arclength_attempt(ds)
            };
            match res {
                Ok(att) if att.lambda.is_finite() => {
                    stats.accumulate(&att.sol.stats);
                    let h = &self.history;
                    let cur = &h[h.len() - 1];
                    let v_new = self.v_of(&att.sol, att.lambda);
                    let d: Vec<f64> = v_new.iter().zip(&cur.v).map(|(a, b)| a - b).collect();
                    let len = wnorm(&d, theta);
                    let mut cos = 1.0;
                    if len > 0.0 && h.len() >= 2 {
                        let prev = &h[h.len() - 2];
                        let dp: Vec<f64> = cur.v.iter().zip(&prev.v).map(|(a, b)| a - b).collect();
                        let lp = wnorm(&dp, theta);
                        if lp > 0.0 {
                            cos = wdot(&d, &dp, theta) / (len * lp);
                        }
                    }
                    let at_min = ds <= self.opts.ds_min;
                    // At ds_min the angle limit is waived, but never a reversal.
                    if len > 0.0 && (cos >= cos_max || (at_min && cos > 0.0)) {
                        break (att, (v_new, len));
                    }
                    if at_min {
                        let source = BvpError::Stalled {
                            iteration: att.iters,
                            residual: att.sol.stats.residual,
                            stats: stats.clone(),
                        };
                        return Err(BvpError::Continuation {
                            step: self.step + 1,
                            lambda: cur.lambda,
                            ds,
                            hint:
                                " (the corrector went backwards along the branch or did not move)",
                            source: Box::new(source),
                        });
                    }
                }
                Ok(att) => stats.accumulate(&att.sol.stats),
                Err(e) => {
                    if let Some(s) = e.stats() {
                        stats.accumulate(s);
                    }
                    if ds <= self.opts.ds_min {
                        return Err(self.wrap(e, ds));
                    }
                }
            }
            rejected = true;
            ds = (0.5 * ds).max(self.opts.ds_min);
        };
        let (v_new, len) = secant_new;
        // Step control for the next step.
        let iters = att.iters.max(1) as f64;
        let mut factor = (self.opts.target_iters as f64 / iters).clamp(0.5, 2.0);
        if rejected {
            factor = factor.min(1.0);
        }
        self.ds = (ds * factor).clamp(self.opts.ds_min, self.opts.ds_max);
        self.step += 1;

        let cur = self
            .history
            .back()
            .cloned()
            .ok_or_else(|| invalid("history", 0, ">= 1"))?;
        let mut node = Node {
            lambda: att.lambda,
            sigma: cur.sigma + len,
            v: v_new,
            sol: att.sol,
        };

        // Fold between the previous point, the current one and the new one?
        let mut fold = None;
        if !natural && self.opts.detect_folds && self.history.len() >= 2 {
            let prev = self.history[self.history.len() - 2].clone();
            let d1 = cur.lambda - prev.lambda;
            let d2 = node.lambda - cur.lambda;
            if d1 * d2 < 0.0 {
                let kind = if d1 > 0.0 {
                    FoldKind::Max
                } else {
                    FoldKind::Min
                };
                fold = Some(locate_fold(
                    self.family,
                    &mut self.solver,
                    &self.opts,
                    [&prev, &cur, &node],
                    kind,
                    &mut stats,
                ));
            }
        }

        // Leaving the bounds: land exactly on the bound instead.
        let mut on_bound = false;
        if node.lambda > lmax || node.lambda < lmin {
            let bound = if node.lambda > lmax { lmax } else { lmin };
            let w = (bound - cur.lambda) / (node.lambda - cur.lambda);
            let guess = if w.is_finite() {
                blend(
                    self.family,
                    (&node.sol, node.lambda, w),
                    (&cur.sol, cur.lambda, 1.0 - w),
                    false,
                )
                .0
            } else {
                Guess::from(&cur.sol)
            };
            let sol = match self.solver.solve(&Member::new(self.family, bound), &guess) {
                Ok(s) => s,
                Err(e) => return Err(self.wrap(e, ds)),
            };
            stats.accumulate(&sol.stats);
            let v = self.v_of(&sol, bound);
            let d: Vec<f64> = v.iter().zip(&cur.v).map(|(a, b)| a - b).collect();
            node = Node {
                lambda: bound,
                sigma: cur.sigma + wnorm(&d, theta),
                v,
                sol,
            };
            on_bound = true;
        } else if node.lambda == lmax || node.lambda == lmin {
            on_bound = true;
        }

        let dlds = {
            let h = &self.history;
            let (s2, l2) = (node.sigma, node.lambda);
            let (s1, l1) = (cur.sigma, cur.lambda);
            let f12 = (l2 - l1) / (s2 - s1);
            if h.len() >= 2 {
                let p = &h[h.len() - 2];
                let f01 = (l1 - p.lambda) / (s1 - p.sigma);
                let f012 = (f12 - f01) / (s2 - p.sigma);
                f12 + f012 * (s2 - s1)
            } else {
                f12
            }
        };

        stats.residual = node.sol.stats.residual;
        stats.error_estimate = node.sol.stats.error_estimate;
        stats.nodes = node.sol.stats.nodes;
        let point = BranchPoint {
            step: self.step,
            lambda: node.lambda,
            solution: node.sol.clone(),
            sigma: node.sigma,
            ds,
            dlambda_dsigma: dlds,
            fold,
            on_bound,
            stats,
        };
        self.push(node);
        Ok(Some(point))
    }
}

impl<P: ParamBvp + ?Sized, S: BvpSolver> Iterator for Continuation<'_, P, S> {
    type Item = Result<BranchPoint, BvpError>;

    fn next(&mut self) -> Option<Self::Item> {
        let res = match self.state {
            State::Done => return None,
            State::Start => self.start_point().map(Some),
            State::Running => self.advance(),
        };
        match res {
            Ok(Some(p)) => {
                self.state = if p.on_bound && p.step > 0 {
                    State::Done
                } else {
                    State::Running
                };
                Some(Ok(p))
            }
            Ok(None) => {
                self.state = State::Done;
                None
            }
            Err(e) => {
                self.state = State::Done;
                Some(Err(e))
            }
        }
    }
}

fn wdot(a: &[f64], b: &[f64], theta: f64) -> f64 {
    let m = a.len();
    let s: f64 = a[..m - 1].iter().zip(&b[..m - 1]).map(|(x, y)| x * y).sum();
    s + theta * a[m - 1] * b[m - 1]
}

fn wnorm(a: &[f64], theta: f64) -> f64 {
    wdot(a, a, theta).sqrt()
}

/// The guess `wx·x + wy·y` on the mesh of `x` (`y` evaluated there if the meshes differ), for
/// states, parameters and `λ`; derivatives are `F` at the blended values. With `with_lambda`, `λ`
/// is appended to the parameters. Returns the guess and the blended `λ`.
fn blend<P: ParamBvp + ?Sized>(
    family: &P,
    (x, lx, wx): (&Solution, f64, f64),
    (y, ly, wy): (&Solution, f64, f64),
    with_lambda: bool,
) -> (Guess, f64) {
    let n = x.n;
    let same = x.mesh == y.mesh;
    let mut z = vec![0.0; x.z.len()];
    let mut buf = vec![0.0; n];
    for (i, &s) in x.mesh.iter().enumerate() {
        let yi: &[f64] = if same {
            y.node(i)
        } else {
            y.eval(s, &mut buf);
            &buf
        };
        for j in 0..n {
            z[i * n + j] = wx * x.z[i * n + j] + wy * yi[j];
        }
    }
    let mut params: Vec<f64> = x
        .params
        .iter()
        .zip(&y.params)
        .map(|(a, b)| wx * a + wy * b)
        .collect();
    let lambda = wx * lx + wy * ly;
    let mut dz = vec![0.0; z.len()];
    for (i, &s) in x.mesh.iter().enumerate() {
        family.rhs(
            s,
            &z[i * n..(i + 1) * n],
            &params,
            lambda,
            &mut dz[i * n..(i + 1) * n],
        );
    }
    let dz = dz.iter().all(|d| d.is_finite()).then_some(dz);
    if with_lambda {
        params.push(lambda);
    }
    (
        Guess {
            n,
            mesh: x.mesh.clone(),
            z,
            dz,
            params,
        },
        lambda,
    )
}

/// Locates the fold bracketed by `pts = [A, B, C]` (`λ_B` extreme) by Brent's minimisation of
/// `∓λ(t)` along the chord parameter `t` (see the module docs).
fn locate_fold<P: ParamBvp + ?Sized, S: BvpSolver>(
    family: &P,
    solver: &mut S,
    opts: &ContinuationOptions,
    pts: [&Node; 3],
    kind: FoldKind,
    stats: &mut Stats,
) -> Fold {
    let theta = opts.theta;
    let [a, b, c] = pts;
    let sgn = if kind == FoldKind::Max { -1.0 } else { 1.0 };
    let mut tau: Vec<f64> = c.v.iter().zip(&a.v).map(|(x, y)| x - y).collect();
    let len = wnorm(&tau, theta);
    tau.iter_mut().for_each(|t| *t /= len);
    let tpar = |v: &[f64]| {
        let d: Vec<f64> = v.iter().zip(&a.v).map(|(x, y)| x - y).collect();
        wdot(&tau, &d, theta)
    };
    // Evaluated points: (t, λ, solution with p only).
    let mut evals: Vec<(f64, f64, Solution)> = vec![
        (0.0, a.lambda, a.sol.clone()),
        (tpar(&b.v), b.lambda, b.sol.clone()),
        (len, c.lambda, c.sol.clone()),
    ];
    let fallback = |evals: &[(f64, f64, Solution)], n_eval: usize| {
        let best = evals
            .iter()
            .min_by(|x, y| (sgn * x.1).total_cmp(&(sgn * y.1)))
            .unwrap_or(&evals[1]);
        Fold {
            lambda: best.1,
            sigma: a.sigma + best.0,
            kind,
            solution: best.2.clone(),
            located: false,
            evaluations: n_eval,
        }
    };
    let tb = evals[1].0;
    if !(tb > 0.0 && tb < len) {
        return fallback(&evals, 0);
    }
    // Curvature of λ(t) from the parabola through A, B, C: λ ≈ λ* − K (t − t*)².
    let f2 = ((c.lambda - b.lambda) / (len - tb) - (b.lambda - a.lambda) / tb) / len;
    let kcurv = f2.abs().max(f64::MIN_POSITIVE);
    let xtol = 0.25 * (opts.fold_tol / kcurv).sqrt();
    let max_eval: u64 = 60;

    let mut eval = |t: f64, evals: &mut Vec<(f64, f64, Solution)>| -> Option<f64> {
        // Warm start: linear blend of the evaluated neighbours in t.
        let lo = evals
            .iter()
            .filter(|e| e.0 <= t)
            .max_by(|x, y| x.0.total_cmp(&y.0))?;
        let hi = evals
            .iter()
            .filter(|e| e.0 >= t)
            .min_by(|x, y| x.0.total_cmp(&y.0))?;
        let w = if hi.0 > lo.0 {
            (t - lo.0) / (hi.0 - lo.0)
        } else {
            0.0
        };
        let (near, far, wn) = if w >= 0.5 {
            (hi, lo, w)
        } else {
            (lo, hi, 1.0 - w)
        };
        let (guess, _) = blend(
            family,
            (&near.2, near.1, wn),
            (&far.2, far.1, 1.0 - wn),
            true,
        );
        let anchor: Vec<f64> = a.v.iter().zip(&tau).map(|(v, d)| v + t * d).collect();
        let problem = Arclength::new(family, tau.clone(), anchor, theta).ok()?;
        match solver.solve(&problem, &guess) {
            Ok(mut sol) => {
                stats.accumulate(&sol.stats);
                let lambda = sol.params.pop()?;
                evals.push((t, lambda, sol));
                Some(sgn * lambda)
            }
            Err(e) => {
                if let Some(s) = e.stats() {
                    stats.accumulate(s);
                }
                None
            }
        }
    };

    // Brent's minimisation (argmin's BrentOpt: golden section with parabolic steps) on [0, len];
    // a failed solve ends it and the best point so far is returned, unlocated
    let (x, fx, located) = {
        let cost = FoldCost {
            f: RefCell::new(|t: f64| eval(t, &mut evals)),
        };
        let solver = BrentOpt::new(0.0, len).set_tolerance(1e-10, xtol);
        match Executor::new(cost, solver)
            .configure(|st| st.max_iters(max_eval))
            .run()
        {
            Ok(r) => {
                let st = r.state();
                let converged = st.get_termination_status()
                    == &TerminationStatus::Terminated(TerminationReason::SolverConverged);
                match st.get_best_param() {
                    Some(&x) => (x, st.get_best_cost(), converged),
                    None => (tb, sgn * b.lambda, false),
                }
            }
            Err(_) => {
                let n_eval = evals.len() - 2;
                return fallback(&evals, n_eval);
            }
        }
    };
    let best = evals
        .iter()
        .min_by(|p, q| (p.0 - x).abs().total_cmp(&(q.0 - x).abs()))
        .unwrap_or(&evals[1]);
    Fold {
        lambda: sgn * fx,
        sigma: a.sigma + x,
        kind,
        solution: best.2.clone(),
        located,
        evaluations: evals.len() - 3,
    }
}

/// A fold's `sgn·λ(t)` as an argmin cost; a failed solve is an error that ends the search.
struct FoldCost<F> {
    f: RefCell<F>,
}

impl<F: FnMut(f64) -> Option<f64>> CostFunction for FoldCost<F> {
    type Param = f64;
    type Output = f64;
    fn cost(&self, t: &f64) -> Result<f64, argmin::core::Error> {
        (self.f.borrow_mut())(*t).ok_or_else(|| argmin::core::Error::msg("the solve failed"))
    }
}
