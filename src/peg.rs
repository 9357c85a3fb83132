//! Point objects: `vibrissa solve --peg`, `vibrissa whisk`, `vibrissa locate`.

use crate::cli::{LocateArgs, SolveArgs, WhiskArgs};
use crate::error::Res;
use crate::present::{Cell, Row, Work};
use crate::scene_args::build_scene;
use crate::table::{csv_line, num, AtomicFile};
use serde::Serialize;
use std::io::{self, Write};
use std::time::Instant;
use vibrissa::{PegPoint, StopReason, Units, WhiskOptions};

/// Columns of a point-object row.
const HEADER: [&str; 11] = [
    "theta",
    "s_c",
    "f",
    "fx",
    "fy",
    "f_axial",
    "f_transverse",
    "m_base",
    "normal",
    "mu",
    "event",
];

/// The physical columns of a whisk with a physical scene (as the scan's).
const PHYSICAL: [&str; 4] = ["f_N", "fx_N", "fy_N", "m_base_Nm"];

/// The columns of a whisk's rows: [`HEADER`], the physical ones before `event`.
fn header(units: Option<Units>) -> Vec<&'static str> {
    let mut h = HEADER[..10].to_vec();
    if units.is_some() {
        h.extend(PHYSICAL);
    }
    h.push("event");
    h
}

/// A whisk's row: [`row`], the physical columns before `event`, and a fold named as a whisk's
/// (it marches in theta: `fold`, as its stop reason, not the scan's `fold_in_d`).
fn whisk_row(p: &PegPoint, units: Option<Units>) -> Vec<String> {
    let mut r = row(p);
    r.pop();
    if let Some(u) = units {
        r.extend([p.f * u.force_n, p.fx * u.force_n, p.fy * u.force_n].map(num));
        r.push(num(p.m_base * u.moment_nm));
    }
    r.push(p.event.map_or("", event_name).to_string());
    r
}

/// An event's name in a whisk's rows.
pub fn event_name(e: vibrissa::Event) -> &'static str {
    match e {
        vibrissa::Event::FoldInD => "fold",
        e => e.name(),
    }
}

fn row(p: &PegPoint) -> Vec<String> {
    let mut r: Vec<String> = [
        p.theta,
        p.s_c,
        p.f,
        p.fx,
        p.fy,
        p.f_axial,
        p.f_transverse,
        p.m_base,
        p.normal,
        p.mu,
    ]
    .iter()
    .map(|v| num(*v))
    .collect();
    r.push(p.event.map_or("", |e| e.name()).to_string());
    r
}

fn options(a: &crate::cli::SolverArgs, scene: &vibrissa::Scene, mu0: Option<f64>) -> WhiskOptions {
    WhiskOptions {
        mu0: mu0.filter(|m| m.is_finite()),
        solver: a.config(scene.start),
        ..WhiskOptions::default()
    }
}

/// `vibrissa solve --peg X,Y [--theta A]`: one row (or a JSON object) with the columns of
/// [`HEADER`], and `--shape-out`.
pub fn run_solve(a: &SolveArgs) -> Res<()> {
    let scene = build_scene(&a.scene, None)?;
    let rod = scene.rod()?;
    let peg = a.peg.expect("run_solve is called with --peg");
    let theta = a.theta.unwrap_or(0.0);
    let opts = WhiskOptions {
        keep_shapes: a.shape_out.as_ref().map(|_| a.shape_points as usize),
        ..options(&a.solver, &scene, a.mu0)
    };
    let (p, shape) = vibrissa::peg::solve_peg_shape(&rod, [peg.x, peg.y], theta, &opts)?;
    crate::progress::stop();
    if let Some(path) = &a.shape_out {
        crate::present::write_shape(path, &shape)?;
    }
    let stdout = io::stdout();
    let mut w = stdout.lock();
    if a.json {
        serde_json::to_writer_pretty(&mut w, &p)?;
        writeln!(w)?;
    } else {
        csv_line(&mut w, &HEADER[..10])?;
        let mut r = row(&p);
        r.pop();
        csv_line(&mut w, &r)?;
    }
    Ok(())
}

/// The JSON summary of a whisk.
#[derive(Serialize)]
struct WhiskSummary<'a> {
    method: &'static str,
    peg: [f64; 2],
    first_touch: f64,
    s_touch: f64,
    points: usize,
    stop: Stop,
    stats: Work<'a>,
    time_ms: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    csv: Option<String>,
}

/// Why a whisk stopped: its reason, the foot angle there, in words.
#[derive(Serialize)]
struct Stop {
    reason: String,
    theta: Option<f64>,
    detail: String,
}

