//! `vibrissa scan` and `vibrissa infer`: the stiction scan (numerical, or closed-form on the
//! paper's rod) and its CSV / JSON / human output.

use crate::cli::{InferArgs, ScanArgs};
use crate::error::{solve_fail, Res};
use crate::present::{mu_text, write_shape_file, Cell, Row, Stop, Work};
use crate::scene_args::{build_scene, Units};
use crate::table::{csv_line, num, opt, Sink};
use serde::Serialize;
use std::io::{self, Write};
use std::time::Instant;
use vibrissa::{Method, ScanOptions, ScanPoint, ScanResult, Scene, StopReason};

/// True when every value of the point is finite (a result row may be printed).
/// (At lift-off the normal force is 0 and the friction ratio unbounded: `mu = ±inf` there.)
fn finite(p: &ScanPoint) -> bool {
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

/// A finished scan as the program presents it: the library's result (its points cut before the
/// first one with a non-finite value), the method that computed the points, why it stopped as
/// written, and the wall time.
#[derive(Clone, Debug)]
pub struct Scanned {
    /// the library's result
    pub result: ScanResult,
    /// the method that computed the points (the rod's own shooter after a handover)
    pub method: Method,
    /// why the scan stopped (a non-finite point is a solver failure there)
    pub stop: StopReason,
    /// wall time in ms
    pub time_ms: f64,
}

/// Run a scan on a validated scene (every method, the closed forms included, through the
/// library's one scan driver); the scene's start and contact model complete `opts`.
pub fn run_scan(scene: &Scene, mut opts: ScanOptions) -> Res<Scanned> {
    let t0 = Instant::now();
    let (rod, surface) = scene.parts()?;
    opts.solver.start = scene.start;
    opts.contact = scene.contact;
    let mut r = vibrissa::scan(&rod, &surface, &opts)?;
    let mut stop = r.stop.clone();
    // never present non-finite rows
    if let Some(bad) = r.points.iter().position(|p| !finite(p)) {
        let d = r.points[bad].d;
        r.points.truncate(bad);
        r.shapes.truncate(bad);
        stop = StopReason::SolverFailure {
            d,
            message: format!("non-finite values at d = {d}"),
        };
    }
    let unbounded = matches!(stop, StopReason::LiftOff { .. }) && r.mu_max.is_infinite();
    if !finite(&r.start) && matches!(stop, StopReason::SolverFailure { .. }) {
        return Err(solve_fail(format!("the scan failed at its start: {stop}")));
    }
    if !finite(&r.start) || !(r.mu_max.is_finite() || unbounded) || !r.d_at_mu_max.is_finite() {
        return Err(solve_fail(
            "the scan produced non-finite start or maximum values",
        ));
    }
    Ok(Scanned {
        method: if r.handover.is_some() {
            Method::Shooting
        } else {
            opts.solver.method
        },
        result: r,
        stop,
        time_ms: t0.elapsed().as_secs_f64() * 1e3,
    })
}

/// Header of the scan CSV: the point, the largest friction ratio a single contact needs
/// (`mu_peak`; `|mu|` with one contact), its contact state (`contact`: `tip`, `side`,
/// `side+tip`, …; `s_c`: the arc length of the first contact inside the rod, empty if none), its
/// physical-unit values (scenes with `[physical]`), and `event` last (empty for grid points; a
/// change of contact state — `touchdown`, `peel_back`, `release` — or the reason the scan
/// stopped — `slip`, `lift_off`, `penetration`, `fold_in_d` — on event rows); with a round tip
/// (`round`) the lab x of its contact point, `x_contact`, after `s_c` (empty where the tip is off
/// the surface), as the drag's.
pub fn header(physical: bool, round: bool) -> Vec<&'static str> {
    let mut h = vec![
        "d", "mu", "alpha", "phi1", "f", "fx", "fy", "m_base", "flex", "s_flex", "y_max", "normal",
        "mu_peak", "contact", "s_c",
    ];
    if round {
        h.push("x_contact");
    }
    if physical {
        h.extend(["d_mm", "f_N", "fx_N", "fy_N", "m_base_Nm"]);
    }
    h.push("event");
    h
}

