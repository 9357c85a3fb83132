//! Fast path of the stiction scan for the uniform clamped rod with single shooting.
//!
//! The generic scan (pseudo-arclength continuation through crate `bvp`, output by extra solves at
//! the grid points) is method-agnostic and handles every scene. For the paper's rod with single
//! shooting most of its work is not needed: `d` itself parametrizes the branch up to a fold in `d`
//! (folds in α or φ1 are regular points here), so the scan can step from grid point to grid point.
//!
//! - Unknowns `u = (m(0), f, α)`; residual `R = (m(1), x(1) − (x* − d), y(1) − η)`.
//! - One integration of the rod and its variational equations in `u` only (16 components instead
//!   of the generic 28), monomorphized and allocation-free, with the 8th-order DOP853 weights on
//!   `N` equal steps. Fixed steps make the sensitivities the exact Jacobian of the discrete
//!   residual (quadratic Newton); the embedded error estimate of each step is checked against
//!   `tol` (`rtol = atol = tol`, Hairer's norm, as the adaptive integrator) and `N` is raised when
//!   it is exceeded, so the accuracy contract is the generic one.
//! - Predictor: the tangent `u' = −J⁻¹ ∂R/∂d` from the Jacobian of the last converged point, plus
//!   curvature and third-order terms from the previous points, so most points need one or two
//!   integrations.
//! - Events are watched at every point as in the generic scan. Anything it does not handle itself
//!   (penetration, slip, a fold in `d` — a sign change of `det J` — or a Newton failure) makes it
//!   give up and leave the scan to the generic path, which redoes it from the start.
//! - μ_max between grid points: the root of `α'(d)` (from the tangent) by Brent's method, each
//!   evaluation a corrected point.

use crate::model::Profile;
use crate::scan::{ScanOptions, ScanPoint, ScanResult, Scanner, StopReason};
use crate::ShapePoint;
use bvp::{Solution, Stats, Status};
use std::f64::consts::FRAC_PI_2;

/// DOP853 nodes/weights (Hairer–Nørsett–Wanner), as in crate `bvp`.
#[allow(clippy::excessive_precision)]
mod tab {
    pub const A: [[f64; 12]; 12] = [
        [0.0; 12],
        [
            5.26001519587677318785587544488e-2,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
        ],
        [
            1.97250569845378994544595329183e-2,
            5.91751709536136983633785987549e-2,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
        ],
        [
            2.95875854768068491816892993775e-2,
            0.0,
            8.87627564304205475450678981324e-2,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
        ],
        [
            2.41365134159266685502369798665e-1,
            0.0,
            -8.84549479328286085344864962717e-1,
            9.24834003261792003115737966543e-1,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
        ],
        [
            3.7037037037037037037037037037e-2,
            0.0,
            0.0,
            1.70828608729473871279604482173e-1,
            1.25467687566822425016691814123e-1,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
        ],
        [
            3.7109375e-2,
            0.0,
            0.0,
            1.70252211019544039314978060272e-1,
            6.02165389804559606850219397283e-2,
            -1.7578125e-2,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
        ],
        [
            3.70920001185047927108779319836e-2,
            0.0,
            0.0,
            1.70383925712239993810214054705e-1,
            1.07262030446373284651809199168e-1,
            -1.53194377486244017527936158236e-2,
            8.27378916381402288758473766002e-3,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
        ],
        [
            6.24110958716075717114429577812e-1,
            0.0,
            0.0,
            -3.36089262944694129406857109825e0,
            -8.68219346841726006818189891453e-1,
            2.75920996994467083049415600797e1,
            2.01540675504778934086186788979e1,
            -4.34898841810699588477366255144e1,
            0.0,
            0.0,
            0.0,
            0.0,
        ],
        [
            4.77662536438264365890433908527e-1,
            0.0,
            0.0,
            -2.48811461997166764192642586468e0,
            -5.90290826836842996371446475743e-1,
            2.12300514481811942347288949897e1,
            1.52792336328824235832596922938e1,
            -3.32882109689848629194453265587e1,
            -2.03312017085086261358222928593e-2,
            0.0,
            0.0,
            0.0,
        ],
        [
            -9.3714243008598732571704021658e-1,
            0.0,
            0.0,
            5.18637242884406370830023853209e0,
            1.09143734899672957818500254654e0,
            -8.14978701074692612513997267357e0,
            -1.85200656599969598641566180701e1,
            2.27394870993505042818970056734e1,
            2.49360555267965238987089396762e0,
            -3.0467644718982195003823669022e0,
            0.0,
            0.0,
        ],
        [
            2.27331014751653820792359768449e0,
            0.0,
            0.0,
            -1.05344954667372501984066689879e1,
            -2.00087205822486249909675718444e0,
            -1.79589318631187989172765950534e1,
            2.79488845294199600508499808837e1,
            -2.85899827713502369474065508674e0,
            -8.87285693353062954433549289258e0,
            1.23605671757943030647266201528e1,
            6.43392746015763530355970484046e-1,
            0.0,
        ],
    ];
    pub const B: [f64; 12] = [
        5.42937341165687622380535766363e-2,
        0.0,
        0.0,
        0.0,
        0.0,
        4.45031289275240888144113950566e0,
        1.89151789931450038304281599044e0,
        -5.8012039600105847814672114227e0,
        3.1116436695781989440891606237e-1,
        -1.52160949662516078556178806805e-1,
        2.01365400804030348374776537501e-1,
        4.47106157277725905176885569043e-2,
    ];
    const BHH1: f64 = 0.244094488188976377952755905512e+00;
    const BHH2: f64 = 0.733846688281611857341361741547e+00;
    const BHH3: f64 = 0.220588235294117647058823529412e-01;
    pub const E3: [f64; 12] = [
        B[0] - BHH1,
        0.0,
        0.0,
        0.0,
        0.0,
        B[5],
        B[6],
        B[7],
        B[8] - BHH2,
        B[9],
        B[10],
        B[11] - BHH3,
    ];
    pub const E5: [f64; 12] = [
        0.1312004499419488073250102996e-01,
        0.0,
        0.0,
        0.0,
        0.0,
        -0.1225156446376204440720569753e+01,
        -0.4957589496572501915214079952e+00,
        0.1664377182454986536961530415e+01,
        -0.3503288487499736816886487290e+00,
        0.3341791187130174790297318841e+00,
        0.8192320648511571246570742613e-01,
        -0.2235530786388629525884427845e-01,
    ];
}

