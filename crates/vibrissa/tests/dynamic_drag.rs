//! The dynamic drag (issue 32, `vibrissa::dynamics::drag`) against the quasi-static drag of the
//! same rod: its start, the first slip's place as the foot slows down, the stuck tip's forces,
//! and the energy balance of a slip. The paper's rod throughout (uniform, clamped, η = 0.75,
//! μs = 0.5, μk = 0.3). The slow-limit study behind the bounds: examples/dynamic_drag.rs.

use vibrissa::dynamics::Whisk;
use vibrissa::dynamics::{
    drag, ContactState, DragEventKind, DynDragEvent, DynDragOptions, DynDragResult, DynDragStop,
};
use vibrissa::{scan, scan_at, Rod, ScanOptions, Surface, VibrissaError};

#[path = "support/light_drag.rs"]
mod light_drag;
use light_drag::light;
#[path = "support/turned.rs"]
mod turned;
use turned::{turn_at_ratio, turned_static};

fn paper(o: &DynDragOptions) -> DynDragResult {
    drag(&Rod::uniform(), &Surface::flat(0.75).unwrap(), o).unwrap()
}

/// The drag reached d_max or stopped where its time step does not resolve the rod (a named
/// stop), not on anything else.
fn assert_ends_by_name(r: &DynDragResult) {
    assert!(
        matches!(
            r.stop,
            DynDragStop::DMax
                | DynDragStop::UnresolvedStick { .. }
                | DynDragStop::UnresolvedStep { .. }
        ),
        "{r}"
    );
}

/// The start is the quasi-static drag's pressed start (f0 = 2.826622, docs/reference.md; the
/// scan's own start to 1e-8), at rest; up to the first slip the tip stays where it was pressed
/// and needs no more than μs.
#[test]
fn starts_pressed_and_sticks_until_mu_s() {
    let o = DynDragOptions {
        speed: 0.1,
        d_max: 0.008,
        dt: 0.02,
        ..DynDragOptions::default()
    };
    let r = paper(&o);
    let s0 = &r.samples[0];
    let q = scan(
        &Rod::uniform(),
        &Surface::flat(0.75).unwrap(),
        &ScanOptions {
            d_max: 0.001,
            points: 2,
            ..ScanOptions::default()
        },
    )
    .unwrap();
    let p0 = &q.points[0];
    assert!((s0.normal - p0.normal).abs() < 1e-8, "{s0:?} {p0:?}");
    assert!((s0.m_base - p0.m_base).abs() < 1e-8, "{s0:?} {p0:?}");
    assert!(s0.tangential.abs() < 1e-8 && s0.kinetic == 0.0);
    assert_eq!(r.stop, DynDragStop::DMax);
    assert!(r.events.is_empty());
    for p in &r.samples {
        assert_eq!(p.state, ContactState::Stuck);
        assert!((p.tip_x - s0.tip_x).abs() < 1e-9 && (p.tip_y - 0.75).abs() < 1e-9);
        assert!(p.tangential.abs() < 0.5 * p.normal, "{p:?}");
    }
    let last = r.samples.last().unwrap();
    assert!((last.d - 0.008).abs() < 1e-15, "{}", last.d);
}

/// Options out of range, and a round tip, are refused (surfaces: tests/dynamic_surfaces.rs).
#[test]
fn refuses_bad_input() {
    let flat = Surface::flat(0.75).unwrap();
    for o in [
        DynDragOptions {
            speed: 0.0,
            ..DynDragOptions::default()
        },
        DynDragOptions {
            mu_k: 0.6,
            ..DynDragOptions::default()
        },
        DynDragOptions {
            grid: 101,
            ..DynDragOptions::default()
        },
        DynDragOptions {
            speed: 1e-9,
            ..DynDragOptions::default()
        },
    ] {
        let e = drag(&Rod::uniform(), &flat, &o).unwrap_err();
        assert!(matches!(e, VibrissaError::OutOfRange { .. }), "{e}");
    }
    // a round tip is the static drag's, not this one's (it used to start with a slip at t = 0)
    let round = Rod::uniform().with_tip_radius(0.01).unwrap();
    let e = drag(&round, &flat, &DynDragOptions::default()).unwrap_err();
    assert!(matches!(e, VibrissaError::OutOfRange { .. }), "{e}");
    assert!(e.to_string().contains("tip radius"), "{e}");
}

/// Energy over the first slip, from the slip to the stick that ends it: the foot's work equals
/// the kinetic and elastic energies' change plus friction's work (no damper on the clamp), by
/// the scheme's trapezoidal identity, to the time scheme's error. Measured on the program's
/// drag (v = 0.05, tol 1e-10, 200 intervals, 2026-11-29): the imbalance is 1.18 dt² of the
/// released elastic energy at dt = 0.02, 1.29 dt² at 0.01, 1.52 dt² at 0.005, 1.95 dt² at
/// 0.0025 (halving dt divides it by 3.66, 3.40, 3.11: the restart after the slip adds a share
/// that falls more slowly; 1.25 dt² at every dt before it); the bound here is 2 dt². Friction takes more than
/// the released energy (the foot keeps working during the slip) and the kinetic energy is back
/// near zero when the tip sticks.
#[test]
fn a_slip_balances_its_energy() {
    let dt = 0.02;
    let r = paper(&light(0.05, dt, 0.0415));
    let e = r.first_slip_balance().unwrap();
    let (released, friction, imbalance) = (e.released, e.friction, e.imbalance);
    eprintln!(
        "released {released:e}, friction {friction:e}, foot {:e}, imbalance {imbalance:e} = {} \
         dt^2 of the released energy",
        e.work,
        imbalance / (dt * dt * released)
    );
    assert!(released > 0.02, "{released}");
    assert!(imbalance.abs() < 2.0 * dt * dt * released, "{imbalance:e}");
    assert!(friction > released);
    // the balance does not hold without friction's work
    assert!((imbalance + friction).abs() > 100.0 * imbalance.abs());
}

/// The first slip's place tends to the quasi-static one, d = 0.0210132486189 (docs/reference.md),
/// as `C v²` (the stuck rod's inertia: the quasi-static path's acceleration is `∝ v²`). Measured
/// by examples/dynamic_drag.rs (dt 0.01, tol 1e-10): errors 6.98e-6, 1.74e-6, 3.2e-7 at
/// v = 0.01, 0.005, 0.002 (orders 1.99, 1.86), `C` = 0.0698, 0.0694, the slip later than the
/// quasi-static one. At v = 0.01 the error must lie within [0.5, 1.5] C v².
#[test]
fn first_slip_tends_to_the_quasi_static_one() {
    let d_qs = 0.021013248618925968;
    let v = 0.01;
    let r = paper(&light(v, 0.02, 0.0211));
    let d = r.first_slip().unwrap();
    let c = 0.0694;
    eprintln!("d {d}, error {:e}, C {}", d - d_qs, (d - d_qs) / (v * v));
    assert!(
        d - d_qs > 0.5 * c * v * v && d - d_qs < 1.5 * c * v * v,
        "{d}"
    );
}

/// The stuck tip at a slow foot (v = 0.002, dt 0.05) follows the quasi-static path: N, T and
/// m(0) at every step's d after the start ramp against the scan at the same d (`scan_at`, the
/// rod's shooter at tol 1e-10). What differs is the stuck rod's inertia, `∝ v²`: measured worst
/// |ΔN|, |ΔT|, |Δm(0)| = 1.73e-5, 3.48e-5, 1.24e-6 at v = 0.002 and 6.4e-5, 1.24e-4, 3.7e-6 at
/// v = 0.004 (ratios 3.7, 3.6, 3.0), the same to 5 % at dt 0.02 and at tol 1e-10 on 200
/// intervals. Bound: 7.5 v², 15 v², 0.55 v² (1.7 times the measured). During the ramp the foot's
/// acceleration adds the rod's inertia `∝ v/ramp` (up to 7e-4 in T here), not compared.
#[test]
fn a_stuck_tip_follows_the_quasi_static_path() {
    let v = 0.002;
    let o = light(v, 0.05, 0.01);
    let r = paper(&o);
    let ds: Vec<f64> = r.samples.iter().map(|p| p.d).collect();
    let q = scan_at(
        &Rod::uniform(),
        &Surface::flat(0.75).unwrap(),
        &ScanOptions {
            d_max: 0.0101,
            ..ScanOptions::default()
        },
        &ds,
    )
    .unwrap();
    let mut worst = [0.0f64; 3];
    for (p, s) in r.samples.iter().zip(&q.points) {
        assert_eq!(p.state, ContactState::Stuck);
        assert!((p.d - s.d).abs() < 1e-15);
        if p.t < o.ramp {
            continue;
        }
        for (w, e) in worst.iter_mut().zip([
            p.normal - s.normal,
            p.tangential - s.mu * s.normal,
            p.m_base - s.m_base,
        ]) {
            *w = w.max(e.abs());
        }
    }
    eprintln!("worst |dN|, |dT|, |dm0|: {worst:?}");
    for (w, c) in worst.iter().zip([7.5, 15.0, 0.55]) {
        assert!(*w < c * v * v, "{worst:?}");
    }
}

