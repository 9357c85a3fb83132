//! Work-precision study (issues #6 and 35): error against run time, one line per method, for
//!
//! 1. one shape, α = −π/8, φ1 = π/8, convex and one-flex branch (the paper's Fig. 3); error in `f`
//!    relative to the closed form (crate `elastica`);
//! 2. the stiction scan at η = 0.75, d ∈ [0, 0.5], 201 points; max error in μ against the closed
//!    form (the library's closed-form scan, `Method::Analytic`), compared at the same `d`;
//! 3. the tapered rod (ρ = 0.1) scan at η = 0.97 (at η = 0.75 the start rod already penetrates
//!    the surface) from the connected start (`StartKind::Connected`), grid of 201 points on
//!    [0, 0.5] up to the scan's fold in d; max error in μ against a very tight solve;
//! 4. a scan where a side touches down: taper ρ = 0.7, η = 0.75, d ∈ [0, 0.5], 201 points,
//!    contact anywhere (a side touches down at d = 0.192); max error in μ against a very tight
//!    solve;
//! 5. the drag of the paper's rod (η = 0.75, μs = 0.5, μk = 0.3, flat) to d = 0.2, 14 slips;
//!    max error of the slip places d against a very tight solve;
//! 6. the whisk of the paper's rod against a point object at distance 0.7 (first touch at
//!    θ = 0.3, s = 0.7), frictionless, 201 angles to θ = 1; max error in m(0) against a very
//!    tight solve.
//!
//! The very tight solves are single shooting at tol 1e-13, cross-checked against collocation of
//! order 6 at tol 1e-11 (the `reference-check` rows). Tolerances 1e-2 (the loosest the solvers
//! accept) … 1e-12; `summary.md` has, per accuracy target 1e-3, 1e-6, 1e-9, the cheapest run of
//! each method reaching it.
//!
//! Run from the workspace root; it writes `work_precision.{csv,svg}`, `summary.md` and
//! `machine.txt` into the directory given as the first argument, else `$WP_OUT`, else
//! `target/work_precision` (never the committed copy in `data/work_precision/` unless asked):
//!
//! ```sh
//! cargo run --release --example work_precision                          # target/work_precision
//! cargo run --release --example work_precision --features ode-baseline -- data/work_precision  # the committed copy
//! ```
//!
//! Problem 1 also runs through the generic crate `bvp` on the rod model: its DOP853 shooting and,
//! with `--features ode-baseline` (as in the committed run), shooting through `ode_solvers`'
//! Dop853, the off-the-shelf baseline of the hand-written integrators.
//!
//! Environment: `WP_CAP_S` (default 8): a method's tolerance sweep on one problem stops after the
//! first run slower than this many seconds (that run is kept); `WP_QUICK=1`: fewer tolerances
//! (smoke test); `WP_PLOT_ONLY=1`: redraw the SVG and `summary.md` from the CSV in the output
//! directory; `WP_ONLY=problem/method` (e.g. `scan/collocation6`): rerun that method's sweep on
//! that problem alone and put its rows in place of its rows in the CSV already in the output
//! directory (the other rows, the SVG and `summary.md` redrawn from them, a line appended to
//! `machine.txt`).
//!
//! Times are wall-clock, single thread, the minimum over batches (each batch repeats a fast run
//! until it lasts ≥ 0.1 s), so they are comparable within one run of this program.

use anyhow::{anyhow, bail, Context, Result};
use elastica::{Branch, Elastica};
use plotters::prelude::*;
use std::f64::consts::PI;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};
use vibrissa::{
    scan_at, solve, BranchChoice, Method, Rod, ScanOptions, Scene, SolverConfig, StartKind,
    Surface, Target,
};

/// One measured configuration.
#[derive(Clone, Debug)]
struct Row {
    problem: &'static str,
    method: String,
    /// The knob: solver tolerance, or the RK4 step count.
    tol: f64,
    rk4_steps: Option<usize>,
    error: f64,
    time_s: f64,
    reps: usize,
    rhs_evals: usize,
    newton_iters: usize,
    note: String,
}

/// Minimum over 3 batches of the mean time of `f` (a batch repeats `f` for ≥ 0.1 s); slow runs
/// (> 1 s) are measured once.
fn time_it<T>(mut f: impl FnMut() -> Result<T>) -> Result<(T, f64, usize)> {
    let t0 = Instant::now();
    let first = f()?;
    let once = t0.elapsed();
    if once > Duration::from_secs(1) {
        return Ok((first, once.as_secs_f64(), 1));
    }
    let per_batch = ((0.1 / once.as_secs_f64().max(1e-7)).ceil() as usize).clamp(1, 100_000);
    let mut best = f64::INFINITY;
    for _ in 0..3 {
        let t = Instant::now();
        for _ in 0..per_batch {
            std::hint::black_box(f()?);
        }
        best = best.min(t.elapsed().as_secs_f64() / per_batch as f64);
    }
    Ok((first, best, 1 + 3 * per_batch))
}

/// The numerical methods of the study: (name, config for a given tolerance).
#[derive(Clone, Copy, Debug)]
enum Knob {
    Tol(f64),
    Steps(usize),
}

/// The tolerances of every method's sweep: 1e-2 (the loosest the solvers accept) … 1e-12 (two
/// with `quick`).
fn tolerances(quick: bool) -> Vec<f64> {
    if quick {
        vec![1e-4, 1e-8]
    } else {
        (2..=12).map(|e| 10f64.powi(-e)).collect()
    }
}

