//! Property tests: the analytic Jacobians of every sample problem agree with central finite
//! differences (error `O(ε^⅔)` ≈ 1e-10 relative) at random states, parameters and abscissae.

use bvp::continuation::ParamBvp;
use bvp::fd::{self, FdScheme, FdScratch};
use bvp::samples::{
    Bratu, BratuFamily, Cantilever, Eigen, LinearNonSeparated, LinearSinh, NanRhs, NoSolution,
    Parabola, SingularNeumann,
};
use bvp::Bvp;
use proptest::prelude::*;

/// `|a − b| ≤ 1e-6 (1 + |b|)` entrywise.
fn close(a: &[f64], b: &[f64], what: &str) -> Result<(), TestCaseError> {
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        prop_assert!(
            (x - y).abs() <= 1e-6 * (1.0 + y.abs()),
            "{what}[{i}]: analytic {x} vs fd {y}"
        );
    }
    Ok(())
}

/// Compares `rhs_jacobian` and `bc_jacobian` of `p` with central differences at `(s, za, zb, q)`.
fn check<P: Bvp>(p: &P, t: f64, za: &[f64], zb: &[f64], q: &[f64]) -> Result<(), TestCaseError> {
    let dims = p.dims();
    let (n, k) = (dims.n, dims.k);
    let m = n + k;
    let (a, b) = p.interval();
    let s = a + t * (b - a);
    let mut scratch = FdScratch::with_scheme(dims, FdScheme::Central);

    let (mut jz, mut jp) = (vec![0.0; n * n], vec![0.0; n * k]);
    prop_assert!(
        p.rhs_jacobian(s, za, q, &mut jz, &mut jp),
        "no analytic rhs Jacobian"
    );
    let (mut fz, mut fp) = (vec![0.0; n * n], vec![0.0; n * k]);
    fd::rhs_jacobian_fd(p, s, za, q, None, &mut fz, &mut fp, &mut scratch);
    close(&jz, &fz, "dF/dz")?;
    close(&jp, &fp, "dF/dp")?;

    let (mut ga, mut gb, mut gp) = (vec![0.0; m * n], vec![0.0; m * n], vec![0.0; m * k]);
    prop_assert!(
        p.bc_jacobian(za, zb, q, &mut ga, &mut gb, &mut gp),
        "no analytic bc Jacobian"
    );
    let (mut ha, mut hb, mut hp) = (vec![0.0; m * n], vec![0.0; m * n], vec![0.0; m * k]);
    fd::bc_jacobian_fd(p, za, zb, q, None, &mut ha, &mut hb, &mut hp, &mut scratch);
    close(&ga, &ha, "dg/dza")?;
    close(&gb, &hb, "dg/dzb")?;
    close(&gp, &hp, "dg/dp")?;
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn big_problems(
        t in 0.0..1.0f64,
        seed in proptest::collection::vec(-1.0..1.0f64, 16),
        q in proptest::collection::vec(0.3..2.0f64, 2),
    ) {
        for params in [false, true] {
            let p = bvp::samples::Big { pairs: 4, params };
            let (za, zb) = (&seed[..8], &seed[8..]);
            check(&p, t, za, zb, if params { &q } else { &[] })?;
        }
    }

    #[test]
    fn two_state_samples(
        t in 0.0..1.0f64,
        za in prop::array::uniform2(-3.0..3.0f64),
        zb in prop::array::uniform2(-3.0..3.0f64),
        lambda in 0.1..40.0f64,
    ) {
        check(&LinearSinh, t, &za, &zb, &[])?;
        check(&LinearNonSeparated, t, &za, &zb, &[])?;
        check(&NoSolution, t, &za, &zb, &[])?;
        check(&SingularNeumann, t, &za, &zb, &[])?;
        check(&Eigen, t, &za, &zb, &[lambda])?;
        check(&Bratu { lambda: lambda / 10.0 }, t, &za, &zb, &[])?;
        check(&Parabola { end: lambda - 20.0 }, t, &za, &zb, &[lambda])?;
    }

    #[test]
    fn cantilever(
        t in 0.0..1.0f64,
        za in prop::array::uniform4(-4.0..4.0f64),
        zb in prop::array::uniform4(-4.0..4.0f64),
        load in 0.0..20.0f64,
    ) {
        check(&Cantilever { load }, t, &za, &zb, &[])?;
    }

    #[test]
    fn nan_rhs_in_its_domain(t in 0.0..1.0f64, y in 0.05..4.0f64, yb in -1.0..1.0f64) {
        check(&NanRhs, t, &[y], &[yb], &[])?;
    }

    #[test]
    fn bratu_family(
        s in 0.0..1.0f64,
        z in prop::array::uniform2(-3.0..3.0f64),
        zb in prop::array::uniform2(-3.0..3.0f64),
        lambda in 0.0..4.0f64,
    ) {
        let f = BratuFamily;
        let (mut jz, mut jl) = ([0.0; 4], [0.0; 2]);
        prop_assert!(f.rhs_jacobian(s, &z, &[], lambda, &mut jz, &mut [], &mut jl));
        // Differentiate with respect to x = (z, λ).
        let mut x = [z[0], z[1], lambda];
        let mut fx = [0.0; 2];
        let mut jac = [0.0; 6];
        let mut work = [0.0; 2];
        fd::jacobian(
            |x, out| f.rhs(s, &x[..2], &[], x[2], out),
            &mut x,
            &mut fx,
            FdScheme::Central,
            &mut jac,
            &mut work,
        );
        for i in 0..2 {
            close(&jz[2 * i..2 * i + 2], &jac[3 * i..3 * i + 2], "dF/dz")?;
            close(&jl[i..i + 1], &jac[3 * i + 2..3 * i + 3], "dF/dλ")?;
        }
        let (mut ga, mut gb, mut gl) = ([0.0; 4], [0.0; 4], [0.0; 2]);
        prop_assert!(f.bc_jacobian(&z, &zb, &[], lambda, &mut ga, &mut gb, &mut [], &mut gl));
        // The member at λ is the plain Bratu problem: reuse its checked bc Jacobian.
        let (mut ha, mut hb) = ([0.0; 4], [0.0; 4]);
        prop_assert!(f.at(lambda).bc_jacobian(&z, &zb, &[], &mut ha, &mut hb, &mut []));
        close(&ga, &ha, "dg/dza")?;
        close(&gb, &hb, "dg/dzb")?;
        close(&gl, &[0.0, 0.0], "dg/dλ")?;
    }
}
