//! Solutions and initial guesses.

use crate::{BvpError, Stats, Status};
use std::fmt;

/// How [`Solution::eval`] interpolates between mesh nodes: each solver's own continuous
/// extension, of the order of the method, so values between nodes are as accurate as the nodes
/// (up to a small constant).
#[derive(Clone, Debug, Default, PartialEq)]
pub enum Dense {
    /// Cubic Hermite on `z`, `dz` (order 4, C¹): Lobatto4 (it is its collocation polynomial,
    /// whose residual the error control measures), RK4 shooting, solutions built by hand.
    #[default]
    Hermite,
    /// Quintic Hermite on `z`, `dz` and `d2z ≈ z''` at the nodes (node-major, like `z`): order 6,
    /// C². For solutions built by hand; Lobatto6 returned it until issue 34, with `z''` from a
    /// central difference across each node, which is wrong next to a node where `F` has a kink
    /// (see [`Dense::QuinticIntervals`]).
    Quintic {
        /// Second derivatives at the nodes, `d/ds F(s, z(s), p)`.
        d2z: Vec<f64>,
    },
    /// Quintic Hermite on `z`, `dz` and `z''` taken from inside each interval: `2n` values per
    /// interval (interval-major), `z''` at its left end, then at its right end, each a one-sided
    /// difference of `F` along the solution's tangent into the interval. Order 6 and C¹ (C² where
    /// `F` is smooth across a node); `F` is never evaluated outside `[a, b]` or across a node, so
    /// a kink of `F` at a node (or at an end) costs no accuracy. Lobatto6.
    QuinticIntervals {
        /// `z''` at the ends of each interval, `[left (n), right (n)]` per interval.
        d2z: Vec<f64>,
    },
    /// DOP853's continuous extension of order 7 (Hairer's `contd8`) on every step: `7n`
    /// coefficients `r1 … r7` per mesh interval (blocks of `n`), see
    /// [`crate::tableau::dop853::D_DENSE`].
    Dop853 {
        /// Coefficients, interval-major.
        coef: Vec<f64>,
    },
}

/// A converged solution: values and derivatives on a mesh, unknown parameters, statistics.
///
/// Values are stored node-major: `z[i * n + j]` is state `j` at `mesh[i]`; `dz` likewise holds
/// `F(s_i, z_i, p)`. [`Solution::eval`] interpolates with the solver's continuous extension
/// ([`Dense`]: Lobatto4's collocation cubic, the quintic Hermite for Lobatto6, cubic Hermite
/// for RK4 shooting, DOP853's own 7th-order extension for adaptive shooting).
///
/// `stats` describe this solution as returned: `residual` is its boundary residual (and the
/// continuity residual of multiple shooting, the collocation residual of collocation) and
/// `error_estimate` the solver's estimate for it and its dense output (see each solver).
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Solution {
    /// Number of states.
    pub n: usize,
    /// Mesh `a = s_0 < s_1 < … < s_N = b`.
    pub mesh: Vec<f64>,
    /// States at the mesh nodes, node-major.
    pub z: Vec<f64>,
    /// Derivatives `F(s_i, z_i, p)` at the mesh nodes, node-major.
    pub dz: Vec<f64>,
    /// Unknown parameters.
    pub params: Vec<f64>,
    /// Termination status (always [`Status::Converged`] for a returned solution).
    pub status: Status,
    /// Statistics of the solve.
    pub stats: Stats,
    /// Interpolation between the nodes (not serialized).
    #[serde(skip)]
    pub dense: Dense,
}

impl Solution {
    /// Number of mesh nodes.
    pub fn len(&self) -> usize {
        self.mesh.len()
    }

    /// True if the mesh is empty (never for a solver's output).
    pub fn is_empty(&self) -> bool {
        self.mesh.is_empty()
    }

    /// States at node `i`.
    pub fn node(&self, i: usize) -> &[f64] {
        &self.z[i * self.n..(i + 1) * self.n]
    }

