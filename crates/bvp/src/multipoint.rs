//! Multipoint problems: interfaces at interior points with conditions across them.
//!
//! # The problem
//!
//! `[a, b]` is split at interfaces `a = ξ_0 < ξ_1 < … < ξ_K = b` into `K` regions; on region `r`
//!
//! ```text
//!     z'(s) = F_r(s, z(s), p)          s ∈ [ξ_r, ξ_{r+1}]
//! ```
//!
//! (`F` may differ per region: a coefficient that jumps, a forcing with a corner at `ξ_r`), and
//! `nK + k` conditions `g(z(ξ_0⁺), …, z(ξ_{K−1}⁺), z(ξ_1⁻), …, z(ξ_K⁻), p) = 0` couple the values
//! at every region's two ends: the boundary conditions at `a` and `b` and the interface
//! conditions — continuity `z(ξ_r⁻) = z(ξ_r⁺)`, a jump, a flux balance — in any form.
//!
//! # How it is solved
//!
//! [`Regions`] maps region `r` onto `τ ∈ [0, 1]`, `s = ξ_r + τ L_r` (`L_r = ξ_{r+1} − ξ_r`), and
//! stacks the regions: `Z = (z_0, …, z_{K−1})` with `nK` states solves the two-point problem
//! `dZ_r/dτ = L_r F_r(ξ_r + τ L_r, Z_r, p)` with `g(Z(0), Z(1), p) = 0` — the rewriting by hand
//! that bvp4c's and scipy's users do, done here. Any solver solves it; every mesh node of the
//! stacked problem is a node of every region, and a kink of `F` at an interface is at a node by
//! construction (never inside an interval). [`Regions::split`] turns the stacked solution into
//! one [`Solution`] per region on its own interval, with its dense output ([`MultiSolution`]).

use crate::{Bvp, Dense, Dims, Guess, Solution};

/// A multipoint problem (see the module docs).
pub trait MultipointBvp {
    /// `n` states (per region) and `k` unknown parameters.
    fn dims(&self) -> Dims;
    /// The interfaces with the ends: `a = ξ_0 < ξ_1 < … < ξ_K = b` (at least two values).
    fn breakpoints(&self) -> &[f64];
    /// `F_r(s, z, p)` on region `r` (`ξ_r ≤ s ≤ ξ_{r+1}`) into `dz`.
    fn rhs(&self, region: usize, s: f64, z: &[f64], p: &[f64], dz: &mut [f64]);
    /// The `nK + k` conditions: `left` holds `z(ξ_r⁺)` and `right` holds `z(ξ_{r+1}⁻)` of every
    /// region `r` (`nK` values each, region-major).
    fn bc(&self, left: &[f64], right: &[f64], p: &[f64], res: &mut [f64]);
}

/// A [`MultipointBvp`] as the stacked two-point problem on `[0, 1]` with `nK` states (see the
/// module docs): pass it to any solver, then [`Regions::split`] the solution.
#[derive(Clone, Debug)]
pub struct Regions<P> {
    /// The multipoint problem.
    pub problem: P,
    lengths: Vec<f64>,
}

impl<P: MultipointBvp> Regions<P> {
    /// Wraps `problem`. Errors: fewer than two breakpoints, or breakpoints that are not finite
    /// and strictly increasing ([`crate::BvpError::InvalidOption`]).
    pub fn new(problem: P) -> Result<Self, crate::BvpError> {
        let xi = problem.breakpoints();
        let ok =
            xi.len() >= 2 && xi.iter().all(|x| x.is_finite()) && xi.windows(2).all(|w| w[1] > w[0]);
        if !ok {
            return Err(crate::BvpError::InvalidOption {
                name: "breakpoints",
                value: format!("{xi:?}"),
                reason: "need at least two, finite and strictly increasing",
            });
        }
        let lengths = xi.windows(2).map(|w| w[1] - w[0]).collect();
        Ok(Regions { problem, lengths })
    }

    /// Number of regions `K`.
    pub fn regions(&self) -> usize {
        self.lengths.len()
    }

    /// A guess for the stacked problem from a guess `f(s, z)` of the multipoint one, sampled on
    /// `nodes` equal nodes of every region (region `r` at `ξ_r + τ L_r`), with parameters.
    pub fn guess(
        &self,
        nodes: usize,
        params: Vec<f64>,
        mut f: impl FnMut(usize, f64, &mut [f64]),
    ) -> Guess {
        let n = self.problem.dims().n;
        let xi = self.problem.breakpoints();
        let k = self.regions();
        let mesh: Vec<f64> = (0..nodes.max(2))
            .map(|i| i as f64 / (nodes.max(2) - 1) as f64)
            .collect();
        Guess::from_fn(n * k, mesh, params, |tau, z| {
            for r in 0..k {
                f(r, xi[r] + tau * self.lengths[r], &mut z[r * n..(r + 1) * n]);
            }
        })
    }

