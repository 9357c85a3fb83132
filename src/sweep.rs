//! `vibrissa sweep`: a grid of stiction scans over scene parameters, in parallel (rayon), with
//! rows streamed in grid order through a bounded reorder buffer, and `--shard K/N`.

use crate::cli::{MethodArg, SweepArgs};
use crate::error::{one_line, usage, Res};
use crate::output::{csv_line, num, Sink};
use crate::scan::{run_scan, ScanSpec};
use crate::scene_args::{apply_overrides, read_scene_file};
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

/// Parse a grid axis: `a:b:n` (n points, both ends included) or a comma list `v1,v2,...`.
pub fn parse_axis(name: &str, s: &str) -> Res<Vec<f64>> {
    let bad = |why: String| usage(format!("--{name} '{s}': {why}"));
    let num = |t: &str| -> Res<f64> {
        let v: f64 = t
            .trim()
            .parse()
            .map_err(|_| bad(format!("'{}' is not a number", t.trim())))?;
        if v.is_finite() {
            Ok(v)
        } else {
            Err(bad(format!("'{}' is not a finite number", t.trim())))
        }
    };
    if s.contains(':') {
        let parts: Vec<&str> = s.split(':').collect();
        if parts.len() != 3 {
            return Err(bad("a range is a:b:n (start, end, number of points)".into()));
        }
        let (a, b) = (num(parts[0])?, num(parts[1])?);
        let n: usize = parts[2]
            .trim()
            .parse()
            .map_err(|_| bad(format!("'{}' is not a point count", parts[2].trim())))?;
        if n == 0 || n > 10_000_000 {
            return Err(bad(format!("point count {n} is outside [1, 10000000]")));
        }
        if n == 1 {
            return Ok(vec![a]);
        }
        Ok((0..n)
            .map(|i| {
                if i + 1 == n {
                    b
                } else {
                    a + (b - a) * i as f64 / (n - 1) as f64
                }
            })
            .collect())
    } else {
        s.split(',').map(num).collect()
    }
}

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
    fn len(&self) -> usize {
        self.eta.len()
            * self.taper.len()
            * self.k0.len()
            * self.k1.len()
            * self.c.len()
            * self.beta.len()
            * self.method.len()
            * self.tol.len()
    }

    fn cell(&self, mut i: usize) -> Cell {
        let mut take = |n: usize| {
            let r = i % n;
            i /= n;
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

fn axis(name: &str, s: &Option<String>) -> Res<Vec<Option<f64>>> {
    Ok(match s {
        Some(s) => parse_axis(name, s)?.into_iter().map(Some).collect(),
        None => vec![None],
    })
}

/// Parse `K/N` (1-based).
pub fn parse_shard(s: &str) -> Res<(usize, usize)> {
    let bad = || {
        usage(format!(
            "--shard '{s}': expected K/N with 1 <= K <= N (e.g. 3/10)"
        ))
    };
    let (k, n) = s.split_once('/').ok_or_else(bad)?;
    let k: usize = k.trim().parse().map_err(|_| bad())?;
    let n: usize = n.trim().parse().map_err(|_| bad())?;
    if n == 0 || k == 0 || k > n {
        return Err(bad());
    }
    Ok((k, n))
}

/// Columns of the sweep CSV.
pub fn header(timing: bool) -> Vec<&'static str> {
    let mut h = vec![
        "index",
        "eta",
        "taper",
        "precurvature",
        "precurvature_slope",
        "support_compliance",
        "surface_angle",
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
    ];
    if timing {
        h.push("time_ms");
    }
    h.push("error");
    h
}

fn scene_cols(sc: &Scene) -> [String; 6] {
    let taper = match &sc.stiffness {
        Stiffness::Uniform {} => num(1.0),
        Stiffness::Taper { ratio } => num(*ratio),
        Stiffness::Table { .. } => "table".into(),
    };
    let (k0, k1) = match &sc.precurvature {
        Precurvature::None {} => (num(0.0), num(0.0)),
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

/// Compute one row (never fails: errors go into the `error` column).
fn one_row(base: &Scene, cell: &Cell, idx: usize, a: &SweepArgs) -> Vec<String> {
    let t0 = Instant::now();
    let mut sc = base.clone();
    if let Some(e) = cell.eta {
        sc.eta = e;
    }
    apply_overrides(&mut sc, cell.taper, cell.k0, cell.k1, cell.c, cell.beta);
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
            String::new()
        }
        Ok(Err(e)) => {
            row.extend((0..6).map(|_| String::new()));
            row.push("error".into());
            row.extend((0..3).map(|_| String::new()));
            e.message()
        }
        Err(p) => {
            let msg = p
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| p.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "panic".into());
            row.extend((0..6).map(|_| String::new()));
            row.push("error".into());
            row.extend((0..3).map(|_| String::new()));
            format!("internal error: {}", one_line(&msg))
        }
    };
    if a.timing {
        row.push(format!("{ms:.3}"));
    }
    row.push(err);
    row
}

