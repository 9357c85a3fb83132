//! The rod's parts as data — stiffness profile, rest curvature, physical dimensions — as a scene
//! file and the [`crate::Rod`] builder give them (validated by [`crate::Rod::new`]).

use serde::{Deserialize, Serialize};

/// Reciprocal bending stiffness profile `b(s)` (`b = 1` at the base of a uniform rod).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Stiffness {
    /// `b ≡ 1`.
    Uniform {},
    /// Conical taper with tip/base radius ratio `ratio ∈ (0, 1]`: `b(s) = (1 − (1 − ratio)·s)^(−4)`.
    Taper {
        /// Tip/base radius ratio ρ.
        ratio: f64,
    },
    /// Tabulated `b` at increasing `s` (piecewise-linear interpolation; must cover [0, 1]).
    Table {
        /// Arc-length abscissae, strictly increasing, from 0 to 1.
        s: Vec<f64>,
        /// Values of `b > 0`.
        b: Vec<f64>,
    },
}

/// Pre-curvature (rest curvature) `κ0(s)`; positive bends the rest shape to the left (counter-clockwise).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Precurvature {
    /// Straight rest shape.
    None {},
    /// `κ0(s) = k0 + k1·s` (constant when `k1 = 0`).
    Linear {
        /// Curvature at the base.
        k0: f64,
        /// Slope dκ0/ds.
        #[serde(default)]
        k1: f64,
    },
    /// Tabulated `κ0` at increasing `s` (piecewise-linear).
    Table {
        /// Arc-length abscissae, strictly increasing, from 0 to 1.
        s: Vec<f64>,
        /// Values of κ0.
        k: Vec<f64>,
    },
}

/// Physical dimensions, to report results in N, N·m and mm as well as normalized.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Physical {
    /// Rod length L in mm.
    pub length_mm: f64,
    /// Young's modulus E in GPa.
    pub youngs_modulus_gpa: f64,
    /// Base diameter in µm (second moment of area I = π d⁴ / 64 at the base).
    pub base_diameter_um: f64,
}

impl Default for Stiffness {
    fn default() -> Self {
        Stiffness::Uniform {}
    }
}

impl Default for Precurvature {
    fn default() -> Self {
        Precurvature::None {}
    }
}
