//! The drag's foot turned instead of moved (`FootMotion::Turn`): the quasi-static whisk against a
//! surface, stick–slip as the support turns with the foot held. The paper's rod (uniform,
//! η = 0.75, μs = 0.5, μk = 0.3) against the static rod of the turned clamp with its tip pinned
//! (`solve` on the rod's shooter; support/turned.rs), which is also the reference of the
//! dynamic whisk's first slip (tests/dynamic_drag.rs); where the turned rod unloads, against the
//! unloaded rod's closed form.

use vibrissa::drag::{DragEvent, Phase};
use vibrissa::{drag, DragOptions, DragResult, FootMotion, Method, Rod, StopReason, Surface};

#[path = "support/turned.rs"]
mod turned;
use turned::{pinned_ratio, turn_at_ratio};
#[path = "support/noisy_trace.rs"]
#[allow(dead_code)] // (the texture read-back's samples are tests/fit.rs's)
mod noisy_trace;
use noisy_trace::{exact, noisy, within_three_standard_errors, Rng};
use vibrissa::fit::{fit, FitOptions, Trace};
use vibrissa::Scene;

#[path = "support/slip_balance.rs"]
mod slip_balance;
use slip_balance::assert_balanced;

fn turned(d_max: f64) -> DragOptions {
    DragOptions {
        d_max,
        points: 61,
        mu_s: Some(0.5),
        mu_k: Some(0.3),
        motion: FootMotion::Turn,
        ..DragOptions::default()
    }
}

fn on_paper_surface(rod: &Rod, o: &DragOptions) -> DragResult {
    drag(rod, &Surface::flat(0.75).unwrap(), o).unwrap()
}

/// Every slip of the turned paper's rod comes at the turn where the rod, its tip pinned where
/// the last slip left it, needs μs (bisection on the pinned static rod), and ends where the rod
/// pinned at the slip's end needs μk. Measured: the nine slips to θ = 0.3 (0.0750944,
/// 0.1120609, 0.1452683, …, 0.2906486) within 6.8e-11 of the bisection, their ends within
/// 4.1e-10 of μk (the solves' tolerance 1e-10). Between slips the tip stays where it stuck.
#[test]
fn each_slip_comes_where_the_pinned_rod_needs_mu_s_and_ends_at_mu_k() {
    let r = on_paper_surface(&Rod::uniform(), &turned(0.3));
    assert_eq!(r.stop, StopReason::DMax);
    assert_eq!(r.slips.len(), 9, "{r}");
    assert!((r.slips[0].d - 0.0750944).abs() < 1e-7, "{}", r.slips[0].d);
    let mut lo = 0.0;
    for s in &r.slips {
        let at = turn_at_ratio(s.before.x_tip, 0.75, 0.5, (lo, s.d + 0.05));
        assert!((s.d - at).abs() < 1e-9, "slip at {} against {at}", s.d);
        let end = pinned_ratio(s.after.x_tip, 0.75, s.d);
        assert!((end - 0.3).abs() < 1e-9, "slip at {}: ends at {end}", s.d);
        assert!(s.jump > 0.0 && s.released > 0.0, "{s:?}");
        lo = s.d;
    }
    // the stuck tip does not move between the slips
    let mut anchor = r.rows[0].x_tip;
    for w in &r.rows {
        if w.event == Some(DragEvent::SlipEnd) {
            anchor = w.x_tip;
        } else if w.phase == Phase::Stick && w.event.is_none() {
            assert!((w.x_tip - anchor).abs() < 1e-12, "{w:?}");
            assert!(w.mu.abs() <= 0.5 * (1.0 + 1e-9), "{w:?}");
        }
    }
    // the start is the drag's pressed start
    let along = DragOptions {
        motion: FootMotion::Along,
        ..turned(0.3)
    };
    let a = on_paper_surface(&Rod::uniform(), &along);
    assert_eq!(a.rows[0], r.rows[0]);
}

/// The generic methods (multiple shooting, collocation of orders 4 and 6) turn the same drag: the
/// nine slips and their ends within 1e-9 of the rod's own shooter's (measured: 2.8e-11, 3.1e-11,
/// 3.1e-11).
#[test]
fn every_method_turns_the_same_drag() {
    let own = on_paper_surface(&Rod::uniform(), &turned(0.3));
    for method in [
        Method::MultipleShooting,
        Method::Collocation4,
        Method::Collocation6,
    ] {
        let mut o = turned(0.3);
        o.solver.method = method;
        let r = on_paper_surface(&Rod::uniform(), &o);
        assert_eq!(r.slips.len(), own.slips.len(), "{method:?}: {r}");
        let worst = (r.slips.iter().zip(&own.slips))
            .map(|(a, b)| (a.d - b.d).abs().max((a.after.x_tip - b.after.x_tip).abs()))
            .fold(0.0f64, f64::max);
        eprintln!("{method:?}: {worst:e}");
        assert!(worst < 1e-9, "{method:?}: {worst:e}");
    }
}

