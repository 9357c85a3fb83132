//! `vibrissa dynamics drag` (the foot dragged at a speed with the tip on the surface, in time:
//! `vibrissa::dynamics::drag`) and `vibrissa dynamics free` (the rod released from a tip force
//! or a foot moment: `vibrissa::dynamics::free`), issue 32; with `--spectrum`, the amplitude
//! spectrum of the moment at the foot (`vibrissa::spectrum`).

use crate::cli::{
    DynamicsArgs, DynamicsCommand, DynamicsDragArgs, DynamicsFreeArgs, TimeSchemeArg,
};
use crate::error::Res;
use crate::scene_args::build_scene;
use crate::table::{csv_line, num, Sink};
use std::io::Write;
use std::path::Path;
use vibrissa::dynamics::{drag, free, DynDragOptions, DynamicsOptions, TimeScheme};
use vibrissa::inertia::{time_unit_s, KERATIN_DENSITY};
use vibrissa::spectrum::amplitude_spectrum;
use vibrissa::{Rod, Units};

/// Columns of the drag's CSV: one row per time step (the start included); with a physical
/// scene [`DRAG_PHYSICAL`] before `event`.
pub const HEADER: [&str; 17] = [
    "t",
    "d",
    "tip_x",
    "tip_y",
    "tip_vx",
    "tip_vy",
    "state",
    "normal",
    "tangential",
    "fx",
    "fy",
    "m_base",
    "kinetic",
    "elastic",
    "foot_work",
    "friction",
    "damper",
];

/// The drag's physical-unit columns (seconds, mm, N, N·m).
pub const DRAG_PHYSICAL: [&str; 9] = [
    "t_s",
    "d_mm",
    "tip_x_mm",
    "tip_y_mm",
    "normal_N",
    "tangential_N",
    "fx_N",
    "fy_N",
    "m_base_Nm",
];

/// The drag's columns of a side's contact (`side_stuck` rows; empty in the others), in a drag
/// that has one, before `event`: its arc length and place.
pub const SIDE_COLUMNS: [&str; 3] = ["side_s", "side_x", "side_y"];

/// The drag's columns of the tip on the surface beside a side (two contacts at once; empty in
/// the other rows), in a drag that has such rows, after [`SIDE_COLUMNS`]: the tip's state and
/// its normal and tangential forces (`normal` and `tangential` are the side's in those rows).
pub const TIP_ALSO_COLUMNS: [&str; 3] = ["tip_state", "tip_normal", "tip_tangential"];

/// Columns of `dynamics free`: one row per time step (the start included); with a physical
/// scene [`FREE_PHYSICAL`] after them.
pub const FREE_HEADER: [&str; 12] = [
    "t", "tip_x", "tip_y", "tip_vx", "tip_vy", "theta", "fx", "fy", "m_base", "kinetic", "elastic",
    "damper",
];

/// The free rod's physical-unit columns.
pub const FREE_PHYSICAL: [&str; 6] = ["t_s", "tip_x_mm", "tip_y_mm", "fx_N", "fy_N", "m_base_Nm"];

/// Run `vibrissa dynamics ...`.
pub fn run(a: &DynamicsArgs) -> Res<()> {
    match &a.command {
        DynamicsCommand::Drag(d) => run_drag(d),
        DynamicsCommand::Free(f) => run_free(f),
    }
}

/// The options of the drag's flags (`--foot-table` read from its file).
pub fn options(a: &DynamicsDragArgs) -> Res<DynDragOptions> {
    let foot_table = match &a.foot_table {
        Some(path) => vibrissa::dynamics::read_foot_table(path)?,
        None => vec![],
    };
    Ok(DynDragOptions {
        speed: a.speed,
        ramp: a.ramp,
        d_max: a.d_max,
        mu_s: a.mu_s.unwrap_or(DynDragOptions::default().mu_s),
        mu_k: a.mu_k.unwrap_or(DynDragOptions::default().mu_k),
        dt: a.dt,
        time_tol: a.time_tol,
        foot_damping: a.foot_damping,
        internal_damping: a.internal_damping,
        external_damping: a.external_damping,
        rotary_inertia: a.rotary_inertia,
        mu_k_table: a
            .mu_k_table
            .as_ref()
            .map(|t| t.0.clone())
            .unwrap_or_default(),
        flight: a.flight,
        foot_table,
        whisk: a.whisk,
        grid: a.grid as usize,
        tol: a.tol,
        event_tol: a.event_tol,
        max_events: a.max_events as usize,
        refinements: a.refinements,
        ..DynDragOptions::default()
    })
}

