//! Damped Newton iteration shared by the solvers.
//!
//! (skeleton: to be implemented — see issue #3)

/// Options of the damped Newton iteration.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct NewtonOptions {
    /// Maximum Newton iterations. Default 50.
    pub max_iter: usize,
    /// Convergence: max-norm of the residual below `tol`. Default 1e-10.
    pub tol: f64,
    /// Convergence: max-norm of the step below `step_tol · (1 + |u|)`. Default 1e-12.
    pub step_tol: f64,
    /// Smallest damping factor of the line search before declaring a stall. Default 1e-6.
    pub min_damping: f64,
}

impl Default for NewtonOptions {
    fn default() -> Self {
        NewtonOptions {
            max_iter: 50,
            tol: 1e-10,
            step_tol: 1e-12,
            min_damping: 1e-6,
        }
    }
}