    /// States at the left end `z(a)`.
    pub fn left(&self) -> &[f64] {
        self.node(0)
    }

    /// States at the right end `z(b)`.
    pub fn right(&self) -> &[f64] {
        self.node(self.mesh.len() - 1)
    }

    /// Evaluates the solution at `s` (clamped to `[a, b]`) into `out` (length `n`) with the
    /// solver's continuous extension ([`Dense`]).
    pub fn eval(&self, s: f64, out: &mut [f64]) {
        let n = self.n;
        let ok = |len: usize, per: usize| len == per * n && self.mesh.len() >= 2;
        match &self.dense {
            Dense::Quintic { d2z } if ok(d2z.len(), self.mesh.len()) => {
                let i = locate(&self.mesh, s);
                let (d0, d1) = (&d2z[i * n..(i + 1) * n], &d2z[(i + 1) * n..(i + 2) * n]);
                self.quintic(i, s, d0, d1, false, out);
            }
            Dense::QuinticIntervals { d2z } if ok(d2z.len(), 2 * (self.mesh.len() - 1)) => {
                let i = locate(&self.mesh, s);
                let (d0, d1) = (
                    &d2z[2 * i * n..(2 * i + 1) * n],
                    &d2z[(2 * i + 1) * n..(2 * i + 2) * n],
                );
                self.quintic(i, s, d0, d1, false, out);
            }
            Dense::Dop853 { coef } if ok(coef.len(), 7 * (self.mesh.len() - 1)) => {
                let i = locate(&self.mesh, s);
                let h = self.mesh[i + 1] - self.mesh[i];
                let t = ((s - self.mesh[i]) / h).clamp(0.0, 1.0);
                let u = 1.0 - t;
                let c = &coef[7 * n * i..7 * n * (i + 1)];
                for j in 0..n {
                    let r = |m: usize| c[m * n + j];
                    let v = r(5) + t * r(6);
                    let v = r(4) + u * v;
                    let v = r(3) + t * v;
                    let v = r(2) + u * v;
                    let v = r(1) + t * v;
                    let v = r(0) + u * v;
                    out[j] = self.z[i * n + j] + t * v;
                }
            }
            _ => hermite_eval(&self.mesh, &self.z, &self.dz, n, s, out),
        }
    }

    /// Convenience: evaluates at `s` into a new vector.
    ///
    /// ```
    /// use bvp::{from_fns, BvpSolver, Collocation, CollocationOptions, Guess};
    ///
    /// // y'' = −y, y(0) = 0, y(π/2) = 1: y = sin s, evaluated between the mesh nodes
    /// let sine = from_fns(
    ///     2,
    ///     (0.0, std::f64::consts::FRAC_PI_2),
    ///     |_s, z, _p, dz| {
    ///         dz[0] = z[1];
    ///         dz[1] = -z[0];
    ///     },
    ///     |za, zb, _p, res| {
    ///         res[0] = za[0];
    ///         res[1] = zb[0] - 1.0;
    ///     },
    /// );
    /// let opts = CollocationOptions { tol: 1e-8, ..CollocationOptions::default() };
    /// let guess = Guess::constant(0.0, std::f64::consts::FRAC_PI_2, 5, &[0.5, 0.5], vec![]);
    /// let sol = Collocation::new(opts)?.solve(&sine, &guess)?;
    /// for s in [0.1, 0.77, 1.3] {
    ///     assert!((sol.at(s)[0] - s.sin()).abs() < 1e-7);
    /// }
    /// # Ok::<(), bvp::BvpError>(())
    /// ```
    pub fn at(&self, s: f64) -> Vec<f64> {
        let mut out = vec![0.0; self.n];
        self.eval(s, &mut out);
        out
    }

