//! `vibrissa figures`: the paper's Figures 2-11 as SVG (plotters) with the CSV behind each.
//! Numerical curves come from the `vibrissa` solvers; the closed forms (`elastica`) are overlaid.
//!
//! Layout: plotters places every element on whole pixels, so the SVG is drawn at `S` times the
//! output size and scaled down by its `viewBox` (coordinates effectively on a 1/S pixel grid, no
//! jagged curves). Legends and curve labels are placed by this module, not by plotters: from the
//! pixel positions of every drawn series, in an empty region of the plot area (or to the right of
//! it when there is none), so that they never cover data. [`PanelLayout`] records those positions.

use crate::cli::{FiguresArgs, MethodArg};
use crate::error::{solve_fail, usage, Fail, Res};
use crate::numeric;
use crate::output::{csv_line, num, AtomicFile};
use crate::scan::{run_scan, ScanOut, ScanSpec};
use crate::solve::ShapeRow;
use elastica::{Branch, Elastica, Phase0End};
use plotters::coord::types::RangedCoordf64;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};
use std::io::Write;
use std::path::Path;
use vibrissa::{BranchChoice, Rod, Scene, SolverConfig, Target};

/// SVG user units per output pixel (the internal drawing resolution).
const S: i32 = 4;

/// Output pixels to SVG user units.
fn u(px: f64) -> i32 {
    (px * S as f64).round() as i32
}

/// How a series is drawn.
#[derive(Clone, Copy, PartialEq, Debug)]
pub(crate) enum Kind {
    /// solid line, 2 px
    Line,
    /// solid line, 1.5 px (a closed form drawn over numerical rings)
    Thin,
    Dashed,
    DashDot,
    /// filled dots
    Points,
    /// hollow circles (numerical points that must not hide the curve under them)
    Ring,
    /// hollow triangles
    Triangle,
    /// hollow squares
    Square,
    Cross,
    /// a segment from `pts[0]` to `pts[1]` with an arrowhead at `pts[1]`
    Arrow,
    /// filled rectangles centred on the points, of these half-widths in data units (heat-map
    /// cells); a filled square in the legend
    Cell(f64, f64),
}

impl Kind {
    fn is_line(self) -> bool {
        matches!(
            self,
            Kind::Line | Kind::Thin | Kind::Dashed | Kind::DashDot | Kind::Arrow
        )
    }

    /// Radius of a marker, output pixels (its extent for collisions, stroke included).
    fn radius(self) -> f64 {
        match self {
            Kind::Points => 3.0,
            Kind::Ring => 4.25,
            Kind::Triangle => 5.5,
            Kind::Square => 5.5,
            Kind::Cross => 7.5,
            _ => 0.0,
        }
    }
}

/// A text placed next to a series' data (e.g. Fig. 2's α of each curve).
pub(crate) struct Tag {
    text: String,
    /// candidate data points to put the text next to, in order of preference
    anchors: Vec<(f64, f64)>,
}

pub(crate) struct Series {
    pub name: String,
    pub kind: Kind,
    pub color: RGBColor,
    pub pts: Vec<(f64, f64)>,
    pub legend: bool,
    pub tag: Option<Tag>,
}

pub(crate) fn series(name: &str, kind: Kind, color: RGBColor, pts: Vec<(f64, f64)>) -> Series {
    Series {
        name: name.into(),
        kind,
        color,
        pts,
        legend: true,
        tag: None,
    }
}

pub(crate) fn unlabeled(mut s: Series) -> Series {
    s.legend = false;
    s
}

pub(crate) struct Panel {
    pub title: String,
    pub xlabel: String,
    pub ylabel: String,
    pub series: Vec<Series>,
    pub equal_aspect: bool,
}

pub(crate) fn panel(title: &str, xlabel: &str, ylabel: &str) -> Panel {
    Panel {
        title: title.into(),
        xlabel: xlabel.into(),
        ylabel: ylabel.into(),
        series: Vec::new(),
        equal_aspect: false,
    }
}

/// One output file: panels side by side, each `w` by `h` output pixels (plus the caption).
pub(crate) struct Fig {
    pub name: String,
    pub caption: String,
    pub panels: Vec<Panel>,
    pub w: u32,
    pub h: u32,
}

fn pe<E: std::fmt::Debug>(e: E) -> Fail {
    solve_fail(format!("drawing the figure failed: {e:?}"))
}

pub(crate) const BLUE_: RGBColor = RGBColor(31, 119, 180);
pub(crate) const ORANGE_: RGBColor = RGBColor(255, 127, 14);
pub(crate) const GREEN_: RGBColor = RGBColor(44, 160, 44);
pub(crate) const RED_: RGBColor = RGBColor(214, 39, 40);
pub(crate) const PURPLE_: RGBColor = RGBColor(148, 103, 189);
pub(crate) const GREY_: RGBColor = RGBColor(110, 110, 110);
pub(crate) const NAVY_: RGBColor = RGBColor(20, 30, 110);
pub(crate) const BROWN_: RGBColor = RGBColor(120, 60, 10);

// ---------------------------------------------------------------------------------------------
// Layout geometry (SVG user units, absolute in the figure)

/// Axis-aligned rectangle, `x0 < x1`, `y0 < y1` (y grows downwards).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Rect {
    pub x0: f64,
    pub y0: f64,
    pub x1: f64,
    pub y1: f64,
}

impl Rect {
    fn at(x0: f64, y0: f64, w: f64, h: f64) -> Rect {
        Rect {
            x0,
            y0,
            x1: x0 + w,
            y1: y0 + h,
        }
    }

    fn grow(&self, g: f64) -> Rect {
        Rect {
            x0: self.x0 - g,
            y0: self.y0 - g,
            x1: self.x1 + g,
            y1: self.y1 + g,
        }
    }

    fn contains(&self, r: &Rect) -> bool {
        r.x0 >= self.x0 && r.x1 <= self.x1 && r.y0 >= self.y0 && r.y1 <= self.y1
    }

    fn overlaps(&self, r: &Rect) -> bool {
        self.x0 < r.x1 && r.x0 < self.x1 && self.y0 < r.y1 && r.y0 < self.y1
    }

    /// Distance from a point (0 inside).
    fn dist(&self, p: (f64, f64)) -> f64 {
        let dx = (self.x0 - p.0).max(p.0 - self.x1).max(0.0);
        let dy = (self.y0 - p.1).max(p.1 - self.y1).max(0.0);
        dx.hypot(dy)
    }
}

/// Something drawn, in SVG user units: a polyline or a marker of radius `r`.
#[derive(Clone, Debug)]
pub(crate) enum Mark {
    Path(Vec<(f64, f64)>),
    Dot((f64, f64), f64),
    /// a filled area
    Area(Rect),
}

/// Whether segment `a`-`b` meets the rectangle (Liang-Barsky clipping).
fn seg_meets(a: (f64, f64), b: (f64, f64), r: &Rect) -> bool {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-dx, a.0 - r.x0),
        (dx, r.x1 - a.0),
        (-dy, a.1 - r.y0),
        (dy, r.y1 - a.1),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return false;
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
            if t0 > t1 {
                return false;
            }
        }
    }
    true
}

