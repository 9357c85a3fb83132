//! Newton on a contact chain at a fixed family parameter: damped Newton for single solves (fresh
//! Jacobian every iteration, step halving while the residual does not fall) and the chord
//! corrector of the marches (the first Jacobian kept while the residual falls tenfold per
//! iteration). Both refine the shooter's meshes until every step is within tolerance before they
//! accept a point: a coarse mesh can have spurious solutions.

use crate::chain::Curve;
use crate::shooter::MAX_STEPS;
use nalgebra::{DMatrix, DVector};

/// Why a Newton solve failed.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum ShotFailure {
    /// The Jacobian is singular (or not finite) at the iterate.
    Singular { iteration: usize },
    /// The residual did not fall below the tolerance within the iterations (or damping stalled).
    NoConvergence { iteration: usize, residual: f64 },
    /// The mesh needed more than [`MAX_STEPS`] steps.
    MeshLimit { steps: usize },
    /// Pseudo-arclength steps down to `ds` converged, but each off the branch it continues: the
    /// tangent turned by more than ~25°, or the corrector moved more than a third of the step.
    Unresolved { ds: f64 },
    /// A generic method's solve of the same problem failed (the fold passage on crate `bvp`).
    Method(Box<bvp::BvpError>),
    /// The own shooter has no rod, or no Jacobian, at a generic method's unknowns.
    NoRod,
    /// Newton's iterate has no rod (a step that ran off: the contacts' arc lengths out of their
    /// order, or values not finite). Was reported as `NoConvergence` with the residual NaN.
    NoRodAt {
        iteration: usize,
        why: crate::chain::EvalError,
    },
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
            ShotFailure::Unresolved { ds } => write!(
                f,
                "the branch is not resolved by arclength steps down to {ds:.1e} (each turned \
                 the tangent by more than 25 degrees or moved the corrector by more than a \
                 third of the step)"
            ),
            ShotFailure::Method(e) => write!(f, "{e}"),
            ShotFailure::NoRod => {
                f.write_str("the own shooter has no rod at the method's unknowns")
            }
            ShotFailure::NoRodAt { iteration, why } => {
                write!(f, "Newton's iterate {iteration} has no rod ({why})")
            }
        }
    }
}

/// A converged point: unknowns, the Jacobians there (for tangents and the fold test), residual.
#[derive(Clone, Debug)]
pub(crate) struct Converged {
    pub u: Vec<f64>,
    pub jac: DMatrix<f64>,
    pub r_lam: DVector<f64>,
    pub residual: f64,
    pub iterations: usize,
}

impl Converged {
    /// Solves `J x = b`; `None` when `J` is singular.
    pub fn solve(&self, b: &DVector<f64>) -> Option<Vec<f64>> {
        let x = self.jac.clone().lu().solve(b)?;
        x.iter()
            .all(|v| v.is_finite())
            .then(|| x.iter().copied().collect())
    }
    /// The tangent `du/dλ = −J⁻¹ ∂R/∂λ`.
    pub fn tangent(&self) -> Option<Vec<f64>> {
        self.solve(&(-&self.r_lam))
    }
    /// `det J`.
    pub fn det(&self) -> f64 {
        self.jac.determinant()
    }
}

/// Converged at the rounding floor: the residual is within a thousand tolerances and Newton's
/// last step changed the unknowns by rounding only (strongly tapered rods, `b` up to 10⁸ at the
/// tip, leave residuals of ~1e-10 that no iteration reduces).
pub(crate) fn at_floor(rn: f64, tol: f64, last_step: f64, u: &[f64]) -> bool {
    rn <= 1e3 * tol && last_step <= 1e-13 * scale(u)
}

/// The size the unknowns' changes are measured against: `1 + max |u_i|`.
fn scale(u: &[f64]) -> f64 {
    1.0 + u.iter().fold(0.0f64, |m, v| m.max(v.abs()))
}

/// `u += du`, and the step's size `max |du_i|`.
fn newton_step(u: &mut [f64], du: &DVector<f64>) -> f64 {
    for (a, d) in u.iter_mut().zip(du.iter()) {
        *a += d;
    }
    max_abs(du)
}

pub(crate) fn max_abs(r: &DVector<f64>) -> f64 {
    r.iter().fold(0.0f64, |a, v| a.max(v.abs()))
}

