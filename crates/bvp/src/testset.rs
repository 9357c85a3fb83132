//! The Cash–Mazzia BVP test set (scalar second-order problems), as [`ParamBvp`] families in `ε`.
//!
//! Source: J. R. Cash and F. Mazzia, *Test set for BVP solvers* (problems 1–30 of the
//! "bvpT" set; also W. H. Enright and P. H. Muir, *Runge–Kutta software with defect control for
//! BVODEs*, 1996, appendix). Every problem here is `y'' = φ(x, y, y'; ε)` with Dirichlet
//! conditions `y(a) = α(ε)`, `y(b) = β(ε)`, written as the first-order system `z = (y, y')`.
//! The family parameter `λ` of [`ParamBvp`] is `ε`, so [`crate::solve_by_continuation`] can
//! walk from an easy `ε` to a hard one.
//!
//! Where the published conditions drop exponentially small terms of the exact solution (e.g.
//! `y(−1) = −1` for `cos πx + e^{(x−1)/√ε}`), `α, β` here are the exact solution's end values,
//! so the exact solution solves the discrete problem's continuous counterpart exactly. Problems 15,
//! 19, 22, 23 and 25–30 have no closed form ([`CashMazzia::exact`] returns `None`).
//!
//! | id | equation (`p = y'`) | interval | conditions | exact `y` |
//! |---|---|---|---|---|
//! | 1 | `ε y'' = y` | [0, 1] | 1, 0 | `(e^{−x/√ε} − e^{(x−2)/√ε}) / (1 − e^{−2/√ε})` |
//! | 2 | `ε y'' = p` | [0, 1] | 1, 0 | `(1 − e^{(x−1)/ε}) / (1 − e^{−1/ε})` |
//! | 3 | `ε y'' = −(2 + cos πx) p + y − (1 + επ²) cos πx − (2 + cos πx) π sin πx` | [−1, 1] | −1, −1 | `cos πx` |
//! | 4 | `ε y'' = −p + (1 + ε) y` | [−1, 1] | exact | `e^{x−1} + e^{−(1+ε)(1+x)/ε}` |
//! | 5 | `ε y'' = −x p + y − (1 + επ²) cos πx − πx sin πx` | [−1, 1] | −1, −1 | `cos πx` |
//! | 6 | `ε y'' = −x p − επ² cos πx − πx sin πx` | [−1, 1] | −2, 0 | `cos πx + erf(x/√(2ε)) / erf(1/√(2ε))` |
//! | 7 | as 5 | [−1, 1] | −1, 1 | `cos πx + x + (x erf(x/√(2ε)) + √(2ε/π) e^{−x²/2ε}) / (erf(1/√(2ε)) + √(2ε/π) e^{−1/2ε})` |
//! | 8 | `ε y'' = −p` | [0, 1] | 1, 2 | `1 + (1 − e^{−x/ε}) / (1 − e^{−1/ε})` |
//! | 9 | `(ε + x²) y'' = −4x p − 2y` | [−1, 1] | exact | `1 / (ε + x²)` |
//! | 10 | `ε y'' = −x p` | [−1, 1] | 0, 2 | `1 + erf(x/√(2ε)) / erf(1/√(2ε))` |
//! | 11 | `ε y'' = y − (επ² + 1) cos πx` | [−1, 1] | −1, −1 | `cos πx` |
//! | 12 | as 11 | [−1, 1] | exact | `cos πx + e^{(x−1)/√ε}` |
//! | 13 | as 11 | [−1, 1] | exact | `cos πx + e^{−(x+1)/√ε}` |
//! | 14 | as 11 | [−1, 1] | exact | `cos πx + e^{(x−1)/√ε} + e^{−(x+1)/√ε}` |
//! | 15 | `ε y'' = x y` | [−1, 1] | 1, 1 | (Airy functions) |
//! | 17 | `y'' = −3ε y / (ε + x²)²` | [−0.1, 0.1] | exact | `x / √(ε + x²)` |
//! | 18 | `ε y'' = −p` | [0, 1] | exact | `e^{−x/ε}` |
//! | 19 | `ε y'' = −e^y p + (π/2) sin(πx/2) e^{2y}` | [0, 1] | 0, 0 | — |
//! | 20 | `ε y'' = 1 − p²` | [0, 1] | exact | `1 + ε ln cosh((x − 0.745)/ε)` |
//! | 21 | `ε y'' = y + y² − e^{−2x/√ε}` | [0, 1] | exact | `e^{−x/√ε}` |
//! | 22 | `ε y'' = −p − y²` | [0, 1] | 0, ½ | — |
//! | 23 | `y'' = (1/ε) sinh(y/ε)` (Troesch, μ = 1/ε) | [0, 1] | 0, 1 | — |
//! | 25–30 | `ε y'' = −y p + y` | [0, 1] | see [`CashMazzia::description`] | — |
//!
//! # Extended set
//!
//! Four problems with closed-form solutions that the published scalar set lacks (ids 101–104,
//! [`CashMazzia::extended`]; manufactured: the exact solution is substituted into the equation,
//! and `tests/testset.rs` checks that it solves it):
//!
//! | id | equation | interval | conditions | exact `y` |
//! |---|---|---|---|---|
//! | 101 | `(ε + x) y'' + 2 y' = 0` | [0, 1] | exact | `1 / (ε + x)` (grows like 1/ε) |
//! | 102 | `y'' = 2 y³` | [0, 1] | exact | `1 / (ε + x)` (nonlinear, grows like 1/ε) |
//! | 103 | `ε y'''' − y'' = −2` | [0, 1] | `y, y'` at both ends | `x² + e^{−x/√ε} + e^{(x−1)/√ε}` |
//! | 104 | `y'''' + y⁵ = 25 / (ε + x)⁵` | [0, 1] | `y, y'` at both ends | `1 / (ε + x)` |
//!
//! Each has a unique solution: the linearizations (`(ε + x) w'' + 2w'`, `−w'' + 6y²w`,
//! `ε w'''' − w''`, `w'''' + 5y⁴w` with the homogeneous conditions) are positive definite or, for
//! 101, have only `w = 0` (`w = c₁ + c₂/(ε + x)`). Fourth-order problems are the first-order systems of `(y, y', y'', y''')` (`n = 4`);
//! [`CashMazzia::exact`] still returns `(y, y')`.
//!
//! Not included: problem 16 (`ε² y'' = −(π²/4) y`, `y = sin(πx/2ε)`: for ε = 1/(2m), as on the
//! study grid, `sin(πx/2ε)` solves the homogeneous problem too, so the problem is singular),
//! problem 24 (a nozzle flow) and the systems 31–35.

