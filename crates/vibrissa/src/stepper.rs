//! The step contract of the marches: a [`Stepper`] predicts and corrects branch points of a
//! contact chain in its family parameter `λ`; the driver loop (module `march`) owns the steps,
//! the events and what is recorded.
//!
//! Two steppers fulfil it on the same chain: the rod's own shooter (module `own`) and any method
//! of crate `bvp` (module `generic`). Each supplies a correction at a given `λ` (natural steps)
//! and a correction on a hyperplane of `(u, λ)` (the fold passage of module `fold`, one loop for
//! both); tangents and the fold test come from the own shooter's exact sensitivities either way.

use crate::arclength::ArcPoint;
use crate::chain::{ContactSet, EvalError, Family};
use crate::rodsolve::ShotFailure;
use crate::search::RootError;
use crate::watch::{Env, Watch};
use bvp::{Solution, Stats};
use nalgebra::DVector;
use std::fmt;

/// A converged point of the branch.
#[derive(Clone, Debug)]
pub(crate) struct Pt {
    /// Family parameter.
    pub lam: f64,
    /// The unknowns of the contact set.
    pub u: Vec<f64>,
    /// Exact tangent `du/dλ`, where the stepper has one.
    pub du: Option<Vec<f64>>,
    /// `det ∂R/∂u` (its sign changes at a fold in `λ`), where the stepper has it.
    pub det: Option<f64>,
    /// Newton iterations it took.
    pub iters: usize,
    /// The whole rod (`params = [f, α]` of the total contact force).
    pub sol: Solution,
    /// What the march watches there.
    pub w: Watch,
    /// The method's own solution, when it is not the rod's own shooter (the generic methods'
    /// stacked segments; their guesses come from it).
    pub raw: Option<Solution>,
}

/// Why a correction was refused.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum StepError {
    /// The corrector landed across a fold in `λ` (`det J` changed sign, and the tangent agrees):
    /// pass or locate it by pseudo-arclength rather than by shorter natural steps.
    CrossedFold,
    /// The own shooter's Newton iteration failed.
    Shot(ShotFailure),
    /// The correction converged where `J` is singular: no tangent.
    NoTangent,
    /// The tangent in `(u, λ)` turned by this many degrees over the step (more than ~30°: the
    /// step was too long for the branch's curvature).
    Turned(f64),
    /// The corrector moved this far from the prediction (another branch).
    Jumped(f64),
    /// The generic method's solve failed.
    Method(Box<bvp::BvpError>),
    /// No method solution to guess from.
    NoPrevious,
    /// The own shooter has no rod at the unknowns it was given (the first point's guess).
    Guess(EvalError),
    /// The own shooter has no rod at the generic method's unknowns.
    Rod(EvalError),
}

impl StepError {
    /// Whether a shorter natural step may succeed (anything but a crossed fold).
    pub fn shorter_may_help(&self) -> bool {
        !matches!(self, StepError::CrossedFold)
    }
    /// Whether the generic method found its Newton matrix singular at its accuracy.
    pub fn singular_method(&self) -> bool {
        matches!(self, StepError::Method(e) if matches!(**e, bvp::BvpError::SingularJacobian { .. }))
    }
}

impl fmt::Display for StepError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            StepError::CrossedFold => f.write_str("the corrector crossed a fold"),
            StepError::Shot(e) => write!(f, "{e}"),
            StepError::NoTangent => f.write_str("singular Jacobian at the solution"),
            StepError::Turned(deg) => write!(f, "the branch turned by {deg:.0}° over the step"),
            StepError::Jumped(corr) => write!(
                f,
                "the corrector moved {corr:.3e} from the prediction (another branch?)"
            ),
            StepError::Method(e) => write!(f, "{e}"),
            StepError::NoPrevious => f.write_str("no previous solution"),
            StepError::Guess(e) => write!(f, "{e:?}"),
            StepError::Rod(e) => write!(f, "the rod at the method's unknowns: {e:?}"),
        }
    }
}

impl From<ShotFailure> for StepError {
    fn from(e: ShotFailure) -> Self {
        StepError::Shot(e)
    }
}

/// Result of the fold passage.
pub(crate) enum Passed {
    /// The branch continues beyond the failed step: its points from there on, in increasing
    /// `λ`, the last one beyond the target or the first where an armed event has ended (never
    /// empty); and the path's last step, to that point (events are located on it where the
    /// branch polynomial in `λ` does not hold them).
    Beyond(Vec<Pt>, Box<Chord>),
    /// `λ` has a maximum along the branch here (with the rod there, if it was found).
    Fold(f64, Option<Box<Pt>>),
    /// Neither.
    Failed(FoldFailure),
}

/// One step of a pseudo-arclength path: from `a` (tangent `ta`) to `b`.
#[derive(Clone, Debug)]
pub(crate) struct Chord {
    pub a: ArcPoint,
    pub ta: DVector<f64>,
    pub b: ArcPoint,
}

