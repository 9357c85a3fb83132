//! # elastica — closed-form reference solutions of the clamped elastica with a tip force
//!
//! Uniform rod of length 1 (units: length L, force EI/L^2, moment EI/L), clamped at the origin
//! pointing up (`phi(0) = pi/2`), free tip loaded by `F = (f sin(alpha), -f cos(alpha))`,
//! `alpha in [-pi/2, 0]` (0: straight down). State `x, y, phi` and the curvature
//! `kappa = phi' = m` (internal moment, `m' = f cos(phi - alpha)`, `m(1) = 0`).
//!
//! ## The math (paper sections 2-3, Appendix A)
//!
//! First integral: `kappa^2 = 2 f [sin(phi - alpha) - sin(phi1 - alpha)]`, i.e.
//! `kappa^2/2 = f [..]`. (The paper's display (2.4) writes `kappa^2/2 = 2f [..]`;
//! that factor 2 is a slip: it contradicts the paper's own (2.6) and the buckling load `pi^2/4`.)
//!
//! With `u = phi1 - alpha`, modulus `k = sin(pi/4 - u/2)` (`m = k^2 = (1 - sin u)/2 <= 1/2` in the
//! domain), the substitution `sin(t/2 - alpha/2 - pi/4) = k sin(theta)` maps the slopes
//! `t = phi1`, `pi/2`, `phi_b = pi + 2 alpha - phi1` to `theta = -pi/2, theta_top, pi/2`,
//! `sin(theta_top) = sin(-alpha/2)/k`, and `dt/sqrt(bracket) = sqrt(2) dtheta/sqrt(1 - m sin^2)`.
//! Hence, with `F_top = F(theta_top|m)`, `K = K(m)`:
//!
//! * convex (2.8): `sqrt(f) = K + F_top`; one flex (2.15): `sqrt(f) = 3K - F_top`;
//! * turning point `phi1 = pi/2 + 2 alpha`: `theta_top = pi/2`, both give
//!   `f_alpha = 4 K^2(m)` with `m = sin^2(alpha/2)` (modulus `sin(alpha/2)`);
//! * buckling: at `alpha = 0`, `phi1 -> pi/2`: `k -> 0`, `F_top = 0`, `f -> pi^2/4` and `9 pi^2/4`;
//! * along the rod `w = F_top -+ sqrt(f) s` (convex/flex), `theta = am(w|m)`; the flex point is at
//!   `w = K`: `s_b = (K - F_top)/sqrt(f)` (2.16), and the second point of slope `pi/2` at
//!   `w = 2K - F_top`, i.e. `s = 2 s_b` (Remark 2.1);
//! * positions: `E(am w)` and `cn w` (see [`Elastica::point_at`]);
//! * `m_base = kappa(0) = -+ 2 sqrt(f) k cos(theta_top)`.
//!
//! ## Sign convention for the clamp moment
//!
//! [`Elastica::m_base`] is `m(0) = kappa(0)`, the internal moment at the clamp: negative for the
//! convex, right-handed rod. The paper's clamp reaction moment is `m0 = -m(0) = -m_base`.
//!
//! ## Numerics
//!
//! Everything is evaluated with Carlson's `R_F`, `R_D` (crate `ellip`) from sines and
//! cancellation-free products: the distance to the turning point
//! `delta = pi/2 + 2 alpha - phi1` is formed in double-double, and
//! `cos^2(theta_top) = sin(delta/2) sin((pi/2 - phi1)/2)/k^2`, so `f` and the tip keep ~1e-15
//! relative accuracy up to and at the turning point and near the buckling corner. The
//! end-point `1/sqrt` singularity of the integrand disappears in the `theta` variable.
//!
//! ## Main items
//!
//! * [`Elastica`], [`Branch`], [`ShapePoint`]: one solution, its shape.
//! * [`convex_force`], [`flex_force`], [`turning_point`], [`lower_limit`], [`solve_eta`].
//! * [`ClosedFormScan`], [`ScanPoint`]: the stiction scan of section 3 (Remark 3.1).
//! * [`ellint`]: elliptic integrals and the paper's `I1..I4`, `K`, `X`, `Y`.
//! * [`roots`]: Brent root finder and maximiser.
//! * [`ElasticaError`]: typed errors; nothing here returns NaN or panics on bad input.
#![warn(missing_docs)]

mod branch;
mod elastica;
pub mod ellint;
mod error;
pub mod roots;
mod scan;

pub use branch::Branch;
pub use elastica::{
    convex_force, flex_force, lower_limit, solve_eta, solve_eta_all, turning_point, Elastica,
    ShapePoint,
};
pub use error::ElasticaError;
pub use scan::{ClosedFormScan, Phase0End, ScanPoint};

/// The examples of the crate's README.md, run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