/// The options of `dynamics free`'s flags.
pub fn free_options(a: &DynamicsFreeArgs) -> DynamicsOptions {
    DynamicsOptions {
        dt: a.dt,
        t_end: a.t_end,
        time_tol: a.time_tol,
        foot_damping: a.foot_damping,
        internal_damping: a.internal_damping,
        external_damping: a.external_damping,
        rotary_inertia: a.rotary_inertia,
        foot_moment: a.foot_moment,
        release_force: [a.release_fx, a.release_fy],
        grid: a.grid as usize,
        tol: a.tol,
        time_scheme: a.time_scheme.map(|s| match s {
            TimeSchemeArg::Newmark => TimeScheme::Newmark,
            TimeSchemeArg::EnergyMomentum => TimeScheme::EnergyMomentum,
        }),
        ..DynamicsOptions::default()
    }
}

/// The unit factors of a rod with physical dimensions, with its time unit in seconds
/// (keratin's density, as `modes`).
fn units(rod: &Rod) -> Option<(Units, f64)> {
    Some((rod.units()?, time_unit_s(rod.physical()?, KERATIN_DENSITY)))
}

/// Writes the amplitude spectrum of `m_base(t)` to `path` (columns `frequency, amplitude`,
/// and `frequency_Hz, amplitude_Nm` with physical dimensions).
fn write_spectrum(path: &Path, t: &[f64], m: &[f64], u: Option<(Units, f64)>) -> Res<()> {
    let s = amplitude_spectrum(t, m)?;
    let mut w = Sink::open(Some(path))?;
    let mut h = vec!["frequency", "amplitude"];
    if u.is_some() {
        h.extend(["frequency_Hz", "amplitude_Nm"]);
    }
    csv_line(&mut w, &h)?;
    for (f, a) in s.frequency.iter().zip(&s.amplitude) {
        let mut v = vec![num(*f), num(*a)];
        if let Some((u, ts)) = u {
            v.extend([num(f / ts), num(a * u.moment_nm)]);
        }
        csv_line(&mut w, &v)?;
    }
    w.finish()
}

/// `vibrissa dynamics drag`: CSV rows of [`HEADER`] (the event's name on the row where it
/// happened), or the library's result as JSON.
fn run_drag(a: &DynamicsDragArgs) -> Res<()> {
    let mut scene = build_scene(&a.scene, a.eta)?;
    crate::texture::apply(&a.texture, &mut scene)?;
    if a.mu_s.is_some() || a.mu_k.is_some() {
        // (the flags replace the scene's texture, as `drag`'s do)
        scene.friction = vibrissa::surface::FrictionProfile::None {};
    }
    let (rod, surface) = scene.parts()?;
    let o = options(a)?;
    o.validate()?;
    let r = drag(&rod, &surface, &o)?;
    // (the turn's column where the foot's support turns)
    let turns = o.whisk.is_some() || !o.foot_table.is_empty();
    crate::progress::stop();
    let u = units(&rod);
    if let Some(path) = &a.spectrum {
        let (t, m): (Vec<f64>, Vec<f64>) = r.samples.iter().map(|p| (p.t, p.m_base)).unzip();
        write_spectrum(path, &t, &m, u)?;
    }
    let stdout = std::io::stdout();
    let mut w = stdout.lock();
    if a.json {
        serde_json::to_writer_pretty(&mut w, &r)?;
        writeln!(w)?;
        return Ok(());
    }
    let mut header = HEADER.to_vec();
    if turns {
        header.insert(2, "theta");
    }
    if u.is_some() {
        header.extend(DRAG_PHYSICAL);
    }
    // (where a side touches, its place: in the drags that have one)
    let sides = r.samples.iter().any(|p| p.side.is_some());
    if sides {
        header.extend(SIDE_COLUMNS);
    }
    let pairs = r.samples.iter().any(|p| p.tip_also.is_some());
    if pairs {
        header.extend(TIP_ALSO_COLUMNS);
    }
    header.push("event");
    writeln!(w, "{}", header.join(","))?;
    let mut events = r.events.iter().peekable();
    for p in &r.samples {
        let mut names = vec![];
        while let Some(e) = events.next_if(|e| e.t == p.t) {
            names.push(e.kind.name());
        }
        let mut v: Vec<String> = [p.t, p.d, p.tip_x, p.tip_y, p.tip_vx, p.tip_vy]
            .map(num)
            .into();
        if turns {
            v.insert(2, num(p.theta));
        }
        v.push(p.state.name().to_string());
        v.extend(
            [
                p.normal,
                p.tangential,
                p.fx,
                p.fy,
                p.m_base,
                p.kinetic,
                p.elastic,
                p.foot_work,
                p.friction,
                p.damper,
            ]
            .map(num),
        );
        if let Some((u, ts)) = u {
            let l = u.length_mm;
            v.push(num(p.t * ts));
            v.extend([p.d, p.tip_x, p.tip_y].map(|x| num(x * l)));
            v.extend([p.normal, p.tangential, p.fx, p.fy].map(|f| num(f * u.force_n)));
            v.push(num(p.m_base * u.moment_nm));
        }
        if sides {
            match p.side {
                Some(c) => v.extend([c.s, c.x, c.y].map(num)),
                None => v.extend([String::new(), String::new(), String::new()]),
            }
        }
        if pairs {
            match p.tip_also {
                Some(c) => {
                    v.push(c.state.name().to_string());
                    v.extend([c.normal, c.tangential].map(num));
                }
                None => v.extend([String::new(), String::new(), String::new()]),
            }
        }
        v.push(names.join(" "));
        writeln!(w, "{}", v.join(","))?;
    }
    use vibrissa::dynamics::DynDragStop;
    if !matches!(r.stop, DynDragStop::DMax | DynDragStop::TableEnd) {
        crate::progress::warn(&format!("the dynamic drag stopped early: {}", r.stop));
    }
    crate::progress::eprint(&format!("dynamics drag: {r}"));
    Ok(())
}

