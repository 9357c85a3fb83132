//! Issue 34: a three-point problem (bvp4c's `threebvp`, Lin & Segel) as a multipoint problem
//! (`bvp::multipoint`: two regions, continuity at `x = 1`, `F` per region) and unsplit (`min(x, 1)`
//! in `F`, solved directly across `x = 1`), by every method: every success within 10·tol of an
//! independent reference (scipy's DOP853 at rtol 1e-13, shooting in `C(0)`,
//! `data/bvp_multipoint/threebvp_reference.py`) on its 2001 points, values of both states.

use bvp::multipoint::{MultiSolution, MultipointBvp, Regions};
use bvp::{
    from_fns, Bvp, BvpError, BvpSolver, Collocation, CollocationOptions, Dims, Guess, Integrator,
    Scheme, Shooting, ShootingOptions, Solution,
};

const REFERENCE: &str = include_str!("../../../data/bvp_multipoint/threebvp_reference.csv");
const N: f64 = 5e-2;
const LAMBDA: f64 = 2.0;
const ETA: f64 = LAMBDA * LAMBDA / (N * 2.0 * 2.0);

fn reference() -> Vec<(f64, [f64; 2])> {
    REFERENCE
        .lines()
        .skip(1)
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            (v[0], [v[1], v[2]])
        })
        .collect()
}

/// The multipoint form: region 0 is `[0, 1]` (`min(x, 1) = x`), region 1 is `[1, λ]` (`= 1`).
struct ThreePoint {
    xi: [f64; 3],
}

impl MultipointBvp for ThreePoint {
    fn dims(&self) -> Dims {
        Dims { n: 2, k: 0 }
    }
    fn breakpoints(&self) -> &[f64] {
        &self.xi
    }
    fn rhs(&self, region: usize, x: f64, y: &[f64], _p: &[f64], dy: &mut [f64]) {
        let forcing = if region == 0 { x } else { 1.0 };
        dy[0] = (y[1] - 1.0) / N;
        dy[1] = (y[0] * y[1] - forcing) / ETA;
    }
    fn bc(&self, left: &[f64], right: &[f64], _p: &[f64], r: &mut [f64]) {
        // left = (v, C) at 0⁺ and at 1⁺; right = (v, C) at 1⁻ and at λ⁻.
        r[0] = left[0]; // v(0) = 0
        r[1] = right[3] - 1.0; // C(λ) = 1
        r[2] = right[0] - left[2]; // v continuous at 1
        r[3] = right[1] - left[3]; // C continuous at 1
    }
}

fn unsplit() -> impl Bvp {
    from_fns(
        2,
        (0.0, LAMBDA),
        |x, y, _p, dy| {
            dy[0] = (y[1] - 1.0) / N;
            dy[1] = (y[0] * y[1] - x.min(1.0)) / ETA;
        },
        |ya, yb, _p, r| {
            r[0] = ya[0];
            r[1] = yb[1] - 1.0;
        },
    )
}

/// Method `m` of [`NAMES`] at `tol` (shooting: DOP853 at `tol/100`, as the test-set study).
fn solve_with<P: Bvp>(m: usize, tol: f64, p: &P, g: &Guess) -> Result<Solution, Box<BvpError>> {
    let r = match m {
        0 | 1 => Collocation::new(CollocationOptions {
            scheme: if m == 0 {
                Scheme::Lobatto4
            } else {
                Scheme::Lobatto6
            },
            tol,
            ..CollocationOptions::default()
        })
        .unwrap()
        .solve(p, g),
        _ => Shooting::new(ShootingOptions {
            integrator: Integrator::Adaptive {
                rtol: 1e-2 * tol,
                atol: 1e-2 * tol,
            },
            segments: if m == 2 { 1 } else { 8 },
            tol: Some(tol),
            ..ShootingOptions::default()
        })
        .unwrap()
        .solve(p, g),
    };
    r.map_err(Box::new)
}

const NAMES: [&str; 4] = ["Lobatto4", "Lobatto6", "shooting", "shooting 8"];

fn error(at: impl Fn(f64) -> Vec<f64>, reference: &[(f64, [f64; 2])]) -> f64 {
    let mut e = 0.0_f64;
    for (x, y) in reference {
        let s = at(*x);
        for c in 0..2 {
            e = e.max((s[c] - y[c]).abs() / (1.0 + y[c].abs()));
        }
    }
    e
}

#[test]
fn three_point_problem_as_multipoint_and_unsplit() {
    let reference = reference();
    assert_eq!(reference.len(), 2001);
    let regions = Regions::new(ThreePoint {
        xi: [0.0, 1.0, LAMBDA],
    })
    .unwrap();
    assert_eq!(regions.dims(), Dims { n: 4, k: 0 });
    for tol in [1e-4, 1e-6, 1e-8] {
        let guess = regions.guess(5, vec![], |_r, _x, y| y.copy_from_slice(&[1.0, 1.0]));
        let flat = Guess::constant(0.0, LAMBDA, 5, &[1.0, 1.0], vec![]);
        for (m, name) in NAMES.iter().enumerate() {
            let multi: MultiSolution = solve_with(m, tol, &regions, &guess)
                .map(|s| regions.split(&s))
                .unwrap_or_else(|e| panic!("{name} tol {tol:e} multipoint: {e}"));
            let e = error(|x| multi.at(x), &reference);
            assert!(e <= 10.0 * tol, "{name} tol {tol:e} multipoint: {e:.3e}");
            // The regions meet at x = 1 (the interface conditions) and carry their intervals.
            let (r0, r1) = (&multi.regions[0], &multi.regions[1]);
            assert_eq!((r0.mesh[0], *r0.mesh.last().unwrap()), (0.0, 1.0));
            assert_eq!((r1.mesh[0], *r1.mesh.last().unwrap()), (1.0, LAMBDA));
            for c in 0..2 {
                assert!(
                    (r0.right()[c] - r1.left()[c]).abs() <= tol,
                    "{name}: jump at 1"
                );
            }
            let sol = solve_with(m, tol, &unsplit(), &flat)
                .unwrap_or_else(|e| panic!("{name} tol {tol:e} unsplit: {e}"));
            let e = error(|x| sol.at(x), &reference);
            assert!(e <= 10.0 * tol, "{name} tol {tol:e} unsplit: {e:.3e}");
        }
    }
}

#[test]
fn breakpoints_are_validated() {
    for xi in [[0.0, 1.0, 1.0], [0.0, f64::NAN, 2.0], [2.0, 1.0, 3.0]] {
        assert!(matches!(
            Regions::new(ThreePoint { xi }),
            Err(BvpError::InvalidOption {
                name: "breakpoints",
                ..
            })
        ));
    }
}
