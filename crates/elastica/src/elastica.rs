//! The uniform clamped rod with a tip force: closed-form solutions of sections 2.1.1 and 2.1.2.

use crate::branch::Branch;
use crate::ellint::{f_e_sc, half_pi_plus, jacobi_am_reduced, modulus_checked, Modulus};
use crate::error::{finite, ElasticaError};
use crate::roots::brent_root;
use serde::{Deserialize, Serialize};
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4};
use std::sync::OnceLock;

/// One point of an elastica: arc length, position, slope and curvature (= internal moment).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ShapePoint {
    /// arc length from the clamp, in `[0, 1]`
    pub s: f64,
    /// x coordinate (clamp at the origin)
    pub x: f64,
    /// y coordinate
    pub y: f64,
    /// slope angle `phi(s)` (`pi/2` at the clamp)
    pub phi: f64,
    /// curvature `kappa(s) = m(s)` (internal bending moment)
    pub kappa: f64,
}

/// A closed-form elastica: clamp at the origin pointing up, tip force
/// `F = (f sin(alpha), -f cos(alpha))`, free tip (no moment), tip slope `phi1`.
///
/// `m_base = m(0) = kappa(0)` is the internal moment at the clamp: negative for the convex
/// (right-handed) rod. The paper's clamp reaction moment is `m0 = -m_base`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Elastica {
    /// force magnitude `f` (units EI/L^2)
    pub f: f64,
    /// force angle `alpha` (0: straight down; negative: rotated clockwise)
    pub alpha: f64,
    /// tip slope `phi1 = phi(1)`
    pub phi1: f64,
    /// family of the solution
    pub branch: Branch,
    /// tip x coordinate `x(1)`
    pub x1: f64,
    /// tip y coordinate `y(1)`
    pub y1: f64,
    /// `m(0) = kappa(0)`; the paper's clamp moment is `m0 = -m_base`
    pub m_base: f64,
    /// slope at the flex point `phi_b = pi + 2 alpha - phi1` (2.12); `None` on the convex branch
    pub phi_b: Option<f64>,
    /// arc length of the flex point (2.16); `None` on the convex branch
    pub s_b: Option<f64>,
    #[serde(skip)]
    md: Option<Modulus>,
}

impl Elastica {
    /// The elastica of `branch` with force angle `alpha` and tip slope `phi1`; `f` from (2.8)
    /// (convex) or (2.15) (one flex), the tip from (2.10) / (2.17).
    ///
    /// Domain: convex `alpha in [-pi/2, 0]`, one flex `alpha in [-pi/4, 0]`, both
    /// `0 <= phi1 <= pi/2 + 2 alpha` (2.5), (2.13) (a few ulp above the bound are accepted and
    /// treated as the turning point).
    pub fn new(branch: Branch, alpha: f64, phi1: f64) -> Result<Elastica, ElasticaError> {
        let md = modulus_checked(branch, alpha, phi1)?;
        Ok(Self::from_modulus(branch, md))
    }

    /// The turning point of `alpha` (`phi1 = pi/2 + 2 alpha` exactly, `kappa(0) = 0`), where the
    /// two branches meet; `alpha in [-pi/4, 0]`.
    pub fn turning(branch: Branch, alpha: f64) -> Result<Elastica, ElasticaError> {
        finite("alpha", alpha)?;
        if !(-FRAC_PI_4..=0.0).contains(&alpha) {
            return Err(ElasticaError::AlphaOutOfRange {
                alpha,
                min: -FRAC_PI_4,
                max: 0.0,
            });
        }
        let phi1 = half_pi_plus(1.0, &[2.0 * alpha]).max(0.0);
        let md = Modulus::new(alpha, phi1, 0.0, -2.0 * alpha)?;
        Ok(Self::from_modulus(branch, md))
    }

