//! Issue 34: residual ≠ error. The seasonal epidemic model with periodic conditions (Schwartz
//! 1983, the "measles" example of the bvp4c tutorial), ill-conditioned: at tol 1e-4 the residual
//! control of Lobatto4 is met (8.5e-5) with an error of 5.2e-3, as with scipy's `solve_bvp`. With
//! `ErrorControl::Error` the estimated true error is held to `tol`: checked against a reference
//! computed independently (scipy's DOP853 at rtol 1e-13 with Newton on the periodicity,
//! `data/bvp_periodic/measles_reference.py`, its accuracy in `measles_reference.txt`) on 2001
//! points of the dense output.

use bvp::{
    from_fns, Bvp, BvpSolver, Collocation, CollocationOptions, ErrorControl, Guess, Scheme,
    Solution,
};

const REFERENCE: &str = include_str!("../../../data/bvp_periodic/measles_reference.csv");

fn measles() -> impl Bvp {
    from_fns(
        3,
        (0.0, 1.0),
        |t, y, _p, dy| {
            let b = 1575.0 * (1.0 + (2.0 * std::f64::consts::PI * t).cos());
            dy[0] = 0.02 - b * y[0] * y[2];
            dy[1] = b * y[0] * y[2] - y[1] / 0.0279;
            dy[2] = y[1] / 0.0279 - y[2] / 0.01;
        },
        |ya, yb, _p, r| {
            for i in 0..3 {
                r[i] = yb[i] - ya[i];
            }
        },
    )
}

/// `(t, y)` rows of the reference.
fn reference() -> Vec<(f64, [f64; 3])> {
    REFERENCE
        .lines()
        .skip(1)
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            (v[0], [v[1], v[2], v[3]])
        })
        .collect()
}

/// Max over the reference's 2001 points of `|S_c − y_c| / (1 + |y_c|)`.
fn error(sol: &Solution, reference: &[(f64, [f64; 3])]) -> f64 {
    let mut e = 0.0_f64;
    for (t, y) in reference {
        let s = sol.at(*t);
        for c in 0..3 {
            e = e.max((s[c] - y[c]).abs() / (1.0 + y[c].abs()));
        }
    }
    e
}

fn solve(scheme: Scheme, tol: f64, control: ErrorControl) -> Solution {
    solve_guarded(scheme, tol, control).0
}

/// The solution and the guard's estimate ([`Collocation::guard_error`]).
fn solve_guarded(scheme: Scheme, tol: f64, control: ErrorControl) -> (Solution, Option<f64>) {
    let guess = Guess::constant(0.0, 1.0, 5, &[0.01, 0.01, 0.01], vec![]);
    let mut solver = Collocation::new(CollocationOptions {
        scheme,
        tol,
        control,
        ..CollocationOptions::default()
    })
    .unwrap();
    let sol = solver
        .solve(&measles(), &guess)
        .unwrap_or_else(|e| panic!("{scheme:?} tol {tol:e} {control:?}: {e}"));
    (sol, solver.guard_error())
}

/// Error control: the true error meets `tol`, and the estimate is within a factor 2 of it.
#[test]
fn error_control_meets_tol_on_the_periodic_problem() {
    let reference = reference();
    assert_eq!(reference.len(), 2001);
    for tol in [1e-3, 1e-4, 1e-6] {
        for scheme in [Scheme::Lobatto4, Scheme::Lobatto6] {
            let sol = solve(scheme, tol, ErrorControl::Error);
            let (err, est) = (error(&sol, &reference), sol.stats.error_estimate.unwrap());
            assert!(err <= tol, "{scheme:?} tol {tol:e}: error {err:.3e}");
            assert!(
                est <= 2.0 * err.max(1e-12) && err <= 2.0 * est,
                "{scheme:?} tol {tol:e}: error {err:.3e}, estimate {est:.3e}"
            );
        }
    }
}

/// Residual control (the default before issue 34's fourth round) holds what it says on this
/// problem: the residual of the returned interpolant meets `tol` and is the reported estimate. Its error is not bounded by
/// `tol` here (measured, not asserted: 5.2e-3 for Lobatto4 at tol 1e-4, 9.5e-4 for Lobatto6);
/// the guard (next test) or error control bound it.
#[test]
fn residual_control_meets_the_residual() {
    for scheme in [Scheme::Lobatto4, Scheme::Lobatto6] {
        let (sol, guard) = solve_guarded(scheme, 1e-4, ErrorControl::Residual);
        let worst = sol
            .residuals(&measles())
            .iter()
            .fold(0.0_f64, |m, v| m.max(*v));
        let est = sol.stats.error_estimate.unwrap();
        assert!(worst <= 1e-4, "{scheme:?}: residual {worst:.3e}");
        assert!(
            (worst - est).abs() <= 1e-3 * est,
            "{scheme:?}: {worst:.3e} vs {est:.3e}"
        );
        assert_eq!(guard, None);
    }
}

