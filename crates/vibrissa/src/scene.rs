//! The scene file: rod stiffness profile, pre-curvature, support, surface, physical units — the
//! format of `vibrissa --scene FILE.toml` and of the command-line flags. The library itself works
//! on its parts, [`Scene::rod`] and [`Scene::surface`].
//!
//! Every `kind` refuses keys it does not have (`{ kind = "uniform", ratio = 0.5 }` is an error,
//! not a uniform rod; see [`Stiffness`]). Lengths are normalized by the rod length L, forces by EI_base/L², moments by
//! EI_base/L, unless stated otherwise.

pub use crate::parts::{Physical, Precurvature, Stiffness};
use crate::rod::{Rod, Surface};
use crate::VibrissaError;
use serde::{Deserialize, Serialize};

/// A whole scene. Defaults: uniform clamped straight rod, horizontal surface at `eta = 0.75`.
///
/// ```
/// use vibrissa::{Scene, Stiffness};
///
/// let scene: Scene = toml::from_str("eta = 0.8\nstiffness = { kind = \"taper\", ratio = 0.5 }")?;
/// assert_eq!(scene.stiffness, Stiffness::Taper { ratio: 0.5 });
/// let (rod, surface) = scene.parts()?;
/// assert_eq!(surface.eta(), 0.8);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
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
    /// Where the rod may touch the surface: `anywhere` (default) or the `tip` alone (the
    /// paper's model).
    pub contact: crate::ContactModel,
    /// The state a scan starts from: `pressed` (default) or `connected`.
    pub start: crate::StartKind,
    /// The surface's shape: `line` (default), `sine`, `circle`, `table`, `sines`, `grating`,
    /// `measured` (module [`crate::surface`]).
    pub surface: crate::surface::SurfaceProfile,
    /// The friction along the surface: `none` (default: the command's coefficients), `uniform`,
    /// `table`, `patches`.
    pub friction: crate::surface::FrictionProfile,
    /// Radius of the round tip, a rigid disk centred at the rod's end (rod lengths; default 0,
    /// the point tip; range [`crate::limits::TIP_RADIUS`]). A round tip takes surface slopes up
    /// to 80°.
    #[serde(skip_serializing_if = "is_zero")]
    pub tip_radius: f64,
}

/// Whether a value is 0 (a default the scene file leaves out).
fn is_zero(v: &f64) -> bool {
    *v == 0.0
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
            contact: crate::ContactModel::Anywhere,
            start: crate::StartKind::Pressed,
            surface: Default::default(),
            friction: Default::default(),
            tip_radius: 0.0,
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
        )?
        .with_tip_radius(self.tip_radius)
    }

    /// The surface of the scene (height, inclination, profile and friction), validated.
    pub fn surface(&self) -> Result<Surface, VibrissaError> {
        Surface::new(self.eta, self.surface_angle)?
            .with_profile_for_tip(&self.surface, self.tip_radius)?
            .with_friction(&self.friction)
    }

    /// Both parts, validated: `(rod, surface)`.
    pub fn parts(&self) -> Result<(Rod, Surface), VibrissaError> {
        Ok((self.rod()?, self.surface()?))
    }

    /// Checks every value (see [`Rod::new`] and [`Surface::new`]); the error names the value and
    /// its valid range.
    pub fn validate(&self) -> Result<(), VibrissaError> {
        let surface = self.surface()?;
        let rod = self.rod()?;
        surface.check_tip(rod.tip_radius())
    }
}

/// A deserializer's message about a scene in the words of the file format: serde names Rust
/// types (``invalid type: integer `3`, expected internally tagged enum StiffnessFile``); this names
/// the tables and values a file has instead (`expected a stiffness table such as
/// { kind = "uniform" }, ...`). Messages without such words are returned unchanged.
///
/// ```
/// let m = vibrissa::scene::plain_message("invalid type: integer `3`, expected internally tagged enum StiffnessFile");
/// assert_eq!(m, "invalid type: integer `3`, expected a stiffness table: { kind = \"uniform\" }, { kind = \"taper\", ratio = RHO } or { kind = \"table\", s = [...], b = [...] }");
/// ```
pub fn plain_message(msg: &str) -> String {
    const WORDS: [(&str, &str); 8] = [
        (
            "internally tagged enum StiffnessFile",
            "a stiffness table: { kind = \"uniform\" }, { kind = \"taper\", ratio = RHO } or { kind = \"table\", s = [...], b = [...] }",
        ),
        (
            "internally tagged enum PrecurvatureFile",
            "a precurvature table: { kind = \"none\" }, { kind = \"linear\", k0 = K0, k1 = K1 } or { kind = \"table\", s = [...], k = [...] }",
        ),
        (
            "struct Physical",
            "a [physical] table with length_mm, youngs_modulus_gpa, base_diameter_um",
        ),
        ("struct Scene", "a table of scene keys"),
        ("expected f64", "expected a number"),
        ("expected a sequence", "expected an array of numbers"),
        ("missing field `kind`", "missing key `kind` (the table's kind: uniform, taper or table for stiffness; none, linear or table for precurvature)"),
        ("missing field", "missing key"),
    ];
    let mut m = msg.to_string();
    for (serde, file) in WORDS {
        if m.contains(serde) {
            m = m.replace(serde, file);
        }
    }
    m.replace(
        ", there are no fields",
        " (this kind has no key but `kind`)",
    )
    .replace("unknown field", "unknown key")
    .replace("unknown variant", "unknown kind")
}
