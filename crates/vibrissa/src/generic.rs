//! The march on a generic method of crate `bvp` (multiple shooting, Lobatto collocation): the
//! contact chain as an ordinary two-point problem, each loaded segment `[s_{k−1}, s_k]` mapped to
//! `σ ∈ [0, 1]` and stacked into one state of `4L` components, the contact unknowns (forces, arc
//! lengths) as the problem's parameters:
//!
//! ```text
//!     dz_k/dσ = ℓ_k F(z_k, s_{k−1} + ℓ_k σ; G_k),   ℓ_k = s_k − s_{k−1}
//!     z_1(0) at the foot,  z_k(1) = z_{k+1}(0),  each contact's conditions at z_k(1),  m_L(1) = 0
//! ```
//!
//! The same conditions as the rod's own shooter (`chain::conditions`), so the methods solve the
//! same problem; tangents and the fold test come from one shot of the own shooter at the
//! method's unknowns.

use crate::arclength::ArcPoint;
use crate::chain::{conditions, Chain, ContactSet, Family};
use crate::config::{Engine, SolverConfig};
use crate::control::{corrector_tol, GENERIC_H_MAX};
use crate::profile::Profile;
use crate::rodsolve::ShotFailure;
use crate::shooter::{rhs, Shooter};
use crate::stepper::{interpolate, same_branch, Pt, StepError, Stepper};
use crate::watch::{fill_slip, has_slider, watch, Env, RodView};
use crate::VibrissaError;
use bvp::continuation::{Arclength, Member, ParamBvp};
use bvp::{BvpSolver, Dims, Guess, Solution, Stats};
use nalgebra::DVector;
use std::f64::consts::FRAC_PI_2;

/// The contact chain in family `family` as a `bvp` problem with parameter `λ`.
#[derive(Clone, Debug)]
pub(crate) struct ChainBvp<P: Profile> {
    pub profile: P,
    pub compliance: f64,
    pub set: ContactSet,
    pub family: Family,
}

impl<P: Profile> ChainBvp<P> {
    /// Loaded segments (one when nothing touches).
    fn segs(&self) -> usize {
        self.set.contacts.len().max(1)
    }
    /// The contacts' unknowns `u` (with `m(0)` in front) from the parameters.
    fn u_of(&self, m0: f64, p: &[f64]) -> Vec<f64> {
        let mut u = Vec::with_capacity(p.len() + 1);
        u.push(m0);
        u.extend_from_slice(p);
        u
    }
    /// Segment bounds and forces at `u`.
    fn layout(&self, u: &[f64]) -> (Vec<f64>, Vec<[f64; 2]>) {
        let set = &self.set;
        let mut bounds = vec![0.0];
        let mut forces = Vec::new();
        for j in 0..set.contacts.len() {
            bounds.push(set.s_of(j, u));
            let o = set.offset(j);
            forces.push(set.contacts[j].force(u[o], u[o + 1]));
        }
        if set.contacts.is_empty() {
            bounds.push(1.0);
        }
        let mut g = vec![[0.0; 2]; self.segs()];
        for k in 0..set.contacts.len() {
            for f in &forces[k..] {
                g[k][0] += f[0];
                g[k][1] += f[1];
            }
        }
        (bounds, g)
    }
}

