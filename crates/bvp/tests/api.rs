//! The problem-definition API: closures ([`bvp::from_fns`]), array problems with row Jacobians,
//! option defaults and non-uniform multiple shooting.

use bvp::fixed::{Fixed, FixedBvp, SimpleBvp};
use bvp::samples::LinearSinh;
use bvp::{
    from_fns, Bvp, BvpError, BvpSolver, Collocation, CollocationOptions, Dims, Guess, Integrator,
    Shooting, ShootingOptions,
};

/// 21 equal nodes on `[0, π]`.
fn mesh() -> Vec<f64> {
    (0..21)
        .map(|i| std::f64::consts::PI * i as f64 / 20.0)
        .collect()
}

/// The guess of the eigenproblems `y'' = −λ y`, `y(0) = y(π) = 0`, `y'(0) = 1`: `y = sin s` on
/// [`mesh`], `λ = lam`.
fn eigen_guess(lam: f64) -> Guess {
    Guess::from_fn(2, mesh(), vec![lam], |s, z| {
        z[0] = s.sin();
        z[1] = s.cos();
    })
}

/// `y'' = y`, `y(0) = 0`, `y(1) = 1` as closures: `y = sinh s / sinh 1`.
#[test]
fn closure_problem_solves_like_the_struct() {
    let p = from_fns(
        2,
        (0.0, 1.0),
        |_s, z, _p, dz| {
            dz[0] = z[1];
            dz[1] = z[0];
        },
        |za, zb, _p, r| {
            r[0] = za[0];
            r[1] = zb[0] - 1.0;
        },
    )
    .with_rhs_jacobian(|_s, _z, _p, dfdz, _dfdp| dfdz.copy_from_slice(&[0.0, 1.0, 1.0, 0.0]))
    .with_bc_jacobian(|_za, _zb, _p, dga, dgb, _dgp| {
        dga.copy_from_slice(&[1.0, 0.0, 0.0, 0.0]);
        dgb.copy_from_slice(&[0.0, 0.0, 1.0, 0.0]);
    });
    assert_eq!(p.dims(), Dims { n: 2, k: 0 });
    let mut jz = [0.0; 4];
    assert!(p.rhs_jacobian(0.3, &[1.0, 2.0], &[], &mut jz, &mut []));
    assert_eq!(jz, [0.0, 1.0, 1.0, 0.0]);
    let sol = Collocation::new(CollocationOptions::default())
        .unwrap()
        .solve(&p, &LinearSinh::guess())
        .unwrap();
    for s in [0.0, 0.25, 0.7, 1.0] {
        let e = LinearSinh::exact(s);
        assert!((sol.at(s)[0] - e[0]).abs() < 1e-6, "s = {s}");
    }
}

/// An eigenvalue problem with a parameter, as closures without Jacobians: `y'' = −λ y`,
/// `y(0) = y(π) = 0`, `y'(0) = 1`, first eigenvalue `λ = 1`.
#[test]
fn closure_problem_with_parameter() {
    let p = from_fns(
        2,
        (0.0, std::f64::consts::PI),
        |_s, z, p, dz| {
            dz[0] = z[1];
            dz[1] = -p[0] * z[0];
        },
        |za, zb, _p, r| {
            r[0] = za[0];
            r[1] = zb[0];
            r[2] = za[1] - 1.0;
        },
    )
    .with_params(1);
    let guess = eigen_guess(1.2);
    let sol = Shooting::new(ShootingOptions::default())
        .unwrap()
        .solve(&p, &guess)
        .unwrap();
    assert!((sol.params[0] - 1.0).abs() < 1e-9, "{}", sol.params[0]);
}

/// `y'' = −λ y` with `k = 1` written with arrays and row Jacobians, checked against finite
/// differences through the [`Bvp`] view (the row layout must land in the flat row-major one).
struct ArrayEigen;

