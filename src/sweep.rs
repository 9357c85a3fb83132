//! `vibrissa sweep`: a grid of stiction scans over scene parameters, in parallel (rayon), with
//! rows streamed in grid order through a bounded reorder buffer, and `--shard K/N`.

use crate::cli::{Shard, SweepArgs};
use crate::error::{one_line, solve_fail, usage, Fail, Res};
use crate::journal;
use crate::number_text::{short, Axis};
use crate::output_files;
use crate::present::mu_text;
use crate::scan::run_scan;
use crate::scene_args::{
    apply_overrides, apply_physical, physical_src, read_scene_file, units_of, Units,
};
use crate::table::{csv_line, num, opt, Sink};
use crate::validate::{self, SceneSrc, Src};
use rayon::prelude::*;
use std::collections::BTreeMap;
use std::io::{IsTerminal, Write};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::time::Instant;
use vibrissa::limits;
use vibrissa::{
    Method, Precurvature, RangeEnd, ScanOptions, Scene, SolverConfig, Stiffness, StopReason,
};

/// Set while a sweep runs: a panic inside one scene becomes that scene's error row, and the
/// panic hook stays quiet.
pub static QUIET_PANICS: AtomicBool = AtomicBool::new(false);

/// One grid point's parameters (`None` for a scene value: the base scene's).
#[derive(Clone, Debug)]
struct Cell {
    eta: Option<f64>,
    taper: Option<f64>,
    k0: Option<f64>,
    k1: Option<f64>,
    c: Option<f64>,
    beta: Option<f64>,
    method: Method,
    tol: f64,
    /// `None`: never slips
    mu0: Option<f64>,
    d_max: f64,
    points: u32,
}

/// The grid: its axes in grid order (the first slowest, the last fastest; the order of the CSV
/// columns) and index arithmetic. Values are computed per cell, never stored: the size of a grid
/// is known without building it.
struct Grid<'a> {
    /// eta, taper, precurvature, precurvature slope, compliance, surface angle
    scene: [Option<&'a Axis>; 6],
    method: Vec<Method>,
    tol: &'a Axis,
    mu0: Option<&'a Axis>,
    d_max: &'a Axis,
    points: &'a Axis,
}

impl Grid<'_> {
    /// The axes' flags and lengths, in grid order.
    fn lens(&self) -> [(&'static str, u64); 11] {
        let len = |a: Option<&Axis>| a.map_or(1, Axis::len);
        let [e, r, k0, k1, c, b] = self.scene.map(len);
        [
            ("--eta", e),
            ("--taper", r),
            ("--precurvature", k0),
            ("--precurvature-slope", k1),
            ("--support-compliance", c),
            ("--surface-angle", b),
            ("--method", self.method.len() as u64),
            ("--tol", self.tol.len()),
            ("--mu0", len(self.mu0)),
            ("--d-max", self.d_max.len()),
            ("--points", self.points.len()),
        ]
    }

    fn cell(&self, mut i: u64) -> Cell {
        let mut at = [0u64; 11];
        for (k, (_, n)) in self.lens().iter().enumerate().rev() {
            at[k] = i % n;
            i /= n;
        }
        let v = |a: Option<&Axis>, k: usize| a.map(|a| a.get(at[k]));
        Cell {
            eta: v(self.scene[0], 0),
            taper: v(self.scene[1], 1),
            k0: v(self.scene[2], 2),
            k1: v(self.scene[3], 3),
            c: v(self.scene[4], 4),
            beta: v(self.scene[5], 5),
            method: self.method[at[6] as usize],
            tol: self.tol.get(at[7]),
            mu0: v(self.mu0, 8).filter(|m| m.is_finite()),
            d_max: self.d_max.get(at[9]),
            points: self.points.get(at[10]) as u32,
        }
    }
}

/// The scene columns of the sweep CSV, its numeric grid axes (with `tol`).
pub const SCENE_AXES: [&str; 6] = [
    "eta",
    "taper",
    "precurvature",
    "precurvature_slope",
    "support_compliance",
    "surface_angle",
];

