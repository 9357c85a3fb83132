//! Collocation solver: accuracy against closed forms and published tables, observed orders,
//! failure reporting.
//!
//! Error bound used for the tolerance tests: the global error `e = z − S` satisfies
//! `e' = J e + r` with the collocation residual `r`, so `‖e‖∞ ≤ K ‖r‖` where `K` is the stability
//! constant of the BVP (norm of its Green's function; ≤ 1.5 for the linear problems on [0, 1]
//! used here). The solver controls the RMS over each interval of `r / (1 + |F|)` (≤ tol); the
//! pointwise maximum of a cubic/quartic residual is at most ~2× its RMS and `1 + |F| ≤ 3` here,
//! so `‖e‖∞ ≲ 1.5 · 2 · 3 · tol ≈ 10 tol`. The tests assert `max error ≤ 10 tol`.

use bvp::samples::{
    Bratu, Cantilever, Eigen, FiniteDifferences, LinearNonSeparated, LinearSinh, NanRhs,
    NoSolution, Parabola, SingularNeumann,
};
use bvp::{
    Bvp, BvpError, BvpSolver, Collocation, CollocationOptions, Guess, Scheme, Solution, Status,
};

const SCHEMES: [Scheme; 2] = [Scheme::Lobatto4, Scheme::Lobatto6];

fn solver(scheme: Scheme, tol: f64) -> Collocation {
    Collocation::new(CollocationOptions {
        scheme,
        tol,
        ..Default::default()
    })
    .unwrap()
}

/// Max over the nodes and over midpoints (dense output) of `|z − exact|`.
fn max_errors(sol: &Solution, exact: impl Fn(f64) -> [f64; 2]) -> (f64, f64) {
    let mut nodal: f64 = 0.0;
    for (i, &s) in sol.mesh.iter().enumerate() {
        for (z, e) in sol.node(i).iter().zip(exact(s)) {
            nodal = nodal.max((z - e).abs());
        }
    }
    let mut dense: f64 = 0.0;
    for w in sol.mesh.windows(2) {
        let s = 0.5 * (w[0] + w[1]);
        for (z, e) in sol.at(s).iter().zip(exact(s)) {
            dense = dense.max((z - e).abs());
        }
    }
    (nodal, dense)
}

fn max_step(sol: &Solution) -> f64 {
    sol.mesh.windows(2).fold(0.0, |m, w| m.max(w[1] - w[0]))
}

#[test]
fn options_are_validated() {
    let bad = [
        CollocationOptions {
            tol: 0.0,
            ..Default::default()
        },
        CollocationOptions {
            tol: f64::NAN,
            ..Default::default()
        },
        CollocationOptions {
            bc_tol: Some(-1.0),
            ..Default::default()
        },
        CollocationOptions {
            max_nodes: 2,
            ..Default::default()
        },
        CollocationOptions {
            max_mesh_passes: 0,
            ..Default::default()
        },
    ];
    let names = ["tol", "tol", "bc_tol", "max_nodes", "max_mesh_passes"];
    for (o, name) in bad.into_iter().zip(names) {
        match Collocation::new(o) {
            Err(BvpError::InvalidOption { name: got, .. }) => assert_eq!(got, name),
            other => panic!("expected InvalidOption for {name}, got {other:?}"),
        }
    }
}

#[test]
fn linear_problems_meet_tolerance() {
    for scheme in SCHEMES {
        for tol in [1e-6, 1e-10] {
            let mut c = solver(scheme, tol);
            let sol = c.solve(&LinearSinh, &LinearSinh::guess()).unwrap();
            let (nodal, dense) = max_errors(&sol, LinearSinh::exact);
            println!(
                "{scheme:?} tol {tol:e} sinh: {} nodes, nodal {nodal:.2e}, dense {dense:.2e}, {}",
                sol.len(),
                sol.stats
            );
            assert!(nodal <= 10.0 * tol, "{scheme:?} {tol}");
            // Lobatto4: eval is the collocation cubic itself. Lobatto6: eval is the cubic Hermite
            // interpolant of the nodal data, whose error is at most h⁴/384 · max|z⁗| (z⁗ = z here,
            // |z| ≤ cosh 1 / sinh 1 < 1.32) on top of the nodal error.
            let dense_bound = match scheme {
                Scheme::Lobatto4 => 10.0 * tol,
                Scheme::Lobatto6 => 10.0 * tol + max_step(&sol).powi(4) / 384.0 * 1.32,
            };
            assert!(
                dense <= dense_bound,
                "{scheme:?} {tol}: dense {dense:e} > {dense_bound:e}"
            );
            assert!(sol.stats.error_estimate.unwrap() <= tol);

            let sol = c
                .solve(&LinearNonSeparated, &LinearNonSeparated::guess())
                .unwrap();
            let (nodal, dense) = max_errors(&sol, LinearNonSeparated::exact);
            println!("{scheme:?} tol {tol:e} non-separated: {} nodes, nodal {nodal:.2e}, dense {dense:.2e}", sol.len());
            assert!(nodal <= 10.0 * tol, "{scheme:?} {tol}");
            if scheme == Scheme::Lobatto4 {
                assert!(dense <= 10.0 * tol, "{scheme:?} {tol}");
            }
        }
    }
}

