//! Solver statistics.

use std::fmt;

/// Work counters and accuracy measures of one solve (or of a failed attempt).
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct Stats {
    /// Evaluations of the right-hand side `F` (including those inside finite differences).
    pub rhs_evals: usize,
    /// Evaluations of `∂F/∂z`, `∂F/∂p` (analytic or by finite differences).
    pub jac_evals: usize,
    /// Evaluations of the boundary residual `g`.
    pub bc_evals: usize,
    /// Newton iterations (summed over mesh refinements for collocation).
    pub newton_iters: usize,
    /// Linear systems factorized.
    pub factorizations: usize,
    /// Integration steps taken (shooting) — accepted and rejected.
    pub steps: usize,
    /// Rejected steps of the adaptive integrator.
    pub rejected_steps: usize,
    /// Mesh nodes of the final mesh (collocation) or segment nodes (shooting).
    pub nodes: usize,
    /// Mesh refinement / coarsening passes (collocation).
    pub mesh_passes: usize,
    /// Max-norm of the final nonlinear residual (boundary and continuity/collocation conditions;
    /// collocation rows divided by `1 + |F|`, see [`crate::newton::NewtonSystem::residual_scale`]).
    pub residual: f64,
    /// Estimated error of the solution as returned (collocation: the max scaled RMS residual of
    /// the returned interpolant over the mesh intervals, or, once error control decided (with
    /// [`crate::ErrorControl::Error`], or after a confirmed alarm of the guard), its estimated
    /// true error; shooting: see
    /// [`crate::Shooting`]).
    pub error_estimate: Option<f64>,
}

impl Stats {
    /// Adds the counters of `other` (not the residual or error estimate) to `self`.
    pub fn accumulate(&mut self, other: &Stats) {
        self.rhs_evals += other.rhs_evals;
        self.jac_evals += other.jac_evals;
        self.bc_evals += other.bc_evals;
        self.newton_iters += other.newton_iters;
        self.factorizations += other.factorizations;
        self.steps += other.steps;
        self.rejected_steps += other.rejected_steps;
        self.mesh_passes += other.mesh_passes;
    }
}

impl fmt::Display for Stats {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "newton {} it, {} factorizations, rhs {} evals, jac {} evals, bc {} evals, {} steps ({} rejected), {} nodes, residual {:.3e}",
            self.newton_iters,
            self.factorizations,
            self.rhs_evals,
            self.jac_evals,
            self.bc_evals,
            self.steps,
            self.rejected_steps,
            self.nodes,
            self.residual
        )?;
        if let Some(e) = self.error_estimate {
            write!(f, ", error estimate {e:.3e}")?;
        }
        Ok(())
    }
}
