//! Issue 33 in the program: the fit takes the drag's surface flags and is never confidently
//! wrong, every long run is bounded, every accepted input means something, the regressions of
//! the pressed start are fixed, and the point-object commands have their units and names.

mod common;
use common::*;

const CORRUGATED: &str =
    "eta = 0.75\n[surface]\nkind = \"sine\"\namplitude = 0.005\nwavelength = 0.1\n";

/// The trace (a drag over a corrugated surface, no noise) fitted with `--scene` and
/// with the `--corrugation-*` flags gives μs, μk to 1e-6 both ways; without them (a flat
/// surface) the fit warns and gives no standard error.
#[test]
fn fit_of_a_corrugated_trace() {
    let dir = tmpdir("fit-corrugated");
    let scene = dir.join("corr.toml");
    std::fs::write(&scene, CORRUGATED).unwrap();
    let trace = dir.join("tr.csv");
    let (s, t) = (scene.to_str().unwrap(), trace.to_str().unwrap());
    ok(&[
        "drag", "--mu-s", "0.5", "--mu-k", "0.3", "--scene", s, "--d-max", "0.3", "--points", "61",
        "--out", t,
    ]);
    let flags = [
        "--corrugation-amplitude",
        "0.005",
        "--corrugation-wavelength",
        "0.1",
    ];
    for extra in [&["--scene", s][..], &flags[..]] {
        let mut args = vec!["fit", "--trace", t, "--json"];
        args.extend(extra);
        let o = ok(&args);
        let v = json(&o.stdout);
        for (k, want) in [(0, 0.5), (1, 0.3)] {
            let p = &v["params"][k];
            close(p["value"].as_f64().unwrap(), want, 1e-6, "the coefficient");
            assert!(p["std_error"].as_f64().unwrap() < 1e-6, "{p}");
        }
        assert!(v["message"].is_null(), "{}", o.stdout);
        assert_eq!(v["consistency"]["consistent"], true);
    }
    let o = ok(&["fit", "--trace", t]);
    assert!(
        o.stderr.contains("tips lie off a straight line"),
        "{}",
        o.stderr
    );
    assert!(
        o.stderr.contains("does not fit the whole trace"),
        "{}",
        o.stderr
    );
    let (h, rows) = csv(&o.stdout);
    let se = h.iter().position(|c| c == "std_error").unwrap();
    assert!(rows.iter().all(|r| r[se].is_empty()), "{}", o.stdout);
    // a row cut to 5 of its 14 fields is refused, not read as missing values
    let text = std::fs::read_to_string(&trace).unwrap();
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    lines[3] = lines[3].split(',').take(5).collect::<Vec<_>>().join(",");
    std::fs::write(&trace, lines.join("\n") + "\n").unwrap();
    let e = bad(&["fit", "--trace", t, "--scene", s], 2);
    assert!(e.contains("line 4 has 5 fields, the header 14"), "{e}");
}

