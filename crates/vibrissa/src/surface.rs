//! Surfaces that are not one straight line, and friction that changes along them (issue 21).
//!
//! A surface profile is a height function of the lab position `x` (the foot at `x = 0` when
//! `d = 0`, the foot's height `y = 0`):
//!
//! ```text
//!     h(x) = η + x·tan β + shape(x)
//!     shape: sine       A·sin(2πx/λ + φ0)                       (a corrugation)
//!            circle     R − √(R² − (x − x0)²)                   (the lower arc of a cylinder of
//!                                                               radius R resting at (x0, η))
//!            table      natural cubic spline through (x_i, y_i)  (C², zero curvature at the ends)
//!            sines      Σ A_i·sin(2πx/λ_i + φ_i)                 (a sum of sines, module `sines`)
//!            grating    flanks ±α, round ridges and grooves     (module `grating`)
//!            measured   the smoothing spline of a file's samples (module `measured`)
//! ```
//!
//! The rod stays below the surface (`y ≤ h(x)` on its free parts). The surface's unit normal into
//! the obstacle is `n(x) = (−sin θ, cos θ)`, its tangent back against the drag `t = (−cos θ,
//! −sin θ)`, `θ = atan h'(x)`; contact forces are resolved in that local frame (normal `N`,
//! friction `T`). Arc length along the surface, `σ(x) = ∫₀ˣ √(1 + h'²) dx`, measures where a stuck
//! contact holds and how far a rolling one has rolled; it is integrated by 10-point
//! Gauss–Legendre on panels (64 per period of a corrugation, 8 per table interval, 256 over a
//! circle's arc), exact to rounding because the integrand is analytic inside every panel.
//!
//! Slopes are limited to `|h'| < 1` (45°, as the straight surface's inclination): the circle and
//! the table end where the surface ends (a contact that reaches the end stops the march), and a
//! corrugation with `|tan β| + 2πA/λ ≥ 1` is refused (a sum of sines with `|tan β| + Σ 2π|A_i|/λ_i
//! ≥ 1`, a grating with `|tan β| + tan α ≥ 1`; a measured profile as a table, after smoothing).
//!
//! Friction profiles give the static and kinetic coefficients `μs(x) ≥ μk(x) ≥ 0` at the lab
//! position of a contact point: uniform, a table (piecewise linear in `x`, constant beyond its
//! ends), or periodic patches (a texture: piecewise constant, patch `i` on `[x_i, x_{i+1})` of
//! each period). At a patch boundary a point takes the value of the patch on the side given
//! (the side a slip came from decides which patch then holds the tip).

use crate::VibrissaError;
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// The surface's shape in a scene file (`[surface]`). Heights are relative to `eta` and add to
/// the inclination `surface_angle` (`h(x) = eta + x·tan(surface_angle) + shape(x)`), except for
/// `line`, today's surface: the straight line through the start's contact point at height `eta`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum SurfaceProfile {
    /// The straight line through the start's contact point (at height `eta`), inclined by
    /// `surface_angle` (the default).
    Line {},
    /// A corrugation `amplitude·sin(2π x / wavelength + phase)`.
    Sine {
        /// Amplitude `A` (rod lengths), `|A| ≤ 0.2`.
        amplitude: f64,
        /// Wavelength `λ > 0` (rod lengths), in `[0.01, 100]`.
        wavelength: f64,
        /// Phase `φ0` (rad) at `x = 0`.
        #[serde(default)]
        phase: f64,
    },
    /// The lower arc of a circle (a cylinder's cross-section above the rod) of radius `radius`
    /// whose lowest point is at `(x0, eta)`; it ends where its slope reaches 45°.
    Circle {
        /// Radius `R` (rod lengths), in `[0.05, 1000]`.
        radius: f64,
        /// Lab `x` of the lowest point.
        #[serde(default)]
        x0: f64,
    },
    /// Heights `y_i` at lab positions `x_i` (strictly increasing, at least 3), interpolated by the
    /// natural cubic spline (continuous curvature, zero curvature at the ends); the surface ends
    /// at the table's ends.
    Table {
        /// Lab positions, strictly increasing.
        x: Vec<f64>,
        /// Heights relative to `eta`.
        y: Vec<f64>,
    },
    /// A sum of sines `Σ amplitude[i]·sin(2π x / wavelength[i] + phase[i])`: a texture's
    /// spectrum, or a corrugation with its harmonics. Each term's ranges are the corrugation's;
    /// the steepest slope `|tan(surface_angle)| + Σ 2π|amplitude[i]|/wavelength[i]` stays below
    /// 1 (45°).
    Sines {
        /// Amplitudes (rod lengths), each in `[-0.2, 0.2]`; 1 to 64 terms.
        amplitude: Vec<f64>,
        /// Wavelengths (rod lengths), each in `[0.01, 100]`.
        wavelength: Vec<f64>,
        /// Phases (rad) at `x = 0`, one per term or none (all 0).
        #[serde(default)]
        phase: Vec<f64>,
    },
    /// A periodic grating: straight flanks at ±`flank_angle` joined by circular arcs of radius
    /// `ridge_radius` at the ridges and grooves (a rounded triangle), with flat lands between
    /// when both the depth and the flank angle are given and leave room for them (module
    /// docs of `grating` in the repository). Its mean height is `eta`; a ridge (the part nearest
    /// the rod, its lowest point at `eta − depth/2`) is centred at `x = offset`. The flank's
    /// slope with the surface angle's, `|tan(surface_angle)| + tan(flank_angle)`, stays below 1.
    Grating {
        /// Period (rod lengths), in `[0.01, 100]`.
        period: f64,
        /// Peak-to-valley depth (rod lengths), in `(0, 0.4]`; without it, the rounded triangle
        /// of `flank_angle`.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        depth: Option<f64>,
        /// Flank angle against the mean line (rad), in `(0, pi/2)`; without it, the rounded
        /// triangle of `depth`.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        flank_angle: Option<f64>,
        /// Radius of the ridges and grooves (rod lengths), in `(0, 100]`, small enough to fit.
        ridge_radius: f64,
        /// Lab `x` of the middle of a ridge (rod lengths), in `[-1000, 1000]`.
        #[serde(default)]
        offset: f64,
    },
    /// A measured height profile: the samples `x, h` of a file (two columns, any spacing and
    /// order; module docs of `measured` in the repository), smoothed by the smoothest natural
    /// cubic spline within `tolerance` of every sample (Reinsch's smoothing spline); the surface
    /// ends at the file's first and last `x`. Slopes as a table's.
    Measured {
        /// The file (a relative path: from the working directory; the program takes it from
        /// the scene file's directory).
        file: std::path::PathBuf,
        /// Largest deviation of the smoothed profile from a sample (rod lengths), in `[0, 0.1]`;
        /// 0 interpolates.
        tolerance: f64,
    },
}

