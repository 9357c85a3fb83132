//! Elliptic integrals: thin checked wrappers of the `ellip` crate, forms that keep full accuracy
//! near their singular points, the Jacobi amplitude, and the paper's auxiliary functions
//! (Appendix A): `I1..I4`, `K(phi, phi1, alpha)`, `X`, `Y`.
//!
//! Conventions: parameter `m = k^2` (modulus `k`), complementary parameter `mc = 1 - m`.
//!
//! Why the extra forms: `F(phi|m)` and `E(phi|m)` computed from the *angle* lose accuracy where
//! the angle itself is ill-determined, e.g. `phi = asin(x)` with `x -> 1`, which is exactly what
//! happens at the elastica's turning point. [`f_e_sc`] takes `sin(phi)` and `cos^2(phi)`
//! separately (Carlson, DLMF 19.25.5 and 19.25.9) so callers can supply `cos^2` in a
//! cancellation-free product form. Likewise [`k_mc`] / [`e_mc`] take the complementary parameter,
//! which is the only way to keep relative accuracy as `m -> 1` (`K` depends on `ln(1 - m)`, so
//! forming `m` in floating point first already loses the digits). In this crate's domain
//! `m = (1 - sin(phi1 - alpha))/2 <= 1/2` always (because `phi1 >= 0 >= alpha`), so `m -> 1` does
//! not occur in the elastica itself; the tests still document `ellip`'s behaviour there.

use crate::branch::Branch;
use crate::error::{finite, ElasticaError};
use std::f64::consts::{FRAC_PI_2, PI, SQRT_2};

fn ell<T>(r: Result<T, &'static str>) -> Result<T, ElasticaError> {
    r.map_err(ElasticaError::Ellip)
}

/// Carlson's symmetric integral `R_F(x, y, z)` (x, y, z >= 0, at most one zero).
pub fn carlson_rf(x: f64, y: f64, z: f64) -> Result<f64, ElasticaError> {
    ell(ellip::elliprf(x, y, z))
}

/// Carlson's symmetric integral `R_D(x, y, z)` (x, y >= 0, at most one zero; z > 0).
pub fn carlson_rd(x: f64, y: f64, z: f64) -> Result<f64, ElasticaError> {
    ell(ellip::elliprd(x, y, z))
}

/// Complete integral of the first kind `K(m)`, `m < 1` (the `ellip` implementation).
pub fn legendre_k(m: f64) -> Result<f64, ElasticaError> {
    finite("m", m)?;
    if m >= 1.0 {
        return Err(ElasticaError::OutOfRange {
            name: "m",
            value: m,
            min: f64::NEG_INFINITY,
            max: 1.0,
        });
    }
    ell(ellip::ellipk(m))
}

/// Complete integral of the second kind `E(m)`, `m <= 1` (the `ellip` implementation).
pub fn legendre_e(m: f64) -> Result<f64, ElasticaError> {
    finite("m", m)?;
    ell(ellip::ellipe(m))
}

/// Incomplete integral of the first kind `F(phi|m) = int_0^phi (1 - m sin^2 t)^(-1/2) dt`
/// (the `ellip` implementation).
pub fn legendre_f(phi: f64, m: f64) -> Result<f64, ElasticaError> {
    finite("phi", phi)?;
    finite("m", m)?;
    ell(ellip::ellipf(phi, m))
}

/// Incomplete integral of the second kind `E(phi|m) = int_0^phi (1 - m sin^2 t)^(1/2) dt`
/// (the `ellip` implementation).
pub fn legendre_e_inc(phi: f64, m: f64) -> Result<f64, ElasticaError> {
    finite("phi", phi)?;
    finite("m", m)?;
    ell(ellip::ellipeinc(phi, m))
}

/// `K` from the complementary parameter: `K = R_F(0, mc, 1)`, accurate to a few ulp for every
/// `mc in (0, 1]`, in particular as `m = 1 - mc -> 1`.
pub fn k_mc(mc: f64) -> Result<f64, ElasticaError> {
    finite("mc", mc)?;
    if mc <= 0.0 {
        return Err(ElasticaError::OutOfRange {
            name: "mc",
            value: mc,
            min: f64::MIN_POSITIVE,
            max: f64::INFINITY,
        });
    }
    carlson_rf(0.0, mc, 1.0)
}

