//! Single and multiple shooting against closed forms and published tables.
//!
//! Sources of the expected values: closed forms derived in `bvp::samples` (sinh, the non-separated
//! linear problem, eigenvalues `(jπ)²`, Bratu's `θ` equation) and Mattiasson (1981) for the
//! cantilever (5 printed digits, so ±6e-6 absolute).

use bvp::samples::{
    Bratu, Cantilever, Eigen, LinearNonSeparated, LinearSinh, NanRhs, NoSolution, SingularNeumann,
};
use bvp::{
    Bvp, BvpError, BvpSolver, Guess, Integrator, NewtonOptions, Shooting, ShootingOptions,
    Solution, Status,
};

fn rk4(steps: usize, segments: usize) -> ShootingOptions {
    ShootingOptions {
        integrator: Integrator::Rk4 { steps },
        segments,
        ..Default::default()
    }
}

fn adaptive(tol: f64, segments: usize) -> ShootingOptions {
    ShootingOptions {
        integrator: Integrator::Adaptive {
            rtol: tol,
            atol: tol,
        },
        segments,
        ..Default::default()
    }
}

fn solve(opts: ShootingOptions, p: &impl Bvp, g: &Guess) -> Solution {
    let mut s = Shooting::new(opts.clone()).unwrap();
    match s.solve(p, g) {
        Ok(sol) => sol,
        Err(e) => panic!("{opts:?}: {e}"),
    }
}

/// Max error over the mesh nodes against `exact`.
fn node_error(sol: &Solution, exact: impl Fn(f64) -> Vec<f64>) -> f64 {
    let mut e = 0.0_f64;
    for (i, &s) in sol.mesh.iter().enumerate() {
        for (a, b) in sol.node(i).iter().zip(exact(s)) {
            e = e.max((a - b).abs());
        }
    }
    e
}

fn all_configs() -> Vec<ShootingOptions> {
    vec![
        rk4(400, 1),
        rk4(400, 4),
        adaptive(1e-12, 1),
        adaptive(1e-12, 4),
    ]
}

#[test]
fn linear_problems_to_1e10() {
    for opts in all_configs() {
        let sol = solve(opts.clone(), &LinearSinh, &LinearSinh::guess());
        let e = node_error(&sol, |s| LinearSinh::exact(s).to_vec());
        eprintln!(
            "sinh {:?} M={}: err {e:.2e}, {}",
            opts.integrator, opts.segments, sol.stats
        );
        assert!(e <= 1e-10, "sinh {opts:?}: {e:e}");
        // Exact Jacobian of a linear discrete map: one Newton step suffices.
        assert!(sol.stats.newton_iters <= 2, "{}", sol.stats);
        assert_eq!(sol.mesh[0], 0.0);
        assert_eq!(*sol.mesh.last().unwrap(), 1.0);
        assert!(sol.stats.steps > 0 && sol.stats.rhs_evals > 0 && sol.stats.factorizations > 0);

        let sol = solve(
            opts.clone(),
            &LinearNonSeparated,
            &LinearNonSeparated::guess(),
        );
        let e = node_error(&sol, |s| LinearNonSeparated::exact(s).to_vec());
        eprintln!(
            "nonsep {:?} M={}: err {e:.2e}, {}",
            opts.integrator, opts.segments, sol.stats
        );
        assert!(e <= 1e-10, "nonsep {opts:?}: {e:e}");
        assert!(sol.stats.newton_iters <= 2, "{}", sol.stats);
    }
}

#[test]
fn rk4_dense_output_between_nodes() {
    // Hermite interpolation between RK4 nodes (h = 1/400) is O(h⁴) accurate too.
    let sol = solve(rk4(400, 1), &LinearSinh, &LinearSinh::guess());
    let mut e = 0.0_f64;
    for i in 0..1000 {
        let s = (i as f64 + 0.37) / 1000.0;
        e = e.max((sol.at(s)[0] - LinearSinh::exact(s)[0]).abs());
    }
    assert!(e <= 1e-10, "{e:e}");
}