fn point_seg_dist(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let l2 = dx * dx + dy * dy;
    let t = if l2 > 0.0 {
        (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p.0 - a.0 - t * dx).hypot(p.1 - a.1 - t * dy)
}

fn seg_rect_dist(a: (f64, f64), b: (f64, f64), r: &Rect) -> f64 {
    if seg_meets(a, b, r) {
        return 0.0;
    }
    let corners = [(r.x0, r.y0), (r.x1, r.y0), (r.x0, r.y1), (r.x1, r.y1)];
    corners
        .iter()
        .map(|&c| point_seg_dist(c, a, b))
        .fold(r.dist(a).min(r.dist(b)), f64::min)
}

/// Smallest distance from the rectangle to any mark (0 when one touches it).
fn clearance(r: &Rect, marks: &[Mark]) -> f64 {
    let mut best = f64::INFINITY;
    for m in marks {
        let d = match m {
            Mark::Dot(c, rad) => (r.dist(*c) - rad).max(0.0),
            Mark::Area(a) => {
                let dx = (a.x0 - r.x1).max(r.x0 - a.x1).max(0.0);
                let dy = (a.y0 - r.y1).max(r.y0 - a.y1).max(0.0);
                dx.hypot(dy)
            }
            Mark::Path(p) if p.len() == 1 => r.dist(p[0]),
            Mark::Path(p) => p
                .windows(2)
                .map(|w| seg_rect_dist(w[0], w[1], r))
                .fold(f64::INFINITY, f64::min),
        };
        best = best.min(d);
        if best == 0.0 {
            break;
        }
    }
    best
}

/// Estimated width of a text in SVG user units (plotters writes `font-size = size / 1.24`;
/// 0.6 em per character is on the wide side of an average sans-serif glyph).
fn text_w(s: &str, size: f64) -> f64 {
    s.chars().count() as f64 * 0.6 * size * S as f64 / 1.24
}

fn text_h(size: f64) -> f64 {
    1.25 * size * S as f64 / 1.24
}

const LEGEND_FONT: f64 = 14.0;
const TAG_FONT: f64 = 14.0;
/// Legend and labels keep at least this many output pixels from any drawn data.
const CLEAR_PX: f64 = 4.0;

/// Where legends and labels of a panel went (SVG user units).
#[derive(Clone, Debug)]
#[cfg_attr(not(test), allow(dead_code))] // the program only draws; the tests read it back
pub(crate) struct PanelLayout {
    /// the whole panel (below the figure caption)
    pub area: Rect,
    /// the plot area (inside the axes)
    pub plot: Rect,
    /// everything drawn from the data
    pub marks: Vec<Mark>,
    /// the legend box, if the panel has one
    pub legend: Option<Rect>,
    /// curve labels: text and box
    pub tags: Vec<(String, Rect)>,
    /// labels that found no free place (not drawn)
    pub untagged: Vec<String>,
}

fn legend_entries(p: &Panel) -> Vec<&Series> {
    p.series
        .iter()
        .filter(|s| s.legend && !s.pts.is_empty())
        .collect()
}

const ROW_PX: f64 = 18.0;
const GLYPH_PX: f64 = 26.0;

fn legend_size(p: &Panel) -> Option<(f64, f64)> {
    let e = legend_entries(p);
    if e.is_empty() {
        return None;
    }
    let tw = e
        .iter()
        .map(|s| text_w(&s.name, LEGEND_FONT))
        .fold(0.0, f64::max);
    let pad = 7.0 * S as f64;
    Some((
        2.0 * pad + (GLYPH_PX + 6.0) * S as f64 + tw,
        2.0 * pad + e.len() as f64 * ROW_PX * S as f64 - 4.0 * S as f64,
    ))
}

/// A free place for a `w` by `h` box inside the plot area: corners first, then edge midpoints,
/// then the grid position farthest from any data.
fn free_spot(plot: &Rect, w: f64, h: f64, marks: &[Mark]) -> Option<Rect> {
    let inset = 8.0 * S as f64;
    let need = CLEAR_PX * S as f64;
    let (xl, xr) = (plot.x0 + inset, plot.x1 - inset - w);
    let (yt, yb) = (plot.y0 + inset, plot.y1 - inset - h);
    if xr < xl || yb < yt {
        return None;
    }
    let (xm, ym) = (0.5 * (xl + xr), 0.5 * (yt + yb));
    for (x, y) in [
        (xr, yt),
        (xl, yt),
        (xr, yb),
        (xl, yb),
        (xm, yt),
        (xm, yb),
        (xl, ym),
        (xr, ym),
    ] {
        let r = Rect::at(x, y, w, h);
        if clearance(&r, marks) >= need {
            return Some(r);
        }
    }
    let step = 6.0 * S as f64;
    let mut best: Option<(f64, Rect)> = None;
    let mut y = yt;
    while y <= yb {
        let mut x = xl;
        while x <= xr {
            let r = Rect::at(x, y, w, h);
            let c = clearance(&r, marks);
            if c >= need && best.is_none_or(|(b, _)| c > b) {
                best = Some((c, r));
            }
            x += step;
        }
        y += step;
    }
    best.map(|b| b.1)
}

/// Place a tag next to one of its anchors, clear of data, the legend and earlier tags.
fn place_tag(
    text: &str,
    anchors: &[(f64, f64)],
    plot: &Rect,
    marks: &[Mark],
    taken: &[Rect],
) -> Option<Rect> {
    let (w, h) = (text_w(text, TAG_FONT), text_h(TAG_FONT));
    let g = 3.0 * S as f64;
    let need = 2.5 * S as f64;
    let inner = plot.grow(-2.0 * S as f64);
    for &(ax, ay) in anchors {
        for (dx, dy) in [
            (g, -g - h),
            (g, g),
            (-g - w, -g - h),
            (-g - w, g),
            (-0.5 * w, -2.0 * g - h),
            (-0.5 * w, 2.0 * g),
            (g, -0.5 * h),
            (-g - w, -0.5 * h),
        ] {
            let r = Rect::at(ax + dx, ay + dy, w, h);
            if inner.contains(&r)
                && !taken.iter().any(|t| t.grow(g).overlaps(&r))
                && clearance(&r, marks) >= need
            {
                return Some(r);
            }
        }
    }
    None
}

// ---------------------------------------------------------------------------------------------
// Drawing

fn font(size: f64) -> TextStyle<'static> {
    TextStyle::from(("sans-serif", size * S as f64).into_font())
}

/// Padded data ranges of a panel.
fn data_ranges(p: &Panel) -> ((f64, f64), (f64, f64)) {
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for s in &p.series {
        let (hw, hh) = match s.kind {
            Kind::Cell(hw, hh) => (hw, hh),
            _ => (0.0, 0.0),
        };
        for &(x, y) in &s.pts {
            if x.is_finite() && y.is_finite() {
                x0 = x0.min(x - hw);
                x1 = x1.max(x + hw);
                y0 = y0.min(y - hh);
                y1 = y1.max(y + hh);
            }
        }
    }
    if x0 > x1 {
        return ((0.0, 1.0), (0.0, 1.0));
    }
    let pad = |a: f64, b: f64| {
        let d = (b - a).max(1e-9) * 0.05;
        (a - d, b + d)
    };
    (pad(x0, x1), pad(y0, y1))
}

