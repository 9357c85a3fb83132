//! The one march: a contact chain followed in its family parameter `λ` (the foot displacement
//! `d` of the scan, the press depth of the start, the foot angle of a whisk), for every rod,
//! every method and every contact set.
//!
//! Natural continuation from output point to output point (intermediate steps where the grid is
//! coarse), each point predicted from the last ones and corrected by a [`Stepper`]; where a
//! natural step fails for tiny steps (near a fold in `λ`) the stepper's pseudo-arclength
//! continuation passes it or locates the fold. After every step the events between the last
//! point and the new one are located on solves inside that step (no restart): a contact lifts,
//! slips, a free part of the rod touches the surface, the tip turns tangent to it, a lying part
//! peels back, an object slips off the tip. The earliest is written as a point with its
//! [`Event`]. An event that ends the contact state but not the scene changes the contact set and
//! the march goes on in the same step sequence (touchdown, peel-back, release); the others end
//! it. The first maximum of `|μ|` (the end of the measurable range) is located on the way, by
//! the root of `d|μ|/dλ` from exact tangents.

use crate::chain::{Contact, ContactSet, Geom, Mode};
use crate::profile::{General, Profile};
use crate::report::{ContactLabel, Event, RangeEnd, ScanPoint, StopReason};
use crate::sampling::flex_and_reversals;
use crate::search;
use crate::shape::{shape_from, ShapePoint};
use crate::surface::Meter;
use crate::watch::{Crossing, Env, Watch, SIDE_FRICTION_LIMIT};
use bvp::{Solution, Stats};

/// A converged point of the branch.
#[derive(Clone, Debug)]
pub(crate) struct Pt {
    /// Family parameter.
    pub lam: f64,
    /// The unknowns of the contact set.
    pub u: Vec<f64>,
    /// Exact tangent `du/dλ`, where the stepper has one.
    pub du: Option<Vec<f64>>,
    /// `det ∂R/∂u` (its sign changes at a fold in `λ`), where the stepper has it.
    pub det: Option<f64>,
    /// Newton iterations it took.
    pub iters: usize,
    /// The whole rod (`params = [f, α]` of the total contact force).
    pub sol: Solution,
    /// What the march watches there.
    pub w: Watch,
    /// The method's own solution, when it is not the rod's own shooter (the generic methods'
    /// stacked segments; their guesses come from it).
    pub raw: Option<Solution>,
}

/// Result of the pseudo-arclength fallback.
pub(crate) enum Passed {
    /// The branch continues beyond the failed step: its points from there on, in increasing
    /// `λ`, the last one beyond the target (never empty).
    Beyond(Vec<Pt>),
    /// `λ` has a maximum along the branch here (with the rod there, if it was found).
    Fold(f64, Option<Box<Pt>>),
    /// Neither.
    Failed(String),
}

/// Why a correction was refused.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum StepError {
    /// The corrector landed across a fold in `λ` (`det J` changed sign, and the tangent agrees):
    /// pass or locate it by pseudo-arclength rather than by shorter natural steps.
    CrossedFold,
    /// Anything else (a shorter step may succeed).
    Failed(String),
}

impl std::fmt::Display for StepError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            StepError::CrossedFold => f.write_str("the corrector crossed a fold"),
            StepError::Failed(m) => f.write_str(m),
        }
    }
}

impl From<String> for StepError {
    fn from(m: String) -> Self {
        StepError::Failed(m)
    }
}

impl From<StepError> for String {
    fn from(e: StepError) -> Self {
        e.to_string()
    }
}

/// Prediction and correction of branch points (the method-specific part of a march).
pub(crate) trait Stepper {
    /// The current contact set.
    fn set(&self) -> &ContactSet;
    /// The point at `λ` from the history `hist` (newest last; `λ` ahead of it or inside its
    /// span); rejects corrections that land on another branch. With `fresh` the tangent is exact
    /// at the point (events that use it).
    fn correct(&mut self, lam: f64, hist: &[Pt], fresh: bool) -> Result<Pt, StepError>;
    /// Pseudo-arclength continuation from the newest point until the branch passes `target` or
    /// turns back in `λ`.
    fn pass_fold(&mut self, hist: &[Pt], target: f64, lam_end: f64) -> Passed;
    /// Changes the contact set at `λ` and corrects `u` (the old state in the new unknowns) there.
    fn switch(&mut self, set: ContactSet, lam: f64, u: Vec<f64>) -> Result<Pt, StepError>;
    /// The exact tangent of the contact set `set` at `(u, λ)` on the rod's own shooter, before
    /// the stepper is switched to it.
    fn tangent_in(&mut self, set: &ContactSet, lam: f64, u: &[f64]) -> Option<Vec<f64>>;
    /// Whether the equilibrium of the current set at `(u, λ)` is singular to working precision
    /// (on the rod's own shooter).
    fn singular_at(&mut self, lam: f64, u: &[f64]) -> bool;
    /// Work done so far.
    fn stats(&self) -> Stats;
    /// Largest natural step in `λ`.
    fn h_max(&self) -> f64;
    /// The foot's x in the lab frame at `λ` (for along-surface anchors).
    fn foot_x(&self, lam: f64) -> f64;
    /// The branch between the points of `hist` as a polynomial in `λ` (from their exact
    /// tangents): `(u, du/dλ)` at `λ`.
    fn interpolant(&self, hist: &[Pt], lam: f64) -> Option<(Vec<f64>, Vec<f64>)> {
        hist.iter()
            .all(|p| p.du.is_some())
            .then(|| interpolate(hist, lam))
    }
}

/// What a march needs besides the stepper.
pub(crate) struct Spec<'a> {
    pub env: &'a Env,
    /// Output values of `λ` (sorted).
    pub grid: &'a [f64],
    /// Where the march ends.
    pub lam_end: f64,
    /// Keep each output point's shape sampled at this many points.
    pub keep_shapes: Option<usize>,
    /// The rod's profile (flex points, shapes).
    pub general: &'a General,
    /// New contacts hold by friction (stuck, rolling) rather than slide freely (the press).
    pub friction: bool,
    /// Whether the first point must be a valid contact state (else it is reported as the event
    /// it is); a press starts at first touch, where the contact force is zero.
    pub check_start: bool,
    /// A stuck contact that reaches `|T| = μ0 N` slides on (`T = ±μ0 N`) instead of ending the
    /// march (a whisk against an object).
    pub slide: bool,
}

/// What a march produced.
pub(crate) struct MarchOut {
    pub points: Vec<ScanPoint>,
    pub shapes: Vec<Vec<ShapePoint>>,
    /// `(|μ|, μ, λ)` at the end of the measurable range, and what ended it.
    pub best: (f64, f64, f64),
    pub range_end: RangeEnd,
    pub stop: StopReason,
    /// The last point and its contact set.
    pub last: Option<(ContactSet, Pt)>,
    pub stats: Stats,
    /// The tip state `z(1)` (foot frame) of each output point.
    pub tips: Vec<[f64; 4]>,
    /// The work integrated along the march (`env.ground.meter`; 0 without one).
    pub metered: f64,
}

/// The first maximum of `|μ|` and what ended the range, once known.
struct RangeTracker {
    best: (f64, f64, f64),
    end: Option<RangeEnd>,
}

