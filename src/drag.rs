//! `vibrissa drag` (the stick–slip drag across a surface) and `vibrissa fit` (μs, μk from a
//! measured drag trace).

use crate::cli::{DragArgs, FitArgs};
use crate::error::{solve_fail, usage, Res};
use crate::present::{mu_text, Stop, Work};
use crate::scene_args::build_scene;
use crate::table::{csv_line, num, opt};
use serde::Serialize;
use std::io::{self, Write};
use std::time::Instant;
use vibrissa::drag::{DragRow, DragSummary, SlipEvent};
use vibrissa::fit::{CorrugationFit, FitOptions, FitResult, Signal, Trace};
use vibrissa::{DragOptions, Scene, StopReason, Units};

/// Columns of the drag CSV (`vibrissa plot` reads them by name); with a physical scene
/// `d_mm, x_tip_mm, y_tip_mm, normal_N, fx_N, fy_N, m_base_Nm` before `event`, as the scan's;
/// with a round tip (`round`) its contact point `x_contact` after the tip's (the disk's centre)
/// `x_tip, y_tip`; with a turning support (`turn`) the first column is the turn `theta` (rad),
/// and the physical columns have no `d_mm`.
pub fn header(physical: bool, round: bool, turn: bool) -> Vec<&'static str> {
    let mut h = vec![if turn { "theta" } else { "d" }, "phase", "x_tip", "y_tip"];
    if round {
        h.push("x_contact");
    }
    h.extend(["mu", "mu_s", "normal", "fx", "fy", "m_base", "contact"]);
    if physical {
        if !turn {
            h.push("d_mm");
        }
        h.extend([
            "x_tip_mm",
            "y_tip_mm",
            "normal_N",
            "fx_N",
            "fy_N",
            "m_base_Nm",
        ]);
    }
    h.extend(["event", "jump", "energy_released"]);
    h
}

fn row(r: &DragRow, u: Option<Units>, round: bool, turn: bool) -> Vec<String> {
    let mut v = vec![num(r.d), r.phase.name().to_string()];
    v.extend([r.x_tip, r.y_tip].map(num));
    if round {
        v.push(opt(r.x_contact));
    }
    v.push(mu_text(r.mu));
    v.push(mu_text(r.mu_s));
    v.extend([r.normal, r.fx, r.fy, r.m_base].map(num));
    v.push(r.contact.name().to_string());
    if let Some(u) = u {
        let l = u.length_mm;
        if !turn {
            v.push(num(r.d * l));
        }
        v.extend([r.x_tip * l, r.y_tip * l].map(num));
        v.extend([r.normal, r.fx, r.fy].map(|f| num(f * u.force_n)));
        v.push(num(r.m_base * u.moment_nm));
    }
    v.push(r.event.map_or("", |e| e.name()).to_string());
    v.push(opt(r.jump));
    v.push(opt(r.released));
    v
}

/// Whether every value of a row may be written (μ is unbounded at lift-off, where N = 0).
fn finite(r: &DragRow) -> bool {
    let lift_off = r.event == Some(vibrissa::drag::DragEvent::Contact(vibrissa::Event::LiftOff));
    [r.d, r.x_tip, r.y_tip, r.normal, r.fx, r.fy, r.m_base]
        .iter()
        .all(|v| v.is_finite())
        && (r.mu.is_finite() || (lift_off && r.mu.is_infinite()))
        && !r.mu_s.is_nan()
        && r.jump.is_none_or(f64::is_finite)
        && r.released.is_none_or(f64::is_finite)
}

/// The scene of a drag: the file and the scene flags, then the texture flags (a corrugation, a
/// sum of sines, a grating or a measured profile as the `[surface]`); validated, messages naming
/// the flags.
pub fn scene(a: &DragArgs) -> Res<Scene> {
    let mut sc = build_scene(&a.scene, a.eta)?;
    crate::texture::apply(&a.texture, &mut sc)?;
    if a.mu_s.is_none() && matches!(sc.friction, vibrissa::surface::FrictionProfile::None {}) {
        return Err(usage(
            "no friction: give --mu-s and --mu-k, or a scene file with a [friction] table",
        ));
    }
    Ok(sc)
}

