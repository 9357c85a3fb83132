//! The scene file: rod stiffness profile, pre-curvature, support, surface, physical units — the
//! format of `vibrissa --scene FILE.toml` and of the command-line flags. The library itself works
//! on its parts, [`Scene::rod`] and [`Scene::surface`].
//!
//! Every `kind` refuses keys it does not have (`{ kind = "uniform", ratio = 0.5 }` is an error,
//! not a uniform rod): the variants without values are empty structs for that reason. All lengths are normalized by the rod length L, forces by EI_base/L²,
//! moments by EI_base/L, unless stated otherwise.

use crate::rod::{Rod, Surface};
use crate::VibrissaError;
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

/// A whole scene. Defaults: uniform clamped straight rod, horizontal surface at `eta = 0.75`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Scene {
    /// Height of the surface above the foot, in rod lengths; `eta ∈ (η_, 1)`, η_ ≈ 0.45695.
    pub eta: f64,
    /// Stiffness profile.
    pub stiffness: Stiffness,
    /// Pre-curvature.
    pub precurvature: Precurvature,
    /// Compliance `c ≥ 0` of the rotational spring at the foot: `φ(0) = π/2 + c·m(0)`; 0 is a clamp.
    pub support_compliance: f64,
    /// Inclination of the surface line through the contact point, radians (0 = horizontal).
    pub surface_angle: f64,
    /// Optional physical dimensions.
    pub physical: Option<Physical>,
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

impl Default for Scene {
    fn default() -> Self {
        Scene {
            eta: 0.75,
            stiffness: Stiffness::Uniform {},
            precurvature: Precurvature::None {},
            support_compliance: 0.0,
            surface_angle: 0.0,
            physical: None,
        }
    }
}

impl Scene {
    /// The rod of the scene (stiffness, rest curvature, support, physical dimensions), validated.
    pub fn rod(&self) -> Result<Rod, VibrissaError> {
        Rod::new(
            self.stiffness.clone(),
            self.precurvature.clone(),
            self.support_compliance,
            self.physical.clone(),
        )
    }

    /// The surface of the scene (height and inclination), validated.
    pub fn surface(&self) -> Result<Surface, VibrissaError> {
        Surface::new(self.eta, self.surface_angle)
    }

    /// Both parts, validated: `(rod, surface)`.
    pub fn parts(&self) -> Result<(Rod, Surface), VibrissaError> {
        Ok((self.rod()?, self.surface()?))
    }

    /// Checks every value (see [`Rod::new`] and [`Surface::new`]); the error names the value and
    /// its valid range.
    pub fn validate(&self) -> Result<(), VibrissaError> {
        self.surface()?;
        self.rod().map(|_| ())
    }
}