/// Max nodal error of the lower Bratu solution (λ = 1) on a uniform mesh without adaptation.
fn bratu_fixed_mesh_error(scheme: Scheme, intervals: usize) -> f64 {
    let bratu = Bratu { lambda: 1.0 };
    let mut opts = CollocationOptions {
        scheme,
        adapt: false,
        ..Default::default()
    };
    opts.newton.tol = 1e-14;
    let mut c = Collocation::new(opts).unwrap();
    let mesh: Vec<f64> = (0..=intervals)
        .map(|i| i as f64 / intervals as f64)
        .collect();
    let guess = Guess::from_fn(2, mesh, vec![], |s, z| {
        z[0] = 0.5 * s * (1.0 - s);
        z[1] = 0.5 - s;
    });
    let sol = c.solve(&bratu, &guess).unwrap();
    assert_eq!(sol.len(), intervals + 1, "fixed mesh must not be adapted");
    max_errors(&sol, |s| bratu.exact(0, s)).0
}

#[test]
fn observed_order_on_uniform_meshes() {
    // Mesh halving; errors well above rounding (≥ 1e-12) so the ratios are clean.
    for (scheme, meshes) in [
        (Scheme::Lobatto4, [4, 8, 16, 32]),
        (Scheme::Lobatto6, [2, 4, 8, 16]),
    ] {
        let errs: Vec<f64> = meshes
            .iter()
            .map(|&m| bratu_fixed_mesh_error(scheme, m))
            .collect();
        let orders: Vec<f64> = errs.windows(2).map(|w| (w[0] / w[1]).log2()).collect();
        println!("{scheme:?}: errors {errs:?}, observed orders {orders:.3?}");
        let p = *orders.last().unwrap();
        assert!(
            (p - scheme.order() as f64).abs() <= 0.2,
            "{scheme:?}: order {p}"
        );
    }
}

#[test]
fn eigenvalues() {
    for scheme in SCHEMES {
        for mode in [1, 2] {
            let tol = 1e-8;
            let mut c = solver(scheme, tol);
            let sol = c.solve(&Eigen, &Eigen::guess_mode(mode)).unwrap();
            let want = Eigen::eigenvalue(mode);
            let rel = (sol.params[0] - want).abs() / want;
            let (nodal, _) = max_errors(&sol, |s| Eigen::exact(mode, s));
            println!(
                "{scheme:?} mode {mode}: λ = {} (rel err {rel:.2e}), nodal {nodal:.2e}, {} nodes",
                sol.params[0],
                sol.len()
            );
            // λ is a functional of the solution: its relative error is bounded like the solution error.
            assert!(
                rel <= 10.0 * tol,
                "{scheme:?} mode {mode}: {}",
                sol.params[0]
            );
            assert!(nodal <= 10.0 * tol);
        }
    }
}

#[test]
fn bratu_both_solutions() {
    let bratu = Bratu { lambda: 1.0 };
    for scheme in SCHEMES {
        let tol = 1e-8;
        let mut c = solver(scheme, tol);
        for (branch, guess) in [(0, bratu.guess()), (1, bratu.guess_upper())] {
            let sol = c.solve(&bratu, &guess).unwrap();
            let (nodal, dense) = max_errors(&sol, |s| bratu.exact(branch, s));
            println!("{scheme:?} Bratu branch {branch}: u(1/2) = {:.10}, nodal {nodal:.2e}, dense {dense:.2e}, {} nodes", sol.at(0.5)[0], sol.len());
            // Upper branch: |u'| up to ≈ 10 and a larger stability constant; allow 10 tol · (1 + max|F|).
            let bound = if branch == 0 { 10.0 * tol } else { 100.0 * tol };
            assert!(nodal <= bound, "{scheme:?} branch {branch}");
            if scheme == Scheme::Lobatto4 {
                assert!(dense <= bound, "{scheme:?} branch {branch}");
            }
        }
    }
}

