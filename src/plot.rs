//! `vibrissa plot`: SVG pictures of the user's own files — a scan (μ and the base signals
//! against d), its `--shapes` (the rod at chosen points, with the surface), a sweep (a heat map
//! of one column over two axes) and a drag (the signals of the stick–slip drag, issue 21).
//!
//! Columns are read by name, so files with more columns (or in another order) plot the same;
//! every value of an `event` column is marked (one marker style and legend entry per event
//! name). Drawing, legend placement and the layout test are those of `chart`.

use crate::chart::{
    panel, render, series, unlabeled, Fig, Kind, Panel, BLUE_, BROWN_, GREEN_, GREY_, NAVY_,
    ORANGE_, PURPLE_, RED_,
};
use crate::cli::{PlotArgs, PlotKind};
use crate::error::{usage, Res};
use crate::table::{num, AtomicFile};
use plotters::style::RGBColor;
use std::collections::BTreeMap;
use std::io::Write;
use std::path::{Path, PathBuf};

mod aligned;

/// A CSV file: header and rows of text fields.
pub(crate) struct Table {
    name: String,
    header: Vec<String>,
    rows: Vec<Vec<String>>,
}

impl Table {
    /// Read a CSV file with a header.
    pub(crate) fn read(path: &Path) -> Res<Table> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| usage(format!("cannot read {}: {e}", path.display())))?;
        Table::parse(&path.display().to_string(), &text)
    }

    /// Parse CSV text (`name` is used in messages).
    pub(crate) fn parse(name: &str, text: &str) -> Res<Table> {
        let mut r = csv::ReaderBuilder::new()
            .flexible(false)
            .from_reader(text.as_bytes());
        let header: Vec<String> = r
            .headers()
            .map_err(|e| usage(format!("{name}: {e}")))?
            .iter()
            .map(str::to_string)
            .collect();
        let mut rows = Vec::new();
        for rec in r.records() {
            let rec = rec.map_err(|e| usage(format!("{name}: {e}")))?;
            rows.push(rec.iter().map(str::to_string).collect());
        }
        if rows.is_empty() {
            return Err(usage(format!("{name}: no rows to plot")));
        }
        Ok(Table {
            name: name.to_string(),
            header,
            rows,
        })
    }

    fn has(&self, col: &str) -> bool {
        self.header.iter().any(|h| h == col)
    }

    fn text(&self, col: &str) -> Option<Vec<&str>> {
        let i = self.header.iter().position(|h| h == col)?;
        Some(self.rows.iter().map(|r| r[i].as_str()).collect())
    }

    /// A numeric column: empty fields are NaN (none), `inf`/`-inf` infinite; text is an error.
    fn num(&self, col: &str) -> Res<Option<Vec<f64>>> {
        let Some(t) = self.text(col) else {
            return Ok(None);
        };
        t.iter()
            .enumerate()
            .map(|(i, v)| {
                if v.is_empty() {
                    Ok(f64::NAN)
                } else {
                    v.parse::<f64>().map_err(|_| {
                        usage(format!(
                            "{}: column {col}, row {}: '{v}' is not a number",
                            self.name,
                            i + 2
                        ))
                    })
                }
            })
            .collect::<Res<Vec<f64>>>()
            .map(Some)
    }

    fn need(&self, col: &str) -> Res<Vec<f64>> {
        self.num(col)?.ok_or_else(|| {
            usage(format!(
                "{}: no column '{col}' (columns: {})",
                self.name,
                self.header.join(", ")
            ))
        })
    }
}

/// The kind of a file from its columns.
pub(crate) fn detect(t: &Table) -> Res<PlotKind> {
    Ok(if t.has("point") && t.has("s") && t.has("x_lab") {
        PlotKind::Shapes
    } else if t.has("point") && t.has("s") && t.has("theta") {
        PlotKind::WhiskShapes
    } else if t.has("theta") && t.has("s_c") && t.has("m_base") {
        PlotKind::Whisk
    } else if t.has("index") && t.has("stop_reason") {
        PlotKind::Sweep
    } else if t.has("t") && t.has("m_base") && t.has("kinetic") {
        PlotKind::Dynamics
    } else if t.has("frequency") && t.has("amplitude") {
        PlotKind::Spectrum
    } else if (t.has("d") || t.has("theta")) && t.has("phase") {
        PlotKind::Drag
    } else if t.has("d") && t.has("mu") {
        PlotKind::Scan
    } else {
        return Err(usage(format!(
            "{}: not a file vibrissa writes (a scan has d and mu, its --shapes point, s and x_lab, a sweep index and stop_reason, a drag d (or theta) and phase, a whisk theta and s_c, its --shapes point, s and theta, a dynamics file t, m_base and kinetic, a spectrum frequency and amplitude); use --kind to say which",
            t.name
        )));
    })
}

/// The parameter column of a drag's file or its shapes file: `d`, or `theta` where the support
/// turned (`drag --turn`).
fn drag_axis(t: &Table) -> &'static str {
    if !t.has("d") && t.has("theta") {
        "theta"
    } else {
        "d"
    }
}

/// Axis label with its unit for a column of the program's files.
fn label(col: &str) -> String {
    let known = match col {
        "d" => "foot displacement d (L)",
        "theta" => "foot angle θ (rad, clockwise)",
        "mu" => "friction ratio μ (–)",
        "normal" => "normal force N (EI/L²)",
        "fx" => "fx (EI/L²)",
        "fy" => "fy (EI/L²)",
        "f" | "f0" => "force f (EI/L²)",
        "m_base" => "m_base (EI/L)",
        "alpha" => "force angle α (rad)",
        "phi1" | "phi1_0" => "tip slope φ1 (rad)",
        "x_tip" => "tip position x (L, lab frame)",
        "eta" => "surface height η (L)",
        "taper" => "taper ratio ρ (–)",
        "precurvature" => "rest curvature K0 (1/L)",
        "precurvature_slope" => "rest-curvature slope K1 (1/L²)",
        "support_compliance" => "support compliance C (L/EI)",
        "surface_angle" => "surface angle β (rad)",
        "tol" => "solver tolerance (–)",
        "mu_max" => "μ_max (–)",
        "mu_end" => "μ at the last point (–)",
        "d_at_mu_max" => "d at μ_max (L)",
        "d_end" => "d at the last point (L)",
        "points" => "points (–)",
        "newton_iters" => "Newton iterations (–)",
        "rhs_evals" => "right-hand-side evaluations (–)",
        "stop_reason" => "stop reason",
        "t" => "time t (√(ρA L⁴/EI))",
        "tip_x" => "tip position x (L)",
        "tip_y" => "tip position y (L)",
        "frequency" => "frequency (1/time unit)",
        "amplitude" => "amplitude of m_base (EI/L)",
        _ => "",
    };
    if known.is_empty() {
        col.to_string()
    } else {
        known.to_string()
    }
}

/// Marker styles and colours of the events, in order of first appearance.
const EVENT_STYLE: [(Kind, RGBColor); 5] = [
    (Kind::Cross, RED_),
    (Kind::Square, PURPLE_),
    (Kind::Triangle, BROWN_),
    (Kind::Ring, NAVY_),
    (Kind::Points, GREEN_),
];

/// The rows of each event name (in order of first appearance).
fn events(t: &Table) -> Vec<(String, Vec<usize>)> {
    let mut out: Vec<(String, Vec<usize>)> = Vec::new();
    for (i, field) in t.text("event").unwrap_or_default().into_iter().enumerate() {
        // (a dynamics file names two events of one step with a space: "slip stick")
        for e in field.split_whitespace() {
            match out.iter_mut().find(|(n, _)| n == e) {
                Some((_, rows)) => rows.push(i),
                None => out.push((e.to_string(), vec![i])),
            }
        }
    }
    out
}