use crate::continuation::{Member, ParamBvp};
use crate::{Dims, Guess};
use std::f64::consts::PI;

/// The problems of the extended set (not in the published one), see the module docs.
pub const EXTENDED_IDS: [u8; 4] = [101, 102, 103, 104];

/// The problem ids implemented, in order.
pub const IDS: [u8; 28] = [
    1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 17, 18, 19, 20, 21, 22, 23, 25, 26, 27, 28,
    29, 30,
];

/// One problem of the set, a family in `λ = ε > 0`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CashMazzia {
    id: u8,
}

/// `ln cosh t` without overflow.
fn ln_cosh(t: f64) -> f64 {
    let a = t.abs();
    a + (-2.0 * a).exp().ln_1p() - std::f64::consts::LN_2
}

impl CashMazzia {
    /// Problem `id` of the set, if implemented (see [`IDS`] and [`EXTENDED_IDS`]).
    pub fn new(id: u8) -> Option<Self> {
        (IDS.contains(&id) || EXTENDED_IDS.contains(&id)).then_some(CashMazzia { id })
    }

    /// All implemented problems of the published set.
    pub fn all() -> impl Iterator<Item = CashMazzia> {
        IDS.iter().map(|&id| CashMazzia { id })
    }

    /// The problems of the extended set (solutions growing like 1/ε, fourth order).
    pub fn extended() -> impl Iterator<Item = CashMazzia> {
        EXTENDED_IDS.iter().map(|&id| CashMazzia { id })
    }

    /// Number of states: 2, or 4 for the fourth-order problems.
    pub fn states(&self) -> usize {
        if matches!(self.id, 103 | 104) {
            4
        } else {
            2
        }
    }

    /// The problem's number in the published set.
    pub fn id(&self) -> u8 {
        self.id
    }