/// The friction along the surface in a scene file (`[friction]`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum FrictionProfile {
    /// None in the scene: the command's coefficients (the default).
    None {},
    /// The same everywhere.
    Uniform {
        /// Static coefficient μs.
        mu_s: f64,
        /// Kinetic coefficient μk < μs.
        mu_k: f64,
    },
    /// Tables at lab positions `x` (strictly increasing), piecewise linear, constant beyond the
    /// ends.
    Table {
        /// Lab positions.
        x: Vec<f64>,
        /// μs at each.
        mu_s: Vec<f64>,
        /// μk at each (< μs).
        mu_k: Vec<f64>,
    },
    /// A periodic texture of patches: patch `i` covers `[x_i, x_{i+1})` of each period
    /// (`0 = x_0 < x_1 < … < period`), shifted by `offset`.
    Patches {
        /// Period (rod lengths), in `[0.01, 1000]`; each patch at least 1e-3 wide.
        period: f64,
        /// Patch starts within the period, from 0, strictly increasing, below `period`.
        x: Vec<f64>,
        /// μs of each patch.
        mu_s: Vec<f64>,
        /// μk of each patch (`μk < μs`).
        mu_k: Vec<f64>,
        /// Lab position of the start of patch 0.
        #[serde(default)]
        offset: f64,
    },
}

impl Default for SurfaceProfile {
    fn default() -> Self {
        SurfaceProfile::Line {}
    }
}

impl Default for FrictionProfile {
    fn default() -> Self {
        FrictionProfile::None {}
    }
}

/// Largest slope `|h'|` of a profile under a point tip (45°, as the straight surface's
/// inclination; a round tip takes [`crate::limits::ROUND_TIP_SLOPE`]).
pub const MAX_PROFILE_SLOPE: f64 = crate::limits::POINT_TIP_SLOPE;

/// The width of the fixed panels of [`Height::arc_scaled`]: about a thousandth of the rod's
/// length, a tenth of the shortest corrugation wavelength the limits allow (0.01).
const SCALED_PANEL: f64 = 1.0 / 1024.0;

/// The slope limit `max` in words: `1, 45 degrees`.
fn slope_limit_text(max: f64) -> String {
    if max == MAX_PROFILE_SLOPE {
        "1, 45 degrees".into()
    } else {
        format!("{max:.6}, {:.0} degrees", max.atan().to_degrees())
    }
}

/// What a refusal at the point tip's slope limit suggests: a round tip.
fn round_tip_hint(max: f64) -> &'static str {
    if max == MAX_PROFILE_SLOPE {
        "; a round tip, tip radius > 0 (--tip-radius, scene key tip_radius), takes slopes up \
         to 80 degrees"
    } else {
        ""
    }
}

#[derive(Clone, Debug, PartialEq, Serialize)]
enum Shape {
    Sine {
        a: f64,
        k: f64,
        phase: f64,
    },
    Circle {
        r: f64,
        x0: f64,
    },
    Spline {
        x: Vec<f64>,
        y: Vec<f64>,
        m: Vec<f64>,
    },
    Sines(crate::sines::Sines),
    Grating(Box<crate::grating::Grating>),
}

/// A resolved height profile (see the module docs): `h`, `h'`, `h''`, its arc length and where
/// it exists.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Height {
    shape: Shape,
    eta: f64,
    slope: f64,
    /// Where the surface exists (lab x); `±inf` for a corrugation.
    lo: f64,
    hi: f64,
    /// Arc length: panel breakpoints (over one period, or the domain) and σ at each.
    panels: Vec<f64>,
    cum: Vec<f64>,
    /// Arc length of one period (corrugation), else 0.
    period_arc: f64,
    /// The tabulated arc length at `x = 0`, where `σ` starts (kept: every `σ` needs it).
    arc0: f64,
}

/// A sine corrugation's shape, its parameters and steepest slope (with the surface's own slope
/// `slope`) checked; errors name the scene key.
fn sine(
    amplitude: f64,
    wavelength: f64,
    phase: f64,
    slope: f64,
    max_slope: f64,
) -> Result<Shape, VibrissaError> {
    if !(amplitude.is_finite() && amplitude.abs() <= 0.2) {
        return Err(VibrissaError::range(
            "surface.amplitude",
            amplitude,
            "[-0.2, 0.2] rod lengths",
        ));
    }
    if !(wavelength.is_finite() && (0.01..=100.0).contains(&wavelength)) {
        return Err(VibrissaError::range(
            "surface.wavelength",
            wavelength,
            "[0.01, 100] rod lengths",
        ));
    }
    if !phase.is_finite() {
        return Err(VibrissaError::range("surface.phase", phase, "finite"));
    }
    let k = std::f64::consts::TAU / wavelength;
    let steepest = slope.abs() + amplitude.abs() * k;
    if steepest >= max_slope {
        return Err(VibrissaError::range(
            "surface.amplitude",
            amplitude,
            format!(
                "|amplitude| < {:.6} for this wavelength and surface_angle (the \
                     steepest slope |tan(surface_angle)| + 2 pi |amplitude| / wavelength \
                     = {steepest:.6} must stay below {}{})",
                ((max_slope - slope.abs()) / k).max(0.0),
                slope_limit_text(max_slope),
                round_tip_hint(max_slope)
            ),
        ));
    }
    Ok(Shape::Sine {
        a: amplitude,
        k,
        phase,
    })
}

impl Height {
    /// The profile of `p` at base height `eta` and inclination `beta` (`None` for a line);
    /// errors name the scene key.
    pub fn new(p: &SurfaceProfile, eta: f64, beta: f64) -> Result<Option<Height>, VibrissaError> {
        Height::for_tip(p, eta, beta, 0.0)
    }

