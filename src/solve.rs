//! `vibrissa solve`: one rod, one load.

use crate::cli::{BranchArg, SolveArgs};
use crate::error::{usage, Res};
use crate::numeric;
use crate::output::{csv_line, num, opt, AtomicFile};
use crate::scene_args::{build_scene, Units};
use serde::Serialize;
use std::io::Write;

/// One point of a rod shape.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct ShapeRow {
    /// arc length
    pub s: f64,
    /// position
    pub x: f64,
    /// position
    pub y: f64,
    /// slope angle
    pub phi: f64,
    /// curvature phi'
    pub kappa: f64,
    /// internal moment
    pub m: f64,
}

/// Result of one solve.
#[derive(Clone, Debug, Serialize)]
pub struct SolveOut {
    /// method used
    pub method: &'static str,
    /// requested branch
    pub branch: &'static str,
    /// force angle
    pub alpha: f64,
    /// tip slope
    pub phi1: f64,
    /// force magnitude
    pub f: f64,
    /// f sin(alpha)
    pub fx: f64,
    /// -f cos(alpha)
    pub fy: f64,
    /// tip x
    pub x1: f64,
    /// tip y
    pub y1: f64,
    /// m(0)
    pub m_base: f64,
    /// number of flex points (sign changes of the curvature)
    pub flex: usize,
    /// sign changes of the bending moment m(s): the branch (0 convex, 1 flex)
    pub load_reversals: usize,
    /// arc length of the (first) flex point
    pub s_flex: Option<f64>,
    /// max over s of y(s)
    pub y_max: f64,
    /// residual of the solve (see README)
    pub residual: f64,
    /// the rod crosses the surface line through its tip (see `clearance`)
    pub penetration: bool,
    /// how the rod lies against that line: largest height above it over s < 1 and where, and
    /// sin(phi1 - beta)
    pub clearance: vibrissa::Clearance,
    /// physical-unit values, when the scene has dimensions
    #[serde(skip_serializing_if = "Option::is_none")]
    pub physical: Option<PhysicalOut>,
    /// shape (not serialized into the row)
    #[serde(skip)]
    pub shape: Vec<ShapeRow>,
}

/// Physical-unit columns.
#[derive(Clone, Debug, Serialize)]
pub struct PhysicalOut {
    /// force in N
    pub f_n: f64,
    /// x force in N
    pub fx_n: f64,
    /// y force in N
    pub fy_n: f64,
    /// m(0) in N*m
    pub m_base_nm: f64,
    /// tip x in mm
    pub x1_mm: f64,
    /// tip y in mm
    pub y1_mm: f64,
}

/// CLI name of a branch.
pub fn branch_name(b: BranchArg) -> &'static str {
    match b {
        BranchArg::Convex => "convex",
        BranchArg::Flex => "flex",
        BranchArg::Any => "any",
    }
}

/// Fill the physical-unit columns.
pub fn add_units(o: &mut SolveOut, u: Option<Units>) {
    o.physical = u.map(|u| PhysicalOut {
        f_n: o.f * u.force_n,
        fx_n: o.fx * u.force_n,
        fy_n: o.fy * u.force_n,
        m_base_nm: o.m_base * u.moment_nm,
        x1_mm: o.x1 * u.length_mm,
        y1_mm: o.y1 * u.length_mm,
    });
}

/// Header of the solve CSV.
pub fn header(physical: bool) -> Vec<&'static str> {
    let mut h = vec![
        "method",
        "branch",
        "alpha",
        "phi1",
        "f",
        "fx",
        "fy",
        "x1",
        "y1",
        "m_base",
        "flex",
        "load_reversals",
        "s_flex",
        "y_max",
        "residual",
        "penetration",
    ];
    if physical {
        h.extend(["f_N", "fx_N", "fy_N", "m_base_Nm", "x1_mm", "y1_mm"]);
    }
    h
}

/// Fields of the solve CSV row.
pub fn row(o: &SolveOut) -> Vec<String> {
    let mut r = vec![
        o.method.to_string(),
        o.branch.to_string(),
        num(o.alpha),
        num(o.phi1),
        num(o.f),
        num(o.fx),
        num(o.fy),
        num(o.x1),
        num(o.y1),
        num(o.m_base),
        o.flex.to_string(),
        o.load_reversals.to_string(),
        opt(o.s_flex),
        num(o.y_max),
        num(o.residual),
        u8::from(o.penetration).to_string(),
    ];
    if let Some(p) = &o.physical {
        r.extend(
            [p.f_n, p.fx_n, p.fy_n, p.m_base_nm, p.x1_mm, p.y1_mm]
                .into_iter()
                .map(num),
        );
    }
    r
}

/// Write a shape CSV atomically.
pub fn write_shape(path: &std::path::Path, shape: &[ShapeRow]) -> Res<()> {
    let mut f = AtomicFile::create(path)?;
    csv_line(&mut f, &["s", "x", "y", "phi", "kappa", "m"])?;
    for p in shape {
        csv_line(&mut f, &[p.s, p.x, p.y, p.phi, p.kappa, p.m].map(num))?;
    }
    f.commit()
}

/// Run `vibrissa solve`.
pub fn run(a: &SolveArgs) -> Res<()> {
    if a.peg.is_some() {
        return crate::peg::run_solve(a);
    }
    let scene = build_scene(&a.scene, None)?;
    let npts = if a.shape_out.is_some() {
        a.shape_points as usize
    } else {
        0
    };
    let mut out = numeric::solve(&scene, a, npts)?;
    crate::progress::stop();
    if out.residual.is_nan() || !out.f.is_finite() {
        return Err(crate::error::solve_fail(
            "the solver returned a non-finite result",
        ));
    }
    if out.penetration {
        let c = &out.clearance;
        let what = if c.height > 0.0 {
            format!(
                "the rod rises {:.3e} above the surface line through its tip at s = {:.6}",
                c.height, c.s
            )
        } else {
            format!(
                "the tip arrives from above the surface line (sin(phi1 - surface angle) = {:.3e})",
                c.tip_approach
            )
        };
        if a.require_contact {
            return Err(usage(format!(
                "no contact at the tip only: {what} (--require-contact)"
            )));
        }
        eprintln!("warning: penetration: {what}");
    }
    add_units(&mut out, scene.rod()?.units());
    if let Some(p) = &a.shape_out {
        write_shape(p, &out.shape)?;
    }
    let stdout = std::io::stdout();
    let mut w = stdout.lock();
    if a.json {
        serde_json::to_writer_pretty(&mut w, &out)?;
        writeln!(w)?;
    } else {
        csv_line(&mut w, &header(out.physical.is_some()))?;
        csv_line(&mut w, &row(&out))?;
    }
    Ok(())
}
