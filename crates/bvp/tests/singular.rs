//! The singular term `S z / x` (issue 24): Lane–Emden equations `y'' + (2/x) y' + yᵐ = 0` with
//! exact solutions, by both collocation schemes and by single and multiple shooting, from
//! scipy's guess (zeros: `y'(0) = 0` is not built in).
//!
//! Sources: index 5, `y = (1 + x²/3)^(−1/2)` (scipy's `solve_bvp` test `test_emden`, on
//! `[0, 1]` with `y'(0) = 0`, `y(1) = √(3/4)`); index 1, `y = sin x / x` (Chandrasekhar, *An
//! introduction to the study of stellar structure*, 1939), on `[0, π/2]` with `y(π/2) = 2/π`
//! (on `[0, π]` with `y(π) = 0` every multiple of it solves: not a test of accuracy).

use bvp::{
    from_fns, Bvp, BvpError, BvpSolver, Collocation, CollocationOptions, Guess, Integrator, Scheme,
    Shooting, ShootingOptions, SingularTerm, Solution,
};

const S: [f64; 4] = [0.0, 0.0, 0.0, -2.0];

/// Lane–Emden of index `m` (1 or 5) with its exact `(y, y')`.
fn lane_emden(m: i32) -> (impl Bvp, impl Fn(f64) -> [f64; 2]) {
    let b = if m == 5 {
        1.0
    } else {
        std::f64::consts::FRAC_PI_2
    };
    let exact = move |x: f64| -> [f64; 2] {
        if m == 5 {
            let q = 1.0 + x * x / 3.0;
            [q.powf(-0.5), -x / 3.0 * q.powf(-1.5)]
        } else if x == 0.0 {
            [1.0, 0.0]
        } else {
            [x.sin() / x, (x * x.cos() - x.sin()) / (x * x)]
        }
    };
    let yb = exact(b)[0];
    let f = from_fns(
        2,
        (0.0, b),
        move |_x, z, _p, dz| {
            dz[0] = z[1];
            dz[1] = -z[0].powi(m);
        },
        move |za, zb, _p, r| {
            r[0] = za[1];
            r[1] = zb[0] - yb;
        },
    )
    .with_rhs_jacobian(move |_x, z, _p, dfdz, _dfdp| {
        dfdz.copy_from_slice(&[0.0, 1.0, -f64::from(m) * z[0].powi(m - 1), 0.0]);
    });
    (SingularTerm::new(f, S.to_vec()), exact)
}

/// Max error of `y`, `y'` and of the derivative of the dense output against the exact solution
/// on 100 equal points (scipy's test grid).
fn errors(sol: &Solution, exact: &impl Fn(f64) -> [f64; 2]) -> (f64, f64) {
    let b = *sol.mesh.last().unwrap();
    let (mut e, mut d) = (0.0_f64, 0.0_f64);
    for i in 0..100 {
        let x = b * i as f64 / 99.0;
        let (z, dz, ex) = (sol.at(x), sol.derivative_at(x), exact(x));
        e = e.max((z[0] - ex[0]).abs()).max((z[1] - ex[1]).abs());
        d = d.max((dz[0] - ex[1]).abs());
    }
    (e, d)
}

#[test]
fn lane_emden_by_every_method() {
    for m in [5, 1] {
        let (p, exact) = lane_emden(m);
        let b = p.interval().1;
        let guess = Guess::constant(0.0, b, 5, &[0.0, 0.0], vec![]);
        let tol = 1e-6;
        let mut runs: Vec<(String, Solution)> = Vec::new();
        for scheme in [Scheme::Lobatto4, Scheme::Lobatto6] {
            let mut s = Collocation::new(CollocationOptions {
                scheme,
                tol,
                ..CollocationOptions::default()
            })
            .unwrap();
            let sol = s
                .solve(&p, &guess)
                .unwrap_or_else(|e| panic!("{scheme:?}: {e}"));
            // scipy's test: the residuals of the returned solution below tol.
            let rms = sol.residuals(&p);
            let worst = rms.iter().fold(0.0_f64, |a, v| a.max(*v));
            assert!(
                worst < 10.0 * tol,
                "index {m} {scheme:?}: residual {worst:e}"
            );
            runs.push((format!("{scheme:?}"), sol));
        }
        for segments in [1, 4] {
            let mut s = Shooting::new(ShootingOptions {
                integrator: Integrator::Adaptive {
                    rtol: 1e-2 * tol,
                    atol: 1e-2 * tol,
                },
                segments,
                tol: Some(tol),
                ..ShootingOptions::default()
            })
            .unwrap();
            let sol = s
                .solve(&p, &guess)
                .unwrap_or_else(|e| panic!("shooting {segments}: {e}"));
            runs.push((format!("shooting {segments}"), sol));
        }
        for (name, sol) in &runs {
            let (e, d) = errors(sol, &exact);
            assert!(e <= 10.0 * tol, "index {m} {name}: error {e:.2e}");
            assert!(
                d <= 100.0 * tol,
                "index {m} {name}: derivative error {d:.2e}"
            );
            assert_eq!(sol.mesh[0], 0.0);
        }
    }
}

/// A singular term needs the interval to start at 0 and `I − S` invertible.
#[test]
fn singular_term_is_validated() {
    let f = from_fns(
        2,
        (0.5, 1.0),
        |_x, z, _p, dz| {
            dz[0] = z[1];
            dz[1] = 0.0;
        },
        |za, zb, _p, r| {
            r[0] = za[1];
            r[1] = zb[0];
        },
    );
    let g = Guess::constant(0.5, 1.0, 5, &[0.0, 0.0], vec![]);
    let off = SingularTerm::new(f, S.to_vec());
    let r = Collocation::new(CollocationOptions::default())
        .unwrap()
        .solve(&off, &g);
    assert!(
        matches!(
            r,
            Err(BvpError::InvalidOption {
                name: "singular_term",
                ..
            })
        ),
        "{r:?}"
    );
    let (p, _) = lane_emden(5);
    let one = SingularTerm::new(p, vec![1.0, 0.0, 0.0, 0.0]);
    let g = Guess::constant(0.0, 1.0, 5, &[0.0, 0.0], vec![]);
    let r = Shooting::new(ShootingOptions::default())
        .unwrap()
        .solve(&one, &g);
    assert!(
        matches!(
            r,
            Err(BvpError::InvalidOption {
                name: "singular_term",
                ..
            })
        ),
        "{r:?}"
    );
}