    /// As [`Height::new`], for a rod whose tip has the radius `tip_radius`: the steepest slope
    /// it takes is [`crate::limits::max_profile_slope`]'s (45° for a point tip, 80° for a round
    /// one; a circle still ends at 45°), and a round tip must fit the surface's concave parts
    /// ([`Height::check_tip`]).
    pub fn for_tip(
        p: &SurfaceProfile,
        eta: f64,
        beta: f64,
        tip_radius: f64,
    ) -> Result<Option<Height>, VibrissaError> {
        let max_slope = crate::limits::max_profile_slope(tip_radius);
        let slope = beta.tan();
        let (shape, lo, hi) = match p {
            SurfaceProfile::Line {} => return Ok(None),
            &SurfaceProfile::Sine {
                amplitude,
                wavelength,
                phase,
            } => (
                sine(amplitude, wavelength, phase, slope, max_slope)?,
                f64::NEG_INFINITY,
                f64::INFINITY,
            ),
            &SurfaceProfile::Circle { radius, x0 } => {
                if !(radius.is_finite() && (0.05..=1000.0).contains(&radius)) {
                    return Err(VibrissaError::range(
                        "surface.radius",
                        radius,
                        "[0.05, 1000] rod lengths",
                    ));
                }
                if !x0.is_finite() {
                    return Err(VibrissaError::range("surface.x0", x0, "finite"));
                }
                // where h' = u/√(R² − u²) + tan β reaches ±1
                let end = |t: f64| radius * t / (1.0 + t * t).sqrt();
                let (lo, hi) = (
                    x0 + end(-MAX_PROFILE_SLOPE - slope),
                    x0 + end(MAX_PROFILE_SLOPE - slope),
                );
                if !(lo < x0 && hi > x0) {
                    return Err(VibrissaError::range(
                        "surface_angle",
                        beta,
                        "(-pi/4, pi/4) radians",
                    ));
                }
                (Shape::Circle { r: radius, x0 }, lo, hi)
            }
            SurfaceProfile::Table { x, y } => {
                let shape = spline(x, y)?;
                let (lo, hi) = (x[0], x[x.len() - 1]);
                (shape, lo, hi)
            }
            SurfaceProfile::Sines {
                amplitude,
                wavelength,
                phase,
            } => (
                Shape::Sines(crate::sines::Sines::new(
                    amplitude, wavelength, phase, slope, max_slope,
                )?),
                f64::NEG_INFINITY,
                f64::INFINITY,
            ),
            &SurfaceProfile::Grating {
                period,
                depth,
                flank_angle,
                ridge_radius,
                offset,
            } => (
                Shape::Grating(Box::new(grating(
                    period,
                    depth,
                    flank_angle,
                    ridge_radius,
                    offset,
                    (slope, max_slope),
                )?)),
                f64::NEG_INFINITY,
                f64::INFINITY,
            ),
            SurfaceProfile::Measured { file, tolerance } => {
                crate::limits::PROFILE_TOLERANCE.check("surface.tolerance", *tolerance)?;
                let (x, y) = crate::measured::read_profile(file)?;
                let (g, _) = crate::measured::smooth(&x, &y, *tolerance);
                let shape = spline(&x, &g)?;
                (shape, x[0], x[x.len() - 1])
            }
        };
        if !(eta.is_finite() && slope.is_finite()) {
            return Err(VibrissaError::range("eta", eta, "finite"));
        }
        let mut h = Height {
            shape,
            eta,
            slope,
            lo,
            hi,
            panels: Vec::new(),
            cum: Vec::new(),
            period_arc: 0.0,
            arc0: 0.0,
        };
        if let Shape::Spline { x, .. } = &h.shape {
            // the steepest slope of each interval: its ends and the vertex of its quadratic
            let x = x.clone();
            for w in x.windows(2) {
                let mut worst = h.jet(w[0]).1.abs().max(h.jet(w[1]).1.abs());
                // h'' changes sign inside: the vertex of h' by bisection on h''
                let (g0, g1) = (h.jet(w[0]).2, h.jet(w[1]).2);
                if g0 * g1 < 0.0 {
                    let (mut a, mut b) = (w[0], w[1]);
                    for _ in 0..60 {
                        let c = 0.5 * (a + b);
                        if h.jet(c).2 * g0 > 0.0 {
                            a = c;
                        } else {
                            b = c;
                        }
                    }
                    worst = worst.max(h.jet(0.5 * (a + b)).1.abs());
                }
                if worst >= max_slope {
                    return Err(VibrissaError::InvalidTable {
                        name: "surface".into(),
                        reason: format!(
                            "the spline through the table (with surface_angle) has the slope \
                             {worst:.6} between x = {} and x = {}; slopes must stay below {}{}",
                            w[0],
                            w[1],
                            if max_slope == MAX_PROFILE_SLOPE {
                                "1 (45 degrees)".to_string()
                            } else {
                                slope_limit_text(max_slope)
                            },
                            round_tip_hint(max_slope)
                        ),
                    });
                }
            }
        }
        h.tabulate_arc();
        h.arc0 = h.arc_from_start(0.0);
        Ok(Some(h))
    }

    /// Whether a tip of radius `tip_radius` may touch this surface: its steepest slope within
    /// [`crate::limits::max_profile_slope`] (a surface made for a round tip is refused to a
    /// point tip where it is steeper than 45°), and a round tip no wider than the surface's
    /// concave parts are round (`r·max(−h''·cos³θ) < 1`: else the disk, centred on the surface
    /// offset by `r`, would touch a groove at two points). Both found on 4096 samples of a
    /// period (a corrugation, a grating), of the domain (a table, a circle), or of `[−2, 4]`
    /// (a sum of sines); errors name the tip radius and where the surface refuses it.
    pub fn check_tip(&self, tip_radius: f64) -> Result<(), VibrissaError> {
        let (a, b) = match &self.shape {
            &Shape::Sine { k, phase, .. } => (-phase / k, (std::f64::consts::TAU - phase) / k),
            Shape::Grating(g) => (g.offset, g.offset + g.period),
            Shape::Sines(_) => (-2.0, 4.0),
            _ => (self.lo, self.hi),
        };
        let n = 4096;
        let (mut steep, mut x_steep) = (0.0f64, a);
        let (mut concave, mut x_concave) = (0.0f64, a);
        for i in 0..=n {
            let x = a + (b - a) * i as f64 / n as f64;
            let (_, d, dd) = self.jet(x);
            if d.abs() > steep {
                (steep, x_steep) = (d.abs(), x);
            }
            let c = -dd / (1.0 + d * d).powf(1.5);
            if c > concave {
                (concave, x_concave) = (c, x);
            }
        }
        let max = crate::limits::max_profile_slope(tip_radius);
        if steep >= max {
            return Err(VibrissaError::range(
                "tip radius",
                tip_radius,
                format!(
                    "(0, {}] on this surface: its slope reaches |h'| = {steep:.6} ({:.1} degrees) \
                     at x = {x_steep:.6}, steeper than a point tip takes (1, 45 degrees); a \
                     round tip (--tip-radius, scene key tip_radius) takes slopes up to 80 degrees",
                    crate::limits::TIP_RADIUS.hi,
                    steep.atan().to_degrees()
                ),
            ));
        }
        if tip_radius > 0.0 && tip_radius * concave >= 1.0 {
            return Err(VibrissaError::range(
                "tip radius",
                tip_radius,
                format!(
                    "[0, {:.6}) on this surface: its concave part at x = {x_concave:.6} is \
                     rounded with the radius {:.6}, and a wider round tip would touch it at two \
                     points (a groove narrower than the tip)",
                    1.0 / concave,
                    1.0 / concave
                ),
            ));
        }
        Ok(())
    }

    /// `(h, h', h'')` at lab `x` (beyond the ends of a circle or a table: continued along the end
    /// tangent, so that solver iterates stay finite; the surface itself ends there).
    pub fn jet(&self, x: f64) -> (f64, f64, f64) {
        self.jet_scaled(x, 1.0)
    }

    /// As [`Height::jet`] with the shape scaled by `amp` (`eta + x·tan β + amp·shape(x)`).
    pub fn jet_scaled(&self, x: f64, amp: f64) -> (f64, f64, f64) {
        if x < self.lo || x > self.hi {
            let e = if x < self.lo { self.lo } else { self.hi };
            let (h, d, _) = self.jet_scaled(e, amp);
            return (h + d * (x - e), d, 0.0);
        }
        let (v, d, dd) = match &self.shape {
            &Shape::Sine { a, k, phase } => {
                let (s, c) = (k * x + phase).sin_cos();
                (a * s, a * k * c, -a * k * k * s)
            }
            &Shape::Circle { r, x0 } => {
                let u = x - x0;
                let w = (r * r - u * u).sqrt();
                (r - w, u / w, r * r / (w * w * w))
            }
            Shape::Spline { x: xs, y, m } => crate::spline::jet(xs, y, m, x),
            Shape::Sines(s) => s.jet(x),
            Shape::Grating(g) => g.jet(x),
        };
        (
            self.eta + self.slope * x + amp * v,
            self.slope + amp * d,
            amp * dd,
        )
    }

    /// `h(x)`.
    pub fn h(&self, x: f64) -> f64 {
        self.jet(x).0
    }

