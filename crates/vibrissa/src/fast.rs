//! Fast paths for the uniform clamped rod with single shooting: the stiction scan and single
//! shapes with a tip-slope or tip-height condition.
//!
//! The generic scan (continuation through crate `bvp`) is method-agnostic and handles every
//! scene. For the paper's rod with single shooting most of its work is not needed: `d` itself
//! parametrizes the branch up to a fold in `d` (folds in α or φ1 are regular points here), so the
//! scan can step from grid point to grid point.
//!
//! - Unknowns `u = (m(0), f, α)`; residual `R = (m(1), x(1) − (x* − d), y(1) − η)`.
//! - One integration of the rod and its variational equations in `u` only (16 components instead
//!   of the generic 28; 4 when no Jacobian is needed), monomorphized and allocation-free, with
//!   the 8th-order DOP853 weights on `N` equal steps, an inline `sin_cos` and an AVX2 build chosen
//!   at run time. Fixed steps make the sensitivities the exact Jacobian of the discrete residual
//!   (quadratic Newton); the embedded error estimate of each step is checked against `tol`
//!   (`rtol = atol = tol`, Hairer's norm, as the adaptive integrator) and `N` is raised when it is
//!   exceeded, so the accuracy contract is the generic one.
//! - Predictor: the quintic Hermite extrapolant through the last three points and their tangents
//!   `u' = −J⁻¹ ∂R/∂d`; chord Newton, so most points cost one shot with and one without
//!   sensitivities.
//! - Events are watched at every point as in the generic scan. Anything it does not handle itself
//!   (penetration, slip, a fold in `d` — a sign change of `det J` — or a Newton failure) makes it
//!   give up and leave the scan to the generic path, which redoes it from the start.
//! - μ_max between grid points: the root of `α'(d)` of the interpolant through the last points,
//!   refined by Newton steps on `α'(d) = 0` with solves and exact tangents.
//! - Single shapes ([`solve_rod`]): unknowns `(m(0), f)`, damped Newton on the same shot; rods
//!   near a turning point (ill-conditioned Jacobian) are left to the generic solver.

use crate::model::Profile;
use crate::scan::{ScanOptions, ScanPoint, ScanResult, Scanner, StopReason};
use crate::ShapePoint;
// DOP853 coefficients, shared with `bvp`'s adaptive integrator.
use bvp::tableau::dop853 as tab;
use bvp::{Solution, Stats, Status};
use std::f64::consts::FRAC_PI_2;

/// State and sensitivities: `y[0..4] = (x, y, φ, m)`, `y[4 + 4q + i] = ∂z_i/∂u_q`.
const NV: usize = 16;
type Y = [f64; NV];

/// `(sin x, cos x)` for moderate `|x|` (here slopes within a few turns): Cody–Waite reduction by
/// π/2 and fdlibm's kernel polynomials on `[−π/4, π/4]` (error ≲ 1 ulp there). About a third of
/// the instructions of libm's general `sincos`, which is the largest single cost of a shot.
#[inline(always)]
#[allow(clippy::excessive_precision)]
fn sin_cos(x: f64) -> (f64, f64) {
    const PIO2_HI: f64 = 1.570_796_326_734_125_614_17; // first 33 bits of π/2
    const PIO2_LO: f64 = 6.077_100_506_506_192_249_99e-11; // π/2 − PIO2_HI
    const S: [f64; 6] = [
        -1.666_666_666_666_663_243_48e-01,
        8.333_333_333_322_489_461_24e-03,
        -1.984_126_982_985_794_931_34e-04,
        2.755_731_370_707_006_767_89e-06,
        -2.505_076_025_340_686_341_95e-08,
        1.589_690_995_211_550_102_21e-10,
    ];
    const C: [f64; 6] = [
        4.166_666_666_666_660_190_37e-02,
        -1.388_888_888_887_410_957_49e-03,
        2.480_158_728_947_672_941_78e-05,
        -2.755_731_435_139_066_330_35e-07,
        2.087_572_321_298_174_827_90e-09,
        -1.135_964_755_778_819_482_65e-11,
    ];
    if x.is_nan() || x.abs() >= 1e5 {
        return x.sin_cos();
    }
    let k = (x * std::f64::consts::FRAC_2_PI).round();
    let r = (x - k * PIO2_HI) - k * PIO2_LO;
    let z = r * r;
    let sp = S[1] + z * (S[2] + z * (S[3] + z * (S[4] + z * S[5])));
    let sr = r + r * z * (S[0] + z * sp);
    let cp = C[0] + z * (C[1] + z * (C[2] + z * (C[3] + z * (C[4] + z * C[5]))));
    let hz = 0.5 * z;
    let w = 1.0 - hz;
    // fdlibm's split keeps 1 − z/2 exact to the last bit
    let cr = w + (((1.0 - w) - hz) + z * z * cp);
    // quadrant by selects rather than a jump table
    let q = k as i64;
    let (s1, c1) = if q & 1 == 0 { (sr, cr) } else { (cr, -sr) };
    if q & 2 == 0 {
        (s1, c1)
    } else {
        (-s1, -c1)
    }
}

