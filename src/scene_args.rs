//! Building a `vibrissa::Scene` from `--scene FILE.toml` and the scene flags.

use crate::cli::SceneArgs;
use crate::error::{usage, Res};
use std::path::Path;
use vibrissa::{Physical, Precurvature, Scene, Stiffness};

/// Physical unit factors (re-exported from the model crate).
pub use vibrissa::Units;

/// Read a scene file (TOML, unknown keys rejected). Errors name the file and the line.
pub fn read_scene_file(path: &Path) -> Res<Scene> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| usage(format!("cannot read scene file {}: {e}", path.display())))?;
    toml::from_str::<Scene>(&text).map_err(|e| {
        let line = e
            .span()
            .map(|sp| text[..sp.start.min(text.len())].matches('\n').count() + 1)
            .map(|l| format!(" (line {l})"))
            .unwrap_or_default();
        usage(format!(
            "scene file {}{line}: {}",
            path.display(),
            e.message()
        ))
    })
}

/// The scene: file values (or defaults), then the flags on top; validated.
pub fn build_scene(a: &SceneArgs, eta: Option<f64>) -> Res<Scene> {
    let sc = build_scene_unchecked(a, eta)?;
    sc.validate()?;
    Ok(sc)
}

/// The scene without the model's validation.
pub fn build_scene_unchecked(a: &SceneArgs, eta: Option<f64>) -> Res<Scene> {
    let mut sc = match &a.scene {
        Some(p) => read_scene_file(p)?,
        None => Scene::default(),
    };
    if let Some(e) = eta {
        sc.eta = e;
    }
    apply_overrides(
        &mut sc,
        a.taper,
        a.precurvature,
        a.precurvature_slope,
        a.support_compliance,
        a.surface_angle,
    );
    match (a.length_mm, a.youngs_modulus_gpa, a.base_diameter_um) {
        (None, None, None) => {}
        (Some(l), Some(e), Some(d)) => {
            sc.physical = Some(Physical {
                length_mm: l,
                youngs_modulus_gpa: e,
                base_diameter_um: d,
            })
        }
        (l, e, d) => {
            // complete a file's physical block, or ask for all three
            let base = sc.physical.clone();
            match base {
                Some(mut p) => {
                    if let Some(l) = l {
                        p.length_mm = l;
                    }
                    if let Some(e) = e {
                        p.youngs_modulus_gpa = e;
                    }
                    if let Some(d) = d {
                        p.base_diameter_um = d;
                    }
                    sc.physical = Some(p);
                }
                None => {
                    return Err(usage(
                        "physical units need all three of --length-mm, --youngs-modulus-gpa, --base-diameter-um",
                    ))
                }
            }
        }
    }
    Ok(sc)
}

/// Apply scene overrides (flags or sweep grid values).
pub fn apply_overrides(
    sc: &mut Scene,
    taper: Option<f64>,
    k0: Option<f64>,
    k1: Option<f64>,
    compliance: Option<f64>,
    surface_angle: Option<f64>,
) {
    if let Some(r) = taper {
        sc.stiffness = Stiffness::Taper { ratio: r };
    }
    if k0.is_some() || k1.is_some() {
        let (old0, old1) = match &sc.precurvature {
            Precurvature::Linear { k0, k1 } => (*k0, *k1),
            _ => (0.0, 0.0),
        };
        sc.precurvature = Precurvature::Linear {
            k0: k0.unwrap_or(old0),
            k1: k1.unwrap_or(old1),
        };
    }
    if let Some(c) = compliance {
        sc.support_compliance = c;
    }
    if let Some(b) = surface_angle {
        sc.surface_angle = b;
    }
}
