//! A stretch of the rod lying on a curved surface (issue 31).

use vibrissa::drag::{DragEvent, DragOptions, DragResult};
use vibrissa::surface::SurfaceProfile;
use vibrissa::{drag, Event, Scene, Stiffness, StopReason};

/// The rod tapered to 0.3 at η 0.75 over the corrugation 0.001 sin(2πx/0.5 + 4π/3): its last
/// contact, a side whose rest beyond is unloaded, reaches the corrugation's inflection at
/// x = 5/12 and lies down.
fn stretch_scene() -> Scene {
    Scene {
        eta: 0.75,
        stiffness: Stiffness::Taper { ratio: 0.3 },
        surface: SurfaceProfile::Sine {
            amplitude: 0.001,
            wavelength: 0.5,
            phase: 4.0 * std::f64::consts::PI / 3.0,
        },
        ..Scene::default()
    }
}

/// The drag of `scene` with `opts`.
fn drag_with(scene: Scene, opts: &DragOptions) -> DragResult {
    let (rod, surface) = scene.parts().unwrap();
    drag(&rod, &surface, opts).unwrap()
}

/// `scene` over the texture grid's corrugation 0.003 sin(2πx/0.2 + 2π/3).
fn on_grid_sine(scene: Scene) -> Scene {
    Scene {
        surface: SurfaceProfile::Sine {
            amplitude: 0.003,
            wavelength: 0.2,
            phase: 2.0 * std::f64::consts::PI / 3.0,
        },
        ..scene
    }
}

/// The drag with the paper's friction (μs 0.5, μk 0.3) to `d_max` on the default grid.
fn paper_friction(d_max: f64) -> DragOptions {
    DragOptions {
        d_max,
        mu_s: Some(0.5),
        mu_k: Some(0.3),
        ..DragOptions::default()
    }
}

/// The drag of `scene` with the paper's friction (μs 0.5, μk 0.3) to `d_max` on `points` grid
/// points.
fn drag_over(scene: Scene, d_max: f64, points: usize) -> DragResult {
    let opts = DragOptions {
        points,
        ..paper_friction(d_max)
    };
    drag_with(scene, &opts)
}

/// The drag of `scene` with `opts` and the energy balance of each slip.
fn balanced_drag(scene: Scene, opts: DragOptions) -> DragResult {
    drag_with(
        scene,
        &DragOptions {
            energy_balance: true,
            ..opts
        },
    )
}

/// Each slip's stick and slip of `r` (a [`balanced_drag`]) balance their energy to 1e-8: the
/// foot's work less the elastic energy's change and the friction of contacts sliding along,
/// and the released energy less the work of every sliding contact.
fn assert_balanced(r: &DragResult) {
    for s in &r.slips {
        let (stick, slip) = s.imbalance().unwrap();
        assert!(
            stick.abs() < 1e-8 && slip.abs() < 1e-8,
            "at d = {}: {stick:e}, {slip:e}",
            s.d
        );
    }
}

fn stretch_drag(points: usize, d_max: f64) -> DragResult {
    drag_over(stretch_scene(), d_max, points)
}

/// The rows of `data/drag/<file>` (`kind`, then the numbers by column name).
fn reference(file: &str) -> Vec<(String, std::collections::HashMap<String, f64>)> {
    let path = format!("{}/../../data/drag/{file}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            let vals = head[1..]
                .iter()
                .zip(&f[1..])
                .map(|(h, v)| (h.to_string(), v.parse().unwrap()))
                .collect();
            (f[0].to_string(), vals)
        })
        .collect()
}

/// The arc length at which the reference's stretch ends (its input, the side's place when it
/// reached the inflection): `S2` of data/drag/make_stretch_reference.py.
const S2: f64 = 0.9658524852769022;