/// Rod right-hand side with the variational equations in `u = (m0, f, α)`.
#[inline(always)]
fn rhs<const VAR: bool>(y: &Y, f: f64, ca: f64, sa: f64) -> Y {
    let (sp, cp) = sin_cos(y[2]);
    // sin/cos(φ − α) from those of φ and α: one sin_cos per evaluation
    let cd = cp * ca + sp * sa;
    let sd = sp * ca - cp * sa;
    let fsd = f * sd;
    let mut d = [0.0; NV];
    d[0] = cp;
    d[1] = sp;
    d[2] = y[3];
    d[3] = f * cd;
    if !VAR {
        return d;
    }
    for q in 0..3 {
        let (dphi, dm) = (y[4 + 4 * q + 2], y[4 + 4 * q + 3]);
        d[4 + 4 * q] = -sp * dphi;
        d[4 + 4 * q + 1] = cp * dphi;
        d[4 + 4 * q + 2] = dm;
        d[4 + 4 * q + 3] = -fsd * dphi;
    }
    d[4 + 4 + 3] += cd; // ∂/∂f
    d[4 + 8 + 3] += fsd; // ∂/∂α
    d
}

/// Result of one integration over `[0, 1]`.
struct Shot {
    /// End state and sensitivities.
    y1: Y,
    /// Max over the steps of the scaled error estimate (≤ 1: within tolerance).
    err: f64,
}

/// The fixed-step integrator and its recorded path.
struct Integrator {
    steps: usize,
    tol: f64,
    /// Nodes' `z` and `F(z)` (node-major, 4 each) of the last integration.
    path_z: Vec<f64>,
    path_dz: Vec<f64>,
    stats: Stats,
}

impl Integrator {
    /// Integrates from `u`; with `VAR` also the sensitivities (else only `z`: 4× less work).
    fn shoot<const VAR: bool>(&mut self, u: &[f64; 3]) -> Shot {
        #[cfg(target_arch = "x86_64")]
        {
            if std::is_x86_feature_detected!("avx2") {
                // SAFETY: the CPU has AVX2 (checked just above), the only requirement of
                // `shoot_avx2`.
                return unsafe { self.shoot_avx2::<VAR>(u) };
            }
        }
        self.shoot_impl::<VAR>(u)
    }

    /// [`Self::shoot_impl`] compiled for AVX2: the 16 components are four 256-bit lanes, which
    /// halves the instructions of the stage sums (the baseline x86-64 target has only SSE2).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn shoot_avx2<const VAR: bool>(&mut self, u: &[f64; 3]) -> Shot {
        self.shoot_impl::<VAR>(u)
    }

    #[inline(always)]
    fn shoot_impl<const VAR: bool>(&mut self, u: &[f64; 3]) -> Shot {
        let nv = if VAR { NV } else { 4 };
        let (m0, f, alpha) = (u[0], u[1], u[2]);
        let (sa, ca) = alpha.sin_cos();
        let n = self.steps;
        let h = 1.0 / n as f64;
        let mut y = [0.0; NV];
        y[2] = FRAC_PI_2;
        y[3] = m0;
        y[4 + 3] = 1.0; // ∂m/∂m0 at s = 0
        self.path_z.clear();
        self.path_dz.clear();
        let mut k = [[0.0; NV]; 12];
        k[0] = rhs::<VAR>(&y, f, ca, sa);
        let mut err_max: f64 = 0.0;
        for _ in 0..n {
            self.path_z.extend_from_slice(&y[..4]);
            self.path_dz.extend_from_slice(&k[0][..4]);
            // stage sums over the nonzero coefficients only, unrolled
            macro_rules! stage {
                ($i:literal, [$($j:literal),*]) => {{
                    let mut t = y;
                    $(
                        let ha = h * tab::A[$i * tab::STAGES + $j];
                        for c in 0..nv {
                            t[c] += ha * k[$j][c];
                        }
                    )*
                    k[$i] = rhs::<VAR>(&t, f, ca, sa);
                }};
            }
            stage!(1, [0]);
            stage!(2, [0, 1]);
            stage!(3, [0, 2]);
            stage!(4, [0, 2, 3]);
            stage!(5, [0, 3, 4]);
            stage!(6, [0, 3, 4, 5]);
            stage!(7, [0, 3, 4, 5, 6]);
            stage!(8, [0, 3, 4, 5, 6, 7]);
            stage!(9, [0, 3, 4, 5, 6, 7, 8]);
            stage!(10, [0, 3, 4, 5, 6, 7, 8, 9]);
            stage!(11, [0, 3, 4, 5, 6, 7, 8, 9, 10]);
            const NZB: [usize; 8] = [0, 5, 6, 7, 8, 9, 10, 11];
            let mut ynew = y;
            for j in NZB {
                let hb = h * tab::B[j];
                for c in 0..nv {
                    ynew[c] += hb * k[j][c];
                }
            }
            // Hairer's DOP853 error norm over z
            let (mut e5, mut e3) = (0.0, 0.0);
            for c in 0..4 {
                let sk = self.tol * (1.0 + y[c].abs().max(ynew[c].abs()));
                let (mut a5, mut a3) = (0.0, 0.0);
                for j in NZB {
                    a5 += tab::E5[j] * k[j][c];
                    a3 += tab::E3[j] * k[j][c];
                }
                e5 += (a5 / sk) * (a5 / sk);
                e3 += (a3 / sk) * (a3 / sk);
            }
            let deno = e5 + 0.01 * e3;
            let err = if deno > 0.0 {
                h * e5 / (4.0 * deno).sqrt()
            } else {
                0.0
            };
            err_max = err_max.max(if err.is_nan() { f64::INFINITY } else { err });
            y = ynew;
            k[0] = rhs::<VAR>(&y, f, ca, sa);
        }
        self.path_z.extend_from_slice(&y[..4]);
        self.path_dz.extend_from_slice(&k[0][..4]);
        self.stats.steps += n;
        self.stats.rhs_evals += 12 * n + 1;
        if VAR {
            self.stats.jac_evals += 12 * n + 1;
        }
        self.stats.bc_evals += 1;
        Shot {
            y1: y,
            err: err_max,
        }
    }
}

