//! The Cash–Mazzia test-set study: every implemented problem (`bvp::testset`) × ε ∈ {1e-1, 1e-2,
//! 1e-3, 1e-4} × tol ∈ {1e-4, 1e-6, 1e-8}, each method with default options (shooting: DOP853 at
//! rtol = atol = tol/100 and `tol` as its accuracy) from the same
//! 101-node straight-line guess; `+cont`: the same solve and, if it fails,
//! `bvp::solve_member`: continuation from ε = 0.1 (same guess). The extended problems
//! (`CashMazzia::extended`: growth like 1/ε, fourth order) are included.
//!
//! ```text
//! cargo run --release -p bvp --example testset [-- --quick] [-- --out DIR] [-- --methods A,B]
//!     [-- --guarded | --confirmed | --residual]
//! ```
//!
//! Writes `DIR/bvp.csv` (one row per case and method) and `DIR/summary.md` (per method: converged
//! count, fine-grid error against tol, nodes, time; beside scipy's `solve_bvp` when
//! `DIR/scipy.csv` from `scipy_testset.py` is present). Default DIR: `data/bvp_testset`.
//! Collocation runs with the default control (`ErrorControl::Confirmed`). `--guarded` /
//! `--confirmed` / `--residual`: every collocation case is also run with
//! `ErrorControl::Guarded` / `Confirmed` / `Residual` (the default before issue 34's fourth
//! round) right after it (same machine state), into `DIR/bvp_guarded.csv` /
//! `DIR/bvp_confirmed.csv` / `DIR/bvp_residual.csv` (columns `guard`: the guard's estimate,
//! `confirmation`: the estimate that checked its alarm) and a table of converged counts,
//! counts within 10·tol and total times of both in `summary.md`. `--methods`: only these (e.g. `lobatto4,lobatto6+cont`).
//!
//! Error: `max |y − y_exact| / (1 + |y_exact|)` over a fine grid (2001 equal points plus 9 inside
//! every mesh interval of the solution) and, separately, over the solution's mesh nodes.

use bvp::testset::CashMazzia;
use bvp::{
    solve_member, BvpError, BvpSolver, Collocation, CollocationOptions, ErrorControl, Integrator,
    PathOptions, Scheme, Shooting, ShootingOptions, Solution,
};
use std::collections::HashMap;
use std::fmt::Write as _;
use std::time::Instant;

const EPS: [f64; 4] = [1e-1, 1e-2, 1e-3, 1e-4];
const TOLS: [f64; 3] = [1e-4, 1e-6, 1e-8];
const GUESS_NODES: usize = 101;
const EPS_EASY: f64 = 0.1;

#[derive(Clone, Copy, Debug, PartialEq)]
enum Method {
    Lobatto4,
    Lobatto6,
    Shoot,
    MShoot,
}

impl Method {
    fn name(self) -> &'static str {
        match self {
            Method::Lobatto4 => "lobatto4",
            Method::Lobatto6 => "lobatto6",
            Method::Shoot => "shoot",
            Method::MShoot => "mshoot16",
        }
    }
}

enum Solver {
    Coll(Box<Collocation>),
    Shoot(Box<Shooting>),
}

impl Solver {
    fn guard_error(&self) -> Option<f64> {
        match self {
            Solver::Coll(s) => s.guard_error(),
            Solver::Shoot(_) => None,
        }
    }
    fn confirmation(&self) -> Option<f64> {
        match self {
            Solver::Coll(s) => s.confirmation(),
            Solver::Shoot(_) => None,
        }
    }
}

impl BvpSolver for Solver {
    fn solve<P: bvp::Bvp + ?Sized>(
        &mut self,
        problem: &P,
        guess: &bvp::Guess,
    ) -> Result<Solution, BvpError> {
        match self {
            Solver::Coll(s) => s.solve(problem, guess),
            Solver::Shoot(s) => s.solve(problem, guess),
        }
    }
    fn tolerance(&self) -> Option<f64> {
        match self {
            Solver::Coll(s) => s.tolerance(),
            Solver::Shoot(s) => s.tolerance(),
        }
    }
    fn set_tolerance(&mut self, tol: f64) {
        match self {
            Solver::Coll(s) => s.set_tolerance(tol),
            Solver::Shoot(s) => s.set_tolerance(tol),
        }
    }
    fn set_walking(&mut self, walking: bool) -> bool {
        match self {
            Solver::Coll(s) => s.set_walking(walking),
            Solver::Shoot(s) => s.set_walking(walking),
        }
    }
}

