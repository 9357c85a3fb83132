//! The program's side of validation: the library's ranges ([`vibrissa::limits`]) checked where
//! the user typed the value, whether a flag, a sweep axis or a scene file, with messages that
//! name what was typed (the flag, or the file and its key), the value with enough digits to see
//! why it is outside, the range and why; which flags go together, the outputs, and the limits on
//! sizes (grid, memory) and threads.

use crate::cli::{Command, FiguresArgs, InferArgs, ScanArgs, SolveArgs, SweepArgs};
use crate::error::{usage, Fail, Res};
use crate::number_text::{digits, short};
use std::f64::consts::PI;
use std::path::Path;
use vibrissa::limits::{self, Range};
use vibrissa::{Precurvature, Scene, Stiffness};

/// Where a value came from, for the message.
#[derive(Clone, Copy, Debug)]
pub enum Src<'a> {
    /// a flag (or a sweep axis), e.g. `--taper`
    Flag(&'static str),
    /// a scene file and its key, e.g. `stiffness.ratio`
    File(&'a Path, &'static str),
    /// the built-in default (always valid)
    Default,
}

/// Check `v` against `r`; the message names the source and shows the range and why.
pub fn check(src: Src, v: f64, r: &Range) -> Res<()> {
    check_why(src, v, r, r.explanation())
}

/// [`check`] with the reason `why` in the message (a range whose end is another flag's value).
pub fn check_why(src: Src, v: f64, r: &Range, why: &str) -> Res<()> {
    if r.contains(v) {
        return Ok(());
    }
    let p = r.digits_for(v);
    let who = match src {
        Src::Flag(f) => format!("{f} {}", digits(v, p)),
        Src::File(path, key) => format!("scene file {}: {key} = {}", path.display(), digits(v, p)),
        Src::Default => format!("the default value {}", digits(v, p)),
    };
    let why = if why.is_empty() {
        String::new()
    } else {
        format!(" ({why})")
    };
    Err(usage(format!(
        "{who} is outside the valid range {}{why}",
        r.text(p)
    )))
}

/// Where each scene quantity came from.
#[derive(Clone, Copy, Debug)]
pub struct SceneSrc<'a> {
    /// the scene file, if any
    pub file: Option<&'a Path>,
    /// `eta` from a flag
    pub eta: Option<&'static str>,
    /// `stiffness.ratio` from a flag
    pub taper: Option<&'static str>,
    /// `precurvature.k0` from a flag
    pub k0: Option<&'static str>,
    /// `precurvature.k1` from a flag
    pub k1: Option<&'static str>,
    /// `support_compliance` from a flag
    pub c: Option<&'static str>,
    /// `surface_angle` from a flag
    pub beta: Option<&'static str>,
    /// `tip_radius` from a flag
    pub tip_radius: Option<&'static str>,
    /// the three physical values from flags
    pub physical: [Option<&'static str>; 3],
}

impl SceneSrc<'_> {
    fn of(&self, flag: Option<&'static str>, key: &'static str) -> Src<'_> {
        match (flag, self.file) {
            (Some(f), _) => Src::Flag(f),
            (None, Some(p)) => Src::File(p, key),
            (None, None) => Src::Default,
        }
    }
}