/// One panel of signals against d: the lines, then every event marked on each line (a marker
/// where the value is finite; a dashed vertical line where it is not, e.g. μ = ±inf at
/// lift-off).
fn signal_panel(
    title: &str,
    (xcol, ylabel): (&str, &str),
    d: &[f64],
    lines: &[(&str, &[f64], RGBColor)],
    ev: &[(String, Vec<usize>)],
) -> Panel {
    let mut p = panel(title, &label(xcol), ylabel);
    let finite = |v: f64| v.is_finite();
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for (name, ys, color) in lines {
        let pts: Vec<(f64, f64)> = d.iter().copied().zip(ys.iter().copied()).collect();
        for &(_, y) in &pts {
            if finite(y) {
                lo = lo.min(y);
                hi = hi.max(y);
            }
        }
        let s = series(name, Kind::Line, *color, pts);
        p.series
            .push(if lines.len() == 1 { unlabeled(s) } else { s });
    }
    for (k, (name, rows)) in ev.iter().enumerate() {
        let (kind, color) = EVENT_STYLE[k % EVENT_STYLE.len()];
        let mut pts = Vec::new();
        let mut off = Vec::new();
        for &r in rows {
            for (_, ys, _) in lines {
                if finite(ys[r]) {
                    pts.push((d[r], ys[r]));
                } else if d[r].is_finite() {
                    off.push(d[r]);
                }
            }
        }
        let count = |n: usize| {
            if n > 1 {
                format!(" ({n})")
            } else {
                String::new()
            }
        };
        if !pts.is_empty() {
            p.series.push(series(
                &format!("{name}{}", count(rows.len())),
                kind,
                color,
                pts,
            ));
        }
        off.dedup();
        for (j, x) in off.iter().enumerate() {
            let s = series(
                &format!("{name} at {xcol} = {} (off the scale)", short(*x)),
                Kind::Dashed,
                color,
                vec![(*x, lo), (*x, hi)],
            );
            p.series.push(if j == 0 { s } else { unlabeled(s) });
        }
    }
    p
}

/// A scan or a drag: μ, the tip force (fx, fy and the normal force), the moment at the foot
/// and, for a drag, the tip position, against d (a whisk: the contact force against the foot
/// angle, `xcol` = "theta").
fn signals(t: &Table, title: &str, xcol: &str) -> Res<Fig> {
    let d = t.need(xcol)?;
    let ev = events(t);
    let mut panels = Vec::new();
    // (a frictionless contact's ratio is Newton's residual, ~1e-13: no panel)
    if let Some(mu) = t.num("mu")?.filter(|m| m.iter().any(|v| v.abs() > 1e-9)) {
        panels.push(signal_panel(
            "friction ratio",
            (xcol, &label("mu")),
            &d,
            &[("μ", &mu, BLUE_)],
            &ev,
        ));
    }
    let (fx, fy, normal) = (t.num("fx")?, t.num("fy")?, t.num("normal")?);
    let mut forces: Vec<(&str, &[f64], RGBColor)> = Vec::new();
    if let Some(v) = &fx {
        forces.push(("fx", v, BLUE_));
    }
    if let Some(v) = &fy {
        forces.push(("fy", v, ORANGE_));
    }
    if let Some(v) = &normal {
        forces.push(("normal force N", v, GREEN_));
    }
    if !forces.is_empty() {
        panels.push(signal_panel(
            if xcol == "theta" {
                "contact force on the rod (= −force on the foot)"
            } else {
                "tip force on the rod (= −force on the foot)"
            },
            (xcol, "force (EI/L²)"),
            &d,
            &forces,
            &ev,
        ));
    }
    if let Some(m) = t.num("m_base")? {
        panels.push(signal_panel(
            "moment at the foot",
            (xcol, &label("m_base")),
            &d,
            &[("m_base", &m, BLUE_)],
            &ev,
        ));
    }
    if let Some(x) = t.num("x_tip")? {
        panels.push(signal_panel(
            "tip position",
            (xcol, &label("x_tip")),
            &d,
            &[("x_tip", &x, BLUE_)],
            &ev,
        ));
    }
    if panels.is_empty() {
        return Err(usage(format!(
            "{}: none of the columns mu, fx, fy, normal, m_base, x_tip to plot against {xcol}",
            t.name
        )));
    }
    Ok(Fig {
        name: String::new(),
        caption: title.to_string(),
        panels,
        w: 520,
        h: 440,
        stack: None,
    })
}