/// Widen one range so that both axes have the same length per pixel.
fn equal_aspect(xr: (f64, f64), yr: (f64, f64), pw: f64, ph: f64) -> ((f64, f64), (f64, f64)) {
    let (sx, sy) = ((xr.1 - xr.0) / pw, (yr.1 - yr.0) / ph);
    if sx > sy {
        let c = 0.5 * (yr.0 + yr.1);
        (xr, (c - 0.5 * sx * ph, c + 0.5 * sx * ph))
    } else {
        let c = 0.5 * (xr.0 + xr.1);
        ((c - 0.5 * sy * pw, c + 0.5 * sy * pw), yr)
    }
}

type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

fn build<'a, DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    right: i32,
    bottom: i32,
    xr: (f64, f64),
    yr: (f64, f64),
) -> Res<Chart<'a, DB>>
where
    DB::ErrorType: 'static,
{
    ChartBuilder::on(area)
        .margin(u(12.0))
        .margin_right(right)
        .margin_bottom(bottom)
        .x_label_area_size(u(45.0))
        .y_label_area_size(u(62.0))
        .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)
        .map_err(pe)
}

fn plot_rect<DB: DrawingBackend>(c: &Chart<'_, DB>) -> Rect {
    let (xs, ys) = c.plotting_area().get_pixel_range();
    Rect {
        x0: xs.start as f64,
        y0: ys.start as f64,
        x1: xs.end as f64,
        y1: ys.end as f64,
    }
}

/// Pixel positions of every series (NaN points dropped) and the marks they draw.
fn to_pixels<DB: DrawingBackend>(
    c: &Chart<'_, DB>,
    p: &Panel,
) -> (Vec<Vec<(f64, f64)>>, Vec<Mark>) {
    let mut px = Vec::with_capacity(p.series.len());
    let mut marks = Vec::new();
    for s in &p.series {
        let v: Vec<(f64, f64)> = s
            .pts
            .iter()
            .filter(|(x, y)| x.is_finite() && y.is_finite())
            .map(|q| {
                let b = c.backend_coord(q);
                (b.0 as f64, b.1 as f64)
            })
            .collect();
        if let Kind::Cell(hw, hh) = s.kind {
            for q in s.pts.iter().filter(|(x, y)| x.is_finite() && y.is_finite()) {
                let a = c.backend_coord(&(q.0 - hw, q.1 + hh));
                let b = c.backend_coord(&(q.0 + hw, q.1 - hh));
                marks.push(Mark::Area(Rect {
                    x0: a.0 as f64,
                    y0: a.1 as f64,
                    x1: b.0 as f64,
                    y1: b.1 as f64,
                }));
            }
        } else if s.kind.is_line() {
            if !v.is_empty() {
                marks.push(Mark::Path(v.clone()));
            }
        } else {
            let r = s.kind.radius() * S as f64;
            marks.extend(v.iter().map(|&q| Mark::Dot(q, r)));
        }
        px.push(v);
    }
    (px, marks)
}

fn marker<DB: DrawingBackend>(
    a: &DrawingArea<DB, plotters::coord::Shift>,
    kind: Kind,
    color: RGBColor,
    (x, y): (i32, i32),
) -> Res<()>
where
    DB::ErrorType: 'static,
{
    let closed = |pts: &[(f64, f64)], w: f64| -> Res<()> {
        let mut v: Vec<(i32, i32)> = pts.iter().map(|&(dx, dy)| (x + u(dx), y + u(dy))).collect();
        v.push(v[0]);
        a.draw(&PathElement::new(v, color.stroke_width(u(w) as u32)))
            .map_err(pe)
    };
    match kind {
        Kind::Points => a
            .draw(&Circle::new((x, y), u(3.0), color.filled()))
            .map_err(pe),
        Kind::Ring => a
            .draw(&Circle::new(
                (x, y),
                u(3.5),
                color.stroke_width(u(1.5) as u32),
            ))
            .map_err(pe),
        Kind::Triangle => closed(&[(0.0, -4.5), (4.0, 2.5), (-4.0, 2.5)], 1.5),
        Kind::Square => closed(&[(-4.0, -4.0), (4.0, -4.0), (4.0, 4.0), (-4.0, 4.0)], 2.0),
        Kind::Cell(..) => a
            .draw(&Rectangle::new(
                [(x - u(5.0), y - u(5.0)), (x + u(5.0), y + u(5.0))],
                color.filled(),
            ))
            .map_err(pe),
        Kind::Cross => {
            let st = color.stroke_width(u(3.0) as u32);
            let h = u(6.0);
            a.draw(&PathElement::new(vec![(x - h, y - h), (x + h, y + h)], st))
                .map_err(pe)?;
            a.draw(&PathElement::new(vec![(x - h, y + h), (x + h, y - h)], st))
                .map_err(pe)
        }
        _ => Ok(()),
    }
}

fn line<DB: DrawingBackend>(
    a: &DrawingArea<DB, plotters::coord::Shift>,
    kind: Kind,
    color: RGBColor,
    pts: Vec<(i32, i32)>,
) -> Res<()>
where
    DB::ErrorType: 'static,
{
    let st = color.stroke_width(u(if kind == Kind::Thin { 1.5 } else { 2.0 }) as u32);
    match kind {
        Kind::Dashed => a
            .draw(&DashedPathElement::new(pts, u(8.0), u(5.0), st))
            .map_err(pe),
        Kind::DashDot => a
            .draw(&DashedPathElement::new(pts, u(3.0), u(4.0), st))
            .map_err(pe),
        Kind::Arrow => {
            if pts.len() < 2 {
                return Ok(());
            }
            let (t, h) = (pts[0], pts[pts.len() - 1]);
            let (dx, dy) = ((h.0 - t.0) as f64, (h.1 - t.1) as f64);
            let l = dx.hypot(dy).max(1.0);
            let (ux, uy) = (dx / l, dy / l);
            let (len, half) = (11.0 * S as f64, 4.5 * S as f64);
            let base = (h.0 as f64 - len * ux, h.1 as f64 - len * uy);
            let p = |x: f64, y: f64| (x.round() as i32, y.round() as i32);
            a.draw(&PathElement::new(vec![t, p(base.0, base.1)], st))
                .map_err(pe)?;
            a.draw(&Polygon::new(
                vec![
                    h,
                    p(base.0 - half * uy, base.1 + half * ux),
                    p(base.0 + half * uy, base.1 - half * ux),
                ],
                color.filled(),
            ))
            .map_err(pe)
        }
        _ => a.draw(&PathElement::new(pts, st)).map_err(pe),
    }
}

/// Draw a text with its top-left corner at `(x, y)` (absolute units).
fn text<DB: DrawingBackend>(
    a: &DrawingArea<DB, plotters::coord::Shift>,
    s: &str,
    size: f64,
    color: RGBColor,
    pos: Pos,
    (x, y): (f64, f64),
) -> Res<()>
where
    DB::ErrorType: 'static,
{
    let b = a.get_base_pixel();
    a.draw(&Text::new(
        s.to_string(),
        (x.round() as i32 - b.0, y.round() as i32 - b.1),
        font(size).color(&color).pos(pos),
    ))
    .map_err(pe)
}

fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    p: &Panel,
) -> Res<PanelLayout>
where
    DB::ErrorType: 'static,
{
    let whole = {
        let (xs, ys) = area.get_pixel_range();
        Rect {
            x0: xs.start as f64,
            y0: ys.start as f64,
            x1: xs.end as f64,
            y1: ys.end as f64,
        }
    };
    // the panel title, then the chart below it
    let (w, _) = area.dim_in_pixel();
    text(
        area,
        &p.title,
        20.0,
        BLACK,
        Pos::new(HPos::Center, VPos::Top),
        (whole.x0 + 0.5 * w as f64, whole.y0 + u(8.0) as f64),
    )?;
    let (_, area) = area.split_vertically(u(36.0));
    let (xr0, yr0) = data_ranges(p);
    let legend_wh = legend_size(p);
    // legend inside the plot area if there is an empty place, else beside it (narrow legends)
    // or below it (wide ones); the plot area shrinks to make room
    let (mut right, mut bottom) = (u(12.0), u(12.0));
    let mut inside = true;
    let (mut chart, px, marks, legend) = loop {
        let mut chart = build(&area, right, bottom, xr0, yr0)?;
        if p.equal_aspect {
            let r = plot_rect(&chart);
            let (xr, yr) = equal_aspect(xr0, yr0, r.x1 - r.x0, r.y1 - r.y0);
            chart = build(&area, right, bottom, xr, yr)?;
        }
        let plot = plot_rect(&chart);
        let (px, marks) = to_pixels(&chart, p);
        let Some((lw, lh)) = legend_wh else {
            break (chart, px, marks, None);
        };
        if inside {
            if let Some(r) = free_spot(&plot, lw, lh, &marks) {
                break (chart, px, marks, Some(r));
            }
            inside = false;
            if lw < 0.3 * (whole.x1 - whole.x0) {
                right += (lw + u(14.0) as f64).ceil() as i32;
            } else {
                bottom += (lh + u(10.0) as f64).ceil() as i32;
            }
            continue;
        }
        let r = if right > u(12.0) {
            Rect::at(plot.x1 + u(12.0) as f64, plot.y0, lw, lh)
        } else {
            // under the x-axis label area
            let y = plot.y1 + u(45.0) as f64 + u(4.0) as f64;
            Rect::at(0.5 * (plot.x0 + plot.x1 - lw), y, lw, lh)
        };
        break (chart, px, marks, Some(r));
    };
    let plot = plot_rect(&chart);
    chart
        .configure_mesh()
        .x_desc(p.xlabel.as_str())
        .y_desc(p.ylabel.as_str())
        .axis_desc_style(font(16.0))
        .label_style(font(13.0))
        .light_line_style(RGBColor(238, 238, 238).stroke_width(u(0.5) as u32))
        .bold_line_style(RGBColor(205, 205, 205).stroke_width(u(1.0) as u32))
        .axis_style(BLACK.stroke_width(u(1.0) as u32))
        .set_all_tick_mark_size(u(5.0))
        .draw()
        .map_err(pe)?;
    // series in pixel space, on the plot area (clipped to it)
    let pa = chart.plotting_area().strip_coord_spec();
    let base = pa.get_base_pixel();
    let rel = |v: &[(f64, f64)]| -> Vec<(i32, i32)> {
        v.iter()
            .map(|&(x, y)| (x as i32 - base.0, y as i32 - base.1))
            .collect()
    };
    // cells first: they fill areas that other series may mark
    let mut cells = 0;
    for m in &marks {
        if let Mark::Area(r) = m {
            let col = cell_color(p, cells);
            cells += 1;
            pa.draw(&Rectangle::new(
                [
                    (r.x0 as i32 - base.0, r.y0 as i32 - base.1),
                    (r.x1 as i32 - base.0, r.y1 as i32 - base.1),
                ],
                col.filled(),
            ))
            .map_err(pe)?;
        }
    }
    for (s, v) in p.series.iter().zip(&px) {
        if matches!(s.kind, Kind::Cell(..)) {
            continue;
        }
        if s.kind.is_line() {
            line(&pa, s.kind, s.color, rel(v))?;
        } else {
            for q in rel(v) {
                marker(&pa, s.kind, s.color, q)?;
            }
        }
    }
    let mut taken: Vec<Rect> = Vec::new();
    if let Some(r) = legend {
        let ab = area.get_base_pixel();
        let rr = |x: f64, y: f64| (x.round() as i32 - ab.0, y.round() as i32 - ab.1);
        area.draw(&Rectangle::new(
            [rr(r.x0, r.y0), rr(r.x1, r.y1)],
            WHITE.mix(0.9).filled(),
        ))
        .map_err(pe)?;
        area.draw(&Rectangle::new(
            [rr(r.x0, r.y0), rr(r.x1, r.y1)],
            RGBColor(170, 170, 170).stroke_width(u(1.0) as u32),
        ))
        .map_err(pe)?;
        let pad = 7.0 * S as f64;
        for (i, s) in legend_entries(p).iter().enumerate() {
            let yc = r.y0 + pad + (i as f64 + 0.5) * ROW_PX * S as f64 - 2.0 * S as f64;
            let x = r.x0 + pad;
            if s.kind.is_line() {
                let ends = vec![rr(x, yc), rr(x + GLYPH_PX * S as f64, yc)];
                line(&area, s.kind, s.color, ends)?;
            } else {
                marker(
                    &area,
                    s.kind,
                    s.color,
                    rr(x + 0.5 * GLYPH_PX * S as f64, yc),
                )?;
            }
            text(
                &area,
                &s.name,
                LEGEND_FONT,
                BLACK,
                Pos::new(HPos::Left, VPos::Center),
                (x + (GLYPH_PX + 6.0) * S as f64, yc),
            )?;
        }
        taken.push(r);
    }
    let mut tags = Vec::new();
    let mut untagged = Vec::new();
    for s in &p.series {
        let Some(t) = &s.tag else { continue };
        let anchors: Vec<(f64, f64)> = t
            .anchors
            .iter()
            .filter(|(x, y)| x.is_finite() && y.is_finite())
            .map(|q| {
                let b = chart.backend_coord(q);
                (b.0 as f64, b.1 as f64)
            })
            .collect();
        match place_tag(&t.text, &anchors, &plot, &marks, &taken) {
            Some(r) => {
                text(
                    &area,
                    &t.text,
                    TAG_FONT,
                    RGBColor(40, 40, 40),
                    Pos::new(HPos::Left, VPos::Top),
                    (r.x0, r.y0),
                )?;
                taken.push(r);
                tags.push((t.text.clone(), r));
            }
            None => untagged.push(t.text.clone()),
        }
    }
    Ok(PanelLayout {
        area: whole,
        plot,
        marks,
        legend,
        tags,
        untagged,
    })
}

/// The colour of the `i`-th cell of a panel (cells are marked in series order).
fn cell_color(p: &Panel, mut i: usize) -> RGBColor {
    for s in p.series.iter().filter(|s| matches!(s.kind, Kind::Cell(..))) {
        let n = s
            .pts
            .iter()
            .filter(|q| q.0.is_finite() && q.1.is_finite())
            .count();
        if i < n {
            return s.color;
        }
        i -= n;
    }
    BLACK
}