#[allow(clippy::needless_range_loop)] // index loops mirror the elimination formulas
/// 3×3 solve `J x = b` by Gaussian elimination with partial pivoting; `None` if singular.
fn solve3(j: &[[f64; 3]; 3], b: &[f64; 3]) -> Option<[f64; 3]> {
    let mut a = *j;
    let mut x = *b;
    for c in 0..3 {
        let p = (c..3).max_by(|&r, &s| a[r][c].abs().total_cmp(&a[s][c].abs()))?;
        if a[p][c] == 0.0 || a[p][c].is_nan() {
            return None;
        }
        a.swap(c, p);
        x.swap(c, p);
        for r in c + 1..3 {
            let l = a[r][c] / a[c][c];
            for cc in c..3 {
                a[r][cc] -= l * a[c][cc];
            }
            x[r] -= l * x[c];
        }
    }
    for c in (0..3).rev() {
        let mut s = x[c];
        for cc in c + 1..3 {
            s -= a[c][cc] * x[cc];
        }
        x[c] = s / a[c][c];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

fn det3(j: &[[f64; 3]; 3]) -> f64 {
    j[0][0] * (j[1][1] * j[2][2] - j[1][2] * j[2][1])
        - j[0][1] * (j[1][0] * j[2][2] - j[1][2] * j[2][0])
        + j[0][2] * (j[1][0] * j[2][1] - j[1][1] * j[2][0])
}

/// A converged point: unknowns, tangent `du/dd`, `det J`, and the rod as a [`Solution`].
#[derive(Clone, Debug)]
struct Point {
    d: f64,
    u: [f64; 3],
    du: [f64; 3],
    det: f64,
}

struct Fast<'s, 'm, Pr: Profile> {
    sc: &'s Scanner<'m, Pr>,
    int: Integrator,
    newton_tol: f64,
}

/// Newton iterations per point before giving up.
const MAX_ITER: usize = 12;
/// Largest internal step in `d` (finer user grids are followed as given).
const H_MAX: f64 = 0.01;

impl<Pr: Profile> Fast<'_, '_, Pr> {
    fn residual(&self, y: &Y, d: f64) -> [f64; 3] {
        let fam = &self.sc.family;
        [y[3], y[0] - (fam.x_star - d), y[1] - fam.eta]
    }

    fn jac(y: &Y) -> [[f64; 3]; 3] {
        // rows: m(1), x(1), y(1); columns: m0, f, α
        let s = |q: usize, i: usize| y[4 + 4 * q + i];
        [
            [s(0, 3), s(1, 3), s(2, 3)],
            [s(0, 0), s(1, 0), s(2, 0)],
            [s(0, 1), s(1, 1), s(2, 1)],
        ]
    }

    /// Newton from `u` at `d`; on success also checks the integration error (raising the step
    /// count and starting over when it is too large).
    ///
    /// Chord iterations: the Jacobian (a shot with sensitivities) is taken at the first iterate,
    /// so from a good predictor the usual cost is one shot with and one without sensitivities,
    /// and the tangent comes from that Jacobian (its `O(|Δu|)` error only enters the next
    /// prediction; after a large correction it is recomputed at the solution). The Jacobian is
    /// refreshed when the residual does not drop by 10× per iteration.
    fn correct(&mut self, mut u: [f64; 3], d: f64) -> Option<Point> {
        let u_start = u;
        'pass: for _pass in 0..6 {
            let mut jac: Option<[[f64; 3]; 3]> = None;
            let mut fresh = false;
            let mut rn_prev = f64::INFINITY;
            for it in 0..=MAX_ITER {
                let shot = if jac.is_none() {
                    let sh = self.int.shoot::<true>(&u);
                    jac = Some(Self::jac(&sh.y1));
                    fresh = true;
                    sh
                } else {
                    self.int.shoot::<false>(&u)
                };
                let r = self.residual(&shot.y1, d);
                let rn = r.iter().fold(0.0f64, |a, v| a.max(v.abs()));
                if !rn.is_finite() {
                    return None;
                }
                if rn <= self.newton_tol {
                    if shot.err > 1.0 {
                        // too few steps for the tolerance: ~order-8 rule with a margin
                        let fac = (shot.err.powf(1.0 / 8.0) * 1.05).clamp(1.05, 4.0);
                        let n = self.int.steps;
                        self.int.steps = ((n as f64 * fac).ceil() as usize).clamp(n + 1, 100_000);
                        u = u_start;
                        continue 'pass;
                    }
                    self.int.stats.residual = rn;
                    let moved = u
                        .iter()
                        .zip(&u_start)
                        .fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
                    if fresh && moved > 1e-6 {
                        // far from the prediction: the first Jacobian is too rough for a tangent
                        let sh = self.int.shoot::<true>(&u);
                        jac = Some(Self::jac(&sh.y1));
                    }
                    let j = jac?;
                    let du = if fresh {
                        solve3(&j, &[0.0, -1.0, 0.0])?
                    } else {
                        [f64::NAN; 3]
                    };
                    return Some(Point {
                        d,
                        u,
                        du,
                        det: det3(&j),
                    });
                }
                if it == MAX_ITER {
                    return None;
                }
                if rn > 0.1 * rn_prev {
                    // slow chord convergence: fresh Jacobian here
                    let sh = self.int.shoot::<true>(&u);
                    jac = Some(Self::jac(&sh.y1));
                    fresh = true;
                }
                rn_prev = rn;
                let du = solve3(&jac?, &[-r[0], -r[1], -r[2]])?;
                self.int.stats.newton_iters += 1;
                self.int.stats.factorizations += 1;
                for (a, b) in u.iter_mut().zip(du) {
                    *a += b;
                }
            }
        }
        None
    }

    /// The exact tangent `du/dd` at `u` (one shot with sensitivities at `u`; overwrites the
    /// recorded path).
    fn tangent_at(&mut self, u: &[f64; 3]) -> Option<[f64; 3]> {
        let sh = self.int.shoot::<true>(u);
        solve3(&Self::jac(&sh.y1), &[0.0, -1.0, 0.0])
    }

    /// The last integration's path as a [`Solution`] with `params = [f, α]`.
    fn solution(&self, p: &Point) -> Solution {
        let n = self.int.steps;
        Solution {
            n: 4,
            mesh: (0..=n).map(|i| i as f64 / n as f64).collect(),
            z: self.int.path_z.clone(),
            dz: self.int.path_dz.clone(),
            params: vec![p.u[1], p.u[2]],
            status: Status::Converged,
            stats: Stats {
                nodes: n + 1,
                residual: self.int.stats.residual,
                ..Stats::default()
            },
        }
    }

    /// Predictor from the last points (`hist`, newest last) to `d`: the Hermite polynomial through
    /// their values and tangents (degree 5 with three points), extrapolated.
    fn predict(hist: &[Point], d: f64) -> [f64; 3] {
        let m = hist.len().min(3);
        let pts = &hist[hist.len() - m..];
        let mut u = [0.0; 3];
        for (i, ui) in u.iter_mut().enumerate() {
            // confluent divided differences, nodes newest first: z = d_m, d_m, d_{m-1}, …
            let mut z = [0.0; 6];
            let mut q = [[0.0; 6]; 6];
            for (j, p) in pts.iter().rev().enumerate() {
                z[2 * j] = p.d;
                z[2 * j + 1] = p.d;
                q[2 * j][0] = p.u[i];
                q[2 * j + 1][0] = p.u[i];
                q[2 * j + 1][1] = p.du[i];
                if j > 0 {
                    q[2 * j][1] = (q[2 * j][0] - q[2 * j - 1][0]) / (z[2 * j] - z[2 * j - 1]);
                }
            }
            let len = 2 * m;
            for k in 2..len {
                for j in k..len {
                    q[j][k] = (q[j][k - 1] - q[j - 1][k - 1]) / (z[j] - z[j - k]);
                }
            }
            let (mut v, mut w) = (0.0, 1.0);
            for k in 0..len {
                v += q[k][k] * w;
                w *= d - z[k];
            }
            *ui = v;
        }
        u
    }
}

#[allow(clippy::needless_range_loop)] // index loops mirror the product formulas
/// Value and derivative at `x` of the polynomial through `(xs[i], ys[i])` (Lagrange form; a few
/// points, distinct abscissae).
fn lagrange(xs: &[f64], ys: &[f64], x: f64) -> (f64, f64) {
    let n = xs.len();
    let (mut v, mut dv) = (0.0, 0.0);
    for i in 0..n {
        let mut den = 1.0;
        let mut l = 1.0;
        for j in 0..n {
            if j != i {
                den *= xs[i] - xs[j];
                l *= x - xs[j];
            }
        }
        // derivative of Π_{j≠i}(x − x_j), without dividing by a possibly zero factor
        let mut dl = 0.0;
        for m in 0..n {
            if m == i {
                continue;
            }
            let mut pr = 1.0;
            for j in 0..n {
                if j != i && j != m {
                    pr *= x - xs[j];
                }
            }
            dl += pr;
        }
        v += ys[i] * l / den;
        dv += ys[i] * dl / den;
    }
    (v, dv)
}

/// Abscissae and the three unknowns' values of points, as columns.
fn columns(pts: &[Point]) -> (Vec<f64>, [Vec<f64>; 3]) {
    let xs = pts.iter().map(|p| p.d).collect();
    let us = [0, 1, 2].map(|i| pts.iter().map(|p| p.u[i]).collect());
    (xs, us)
}

/// Points of the interpolant that locates the maximum of μ (degree 5).
const POLY: usize = 6;

/// `m(s)` of a solution on the uniform mesh `i / n`: the cubic Hermite interpolant of
/// [`Solution::eval`] (same interval choice), as per-interval polynomial coefficients so that an
/// evaluation is a few operations (equal to `eval` up to rounding).
struct MCubic<'a> {
    mesh: &'a [f64],
    coef: Vec<[f64; 4]>,
}