    /// Whether the surface exists at `x`.
    pub fn covers(&self, x: f64) -> bool {
        x >= self.lo && x <= self.hi
    }

    /// Where the surface exists, `(lo, hi)` (lab x; infinite for a corrugation).
    pub fn domain(&self) -> (f64, f64) {
        (self.lo, self.hi)
    }

    /// The surface's inclination `θ = atan h'` at `x` and `dθ/dx`.
    pub fn angle(&self, x: f64) -> (f64, f64) {
        self.angle_scaled(x, 1.0)
    }

    /// As [`Height::angle`] with the shape scaled by `amp`.
    pub fn angle_scaled(&self, x: f64, amp: f64) -> (f64, f64) {
        let (_, d, dd) = self.jet_scaled(x, amp);
        (d.atan(), dd / (1.0 + d * d))
    }

    /// The shape alone (without `η` and the trend) and its first derivative at `x` (continued
    /// as [`Height::jet`] beyond the ends).
    pub fn shape(&self, x: f64) -> (f64, f64) {
        let (h1, d1, _) = self.jet_scaled(x, 1.0);
        let (h0, d0, _) = self.jet_scaled(x, 0.0);
        (h1 - h0, d1 - d0)
    }

    /// The straight trend's slope `tan β`.
    pub fn trend(&self) -> f64 {
        self.slope
    }

    /// `dσ/dx = √(1 + h'²)` at `x` (as [`Height::sigma`] gives it).
    pub(crate) fn speed(&self, x: f64) -> f64 {
        let d = self.jet(x).1;
        (1.0 + d * d).sqrt()
    }

    fn tabulate_arc(&mut self) {
        let (a, b, n) = match &self.shape {
            Shape::Sine { k, .. } => (0.0, std::f64::consts::TAU / k, 64),
            Shape::Circle { .. } => (self.lo, self.hi, 256),
            Shape::Spline { x, .. } => {
                let mut p = Vec::new();
                for w in x.windows(2) {
                    for j in 0..8 {
                        p.push(w[0] + (w[1] - w[0]) * j as f64 / 8.0);
                    }
                }
                p.push(x[x.len() - 1]);
                self.set_panels(p);
                return;
            }
            // their own arc lengths
            Shape::Sines(_) | Shape::Grating(_) => return,
        };
        let p: Vec<f64> = (0..=n).map(|i| a + (b - a) * i as f64 / n as f64).collect();
        self.set_panels(p);
        if let Shape::Sine { .. } = self.shape {
            self.period_arc = self.cum[self.cum.len() - 1];
        }
    }

    fn set_panels(&mut self, p: Vec<f64>) {
        let mut cum = vec![0.0; p.len()];
        for i in 1..p.len() {
            cum[i] = cum[i - 1] + crate::gauss::gauss10(p[i - 1], p[i], |x| self.speed(x));
        }
        self.panels = p;
        self.cum = cum;
    }

    /// Arc length from the panels' start to `x` (inside the tabulated span).
    fn arc_in(&self, x: f64) -> f64 {
        let p = &self.panels;
        let i = p.partition_point(|&t| t <= x).clamp(1, p.len() - 1) - 1;
        self.cum[i] + crate::gauss::gauss10(p[i], x, |t| self.speed(t))
    }

    /// Arc length `σ(x)` along the surface from `x = 0` (signed), and `dσ/dx = √(1 + h'²)`.
    pub fn sigma(&self, x: f64) -> (f64, f64) {
        (self.arc_from_start(x) - self.arc0, self.speed(x))
    }

    /// Arc length `σ(x)` and `dσ/dx` on the surface with its shape scaled by `amp` (as
    /// [`Height::jet_scaled`]; the start grows the shape), from its value `sa` at `xa`
    /// ([`Height::arc_scaled`]).
    pub(crate) fn sigma_scaled_from(&self, xa: f64, sa: f64, x: f64, amp: f64) -> (f64, f64) {
        (sa + self.arc_scaled(xa, x, amp), self.speed_scaled(x, amp))
    }

    /// `∫ √(1 + h'²) dx` from `a` to `b` on the surface scaled by `amp`: 10-point Gauss on the
    /// panels of a fixed grid of width [`SCALED_PANEL`] = 1/1024 (`[k·w, (k+1)·w]`, cut at `a`
    /// and `b`), so that the integral to `x` is smooth in `x`. On a sine of the shortest
    /// wavelength, 0.01, a panel is a tenth of the period, where the rule is exact to rounding;
    /// across the kinks of `h''` (a grating's rounded corners, a spline's knots) its error is of
    /// the panel's cube times the jump. It serves the start's growth only: the grown state is
    /// solved again on [`Height::sigma`] at the full amplitude.
    pub(crate) fn arc_scaled(&self, a: f64, b: f64, amp: f64) -> f64 {
        let (lo, hi, sign) = if a <= b { (a, b, 1.0) } else { (b, a, -1.0) };
        let w = SCALED_PANEL;
        let speed = |t: f64| self.speed_scaled(t, amp);
        let (mut k, mut sum, mut x) = ((lo / w).floor(), 0.0, lo);
        while x < hi {
            let next = ((k + 1.0) * w).min(hi);
            if next > x {
                sum += crate::gauss::gauss10(x, next, speed);
            }
            x = next;
            k += 1.0;
        }
        sign * sum
    }

    /// `dσ/dx` on the surface scaled by `amp`.
    pub(crate) fn speed_scaled(&self, x: f64, amp: f64) -> f64 {
        let d = self.jet_scaled(x, amp).1;
        (1.0 + d * d).sqrt()
    }

    /// The tabulated arc length at lab `x` (from the panels' start, or the shape's own).
    fn arc_from_start(&self, x: f64) -> f64 {
        {
            match &self.shape {
                Shape::Sines(s) => s.arc(x),
                Shape::Grating(g) => g.arc(x),
                &Shape::Sine { k, .. } => {
                    let period = std::f64::consts::TAU / k;
                    let n = (x / period).floor();
                    n * self.period_arc + self.arc_in(x - n * period)
                }
                _ => {
                    if x < self.lo {
                        self.arc_in(self.lo) - (self.lo - x) * self.speed(self.lo)
                    } else if x > self.hi {
                        self.arc_in(self.hi) + (x - self.hi) * self.speed(self.hi)
                    } else {
                        self.arc_in(x)
                    }
                }
            }
        }
    }
}

/// Where a round tip touches a curved surface: the contact point `x_c` of the disk of radius `r`
/// centred at the rod's end `P` (lab `px`) on the surface at amplitude `amp`, the surface's angle
/// `θ` and `dθ/dx` there, and `J = 1 + r cos θ·θ'`, the rate of the centre's `x` along the
/// contact point's (`P = C − r·n(x_c)`, so `P_x = x_c + r sin θ(x_c)`; the centre's curve, the
/// surface offset by `r`, has the slope `tan θ(x_c)` there).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Disk {
    pub xc: f64,
    pub th: f64,
    pub dth: f64,
    pub jac: f64,
}

