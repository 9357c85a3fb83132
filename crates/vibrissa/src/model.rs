//! A validated scene ready to solve, and its physical units.

use crate::profile::{is_uniform, General};
use crate::scene::Scene;
use crate::VibrissaError;

/// Physical units of a scene with [`crate::Physical`] dimensions.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Units {
    /// Force unit `E·I/L²` in N (`I = π d⁴/64` at the base).
    pub force_n: f64,
    /// Moment unit `E·I/L` in N·m.
    pub moment_nm: f64,
    /// Length unit `L` in mm.
    pub length_mm: f64,
}

/// A validated scene, ready to solve.
#[derive(Clone, Debug, PartialEq)]
pub struct Model {
    scene: Scene,
    paper: bool,
    uniform_profile: bool,
}

impl Model {
    /// Validates `scene` (see [`Scene::validate`]).
    pub fn new(scene: &Scene) -> Result<Model, VibrissaError> {
        scene.validate()?;
        let uniform_profile = is_uniform(&scene.stiffness, &scene.precurvature);
        Ok(Model {
            scene: scene.clone(),
            paper: scene.is_paper_scene(),
            uniform_profile,
        })
    }
    /// The scene.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }
    /// True for the paper's scene (uniform, straight, clamped, horizontal surface), where the
    /// closed forms of crate `elastica` apply and [`crate::Method::Analytic`] is allowed.
    pub fn is_paper_scene(&self) -> bool {
        self.paper
    }
    /// True when `b ≡ 1` and `κ0 ≡ 0` (compliance and surface angle may still be set).
    pub fn has_uniform_profile(&self) -> bool {
        self.uniform_profile
    }
    /// The profile at homotopy amplitude `t` (1: the scene).
    pub fn profile(&self, t: f64) -> General {
        General::new(&self.scene, t)
    }
    /// Physical units, if the scene has physical dimensions.
    pub fn units(&self) -> Option<Units> {
        let p = self.scene.physical.as_ref()?;
        let l = p.length_mm * 1e-3;
        let d = p.base_diameter_um * 1e-6;
        let e = p.youngs_modulus_gpa * 1e9;
        let i = std::f64::consts::PI * d.powi(4) / 64.0;
        Some(Units {
            force_n: e * i / (l * l),
            moment_nm: e * i / l,
            length_mm: p.length_mm,
        })
    }
}
