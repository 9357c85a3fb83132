//! The valid ranges of the values of a scene and of the options, and the limits on sizes: one
//! place for the library's own checks, the program's flags and their `--help`, and Python.
//!
//! A [`Range`] knows its ends, whether each is included, its symbolic form (`(-pi/4, pi/4)`),
//! its unit and why it is what it is. The library's errors name the range with its unit
//! ([`Range::check`]: `support compliance = 2000 is outside the valid range [0, 1000] (L/EI)`);
//! a front end that can say more shows [`Range::explanation`] instead of the unit.

use crate::VibrissaError;
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

/// An interval, closed or open at either end, with its symbolic form, unit and reason.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Range {
    /// Lower end.
    pub lo: f64,
    /// Whether `lo` itself is allowed.
    pub lo_closed: bool,
    /// Upper end.
    pub hi: f64,
    /// Whether `hi` itself is allowed.
    pub hi_closed: bool,
    /// The ends are whole numbers (counts): written as such (`1000000`, not `1e6`).
    pub whole: bool,
    /// Symbolic form, e.g. `(-pi/4, pi/4)`, or empty.
    pub symbol: &'static str,
    /// The unit (`rod lengths`, `1/L`), or empty.
    pub unit: &'static str,
    /// Why the range is what it is (starting with the unit where there is one), or empty.
    pub why: &'static str,
}

impl Range {
    /// The interval from `lo` to `hi`, each end included or not.
    pub const fn new(lo: f64, lo_closed: bool, hi: f64, hi_closed: bool) -> Range {
        Range {
            lo,
            lo_closed,
            hi,
            hi_closed,
            whole: false,
            symbol: "",
            unit: "",
            why: "",
        }
    }
    /// The whole numbers from `lo` to `hi`, both included.
    pub const fn count(lo: usize, hi: usize) -> Range {
        Range {
            whole: true,
            ..Range::new(lo as f64, true, hi as f64, true)
        }
    }
    /// With a symbolic form.
    pub const fn symbol(mut self, symbol: &'static str) -> Range {
        self.symbol = symbol;
        self
    }
    /// With a unit.
    pub const fn unit(mut self, unit: &'static str) -> Range {
        self.unit = unit;
        self
    }
    /// With a reason.
    pub const fn why(mut self, why: &'static str) -> Range {
        self.why = why;
        self
    }

    /// Whether `v` is inside (NaN never is).
    pub fn contains(&self, v: f64) -> bool {
        let lo = if self.lo_closed {
            v >= self.lo
        } else {
            v > self.lo
        };
        let hi = if self.hi_closed {
            v <= self.hi
        } else {
            v < self.hi
        };
        lo && hi
    }

    /// Whether the count `n` is inside.
    pub fn contains_count(&self, n: usize) -> bool {
        self.contains(n as f64)
    }

    /// Significant digits that show `v` apart from both ends (at least 6).
    pub fn digits_for(&self, v: f64) -> usize {
        digits_to_decide(v, &[self.lo, self.hi])
    }

    /// The interval written with `p` significant digits: `[0.01, 1]`, or with its symbolic form
    /// `(-pi/4, pi/4) = (-0.785398, 0.785398)`.
    pub fn text(&self, p: usize) -> String {
        let end = |v: f64| {
            if v.is_infinite() {
                if v > 0.0 { "inf" } else { "-inf" }.to_string()
            } else if self.whole {
                format!("{}", v as i64)
            } else {
                digits(v, p)
            }
        };
        let num = format!(
            "{}{}, {}{}",
            if self.lo_closed { '[' } else { '(' },
            end(self.lo),
            end(self.hi),
            if self.hi_closed { ']' } else { ')' }
        );
        if self.symbol.is_empty() {
            num
        } else {
            format!("{} = {num}", self.symbol)
        }
    }