/// `vibrissa dynamics free`: CSV rows of [`FREE_HEADER`], or the library's result as JSON.
fn run_free(a: &DynamicsFreeArgs) -> Res<()> {
    let scene = build_scene(&a.scene, None)?;
    let rod = scene.rod()?;
    let o = free_options(a);
    o.validate()?;
    if o.foot_moment != 0.0 && rod.support_compliance() == 0.0 {
        crate::progress::warn(
            "--foot-moment turns the foot only through its spring: with --support-compliance 0 (a clamp) it has no effect",
        );
    }
    let r = free(&rod, &|_| [0.0, 0.0], &o)?;
    crate::progress::stop();
    let u = units(&rod);
    if let Some(path) = &a.spectrum {
        let (t, m): (Vec<f64>, Vec<f64>) = r.samples.iter().map(|p| (p.t, p.m_base)).unzip();
        write_spectrum(path, &t, &m, u)?;
    }
    let mut w = Sink::open(None)?;
    if a.json {
        serde_json::to_writer_pretty(&mut w, &r)?;
        writeln!(w)?;
        return w.finish();
    }
    let mut header = FREE_HEADER.to_vec();
    if u.is_some() {
        header.extend(FREE_PHYSICAL);
    }
    csv_line(&mut w, &header)?;
    for p in &r.samples {
        let mut v: Vec<String> = [
            p.t,
            p.tip_x,
            p.tip_y,
            p.tip_vx,
            p.tip_vy,
            p.theta,
            p.gx_base,
            p.gy_base,
            p.m_base,
            p.kinetic,
            p.elastic,
            p.dissipated,
        ]
        .map(num)
        .into();
        if let Some((u, ts)) = u {
            let l = u.length_mm;
            v.push(num(p.t * ts));
            v.extend([p.tip_x * l, p.tip_y * l].map(num));
            v.extend([p.gx_base, p.gy_base].map(|f| num(f * u.force_n)));
            v.push(num(p.m_base * u.moment_nm));
        }
        csv_line(&mut w, &v)?;
    }
    w.finish()?;
    let rejected = if o.time_tol.is_some() {
        format!("; {} steps rejected", r.stats.rejected_steps)
    } else {
        String::new()
    };
    crate::progress::eprint(&format!(
        "dynamics free: {} steps to t = {}, {} Newton iterations, largest mesh {}{rejected}",
        r.stats.steps,
        r.samples.last().map_or(0.0, |p| p.t),
        r.stats.newton_iterations,
        r.stats.max_nodes
    ));
    Ok(())
}
