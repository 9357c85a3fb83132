//! The dynamic drag of the bench group `dynamic_drag` (issue 32), error against time: the
//! paper's rod (uniform, clamped, η = 0.75, μs = 0.5, μk = 0.3) dragged by
//! `vibrissa::dynamics::drag` at v = 0.05 (ramp 2) from the pressed start.
//!
//! By default: the drag to its first slip at a sequence of (dt, grid, tol), each with its steps,
//! the CPU time of the thread and the slip's place `d` against `D_SLIP` (the same drag with
//! dt → 0, `-- --reference` recomputes it). `-- --ten`: the bench's 10 slips (20 events) at
//! dt 0.02, 0.01 (grid 100, tol 1e-8; grid 200, tol 1e-10) and 0.005 (grid 200, tol 1e-10),
//! with the places of every slip and stick (slips 2 to 5 converge as dt → 0 since the slip test
//! on the held force, docs/model.md; docs/performance.md compares the first slip, the one the
//! peer's drag also converges in). `-- --settings dt,grid,tol,dt,grid,tol,...` picks the settings of either;
//! `-- --d-max D` runs each drag over the foot's travel `0..D` instead (with `--ten`: the span of
//! `benches/pyelastica_drag.py --d-max D`, the comparison at equal accuracy in the first
//! frequency, docs/performance.md).
//! `-- --internal-damping G` gives the rod Kelvin–Voigt damping `γ_i = G`, `-- --external-damping G`
//! external viscous damping `γ_e = G` (default 0 both).
//!
//! The peer's side of the same drag: `benches/pyelastica_drag.py`.
//!
//! Run: `cargo run --release -p vibrissa --example drag_slips` (seconds; `--ten` about 4
//! minutes, `--reference` about 2 minutes on one core).

use vibrissa::dynamics::{drag, DragEventKind, DynDragOptions};
use vibrissa::{Rod, Surface, VibrissaError};

#[path = "../benches/support/clock.rs"]
mod clock;

/// The value after `name` on the command line, else 0.
fn flag(name: &str) -> f64 {
    std::env::args()
        .skip_while(|a| a != name)
        .nth(1)
        .and_then(|v| v.parse().ok())
        .unwrap_or(0.0)
}

/// `--d-max D`: the drag over the foot's travel `0..D` whatever its events (the span of the
/// peer's run with the same flag), instead of to its `events`-th event; 0 when not given.
fn span() -> f64 {
    flag("--d-max")
}

/// The slip and stick places `d` of the drag at `(dt, grid, tol)` through `events` events,
/// its CPU time in s and its work.
type Run = (Vec<f64>, Vec<f64>, f64, String);
fn slips(dt: f64, grid: usize, tol: f64, events: usize) -> Result<Run, VibrissaError> {
    let o = DynDragOptions {
        speed: 0.05,
        dt,
        tol,
        grid,
        d_max: if span() > 0.0 { span() } else { 10.0 },
        max_events: if span() > 0.0 { 10_000 } else { events },
        internal_damping: flag("--internal-damping"),
        external_damping: flag("--external-damping"),
        ..DynDragOptions::default()
    };
    let surface = Surface::flat(0.75)?;
    let (r, spent) = clock::timed(|| drag(&Rod::uniform(), &surface, &o));
    let r = r?;
    if std::env::args().any(|a| a == "--events") {
        for e in &r.events {
            println!(
                "  {:<6} t {:.10} d {:.10} tip_x {:.8} vx {:.3e} N {:.6} T/N {:.6}",
                e.kind.name(),
                e.t,
                e.d,
                e.tip_x,
                e.tip_vx,
                e.normal,
                e.tangential / e.normal
            );
        }
    }
    let of = |kind| {
        r.events
            .iter()
            .filter(|e| e.kind == kind)
            .map(|e| e.d)
            .collect()
    };
    Ok((
        of(DragEventKind::Slip),
        of(DragEventKind::Stick),
        spent.as_secs_f64(),
        format!("{}; last step's mesh {}", r.stats, r.stats.mesh_nodes),
    ))
}

/// The first slip's place by `drag` at dt 0.0025 and 0.00125 (grid 200, tol 1e-12),
/// Richardson's extrapolation (second order in dt: the differences of dt 0.01, 0.005, 0.0025,
/// 0.00125 fall 3.73 and 4.00 times); the pair 0.005 + 0.0025 gives the same to 1e-10
/// (`-- --reference` recomputes both).
const D_SLIP: f64 = 0.021_003_157_884;

