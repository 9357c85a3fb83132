//! A periodic grating (issue 31): straight flanks of inclination ±α joined by circular arcs of
//! radius `r` tangent to them, flat lands of equal width at the ridges and grooves when the depth
//! leaves room for them.
//!
//! One period of the shape `s(u)`, `u = (x − offset) mod p`, starts in the middle of a ridge (the
//! part that stands out towards the rod, the lowest height `s = −D/2`); `l` is half a land's width:
//!
//! ```text
//!     [0, l)                    land          s = −D/2
//!     [l, l + r sin α)          ridge arc     s = −D/2 + r − √(r² − (u − l)²)        (convex)
//!     … p/2 − l − r sin α)      flank         s = −D/2 + r(1 − cos α) + (u − l − r sin α)·tan α
//!     … p/2 − l)                groove arc    s = D/2 − r + √(r² − (u − p/2 + l)²)   (concave)
//!     [p/2 − l, p/2 + l)        land          s = D/2
//!     and mirrored: s(p − u) = s(u)
//! ```
//!
//! The flank closes the cell when `tan α·(p/2 − 2l − 2r sin α) = D − 2r(1 − cos α)`: two of the
//! depth `D`, the flank angle `α` and the lands `l` give the third; without lands (`l = 0`, the
//! rounded triangle) `α` solves `(p/2) sin α + (2r − D) cos α = 2r`, i.e.
//! `α = asin(2r/ρ) − ψ` with `ρ·(cos ψ, sin ψ) = (p/2, 2r − D)`. The mean of `s` is 0 (the shape is
//! odd about the middle of each flank).
//!
//! The profile is C¹: slopes agree where an arc meets a flank or a land; the curvature jumps
//! there (`±1/r` on an arc, 0 on a flank). A sharp corner (`r = 0`) is refused: the contact
//! conditions need the surface's tangent everywhere.
//!
//! Arc length with the trend `t = tan β`: a straight piece of run `Δu` and slope `m` is
//! `Δu·√(1 + (t + m)²)`; on an arc `u − c = r sin θ`, `s' = ±tan θ` and
//! `dσ = r·√(cos²θ + (t cos θ ± sin θ)²) dθ` — `r·Δθ` without a trend; with one, an elliptic
//! integral, by 10-point Gauss–Legendre on panels of at most 0.1 rad (its singularities lie
//! ≥ 0.4 rad off the real axis for `|t| < 1`: error below 1e-20 per panel).

use crate::VibrissaError;
use serde::Serialize;

/// One smooth piece of the cell.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
enum Piece {
    /// `s = s0 + m·(u − u0)` from the piece's start `u0`.
    Line { s0: f64, m: f64 },
    /// `s = cy − sign·√(r² − (u − cx)²)`: `sign = 1` convex (a ridge), −1 concave (a groove).
    Arc { cx: f64, cy: f64, sign: f64 },
}

/// A resolved grating (see the module docs).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub(crate) struct Grating {
    /// Period `p`.
    pub period: f64,
    /// Lab x of the middle of a ridge.
    pub offset: f64,
    /// Peak-to-valley depth `D`.
    pub depth: f64,
    /// Flank angle α (rad).
    pub flank_angle: f64,
    /// Radius of the ridges and grooves.
    pub radius: f64,
    /// Half the width of a land (0: the rounded triangle).
    pub land: f64,
    /// The trend `tan β` the arc length includes.
    trend: f64,
    /// Piece starts within the cell, and `p` last.
    starts: Vec<f64>,
    pieces: Vec<Piece>,
    /// Arc length from the cell's start to each piece's start, and the cell's last.
    cum: Vec<f64>,
}

/// The arc panels' largest width in θ.
const ARC_PANEL: f64 = 0.1;