fn solver(m: Method, tol: f64, control: ErrorControl) -> Solver {
    match m {
        Method::Lobatto4 | Method::Lobatto6 => Solver::Coll(Box::new(
            Collocation::new(CollocationOptions {
                scheme: if m == Method::Lobatto4 {
                    Scheme::Lobatto4
                } else {
                    Scheme::Lobatto6
                },
                tol,
                control,
                ..CollocationOptions::default()
            })
            .expect("valid options"),
        )),
        Method::Shoot | Method::MShoot => Solver::Shoot(Box::new(
            Shooting::new(ShootingOptions {
                integrator: Integrator::Adaptive {
                    rtol: 1e-2 * tol,
                    atol: 1e-2 * tol,
                },
                segments: if m == Method::MShoot { 16 } else { 1 },
                tol: Some(tol),
                ..ShootingOptions::default()
            })
            .expect("valid options"),
        )),
    }
}

/// Errors of `y` against the exact solution over a fine grid (2001 equal points plus 9 inside
/// every mesh interval of the solution, and the nodes): `(scaled, pointwise, nodes)`, with
/// `scaled = max |y − y_exact| / (1 + max |y_exact|)` (the solution's scale, the study's measure),
/// `pointwise = max |y − y_exact| / (1 + |y_exact|)` and `nodes` the pointwise error at the nodes.
fn errors(p: &CashMazzia, eps: f64, sol: &Solution) -> (f64, f64, f64) {
    let Some(_) = p.exact(0.0, eps) else {
        return (f64::NAN, f64::NAN, f64::NAN);
    };
    let (a, b) = p.span();
    let mut xs: Vec<f64> = (0..=2000)
        .map(|i| a + (b - a) * i as f64 / 2000.0)
        .collect();
    for w in sol.mesh.windows(2) {
        xs.extend((1..10).map(|j| w[0] + (w[1] - w[0]) * j as f64 / 10.0));
    }
    let mut out = vec![0.0; sol.n];
    let (mut abs, mut top, mut point) = (0.0_f64, 0.0_f64, 0.0_f64);
    let mut node = 0.0_f64;
    for (i, &x) in xs.iter().chain(&sol.mesh).enumerate() {
        let e = p.exact(x, eps).map_or(f64::NAN, |v| v[0]);
        let y = if i >= xs.len() {
            sol.node(i - xs.len())[0]
        } else {
            sol.eval(x, &mut out);
            out[0]
        };
        let d = (y - e).abs();
        abs = abs.max(d);
        top = top.max(e.abs());
        point = point.max(d / (1.0 + e.abs()));
        if i >= xs.len() {
            node = node.max(d / (1.0 + e.abs()));
        }
    }
    (abs / (1.0 + top), point, node)
}

struct Row {
    id: u8,
    eps: f64,
    tol: f64,
    method: String,
    status: String,
    error: f64,
    pointwise: f64,
    node_error: f64,
    estimate: f64,
    /// With `ErrorControl::Guarded`: the guard's estimate of the true error
    /// (`Collocation::guard_error`).
    guard: f64,
    /// With `ErrorControl::Confirmed`: the estimate that checked the guard's alarm
    /// (`Collocation::confirmation`).
    confirmation: f64,
    /// The error's variant (`Fold`, `MeshLimit`, …) of a failed case, else empty.
    kind: String,
    nodes: usize,
    time: f64,
}