/// The drag of the rod tapered to 0.3 whose side lies down at the corrugation's inflection,
/// against the independent computation of `data/drag/make_stretch_reference.py` (scipy: the loaded
/// rod shot from the foot to the stretch's inner end, with the moment at the foot, the
/// stretch's resultant and the inner end's arc length as unknowns; its spread from rtol 1e-13 to
/// 1e-12 is 3.3e-11): the lie-down at the inflection x = 5/12 (where the reference's stretch
/// begins), then at d = 0.05, 0.1, …, 0.7 the inner end's place, the resultant in the surface's
/// frame there, the base force and moment, and the peel-up where the stretch has shrunk back to
/// its outer end — to 1e-8.
#[test]
fn a_lying_stretch_matches_the_independent_reference() {
    let r = stretch_drag(16, 0.75);
    let stretch = |q: &vibrissa::drag::DragRow| q.contact.name() == "stretch";
    // the side lies down at the inflection, where the reference's stretch ends
    let lie = r
        .rows
        .iter()
        .find(|q| q.event == Some(DragEvent::Contact(Event::LieDown)))
        .expect("a lie-down");
    let c = lie.contacts[0];
    assert!((c.x - 5.0 / 12.0).abs() < 1e-9, "lies down at x = {}", c.x);
    assert!((c.s - S2).abs() < 1e-9, "lies down at s = {}", c.s);
    let mut worst = 0.0f64;
    let mut seen = 0;
    for (kind, want) in reference("stretch_reference.csv") {
        let d = want["d"];
        let q = if kind == "peel_up" {
            r.rows
                .iter()
                .find(|q| q.event == Some(DragEvent::Contact(Event::PeelUp)))
                .expect("a peel-up")
        } else {
            r.rows
                .iter()
                .find(|q| q.event.is_none() && (q.d - d).abs() < 1e-12)
                .unwrap_or_else(|| panic!("no row at d = {d}"))
        };
        assert!(
            stretch(q),
            "{kind} at d = {d}: contact {}",
            q.contact.name()
        );
        let c = q.contacts[0];
        let got = [
            ("d", q.d),
            ("s1", c.s),
            ("x1", c.x),
            ("normal", c.normal),
            ("tangential", c.tangential),
            ("fx", q.fx),
            ("fy", q.fy),
            ("m_base", q.m_base),
        ];
        for (name, v) in got {
            let e = (v - want[name]).abs();
            worst = worst.max(e);
            assert!(
                e < 1e-8,
                "{kind} at d = {d}: {name} {v} against {} (reference)",
                want[name]
            );
        }
        seen += 1;
    }
    assert_eq!(seen, 15);
    eprintln!("lying stretch: 15 reference rows, largest difference {worst:.2e}");
}

/// After the peel-up the side rolls on to the tip (the line's peel-back on a curve) and the
/// equilibria fold back (a snap) at d = 0.8247: every state on the way is named, and the rows
/// between the lie-down and the peel-up are the stretch's.
#[test]
fn a_lying_stretch_peels_up_and_the_drag_goes_on() {
    let r = stretch_drag(41, 1.0);
    let events: Vec<_> = r.rows.iter().filter_map(|q| q.event).collect();
    assert_eq!(
        events,
        vec![
            DragEvent::Contact(Event::LieDown),
            DragEvent::Contact(Event::PeelUp),
            DragEvent::Contact(Event::PeelBack),
            DragEvent::Contact(Event::FoldInD),
        ],
        "{r}"
    );
    assert!(matches!(r.stop, StopReason::FoldInD { .. }), "{r}");
    let at = |e: Event| {
        r.rows
            .iter()
            .position(|q| q.event == Some(DragEvent::Contact(e)))
            .unwrap()
    };
    let (a, b) = (at(Event::LieDown), at(Event::PeelUp));
    for q in &r.rows[a + 1..=b] {
        assert_eq!(q.contact.name(), "stretch", "at d = {}", q.d);
    }
    assert_eq!(r.rows[b + 1].contact.name(), "side");
}

/// A free part that reaches the surface within one step of a new stretch is met whatever the
/// output grid: the rod tapered to 0.3 over 0.003 sin(2πx/0.2 + 2π/3) lies down at
/// d = 0.0905768 with a free part 6.3e-6 above the surface, which touches down at 0.0908549;
/// the set without that touchdown folds at 0.0911078. With 11 output points the step after the
/// lie-down went to d = 0.1 on another branch of the stretch's set, and the drag made 435 slips
/// where 201 points make 436. Now both make the same events, their places within the tolerance
/// of the drag (1e-8; measured 2.5e-10).
#[test]
fn a_touchdown_beside_a_new_stretch_is_met_on_any_output_grid() {
    let scene = on_grid_sine(Scene {
        stiffness: Stiffness::Taper { ratio: 0.3 },
        ..stretch_scene()
    });
    let coarse = drag_over(scene.clone(), 0.1, 11);
    let fine = drag_over(scene, 0.1, 201);
    assert_eq!(coarse.slips.len(), fine.slips.len(), "{coarse}\n{fine}");
    let events = |r: &DragResult| -> Vec<(DragEvent, f64)> {
        r.rows
            .iter()
            .filter_map(|q| q.event.map(|e| (e, q.d)))
            .filter(|&(_, d)| d > 0.09)
            .collect()
    };
    let (a, b) = (events(&coarse), events(&fine));
    assert_eq!(
        a.iter().map(|e| e.0).collect::<Vec<_>>(),
        b.iter().map(|e| e.0).collect::<Vec<_>>()
    );
    for ((e, x), (_, y)) in a.iter().zip(&b) {
        assert!((x - y).abs() < 1e-8, "{e:?} at d = {x} and {y}");
    }
    assert_eq!(a[0].0, DragEvent::Contact(Event::LieDown));
    assert_eq!(a[1].0, DragEvent::Contact(Event::Touchdown));
    assert!((a[1].1 - 0.0908549).abs() < 1e-6, "{:?}", a[1]);
}

