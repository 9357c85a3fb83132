//! Single and multiple shooting.
//!
//! # Method
//!
//! Split `[a, b]` into `M` segments `a = t_0 < t_1 < … < t_M = b` (`M = segments` equal ones, or
//! the given [`ShootingOptions::nodes`]; `M = 1` is single shooting). The unknowns are the states at the segment starts and the parameters,
//!
//! ```text
//!     u = (z_0, z_1, …, z_{M−1}, p)            N = M n + k unknowns,
//! ```
//!
//! and `Z_j(t; z_j, p)` is the numerical solution on segment `j` started from `z_j` at `t_j`. The
//! residual stacks the boundary conditions and the continuity conditions
//!
//! ```text
//!     R(u) = ( g(z_0, Z_{M−1}(b), p),   Z_0(t_1) − z_1,  …,  Z_{M−2}(t_{M−1}) − z_{M−1} ).
//! ```
//!
//! Its Jacobian is assembled from `Φ_j = ∂Z_j/∂z_j` and `Ψ_j = ∂Z_j/∂p`, integrated with the
//! variational equations by the same Runge–Kutta stages (see below; `∂F/∂z` at every stage,
//! analytic or by central differences with the columns grouped by its learned sparsity,
//! [`crate::fd`]; with a learned pattern only the entries of `Φ` it can reach are integrated),
//! and the boundary Jacobians
//! `G_a, G_b, G_p` (analytic or finite differences, [`crate::fd`]):
//!
//! ```text
//!     BC rows:          G_a at z_0,   G_b Φ_{M−1} at z_{M−1},   G_p + G_b Ψ_{M−1} at p
//!     continuity j:     Φ_j at z_j,   −I at z_{j+1},            Ψ_j at p
//! ```
//!
//! The `N × N` system is solved by dense LU with partial pivoting ([`crate::linalg`]; `N` is small)
//! inside the damped Newton iteration of [`crate::newton`].
//!
//! # Integrators
//!
//! - [`Integrator::Rk4`]: classical RK4 with `steps` steps in total, split over the segments in
//!   proportion to their lengths (at least one each). The variational equations are integrated with the same stages,
//!   so the Newton matrix is the exact Jacobian of the discrete residual: quadratic convergence.
//!   Global error `O(h⁴)`.
//! - [`Integrator::Adaptive`]: Dormand–Prince 8(5,3) (DOP853) with Hairer's error norm on `z`,
//!   tolerance `atol + rtol·|z|` per component, I controller. The variational equations use the
//!   same stages and accepted steps, so the Jacobian is exact for the frozen step sequence; the
//!   dependence of the step sizes on `u` is ignored (it is of the size of the local tolerance).
//!   Each integration starts from Hairer's initial step estimate, so the discrete map depends on
//!   `u` only.
//!
//! # Output: what is returned is what is checked
//!
//! Newton converges on the trajectory of the integrator's own tolerance (the *coarse* one). The
//! returned [`Solution`] is a second, *fine* trajectory from the converged segment starts:
//! RK4 repeats the same steps; DOP853 integrates at `rtol/100`, `atol/100` (steps ≈ 1.8×
//! shorter), because its nodal values are far more accurate than its 7th-order continuous
//! extension between them. For the adaptive pair:
//!
//! 1. The fine trajectory's own residual `R` (boundary conditions on its ends, jumps at the
//!    segment joints) is evaluated; while it exceeds Newton's threshold, chord steps
//!    `u ← u − J⁻¹ R` with Newton's last matrix (at most 3) and, if they do not converge, Newton
//!    on the fine trajectory itself correct the starts. `stats.residual` is the max-norm of `R`
//!    of the trajectory returned.
//! 2. Error estimate: `max |S_coarse(s) − S_fine(s)|_j / (1 + max |z_j|)` over the fine nodes and
//!    the midpoints of the fine steps (both dense outputs), componentwise relative to the
//!    solution's scale (`max |z_j|` over the returned trajectory). It estimates the coarse
//!    trajectory's error, so it bounds the returned one's with a margin (by DOP853's tolerance
//!    proportionality, typically 100×: the Cash–Mazzia study measures the error/estimate ratio
//!    below 1 wherever the error exceeds `1e-9`). `stats.error_estimate`.
//! 3. Both are checked against [`ShootingOptions::tol`] (default `1000·rtol`); a miss is
//!    [`BvpError::Inaccurate`], never a success.
//! 4. Conditioning: `A = ‖J⁻¹‖∞` (two solves with Newton's factorization): the integration
//!    leaves residuals of relative size `δ = min(rtol, 1e-6)` (at loose `rtol` DOP853 delivers
//!    far more than asked), which may move the solution by `A · δ · (1 + ‖u‖∞)`; if `A · δ > 1`
//!    no digit is certain (a problem without a
//!    locally unique solution, e.g. a homogeneous solution that meets the boundary conditions)
//!    and [`BvpError::SingularJacobian`] is reported, as collocation does.
//!
//! The mesh of the returned solution is every accepted step of the fine pass (segment ends
//! coincide with the next segment's start; the start value is kept), `dz = F(s_i, z_i, p)`, and
//! [`Solution::eval`] interpolates with each integrator's own continuous extension: cubic Hermite
//! for RK4 (`O(h⁴)`, its order) and DOP853's 7th-order extension (Hairer's `contd8`, three extra
//! stages per step, [`crate::Dense::Dop853`]). Statistics: `rhs_evals`, `jac_evals` (`∂F`
//! evaluations, one per stage when linearizing), `bc_evals`, `steps`, `rejected_steps`,
//! `newton_iters`, `factorizations`, `nodes` (= `M + 1` segment nodes), `residual` and
//! `error_estimate` as above (RK4: no estimate; fixed steps have no error control).
//!
//! Globalization is local: damped Newton only finds the solution the guess is attracted to. Single
//! shooting can fail where the initial-value problem is sensitive (see
//! [`crate::samples::Cantilever::guess`]); more segments, a better guess or continuation help.
//!
//! The solver owns its work buffers: repeated solves of problems of the same size do not allocate
//! except for the returned [`Solution`].