impl FixedBvp<2, 1> for ArrayEigen {
    fn interval(&self) -> (f64, f64) {
        (0.0, std::f64::consts::PI)
    }
    fn rhs(&self, _s: f64, z: &[f64; 2], p: &[f64; 1]) -> [f64; 2] {
        [z[1], -p[0] * z[0]]
    }
    fn bc(&self, za: &[f64; 2], zb: &[f64; 2], _p: &[f64; 1], res: &mut [f64]) {
        res[0] = za[0];
        res[1] = zb[0];
        res[2] = za[1] - 1.0;
    }
    fn rhs_jacobian(&self, _s: f64, _z: &[f64; 2], p: &[f64; 1], dfdz: &mut [[f64; 2]; 2]) -> bool {
        *dfdz = [[0.0, 1.0], [-p[0], 0.0]];
        true
    }
    fn rhs_param_jacobian(
        &self,
        _s: f64,
        z: &[f64; 2],
        _p: &[f64; 1],
        dfdp: &mut [[f64; 1]; 2],
    ) -> bool {
        *dfdp = [[0.0], [-z[0]]];
        true
    }
    fn bc_jacobian(
        &self,
        _za: &[f64; 2],
        _zb: &[f64; 2],
        _p: &[f64; 1],
        dga: &mut [[f64; 2]],
        dgb: &mut [[f64; 2]],
    ) -> bool {
        assert_eq!((dga.len(), dgb.len()), (3, 3));
        dga.copy_from_slice(&[[1.0, 0.0], [0.0, 0.0], [0.0, 1.0]]);
        dgb.copy_from_slice(&[[0.0, 0.0], [1.0, 0.0], [0.0, 0.0]]);
        true
    }
    fn bc_param_jacobian(
        &self,
        _za: &[f64; 2],
        _zb: &[f64; 2],
        _p: &[f64; 1],
        dgp: &mut [[f64; 1]],
    ) -> bool {
        assert_eq!(dgp.len(), 3);
        dgp.copy_from_slice(&[[0.0]; 3]);
        true
    }
}

#[test]
fn array_rows_are_row_major() {
    let p = Fixed(ArrayEigen);
    let (z, q) = ([0.7, -0.2], [1.3]);
    let (mut jz, mut jp) = ([0.0; 4], [0.0; 2]);
    assert!(p.rhs_jacobian(0.1, &z, &q, &mut jz, &mut jp));
    assert_eq!(jz, [0.0, 1.0, -1.3, 0.0]);
    assert_eq!(jp, [0.0, -0.7]);
    let (mut ga, mut gb, mut gp) = ([9.0; 6], [9.0; 6], [9.0; 3]);
    assert!(p.bc_jacobian(&z, &z, &q, &mut ga, &mut gb, &mut gp));
    assert_eq!(ga, [1.0, 0.0, 0.0, 0.0, 0.0, 1.0]);
    assert_eq!(gb, [0.0, 0.0, 1.0, 0.0, 0.0, 0.0]);
    assert_eq!(gp, [0.0; 3]);
    let guess = eigen_guess(0.8);
    let sol = Collocation::new(CollocationOptions::default())
        .unwrap()
        .solve(&p, &guess)
        .unwrap();
    assert!((sol.params[0] - 1.0).abs() < 1e-6, "{}", sol.params[0]);
}

/// The same problem without its parameter Jacobians: the state parts alone are not a whole
/// Jacobian, so the view reports none and the solvers difference all of it.
struct ArrayEigenStateJacobians;

impl FixedBvp<2, 1> for ArrayEigenStateJacobians {
    fn interval(&self) -> (f64, f64) {
        ArrayEigen.interval()
    }
    fn rhs(&self, s: f64, z: &[f64; 2], p: &[f64; 1]) -> [f64; 2] {
        ArrayEigen.rhs(s, z, p)
    }
    fn bc(&self, za: &[f64; 2], zb: &[f64; 2], p: &[f64; 1], res: &mut [f64]) {
        ArrayEigen.bc(za, zb, p, res)
    }
    fn rhs_jacobian(&self, s: f64, z: &[f64; 2], p: &[f64; 1], dfdz: &mut [[f64; 2]; 2]) -> bool {
        ArrayEigen.rhs_jacobian(s, z, p, dfdz)
    }
    fn bc_jacobian(
        &self,
        za: &[f64; 2],
        zb: &[f64; 2],
        p: &[f64; 1],
        dga: &mut [[f64; 2]],
        dgb: &mut [[f64; 2]],
    ) -> bool {
        ArrayEigen.bc_jacobian(za, zb, p, dga, dgb)
    }
}

