//! What a solved rod is: its branch (load reversals) or why it is no proper rod.

use serde::Serialize;
use std::fmt;

/// What a solved rod is, in the terms of [`crate::BranchChoice`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum ShapeKind {
    /// `load_reversals` sign changes of the moment, a proper tip load (f ≥ 0), no loop.
    Regular {
        /// Sign changes of `m(s)` on `[0, 1)`.
        load_reversals: usize,
    },
    /// The slope turns through more than a full turn.
    Looping,
    /// The tip is pulled (f < 0).
    Pulled,
    /// The solution is not finite.
    NonFinite,
}

impl fmt::Display for ShapeKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ShapeKind::Regular { load_reversals: 0 } => f.write_str("convex (no load reversal)"),
            ShapeKind::Regular { load_reversals: 1 } => f.write_str("flex (one load reversal)"),
            ShapeKind::Regular { load_reversals: n } => write!(f, "{n} load reversals"),
            ShapeKind::Looping => f.write_str("a looping rod (slope range over 2 pi)"),
            ShapeKind::Pulled => f.write_str("a rod pulled at the tip (f < 0)"),
            ShapeKind::NonFinite => f.write_str("a non-finite solution"),
        }
    }
}