impl Grating {
    /// The grating of period `p`, radius `r`, offset, with the depth and/or the flank angle (one
    /// may be `None`; see the module docs), on the trend `t`. Ranges are the caller's; this
    /// checks that the pieces fit, naming the keys.
    pub fn new(
        p: f64,
        depth: Option<f64>,
        flank: Option<f64>,
        r: f64,
        offset: f64,
        trend: f64,
    ) -> Result<Grating, VibrissaError> {
        let (d, a) = match (depth, flank) {
            (Some(d), Some(a)) => (d, a),
            (None, Some(a)) => (
                (0.5 * p - 2.0 * r * a.sin()) * a.tan() + 2.0 * r * (1.0 - a.cos()),
                a,
            ),
            (Some(d), None) => {
                let rho = (0.5 * p).hypot(2.0 * r - d);
                if 2.0 * r >= rho {
                    return Err(too_round(r, p, d, None));
                }
                (d, (2.0 * r / rho).asin() - (2.0 * r - d).atan2(0.5 * p))
            }
            (None, None) => {
                return Err(VibrissaError::InvalidTable {
                    name: "surface".into(),
                    reason: "a grating needs its depth, its flank_angle, or both (then with flat \
                             lands at the ridges and grooves)"
                        .into(),
                })
            }
        };
        let (sa, ca, ta) = (a.sin(), a.cos(), a.tan());
        if !(a > 0.0 && d > 0.0 && d.is_finite()) {
            return Err(too_round(r, p, d, Some(a)));
        }
        // the arcs' rise and run; what is left to the flank and the lands
        let rise = d - 2.0 * r * (1.0 - ca);
        let mut land = 0.5 * (0.5 * p - 2.0 * r * sa - rise / ta);
        if land.abs() <= 1e-12 * p {
            // the triangle itself (rounding of the closed forms)
            land = 0.0;
        }
        if rise < 0.0 || land < 0.0 {
            return Err(if depth.is_some() && flank.is_some() && rise >= 0.0 {
                // too deep or too steep for the period
                let need = 2.0 * (2.0 * r * sa + rise / ta);
                VibrissaError::range(
                    "surface.period",
                    p,
                    format!(
                        "[{need:.6}, 100] rod lengths: depth = {d} at flank_angle = {a} with \
                         ridge_radius = {r} needs at least this period (without lands); give a \
                         smaller depth or flank_angle, or only one of them"
                    ),
                )
            } else {
                too_round(r, p, d, Some(a))
            });
        }
        let h = 0.5 * d;
        let q = 0.5 * p;
        let run = r * sa;
        let mut cell: Vec<(f64, Piece)> = vec![
            (0.0, Piece::Line { s0: -h, m: 0.0 }),
            (
                land,
                Piece::Arc {
                    cx: land,
                    cy: -h + r,
                    sign: 1.0,
                },
            ),
            (
                land + run,
                Piece::Line {
                    s0: -h + r * (1.0 - ca),
                    m: ta,
                },
            ),
            (
                q - land - run,
                Piece::Arc {
                    cx: q - land,
                    cy: h - r,
                    sign: -1.0,
                },
            ),
            (q - land, Piece::Line { s0: h, m: 0.0 }),
            (
                q + land,
                Piece::Arc {
                    cx: q + land,
                    cy: h - r,
                    sign: -1.0,
                },
            ),
            (
                q + land + run,
                Piece::Line {
                    s0: h - r * (1.0 - ca),
                    m: -ta,
                },
            ),
            (
                p - land - run,
                Piece::Arc {
                    cx: p - land,
                    cy: -h + r,
                    sign: 1.0,
                },
            ),
            (p - land, Piece::Line { s0: -h, m: 0.0 }),
        ];
        cell.push((p, Piece::Line { s0: -h, m: 0.0 }));
        // pieces of zero width (no lands, or no flank) go
        let mut starts = Vec::new();
        let mut pieces = Vec::new();
        for w in cell.windows(2) {
            if w[1].0 > w[0].0 {
                starts.push(w[0].0);
                pieces.push(w[0].1);
            }
        }
        starts.push(p);
        let mut g = Grating {
            period: p,
            offset,
            depth: d,
            flank_angle: a,
            radius: r,
            land,
            trend,
            starts,
            pieces,
            cum: Vec::new(),
        };
        let mut cum = vec![0.0];
        for i in 0..g.pieces.len() {
            let len = g.arc_of(i, g.starts[i + 1]);
            cum.push(cum[i] + len);
        }
        g.cum = cum;
        Ok(g)
    }