    /// The equation in words, e.g. `"eps y'' = y"`.
    pub fn description(&self) -> &'static str {
        match self.id {
            1 => "eps y'' = y",
            2 => "eps y'' = y'",
            3 => "eps y'' = -(2+cos pi x) y' + y + f(x)",
            4 => "eps y'' = -y' + (1+eps) y",
            5 => "eps y'' = -x y' + y + f(x), y(1) = -1",
            6 => "eps y'' = -x y' + f(x) (erf layer)",
            7 => "eps y'' = -x y' + y + f(x), y(1) = 1",
            8 => "eps y'' = -y', y(1) = 2",
            9 => "(eps + x^2) y'' = -4x y' - 2y",
            10 => "eps y'' = -x y'",
            11 => "eps y'' = y - (eps pi^2 + 1) cos pi x",
            12 => "as 11, right layer",
            13 => "as 11, left layer",
            14 => "as 11, both layers",
            15 => "eps y'' = x y (Airy)",
            16 => "eps^2 y'' = -(pi^2/4) y (oscillatory)",
            17 => "y'' = -3 eps y / (eps + x^2)^2",
            18 => "eps y'' = -y', y = exp(-x/eps)",
            19 => "eps y'' = -exp(y) y' + pi/2 sin(pi x/2) exp(2y)",
            20 => "eps y'' = 1 - y'^2",
            21 => "eps y'' = y + y^2 - exp(-2x/sqrt eps)",
            22 => "eps y'' = -y' - y^2",
            23 => "y'' = (1/eps) sinh(y/eps) (Troesch)",
            25 => "eps y'' = -y y' + y, y(0) = -1/3, y(1) = 1/3",
            26 => "eps y'' = -y y' + y, y(0) = 1, y(1) = -1/3",
            27 => "eps y'' = -y y' + y, y(0) = 1, y(1) = 1/3",
            28 => "eps y'' = -y y' + y, y(0) = 1, y(1) = 3/2",
            29 => "eps y'' = -y y' + y, y(0) = 0, y(1) = 3/2",
            30 => "eps y'' = -y y' + y, y(0) = -7/6, y(1) = 3/2",
            101 => "(eps + x) y'' + 2 y' = 0, y = 1/(eps + x)",
            102 => "y'' = 2 y^3, y = 1/(eps + x)",
            103 => "eps y'''' - y'' = -2, y = x^2 + two layers",
            104 => "y'''' + y^5 = 25/(eps + x)^5, y = 1/(eps + x)",
            _ => "",
        }
    }

    /// True for the linear problems (1–18, 101, 103).
    pub fn is_linear(&self) -> bool {
        self.id <= 18 || matches!(self.id, 101 | 103)
    }

    /// The member at `eps` as an ordinary [`crate::Bvp`].
    pub fn at(&self, eps: f64) -> Member<'_, Self> {
        Member::new(self, eps)
    }

    /// The interval `[a, b]`.
    pub fn span(&self) -> (f64, f64) {
        match self.id {
            3..=7 | 9..=15 => (-1.0, 1.0),
            17 => (-0.1, 0.1),
            _ => (0.0, 1.0),
        }
    }

    /// Boundary values `(y(a), y(b))` at `eps`.
    pub fn boundary_values(&self, eps: f64) -> (f64, f64) {
        let (a, b) = self.span();
        match self.id {
            1 | 2 => (1.0, 0.0),
            3 | 5 | 11 | 15 => (-1.0, -1.0),
            6 => (-2.0, 0.0),
            7 => (-1.0, 1.0),
            8 => (1.0, 2.0),
            10 => (0.0, 2.0),
            19 => (0.0, 0.0),
            22 => (0.0, 0.5),
            23 => (0.0, 1.0),
            25 => (-1.0 / 3.0, 1.0 / 3.0),
            26 => (1.0, -1.0 / 3.0),
            27 => (1.0, 1.0 / 3.0),
            28 => (1.0, 1.5),
            29 => (0.0, 1.5),
            30 => (-7.0 / 6.0, 1.5),
            _ => {
                let e = |x| self.exact(x, eps).map_or(f64::NAN, |v| v[0]);
                (e(a), e(b))
            }
        }
    }

    /// Exact `(y, y')` at `x` for `eps`, where a closed form exists.
    pub fn exact(&self, x: f64, eps: f64) -> Option<[f64; 2]> {
        let (c, s) = ((PI * x).cos(), (PI * x).sin());
        let cosp = [c, -PI * s];
        let add = |a: [f64; 2], b: [f64; 2]| [a[0] + b[0], a[1] + b[1]];
        let r = eps.sqrt();
        // e^{(x−x0)·k} and its derivative.
        let ex = |k: f64, x0: f64| {
            let v = ((x - x0) * k).exp();
            [v, k * v]
        };
        let erf_layer = || {
            // erf(x/√(2ε)) / erf(1/√(2ε)) and its derivative.
            let c2 = (2.0 * eps).sqrt();
            let d = libm::erf(1.0 / c2);
            [
                libm::erf(x / c2) / d,
                2.0 / (PI.sqrt() * c2) * (-x * x / (2.0 * eps)).exp() / d,
            ]
        };
        Some(match self.id {
            1 => {
                let d = 1.0 - (-2.0 / r).exp();
                let (u, v) = ((-x / r).exp(), ((x - 2.0) / r).exp());
                [(u - v) / d, (-u - v) / (r * d)]
            }
            2 => {
                let d = 1.0 - (-1.0 / eps).exp();
                let v = ((x - 1.0) / eps).exp();
                [(1.0 - v) / d, -v / (eps * d)]
            }
            3 | 5 | 11 => cosp,
            4 => add(ex(1.0, 1.0), ex(-(1.0 + eps) / eps, -1.0)),
            6 => add(cosp, erf_layer()),
            7 => {
                let c2 = (2.0 * eps).sqrt();
                let k = (2.0 * eps / PI).sqrt();
                let d = libm::erf(1.0 / c2) + k * (-1.0 / (2.0 * eps)).exp();
                let g = (-x * x / (2.0 * eps)).exp();
                let v = x * libm::erf(x / c2) + k * g;
                let dv = libm::erf(x / c2);
                [c + x + v / d, -PI * s + 1.0 + dv / d]
            }
            8 => {
                let d = 1.0 - (-1.0 / eps).exp();
                let v = (-x / eps).exp();
                [1.0 + (1.0 - v) / d, v / (eps * d)]
            }
            9 => {
                let q = eps + x * x;
                [1.0 / q, -2.0 * x / (q * q)]
            }
            10 => {
                let l = erf_layer();
                [1.0 + l[0], l[1]]
            }
            12 => add(cosp, ex(1.0 / r, 1.0)),
            13 => add(cosp, ex(-1.0 / r, -1.0)),
            14 => add(add(cosp, ex(1.0 / r, 1.0)), ex(-1.0 / r, -1.0)),
            16 => {
                let w = PI / (2.0 * eps);
                [(w * x).sin(), w * (w * x).cos()]
            }
            17 => {
                let q = eps + x * x;
                [x / q.sqrt(), eps / (q * q.sqrt())]
            }
            18 => ex(-1.0 / eps, 0.0),
            20 => {
                let t = (x - 0.745) / eps;
                [1.0 + eps * ln_cosh(t), t.tanh()]
            }
            21 => ex(-1.0 / r, 0.0),
            101 | 102 | 104 => {
                let q = eps + x;
                [1.0 / q, -1.0 / (q * q)]
            }
            103 => add(add([x * x, 2.0 * x], ex(-1.0 / r, 0.0)), ex(1.0 / r, 1.0)),
            _ => return None,
        })
    }

    /// True if [`CashMazzia::exact`] has a closed form.
    pub fn has_exact(&self) -> bool {
        self.exact(0.0, 0.1).is_some()
    }

    /// The straight line between the boundary values on `nodes` equal nodes (`y'` its slope,
    /// higher derivatives 0): the common starting guess of the test-set study.
    pub fn guess(&self, eps: f64, nodes: usize) -> Guess {
        let (a, b) = self.span();
        let (ya, yb) = self.boundary_values(eps);
        let slope = (yb - ya) / (b - a);
        let nodes = nodes.max(2);
        let mesh = (0..nodes)
            .map(|i| a + (b - a) * i as f64 / (nodes - 1) as f64)
            .collect();
        Guess::from_fn(self.states(), mesh, vec![], |x, z| {
            z.fill(0.0);
            z[0] = ya + slope * (x - a);
            z[1] = slope;
        })
    }

    /// Fourth-order problems: `(y'''', ∂/∂y, ∂/∂y'', ∂/∂ε)` of `y'''' = ψ(x, y, y''; ε)`.
    fn psi(&self, x: f64, y: f64, y2: f64, eps: f64) -> [f64; 4] {
        match self.id {
            103 => [(y2 - 2.0) / eps, 0.0, 1.0 / eps, -(y2 - 2.0) / (eps * eps)],
            104 => {
                let y4 = y * y * y * y;
                let q5 = (eps + x).powi(5);
                [
                    25.0 / q5 - y4 * y,
                    -5.0 * y4,
                    0.0,
                    -125.0 / (q5 * (eps + x)),
                ]
            }
            _ => [f64::NAN; 4],
        }
    }

    /// `(φ, ∂φ/∂y, ∂φ/∂y', ∂φ/∂ε)` of `y'' = φ(x, y, y'; ε)` (second-order problems).
    pub fn phi(&self, x: f64, y: f64, p: f64, eps: f64) -> [f64; 4] {
        let e2 = eps * eps;
        // ε y'' = N(x, y, p; ε) with ∂N/∂y, ∂N/∂p, ∂N/∂ε (the explicit ε in N).
        let over_eps =
            |n: f64, ny: f64, np: f64, ne: f64| [n / eps, ny / eps, np / eps, ne / eps - n / e2];
        let (c, s) = ((PI * x).cos(), (PI * x).sin());
        match self.id {
            1 => over_eps(y, 1.0, 0.0, 0.0),
            2 => over_eps(p, 0.0, 1.0, 0.0),
            3 => over_eps(
                -(2.0 + c) * p + y - (1.0 + eps * PI * PI) * c - (2.0 + c) * PI * s,
                1.0,
                -(2.0 + c),
                -PI * PI * c,
            ),
            4 => over_eps(-p + (1.0 + eps) * y, 1.0 + eps, -1.0, y),
            5 | 7 => over_eps(
                -x * p + y - (1.0 + eps * PI * PI) * c - PI * x * s,
                1.0,
                -x,
                -PI * PI * c,
            ),
            6 => over_eps(
                -x * p - eps * PI * PI * c - PI * x * s,
                0.0,
                -x,
                -PI * PI * c,
            ),
            8 | 18 => over_eps(-p, 0.0, -1.0, 0.0),
            9 => {
                let q = eps + x * x;
                let f = (-4.0 * x * p - 2.0 * y) / q;
                [f, -2.0 / q, -4.0 * x / q, -f / q]
            }
            10 => over_eps(-x * p, 0.0, -x, 0.0),
            11..=14 => over_eps(y - (eps * PI * PI + 1.0) * c, 1.0, 0.0, -PI * PI * c),
            15 => over_eps(x * y, x, 0.0, 0.0),
            16 => {
                let w = PI * PI / (4.0 * e2);
                [-w * y, -w, 0.0, 2.0 * w * y / eps]
            }
            17 => {
                let q = eps + x * x;
                let q2 = q * q;
                [
                    -3.0 * eps * y / q2,
                    -3.0 * eps / q2,
                    0.0,
                    -3.0 * y / q2 + 6.0 * eps * y / (q2 * q),
                ]
            }
            19 => {
                let (ey, sx) = (y.exp(), 0.5 * PI * (0.5 * PI * x).sin());
                over_eps(
                    -ey * p + sx * ey * ey,
                    -ey * p + 2.0 * sx * ey * ey,
                    -ey,
                    0.0,
                )
            }
            20 => over_eps(1.0 - p * p, 0.0, -2.0 * p, 0.0),
            21 => {
                let r = eps.sqrt();
                let g = (-2.0 * x / r).exp();
                over_eps(y + y * y - g, 1.0 + 2.0 * y, 0.0, -g * x / (eps * r))
            }
            22 => over_eps(-p - y * y, -2.0 * y, -1.0, 0.0),
            23 => {
                let (sh, ch) = ((y / eps).sinh(), (y / eps).cosh());
                [sh / eps, ch / e2, 0.0, -sh / e2 - y * ch / (e2 * eps)]
            }
            25..=30 => over_eps(-y * p + y, 1.0 - p, -y, 0.0),
            101 => {
                let q = eps + x;
                [-2.0 * p / q, 0.0, -2.0 / q, 2.0 * p / (q * q)]
            }
            102 => [2.0 * y * y * y, 6.0 * y * y, 0.0, 0.0],
            _ => [f64::NAN; 4],
        }
    }
}