/// Residual control with its guard (`ErrorControl::Guarded`): the guard's estimate of the true
/// error (deferred correction) exceeds `tol` where the residual is met with a large error (Lobatto4 at
/// tol 1e-4: estimate 3.2e-3 for an error of 5.2e-3), the solve goes on under error control, and
/// every success is within `tol` of the reference (measured at tol 1e-3 / 1e-4 / 1e-6: Lobatto4
/// 2.0e-4 / 1.9e-5 / 2.4e-7, Lobatto6 1.1e-5 / 9.5e-6 / 2.2e-7).
#[test]
fn guarded_residual_control_meets_tol_on_the_periodic_problem() {
    let reference = reference();
    for tol in [1e-3, 1e-4, 1e-6] {
        for scheme in [Scheme::Lobatto4, Scheme::Lobatto6] {
            let (sol, guard) = solve_guarded(scheme, tol, ErrorControl::Guarded);
            let err = error(&sol, &reference);
            assert!(err <= tol, "{scheme:?} tol {tol:e}: error {err:.3e}");
            assert!(guard.is_some(), "{scheme:?} tol {tol:e}");
        }
    }
    let guard = solve_guarded(Scheme::Lobatto4, 1e-4, ErrorControl::Guarded).1;
    assert!(guard.unwrap() > 1e-3, "guard {guard:?}");
}

/// Residual control whose guard's alarms are confirmed (`ErrorControl::Confirmed`): an alarm
/// is checked against error control's reference before the solve goes on under error control,
/// so every success is within 10·tol of the reference (measured at tol 1e-3 / 1e-4 / 1e-6:
/// Lobatto4 2.0e-4 / 1.9e-5 / 2.4e-7, Lobatto6 1.1e-5 / 9.5e-6 / 2.2e-7; with `Residual`
/// Lobatto4 at 1e-4 is 5.2e-3 off). At tol 1e-4 Lobatto4's alarm is confirmed (guard 3.2e-3,
/// reference 6.3e-3).
#[test]
fn confirmed_control_is_within_ten_tol_on_the_periodic_problem() {
    let reference = reference();
    for tol in [1e-3, 1e-4, 1e-6] {
        for scheme in [Scheme::Lobatto4, Scheme::Lobatto6] {
            let guess = Guess::constant(0.0, 1.0, 5, &[0.01, 0.01, 0.01], vec![]);
            let mut solver = Collocation::new(CollocationOptions {
                scheme,
                tol,
                control: ErrorControl::Confirmed,
                ..CollocationOptions::default()
            })
            .unwrap();
            let sol = solver
                .solve(&measles(), &guess)
                .unwrap_or_else(|e| panic!("{scheme:?} tol {tol:e}: {e}"));
            let err = error(&sol, &reference);
            assert!(
                err <= 10.0 * tol,
                "{scheme:?} tol {tol:e}: error {err:.3e} (guard {:?}, confirmation {:?})",
                solver.guard_error(),
                solver.confirmation()
            );
            if (scheme, tol) == (Scheme::Lobatto4, 1e-4) {
                let confirmed = solver.confirmation().unwrap();
                assert!(confirmed > tol, "confirmation {confirmed:.3e}");
            }
        }
    }
}

/// The default options (`ErrorControl::Confirmed` since issue 34's fourth round): every
/// collocation scheme reports success at tol 1e-3 / 1e-4 / 1e-6 / 1e-8 and is within 10·tol of
/// the reference on its 2001 points (measured: Lobatto4 1.98e-4 / 1.87e-5 / 2.41e-7 / 3.37e-9,
/// Lobatto6 1.06e-5 / 9.53e-6 / 2.19e-7 / 9.68e-9; with `Residual` Lobatto4 at 1e-4 is
/// 5.2e-3 off, 52·tol).
#[test]
fn default_options_are_within_ten_tol_on_the_periodic_problem() {
    let reference = reference();
    for tol in [1e-3, 1e-4, 1e-6, 1e-8] {
        for scheme in [Scheme::Lobatto4, Scheme::Lobatto6] {
            let guess = Guess::constant(0.0, 1.0, 5, &[0.01, 0.01, 0.01], vec![]);
            let mut solver = Collocation::new(CollocationOptions {
                scheme,
                tol,
                ..CollocationOptions::default()
            })
            .unwrap();
            let sol = solver
                .solve(&measles(), &guess)
                .unwrap_or_else(|e| panic!("{scheme:?} tol {tol:e}: {e}"));
            let err = error(&sol, &reference);
            assert!(
                err <= 10.0 * tol,
                "{scheme:?} tol {tol:e}: error {err:.3e} (guard {:?}, confirmation {:?})",
                solver.guard_error(),
                solver.confirmation()
            );
        }
    }
}
