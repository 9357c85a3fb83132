//! Explicit Runge–Kutta integration of `z' = F(s, z, p)` together with its variational equations.
//!
//! The augmented state is `Y = (z, W)` with `W = [Φ | Ψ]` (row-major `n × (n + k)`),
//!
//! ```text
//!     z' = F(s, z, p),    W' = F_z W + [0 | F_p],    z(t0) = z0,  W(t0) = [I | 0],
//! ```
//!
//! so that at the end `Φ = ∂z(t1)/∂z0` and `Ψ = ∂z(t1)/∂p`. Integrating the augmented system with
//! the *same* Runge–Kutta stages makes `W` the exact derivative of the discrete map `z0 ↦ z1` for a
//! fixed step sequence (RK methods commute with linearization). For fixed-step RK4 that is the
//! exact Jacobian of the shooting residual, hence quadratic Newton convergence. For the adaptive
//! pair the step sequence itself depends (piecewise constantly, through the controller) on `z0`
//! and `p`; `W` ignores that dependence ("internal numerical differentiation", Bock 1981), which is
//! of the order of the local tolerance and only slows Newton near convergence in the last digits.
//!
//! Tableaus: classical RK4, and Dormand & Prince's DOP853 (order 8 with 5th- and 3rd-order
//! embedded error estimates, 12 stages; Hairer, Nørsett & Wanner, *Solving ODEs I*, §II.10). The
//! error norm and I step-size controller follow Hairer's DOP853 (error exponent 1/8, safety 0.9,
//! step ratio in `[1/3, 6]`, no growth right after a rejection); only `z` (not `W`) enters the
//! error norm.

// The coefficient tables keep their published digits.
#![allow(clippy::excessive_precision)]

use crate::fd::{rhs_jacobian_or_fd, FdScratch};
use crate::newton::non_finite;
use crate::{Bvp, BvpError, Dims, Stats};

/// A Butcher tableau with an optional DOP853-style error estimator.
pub(crate) struct Tableau {
    stages: usize,
    c: &'static [f64],
    /// Row-major `stages × stages`, strictly lower triangular.
    a: &'static [f64],
    b: &'static [f64],
    /// 5th-order error weights (DOP853 `er`), empty for fixed-step tableaus.
    e5: &'static [f64],
    /// 3rd-order error weights (`b − b̂₃`).
    e3: &'static [f64],
}

const RK4_A: [f64; 16] = [
    0.0, 0.0, 0.0, 0.0, //
    0.5, 0.0, 0.0, 0.0, //
    0.0, 0.5, 0.0, 0.0, //
    0.0, 0.0, 1.0, 0.0,
];

pub(crate) static RK4: Tableau = Tableau {
    stages: 4,
    c: &[0.0, 0.5, 0.5, 1.0],
    a: &RK4_A,
    b: &[1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0],
    e5: &[],
    e3: &[],
};

use crate::tableau::dop853 as d8;

pub(crate) static DOP853: Tableau = Tableau {
    stages: 12,
    c: &d8::C,
    a: &d8::A,
    b: &d8::B,
    e5: &d8::E5,
    e3: &d8::E3,
};

/// How to integrate one segment.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Mode {
    /// RK4 with this many equal steps.
    Fixed { steps: usize },
    /// DOP853 with error control.
    Adaptive {
        rtol: f64,
        atol: f64,
        max_steps: usize,
    },
}

/// Where accepted step nodes are appended (values and derivatives of `z`, node-major).
pub(crate) struct Recorder<'a> {
    pub mesh: &'a mut Vec<f64>,
    pub z: &'a mut Vec<f64>,
    pub dz: &'a mut Vec<f64>,
    /// DOP853 only: if given, each accepted step is appended here instead, as
    /// `[s, z (n), dz (n), r1 … r7 (7n)]` ([`DENSE_RECORD`] values per state), with `r1 … r7` the
    /// coefficients of the 7th-order continuous extension ([`crate::tableau::dop853::D_DENSE`]).
    pub dense: Option<&'a mut Vec<f64>>,
}

/// Values per state (plus one for `s`) of a dense record: `z`, `dz`, `r1 … r7`.
pub(crate) const DENSE_RECORD: usize = 9;

