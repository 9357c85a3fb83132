//! `vibrissa modes`: natural frequencies (and shapes) of a static state.

use crate::cli::{ModesArgs, ModesTip};
use crate::error::Res;
use crate::present::{Cell, Row};
use crate::scene_args::build_scene;
use std::io::Write;
use vibrissa::modes::{modes, BaseLoad, ModeOptions, TipCondition};

/// Run `vibrissa modes`: CSV rows `n, omega2, omega, stable` (and `f_Hz` for a scene with
/// physical dimensions, keratin's density 1250 kg/m³), or the library's result as JSON.
pub fn run(a: &ModesArgs) -> Res<()> {
    let scene = build_scene(&a.scene, None)?;
    let rod = scene.rod()?;
    let tip = match a.tip {
        ModesTip::Free => TipCondition::Free,
        ModesTip::Pinned => TipCondition::Pinned,
        ModesTip::Sliding => TipCondition::Sliding { angle: a.tip_angle },
    };
    let load = BaseLoad {
        m_base: a.m_base,
        fx: a.fx,
        fy: a.fy,
    };
    let opts = ModeOptions {
        count: a.count as usize,
        rotary_inertia: a.rotary_inertia,
        shape_points: a.points as usize,
        ..ModeOptions::default()
    };
    let r = modes(&rod, &load, tip, &opts)?;
    crate::progress::stop();
    let stdout = std::io::stdout();
    let mut w = stdout.lock();
    if a.json {
        serde_json::to_writer_pretty(&mut w, &r)?;
        writeln!(w)?;
        return Ok(());
    }
    // scenes with dimensions: the frequency in Hz (keratin's density)
    let unit_s = rod
        .physical()
        .map(|p| vibrissa::inertia::time_unit_s(p, vibrissa::inertia::KERATIN_DENSITY));
    for (i, m) in r.modes.iter().enumerate() {
        let mut row = Row(vec![
            ("n", Cell::Count(i + 1)),
            ("omega2", Cell::Num(m.omega2)),
            ("omega", Cell::Num(m.omega)),
            ("stable", Cell::Flag(m.omega2 > 0.0)),
        ]);
        if let Some(t) = unit_s {
            row.0.push((
                "f_Hz",
                Cell::Num(m.omega / (2.0 * std::f64::consts::PI * t)),
            ));
        }
        if i == 0 {
            row.write_csv(&mut w)?;
        } else {
            row.write_values(&mut w)?;
        }
    }
    Ok(())
}
