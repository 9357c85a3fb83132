//! The two [`Stepper`]s of the scan march.
//!
//! - [`OwnStepper`]: the rod's own shooter ([`crate::shooter`]) for every profile: unknowns
//!   `u = (m(0), f, α)`, residual `(m(1), x(1) − (x* − d), y(1) − η)`, quintic Hermite predictor
//!   through the last three points and their exact tangents `u' = −J⁻¹ ∂R/∂d`, chord Newton. A
//!   sign change of `det J` between neighbours means the corrector crossed a fold: rejected.
//! - [`GenericStepper`]: any method of crate `bvp` (multiple shooting, collocation) on the
//!   [`ScanFamily`] problem, predicted by Lagrange extrapolation of the last solutions.
//!
//! Both pass folds in `d` by the pseudo-arclength continuation of crate `bvp`.

use crate::arclength::{self, Arc, Steps, TipLine};
use crate::config::{Engine, NEWTON_TOL_MAX};
use crate::equations::ScanFamily;
use crate::march::{Passed, Pt, StepError, Stepper};
use crate::profile::Profile;
use crate::rodsolve::{correct_chord, ShotFailure, TipCond};
use crate::search;
use crate::shooter::Shooter;
use bvp::continuation::{Continuation, ContinuationOptions, FoldKind};
use bvp::{BvpSolver, Guess, ParamBvp, Solution, Stats};

/// Newton iterations per point before a natural step is given up.
const MAX_ITER: usize = 12;

/// The stepper on the rod's own shooter.
pub(crate) struct OwnStepper<P: Profile> {
    pub shooter: Shooter<P>,
    pub eta: f64,
    pub x_star: f64,
}

impl<P: Profile> OwnStepper<P> {
    /// The point at `d` from the prediction `u`.
    pub(crate) fn correct_from(
        &mut self,
        d: f64,
        u: [f64; 3],
        newest: Option<&Pt>,
    ) -> Result<Pt, StepError> {
        let tol = corrector_tol(self.shooter.tol);
        let cond = TipCond::Pos {
            x1: self.x_star - d,
            y1: self.eta,
        };
        let cv =
            correct_chord(&mut self.shooter, &cond, u, tol, MAX_ITER).map_err(|e| e.to_string())?;
        let du = cv
            .solve([0.0, -1.0, 0.0])
            .ok_or_else(|| StepError::Failed("singular Jacobian at the solution".into()))?;
        let det = cv.det();
        let p = Pt {
            d,
            u: cv.u,
            du: Some(du),
            det: Some(det),
            iters: cv.iterations,
            sol: self.shooter.solution(vec![cv.u[1], cv.u[2]], cv.residual),
        };
        if let Some(last) = newest {
            same_branch(last, &u, &p)?;
        }
        Ok(p)
    }
}

/// The Newton tolerance of the scan's corrector for the integration tolerance `tol`.
///
/// The chord iteration converges linearly: stopping it at a tenth of `tol` keeps Newton's share
/// of the error in `(m(0), f, α)` below the discretization's (at tol 1e-10 the paper scan's μ is
/// off by 9.3e-11 instead of 2.2e-9, for ~1 % more time). And never above 1e-9: the predictor
/// extrapolates the last points and the branch checks compare corrections with the change over
/// a step, so a point left with a residual of 1e-4 is noise that shrinking steps amplify (the
/// paper scan at tol 1e-3 stopped at d = 0.16 with steps of 1e-7 and "corrections" of 4).
pub(crate) fn corrector_tol(tol: f64) -> f64 {
    (0.1 * tol).min(NEWTON_TOL_MAX)
}

/// Whether the corrected point `p` (predicted at `pred`) continues the branch from `last`: `det J`
/// keeps its sign (else the step crossed a fold in `d`), the tangent in `(u, d)` turned by less
/// than ~30° (else the step was too long for the branch's curvature), and the correction is
/// small against the change over the step (else it jumped to another branch).
fn same_branch(last: &Pt, pred: &[f64; 3], p: &Pt) -> Result<(), StepError> {
    if let (Some(d0), Some(d1)) = (last.det, p.det) {
        if d0.signum() != d1.signum() {
            return Err(StepError::CrossedFold);
        }
    }
    if let (Some(a), Some(b)) = (last.du, p.du) {
        let unit = |t: [f64; 3]| {
            let n = (t.iter().map(|v| v * v).sum::<f64>() + 1.0).sqrt();
            [t[0] / n, t[1] / n, t[2] / n, 1.0 / n]
        };
        let (ta, tb) = (unit(a), unit(b));
        let cos: f64 = ta.iter().zip(&tb).map(|(x, y)| x * y).sum();
        if cos < 0.85 {
            return Err(StepError::Failed(format!(
                "the branch turned by {:.0}° over the step",
                cos.clamp(-1.0, 1.0).acos().to_degrees()
            )));
        }
    }
    let corr = max_diff(&p.u, pred);
    let change = max_diff(&p.u, &last.u);
    let scale = 1.0 + p.u.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    if !(corr <= 0.5 * change.max(1e-3 * scale * (p.d - last.d).abs().min(1.0))
        || corr < 1e-9 * scale)
    {
        return Err(StepError::Failed(format!(
            "the corrector moved {corr:.3e} from the prediction (another branch?)"
        )));
    }
    Ok(())
}

