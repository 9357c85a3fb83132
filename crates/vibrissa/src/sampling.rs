//! Sampling a numerical solution on its cubic Hermite interpolant (positions, slope and moment
//! with their derivatives at the nodes): sign changes of the moment and the curvature (load
//! reversals, flex points), extrema of a height, the clearance under a surface line. Per-interval
//! polynomials searched from a hint, so that these cost a few hundred operations per rod whatever
//! its profile.

use crate::profile::Profile;
use bvp::Solution;
use serde::Serialize;

/// The moment `m(s)` of a solution as per-interval cubic Hermite polynomials (the interpolant of
/// [`Solution::eval`]'s default form), evaluated from an interval hint.
pub(crate) struct Sampler<'a> {
    mesh: &'a [f64],
    /// The cubic of `m` on interval `i`, in `t ∈ [0, 1]`.
    coef: Vec<[f64; 4]>,
}

impl<'a> Sampler<'a> {
    /// The interpolant of the moment (component 3) of `sol`.
    pub fn new(sol: &'a Solution) -> Self {
        let n = sol.mesh.len() - 1;
        let (w, c) = (sol.n, 3);
        let coef = (0..n)
            .map(|i| {
                let h = sol.mesh[i + 1] - sol.mesh[i];
                let (z0, z1) = (sol.z[w * i + c], sol.z[w * (i + 1) + c]);
                let (d0, d1) = (h * sol.dz[w * i + c], h * sol.dz[w * (i + 1) + c]);
                [
                    z0,
                    d0,
                    -3.0 * z0 - 2.0 * d0 + 3.0 * z1 - d1,
                    2.0 * z0 + d0 - 2.0 * z1 + d1,
                ]
            })
            .collect();
        Sampler {
            mesh: &sol.mesh,
            coef,
        }
    }

    /// `m(s)`, searching the interval from the hint `i`; also returns the interval.
    #[inline]
    pub fn at(&self, s: f64, mut i: usize) -> (f64, usize) {
        let n = self.mesh.len() - 1;
        let mesh = self.mesh;
        i = i.min(n - 1);
        while i + 1 < n && mesh[i + 1] <= s {
            i += 1;
        }
        while i > 0 && mesh[i] > s {
            i -= 1;
        }
        let t = ((s - mesh[i]) / (mesh[i + 1] - mesh[i])).clamp(0.0, 1.0);
        let k = &self.coef[i];
        (((k[3] * t + k[2]) * t + k[1]) * t + k[0], i)
    }

    /// Sign changes of `m(s)` itself on `[0, 1)`, exact on the interpolant: each interval's cubic
    /// is split at its critical points into monotone pieces, whose end values are compared
    /// (values within `1e-9` of the largest treated as zero; the tip, where `m(1) = 0`, excluded).
    /// The first one's arc length by Brent's method on its piece.
    pub fn moment_sign_changes(&self) -> (usize, Option<f64>) {
        let n = self.coef.len();
        let poly = |k: &[f64; 4], t: f64| ((k[3] * t + k[2]) * t + k[1]) * t + k[0];
        let scale = self
            .coef
            .iter()
            .map(|k| k[0].abs())
            .fold(poly(&self.coef[n - 1], 1.0).abs(), f64::max);
        let eps = 1e-9 * scale.max(1e-300);
        let (mut count, mut first) = (0, None);
        // the last value beyond eps: (interval, t, value)
        let mut prev: Option<(usize, f64, f64)> = None;
        for (i, k) in self.coef.iter().enumerate() {
            // critical points of the cubic in (0, 1): roots of 3 k3 t² + 2 k2 t + k1
            let (a, b, c) = (3.0 * k[3], 2.0 * k[2], k[1]);
            let mut ts = [0.0, 1.0, 1.0, 1.0];
            let mut m = 1;
            let disc = b * b - 4.0 * a * c;
            if a != 0.0 && disc > 0.0 {
                let q = -0.5 * (b + b.signum() * disc.sqrt());
                for r in [q / a, c / q] {
                    if r > 0.0 && r < 1.0 {
                        ts[m] = r;
                        m += 1;
                    }
                }
            } else if a == 0.0 && b != 0.0 {
                let r = -c / b;
                if r > 0.0 && r < 1.0 {
                    ts[m] = r;
                    m += 1;
                }
            }
            ts[m] = 1.0;
            ts[1..m].sort_by(f64::total_cmp);
            let last = if i + 1 == n { m - 1 } else { m };
            for &t in &ts[usize::from(i > 0)..=last] {
                let v = poly(k, t);
                if v.abs() <= eps {
                    continue;
                }
                if let Some((pi, pt, pv)) = prev {
                    if pv.signum() != v.signum() {
                        count += 1;
                        if first.is_none() {
                            first = Some(self.root_between((pi, pt), (i, t)));
                        }
                    }
                }
                prev = Some((i, t, v));
            }
        }
        (count, first)
    }

