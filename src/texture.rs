//! The surface textures of a drag from flags: a corrugation or a sum of sines
//! (`--corrugation-*`), a grating (`--grating-*`), a measured profile (`--surface-profile`,
//! `--profile-tolerance`). Each replaces the scene's `[surface]`; the library checks the shape
//! (its ranges are those of `vibrissa::limits`), and its messages name the flags.

use crate::cli::TextureArgs;
use crate::error::{usage, Res};
use crate::number_text::short;
use crate::validate::{check, Src};
use vibrissa::limits;
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

/// The flags' own values against their ranges, and which go together.
pub fn check_flags(a: &TextureArgs) -> Res<()> {
    for (vals, flag, r) in [
        (
            &a.corrugation_amplitude,
            "--corrugation-amplitude",
            &limits::CORRUGATION_AMPLITUDE,
        ),
        (
            &a.corrugation_wavelength,
            "--corrugation-wavelength",
            &limits::CORRUGATION_WAVELENGTH,
        ),
        (
            &a.corrugation_phase,
            "--corrugation-phase",
            &limits::CORRUGATION_PHASE,
        ),
    ] {
        for &v in vals {
            check(Src::Flag(flag), v, r)?;
        }
    }
    for (v, flag, r) in [
        (
            a.grating_period,
            "--grating-period",
            &limits::GRATING_PERIOD,
        ),
        (a.grating_depth, "--grating-depth", &limits::GRATING_DEPTH),
        (
            a.grating_flank_angle,
            "--grating-flank-angle",
            &limits::GRATING_FLANK_ANGLE,
        ),
        (
            a.grating_ridge_radius,
            "--grating-ridge-radius",
            &limits::GRATING_RIDGE_RADIUS,
        ),
        (
            a.grating_offset,
            "--grating-offset",
            &limits::GRATING_OFFSET,
        ),
        (
            a.profile_tolerance,
            "--profile-tolerance",
            &limits::PROFILE_TOLERANCE,
        ),
    ] {
        if let Some(v) = v {
            check(Src::Flag(flag), v, r)?;
        }
    }
    let (na, nw, np) = (
        a.corrugation_amplitude.len(),
        a.corrugation_wavelength.len(),
        a.corrugation_phase.len(),
    );
    match (na, nw) {
        (0, 0) => {}
        (_, 0) => {
            return Err(usage(
                "--corrugation-amplitude needs --corrugation-wavelength",
            ))
        }
        (0, _) => {
            return Err(usage(
                "--corrugation-wavelength needs --corrugation-amplitude",
            ))
        }
        (na, nw) if na != nw => {
            return Err(usage(format!(
                "--corrugation-amplitude has {na} values and --corrugation-wavelength {nw}: one wavelength per amplitude (a sum of sines)"
            )))
        }
        _ => {}
    }
    if np > 0 && na == 0 {
        return Err(usage(
            "--corrugation-phase needs --corrugation-amplitude and --corrugation-wavelength",
        ));
    }
    if np > 0 && np != na {
        return Err(usage(format!(
            "--corrugation-phase has {np} values and --corrugation-amplitude {na}: one phase per amplitude, or none"
        )));
    }
    if !limits::SINES_TERMS.contains_count(na.max(1)) {
        return Err(usage(format!(
            "--corrugation-amplitude has {na} values: a sum of at most {} sines",
            limits::SINES_TERMS.hi
        )));
    }
    let grating = [
        a.grating_depth,
        a.grating_flank_angle,
        a.grating_ridge_radius,
        a.grating_offset,
    ]
    .iter()
    .any(Option::is_some);
    if grating || a.grating_period.is_some() {
        if a.grating_period.is_none() {
            return Err(usage(
                "the --grating flags need --grating-period (and --grating-ridge-radius)",
            ));
        }
        if a.grating_ridge_radius.is_none() {
            return Err(usage(
                "--grating-period needs --grating-ridge-radius (the radius of the ridges and grooves)",
            ));
        }
        if a.grating_depth.is_none() && a.grating_flank_angle.is_none() {
            return Err(usage(
                "--grating-period needs --grating-depth, --grating-flank-angle or both",
            ));
        }
    }
    match (&a.surface_profile, a.profile_tolerance) {
        (Some(_), None) => {
            return Err(usage(
                "--surface-profile needs --profile-tolerance (the largest deviation of the smoothed profile from a sample; 0 interpolates)",
            ))
        }
        (None, Some(_)) => return Err(usage("--profile-tolerance needs --surface-profile")),
        _ => {}
    }
    let kinds: Vec<&str> = [
        (na > 0, "--corrugation-amplitude"),
        (a.grating_period.is_some(), "--grating-period"),
        (a.surface_profile.is_some(), "--surface-profile"),
    ]
    .iter()
    .filter(|k| k.0)
    .map(|k| k.1)
    .collect();
    if kinds.len() > 1 {
        return Err(usage(format!(
            "{} each set the surface: give one of them",
            kinds.join(" and ")
        )));
    }
    Ok(())
}

/// The texture of the flags (checked by [`check_flags`]), if any.
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
        if steepest >= vibrissa::surface::MAX_PROFILE_SLOPE {
            let mut m = format!(
                "--corrugation-amplitude {} with --corrugation-wavelength {} makes the surface's steepest slope ",
                list(amp),
                list(wave)
            );
            if amp.len() == 1 {
                let k = tau / wave[0];
                m += &format!(
                    "|tan(surface angle)| + 2 pi |A| / W = {} reach 1 (45 degrees, the steepest surface the model takes); |A| must stay below {}",
                    short(steepest),
                    short(((vibrissa::surface::MAX_PROFILE_SLOPE - beta) / k).max(0.0))
                );
            } else {
                m += &format!(
                    "|tan(surface angle)| + the sum of 2 pi |A| / W = {} reach 1 (45 degrees, the steepest surface the model takes); lower the amplitudes",
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