/// A stretch with the tip stuck on the surface beyond it: the rod tapered to 0.3 over
/// 0.003 sin(2πx/0.5 + 2.4), whose side lies down at d = 0.1391 with the tip stuck 0.067 beyond,
/// against the second scene of `data/drag/make_stretch_reference.py` (the segment beyond the
/// stretch starts at its outer end on the surface, an unknown, and ends at the stuck tip): at
/// d = 0.15, 0.2, 0.25, 0.3 the inner and outer ends, the stretch's and the tip's normal forces,
/// the base force and moment to 1e-8. The tangential forces of the stretch and the tip to 1e-7:
/// the segment between them, held at both ends without slip, is trapped (docs/model.md, "Two
/// contacts that do not slip trap the rod"), and their split is determined only to ~1e-8 — the
/// reference's own values move by 5.1e-8 from rtol 1e-13 to 1e-12, and the tip's by 4.6e-9
/// from row to row where it is constant. Measured: 2.8e-8 in the split, 1.1e-9 elsewhere.
#[test]
fn a_stretch_with_the_tip_beyond_matches_the_independent_reference() {
    let scene = Scene {
        surface: SurfaceProfile::Sine {
            amplitude: 0.003,
            wavelength: 0.5,
            phase: 2.4,
        },
        ..stretch_scene()
    };
    let r = drag_over(scene, 0.3, 7);
    assert_eq!(r.stop, StopReason::DMax, "{r}");
    let lie = r
        .rows
        .iter()
        .find(|q| q.event == Some(DragEvent::Contact(Event::LieDown)))
        .expect("a lie-down");
    // (the reference's inputs: the side's place and the tip's where it lay down)
    let (side, tip) = (lie.contacts[0], lie.contacts[1]);
    assert!((side.s - 0.9328531919102035).abs() < 1e-9, "{side}");
    assert!((side.x - 0.47855232184548324).abs() < 1e-9, "{side}");
    assert!(
        tip.tip && (tip.x - 0.5456672492594945).abs() < 1e-9,
        "{tip}"
    );
    let (mut worst, mut split) = (0.0f64, 0.0f64);
    let rows = reference("stretch_tip_reference.csv");
    assert_eq!(rows.len(), 4);
    for (_, want) in rows {
        let d = want["d"];
        let q = r
            .rows
            .iter()
            .find(|q| q.event.is_none() && (q.d - d).abs() < 1e-12)
            .unwrap_or_else(|| panic!("no row at d = {d}"));
        assert_eq!(q.contact.name(), "stretch+tip", "at d = {d}");
        let (st, tp) = (q.contacts[0], q.contacts[1]);
        let got = [
            ("s1", st.s, 1e-8),
            ("s2", st.lies_to.unwrap(), 1e-8),
            ("n_stretch", st.normal, 1e-8),
            ("n_tip", tp.normal, 1e-8),
            ("fx", q.fx, 1e-8),
            ("fy", q.fy, 1e-8),
            ("m_base", q.m_base, 1e-8),
            ("t_stretch", st.tangential, 1e-7),
            ("t_tip", tp.tangential, 1e-7),
        ];
        for (name, v, tol) in got {
            let e = (v - want[name]).abs();
            if tol > 1e-8 {
                split = split.max(e);
            } else {
                worst = worst.max(e);
            }
            assert!(
                e < tol,
                "at d = {d}: {name} {v} against {} (reference)",
                want[name]
            );
        }
    }
    eprintln!("stretch+tip: largest difference {worst:.2e}, tangential split {split:.2e}");
}

