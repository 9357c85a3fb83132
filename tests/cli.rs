//! End-to-end tests of the `vibrissa` program: run the built binary, check values against the
//! closed forms (crate `elastica`) and the paper's printed numbers, and check the error contract.

use std::f64::consts::PI;
use std::path::Path;
use std::process::Command;

mod common;
use common::*;

const A8: &str = "-0.39269908169872414"; // -pi/8
const P8: &str = "0.39269908169872414"; // (pi/2 + 2(-pi/8))/2 = pi/8

#[test]
fn solve_analytic_matches_closed_forms_and_paper() {
    let o = ok(&["solve", "--alpha", A8, "--phi1", P8, "--method", "analytic"]);
    let (h, rows) = csv(&o.stdout);
    assert_eq!(rows.len(), 1);
    for c in [
        "f", "alpha", "phi1", "x1", "y1", "m_base", "flex", "s_flex", "residual", "fx", "fy",
        "y_max", "method",
    ] {
        assert!(h.iter().any(|x| x == c), "missing column {c}");
    }
    let r = &rows[0];
    let e = elastica::Elastica::new(
        elastica::Branch::Convex,
        -std::f64::consts::FRAC_PI_8,
        std::f64::consts::FRAC_PI_8,
    )
    .unwrap();
    close(col(&h, r, "f"), e.f, 1e-13 * e.f, "f");
    close(col(&h, r, "x1"), e.x1, 1e-14, "x1");
    close(col(&h, r, "y1"), e.y1, 1e-14, "y1");
    close(col(&h, r, "m_base"), e.m_base, 1e-13, "m_base");
    // the paper's Fig. 3 prints f = 4.72 (convex) and 19.0 (one flex)
    close(col(&h, r, "f"), 4.72, 0.005, "paper Fig. 3 convex force");
    // sign conventions: fx = f sin(alpha), fy = -f cos(alpha)
    let (f, a) = (col(&h, r, "f"), col(&h, r, "alpha"));
    close(col(&h, r, "fx"), f * a.sin(), 1e-13, "fx");
    close(col(&h, r, "fy"), -f * a.cos(), 1e-13, "fy");
    assert!(col(&h, r, "residual") < 1e-12);

    let o = ok(&[
        "solve", "--alpha", A8, "--phi1", P8, "--branch", "flex", "--method", "analytic", "--json",
    ]);
    let v = json(&o.stdout);
    close(
        v["f"].as_f64().unwrap(),
        19.0,
        0.05,
        "paper Fig. 3 one-flex force",
    );
    assert_eq!(v["flex"].as_u64(), Some(1));
    // Remark 2.1: the flex point bisects the arc between the two points of slope pi/2, and the
    // second one is at s = 2 s_b < 1 here
    let sb = v["s_flex"].as_f64().unwrap();
    assert!(sb > 0.0 && 2.0 * sb < 1.0, "s_flex = {sb}");

    // buckling: alpha = 0, phi1 -> pi/2 gives f -> pi^2/4 (first critical load); near the corner
    // f = pi^2/4 (1 + (pi/2 - phi1)^2 / 8 + ...) so 1e-4 off pi/2 is within 1e-8 relative
    let o = ok(&[
        "solve",
        "--alpha",
        "0",
        "--phi1",
        "1.5706963267948966",
        "--method",
        "analytic",
        "--json",
    ]);
    let f = json(&o.stdout)["f"].as_f64().unwrap();
    close(
        f,
        std::f64::consts::PI.powi(2) / 4.0,
        1e-7,
        "first buckling load",
    );
}

#[test]
fn solve_eta_and_shape_out() {
    let d = tmpdir("shape");
    let shape = d.join("shape.csv");
    let o = ok(&[
        "solve",
        "--alpha",
        "0",
        "--eta",
        "0.75",
        "--method",
        "analytic",
        "--shape-out",
        shape.to_str().unwrap(),
        "--shape-points",
        "11",
    ]);
    let (h, rows) = csv(&o.stdout);
    close(col(&h, &rows[0], "y1"), 0.75, 1e-13, "tip height");
    let (sh, srows) = csv(&std::fs::read_to_string(&shape).unwrap());
    assert_eq!(srows.len(), 11);
    assert_eq!(sh, ["s", "x", "y", "phi", "kappa", "m"]);
    close(col(&sh, &srows[10], "y"), 0.75, 1e-13, "shape tip");
    close(
        col(&sh, &srows[0], "phi"),
        std::f64::consts::FRAC_PI_2,
        1e-15,
        "clamp slope",
    );
}

#[test]
fn solve_numerical_matches_analytic() {
    let a = ok(&[
        "solve", "--alpha", A8, "--phi1", P8, "--method", "analytic", "--json",
    ]);
    let a = json(&a.stdout);
    for m in ["shooting", "multiple-shooting"] {
        let n = ok(&[
            "solve", "--alpha", A8, "--phi1", P8, "--method", m, "--json",
        ]);
        let n = json(&n.stdout);
        for k in ["f", "x1", "y1", "m_base"] {
            close(
                n[k].as_f64().unwrap(),
                a[k].as_f64().unwrap(),
                1e-7,
                &format!("{m} {k}"),
            );
        }
        assert!(n["residual"].as_f64().unwrap() < 1e-8);
    }
    // tip-height target on the flex branch
    let n = ok(&[
        "solve", "--alpha", "-0.6", "--eta", "0.75", "--branch", "flex", "--json",
    ]);
    let n = json(&n.stdout);
    close(
        n["y1"].as_f64().unwrap(),
        0.75,
        1e-8,
        "numerical tip height",
    );
    let e = elastica::Elastica::new(elastica::Branch::OneFlex, -0.6, n["phi1"].as_f64().unwrap())
        .unwrap();
    close(n["f"].as_f64().unwrap(), e.f, 1e-6 * e.f, "flex f at eta");
}