fn csv_string(fields: &[String]) -> String {
    let mut v = Vec::new();
    // writing to a Vec cannot fail
    let _ = csv_line(&mut v, fields);
    String::from_utf8_lossy(&v).into_owned()
}

/// Run `vibrissa sweep`.
pub fn run(a: &SweepArgs) -> Res<()> {
    let base = match &a.scene {
        Some(p) => read_scene_file(p)?,
        None => Scene::default(),
    };
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
    let tols = parse_axis("tol", &a.tol)?;
    if let Some(t) = tols.iter().find(|t| **t <= 0.0) {
        return Err(usage(format!("--tol: {t} must be > 0")));
    }
    let grid = Grid {
        eta: axis("eta", &a.eta)?,
        taper: axis("taper", &a.taper)?,
        k0: axis("precurvature", &a.precurvature)?,
        k1: axis("precurvature-slope", &a.precurvature_slope)?,
        c: axis("support-compliance", &a.support_compliance)?,
        beta: axis("surface-angle", &a.surface_angle)?,
        method: methods,
        tol: tols,
    };
    let total = grid.len();
    let (k, n) = match &a.shard {
        Some(s) => parse_shard(s)?,
        None => (1, 1),
    };
    // shard k gets the k-th contiguous block: concatenation keeps the grid order
    let lo = ((k - 1) as u128 * total as u128 / n as u128) as usize;
    let hi = (k as u128 * total as u128 / n as u128) as usize;
    if a.dry_run {
        eprintln!(
            "sweep: {total} scenes; shard {k}/{n}: rows {lo}..{hi} ({} scenes)",
            hi - lo
        );
        return Ok(());
    }
    let jobs = a
        .jobs
        .map(|j| j as usize)
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs)
        .build()
        .map_err(|e| usage(format!("cannot start {jobs} worker threads: {e}")))?;
    let mut sink = Sink::open(a.out.as_deref())?;
    if k == 1 && !a.no_header {
        csv_line(&mut sink, &header(a.timing))?;
    }
    let bar = if std::io::stderr().is_terminal() {
        let b = indicatif::ProgressBar::new((hi - lo) as u64);
        if let Ok(style) = indicatif::ProgressStyle::with_template(
            "{elapsed_precise} [{bar:40}] {pos}/{len} scenes (eta {eta})",
        ) {
            b.set_style(style.progress_chars("=> "));
        }
        b
    } else {
        indicatif::ProgressBar::hidden()
    };
    QUIET_PANICS.store(true, Ordering::SeqCst);
    // bounded window: at most `window` rows wait in the reorder buffer
    let window = (jobs * 32).max(64);
    let (tx, rx) = mpsc::sync_channel::<(usize, String)>(window);
    let grid = &grid;
    let base = &base;
    let mut write_err = None;
    std::thread::scope(|s| {
        s.spawn(move || {
            pool.install(|| {
                let mut start = lo;
                while start < hi {
                    let end = (start + window).min(hi);
                    (start..end)
                        .into_par_iter()
                        .for_each_with(tx.clone(), |tx, i| {
                            let row = one_row(base, &grid.cell(i), i, a);
                            let _ = tx.send((i, csv_string(&row)));
                        });
                    start = end;
                }
            });
            drop(tx);
        });
        let mut next = lo;
        let mut buf: BTreeMap<usize, String> = BTreeMap::new();
        for (i, line) in rx {
            buf.insert(i, line);
            while let Some(l) = buf.remove(&next) {
                if write_err.is_none() {
                    if let Err(e) = sink.write_all(l.as_bytes()) {
                        write_err = Some(e);
                    }
                }
                next += 1;
                bar.inc(1);
            }
            if write_err.is_none() {
                if let Err(e) = sink.flush() {
                    write_err = Some(e);
                }
            }
        }
    });
    QUIET_PANICS.store(false, Ordering::SeqCst);
    bar.finish_and_clear();
    if let Some(e) = write_err {
        return Err(e.into());
    }
    sink.finish()
}
