//! Newton on the rod's own shot: the unknowns `u = (m(0), f, α)` and three conditions
//! `(m(1), c₁, c₂)` at the tip, one 3×3 system for every tip condition (α fixed is the row
//! `α − α_given = 0`). Used by single solves (damped Newton) and the scan (chord Newton with
//! tangents); families of rods are followed by [`crate::arclength`].

use crate::equations::Y;
use crate::profile::Profile;
use crate::shooter::{Shooter, MAX_STEPS};
use nalgebra::{Matrix3, Vector3};

/// The two tip conditions besides `m(1) = 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum TipCond {
    /// `φ(1) = phi1` at the given force angle.
    Phi1 { phi1: f64, alpha: f64 },
    /// `y(1) = eta` at the given force angle.
    Eta { eta: f64, alpha: f64 },
    /// `x(1) = x1`, `y(1) = y1` (α unknown).
    Pos { x1: f64, y1: f64 },
}

impl TipCond {
    /// Residual `(m(1), c₁, c₂)` at the end state `y` of the shot from `u`.
    #[inline]
    pub fn residual(&self, y: &Y, u: &[f64; 3]) -> Vector3<f64> {
        match *self {
            TipCond::Phi1 { phi1, alpha } => Vector3::new(y[3], y[2] - phi1, u[2] - alpha),
            TipCond::Eta { eta, alpha } => Vector3::new(y[3], y[1] - eta, u[2] - alpha),
            TipCond::Pos { x1, y1 } => Vector3::new(y[3], y[0] - x1, y[1] - y1),
        }
    }

    /// `∂(m(1), c₁, c₂)/∂u` from the sensitivities of a shot.
    #[inline]
    pub fn jacobian(&self, y: &Y) -> Matrix3<f64> {
        let s = |q: usize, i: usize| y[4 + 4 * q + i];
        let row = |i: usize| [s(0, i), s(1, i), s(2, i)];
        let (r1, r2) = match self {
            TipCond::Phi1 { .. } => (row(2), [0.0, 0.0, 1.0]),
            TipCond::Eta { .. } => (row(1), [0.0, 0.0, 1.0]),
            TipCond::Pos { .. } => (row(0), row(1)),
        };
        let r0 = row(3);
        Matrix3::new(
            r0[0], r0[1], r0[2], r1[0], r1[1], r1[2], r2[0], r2[1], r2[2],
        )
    }
}

/// Why a Newton solve on the shot failed.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum ShotFailure {
    /// The Jacobian is singular (or not finite) at the iterate.
    Singular { iteration: usize },
    /// The residual did not fall below the tolerance within the iterations (or damping stalled).
    NoConvergence { iteration: usize, residual: f64 },
    /// The mesh needed more than [`MAX_STEPS`] steps.
    MeshLimit { steps: usize },
}

impl std::fmt::Display for ShotFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ShotFailure::Singular { iteration } => {
                write!(f, "singular Jacobian at Newton iteration {iteration}")
            }
            ShotFailure::NoConvergence {
                iteration,
                residual,
            } => write!(
                f,
                "Newton did not converge (iteration {iteration}, residual {residual:.3e})"
            ),
            ShotFailure::MeshLimit { steps } => {
                write!(f, "the integration needs more than {steps} steps")
            }
        }
    }
}

/// A converged shot: unknowns, the Jacobian there (for tangents and the fold test), residual.
#[derive(Clone, Debug)]
pub(crate) struct Converged {
    pub u: [f64; 3],
    pub jac: Matrix3<f64>,
    pub residual: f64,
    pub iterations: usize,
}

impl Converged {
    /// Solves `J x = b`; `None` when `J` is singular.
    pub fn solve(&self, b: [f64; 3]) -> Option<[f64; 3]> {
        let x = self.jac.lu().solve(&Vector3::from(b))?;
        x.iter().all(|v| v.is_finite()).then(|| [x[0], x[1], x[2]])
    }
    /// `det J`.
    pub fn det(&self) -> f64 {
        self.jac.determinant()
    }
    /// The 1-norm condition number of `J` (infinite when singular).
    pub fn cond(&self) -> f64 {
        let norm1 = |m: &Matrix3<f64>| {
            (0..3)
                .map(|c| m.column(c).iter().map(|v| v.abs()).sum::<f64>())
                .fold(0.0, f64::max)
        };
        match self.jac.try_inverse() {
            Some(inv) => norm1(&self.jac) * norm1(&inv),
            None => f64::INFINITY,
        }
    }
}

fn max_abs(r: &Vector3<f64>) -> f64 {
    r.iter().fold(0.0f64, |a, v| a.max(v.abs()))
}

/// Grows the mesh after a converged shot whose step errors exceed the tolerance; `Err` past the
/// step limit.
fn refine<P: Profile>(sh: &mut Shooter<P>) -> Result<(), ShotFailure> {
    if sh.refine() {
        Ok(())
    } else {
        Err(ShotFailure::MeshLimit { steps: MAX_STEPS })
    }
}

