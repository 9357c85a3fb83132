//! The rough edges of issue 20 around continuation: the logarithmic scale from 0.1 to 0.01,
//! failure hints, the bridge from any problem to a family, looser intermediate tolerances, the
//! automatic continuation fallback, and what `Dense` a collocation solution carries.

use bvp::continuation::{family, ContinuationOptions, Method};
use bvp::fixed::{Fixed, SimpleBvp};
use bvp::samples::{Bratu, BratuFamily};
use bvp::testset::CashMazzia;
use bvp::{
    from_fns, solve_by_continuation, solve_member, BvpError, BvpSolver, Collocation,
    CollocationOptions, Dense, ErrorControl, Guess, PathOptions, Scheme, Shooting, ShootingOptions,
    Status,
};

fn lobatto(scheme: Scheme, tol: f64) -> Collocation {
    Collocation::new(CollocationOptions {
        scheme,
        tol,
        ..CollocationOptions::default()
    })
    .unwrap()
}

/// `max |y − y_exact| / (1 + max |y_exact|)` at the nodes and 9 points inside each interval.
fn scaled_error(p: &CashMazzia, eps: f64, sol: &bvp::Solution) -> f64 {
    let (mut d, mut top) = (0.0_f64, 0.0_f64);
    for w in sol.mesh.windows(2) {
        for j in 0..10 {
            let x = w[0] + (w[1] - w[0]) * j as f64 / 10.0;
            let ex = p.exact(x, eps).unwrap()[0];
            d = d.max((sol.at(x)[0] - ex).abs());
            top = top.max(ex.abs());
        }
    }
    d / (1.0 + top)
}

/// 0.01 / 0.1 is 0.09999999999999999 in floating point: the automatic scale once took that for
/// less than a factor 10 and walked linearly, in one jump of 0.09. Now the walk is logarithmic:
/// the first step is `ds = 0.2` in ln ε.
#[test]
fn one_decade_is_walked_on_the_log_scale() {
    let p = CashMazzia::new(20).unwrap();
    let res = solve_by_continuation(
        &p,
        &mut lobatto(Scheme::Lobatto4, 1e-6),
        &p.guess(0.1, 101),
        0.1,
        0.01,
        &PathOptions::default(),
    )
    .unwrap();
    assert!(res.path.len() > 3, "{:?}", res.path);
    let first = res.path[1] / res.path[0];
    assert!((first - (-0.2_f64).exp()).abs() < 1e-12, "{:?}", res.path);
}

/// A family whose right-hand side is NaN beyond λ = 0.5: natural continuation stops there, and
/// the error says NonFinite without calling it a fold.
#[test]
fn non_finite_failures_are_not_called_folds() {
    let fam = family(|l: f64| {
        from_fns(
            2,
            (0.0, 1.0),
            move |_s, z, _p, dz| {
                dz[0] = z[1];
                dz[1] = if l > 0.5 { f64::NAN } else { -l * z[0] };
            },
            |za, zb, _p, r| {
                r[0] = za[0];
                r[1] = zb[0] - 1.0;
            },
        )
    });
    let mut opts = PathOptions {
        scale: bvp::Scale::Linear,
        ..PathOptions::default()
    };
    opts.continuation.ds_min = 1e-3;
    let guess = Guess::constant(0.0, 1.0, 11, &[0.5, 1.0], vec![]);
    let err = solve_by_continuation(
        &fam,
        &mut lobatto(Scheme::Lobatto4, 1e-6),
        &guess,
        0.1,
        1.0,
        &opts,
    )
    .unwrap_err();
    assert_eq!(err.status(), Status::NonFinite, "{err}");
    assert!(!err.to_string().contains("fold"), "{err}");
}

/// A real fold (Bratu at λ* = 3.513830719, Bratu's closed form via `θ = √(2λ) cosh(θ/4)`) met by
/// natural continuation is reported as `BvpError::Fold` with its estimated parameter value, by
/// shooting and both collocation schemes, linear and logarithmic walks (issue 34: a collocation
/// walk used to end in "non-finite value in rhs").
#[test]
fn folds_met_by_natural_continuation_are_reported_as_folds() {
    for scale in [bvp::Scale::Linear, bvp::Scale::Log] {
        let mut opts = PathOptions {
            scale,
            ..PathOptions::default()
        };
        opts.continuation = ContinuationOptions {
            method: Method::Natural,
            ds_min: 1e-3,
            ..opts.continuation
        };
        for method in 0..3 {
            let guess = Bratu { lambda: 1.0 }.guess();
            let err = match method {
                0 => solve_by_continuation(
                    &BratuFamily,
                    &mut Shooting::new(ShootingOptions::default()).unwrap(),
                    &guess,
                    1.0,
                    4.0,
                    &opts,
                ),
                m => solve_by_continuation(
                    &BratuFamily,
                    &mut lobatto(
                        if m == 1 {
                            Scheme::Lobatto4
                        } else {
                            Scheme::Lobatto6
                        },
                        1e-6,
                    ),
                    &guess,
                    1.0,
                    4.0,
                    &opts,
                ),
            }
            .unwrap_err();
            match &err {
                BvpError::Fold { lambda, fold, .. } => {
                    assert!(
                        *lambda > 3.4 && *lambda < 3.5139,
                        "{scale:?} {method}: {err}"
                    );
                    assert!(
                        (fold - 3.513830719).abs() < 1e-4,
                        "{scale:?} {method}: {err}"
                    );
                    assert_eq!(err.status(), Status::PathEnded);
                }
                e => panic!("{scale:?} {method}: {e}"),
            }
        }
    }
}