/// The contact point of the disk of radius `r` centred at lab `px` on `h` (amplitude `amp`):
/// Newton on `g(x_c) = x_c + r sin θ(x_c) − px = 0`, kept inside the bracket the signs of `g`
/// narrow. `None` where `J ≤ 0` (the disk is wider than a concave part of the surface is round:
/// it would touch at a second point) or Newton fails.
///
/// `|r sin θ| ≤ r`, so the root lies in `[px − r, px + r]`, and `g` rises at the rate `J` where
/// the disk fits. A Newton step that leaves the bracket is replaced by its midpoint: where the
/// disk barely fits (`J` about 0.03 under the crests of a corrugation about as round as the
/// disk, `J` near 2 beside them) plain Newton's steps could leave the bracket, and states of
/// a drag over such a corrugation had no contact point (issue 31's drag property, seed 21: a
/// residual NaN, slips off their energy balance by 1e-6). Where Newton stays inside, its
/// iterates are the plain ones.
pub(crate) fn disk_on_curve(h: &Height, r: f64, px: f64, amp: f64) -> Option<Disk> {
    let at = |xc: f64| {
        let (th, dth) = h.angle_scaled(xc, amp);
        Disk {
            xc,
            th,
            dth,
            jac: 1.0 + r * th.cos() * dth,
        }
    };
    let (mut lo, mut hi) = (px - r, px + r);
    let mut dk = at(px - r * h.angle_scaled(px, amp).0.sin());
    for _ in 0..DISK_ITERATIONS {
        if dk.jac.is_nan() || dk.jac <= 0.0 {
            return None;
        }
        let g = dk.xc + r * dk.th.sin() - px;
        let step = g / dk.jac;
        if step.abs() <= 1e-15 * (1.0 + px.abs()) {
            dk = at(dk.xc - step);
            return (dk.jac > 0.0).then_some(dk);
        }
        if g < 0.0 {
            lo = lo.max(dk.xc);
        } else {
            hi = hi.min(dk.xc);
        }
        let newton = dk.xc - step;
        dk = at(if newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        });
    }
    None
}

/// Iterations of [`disk_on_curve`] (bisection alone halves the bracket of width `2r ≤ 0.1` to
/// below 1e-15 in 47).
const DISK_ITERATIONS: usize = 100;

/// The grating of a scene's `[surface]` on the trend `tan β = slope`, validated (the ranges of
/// module `limits`, then the fit of its pieces and its steepest slope); errors name the key.
fn grating(
    period: f64,
    depth: Option<f64>,
    flank_angle: Option<f64>,
    ridge_radius: f64,
    offset: f64,
    (slope, max_slope): (f64, f64),
) -> Result<crate::grating::Grating, VibrissaError> {
    use crate::limits;
    limits::GRATING_PERIOD.check("surface.period", period)?;
    if let Some(d) = depth {
        limits::GRATING_DEPTH.check("surface.depth", d)?;
    }
    if let Some(a) = flank_angle {
        limits::GRATING_FLANK_ANGLE.check("surface.flank_angle", a)?;
    }
    limits::GRATING_RIDGE_RADIUS.check("surface.ridge_radius", ridge_radius)?;
    limits::GRATING_OFFSET.check("surface.offset", offset)?;
    let g = crate::grating::Grating::new(period, depth, flank_angle, ridge_radius, offset, slope)?;
    if let (None, Some(a)) = (depth, flank_angle) {
        // the rounded triangle's own depth
        if !limits::GRATING_DEPTH.contains(g.depth) {
            return Err(VibrissaError::range(
                "surface.flank_angle",
                a,
                format!(
                    "angles whose rounded triangle of period {period} is at most {} deep (this \
                     one is {:.6}); give a smaller flank_angle, or the depth too (then with \
                     flat lands)",
                    limits::GRATING_DEPTH.hi,
                    g.depth
                ),
            ));
        }
    }
    let steepest = slope.abs() + g.flank_angle.tan();
    if steepest.is_nan() || steepest >= max_slope {
        let (key, value) = match flank_angle {
            Some(a) => ("surface.flank_angle", a),
            None => ("surface.depth", g.depth),
        };
        return Err(VibrissaError::range(
            key,
            value,
            format!(
                "a grating whose steepest slope |tan(surface_angle)| + tan(flank_angle) = \
                 {steepest:.6} (flank_angle {:.6} rad) stays below {}{}",
                g.flank_angle,
                if max_slope == MAX_PROFILE_SLOPE {
                    "1 (45 degrees)".to_string()
                } else {
                    slope_limit_text(max_slope)
                },
                round_tip_hint(max_slope)
            ),
        ));
    }
    Ok(g)
}

/// The natural cubic spline through a table (second derivatives `m`, zero at the ends).
fn spline(x: &[f64], y: &[f64]) -> Result<Shape, VibrissaError> {
    let bad = |reason: String| VibrissaError::InvalidTable {
        name: "surface".into(),
        reason,
    };
    if x.len() != y.len() {
        return Err(bad(format!(
            "x has {} entries and y has {}: one height per position",
            x.len(),
            y.len()
        )));
    }
    if x.len() < 3 || x.len() > 100_000 {
        return Err(bad(format!(
            "{} points: a table needs at least 3 (and at most 100000)",
            x.len()
        )));
    }
    for (i, (&a, &b)) in x.iter().zip(y).enumerate() {
        if !(a.is_finite() && b.is_finite() && b.abs() <= 1.0) {
            return Err(bad(format!(
                "entry {i}: x = {a}, y = {b} (finite, |y| <= 1 rod length)"
            )));
        }
        if i > 0 && a <= x[i - 1] {
            return Err(bad(format!(
                "x[{i}] = {a} is not above x[{}] = {}: x must increase strictly",
                i - 1,
                x[i - 1]
            )));
        }
    }
    let m = crate::spline::natural_moments(x, y);
    Ok(Shape::Spline {
        x: x.to_vec(),
        y: y.to_vec(),
        m,
    })
}

/// A resolved friction profile: `μs(x)`, `μk(x)`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Texture {
    profile: FrictionProfile,
}