/// The imbalance `W − (ΔK + ΔE + D_f + D_c + D_i + D_e + impact)` from sample `a` to sample `b`, and
/// the energy the dampers took between them (`DragSample::balance_to`).
fn imbalance(a: &vibrissa::dynamics::DragSample, b: &vibrissa::dynamics::DragSample) -> (f64, f64) {
    let e = a.balance_to(b);
    (e.imbalance, e.damping)
}

/// The drag with internal (Kelvin–Voigt, γ_i = 0.01) and external (γ_e = 0.1) damping: over
/// the first slip the foot's work equals the energies' change plus friction's and the
/// dampings' work, to the time scheme's error as without damping (bound 2 dt² of the released
/// energy); without the dampings' work it does not balance. Measured: the slip at d = 0.020431
/// (0.021005 undamped), 0.0292 released, the dampings take 3.79e-3 and the imbalance is
/// 9.7e-6 = 0.83 dt² of the released energy.
#[test]
fn a_damped_slip_balances_its_energy() {
    let dt = 0.02;
    let o = DynDragOptions {
        internal_damping: 0.01,
        external_damping: 0.1,
        ..light(0.05, dt, 0.0415)
    };
    let r = paper(&o);
    let (slip, stick) = first_slip(&r);
    let at = |t: f64| r.samples.iter().find(|p| p.t == t).unwrap();
    let (a, b) = (at(slip.t), at(stick.t));
    let released = a.elastic - b.elastic;
    let (bad, damping) = imbalance(a, b);
    let (whole, whole_damping) = imbalance(&r.samples[0], r.samples.last().unwrap());
    eprintln!(
        "slip at d = {}, released {released:e}, dampings {damping:e}, imbalance {bad:e} = {} dt^2 \
         of the released energy; whole drag: dampings {whole_damping:e}, imbalance {whole:e}",
        slip.d,
        bad / (dt * dt * released)
    );
    assert!(released > 0.02, "{released}");
    assert!(bad.abs() < 2.0 * dt * dt * released, "{bad:e}");
    assert!(damping > 100.0 * bad.abs(), "{damping:e}");
}

/// The drag with rotary inertia (g0 = 0.05): over the first slip the foot's work equals the
/// kinetic energy's change, the rotation's share `½∫ j φ_t²` in it, plus the elastic energy's
/// and friction's, to the time scheme's error as without it (bound 2 dt² of the released
/// energy). Measured (v 0.05, dt 0.02, tol 1e-8 on 100 intervals, 2026-11-29): the slip at
/// d = 0.0210022 (0.0210051 without rotary inertia), 0.0299 released, imbalance 1.7e-5 =
/// 1.44 dt² of it (1.18 dt² without).
#[test]
fn a_slip_with_rotary_inertia_balances_its_energy() {
    let dt = 0.02;
    let o = DynDragOptions {
        rotary_inertia: 0.05,
        ..light(0.05, dt, 0.0415)
    };
    let r = paper(&o);
    let (slip, stick) = first_slip(&r);
    let at = |t: f64| r.samples.iter().find(|p| p.t == t).unwrap();
    let (a, b) = (at(slip.t), at(stick.t));
    let released = a.elastic - b.elastic;
    let (bad, _) = imbalance(a, b);
    let plain = paper(&light(0.05, dt, 0.0415));
    eprintln!(
        "slip at d = {} (without rotary inertia {}), released {released:e}, kinetic at the \
         stick {:e}, imbalance {bad:e} = {} dt^2 of the released energy",
        slip.d,
        plain.first_slip().unwrap(),
        b.kinetic,
        bad / (dt * dt * released)
    );
    assert!(released > 0.02, "{released}");
    assert!(bad.abs() < 2.0 * dt * dt * released, "{bad:e}");
}

/// The first slip of a drag: the slip and the stick that ends it.
fn first_slip(r: &DynDragResult) -> (DynDragEvent, DynDragEvent) {
    let (slip, stick) = r.first_slip_and_stick().unwrap();
    (*slip, *stick)
}

/// A constant table of μk(|v|) is the constant μk: the same drag (events and samples) to 1e-12.
#[test]
fn a_constant_friction_table_is_the_constant_mu_k() {
    let o = light(0.05, 0.02, 0.0415);
    let a = paper(&o);
    let b = paper(&DynDragOptions {
        mu_k_table: vec![[0.0, 0.3], [0.1, 0.3]],
        ..o.clone()
    });
    assert_eq!(a.events.len(), b.events.len());
    assert_eq!(a.samples.len(), b.samples.len());
    let mut worst = 0.0f64;
    for (e, f) in a.events.iter().zip(&b.events) {
        assert_eq!((e.kind, e.state), (f.kind, f.state));
        for (x, y) in [(e.t, f.t), (e.tip_x, f.tip_x), (e.normal, f.normal)] {
            worst = worst.max((x - y).abs());
        }
    }
    for (p, q) in a.samples.iter().zip(&b.samples) {
        for (x, y) in [
            (p.tip_x, q.tip_x),
            (p.tangential, q.tangential),
            (p.friction, q.friction),
        ] {
            worst = worst.max((x - y).abs());
        }
    }
    eprintln!("{} events, worst difference {worst:e}", a.events.len());
    assert!(worst < 1e-12, "{worst:e}");
}

/// A falling (Stribeck-like) μk: 0.3 at rest to 0.2 from |v| = 0.05 on. Friction is lower
/// while the tip slides fast, so the first slip goes further than under the constant 0.3; the
/// slip's energy balances to the time scheme's second-order error, and the sliding tip's
/// friction is `μk(|ẋ(1)|)·N` at every step. Measured (v = 0.05, dt 0.02): slip length 0.04854
/// (constant 0.3: 0.04413; constant 0.2: 0.04828 — where the tip stops depends on the rod's
/// ringing as well, so the falling law's slip need not lie between the two); imbalance
/// 3.50 dt² of the released 0.0222 (3.49 dt² at dt 0.01: second order; bound 5 dt²);
/// |T − μk(v) N| ≤ 4.8e-10.
#[test]
fn a_falling_mu_k_lengthens_the_slip() {
    let dt = 0.02;
    let o = light(0.05, dt, 0.05);
    let table = vec![[0.0, 0.3], [0.05, 0.2]];
    let falling = paper(&DynDragOptions {
        mu_k_table: table.clone(),
        ..o.clone()
    });
    let length = |r: &DynDragResult| {
        let (slip, stick) = first_slip(r);
        (stick.tip_x - slip.tip_x, slip, stick)
    };
    let (l, slip, stick) = length(&falling);
    let (l3, ..) = length(&paper(&o));
    let (l2, ..) = length(&paper(&DynDragOptions {
        mu_k: 0.2,
        ..o.clone()
    }));
    let at = |t: f64| falling.samples.iter().find(|p| p.t == t).unwrap();
    let (a, b) = (at(slip.t), at(stick.t));
    let released = a.elastic - b.elastic;
    let (bad, _) = imbalance(a, b);
    let mut worst = 0.0f64;
    for p in falling
        .samples
        .iter()
        .filter(|p| p.t > slip.t && p.t < stick.t)
    {
        let mk = if p.tip_vx >= 0.05 {
            0.2
        } else {
            0.3 - 2.0 * p.tip_vx.max(0.0)
        };
        // (the condition of the step's end: its own forces, T = −Gx(1), N = −Gy(1))
        let [gx, gy] = p.step_end_forces[1];
        worst = worst.max((-gx + mk * gy).abs());
    }
    eprintln!(
        "first slip at d = {}: length {l} (constant 0.3: {l3}, constant 0.2: {l2}); released \
         {released:e}, imbalance {bad:e} = {} dt^2 of it; |T − μk(v) N| {worst:e}",
        slip.d,
        bad / (dt * dt * released)
    );
    assert!(l > l3, "{l} {l3} {l2}");
    assert!(bad.abs() < 5.0 * dt * dt * released, "{bad:e}");
    assert!(worst < 1e-8, "{worst:e}");
}