fn configs(quick: bool) -> Vec<(String, Vec<(Knob, SolverConfig)>)> {
    let tols = tolerances(quick);
    let steps: Vec<usize> = if quick {
        vec![32, 256]
    } else {
        vec![16, 32, 64, 128, 256, 512, 1024, 2048]
    };
    let base = SolverConfig::default();
    let by_tol = |method: Method, segments: usize| -> Vec<(Knob, SolverConfig)> {
        tols.iter()
            .map(|&tol| {
                (
                    Knob::Tol(tol),
                    SolverConfig {
                        method,
                        tol,
                        segments,
                        rk4_steps: None,
                        ..SolverConfig::default()
                    },
                )
            })
            .collect()
    };
    let rk4: Vec<(Knob, SolverConfig)> = steps
        .iter()
        .map(|&n| {
            (
                Knob::Steps(n),
                SolverConfig {
                    method: Method::Shooting,
                    tol: 1e-12,
                    rk4_steps: Some(n),
                    ..base.clone()
                },
            )
        })
        .collect();
    vec![
        ("shooting-rk4".to_string(), rk4),
        ("shooting-dop853".to_string(), by_tol(Method::Shooting, 1)),
        (
            "multiple-shooting-8".to_string(),
            by_tol(Method::MultipleShooting, 8),
        ),
        ("collocation4".to_string(), by_tol(Method::Collocation4, 1)),
        ("collocation6".to_string(), by_tol(Method::Collocation6, 1)),
    ]
}

fn knob_parts(k: Knob) -> (f64, Option<usize>) {
    match k {
        Knob::Tol(t) => (t, None),
        Knob::Steps(n) => (1e-12, Some(n)),
    }
}

/// Problem 1: one shape per branch; error = max over the two branches of |f − f_cf| / f_cf.
///
/// The closed form would be an exact start (Newton stops at once), so every method starts from
/// the same warm start of a neighbouring rod instead: the RK4 (20 steps) shape at
/// `(0.9 α, 0.9 φ1)` — 10–20 % off in `f`, mesh of 21 uniform nodes.
fn single_shape(rows: &mut Vec<Row>, quick: bool, cap: f64) -> Result<()> {
    let alpha = -PI / 8.0;
    let phi1 = PI / 8.0;
    let rod = Rod::uniform();
    let near = |b: BranchChoice| -> Result<BranchChoice> {
        let cfg = SolverConfig {
            rk4_steps: Some(20),
            ..SolverConfig::default()
        };
        let s = solve(&rod, 0.9 * alpha, Target::Phi1(0.9 * phi1), &b, &cfg)?;
        Ok(BranchChoice::Guess(Box::new(s)))
    };
    let branches = [
        (Branch::Convex, near(BranchChoice::Convex)?),
        (Branch::OneFlex, near(BranchChoice::Flex)?),
    ];
    let f_ref: Vec<f64> = branches
        .iter()
        .map(|(b, _)| Elastica::new(*b, alpha, phi1).map(|e| e.f))
        .collect::<Result<_, _>>()?;
    let only = std::env::var("WP_ONLY").ok();
    for (name, cfgs) in configs(quick) {
        if only.as_ref().is_some_and(|o| *o != format!("shape/{name}")) {
            continue;
        }
        for (knob, cfg) in cfgs {
            let time = shape_row(rows, &name, knob, &f_ref, |i| {
                let s = solve(&rod, alpha, Target::Phi1(phi1), &branches[i].1, &cfg)?;
                Ok((s.f, s.stats))
            });
            if time > cap {
                break;
            }
        }
    }
    generic_shape(rows, &branches, &f_ref, alpha, phi1, quick, cap)?;
    // The closed form itself, against the mpmath values of data/elastica/special_values.csv.
    #[allow(clippy::excessive_precision)] // the digits as printed in the data file
    let mp = [4.718_125_860_964_310_5, 19.028_967_652_434_935];
    let mut err: f64 = 0.0;
    let mut time = 0.0;
    let mut reps = 0;
    for (choice, &fm) in [BranchChoice::Convex, BranchChoice::Flex].iter().zip(&mp) {
        let cfg = SolverConfig {
            method: Method::Analytic,
            ..SolverConfig::default()
        };
        let (shape, t, n) =
            time_it(|| solve(&rod, alpha, Target::Phi1(phi1), choice, &cfg).map_err(Into::into))?;
        err = err.max((shape.f - fm).abs() / fm);
        time += t;
        reps = n;
    }
    rows.push(Row {
        problem: "shape",
        method: "analytic".into(),
        tol: f64::NAN,
        rk4_steps: None,
        error: err,
        time_s: time,
        reps,
        rhs_evals: 0,
        newton_iters: 0,
        note: "error against mpmath (data/elastica/special_values.csv)".into(),
    });
    Ok(())
}

/// One setting of problem 1: both branches solved by `solve_branch(i)` (`f` and the work
/// counters) and timed; error = the larger relative error in `f` against `f_ref`. Appends the
/// row and returns the time of both branches.
fn shape_row(
    rows: &mut Vec<Row>,
    method: &str,
    knob: Knob,
    f_ref: &[f64],
    mut solve_branch: impl FnMut(usize) -> Result<(f64, bvp::Stats)>,
) -> f64 {
    let (mut err, mut time, mut reps, mut rhs, mut newton) = (0.0_f64, 0.0, 0, 0, 0);
    let mut note = String::new();
    for (i, &fr) in f_ref.iter().enumerate() {
        match time_it(|| solve_branch(i)) {
            Ok(((f, stats), t, n)) => {
                err = err.max((f - fr).abs() / fr);
                time += t;
                reps = n;
                rhs += stats.rhs_evals;
                newton += stats.newton_iters;
            }
            Err(e) => {
                note = format!("failed: {e}");
                err = f64::NAN;
            }
        }
    }
    let (tol, rk4_steps) = knob_parts(knob);
    eprintln!("shape  {method:20} {knob:?}: err {err:.2e} time {time:.3e} s");
    rows.push(Row {
        problem: "shape",
        method: method.to_string(),
        tol,
        rk4_steps,
        error: err,
        time_s: time,
        reps,
        rhs_evals: rhs,
        newton_iters: newton,
        note,
    });
    time
}

/// One configured generic solver, applied to a guess.
type Runner = Box<dyn FnMut(&bvp::Guess) -> Result<bvp::Solution>>;