/// A column that changes (a drag's tip height, fixed at η, does not).
fn varies(v: &[f64]) -> bool {
    let (lo, hi) = v
        .iter()
        .filter(|x| x.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    hi > lo
}

/// A dynamics file (`dynamics drag`, `dynamics free`): the moment at the foot, the force at
/// the foot, the turn of a drag's support where it turns (`--whisk`, `--foot-table`) and the
/// tip's position (x, and y where it changes) against time, events marked.
fn dynamics(t: &Table) -> Res<Fig> {
    let time = t.need("t")?;
    let ev = events(t);
    let m = t.need("m_base")?;
    let mut panels = vec![signal_panel(
        "moment at the foot",
        ("t", &label("m_base")),
        &time,
        &[("m_base", &m, BLUE_)],
        &ev,
    )];
    let (fx, fy) = (t.need("fx")?, t.need("fy")?);
    panels.push(signal_panel(
        "force at the foot G(0)",
        ("t", "force (EI/L²)"),
        &time,
        &[("fx", &fx, BLUE_), ("fy", &fy, ORANGE_)],
        &ev,
    ));
    // (a drag's theta is its support's turn, clockwise; `dynamics free`'s, without d, is the
    // support's own rotation and is not drawn)
    if let (true, Some(v)) = (t.has("d"), t.num("theta")?.filter(|v| varies(v))) {
        panels.push(signal_panel(
            "turn of the support",
            ("t", &label("theta")),
            &time,
            &[("theta", &v, BLUE_)],
            &ev,
        ));
    }
    for col in ["tip_x", "tip_y"] {
        if let Some(v) = t.num(col)?.filter(|v| varies(v)) {
            panels.push(signal_panel(
                "tip position",
                ("t", &label(col)),
                &time,
                &[(col, &v, BLUE_)],
                &ev,
            ));
        }
    }
    Ok(Fig {
        name: String::new(),
        caption: format!("dynamics {}", t.name),
        panels,
        w: 520,
        h: 440,
        stack: None,
    })
}

/// A spectrum file (`dynamics --spectrum`): the amplitude against frequency, drawn up to 1.2
/// times the highest frequency whose amplitude reaches 0.1 % of the largest (at least 8 bins).
fn spectrum(t: &Table) -> Res<Fig> {
    let (f, a) = (t.need("frequency")?, t.need("amplitude")?);
    let top = a
        .iter()
        .copied()
        .filter(|v| v.is_finite())
        .fold(0.0, f64::max);
    let last = a
        .iter()
        .rposition(|v| *v >= 1e-3 * top)
        .unwrap_or(f.len() - 1);
    let cut = (1.2 * f[last]).max(f[8.min(f.len() - 1)]);
    let pts: Vec<(f64, f64)> = f
        .iter()
        .zip(&a)
        .filter(|(f, a)| **f <= cut && a.is_finite())
        .map(|(f, a)| (*f, *a))
        .collect();
    let mut p = panel(
        "amplitude spectrum of the moment at the foot",
        &label("frequency"),
        &label("amplitude"),
    );
    p.series
        .push(unlabeled(series("amplitude", Kind::Line, BLUE_, pts)));
    Ok(Fig {
        name: String::new(),
        caption: format!("spectrum {}", t.name),
        panels: vec![p],
        w: 520,
        h: 440,
        stack: None,
    })
}

/// Colours of successive shapes.
const SHAPE_COLORS: [RGBColor; 8] = [
    BLUE_,
    ORANGE_,
    GREEN_,
    PURPLE_,
    BROWN_,
    NAVY_,
    RGBColor(227, 119, 194),
    RGBColor(23, 190, 207),
];

/// The rows of each point of a shapes file (in file order).
fn shape_rows(t: &Table) -> Res<BTreeMap<usize, Vec<usize>>> {
    let point = t.need("point")?;
    let mut by_point: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for (i, p) in point.iter().enumerate() {
        if !(p.is_finite() && *p >= 0.0 && p.fract() == 0.0) {
            return Err(usage(format!(
                "{}: row {}: point '{p}' is not an index",
                t.name,
                i + 2
            )));
        }
        by_point.entry(*p as usize).or_default().push(i);
    }
    Ok(by_point)
}

/// `--select`, checked against the points of the file, else `default`.
fn chosen_points(
    t: &Table,
    by_point: &BTreeMap<usize, Vec<usize>>,
    select: Option<&[usize]>,
    default: impl FnOnce() -> Vec<usize>,
) -> Res<Vec<usize>> {
    let Some(sel) = select else {
        return Ok(default());
    };
    for p in sel {
        if !by_point.contains_key(p) {
            let all: Vec<usize> = by_point.keys().copied().collect();
            return Err(usage(format!(
                "--select {p}: {} has points {}..={}",
                t.name,
                all[0],
                all[all.len() - 1]
            )));
        }
    }
    Ok(sel.to_vec())
}

/// The panel of shapes: the rod at the `chosen` points, each in its style (line kind and
/// colour), in the lab frame (foot at (d, 0)) or, for a whisk, the frame of the unturned foot;
/// the feet, and (not for a whisk) the surface line through the first shape's tip inclined by
/// `beta`.
fn shape_panel(
    t: &Table,
    by_point: &BTreeMap<usize, Vec<usize>>,
    chosen: &[(usize, Kind, RGBColor)],
    (title, beta, whisk): (&str, f64, bool),
) -> Res<Panel> {
    let (pcol, xcol) = if whisk {
        ("theta", "x")
    } else {
        (drag_axis(t), "x_lab")
    };
    let (d, s, x, y) = (t.need(pcol)?, t.need("s")?, t.need(xcol)?, t.need("y")?);
    let ev = t.text("event");
    let mut p = panel(title, "x (L)", "y (L)");
    p.equal_aspect = true;
    let mut feet = Vec::new();
    let (mut xmin, mut xmax) = (f64::INFINITY, f64::NEG_INFINITY);
    let mut tip = None;
    for &(pt, kind, color) in chosen {
        let rows = &by_point[&pt];
        let pts: Vec<(f64, f64)> = rows.iter().map(|&r| (x[r], y[r])).collect();
        for q in &pts {
            xmin = xmin.min(q.0);
            xmax = xmax.max(q.0);
        }
        let r0 = rows[0];
        let last = *rows
            .iter()
            .max_by(|a, b| s[**a].total_cmp(&s[**b]))
            .unwrap_or(&r0);
        tip.get_or_insert((x[last], y[last]));
        feet.push((if whisk { 0.0 } else { d[r0] }, 0.0));
        let event = ev.as_ref().map_or("", |e| e[r0]);
        let name = if event.is_empty() {
            format!("{pcol} = {}", short(d[r0]))
        } else {
            format!("{pcol} = {} ({event})", short(d[r0]))
        };
        p.series.push(series(&name, kind, color, pts));
    }
    p.series.push(series("foot", Kind::Square, GREY_, feet));
    if let Some((tx, ty)) = tip.filter(|_| !whisk) {
        let pad = 0.15 * (xmax - xmin).max(0.2);
        let line: Vec<(f64, f64)> = [xmin - pad, xmax + pad]
            .iter()
            .map(|&xx| (xx, ty + (xx - tx) * beta.tan()))
            .collect();
        p.series.push(series(
            &format!("surface (β = {} rad)", short(beta)),
            Kind::Dashed,
            RGBColor(60, 60, 60),
            line,
        ));
    }
    Ok(p)
}

/// Shapes: the rod at the chosen points in the lab frame (foot at (d, 0), the tip fixed), the
/// feet, and the surface line through the tip inclined by `beta`.
fn shapes(t: &Table, select: Option<&[usize]>, beta: f64, whisk: bool) -> Res<Fig> {
    let by_point = shape_rows(t)?;
    let all: Vec<usize> = by_point.keys().copied().collect();
    let ev = t.text("event");
    let chosen = chosen_points(t, &by_point, select, || {
        // six points spread over the file, and every point with an event
        let n = all.len();
        let mut c: Vec<usize> = (0..6.min(n))
            .map(|k| all[if n <= 6 { k } else { k * (n - 1) / 5 }])
            .collect();
        if let Some(ev) = &ev {
            for (&p, rows) in &by_point {
                if !ev[rows[0]].is_empty() {
                    c.push(p);
                }
            }
        }
        c.sort_unstable();
        c.dedup();
        c
    })?;
    let styled: Vec<(usize, Kind, RGBColor)> = chosen
        .iter()
        .enumerate()
        .map(|(k, &pt)| (pt, Kind::Line, SHAPE_COLORS[k % SHAPE_COLORS.len()]))
        .collect();
    let title = if whisk {
        "rod shapes (frame of the unturned foot: the foot turns by theta)"
    } else {
        "rod shapes (lab frame: the tip sticks, the foot moves by d)"
    };
    Ok(Fig {
        name: String::new(),
        caption: format!("{}: {} of {} shapes", t.name, chosen.len(), all.len()),
        panels: vec![shape_panel(t, &by_point, &styled, (title, beta, whisk))?],
        w: 760,
        h: 560,
        stack: None,
    })
}

/// Slips whose shapes a drag's picture draws by default.
const DRAG_SHAPE_SLIPS: usize = 3;

/// A drag with its `--shapes` file: the signals against d with the slips marked, and a panel of
/// the rod just before (solid) and just after (dashed, same colour) each of the first three
/// slips (`--select` chooses other points).
fn drag_with_shapes(t: &Table, sh: &Table, select: Option<&[usize]>, beta: f64) -> Res<Fig> {
    let mut fig = signals(t, &format!("drag {}", t.name), drag_axis(t))?;
    let by_point = shape_rows(sh)?;
    let ev = sh.text("event").ok_or_else(|| {
        usage(format!(
            "{}: no column 'event': not the --shapes file of a drag",
            sh.name
        ))
    })?;
    let event = |pt: &usize| ev[by_point[pt][0]];
    let chosen = chosen_points(sh, &by_point, select, || {
        let mut c = Vec::new();
        let mut slips = 0;
        for pt in by_point.keys() {
            match event(pt) {
                "slip" if slips < DRAG_SHAPE_SLIPS => {
                    slips += 1;
                    c.push(*pt);
                }
                "slip_end" if slips > 0 && c.len() < 2 * slips => c.push(*pt),
                _ => {}
            }
        }
        c
    })?;
    if chosen.is_empty() {
        return Err(usage(format!(
            "{}: no slip to draw (the drag did not slip; --select chooses points)",
            sh.name
        )));
    }
    // a slip and its end share the colour, the end dashed
    let mut slips = 0usize;
    let styled: Vec<(usize, Kind, RGBColor)> = chosen
        .iter()
        .map(|pt| {
            let end = event(pt) == "slip_end";
            if !end {
                slips += 1;
            }
            let kind = if end { Kind::Dashed } else { Kind::Line };
            let k = slips.saturating_sub(1) % SHAPE_COLORS.len();
            (*pt, kind, SHAPE_COLORS[k])
        })
        .collect();
    let mut panel = shape_panel(
        sh,
        &by_point,
        &styled,
        (
            "rod at the slips (lab frame; before: solid, after: dashed)",
            beta,
            false,
        ),
    )?;
    if let Some(path) = curved_surface(t)? {
        // a curved surface: the drag's file does not describe it, but its tips lie on it (issue
        // 33: a flat line was drawn under a corrugated drag)
        if panel
            .series
            .last()
            .is_some_and(|s| s.name.starts_with("surface"))
        {
            panel.series.pop();
        }
        panel.series.push(series(
            "surface (where the tip touched: x_tip, y_tip)",
            Kind::Dashed,
            RGBColor(60, 60, 60),
            path,
        ));
    }
    fig.panels.push(panel);
    Ok(fig)
}

/// The tips of a drag's rows sorted along x, when they are not on one straight line (a
/// corrugated or curved surface; more than 1e-9 off the line through the first and last).
fn curved_surface(t: &Table) -> Res<Option<Vec<(f64, f64)>>> {
    let (Some(x), Some(y)) = (t.num("x_tip")?, t.num("y_tip")?) else {
        return Ok(None);
    };
    let mut pts: Vec<(f64, f64)> = x
        .into_iter()
        .zip(y)
        .filter(|p| p.0.is_finite() && p.1.is_finite())
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    pts.dedup_by(|a, b| a.0 == b.0);
    let (Some(&a), Some(&b)) = (pts.first(), pts.last()) else {
        return Ok(None);
    };
    let slope = if b.0 > a.0 {
        (b.1 - a.1) / (b.0 - a.0)
    } else {
        0.0
    };
    let off = pts
        .iter()
        .map(|p| (p.1 - a.1 - slope * (p.0 - a.0)).abs())
        .fold(0.0, f64::max);
    Ok((pts.len() > 2 && off > 1e-9).then_some(pts))
}

/// A number for a label: 4 significant digits.
fn short(v: f64) -> String {
    crate::number_text::digits(v, 4)
}

/// The grid columns of a sweep CSV that can be heat-map axes: the scene's and the tolerance.
fn sweep_axes() -> impl Iterator<Item = &'static str> {
    crate::sweep::SCENE_AXES.into_iter().chain(["tol"])
}