fn refine<C: Curve + ?Sized>(ch: &mut C) -> Result<(), ShotFailure> {
    if ch.refine() {
        Ok(())
    } else {
        Err(ShotFailure::MeshLimit { steps: MAX_STEPS })
    }
}

/// Damped Newton from `u0` to `|R| ≤ tol` at `λ = lam`, with every step error within tolerance;
/// the shooter's paths hold the solution afterwards.
pub(crate) fn solve_damped<C: Curve + ?Sized>(
    ch: &mut C,
    lam: f64,
    u0: &[f64],
    tol: f64,
    max_iter: usize,
) -> Result<Converged, ShotFailure> {
    let mut u = u0.to_vec();
    // last accepted iterate, its step, residual and the damping tried
    let mut prev: Option<(Vec<f64>, Vec<f64>, f64, f64)> = None;
    let mut iter = 0;
    for _ in 0..16 * max_iter {
        let ev = ch.eval(&u, lam, true);
        let rn = match &ev {
            Ok(e) => max_abs(&e.r),
            Err(_) => f64::NAN,
        };
        if let Ok(e) = &ev {
            if rn <= tol {
                if e.err > 1.0 {
                    // a coarse mesh can have spurious solutions: start over from the guess
                    refine(ch)?;
                    prev = None;
                    u = u0.to_vec();
                    iter = 0;
                    continue;
                }
                return Ok(Converged {
                    u,
                    jac: e.jac.clone().unwrap_or_else(|| DMatrix::zeros(0, 0)),
                    r_lam: e.r_lam.clone().unwrap_or_else(|| DVector::zeros(0)),
                    residual: rn,
                    iterations: iter,
                });
            }
        }
        if let Some((uo, du, rno, lamd)) = &prev {
            if rn.is_nan() || rn >= *rno {
                if *lamd < 1e-3 {
                    return Err(ShotFailure::NoConvergence {
                        iteration: iter,
                        residual: *rno,
                    });
                }
                let lamd = 0.5 * lamd;
                u = uo.iter().zip(du).map(|(a, d)| a + lamd * d).collect();
                prev = Some((uo.clone(), du.clone(), *rno, lamd));
                continue;
            }
        }
        let e = match ev {
            Ok(e) if rn.is_finite() => e,
            Ok(_) => {
                return Err(ShotFailure::NoConvergence {
                    iteration: iter,
                    residual: rn,
                })
            }
            Err(why) => {
                return Err(ShotFailure::NoRodAt {
                    iteration: iter,
                    why,
                })
            }
        };
        if iter == max_iter {
            return Err(ShotFailure::NoConvergence {
                iteration: iter,
                residual: rn,
            });
        }
        let jac = e.jac.unwrap_or_else(|| DMatrix::zeros(0, 0));
        let du = jac
            .lu()
            .solve(&(-&e.r))
            .filter(|x| x.iter().all(|v| v.is_finite()))
            .ok_or(ShotFailure::Singular { iteration: iter })?;
        ch.count_iteration();
        iter += 1;
        let du: Vec<f64> = du.iter().copied().collect();
        prev = Some((u.clone(), du.clone(), rn, 1.0));
        u = u.iter().zip(&du).map(|(a, d)| a + d).collect();
    }
    Err(ShotFailure::NoConvergence {
        iteration: iter,
        residual: f64::NAN,
    })
}

/// Whether the residuals `rns` of a Newton iteration towards `tol` have stalled: the last
/// `STALL` of them did not halve the best before them, which is still far above `tol`. Beyond
/// a fold (no solution) the residual wanders at a level (1e-7 to 1e-2 on the cluster grid of
/// docs/reference.md) without falling, where a converging iteration (quadratic, or a chord
/// iteration whose Jacobian is renewed when it slows) falls by far more. Near `tol` the
/// iteration is left its iterations: where a contact's equations become singular (a side
/// contact letting go) it creeps at 1e-10 and still gets through.
fn stalled(rns: &[f64], tol: f64) -> bool {
    let k = rns.len();
    if k <= STALL {
        return false;
    }
    let before = rns[..k - STALL]
        .iter()
        .cloned()
        .fold(f64::INFINITY, f64::min);
    let recent = rns[k - STALL..]
        .iter()
        .cloned()
        .fold(f64::INFINITY, f64::min);
    recent > 0.5 * before && before > 1e4 * tol
}

