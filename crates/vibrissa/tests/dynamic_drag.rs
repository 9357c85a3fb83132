//! The dynamic drag (issue 32, `vibrissa::dynamics::drag`) against the quasi-static drag of the
//! same rod: its start, the first slip's place as the foot slows down, the stuck tip's forces,
//! and the energy balance of a slip. The paper's rod throughout (uniform, clamped, η = 0.75,
//! μs = 0.5, μk = 0.3). The slow-limit study behind the bounds: examples/dynamic_drag.rs.

use vibrissa::dynamics::{drag, ContactState, DynDragOptions, DynDragResult, DynDragStop};
use vibrissa::{scan, Rod, ScanOptions, Surface, VibrissaError};

fn paper(o: &DynDragOptions) -> DynDragResult {
    drag(&Rod::uniform(), &Surface::flat(0.75).unwrap(), o).unwrap()
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

/// Options out of range, and a surface that is not flat, are refused.
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
    let tilted = Surface::new(0.75, 0.1).unwrap();
    let e = drag(&Rod::uniform(), &tilted, &DynDragOptions::default()).unwrap_err();
    assert!(e.is_input(), "{e}");
}