/// The first slip at each setting (the drag to its first event), its error against
/// [`D_SLIP`] and the CPU time.
fn first_slip(settings: &[(f64, usize, f64)]) -> Result<(), VibrissaError> {
    println!("the first slip, against d = {D_SLIP} (vibrissa, dt -> 0)");
    println!(
        "{:>8} {:>5} {:>7} {:>7} {:>10} {:>16} {:>10}",
        "dt", "grid", "tol", "steps", "cpu_s", "slip_d", "error"
    );
    for &(dt, grid, tol) in settings {
        let (s, _, cpu, stats) = slips(dt, grid, tol, 1)?;
        let steps = stats.split(' ').next().unwrap_or("");
        println!(
            "{dt:>8} {grid:>5} {tol:>7.0e} {steps:>7} {cpu:>10.3} {:>16.13} {:>10.3e}",
            s[0],
            (s[0] - D_SLIP).abs()
        );
    }
    Ok(())
}

/// [`D_SLIP`] recomputed: the first slip at dt 0.01 … 0.00125 (grid 200, tol 1e-12) and the
/// Richardson extrapolations of successive pairs.
fn reference() -> Result<(), VibrissaError> {
    let dts = [0.01, 0.005, 0.0025, 0.00125];
    let mut d = vec![];
    for dt in dts {
        let (s, _, cpu, _) = slips(dt, 200, 1e-12, 1)?;
        println!("dt {dt}: first slip d {:.13} (cpu {cpu:.1} s)", s[0]);
        d.push(s[0]);
    }
    for i in 0..3 {
        println!(
            "Richardson dt {} + {}: {:.13}",
            dts[i],
            dts[i + 1],
            d[i + 1] + (d[i + 1] - d[i]) / 3.0
        );
    }
    Ok(())
}

/// The ten slips at each setting (the bench's drag): the places of the slips.
fn ten_slips(settings: &[(f64, usize, f64)]) -> Result<(), VibrissaError> {
    if span() > 0.0 {
        println!("the drag to d = {}", span());
    } else {
        println!("the first 10 slips (20 events)");
    }
    for &(dt, grid, tol) in settings {
        let (s, k, cpu, stats) = slips(dt, grid, tol, 20)?;
        let list = |v: &[f64]| {
            v.iter()
                .map(|x| format!("{x:.6}"))
                .collect::<Vec<_>>()
                .join(" ")
        };
        println!(
            "dt {dt} grid {grid} tol {tol:e}: cpu {cpu:.2} s; {stats}\n  slips  {}\n  sticks {}",
            list(&s),
            list(&k)
        );
    }
    Ok(())
}

fn main() -> Result<(), VibrissaError> {
    let args: Vec<String> = std::env::args().collect();
    let picked: Vec<f64> = args
        .iter()
        .skip_while(|a| *a != "--settings")
        .nth(1)
        .map(|v| v.split(',').filter_map(|x| x.parse().ok()).collect())
        .unwrap_or_default();
    let chosen: Vec<(f64, usize, f64)> = picked
        .chunks(3)
        .map(|c| (c[0], c[1] as usize, c[2]))
        .collect();
    println!(
        "paper's rod, eta 0.75, mu_s 0.5, mu_k 0.3, v 0.05, ramp 2 ({})",
        clock::name()
    );
    if args.iter().any(|a| a == "--reference") {
        return reference();
    }
    if args.iter().any(|a| a == "--ten") {
        let bench = [
            (0.02, 100, 1e-8),
            (0.01, 100, 1e-8),
            (0.01, 200, 1e-10),
            (0.005, 200, 1e-10),
        ];
        return ten_slips(if chosen.is_empty() { &bench } else { &chosen });
    }
    let curve = [
        (0.5, 20, 1e-6),
        (0.25, 20, 1e-6),
        (0.2, 20, 1e-6),
        (0.1, 20, 1e-6),
        (0.05, 20, 1e-6),
        (0.02, 50, 1e-8),
        (0.01, 100, 1e-8),
        (0.005, 200, 1e-10),
        (0.0025, 200, 1e-12),
    ];
    first_slip(if chosen.is_empty() { &curve } else { &chosen })
}