/// The JSON summary of a drag.
#[derive(Serialize)]
struct DragOut<'a> {
    method: &'static str,
    eta: f64,
    mu_s: Option<f64>,
    mu_k: Option<f64>,
    rows: usize,
    #[serde(flatten)]
    summary: &'a DragSummary,
    stop: Stop,
    stop_reason: String,
    stats: Work<'a>,
    time_ms: f64,
    slips: &'a [SlipEvent],
    #[serde(skip_serializing_if = "Option::is_none")]
    csv: Option<String>,
}

/// `vibrissa drag`.
pub fn run(a: &DragArgs) -> Res<()> {
    let t0 = Instant::now();
    let sc = scene(a)?;
    let (rod, surface) = sc.parts()?;
    let opts = DragOptions {
        d_max: a.d_max,
        points: a.points as usize,
        mu_s: a.mu_s,
        mu_k: a.mu_k,
        solver: a.solver.config(sc.start),
        keep_shapes: a.shapes.as_ref().map(|_| a.shape_points as usize),
        contact: sc.contact,
        energy_balance: a.energy_balance,
        max_slips: a.max_slips as usize,
        motion: if a.turn {
            vibrissa::FootMotion::Turn
        } else {
            vibrissa::FootMotion::Along
        },
    };
    let r = vibrissa::drag(&rod, &surface, &opts)?;
    crate::progress::stop();
    if let StopReason::SolverFailure { .. } = r.stop {
        return Err(solve_fail(format!("drag: {}", r.stop)));
    }
    if let Some(bad) = r.rows.iter().find(|p| !finite(p)) {
        return Err(solve_fail(format!(
            "drag: non-finite values in the row at d = {}",
            bad.d
        )));
    }
    if let Some(path) = &a.shapes {
        crate::present::write_shape_file(
            path,
            r.rows
                .iter()
                .zip(&r.shapes)
                .map(|(p, sh)| (p.d, p.event.map_or("", |e| e.name()), sh.as_slice())),
            a.turn,
        )?;
    }
    if a.out.is_some() || !a.json {
        let u = crate::scene_args::units_of(&sc);
        let round = sc.tip_radius > 0.0;
        let h = header(u.is_some(), round, a.turn);
        crate::table::write_table(a.out.as_deref(), &h, &r.rows, |p| row(p, u, round, a.turn))?;
    }
    let stop = Stop::from(&r.stop);
    if !matches!(r.stop, StopReason::DMax) {
        crate::progress::warn(&format!("the drag stopped early: {}", stop.detail));
    }
    speed_warning(a, &rod, &r)?;
    if let Some(h) = &r.handover {
        crate::progress::warn(h);
    }
    let out = DragOut {
        // the method that computed the rows
        method: if r.handover.is_some() {
            vibrissa::Method::Shooting.name()
        } else {
            a.solver.method.name()
        },
        eta: sc.eta,
        mu_s: a.mu_s,
        mu_k: a.mu_k,
        rows: r.rows.len(),
        summary: &r.summary,
        stop_reason: stop.reason.clone(),
        stop,
        stats: Work(&r.stats),
        time_ms: t0.elapsed().as_secs_f64() * 1e3,
        slips: &r.slips,
        csv: a.out.as_ref().map(|p| p.display().to_string()),
    };
    if a.json {
        writeln!(io::stdout(), "{}", serde_json::to_string_pretty(&out)?)?;
    } else {
        let (what, p) = if a.turn {
            ("drag, the support turned,", "theta")
        } else {
            ("drag", "d")
        };
        let line = if r.slips.is_empty() {
            format!(
                "{what} eta = {} ({}): no slip up to {p} = {}; {} rows; stopped: {}; {:.1} ms",
                sc.eta,
                out.method,
                // where the drag ended (d_max only when it got there)
                out.stop.d.unwrap_or(a.d_max),
                out.rows,
                out.stop.detail,
                out.time_ms
            )
        } else {
            let s = &r.summary;
            format!(
                "{what} eta = {} ({}): {} slip{}, first at {p} = {}; slip length {} ± {:.2e}, fx drop {} ± {:.2e}, released energy {:.6e} ± {:.2e}; {} rows; stopped: {}; {:.1} ms",
                sc.eta,
                out.method,
                s.cycles,
                if s.cycles == 1 { "" } else { "s" },
                six_places(r.slips[0].d),
                six_places(s.jump_mean),
                s.jump_std,
                six_places(s.drop_fx_mean),
                s.drop_fx_std,
                s.released_mean,
                s.released_std,
                out.rows,
                out.stop.detail,
                out.time_ms
            )
        };
        match &a.out {
            Some(p) => writeln!(io::stdout(), "{line}\nCSV written to {}", p.display())?,
            None => crate::progress::note(&line),
        }
    }
    Ok(())
}

