//! `vibrissa sweep`: a grid of stiction scans over scene parameters, in parallel (rayon), with
//! rows streamed in grid order through a bounded reorder buffer, and `--shard K/N`.

use crate::cli::{MethodArg, Shard, SweepArgs};
use crate::error::{one_line, solve_fail, usage, Res};
use crate::numbers::{short, Axis};
use crate::output::{csv_line, num, Sink};
use crate::outputs;
use crate::scan::{run_scan, ScanSpec};
use crate::scene_args::{
    apply_overrides, apply_physical, physical_src, read_scene_file, units_of, Units,
};
use crate::validate::{self, SceneSrc, Src};
use clap::ValueEnum;
use rayon::prelude::*;
use std::collections::BTreeMap;
use std::io::{IsTerminal, Write};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::time::Instant;
use vibrissa::{Precurvature, Scene, Stiffness};

/// Set while a sweep runs: a panic inside one scene becomes that scene's error row, and the
/// panic hook stays quiet.
pub static QUIET_PANICS: AtomicBool = AtomicBool::new(false);

/// One grid point's parameters (`None`: the base scene's value).
#[derive(Clone, Debug)]
struct Cell {
    eta: Option<f64>,
    taper: Option<f64>,
    k0: Option<f64>,
    k1: Option<f64>,
    c: Option<f64>,
    beta: Option<f64>,
    method: MethodArg,
    tol: f64,
}

/// The grid: axes and index arithmetic (last axis fastest).
struct Grid {
    eta: Vec<Option<f64>>,
    taper: Vec<Option<f64>>,
    k0: Vec<Option<f64>>,
    k1: Vec<Option<f64>>,
    c: Vec<Option<f64>>,
    beta: Vec<Option<f64>>,
    method: Vec<MethodArg>,
    tol: Vec<f64>,
}

impl Grid {
    fn cell(&self, mut i: u64) -> Cell {
        let mut take = |n: usize| {
            let r = (i % n as u64) as usize;
            i /= n as u64;
            r
        };
        let it = take(self.tol.len());
        let im = take(self.method.len());
        let ib = take(self.beta.len());
        let ic = take(self.c.len());
        let i1 = take(self.k1.len());
        let i0 = take(self.k0.len());
        let ir = take(self.taper.len());
        let ie = take(self.eta.len());
        Cell {
            eta: self.eta[ie],
            taper: self.taper[ir],
            k0: self.k0[i0],
            k1: self.k1[i1],
            c: self.c[ic],
            beta: self.beta[ib],
            method: self.method[im],
            tol: self.tol[it],
        }
    }
}

