//! The crate's error type.

/// Everything that can go wrong in this crate. Variants carry the offending value and, where
/// there is one, the valid range, so the message alone says what to fix.
#[derive(thiserror::Error, Debug, Clone, PartialEq)]
pub enum VibrissaError {
    /// A scalar input is outside its valid range (or NaN).
    #[error("{name} = {value} is outside the valid range {range}")]
    OutOfRange {
        /// Name of the value (e.g. `eta`, `stiffness.ratio`).
        name: String,
        /// Offending value.
        value: f64,
        /// The valid range, in words (e.g. `(0.45695, 1)`).
        range: String,
    },
    /// A table (`s`, values) is malformed.
    #[error("invalid table {name}: {reason}")]
    InvalidTable {
        /// Which table.
        name: String,
        /// What is wrong, with the offending entry.
        reason: String,
    },
    /// The method is not available for this scene (e.g. `analytic` off the paper's scene).
    #[error("method {method} is not available here: {reason}")]
    MethodUnavailable {
        /// The method asked for.
        method: String,
        /// Why not.
        reason: String,
    },
    /// The solve converged, but to another branch than the one asked for.
    #[error("wrong branch: requested {requested} load reversal(s) (0: convex, 1: flex), the solver converged to {found}")]
    WrongBranch {
        /// Load reversals (sign changes of the moment) of the branch asked for.
        requested: usize,
        /// What the solution is.
        found: crate::kind::ShapeKind,
    },
    /// The rod does not reach the surface: the solution connected to the pressed uniform rod
    /// would need the tip pulled up to height `eta` (`f < 0`), or it is not a proper rod.
    #[error("no contact: the rod does not reach the surface at eta = {eta} by itself ({found}, f = {f:.6e}); lower the surface or change the rest curvature")]
    NoContact {
        /// Surface height.
        eta: f64,
        /// The force the contact would need (negative: a pull).
        f: f64,
        /// What the solution is.
        found: crate::kind::ShapeKind,
    },
    /// No contact: the rod does not reach the surface or the object without being pulled.
    #[error("no contact: {what} (it reaches {reach:.6}, the contact needs {needed:.6})")]
    OutOfReach {
        /// What does not reach what, in words.
        what: String,
        /// How far the rod reaches (a height, a distance).
        reach: f64,
        /// How far it would have to reach.
        needed: f64,
    },
    /// There is no start for the scan: the rod does not reach the surface, or pressing it onto
    /// the surface does not end in a contact state (the reason says which, with its values).
    #[error("no start: {reason}")]
    NoStart {
        /// What happened, with the numbers.
        reason: String,
    },
    /// A curved surface gives the rod no quasi-static pressed start: pressed onto the surface's
    /// straight trend, the rod snaps as the surface's shape grows from that trend to its full
    /// amplitude (its equilibria fold back at the fraction `amplitude` of it), so no pressed
    /// state follows the shape there without a jump; nor does the other path tried, the shape
    /// grown at lighter presses and the rod pressed down onto it.
    #[error("the rod pressed onto the surface's straight trend snaps as the surface's shape grows to its full amplitude (its equilibria fold back at {:.2}% of it), and grown at lighter presses and pressed down onto it, it ends short too: on this surface it has no quasi-static pressed start", 100.0 * amplitude)]
    StartSnaps {
        /// Where the equilibria fold back: the fraction of the full amplitude (0 to 1).
        amplitude: f64,
    },
    /// A curved surface gives the rod no pressed start in the point-contact model: pressed onto
    /// the surface's straight trend, the rod begins to lie along a stretch of the surface near
    /// `s` as the surface's shape grows (at the fraction `amplitude` of its full amplitude): two
    /// of its contacts come within `spacing` of each other (of the rod's length 1), the rod
    /// between them following the surface, which point contacts do not resolve; the other path
    /// tried, the shape grown at lighter presses and the rod pressed down onto it, ends short
    /// too.
    #[error("the rod pressed onto the surface's straight trend lies down along the surface near s = {s:.6} as the surface's shape grows (at {:.2}% of its full amplitude two of its contacts come within {spacing:.2e} of each other, the rod between them following the surface): a rod lying along a stretch of the surface is not in the point-contact model, and grown at lighter presses and pressed down onto it, the rod ends short too: on this surface it has no pressed start", 100.0 * amplitude)]
    StartLies {
        /// Where it begins to lie: the fraction of the full amplitude (0 to 1).
        amplitude: f64,
        /// Where along the rod (the first of the close contacts).
        s: f64,
        /// How far apart the two contacts are along the rod.
        spacing: f64,
    },
    /// The BVP solver failed.
    #[error("{context}: {source}")]
    Solver {
        /// Which solve (target, d, homotopy step, ...).
        context: String,
        /// The solver's error.
        source: Box<bvp::BvpError>,
    },
    /// The closed forms failed (analytic method, or the initial guess).
    #[error("{context}: {source}")]
    Elastica {
        /// Which computation.
        context: String,
        /// The closed-form error.
        source: elastica::ElasticaError,
    },
    /// `infer`: the displacement is outside the measurable range.
    #[error("d0 = {d0} is outside the measurable range [0, {max}], which ends at {end}")]
    NotMeasurable {
        /// Offending displacement.
        d0: f64,
        /// Upper end of the range.
        max: f64,
        /// What ends the range.
        end: String,
    },
    /// `infer`: the scan reached `d_max` while `|μ|` still rose, so the measurable range is not
    /// known.
    #[error("d_max = {d_max} cuts the measurable range short (|mu| = {mu} is still rising there); {}", match full {
        Some((max, end)) => format!("the measurable range is [0, {max}], ending at {end}: raise d_max above {max}"),
        None => "raise d_max".to_string(),
    })]
    RangeCutShort {
        /// The scan's end.
        d_max: f64,
        /// `|μ|` there.
        mu: f64,
        /// The whole range's upper end and what ends it, from a scan to the largest `d_max`
        /// (`None` if that scan does not find it either).
        full: Option<(f64, String)>,
    },
    /// A computation did not reach its goal (continuation stalled, homotopy failed, ...).
    #[error("{what} failed: {reason}")]
    NoConvergence {
        /// What was computed.
        what: String,
        /// Why it stopped.
        reason: String,
    },
    /// A name (method, branch, ...) that is not one of the valid ones.
    #[error("invalid {name} '{value}': valid values are {valid}")]
    InvalidName {
        /// What was named.
        name: &'static str,
        /// The name given.
        value: String,
        /// The valid names.
        valid: &'static str,
    },
    /// Not implemented yet.
    #[error("not implemented: {0}")]
    NotImplemented(&'static str),
}

