//! Finite-difference Jacobians (the default when a problem has no analytic ones).
//!
//! # Steps
//!
//! For a variable `x_j` the increment is
//!
//! ```text
//!     forward:  h_j = √ε · max(|x_j|, 1)      J[:, j] ≈ (f(x + h_j e_j) − f(x)) / h_j          error O(√ε)
//!     central:  h_j = ∛ε · max(|x_j|, 1)      J[:, j] ≈ (f(x + h_j e_j) − f(x − h_j e_j)) / 2h_j  error O(ε^⅔)
//! ```
//!
//! with `h_j` rounded so that `x_j + h_j` is exactly representable (`h = (x + h) − x`). Forward
//! differences cost one evaluation per column (plus `f(x)`, which callers usually have); central
//! ones two, but are about 1000× more accurate (≈ 1e-11 relative vs 1e-8).
//!
//! # Functions
//!
//! - [`jacobian`]: generic `m × N` Jacobian of a closure `f(x, out)`;
//! - [`rhs_jacobian_fd`], [`bc_jacobian_fd`]: `∂F/∂z, ∂F/∂p` and `∂g/∂z(a), ∂g/∂z(b), ∂g/∂p` of a
//!   [`Bvp`] (row-major, the layout of [`Bvp::rhs_jacobian`]);
//! - [`rhs_jacobian_or_fd`], [`bc_jacobian_or_fd`]: the analytic Jacobian when the problem
//!   provides it, else finite differences; they count evaluations in [`Stats`] and check the
//!   output for NaN/∞ ([`BvpError::NonFinite`] with location `"jacobian"`).
//!
//! All work vectors live in [`FdScratch`], so these functions do not allocate.
//!
//! # Sparse `∂F/∂z` (grouped columns)
//!
//! When a solver switches it on ([`FdScratch::learn_sparsity`]), [`rhs_jacobian_fd`] learns the
//! sparsity pattern of `∂F/∂z` at its first call: the nonzeros of the full difference quotient
//! there and of a forward-difference one at a deterministic perturbation of `z` (relative size
//! `1e-3`, so that entries that vanish only at this `z` — e.g. `∂(z_1 z_2)/∂z_1` at `z_2 = 0` —
//! are still found). Columns that share no row are grouped greedily (Curtis, Powell & Reid 1974)
//! and differenced together: one evaluation of `F` (two for central differences) per group
//! instead of per column, with the same step `h_j` per column as the plain formula. A system of
//! `n/2` uncoupled second-order equations needs one group instead of `n` columns.
//!
//! The pattern is checked at every later call: a row that no column of a group touches must come
//! out bit-for-bit unchanged (it reads nothing that was perturbed). A change means an entry was
//! missed (a piecewise `F`, a dependence that vanished at both probes): that Jacobian is
//! recomputed column by column, its nonzeros are added to the pattern and the columns regrouped.
//! An entry missed in a row that another column of its group covers cannot be seen that way; it
//! only slows Newton (a solver's acceptance never rests on the Jacobian). If grouping saves no
//! evaluation, the plain formula is used.

use crate::{Bvp, BvpError, Dims, Stats};

/// `√ε` and `∛ε` (`f64::EPSILON.cbrt()` is not `const`; the values are checked by a test):
/// computing them at every step took a seventh of multiple shooting's time on 60 states.
const SQRT_EPS: f64 = 1.490_116_119_384_765_6e-8;
const CBRT_EPS: f64 = 6.055_454_452_393_339_5e-6;

/// Finite-difference formula.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize)]
pub enum FdScheme {
    /// One-sided, step `√ε · max(|x|, 1)`.
    Forward,
    /// Central, step `∛ε · max(|x|, 1)`. The default.
    #[default]
    Central,
}

impl FdScheme {
    /// The increment for variable value `x` (exactly representable: `(x + h) − x == h`).
    pub fn step(self, x: f64) -> f64 {
        let base = match self {
            FdScheme::Forward => SQRT_EPS,
            FdScheme::Central => CBRT_EPS,
        };
        let h = base * x.abs().max(1.0);
        (x + h) - x
    }
}