/// Columns of the sweep CSV (`physical`: the base scene has physical dimensions).
pub fn header(timing: bool, physical: bool) -> Vec<&'static str> {
    let mut h = vec!["index"];
    h.extend(SCENE_AXES);
    h.extend([
        "method",
        "tol",
        "mu0",
        "d_max",
        "grid_points",
        "f0",
        "phi1_0",
        "mu_max",
        "d_at_mu_max",
        "mu_end",
        "d_end",
        "stop_reason",
        "points",
        "newton_iters",
        "rhs_evals",
    ]);
    if physical {
        h.extend(["f0_N", "d_at_mu_max_mm", "d_end_mm"]);
    }
    if timing {
        h.push("time_ms");
    }
    h.push("error");
    h
}

fn scene_cols(sc: &Scene) -> [String; 6] {
    let taper = match &sc.stiffness {
        Stiffness::Uniform => num(1.0),
        Stiffness::Taper { ratio } => num(*ratio),
        Stiffness::Table { .. } => "table".into(),
    };
    let (k0, k1) = match &sc.precurvature {
        Precurvature::None => (num(0.0), num(0.0)),
        Precurvature::Linear { k0, k1 } => (num(*k0), num(*k1)),
        Precurvature::Table { .. } => ("table".into(), "table".into()),
    };
    [
        num(sc.eta),
        taper,
        k0,
        k1,
        num(sc.support_compliance),
        num(sc.surface_angle),
    ]
}

/// The scene of one grid point.
fn cell_scene(base: &Scene, cell: &Cell) -> Scene {
    let mut sc = base.clone();
    if let Some(e) = cell.eta {
        sc.eta = e;
    }
    apply_overrides(&mut sc, cell.taper, cell.k0, cell.k1, cell.c, cell.beta);
    sc
}

/// Compute one row (never fails: errors go into the `error` column). `Err` only when the
/// scene failed (for the summary count).
fn one_row(base: &Scene, cell: &Cell, idx: u64, a: &SweepArgs) -> (Vec<String>, bool) {
    let t0 = Instant::now();
    let sc = cell_scene(base, cell);
    let mut row = vec![idx.to_string()];
    row.extend(scene_cols(&sc));
    row.push(cell.method.name().to_string());
    row.push(num(cell.tol));
    row.push(opt(cell.mu0));
    row.push(num(cell.d_max));
    row.push(cell.points.to_string());
    let opts = ScanOptions {
        d_max: cell.d_max,
        points: cell.points as usize,
        mu0: cell.mu0,
        solver: SolverConfig {
            method: cell.method,
            tol: cell.tol,
            ..SolverConfig::default()
        },
        ..ScanOptions::default()
    };
    let result = std::panic::catch_unwind(|| -> Res<_> {
        sc.validate()?;
        run_scan(&sc, opts)
    });
    let ms = t0.elapsed().as_secs_f64() * 1e3;
    if let Ok(Ok(o)) = &result {
        // the method that computed the row (a handover to the rod's own shooter shows here)
        row[7] = o.method.to_string();
    }
    let physical = base.physical.is_some();
    let units = if physical { units_of(&sc) } else { None };
    let blank = |row: &mut Vec<String>| {
        row.extend((0..6).map(|_| String::new()));
        row.push("error".into());
        row.extend((0..3).map(|_| String::new()));
        if physical {
            row.extend((0..3).map(|_| String::new()));
        }
    };
    let err = match result {
        Ok(Ok(o)) => {
            let r = &o.result;
            let last = r.points.last().copied().unwrap_or(r.start);
            let failed = matches!(o.stop, StopReason::SolverFailure { .. });
            let known = max_is_known(failed, r.range_end, r.d_at_mu_max, last.d);
            let d_at_mu_max = known.then_some(r.d_at_mu_max);
            row.extend([
                num(r.start.f),
                num(r.start.phi1),
                if known {
                    mu_text(r.mu_max)
                } else {
                    String::new()
                },
                opt(d_at_mu_max),
                mu_text(last.mu),
                num(last.d),
                o.stop.name().to_string(),
                r.points.len().to_string(),
                r.stats.newton_iters.to_string(),
                r.stats.rhs_evals.to_string(),
            ]);
            if physical {
                let u = units.unwrap_or(Units {
                    force_n: f64::NAN,
                    moment_nm: f64::NAN,
                    length_mm: f64::NAN,
                });
                row.extend([
                    num(r.start.f * u.force_n),
                    opt(d_at_mu_max.map(|d| d * u.length_mm)),
                    num(last.d * u.length_mm),
                ]);
            }
            if failed {
                // the scan's rows up to the failure are results; the scene is not
                crate::number_text::shorten_numbers(&one_line(&o.stop.to_string()))
            } else {
                String::new()
            }
        }
        Ok(Err(e)) => {
            blank(&mut row);
            crate::error::shorten(e).message()
        }
        Err(p) => {
            let msg = p
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| p.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "panic".into());
            blank(&mut row);
            format!("internal error: {}", one_line(&msg))
        }
    };
    if a.timing {
        row.push(format!("{ms:.3}"));
    }
    let failed = !err.is_empty();
    row.push(err);
    (row, failed)
}