impl RangeTracker {
    fn see(&mut self, w: &Watch) {
        if self.end.is_none() && w.mu.abs() >= self.best.0 {
            self.best = (w.mu.abs(), w.mu, w.lam);
        }
    }
    fn close(&mut self, end: RangeEnd) {
        if self.end.is_none() {
            self.end = Some(end);
        }
    }
}

/// Runs the march from the point `p0` (λ = `p0.lam`) over the grid.
pub(crate) fn march<P: Profile>(
    stepper: &mut dyn Stepper,
    spec: &Spec<'_>,
    profile: &P,
    p0: Pt,
    mut stats: Stats,
) -> MarchOut {
    let mut out = Output {
        points: Vec::with_capacity(spec.grid.len() + 1),
        shapes: Vec::new(),
        gi: spec.grid.partition_point(|&g| g < p0.lam),
        tips: Vec::with_capacity(spec.grid.len() + 1),
        metered: 0.0,
    };
    let mut range = RangeTracker {
        best: (p0.w.mu.abs(), p0.w.mu, p0.lam),
        end: None,
    };
    let start_event = if spec.check_start {
        start_event(spec.env, stepper.set(), &p0.w)
    } else {
        None
    };
    let mut last = None;
    // a start that traps the rod between contacts whose equilibrium is singular to working
    // precision: the tangential pair between them has no determined value (the corrections
    // return any of a line of states, |T|/N of 1e3 on a frictionless press)
    let indeterminate = start_event.is_none()
        && spec.check_start
        && crate::watch::traps(stepper.set())
        && stepper.singular_at(p0.lam, &p0.u);
    let stop = if let Some(ev) = start_event {
        // the start itself is not a valid state (the rod crosses the surface, is pulled, or
        // slips): it is reported as the event, never as a grid row
        range.close(RangeEnd::Event);
        out.push(spec, profile, stepper.set(), &p0, Some(ev));
        let s = stop_reason(ev, &p0.w, stepper.set());
        last = Some((stepper.set().clone(), p0));
        s
    } else {
        let set = stepper.set().clone();
        let mut run = Run {
            stepper,
            spec,
            profile,
            out: &mut out,
            range: &mut range,
        };
        if indeterminate {
            let at: Vec<String> = (0..set.contacts.len())
                .map(|j| format!("{:.6}", set.s_of(j, &p0.u)))
                .collect();
            // the start itself is a state (frictionless, T = 0): its grid row
            let emitted = run.emit(std::slice::from_ref(&p0), p0.lam);
            run.range.close(RangeEnd::Event);
            let d = p0.lam;
            let message = format!(
                "the start {} traps the rod between contacts at s = {} that hold without slip, \
                 and its equilibrium is singular to working precision: the pair of tangential \
                 forces between them is indeterminate; the point-contact model does not resolve \
                 it",
                set.label(),
                at.join(" and ")
            );
            last = Some((set, p0));
            emitted
                .err()
                .unwrap_or(StopReason::ContactChange { d, message })
        } else {
            let (s, l) = run.run(p0);
            last = l.or(last);
            s
        }
    };
    stats.accumulate(&stepper.stats());
    if let Some((_, p)) = &last {
        stats.residual = p.sol.stats.residual;
        stats.nodes = p.sol.mesh.len();
    }
    MarchOut {
        points: out.points,
        shapes: out.shapes,
        best: range.best,
        range_end: range.end.unwrap_or(RangeEnd::SolverFailure),
        stop,
        last,
        stats,
        tips: out.tips,
        metered: out.metered,
    }
}

/// An event already true at the start.
fn start_event(env: &Env, set: &ContactSet, w: &Watch) -> Option<Event> {
    if set.contacts.is_empty() {
        return None;
    }
    if w.clear > 0.0 || w.tip_approach < 0.0 || (!env.compound && set.label() != "tip") {
        // a start that crosses the surface, or (the paper's tip-only model) touches it with
        // its side
        return Some(Event::Penetration);
    }
    if w.contacts.iter().any(|c| c.normal <= 0.0) {
        return Some(Event::LiftOff);
    }
    if let Some(m) = env.mu0 {
        if w.contacts
            .iter()
            .any(|c| c.tangential.abs() >= m * c.normal)
        {
            return Some(Event::Slip);
        }
    }
    None
}

fn stop_reason(ev: Event, w: &Watch, set: &ContactSet) -> StopReason {
    let d = w.lam;
    match ev {
        Event::Slip => StopReason::Slip { d, mu: w.mu },
        Event::LiftOff => StopReason::LiftOff { d, limit: None },
        // a side touching at the start (tip-only model), the tip turning into the surface, or
        // the free rod reaching it
        Event::Penetration => {
            let (s, y) = if let Some(j) = set.contacts.iter().position(|c| !c.tip) {
                (w.contacts[j].s, w.last_y)
            } else if w.tip_approach < 0.0 || w.tip_approach.abs() < w.clear.abs() {
                (1.0, w.last_y)
            } else {
                (w.clear_s, w.clear_z[1])
            };
            StopReason::Penetration { d, s, y }
        }
        Event::FoldInD => StopReason::FoldInD { d },
        Event::SlipOff => StopReason::SlipOff { d },
        Event::Touchdown | Event::PeelBack | Event::Release => StopReason::ContactChange {
            d,
            message: format!("{} in state {}", ev.name(), set.label()),
        },
    }
}

struct Run<'a, 'b, P: Profile> {
    stepper: &'a mut dyn Stepper,
    spec: &'a Spec<'b>,
    profile: &'a P,
    out: &'a mut Output,
    range: &'a mut RangeTracker,
}

/// A located event inside a step.
struct Found {
    cross: Crossing,
    pt: Pt,
}