/// Where the tip lies down on a curve that bends more than the rod's end, the side it becomes
/// lies along the surface from that state's first point: it lies down there (before, "a stretch
/// lying on the surface from a contact state's first point is not followed"). The short rat
/// preset over 0.02 sin(2πx/0.5) (issue 31's texture grid) does so at d = 0.23643 after 11 949
/// slips; at d = 0.24040 the stretch needs μs all along it and slips (until 2026-12-01 a stop,
/// "a stretch sliding along the surface is not in the model", at d = 0.24034 where its
/// resultant's |T|/N reached μs), shrinks to its outer end as it slides (`peel_up`), the side
/// peels back to the tip, and the drag reaches d_max. Ignored by default: 15 s of CPU in
/// release.
#[test]
#[ignore = "slow: 11 949 slips, 15 s of CPU in release"]
fn a_side_that_lies_from_its_first_point_lies_down_there() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../data/scenes/rat_mystacial_short.toml"
    );
    let rat: Scene = toml::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let scene = Scene {
        eta: 0.75,
        surface: SurfaceProfile::Sine {
            amplitude: 0.02,
            wavelength: 0.5,
            phase: 0.0,
        },
        ..rat
    };
    let r = drag_over(scene, 0.3, DragOptions::default().points);
    let events: Vec<_> = r.rows.iter().filter_map(|q| q.event).collect();
    let lie = events
        .iter()
        .position(|e| *e == DragEvent::Contact(Event::LieDown))
        .expect("a lie-down");
    assert_eq!(events[lie - 1], DragEvent::Contact(Event::Touchdown), "{r}");
    assert_eq!(r.stop, StopReason::DMax, "{r}");
    let slip = r
        .rows
        .iter()
        .position(|q| q.event == Some(DragEvent::Slip) && q.contact.name() == "stretch")
        .expect("the stretch slips");
    assert!((r.rows[slip].d - 0.24040).abs() < 1e-5, "{r}");
    let next = r.rows[slip + 1].event;
    assert_eq!(next, Some(DragEvent::Contact(Event::PeelUp)), "{r}");
}

/// A stretch that slips: the rod tapered to 0.3 whose side lies down at the corrugation's
/// inflection (as above), with μs 0.42, against the third scene of
/// `data/drag/make_stretch_reference.py` (scipy, its own formulation: the distributed pressure
/// and friction along the stretch from `m''` in closed form, the slip threshold where the
/// stretch held without slip needs μs all along it, the slide with the foot held until μk all
/// along it balances it). With μk 0.38 three slips of the stretch, each sliding it by 0.013 and
/// ending with it intact; with μk 0.3 the first slide shrinks the stretch to its outer end
/// (`peel_up` during the slip) and the side slides on. The stuck stretch at d = 0.04, each
/// slip's place, state and energy, each slide's end (its length, the state, the released
/// energy) agree to 1e-8 (the reference's spread from rtol 1e-13 to 1e-12: 3.0e-11), and each
/// slip's released energy equals the work of the stretch's friction to 1e-8 (measured 1.6e-10;
/// without the capstan term `q1(0)` in that work, 5.1e-7).
#[test]
fn a_slipping_stretch_matches_the_independent_reference() {
    let rows = reference("stretch_slip_reference.csv");
    let mut worst = 0.0f64;
    for (mu_k, d_max, points) in [(0.3, 0.06, 13), (0.38, 0.085, 18)] {
        let opts = DragOptions {
            d_max,
            points,
            mu_s: Some(0.42),
            mu_k: Some(mu_k),
            ..DragOptions::default()
        };
        let r = balanced_drag(stretch_scene(), opts);
        assert_eq!(r.stop, StopReason::DMax, "{r}");
        let want: Vec<_> = rows.iter().filter(|(_, w)| w["mu_k"] == mu_k).collect();
        let (mut slips, mut ends) = (0, 0);
        for (kind, w) in want {
            let d = w["d"];
            let (q, slip) = match kind.as_str() {
                "stick" => {
                    let q = r
                        .rows
                        .iter()
                        .find(|q| q.event.is_none() && (q.d - d).abs() < 1e-12);
                    (q.unwrap_or_else(|| panic!("no row at d = {d}")), None)
                }
                "slip" => {
                    slips += 1;
                    let mut all = r.rows.iter().filter(|q| q.event == Some(DragEvent::Slip));
                    (all.nth(slips - 1).expect("a slip"), r.slips.get(slips - 1))
                }
                _ => {
                    ends += 1;
                    let end = if kind == "slid" {
                        DragEvent::SlipEnd
                    } else {
                        DragEvent::Contact(Event::PeelUp)
                    };
                    let mut all = r.rows.iter().filter(|q| q.event == Some(end));
                    (all.nth(ends - 1).expect("a slide's end"), None)
                }
            };
            assert_eq!(q.contact.name(), "stretch", "{kind} at d = {d}");
            let c = q.contacts[0];
            // the slides so far and, at a slide's end, its slip's released energy
            let done = &r.slips[..slips];
            let shift: f64 = done.iter().map(|s| s.jump).sum::<f64>()
                - if kind == "slip" {
                    done[slips - 1].jump
                } else {
                    0.0
                };
            let mut got = vec![
                ("d", q.d),
                ("s1", c.s),
                ("x1", c.x),
                ("normal", c.normal),
                ("tangential", c.tangential),
                ("fx", q.fx),
                ("fy", q.fy),
                ("m_base", q.m_base),
                ("s2", c.lies_to.unwrap()),
            ];
            if let Some(s) = slip {
                got.push(("energy", s.before.energy));
            }
            // (a peel-up during a slide is part way through it: its slip's length and energy
            // are the whole slide's)
            if kind != "slide_peel_up" {
                got.push(("shift", shift));
            }
            if kind == "slid" {
                got.push(("released", done[ends - 1].released));
            }
            for (name, v) in got {
                let e = (v - w[name]).abs();
                worst = worst.max(e);
                assert!(
                    e < 1e-8,
                    "mu_k {mu_k}, {kind} at d = {d}: {name} {v} against {}",
                    w[name]
                );
            }
        }
        assert_eq!(r.slips.len(), slips, "{r}");
        assert_balanced(&r);
    }
    eprintln!("slipping stretch: largest difference {worst:.2e}");
}