impl<P: Profile> ParamBvp for ChainBvp<P> {
    fn dims(&self) -> Dims {
        Dims {
            n: 4 * self.segs(),
            k: self.set.n() - 1,
        }
    }
    fn interval(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn rhs(&self, sigma: f64, z: &[f64], p: &[f64], _lam: f64, dz: &mut [f64]) {
        let u = self.u_of(0.0, p);
        let (bounds, g) = self.layout(&u);
        for k in 0..self.segs() {
            let (a, b) = (bounds[k], bounds[k + 1]);
            let len = b - a;
            let s = a + len * sigma;
            let (bb, kk) = if P::UNIFORM {
                (1.0, 0.0)
            } else {
                (self.profile.b(s), self.profile.k0(s))
            };
            let y = [z[4 * k], z[4 * k + 1], z[4 * k + 2], z[4 * k + 3]];
            let d = rhs::<4>(&y, g[k][0], g[k][1], bb, kk);
            for i in 0..4 {
                dz[4 * k + i] = len * d[i];
            }
        }
    }
    fn bc(&self, za: &[f64], zb: &[f64], p: &[f64], lam: f64, res: &mut [f64]) {
        let (pose, dpose) = self.family.pose(lam);
        let u = self.u_of(za[3], p);
        let c = self.compliance;
        res[0] = za[0];
        res[1] = za[1];
        res[2] = za[2] - (FRAC_PI_2 - pose.theta + c * za[3]);
        let mut row = 3;
        let nseg = self.segs();
        for k in 0..nseg - 1 {
            for i in 0..4 {
                res[row] = zb[4 * k + i] - za[4 * (k + 1) + i];
                row += 1;
            }
        }
        let set = &self.set;
        for (j, ct) in set.contacts.iter().enumerate() {
            let z = [zb[4 * j], zb[4 * j + 1], zb[4 * j + 2], zb[4 * j + 3]];
            let o = set.offset(j);
            let cs = conditions(ct, &z, &u[o..o + ct.unknowns()], &pose, &dpose, 0.0);
            for i in 0..cs.rows {
                res[row] = cs.val[i];
                row += 1;
            }
        }
        res[row] = zb[4 * (nseg - 1) + 3];
    }
    fn rhs_jacobian(
        &self,
        sigma: f64,
        z: &[f64],
        p: &[f64],
        _lam: f64,
        dfdz: &mut [f64],
        dfdp: &mut [f64],
        dfdl: &mut [f64],
    ) -> bool {
        let set = &self.set;
        let n = 4 * self.segs();
        let k = p.len();
        let u = self.u_of(0.0, p);
        let (bounds, g) = self.layout(&u);
        dfdz.fill(0.0);
        dfdp.fill(0.0);
        dfdl.fill(0.0);
        for seg in 0..self.segs() {
            let (a, b) = (bounds[seg], bounds[seg + 1]);
            let len = b - a;
            let s = a + len * sigma;
            let (bb, kk) = if P::UNIFORM {
                (1.0, 0.0)
            } else {
                (self.profile.b(s), self.profile.k0(s))
            };
            let o = 4 * seg;
            let (sp, cp) = z[o + 2].sin_cos();
            let m = z[o + 3];
            let (gx, gy) = (g[seg][0], g[seg][1]);
            // ∂F/∂z, scaled by the segment's length
            dfdz[(o) * n + o + 2] = -len * sp;
            dfdz[(o + 1) * n + o + 2] = len * cp;
            dfdz[(o + 2) * n + o + 3] = len * bb;
            dfdz[(o + 3) * n + o + 2] = len * (gx * cp + gy * sp);
            // the forces of the contacts from this segment on: m' = Gx sin φ − Gy cos φ
            for j in seg..set.contacts.len() {
                let ct = &set.contacts[j];
                let q = set.offset(j) - 1;
                let t = ct.t();
                for (col, fx, fy) in [(q, -ct.n[0], -ct.n[1]), (q + 1, t[0], t[1])] {
                    dfdp[(o + 3) * k + col] += len * (fx * sp - fy * cp);
                }
            }
            // the ends of the segment: ℓ and s = a + ℓσ move with them
            let f = [cp, sp, kk + bb * m, gx * sp - gy * cp];
            let (db, dk) = self.profile.slopes(s);
            let fs = [0.0, 0.0, dk + db * m, 0.0];
            let mut end = |j: usize, dl: f64, ds: f64| {
                if set.contacts[j].tip {
                    return;
                }
                let col = set.offset(j) + 1;
                for i in 0..4 {
                    dfdp[(o + i) * k + col] += dl * f[i] + len * fs[i] * ds;
                }
            };
            if seg < set.contacts.len() {
                // b = s_seg: ∂ℓ/∂b = 1, ∂s/∂b = σ
                end(seg, 1.0, sigma);
            }
            if seg > 0 {
                // a = s_{seg−1}: ∂ℓ/∂a = −1, ∂s/∂a = 1 − σ
                end(seg - 1, -1.0, 1.0 - sigma);
            }
        }
        true
    }
    fn bc_jacobian(
        &self,
        za: &[f64],
        zb: &[f64],
        p: &[f64],
        lam: f64,
        dga: &mut [f64],
        dgb: &mut [f64],
        dgp: &mut [f64],
        dgl: &mut [f64],
    ) -> bool {
        let (pose, dpose) = self.family.pose(lam);
        let set = &self.set;
        let n = 4 * self.segs();
        let k = p.len();
        let u = self.u_of(za[3], p);
        dga.fill(0.0);
        dgb.fill(0.0);
        dgp.fill(0.0);
        dgl.fill(0.0);
        let c = self.compliance;
        dga[0] = 1.0;
        dga[n + 1] = 1.0;
        dga[2 * n + 2] = 1.0;
        dga[2 * n + 3] = -c;
        dgl[2] = dpose.theta;
        let mut row = 3;
        let nseg = self.segs();
        for seg in 0..nseg - 1 {
            for i in 0..4 {
                dgb[row * n + 4 * seg + i] = 1.0;
                dga[row * n + 4 * (seg + 1) + i] = -1.0;
                row += 1;
            }
        }
        for (j, ct) in set.contacts.iter().enumerate() {
            let z = [zb[4 * j], zb[4 * j + 1], zb[4 * j + 2], zb[4 * j + 3]];
            let o = set.offset(j);
            let cs = conditions(ct, &z, &u[o..o + ct.unknowns()], &pose, &dpose, 0.0);
            for i in 0..cs.rows {
                for q in 0..4 {
                    dgb[row * n + 4 * j + q] = cs.dz[i][q];
                }
                for q in 0..ct.unknowns() {
                    dgp[row * k + o - 1 + q] = cs.down[i][q];
                }
                dgl[row] = cs.dlam[i];
                row += 1;
            }
        }
        dgb[row * n + 4 * (nseg - 1) + 3] = 1.0;
        true
    }
}

/// `∂R/∂u` and `∂R/∂λ` of the own shooter.
type Jacobians = (nalgebra::DMatrix<f64>, nalgebra::DVector<f64>);

/// The stepper on a generic method of crate `bvp`.
pub(crate) struct GenericStepper<P: Profile> {
    pub bvp: ChainBvp<P>,
    pub engine: Engine,
    pub env: Env,
    pub stats: Stats,
    /// The own shooter's chain: tangents, `det J`, the unloaded rest of the rod.
    pub chain: Chain<P>,
    /// The method's last solution.
    last: Option<Solution>,
    cancel: crate::config::Cancel,
}

// the solver's own error, passed through unboxed as crate `bvp` returns it
#[allow(clippy::result_large_err)]
impl<P: Profile> GenericStepper<P> {
    /// A stepper of `cfg`'s method on the chain of `set` in `family`.
    pub fn new(
        profile: P,
        compliance: f64,
        set: ContactSet,
        family: Family,
        env: Env,
        cfg: &SolverConfig,
    ) -> Result<Self, VibrissaError> {
        Ok(GenericStepper {
            bvp: ChainBvp {
                profile: profile.clone(),
                compliance,
                set: set.clone(),
                family,
            },
            engine: Engine::with_max_iter(cfg, 12)?,
            env,
            stats: Stats::default(),
            chain: Chain::new(
                Shooter::with_steps(profile, compliance, cfg.tol.min(1e-8), 8),
                set,
                family,
            ),
            last: None,
            cancel: cfg.cancel.clone(),
        })
    }