use crate::fd::{bc_jacobian_or_fd, FdScratch};
use crate::linalg::{DenseLu, DEFAULT_PIVOT_TOL};
use crate::newton::{attach, non_finite, singular, Newton, NewtonSystem};
use crate::rk::{Mode, Recorder, RkWork, DENSE_RECORD};
use crate::singular::{Regular, SERIES_START};
use crate::{
    Bvp, BvpError, BvpSolver, Check, Dense, Dims, Guess, NewtonOptions, Solution, Stats, Status,
};

/// Integrator used for shooting.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub enum Integrator {
    /// Classical fixed-step RK4 with `steps` steps over the whole interval (split over segments).
    Rk4 {
        /// Total number of steps over `[a, b]`.
        steps: usize,
    },
    /// Adaptive embedded Runge–Kutta pair with error control (DOP853).
    Adaptive {
        /// Relative tolerance.
        rtol: f64,
        /// Absolute tolerance.
        atol: f64,
    },
}

/// Options of [`Shooting`].
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ShootingOptions {
    /// Integrator. Default: `Adaptive { rtol: 1e-10, atol: 1e-12 }`.
    pub integrator: Integrator,
    /// Number of equal shooting segments; 1 is single shooting. Default 1. Ignored when `nodes`
    /// is given.
    pub segments: usize,
    /// Segment boundaries `a = t_0 < t_1 < … < t_M = b` for non-uniform multiple shooting
    /// (e.g. denser where the solution varies fast). Default empty: `segments` equal segments.
    /// Valid: finite, strictly increasing, at least 2 values; the first and last must be the
    /// problem's interval ends (checked at solve time).
    pub nodes: Vec<f64>,
    /// Newton options. Default [`NewtonOptions::default`].
    pub newton: NewtonOptions,
    /// Cap on the steps of one adaptive integration of one segment (exceeding it is reported as
    /// [`BvpError::StepSizeTooSmall`]). Default 100 000.
    pub max_steps: usize,
    /// Relative pivot threshold of the dense LU (see [`crate::linalg`]): the Newton matrix counts
    /// as singular when a pivot is below `pivot_tol · max|J_ij|`. Default 1e-14.
    pub pivot_tol: f64,
    /// Accuracy the returned solution must meet: its error estimate (scaled componentwise by
    /// `1 + max |z_j|` over the trajectory, see the module docs) and the boundary and continuity
    /// residual of the returned trajectory, else [`BvpError::Inaccurate`]. Default `None`:
    /// `1000 · rtol` for the adaptive integrator (the estimate describes the Newton-tolerance
    /// trajectory, typically ~100× less accurate than the returned one, so this asks for a
    /// returned error near `10 · rtol`), no check for RK4 (fixed steps have no error estimate;
    /// the residual of its trajectory is Newton's). Set it to state the accuracy you need, with
    /// `rtol ≈ tol / 100` (what [`BvpSolver::set_tolerance`] does). Valid: `0 < tol < 1`.
    pub tol: Option<f64>,
}

