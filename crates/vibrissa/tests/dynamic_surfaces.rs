//! The dynamic drag (issue 32) on surfaces that are not flat: an inclined line and a sine
//! corrugation under the tip, against the quasi-static drag of the same scene
//! (`vibrissa::drag`, the rod's own shooter and march: an independent computation of the slow
//! limit). The paper's rod (uniform, clamped, η = 0.75, μs = 0.5, μk = 0.3) throughout.

use vibrissa::dynamics::{
    drag, ContactState, DragEventKind, DynDragOptions, DynDragResult, DynDragStop,
};
use vibrissa::surface::SurfaceProfile;
use vibrissa::{DragOptions, Rod, Surface, VibrissaError};

#[path = "support/light_drag.rs"]
mod light_drag;
use light_drag::light;

fn inclined() -> Surface {
    Surface::new(0.75, 0.1).unwrap()
}

fn corrugated(amplitude: f64, wavelength: f64) -> Surface {
    Surface::flat(0.75)
        .unwrap()
        .with_profile(&SurfaceProfile::Sine {
            amplitude,
            wavelength,
            phase: 0.0,
        })
        .unwrap()
}

/// The quasi-static drag's first slip on `surface` (its default tolerance, 1e-10).
fn quasi_static_first_slip(surface: &Surface) -> f64 {
    let r = vibrissa::drag(
        &Rod::uniform(),
        surface,
        &DragOptions {
            mu_s: Some(0.5),
            mu_k: Some(0.3),
            d_max: 0.03,
            ..DragOptions::default()
        },
    )
    .unwrap();
    r.slips[0].d
}

/// Every row is a contact the surface can hold: the tip on the surface `h` (to the solver's
/// tolerance), pushed (N > 0), stuck rows within the cone `|T| ≤ μs N`, sliding rows on it with
/// `|T| = μk N` against the slide, the forces taken along the surface's own normal at the tip.
/// (The restart after a slip takes the mean of two probe steps' tip forces, whose tip stood
/// where the surface's normal differs: on a curve it missed `|T| = μk N` by 5e-6 N in the row
/// after the slip at tol 1e-8, until the drag set its tangential part to the slide's.)
fn rows_hold(r: &DynDragResult, h: &dyn Fn(f64) -> f64) {
    for p in &r.samples {
        assert!((p.tip_y - h(p.tip_x)).abs() < 1e-9, "{p:?}");
        assert!(p.normal > 0.0, "{p:?}");
        match p.state {
            ContactState::Stuck => assert!(p.tangential.abs() <= 0.5 * p.normal + 1e-9, "{p:?}"),
            s => {
                let dir = if s == ContactState::SlidingForward {
                    1.0
                } else {
                    -1.0
                };
                assert!(
                    (p.tangential - dir * 0.3 * p.normal).abs() < 1e-9 * p.normal,
                    "{p:?}"
                );
            }
        }
    }
}

/// On a surface inclined by β = 0.1 the first slip tends to the quasi-static one as the foot
/// slows down, as `C v²` on the flat surface. Measured (dt 0.02, tol 1e-8 on 100 intervals,
/// 2026-11-29): the quasi-static slip at d = 0.0133558120, the dynamic one 6.24e-6 and
/// 1.44e-6 later at v = 0.01 and 0.005 (ratio 4.3: order 2). Bounds: 1.5 times the measured
/// error at v = 0.01, a ratio above 3.
#[test]
fn an_inclined_surface_s_first_slip_tends_to_the_quasi_static_one() {
    let d_qs = quasi_static_first_slip(&inclined());
    let e: Vec<f64> = [0.01, 0.005]
        .iter()
        .map(|&v| {
            let r = drag(&Rod::uniform(), &inclined(), &light(v, 0.02, 0.0135)).unwrap();
            rows_hold(&r, &|x| inclined_h(&r, x));
            r.first_slip().unwrap() - d_qs
        })
        .collect();
    eprintln!("quasi-static {d_qs}, errors {e:?}, ratio {}", e[0] / e[1]);
    assert!(e[0] > 0.0 && e[0] < 1.5 * 6.24e-6, "{e:?}");
    assert!(e[0] / e[1] > 3.0, "{e:?}");
}

/// The inclined line through the pressed tip (slope tan 0.1).
fn inclined_h(r: &DynDragResult, x: f64) -> f64 {
    let p = &r.samples[0];
    p.tip_y + 0.1f64.tan() * (x - p.tip_x)
}