#[test]
fn rk4_observed_order_four() {
    // Error of u'(0) on Bratu's lower branch at λ = 1 under step halving, in the asymptotic range
    // (h = 1/32 … 1/256; errors 3e-9 … 7e-13, above rounding).
    let p = Bratu { lambda: 1.0 };
    let exact = p.exact(0, 0.0)[1];
    let errs: Vec<f64> = [32, 64, 128]
        .iter()
        .map(|&steps| {
            let sol = solve(rk4(steps, 1), &p, &p.guess());
            (sol.left()[1] - exact).abs()
        })
        .collect();
    for w in errs.windows(2) {
        let order = (w[0] / w[1]).log2();
        eprintln!("errors {errs:?} order {order:.3}");
        assert!(
            (order - 4.0).abs() < 0.15,
            "observed order {order}, errors {errs:?}"
        );
    }
}

#[test]
fn eigenvalues_to_1e10() {
    for (mode, guess) in [(1, Eigen::guess()), (2, Eigen::guess_mode(2))] {
        let exact = Eigen::eigenvalue(mode);
        for opts in [
            adaptive(1e-13, 1),
            adaptive(1e-13, 4),
            rk4(1000, 1),
            rk4(1000, 8),
        ] {
            let sol = solve(opts.clone(), &Eigen, &guess);
            let e = (sol.params[0] - exact).abs();
            eprintln!(
                "eigen mode {mode} {:?} M={}: λ err {e:.2e}, {}",
                opts.integrator, opts.segments, sol.stats
            );
            assert!(
                e <= 1e-10 * exact.max(1.0),
                "mode {mode} {opts:?}: λ = {}",
                sol.params[0]
            );
            let ez = node_error(&sol, |s| Eigen::exact(mode, s).to_vec());
            assert!(ez <= 1e-9, "mode {mode}: state error {ez:e}");
        }
    }
}

#[test]
fn bratu_both_branches() {
    let p = Bratu { lambda: 1.0 };
    for (branch, guess) in [(0, p.guess()), (1, p.guess_upper())] {
        for opts in [adaptive(1e-13, 1), adaptive(1e-13, 4), rk4(2000, 4)] {
            let sol = solve(opts.clone(), &p, &guess);
            let e = node_error(&sol, |s| p.exact(branch, s).to_vec());
            eprintln!(
                "bratu branch {branch} {:?} M={}: err {e:.2e}, {}",
                opts.integrator, opts.segments, sol.stats
            );
            assert!(e <= 1e-9, "branch {branch} {opts:?}: {e:e}");
        }
    }
}

#[test]
fn warm_start_converges_immediately() {
    let p = Bratu { lambda: 1.0 };
    let mut s = Shooting::new(adaptive(1e-12, 2)).unwrap();
    let sol = s.solve(&p, &p.guess()).unwrap();
    let again = s.solve(&p, &Guess::from(&sol)).unwrap();
    assert!(again.stats.newton_iters <= 1, "{}", again.stats);
    // Nearby parameter: a few iterations.
    let near = s
        .solve(&Bratu { lambda: 1.05 }, &Guess::from(&sol))
        .unwrap();
    assert!(near.stats.newton_iters <= 4, "{}", near.stats);
}

fn check_cantilever(load: f64, want: [f64; 4], opts: &ShootingOptions, sol: &Solution) {
    let got = Cantilever::quantities(sol.left(), sol.right());
    eprintln!(
        "P = {load} {:?} M={}: {got:?} {}",
        opts.integrator, opts.segments, sol.stats
    );
    for q in 0..4 {
        assert!(
            (got[q] - want[q]).abs() <= 6e-6,
            "P = {load}, {opts:?}: quantity {q} = {} vs {}",
            got[q],
            want[q]
        );
    }
}