impl Default for ShootingOptions {
    fn default() -> Self {
        ShootingOptions {
            integrator: Integrator::Adaptive {
                rtol: 1e-10,
                atol: 1e-12,
            },
            segments: 1,
            nodes: Vec::new(),
            newton: NewtonOptions::default(),
            max_steps: 100_000,
            pivot_tol: DEFAULT_PIVOT_TOL,
            tol: None,
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

impl ShootingOptions {
    /// Number of segments `M`: from `nodes` if given, else `segments`.
    pub fn segment_count(&self) -> usize {
        if self.nodes.is_empty() {
            self.segments
        } else {
            self.nodes.len() - 1
        }
    }

    /// The accuracy checked on the returned solution: `tol`, or `1000 · rtol` (adaptive) when
    /// unset; `None` for RK4 without `tol`.
    pub fn accuracy_tol(&self) -> Option<f64> {
        match (self.tol, self.integrator) {
            (Some(t), _) => Some(t),
            (None, Integrator::Adaptive { rtol, .. }) => Some(DEFAULT_TOL_FACTOR * rtol),
            (None, Integrator::Rk4 { .. }) => None,
        }
    }

    /// Checks the ranges: `segments ≥ 1`; RK4: `steps ≥ 1` and `segments ≤ steps`; adaptive:
    /// `0 < rtol < 1`, `atol ≥ 0` (finite); `max_steps ≥ 1`; `0 ≤ pivot_tol < 1`; Newton options
    /// ([`NewtonOptions::validate`]).
    pub fn validate(&self) -> Result<(), BvpError> {
        if self.segments < 1 {
            return Err(invalid("segments", self.segments, "must be >= 1"));
        }
        if !self.nodes.is_empty()
            && (self.nodes.len() < 2
                || !self.nodes.iter().all(|t| t.is_finite())
                || !self.nodes.windows(2).all(|w| w[1] > w[0]))
        {
            return Err(invalid(
                "nodes",
                format!("{:?}", self.nodes),
                "must be empty or >= 2 finite, strictly increasing values",
            ));
        }
        match self.integrator {
            Integrator::Rk4 { steps } => {
                if steps < 1 {
                    return Err(invalid("integrator.steps", steps, "must be >= 1"));
                }
                if self.segment_count() > steps {
                    return Err(invalid(
                        "segments",
                        self.segments,
                        "must be <= integrator.steps (each segment needs an RK4 step)",
                    ));
                }
            }
            Integrator::Adaptive { rtol, atol } => {
                if !(rtol > 0.0 && rtol < 1.0) {
                    return Err(invalid("integrator.rtol", rtol, "must be in (0, 1)"));
                }
                if !(atol >= 0.0 && atol.is_finite()) {
                    return Err(invalid("integrator.atol", atol, "must be finite and >= 0"));
                }
            }
        }
        if self.max_steps < 1 {
            return Err(invalid("max_steps", self.max_steps, "must be >= 1"));
        }
        if !(self.pivot_tol >= 0.0 && self.pivot_tol < 1.0) {
            return Err(invalid("pivot_tol", self.pivot_tol, "must be in [0, 1)"));
        }
        if let Some(tol) = self.tol {
            if !(tol > 0.0 && tol < 1.0) {
                return Err(invalid("tol", tol, "must be in (0, 1)"));
            }
        }
        self.newton.validate()
    }
}

/// Work buffers (sized on each solve, reused between solves).
#[derive(Clone, Debug, Default)]
struct Work {
    dims: Option<Dims>,
    segments: usize,
    /// Segment nodes `t_0..t_M`.
    nodes: Vec<f64>,
    rk: RkWork,
    /// End states `Z_j(t_{j+1})`, `M × n`.
    zend: Vec<f64>,
    /// End sensitivities `W_j = [Φ_j | Ψ_j]`, `M × n × (n + k)`.
    wend: Vec<f64>,
    /// `u` at which `zend`, `wend` were computed (valid if `cached`).
    cache_u: Vec<f64>,
    cached: bool,
    r_scratch: Vec<f64>,
    dga: Vec<f64>,
    dgb: Vec<f64>,
    dgp: Vec<f64>,
    fd: FdScratch,
    lu: DenseLu,
    /// DOP853 steps of an output pass with their continuous extension (reused between passes).
    records: Vec<f64>,
    /// Singular term: the first segment starts at this offset from the series at `s = 0`.
    series: Option<f64>,
    /// Start state of a segment started from the series.
    zs: Vec<f64>,
    /// Residual of an output pass, chord steps, and `n`-vectors of the error estimate.
    r_out: Vec<f64>,
    du: Vec<f64>,
    va: Vec<f64>,
    vb: Vec<f64>,
    scale: Vec<f64>,
}

impl Work {
    fn resize(&mut self, dims: Dims, segments: usize, a: f64, b: f64, given: &[f64]) {
        let (n, k) = (dims.n, dims.k);
        let m = n + k;
        let big_n = segments * n + k;
        if self.dims != Some(dims) || self.segments != segments {
            self.rk.resize(dims);
            self.fd.resize(dims);
            for (v, len) in [
                (&mut self.zend, segments * n),
                (&mut self.wend, segments * n * m),
                (&mut self.cache_u, big_n),
                (&mut self.r_scratch, big_n),
                (&mut self.dga, m * n),
                (&mut self.dgb, m * n),
                (&mut self.dgp, m * k),
                (&mut self.r_out, big_n),
                (&mut self.du, big_n),
                (&mut self.va, n),
                (&mut self.vb, n),
                (&mut self.zs, n),
                (&mut self.scale, n),
            ] {
                v.clear();
                v.resize(len, 0.0);
            }
            self.lu.resize(big_n);
            self.dims = Some(dims);
            self.segments = segments;
        }
        self.nodes.clear();
        if given.is_empty() {
            self.nodes
                .extend((0..=segments).map(|j| a + (b - a) * j as f64 / segments as f64));
        } else {
            self.nodes.extend_from_slice(given);
            self.nodes[0] = a;
        }
        self.nodes[segments] = b;
        self.cached = false;
    }
}

impl Work {
    /// Start of segment `j` from the unknowns `uj` (its start values): `(t_j, z)` with `z` in
    /// `zs`; the first segment of a singular problem starts at `δ` from the series
    /// `z(δ) = z(0) + δ z'(0)`, `z'(0) = F(0, z(0))` of the regularized problem.
    fn start<P: Bvp + ?Sized>(
        &mut self,
        problem: &P,
        p: &[f64],
        j: usize,
        uj: &[f64],
        stats: &mut Stats,
    ) -> f64 {
        match self.series {
            Some(delta) if j == 0 => {
                problem.rhs(self.nodes[0], uj, p, &mut self.zs);
                stats.rhs_evals += 1;
                for (z, u) in self.zs.iter_mut().zip(uj) {
                    *z = u + delta * *z;
                }
                self.nodes[0] + delta
            }
            _ => {
                self.zs.copy_from_slice(uj);
                self.nodes[j]
            }
        }
    }
}

/// Default accuracy of the returned solution in units of `rtol` ([`ShootingOptions::tol`]).
const DEFAULT_TOL_FACTOR: f64 = 1000.0;
/// Largest relative residual size assumed by the conditioning check.
const CONDITIONING_DELTA_MAX: f64 = 1e-6;
/// `rtol` per unit of `tol` set by [`BvpSolver::set_tolerance`].
const RTOL_PER_TOL: f64 = 0.01;
/// Tolerance factor of the adaptive output pass (see [`Solution`] in the module docs).
const DENSE_TOL_FACTOR: f64 = 0.01;
/// Smallest relative tolerance of the output pass (DOP853 near the rounding limit).
const OUTPUT_RTOL_MIN: f64 = 2.5e-14;

/// Single / multiple shooting solver.
#[derive(Clone, Debug)]
pub struct Shooting {
    opts: ShootingOptions,
    work: Work,
    newton: Newton,
    u: Vec<f64>,
}

impl Shooting {
    /// Creates a solver; validates the options.
    pub fn new(opts: ShootingOptions) -> Result<Self, BvpError> {
        opts.validate()?;
        Ok(Shooting {
            opts,
            work: Work::default(),
            newton: Newton::new(),
            u: Vec::new(),
        })
    }
    /// The options.
    pub fn options(&self) -> &ShootingOptions {
        &self.opts
    }
}

/// Steps of RK4 on segment `j` of `nodes`: `steps` in total in proportion to the segment lengths,
/// at least one per segment (equal segments: the remainder goes to the first ones).
fn rk4_steps(steps: usize, nodes: &[f64], uniform: bool, j: usize) -> usize {
    let segments = nodes.len() - 1;
    if uniform {
        return steps / segments + usize::from(j < steps % segments);
    }
    let len = nodes[segments] - nodes[0];
    let extra = steps - segments;
    // Cumulative rounding keeps the total exact.
    let cum = |i: usize| ((nodes[i] - nodes[0]) / len * extra as f64 + 1e-9).floor() as usize;
    let end = if j + 1 == segments { extra } else { cum(j + 1) };
    1 + end - cum(j)
}

/// The Newton system of (multiple) shooting.
struct System<'a, P: ?Sized> {
    problem: &'a P,
    opts: &'a ShootingOptions,
    w: &'a mut Work,
    /// Integrate at the output tolerances (`DENSE_TOL_FACTOR` × the integrator's).
    fine: bool,
}

impl<P: Bvp + ?Sized> System<'_, P> {
    fn mode(&self, j: usize) -> Mode {
        match self.opts.integrator {
            Integrator::Rk4 { steps } => Mode::Fixed {
                steps: rk4_steps(steps, &self.w.nodes, self.opts.nodes.is_empty(), j),
            },
            // Output tolerances: steps 100^(1/8) ≈ 1.8× shorter than Newton's, so the 7th-order
            // extension between them is as accurate as the nodes (which DOP853 gets far below
            // rtol).
            Integrator::Adaptive { rtol, atol } if self.fine => Mode::Adaptive {
                rtol: (DENSE_TOL_FACTOR * rtol).max(OUTPUT_RTOL_MIN),
                atol: DENSE_TOL_FACTOR * atol,
                max_steps: 2 * self.opts.max_steps,
            },
            Integrator::Adaptive { rtol, atol } => Mode::Adaptive {
                rtol,
                atol,
                max_steps: self.opts.max_steps,
            },
        }
    }

    /// Integrates all segments (with sensitivities) from `u` and writes `R(u)` into `r`.
    fn evaluate(&mut self, u: &[f64], r: &mut [f64], stats: &mut Stats) -> Result<(), BvpError> {
        let Dims { n, k } = self.problem.dims();
        let m = n + k;
        let segs = self.w.segments;
        let p = &u[segs * n..];
        self.w.cached = false;
        for j in 0..segs {
            let mode = self.mode(j);
            let w = &mut *self.w;
            let t0 = w.start(self.problem, p, j, &u[j * n..(j + 1) * n], stats);
            w.rk.integrate(
                self.problem,
                p,
                t0,
                w.nodes[j + 1],
                &w.zs,
                true,
                mode,
                None,
                stats,
            )?;
            w.zend[j * n..(j + 1) * n].copy_from_slice(w.rk.z());
            w.wend[j * n * m..(j + 1) * n * m].copy_from_slice(w.rk.w());
        }
        let w = &mut *self.w;
        let zb = &w.zend[(segs - 1) * n..segs * n];
        self.problem.bc(&u[..n], zb, p, &mut r[..m]);
        stats.bc_evals += 1;
        if !r[..m].iter().all(|v| v.is_finite()) {
            return Err(non_finite("bc", f64::NAN));
        }
        for j in 0..segs - 1 {
            for i in 0..n {
                r[m + j * n + i] = w.zend[j * n + i] - u[(j + 1) * n + i];
            }
        }
        w.cache_u.copy_from_slice(u);
        w.cached = true;
        Ok(())
    }
}

impl<P: Bvp + ?Sized> NewtonSystem for System<'_, P> {
    fn residual(&mut self, u: &[f64], r: &mut [f64], stats: &mut Stats) -> Result<(), BvpError> {
        self.evaluate(u, r, stats)
    }