/// Draw a figure into an SVG string; returns it with the layout of each panel.
pub(crate) fn render(fig: &Fig) -> Res<(String, Vec<PanelLayout>)> {
    let (w, h) = (fig.w * fig.panels.len() as u32, fig.h + 40);
    let mut svg = String::new();
    let mut layouts = Vec::new();
    {
        let root =
            SVGBackend::with_string(&mut svg, (w * S as u32, h * S as u32)).into_drawing_area();
        root.fill(&WHITE).map_err(pe)?;
        text(
            &root,
            &fig.caption,
            22.0,
            BLACK,
            Pos::new(HPos::Center, VPos::Top),
            (0.5 * (w * S as u32) as f64, u(8.0) as f64),
        )?;
        let (_, body) = root.split_vertically(u(40.0));
        for (a, p) in body
            .split_evenly((1, fig.panels.len()))
            .iter()
            .zip(&fig.panels)
        {
            layouts.push(draw_panel(a, p)?);
        }
        root.present().map_err(pe)?;
    }
    // show the drawing at 1/S of its internal size (the viewBox keeps the fine coordinates)
    let inner = format!("width=\"{}\" height=\"{}\"", w * S as u32, h * S as u32);
    let svg = svg.replacen(&inner, &format!("width=\"{w}\" height=\"{h}\""), 1);
    Ok((svg, layouts))
}

/// Write a figure's SVG and the CSV of its data (both atomically).
fn write_fig(dir: &Path, fig: &Fig) -> Res<()> {
    let (svg, _) = render(fig)?;
    let mut f = AtomicFile::create(&dir.join(format!("{}.svg", fig.name)))?;
    std::io::Write::write_all(&mut f, svg.as_bytes())?;
    f.commit()?;
    let mut c = AtomicFile::create(&dir.join(format!("{}.csv", fig.name)))?;
    csv_line(&mut c, &["panel", "series", "x", "y"])?;
    for (i, p) in fig.panels.iter().enumerate() {
        for s in &p.series {
            for &(x, y) in &s.pts {
                csv_line(
                    &mut c,
                    &[(i + 1).to_string(), s.name.clone(), num(x), num(y)],
                )?;
            }
        }
    }
    c.commit()
}

// ---------------------------------------------------------------------------------------------
// The figures

fn lin(a: f64, b: f64, n: usize) -> impl Iterator<Item = f64> {
    (0..n).map(move |i| {
        if i + 1 == n {
            b
        } else {
            a + (b - a) * i as f64 / (n - 1) as f64
        }
    })
}

struct Ctx {
    cfg: SolverConfig,
    rod: Rod,
    method: MethodArg,
    tol: f64,
}

impl Ctx {
    fn solve(&self, branch: Branch, alpha: f64, target: Target) -> Option<vibrissa::Shape> {
        let b = match branch {
            Branch::Convex => BranchChoice::Convex,
            Branch::OneFlex => BranchChoice::Flex,
        };
        vibrissa::solve(&self.rod, alpha, target, &b, &self.cfg).ok()
    }

    fn scan(&self, eta: f64, d_max: f64, points: usize, shapes: usize) -> Res<ScanOut> {
        let scene = Scene {
            eta,
            ..Scene::default()
        };
        run_scan(
            &scene,
            &ScanSpec {
                method: self.method,
                tol: self.tol,
                d_max,
                points,
                mu0: None,
                shape_points: shapes,
            },
        )
    }
}

/// `-k pi/40` as a reduced fraction of pi: "−π/4", "−9π/40", "0".
fn pi_over_40(k: i32) -> String {
    if k == 0 {
        return "0".into();
    }
    let gcd = |mut a: i32, mut b: i32| {
        while b != 0 {
            (a, b) = (b, a % b);
        }
        a
    };
    let g = gcd(k.abs(), 40);
    let (n, d) = (k.abs() / g, 40 / g);
    let sign = if k < 0 { "−" } else { "" };
    if n == 1 {
        format!("{sign}π/{d}")
    } else {
        format!("{sign}{n}π/{d}")
    }
}

fn fig2(cx: &Ctx) -> Res<Fig> {
    let mut p = panel(
        "Force f vs tip slope phi1; curves labelled by alpha = -pi/4 (pi/40) 0",
        "tip slope phi1 (rad)",
        "force f (EI/L^2)",
    );
    let mut num_c = Vec::new();
    let mut num_f = Vec::new();
    for j in 0..=10 {
        let alpha = -FRAC_PI_4 + j as f64 * PI / 40.0;
        let top = (FRAC_PI_2 + 2.0 * alpha).max(0.0);
        let top_c = if j == 10 { top - 1e-6 } else { top };
        // denser near the turning point, where the curves turn fast
        let qs = || lin(0.0, 1.0, 120).map(|t| top_c * (1.0 - (1.0 - t) * (1.0 - t)));
        let conv: Vec<(f64, f64)> = qs()
            .filter_map(|q| {
                Elastica::new(Branch::Convex, alpha, q)
                    .ok()
                    .map(|e| (q, e.f))
            })
            .collect();
        let flex: Vec<(f64, f64)> = qs()
            .filter_map(|q| {
                Elastica::new(Branch::OneFlex, alpha, q)
                    .ok()
                    .map(|e| (q, e.f))
            })
            .collect();
        // the label goes next to the turning point (where the two branches meet), else along
        // the one-flex curve, else along the convex one
        let mut anchors: Vec<(f64, f64)> = conv.last().copied().into_iter().collect();
        anchors.extend(flex.iter().rev().step_by(4));
        anchors.extend(conv.iter().rev().step_by(4));
        let first = j == 0;
        let text = match j {
            0 | 10 => format!("α = {}", pi_over_40(j - 10)),
            _ => pi_over_40(j - 10),
        };
        let mut s1 = series("convex (2.8), closed form", Kind::Line, BLUE_, conv);
        let mut s2 = series("one flex (2.15), closed form", Kind::Dashed, ORANGE_, flex);
        if j == 10 {
            // alpha = 0: the two branches do not meet; label each
            s2.tag = Some(Tag {
                text: text.clone(),
                anchors: s2.pts.iter().rev().step_by(4).copied().collect(),
            });
        }
        s1.tag = Some(Tag { text, anchors });
        p.series.push(if first { s1 } else { unlabeled(s1) });
        p.series.push(if first { s2 } else { unlabeled(s2) });
        for q in lin(0.0, top, 6).take(5) {
            if let Some(s) = cx.solve(Branch::Convex, alpha, Target::Phi1(q)) {
                num_c.push((s.phi1, s.f));
            }
            if let Some(s) = cx.solve(Branch::OneFlex, alpha, Target::Phi1(q)) {
                num_f.push((s.phi1, s.f));
            }
        }
    }
    let locus: Vec<(f64, f64)> = lin(-FRAC_PI_4, -1e-6, 100)
        .filter_map(|a| elastica::turning_point(a).ok())
        .collect();
    p.series.push(series(
        "turning points (pi/2 + 2 alpha, 4 K^2(sin(alpha/2)))",
        Kind::DashDot,
        GREEN_,
        locus,
    ));
    p.series
        .push(series("numerical, convex", Kind::Points, RED_, num_c));
    p.series
        .push(series("numerical, one flex", Kind::Points, GREY_, num_f));
    Ok(Fig {
        name: "fig02".into(),
        caption: "Fig. 2: (phi1, f) families of the clamped elastica".into(),
        panels: vec![p],
        w: 860,
        h: 640,
    })
}

fn shape_xy(s: &vibrissa::Shape, n: usize) -> Vec<(f64, f64)> {
    s.samples(n).iter().map(|p| (p.x, p.y)).collect()
}

fn elastica_xy(e: &Elastica, n: usize) -> Vec<(f64, f64)> {
    e.shape(n)
        .map(|v| v.iter().map(|p| (p.x, p.y)).collect())
        .unwrap_or_default()
}