/// Check every value of a scene.
pub fn scene(sc: &Scene, src: &SceneSrc) -> Res<()> {
    check(src.of(src.eta, "eta"), sc.eta, &limits::eta())?;
    match &sc.stiffness {
        Stiffness::Uniform => {}
        Stiffness::Taper { ratio } => {
            check(src.of(src.taper, "stiffness.ratio"), *ratio, &limits::TAPER)?;
        }
        Stiffness::Table { b, .. } => {
            for v in b {
                check(src.of(None, "stiffness.b"), *v, &limits::TABLE_B)?;
            }
        }
    }
    match &sc.precurvature {
        Precurvature::None => {}
        Precurvature::Linear { k0, k1 } => {
            check(
                src.of(src.k0, "precurvature.k0"),
                *k0,
                &limits::PRECURVATURE,
            )?;
            check(
                src.of(src.k1, "precurvature.k1"),
                *k1,
                &limits::PRECURVATURE_SLOPE,
            )?;
            let end = k0 + k1;
            if !limits::PRECURVATURE.contains(end) {
                let who = match (src.k0.or(src.k1), src.file) {
                    (Some(_), _) | (None, None) => {
                        "--precurvature K0 + --precurvature-slope K1".to_string()
                    }
                    (None, Some(p)) => {
                        format!(
                            "scene file {}: precurvature.k0 + precurvature.k1",
                            p.display()
                        )
                    }
                };
                return Err(usage(format!(
                    "{who} = {} (the rest curvature at the tip) is outside the valid range {} ({})",
                    short(end),
                    limits::PRECURVATURE.text(6),
                    limits::PRECURVATURE.unit
                )));
            }
        }
        Precurvature::Table { k, .. } => {
            for v in k {
                check(src.of(None, "precurvature.k"), *v, &limits::PRECURVATURE)?;
            }
        }
    }
    check(
        src.of(src.c, "support_compliance"),
        sc.support_compliance,
        &limits::SUPPORT_COMPLIANCE,
    )?;
    check(
        src.of(src.beta, "surface_angle"),
        sc.surface_angle,
        &limits::SURFACE_ANGLE,
    )?;
    check(
        src.of(src.tip_radius, "tip_radius"),
        sc.tip_radius,
        &limits::TIP_RADIUS,
    )?;
    if let Some(p) = &sc.physical {
        let keys = [
            "physical.length_mm",
            "physical.youngs_modulus_gpa",
            "physical.base_diameter_um",
        ];
        let vals = [p.length_mm, p.youngs_modulus_gpa, p.base_diameter_um];
        for i in 0..3 {
            check(src.of(src.physical[i], keys[i]), vals[i], &limits::PHYSICAL)?;
        }
        // in logarithms: the factors alone may overflow (E in Pa = GPa·1e9, d in m = µm·1e-6)
        let ln10 = std::f64::consts::LN_10;
        let log_l = p.length_mm.ln() - 3.0 * ln10;
        let log_ei = p.youngs_modulus_gpa.ln()
            + 9.0 * ln10
            + (PI / 64.0).ln()
            + 4.0 * (p.base_diameter_um.ln() - 6.0 * ln10);
        for (name, unit, log_v) in [
            ("the length unit L", "mm", p.length_mm.ln()),
            ("the force unit EI/L^2", "N", log_ei - 2.0 * log_l),
            ("the moment unit EI/L", "N m", log_ei - log_l),
        ] {
            let v = log_v.exp();
            if !(log_v >= limits::UNIT.lo.ln() && log_v <= limits::UNIT.hi.ln()) {
                let shown = if v.is_finite() && v > 0.0 {
                    short(v)
                } else {
                    format!("1e{:.0}", log_v / std::f64::consts::LN_10)
                };
                return Err(usage(format!(
                    "the physical dimensions (length {} mm, Young's modulus {} GPa, base diameter {} um) give {name} = {shown} {unit}, outside {}: the physical-unit columns would overflow or vanish",
                    short(p.length_mm),
                    short(p.youngs_modulus_gpa),
                    short(p.base_diameter_um),
                    limits::UNIT.text(6)
                )));
            }
        }
    }
    Ok(())
}

fn tol(t: f64) -> Res<()> {
    check(Src::Flag("--tol"), t, &limits::TOL)
}

/// `--mu0`: the library's range, and `inf` (never slips: no threshold).
const MU0_FLAG: Range = Range {
    hi_closed: true,
    ..limits::MU0
};

fn mu0(m: &mut Option<f64>) -> Res<()> {
    if let Some(v) = *m {
        check(Src::Flag("--mu0"), v, &MU0_FLAG)?;
        if v == f64::INFINITY {
            // never slips: the same as no threshold
            *m = None;
        }
    }
    Ok(())
}

