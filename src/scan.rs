//! `vibrissa scan` and `vibrissa infer`: the stiction scan (numerical, or closed-form on the
//! paper's rod) and its CSV / JSON / human output.

use crate::cli::{InferArgs, MethodArg, ScanArgs};
use crate::error::{solve_fail, usage, Fail, Res};
use crate::numeric;
use crate::output::{csv_line, num, opt, AtomicFile, Sink};
use crate::scene_args::{build_scene, is_paper_rod, not_analytic, units_of, Units};
use crate::solve::ShapeRow;
use elastica::roots::try_brent_root;
use elastica::{Branch, ClosedFormScan, Elastica, ElasticaError, Phase0End};
use serde::Serialize;
use std::io::{self, Write};
use std::time::Instant;
use vibrissa::{ScanOptions, Scene, StopReason};

/// One scan point (the columns of the scan CSV): the library's point, also built from the closed
/// forms for `--method analytic`.
pub type Pt = vibrissa::ScanPoint;

/// True when every value of the point is finite (a result row may be printed).
fn finite(p: &Pt) -> bool {
    [
        p.d, p.mu, p.alpha, p.phi1, p.f, p.fx, p.fy, p.m_base, p.y_max,
    ]
    .iter()
    .all(|v| v.is_finite())
        && p.s_flex.is_none_or(f64::is_finite)
}

/// Why the scan stopped, flattened for CSV / JSON.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct Stop {
    /// `d_max`, `slip`, `penetration`, `fold_in_d`, `solver_failure`, `closed_form_end`
    pub reason: String,
    /// where (last displacement)
    pub d: Option<f64>,
    /// human description
    pub detail: String,
}

impl From<&StopReason> for Stop {
    fn from(s: &StopReason) -> Stop {
        let (reason, d) = match s {
            StopReason::DMax => ("d_max", None),
            StopReason::Slip { d, .. } => ("slip", Some(*d)),
            StopReason::LiftOff { d } => ("lift_off", Some(*d)),
            StopReason::Penetration { d, .. } => ("penetration", Some(*d)),
            StopReason::FoldInD { d } => ("fold_in_d", Some(*d)),
            StopReason::SolverFailure { d, .. } => ("solver_failure", Some(*d)),
        };
        Stop {
            reason: reason.into(),
            d,
            detail: s.to_string(),
        }
    }
}

/// Solver work counters of a scan.
#[derive(Clone, Copy, Debug, Serialize, Default, PartialEq)]
pub struct Work {
    /// Newton iterations
    pub newton_iters: usize,
    /// right-hand-side evaluations
    pub rhs_evals: usize,
    /// linear systems factorized
    pub factorizations: usize,
}

/// A finished scan.
#[derive(Clone, Debug, Serialize)]
pub struct ScanOut {
    /// method used
    pub method: &'static str,
    /// surface height
    pub eta: f64,
    /// start (d = 0)
    pub start: Pt,
    /// mu_max over the scan
    pub mu_max: f64,
    /// d at mu_max (upper end of the measurable range)
    pub d_at_mu_max: f64,
    /// stop reason
    pub stop: Stop,
    /// number of points
    pub points: usize,
    /// solver work
    pub stats: Work,
    /// wall time in ms
    pub time_ms: f64,
    /// the points
    #[serde(skip)]
    pub pts: Vec<Pt>,
    /// shapes of the points (if asked for)
    #[serde(skip)]
    pub shapes: Vec<Vec<ShapeRow>>,
}

/// Scan settings.
#[derive(Clone, Copy, Debug)]
pub struct ScanSpec {
    /// method
    pub method: MethodArg,
    /// tolerance
    pub tol: f64,
    /// largest d
    pub d_max: f64,
    /// output points
    pub points: usize,
    /// slip threshold
    pub mu0: Option<f64>,
    /// samples per shape (0: none)
    pub shape_points: usize,
}

/// Run a scan on a validated scene.
pub fn run_scan(scene: &Scene, spec: &ScanSpec) -> Res<ScanOut> {
    let t0 = Instant::now();
    let mut out = if spec.method == MethodArg::Analytic {
        if !is_paper_rod(scene, true) {
            return Err(not_analytic());
        }
        analytic_scan(scene.eta, spec)?
    } else {
        numeric_scan(scene, spec)?
    };
    // never present non-finite rows
    if let Some(bad) = out.pts.iter().position(|p| !finite(p)) {
        let d = out.pts[bad].d;
        out.pts.truncate(bad);
        out.shapes.truncate(bad);
        out.stop = Stop {
            reason: "solver_failure".into(),
            d: Some(d),
            detail: format!("non-finite values at d = {d}"),
        };
    }
    if !finite(&out.start) || !out.mu_max.is_finite() || !out.d_at_mu_max.is_finite() {
        return Err(solve_fail(
            "the scan produced non-finite start or maximum values",
        ));
    }
    out.points = out.pts.len();
    out.time_ms = t0.elapsed().as_secs_f64() * 1e3;
    Ok(out)
}