/// `E` from the complementary parameter: `E = R_F(0, mc, 1) - (m/3) R_D(0, mc, 1)`,
/// `m = 1 - mc` (DLMF 19.25.1), accurate for every `mc in [0, 1]`.
pub fn e_mc(mc: f64) -> Result<f64, ElasticaError> {
    finite("mc", mc)?;
    if !(0.0..=1.0).contains(&mc) {
        return Err(ElasticaError::OutOfRange {
            name: "mc",
            value: mc,
            min: 0.0,
            max: 1.0,
        });
    }
    if mc == 0.0 {
        return Ok(1.0);
    }
    let m = 1.0 - mc;
    Ok(carlson_rf(0.0, mc, 1.0)? - m / 3.0 * carlson_rd(0.0, mc, 1.0)?)
}

/// `F(phi|m)` and `E(phi|m)` for `|phi| <= pi/2` from the complementary parameter `mc = 1 - m`.
///
/// The mend for `m -> 1`: `ellip` forms `1 - m sin^2(phi)` directly, which cancels
/// catastrophically when both `m` and `sin^2(phi)` are near 1 (measured: 4e-10 relative error at
/// `m = 1 - 2^-52`, `phi = 1.5707963267948966`); here it is `cos^2(phi) + mc sin^2(phi)`, a sum of
/// positive terms, and the integrals come from Carlson's `R_F`, `R_D` (DLMF 19.25.5, 19.25.9).
pub fn legendre_f_e_mc(phi: f64, mc: f64) -> Result<(f64, f64), ElasticaError> {
    finite("phi", phi)?;
    finite("mc", mc)?;
    if phi.abs() > FRAC_PI_2 {
        return Err(ElasticaError::OutOfRange {
            name: "phi",
            value: phi,
            min: -FRAC_PI_2,
            max: FRAC_PI_2,
        });
    }
    if !(0.0..=1.0).contains(&mc) {
        return Err(ElasticaError::OutOfRange {
            name: "mc",
            value: mc,
            min: 0.0,
            max: 1.0,
        });
    }
    let (s, c) = phi.sin_cos();
    let c2 = c * c;
    f_e_sc(s, c2, c2 + mc * s * s, 1.0 - mc)
}

/// `F(phi|m)` and `E(phi|m)` for `|phi| <= pi/2` from `s = sin(phi)`, `c2 = cos^2(phi)` and
/// `dn2 = 1 - m sin^2(phi)`, all supplied by the caller (DLMF 19.25.5, 19.25.9):
/// `F = s R_F(c2, dn2, 1)`, `E = F - (m/3) s^3 R_D(c2, dn2, 1)`.
pub fn f_e_sc(s: f64, c2: f64, dn2: f64, m: f64) -> Result<(f64, f64), ElasticaError> {
    if s == 0.0 {
        return Ok((0.0, 0.0));
    }
    let rf = carlson_rf(c2.max(0.0), dn2, 1.0)?;
    let rd = carlson_rd(c2.max(0.0), dn2, 1.0)?;
    let f = s * rf;
    Ok((f, f - m / 3.0 * s * s * s * rd))
}

