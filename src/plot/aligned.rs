//! `vibrissa plot DRAG.csv --shapes SHAPES.csv --aligned` (issue 31): one picture of a drag over
//! its surface. Above, in the lab frame, the surface, the rod just before (solid) and just after
//! (dashed) every slip, the feet and the tip's contacts (where it slipped from, where it
//! stopped); below, the moment at the foot `m_base(d)` with the slips marked. The foot stands at
//! `x = d`, so both panels share their x axis: the lower one takes the upper one's range and the
//! same horizontal extent (`Fig::stack`), and a slip's foot stands above its corner of the
//! sawtooth.

use super::{events, label, shape_rows, short, signal_panel, Table};
use crate::chart::{
    panel, series, unlabeled, Fig, Kind, Panel, Series, BLUE_, GREY_, ORANGE_, RED_,
};
use crate::error::{usage, Res};
use plotters::style::RGBColor;
use vibrissa::surface::Height;

/// Width of the picture (output pixels).
const WIDTH: u32 = 900;
/// Height of the lower panel (output pixels).
const LOWER: u32 = 300;
/// The upper panel's height: at most this, at least [`UPPER_MIN`] (output pixels).
const UPPER_MAX: u32 = 1000;
/// See [`UPPER_MAX`].
const UPPER_MIN: u32 = 260;
/// Samples of the surface across the upper panel.
const SURFACE_SAMPLES: usize = 800;
/// How far the tips may lie off a given surface (rod lengths) before it is called another one.
pub(crate) const TIPS_ON_SURFACE: f64 = 1e-6;

const SURFACE_COLOR: RGBColor = RGBColor(60, 60, 60);
const STOP_COLOR: RGBColor = RGBColor(44, 160, 44);

/// The picture (module docs). `shape` is the surface's shape without its height (the
/// `--corrugation` or other texture flags with η = 0), if given: its height is read off the
/// tips, which must lie on it to [`TIPS_ON_SURFACE`]; without it the surface is the line through
/// the tips inclined by `beta`, or the path through them when they are not on one line.
pub(super) fn drag_over_surface(
    t: &Table,
    sh: &Table,
    select: Option<&[usize]>,
    shape: Option<&Height>,
    beta: f64,
) -> Res<Fig> {
    let mut upper = rods_at_slips(t, sh, select)?;
    let (xr, yr) = extent(&upper);
    let pad = 0.08 * (xr.1 - xr.0).max(0.05);
    let (x0, x1) = (xr.0 - pad, xr.1 + pad);
    upper.series.insert(0, surface(t, shape, beta, (x0, x1))?);
    let (lo, hi) = extent(&upper).1;
    // the upper panel as tall as the rods at equal scales need, within bounds
    let plot_w = f64::from(WIDTH) - 90.0;
    let plot_h = plot_w * (hi - lo).max(yr.1 - yr.0) / (x1 - x0) * 1.12;
    let h_upper = (plot_h as u32 + 130).clamp(UPPER_MIN, UPPER_MAX);
    let d = t.need("d")?;
    let m = t.need("m_base")?;
    let mut lower: Panel = signal_panel(
        "moment at the foot (the foot at x = d)",
        ("d", &label("m_base")),
        &d,
        &[("m_base", &m, BLUE_)],
        &events(t),
    );
    lower.xlabel = "d = the foot's x (L)".into();
    Ok(Fig {
        name: String::new(),
        caption: format!("drag {} over its surface, with {}", t.name, sh.name),
        panels: vec![upper, lower],
        w: WIDTH,
        h: h_upper + LOWER,
        stack: Some(vec![h_upper, LOWER]),
    })
}

/// The finite extent `((x0, x1), (y0, y1))` of a panel's series.
fn extent(p: &Panel) -> ((f64, f64), (f64, f64)) {
    let mut e = (
        (f64::INFINITY, f64::NEG_INFINITY),
        (f64::INFINITY, f64::NEG_INFINITY),
    );
    for &(x, y) in p.series.iter().flat_map(|s| &s.pts) {
        if x.is_finite() && y.is_finite() {
            e.0 = (e.0 .0.min(x), e.0 .1.max(x));
            e.1 = (e.1 .0.min(y), e.1 .1.max(y));
        }
    }
    e
}