/// Work buffers of the integrator (sized once per problem, reused across integrations).
#[derive(Clone, Debug, Default)]
pub(crate) struct RkWork {
    n: usize,
    k: usize,
    y: Vec<f64>,
    ytmp: Vec<f64>,
    ynew: Vec<f64>,
    stages: Vec<f64>,
    dfdz: Vec<f64>,
    dfdp: Vec<f64>,
    /// `f(t + h, y_new)` and the three extra stages of the continuous extension (`4n`).
    kx: Vec<f64>,
    /// Column indices of one row's nonzeros of `∂F/∂z` (`n`).
    cols: Vec<usize>,
    fd: FdScratch,
    reach: Reach,
}

/// Compressed storage of `Φ` by the learned pattern of `∂F/∂z` (see [`RkWork::integrate`]):
/// row `i` keeps the columns `i` reaches in the pattern's graph (`i → l` where `∂F_i/∂z_l ≠ 0`),
/// reflexive and transitive, the only entries `Φ' = F_z Φ`, `Φ(t0) = I` can make nonzero.
#[derive(Clone, Debug, Default)]
struct Reach {
    /// The relearn count of the pattern it was built from; `None`: not built this solve.
    built: Option<usize>,
    /// Compression in use (the closure holds fewer than half the `n²` entries).
    on: bool,
    /// CSR of the closure: row `i` is `col[ptr[i]..ptr[i + 1]]`, increasing.
    ptr: Vec<usize>,
    col: Vec<usize>,
    /// CSR of the pattern itself (the columns `l` of row `i` with `∂F_i/∂z_l` possibly nonzero).
    pptr: Vec<usize>,
    pcol: Vec<usize>,
    /// Scatter row (`n`), depth-first stack and marks (`n` each).
    acc: Vec<f64>,
    stack: Vec<usize>,
    seen: Vec<bool>,
    /// The last integration's `W` expanded to `n × (n + k)`, when it was compressed.
    dense: Vec<f64>,
    last_compressed: bool,
}

impl Reach {
    /// Builds the closure of `pattern` (`n × n`); compression on if it saves half the entries.
    fn build(&mut self, pattern: &[bool], n: usize, version: usize) {
        self.built = Some(version);
        self.pptr.clear();
        self.pcol.clear();
        self.pptr.push(0);
        for i in 0..n {
            self.pcol.extend((0..n).filter(|&l| pattern[i * n + l]));
            self.pptr.push(self.pcol.len());
        }
        self.ptr.clear();
        self.col.clear();
        self.ptr.push(0);
        for i in 0..n {
            self.seen.fill(false);
            self.seen[i] = true;
            self.stack.clear();
            self.stack.push(i);
            while let Some(u) = self.stack.pop() {
                for l in 0..n {
                    if pattern[u * n + l] && !self.seen[l] {
                        self.seen[l] = true;
                        self.stack.push(l);
                    }
                }
            }
            self.col.extend((0..n).filter(|&c| self.seen[c]));
            self.ptr.push(self.col.len());
        }
        self.on = 2 * self.col.len() < n * n;
    }
}

/// Evaluates the augmented right-hand side `(F, F_z W + [0 | F_p])` at `(s, y)`.
#[allow(clippy::too_many_arguments)]
fn aug_rhs<P: Bvp + ?Sized>(
    problem: &P,
    s: f64,
    y: &[f64],
    p: &[f64],
    out: &mut [f64],
    var: bool,
    n: usize,
    k: usize,
    dfdz: &mut [f64],
    dfdp: &mut [f64],
    cols: &mut [usize],
    fd: &mut FdScratch,
    reach: Option<&mut Reach>,
    stats: &mut Stats,
) -> Result<(), BvpError> {
    let (z, w) = y.split_at(n);
    let (dz, dw) = out.split_at_mut(n);
    problem.rhs(s, z, p, dz);
    stats.rhs_evals += 1;
    if !dz.iter().all(|v| v.is_finite()) {
        return Err(non_finite("rhs", s));
    }
    if var {
        rhs_jacobian_or_fd(problem, s, z, p, Some(dz), dfdz, dfdp, fd, stats)?;
        if let Some(r) = reach {
            compressed_variational(n, k, dfdz, dfdp, r, w, dw);
            return Ok(());
        }
        let m = n + k;
        for i in 0..n {
            let row = &mut dw[i * m..(i + 1) * m];
            row.fill(0.0);
            // One pass over W per nonzero of row i.
            let nnz = row_nonzeros(&dfdz[i * n..(i + 1) * n], cols);
            for &l in &cols[..nnz] {
                let a = dfdz[i * n + l];
                let wl = &w[l * m..(l + 1) * m];
                for (r, &x) in row.iter_mut().zip(wl) {
                    *r += a * x;
                }
            }
            for j in 0..k {
                row[n + j] += dfdp[i * k + j];
            }
        }
    }
    Ok(())
}