/// Whether a scan's `mu_max` is a result: always when the scan ended at an event or at d_max;
/// after a solver failure only when the first maximum of |mu| was found before it, at or before
/// the last point the scan reports (`d_last`). Otherwise the measurable range is unknown (|mu|
/// was still rising, or the value comes from beyond the last reported point) and the row leaves
/// `mu_max` and `d_at_mu_max` empty.
fn max_is_known(failed: bool, range_end: RangeEnd, d_at_mu_max: f64, d_last: f64) -> bool {
    !failed || (range_end == RangeEnd::FirstMaximum && d_at_mu_max <= d_last)
}

fn csv_string(fields: &[String]) -> String {
    let mut v = Vec::new();
    // writing to a Vec cannot fail
    let _ = csv_line(&mut v, fields);
    String::from_utf8_lossy(&v).into_owned()
}

/// The base scene (file, then the physical flags), each value checked where the grid does not
/// override it.
fn base_scene(a: &SweepArgs) -> Res<Scene> {
    let mut base = match &a.scene {
        Some(p) => read_scene_file(p)?,
        None => Scene::default(),
    };
    apply_physical(&mut base, &a.physical)?;
    if let Some(r) = a.tip_radius {
        base.tip_radius = r;
    }
    // check the base with the axes' first values in place: each quantity is then checked from
    // where it came (the flag or the file's key); the axes' other values are checked below
    let first = |x: &Option<Axis>| x.as_ref().map(Axis::first);
    let mut probe = base.clone();
    if let Some(e) = first(&a.eta) {
        probe.eta = e;
    }
    apply_overrides(
        &mut probe,
        first(&a.taper),
        first(&a.precurvature),
        first(&a.precurvature_slope),
        first(&a.support_compliance),
        first(&a.surface_angle),
    );
    let flag = |x: &Option<Axis>, f: &'static str| x.as_ref().map(|_| f);
    let src = SceneSrc {
        file: a.scene.as_deref(),
        eta: flag(&a.eta, "--eta"),
        taper: flag(&a.taper, "--taper"),
        k0: flag(&a.precurvature, "--precurvature"),
        k1: flag(&a.precurvature_slope, "--precurvature-slope"),
        c: flag(&a.support_compliance, "--support-compliance"),
        beta: flag(&a.surface_angle, "--surface-angle"),
        tip_radius: a.tip_radius.map(|_| "--tip-radius"),
        physical: physical_src(&a.physical),
    };
    validate::scene(&probe, &src)?;
    validate::model_check(&probe, a.scene.as_deref())?;
    for (x, f, r) in [
        (&a.eta, "--eta", limits::eta()),
        (&a.taper, "--taper", limits::TAPER),
        (&a.precurvature, "--precurvature", limits::PRECURVATURE),
        (
            &a.precurvature_slope,
            "--precurvature-slope",
            limits::PRECURVATURE_SLOPE,
        ),
        (
            &a.support_compliance,
            "--support-compliance",
            limits::SUPPORT_COMPLIANCE,
        ),
        (&a.surface_angle, "--surface-angle", limits::SURFACE_ANGLE),
    ] {
        if let Some(x) = x {
            // the ends of a range suffice: its other values lie between them
            for v in x.extremes() {
                validate::check(Src::Flag(f), v, &r)?;
            }
        }
    }
    // the rest curvature at the tip, K0 + K1, over the extreme combinations
    if a.precurvature.is_some() || a.precurvature_slope.is_some() {
        let (b0, b1) = match &base.precurvature {
            Precurvature::Linear { k0, k1 } => (*k0, *k1),
            _ => (0.0, 0.0),
        };
        let ext = |x: &Option<Axis>, b: f64| x.as_ref().map_or((b, b), Axis::min_max);
        let (lo0, hi0) = ext(&a.precurvature, b0);
        let (lo1, hi1) = ext(&a.precurvature_slope, b1);
        for end in [lo0 + lo1, hi0 + hi1] {
            if !limits::PRECURVATURE.contains(end) {
                return Err(usage(format!(
                    "--precurvature K0 + --precurvature-slope K1 reaches {} (the rest curvature at the tip), outside the valid range {} ({})",
                    short(end),
                    limits::PRECURVATURE.text(6),
                    limits::PRECURVATURE.unit
                )));
            }
        }
    }
    Ok(base)
}