    /// The piece of the cell position `u ∈ [0, p)`.
    fn piece(&self, u: f64) -> usize {
        let n = self.pieces.len();
        self.starts.partition_point(|&t| t <= u).clamp(1, n) - 1
    }

    /// The cell position of lab `x` and the number of whole periods before it.
    fn cell(&self, x: f64) -> (f64, f64) {
        let q = x - self.offset;
        let n = (q / self.period).floor();
        let u = (q - n * self.period).clamp(0.0, self.period);
        (u, n)
    }

    /// `(s, s', s'')` of the shape at lab `x`.
    pub fn jet(&self, x: f64) -> (f64, f64, f64) {
        let (u, _) = self.cell(x);
        let i = self.piece(u);
        match self.pieces[i] {
            Piece::Line { s0, m } => (s0 + m * (u - self.starts[i]), m, 0.0),
            Piece::Arc { cx, cy, sign } => {
                let r = self.radius;
                let v = (u - cx).clamp(-r, r);
                let w = (r * r - v * v).sqrt();
                (cy - sign * w, sign * v / w, sign * r * r / (w * w * w))
            }
        }
    }

    /// Arc length (with the trend) from the start of piece `i` to the cell position `u` in it.
    fn arc_of(&self, i: usize, u: f64) -> f64 {
        let t = self.trend;
        let u0 = self.starts[i];
        match self.pieces[i] {
            Piece::Line { m, .. } => (u - u0) * (1.0 + (t + m) * (t + m)).sqrt(),
            Piece::Arc { cx, sign, .. } => {
                let r = self.radius;
                let th = |u: f64| ((u - cx) / r).clamp(-1.0, 1.0).asin();
                let (a, b) = (th(u0), th(u));
                if t == 0.0 {
                    return r * (b - a);
                }
                let n = ((b - a).abs() / ARC_PANEL).ceil().max(1.0) as usize;
                let speed = |q: f64| {
                    let (s, c) = q.sin_cos();
                    let e = t * c + sign * s;
                    (c * c + e * e).sqrt()
                };
                (0..n)
                    .map(|k| {
                        let lo = a + (b - a) * k as f64 / n as f64;
                        let hi = a + (b - a) * (k + 1) as f64 / n as f64;
                        crate::gauss::gauss10(lo, hi, speed)
                    })
                    .sum::<f64>()
                    * r
            }
        }
    }

    /// Arc length of one period (with the trend).
    pub fn period_arc(&self) -> f64 {
        self.cum[self.cum.len() - 1]
    }

    /// Arc length from lab `offset` (a ridge's middle) to `x`, signed.
    pub fn arc(&self, x: f64) -> f64 {
        let (u, n) = self.cell(x);
        let i = self.piece(u);
        n * self.period_arc() + self.cum[i] + self.arc_of(i, u)
    }
}

/// The error of a radius that does not fit the period and depth.
fn too_round(r: f64, p: f64, d: f64, a: Option<f64>) -> VibrissaError {
    let detail = match a {
        Some(a) => format!(
            "the arcs take 2 r (1 - cos(flank_angle)) = {:.6} of the depth {d:.6} and 4 r \
             sin(flank_angle) = {:.6} of the period {p}",
            2.0 * r * (1.0 - a.cos()),
            4.0 * r * a.sin()
        ),
        None => format!("no rounded triangle of depth {d} and period {p} has ridges this round"),
    };
    VibrissaError::range(
        "surface.ridge_radius",
        r,
        format!(
            "(0, 100] rod lengths, and small enough for the ridges and grooves to fit: {detail}"
        ),
    )
}