    /// What a message says after the interval: why it is what it is, else its unit.
    pub fn explanation(&self) -> &'static str {
        if self.why.is_empty() {
            self.unit
        } else {
            self.why
        }
    }

    /// `Ok` inside, else [`VibrissaError::OutOfRange`] naming `name`, `v` and the interval with
    /// its unit.
    pub fn check(&self, name: &str, v: f64) -> Result<(), VibrissaError> {
        if self.contains(v) {
            return Ok(());
        }
        let unit = if self.unit.is_empty() {
            String::new()
        } else {
            format!(" ({})", self.unit)
        };
        Err(VibrissaError::OutOfRange {
            name: name.to_string(),
            value: v,
            range: format!("{}{unit}", self.text(self.digits_for(v))),
        })
    }

    /// [`Range::check`] for a count.
    pub fn check_count(&self, name: &str, n: usize) -> Result<(), VibrissaError> {
        self.check(name, n as f64)
    }
}

/// Surface height `eta ∈ (η_, 1)`: η_ ≈ 0.456947 is the tip height of the uniform clamped rod
/// pushed straight down with a horizontal tip; on a lower surface the scan would start with the
/// rod crossing it.
pub fn eta() -> Range {
    let (_, lo) = elastica::lower_limit();
    Range::new(lo, false, 1.0, false).symbol("(eta_, 1)").unit("rod lengths").why(
        "eta_ = 0.456946581044463625... is the tip height of the uniform clamped rod pushed straight down (alpha = 0) with a horizontal tip (phi1 = 0); on a lower surface the scan would start with the rod crossing it",
    )
}

/// Taper ratio ρ (tip/base radius): below 0.01 the tip is over 10⁸ times more flexible than the
/// foot, beyond what the solvers resolve and beyond real whiskers (0.02–0.2).
pub const TAPER: Range = Range::new(0.01, true, 1.0, true).why(
    "tip/base radius ratio; real whiskers have 0.02-0.2, and below 0.01 the tip would be over 10^8 times more flexible than the foot",
);
/// Rest curvature `κ0(s)` anywhere along the rod (1/L): whiskers have `|κ0| < 2`; 3 already
/// bends the rest shape through 172°. More curled rods touch a surface above them only when
/// pulled, or start on branches that pressing cannot reach.
pub const PRECURVATURE: Range = Range::new(-3.0, true, 3.0, true).unit("1/L").why(
    "1/L; the rest curvature K0 + K1 s must stay within [-3, 3] along the rod: whiskers have |K0| < 2, and 3 already bends the rest shape through 172 degrees",
);
/// Slope `K1` of a linear rest curvature (1/L²): with `|K0| ≤ 3` and `|K0 + K1| ≤ 3`, `|K1| ≤ 6`.
pub const PRECURVATURE_SLOPE: Range = Range::new(-6.0, true, 6.0, true)
    .unit("1/L^2")
    .why("1/L^2; the rest curvature K0 + K1 s must stay within [-3, 3] along the rod");
/// Support compliance `c` (L/EI): 0 is a clamp; with 1000 the foot turns a thousand times more
/// than the rod bends, a hinge for every purpose (μ_max within 0.2 % of `c = 10⁴`).
pub const SUPPORT_COMPLIANCE: Range = Range::new(0.0, true, 1000.0, true).unit("L/EI").why(
    "L/(EI); 0 is a clamp, and with 1000 the foot turns a thousand times more than the rod bends: a hinge",
);
/// Surface inclination β (rad).
pub const SURFACE_ANGLE: Range = Range::new(-FRAC_PI_4, false, FRAC_PI_4, false)
    .symbol("(-pi/4, pi/4)")
    .unit("radians");
/// Radius `r` of the round tip (rod lengths): the rod's end carries a rigid disk of radius `r`
/// centred at its end point; 0 is the point tip. A whisker's tip is a few µm across on a rod of
/// tens of mm (r ~ 1e-4); 0.05 is a tip as wide as a tenth of the rod.
pub const TIP_RADIUS: Range = Range::new(0.0, true, 0.05, true).unit("rod lengths").why(
    "rod lengths; 0 is a point tip, and a disk wider than a tenth of the rod is no whisker tip",
);
/// Steepest surface slope `|h'|` a point tip takes (45°, the straight surface's inclination):
/// steeper, the tip would meet the surface edge-on where it turns.
pub const POINT_TIP_SLOPE: f64 = 1.0;
/// Steepest surface slope `|h'|` a round tip (tip radius > 0) takes: `tan 80°` (a disk meets a
/// surface at any angle; beyond 80° the surface's arc length per unit x grows without bound).
pub const ROUND_TIP_SLOPE: f64 = 5.671_281_819_617_707;