/// A lightly pressed precurved rod (κ0 = 1: its free tip at y = sin 1 = 0.841; η = 0.83,
/// N = 0.0997 at the start) dragged fast (v = 0.3, ramp 0.2) with `flight`: the tip slips at
/// once (at μs N), lifts off where N falls to zero, flies (free tip, N = 0, below the surface),
/// touches down again (a plastic impact) and goes on: it slides, lifts off and touches down
/// again, up to d_max. Checked at dt 0.005: the slip within the cone, every lift-off's N and
/// touchdown's gap `η − y(1)` at the located times (Brent on the step's length to 1e-10 in
/// time), every flight (free tip, below the surface), every impact (the tip's normal velocity
/// zero after it, its energy booked), the contact force after a touchdown (no pull: the
/// impact's backward-Euler steps, `IMPACT_STEPS`), no lift-off and touchdown within the
/// shortest step of each other (the held force's lift-off test), and the energy balance over
/// the whole drag; also pressed onto η = 0.8. Measured (2026-11-30), η 0.83: touchdowns at
/// t = 0.834744 and 0.96705, lift-offs at |N| ≤ 4.1e-14, gaps ≤ 1.2e-13, N ≥ 0.0062 in contact
/// after a touchdown; impacts 3.60e-3 (the impact's backward-Euler steps' loss with the tip
/// node's); imbalance −2.6e-6 of the foot's work 0.0538 (4.8e-5); η 0.8: 3 touchdowns, 4
/// lift-offs at |N| ≤ 4.1e-11, N ≥ 0.26 in contact, imbalance 4.9e-6 of 0.0877 (5.6e-5);
/// bound 2e-4 of the work. (Before 2026-11-30 the drag ended at the first touchdown: the
/// trapezoidal rule rang on the impact's force; and η 0.8's third touchdown was followed 1e-5
/// later by a lift-off at N = 3.1, its test reading the flight's N = 0 at the step's start.)
#[test]
fn a_flying_tip_touches_down_and_goes_on() {
    for eta in [0.83, 0.8] {
        flies_and_lands(eta);
    }
}

fn flies_and_lands(eta: f64) {
    let rod = Rod::builder().precurvature(1.0, 0.0).build().unwrap();
    let dt = 0.005;
    let o = DynDragOptions {
        speed: 0.3,
        ramp: 0.2,
        d_max: 0.3,
        flight: true,
        ..light(0.3, dt, 0.3)
    };
    let r = drag(&rod, &Surface::flat(eta).unwrap(), &o).unwrap();
    assert!(matches!(r.stop, DynDragStop::DMax), "{r}");
    let kinds: Vec<_> = r.events.iter().map(|e| e.kind).collect();
    assert_eq!(kinds[0], DragEventKind::Slip, "{r}");
    let downs: Vec<_> = r
        .events
        .iter()
        .filter(|e| e.kind == DragEventKind::Touchdown)
        .collect();
    let lifts: Vec<_> = r
        .events
        .iter()
        .filter(|e| e.kind == DragEventKind::LiftOff)
        .collect();
    assert!(downs.len() >= 2, "{r}");
    let slip = r.events[0];
    assert!(
        slip.tangential.abs() <= 0.5 * (1.0 + 1e-9) * slip.normal,
        "{slip:?}"
    );
    let shortest = 1e-5;
    for w in r.events.windows(2) {
        // (a tip that lifts off flies, one that touches down slides or sticks: no event pair
        // closer than the shortest step)
        if w[0].kind == DragEventKind::LiftOff {
            assert_eq!(w[1].kind, DragEventKind::Touchdown, "{r}");
            assert!(w[1].t - w[0].t > 10.0 * shortest, "{:?} {:?}", w[0], w[1]);
        }
    }
    let worst_lift = lifts.iter().map(|e| e.normal.abs()).fold(0.0, f64::max);
    let at = |t: f64| r.samples.iter().position(|p| p.t == t).unwrap();
    let mut worst_gap = 0.0f64;
    let mut least_n = f64::INFINITY;
    for (k, down) in downs.iter().enumerate() {
        let i = at(down.t);
        let (before, now) = (&r.samples[i - 1], &r.samples[i]);
        let gap = eta - now.tip_y;
        worst_gap = worst_gap.max(gap.abs());
        assert!(before.tip_y < eta, "{before:?}");
        assert_eq!(now.tip_vy, 0.0);
        assert!(now.impact > before.impact, "{k}: {now:?}");
        // the contact after it pushes until the tip lifts off again
        let end = lifts
            .iter()
            .find(|l| l.t > down.t)
            .map_or(f64::INFINITY, |l| l.t);
        for p in r.samples[i + 1..].iter().take_while(|p| p.t < end) {
            least_n = least_n.min(p.normal);
        }
    }
    for p in r.samples.iter().filter(|p| p.state == ContactState::Flying) {
        // (the touchdown's own sample is the flight's last, on the surface)
        let landed = downs.iter().any(|e| e.t == p.t);
        assert!((p.tip_y < eta || landed) && p.normal.abs() < 1e-10, "{p:?}");
    }
    let (a, b) = (&r.samples[0], r.samples.last().unwrap());
    let (bad, _) = imbalance(a, b);
    eprintln!(
        "eta {eta}, dt {dt}: {} touchdowns, {} lift-offs; largest |N| at a lift-off {worst_lift:e}, \
         |gap| at a touchdown {worst_gap:e}, least N in contact after a touchdown {least_n}; \
         impact {:e}, foot work {:e}, imbalance {bad:e}; {r}",
        downs.len(),
        lifts.len(),
        b.impact,
        b.foot_work
    );
    assert!(worst_lift < 1e-8, "{worst_lift:e}");
    assert!(worst_gap < 1e-10, "{worst_gap:e}");
    assert!(least_n > 0.0, "{least_n}");
    assert!(bad.abs() < 2e-4 * b.foot_work, "{bad:e}");
}

/// A friction table out of order or above μs, and negative dampings, are refused.
#[test]
fn refuses_a_bad_friction_table_or_damping() {
    let flat = Surface::flat(0.75).unwrap();
    for o in [
        DynDragOptions {
            mu_k_table: vec![[0.1, 0.3], [0.05, 0.2]],
            ..DynDragOptions::default()
        },
        DynDragOptions {
            mu_k_table: vec![[0.0, 0.3], [0.05, 0.5]],
            ..DynDragOptions::default()
        },
        DynDragOptions {
            mu_k_table: vec![[-0.1, 0.3]],
            ..DynDragOptions::default()
        },
        DynDragOptions {
            internal_damping: -1.0,
            ..DynDragOptions::default()
        },
        DynDragOptions {
            external_damping: f64::NAN,
            ..DynDragOptions::default()
        },
    ] {
        let e = drag(&Rod::uniform(), &flat, &o).unwrap_err();
        assert!(matches!(e, VibrissaError::OutOfRange { .. }), "{e}");
    }
}

/// Half the step-to-step alternation of the stuck tip's T/N over the ten steps after the
/// drag's first stick, `max |μ_k − (μ_{k−1} + μ_{k+1})/2| / 2`.
fn alternation_after_the_stick(r: &DynDragResult) -> f64 {
    let stick = r
        .events
        .iter()
        .find(|e| e.kind == DragEventKind::Stick)
        .unwrap();
    let i = r.samples.iter().position(|p| p.t == stick.t).unwrap();
    let mu: Vec<f64> = r.samples[i + 1..i + 13]
        .iter()
        .map(|p| {
            assert_eq!(p.state, ContactState::Stuck, "{p:?}");
            // (the step's end force itself: the rows' leave the mode out)
            let [tx, ny] = p.step_end_forces[1];
            tx / ny
        })
        .collect();
    (1..11)
        .map(|k| (mu[k] - 0.5 * (mu[k - 1] + mu[k + 1])).abs() / 2.0)
        .fold(0.0, f64::max)
}

/// Where the tip sticks, the force that holds it jumps (T/N from μk = 0.3 to about −0.1 within
/// the first steps), and the trapezoidal rule answers a jump of a force with a mode that
/// alternates from step to step at half the jump, whatever the step. Without the restart
/// after the stick (`Rothe::restart`) the tip's T/N alternated by ±0.34 to ±0.36 at dt 0.01,
/// 0.005, 0.0025 (tol 1e-10, grid 200), and that mode decided where the tip slipped next; with it
/// ±0.058, ±0.020, ±0.012. Here (dt 0.01, tol 1e-8, grid 100) the bound is 0.1.
#[test]
fn a_stuck_tip_s_force_does_not_alternate_after_a_stick() {
    let r = paper(&light(0.05, 0.01, 0.05));
    assert_eq!(r.stats.restarts, r.stats.slips + r.stats.sticks, "{r}");
    let eps = alternation_after_the_stick(&r);
    eprintln!("alternation {eps:e}");
    assert!(eps < 0.1, "{eps}");
}