/// A side that slides during a slip lies down and the stretch slides on: the rod tapered to 0.3
/// over 0.003 sin(2πx/0.2 + 2π/3) (issue 31's texture grid; until 2026-12-01 this drag stopped
/// at d = 0.0882, "a stretch that slides along the surface is not in the model"). At d = 0.0882
/// the slip of the side nearer the foot drags the last side, which slides with μk until it
/// lies down; the stretch slides on with μk all along it (module `chain`, `Stretch::capstan`)
/// until the first side lets go and the stretch shrinks back to its outer end. At d = 0.0977
/// the last side drives the slip and lies down: the stretch drives it on. Each slip's released
/// energy equals the work of every sliding contact, the stretch's included, to 1e-8 (measured
/// 1.1e-10).
#[test]
fn a_side_sliding_in_a_slip_lies_down_and_slides_on() {
    // (on the default grid of 201 rows: with 11 the march's step from the stick's lie-down at
    // d = 0.0906 to 0.1 passes over a touchdown at 0.09085 whose side lifts again before 0.1,
    // a crossing and its return within one step that no event function sees)
    let r = balanced_drag(on_grid_sine(stretch_scene()), paper_friction(0.1));
    assert_eq!(r.stop, StopReason::DMax, "{r}");
    let lies: Vec<_> = r
        .rows
        .iter()
        .enumerate()
        .filter(|(_, q)| q.event == Some(DragEvent::Contact(Event::LieDown)))
        .filter(|(_, q)| q.phase == vibrissa::drag::Phase::Slip)
        .map(|(i, _)| i)
        .collect();
    assert_eq!(lies.len(), 2, "{r}");
    // the states after the lie-downs: a stretch that slides along with kinetic friction, then
    // one that drives the slip
    let holds: Vec<_> = lies
        .iter()
        .map(|&i| {
            let q = &r.rows[i + 1];
            let st = q
                .contacts
                .iter()
                .find(|c| c.lies_to.is_some())
                .expect("a stretch");
            st.hold
        })
        .collect();
    assert!(
        matches!(
            holds[..],
            [
                vibrissa::drag::Hold::Sliding { .. },
                vibrissa::drag::Hold::Slipping { .. }
            ]
        ),
        "{holds:?}"
    );
    assert_balanced(&r);
}

/// A stretch with the tip beyond it that slips: the rod tapered to 0.3 with a round tip
/// (r = 0.005) over 0.003 sin(2πx/0.2 + 2π/3) (issue 31's texture grid; until 2026-12-01 its
/// drag stopped at d = 0.0766, "a stretch sliding along the surface is not in the model"). The
/// stretch, loaded by the tip stuck beyond it, needs μs all along it at d = 0.07656 and drives a
/// slip (its balance with the load's term, `Capstan::q`), shrinking to its outer end
/// as it slides; again at d = 0.12269. Each slip's released energy equals the work of the
/// sliding contacts to 1e-8 (measured 1.9e-10: the load's term in the stretch's work is part of
/// it).
#[test]
fn a_stretch_with_the_tip_beyond_slips() {
    let scene = Scene {
        tip_radius: 0.005,
        ..on_grid_sine(stretch_scene())
    };
    let r = balanced_drag(scene, paper_friction(0.13));
    assert_eq!(r.stop, StopReason::DMax, "{r}");
    let slips: Vec<f64> = r
        .rows
        .iter()
        .filter(|q| q.event == Some(DragEvent::Slip) && q.contact.name() == "stretch+tip")
        .map(|q| q.d)
        .collect();
    assert_eq!(slips.len(), 2, "{slips:?}");
    for (d, want) in slips.iter().zip([0.07656, 0.12269]) {
        assert!((d - want).abs() < 1e-5, "a slip at d = {d}");
    }
    assert_balanced(&r);
}