    fn solve_linearized(
        &mut self,
        u: &[f64],
        r: &[f64],
        du: &mut [f64],
        stats: &mut Stats,
    ) -> Result<(), BvpError> {
        if !(self.w.cached && self.w.cache_u == u) {
            let mut rs = std::mem::take(&mut self.w.r_scratch);
            let res = self.evaluate(u, &mut rs, stats);
            self.w.r_scratch = rs;
            res?;
        }
        let Dims { n, k } = self.problem.dims();
        let m = n + k;
        let segs = self.w.segments;
        let big_n = segs * n + k;
        let w = &mut *self.w;
        let p = &u[segs * n..];
        let zb = &w.zend[(segs - 1) * n..segs * n];
        bc_jacobian_or_fd(
            self.problem,
            &u[..n],
            zb,
            p,
            Some(&r[..m]),
            &mut w.dga,
            &mut w.dgb,
            &mut w.dgp,
            &mut w.fd,
            stats,
        )?;

        w.lu.pivot_tol = self.opts.pivot_tol;
        let a = w.lu.matrix_mut();
        a.fill(0.0);
        let last = segs - 1;
        let wl = &w.wend[last * n * m..(last + 1) * n * m];
        // Boundary rows.
        for i in 0..m {
            let row = &mut a[i * big_n..(i + 1) * big_n];
            for (x, &g) in row[..n].iter_mut().zip(&w.dga[i * n..(i + 1) * n]) {
                *x += g;
            }
            // G_b W_{M−1} into the columns of z_{M−1} and p.
            for l in 0..n {
                let g = w.dgb[i * n + l];
                if g != 0.0 {
                    for c in 0..n {
                        row[last * n + c] += g * wl[l * m + c];
                    }
                    for c in 0..k {
                        row[segs * n + c] += g * wl[l * m + n + c];
                    }
                }
            }
            for c in 0..k {
                row[segs * n + c] += w.dgp[i * k + c];
            }
        }
        // Continuity rows.
        for j in 0..last {
            let wj = &w.wend[j * n * m..(j + 1) * n * m];
            for i in 0..n {
                let row = &mut a[(m + j * n + i) * big_n..(m + j * n + i + 1) * big_n];
                row[j * n..(j + 1) * n].copy_from_slice(&wj[i * m..i * m + n]);
                row[(j + 1) * n + i] = -1.0;
                row[segs * n..].copy_from_slice(&wj[i * m + n..(i + 1) * m]);
            }
        }
        stats.factorizations += 1;
        w.lu.factor().map_err(|_| singular())?;
        for (d, v) in du.iter_mut().zip(r) {
            *d = -v;
        }
        w.lu.solve(du);
        Ok(())
    }