/// An array problem with its parameter as a field, walked by continuation through the
/// [`family`] bridge: the same path and answer as the hand-written `BratuFamily`.
struct ArrayBratu(f64);

impl SimpleBvp<2> for ArrayBratu {
    fn interval(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn rhs(&self, _s: f64, z: &[f64; 2]) -> [f64; 2] {
        [z[1], -self.0 * z[0].exp()]
    }
    fn bc(&self, za: &[f64; 2], zb: &[f64; 2]) -> [f64; 2] {
        [za[0], zb[0]]
    }
    fn rhs_jacobian(&self, _s: f64, z: &[f64; 2], dfdz: &mut [[f64; 2]; 2]) -> bool {
        *dfdz = [[0.0, 1.0], [-self.0 * z[0].exp(), 0.0]];
        true
    }
}

#[test]
fn any_problem_becomes_a_family() {
    let fam = family(|l| Fixed(ArrayBratu(l)));
    // ∂F/∂λ by central differences against the analytic −e^y.
    let (mut jz, mut jl) = ([0.0; 4], [0.0; 2]);
    assert!(bvp::ParamBvp::rhs_jacobian(
        &fam,
        0.3,
        &[0.4, 0.1],
        &[],
        2.0,
        &mut jz,
        &mut [],
        &mut jl
    ));
    assert!((jl[1] + 0.4_f64.exp()).abs() < 1e-9, "{jl:?}");
    assert_eq!(jz, [0.0, 1.0, -2.0 * 0.4_f64.exp(), 0.0]);
    let guess = Bratu { lambda: 0.5 }.guess();
    let walk = |f: &dyn Fn(&mut Shooting) -> bvp::PathSolution| {
        let mut s = Shooting::new(ShootingOptions::default()).unwrap();
        f(&mut s)
    };
    let a = walk(&|s| {
        solve_by_continuation(&fam, s, &guess, 0.5, 3.0, &PathOptions::default()).unwrap()
    });
    let b = walk(&|s| {
        solve_by_continuation(&BratuFamily, s, &guess, 0.5, 3.0, &PathOptions::default()).unwrap()
    });
    assert_eq!(a.path.len(), b.path.len());
    let (ya, yb) = (a.solution.left()[1], b.solution.left()[1]);
    assert!((ya - yb).abs() < 1e-9, "{ya} vs {yb}");
}

/// Intermediate members at a looser tolerance: the member at `to` is still solved at the
/// solver's own (within 10·tol of the exact solution), for less work.
#[test]
fn intermediate_members_at_a_looser_tolerance() {
    let (eps, tol) = (1e-3, 1e-8);
    let p = CashMazzia::new(20).unwrap();
    let run = |intermediate: Option<f64>| {
        let mut solver = lobatto(Scheme::Lobatto6, tol);
        let opts = PathOptions {
            intermediate_tol: intermediate,
            ..PathOptions::default()
        };
        let res =
            solve_by_continuation(&p, &mut solver, &p.guess(0.1, 101), 0.1, eps, &opts).unwrap();
        assert_eq!(
            solver.tolerance(),
            Some(tol),
            "the solver's tolerance is restored"
        );
        res
    };
    let (strict, loose) = (run(None), run(Some(1e-4)));
    for r in [&strict, &loose] {
        let e = scaled_error(&p, eps, &r.solution);
        assert!(e <= 10.0 * tol, "error {e:.2e}");
        assert!(r.solution.stats.error_estimate.unwrap() <= tol);
    }
    assert!(
        loose.stats.rhs_evals < strict.stats.rhs_evals,
        "{} vs {}",
        loose.stats.rhs_evals,
        strict.stats.rhs_evals
    );
    let bad = PathOptions {
        intermediate_tol: Some(2.0),
        ..PathOptions::default()
    };
    assert!(matches!(
        bad.validate(),
        Err(BvpError::InvalidOption {
            name: "intermediate_tol",
            ..
        })
    ));
}

/// The automatic fallback: a member out of Newton's reach from the straight line is solved by
/// continuation from the named easy value; an easy member directly (path of one point).
#[test]
fn solve_member_falls_back_to_continuation() {
    let p = CashMazzia::new(20).unwrap();
    let tol = 1e-6;
    for (eps, direct) in [(0.05, true), (1e-3, false)] {
        let mut s = lobatto(Scheme::Lobatto4, tol);
        if !direct {
            assert!(s.solve(&p.at(eps), &p.guess(eps, 101)).is_err());
        }
        let res = solve_member(
            &p,
            &mut s,
            &p.guess(eps, 101),
            eps,
            0.1,
            &PathOptions::default(),
        )
        .unwrap();
        assert_eq!(res.path.len() == 1, direct, "{:?}", res.path);
        assert!(scaled_error(&p, eps, &res.solution) <= 10.0 * tol);
        assert!(res.stats.rhs_evals >= res.solution.stats.rhs_evals);
    }
}

/// `solve_by_continuation` marks the steps of its walk (`BvpSolver::set_walking`): collocation
/// with the default control (`ErrorControl::Confirmed`) solves them without the guard and the
/// member it returns once more with it; under `ErrorControl::Residual` no solve runs the guard
/// and the walk's last solution is returned.
#[test]
fn continuation_checks_the_member_it_returns() {
    struct Recorder {
        inner: Collocation,
        walking: Vec<bool>,
        guarded: Vec<bool>,
    }
    impl BvpSolver for Recorder {
        fn solve<P: bvp::Bvp + ?Sized>(
            &mut self,
            problem: &P,
            guess: &Guess,
        ) -> Result<bvp::Solution, BvpError> {
            let r = self.inner.solve(problem, guess);
            self.guarded.push(self.inner.guard_error().is_some());
            r
        }
        fn set_walking(&mut self, walking: bool) -> bool {
            self.walking.push(walking);
            self.inner.set_walking(walking)
        }
    }
    let (eps, tol) = (1e-3, 1e-6);
    let p = CashMazzia::new(20).unwrap();
    for control in [ErrorControl::Confirmed, ErrorControl::Residual] {
        let mut rec = Recorder {
            inner: Collocation::new(CollocationOptions {
                scheme: Scheme::Lobatto6,
                tol,
                control,
                ..CollocationOptions::default()
            })
            .unwrap(),
            walking: Vec::new(),
            guarded: Vec::new(),
        };
        let opts = PathOptions::default();
        let res = solve_by_continuation(&p, &mut rec, &p.guess(0.1, 101), 0.1, eps, &opts)
            .unwrap_or_else(|e| panic!("{control:?}: {e}"));
        assert_eq!(rec.walking, [true, false], "{control:?}");
        let (last, steps) = rec.guarded.split_last().unwrap();
        assert!(
            steps.len() >= res.path.len() - 1,
            "{control:?}: {}",
            steps.len()
        );
        assert!(steps.iter().all(|g| !g), "{control:?}: {:?}", rec.guarded);
        assert_eq!(*last, control == ErrorControl::Confirmed, "{control:?}");
        let e = scaled_error(&p, eps, &res.solution);
        assert!(e <= 10.0 * tol, "{control:?}: error {e:.2e}");
    }
}

/// The dense output of each method is what its docs say: Lobatto4 its collocation cubic
/// (`Dense::Hermite`, whose residual its error control measures), Lobatto6 the quintic Hermite
/// with `z''` from inside each interval (`Dense::QuinticIntervals`), RK4 shooting the cubic,
/// DOP853 its own extension.
#[test]
fn dense_output_kinds() {
    let b = Bratu { lambda: 1.0 };
    let sol = lobatto(Scheme::Lobatto4, 1e-6)
        .solve(&b, &b.guess())
        .unwrap();
    assert!(matches!(sol.dense, Dense::Hermite));
    let sol = lobatto(Scheme::Lobatto6, 1e-6)
        .solve(&b, &b.guess())
        .unwrap();
    assert!(matches!(sol.dense, Dense::QuinticIntervals { .. }));
    let rk4 = Shooting::new(ShootingOptions {
        integrator: bvp::Integrator::Rk4 { steps: 100 },
        ..ShootingOptions::default()
    })
    .unwrap()
    .solve(&b, &b.guess())
    .unwrap();
    assert!(matches!(rk4.dense, Dense::Hermite));
    let dop = Shooting::new(ShootingOptions::default())
        .unwrap()
        .solve(&b, &b.guess())
        .unwrap();
    assert!(matches!(dop.dense, Dense::Dop853 { .. }));
}
