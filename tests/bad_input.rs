//! The bad-input study kept as a test: bad or extreme invocations of every command, each
//! asserting the error contract: exit code 2 (bad input) or 1 (solver or I/O failure), exactly
//! one line on stderr starting with `error: `, no panic, no NaN on stdout, and no file changed
//! or left behind (a pre-existing `precious.csv` keeps its bytes; no temporary remains).

mod common;
use common::*;

/// Scene files used by the table (name, text).
const SCENES: &[(&str, &str)] = &[
    (
        "uni_ratio.toml",
        "stiffness = { kind = \"uniform\", ratio = 0.5 }\n",
    ),
    (
        "none_k0.toml",
        "precurvature = { kind = \"none\", k0 = -0.5 }\n",
    ),
    (
        "none_k0_table.toml",
        "eta = 0.7\n[precurvature]\nkind = \"none\"\nk0 = -0.5\n",
    ),
    (
        "taper_b.toml",
        "stiffness = { kind = \"taper\", ratio = 0.5, b = [1.0] }\n",
    ),
    (
        "linear_s.toml",
        "precurvature = { kind = \"linear\", k0 = 0.1, s = [0.0, 1.0] }\n",
    ),
    (
        "table_k.toml",
        "stiffness = { kind = \"table\", s = [0.0, 1.0], b = [1.0, 1.0], k = [0.0, 0.0] }\n",
    ),
    ("typo.toml", "eta = 0.7\nsuport_compliance = 0.1\n"),
    ("eta_low.toml", "eta = 0.3\n"),
    ("eta_str.toml", "eta = \"high\"\n"),
    (
        "ratio0.toml",
        "stiffness = { kind = \"taper\", ratio = 0 }\n",
    ),
    (
        "ratio_huge.toml",
        "stiffness = { kind = \"taper\", ratio = 1e300 }\n",
    ),
    (
        "k0_huge.toml",
        "precurvature = { kind = \"linear\", k0 = 1e300 }\n",
    ),
    ("c_neg.toml", "support_compliance = -1.0\n"),
    ("c_huge.toml", "support_compliance = 1e300\n"),
    ("beta.toml", "surface_angle = 1.0\n"),
    (
        "phys_neg.toml",
        "[physical]\nlength_mm = -30.0\nyoungs_modulus_gpa = 3.3\nbase_diameter_um = 100.0\n",
    ),
    (
        "phys_tiny.toml",
        "[physical]\nlength_mm = 1e-200\nyoungs_modulus_gpa = 3.3\nbase_diameter_um = 100.0\n",
    ),
    ("phys_missing.toml", "[physical]\nlength_mm = 30.0\n"),
    (
        "table_unsorted.toml",
        "stiffness = { kind = \"table\", s = [0.0, 0.7, 0.5, 1.0], b = [1.0, 1.0, 1.0, 1.0] }\n",
    ),
    (
        "table_b_huge.toml",
        "stiffness = { kind = \"table\", s = [0.0, 1.0], b = [1.0, 1e300] }\n",
    ),
    ("kind_unknown.toml", "stiffness = { kind = \"conical\" }\n"),
    ("no_kind.toml", "stiffness = { ratio = 0.5 }\n"),
    ("not_toml.toml", "eta = = 1\n"),
    ("nan.toml", "eta = nan\n"),
];

