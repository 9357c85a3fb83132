//! Solutions and initial guesses.

use crate::{Stats, Status};
use std::fmt;

/// A converged solution: values and derivatives on a mesh, unknown parameters, statistics.
///
/// Values are stored node-major: `z[i * n + j]` is state `j` at `mesh[i]`; `dz` likewise holds
/// `F(s_i, z_i, p)`. [`Solution::eval`] interpolates with cubic Hermite polynomials, which is
/// fourth-order accurate and continuous in value and slope (collocation solvers may override
/// accuracy by using finer meshes).
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

    /// Evaluates the solution at `s` (clamped to `[a, b]`) into `out` (length `n`) by cubic Hermite
    /// interpolation between nodes.
    pub fn eval(&self, s: f64, out: &mut [f64]) {
        hermite_eval(&self.mesh, &self.z, &self.dz, self.n, s, out);
    }

    /// Convenience: evaluates at `s` into a new vector.
    pub fn at(&self, s: f64) -> Vec<f64> {
        let mut out = vec![0.0; self.n];
        self.eval(s, &mut out);
        out
    }
}

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
