//! `vibrissa figures`: the paper's Figures 2-11 as SVG (plotters) with the CSV behind each.
//! Numerical curves come from the `vibrissa` solvers; the closed forms (`elastica`) are overlaid.

use crate::cli::{FiguresArgs, MethodArg};
use crate::error::{solve_fail, usage, Fail, Res};
use crate::numeric;
use crate::output::{csv_line, num, AtomicFile};
use crate::scan::{run_scan, ScanOut, ScanSpec};
use elastica::{Branch, Elastica};
use plotters::prelude::*;
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};
use std::io::Write;
use std::path::Path;
use vibrissa::{BranchChoice, Rod, Scene, SolverConfig, Target};

/// How a series is drawn.
#[derive(Clone, Copy, PartialEq)]
enum Kind {
    Line,
    Dashed,
    DashDot,
    Points,
    Cross,
}

struct Series {
    name: String,
    kind: Kind,
    color: RGBColor,
    pts: Vec<(f64, f64)>,
    legend: bool,
}

fn series(name: &str, kind: Kind, color: RGBColor, pts: Vec<(f64, f64)>) -> Series {
    Series {
        name: name.into(),
        kind,
        color,
        pts,
        legend: true,
    }
}

fn unlabeled(mut s: Series) -> Series {
    s.legend = false;
    s
}

struct Panel {
    title: String,
    xlabel: String,
    ylabel: String,
    series: Vec<Series>,
    equal_aspect: bool,
    legend_pos: SeriesLabelPosition,
}

fn panel(title: &str, xlabel: &str, ylabel: &str) -> Panel {
    Panel {
        title: title.into(),
        xlabel: xlabel.into(),
        ylabel: ylabel.into(),
        series: Vec::new(),
        equal_aspect: false,
        legend_pos: SeriesLabelPosition::UpperRight,
    }
}

fn pe<E: std::fmt::Debug>(e: E) -> Fail {
    solve_fail(format!("drawing the figure failed: {e:?}"))
}

const BLUE_: RGBColor = RGBColor(31, 119, 180);
const ORANGE_: RGBColor = RGBColor(255, 127, 14);
const GREEN_: RGBColor = RGBColor(44, 160, 44);
const RED_: RGBColor = RGBColor(214, 39, 40);
const GREY_: RGBColor = RGBColor(110, 110, 110);