/// `code | arguments | text the message must contain (optional)`; run in a directory holding
/// `precious.csv` and the scene files above.
const CASES: &str = r#"
# solve: out-of-range, non-finite and huge values, named by the flag typed
2 | solve --alpha -inf --phi1 0.3 | --alpha
2 | solve --alpha -1E3 --phi1 0.3 | --alpha -1000 is outside the valid range (-pi/2, pi/2)
2 | solve --alpha -1e300 --phi1 0.3 | -1e300
2 | solve --alpha -1.5708 --phi1 0.3 | (-1.570796
2 | solve --alpha 1.5707963267948966 --phi1 0.3 | --alpha
2 | solve --alpha -2 --phi1 0.3 | (-pi/2, pi/2)
2 | solve --alpha -0.3 --phi1 -4 | --phi1
2 | solve --alpha -0.3 --phi1 -inf | --phi1
2 | solve --alpha -0.3 --phi1 1e300 | --phi1 1e300
2 | solve --alpha -0.3 --eta -1 | --eta
2 | solve --alpha -0.3 --eta 1 | --eta
2 | solve --alpha -0.3 --eta 1e-300 --phi1 0.3 | cannot be used with
2 | solve --alpha -0.3 --phi1 0.3 --tol -1e-10 | --tol
2 | solve --alpha -0.3 --phi1 0.3 --tol 0.5 | [1e-15, 0.01]
2 | solve --alpha -0.3 --phi1 0.3 --tol 1e-300 | --tol 1e-300
2 | solve --alpha -0.3 --phi1 0.3 --tol 0 | --tol
2 | solve --alpha -0.3 --phi1 0.3 --tol inf | --tol
2 | solve --alpha -0.3 --phi1 0.3 --shape-points -1 --shape-out s.csv | --shape-points
2 | solve --alpha -0.3 --phi1 0.3 --shape-points 1 --shape-out s.csv | [2, 1000000]
2 | solve --alpha -0.3 --phi1 0.3 --shape-points 5 | --shape-out
2 | solve --alpha -0.3 --phi1 0.3 --shape-out - | stdout
2 | solve --alpha -0.3 --phi1 0.3 --shape-out . | directory
2 | solve --alpha -0.3 --phi1 0.3 --taper -0.5 | --taper -0.5
2 | solve --alpha -0.3 --phi1 0.3 --taper 0 | --taper 0 is outside
2 | solve --alpha -0.3 --phi1 0.3 --taper 1e-300 | --taper 1e-300
2 | solve --alpha -0.3 --phi1 0.3 --taper 1.5 | [0.01, 1]
2 | solve --alpha -0.3 --phi1 0.3 --precurvature 1e300 | --precurvature 1e300
2 | solve --alpha -0.3 --phi1 0.3 --precurvature -5e1 | --precurvature -50
2 | solve --alpha -0.3 --phi1 0.3 --precurvature-slope -7 | --precurvature-slope
2 | solve --alpha -0.3 --phi1 0.3 --precurvature 2 --precurvature-slope 2 | rest curvature at the tip
2 | solve --alpha -0.3 --phi1 0.3 --support-compliance -.5 | --support-compliance -0.5
2 | solve --alpha -0.3 --phi1 0.3 --support-compliance 1e300 | --support-compliance 1e300
2 | solve --alpha -0.3 --phi1 0.3 --support-compliance 1e6 | [0, 1000]
2 | solve --alpha -0.3 --phi1 0.3 --surface-angle 0.8 | (-pi/4, pi/4)
2 | solve --alpha -0.3 --phi1 0.3 --surface-angle -0.7853981633974483 | --surface-angle
2 | solve --alpha -0.3 --phi1 0.3 --length-mm 30 | all three
2 | solve --alpha -0.3 --phi1 0.3 --length-mm -30 --youngs-modulus-gpa 3.3 --base-diameter-um 100 | --length-mm -30
2 | solve --alpha -0.3 --phi1 0.3 --length-mm 1e-200 --youngs-modulus-gpa 3.3 --base-diameter-um 100 | overflow
2 | solve --alpha -0.3 --phi1 0.3 --length-mm 30 --youngs-modulus-gpa 1e300 --base-diameter-um 100 | overflow
2 | solve --alpha -0.3 --phi1 0.3 --length-mm 30 --youngs-modulus-gpa 3.3 --base-diameter-um 0 | --base-diameter-um 0
2 | solve --alpha -0.3 --phi1 0.3 --length-mm 30 --youngs-modulus-gpa 3.3 --base-diameter-um 1e-300 | vanish
2 | solve --alpha -0.3 --phi1 0.3 --length-mm 30 --youngs-modulus-gpa 3.3 --base-diameter-um inf | --base-diameter-um
2 | solve --alpha -0.3 --phi1 0.3 --method analytic --taper 0.5 | analytic
2 | solve --alpha -1 --phi1 0.3 --method analytic | valid range
2 | solve --alpha -0.2 --phi1 1.4 --method analytic | phi1
2 | solve --alpha -0.3 --phi1 0.3 --method newton | newton
2 | solve --alpha -0.3 --phi1 0.3 --branch sideways | sideways
2 | solve --alpha -0.3 | --phi1
2 | solve --phi1 0.3 | --alpha
2 | solve --alpha -0.3 --phi1 0.3 --eta 0.7 | cannot be used with
2 | solve --alpha abc --phi1 0.3 | 'abc' is not a number
2 | solve --alpha NaN --phi1 0.3 | --alpha
2 | solve --alpha nan --phi1 0.3 | --alpha
2 | solve --alpha 0x10 --phi1 0.3 | --alpha
2 | solve --alpha 1,2 --phi1 0.3 | --alpha
2 | solve --alpha 1e --phi1 0.3 | --alpha
2 | solve --alpha --phi1 0.3 | --alpha needs a value
2 | solve --alpha= --phi1 0.3 | --alpha
2 | solve --alpha -0.3 --phi1 0.3 --frobnicate | --frobnicate
2 | solve --alpha -0.3 --phi1 0.3 --scene missing.toml | missing.toml
2 | solve --alpha -0.3 --phi1 0.3 --scene . | scene file
2 | solve --alpha -0.3 --phi1 0.3 --scene ratio0.toml | stiffness.ratio = 0
2 | solve --alpha -0.3 --phi1 0.3 extra | extra
# scan
2 | scan --out - --json --points 3 | --out - with --json
2 | scan --json --out - --shapes precious.csv | same stdout
2 | scan --eta 0.456946581 --out precious.csv | (0.45694658104, 1)
2 | scan --eta 0.45694658104446 --out precious.csv | eta_ =
2 | scan --eta 1 --out precious.csv | --eta 1 is outside
2 | scan --eta -.5 --out precious.csv | --eta -0.5
2 | scan --eta 1e300 --out precious.csv | --eta 1e300
2 | scan --eta -1e-300 --out precious.csv | --eta -1e-300
2 | scan --eta -inf | --eta
2 | scan --d-max 0 --out precious.csv | --d-max 0
2 | scan --d-max -1e-3 | --d-max -0.001
2 | scan --d-max 2 | (0, 2)
2 | scan --d-max 1e300 | --d-max 1e300
2 | scan --d-max 1e300 --method analytic | --d-max 1e300
2 | scan --d-max inf --method analytic | --d-max
2 | scan --points 1 | --points
2 | scan --points -5 | --points
2 | scan --points 1.5 | --points
2 | scan --points 1000001 | [2, 1000000]
2 | scan --points 99999999999999999999 | --points
2 | scan --points 99999999999999999999999999999999999999999 | --points
2 | scan --mu0 -0.1 | --mu0 -0.1
2 | scan --mu0 -inf | --mu0
2 | scan --mu0 nan | --mu0
2 | scan --tol 1e-16 | --tol
2 | scan --tol 0.02 | --tol
2 | scan --shapes s.csv --shape-points 1 | --shape-points
2 | scan --shapes s.csv --shape-points 100001 | --shape-points
2 | scan --shape-points 10 | --shapes
2 | scan --points 2001 --shapes s.csv --shape-points 100000 | --points 2001 × --shape-points 100000
2 | scan --points 1000000 --shapes s.csv --shape-points 100 | memory
2 | scan --out x.csv --shapes x.csv | same file
2 | scan --out x.csv --shapes ./x.csv | same file
2 | scan --out precious.csv --shapes precious.csv | same file
2 | scan --out link_to_precious.csv --shapes precious.csv | same file
2 | scan --shapes - | stdout
2 | scan --out . | directory
2 | scan --out sub/ | not a file name
2 | scan --out "" | --out
1 | scan --points 3 --out nodir/x.csv --shapes precious.csv | nodir
1 | scan --points 3 --out precious.csv/x.csv | precious.csv/x.csv
1 | scan --points 3 --out /dev/full | --out /dev/full
1 | scan --points 3 --shapes /dev/full --out precious.csv | --shapes /dev/full
1 | scan --points 3 --out precious.csv --shapes /dev/full | /dev/full
2 | scan --taper 1e-300 --out precious.csv | --taper
2 | scan --taper 0 --out precious.csv | --taper 0
2 | scan --method analytic --taper 0.5 --out precious.csv | analytic
2 | scan --method analytic --support-compliance 0.1 | analytic
2 | scan --method analytic --surface-angle 0.1 | analytic
2 | scan --method analytic --eta 0.3 | --eta
2 | scan --scene uni_ratio.toml --out precious.csv | unknown key 'ratio'
2 | scan --scene none_k0.toml | unknown key 'k0'
2 | scan --scene none_k0_table.toml | line 4
2 | scan --scene taper_b.toml | unknown
2 | scan --scene linear_s.toml | unknown
2 | scan --scene table_k.toml | unknown
2 | scan --scene typo.toml | line 2
2 | scan --scene eta_low.toml | eta = 0.3
2 | scan --scene eta_str.toml | eta_str.toml
2 | scan --scene ratio0.toml | stiffness.ratio = 0
2 | scan --scene ratio_huge.toml | stiffness.ratio = 1e300
2 | scan --scene k0_huge.toml | precurvature.k0 = 1e300
2 | scan --scene c_neg.toml | support_compliance = -1
2 | scan --scene c_huge.toml | support_compliance = 1e300
2 | scan --scene beta.toml | surface_angle = 1
2 | scan --scene phys_neg.toml | physical.length_mm = -30
2 | scan --scene phys_tiny.toml | overflow
2 | scan --scene phys_missing.toml | phys_missing.toml
2 | scan --scene table_unsorted.toml | increasing
2 | scan --scene table_b_huge.toml | stiffness.b = 1e300
2 | scan --scene kind_unknown.toml | conical
2 | scan --scene no_kind.toml | kind
2 | scan --scene not_toml.toml | not_toml.toml
2 | scan --scene nan.toml | eta
2 | scan --scene missing.toml | missing.toml
2 | scan --scene ratio0.toml --taper 0.5 --precurvature 9 | --precurvature 9
2 | scan --precurvature 1 --scene ratio0.toml | stiffness.ratio
# the rest tip is at sin(2)/2 = 0.45 < 0.75: no pushed contact (a solver failure, exit 1)
2 | scan --precurvature -2 --points 3 --out precious.csv | does not reach the surface
# infer
2 | infer | --d0
2 | infer --d0 -0.1 | --d0 -0.1
2 | infer --d0 -inf | --d0
2 | infer --d0 0.6 | [0, 0.5]
2 | infer --d0 0.3 --method analytic | measurable range
2 | infer --d0 0.05 --d-max 0 | --d-max
2 | infer --d0 0.05 --d-max 1e300 --method analytic | --d-max 1e300
2 | infer --d0 0.05 --points 1 | --points
2 | infer --d0 0.05 --eta 0.3 | --eta 0.3
2 | infer --d0 0.05 --tol 1 | --tol
2 | infer --d0 0.05 --scene uni_ratio.toml | unknown key
2 | infer --d0 1e300 | --d0 1e300
# sweep
2 | sweep --eta 0.5:0.9 --out precious.csv | a:b:n
2 | sweep --eta 0.5:0.9:0 | --eta
2 | sweep --eta 0.5:0.9:-3 | --eta
2 | sweep --eta 0.5:0.9:1 | a = b
2 | sweep --eta 0.5:0.9:1e3 | point count
2 | sweep --eta 0.5:0.9:10000001 | [1, 10000000]
2 | sweep --eta a:b:3 | 'a' is not a number
2 | sweep --eta 0.5:inf:3 | finite
2 | sweep --eta 0.5,,0.6 | --eta
2 | sweep --eta= | empty
2 | sweep --eta 0.3,0.7 --out precious.csv | --eta 0.3
2 | sweep --eta 0.5:0.9:3:4 | --eta
2 | sweep --taper 0:1:3 | --taper 0
2 | sweep --taper -1,0.5 | --taper -1
2 | sweep --precurvature -1e300 | --precurvature -1e300
2 | sweep --precurvature -3,3 --precurvature-slope 1 | rest curvature at the tip
2 | sweep --precurvature-slope -7 | --precurvature-slope -7
2 | sweep --support-compliance -0.1:0.1:3 | --support-compliance -0.1
2 | sweep --support-compliance 1e6 | --support-compliance 1e6
2 | sweep --surface-angle -1:1:3 | --surface-angle -1
2 | sweep --tol 0 | --tol
2 | sweep --tol 1e-10,0.5 | --tol 0.5
2 | sweep --tol -1e-10 | --tol
2 | sweep --method newton | newton
2 | sweep --method shooting, | --method
2 | sweep --shard 4/3 | --shard
2 | sweep --shard 0/3 | --shard
2 | sweep --shard -1/3 | --shard
2 | sweep --shard 1/0 | --shard
2 | sweep --shard 1 | --shard
2 | sweep --shard a/b | --shard
2 | sweep --jobs 0 | --jobs
2 | sweep --jobs -1 | --jobs
2 | sweep --jobs 100000 | --jobs
2 | sweep --points 1 | --points
2 | sweep --points 2000000 | --points
2 | sweep --d-max 0 | --d-max
2 | sweep --d-max 1e300 | --d-max 1e300
2 | sweep --mu0 -1 | --mu0
2 | sweep --eta 0.6:0.9:65536 --taper 0.1:1:65536 --precurvature 0:1:65536 --support-compliance 0:1:65536 --out precious.csv | limit
2 | sweep --eta 0.6:0.9:100000 --taper 0.1:1:100000 --out precious.csv | 1e10 scenes
2 | sweep --eta 0.6:0.9:100 --points 1000000 --jobs 8 --out precious.csv | --jobs 8 × --points 1000000
2 | sweep --scene uni_ratio.toml --out precious.csv | unknown key
2 | sweep --scene ratio0.toml | stiffness.ratio = 0
2 | sweep --scene ratio0.toml --dry-run | stiffness.ratio = 0
2 | sweep --length-mm 30 | all three
2 | sweep --length-mm 1e-200 --youngs-modulus-gpa 3.3 --base-diameter-um 100 | overflow
2 | sweep --out . | directory
2 | sweep --out sub/ --dry-run | not a file name
1 | sweep --eta 0.7 --points 3 --out /dev/full | --out /dev/full
1 | sweep --eta 0.7 --points 3 --out nodir/x.csv | nodir
2 | sweep --eta 0.7 --scene missing.toml | missing.toml
2 | sweep --timing=yes | --timing
# figures
2 | figures --tol 0.5 --out-dir figs | --tol 0.5
2 | figures --tol 1e-300 --out-dir figs | --tol 1e-300
2 | figures --tol -1e-10 --out-dir figs | --tol
2 | figures --tol 0 --out-dir figs | --tol
2 | figures --only 1 --out-dir figs | --only
2 | figures --only 12 --out-dir figs | --only
2 | figures --only -1 --out-dir figs | --only
2 | figures --method analytic --out-dir figs | possible values: shooting, multiple-shooting, collocation, collocation6]
1 | figures --out-dir precious.csv --only 3 | precious.csv
2 | figures --scene x.toml | --scene
# the program
2 | frobnicate | frobnicate
2 | --frobnicate | --frobnicate
2 | scan extra | extra
"#;