/// The upper panel without its surface: the rod just before and after each slip (all of them,
/// or the `--select`ed points), the feet at the slips, and the tip where each slip starts and
/// where it stops (the drag's `slip` and `slip_end` rows).
fn rods_at_slips(t: &Table, sh: &Table, select: Option<&[usize]>) -> Res<Panel> {
    let by_point = shape_rows(sh)?;
    let ev = sh.text("event").ok_or_else(|| {
        usage(format!(
            "{}: no column 'event': not the --shapes file of a drag",
            sh.name
        ))
    })?;
    let event = |pt: usize| ev[by_point[&pt][0]];
    let chosen: Vec<usize> = match select {
        Some(sel) => super::chosen_points(sh, &by_point, Some(sel), Vec::new)?,
        None => by_point
            .keys()
            .copied()
            .filter(|&pt| matches!(event(pt), "slip" | "slip_end"))
            .collect(),
    };
    if chosen.is_empty() {
        return Err(usage(format!(
            "{}: no slip to draw (the drag did not slip; --select chooses points)",
            sh.name
        )));
    }
    let (d, x, y) = (sh.need("d")?, sh.need("x_lab")?, sh.need("y")?);
    let mut p = panel(
        "the rod at the slips over the surface (lab frame; before: solid, after: dashed)",
        "x (L)",
        "y (L)",
    );
    p.equal_aspect = true;
    let (mut before, mut after, mut feet) = (0, 0, Vec::new());
    for &pt in &chosen {
        let rows = &by_point[&pt];
        let pts: Vec<(f64, f64)> = rows.iter().map(|&r| (x[r], y[r])).collect();
        let end = event(pt) == "slip_end";
        let n = if end { &mut after } else { &mut before };
        *n += 1;
        let s = if end {
            series("rod just after a slip", Kind::Dashed, ORANGE_, pts)
        } else {
            series("rod just before a slip", Kind::Line, BLUE_, pts)
        };
        p.series.push(if *n == 1 { s } else { unlabeled(s) });
        if !end {
            feet.push((d[rows[0]], 0.0));
        }
    }
    if !feet.is_empty() {
        p.series
            .push(series("foot at a slip (x = d)", Kind::Square, GREY_, feet));
    }
    let (tx, ty) = (t.need("x_tip")?, t.need("y_tip")?);
    for (name, what, kind, color) in [
        ("slip", "tip where it slips", Kind::Cross, RED_),
        ("slip_end", "tip where it stops", Kind::Ring, STOP_COLOR),
    ] {
        let tips: Vec<(f64, f64)> = events(t)
            .into_iter()
            .filter(|(e, _)| e == name)
            .flat_map(|(_, rows)| rows)
            .map(|r| (tx[r], ty[r]))
            .collect();
        if !tips.is_empty() {
            let label = format!("{what} ({})", tips.len());
            p.series.push(series(&label, kind, color, tips));
        }
    }
    Ok(p)
}

/// The surface across `(x0, x1)`: the given shape at the height its tips read off, else the line
/// through the tips (inclined by `beta`), or the path through them when they are not on one
/// line.
fn surface(t: &Table, shape: Option<&Height>, beta: f64, (x0, x1): (f64, f64)) -> Res<Series> {
    let (tx, ty) = (t.need("x_tip")?, t.need("y_tip")?);
    let tips: Vec<(f64, f64)> = tx
        .iter()
        .zip(&ty)
        .map(|(&x, &y)| (x, y))
        .filter(|p| p.0.is_finite() && p.1.is_finite())
        .collect();
    let Some(&(xa, ya)) = tips.first() else {
        return Err(usage(format!("{}: no tip position to draw", t.name)));
    };
    let xs = (0..SURFACE_SAMPLES).map(|i| x0 + (x1 - x0) * i as f64 / (SURFACE_SAMPLES - 1) as f64);
    if let Some(h) = shape {
        // its height: where the tips say (the median of their offsets), and all of them on it
        let mut off: Vec<f64> = tips.iter().map(|&(x, y)| y - h.h(x)).collect();
        off.sort_by(f64::total_cmp);
        let eta = off[off.len() / 2];
        let worst = off.iter().map(|o| (o - eta).abs()).fold(0.0f64, f64::max);
        if worst > TIPS_ON_SURFACE {
            return Err(usage(format!(
                "{}: the tips lie up to {} rod lengths off the surface the texture flags give \
                 (more than {}): give the drag's own --corrugation, --grating or \
                 --surface-profile flags (and --surface-angle)",
                t.name,
                short(worst),
                short(TIPS_ON_SURFACE)
            )));
        }
        let pts = xs.map(|x| (x, eta + h.h(x))).collect();
        return Ok(series(
            &format!("surface (η = {} from the tips)", short(eta)),
            Kind::Thin,
            SURFACE_COLOR,
            pts,
        ));
    }
    if let Some(path) = super::curved_surface(t)? {
        return Ok(series(
            "surface (where the tip touched: x_tip, y_tip)",
            Kind::Dashed,
            SURFACE_COLOR,
            path,
        ));
    }
    let pts = [x0, x1]
        .iter()
        .map(|&x| (x, ya + (x - xa) * beta.tan()))
        .collect();
    Ok(series(
        &format!("surface (β = {} rad)", short(beta)),
        Kind::Thin,
        SURFACE_COLOR,
        pts,
    ))
}
