//! The round tip (issue 31): the rod's end carries a rigid disk of radius r centred at its end
//! point (docs/model.md, "The round tip").

use vibrissa::drag::Hold;
use vibrissa::surface::SurfaceProfile;
use vibrissa::{DragOptions, DragResult, Rod, ScanOptions, Scene, StopReason, Surface};

#[path = "support/slip_balance.rs"]
mod slip_balance;
use slip_balance::assert_balanced;

fn scan_points(rod: &Rod, surface: &Surface, d: &[f64]) -> Vec<vibrissa::ScanPoint> {
    vibrissa::scan_at(rod, surface, &ScanOptions::default(), d)
        .expect("scan")
        .points
}

/// On a flat surface a frictionless disk (the pressed start: the contact force normal to the
/// surface, T = 0) carries no moment about its centre, so its rod is the point-tip rod whose
/// contact line is lowered by r: the centre runs on y = η − r and m(1) = 0. Both solved by the
/// same shooter to its tolerance (1e-10 by default): equal to 1e-10.
#[test]
fn a_frictionless_disk_on_a_flat_surface_is_the_point_tip_on_the_lowered_line() {
    for (eta, r) in [(0.75, 0.01), (0.8, 0.05), (0.6, 0.002)] {
        let disk = Rod::builder().tip_radius(r).build().unwrap();
        let a = &scan_points(&disk, &Surface::flat(eta).unwrap(), &[0.0])[0];
        let b = &scan_points(&Rod::uniform(), &Surface::flat(eta - r).unwrap(), &[0.0])[0];
        for (what, x, y) in [
            ("m_base", a.m_base, b.m_base),
            ("fx", a.fx, b.fx),
            ("fy", a.fy, b.fy),
            ("phi1", a.phi1, b.phi1),
            ("mu", a.mu, b.mu),
        ] {
            assert!(
                (x - y).abs() <= 1e-10,
                "eta {eta}, r {r}: {what} {x} against the lowered point tip's {y}"
            );
        }
        // T = 0: no moment about the centre, m(1) = r T = 0
        assert!(a.mu.abs() <= 1e-12, "mu {}", a.mu);
        // the contact point right above the centre
        let xc = a.x_contact.expect("a round tip reports its contact point");
        assert!(xc.is_finite());
    }
}

/// A stuck disk rolls without slipping: on a flat surface its contact point moves by r times
/// the turn of the rod's end, x_c − x_c0 = r (φ(1) − φ(1)_0), to 1e-10 (the solve's tolerance).
#[test]
fn a_stuck_disk_rolls_on_a_flat_surface() {
    let r = 0.02;
    let disk = Rod::builder().tip_radius(r).build().unwrap();
    let pts = scan_points(
        &disk,
        &Surface::flat(0.75).unwrap(),
        &[0.0, 0.02, 0.05, 0.1],
    );
    let (x0, p0) = (pts[0].x_contact.unwrap(), pts[0].phi1);
    for p in &pts[1..] {
        let xc = p.x_contact.unwrap();
        let want = r * (p.phi1 - p0);
        assert!(
            (xc - x0 - want).abs() <= 1e-10,
            "d {}: x_c − x_c0 = {} against r (φ1 − φ1_0) = {want}",
            p.d,
            xc - x0
        );
        // it did turn (the check is not of a tip standing still)
        assert!((p.phi1 - p0).abs() > 1e-3);
    }
}

/// The paper's rod with a tip of radius `r` over `0.75 + a sin(2πx/w + phase)`.
fn round_tip_over(r: f64, a: f64, w: f64, phase: f64) -> Scene {
    Scene {
        surface: SurfaceProfile::Sine {
            amplitude: a,
            wavelength: w,
            phase,
        },
        tip_radius: r,
        ..Scene::default()
    }
}