/// A side sliding along in a slip with the tip beyond it lies down, the stretch slides on
/// loaded by the tip, and reaches the tip: the short rat preset over 0.003 sin(2πx/0.2 + 4π/3)
/// (issue 31's texture grid; until 2026-12-01 this drag stopped at d = 0.0529120 after 2317
/// slips, "a stretch with contacts beyond it that forms sliding along the surface is not
/// followed"; 0 and 2π/3 alike). In the slip at d = 0.0529120 the side at s = 0.98630, sliding
/// between the side at s = 0.96618 and the tip, lies down; the stretch slides on with the slip
/// to its end, where every contact holds, and the drag goes on through 64 more slips to
/// d = 0.054255. There the tip slips beside the side and the stretch; the side breaks free and
/// drives the slide, the tip and the stretch sliding along, and the stretch's outer end moves
/// out towards the tip. Where 5.6e-4 of free rod is left between them the solver no longer
/// resolves the slide (the two forces come to act at one point; its fold passage takes the
/// noise there for a fold); 1.0e-5 of the slide further on the stretch, the tip's force gone
/// over to its outer end, has reached the tip (`reach_tip`, march.rs `Run::reach_tip`): its
/// outer end, where the rod's moment is zero, 7.2e-6 inside the tip. The slip goes on with the
/// side and the stretch alone, the outer end drawing back from the tip. From 2026-12-01 to
/// 2026-12-03 the drag stopped there (to d 0.3: "the stretch ... reaches the tip: ... not
/// followed"; to d 0.06: "the equilibria fold back ... (a snap)"). (The stretch holds by the
/// friction ratio it needs, solved with the tip's load beyond it, 4.6 times its own normal
/// force, by secant steps, chain.rs `friction_ratio`.) Each slip's stick and slip balance their
/// energy to 1e-8, the sliding stretch's work included, and the work across the gap the solver
/// does not reach (4e-7, the slip's release 5.05e-5: 1.5e-11 with it). About 4 s of CPU in
/// release.
#[test]
#[ignore = "slow: 2400 slips, about 4 s of CPU in release"]
fn a_side_sliding_with_the_tip_beyond_lies_down_in_a_slip() {
    let r = rat_drag_to(0.003, 0.2, 4.0 * std::f64::consts::PI / 3.0, 0.06);
    assert_eq!(r.stop, StopReason::DMax, "{r}");
    // the lie-down in the slip at d = 0.0529120: from side+side+tip, the stretch sliding along
    // with the tip beyond it
    let at = r
        .rows
        .iter()
        .position(|q| {
            q.event == Some(DragEvent::Contact(Event::LieDown))
                && q.phase == vibrissa::drag::Phase::Slip
                && (q.d - 0.0529120).abs() < 1e-6
        })
        .unwrap_or_else(|| panic!("no lie-down in the slip at d = 0.0529120: {r}"));
    // the slip ends with the stretch, its inner end at s = 0.98134, holding
    let after = &r.rows[at + 1];
    assert_eq!(after.event, Some(DragEvent::SlipEnd), "{r}");
    assert_eq!(after.contact.name(), "side+stretch+tip", "{r}");
    assert!(after.contacts.iter().any(|c| c.lies_to.is_some()), "{r}");
    // the stretch reaches the tip in the slip at d = 0.054255: the row of the joined state,
    // its outer end at the tip, after the slide's rows with the tip beyond it
    let reach = r
        .rows
        .iter()
        .position(|q| q.event == Some(DragEvent::Contact(Event::ReachTip)))
        .unwrap_or_else(|| panic!("no reach_tip: {r}"));
    let q = &r.rows[reach];
    assert!(
        q.phase == vibrissa::drag::Phase::Slip && (q.d - 0.054255).abs() < 1e-6,
        "{q:?}"
    );
    assert_eq!(q.contact.name(), "side+stretch", "{q:?}");
    // (the first joined state the solver resolves: its outer end within 2e-5 inside the tip)
    let s2 = q.contacts.iter().find_map(|c| c.lies_to);
    assert!(s2.is_some_and(|s| s < 1.0 && s > 1.0 - 2e-5), "{q:?}");
    assert_eq!(r.rows[reach - 1].contact.name(), "side+stretch+tip", "{r}");
    assert!(r.slips.len() > 2381, "{} slips", r.slips.len());
    assert_balanced(&r);
}

