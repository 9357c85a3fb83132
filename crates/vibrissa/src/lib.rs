//! The vibrissa model: an elastic rod with optional taper, pre-curvature and compliant support,
//! pressed with its tip on a surface, and the quasi-static stiction scan.
#![warn(missing_docs)]

mod analytic;
mod error;
mod fast;
pub mod model;
pub mod scan;
pub mod scene;
pub mod solve;

pub use error::VibrissaError;
pub use model::{Model, Units};
pub use scan::{infer, scan, scan_at, Inference, ScanOptions, ScanPoint, ScanResult, StopReason};
pub use scene::{Physical, Precurvature, Scene, Stiffness};
pub use solve::{solve, BranchChoice, Method, Shape, ShapePoint, SolverConfig, Target};
