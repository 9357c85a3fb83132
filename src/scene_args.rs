//! Building a `vibrissa::Scene` from `--scene FILE.toml` and the scene flags, validated by the
//! shared validation layer (messages name the flag or the file's key the value came from).

use crate::cli::{PhysicalArgs, SceneArgs};
use crate::error::{usage, Res};
use crate::validate::{self, SceneSrc};
use std::io::Read;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use vibrissa::{Physical, Precurvature, Scene, Stiffness};

/// Physical unit factors (re-exported from the model crate).
pub use vibrissa::Units;

/// Scene files read so far, by the path as given, with their text.
static READ: Mutex<Vec<(PathBuf, String)>> = Mutex::new(Vec::new());

/// The text of a scene file, read once per process: a command that builds its scene twice (to
/// check it before any work, then to run) gets the same text the second time, so `/dev/stdin`,
/// a pipe or a FIFO (whose second read would be empty, or wait for a writer that never comes)
/// work like a file. `-` is stdin.
fn scene_text(path: &Path) -> Res<String> {
    // a panic while holding the lock leaves the list usable
    let mut read = READ.lock().unwrap_or_else(|p| p.into_inner());
    if let Some((_, text)) = read.iter().find(|(p, _)| p == path) {
        return Ok(text.clone());
    }
    let text = if path.as_os_str() == "-" {
        let mut t = String::new();
        std::io::stdin()
            .read_to_string(&mut t)
            .map(|_| t)
            .map_err(|e| usage(format!("cannot read the scene from stdin (--scene -): {e}")))?
    } else {
        std::fs::read_to_string(path)
            .map_err(|e| usage(format!("cannot read scene file {}: {e}", path.display())))?
    };
    read.push((path.to_path_buf(), text.clone()));
    Ok(text)
}

/// Read a scene file (TOML; unknown keys, also those that do not belong to a table's `kind`, are
/// refused). Errors name the file and the line. Each file is read once per process (see
/// [`scene_text`]).
pub fn read_scene_file(path: &Path) -> Res<Scene> {
    let text = scene_text(path)?;
    // first the keys of each kind: its message has the key's own line and the valid keys
    validate::scene_file_keys(path, &text)?;
    let sc = toml::from_str::<Scene>(&text).map_err(|e| {
        let line = e
            .span()
            .map(|sp| text[..sp.start.min(text.len())].matches('\n').count() + 1)
            .map(|l| format!(" (line {l})"))
            .unwrap_or_default();
        usage(format!(
            "scene file {}{line}: {}",
            path.display(),
            vibrissa::scene::plain_message(e.message())
        ))
    })?;
    let mut sc = sc;
    // a measured profile's file is named from the scene file's directory
    if let vibrissa::surface::SurfaceProfile::Measured { file, .. } = &mut sc.surface {
        if file.is_relative() && path.as_os_str() != "-" {
            if let Some(dir) = path.parent() {
                *file = dir.join(&*file);
            }
        }
    }
    Ok(sc)
}

/// The scene: file values (or defaults), then the flags on top (`eta`: the `--eta` flag of scan
/// and infer); validated.
pub fn build_scene(a: &SceneArgs, eta: Option<f64>) -> Res<Scene> {
    let sc = build_scene_unchecked(a, eta)?;
    let flag = |present: bool, f: &'static str| present.then_some(f);
    let src = SceneSrc {
        file: a.scene.as_deref(),
        eta: flag(eta.is_some(), "--eta"),
        taper: flag(a.taper.is_some(), "--taper"),
        k0: flag(a.precurvature.is_some(), "--precurvature"),
        k1: flag(a.precurvature_slope.is_some(), "--precurvature-slope"),
        c: flag(a.support_compliance.is_some(), "--support-compliance"),
        beta: flag(a.surface_angle.is_some(), "--surface-angle"),
        tip_radius: flag(a.tip_radius.is_some(), "--tip-radius"),
        physical: physical_src(&a.physical),
    };
    validate::scene(&sc, &src)?;
    validate::model_check(&sc, a.scene.as_deref())?;
    Ok(sc)
}

/// Which physical values came from flags.
pub fn physical_src(p: &PhysicalArgs) -> [Option<&'static str>; 3] {
    [
        p.length_mm.map(|_| "--length-mm"),
        p.youngs_modulus_gpa.map(|_| "--youngs-modulus-gpa"),
        p.base_diameter_um.map(|_| "--base-diameter-um"),
    ]
}

/// The scene without validation.
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
    apply_physical(&mut sc, &a.physical)?;
    if let Some(c) = a.contact {
        sc.contact = c;
    }
    if let Some(s) = a.start {
        sc.start = s;
    }
    if let Some(r) = a.tip_radius {
        sc.tip_radius = r;
    }
    Ok(sc)
}

/// The physical flags on top of the file's `[physical]`: all three, or those the file lacks.
pub fn apply_physical(sc: &mut Scene, a: &PhysicalArgs) -> Res<()> {
    match (a.length_mm, a.youngs_modulus_gpa, a.base_diameter_um) {
        (None, None, None) => {}
        (Some(l), Some(e), Some(d)) => {
            sc.physical = Some(Physical {
                length_mm: l,
                youngs_modulus_gpa: e,
                base_diameter_um: d,
            })
        }
        (l, e, d) => match sc.physical.as_mut() {
            // complete a file's physical block
            Some(p) => {
                if let Some(l) = l {
                    p.length_mm = l;
                }
                if let Some(e) = e {
                    p.youngs_modulus_gpa = e;
                }
                if let Some(d) = d {
                    p.base_diameter_um = d;
                }
            }
            None => {
                return Err(usage(
                    "physical units need all three of --length-mm, --youngs-modulus-gpa, --base-diameter-um (or a scene file with [physical])",
                ))
            }
        },
    }
    Ok(())
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

/// Physical unit factors of a (validated) scene.
pub fn units_of(sc: &Scene) -> Option<Units> {
    sc.rod().ok().and_then(|r| r.units())
}