fn numeric_scan(scene: &Scene, spec: &ScanSpec) -> Res<ScanOut> {
    let model = numeric::model(scene)?;
    let opts = ScanOptions {
        d_max: spec.d_max,
        points: spec.points,
        mu0: spec.mu0,
        solver: numeric::config(spec.method, spec.tol),
        keep_shapes: (spec.shape_points >= 2).then_some(spec.shape_points),
    };
    let r = vibrissa::scan(&model, &opts)?;
    Ok(ScanOut {
        method: spec.method.name(),
        eta: r.eta,
        start: r.start,
        mu_max: r.mu_max,
        d_at_mu_max: r.d_at_mu_max,
        stop: Stop::from(&r.stop),
        points: r.points.len(),
        stats: Work {
            newton_iters: r.stats.newton_iters,
            rhs_evals: r.stats.rhs_evals,
            factorizations: r.stats.factorizations,
        },
        time_ms: 0.0,
        pts: r.points.clone(),
        shapes: r
            .shapes
            .iter()
            .map(|sh| {
                sh.iter()
                    .map(|p| ShapeRow {
                        s: p.s,
                        x: p.x,
                        y: p.y,
                        phi: p.phi,
                        kappa: p.kappa,
                        m: p.m,
                    })
                    .collect()
            })
            .collect(),
    })
}

/// The closed-form scan along one curve parameter `t`: `t ∈ [0, 1]` phase 0 (alpha from 0 to
/// alpha_t), `t ∈ [1, 2]` phase 1 (phi1 from phi1_t down to phi1_min), `t ∈ [2, 3]` the other
/// sheet beyond the fold in phi1 (phi1 back up). `d(t)` is checked to increase.
pub struct ClosedCurve {
    /// the closed-form scan
    pub cf: ClosedFormScan,
    t_end: f64,
}

impl ClosedCurve {
    /// Set up at height `eta`.
    pub fn new(eta: f64) -> Res<ClosedCurve> {
        let cf = ClosedFormScan::new(eta)?;
        let t_end = cf.curve_end();
        Ok(ClosedCurve { cf, t_end })
    }

    /// The rod at curve parameter `t`.
    pub fn at(&self, t: f64) -> Result<(Elastica, f64), ElasticaError> {
        let cf = &self.cf;
        let p = cf.curve_at(t)?;
        let br = if t <= 1.0 || p.flex == 0 {
            Branch::Convex
        } else {
            Branch::OneFlex
        };
        let e = if t == 1.0 && br == Branch::Convex && cf.phase0_end == Phase0End::TurningPoint {
            Elastica::turning(Branch::Convex, p.alpha)?
        } else {
            Elastica::new(br, p.alpha, p.phi1)?
        };
        Ok((e, p.d))
    }

    /// Scan point at `t`.
    pub fn pt(&self, t: f64) -> Result<Pt, ElasticaError> {
        let (e, d) = self.at(t)?;
        Ok(pt_of(&e, d))
    }
}

fn pt_of(e: &Elastica, d: f64) -> Pt {
    Pt {
        d,
        mu: (-e.alpha).tan(),
        normal: e.f * e.alpha.cos(),
        alpha: e.alpha,
        phi1: e.phi1,
        f: e.f,
        fx: e.fx(),
        fy: e.fy(),
        m_base: e.m_base,
        flex: e.flex_count(),
        s_flex: if e.flex_count() > 0 { e.s_b } else { None },
        y_max: e.y_max(),
        event: None,
    }
}