fn run_case(
    p: &CashMazzia,
    (eps, tol): (f64, f64),
    (m, cont): (Method, bool),
    control: ErrorControl,
) -> Row {
    if std::env::var("BVP_DEBUG").is_ok() {
        eprintln!("CASE {} {eps:e} {tol:e} {}", p.id(), m.name());
    }
    let guess = p.guess(eps, GUESS_NODES);
    let mut best = f64::INFINITY;
    let mut result = None;
    let (mut guard, mut confirmation) = (None, None);
    let t_all = Instant::now();
    // Repeat fast solves for a steadier time (minimum of the repeats).
    for _ in 0..20 {
        let mut s = solver(m, tol, control);
        let t = Instant::now();
        let r = if cont {
            // Direct first, continuation from EPS_EASY if that fails (bvp::solve_member).
            let opts = PathOptions::default();
            solve_member(p, &mut s, &guess, eps, EPS_EASY, &opts).map(|r| r.solution)
        } else {
            s.solve(&p.at(eps), &guess)
        };
        best = best.min(t.elapsed().as_secs_f64());
        guard = s.guard_error();
        confirmation = s.confirmation();
        let done = t_all.elapsed().as_secs_f64() > 0.05;
        result = Some(r);
        if done {
            break;
        }
    }
    let r = result.expect("at least one run");
    let mut method = format!("{}{}", m.name(), if cont { "+cont" } else { "" });
    if control != ErrorControl::default() {
        write!(method, " ({})", control_name(control)).expect("a String");
    }
    let guard = guard.unwrap_or(f64::NAN);
    let confirmation = confirmation.unwrap_or(f64::NAN);
    match r {
        Ok(sol) => {
            let (error, pointwise, node_error) = errors(p, eps, &sol);
            Row {
                id: p.id(),
                eps,
                tol,
                method,
                status: "Converged".into(),
                error,
                pointwise,
                node_error,
                estimate: sol.stats.error_estimate.unwrap_or(f64::NAN),
                guard,
                confirmation,
                kind: String::new(),
                nodes: sol.len(),
                time: best,
            }
        }
        Err(e) => Row {
            id: p.id(),
            eps,
            tol,
            method,
            status: format!("{:?}", e.status()),
            error: f64::NAN,
            pointwise: f64::NAN,
            node_error: f64::NAN,
            estimate: e.stats().and_then(|s| s.error_estimate).unwrap_or(f64::NAN),
            guard,
            confirmation,
            kind: format!("{e:?}")
                .split([' ', '{', '('])
                .next()
                .unwrap_or("")
                .to_string(),
            nodes: e.stats().map_or(0, |s| s.nodes),
            time: best,
        },
    }
}

/// The name of a control in method names and file names.
fn control_name(control: ErrorControl) -> &'static str {
    match control {
        ErrorControl::Residual => "residual",
        ErrorControl::Guarded => "guarded",
        ErrorControl::Confirmed => "confirmed",
        ErrorControl::Error => "error",
    }
}