#[test]
fn cantilever_single_shooting_with_load_stepping() {
    // Single shooting from the straight rod fails for P = 5: its base moment m(0) = 5 puts the
    // pendulum φ'' = −P sin φ beyond the separatrix (m(0)² > 2P), where m(1) has a spurious local
    // minimum; jumping from P = 2 to 5 also stalls. So the load is stepped by 1 (P = 1 from the
    // straight rod, each next load from the previous solution), checking the table loads.
    for opts in [rk4(400, 1), adaptive(1e-10, 1)] {
        let mut s = Shooting::new(opts.clone()).unwrap();
        let mut guess = Cantilever { load: 1.0 }.guess();
        for step in 1..=10 {
            let load = step as f64;
            let sol = s.solve(&Cantilever { load }, &guess).unwrap();
            if let Some((_, want)) = Cantilever::MATTIASSON.iter().find(|(l, _)| *l == load) {
                check_cantilever(load, *want, &opts, &sol);
            }
            guess = Guess::from(&sol);
        }
    }
}

#[test]
fn cantilever_multiple_shooting_from_straight_rod() {
    for opts in [
        adaptive(1e-10, 4),
        adaptive(1e-10, 8),
        rk4(400, 4),
        rk4(400, 8),
    ] {
        for (load, want) in Cantilever::MATTIASSON {
            let p = Cantilever { load };
            let sol = solve(opts.clone(), &p, &p.guess());
            check_cantilever(load, want, &opts, &sol);
        }
    }
}

#[test]
fn cantilever_single_shooting_fails_honestly_beyond_separatrix() {
    let p = Cantilever { load: 5.0 };
    let mut s = Shooting::new(rk4(400, 1)).unwrap();
    let e = s.solve(&p, &p.guess()).unwrap_err();
    assert!(
        matches!(e.status(), Status::Stalled | Status::MaxIterations),
        "{e}"
    );
}

#[test]
fn no_solution_fails_cleanly() {
    for opts in [
        rk4(200, 1),
        adaptive(1e-10, 1),
        adaptive(1e-10, 4),
        rk4(200, 4),
    ] {
        let mut s = Shooting::new(opts.clone()).unwrap();
        let e = s.solve(&NoSolution, &NoSolution::guess()).unwrap_err();
        eprintln!("no solution {opts:?}: {e}");
        assert!(
            matches!(
                e.status(),
                Status::Stalled | Status::MaxIterations | Status::SingularJacobian
            ),
            "{opts:?}: {e}"
        );
        let st = e.stats().expect("stats");
        assert!(st.rhs_evals > 0 && st.steps > 0);
    }
}

#[test]
fn singular_jacobian_is_reported_with_statistics() {
    for opts in all_configs() {
        let mut s = Shooting::new(opts.clone()).unwrap();
        let e = s
            .solve(&SingularNeumann, &SingularNeumann::guess())
            .unwrap_err();
        eprintln!("singular {opts:?}: {e}");
        match &e {
            BvpError::SingularJacobian { iteration, stats } => {
                assert_eq!(*iteration, 1, "{e}");
                assert!(stats.rhs_evals > 0 && stats.steps > 0, "{stats}");
            }
            other => panic!("{opts:?}: expected SingularJacobian, got {other}"),
        }
        assert_eq!(e.status(), Status::SingularJacobian);
    }
}

#[test]
fn nan_rhs_reports_non_finite() {
    for opts in [rk4(100, 1), adaptive(1e-8, 1), adaptive(1e-8, 2)] {
        let mut s = Shooting::new(opts.clone()).unwrap();
        let e = s.solve(&NanRhs, &NanRhs::guess()).unwrap_err();
        eprintln!("nan {opts:?}: {e}");
        match e {
            BvpError::NonFinite { location, s, .. } => {
                assert_eq!(location, "rhs");
                assert!(s > 1.5 && s < 2.5, "s = {s}");
            }
            other => panic!("{opts:?}: expected NonFinite, got {other}"),
        }
    }
}