    /// The method's solve at `λ` from `guess`.
    fn solve_at(&mut self, lam: f64, guess: &Guess) -> Result<Solution, StepError> {
        let problem = Member::new(&self.bvp, lam);
        solve_counted(&mut self.engine, &mut self.stats, &problem, guess).map_err(StepError::Method)
    }

    /// The first point: the method's solve at `λ` from the shooter's rod at the unknowns `u`.
    fn start_at(&mut self, lam: f64, u: &[f64]) -> Result<Pt, StepError> {
        // the own shooter's rod as the guess
        self.chain.eval(u, lam, false).map_err(StepError::Guess)?;
        let guess = self.stacked_guess(u);
        let sol = self.solve_at(lam, &guess)?;
        self.point(lam, sol)
    }

    /// The method's own last solution when it is one segment (the tip alone touches): the rod on
    /// `[0, 1]` with `params = [f, α]` of the contact force.
    fn own_solution(&self) -> Option<Solution> {
        let sol = self.last.as_ref()?;
        if sol.n != 4 {
            return None;
        }
        let u = self.bvp.u_of(sol.left()[3], &sol.params);
        let f = self.chain.total_force(&u);
        let mut s = sol.clone();
        s.params = crate::chain::polar(f, self.bvp.set.contacts.first().map(|c| c.n)).to_vec();
        Some(s)
    }