/// The nonzeros of row `i` of `dfdz` into `cols` (without a branch per entry: a test per entry
/// mispredicted often enough to dominate sparse Jacobians); returns their number.
fn row_nonzeros(row: &[f64], cols: &mut [usize]) -> usize {
    let mut nnz = 0;
    for (l, &a) in row.iter().enumerate() {
        cols[nnz] = l;
        nnz += usize::from(a != 0.0);
    }
    nnz
}

/// `(F_z Φ, F_z Ψ + F_p)` with `Φ` compressed by the closure `r.ptr, r.col` (`w = [Φ_c | Ψ]`,
/// `Ψ` row-major `n × k`), over the pattern's entries of `F_z`: the same sums in the same order
/// as the dense product, over the entries the closure keeps (`Φ_l`'s columns are among `Φ_i`'s
/// when `∂F_i/∂z_l ≠ 0`).
fn compressed_variational(
    n: usize,
    k: usize,
    dfdz: &[f64],
    dfdp: &[f64],
    r: &mut Reach,
    w: &[f64],
    dw: &mut [f64],
) {
    let Reach {
        ptr,
        col,
        pptr,
        pcol,
        acc,
        ..
    } = r;
    let nnz_w = ptr[n];
    let (phi, psi) = w.split_at(nnz_w);
    let (dphi, dpsi) = dw.split_at_mut(nnz_w);
    for i in 0..n {
        let own = ptr[i]..ptr[i + 1];
        for &c in &col[own.clone()] {
            acc[c] = 0.0;
        }
        let prow = &mut dpsi[i * k..(i + 1) * k];
        prow.fill(0.0);
        for &l in &pcol[pptr[i]..pptr[i + 1]] {
            let a = dfdz[i * n + l];
            for t in ptr[l]..ptr[l + 1] {
                acc[col[t]] += a * phi[t];
            }
            for (r, &x) in prow.iter_mut().zip(&psi[l * k..(l + 1) * k]) {
                *r += a * x;
            }
        }
        for t in own {
            dphi[t] = acc[col[t]];
        }
        for (r, &g) in prow.iter_mut().zip(&dfdp[i * k..(i + 1) * k]) {
            *r += g;
        }
    }
}

impl RkWork {
    /// Sizes the buffers for `dims` (variational part included).
    pub fn resize(&mut self, dims: Dims) {
        let (n, k) = (dims.n, dims.k);
        self.n = n;
        self.k = k;
        let dim = n * (1 + n + k);
        for (v, len) in [
            (&mut self.y, dim),
            (&mut self.ytmp, dim),
            (&mut self.ynew, dim),
            (&mut self.stages, 12 * dim),
            (&mut self.dfdz, n * n),
            (&mut self.dfdp, n * k),
            (&mut self.kx, 4 * n),
        ] {
            v.clear();
            v.resize(len, 0.0);
        }
        self.cols.clear();
        self.cols.resize(n, 0);
        self.fd.resize(dims);
        let r = &mut self.reach;
        r.built = None;
        r.on = false;
        r.last_compressed = false;
        r.ptr.reserve(n + 1);
        r.col.reserve(n * n);
        r.pptr.reserve(n + 1);
        r.pcol.reserve(n * n);
        r.stack.reserve(n);
        r.seen.clear();
        r.seen.resize(n, false);
        r.acc.clear();
        r.acc.resize(n, 0.0);
        r.dense.clear();
        r.dense.resize(n * (n + k), 0.0);
    }