/// Flags whose values may differ when a journal is resumed: they do not change the rows
/// (`--out` is where the journal is; of `--scene` the content counts, not the name).
const NOT_IN_IDENTITY: [&str; 4] = ["jobs", "dry-run", "out", "scene"];

/// What a sweep is, for its journal: the program, the base scene as read (the file's content,
/// not its name alone) and every flag as typed, except [`NOT_IN_IDENTITY`].
fn identity(base: &Scene) -> journal::Identity {
    let mut id = vec![
        (
            "program".to_string(),
            format!("vibrissa {}", env!("CARGO_PKG_VERSION")),
        ),
        (
            "base scene".to_string(),
            serde_json::to_string(base).unwrap_or_default(),
        ),
    ];
    id.extend(crate::cli::typed_values("sweep", &NOT_IN_IDENTITY));
    id
}

/// The grid of a sweep: its axes from the flags (the methods parsed here).
fn grid(a: &SweepArgs) -> Res<Grid<'_>> {
    let methods = a
        .method
        .split(',')
        .map(|m| {
            m.trim().parse::<Method>().map_err(|e| match e {
                // the library's list of names, in the flag's words
                vibrissa::VibrissaError::InvalidName { value, valid, .. } => {
                    usage(format!("--method '{value}': valid values are {valid}"))
                }
                e => e.into(),
            })
        })
        .collect::<Res<Vec<_>>>()?;
    Ok(Grid {
        scene: [
            a.eta.as_ref(),
            a.taper.as_ref(),
            a.precurvature.as_ref(),
            a.precurvature_slope.as_ref(),
            a.support_compliance.as_ref(),
            a.surface_angle.as_ref(),
        ],
        method: methods,
        tol: &a.tol,
        mu0: a.mu0.as_ref(),
        d_max: &a.d_max,
        points: &a.points,
    })
}

/// This process's part of the grid and how it runs: shard `k` of `n` gets the rows `lo..hi`
/// (the `k`-th contiguous block: concatenation keeps the grid order), on `jobs` threads; a
/// file output keeps its finished rows in `journal`.
struct Plan {
    total: u64,
    k: u64,
    n: u64,
    lo: u64,
    hi: u64,
    jobs: usize,
    journal: Option<std::path::PathBuf>,
}

impl Plan {
    fn new(a: &SweepArgs, total: u64) -> Res<Plan> {
        let Shard { k, n } = a.shard.unwrap_or(Shard { k: 1, n: 1 });
        let lo = ((k - 1) as u128 * total as u128 / n as u128) as u64;
        let hi = (k as u128 * total as u128 / n as u128) as u64;
        let jobs = validate::jobs(a.jobs, hi - lo);
        // each worker holds one scan of --points points
        let most_points = a.points.min_max().1 as u64;
        validate::budget(
            "--jobs",
            jobs as u64,
            "--points",
            most_points,
            "scan points",
            limits::BYTES_PER_SCAN_POINT,
        )?;
        if let Some(p) = &a.out {
            output_files::plan(&[("--out", p)], a.dry_run)?;
        }
        let journal = match &a.out {
            Some(p) => output_files::file_target("--out", p)?.map(|t| journal::path_of(&t)),
            None => None,
        };
        Ok(Plan {
            total,
            k,
            n,
            lo,
            hi,
            jobs,
            journal,
        })
    }