/// Jacobi amplitude `am(w|m)` for `m <= 1/2 ... < 1` and `|w| <= K(m)`: the `theta` in
/// `[-pi/2, pi/2]` with `F(theta|m) = w`. Safeguarded Newton iteration (`dF/dtheta =
/// 1/sqrt(1 - m sin^2)`, between 1 and `1/sqrt(mc)`) inside the bracket `[-pi/2, pi/2]`.
/// `kk` is `K(m)`; `|w| >= kk` returns `+-pi/2` exactly.
pub fn jacobi_am_reduced(w: f64, m: f64, kk: f64) -> Result<f64, ElasticaError> {
    finite("w", w)?;
    if w >= kk {
        return Ok(FRAC_PI_2);
    }
    if w <= -kk {
        return Ok(-FRAC_PI_2);
    }
    if w == 0.0 {
        return Ok(0.0);
    }
    let (mut lo, mut hi) = (-FRAC_PI_2, FRAC_PI_2);
    let mut th = w * FRAC_PI_2 / kk;
    for _ in 0..100 {
        let (s, c) = th.sin_cos();
        let dn2 = 1.0 - m * s * s;
        let (f, _) = f_e_sc(s, c * c, dn2, m)?;
        let r = f - w;
        if r > 0.0 {
            hi = th;
        } else {
            lo = th;
        }
        let step = r * dn2.sqrt();
        let mut next = th - step;
        if !(next > lo && next < hi) {
            next = 0.5 * (lo + hi);
        }
        let done = (next - th).abs() <= 2.0 * f64::EPSILON * th.abs().max(1e-300);
        th = next;
        if done || hi - lo <= 2.0 * f64::EPSILON * th.abs() {
            return Ok(th);
        }
    }
    Err(ElasticaError::NoConvergence {
        what: "jacobi_am",
        iterations: 100,
        width: hi - lo,
    })
}

// ------------------------------------------------------------------------------------------
// Exact-ish angle arithmetic: pi/2 + a + b + ... in double-double, so that the distance to the
// ends of the domain (e.g. delta = pi/2 + 2 alpha - phi1 at the turning point) keeps its full
// relative accuracy even when it is a few ulp of pi/2.
// ------------------------------------------------------------------------------------------
const PI_2_LO: f64 = 6.123_233_995_736_766e-17; // pi/2 - FRAC_PI_2

fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// `k * pi/2 + sum(terms)` with the rounding errors of the sum carried along (double-double).
pub(crate) fn half_pi_plus(k: f64, terms: &[f64]) -> f64 {
    let (mut s, mut e) = (k * FRAC_PI_2, k * PI_2_LO);
    for &t in terms {
        let (s2, e2) = two_sum(s, t);
        s = s2;
        e += e2;
    }
    s + e
}

// ------------------------------------------------------------------------------------------
// The modulus data of an elastica (alpha, phi1), shared by everything below.
// ------------------------------------------------------------------------------------------

/// Elliptic data of the family `[sin(t - alpha) - sin(phi1 - alpha)]^(-1/2)` at given
/// `(alpha, phi1)`, computed once. With `u = phi1 - alpha`, `k = sin(pi/4 - u/2)`,
/// `m = k^2 = (1 - sin u)/2` (Appendix A) and the substitution `sin(t/2 - alpha/2 - pi/4) =
/// k sin(theta)`, the zeros `t = phi1` and `t = phi_b = pi + 2 alpha - phi1` map to
/// `theta = -pi/2, pi/2` and the clamp slope `t = pi/2` maps to `theta_top`,
/// `sin(theta_top) = sin(-alpha/2)/k`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Modulus {
    pub alpha: f64,
    pub phi1: f64,
    /// `pi/2 + 2 alpha - phi1 >= 0` (distance to the turning point)
    pub delta: f64,
    /// `pi/2 - phi1`
    pub eps: f64,
    /// `pi/2 - u = pi/2 - phi1 + alpha`
    pub h: f64,
    pub k: f64,
    pub m: f64,
    pub mc: f64,
    /// complete integrals K(m), E(m)
    pub kk: f64,
    pub ee: f64,
    /// sin, cos of theta_top
    pub s_top: f64,
    pub c_top: f64,
    /// F(theta_top|m), E(theta_top|m)
    pub f_top: f64,
    pub e_top: f64,
}