/// Problem 1 through the generic crate `bvp` alone (the rod model `RodBvp`, the same warm starts,
/// no closed-form start, branch check or shape post-processing): its DOP853 single shooting
/// (variational equations on the same stages) and, with `--features ode-baseline`, single
/// shooting through `ode_solvers`' Dop853 (Sparse output, forward-difference Newton matrix), the
/// off-the-shelf baseline of the hand-written integrator. Tolerance `tol` for rtol, atol and
/// Newton alike.
fn generic_shape(
    rows: &mut Vec<Row>,
    branches: &[(Branch, BranchChoice)],
    f_ref: &[f64],
    alpha: f64,
    phi1: f64,
    quick: bool,
    cap: f64,
) -> Result<()> {
    use bvp::{BvpSolver, Guess, Integrator, NewtonOptions, Shooting, ShootingOptions};
    use vibrissa::equations::{Ends, RodBvp};
    use vibrissa::profile::Uniform;
    let problem = RodBvp {
        profile: Uniform,
        compliance: 0.0,
        alpha,
        ends: Ends::Phi1 { phi1 },
    };
    let guesses: Vec<Guess> = branches
        .iter()
        .map(|(_, choice)| {
            let BranchChoice::Guess(w) = choice else {
                bail!("warm start expected")
            };
            let sol = w
                .solution()
                .ok_or_else(|| anyhow!("numeric warm start expected"))?;
            let mut g = Guess::from(sol);
            g.params = vec![w.f];
            Ok(g)
        })
        .collect::<Result<_>>()?;
    let newton = |tol: f64| NewtonOptions {
        tol,
        ..NewtonOptions::default()
    };
    let mut sweep = |name: &str, make: &mut dyn FnMut(f64) -> Result<Runner>| -> Result<()> {
        for tol in tolerances(quick) {
            let mut solve_one = make(tol)?;
            let time = shape_row(rows, name, Knob::Tol(tol), f_ref, |i| {
                let sol = solve_one(&guesses[i])?;
                Ok((sol.params[0], sol.stats))
            });
            if time > cap {
                break;
            }
        }
        Ok(())
    };
    let p = problem.clone();
    sweep("bvp-shooting-dop853", &mut |tol| {
        let mut solver = Shooting::new(ShootingOptions {
            integrator: Integrator::Adaptive {
                rtol: tol,
                atol: tol,
            },
            newton: newton(tol),
            ..ShootingOptions::default()
        })?;
        let p = p.clone();
        Ok(Box::new(move |g: &Guess| Ok(solver.solve(&p, g)?)))
    })?;
    #[cfg(feature = "ode-baseline")]
    {
        use bvp::odes::{OdeShooting, OdeShootingOptions};
        let p = problem.clone();
        sweep("ode_solvers-dop853", &mut |tol| {
            let mut solver = OdeShooting::new(OdeShootingOptions {
                rtol: tol,
                atol: tol,
                newton: newton(tol),
                ..OdeShootingOptions::default()
            })?;
            let p = p.clone();
            Ok(Box::new(move |g: &Guess| Ok(solver.solve(&p, g)?)))
        })?;
    }
    Ok(())
}

/// The `(d, μ)` of a scan's grid points (without the row of the event that ends it).
fn grid_points(points: &[vibrissa::ScanPoint]) -> Vec<(f64, f64)> {
    points
        .iter()
        .filter(|p| p.event.is_none())
        .map(|p| (p.d, p.mu))
        .collect()
}

/// Max |Δμ| over the displacements present in both lists (the same grid values), and how many.
fn max_diff(a: &[(f64, f64)], b: &[(f64, f64)]) -> (f64, usize) {
    let mut err: f64 = 0.0;
    let mut n = 0;
    for &(d, mu) in a {
        if let Some(&(_, mr)) = b.iter().find(|q| q.0 == d) {
            err = err.max((mu - mr).abs());
            n += 1;
        }
    }
    (err, n)
}

/// What one run of a problem gives: its error against the reference (NaN: not comparable), a
/// note, and the work counters.
type Outcome = (f64, String, bvp::Stats);

/// One problem's sweep over every method and setting: `run` solves with a configuration (timed),
/// `judge` compares its result with the reference (not timed).
fn sweep<R>(
    rows: &mut Vec<Row>,
    problem: &'static str,
    quick: bool,
    cap: f64,
    mut run: impl FnMut(&SolverConfig) -> Result<R>,
    judge: impl Fn(&R) -> Outcome,
) {
    let only = std::env::var("WP_ONLY").ok();
    for (name, cfgs) in configs(quick) {
        if only
            .as_ref()
            .is_some_and(|o| *o != format!("{problem}/{name}"))
        {
            continue;
        }
        for (knob, cfg) in cfgs {
            let (tol, rk4_steps) = knob_parts(knob);
            let (err, time, reps, stats, note) = match time_it(|| run(&cfg)) {
                Ok((res, t, n)) => {
                    let (err, note, stats) = judge(&res);
                    (err, t, n, stats, note)
                }
                Err(e) => (
                    f64::NAN,
                    f64::NAN,
                    0,
                    bvp::Stats::default(),
                    format!("failed: {e}"),
                ),
            };
            eprintln!("{problem:6} {name:20} {knob:?}: err {err:.2e} time {time:.3e} s {note}");
            rows.push(Row {
                problem,
                method: name.clone(),
                tol,
                rk4_steps,
                error: err,
                time_s: time,
                reps,
                rhs_evals: stats.rhs_evals,
                newton_iters: stats.newton_iters,
                note,
            });
            // also stop after a failed run (NaN time)
            if time.is_nan() || time > cap {
                break;
            }
        }
    }
}

/// Max |Δ| over the grid points a run shares with the reference; NaN when more than two of the
/// reference's are missing (a run that stopped early), with a note saying how many were compared.
fn grid_error(grid: &[(f64, f64)], reference: &[(f64, f64)], stop: &str) -> (f64, String) {
    let (err, compared) = max_diff(grid, reference);
    let note = if compared != reference.len() {
        format!(
            "{compared} grid points compared, reference {}: {stop}",
            reference.len()
        )
    } else {
        String::new()
    };
    let err = if compared + 2 < reference.len() {
        f64::NAN
    } else {
        err
    };
    (err, note)
}