#[test]
fn scan_matches_closed_form_scan() {
    let cf = elastica::ClosedFormScan::new(0.75).unwrap();
    let best = cf.mu_max().unwrap();
    let d = tmpdir("scan");
    let out = d.join("scan.csv");
    let o = ok(&[
        "scan",
        "--points",
        "11",
        "--out",
        out.to_str().unwrap(),
        "--json",
    ]);
    let v = json(&o.stdout);
    for k in ["mu_max", "d_at_mu_max", "points", "stop_reason"] {
        assert!(!v[k].is_null(), "missing {k} in {v}");
    }
    assert_eq!(v["stop_reason"], "d_max");
    close(v["mu_max"].as_f64().unwrap(), best.mu, 1e-7, "mu_max");
    close(
        v["d_at_mu_max"].as_f64().unwrap(),
        best.d,
        1e-4,
        "d at mu_max",
    );
    let (h, rows) = csv(&std::fs::read_to_string(&out).unwrap());
    for c in [
        "d", "mu", "alpha", "phi1", "f", "fx", "fy", "m_base", "flex", "y_max",
    ] {
        assert!(h.iter().any(|x| x == c), "missing column {c}");
    }
    assert_eq!(rows.len(), 11);
    // each row against the closed form at the same d: mu = tan(-alpha) and the curve
    for r in &rows {
        let (dd, mu, a) = (col(&h, r, "d"), col(&h, r, "mu"), col(&h, r, "alpha"));
        close(mu, (-a).tan(), 1e-12, "mu = tan(-alpha)");
        assert!(col(&h, r, "y_max") <= 0.75 + 1e-8);
        assert!(dd >= 0.0);
    }
    // start: alpha = 0 rod with tip at 0.75
    close(col(&h, &rows[0], "f"), cf.start.f, 1e-8, "f0");
    close(col(&h, &rows[0], "phi1"), cf.start.phi1, 1e-8, "phi1_0");
    // the analytic scan agrees with the numerical one row by row
    let a = ok(&["scan", "--points", "11", "--method", "analytic"]);
    let (ha, ra) = csv(&a.stdout);
    assert_eq!(ra.len(), rows.len());
    for (x, y) in rows.iter().zip(&ra) {
        for c in ["d", "mu", "f", "phi1", "m_base"] {
            close(col(&h, x, c), col(&ha, y, c), 1e-7, c);
        }
    }
    assert!(
        a.stderr.contains("mu_max"),
        "summary on stderr: {}",
        a.stderr
    );
}

#[test]
fn scan_low_surface_stops_with_penetration_and_slip() {
    // the paper's tip-only model: the tip turning horizontal ends the scan
    let o = ok(&[
        "scan",
        "--eta",
        "0.6",
        "--points",
        "11",
        "--json",
        "--contact",
        "tip",
    ]);
    let v = json(&o.stdout);
    assert_eq!(v["stop_reason"], "penetration");
    // the paper: at eta = 0.6 the convex phase ends close to alpha = -pi/4, phi1 = 0
    let cf = elastica::ClosedFormScan::new(0.6).unwrap();
    close(
        v["stop"]["d"].as_f64().unwrap(),
        cf.turning.d,
        1e-6,
        "penetration d",
    );
    assert!(o.stderr.contains("stopped early"));
    // contact anywhere (the default): the tip lies down there and the scan goes on to d_max,
    // the touchdown a row of its own at the same d
    let o = ok(&["scan", "--eta", "0.6", "--points", "11"]);
    let rows: Vec<&str> = o.stdout.lines().collect();
    let touchdown = rows
        .iter()
        .find(|r| r.ends_with(",touchdown"))
        .expect("a touchdown row");
    close(
        touchdown.split(',').next().unwrap().parse().unwrap(),
        cf.turning.d,
        1e-6,
        "touchdown d",
    );
    assert!(rows.last().unwrap().starts_with("0.5,"), "{}", o.stdout);
    // slip threshold
    let o = ok(&[
        "scan", "--points", "21", "--mu0", "0.5", "--json", "--method", "analytic",
    ]);
    let v = json(&o.stdout);
    assert_eq!(v["stop_reason"], "slip");
    close(v["mu_max"].as_f64().unwrap(), 0.5, 1e-10, "slip mu");
}

#[test]
fn infer_reads_mu0_off_the_scan() {
    let cf = elastica::ClosedFormScan::new(0.75).unwrap();
    let p = cf.phase0_at_alpha(-0.5).unwrap();
    let d0 = p.d.to_string();
    for m in ["analytic", "shooting"] {
        let o = ok(&[
            "infer", "--d0", &d0, "--method", m, "--points", "21", "--json",
        ]);
        let v = json(&o.stdout);
        close(v["mu0"].as_f64().unwrap(), p.mu, 1e-6, &format!("{m} mu0"));
    }
    let best = cf.mu_max().unwrap();
    let msg = bad(&["infer", "--d0", "0.3", "--method", "analytic"], 2);
    assert!(msg.contains("measurable range"), "{msg}");
    assert!(
        msg.contains(&format!("{}", best.d)) || msg.contains("0.130"),
        "{msg}"
    );
}