    fn resolve(&mut self, r: &[f64], du: &mut [f64]) -> Result<bool, BvpError> {
        for (d, v) in du.iter_mut().zip(r) {
            *d = -v;
        }
        self.w.lu.solve(du);
        Ok(true)
    }
}

impl BvpSolver for Shooting {
    fn tolerance(&self) -> Option<f64> {
        self.opts.accuracy_tol()
    }

    /// Sets `tol` and, for the adaptive integrator, `rtol = tol / 100` (and `atol` in the same
    /// ratio); values outside `(0, 1)` are ignored.
    fn set_tolerance(&mut self, tol: f64) {
        if !(tol > 0.0 && tol < 1.0) {
            return;
        }
        if let Integrator::Adaptive { rtol, atol } = self.opts.integrator {
            let new = tol * RTOL_PER_TOL;
            self.opts.integrator = Integrator::Adaptive {
                rtol: new,
                atol: atol * new / rtol,
            };
        }
        self.opts.tol = Some(tol);
    }

    fn solve<P: Bvp + ?Sized>(&mut self, problem: &P, guess: &Guess) -> Result<Solution, BvpError> {
        match Regular::new(problem)? {
            Some(reg) => self.solve_plain(&reg, guess, true),
            None => self.solve_plain(problem, guess, false),
        }
    }
}