    /// The stacked guess of the shooter's last rod at `u` (segment by segment on `σ`).
    fn stacked_guess(&mut self, u: &[f64]) -> Guess {
        let nseg = self.bvp.segs();
        let (bounds, _) = self.bvp.layout(u);
        let nodes = 41;
        let mesh: Vec<f64> = (0..nodes).map(|i| i as f64 / (nodes - 1) as f64).collect();
        let mut z = vec![0.0; 4 * nseg * nodes];
        for (i, &sig) in mesh.iter().enumerate() {
            for k in 0..nseg {
                let s = bounds[k] + (bounds[k + 1] - bounds[k]) * sig;
                // inside segment k of the last shot: its own path
                let zz = self.chain.sh.state_at(k, s);
                z[4 * nseg * i + 4 * k..4 * nseg * i + 4 * k + 4].copy_from_slice(&zz);
            }
        }
        Guess {
            n: 4 * nseg,
            mesh,
            z,
            dz: None,
            params: u[1..].to_vec(),
        }
    }

    /// `∂R/∂u` and `∂R/∂λ` of the own shooter at the method's unknowns `u` (its meshes refined
    /// until the shot is within tolerance, at most 8 times); `None` where they are not known.
    fn own_jacobians(&mut self, u: &[f64], lam: f64) -> Result<Option<Jacobians>, StepError> {
        let mut ev = None;
        for _ in 0..8 {
            match self.chain.eval(u, lam, true) {
                Ok(e) if e.err > 1.0 => {
                    if !self.chain.refine() {
                        break;
                    }
                }
                Ok(e) => {
                    ev = Some(e);
                    break;
                }
                Err(e) => return Err(StepError::Rod(e)),
            }
        }
        Ok(ev.and_then(|e| e.jac.zip(e.r_lam)))
    }