impl<'a> MCubic<'a> {
    fn new(sol: &'a Solution) -> Self {
        let n = sol.mesh.len() - 1;
        let coef = (0..n)
            .map(|i| {
                let h = sol.mesh[i + 1] - sol.mesh[i];
                let (z0, z1) = (sol.z[4 * i + 3], sol.z[4 * (i + 1) + 3]);
                let (d0, d1) = (h * sol.dz[4 * i + 3], h * sol.dz[4 * (i + 1) + 3]);
                [
                    z0,
                    d0,
                    -3.0 * z0 - 2.0 * d0 + 3.0 * z1 - d1,
                    2.0 * z0 + d0 - 2.0 * z1 + d1,
                ]
            })
            .collect();
        MCubic {
            mesh: &sol.mesh,
            coef,
        }
    }

    /// `m(s)`, searching the interval from the guess `i` (cheap when `s` is near it); also
    /// returns the interval, the guess for a nearby next point.
    #[inline]
    fn at(&self, s: f64, mut i: usize) -> (f64, usize) {
        let n = self.coef.len();
        let mesh = self.mesh;
        i = i.min(n - 1);
        while i + 1 < n && mesh[i + 1] <= s {
            i += 1;
        }
        while i > 0 && mesh[i] > s {
            i -= 1;
        }
        let t = ((s - mesh[i]) / (mesh[i + 1] - mesh[i])).clamp(0.0, 1.0);
        let c = &self.coef[i];
        (((c[3] * t + c[2]) * t + c[1]) * t + c[0], i)
    }
}