/// Eight colours from dark blue to yellow (viridis stops).
const SCALE: [RGBColor; 8] = [
    RGBColor(68, 1, 84),
    RGBColor(70, 50, 126),
    RGBColor(54, 92, 141),
    RGBColor(39, 127, 142),
    RGBColor(31, 161, 135),
    RGBColor(74, 193, 109),
    RGBColor(160, 218, 57),
    RGBColor(253, 231, 37),
];

/// The rows of a sweep file that `wheres` (`COL=VALUE`) select, and the columns they fix.
fn selected_rows(t: &Table, wheres: &[String]) -> Res<(Vec<usize>, Vec<String>)> {
    let mut keep: Vec<bool> = vec![true; t.rows.len()];
    let mut fixed = Vec::new();
    for w in wheres {
        let (col, val) = w
            .split_once('=')
            .ok_or_else(|| usage(format!("--where {w}: expected COL=VALUE")))?;
        let vals = t
            .text(col)
            .ok_or_else(|| usage(format!("--where {w}: {} has no column '{col}'", t.name)))?;
        let want = val.parse::<f64>().ok();
        for (k, v) in keep.iter_mut().zip(&vals) {
            let same = match (want, v.parse::<f64>().ok()) {
                (Some(a), Some(b)) => a == b,
                _ => *v == val,
            };
            *k &= same;
        }
        fixed.push(col.to_string());
    }
    let rows: Vec<usize> = (0..t.rows.len()).filter(|&i| keep[i]).collect();
    if rows.is_empty() {
        return Err(usage(format!(
            "--where {}: no row matches",
            wheres.join(" ")
        )));
    }
    Ok((rows, fixed))
}

/// The distinct finite values of column `col` over `rows`, in increasing order.
fn distinct(t: &Table, rows: &[usize], col: &str) -> Res<Vec<f64>> {
    let v = t.need(col)?;
    let mut u: Vec<f64> = rows
        .iter()
        .map(|&r| v[r])
        .filter(|v| v.is_finite())
        .collect();
    u.sort_by(f64::total_cmp);
    u.dedup();
    Ok(u)
}

/// The heat map's axes: `x` and `y` as given, else the grid columns that vary, in order; every
/// other varying column must be fixed by `--where`.
fn heat_axes(
    t: &Table,
    rows: &[usize],
    (x, y): (Option<&str>, Option<&str>),
    fixed: &[String],
) -> Res<(String, String)> {
    let varying: Vec<&str> = sweep_axes()
        .filter(|c| t.has(c) && distinct(t, rows, c).is_ok_and(|u| u.len() > 1))
        .collect();
    let (xc, yc) =
        match (x, y) {
            (Some(x), Some(y)) => (x.to_string(), y.to_string()),
            _ => {
                let mut free = varying
                    .iter()
                    .filter(|c| Some(**c) != x && Some(**c) != y)
                    .map(|c| c.to_string());
                let xc = x.map(str::to_string).or_else(|| free.next());
                let yc = y.map(str::to_string).or_else(|| free.next());
                match (xc, yc) {
                    (Some(a), Some(b)) => (a, b),
                    _ => {
                        return Err(usage(format!(
                        "{}: a heat map needs two axes that vary; varying: {} (give --x and --y)",
                        t.name,
                        if varying.is_empty() { "none".into() } else { varying.join(", ") }
                    )))
                    }
                }
            }
        };
    // every other varying axis must be fixed
    let loose: Vec<&str> = varying
        .iter()
        .copied()
        .filter(|c| *c != xc && *c != yc && !fixed.iter().any(|f| f == c))
        .collect();
    if let Some(c) = loose.first() {
        let u = distinct(t, rows, c)?;
        return Err(usage(format!(
            "{}: {} also {}; choose one value with --where, e.g. --where {c}={}",
            t.name,
            loose.join(", "),
            if loose.len() == 1 { "varies" } else { "vary" },
            num(u[0])
        )));
    }
    Ok((xc, yc))
}

/// Half the smallest gap between the values of `col` (a cell's half width).
fn half_gap(t: &Table, rows: &[usize], col: &str) -> Res<f64> {
    let u = distinct(t, rows, col)?;
    let gap = u
        .windows(2)
        .map(|w| w[1] - w[0])
        .fold(f64::INFINITY, f64::min);
    Ok(if gap.is_finite() {
        0.5 * gap
    } else {
        0.05 * u[0].abs().max(1.0)
    })
}

/// The rows whose scene failed (an error, or the stop reason `error`).
fn failed_rows(t: &Table) -> Vec<bool> {
    let err = t.text("error").unwrap_or_default();
    let stop = t.text("stop_reason").unwrap_or_default();
    (0..t.rows.len())
        .map(|i| {
            err.get(i).is_some_and(|e| !e.is_empty()) || stop.get(i).is_some_and(|s| *s == "error")
        })
        .collect()
}

/// The cells of a heat map: where each row lies, its cell's half sizes, and which rows failed.
struct Cells<'a> {
    rows: &'a [usize],
    xv: &'a [f64],
    yv: &'a [f64],
    half: (f64, f64),
    failed: &'a [bool],
}

impl Cells<'_> {
    /// A numeric column in eight equal bins (one when all values are equal).
    fn binned(&self, p: &mut Panel, z: &str, zv: &[f64]) {
        let (rows, xv, yv, failed) = (self.rows, self.xv, self.yv, self.failed);
        let (hw, hh) = self.half;
        let fin: Vec<f64> = rows
            .iter()
            .map(|&r| zv[r])
            .filter(|v| v.is_finite())
            .collect();
        let lo = fin.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = fin.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let nb = if hi > lo { SCALE.len() } else { 1 };
        let mut bins: Vec<Vec<(f64, f64)>> = vec![Vec::new(); nb];
        for &r in rows {
            if zv[r].is_finite() && !failed[r] {
                let b = if nb == 1 {
                    0
                } else {
                    (((zv[r] - lo) / (hi - lo) * nb as f64) as usize).min(nb - 1)
                };
                bins[b].push((xv[r], yv[r]));
            }
        }
        for (b, pts) in bins.into_iter().enumerate() {
            let (a, c) = if nb == 1 {
                (lo, hi)
            } else {
                (
                    lo + (hi - lo) * b as f64 / nb as f64,
                    lo + (hi - lo) * (b + 1) as f64 / nb as f64,
                )
            };
            let name = if nb == 1 {
                format!("{z} = {}", short(a))
            } else {
                format!("{z} {} – {}", short(a), short(c))
            };
            let color = if nb == 1 { SCALE[4] } else { SCALE[b] };
            p.series.push(series(&name, Kind::Cell(hw, hh), color, pts));
        }
    }

    /// A text column, one colour per value.
    fn categories(&self, p: &mut Panel, z: &str, zt: &[&str]) {
        let (rows, xv, yv, failed) = (self.rows, self.xv, self.yv, self.failed);
        let (hw, hh) = self.half;
        let mut cats: Vec<(String, Vec<(f64, f64)>)> = Vec::new();
        for &r in rows {
            if failed[r] {
                continue;
            }
            let v = zt[r].to_string();
            match cats.iter_mut().find(|(n, _)| *n == v) {
                Some((_, pts)) => pts.push((xv[r], yv[r])),
                None => cats.push((v, vec![(xv[r], yv[r])])),
            }
        }
        let palette = [BLUE_, ORANGE_, GREEN_, PURPLE_, BROWN_, NAVY_, GREY_, RED_];
        for (k, (name, pts)) in cats.into_iter().enumerate() {
            let name = if name.is_empty() {
                "(empty)".to_string()
            } else {
                name
            };
            p.series.push(series(
                &format!("{z}: {name}"),
                Kind::Cell(hw, hh),
                palette[k % palette.len()],
                pts,
            ));
        }
    }
}