    fn from_modulus(branch: Branch, md: Modulus) -> Elastica {
        let k = md.k;
        // g = sqrt(f): (2.8) is g = K + F_top, (2.15) is g = 3K - F_top.
        let (g, a1, b1, sign) = match branch {
            Branch::Convex => {
                let g = md.kk + md.f_top;
                (
                    g,
                    2.0 * (md.ee + md.e_top) / g - 1.0,
                    2.0 * k * md.c_top / g,
                    -1.0,
                )
            }
            Branch::OneFlex => {
                let g = 3.0 * md.kk - md.f_top;
                (
                    g,
                    2.0 * (3.0 * md.ee - md.e_top) / g - 1.0,
                    -2.0 * k * md.c_top / g,
                    1.0,
                )
            }
        };
        let (sa, ca) = md.alpha.sin_cos();
        let (phi_b, s_b) = match branch {
            Branch::Convex => (None, None),
            Branch::OneFlex => (Some(md.phi_b()), Some(md.k_minus_f_top() / g)),
        };
        Elastica {
            f: g * g,
            alpha: md.alpha,
            phi1: md.phi1,
            branch,
            x1: -a1 * sa + b1 * ca,
            y1: a1 * ca + b1 * sa,
            m_base: sign * 2.0 * g * k * md.c_top + 0.0, // + 0.0: no -0 at the turning point
            phi_b,
            s_b,
            md: Some(md),
        }
    }

    fn modulus(&self) -> Result<Modulus, ElasticaError> {
        match self.md {
            Some(md) => Ok(md),
            // deserialized value: recompute
            None => modulus_checked(self.branch, self.alpha, self.phi1),
        }
    }

    /// Horizontal force component `f sin(alpha)` (<= 0: points to -x).
    pub fn fx(&self) -> f64 {
        self.f * self.alpha.sin()
    }

    /// Vertical force component `-f cos(alpha)` (<= 0: points down).
    pub fn fy(&self) -> f64 {
        -self.f * self.alpha.cos()
    }

    /// Number of flex points: 0 on the convex branch, 1 on the one-flex branch (0 at the turning
    /// point itself, where the flex point sits at the clamp).
    pub fn flex_count(&self) -> usize {
        match self.s_b {
            Some(sb) if sb > 0.0 => 1,
            _ => 0,
        }
    }

    /// Highest point of the rod: with `0 <= phi <= pi` all along (true in this domain) `y` is
    /// non-decreasing in `s`, so it is the tip height `y1`.
    pub fn y_max(&self) -> f64 {
        self.y1
    }

    /// `n >= 2` points uniformly in `s` on `[0, 1]` (both ends included).
    pub fn shape(&self, n: usize) -> Result<Vec<ShapePoint>, ElasticaError> {
        if n < 2 {
            return Err(ElasticaError::OutOfRange {
                name: "n",
                value: n as f64,
                min: 2.0,
                max: f64::INFINITY,
            });
        }
        (0..n)
            .map(|i| {
                self.point_at(if i + 1 == n {
                    1.0
                } else {
                    i as f64 / (n - 1) as f64
                })
            })
            .collect()
    }