#[test]
fn cantilever_matches_mattiasson() {
    for scheme in SCHEMES {
        let mut c = solver(scheme, 1e-8);
        for (load, want) in Cantilever::MATTIASSON {
            let prob = Cantilever { load };
            let sol = c.solve(&prob, &prob.guess()).unwrap();
            let got = Cantilever::quantities(sol.left(), sol.right());
            println!(
                "{scheme:?} P = {load}: {got:.6?} ({} nodes, {} passes)",
                sol.len(),
                sol.stats.mesh_passes
            );
            for j in 0..4 {
                // Table printed to 5 decimals: half a unit (5e-6) plus the solve's 1e-6 margin.
                assert!(
                    (got[j] - want[j]).abs() <= 6e-6,
                    "{scheme:?} P = {load}, quantity {j}: {} vs {}",
                    got[j],
                    want[j]
                );
            }
        }
    }
}

#[test]
fn warm_start_reuses_mesh_and_symbolic_factorization() {
    let bratu = Bratu { lambda: 1.0 };
    for scheme in SCHEMES {
        let mut c = solver(scheme, 1e-8);
        let sol = c.solve(&bratu, &bratu.guess()).unwrap();
        let sym = c.symbolic_factorizations();
        let again = c.solve(&bratu, &Guess::from(&sol)).unwrap();
        assert_eq!(again.mesh, sol.mesh);
        assert_eq!(again.stats.mesh_passes, 1);
        assert!(again.stats.newton_iters <= 1, "{}", again.stats);
        assert_eq!(
            c.symbolic_factorizations(),
            sym,
            "symbolic LU must be reused"
        );
        // Nearby problem (continuation step) from the previous solution.
        let near = Bratu { lambda: 1.05 };
        let sol2 = c.solve(&near, &Guess::from(&sol)).unwrap();
        let (nodal, _) = max_errors(&sol2, |s| near.exact(0, s));
        assert!(nodal <= 1e-7);
    }
}

#[test]
fn short_guess_mesh_uses_default_mesh() {
    let guess = Guess::constant(0.0, 1.0, 2, &[0.0, 0.0], vec![]);
    for scheme in SCHEMES {
        let sol = solver(scheme, 1e-6).solve(&LinearSinh, &guess).unwrap();
        let (nodal, _) = max_errors(&sol, LinearSinh::exact);
        assert!(nodal <= 1e-5);
    }
}

#[test]
fn node_cap_reports_mesh_limit() {
    let prob = Cantilever { load: 10.0 };
    for scheme in SCHEMES {
        let mut c = Collocation::new(CollocationOptions {
            scheme,
            tol: 1e-10,
            max_nodes: 12,
            ..Default::default()
        })
        .unwrap();
        match c.solve(&prob, &prob.guess()) {
            Err(BvpError::MeshLimit {
                max_nodes,
                needed,
                residual,
                stats,
            }) => {
                assert_eq!(max_nodes, 12);
                assert!(needed > 12 && residual > 1e-10);
                assert!(stats.newton_iters > 0 && stats.nodes > 0 && stats.mesh_passes > 0);
            }
            other => panic!("{scheme:?}: expected MeshLimit, got {other:?}"),
        }
    }
}

#[test]
fn nan_rhs_is_reported() {
    for scheme in SCHEMES {
        let r = solver(scheme, 1e-6).solve(&NanRhs, &NanRhs::guess());
        match r {
            Err(BvpError::NonFinite { s, .. }) => {
                assert!(s.is_nan() || (s > 1.0 && s <= 4.0), "s = {s}")
            }
            other => panic!("{scheme:?}: expected NonFinite, got {other:?}"),
        }
    }
}

#[test]
fn no_solution_is_reported() {
    for scheme in SCHEMES {
        let r = solver(scheme, 1e-6).solve(&NoSolution, &NoSolution::guess());
        match r {
            Err(
                e @ (BvpError::Stalled { .. }
                | BvpError::MaxIterations { .. }
                | BvpError::SingularJacobian { .. }),
            ) => {
                assert!(e.stats().is_some());
            }
            other => panic!("{scheme:?}: expected a Newton failure, got {other:?}"),
        }
    }
}

#[test]
fn singular_jacobian_is_reported() {
    for scheme in SCHEMES {
        let r = solver(scheme, 1e-6).solve(&SingularNeumann, &SingularNeumann::guess());
        match r {
            Err(e @ BvpError::SingularJacobian { .. }) => {
                eprintln!("{scheme:?}: {e}");
                assert_eq!(e.status(), Status::SingularJacobian);
                assert!(e.stats().is_some_and(|st| st.rhs_evals > 0 && st.nodes > 0));
            }
            other => panic!("{scheme:?}: expected SingularJacobian, got {other:?}"),
        }
    }
}