/// Fields of one scan CSV row.
pub fn row(p: &ScanPoint, u: Option<Units>, round: bool) -> Vec<String> {
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
    if round {
        r.push(opt(p.x_contact));
    }
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

/// Write the scan points as CSV (`round`: the rod has a round tip); with `modes`, the column
/// `omega1_sq` before `event`.
pub fn write_points<W: Write>(
    w: &mut W,
    points: &[ScanPoint],
    (u, round): (Option<Units>, bool),
    modes: Option<&[Option<f64>]>,
) -> Res<()> {
    let mut h = header(u.is_some(), round);
    if modes.is_some() {
        h.insert(h.len() - 1, "omega1_sq");
    }
    csv_line(w, &h)?;
    for (i, p) in points.iter().enumerate() {
        let mut r = row(p, u, round);
        if let Some(m) = modes {
            r.insert(r.len() - 1, opt(m.get(i).copied().flatten()));
        }
        csv_line(w, &r)?;
    }
    Ok(())
}

/// The lowest ω² of each point's state with the tip stuck (`None` where a side touches).
fn lowest_modes(scene: &Scene, points: &[ScanPoint]) -> Res<Vec<Option<f64>>> {
    let (rod, surface) = scene.parts()?;
    let o = vibrissa::modes::ModeOptions {
        count: 1,
        ..Default::default()
    };
    let mut out = Vec::with_capacity(points.len());
    let mut unstable = Vec::new();
    for p in points {
        if p.contact.name() != "tip" {
            out.push(None);
            continue;
        }
        let m = vibrissa::modes::modes_of_point(&rod, &surface, p, &o)?;
        let w2 = m.modes[0].omega2;
        if w2 < 0.0 && p.event != Some(vibrissa::Event::FoldInD) {
            unstable.push(p.d);
        }
        out.push(Some(w2));
    }
    if let Some(d) = unstable.first() {
        crate::progress::warn(&format!(
            "{} rows are unstable (omega1_sq < 0), the first at d = {d}",
            unstable.len()
        ));
    }
    Ok(out)
}

/// Write the shapes CSV: point index, d, then the shape in the foot frame (x, y) and in the lab
/// frame, and the point's event.
pub fn write_shapes(path: &std::path::Path, r: &ScanResult) -> Res<()> {
    write_shape_file(
        path,
        r.points
            .iter()
            .zip(&r.shapes)
            .map(|(p, sh)| (p.d, p.event.map_or("", |e| e.name()), sh.as_slice())),
        false,
    )
}

/// A short human summary.
pub fn summary(out: &Scanned, csv: Option<&std::path::Path>) -> String {
    let r = &out.result;
    let mut s = format!(
        "scan eta = {} ({}): mu_max = {:.6} (mu = {:.6}) at d = {:.6}; start f0 = {:.6}, phi1_0 = {:.6}; {} points; stopped: {}; {:.1} ms",
        r.eta,
        out.method,
        r.mu_max,
        r.mu_at_max,
        r.d_at_mu_max,
        r.start.f,
        r.start.phi1,
        r.points.len(),
        out.stop,
        out.time_ms
    );
    if let Some(p) = csv {
        s.push_str(&format!("\nCSV written to {}", p.display()));
    }
    s
}

/// The JSON summary of a scan: the library's result without its points and shapes, with the
/// method, the stop as written, the wall time and the CSV file.
#[derive(Serialize)]
struct ScanJson<'a> {
    method: Method,
    eta: f64,
    start: &'a ScanPoint,
    mu_max: f64,
    mu_at_max: f64,
    d_at_mu_max: f64,
    range_end: vibrissa::RangeEnd,
    stop: Stop,
    stop_reason: &'a str,
    points: usize,
    stats: Work<'a>,
    time_ms: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    handover: Option<&'a str>,
    #[serde(skip_serializing_if = "Option::is_none")]
    csv: Option<String>,
}