#[test]
fn sweep_shards_concatenate_to_the_full_file() {
    let d = tmpdir("sweep");
    let full = d.join("full.csv");
    let base = [
        "sweep",
        "--eta",
        "0.7,0.75,0.8,0.9",
        "--taper",
        "1,0.5",
        "--method",
        "analytic,shooting",
        "--points",
        "6",
    ];
    let mut args: Vec<&str> = base.to_vec();
    let fs = full.to_str().unwrap().to_string();
    args.extend(["--out", &fs, "--jobs", "2"]);
    ok(&args);
    let text = std::fs::read_to_string(&full).unwrap();
    let (h, rows) = csv(&text);
    assert_eq!(rows.len(), 16);
    // grid order: eta slowest, method fastest; a scene that fails is a row with its error
    let ie = h.iter().position(|c| c == "error").unwrap();
    let im = h.iter().position(|c| c == "method").unwrap();
    assert_eq!(rows[0][im], "analytic");
    assert_eq!(rows[1][im], "shooting");
    // the closed forms exist only for the uniform rod: an error row, and the sweep goes on
    assert!(rows[2][ie].contains("analytic"), "taper 0.5: {:?}", rows[2]);
    assert_eq!(col(&h, &rows[2], "taper"), 0.5);
    assert!(rows[3][ie].is_empty(), "taper 0.5, shooting: {:?}", rows[3]);
    assert!(rows[0][ie].is_empty());
    // the uniform-rod rows: numerical and closed form agree
    for k in [0, 4, 8, 12] {
        let (a, n) = (&rows[k], &rows[k + 1]);
        close(col(&h, a, "f0"), col(&h, n, "f0"), 1e-7, "f0");
        close(col(&h, a, "mu_max"), col(&h, n, "mu_max"), 1e-5, "mu_max");
    }
    assert!(!text.contains("NaN"));
    // shards: header only in shard 1, concatenation byte-equal
    let mut cat = Vec::new();
    for (k, jobs) in [("1/3", "1"), ("2/3", "2"), ("3/3", "1")] {
        let mut a: Vec<&str> = base.to_vec();
        a.extend(["--shard", k, "--jobs", jobs]);
        cat.extend(ok(&a).stdout.into_bytes());
    }
    assert_eq!(String::from_utf8(cat).unwrap(), text);
    // more shards than scenes: empty shards are fine (shard 1 still writes the header)
    let mut a: Vec<&str> = base.to_vec();
    a.extend(["--shard", "1/20"]);
    assert_eq!(ok(&a).stdout.lines().count(), 1);
}

fn write(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_string()
}

#[test]
fn scene_files_and_flags() {
    let d = tmpdir("scene");
    // the flag overrides the file
    let f = write(&d, "s.toml", "eta = 0.7\nsupport_compliance = 0.5\n");
    let o = ok(&[
        "scan",
        "--scene",
        &f,
        "--support-compliance",
        "0",
        "--method",
        "analytic",
        "--points",
        "3",
        "--json",
    ]);
    let v = json(&o.stdout);
    close(v["eta"].as_f64().unwrap(), 0.7, 0.0, "eta from file");
    // physical units add columns
    let o = ok(&[
        "solve",
        "--alpha",
        "-0.3",
        "--phi1",
        "0.5",
        "--method",
        "analytic",
        "--scene",
        "data/scenes/paper.toml",
        "--length-mm",
        "30",
        "--youngs-modulus-gpa",
        "3.3",
        "--base-diameter-um",
        "100",
    ]);
    let (h, rows) = csv(&o.stdout);
    let ei = 3.3e9 * std::f64::consts::PI * 1e-4f64.powi(4) / 64.0;
    close(
        col(&h, &rows[0], "f_N"),
        col(&h, &rows[0], "f") * ei / 0.03f64.powi(2),
        1e-15,
        "f in N",
    );
    close(
        col(&h, &rows[0], "x1_mm"),
        col(&h, &rows[0], "x1") * 30.0,
        1e-12,
        "x1 mm",
    );
    // presets parse
    for e in std::fs::read_dir("data/scenes").unwrap() {
        let p = e.unwrap().path();
        if p.extension().is_some_and(|x| x == "toml") {
            let text = std::fs::read_to_string(&p).unwrap();
            toml::from_str::<vibrissa::Scene>(&text)
                .unwrap_or_else(|e| panic!("{}: {e}", p.display()));
        }
    }
}

#[test]
fn bad_input_is_one_line_and_nonzero() {
    let d = tmpdir("bad");
    let out = d.join("never.csv");
    let outs = out.to_str().unwrap();
    // unknown flag, missing flags, non-numeric, NaN
    bad(
        &["solve", "--alpha", "0", "--phi1", "0.3", "--frobnicate"],
        2,
    );
    bad(&["solve", "--phi1", "0.3"], 2);
    bad(&["solve", "--alpha", "abc", "--phi1", "0.3"], 2);
    bad(&["solve", "--alpha", "NaN", "--phi1", "0.3"], 2);
    bad(&["frobnicate"], 2);
    // out-of-domain values name the valid range
    let m = bad(
        &[
            "solve", "--alpha", "-1", "--phi1", "0.3", "--method", "analytic",
        ],
        2,
    );
    assert!(m.contains("valid range"), "{m}");
    let m = bad(
        &[
            "solve", "--alpha", "-0.2", "--phi1", "1.4", "--method", "analytic",
        ],
        2,
    );
    assert!(m.contains("phi1") && m.contains("valid range"), "{m}");
    let m = bad(&["scan", "--eta", "0.3", "--out", outs], 2);
    assert!(m.contains("eta") && m.contains("valid range"), "{m}");
    let m = bad(
        &[
            "scan",
            "--taper",
            "1",
            "--precurvature",
            "0.3",
            "--method",
            "analytic",
            "--out",
            outs,
        ],
        2,
    );
    assert!(m.contains("analytic"), "{m}");
    // scene files: typo'd key, missing file, non-numeric field
    let typo = write(&d, "typo.toml", "eta = 0.7\nsuport_compliance = 0.1\n");
    let m = bad(&["scan", "--scene", &typo, "--out", outs], 2);
    assert!(
        m.contains("suport_compliance") && m.contains("line 2"),
        "{m}"
    );
    let m = bad(
        &["scan", "--scene", "/nonexistent/scene.toml", "--out", outs],
        2,
    );
    assert!(m.contains("/nonexistent/scene.toml"), "{m}");
    let nonnum = write(&d, "nonnum.toml", "eta = \"high\"\n");
    bad(&["scan", "--scene", &nonnum, "--out", outs], 2);
    let badtaper = write(
        &d,
        "taper.toml",
        "stiffness = { kind = \"taper\", ratio = 2.0 }\n",
    );
    let m = bad(
        &[
            "solve", "--alpha", "0", "--phi1", "0.3", "--scene", &badtaper,
        ],
        2,
    );
    assert!(m.contains("ratio"), "{m}");
    // sweep grid syntax, shard syntax
    bad(&["sweep", "--eta", "0.5:0.9", "--out", outs], 2);
    bad(&["sweep", "--shard", "4/3", "--out", outs], 2);
    bad(&["sweep", "--method", "newton", "--out", outs], 2);
    // no partial CSV was left behind
    assert!(!out.exists());
    assert_eq!(
        std::fs::read_dir(&d).unwrap().count(),
        3,
        "only the scene files"
    );
}

