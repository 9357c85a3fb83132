//! Pseudo-arclength continuation on the rod's own shooter, for every curve `R(u, λ) = 0` of a
//! contact chain (the foot dragged, turned, the surface pressed) or of the rod itself (the
//! homotopy from the uniform straight rod).
//!
//! The curve is followed in `v = (u, λ)`: Euler predictor along the unit tangent `τ` (the null
//! vector of `[J  R_λ]` by cofactors, oriented like the last one), Newton corrector on the
//! hyperplane `τ·(v − v_pred) = 0` with the bordered Jacobian (nalgebra LU), step control by the
//! corrector's iterations and the turn of the tangent. The same corrector with the hyperplane
//! normal `e_λ` solves one member at a given `λ`, and with the normal of a step it parametrizes
//! the curve between two points (where events are located). A fold in `λ` is where `τ_λ` (whose
//! sign is that of `det J`) changes sign.

use crate::chain::Curve;
use crate::rodsolve::{at_floor, max_abs, Converged, ShotFailure};
use crate::shooter::MAX_STEPS;
use bvp::Solution;
use nalgebra::{DMatrix, DVector};

/// A converged point of a curve.
#[derive(Clone, Debug)]
pub(crate) struct ArcPoint {
    /// `(u, λ)`.
    pub v: DVector<f64>,
    /// `∂R/∂u` there.
    pub jac: DMatrix<f64>,
    /// `∂R/∂λ` there.
    pub r_lam: DVector<f64>,
    /// Max-norm of `R`.
    pub residual: f64,
    /// Newton iterations it took.
    pub iterations: usize,
    /// The method's own solution there, when a generic method of crate `bvp` corrected it
    /// (`None` on the rod's own shooter).
    pub raw: Option<Solution>,
}

impl ArcPoint {
    /// Number of unknowns.
    pub fn n(&self) -> usize {
        self.v.len() - 1
    }
    /// The unknowns `u`.
    pub fn u(&self) -> Vec<f64> {
        self.v.iter().take(self.n()).copied().collect()
    }
    /// The family parameter.
    pub fn lam(&self) -> f64 {
        self.v[self.n()]
    }
    /// As a converged solve at fixed `λ`.
    pub fn converged(&self) -> Converged {
        Converged {
            u: self.u(),
            jac: self.jac.clone(),
            r_lam: self.r_lam.clone(),
            residual: self.residual,
            iterations: self.iterations,
        }
    }
    /// A converged solve as a point at `lam`.
    pub fn from_converged(c: &Converged, lam: f64) -> ArcPoint {
        let n = c.u.len();
        let mut v = DVector::zeros(n + 1);
        for (i, x) in c.u.iter().enumerate() {
            v[i] = *x;
        }
        v[n] = lam;
        ArcPoint {
            v,
            jac: c.jac.clone(),
            r_lam: c.r_lam.clone(),
            residual: c.residual,
            iterations: c.iterations,
            raw: None,
        }
    }
    /// The unit tangent, oriented along `along` (or with `dλ > 0` when `along` is `None`).
    pub fn tangent(&self, along: Option<&DVector<f64>>) -> Option<DVector<f64>> {
        let t = null_vector(&self.jac, &self.r_lam)?;
        let flip = match along {
            Some(d) => t.dot(d) < 0.0,
            None => t[self.n()] < 0.0,
        };
        Some(if flip { -t } else { t })
    }
}