/// Turned on, the rod unloads: the slips come ever closer as the normal force falls, and the
/// drag ends with a lift-off where the unloaded rod's tip meets the surface (extrapolated, to
/// `UNLOAD_TOL` = 1e-6). The straight rods (uniform, taper 0.3) at `θ = acos η`, the rod of
/// rest curvature −1 (a circular arc) where `cos(φ0 − 1) − cos φ0 = η`, `φ0 = π/2 − θ`:
/// 0.172629434569279 (bisection). Measured: 1.5e-8, 2.4e-9 and 3.7e-8 off, after 6806, 3782
/// and 84 slips.
#[test]
fn a_turned_rod_unloads_where_its_rest_shape_meets_the_surface() {
    let straight = 0.75f64.acos();
    for (rod, theta) in [
        (Rod::uniform(), straight),
        (Rod::builder().taper(0.3).build().unwrap(), straight),
        (
            Rod::builder().precurvature(-1.0, 0.0).build().unwrap(),
            0.172629434569279,
        ),
    ] {
        let r = on_paper_surface(&rod, &turned(1.0));
        let StopReason::LiftOff {
            d,
            limit: Some(why),
        } = &r.stop
        else {
            panic!("{r}")
        };
        assert!((d - theta).abs() < 1e-6, "{d} against {theta}");
        assert!(why.contains("unload"), "{why}");
        let last = r.slips.last().unwrap();
        assert!(last.before.normal < 0.02 && last.d < *d, "{last:?}");
    }
}

/// A turn beyond the range of a support's turn is refused by name.
#[test]
fn refuses_a_turn_out_of_range() {
    let e = drag(&Rod::uniform(), &Surface::flat(0.75).unwrap(), &turned(1.6)).unwrap_err();
    assert!(
        e.is_input() && e.to_string().contains("largest turn"),
        "{e}"
    );
}

/// The energy balance of every phase of a turned drag to 1e-8: over a stick the support's work
/// `∫ m(0) dθ` (the clamp holds the slope `π/2 − θ`) equals the change of the elastic energy
/// (the support's spring's included), over a slip the work the sliding tip absorbs equals the
/// energy released; the paper's rod, a tapered pre-curved rod on a compliant support and a
/// corrugated surface. Measured: 1.9e-11 at most over the 45 slips. Turned clockwise, the
/// pressed rod relaxes: the support's work over each stick is negative (−0.100 over the paper's
/// rod's first), the rod works on it.
#[test]
fn a_turned_drag_balances_its_energy() {
    let scene = |f: &dyn Fn(&mut Scene)| {
        let mut s = Scene::default();
        f(&mut s);
        s
    };
    let cases = [
        ("paper", scene(&|_| {}), 0.3),
        (
            "taper 0.3, rest curvature -0.8 + 0.6 s, compliance 0.2",
            scene(&|s| {
                s.stiffness = vibrissa::Stiffness::Taper { ratio: 0.3 };
                s.precurvature = vibrissa::Precurvature::Linear { k0: -0.8, k1: 0.6 };
                s.support_compliance = 0.2;
                s.eta = 0.8;
            }),
            0.3,
        ),
        (
            "corrugated",
            scene(&|s| {
                s.surface = vibrissa::surface::SurfaceProfile::Sine {
                    amplitude: 0.01,
                    wavelength: 0.2,
                    phase: 2.0,
                }
            }),
            0.2,
        ),
    ];
    let (mut worst, mut slips) = (0.0_f64, 0);
    for (name, s, d_max) in cases {
        let (rod, surface) = s.parts().unwrap();
        let o = DragOptions {
            energy_balance: true,
            ..turned(d_max)
        };
        let r = drag(&rod, &surface, &o).unwrap();
        assert!(r.slips.len() >= 2, "{name}: {r}");
        slips += r.slips.len();
        for (k, e) in r.slips.iter().enumerate() {
            worst = worst.max(assert_balanced(name, k, e, 1e-8));
        }
    }
    eprintln!("largest imbalance {worst:e} over {slips} slips");
}

/// `fit` reads μs and μk off a turned trace (column `theta`: `Trace::motion` is `Turn`, its
/// model's drags turn too): from the exact trace of the first six slips to 1e-9, and from noisy
/// ones (the fit tests' noise levels: σ 2e-4 on the slips' turns, 2e-3 on the signals; two
/// seeds) within 3 standard errors. Measured: seed 3 0.53 and 0.95 standard errors off (μs, μk;
/// standard errors 1.0e-4, 1.5e-4), seed 11 0.80 and 0.87.
#[test]
fn fit_reads_mu_s_and_mu_k_off_a_turned_trace() {
    let r = on_paper_surface(&Rod::uniform(), &turned(0.3));
    let turn = |mut t: Trace| {
        t.motion = FootMotion::Turn;
        t
    };
    let f = fit(
        &Scene::default(),
        &turn(exact(&r, 6)),
        &FitOptions::default(),
    )
    .unwrap();
    eprintln!("exact: {f}");
    for (name, want) in [("mu_s", 0.5), ("mu_k", 0.3)] {
        assert!((f.get(name).unwrap().value - want).abs() < 1e-9, "{f}");
    }
    for seed in [3, 11] {
        let t = turn(noisy(&r, 6, &mut Rng(seed)));
        let f = fit(&Scene::default(), &t, &FitOptions::default()).unwrap();
        eprintln!("seed {seed}: {f}");
        within_three_standard_errors(&f, seed);
    }
}
