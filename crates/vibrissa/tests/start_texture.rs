//! The start of a drag on a corrugation where the rod pressed onto the straight trend lies along
//! it (issue 31's texture grid, data/drag/texture_grid.csv): the tapered rod (ρ = 0.3) at
//! η = 0.75 touches the flat surface with a side near its tip and its straight, unloaded tail
//! beyond lies on the line. Grown from the flat surface, the corrugation crossed that tail at
//! once, and the start ended with "no start: ... the height of the free rod above the surface
//! (it would cross it) = 2.860e-5 after the change". Now the contacts the corrugation makes
//! with the tail are found at a small amplitude and the growth goes on from there.

use vibrissa::surface::{Height, SurfaceProfile};
use vibrissa::{drag, DragOptions, Scene, Stiffness};

/// The corrugation of the docs' example (docs/robustness.md, "Textures: issue 31's grid").
const SINE: SurfaceProfile = SurfaceProfile::Sine {
    amplitude: 0.001,
    wavelength: 0.02,
    phase: 0.0,
};

/// How far a sampled point of the rod may lie above the surface, and a contact point off it:
/// the rounding of the rod's heights (the start is solved to 1e-10 relative in the solver's
/// tolerance, its contact conditions are residuals at rounding).
const ON_SURFACE: f64 = 1e-12;

/// The start holds: each contact pushes (N > 0), needs no more friction than μs (frictionless
/// here: the start is pressed without friction), lies on the surface to 1e-12; the rod sampled
/// at 1001 points nowhere above it by more than 1e-12; the tail touches the corrugation (more
/// contacts than the one side on the flat surface). The drag's first rows go on from it: the
/// row after the start has the same contact set and base signals within 1e-3 of the start's
/// (over less than 1e-5 of d; a jump away from the start would change them by O(0.1)).
#[test]
fn a_tapered_rod_lying_on_the_trend_starts_on_the_corrugation() {
    let scene = Scene {
        stiffness: Stiffness::Taper { ratio: 0.3 },
        surface: SINE,
        ..Scene::default()
    };
    assert_eq!(scene.eta, 0.75);
    let (rod, surface) = scene.parts().unwrap();
    let opts = DragOptions {
        d_max: 0.3,
        points: 11,
        mu_s: Some(0.5),
        mu_k: Some(0.3),
        keep_shapes: Some(1001),
        ..DragOptions::default()
    };
    let r = drag(&rod, &surface, &opts).expect("a start on the corrugation");
    let h = Height::new(&SINE, 0.75, 0.0).unwrap().unwrap();
    let start = &r.rows[0];
    assert_eq!(start.d, 0.0);
    assert!(start.contacts.len() >= 2, "{:?}", start.contacts);
    for c in &start.contacts {
        assert!(c.normal > 0.0, "a tensile contact at the start: {c}");
        assert!(c.tangential.abs() <= 0.5 * c.normal, "beyond μs: {c}");
        let off = c.y - h.jet(c.x).0;
        assert!(off.abs() <= ON_SURFACE, "off the surface by {off:e}: {c}");
    }
    let shape = &r.shapes[0];
    assert_eq!(shape.len(), 1001);
    let worst = shape
        .iter()
        .map(|p| p.y - h.jet(p.x).0)
        .fold(f64::NEG_INFINITY, f64::max);
    assert!(
        worst <= ON_SURFACE,
        "the start crosses the surface by {worst:e}"
    );
    eprintln!(
        "start {}: highest point of the rod above the surface {worst:.2e}",
        start.contact.name()
    );
    for c in &start.contacts {
        eprintln!("  {c}; off the surface {:.2e}", c.y - h.jet(c.x).0);
    }
    let next = &r.rows[1];
    assert!(next.d > 0.0 && next.d < 1e-5, "{}", next.d);
    assert_eq!(next.contact, start.contact);
    for (a, b) in [
        (next.fx, start.fx),
        (next.fy, start.fy),
        (next.m_base, start.m_base),
    ] {
        assert!((a - b).abs() < 1e-3, "{a} against the start's {b}");
    }
}
