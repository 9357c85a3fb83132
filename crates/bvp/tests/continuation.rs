//! Continuation: Bratu through its fold (closed form), linear families with closed-form branches,
//! `point_at` against direct solves, natural continuation stopping at a fold, the extended
//! problem's Jacobians, option validation.
//!
//! Reference values:
//! - Bratu `u'' + λ eᵘ = 0`, `u(0) = u(1) = 0`: `u = −2 ln(cosh((x − ½)θ/2) / cosh(θ/4))` with
//!   `θ = √(2λ) cosh(θ/4)`; so `u'(0) = θ tanh(θ/4)`, `u(½) = 2 ln cosh(θ/4)`. The fold is where
//!   `(θ/4) tanh(θ/4) = 1`; `λ_c = 3.51383071912516` (e.g. Ascher, Mattheij & Russell, *Numerical
//!   Solution of BVPs for ODEs*, and Boyd 2011 "One-point pseudospectral collocation for the
//!   one-dimensional Bratu equation"). The roots are computed here by bisection on the closed form.
//! - `y'' = y, y(0) = 0, y(1) = λ`: `y = λ sinh(x)/sinh(1)`.
//! - `y'' = p, y(0) = 0, y'(0) = 0, y(1) = λ` (p unknown): `y = λx²`, `p = 2λ`.

use bvp::continuation::{Arclength, Continuation, ContinuationOptions, FoldKind, Member, Method};
use bvp::{
    Bvp, BvpError, BvpSolver, Collocation, CollocationOptions, Dims, Guess, Integrator, ParamBvp,
    Scheme, Shooting, ShootingOptions, Solution, Status,
};

const LAMBDA_C: f64 = 3.51383071912516;

/// Bratu family with analytic Jacobians (or without, to exercise finite differences).
struct Bratu {
    jacobians: bool,
}