#[test]
fn help_documents_every_flag() {
    for (cmd, flags) in [
        (
            "solve",
            &[
                "--alpha",
                "--phi1",
                "--eta",
                "--branch",
                "--method",
                "--tol",
                "--json",
                "--shape-out",
                "--shape-points",
                "--taper",
                "--precurvature",
                "--precurvature-slope",
                "--support-compliance",
                "--surface-angle",
                "--scene",
            ][..],
        ),
        (
            "scan",
            &[
                "--eta", "--d-max", "--points", "--mu0", "--method", "--tol", "--out", "--shapes",
                "--json", "--taper",
            ][..],
        ),
        (
            "sweep",
            &[
                "--eta",
                "--taper",
                "--precurvature",
                "--precurvature-slope",
                "--support-compliance",
                "--method",
                "--tol",
                "--jobs",
                "--shard",
                "--no-header",
                "--timing",
                "--out",
            ][..],
        ),
        ("infer", &["--eta", "--d0", "--json", "--method"][..]),
        ("figures", &["--out-dir"][..]),
    ] {
        let o = ok(&[cmd, "--help"]);
        for f in flags {
            assert!(o.stdout.contains(f), "{cmd} --help lacks {f}");
        }
        assert!(
            o.stdout.contains("default"),
            "{cmd} --help shows no defaults"
        );
    }
}

/// Statements of `--help` that README.md and docs/reference.md rely on.
#[test]
fn help_states_ranges_and_requirements() {
    let h = ok(&["solve", "--help"]).stdout;
    assert!(h.contains("One of --phi1 and --eta is required"), "{h}");
    assert!(
        h.contains("(-pi/2, pi/2)"),
        "solve --help: the range of --alpha"
    );
    let h = ok(&["scan", "--help"]).stdout;
    assert!(
        h.contains("point, d, s, x, y, x_lab, phi, kappa, m"),
        "scan --help: --shapes columns"
    );
    assert!(h.contains("eta_ = 0.456946581044463625"), "eta_ defined");
    // one layout for every command: flags on their own line, Scene and Physical sections
    for cmd in ["solve", "scan", "infer", "sweep"] {
        let h = ok(&[cmd, "--help"]).stdout;
        assert!(h.contains("\nScene:\n"), "{cmd}: no Scene section");
        assert!(
            h.contains("\nPhysical units:\n"),
            "{cmd}: no Physical units section"
        );
        assert!(h.contains("\n      --scene <FILE.toml>\n"), "{cmd}: layout");
    }
    let h = ok(&["figures", "--help"]).stdout;
    assert!(!h.contains("--scene"), "figures takes no scene");
}

/// A sweep with physical dimensions adds the physical columns, f0_N = f0 · EI/L².
#[test]
fn sweep_physical_columns() {
    let o = ok(&[
        "sweep",
        "--eta",
        "0.7,0.8",
        "--points",
        "3",
        "--length-mm",
        "30",
        "--youngs-modulus-gpa",
        "3.3",
        "--base-diameter-um",
        "100",
    ]);
    let (h, rows) = csv(&o.stdout);
    assert_eq!(rows.len(), 2);
    let ei = 3.3e9 * PI * 1e-4f64.powi(4) / 64.0;
    for r in &rows {
        close(
            col(&h, r, "f0_N"),
            col(&h, r, "f0") * ei / 0.03f64.powi(2),
            1e-15,
            "f0 in N",
        );
        close(
            col(&h, r, "d_end_mm"),
            col(&h, r, "d_end") * 30.0,
            1e-12,
            "d_end in mm",
        );
    }
}

#[test]
fn figures_are_valid_svg_with_data() {
    let d = tmpdir("figs");
    let ds = d.to_str().unwrap();
    let o = ok(&["figures", "--out-dir", ds]);
    assert!(o.stdout.contains(ds));
    // (figure, minimum number of drawn lines, minimum number of dots)
    for (n, lines, dots) in [
        (2, 23, 40),
        (3, 25, 21), // one-flex closed form: 21 triangles (polylines)
        (4, 2, 20),
        (5, 4, 42),
        (6, 1, 101),
        (7, 11, 5),
        (8, 1, 101),
        (9, 1, 5),
        (10, 8, 0),
        (11, 1, 5),
    ] {
        let svg = std::fs::read_to_string(d.join(format!("fig{n:02}.svg"))).unwrap();
        assert!(svg.trim_start().starts_with("<svg"), "fig {n}");
        assert!(svg.trim_end().ends_with("</svg>"), "fig {n}");
        assert!(svg.contains("<text"), "fig {n}: no labels");
        let polylines = svg.matches("<polyline").count() + svg.matches("<path").count();
        // the axes and grid add polylines too; series are on top of those
        assert!(polylines >= lines, "fig {n}: {polylines} lines");
        let circles = svg.matches("<circle").count();
        assert!(circles >= dots, "fig {n}: {circles} dots");
        assert!(!svg.contains("NaN"), "fig {n}");
        let text = std::fs::read_to_string(d.join(format!("fig{n:02}.csv"))).unwrap();
        let (h, rows) = csv(&text);
        assert_eq!(h, ["panel", "series", "x", "y"]);
        assert!(!rows.is_empty());
    }
    // Fig. 8: the numerical mu(d) points (101) match the closed-form mu_max
    let (h, rows) = csv(&std::fs::read_to_string(d.join("fig08.csv")).unwrap());
    let num: Vec<&Vec<String>> = rows
        .iter()
        .filter(|r| r[1].starts_with("numerical"))
        .collect();
    assert_eq!(num.len(), 101);
    let best = elastica::ClosedFormScan::new(0.75)
        .unwrap()
        .mu_max()
        .unwrap();
    let m = num.iter().map(|r| col(&h, r, "y")).fold(f64::MIN, f64::max);
    assert!(
        m <= best.mu + 1e-8 && m > best.mu - 1e-3,
        "grid max {m} vs {}",
        best.mu
    );
    // Fig. 2: the turning-point locus is f = 4 K^2(sin(alpha/2)); at alpha -> 0 it tends to pi^2
    let (h, rows) = csv(&std::fs::read_to_string(d.join("fig02.csv")).unwrap());
    let locus: Vec<&Vec<String>> = rows
        .iter()
        .filter(|r| r[1].starts_with("turning"))
        .collect();
    let last = locus.last().unwrap();
    close(
        col(&h, last, "y"),
        PI * PI,
        1e-4,
        "turning point at alpha -> 0",
    );
}