fn axis(a: &Option<Axis>) -> Vec<Option<f64>> {
    match a {
        Some(a) => a.values.iter().copied().map(Some).collect(),
        None => vec![None],
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
    let spec = ScanSpec {
        method: cell.method,
        tol: cell.tol,
        d_max: a.d_max,
        points: a.points as usize,
        mu0: a.mu0,
        shape_points: 0,
    };
    let result = std::panic::catch_unwind(|| -> Res<_> {
        sc.validate()?;
        run_scan(&sc, &spec)
    });
    let ms = t0.elapsed().as_secs_f64() * 1e3;
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
            let last = o.pts.last().copied().unwrap_or(o.start);
            row.extend([
                num(o.start.f),
                num(o.start.phi1),
                num(o.mu_max),
                num(o.d_at_mu_max),
                num(last.mu),
                num(last.d),
                o.stop.reason.clone(),
                o.points.to_string(),
                o.stats.newton_iters.to_string(),
                o.stats.rhs_evals.to_string(),
            ]);
            if physical {
                let u = units.unwrap_or(Units {
                    force_n: f64::NAN,
                    moment_nm: f64::NAN,
                    length_mm: f64::NAN,
                });
                row.extend(
                    [
                        o.start.f * u.force_n,
                        o.d_at_mu_max * u.length_mm,
                        last.d * u.length_mm,
                    ]
                    .map(num),
                );
            }
            String::new()
        }
        Ok(Err(e)) => {
            blank(&mut row);
            validate::shorten(e).message()
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
    // check the base with the axes' first values in place: each quantity is then checked from
    // where it came (the flag or the file's key); the axes' other values are checked below
    let first = |x: &Option<Axis>| x.as_ref().and_then(|x| x.values.first().copied());
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
        physical: physical_src(&a.physical),
    };
    validate::scene(&probe, &src)?;
    validate::model_check(&probe, a.scene.as_deref())?;
    for (x, f, r) in [
        (&a.eta, "--eta", validate::eta_range()),
        (&a.taper, "--taper", validate::TAPER),
        (&a.precurvature, "--precurvature", validate::PRECURVATURE),
        (
            &a.precurvature_slope,
            "--precurvature-slope",
            validate::PRECURVATURE_SLOPE,
        ),
        (
            &a.support_compliance,
            "--support-compliance",
            validate::SUPPORT_COMPLIANCE,
        ),
        (&a.surface_angle, "--surface-angle", validate::SURFACE_ANGLE),
    ] {
        if let Some(x) = x {
            for v in &x.values {
                validate::check(Src::Flag(f), *v, &r)?;
            }
        }
    }
    // the rest curvature at the tip, K0 + K1, over the extreme combinations
    if a.precurvature.is_some() || a.precurvature_slope.is_some() {
        let (b0, b1) = match &base.precurvature {
            Precurvature::Linear { k0, k1 } => (*k0, *k1),
            _ => (0.0, 0.0),
        };
        let ext = |x: &Option<Axis>, b: f64| match x {
            Some(x) => x
                .values
                .iter()
                .fold((f64::MAX, f64::MIN), |(lo, hi), v| (lo.min(*v), hi.max(*v))),
            None => (b, b),
        };
        let (lo0, hi0) = ext(&a.precurvature, b0);
        let (lo1, hi1) = ext(&a.precurvature_slope, b1);
        for end in [lo0 + lo1, hi0 + hi1] {
            if !validate::PRECURVATURE.contains(end) {
                return Err(usage(format!(
                    "--precurvature K0 + --precurvature-slope K1 reaches {} (the rest curvature at the tip), outside the valid range [-3, 3] (1/L)",
                    short(end)
                )));
            }
        }
    }
    Ok(base)
}