    /// The root of `m` between two points `(interval, t)` of opposite signs. On one monotone
    /// piece of one cubic (the usual case) by Newton's method on the cubic, kept in the bracket by
    /// bisection — a polynomial root, ~10× cheaper than a general 1-D search per output point;
    /// across intervals by Brent's method.
    fn root_between(&self, a: (usize, f64), b: (usize, f64)) -> f64 {
        let s_of = |(i, t): (usize, f64)| self.mesh[i] + t * (self.mesh[i + 1] - self.mesh[i]);
        if a.0 == b.0 {
            let k = &self.coef[a.0];
            let p = |t: f64| ((k[3] * t + k[2]) * t + k[1]) * t + k[0];
            let dp = |t: f64| (3.0 * k[3] * t + 2.0 * k[2]) * t + k[1];
            let (mut lo, mut hi) = (a.1, b.1);
            let neg_lo = p(lo) < 0.0;
            let mut t = 0.5 * (lo + hi);
            for _ in 0..100 {
                let v = p(t);
                if v == 0.0 {
                    break;
                }
                if (v < 0.0) == neg_lo {
                    lo = t;
                } else {
                    hi = t;
                }
                let newton = t - v / dp(t);
                let next = if newton > lo.min(hi) && newton < lo.max(hi) {
                    newton
                } else {
                    0.5 * (lo + hi)
                };
                if (next - t).abs() <= 1e-15 * (1.0 + t.abs()) {
                    t = next;
                    break;
                }
                t = next;
            }
            return s_of((a.0, t));
        }
        let (sa, sb) = (s_of(a), s_of(b));
        let mut g = |s: f64| -> Result<f64, std::convert::Infallible> { Ok(self.at(s, a.0).0) };
        // the ends bracket the root: Brent cannot fail here, take the midpoint if it does
        crate::search::root(&mut g, sa, sb, 1e-14).unwrap_or(0.5 * (sa + sb))
    }

    /// Sign changes of `g(s, m(s))` on `[0, 1)` (129 samples, values within `1e-9` of the largest
    /// treated as zero, the tip excluded where `m(1) = 0`) and the first one's arc length
    /// (bisection to rounding).
    pub fn sign_changes(&self, g: impl Fn(f64, f64) -> f64) -> (usize, Option<f64>) {
        const N: usize = 128;
        let val = |s: f64, hint: usize| {
            let (m, i) = self.at(s, hint);
            (g(s, m), i)
        };
        let mut vals = [0.0; N + 1];
        let mut hint = 0;
        for (i, v) in vals.iter_mut().enumerate() {
            (*v, hint) = val(i as f64 / N as f64, hint);
        }
        let scale = vals.iter().map(|v| v.abs()).fold(0.0, f64::max);
        let eps = 1e-9 * scale.max(1e-300);
        let mut count = 0;
        let mut first = None;
        let mut prev: Option<(f64, f64)> = None;
        for (i, &k) in vals.iter().enumerate().take(N) {
            let s = i as f64 / N as f64;
            if k.abs() <= eps {
                continue;
            }
            if let Some((sp, kp)) = prev {
                if kp.signum() != k.signum() {
                    count += 1;
                    if first.is_none() {
                        let hint = self.at(sp, 0).1;
                        let mut g = |c: f64| -> Result<f64, std::convert::Infallible> {
                            Ok(val(c, hint).0)
                        };
                        // the samples bracket the root: Brent cannot fail here, bisect if it does
                        first = Some(
                            crate::search::root(&mut g, sp, s, 1e-14).unwrap_or(0.5 * (sp + s)),
                        );
                    }
                }
            }
            prev = Some((s, k));
        }
        (count, first)
    }
}

/// Flex points (sign changes of `κ = κ0 + b·m`, the first one's `s`) and load reversals (sign
/// changes of `m`) of a solution.
pub(crate) fn flex_and_reversals<P: Profile>(
    sol: &Solution,
    profile: &P,
) -> (usize, Option<f64>, usize) {
    let smp = Sampler::new(sol);
    let (rev, s_rev) = smp.moment_sign_changes();
    if P::UNIFORM {
        return (rev, s_rev, rev);
    }
    let (flex, s_flex) = smp.sign_changes(|s, m| profile.kappa(s, m));
    (flex, s_flex, rev)
}

/// Extrema of `h(s) = cx·x(s) + cy·y(s)` along a solution (cubic Hermite between nodes).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Extrema {
    /// Maximum over `[0, 1]`.
    pub max: f64,
    /// Largest interior local maximum (`s < 1`), `-inf` if none.
    pub interior: f64,
    /// Its arc length.
    pub s_interior: f64,
}

/// Arc lengths of the interior local maxima (`p' = 0`, `p'' < 0` inside an interval) of
/// `h(s) = cx·x(s) + cy·y(s)` on the cubic Hermite interpolant: candidates to refine on the rod.
pub(crate) fn local_maxima(sol: &Solution, cx: f64, cy: f64) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for_each_max(sol, cx, cy, |s, v| out.push((s, v)));
    out
}