#[test]
fn bad_guess_dimensions_are_rejected() {
    let guess = Guess::constant(0.0, 1.0, 5, &[0.0], vec![]);
    let r = solver(Scheme::Lobatto4, 1e-6).solve(&LinearSinh, &guess);
    assert!(matches!(r, Err(BvpError::Dimension { .. })), "{r:?}");
    let guess = Guess::constant(0.0, 1.0, 5, &[0.0, 0.0], vec![1.0]);
    let r = solver(Scheme::Lobatto4, 1e-6).solve(&LinearSinh, &guess);
    assert!(matches!(r, Err(BvpError::Dimension { .. })), "{r:?}");
    let _ = LinearSinh.dims();
}

#[test]
fn finite_difference_jacobians_give_the_same_answer() {
    // Eigen has an unknown parameter, so ∂F/∂p and ∂g/∂p are differenced too.
    for scheme in SCHEMES {
        let tol = 1e-8;
        let analytic = solver(scheme, tol).solve(&Eigen, &Eigen::guess()).unwrap();
        let fd = solver(scheme, tol)
            .solve(&FiniteDifferences(Eigen), &Eigen::guess())
            .unwrap();
        let want = Eigen::eigenvalue(1);
        assert!(
            (fd.params[0] - want).abs() <= 10.0 * tol * want,
            "{}",
            fd.params[0]
        );
        assert!((fd.params[0] - analytic.params[0]).abs() <= 10.0 * tol * want);
        // Forward differences: n + k extra rhs evaluations per Jacobian evaluation.
        assert!(fd.stats.rhs_evals > analytic.stats.rhs_evals);
        assert!(fd.stats.jac_evals > 0 && fd.stats.bc_evals > analytic.stats.bc_evals);
    }
}

#[test]
fn exact_start_with_finite_difference_jacobians_is_accepted() {
    // The conditioning check at acceptance must linearize at the solution even when Newton did
    // not factorize on the accepted mesh (coarsened mesh, warm start): it once differenced the
    // boundary conditions against its own right-hand side and reported SingularJacobian here.
    for scheme in SCHEMES {
        for end in [0.5, 1.0, -2.0] {
            let exact = Parabola { end };
            let prob = FiniteDifferences(exact);
            let mut c = solver(scheme, 1e-9);
            let sol = c
                .solve(&prob, &Parabola::guess())
                .unwrap_or_else(|e| panic!("{scheme:?} end {end}: {e}"));
            // Exact polynomial: only rounding and the √ε differences remain.
            let check = |sol: &Solution| {
                assert!(
                    (sol.params[0] - exact.parameter()).abs() <= 1e-10,
                    "{scheme:?} p"
                );
                let (nodal, dense) = max_errors(sol, |s| exact.exact(s));
                assert!(nodal <= 1e-10 && dense <= 1e-10, "{nodal:e} {dense:e}");
            };
            check(&sol);
            let again = c
                .solve(&prob, &Guess::from(&sol))
                .unwrap_or_else(|e| panic!("{scheme:?} end {end}, warm: {e}"));
            assert_eq!(again.stats.newton_iters, 0, "{}", again.stats);
            check(&again);
        }
    }
}

#[test]
fn overly_fine_guess_mesh_is_coarsened() {
    let fine = Guess::from_fn(
        2,
        (0..=2000).map(|i| i as f64 / 2000.0).collect(),
        vec![],
        |s, z| z.copy_from_slice(&LinearSinh::exact(s)),
    );
    for scheme in SCHEMES {
        let tol = 1e-6;
        let sol = solver(scheme, tol).solve(&LinearSinh, &fine).unwrap();
        let (nodal, _) = max_errors(&sol, LinearSinh::exact);
        println!(
            "{scheme:?}: 2001 guess nodes -> {} nodes, {} passes",
            sol.len(),
            sol.stats.mesh_passes
        );
        assert!(sol.len() <= 200, "{} nodes", sol.len());
        assert!(nodal <= 10.0 * tol);
        assert!(sol.stats.error_estimate.unwrap() <= tol);
    }
}