impl VibrissaError {
    /// Whether the error is the caller's to fix by changing the input: a value outside its
    /// range, a malformed table or name, a method this scene does not have, a displacement
    /// outside the measurable range, a surface or object the rod does not reach (and a closed
    /// form refused for its input). The others are failures of a computation on valid input.
    /// The program reports the first kind as bad input (exit 2), Python raises `InputError`.
    pub fn is_input(&self) -> bool {
        match self {
            VibrissaError::OutOfRange { .. }
            | VibrissaError::InvalidTable { .. }
            | VibrissaError::MethodUnavailable { .. }
            | VibrissaError::NotMeasurable { .. }
            | VibrissaError::RangeCutShort { .. }
            | VibrissaError::NoContact { .. }
            | VibrissaError::OutOfReach { .. }
            | VibrissaError::InvalidName { .. } => true,
            VibrissaError::Elastica { source, .. } => source.is_input(),
            _ => false,
        }
    }

    pub(crate) fn range(name: impl Into<String>, value: f64, range: impl Into<String>) -> Self {
        VibrissaError::OutOfRange {
            name: name.into(),
            value,
            range: range.into(),
        }
    }
    pub(crate) fn solver(context: impl Into<String>, source: bvp::BvpError) -> Self {
        VibrissaError::Solver {
            context: context.into(),
            source: Box::new(source),
        }
    }
    pub(crate) fn elastica(context: impl Into<String>, source: elastica::ElasticaError) -> Self {
        VibrissaError::Elastica {
            context: context.into(),
            source,
        }
    }
}
