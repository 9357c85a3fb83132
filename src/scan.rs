//! `vibrissa scan` and `vibrissa infer`: the stiction scan (numerical, or closed-form on the
//! paper's rod) and its CSV / JSON / human output.

use crate::cli::{InferArgs, MethodArg, ScanArgs};
use crate::error::{solve_fail, Res};
use crate::numeric;
use crate::output::{csv_line, num, opt, AtomicFile, Sink};
use crate::scene_args::{build_scene, Units};
use crate::solve::ShapeRow;
use serde::Serialize;
use std::io::{self, Write};
use std::time::Instant;
use vibrissa::{RangeEnd, ScanOptions, Scene, StopReason};

/// One scan point (the columns of the scan CSV).
pub type Pt = vibrissa::ScanPoint;

/// True when every value of the point is finite (a result row may be printed).
/// (At lift-off the normal force is 0 and the friction ratio unbounded: `mu = ±inf` there.)
fn finite(p: &Pt) -> bool {
    let lift_off = p.event == Some(vibrissa::Event::LiftOff);
    [
        p.d, p.normal, p.alpha, p.phi1, p.f, p.fx, p.fy, p.m_base, p.y_max,
    ]
    .iter()
    .all(|v| v.is_finite())
        && (p.mu.is_finite() || (lift_off && p.mu.is_infinite()))
        && (p.mu_peak.is_finite() || (lift_off && p.mu_peak.is_infinite()))
        && p.s_flex.is_none_or(f64::is_finite)
        && p.s_c.is_none_or(f64::is_finite)
}

/// μ as written: `inf`/`-inf` at lift-off, where it is unbounded.
pub fn mu_text(mu: f64) -> String {
    if mu.is_infinite() {
        if mu > 0.0 { "inf" } else { "-inf" }.to_string()
    } else {
        num(mu)
    }
}

/// Why the scan stopped, flattened for CSV / JSON.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct Stop {
    /// `d_max`, `slip`, `lift_off`, `penetration`, `fold_in_d`, `solver_failure`
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
            StopReason::LiftOff { d, .. } => ("lift_off", Some(*d)),
            StopReason::Penetration { d, .. } => ("penetration", Some(*d)),
            StopReason::FoldInD { d } => ("fold_in_d", Some(*d)),
            StopReason::SlipOff { d } => ("slip_off", Some(*d)),
            StopReason::ContactChange { d, .. } => ("contact_change", Some(*d)),
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
    /// largest |mu| over the measurable range
    pub mu_max: f64,
    /// the signed mu there
    pub mu_at_max: f64,
    /// d at mu_max (upper end of the measurable range)
    pub d_at_mu_max: f64,
    /// what ends the measurable range
    pub range_end: RangeEnd,
    /// stop reason
    pub stop: Stop,
    /// number of points
    pub points: usize,
    /// solver work
    pub stats: Work,
    /// wall time in ms
    pub time_ms: f64,
    /// why the scan ran on the rod's own shooter instead of the requested method
    #[serde(skip_serializing_if = "Option::is_none")]
    pub handover: Option<String>,
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

/// Run a scan on a validated scene (every method, the closed forms included, through the
/// library's one scan driver).
pub fn run_scan(scene: &Scene, spec: &ScanSpec) -> Res<ScanOut> {
    let t0 = Instant::now();
    let (rod, surface) = numeric::parts(scene)?;
    let opts = ScanOptions {
        d_max: spec.d_max,
        points: spec.points,
        mu0: spec.mu0,
        solver: vibrissa::SolverConfig {
            start: scene.start,
            ..numeric::config(spec.method, spec.tol)
        },
        keep_shapes: (spec.shape_points >= 2).then_some(spec.shape_points),
        contact: scene.contact,
    };
    let r = vibrissa::scan(&rod, &surface, &opts)?;
    let mut out = ScanOut {
        // the method that computed the points
        method: if r.handover.is_some() {
            MethodArg::Shooting.name()
        } else {
            spec.method.name()
        },
        handover: r.handover.clone(),
        eta: r.eta,
        start: r.start,
        mu_max: r.mu_max,
        mu_at_max: r.mu_at_max,
        d_at_mu_max: r.d_at_mu_max,
        range_end: r.range_end,
        stop: Stop::from(&r.stop),
        points: r.points.len(),
        stats: Work {
            newton_iters: r.stats.newton_iters,
            rhs_evals: r.stats.rhs_evals,
            factorizations: r.stats.factorizations,
        },
        time_ms: 0.0,
        pts: r.points,
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
    let unbounded = out.stop.reason == "lift_off" && out.mu_max.is_infinite();
    if !finite(&out.start) && out.stop.reason == "solver_failure" {
        return Err(solve_fail(format!(
            "the scan failed at its start: {}",
            out.stop.detail
        )));
    }
    if !finite(&out.start) || !(out.mu_max.is_finite() || unbounded) || !out.d_at_mu_max.is_finite()
    {
        return Err(solve_fail(
            "the scan produced non-finite start or maximum values",
        ));
    }
    out.points = out.pts.len();
    out.time_ms = t0.elapsed().as_secs_f64() * 1e3;
    Ok(out)
}

/// Header of the scan CSV: the point, the largest friction ratio a single contact needs
/// (`mu_peak`; `|mu|` with one contact), its contact state (`contact`: `tip`, `side`,
/// `side+tip`, …; `s_c`: the arc length of the first contact inside the rod, empty if none), its
/// physical-unit values (scenes with `[physical]`), and `event` last (empty for grid points; a
/// change of contact state — `touchdown`, `peel_back`, `release` — or the reason the scan
/// stopped — `slip`, `lift_off`, `penetration`, `fold_in_d` — on event rows).
pub fn header(physical: bool) -> Vec<&'static str> {
    let mut h = vec![
        "d", "mu", "alpha", "phi1", "f", "fx", "fy", "m_base", "flex", "s_flex", "y_max", "normal",
        "mu_peak", "contact", "s_c",
    ];
    if physical {
        h.extend(["d_mm", "f_N", "fx_N", "fy_N", "m_base_Nm"]);
    }
    h.push("event");
    h
}