#[test]
fn bad_invocations_fail_cleanly_and_change_no_file() {
    let d = tmpdir("badtable");
    let precious = d.join("precious.csv");
    let content = "precious\n1,2,3\n";
    std::fs::write(&precious, content).unwrap();
    for (name, text) in SCENES {
        std::fs::write(d.join(name), text).unwrap();
    }
    #[cfg(unix)]
    std::os::unix::fs::symlink("precious.csv", d.join("link_to_precious.csv")).unwrap();
    let before = listing(&d);
    let mut n = 0;
    let mut failures = Vec::new();
    for line in CASES.lines() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let parts: Vec<&str> = line.split(" | ").collect();
        let code: i32 = parts[0].parse().unwrap();
        let args: Vec<&str> = parts[1]
            .split_whitespace()
            .map(|a| if a == "\"\"" { "" } else { a })
            .collect();
        let o = run_in(&d, &args);
        let what = format!("vibrissa {}", parts[1]);
        let lines: Vec<&str> = o.stderr.lines().collect();
        let mut why = Vec::new();
        if o.code != code {
            why.push(format!("exit {} instead of {code}", o.code));
        }
        if lines.len() != 1 || !lines[0].starts_with("error: ") {
            why.push("not exactly one `error:` line".to_string());
        }
        if o.stderr.contains("panicked") || o.stdout.contains("NaN") {
            why.push("a panic or NaN".to_string());
        }
        // short numbers: never a 300-digit decimal
        if o.stderr.contains("0000000000000000000000") {
            why.push("a long decimal".to_string());
        }
        if let Some(want) = parts.get(2) {
            if !o.stderr.contains(want) {
                why.push(format!("the message lacks {want:?}"));
            }
        }
        if std::fs::read_to_string(&precious).unwrap() != content {
            why.push("precious.csv changed".to_string());
            std::fs::write(&precious, content).unwrap();
        }
        if listing(&d) != before {
            why.push(format!("files changed: {:?}", listing(&d)));
        }
        if !why.is_empty() {
            failures.push(format!("{what}: {}; stderr {:?}", why.join(", "), o.stderr));
        }
        n += 1;
    }
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
    assert!(n >= 150, "only {n} invocations");
}