/// A scan problem: `scan_at` from `start` on the reference's displacements, max error in μ at
/// the grid points.
#[allow(clippy::too_many_arguments)] // one problem's whole definition
fn scan_problem(
    rows: &mut Vec<Row>,
    problem: &'static str,
    rod: &Rod,
    surface: &Surface,
    start: StartKind,
    reference: &[(f64, f64)],
    quick: bool,
    cap: f64,
) {
    let d: Vec<f64> = reference.iter().map(|p| p.0).collect();
    let run = |cfg: &SolverConfig| {
        let opts = ScanOptions {
            d_max: 0.5,
            solver: SolverConfig {
                start,
                ..cfg.clone()
            },
            ..ScanOptions::default()
        };
        scan_at(rod, surface, &opts, &d).map_err(Into::into)
    };
    // compared at the grid points both have (the reference may stop early too); the row of
    // the event that ends a scan (e.g. the fold in d) is not a grid point: near a fold in d,
    // mu(d) has a square-root singularity and a 1e-12 shift of the fold moves mu there by 1e-6
    let judge = |res: &vibrissa::ScanResult| {
        let (err, mut note) =
            grid_error(&grid_points(&res.points), reference, &res.stop.to_string());
        if let Some(h) = &res.handover {
            note = format!("{note} handover: {h}");
        }
        (err, note, res.stats.clone())
    };
    sweep(rows, problem, quick, cap, run, judge);
}

/// The reference of a problem: `tight(Method::Shooting, 1e-13)`, cross-checked against
/// `tight(Method::Collocation6, 1e-11)` (max |Δ| by `diff`; skipped with `quick`), recorded as
/// the problem's `reference-check` row.
fn reference<T>(
    rows: &mut Vec<Row>,
    problem: &'static str,
    quick: bool,
    tight: impl Fn(Method, f64) -> Result<T>,
    diff: impl Fn(&T, &T) -> f64,
) -> Result<T> {
    let reference = tight(Method::Shooting, 1e-13).context("reference (shooting)")?;
    let check = if quick {
        f64::NAN
    } else {
        let c = tight(Method::Collocation6, 1e-11).context("cross-check (collocation6)")?;
        diff(&reference, &c)
    };
    eprintln!("{problem} reference: shooting 1e-13 vs collocation6 1e-11: max diff {check:.2e}");
    rows.push(Row {
        problem,
        method: "reference-check".into(),
        tol: 1e-13,
        rk4_steps: None,
        error: check,
        time_s: f64::NAN,
        reps: 0,
        rhs_evals: 0,
        newton_iters: 0,
        note: "reference (shooting-dop853 tol 1e-13) vs collocation6 tol 1e-11".into(),
    });
    Ok(reference)
}

/// A config of `method` at `tol`.
fn at_tol(method: Method, tol: f64) -> SolverConfig {
    SolverConfig {
        method,
        tol,
        ..SolverConfig::default()
    }
}

fn uniform_scan(rows: &mut Vec<Row>, quick: bool, cap: f64) -> Result<()> {
    let (rod, surface) = Scene::default().parts()?;
    let grid: Vec<f64> = (0..201).map(|i| 0.5 * i as f64 / 200.0).collect();
    // the reference: the library's closed-form scan (elastica's curve across the fold in φ1,
    // each d found on it by Brent's method)
    let analytic = ScanOptions {
        d_max: 0.5,
        solver: SolverConfig {
            method: Method::Analytic,
            ..SolverConfig::default()
        },
        ..ScanOptions::default()
    };
    let (r, t_cf, reps) =
        time_it(|| scan_at(&rod, &surface, &analytic, &grid).map_err(Into::into))?;
    let reference = grid_points(&r.points);
    if reference.len() != grid.len() {
        bail!("the closed-form reference stopped early: {}", r.stop);
    }
    rows.push(Row {
        problem: "scan",
        method: "analytic".into(),
        tol: f64::NAN,
        rk4_steps: None,
        error: f64::NAN,
        time_s: t_cf,
        reps,
        rhs_evals: 0,
        newton_iters: 0,
        note: "the reference itself (vibrissa::scan_at with Method::Analytic, 201 points)".into(),
    });
    scan_problem(
        rows,
        "scan",
        &rod,
        &surface,
        StartKind::Pressed,
        &reference,
        quick,
        cap,
    );
    Ok(())
}

fn tapered_scan(rows: &mut Vec<Row>, quick: bool, cap: f64) -> Result<()> {
    // ρ = 0.1 makes the tip so flexible that for η ≤ 0.93 the start rod already dips below
    // the surface line (penetration at d = 0); at η = 0.97 the scan runs to its fold in d
    let scene = Scene {
        eta: 0.97,
        stiffness: vibrissa::Stiffness::Taper { ratio: 0.1 },
        ..Scene::default()
    };
    let (rod, surface) = scene.parts()?;
    let grid: Vec<f64> = (0..201).map(|i| 0.5 * i as f64 / 200.0).collect();
    // from the tip-loaded state connected to the straight uniform rod (`StartKind::Connected`):
    // the rod pressed onto the surface from its rest shape (the default start) reaches
    // different equilibria at different tolerances here (f0 = 0.796 or 1.439), whose scans end
    // at different folds; the connected start is the same rod at every tolerance and method
    let start = StartKind::Connected;
    let tight = tight_scan(&rod, &surface, start, &grid);
    let reference = reference(rows, "taper", quick, tight, |a, b| max_diff(a, b).0)?;
    scan_problem(rows, "taper", &rod, &surface, start, &reference, quick, cap);
    Ok(())
}

/// The grid points `(d, μ)` of a tight scan from `start` at `grid` (an error if it stops within
/// 10 points).
fn tight_scan<'a>(
    rod: &'a Rod,
    surface: &'a Surface,
    start: StartKind,
    grid: &'a [f64],
) -> impl Fn(Method, f64) -> Result<Vec<(f64, f64)>> + 'a {
    move |method, tol| {
        let opts = ScanOptions {
            d_max: 0.5,
            solver: SolverConfig {
                start,
                ..at_tol(method, tol)
            },
            ..ScanOptions::default()
        };
        let r = scan_at(rod, surface, &opts, grid)?;
        eprintln!(
            "{method:?} {tol:e}: {} points, stop: {}",
            r.points.len(),
            r.stop
        );
        if r.points.len() < 10 {
            bail!("reference scan stopped early: {}", r.stop);
        }
        Ok(grid_points(&r.points))
    }
}

