//! `vibrissa dynamics drag`: the foot dragged at a speed with the tip on the surface, in time
//! (`vibrissa::dynamics::drag`, issue 32).

use crate::cli::{DynamicsArgs, DynamicsCommand, DynamicsDragArgs};
use crate::error::Res;
use crate::scene_args::build_scene;
use crate::table::num;
use std::io::Write;
use vibrissa::dynamics::{drag, DynDragOptions};

/// Columns of the CSV: one row per time step (the start included).
pub const HEADER: [&str; 18] = [
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
    "event",
];

/// Run `vibrissa dynamics ...`.
pub fn run(a: &DynamicsArgs) -> Res<()> {
    match &a.command {
        DynamicsCommand::Drag(d) => run_drag(d),
    }
}

/// The options of the flags.
pub fn options(a: &DynamicsDragArgs) -> DynDragOptions {
    DynDragOptions {
        speed: a.speed,
        ramp: a.ramp,
        d_max: a.d_max,
        mu_s: a.mu_s,
        mu_k: a.mu_k,
        dt: a.dt,
        foot_damping: a.foot_damping,
        ..DynDragOptions::default()
    }
}

/// `vibrissa dynamics drag`: CSV rows of [`HEADER`] (the event's name on the row where it
/// happened), or the library's result as JSON.
fn run_drag(a: &DynamicsDragArgs) -> Res<()> {
    let scene = build_scene(&a.scene, a.eta)?;
    let (rod, surface) = scene.parts()?;
    let o = options(a);
    o.validate()?;
    let r = drag(&rod, &surface, &o)?;
    crate::progress::stop();
    let stdout = std::io::stdout();
    let mut w = stdout.lock();
    if a.json {
        serde_json::to_writer_pretty(&mut w, &r)?;
        writeln!(w)?;
        return Ok(());
    }
    writeln!(w, "{}", HEADER.join(","))?;
    let mut events = r.events.iter().peekable();
    for p in &r.samples {
        let mut names = vec![];
        while let Some(e) = events.next_if(|e| e.t == p.t) {
            names.push(e.kind.name());
        }
        let mut v: Vec<String> = [p.t, p.d, p.tip_x, p.tip_y, p.tip_vx, p.tip_vy]
            .map(num)
            .into();
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
        v.push(names.join(" "));
        writeln!(w, "{}", v.join(","))?;
    }
    if r.stop != vibrissa::dynamics::DynDragStop::DMax {
        crate::progress::warn(&format!("the dynamic drag stopped early: {}", r.stop));
    }
    crate::progress::eprint(&format!("dynamics drag: {r}"));
    Ok(())
}