    /// Evaluates the first derivative `d/ds` of the continuous extension at `s` (clamped to
    /// `[a, b]`) into `out` (length `n`): scipy's `sol(x, 1)`. It equals `dz` at the nodes and
    /// is of one order less than [`Solution::eval`] between them (quintic: 5, DOP853's
    /// extension: 6, cubic Hermite: 3). Fluxes, slopes and moments of the solution come from
    /// here, not from differencing the interpolant.
    #[allow(clippy::needless_range_loop)] // the formulas index several arrays alike
    pub fn eval_derivative(&self, s: f64, out: &mut [f64]) {
        let n = self.n;
        let nodes = self.mesh.len();
        if nodes < 2 {
            out.copy_from_slice(&self.dz[..n]);
            return;
        }
        let i = locate(&self.mesh, s);
        let h = self.mesh[i + 1] - self.mesh[i];
        let t = ((s - self.mesh[i]) / h).clamp(0.0, 1.0);
        let (a, b) = (i * n, (i + 1) * n);
        let ok = |len: usize, per: usize| len == per * n;
        match &self.dense {
            Dense::Quintic { d2z } if ok(d2z.len(), nodes) => {
                self.quintic(i, s, &d2z[a..b], &d2z[b..b + n], true, out);
            }
            Dense::QuinticIntervals { d2z } if ok(d2z.len(), 2 * (nodes - 1)) => {
                let (d0, d1) = (&d2z[2 * a..2 * a + n], &d2z[2 * a + n..2 * b]);
                self.quintic(i, s, d0, d1, true, out);
            }
            Dense::Dop853 { coef } if ok(coef.len(), 7 * (nodes - 1)) => {
                let u = 1.0 - t;
                let c = &coef[7 * n * i..7 * n * (i + 1)];
                for j in 0..n {
                    let r = |m: usize| c[m * n + j];
                    // z = z_i + t·v(t), v nested as in `eval`; carry (value, d/dt).
                    let (v5, d5) = (r(5) + t * r(6), r(6));
                    let (v4, d4) = (r(4) + u * v5, -v5 + u * d5);
                    let (v3, d3) = (r(3) + t * v4, v4 + t * d4);
                    let (v2, d2) = (r(2) + u * v3, -v3 + u * d3);
                    let (v1, d1) = (r(1) + t * v2, v2 + t * d2);
                    let (v0, d0) = (r(0) + u * v1, -v1 + u * d1);
                    out[j] = (v0 + t * d0) / h;
                }
            }
            _ => {
                let h00 = 6.0 * t * t - 6.0 * t;
                let h10 = 3.0 * t * t - 4.0 * t + 1.0;
                let h11 = 3.0 * t * t - 2.0 * t;
                for j in 0..n {
                    out[j] = (h00 * (self.z[a + j] - self.z[b + j])) / h
                        + h10 * self.dz[a + j]
                        + h11 * self.dz[b + j];
                }
            }
        }
    }