/// A sweep: the column `z` as a heat map over the axes `x` and `y` (the rows selected by
/// `wheres`, `COL=VALUE`), numeric values in eight equal bins, text values one colour each;
/// scenes whose scan failed are crossed.
fn sweep(t: &Table, x: Option<&str>, y: Option<&str>, z: &str, wheres: &[String]) -> Res<Fig> {
    let (rows, fixed) = selected_rows(t, wheres)?;
    let (xc, yc) = heat_axes(t, &rows, (x, y), &fixed)?;
    let (xv, yv) = (t.need(&xc)?, t.need(&yc)?);
    let (hw, hh) = (half_gap(t, &rows, &xc)?, half_gap(t, &rows, &yc)?);
    let failed = failed_rows(t);
    let zt = t.text(z).ok_or_else(|| {
        usage(format!(
            "{}: no column '{z}' (columns: {})",
            t.name,
            t.header.join(", ")
        ))
    })?;
    let mut seen = std::collections::HashSet::new();
    for &r in &rows {
        if !seen.insert((xv[r].to_bits(), yv[r].to_bits())) {
            return Err(usage(format!(
                "{}: several rows at {xc} = {}, {yc} = {}: fix the other columns with --where (e.g. method or tol)",
                t.name,
                num(xv[r]),
                num(yv[r])
            )));
        }
    }
    let mut p = panel(&format!("{z} over {xc} and {yc}"), &label(&xc), &label(&yc));
    let cells = Cells {
        rows: &rows,
        xv: &xv,
        yv: &yv,
        half: (hw, hh),
        failed: &failed,
    };
    match t.num(z).ok().flatten() {
        Some(zv) => cells.binned(&mut p, z, &zv),
        None => cells.categories(&mut p, z, &zt),
    }
    let fails: Vec<(f64, f64)> = rows
        .iter()
        .filter(|&&r| failed[r])
        .map(|&r| (xv[r], yv[r]))
        .collect();
    p.series.push(series(
        "scan failed (error)",
        Kind::Cross,
        RGBColor(0, 0, 0),
        fails,
    ));
    let mut caption = t.name.clone();
    if !wheres.is_empty() {
        caption.push_str(&format!(" ({})", wheres.join(", ")));
    }
    Ok(Fig {
        name: String::new(),
        caption,
        panels: vec![p],
        w: 760,
        h: 560,
        stack: None,
    })
}

/// The figure of a file.
pub(crate) fn figure(t: &Table, a: &PlotArgs) -> Res<Fig> {
    let kind = match a.kind {
        PlotKind::Auto => detect(t)?,
        k => k,
    };
    if kind != PlotKind::Sweep {
        // (the sweep's axes; a scan's, a drag's or a whisk's plot has its own: refused, not
        // ignored, naming the column when the file has none of that name, issue 33)
        let given = [("--x", a.x.as_deref()), ("--y", a.y.as_deref())];
        if let Some((flag, Some(col))) = given.into_iter().find(|g| g.1.is_some()) {
            let has = t.has(col);
            return Err(usage(format!(
                "{flag} {col}: {}; {flag} chooses an axis of a sweep's plot, and {} is a {} file, whose plot has its own axes",
                if has { "a column of the file" } else { "no such column in the file" },
                t.name,
                kind.kind_name()
            )));
        }
        if !a.r#where.is_empty() {
            return Err(usage(format!(
                "--where applies to a sweep's file; {} is a {} file",
                t.name,
                kind.kind_name()
            )));
        }
    }
    if a.shapes.is_some() && kind != PlotKind::Drag {
        return Err(usage(format!(
            "--shapes: the rod at the slips is drawn with a drag's file; {} is not one",
            t.name
        )));
    }
    let mut sc = vibrissa::Scene {
        surface_angle: a.surface_angle,
        ..vibrissa::Scene::default()
    };
    let textured = crate::texture::apply(&a.texture, &mut sc)?;
    if textured && !a.aligned {
        return Err(usage(
            "the texture flags (--corrugation-*, --grating-*, --surface-profile) give the surface \
             of a drag's picture with --aligned",
        ));
    }
    let mut fig = match kind {
        PlotKind::Scan => signals(t, &format!("scan {}", t.name), "d")?,
        PlotKind::Drag if a.aligned && drag_axis(t) == "theta" => {
            return Err(usage(format!(
                "{}: --aligned draws a drag whose foot moves along the surface; this drag's \
                 support turned (its column theta): plot it without --aligned",
                t.name
            )))
        }
        PlotKind::Drag if a.aligned => {
            let shape = if textured {
                vibrissa::surface::Height::new(&sc.surface, 0.0, a.surface_angle)?
            } else {
                None
            };
            let path = a
                .shapes
                .as_ref()
                .ok_or_else(|| usage("--aligned needs --shapes"))?;
            aligned::drag_over_surface(
                t,
                &Table::read(path)?,
                a.select.as_deref(),
                shape.as_ref(),
                a.surface_angle,
            )?
        }
        PlotKind::Drag => match &a.shapes {
            Some(path) => {
                drag_with_shapes(t, &Table::read(path)?, a.select.as_deref(), a.surface_angle)?
            }
            None => signals(t, &format!("drag {}", t.name), drag_axis(t))?,
        },
        PlotKind::Whisk => signals(t, &format!("whisk {}", t.name), "theta")?,
        PlotKind::Shapes => shapes(t, a.select.as_deref(), a.surface_angle, false)?,
        PlotKind::WhiskShapes => shapes(t, a.select.as_deref(), a.surface_angle, true)?,
        PlotKind::Sweep => sweep(t, a.x.as_deref(), a.y.as_deref(), &a.z, &a.r#where)?,
        PlotKind::Dynamics => dynamics(t)?,
        PlotKind::Spectrum => spectrum(t)?,
        PlotKind::Auto => unreachable!("detected above"),
    };
    if let Some(title) = &a.title {
        fig.caption = title.clone();
    }
    Ok(fig)
}

/// Where the SVG goes: `--out`, else the input with `.svg`.
pub fn out_path(a: &PlotArgs) -> PathBuf {
    a.out
        .clone()
        .unwrap_or_else(|| a.file.with_extension("svg"))
}