fn ranges(p: &Panel, w: f64, h: f64) -> ((f64, f64), (f64, f64)) {
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for s in &p.series {
        for &(x, y) in &s.pts {
            if x.is_finite() && y.is_finite() {
                x0 = x0.min(x);
                x1 = x1.max(x);
                y0 = y0.min(y);
                y1 = y1.max(y);
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
    let (mut xr, mut yr) = (pad(x0, x1), pad(y0, y1));
    if p.equal_aspect {
        // same length per pixel on both axes (plot area about w - 90 by h - 110 pixels)
        let (pw, ph) = (w - 90.0, h - 110.0);
        let (sx, sy) = ((xr.1 - xr.0) / pw, (yr.1 - yr.0) / ph);
        if sx > sy {
            let c = 0.5 * (yr.0 + yr.1);
            yr = (c - 0.5 * sx * ph, c + 0.5 * sx * ph);
        } else {
            let c = 0.5 * (xr.0 + xr.1);
            xr = (c - 0.5 * sy * pw, c + 0.5 * sy * pw);
        }
    }
    (xr, yr)
}

fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    p: &Panel,
) -> Res<()>
where
    DB::ErrorType: 'static,
{
    let (w, h) = area.dim_in_pixel();
    let (xr, yr) = ranges(p, w as f64, h as f64);
    let mut chart = ChartBuilder::on(area)
        .caption(&p.title, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(60)
        .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)
        .map_err(pe)?;
    chart
        .configure_mesh()
        .x_desc(p.xlabel.as_str())
        .y_desc(p.ylabel.as_str())
        .axis_desc_style(("sans-serif", 16))
        .label_style(("sans-serif", 13))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()
        .map_err(pe)?;
    let mut any_legend = false;
    for s in &p.series {
        let color = s.color;
        let pts = s
            .pts
            .iter()
            .copied()
            .filter(|(x, y)| x.is_finite() && y.is_finite());
        let anno = match s.kind {
            Kind::Line => chart
                .draw_series(LineSeries::new(pts, color.stroke_width(2)))
                .map_err(pe)?,
            Kind::Dashed => chart
                .draw_series(DashedLineSeries::new(pts, 8, 5, color.stroke_width(2)))
                .map_err(pe)?,
            Kind::DashDot => chart
                .draw_series(DashedLineSeries::new(pts, 3, 4, color.stroke_width(2)))
                .map_err(pe)?,
            Kind::Points => chart
                .draw_series(pts.map(|c| Circle::new(c, 3, color.filled())))
                .map_err(pe)?,
            Kind::Cross => chart
                .draw_series(pts.map(|c| Cross::new(c, 7, color.stroke_width(3))))
                .map_err(pe)?,
        };
        if s.legend {
            any_legend = true;
            let kind = s.kind;
            anno.label(s.name.as_str()).legend(
                move |(x, y)| -> DynElement<'static, DB, (i32, i32)> {
                    match kind {
                        Kind::Points => Circle::new((x + 10, y), 3, color.filled()).into_dyn(),
                        Kind::Cross => Cross::new((x + 10, y), 5, color.stroke_width(2)).into_dyn(),
                        Kind::Line => {
                            PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                                .into_dyn()
                        }
                        Kind::Dashed | Kind::DashDot => {
                            PathElement::new(vec![(x, y), (x + 7, y)], color.stroke_width(2))
                                .into_dyn()
                        }
                    }
                },
            );
        }
    }
    if any_legend {
        chart
            .configure_series_labels()
            .position(p.legend_pos.clone())
            .background_style(WHITE.mix(0.85))
            .border_style(RGBColor(180, 180, 180))
            .label_font(("sans-serif", 13))
            .draw()
            .map_err(pe)?;
    }
    Ok(())
}

/// Draw the panels side by side into one SVG (atomic write) and write their data as CSV.
fn figure(dir: &Path, name: &str, caption: &str, panels: &[Panel], w: u32, h: u32) -> Res<()> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (w * panels.len() as u32, h + 40))
            .into_drawing_area();
        root.fill(&WHITE).map_err(pe)?;
        let root = root.titled(caption, ("sans-serif", 22)).map_err(pe)?;
        let areas = root.split_evenly((1, panels.len()));
        for (a, p) in areas.iter().zip(panels) {
            draw_panel(a, p)?;
        }
        root.present().map_err(pe)?;
    }
    let mut f = AtomicFile::create(&dir.join(format!("{name}.svg")))?;
    std::io::Write::write_all(&mut f, svg.as_bytes())?;
    f.commit()?;
    let mut c = AtomicFile::create(&dir.join(format!("{name}.csv")))?;
    csv_line(&mut c, &["panel", "series", "x", "y"])?;
    for (i, p) in panels.iter().enumerate() {
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

fn fig2(dir: &Path, cx: &Ctx) -> Res<()> {
    let mut p = panel(
        "Force f vs tip slope phi1 for alpha = -pi/4 (pi/40) 0",
        "tip slope phi1 (rad)",
        "force f (EI/L^2)",
    );
    p.legend_pos = SeriesLabelPosition::UpperLeft;
    let mut num_c = Vec::new();
    let mut num_f = Vec::new();
    for j in 0..=10 {
        let alpha = -FRAC_PI_4 + j as f64 * PI / 40.0;
        let top = (FRAC_PI_2 + 2.0 * alpha).max(0.0);
        let top_c = if j == 10 { top - 1e-6 } else { top };
        let conv: Vec<(f64, f64)> = lin(0.0, top_c, 80)
            .filter_map(|q| {
                Elastica::new(Branch::Convex, alpha, q)
                    .ok()
                    .map(|e| (q, e.f))
            })
            .collect();
        let flex: Vec<(f64, f64)> = lin(0.0, top_c, 80)
            .filter_map(|q| {
                Elastica::new(Branch::OneFlex, alpha, q)
                    .ok()
                    .map(|e| (q, e.f))
            })
            .collect();
        let first = j == 0;
        let s1 = series("convex (2.8), closed form", Kind::Line, BLUE_, conv);
        let s2 = series("one flex (2.15), closed form", Kind::Dashed, ORANGE_, flex);
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
    figure(
        dir,
        "fig02",
        "Fig. 2: (phi1, f) families of the clamped elastica",
        &[p],
        820,
        620,
    )
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

fn fig3(dir: &Path, cx: &Ctx) -> Res<()> {
    let alpha = -PI / 8.0;
    let phi1 = 0.5 * (FRAC_PI_2 + 2.0 * alpha);
    let mut p = panel("alpha = -pi/8, phi1 = (pi/2 + 2 alpha)/2", "x (L)", "y (L)");
    p.equal_aspect = true;
    p.legend_pos = SeriesLabelPosition::LowerRight;
    for (br, name, color) in [
        (Branch::Convex, "convex", BLUE_),
        (Branch::OneFlex, "one flex", ORANGE_),
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
            Kind::Points,
            GREY_,
            elastica_xy(&e, 21),
        ));
        p.series.push(series(
            &format!("{name}: tip force f/40"),
            Kind::Dashed,
            color,
            force_seg(e.x1, e.y1, e.f, alpha, 40.0),
        ));
        if let Some(Ok(pt)) = e.s_b.map(|sb| e.point_at(sb)) {
            p.series
                .push(series("flex point", Kind::Cross, RED_, vec![(pt.x, pt.y)]));
        }
    }
    figure(
        dir,
        "fig03",
        "Fig. 3: elastic lines with zero and one flex point",
        &[p],
        720,
        720,
    )
}

fn fig4(dir: &Path, cx: &Ctx) -> Res<()> {
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
    a.legend_pos = SeriesLabelPosition::UpperLeft;
    a.series
        .push(series("closed form", Kind::Line, BLUE_, cf_phi));
    a.series
        .push(series("numerical", Kind::Points, RED_, n_phi));
    let mut b = panel("force f_eta", "surface height eta (L)", "f_eta (EI/L^2)");
    b.legend_pos = SeriesLabelPosition::UpperLeft;
    b.series
        .push(series("closed form", Kind::Line, BLUE_, cf_f));
    b.series.push(series("numerical", Kind::Points, RED_, n_f));
    figure(
        dir,
        "fig04",
        "Fig. 4: start of the scan (vertical force, alpha = 0) vs eta",
        &[a, b],
        560,
        460,
    )
}

fn fig5(dir: &Path, cx: &Ctx) -> Res<()> {
    let mut p = panel("vertical tip force, tip at height eta", "x (L)", "y (L)");
    p.equal_aspect = true;
    p.legend_pos = SeriesLabelPosition::LowerRight;
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
            Kind::Points,
            GREY_,
            elastica_xy(&e, 21),
        )));
        p.series.push(series(
            &format!("surface y = {eta}"),
            Kind::Dashed,
            color,
            vec![(0.3, eta), (0.85, eta)],
        ));
    }
    if let Some(s) = p.series.iter_mut().find(|s| s.kind == Kind::Points) {
        s.legend = true;
        s.name = "closed form".into();
    }
    figure(
        dir,
        "fig05",
        "Fig. 5: elastic lines at the start of the scan",
        &[p],
        620,
        720,
    )
}

