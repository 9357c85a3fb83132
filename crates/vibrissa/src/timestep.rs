//! Step-size control of the rod in time (issue 32): the bounds of the controller in one place,
//! the proposal of the next step from a local error estimate, and the estimate itself for
//! Newmark's average-acceleration rule (module `rothe` forms it from a step's accelerations).
//!
//! The estimate (Zienkiewicz and Xie, "A simple error estimator and adaptive time stepping
//! procedure for dynamic analysis", Earthquake Eng. Struct. Dyn. 20, 1991): Newmark's rule with
//! parameter `β` makes a local error in the positions of `(β − 1/6) Δt³ r_ttt + O(Δt⁴)`; the
//! average-acceleration rule has `β = 1/4`, so
//!
//! ```text
//!     e = Δt³/12 · max_i |r_ttt(s_i)|,    r_ttt ≈ (aⁿ⁺¹ − aⁿ⁻¹)/(Δt + h)
//! ```
//!
//! with `h` the last step, `|·|` the Euclidean length of `(x_ttt, y_ttt)` at a node `s_i` of the
//! history grid and the maximum over all its nodes (an absolute error in rod lengths). The
//! difference is taken over two steps, not Zienkiewicz and Xie's one step `(aⁿ⁺¹ − aⁿ)/Δt`:
//! the rule carries a mode in the accelerations that alternates from step to step, which cancels
//! in `aⁿ⁺¹ − aⁿ⁻¹` and enters `aⁿ⁺¹ − aⁿ` doubled (with it the steps shrank from period to period;
//! docs/model.md, "Adaptive time steps"). The first step, and the first after a restart, a stick
//! or a touchdown (which replace the accelerations), take the one-step difference.
//! A step is accepted when `e ≤ time_tol`, else tried again shorter; either way the next step is
//! `Δt · clamp(safety · (time_tol/e)^(1/3), max_shrink, max_growth)`, at most `max_growth` after
//! an accepted step and at most 1 after a rejected one, within `[h_min, h_max]`.
//!
//! The scheme's properties with steps of varying length (docs/model.md, "Adaptive time
//! steps"): the rule is written for any step (`r_tt = 4/Δt² (r − r̂)`, `r̂ = rⁿ + Δt vⁿ + Δt²/4
//! aⁿ`, `vⁿ⁺¹ = vⁿ + Δt/2 (aⁿ + aⁿ⁺¹)`), each step is the trapezoidal rule on `(r, r_t)`, so it
//! stays second order and implicit; for the linear(ized) undamped rod each step conserves the
//! energy exactly whatever its length (the trapezoidal rule conserves quadratic invariants of a
//! linear system step by step), so changing the step adds no numerical damping.

use crate::VibrissaError;
use serde::Serialize;

/// The bounds of the time-step controller of `dynamics::free` and `dynamics::drag` with
/// `time_tol` set (module docs: the estimate and the proposal).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct TimeStepControl {
    /// Safety factor on the proposed step, in `(0, 1]`. Default 0.9.
    pub safety: f64,
    /// Largest growth of the step from one step to the next, in `(1, 10]`. Default 2.
    pub max_growth: f64,
    /// Largest shrink: the next step is at least this share of the last, in `(0, 1)`.
    /// Default 0.2.
    pub max_shrink: f64,
    /// Shortest step, in `[1e-9, h_max]`: a step rejected at this length is an error. Default
    /// 1e-5 (the shortest step the dynamic drag's events make, at its default `dt`).
    pub h_min: f64,
    /// Longest step, in `[h_min, 1]`. Default 0.25 (about a seventh of the uniform clamped–free
    /// rod's first period).
    pub h_max: f64,
}

impl Default for TimeStepControl {
    fn default() -> Self {
        TimeStepControl {
            safety: 0.9,
            max_growth: 2.0,
            max_shrink: 0.2,
            h_min: 1e-5,
            h_max: 0.25,
        }
    }
}

/// The range of `time_tol` (rod lengths): `[1e-14, 1e-1]`.
pub const TIME_TOL_RANGE: (f64, f64) = (1e-14, 1e-1);

impl TimeStepControl {
    /// Checks every bound; the error names it and its valid range.
    pub fn validate(&self) -> Result<(), VibrissaError> {
        let bad = |name: &str, v: f64, r: &str| Err(VibrissaError::range(name, v, r));
        if !(self.safety > 0.0 && self.safety <= 1.0) {
            return bad("step_control.safety", self.safety, "(0, 1]");
        }
        if !(self.max_growth > 1.0 && self.max_growth <= 10.0) {
            return bad("step_control.max_growth", self.max_growth, "(1, 10]");
        }
        if !(self.max_shrink > 0.0 && self.max_shrink < 1.0) {
            return bad("step_control.max_shrink", self.max_shrink, "(0, 1)");
        }
        if !(self.h_max >= 1e-9 && self.h_max <= 1.0) {
            return bad("step_control.h_max", self.h_max, "[1e-9, 1]");
        }
        if !(self.h_min >= 1e-9 && self.h_min <= self.h_max) {
            return bad("step_control.h_min", self.h_min, "[1e-9, h_max]");
        }
        Ok(())
    }