/// The user's foot speed in normalized units (`--speed`, or `--speed-mm-s` through the time
/// unit of a rod with physical dimensions, keratin's density); `None` without either.
pub fn foot_speed(a: &DragArgs, sc: &Scene) -> Res<Option<f64>> {
    let v = match (a.speed, a.speed_mm_s) {
        (Some(v), _) => (v, "--speed"),
        (None, Some(v)) => (v, "--speed-mm-s"),
        (None, None) => return Ok(None),
    };
    if v.0 <= 0.0 {
        return Err(usage(format!(
            "{} = {} is outside the valid range (0, inf)",
            v.1, v.0
        )));
    }
    if v.1 == "--speed" {
        return Ok(Some(v.0));
    }
    let p = sc.physical.as_ref().ok_or_else(|| {
        usage("--speed-mm-s needs physical dimensions (--length-mm, --youngs-modulus-gpa, --base-diameter-um or a scene's [physical]); --speed takes the normalized speed")
    })?;
    let unit_s = vibrissa::inertia::time_unit_s(p, vibrissa::inertia::KERATIN_DENSITY);
    Ok(Some(v.0 * unit_s / p.length_mm))
}

/// With `--speed`/`--speed-mm-s`: one warning line when the speed is above the scene's
/// quasi-static bound (`vibrissa::quasistatic::speed_bound`, from the first slip and the stuck
/// start's first frequency); nothing without a slip.
fn speed_warning(a: &DragArgs, rod: &vibrissa::Rod, r: &vibrissa::DragResult) -> Res<()> {
    let Some(v) = foot_speed(a, &scene(a)?)? else {
        return Ok(());
    };
    let (Some(start), Some(slip)) = (r.rows.first(), r.slips.first()) else {
        return Ok(());
    };
    let load = vibrissa::modes::BaseLoad {
        m_base: start.m_base,
        fx: start.fx,
        fy: start.fy,
    };
    match vibrissa::quasistatic::speed_bound(rod, &load, slip.d) {
        Ok(b) if v > b.speed => crate::progress::warn(&format!(
            "at the foot speed {v} (rod lengths per time unit) the rod's inertia moves the first slip by more than {} of d = {} (the quasi-static bound of this scene is about {:.3e}: {} x omega1 {:.4} x d; docs/model.md, \"When the quasi-static drag holds\"); these rows are the slow limit",
            vibrissa::quasistatic::SLIP_AGREEMENT,
            slip.d,
            b.speed,
            vibrissa::quasistatic::SPEED_FACTOR,
            b.omega1
        )),
        Ok(_) => {}
        Err(e) => crate::progress::warn(&format!(
            "the quasi-static speed bound of this scene could not be estimated: {e}"
        )),
    }
    Ok(())
}

/// The slips of a trace CSV (see `fit --help`; the library's [`Trace::from_csv`]), with the
/// signals `use_sig` (in [`Signal::ALL`] order) where the file has them.
pub fn read_trace(text: &str, name: &str, use_sig: &[bool; 3]) -> Res<Trace> {
    Trace::from_csv(text, *use_sig).map_err(|e| match e {
        vibrissa::VibrissaError::InvalidTable { reason, .. } => {
            usage(format!("--trace {name}: {reason}"))
        }
        e => e.into(),
    })
}