/// Work vectors for the finite-difference routines (sized for one problem's [`Dims`]).
#[derive(Clone, Debug, Default)]
pub struct FdScratch {
    /// The formula used. Default [`FdScheme::Central`].
    pub scheme: FdScheme,
    x: Vec<f64>,
    y: Vec<f64>,
    q: Vec<f64>,
    f0: Vec<f64>,
    f1: Vec<f64>,
    f2: Vec<f64>,
    sparse: Sparsity,
}

/// Learned sparsity of `∂F/∂z` and its column groups (see the module docs).
#[derive(Clone, Debug, Default)]
struct Sparsity {
    /// Grouped differences switched on ([`FdScratch::learn_sparsity`]).
    enabled: bool,
    /// The pattern has been learned (at the first call after switching on).
    learned: bool,
    /// `n × n`, row-major: `∂F_i/∂z_j` seen nonzero.
    pattern: Vec<bool>,
    /// Number of column groups (grouping is used when `ngroups < n`).
    ngroups: usize,
    /// The group of each column.
    col_group: Vec<usize>,
    /// `n × n` (first `ngroups` rows used): the column of group `g` that touches row `i`, or
    /// [`NONE`].
    owner: Vec<usize>,
    /// The probe's `n × n` Jacobian.
    probe: Vec<f64>,
    /// The unperturbed point and the probe's `F` (`n` each).
    x0: Vec<f64>,
    fp: Vec<f64>,
    /// Column steps of the grouped formula (`h` forward, `h + h⁻` central).
    steps: Vec<f64>,
    /// Times the pattern was found incomplete and relearned (for tests and diagnostics).
    relearned: usize,
}

const NONE: usize = usize::MAX;

impl FdScratch {
    /// Scratch for a problem with `dims` (central differences).
    pub fn new(dims: Dims) -> Self {
        let mut s = FdScratch::default();
        s.resize(dims);
        s
    }

    /// Same, with the given scheme.
    pub fn with_scheme(dims: Dims, scheme: FdScheme) -> Self {
        let mut s = Self::new(dims);
        s.scheme = scheme;
        s
    }

    /// Resizes for `dims` (allocates only when growing).
    pub fn resize(&mut self, dims: Dims) {
        let (n, k) = (dims.n, dims.k);
        let m = n + k;
        for (v, len) in [
            (&mut self.x, n),
            (&mut self.y, n),
            (&mut self.q, k),
            (&mut self.f0, m),
            (&mut self.f1, m),
            (&mut self.f2, m),
        ] {
            v.clear();
            v.resize(len, 0.0);
        }
        let sp = &mut self.sparse;
        if sp.pattern.len() != n * n {
            sp.learned = false;
            sp.pattern.clear();
            sp.pattern.resize(n * n, false);
            sp.owner.clear();
            sp.owner.resize(n * n, NONE);
            sp.col_group.clear();
            sp.col_group.resize(n, 0);
            for (v, len) in [
                (&mut sp.probe, n * n),
                (&mut sp.x0, n),
                (&mut sp.fp, n),
                (&mut sp.steps, n),
            ] {
                v.clear();
                v.resize(len, 0.0);
            }
        }
    }

    /// Switches grouped differences of `∂F/∂z` on (`true`) or off for the following calls of
    /// [`rhs_jacobian_fd`] and forgets any learned pattern: call it at the start of each solve
    /// (a pattern belongs to one problem). Off by default.
    pub fn learn_sparsity(&mut self, on: bool) {
        self.sparse.enabled = on;
        self.sparse.learned = false;
        self.sparse.relearned = 0;
    }

    /// Column groups of the learned pattern of `∂F/∂z` (evaluations of `F` per forward
    /// difference), if grouped differences are in use.
    pub fn groups(&self) -> Option<usize> {
        let sp = &self.sparse;
        let n = self.x.len();
        (sp.enabled && sp.learned && sp.ngroups < n).then_some(sp.ngroups)
    }

    /// Grouped differences are on and have not learned a pattern yet.
    pub(crate) fn wants_pattern(&self) -> bool {
        self.sparse.enabled && !self.sparse.learned
    }