    /// The point at arc length `s in [0, 1]`.
    ///
    /// With `g = sqrt(f)` the Jacobi argument `w = F_top - g s` (convex) or `w = F_top + g s`
    /// (one flex) runs from `F(theta_top)` to `-K` resp. `3K`, and with `theta = am(w|m)`:
    /// `sin(sigma/2) = k sn`, `phi = alpha + pi/2 + sigma`, `kappa = +-2 g k cn`,
    /// and along `e_a = (-sin a, cos a)`, `e_b = (cos a, sin a)`:
    /// `a(s) = +-(2/g)(E(am w) - E(theta_top)) - s`, `b(s) = +-(2k/g)(cn w - cos theta_top)`
    /// (upper sign for one flex). The one-flex arc is thus covered piecewise by one formula:
    /// `w < K` before the flex point, `w > K` after it.
    pub fn point_at(&self, s: f64) -> Result<ShapePoint, ElasticaError> {
        finite("s", s)?;
        if !(0.0..=1.0).contains(&s) {
            return Err(ElasticaError::OutOfRange {
                name: "s",
                value: s,
                min: 0.0,
                max: 1.0,
            });
        }
        if s == 0.0 {
            return Ok(ShapePoint {
                s,
                x: 0.0,
                y: 0.0,
                phi: FRAC_PI_2,
                kappa: self.m_base,
            });
        }
        if s == 1.0 {
            return Ok(ShapePoint {
                s,
                x: self.x1,
                y: self.y1,
                phi: self.phi1,
                kappa: 0.0,
            });
        }
        let md = self.modulus()?;
        let g = self.f.sqrt();
        let sign = match self.branch {
            Branch::Convex => -1.0,
            Branch::OneFlex => 1.0,
        };
        let w = md.f_top + sign * g * s;
        // reduce to |r| <= K: am(w) = n pi + am(w - 2nK), E(am w) = 2nE + E(am r)
        let n = (w / (2.0 * md.kk)).round();
        let r = w - 2.0 * n * md.kk;
        let th = jacobi_am_reduced(r, md.m, md.kk)?;
        let (sr, cr) = th.sin_cos();
        let dn2 = 1.0 - md.m * sr * sr;
        let (_, er) = f_e_sc(sr, cr * cr, dn2, md.m)?;
        let parity = if (n as i64) % 2 == 0 { 1.0 } else { -1.0 };
        let (sn, cn) = (parity * sr, parity * cr);
        let e_w = 2.0 * n * md.ee + er;
        let sigma = 2.0 * (md.k * sn).atan2(dn2.sqrt());
        let a = sign * 2.0 / g * (e_w - md.e_top) - s;
        let b = sign * 2.0 * md.k / g * (cn - md.c_top);
        let (sa, ca) = self.alpha.sin_cos();
        Ok(ShapePoint {
            s,
            x: -a * sa + b * ca,
            y: a * ca + b * sa,
            phi: half_pi_plus(1.0, &[self.alpha, sigma]),
            kappa: sign * 2.0 * g * md.k * cn,
        })
    }
}

/// Force of the convex elastica (2.8): `f = K(phi1, phi1, alpha)^2 / 2 = (K(m) + F(theta_top|m))^2`.
pub fn convex_force(alpha: f64, phi1: f64) -> Result<f64, ElasticaError> {
    Ok(Elastica::new(Branch::Convex, alpha, phi1)?.f)
}

/// Force of the one-flex elastica (2.15):
/// `f = [K(phi1, phi1, a) - 2 K(pi + 2a - phi1, phi1, a)]^2 / 2 = (3 K(m) - F(theta_top|m))^2`.
pub fn flex_force(alpha: f64, phi1: f64) -> Result<f64, ElasticaError> {
    Ok(Elastica::new(Branch::OneFlex, alpha, phi1)?.f)
}

/// Turning point of the convex family at `alpha in [-pi/4, 0]` (section 2.1.2):
/// `(phi1_a, f_a) = (pi/2 + 2 alpha, 4 K^2(k = sin(alpha/2)))`, i.e. `m = sin^2(alpha/2)`.
/// At `alpha = 0` this is the limit `alpha -> 0-`, `f = pi^2` (the convex family at `alpha = 0`
/// itself ends at `pi^2/4`: the corner `(alpha, phi1) = (0, pi/2)` is singular).
pub fn turning_point(alpha: f64) -> Result<(f64, f64), ElasticaError> {
    finite("alpha", alpha)?;
    if !(-FRAC_PI_4..=0.0).contains(&alpha) {
        return Err(ElasticaError::AlphaOutOfRange {
            alpha,
            min: -FRAC_PI_4,
            max: 0.0,
        });
    }
    // complementary parameter mc = cos^2(alpha/2) keeps K accurate (m = sin^2(alpha/2))
    let c = (0.5 * alpha).cos();
    let kk = crate::ellint::k_mc(c * c)?;
    Ok((half_pi_plus(1.0, &[2.0 * alpha]).max(0.0), 4.0 * kk * kk))
}