impl<P: Profile> Run<'_, '_, P> {
    /// The march proper; returns why it stopped and the last point.
    fn run(&mut self, p0: Pt) -> (StopReason, Option<(ContactSet, Pt)>) {
        let spec = self.spec;
        let lam_end = spec.lam_end;
        let h_max = self.stepper.h_max().min(lam_end - p0.lam).max(1e-12);
        let mut h: f64 = 0.01_f64.min(h_max);
        let h_min = 1e-7 * (1.0 + lam_end.abs());
        let mut steps = 0usize;
        let max_steps = 10 * spec.grid.len() + 100_000;
        let mut stalled = 0usize;
        let lam0 = p0.lam;
        let mut hist: Vec<Pt> = vec![p0];
        // event functions that are zero at the last change of the contact set, until they
        // leave zero (on the side where the new state holds)
        let mut pending: Vec<Crossing> = Crossing::all(spec.env, self.stepper.set())
            .into_iter()
            .filter(|c| !holds(c.of_watch(spec.env, &hist[0].w)))
            .collect();
        let mut pprev: Option<Watch> = None;
        // points of a pseudo-arclength path still to be taken as steps
        let mut queue: std::collections::VecDeque<Pt> = std::collections::VecDeque::new();
        loop {
            let prev = hist[hist.len() - 1].clone();
            let lam = prev.lam;
            let last_of =
                |hist: &[Pt], set: &ContactSet| Some((set.clone(), hist[hist.len() - 1].clone()));
            if lam >= lam_end {
                self.range.close(RangeEnd::DMax);
                if let Err(fail) = self.emit(&hist, lam_end) {
                    return (fail, last_of(&hist, self.stepper.set()));
                }
                return (StopReason::DMax, last_of(&hist, self.stepper.set()));
            }
            steps += 1;
            if steps > max_steps {
                self.range.close(RangeEnd::SolverFailure);
                return (
                    StopReason::SolverFailure {
                        d: lam,
                        message: format!(
                            "the march needed more than {max_steps} steps (10 per output point and \
                             100000 more)"
                        ),
                    },
                    last_of(&hist, self.stepper.set()),
                );
            }
            let armed: Vec<Crossing> = Crossing::all(spec.env, self.stepper.set())
                .into_iter()
                .filter(|c| !pending.contains(c))
                .collect();
            let queued = queue.pop_front();
            let from_queue = queued.is_some();
            let p = if let Some(q) = queued {
                q
            } else {
                // the first step from the start predicts a change of at most a quarter of the
                // state's size (1 + its largest component): a start near a bifurcation has a
                // steep branch, and Newton from a longer linear prediction lands on whichever
                // branch is nearest (a higher Euler mode)
                if let (true, Some(du)) = (hist.len() == 1 && lam == lam0, &prev.du) {
                    let rate = du.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                    let size = 1.0 + prev.u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                    if rate * h > 0.25 * size {
                        h = (0.25 * size / rate).max(h_min);
                    }
                }
                // next target: at most h ahead, never past the next grid point
                let mut target = (lam + h).min(lam_end);
                if let Some(&g) = spec.grid.get(self.out.gi) {
                    if g > lam && g < target {
                        target = g;
                    }
                }
                if lam_end - target < 1e-3 * h {
                    target = lam_end;
                }
                // an event the predictor sees coming within the step: step to just past it (the
                // event is then located on a short step, and the march pays no full step beyond
                // it)
                for &c in &armed {
                    if let Some(ds) = self.predicted_crossing(&hist, lam, target, c) {
                        // (not when it is as good as here: the step would not move)
                        if ds - lam > h_min {
                            target = ds + 1e-6 * (target - ds);
                        }
                    }
                }
                let corrected = self.stepper.correct(target, &hist, false);
                // a failed step where the only contact lets go ends the branch (see
                // vanishing_normal)
                let vanish = match &corrected {
                    Err(StepError::Failed(_)) => vanishing_normal(&hist),
                    _ => None,
                };
                match (corrected, vanish) {
                    (Ok(p), _) => {
                        h = if p.iters <= 2 {
                            (2.0 * h).min(h_max)
                        } else if p.iters <= 4 {
                            (1.25 * h).min(h_max)
                        } else {
                            0.5 * h
                        };
                        p
                    }
                    (Err(StepError::Failed(_)), _) if h > h_min => {
                        h *= 0.25;
                        continue;
                    }
                    (Err(StepError::Failed(_)), Some((ls, limit, w))) => {
                        // the branch ends where a contact lets go: a lift-off, located by
                        // extrapolation (no state beyond it brackets the root, and a
                        // pseudo-arclength crawl towards it costs without end)
                        self.range.see(&w);
                        self.range.close(RangeEnd::Event);
                        return (
                            StopReason::LiftOff {
                                d: ls,
                                limit: Some(limit),
                            },
                            last_of(&hist, self.stepper.set()),
                        );
                    }
                    (Err(e), _) => match self.stepper.pass_fold(&hist, target, lam_end) {
                        Passed::Beyond(ps) => {
                            // every point of the path, each taken as a step: a branch too steep
                            // for natural steps (near a bifurcation) is not a polynomial in λ
                            // between far points, and events inside it are found on it
                            let mut ps = ps.into_iter();
                            let Some(first) = ps.next() else {
                                self.range.close(RangeEnd::SolverFailure);
                                let message = format!(
                                    "natural step to {target}: {e}; pseudo-arclength passed it \
                                     without a point"
                                );
                                let d = lam;
                                let stop = StopReason::SolverFailure { d, message };
                                return (stop, last_of(&hist, self.stepper.set()));
                            };
                            queue.extend(ps);
                            first
                        }
                        Passed::Fold(lf, pt) => {
                            // the fold's own point belongs to the measurable range it ends
                            if let Some(p) = &pt {
                                self.range.see(&p.w);
                            }
                            self.range.close(RangeEnd::Event);
                            if let Err(fail) = self.emit(&hist, lf.min(lam_end)) {
                                return (fail, last_of(&hist, self.stepper.set()));
                            }
                            if let Some(p) = pt {
                                self.out.push(
                                    spec,
                                    self.profile,
                                    self.stepper.set(),
                                    &p,
                                    Some(Event::FoldInD),
                                );
                                let set = self.stepper.set().clone();
                                return (StopReason::FoldInD { d: lf }, Some((set, *p)));
                            }
                            return (
                                StopReason::FoldInD { d: lf },
                                last_of(&hist, self.stepper.set()),
                            );
                        }
                        Passed::Failed(msg) => {
                            self.range.close(RangeEnd::SolverFailure);
                            return (
                                StopReason::SolverFailure {
                                    d: lam,
                                    message: format!("natural step to {target}: {e}; {msg}"),
                                },
                                last_of(&hist, self.stepper.set()),
                            );
                        }
                    },
                }
            };
            // a change of contact set holds only if its new event functions leave zero inwards
            let mut wrong = None;
            pending.retain(|&c| {
                let v = c.of_watch(spec.env, &p.w);
                if v > 0.0 {
                    wrong.get_or_insert((c, v));
                }
                !holds(v)
            });
            if let Some((c, v)) = wrong {
                self.range.close(RangeEnd::Event);
                let set = self.stepper.set().clone();
                return (
                    StopReason::ContactChange {
                        d: lam,
                        message: format!(
                            "the contact state {} does not hold beyond d = {lam}: {} = {v:.3e} after the change, and the state before it ended there: the model has no contact state that continues",
                            set.label(),
                            c.describe()
                        ),
                    },
                    last_of(&hist, &set),
                );
            }
            if !from_queue && p.lam - lam <= 1e-12 * (1.0 + lam.abs()) {
                stalled += 1;
                if stalled > 50 {
                    self.range.close(RangeEnd::SolverFailure);
                    return (
                        StopReason::SolverFailure {
                            d: lam,
                            message: "the march stalled: 50 steps without progress".into(),
                        },
                        last_of(&hist, self.stepper.set()),
                    );
                }
            } else {
                stalled = 0;
            }
            // a point a rounding away from the newest (a step that ended a rounding short of a
            // grid value, then the grid value) replaces it: the interpolant through two such
            // points is degenerate
            if hist
                .last()
                .is_some_and(|q| (p.lam - q.lam).abs() <= 1e-13 * (1.0 + q.lam.abs()))
            {
                hist.pop();
            }
            hist.push(p.clone());
            if hist.len() > 4 {
                hist.remove(0);
            }
            // events between λ and the new point, the earliest first
            let mut found: Option<Found> = None;
            let mut failure: Option<StopReason> = None;
            for &c in &armed {
                if !ended(c.of_watch(spec.env, &p.w)) {
                    continue;
                }
                match self.locate(&hist, lam, p.lam, c) {
                    Ok(pe) => {
                        let v = c.of_watch(spec.env, &pe.w);
                        if c == Crossing::Touchdown && spec.env.ground.curve.is_some() && v < -JUMP
                        {
                            // not a root but a jump of the highest free point (one the clearance
                            // did not see before): no contact to insert there
                            failure.get_or_insert(StopReason::SolverFailure {
                                d: lam,
                                message: format!(
                                    "{} jumps from {v:.3e} to {:.3e} at d = {}",
                                    c.describe(),
                                    c.of_watch(spec.env, &p.w),
                                    pe.lam
                                ),
                            });
                            continue;
                        }
                        if found.as_ref().is_none_or(|f| pe.lam < f.pt.lam) {
                            found = Some(Found { cross: c, pt: pe });
                        }
                    }
                    Err(msg) => {
                        failure.get_or_insert(StopReason::SolverFailure {
                            d: lam,
                            message: format!("locating the {c:?} event: {msg}"),
                        });
                    }
                }
            }
            if found.is_none() {
                if let Some(f) = failure {
                    // a step too long for the event's scale (a light touch changes fast): the
                    // step again, shorter, before giving up
                    if p.lam - lam > h_min {
                        hist.pop();
                        queue.clear();
                        h = 0.25 * (p.lam - lam);
                        continue;
                    }
                    self.range.close(RangeEnd::SolverFailure);
                    return (f, last_of(&hist, self.stepper.set()));
                }
            }
            let l_stop = found.as_ref().map_or(p.lam, |f| f.pt.lam);
            if let Some(m) = spec.env.ground.meter {
                let end = found.as_ref().map_or(&p, |f| &f.pt).clone();
                self.out.metered += self.meter_between(m, &hist, &prev, &end, 0);
            }
            // the first maximum of |μ| between the last point and l_stop
            if self.range.end.is_none() {
                if let Some(m) = self.first_max(&hist, &prev.w, pprev.as_ref(), &p.w, l_stop) {
                    self.range.see(&m);
                    self.range.close(RangeEnd::FirstMaximum);
                }
            }
            match &found {
                Some(f) => self.range.see(&f.pt.w),
                None => self.range.see(&p.w),
            }
            if let Err(fail) = self.emit(&hist, l_stop) {
                return (fail, last_of(&hist, self.stepper.set()));
            }
            let Some(Found { cross, pt: mut pe }) = found else {
                pprev = Some(prev.w.clone());
                continue;
            };
            // an event: a change of contact set, or the end
            let set = self.stepper.set().clone();
            match self.transition(&set, cross, &pe) {
                Next::Done => {
                    self.range.close(RangeEnd::DMax);
                    return (StopReason::DMax, Some((set, pe)));
                }
                Next::Stop(ev) => {
                    if ev == Event::LiftOff {
                        lifted(&mut pe.w);
                    }
                    self.range.see(&pe.w);
                    self.range.close(RangeEnd::Event);
                    self.out.push(spec, self.profile, &set, &pe, Some(ev));
                    return (stop_reason(ev, &pe.w, &set), Some((set, pe)));
                }
                Next::Limit(message) => {
                    // (the event point is already in the range: seen where it was found)
                    self.range.close(RangeEnd::Event);
                    let stop = StopReason::ContactChange { d: pe.lam, message };
                    return (stop, Some((set, pe)));
                }
                Next::Switch(ev, new_set, u) => {
                    self.out.push(spec, self.profile, &set, &pe, Some(ev));
                    if new_set.contacts.len() > set.contacts.len() {
                        let du = self.stepper.tangent_in(&new_set, pe.lam, &u);
                        let mu0 = spec.env.mu0;
                        if let Some(message) = forming_slip(&set, &new_set, &u, du, mu0) {
                            self.range.close(RangeEnd::Event);
                            let stop = StopReason::ContactChange { d: pe.lam, message };
                            return (stop, Some((set, pe)));
                        }
                    }
                    let rising = pe.w.dmu_abs;
                    match self.stepper.switch(new_set.clone(), pe.lam, u) {
                        Ok(q) => {
                            // a maximum of |μ| at the kink of the change
                            if self.range.end.is_none()
                                && rising.is_some_and(|s| s > 0.0)
                                && q.w.dmu_abs.is_some_and(|s| s < 0.0)
                            {
                                self.range.see(&q.w);
                                self.range.close(RangeEnd::FirstMaximum);
                            }
                            // (one within rounding of zero too: its side is noise, and an armed
                            // one would cross back at once, an event the grid decides)
                            pending = Crossing::all(spec.env, &new_set)
                                .into_iter()
                                .filter(|c| {
                                    let v = c.of_watch(spec.env, &q.w);
                                    !holds(v) || v.abs() <= AT_ZERO
                                })
                                .collect();
                            hist = vec![q];
                            queue.clear();
                            pprev = None;
                        }
                        Err(e) => {
                            self.range.close(RangeEnd::SolverFailure);
                            return (
                                StopReason::ContactChange {
                                    d: pe.lam,
                                    message: format!(
                                        "{} ({} to {}): the new contact state does not hold: {e}",
                                        ev.name(),
                                        set.label(),
                                        new_set.label()
                                    ),
                                },
                                Some((set, pe)),
                            );
                        }
                    }
                }
            }
        }
    }
}