/// scipy rows keyed by (id, eps, tol): (converged, error, nodes, time).
/// A titled subset of the problems, by id.
type Subset = (&'static str, fn(u8) -> bool);
/// (problem, eps, tol) as formatted keys.
type Key = (u8, String, String);
/// scipy: (converged, error, nodes, time).
type ScipyRow = (bool, f64, usize, f64);
/// One case of a method: (converged, error, tol, nodes, time, key).
type Case = (bool, f64, f64, usize, f64, Key);

fn read_scipy(path: &std::path::Path) -> HashMap<Key, ScipyRow> {
    let mut out = HashMap::new();
    let Ok(text) = std::fs::read_to_string(path) else {
        return out;
    };
    for line in text.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        if f.len() < 8 {
            continue;
        }
        let key = (
            f[0].parse().unwrap_or(0),
            format!("{:e}", f[1].parse::<f64>().unwrap_or(f64::NAN)),
            format!("{:e}", f[2].parse::<f64>().unwrap_or(f64::NAN)),
        );
        out.insert(
            key,
            (
                f[4] == "Converged",
                f[5].parse().unwrap_or(f64::NAN),
                f[7].parse().unwrap_or(0),
                f[8].parse().unwrap_or(f64::NAN),
            ),
        );
    }
    out
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let quick = args.iter().any(|a| a == "--quick");
    // Each collocation case also with another control, right after it (same machine state):
    // rows in `bvp_<control>.csv`, totals in the summary.
    let second = if args.iter().any(|a| a == "--guarded") {
        Some(ErrorControl::Guarded)
    } else if args.iter().any(|a| a == "--confirmed") {
        Some(ErrorControl::Confirmed)
    } else if args.iter().any(|a| a == "--residual") {
        Some(ErrorControl::Residual)
    } else {
        None
    };
    let only: Option<String> = args
        .iter()
        .position(|a| a == "--methods")
        .and_then(|i| args.get(i + 1).cloned());
    let dir = args
        .iter()
        .position(|a| a == "--out")
        .and_then(|i| args.get(i + 1).cloned())
        .unwrap_or_else(|| "data/bvp_testset".into());
    let dir = std::path::PathBuf::from(dir);
    std::fs::create_dir_all(&dir)?;

    let methods = [
        (Method::Lobatto4, false),
        (Method::Lobatto6, false),
        (Method::Shoot, false),
        (Method::MShoot, false),
        (Method::Lobatto4, true),
        (Method::Lobatto6, true),
        (Method::Shoot, true),
        (Method::MShoot, true),
    ];
    let problems: Vec<CashMazzia> = if quick {
        [1, 6, 20, 23, 25]
            .iter()
            .filter_map(|&i| CashMazzia::new(i))
            .collect()
    } else {
        CashMazzia::all().chain(CashMazzia::extended()).collect()
    };
    let (mut rows, mut base) = (Vec::new(), Vec::new());
    for &(m, cont) in &methods {
        let name = format!("{}{}", m.name(), if cont { "+cont" } else { "" });
        if let Some(o) = &only {
            if !o.split(',').any(|x| x == name) {
                continue;
            }
        }
        let t = Instant::now();
        for p in &problems {
            for &eps in &EPS {
                for &tol in &TOLS {
                    rows.push(run_case(p, (eps, tol), (m, cont), ErrorControl::default()));
                    if let (Some(control), Method::Lobatto4 | Method::Lobatto6) = (second, m) {
                        base.push(run_case(p, (eps, tol), (m, cont), control));
                    }
                }
            }
        }
        eprintln!("{name}: {:.1} s", t.elapsed().as_secs_f64());
    }

    std::fs::write(dir.join("bvp.csv"), csv_of(&rows)?)?;
    if let Some(control) = second {
        let file = format!("bvp_{}.csv", control_name(control));
        std::fs::write(dir.join(file), csv_of(&base)?)?;
    }

    // Summary.
    let scipy = read_scipy(&dir.join("scipy.csv"));
    let mut md = String::new();
    writeln!(
        md,
        "Cash–Mazzia test set × ε ∈ {{1e-1, 1e-2, 1e-3, 1e-4}} × tol ∈ {{1e-4, 1e-6, 1e-8}}; 101-node straight-line guess; default options (shooting: DOP853 at rtol = atol = tol/100, `tol` its accuracy); `+cont`: `bvp::solve_member` (on failure, continuation from ε = 0.1). Error: max |y − y_exact| / (1 + max |y_exact|) over 2001 points, 9 inside every mesh interval and the nodes (relative to the solution's scale).\n"
    )?;
    let subsets: [Subset; 2] = [
        ("published set (28 problems)", |id| id < 100),
        ("published and extended set (32 problems)", |_| true),
    ];
    for (title, keep) in subsets {
        let problems: Vec<CashMazzia> = problems.iter().copied().filter(|p| keep(p.id())).collect();
        let rows: Vec<&Row> = rows.iter().filter(|r| keep(r.id)).collect();
        let cases = problems.len() * EPS.len() * TOLS.len();
        let exact_cases =
            problems.iter().filter(|p| p.has_exact()).count() * EPS.len() * TOLS.len();
        writeln!(
            md,
            "\n### {title}: {cases} cases ({exact_cases} with exact solutions)\n"
        )?;
        writeln!(md, "| solver | converged / {cases} | error ≤ 10·tol (of converged with exact) | median error/tol | median nodes | time vs scipy (geo. mean, both converged) |")?;
        writeln!(md, "|---|---|---|---|---|---|")?;
        let summary = |name: &str, rs: &[Case]| {
            let conv = rs.iter().filter(|r| r.0).count();
            let with_exact: Vec<_> = rs.iter().filter(|r| r.0 && r.1.is_finite()).collect();
            let good = with_exact.iter().filter(|r| r.1 <= 10.0 * r.2).count();
            let mut ratios: Vec<f64> = with_exact.iter().map(|r| r.1 / r.2).collect();
            ratios.sort_by(f64::total_cmp);
            let med = ratios.get(ratios.len() / 2).copied().unwrap_or(f64::NAN);
            let mut nodes: Vec<usize> = rs.iter().filter(|r| r.0).map(|r| r.3).collect();
            nodes.sort_unstable();
            let medn = nodes.get(nodes.len() / 2).copied().unwrap_or(0);
            let mut logs = Vec::new();
            for r in rs.iter().filter(|r| r.0) {
                if let Some(s) = scipy.get(&r.5) {
                    if s.0 && s.3 > 0.0 && r.4 > 0.0 {
                        logs.push((s.3 / r.4).ln());
                    }
                }
            }
            let speed = if logs.is_empty() || name == "scipy solve_bvp" {
                "—".to_string()
            } else {
                format!(
                    "{:.1}× faster ({} cases)",
                    (logs.iter().sum::<f64>() / logs.len() as f64).exp(),
                    logs.len()
                )
            };
            let pct = if with_exact.is_empty() {
                "—".into()
            } else {
                format!(
                    "{good}/{} ({:.0} %)",
                    with_exact.len(),
                    100.0 * good as f64 / with_exact.len() as f64
                )
            };
            format!("| {name} | {conv} | {pct} | {med:.2e} | {medn} | {speed} |")
        };
        if !scipy.is_empty() {
            let rs: Vec<_> = scipy
                .iter()
                .filter(|(k, _)| problems.iter().any(|p| p.id() == k.0))
                .map(|(k, v)| {
                    let tol: f64 = k.2.parse().unwrap_or(f64::NAN);
                    (v.0, v.1, tol, v.2, v.3, k.clone())
                })
                .collect();
            writeln!(md, "{}", summary("scipy solve_bvp", &rs))?;
        }
        let mut names: Vec<String> = Vec::new();
        for r in rows.iter() {
            if !names.contains(&r.method) {
                names.push(r.method.clone());
            }
        }
        for name in &names {
            let rs: Vec<_> = rows
                .iter()
                .filter(|r| &r.method == name)
                .map(|r| {
                    (
                        r.status == "Converged",
                        r.error,
                        r.tol,
                        r.nodes,
                        r.time,
                        (r.id, format!("{:e}", r.eps), format!("{:e}", r.tol)),
                    )
                })
                .collect();
            writeln!(md, "{}", summary(name, &rs))?;
        }
    }
    if let Some(control) = second {
        let name = control_name(control);
        writeln!(
            md,
            "\n### default against `ErrorControl::{control:?}` (all {} problems, each case run both ways back to back)\n",
            problems.len()
        )?;
        writeln!(
            md,
            "| solver | converged default / {name} | error ≤ 10·tol (of converged with exact) default / {name} | total time default / {name} (s) |"
        )?;
        writeln!(md, "|---|---|---|---|")?;
        let suffix = format!(" ({name})");
        let mut names: Vec<&str> = Vec::new();
        for r in &base {
            let name = r.method.trim_end_matches(suffix.as_str());
            if !names.contains(&name) {
                names.push(name);
            }
        }
        for method in names {
            let first: Vec<&Row> = rows.iter().filter(|r| r.method == method).collect();
            let other: Vec<&Row> = base
                .iter()
                .filter(|r| r.method.trim_end_matches(suffix.as_str()) == method)
                .collect();
            let conv = |v: &[&Row]| v.iter().filter(|r| r.status == "Converged").count();
            let good = |v: &[&Row]| {
                let exact = v
                    .iter()
                    .filter(|r| r.status == "Converged" && r.error.is_finite());
                let n = exact.clone().count();
                let ok = exact.filter(|r| r.error <= 10.0 * r.tol).count();
                format!("{ok}/{n}")
            };
            let time = |v: &[&Row]| v.iter().map(|r| r.time).sum::<f64>();
            writeln!(
                md,
                "| {method} | {} / {} | {} / {} | {:.2} / {:.2} |",
                conv(&first),
                conv(&other),
                good(&first),
                good(&other),
                time(&first),
                time(&other)
            )?;
        }
    }
    std::fs::write(dir.join("summary.md"), &md)?;
    print!("{md}");
    Ok(())
}

/// The rows as CSV.
fn csv_of(rows: &[Row]) -> Result<String, std::fmt::Error> {
    let mut csv = String::from(
        "problem,eps,tol,method,status,error,node_error,nodes,time_s,pointwise_error,estimate,guard,error_kind,confirmation\n",
    );
    for r in rows {
        writeln!(
            csv,
            "{},{:e},{:e},{},{},{:.3e},{:.3e},{},{:.4e},{:.3e},{:.3e},{:.3e},{},{:.3e}",
            r.id,
            r.eps,
            r.tol,
            r.method,
            r.status,
            r.error,
            r.node_error,
            r.nodes,
            r.time,
            r.pointwise,
            r.estimate,
            r.guard,
            r.kind,
            r.confirmation
        )?;
    }
    Ok(csv)
}