/// `crate::solve::flex_points` for the uniform rod (κ = m) on a uniform mesh: the same samples,
/// threshold and bisection, with the cheap [`MCubic`].
fn flex_uniform(sol: &Solution) -> (usize, Option<f64>) {
    const N: usize = 128;
    let mc = MCubic::new(sol);
    // the samples are reused by the scale and the sign scan (same values as evaluating twice)
    let mut vals = [0.0; N + 1];
    let mut hint = 0;
    for (i, v) in vals.iter_mut().enumerate() {
        (*v, hint) = mc.at(i as f64 / N as f64, hint);
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
                    let (mut a, mut b, ka) = (sp, s, kp);
                    let mut hint = mc.at(a, 0).1;
                    for _ in 0..60 {
                        let c = 0.5 * (a + b);
                        let (kc, ic) = mc.at(c, hint);
                        hint = ic;
                        if (kc > 0.0) == (ka > 0.0) {
                            a = c;
                        } else {
                            b = c;
                        }
                    }
                    first = Some(0.5 * (a + b));
                }
            }
        }
        prev = Some((s, k));
    }
    (count, first)
}

/// The output point of a solution (as `Scanner::point` for the uniform rod, without building a
/// [`crate::Shape`]).
fn fast_point(sol: &Solution, d: f64, mu: f64) -> ScanPoint {
    let (f, alpha) = (sol.params[0], sol.params[1]);
    let (flex, s_flex) = flex_uniform(sol);
    ScanPoint {
        d,
        mu,
        alpha,
        phi1: sol.right()[2],
        f,
        fx: f * alpha.sin(),
        fy: -f * alpha.cos(),
        m_base: sol.left()[3],
        flex,
        s_flex,
        y_max: crate::solve::extrema(sol, 0.0, 1.0).max,
    }
}