impl<P: Profile> OwnStepper<P> {
    /// Pseudo-arclength from the newest point until the branch passes `target` (or `d_end`) or
    /// turns back in `d`; the fold is located as the root of `dd/dσ` between the two points that
    /// straddle it.
    fn follow(&mut self, hist: &[Pt], target: f64, d_end: f64) -> Result<Passed, ShotFailure> {
        let tol = corrector_tol(self.shooter.tol);
        let fam = TipLine {
            x0: self.x_star,
            slope: -1.0,
            y1: self.eta,
        };
        let last = &hist[hist.len() - 1];
        let start = arclength::at_lambda(&mut self.shooter, &fam, last.u, last.d, tol, 16)?;
        let steps = Steps {
            ds: 1e-3,
            ds_min: 1e-10,
            ds_max: 0.05,
        };
        let mut arc = Arc::new(start, 1.0, steps, tol)?;
        for _ in 0..5000 {
            let (prev, tprev) = arc.step(&mut self.shooter, &fam)?;
            if arc.tau[3] <= 0.0 && tprev[3] > 0.0 {
                let b = arc.last.clone();
                let span = tprev.dot(&(b.v - prev.v));
                let sh = &mut self.shooter;
                let mut slope = |sigma: f64| -> Result<f64, String> {
                    let p = arclength::between(sh, &fam, &prev, &tprev, &b, sigma, tol)
                        .map_err(|e| e.to_string())?;
                    p.tangent(Some(&tprev))
                        .map(|t| t[3])
                        .ok_or_else(|| "singular tangent".to_string())
                };
                let sigma = match search::root(&mut slope, 0.0, span, 1e-14 * (1.0 + span)) {
                    Ok(x) => x,
                    Err(e) => {
                        return Ok(Passed::Failed(format!("locating the fold in d: {e}")));
                    }
                };
                let p = arclength::between(sh, &fam, &prev, &tprev, &b, sigma, tol)?;
                let sol = self.shooter.solution(vec![p.v[1], p.v[2]], p.residual);
                return Ok(Passed::Fold(p.lam(), Some(sol)));
            }
            if arc.last.lam() > target || arc.last.lam() >= d_end {
                let p = &arc.last;
                let cv = p.converged();
                let du = cv
                    .solve([0.0, -1.0, 0.0])
                    .ok_or(ShotFailure::Singular { iteration: 0 })?;
                return Ok(Passed::Beyond(Pt {
                    d: p.lam(),
                    u: cv.u,
                    du: Some(du),
                    det: Some(cv.det()),
                    iters: p.iterations,
                    sol: self.shooter.solution(vec![cv.u[1], cv.u[2]], cv.residual),
                }));
            }
        }
        Ok(Passed::Failed(format!(
            "pseudo-arclength did not pass d = {target} in 5000 steps (last d = {})",
            arc.last.lam()
        )))
    }
}

fn max_diff(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
}

impl<P: Profile> Stepper for OwnStepper<P> {
    fn correct(&mut self, d: f64, hist: &[Pt]) -> Result<Pt, StepError> {
        self.correct_from(d, predict(hist, d), hist.last())
    }

    fn pass_fold(&mut self, hist: &[Pt], target: f64, d_end: f64) -> Passed {
        match self.follow(hist, target, d_end) {
            Ok(p) => p,
            Err(e) => Passed::Failed(format!("pseudo-arclength in d: {e}")),
        }
    }

    fn stats(&self) -> Stats {
        self.shooter.stats.clone()
    }

    fn h_max(&self) -> f64 {
        0.01
    }

    fn interpolant(&self, hist: &[Pt], d: f64) -> Option<([f64; 3], [f64; 3])> {
        hist.iter()
            .all(|p| p.du.is_some())
            .then(|| interpolate(hist, d))
    }
}

/// Predictor from the last (at most three) points to `d`: the Hermite polynomial through their
/// values and tangents (degree 5 with three points) where all have tangents, else Lagrange.
pub(crate) fn predict(hist: &[Pt], d: f64) -> [f64; 3] {
    interpolate(hist, d).0
}

