//! The surface textures of a drag from flags: a corrugation or a sum of sines
//! (`--corrugation-*`), a grating (`--grating-*`), a measured profile (`--surface-profile`,
//! `--profile-tolerance`). Each replaces the scene's `[surface]`; the library checks the shape
//! (its ranges are those of `vibrissa::limits`; the flags' own values and which go together are
//! checked in `validate`), and its messages name the flags.

use crate::cli::TextureArgs;
use crate::error::{usage, Res};
use crate::number_text::short;
use vibrissa::surface::SurfaceProfile;
use vibrissa::Scene;

/// The scene keys of the textures and the flags that set them.
const KEYS: [(&str, &str); 9] = [
    ("surface.amplitude", "--corrugation-amplitude"),
    ("surface.wavelength", "--corrugation-wavelength"),
    ("surface.phase", "--corrugation-phase"),
    ("surface.period", "--grating-period"),
    ("surface.depth", "--grating-depth"),
    ("surface.flank_angle", "--grating-flank-angle"),
    ("surface.ridge_radius", "--grating-ridge-radius"),
    ("surface.offset", "--grating-offset"),
    ("surface.tolerance", "--profile-tolerance"),
];

fn list(v: &[f64]) -> String {
    v.iter().map(|x| short(*x)).collect::<Vec<_>>().join(",")
}

/// The texture of the flags (checked by `validate`), if any.
fn profile(a: &TextureArgs) -> Option<SurfaceProfile> {
    if let (Some(period), Some(ridge_radius)) = (a.grating_period, a.grating_ridge_radius) {
        return Some(SurfaceProfile::Grating {
            period,
            depth: a.grating_depth,
            flank_angle: a.grating_flank_angle,
            ridge_radius,
            offset: a.grating_offset.unwrap_or(0.0),
        });
    }
    if let (Some(file), Some(tolerance)) = (&a.surface_profile, a.profile_tolerance) {
        return Some(SurfaceProfile::Measured {
            file: file.clone(),
            tolerance,
        });
    }
    match a.corrugation_amplitude.len() {
        0 => None,
        1 => Some(SurfaceProfile::Sine {
            amplitude: a.corrugation_amplitude[0],
            wavelength: a.corrugation_wavelength[0],
            phase: a.corrugation_phase.first().copied().unwrap_or(0.0),
        }),
        _ => Some(SurfaceProfile::Sines {
            amplitude: a.corrugation_amplitude.clone(),
            wavelength: a.corrugation_wavelength.clone(),
            phase: a.corrugation_phase.clone(),
        }),
    }
}

/// The flags' texture as the scene's surface, validated by the library, its messages naming the
/// flags; `false` if the flags give none.
pub fn apply(a: &TextureArgs, sc: &mut Scene) -> Res<bool> {
    let Some(p) = profile(a) else {
        return Ok(false);
    };
    let beta = sc.surface_angle.tan().abs();
    if !a.corrugation_amplitude.is_empty() {
        let (amp, wave) = (&a.corrugation_amplitude, &a.corrugation_wavelength);
        let tau = std::f64::consts::TAU;
        let steep: f64 = amp.iter().zip(wave).map(|(a, w)| tau * a.abs() / w).sum();
        let steepest = beta + steep;
        // (a round tip takes slopes up to 80 degrees: the library's limit for the scene's tip)
        let max = vibrissa::limits::max_profile_slope(sc.tip_radius);
        let (limit, hint) = if sc.tip_radius > 0.0 {
            (
                format!(
                    "{} (80 degrees, the steepest surface a round tip takes)",
                    short(max)
                ),
                "",
            )
        } else {
            (
                "1 (45 degrees, the steepest surface a point tip takes)".to_string(),
                "; a round tip (--tip-radius R > 0) takes slopes up to 80 degrees",
            )
        };
        if steepest >= max {
            let mut m = format!(
                "--corrugation-amplitude {} with --corrugation-wavelength {} makes the surface's steepest slope ",
                list(amp),
                list(wave)
            );
            if amp.len() == 1 {
                let k = tau / wave[0];
                m += &format!(
                    "|tan(surface angle)| + 2 pi |A| / W = {} reach {limit}; |A| must stay below {}{hint}",
                    short(steepest),
                    short(((max - beta) / k).max(0.0))
                );
            } else {
                m += &format!(
                    "|tan(surface angle)| + the sum of 2 pi |A| / W = {} reach {limit}; lower the amplitudes{hint}",
                    short(steepest)
                );
            }
            return Err(usage(m));
        }
    }
    sc.surface = p;
    sc.validate().map_err(|e| {
        let mut m = e.to_string();
        for (key, flag) in KEYS {
            m = m.replace(key, flag);
        }
        m = m.replace("surface.file", "--surface-profile");
        if e.is_input() {
            usage(m)
        } else {
            crate::error::solve_fail(m)
        }
    })?;
    Ok(true)
}