/// The fast scan; `None` when it does not apply or gives up (the caller runs the generic scan).
pub(crate) fn scan_uniform<Pr: Profile>(
    sc: &Scanner<'_, Pr>,
    start_sol: &Solution,
    opts: &ScanOptions,
    grid: &[f64],
) -> Option<ScanResult> {
    if !Pr::UNIFORM || sc.family.rod.compliance != 0.0 {
        return None;
    }
    let tol = opts.solver.tol;
    let mut fast = Fast {
        sc,
        int: Integrator {
            steps: 8,
            tol,
            path_z: Vec::new(),
            path_dz: Vec::new(),
            stats: Stats::default(),
        },
        newton_tol: tol,
    };
    let u0 = [
        start_sol.left()[3],
        start_sol.params[0],
        start_sol.params[1],
    ];
    let p0 = fast.correct(u0, 0.0)?;
    let (start_point, start_shape) = sc.point(&fast.solution(&p0), 0.0);
    let mut points: Vec<ScanPoint> = Vec::with_capacity(grid.len());
    let mut shapes: Vec<Vec<ShapePoint>> = Vec::new();
    let keep = |shapes: &mut Vec<Vec<ShapePoint>>, sh: &crate::Shape| {
        if let Some(ns) = opts.keep_shapes {
            shapes.push(sh.samples(ns));
        }
    };
    let mut gi = 0;
    while gi < grid.len() && grid[gi] <= 0.0 {
        points.push(start_point);
        keep(&mut shapes, &start_shape);
        gi += 1;
    }
    let beta = sc.beta;
    let mu_of = |u: &[f64; 3]| (beta - u[2]).tan();
    let mut best = (mu_of(&p0.u), 0.0);
    let mut hist: Vec<Point> = vec![p0];
    let d_end = opts.d_max;
    loop {
        let last = hist[hist.len() - 1].clone();
        if last.d >= d_end {
            break;
        }
        // next internal point: the next grid point, or closer if that is far
        let target = if gi < grid.len() { grid[gi] } else { d_end };
        let d = if target - last.d > H_MAX {
            let k = ((target - last.d) / H_MAX).ceil();
            last.d + (target - last.d) / k
        } else {
            target
        };
        let p = fast.correct(Fast::<Pr>::predict(&hist, d), d)?;
        // a fold in d between the points: leave it to pseudo-arclength continuation
        if p.det.signum() != last.det.signum() {
            return None;
        }
        let sol = fast.solution(&p);
        let w = sc.watch(&sol, d);
        if w.pen > 0.0 {
            return None;
        }
        if let Some(mu0) = opts.mu0 {
            if w.mu >= mu0 {
                return None;
            }
        }
        // local maximum of μ between the last point and this one (μ' ∝ −α'): the root of α' of
        // the interpolant, refined by Newton steps with solves
        if last.du[2] < 0.0 && p.du[2] >= 0.0 {
            let mut h2 = hist[hist.len() + 1 - POLY.min(hist.len() + 1)..].to_vec();
            h2.push(p.clone());
            let (xs, us) = columns(&h2);
            let da =
                |x: f64| -> Result<f64, elastica::ElasticaError> { Ok(lagrange(&xs, &us[2], x).1) };
            let mut dm = elastica::roots::try_brent_root(da, last.d, d, 1e-15, 200).ok()?;
            // refine with solves: Newton on α'(d) = 0, α' from the exact tangent at each solve,
            // α'' from the interpolant (the interpolant alone is O(h⁵) off in d on coarse grids)
            let mut at = None;
            for _ in 0..4 {
                let q = fast.correct(Fast::<Pr>::predict(&hist, dm), dm)?;
                let g = fast.tangent_at(&q.u)?[2];
                at = Some((mu_of(&q.u), dm));
                let e = 1e-4 * (d - last.d);
                let a2 =
                    (lagrange(&xs, &us[2], dm + e).1 - lagrange(&xs, &us[2], dm - e).1) / (2.0 * e);
                let step = if a2 != 0.0 { -g / a2 } else { 0.0 };
                if step.is_nan() || step.abs() <= 1e-13 {
                    break;
                }
                dm = (dm + step).clamp(last.d, d);
            }
            let (mm, dm) = at?;
            if mm > best.0 {
                best = (mm, dm);
            }
            // the path buffers hold the maximum's rod now; `sol` was built before
        }
        if gi < grid.len() && grid[gi] == d {
            let pt = fast_point(&sol, d, w.mu);
            let sh = opts.keep_shapes.map(|_| sc.point(&sol, d).1);
            // repeated grid values too
            while gi < grid.len() && grid[gi] == d {
                points.push(pt);
                if let Some(sh) = &sh {
                    keep(&mut shapes, sh);
                }
                gi += 1;
            }
        }
        if w.mu > best.0 {
            best = (w.mu, d);
        }
        hist.push(p);
        if hist.len() > POLY {
            hist.remove(0);
        }
    }
    let mut stats = start_sol.stats.clone();
    stats.accumulate(&fast.int.stats);
    stats.residual = fast.int.stats.residual;
    stats.nodes = fast.int.steps + 1;
    Some(ScanResult {
        eta: sc.family.eta,
        start: start_point,
        points,
        mu_max: best.0,
        d_at_mu_max: best.1,
        stop: StopReason::DMax,
        stats,
        shapes,
    })
}