/// The polynomial of [`predict`] and its derivative at `d`.
pub(crate) fn interpolate(hist: &[Pt], d: f64) -> ([f64; 3], [f64; 3]) {
    let m = hist.len().min(3);
    let pts = &hist[hist.len() - m..];
    let hermite = pts.iter().all(|p| p.du.is_some());
    let (mut u, mut du) = ([0.0; 3], [0.0; 3]);
    for i in 0..3 {
        // divided differences, nodes newest first (confluent pairs with tangents)
        let mut z = [0.0; 6];
        let mut q = [[0.0; 6]; 6];
        let mut len = 0;
        for p in pts.iter().rev() {
            let reps = if hermite { 2 } else { 1 };
            for r in 0..reps {
                z[len] = p.d;
                q[len][0] = p.u[i];
                if r == 1 {
                    q[len][1] = p.du.map_or(0.0, |du| du[i]);
                } else if len > 0 {
                    q[len][1] = (q[len][0] - q[len - 1][0]) / (z[len] - z[len - 1]);
                }
                len += 1;
            }
        }
        for k in 2..len {
            for j in k..len {
                q[j][k] = (q[j][k - 1] - q[j - 1][k - 1]) / (z[j] - z[j - k]);
            }
        }
        // Newton form and its derivative (product rule on the nested factors)
        let (mut v, mut dv, mut w, mut dw) = (0.0, 0.0, 1.0, 0.0);
        for k in 0..len {
            v += q[k][k] * w;
            dv += q[k][k] * dw;
            dw = dw * (d - z[k]) + w;
            w *= d - z[k];
        }
        u[i] = v;
        du[i] = dv;
    }
    (u, du)
}

/// The stepper on a generic method of crate `bvp`. Its points get their tangents `du/dd` from the
/// rod's own shooter (one shot with sensitivities at the converged unknowns), so its predictor,
/// its branch check and the event location work as on the own stepper, whatever the method.
pub(crate) struct GenericStepper<P: Profile> {
    pub family: ScanFamily<P>,
    pub engine: Engine,
    pub stats: Stats,
    /// The shooter that gives the tangents.
    pub tangents: Shooter<P>,
}

// the solver's own error, passed through unboxed as crate `bvp` returns it
#[allow(clippy::result_large_err)]
impl<P: Profile> GenericStepper<P> {
    fn solve(&mut self, d: f64, guess: &Guess) -> Result<Solution, bvp::BvpError> {
        let r = self
            .engine
            .solve(&bvp::continuation::Member::new(&self.family, d), guess);
        match &r {
            Ok(s) => self.stats.accumulate(&s.stats),
            Err(e) => {
                if let Some(st) = e.stats() {
                    self.stats.accumulate(st);
                }
            }
        }
        r
    }

    /// The point at `d` from `guess`.
    pub fn point(&mut self, d: f64, guess: &Guess) -> Result<Pt, String> {
        let sol = self.solve(d, guess).map_err(|e| e.to_string())?;
        Ok(self.pt(d, sol))
    }

    /// The branch point of a converged solution, with its tangent where the shooter resolves it.
    fn pt(&mut self, d: f64, sol: Solution) -> Pt {
        let u = [sol.left()[3], sol.params[0], sol.params[1]];
        let (du, det) = match self.tangent(d, &u) {
            Some((du, det)) => (Some(du), Some(det)),
            None => (None, None),
        };
        Pt {
            d,
            u,
            du,
            det,
            iters: sol.stats.newton_iters,
            sol,
        }
    }

    /// `du/dd = −J⁻¹ ∂R/∂d` and `det J` from one shot with sensitivities at `u` (on a mesh within
    /// the tolerance).
    fn tangent(&mut self, d: f64, u: &[f64; 3]) -> Option<([f64; 3], f64)> {
        let cond = TipCond::Pos {
            x1: self.family.x_star - d,
            y1: self.family.eta,
        };
        for _ in 0..8 {
            let shot = self.tangents.shoot::<true>(u);
            if shot.err > 1.0 {
                if !self.tangents.refine() {
                    return None;
                }
                continue;
            }
            let j = cond.jacobian(&shot.y1);
            let du = j.lu().solve(&nalgebra::Vector3::new(0.0, -1.0, 0.0))?;
            let du = [du[0], du[1], du[2]];
            return du
                .iter()
                .all(|v| v.is_finite())
                .then(|| (du, j.determinant()));
        }
        None
    }