    /// Grouped finite differences of `∂F/∂z` for the variational equations
    /// ([`FdScratch::learn_sparsity`]; call at the start of each solve).
    pub fn learn_sparsity(&mut self, on: bool) {
        self.fd.learn_sparsity(on);
        self.reach.built = None;
        self.reach.on = false;
    }

    /// The final `z` of the last integration.
    pub fn z(&self) -> &[f64] {
        &self.y[..self.n]
    }

    /// The final `W = [Φ | Ψ]` (row-major `n × (n + k)`) of the last integration with `var`.
    pub fn w(&self) -> &[f64] {
        if self.reach.last_compressed {
            &self.reach.dense
        } else {
            &self.y[self.n..self.n * (1 + self.n + self.k)]
        }
    }

    /// Integrates from `(t0, z0)` to `t1 > t0`. With `var`, also the variational equations from
    /// `W = [I | 0]`. Accepted step starts are appended to `rec` (the end point is not).
    ///
    /// When `∂F/∂z` is differenced with a learned pattern ([`FdScratch::learn_sparsity`]) whose
    /// closure holds fewer than half of `Φ`'s entries, `Φ` is integrated compressed to that
    /// closure: the same numbers (the other entries stay exactly zero) at `O(closure)` instead
    /// of `O(n²)` per stage. If the pattern is relearned during the integration (it missed an
    /// entry), the integration is repeated with dense `Φ`.
    #[allow(clippy::too_many_arguments)]
    pub fn integrate<P: Bvp + ?Sized>(
        &mut self,
        problem: &P,
        p: &[f64],
        t0: f64,
        t1: f64,
        z0: &[f64],
        var: bool,
        mode: Mode,
        rec: Option<&mut Recorder<'_>>,
        stats: &mut Stats,
    ) -> Result<(), BvpError> {
        let n = self.n;
        if var && rec.is_none() {
            if self.fd.wants_pattern() {
                // Learn the pattern before the first integration rather than at its first stage,
                // so that it is compressed too (analytic Jacobians: nothing to learn).
                let RkWork { dfdz, dfdp, fd, .. } = self;
                if problem.rhs_jacobian(t0, z0, p, dfdz, dfdp) {
                    fd.learn_sparsity(false);
                } else {
                    stats.rhs_evals +=
                        crate::fd::rhs_jacobian_fd(problem, t0, z0, p, None, dfdz, dfdp, fd);
                }
            }
            if let Some((pattern, version)) = self.fd.pattern() {
                if self.reach.built != Some(version) {
                    self.reach.build(pattern, n, version);
                }
                if self.reach.on {
                    self.integrate_with(problem, p, t0, t1, z0, var, mode, None, true, stats)?;
                    if self.fd.pattern().map(|x| x.1) == Some(version) {
                        self.expand();
                        return Ok(());
                    }
                }
            }
        }
        self.integrate_with(problem, p, t0, t1, z0, var, mode, rec, false, stats)
    }

    /// `W` of a compressed integration into `reach.dense`.
    fn expand(&mut self) {
        let (n, k) = (self.n, self.k);
        let m = n + k;
        let r = &mut self.reach;
        let nnz = r.ptr[n];
        let (phi, psi) = self.y[n..n + nnz + n * k].split_at(nnz);
        r.dense.fill(0.0);
        for i in 0..n {
            let own = r.ptr[i]..r.ptr[i + 1];
            for (&c, &v) in r.col[own.clone()].iter().zip(&phi[own]) {
                r.dense[i * m + c] = v;
            }
            r.dense[i * m + n..(i + 1) * m].copy_from_slice(&psi[i * k..(i + 1) * k]);
        }
        r.last_compressed = true;
    }