/// Why the fold passage neither passed nor located a fold.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum FoldFailure {
    /// A pseudo-arclength step (or the start on the curve) failed.
    Arc(ShotFailure),
    /// The root of `dλ/dσ` between the points that straddle the fold was not found.
    Locating(RootError<ShotFailure>),
    /// The target was not passed within the step budget (the last `λ` reached).
    Budget {
        target: f64,
        steps: usize,
        last: f64,
    },
}

impl fmt::Display for FoldFailure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FoldFailure::Arc(e) => write!(f, "pseudo-arclength: {e}"),
            FoldFailure::Locating(e) => write!(f, "locating the fold: {e}"),
            FoldFailure::Budget {
                target,
                steps,
                last,
            } => write!(
                f,
                "pseudo-arclength did not pass {target} in {steps} steps (last {last})"
            ),
        }
    }
}

/// Prediction and correction of branch points (the method-specific part of a march).
pub(crate) trait Stepper {
    /// The current contact set.
    fn set(&self) -> &ContactSet;
    /// The point at `λ` from the history `hist` (newest last; `λ` ahead of it or inside its
    /// span); rejects corrections that land on another branch. With `fresh` the tangent is exact
    /// at the point (events that use it).
    fn correct(&mut self, lam: f64, hist: &[Pt], fresh: bool) -> Result<Pt, StepError>;
    /// The point at `λ` inside the span of two points `a`, `b` of one branch (the metered
    /// work's midpoints), predicted from their cubic and refused only where it crossed a fold
    /// or jumped ([`within_span`]). Default: [`Stepper::correct`] from the two.
    fn correct_within(&mut self, lam: f64, a: &Pt, b: &Pt) -> Result<Pt, StepError> {
        self.correct(lam, &[a.clone(), b.clone()], true)
    }
    /// The first point of a march at `λ` from the own shooter's converged unknowns `u`.
    fn first(&mut self, lam: f64, u: &[f64]) -> Result<Pt, StepError>;
    /// Changes the contact set at `λ` and corrects `u` (the old state in the new unknowns) there.
    fn switch(&mut self, set: ContactSet, lam: f64, u: Vec<f64>) -> Result<Pt, StepError>;
    /// Sets the family and the march's view for the next phase (a drag's stick and slip).
    fn phase(&mut self, family: Family, env: &Env);
    /// The exact tangent of the contact set `set` at `(u, λ)` on the rod's own shooter, before
    /// the stepper is switched to it.
    fn tangent_in(&mut self, set: &ContactSet, lam: f64, u: &[f64]) -> Option<Vec<f64>>;
    /// Whether the equilibrium of the current set at `(u, λ)` is singular to working precision
    /// (on the rod's own shooter).
    fn singular_at(&mut self, lam: f64, u: &[f64]) -> bool;
    /// Whether `set` (the stepper's set at `(u, λ)`) traps the rod in an equilibrium singular to
    /// working precision: two surface contacts that hold without slip, whose tangential pair
    /// the equilibrium does not determine (the Newton matrix singular there). The start, a
    /// contact that halts, a new contact held at the end of a straight stretch and a drag's
    /// stick after a slip all ask this.
    fn trapped_singular(&mut self, set: &ContactSet, lam: f64, u: &[f64]) -> bool {
        crate::watch::traps(set) && self.singular_at(lam, u)
    }
    /// The elastic energy of the rod at `(u, λ)` (on the rod's own shooter).
    fn energy(&mut self, u: &[f64], lam: f64) -> Option<f64>;
    /// Whether the points made from now on may leave out the free parts' clearance
    /// ([`crate::watch::watch`]'s `light`; an event search of the contacts). Default: ignored,
    /// every point whole.
    fn set_light(&mut self, _light: bool) {}
    /// Whether the corrector takes one more Newton step from an iterate within its residual's
    /// tolerance whose correction is still large (`rodsolve::large_correction`): an event's
    /// search that ended on a jump of its function between such iterates and corrected ones
    /// is searched again so. Default: ignored (the generic methods' solvers).
    fn set_polish(&mut self, _polish: bool) {}
    /// Whether a point whose prediction needed a second chord step gets the exact Jacobian at
    /// its solution, for its tangent (`rodsolve::Flags::retangent`). Default: ignored.
    fn set_retangent(&mut self, _retangent: bool) {}
    /// Sets the meter its points' watches are made for (the works' integrands, a lying
    /// stretch's friction work among them), `None` without one; the march's is the one
    /// [`Stepper::phase`] set. Default: ignored.
    fn set_meter(&mut self, _meter: Option<crate::surface::Meter>) {}
    /// The point `p` with its whole watch where it was made light: the same values as a point
    /// made whole, read on the shot of the same state (the one the shooter still holds, else
    /// the state shot again on the meshes as they are). Default: `p`.
    fn complete(&mut self, p: Pt) -> Result<Pt, StepError> {
        Ok(p)
    }
    /// The rate `dg/dλ` of the free parts' clearance `g` ([`crate::watch::Watch::clear`]) along
    /// the branch at the converged point `p`: `g` on the rod of the tangent's prediction a short
    /// way on, against `p`'s. `None` where the stepper has no tangent, or the prediction's rod or
    /// clearance is not a number. Default: `None` (no forecast).
    fn clear_rate(&mut self, _p: &Pt) -> Option<f64> {
        None
    }
    /// Work done so far.
    fn stats(&self) -> Stats;
    /// Largest natural step in `λ`.
    fn h_max(&self) -> f64;
    /// Whether it solves a set with a stretch lying on the surface (module `chain`, `Lying`): the
    /// rod's own shooter. Default: no.
    fn lies(&self) -> bool {
        false
    }
    /// The foot at `λ`: its x in the lab frame (for along-surface anchors) and its support's
    /// clockwise turn.
    fn foot(&self, lam: f64) -> (f64, f64);
    /// The method's own last solution of a one-segment chain (the tip alone touches): the rod on
    /// `[0, 1]` with `params = [f, α]`; `None` on the rod's own shooter.
    fn method_solution(&self) -> Option<Solution> {
        None
    }
    /// The Newton tolerance of the fold passage's corrections.
    fn corrector_tol(&self) -> f64;
    /// Whether the run was asked to stop (its configuration's [`crate::Cancel`]).
    fn cancelled(&self) -> bool;
    /// The newest point as the start of a pseudo-arclength path.
    fn arc_start(&mut self, last: &Pt, tol: f64) -> Result<ArcPoint, ShotFailure>;
    /// The point of the branch on the hyperplane `normal·(v − pred) = 0` of `v = (u, λ)`, from
    /// the prediction `pred` next to the converged point `near`.
    fn on_plane(
        &mut self,
        near: &ArcPoint,
        pred: &DVector<f64>,
        normal: &DVector<f64>,
        tol: f64,
        max_iter: usize,
    ) -> Result<ArcPoint, ShotFailure>;
    /// A converged point of a pseudo-arclength path as a branch point.
    fn arc_point(&mut self, a: &ArcPoint) -> Result<Pt, StepError>;
    /// The branch between the points of `hist` as a polynomial in `λ` (from their exact
    /// tangents): `(u, du/dλ)` at `λ`.
    fn interpolant(&self, hist: &[Pt], lam: f64) -> Option<(Vec<f64>, Vec<f64>)> {
        hist.iter()
            .all(|p| p.du.is_some())
            .then(|| interpolate(hist, lam))
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
            return Err(StepError::Turned(cos.clamp(-1.0, 1.0).acos().to_degrees()));
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
        return Err(StepError::Jumped(corr));
    }
    Ok(())
}