/// A side that lies down in a slip between another side and the tip, and the side before it that
/// then closes up to the stretch that forms: the rod tapered to 0.3 over 0.02 sin(2πx/0.5 +
/// 2π/3) (issue 31's texture grid). In the slip at d = 0.2196442 the side at s = 0.93591 lies
/// down, and the side at s = 0.913309, sliding, closes up to the stretch (its inner end then at
/// s = 0.924322): the rod between them comes within 1e-11 of lying along the surface, where the
/// state is singular (`Crossing::Close`). Until that event the drag ended at the lie-down, "the
/// stretch that forms sliding along the surface, with contacts beyond it, is not resolved", the
/// fold passage failing 0.005 of the slide further on; from 2026-12-01 it ended at the closing by
/// name. Since 2026-12-02 the side lies down with the stretch there, as one stretch from the
/// side's place (events.rs `merged`), and the drag reaches d_max, every slip balanced.
#[test]
fn a_side_closing_up_to_a_stretch_that_formed_sliding_lies_down_with_it() {
    let r = balanced_drag(closing_scene(0.02), paper_grid());
    assert!(matches!(r.stop, StopReason::DMax), "{r}");
    assert_balanced(&r);
    let lies = |q: &&vibrissa::drag::DragRow| {
        q.event == Some(DragEvent::Contact(Event::LieDown)) && (q.d - 0.2196442).abs() < 1e-6
    };
    // (the side at 0.93591 lies down, then the side before it closes up to that stretch)
    let at: Vec<usize> = (0..r.rows.len()).filter(|&i| lies(&&r.rows[i])).collect();
    assert_eq!(at.len(), 2, "{r}");
    let (before, after) = (&r.rows[at[1]], &r.rows[at[1] + 1]);
    assert_eq!(before.contact.name(), "side+stretch+tip", "{r}");
    assert_eq!(after.contact.name(), "stretch+tip", "{r}");
    // (the side that closes up; the row after is the slip's end, the stretch slid on)
    let side = before.contacts[0].s;
    assert!((side - 0.913309).abs() < 1e-6, "{side}");
    assert!(after.contacts[0].lies_to.is_some(), "{r}");
}

/// The drag of the short rat preset at η 0.75 over `amplitude sin(2πx/wavelength + phase)`
/// (issue 31's texture grid) with the paper's friction to d = 0.3 on the program's 201 rows
/// (its trains of slips are chaotic, their counts set by the steps the output grid allows),
/// each slip's energy balance on.
fn rat_drag(amplitude: f64, wavelength: f64, phase: f64) -> DragResult {
    rat_drag_to(amplitude, wavelength, phase, 0.3)
}

/// [`rat_drag`] to `d_max`.
fn rat_drag_to(amplitude: f64, wavelength: f64, phase: f64, d_max: f64) -> DragResult {
    let path = format!(
        "{}/../../data/scenes/rat_mystacial_short.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let rat: Scene = toml::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let scene = Scene {
        eta: 0.75,
        surface: SurfaceProfile::Sine {
            amplitude,
            wavelength,
            phase,
        },
        ..rat
    };
    let opts = DragOptions {
        points: 201,
        ..paper_friction(d_max)
    };
    balanced_drag(scene, opts)
}

/// The short rat preset over 0.001 sin(2πx/0.05 + 2π/3) ([`rat_drag`]).
fn heavy_load_drag() -> DragResult {
    rat_drag(0.001, 0.05, 2.0 * std::f64::consts::PI / 3.0)
}

/// A stretch loaded by the tip beyond it with more than its own normal force holds by the
/// friction ratio it needs, not by its `T/N` ([`heavy_load_drag`]). The ratio's fixed point
/// diverges there (its factor `|dq1/dμ|/N` passes 1), and the balance is solved by secant
/// steps (chain.rs `Capstan::friction_ratio`). Until 2026-12-01 the ratio was NaN, the
/// stretch's slip limit was its `|T| = μs N`, and the drag jammed at d = 0.05083 after 10
/// slips. Later in the drag the stretch, the tip lifted, drives slips alone; where μk holds it
/// is located by its balance at μk (`ContactForce::kinetic_balance`), not by the ratio it
/// needs, which has no value as its normal force falls on towards a lift-off: searched by that
/// ratio, the slip at d = 0.0868199 ended where it began (3.0e-4 of released energy with no
/// friction work), and the one at d = 0.23115 in a lift-off that ended the drag. It now
/// reaches d_max after 52 slips, each balanced to 1e-8.
#[test]
fn a_stretch_under_a_heavy_load_beyond_holds_by_the_ratio_it_needs() {
    let r = heavy_load_drag();
    assert!(matches!(r.stop, StopReason::DMax), "{r}");
    assert_eq!(r.slips.len(), 52, "{r}");
    assert_balanced(&r);
    // (the slip that ended where it began, and the one that lifted off: each slides)
    for d in [0.0868199, 0.2311472] {
        let s = r.slips.iter().find(|s| (s.d - d).abs() < 1e-6).unwrap();
        assert!(s.jump > 1e-3, "at d = {d}: {}", s.jump);
    }
}