/// Problem 4: the tapered rod ρ = 0.7 at η = 0.75, d ∈ [0, 0.5], 201 points, contact anywhere:
/// a side touches down at d = 0.192 and the scan goes on with two contacts; max error in μ at
/// the grid points against a tight solve.
fn side_scan(rows: &mut Vec<Row>, quick: bool, cap: f64) -> Result<()> {
    let scene = Scene {
        stiffness: vibrissa::Stiffness::Taper { ratio: 0.7 },
        ..Scene::default()
    };
    let (rod, surface) = scene.parts()?;
    let grid: Vec<f64> = (0..201).map(|i| 0.5 * i as f64 / 200.0).collect();
    let tight = tight_scan(&rod, &surface, StartKind::Pressed, &grid);
    let reference = reference(rows, "side", quick, tight, |a, b| max_diff(a, b).0)?;
    if reference.len() != grid.len() {
        bail!("the side-contact reference stopped early");
    }
    scan_problem(
        rows,
        "side",
        &rod,
        &surface,
        StartKind::Pressed,
        &reference,
        quick,
        cap,
    );
    Ok(())
}

/// The drag of problem 5 with `solver`.
fn drag_run(solver: &SolverConfig) -> Result<vibrissa::DragResult> {
    let (rod, surface) = Scene::default().parts()?;
    let opts = vibrissa::DragOptions {
        d_max: DRAG_D_MAX,
        points: 201,
        mu_s: Some(0.5),
        mu_k: Some(0.3),
        solver: solver.clone(),
        ..vibrissa::DragOptions::default()
    };
    Ok(vibrissa::drag(&rod, &surface, &opts)?)
}

/// The drag's foot travel: fourteen slips (the first at d = 0.0210, then every 0.0131).
const DRAG_D_MAX: f64 = 0.2;

/// Max |Δd| of the slip places (the foot displacement at each slip); NaN if the numbers differ.
fn slip_error(a: &vibrissa::DragResult, b: &[f64]) -> (f64, String) {
    if a.slips.len() != b.len() {
        return (
            f64::NAN,
            format!("{} slips, reference {}: {}", a.slips.len(), b.len(), a.stop),
        );
    }
    let err = a
        .slips
        .iter()
        .zip(b)
        .map(|(s, d)| (s.d - d).abs())
        .fold(0.0, f64::max);
    (err, String::new())
}

/// Problem 5: the drag of the paper's rod (η = 0.75, μs = 0.5, μk = 0.3, flat surface) to
/// d = 0.2: fourteen slips; max error of the slip places d against a tight run.
fn drag_problem(rows: &mut Vec<Row>, quick: bool, cap: f64) -> Result<()> {
    let tight = |method, tol| -> Result<Vec<f64>> {
        let r = drag_run(&at_tol(method, tol))?;
        let ds: Vec<f64> = r.slips.iter().map(|s| s.d).collect();
        eprintln!(
            "drag {method:?} {tol:e}: slips at d = {ds:?}, stop: {}",
            r.stop
        );
        if ds.is_empty() {
            bail!("reference drag without a slip: {}", r.stop);
        }
        Ok(ds)
    };
    let diff = |a: &Vec<f64>, b: &Vec<f64>| {
        if a.len() != b.len() {
            return f64::NAN;
        }
        a.iter()
            .zip(b)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max)
    };
    let reference = reference(rows, "drag", quick, tight, diff)?;
    let judge = |r: &vibrissa::DragResult| {
        let (err, mut note) = slip_error(r, &reference);
        if let Some(h) = &r.handover {
            note = format!("{note} handover: {h}");
        }
        (err, note, r.stats.clone())
    };
    sweep(rows, "drag", quick, cap, drag_run, judge);
    Ok(())
}

/// The whisk of problem 6 with `solver`: the paper's rod turned to θ = 1 against a point object
/// at distance 0.7 from the foot, 0.3 rad off its rest line (first touch at θ = 0.3, s = 0.7),
/// frictionless, 201 angles.
fn whisk_run(solver: &SolverConfig) -> Result<vibrissa::WhiskResult> {
    let peg = [0.7 * 0.3f64.sin(), 0.7 * 0.3f64.cos()];
    let opts = vibrissa::WhiskOptions {
        theta_max: 1.0,
        points: 201,
        solver: solver.clone(),
        ..vibrissa::WhiskOptions::default()
    };
    Ok(vibrissa::whisk(&Rod::uniform(), peg, &opts)?)
}

/// `(θ, m(0))` of a whisk's output angles (without event rows).
fn whisk_points(r: &vibrissa::WhiskResult) -> Vec<(f64, f64)> {
    r.points
        .iter()
        .filter(|p| p.event.is_none())
        .map(|p| (p.theta, p.m_base))
        .collect()
}

/// Problem 6: the whisk; max error in the base moment m(0) at the output angles against a
/// tight run.
fn whisk_problem(rows: &mut Vec<Row>, quick: bool, cap: f64) -> Result<()> {
    let tight = |method, tol| -> Result<Vec<(f64, f64)>> {
        let r = whisk_run(&at_tol(method, tol))?;
        eprintln!(
            "whisk {method:?} {tol:e}: {} points, stop: {}",
            r.points.len(),
            r.stop
        );
        Ok(whisk_points(&r))
    };
    let reference = reference(rows, "whisk", quick, tight, |a, b| max_diff(a, b).0)?;
    if reference.len() != 201 {
        bail!("the whisk reference has {} of 201 angles", reference.len());
    }
    let judge = |r: &vibrissa::WhiskResult| {
        let (err, note) = grid_error(&whisk_points(r), &reference, &r.stop.to_string());
        (err, note, r.stats.clone())
    };
    sweep(rows, "whisk", quick, cap, whisk_run, judge);
    Ok(())
}