    /// `--dry-run`: the grid, this shard and what a journal holds, on stderr.
    fn report(&self, found: Option<&mut journal::Found>) -> Res<()> {
        let (total, k, n, lo, hi, jobs) = (self.total, self.k, self.n, self.lo, self.hi, self.jobs);
        let mut resume = String::new();
        if let (Some(f), Some(j)) = (found, &self.journal) {
            let (done, _) = f.rows(lo, hi, |_| Ok(()))?;
            resume = format!(
                "; resumes from {}: {} of {} rows done",
                j.display(),
                done.rows,
                hi - lo
            );
        }
        crate::progress::note(&format!(
            "sweep: {total} scenes; shard {k}/{n}: rows {lo}..{hi} ({} scenes); {jobs} thread{}{resume}",
            hi - lo,
            if jobs == 1 { "" } else { "s" }
        ));
        Ok(())
    }
}

/// Where the rows go: the output (a file or stdout), the progress bar on a terminal's stderr,
/// the journal.
struct Rows {
    sink: Sink,
    bar: indicatif::ProgressBar,
    show_bar: bool,
    /// rows written to the terminal must not share the bar's line
    to_terminal: bool,
    journal: Option<journal::Journal>,
}

impl Rows {
    fn open(a: &SweepArgs, n: u64) -> Res<Rows> {
        let sink = Sink::open(a.out.as_deref())?;
        let show_bar = std::io::stderr().is_terminal();
        let bar = if show_bar {
            let b = indicatif::ProgressBar::new(n);
            if let Ok(style) = indicatif::ProgressStyle::with_template(
                "{elapsed_precise} [{bar:40}] {pos}/{len} scenes (eta {eta})",
            ) {
                b.set_style(style.progress_chars("=> "));
            }
            b
        } else {
            indicatif::ProgressBar::hidden()
        };
        Ok(Rows {
            sink,
            bar,
            show_bar,
            to_terminal: show_bar && a.out.is_none() && std::io::stdout().is_terminal(),
            journal: None,
        })
    }

    /// Text to the output (around the bar on a terminal).
    fn write(&mut self, text: &str) -> std::io::Result<()> {
        let sink = &mut self.sink;
        if self.to_terminal {
            self.bar.suspend(|| {
                sink.write_all(text.as_bytes())?;
                sink.flush()
            })
        } else {
            sink.write_all(text.as_bytes())
        }
    }

    /// A computed row: to the output and the journal.
    fn put(&mut self, line: &str) -> std::io::Result<()> {
        self.write(line)?;
        match self.journal.as_mut() {
            Some(j) => j
                .append(line)
                .map_err(|e| output_files::named(&j.path().display().to_string(), e)),
            None => Ok(()),
        }
    }

    /// The header (shard 1 only), the journal's finished rows as they were, and the journal
    /// opened for the rest: the rows resumed.
    fn start(
        &mut self,
        a: &SweepArgs,
        plan: &Plan,
        id: &journal::Identity,
        found: Option<journal::Found>,
        physical: bool,
    ) -> Res<journal::Finished> {
        if plan.k == 1 && !a.no_header {
            self.write(&csv_string(&to_strings(&header(a.timing, physical))))?;
        }
        let mut resumed = journal::Finished::default();
        if let Some(j) = &plan.journal {
            let len = match found {
                Some(mut f) => {
                    let (done, len) = f.rows(plan.lo, plan.hi, |row| Ok(self.write(row)?))?;
                    resumed = done;
                    len
                }
                None => 0,
            };
            self.journal = Some(journal::Journal::open(j, id, len)?);
            output_files::note_on_signal(format!(
                "sweep interrupted: its finished rows are kept in {}; the same command resumes it",
                j.display()
            ));
        }
        self.bar.set_position(resumed.rows);
        Ok(resumed)
    }
}