    /// The learned pattern of `∂F/∂z` (`n × n` row-major, `true` where nonzero) and its
    /// version (the relearn count), if grouped differences learned one.
    pub(crate) fn pattern(&self) -> Option<(&[bool], usize)> {
        let sp = &self.sparse;
        (sp.enabled && sp.learned).then_some((&sp.pattern[..], sp.relearned))
    }

    /// How often the learned pattern was found incomplete and relearned since
    /// [`FdScratch::learn_sparsity`].
    pub fn relearned(&self) -> usize {
        self.sparse.relearned
    }
}

impl Sparsity {
    /// Adds the nonzeros of `jac` (`n × n`) to the pattern.
    fn add(&mut self, jac: &[f64]) {
        for (p, v) in self.pattern.iter_mut().zip(jac) {
            *p |= *v != 0.0;
        }
    }

    /// Greedy grouping of the columns: column `c` joins the first group none of whose columns
    /// shares a row with it.
    fn group(&mut self, n: usize) {
        self.owner.fill(NONE);
        self.ngroups = 0;
        for c in 0..n {
            let rows = |i: &usize| self.pattern[i * n + c];
            let free = |g: usize| (0..n).filter(rows).all(|i| self.owner[g * n + i] == NONE);
            let g = (0..self.ngroups).find(|&g| free(g)).unwrap_or(self.ngroups);
            if g == self.ngroups {
                self.ngroups += 1;
            }
            for i in 0..n {
                if self.pattern[i * n + c] {
                    self.owner[g * n + i] = c;
                }
            }
            self.col_group[c] = g;
        }
    }
}

/// The deterministic probe perturbation of variable `j` at value `x` (relative `1e-3`, varying
/// in size and sign with `j` so that no combination of variables cancels by symmetry).
fn probe_offset(j: usize, x: f64) -> f64 {
    let u = ((j + 1) as f64 * 0.618_033_988_749_895).fract();
    let sign = if j % 2 == 0 { 1.0 } else { -1.0 };
    sign * (0.5 + u) * 1e-3 * x.abs().max(1.0)
}

/// Where in `[a, b]` the probe evaluates `F`: a generic interior point (golden section), not the
/// abscissa of the first Jacobian, which is usually an end of the interval where a term of `F`
/// may vanish (a singular term `−2 z₁/s` written as `0` at `s = 0`: learned there alone, the
/// pattern missed `∂F₁/∂z₁` and Newton stalled on 707 nodes).
fn probe_abscissa(interval: (f64, f64)) -> f64 {
    let (a, b) = interval;
    a + 0.618_033_988_749_895 * (b - a)
}

/// Adds the nonzeros of a forward-difference `∂F/∂z` at the probe point (`x` perturbed by
/// [`probe_offset`], at [`probe_abscissa`]) to the pattern; a probe with NaN/∞ switches grouping
/// off for this solve (the perturbed point may lie outside `F`'s domain). Returns the evaluations.
fn probe<P: Bvp + ?Sized>(
    problem: &P,
    x: &[f64],
    q: &[f64],
    work: &mut [f64],
    sp: &mut Sparsity,
) -> usize {
    let n = x.len();
    for (j, (xp, &xj)) in sp.x0.iter_mut().zip(x).enumerate() {
        *xp = xj + probe_offset(j, xj);
    }
    let s = probe_abscissa(problem.interval());
    problem.rhs(s, &sp.x0, q, &mut sp.fp);
    let mut evals = 1;
    if sp.fp.iter().all(|v| v.is_finite()) {
        evals += jacobian(
            |xx, out| problem.rhs(s, xx, q, out),
            &mut sp.x0,
            &mut sp.fp,
            FdScheme::Forward,
            &mut sp.probe,
            work,
        );
    }
    if sp.probe[..n * n].iter().all(|v| v.is_finite()) && sp.fp.iter().all(|v| v.is_finite()) {
        let probe = std::mem::take(&mut sp.probe);
        sp.add(&probe[..n * n]);
        sp.probe = probe;
    } else {
        sp.enabled = false;
    }
    evals
}

