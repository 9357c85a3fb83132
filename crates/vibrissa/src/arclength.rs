//! Pseudo-arclength continuation on the rod's own shooter, for every one-parameter family of rods:
//! the homotopy from the uniform straight rod to any rod, the tip moved along a line, and the scan
//! in the foot displacement `d` where it folds.
//!
//! The curve `R(u, λ) = 0` (`u = (m(0), f, α)`, three tip conditions `R`) is followed in
//! `v = (u, λ)`: Euler predictor along the unit tangent `τ` (`[J  R_λ] τ = 0`, oriented like the
//! last one), Newton corrector on the hyperplane `τ·(v − v_pred) = 0` with the 4×4 bordered
//! Jacobian (nalgebra LU), step control by the corrector's iterations and the turn of the tangent.
//! The same corrector with the hyperplane normal `e_λ` solves one member at a given `λ`, and with
//! the normal of a step it parametrizes the curve between two points (where events are located).
//! A fold in `λ` is where `τ_λ` (whose sign is that of `det J`) changes sign.

use crate::profile::Profile;
use crate::rodsolve::{Converged, ShotFailure, TipCond};
use crate::shooter::{Shooter, MAX_STEPS};
use nalgebra::{Matrix3, Matrix4, Vector3, Vector4};

/// A one-parameter family of rods on the shooter.
pub(crate) trait Family<P: Profile> {
    /// Sets the shooter to member `lam` (profile, support) and returns its tip condition.
    fn set(&self, sh: &mut Shooter<P>, lam: f64) -> TipCond;
    /// `∂R/∂λ` at `u` of member `lam`; may shoot (the caller shoots `u` at `lam` afterwards).
    fn r_lam(&self, sh: &mut Shooter<P>, u: &[f64; 3], lam: f64) -> Vector3<f64>;
}

/// The tip moved along a horizontal line: `x(1) = x0 + slope·λ`, `y(1) = y1`, α unknown. The scan
/// is `x0 = x*`, `slope = −1` (λ = d); moving the tip to a target x is `slope = 1`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct TipLine {
    pub x0: f64,
    pub slope: f64,
    pub y1: f64,
}

impl<P: Profile> Family<P> for TipLine {
    fn set(&self, _sh: &mut Shooter<P>, lam: f64) -> TipCond {
        TipCond::Pos {
            x1: self.x0 + self.slope * lam,
            y1: self.y1,
        }
    }
    fn r_lam(&self, _sh: &mut Shooter<P>, _u: &[f64; 3], _lam: f64) -> Vector3<f64> {
        Vector3::new(0.0, -self.slope, 0.0)
    }
}

/// The homotopy: member `t` is the rod `member(t)` (profile and compliance) under the fixed tip
/// condition `cond`. `∂R/∂t` by a forward difference (the profile enters through its table).
pub(crate) struct Homotopy<M> {
    pub member: M,
    pub cond: TipCond,
}

impl<P: Profile, M: Fn(f64) -> (P, f64)> Family<P> for Homotopy<M> {
    fn set(&self, sh: &mut Shooter<P>, lam: f64) -> TipCond {
        let (p, c) = (self.member)(lam);
        sh.set_profile(p, c);
        self.cond
    }
    fn r_lam(&self, sh: &mut Shooter<P>, u: &[f64; 3], lam: f64) -> Vector3<f64> {
        let h = 1e-7;
        self.set(sh, lam);
        let r0 = self.cond.residual(&sh.shoot::<false>(u).y1, u);
        self.set(sh, lam + h);
        let r1 = self.cond.residual(&sh.shoot::<false>(u).y1, u);
        (r1 - r0) / h
    }
}

/// A converged point of a family.
#[derive(Clone, Debug)]
pub(crate) struct ArcPoint {
    /// `(m(0), f, α, λ)`.
    pub v: Vector4<f64>,
    /// `∂R/∂u` there.
    pub jac: Matrix3<f64>,
    /// `∂R/∂λ` there.
    pub r_lam: Vector3<f64>,
    /// Max-norm of `R`.
    pub residual: f64,
    /// Newton iterations it took.
    pub iterations: usize,
}

impl ArcPoint {
    /// The unknowns `u`.
    pub fn u(&self) -> [f64; 3] {
        [self.v[0], self.v[1], self.v[2]]
    }
    /// The family parameter.
    pub fn lam(&self) -> f64 {
        self.v[3]
    }
    /// As a converged solve at fixed `λ`.
    pub fn converged(&self) -> Converged {
        Converged {
            u: self.u(),
            jac: self.jac,
            residual: self.residual,
            iterations: self.iterations,
        }
    }
    /// The unit tangent, oriented along `along` (or with `dλ > 0` when `along` is `None`).
    pub fn tangent(&self, along: Option<&Vector4<f64>>) -> Option<Vector4<f64>> {
        // the null vector of [J R_λ] by cofactors: τ_i = (−1)^i det of [J R_λ] without column i
        let col = |c: usize| -> Vector3<f64> {
            if c < 3 {
                self.jac.column(c).into()
            } else {
                self.r_lam
            }
        };
        let minor = |skip: usize| {
            let mut idx = (0..4).filter(|&c| c != skip);
            let (a, b, c) = (idx.next(), idx.next(), idx.next());
            match (a, b, c) {
                (Some(a), Some(b), Some(c)) => {
                    Matrix3::from_columns(&[col(a), col(b), col(c)]).determinant()
                }
                _ => f64::NAN,
            }
        };
        let mut t = Vector4::new(-minor(0), minor(1), -minor(2), minor(3));
        let n = t.norm();
        if !(n > 0.0 && n.is_finite()) {
            return None;
        }
        t /= n;
        let flip = match along {
            Some(d) => t.dot(d) < 0.0,
            None => t[3] < 0.0,
        };
        Some(if flip { -t } else { t })
    }
}