/// Run `vibrissa sweep`.
pub fn run(a: &SweepArgs) -> Res<()> {
    let base = base_scene(a)?;
    let methods = a
        .method
        .split(',')
        .map(|m| {
            MethodArg::from_str(m.trim(), false).map_err(|_| {
                usage(format!(
                    "--method '{}': valid values are shooting, multiple-shooting, collocation, collocation6, analytic",
                    m.trim()
                ))
            })
        })
        .collect::<Res<Vec<_>>>()?;
    let grid = Grid {
        eta: axis(&a.eta),
        taper: axis(&a.taper),
        k0: axis(&a.precurvature),
        k1: axis(&a.precurvature_slope),
        c: axis(&a.support_compliance),
        beta: axis(&a.surface_angle),
        method: methods,
        tol: a.tol.values.clone(),
    };
    let total = validate::grid_size(&[
        ("--eta", grid.eta.len()),
        ("--taper", grid.taper.len()),
        ("--precurvature", grid.k0.len()),
        ("--precurvature-slope", grid.k1.len()),
        ("--support-compliance", grid.c.len()),
        ("--surface-angle", grid.beta.len()),
        ("--method", grid.method.len()),
        ("--tol", grid.tol.len()),
    ])?;
    let Shard { k, n } = a.shard.unwrap_or(Shard { k: 1, n: 1 });
    // shard k gets the k-th contiguous block: concatenation keeps the grid order
    let lo = ((k - 1) as u128 * total as u128 / n as u128) as u64;
    let hi = (k as u128 * total as u128 / n as u128) as u64;
    let jobs = validate::jobs(a.jobs, hi - lo);
    // each worker holds one scan of --points points
    validate::budget(
        "--jobs",
        jobs as u64,
        "--points",
        a.points as u64,
        "scan points",
        validate::BYTES_PER_SCAN_POINT,
    )?;
    if a.dry_run {
        if let Some(p) = &a.out {
            outputs::plan(&[("--out", p)], true)?;
        }
        crate::progress::note(&format!(
            "sweep: {total} scenes; shard {k}/{n}: rows {lo}..{hi} ({} scenes); {jobs} threads",
            hi - lo
        ));
        return Ok(());
    }
    if let Some(p) = &a.out {
        outputs::plan(&[("--out", p)], false)?;
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs)
        .build()
        .map_err(|e| solve_fail(format!("cannot start {jobs} worker threads: {e}")))?;
    let mut sink = Sink::open(a.out.as_deref())?;
    let physical = base.physical.is_some();
    let t0 = Instant::now();
    let show_bar = std::io::stderr().is_terminal();
    let bar = if show_bar {
        let b = indicatif::ProgressBar::new(hi - lo);
        if let Ok(style) = indicatif::ProgressStyle::with_template(
            "{elapsed_precise} [{bar:40}] {pos}/{len} scenes (eta {eta})",
        ) {
            b.set_style(style.progress_chars("=> "));
        }
        b
    } else {
        indicatif::ProgressBar::hidden()
    };
    // rows written to the terminal must not share the bar's line
    let to_terminal = show_bar && a.out.is_none() && std::io::stdout().is_terminal();
    let write = |sink: &mut Sink, text: &str| -> std::io::Result<()> {
        if to_terminal {
            bar.suspend(|| {
                sink.write_all(text.as_bytes())?;
                sink.flush()
            })
        } else {
            sink.write_all(text.as_bytes())
        }
    };
    if k == 1 && !a.no_header {
        write(
            &mut sink,
            &csv_string(&to_strings(&header(a.timing, physical))),
        )?;
    }
    QUIET_PANICS.store(true, Ordering::SeqCst);
    // set when the output failed or closed: workers skip the remaining scenes
    let stop = AtomicBool::new(false);
    // bounded window: at most `window` rows wait in the reorder buffer
    let window = (jobs as u64 * 32).max(64);
    let (tx, rx) = mpsc::sync_channel::<(u64, String, bool)>(window as usize);
    let grid = &grid;
    let base = &base;
    let stop = &stop;
    let mut write_err = None;
    let mut failed = 0u64;
    let mut done = 0u64;
    std::thread::scope(|s| {
        s.spawn(move || {
            pool.install(|| {
                let mut start = lo;
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
        let mut next = lo;
        let mut buf: BTreeMap<u64, (String, bool)> = BTreeMap::new();
        for (i, line, bad) in rx.iter() {
            buf.insert(i, (line, bad));
            while let Some((l, bad)) = buf.remove(&next) {
                if let Err(e) = write(&mut sink, &l) {
                    write_err = Some(e);
                    break;
                }
                failed += bad as u64;
                done += 1;
                next += 1;
                bar.inc(1);
            }
            if write_err.is_none() && !to_terminal {
                if let Err(e) = sink.flush() {
                    write_err = Some(e);
                }
            }
            if write_err.is_some() {
                // stop promptly: no more scenes, and the workers' sends fail from now on
                stop.store(true, Ordering::Relaxed);
                break;
            }
        }
        drop(rx);
    });
    QUIET_PANICS.store(false, Ordering::SeqCst);
    bar.finish_and_clear();
    if let Some(e) = write_err {
        return Err(e.into());
    }
    sink.finish()?;
    if show_bar {
        let dest = match &a.out {
            Some(p) => format!("; written to {}", p.display()),
            None => String::new(),
        };
        crate::progress::note(&format!(
            "sweep: {done} scenes in {:.1} s ({} solved, {failed} with an error){dest}",
            t0.elapsed().as_secs_f64(),
            done - failed
        ));
    }
    Ok(())
}

fn to_strings(v: &[&str]) -> Vec<String> {
    v.iter().map(|s| s.to_string()).collect()
}