    /// Lagrange inter-/extrapolation in `d` of the (at most three) nearest points, on the mesh of
    /// the newest one.
    fn guess_at(&self, hist: &[Pt], d: f64) -> Guess {
        let mut idx: Vec<usize> = (0..hist.len()).collect();
        idx.sort_by(|&a, &b| (hist[a].d - d).abs().total_cmp(&(hist[b].d - d).abs()));
        idx.truncate(3);
        let newest = &hist[hist.len() - 1].sol;
        let w: Vec<f64> = idx
            .iter()
            .map(|&i| {
                idx.iter()
                    .filter(|&&j| j != i)
                    .map(|&j| (d - hist[j].d) / (hist[i].d - hist[j].d))
                    .product()
            })
            .collect();
        let n = newest.n;
        let mesh = newest.mesh.clone();
        let mut z = vec![0.0; n * mesh.len()];
        let mut buf = vec![0.0; n];
        for (&i, &wi) in idx.iter().zip(&w) {
            for (node, &s) in mesh.iter().enumerate() {
                hist[i].sol.eval(s, &mut buf);
                for j in 0..n {
                    z[node * n + j] += wi * buf[j];
                }
            }
        }
        let mut params = vec![0.0; newest.params.len()];
        for (&i, &wi) in idx.iter().zip(&w) {
            for (p, &q) in params.iter_mut().zip(&hist[i].sol.params) {
                *p += wi * q;
            }
        }
        let mut dz = vec![0.0; z.len()];
        for (node, &s) in mesh.iter().enumerate() {
            self.family.rhs(
                s,
                &z[node * n..(node + 1) * n],
                &params,
                d,
                &mut dz[node * n..(node + 1) * n],
            );
        }
        Guess {
            n,
            mesh,
            z,
            dz: Some(dz),
            params,
        }
    }
}

impl<P: Profile> Stepper for GenericStepper<P> {
    fn correct(&mut self, d: f64, hist: &[Pt]) -> Result<Pt, StepError> {
        let mut g = self.guess_at(hist, d);
        // with tangents the unknowns come from the Hermite predictor
        let ug = match self.interpolant(hist, d) {
            Some((u, _)) => {
                g.params = vec![u[1], u[2]];
                u
            }
            None => [g.z[3], g.params[0], g.params[1]],
        };
        let p = self.point(d, &g)?;
        same_branch(&hist[hist.len() - 1], &ug, &p)?;
        Ok(p)
    }

    fn pass_fold(&mut self, hist: &[Pt], target: f64, d_end: f64) -> Passed {
        let last = &hist[hist.len() - 1];
        let d = last.d;
        let copts = ContinuationOptions {
            ds: 1e-3,
            ds_min: 1e-9,
            ds_max: 0.05,
            max_steps: 2000,
            lambda_min: -0.25,
            lambda_max: d_end,
            detect_folds: true,
            fold_tol: 1e-10,
            history: 4,
            ..ContinuationOptions::default()
        };
        let mut stats = Stats::default();
        let mut beyond = None;
        let result = (|| {
            let mut cont =
                match Continuation::new(&self.family, &mut self.engine, last.sol.clone(), d, copts)
                {
                    Ok(c) => c,
                    Err(e) => return Passed::Failed(e.to_string()),
                };
            let _ = cont.next(); // the start, already converged
            let mut prev = d;
            for item in cont.by_ref() {
                let bp = match item {
                    Ok(bp) => bp,
                    Err(e) => return Passed::Failed(format!("pseudo-arclength: {e}")),
                };
                stats.accumulate(&bp.stats);
                if let Some(f) = bp.fold {
                    if f.kind == FoldKind::Max {
                        return Passed::Fold(f.lambda, Some(f.solution));
                    }
                }
                if bp.lambda < prev {
                    return Passed::Fold(prev, None);
                }
                prev = bp.lambda;
                if bp.lambda > target || bp.on_bound {
                    beyond = Some((bp.lambda, bp.solution));
                    return Passed::Failed(String::new());
                }
            }
            Passed::Failed(format!(
                "pseudo-arclength continuation did not pass d = {target} (last d = {prev})"
            ))
        })();
        self.stats.accumulate(&stats);
        match beyond {
            Some((d, sol)) => Passed::Beyond(self.pt(d, sol)),
            None => result,
        }
    }

    fn stats(&self) -> Stats {
        let mut s = self.stats.clone();
        s.accumulate(&self.tangents.stats);
        s
    }

    fn h_max(&self) -> f64 {
        0.05
    }

    fn interpolant(&self, hist: &[Pt], d: f64) -> Option<([f64; 3], [f64; 3])> {
        hist.iter()
            .all(|p| p.du.is_some())
            .then(|| interpolate(hist, d))
    }
}