/// `vibrissa scan | head`: when the reader closes stdout early the program stops quietly with
/// exit code 0 (as `rg` does), with no error line and no panic. The output (5000 rows, ≈ 1 MB) is
/// far larger than a pipe buffer, so the program is still writing when the pipe closes.
#[test]
fn closed_stdout_is_not_an_error() {
    use std::io::{BufRead, BufReader};
    use std::process::Stdio;
    let mut child = Command::new(env!("CARGO_BIN_EXE_vibrissa"))
        .args(["scan", "--points", "5000"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run vibrissa");
    let mut header = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut header)
        .unwrap();
    assert!(header.starts_with("d,mu,alpha"), "{header:?}");
    // the reader (and the pipe's read end) is dropped here
    let o = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "stderr {stderr:?}");
    assert!(stderr.is_empty(), "stderr {stderr:?}");
}

/// A scene file is read once (issue 19): `--scene /dev/stdin`, `--scene -` and a FIFO give the
/// same output as the same scene in a regular file, for every command that takes a scene (the
/// scene was read twice: the second read of a pipe is empty, so the scene was silently replaced
/// by the defaults, and a FIFO waited for a second writer forever).
#[cfg(unix)]
#[test]
fn a_scene_is_read_once_from_stdin_a_pipe_or_a_fifo() {
    let d = tmpdir("scene-once");
    let text = "eta = 0.7\nsupport_compliance = 0.5\n";
    let file = write(&d, "s.toml", text);
    let fifo = d.join("scene.fifo");
    assert!(Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap()
        .success());
    let fifo = fifo.to_str().unwrap().to_string();
    let commands: [&[&str]; 4] = [
        &["solve", "--alpha", "-0.2", "--eta", "0.7"],
        &["scan", "--points", "5"],
        &["infer", "--d0", "0.02", "--points", "5"],
        &["sweep", "--points", "5", "--taper", "1,0.8"],
    ];
    for args in commands {
        fn with<'a>(args: &[&'a str], scene: &'a str) -> Vec<&'a str> {
            [args, &["--scene", scene]].concat()
        }
        let reference = ok(&with(args, &file)).stdout;
        // the scene matters: without it the output differs
        assert_ne!(
            ok(args).stdout,
            reference,
            "{args:?}: the scene changes nothing"
        );
        for (scene, input) in [
            ("/dev/stdin", Some(text)),
            ("-", Some(text)),
            // a FIFO: a writer writes the scene once
            (fifo.as_str(), None),
        ] {
            let writer = input.is_none().then(|| {
                let f = fifo.clone();
                std::thread::spawn(move || std::fs::write(f, text).unwrap())
            });
            let o = run_fed(&with(args, scene), input);
            if let Some(w) = writer {
                w.join().unwrap();
            }
            assert_eq!(o.code, 0, "{args:?} --scene {scene}: {}", o.stderr);
            assert_eq!(o.stdout, reference, "{args:?} --scene {scene}");
        }
    }
    // a bad scene from stdin is named as such
    let o = run_fed(&["scan", "--scene", "-"], Some("eta = 0.3\n"));
    assert_eq!(o.code, 2);
    assert!(
        o.stderr.starts_with("error: scene file -: eta = 0.3"),
        "{}",
        o.stderr
    );
}

