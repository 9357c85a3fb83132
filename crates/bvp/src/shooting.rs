//! Single and multiple shooting.
//!
//! (skeleton: to be implemented — see issue #3)

use crate::{Bvp, BvpError, BvpSolver, Guess, NewtonOptions, Solution};

/// Integrator used for shooting.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub enum Integrator {
    /// Classical fixed-step RK4 with `steps` steps over the whole interval (split over segments).
    Rk4 {
        /// Total number of steps over `[a, b]`.
        steps: usize,
    },
    /// Adaptive embedded Runge–Kutta pair with error control.
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
    /// Number of shooting segments; 1 is single shooting. Default 1.
    pub segments: usize,
    /// Newton options.
    pub newton: NewtonOptions,
}

/// Single / multiple shooting solver.
#[derive(Clone, Debug)]
pub struct Shooting {
    opts: ShootingOptions,
}

impl Shooting {
    /// Creates a solver; validates the options.
    pub fn new(opts: ShootingOptions) -> Result<Self, BvpError> {
        Ok(Shooting { opts })
    }
    /// The options.
    pub fn options(&self) -> &ShootingOptions {
        &self.opts
    }
}

impl BvpSolver for Shooting {
    fn solve<P: Bvp + ?Sized>(
        &mut self,
        _problem: &P,
        _guess: &Guess,
    ) -> Result<Solution, BvpError> {
        todo!("shooting")
    }
}