/// The machine's load (other processes compete for the cores while timing).
fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_else(|_| "unknown".into())
}

fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|s| s.trim().to_string())
        })
        .unwrap_or_else(|| "unknown".into());
    let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
    format!(
        "cpu: {cpu}\nlogical cores (nproc): {cores}\nos: {}\nbuild: release, single thread\n",
        std::env::consts::OS
    )
}

fn write_csv(path: &Path, rows: &[Row]) -> Result<()> {
    let mut s = String::from(
        "problem,method,tol,rk4_steps,error,time_s,reps,rhs_evals,newton_iters,note\n",
    );
    for r in rows {
        let f = |v: f64| {
            if v.is_nan() {
                String::new()
            } else {
                format!("{v:.6e}")
            }
        };
        writeln!(
            s,
            "{},{},{},{},{},{},{},{},{},\"{}\"",
            r.problem,
            r.method,
            f(r.tol),
            r.rk4_steps.map_or(String::new(), |n| n.to_string()),
            f(r.error),
            f(r.time_s),
            r.reps,
            r.rhs_evals,
            r.newton_iters,
            r.note.replace('"', "'")
        )?;
    }
    std::fs::write(path, s)?;
    Ok(())
}

/// Reads the rows back (for `WP_PLOT_ONLY=1`).
fn read_csv(path: &Path) -> Result<Vec<Row>> {
    let mut rd = csv::Reader::from_path(path)?;
    let num = |s: &str| -> f64 { s.parse().unwrap_or(f64::NAN) };
    let mut rows = Vec::new();
    for rec in rd.records() {
        let r = rec?;
        let problem = PROBLEMS
            .iter()
            .map(|p| p.0)
            .find(|p| *p == &r[0])
            .ok_or_else(|| anyhow!("unknown problem {}", &r[0]))?;
        rows.push(Row {
            problem,
            method: r[1].to_string(),
            tol: num(&r[2]),
            rk4_steps: r[3].parse().ok(),
            error: num(&r[4]),
            time_s: num(&r[5]),
            reps: r[6].parse().unwrap_or(0),
            rhs_evals: r[7].parse().unwrap_or(0),
            newton_iters: r[8].parse().unwrap_or(0),
            note: r[9].to_string(),
        });
    }
    Ok(rows)
}

const PROBLEMS: [(&str, &str); 6] = [
    ("shape", "1. one shape (Fig. 3): rel. error in f"),
    ("scan", "2. scan eta = 0.75: max error in mu"),
    ("taper", "3. taper rho = 0.1, eta = 0.97: max error in mu"),
    ("side", "4. taper 0.7, a side touches: max error in mu"),
    ("drag", "5. drag mu_s 0.5, mu_k 0.3: max error of slip d"),
    ("whisk", "6. whisk, object at 0.7: max error in m(0)"),
];

/// Accuracy targets of the summary tables (issue 35), the same for every problem.
const TARGETS: [f64; 3] = [1e-3, 1e-6, 1e-9];

const METHODS: [&str; 8] = [
    "shooting-rk4",
    "shooting-dop853",
    "multiple-shooting-8",
    "collocation4",
    "collocation6",
    "analytic",
    "bvp-shooting-dop853",
    "ode_solvers-dop853",
];

/// SVG user units per output pixel: plotters rounds to whole units, so the plot is drawn `S`
/// times larger and shown at the output size through the `viewBox` (no jagged lines).
const S: u32 = 4;

/// Errors below this (including exact 0) are drawn at it.
const FLOOR: f64 = 1e-17;

fn font(size: u32) -> (&'static str, u32) {
    ("sans-serif", size * S)
}

