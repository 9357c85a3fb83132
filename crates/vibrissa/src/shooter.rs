//! The rod's own shooter: one integration of the rod equations over `s ∈ [0, 1]` from the foot
//! state given by `u = (m(0), f, α)`, with the sensitivities `∂z/∂u` carried on the same stages.
//!
//! - 8th-order DOP853 weights on a fixed mesh; fixed steps make the sensitivities the exact
//!   Jacobian of the discrete residual, so Newton converges quadratically. The embedded error
//!   estimate of each step is checked against `tol` (`rtol = atol = tol`, Hairer's norm, as the
//!   adaptive integrator of crate `bvp`); steps that exceed it are split and the solve redone, so
//!   the mesh grades itself (fine near the thin tip of a tapered rod) and the accuracy contract is
//!   the generic one.
//! - Generic over the [`Profile`]: the uniform rod folds `b ≡ 1`, `κ0 ≡ 0` away; any other
//!   profile is evaluated once per mesh at the stage abscissae and read from a table, so a shot
//!   costs the same for a tapered, pre-curved or tabulated rod.
//! - Allocation-free per shot (buffers kept), an inline `sin_cos`, and an AVX2 build chosen at run
//!   time (the 16 components are four 256-bit lanes).

use crate::equations::{rod_rhs_var, NV, Y};
use crate::profile::Profile;
use bvp::tableau::dop853 as tab;
use bvp::{Solution, Stats, Status};
use std::f64::consts::FRAC_PI_2;

/// Largest number of steps before a shot gives up refining (a far-off Newton iterate).
pub(crate) const MAX_STEPS: usize = 100_000;

/// Result of one integration over `[0, 1]`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Shot {
    /// End state and sensitivities: `y[0..4] = z(1)`, `y[4 + 4q + i] = ∂z_i(1)/∂u_q`.
    pub y1: Y,
    /// Max over the steps of the scaled error estimate (≤ 1: within tolerance).
    pub err: f64,
}

/// The fixed-mesh integrator of one rod, with its recorded path.
#[derive(Clone, Debug)]
pub(crate) struct Shooter<P: Profile> {
    /// Stiffness and rest curvature.
    pub profile: P,
    /// Support compliance `c`: `φ(0) = π/2 + c·m(0)`.
    pub compliance: f64,
    /// Tolerance of the step error estimates.
    pub tol: f64,
    /// Mesh nodes, `0 = s_0 < … < s_N = 1`.
    nodes: Vec<f64>,
    /// `(b, κ0)` at the 12 stage abscissae of each step, then at `s = 1` (non-uniform profiles).
    coef: Vec<[f64; 2]>,
    /// Scaled error estimate of each step of the last shot.
    step_err: Vec<f64>,
    /// Nodes' `z` and `F(z)` (node-major, 4 each) of the last shot.
    path_z: Vec<f64>,
    path_dz: Vec<f64>,
    /// Work counters.
    pub stats: Stats,
}

impl<P: Profile> Shooter<P> {
    /// A shooter with `steps` equal steps.
    pub fn new(profile: P, compliance: f64, tol: f64, steps: usize) -> Self {
        let mut s = Shooter {
            profile,
            compliance,
            tol,
            nodes: Vec::new(),
            coef: Vec::new(),
            step_err: Vec::new(),
            path_z: Vec::new(),
            path_dz: Vec::new(),
            stats: Stats::default(),
        };
        s.set_mesh((0..=steps).map(|i| i as f64 / steps as f64).collect());
        s
    }

    /// A shooter on the mesh `nodes` (`0 = s_0 < … < s_N = 1`), e.g. the one a solve ended on.
    pub fn on_mesh(profile: P, compliance: f64, tol: f64, nodes: Vec<f64>) -> Self {
        let mut s = Shooter::new(profile, compliance, tol, 1);
        s.set_mesh(nodes);
        s
    }

    /// Number of steps.
    pub fn steps(&self) -> usize {
        self.nodes.len() - 1
    }

    /// Replaces the profile (homotopy), keeping the mesh.
    pub fn set_profile(&mut self, profile: P, compliance: f64) {
        self.profile = profile;
        self.compliance = compliance;
        let nodes = std::mem::take(&mut self.nodes);
        self.set_mesh(nodes);
    }

    fn set_mesh(&mut self, nodes: Vec<f64>) {
        self.nodes = nodes;
        self.coef.clear();
        if !P::UNIFORM {
            for w in self.nodes.windows(2) {
                let h = w[1] - w[0];
                for c in tab::C {
                    let s = w[0] + c * h;
                    self.coef.push([self.profile.b(s), self.profile.k0(s)]);
                }
            }
            self.coef.push([self.profile.b(1.0), self.profile.k0(1.0)]);
        }
    }