/// Which of the corrugation's parameters `--fit-corrugation[=PARTS]` frees (the library reads
/// the names).
fn corrugation_parts(list: Option<&str>) -> Res<CorrugationFit> {
    match list {
        None => Ok(CorrugationFit::default()),
        Some(l) => CorrugationFit::from_names(l.split(',')).map_err(|e| match e {
            vibrissa::VibrissaError::InvalidName { value, valid, .. } => usage(format!(
                "--fit-corrugation: '{value}' is not a part of the corrugation ({valid})"
            )),
            e => e.into(),
        }),
    }
}

/// The answer of `vibrissa fit`.
#[derive(Serialize)]
struct FitOut<'a> {
    method: &'static str,
    slips: usize,
    signals: Vec<&'static str>,
    #[serde(flatten)]
    fit: &'a FitResult,
}

/// `vibrissa fit`.
pub fn run_fit(a: &FitArgs) -> Res<()> {
    let mut sc = build_scene(&a.scene, a.eta)?;
    crate::texture::apply(&a.texture, &mut sc)?;
    let name = a.trace.display().to_string();
    let text = if a.trace.as_os_str() == "-" {
        io::read_to_string(io::stdin())
            .map_err(|e| usage(format!("cannot read the trace from stdin (--trace -): {e}")))?
    } else {
        std::fs::read_to_string(&a.trace)
            .map_err(|e| usage(format!("cannot read --trace {name}: {e}")))?
    };
    let mut use_sig = [!a.places_only; 3];
    if let Some(list) = &a.signals {
        use_sig = [false; 3];
        for s in list {
            match Signal::ALL.iter().position(|g| g.name() == s.trim()) {
                Some(k) => use_sig[k] = true,
                None => {
                    return Err(usage(format!(
                        "--signals: '{s}' is not a base signal (fx, fy, m_base)"
                    )))
                }
            }
        }
    }
    let trace = read_trace(&text, &name, &use_sig)?;
    let signals: Vec<&'static str> = Signal::ALL
        .iter()
        .enumerate()
        .filter(|(k, _)| {
            trace
                .slips
                .iter()
                .any(|s| s.before[*k].is_some() || s.after[*k].is_some())
        })
        .map(|(_, s)| s.name())
        .collect();
    let opts = FitOptions {
        fit_eta: a.fit_eta,
        fit_angle: a.fit_angle,
        corrugation: corrugation_parts(a.fit_corrugation.as_deref())?,
        guess: a.mu_s.zip(a.mu_k),
        solver: a.solver.config(sc.start),
        contact: sc.contact,
        ..FitOptions::default()
    };
    let f = vibrissa::fit(&sc, &trace, &opts)?;
    crate::progress::stop();
    if f.params.iter().any(|p| !p.value.is_finite()) {
        return Err(solve_fail(format!("fit: non-finite estimate: {f}")));
    }
    if let Some(m) = &f.message {
        crate::progress::warn(m);
    }
    let out = FitOut {
        method: a.solver.method.name(),
        slips: trace.slips.len(),
        signals,
        fit: &f,
    };
    let stdout = io::stdout();
    let mut w = stdout.lock();
    if a.json {
        serde_json::to_writer_pretty(&mut w, &out)?;
        writeln!(w)?;
    } else {
        csv_line(
            &mut w,
            &["parameter", "value", "std_error", "dof", "identifiable"],
        )?;
        for p in &f.params {
            csv_line(
                &mut w,
                &[
                    p.name.to_string(),
                    num(p.value),
                    opt(p.std_error),
                    opt(p.dof),
                    p.identifiable.to_string(),
                ],
            )?;
        }
    }
    Ok(())
}

/// A summary's value with six decimals (`0.021013`), or in scientific form with six significant
/// digits where six decimals would not show it (`2.34122e-7`, not `0.000000`: a soft support's
/// slips are that short).
fn six_places(v: f64) -> String {
    if v == 0.0 || v.abs() >= 1e-3 || !v.is_finite() {
        format!("{v:.6}")
    } else {
        vibrissa::limits::digits(v, 6)
    }
}