    /// The quintic Hermite interpolant on interval `i` with second derivatives `d0`, `d1` at its
    /// ends: its value at `s` (clamped to the interval), or its derivative (`derivative`).
    fn quintic(&self, i: usize, s: f64, d0: &[f64], d1: &[f64], derivative: bool, out: &mut [f64]) {
        let n = self.n;
        let h = self.mesh[i + 1] - self.mesh[i];
        let t = ((s - self.mesh[i]) / h).clamp(0.0, 1.0);
        let (t2, t3) = (t * t, t * t * t);
        let (t4, t5) = (t3 * t, t3 * t2);
        let (a, b) = (i * n, (i + 1) * n);
        // Basis functions of z_a, z_b, h z'_a, h z'_b, h² z''_a, h² z''_b (value), or their
        // d/dt divided by h (derivative).
        let w = if derivative {
            let h0 = (-30.0 * t2 + 60.0 * t3 - 30.0 * t4) / h;
            [
                h0,
                -h0,
                1.0 - 18.0 * t2 + 32.0 * t3 - 15.0 * t4,
                -12.0 * t2 + 28.0 * t3 - 15.0 * t4,
                0.5 * h * (2.0 * t - 9.0 * t2 + 12.0 * t3 - 5.0 * t4),
                0.5 * h * (3.0 * t2 - 8.0 * t3 + 5.0 * t4),
            ]
        } else {
            let h0 = 1.0 - 10.0 * t3 + 15.0 * t4 - 6.0 * t5;
            [
                h0,
                1.0 - h0,
                h * (t - 6.0 * t3 + 8.0 * t4 - 3.0 * t5),
                h * (-4.0 * t3 + 7.0 * t4 - 3.0 * t5),
                0.5 * h * h * (t2 - 3.0 * t3 + 3.0 * t4 - t5),
                0.5 * h * h * (t3 - 2.0 * t4 + t5),
            ]
        };
        for j in 0..n {
            out[j] = w[0] * self.z[a + j]
                + w[1] * self.z[b + j]
                + w[2] * self.dz[a + j]
                + w[3] * self.dz[b + j]
                + w[4] * d0[j]
                + w[5] * d1[j];
        }
    }

    /// Convenience: the first derivative at `s` into a new vector ([`Solution::eval_derivative`]).
    pub fn derivative_at(&self, s: f64) -> Vec<f64> {
        let mut out = vec![0.0; self.n];
        self.eval_derivative(s, &mut out);
        out
    }

    /// Per-interval residual of the returned solution as a function: on each mesh interval the
    /// RMS (5-point Lobatto quadrature, as collocation's error control) of
    /// `(S'(s) − F(s, S(s), p)) / (1 + |F(s, S(s), p)|)` componentwise, with `S` the continuous
    /// extension ([`Solution::eval`], [`Solution::eval_derivative`]): where the returned
    /// interpolant fails to satisfy the ODE, and by how much (scipy's `rms_residuals`).
    /// `problem` must be the one solved (with `singular_term` if any).
    pub fn residuals<P: crate::Bvp + ?Sized>(&self, problem: &P) -> Vec<f64> {
        match crate::singular::Regular::new(problem) {
            Ok(Some(reg)) => self.residuals_of(&reg),
            _ => self.residuals_of(problem),
        }
    }

    pub(crate) fn residuals_of<P: crate::Bvp + ?Sized>(&self, problem: &P) -> Vec<f64> {
        let n = self.n;
        let (mut y, mut dy, mut f) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        let mut out = Vec::with_capacity(self.mesh.len().saturating_sub(1));
        for w in self.mesh.windows(2) {
            let h = w[1] - w[0];
            let mut sum = 0.0;
            for (t, wt) in EST_T.iter().zip(EST_W) {
                let s = w[0] + t * h;
                self.eval(s, &mut y);
                self.eval_derivative(s, &mut dy);
                problem.rhs(s, &y, &self.params, &mut f);
                let mut ss = 0.0;
                for c in 0..n {
                    let r = (dy[c] - f[c]) / (1.0 + f[c].abs());
                    ss += r * r;
                }
                sum += wt * ss;
            }
            out.push(sum.sqrt());
        }
        out
    }
}

/// Interior nodes of 5-point Lobatto quadrature on `[0, 1]` and their weights (the end nodes carry
/// weight 1/20 each but the residual vanishes there by construction: the interpolants match `F`
/// at the nodes).
pub(crate) const EST_T: [f64; 3] = [
    0.5 - 0.5 * 0.654_653_670_707_977_1, // sqrt(3/7)
    0.5,
    0.5 + 0.5 * 0.654_653_670_707_977_1,
];
pub(crate) const EST_W: [f64; 3] = [49.0 / 180.0, 16.0 / 45.0, 49.0 / 180.0];