/// Check the values of a command that are not part of the scene (those are checked when the
/// scene is built), and normalize a few spellings (`--out -` is stdout, `--mu0 inf` is none).
pub fn command(cmd: &mut Command) -> Res<()> {
    match cmd {
        Command::Solve(a) => solve(a),
        Command::Scan(a) => scan(a),
        Command::Infer(a) => infer(a),
        Command::Sweep(a) => sweep_flags(a),
        Command::Figures(a) => figures(a),
        Command::Whisk(a) => whisk(a),
        Command::Locate(a) => locate(a),
        Command::Drag(a) => drag(a),
        Command::Fit(a) => fit(a),
        Command::Modes(a) => {
            check(Src::Flag("--tip-angle"), a.tip_angle, &limits::TIP_ANGLE)?;
            check(
                Src::Flag("--rotary-inertia"),
                a.rotary_inertia,
                &limits::ROTARY_INERTIA,
            )
        }
        Command::Plot(a) => {
            check(
                Src::Flag("--surface-angle"),
                a.surface_angle,
                &limits::SURFACE_ANGLE,
            )?;
            texture(&a.texture)
        }
        // the library's DynDragOptions::validate names each value as its flag (main.rs)
        Command::Dynamics(_) => Ok(()),
    }
}

fn solve(a: &mut SolveArgs) -> Res<()> {
    tol(a.solver.tol)?;
    if let Some(p) = a.peg {
        peg(p)?;
        check(Src::Flag("--theta"), a.theta.unwrap_or(0.0), &limits::THETA)?;
        mu0(&mut a.mu0)?;
    } else if a.phi1.is_none() && a.eta.is_none() {
        return Err(usage(
            "one of --phi1 and --eta is required (the tip condition), or --peg X,Y for a point object",
        ));
    }
    if let Some(al) = a.alpha {
        check(Src::Flag("--alpha"), al, &limits::ALPHA)?;
    }
    if let Some(p) = a.phi1 {
        check(Src::Flag("--phi1"), p, &limits::PHI1)?;
    }
    if let Some(h) = a.eta {
        check(Src::Flag("--eta"), h, &limits::TIP_HEIGHT)?;
    }
    if a.shape_out.as_deref().is_some_and(is_stdout) {
        return Err(usage(
            "--shape-out - would share stdout with the result; give it a file name",
        ));
    }
    Ok(())
}

/// A point object: inside the reach of the rod (distance from the foot in (0, 1)).
fn peg(p: crate::cli::Point) -> Res<()> {
    let r = (p.x * p.x + p.y * p.y).sqrt();
    if !(r > 0.0 && r < 1.0) {
        return Err(usage(format!(
            "--peg {},{} is at distance {} from the foot, outside the valid range (0, 1) (rod lengths: a point the rod can reach)",
            p.x, p.y, r
        )));
    }
    Ok(())
}

/// The scene flags a point object has no use for (it has no surface): refused, not ignored.
fn no_surface(a: &crate::cli::SceneArgs, what: &str) -> Res<()> {
    let given = [
        (a.surface_angle.is_some(), "--surface-angle"),
        (a.contact.is_some(), "--contact"),
    ];
    match given.iter().find(|g| g.0) {
        Some((_, flag)) => Err(usage(format!(
            "{flag} does not apply to {what}: a point object has no surface (its place is --peg, friction at it --mu0)"
        ))),
        None => Ok(()),
    }
}

fn whisk(a: &mut crate::cli::WhiskArgs) -> Res<()> {
    tol(a.solver.tol)?;
    no_surface(&a.scene, "whisk")?;
    peg(a.peg)?;
    check(Src::Flag("--theta-max"), a.theta_max, &limits::THETA)?;
    mu0(&mut a.mu0)?;
    if a.out.as_deref().is_some_and(is_stdout) && a.json {
        return Err(usage(
            "--out - with --json would put the rows and the JSON summary on the same stdout; give --out a file name",
        ));
    }
    Ok(())
}