/// The end of a branch at a singular lift-off. A side contact whose normal force vanishes
/// rolls towards the tip faster and faster (its place `s` grows like a small power of `N`, and
/// its column of the Jacobian vanishes with `N`), so the corrector stalls short of `N = 0` and
/// no state beyond exists to bracket the root. When a step fails where the newest points show
/// the normal force of the only contact falling and below `1e-3` of its contact force, its zero is
/// the secant's, at most `1e-4 (1 + |λ|)` further on. The secant is first order: `|N'|` eases
/// as `N → 0`, so the zero lies a few percent of that distance further (on the scene of
/// `tests/scan_fixes.rs`, 11 to 3831 points and every method give lift-offs within 3e-7 of
/// each other, 6e-6 beyond the last state). Returns the lift-off's `λ`, the evidence, and the
/// watch there (`N = 0`, `μ` unbounded with the tangential force's sign).
fn vanishing_normal(hist: &[Pt]) -> Option<(f64, String, Watch)> {
    let [.., a, b] = hist else {
        return None;
    };
    // (one of several contacts letting go is a change of the contact set, not the end)
    let ([ca], [cb]) = (&a.w.contacts[..], &b.w.contacts[..]) else {
        return None;
    };
    let (na, nb) = (ca.normal, cb.normal);
    if !(nb > 0.0 && na > nb && nb <= 1e-3 * nb.hypot(cb.tangential)) {
        return None;
    }
    let dl = nb * (b.lam - a.lam) / (na - nb);
    if !(dl.is_finite() && dl <= 1e-4 * (1.0 + b.lam.abs())) {
        return None;
    }
    let ls = b.lam + dl;
    let mut w = b.w.clone();
    w.lam = ls;
    lifted(&mut w);
    let why = format!(
        "extrapolated: the normal force of the contact falls to {nb:.3e} at {} (s = {:.6}), \
         where the equations stop determining the contact; its zero lies {dl:.2e} further on",
        b.lam, cb.s
    );
    Some((ls, why, w))
}

/// The watch `w` at a lift-off: the normal force of the contact letting go (the one with the
/// least) and the total are 0 exactly there, so the friction ratio is unbounded, with the
/// tangential force's sign (μ itself may have crossed the pole).
fn lifted(w: &mut Watch) {
    w.normal = 0.0;
    let t: f64 = w.contacts.iter().map(|c| c.tangential).sum();
    w.mu = f64::INFINITY.copysign(t);
    if let Some(c) = w
        .contacts
        .iter_mut()
        .min_by(|a, b| a.normal.total_cmp(&b.normal))
    {
        c.normal = 0.0;
    }
}