/// Whether the point `p` (predicted at `pred`) inside the span of the branch points `a`, `b`
/// is on their branch: `det J` has their sign, and the correction is small against the
/// change over the span. The tangent's turn is not asked: an accepted step may span a place
/// where the branch turns fast and smoothly (where a lying stretch's end runs along the
/// surface, `μ` rose by 0.01 within 1e-4 of d and the tangent turned 32° from a midpoint to
/// the span's end 1e-4 away).
pub(crate) fn within_span(a: &Pt, b: &Pt, pred: &[f64], p: &Pt, tol: f64) -> Result<(), StepError> {
    if let Some(d) = p.det {
        if [a.det, b.det]
            .iter()
            .flatten()
            .any(|e| e.signum() != d.signum())
        {
            return Err(StepError::CrossedFold);
        }
    }
    let corr = max_diff(&p.u, pred);
    let scale = 1.0 + p.u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if !(corr <= 0.5 * max_diff(&a.u, &b.u) || corr < tol.max(1e-9) * scale) {
        return Err(StepError::Jumped(corr));
    }
    Ok(())
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
}

/// Predictor from the last (at most three) points to `λ`: the Hermite polynomial through their
/// values and tangents (degree 5 with three points) where all have tangents, else Lagrange; and
/// its derivative.
pub(crate) fn interpolate(hist: &[Pt], lam: f64) -> (Vec<f64>, Vec<f64>) {
    let m = hist.len().min(3);
    let pts = &hist[hist.len() - m..];
    let hermite = pts.iter().all(|p| p.du.is_some());
    let n = pts[pts.len() - 1].u.len();
    let (mut u, mut du) = (vec![0.0; n], vec![0.0; n]);
    for i in 0..n {
        // divided differences, nodes newest first (confluent pairs with tangents)
        let mut z = [0.0; 6];
        let mut q = [[0.0; 6]; 6];
        let mut len = 0;
        for p in pts.iter().rev() {
            let reps = if hermite { 2 } else { 1 };
            for r in 0..reps {
                z[len] = p.lam;
                q[len][0] = p.u[i];
                if r == 1 {
                    q[len][1] = p.du.as_ref().map_or(0.0, |du| du[i]);
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
            dw = dw * (lam - z[k]) + w;
            w *= lam - z[k];
        }
        u[i] = v;
        du[i] = dv;
    }
    (u, du)
}