/// What the computed part of a sweep gave: rows written, rows with an error, and the output's
/// failure if it failed or closed (the workers stop then).
struct Computed {
    done: u64,
    failed: u64,
    write_err: Option<std::io::Error>,
}

/// Compute the rows `first..hi` on `pool` and write them in grid order: the workers send each
/// row as it is done, a bounded reorder buffer (`window` rows) passes them on in order.
fn compute(
    rows: &mut Rows,
    pool: rayon::ThreadPool,
    (grid, base, a): (&Grid, &Scene, &SweepArgs),
    (first, hi): (u64, u64),
    jobs: usize,
) -> Computed {
    // set when the output failed or closed: workers skip the remaining scenes
    let stop = AtomicBool::new(false);
    let window = (jobs as u64 * 32).max(64);
    let (tx, rx) = mpsc::sync_channel::<(u64, String, bool)>(window as usize);
    let stop = &stop;
    let mut c = Computed {
        done: 0,
        failed: 0,
        write_err: None,
    };
    std::thread::scope(|s| {
        s.spawn(move || {
            pool.install(|| {
                let mut start = first;
                while start < hi && !stop.load(Ordering::Relaxed) {
                    let end = (start + window).min(hi);
                    (start..end)
                        .into_par_iter()
                        .for_each_with(tx.clone(), |tx, i| {
                            if stop.load(Ordering::Relaxed) {
                                return;
                            }
                            let (row, bad) = one_row(base, &grid.cell(i), i, a);
                            if tx.send((i, csv_string(&row), bad)).is_err() {
                                stop.store(true, Ordering::Relaxed);
                            }
                        });
                    start = end;
                }
            });
            drop(tx);
        });
        let mut next = first;
        let mut buf: BTreeMap<u64, (String, bool)> = BTreeMap::new();
        for (i, line, bad) in rx.iter() {
            buf.insert(i, (line, bad));
            while let Some((l, bad)) = buf.remove(&next) {
                if let Err(e) = rows.put(&l) {
                    c.write_err = Some(e);
                    break;
                }
                c.failed += bad as u64;
                c.done += 1;
                next += 1;
                rows.bar.inc(1);
            }
            if c.write_err.is_none() && !rows.to_terminal {
                if let Err(e) = rows.sink.flush() {
                    c.write_err = Some(e);
                }
            }
            if c.write_err.is_some() {
                // stop promptly: no more scenes, and the workers' sends fail from now on
                stop.store(true, Ordering::Relaxed);
                break;
            }
        }
        drop(rx);
    });
    c
}

/// Run `vibrissa sweep`.
pub fn run(a: &SweepArgs) -> Res<()> {
    let base = base_scene(a)?;
    let grid = grid(a)?;
    let plan = Plan::new(a, validate::grid_size(&grid.lens())?)?;
    let id = identity(&base);
    let mut found = match &plan.journal {
        Some(j) => journal::find(j, &id)?,
        None => None,
    };
    if a.dry_run {
        return plan.report(found.as_mut());
    }
    let jobs = plan.jobs;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs)
        .build()
        .map_err(|e| solve_fail(format!("cannot start {jobs} worker threads: {e}")))?;
    let mut rows = Rows::open(a, plan.hi - plan.lo)?;
    let t0 = Instant::now();
    // the journal's rows go to the output as they were; the rest is computed
    let resumed = rows.start(a, &plan, &id, found, base.physical.is_some())?;
    QUIET_PANICS.store(true, Ordering::SeqCst);
    let c = compute(
        &mut rows,
        pool,
        (&grid, &base, a),
        (plan.lo + resumed.rows, plan.hi),
        jobs,
    );
    QUIET_PANICS.store(false, Ordering::SeqCst);
    rows.bar.finish_and_clear();
    finish(a, &plan, rows, resumed, c, t0)
}

