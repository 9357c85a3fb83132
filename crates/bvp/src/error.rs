//! Error and termination status.

use crate::Stats;

/// How a solve terminated.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub enum Status {
    /// Converged to the requested tolerances.
    Converged,
    /// Newton made no progress (damping reached its minimum without decrease of the residual,
    /// which was above the precision floor `newton.step_residual_tol`).
    Stalled,
    /// The Newton iteration limit was reached.
    MaxIterations,
    /// The Newton matrix was singular, or numerically so (collocation: residuals at the
    /// tolerance could move the solution by more than its size).
    SingularJacobian,
    /// The right-hand side, the boundary conditions or a Jacobian produced NaN or infinity.
    NonFinite,
    /// Collocation needed more nodes than allowed.
    MeshLimit,
    /// The adaptive integrator could not meet its tolerance (step size underflow).
    StepSizeTooSmall,
    /// Options or problem dimensions were invalid.
    InvalidInput,
    /// A continuation path ended before its target (step limit, or the branch turned back).
    PathEnded,
    /// The solve converged, but the solution it would return fails its own check: its error
    /// estimate or boundary residual exceeds the tolerance.
    Inaccurate,
}

/// Why a solve failed. Every variant that comes from a solve carries the [`Stats`] gathered so far.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum BvpError {
    /// An option is outside its valid range.
    #[error("invalid option {name} = {value}: {reason}")]
    InvalidOption {
        /// Option name.
        name: &'static str,
        /// Offending value, formatted.
        value: String,
        /// The valid range or rule.
        reason: &'static str,
    },
    /// A guess, mesh or problem has the wrong size or is malformed.
    #[error("invalid input: {what} has {got}, expected {expected}")]
    Dimension {
        /// What was malformed.
        what: &'static str,
        /// What it had.
        got: usize,
        /// What was expected.
        expected: usize,
    },
    /// The guess is malformed: its mesh is not finite and strictly increasing or does not span
    /// the problem's interval, or a value is not finite.
    #[error("invalid guess: {what} at index {index} (value {value}): {reason}")]
    InvalidGuess {
        /// What is wrong: "mesh", "values", "derivatives", "parameters".
        what: &'static str,
        /// Index of the first offending entry.
        index: usize,
        /// Its value.
        value: f64,
        /// The rule it breaks.
        reason: &'static str,
    },
    /// The Newton matrix is singular.
    #[error(
        "singular Jacobian at Newton iteration {iteration}: the problem (or its discretization at \
         this tolerance) has no locally unique solution; check the boundary conditions and \
         parameters, or try another guess ({stats})"
    )]
    SingularJacobian {
        /// Newton iteration at which factorization failed.
        iteration: usize,
        /// Statistics so far.
        stats: Stats,
    },
    /// Damped Newton could not reduce the residual.
    #[error(
        "Newton stalled at iteration {iteration} with (scaled) residual {residual:.3e}: the damped \
         step cannot reduce it (line search down to newton.min_damping); try a better guess or \
         solve_by_continuation, or, if this is the rounding floor of the problem, raise \
         newton.step_residual_tol ({stats})"
    )]
    Stalled {
        /// Newton iteration.
        iteration: usize,
        /// Residual max-norm when it stalled.
        residual: f64,
        /// Statistics so far.
        stats: Stats,
    },
    /// Iteration limit reached.
    #[error(
        "no convergence in {max_iter} Newton iterations (raise newton.max_iter), residual \
         {residual:.3e} ({stats})"
    )]
    MaxIterations {
        /// The limit.
        max_iter: usize,
        /// Residual max-norm at the end.
        residual: f64,
        /// Statistics so far.
        stats: Stats,
    },
    /// NaN or infinity appeared.
    #[error("non-finite value in {location} at s = {s} ({stats})")]
    NonFinite {
        /// Where: "rhs", "bc", "jacobian", "newton step".
        location: &'static str,
        /// Abscissa where it appeared (NaN if not applicable).
        s: f64,
        /// Statistics so far.
        stats: Stats,
    },
    /// Collocation mesh would exceed `max_nodes`.
    #[error(
        "mesh limit: {needed} nodes needed but max_nodes = {max_nodes} (raise max_nodes or \
         max_mesh_passes, or loosen tol); residual {residual:.3e} ({stats})"
    )]
    MeshLimit {
        /// The cap.
        max_nodes: usize,
        /// Nodes the next refinement asked for.
        needed: usize,
        /// Max scaled collocation residual at the last mesh.
        residual: f64,
        /// Statistics so far.
        stats: Stats,
    },
    /// Adaptive integration failed.
    #[error(
        "integration failed at s = {s}: step size {h:.3e} too small or max_steps reached (raise \
         max_steps, loosen rtol/atol, or use more shooting segments) ({stats})"
    )]
    StepSizeTooSmall {
        /// Where.
        s: f64,
        /// The step size.
        h: f64,
        /// Statistics so far.
        stats: Stats,
    },
    /// Continuation could not take a step even at the minimum step length (or locate a fold);
    /// `source` is the last solver error, `hint` a likely cause (e.g. a fold for natural continuation).
    #[error(
        "continuation step {step} from lambda = {lambda} failed at ds = {ds:.3e}{hint}: {source}"
    )]
    Continuation {
        /// Index of the branch point that could not be computed.
        step: usize,
        /// Parameter value of the last accepted point.
        lambda: f64,
        /// Step length of the last attempt.
        ds: f64,
        /// Likely cause, or empty.
        hint: &'static str,
        /// The solver's error at the last attempt.
        #[source]
        source: Box<BvpError>,
    },
    /// Natural continuation met a fold (a limit point in `λ`), which it cannot pass: its last
    /// step failed at the smallest step length and its last three points show `λ` turning back
    /// ahead of them (`fold`: the extremum of the quadratic `λ(σ)` through them, `σ` the
    /// arclength). Whatever the corrector's own error was (a stall, NaN/∞ past the fold).
    #[error(
        "natural continuation met a fold at lambda ≈ {fold:.6} (last point lambda = {lambda}, \
         step {step}); it cannot pass a fold in lambda: use PseudoArclength (the corrector: \
         {source})"
    )]
    Fold {
        /// Index of the branch point that could not be computed.
        step: usize,
        /// Parameter value of the last accepted point.
        lambda: f64,
        /// Estimated parameter value of the fold.
        fold: f64,
        /// The solver's error at the last attempt.
        #[source]
        source: Box<BvpError>,
    },
    /// [`crate::solve_by_continuation`] took every step it could and stopped short of its
    /// target: `continuation.max_steps` ran out, or the branch turned back (a fold in the
    /// parameter) and ended on the starting side.
    #[error(
        "continuation stopped at lambda = {lambda} after {steps} steps, short of its target: \
         {} ({stats})",
        path_end(*.turned_back)
    )]
    PathEnded {
        /// Parameter value of the last point.
        lambda: f64,
        /// Points computed after the start.
        steps: usize,
        /// The branch turned back (else the step limit ran out).
        turned_back: bool,
        /// Statistics of the whole path.
        stats: Stats,
    },
    /// Newton converged, but the solution it would return fails the solver's own check of it
    /// (e.g. shooting: the error estimate of the returned trajectory exceeds `tol`): no solution
    /// is returned rather than a wrong one.
    #[error(
        "the converged solution misses its tolerance: {check} {value:.3e} > tol {tol:.3e} \
         (tighten the integrator, use more segments, or collocation) ({stats})"
    )]
    Inaccurate {
        /// Which check failed.
        check: Check,
        /// The measured value.
        value: f64,
        /// The tolerance it had to meet.
        tol: f64,
        /// Statistics of the solve.
        stats: Stats,
    },
}

