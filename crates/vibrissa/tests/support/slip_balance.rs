//! Each slip's energy balance asserted (tests/drag.rs, drag_turn.rs, round_tip.rs).

use vibrissa::drag::SlipEvent;

/// Asserts that slip `k` of the scene `name` (a drag with `energy_balance`) balances its stick
/// phase and its slip to `bound` ([`SlipEvent::imbalance`]); returns the larger imbalance.
pub fn assert_balanced(name: &str, k: usize, e: &SlipEvent, bound: f64) -> f64 {
    let (stick, slip) = e.imbalance().unwrap();
    assert!(
        stick.abs() < bound,
        "{name}, stick {k}: imbalance {stick} ({e:?})"
    );
    assert!(
        slip.abs() < bound,
        "{name}, slip {k}: imbalance {slip} ({e:?})"
    );
    stick.abs().max(slip.abs())
}