    /// The branch point of the method's solution `sol` at `λ`: the whole rod (the method's
    /// segments, then the unloaded rest by the own shooter), the tangent and `det J` from one
    /// shot with sensitivities.
    fn point(&mut self, lam: f64, sol: Solution) -> Result<Pt, StepError> {
        let u = self.bvp.u_of(sol.left()[3], &sol.params);
        let (du, det) = match self.own_jacobians(&u, lam)? {
            Some((j, l)) => {
                let det = j.determinant();
                let du = j
                    .lu()
                    .solve(&(-l))
                    .map(|x| x.iter().copied().collect::<Vec<_>>());
                (du.filter(|d| d.iter().all(|v| v.is_finite())), Some(det))
            }
            None => (None, None),
        };
        let path = self.path_of(&u, &sol);
        let xf = self.bvp.family.pose(lam).0.xf;
        let (bounds, _) = self.bvp.layout(&u);
        let nseg = self.bvp.segs();
        let chain = &self.chain;
        let profile = &self.bvp.profile;
        let mut exact = |s: f64| -> [f64; 4] {
            let k = bounds[1..].partition_point(|&b| b < s);
            if k >= nseg {
                return chain.state_at(s);
            }
            let (a, b) = (bounds[k], bounds[k + 1]);
            let sig = if b > a { (s - a) / (b - a) } else { 0.0 };
            let mut zz = vec![0.0; sol.n];
            sol.eval(sig, &mut zz);
            [zz[4 * k], zz[4 * k + 1], zz[4 * k + 2], zz[4 * k + 3]]
        };
        let mut w = watch(
            &self.env,
            &self.bvp.set,
            lam,
            &u,
            du.as_deref(),
            RodView {
                sol: &path,
                xf,
                exact: &mut exact,
                kappa: &|s, m| profile.kappa(s, m),
                straight: profile.straight(),
            },
            false,
        );
        if let (true, Some(d)) = (has_slider(&self.bvp.set), du.as_deref()) {
            let foot = self.bvp.family.pose(lam).1.xf;
            if let Some(r) = self.chain.contact_rates(&u, lam, d) {
                fill_slip(&mut w, &self.bvp.set, (&u, d), &r, foot);
            }
        }
        self.last = Some(sol.clone());
        Ok(Pt {
            lam,
            u,
            du,
            det,
            iters: sol.stats.newton_iters,
            sol: path,
            w,
            raw: Some(sol),
        })
    }

    /// The whole rod: the method's segments mapped to `s`, then the unloaded rest (the own
    /// shooter's last evaluation at the same unknowns).
    fn path_of(&mut self, u: &[f64], sol: &Solution) -> Solution {
        let nseg = self.bvp.segs();
        let (bounds, g) = self.bvp.layout(u);
        let (mut mesh, mut z, mut dz) = (Vec::new(), Vec::new(), Vec::new());
        for k in 0..nseg {
            let (a, b) = (bounds[k], bounds[k + 1]);
            let len = b - a;
            for (i, &sig) in sol.mesh.iter().enumerate() {
                let s = a + len * sig;
                let zk = [
                    sol.z[sol.n * i + 4 * k],
                    sol.z[sol.n * i + 4 * k + 1],
                    sol.z[sol.n * i + 4 * k + 2],
                    sol.z[sol.n * i + 4 * k + 3],
                ];
                let (bb, kk) = if P::UNIFORM {
                    (1.0, 0.0)
                } else {
                    (self.bvp.profile.b(s), self.bvp.profile.k0(s))
                };
                mesh.push(s);
                z.extend_from_slice(&zk);
                dz.extend_from_slice(&rhs::<4>(&zk, g[k][0], g[k][1], bb, kk));
            }
        }
        let own = self.chain.path(u);
        let s_end = bounds[nseg];
        if s_end < 1.0 {
            let first = own.mesh.partition_point(|&s| s < s_end);
            // the rest beyond the last contact, skipping its first node (the contact itself)
            for i in first + 1..own.mesh.len() {
                mesh.push(own.mesh[i]);
                z.extend_from_slice(own.node(i));
                dz.extend_from_slice(&own.dz[4 * i..4 * i + 4]);
            }
        }
        Solution {
            n: 4,
            mesh,
            z,
            dz,
            params: own.params,
            status: bvp::Status::Converged,
            stats: sol.stats.clone(),
            dense: bvp::Dense::Hermite,
        }
    }

