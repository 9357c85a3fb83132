//! `--tip-radius` end to end (issue 31): the drag's CSV gains the contact point `x_contact` with
//! a round tip (and only then), the flag's range, and the point tip's refusal of a surface
//! steeper than 45° names the slope and suggests the flag.

mod common;
use common::*;

/// A round tip's drag writes `x_contact` after `x_tip, y_tip`; on the flat surface the contact
/// point is right above the disk's centre (x_contact = x_tip, to the printed digits) and the
/// centre runs r below the surface (y_tip = η − r, 1e-12).
#[test]
fn the_drag_of_a_round_tip_has_its_contact_point() {
    let args = [
        "drag", "--mu-s", "0.5", "--mu-k", "0.3", "--d-max", "0.05", "--points", "3",
    ];
    let (h0, _) = csv(&ok(&args).stdout);
    assert!(!h0.iter().any(|c| c == "x_contact"));
    let mut round = args.to_vec();
    round.extend(["--tip-radius", "0.01"]);
    let (h, rows) = csv(&ok(&round).stdout);
    assert_eq!(h[..5], ["d", "phase", "x_tip", "y_tip", "x_contact"]);
    for r in &rows {
        let (x, xc, y) = (
            col(&h, r, "x_tip"),
            col(&h, r, "x_contact"),
            col(&h, r, "y_tip"),
        );
        assert!((x - xc).abs() <= 1e-12, "{r:?}");
        assert!((y - 0.74).abs() <= 1e-12, "{r:?}");
    }
}

/// A round tip's scan writes `x_contact` after `s_c`, and only then; the stuck disk rolls on the
/// flat surface, so its contact point moves by the arc it turns through:
/// `x_contact − x_contact(0) = r·(φ1 − φ1(0))` (as the library's test, here through the CSV's
/// printed digits, 1e-9).
#[test]
fn the_scan_of_a_round_tip_has_its_contact_point() {
    let args = ["scan", "--points", "5", "--d-max", "0.2"];
    let (h0, _) = csv(&ok(&args).stdout);
    assert!(!h0.iter().any(|c| c == "x_contact"));
    let mut round = args.to_vec();
    round.extend(["--tip-radius", "0.02"]);
    let (h, rows) = csv(&ok(&round).stdout);
    let i = h.iter().position(|c| c == "s_c").expect("s_c");
    assert_eq!(h[i + 1], "x_contact");
    let (xc0, phi0) = (col(&h, &rows[0], "x_contact"), col(&h, &rows[0], "phi1"));
    assert!(rows.len() == 5 && col(&h, &rows[4], "d") == 0.2);
    for r in &rows {
        let (xc, phi) = (col(&h, r, "x_contact"), col(&h, r, "phi1"));
        assert!((xc - xc0 - 0.02 * (phi - phi0)).abs() <= 1e-9, "{r:?}");
    }
}

/// The flag's range comes from the library, and a point tip on a corrugation steeper than 45°
/// is refused with a message that names the slope and the flag.
#[test]
fn tip_radius_refusals() {
    let e = bad(&["scan", "--tip-radius", "0.2"], 2);
    assert!(e.contains("--tip-radius") && e.contains("[0, 0.05]"), "{e}");
    let steep = [
        "drag",
        "--mu-s",
        "0.5",
        "--mu-k",
        "0.3",
        "--corrugation-amplitude",
        "0.01",
        "--corrugation-wavelength",
        "0.05",
    ];
    let e = bad(&steep, 2);
    assert!(e.contains("1.25664") && e.contains("--tip-radius"), "{e}");
}