/// Wrong types in a scene file are told in the file's words (tables, numbers, keys), never in
/// serde's Rust types ("internally tagged enum", "f64", "struct").
#[test]
fn scene_type_errors_speak_the_file_format() {
    let dir = tmpdir("scene-types");
    for (text, want) in [
        (
            "stiffness = 3\n",
            "expected a stiffness table: { kind = \"uniform\" }",
        ),
        ("stiffness = \"taper\"\n", "expected a stiffness table"),
        (
            "precurvature = 0.5\n",
            "expected a precurvature table: { kind = \"none\" }",
        ),
        ("eta = \"high\"\n", "expected a number"),
        (
            "stiffness = { kind = \"taper\", ratio = \"x\" }\n",
            "expected a number",
        ),
        ("physical = 3\n", "expected a [physical] table"),
        ("stiffness = { ratio = 0.5 }\n", "missing key `kind`"),
        ("stiffness = { kind = \"cone\" }\n", "unknown kind `cone`"),
    ] {
        let path = dir.join("scene.toml");
        std::fs::write(&path, text).unwrap();
        let e = bad(&["scan", "--scene", path.to_str().unwrap()], 2);
        assert!(e.contains(want), "{text:?}: {e}");
        for serde_word in ["internally tagged", "f64", "struct ", "variant", "field"] {
            assert!(!e.contains(serde_word), "{text:?}: {e}");
        }
    }
}

/// `figures --help` offers only the methods it accepts; `analytic` is refused by the parser
/// with the list of valid ones. `solve` without a tip condition names both flags.
#[test]
fn help_offers_what_the_commands_accept() {
    let help = ok(&["figures", "--help"]).stdout;
    let methods = &help[help.find("--method").unwrap()..];
    let methods = &methods[..methods.find("--tol").unwrap()];
    for m in ["shooting", "multiple-shooting", "collocation6"] {
        assert!(methods.contains(m), "{methods}");
    }
    assert!(!methods.contains("- analytic"), "{methods}");
    let e = bad(&["figures", "--method", "analytic"], 2);
    assert!(
        e.contains("possible values: shooting, multiple-shooting"),
        "{e}"
    );
    let e = bad(&["solve", "--alpha", "0.1"], 2);
    assert!(e.contains("--phi1") && e.contains("--eta"), "{e}");
    let help = ok(&["scan", "--help"]).stdout;
    let shapes = &help[help.find("--shapes").unwrap()..help.find("--shape-points").unwrap()];
    assert!(shapes.contains("kappa, m, event"), "{shapes}");
}