impl Shooting {
    /// [`BvpSolver::solve`]; `series`: the problem is a regularized singular one (start the
    /// first segment from the series at `s = 0`, see [`Bvp::singular_term`]).
    fn solve_plain<P: Bvp + ?Sized>(
        &mut self,
        problem: &P,
        guess: &Guess,
        series: bool,
    ) -> Result<Solution, BvpError> {
        let dims = problem.dims();
        let Dims { n, k } = dims;
        let (a, b) = problem.interval();
        guess.validate(dims, (a, b))?;
        let segs = self.opts.segment_count();
        if let (Some(&t0), Some(&t1)) = (self.opts.nodes.first(), self.opts.nodes.last()) {
            let tol = 1e-12 * (b - a);
            if (t0 - a).abs() > tol || (t1 - b).abs() > tol {
                return Err(invalid(
                    "nodes",
                    format!("[{t0}, …, {t1}]"),
                    "must start at a and end at b of the problem's interval",
                ));
            }
        }
        self.work.resize(dims, segs, a, b, &self.opts.nodes);
        self.work.series = series.then_some(SERIES_START * (b - a));
        // A regularized singular problem changes form at s = 0: no learned pattern there.
        self.work.rk.learn_sparsity(!series);

        // Warm start: guess values at the segment starts, guess parameters.
        self.u.clear();
        self.u.resize(segs * n + k, 0.0);
        for j in 0..segs {
            guess.eval(self.work.nodes[j], &mut self.u[j * n..(j + 1) * n]);
        }
        self.u[segs * n..].copy_from_slice(&guess.params);

        let mut stats = Stats {
            nodes: segs + 1,
            ..Stats::default()
        };
        {
            let nopts = self.newton_options();
            let mut sys = System {
                problem,
                opts: &self.opts,
                w: &mut self.work,
                fine: false,
            };
            self.newton
                .solve(&mut sys, &mut self.u, &nopts, &mut stats)?;
        }

        let newton_residual = stats.residual;
        let adaptive = matches!(self.opts.integrator, Integrator::Adaptive { .. });
        let big_n = segs * n + k;
        let mut r = std::mem::take(&mut self.work.r_out);
        r.resize(big_n, 0.0);
        let out = self.output(problem, adaptive, newton_residual, &mut r, &mut stats);
        self.work.r_out = r;
        let (sol, est) = out?;
        let res = max_norm(&self.work.r_out);
        self.finish(sol, res, est, stats)
    }
}

impl Shooting {
    /// Newton's options with the residual threshold `min(newton.tol, tol)`: the returned
    /// trajectory's boundary residual is checked against `tol`.
    fn newton_options(&self) -> NewtonOptions {
        let mut o = self.opts.newton.clone();
        if let Some(tol) = self.opts.accuracy_tol() {
            o.tol = o.tol.min(tol);
        }
        o
    }

    /// The output pass and its checks (see [`BvpSolver::solve`]): the returned trajectory with
    /// its residual in `r` and its error estimate.
    fn output<P: Bvp + ?Sized>(
        &mut self,
        problem: &P,
        adaptive: bool,
        newton_residual: f64,
        r: &mut [f64],
        stats: &mut Stats,
    ) -> Result<(Solution, Option<f64>), BvpError> {
        if !adaptive {
            // RK4: the output pass repeats Newton's discretization; its residual is checked.
            self.check_conditioning(problem, stats)?;
            return Ok((self.trace(problem, false, r, stats)?, None));
        }
        // The trajectory Newton converged on (coarse), then the output pass at a tighter
        // tolerance from the same starts; chord steps with Newton's last matrix until the
        // output trajectory itself meets the boundary and continuity conditions.
        let coarse = self.trace(problem, false, r, stats)?;
        let threshold = self.newton_options().tol.max(newton_residual);
        let mut chords = 0;
        let mut checked = false;
        let mut polished = false;
        let mut first = None;
        let fine = loop {
            let sol = self.trace(problem, true, r, stats)?;
            let res = max_norm(r);
            if !checked {
                checked = true;
                self.check_conditioning(problem, stats)?;
            }
            // After a polishing Newton the residual is Newton's own (checked against tol below).
            if res <= threshold || polished {
                break sol;
            }
            if first.is_none() {
                first = Some((sol, r.to_vec(), self.u.clone()));
            }
            if chords < MAX_CHORDS && res.is_finite() {
                chords += 1;
                self.chord_step(problem, r, stats)?;
            } else {
                // The chord with Newton's matrix does not converge: Newton at the output
                // tolerances.
                polished = true;
                let nopts = self.newton_options();
                let mut sys = System {
                    problem,
                    opts: &self.opts,
                    w: &mut self.work,
                    fine: true,
                };
                self.newton.solve(&mut sys, &mut self.u, &nopts, stats)?;
            }
        };
        let w = &mut self.work;
        let est = estimate(&coarse, &fine, &mut w.scale, &mut w.va, &mut w.vb) * ESTIMATE_FACTOR;
        let (Some(tol), Some((sol1, r1, u1))) = (self.opts.accuracy_tol(), first) else {
            return Ok((fine, Some(est)));
        };
        if est <= tol && max_norm(r) <= tol {
            return Ok((fine, Some(est)));
        }
        // The corrected trajectory fails its checks, but the one from Newton's own starts may
        // pass them (at `tol`, not at Newton's tighter threshold): where the problem is not
        // locally unique in some direction (scipy's 60-state problem with parameters: `c sin x`
        // for any `c`), the correction drifts along it (estimate 0.99 there) while the
        // uncorrected trajectory is within 5e-6 of the solution nearest Newton's.
        let est1 = estimate(&coarse, &sol1, &mut w.scale, &mut w.va, &mut w.vb) * ESTIMATE_FACTOR;
        if est1 <= tol && max_norm(&r1) <= tol {
            r.copy_from_slice(&r1);
            self.u = u1;
            return Ok((sol1, Some(est1)));
        }
        Ok((fine, Some(est)))
    }
}