impl Texture {
    /// The texture of `p` (`None` for `none`); errors name the scene key.
    pub fn new(p: &FrictionProfile) -> Result<Option<Texture>, VibrissaError> {
        let pair = |i: usize, s: f64, k: f64| -> Result<(), VibrissaError> {
            let at = if i == usize::MAX {
                String::new()
            } else {
                format!("[{i}]")
            };
            crate::limits::MU_S.check(&format!("friction.mu_s{at}"), s)?;
            // as the flags --mu-s, --mu-k (issue 33: mu_k = mu_s was accepted from a file, and
            // the drag then slips without end by zero lengths)
            crate::limits::kinetic_friction(s)
                .check(&format!("friction.mu_k{at}"), k)
                .map_err(|e| match e {
                    VibrissaError::OutOfRange { name, value, .. } => VibrissaError::OutOfRange {
                        name,
                        value,
                        range: format!("[0, mu_s{at} = {s}) ({})", crate::limits::STICK_SLIP),
                    },
                    e => e,
                })
        };
        let lists = |x: &[f64], s: &[f64], k: &[f64]| -> Result<(), VibrissaError> {
            if x.is_empty() || x.len() != s.len() || x.len() != k.len() {
                return Err(VibrissaError::InvalidTable {
                    name: "friction".into(),
                    reason: format!(
                        "x, mu_s and mu_k need the same number of entries, at least 1 (they have \
                         {}, {}, {})",
                        x.len(),
                        s.len(),
                        k.len()
                    ),
                });
            }
            for i in 0..x.len() {
                if !x[i].is_finite() || (i > 0 && x[i] <= x[i - 1]) {
                    return Err(VibrissaError::InvalidTable {
                        name: "friction".into(),
                        reason: format!("x[{i}] = {} must be finite and above x[i-1]", x[i]),
                    });
                }
                pair(i, s[i], k[i])?;
            }
            Ok(())
        };
        match p {
            FrictionProfile::None {} => return Ok(None),
            &FrictionProfile::Uniform { mu_s, mu_k } => pair(usize::MAX, mu_s, mu_k)?,
            FrictionProfile::Table { x, mu_s, mu_k } => lists(x, mu_s, mu_k)?,
            FrictionProfile::Patches {
                period,
                x,
                mu_s,
                mu_k,
                offset,
            } => {
                crate::limits::FRICTION_PERIOD.check("friction.period", *period)?;
                if !offset.is_finite() {
                    return Err(VibrissaError::range("friction.offset", *offset, "finite"));
                }
                lists(x, mu_s, mu_k)?;
                if x[0] != 0.0 || x[x.len() - 1] >= *period {
                    return Err(VibrissaError::InvalidTable {
                        name: "friction".into(),
                        reason: format!(
                            "patch starts x must begin at 0 and stay below the period {period} \
                             (they are {x:?})"
                        ),
                    });
                }
                for i in 0..x.len() {
                    let width = x.get(i + 1).unwrap_or(period) - x[i];
                    crate::limits::PATCH_WIDTH
                        .check(&format!("friction patch {i}'s width"), width)?;
                    if mu_k[i] >= mu_s[i] {
                        return Err(VibrissaError::range(
                            format!("friction.mu_k[{i}]"),
                            mu_k[i],
                            format!(
                                "[0, mu_s[{i}] = {}) (a texture's patches need kinetic friction \
                                 below static)",
                                mu_s[i]
                            ),
                        ));
                    }
                }
            }
        }
        Ok(Some(Texture { profile: p.clone() }))
    }

    /// `(μs, μk)` at lab `x`; at a patch boundary (within 1e-9) the patch on the side `side`
    /// (`+1`: towards +x).
    pub fn at(&self, x: f64, side: f64) -> (f64, f64) {
        let interp = |xs: &[f64], v: &[f64]| -> f64 {
            let n = xs.len();
            if x <= xs[0] {
                return v[0];
            }
            if x >= xs[n - 1] {
                return v[n - 1];
            }
            let i = xs.partition_point(|&t| t <= x).clamp(1, n - 1) - 1;
            let t = (x - xs[i]) / (xs[i + 1] - xs[i]);
            v[i] + t * (v[i + 1] - v[i])
        };
        match &self.profile {
            FrictionProfile::None {} => (f64::INFINITY, f64::INFINITY),
            &FrictionProfile::Uniform { mu_s, mu_k } => (mu_s, mu_k),
            FrictionProfile::Table { x: xs, mu_s, mu_k } => (interp(xs, mu_s), interp(xs, mu_k)),
            FrictionProfile::Patches {
                period,
                x: xs,
                mu_s,
                mu_k,
                offset,
            } => {
                let q = x + side.signum() * 1e-9 - offset;
                let r = q - period * (q / period).floor();
                let i = xs.partition_point(|&t| t <= r).max(1) - 1;
                (mu_s[i], mu_k[i])
            }
        }
    }

    /// Whether μs and μk change continuously along the surface (a table, or uniform); patches
    /// jump at their boundaries ([`Texture::next_boundary`]).
    pub fn continuous(&self) -> bool {
        !matches!(self.profile, FrictionProfile::Patches { .. })
    }

    /// `μk` at lab `x` of a continuous texture and its slope `dμk/dx` (a table's segment's; 0
    /// beyond its ends, and the right segment's at a table point).
    pub fn kinetic_slope(&self, x: f64) -> (f64, f64) {
        let value = self.at(x, 1.0).1;
        let FrictionProfile::Table { x: xs, mu_k, .. } = &self.profile else {
            return (value, 0.0);
        };
        let n = xs.len();
        if n < 2 || x < xs[0] || x >= xs[n - 1] {
            return (value, 0.0);
        }
        let i = xs.partition_point(|&t| t <= x).clamp(1, n - 1) - 1;
        (value, (mu_k[i + 1] - mu_k[i]) / (xs[i + 1] - xs[i]))
    }

    /// The first patch boundary beyond `x` (by more than 1e-12) in the direction `dir`, if the
    /// texture has patches.
    pub fn next_boundary(&self, x: f64, dir: f64) -> Option<f64> {
        let FrictionProfile::Patches {
            period,
            x: xs,
            offset,
            ..
        } = &self.profile
        else {
            return None;
        };
        let q = x - offset;
        let n = (q / period).floor();
        let mut best: Option<f64> = None;
        for k in [n - 1.0, n, n + 1.0] {
            for &b in xs {
                let xb = offset + k * period + b;
                if dir * (xb - x) > 1e-12 && best.is_none_or(|c| dir * (xb - c) < 0.0) {
                    best = Some(xb);
                }
            }
        }
        best
    }

    /// Whether μk is the same everywhere (then the end of a slip is predicted from the unknowns
    /// alone); `Some(μk)`.
    pub fn uniform_mu_k(&self) -> Option<f64> {
        match self.profile {
            FrictionProfile::Uniform { mu_k, .. } => Some(mu_k),
            _ => None,
        }
    }
}

/// What a march knows of the surface besides a straight line: the curved profile the contacts
/// touch, the friction texture, and whether this march is a slip (the tip sliding, its end where
/// the needed friction ratio falls to μk).
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Ground {
    pub curve: Option<Arc<Height>>,
    pub texture: Option<Arc<Texture>>,
    pub slide: Option<Slide>,
    /// Kinetic friction off a texture (a drag's μk): a contact that forms needing more than μs
    /// slides with it, and a contact that slides passively during a slip carries it.
    pub mu_k: Option<f64>,
    /// Integrate the work along the march (the drag's energy balance).
    pub meter: Option<Meter>,
    /// The march grows the curve's shape: its amplitude is `λ` (the start on a curve).
    pub grow: bool,
}

/// The work a march integrates over its accepted points (`MarchOut::metered`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Meter {
    /// The work of the foot as it moves in x: `∫ −F_x dλ` (the foot carries minus the total
    /// contact force).
    Foot,
    /// The work the sliding tip's contact force absorbs: `∫ −F·dr_tip` (`∫ T dσ` on the surface).
    Slide,
    /// The work of the support as it turns (the foot held): `∫ m(0) dθ`, `m(0)` the moment at
    /// the foot (the clamp holds the slope `π/2 − θ`).
    Turn,
}

/// A slip in progress.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Slide {
    /// The direction the driving contact slides along the surface (`+1`: towards +x).
    pub dir: f64,
    /// μk when there is no texture.
    pub mu_k: f64,
    /// The contact whose slide is the march's parameter.
    pub driver: usize,
}

impl Ground {
    /// `(μs, μk)` at lab `x` from the texture, else `None`.
    pub fn friction_at(&self, x: f64, side: f64) -> Option<(f64, f64)> {
        self.texture.as_ref().map(|t| t.at(x, side))
    }
    /// μk at `x` during the slide (`None` outside one).
    pub fn mu_k_at(&self, x: f64) -> Option<f64> {
        let s = self.slide?;
        Some(self.friction_at(x, s.dir).map_or(s.mu_k, |p| p.1))
    }
}