/// The steepest surface slope `|h'|` the tip of radius `tip_radius` takes: [`POINT_TIP_SLOPE`]
/// for a point tip, [`ROUND_TIP_SLOPE`] for a round one.
pub fn max_profile_slope(tip_radius: f64) -> f64 {
    if tip_radius > 0.0 {
        ROUND_TIP_SLOPE
    } else {
        POINT_TIP_SLOPE
    }
}

/// A tabulated reciprocal stiffness `b` (relative to the foot).
pub const TABLE_B: Range = Range::new(1e-8, true, 1e8, true);
/// Physical dimensions (mm, GPa, µm).
pub const PHYSICAL: Range = Range::new(0.0, false, f64::INFINITY, false);
/// Unit factors of physical-unit values (mm, N, N m): beyond them the values would overflow or
/// vanish.
pub const UNIT: Range = Range::new(1e-150, true, 1e150, true);

/// Solver tolerance.
pub const TOL: Range = Range::new(1e-15, true, 1e-2, true);
/// Segments of multiple shooting.
pub const SEGMENTS: Range = Range::count(1, 10_000);
/// Steps of the fixed-step RK4 integrator.
pub const RK4_STEPS: Range = Range::count(1, 10_000_000);

/// Largest foot displacement of a scan.
pub const D_MAX: Range = Range::new(0.0, false, 2.0, false).unit("rod lengths");
/// Output points of a scan, a whisk or a drag.
pub const POINTS: Range = Range::count(2, 1_000_000);
/// Output displacements given to a scan as a list (`scan_at`): at least one (an empty list has
/// no point to measure over).
pub const OUTPUT_DISPLACEMENTS: Range = Range::count(1, 1_000_000);
/// Samples of one kept shape.
pub const SHAPE_POINTS: Range = Range::count(2, 100_000);
/// Stiction coefficient μ0 (finite; no threshold is `None`).
pub const MU0: Range = Range::new(0.0, true, f64::INFINITY, false);
/// The slip displacement `d0` of `infer`, up to the scan's `d_max`.
pub fn d0(d_max: f64) -> Range {
    Range::new(0.0, true, d_max, true).unit("rod lengths")
}

/// Force angle α of a solve (rad): the contact pushes the tip down, `fy = −f cos α < 0`.
pub const ALPHA: Range = Range::new(-FRAC_PI_2, false, FRAC_PI_2, false)
    .symbol("(-pi/2, pi/2)")
    .unit("radians")
    .why("radians; the contact pushes the tip down, fy = -f cos(alpha) < 0");
/// Tip slope φ(1) of a solve (rad).
pub const PHI1: Range = Range::new(-PI, true, PI, true)
    .symbol("[-pi, pi]")
    .unit("radians");
/// Tip height of a solve.
pub const TIP_HEIGHT: Range = Range::new(-1.0, false, 1.0, false).unit("rod lengths");
/// Foot angle θ of a whisk (rad, clockwise): within a quarter turn either way.
pub const THETA: Range = Range::new(-FRAC_PI_2, false, FRAC_PI_2, false)
    .symbol("(-pi/2, pi/2)")
    .unit("radians")
    .why("the foot turned clockwise, within a quarter turn");
/// Rows of the dynamic drag's foot table (`DynDragOptions::foot_table`).
pub const FOOT_TABLE_ROWS: Range = Range::count(2, 100_000);
/// Whisks per time unit of the dynamic drag's whisking turn.
pub const WHISK_FREQUENCY: Range = Range::new(0.0, false, 1000.0, true).unit("per time unit");