#[test]
fn invalid_options_rejected() {
    let bad = [
        rk4(0, 1),
        rk4(3, 4),
        ShootingOptions {
            segments: 0,
            ..Default::default()
        },
        adaptive(0.0, 1),
        adaptive(f64::NAN, 1),
        ShootingOptions {
            integrator: Integrator::Adaptive {
                rtol: 1e-8,
                atol: -1.0,
            },
            ..Default::default()
        },
        ShootingOptions {
            newton: NewtonOptions {
                max_iter: 0,
                ..Default::default()
            },
            ..Default::default()
        },
    ];
    for o in bad {
        match Shooting::new(o.clone()) {
            Err(e @ BvpError::InvalidOption { .. }) => {
                assert_eq!(e.status(), Status::InvalidInput);
                eprintln!("{e}");
            }
            other => panic!("{o:?}: {other:?}"),
        }
    }
    // Wrong guess size.
    let mut s = Shooting::new(ShootingOptions::default()).unwrap();
    let g = Guess::constant(0.0, 1.0, 3, &[0.0, 0.0, 0.0], vec![]);
    assert!(matches!(
        s.solve(&LinearSinh, &g),
        Err(BvpError::Dimension { .. })
    ));
}

/// Issue 34: single shooting reads the guess only at `a` and says so. `y'' = −|y|`, `y(0) = 0`,
/// `y(4) = −2` (bvp4c's `twobvp`) has two solutions (closed forms: `A sin x` on `[0, π]` then
/// `−A sinh(x − π)`, `A = 2 / sinh(4 − π)`; and `−2 sinh x / sinh 4`). A guess with the first
/// one's shape but the second one's start values: single shooting returns the second
/// (`Shooting::guess_points() == 1`); 8-segment shooting reads the shape at its segment starts
/// and returns the first.
#[test]
fn single_shooting_says_it_used_only_the_start_values() {
    let pi = std::f64::consts::PI;
    let amp = 2.0 / (4.0 - pi).sinh();
    let positive = move |x: f64| {
        if x <= pi {
            [amp * x.sin(), amp * x.cos()]
        } else {
            [-amp * (x - pi).sinh(), -amp * (x - pi).cosh()]
        }
    };
    let negative = |x: f64| {
        let c = -2.0 / 4.0_f64.sinh();
        [c * x.sinh(), c * x.cosh()]
    };
    let problem = bvp::from_fns(
        2,
        (0.0, 4.0),
        |_s, z, _p, dz| {
            dz[0] = z[1];
            dz[1] = -z[0].abs();
        },
        |za, zb, _p, r| {
            r[0] = za[0];
            r[1] = zb[0] + 2.0;
        },
    );
    let mesh: Vec<f64> = (0..=40).map(|i| 0.1 * i as f64).collect();
    let guess = Guess::from_fn(2, mesh, vec![], |x, z| {
        z.copy_from_slice(&if x == 0.0 { negative(x) } else { positive(x) })
    });
    let error = |sol: &Solution, exact: &dyn Fn(f64) -> [f64; 2]| {
        (0..=400).fold(0.0_f64, |m, i| {
            let x = 0.01 * i as f64;
            let (s, e) = (sol.at(x), exact(x));
            m.max((s[0] - e[0]).abs().max((s[1] - e[1]).abs()))
        })
    };
    let mut shooter = Shooting::new(adaptive(1e-10, 1)).unwrap();
    assert_eq!(shooter.guess_points(), 1);
    let single = shooter.solve(&problem, &guess).unwrap();
    assert!(
        error(&single, &negative) < 1e-7,
        "{}",
        error(&single, &negative)
    );
    let mut shooter = Shooting::new(adaptive(1e-10, 8)).unwrap();
    assert_eq!(shooter.guess_points(), 8);
    let multiple = shooter.solve(&problem, &guess).unwrap();
    assert!(
        error(&multiple, &positive) < 1e-7,
        "{}",
        error(&multiple, &positive)
    );
}
