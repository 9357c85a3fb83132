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

/// Whether an event of the march has ended at a branch point (the fold passage hands its path
/// back there: the march locates the event between the path's points).
pub(crate) type Ended<'a> = &'a mut dyn FnMut(&Pt) -> bool;

/// Follows the branch from the newest point of `hist` until `λ` passes `target` (or reaches
/// `lam_end`) or the branch turns back, or an event has `ended` at a point of a long path.
pub(crate) fn pass(
    st: &mut dyn Stepper,
    hist: &[Pt],
    (target, lam_end): (f64, f64),
    ended: Ended<'_>,
) -> Passed {
    match follow(st, hist, (target, lam_end), &FOLD_STEPS, ended) {
        Ok(p) => p,
        Err(e) => Passed::Failed(FoldFailure::Arc(e)),
    }
}

/// The path's lengths at which [`follow`] asks whether an event has ended (at the 8th, 16th,
/// 32nd … point: a passage of a few steps pays nothing, a long one a watch per doubling).
fn asks_at(k: usize) -> bool {
    k >= 8 && k.is_power_of_two()
}

fn follow(
    st: &mut dyn Stepper,
    hist: &[Pt],
    (target, lam_end): (f64, f64),
    ctl: &FoldSteps,
    ended: Ended<'_>,
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
    let mut path = Vec::new();
    for _ in 0..ctl.max_steps {
        let (prev, tprev) = arc.step(&mut Plane(st))?;
        path.push(arc.last.clone());
        if arc.tau[n] <= 0.0 && tprev[n] > 0.0 {
            return locate_fold(st, &prev, &tprev, &arc.last, tol);
        }
        if arc.last.lam() > target || arc.last.lam() >= lam_end {
            return beyond(st, path, target, lam_end);
        }
        // a branch far steeper in u than in λ (a rod trapped between a sliding contact and one
        // that holds: its force pair changes by ~1e8 per unit slide) can take thousands of steps
        // to the target, through an event that ends the state long before it (the held
        // contact's slip limit)
        if asks_at(path.len()) && st.arc_point(&arc.last).is_ok_and(|q| ended(&q)) {
            return Ok(Passed::Beyond(upto_event(st, path)));
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

/// The path's points as branch points up to a point where an event ended (the last): those
/// with a tangent, for the march to step through and locate the event on.
fn upto_event(st: &mut dyn Stepper, path: Vec<ArcPoint>) -> Vec<Pt> {
    path.iter()
        .filter_map(|a| st.arc_point(a).ok())
        .filter(|q| q.du.is_some())
        .collect()
}

/// The path's points as branch points, the last one beyond `target` (or at `lam_end`). A point
/// without a tangent cannot be interpolated through: left out, unless it is that last one.
fn beyond(
    st: &mut dyn Stepper,
    path: Vec<ArcPoint>,
    target: f64,
    lam_end: f64,
) -> Result<Passed, ShotFailure> {
    let mut pts = Vec::with_capacity(path.len());
    for a in path {
        match st.arc_point(&a) {
            Ok(q) if q.du.is_some() => pts.push(q),
            _ if a.lam() > target || a.lam() >= lam_end => {
                return Err(ShotFailure::Singular { iteration: 0 })
            }
            _ => {}
        }
    }
    Ok(Passed::Beyond(pts))
}