/// How far below zero a located touchdown's clearance on a curved surface may lie and still be
/// a root (a rounding of the rod's heights is ~1e-12; a jump is of the size of the rod's
/// features).
const JUMP: f64 = 1e-6;
/// An event function this close to zero right after a change of contact set is at zero.
const AT_ZERO: f64 = 1e-12;

/// The set with the interior contact `ct` touched down at `s` (in its place along the rod; its
/// unknowns N, T start at zero), and its unknowns.
fn touchdown(set: &ContactSet, u: &[f64], ct: Contact, s: f64) -> Next {
    let j = (0..set.contacts.len())
        .find(|&j| set.s_of(j, u) > s)
        .unwrap_or(set.contacts.len());
    let mut ns = set.clone();
    ns.contacts.insert(j, ct);
    let o = if j < set.contacts.len() {
        set.offset(j)
    } else {
        u.len()
    };
    let mut nu = u.to_vec();
    nu.splice(o..o, [0.0, 0.0, s]);
    Next::Switch(Event::Touchdown, ns, nu)
}

/// Why a contact that has just formed beside others cannot hold: the friction ratio it needs
/// from the moment it forms, `|dT/dλ| / (dN/dλ)` on the new state's exact tangent, exceeds `μ0`
/// (or, without it, [`SIDE_FRICTION_LIMIT`]). This happens where a side touches down next to
/// a contact that does not slip (the stuck tip): the segment between them is trapped, its chord
/// minus its length is frozen by the two no-slip conditions, and keeping it so as the rod is
/// dragged takes equal and opposite tangential forces, large because they bend the nearly
/// straight segment only through its sag (10²–10⁴ times the new normal force). On any real
/// surface the side slips at once, and a sliding side contact is not in the scan's model. `None`
/// where the new contact is not in a no-slip mode, does not load, or needs less.
fn forming_slip(
    old: &ContactSet,
    new: &ContactSet,
    u: &[f64],
    du: Option<Vec<f64>>,
    mu0: Option<f64>,
) -> Option<String> {
    let j = new
        .contacts
        .iter()
        .position(|c| !old.contacts.contains(c))?;
    if !new.contacts[j].mode.no_slip() {
        return None;
    }
    let du = du?;
    let o = new.offset(j);
    let (dn, dt) = (du[o], du[o + 1]);
    let ratio = (dt / dn).abs();
    let limit = mu0.unwrap_or(SIDE_FRICTION_LIMIT);
    // (a contact that does not load pulls: the pending check says so)
    let slips = dn > 0.0 && ratio > limit;
    if !slips {
        return None;
    }
    let s = new.s_of(j, u);
    let bound = match mu0 {
        Some(m) => format!("mu0 = {m}"),
        None => format!("any dry surface provides ({SIDE_FRICTION_LIMIT})"),
    };
    let neighbour = [j.checked_sub(1), Some(j + 1)]
        .into_iter()
        .flatten()
        .filter(|&k| k < new.contacts.len())
        .filter(|&k| new.contacts[k].mode.no_slip())
        .map(|k| {
            let name = if new.contacts[k].tip {
                "stuck tip"
            } else {
                "rolling side"
            };
            (new.s_of(k, u), name)
        })
        .min_by(|a, b| (a.0 - s).abs().total_cmp(&(b.0 - s).abs()));
    let trap = match neighbour {
        Some((sk, name)) => format!(
            " (with the {name} at s = {sk:.6} it traps a segment of length {:.3e} that neither end lets slip)",
            (sk - s).abs()
        ),
        None => String::new(),
    };
    Some(format!(
        "a side contact forms at s = {s:.6}{trap} and needs a friction ratio |T|/N = {ratio:.3e} from the moment it forms, more than {bound}: it slips at once, and a sliding side contact is not in the scan's model"
    ))
}

/// An event function's value where its contact state holds strictly (NaN: not known to).
fn holds(v: f64) -> bool {
    v < 0.0
}

/// Its value where the event has happened (zero included).
fn ended(v: f64) -> bool {
    v >= 0.0
}

/// Its value beyond the event (NaN: not known to be).
fn beyond(v: f64) -> bool {
    v > 0.0
}

/// What follows an event.
enum Next {
    /// The march ends with this event.
    Stop(Event),
    /// The contact set changes (the event, the new set, the old state in its unknowns).
    Switch(Event, ContactSet, Vec<f64>),
    /// The march reached its target.
    Done,
    /// The march ends at a limit of the model (a contact change; the evidence).
    Limit(String),
}

/// The contact set after a touchdown, the tip lying down, or a peel-back on a curved surface (as
/// on a line, with the surface's arc length for the places and its local frame for the forces).
fn curve_transition(
    h: &'static crate::surface::Height,
    set: &ContactSet,
    cross: Crossing,
    pe: &Pt,
    xf: f64,
    friction: bool,
) -> Next {
    let u = &pe.u;
    let rolling = |z: &[f64], s: f64| -> (Mode, f64) {
        let x = z[0] + xf;
        let th = h.angle(x).0;
        let phi_ref = crate::chain::slope_on(th, z[2]);
        let dir = (phi_ref - th).cos().round();
        let mode = if friction {
            Mode::Rolling(h.sigma(x).0 - dir * s)
        } else {
            Mode::Free
        };
        (mode, phi_ref)
    };
    match cross {
        Crossing::Touchdown => {
            let s = pe.w.clear_s;
            let z = pe.w.clear_z;
            let (mode, phi_ref) = rolling(&z, s);
            let ct = Contact::on_curve(false, h, z[0] + xf, mode, phi_ref);
            touchdown(set, u, ct, s)
        }
        Crossing::TipTangent => {
            let j = set.contacts.len() - 1;
            let zb = pe.sol.right();
            let (mode, phi_ref) = rolling(zb, 1.0);
            let mut ns = set.clone();
            // the force keeps its frame (the unknowns carry over)
            ns.contacts[j] = Contact {
                tip: false,
                mode,
                phi_ref,
                ..set.contacts[j]
            };
            let mut nu = u.clone();
            nu.push(1.0);
            Next::Switch(Event::Touchdown, ns, nu)
        }
        Crossing::PeelBack(j) => {
            let o = set.offset(j);
            let mut ns = set.clone();
            let mut nu = u.clone();
            if set.tip() {
                // the rolling contact reaches the touching tip: one contact there (its force
                // expressed in the tip's frame)
                let jt = set.contacts.len() - 1;
                let ot = set.offset(jt);
                let f = set.contacts[j].force(u[o], u[o + 1]);
                let ct = set.contacts[jt];
                let t = ct.t();
                nu[ot] -= f[0] * ct.n[0] + f[1] * ct.n[1];
                nu[ot + 1] += f[0] * t[0] + f[1] * t[1];
                nu.drain(o..o + 3);
                ns.contacts.remove(j);
            } else {
                let zb = pe.sol.right();
                let mode = if friction {
                    Mode::Stuck(h.sigma(zb[0] + xf).0)
                } else {
                    Mode::Free
                };
                ns.contacts[j] = Contact {
                    tip: true,
                    mode,
                    ..set.contacts[j]
                };
                nu.remove(o + 2);
            }
            Next::Switch(Event::PeelBack, ns, nu)
        }
        _ => Next::Stop(Event::Penetration),
    }
}