    /// Lagrange inter-/extrapolation in `λ` of the method's solutions of the (at most three)
    /// nearest points of `hist`, on the mesh of the newest one, with the parameters `params`.
    fn guess_at(hist: &[Pt], lam: f64, params: Vec<f64>) -> Option<Guess> {
        let newest = hist.last()?.raw.as_ref()?;
        let mut idx: Vec<usize> = (0..hist.len())
            .filter(|&i| hist[i].raw.as_ref().is_some_and(|r| r.n == newest.n))
            .collect();
        idx.sort_by(|&a, &b| {
            (hist[a].lam - lam)
                .abs()
                .total_cmp(&(hist[b].lam - lam).abs())
        });
        idx.dedup_by(|a, b| hist[*a].lam == hist[*b].lam);
        idx.truncate(3);
        let w: Vec<f64> = idx
            .iter()
            .map(|&i| {
                idx.iter()
                    .filter(|&&j| j != i)
                    .map(|&j| (lam - hist[j].lam) / (hist[i].lam - hist[j].lam))
                    .product()
            })
            .collect();
        let n = newest.n;
        let mesh = newest.mesh.clone();
        let mut z = vec![0.0; n * mesh.len()];
        let mut buf = vec![0.0; n];
        for (&i, &wi) in idx.iter().zip(&w) {
            let r = hist[i].raw.as_ref()?;
            for (node, &s) in mesh.iter().enumerate() {
                r.eval(s, &mut buf);
                for j in 0..n {
                    z[node * n + j] += wi * buf[j];
                }
            }
        }
        Some(Guess {
            n,
            mesh,
            z,
            dz: None,
            params,
        })
    }
}

/// `engine`'s solve of `problem` from `guess`, its work added to `stats` (a failed solve's too).
fn solve_counted<B: bvp::Bvp + ?Sized>(
    engine: &mut Engine,
    stats: &mut Stats,
    problem: &B,
    guess: &Guess,
) -> Result<Solution, Box<bvp::BvpError>> {
    let r = engine.solve(problem, guess);
    match &r {
        Ok(s) => stats.accumulate(&s.stats),
        Err(e) => {
            if let Some(st) = e.stats() {
                stats.accumulate(st);
            }
        }
    }
    r.map_err(Box::new)
}

impl<P: Profile> GenericStepper<P> {
    /// The pseudo-arclength corrector as the method's own problem: the chain's conditions plus
    /// `normal·(v − pred) = 0` with `λ` an unknown parameter (crate `bvp`'s [`Arclength`], in its
    /// coordinates `(z(a), z(b), p, λ)`, where `v = (m(0), p, λ)` and `m(0) = z_4(a)`), solved from
    /// the method's solution `base`; the point with the own shooter's Jacobians at its unknowns.
    fn solve_on_plane(
        &mut self,
        base: &Solution,
        pred: &DVector<f64>,
        normal: &DVector<f64>,
    ) -> Result<ArcPoint, ShotFailure> {
        let Dims { n, k } = self.bvp.dims();
        let m = 2 * n + k + 1;
        let (mut tangent, mut anchor) = (vec![0.0; m], vec![0.0; m]);
        // v = (m(0), p, λ) in the coordinates (z(a), z(b), p, λ): m(0) is z_4(a)
        let slots = std::iter::once(3).chain((0..=k).map(|j| 2 * n + j));
        for (i, slot) in slots.enumerate() {
            tangent[slot] = normal[i];
            anchor[slot] = pred[i];
        }
        let method = |e: bvp::BvpError| ShotFailure::Method(Box::new(e));
        let problem = Arclength::new(&self.bvp, tangent, anchor, 1.0).map_err(method)?;
        let guess = Guess {
            n,
            mesh: base.mesh.clone(),
            z: base.z.clone(),
            dz: None,
            params: pred.iter().skip(1).copied().collect(),
        };
        let mut raw = solve_counted(&mut self.engine, &mut self.stats, &problem, &guess)
            .map_err(ShotFailure::Method)?;
        let lam = raw.params[k];
        raw.params.truncate(k);
        let u = self.bvp.u_of(raw.left()[3], &raw.params);
        let (jac, r_lam) = self
            .own_jacobians(&u, lam)
            .ok()
            .flatten()
            .ok_or(ShotFailure::NoRod)?;
        let mut v = DVector::from_vec(u);
        v = v.push(lam);
        Ok(ArcPoint {
            v,
            jac,
            r_lam,
            residual: raw.stats.residual,
            iterations: raw.stats.newton_iters,
            raw: Some(raw),
        })
    }
}

impl<P: Profile> Stepper for GenericStepper<P> {
    fn set(&self) -> &ContactSet {
        &self.bvp.set
    }