/// What an [`BvpError::Inaccurate`] solution missed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub enum Check {
    /// The estimated error of the returned trajectory and of its dense output, scaled by the
    /// solution's size (see the solver's docs).
    ErrorEstimate,
    /// The boundary conditions (and, multiple shooting, the continuity at the segment joints)
    /// evaluated on the returned trajectory.
    BoundaryResidual,
}

impl std::fmt::Display for Check {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Check::ErrorEstimate => "error estimate",
            Check::BoundaryResidual => "boundary residual",
        })
    }
}

fn path_end(turned_back: bool) -> &'static str {
    if turned_back {
        "the branch turned back at a fold in the parameter and returned to the starting side \
         (the target is not on this branch)"
    } else {
        "continuation.max_steps ran out (raise it; a step length that stays small means the \
         corrector struggles there)"
    }
}

impl BvpError {
    /// The termination status this error stands for.
    pub fn status(&self) -> Status {
        match self {
            BvpError::InvalidOption { .. }
            | BvpError::Dimension { .. }
            | BvpError::InvalidGuess { .. } => Status::InvalidInput,
            BvpError::SingularJacobian { .. } => Status::SingularJacobian,
            BvpError::Stalled { .. } => Status::Stalled,
            BvpError::MaxIterations { .. } => Status::MaxIterations,
            BvpError::NonFinite { .. } => Status::NonFinite,
            BvpError::MeshLimit { .. } => Status::MeshLimit,
            BvpError::StepSizeTooSmall { .. } => Status::StepSizeTooSmall,
            BvpError::Continuation { source, .. } => source.status(),
            BvpError::PathEnded { .. } | BvpError::Fold { .. } => Status::PathEnded,
            BvpError::Inaccurate { .. } => Status::Inaccurate,
        }
    }

    /// Statistics of the failed solve, if it got that far.
    pub fn stats(&self) -> Option<&Stats> {
        match self {
            BvpError::InvalidOption { .. }
            | BvpError::Dimension { .. }
            | BvpError::InvalidGuess { .. } => None,
            BvpError::SingularJacobian { stats, .. }
            | BvpError::Stalled { stats, .. }
            | BvpError::MaxIterations { stats, .. }
            | BvpError::NonFinite { stats, .. }
            | BvpError::MeshLimit { stats, .. }
            | BvpError::StepSizeTooSmall { stats, .. }
            | BvpError::PathEnded { stats, .. }
            | BvpError::Inaccurate { stats, .. } => Some(stats),
            BvpError::Continuation { source, .. } | BvpError::Fold { source, .. } => source.stats(),
        }
    }
}
