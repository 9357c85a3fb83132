//! The chart toolkit of `vibrissa figures` and `vibrissa plot`: panels of series (lines,
//! markers, heat-map cells) drawn as SVG with plotters.
//!
//! Layout: plotters places every element on whole pixels, so the SVG is drawn at `S` times the
//! output size and scaled down by its `viewBox` (coordinates effectively on a 1/S pixel grid, no
//! jagged curves). Legends and curve labels are placed by this module, not by plotters: from the
//! pixel positions of every drawn series, in an empty region of the plot area (or to the right of
//! it when there is none), so that they never cover data. [`PanelLayout`] records those positions.

use crate::error::{solve_fail, Fail, Res};
use plotters::coord::types::RangedCoordf64;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// SVG user units per output pixel (the internal drawing resolution).
pub(crate) const S: i32 = 4;

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
    pub text: String,
    /// candidate data points to put the text next to, in order of preference
    pub anchors: Vec<(f64, f64)>,
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
    /// Instead of the grid: the panels in one column, each `w` wide and of these heights; their
    /// plot areas have the same horizontal extent and every panel after the first takes the
    /// first one's x range (aligned in x: legends that do not fit inside go below, never
    /// beside).
    pub stack: Option<Vec<u32>>,
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
    /// the x range of the plot area (data units)
    pub x_range: (f64, f64),
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

/// A chart laid out in a panel: the chart, its series in pixels, what they mark, and where the
/// legend goes (if the panel has one).
type Laid<'a, DB> = (Chart<'a, DB>, Vec<Vec<(f64, f64)>>, Vec<Mark>, Option<Rect>);