/// Values that were accepted and then ran without end or meant nothing: refused, or the run
/// ends at once with the reason.
#[test]
fn long_runs_are_bounded_and_inputs_meaningful() {
    let dir = tmpdir("limits");
    let file = |name: &str, text: &str| {
        let p = dir.join(name);
        std::fs::write(&p, text).unwrap();
        p.to_str().unwrap().to_string()
    };
    // kinetic friction equal to static in a file, as the flags refuse it
    let f = file(
        "eq.toml",
        "[friction]\nkind = \"uniform\"\nmu_s = 0.5\nmu_k = 0.5\n",
    );
    let e = bad(&["drag", "--scene", &f, "--d-max", "0.1"], 2);
    assert!(
        e.contains("friction.mu_k = 0.5 is outside the valid range [0, mu_s = 0.5)"),
        "{e}"
    );
    // a texture finer than the march resolves
    let f = file(
        "fine.toml",
        "[friction]\nkind = \"patches\"\nperiod = 1e-9\nx = [0.0]\nmu_s = [0.5]\nmu_k = [0.3]\n",
    );
    let e = bad(&["drag", "--scene", &f, "--d-max", "0.1"], 2);
    assert!(
        e.contains("friction.period = 0.000000001 is outside the valid range [0.01, 1000]"),
        "{e}"
    );
    // kinetic friction a hair below static: the drag ends at its third slip, saying why (was
    // 100 000 slips of no length)
    let o = ok(&[
        "drag",
        "--mu-s",
        "0.5",
        "--mu-k",
        "0.4999999999",
        "--d-max",
        "0.3",
        "--points",
        "4",
        "--json",
    ]);
    let v = json(&o.stdout);
    assert_eq!(v["stop_reason"], "contact_change", "{}", o.stdout);
    assert!(v["cycles"].as_u64().unwrap() <= 3, "{}", o.stdout);
    assert!(o.stderr.contains("would exceed max_slips"), "{}", o.stderr);
    assert!(
        o.stderr.contains("kinetic friction this close to static"),
        "{}",
        o.stderr
    );
    // a threshold below the solver's noise in mu (the start's |mu| ~ 1e-22): the tip slips at
    // d = 0 (was: "locating the Slip(0) event: no sign change")
    let o = ok(&["scan", "--mu0", "1e-300", "--points", "5", "--json"]);
    let v = json(&o.stdout);
    assert_eq!(v["stop"]["reason"], "slip", "{}", o.stdout);
    assert_eq!(v["stop"]["d"], 0.0, "{}", o.stdout);
    let o = ok(&[
        "drag", "--mu-s", "1e-300", "--mu-k", "0", "--points", "5", "--json",
    ]);
    let v = json(&o.stdout);
    assert_eq!(v["stop"]["d"], 0.0, "{}", o.stdout);
    assert_eq!(v["slips"][0]["d"], 0.0, "{}", o.stdout);
    assert!(o.stderr.contains("the slips come 0 apart"), "{}", o.stderr);
    // a hinge (support compliance at its limit): the pressed start is past mu_s already, and
    // the drag ends at once, named (was: solver internals; then a snap at the first slip, d
    // 3.2e-12, found by the fold passage beyond the slip's end, where the tip pulled with
    // N = -81: the slip ends where mu_k holds it, after 1.9e-12, with N = 0.0017 > 0, and the
    // slips come that far apart)
    let o = ok(&[
        "drag",
        "--support-compliance",
        "1000",
        "--mu-s",
        "0.5",
        "--mu-k",
        "0.3",
        "--json",
    ]);
    let v = json(&o.stdout);
    assert!(v["stop"]["d"].as_f64().unwrap() < 1e-10, "{}", o.stdout);
    assert!(o.stderr.contains("would exceed max_slips"), "{}", o.stderr);
    // μs − μk = 0.2 is not what makes these slips short, and the stop does not say it is
    // (it did: "kinetic friction this close to static"); it says what each slip does
    assert!(!o.stderr.contains("kinetic friction"), "{}", o.stderr);
    assert!(
        o.stderr.contains("each slip moves the tip by") && o.stderr.contains("releases"),
        "{}",
        o.stderr
    );
    // a circle whose end lies before the pressed tip is refused (was replaced by its end
    // tangent without a word), and a drag stops where the tip leaves one
    let f = file(
        "circle.toml",
        "eta = 0.75\n[surface]\nkind = \"circle\"\nradius = 0.1\n",
    );
    let e = bad(
        &[
            "drag", "--scene", &f, "--mu-s", "0.5", "--mu-k", "0.3", "--d-max", "0.5",
        ],
        2,
    );
    assert!(e.contains("where the surface exists"), "{e}");
    let f = file(
        "circle2.toml",
        "eta = 0.75\n[surface]\nkind = \"circle\"\nradius = 0.5\nx0 = 0.25\n",
    );
    let o = ok(&[
        "drag", "--scene", &f, "--mu-s", "0.5", "--mu-k", "0.3", "--d-max", "0.5", "--points",
        "11", "--json",
    ]);
    assert!(
        o.stderr
            .contains("the tip left the surface at its end (x = 0.6035533905932737"),
        "{}",
        o.stderr
    );
}

/// The drag's slip cap is the program's to set: a cap of 3 ends the paper's drag after 3 slips,
/// by name and with how far it was from d_max, and the library's range is the flag's.
#[test]
fn the_slip_cap_ends_a_drag_by_name() {
    let o = ok(&[
        "drag",
        "--mu-s",
        "0.5",
        "--mu-k",
        "0.3",
        "--d-max",
        "1",
        "--max-slips",
        "3",
        "--json",
    ]);
    let v = json(&o.stdout);
    assert_eq!(v["cycles"], 3, "{}", o.stdout);
    assert!(o.stderr.contains("max_slips = 3 reached"), "{}", o.stderr);
    // the stop says how far the drag was from d_max: the slips' spacing and the count at it
    let d: Vec<f64> = (0..3)
        .map(|i| v["slips"][i]["d"].as_f64().unwrap())
        .collect();
    let spacing = (d[2] - d[0]) / 2.0;
    let ahead = ((1.0 - v["stop"]["d"].as_f64().unwrap()) / spacing).ceil();
    let said = format!(
        "the last slips came {} apart in d, so d_max = 1 needs about {ahead} more",
        vibrissa::limits::digits(spacing, 3)
    );
    assert!(o.stderr.contains(&said), "{said}: {}", o.stderr);
    for v in ["0", "1000001"] {
        let e = bad(
            &["drag", "--mu-s", "0.5", "--mu-k", "0.3", "--max-slips", v],
            2,
        );
        assert!(
            e.contains("--max-slips") && e.contains("[1, 1000000]"),
            "{e}"
        );
    }
}