    /// [`RkWork::integrate`] with `Φ` compressed by `reach` (`compress`) or dense.
    #[allow(clippy::too_many_arguments)]
    fn integrate_with<P: Bvp + ?Sized>(
        &mut self,
        problem: &P,
        p: &[f64],
        t0: f64,
        t1: f64,
        z0: &[f64],
        var: bool,
        mode: Mode,
        mut rec: Option<&mut Recorder<'_>>,
        compress: bool,
        stats: &mut Stats,
    ) -> Result<(), BvpError> {
        let (n, k) = (self.n, self.k);
        let m = n + k;
        let dim = match (var, compress) {
            (false, _) => n,
            (true, false) => n * (1 + m),
            (true, true) => n + self.reach.ptr[n] + n * k,
        };
        self.reach.last_compressed = false;
        let RkWork {
            y,
            ytmp,
            ynew,
            stages,
            dfdz,
            dfdp,
            kx,
            cols,
            fd,
            reach,
            ..
        } = self;
        let (y, ytmp, ynew) = (&mut y[..dim], &mut ytmp[..dim], &mut ynew[..dim]);
        y[..n].copy_from_slice(z0);
        if var {
            let w = &mut y[n..];
            w.fill(0.0);
            for i in 0..n {
                if compress {
                    let t = reach.ptr[i]
                        + reach.col[reach.ptr[i]..reach.ptr[i + 1]].partition_point(|&c| c < i);
                    w[t] = 1.0;
                } else {
                    w[i * m + i] = 1.0;
                }
            }
        }
        let mut f = |s: f64, yy: &[f64], out: &mut [f64], stats: &mut Stats| {
            let r = compress.then_some(&mut *reach);
            aug_rhs(
                problem, s, yy, p, out, var, n, k, dfdz, dfdp, cols, fd, r, stats,
            )
        };

        // k1 = f(t0, y0); after each accepted step it is re-evaluated at the new point.
        f(t0, y, &mut stages[..dim], stats)?;

        match mode {
            Mode::Fixed { steps } => {
                let tab = &RK4;
                let span = t1 - t0;
                for i in 0..steps {
                    let s = t0 + span * i as f64 / steps as f64;
                    let s_next = if i + 1 == steps {
                        t1
                    } else {
                        t0 + span * (i + 1) as f64 / steps as f64
                    };
                    let h = s_next - s;
                    rk_step(tab, s, h, y, ytmp, ynew, stages, dim, &mut f, stats)?;
                    stats.steps += 1;
                    if let Some(r) = rec.as_deref_mut() {
                        record(r, s, &y[..n], &stages[..n]);
                    }
                    y.copy_from_slice(ynew);
                    f(s_next, y, &mut stages[..dim], stats)?;
                }
            }
            Mode::Adaptive {
                rtol,
                atol,
                max_steps,
            } => {
                let tab = &DOP853;
                let mut h = initial_step(
                    problem,
                    p,
                    t0,
                    t1,
                    &y[..n],
                    &stages[..n],
                    rtol,
                    atol,
                    ytmp,
                    ynew,
                    stats,
                )?;
                let mut s = t0;
                let mut taken = 0usize;
                let mut rejected_last = false;
                while s < t1 {
                    if taken >= max_steps {
                        return Err(BvpError::StepSizeTooSmall {
                            s,
                            h,
                            stats: Stats::default(),
                        });
                    }
                    // Hit t1 exactly; avoid a sliver of a last step.
                    let last = s + 1.01 * h >= t1;
                    if last {
                        h = t1 - s;
                    }
                    rk_step(tab, s, h, y, ytmp, ynew, stages, dim, &mut f, stats)?;
                    taken += 1;
                    stats.steps += 1;
                    let err = error_norm(tab, h, &y[..n], &ynew[..n], stages, dim, n, rtol, atol);
                    if err <= 1.0 {
                        let s_new = if last { t1 } else { s + h };
                        let dense = rec.as_deref_mut().and_then(|r| r.dense.as_deref_mut());
                        if let (Some(out), false) = (dense, var) {
                            // Continuous extension: f(s_new, y_new) (also the next k1) and three
                            // extra stages, then the coefficients r1 … r7.
                            f(s_new, ynew, &mut kx[..n], stats)?;
                            dense_record(
                                tab, s, h, y, ynew, stages, kx, ytmp, n, &mut f, stats, out,
                            )?;
                            y.copy_from_slice(ynew);
                            stages[..n].copy_from_slice(&kx[..n]);
                        } else {
                            if let Some(r) = rec.as_deref_mut() {
                                record(r, s, &y[..n], &stages[..n]);
                            }
                            y.copy_from_slice(ynew);
                            f(s_new, y, &mut stages[..dim], stats)?;
                        }
                        let mut fac = if err == 0.0 {
                            6.0
                        } else {
                            (0.9 * err.powf(-1.0 / 8.0)).clamp(1.0 / 3.0, 6.0)
                        };
                        if rejected_last {
                            fac = fac.min(1.0);
                        }
                        rejected_last = false;
                        s = s_new;
                        h *= fac;
                    } else {
                        stats.rejected_steps += 1;
                        rejected_last = true;
                        let fac = if err.is_finite() {
                            (0.9 * err.powf(-1.0 / 8.0)).max(1.0 / 3.0)
                        } else {
                            0.1
                        };
                        h *= fac;
                        if h <= 16.0 * f64::EPSILON * s.abs().max(t1.abs()).max(1.0) {
                            return Err(BvpError::StepSizeTooSmall {
                                s,
                                h,
                                stats: Stats::default(),
                            });
                        }
                    }
                }
            }
        }
        Ok(())
    }
}