/// `∂F/∂z` by grouped differences with the learned pattern (`fb` = `F(s, z, p)` for the forward
/// scheme, scratch for central). Returns the evaluations and whether every row outside the
/// pattern stayed unchanged (else an entry was missed and `dfdz` is incomplete). `x` is restored
/// exactly.
#[allow(clippy::too_many_arguments)]
fn grouped<P: Bvp + ?Sized>(
    problem: &P,
    s: f64,
    x: &mut [f64],
    q: &[f64],
    fb: &mut [f64],
    f1: &mut [f64],
    scheme: FdScheme,
    sp: &mut Sparsity,
    dfdz: &mut [f64],
) -> (usize, bool) {
    let n = x.len();
    let mut evals = 0;
    let mut complete = true;
    dfdz[..n * n].fill(0.0);
    let Sparsity {
        col_group,
        owner,
        steps,
        x0,
        ngroups,
        ..
    } = sp;
    x0[..n].copy_from_slice(x);
    for g in 0..*ngroups {
        for c in (0..n).filter(|&c| col_group[c] == g) {
            let h = scheme.step(x0[c]);
            x[c] = x0[c] + h;
            steps[c] = h;
        }
        problem.rhs(s, x, q, f1);
        evals += 1;
        if scheme == FdScheme::Central {
            for c in (0..n).filter(|&c| col_group[c] == g) {
                let hm = x0[c] - (x0[c] - steps[c]);
                x[c] = x0[c] - hm;
                steps[c] += hm;
            }
            problem.rhs(s, x, q, fb);
            evals += 1;
        }
        x.copy_from_slice(&x0[..n]);
        for i in 0..n {
            let c = owner[g * n + i];
            if c == NONE {
                // Bit-for-bit unchanged (NaN compares unequal: also a miss).
                complete &= f1[i] == fb[i];
            } else {
                dfdz[i * n + c] = (f1[i] - fb[i]) / steps[c];
            }
        }
    }
    (evals, complete)
}

/// Generic Jacobian `jac[i * nx + j] = ∂f_i/∂x_j` of `f: R^nx → R^m` (`m = fx.len()`).
///
/// `x` is perturbed in place and restored exactly. For [`FdScheme::Forward`], `fx` must hold
/// `f(x)`; for central it is only used as the length `m` and as scratch for `f(x − h)`. `work`
/// must have length `m`. Returns the number of evaluations of `f`.
pub fn jacobian(
    mut f: impl FnMut(&[f64], &mut [f64]),
    x: &mut [f64],
    fx: &mut [f64],
    scheme: FdScheme,
    jac: &mut [f64],
    work: &mut [f64],
) -> usize {
    let nx = x.len();
    let m = fx.len();
    let mut evals = 0;
    for j in 0..nx {
        let xj = x[j];
        let h = scheme.step(xj);
        x[j] = xj + h;
        f(x, work);
        evals += 1;
        match scheme {
            FdScheme::Forward => {
                x[j] = xj;
                for i in 0..m {
                    jac[i * nx + j] = (work[i] - fx[i]) / h;
                }
            }
            FdScheme::Central => {
                let hm = xj - (xj - h);
                x[j] = xj - hm;
                f(x, fx);
                evals += 1;
                x[j] = xj;
                for i in 0..m {
                    jac[i * nx + j] = (work[i] - fx[i]) / (h + hm);
                }
            }
        }
    }
    evals
}