/// Run `vibrissa plot`.
pub fn run(a: &PlotArgs) -> Res<()> {
    let t = Table::read(&a.file)?;
    let fig = figure(&t, a)?;
    let (svg, _) = render(&fig)?;
    let out = out_path(a);
    let mut f = AtomicFile::create(&out)?;
    f.write_all(svg.as_bytes())?;
    f.commit()?;
    writeln!(std::io::stdout(), "plot written to {}", out.display())?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::chart::layout_check::check_panel;
    use crate::chart::{Mark, Series};

    fn err<T>(r: Res<T>) -> String {
        match r {
            Ok(_) => panic!("expected an error"),
            Err(e) => e.message(),
        }
    }

    const SCAN: &str = include_str!("../tests/fixtures/plot/scan.csv");
    const SHAPES: &str = include_str!("../tests/fixtures/plot/shapes.csv");
    const SWEEP: &str = include_str!("../tests/fixtures/plot/sweep.csv");
    const DRAG: &str = include_str!("../tests/fixtures/plot/drag.csv");
    const DRAG_SHAPES: &str = include_str!("../tests/fixtures/plot/drag_shapes.csv");
    const WHISK: &str = include_str!("../tests/fixtures/plot/whisk.csv");
    const WHISK_SHAPES: &str = include_str!("../tests/fixtures/plot/whisk_shapes.csv");
    const DYNAMICS: &str = include_str!("../tests/fixtures/plot/dynamics_drag.csv");
    const WHISK_DYNAMICS: &str = include_str!("../tests/fixtures/plot/dynamics_whisk.csv");
    const SPECTRUM: &str = include_str!("../tests/fixtures/plot/dynamics_spectrum.csv");
    const CORRUGATED: &str = include_str!("../tests/fixtures/plot/drag_corrugated.csv");
    const CORRUGATED_SHAPES: &str =
        include_str!("../tests/fixtures/plot/drag_corrugated_shapes.csv");

    fn args(kind: PlotKind) -> PlotArgs {
        PlotArgs {
            file: PathBuf::from("x.csv"),
            kind,
            out: None,
            title: None,
            select: None,
            shapes: None,
            aligned: false,
            texture: crate::cli::TextureArgs::default(),
            surface_angle: 0.0,
            x: None,
            y: None,
            z: "mu_max".into(),
            r#where: Vec::new(),
        }
    }

    fn fig(name: &str, text: &str, a: &PlotArgs) -> Fig {
        figure(&Table::parse(name, text).unwrap(), a).unwrap()
    }

    /// Renders the figure and checks every panel's layout (legends and labels touch no data,
    /// every point is drawn); returns the layouts.
    fn checked(f: &Fig) -> Vec<crate::chart::PanelLayout> {
        let (svg, l) = render(f).unwrap();
        assert!(svg.starts_with("<svg"), "{}", &svg[..40]);
        for (p, lay) in f.panels.iter().zip(&l) {
            check_panel(&f.caption, p, lay);
        }
        l
    }

    /// A dynamics file's figure: detected as one from its columns, drawn, its layout checked.
    fn dynamics_fig(name: &str, text: &str) -> Fig {
        let t = Table::parse(name, text).unwrap();
        assert_eq!(detect(&t).unwrap(), PlotKind::Dynamics);
        let f = figure(&t, &args(PlotKind::Auto)).unwrap();
        checked(&f);
        f
    }

    fn names(p: &Panel) -> Vec<&str> {
        p.series
            .iter()
            .filter(|s| s.legend && !s.pts.is_empty())
            .map(|s| s.name.as_str())
            .collect()
    }

    #[test]
    fn every_kind_is_detected_and_drawn_without_covering_data() {
        for (name, text, kind, panels) in [
            ("scan.csv", SCAN, PlotKind::Scan, 3),
            ("shapes.csv", SHAPES, PlotKind::Shapes, 1),
            ("sweep.csv", SWEEP, PlotKind::Sweep, 1),
            ("drag.csv", DRAG, PlotKind::Drag, 4),
            ("whisk.csv", WHISK, PlotKind::Whisk, 3),
            ("whisk_shapes.csv", WHISK_SHAPES, PlotKind::WhiskShapes, 1),
        ] {
            let t = Table::parse(name, text).unwrap();
            assert_eq!(detect(&t).unwrap(), kind, "{name}");
            let f = figure(&t, &args(PlotKind::Auto)).unwrap();
            assert_eq!(f.panels.len(), panels, "{name}");
            checked(&f);
        }
    }

    /// A dynamics file (`dynamics drag --speed 0.1 --d-max 0.03 --dt 0.02`: one slip at
    /// t = 1.0967535139444828) and its `--spectrum`: detected from their columns; against time
    /// the moment, the force (fx, fy) and the tip's x (its y, fixed at η, is left out), the slip
    /// marked on each; the spectrum drawn up to 1.2 times its last frequency above 0.1 % of the
    /// peak; two events of one step ("slip stick") are marked as two.
    #[test]
    fn dynamics_and_spectrum_files_are_detected_and_drawn() {
        let f = dynamics_fig("dyn.csv", DYNAMICS);
        let titles: Vec<&str> = f.panels.iter().map(|p| p.title.as_str()).collect();
        assert_eq!(
            titles,
            [
                "moment at the foot",
                "force at the foot G(0)",
                "tip position"
            ]
        );
        assert_eq!(f.panels[2].ylabel, "tip position x (L)");
        for p in &f.panels {
            assert_eq!(p.xlabel, "time t (√(ρA L⁴/EI))");
            let slip: Vec<&Series> = p.series.iter().filter(|s| s.name == "slip").collect();
            assert_eq!(slip.len(), 1, "{}", p.title);
            assert!((slip[0].pts[0].0 - 1.0967535139444828).abs() < 1e-15);
        }
        let s = Table::parse("spec.csv", SPECTRUM).unwrap();
        assert_eq!(detect(&s).unwrap(), PlotKind::Spectrum);
        let f = figure(&s, &args(PlotKind::Auto)).unwrap();
        checked(&f);
        assert_eq!(f.panels.len(), 1);
        let pts = &f.panels[0].series[0].pts;
        let a = s.need("amplitude").unwrap();
        let top = a.iter().copied().fold(0.0, f64::max);
        let fr = s.need("frequency").unwrap();
        let last = a.iter().rposition(|v| *v >= 1e-3 * top).unwrap();
        assert!(pts.iter().all(|p| p.0 <= 1.2 * fr[last] + 1e-12));
        assert!(
            pts.len() > last && pts.len() < fr.len(),
            "{} of {}",
            pts.len(),
            fr.len()
        );
        // two events in one step
        let two = DYNAMICS.replacen(",slip\n", ",slip stick\n", 1);
        let f = fig("dyn.csv", &two, &args(PlotKind::Auto));
        let n = names(&f.panels[0]);
        assert!(n.contains(&"slip") && n.contains(&"stick"), "{n:?}");
    }

    /// A dynamic whisk (`dynamics drag --foot-table` of `0,0` and `4,0`, `--whisk 0.3,0.05`,
    /// `--dt 0.05`: a slip at t = 3.3357, a stick at 3.6784): a panel of the support's turn
    /// between the force and the tip, the events marked on it.
    #[test]
    fn a_dynamic_whisk_draws_the_turn_of_its_support() {
        let f = dynamics_fig("whisk_dyn.csv", WHISK_DYNAMICS);
        let titles: Vec<&str> = f.panels.iter().map(|p| p.title.as_str()).collect();
        assert_eq!(
            titles,
            [
                "moment at the foot",
                "force at the foot G(0)",
                "turn of the support",
                "tip position"
            ]
        );
        let turn = &f.panels[2];
        assert_eq!(turn.ylabel, "foot angle θ (rad, clockwise)");
        let marks: Vec<&str> = turn.series.iter().map(|s| s.name.as_str()).collect();
        assert!(
            marks.contains(&"slip") && marks.contains(&"stick"),
            "{marks:?}"
        );
    }
    #[test]
    fn events_are_marked_on_every_signal() {
        // the scan stops at penetration: one marker per line of each panel, in the legend
        let f = fig("scan.csv", SCAN, &args(PlotKind::Auto));
        for p in &f.panels {
            let ev: Vec<&Series> = p
                .series
                .iter()
                .filter(|s| s.name == "penetration")
                .collect();
            let lines = p.series.iter().filter(|s| s.kind == Kind::Line).count();
            assert_eq!(ev.len(), 1, "{}", p.title);
            assert_eq!(ev[0].pts.len(), lines, "{}", p.title);
            assert!((ev[0].pts[0].0 - 0.07931594116001564).abs() < 1e-15);
        }
        // the drag's three slips, in every panel (the tip position too)
        let f = fig("drag.csv", DRAG, &args(PlotKind::Auto));
        assert_eq!(f.panels[3].title, "tip position");
        for p in &f.panels {
            assert!(
                names(p).contains(&"slip (3)"),
                "{}: {:?}",
                p.title,
                names(p)
            );
        }
        // axis labels carry units
        assert_eq!(f.panels[0].xlabel, "foot displacement d (L)");
        assert_eq!(f.panels[1].ylabel, "force (EI/L²)");
        assert_eq!(f.panels[2].ylabel, "m_base (EI/L)");
    }

    #[test]
    fn columns_are_read_by_name() {
        // a file with new columns (a contact state and its arc length, as the contact rework
        // plans) and the columns in another order draws the same curves
        let t = Table::parse("scan.csv", SCAN).unwrap();
        let mut order: Vec<usize> = (0..t.header.len()).rev().collect();
        order.swap(0, 3);
        let mut text = String::new();
        let head: Vec<&str> = order.iter().map(|&i| t.header[i].as_str()).collect();
        text.push_str(&format!("contact,{},s_c\n", head.join(",")));
        for r in &t.rows {
            let f: Vec<&str> = order.iter().map(|&i| r[i].as_str()).collect();
            text.push_str(&format!("tip,{},0.93\n", f.join(",")));
        }
        let a = fig("scan.csv", SCAN, &args(PlotKind::Auto));
        let b = fig("scan.csv", &text, &args(PlotKind::Auto));
        assert_eq!(a.panels.len(), b.panels.len());
        for (p, q) in a.panels.iter().zip(&b.panels) {
            assert_eq!(p.series.len(), q.series.len());
            for (s, r) in p.series.iter().zip(&q.series) {
                assert_eq!((&s.name, &s.pts), (&r.name, &r.pts));
            }
        }
    }

    #[test]
    fn an_event_off_the_scale_is_a_dashed_line() {
        // lift-off: mu = inf on the event row (the scan writes it so)
        let mut rows: Vec<String> = SCAN.lines().map(str::to_string).collect();
        let last = rows.len() - 1;
        let mut f: Vec<String> = rows[last].split(',').map(str::to_string).collect();
        f[1] = "inf".into();
        let n = f.len();
        f[n - 1] = "lift_off".into();
        rows[last] = f.join(",");
        let f = fig(
            "liftoff.csv",
            &(rows.join("\n") + "\n"),
            &args(PlotKind::Auto),
        );
        let mu = &f.panels[0];
        let line = mu
            .series
            .iter()
            .find(|s| s.name.starts_with("lift_off at d = "))
            .unwrap();
        assert_eq!(line.kind, Kind::Dashed);
        assert!(line.pts.iter().all(|q| q.1.is_finite()));
        // on the other panels the event has finite values: markers
        assert!(names(&f.panels[1]).contains(&"lift_off"));
        checked(&f);
    }

    #[test]
    fn shapes_draw_the_chosen_points_the_feet_and_the_surface() {
        let f = fig("shapes.csv", SHAPES, &args(PlotKind::Auto));
        let p = &f.panels[0];
        assert!(p.equal_aspect);
        let n = names(p);
        // six spread points (0..=16, the last with its event) and the two extra entries
        assert_eq!(n.len(), 8, "{n:?}");
        assert!(n[5].ends_with("(penetration)"), "{n:?}");
        assert_eq!(n[6], "foot");
        assert_eq!(n[7], "surface (β = 0 rad)");
        let mut a = args(PlotKind::Auto);
        a.select = Some(vec![0, 4]);
        a.surface_angle = -0.1;
        let f = fig("shapes.csv", SHAPES, &a);
        let p = &f.panels[0];
        assert_eq!(
            names(p),
            ["d = 0", "d = 0.02", "foot", "surface (β = -0.1 rad)"]
        );
        // the surface line passes through the tip, inclined by beta
        let s = p.series.last().unwrap();
        let slope = (s.pts[1].1 - s.pts[0].1) / (s.pts[1].0 - s.pts[0].0);
        assert!((slope - (-0.1f64).tan()).abs() < 1e-12);
        checked(&f);
        a.select = Some(vec![99]);
        let e = err(figure(&Table::parse("shapes.csv", SHAPES).unwrap(), &a));
        assert!(e.contains("--select 99"), "{e}");
    }

    /// The corrugation of the fixture (README there): `A sin(2πx/W)` at height 0.
    fn corrugation() -> vibrissa::surface::Height {
        let p = vibrissa::surface::SurfaceProfile::Sine {
            amplitude: 0.005,
            wavelength: 0.1,
            phase: 0.0,
        };
        vibrissa::surface::Height::new(&p, 0.0, 0.0)
            .unwrap()
            .unwrap()
    }

    /// Issue 31's picture of a drag over its surface (15 slips over a corrugation): above, the
    /// surface at the height the tips give (η = 0.75, to 1e-6), the rod before and after every
    /// slip, the feet at x = d and the tip's contacts; below, m_base(d) with the slips marked —
    /// in the same x range and the same horizontal pixel extent, so that a foot at x = d
    /// stands above its corner of the sawtooth.
    #[test]
    fn a_drag_over_its_surface_aligns_the_rods_with_the_sawtooth() {
        let t = Table::parse("drag_corrugated.csv", CORRUGATED).unwrap();
        let sh = Table::parse("drag_corrugated_shapes.csv", CORRUGATED_SHAPES).unwrap();
        let h = corrugation();
        let f = aligned::drag_over_surface(&t, &sh, None, Some(&h), 0.0).unwrap();
        assert_eq!(f.panels.len(), 2);
        let (up, low) = (&f.panels[0], &f.panels[1]);
        assert!(up.equal_aspect && !low.equal_aspect);
        assert_eq!(
            names(up),
            [
                "surface (η = 0.75 from the tips)",
                "rod just before a slip",
                "rod just after a slip",
                "foot at a slip (x = d)",
                "tip where it slips (15)",
                "tip where it stops (15)"
            ]
        );
        // 15 slips: 30 rods of 9 samples from the foot (d, 0) to the tip on the surface
        let rods: Vec<&Series> = up
            .series
            .iter()
            .filter(|s| matches!(s.kind, Kind::Line | Kind::Dashed) && s.pts.len() == 9)
            .collect();
        assert_eq!(rods.len(), 30);
        for s in &rods {
            let (foot, tip) = (s.pts[0], s.pts[8]);
            assert_eq!(foot.1, 0.0);
            assert!((tip.1 - 0.75 - h.h(tip.0)).abs() < 1e-6, "{tip:?}");
        }
        // the surface passes through every contact of the tip
        let surface = &up.series[0];
        for s in up.series.iter().filter(|s| s.name.starts_with("tip where")) {
            for &(x, y) in &s.pts {
                assert!((y - 0.75 - h.h(x)).abs() < 1e-6, "{}: ({x}, {y})", s.name);
                assert!(surface.pts[0].0 < x && x < surface.pts.last().unwrap().0);
            }
        }
        // below: the moment with its slips (and their ends) marked
        let n = names(low);
        assert!(
            n.contains(&"slip (15)") && n.contains(&"slip_end (15)"),
            "{n:?}"
        );
        let (svg, l) = render(&f).unwrap();
        for (a, b) in [(l[0].plot.x0, l[1].plot.x0), (l[0].plot.x1, l[1].plot.x1)] {
            assert!((a - b).abs() < 1e-9, "plot areas at {a} and {b}");
        }
        assert_eq!(l[0].x_range, l[1].x_range);
        // every foot and every slip of the sawtooth inside the shared range
        let d = t.need("d").unwrap();
        assert!(l[0].x_range.0 < 0.0 && d.iter().all(|&x| x < l[0].x_range.1));
        for p in [up, low] {
            assert!(svg.contains(&p.title), "{}", p.title);
        }
        for (p, lay) in f.panels.iter().zip(&l) {
            check_panel("drag over its surface", p, lay);
        }
        // without the texture, the surface is the path through the tips
        let f = aligned::drag_over_surface(&t, &sh, None, None, 0.0).unwrap();
        assert!(names(&f.panels[0])[0].starts_with("surface (where the tip touched"));
        // another corrugation is refused: the tips are not on it
        let p = vibrissa::surface::SurfaceProfile::Sine {
            amplitude: 0.005,
            wavelength: 0.11,
            phase: 0.0,
        };
        let other = vibrissa::surface::Height::new(&p, 0.0, 0.0)
            .unwrap()
            .unwrap();
        let e = err(aligned::drag_over_surface(&t, &sh, None, Some(&other), 0.0));
        assert!(e.contains("the tips lie up to"), "{e}");
        // the texture flags draw --aligned's surface only
        let mut a = args(PlotKind::Auto);
        a.texture.corrugation_amplitude = vec![0.005];
        a.texture.corrugation_wavelength = vec![0.1];
        let e = err(figure(&t, &a));
        assert!(e.contains("with --aligned"), "{e}");
    }

    #[test]
    fn a_drag_with_its_shapes_draws_the_rod_before_and_after_the_slips() {
        let t = Table::parse("drag.csv", DRAG).unwrap();
        let sh = Table::parse("drag_shapes.csv", DRAG_SHAPES).unwrap();
        let f = drag_with_shapes(&t, &sh, None, 0.0).unwrap();
        // the four signal panels, then the shapes
        assert_eq!(f.panels.len(), 5);
        assert_eq!(f.panels[3].title, "tip position");
        let p = &f.panels[4];
        assert!(p.equal_aspect);
        // the three slips of the file (points 8, 14, 20) and their ends, one colour each
        assert_eq!(
            names(p),
            [
                "d = 0.0358 (slip)",
                "d = 0.0358 (slip_end)",
                "d = 0.05661 (slip)",
                "d = 0.05661 (slip_end)",
                "d = 0.07743 (slip)",
                "d = 0.07743 (slip_end)",
                "foot",
                "surface (β = 0 rad)"
            ]
        );
        for pair in p.series[..6].chunks(2) {
            assert_eq!((pair[0].kind, pair[1].kind), (Kind::Line, Kind::Dashed));
            assert_eq!(pair[0].color, pair[1].color);
            // the rod from the foot at (d, 0) to the tip on the surface (y = 0.75), 9 samples
            assert_eq!(pair[0].pts.len(), 9);
            for s in pair {
                let (foot, tip) = (s.pts[0], s.pts[8]);
                assert_eq!(foot.1, 0.0);
                assert!((tip.1 - 0.75).abs() < 1e-9, "{}: tip {tip:?}", s.name);
            }
            // the slip moves the tip forward, the foot stays
            assert_eq!(pair[0].pts[0], pair[1].pts[0]);
            assert!(pair[1].pts[8].0 > pair[0].pts[8].0 + 1e-3);
        }
        assert_ne!(p.series[0].color, p.series[2].color);
        checked(&f);
        // --select chooses; a shapes file without a slip, or --shapes with a scan, is refused
        let f = drag_with_shapes(&t, &sh, Some(&[0, 9]), 0.0).unwrap();
        assert_eq!(names(&f.panels[4])[..2], ["d = 0", "d = 0.0358 (slip_end)"]);
        let e = err(drag_with_shapes(
            &t,
            &Table::parse("shapes.csv", SHAPES).unwrap(),
            None,
            0.0,
        ));
        assert!(e.contains("no slip to draw"), "{e}");
        let mut a = args(PlotKind::Auto);
        a.shapes = Some(PathBuf::from("drag_shapes.csv"));
        let e = err(figure(&Table::parse("scan.csv", SCAN).unwrap(), &a));
        assert!(e.contains("scan.csv is not one"), "{e}");
    }

    #[test]
    fn sweep_heat_map_bins_values_and_crosses_failures() {
        let f = fig("sweep.csv", SWEEP, &args(PlotKind::Auto));
        let p = &f.panels[0];
        assert_eq!(
            (p.xlabel.as_str(), p.ylabel.as_str()),
            ("surface height η (L)", "rest curvature K0 (1/L)")
        );
        let cells: usize = p
            .series
            .iter()
            .filter(|s| matches!(s.kind, Kind::Cell(..)))
            .map(|s| s.pts.len())
            .sum();
        let failed = p
            .series
            .iter()
            .find(|s| s.name == "scan failed (error)")
            .unwrap();
        let errors = SWEEP.lines().skip(1).filter(|l| !l.ends_with(',')).count();
        assert_eq!(failed.pts.len(), errors);
        assert_eq!(cells + errors, 72);
        // the cells fill the plot: the legend goes beside it, and the check still passes
        let l = checked(&f);
        let (pl, lg) = (l[0].plot, l[0].legend.unwrap());
        assert!(lg.x0 >= pl.x1 || lg.y0 >= pl.y1, "{lg:?} beside {pl:?}");
        // text columns: one colour per value
        let mut a = args(PlotKind::Auto);
        a.z = "stop_reason".into();
        let f = fig("sweep.csv", SWEEP, &a);
        let n = names(&f.panels[0]);
        assert!(
            n.contains(&"stop_reason: penetration") && n.contains(&"stop_reason: d_max"),
            "{n:?}"
        );
        checked(&f);
    }

    #[test]
    fn sweep_needs_two_axes_and_the_others_fixed() {
        // three varying axes: a taper column added with two values
        let mut text = String::new();
        for (i, l) in SWEEP.lines().enumerate() {
            text.push_str(&if i == 0 {
                l.to_string()
            } else {
                let mut f: Vec<&str> = l.split(',').collect();
                let v = if i % 2 == 0 { "0.5" } else { "1.0" };
                f[2] = v;
                f.join(",")
            });
            text.push('\n');
        }
        let t3 = Table::parse("sweep3.csv", &text).unwrap();
        let e = err(figure(&t3, &args(PlotKind::Auto)));
        // x and y default to the first two varying grid columns, eta and taper
        assert!(e.contains("precurvature also varies; choose one value with --where, e.g. --where precurvature=-1.0"), "{e}");
        let mut a = args(PlotKind::Auto);
        a.r#where = vec!["precurvature=0.5".into()];
        let f = figure(&t3, &a).unwrap();
        assert_eq!(f.panels[0].ylabel, "taper ratio ρ (–)");
        checked(&f);
        a.r#where = vec!["precurvature=0.7".into()];
        assert!(err(figure(&t3, &a)).contains("no row matches"));
        // two rows for one cell (a sweep over two methods, say)
        let twice = format!("{SWEEP}{}", SWEEP.split_once('\n').unwrap().1);
        let e = err(figure(
            &Table::parse("twice.csv", &twice).unwrap(),
            &args(PlotKind::Auto),
        ));
        assert!(e.contains("several rows at eta"), "{e}");
    }

    #[test]
    fn the_layout_check_fails_on_a_legend_over_a_cell() {
        let f = fig("sweep.csv", SWEEP, &args(PlotKind::Auto));
        let (_, mut l) = render(&f).unwrap();
        // move the legend onto the first cell: the check must refuse it
        let cell = l[0]
            .marks
            .iter()
            .find_map(|m| match m {
                Mark::Area(r) => Some(*r),
                _ => None,
            })
            .unwrap();
        let lg = l[0].legend.unwrap();
        l[0].legend = Some(crate::chart::Rect {
            x0: cell.x0 + 1.0,
            y0: cell.y0 + 1.0,
            x1: cell.x0 + 1.0 + (lg.x1 - lg.x0),
            y1: cell.y0 + 1.0 + (lg.y1 - lg.y0),
        });
        let r = std::panic::catch_unwind(|| check_panel("moved", &f.panels[0], &l[0]));
        assert!(
            r.is_err(),
            "a legend over a heat-map cell must fail the check"
        );
    }

    #[test]
    fn files_that_are_not_ours_are_refused() {
        let t = Table::parse("other.csv", "a,b\n1,2\n").unwrap();
        let e = err(detect(&t));
        assert!(e.contains("not a file vibrissa writes"), "{e}");
        let t = Table::parse("bad.csv", "d,mu\n0,zero\n").unwrap();
        let e = err(figure(&t, &args(PlotKind::Auto)));
        assert!(
            e.contains("column mu, row 2: 'zero' is not a number"),
            "{e}"
        );
        assert!(err(Table::parse("empty.csv", "d,mu\n")).contains("no rows"));
    }
}