impl fmt::Display for Solution {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{:?}: {} states, {} nodes on [{}, {}], params {:?}; {}",
            self.status,
            self.n,
            self.mesh.len(),
            self.mesh.first().copied().unwrap_or(f64::NAN),
            self.mesh.last().copied().unwrap_or(f64::NAN),
            self.params,
            self.stats
        )
    }
}

/// Locates the interval of `mesh` holding `s` (clamped), by bisection.
pub(crate) fn locate(mesh: &[f64], s: f64) -> usize {
    let last = mesh.len() - 1;
    if s <= mesh[0] {
        return 0;
    }
    if s >= mesh[last] {
        return last.saturating_sub(1);
    }
    let (mut lo, mut hi) = (0, last);
    while hi - lo > 1 {
        let mid = (lo + hi) / 2;
        if mesh[mid] <= s {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}

fn hermite_eval(mesh: &[f64], z: &[f64], dz: &[f64], n: usize, s: f64, out: &mut [f64]) {
    if mesh.len() == 1 {
        out.copy_from_slice(&z[..n]);
        return;
    }
    let i = locate(mesh, s);
    let (s0, s1) = (mesh[i], mesh[i + 1]);
    let h = s1 - s0;
    let t = ((s - s0) / h).clamp(0.0, 1.0);
    let t2 = t * t;
    let t3 = t2 * t;
    let h00 = 2.0 * t3 - 3.0 * t2 + 1.0;
    let h10 = t3 - 2.0 * t2 + t;
    let h01 = -2.0 * t3 + 3.0 * t2;
    let h11 = t3 - t2;
    for j in 0..n {
        out[j] = h00 * z[i * n + j]
            + h10 * h * dz[i * n + j]
            + h01 * z[(i + 1) * n + j]
            + h11 * h * dz[(i + 1) * n + j];
    }
}

/// An initial guess: values on a mesh (linearly interpolated) and parameter values.
///
/// Build one from a function ([`Guess::from_fn`]), a constant, or a previous [`Solution`]
/// (`Guess::from(&solution)`, used for warm starts in continuation).
#[derive(Clone, Debug, PartialEq)]
pub struct Guess {
    /// Number of states.
    pub n: usize,
    /// Mesh of the guess (at least one node; two or more for collocation).
    pub mesh: Vec<f64>,
    /// States at the mesh nodes, node-major.
    pub z: Vec<f64>,
    /// Derivatives at the nodes, if known (then interpolation is cubic Hermite, else linear).
    pub dz: Option<Vec<f64>>,
    /// Parameter guesses.
    pub params: Vec<f64>,
}

impl Guess {
    /// Samples `f(s, z)` on `mesh`.
    pub fn from_fn(
        n: usize,
        mesh: Vec<f64>,
        params: Vec<f64>,
        mut f: impl FnMut(f64, &mut [f64]),
    ) -> Self {
        let mut z = vec![0.0; n * mesh.len()];
        for (i, &s) in mesh.iter().enumerate() {
            f(s, &mut z[i * n..(i + 1) * n]);
        }
        Guess {
            n,
            mesh,
            z,
            dz: None,
            params,
        }
    }

    /// The constant `z0` on `nodes` equally spaced nodes of `[a, b]`.
    pub fn constant(a: f64, b: f64, nodes: usize, z0: &[f64], params: Vec<f64>) -> Self {
        let nodes = nodes.max(2);
        let mesh = (0..nodes)
            .map(|i| a + (b - a) * i as f64 / (nodes - 1) as f64)
            .collect();
        Self::from_fn(z0.len(), mesh, params, |_, z| z.copy_from_slice(z0))
    }

    /// Checks the guess against a problem of `dims` on `interval` (called by every solver):
    /// `n` states, `k` parameters, `z` (and `dz`) of `n` values per node, at least one node, a
    /// mesh of two or more nodes finite, strictly increasing and spanning the interval (ends
    /// within `1e-12 (b − a)`), every value finite. Errors: [`BvpError::Dimension`],
    /// [`BvpError::InvalidGuess`], [`BvpError::InvalidOption`] for a bad interval.
    pub fn validate(&self, dims: crate::Dims, interval: (f64, f64)) -> Result<(), BvpError> {
        let crate::Dims { n, k } = dims;
        let dim = |what, got, expected| {
            if got == expected {
                Ok(())
            } else {
                Err(BvpError::Dimension {
                    what,
                    got,
                    expected,
                })
            }
        };
        if n == 0 {
            return Err(BvpError::Dimension {
                what: "problem states n",
                got: 0,
                expected: 1,
            });
        }
        let (a, b) = interval;
        if !(a < b && a.is_finite() && b.is_finite()) {
            return Err(BvpError::InvalidOption {
                name: "interval",
                value: format!("[{a}, {b}]"),
                reason: "must be finite with a < b",
            });
        }
        dim("guess states", self.n, n)?;
        dim("guess parameters", self.params.len(), k)?;
        if self.mesh.is_empty() {
            return Err(BvpError::Dimension {
                what: "guess mesh nodes",
                got: 0,
                expected: 1,
            });
        }
        dim("guess values", self.z.len(), n * self.mesh.len())?;
        if let Some(dz) = &self.dz {
            dim("guess derivatives", dz.len(), self.z.len())?;
        }
        let bad = |what, index: usize, value: f64, reason| {
            Err(BvpError::InvalidGuess {
                what,
                index,
                value,
                reason,
            })
        };
        let m = &self.mesh;
        if let Some(i) = m.iter().position(|t| !t.is_finite()) {
            return bad("mesh", i, m[i], "must be finite");
        }
        if let Some(i) = m.windows(2).position(|w| w[1] <= w[0]) {
            return bad("mesh", i + 1, m[i + 1], "must be strictly increasing");
        }
        if m.len() >= 2 {
            let slack = 1e-12 * (b - a);
            if (m[0] - a).abs() > slack {
                return bad("mesh", 0, m[0], "must start at a, the interval's left end");
            }
            if (m[m.len() - 1] - b).abs() > slack {
                return bad(
                    "mesh",
                    m.len() - 1,
                    m[m.len() - 1],
                    "must end at b, the interval's right end",
                );
            }
        }
        for (what, v) in [("values", &self.z), ("parameters", &self.params)] {
            if let Some(i) = v.iter().position(|x| !x.is_finite()) {
                return bad(what, i, v[i], "must be finite");
            }
        }
        if let Some(dz) = &self.dz {
            if let Some(i) = dz.iter().position(|x| !x.is_finite()) {
                return bad("derivatives", i, dz[i], "must be finite");
            }
        }
        Ok(())
    }

    /// Evaluates the guess at `s` into `out`.
    pub fn eval(&self, s: f64, out: &mut [f64]) {
        let n = self.n;
        if let Some(dz) = &self.dz {
            return hermite_eval(&self.mesh, &self.z, dz, n, s, out);
        }
        if self.mesh.len() == 1 {
            out.copy_from_slice(&self.z[..n]);
            return;
        }
        let i = locate(&self.mesh, s);
        let (s0, s1) = (self.mesh[i], self.mesh[i + 1]);
        let t = ((s - s0) / (s1 - s0)).clamp(0.0, 1.0);
        let (z0, z1) = (
            &self.z[i * n..(i + 1) * n],
            &self.z[(i + 1) * n..(i + 2) * n],
        );
        for ((o, &a), &b) in out[..n].iter_mut().zip(z0).zip(z1) {
            *o = (1.0 - t) * a + t * b;
        }
    }
}

impl From<&Solution> for Guess {
    fn from(sol: &Solution) -> Self {
        Guess {
            n: sol.n,
            mesh: sol.mesh.clone(),
            z: sol.z.clone(),
            dz: Some(sol.dz.clone()),
            params: sol.params.clone(),
        }
    }
}