fn locate(a: &mut crate::cli::LocateArgs) -> Res<()> {
    tol(a.solver.tol)?;
    no_surface(&a.scene, "locate")?;
    check(Src::Flag("--theta"), a.theta, &limits::THETA)
}

fn scan(a: &mut ScanArgs) -> Res<()> {
    tol(a.solver.tol)?;
    check(Src::Flag("--d-max"), a.d_max, &limits::D_MAX)?;
    mu0(&mut a.mu0)?;
    table_outputs(
        "scan",
        &mut a.out,
        a.json,
        a.shapes.as_deref(),
        a.points,
        a.shape_points,
    )
}

/// The outputs of a command with a table (`--out`, `-` for stdout), a `--json` summary and
/// `--shapes`: `--out -` means stdout (not with `--json`), `--shapes` needs a file, and the shapes
/// must fit the memory budget.
fn table_outputs(
    what: &str,
    out: &mut Option<std::path::PathBuf>,
    json: bool,
    shapes: Option<&Path>,
    points: u32,
    shape_points: u32,
) -> Res<()> {
    if out.as_deref().is_some_and(is_stdout) {
        if json {
            return Err(usage(format!(
                "--out - with --json would put the {what}'s CSV and its JSON summary on the same stdout; give --out a file name (the JSON then names it), or leave out --out - (--json alone prints only the summary)"
            )));
        }
        *out = None;
    }
    if shapes.is_some_and(is_stdout) {
        return Err(usage(format!(
            "--shapes - would share stdout with the {what}'s table or summary; give it a file name"
        )));
    }
    if shapes.is_some() {
        budget(
            "--points",
            points as u64,
            "--shape-points",
            shape_points as u64,
            "shape samples",
            limits::BYTES_PER_SHAPE_SAMPLE,
        )?;
    }
    Ok(())
}

fn drag(a: &mut crate::cli::DragArgs) -> Res<()> {
    tol(a.solver.tol)?;
    check(Src::Flag("--d-max"), a.d_max, &limits::DRAG_D_MAX)?;
    friction(a.mu_s, a.mu_k)?;
    texture(&a.texture)?;
    table_outputs(
        "drag",
        &mut a.out,
        a.json,
        a.shapes.as_deref(),
        a.points,
        a.shape_points,
    )
}

/// `--mu-s` with `--mu-k` (both or neither), kinetic below static.
fn friction(mu_s: Option<f64>, mu_k: Option<f64>) -> Res<()> {
    match (mu_s, mu_k) {
        (Some(s), Some(k)) => {
            check(Src::Flag("--mu-s"), s, &limits::MU_S)?;
            let why = format!(
                "kinetic friction below static, the upper end is --mu-s: {}",
                limits::STICK_SLIP
            );
            check_why(Src::Flag("--mu-k"), k, &limits::kinetic_friction(s), &why)?;
        }
        (Some(_), None) => {
            return Err(usage(
                "--mu-s needs --mu-k (the kinetic coefficient the slipping tip stops at)",
            ))
        }
        (None, Some(_)) => {
            return Err(usage(
                "--mu-k needs --mu-s (the static coefficient at which the tip slips)",
            ))
        }
        (None, None) => {}
    }
    Ok(())
}

fn fit(a: &mut crate::cli::FitArgs) -> Res<()> {
    tol(a.solver.tol)?;
    friction(a.mu_s, a.mu_k)?;
    texture(&a.texture)
}