/// `vibrissa plot` draws each kind of file (the fixtures of `tests/fixtures/plot`), next to the
/// input by default, and refuses a file it does not know without leaving an output.
#[test]
fn plot_draws_each_kind_of_file() {
    let dir = tmpdir("plot");
    let fixtures = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/plot");
    for name in ["scan", "shapes", "sweep", "drag"] {
        let input = dir.join(format!("{name}.csv"));
        std::fs::copy(fixtures.join(format!("{name}.csv")), &input).unwrap();
        let o = ok(&["plot", input.to_str().unwrap()]);
        let out = dir.join(format!("{name}.svg"));
        assert_eq!(
            o.stdout.trim(),
            format!("plot written to {}", out.display()),
            "{name}"
        );
        let svg = std::fs::read_to_string(&out).unwrap();
        assert!(svg.starts_with("<svg") && svg.contains("</svg>"), "{name}");
    }
    let out = dir.join("chosen.svg");
    let sweep = fixtures.join("sweep.csv");
    ok(&[
        "plot",
        sweep.to_str().unwrap(),
        "--z",
        "stop_reason",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(std::fs::read_to_string(&out)
        .unwrap()
        .contains("stop_reason: penetration"));
    let other = dir.join("other.csv");
    std::fs::write(&other, "a,b\n1,2\n").unwrap();
    let e = bad(&["plot", other.to_str().unwrap()], 2);
    assert!(e.contains("not a file vibrissa writes"), "{e}");
    assert!(!dir.join("other.svg").exists());
    let e = bad(
        &[
            "plot",
            fixtures.join("shapes.csv").to_str().unwrap(),
            "--surface-angle",
            "1",
            "--out",
            dir.join("x.svg").to_str().unwrap(),
        ],
        2,
    );
    assert!(e.contains("--surface-angle 1 is outside"), "{e}");
}

/// `plot DRAG.csv --shapes SHAPES.csv --aligned` with the drag's corrugation (issue 31): one SVG
/// of the surface and the rods at the slips above the moment at the foot.
#[test]
fn plot_aligned_draws_a_drag_over_its_surface() {
    let dir = tmpdir("plot_aligned");
    let fixtures = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/plot");
    let out = dir.join("over.svg");
    let o = ok(&[
        "plot",
        fixtures.join("drag_corrugated.csv").to_str().unwrap(),
        "--shapes",
        fixtures
            .join("drag_corrugated_shapes.csv")
            .to_str()
            .unwrap(),
        "--aligned",
        "--corrugation-amplitude",
        "0.005",
        "--corrugation-wavelength",
        "0.1",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(
        o.stdout.trim(),
        format!("plot written to {}", out.display())
    );
    let svg = std::fs::read_to_string(&out).unwrap();
    for text in [
        "the rod at the slips over the surface",
        "surface (η = 0.75 from the tips)",
        "rod just before a slip",
        "rod just after a slip",
        "tip where it slips (15)",
        "moment at the foot (the foot at x = d)",
        "slip (15)",
    ] {
        assert!(svg.contains(text), "{text}");
    }
    let e = bad(
        &[
            "plot",
            fixtures.join("drag_corrugated.csv").to_str().unwrap(),
            "--aligned",
        ],
        2,
    );
    assert!(e.contains("--shapes"), "{e}");
}

#[test]
fn a_handover_to_the_own_shooter_is_said() {
    // A trapped start multiple shooting cannot take (docs/robustness.md, third grid): `scan`
    // warns and names the method that ran; a sweep row carries it in `method`.
    let scene = [
        "--eta",
        "0.55",
        "--precurvature",
        "0.3",
        "--precurvature-slope",
        "-0.2",
        "--surface-angle",
        "0.2",
        "--method",
        "multiple-shooting",
    ];
    let dir = tmpdir("handover");
    let out = dir.join("scan.csv");
    let mut args = vec!["scan", "--out", out.to_str().unwrap()];
    args.extend(scene);
    let o = ok(&args);
    assert!(
        o.stderr.contains("the scan ran on the rod's own shooter"),
        "{}",
        o.stderr
    );
    assert!(o.stdout.contains("(shooting)"), "{}", o.stdout);
    let mut args = vec!["sweep", "--points", "11"];
    args.extend(scene);
    let o = ok(&args);
    let (h, rows) = csv(&o.stdout);
    let m = h.iter().position(|c| c == "method").unwrap();
    let s = h.iter().position(|c| c == "stop_reason").unwrap();
    assert_eq!(rows.len(), 1);
    assert_eq!(
        (rows[0][m].as_str(), rows[0][s].as_str()),
        ("shooting", "contact_change")
    );
}

/// `vibrissa modes`: the uniform clamped rod's frequencies β_n² (cos β cosh β = −1, Blevins,
/// *Formulas for natural frequency and mode shape*, table 8-1), pinned `tan β = tanh β`; a
/// compressive tip load beyond Euler's π²/4 is unstable (ω² < 0, `stable` 0, ω empty); bad
/// values are one line on stderr.
#[test]
fn modes_of_the_uniform_rod() {
    let o = ok(&["modes"]);
    let (h, rows) = csv(&o.stdout);
    assert_eq!(h, ["n", "omega2", "omega", "stable"]);
    assert_eq!(rows.len(), 3);
    for (r, beta) in rows
        .iter()
        .zip([1.87510406871196f64, 4.69409113297418, 7.85475743823761])
    {
        close(
            col(&h, r, "omega"),
            beta * beta,
            1e-10 * beta * beta,
            "omega",
        );
        assert_eq!(r[3], "1");
    }
    let o = ok(&["modes", "--tip", "pinned", "--count", "1"]);
    let (h, rows) = csv(&o.stdout);
    let b = 3.92660231204792f64;
    close(
        col(&h, &rows[0], "omega"),
        b * b,
        1e-10 * b * b,
        "pinned omega",
    );
    let o = ok(&["modes", "--fy", "-2.6", "--count", "1"]);
    let (_, rows) = csv(&o.stdout);
    assert!(rows[0][1].parse::<f64>().unwrap() < 0.0, "{:?}", rows[0]);
    assert_eq!((rows[0][2].as_str(), rows[0][3].as_str()), ("", "0"));
    let e = bad(&["modes", "--count", "0"], 2);
    assert!(e.contains("--count"), "{e}");
    let e = bad(&["modes", "--tip", "sliding", "--tip-angle", "2"], 2);
    assert!(e.contains("--tip-angle"), "{e}");
    let o = ok(&["modes", "--json", "--count", "1", "--points", "5"]);
    let v: serde_json::Value = serde_json::from_str(&o.stdout).unwrap();
    assert_eq!(v["modes"][0]["shape"].as_array().unwrap().len(), 5);
    assert_eq!(v["stable"], true);
}

/// `vibrissa dynamics drag`: one row per time step from the pressed start (N = 2.8266222292,
/// the scan's f0, docs/reference.md; the tip stuck where it was pressed), the foot at d_max at
/// the end; `--json` the library's result; a bad value or a round tip is one line, exit 2
/// (surfaces: `dynamics_drag_over_a_corrugation`).
#[test]
fn dynamics_drag_rows() {
    let args = [
        "dynamics", "drag", "--speed", "0.1", "--d-max", "0.003", "--dt", "0.05",
    ];
    let o = ok(&args);
    let (h, rows) = csv(&o.stdout);
    assert_eq!(h[..3], ["t", "d", "tip_x"]);
    assert_eq!(h.last().unwrap(), "event");
    assert_eq!(rows.len(), 14);
    close(col(&h, &rows[0], "normal"), 2.8266222292, 1e-9, "normal");
    close(col(&h, &rows[13], "d"), 0.003, 1e-15, "d");
    for r in &rows {
        assert_eq!(r[6], "stuck");
        close(
            col(&h, r, "tip_x"),
            col(&h, &rows[0], "tip_x"),
            1e-9,
            "tip_x",
        );
    }
    let mut j = args.to_vec();
    j.push("--json");
    let v: serde_json::Value = serde_json::from_str(&ok(&j).stdout).unwrap();
    assert_eq!(v["samples"].as_array().unwrap().len(), 14);
    assert_eq!(v["stop"]["reason"], "d_max");
    let e = bad(&["dynamics", "drag", "--speed", "-1"], 2);
    assert!(e.contains("speed"), "{e}");
    // a round tip needs internal damping (its friction moment makes the undamped rod's short
    // waves unstable); with it, its centre runs on the surface lowered by the radius
    let e = bad(&["dynamics", "drag", "--tip-radius", "0.01"], 2);
    assert!(
        e.contains("internal damping") && e.contains("round tip"),
        "{e}"
    );
    let disk = [
        "dynamics",
        "drag",
        "--tip-radius",
        "0.02",
        "--internal-damping",
        "1e-4",
        "--dt",
        "0.05",
        "--d-max",
        "0.003",
    ];
    let (h, rows) = csv(&ok(&disk).stdout);
    for r in &rows {
        close(col(&h, r, "tip_y"), 0.73, 1e-9, "disk centre's height");
        assert!(col(&h, r, "normal") > 0.0);
    }
}

/// `vibrissa dynamics drag --foot-table FILE --whisk A,F`: the column `theta` after `d` with the
/// support's turn `A (1 − cos 2πFt)/2` on every row (a negative A turns it the other way and is
/// taken without `=`), the foot where the table puts it, the stop `table_end`; the table's flag
/// conflicts with `--d-max`.
#[test]
fn dynamics_drag_whisk_columns() {
    let d = tmpdir("whisk");
    let table = d.join("foot.csv");
    std::fs::write(&table, "t,d\n0,0\n0.3,0.002\n").unwrap();
    let t = table.to_str().unwrap();
    let args = [
        "dynamics",
        "drag",
        "--foot-table",
        t,
        "--whisk",
        "-0.02,0.5",
        "--dt",
        "0.05",
    ];
    let o = ok(&args);
    let (h, rows) = csv(&o.stdout);
    assert_eq!(h[..4], ["t", "d", "theta", "tip_x"]);
    assert_eq!(rows.len(), 7);
    for r in &rows {
        let time = col(&h, r, "t");
        let want = -0.02 * (1.0 - (std::f64::consts::TAU * 0.5 * time).cos()) / 2.0;
        close(col(&h, r, "theta"), want, 1e-15, "theta");
    }
    close(col(&h, &rows[6], "d"), 0.002, 1e-15, "d");
    let mut j = args.to_vec();
    j.push("--json");
    let v: serde_json::Value = serde_json::from_str(&ok(&j).stdout).unwrap();
    assert_eq!(v["stop"]["reason"], "table_end");
    let e = bad(
        &["dynamics", "drag", "--foot-table", t, "--d-max", "0.1"],
        2,
    );
    assert!(e.contains("--foot-table") && e.contains("--d-max"), "{e}");
}

/// `dynamics drag` over a corrugation from the texture flags: the tip's rows on the surface
/// `0.75 + A sin(2πx/W)` (1e-9), each row's contact pushed; where the rod's end lies down on
/// the surface (the event `side_contact`) the rows after it are a side's (`side_stuck`, its
/// place in `side_s, side_x, side_y` on the surface, the columns empty before), and where that
/// side has slid until its contact reaches the tip the tip takes the contact over (the event
/// `to_tip`; its rows the tip's, sliding, on the surface, the side's columns empty), exit 0;
/// a start with two crests under the rod is one line and exit 1.
#[test]
fn dynamics_drag_over_a_corrugation() {
    let corr = |a: &'static str, w: &'static str, d_max: &'static str| {
        [
            "dynamics",
            "drag",
            "--speed",
            "0.05",
            "--dt",
            "0.02",
            "--d-max",
            d_max,
            "--corrugation-amplitude",
            a,
            "--corrugation-wavelength",
            w,
        ]
    };
    let o = ok(&corr("0.003", "0.1", "0.013"));
    let (h, rows) = csv(&o.stdout);
    let surface = |x: f64| 0.75 + 0.003 * (std::f64::consts::TAU * x / 0.1).sin();
    for r in &rows {
        close(
            col(&h, r, "tip_y"),
            surface(col(&h, r, "tip_x")),
            1e-9,
            "tip_y",
        );
        assert!(col(&h, r, "normal") > 0.0);
    }
    assert!(rows.iter().any(|r| r.last().unwrap() == "slip"));
    let o = ok(&corr("0.02", "0.2", "0.002"));
    let (h, rows) = csv(&o.stdout);
    let surface = |x: f64| 0.75 + 0.02 * (std::f64::consts::TAU * x / 0.2).sin();
    let lies = rows
        .iter()
        .position(|r| r.last().unwrap() == "side_contact")
        .unwrap();
    assert!(lies + 1 < rows.len());
    let state = h.iter().position(|c| c == "state").unwrap();
    for r in &rows[lies + 1..] {
        assert_eq!(r[state], "side_stuck");
        close(
            col(&h, r, "side_y"),
            surface(col(&h, r, "side_x")),
            1e-9,
            "side_y",
        );
        assert!(col(&h, r, "side_s") < 1.0 && col(&h, r, "normal") > 0.0);
    }
    for r in &rows[..=lies] {
        assert_eq!(r[h.iter().position(|c| c == "side_s").unwrap()], "");
    }
    assert!(
        o.stderr.is_empty() || !o.stderr.contains("stopped early"),
        "{}",
        o.stderr
    );
    // (its side slips, slides, and its contact reaches the tip, which slides on)
    let o = ok(&corr("0.02", "0.2", "0.012"));
    assert!(!o.stderr.contains("stopped early"), "{}", o.stderr);
    let (h, rows) = csv(&o.stdout);
    let back = rows
        .iter()
        .position(|r| r.last().unwrap() == "to_tip")
        .unwrap();
    assert_eq!(rows[back][state], "side_sliding_forward");
    assert!(back + 1 < rows.len());
    for r in &rows[back + 1..] {
        assert_eq!(r[state], "sliding_forward");
        assert_eq!(r[h.iter().position(|c| c == "side_s").unwrap()], "");
        close(
            col(&h, r, "tip_y"),
            surface(col(&h, r, "tip_x")),
            1e-9,
            "tip_y",
        );
    }
    let mut taper = corr("0.001", "0.02", "0.001").to_vec();
    taper.extend(["--taper", "0.3"]);
    let e = bad(&taper, 1);
    assert!(e.contains("side+side"), "{e}");
}

/// `dynamics drag` with the scene's `[friction]` table along x: the first slip at μs of the
/// stuck tip's x (0.5 + 0.5 (x − 0.55) here), every sliding row at `T = μk(x) N` of its own
/// x; `--mu-s`, `--mu-k` replace the texture (the rows of the drag without one).
#[test]
fn dynamics_drag_on_a_friction_table() {
    let d = tmpdir("friction_table");
    let scene = d.join("table.toml");
    std::fs::write(
        &scene,
        "eta = 0.75\n[friction]\nkind = \"table\"\nx = [0.55, 0.75]\nmu_s = [0.5, 0.6]\n\
         mu_k = [0.3, 0.45]\n",
    )
    .unwrap();
    let sc = scene.to_str().unwrap();
    let args = [
        "dynamics", "drag", "--scene", sc, "--speed", "0.05", "--dt", "0.02", "--d-max", "0.03",
    ];
    let (h, rows) = csv(&ok(&args).stdout);
    let slip = rows.iter().find(|r| r.last().unwrap() == "slip").unwrap();
    let x = col(&h, slip, "tip_x");
    let ratio = col(&h, slip, "tangential") / col(&h, slip, "normal");
    close(ratio, 0.5 + 0.5 * (x - 0.55), 1e-9, "slip's T/N");
    let mut sliding = 0;
    let state = h.iter().position(|c| c == "state").unwrap();
    for r in rows.iter().filter(|r| r[state] == "sliding_forward") {
        let mu_k = 0.3 + 0.75 * (col(&h, r, "tip_x") - 0.55);
        close(
            col(&h, r, "tangential") / col(&h, r, "normal"),
            mu_k,
            1e-9,
            "sliding T/N",
        );
        sliding += 1;
    }
    assert!(sliding > 5, "{sliding}");
    let mut flags = args.to_vec();
    flags.extend(["--mu-s", "0.5", "--mu-k", "0.3"]);
    let plain = [
        "dynamics", "drag", "--speed", "0.05", "--dt", "0.02", "--d-max", "0.03",
    ];
    assert_eq!(ok(&flags).stdout, ok(&plain).stdout);
}

/// `scan --modes`: the lowest ω² of each row with the tip stuck, positive on the rows of the
/// paper's rod at η = 0.95 and 0 (to 1e-6) at the fold in d where the scan stops; without the
/// flag the columns are unchanged.
#[test]
fn scan_modes_column() {
    let args = ["scan", "--eta", "0.95", "--d-max", "0.6", "--points", "7"];
    let (h0, _) = csv(&ok(&args).stdout);
    assert!(!h0.iter().any(|c| c == "omega1_sq"));
    let mut with = args.to_vec();
    with.push("--modes");
    let (h, rows) = csv(&ok(&with).stdout);
    assert_eq!(h.len(), h0.len() + 1);
    assert_eq!(h[h.len() - 2], "omega1_sq");
    assert_eq!(h.last().unwrap(), "event");
    let (last, rest) = rows.split_last().unwrap();
    for r in rest {
        assert!(col(&h, r, "omega1_sq") > 0.0, "{r:?}");
    }
    assert_eq!(last.last().unwrap(), "fold_in_d");
    assert!(col(&h, last, "omega1_sq").abs() <= 1e-6, "{last:?}");
}

/// `vibrissa modes` on a scene with dimensions adds the frequency in Hz: the textbook cantilever
/// `f₁ = β₁²/(2π) √(EI/(ρA L⁴))` (Blevins, table 8-1) with `I = πd⁴/64`, `A = πd²/4` and
/// keratin's ρ = 1250 kg/m³.
#[test]
fn modes_in_hertz() {
    let o = ok(&[
        "modes",
        "--count",
        "1",
        "--length-mm",
        "45",
        "--youngs-modulus-gpa",
        "3.3",
        "--base-diameter-um",
        "180",
    ]);
    let (h, rows) = csv(&o.stdout);
    assert_eq!(h.last().unwrap(), "f_Hz");
    let (l, d, e, rho) = (0.045f64, 180e-6f64, 3.3e9, 1250.0);
    let (i, a) = (PI * d.powi(4) / 64.0, PI * d * d / 4.0);
    let f1 = 1.87510406871196f64.powi(2) / (2.0 * PI) * (e * i / (rho * a * l.powi(4))).sqrt();
    close(col(&h, &rows[0], "f_Hz"), f1, 1e-10 * f1, "f_Hz");
}