/// Chord steps of the output pass before its boundary residual is reported as missed.
const MAX_CHORDS: usize = 3;
/// Factor from the difference of the Newton (coarse) and output (fine) trajectories to the
/// error estimate of the fine one (see the module docs).
const ESTIMATE_FACTOR: f64 = 1.0;

fn max_norm(x: &[f64]) -> f64 {
    x.iter().fold(0.0_f64, |m, v| m.max(v.abs()))
}

/// `max |coarse − fine| / (1 + max |fine|)` componentwise, over the nodes of `fine` and the
/// midpoints of its steps (dense output of both).
fn estimate(
    coarse: &Solution,
    fine: &Solution,
    scale: &mut [f64],
    a: &mut [f64],
    b: &mut [f64],
) -> f64 {
    let n = fine.n;
    scale.fill(1.0);
    for zi in fine.z.chunks_exact(n) {
        for (s, v) in scale.iter_mut().zip(zi) {
            *s = s.max(1.0 + v.abs());
        }
    }
    let mut est = 0.0_f64;
    for (i, &s) in fine.mesh.iter().enumerate() {
        let mid = fine.mesh.get(i + 1).map(|&t| 0.5 * (s + t));
        for x in std::iter::once(s).chain(mid) {
            coarse.eval(x, a);
            fine.eval(x, b);
            for j in 0..n {
                est = est.max((a[j] - b[j]).abs() / scale[j]);
            }
        }
    }
    est
}

impl Shooting {
    /// Integrates every segment from the current unknowns (without sensitivities), recording
    /// the steps (`fine`: at the output tolerances), and writes the residual `R` of that
    /// trajectory (boundary conditions on its ends, jumps at the segment joints) into `r`.
    fn trace<P: Bvp + ?Sized>(
        &mut self,
        problem: &P,
        fine: bool,
        r: &mut [f64],
        stats: &mut Stats,
    ) -> Result<Solution, BvpError> {
        let Dims { n, k } = problem.dims();
        let segs = self.work.segments;
        let u = &self.u;
        let p = &u[segs * n..];
        // RK4 knows its node count: one allocation per output vector.
        let nodes = match self.opts.integrator {
            Integrator::Rk4 { steps } => steps + 1,
            Integrator::Adaptive { .. } => 0,
        };
        let adaptive = matches!(self.opts.integrator, Integrator::Adaptive { .. });
        let mut mesh = Vec::with_capacity(nodes);
        let mut z = Vec::with_capacity(nodes * n);
        let mut dz = Vec::with_capacity(nodes * n);
        // DOP853 steps with their continuous extension, unpacked below.
        let mut records = std::mem::take(&mut self.work.records);
        records.clear();
        let sys = System {
            problem,
            opts: &self.opts,
            w: &mut self.work,
            fine,
        };
        let m = n + k;
        for j in 0..segs {
            let mode = sys.mode(j);
            let w = &mut *sys.w;
            let t0 = w.start(problem, p, j, &u[j * n..(j + 1) * n], stats);
            if t0 != w.nodes[j] {
                // Series start: the node s = 0 and the line to z(δ) (slope z'(0)).
                let u0 = &u[..n];
                let f0 =
                    w.zs.iter()
                        .zip(u0)
                        .map(|(a, b)| (a - b) / (t0 - w.nodes[0]));
                if adaptive {
                    records.push(w.nodes[0]);
                    records.extend_from_slice(u0);
                    records.extend(f0);
                    records.extend(w.zs.iter().zip(u0).map(|(a, b)| a - b));
                    records.extend(std::iter::repeat_n(0.0, 6 * n));
                } else {
                    mesh.push(w.nodes[0]);
                    z.extend_from_slice(u0);
                    dz.extend(f0);
                }
            }
            let mut rec = Recorder {
                mesh: &mut mesh,
                z: &mut z,
                dz: &mut dz,
                dense: adaptive.then_some(&mut records),
            };
            w.rk.integrate(
                problem,
                p,
                t0,
                w.nodes[j + 1],
                &w.zs,
                false,
                mode,
                Some(&mut rec),
                stats,
            )
            .map_err(|e| attach(e, stats.newton_iters, stats))?;
            if j + 1 < segs {
                for i in 0..n {
                    r[m + j * n + i] = w.rk.z()[i] - u[(j + 1) * n + i];
                }
            }
        }
        let mut coef = Vec::new();
        if adaptive {
            let per = DENSE_RECORD * n + 1;
            let steps = records.len() / per;
            mesh.reserve_exact(steps + 1);
            z.reserve_exact((steps + 1) * n);
            dz.reserve_exact((steps + 1) * n);
            coef.reserve_exact(7 * n * steps);
            for rc in records.chunks_exact(per) {
                mesh.push(rc[0]);
                z.extend_from_slice(&rc[1..1 + n]);
                dz.extend_from_slice(&rc[1 + n..1 + 2 * n]);
                coef.extend_from_slice(&rc[1 + 2 * n..]);
            }
        }
        sys.w.records = records;
        let zb = sys.w.rk.z();
        let b = sys.w.nodes[segs];
        let fb = &mut sys.w.va;
        problem.rhs(b, zb, p, fb);
        stats.rhs_evals += 1;
        problem.bc(&u[..n], zb, p, &mut r[..m]);
        stats.bc_evals += 1;
        mesh.push(b);
        z.extend_from_slice(zb);
        dz.extend_from_slice(fb);
        Ok(Solution {
            n,
            mesh,
            z,
            dz,
            params: p.to_vec(),
            status: Status::Converged,
            stats: Stats::default(),
            dense: if adaptive {
                Dense::Dop853 { coef }
            } else {
                Dense::Hermite
            },
        })
    }