/// The single-shooting tolerance of `engine` when it is plain single shooting with the adaptive
/// integrator (the configuration the fast paths replace), else `None`.
pub(crate) fn single_shooting_tol(engine: &crate::solve::Engine) -> Option<f64> {
    match engine {
        crate::solve::Engine::Shoot(s) => {
            let o = s.options();
            match o.integrator {
                bvp::Integrator::Adaptive { rtol, atol } if o.segments == 1 && rtol == atol => {
                    Some(o.newton.tol.min(rtol))
                }
                _ => None,
            }
        }
        crate::solve::Engine::Coll(_) => None,
    }
}

/// One shape of the uniform clamped rod with a tip-slope or tip-height condition and fixed α,
/// by the shot of the fast scan: unknowns `(m(0), f)`, residual `(m(1), φ(1) − φ1)` or
/// `(m(1), y(1) − η)`, damped Newton (halving on a residual increase) with the same tolerance
/// contract as single shooting (`|R| ≤ tol`, step error estimates within `tol`). `None` when it
/// does not apply or does not converge: the caller then runs the generic solver.
pub(crate) fn solve_rod<Pr: Profile>(
    rod: &crate::model::RodBvp<Pr>,
    guess: &bvp::Guess,
    tol: f64,
) -> Option<Solution> {
    use crate::model::Ends;
    if !Pr::UNIFORM || rod.compliance != 0.0 || guess.params.len() != 1 {
        return None;
    }
    // component of z(1) that the end condition fixes, and its value
    let (comp, target) = match rod.ends {
        Ends::Phi1 { phi1 } => (2, phi1),
        Ends::Eta { eta } => (1, eta),
        Ends::Tip { .. } => return None,
    };
    let mut z0 = [0.0; 4];
    guess.eval(0.0, &mut z0);
    let alpha = rod.alpha;
    let mut u = [z0[3], guess.params[0], alpha];
    let mut int = Integrator {
        steps: 8,
        tol,
        path_z: Vec::new(),
        path_dz: Vec::new(),
        stats: Stats::default(),
    };
    let res = |y: &Y| [y[3], y[comp] - target];
    let norm = |r: &[f64; 2]| r[0].abs().max(r[1].abs());
    // last accepted point, its Newton step, residual and the damping tried
    let mut prev: Option<([f64; 3], [f64; 2], f64, f64)> = None;
    for _ in 0..60 {
        let shot = int.shoot::<true>(&u);
        let r = res(&shot.y1);
        let rn = norm(&r);
        let y = &shot.y1;
        let (a, b) = (y[4 + 3], y[4 + 4 + 3]);
        let (c, d) = (y[4 + comp], y[4 + 4 + comp]);
        let det = a * d - b * c;
        if rn <= tol {
            if shot.err > 1.0 {
                let fac = (shot.err.powf(1.0 / 8.0) * 1.05).clamp(1.05, 4.0);
                let n = int.steps;
                int.steps = ((n as f64 * fac).ceil() as usize).clamp(n + 1, 100_000);
                prev = None;
                continue;
            }
            // near a turning point the residual says little about the unknowns (square-root
            // dependence): leave such rods to the generic solver
            let cond = (a.abs() + b.abs()).max(c.abs() + d.abs())
                * (d.abs() + b.abs()).max(c.abs() + a.abs())
                / det.abs();
            if cond.is_nan() || cond >= 1e6 {
                return None;
            }
            let n = int.steps;
            int.stats.residual = rn;
            int.stats.nodes = n + 1;
            return Some(Solution {
                n: 4,
                mesh: (0..=n).map(|i| i as f64 / n as f64).collect(),
                z: std::mem::take(&mut int.path_z),
                dz: std::mem::take(&mut int.path_dz),
                params: vec![u[1]],
                status: Status::Converged,
                stats: int.stats,
            });
        }
        if let Some((uo, du, rno, lam)) = prev {
            // no decrease (or a non-finite residual): halve the last step
            if rn.is_nan() || rn >= rno {
                if lam < 1e-3 {
                    return None;
                }
                let lam = 0.5 * lam;
                u = [uo[0] + lam * du[0], uo[1] + lam * du[1], alpha];
                prev = Some((uo, du, rno, lam));
                continue;
            }
        }
        if !rn.is_finite() {
            return None;
        }
        // 2×2 Newton step in (m0, f)
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let du = [(-r[0] * d + r[1] * b) / det, (-r[1] * a + r[0] * c) / det];
        int.stats.newton_iters += 1;
        int.stats.factorizations += 1;
        prev = Some((u, du, rn, 1.0));
        u = [u[0] + du[0], u[1] + du[1], alpha];
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Ends, RodBvp, Uniform};
    use crate::Model;

    /// The fast point equals the generic `shape_from` + `watch` one on the same solution (convex
    /// and one-flex rods), so the fast scan reports what the generic scan would.
    #[test]
    fn fast_point_matches_generic() {
        let model = Model::new(&crate::Scene::default()).unwrap();
        let rod = RodBvp {
            profile: Uniform,
            compliance: 0.0,
            alpha: 0.0,
            ends: Ends::Tip { x1: 0.5, y1: 0.75 },
        };
        for (branch, a, p) in [
            (elastica::Branch::Convex, -0.2, 0.4),
            (elastica::Branch::OneFlex, -0.3, 0.2),
        ] {
            let e = elastica::Elastica::new(branch, a, p).unwrap();
            let mut int = Integrator {
                steps: 13,
                tol: 1e-10,
                path_z: Vec::new(),
                path_dz: Vec::new(),
                stats: Stats::default(),
            };
            int.shoot::<true>(&[e.m_base, e.f, a]);
            let n = int.steps;
            let sol = Solution {
                n: 4,
                mesh: (0..=n).map(|i| i as f64 / n as f64).collect(),
                z: int.path_z.clone(),
                dz: int.path_dz.clone(),
                params: vec![e.f, a],
                status: Status::Converged,
                stats: Stats::default(),
            };
            let fast = fast_point(&sol, 0.1, 0.3);
            let shape = crate::solve::shape_from(sol.clone(), &rod, model.profile(1.0));
            assert_eq!(fast.flex, shape.flex);
            assert_eq!(fast.flex, e.flex_count());
            match (fast.s_flex, shape.s_flex) {
                (Some(x), Some(y)) => assert!((x - y).abs() < 1e-15, "{x} {y}"),
                (None, None) => {}
                other => panic!("flex points differ: {other:?}"),
            }
            assert_eq!(fast.y_max, shape.y_max);
            assert_eq!(fast.phi1, shape.phi1);
            assert_eq!(fast.m_base, shape.m_base);
            // the 13-step path is an accurate rod: the tip slope against the closed form
            assert!((fast.phi1 - p).abs() < 1e-9, "{} {p}", fast.phi1);
        }
    }
}