#[test]
fn partial_jacobians_fall_back_to_differences() {
    let p = Fixed(ArrayEigenStateJacobians);
    let (z, q) = ([0.7, -0.2], [1.3]);
    let (mut jz, mut jp) = ([0.0; 4], [0.0; 2]);
    assert!(!p.rhs_jacobian(0.1, &z, &q, &mut jz, &mut jp));
    let (mut ga, mut gb, mut gp) = ([0.0; 6], [0.0; 6], [0.0; 3]);
    assert!(!p.bc_jacobian(&z, &z, &q, &mut ga, &mut gb, &mut gp));
    let guess = eigen_guess(0.8);
    let sol = Collocation::new(CollocationOptions::default())
        .unwrap()
        .solve(&p, &guess)
        .unwrap();
    assert!((sol.params[0] - 1.0).abs() < 1e-6, "{}", sol.params[0]);
}

#[test]
fn bc_tol_defaults_to_tol() {
    let o = CollocationOptions {
        tol: 1e-5,
        ..Default::default()
    };
    assert_eq!(o.bc_tol, None);
    assert_eq!(o.bc_tol(), 1e-5);
    let o = CollocationOptions {
        bc_tol: Some(1e-9),
        ..o
    };
    assert_eq!(o.bc_tol(), 1e-9);
}

/// Non-uniform segments give the same solution as uniform ones; RK4 steps follow the lengths.
#[test]
fn non_uniform_multiple_shooting() {
    let nodes = vec![0.0, 0.1, 0.15, 0.5, 1.0];
    for integrator in [
        Integrator::Rk4 { steps: 200 },
        Integrator::Adaptive {
            rtol: 1e-10,
            atol: 1e-12,
        },
    ] {
        let mut s = Shooting::new(ShootingOptions {
            integrator,
            nodes: nodes.clone(),
            ..Default::default()
        })
        .unwrap();
        let sol = s.solve(&LinearSinh, &LinearSinh::guess()).unwrap();
        assert_eq!(sol.stats.nodes, 5);
        for &t in &nodes {
            let e = LinearSinh::exact(t);
            assert!((sol.at(t)[0] - e[0]).abs() < 1e-8, "t = {t}");
            assert!((sol.at(t)[1] - e[1]).abs() < 1e-8, "t = {t}");
        }
        if let Integrator::Rk4 { steps } = integrator {
            // One node per RK4 step, segments included.
            assert_eq!(sol.mesh.len(), steps + 1);
        }
    }
}

#[test]
fn bad_shooting_nodes_are_rejected() {
    let bad = ShootingOptions {
        nodes: vec![0.0, 0.5, 0.5, 1.0],
        ..Default::default()
    };
    assert!(matches!(
        Shooting::new(bad),
        Err(BvpError::InvalidOption { name: "nodes", .. })
    ));
    // Valid on their own, but not spanning the problem's interval [0, 1].
    let mut s = Shooting::new(ShootingOptions {
        nodes: vec![0.0, 0.5, 2.0],
        ..Default::default()
    })
    .unwrap();
    assert!(matches!(
        s.solve(&LinearSinh, &LinearSinh::guess()),
        Err(BvpError::InvalidOption { name: "nodes", .. })
    ));
}

/// `y'' = −y`, `y(0) = 0`, `y(π/2) = 1` (`y = sin s`) as a [`SimpleBvp`] (no parameter
/// arguments) with analytic Jacobians.
struct SineSimple;

impl SimpleBvp<2> for SineSimple {
    fn interval(&self) -> (f64, f64) {
        (0.0, std::f64::consts::FRAC_PI_2)
    }
    fn rhs(&self, _s: f64, z: &[f64; 2]) -> [f64; 2] {
        [z[1], -z[0]]
    }
    fn bc(&self, za: &[f64; 2], zb: &[f64; 2]) -> [f64; 2] {
        [za[0], zb[0] - 1.0]
    }
    fn rhs_jacobian(&self, _s: f64, _z: &[f64; 2], dfdz: &mut [[f64; 2]; 2]) -> bool {
        *dfdz = [[0.0, 1.0], [-1.0, 0.0]];
        true
    }
    fn bc_jacobian(
        &self,
        _za: &[f64; 2],
        _zb: &[f64; 2],
        dga: &mut [[f64; 2]; 2],
        dgb: &mut [[f64; 2]; 2],
    ) -> bool {
        *dga = [[1.0, 0.0], [0.0, 0.0]];
        *dgb = [[0.0, 0.0], [1.0, 0.0]];
        true
    }
}