impl ParamBvp for CashMazzia {
    fn dims(&self) -> Dims {
        Dims {
            n: self.states(),
            k: 0,
        }
    }
    fn interval(&self) -> (f64, f64) {
        self.span()
    }
    fn rhs(&self, s: f64, z: &[f64], _p: &[f64], eps: f64, dz: &mut [f64]) {
        if self.states() == 4 {
            dz[..3].copy_from_slice(&z[1..4]);
            dz[3] = self.psi(s, z[0], z[2], eps)[0];
        } else {
            dz[0] = z[1];
            dz[1] = self.phi(s, z[0], z[1], eps)[0];
        }
    }
    fn bc(&self, za: &[f64], zb: &[f64], _p: &[f64], eps: f64, res: &mut [f64]) {
        if self.states() == 4 {
            let (a, b) = self.span();
            let ea = self.exact(a, eps).unwrap_or([f64::NAN; 2]);
            let eb = self.exact(b, eps).unwrap_or([f64::NAN; 2]);
            res.copy_from_slice(&[za[0] - ea[0], za[1] - ea[1], zb[0] - eb[0], zb[1] - eb[1]]);
            return;
        }
        let (ya, yb) = self.boundary_values(eps);
        res[0] = za[0] - ya;
        res[1] = zb[0] - yb;
    }
    fn rhs_jacobian(
        &self,
        s: f64,
        z: &[f64],
        _p: &[f64],
        eps: f64,
        dfdz: &mut [f64],
        _dfdp: &mut [f64],
        dfdl: &mut [f64],
    ) -> bool {
        if self.states() == 4 {
            let [_, fy, fy2, fe] = self.psi(s, z[0], z[2], eps);
            dfdz.fill(0.0);
            for i in 0..3 {
                dfdz[i * 4 + i + 1] = 1.0;
            }
            dfdz[12] = fy;
            dfdz[14] = fy2;
            dfdl.fill(0.0);
            dfdl[3] = fe;
            return true;
        }
        let [_, fy, fp, fe] = self.phi(s, z[0], z[1], eps);
        dfdz.copy_from_slice(&[0.0, 1.0, fy, fp]);
        dfdl[0] = 0.0;
        dfdl[1] = fe;
        true
    }
    fn bc_jacobian(
        &self,
        _za: &[f64],
        _zb: &[f64],
        _p: &[f64],
        eps: f64,
        dga: &mut [f64],
        dgb: &mut [f64],
        _dgp: &mut [f64],
        dgl: &mut [f64],
    ) -> bool {
        // Boundary values that follow the exact solution depend on ε: central difference.
        let h = 1e-6 * eps;
        if self.states() == 4 {
            dga.fill(0.0);
            dgb.fill(0.0);
            dga[0] = 1.0;
            dga[5] = 1.0;
            dgb[8] = 1.0;
            dgb[13] = 1.0;
            let (a, b) = self.span();
            let at = |x: f64, e: f64| self.exact(x, e).unwrap_or([f64::NAN; 2]);
            let (a1, a0) = (at(a, eps + h), at(a, eps - h));
            let (b1, b0) = (at(b, eps + h), at(b, eps - h));
            for j in 0..2 {
                dgl[j] = -(a1[j] - a0[j]) / (2.0 * h);
                dgl[2 + j] = -(b1[j] - b0[j]) / (2.0 * h);
            }
            return true;
        }
        dga.copy_from_slice(&[1.0, 0.0, 0.0, 0.0]);
        dgb.copy_from_slice(&[0.0, 0.0, 1.0, 0.0]);
        let (a1, b1) = self.boundary_values(eps + h);
        let (a0, b0) = self.boundary_values(eps - h);
        dgl[0] = -(a1 - a0) / (2.0 * h);
        dgl[1] = -(b1 - b0) / (2.0 * h);
        true
    }
}