#[test]
fn statistics_are_filled_in() {
    let prob = Cantilever { load: 2.0 };
    let sol = solver(Scheme::Lobatto4, 1e-6)
        .solve(&prob, &prob.guess())
        .unwrap();
    let st = &sol.stats;
    assert_eq!(st.nodes, sol.len());
    assert!(
        st.mesh_passes >= 2,
        "the 11-node guess mesh is too coarse for 1e-6"
    );
    assert!(st.newton_iters >= st.mesh_passes - 1 && st.factorizations >= st.newton_iters);
    assert!(st.rhs_evals > 0 && st.jac_evals > 0 && st.bc_evals > 0);
    assert!(st.residual <= 1e-10);
    let est = st.error_estimate.unwrap();
    assert!(est > 0.0 && est <= 1e-6);
    assert_eq!(sol.dz.len(), sol.z.len());
    // dz holds F at the nodes.
    let mut f = [0.0; 4];
    prob.rhs(sol.mesh[3], sol.node(3), &[], &mut f);
    assert_eq!(&sol.dz[12..16], &f);
}

#[test]
fn higher_order_needs_fewer_nodes() {
    let bratu = Bratu { lambda: 1.0 };
    let nodes = |scheme| {
        solver(scheme, 1e-10)
            .solve(&bratu, &bratu.guess())
            .unwrap()
            .len()
    };
    let (n4, n6) = (nodes(Scheme::Lobatto4), nodes(Scheme::Lobatto6));
    println!("Bratu tol 1e-10: Lobatto4 {n4} nodes, Lobatto6 {n6} nodes");
    // Residual O(h³) vs O(h⁴): h ∝ tol^(1/3) vs tol^(1/4), i.e. ≈ 5× fewer intervals at 1e-10.
    assert!(2 * n6 < n4, "{n6} vs {n4}");
}

#[test]
fn malformed_input_is_an_error_not_a_panic() {
    // NaN in the guess: rejected before any evaluation (it used to surface as NonFinite).
    let guess = Guess::constant(0.0, 1.0, 5, &[f64::NAN, 0.0], vec![]);
    let r = solver(Scheme::Lobatto6, 1e-6).solve(&LinearSinh, &guess);
    assert!(
        matches!(r, Err(BvpError::InvalidGuess { what: "values", .. })),
        "{r:?}"
    );
    // Non-increasing guess mesh: an error naming the node (it used to be silently replaced by
    // the default mesh).
    let guess = Guess::from_fn(2, vec![0.0, 0.7, 0.3, 1.0], vec![], |s, z| {
        z[0] = s;
        z[1] = 1.0;
    });
    let r = solver(Scheme::Lobatto4, 1e-6).solve(&LinearSinh, &guess);
    assert!(
        matches!(
            r,
            Err(BvpError::InvalidGuess {
                what: "mesh",
                index: 2,
                ..
            })
        ),
        "{r:?}"
    );
    // Wrong parameter count for a problem with an unknown parameter.
    let mut g = Eigen::guess();
    g.params.clear();
    let r = solver(Scheme::Lobatto4, 1e-6).solve(&Eigen, &g);
    assert!(matches!(r, Err(BvpError::Dimension { .. })), "{r:?}");
}

/// Issue 34: Lobatto6 converges from the bvp4c tutorial's Falkner–Skan guess `(f, f', f'') ≡
/// (0, 0, 1)` on 5 nodes of `[0, ∞ = 6]` (and `[0, 10]`), `β = 0.5`, like Lobatto4: its Newton
/// failed on the first mesh (damped and homotopy), it restarts from Lobatto4's solution at
/// `max(tol, 1e-3)` (it stalled on 8 299 nodes after 4.7 s). `f''(0) = 0.927680` (Falkner–Skan
/// tables, e.g. White, *Viscous Fluid Flow*, β = 0.5; the same to 1e-8 on `[0, 6]` and
/// `[0, 10]` here).
#[test]
fn lobatto6_from_the_falkner_skan_tutorial_guess() {
    for inf in [6.0, 10.0] {
        let beta = 0.5;
        let p = bvp::from_fns(
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
        );
        let guess = Guess::constant(0.0, inf, 5, &[0.0, 0.0, 1.0], vec![]);
        for scheme in [Scheme::Lobatto4, Scheme::Lobatto6] {
            let sol = solver(scheme, 1e-6)
                .solve(&p, &guess)
                .unwrap_or_else(|e| panic!("{scheme:?} on [0, {inf}]: {e}"));
            let fpp = sol.node(0)[2];
            assert!(
                (fpp - 0.927680).abs() < 1e-5,
                "{scheme:?} on [0, {inf}]: {fpp}"
            );
            assert!(sol.len() < 100, "{scheme:?}: {} nodes", sol.len());
        }
    }
}