impl ParamBvp for Bratu {
    fn dims(&self) -> Dims {
        Dims { n: 2, k: 0 }
    }
    fn interval(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn rhs(&self, _s: f64, z: &[f64], _p: &[f64], l: f64, dz: &mut [f64]) {
        dz[0] = z[1];
        dz[1] = -l * z[0].exp();
    }
    fn bc(&self, za: &[f64], zb: &[f64], _p: &[f64], _l: f64, r: &mut [f64]) {
        r[0] = za[0];
        r[1] = zb[0];
    }
    fn rhs_jacobian(
        &self,
        _s: f64,
        z: &[f64],
        _p: &[f64],
        l: f64,
        dfdz: &mut [f64],
        _dfdp: &mut [f64],
        dfdl: &mut [f64],
    ) -> bool {
        if !self.jacobians {
            return false;
        }
        dfdz.copy_from_slice(&[0.0, 1.0, -l * z[0].exp(), 0.0]);
        dfdl.copy_from_slice(&[0.0, -z[0].exp()]);
        true
    }
    fn bc_jacobian(
        &self,
        _za: &[f64],
        _zb: &[f64],
        _p: &[f64],
        _l: f64,
        dga: &mut [f64],
        dgb: &mut [f64],
        _dgp: &mut [f64],
        dgl: &mut [f64],
    ) -> bool {
        if !self.jacobians {
            return false;
        }
        dga.copy_from_slice(&[1.0, 0.0, 0.0, 0.0]);
        dgb.copy_from_slice(&[0.0, 0.0, 1.0, 0.0]);
        dgl.fill(0.0);
        true
    }
}

fn bisect(mut lo: f64, mut hi: f64, f: impl Fn(f64) -> f64) -> f64 {
    let flo = f(lo);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if (f(mid) > 0.0) == (flo > 0.0) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// θ at the fold: (θ/4) tanh(θ/4) = 1.
fn theta_c() -> f64 {
    4.0 * bisect(0.5, 2.0, |x| x * x.tanh() - 1.0)
}

/// Exact θ(λ) on the lower (`upper = false`) or upper branch.
fn theta(lambda: f64, upper: bool) -> f64 {
    let f = |t: f64| t - (2.0 * lambda).sqrt() * (t / 4.0).cosh();
    let tc = theta_c();
    if upper {
        bisect(tc, 60.0, f)
    } else {
        bisect(0.0, tc, f)
    }
}

/// Exact (u'(0), u(1/2)).
fn bratu_exact(lambda: f64, upper: bool) -> (f64, f64) {
    let t = theta(lambda, upper);
    (t * (t / 4.0).tanh(), 2.0 * (t / 4.0).cosh().ln())
}

/// Checks a computed Bratu solution against the closed form, in the well-conditioned direction
/// (also at the fold): θ from the computed u'(0) = θ tanh(θ/4) (monotone in θ), then
/// λ(θ) = θ²/(2 cosh²(θ/4)) against the computed λ (relative `tol`) and u(1/2) = 2 ln cosh(θ/4)
/// against the interpolated solution (relative `tol_mid`). Returns θ.
fn check_bratu(lambda: f64, sol: &Solution, tol: f64, tol_mid: f64) -> f64 {
    let du0 = sol.left()[1];
    let t = bisect(0.0, 60.0, |t| t * (t / 4.0).tanh() - du0);
    let c = (t / 4.0).cosh();
    let l_exact = t * t / (2.0 * c * c);
    assert!(
        (lambda - l_exact).abs() <= tol * lambda.max(1.0),
        "u'(0) = {du0}: λ = {lambda} vs closed form {l_exact} (error {:.2e})",
        lambda - l_exact
    );
    let umid = 2.0 * c.ln();
    let got = sol.at(0.5)[0];
    assert!(
        (got - umid).abs() <= tol_mid * umid.max(1.0),
        "λ = {lambda}: u(1/2) = {got} vs closed form {umid} (error {:.2e})",
        got - umid
    );
    t
}

fn shooting() -> Shooting {
    Shooting::new(ShootingOptions {
        integrator: Integrator::Adaptive {
            rtol: 1e-12,
            atol: 1e-13,
        },
        ..ShootingOptions::default()
    })
    .unwrap()
}

fn collocation() -> Collocation {
    Collocation::new(CollocationOptions {
        scheme: Scheme::Lobatto6,
        tol: 1e-9,
        ..CollocationOptions::default()
    })
    .unwrap()
}

fn start<P: ParamBvp, S: BvpSolver>(family: &P, solver: &mut S, lambda: f64) -> Solution {
    let guess = Guess::constant(0.0, 1.0, 11, &[0.0, 0.0], vec![0.0; family.dims().k]);
    solver.solve(&Member::new(family, lambda), &guess).unwrap()
}

/// Traces Bratu from λ = 0.1 on the lower branch through the fold back to λ = 0.1 (a bound) on
/// the upper branch; checks every point, the fold and the upper solution at λ = 1.
fn bratu_through_fold<S: BvpSolver>(mut solver: S, jacobians: bool, tol_lambda: f64, tol_mid: f64) {
    let family = Bratu { jacobians };
    let s0 = start(&family, &mut solver, 0.1);
    let opts = ContinuationOptions {
        lambda_min: 0.1,
        lambda_max: 10.0,
        ds: 0.05,
        ds_max: 0.5,
        max_steps: 200,
        fold_tol: 1e-10,
        ..Default::default()
    };
    let mut cont = Continuation::new(&family, solver, s0, 0.1, opts).unwrap();
    let mut folds = vec![];
    let mut upper = false;
    let tc = theta_c();
    let mut last = None;
    let mut prev_sigma = -1.0;
    for p in cont.by_ref() {
        let p = p.unwrap();
        assert!(p.sigma > prev_sigma, "arclength must increase");
        if let Some(f) = &p.fold {
            assert_eq!(f.kind, FoldKind::Max);
            assert!(f.located, "fold not located: {f:?}");
            folds.push(f.clone());
        }
        let t = check_bratu(p.lambda, &p.solution, tol_lambda, tol_mid);
        // λ grows along the lower branch (θ < θ_c) and falls along the upper one; the estimate
        // of dλ/dσ may be off only next to the fold.
        if p.step > 0 && (t - tc).abs() > 0.5 {
            assert_eq!(
                p.dlambda_dsigma > 0.0,
                t < tc,
                "dλ/dσ = {} at λ = {} (θ = {t})",
                p.dlambda_dsigma,
                p.lambda
            );
        }
        if p.step > 0 {
            assert!(p.stats.newton_iters > 0 && p.ds > 0.0);
        }
        // Lower branch (θ < θ_c) first, then the upper one, never back.
        if t > tc {
            upper = true;
        }
        assert!(
            !upper || t > tc,
            "back on the lower branch at λ = {}",
            p.lambda
        );
        prev_sigma = p.sigma;
        last = Some(p);
    }
    assert!(upper, "never reached the upper branch");
    let last = last.unwrap();
    assert!(last.on_bound);
    assert_eq!(last.lambda, 0.1, "must land exactly on the bound");
    assert_eq!(folds.len(), 1, "exactly one fold");
    let f = &folds[0];
    eprintln!(
        "fold λ = {:.15} (error {:.2e}, {} solves), {} points, last σ = {:.3}",
        f.lambda,
        f.lambda - LAMBDA_C,
        f.evaluations,
        last.step + 1,
        last.sigma
    );
    assert!(
        (f.lambda - LAMBDA_C).abs() <= 1e-8,
        "fold at λ = {} vs λ_c = {LAMBDA_C}: error {:.2e}",
        f.lambda,
        f.lambda - LAMBDA_C
    );
    // The fold solution is the one with θ = θ_c.
    assert!((f.solution.left()[1] - tc * (tc / 4.0).tanh()).abs() < 1e-4);
    // Upper branch at λ = 1 via point_at (warm-started from the upper branch, the latest).
    let s = cont.point_at(1.0).unwrap();
    let (du0, umid) = bratu_exact(1.0, true);
    // Every mesh value against u = −2 ln(cosh((x − ½)θ/2)/cosh(θ/4)), u' = −θ tanh((x − ½)θ/2).
    let t1 = theta(1.0, true);
    for (i, &x) in s.mesh.iter().enumerate() {
        let u = -2.0 * (((x - 0.5) * t1 / 2.0).cosh() / (t1 / 4.0).cosh()).ln();
        let du = -t1 * ((x - 0.5) * t1 / 2.0).tanh();
        let z = s.node(i);
        assert!(
            (z[0] - u).abs() <= 1e-9 * u.abs().max(1.0)
                && (z[1] - du).abs() <= 1e-9 * du.abs().max(1.0),
            "upper branch at λ = 1, x = {x}: {z:?} vs ({u}, {du})"
        );
    }
    // u'(0) is a mesh value; u(1/2) comes from the cubic Hermite dense output.
    let err = ((s.left()[1] - du0) / du0).abs();
    assert!(
        err < 1e-9,
        "upper branch at λ = 1: u'(0) relative error {err:.2e}"
    );
    let err_mid = ((s.at(0.5)[0] - umid) / umid).abs();
    assert!(
        err_mid < 1e-6,
        "upper branch at λ = 1: u(1/2) relative error {err_mid:.2e}"
    );
    eprintln!("upper branch at λ = 1: u'(0) rel. error {err:.2e}, u(1/2) rel. error {err_mid:.2e}");
    assert!(
        du0 > 10.0,
        "the exact upper-branch solution at λ = 1 has u'(0) = {du0}"
    );
}

#[test]
fn bratu_fold_shooting() {
    bratu_through_fold(shooting(), true, 1e-10, 1e-6);
}

#[test]
fn bratu_fold_shooting_fd_jacobians() {
    bratu_through_fold(shooting(), false, 1e-10, 1e-6);
}

#[test]
fn bratu_fold_multiple_shooting() {
    let solver = Shooting::new(ShootingOptions {
        integrator: Integrator::Adaptive {
            rtol: 1e-12,
            atol: 1e-13,
        },
        segments: 4,
        ..ShootingOptions::default()
    })
    .unwrap();
    bratu_through_fold(solver, true, 1e-10, 1e-6);
}

#[test]
fn bratu_fold_collocation() {
    bratu_through_fold(collocation(), true, 1e-9, 1e-6);
}

#[test]
fn natural_continuation_stops_at_fold() {
    let family = Bratu { jacobians: true };
    let mut solver = shooting();
    let s0 = start(&family, &mut solver, 0.1);
    let opts = ContinuationOptions {
        method: Method::Natural,
        ds: 0.2,
        ds_min: 1e-4,
        ds_max: 0.5,
        max_steps: 500,
        ..Default::default()
    };
    let mut cont = Continuation::new(&family, solver, s0, 0.1, opts).unwrap();
    let mut last_lambda = f64::NAN;
    let mut err = None;
    for p in cont.by_ref() {
        match p {
            Ok(p) => {
                assert!(p.lambda < LAMBDA_C);
                let t = check_bratu(p.lambda, &p.solution, 1e-10, 1e-6);
                assert!(
                    t < theta_c(),
                    "natural continuation jumped to the upper branch"
                );
                last_lambda = p.lambda;
            }
            Err(e) => err = Some(e),
        }
    }
    let err = err.expect("natural continuation must fail at the fold");
    eprintln!("natural continuation stopped after λ = {last_lambda}: {err}");
    // Reported as the fold it is, with its parameter value (issue 34).
    match &err {
        BvpError::Fold { fold, source, .. } => {
            assert!((fold - LAMBDA_C).abs() < 1e-4, "{err}");
            assert!(
                matches!(
                    source.status(),
                    Status::Stalled
                        | Status::SingularJacobian
                        | Status::MaxIterations
                        | Status::NonFinite
                ),
                "{:?}",
                source.status()
            );
        }
        e => panic!("{e}"),
    }
    assert_eq!(err.status(), Status::PathEnded);
    // It got close to the fold (within a few ds_min steps in λ; λ_c − λ ~ ds² near a fold).
    assert!(
        LAMBDA_C - last_lambda < 1e-2,
        "stopped at λ = {last_lambda}"
    );
    assert!(cont.next().is_none(), "iterator ends after an error");
}

/// y'' = y, y(0) = 0, y(1) = λ.
struct LinearSinh;

impl ParamBvp for LinearSinh {
    fn dims(&self) -> Dims {
        Dims { n: 2, k: 0 }
    }
    fn interval(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn rhs(&self, _s: f64, z: &[f64], _p: &[f64], _l: f64, dz: &mut [f64]) {
        dz[0] = z[1];
        dz[1] = z[0];
    }
    fn bc(&self, za: &[f64], zb: &[f64], _p: &[f64], l: f64, r: &mut [f64]) {
        r[0] = za[0];
        r[1] = zb[0] - l;
    }
}

/// y'' = p, y(0) = 0, y'(0) = 0, y(1) = λ; p unknown.
struct Quadratic;

impl ParamBvp for Quadratic {
    fn dims(&self) -> Dims {
        Dims { n: 2, k: 1 }
    }
    fn interval(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn rhs(&self, _s: f64, z: &[f64], p: &[f64], _l: f64, dz: &mut [f64]) {
        dz[0] = z[1];
        dz[1] = p[0];
    }
    fn bc(&self, za: &[f64], zb: &[f64], _p: &[f64], l: f64, r: &mut [f64]) {
        r[0] = za[0];
        r[1] = za[1];
        r[2] = zb[0] - l;
    }
}

fn linear_branches<S: BvpSolver>(mut make: impl FnMut() -> S) {
    for method in [Method::PseudoArclength, Method::Natural] {
        for direction in [1.0, -1.0] {
            let opts = ContinuationOptions {
                method,
                direction,
                lambda_min: -2.0,
                lambda_max: 3.0,
                ds: 0.1,
                ds_max: 0.4,
                ..Default::default()
            };
            // sinh family: points checked against y = λ sinh(x)/sinh(1).
            let mut solver = make();
            let s0 = start(&LinearSinh, &mut solver, 0.5);
            let cont = Continuation::new(&LinearSinh, solver, s0, 0.5, opts.clone()).unwrap();
            let mut n = 0;
            let mut last = f64::NAN;
            for p in cont {
                let p = p.unwrap();
                n += 1;
                // All mesh values (the continuation's output; dense output between nodes is
                // the solver's business).
                let sol = &p.solution;
                for (i, &x) in sol.mesh.iter().enumerate() {
                    let got = sol.node(i);
                    let exact = [
                        p.lambda * x.sinh() / 1f64.sinh(),
                        p.lambda * x.cosh() / 1f64.sinh(),
                    ];
                    for j in 0..2 {
                        assert!(
                            (got[j] - exact[j]).abs() <= 1e-10,
                            "{method:?} λ = {}: y[{j}]({x}) = {} vs {}",
                            p.lambda,
                            got[j],
                            exact[j]
                        );
                    }
                }
                if p.step > 0 && p.step < 3 {
                    assert!((p.lambda - 0.5) * direction > 0.0, "wrong direction");
                }
                assert!(p.fold.is_none());
                last = p.lambda;
            }
            assert!(n >= 4);
            assert_eq!(last, if direction > 0.0 { 3.0 } else { -2.0 });

            // Quadratic family with an unknown parameter: p = 2λ, y = λx².
            let mut solver = make();
            let s0 = start(&Quadratic, &mut solver, 0.5);
            let cont = Continuation::new(&Quadratic, solver, s0, 0.5, opts).unwrap();
            let mut n = 0;
            for p in cont {
                let p = p.unwrap();
                n += 1;
                assert!(
                    (p.solution.params[0] - 2.0 * p.lambda).abs() <= 1e-10,
                    "{method:?} λ = {}: p = {}",
                    p.lambda,
                    p.solution.params[0]
                );
                for x in [0.25, 0.5, 0.75] {
                    let y = p.solution.at(x)[0];
                    assert!((y - p.lambda * x * x).abs() <= 1e-10, "y({x}) = {y}");
                }
            }
            assert!(n >= 4);
        }
    }
}

#[test]
fn linear_families_shooting() {
    linear_branches(shooting);
}

#[test]
fn linear_families_collocation() {
    linear_branches(collocation);
}

/// point_at on a λ grid equals a direct solve at that λ (from a neutral guess).
#[test]
fn point_at_matches_direct_solves() {
    let family = Bratu { jacobians: true };
    let mut solver = shooting();
    let s0 = start(&family, &mut solver, 0.1);
    let opts = ContinuationOptions {
        lambda_max: 3.0,
        ds: 0.1,
        ..Default::default()
    };
    let mut cont = Continuation::new(&family, solver, s0, 0.1, opts).unwrap();
    let grid: Vec<f64> = (1..=6).map(|i| 0.5 * i as f64).collect();
    let mut got = vec![];
    let mut prev = f64::NAN;
    while let Some(p) = cont.next() {
        let p = p.unwrap();
        for &l in grid.iter().filter(|&&l| l > prev && l <= p.lambda) {
            got.push((l, cont.point_at(l).unwrap()));
        }
        prev = p.lambda;
    }
    assert_eq!(got.len(), grid.len());
    let mut direct_solver = shooting();
    for (l, s) in got {
        let direct = start(&family, &mut direct_solver, l);
        let d = (s.left()[1] - direct.left()[1]).abs();
        assert!(
            d <= 1e-9,
            "λ = {l}: point_at u'(0) = {} vs direct {}",
            s.left()[1],
            direct.left()[1]
        );
        // And both are the lower-branch closed form.
        let (du0, _) = bratu_exact(l, false);
        assert!((s.left()[1] - du0).abs() <= 1e-8 * du0.max(1.0));
    }
}

/// The extended problem's analytic Jacobians equal central differences of its residuals.
#[test]
fn arclength_jacobians_match_differences() {
    struct Fam;
    impl ParamBvp for Fam {
        fn dims(&self) -> Dims {
            Dims { n: 2, k: 1 }
        }
        fn interval(&self) -> (f64, f64) {
            (0.0, 2.0)
        }
        fn rhs(&self, s: f64, z: &[f64], p: &[f64], l: f64, dz: &mut [f64]) {
            dz[0] = z[1] * p[0] + l * s;
            dz[1] = -l * z[0].sin() + p[0] * l * z[1];
        }
        fn bc(&self, za: &[f64], zb: &[f64], p: &[f64], l: f64, r: &mut [f64]) {
            r[0] = za[0] - l * l;
            r[1] = zb[1] * za[1] - p[0];
            r[2] = zb[0] + l * p[0];
        }
        fn rhs_jacobian(
            &self,
            s: f64,
            z: &[f64],
            p: &[f64],
            l: f64,
            dfdz: &mut [f64],
            dfdp: &mut [f64],
            dfdl: &mut [f64],
        ) -> bool {
            dfdz.copy_from_slice(&[0.0, p[0], -l * z[0].cos(), p[0] * l]);
            dfdp.copy_from_slice(&[z[1], l * z[1]]);
            dfdl.copy_from_slice(&[s, -z[0].sin() + p[0] * z[1]]);
            true
        }
        fn bc_jacobian(
            &self,
            za: &[f64],
            zb: &[f64],
            p: &[f64],
            l: f64,
            dga: &mut [f64],
            dgb: &mut [f64],
            dgp: &mut [f64],
            dgl: &mut [f64],
        ) -> bool {
            dga.copy_from_slice(&[1.0, 0.0, 0.0, zb[1], 0.0, 0.0]);
            dgb.copy_from_slice(&[0.0, 0.0, 0.0, za[1], 1.0, 0.0]);
            dgp.copy_from_slice(&[0.0, -1.0, l]);
            dgl.copy_from_slice(&[-2.0 * l, 0.0, p[0]]);
            true
        }
    }
    let tau = vec![0.3, -0.2, 0.5, 0.1, -0.4, 0.7];
    let anchor = vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.0];
    let pb = Arclength::new(&Fam, tau, anchor, 0.7).unwrap();
    assert_eq!(pb.dims(), Dims { n: 2, k: 2 });
    let (za, zb, p) = ([0.3, -0.7], [1.1, 0.4], [0.9, 1.3]);
    let (n, k, m) = (2, 2, 5);
    let mut dga = vec![0.0; m * n];
    let mut dgb = vec![0.0; m * n];
    let mut dgp = vec![0.0; m * k];
    assert!(pb.bc_jacobian(&za, &zb, &p, &mut dga, &mut dgb, &mut dgp));
    let h = 1e-6;
    let fd = |which: usize, j: usize| {
        let (mut a1, mut b1, mut p1) = (za, zb, p);
        let (mut a2, mut b2, mut p2) = (za, zb, p);
        match which {
            0 => (a1[j] += h, a2[j] -= h),
            1 => (b1[j] += h, b2[j] -= h),
            _ => (p1[j] += h, p2[j] -= h),
        };
        let (mut r1, mut r2) = (vec![0.0; m], vec![0.0; m]);
        pb.bc(&a1, &b1, &p1, &mut r1);
        pb.bc(&a2, &b2, &p2, &mut r2);
        r1.iter()
            .zip(&r2)
            .map(|(x, y)| (x - y) / (2.0 * h))
            .collect::<Vec<_>>()
    };
    for j in 0..n {
        let (ca, cb) = (fd(0, j), fd(1, j));
        for i in 0..m {
            assert!((dga[i * n + j] - ca[i]).abs() < 1e-8, "dga[{i},{j}]");
            assert!((dgb[i * n + j] - cb[i]).abs() < 1e-8, "dgb[{i},{j}]");
        }
    }
    for j in 0..k {
        let cp = fd(2, j);
        for i in 0..m {
            assert!((dgp[i * k + j] - cp[i]).abs() < 1e-8, "dgp[{i},{j}]");
        }
    }
    let s = 0.8;
    let z = [0.4, -0.6];
    let mut dfdz = vec![0.0; n * n];
    let mut dfdp = vec![0.0; n * k];
    assert!(pb.rhs_jacobian(s, &z, &p, &mut dfdz, &mut dfdp));
    for j in 0..n + k {
        let (mut z1, mut p1, mut z2, mut p2) = (z, p, z, p);
        if j < n {
            z1[j] += h;
            z2[j] -= h;
        } else {
            p1[j - n] += h;
            p2[j - n] -= h;
        }
        let (mut f1, mut f2) = ([0.0; 2], [0.0; 2]);
        pb.rhs(s, &z1, &p1, &mut f1);
        pb.rhs(s, &z2, &p2, &mut f2);
        for i in 0..n {
            let d = (f1[i] - f2[i]) / (2.0 * h);
            let a = if j < n {
                dfdz[i * n + j]
            } else {
                dfdp[i * k + j - n]
            };
            assert!((a - d).abs() < 1e-8, "dF[{i},{j}]: {a} vs {d}");
        }
    }
}

#[test]
fn invalid_options_are_rejected() {
    let family = Bratu { jacobians: true };
    let sol = Solution {
        n: 2,
        mesh: vec![0.0, 1.0],
        z: vec![0.0; 4],
        dz: vec![0.0; 4],
        params: vec![],
        status: Status::Converged,
        stats: Default::default(),
        dense: Default::default(),
    };
    let bad = [
        ContinuationOptions {
            ds: 0.0,
            ..Default::default()
        },
        ContinuationOptions {
            ds_min: 1.0,
            ..Default::default()
        },
        ContinuationOptions {
            direction: 0.5,
            ..Default::default()
        },
        ContinuationOptions {
            lambda_min: 1.0,
            lambda_max: 0.0,
            ..Default::default()
        },
        ContinuationOptions {
            fold_tol: -1.0,
            ..Default::default()
        },
        ContinuationOptions {
            theta: f64::NAN,
            ..Default::default()
        },
        ContinuationOptions {
            max_angle: 4.0,
            ..Default::default()
        },
    ];
    for o in bad {
        let e = Continuation::new(&family, shooting(), sol.clone(), 0.1, o.clone()).unwrap_err();
        assert_eq!(e.status(), Status::InvalidInput, "{o:?}");
    }
    // λ0 outside the bounds.
    let o = ContinuationOptions {
        lambda_max: 0.05,
        ..Default::default()
    };
    assert!(matches!(
        Continuation::new(&family, shooting(), sol.clone(), 0.1, o),
        Err(BvpError::InvalidOption {
            name: "lambda0",
            ..
        })
    ));
    // Wrong start dimensions.
    let mut bad_sol = sol;
    bad_sol.params = vec![1.0];
    assert!(matches!(
        Continuation::new(&family, shooting(), bad_sol, 0.1, Default::default()),
        Err(BvpError::Dimension { .. })
    ));
}

/// Bratu with λ → −λ: `u'' − λ eᵘ = 0`; the fold is a minimum of λ at −λ_c. Traced downwards
/// (direction −1) with collocation and no analytic Jacobians.
struct NegBratu;

impl ParamBvp for NegBratu {
    fn dims(&self) -> Dims {
        Dims { n: 2, k: 0 }
    }
    fn interval(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn rhs(&self, _s: f64, z: &[f64], _p: &[f64], l: f64, dz: &mut [f64]) {
        dz[0] = z[1];
        dz[1] = l * z[0].exp();
    }
    fn bc(&self, za: &[f64], zb: &[f64], _p: &[f64], _l: f64, r: &mut [f64]) {
        r[0] = za[0];
        r[1] = zb[0];
    }
}

#[test]
fn fold_minimum_downwards() {
    let mut solver = collocation();
    let s0 = start(&NegBratu, &mut solver, -0.5);
    let opts = ContinuationOptions {
        direction: -1.0,
        lambda_min: -10.0,
        lambda_max: -0.5,
        ds: 0.1,
        ..Default::default()
    };
    let cont = Continuation::new(&NegBratu, solver, s0, -0.5, opts).unwrap();
    let mut folds = vec![];
    let mut last = None;
    for p in cont {
        let p = p.unwrap();
        check_bratu(-p.lambda, &p.solution, 1e-9, 1e-6);
        if let Some(f) = p.fold.clone() {
            folds.push(f);
        }
        last = Some(p);
    }
    assert_eq!(folds.len(), 1);
    assert_eq!(folds[0].kind, FoldKind::Min);
    assert!(
        (folds[0].lambda + LAMBDA_C).abs() <= 1e-8,
        "fold at {}",
        folds[0].lambda
    );
    let last = last.unwrap();
    assert!(last.on_bound && last.lambda == -0.5);
}
