//! The scene: rod stiffness profile, pre-curvature, support, surface, physical units.
//!
//! The same fields are read from a TOML scene file (`vibrissa --scene FILE.toml`) and set by
//! command-line flags. All lengths are normalized by the rod length L, forces by EI_base/L²,
//! moments by EI_base/L, unless stated otherwise.

use serde::{Deserialize, Serialize};

/// Reciprocal bending stiffness profile `b(s)` (`b = 1` at the base of a uniform rod).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, Default)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Stiffness {
    /// `b ≡ 1`.
    #[default]
    Uniform,
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
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, Default)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Precurvature {
    /// Straight rest shape.
    #[default]
    None,
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

impl Default for Scene {
    fn default() -> Self {
        Scene {
            eta: 0.75,
            stiffness: Stiffness::Uniform,
            precurvature: Precurvature::None,
            support_compliance: 0.0,
            surface_angle: 0.0,
            physical: None,
        }
    }
}

use crate::VibrissaError;

fn finite(name: &str, v: f64) -> Result<(), VibrissaError> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(VibrissaError::range(name, v, "(finite numbers)"))
    }
}

/// Checks a piecewise-linear table: equal lengths >= 2, finite, `s` strictly increasing from 0 to 1.
fn check_table(name: &str, s: &[f64], v: &[f64], positive: bool) -> Result<(), VibrissaError> {
    let bad = |reason: String| VibrissaError::InvalidTable {
        name: name.to_string(),
        reason,
    };
    if s.len() != v.len() {
        return Err(bad(format!(
            "s has {} entries but the values have {}; they must have the same length",
            s.len(),
            v.len()
        )));
    }
    if s.len() < 2 {
        return Err(bad(format!(
            "{} entries; at least 2 are needed to cover [0, 1]",
            s.len()
        )));
    }
    for (i, (&si, &vi)) in s.iter().zip(v).enumerate() {
        if !si.is_finite() || !vi.is_finite() {
            return Err(bad(format!(
                "entry {i} (s = {si}, value = {vi}) is not finite"
            )));
        }
        if positive && vi <= 0.0 {
            return Err(bad(format!(
                "value {vi} at s = {si} (entry {i}) must be > 0 (valid range (0, inf))"
            )));
        }
        if i > 0 && si <= s[i - 1] {
            return Err(bad(format!(
                "s must be strictly increasing: s[{i}] = {si} <= s[{}] = {}",
                i - 1,
                s[i - 1]
            )));
        }
    }
    let (s0, s1) = (s[0], s[s.len() - 1]);
    if s0 > 0.0 || s1 < 1.0 {
        return Err(bad(format!(
            "s covers [{s0}, {s1}] but must cover [0, 1] (first entry <= 0, last >= 1)"
        )));
    }
    Ok(())
}

impl Scene {
    /// Checks every value; the error names the value and its valid range.
    pub fn validate(&self) -> Result<(), VibrissaError> {
        let (_, eta_low) = elastica::lower_limit();
        if !(self.eta > eta_low && self.eta < 1.0) {
            return Err(VibrissaError::range(
                "eta",
                self.eta,
                format!("({eta_low:.8}, 1) = (eta_, 1)"),
            ));
        }
        match &self.stiffness {
            Stiffness::Uniform => {}
            Stiffness::Taper { ratio } => {
                if !(*ratio > 0.0 && *ratio <= 1.0) {
                    return Err(VibrissaError::range("stiffness.ratio", *ratio, "(0, 1]"));
                }
            }
            Stiffness::Table { s, b } => check_table("stiffness", s, b, true)?,
        }
        match &self.precurvature {
            Precurvature::None => {}
            Precurvature::Linear { k0, k1 } => {
                finite("precurvature.k0", *k0)?;
                finite("precurvature.k1", *k1)?;
            }
            Precurvature::Table { s, k } => check_table("precurvature", s, k, false)?,
        }
        let c = self.support_compliance;
        if !(c.is_finite() && c >= 0.0) {
            return Err(VibrissaError::range("support_compliance", c, "[0, inf)"));
        }
        let beta = self.surface_angle;
        if !(beta.is_finite() && beta.abs() < std::f64::consts::FRAC_PI_4) {
            return Err(VibrissaError::range(
                "surface_angle",
                beta,
                "(-pi/4, pi/4) radians",
            ));
        }
        if let Some(p) = &self.physical {
            for (name, v) in [
                ("physical.length_mm", p.length_mm),
                ("physical.youngs_modulus_gpa", p.youngs_modulus_gpa),
                ("physical.base_diameter_um", p.base_diameter_um),
            ] {
                if !(v.is_finite() && v > 0.0) {
                    return Err(VibrissaError::range(name, v, "(0, inf)"));
                }
            }
        }
        Ok(())
    }

    /// True for the paper's scene: uniform, straight, clamped rod, horizontal surface.
    pub fn is_paper_scene(&self) -> bool {
        crate::profile::is_uniform(&self.stiffness, &self.precurvature)
            && self.support_compliance == 0.0
            && self.surface_angle == 0.0
    }
}