/// The largest height `y(s) − h(x(s)) − off` of the rod's free parts above a curved surface and
/// where: the maxima are where the exact slope of the gap `sin φ − h' cos φ` turns from rising to
/// falling between samples of the interpolant `sample(s) = (x_lab, y, φ, κ)` — `n + 1` even
/// ones and eight times finer within two intervals of each contact at `near` (where a maximum
/// is born out of a contact and stays narrow) — or, a maximum and a minimum between the same two
/// samples, where the cubic through their values and slopes has its maximum; those within 1e-3
/// of the surface refined on the rod (`exact`, same layout; Newton on the slope). Points near
/// `skip(s)` (the contacts) and outside the surface's domain do not count.
#[allow(clippy::too_many_arguments)]
pub(crate) fn curve_clearance(
    h: &Height,
    amp: f64,
    off: f64,
    n: usize,
    near: &[f64],
    sample: &mut dyn FnMut(f64) -> [f64; 4],
    exact: &mut dyn FnMut(f64) -> [f64; 4],
    skip: &dyn Fn(f64) -> bool,
) -> (f64, f64) {
    let gap = |z: &[f64; 4]| z[1] - h.jet_scaled(z[0], amp).0 - off;
    // (one evaluation of the profile for both: on a corrugation it is a sin_cos, and the
    // samples are most of the drag's cost)
    let gap_slope = |z: &[f64; 4]| {
        let (hv, hd, _) = h.jet_scaled(z[0], amp);
        let (sp, cp) = z[2].sin_cos();
        (z[1] - hv - off, sp - hd * cp)
    };
    let nf = n as f64;
    let mut ss: Vec<f64> = (0..=n).map(|i| i as f64 / nf).collect();
    for &c in near {
        ss.extend((-16..=16).map(|k| c + f64::from(k) / (8.0 * nf)));
    }
    ss.retain(|s| (0.0..=1.0).contains(s));
    ss.sort_by(f64::total_cmp);
    ss.dedup();
    // (s, gap, slope)
    let pts: Vec<(f64, f64, f64)> = ss
        .into_iter()
        .map(|s| {
            let (g, sl) = gap_slope(&sample(s));
            (s, g, sl)
        })
        .collect();
    let mut best = (f64::NEG_INFINITY, f64::NAN);
    for w in pts.windows(2) {
        let ((sa, va, ga), (sb, vb, gb)) = (w[0], w[1]);
        let s0 = if ga > 0.0 && gb <= 0.0 {
            // start on the higher end
            if va >= vb {
                sa
            } else {
                sb
            }
        } else {
            // a maximum and a minimum between the same two samples (a pair just born, or
            // born out of a contact): the cubic through the values and slopes shows them
            match hermite_max(sb - sa, [va, ga], [vb, gb]) {
                Some(t) => sa + t * (sb - sa),
                None => continue,
            }
        };
        if skip(s0) && skip(sa) && skip(sb) {
            continue;
        }
        let z0 = sample(s0);
        let g0 = gap(&z0);
        if g0 < -1e-3 {
            // far below the surface the interpolant's error (~1e-8) does not matter
            if !skip(s0) && h.covers(z0[0]) && g0 > best.0 {
                best = (g0, s0);
            }
            continue;
        }
        // Newton on the slope (g'' = κ(cos φ + h' sin φ) − h'' cos² φ)
        let (mut s1, mut z1) = (s0, exact(s0));
        for _ in 0..16 {
            let (_, d, dd) = h.jet_scaled(z1[0], amp);
            let (sp, cp) = z1[2].sin_cos();
            let d1 = sp - d * cp;
            let d2 = z1[3] * (cp + d * sp) - dd * cp * cp;
            if d2 >= 0.0 || !d2.is_finite() {
                break;
            }
            let next = (s1 - d1 / d2).clamp(sa, sb);
            let step = (next - s1).abs();
            s1 = next;
            z1 = exact(s1);
            if step < 1e-14 {
                break;
            }
        }
        if skip(s1) || !h.covers(z1[0]) {
            continue;
        }
        let g1 = gap(&z1);
        if g1 > best.0 {
            best = (g1, s1);
        }
    }
    best
}