/// Tip force as a segment from the tip, length f/scale, direction (sin a, -cos a).
fn force_seg(x1: f64, y1: f64, f: f64, alpha: f64, scale: f64) -> Vec<(f64, f64)> {
    vec![
        (x1, y1),
        (x1 + f / scale * alpha.sin(), y1 - f / scale * alpha.cos()),
    ]
}

fn fig3(cx: &Ctx) -> Res<Fig> {
    let alpha = -PI / 8.0;
    let phi1 = 0.5 * (FRAC_PI_2 + 2.0 * alpha);
    let mut p = panel("alpha = -pi/8, phi1 = (pi/2 + 2 alpha)/2", "x (L)", "y (L)");
    p.equal_aspect = true;
    for (br, name, color, cf_kind, cf_color) in [
        (Branch::Convex, "convex", BLUE_, Kind::Ring, NAVY_),
        (Branch::OneFlex, "one flex", ORANGE_, Kind::Triangle, BROWN_),
    ] {
        let e = Elastica::new(br, alpha, phi1)?;
        if let Some(s) = cx.solve(br, alpha, Target::Phi1(phi1)) {
            p.series.push(series(
                &format!("{name}, numerical (f = {:.2})", s.f),
                Kind::Line,
                color,
                shape_xy(&s, 120),
            ));
        }
        p.series.push(series(
            &format!("{name}, closed form"),
            cf_kind,
            cf_color,
            elastica_xy(&e, 21),
        ));
        p.series.push(series(
            &format!("{name}: tip force on the rod, f/40"),
            Kind::Arrow,
            color,
            force_seg(e.x1, e.y1, e.f, alpha, 40.0),
        ));
        if let Some(Ok(pt)) = e.s_b.map(|sb| e.point_at(sb)) {
            p.series
                .push(series("flex point", Kind::Cross, RED_, vec![(pt.x, pt.y)]));
        }
    }
    Ok(Fig {
        name: "fig03".into(),
        caption: "Fig. 3: elastic lines with zero and one flex point".into(),
        panels: vec![p],
        w: 720,
        h: 720,
    })
}

fn fig4(cx: &Ctx) -> Res<Fig> {
    let (_, eta_low) = elastica::lower_limit();
    let mut cf_phi = Vec::new();
    let mut cf_f = Vec::new();
    for eta in lin(eta_low + 1e-9, 1.0 - 1e-6, 120) {
        if let Ok(e) = elastica::solve_eta(Branch::Convex, 0.0, eta) {
            cf_phi.push((eta, e.phi1));
            cf_f.push((eta, e.f));
        }
    }
    let mut n_phi = Vec::new();
    let mut n_f = Vec::new();
    for eta in lin(0.47, 0.97, 11) {
        if let Some(s) = cx.solve(Branch::Convex, 0.0, Target::Eta(eta)) {
            n_phi.push((eta, s.phi1));
            n_f.push((eta, s.f));
        }
    }
    let mut a = panel(
        "tip slope phi1_eta",
        "surface height eta (L)",
        "phi1_eta (rad)",
    );
    a.series
        .push(series("closed form", Kind::Line, BLUE_, cf_phi));
    a.series
        .push(series("numerical", Kind::Points, RED_, n_phi));
    let mut b = panel("force f_eta", "surface height eta (L)", "f_eta (EI/L^2)");
    b.series
        .push(series("closed form", Kind::Line, BLUE_, cf_f));
    b.series.push(series("numerical", Kind::Points, RED_, n_f));
    Ok(Fig {
        name: "fig04".into(),
        caption: "Fig. 4: start of the scan (vertical force, alpha = 0) vs eta".into(),
        panels: vec![a, b],
        w: 560,
        h: 460,
    })
}

fn fig5(cx: &Ctx) -> Res<Fig> {
    let mut p = panel("vertical tip force, tip at height eta", "x (L)", "y (L)");
    p.equal_aspect = true;
    for (eta, color) in [(0.6, BLUE_), (0.75, ORANGE_)] {
        let e = elastica::solve_eta(Branch::Convex, 0.0, eta)?;
        if let Some(s) = cx.solve(Branch::Convex, 0.0, Target::Eta(eta)) {
            p.series.push(series(
                &format!("eta = {eta}, numerical (f = {:.3})", s.f),
                Kind::Line,
                color,
                shape_xy(&s, 120),
            ));
        }
        p.series.push(unlabeled(series(
            "closed form",
            Kind::Ring,
            NAVY_,
            elastica_xy(&e, 21),
        )));
        p.series.push(series(
            &format!("surface y = {eta}"),
            Kind::Dashed,
            color,
            vec![(0.3, eta), (0.85, eta)],
        ));
    }
    if let Some(s) = p.series.iter_mut().find(|s| s.kind == Kind::Ring) {
        s.legend = true;
        s.name = "closed form".into();
    }
    Ok(Fig {
        name: "fig05".into(),
        caption: "Fig. 5: elastic lines at the start of the scan".into(),
        panels: vec![p],
        w: 620,
        h: 720,
    })
}

/// The flex point at arc length `sf` on a sampled shape (linear in s between samples).
fn flex_xy(sh: &[ShapeRow], sf: f64) -> Option<(f64, f64)> {
    let k = sh.windows(2).position(|w| w[0].s <= sf && sf <= w[1].s)?;
    let (a, b) = (&sh[k], &sh[k + 1]);
    let t = if b.s > a.s {
        (sf - a.s) / (b.s - a.s)
    } else {
        0.0
    };
    Some((a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)))
}

/// Figures 6-8 (eta = 0.75) or 9-11 (eta = 0.6), those of them that `want`.
fn scan_figs(cx: &Ctx, eta: f64, first: usize, want: &dyn Fn(usize) -> bool) -> Res<Vec<Fig>> {
    let mut figs = Vec::new();
    // the low surface's scan ends near d = 0.094: zoom in
    let d_max = if eta < 0.65 { 0.1 } else { 0.5 };
    let tag = format!("eta = {eta}");
    let c = elastica::ClosedFormScan::new(eta)?;
    if want(first) || want(first + 2) {
        let dense = cx.scan(eta, d_max, 101, 0)?;
        // closed-form curve in the curve parameter (also beyond the fold in phi1)
        let tmax = c.curve_end();
        let last_d = dense.pts.last().map_or(0.0, |p| p.d);
        let cf: Vec<elastica::ScanPoint> = lin(0.0, tmax, (tmax * 150.0) as usize + 1)
            .filter_map(|t| c.curve_at(t).ok())
            .filter(|p| p.d <= last_d + 1e-9)
            .collect();
        let numerical = format!("numerical scan ({})", cx.method.name());
        if want(first) {
            fig_sequence(&mut figs, &c, &dense, &cf, &numerical, first, &tag);
        }
        if want(first + 2) {
            fig_mu(&mut figs, &dense, &cf, &numerical, first + 2, &tag);
        }
    }
    if want(first + 1) {
        figs.push(fig_lines(cx, &c, eta, d_max, first + 1, &tag)?);
    }
    figs.sort_by(|a, b| a.name.cmp(&b.name));
    Ok(figs)
}