fn plot(path: &Path, rows: &[Row]) -> Result<()> {
    let (w, h) = (1500u32, 1080u32);
    let colors = [
        RGBColor(31, 119, 180),
        RGBColor(255, 127, 14),
        RGBColor(44, 160, 44),
        RGBColor(214, 39, 40),
        RGBColor(148, 103, 189),
        RGBColor(0, 0, 0),
        RGBColor(140, 86, 75),
        RGBColor(227, 119, 194),
    ];
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (w * S, h * S)).into_drawing_area();
        root.fill(&WHITE)?;
        // the legend has its own row under the panels: it never covers data
        let (body, legend) = root.split_vertically((h - 76) * S);
        for (panel, (prob, title)) in body.split_evenly((2, 3)).iter().zip(PROBLEMS) {
            // drawn: runs with an error, and the closed-form reference (time only)
            let pts: Vec<&Row> = rows
                .iter()
                .filter(|r| r.problem == prob && r.time_s.is_finite() && r.time_s > 0.0)
                .filter(|r| r.error.is_finite() || r.method == "analytic")
                .collect();
            let errs = pts
                .iter()
                .filter(|r| r.error.is_finite())
                .map(|r| r.error.max(FLOOR));
            let emin = errs.clone().fold(f64::INFINITY, f64::min);
            let emax = errs.fold(0.0, f64::max);
            let tmin = pts.iter().map(|r| r.time_s).fold(f64::INFINITY, f64::min);
            let tmax = pts.iter().map(|r| r.time_s).fold(0.0, f64::max);
            let (xr, yr) = (emin / 4.0..emax * 4.0, tmin / 2.0..tmax * 2.0);
            let mut chart = ChartBuilder::on(panel)
                .caption(title, font(17))
                .margin(12 * S)
                .x_label_area_size(44 * S)
                .y_label_area_size(64 * S)
                .build_cartesian_2d(xr.clone().log_scale(), yr.log_scale())?;
            chart
                .configure_mesh()
                .x_desc("error (0 drawn at 1e-17)")
                .y_desc("time per solve / scan [s]")
                .x_label_formatter(&|v| format!("{v:.0e}"))
                .y_label_formatter(&|v| format!("{v:.0e}"))
                .axis_desc_style(font(15))
                .label_style(font(13))
                .light_line_style(RGBColor(238, 238, 238).stroke_width(S / 2))
                .bold_line_style(RGBColor(205, 205, 205).stroke_width(S))
                .axis_style(BLACK.stroke_width(S))
                .set_all_tick_mark_size(5 * S)
                .draw()?;
            for (m, c) in METHODS.iter().zip(colors) {
                let mine: Vec<&&Row> = pts.iter().filter(|r| r.method == *m).collect();
                // failed or incomparable runs (NaN error) are in the CSV, not on the plot
                let mut line: Vec<(f64, f64)> = mine
                    .iter()
                    .filter(|r| r.error.is_finite())
                    .map(|r| (r.error.max(FLOOR), r.time_s))
                    .collect();
                // the line joins, in order of cost, the runs that no faster run of the method
                // beats in accuracy (the Pareto front: time up, error down, no zigzag); the
                // other runs are hollow dots
                line.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.0.total_cmp(&b.0)));
                let mut front: Vec<(f64, f64)> = Vec::new();
                let mut rest: Vec<(f64, f64)> = Vec::new();
                for p in line {
                    if front.last().is_none_or(|q| p.0 < q.0) {
                        front.push(p);
                    } else {
                        rest.push(p);
                    }
                }
                chart.draw_series(LineSeries::new(front.clone(), c.stroke_width(2 * S)))?;
                chart.draw_series(front.iter().map(|&p| Circle::new(p, 3 * S, c.filled())))?;
                chart.draw_series(
                    rest.iter()
                        .map(|&p| Circle::new(p, 3 * S, c.stroke_width(S * 3 / 2))),
                )?;
                // the closed-form reference of a scan has no error of its own: its time as a
                // dashed horizontal line
                for r in mine
                    .iter()
                    .filter(|r| !r.error.is_finite() && *m == "analytic")
                {
                    chart.draw_series(DashedLineSeries::new(
                        [(xr.start, r.time_s), (xr.end, r.time_s)],
                        6 * S,
                        5 * S,
                        c.stroke_width(S),
                    ))?;
                }
            }
        }
        let names = [
            "shooting, RK4 (steps)",
            "shooting, DOP853 (tol)",
            "multiple shooting, 8 segments",
            "collocation, order 4",
            "collocation, order 6",
            "closed form (dashed: scan reference, time only)",
            "generic bvp shooting, DOP853 (shape only)",
            "ode_solvers Dop853 shooting (shape only)",
        ];
        legend.draw(&Text::new(
            "lines: for each method the runs that no faster run beats in accuracy; hollow dots: \
             the other runs",
            (30 * S as i32, 50 * S as i32),
            font(13),
        ))?;
        let (mut x, mut y) = (30 * S as i32, 16 * S as i32);
        for (name, c) in names.iter().zip(colors) {
            let width = (44 + 7 * name.len() as u32) as i32 * S as i32;
            if x + width > (w - 20) as i32 * S as i32 {
                (x, y) = (30 * S as i32, y + 20 * S as i32);
            }
            legend.draw(&PathElement::new(
                vec![(x, y), (x + 26 * S as i32, y)],
                c.stroke_width(2 * S),
            ))?;
            legend.draw(&Circle::new((x + 13 * S as i32, y), 3 * S, c.filled()))?;
            let t = name.to_string();
            legend.draw(&Text::new(
                t,
                (x + 32 * S as i32, y - 7 * S as i32),
                font(14),
            ))?;
            x += width;
        }
        root.present()?;
    }
    let inner = format!("width=\"{}\" height=\"{}\"", w * S, h * S);
    let svg = svg.replacen(&inner, &format!("width=\"{w}\" height=\"{h}\""), 1);
    std::fs::write(path, svg)?;
    Ok(())
}

/// Three significant digits in µs, ms or s.
fn fmt_time(t: f64) -> String {
    let (v, unit) = if t < 1e-3 {
        (t * 1e6, "µs")
    } else if t < 1.0 {
        (t * 1e3, "ms")
    } else {
        (t, "s")
    };
    let prec = if v >= 100.0 {
        0
    } else if v >= 10.0 {
        1
    } else {
        2
    };
    format!("{v:.prec$} {unit}")
}

fn setting(r: &Row) -> String {
    match r.rk4_steps {
        Some(n) => format!("{n} steps"),
        None if r.tol.is_finite() => format!("tol {:.0e}", r.tol),
        None => "—".into(),
    }
}

/// The runs of `method` on `problem` with an error and a time.
fn runs<'a>(rows: &'a [Row], problem: &str, method: &str) -> Vec<&'a Row> {
    rows.iter()
        .filter(|r| r.problem == problem && r.method == method && r.error.is_finite())
        .filter(|r| r.time_s.is_finite())
        .collect()
}