/// The flags' own values against their ranges, and which go together.
pub fn texture(a: &crate::cli::TextureArgs) -> Res<()> {
    texture_ranges(a)?;
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
    grating_flags(a)?;
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

/// Each texture flag's value in its range.
fn texture_ranges(a: &crate::cli::TextureArgs) -> Res<()> {
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
    Ok(())
}

/// The grating's flags that go together: period and ridge radius, with a depth or a flank angle.
fn grating_flags(a: &crate::cli::TextureArgs) -> Res<()> {
    let grating = [
        a.grating_depth,
        a.grating_flank_angle,
        a.grating_ridge_radius,
        a.grating_offset,
    ]
    .iter()
    .any(Option::is_some);
    if grating || a.grating_period.is_some() {
        let given: Vec<&str> = [
            (a.grating_period, "--grating-period"),
            (a.grating_depth, "--grating-depth"),
            (a.grating_flank_angle, "--grating-flank-angle"),
            (a.grating_ridge_radius, "--grating-ridge-radius"),
            (a.grating_offset, "--grating-offset"),
        ]
        .iter()
        .filter(|g| g.0.is_some())
        .map(|g| g.1)
        .collect();
        let who = given.join(" with ");
        if a.grating_period.is_none() || a.grating_ridge_radius.is_none() {
            return Err(usage(format!(
                "{who} needs --grating-period and --grating-ridge-radius (a grating's period and the radius of its ridges and grooves)"
            )));
        }
        if a.grating_depth.is_none() && a.grating_flank_angle.is_none() {
            return Err(usage(format!(
                "{who} needs --grating-depth, --grating-flank-angle or both"
            )));
        }
    }
    Ok(())
}

fn infer(a: &mut InferArgs) -> Res<()> {
    tol(a.solver.tol)?;
    check(Src::Flag("--d-max"), a.d_max, &limits::D_MAX)?;
    let why = "rod lengths; the upper end is --d-max";
    check_why(Src::Flag("--d0"), a.d0, &limits::d0(a.d_max), why)
}

fn sweep_flags(a: &mut SweepArgs) -> Res<()> {
    // the ends of a range suffice: its other values lie between them
    for t in a.tol.extremes() {
        tol(t)?;
    }
    for v in a.d_max.extremes() {
        check(Src::Flag("--d-max"), v, &limits::D_MAX)?;
    }
    if let Some(m) = &a.mu0 {
        for v in m.extremes() {
            check(Src::Flag("--mu0"), v, &MU0_FLAG)?;
        }
    }
    if let Some(v) = a.points.first_fraction() {
        return Err(usage(format!(
            "--points {} gives {}, not a whole number of points per scan",
            a.points.text,
            short(v)
        )));
    }
    // whole numbers, shown as such (as scan's --points: [2, 1000000])
    for v in a.points.extremes() {
        if !limits::POINTS.contains(v) {
            let shown = if v.abs() < 1e15 {
                format!("{}", v as i64)
            } else {
                short(v)
            };
            return Err(usage(format!(
                "--points {shown} is outside the valid range {} (points per scan)",
                limits::POINTS.text(6)
            )));
        }
    }
    if a.out.as_deref().is_some_and(is_stdout) {
        a.out = None;
    }
    Ok(())
}

fn figures(a: &mut FiguresArgs) -> Res<()> {
    tol(a.tol)
}

/// `-` means stdout.
pub fn is_stdout(p: &Path) -> bool {
    p.as_os_str() == "-"
}

/// `a × b` items of `bytes` each within the memory budget ([`limits::MEMORY_BUDGET`]), else an
/// error naming the product.
pub fn budget(fa: &str, a: u64, fb: &str, b: u64, what: &str, bytes: u64) -> Res<()> {
    let prod = a.saturating_mul(b);
    let need = prod.saturating_mul(bytes);
    if need > limits::MEMORY_BUDGET {
        return Err(usage(format!(
            "{fa} {a} × {fb} {b} = {} {what} to hold in memory at once, about {} GB at {bytes} bytes each, more than the budget of 1 GB; lower one of them",
            short(prod as f64),
            digits(need as f64 / 1e9, 2)
        )));
    }
    Ok(())
}

/// Number of grid points: the product of the axis lengths, checked against
/// [`limits::MAX_SCENES`] by arithmetic (the grid itself is never built).
pub fn grid_size(axes: &[(&str, u64)]) -> Res<u64> {
    let mut n: u64 = 1;
    let mut overflow = false;
    for &(_, len) in axes {
        match n.checked_mul(len) {
            Some(m) if m <= limits::MAX_SCENES => n = m,
            _ => {
                overflow = true;
                break;
            }
        }
    }
    if overflow {
        let total: f64 = axes.iter().map(|&(_, l)| l as f64).product();
        let sizes: Vec<String> = axes
            .iter()
            .filter(|a| a.1 > 1)
            .map(|(name, l)| format!("{l} ({name})"))
            .collect();
        return Err(usage(format!(
            "the grid has {} = {} scenes, more than the limit of {}; split it into several sweeps",
            sizes.join(" × "),
            short(total),
            short(limits::MAX_SCENES as f64)
        )));
    }
    Ok(n)
}

/// Worker threads: `asked` (default: the cores), capped at [`limits::JOBS_PER_CORE`] per core
/// with a warning, and at the number of scenes.
pub fn jobs(asked: Option<u32>, scenes: u64) -> usize {
    use limits::JOBS_PER_CORE;
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let cap = JOBS_PER_CORE * cores;
    let mut j = asked.map_or(cores, |j| j as usize);
    if j > cap {
        crate::progress::warn(&format!(
            "--jobs {j} is more than {JOBS_PER_CORE} threads per core; using {cap} ({cores} cores)"
        ));
        j = cap;
    }
    j.min(scenes.max(1) as usize).max(1)
}

/// The model's own check of a scene (tables and the rest), its message prefixed with the file.
pub fn model_check(sc: &Scene, file: Option<&Path>) -> Res<()> {
    sc.validate().map_err(|e| {
        let f = crate::error::shorten(e.into());
        match (file, f) {
            (Some(p), Fail::Usage(m)) => usage(format!("scene file {}: {m}", p.display())),
            (_, f) => f,
        }
    })
}

/// Scene-file check that serde cannot do: keys that do not belong to the table's `kind` (serde
/// ignores extra keys next to a unit variant such as `{ kind = "uniform", ratio = 0.5 }`).
pub fn scene_file_keys(path: &Path, text: &str) -> Res<()> {
    #[derive(serde::Deserialize)]
    struct Kinds {
        stiffness: Option<toml::Spanned<toml::Value>>,
        precurvature: Option<toml::Spanned<toml::Value>>,
    }
    // a file that does not parse is reported by the full parse, with its line
    let Ok(k) = toml::from_str::<Kinds>(text) else {
        return Ok(());
    };
    let line_of = |pos: usize| text[..pos.min(text.len())].matches('\n').count() + 1;
    for (name, t, kinds) in [
        (
            "stiffness",
            k.stiffness,
            &[
                ("uniform", &["kind"][..]),
                ("taper", &["kind", "ratio"][..]),
                ("table", &["kind", "s", "b"][..]),
            ][..],
        ),
        (
            "precurvature",
            k.precurvature,
            &[
                ("none", &["kind"][..]),
                ("linear", &["kind", "k0", "k1"][..]),
                ("table", &["kind", "s", "k"][..]),
            ][..],
        ),
    ] {
        let Some(t) = t else { continue };
        let span = t.span();
        let toml::Value::Table(tab) = t.into_inner() else {
            continue;
        };
        let Some(kind) = tab.get("kind").and_then(|v| v.as_str()) else {
            continue;
        };
        let Some((_, allowed)) = kinds.iter().find(|(k, _)| *k == kind) else {
            continue;
        };
        for key in tab.keys() {
            if !allowed.contains(&key.as_str()) {
                // the line of `key =` from the table's start on (the span of a `[table]`
                // may cover its header only)
                let from = span.start.min(text.len());
                let mut pos = from;
                let mut off = from;
                for l in text[from..].split_inclusive('\n') {
                    let t = l.trim_start().trim_start_matches('{').trim_start();
                    if t.starts_with(key.as_str()) || l.contains(&format!(" {key} =")) {
                        pos = off;
                        break;
                    }
                    off += l.len();
                }
                return Err(usage(format!(
                    "scene file {} (line {}): unknown key '{key}' in {name} of kind \"{kind}\"; its keys are {}",
                    path.display(),
                    line_of(pos),
                    allowed.join(", ")
                )));
            }
        }
    }
    Ok(())
}