    /// A new mesh after a shot with steps over tolerance: each such step should shrink by
    /// `0.9·e^(−1/8)` (the order-8 rule with a margin; a quarter where `e` is not finite), the
    /// others keep their size, and the nodes equidistribute that step-size function, so the mesh
    /// grows by what the errors ask for rather than by halving whole steps. `false` when it would
    /// exceed [`MAX_STEPS`].
    pub fn refine(&mut self) -> bool {
        // steps per unit of the old step of each interval
        let shrink: Vec<f64> = (0..self.steps())
            .map(|i| {
                let e = self.step_err.get(i).copied().unwrap_or(0.0);
                if !e.is_finite() {
                    4.0
                } else if e > 1.0 {
                    1.0 / (0.9 * e.powf(-1.0 / 8.0))
                } else {
                    1.0
                }
            })
            .collect();
        let total: f64 = shrink.iter().sum();
        let n_new = total.ceil() as usize;
        if n_new > MAX_STEPS || n_new <= self.steps() {
            return false;
        }
        // the nodes where the cumulative step count, stretched to n_new, is an integer
        let stretch = n_new as f64 / total;
        let mut nodes = Vec::with_capacity(n_new + 1);
        nodes.push(0.0);
        let mut count = 0.0;
        for (w, k) in self.nodes.windows(2).zip(&shrink) {
            let per = k * stretch;
            let next = count + per;
            while (nodes.len() as f64) < next - 1e-9 && nodes.len() < n_new {
                let t = (nodes.len() as f64 - count) / per;
                nodes.push(w[0] + (w[1] - w[0]) * t);
            }
            count = next;
        }
        nodes.push(1.0);
        self.set_mesh(nodes);
        true
    }