/// The second and third slips' places at dt 0.0025 on the test drags' discretization
/// (`cargo run --release -p vibrissa --example drag_slips -- --ten --settings 0.0025,100,1e-8`):
/// within 4e-5 and 1.5e-4 of dt 0.005's, so their limits to about that (grid 200, tol 1e-10 at
/// dt 0.005: 0.061728, 0.097811). Measured again 2026-11-30 with the velocity mismatch's term
/// out of the slip search (0.061765 and 0.097679 before).
const D2_LIMIT: f64 = 0.061767;
const D3_LIMIT: f64 = 0.097690;

/// The slips' places `d` of a drag (in order).
fn slip_places(r: &DynDragResult) -> Vec<f64> {
    r.events
        .iter()
        .filter(|e| e.kind == DragEventKind::Slip)
        .map(|e| e.d)
        .collect()
}

/// The second slip converges as dt → 0 (to [`D2_LIMIT`]). After the first stick the stuck rod
/// rings about a T/N that rises towards μs, and the tip slips at the first crest that reaches
/// μs N; the slip test on the held force without the trapezoidal rule's alternating mode
/// (`dyndrag.rs` `Drive::held_force`) makes that crest the rod's own. Measured at these
/// settings (tol 1e-8, grid 100): d = 0.063336, 0.062094, 0.061733, 0.061767 at dt 0.02, 0.01,
/// 0.005, 0.0025 (0.063333, 0.062093, 0.061729, 0.061765 before the velocity mismatch's term
/// was taken out of the search, 2026-11-30); the bound at dt 0.01 is about 3 times its distance
/// from the limit (3.3e-4).
/// Without that test the alternation, grown to ±0.04 in T/N by then at every dt, made the tip
/// slip a crest earlier, at d = 0.055837 (dt 0.01; 0.055790 and 0.055706 at 0.005 and 0.0025).
#[test]
fn the_second_slip_comes_at_its_limit() {
    let r = paper(&light(0.05, 0.01, 0.064));
    let d = slip_places(&r);
    eprintln!("{r}; slips {d:?}");
    // its row reports the force the slip test takes, so T/N there is μs (measured 0.5 − 4.9e-11),
    // not the end force with the rule's alternating mode (±0.04 in T/N by then; the row said
    // 0.554 when it reported the end force)
    let second = r
        .events
        .iter()
        .filter(|e| e.kind == DragEventKind::Slip)
        .nth(1);
    let second = second.expect("a second slip");
    let ratio = second.tangential / second.normal;
    eprintln!("second slip's T/N {ratio}");
    assert!((ratio - 0.5).abs() < 1e-6, "{second:?}");
    assert!(d.len() >= 2, "{r}");
    assert!((d[1] - D2_LIMIT).abs() < 1e-3, "{}", d[1]);
}

/// The third slip converges as the second does (measured at these settings: d = 0.101367,
/// 0.098300, 0.097828, 0.097690 at dt 0.02, 0.01, 0.005, 0.0025, differences falling 6.5 and
/// 3.4 times; 0.101450, 0.098306, 0.097828, 0.097679 before the velocity mismatch's term was
/// taken out of the search; without the held force's test 0.100286 and 0.097859 at dt 0.02 and 0.01, 0.090683
/// at 0.005 on grid 200, tol 1e-10); the bound is about 3 times the distance at dt 0.01 from the
/// limit (6.1e-4).
#[test]
#[ignore = "slow: 2 drags to d 0.1, about a minute in debug; the default guard is the_second_slip_comes_at_its_limit"]
fn the_third_slip_converges_in_dt() {
    for dt in [0.01, 0.005] {
        let r = paper(&light(0.05, dt, 0.1));
        let d = slip_places(&r);
        eprintln!("dt {dt}: {r}; slips {d:?}");
        assert!(d.len() >= 3, "{r}");
        assert!((d[2] - D3_LIMIT).abs() < 2e-3, "{}", d[2]);
    }
}

/// A finer time step goes at least as far as a coarser one. Over a stuck phase the rod's
/// velocities drift from the held tip's condition (the trapezoidal rule does not damp the
/// mismatch, and each step adds to it), and a step of length τ from such a state puts a term
/// like `1/τ` into the held force. The slip search reads the force at steps down to 1e-5, so
/// until 2026-11-30 it found a slip there, and the drag stopped as `unresolved_step`. At these
/// settings dt 0.0025 stopped at d 0.13298 after three slips and dt 0.005 at d 0.31146 after
/// eight, while dt 0.01 went through ten. The search now takes that term out
/// (`dyndrag.rs` `Drive::deflate`). The drag at dt 0.0025 then passes d 0.14 with its fourth
/// slip at |T| = μs N (0.132999; 0.132895 at dt 0.005).
#[test]
fn a_finer_step_goes_as_far() {
    let r = paper(&light(0.05, 0.0025, 0.14));
    eprintln!("{r}; slips {:?}", slip_places(&r));
    assert_eq!(r.stop, DynDragStop::DMax, "{r}");
    let slips: Vec<&DynDragEvent> = r
        .events
        .iter()
        .filter(|e| e.kind == DragEventKind::Slip)
        .collect();
    assert_eq!(slips.len(), 4, "{r}");
    for e in slips {
        assert!((e.tangential / e.normal - 0.5).abs() < 1e-6, "{e:?}");
    }
}

/// The mesh of the drag's steps comes back down after the events (dt 0.01, tol 1e-8, grid 100;
/// the drag of [`the_second_slip_comes_at_its_limit`], past the first slip, the first stick
/// and the second slip). The collocation refines a step's mesh where its residual exceeds tol
/// and does not coarsen it; when every step started from the last solution's mesh, the nodes
/// added for one step stayed, and the last step's mesh had grown from the history grid's 101
/// nodes to 157 by d = 0.064 (220 by the tenth stick), each node a cost in every Newton
/// iteration's factorization. Since a step starts from that mesh with the intervals whose
/// residual is below tol/100 merged in pairs (never across a node of the history grid): 122
/// (docs/performance.md, "The dynamic drag against PyElastica"). The bound is halfway. And a
/// step the event's search tries again from the same state with the same length is not solved
/// again: 250 solves where there were 257 (the bound halfway; 252 since the slip search tests
/// the held force's velocity mismatch with two more steps, `Drive::deflate`).
#[test]
fn the_mesh_comes_back_down_after_the_events() {
    let r = paper(&light(0.05, 0.01, 0.064));
    eprintln!("{r}; last mesh {}", r.stats.mesh_nodes);
    assert!(slip_places(&r).len() >= 2, "{r}");
    assert!(r.stats.mesh_nodes < 140, "{}", r.stats.mesh_nodes);
    assert!(r.stats.solves < 254, "{r}");
}

/// The most events `r` has at one instant (no step between them).
fn most_at_one_instant(r: &DynDragResult) -> usize {
    let mut most = 0;
    let mut run = 0;
    for (k, e) in r.events.iter().enumerate() {
        run = if k > 0 && e.t == r.events[k - 1].t {
            run + 1
        } else {
            1
        };
        most = most.max(run);
    }
    most
}

/// A coarse drag (dt 0.05, grid 20, tol 1e-6) ends by name. It used to cycle without end at
/// d = 0.23367 (a stick, then over and over a slip and a stick at the same instant): the stuck
/// tip's slip search kept the flag of the slip before it, so a stick at once was taken for a
/// slip at once. With that mended, an event searched below a step of 5e-5 read the forces of so
/// short a step, which at tol 1e-6 carry the positions' error times 4/τ² (1.6e3): a slip with
/// N = −480 and then a lift-off. Events are no longer searched on steps shorter than
/// `0.1 √tol` (1e-4 here; 1e-5 at tol 1e-8 and below as before), and the drag stopped at d =
/// 0.2266, a stick the step does not resolve, after five slips; since 2026-11-29 it stops at
/// d = 0.2055 after four, a stuck rod the step does not resolve (the fifth slip read
/// T/N = 1.65 within the shortest step: `unresolved_step`; one of its slips reads T/N = 0.507 at
/// this tol). Every event's normal force is compressive and no more than three share an
/// instant.
#[test]
fn a_coarse_drag_ends_by_name() {
    let o = DynDragOptions {
        speed: 0.05,
        dt: 0.05,
        d_max: 0.25,
        tol: 1e-6,
        grid: 20,
        max_events: 60,
        ..DynDragOptions::default()
    };
    let r = paper(&o);
    eprintln!("{r}");
    assert_ends_by_name(&r);
    assert!(slip_places(&r).len() >= 4, "{r}");
    for e in &r.events {
        assert!(e.normal > 0.0, "{e:?}");
    }
    assert!(most_at_one_instant(&r) <= 3, "{r}");
}