/// The paper's rod at η 0.75 with a round tip of radius `r` over the corrugation
/// `A sin(2πx/W)`, dragged with μs 0.5, μk 0.3 to `d_max`.
fn corrugated(r: f64, a: f64, w: f64, d_max: f64, balance: bool) -> DragResult {
    let (rod, surface) = round_tip_over(r, a, w, 0.0).parts().unwrap();
    let o = DragOptions {
        d_max,
        points: 11,
        mu_s: Some(0.5),
        mu_k: Some(0.3),
        energy_balance: balance,
        ..DragOptions::default()
    };
    vibrissa::drag(&rod, &surface, &o).unwrap()
}

/// The energy balance of every phase with a round tip (as `tests/drag.rs` for the point tip, to
/// 1e-8): over a stick the foot's work is the elastic energy's change (a rolling tip does no
/// work), over a slip the energy released is the work friction absorbs at the contact point, its
/// tangential force times the material slip there (the place of the rolling tip, arc length less
/// r times the disk's turn against the surface). A wrong moment at the tip, or a wrong rolling
/// condition, breaks both. On the flat surface and on a corrugation.
#[test]
fn energy_balance_with_a_round_tip() {
    for (name, a, w, d_max) in [("flat", 0.0, 0.1, 0.08), ("corrugated", 0.005, 0.05, 0.06)] {
        let r = if a == 0.0 {
            let (rod, surface) = Scene {
                tip_radius: 0.01,
                ..Scene::default()
            }
            .parts()
            .unwrap();
            let o = DragOptions {
                d_max,
                points: 11,
                mu_s: Some(0.5),
                mu_k: Some(0.3),
                energy_balance: true,
                ..DragOptions::default()
            };
            vibrissa::drag(&rod, &surface, &o).unwrap()
        } else {
            corrugated(0.005, a, w, d_max, true)
        };
        assert!(r.slips.len() >= 2, "{name}: {r}");
        for (k, e) in r.slips.iter().enumerate() {
            assert_balanced(name, k, e, 1e-8);
            assert!(
                e.released > 1e-6,
                "{name}, slip {k}: released {}",
                e.released
            );
        }
    }
}

/// `vibrissa drag --eta 0.75 --corrugation-amplitude 0.005 --corrugation-wavelength 0.05`: the
/// point tip ended after 3 slips at d 0.0105 ("the tip would turn into the surface"), where its
/// lying down inside the third slip was not located; it now lies down there and slides on as a
/// side, past d 0.0105 (to a snap a few slips later, docs/robustness.md); with a round tip of
/// radius 0.005 the drag runs on much further (docs/robustness.md reports where it ends and why).
#[test]
fn a_round_tip_runs_past_where_the_point_tip_turns_into_the_corrugation() {
    let point = corrugated(0.0, 0.005, 0.05, 0.3, false);
    assert!(point.slips.len() > 3, "{point}");
    assert!(
        point.stop.at().is_none_or(|d| d > 0.0105114)
            && !point.stop.to_string().contains("no contact state"),
        "{point}"
    );
    let round = corrugated(0.005, 0.005, 0.05, 0.3, false);
    let end = match &round.stop {
        StopReason::DMax => 0.3,
        s => s.at().unwrap_or(f64::NAN),
    };
    assert!(end > 0.1, "{round}");
    assert!(round.slips.len() > 3, "{round}");
}