    /// The next step after a step of length `h` whose estimate was `err` against the tolerance
    /// `tol` (`err ≤ tol`: accepted): `h·clamp(safety·(tol/err)^(1/3), max_shrink, growth)`
    /// with `growth = max_growth` after an accepted step and 1 after a rejected one, within
    /// `[h_min, h_max]`.
    pub fn next(&self, h: f64, err: f64, tol: f64) -> f64 {
        let up = if err <= tol { self.max_growth } else { 1.0 };
        let f = if err > 0.0 {
            self.safety * (tol / err).cbrt()
        } else {
            up
        };
        (h * f.clamp(self.max_shrink, up)).clamp(self.h_min, self.h_max)
    }

    /// The first step to try from the given `dt`, within `[h_min, h_max]`.
    pub(crate) fn first(&self, dt: f64) -> f64 {
        dt.clamp(self.h_min, self.h_max)
    }

    /// The verdict on a step of length `tau` tried from `t` whose estimate was `err` against
    /// `tol`: whether it is rejected, and the next step to try ([`TimeStepControl::next`]); a
    /// step rejected at `h_min` is an error (the drag and the free rod share this).
    pub(crate) fn judge(
        &self,
        t: f64,
        tau: f64,
        err: f64,
        tol: f64,
    ) -> Result<(bool, f64), VibrissaError> {
        let rejected = err > tol;
        if rejected && tau <= self.h_min {
            return Err(too_short(t, tau, err, tol));
        }
        Ok((rejected, self.next(tau, err, tol)))
    }
}

/// Checks `time_tol` (`None`: fixed steps) and, with it, the controller's bounds.
pub(crate) fn check_time_tol(
    time_tol: Option<f64>,
    control: &TimeStepControl,
) -> Result<(), VibrissaError> {
    if let Some(t) = time_tol {
        let (lo, hi) = TIME_TOL_RANGE;
        if !(t >= lo && t <= hi) {
            return Err(VibrissaError::range(
                "time_tol",
                t,
                format!("[{lo:e}, {hi:e}]"),
            ));
        }
        control.validate()?;
    }
    Ok(())
}

/// The error of a step rejected at the shortest step.
fn too_short(t: f64, h: f64, err: f64, tol: f64) -> VibrissaError {
    VibrissaError::NoConvergence {
        what: format!("the adaptive time step from t = {t}"),
        reason: format!(
            "the local error estimate {err:e} exceeds time_tol {tol:e} at the shortest step \
             h_min = {h:e}"
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The proposal: an estimate at the tolerance keeps the step times the safety factor, one
    /// 8× below it doubles it (the cube root), one far above it shrinks by `max_shrink`, and
    /// the bounds hold.
    #[test]
    fn next_step_follows_the_cube_root_of_the_ratio() {
        let c = TimeStepControl::default();
        assert!((c.next(0.01, 1e-8, 1e-8) - 0.009).abs() < 1e-15);
        assert!((c.next(0.01, 1e-8 / 8.0, 1e-8) - 0.018).abs() < 1e-15);
        assert!((c.next(0.01, 1e-3, 1e-8) - 0.002).abs() < 1e-15);
        assert_eq!(c.next(0.01, 0.0, 1e-8), 0.02);
        assert_eq!(c.next(0.2, 0.0, 1e-8), 0.25);
        assert_eq!(c.next(2e-5, 1.0, 1e-8), 1e-5);
        // rejected: never longer than the step tried
        assert!(c.next(0.01, 1.01e-8, 1e-8) < 0.01);
    }

    /// Bounds out of range are refused; `time_tol` too.
    #[test]
    fn bounds_are_checked() {
        let c = TimeStepControl::default();
        assert!(c.validate().is_ok());
        for bad in [
            TimeStepControl { safety: 0.0, ..c },
            TimeStepControl {
                max_growth: 1.0,
                ..c
            },
            TimeStepControl {
                max_shrink: 1.0,
                ..c
            },
            TimeStepControl { h_min: 0.5, ..c },
            TimeStepControl { h_max: 2.0, ..c },
        ] {
            assert!(matches!(
                bad.validate(),
                Err(VibrissaError::OutOfRange { .. })
            ));
        }
        assert!(check_time_tol(None, &TimeStepControl { safety: 0.0, ..c }).is_ok());
        assert!(check_time_tol(Some(0.0), &c).is_err());
        assert!(check_time_tol(Some(1.0), &c).is_err());
        assert!(check_time_tol(Some(1e-8), &c).is_ok());
    }
}