    /// The solution of the stacked problem as one [`Solution`] per region, each on its own
    /// interval `[ξ_r, ξ_{r+1}]` with its dense output (the stacked one's, mapped: `z` as is,
    /// `z'` divided by `L_r`, `z''` by `L_r²`).
    pub fn split(&self, stacked: &Solution) -> MultiSolution {
        let n = self.problem.dims().n;
        let xi = self.problem.breakpoints();
        let regions = (0..self.regions())
            .map(|r| region_of(stacked, n, r, xi[r], self.lengths[r]))
            .collect();
        MultiSolution {
            breakpoints: xi.to_vec(),
            regions,
        }
    }
}

/// Region `r` (states `rn … rn + n`) of the stacked solution, mapped to `[x0, x0 + len]`.
fn region_of(st: &Solution, n: usize, r: usize, x0: f64, len: f64) -> Solution {
    let big = st.n;
    let pick = |v: &[f64], per: usize, scale: f64| -> Vec<f64> {
        v.chunks_exact(big * per)
            .flat_map(|c| {
                (0..per).flat_map(move |q| {
                    c[q * big + r * n..q * big + (r + 1) * n]
                        .iter()
                        .map(move |x| x * scale)
                })
            })
            .collect()
    };
    let dense = match &st.dense {
        Dense::Hermite => Dense::Hermite,
        Dense::Quintic { d2z } => Dense::Quintic {
            d2z: pick(d2z, 1, 1.0 / (len * len)),
        },
        Dense::QuinticIntervals { d2z } => Dense::QuinticIntervals {
            d2z: pick(d2z, 2, 1.0 / (len * len)),
        },
        // DOP853's coefficients are in the step's own normalized time: values only.
        Dense::Dop853 { coef } => Dense::Dop853 {
            coef: pick(coef, 7, 1.0),
        },
    };
    Solution {
        n,
        mesh: st.mesh.iter().map(|t| x0 + t * len).collect(),
        z: pick(&st.z, 1, 1.0),
        dz: pick(&st.dz, 1, 1.0 / len),
        params: st.params.clone(),
        status: st.status,
        stats: st.stats.clone(),
        dense,
    }
}

impl<P: MultipointBvp> Bvp for Regions<P> {
    fn dims(&self) -> Dims {
        let Dims { n, k } = self.problem.dims();
        Dims {
            n: n * self.regions(),
            k,
        }
    }
    fn interval(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn rhs(&self, tau: f64, z: &[f64], p: &[f64], dz: &mut [f64]) {
        let n = self.problem.dims().n;
        let xi = self.problem.breakpoints();
        for (r, &len) in self.lengths.iter().enumerate() {
            let (zr, dr) = (&z[r * n..(r + 1) * n], &mut dz[r * n..(r + 1) * n]);
            // τ = 1 maps exactly onto ξ_{r+1}: the region's own end, not the next region.
            let s = if tau >= 1.0 {
                xi[r + 1]
            } else {
                xi[r] + tau * len
            };
            self.problem.rhs(r, s, zr, p, dr);
            for v in dr.iter_mut() {
                *v *= len;
            }
        }
    }
    fn bc(&self, za: &[f64], zb: &[f64], p: &[f64], res: &mut [f64]) {
        self.problem.bc(za, zb, p, res);
    }
}

/// A multipoint solution: one [`Solution`] per region.
#[derive(Clone, Debug, PartialEq)]
pub struct MultiSolution {
    /// `a = ξ_0 < … < ξ_K = b`.
    pub breakpoints: Vec<f64>,
    /// The solution on each region `[ξ_r, ξ_{r+1}]`.
    pub regions: Vec<Solution>,
}

impl MultiSolution {
    /// The region holding `s`: `r` with `ξ_r ≤ s < ξ_{r+1}` (the last region for `s ≥ ξ_K`, the
    /// first for `s < ξ_0`). At an interface the region to its right: use
    /// [`MultiSolution::regions`] for the left-hand limit.
    pub fn region_at(&self, s: f64) -> usize {
        let k = self.regions.len();
        self.breakpoints[1..k]
            .iter()
            .take_while(|&&x| x <= s)
            .count()
    }

    /// The solution at `s` (the region of [`MultiSolution::region_at`]).
    pub fn at(&self, s: f64) -> Vec<f64> {
        self.regions[self.region_at(s)].at(s)
    }

    /// Its derivative at `s` (same region).
    pub fn derivative_at(&self, s: f64) -> Vec<f64> {
        self.regions[self.region_at(s)].derivative_at(s)
    }
}
