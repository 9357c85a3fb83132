//! The quasi-static stiction scan (paper §3) by pseudo-arclength continuation in the foot
//! displacement `d`, and its inverse.

use crate::solve::SolverConfig;
use crate::{Model, ShapePoint, VibrissaError};
use serde::Serialize;
use std::fmt;

/// Options of [`scan`].
#[derive(Clone, Debug, PartialEq, Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ScanOptions {
    /// Largest foot displacement. Default 0.5.
    pub d_max: f64,
    /// Output points, uniformly on `[0, d_max]` (both included). Default 201.
    pub points: usize,
    /// Slip threshold μ0: the scan stops where μ reaches it. Default none.
    pub mu0: Option<f64>,
    /// Solver settings.
    pub solver: SolverConfig,
    /// `Some(n)`: keep each output point's shape sampled at `n` points.
    pub keep_shapes: Option<usize>,
}

impl Default for ScanOptions {
    fn default() -> Self {
        ScanOptions {
            d_max: 0.5,
            points: 201,
            mu0: None,
            solver: SolverConfig::default(),
            keep_shapes: None,
        }
    }
}

impl ScanOptions {
    /// Checks: `d_max ∈ (0, 2)`, `points ∈ [2, 1e6]`, `mu0 ≥ 0` finite, `keep_shapes ≥ 2`.
    pub fn validate(&self) -> Result<(), VibrissaError> {
        if !(self.d_max > 0.0 && self.d_max < 2.0) {
            return Err(VibrissaError::range("d_max", self.d_max, "(0, 2)"));
        }
        if !(2..=1_000_000).contains(&self.points) {
            return Err(VibrissaError::range(
                "points",
                self.points as f64,
                "[2, 1000000]",
            ));
        }
        if let Some(mu0) = self.mu0 {
            if !(mu0.is_finite() && mu0 >= 0.0) {
                return Err(VibrissaError::range("mu0", mu0, "[0, inf)"));
            }
        }
        if let Some(n) = self.keep_shapes {
            if !(2..=100_000).contains(&n) {
                return Err(VibrissaError::range("keep_shapes", n as f64, "[2, 100000]"));
            }
        }
        self.solver.validate()
    }
}

/// One point of the scan.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ScanPoint {
    /// Foot displacement.
    pub d: f64,
    /// Friction ratio the contact must supply, `tan(β − α)` (β: surface angle; `tan(−α)` flat).
    pub mu: f64,
    /// Force angle.
    pub alpha: f64,
    /// Tip slope.
    pub phi1: f64,
    /// Force magnitude.
    pub f: f64,
    /// `f·sin α`.
    pub fx: f64,
    /// `−f·cos α`.
    pub fy: f64,
    /// `m(0)` (the paper's clamp moment is `−m(0)`).
    pub m_base: f64,
    /// Number of flex points.
    pub flex: usize,
    /// Arc length of the first flex point.
    pub s_flex: Option<f64>,
    /// Maximum of `y(s)`.
    pub y_max: f64,
}

/// Why a scan stopped.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "reason", rename_all = "snake_case")]
pub enum StopReason {
    /// `d_max` reached.
    DMax,
    /// μ reached μ0 at `d`: the tip slips.
    Slip {
        /// Displacement.
        d: f64,
        /// μ there (= μ0).
        mu: f64,
    },
    /// The rod crosses the surface at arc length `s` (`y(s) = η` with `s < 1`, or the tip
    /// slope turns downwards at `s = 1`).
    Penetration {
        /// Displacement.
        d: f64,
        /// Arc length of the touching point.
        s: f64,
        /// Its height.
        y: f64,
    },
    /// `d` has a maximum along the solution curve: snap-through.
    FoldInD {
        /// Displacement at the fold.
        d: f64,
    },
    /// The solver failed.
    SolverFailure {
        /// Last displacement reached.
        d: f64,
        /// Diagnostics.
        message: String,
    },
}

impl fmt::Display for StopReason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            StopReason::DMax => write!(f, "d_max reached"),
            StopReason::Slip { d, mu } => write!(f, "slip at d = {d} (mu = {mu})"),
            StopReason::Penetration { d, s, y } => {
                write!(f, "penetration at d = {d} (s = {s}, y = {y})")
            }
            StopReason::FoldInD { d } => write!(f, "fold in d (snap-through) at d = {d}"),
            StopReason::SolverFailure { d, message } => {
                write!(f, "solver failure after d = {d}: {message}")
            }
        }
    }
}

/// Result of [`scan`].
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ScanResult {
    /// Surface height.
    pub eta: f64,
    /// The starting rod (d = 0).
    pub start: ScanPoint,
    /// Points at the requested displacements, up to where the scan stopped.
    pub points: Vec<ScanPoint>,
    /// Largest μ over the scan (located by a 1-D search, not the grid maximum).
    pub mu_max: f64,
    /// The d where it occurs: the upper end of the measurable range.
    pub d_at_mu_max: f64,
    /// Why the scan stopped.
    pub stop: StopReason,
    /// Accumulated solver statistics.
    pub stats: bvp::Stats,
    /// Shapes of the output points (if `keep_shapes`).
    pub shapes: Vec<Vec<ShapePoint>>,
}

/// Result of [`infer`].
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Inference {
    /// The stiction coefficient μ0 = μ(d0).
    pub mu0: f64,
    /// The displacement at which the tip slipped.
    pub d0: f64,
    /// The measurable range `[0, d at μ_max]`.
    pub measurable_d: (f64, f64),
    /// μ_max.
    pub mu_max: f64,
}

/// Runs the stiction scan. Errors only for invalid input or when it cannot even start;
/// failures along the way end the scan with [`StopReason::SolverFailure`].
pub fn scan(model: &Model, opts: &ScanOptions) -> Result<ScanResult, VibrissaError> {
    opts.validate()?;
    let _ = model;
    Err(VibrissaError::NotImplemented("scan"))
}

/// Infers μ0 from the displacement `d0` at which the tip slipped.
pub fn infer(model: &Model, d0: f64, opts: &ScanOptions) -> Result<Inference, VibrissaError> {
    opts.validate()?;
    let _ = (model, d0);
    Err(VibrissaError::NotImplemented("infer"))
}
