//! The fold passage: where natural steps in `λ` fail for tiny steps (near a fold in `λ`, or on a
//! branch too steep for them next to a bifurcation), the branch is followed by pseudo-arclength
//! in `v = (u, λ)` from the newest point until `λ` passes the target — its points are handed
//! back to the march — or turns back: a fold, located as the root of `τ_λ = dλ/dσ` (whose sign
//! is that of `det J`) between the two points that straddle it, by Brent's method on
//! corrections along the chord between them.
//!
//! One loop for every stepper: each supplies only its correction on the hyperplane
//! `τ·(v − v_pred) = 0` ([`Stepper::on_plane`]: the bordered Newton of the rod's own shooter, or
//! a generic method's solve of the same problem with `λ` as an unknown parameter) and turns a
//! converged point into a branch point; tangents come from the own shooter's exact Jacobians.

use crate::arclength::{self, Arc, ArcPoint, OnPlane, Steps};
use crate::control::{FoldSteps, FOLD_STEPS};
use crate::rodsolve::ShotFailure;
use crate::search;
use crate::stepper::{FoldFailure, Passed, Pt, Stepper};
use nalgebra::DVector;

/// A stepper seen as the corrector of a pseudo-arclength path.
struct Plane<'s>(&'s mut dyn Stepper);

impl OnPlane for Plane<'_> {
    fn on_plane(
        &mut self,
        near: &ArcPoint,
        pred: &DVector<f64>,
        normal: &DVector<f64>,
        tol: f64,
        max_iter: usize,
    ) -> Result<ArcPoint, ShotFailure> {
        self.0.on_plane(near, pred, normal, tol, max_iter)
    }
}

/// Follows the branch from the newest point of `hist` until `λ` passes `target` (or reaches
/// `lam_end`), the branch turns back, or a branch point satisfies `done` (an event of the march
/// ended there: the march locates it in the step that ends at that point and never takes the
/// points beyond, so they are not made; a slip's slide that μk ends after 4e-10 was followed
/// for 792 points to its natural step's 5e-7, 1090 Newton iterations a slip).
pub(crate) fn pass(
    st: &mut dyn Stepper,
    hist: &[Pt],
    (target, lam_end): (f64, f64),
    done: &dyn Fn(&Pt) -> bool,
) -> Passed {
    match follow(st, hist, (target, lam_end), done, &FOLD_STEPS) {
        Ok(p) => p,
        Err(e) => Passed::Failed(FoldFailure::Arc(e)),
    }
}

/// The path's points as branch points, each made as it is reached; the last one beyond
/// `target` (or at `lam_end`) or the first that is `done`. A point without a tangent cannot be
/// interpolated through: left out, unless it is the last one beyond `target`.
fn follow(
    st: &mut dyn Stepper,
    hist: &[Pt],
    (target, lam_end): (f64, f64),
    done: &dyn Fn(&Pt) -> bool,
    ctl: &FoldSteps,
) -> Result<Passed, ShotFailure> {
    let tol = st.corrector_tol();
    let last = &hist[hist.len() - 1];
    let start = st.arc_start(last, tol)?;
    let steps = Steps {
        ds: ctl.ds,
        ds_min: ctl.ds_min,
        ds_max: ctl.ds_max,
    };
    let mut arc = Arc::new(start, 1.0, steps, tol)?;
    let n = last.u.len();
    let mut pts = Vec::new();
    for _ in 0..ctl.max_steps {
        let (prev, tprev) = arc.step(&mut Plane(st))?;
        if arc.tau[n] <= 0.0 && tprev[n] > 0.0 {
            return locate_fold(st, &prev, &tprev, &arc.last, tol);
        }
        let past = arc.last.lam() > target || arc.last.lam() >= lam_end;
        match st.arc_point(&arc.last) {
            Ok(q) if q.du.is_some() => {
                let stop = past || done(&q);
                pts.push(q);
                if stop {
                    return Ok(Passed::Beyond(pts));
                }
            }
            _ if past => return Err(ShotFailure::Singular { iteration: 0 }),
            _ => {}
        }
    }
    Ok(Passed::Failed(FoldFailure::Budget {
        target,
        steps: ctl.max_steps,
        last: arc.last.lam(),
    }))
}

/// The fold between the path's points `a` (tangent `ta`, `τ_λ > 0`) and `b` (`τ_λ ≤ 0`): the root
/// of `τ_λ` along the chord, and the rod there (without a tangent: `du/dλ` is unbounded).
fn locate_fold(
    st: &mut dyn Stepper,
    a: &ArcPoint,
    ta: &DVector<f64>,
    b: &ArcPoint,
    tol: f64,
) -> Result<Passed, ShotFailure> {
    let n = a.n();
    let span = ta.dot(&(&b.v - &a.v));
    let mut slope = |sigma: f64| -> Result<f64, ShotFailure> {
        let p = arclength::between(&mut Plane(&mut *st), a, ta, b, sigma, tol)?;
        p.tangent(Some(ta))
            .map(|t| t[n])
            .ok_or(ShotFailure::Singular { iteration: 0 })
    };
    let sigma = match search::root(&mut slope, 0.0, span, 1e-14 * (1.0 + span)) {
        Ok(x) => x,
        Err(e) => return Ok(Passed::Failed(FoldFailure::Locating(e))),
    };
    let p = arclength::between(&mut Plane(&mut *st), a, ta, b, sigma, tol)?;
    let lam = p.lam();
    let pt = st.arc_point(&p).ok().map(|mut q| {
        // at the fold du/dλ is unbounded: no tangent
        q.du = None;
        q
    });
    Ok(Passed::Fold(lam, pt.map(Box::new)))
}