/// `vibrissa whisk`.
pub fn run_whisk(a: &WhiskArgs) -> Res<()> {
    let t0 = Instant::now();
    let scene = build_scene(&a.scene, None)?;
    let rod = scene.rod()?;
    let opts = WhiskOptions {
        theta_max: a.theta_max,
        points: a.points as usize,
        keep_shapes: a.shapes.as_ref().map(|_| a.shape_points as usize),
        ..options(&a.solver, &scene, a.mu0)
    };
    let r = vibrissa::whisk(&rod, [a.peg.x, a.peg.y], &opts)?;
    crate::progress::stop();
    if let StopReason::SolverFailure { .. } = r.stop {
        return Err(crate::error::solve_fail(format!("whisk: {}", r.stop)));
    }
    if let Some(path) = &a.shapes {
        let mut f = AtomicFile::create(path)?;
        csv_line(
            &mut f,
            &[
                "point", "theta", "s", "x", "y", "phi", "kappa", "m", "event",
            ],
        )?;
        for (i, (p, sh)) in r.points.iter().zip(&r.shapes).enumerate() {
            for q in sh {
                let mut row = vec![i.to_string()];
                row.extend([p.theta, q.s, q.x, q.y, q.phi, q.kappa, q.m].map(num));
                row.push(p.event.map_or("", event_name).to_string());
                csv_line(&mut f, &row)?;
            }
        }
        f.commit()?;
    }
    if a.out.is_some() || !a.json {
        let units = crate::scene_args::units_of(&scene);
        crate::table::write_table(a.out.as_deref(), &header(units), &r.points, |p| {
            whisk_row(p, units)
        })?;
    }
    // a whisk marches in theta: its own names for the end of the range and a fold
    let reason = match &r.stop {
        StopReason::DMax => "theta_max",
        StopReason::FoldInD { .. } => "fold",
        other => other.name(),
    };
    let summary = WhiskSummary {
        method: a.solver.method.name(),
        peg: [a.peg.x, a.peg.y],
        first_touch: r.first_touch,
        s_touch: r.s_touch,
        points: r.points.len(),
        stop: Stop {
            reason: reason.to_string(),
            theta: r.stop.at(),
            detail: match r.stop {
                StopReason::DMax => format!("theta_max = {} reached", a.theta_max),
                _ => r.stop.describe("theta"),
            },
        },
        stats: Work(&r.stats),
        time_ms: t0.elapsed().as_secs_f64() * 1e3,
        csv: a.out.as_ref().map(|p| p.display().to_string()),
    };
    if a.json {
        writeln!(io::stdout(), "{}", serde_json::to_string_pretty(&summary)?)?;
    } else {
        let line = format!(
            "whisk against ({}, {}) ({}): first touch at theta = {:.6} (s = {:.6}); {} rows; stopped: {}",
            a.peg.x,
            a.peg.y,
            summary.method,
            r.first_touch,
            r.s_touch,
            r.points.len(),
            summary.stop.detail
        );
        if a.out.is_some() {
            writeln!(io::stdout(), "{line}")?;
        } else {
            crate::progress::note(&line);
        }
    }
    Ok(())
}

/// `vibrissa locate`.
pub fn run_locate(a: &LocateArgs) -> Res<()> {
    let scene = build_scene(&a.scene, None)?;
    let rod = scene.rod()?;
    // (the scene's start does not enter: the rod is solved through the contact found)
    let cfg = a.solver.config(Default::default());
    let (x, y, s_c) = vibrissa::locate(&rod, a.theta, a.m_base, [a.fx, a.fy], &cfg)?;
    let mut cells: Vec<(&'static str, Cell)> = [
        ("theta", a.theta),
        ("m_base", a.m_base),
        ("fx", a.fx),
        ("fy", a.fy),
        ("x", x),
        ("y", y),
        ("s_c", s_c),
    ]
    .map(|(k, v)| (k, Cell::Num(v)))
    .into();
    if let Some(u) = rod.units() {
        // the object's place in mm (the signals are given in the model's units)
        cells.push(("x_mm", Cell::Num(x * u.length_mm)));
        cells.push(("y_mm", Cell::Num(y * u.length_mm)));
    }
    let out = Row(cells);
    let stdout = io::stdout();
    let mut w = stdout.lock();
    if a.json {
        serde_json::to_writer_pretty(&mut w, &out)?;
        writeln!(w)?;
    } else {
        out.write_csv(&mut w)?;
    }
    Ok(())
}
