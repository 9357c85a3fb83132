//! `vibrissa solve`: one rod, one load.

use crate::cli::SolveArgs;
use crate::error::{solve_fail, usage, Res};
use crate::present::{Cell, Object, Row};
use crate::scene_args::build_scene;
use serde::ser::{SerializeMap, Serializer};
use serde::Serialize;
use std::io::Write;
use vibrissa::{Clearance, Shape, Target, Units};

/// A solve as the program presents it: the library's [`Shape`] with what was asked (method,
/// branch) and how the rod lies against the surface line through its tip.
struct Solved<'a> {
    args: &'a SolveArgs,
    shape: Shape,
    clearance: Clearance,
    units: Option<Units>,
}

impl Solved<'_> {
    /// The columns of the row, in order (the CSV's, and the JSON object's keys).
    fn columns(&self) -> Row {
        let sh = &self.shape;
        Row(vec![
            ("method", Cell::Name(self.args.solver.method.name())),
            ("branch", Cell::Name(self.args.branch.name())),
            ("alpha", Cell::Num(sh.alpha)),
            ("phi1", Cell::Num(sh.phi1)),
            ("f", Cell::Num(sh.f)),
            ("fx", Cell::Num(sh.fx)),
            ("fy", Cell::Num(sh.fy)),
            ("x1", Cell::Num(sh.x1)),
            ("y1", Cell::Num(sh.y1)),
            ("m_base", Cell::Num(sh.m_base)),
            ("flex", Cell::Count(sh.flex)),
            ("load_reversals", Cell::Count(sh.load_reversals)),
            ("s_flex", Cell::Opt(sh.s_flex)),
            ("y_max", Cell::Num(sh.y_max)),
            ("residual", Cell::Num(sh.residual)),
            ("penetration", Cell::Flag(self.clearance.penetrates())),
        ])
    }

    /// The physical-unit columns (scenes with dimensions): the CSV's names; the JSON's are the
    /// same in lower case.
    fn physical(&self) -> Option<[(&'static str, f64); 6]> {
        let (u, sh) = (self.units?, &self.shape);
        Some([
            ("f_N", sh.f * u.force_n),
            ("fx_N", sh.fx * u.force_n),
            ("fy_N", sh.fy * u.force_n),
            ("m_base_Nm", sh.m_base * u.moment_nm),
            ("x1_mm", sh.x1 * u.length_mm),
            ("y1_mm", sh.y1 * u.length_mm),
        ])
    }

    fn write_csv<W: Write>(&self, w: &mut W) -> Res<()> {
        let mut row = self.columns();
        for (name, v) in self.physical().iter().flatten() {
            row.0.push((name, Cell::Num(*v)));
        }
        row.write_csv(w)
    }
}

impl Serialize for Solved<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut m = s.serialize_map(None)?;
        for (k, v) in &self.columns().0 {
            m.serialize_entry(k, v)?;
        }
        m.serialize_entry("clearance", &self.clearance)?;
        if let Some(p) = self.physical() {
            let lower: Vec<(String, f64)> = p.iter().map(|(k, v)| (k.to_lowercase(), *v)).collect();
            m.serialize_entry("physical", &Object(&lower))?;
        }
        m.end()
    }
}

/// The penetration of a solved rod in words.
fn penetration(c: &Clearance) -> String {
    if c.height > 0.0 {
        format!(
            "the rod rises {:.3e} above the surface line through its tip at s = {:.6}",
            c.height, c.s
        )
    } else {
        format!(
            "the tip arrives from above the surface line (sin(phi1 - surface angle) = {:.3e})",
            c.tip_approach
        )
    }
}

/// Run `vibrissa solve` with a tip condition (`--peg`: `peg::run_solve`).
pub fn run(a: &SolveArgs) -> Res<()> {
    let scene = build_scene(&a.scene, None)?;
    let rod = scene.rod()?;
    let target = match (a.phi1, a.eta) {
        (Some(p), _) => Target::Phi1(p),
        (None, Some(h)) => Target::Eta(h),
        (None, None) => return Err(usage("give --phi1 or --eta")),
    };
    let cfg = a.solver.config(scene.start);
    let shape = vibrissa::solve(&rod, a.alpha.unwrap_or(0.0), target, &a.branch, &cfg)?;
    let clearance = shape.clearance(scene.surface_angle);
    crate::progress::stop();
    if shape.residual.is_nan() || !shape.f.is_finite() {
        return Err(solve_fail("the solver returned a non-finite result"));
    }
    if clearance.penetrates() {
        let what = penetration(&clearance);
        if a.require_contact {
            return Err(usage(format!(
                "no contact at the tip only: {what} (--require-contact)"
            )));
        }
        eprintln!("warning: penetration: {what}");
    }
    if let Some(p) = &a.shape_out {
        crate::present::write_shape(p, &shape.samples(a.shape_points as usize))?;
    }
    let out = Solved {
        args: a,
        units: rod.units(),
        shape,
        clearance,
    };
    let stdout = std::io::stdout();
    let mut w = stdout.lock();
    if a.json {
        serde_json::to_writer_pretty(&mut w, &out)?;
        writeln!(w)?;
    } else {
        out.write_csv(&mut w)?;
    }
    Ok(())
}