/// The same problem implemented as a parameter-free [`FixedBvp`] directly (still possible next
/// to the blanket implementation for [`SimpleBvp`]), without Jacobians.
struct SineFixed;

impl FixedBvp<2> for SineFixed {
    fn interval(&self) -> (f64, f64) {
        (0.0, std::f64::consts::FRAC_PI_2)
    }
    fn rhs(&self, _s: f64, z: &[f64; 2], _p: &[f64; 0]) -> [f64; 2] {
        [z[1], -z[0]]
    }
    fn bc(&self, za: &[f64; 2], zb: &[f64; 2], _p: &[f64; 0], res: &mut [f64]) {
        res[0] = za[0];
        res[1] = zb[0] - 1.0;
    }
}

#[test]
fn simple_problems_are_fixed_problems() {
    let p = Fixed(SineSimple);
    assert_eq!(p.dims(), Dims { n: 2, k: 0 });
    let (z, q): ([f64; 2], [f64; 0]) = ([0.3, 0.4], []);
    let (mut jz, mut jp) = ([0.0; 4], [0.0; 0]);
    assert!(p.rhs_jacobian(0.1, &z, &q, &mut jz, &mut jp));
    assert_eq!(jz, [0.0, 1.0, -1.0, 0.0]);
    let (mut ga, mut gb, mut gp) = ([9.0; 4], [9.0; 4], [0.0; 0]);
    assert!(p.bc_jacobian(&z, &z, &q, &mut ga, &mut gb, &mut gp));
    assert_eq!((ga, gb), ([1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]));
    let mut res = [9.0; 2];
    p.bc(&z, &[1.5, 0.0], &q, &mut res);
    assert_eq!(res, [0.3, 0.5]);
    let guess = Guess::constant(0.0, std::f64::consts::FRAC_PI_2, 11, &[0.5, 0.5], vec![]);
    let mut solver = Collocation::new(CollocationOptions {
        tol: 1e-8,
        ..CollocationOptions::default()
    })
    .unwrap();
    let a = solver.solve(&p, &guess).unwrap();
    let b = solver.solve(&Fixed(SineFixed), &guess).unwrap();
    for (i, &s) in a.mesh.iter().enumerate() {
        assert!((a.node(i)[0] - s.sin()).abs() < 1e-7, "{s}");
    }
    for (i, &s) in b.mesh.iter().enumerate() {
        assert!((b.node(i)[0] - s.sin()).abs() < 1e-7, "{s}");
    }
}

/// Every malformed guess is a typed error from every solver, naming the entry (issue 24: a mesh
/// `[0, 1, 0.5]` or one not spanning the interval was silently replaced by a uniform one).
#[test]
fn malformed_guesses_are_typed_errors() {
    let mk = |mesh: Vec<f64>| Guess::from_fn(2, mesh, vec![], |s, z| z.copy_from_slice(&[s, 1.0]));
    let mut nan_value = mk(vec![0.0, 0.5, 1.0]);
    nan_value.z[3] = f64::NAN;
    let cases = [
        (mk(vec![0.0, 1.0, 0.5]), "mesh", 2),
        (mk(vec![0.0, 0.5]), "mesh", 1),
        (mk(vec![0.1, 0.5, 1.0]), "mesh", 0),
        (mk(vec![0.0, f64::NAN, 1.0]), "mesh", 1),
        (nan_value, "values", 3),
    ];
    let mut coll = Collocation::new(CollocationOptions::default()).unwrap();
    let mut shoot = Shooting::new(ShootingOptions::default()).unwrap();
    for (guess, what, index) in cases {
        for r in [
            coll.solve(&LinearSinh, &guess),
            shoot.solve(&LinearSinh, &guess),
        ] {
            match r {
                Err(BvpError::InvalidGuess {
                    what: w, index: i, ..
                }) => assert_eq!((w, i), (what, index), "{:?}", guess.mesh),
                other => panic!("{:?}: {other:?}", guess.mesh),
            }
        }
    }
    // Shape errors stay dimension errors; a one-node guess (a constant) is valid.
    let short = Guess {
        z: vec![0.0; 3],
        ..mk(vec![0.0, 1.0])
    };
    assert!(matches!(
        coll.solve(&LinearSinh, &short),
        Err(BvpError::Dimension {
            what: "guess values",
            ..
        })
    ));
    let one = Guess::from_fn(2, vec![0.3], vec![], |_, z| z.copy_from_slice(&[0.5, 1.0]));
    assert!(coll.solve(&LinearSinh, &one).is_ok());
    assert!(shoot.solve(&LinearSinh, &one).is_ok());
}