/// Complete the output and the journal, and say how the sweep went: on a terminal the count,
/// and an error when every scene failed.
fn finish(
    a: &SweepArgs,
    plan: &Plan,
    rows: Rows,
    resumed: journal::Finished,
    c: Computed,
    t0: Instant,
) -> Res<()> {
    let kept = |f: Fail| match (&f, &plan.journal) {
        (Fail::Solve(m), Some(j)) => solve_fail(format!(
            "{m}; the {} finished rows are kept in {}: the same command resumes the sweep",
            resumed.rows + c.done,
            j.display()
        )),
        _ => f,
    };
    if let Some(e) = c.write_err {
        return Err(kept(e.into()));
    }
    let Rows {
        sink,
        journal,
        show_bar,
        ..
    } = rows;
    sink.finish().map_err(kept)?;
    if let Some(j) = journal {
        let path = j.path().to_path_buf();
        j.close().map_err(kept)?;
        output_files::remove_after_commit(path);
    }
    let total = resumed.rows + c.done;
    let failed = resumed.failed + c.failed;
    let dest = match &a.out {
        Some(p) => format!("; written to {}", p.display()),
        None => String::new(),
    };
    if show_bar {
        let from = if resumed.rows > 0 {
            format!(", {} of them resumed from the journal", resumed.rows)
        } else {
            String::new()
        };
        crate::progress::note(&format!(
            "sweep: {total} scenes in {:.1} s ({} solved, {failed} with an error{from}){dest}",
            t0.elapsed().as_secs_f64(),
            total - failed
        ));
    }
    if total > 0 && failed == total {
        // the file is written (every row says why its scene failed), and the exit code says
        // that no scene has a result
        output_files::commit_all()?;
        let which = if plan.n > 1 {
            format!("of shard {}/{} ", plan.k, plan.n)
        } else {
            String::new()
        };
        return Err(solve_fail(format!(
            "every scene {which}failed ({total} of {total} rows have an error; the error column says why){dest}"
        )));
    }
    Ok(())
}

fn to_strings(v: &[&str]) -> Vec<String> {
    v.iter().map(|s| s.to_string()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_failed_scan_reports_only_a_maximum_it_reached() {
        use RangeEnd::*;
        // a scan that ended at an event or d_max: its maximum is the result
        for end in [FirstMaximum, Event, DMax] {
            assert!(max_is_known(false, end, 0.3, 0.5));
        }
        // failed: only a first maximum found at or before the last reported point
        assert!(max_is_known(true, FirstMaximum, 0.1, 0.2));
        assert!(max_is_known(true, FirstMaximum, 0.2, 0.2));
        // the scene: the maximum at d = 0.00262 beyond the last point d = 0
        assert!(!max_is_known(true, SolverFailure, 0.00262, 0.0));
        assert!(!max_is_known(true, FirstMaximum, 0.00262, 0.0));
        // |mu| still rising when the solver failed: the measurable range is unknown
        assert!(!max_is_known(true, SolverFailure, 0.1, 0.2));
    }

    #[test]
    fn grid_order_is_the_column_order() {
        let ax = |s: &str| crate::number_text::parse_axis(s).unwrap();
        let (eta, tol, d_max, points) = (ax("0.7,0.8"), ax("1e-10"), ax("0.1,0.2"), ax("3:5:2"));
        let mu0 = crate::number_text::parse_axis_or_inf("0.5,inf").unwrap();
        let g = Grid {
            scene: [Some(&eta), None, None, None, None, None],
            method: vec![Method::Shooting],
            tol: &tol,
            mu0: Some(&mu0),
            d_max: &d_max,
            points: &points,
        };
        let n: u64 = g.lens().iter().map(|l| l.1).product();
        assert_eq!(n, 16);
        let c = |i| {
            let c = g.cell(i);
            (c.eta, c.mu0, c.d_max, c.points)
        };
        assert_eq!(c(0), (Some(0.7), Some(0.5), 0.1, 3));
        assert_eq!(c(1), (Some(0.7), Some(0.5), 0.1, 5));
        assert_eq!(c(2), (Some(0.7), Some(0.5), 0.2, 3));
        // inf never slips
        assert_eq!(c(4), (Some(0.7), None, 0.1, 3));
        assert_eq!(c(15), (Some(0.8), None, 0.2, 5));
    }
}