impl Modulus {
    /// `delta` and `eps` must be computed accurately by the caller (see `half_pi_plus`).
    pub fn new(alpha: f64, phi1: f64, delta: f64, eps: f64) -> Result<Modulus, ElasticaError> {
        let delta = delta.max(0.0);
        let eps = eps.max(delta);
        let h = 0.5 * (delta + eps);
        let k = (0.5 * h).sin();
        let m = k * k;
        let mc = {
            let c = (0.5 * h).cos();
            c * c
        };
        let sa = (-0.5 * alpha).sin();
        // cos^2(theta_top) = (k^2 - sa^2)/k^2 = sin(delta/2) sin(eps/2) / k^2: no cancellation
        let (s_top, c2_top) = if k == 0.0 {
            (0.0, 1.0)
        } else {
            let s = (sa / k).min(1.0);
            let c2 = (0.5 * delta).sin() * (0.5 * eps).sin() / (k * k);
            let r2 = s * s + c2; // = 1 up to rounding; normalise for consistency
            (s / r2.sqrt(), c2 / r2)
        };
        let dn2_top = {
            let c = (0.5 * alpha).cos();
            c * c
        };
        let (f_top, e_top) = f_e_sc(s_top, c2_top, dn2_top, m)?;
        let kk = carlson_rf(0.0, mc, 1.0)?;
        let ee = kk - m / 3.0 * carlson_rd(0.0, mc, 1.0)?;
        Ok(Modulus {
            alpha,
            phi1,
            delta,
            eps,
            h,
            k,
            m,
            mc,
            kk,
            ee,
            s_top,
            c_top: c2_top.sqrt(),
            f_top,
            e_top,
        })
    }

    /// `K(m) - F(theta_top|m)` without cancellation near the turning point (`theta_top -> pi/2`):
    /// by the addition theorem `F(theta) + F(psi) = K` when `tan(theta) tan(psi) = 1/k'`
    /// (Byrd and Friedman 1971, 117.01), so it equals `F(psi)` with
    /// `sin^2 psi = c^2/(c^2 + mc s^2)`, `cos^2 psi = mc s^2/(c^2 + mc s^2)`,
    /// `1 - m sin^2 psi = mc/(c^2 + mc s^2)` (`s, c` of `theta_top`).
    pub fn k_minus_f_top(&self) -> f64 {
        let (s, c) = (self.s_top, self.c_top);
        let d = c * c + self.mc * s * s;
        if c == 0.0 {
            return 0.0;
        }
        match f_e_sc(c / d.sqrt(), self.mc * s * s / d, self.mc / d, self.m) {
            Ok((f, _)) => f,
            Err(_) => self.kk - self.f_top,
        }
    }

    /// `phi_b = pi + 2 alpha - phi1`, the other zero of the bracket (2.12).
    pub fn phi_b(&self) -> f64 {
        half_pi_plus(1.0, &[self.alpha, self.h])
    }

    /// `(sin theta, cos^2 theta)` of the slope `phi in [phi1, phi_b]`.
    pub fn theta_sc(&self, phi: f64) -> (f64, f64) {
        if self.k == 0.0 {
            return (0.0, 1.0);
        }
        // sin(theta) = sin((phi - alpha - pi/2)/2)/k;
        // cos^2(theta) = sin((phi - phi1)/2) sin((phi_b - phi)/2)/k^2
        let x = half_pi_plus(-1.0, &[phi, -self.alpha]);
        let s = ((0.5 * x).sin() / self.k).clamp(-1.0, 1.0);
        let a = phi - self.phi1;
        let b = half_pi_plus(2.0, &[2.0 * self.alpha, -self.phi1, -phi]);
        let c2 = ((0.5 * a).sin() * (0.5 * b).sin() / (self.k * self.k)).max(0.0);
        let r2 = s * s + c2;
        (s / r2.sqrt(), c2 / r2)
    }

    /// `F` and `E` at the slope `phi` (see `theta_sc`).
    pub fn f_e_at_phi(&self, phi: f64) -> Result<(f64, f64, f64), ElasticaError> {
        let (s, c2) = self.theta_sc(phi);
        let (f, e) = f_e_sc(s, c2, 1.0 - self.m * s * s, self.m)?;
        Ok((f, e, c2.sqrt()))
    }

    /// `(A, B)`: `-int_{pi/2}^{phi} (cos t, sin t)[..]^(-1/2) dt` split along
    /// `e_a = (-sin a, cos a)` and `e_b = (cos a, sin a)`.
    pub fn ab_unscaled(&self, phi: f64) -> Result<(f64, f64), ElasticaError> {
        let (f, e, c) = self.f_e_at_phi(phi)?;
        let ja = SQRT_2 * (2.0 * (e - self.e_top) - (f - self.f_top));
        let jb = -2.0 * SQRT_2 * self.k * (self.c_top - c);
        Ok((-ja, -jb))
    }
}

