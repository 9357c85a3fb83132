//! The crate's error type.

use crate::branch::Branch;

/// Everything that can go wrong in this crate. Every variant carries the offending value and,
/// where there is one, the valid range, so that the message alone tells the caller what to fix.
/// No function of this crate returns NaN or panics on bad input; it returns one of these.
#[derive(thiserror::Error, Debug, Clone, PartialEq)]
pub enum ElasticaError {
    /// The force angle is outside the branch's admissible range.
    #[error("alpha = {alpha} is outside the valid range [{min}, {max}] (radians; -pi/2 = {:.6}, -pi/4 = {:.6})", -std::f64::consts::FRAC_PI_2, -std::f64::consts::FRAC_PI_4)]
    AlphaOutOfRange {
        /// offending value
        alpha: f64,
        /// lower end of the valid range
        min: f64,
        /// upper end of the valid range
        max: f64,
    },
    /// The tip slope is outside `[0, pi/2 + 2 alpha]` (2.5)/(2.13); the range is empty when
    /// `alpha < -pi/4`.
    #[error("phi1 = {phi1} is outside the valid range [{min}, {max}] = [0, pi/2 + 2 alpha] of the {branch:?} branch (the range is empty for alpha < -pi/4)")]
    Phi1OutOfRange {
        /// offending value
        phi1: f64,
        /// lower end of the valid range
        min: f64,
        /// upper end of the valid range
        max: f64,
        /// branch asked for
        branch: Branch,
    },
    /// The surface height is outside `(eta_, 1)` of section 3.1.
    #[error(
        "eta = {eta} is outside the valid range ({min}, {max}) = (eta_, 1) of the stiction scan"
    )]
    EtaOutOfRange {
        /// offending value
        eta: f64,
        /// lower end (eta_ of section 3.1)
        min: f64,
        /// upper end (1: the straight rod)
        max: f64,
    },
    /// An input is NaN or infinite.
    #[error("{name} = {value} is not a finite number")]
    NotFinite {
        /// name of the argument
        name: &'static str,
        /// offending value
        value: f64,
    },
    /// An arc-length or other parameter outside its range.
    #[error("{name} = {value} is outside the valid range [{min}, {max}]")]
    OutOfRange {
        /// name of the argument
        name: &'static str,
        /// offending value
        value: f64,
        /// lower end of the valid range
        min: f64,
        /// upper end of the valid range
        max: f64,
    },
    /// A root was asked for on an interval where the function does not change sign.
    #[error("no root of {what} in [{a}, {b}]: f(a) = {fa}, f(b) = {fb} have the same sign")]
    NoRoot {
        /// what was being solved
        what: &'static str,
        /// left end of the search interval
        a: f64,
        /// right end of the search interval
        b: f64,
        /// function value at a
        fa: f64,
        /// function value at b
        fb: f64,
    },
    /// An iteration did not converge within its budget.
    #[error("{what} did not converge in {iterations} iterations (last interval width {width})")]
    NoConvergence {
        /// what was iterated
        what: &'static str,
        /// iterations spent
        iterations: usize,
        /// width of the last bracket
        width: f64,
    },
    /// The requested quantity cannot be computed to a useful accuracy here.
    #[error("{what} is ill-conditioned at {name} = {value}: {reason}")]
    IllConditioned {
        /// what was computed
        what: &'static str,
        /// name of the parameter that is too close to a singular value
        name: &'static str,
        /// its value
        value: f64,
        /// why
        reason: &'static str,
    },
    /// The stiction scan at this height has no one-flex phase: the convex phase ends with a
    /// horizontal tip (phi1 = 0) before the turning point (e.g. eta = 0.6), and continuing would
    /// need phi1 < 0, i.e. the rod would cross the surface.
    #[error("the scan at eta = {eta} has no one-flex phase: the convex phase ends at alpha = {alpha_end} with phi1 = 0 (the tip would have to dip below the surface to go on)")]
    NoFlexPhase {
        /// surface height
        eta: f64,
        /// alpha at the end of the convex phase
        alpha_end: f64,
    },
    /// An error reported by the `ellip` crate.
    #[error("elliptic integral: {0}")]
    Ellip(&'static str),
}

impl ElasticaError {
    /// Whether the error is about the input (a value outside the closed forms' domain, or a
    /// scan height without the phase asked for) rather than a failed computation: the caller's
    /// to fix by changing the input.
    pub fn is_input(&self) -> bool {
        matches!(
            self,
            ElasticaError::AlphaOutOfRange { .. }
                | ElasticaError::Phi1OutOfRange { .. }
                | ElasticaError::EtaOutOfRange { .. }
                | ElasticaError::NotFinite { .. }
                | ElasticaError::OutOfRange { .. }
                | ElasticaError::NoFlexPhase { .. }
        )
    }
}

/// Check that `value` is finite.
pub(crate) fn finite(name: &'static str, value: f64) -> Result<f64, ElasticaError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(ElasticaError::NotFinite { name, value })
    }
}