/// Computes the extra stages and appends `[s, z, dz, r1 … r7]` of one accepted DOP853 step
/// (`kx[..n]` holds `f(s + h, y_new)`; `stages` the twelve stages of the step, `dim = n`).
#[allow(clippy::too_many_arguments)]
fn dense_record<F>(
    tab: &Tableau,
    s: f64,
    h: f64,
    y: &[f64],
    ynew: &[f64],
    stages: &[f64],
    kx: &mut [f64],
    ytmp: &mut [f64],
    n: usize,
    f: &mut F,
    stats: &mut Stats,
    out: &mut Vec<f64>,
) -> Result<(), BvpError>
where
    F: FnMut(f64, &[f64], &mut [f64], &mut Stats) -> Result<(), BvpError>,
{
    use crate::tableau::dop853::{A_DENSE, C_DENSE, D_DENSE};
    let ns = tab.stages;
    // Stage j of the extended set: 0..12 the step's, 12 = f_new, 13.. the extra ones.
    let stage = |j: usize, kx: &[f64], i: usize| -> f64 {
        if j < ns {
            stages[j * n + i]
        } else {
            kx[(j - ns) * n + i]
        }
    };
    for r in 0..3 {
        for i in 0..n {
            let mut acc = 0.0;
            for (j, &a) in A_DENSE[r].iter().enumerate().take(ns + 1 + r) {
                if a != 0.0 {
                    acc += a * stage(j, kx, i);
                }
            }
            ytmp[i] = y[i] + h * acc;
        }
        let tail = &mut kx[(r + 1) * n..];
        f(s + C_DENSE[r] * h, &ytmp[..n], &mut tail[..n], stats)?;
    }
    out.push(s);
    out.extend_from_slice(&y[..n]);
    out.extend_from_slice(&stages[..n]);
    out.extend((0..n).map(|i| ynew[i] - y[i]));
    out.extend((0..n).map(|i| h * stages[i] - (ynew[i] - y[i])));
    out.extend((0..n).map(|i| 2.0 * (ynew[i] - y[i]) - h * (stages[i] + kx[i])));
    for d in &D_DENSE {
        for i in 0..n {
            let mut acc = 0.0;
            for (j, &w) in d.iter().enumerate() {
                if w != 0.0 {
                    acc += w * stage(j, kx, i);
                }
            }
            out.push(h * acc);
        }
    }
    Ok(())
}

fn record(r: &mut Recorder<'_>, s: f64, z: &[f64], dz: &[f64]) {
    r.mesh.push(s);
    r.z.extend_from_slice(z);
    r.dz.extend_from_slice(dz);
}