    /// Integrates from `u = (m(0), f, α)`; with `VAR` also the sensitivities (else only `z`).
    #[inline]
    pub fn shoot<const VAR: bool>(&mut self, u: &[f64; 3]) -> Shot {
        #[cfg(target_arch = "x86_64")]
        {
            if std::is_x86_feature_detected!("avx2") {
                // SAFETY: the CPU has AVX2 (checked just above), the only requirement of
                // `shoot_avx2`.
                return unsafe { self.shoot_avx2::<VAR>(u) };
            }
        }
        self.shoot_width::<VAR>(u)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn shoot_avx2<const VAR: bool>(&mut self, u: &[f64; 3]) -> Shot {
        self.shoot_width::<VAR>(u)
    }

    #[inline(always)]
    fn shoot_width<const VAR: bool>(&mut self, u: &[f64; 3]) -> Shot {
        if VAR {
            self.shoot_impl::<true, NV>(u)
        } else {
            self.shoot_impl::<false, 4>(u)
        }
    }

    #[inline(always)]
    fn shoot_impl<const VAR: bool, const N: usize>(&mut self, u: &[f64; 3]) -> Shot {
        let (m0, f, alpha) = (u[0], u[1], u[2]);
        let (sa, ca) = alpha.sin_cos();
        let c = self.compliance;
        let n = self.nodes.len() - 1;
        let mut y = [0.0; N];
        y[2] = FRAC_PI_2 + c * m0;
        y[3] = m0;
        if VAR {
            y[4 + 2] = c; // ∂φ(0)/∂m0
            y[4 + 3] = 1.0; // ∂m(0)/∂m0
        }
        self.path_z.clear();
        self.path_dz.clear();
        self.step_err.clear();
        let bk = |i: usize| -> (f64, f64) {
            if P::UNIFORM {
                (1.0, 0.0)
            } else {
                let e = self.coef[i];
                (e[0], e[1])
            }
        };
        let mut k = [[0.0; N]; 12];
        let (b0, q0) = bk(0);
        k[0] = rod_rhs_var::<N>(&y, f, ca, sa, b0, q0);
        let mut err_max: f64 = 0.0;
        for step in 0..n {
            let h = self.nodes[step + 1] - self.nodes[step];
            let base = 12 * step;
            self.path_z.extend_from_slice(&y[..4]);
            self.path_dz.extend_from_slice(&k[0][..4]);
            // stage sums over the nonzero coefficients only, unrolled
            macro_rules! stage {
                ($i:literal, [$($j:literal),*]) => {{
                    let mut t = y;
                    $(
                        let ha = h * tab::A[$i * tab::STAGES + $j];
                        for cc in 0..N {
                            t[cc] += ha * k[$j][cc];
                        }
                    )*
                    let (bb, qq) = bk(base + $i);
                    k[$i] = rod_rhs_var::<N>(&t, f, ca, sa, bb, qq);
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
                for cc in 0..N {
                    ynew[cc] += hb * k[j][cc];
                }
            }
            // Hairer's DOP853 error norm over z
            let (mut e5, mut e3) = (0.0, 0.0);
            for cc in 0..4 {
                let sk = self.tol * (1.0 + y[cc].abs().max(ynew[cc].abs()));
                let (mut a5, mut a3) = (0.0, 0.0);
                for j in NZB {
                    a5 += tab::E5[j] * k[j][cc];
                    a3 += tab::E3[j] * k[j][cc];
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
            let err = if err.is_nan() { f64::INFINITY } else { err };
            self.step_err.push(err);
            err_max = err_max.max(err);
            y = ynew;
            let (bb, qq) = bk(base + 12);
            k[0] = rod_rhs_var::<N>(&y, f, ca, sa, bb, qq);
        }
        self.path_z.extend_from_slice(&y[..4]);
        self.path_dz.extend_from_slice(&k[0][..4]);
        self.stats.steps += n;
        self.stats.rhs_evals += 12 * n + 1;
        if VAR {
            self.stats.jac_evals += 12 * n + 1;
        }
        self.stats.bc_evals += 1;
        let mut y1 = [0.0; NV];
        y1[..N].copy_from_slice(&y);
        Shot { y1, err: err_max }
    }

    /// The last shot's path as a [`Solution`] (cubic Hermite between the mesh nodes).
    pub fn solution(&self, params: Vec<f64>, residual: f64) -> Solution {
        Solution {
            n: 4,
            mesh: self.nodes.clone(),
            z: self.path_z.clone(),
            dz: self.path_dz.clone(),
            params,
            status: Status::Converged,
            stats: Stats {
                nodes: self.nodes.len(),
                residual,
                ..Stats::default()
            },
            dense: bvp::Dense::Hermite,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::profile::{General, Uniform};
    use crate::{Precurvature, Scene, Stiffness};

    /// A general profile with b ≡ 1, κ0 ≡ 0 gives the uniform rod's shot bit for bit (the table
    /// path and the folded path are the same arithmetic).
    #[test]
    fn general_uniform_profile_matches_uniform() {
        let scene = Scene {
            stiffness: Stiffness::Taper { ratio: 1.0 },
            precurvature: Precurvature::Linear { k0: 0.0, k1: 0.0 },
            ..Scene::default()
        };
        let u = [-1.2, 3.0, -0.2];
        let mut a = Shooter::new(Uniform, 0.0, 1e-10, 16);
        let mut b = Shooter::new(
            General::new(&scene.stiffness, &scene.precurvature, 1.0),
            0.0,
            1e-10,
            16,
        );
        let (sa, sb) = (a.shoot::<true>(&u), b.shoot::<true>(&u));
        assert_eq!(sa.y1, sb.y1);
    }

    /// Sensitivities against central differences of the shot, for a tapered, pre-curved,
    /// compliant rod (the shot is smooth in u; the difference error is ~h² ≈ 1e-10).
    #[test]
    fn sensitivities_match_differences() {
        let scene = Scene {
            stiffness: Stiffness::Taper { ratio: 0.5 },
            precurvature: Precurvature::Linear { k0: 0.4, k1: -0.3 },
            support_compliance: 0.7,
            ..Scene::default()
        };
        let mut sh = Shooter::new(
            General::new(&scene.stiffness, &scene.precurvature, 1.0),
            0.7,
            1e-10,
            40,
        );
        let u = [-0.8, 2.5, -0.3];
        let y = sh.shoot::<true>(&u).y1;
        for q in 0..3 {
            let e = 1e-5;
            let (mut up, mut um) = (u, u);
            up[q] += e;
            um[q] -= e;
            let (yp, ym) = (sh.shoot::<false>(&up).y1, sh.shoot::<false>(&um).y1);
            for i in 0..4 {
                let fd = (yp[i] - ym[i]) / (2.0 * e);
                let an = y[4 + 4 * q + i];
                assert!(
                    (fd - an).abs() <= 1e-7 * (1.0 + an.abs()),
                    "∂z{i}/∂u{q}: fd {fd} analytic {an}"
                );
            }
        }
    }

    /// Refinement splits only the steps over tolerance: a strongly tapered rod gets a mesh graded
    /// towards its thin tip.
    #[test]
    fn refinement_grades_the_mesh() {
        let scene = Scene {
            stiffness: Stiffness::Taper { ratio: 0.1 },
            ..Scene::default()
        };
        let mut sh = Shooter::new(
            General::new(&scene.stiffness, &scene.precurvature, 1.0),
            0.0,
            1e-10,
            8,
        );
        let u = [-0.05, 0.3, 0.0];
        let mut passes = 0;
        while sh.shoot::<false>(&u).err > 1.0 {
            assert!(sh.refine());
            passes += 1;
            assert!(passes < 20);
        }
        let n = sh.steps();
        let first = sh.nodes[1] - sh.nodes[0];
        let last = sh.nodes[n] - sh.nodes[n - 1];
        assert!(last < 0.5 * first, "first step {first}, last {last}");
    }
}