/// Grid of the curve: (t, d) with d increasing, and how it ends.
fn curve_grid(c: &ClosedCurve) -> (Vec<(f64, f64)>, Stop) {
    const PER_UNIT: usize = 64;
    let n = (c.t_end * PER_UNIT as f64) as usize;
    let mut grid: Vec<(f64, f64)> = Vec::with_capacity(n + 1);
    for i in 0..=n {
        let t = if i == n {
            c.t_end
        } else {
            i as f64 / PER_UNIT as f64
        };
        match c.at(t) {
            Ok((_, d)) => {
                if let Some(&(_, dp)) = grid.last() {
                    if d < dp {
                        return (
                            grid,
                            Stop {
                                reason: "fold_in_d".into(),
                                d: Some(dp),
                                detail: format!("fold in d (snap-through) near d = {dp}"),
                            },
                        );
                    }
                }
                grid.push((t, d));
            }
            Err(e) => {
                let d = grid.last().map(|g| g.1).unwrap_or(0.0);
                return (
                    grid,
                    Stop {
                        reason: "closed_form_end".into(),
                        d: Some(d),
                        detail: format!("closed forms end after d = {d}: {e}"),
                    },
                );
            }
        }
    }
    let d = grid.last().map(|g| g.1).unwrap_or(0.0);
    let stop = if c.cf.phase0_end == Phase0End::TipHorizontal || c.t_end == 2.0 {
        Stop {
            reason: "penetration".into(),
            d: Some(d),
            detail: format!(
                "penetration at d = {d}: the tip slope reaches 0, beyond it the rod would cross the surface"
            ),
        }
    } else {
        Stop {
            reason: "closed_form_end".into(),
            d: Some(d),
            detail: format!("end of the closed-form branches at d = {d}"),
        }
    };
    (grid, stop)
}

/// Parameter `t` with `d(t) = d` inside the grid cell that brackets it.
fn t_of_d(c: &ClosedCurve, grid: &[(f64, f64)], d: f64) -> Res<f64> {
    let i = grid.partition_point(|g| g.1 < d);
    if i == 0 {
        return Ok(grid[0].0);
    }
    if i >= grid.len() {
        return Err(solve_fail(format!(
            "d = {d} is beyond the closed-form curve"
        )));
    }
    let (ta, tb) = (grid[i - 1].0, grid[i].0);
    if grid[i].1 == d {
        return Ok(tb);
    }
    Ok(try_brent_root(|t| Ok(c.at(t)?.1 - d), ta, tb, 1e-15, 200)?)
}

/// The closed-form scan at `d = d_max·i/(N−1)`.
pub fn analytic_scan(eta: f64, spec: &ScanSpec) -> Res<ScanOut> {
    let c = ClosedCurve::new(eta)?;
    let (grid, end) = curve_grid(&c);
    let d_reach = grid.last().map(|g| g.1).unwrap_or(0.0);
    let start = c.pt(0.0)?;
    let n = spec.points;
    let mut pts = Vec::with_capacity(n);
    let mut shapes = Vec::new();
    let mut stop = Stop {
        reason: "d_max".into(),
        d: None,
        detail: "d_max reached".into(),
    };
    let mut prev_t = 0.0;
    for i in 0..n {
        let d = if i + 1 == n {
            spec.d_max
        } else {
            spec.d_max * i as f64 / (n - 1) as f64
        };
        if d > d_reach {
            // the last point is where the curve ends (penetration, fold, end of closed forms)
            if let Some(&(te, de)) = grid.last() {
                if pts.last().is_none_or(|p: &Pt| p.d < de) {
                    let (e, _) = c.at(te)?;
                    pts.push(pt_of(&e, de));
                    if spec.shape_points >= 2 {
                        shapes.push(elastica_shape(&e, spec.shape_points)?);
                    }
                }
            }
            stop = end.clone();
            break;
        }
        let t = t_of_d(&c, &grid, d)?;
        let (mut e, _) = c.at(t)?;
        let mut p = pt_of(&e, d);
        if let Some(mu0) = spec.mu0 {
            if p.mu >= mu0 {
                // the slip point between the previous output point and this one
                let ts = if i == 0 {
                    0.0
                } else {
                    try_brent_root(|t| Ok(c.pt(t)?.mu - mu0), prev_t, t, 1e-15, 200)?
                };
                let (es, ds) = c.at(ts)?;
                e = es;
                p = pt_of(&e, ds);
                stop = Stop {
                    reason: "slip".into(),
                    d: Some(ds),
                    detail: format!("slip at d = {ds} (mu = {})", p.mu),
                };
                pts.push(p);
                if spec.shape_points >= 2 {
                    shapes.push(elastica_shape(&e, spec.shape_points)?);
                }
                break;
            }
        }
        pts.push(p);
        if spec.shape_points >= 2 {
            shapes.push(elastica_shape(&e, spec.shape_points)?);
        }
        prev_t = t;
    }
    // mu_max over what was scanned: the closed-form maximum if reached, else the last point
    let best = c.cf.mu_max()?;
    let last_d = pts.last().map(|p| p.d).unwrap_or(0.0);
    let (mu_max, d_at) = if best.d <= last_d {
        (best.mu, best.d)
    } else {
        let m = pts
            .iter()
            .max_by(|a, b| a.mu.total_cmp(&b.mu))
            .copied()
            .unwrap_or(start);
        (m.mu, m.d)
    };
    Ok(ScanOut {
        method: "analytic",
        eta,
        start,
        mu_max,
        d_at_mu_max: d_at,
        stop,
        points: pts.len(),
        stats: Work::default(),
        time_ms: 0.0,
        pts,
        shapes,
    })
}