/// One table per accuracy target (per problem and method the cheapest run reaching it, methods
/// in order of that time) and one of the most accurate runs.
fn summary(rows: &[Row], cap: f64) -> String {
    let mut s = format!(
        "Per accuracy target, the cheapest run of each method reaching it, and the most accurate \
         run of each method (cap {cap} s: a method's sweep stops after the first run slower than \
         the cap; that run is kept). Errors: shape relative in f; scan, taper, side max |Δμ| at \
         the grid points; drag max |Δd| of the slip places; whisk max |Δm(0)| at the output \
         angles. \"not reached\": no run of the method within the cap reached the target.\n"
    );
    let line = |r: &Row| {
        format!(
            "{} | {:.1e} | {} | {}",
            setting(r),
            r.error,
            fmt_time(r.time_s),
            r.rhs_evals
        )
    };
    for target in TARGETS {
        let _ = write!(
            s,
            "\n## Error ≤ {target:.0e}\n\n| problem | method | cheapest run | error | time | \
             rhs evals |\n|---|---|---|---|---|---|\n"
        );
        for (prob, _) in PROBLEMS {
            let mut lines: Vec<(f64, String)> = Vec::new();
            for m in METHODS {
                let runs = runs(rows, prob, m);
                if runs.is_empty() {
                    continue;
                }
                let cheap = runs
                    .iter()
                    .filter(|r| r.error <= target)
                    .min_by(|a, b| a.time_s.total_cmp(&b.time_s));
                lines.push(match cheap {
                    Some(r) => (r.time_s, format!("| {prob} | {m} | {} |\n", line(r))),
                    None => (
                        f64::INFINITY,
                        format!("| {prob} | {m} | not reached | | | |\n"),
                    ),
                });
            }
            lines.sort_by(|a, b| a.0.total_cmp(&b.0));
            for (_, l) in lines {
                s.push_str(&l);
            }
        }
    }
    s.push_str(
        "\n## Most accurate run\n\n| problem | method | run | error | time | rhs evals |\n\
         |---|---|---|---|---|---|\n",
    );
    for (prob, _) in PROBLEMS {
        for m in METHODS {
            if let Some(best) = runs(rows, prob, m)
                .into_iter()
                .min_by(|a, b| a.error.total_cmp(&b.error))
            {
                let _ = writeln!(s, "| {prob} | {m} | {} |", line(best));
            }
        }
    }
    let checks: Vec<&Row> = rows
        .iter()
        .filter(|r| r.method == "reference-check" && r.error.is_finite())
        .collect();
    if !checks.is_empty() {
        s.push_str(
            "\n## References\n\nEach reference is single shooting at tol 1e-13 (the closed form \
             for shape and scan); its largest difference from collocation of order 6 at tol \
             1e-11, the same measure as the errors:\n\n| problem | difference |\n|---|---|\n",
        );
        for r in checks {
            let _ = writeln!(s, "| {} | {:.1e} |", r.problem, r.error);
        }
    }
    s
}

/// `WP_ONLY=problem/method`: that method's sweep on that problem, its rows put in place of its
/// rows in the CSV in `dir` (appended if it had none); SVG and summary redrawn, a line appended
/// to `machine.txt`.
fn rerun_only(dir: &Path, only: &str, quick: bool, cap: f64) -> Result<()> {
    let (problem, method) = only.split_once('/').ok_or_else(|| {
        anyhow!("WP_ONLY={only}: expected problem/method, e.g. scan/collocation6")
    })?;
    type Problem = fn(&mut Vec<Row>, bool, f64) -> Result<()>;
    let problems: [(&str, Problem); 6] = [
        ("shape", single_shape),
        ("scan", uniform_scan),
        ("taper", tapered_scan),
        ("side", side_scan),
        ("drag", drag_problem),
        ("whisk", whisk_problem),
    ];
    let run = problems
        .iter()
        .find(|p| p.0 == problem)
        .ok_or_else(|| anyhow!("WP_ONLY={only}: no problem {problem}"))?
        .1;
    let csv = dir.join("work_precision.csv");
    let old = read_csv(&csv)?;
    let load_start = load_average();
    let t0 = Instant::now();
    let mut new = Vec::new();
    run(&mut new, quick, cap)?;
    let total = t0.elapsed().as_secs_f64();
    let is = |r: &Row| r.problem == problem && r.method == method;
    let new: Vec<Row> = new.into_iter().filter(|r| is(r)).collect();
    if new.is_empty() {
        bail!("WP_ONLY={only}: no such rows");
    }
    let at = old.iter().position(&is).unwrap_or(old.len());
    let mut rows: Vec<Row> = old[..at].to_vec();
    rows.extend(new);
    rows.extend(old[at..].iter().filter(|r| !is(r)).cloned());
    write_csv(&csv, &rows)?;
    plot(&dir.join("work_precision.svg"), &rows)?;
    std::fs::write(dir.join("summary.md"), summary(&rows, cap))?;
    let note = format!(
        "rows {only} rerun alone (WP_ONLY): load average at start {load_start}; at end {}; run time {total:.0} s\n",
        load_average()
    );
    let machine = dir.join("machine.txt");
    let before = std::fs::read_to_string(&machine).unwrap_or_default();
    std::fs::write(&machine, before + &note)?;
    eprintln!("rows {only} replaced in {}", csv.display());
    Ok(())
}

/// The output directory: the first argument, else `WP_OUT`, else `target/work_precision`.
fn out_dir() -> PathBuf {
    std::env::args_os()
        .nth(1)
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("WP_OUT").map(PathBuf::from))
        .unwrap_or_else(|| PathBuf::from("target/work_precision"))
}

fn main() -> Result<()> {
    let quick = std::env::var("WP_QUICK").is_ok_and(|v| v == "1");
    let cap: f64 = std::env::var("WP_CAP_S")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(8.0);
    let dir = out_dir();
    std::fs::create_dir_all(&dir)?;
    if std::env::var("WP_PLOT_ONLY").is_ok_and(|v| v == "1") {
        let rows = read_csv(&dir.join("work_precision.csv"))?;
        plot(&dir.join("work_precision.svg"), &rows)?;
        std::fs::write(dir.join("summary.md"), summary(&rows, cap))?;
        eprintln!("re-plotted {}", dir.display());
        return Ok(());
    }
    if let Ok(only) = std::env::var("WP_ONLY") {
        return rerun_only(&dir, &only, quick, cap);
    }
    let load_start = load_average();
    let mut rows = Vec::new();
    let t0 = Instant::now();
    single_shape(&mut rows, quick, cap)?;
    uniform_scan(&mut rows, quick, cap)?;
    tapered_scan(&mut rows, quick, cap)?;
    side_scan(&mut rows, quick, cap)?;
    drag_problem(&mut rows, quick, cap)?;
    whisk_problem(&mut rows, quick, cap)?;
    let total = t0.elapsed().as_secs_f64();
    write_csv(&dir.join("work_precision.csv"), &rows)?;
    plot(&dir.join("work_precision.svg"), &rows)?;
    std::fs::write(dir.join("summary.md"), summary(&rows, cap))?;
    let load = format!(
        "load average (1, 5, 15 min) at start: {load_start}; at end: {}\nrun time: {total:.0} s\n",
        load_average()
    );
    std::fs::write(dir.join("machine.txt"), machine() + &load)?;
    eprintln!("wrote {}", dir.display());
    Ok(())
}