/// The program's (and Python's) foot displacement a drag goes to unless asked otherwise (shorter
/// than [`DragOptions::default`](crate::DragOptions)'s 2: a few slips, quickly).
pub const DEFAULT_DRAG_D_MAX: f64 = 1.0;
/// The program's (and Python's) output points of a drag unless asked otherwise.
pub const DEFAULT_DRAG_POINTS: usize = 201;
/// Largest foot displacement of a drag.
pub const DRAG_D_MAX: Range = Range::new(0.0, false, 1000.0, true).unit("rod lengths");
/// Static friction coefficient μs of a drag.
pub const MU_S: Range = Range::new(0.0, true, 100.0, true);
/// Why kinetic friction stays below static (see [`kinetic_friction`]).
pub const STICK_SLIP: &str = "with mu_k = mu_s the tip would slide steadily, without stick-slip";
/// Kinetic friction coefficient μk of a drag: `[0, μs)`, kinetic friction below static.
pub fn kinetic_friction(mu_s: f64) -> Range {
    Range::new(0.0, true, mu_s, false).unit(
        "kinetic friction below static: with mu_k = mu_s the tip would slide steadily, without stick-slip",
    )
}
/// Most slips of a drag (a guard).
pub const MAX_SLIPS: Range = Range::count(1, 1_000_000);
/// Amplitude of a sinusoidal corrugation of the surface.
pub const CORRUGATION_AMPLITUDE: Range = Range::new(-0.2, true, 0.2, true).unit("rod lengths");
/// Wavelength of a corrugation.
pub const CORRUGATION_WAVELENGTH: Range = Range::new(0.01, true, 100.0, true).unit("rod lengths");
/// Period of a friction texture of patches: as a corrugation's wavelength (issue 33: a period
/// of 1e-9 was accepted and the drag, an event at every patch boundary, never ended).
pub const FRICTION_PERIOD: Range = Range::new(0.01, true, 1000.0, true).unit("rod lengths").why(
    "rod lengths; each patch boundary the tip passes is an event of the drag: a finer texture than 0.01 would take without end, and the model's tip is a point",
);
/// Width of one friction patch.
pub const PATCH_WIDTH: Range = Range::new(1e-3, true, f64::INFINITY, false).unit("rod lengths");
/// Phase of a corrugation at `x = 0`.
pub const CORRUGATION_PHASE: Range = Range::new(-1000.0, true, 1000.0, true).unit("radians");

/// Terms of a sum of sines (`[surface] kind = "sines"`).
pub const SINES_TERMS: Range = Range::count(1, 64);
/// Period of a grating (as a corrugation's wavelength).
pub const GRATING_PERIOD: Range = Range::new(0.01, true, 100.0, true).unit("rod lengths");
/// Peak-to-valley depth of a grating (twice a corrugation's largest amplitude).
pub const GRATING_DEPTH: Range = Range::new(0.0, false, 0.4, true).unit("rod lengths");
/// Flank angle of a grating, against the grating's mean line (the steepest slope also keeps
/// below the profiles' limit with the surface angle added).
pub const GRATING_FLANK_ANGLE: Range = Range::new(0.0, false, FRAC_PI_2, false)
    .symbol("(0, pi/2)")
    .unit("radians");
/// Radius of a grating's ridges and grooves: a sharp corner (0) has no tangent, and the contact
/// conditions need one.
pub const GRATING_RIDGE_RADIUS: Range = Range::new(0.0, false, 100.0, true).unit("rod lengths").why(
    "rod lengths; a sharp corner (0) has no tangent, and the contact conditions need the surface's tangent everywhere",
);
/// Lab x of the middle of a grating's ridge.
pub const GRATING_OFFSET: Range = Range::new(-1000.0, true, 1000.0, true).unit("rod lengths");
/// Largest deviation of a smoothed measured profile from its samples.
pub const PROFILE_TOLERANCE: Range = Range::new(0.0, true, 0.1, true).unit(
    "rod lengths; the smoothed profile passes within this of every measured height (0: through them)",
);
/// Samples of a measured profile (or a table): a spline needs 3.
pub const PROFILE_POINTS: Range = Range::count(3, 100_000);
/// Modes asked for at once (issue 32).
pub const MODE_COUNT: Range = Range::count(1, 50);
/// Tolerance of the modes' integrations along the rod.
pub const MODE_TOL: Range = Range::new(1e-14, true, 1e-6, true);
/// Inclination of the line a sliding tip moves on in the modes (rad).
pub const TIP_ANGLE: Range = Range::new(-FRAC_PI_2, true, FRAC_PI_2, true)
    .symbol("[-pi/2, pi/2]")
    .unit("radians");
