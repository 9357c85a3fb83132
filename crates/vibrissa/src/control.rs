//! Step control of the marches: the natural steps in the family parameter `λ`, the
//! pseudo-arclength steps of the fold passage, and the corrector's tolerance. One place for every
//! constant the driver loop uses, each with why it has its value.

use crate::config::NEWTON_TOL_MAX;

/// Natural-continuation step control of a march in `λ` (module `march`).
///
/// The step `h` starts at `h_init` (never above `h_max` nor the span to the end), grows after a
/// correction that converged in few iterations and shrinks after one that needed many; a failed
/// correction is retried `reject`-times shorter until `h` would fall below
/// `h_min_rel·(1 + |λ_end|)`, where the fold passage (pseudo-arclength) takes over.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct StepControl {
    /// First step. Default 0.01 (a hundredth of a rod length in `d`).
    pub h_init: f64,
    /// Largest step: the stepper's (0.01 on the rod's own shooter, whose quintic predictor is
    /// exact enough there for one chord iteration; 0.05 on a generic method, whose every
    /// correction is a whole BVP solve).
    pub h_max: f64,
    /// Smallest step relative to `1 + |λ_end|`. Default 1e-7: below it a natural step near a fold
    /// would crawl; the fold passage takes over.
    pub h_min_rel: f64,
    /// Corrections within this many iterations double the step. Default 2.
    pub fast_iters: usize,
    /// Corrections within this many (and more than `fast_iters`) grow it by `grow_slow`.
    /// Default 4; slower ones halve it.
    pub slow_iters: usize,
    /// Growth after a fast correction. Default 2.
    pub grow_fast: f64,
    /// Growth after a slower one. Default 1.25.
    pub grow_slow: f64,
    /// Shrink after a correction over `slow_iters`. Default 0.5.
    pub shrink: f64,
    /// Shrink after a failed correction (and after an event that could not be located in a long
    /// step). Default 0.25.
    pub reject: f64,
    /// The first step predicts a change of at most this share of the state's size (`1 +` its
    /// largest component). Default 0.25: a start next to a bifurcation has a steep branch, and
    /// Newton from a longer linear prediction lands on whichever branch is nearest.
    pub first_change: f64,
    /// A target closer to the end than this share of `h` is the end. Default 1e-3.
    pub snap_end: f64,
    /// An event predicted inside the step is stepped to just past it, by this share of the rest
    /// of the step. Default 1e-6.
    pub past_event: f64,
    /// Steps per output point, plus `extra_steps`, before the march gives up. Default 10.
    pub steps_per_point: usize,
    /// Default 100 000.
    pub extra_steps: usize,
    /// Steps without progress in `λ` before the march gives up. Default 50.
    pub max_stalled: usize,
}

impl Default for StepControl {
    fn default() -> Self {
        StepControl {
            h_init: 0.01,
            h_max: OWN_H_MAX,
            h_min_rel: 1e-7,
            fast_iters: 2,
            slow_iters: 4,
            grow_fast: 2.0,
            grow_slow: 1.25,
            shrink: 0.5,
            reject: 0.25,
            first_change: 0.25,
            snap_end: 1e-3,
            past_event: 1e-6,
            steps_per_point: 10,
            extra_steps: 100_000,
            max_stalled: 50,
        }
    }
}

/// Largest natural step on the rod's own shooter.
pub(crate) const OWN_H_MAX: f64 = 0.01;
/// Largest natural step on a generic method of crate `bvp`.
pub(crate) const GENERIC_H_MAX: f64 = 0.05;

impl StepControl {
    /// The step after a correction that took `iters` iterations.
    pub fn after(&self, h: f64, iters: usize, h_max: f64) -> f64 {
        if iters <= self.fast_iters {
            (self.grow_fast * h).min(h_max)
        } else if iters <= self.slow_iters {
            (self.grow_slow * h).min(h_max)
        } else {
            self.shrink * h
        }
    }
    /// The smallest natural step of a march that ends at `lam_end`.
    pub fn h_min(&self, lam_end: f64) -> f64 {
        self.h_min_rel * (1.0 + lam_end.abs())
    }
    /// Most steps of a march with `points` output points.
    pub fn max_steps(&self, points: usize) -> usize {
        self.steps_per_point * points + self.extra_steps
    }
}

/// Step settings of the fold passage (pseudo-arclength in `(u, λ)`, module `fold`): the first
/// arclength step, its bounds, and how many steps it may take before the passage gives up.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct FoldSteps {
    /// First step. 1e-3: the passage starts where natural steps of 1e-7 failed.
    pub ds: f64,
    /// Smallest step: 1e-10 (a step this short that still fails has no resolvable branch).
    pub ds_min: f64,
    /// Largest step: 0.05.
    pub ds_max: f64,
    /// Steps before it gives up: 5000.
    pub max_steps: usize,
}

/// The fold passage's steps, for every stepper.
pub(crate) const FOLD_STEPS: FoldSteps = FoldSteps {
    ds: 1e-3,
    ds_min: 1e-10,
    ds_max: 0.05,
    max_steps: 5000,
};

/// Newton iterations per natural step before it is given up (the own shooter's chord corrector).
pub(crate) const MAX_ITER: usize = 12;

/// The smallest Newton tolerance: a few units of rounding on residuals of order one.
const NEWTON_TOL_MIN: f64 = 1e-15;

/// The Newton tolerance of the marches' corrector for the integration tolerance `tol`.
///
/// The chord iteration converges linearly: stopping it at a hundredth of `tol` keeps Newton's
/// share of the error below the discretization's and the contact conditions (a point on the
/// surface, a side tangent to it) to ~1e-12 at the default tolerance, so that no row has the
/// rod beyond the surface by more than that. And never above 1e-9: the predictor extrapolates
/// the last points and the branch checks compare corrections with the change over a step, so a
/// point left with a residual of 1e-4 is noise that shrinking steps amplify (the paper scan at
/// tol 1e-3 stopped at d = 0.16 with steps of 1e-7 and "corrections" of 4).
/// And never below 1e-15: residuals of order one carry rounding of ~1e-16, which no iteration
/// removes (the press's first point at tol 5e-15 stalled at 1.1e-16 against 5e-17).
pub(crate) fn corrector_tol(tol: f64) -> f64 {
    (0.01 * tol).clamp(NEWTON_TOL_MIN, NEWTON_TOL_MAX)
}