/// The regressions of the pressed start: solve at alpha 0 on the flex branch (the closed form's
/// f = 27.42958391862498, `--method analytic`), and scans of tips far more flexible than the
/// foot. The rod tapered to 0.01 at η 0.97 had no start (its buckled start's Newton in f did not
/// converge), then started on its tenth buckling mode (nine flex points, unstable), the
/// bracket of its buckling load having stepped over the first nine; on its first mode (since
/// 2026-11-30, start.rs `first_buckling_below`) its soft tip turns into the surface while it is
/// pressed, a named limit of the point-contact model (the tip would lie down), as the rod
/// tapered to 0.04 did before; the rod tapered to 0.05 starts on its first mode.
#[test]
fn regressions_of_the_pressed_start() {
    for m in [
        "shooting",
        "multiple-shooting",
        "collocation",
        "collocation6",
    ] {
        let o = ok(&[
            "solve", "--alpha", "0", "--phi1", "0.3", "--branch", "flex", "--method", m,
        ]);
        let (h, rows) = csv(&o.stdout);
        close(col(&h, &rows[0], "f"), 27.42958391862498, 1e-8, m);
    }
    let e = bad(
        &["scan", "--taper", "0.01", "--eta", "0.97", "--points", "11"],
        1,
    );
    assert!(
        e.contains("no start") && e.contains("the tip would turn into the surface"),
        "{e}"
    );
    let o = ok(&["scan", "--taper", "0.05", "--eta", "0.97", "--points", "11"]);
    let (h, rows) = csv(&o.stdout);
    assert!(rows.len() >= 2, "{}", o.stdout);
    assert_eq!(col(&h, &rows[0], "flex"), 0.0, "{}", o.stdout);
    let o = ok(&[
        "scan", "--tol", "1e-2", "--taper", "0.1", "--eta", "0.6", "--points", "11",
    ]);
    assert_eq!(csv(&o.stdout).1.len(), 11, "{}", o.stdout);
}

/// The point-object commands: physical columns with a physical scene, a whisk's fold named as a
/// whisk's, surface flags refused, the one angle of `solve --peg` named as such.
#[test]
fn point_objects_have_units_and_names() {
    let sc = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/data/scenes/rat_mystacial_short.toml"
    );
    let o = ok(&["whisk", "--scene", sc, "--peg", "0.4,0.7", "--points", "5"]);
    let (h, _) = csv(&o.stdout);
    for c in ["f_N", "fx_N", "fy_N", "m_base_Nm"] {
        assert!(h.iter().any(|x| x == c), "{h:?}");
    }
    let o = ok(&[
        "locate", "--scene", sc, "--theta", "0.2", "--m-base", "-0.3", "--fx", "0.5", "--fy",
        "-0.2",
    ]);
    let (h, _) = csv(&o.stdout);
    assert!(
        h.iter().any(|x| x == "x_mm") && h.iter().any(|x| x == "y_mm"),
        "{h:?}"
    );
    let e = bad(&["whisk", "--peg", "0.5,0.6", "--surface-angle", "0.1"], 2);
    assert!(e.contains("--surface-angle does not apply to whisk"), "{e}");
    let e = bad(&["whisk", "--peg", "0.5,0.6", "--contact", "tip"], 2);
    assert!(e.contains("--contact does not apply to whisk"), "{e}");
    let e = bad(&["solve", "--peg", "0.5,0.6", "--theta=-1"], 2);
    assert!(e.contains("beyond theta = -1"), "{e}");
}

/// `plot --x` on a file whose plot has its own axes is refused, naming the column; a drag's
/// five panels are drawn on two rows of three (was one row, 2600 × 480 px); a corrugated drag's
/// rods stand on the surface the tips touched, not on a flat line.
#[test]
fn plot_names_the_column_and_lays_out_panels() {
    let dir = tmpdir("plot-limits");
    let scene = dir.join("corr.toml");
    std::fs::write(&scene, CORRUGATED).unwrap();
    let (tr, sh) = (dir.join("tr.csv"), dir.join("sh.csv"));
    ok(&[
        "drag",
        "--mu-s",
        "0.5",
        "--mu-k",
        "0.3",
        "--scene",
        scene.to_str().unwrap(),
        "--d-max",
        "0.1",
        "--points",
        "21",
        "--out",
        tr.to_str().unwrap(),
        "--shapes",
        sh.to_str().unwrap(),
    ]);
    let e = bad(&["plot", tr.to_str().unwrap(), "--x", "bogus"], 2);
    assert!(e.contains("--x bogus: no such column in the file"), "{e}");
    let svg = dir.join("tr.svg");
    ok(&[
        "plot",
        tr.to_str().unwrap(),
        "--shapes",
        sh.to_str().unwrap(),
        "--out",
        svg.to_str().unwrap(),
    ]);
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(
        text.starts_with("<svg width=\"1560\" height=\"920\""),
        "{}",
        &text[..80]
    );
    assert!(text.contains("where the tip touched"));
}