/// Radius of gyration of the foot's section over the rod length (rotary inertia `g0²/b`).
pub const ROTARY_INERTIA: Range = Range::new(0.0, true, 0.1, true).unit("rod lengths");

/// Samples of a shape kept with each point of a scan, a whisk or a drag unless asked otherwise.
pub const DEFAULT_SHAPE_POINTS: usize = 41;
/// Samples of one solved shape unless asked otherwise.
pub const DEFAULT_SOLVE_SHAPE_POINTS: usize = 101;

/// Most scenes of one sweep grid (the product of its axes' lengths).
pub const MAX_SCENES: u64 = 1_000_000_000;
/// Memory budget of the values a run holds at once (bytes).
pub const MEMORY_BUDGET: u64 = 1 << 30;
/// Memory per kept shape sample (measured: 1e6 samples, 100 MB resident).
pub const BYTES_PER_SHAPE_SAMPLE: u64 = 100;
/// Memory per scan point (measured: a 1e5-point scan, 22 MB resident above start-up).
pub const BYTES_PER_SCAN_POINT: u64 = 250;
/// Worker threads per core beyond which more are not useful (a request is capped there).
pub const JOBS_PER_CORE: usize = 4;
/// Worker threads a sweep may be asked for (more than [`JOBS_PER_CORE`] per core are capped).
pub const JOBS: Range = Range::count(1, 65_536);

/// The fixed ranges by the name of the value they bound (the scene file's key or the option's
/// field), for front ends that list them (Python's `vibrissa.limits()`). Not listed: the ranges
/// that depend on another value ([`d0`]: the scan's `d_max`; [`kinetic_friction`]: `mu_s`).
pub fn named() -> Vec<(&'static str, Range)> {
    vec![
        ("eta", eta()),
        ("taper", TAPER),
        ("precurvature", PRECURVATURE),
        ("precurvature_slope", PRECURVATURE_SLOPE),
        ("support_compliance", SUPPORT_COMPLIANCE),
        ("surface_angle", SURFACE_ANGLE),
        ("tip_radius", TIP_RADIUS),
        ("table_b", TABLE_B),
        ("physical", PHYSICAL),
        ("tol", TOL),
        ("segments", SEGMENTS),
        ("rk4_steps", RK4_STEPS),
        ("d_max", D_MAX),
        ("points", POINTS),
        ("d", OUTPUT_DISPLACEMENTS),
        ("shape_points", SHAPE_POINTS),
        ("mu0", MU0),
        ("alpha", ALPHA),
        ("phi1", PHI1),
        ("tip_height", TIP_HEIGHT),
        ("theta", THETA),
        ("drag_d_max", DRAG_D_MAX),
        ("mu_s", MU_S),
        ("max_slips", MAX_SLIPS),
        ("corrugation_amplitude", CORRUGATION_AMPLITUDE),
        ("corrugation_wavelength", CORRUGATION_WAVELENGTH),
        ("corrugation_phase", CORRUGATION_PHASE),
        ("friction_period", FRICTION_PERIOD),
        ("patch_width", PATCH_WIDTH),
        ("jobs", JOBS),
    ]
}

/// `Ok` when `outputs` kept shapes of `samples` samples each fit [`MEMORY_BUDGET`]; else
/// [`VibrissaError::OutOfRange`] naming `name` (the samples per shape) and the most that fit.
pub fn check_shapes(name: &str, samples: usize, outputs: usize) -> Result<(), VibrissaError> {
    let need = samples as f64 * outputs as f64 * BYTES_PER_SHAPE_SAMPLE as f64;
    if need <= MEMORY_BUDGET as f64 {
        return Ok(());
    }
    let most = MEMORY_BUDGET / (outputs.max(1) as u64 * BYTES_PER_SHAPE_SAMPLE);
    Err(VibrissaError::OutOfRange {
        name: name.to_string(),
        value: samples as f64,
        range: format!(
            "[2, {most}] with {outputs} output points ({BYTES_PER_SHAPE_SAMPLE} bytes per shape \
             sample; the shapes must fit the memory budget of {} GB)",
            MEMORY_BUDGET as f64 / 1e9
        ),
    })
}

