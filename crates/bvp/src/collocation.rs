//! Lobatto IIIA collocation with residual control and mesh adaptation.
//!
//! (skeleton: to be implemented — see issue #3)

use crate::{Bvp, BvpError, BvpSolver, Guess, NewtonOptions, Solution};

/// Collocation scheme.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub enum Scheme {
    /// 3-point Lobatto IIIA, order 4 (the `bvp4c` / `solve_bvp` scheme).
    Lobatto4,
    /// 4-point Lobatto IIIA, order 6.
    Lobatto6,
}

/// Options of [`Collocation`].
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct CollocationOptions {
    /// Scheme. Default `Lobatto4`.
    pub scheme: Scheme,
    /// Tolerance on the scaled ODE residual between nodes. Default 1e-6.
    pub tol: f64,
    /// Tolerance on the boundary conditions. Default 1e-10.
    pub bc_tol: f64,
    /// Cap on mesh nodes. Default 10 000.
    pub max_nodes: usize,
    /// Newton options.
    pub newton: NewtonOptions,
}

/// Collocation solver.
#[derive(Clone, Debug)]
pub struct Collocation {
    opts: CollocationOptions,
}

impl Collocation {
    /// Creates a solver; validates the options.
    pub fn new(opts: CollocationOptions) -> Result<Self, BvpError> {
        Ok(Collocation { opts })
    }
    /// The options.
    pub fn options(&self) -> &CollocationOptions {
        &self.opts
    }
}

impl BvpSolver for Collocation {
    fn solve<P: Bvp + ?Sized>(
        &mut self,
        _problem: &P,
        _guess: &Guess,
    ) -> Result<Solution, BvpError> {
        todo!("collocation")
    }
}