/// Fields of one scan CSV row.
pub fn row(p: &Pt, u: Option<Units>) -> Vec<String> {
    let mut r = vec![
        num(p.d),
        mu_text(p.mu),
        num(p.alpha),
        num(p.phi1),
        num(p.f),
        num(p.fx),
        num(p.fy),
        num(p.m_base),
        p.flex.to_string(),
        opt(p.s_flex),
        num(p.y_max),
        num(p.normal),
        mu_text(p.mu_peak),
        p.contact.name().to_string(),
        opt(p.s_c),
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
    r.push(p.event.map_or("", |e| e.name()).to_string());
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
/// frame (x_lab = x + d: the foot started at 0, the tip stays put), and the point's event.
pub fn write_shapes(path: &std::path::Path, out: &ScanOut) -> Res<()> {
    write_shape_file(
        path,
        out.pts.iter().zip(&out.shapes).map(|(p, sh)| {
            let rows = sh.iter().map(|q| [q.s, q.x, q.y, q.phi, q.kappa, q.m]);
            (p.d, p.event.map_or("", |e| e.name()), rows.collect())
        }),
    )
}

/// The shapes file of a scan or a drag (columns point, d, s, x, y, x_lab, phi, kappa, m, event;
/// `vibrissa plot` reads it): one `(d, event, samples [s, x, y, φ, κ, m])` per point.
pub fn write_shape_file<'a>(
    path: &std::path::Path,
    points: impl Iterator<Item = (f64, &'a str, Vec<[f64; 6]>)>,
) -> Res<()> {
    let mut f = AtomicFile::create(path)?;
    csv_line(
        &mut f,
        &[
            "point", "d", "s", "x", "y", "x_lab", "phi", "kappa", "m", "event",
        ],
    )?;
    for (i, (d, event, sh)) in points.enumerate() {
        for [s, x, y, phi, kappa, m] in sh {
            let mut r = vec![i.to_string()];
            r.extend([d, s, x, y, x + d, phi, kappa, m].map(num));
            r.push(event.to_string());
            csv_line(&mut f, &r)?;
        }
    }
    f.commit()
}

/// A short human summary.
pub fn summary(out: &ScanOut, csv: Option<&std::path::Path>) -> String {
    let mut s = format!(
        "scan eta = {} ({}): mu_max = {:.6} (mu = {:.6}) at d = {:.6}; start f0 = {:.6}, phi1_0 = {:.6}; {} points; stopped: {}; {:.1} ms",
        out.eta,
        out.method,
        out.mu_max,
        out.mu_at_max,
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
    let u = numeric::parts(&scene)?.0.units();
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
    if let Some(h) = &out.handover {
        crate::progress::warn(h);
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
    /// inferred stiction coefficient |mu(d0)|
    pub mu0: f64,
    /// largest |mu| of the scan (the end of the measurable range of mu0)
    pub mu_max: f64,
    /// measurable range of d: [0, d at mu_max]
    pub d_min: f64,
    /// upper end of the measurable range
    pub d_max_measurable: f64,
}

/// Run `vibrissa infer`.
pub fn run_infer(a: &InferArgs) -> Res<()> {
    let scene = build_scene(&a.scene, a.eta)?;
    let (rod, surface) = numeric::parts(&scene)?;
    let opts = ScanOptions {
        d_max: a.d_max,
        points: a.points as usize,
        mu0: None,
        solver: vibrissa::SolverConfig {
            start: scene.start,
            ..numeric::config(a.solver.method, a.solver.tol)
        },
        keep_shapes: None,
        contact: scene.contact,
    };
    let r = vibrissa::infer(&rod, &surface, a.d0, &opts)?;
    let out = InferOut {
        method: a.solver.method.name(),
        eta: scene.eta,
        d0: r.d0,
        mu0: r.mu0,
        mu_max: r.mu_max,
        d_min: r.measurable_d.0,
        d_max_measurable: r.measurable_d.1,
    };
    crate::progress::stop();
    // (μ_max is unbounded where the measurable range ends at lift-off: written as inf)
    if !(out.mu0.is_finite() && (out.mu_max.is_finite() || out.mu_max == f64::INFINITY)) {
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
                mu_text(out.mu_max),
                num(out.d_min),
                num(out.d_max_measurable),
            ],
        )?;
    }
    Ok(())
}
