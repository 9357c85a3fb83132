//! Issue 34: a solution extended to a longer interval, and continuation in the interval's end.
//! Falkner–Skan `f''' + f f'' + β(1 − f'²) = 0`, `f(0) = f'(0) = 0`, `f'(∞) = 1`, `β = 0.5`:
//! `f''(0) = 0.927680` (Falkner–Skan tables, e.g. White, *Viscous Fluid Flow*), the "infinity"
//! moved from 3 to 6 (a) by a guess from the solution on `[0, 3]` (`Guess::extended`, MATLAB's
//! `bvpinit(sol, [0 6])`, and `Guess::rescaled`) and (b) by continuation in the end
//! (`IntervalFamily`).

use bvp::{
    from_fns, solve_by_continuation, Bvp, BvpSolver, Collocation, CollocationOptions, Guess,
    IntervalFamily, PathOptions, Scheme, Solution,
};

fn falkner_skan(inf: f64) -> impl Bvp + Clone {
    let beta = 0.5;
    from_fns(
        3,
        (0.0, inf),
        move |_s, f, _p, df| {
            df[0] = f[1];
            df[1] = f[2];
            df[2] = -f[0] * f[2] - beta * (1.0 - f[1] * f[1]);
        },
        |fa, fb, _p, r| {
            r[0] = fa[0];
            r[1] = fa[1];
            r[2] = fb[1] - 1.0;
        },
    )
}

fn solver(scheme: Scheme) -> Collocation {
    Collocation::new(CollocationOptions {
        scheme,
        tol: 1e-8,
        ..CollocationOptions::default()
    })
    .unwrap()
}

/// `f''(0)` and the largest difference of `f'` on `[0, 6]` from `reference`.
fn compare(sol: &Solution, reference: &Solution) -> (f64, f64) {
    let mut d = 0.0_f64;
    for i in 0..=600 {
        let s = 6.0 * i as f64 / 600.0;
        d = d.max((sol.at(s)[1] - reference.at(s)[1]).abs());
    }
    (sol.node(0)[2], d)
}

#[test]
fn extension_to_a_longer_interval() {
    for scheme in [Scheme::Lobatto4, Scheme::Lobatto6] {
        let short = solver(scheme)
            .solve(
                &falkner_skan(3.0),
                &Guess::constant(0.0, 3.0, 5, &[0.0, 0.0, 1.0], vec![]),
            )
            .unwrap();
        let direct = solver(scheme)
            .solve(
                &falkner_skan(6.0),
                &Guess::constant(0.0, 6.0, 5, &[0.0, 0.0, 1.0], vec![]),
            )
            .unwrap();
        assert!((direct.node(0)[2] - 0.927680).abs() < 1e-5);
        for guess in [
            Guess::extended(&short, 0.0, 6.0, 5),
            Guess::rescaled(&short, 0.0, 6.0),
        ] {
            assert_eq!((guess.mesh[0], *guess.mesh.last().unwrap()), (0.0, 6.0));
            let long = solver(scheme).solve(&falkner_skan(6.0), &guess).unwrap();
            let (fpp, d) = compare(&long, &direct);
            assert!((fpp - 0.927680).abs() < 1e-5, "{scheme:?}: {fpp}");
            assert!(d < 1e-6, "{scheme:?}: {d:e}");
        }
    }
    // Beyond the old interval the extension holds the end values (bvpinit's extrapolation).
    let short = solver(Scheme::Lobatto4)
        .solve(
            &falkner_skan(3.0),
            &Guess::constant(0.0, 3.0, 5, &[0.0, 0.0, 1.0], vec![]),
        )
        .unwrap();
    let g = Guess::extended(&short, 0.0, 6.0, 5);
    let mut z = [0.0; 3];
    g.eval(5.0, &mut z);
    assert_eq!(z.to_vec(), short.right().to_vec());
}

#[test]
fn continuation_in_the_interval_end() {
    for scheme in [Scheme::Lobatto4, Scheme::Lobatto6] {
        let family = IntervalFamily::new(falkner_skan(3.0));
        let short = solver(scheme)
            .solve(
                &falkner_skan(3.0),
                &Guess::constant(0.0, 3.0, 5, &[0.0, 0.0, 1.0], vec![]),
            )
            .unwrap();
        let mut s = solver(scheme);
        let res = solve_by_continuation(
            &family,
            &mut s,
            &family.guess(&short),
            3.0,
            6.0,
            &PathOptions::default(),
        )
        .unwrap();
        let long = family.solution(&res.solution, 6.0);
        assert_eq!((long.mesh[0], *long.mesh.last().unwrap()), (0.0, 6.0));
        let direct = solver(scheme)
            .solve(
                &falkner_skan(6.0),
                &Guess::constant(0.0, 6.0, 5, &[0.0, 0.0, 1.0], vec![]),
            )
            .unwrap();
        let (fpp, d) = compare(&long, &direct);
        assert!((fpp - 0.927680).abs() < 1e-5, "{scheme:?}: {fpp}");
        assert!(d < 1e-6, "{scheme:?}: {d:e}");
        // The mapped solution solves the problem on [0, 6]: its residual meets tol.
        let worst = long
            .residuals(&falkner_skan(6.0))
            .iter()
            .fold(0.0_f64, |m, v| m.max(*v));
        assert!(worst <= 1e-8 * 1.001, "{scheme:?}: residual {worst:e}");
    }
}