/// Lay out the chart below the title: the legend inside the plot area if there is an empty
/// place, else beside it (narrow legends) or below it (wide ones); the plot area shrinks to make
/// room.
fn lay_out<'a, DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    p: &Panel,
    whole: &Rect,
    (x_fixed, keep_width): (Option<(f64, f64)>, bool),
) -> Res<Laid<'a, DB>>
where
    DB::ErrorType: 'static,
{
    let (mut xr0, yr0) = data_ranges(p);
    if let Some(x) = x_fixed {
        xr0 = x;
    }
    let legend_wh = legend_size(p);
    // legend inside the plot area if there is an empty place, else beside it (narrow legends)
    // or below it (wide ones); the plot area shrinks to make room
    let (mut right, mut bottom) = (u(12.0), u(12.0));
    let mut inside = true;
    let laid = loop {
        let mut chart = build(area, right, bottom, xr0, yr0)?;
        if p.equal_aspect {
            let r = plot_rect(&chart);
            let (xr, yr) = equal_aspect(xr0, yr0, r.x1 - r.x0, r.y1 - r.y0);
            chart = build(area, right, bottom, xr, yr)?;
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
            // (a panel aligned with another keeps its width: its legend goes below)
            if !keep_width && lw < 0.3 * (whole.x1 - whole.x0) {
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
    Ok(laid)
}

/// Draw the series on the plot area (clipped to it): cells first, as they fill areas that other
/// series may mark.
fn draw_series<DB: DrawingBackend>(
    chart: &Chart<'_, DB>,
    p: &Panel,
    px: &[Vec<(f64, f64)>],
    marks: &[Mark],
) -> Res<()>
where
    DB::ErrorType: 'static,
{
    let pa = chart.plotting_area().strip_coord_spec();
    let base = pa.get_base_pixel();
    let rel = |v: &[(f64, f64)]| -> Vec<(i32, i32)> {
        v.iter()
            .map(|&(x, y)| (x as i32 - base.0, y as i32 - base.1))
            .collect()
    };
    let mut cells = 0;
    for m in marks {
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
    for (s, v) in p.series.iter().zip(px) {
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
    Ok(())
}

/// Draw the legend in its box `r` of the panel's area.
fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    p: &Panel,
    r: &Rect,
) -> Res<()>
where
    DB::ErrorType: 'static,
{
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
            line(area, s.kind, s.color, ends)?;
        } else {
            marker(area, s.kind, s.color, rr(x + 0.5 * GLYPH_PX * S as f64, yc))?;
        }
        text(
            area,
            &s.name,
            LEGEND_FONT,
            BLACK,
            Pos::new(HPos::Left, VPos::Center),
            (x + (GLYPH_PX + 6.0) * S as f64, yc),
        )?;
    }
    Ok(())
}

/// The tags placed (text and box) and the texts that found no place.
type Tags = (Vec<(String, Rect)>, Vec<String>);

/// Place and draw the series' tags where they cover neither data nor what is `taken`; returns
/// the placed tags and the texts that found no place.
fn draw_tags<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    (chart, plot): (&Chart<'_, DB>, &Rect),
    p: &Panel,
    marks: &[Mark],
    taken: &mut Vec<Rect>,
) -> Res<Tags>
where
    DB::ErrorType: 'static,
{
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
        match place_tag(&t.text, &anchors, plot, marks, taken) {
            Some(r) => {
                text(
                    area,
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
    Ok((tags, untagged))
}

fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    p: &Panel,
    aligned: (Option<(f64, f64)>, bool),
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
    let (mut chart, px, marks, legend) = lay_out(&area, p, &whole, aligned)?;
    let plot = plot_rect(&chart);
    let x_range = {
        let r = chart.x_range();
        (r.start, r.end)
    };
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
    draw_series(&chart, p, &px, &marks)?;
    let mut taken: Vec<Rect> = Vec::new();
    if let Some(r) = legend {
        draw_legend(&area, p, &r)?;
        taken.push(r);
    }
    let (tags, untagged) = draw_tags(&area, (&chart, &plot), p, &marks, &mut taken)?;
    Ok(PanelLayout {
        area: whole,
        plot,
        marks,
        legend,
        tags,
        untagged,
        x_range,
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

/// Most panels side by side: more go on further rows (issue 33: a drag's five panels in one row
/// made a picture 2600 px wide and 480 high).
pub(crate) const PANELS_PER_ROW: usize = 3;

/// The rows and columns of `n` panels.
pub(crate) fn panel_grid(n: usize) -> (usize, usize) {
    let cols = n.clamp(1, PANELS_PER_ROW);
    (n.div_ceil(cols).max(1), cols)
}

/// The size of a figure's picture (output pixels): its panels on [`panel_grid`], the caption
/// above.
pub(crate) fn picture_size(fig: &Fig) -> (u32, u32) {
    if let Some(heights) = &fig.stack {
        return (fig.w, heights.iter().sum::<u32>() + 40);
    }
    let (rows, cols) = panel_grid(fig.panels.len());
    (fig.w * cols as u32, fig.h * rows as u32 + 40)
}

/// Draw a figure into an SVG string; returns it with the layout of each panel.
pub(crate) fn render(fig: &Fig) -> Res<(String, Vec<PanelLayout>)> {
    let (w, h) = picture_size(fig);
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
        match &fig.stack {
            Some(heights) => {
                // one column; the panels after the first in the first one's x range
                let mut edge = 0;
                let breaks: Vec<i32> = heights
                    .iter()
                    .map(|h| {
                        edge += *h as i32 * S;
                        edge
                    })
                    .collect();
                let areas = body.split_by_breakpoints(
                    Vec::<i32>::new(),
                    &breaks[..breaks.len().saturating_sub(1)],
                );
                let mut x_fixed = None;
                for (a, p) in areas.iter().zip(&fig.panels) {
                    let l = draw_panel(a, p, (x_fixed, true))?;
                    x_fixed = x_fixed.or(Some(l.x_range));
                    layouts.push(l);
                }
            }
            None => {
                for (a, p) in body
                    .split_evenly(panel_grid(fig.panels.len()))
                    .iter()
                    .zip(&fig.panels)
                {
                    layouts.push(draw_panel(a, p, (None, false))?);
                }
            }
        }
        root.present().map_err(pe)?;
    }
    // show the drawing at 1/S of its internal size (the viewBox keeps the fine coordinates)
    let inner = format!("width=\"{}\" height=\"{}\"", w * S as u32, h * S as u32);
    let svg = svg.replacen(&inner, &format!("width=\"{w}\" height=\"{h}\""), 1);
    Ok((svg, layouts))
}

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
            stack: None,
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
}