/// One explicit RK step from `(s, y)` with `k1` already in `stages[..dim]`; writes `ynew`.
#[allow(clippy::too_many_arguments)]
fn rk_step<F>(
    tab: &Tableau,
    s: f64,
    h: f64,
    y: &[f64],
    ytmp: &mut [f64],
    ynew: &mut [f64],
    stages: &mut [f64],
    dim: usize,
    f: &mut F,
    stats: &mut Stats,
) -> Result<(), BvpError>
where
    F: FnMut(f64, &[f64], &mut [f64], &mut Stats) -> Result<(), BvpError>,
{
    let ns = tab.stages;
    for i in 1..ns {
        ytmp.copy_from_slice(y);
        for j in 0..i {
            let a = tab.a[i * ns + j];
            if a != 0.0 {
                let ha = h * a;
                let kj = &stages[j * dim..(j + 1) * dim];
                for (t, &x) in ytmp.iter_mut().zip(kj) {
                    *t += ha * x;
                }
            }
        }
        f(
            s + tab.c[i] * h,
            ytmp,
            &mut stages[i * dim..(i + 1) * dim],
            stats,
        )?;
    }
    ynew.copy_from_slice(y);
    for j in 0..ns {
        let b = tab.b[j];
        if b != 0.0 {
            let hb = h * b;
            let kj = &stages[j * dim..(j + 1) * dim];
            for (t, &x) in ynew.iter_mut().zip(kj) {
                *t += hb * x;
            }
        }
    }
    Ok(())
}

/// DOP853 error norm (≤ 1: accept) over the `n` state components.
#[allow(clippy::too_many_arguments)]
fn error_norm(
    tab: &Tableau,
    h: f64,
    y: &[f64],
    ynew: &[f64],
    stages: &[f64],
    dim: usize,
    n: usize,
    rtol: f64,
    atol: f64,
) -> f64 {
    let (mut e5, mut e3) = (0.0, 0.0);
    for i in 0..n {
        let sk = atol + rtol * y[i].abs().max(ynew[i].abs());
        let (mut a5, mut a3) = (0.0, 0.0);
        for j in 0..tab.stages {
            let kij = stages[j * dim + i];
            a5 += tab.e5[j] * kij;
            a3 += tab.e3[j] * kij;
        }
        e5 += (a5 / sk).powi(2);
        e3 += (a3 / sk).powi(2);
    }
    let mut deno = e5 + 0.01 * e3;
    if deno <= 0.0 {
        deno = 1.0;
    }
    let err = h.abs() * e5 / (n as f64 * deno).sqrt();
    if err.is_nan() {
        f64::INFINITY
    } else {
        err
    }
}