/// Where a step is too coarse to resolve a stick, the drag says so and stops. Right after a
/// stick the rod's held force starts from the sliding one (it changes like `√t`), so a stuck
/// tip that needs a pull or more than μs N at once is the time step's. At dt 0.05 (grid 20,
/// tol 1e-8) the tip sticks at d = 0.1298 and needs |T| = 0.87 N at once by the restart's
/// forces (1.12 N at d = 0.12971 since the slip search takes the velocity mismatch's term out
/// of the held force, 2026-11-30); slipping the way that force points it moves the other way, and stuck again it needs
/// the same: it used to slip and stick at that instant until `max_events`. At dt 0.1 (grid 20,
/// tol 1e-10) it sticks at d = 0.0418 and needs a pull at once (N = −0.82; −0.83 at grid 200),
/// which was taken for a slip with a tensile force. (The force needed at once depends on the
/// restart's steps, `tol^(1/3)` long: at tol 1e-8 and 1e-9 the same stick needs N = 1.76 and
/// 0.94 and more than μs N, as a numerical force does.) Both stop `UnresolvedStick` at the stick, without an event
/// that has a pull, and at dt 0.02 the first drag goes on past it.
#[test]
fn a_stick_the_step_cannot_resolve_is_a_named_stop() {
    let coarse = DynDragOptions {
        speed: 0.05,
        dt: 0.05,
        d_max: 0.15,
        tol: 1e-8,
        grid: 20,
        max_events: 200,
        refinements: 0,
        ..DynDragOptions::default()
    };
    for (dt, tol, at, pull) in [(0.05, 1e-8, 0.1298, false), (0.1, 1e-10, 0.0418, true)] {
        let r = paper(&DynDragOptions {
            dt,
            tol,
            ..coarse.clone()
        });
        eprintln!("{r}");
        let DynDragStop::UnresolvedStick {
            d,
            normal,
            tangential,
            ..
        } = r.stop
        else {
            panic!("{r}")
        };
        assert!((d - at).abs() < 1e-3, "{r}");
        assert_eq!(normal < 0.0, pull, "{r}");
        assert!(pull || tangential.abs() > coarse.mu_s * normal, "{r}");
        assert!(r.events.len() < 20, "{r}");
        assert!(r.events.iter().all(|e| e.normal > 0.0), "{r}");
        assert!(r.stop.to_string().contains("shorter dt"), "{}", r.stop);
    }
    let finer = paper(&DynDragOptions { dt: 0.02, ..coarse });
    assert_eq!(finer.stop, DynDragStop::DMax, "{finer}");
    assert!(most_at_one_instant(&finer) <= 3, "{finer}");
}

/// The same coarse drags with the program's refinements (`refinements` 3, the default): the
/// steps from the last event before each unresolved stick are taken again at dt/2, dt/4 and
/// dt/8 where needed. At dt 0.05 the drag goes on to `d_max` (one refinement), as the finer
/// dt 0.02 does without them; at dt 0.1 (tol 1e-10) from its stop at d = 0.0418 on through two
/// more slips to one at d = 0.1263 that dt/8 does not resolve either (seven refinements). Every
/// event compressive and every located slip inside the friction cone (to 1e-6 of μs N).
#[test]
fn a_stick_the_step_does_not_resolve_is_taken_again_with_shorter_steps() {
    for (dt, tol, end) in [(0.05, 1e-8, 0.15), (0.1, 1e-10, 0.1263)] {
        let r = paper(&DynDragOptions {
            speed: 0.05,
            dt,
            d_max: 0.15,
            tol,
            grid: 20,
            max_events: 200,
            ..DynDragOptions::default()
        });
        eprintln!("{r}");
        match r.stop {
            DynDragStop::DMax => assert_eq!(end, 0.15, "{r}"),
            DynDragStop::UnresolvedStick { d, .. } => assert!((d - end).abs() < 1e-3, "{r}"),
            _ => panic!("{r}"),
        }
        assert!(r.stats.refinements >= 1, "{r}");
        assert!(most_at_one_instant(&r) <= 3, "{r}");
        for (i, e) in r.events.iter().enumerate() {
            assert!(e.normal > 0.0, "{e:?}");
            let at_once = i > 0 && r.events[i - 1].t == e.t;
            if e.kind == DragEventKind::Slip && !at_once {
                assert!(e.tangential.abs() <= 0.5 * e.normal * (1.0 + 1e-6), "{e:?}");
            }
        }
        // the returned drag's own counts: its samples' steps, its events' slips
        let slips = r
            .events
            .iter()
            .filter(|e| e.kind == DragEventKind::Slip)
            .count();
        assert_eq!(r.stats.slips, slips, "{r}");
        assert!(r.samples.windows(2).all(|w| w[1].t > w[0].t), "{r}");
    }
}

/// A step the collocation does not solve is taken again with shorter steps, as a stick the step
/// does not resolve. The paper's rod at dt 0.0625, grid 20, tol 1e-6 (v 0.05): the first full
/// step after the slip at t = 7.1387 stalled Newton (residual 2.3e3 on 1967
/// nodes), and the drag ended in that solver error; from the state after the event before, at
/// dt/2, it goes past that instant. Without refinements the error stands (the failure is real).
/// One slip, at d 0.30224 (t 7.0449), lies beyond the cone (T/N 0.557): it is placed on the
/// shorter steps taken again from the stick at t 6.7636 (at dt the tip stayed stuck there), its
/// own refinements do not resolve it, and the drag goes on from it by the rule for such slips;
/// every other slip is inside.
#[test]
fn a_step_newton_does_not_solve_is_taken_again_with_shorter_steps() {
    let o = DynDragOptions {
        speed: 0.05,
        dt: 0.0625,
        d_max: 0.31,
        tol: 1e-6,
        grid: 20,
        ..DynDragOptions::default()
    };
    let r = paper(&o);
    assert_eq!(r.stop, DynDragStop::DMax, "{r}");
    assert!(r.stats.refinements >= 1, "{r}");
    let mut beyond = 0;
    for e in &r.events {
        assert!(e.normal > 0.0, "{e:?}");
        if e.kind == DragEventKind::Slip && e.tangential.abs() > 0.5 * e.normal * (1.0 + 1e-6) {
            beyond += 1;
        }
    }
    assert!(beyond <= 1, "{r}");
    // past the failed instant, the rows going on in time
    assert!(r.samples.last().is_some_and(|p| p.t > 7.19), "{r}");
    assert!(r.samples.windows(2).all(|w| w[1].t > w[0].t), "{r}");
    let without = drag(
        &Rod::uniform(),
        &Surface::flat(0.75).unwrap(),
        &DynDragOptions {
            refinements: 0,
            ..o
        },
    );
    assert!(
        matches!(without, Err(VibrissaError::Solver { .. })),
        "{without:?}"
    );
}

/// A stick that needs a pull within the shortest step after it is the time step's too. At
/// dt 0.05 with internal damping 0.01 (v = 0.01, grid 20, tol 1e-10) the third stick, at
/// d = 0.07705, is within the limits at once, but the slip search of the next step found its
/// root inside the shortest step (5e-5), whose force is a pull: the drag recorded a slip with
/// N = −15.5 (and ended cycling). Now it stops `UnresolvedStick` there with that force, and no
/// event has a pull (since the search takes the velocity mismatch's term out of the held force,
/// 2026-11-30: the stick at d = 0.077017, N = −15.2).
#[test]
fn a_pull_within_the_shortest_step_after_a_stick_is_unresolved() {
    let o = DynDragOptions {
        speed: 0.01,
        dt: 0.05,
        d_max: 0.08,
        tol: 1e-10,
        grid: 20,
        internal_damping: 0.01,
        max_events: 200,
        refinements: 0,
        ..DynDragOptions::default()
    };
    let r = paper(&o);
    eprintln!("{r}");
    let DynDragStop::UnresolvedStick { d, normal, .. } = r.stop else {
        panic!("{r}")
    };
    assert!((d - 0.07705).abs() < 1e-4 && normal < 0.0, "{r}");
    assert_eq!(r.events.len(), 6, "{r}");
    assert!(r.events.iter().all(|e| e.normal > 0.0), "{r}");
}

/// A whisk of amplitude `a` at `f` whisks per time unit with the foot held (a table of `d ≡ 0`
/// to `t_end`), time step `dt`, on the test drags' discretization (tol 1e-8, 100 intervals).
fn held_foot_whisk(t_end: f64, a: f64, f: f64, dt: f64) -> DynDragOptions {
    DynDragOptions {
        foot_table: vec![[0.0, 0.0, 0.0], [t_end, 0.0, 0.0]],
        whisk: Some(Whisk {
            amplitude: a,
            frequency: f,
        }),
        dt,
        grid: 100,
        tol: 1e-8,
        ..DynDragOptions::default()
    }
}