/// A change of contact set made with a sliding side already closed up to its neighbour: the rod
/// tapered to 0.3 over 0.003 sin(2πx/0.5 + 2π/3) (issue 31's texture grid), in the slip at d =
/// 0.1966754 after 4990. The rod touches down at s = 0.916757, 1e-11 (`CLOSED`) from lying along
/// the surface from the sliding side at s = 0.908027, so the new state's closing event is
/// positive at its first point. The march took that for a state that does not hold, a jam in a
/// slip, when the threshold of 1e-11 was first tried; from 2026-12-01 a closing pending at a
/// change ended the drag as the closing does, and since 2026-12-02 the two lie down there as one
/// stretch (march.rs `check_pending`, events.rs `merged`), 1.3e-3 of free rod short of the tip.
/// The slide's equilibria fold there at once; until 2026-12-03 that ended the drag as a snap
/// ("the equilibria fold back"). The fold is the stretch reaching the tip 8.0e-6 further on
/// (one path in energy to 1.2e-12: march.rs `Run::reach_tip`), its outer end at the sine's
/// inflection x = 7/12 (the rod's rest is straight), at the tip. Beyond, the free rod came down
/// onto the surface at the tip at once, and the stretch with the tip beyond it did not go on: a
/// jam, after the same 4990 slips and at the same d. (Before the join, on 11, 51, 101 and 401
/// rows and at tol 1e-11, the fold passage there was not resolved and the drag ended at the
/// closing by name.) Since the moving ends' derivatives are exact (2026-12-04) the fold's
/// location there is not solved; the join is tried on that failure too (where a lie-down is
/// pending, march.rs `march`), and beyond it the stretch slides on with the tip: d_max after
/// 4991 slips ([`assert_reaches_the_tip`]).
#[test]
fn a_closing_pending_at_a_change_of_set_lies_down_there() {
    let r = drag_over(closing_scene(0.003), 0.3, 201);
    assert_reaches_the_tip(&r);
}

/// [`a_closing_pending_at_a_change_of_set_lies_down_there`] with each slip's energy balance: to
/// 1e-8, the join's gap included. About 7 s of CPU in release.
#[test]
#[ignore = "slow: 4991 slips metered, about 7 s of CPU in release"]
fn a_stretch_that_reaches_the_tip_at_an_inflection_balances_every_slip() {
    let r = balanced_drag(closing_scene(0.003), paper_grid());
    assert_reaches_the_tip(&r);
    assert_balanced(&r);
}

/// The taper's drag over 0.003/0.5/2π/3 ([`a_closing_pending_at_a_change_of_set_lies_down_there`]):
/// in the slip at d = 0.1966754 after 4990 slips the two sides lie down as one stretch and the
/// stretch reaches the tip at the inflection x = 7/12. Then either the tip touches down beyond
/// it, a jam (the moving ends' derivatives by differences, before 2026-12-04), or the stretch
/// slides on with the tip and the drag reaches d_max after 4991 slips (with them exact, and as
/// a fold passed at once did, docs/performance.md): which one is decided by rounding in that
/// singular state, both by the model.
fn assert_reaches_the_tip(r: &DragResult) {
    let i = r
        .rows
        .iter()
        .position(|q| q.event == Some(DragEvent::Contact(Event::LieDown)))
        .unwrap_or_else(|| panic!("no lie-down: {r}"));
    let (lie, reach) = (&r.rows[i], &r.rows[i + 1]);
    assert!((lie.d - 0.1966754).abs() < 1e-6, "{lie:?}");
    assert_eq!(lie.contact.name(), "side+side+tip", "{r}");
    assert_eq!(
        reach.event,
        Some(DragEvent::Contact(Event::ReachTip)),
        "{reach:?}"
    );
    assert!((reach.x_tip - 7.0 / 12.0).abs() < 1e-6, "{reach:?}");
    match &r.stop {
        StopReason::Jam { d, message } => {
            assert!(
                (d - 0.1966754).abs() < 1e-6
                    && message.contains("a tip contact forms at s = 1.000000"),
                "{r}"
            );
            assert_eq!(r.slips.len(), 4990, "{r}");
            let touch = r.rows.last().unwrap();
            assert_eq!(
                touch.event,
                Some(DragEvent::Contact(Event::Touchdown)),
                "{touch:?}"
            );
        }
        StopReason::DMax => assert_eq!(r.slips.len(), 4991, "{r}"),
        _ => panic!("{r}"),
    }
}

/// The rod tapered to 0.3 over `amplitude sin(2πx/0.5 + 2π/3)`.
fn closing_scene(amplitude: f64) -> Scene {
    Scene {
        surface: SurfaceProfile::Sine {
            amplitude,
            wavelength: 0.5,
            phase: 2.0 * std::f64::consts::PI / 3.0,
        },
        ..stretch_scene()
    }
}

/// The paper's friction to d = 0.3 on the program's 201 rows.
fn paper_grid() -> DragOptions {
    DragOptions {
        points: 201,
        ..paper_friction(0.3)
    }
}