/// `∂F/∂z` (n×n) and `∂F/∂p` (n×k) at `(s, z, p)` by finite differences. `f0` = `F(s, z, p)` is
/// needed for the forward scheme (pass `None` to have it computed). Returns the number of
/// right-hand-side evaluations.
#[allow(clippy::too_many_arguments)]
pub fn rhs_jacobian_fd<P: Bvp + ?Sized>(
    problem: &P,
    s: f64,
    z: &[f64],
    p: &[f64],
    f0: Option<&[f64]>,
    dfdz: &mut [f64],
    dfdp: &mut [f64],
    scratch: &mut FdScratch,
) -> usize {
    let Dims { n, k } = problem.dims();
    let scheme = scratch.scheme;
    let FdScratch {
        x,
        q,
        f0: fb,
        f1,
        sparse: sp,
        ..
    } = scratch;
    let (x, q, fb, f1) = (&mut x[..n], &mut q[..k], &mut fb[..n], &mut f1[..n]);
    x.copy_from_slice(z);
    q.copy_from_slice(p);
    let mut evals = 0;
    if scheme == FdScheme::Forward {
        match f0 {
            Some(f) => fb.copy_from_slice(&f[..n]),
            None => {
                problem.rhs(s, x, q, fb);
                evals += 1;
            }
        }
    }
    let use_groups = sp.enabled && sp.learned && sp.ngroups < n;
    let mut missed = false;
    if use_groups {
        let (e, complete) = grouped(problem, s, x, q, fb, f1, scheme, sp, dfdz);
        evals += e;
        missed = !complete;
    }
    if !use_groups || missed {
        evals += jacobian(
            |xx, out| problem.rhs(s, xx, q, out),
            x,
            fb,
            scheme,
            dfdz,
            f1,
        );
        if sp.enabled && (!sp.learned || missed) {
            if missed {
                sp.relearned += 1;
            } else {
                evals += probe(problem, x, q, f1, sp);
            }
            sp.add(&dfdz[..n * n]);
            sp.group(n);
            sp.learned = true;
        }
    }
    if k > 0 {
        // Forward: `fb` still holds F(s, z, p); central only used it as scratch.
        evals += jacobian(
            |qq, out| problem.rhs(s, x, qq, out),
            q,
            fb,
            scheme,
            dfdp,
            f1,
        );
    }
    evals
}

/// `∂g/∂z(a)`, `∂g/∂z(b)` ((n+k)×n each) and `∂g/∂p` ((n+k)×k) by finite differences. `g0` =
/// `g(za, zb, p)` is needed for the forward scheme (`None`: computed). Returns the number of
/// boundary-condition evaluations.
#[allow(clippy::too_many_arguments)]
pub fn bc_jacobian_fd<P: Bvp + ?Sized>(
    problem: &P,
    za: &[f64],
    zb: &[f64],
    p: &[f64],
    g0: Option<&[f64]>,
    dga: &mut [f64],
    dgb: &mut [f64],
    dgp: &mut [f64],
    scratch: &mut FdScratch,
) -> usize {
    let Dims { n, k } = problem.dims();
    let m = n + k;
    let scheme = scratch.scheme;
    let FdScratch {
        x,
        y,
        q,
        f0: gb,
        f1,
        ..
    } = scratch;
    let (x, y, q, gb, f1) = (
        &mut x[..n],
        &mut y[..n],
        &mut q[..k],
        &mut gb[..m],
        &mut f1[..m],
    );
    x.copy_from_slice(za);
    y.copy_from_slice(zb);
    q.copy_from_slice(p);
    let mut evals = 0;
    if scheme == FdScheme::Forward {
        match g0 {
            Some(g) => gb.copy_from_slice(&g[..m]),
            None => {
                problem.bc(x, y, q, gb);
                evals += 1;
            }
        }
    }
    evals += jacobian(|xx, out| problem.bc(xx, y, q, out), x, gb, scheme, dga, f1);
    evals += jacobian(|yy, out| problem.bc(x, yy, q, out), y, gb, scheme, dgb, f1);
    if k > 0 {
        evals += jacobian(|qq, out| problem.bc(x, y, qq, out), q, gb, scheme, dgp, f1);
    }
    evals
}

/// No NaN/∞ in `v`. Without early exit, in four lanes (`x · 0` is `±0` for finite `x`, NaN
/// otherwise), so that it vectorizes: the `n²` entries of a Jacobian are checked at every
/// Runge–Kutta stage of multiple shooting.
pub(crate) fn all_finite(v: &[f64]) -> bool {
    let mut acc = [0.0f64; 4];
    let chunks = v.chunks_exact(4);
    let rest = chunks.remainder();
    for c in chunks {
        for (a, x) in acc.iter_mut().zip(c) {
            *a += x * 0.0;
        }
    }
    acc.iter().sum::<f64>() == 0.0 && rest.iter().all(|x| x.is_finite())
}

