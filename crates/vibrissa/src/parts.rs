//! The rod's parts as data — stiffness profile, rest curvature, physical dimensions — as a scene
//! file and the [`crate::Rod`] builder give them (validated by [`crate::Rod::new`]).
//!
//! In files the parts are tables tagged by `kind` (`{ kind = "uniform" }`, `{ kind = "taper",
//! ratio = 0.3 }`), and a kind refuses keys it does not have (`{ kind = "uniform", ratio = 0.5 }`
//! is an error, not a uniform rod). Serde ignores extra keys next to a unit variant, so the
//! file format goes through private mirrors whose valueless variants are empty structs.

use serde::{Deserialize, Serialize};

/// Reciprocal bending stiffness profile `b(s)` (`b = 1` at the base of a uniform rod).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(from = "StiffnessFile", into = "StiffnessFile")]
pub enum Stiffness {
    /// `b ≡ 1`.
    #[default]
    Uniform,
    /// Conical taper with tip/base radius ratio `ratio ∈ [MIN_TAPER, 1]` = `[0.01, 1]`
    /// ([`crate::MIN_TAPER`]): `b(s) = (1 − (1 − ratio)·s)^(−4)`.
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
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(from = "PrecurvatureFile", into = "PrecurvatureFile")]
pub enum Precurvature {
    /// Straight rest shape.
    #[default]
    None,
    /// `κ0(s) = k0 + k1·s` (constant when `k1 = 0`).
    Linear {
        /// Curvature at the base.
        k0: f64,
        /// Slope dκ0/ds (0 when a file leaves it out).
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

/// [`Stiffness`] as written in files (see the module docs).
#[derive(Clone, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
enum StiffnessFile {
    Uniform {},
    Taper { ratio: f64 },
    Table { s: Vec<f64>, b: Vec<f64> },
}

impl From<StiffnessFile> for Stiffness {
    fn from(f: StiffnessFile) -> Self {
        match f {
            StiffnessFile::Uniform {} => Stiffness::Uniform,
            StiffnessFile::Taper { ratio } => Stiffness::Taper { ratio },
            StiffnessFile::Table { s, b } => Stiffness::Table { s, b },
        }
    }
}

impl From<Stiffness> for StiffnessFile {
    fn from(f: Stiffness) -> Self {
        match f {
            Stiffness::Uniform => StiffnessFile::Uniform {},
            Stiffness::Taper { ratio } => StiffnessFile::Taper { ratio },
            Stiffness::Table { s, b } => StiffnessFile::Table { s, b },
        }
    }
}

/// [`Precurvature`] as written in files (see the module docs).
#[derive(Clone, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
enum PrecurvatureFile {
    None {},
    Linear {
        k0: f64,
        #[serde(default)]
        k1: f64,
    },
    Table {
        s: Vec<f64>,
        k: Vec<f64>,
    },
}

impl From<PrecurvatureFile> for Precurvature {
    fn from(f: PrecurvatureFile) -> Self {
        match f {
            PrecurvatureFile::None {} => Precurvature::None,
            PrecurvatureFile::Linear { k0, k1 } => Precurvature::Linear { k0, k1 },
            PrecurvatureFile::Table { s, k } => Precurvature::Table { s, k },
        }
    }
}

impl From<Precurvature> for PrecurvatureFile {
    fn from(f: Precurvature) -> Self {
        match f {
            Precurvature::None => PrecurvatureFile::None {},
            Precurvature::Linear { k0, k1 } => PrecurvatureFile::Linear { k0, k1 },
            Precurvature::Table { s, k } => PrecurvatureFile::Table { s, k },
        }
    }
}