/// `v` with `p` significant digits, trailing zeros removed, scientific below 1e-4 and from 1e6
/// on (`digits(1e300, 6) = "1e300"`, never a 300-digit decimal).
pub fn digits(v: f64, p: usize) -> String {
    if !v.is_finite() {
        return if v.is_nan() {
            "NaN".into()
        } else if v > 0.0 {
            "inf".into()
        } else {
            "-inf".into()
        };
    }
    if v == 0.0 {
        return "0".into();
    }
    let p = p.clamp(1, 17);
    let sci = format!("{:.*e}", p - 1, v);
    let (mant, exp) = sci.split_once('e').unwrap_or((&sci, "0"));
    let exp: i32 = exp.parse().unwrap_or(0);
    let mant = if mant.contains('.') {
        mant.trim_end_matches('0').trim_end_matches('.')
    } else {
        mant
    };
    if !(-4..6).contains(&exp) {
        return format!("{mant}e{exp}");
    }
    // plain decimal from the rounded mantissa
    let ds: String = mant.chars().filter(|c| c.is_ascii_digit()).collect();
    let mut out = String::new();
    if mant.starts_with('-') {
        out.push('-');
    }
    if exp < 0 {
        out.push_str("0.");
        for _ in 0..(-exp - 1) {
            out.push('0');
        }
        out.push_str(&ds);
    } else {
        let int_len = exp as usize + 1;
        if ds.len() <= int_len {
            out.push_str(&ds);
            for _ in ds.len()..int_len {
                out.push('0');
            }
        } else {
            out.push_str(&ds[..int_len]);
            out.push('.');
            out.push_str(&ds[int_len..]);
        }
    }
    out
}

/// Significant digits needed so that `v` and every bound print differently (at least 6).
pub fn digits_to_decide(v: f64, bounds: &[f64]) -> usize {
    let mut p = 6;
    while p < 17 {
        let sv = digits(v, p);
        if bounds
            .iter()
            .all(|&b| b == v || !b.is_finite() || digits(b, p) != sv)
        {
            break;
        }
        p += 1;
    }
    p
}

#[cfg(test)]
mod tests {
    #[test]
    fn named_ranges_are_unique_and_ordered() {
        let all = named();
        let mut names: Vec<&str> = all.iter().map(|(n, _)| *n).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), all.len());
        for (n, r) in &all {
            assert!(r.lo <= r.hi, "{n}");
        }
        let (_, sp) = all.iter().find(|(n, _)| *n == "shape_points").unwrap();
        assert_eq!(*sp, SHAPE_POINTS);
    }

    use super::*;

    #[test]
    fn ranges_are_written_as_the_messages_say_them() {
        assert_eq!(TAPER.text(6), "[0.01, 1]");
        assert_eq!(
            SURFACE_ANGLE.text(6),
            "(-pi/4, pi/4) = (-0.785398, 0.785398)"
        );
        assert_eq!(POINTS.text(6), "[2, 1000000]");
        assert_eq!(TOL.text(6), "[1e-15, 0.01]");
        assert_eq!(MU0.text(6), "[0, inf)");
        // a value next to an end gets the digits that tell them apart
        assert_eq!(D_MAX.digits_for(1.9999999), 8);
        let e = SUPPORT_COMPLIANCE.check("support compliance", 2000.0);
        assert_eq!(
            e.unwrap_err().to_string(),
            "support compliance = 2000 is outside the valid range [0, 1000] (L/EI)"
        );
        assert!(kinetic_friction(0.5).check("mu_k", 0.5).is_err());
        assert!(kinetic_friction(0.5).check("mu_k", 0.49).is_ok());
        assert!(MU0.check("mu0", f64::INFINITY).is_err());
        assert!(TAPER.check("taper ratio", f64::NAN).is_err());
    }
}