impl<P: Profile> Run<'_, '_, P> {
    /// The contact set after the event `cross` at the point `pe` (or the end).
    fn transition(&self, set: &ContactSet, cross: Crossing, pe: &Pt) -> Next {
        let env = self.spec.env;
        let friction = self.spec.friction;
        let u = &pe.u;
        let xf = self.stepper.foot_x(pe.lam);
        let along = |z: &[f64], beta: f64, p0: [f64; 2]| {
            let (sb, cb) = beta.sin_cos();
            cb * (z[0] + xf - p0[0]) + sb * (z[1] - p0[1])
        };
        match cross {
            Crossing::Slip(j) if self.spec.slide => {
                let c = pe.w.contacts[j];
                let mut ns = set.clone();
                ns.contacts[j].mode = Mode::Sliding(c.tangential / c.normal);
                Next::Switch(Event::Slip, ns, u.clone())
            }
            // a contact that traps the rod reaches the bound of dry friction (no μ0)
            Crossing::Slip(j) if env.mu0.is_none() && env.ground.texture.is_none() => {
                let c = pe.w.contacts[j];
                let name = if set.contacts[j].tip {
                    "tip"
                } else {
                    "side contact"
                };
                Next::Limit(format!(
                    "the {name} at s = {:.6} would slip: with another contact that does not slip it traps the rod between them, and the friction ratio it needs, |T|/N, reached {} (the bound of dry friction without mu0); a sliding contact beside another is not in the scan's model",
                    c.s, c.mu_s
                ))
            }
            Crossing::Slip(_) => Next::Stop(Event::Slip),
            Crossing::Lie(j) => Next::Limit(format!(
                "the side contact at s = {:.6} begins to lie along the surface: the rod's curvature relative to the surface there fell to zero, so beyond it the rod would run along the line; a lying stretch pressed by a distributed force is not in the model",
                pe.w.contacts[j].s
            )),
            // the end of a slip: the march in the slip's parameter reached its goal
            Crossing::Stick(_) => Next::Done,
            Crossing::SlipOff(_) => Next::Stop(Event::SlipOff),
            Crossing::MuMax => Next::Stop(Event::FoldInD),
            Crossing::Target(_) => Next::Done,
            Crossing::Lift(j) => {
                if set.contacts.len() == 1 {
                    return Next::Stop(Event::LiftOff);
                }
                let mut ns = set.clone();
                ns.contacts.remove(j);
                let o = set.offset(j);
                let mut nu = u.clone();
                nu.drain(o..o + set.contacts[j].unknowns());
                Next::Switch(Event::Release, ns, nu)
            }
            Crossing::Touchdown | Crossing::TipTangent if !env.compound => {
                Next::Stop(Event::Penetration)
            }
            Crossing::Touchdown | Crossing::TipTangent | Crossing::PeelBack(_)
                if env.ground.curve.is_some() =>
            {
                match env.ground.curve {
                    Some(h) => curve_transition(h, set, cross, pe, xf, friction),
                    None => Next::Stop(Event::Penetration),
                }
            }
            Crossing::Touchdown => {
                let Some((p0, beta)) = env.line else {
                    return Next::Stop(Event::Penetration);
                };
                let s = pe.w.clear_s;
                let z = pe.w.clear_z;
                let phi_ref = crate::chain::slope_on(beta, z[2]);
                let mode = if friction {
                    Mode::Rolling(along(&z, beta, p0) - (phi_ref - beta).cos().round() * s)
                } else {
                    Mode::Free
                };
                let ct = Contact::on_surface(false, p0, beta, mode, phi_ref);
                touchdown(set, u, ct, s)
            }
            Crossing::TipTangent => {
                let j = set.contacts.len() - 1;
                let ct = set.contacts[j];
                let Geom::Line { p0, beta } = ct.geom else {
                    return Next::Stop(Event::Penetration);
                };
                let zb = pe.sol.right();
                let phi_ref = crate::chain::slope_on(beta, zb[2]);
                let mode = if friction {
                    Mode::Rolling(along(zb, beta, p0) - (phi_ref - beta).cos().round())
                } else {
                    Mode::Free
                };
                let mut ns = set.clone();
                ns.contacts[j] = Contact::on_surface(false, p0, beta, mode, phi_ref);
                let mut nu = u.clone();
                nu.push(1.0);
                Next::Switch(Event::Touchdown, ns, nu)
            }
            Crossing::PeelBack(j) => {
                let ct = set.contacts[j];
                let Geom::Line { p0, beta } = ct.geom else {
                    return Next::Stop(Event::SlipOff);
                };
                let o = set.offset(j);
                let mut ns = set.clone();
                let mut nu = u.clone();
                if set.tip() {
                    // the rolling contact reaches the touching tip: one contact there
                    let ot = set.offset(set.contacts.len() - 1);
                    nu[ot] += u[o];
                    nu[ot + 1] += u[o + 1];
                    nu.drain(o..o + 3);
                    ns.contacts.remove(j);
                } else {
                    let zb = pe.sol.right();
                    let mode = if friction {
                        Mode::Stuck(along(zb, beta, p0))
                    } else {
                        Mode::Free
                    };
                    ns.contacts[j] = Contact::on_surface(true, p0, beta, mode, 0.0);
                    nu.remove(o + 2);
                }
                Next::Switch(Event::PeelBack, ns, nu)
            }
        }
    }

    /// `∫ rate dλ` of the work `m` from `a` to `b` on the branch (points of `hist`'s span):
    /// the Hermite-corrected trapezoid, halved with solves at the midpoints until the halves agree
    /// with the whole to 1e-11 (its error falls 16-fold per halving: the halves' sum is then
    /// extrapolated).
    fn meter_between(&mut self, m: Meter, hist: &[Pt], a: &Pt, b: &Pt, depth: u32) -> f64 {
        let env = self.spec.env;
        let ends = |st: &dyn Stepper, a: &Pt, b: &Pt| {
            let set = st.set();
            metered(m, env, set, (a, st.foot_x(a.lam)), (b, st.foot_x(b.lam)))
        };
        let whole = ends(&*self.stepper, a, b);
        if depth >= 16 || b.lam - a.lam <= 1e-13 * (1.0 + b.lam.abs()) {
            return whole;
        }
        let Ok(mid) = self.stepper.correct(0.5 * (a.lam + b.lam), hist, true) else {
            return whole;
        };
        let halves = ends(&*self.stepper, a, &mid) + ends(&*self.stepper, &mid, b);
        if (halves - whole).abs() <= 1e-11 * (1.0 + whole.abs()) {
            return halves + (halves - whole) / 15.0;
        }
        self.meter_between(m, hist, a, &mid, depth + 1)
            + self.meter_between(m, hist, &mid, b, depth + 1)
    }

    /// Where the branch polynomial, extrapolated from the last points, predicts `c` to reach 0
    /// within `(a, b]` (`None` without a polynomial, or when it does not).
    fn predicted_crossing(&self, hist: &[Pt], a: f64, b: f64, c: Crossing) -> Option<f64> {
        let env = self.spec.env;
        let set = self.stepper.set();
        let on_poly = |lam: f64| -> Result<f64, String> {
            let (u, _) = self
                .stepper
                .interpolant(hist, lam)
                .ok_or_else(|| "no polynomial".to_string())?;
            c.of_u(env, set, &u)
                .ok_or_else(|| "not a function of the unknowns".to_string())
        };
        let (ga, gb) = (on_poly(a).ok()?, on_poly(b).ok()?);
        if !(ga < 0.0 && gb >= 0.0) {
            return None;
        }
        let mut f = on_poly;
        search::root(&mut f, a, b, 1e-15 * (1.0 + b.abs())).ok()
    }