/// Closed-form shape samples.
pub fn elastica_shape(e: &Elastica, n: usize) -> Res<Vec<ShapeRow>> {
    Ok(e.shape(n)?
        .into_iter()
        .map(|p| ShapeRow {
            s: p.s,
            x: p.x,
            y: p.y,
            phi: p.phi,
            kappa: p.kappa,
            m: p.kappa,
        })
        .collect())
}

/// Header of the scan CSV.
pub fn header(physical: bool) -> Vec<&'static str> {
    let mut h = vec![
        "d", "mu", "alpha", "phi1", "f", "fx", "fy", "m_base", "flex", "s_flex", "y_max",
    ];
    if physical {
        h.extend(["d_mm", "f_N", "fx_N", "fy_N", "m_base_Nm"]);
    }
    h
}

/// Fields of one scan CSV row.
pub fn row(p: &Pt, u: Option<Units>) -> Vec<String> {
    let mut r = vec![
        num(p.d),
        num(p.mu),
        num(p.alpha),
        num(p.phi1),
        num(p.f),
        num(p.fx),
        num(p.fy),
        num(p.m_base),
        p.flex.to_string(),
        opt(p.s_flex),
        num(p.y_max),
    ];
    if let Some(u) = u {
        r.extend(
            [
                p.d * u.length_mm,
                p.f * u.force_n,
                p.fx * u.force_n,
                p.fy * u.force_n,
                p.m_base * u.moment_nm,
            ]
            .map(num),
        );
    }
    r
}

/// Write the scan points as CSV.
pub fn write_points<W: Write>(w: &mut W, out: &ScanOut, u: Option<Units>) -> Res<()> {
    csv_line(w, &header(u.is_some()))?;
    for p in &out.pts {
        csv_line(w, &row(p, u))?;
    }
    Ok(())
}

/// Write the shapes CSV: point index, d, then the shape in the foot frame (x, y) and in the lab
/// frame (x_lab = x + d: the foot started at 0, the tip stays put).
pub fn write_shapes(path: &std::path::Path, out: &ScanOut) -> Res<()> {
    let mut f = AtomicFile::create(path)?;
    csv_line(
        &mut f,
        &["point", "d", "s", "x", "y", "x_lab", "phi", "kappa", "m"],
    )?;
    for (i, (p, sh)) in out.pts.iter().zip(&out.shapes).enumerate() {
        for q in sh {
            let mut r = vec![i.to_string()];
            r.extend([p.d, q.s, q.x, q.y, q.x + p.d, q.phi, q.kappa, q.m].map(num));
            csv_line(&mut f, &r)?;
        }
    }
    f.commit()
}

/// A short human summary.
pub fn summary(out: &ScanOut, csv: Option<&std::path::Path>) -> String {
    let mut s = format!(
        "scan eta = {} ({}): mu_max = {:.6} at d = {:.6}; start f0 = {:.6}, phi1_0 = {:.6}; {} points; stopped: {}; {:.1} ms",
        out.eta,
        out.method,
        out.mu_max,
        out.d_at_mu_max,
        out.start.f,
        out.start.phi1,
        out.points,
        out.stop.detail,
        out.time_ms
    );
    if let Some(p) = csv {
        s.push_str(&format!("\nCSV written to {}", p.display()));
    }
    s
}

/// JSON summary object.
pub fn json_summary(out: &ScanOut, csv: Option<&std::path::Path>) -> serde_json::Value {
    let mut v = serde_json::to_value(out).unwrap_or(serde_json::Value::Null);
    if let serde_json::Value::Object(m) = &mut v {
        m.insert(
            "stop_reason".into(),
            serde_json::Value::String(out.stop.reason.clone()),
        );
        if let Some(p) = csv {
            m.insert(
                "csv".into(),
                serde_json::Value::String(p.display().to_string()),
            );
        }
    }
    v
}