/// Figures 6-8 (eta = 0.75) or 9-11 (eta = 0.6).
fn scan_figs(dir: &Path, cx: &Ctx, eta: f64, first: usize) -> Res<()> {
    // the low surface's scan ends near d = 0.094: zoom in
    let d_max = if eta < 0.65 { 0.1 } else { 0.5 };
    let dense = cx.scan(eta, d_max, 101, 0)?;
    let c = elastica::ClosedFormScan::new(eta)?;
    // closed-form curve in the curve parameter (also beyond the fold in phi1)
    let mut cf: Vec<elastica::ScanPoint> = Vec::new();
    let tmax = c.curve_end();
    let last_d = dense.pts.last().map_or(0.0, |p| p.d);
    for t in lin(0.0, tmax, (tmax * 150.0) as usize + 1) {
        if let Ok(p) = c.curve_at(t) {
            if p.d <= last_d + 1e-9 {
                cf.push(p);
            }
        }
    }
    let tag = format!("eta = {eta}");
    // (phi1, f) sequence with the turning point / end of phase 0
    let mut a = panel(
        &format!("(phi1, f) sequence, {tag}"),
        "tip slope phi1 (rad)",
        "force f (EI/L^2)",
    );
    a.series.push(series(
        "closed form (Remark 3.1)",
        Kind::Line,
        BLUE_,
        cf.iter().map(|p| (p.phi1, p.f)).collect(),
    ));
    a.series.push(series(
        &format!("numerical scan ({})", cx.method.name()),
        Kind::Points,
        RED_,
        dense.pts.iter().map(|p| (p.phi1, p.f)).collect(),
    ));
    let end_name = if c.phase0_end == elastica::Phase0End::TurningPoint {
        "turning point (closed form)"
    } else {
        "end of phase 0: phi1 = 0"
    };
    a.series.push(series(
        end_name,
        Kind::Cross,
        GREEN_,
        vec![(c.turning.phi1, c.turning.f)],
    ));
    a.legend_pos = SeriesLabelPosition::UpperRight;
    figure(
        dir,
        &format!("fig{first:02}"),
        &format!("Fig. {first}: sequence (phi1_i, f_i) for {tag}"),
        &[a],
        720,
        540,
    )?;

    // elastic lines in the lab frame (tip fixed, foot at x = d), flex points as dots
    let shapes = cx.scan(eta, d_max, 11, 80)?;
    let mut b = panel(
        &format!("elastic lines while the foot moves, {tag}"),
        "x (L), lab frame",
        "y (L)",
    );
    b.equal_aspect = true;
    b.legend_pos = SeriesLabelPosition::LowerLeft;
    let mut flex = Vec::new();
    let n = shapes.pts.len();
    for (i, (p, sh)) in shapes.pts.iter().zip(&shapes.shapes).enumerate() {
        let g = 40 + (160 * i / n.max(1)) as u8;
        let col = RGBColor(g / 3, g / 2 + 40, 200);
        let pts: Vec<(f64, f64)> = sh.iter().map(|q| (q.x + p.d, q.y)).collect();
        let name = format!("d = {:.3}, mu = {:.3}", p.d, p.mu);
        b.series.push(if i == 0 || i + 1 == n {
            series(&name, Kind::Line, col, pts)
        } else {
            unlabeled(series(&name, Kind::Line, col, pts))
        });
        if let Some(sf) = p.s_flex {
            // interpolate the flex point on the sampled shape
            let k = ((sf * (sh.len() - 1) as f64).round() as usize).min(sh.len() - 1);
            flex.push((sh[k].x + p.d, sh[k].y));
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
    figure(
        dir,
        &format!("fig{:02}", first + 1),
        &format!("Fig. {}: elastic lines, {tag}", first + 1),
        &[b],
        720,
        640,
    )?;

    // mu vs d
    let mut m = panel(
        &format!("friction ratio vs foot displacement, {tag}"),
        "foot displacement d (L)",
        "mu = |fx/fy| = tan(-alpha)",
    );
    m.series.push(series(
        "closed form",
        Kind::Line,
        BLUE_,
        cf.iter().map(|p| (p.d, p.mu)).collect(),
    ));
    m.series.push(series(
        &format!("numerical scan ({})", cx.method.name()),
        Kind::Points,
        RED_,
        dense.pts.iter().map(|p| (p.d, p.mu)).collect(),
    ));
    m.series.push(series(
        &format!(
            "mu_max = {:.4} at d = {:.4}",
            dense.mu_max, dense.d_at_mu_max
        ),
        Kind::Cross,
        GREEN_,
        vec![(dense.d_at_mu_max, dense.mu_max)],
    ));
    m.legend_pos = SeriesLabelPosition::LowerRight;
    figure(
        dir,
        &format!("fig{:02}", first + 2),
        &format!(
            "Fig. {}: mu vs d, {tag} (scan stops: {})",
            first + 2,
            dense.stop.reason
        ),
        &[m],
        720,
        540,
    )
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
    if a.method == MethodArg::Analytic {
        return Err(usage(
            "figures overlay numerical solutions on the closed forms: choose a numerical --method",
        ));
    }
    std::fs::create_dir_all(&a.out_dir)
        .map_err(|e| solve_fail(format!("cannot create {}: {e}", a.out_dir.display())))?;
    let cx = Ctx {
        cfg: numeric::config(a.method, a.tol),
        rod: Rod::uniform(),
        method: a.method,
        tol: a.tol,
    };
    let dir = a.out_dir.as_path();
    let want = |n: usize| only.contains(&n);
    if want(2) {
        fig2(dir, &cx)?;
    }
    if want(3) {
        fig3(dir, &cx)?;
    }
    if want(4) {
        fig4(dir, &cx)?;
    }
    if want(5) {
        fig5(dir, &cx)?;
    }
    if want(6) || want(7) || want(8) {
        scan_figs(dir, &cx, 0.75, 6)?;
    }
    if want(9) || want(10) || want(11) {
        scan_figs(dir, &cx, 0.6, 9)?;
    }
    writeln!(
        std::io::stdout(),
        "figures written to {}",
        a.out_dir.display()
    )?;
    Ok(())
}
