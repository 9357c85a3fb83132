//! `vibrissa figures`: the paper's Figures 2-11 as SVG (drawn by `chart`) with the CSV behind
//! each. Numerical curves come from the `vibrissa` solvers; the closed forms (`elastica`) are
//! overlaid.

use crate::chart::*;
use crate::cli::FiguresArgs;
use crate::error::{solve_fail, usage, Res};
use crate::scan::{run_scan, Scanned};
use crate::table::{csv_line, num, AtomicFile};
use elastica::{Branch, Elastica, Phase0End};
use plotters::style::RGBColor;
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};
use std::io::Write;
use std::path::Path;
use vibrissa::{BranchChoice, Method, Rod, ScanOptions, Scene, ShapePoint, SolverConfig, Target};

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
}

impl Ctx {
    fn solve(&self, branch: Branch, alpha: f64, target: Target) -> Option<vibrissa::Shape> {
        let b = match branch {
            Branch::Convex => BranchChoice::Convex,
            Branch::OneFlex => BranchChoice::Flex,
        };
        vibrissa::solve(&self.rod, alpha, target, &b, &self.cfg).ok()
    }

    fn scan(&self, eta: f64, d_max: f64, points: usize, shapes: usize) -> Res<Scanned> {
        let scene = Scene {
            eta,
            ..Scene::default()
        };
        let opts = ScanOptions {
            d_max,
            points,
            solver: self.cfg.clone(),
            keep_shapes: (shapes >= 2).then_some(shapes),
            ..ScanOptions::default()
        };
        run_scan(&scene, opts)
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
        stack: None,
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
        stack: None,
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
        stack: None,
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
        stack: None,
    })
}

/// The flex point at arc length `sf` on a sampled shape (linear in s between samples).
fn flex_xy(sh: &[ShapePoint], sf: f64) -> Option<(f64, f64)> {
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
        let last_d = dense.result.points.last().map_or(0.0, |p| p.d);
        let cf: Vec<elastica::ScanPoint> = lin(0.0, tmax, (tmax * 150.0) as usize + 1)
            .filter_map(|t| c.curve_at(t).ok())
            .filter(|p| p.d <= last_d + 1e-9)
            .collect();
        let numerical = format!("numerical scan ({})", cx.cfg.method.name());
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
    dense: &Scanned,
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
        dense.result.points.iter().map(|p| (p.phi1, p.f)).collect(),
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
        stack: None,
    });
}

/// mu vs d with the largest mu of the scan (Figs. 8, 11).
fn fig_mu(
    figs: &mut Vec<Fig>,
    dense: &Scanned,
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
        dense.result.points.iter().map(|p| (p.d, p.mu)).collect(),
    ));
    m.series.push(series(
        "closed form",
        Kind::Thin,
        BLUE_,
        cf.iter().map(|p| (p.d, p.mu)).collect(),
    ));
    // a maximum inside the scan, or only the largest value at its end (mu still rising there)
    let last_d = dense.result.points.last().map_or(0.0, |p| p.d);
    let interior = dense.result.d_at_mu_max < last_d - 1e-9;
    let name = if interior {
        format!(
            "mu_max = {:.4} at d = {:.4} (measurable range ends)",
            dense.result.mu_max, dense.result.d_at_mu_max
        )
    } else {
        format!(
            "scan end ({}): mu = {:.4} at d = {:.4}, still rising",
            dense.stop.name(),
            dense.result.mu_max,
            dense.result.d_at_mu_max
        )
    };
    m.series.push(series(
        &name,
        Kind::Cross,
        GREEN_,
        vec![(dense.result.d_at_mu_max, dense.result.mu_max)],
    ));
    figs.push(Fig {
        name: format!("fig{n:02}"),
        caption: format!(
            "Fig. {n}: mu vs d, {tag} (scan stops: {})",
            dense.stop.name()
        ),
        panels: vec![m],
        w: 760,
        h: 560,
        stack: None,
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
    let k = shapes.result.points.len();
    for (i, (p, sh)) in shapes
        .result
        .points
        .iter()
        .zip(&shapes.result.shapes)
        .enumerate()
    {
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
        stack: None,
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

fn context(method: Method, tol: f64) -> Res<Ctx> {
    Ok(Ctx {
        cfg: SolverConfig {
            method,
            tol,
            ..SolverConfig::default()
        },
        rod: Rod::uniform(),
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
mod tests {
    use super::layout_check::*;
    use super::*;

    #[test]
    fn legends_and_labels_never_cover_data() {
        let cx = context(Method::Shooting, 1e-10).unwrap();
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
            let (w, h) = crate::chart::picture_size(fig);
            assert!(
                fig.panels.len() <= crate::chart::PANELS_PER_ROW,
                "{}",
                fig.name
            );
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

    #[test]
    fn only_writes_the_figures_asked_for() {
        let cx = context(Method::Shooting, 1e-10).unwrap();
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