/// `∂F/∂z`, `∂F/∂p` at `(s, z, p)`: analytic if [`Bvp::rhs_jacobian`] returns true, else finite
/// differences with `scratch.scheme` (`f0` = `F(s, z, p)` if known, saves one evaluation for the
/// forward scheme). Counts `jac_evals` (+1) and the right-hand-side evaluations in `stats`; returns
/// [`BvpError::NonFinite`] (location `"jacobian"`, abscissa `s`) if an entry is NaN/∞.
#[allow(clippy::too_many_arguments)]
pub fn rhs_jacobian_or_fd<P: Bvp + ?Sized>(
    problem: &P,
    s: f64,
    z: &[f64],
    p: &[f64],
    f0: Option<&[f64]>,
    dfdz: &mut [f64],
    dfdp: &mut [f64],
    scratch: &mut FdScratch,
    stats: &mut Stats,
) -> Result<(), BvpError> {
    stats.jac_evals += 1;
    if !problem.rhs_jacobian(s, z, p, dfdz, dfdp) {
        stats.rhs_evals += rhs_jacobian_fd(problem, s, z, p, f0, dfdz, dfdp, scratch);
    }
    let Dims { n, k } = problem.dims();
    if all_finite(&dfdz[..n * n]) && all_finite(&dfdp[..n * k]) {
        Ok(())
    } else {
        Err(crate::newton::non_finite("jacobian", s))
    }
}