/// The foot turned: `whisk` with the foot held and the tip held by a large μs, at `f` whisks per
/// time unit over a quarter whisk, dt `dt`. Returns the largest `|Δm(0)|` against the static rod
/// at the same turn with the tip where it is held ([`turned_static`]), and the run.
fn slow_whisk(f: f64, dt: f64) -> (f64, DynDragResult) {
    let o = DynDragOptions {
        mu_s: 100.0,
        ..held_foot_whisk(0.25 / f, 0.2, f, dt)
    };
    let r = paper(&o);
    assert_eq!(r.stop, DynDragStop::TableEnd, "{}", r.stop);
    let mut worst = 0.0f64;
    for p in &r.samples {
        assert_eq!(p.state, ContactState::Stuck);
        let q = turned_static(p.tip_x, p.tip_y, p.theta);
        worst = worst.max((p.m_base - q.m_base).abs());
    }
    (worst, r)
}

/// A slow whisk follows the static states of the turned rod: m(0) of the dynamic whisk against
/// the static solve at the same turn, with the tip where it is held. The difference is the rod's
/// inertia, `∝ f²`: measured worst |Δm(0)| 8.79e-6 at f = 0.02 and 2.24e-6 at 0.01 (ratio
/// 3.92; dt 0.1, tol 1e-8 on 100 intervals), bound 0.035 f² (1.6 times the measured).
#[test]
fn a_slow_whisk_follows_the_turned_static_rod() {
    let (e1, r1) = slow_whisk(0.02, 0.1);
    let (e2, _) = slow_whisk(0.01, 0.1);
    let last = r1.samples.last().unwrap();
    assert!((last.theta - 0.1).abs() < 1e-12, "{}", last.theta);
    for (e, f) in [(e1, 0.02), (e2, 0.01)] {
        assert!(e < 0.035 * f * f, "f {f}: {e:e}");
    }
    assert!(e1 / e2 > 3.0 && e1 / e2 < 5.0, "{e1:e} {e2:e}");
}

/// A whisk against the surface with the foot held: the support turns by `A (1 − cos 2πft)/2`
/// (A 0.3, f 0.05) to t = 6, through its first two slips; the energy balance from the start to
/// the end, the turn's work `m(0) δθ` in the foot's. Measured (tol 1e-8, 100 intervals): the
/// foot's work −0.2570 (the turn relieves the pressed rod), friction's 0.032, imbalance 2.70e-5
/// at dt 0.02 and 9.06e-6 at dt 0.01 (0.26 and 0.35 dt² of the work); with the turn's work
/// left out, or its sign turned, the imbalance would be the work itself.
#[test]
fn a_whisk_balances_its_energy() {
    for dt in [0.02, 0.01] {
        let o = held_foot_whisk(6.0, 0.3, 0.05, dt);
        let r = paper(&o);
        assert_eq!(r.stop, DynDragStop::TableEnd);
        assert_eq!(r.stats.slips, 2, "{}", r.stats);
        let (a, b) = (&r.samples[0], r.samples.last().unwrap());
        let (imb, _) = imbalance(a, b);
        assert!(b.foot_work < -0.25 && b.friction > 0.03, "{b:?}");
        assert!(
            imb.abs() < 0.5 * dt * dt * b.foot_work.abs(),
            "dt {dt}: {imb:e}"
        );
        assert!(b.d == 0.0 && (b.theta - o.turn_at(6.0)).abs() < 1e-15);
    }
}

/// A foot table of two rows is the straight line through them: the drag at speed `v` from
/// `t = 0` (`ramp` 0), the same to rounding (first slip and stick within 1e-9 in d and t).
#[test]
fn a_two_row_foot_table_is_the_constant_speed() {
    let (v, t_end) = (0.05, 1.0);
    let line = DynDragOptions {
        foot_table: vec![[0.0, 0.0, 0.0], [t_end, v * t_end, 0.0]],
        ..light(v, 0.02, 0.05)
    };
    let ramp0 = DynDragOptions {
        ramp: 0.0,
        ..light(v, 0.02, 0.05)
    };
    let (a, b) = (paper(&line), paper(&ramp0));
    assert_eq!(a.stop, DynDragStop::TableEnd);
    assert_eq!(b.stop, DynDragStop::DMax);
    assert_eq!(a.events.len(), b.events.len());
    assert!(!a.events.is_empty());
    for (p, q) in a.events.iter().zip(&b.events) {
        assert_eq!(p.kind, q.kind);
        assert!(
            (p.d - q.d).abs() < 1e-9 && (p.t - q.t).abs() < 1e-9,
            "{p:?} {q:?}"
        );
    }
    assert!(a.samples.iter().all(|p| p.theta == 0.0));
}

/// A foot table or a whisk out of range is refused by name.
#[test]
fn refuses_a_bad_foot_table_or_whisk() {
    let flat = Surface::flat(0.75).unwrap();
    let table = |rows: Vec<[f64; 3]>| DynDragOptions {
        foot_table: rows,
        ..DynDragOptions::default()
    };
    for o in [
        table(vec![[0.0, 0.0, 0.0]]),
        table(vec![[0.1, 0.0, 0.0], [1.0, 0.1, 0.0]]),
        table(vec![[0.0, 0.0, 0.0], [1.0, 0.1, 0.0], [1.0, 0.2, 0.0]]),
        table(vec![[0.0, 0.0, 0.0], [1.0, f64::NAN, 0.0]]),
        table(vec![[0.0, 0.0, 0.0], [1.0, 0.1, 2.0]]),
    ] {
        let e = drag(&Rod::uniform(), &flat, &o).unwrap_err();
        assert!(
            matches!(&e, VibrissaError::InvalidTable { name, .. } if name == "foot"),
            "{e}"
        );
        assert!(e.is_input());
    }
    for (amplitude, frequency) in [(2.0, 0.1), (0.1, 0.0), (0.1, 2000.0), (f64::NAN, 1.0)] {
        let o = DynDragOptions {
            whisk: Some(Whisk {
                amplitude,
                frequency,
            }),
            ..DynDragOptions::default()
        };
        let e = drag(&Rod::uniform(), &flat, &o).unwrap_err();
        assert!(e.to_string().contains("whisk"), "{e}");
    }
    let parsed = vibrissa::dynamics::parse_foot_table("t d theta\n0 0\n1, 0.1, 0.05 # turned\n");
    assert_eq!(parsed.unwrap(), vec![[0.0, 0.0, 0.0], [1.0, 0.1, 0.05]]);
    let e = vibrissa::dynamics::parse_foot_table("0 0\n1 x\n").unwrap_err();
    assert!(e.to_string().contains("line 2"), "{e}");
}

/// Largest `|x_i − (x_{i−1} + x_{i+1})/2|` over the stuck rows `i` with stuck neighbours after
/// the first stick, of `f(sample)`.
fn stuck_alternation(r: &DynDragResult, f: &dyn Fn(&vibrissa::dynamics::DragSample) -> f64) -> f64 {
    let first = r.events[0].t;
    r.samples
        .windows(3)
        .filter(|w| {
            w.iter()
                .all(|p| p.state == ContactState::Stuck && p.t > first)
        })
        .map(|w| (f(&w[1]) - 0.5 * (f(&w[0]) + f(&w[2]))).abs())
        .fold(0.0, f64::max)
}

/// The rows' forces after the first event leave the time rule's alternating mode out (as the
/// stuck tip's tests do): the paper's drag at dt 0.02 through five slips. Measured (tol 1e-8,
/// 100 intervals): over the stuck rows the largest |T|/N is 0.5 + 7e-13 (the step's end
/// forces: 0.578, a stuck tip beyond μs), and the largest second difference of neighbouring
/// stuck rows is 0.102 in N and 0.272 in fy against the end forces' 0.453 and 0.777 (what is
/// left is the stuck rod's own ringing, about seven steps a period).
#[test]
fn the_rows_forces_leave_the_mode_out() {
    let r = paper(&light(0.05, 0.02, 0.2));
    assert_eq!(r.stats.slips, 5, "{r}");
    let stuck = || r.samples.iter().filter(|p| p.state == ContactState::Stuck);
    let ratio = stuck()
        .map(|p| p.tangential.abs() / p.normal)
        .fold(0.0, f64::max);
    let end_ratio = stuck()
        .map(|p| (p.step_end_forces[1][0] / p.step_end_forces[1][1]).abs())
        .fold(0.0, f64::max);
    assert!(ratio < 0.5 * (1.0 + 1e-9), "{ratio}");
    assert!(end_ratio > 0.55, "{end_ratio}");
    for (rows, ends) in [
        (
            stuck_alternation(&r, &|p| p.normal),
            stuck_alternation(&r, &|p| -p.step_end_forces[1][1]),
        ),
        (
            stuck_alternation(&r, &|p| p.fy),
            stuck_alternation(&r, &|p| p.step_end_forces[0][1]),
        ),
    ] {
        assert!(rows < 0.4 * ends, "{rows:e} {ends:e}");
    }
}