/// Over a gentle corrugation (amplitude 0.003, wavelength 0.1) the first slip tends to the
/// quasi-static one (d = 0.0114507118, the tip on the corrugation's flank). Measured (dt 0.02,
/// tol 1e-8 on 100 intervals, 2026-11-29): 6.02e-6 and 1.51e-6 later at v = 0.01 and 0.005
/// (ratio 3.97). Bounds as on the inclined line: 1.5 times the error at v = 0.01, a ratio
/// above 3.
#[test]
fn a_corrugation_s_first_slip_tends_to_the_quasi_static_one() {
    let surface = corrugated(0.003, 0.1);
    let h = surface.profile().unwrap().clone();
    let d_qs = quasi_static_first_slip(&surface);
    let e: Vec<f64> = [0.01, 0.005]
        .iter()
        .map(|&v| {
            let r = drag(&Rod::uniform(), &surface, &light(v, 0.02, 0.0116)).unwrap();
            rows_hold(&r, &|x| h.h(x));
            r.first_slip().unwrap() - d_qs
        })
        .collect();
    eprintln!("quasi-static {d_qs}, errors {e:?}, ratio {}", e[0] / e[1]);
    assert!(e[0] > 0.0 && e[0] < 1.5 * 6.02e-6, "{e:?}");
    assert!(e[0] / e[1] > 3.0, "{e:?}");
}

/// Energy over the first slip on the corrugation, from the slip to the stick that ends it: the
/// foot's work equals the kinetic and elastic energies' change plus friction's work (the tip's
/// force times its motion, along the curved surface), to the time scheme's error. Measured
/// (v 0.05, dt 0.02, 2026-11-29): the slip at d = 0.011369, the stick at 0.026445, 0.0172
/// released, friction takes 0.0222, imbalance 6.2e-6 = 0.90 dt² of the released energy. Bound
/// 2 dt² of the released energy, as on the flat surface; without friction's work (both
/// components of the tip's motion) it does not balance.
#[test]
fn a_slip_on_a_corrugation_balances_its_energy() {
    let dt = 0.02;
    let surface = corrugated(0.003, 0.1);
    let h = surface.profile().unwrap().clone();
    let r = drag(&Rod::uniform(), &surface, &light(0.05, dt, 0.04)).unwrap();
    rows_hold(&r, &|x| h.h(x));
    let e = r.first_slip_balance().unwrap();
    let (released, friction, imbalance) = (e.released, e.friction, e.imbalance);
    eprintln!(
        "first slip {:?}, released {released:e}, friction {friction:e}, imbalance {imbalance:e} \
         = {} dt^2",
        r.first_slip(),
        imbalance / (dt * dt * released)
    );
    assert!(released > 0.01, "{released}");
    assert!(imbalance.abs() < 2.0 * dt * dt * released, "{imbalance:e}");
    assert!(friction > released);
    assert!((imbalance + friction).abs() > 100.0 * imbalance.abs());
}

/// Where the corrugation turns the rod's end into the surface (amplitude 0.02, wavelength 0.2:
/// the quasi-static drag's side touches down next to the tip at d = 0.00073344), the dynamic
/// drag stops by name, the rod's end lying down, at a place that tends to the quasi-static one
/// as the foot slows down. Measured (dt 0.02, 2026-11-29): 6.38e-6 and 1.09e-6 after it at
/// v = 0.01 and 0.002. Bounds: 1.5 times the error at v = 0.01, the slower one below a third of
/// it.
#[test]
fn a_side_reaching_the_surface_ends_the_drag_by_name() {
    let surface = corrugated(0.02, 0.2);
    let q = vibrissa::drag(
        &Rod::uniform(),
        &surface,
        &DragOptions {
            mu_s: Some(0.5),
            mu_k: Some(0.3),
            d_max: 0.002,
            ..DragOptions::default()
        },
    )
    .unwrap();
    let d_qs = q
        .rows
        .iter()
        .find(|r| r.event.is_some_and(|e| e.name() == "touchdown"))
        .unwrap()
        .d;
    let mut e = vec![];
    for v in [0.01, 0.002] {
        let r = drag(&Rod::uniform(), &surface, &light(v, 0.02, 0.01)).unwrap();
        let DynDragStop::SideContact { d, s, .. } = r.stop else {
            panic!("{}", r.stop);
        };
        assert_eq!(s, 1.0);
        assert!(r.stop.to_string().contains("end lies down"), "{}", r.stop);
        assert_eq!(r.events.last().unwrap().kind, DragEventKind::SideContact);
        e.push(d - d_qs);
    }
    eprintln!("quasi-static {d_qs}, errors {e:?}");
    assert!(e[0] > 0.0 && e[0] < 1.5 * 6.38e-6, "{e:?}");
    assert!(e[1] > 0.0 && e[1] < e[0] / 3.0, "{e:?}");
}

/// What the dynamic drag does not model is refused by name: a start with a side on the
/// surface (the rod tapered to 0.3 over a fine corrugation is pressed onto two of its crests).
/// (A friction texture is modelled: tests/dynamic_friction.rs.)
#[test]
fn refuses_a_side_at_the_start() {
    let o = light(0.05, 0.02, 0.01);
    let tapered = Rod::builder().taper(0.3).build().unwrap();
    let e = drag(&tapered, &corrugated(0.001, 0.02), &o).unwrap_err();
    assert!(matches!(e, VibrissaError::NoStart { .. }), "{e}");
    assert!(e.to_string().contains("side+side"), "{e}");
}

