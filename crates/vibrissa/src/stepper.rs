//! The [`Stepper`]s of the march.
//!
//! - [`OwnStepper`]: the rod's own shooter on the contact chain ([`crate::chain`]) for every
//!   profile and contact set: quintic Hermite predictor through the last three points and their
//!   exact tangents `u' = −J⁻¹ ∂R/∂λ`, chord Newton. A sign change of `det J` between neighbours
//!   means the corrector crossed a fold: rejected, and passed or located by pseudo-arclength.
//! - [`GenericStepper`] (module `generic`): any method of crate `bvp` (multiple shooting,
//!   collocation) on the same chain, its points' tangents from the shooter.

use crate::arclength::{self, Arc, Steps};
use crate::chain::{Chain, ContactSet};
use crate::config::NEWTON_TOL_MAX;
use crate::march::{interpolate, Passed, Pt, StepError, Stepper};
use crate::profile::Profile;
use crate::rodsolve::{correct_chord, Converged, ShotFailure};
use crate::search;
use crate::watch::{watch, Env, RodView};
use bvp::Stats;

/// Newton iterations per point before a natural step is given up.
const MAX_ITER: usize = 12;

/// The stepper on the rod's own shooter.
pub(crate) struct OwnStepper<P: Profile> {
    pub chain: Chain<P>,
    pub env: Env,
}

/// The Newton tolerance of the marches' corrector for the integration tolerance `tol`.
///
/// The chord iteration converges linearly: stopping it at a hundredth of `tol` keeps Newton's
/// share of the error below the discretization's and the contact conditions (a point on the
/// surface, a side tangent to it) to ~1e-12 at the default tolerance, so that no row has the
/// rod beyond the surface by more than that. And never above 1e-9: the predictor extrapolates
/// the last points and the branch checks compare corrections with the change over a step, so a
/// point left with a residual of 1e-4 is noise that shrinking steps amplify (the paper scan at
/// tol 1e-3 stopped at d = 0.16 with steps of 1e-7 and "corrections" of 4).
/// And never below 1e-15: residuals of order one carry rounding of ~1e-16, which no iteration
/// removes (the press's first point at tol 5e-15 stalled at 1.1e-16 against 5e-17).
pub(crate) fn corrector_tol(tol: f64) -> f64 {
    (0.01 * tol).clamp(NEWTON_TOL_MIN, NEWTON_TOL_MAX)
}

/// The smallest Newton tolerance: a few units of rounding on residuals of order one.
const NEWTON_TOL_MIN: f64 = 1e-15;

impl<P: Profile> OwnStepper<P> {
    /// The branch point of a converged solve at `λ` (the shooter's paths hold it).
    pub(crate) fn point(&mut self, lam: f64, cv: Converged) -> Result<Pt, StepError> {
        let du = cv.tangent();
        let det = cv.det();
        let sol = self.chain.path(&cv.u);
        let xf = self.chain.family.pose(lam).0.xf;
        let chain = &self.chain;
        let w = watch(
            &self.env,
            &chain.set,
            lam,
            &cv.u,
            du.as_deref(),
            RodView {
                sol: &sol,
                xf,
                exact: &mut |s| chain.state_at(s),
                kappa: &|s, m| chain.sh.profile.kappa(s, m),
                straight: chain.sh.profile.straight(),
            },
        );
        Ok(Pt {
            lam,
            u: cv.u,
            du,
            det: Some(det),
            iters: cv.iterations,
            sol,
            w,
            raw: None,
        })
    }

    /// The point at `λ` from the prediction `u`.
    pub(crate) fn correct_from(
        &mut self,
        lam: f64,
        u: &[f64],
        newest: Option<&Pt>,
        fresh: bool,
    ) -> Result<Pt, StepError> {
        let tol = corrector_tol(self.chain.sh.tol);
        let cv = correct_chord(&mut self.chain, lam, u, tol, MAX_ITER, fresh)
            .map_err(|e| e.to_string())?;
        let p = self.point(lam, cv)?;
        if p.du.is_none() {
            return Err(StepError::Failed(
                "singular Jacobian at the solution".into(),
            ));
        }
        if let Some(last) = newest {
            same_branch(last, u, &p, self.chain.sh.tol)?;
        }
        Ok(p)
    }