/// Run `vibrissa scan`.
pub fn run(a: &ScanArgs) -> Res<()> {
    let scene = build_scene(&a.scene, a.eta)?;
    let spec = ScanSpec {
        method: a.solver.method,
        tol: a.solver.tol,
        d_max: a.d_max,
        points: a.points as usize,
        mu0: a.mu0,
        shape_points: if a.shapes.is_some() {
            a.shape_points as usize
        } else {
            0
        },
    };
    let mut out = run_scan(&scene, &spec)?;
    crate::progress::stop();
    if out.pts.is_empty() {
        // the start (d = 0) was solved (run_scan checks it): report it, and why the scan stopped
        out.pts.push(out.start);
        out.points = 1;
    }
    let u = units_of(&scene);
    if let Some(p) = &a.shapes {
        write_shapes(p, &out)?;
    }
    if a.out.is_some() || !a.json {
        let mut sink = Sink::open(a.out.as_deref())?;
        write_points(&mut sink, &out, u)?;
        sink.finish()?;
    }
    if out.stop.reason != "d_max" {
        crate::progress::warn(&format!("the scan stopped early: {}", out.stop.detail));
    }
    if a.json {
        let v = json_summary(&out, a.out.as_deref());
        writeln!(io::stdout(), "{}", serde_json::to_string_pretty(&v)?)?;
    } else if a.out.is_some() {
        writeln!(io::stdout(), "{}", summary(&out, a.out.as_deref()))?;
    } else {
        crate::progress::note(&summary(&out, None));
    }
    Ok(())
}

/// Result of `infer`.
#[derive(Clone, Debug, Serialize)]
pub struct InferOut {
    /// method
    pub method: &'static str,
    /// surface height
    pub eta: f64,
    /// slip displacement
    pub d0: f64,
    /// inferred stiction coefficient
    pub mu0: f64,
    /// mu_max of the scan
    pub mu_max: f64,
    /// measurable range of d: [0, d at mu_max]
    pub d_min: f64,
    /// upper end of the measurable range
    pub d_max_measurable: f64,
}

fn not_measurable(d0: f64, hi: f64) -> Fail {
    usage(format!(
        "d0 = {d0} is outside the measurable range [0, {hi}] = [0, d at mu_max]; beyond d at mu_max mu decreases and d0 does not determine mu0"
    ))
}

/// Run `vibrissa infer`.
pub fn run_infer(a: &InferArgs) -> Res<()> {
    let scene = build_scene(&a.scene, a.eta)?;
    let out = if a.solver.method == MethodArg::Analytic {
        if !is_paper_rod(&scene, true) {
            return Err(not_analytic());
        }
        let c = ClosedCurve::new(scene.eta)?;
        let best = c.cf.mu_max()?;
        if !(a.d0 >= 0.0 && a.d0 <= best.d) {
            return Err(not_measurable(a.d0, best.d));
        }
        let (grid, _) = curve_grid(&c);
        let t = t_of_d(&c, &grid, a.d0)?;
        InferOut {
            method: "analytic",
            eta: scene.eta,
            d0: a.d0,
            mu0: c.pt(t)?.mu,
            mu_max: best.mu,
            d_min: 0.0,
            d_max_measurable: best.d,
        }
    } else {
        let model = numeric::model(&scene)?;
        let opts = ScanOptions {
            d_max: a.d_max,
            points: a.points as usize,
            mu0: None,
            solver: numeric::config(a.solver.method, a.solver.tol),
            keep_shapes: None,
        };
        let r = vibrissa::infer(&model, a.d0, &opts)?;
        InferOut {
            method: a.solver.method.name(),
            eta: scene.eta,
            d0: r.d0,
            mu0: r.mu0,
            mu_max: r.mu_max,
            d_min: r.measurable_d.0,
            d_max_measurable: r.measurable_d.1,
        }
    };
    crate::progress::stop();
    if !(out.mu0.is_finite() && out.mu_max.is_finite()) {
        return Err(solve_fail("the inference produced non-finite values"));
    }
    if a.json {
        writeln!(io::stdout(), "{}", serde_json::to_string_pretty(&out)?)?;
    } else {
        let mut w = std::io::stdout().lock();
        csv_line(
            &mut w,
            &[
                "method",
                "eta",
                "d0",
                "mu0",
                "mu_max",
                "d_min",
                "d_max_measurable",
            ],
        )?;
        csv_line(
            &mut w,
            &[
                out.method.to_string(),
                num(out.eta),
                num(out.d0),
                num(out.mu0),
                num(out.mu_max),
                num(out.d_min),
                num(out.d_max_measurable),
            ],
        )?;
    }
    Ok(())
}