    /// The first `λ` in `[a, b]` where `c` reaches 0 (`c(a) < 0 ≤ c(b)`). Where the stepper has
    /// the branch as a polynomial and `c` depends on the unknowns alone: Brent's method on that
    /// polynomial, refined by Newton steps with solves — one or two solves. Otherwise Brent's
    /// method on solves within the step (the event function evaluated on the rod).
    fn locate(&mut self, hist: &[Pt], a: f64, b: f64, c: Crossing) -> Result<Pt, String> {
        let env = self.spec.env;
        let fresh = c == Crossing::MuMax;
        let set = self.stepper.set().clone();
        let poly_val = |st: &dyn Stepper, lam: f64| -> Option<f64> {
            let (u, du) = st.interpolant(hist, lam)?;
            match c {
                Crossing::MuMax => Some(-mu_slope(&set, &u, &du)),
                _ => c.of_u(env, &set, &u),
            }
        };
        if poly_val(&*self.stepper, a).is_some() {
            let st: &dyn Stepper = &*self.stepper;
            let mut poly = |lam: f64| poly_val(st, lam).ok_or_else(|| "no polynomial".to_string());
            if let Ok(mut lam) = search::root(&mut poly, a, b, 1e-15 * (1.0 + b.abs())) {
                let eps = 1e-6 * (b - a);
                for _ in 0..4 {
                    let p = self.stepper.correct(lam, hist, fresh)?;
                    let st: &dyn Stepper = &*self.stepper;
                    let slope = match (poly_val(st, lam + eps), poly_val(st, lam - eps)) {
                        (Some(gp), Some(gm)) => (gp - gm) / (2.0 * eps),
                        _ => break,
                    };
                    let step = c.of_watch(env, &p.w) / slope;
                    if !step.is_finite() || !(a..=b).contains(&(lam - step)) {
                        break;
                    }
                    if step.abs() <= 1e-13 * (1.0 + lam.abs()) {
                        return Ok(p);
                    }
                    lam -= step;
                }
            }
        }
        let stepper = &mut *self.stepper;
        let mut eval = |lam: f64| -> Result<f64, String> {
            let p = stepper.correct(lam, hist, fresh)?;
            Ok(c.of_watch(env, &p.w))
        };
        let lam = search::root(&mut eval, a, b, 1e-13 * (1.0 + b.abs()))?;
        let p = self.stepper.correct(lam, hist, fresh)?;
        self.inside(hist, a, p, c, fresh)
    }

    /// The located event point on the side where the old state still holds (`c ≤ 0`): a root to
    /// ~1e-13 in λ may lie a rounding beyond it (a free part ~1e-12 above the surface); then λ
    /// moves back by twice the secant step towards `a`, doubling until the point is inside.
    fn inside(
        &mut self,
        hist: &[Pt],
        a: f64,
        p: Pt,
        c: Crossing,
        fresh: bool,
    ) -> Result<Pt, String> {
        let env = self.spec.env;
        let g = c.of_watch(env, &p.w);
        if !beyond(g) {
            return Ok(p);
        }
        let ga = hist
            .iter()
            .find(|q| q.lam == a)
            .map_or(-1.0, |q| c.of_watch(env, &q.w));
        let secant = g * (p.lam - a) / (g - ga);
        for k in 0..8 {
            let lam = (p.lam - 2.0 * secant * f64::from(1 << k)).max(a);
            let q = self.stepper.correct(lam, hist, fresh)?;
            if !beyond(c.of_watch(env, &q.w)) {
                return Ok(q);
            }
        }
        Ok(p)
    }

    /// The first maximum of `|μ|` in `(prev.λ, l_stop]`, if there is one: the root of `d|μ|/dλ`
    /// where tangents are known, else (three-point pattern) Brent's maximizer.
    fn first_max(
        &mut self,
        hist: &[Pt],
        prev: &Watch,
        pprev: Option<&Watch>,
        w: &Watch,
        l_stop: f64,
    ) -> Option<Watch> {
        // μ = ΣT/ΣN has a pole where the total normal force passes zero (lift-off): the sign
        // change of d|μ|/dλ across it is no maximum
        if w.normal <= 0.0 {
            return None;
        }
        if let (Some(s0), Some(s1)) = (prev.dmu_abs, w.dmu_abs) {
            if !(s0 > 0.0 && s1 <= 0.0) {
                return None;
            }
            let p = self.locate(hist, prev.lam, w.lam, Crossing::MuMax).ok()?;
            return (p.lam <= l_stop).then_some(p.w);
        }
        let pp = pprev?;
        if !(prev.mu.abs() > pp.mu.abs() && prev.mu.abs() >= w.mu.abs()) {
            return None;
        }
        let stepper = &mut *self.stepper;
        let mut eval =
            |lam: f64| -> Result<f64, String> { Ok(stepper.correct(lam, hist, false)?.w.mu.abs()) };
        let (lam, _) = search::maximize(&mut eval, pp.lam, w.lam.min(l_stop), 1e-12).ok()?;
        Some(self.stepper.correct(lam, hist, false).ok()?.w)
    }

    /// Emits the grid points up to `upto` (the branch point itself where one is at the grid
    /// value, else a solve from the history). A point that cannot be solved ends the march.
    fn emit(&mut self, hist: &[Pt], upto: f64) -> Result<(), StopReason> {
        while let Some(&g) = self.spec.grid.get(self.out.gi) {
            if g > upto {
                break;
            }
            let p = match hist.iter().rev().find(|p| p.lam == g) {
                Some(p) => p.clone(),
                None => match self.stepper.correct(g, hist, false) {
                    Ok(p) => p,
                    Err(e) => self
                        .bridge(hist, g)
                        .map_err(|e2| StopReason::SolverFailure {
                            d: hist
                                .iter()
                                .map(|p| p.lam)
                                .filter(|&l| l < g)
                                .fold(0.0, f64::max),
                            message: format!("output point at {g}: {e}; in shorter steps: {e2}"),
                        })?,
                },
            };
            let set = self.stepper.set().clone();
            self.out.push(self.spec, self.profile, &set, &p, None);
            self.out.gi += 1;
        }
        Ok(())
    }
}

impl<P: Profile> Run<'_, '_, P> {
    /// The point at `g` by natural steps from the last point of `hist` before it (where one
    /// correction from the whole history fails, e.g. after pseudo-arclength jumped past `g`).
    fn bridge(&mut self, hist: &[Pt], g: f64) -> Result<Pt, String> {
        let mut local: Vec<Pt> = hist.iter().filter(|p| p.lam < g).cloned().collect();
        let Some(last) = local.last() else {
            return Err("no point before it".into());
        };
        let mut h = (g - last.lam) / 4.0;
        for _ in 0..200 {
            let lam = local[local.len() - 1].lam;
            let target = (lam + h).min(g);
            match self.stepper.correct(target, &local, false) {
                Ok(p) => {
                    if target == g {
                        return Ok(p);
                    }
                    local.push(p);
                    if local.len() > 4 {
                        local.remove(0);
                    }
                    h *= 1.5;
                }
                Err(e) => {
                    h *= 0.25;
                    if h < 1e-9 * (1.0 + g.abs()) {
                        return Err(e.to_string());
                    }
                }
            }
        }
        Err("no convergence in 200 steps".into())
    }
}