#[cfg(test)]
mod shape_tests {
    use super::*;
    use crate::model::{Ends, RodBvp, Uniform};

    // mpmath digits as printed in the data file
    #[allow(clippy::excessive_precision)]
    /// The fast single shape against the closed form (paper's Fig. 3 rods, mpmath values in
    /// data/elastica/special_values.csv), from a start 10 % off in `m(0)` and `f`.
    #[test]
    fn solve_rod_matches_closed_form() {
        let (alpha, phi1) = (-std::f64::consts::PI / 8.0, std::f64::consts::PI / 8.0);
        for (branch, f_mp) in [
            (elastica::Branch::Convex, 4.718_125_860_964_310_5),
            (elastica::Branch::OneFlex, 19.028_967_652_434_935),
        ] {
            let e = elastica::Elastica::new(branch, alpha, phi1).unwrap();
            let rod = RodBvp {
                profile: Uniform,
                compliance: 0.0,
                alpha,
                ends: Ends::Phi1 { phi1 },
            };
            let guess = bvp::Guess::constant(
                0.0,
                1.0,
                2,
                &[0.0, 0.0, FRAC_PI_2, 0.9 * e.m_base],
                vec![0.9 * e.f],
            );
            let sol = solve_rod(&rod, &guess, 1e-11).expect("converges");
            let f = sol.params[0];
            assert!(
                (f - f_mp).abs() < 1e-10 * f_mp,
                "{branch:?}: f = {f}, mpmath {f_mp}"
            );
            assert!((sol.right()[2] - phi1).abs() < 1e-11);
        }
    }
}

#[cfg(test)]
mod scan_tests {
    use crate::{scan, Model, ScanOptions, Scene};

    /// μ_max and where it occurs against the closed form, also on a coarse grid (where the
    /// maximum lies far from the grid points and must be located by solves).
    #[test]
    fn mu_max_located_on_coarse_grids() {
        let cf = elastica::ClosedFormScan::new(0.75)
            .unwrap()
            .mu_max()
            .unwrap();
        let model = Model::new(&Scene::default()).unwrap();
        for points in [11, 201] {
            let o = ScanOptions {
                points,
                ..ScanOptions::default()
            };
            let r = scan(&model, &o).unwrap();
            assert!(
                (r.mu_max - cf.mu).abs() < 1e-9,
                "{points}: {} {}",
                r.mu_max,
                cf.mu
            );
            // μ is flat at its maximum: d is determined to ~sqrt(tol)
            assert!(
                (r.d_at_mu_max - cf.d).abs() < 1e-6,
                "{points}: {} {}",
                r.d_at_mu_max,
                cf.d
            );
        }
    }
}

#[cfg(test)]
mod sincos_tests {
    /// The fast `sin_cos` against libm over several turns (a few ulp).
    #[test]
    fn sin_cos_matches_libm() {
        for i in -20_000..=20_000 {
            let x = i as f64 * 1.234_567e-3;
            let (s, c) = super::sin_cos(x);
            let (s0, c0) = x.sin_cos();
            assert!((s - s0).abs() <= 4.0 * f64::EPSILON, "sin {x}: {s} {s0}");
            assert!((c - c0).abs() <= 4.0 * f64::EPSILON, "cos {x}: {c} {c0}");
        }
    }
}