/// `(f_, eta_)` of section 3.1: the vertical load (`alpha = 0`) that makes the convex rod's tip
/// horizontal (`phi1 = 0`), `f_ = K(1/2)^2`, and that rod's tip height `eta_` (computed once).
pub fn lower_limit() -> (f64, f64) {
    static CELL: OnceLock<(f64, f64)> = OnceLock::new();
    *CELL.get_or_init(|| match Elastica::new(Branch::Convex, 0.0, 0.0) {
        Ok(e) => (e.f, e.y1),
        // unreachable: (0, 0) is inside the domain; keep the published digits as a fallback
        Err(_) => (3.437_592_909_010_186, 0.456_946_581_044_463_6),
    })
}

fn y1_of(branch: Branch, alpha: f64, phi1: f64) -> Result<f64, ElasticaError> {
    Ok(Elastica::new(branch, alpha, phi1)?.y1)
}

/// All tip slopes `phi1 in [0, pi/2 + 2 alpha]` with tip height `y1 = eta` on `branch`, in
/// increasing `phi1`. Roots are bracketed on a 64-interval grid and refined by Brent's method
/// (two roots closer than the grid spacing may be missed).
pub fn solve_eta_all(branch: Branch, alpha: f64, eta: f64) -> Result<Vec<Elastica>, ElasticaError> {
    finite("eta", eta)?;
    modulus_checked(branch, alpha, 0.0)?;
    let top = (FRAC_PI_2 + 2.0 * alpha).max(0.0);
    const N: usize = 64;
    let grid: Vec<f64> = (0..=N)
        .map(|i| {
            if i == N {
                top
            } else {
                top * i as f64 / N as f64
            }
        })
        .collect();
    let vals: Vec<f64> = grid
        .iter()
        .map(|&p| y1_of(branch, alpha, p).map(|y| y - eta))
        .collect::<Result<_, _>>()?;
    let mut out = Vec::new();
    let end_tol = 1e-13;
    if vals[0].abs() <= end_tol {
        out.push(0.0);
    }
    for i in 0..N {
        let (a, b, fa, fb) = (grid[i], grid[i + 1], vals[i], vals[i + 1]);
        if fa.abs() <= end_tol {
            continue;
        }
        if fb.abs() <= end_tol {
            out.push(b);
            continue;
        }
        if fa.signum() != fb.signum() {
            let r = brent_root(
                |p| y1_of(branch, alpha, p).map(|y| y - eta),
                a,
                b,
                1e-15,
                200,
            )?;
            out.push(r);
        }
    }
    if out.is_empty() && top == 0.0 && vals[0].abs() <= 1e-12 {
        out.push(0.0);
    }
    out.into_iter()
        .map(|p| Elastica::new(branch, alpha, p))
        .collect()
}

/// The tip slope `phi1` with tip height `y1 = eta` at this `alpha` on `branch` (1-D root in
/// `phi1` over `[0, pi/2 + 2 alpha]`). On the convex branch `y1` is increasing in `phi1` and the
/// root is unique; on the one-flex branch `y1(phi1)` rises and falls, and the root with the
/// largest `phi1` is returned (see [`solve_eta_all`] for all of them).
pub fn solve_eta(branch: Branch, alpha: f64, eta: f64) -> Result<Elastica, ElasticaError> {
    let all = solve_eta_all(branch, alpha, eta)?;
    match all.last() {
        Some(e) => Ok(*e),
        None => {
            let top = (FRAC_PI_2 + 2.0 * alpha).max(0.0);
            Err(ElasticaError::NoRoot {
                what: "y1(phi1) = eta",
                a: 0.0,
                b: top,
                fa: y1_of(branch, alpha, 0.0)? - eta,
                fb: y1_of(branch, alpha, top)? - eta,
            })
        }
    }
}