/// (phi1, f) sequence with the end of phase 0 and the fold in phi1 (Figs. 6, 9).
fn fig_sequence(
    figs: &mut Vec<Fig>,
    c: &elastica::ClosedFormScan,
    dense: &ScanOut,
    cf: &[elastica::ScanPoint],
    numerical: &str,
    n: usize,
    tag: &str,
) {
    let mut a = panel(
        &format!("(phi1, f) sequence, {tag}"),
        "tip slope phi1 (rad)",
        "force f (EI/L^2)",
    );
    // numerical rings under the closed form, so both stay visible
    a.series.push(series(
        numerical,
        Kind::Ring,
        RED_,
        dense.pts.iter().map(|p| (p.phi1, p.f)).collect(),
    ));
    a.series.push(series(
        "closed form (Remark 3.1)",
        Kind::Thin,
        BLUE_,
        cf.iter().map(|p| (p.phi1, p.f)).collect(),
    ));
    let t = &c.turning;
    let end_name = if c.phase0_end == Phase0End::TurningPoint {
        format!(
            "convex -> one flex (Fig. 2 turning point, alpha = {:.3})",
            t.alpha
        )
    } else {
        "end of phase 0: tip horizontal, phi1 = 0".to_string()
    };
    a.series
        .push(series(&end_name, Kind::Cross, GREEN_, vec![(t.phi1, t.f)]));
    if let Some(fold) = &c.fold {
        a.series.push(series(
            &format!("fold: smallest phi1 = {:.4} (closed form)", fold.phi1),
            Kind::Square,
            PURPLE_,
            vec![(fold.phi1, fold.f)],
        ));
    }
    figs.push(Fig {
        name: format!("fig{n:02}"),
        caption: format!("Fig. {n}: sequence (phi1_i, f_i) for {tag}"),
        panels: vec![a],
        w: 760,
        h: 560,
    });
}

/// mu vs d with the largest mu of the scan (Figs. 8, 11).
fn fig_mu(
    figs: &mut Vec<Fig>,
    dense: &ScanOut,
    cf: &[elastica::ScanPoint],
    numerical: &str,
    n: usize,
    tag: &str,
) {
    let mut m = panel(
        &format!("friction ratio vs foot displacement, {tag}"),
        "foot displacement d (L)",
        "friction ratio mu = tan(-alpha)",
    );
    m.series.push(series(
        numerical,
        Kind::Ring,
        RED_,
        dense.pts.iter().map(|p| (p.d, p.mu)).collect(),
    ));
    m.series.push(series(
        "closed form",
        Kind::Thin,
        BLUE_,
        cf.iter().map(|p| (p.d, p.mu)).collect(),
    ));
    // a maximum inside the scan, or only the largest value at its end (mu still rising there)
    let last_d = dense.pts.last().map_or(0.0, |p| p.d);
    let interior = dense.d_at_mu_max < last_d - 1e-9;
    let name = if interior {
        format!(
            "mu_max = {:.4} at d = {:.4} (measurable range ends)",
            dense.mu_max, dense.d_at_mu_max
        )
    } else {
        format!(
            "scan end ({}): mu = {:.4} at d = {:.4}, still rising",
            dense.stop.reason, dense.mu_max, dense.d_at_mu_max
        )
    };
    m.series.push(series(
        &name,
        Kind::Cross,
        GREEN_,
        vec![(dense.d_at_mu_max, dense.mu_max)],
    ));
    figs.push(Fig {
        name: format!("fig{n:02}"),
        caption: format!(
            "Fig. {n}: mu vs d, {tag} (scan stops: {})",
            dense.stop.reason
        ),
        panels: vec![m],
        w: 760,
        h: 560,
    });
}

/// Elastic lines in the lab frame (tip fixed, foot at x = d), flex points as dots (Figs. 7, 10).
fn fig_lines(
    cx: &Ctx,
    c: &elastica::ClosedFormScan,
    eta: f64,
    d_max: f64,
    n: usize,
    tag: &str,
) -> Res<Fig> {
    let shapes = cx.scan(eta, d_max, 11, 80)?;
    let mut b = panel(
        &format!("elastic lines while the foot moves, {tag}"),
        "x (L), lab frame",
        "y (L)",
    );
    b.equal_aspect = true;
    let mut flex = Vec::new();
    let k = shapes.pts.len();
    for (i, (p, sh)) in shapes.pts.iter().zip(&shapes.shapes).enumerate() {
        let g = 40 + (160 * i / k.max(1)) as u8;
        let col = RGBColor(g / 3, g / 2 + 40, 200);
        let pts: Vec<(f64, f64)> = sh.iter().map(|q| (q.x + p.d, q.y)).collect();
        let name = format!("d = {:.3}, mu = {:.3}", p.d, p.mu);
        b.series.push(if i == 0 || i + 1 == k {
            series(&name, Kind::Line, col, pts)
        } else {
            unlabeled(series(&name, Kind::Line, col, pts))
        });
        if let Some((x, y)) = p.s_flex.and_then(|sf| flex_xy(sh, sf)) {
            flex.push((x + p.d, y));
        }
    }
    let x1s = c.start.x1;
    b.series.push(series(
        &format!("surface y = {eta}"),
        Kind::Dashed,
        GREY_,
        vec![(x1s - 0.6, eta), (x1s + 0.1, eta)],
    ));
    b.series
        .push(series("flex points", Kind::Points, RED_, flex));
    Ok(Fig {
        name: format!("fig{n:02}"),
        caption: format!("Fig. {n}: elastic lines, {tag}"),
        panels: vec![b],
        w: 720,
        h: 660,
    })
}

/// The figures `want` selects, in order.
fn figures(cx: &Ctx, want: &dyn Fn(usize) -> bool) -> Res<Vec<Fig>> {
    let mut figs = Vec::new();
    if want(2) {
        figs.push(fig2(cx)?);
    }
    if want(3) {
        figs.push(fig3(cx)?);
    }
    if want(4) {
        figs.push(fig4(cx)?);
    }
    if want(5) {
        figs.push(fig5(cx)?);
    }
    if (6..=8).any(want) {
        figs.extend(scan_figs(cx, 0.75, 6, want)?);
    }
    if (9..=11).any(want) {
        figs.extend(scan_figs(cx, 0.6, 9, want)?);
    }
    Ok(figs)
}

fn context(method: MethodArg, tol: f64) -> Res<Ctx> {
    Ok(Ctx {
        cfg: numeric::config(method, tol),
        rod: Rod::uniform(),
        method,
        tol,
    })
}

/// Run `vibrissa figures`.
pub fn run(a: &FiguresArgs) -> Res<()> {
    let only: Vec<usize> = match &a.only {
        Some(s) => s
            .split(',')
            .map(|t| {
                t.trim()
                    .parse::<usize>()
                    .ok()
                    .filter(|n| (2..=11).contains(n))
                    .ok_or_else(|| {
                        usage(format!(
                            "--only: '{}' is not a figure number 2-11",
                            t.trim()
                        ))
                    })
            })
            .collect::<Res<_>>()?,
        None => (2..=11).collect(),
    };
    std::fs::create_dir_all(&a.out_dir)
        .map_err(|e| solve_fail(format!("cannot create {}: {e}", a.out_dir.display())))?;
    let cx = context(a.method, a.tol)?;
    for fig in figures(&cx, &|n| only.contains(&n))? {
        write_fig(&a.out_dir, &fig)?;
    }
    writeln!(
        std::io::stdout(),
        "figures written to {}",
        a.out_dir.display()
    )?;
    Ok(())
}