/// The first slip of a slow whisk (A 0.3, the foot held) comes at the turn where the static
/// rod, its tip pinned where it was pressed, needs μs: 0.0750944 (the static solve on the rod's
/// shooter, another method than the steps' collocation). Measured (dt 0.1, tol 1e-8 on 100
/// intervals): the dynamic whisk's first slip is off by −4.9e-5, 7.3e-6, 2.0e-6, −7.9e-8,
/// −2.1e-7 at f = 0.08, 0.04, 0.02, 0.01, 0.005 (the rod's inertia, then the steps' own error);
/// bounds 1.5e-5 at 0.04, 4e-6 at 0.02, 5e-7 at 0.005.
#[test]
fn the_first_slip_of_a_slow_whisk_tends_to_the_quasi_static_one() {
    let run = |f: f64| {
        let o = DynDragOptions {
            max_events: 1,
            ..held_foot_whisk(0.2 / f, 0.3, f, 0.1)
        };
        let r = paper(&o);
        let e = r.events[0];
        assert_eq!(e.kind, DragEventKind::Slip);
        (o.turn_at(e.t), r.samples[0].tip_x)
    };
    let (_, x_a) = run(0.02);
    let qs = turn_at_ratio(x_a, 0.75, 0.5, (0.0, 0.12));
    assert!((qs - 0.0750944).abs() < 1e-6, "{qs}");
    for (f, bound) in [(0.04, 1.5e-5), (0.02, 4e-6), (0.005, 5e-7)] {
        let (turn, _) = run(f);
        assert!((turn - qs).abs() < bound, "f {f}: {turn} against {qs}");
    }
}

/// The paper's rod on a viscoelastic support (compliance 1, damper `c` at the foot; v = 0.1,
/// ramp 2): the first slip is located at |T| = μs N and its place converges in dt. Before the
/// drag's first event the end forces carry a velocity mismatch's `1/τ` term (the velocities miss
/// the stuck tip's condition by what each step's solve leaves; measured `A` = 7.2e-7 against
/// N = 1.73 at c = 0, dt 0.005), which the slip's search read at its shortest steps: at the
/// program's defaults (grid 200, tol 1e-10) the drag stopped as `unresolved_step` before any
/// slip at dt 0.01 for c = 0.2, 0.5, 2 (at dt 0.005 too for c = 2), and at c = 0, dt 0.005 it
/// slipped at T/N = 0.5231. The search now takes the term out of the end forces too
/// (dyndrag.rs `end_mismatch_weight`). Measured here (grid 100, tol 1e-8): c = 0 slips at
/// d = 0.00100195 and 0.00100163 at dt 0.01 and 0.005, c = 0.5 at 0.00056910 and 0.00057354,
/// T/N within 1.7e-8 of μs; before, c = 0 at dt 0.005 slipped at T/N = 0.5274. Bounds: 1e-6 in
/// T/N, 1e-5 between the two steps' places.
#[test]
fn a_viscoelastic_support_slips_at_mu_s() {
    let rod = Rod::builder().support_compliance(1.0).build().unwrap();
    let first = |c: f64, dt: f64| {
        let o = DynDragOptions {
            foot_damping: c,
            ..light(0.1, dt, 0.0012)
        };
        let r = drag(&rod, &Surface::flat(0.75).unwrap(), &o).unwrap();
        eprintln!("c {c}, dt {dt}: {r}");
        assert_eq!(r.stop, DynDragStop::DMax, "{r}");
        let e = r.events[0];
        assert_eq!(e.kind, DragEventKind::Slip, "{r}");
        let ratio = e.tangential / e.normal;
        eprintln!("  slip at d {}, T/N {ratio}", e.d);
        assert!((ratio - 0.5).abs() < 1e-6, "{ratio}");
        e.d
    };
    for c in [0.0, 0.5] {
        let (coarse, fine) = (first(c, 0.01), first(c, 0.005));
        assert!((coarse - fine).abs() < 1e-5, "c {c}: {coarse} {fine}");
    }
}

/// A whisk drawn back fast after a touchdown (`--whisk -0.3,2 --speed 0.05 --flight`): the tip
/// lands, sticks, and slips at once with a force far outside the cone (the scheme's, as a stick
/// the step does not resolve); the slip's first step is then not solved. That is the named stop
/// `unresolved_stick` with the force of the slip at once, not a solver failure (measured at the
/// program's defaults, dt 0.01: stick at t = 0.93091 at N = 16.6, slip at once at N = 49.5,
/// T/N = 3.04; before, the drag failed with a Newton stall there; dt 0.005 stops by name at
/// t = 0.93018 after a stick at once). At grid 100 (tol 1e-8 or 1e-10) the drag ends on the
/// same stick by the other routes, so the test runs the program's defaults: 11 s in a release
/// build, ignored in the default run (`cargo test --release -p vibrissa --test dynamic_drag --
/// --ignored a_slip_at_once`).
#[test]
#[ignore = "slow: the program's defaults (grid 200, tol 1e-10), 11 s in a release build"]
fn a_slip_at_once_whose_step_fails_is_an_unresolved_stick() {
    let o = DynDragOptions {
        speed: 0.05,
        d_max: 0.1,
        flight: true,
        whisk: Some(Whisk {
            amplitude: -0.3,
            frequency: 2.0,
        }),
        ..DynDragOptions::default()
    };
    let r = paper(&o);
    eprintln!("{r}");
    let kinds: Vec<DragEventKind> = r.events.iter().map(|e| e.kind).collect();
    eprintln!("{kinds:?}");
    assert!(kinds.contains(&DragEventKind::Touchdown), "{kinds:?}");
    let DynDragStop::UnresolvedStick {
        normal, tangential, ..
    } = r.stop
    else {
        panic!("{r}");
    };
    assert!(tangential.abs() > 0.5 * normal, "{normal} {tangential}");
}

/// The paper's rod on a support of compliance `c`, dragged at v 0.1 to d 0.001 (program
/// defaults otherwise).
fn strut_drag(c: f64) -> DynDragResult {
    let rod = Rod::builder().support_compliance(c).build().unwrap();
    let o = DynDragOptions {
        speed: 0.1,
        d_max: 0.001,
        ..DynDragOptions::default()
    };
    let r = drag(&rod, &Surface::flat(0.75).unwrap(), &o).unwrap();
    eprintln!("{r}");
    r
}

/// A support of compliance 10 turns the pressed rod by 0.7 rad at rest (φ(0) = 0.836 against
/// π/2): the rod is nearly a straight strut from its foot to its tip, and its quasi-static force
/// rises from 0.106 to 8.35 by d = 0.0025. Moving the foot by 3.1e-10 in the drag's first step
/// moved the rod's interior up to 2 000 times as much, and Newton's full step did not lower the
/// residual (the product of force and angle in `m'`); the collocation's precision-floor test took
/// that for rounding and stopped with the foot's condition unmet at 3.1e-10 (tol 1e-10), and the
/// drag failed at its first step with a Newton stall. Now the collocation goes on from that
/// iterate with its floor at the boundary tolerance (bvp `Run::floor_missed`) and the steps
/// converge; at the program's defaults (dt 0.01) the drag ends by name where the step cannot
/// follow the strut's force (`unresolved_step`; since the refinements at t = 0.01 after three;
/// docs/model.md, "A very soft support").
#[test]
fn a_strut_on_a_compliant_support_is_stepped() {
    let r = strut_drag(10.0);
    assert!(r.samples.len() > 2, "{r}");
    assert_ends_by_name(&r);
}

/// A whisk turned back while the tip slides (`--whisk 0.2,3 --speed 0.1`): the tip slips at
/// t = 0.042, slows down while the turning foot draws it back, and its velocity reaches zero at
/// t = 0.2946 with N = 0.29. Held there, it would need a pull at once (N = −2.7, T = −3.7, the
/// restart's held force); sliding back it is pushed (N = 0.16, T = −μk N) and accelerates
/// backwards, so it slips back at once (Coulomb's law at that instant, dyndrag.rs
/// `unstick_at_once`) and lifts off at t = 0.301 (measured at the program's defaults: 0.3011,
/// 0.3021, 0.2995 at dt 0.01, 0.005, 0.0025). Before, the drag stopped at the stick as
/// `unresolved_stick` at every dt. Checked here (grid 100, tol 1e-8, dt 0.01): the events, the
/// reversed slip's force (pushing, T = −μk N to 1e-9), the lift-off within 0.01 of 0.301.
#[test]
fn a_tip_the_whisk_draws_back_slips_back_at_once_and_lifts_off() {
    let o = DynDragOptions {
        whisk: Some(Whisk {
            amplitude: 0.2,
            frequency: 3.0,
        }),
        ..light(0.1, 0.01, 0.1)
    };
    let r = paper(&o);
    eprintln!("{r}");
    let kinds: Vec<DragEventKind> = r.events.iter().map(|e| e.kind).collect();
    assert_eq!(
        kinds,
        [
            DragEventKind::Slip,
            DragEventKind::Stick,
            DragEventKind::Slip,
            DragEventKind::LiftOff
        ],
        "{r}"
    );
    let (stick, back, lift) = (r.events[1], r.events[2], r.events[3]);
    assert_eq!(stick.t, back.t);
    assert_eq!(back.state, ContactState::SlidingBack);
    assert!(back.normal > 0.0, "{back:?}");
    assert!(
        (back.tangential + 0.3 * back.normal).abs() < 1e-9,
        "{back:?}"
    );
    assert!((lift.t - 0.301).abs() < 0.01, "{lift:?}");
    assert!(matches!(r.stop, DynDragStop::LiftOff { .. }), "{r}");
}

