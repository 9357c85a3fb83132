//! Every numeric flag of every command takes negative values in every spelling Rust's `f64`
//! parser accepts (`-1e-3`, `-.5`, `-5e-1`, `-0`, `-inf`, lists `-1,0,1`, ranges `-0.1:0.1:3`)
//! without `=`. The flags are listed from the program's own clap command (src/cli.rs, included
//! here), so a new numeric flag is covered without editing this test.

#[allow(dead_code)]
#[path = "../src/number_text.rs"]
mod number_text;

#[allow(dead_code)]
#[path = "../src/cli.rs"]
mod cli;

mod common;
use common::*;

/// Arguments that make each command cheap and valid, by flag (dropped when that flag, or one
/// that conflicts with it, is the one tested).
fn base(cmd: &str) -> Vec<(&'static str, &'static str)> {
    match cmd {
        "solve" => vec![("--alpha", "-0.3"), ("--phi1", "0.3")],
        "scan" => vec![("--points", "3"), ("--d-max", "0.01")],
        // (a surface inclined by −1e-3 has the pressed rod lean left, its measurable range
        // ending at lift-off, d = 0.014: a d0 inside every scene's range)
        "infer" => vec![("--d0", "0.005"), ("--points", "5")],
        // --dry-run checks every value (grid included) without solving
        "sweep" => vec![("--dry-run", ""), ("--points", "3")],
        "figures" => vec![("--only", "3")],
        "whisk" => vec![("--peg", "0.1,0.4"), ("--points", "3")],
        "locate" => vec![("--m-base", "0.1"), ("--fx", "-0.2"), ("--fy", "0")],
        "drag" => vec![
            ("--mu-s", "0.5"),
            ("--mu-k", "0.3"),
            ("--points", "3"),
            ("--d-max", "0.01"),
        ],
        // (made by `vibrissa drag --mu-s 0.5 --mu-k 0.3 --d-max 0.04 --points 2`: two slips)
        "fit" => vec![
            ("--trace", "tests/fixtures/drag/trace.csv"),
            ("--places-only", ""),
        ],
        // the file to draw (cargo runs tests in the package directory)
        "plot" => vec![
            ("tests/fixtures/plot/shapes.csv", ""),
            ("--out", "/dev/null"),
        ],
        _ => vec![],
    }
}

/// Flags that cannot go together with the tested one.
fn conflicts(flag: &str) -> &'static [&'static str] {
    match flag {
        "--eta" => &["--phi1"],
        "--phi1" => &["--eta"],
        _ => &[],
    }
}

/// Negative spellings for a flag's value type.
fn spellings(a: &clap::Arg) -> &'static [&'static str] {
    let t = a.get_value_parser().type_id();
    if t == std::any::TypeId::of::<u32>() {
        &["-1", "-0", "-1e-3", "-.5"]
    } else if t == std::any::TypeId::of::<number_text::Axis>() {
        &["-0.1:0.1:3", "-1,0,1", "-.5", "-1e-3", "-5e-1,-.25", "-inf"]
    } else if t == std::any::TypeId::of::<cli::Shard>() {
        &["-1/3", "-1"]
    } else {
        &["-1e-3", "-.5", "-5e-1", "-0", "-inf", "-1", "-1E3", "-0.5"]
    }
}

