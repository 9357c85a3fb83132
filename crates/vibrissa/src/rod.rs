//! The rod (stiffness profile, rest curvature, support; no surface) and the surface its tip
//! touches, each validated once; physical units.

use crate::limits::{self, Range};
use crate::parts::{Physical, Precurvature, Stiffness};
use crate::profile::General;
use crate::VibrissaError;
use std::sync::Arc;

/// Physical units of a rod with [`Physical`] dimensions.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Units {
    /// Force unit `E·I/L²` in N (`I = π d⁴/64` at the base).
    pub force_n: f64,
    /// Moment unit `E·I/L` in N·m.
    pub moment_nm: f64,
    /// Length unit `L` in mm.
    pub length_mm: f64,
}

/// Largest rest curvature `|κ0(s)|` (1/L): 3 already bends the rest shape through 172°; whiskers
/// have `|κ0| < 2`. More curled rods touch a surface above them only when pulled, or start on
/// branches that pressing cannot reach.
pub const MAX_PRECURVATURE: f64 = limits::PRECURVATURE.hi;
/// Largest support compliance `c` (L/EI): with `c = 1000` the foot turns a thousand times more
/// than the rod bends, a hinge for every purpose (μ_max within 0.2 % of `c = 10⁴`).
pub const MAX_COMPLIANCE: f64 = limits::SUPPORT_COMPLIANCE.hi;
/// Smallest taper ratio ρ (tip/base radius): the tip is `ρ⁻⁴ = 10⁸` times more flexible than the
/// foot; real whiskers have 0.02–0.2.
pub const MIN_TAPER: f64 = limits::TAPER.lo;
/// Range `[MIN_B, MAX_B]` of a tabulated reciprocal stiffness `b` (relative to the foot).
pub const MIN_B: f64 = limits::TABLE_B.lo;
/// See [`MIN_B`].
pub const MAX_B: f64 = limits::TABLE_B.hi;
/// Largest surface inclination `|β|` (rad, exclusive).
pub const MAX_SURFACE_ANGLE: f64 = limits::SURFACE_ANGLE.hi;

/// A validated rod: reciprocal bending stiffness `b(s)`, rest curvature `κ0(s)`, support
/// compliance `c` (`φ(0) = π/2 + c·m(0)`; 0 is a clamp), optional physical dimensions. It carries
/// no surface ([`Surface`] belongs to the scan and the tip-height solve).
///
/// ```
/// use vibrissa::Rod;
/// let whisker = Rod::builder()
///     .taper(0.3)
///     .precurvature(-0.5, 0.2)
///     .support_compliance(0.1)
///     .build()?;
/// assert!(!whisker.is_uniform_clamped());
/// assert!(Rod::uniform().is_uniform_clamped());
/// # Ok::<(), vibrissa::VibrissaError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Rod {
    stiffness: Stiffness,
    precurvature: Precurvature,
    compliance: f64,
    physical: Option<Physical>,
    uniform_profile: bool,
    tip_radius: f64,
}

/// Builder of a [`Rod`]; every setting defaults to the uniform, straight, clamped rod.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RodBuilder {
    stiffness: Stiffness,
    precurvature: Precurvature,
    compliance: f64,
    physical: Option<Physical>,
    tip_radius: f64,
}

impl RodBuilder {
    /// Conical taper with tip/base radius ratio `ratio ∈ [MIN_TAPER, 1]`: `b = (1 − (1 − ρ)s)⁻⁴`.
    pub fn taper(mut self, ratio: f64) -> Self {
        self.stiffness = Stiffness::Taper { ratio };
        self
    }
    /// Any stiffness profile.
    pub fn stiffness(mut self, stiffness: Stiffness) -> Self {
        self.stiffness = stiffness;
        self
    }
    /// Linear rest curvature `κ0(s) = k0 + k1·s` (1/L; positive bends the rest shape left).
    pub fn precurvature(mut self, k0: f64, k1: f64) -> Self {
        self.precurvature = Precurvature::Linear { k0, k1 };
        self
    }
    /// Any rest-curvature profile.
    pub fn precurvature_profile(mut self, precurvature: Precurvature) -> Self {
        self.precurvature = precurvature;
        self
    }
    /// Compliance `c ≥ 0` of the rotational spring at the foot.
    pub fn support_compliance(mut self, c: f64) -> Self {
        self.compliance = c;
        self
    }
    /// Physical dimensions (results also in N, N·m, mm).
    pub fn physical(mut self, physical: Physical) -> Self {
        self.physical = Some(physical);
        self
    }
    /// A round tip: the rod's end carries a rigid disk of radius `r ∈` [`limits::TIP_RADIUS`]
    /// centred at its end point (default 0, the point tip).
    pub fn tip_radius(mut self, r: f64) -> Self {
        self.tip_radius = r;
        self
    }
    /// Validates and builds; the error names the value and its valid range.
    pub fn build(self) -> Result<Rod, VibrissaError> {
        Rod::new(
            self.stiffness,
            self.precurvature,
            self.compliance,
            self.physical,
        )?
        .with_tip_radius(self.tip_radius)
    }
}