/// The rate of the work `m` at the point `p` (foot at `xf`) and its slope in `λ`.
fn meter_rate(m: Meter, env: &Env, set: &ContactSet, p: &Pt, xf: f64) -> (f64, f64) {
    let zero = vec![0.0; p.u.len()];
    let du = p.du.as_deref().unwrap_or(&zero);
    match m {
        Meter::Foot => {
            let (mut r, mut dr) = (0.0, 0.0);
            for (j, ct) in set.contacts.iter().enumerate() {
                let o = set.offset(j);
                r -= ct.force(p.u[o], p.u[o + 1])[0];
                dr -= ct.force(du[o], du[o + 1])[0];
            }
            (r, dr)
        }
        Meter::Slide => {
            let dir = env.ground.slide.map_or(1.0, |s| s.dir);
            let Some(j) = set.contacts.iter().position(|c| c.tip) else {
                return (0.0, 0.0);
            };
            let ct = set.contacts[j];
            let o = set.offset(j);
            let f = ct.force(p.u[o], p.u[o + 1]);
            let df = ct.force(du[o], du[o + 1]);
            // the unit tangent along +σ at the tip and its turn per unit arc length
            let (e, de) = match ct.geom {
                Geom::Curve { h } => {
                    let x = p.sol.right()[0] + xf;
                    let (_, d, dd) = h.jet(x);
                    let w = (1.0 + d * d).sqrt();
                    let kappa = dd / (w * w * w);
                    ([1.0 / w, d / w], [-d / w * kappa, kappa / w])
                }
                Geom::Line { beta, .. } => ([beta.cos(), beta.sin()], [0.0, 0.0]),
                _ => return (0.0, 0.0),
            };
            let r = -dir * (f[0] * e[0] + f[1] * e[1]);
            let dr = -dir * (df[0] * e[0] + df[1] * e[1]) - (f[0] * de[0] + f[1] * de[1]);
            (r, dr)
        }
    }
}

/// `∫ rate dλ` between two points of one branch: the trapezoid with the end-slope correction
/// (exact for cubics; Hermite data from the exact tangents).
fn metered(m: Meter, env: &Env, set: &ContactSet, a: (&Pt, f64), b: (&Pt, f64)) -> f64 {
    let h = b.0.lam - a.0.lam;
    if h == 0.0 {
        return 0.0;
    }
    let (ra, da) = meter_rate(m, env, set, a.0, a.1);
    let (rb, db) = meter_rate(m, env, set, b.0, b.1);
    0.5 * h * (ra + rb) + h * h / 12.0 * (da - db)
}

/// `d|μ|/dλ` of the total friction ratio from the unknowns and their tangent (surface
/// contacts; the unknowns are the forces in the surface frame).
fn mu_slope(set: &ContactSet, u: &[f64], du: &[f64]) -> f64 {
    let (mut n, mut t, mut dn, mut dt) = (0.0, 0.0, 0.0, 0.0);
    for j in 0..set.contacts.len() {
        let o = set.offset(j);
        n += u[o];
        t += u[o + 1];
        dn += du[o];
        dt += du[o + 1];
    }
    let mu = t / n;
    let dmu = (dt * n - t * dn) / (n * n);
    if mu == 0.0 {
        dmu.abs()
    } else {
        mu.signum() * dmu
    }
}

/// The output point of a branch point.
pub(crate) fn scan_point<P: Profile>(
    p: &Pt,
    set: &ContactSet,
    profile: &P,
    event: Option<Event>,
) -> ScanPoint {
    let w = &p.w;
    let (fx, fy) = (w.force[0], w.force[1]);
    let f = (fx * fx + fy * fy).sqrt();
    let alpha = fx.atan2(-fy);
    let (flex, s_flex, _) = flex_and_reversals(&p.sol, profile);
    let s_c = set
        .contacts
        .iter()
        .position(|c| !c.tip)
        .map(|j| set.s_of(j, &p.u));
    let mu_peak = w
        .contacts
        .iter()
        .map(|c| match c.normal {
            // lift-off: unbounded unless no tangential force is needed
            0.0 if c.tangential == 0.0 => 0.0,
            n => (c.tangential / n).abs(),
        })
        .fold(0.0, f64::max);
    ScanPoint {
        d: p.lam,
        mu: w.mu,
        normal: w.normal,
        mu_peak,
        alpha,
        phi1: p.sol.right()[2],
        f,
        fx,
        fy,
        m_base: p.sol.left()[3],
        flex,
        s_flex,
        y_max: w.y_max,
        contact: ContactLabel::of(set),
        s_c,
        event,
    }
}

/// Output points on the grid, filled as the march passes them, and the event points.
struct Output {
    points: Vec<ScanPoint>,
    shapes: Vec<Vec<ShapePoint>>,
    gi: usize,
    tips: Vec<[f64; 4]>,
    metered: f64,
}

impl Output {
    fn push<P: Profile>(
        &mut self,
        spec: &Spec<'_>,
        profile: &P,
        set: &ContactSet,
        p: &Pt,
        event: Option<Event>,
    ) {
        self.points.push(scan_point(p, set, profile, event));
        let zb = p.sol.right();
        self.tips.push([zb[0], zb[1], zb[2], zb[3]]);
        if let Some(ns) = spec.keep_shapes {
            let shape = shape_from(p.sol.clone(), 0.0, spec.general.clone());
            self.shapes.push(shape.samples(ns));
        }
    }
}

/// Predictor from the last (at most three) points to `λ`: the Hermite polynomial through their
/// values and tangents (degree 5 with three points) where all have tangents, else Lagrange; and
/// its derivative.
pub(crate) fn interpolate(hist: &[Pt], lam: f64) -> (Vec<f64>, Vec<f64>) {
    let m = hist.len().min(3);
    let pts = &hist[hist.len() - m..];
    let hermite = pts.iter().all(|p| p.du.is_some());
    let n = pts[pts.len() - 1].u.len();
    let (mut u, mut du) = (vec![0.0; n], vec![0.0; n]);
    for i in 0..n {
        // divided differences, nodes newest first (confluent pairs with tangents)
        let mut z = [0.0; 6];
        let mut q = [[0.0; 6]; 6];
        let mut len = 0;
        for p in pts.iter().rev() {
            let reps = if hermite { 2 } else { 1 };
            for r in 0..reps {
                z[len] = p.lam;
                q[len][0] = p.u[i];
                if r == 1 {
                    q[len][1] = p.du.as_ref().map_or(0.0, |du| du[i]);
                } else if len > 0 {
                    q[len][1] = (q[len][0] - q[len - 1][0]) / (z[len] - z[len - 1]);
                }
                len += 1;
            }
        }
        for k in 2..len {
            for j in k..len {
                q[j][k] = (q[j][k - 1] - q[j - 1][k - 1]) / (z[j] - z[j - k]);
            }
        }
        // Newton form and its derivative (product rule on the nested factors)
        let (mut v, mut dv, mut w, mut dw) = (0.0, 0.0, 1.0, 0.0);
        for k in 0..len {
            v += q[k][k] * w;
            dv += q[k][k] * dw;
            dw = dw * (lam - z[k]) + w;
            w *= lam - z[k];
        }
        u[i] = v;
        du[i] = dv;
    }
    (u, du)
}