/// Hairer's starting step for an order-8 method (one extra evaluation of `F`).
#[allow(clippy::too_many_arguments)]
fn initial_step<P: Bvp + ?Sized>(
    problem: &P,
    p: &[f64],
    t0: f64,
    t1: f64,
    z0: &[f64],
    f0: &[f64],
    rtol: f64,
    atol: f64,
    zt: &mut [f64],
    ft: &mut [f64],
    stats: &mut Stats,
) -> Result<f64, BvpError> {
    let n = z0.len();
    let span = t1 - t0;
    let (mut dnf, mut dny) = (0.0, 0.0);
    for i in 0..n {
        let sk = atol + rtol * z0[i].abs();
        dnf += (f0[i] / sk).powi(2);
        dny += (z0[i] / sk).powi(2);
    }
    let mut h = if dnf <= 1e-10 || dny <= 1e-10 {
        1e-6
    } else {
        0.01 * (dny / dnf).sqrt()
    };
    h = h.min(span);
    let (zt, ft) = (&mut zt[..n], &mut ft[..n]);
    for i in 0..n {
        zt[i] = z0[i] + h * f0[i];
    }
    problem.rhs(t0 + h, zt, p, ft);
    stats.rhs_evals += 1;
    if !ft.iter().all(|v| v.is_finite()) {
        return Err(non_finite("rhs", t0 + h));
    }
    let mut der2 = 0.0;
    for i in 0..n {
        let sk = atol + rtol * z0[i].abs();
        der2 += ((ft[i] - f0[i]) / sk).powi(2);
    }
    let der2 = der2.sqrt() / h;
    let der12 = der2.max(dnf.sqrt());
    let h1 = if der12 <= 1e-15 {
        (h * 1e-3).max(1e-6)
    } else {
        (0.01 / der12).powf(1.0 / 8.0)
    };
    Ok((100.0 * h).min(h1).min(span))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check_order_conditions(tab: &Tableau, order: usize) {
        let s = tab.stages;
        // Row sums equal c.
        for i in 0..s {
            let r: f64 = (0..s).map(|j| tab.a[i * s + j]).sum();
            assert!((r - tab.c[i]).abs() < 1e-14, "row {i}");
        }
        // Bushy-tree conditions Σ b c^q = 1/(q+1) up to the order.
        for q in 0..order {
            let v: f64 = (0..s).map(|i| tab.b[i] * tab.c[i].powi(q as i32)).sum();
            assert!((v - 1.0 / (q + 1) as f64).abs() < 1e-13, "q = {q}: {v}");
        }
        // Σ b_i a_ij c_j = 1/6.
        let v: f64 = (0..s)
            .map(|i| tab.b[i] * (0..s).map(|j| tab.a[i * s + j] * tab.c[j]).sum::<f64>())
            .sum();
        assert!((v - 1.0 / 6.0).abs() < 1e-13);
        // Error weights of a consistent estimator sum to 0.
        if !tab.e5.is_empty() {
            assert!(tab.e5.iter().sum::<f64>().abs() < 1e-13);
            assert!(tab.e3.iter().sum::<f64>().abs() < 1e-13);
        }
    }

    /// `W` of one DOP853 integration of `problem` from `z0` with grouped differences (and so
    /// compressed `Φ`) on or off, and the number of compressed integrations.
    fn variational(problem: &impl Bvp, z0: &[f64], p: &[f64], sparse: bool) -> (Vec<f64>, bool) {
        let mut rk = RkWork::default();
        rk.resize(problem.dims());
        rk.learn_sparsity(sparse);
        let mode = Mode::Adaptive {
            rtol: 1e-6,
            atol: 1e-6,
            max_steps: 10_000,
        };
        let (a, b) = problem.interval();
        let mut stats = Stats::default();
        rk.integrate(problem, p, a, b, z0, true, mode, None, &mut stats)
            .unwrap();
        (rk.w().to_vec(), rk.reach.last_compressed)
    }

    #[test]
    fn compressed_variational_equations_match_dense_ones() {
        let big = crate::samples::FiniteDifferences(crate::samples::Big {
            pairs: 6,
            params: true,
        });
        let z0: Vec<f64> = (0..12).map(|i| 0.2 * i as f64 - 0.5).collect();
        let (dense, c0) = variational(&big, &z0, &[0.7, 1.3], false);
        let (sparse, c1) = variational(&big, &z0, &[0.7, 1.3], true);
        assert!(!c0 && c1);
        assert_eq!(dense, sparse);
    }

    /// `F = (z_1, max(z_0, 0) · z_2, 0)`: `∂F_1/∂z_0` vanishes where the pattern is learned
    /// (`z_0 < 0`) and appears once `z_0` turns positive during the integration.
    struct Kink;
    impl Bvp for Kink {
        fn dims(&self) -> Dims {
            Dims { n: 3, k: 0 }
        }
        fn interval(&self) -> (f64, f64) {
            (0.0, 2.0)
        }
        fn rhs(&self, _s: f64, z: &[f64], _p: &[f64], dz: &mut [f64]) {
            dz[0] = z[1];
            dz[1] = z[0].max(0.0) * z[2];
            dz[2] = 0.0;
        }
        fn bc(&self, za: &[f64], zb: &[f64], _p: &[f64], res: &mut [f64]) {
            res.copy_from_slice(&[za[0], zb[0], za[2]]);
        }
    }

    #[test]
    fn a_pattern_missed_during_the_integration_falls_back_to_dense() {
        let z0 = [-0.5, 1.0, 1.0];
        let (dense, _) = variational(&Kink, &z0, &[], false);
        let (sparse, compressed) = variational(&Kink, &z0, &[], true);
        assert!(!compressed, "repeated with dense Φ");
        assert_eq!(dense, sparse);
        // ∂z_1(b)/∂z_0(a) is nonzero only through the entry the first pattern missed.
        assert!(dense[3] != 0.0);
    }

    #[test]
    fn tableaus_satisfy_order_conditions() {
        check_order_conditions(&RK4, 4);
        check_order_conditions(&DOP853, 8);
    }
}