/// The Newton correction `−J⁻¹ r` of an iterate whose residual `r` is within `tol`, where it
/// still moves the unknowns by more than `POLISH · tol` (relative to their size): a residual
/// within tolerance does not bound the error along a direction the Jacobian nearly loses. Two
/// contacts that hold near a state where their tangential pair is indeterminate (a tip nearly
/// tangent to the surface next to a side, with 0.33 % of the load) had predictions accepted at
/// a residual of 9.9e-13 (tol 1e-12) whose correction was 5.2e-6 in the pair's forces: the
/// slip's event function jumped by 5.2e-6 between points accepted so and points corrected
/// once, and the slip was located on that jump, 1.07e-7 before its place (d 3.32982e-5 against
/// 3.34051e-5 at tol 1e-12; tests/contact.rs). `None` where the correction is within that (on
/// every well-conditioned point: the result is that of the iterate), or not a number.
///
/// Taken only where asked (`correct_chord`'s `polish`: an event's search that ended on such a
/// jump, `events::jumped`). Taken at every point of a march it changed 85 of the 450 drags of
/// the texture grid, most of them to a trapped slide: a drag's trapped pair follows the split
/// of its tangential forces that the predictions carry from point to point.
fn large_correction(
    lu: Option<&nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>>,
    r: &DVector<f64>,
    tol: f64,
    u: &[f64],
) -> Option<DVector<f64>> {
    let du = lu?.solve(&(-r))?;
    let size = max_abs(&du);
    (size.is_finite() && size > POLISH * tol * scale(u)).then_some(du)
}

/// How much smaller than a polishing step ([`large_correction`]) the Newton correction after it
/// must be for the step to be kept: where the residual had room above its rounding floor the
/// step converges (5.2e-6, then 1e-8 on the pair above); where the floor over the small
/// singular value is as large as the step (a pair whose forces scatter by 1.5e-6 at a residual
/// of 1e-15), the step moves the unknowns within what the equations determine (polished so at
/// every point of a scan, such a pair's slip came out with its ratio 2.1e-6 below μ0, where the
/// iterates before the steps had it at μ0).
const POLISHED: f64 = 0.1;

/// How many residual tolerances an iterate within the residual's tolerance may still be moved
/// by its Newton correction ([`large_correction`]): the corrector's tolerance is a hundredth of
/// the shooter's (`control::corrector_tol`), so this is the shooter's own tolerance.
const POLISH: f64 = 100.0;

/// The iterations [`stalled`] looks back over.
const STALL: usize = 4;

/// What [`correct_chord`] is asked for besides the solution.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Flags {
    /// The returned Jacobian exact at the solution (tangents, events).
    pub fresh: bool,
    /// One more Newton step from an iterate within the residual's tolerance whose correction
    /// is still large ([`large_correction`]).
    pub polish: bool,
    /// The returned Jacobian exact at the solution where the prediction needed a second chord
    /// step. The chord's Jacobian, made at a prediction that far off, gives a tangent whose
    /// error feeds the next prediction: the long rat preset's predictions, made from such
    /// tangents of predictions 8e-6 off, stayed that far off (two chord steps a point instead
    /// of one; its scan 293 → 223 Newton iterations, 164 301 → 144 262 right-hand sides with
    /// it). The scan's march only (`march::Spec::retangent`).
    pub retangent: bool,
}