    /// Pseudo-arclength from the newest point until the branch passes `target` (or `lam_end`) or
    /// turns back in `λ`; the fold is located as the root of `dλ/dσ` between the two points that
    /// straddle it.
    fn follow(&mut self, hist: &[Pt], target: f64, lam_end: f64) -> Result<Passed, ShotFailure> {
        let tol = corrector_tol(self.chain.sh.tol);
        let last = &hist[hist.len() - 1];
        let start = arclength::at_lambda(&mut self.chain, &last.u, last.lam, tol, 16)?;
        let steps = Steps {
            ds: 1e-3,
            ds_min: 1e-10,
            ds_max: 0.05,
        };
        let mut arc = Arc::new(start, 1.0, steps, tol)?;
        let n = last.u.len();
        let mut path = Vec::new();
        for _ in 0..5000 {
            let (prev, tprev) = arc.step(&mut self.chain)?;
            path.push(arc.last.clone());
            if arc.tau[n] <= 0.0 && tprev[n] > 0.0 {
                let b = arc.last.clone();
                let span = tprev.dot(&(&b.v - &prev.v));
                let ch = &mut self.chain;
                let mut slope = |sigma: f64| -> Result<f64, String> {
                    let p = arclength::between(ch, &prev, &tprev, &b, sigma, tol)
                        .map_err(|e| e.to_string())?;
                    p.tangent(Some(&tprev))
                        .map(|t| t[n])
                        .ok_or_else(|| "singular tangent".to_string())
                };
                let sigma = match search::root(&mut slope, 0.0, span, 1e-14 * (1.0 + span)) {
                    Ok(x) => x,
                    Err(e) => {
                        return Ok(Passed::Failed(format!("locating the fold: {e}")));
                    }
                };
                let p = arclength::between(&mut self.chain, &prev, &tprev, &b, sigma, tol)?;
                let lam = p.lam();
                let pt = self.point(lam, p.converged()).ok().map(|mut q| {
                    // at the fold du/dλ is unbounded: no tangent
                    q.du = None;
                    q
                });
                return Ok(Passed::Fold(lam, pt.map(Box::new)));
            }
            if arc.last.lam() > target || arc.last.lam() >= lam_end {
                let mut pts = Vec::with_capacity(path.len());
                for a in path {
                    // (a point without a tangent cannot be interpolated through: left out,
                    // unless it is the one beyond the target)
                    match self.point(a.lam(), a.converged()) {
                        Ok(q) if q.du.is_some() => pts.push(q),
                        _ if a.lam() > target || a.lam() >= lam_end => {
                            return Err(ShotFailure::Singular { iteration: 0 })
                        }
                        _ => {}
                    }
                }
                return Ok(Passed::Beyond(pts));
            }
        }
        Ok(Passed::Failed(format!(
            "pseudo-arclength did not pass {target} in 5000 steps (last {})",
            arc.last.lam()
        )))
    }
}

/// Whether the corrected point `p` (predicted at `pred`) continues the branch from `last`: `det J`
/// keeps its sign (else the step crossed a fold), the tangent in `(u, λ)` turned by less than
/// ~30° (else the step was too long for the branch's curvature), and the correction is small
/// against the change over the step (else it jumped to another branch).
pub(crate) fn same_branch(last: &Pt, pred: &[f64], p: &Pt, tol: f64) -> Result<(), StepError> {
    if let (Some(d0), Some(d1)) = (last.det, p.det) {
        if d0.signum() != d1.signum() {
            return Err(StepError::CrossedFold);
        }
    }
    if let (Some(a), Some(b)) = (&last.du, &p.du) {
        let unit = |t: &[f64]| {
            let n = (t.iter().map(|v| v * v).sum::<f64>() + 1.0).sqrt();
            let mut v: Vec<f64> = t.iter().map(|x| x / n).collect();
            v.push(1.0 / n);
            v
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
    // (a correction within the discretization's own tolerance is noise: meshes refined between
    // points move the discrete solution by that much)
    if !(corr <= 0.5 * change.max(1e-3 * scale * (p.lam - last.lam).abs().min(1.0))
        || corr < tol.max(1e-9) * scale)
    {
        return Err(StepError::Failed(format!(
            "the corrector moved {corr:.3e} from the prediction (another branch?)"
        )));
    }
    Ok(())
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
}

impl<P: Profile> Stepper for OwnStepper<P> {
    fn set(&self) -> &ContactSet {
        &self.chain.set
    }

    fn correct(&mut self, lam: f64, hist: &[Pt], fresh: bool) -> Result<Pt, StepError> {
        let u = interpolate(hist, lam).0;
        self.correct_from(lam, &u, hist.last(), fresh)
    }

    fn pass_fold(&mut self, hist: &[Pt], target: f64, lam_end: f64) -> Passed {
        match self.follow(hist, target, lam_end) {
            Ok(p) => p,
            Err(e) => Passed::Failed(format!("pseudo-arclength: {e}")),
        }
    }

    fn switch(&mut self, set: ContactSet, lam: f64, u: Vec<f64>) -> Result<Pt, StepError> {
        self.chain.set = set;
        self.correct_from(lam, &u, None, true)
    }

    fn tangent_in(&mut self, set: &ContactSet, lam: f64, u: &[f64]) -> Option<Vec<f64>> {
        self.chain.tangent_in(set.clone(), u, lam)
    }

    fn singular_at(&mut self, lam: f64, u: &[f64]) -> bool {
        self.chain.singular_to_precision(u, lam)
    }

    fn stats(&self) -> Stats {
        self.chain.sh.stats.clone()
    }

    fn h_max(&self) -> f64 {
        0.01
    }

    fn foot_x(&self, lam: f64) -> f64 {
        self.chain.family.pose(lam).0.xf
    }
}