/// Where the cubic Hermite interpolant on an interval of length `h` through the values and
/// slopes `(g, g')` at its ends has a local maximum inside, as a fraction `t ∈ (0, 1)`.
fn hermite_max(h: f64, [g0, m0]: [f64; 2], [g1, m1]: [f64; 2]) -> Option<f64> {
    // p'(t) = A t² + B t + C, p''(t) = 2 A t + B
    let a = 6.0 * (g0 - g1) + 3.0 * h * (m0 + m1);
    let b = 6.0 * (g1 - g0) - h * (4.0 * m0 + 2.0 * m1);
    let c = h * m0;
    let roots = if a.abs() <= 1e-300 {
        [(b != 0.0).then(|| -c / b), None]
    } else {
        let disc = b * b - 4.0 * a * c;
        if disc < 0.0 {
            return None;
        }
        // (the stable pair of the quadratic's roots)
        let q = -0.5 * (b + b.signum() * disc.sqrt());
        [Some(q / a), (q != 0.0).then(|| c / q)]
    };
    roots
        .into_iter()
        .flatten()
        .find(|&t| t > 0.0 && t < 1.0 && 2.0 * a * t + b < 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cubic is its own Hermite interpolant: p(t) = −t³ + 1.5t² − 0.54t falls at both ends
    /// (p' = −0.54) and has its maximum inside at t = (1 + √0.28)/2 (p' = 0, p'' < 0).
    #[test]
    fn hermite_max_finds_a_maximum_between_falling_ends() {
        let p = |t: f64| -t * t * t + 1.5 * t * t - 0.54 * t;
        for h in [1.0, 1e-3] {
            // on [0, h] in s: slopes scale by 1/h
            let t = hermite_max(h, [p(0.0), -0.54 / h], [p(1.0), -0.54 / h]).unwrap();
            assert!((t - (1.0 + 0.28f64.sqrt()) / 2.0).abs() < 1e-12, "{t}");
        }
        // a monotone cubic has none
        assert_eq!(hermite_max(1.0, [0.0, -1.0], [-1.0, -1.0]), None);
    }

    /// The start's arc length on the sine scaled by `a` (`Height::arc_scaled`): over a period
    /// `P` of `h' = a·A·k·cos(kx + p)` it is `(P/2π)·4·√(1 + B²)·E(B²/(1 + B²))`, `B = a·A·k`,
    /// the complete elliptic integral of the second kind (crate `elastica`), to 1e-14 relative;
    /// it splits at any point to rounding, and at `a = 1` it is the profile's own `σ`.
    #[test]
    fn scaled_arc_length_matches_the_elliptic_closed_form() {
        let (amplitude, wavelength) = (0.005, 0.05);
        let h = Height::new(
            &SurfaceProfile::Sine {
                amplitude,
                wavelength,
                phase: 0.7,
            },
            0.75,
            0.0,
        )
        .unwrap()
        .unwrap();
        let k = std::f64::consts::TAU / wavelength;
        for amp in [0.0, 0.3, 0.7, 1.0] {
            let b2 = (amp * amplitude * k).powi(2);
            let exact = wavelength / std::f64::consts::TAU
                * 4.0
                * (1.0 + b2).sqrt()
                * elastica::ellint::legendre_e(b2 / (1.0 + b2)).unwrap();
            for x0 in [-0.3, 0.0123, 0.41] {
                let got = h.arc_scaled(x0, x0 + wavelength, amp);
                assert!(
                    (got - exact).abs() <= 1e-14 * exact,
                    "amplitude {amp}, from {x0}: {got} against {exact}"
                );
                let (m, e) = (x0 + 0.3 * wavelength, x0 + 0.8 * wavelength);
                let split = h.arc_scaled(x0, m, amp) + h.arc_scaled(m, e, amp);
                let whole = h.arc_scaled(x0, e, amp);
                assert!((split - whole).abs() <= 1e-15, "{split} against {whole}");
                assert_eq!(h.arc_scaled(e, x0, amp), -whole);
            }
        }
        let (a, b) = (0.0123, 0.6);
        let full = h.sigma(b).0 - h.sigma(a).0;
        let scaled = h.sigma_scaled_from(a, h.sigma(a).0, b, 1.0).0 - h.sigma(a).0;
        assert!((scaled - full).abs() <= 1e-14, "{scaled} against {full}");
    }

    #[test]
    fn sine_arc_length_matches_a_fine_sum() {
        let h = Height::new(
            &SurfaceProfile::Sine {
                amplitude: 0.05,
                wavelength: 0.4,
                phase: 0.3,
            },
            0.75,
            0.1,
        )
        .unwrap()
        .unwrap();
        // composite Simpson with 200 000 intervals (error ~1e-16 per unit)
        let simpson = |a: f64, b: f64| {
            let n = 200_000;
            let w = (b - a) / n as f64;
            let f = |x: f64| (1.0 + h.jet(x).1.powi(2)).sqrt();
            let mut s = f(a) + f(b);
            for i in 1..n {
                s += f(a + i as f64 * w) * if i % 2 == 1 { 4.0 } else { 2.0 };
            }
            s * w / 3.0
        };
        for x in [-1.3, -0.05, 0.0, 0.17, 0.9, 3.7] {
            let want = if x >= 0.0 {
                simpson(0.0, x)
            } else {
                -simpson(x, 0.0)
            };
            assert!(
                (h.sigma(x).0 - want).abs() < 1e-12,
                "{x}: {} {want}",
                h.sigma(x).0
            );
        }
    }

    #[test]
    fn spline_derivatives_are_consistent() {
        let h = Height::new(
            &SurfaceProfile::Table {
                x: vec![-1.0, -0.3, 0.2, 0.8, 1.5],
                y: vec![0.0, 0.05, -0.02, 0.04, 0.0],
            },
            0.75,
            0.0,
        )
        .unwrap()
        .unwrap();
        // (at the knot -0.3 the third derivative jumps: the difference of h' is off by ~e·jump)
        for x in [-0.9, -0.3, 0.0, 0.5, 1.4] {
            let e = 1e-7;
            let (_, d, dd) = h.jet(x);
            let fd = (h.h(x + e) - h.h(x - e)) / (2.0 * e);
            let fdd = (h.jet(x + e).1 - h.jet(x - e).1) / (2.0 * e);
            assert!((d - fd).abs() < 1e-8 && (dd - fdd).abs() < 1e-6, "{x}");
        }
        // the spline interpolates and has zero curvature at the ends
        assert!((h.h(0.2) - 0.73).abs() < 1e-15);
        assert!(h.jet(-1.0).2.abs() < 1e-12 && h.jet(1.5).2.abs() < 1e-12);
    }

    #[test]
    fn circle_and_patches() {
        let h = Height::new(
            &SurfaceProfile::Circle {
                radius: 2.0,
                x0: 0.1,
            },
            0.8,
            0.0,
        )
        .unwrap()
        .unwrap();
        let (lo, hi) = h.domain();
        assert!((hi - 0.1 - 2.0 / 2f64.sqrt()).abs() < 1e-14 && (lo + hi - 0.2).abs() < 1e-14);
        // arc length of a circle: R·asin(u/R)
        let want = 2.0 * ((0.6f64 - 0.1) / 2.0).asin() - 2.0 * ((0.0f64 - 0.1) / 2.0).asin();
        assert!((h.sigma(0.6).0 - want).abs() < 1e-13);
        let t = Texture::new(&FrictionProfile::Patches {
            period: 0.3,
            x: vec![0.0, 0.1],
            mu_s: vec![0.5, 0.8],
            mu_k: vec![0.3, 0.6],
            offset: 0.05,
        })
        .unwrap()
        .unwrap();
        assert_eq!(t.at(0.1, 1.0), (0.5, 0.3));
        assert_eq!(t.at(0.16, 1.0), (0.8, 0.6));
        assert_eq!(t.at(0.15, 1.0), (0.8, 0.6));
        assert_eq!(t.at(0.15, -1.0), (0.5, 0.3));
        assert_eq!(t.at(0.05 + 0.3 * 7.0, 1.0), (0.5, 0.3));
        assert!((t.next_boundary(0.16, 1.0).unwrap() - 0.35).abs() < 1e-15);
        assert!((t.next_boundary(0.16, -1.0).unwrap() - 0.15).abs() < 1e-15);
        assert!((t.next_boundary(0.35, 1.0).unwrap() - 0.45).abs() < 1e-15);
    }

    /// Nothing keeps a surface's shared parts once the caller drops it (issue 35: a sweep over
    /// 10⁵ surfaces runs in constant memory): a scan and a drag over a corrugation with a
    /// friction texture hold no count of its profile or texture after they return (no cache,
    /// no result refers to them), and dropping the surface frees both.
    #[test]
    fn a_dropped_surface_leaves_nothing_behind() {
        use std::sync::Arc;
        let scene = crate::Scene {
            surface: SurfaceProfile::Sine {
                amplitude: 0.01,
                wavelength: 0.5,
                phase: 2.0,
            },
            friction: FrictionProfile::Uniform {
                mu_s: 0.5,
                mu_k: 0.3,
            },
            ..crate::Scene::default()
        };
        let (rod, surface) = scene.parts().unwrap();
        let profile = Arc::downgrade(&surface.profile_shared().unwrap());
        let texture = Arc::downgrade(&surface.texture_shared().unwrap());
        let scan = crate::scan(
            &rod,
            &surface,
            &crate::ScanOptions {
                d_max: 0.05,
                points: 3,
                ..crate::ScanOptions::default()
            },
        )
        .unwrap();
        let drag = crate::drag(
            &rod,
            &surface,
            &crate::DragOptions {
                d_max: 0.1,
                points: 3,
                ..crate::DragOptions::default()
            },
        )
        .unwrap();
        assert_eq!(scan.stop, crate::StopReason::DMax, "{}", scan.stop);
        assert!(!drag.slips.is_empty(), "{}", drag.stop);
        // only the surface itself holds them
        assert_eq!(profile.strong_count(), 1);
        assert_eq!(texture.strong_count(), 1);
        drop(surface);
        assert!(profile.upgrade().is_none() && texture.upgrade().is_none());
    }
}