/// A corrugation with flanks steeper than 45° (A 0.01, W 0.05: the steepest slope 2πA/W = 1.26,
/// 51.5°): refused to the point tip, with a message that names the slope and the tip radius;
/// with a round tip of radius 0.005 the drag runs through 12 slips and on: at d 0.0193 a side
/// touches down behind the disk during a slip and joins it, and this run (11 output points)
/// goes on to a jam at d 0.0313 after 175 slips (docs/robustness.md, "With a round tip").
#[test]
fn a_round_tip_takes_flanks_steeper_than_45_degrees() {
    let steep = |r: f64| round_tip_over(r, 0.01, 0.05, 0.0);
    let e = steep(0.0).parts().unwrap_err().to_string();
    assert!(
        e.contains("1.256637") && e.contains("tip radius"),
        "the point tip's refusal: {e}"
    );
    // a surface made for a round tip is refused to a point tip
    let (_, surface) = steep(0.005).parts().unwrap();
    let o = DragOptions {
        mu_s: Some(0.5),
        mu_k: Some(0.3),
        ..DragOptions::default()
    };
    let e = vibrissa::drag(&Rod::uniform(), &surface, &o).unwrap_err();
    assert!(e.to_string().contains("45 degrees"), "{e}");
    let r = corrugated(0.005, 0.01, 0.05, 0.3, false);
    assert!(r.slips.len() >= 10, "{r}");
    assert!(
        !matches!(r.stop, StopReason::SolverFailure { .. }) && r.stop.at().unwrap_or(0.3) > 0.015,
        "{r}"
    );
}

/// `solve` at a surface height with a round tip: a vertical force (α = 0) has no tangential
/// part on the flat surface, so no moment about the disk's centre, and the rod is the point
/// tip's on the line lowered by r (1e-10); a slope or a tip position target is refused.
#[test]
fn solve_at_a_height_with_a_round_tip() {
    use vibrissa::{BranchChoice, SolverConfig, Target};
    let cfg = SolverConfig::default();
    let r = 0.02;
    let disk = Rod::builder().tip_radius(r).build().unwrap();
    let a = vibrissa::solve(&disk, 0.0, Target::Eta(0.75), &BranchChoice::Convex, &cfg).unwrap();
    let b = vibrissa::solve(
        &Rod::uniform(),
        0.0,
        Target::Eta(0.75 - r),
        &BranchChoice::Convex,
        &cfg,
    )
    .unwrap();
    assert!((a.f - b.f).abs() <= 1e-10, "f {} against {}", a.f, b.f);
    let slope = vibrissa::solve(&disk, 0.0, Target::Phi1(0.3), &BranchChoice::Convex, &cfg);
    assert!(slope.is_err());
}

/// A round tip is solved on the rod's own shooter: the generic methods and the closed forms
/// refuse it by name, as does a tip radius outside [0, 0.05].
#[test]
fn a_round_tip_is_refused_where_it_is_not_modelled() {
    use vibrissa::{Method, SolverConfig, VibrissaError};
    let disk = Rod::builder().tip_radius(0.01).build().unwrap();
    let surface = Surface::flat(0.75).unwrap();
    for method in [
        Method::MultipleShooting,
        Method::Collocation4,
        Method::Analytic,
    ] {
        let o = ScanOptions {
            solver: SolverConfig {
                method,
                ..SolverConfig::default()
            },
            ..ScanOptions::default()
        };
        let e = vibrissa::scan(&disk, &surface, &o).unwrap_err();
        assert!(
            matches!(e, VibrissaError::MethodUnavailable { .. }),
            "{method:?}: {e}"
        );
    }
    for r in [-1e-3, 0.06, f64::NAN] {
        assert!(Rod::builder().tip_radius(r).build().is_err(), "r = {r}");
    }
}