/// Jacobians of the boundary conditions: analytic if [`Bvp::bc_jacobian`] returns true, else
/// finite differences. Counts `bc_evals` in `stats`; [`BvpError::NonFinite`] (location
/// `"jacobian"`, `s` = NaN) on NaN/∞.
#[allow(clippy::too_many_arguments)]
pub fn bc_jacobian_or_fd<P: Bvp + ?Sized>(
    problem: &P,
    za: &[f64],
    zb: &[f64],
    p: &[f64],
    g0: Option<&[f64]>,
    dga: &mut [f64],
    dgb: &mut [f64],
    dgp: &mut [f64],
    scratch: &mut FdScratch,
    stats: &mut Stats,
) -> Result<(), BvpError> {
    if !problem.bc_jacobian(za, zb, p, dga, dgb, dgp) {
        stats.bc_evals += bc_jacobian_fd(problem, za, zb, p, g0, dga, dgb, dgp, scratch);
    }
    let Dims { n, k } = problem.dims();
    let m = n + k;
    if all_finite(&dga[..m * n]) && all_finite(&dgb[..m * n]) && all_finite(&dgp[..m * k]) {
        Ok(())
    } else {
        Err(crate::newton::non_finite("jacobian", f64::NAN))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `∂F/∂z` of `problem` at `z` with `scratch`; returns it and the evaluations.
    fn dfdz(problem: &impl Bvp, s: f64, z: &[f64], scratch: &mut FdScratch) -> (Vec<f64>, usize) {
        let Dims { n, k } = problem.dims();
        let p = vec![1.0; k];
        let (mut jz, mut jp) = (vec![0.0; n * n], vec![0.0; n * k]);
        let e = rhs_jacobian_fd(problem, s, z, &p, None, &mut jz, &mut jp, scratch);
        (jz, e)
    }

    #[test]
    fn grouped_differences_match_column_by_column() {
        // scipy's big problem, 20 states (10 uncoupled pairs): one group of columns.
        let big = crate::samples::Big {
            pairs: 10,
            params: true,
        };
        let n = 20;
        let z: Vec<f64> = (0..n).map(|i| 0.3 + 0.1 * i as f64).collect();
        for scheme in [FdScheme::Forward, FdScheme::Central] {
            let dims = big.dims();
            let mut plain = FdScratch::with_scheme(dims, scheme);
            let mut sparse = FdScratch::with_scheme(dims, scheme);
            sparse.learn_sparsity(true);
            let (want, e_plain) = dfdz(&big, 0.5, &z, &mut plain);
            let per_col = if scheme == FdScheme::Forward { 1 } else { 2 };
            // Forward: F(z) once, then one evaluation per column of z and of p; central two.
            let own_f = usize::from(scheme == FdScheme::Forward);
            assert_eq!(e_plain, own_f + per_col * (n + 2));
            // First call: column by column plus the probe (n + 1 forward evaluations).
            let (first, e_first) = dfdz(&big, 0.5, &z, &mut sparse);
            assert_eq!(first, want);
            assert_eq!(e_first, e_plain + n + 1);
            assert_eq!(sparse.groups(), Some(1));
            // Later calls: one group, the same numbers bit for bit.
            let z2: Vec<f64> = z.iter().map(|v| v * 1.7 - 0.2).collect();
            let (want2, _) = dfdz(&big, 0.9, &z2, &mut plain);
            let (got2, e2) = dfdz(&big, 0.9, &z2, &mut sparse);
            assert_eq!(got2, want2, "{scheme:?}");
            assert_eq!(e2, own_f + per_col * (1 + 2), "{scheme:?}");
            assert_eq!(sparse.relearned(), 0);
        }
    }

    /// `F = (max(z_1, 0), z_0)`: `∂F_0/∂z_1` vanishes where it is learned (`z_1 < 0`).
    struct Kink;
    impl Bvp for Kink {
        fn dims(&self) -> Dims {
            Dims { n: 2, k: 0 }
        }
        fn interval(&self) -> (f64, f64) {
            (0.0, 1.0)
        }
        fn rhs(&self, _s: f64, z: &[f64], _p: &[f64], dz: &mut [f64]) {
            dz[0] = z[1].max(0.0);
            dz[1] = z[0];
        }
        fn bc(&self, za: &[f64], zb: &[f64], _p: &[f64], res: &mut [f64]) {
            res[0] = za[0];
            res[1] = zb[0];
        }
    }

    #[test]
    fn a_missed_entry_is_seen_and_relearned() {
        let mut sp = FdScratch::with_scheme(Kink.dims(), FdScheme::Forward);
        sp.learn_sparsity(true);
        let (j, _) = dfdz(&Kink, 0.0, &[1.0, -1.0], &mut sp);
        assert_eq!(j, [0.0, 0.0, 1.0, 0.0]);
        assert_eq!(sp.groups(), Some(1), "both columns in one group");
        // Where z_1 > 0 the group's evaluation changes row 0, which no column of the learned
        // pattern touches: recomputed column by column and relearned.
        let (j, _) = dfdz(&Kink, 0.0, &[1.0, 2.0], &mut sp);
        assert_eq!(sp.relearned(), 1);
        assert_eq!(j, [0.0, 1.0, 1.0, 0.0]);
        let (j, e) = dfdz(&Kink, 0.0, &[1.0, 3.0], &mut sp);
        assert_eq!(
            (j.as_slice(), e, sp.relearned()),
            ([0.0, 1.0, 1.0, 0.0].as_slice(), 2, 1)
        );
    }

    #[test]
    fn all_finite_sees_every_position() {
        for len in 0..11 {
            let mut v: Vec<f64> = (0..len).map(|i| i as f64 - 3.0).collect();
            assert!(all_finite(&v));
            for i in 0..len {
                for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
                    let keep = std::mem::replace(&mut v[i], bad);
                    assert!(!all_finite(&v), "{len} {i} {bad}");
                    v[i] = keep;
                }
            }
        }
    }

    #[test]
    fn step_constants_are_the_roots_of_epsilon() {
        assert_eq!(SQRT_EPS, f64::EPSILON.sqrt());
        assert_eq!(CBRT_EPS, f64::EPSILON.cbrt());
    }

    #[test]
    fn generic_jacobian_accuracy() {
        let f = |x: &[f64], out: &mut [f64]| {
            out[0] = x[0].sin() * x[1];
            out[1] = (x[0] * x[1]).exp();
        };
        let exact = |x: &[f64]| {
            [
                x[0].cos() * x[1],
                x[0].sin(),
                x[1] * (x[0] * x[1]).exp(),
                x[0] * (x[0] * x[1]).exp(),
            ]
        };
        for (scheme, tol) in [(FdScheme::Forward, 1e-6), (FdScheme::Central, 1e-9)] {
            let mut x = [0.7, -1.3];
            let mut fx = [0.0; 2];
            f(&x, &mut fx);
            let mut jac = [0.0; 4];
            let mut work = [0.0; 2];
            jacobian(f, &mut x, &mut fx, scheme, &mut jac, &mut work);
            assert_eq!(x, [0.7, -1.3]);
            let e = exact(&x);
            for i in 0..4 {
                assert!((jac[i] - e[i]).abs() < tol, "{scheme:?} {jac:?} {e:?}");
            }
        }
    }
}