/// The derivative of the dense output (scipy's `sol(x, 1)`) for every kind of dense output:
/// equal to `dz` at the nodes and close to the exact `y'`, `y''` between them; and the
/// per-interval residuals of the returned solution are small.
#[test]
fn derivatives_and_residuals_of_the_solution() {
    use bvp::Scheme;
    let exact = LinearSinh::exact; // (sinh s, cosh s) / sinh 1
    let mut sols = Vec::new();
    for scheme in [Scheme::Lobatto4, Scheme::Lobatto6] {
        let mut s = Collocation::new(CollocationOptions {
            scheme,
            tol: 1e-8,
            ..CollocationOptions::default()
        })
        .unwrap();
        sols.push((
            format!("{scheme:?}"),
            s.solve(&LinearSinh, &LinearSinh::guess()).unwrap(),
        ));
    }
    for integrator in [
        Integrator::Rk4 { steps: 200 },
        Integrator::Adaptive {
            rtol: 1e-10,
            atol: 1e-10,
        },
    ] {
        let mut s = Shooting::new(ShootingOptions {
            integrator,
            ..ShootingOptions::default()
        })
        .unwrap();
        sols.push((
            format!("{integrator:?}"),
            s.solve(&LinearSinh, &LinearSinh::guess()).unwrap(),
        ));
    }
    for (name, sol) in &sols {
        for i in 0..sol.len() {
            let d = sol.derivative_at(sol.mesh[i]);
            for (got, want) in d.iter().zip(&sol.dz[i * 2..i * 2 + 2]) {
                assert!(
                    (got - want).abs() <= 1e-9 * (1.0 + want.abs()),
                    "{name} node {i}"
                );
            }
        }
        for k in 0..50 {
            let s = (k as f64 + 0.37) / 50.0;
            let d = sol.derivative_at(s);
            let e = exact(s);
            // y' = cosh/sinh 1 and y'' = y.
            assert!(
                (d[0] - e[1]).abs() < 1e-6,
                "{name} s {s}: y' {} vs {}",
                d[0],
                e[1]
            );
            assert!(
                (d[1] - e[0]).abs() < 1e-6,
                "{name} s {s}: y'' {} vs {}",
                d[1],
                e[0]
            );
        }
        let worst = sol
            .residuals(&LinearSinh)
            .iter()
            .fold(0.0_f64, |m, v| m.max(*v));
        assert!(worst < 1e-6, "{name}: residual {worst:e}");
    }
}

/// The observer sees every mesh pass, the last one converged within tol.
#[test]
fn collocation_progress_is_observed() {
    let mut passes = Vec::new();
    let mut s = Collocation::new(CollocationOptions {
        tol: 1e-8,
        ..CollocationOptions::default()
    })
    .unwrap();
    let sol = s
        .solve_observed(&LinearSinh, &LinearSinh::guess(), &mut |p| {
            let max = p.residuals.iter().fold(0.0_f64, |m, v| m.max(*v));
            passes.push((p.pass, p.mesh.len(), p.newton_converged, max));
        })
        .unwrap();
    assert_eq!(passes.len(), sol.stats.mesh_passes, "{passes:?}");
    assert!(passes.len() >= 2, "{passes:?}");
    assert!(passes.iter().enumerate().all(|(i, p)| p.0 == i + 1));
    assert!(
        passes
            .iter()
            .any(|p| p.2 && p.3 <= 1e-8 && p.1 == sol.len()),
        "{passes:?}"
    );
}