/// Chord Newton from a good prediction `u0` (the marches' corrector): the Jacobian of the first
/// iterate is kept while the residual falls by 10× per iteration, so from a good predictor a
/// point costs one shot with and one without sensitivities. With `fresh` (or when the iterate
/// moved more than `1e-5`, or, with `retangent`, needed a second chord step) the returned
/// Jacobian is recomputed at the solution: tangents and the events that use them need it exact,
/// and the next prediction is made from this tangent ([`Flags::retangent`]); an iterate the
/// chord's rate expects to converge is shot with its sensitivities at once (the same bits as
/// without, so the same iterations). An iteration that [`stalled`] gives up early.
pub(crate) fn correct_chord<C: Curve + ?Sized>(
    ch: &mut C,
    lam: f64,
    u0: &[f64],
    tol: f64,
    max_iter: usize,
    Flags {
        fresh,
        polish,
        retangent,
    }: Flags,
) -> Result<Converged, ShotFailure> {
    for _pass in 0..16 {
        let mut u = u0.to_vec();
        let mut lu = None;
        let mut jac0: Option<(DMatrix<f64>, DVector<f64>)> = None;
        let mut is_fresh = false;
        let mut refined = false;
        let mut last_step = f64::INFINITY;
        // (with `polish`: whether the polishing step was taken, and the iterate before it with
        // that step's size, until the step is judged)
        let mut polished = !polish;
        let mut before_polish: Option<(Vec<f64>, f64)> = None;
        let mut rns = Vec::with_capacity(max_iter + 1);
        for it in 0..=max_iter {
            let need = lu.is_none();
            let moved = u
                .iter()
                .zip(u0)
                .fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
            // (a Jacobian made at this very iterate is exact already; a prediction that needed
            // a second chord step was far enough off that the chord's Jacobian, made there,
            // would give a tangent whose error feeds the next prediction)
            let exact_wanted = (fresh || moved > 1e-5 || (retangent && it >= 2))
                && !((is_fresh || need) && it == 0);
            // where the chord's rate says this iterate converges and its Jacobian would then be
            // recomputed here, the sensitivities come with this shot (the state's bits are those
            // of a shot without them); a wrong guess costs them, unused
            let ahead = matches!(rns[..], [.., before, last] if last * (last / before) <= tol);
            let spec = !need && exact_wanted && ahead;
            let e = ch
                .eval(&u, lam, need || spec)
                .map_err(|why| ShotFailure::NoRodAt { iteration: it, why })?;
            if need {
                let j = e.jac.clone().unwrap_or_else(|| DMatrix::zeros(0, 0));
                lu = Some(j.clone().lu());
                jac0 = Some((j, e.r_lam.clone().unwrap_or_else(|| DVector::zeros(0))));
                is_fresh = true;
            }
            let rn = max_abs(&e.r);
            if !rn.is_finite() {
                return Err(ShotFailure::NoConvergence {
                    iteration: it,
                    residual: rn,
                });
            }
            if let Some((prev, step)) = before_polish.take() {
                let next = lu
                    .as_ref()
                    .and_then(|l| l.solve(&(-&e.r)))
                    .map_or(f64::INFINITY, |d| d.amax());
                // (NaN, a correction not known, keeps the iterate before)
                let converged = next <= POLISHED * step;
                if !converged {
                    // the step's own correction is as large as the step: the residual is at
                    // its rounding floor, and the step moved the unknowns within what the
                    // floor determines; the iterate before it is kept (shot again)
                    u = prev;
                    continue;
                }
            }
            if rn <= tol || at_floor(rn, tol, last_step, &u) {
                if e.err > 1.0 {
                    refine(ch)?;
                    refined = true;
                    break;
                }
                if !polished && it + 2 <= max_iter {
                    if let Some(du) = large_correction(lu.as_ref(), &e.r, tol, &u) {
                        polished = true;
                        ch.count_iteration();
                        let before = u.clone();
                        last_step = newton_step(&mut u, &du);
                        before_polish = Some((before, last_step));
                        continue;
                    }
                }
                let (mut j, mut rl) = jac0.take().unwrap_or_default();
                if exact_wanted {
                    // one more shot at the solution for an exact tangent (it leaves the same
                    // paths in the shooter, the state being the same), unless this one had them
                    let e2 = if spec {
                        e
                    } else {
                        ch.eval(&u, lam, true)
                            .map_err(|_| ShotFailure::Singular { iteration: it })?
                    };
                    j = e2.jac.unwrap_or(j);
                    rl = e2.r_lam.unwrap_or(rl);
                }
                return Ok(Converged {
                    u,
                    jac: j,
                    r_lam: rl,
                    residual: rn,
                    iterations: it,
                });
            }
            rns.push(rn);
            if it == max_iter || stalled(&rns, tol) {
                return Err(ShotFailure::NoConvergence {
                    iteration: it,
                    residual: rn,
                });
            }
            if matches!(rns[..], [.., before, _] if rn > 0.1 * before) {
                // slow chord convergence: a fresh Jacobian here
                let (jac, r_lam) = if spec {
                    (e.jac.clone(), e.r_lam.clone())
                } else {
                    let e2 = ch
                        .eval(&u, lam, true)
                        .map_err(|_| ShotFailure::Singular { iteration: it })?;
                    (e2.jac, e2.r_lam)
                };
                let j = jac.unwrap_or_else(|| DMatrix::zeros(0, 0));
                lu = Some(j.clone().lu());
                jac0 = Some((j, r_lam.unwrap_or_else(|| DVector::zeros(0))));
                is_fresh = false;
            }
            let du = lu
                .as_ref()
                .and_then(|l| l.solve(&(-&e.r)))
                .filter(|x| x.iter().all(|v| v.is_finite()))
                .ok_or(ShotFailure::Singular { iteration: it })?;
            ch.count_iteration();
            last_step = newton_step(&mut u, &du);
        }
        if !refined {
            break;
        }
    }
    Err(ShotFailure::MeshLimit { steps: MAX_STEPS })
}