fn max_abs(r: &Vector3<f64>) -> f64 {
    r.iter().fold(0.0f64, |a, v| a.max(v.abs()))
}

/// Newton on `R(v) = 0`, `normal·(v − v_pred) = 0` from `v_pred` to `|R| ≤ tol` with every step
/// error of the shot within tolerance; the shooter's path holds the point afterwards.
pub(crate) fn correct<P: Profile, F: Family<P>>(
    sh: &mut Shooter<P>,
    fam: &F,
    v_pred: Vector4<f64>,
    normal: Vector4<f64>,
    tol: f64,
    max_iter: usize,
) -> Result<ArcPoint, ShotFailure> {
    for _pass in 0..16 {
        let mut v = v_pred;
        let mut rn_prev = f64::INFINITY;
        let mut refined = false;
        for it in 0..=max_iter {
            let u = [v[0], v[1], v[2]];
            let lam = v[3];
            let r_lam = fam.r_lam(sh, &u, lam);
            let cond = fam.set(sh, lam);
            let shot = sh.shoot::<true>(&u);
            let r = cond.residual(&shot.y1, &u);
            let rn = max_abs(&r);
            if !rn.is_finite() || !r_lam.iter().all(|x| x.is_finite()) {
                return Err(ShotFailure::NoConvergence {
                    iteration: it,
                    residual: rn,
                });
            }
            let jac = cond.jacobian(&shot.y1);
            if rn <= tol {
                if shot.err > 1.0 {
                    // a coarse mesh can have spurious solutions: refine, start over
                    if !sh.refine() {
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
            let mut m = Matrix4::zeros();
            m.fixed_view_mut::<3, 3>(0, 0).copy_from(&jac);
            m.fixed_view_mut::<3, 1>(0, 3).copy_from(&r_lam);
            m.set_row(3, &normal.transpose());
            let rhs = Vector4::new(-r[0], -r[1], -r[2], -normal.dot(&(v - v_pred)));
            let dv = m
                .lu()
                .solve(&rhs)
                .filter(|x| x.iter().all(|c| c.is_finite()))
                .ok_or(ShotFailure::Singular { iteration: it })?;
            sh.stats.newton_iters += 1;
            sh.stats.factorizations += 1;
            v += dv;
        }
        if !refined {
            break;
        }
    }
    Err(ShotFailure::MeshLimit { steps: sh.steps() })
}

/// The member at `λ = lam` from the prediction `u`.
pub(crate) fn at_lambda<P: Profile, F: Family<P>>(
    sh: &mut Shooter<P>,
    fam: &F,
    u: [f64; 3],
    lam: f64,
    tol: f64,
    max_iter: usize,
) -> Result<ArcPoint, ShotFailure> {
    let v = Vector4::new(u[0], u[1], u[2], lam);
    correct(sh, fam, v, Vector4::new(0.0, 0.0, 0.0, 1.0), tol, max_iter)
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
    pub tau: Vector4<f64>,
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

    /// One accepted step along the curve (the step size shrinks on failures and grows after easy
    /// steps); returns the previous point and its tangent.
    pub fn step<P: Profile, F: Family<P>>(
        &mut self,
        sh: &mut Shooter<P>,
        fam: &F,
    ) -> Result<(ArcPoint, Vector4<f64>), ShotFailure> {
        loop {
            let ds = self.steps.ds;
            let pred = self.last.v + self.tau * ds;
            let attempt = correct(sh, fam, pred, self.tau, self.tol, ARC_ITER).and_then(|p| {
                let t = p
                    .tangent(Some(&self.tau))
                    .ok_or(ShotFailure::Singular { iteration: 0 })?;
                Ok((p, t))
            });
            match attempt {
                // the tangent turned by less than ~25° and the corrector moved less than a third
                // of the step: the same branch, resolved
                Ok((p, t)) if t.dot(&self.tau) > 0.9 && (p.v - pred).norm() < 0.3 * ds => {
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
                            Ok(_) => ShotFailure::NoConvergence {
                                iteration: 0,
                                residual: 0.0,
                            },
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
pub(crate) fn between<P: Profile, F: Family<P>>(
    sh: &mut Shooter<P>,
    fam: &F,
    a: &ArcPoint,
    ta: &Vector4<f64>,
    b: &ArcPoint,
    sigma: f64,
    tol: f64,
) -> Result<ArcPoint, ShotFailure> {
    let span = ta.dot(&(b.v - a.v));
    let w = if span != 0.0 { sigma / span } else { 0.0 };
    let pred = a.v + (b.v - a.v) * w;
    // the hyperplane ta·(v − a) = sigma through the prediction
    let shifted = pred + ta * (sigma - ta.dot(&(pred - a.v)));
    correct(sh, fam, shifted, *ta, tol, 2 * ARC_ITER)
}
