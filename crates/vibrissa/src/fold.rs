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
use crate::events::{Crossing, LocateError};
use crate::rodsolve::ShotFailure;
use crate::search;
use crate::stepper::{Chord, FoldFailure, Passed, Pt, StepError, Stepper};
use crate::watch::Env;
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

/// Whether the last two points of `hist` put a fold in `λ` within the natural step to
/// `target`. Near a fold `u − u*` goes as `√(λ* − λ)`, so `|du/dλ|⁻²` falls linearly to zero at
/// `λ*`: its extrapolation through the two points' exact tangents is the fold to first order.
/// Where it lies within a failed natural step of a scan (`march::Spec::pass_fold_ahead`), the
/// march takes the passage at once instead of shrinking the step towards the fold (the `√`
/// branch lets only steps of about a quarter of the distance left succeed: the ρ = 0.1 rod's
/// scan crawled 7.4e-4 to its fold in 21 natural steps and 85 Newton iterations, a third of the
/// scan's right-hand sides, where the passage from the first failure takes 26 in all;
/// docs/performance.md).
pub(crate) fn ahead(hist: &[Pt], target: f64) -> bool {
    let [.., a, b] = hist else {
        return false;
    };
    match (&a.du, &b.du) {
        (Some(da), Some(db)) => predicted((a.lam, da), (b.lam, db)).is_some_and(|l| l <= target),
        _ => false,
    }
}

/// The fold `λ*` where `|du/dλ|⁻²` through `(λ_a, du_a)` and `(λ_b, du_b)` (`λ_a < λ_b`) reaches
/// zero, if it falls towards it.
fn predicted((la, da): (f64, &[f64]), (lb, db): (f64, &[f64])) -> Option<f64> {
    let q = |du: &[f64]| 1.0 / du.iter().map(|v| v * v).sum::<f64>();
    let (qa, qb) = (q(da), q(db));
    (lb > la && qa > qb && qb > 0.0).then(|| lb + qb * (lb - la) / (qa - qb))
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
                    let b = arc.last.clone();
                    let chord = Chord {
                        a: prev,
                        ta: tprev,
                        b,
                    };
                    return Ok(Passed::Beyond(pts, Box::new(chord)));
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
        let p = on_chord(&mut *st, (a, ta, b), sigma, tol)?;
        p.tangent(Some(ta))
            .map(|t| t[n])
            .ok_or(ShotFailure::Singular { iteration: 0 })
    };
    let sigma = match search::root(&mut slope, 0.0, span, 1e-14 * (1.0 + span)) {
        Ok(x) => x,
        Err(e) => return Ok(Passed::Failed(FoldFailure::Locating(e))),
    };
    let p = on_chord(&mut *st, (a, ta, b), sigma, tol)?;
    let lam = p.lam();
    let pt = st.arc_point(&p).ok().map(|mut q| {
        // at the fold du/dλ is unbounded: no tangent
        q.du = None;
        q
    });
    Ok(Passed::Fold(lam, pt.map(Box::new)))
}

/// How far above the corrector's tolerance a correction on the fold's chord may stall and still
/// be taken (as [`crate::rodsolve::at_floor`]'s thousand tolerances).
const CHORD_FLOOR: f64 = 1e3;

/// The point of the branch on the chord's hyperplane at `sigma` ([`arclength::between`]); where
/// Newton stalls within [`CHORD_FLOOR`] tolerances it is solved again to that. Why: on a thin
/// tip the residual has a floor that no iteration lowers (~1e-10 on the short rat preset,
/// against the tolerance 1e-12), and there the located fold ended the drag with "Newton did not
/// converge (iteration 2, residual 1.414e-10)" where every point of the path had converged. Only
/// a stalled correction is solved again, so every fold located before is located the same.
fn on_chord(
    st: &mut dyn Stepper,
    (a, ta, b): (&ArcPoint, &DVector<f64>, &ArcPoint),
    sigma: f64,
    tol: f64,
) -> Result<ArcPoint, ShotFailure> {
    match arclength::between(&mut Plane(&mut *st), a, ta, b, sigma, tol) {
        Err(ShotFailure::NoConvergence { residual, .. }) if residual <= CHORD_FLOOR * tol => {
            arclength::between(&mut Plane(st), a, ta, b, sigma, CHORD_FLOOR * tol)
        }
        r => r,
    }
}

/// Where the event `c` ends on the path's step `chord` (holding at its start, ended at its end):
/// Brent's method on the event's value at the branch points on the hyperplanes
/// `ta·(v − a) = σ` between them, as the fold is located. The march's event search interpolates
/// the branch in `λ` through its last points; where the path turned back and forth in `λ` within
/// a step of the fold passage (a short rat preset's drag over 0.001/0.2/2π/3: a slip limit
/// reached 2e-7 past the branch's last natural point, the branch turning by 173° in between)
/// that search failed, and the drag ended as a solver failure.
pub(crate) fn locate_on_chord(
    st: &mut dyn Stepper,
    env: &Env,
    chord: &Chord,
    c: Crossing,
) -> Result<Pt, LocateError> {
    let tol = st.corrector_tol();
    let Chord { a, ta, b } = chord;
    let span = ta.dot(&(&b.v - &a.v));
    let mut at = |sigma: f64| -> Result<Pt, StepError> {
        let q = on_chord(&mut *st, (a, ta, b), sigma, tol)?;
        st.arc_point(&q)
    };
    let mut value = |sigma: f64| at(sigma).map(|p| c.of_watch(env, &p.w));
    let sigma = search::root(&mut value, 0.0, span, 1e-14 * (1.0 + span))?;
    at(sigma).map_err(LocateError::Caller)
}

#[cfg(test)]
mod tests {
    use super::predicted;

    /// On the normal form of a fold, `u = u* ± c·√(λ* − λ)` in every component, the prediction
    /// is the fold itself, from any two points before it; on a branch without a fold (a constant
    /// or shrinking tangent) there is none.
    #[test]
    fn the_fold_of_the_normal_form_is_predicted_exactly() {
        let (star, c) = (0.2082, [0.3, -1.7, 4.0]);
        let du = |l: f64| c.map(|ci| -ci / (2.0 * (star - l).sqrt()));
        for (la, lb) in [(0.1, 0.2), (0.2075, 0.208), (0.0, 0.2082 - 1e-9)] {
            let got = predicted((la, &du(la)), (lb, &du(lb))).unwrap();
            assert!(
                (got - star).abs() < 1e-12 * (1.0 + (star - la)),
                "{la} {lb}: {got}"
            );
        }
        let flat = [1.0, 2.0, 3.0];
        assert_eq!(predicted((0.1, &flat), (0.2, &flat)), None);
        assert_eq!(predicted((0.1, &flat), (0.2, &[0.5, 1.0, 1.5])), None);
        assert_eq!(predicted((0.2, &du(0.2)), (0.1, &du(0.1))), None);
    }
}