/// The unit null vector of `[J  r]` (n × (n + 1)) by cofactors: `τ_i = (−1)^i det` of the matrix
/// without column `i`; `τ_λ` has the sign of `det J`.
pub(crate) fn null_vector(jac: &DMatrix<f64>, r_lam: &DVector<f64>) -> Option<DVector<f64>> {
    let n = jac.nrows();
    let full = {
        let mut m = DMatrix::zeros(n, n + 1);
        m.view_mut((0, 0), (n, n)).copy_from(jac);
        m.set_column(n, r_lam);
        m
    };
    let mut t = DVector::zeros(n + 1);
    for skip in 0..=n {
        let cols: Vec<usize> = (0..=n).filter(|&c| c != skip).collect();
        let minor = full.select_columns(cols.iter());
        // the sign puts det J on the λ component: τ_λ = (−1)^n · (−1)^n det J
        let sign = if (n + skip) % 2 == 0 { 1.0 } else { -1.0 };
        t[skip] = sign * minor.determinant();
    }
    let norm = t.norm();
    if !(norm > 0.0 && norm.is_finite()) {
        return None;
    }
    Some(t / norm)
}

/// Newton on `R(v) = 0`, `normal·(v − v_pred) = 0` from `v_pred` to `|R| ≤ tol` with every step
/// error of the shot within tolerance; the shooter's paths hold the point afterwards.
pub(crate) fn correct<C: Curve + ?Sized>(
    cv: &mut C,
    v_pred: &DVector<f64>,
    normal: &DVector<f64>,
    tol: f64,
    max_iter: usize,
) -> Result<ArcPoint, ShotFailure> {
    let n = cv.n();
    for _pass in 0..16 {
        let mut v = v_pred.clone();
        let mut rn_prev = f64::INFINITY;
        let mut refined = false;
        let mut last_step = f64::INFINITY;
        for it in 0..=max_iter {
            let u: Vec<f64> = v.iter().take(n).copied().collect();
            let lam = v[n];
            let e = cv
                .eval(&u, lam, true)
                .map_err(|why| ShotFailure::NoRodAt { iteration: it, why })?;
            let (jac, r_lam) = match (e.jac, e.r_lam) {
                (Some(j), Some(l)) => (j, l),
                _ => return Err(ShotFailure::Singular { iteration: it }),
            };
            let rn = max_abs(&e.r);
            if !rn.is_finite() || !r_lam.iter().all(|x| x.is_finite()) {
                return Err(ShotFailure::NoConvergence {
                    iteration: it,
                    residual: rn,
                });
            }
            if rn <= tol || at_floor(rn, tol, last_step, &u) {
                if e.err > 1.0 {
                    // a coarse mesh can have spurious solutions: refine, start over
                    if !cv.refine() {
                        return Err(ShotFailure::MeshLimit { steps: MAX_STEPS });
                    }
                    refined = true;
                    break;
                }
                return Ok(ArcPoint {
                    v,
                    jac,
                    r_lam,
                    residual: rn,
                    iterations: it,
                    raw: None,
                });
            }
            // a corrector that does not contract is off the curve: the caller shortens the step
            if it == max_iter || (it >= 2 && rn > 0.5 * rn_prev) {
                return Err(ShotFailure::NoConvergence {
                    iteration: it,
                    residual: rn,
                });
            }
            rn_prev = rn;
            let mut m = DMatrix::zeros(n + 1, n + 1);
            m.view_mut((0, 0), (n, n)).copy_from(&jac);
            m.view_mut((0, n), (n, 1)).copy_from(&r_lam);
            m.set_row(n, &normal.transpose());
            let mut rhs = DVector::zeros(n + 1);
            for i in 0..n {
                rhs[i] = -e.r[i];
            }
            rhs[n] = -normal.dot(&(&v - v_pred));
            let dv = m
                .lu()
                .solve(&rhs)
                .filter(|x| x.iter().all(|c| c.is_finite()))
                .ok_or(ShotFailure::Singular { iteration: it })?;
            cv.count_iteration();
            last_step = dv.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            v += dv;
        }
        if !refined {
            break;
        }
    }
    Err(ShotFailure::MeshLimit { steps: MAX_STEPS })
}

/// What a pseudo-arclength path corrects on: the point of a curve `R(u, λ) = 0` on the
/// hyperplane `normal·(v − pred) = 0` of `v = (u, λ)`, from the prediction `pred` next to the
/// converged point `near` (a generic method starts its solve from `near`'s solution).
pub(crate) trait OnPlane {
    /// The corrected point.
    fn on_plane(
        &mut self,
        near: &ArcPoint,
        pred: &DVector<f64>,
        normal: &DVector<f64>,
        tol: f64,
        max_iter: usize,
    ) -> Result<ArcPoint, ShotFailure>;
}