/// Checks a piecewise-linear table: equal lengths ≥ 2, finite, `s` strictly increasing, covering
/// `[0, 1]`; values in `valid`.
fn check_table(name: &str, s: &[f64], v: &[f64], valid: &Range) -> Result<(), VibrissaError> {
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
        if !valid.contains(vi) {
            let unit = match valid.unit {
                "" => String::new(),
                u => format!(" ({u})"),
            };
            return Err(bad(format!(
                "value {vi} at s = {si} (entry {i}) is outside the valid range {}{unit}",
                valid.text(6)
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

impl Rod {
    /// The uniform, straight, clamped rod (the paper's).
    pub fn uniform() -> Rod {
        Rod {
            stiffness: Stiffness::Uniform,
            precurvature: Precurvature::None,
            compliance: 0.0,
            physical: None,
            uniform_profile: true,
            tip_radius: 0.0,
        }
    }

    /// A builder starting from the uniform, straight, clamped rod.
    pub fn builder() -> RodBuilder {
        RodBuilder::default()
    }

    /// Validates the parts of a rod: taper ratio in `[MIN_TAPER, 1]`, tabulated `b` in
    /// `[MIN_B, MAX_B]`, `|κ0| ≤ MAX_PRECURVATURE`, `c ∈ [0, MAX_COMPLIANCE]`, physical
    /// dimensions positive with finite units.
    pub fn new(
        stiffness: Stiffness,
        precurvature: Precurvature,
        support_compliance: f64,
        physical: Option<Physical>,
    ) -> Result<Rod, VibrissaError> {
        match &stiffness {
            Stiffness::Uniform => {}
            Stiffness::Taper { ratio } => limits::TAPER.check("taper ratio", *ratio)?,
            Stiffness::Table { s, b } => check_table("stiffness", s, b, &limits::TABLE_B)?,
        }
        match &precurvature {
            Precurvature::None => {}
            Precurvature::Linear { k0, k1 } => {
                limits::PRECURVATURE.check("precurvature k0", *k0)?;
                limits::PRECURVATURE.check("precurvature k0 + k1", k0 + k1)?;
            }
            Precurvature::Table { s, k } => {
                check_table("precurvature", s, k, &limits::PRECURVATURE)?
            }
        }
        let c = support_compliance;
        limits::SUPPORT_COMPLIANCE.check("support compliance", c)?;
        if let Some(p) = &physical {
            for (name, v) in [
                ("length_mm", p.length_mm),
                ("youngs_modulus_gpa", p.youngs_modulus_gpa),
                ("base_diameter_um", p.base_diameter_um),
            ] {
                limits::PHYSICAL.check(name, v)?;
            }
        }
        let uniform_profile = crate::profile::is_uniform(&stiffness, &precurvature);
        let rod = Rod {
            stiffness,
            precurvature,
            compliance: c,
            physical,
            uniform_profile,
            tip_radius: 0.0,
        };
        if let Some(u) = rod.units() {
            for (name, v) in [
                ("force unit EI/L^2 (N)", u.force_n),
                ("moment unit EI/L (N m)", u.moment_nm),
            ] {
                limits::UNIT
                    .unit("the physical dimensions over- or underflow")
                    .check(name, v)?;
            }
        }
        Ok(rod)
    }

    /// The stiffness profile.
    pub fn stiffness(&self) -> &Stiffness {
        &self.stiffness
    }
    /// The rest-curvature profile.
    pub fn precurvature(&self) -> &Precurvature {
        &self.precurvature
    }
    /// Support compliance `c`.
    pub fn support_compliance(&self) -> f64 {
        self.compliance
    }
    /// The rod with a round tip of radius `r` (a rigid disk centred at the rod's end point,
    /// turning with it; 0: the point tip); `r` must lie in [`limits::TIP_RADIUS`].
    pub fn with_tip_radius(self, r: f64) -> Result<Rod, VibrissaError> {
        limits::TIP_RADIUS.check("tip radius", r)?;
        Ok(Rod {
            tip_radius: r,
            ..self
        })
    }
    /// The radius of the round tip (0: a point tip).
    pub fn tip_radius(&self) -> f64 {
        self.tip_radius
    }
    /// Physical dimensions, if any.
    pub fn physical(&self) -> Option<&Physical> {
        self.physical.as_ref()
    }
    /// True when `b ≡ 1` and `κ0 ≡ 0` (the support may still be compliant).
    pub fn has_uniform_profile(&self) -> bool {
        self.uniform_profile
    }
    /// The paper's rod: uniform, straight and clamped, where the closed forms of crate
    /// `elastica` hold (the one test of "paper's rod" in the workspace).
    pub fn is_uniform_clamped(&self) -> bool {
        self.uniform_profile && self.compliance == 0.0
    }
    /// The profile at homotopy amplitude `t` (1: the rod itself).
    pub fn profile(&self, t: f64) -> General {
        General::new(&self.stiffness, &self.precurvature, t)
    }
    /// Physical units, if the rod has physical dimensions.
    pub fn units(&self) -> Option<Units> {
        let p = self.physical.as_ref()?;
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

/// The surface the tip touches: the height `eta` of the contact point above the foot (in rod
/// lengths) and the inclination `angle` β of the surface line (rad, 0 = horizontal).
///
/// A curved profile and a friction texture are held by shared ownership: every contact and
/// march that refers to them holds a count, and the memory goes with the last one (a fit or a
/// sweep that tries 10⁵ surfaces does not keep them).
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Surface {
    eta: f64,
    angle: f64,
    /// A curved profile (none: the straight line through the contact point).
    #[serde(skip_serializing_if = "Option::is_none")]
    profile: Option<Arc<crate::surface::Height>>,
    /// A friction profile.
    #[serde(skip_serializing_if = "Option::is_none")]
    texture: Option<Arc<crate::surface::Texture>>,
}

impl Surface {
    /// A surface at height `eta ∈ (η_, 1)` (η_ ≈ 0.456947, the lowest height at which the uniform
    /// rod's start touches with its tip) inclined by `angle ∈ (−π/4, π/4)`.
    ///
    /// ```
    /// let s = vibrissa::Surface::new(0.8, -0.1)?;
    /// assert_eq!((s.eta(), s.angle()), (0.8, -0.1));
    /// assert!(vibrissa::Surface::new(0.3, 0.0).is_err()); // below eta_
    /// # Ok::<(), vibrissa::VibrissaError>(())
    /// ```
    pub fn new(eta: f64, angle: f64) -> Result<Surface, VibrissaError> {
        limits::eta().check("eta", eta)?;
        limits::SURFACE_ANGLE.check("surface angle", angle)?;
        Ok(Surface {
            eta,
            angle,
            profile: None,
            texture: None,
        })
    }
    /// `Ok` when the lab `x` of a start's contact lies where the surface exists (a circle
    /// between its 45° points, a table between its ends); else an error naming the surface's
    /// ends (issue 33: a circle whose lowest point is far from the pressed tip was replaced by
    /// its end tangent without a word, and the drag marched minutes on it).
    pub fn check_on(&self, x: f64) -> Result<(), VibrissaError> {
        let Some(h) = self.profile() else {
            return Ok(());
        };
        if h.covers(x) {
            return Ok(());
        }
        let (lo, hi) = h.domain();
        Err(VibrissaError::OutOfRange {
            name: "the start's contact point x".into(),
            value: x,
            range: format!(
                "[{lo}, {hi}], where the surface exists (a circle ends where its slope reaches 45 \
                 degrees, a table at its ends): move the surface under the pressed tip (a \
                 circle's x0, a table's x)"
            ),
        })
    }
    /// A horizontal surface at height `eta`.
    pub fn flat(eta: f64) -> Result<Surface, VibrissaError> {
        Surface::new(eta, 0.0)
    }
    /// Height of the contact point.
    pub fn eta(&self) -> f64 {
        self.eta
    }
    /// Inclination β.
    pub fn angle(&self) -> f64 {
        self.angle
    }
    /// The surface with the height profile `p` (heights relative to `eta`, plus the inclination;
    /// see [`crate::surface`]); errors name the scene key.
    pub fn with_profile(
        self,
        p: &crate::surface::SurfaceProfile,
    ) -> Result<Surface, VibrissaError> {
        self.with_profile_for_tip(p, 0.0)
    }
    /// The surface with the height profile `p` for a tip of radius `tip_radius` (a round tip
    /// takes slopes up to 80°, [`crate::surface::Height::for_tip`]); errors name the scene key.
    pub fn with_profile_for_tip(
        self,
        p: &crate::surface::SurfaceProfile,
        tip_radius: f64,
    ) -> Result<Surface, VibrissaError> {
        let profile =
            crate::surface::Height::for_tip(p, self.eta, self.angle, tip_radius)?.map(Arc::new);
        Ok(Surface { profile, ..self })
    }
    /// `Ok` when a tip of radius `tip_radius` may touch this surface
    /// ([`crate::surface::Height::check_tip`]; a line takes any tip).
    pub fn check_tip(&self, tip_radius: f64) -> Result<(), VibrissaError> {
        match self.profile() {
            Some(h) => h.check_tip(tip_radius),
            None => Ok(()),
        }
    }
    /// The surface with the friction profile `f` (see [`crate::surface`]).
    pub fn with_friction(
        self,
        f: &crate::surface::FrictionProfile,
    ) -> Result<Surface, VibrissaError> {
        let texture = crate::surface::Texture::new(f)?.map(Arc::new);
        Ok(Surface { texture, ..self })
    }
    /// The curved height profile, if not a straight line.
    pub fn profile(&self) -> Option<&crate::surface::Height> {
        self.profile.as_deref()
    }
    /// The friction profile, if any.
    pub fn texture(&self) -> Option<&crate::surface::Texture> {
        self.texture.as_deref()
    }
    /// The curved height profile, shared.
    pub(crate) fn profile_shared(&self) -> Option<Arc<crate::surface::Height>> {
        self.profile.clone()
    }
    /// The friction profile, shared.
    pub(crate) fn texture_shared(&self) -> Option<Arc<crate::surface::Texture>> {
        self.texture.clone()
    }
}