/// Tolerance on `phi1 <= pi/2 + 2 alpha`: a caller who computes `pi/2 + 2 alpha` in floating
/// point may exceed the exact bound by a few ulp; such `phi1` are taken as the turning point.
const TURNING_TOL: f64 = 4.0 * f64::EPSILON;

/// Validate `(branch, alpha, phi1)` and compute the elliptic data.
pub(crate) fn modulus_checked(
    branch: Branch,
    alpha: f64,
    phi1: f64,
) -> Result<Modulus, ElasticaError> {
    finite("alpha", alpha)?;
    finite("phi1", phi1)?;
    let (min, max) = branch.alpha_range();
    if !(min..=max).contains(&alpha) {
        return Err(ElasticaError::AlphaOutOfRange { alpha, min, max });
    }
    let delta = half_pi_plus(1.0, &[2.0 * alpha, -phi1]);
    if phi1 < 0.0 || delta < -TURNING_TOL {
        return Err(ElasticaError::Phi1OutOfRange {
            phi1,
            min: 0.0,
            max: FRAC_PI_2 + 2.0 * alpha,
            branch,
        });
    }
    let eps = half_pi_plus(1.0, &[-phi1]);
    Modulus::new(alpha, phi1, delta, eps)
}

/// Validate the general (branch-free) domain of the paper's integrals: `alpha in [-pi/2, 0]`,
/// `phi1 in [0, pi/2 + 2 alpha]`, and `phi in [phi1, phi_b]`.
fn modulus_for(phi: f64, phi1: f64, alpha: f64) -> Result<Modulus, ElasticaError> {
    let md = modulus_checked(Branch::Convex, alpha, phi1)?;
    finite("phi", phi)?;
    let phib = md.phi_b();
    if phi < phi1 || phi > phib {
        return Err(ElasticaError::OutOfRange {
            name: "phi",
            value: phi,
            min: phi1,
            max: phib,
        });
    }
    Ok(md)
}

/// The paper's `K(phi, phi1, alpha) = -int_{pi/2}^{phi} [sin(t - alpha) - sin(phi1 - alpha)]^(-1/2) dt`
/// (2.7), for `phi in [phi1, pi + 2 alpha - phi1]`; `sqrt(2 f) s = K(phi, ..)` on the convex arc.
/// Computed as `sqrt(2) [F(theta_top|m) - F(theta(phi)|m)]`; both terms are at most
/// `K(1/2) = 1.854`, so the difference has an absolute error of a few 1e-16.
pub fn big_k(phi: f64, phi1: f64, alpha: f64) -> Result<f64, ElasticaError> {
    let md = modulus_for(phi, phi1, alpha)?;
    let (f, _, _) = md.f_e_at_phi(phi)?;
    Ok(SQRT_2 * (md.f_top - f))
}

/// The paper's `X(phi; f, phi1, alpha)` (2.10): `-1/sqrt(2f) int_{pi/2}^{phi} cos(t)[..]^(-1/2) dt`.
pub fn big_x(phi: f64, f: f64, phi1: f64, alpha: f64) -> Result<f64, ElasticaError> {
    let md = modulus_for(phi, phi1, alpha)?;
    let g = force_scale(f)?;
    let (a, b) = md.ab_unscaled(phi)?;
    Ok((-a * alpha.sin() + b * alpha.cos()) / g)
}

/// The paper's `Y(phi; f, phi1, alpha)` (2.10): `-1/sqrt(2f) int_{pi/2}^{phi} sin(t)[..]^(-1/2) dt`.
pub fn big_y(phi: f64, f: f64, phi1: f64, alpha: f64) -> Result<f64, ElasticaError> {
    let md = modulus_for(phi, phi1, alpha)?;
    let g = force_scale(f)?;
    let (a, b) = md.ab_unscaled(phi)?;
    Ok((a * alpha.cos() + b * alpha.sin()) / g)
}