#[cfg(test)]
mod tests {
    use super::{correct_chord, solve_damped, stalled, Flags, ShotFailure};
    use crate::chain::{Curve, Eval, EvalError};
    use nalgebra::{DMatrix, DVector};

    /// `R(u) = u − 10`, which has no value (contacts out of order) beyond `u = 5`.
    struct RunsOff;

    impl Curve for RunsOff {
        fn n(&self) -> usize {
            1
        }
        fn eval(&mut self, u: &[f64], _lam: f64, var: bool) -> Result<Eval, EvalError> {
            if u[0] > 5.0 {
                return Err(EvalError::Order);
            }
            Ok(Eval {
                r: DVector::from_element(1, u[0] - 10.0),
                jac: var.then(|| DMatrix::from_element(1, 1, 1.0)),
                r_lam: var.then(|| DVector::zeros(1)),
                err: 0.0,
            })
        }
        fn refine(&mut self) -> bool {
            false
        }
        fn count_iteration(&mut self) {}
    }

    /// An iterate without a rod is said as such, with the iteration and why (it read "Newton
    /// did not converge (residual NaN)": the short rat preset's touchdown beside a side 1.8e-5
    /// before its tip, whose seventh iterate put the side beyond the tip).
    #[test]
    fn an_iterate_without_a_rod_says_why() {
        let e = correct_chord(&mut RunsOff, 0.0, &[0.0], 1e-12, 10, Flags::default()).unwrap_err();
        assert_eq!(
            e,
            ShotFailure::NoRodAt {
                iteration: 1,
                why: EvalError::Order
            }
        );
        assert_eq!(
            e.to_string(),
            "Newton's iterate 1 has no rod (the contacts' arc lengths leave their order in (0, 1])"
        );
        // a guess without a rod, for the damped Newton of single solves
        let e = solve_damped(&mut RunsOff, 0.0, &[6.0], 1e-12, 10).unwrap_err();
        assert_eq!(
            e,
            ShotFailure::NoRodAt {
                iteration: 0,
                why: EvalError::Order
            }
        );
    }

    /// Residual sequences of the corrector (tol 1e-12) on the cluster grid's slowest scene
    /// (η 0.5, taper 0.05, κ0 = 0, a fold in d at 0.46983) and on the side contact letting go of
    /// `tests/scan_fixes.rs` (η 0.6, taper 0.1, β −0.3).
    #[test]
    fn stalls_beyond_a_fold_but_not_while_converging_or_creeping_near_tol() {
        let when = |rns: &[f64]| (1..=rns.len()).find(|&k| stalled(&rns[..k], 1e-12));
        // beyond the fold: given up after 5 of 13 iterations
        let fold = [
            3.0e-3, 1.6e-3, 7.4e-2, 1.7e-2, 4.9e-3, 1.9e-3, 3.6e-3, 1.7e-3, 5.7e-2, 1.4e-2, 4.0e-3,
        ];
        assert_eq!(when(&fold), Some(5));
        let hover = [3.4e-7, 1.2e-7, 1.5e-7, 1.0e-7, 4.0e-7, 1.3e-7, 1.2e-7];
        assert_eq!(when(&hover), Some(6));
        // converging in 6 iterations
        let ok = [2.2e-2, 3.4e-3, 2.3e-4, 3.2e-5, 2.9e-8, 5.5e-11, 1.1e-13];
        assert_eq!(when(&ok), None);
        // creeping near tol where the contact's equations turn singular: left to max_iter
        let creep = [
            7.9e-5, 1.6e-5, 1.7e-6, 6.4e-9, 5.1e-11, 3.2e-9, 2.1e-9, 1.2e-9, 2.9e-9,
        ];
        assert_eq!(when(&creep), None);
    }
}