/// Damped Newton (fresh Jacobian every iteration, step halving while the residual does not
/// decrease) from `u0` to `|R| ≤ tol` with every step error within tolerance; the shooter's path
/// holds the solution afterwards.
pub(crate) fn solve_damped<P: Profile>(
    sh: &mut Shooter<P>,
    cond: &TipCond,
    u0: [f64; 3],
    tol: f64,
    max_iter: usize,
) -> Result<Converged, ShotFailure> {
    let mut u = u0;
    // last accepted iterate, its step, residual and the damping tried
    let mut prev: Option<([f64; 3], [f64; 3], f64, f64)> = None;
    let mut iter = 0;
    for _ in 0..16 * max_iter {
        let shot = sh.shoot::<true>(&u);
        let r = cond.residual(&shot.y1, &u);
        let rn = max_abs(&r);
        if rn <= tol {
            let jac = cond.jacobian(&shot.y1);
            if shot.err > 1.0 {
                // a coarse mesh can have spurious solutions: start over from the guess
                refine(sh)?;
                prev = None;
                u = u0;
                iter = 0;
                continue;
            }
            return Ok(Converged {
                u,
                jac,
                residual: rn,
                iterations: iter,
            });
        }
        if let Some((uo, du, rno, lam)) = prev {
            if rn.is_nan() || rn >= rno {
                if lam < 1e-3 {
                    return Err(ShotFailure::NoConvergence {
                        iteration: iter,
                        residual: rno,
                    });
                }
                let lam = 0.5 * lam;
                u = [
                    uo[0] + lam * du[0],
                    uo[1] + lam * du[1],
                    uo[2] + lam * du[2],
                ];
                prev = Some((uo, du, rno, lam));
                continue;
            }
        }
        if !rn.is_finite() {
            return Err(ShotFailure::NoConvergence {
                iteration: iter,
                residual: rn,
            });
        }
        if iter == max_iter {
            return Err(ShotFailure::NoConvergence {
                iteration: iter,
                residual: rn,
            });
        }
        let jac = cond.jacobian(&shot.y1);
        let du = jac
            .lu()
            .solve(&(-r))
            .filter(|x| x.iter().all(|v| v.is_finite()))
            .ok_or(ShotFailure::Singular { iteration: iter })?;
        sh.stats.newton_iters += 1;
        sh.stats.factorizations += 1;
        iter += 1;
        let du = [du[0], du[1], du[2]];
        prev = Some((u, du, rn, 1.0));
        u = [u[0] + du[0], u[1] + du[1], u[2] + du[2]];
    }
    Err(ShotFailure::NoConvergence {
        iteration: iter,
        residual: f64::NAN,
    })
}

/// Chord Newton from a good prediction `u0` (the scan's corrector): the Jacobian of the first
/// iterate is kept while the residual falls by 10× per iteration, so from a good predictor a
/// point costs one shot with and one without sensitivities. The returned Jacobian is fresh at the
/// solution when the iterate moved more than `1e-5` (tangents come from it).
pub(crate) fn correct_chord<P: Profile>(
    sh: &mut Shooter<P>,
    cond: &TipCond,
    u0: [f64; 3],
    tol: f64,
    max_iter: usize,
) -> Result<Converged, ShotFailure> {
    let u_start = u0;
    for _pass in 0..16 {
        let mut u = u_start;
        let mut jac: Option<Matrix3<f64>> = None;
        let mut lu = None;
        let mut fresh = false;
        let mut rn_prev = f64::INFINITY;
        for it in 0..=max_iter {
            let shot = if jac.is_none() {
                let s = sh.shoot::<true>(&u);
                let j = cond.jacobian(&s.y1);
                lu = Some(j.lu());
                jac = Some(j);
                fresh = true;
                s
            } else {
                sh.shoot::<false>(&u)
            };
            let r = cond.residual(&shot.y1, &u);
            let rn = max_abs(&r);
            if !rn.is_finite() {
                return Err(ShotFailure::NoConvergence {
                    iteration: it,
                    residual: rn,
                });
            }
            if rn <= tol {
                if shot.err > 1.0 {
                    // a coarse mesh can have spurious solutions: start over from the prediction
                    refine(sh)?;
                    break;
                }
                let moved = u
                    .iter()
                    .zip(&u_start)
                    .fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
                let mut j = jac.unwrap_or_else(Matrix3::zeros);
                if !fresh || moved > 1e-5 {
                    // the first Jacobian is too rough for a tangent: one more shot at the solution
                    // (it leaves the same path in the shooter, the state being the same)
                    let s = sh.shoot::<true>(&u);
                    j = cond.jacobian(&s.y1);
                }
                return Ok(Converged {
                    u,
                    jac: j,
                    residual: rn,
                    iterations: it,
                });
            }
            if it == max_iter {
                return Err(ShotFailure::NoConvergence {
                    iteration: it,
                    residual: rn,
                });
            }
            if rn > 0.1 * rn_prev {
                // slow chord convergence: a fresh Jacobian here
                let s = sh.shoot::<true>(&u);
                let j = cond.jacobian(&s.y1);
                lu = Some(j.lu());
                jac = Some(j);
                fresh = true;
            }
            rn_prev = rn;
            let du = lu
                .as_ref()
                .and_then(|l| l.solve(&(-r)))
                .filter(|x| x.iter().all(|v| v.is_finite()))
                .ok_or(ShotFailure::Singular { iteration: it })?;
            sh.stats.newton_iters += 1;
            sh.stats.factorizations += 1;
            for i in 0..3 {
                u[i] += du[i];
            }
        }
    }
    Err(ShotFailure::MeshLimit { steps: sh.steps() })
}
