//! Extending a solution to another interval, and continuation in an end of the interval.
//!
//! - [`Guess::extended`]: a guess on `[a', b']` from a solution on `[a, b]` (MATLAB's
//!   `bvpinit(sol, [a' b'])`): the solution's dense output where the intervals overlap, its end
//!   values held constant beyond them.
//! - [`Guess::rescaled`]: the solution stretched affinely onto `[a', b']` (a boundary layer or a
//!   decay keeps its shape relative to the interval: a Falkner–Skan "infinity" moved from 3 to 6).
//! - [`IntervalFamily`]: a problem whose right end `b = λ` is the continuation parameter of a
//!   [`ParamBvp`] family, solved on the fixed `τ ∈ [0, 1]`, `s = a + τ (λ − a)`:
//!   `dz/dτ = (λ − a) F(s, z, p)`; natural or pseudo-arclength continuation (or
//!   [`crate::solve_by_continuation`]) then walks the interval's end, and
//!   [`IntervalFamily::solution`] maps a member back onto `[a, λ]`.

use crate::continuation::ParamBvp;
use crate::{Bvp, Dense, Dims, Guess, Solution};

impl Guess {
    /// A guess on `[a, b]` from `sol` on another interval: nodes of `sol` inside `[a, b]` with
    /// its dense values, plus `a`, `b` and `extra` equally spaced nodes over each part of
    /// `[a, b]` outside `sol`'s interval, where the nearest end value of `sol` is held constant
    /// (as MATLAB's `bvpinit(sol, [a b])`). Parameters as in `sol`.
    pub fn extended(sol: &Solution, a: f64, b: f64, extra: usize) -> Guess {
        let (a0, b0) = (sol.mesh[0], sol.mesh[sol.mesh.len() - 1]);
        let mut mesh = Vec::new();
        let push_uniform = |lo: f64, hi: f64, mesh: &mut Vec<f64>| {
            for i in 0..=extra {
                mesh.push(lo + (hi - lo) * i as f64 / (extra + 1) as f64);
            }
        };
        if a < a0 {
            push_uniform(a, a0.min(b), &mut mesh);
        }
        mesh.extend(sol.mesh.iter().copied().filter(|&s| s >= a && s <= b));
        if b > b0 {
            let lo = b0.max(a);
            if mesh.last() == Some(&lo) {
                mesh.pop();
            }
            push_uniform(lo, b, &mut mesh);
        }
        if mesh.first() != Some(&a) {
            mesh.insert(0, a);
        }
        if mesh.last() != Some(&b) {
            mesh.push(b);
        }
        mesh.dedup();
        Guess::from_fn(sol.n, mesh, sol.params.clone(), |s, z| sol.eval(s, z))
    }

    /// `sol` stretched affinely onto `[a, b]`: its mesh mapped by
    /// `s' = a + (s − a₀)(b − a)/(b₀ − a₀)`, the same values, slopes scaled by the inverse
    /// stretch (`dz` of the guess, so it interpolates by cubic Hermite). Parameters as in `sol`.
    pub fn rescaled(sol: &Solution, a: f64, b: f64) -> Guess {
        let (a0, b0) = (sol.mesh[0], sol.mesh[sol.mesh.len() - 1]);
        let stretch = (b - a) / (b0 - a0);
        let last = sol.mesh.len() - 1;
        let mesh = sol
            .mesh
            .iter()
            .enumerate()
            .map(|(i, s)| match i {
                0 => a,
                i if i == last => b,
                _ => a + (s - a0) * stretch,
            })
            .collect();
        Guess {
            n: sol.n,
            mesh,
            z: sol.z.clone(),
            dz: Some(sol.dz.iter().map(|d| d / stretch).collect()),
            params: sol.params.clone(),
        }
    }
}

/// A [`Bvp`] as a [`ParamBvp`] family in its right end `λ = b` (see the module docs): solved on
/// `τ ∈ [0, 1]`. The problem's own `interval().1` is ignored; `F` and `g` must make sense for
/// every `λ` walked (a condition "at infinity" imposed at `λ`).
#[derive(Clone, Debug)]
pub struct IntervalFamily<P> {
    /// The problem; its left end `a` is kept.
    pub problem: P,
}

impl<P: Bvp> IntervalFamily<P> {
    /// The family of `problem` in its right end.
    pub fn new(problem: P) -> Self {
        IntervalFamily { problem }
    }

    fn left(&self) -> f64 {
        self.problem.interval().0
    }

    /// A guess for the family (on `τ ∈ [0, 1]`) from a solution on `[a, λ]`.
    pub fn guess(&self, sol: &Solution) -> Guess {
        Guess::rescaled(sol, 0.0, 1.0)
    }

    /// A member solved on `τ ∈ [0, 1]` mapped back onto `[a, λ]` (mesh, slopes and the
    /// second derivatives of the dense output scaled; DOP853's coefficients are in each step's
    /// own time and stay).
    pub fn solution(&self, member: &Solution, lambda: f64) -> Solution {
        let a = self.left();
        let len = lambda - a;
        let mut sol = member.clone();
        sol.mesh = member.mesh.iter().map(|t| a + t * len).collect();
        sol.dz = member.dz.iter().map(|d| d / len).collect();
        match &mut sol.dense {
            Dense::Quintic { d2z } | Dense::QuinticIntervals { d2z } => {
                d2z.iter_mut().for_each(|d| *d /= len * len)
            }
            Dense::Hermite | Dense::Dop853 { .. } => {}
        }
        sol
    }
}

impl<P: Bvp> ParamBvp for IntervalFamily<P> {
    fn dims(&self) -> Dims {
        self.problem.dims()
    }
    fn interval(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn rhs(&self, tau: f64, z: &[f64], p: &[f64], lambda: f64, dz: &mut [f64]) {
        let a = self.left();
        let s = if tau >= 1.0 {
            lambda
        } else {
            a + tau * (lambda - a)
        };
        self.problem.rhs(s, z, p, dz);
        dz.iter_mut().for_each(|d| *d *= lambda - a);
    }
    fn bc(&self, za: &[f64], zb: &[f64], p: &[f64], _lambda: f64, res: &mut [f64]) {
        self.problem.bc(za, zb, p, res);
    }
}