/// The drag's end is reached without a sliver step: where `d_max` lies less than the shortest
/// step past a step's end, the last step takes the remainder with it. Alone, a step of 4.5e-7
/// (`4/τ²` ≈ 2e13 on the ringing rod's rounding) ran into the collocation's mesh limit: the
/// paper's rod at v 0.05 to d_max 0.045 ended with a solver error at dt 0.00125 (grid 400,
/// tol 1e-11, and grid 200, tol 1e-12) after its slip and stick; now both end at d_max. Here the
/// stuck rod before its first slip, where the step is not yet costly: at dt 0.05 the foot's
/// ramp reaches d = 0.0078125 at t = 1 exactly (20 steps); a d_max 1e-7 in time further is
/// reached in the same 20 steps, the last 0.05 + 1e-7 long (21 before, the last 1e-7).
#[test]
fn the_last_step_takes_a_remainder_shorter_than_the_shortest_step() {
    let o = DynDragOptions {
        speed: 0.05,
        dt: 0.05,
        grid: 20,
        tol: 1e-8,
        ..DynDragOptions::default()
    };
    let d_at = |t: f64| {
        DynDragOptions {
            d_max: 1.0,
            ..o.clone()
        }
        .foot_at(t)
    };
    let on_grid = paper(&DynDragOptions {
        d_max: d_at(1.0),
        ..o.clone()
    });
    let past = paper(&DynDragOptions {
        d_max: d_at(1.0 + 1e-7),
        ..o.clone()
    });
    for r in [&on_grid, &past] {
        assert!(matches!(r.stop, DynDragStop::DMax), "{r}");
        assert!(r.events.is_empty(), "{r}");
        assert_eq!(r.stats.steps, 20, "{r}");
        let shortest = r
            .samples
            .windows(2)
            .map(|w| w[1].t - w[0].t)
            .fold(f64::INFINITY, f64::min);
        assert!(shortest >= 0.05 - 1e-12, "{shortest}");
    }
    let end = past.samples.last().unwrap();
    assert!((end.t - (1.0 + 1e-7)).abs() < 1e-12, "{}", end.t);
}

/// A cycle of events at one instant (a stick, a slip at once, a stick at once, and a fourth
/// that would repeat them) stops as `UnresolvedStick` with the force the stuck tip needed where
/// it slipped at once, beyond μs N, not the state's at the fourth event (the slide's, inside
/// the cone, until 2026-11-30: N = 0.00976, T/N = −0.30 here). The long rat preset at the
/// program's defaults, v 0.01 (the dynamic grid's row at dt 0.01): its stick at d = 0.037607
/// needs N = 0.00783, T/N = −0.69.
#[test]
fn a_cycle_at_one_instant_reports_the_force_beyond_the_cone() {
    let path = format!(
        "{}/../../data/scenes/rat_mystacial_long.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let s: vibrissa::Scene = toml::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let (rod, surface) = s.parts().unwrap();
    let o = DynDragOptions {
        speed: 0.01,
        d_max: 0.04,
        ..DynDragOptions::default()
    };
    let r = drag(&rod, &surface, &o).unwrap();
    eprintln!("{r}");
    let DynDragStop::UnresolvedStick {
        t,
        d,
        normal,
        tangential,
    } = r.stop
    else {
        panic!("{r}")
    };
    assert!((d - 0.037607).abs() < 1e-5, "{r}");
    assert!(normal > 0.0, "{r}");
    assert!(tangential.abs() > o.mu_s * normal, "{normal} {tangential}");
    let at_stop = r.events.iter().filter(|e| e.t == t).count();
    assert_eq!(at_stop, 3, "{r}");
}

/// A rod on a support of compliance 20 is pressed into a nearly straight strut (f0 = 0.054),
/// and the foot's first steps raise its tip force far faster than the quasi-static drag
/// (docs/model.md, "A very soft support"). The slip search's shortest step (1e-5) is not
/// solved there (the collocation's mesh limit), which ended the drag with a solver error until
/// 2026-11-30. A search the collocation cannot finish in a stuck phase is now a step the time
/// step does not resolve (`UnresolvedStep`, with the full step's force), so the drag takes the
/// steps again at dt/2: the tip slips at once (d = 1.3e-9, T/N = μs) and slides at μk to d_max.
#[test]
fn a_strut_on_a_very_soft_support_slips_and_slides() {
    let (r, o) = (strut_drag(20.0), DynDragOptions::default());
    assert_eq!(r.stop, DynDragStop::DMax, "{r}");
    assert_eq!(r.stats.refinements, 1, "{r}");
    let [slip] = &r.events[..] else { panic!("{r}") };
    assert_eq!(slip.kind, DragEventKind::Slip, "{r}");
    assert!(slip.d < 1e-8, "{slip:?}");
    assert!(
        (slip.tangential / slip.normal - o.mu_s).abs() < 1e-6,
        "{slip:?}"
    );
    let end = r.samples.last().unwrap();
    assert!(end.normal > 0.0, "{end:?}");
    assert!(
        (end.tangential / end.normal - o.mu_k).abs() < 1e-9,
        "{end:?}"
    );
}

/// The softest supports (compliance 100 here, 50 in the ignored test below: the paper's rod
/// pressed into a strut straighter still than at 20), v 0.1, dt 0.01. The first step's Newton direction moves the strut's force
/// from N = 0.022 by about 0.1 for a foot moved by 3.1e-10; the residual's line search (Armijo)
/// then took 1 % of a step at a time to its iteration limit or a stall, and the drag ended with
/// a solver error at its first step until 2026-12-01. A step the first damping cannot solve is
/// now solved again with the affine-invariant damping (rothe.rs `StepSolver`), and the slip's
/// search then met trials 2e-9 apart in time solved to T/N = 0.492 and 0.684: its test jumps
/// instead of crossing μs, and where a search ends on a force inside the cone the step does not
/// resolve the rod (dyndrag.rs `inside_cone`). So the drag ends by name in its first step, the
/// force before it the pressed start's (the quasi-static `scan`'s at d = 0, to 1e-8), the force
/// within it inside the cone.
#[test]
fn a_strut_on_the_softest_support_ends_by_name_not_in_a_solver_error() {
    softest_strut_ends_by_name(100.0);
}

/// As [`a_strut_on_the_softest_support_ends_by_name_not_in_a_solver_error`] at compliance 50
/// (65 s in the test profile: the first damping fails on every trial of the slip's search, each
/// after 400–500 Newton iterations on meshes refined up to 6 401 nodes).
#[test]
#[ignore = "65 s in the test profile"]
fn a_strut_on_a_support_of_compliance_50_ends_by_name_not_in_a_solver_error() {
    softest_strut_ends_by_name(50.0);
}

fn softest_strut_ends_by_name(c: f64) {
    let mu_s = DynDragOptions::default().mu_s;
    let r = strut_drag(c);
    let DynDragStop::UnresolvedStep {
        t,
        before,
        normal,
        tangential,
        ..
    } = r.stop
    else {
        panic!("{c}: {r}")
    };
    assert_eq!(t, 0.0, "{c}: {r}");
    assert!(r.events.is_empty(), "{c}: {r}");
    let rod = Rod::builder().support_compliance(c).build().unwrap();
    let q = scan(
        &rod,
        &Surface::flat(0.75).unwrap(),
        &ScanOptions {
            d_max: 1e-9,
            points: 2,
            ..ScanOptions::default()
        },
    )
    .unwrap();
    let p0 = &q.points[0];
    assert!(
        (before[0] - p0.normal).abs() < 1e-8,
        "{c}: {before:?} {p0:?}"
    );
    assert!(before[1].abs() < 1e-8, "{c}: {before:?}");
    assert!(normal > 0.0 && tangential.abs() < mu_s * normal, "{c}: {r}");
}