/// State and sensitivities: `y[0..4] = (x, y, φ, m)`, `y[4 + 4q + i] = ∂z_i/∂u_q`.
const NV: usize = 16;
type Y = [f64; NV];

/// Rod right-hand side with the variational equations in `u = (m0, f, α)`.
#[inline(always)]
fn rhs<const VAR: bool>(y: &Y, f: f64, ca: f64, sa: f64) -> Y {
    let (sp, cp) = y[2].sin_cos();
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
            for i in 1..12 {
                let mut t = y;
                for (j, kj) in k.iter().enumerate().take(i) {
                    let a = tab::A[i][j];
                    if a != 0.0 {
                        let ha = h * a;
                        for c in 0..nv {
                            t[c] += ha * kj[c];
                        }
                    }
                }
                k[i] = rhs::<VAR>(&t, f, ca, sa);
            }
            let mut ynew = y;
            for (j, kj) in k.iter().enumerate() {
                let b = tab::B[j];
                if b != 0.0 {
                    let hb = h * b;
                    for c in 0..nv {
                        ynew[c] += hb * kj[c];
                    }
                }
            }
            // Hairer's DOP853 error norm over z
            let (mut e5, mut e3) = (0.0, 0.0);
            for c in 0..4 {
                let sk = self.tol * (1.0 + y[c].abs().max(ynew[c].abs()));
                let (mut a5, mut a3) = (0.0, 0.0);
                for (j, kj) in k.iter().enumerate() {
                    a5 += tab::E5[j] * kj[c];
                    a3 += tab::E3[j] * kj[c];
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
    /// Chord iterations: the Jacobian (a shot with sensitivities) is taken at the first iterate
    /// only and refreshed when the residual does not drop by 10×; the other shots integrate the
    /// rod alone. From a good predictor the first step lands within `O(|Δu|²)`, so the usual cost
    /// is one shot with and one without sensitivities. The tangent uses the first Jacobian (its
    /// `O(|Δu|)` error only enters the next prediction).
    fn correct(&mut self, mut u: [f64; 3], d: f64) -> Option<Point> {
        let u_start = u;
        'pass: for _pass in 0..6 {
            let mut jac: Option<[[f64; 3]; 3]> = None;
            let mut jac0 = None;
            let mut rn_prev = f64::INFINITY;
            for it in 0..=MAX_ITER {
                let shot = if jac.is_none() {
                    let sh = self.int.shoot::<true>(&u);
                    jac = Some(Self::jac(&sh.y1));
                    if jac0.is_none() {
                        jac0 = jac;
                    }
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
                    if moved > 1e-6 {
                        // far from the prediction: the first Jacobian is too rough for a tangent
                        let sh = self.int.shoot::<true>(&u);
                        jac0 = Some(Self::jac(&sh.y1));
                    }
                    let j0 = jac0?;
                    let du = solve3(&j0, &[0.0, -1.0, 0.0])?;
                    return Some(Point {
                        d,
                        u,
                        du,
                        det: det3(&j0),
                    });
                }
                if it == MAX_ITER {
                    return None;
                }
                if rn > 0.1 * rn_prev {
                    // slow chord convergence: fresh Jacobian here
                    let sh = self.int.shoot::<true>(&u);
                    jac = Some(Self::jac(&sh.y1));
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

/// `m(s)` of a solution on the uniform mesh `i / n` by the cubic Hermite interpolant of
/// [`Solution::eval`] (same interval choice and formula), without the search and the other states.
#[inline]
fn m_at(sol: &Solution, s: f64) -> f64 {
    let n = sol.mesh.len() - 1;
    let s = s.clamp(0.0, 1.0);
    let node = |i: usize| i as f64 / n as f64;
    let mut i = ((s * n as f64) as usize).min(n - 1);
    while i + 1 < n && node(i + 1) <= s {
        i += 1;
    }
    while i > 0 && node(i) > s {
        i -= 1;
    }
    let (s0, s1) = (sol.mesh[i], sol.mesh[i + 1]);
    let h = s1 - s0;
    let t = ((s - s0) / h).clamp(0.0, 1.0);
    let t2 = t * t;
    let t3 = t2 * t;
    (2.0 * t3 - 3.0 * t2 + 1.0) * sol.z[4 * i + 3]
        + (t3 - 2.0 * t2 + t) * h * sol.dz[4 * i + 3]
        + (-2.0 * t3 + 3.0 * t2) * sol.z[4 * (i + 1) + 3]
        + (t3 - t2) * h * sol.dz[4 * (i + 1) + 3]
}

/// `crate::solve::flex_points` for the uniform rod (κ = m) on a uniform mesh: the same samples,
/// threshold and bisection, with the cheap [`m_at`].
fn flex_uniform(sol: &Solution) -> (usize, Option<f64>) {
    const N: usize = 128;
    let kap = |s: f64| m_at(sol, s);
    // the samples are reused by the scale and the sign scan (same values as evaluating twice)
    let mut vals = [0.0; N + 1];
    for (i, v) in vals.iter_mut().enumerate() {
        *v = kap(i as f64 / N as f64);
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
                    for _ in 0..60 {
                        let c = 0.5 * (a + b);
                        if (kap(c) > 0.0) == (ka > 0.0) {
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
        let u = Fast::<Pr>::predict(&hist, d);
        let p = fast.correct(u, d)?;
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
        // local maximum of μ between the last point and this one: μ' ∝ −α'
        if last.du[2] < 0.0 && p.du[2] >= 0.0 {
            let mut eval = |dd: f64| -> Result<f64, elastica::ElasticaError> {
                let u = Fast::<Pr>::predict(&hist, dd);
                fast.correct(u, dd)
                    .map(|q| q.du[2])
                    .ok_or(elastica::ElasticaError::NotFinite {
                        name: "fast scan solve",
                        value: dd,
                    })
            };
            let dm = elastica::roots::try_brent_root(&mut eval, last.d, d, 1e-13, 100).ok()?;
            let q = fast.correct(Fast::<Pr>::predict(&hist, dm), dm)?;
            let mm = mu_of(&q.u);
            if mm > best.0 {
                best = (mm, dm);
            }
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
        if hist.len() > 3 {
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