fn force_scale(f: f64) -> Result<f64, ElasticaError> {
    finite("f", f)?;
    if f <= 0.0 {
        return Err(ElasticaError::OutOfRange {
            name: "f",
            value: f,
            min: f64::MIN_POSITIVE,
            max: f64::INFINITY,
        });
    }
    Ok((2.0 * f).sqrt())
}

/// Modulus `k(u) = sqrt((1 - sin u)/2)` and the amplitude of `x` for Appendix A, with the
/// domain check `u <= x <= pi - u`, `u in [-pi/2, pi/2]`.
fn appendix_theta(x: f64, u: f64) -> Result<(f64, f64, f64, f64), ElasticaError> {
    finite("x", x)?;
    finite("u", u)?;
    if !(-FRAC_PI_2..=FRAC_PI_2).contains(&u) {
        return Err(ElasticaError::OutOfRange {
            name: "u",
            value: u,
            min: -FRAC_PI_2,
            max: FRAC_PI_2,
        });
    }
    if x < u || x > PI - u {
        return Err(ElasticaError::OutOfRange {
            name: "x",
            value: x,
            min: u,
            max: PI - u,
        });
    }
    let hu = half_pi_plus(0.5, &[-0.5 * u]); // pi/4 - u/2
    let k = hu.sin();
    let m = k * k;
    if k == 0.0 {
        return Ok((0.0, 1.0, 0.0, 0.0));
    }
    let s = ((half_pi_plus(-1.0, &[x]) * 0.5).sin() / k).clamp(-1.0, 1.0);
    // cos^2 theta = sin((x - u)/2) sin((pi - u - x)/2) / k^2
    let c2 = ((0.5 * (x - u)).sin() * (0.5 * half_pi_plus(2.0, &[-u, -x])).sin() / m).max(0.0);
    let r2 = s * s + c2;
    Ok((s / r2.sqrt(), c2 / r2, k, m))
}

/// Appendix A: `I1(x, u) = int_{pi/2}^{x} [sin t - sin u]^(-1/2) dt = sqrt(2) F(theta|k^2)`,
/// `sin(theta) = sin(x/2 - pi/4)/k`, `k = sqrt((1 - sin u)/2)`, for `u <= x <= pi - u`.
pub fn i1(x: f64, u: f64) -> Result<f64, ElasticaError> {
    let (s, c2, _, m) = appendix_theta(x, u)?;
    Ok(SQRT_2 * f_e_sc(s, c2, 1.0 - m * s * s, m)?.0)
}

/// Appendix A: `I2(x, u) = int_{pi/2}^{x} [sin t - sin u]^(1/2) dt = 2 sqrt(2) [E - (1 - k^2) F]`.
pub fn i2(x: f64, u: f64) -> Result<f64, ElasticaError> {
    let (s, c2, _, m) = appendix_theta(x, u)?;
    let (f, e) = f_e_sc(s, c2, 1.0 - m * s * s, m)?;
    Ok(2.0 * SQRT_2 * (e - (1.0 - m) * f))
}

/// Appendix A: `I3(x, u) = int_{pi/2}^{x} sin t [sin t - sin u]^(-1/2) dt = sin(u) I1 + I2`.
pub fn i3(x: f64, u: f64) -> Result<f64, ElasticaError> {
    Ok(u.sin() * i1(x, u)? + i2(x, u)?)
}

/// Appendix A: `I4(x, u) = int_{pi/2}^{x} cos t [sin t - sin u]^(-1/2) dt
/// = 2 [sqrt(sin x - sin u) - sqrt(1 - sin u)]`.
pub fn i4(x: f64, u: f64) -> Result<f64, ElasticaError> {
    let (_, _, _, _) = appendix_theta(x, u)?;
    // sin x - sin u = 2 cos((x+u)/2) sin((x-u)/2); 1 - sin u = 2 sin^2(pi/4 - u/2)
    let d = (2.0 * (0.5 * (x + u)).cos() * (0.5 * (x - u)).sin()).max(0.0);
    let k = half_pi_plus(0.5, &[-0.5 * u]).sin();
    Ok(2.0 * (d.sqrt() - SQRT_2 * k))
}