/// JSON summary object (keys in alphabetical order).
pub fn json_summary(out: &Scanned, csv: Option<&std::path::Path>) -> serde_json::Value {
    let r = &out.result;
    let j = ScanJson {
        method: out.method,
        eta: r.eta,
        start: &r.start,
        mu_max: r.mu_max,
        mu_at_max: r.mu_at_max,
        d_at_mu_max: r.d_at_mu_max,
        range_end: r.range_end,
        stop: Stop::from(&out.stop),
        stop_reason: out.stop.name(),
        points: r.points.len(),
        stats: Work(&r.stats),
        time_ms: out.time_ms,
        handover: r.handover.as_deref(),
        csv: csv.map(|p| p.display().to_string()),
    };
    serde_json::to_value(j).unwrap_or(serde_json::Value::Null)
}

/// The options of a scan from its flags.
fn scan_options(a: &ScanArgs) -> ScanOptions {
    ScanOptions {
        d_max: a.d_max,
        points: a.points as usize,
        mu0: a.mu0,
        solver: a.solver.config(Default::default()),
        keep_shapes: a.shapes.as_ref().map(|_| a.shape_points as usize),
        ..ScanOptions::default()
    }
}

/// Run `vibrissa scan`.
pub fn run(a: &ScanArgs) -> Res<()> {
    let scene = build_scene(&a.scene, a.eta)?;
    let mut out = run_scan(&scene, scan_options(a))?;
    crate::progress::stop();
    let r = &mut out.result;
    if r.points.is_empty() {
        // the start (d = 0) was solved (run_scan checks it): report it, and why the scan stopped
        r.points.push(r.start);
    }
    let u = scene.rod()?.units();
    if let Some(p) = &a.shapes {
        write_shapes(p, &out.result)?;
    }
    let modes = if a.modes {
        Some(lowest_modes(&scene, &out.result.points)?)
    } else {
        None
    };
    if a.out.is_some() || !a.json {
        let mut sink = Sink::open(a.out.as_deref())?;
        let round = scene.tip_radius > 0.0;
        write_points(&mut sink, &out.result.points, (u, round), modes.as_deref())?;
        sink.finish()?;
    }
    if !matches!(out.stop, StopReason::DMax) {
        crate::progress::warn(&format!("the scan stopped early: {}", out.stop));
    }
    if let Some(h) = &out.result.handover {
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

/// Run `vibrissa infer`.
pub fn run_infer(a: &InferArgs) -> Res<()> {
    let scene = build_scene(&a.scene, a.eta)?;
    let (rod, surface) = scene.parts()?;
    let opts = ScanOptions {
        d_max: a.d_max,
        points: a.points as usize,
        solver: a.solver.config(scene.start),
        contact: scene.contact,
        ..ScanOptions::default()
    };
    let r = vibrissa::infer(&rod, &surface, a.d0, &opts)?;
    crate::progress::stop();
    // (μ_max is unbounded where the measurable range ends at lift-off: written as inf)
    if !(r.mu0.is_finite() && (r.mu_max.is_finite() || r.mu_max == f64::INFINITY)) {
        return Err(solve_fail("the inference produced non-finite values"));
    }
    let out = Row(vec![
        ("method", Cell::Name(a.solver.method.name())),
        ("eta", Cell::Num(scene.eta)),
        ("d0", Cell::Num(r.d0)),
        ("mu0", Cell::Num(r.mu0)),
        ("mu_max", Cell::Mu(r.mu_max)),
        ("d_min", Cell::Num(r.measurable_d.0)),
        ("d_max_measurable", Cell::Num(r.measurable_d.1)),
    ]);
    if a.json {
        writeln!(io::stdout(), "{}", serde_json::to_string_pretty(&out)?)?;
    } else {
        out.write_csv(&mut std::io::stdout().lock())?;
    }
    Ok(())
}