impl<C: Curve + ?Sized> OnPlane for C {
    fn on_plane(
        &mut self,
        _near: &ArcPoint,
        pred: &DVector<f64>,
        normal: &DVector<f64>,
        tol: f64,
        max_iter: usize,
    ) -> Result<ArcPoint, ShotFailure> {
        correct(self, pred, normal, tol, max_iter)
    }
}

/// The member at `λ = lam` from the prediction `u`.
pub(crate) fn at_lambda<C: Curve + ?Sized>(
    cv: &mut C,
    u: &[f64],
    lam: f64,
    tol: f64,
    max_iter: usize,
) -> Result<ArcPoint, ShotFailure> {
    let n = u.len();
    let mut v = DVector::zeros(n + 1);
    for (i, x) in u.iter().enumerate() {
        v[i] = *x;
    }
    v[n] = lam;
    let mut normal = DVector::zeros(n + 1);
    normal[n] = 1.0;
    correct(cv, &v, &normal, tol, max_iter)
}

/// Step-size settings of [`Arc`].
#[derive(Clone, Copy, Debug)]
pub(crate) struct Steps {
    pub ds: f64,
    pub ds_min: f64,
    pub ds_max: f64,
}

/// A followed curve: the last point and its tangent, the step size.
pub(crate) struct Arc {
    pub last: ArcPoint,
    pub tau: DVector<f64>,
    pub steps: Steps,
    pub tol: f64,
}

/// Corrector iterations per arclength step.
const ARC_ITER: usize = 8;

impl Arc {
    /// Starts at the converged point `p`, heading towards `dλ` of the sign of `dir`.
    pub fn new(p: ArcPoint, dir: f64, steps: Steps, tol: f64) -> Result<Arc, ShotFailure> {
        let mut tau = p
            .tangent(None)
            .ok_or(ShotFailure::Singular { iteration: 0 })?;
        if dir < 0.0 {
            tau = -tau;
        }
        Ok(Arc {
            last: p,
            tau,
            steps,
            tol,
        })
    }

    /// Starts at `p` heading along `tau` (any orientation the caller chose).
    pub fn along(p: ArcPoint, tau: DVector<f64>, steps: Steps, tol: f64) -> Arc {
        Arc {
            last: p,
            tau,
            steps,
            tol,
        }
    }

    /// One accepted step along the curve (the step size shrinks on failures and grows after easy
    /// steps); returns the previous point and its tangent.
    pub fn step<C: OnPlane + ?Sized>(
        &mut self,
        cv: &mut C,
    ) -> Result<(ArcPoint, DVector<f64>), ShotFailure> {
        loop {
            let ds = self.steps.ds;
            let pred = &self.last.v + &self.tau * ds;
            let attempt = cv
                .on_plane(&self.last, &pred, &self.tau, self.tol, ARC_ITER)
                .and_then(|p| {
                    let t = p
                        .tangent(Some(&self.tau))
                        .ok_or(ShotFailure::Singular { iteration: 0 })?;
                    Ok((p, t))
                });
            match attempt {
                // the tangent turned by less than ~25° and the corrector moved less than a third
                // of the step: the same branch, resolved
                Ok((p, t)) if t.dot(&self.tau) > 0.9 && (&p.v - &pred).norm() < 0.3 * ds => {
                    let it = p.iterations;
                    let prev = std::mem::replace(&mut self.last, p);
                    let tprev = std::mem::replace(&mut self.tau, t);
                    if it <= 2 {
                        self.steps.ds = (ds * 2.0).min(self.steps.ds_max);
                    } else if it <= 4 {
                        self.steps.ds = (ds * 1.25).min(self.steps.ds_max);
                    }
                    return Ok((prev, tprev));
                }
                other => {
                    if ds * 0.5 < self.steps.ds_min {
                        return Err(match other {
                            Err(e) => e,
                            // the tangent kept turning: no resolvable branch here
                            Ok(_) => ShotFailure::Unresolved { ds },
                        });
                    }
                }
            }
            self.steps.ds = ds * 0.5;
        }
    }
}