#[test]
fn every_numeric_flag_takes_every_negative_spelling() {
    let d = tmpdir("numeric");
    let shapes = d.join("shapes.csv");
    let shapes = shapes.to_str().unwrap();
    let cmd = cli::command();
    let mut tested = 0;
    let mut flags = Vec::new();
    for sub in cmd.get_subcommands() {
        let name = sub.get_name();
        for a in sub.get_arguments().filter(|a| cli::is_numeric(a)) {
            let long = format!("--{}", a.get_long().unwrap());
            flags.push(format!("{name} {long}"));
            for v in spellings(a) {
                let mut args: Vec<String> = vec![name.to_string()];
                for (f, val) in base(name) {
                    if f == long || conflicts(&long).contains(&f) {
                        continue;
                    }
                    args.push(f.to_string());
                    if !val.is_empty() {
                        args.push(val.to_string());
                    }
                }
                // --shape-points needs its file
                if long == "--shape-points" {
                    args.push(
                        if name == "solve" {
                            "--shape-out"
                        } else {
                            "--shapes"
                        }
                        .into(),
                    );
                    args.push(shapes.into());
                }
                args.push(long.clone());
                args.push(v.to_string());
                let argv: Vec<&str> = args.iter().map(String::as_str).collect();
                let o = run(&argv);
                let what = format!("vibrissa {}", args.join(" "));
                assert!(!o.stderr.contains("panicked"), "{what}: {}", o.stderr);
                assert!(!o.stdout.contains("NaN"), "{what}: {}", o.stdout);
                // the value reached the flag: either accepted, or refused by the flag's own
                // check, naming the flag (or the quantity) -- never "unexpected argument"
                if o.code != 0 {
                    let lines: Vec<&str> = o.stderr.lines().collect();
                    assert_eq!(lines.len(), 1, "{what}: {:?}", o.stderr);
                    let l = lines[0];
                    assert!(l.starts_with("error: "), "{what}: {l}");
                    assert!(
                        !l.contains("unexpected argument") && !l.contains("found"),
                        "{what}: the value did not reach the flag: {l}"
                    );
                    let id = long.trim_start_matches("--").replace('-', "_");
                    assert!(
                        l.contains(&long) || l.contains(&id),
                        "{what}: the message does not name {long}: {l}"
                    );
                    assert!(o.code == 1 || o.code == 2, "{what}: exit {}", o.code);
                }
                tested += 1;
            }
        }
    }
    // every command has numeric flags, and the list is not trivially short
    for c in ["solve", "scan", "infer", "sweep", "figures", "plot"] {
        assert!(
            flags.iter().any(|f| f.starts_with(&format!("{c} "))),
            "{c}: no numeric flag found in {flags:?}"
        );
    }
    assert!(flags.len() >= 40, "{flags:?}");
    assert!(tested >= 250, "{tested}");
}

/// Negative values that are valid are accepted and used (not only parsed).
#[test]
fn negative_values_are_used() {
    // -1e-3 as alpha: the force leans slightly clockwise, fx = f sin(alpha) < 0
    let o = ok(&[
        "solve", "--alpha", "-1e-3", "--phi1", ".3", "--method", "analytic",
    ]);
    let (h, rows) = csv(&o.stdout);
    assert_eq!(col(&h, &rows[0], "alpha"), -1e-3);
    assert!(col(&h, &rows[0], "fx") < 0.0);
    let o = ok(&[
        "solve", "--alpha", "-.5", "--phi1", "3e-1", "--method", "analytic",
    ]);
    let (h, rows) = csv(&o.stdout);
    assert_eq!(col(&h, &rows[0], "alpha"), -0.5);
    // a negative list and a negative range reach the grid exactly
    let o = ok(&[
        "sweep",
        "--surface-angle",
        "-0.1:0.1:3",
        "--precurvature",
        "-1,0,1",
        "--points",
        "3",
        "--d-max",
        "0.01",
    ]);
    let (h, rows) = csv(&o.stdout);
    assert_eq!(rows.len(), 9);
    let beta: Vec<f64> = rows.iter().map(|r| col(&h, r, "surface_angle")).collect();
    let k0: Vec<f64> = rows.iter().map(|r| col(&h, r, "precurvature")).collect();
    assert_eq!(beta[..3], [-0.1, 0.0, 0.1]);
    assert_eq!([k0[0], k0[3], k0[6]], [-1.0, 0.0, 1.0]);
}

/// The same quantity has the same default in every command (scan and sweep once disagreed on
/// --points), and every scene-taking command has the Scene and Physical units sections.
#[test]
fn commands_agree_on_defaults_and_sections() {
    let cmd = cli::command();
    let default = |sub: &str, id: &str| -> Option<String> {
        let s = cmd.find_subcommand(sub).unwrap();
        let a = s.get_arguments().find(|a| a.get_id() == id)?;
        a.get_default_values()
            .first()
            .map(|v| v.to_string_lossy().into_owned())
    };
    for id in ["points", "d_max", "tol", "method"] {
        let vals: Vec<(String, Option<String>)> = ["scan", "infer", "sweep"]
            .iter()
            .map(|s| (s.to_string(), default(s, id)))
            .collect();
        assert!(
            vals.windows(2).all(|w| w[0].1 == w[1].1),
            "--{id} defaults differ: {vals:?}"
        );
    }
    for sub in ["solve", "scan", "infer", "sweep"] {
        let s = cmd.find_subcommand(sub).unwrap();
        for (heading, ids) in [
            (
                "Scene",
                &["scene", "taper", "precurvature", "support_compliance"][..],
            ),
            (
                "Physical units",
                &["length_mm", "youngs_modulus_gpa", "base_diameter_um"][..],
            ),
        ] {
            for id in ids {
                let a = s.get_arguments().find(|a| a.get_id() == *id);
                assert_eq!(
                    a.and_then(|a| a.get_help_heading()),
                    Some(heading),
                    "{sub} --{id}"
                );
            }
        }
    }
}