/// The layout check of the tests (figures and `plot`): legends and labels never cover data.
#[cfg(test)]
pub(crate) mod layout_check {
    use super::*;

    /// Whether a drawn mark reaches into the rectangle, checked independently of the layout code:
    /// every segment sampled every 1/4 output pixel, markers as disks of their radius.
    pub(crate) fn covers(r: &Rect, m: &Mark) -> bool {
        match m {
            Mark::Area(a) => a.overlaps(r),
            Mark::Dot(c, rad) => {
                let dx = (r.x0 - c.0).max(c.0 - r.x1).max(0.0);
                let dy = (r.y0 - c.1).max(c.1 - r.y1).max(0.0);
                dx * dx + dy * dy <= rad * rad
            }
            Mark::Path(p) => {
                let inside =
                    |q: (f64, f64)| r.x0 <= q.0 && q.0 <= r.x1 && r.y0 <= q.1 && q.1 <= r.y1;
                p.iter().any(|&q| inside(q))
                    || p.windows(2).any(|w| {
                        let l = (w[1].0 - w[0].0).hypot(w[1].1 - w[0].1);
                        let n = (l / (0.25 * S as f64)).ceil().max(1.0) as usize;
                        (0..=n).any(|i| {
                            let t = i as f64 / n as f64;
                            inside((
                                w[0].0 + t * (w[1].0 - w[0].0),
                                w[0].1 + t * (w[1].1 - w[0].1),
                            ))
                        })
                    })
            }
        }
    }

    /// Legends and labels of one rendered panel: present when the panel has legend entries or
    /// tags, inside the panel, and touching no drawn data (nor each other).
    pub(crate) fn check_panel(fig: &str, p: &Panel, l: &PanelLayout) {
        let drawn: usize = l
            .marks
            .iter()
            .map(|m| match m {
                Mark::Path(v) => v.len(),
                Mark::Dot(..) | Mark::Area(..) => 1,
            })
            .sum();
        let finite: usize = p
            .series
            .iter()
            .map(|s| {
                s.pts
                    .iter()
                    .filter(|q| q.0.is_finite() && q.1.is_finite())
                    .count()
            })
            .sum();
        assert_eq!(drawn, finite, "{fig}: every data point is in the layout");
        let mut boxes: Vec<(String, Rect)> = l.tags.clone();
        match (legend_entries(p).is_empty(), l.legend) {
            (true, None) => {}
            (false, Some(r)) => boxes.push(("legend".into(), r)),
            (e, r) => panic!("{fig}: legend entries {} but legend {r:?}", !e),
        }
        assert!(
            l.untagged.is_empty(),
            "{fig}: no room for labels {:?}",
            l.untagged
        );
        let tags: usize = p.series.iter().filter(|s| s.tag.is_some()).count();
        assert_eq!(l.tags.len(), tags, "{fig}: every label placed");
        for (i, (name, r)) in boxes.iter().enumerate() {
            assert!(
                l.area.contains(r),
                "{fig}: {name} {r:?} outside the panel {:?}",
                l.area
            );
            for m in &l.marks {
                assert!(!covers(r, m), "{fig}: {name} {r:?} covers data {m:?}");
            }
            for (other, q) in &boxes[i + 1..] {
                assert!(!r.overlaps(q), "{fig}: {name} overlaps {other}");
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::layout_check::*;
    use super::*;

    #[test]
    fn legends_and_labels_never_cover_data() {
        let cx = context(MethodArg::Shooting, 1e-10).unwrap();
        let figs = figures(&cx, &|_| true).unwrap();
        let names: Vec<&str> = figs.iter().map(|f| f.name.as_str()).collect();
        assert_eq!(
            names,
            [
                "fig02", "fig03", "fig04", "fig05", "fig06", "fig07", "fig08", "fig09", "fig10",
                "fig11"
            ]
        );
        for fig in &figs {
            let (svg, layouts) = render(fig).unwrap();
            // shown at the output size, drawn S times finer
            let (w, h) = (fig.w * fig.panels.len() as u32, fig.h + 40);
            let head = format!(
                "<svg width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {} {}\"",
                w * S as u32,
                h * S as u32
            );
            assert!(svg.starts_with(&head), "{}: {}", fig.name, &svg[..100]);
            assert_eq!(layouts.len(), fig.panels.len());
            for (p, l) in fig.panels.iter().zip(&layouts) {
                check_panel(&fig.name, p, l);
            }
        }
        // Fig. 2 labels its 11 values of alpha (alpha = 0 twice: its branches do not meet)
        let (_, l2) = render(&figs[0]).unwrap();
        assert_eq!(l2[0].tags.len(), 12);
    }

    /// The check itself can fail: a box on a curve, on a marker, and a panel filled with data
    /// whose legend has to go outside the plot area.
    #[test]
    fn the_overlap_check_detects_overlaps() {
        let r = Rect::at(10.0, 10.0, 20.0, 10.0);
        // a segment crossing the box without a vertex inside it
        assert!(covers(&r, &Mark::Path(vec![(0.0, 15.0), (40.0, 16.0)])));
        assert!(!covers(&r, &Mark::Path(vec![(0.0, 25.0), (40.0, 26.0)])));
        assert!(covers(&r, &Mark::Dot((35.0, 15.0), 6.0)));
        assert!(!covers(&r, &Mark::Dot((35.0, 15.0), 4.0)));
        assert_eq!(
            clearance(&r, &[Mark::Path(vec![(0.0, 25.0), (40.0, 25.0)])]),
            5.0
        );
        // dots on a fine grid leave no free place inside: the legend goes beside the plot
        let mut p = panel("full", "x", "y");
        let grid: Vec<(f64, f64)> = (0..2500)
            .map(|i| ((i % 50) as f64, (i / 50) as f64))
            .collect();
        p.series.push(series("grid", Kind::Points, RED_, grid));
        p.series.push(series(
            "a line",
            Kind::Line,
            BLUE_,
            vec![(0.0, 0.0), (49.0, 49.0)],
        ));
        let fig = Fig {
            name: "full".into(),
            caption: "full".into(),
            panels: vec![p],
            w: 600,
            h: 400,
        };
        let (_, l) = render(&fig).unwrap();
        let legend = l[0].legend.unwrap();
        assert!(
            !l[0].plot.overlaps(&legend),
            "{legend:?} in {:?}",
            l[0].plot
        );
        check_panel("full", &fig.panels[0], &l[0]);
    }

    #[test]
    fn only_writes_the_figures_asked_for() {
        let cx = context(MethodArg::Shooting, 1e-10).unwrap();
        let names = |want: &dyn Fn(usize) -> bool| -> Vec<String> {
            figures(&cx, want)
                .unwrap()
                .into_iter()
                .map(|f| f.name)
                .collect()
        };
        assert_eq!(names(&|n| n == 6 || n == 8), ["fig06", "fig08"]);
        assert_eq!(names(&|n| n == 10), ["fig10"]);
    }

    #[test]
    fn alpha_labels() {
        assert_eq!(pi_over_40(-10), "−π/4");
        assert_eq!(pi_over_40(-9), "−9π/40");
        assert_eq!(pi_over_40(-8), "−π/5");
        assert_eq!(pi_over_40(-6), "−3π/20");
        assert_eq!(pi_over_40(0), "0");
    }
}