/// The point between `a` (tangent `ta`) and `b` at arclength `sigma` along `ta` from `a`
/// (`0 ≤ sigma ≤ ta·(b − a)`), predicted linearly between them.
pub(crate) fn between<C: OnPlane + ?Sized>(
    cv: &mut C,
    a: &ArcPoint,
    ta: &DVector<f64>,
    b: &ArcPoint,
    sigma: f64,
    tol: f64,
) -> Result<ArcPoint, ShotFailure> {
    let span = ta.dot(&(&b.v - &a.v));
    let w = if span != 0.0 { sigma / span } else { 0.0 };
    let pred = &a.v + (&b.v - &a.v) * w;
    // the hyperplane ta·(v − a) = sigma through the prediction
    let shifted = &pred + ta * (sigma - ta.dot(&(&pred - &a.v)));
    cv.on_plane(a, &shifted, ta, tol, 2 * ARC_ITER)
}

/// Why [`follow_to`] did not reach its member.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum FollowError {
    /// The curve turns back (a fold) before `to`: the furthest `λ` it reached.
    TurnedBack { reached: f64 },
    /// A step failed at `λ`.
    Step { at: f64, reason: String },
}

impl std::fmt::Display for FollowError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            FollowError::TurnedBack { reached } => {
                write!(f, "the curve turns back at {reached} (a fold)")
            }
            FollowError::Step { at, reason } => write!(f, "at {at}: {reason}"),
        }
    }
}

/// Follows `cv` by pseudo-arclength from its converged point `first` (at `λ = from`) until `λ`
/// passes `to`, and returns the member at `to`.
pub(crate) fn follow_to<C: Curve + ?Sized>(
    cv: &mut C,
    first: ArcPoint,
    to: f64,
    tol: f64,
) -> Result<ArcPoint, FollowError> {
    let from = first.lam();
    if to == from {
        return Ok(first);
    }
    let span = (to - from).abs();
    let steps = Steps {
        ds: 0.1 * span,
        ds_min: 1e-7 * span,
        ds_max: 0.25 * span,
    };
    let dir = (to - from).signum();
    let step_err = |at: f64, e: ShotFailure| FollowError::Step {
        at,
        reason: e.to_string(),
    };
    let mut arc = Arc::new(first, dir, steps, tol).map_err(|e| step_err(from, e))?;
    let mut reached = from;
    for _ in 0..2000 {
        let (prev, _) = arc.step(cv).map_err(|e| step_err(arc.last.lam(), e))?;
        let (l0, l1) = (prev.lam(), arc.last.lam());
        if (l1 - reached) * dir > 0.0 {
            reached = l1;
        }
        if (l1 - to) * dir >= 0.0 {
            // the member at `to`, from the chord between the points on either side
            let w = (to - l0) / (l1 - l0);
            let (a, b) = (prev.u(), arc.last.u());
            let u: Vec<f64> = a.iter().zip(&b).map(|(x, y)| x + w * (y - x)).collect();
            return at_lambda(cv, &u, to, tol, 16).map_err(|e| step_err(to, e));
        }
        // the curve turned back past its start: no member at `to` connected to it
        if (l1 - from) * dir < -span || (reached - l1) * dir > span {
            return Err(FollowError::TurnedBack { reached });
        }
    }
    // a curve that turned at `reached` and keeps winding short of it (a closed loop of states)
    if (reached - arc.last.lam()) * dir > 0.0 {
        return Err(FollowError::TurnedBack { reached });
    }
    Err(FollowError::Step {
        at: arc.last.lam(),
        reason: "no member reached in 2000 steps".into(),
    })
}