/// The steep flank (0.02/0.1) with r = 0.005: in the tip's slip at d 0.004694 a side
/// touches down behind it (s ≈ 0.978) and slides with it; the slip ends where μk holds both
/// (each at `T = μk N`, pressed, on the surface), its energy released equal to the work of both
/// sliding contacts (1e-8), and the drag goes on. (The slip's driver, the tip, moves one place
/// up the contact set; it stopped there as "not followed" before.)
#[test]
fn a_side_touching_down_behind_a_sliding_tip_joins_the_slip() {
    let (_, surface) = round_tip_over(0.005, 0.02, 0.1, 0.0).parts().unwrap();
    let h = surface.profile().unwrap();
    let r = corrugated(0.005, 0.02, 0.1, 0.3, true);
    let i = r
        .slips
        .iter()
        .position(|e| (e.d - 0.004694).abs() < 1e-5)
        .unwrap_or_else(|| panic!("no slip at d 0.004694: {r}"));
    let (e, after) = (&r.slips[i], &r.slip_contacts[i].after);
    assert_eq!(r.slip_contacts[i].before.len(), 1, "{r}");
    assert_eq!(after.len(), 2, "{r}");
    assert!(
        after[0].s > 0.9 && after[0].s < 1.0 && !after[0].tip,
        "{}",
        after[0]
    );
    for c in after {
        assert!(matches!(c.hold, Hold::Sliding { dir } if dir > 0.0), "{c}");
        assert!(c.normal > 0.0, "{c}");
        assert!((c.tangential - 0.3 * c.normal).abs() <= 1e-9, "{c}");
        assert!((c.y - h.h(c.x)).abs() <= 1e-12, "{c}");
    }
    let diss = e.dissipated.unwrap();
    assert!((diss - e.released).abs() <= 1e-8, "{diss} {}", e.released);
    assert!(r.rows.last().unwrap().d > 0.0047, "{r}");
}

/// Against the independent computation of `data/drag/round_tip_reference.csv`
/// (`make_round_reference.py`: scipy, Cartesian tip forces, the disk's centre on the offset
/// surface, its own rolling condition and continuation; its own spread 2.5e-11): the paper's
/// rod with a disk of radius 0.005 over `0.75 + 0.02 sin(2πx/0.1 + 5)` (flanks to 51.5°), μs 0.5,
/// μk 0.3, 21 points to d 0.02 — every slip's place, the disk centre's lab x and μ before and
/// after it, and the rows' d, contact point, centre and μ, to 1e-8. From slip 3 on the contact
/// sits on flanks steeper than 45°.
#[test]
fn a_round_tip_matches_the_independent_reference() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../data/drag/round_tip_reference.csv"
    ))
    .unwrap();
    let (rod, surface) = round_tip_over(0.005, 0.02, 0.1, 5.0).parts().unwrap();
    let o = DragOptions {
        d_max: 0.02,
        points: 21,
        mu_s: Some(0.5),
        mu_k: Some(0.3),
        ..DragOptions::default()
    };
    let r = vibrissa::drag(&rod, &surface, &o).unwrap();
    assert_eq!(r.slips.len(), 11, "{r}");
    let (mut checked, mut worst, mut steep) = (0, 0.0f64, 0);
    for line in text.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let (kind, k) = (f[0], f[1].parse::<usize>().unwrap());
        let v: Vec<f64> = f[2..7].iter().map(|x| x.parse().unwrap()).collect();
        let [d, xc, xt, mu, slope] = [v[0], v[1], v[2], v[3], v[4]];
        if slope.abs() > 1.0 {
            steep += 1;
        }
        let ours: Vec<(&str, f64, f64)> = match kind {
            "slip" | "slip_end" => {
                let e = &r.slips[k];
                let s = if kind == "slip" { &e.before } else { &e.after };
                vec![("d", e.d, d), ("x_tip", s.x_tip, xt), ("mu", s.mu, mu)]
            }
            _ => {
                let g = r
                    .rows
                    .iter()
                    .find(|q| q.event.is_none() && (q.d - d).abs() < 1e-15)
                    .unwrap_or_else(|| panic!("no row at d = {d}"));
                vec![
                    ("d", g.d, d),
                    ("x_contact", g.x_contact.unwrap(), xc),
                    ("x_tip", g.x_tip, xt),
                    ("mu", g.mu, mu),
                ]
            }
        };
        for (what, a, b) in ours {
            worst = worst.max((a - b).abs());
            assert!(
                (a - b).abs() < 1e-8,
                "{kind} {k}: {what} {a} against {b} (reference)"
            );
        }
        checked += 1;
    }
    assert!(
        checked >= 40 && steep >= 10,
        "{checked} values, {steep} on steep flanks"
    );
    eprintln!("round tip: {checked} reference points, largest difference {worst:.2e}");
}