    fn correct(&mut self, lam: f64, hist: &[Pt], _fresh: bool) -> Result<Pt, StepError> {
        let (ug, _) = interpolate(hist, lam);
        let g = Self::guess_at(hist, lam, ug[1..].to_vec()).ok_or(StepError::NoPrevious)?;
        let sol = self.solve_at(lam, &g)?;
        let p = self.point(lam, sol)?;
        same_branch(&hist[hist.len() - 1], &ug, &p, self.chain.sh.tol)?;
        Ok(p)
    }

    fn first(&mut self, lam: f64, u: &[f64]) -> Result<Pt, StepError> {
        self.start_at(lam, u)
    }

    fn switch(&mut self, set: ContactSet, lam: f64, u: Vec<f64>) -> Result<Pt, StepError> {
        self.bvp.set = set.clone();
        self.chain.set = set;
        self.start_at(lam, &u)
    }

    fn phase(&mut self, family: Family, env: &Env) {
        self.bvp.family = family;
        self.chain.family = family;
        self.env = env.clone();
    }

    fn tangent_in(&mut self, set: &ContactSet, lam: f64, u: &[f64]) -> Option<Vec<f64>> {
        self.chain.tangent_in(set.clone(), u, lam)
    }

    fn singular_at(&mut self, lam: f64, u: &[f64]) -> bool {
        self.chain.singular_to_precision(u, lam)
    }

    fn energy(&mut self, u: &[f64], lam: f64) -> Option<f64> {
        self.chain.elastic_energy(u, lam)
    }

    fn stats(&self) -> Stats {
        let mut s = self.stats.clone();
        s.accumulate(&self.chain.sh.stats);
        s
    }

    fn h_max(&self) -> f64 {
        GENERIC_H_MAX
    }

    fn foot(&self, lam: f64) -> (f64, f64) {
        let p = self.bvp.family.pose(lam).0;
        (p.xf, p.theta)
    }

    fn method_solution(&self) -> Option<Solution> {
        self.own_solution()
    }

    fn cancelled(&self) -> bool {
        self.cancel.is_set()
    }

    fn corrector_tol(&self) -> f64 {
        corrector_tol(self.chain.sh.tol)
    }

    fn arc_start(&mut self, last: &Pt, _tol: f64) -> Result<ArcPoint, ShotFailure> {
        let raw = last.raw.clone().ok_or(ShotFailure::NoRod)?;
        let (jac, r_lam) = self
            .own_jacobians(&last.u, last.lam)
            .ok()
            .flatten()
            .ok_or(ShotFailure::NoRod)?;
        let mut v = DVector::from_vec(last.u.clone());
        v = v.push(last.lam);
        Ok(ArcPoint {
            v,
            jac,
            r_lam,
            residual: raw.stats.residual,
            iterations: last.iters,
            raw: Some(raw),
        })
    }

    fn on_plane(
        &mut self,
        near: &ArcPoint,
        pred: &DVector<f64>,
        normal: &DVector<f64>,
        _tol: f64,
        _max_iter: usize,
    ) -> Result<ArcPoint, ShotFailure> {
        let base = near.raw.as_ref().ok_or(ShotFailure::NoRod)?;
        self.solve_on_plane(base, pred, normal)
    }

    fn arc_point(&mut self, a: &ArcPoint) -> Result<Pt, StepError> {
        let raw = a.raw.clone().ok_or(StepError::NoPrevious)?;
        self.point(a.lam(), raw)
    }
}
