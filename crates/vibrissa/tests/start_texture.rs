//! The start of a drag on a corrugation where the rod pressed onto the straight trend lies along
//! it (issue 31's texture grid, data/drag/texture_grid.csv): the tapered rod (ρ = 0.3) at
//! η = 0.75 touches the flat surface with a side near its tip and its straight, unloaded tail
//! beyond lies on the line. Grown from the flat surface, the corrugation crossed that tail at
//! once, and the start ended with "no start: ... the height of the free rod above the surface
//! (it would cross it) = 2.860e-5 after the change". Now the contacts the corrugation makes
//! with the tail are found at a small amplitude and the growth goes on from there.

use vibrissa::surface::{Height, SurfaceProfile};
use vibrissa::{drag, DragOptions, Scene, Stiffness, VibrissaError};

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
    let r = grid_drag(scene, 0.3, 11).expect("a start on the corrugation");
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

/// The rat preset (data/scenes/rat_mystacial_short.toml) at the grid's η = 0.75.
fn rat_short() -> Scene {
    let path = format!(
        "{}/../../data/scenes/rat_mystacial_short.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let s: Scene = toml::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    Scene { eta: 0.75, ..s }
}

/// The tapered rod (ρ = 0.3) of the grid.
fn taper() -> Scene {
    Scene {
        stiffness: Stiffness::Taper { ratio: 0.3 },
        ..Scene::default()
    }
}

/// `scene` on the sine of amplitude `a`, wavelength `w`, phase `p`, with the grid's friction,
/// dragged a short way (the start is what is tested).
fn on_sine(scene: Scene, a: f64, w: f64, p: f64) -> Result<vibrissa::DragResult, VibrissaError> {
    let scene = Scene {
        surface: sine(a, w, p),
        ..scene
    };
    grid_drag(scene, 1e-3, 2)
}

/// The drag of `scene` with the grid's friction (μs 0.5, μk 0.3) to `d_max` on `points` output
/// points, the shapes kept at 1001 points each.
fn grid_drag(
    scene: Scene,
    d_max: f64,
    points: usize,
) -> Result<vibrissa::DragResult, VibrissaError> {
    let (rod, surface) = scene.parts().unwrap();
    let opts = DragOptions {
        d_max,
        points,
        mu_s: Some(0.5),
        mu_k: Some(0.3),
        keep_shapes: Some(1001),
        ..DragOptions::default()
    };
    drag(&rod, &surface, &opts)
}

/// The sine of amplitude `a`, wavelength `w` and phase `p`.
fn sine(a: f64, w: f64, p: f64) -> SurfaceProfile {
    SurfaceProfile::Sine {
        amplitude: a,
        wavelength: w,
        phase: p,
    }
}

/// The drag of `scene` on the sine `(a, w, p)` starts, and its start holds ([`start_holds`]):
/// the number of its contacts.
fn starts_on(scene: Scene, a: f64, w: f64, p: f64) -> usize {
    let r = on_sine(scene, a, w, p).expect("a start on the sine");
    start_holds(&r, &sine(a, w, p))
}

/// The start of `r` (on `profile` at η = 0.75) holds: every contact pushes (N > 0) with
/// |T| ≤ μs N, lies on the surface to [`ON_SURFACE`], and the rod sampled at 1001 points is
/// nowhere beyond the surface by more than that. Returns the number of contacts.
fn start_holds(r: &vibrissa::DragResult, profile: &SurfaceProfile) -> usize {
    let h = Height::new(profile, 0.75, 0.0).unwrap().unwrap();
    let start = &r.rows[0];
    assert_eq!(start.d, 0.0);
    for c in &start.contacts {
        assert!(c.normal > 0.0, "a tensile contact at the start: {c}");
        assert!(c.tangential.abs() <= 0.5 * c.normal, "beyond μs: {c}");
        let off = c.y - h.jet(c.x).0;
        assert!(off.abs() <= ON_SURFACE, "off the surface by {off:e}: {c}");
    }
    let worst = r.shapes[0]
        .iter()
        .map(|p| p.y - h.jet(p.x).0)
        .fold(f64::NEG_INFINITY, f64::max);
    assert!(
        worst <= ON_SURFACE,
        "the start crosses the surface by {worst:e}"
    );
    start.contacts.len()
}

/// Issue 31's grid, taper 0.3 on the sine 0.001 / 0.05 / phase 0: the tail lying on the trend
/// settled at the small amplitudes into two contacts 4e-4 apart with the rod between them
/// within rounding of the sine, which the march in the amplitude could not follow ("no start:
/// ... side+side does not hold beyond d = 0.001"). Settled at a tenth of the amplitude its
/// contacts lie apart and the growth reaches the full sine: the start holds, with the tail on
/// the sine (more than the one side of the flat surface).
#[test]
fn a_tail_lying_on_the_trend_settles_at_a_larger_amplitude() {
    assert!(starts_on(taper(), 0.001, 0.05, 0.0) >= 2);
}

/// Issue 31's grid, taper 0.3 on the sine 0.003 / 0.02 / phase 0: the march in the amplitude
/// stopped at its first point ("no start: ... the contact state side does not hold beyond
/// d = 0: the height of the free rod above the surface (it would cross it) = 8.841e-5").
/// Resumed a little further on, it reaches the full sine: the start holds.
#[test]
fn a_march_in_the_amplitude_that_stops_is_resumed() {
    assert!(starts_on(taper(), 0.003, 0.02, 0.0) >= 1);
}

/// Issue 31's grid, the short rat preset on the sine 0.003 / 0.1 / phase 2π/3: the march in
/// the amplitude met a side touching down whose new state Newton did not solve; then, with sides
/// on a curve watched, a side whose curvature met the surface's, and the start stopped there
/// (`StartLies`: the rod lying down along the sine). Since a stretch lies down as the texture
/// grows (frictionless, on the scaled surface's arc length), the rod lies along the sine from
/// s = 0.9749, and the stretch grows to the rod's end at 19.9 % of the amplitude: beyond, the
/// tip would press beyond it, which is not followed; the start stopped there, by name. Now the
/// sine is grown at a lighter press instead (halfway from η to first touch, where the lightly
/// bent rod rides it on its tip) and the rod pressed down onto it: the start holds, a side and
/// the tip on the sine (the drag of the grid's row runs from it to `d_max`, 10 630 slips).
#[test]
fn a_rat_whisker_whose_stretch_reaches_its_end_as_the_texture_grows_starts_pressed_down() {
    let p = 2.0 * std::f64::consts::PI / 3.0;
    let r = on_sine(rat_short(), 0.003, 0.1, p).expect("a start pressed down onto the sine");
    assert_eq!(r.rows[0].contact.name(), "side+tip");
    assert_eq!(start_holds(&r, &sine(0.003, 0.1, p)), 2);
}

/// The other starts of issue 31's grid that ended short of the full sine as it grew at η and
/// now start from a lighter press (`data/drag/texture_grid.csv`): the stretch reached the
/// rod's end (the rat preset over 0.001/0.1, 0.01/0.5, 0.02/0.5, 0.05/0.5 at 2π/3; taper 0.3
/// over 0.02/0.5 at 4π/3), a new contact beyond a lying stretch (the rat preset over
/// 0.01/0.1/2π/3, taper 0.3 over 0.05/0.5/4π/3) or a stretch that did not hold (the rat preset
/// over 0.003/0.05/2π/3). Each start holds ([`start_holds`]).
#[test]
fn starts_that_end_short_as_the_texture_grows_are_pressed_down_onto_it() {
    let (p2, p4) = (
        2.0 * std::f64::consts::PI / 3.0,
        4.0 * std::f64::consts::PI / 3.0,
    );
    let cases = [
        (rat_short(), 0.001, 0.1, p2),
        (rat_short(), 0.01, 0.5, p2),
        (rat_short(), 0.02, 0.5, p2),
        (rat_short(), 0.05, 0.5, p2),
        (rat_short(), 0.01, 0.1, p2),
        (rat_short(), 0.003, 0.05, p2),
        (taper(), 0.02, 0.5, p4),
        (taper(), 0.05, 0.5, p4),
    ];
    for (scene, a, w, p) in cases {
        let r = on_sine(scene, a, w, p).unwrap_or_else(|e| panic!("{a}/{w}/{p}: {e}"));
        start_holds(&r, &sine(a, w, p));
    }
}

/// Issue 31's grid, taper 0.3 with a round tip (radius 0.005) on the steep sine 0.05 / 0.1 /
/// phase 0: the pressed rod's equilibria fold back as the sine grows, so there is no
/// quasi-static pressed start; the start says so as a snap, at an amplitude inside (0, 1).
#[test]
fn a_rod_that_snaps_as_the_texture_grows_has_no_start() {
    let scene = Scene {
        tip_radius: 0.005,
        ..taper()
    };
    match on_sine(scene, 0.05, 0.1, 0.0) {
        Err(VibrissaError::StartSnaps { amplitude }) => {
            assert!(amplitude > 0.0 && amplitude < 1.0, "{amplitude}")
        }
        other => panic!("expected a snap at the start, got {other:?}"),
    }
}

/// Issue 31's grid, the short rat preset on the sine 0.001 / 0.05 / phase 2π/3: as the sine
/// grows, the rod's free curved tail meets a stretch whose curvature equals its own, and the
/// rod lies down along it. Until a stretch could lie down as the texture grows, the start
/// stopped there (`StartLies`: two contacts closer than 1e-3, the march turning back at every
/// step). Now the stretch lies down (frictionless, on the scaled surface's arc length) and the
/// growth reaches the full sine: the start holds with the rod lying along it.
#[test]
fn a_rod_that_lies_down_as_the_texture_grows_starts_lying_on_it() {
    let p = 2.0 * std::f64::consts::PI / 3.0;
    let r = on_sine(rat_short(), 0.001, 0.05, p).expect("a start lying on the sine");
    assert!(
        r.rows[0].contact.name().contains("stretch"),
        "{}",
        r.rows[0].contact.name()
    );
    start_holds(&r, &sine(0.001, 0.05, p));
}

/// Issue 31's grid, taper 0.3 on the sine 0.001 / 0.2 / phase 2π/3: the straight tail lying
/// on the trend beyond the side at s = 0.9722 runs over the sine's inflection, and as the sine
/// grew the tail crossed it beyond (by 1.4e-8 at 0.1 % of the amplitude, at s = 0.9898). A
/// second side there was not solved (Newton stalled at residuals 1.4e-8), the side alone came
/// back as the same state 32 times, and the start ended as "lies down along the surface ... no
/// pressed start". Now the side lies down as a stretch where the tail crosses beyond it: the
/// rod follows the sine out to where the moment vanishes, which on this rod without
/// pre-curvature is where the sine's curvature does (its inflection), and the tail beyond,
/// unloaded and straight, clears the sine. The start holds ([`start_holds`]) with the stretch's
/// outer end at the inflection to 1e-6 of the sine's largest curvature (the shape sampled at
/// 1001 points, interpolated linearly), and the drag reaches d_max.
#[test]
fn a_tail_over_an_inflection_lies_down_to_it_as_the_texture_grows() {
    let (a, w, p) = (0.001, 0.2, 2.0 * std::f64::consts::PI / 3.0);
    let scene = Scene {
        surface: sine(a, w, p),
        ..taper()
    };
    let r = grid_drag(scene, 0.3, 11).expect("a start lying on the sine");
    assert_eq!(r.stop, vibrissa::StopReason::DMax, "{}", r.stop);
    start_holds(&r, &sine(a, w, p));
    let start = &r.rows[0];
    let lying = start
        .contacts
        .iter()
        .find_map(|c| c.lies_to.map(|s2| (c.s, s2)));
    let (s1, s2) =
        lying.unwrap_or_else(|| panic!("no stretch at the start: {}", start.contact.name()));
    assert!(
        s1 < 0.98 && s2 > s1 + 1e-3 && s2 < 1.0,
        "the stretch {s1}..{s2}"
    );
    let shape = &r.shapes[0];
    let k = shape.partition_point(|q| q.s < s2);
    let (q0, q1) = (&shape[k - 1], &shape[k]);
    let x2 = q0.x + (q1.x - q0.x) * (s2 - q0.s) / (q1.s - q0.s);
    let h = Height::new(&sine(a, w, p), 0.75, 0.0).unwrap().unwrap();
    let most = a * (2.0 * std::f64::consts::PI / w).powi(2);
    let curv = h.jet(x2).2;
    eprintln!(
        "stretch from s = {s1:.6} to {s2:.6} (x = {x2:.6}); the sine's curvature there {:.2e} of \
         its largest; {} slips",
        curv / most,
        r.slips.len()
    );
    assert!(
        curv.abs() <= 1e-6 * most,
        "the sine's curvature at the stretch's outer end (s = {s2}, x = {x2}): {curv:e}"
    );
}