/// Calls `f(s, h)` at every interior local maximum of `h = cx·x + cy·y` on the interpolant.
fn for_each_max(sol: &Solution, cx: f64, cy: f64, mut f: impl FnMut(f64, f64)) {
    let n = sol.n;
    let len = sol.mesh.len();
    let h = |i: usize| cx * sol.z[i * n] + cy * sol.z[i * n + 1];
    let dh = |i: usize| cx * sol.dz[i * n] + cy * sol.dz[i * n + 1];
    for i in 0..len.saturating_sub(1) {
        let (s0, s1) = (sol.mesh[i], sol.mesh[i + 1]);
        let w = s1 - s0;
        if w <= 0.0 {
            continue;
        }
        let (y0, y1) = (h(i), h(i + 1));
        let (d0, d1) = (dh(i) * w, dh(i + 1) * w);
        // Hermite cubic p(t); p'(t) = a t² + b t + c, p''(t) = 2 a t + b. Every local maximum
        // inside the interval counts, also where p' has the same sign at both ends (a maximum
        // and a minimum inside one interval, as near the tip of an S-shaped rod).
        let a = 6.0 * y0 + 3.0 * d0 - 6.0 * y1 + 3.0 * d1;
        let b = -6.0 * y0 - 4.0 * d0 + 6.0 * y1 - 2.0 * d1;
        let c = d0;
        let mut roots = [f64::NAN; 2];
        if a.abs() <= 1e-14 * (b.abs() + c.abs()) {
            if b != 0.0 {
                roots[0] = -c / b;
            }
        } else {
            let disc = b * b - 4.0 * a * c;
            if disc >= 0.0 {
                let q = -0.5 * (b + b.signum() * disc.sqrt());
                roots = [q / a, if q != 0.0 { c / q } else { f64::NAN }];
            }
        }
        for t in roots {
            if !((0.0..=1.0).contains(&t) && 2.0 * a * t + b < 0.0) {
                continue;
            }
            let (t2, t3) = (t * t, t * t * t);
            let y = (2.0 * t3 - 3.0 * t2 + 1.0) * y0
                + (t3 - 2.0 * t2 + t) * d0
                + (-2.0 * t3 + 3.0 * t2) * y1
                + (t3 - t2) * d1;
            f(s0 + t * w, y);
        }
    }
}

pub(crate) fn extrema(sol: &Solution, cx: f64, cy: f64) -> Extrema {
    let n = sol.n;
    let mut out = Extrema {
        max: f64::NEG_INFINITY,
        interior: f64::NEG_INFINITY,
        s_interior: f64::NAN,
    };
    for i in 0..sol.mesh.len() {
        out.max = out.max.max(cx * sol.z[i * n] + cy * sol.z[i * n + 1]);
    }
    for_each_max(sol, cx, cy, |s, y| {
        out.max = out.max.max(y);
        if s < 1.0 - 1e-9 && y > out.interior {
            out.interior = y;
            out.s_interior = s;
        }
    });
    out
}

/// How a rod lies against the surface line through its tip, inclined by β (normal
/// `n = (−sin β, cos β)`): the largest height above that line over `s < 1` and where, and how the
/// tip arrives at it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Clearance {
    /// Largest height `n·(p(s) − p(1))` over `s < 1` (negative: the rod stays below the line).
    pub height: f64,
    /// Its arc length.
    pub s: f64,
    /// `sin(φ(1) − β)`: positive when the tip arrives from below the surface.
    pub tip_approach: f64,
}

impl Clearance {
    /// The rod crosses the surface: a point with `s < 1` above the line, or the tip arriving from
    /// above it (then the points just before the tip are above).
    pub fn penetrates(&self) -> bool {
        self.excess().0 > 0.0
    }
    /// One measure that is positive exactly when the rod penetrates, and the arc length it refers
    /// to: `max(height, −tip_approach)`.
    pub(crate) fn excess(&self) -> (f64, f64) {
        if self.height > -self.tip_approach {
            (self.height, self.s)
        } else {
            (-self.tip_approach, 1.0)
        }
    }
}

/// The [`Clearance`] of a numerical solution (exact on its cubic Hermite interpolant).
pub(crate) fn clearance(sol: &Solution, beta: f64) -> Clearance {
    let (sb, cb) = beta.sin_cos();
    let ex = extrema(sol, -sb, cb);
    let (za, zb) = (sol.left(), sol.right());
    let h = |z: &[f64]| -sb * z[0] + cb * z[1];
    let (height, s) = if ex.interior > h(za) {
        (ex.interior, ex.s_interior)
    } else {
        (h(za), 0.0)
    };
    Clearance {
        height: height - h(zb),
        s,
        tip_approach: (zb[2] - beta).sin(),
    }
}