/// A stuck rod's velocity mismatch does not end the drag. Over the corrugation (amplitude
/// 0.003, wavelength 0.1) at dt 0.02, v 0.01 the stuck phases leave the rod's velocities a
/// mismatch with the held tip that grows from slip to slip, and its `1/τ` term in the held
/// force, not the rod, put a slip within the shortest step at T/N = 1.52: until 2026-11-30
/// the drag stopped there (`unresolved_step`, d 0.0364, after two slips). With the term taken
/// out of the search (docs/model.md, "A stuck rod the time step does not resolve") it goes on
/// through four more slips located at |T| = μs N, and ends by name where the coarse step does
/// not resolve a stick (d 0.0949; dt 0.01 reaches d_max). No event has a pulling normal force.
#[test]
fn a_stuck_rod_s_velocity_mismatch_does_not_end_the_drag() {
    let surface = corrugated(0.003, 0.1);
    let r = drag(&Rod::uniform(), &surface, &light(0.01, 0.02, 0.12)).unwrap();
    eprintln!("{r}");
    let mut located = 0;
    for (i, e) in r.events.iter().enumerate() {
        assert!(e.normal > 0.0, "{e:?}");
        // (a slip at the instant of a stick is the stick's: the force it needed at once)
        let at_once = i > 0 && r.events[i - 1].t == e.t;
        if e.kind == DragEventKind::Slip && !at_once {
            assert!(
                (e.tangential.abs() - 0.5 * e.normal).abs() < 1e-6 * e.normal,
                "{e:?}"
            );
            located += 1;
        }
    }
    assert!(located >= 6, "{located} slips located: {r}");
    let stop_d = match r.stop {
        DynDragStop::UnresolvedStick { d, .. } | DynDragStop::UnresolvedStep { d, .. } => d,
        DynDragStop::DMax => 0.12,
        _ => panic!("{}", r.stop),
    };
    assert!(stop_d > 0.09, "{}", r.stop);
    if r.stop != DynDragStop::DMax {
        assert!(r.stop.to_string().contains("shorter dt"), "{}", r.stop);
    }
}

/// A flying tip touching down on a sloped line (the precurved rod of tests/dynamic_drag.rs's
/// flight, κ0 = 1, η = 0.83, v 0.3, ramp 0.2, dt 0.005, the surface inclined by 0.02): the
/// impact removes the tip's velocity along the surface's normal there, both components of the
/// touchdown row say so (its `tip_vx` kept the velocity before the impact until 2026-11-29:
/// 2.5e-5 along the normal), and the energy from the start through the impact balances with it
/// as on the flat surface (bound 3e-5 of the foot's work); the drag goes on to d_max.
/// Measured (2026-11-29): touchdown at d = 0.230828, normal velocity 1.6e-17, impact 6.5e-6,
/// imbalance 8.6e-8 of the foot's work 0.130 (9.8e-8 since the sliding tip's lift-off test takes the
/// held force, 2026-11-30).
#[test]
fn a_touchdown_on_a_sloped_line_stops_the_normal_velocity() {
    let rod = Rod::builder().precurvature(1.0, 0.0).build().unwrap();
    let surface = Surface::new(0.83, 0.02).unwrap();
    let o = DynDragOptions {
        ramp: 0.2,
        flight: true,
        ..light(0.3, 0.005, 0.25)
    };
    let r = drag(&rod, &surface, &o).unwrap();
    // (the drag goes on after the touchdown since 2026-11-30)
    assert_eq!(r.stop, DynDragStop::DMax, "{r}");
    let down = *r
        .events
        .iter()
        .find(|e| e.kind == DragEventKind::Touchdown)
        .unwrap();
    let (a, p) = (
        &r.samples[0],
        r.samples.iter().find(|p| p.t == down.t).unwrap(),
    );
    let slope = 0.02f64.tan();
    let normal_velocity = (p.tip_vy - slope * p.tip_vx) / slope.hypot(1.0);
    let imbalance = p.foot_work
        - (p.kinetic - a.kinetic + p.elastic - a.elastic + p.friction + p.damper + p.impact);
    eprintln!(
        "touchdown at d = {}, normal velocity {normal_velocity:e}, impact {:e}, imbalance \
         {imbalance:e} of the foot's work {}",
        down.d, p.impact, p.foot_work
    );
    assert!(normal_velocity.abs() < 1e-12, "{p:?}");
    assert!(p.impact > 0.0, "{p:?}");
    assert!(imbalance.abs() < 3e-5 * p.foot_work, "{imbalance:e}");
}