    /// Conditioning: the integration leaves residuals of relative size `δ` (DOP853:
    /// `min(rtol, 1e-6)`, since at loose `rtol` its 8th-order steps deliver far more than asked;
    /// RK4: `tol` if set, else no check), which may move the solution by
    /// `‖J⁻¹‖∞ · δ · (1 + ‖u‖∞)`;
    /// beyond `1 + ‖u‖∞`, i.e. `‖J⁻¹‖∞ · δ > 1`, no digit is certain (the problem has no locally
    /// unique solution at this accuracy, e.g. a homogeneous solution meets the boundary
    /// conditions) and [`BvpError::SingularJacobian`] is reported.
    fn check_conditioning<P: Bvp + ?Sized>(
        &mut self,
        problem: &P,
        stats: &mut Stats,
    ) -> Result<(), BvpError> {
        let delta = match (self.opts.integrator, self.opts.tol) {
            (Integrator::Adaptive { rtol, .. }, _) => rtol.min(CONDITIONING_DELTA_MAX),
            (Integrator::Rk4 { .. }, Some(tol)) => tol.min(CONDITIONING_DELTA_MAX),
            (Integrator::Rk4 { .. }, None) => return Ok(()),
        };
        let amp = self.amplification(problem, stats)?;
        if amp * delta > 1.0 {
            return Err(BvpError::SingularJacobian {
                iteration: stats.newton_iters,
                stats: stats.clone(),
            });
        }
        Ok(())
    }

    /// `‖J⁻¹‖∞` estimated by two solves with Newton's last factorization (formed at `u` if Newton
    /// took no step), right-hand sides `(1, 1, …)` and `(1, −1, 1, …)`.
    fn amplification<P: Bvp + ?Sized>(
        &mut self,
        problem: &P,
        stats: &mut Stats,
    ) -> Result<f64, BvpError> {
        self.ensure_factored(problem, stats)?;
        let mut best = 0.0_f64;
        let w = &mut self.work;
        for sign in [1.0, -1.0] {
            for (i, x) in w.du.iter_mut().enumerate() {
                *x = if i % 2 == 0 { 1.0 } else { sign };
            }
            w.lu.solve(&mut w.du);
            best = best.max(max_norm(&w.du));
        }
        Ok(best)
    }

    fn ensure_factored<P: Bvp + ?Sized>(
        &mut self,
        problem: &P,
        stats: &mut Stats,
    ) -> Result<(), BvpError> {
        if stats.factorizations == 0 {
            let mut sys = System {
                problem,
                opts: &self.opts,
                w: &mut self.work,
                fine: false,
            };
            let (mut rc, mut du) = (
                std::mem::take(&mut sys.w.r_scratch),
                std::mem::take(&mut sys.w.du),
            );
            let res = sys.residual(&self.u, &mut rc, stats).and_then(|()| {
                sys.solve_linearized(&self.u, &rc, &mut du, stats)
                    .map_err(|e| attach(e, stats.newton_iters, stats))
            });
            (sys.w.r_scratch, sys.w.du) = (rc, du);
            res?;
        }
        Ok(())
    }

    /// One chord step `u ← u − J⁻¹ r` with Newton's last factorization (formed here at `u` if
    /// Newton took no step).
    fn chord_step<P: Bvp + ?Sized>(
        &mut self,
        problem: &P,
        r: &[f64],
        stats: &mut Stats,
    ) -> Result<(), BvpError> {
        self.ensure_factored(problem, stats)?;
        let w = &mut self.work;
        for (d, v) in w.du.iter_mut().zip(r) {
            *d = -v;
        }
        w.lu.solve(&mut w.du);
        for (x, d) in self.u.iter_mut().zip(&w.du) {
            *x += d;
        }
        Ok(())
    }

    /// The returned solution with its statistics: `residual` the boundary/continuity residual
    /// `res` of the returned trajectory, `error_estimate` `est`; both checked against `tol`.
    fn finish(
        &self,
        mut sol: Solution,
        res: f64,
        est: Option<f64>,
        mut stats: Stats,
    ) -> Result<Solution, BvpError> {
        stats.residual = res;
        stats.error_estimate = est;
        let tol = self.opts.accuracy_tol();
        if let Some(tol) = tol {
            for (check, value) in [
                (Check::BoundaryResidual, Some(stats.residual)),
                (Check::ErrorEstimate, est),
            ] {
                if let Some(v) = value {
                    if v > tol || v.is_nan() {
                        return Err(BvpError::Inaccurate {
                            check,
                            value: v,
                            tol,
                            stats,
                        });
                    }
                }
            }
        }
        sol.stats = stats;
        Ok(sol)
    }
}
