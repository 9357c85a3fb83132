//! The vibrissa model: an elastic rod with optional taper, pre-curvature and compliant support,
//! pressed with its tip on a surface, and the quasi-static stiction scan.
//!
//! (skeleton: to be implemented — see issue #4)
#![warn(missing_docs)]

pub mod scene;

pub use scene::{Physical, Precurvature, Scene, Stiffness};
