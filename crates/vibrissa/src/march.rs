//! The one march: a contact chain followed in its family parameter `λ` (the foot displacement
//! `d` of the scan, the press depth of the start, the foot angle of a whisk, the slide of a
//! slipping contact), for every rod, every method and every contact set.
//!
//! One driver loop over the step contract of module `stepper`: each step predicts the next point
//! from the last ones and corrects it (natural continuation from output point to output point,
//! intermediate steps where the grid is coarse; step control in module `control`); where a
//! natural step fails for tiny steps (near a fold in `λ`) the fold passage (module `fold`)
//! passes it or locates the fold. After every accepted step the events between the last point
//! and the new one are located inside that step (module `events`; no restart), and the earliest
//! is the step's outcome: the march backs up to it, writes it as a point with its [`Event`],
//! and either changes the contact set and goes on in the same step sequence (touchdown,
//! peel-back, release, a contact sliding on) or ends. What is recorded (rows, shapes, the first
//! maximum of `|μ|`, metered work) is observed by module `record`.

use crate::chain::{ContactSet, Geom, Mode};
use crate::control::StepControl;
use crate::events::{
    beyond, ended, first_max, forming_slip, holds, lifted, locate, predicted_crossing,
    sliding_from_start, start_event, stop_reason, transition, vanishing_normal, Crossing, Next,
    Rules, AT_ZERO, JUMP,
};
use crate::fold;
use crate::profile::{General, Profile};
use crate::record::{meter_between, Output, RangeTracker};
use crate::report::{Event, RangeEnd, ScanPoint, StopReason};
use crate::search;
use crate::shape::ShapePoint;
use crate::stepper::{Chord, Passed, Pt, StepError, Stepper};
use crate::surface::Meter;
use crate::watch::{Env, Watch};
use bvp::Stats;
use std::collections::VecDeque;

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
    /// A natural step that fails with a fold predicted within it hands over to the fold passage
    /// at once ([`fold::ahead`]) instead of shrinking towards the fold: the scan. The drag's
    /// marches crawl as before: a stretch that reaches the tip is joined where the crawl fails
    /// (`Run::reach_tip`), and with the fold passed at once three rows of the texture grid met a
    /// trapped slide before it (docs/performance.md, "A fold ahead is passed at once").
    pub pass_fold_ahead: bool,
    /// A point whose prediction needed a second chord step gets its exact tangent
    /// (`rodsolve::Flags::retangent`): the scan. In the drag's marches the same rule changed the
    /// paths through trapped pairs, whose outcomes rounding decides (docs/performance.md, "The
    /// rat presets under 3×"), so they run as before.
    pub retangent: bool,
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
    /// The contacts of each output point.
    pub contacts: Vec<Vec<crate::contacts::ContactState>>,
    /// In a slip: the driver's number in each output point's set.
    pub drivers: Vec<Option<usize>>,
    /// The works integrated along the march (`env.ground.meter`; 0 without one): the foot's and
    /// what friction absorbed at the sliding contacts.
    pub metered: [f64; 2],
    /// In a slip: the driver's number in the last point's set (one less for each contact before
    /// it that let go during the march); `None` where the driver itself let go (the march ends at
    /// the first point without it).
    pub driver: Option<usize>,
    /// Where the slip's driver let go: the contacts that slid along with it, held where they were
    /// then (their numbers in the last point's set, and their friction ratios `T/N`).
    pub riders: Vec<(usize, f64)>,
}

/// Runs the march from the point `p0` (λ = `p0.lam`) over the grid.
pub(crate) fn march<P: Profile>(
    stepper: &mut dyn Stepper,
    spec: &Spec<'_>,
    profile: &P,
    p0: Pt,
    mut stats: Stats,
) -> MarchOut {
    stepper.set_retangent(spec.retangent);
    let gi = spec.grid.partition_point(|&g| g < p0.lam);
    let rows = spec.grid.len() + 1;
    let mut out = Output::new(rows, gi, spec.keep_shapes, profile, spec.general);
    out.driver = spec.env.ground.slide.map(|s| s.driver);
    let mut range = RangeTracker {
        best: (p0.w.mu.abs(), p0.w.mu, p0.lam),
        end: None,
    };
    let start_event = if spec.check_start {
        start_event(spec.env, stepper.set(), &p0.w)
    } else {
        None
    };
    // a start that traps the rod between contacts whose equilibrium is singular to working
    // precision: the tangential pair between them has no determined value (the corrections
    // return any of a line of states, |T|/N of 1e3 on a frictionless press)
    let indeterminate = start_event.is_none() && spec.check_start && {
        let set = stepper.set().clone();
        stepper.trapped_singular(&set, p0.lam, &p0.u)
    };
    let set = stepper.set().clone();
    let (stop, last) = if let Some(ev) = start_event {
        // the start itself is not a valid state (the rod crosses the surface, is pulled, or
        // slips): it is reported as the event, never as a grid row
        range.close(RangeEnd::Event);
        out.push(&set, &p0, Some(ev));
        (stop_reason(ev, &p0.w, &set), Some((set, p0)))
    } else {
        let mut run = Run {
            stepper: &mut *stepper,
            spec,
            env: spec.env.clone(),
            ctl: StepControl::default(),
            out: &mut out,
            range: &mut range,
            lain: None,
            metered_to: None,
            reaches: 0,
        };
        // (in a drag, the pair's member that friction lets go first slides from the start)
        let start = match indeterminate {
            false => Ok((p0, None)),
            true => run.slides_at_start(&set, &p0).ok_or(p0),
        };
        match start {
            Err(p0) => {
                let stop = run.indeterminate(&set, &p0);
                (stop, Some((set, p0)))
            }
            Ok((p0, quiet)) => {
                let (mut stop, mut last) = run.run(p0, quiet);
                // (a failure where the stretch lying on the surface reaches the tip: the tip
                // joins it and the march goes on, as often as it reaches it; also where a side
                // has just lain down, whose stop by the lie's name then no longer applies)
                loop {
                    let failed = matches!(stop, StopReason::SolverFailure { .. });
                    let Some(q) = failed
                        .then(|| last.as_ref().and_then(|(set, p)| run.reach_tip(set, p)))
                        .flatten()
                    else {
                        break;
                    };
                    run.lain = None;
                    (stop, last) = run.run(q, None);
                }
                // (a failure with the tip just beyond a lying stretch: the stretch reaches the
                // tip, a singular state, named at the last point)
                let near = matches!(stop, StopReason::SolverFailure { .. })
                    .then_some(last.as_ref())
                    .flatten()
                    .and_then(|(set, p)| Some((crate::events::stretch_at_tip(set, p)?, p.lam)));
                match (stop, run.lain.take(), near) {
                    (StopReason::SolverFailure { message, .. }, Some(lain), _) => {
                        let Lain {
                            set,
                            pe,
                            lie,
                            mark,
                            range,
                        } = *lain;
                        run.out.rewind(mark);
                        *run.range = range;
                        run.range.close(RangeEnd::Event);
                        let stop = StopReason::ContactChange {
                            d: pe.lam,
                            message: format!("{lie} ({message})"),
                        };
                        (stop, Some((set, pe)))
                    }
                    (StopReason::SolverFailure { message, .. }, None, Some((why, at))) => {
                        run.range.close(RangeEnd::Event);
                        let stop = StopReason::ContactChange {
                            d: at,
                            message: format!("{why} ({message})"),
                        };
                        (stop, last)
                    }
                    (stop, _, _) => (stop, last),
                }
            }
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
        contacts: out.contacts,
        driver: out.driver,
        drivers: out.drivers,
        metered: out.metered,
        riders: out.riders,
    }
}

/// The driver: the stepper, what the march must do, its step control, and what it records.
struct Run<'a, 'b, P: Profile> {
    stepper: &'a mut dyn Stepper,
    spec: &'a Spec<'b>,
    /// The march's environment: the spec's, with a slip's driver renumbered where a contact
    /// before it lets go.
    env: Env,
    ctl: StepControl,
    out: &'a mut Output<'b, P>,
    range: &'a mut RangeTracker,
    /// A side that lay down sliding along the surface with contacts beyond it, while the set it
    /// formed is the march's: the set and point where it did, and the stop there, said as the
    /// lie. A solver failure in that set ends the march at the lie-down with that stop (the
    /// failure's message added): a side that lies down in a slip between another side and the
    /// tip leaves a state the solver may not resolve (issue 31's texture grid, taper 0.3 over
    /// 0.003/0.5 and 0.02/0.5 at 2π/3: Newton and the fold passage failed 0.009 and 0.005 of
    /// the slide further on), and the lie-down is the last change the model followed.
    lain: Option<Box<Lain>>,
    /// The point of the march's set up to which its works are metered (with a meter): a
    /// failure's last point may lie past it ([`Run::reach_tip`] meters the rest).
    metered_to: Option<Pt>,
    /// How often the march has taken the stretch reaching the tip ([`Run::reach_tip`]; at most
    /// [`REACHES`]).
    reaches: usize,
}

/// A lie-down the march followed that a later failure falls back on ([`Run::lain`]).
struct Lain {
    set: ContactSet,
    pe: Pt,
    /// The stop at the lie, said as it.
    lie: String,
    /// The record and the range at the lie, before its row.
    mark: crate::record::Mark,
    range: RangeTracker,
}

/// The march's state between steps.
struct Walk {
    /// The next natural step, its bounds.
    h: f64,
    h_max: f64,
    h_min: f64,
    /// Steps taken, and the budget.
    steps: usize,
    max_steps: usize,
    /// Steps in a row without progress in `λ`.
    stalled: usize,
    /// Where the march started.
    lam0: f64,
    /// The last (at most four) points of the branch, newest last.
    hist: Vec<Pt>,
    /// Event functions that are zero at the last change of the contact set, until they leave
    /// zero (on the side where the new state holds).
    pending: Vec<Crossing>,
    /// The watch of the point before the newest (the three-point pattern of a maximum of |μ|).
    pprev: Option<Watch>,
    /// Points of a pseudo-arclength path still to be taken as steps.
    queue: VecDeque<Pt>,
    /// The free parts' clearance rate at a state's first point, `(λ, dg/dλ)`: the touchdown's
    /// forecast on a curve where the history has one point (see [`Run::touchdown_forecast`]).
    rate0: Option<(f64, f64)>,
    /// The last step `(from, to)` taken again shorter after its events failed to be located.
    failed: Option<(f64, f64)>,
    /// The sliding contact whose halts at its slip rate's noise are not located, since held
    /// there it traps the rod in an equilibrium singular to working precision (until the
    /// contact set changes; [`noise_halt`]).
    quiet: Option<usize>,
    /// The fold passage's step to its point where an armed event ended ([`Passed::Beyond`]).
    chord: Option<Box<Chord>>,
}

/// How a step ended.
enum Flow {
    /// The march goes on.
    Go,
    /// The march ends: why, and its last point (`None`: the newest of the history).
    End(StopReason, Option<Box<(ContactSet, Pt)>>),
    /// The contact set an event changed to does not hold at the event's point (the switch's
    /// Newton failed): the end as [`Flow::End`], unless the step is taken again shorter
    /// ([`Run::after_step`]).
    Unheld(StopReason, Box<(ContactSet, Pt)>),
    /// The sliding contact `j` halted at its slip rate's noise into a held state that traps
    /// the rod, singular to working precision: the end as [`Flow::End`], unless the step is
    /// taken again with that contact's noise halts not located ([`Run::after_step`]).
    Quiet(usize, StopReason, Box<(ContactSet, Pt)>),
}

/// The stop where a fold is reached in a state that pulls at one of its contacts (`N < 0` beyond
/// rounding): such a point is no state of the model, so it is not recorded; the contact set
/// entered before it (a tip touching down in a slide, seen in issue 31's property test) cannot
/// continue quasi-statically.
fn pulling(set: &ContactSet, p: &Pt, d: f64) -> Option<StopReason> {
    let total: f64 = p.w.contacts.iter().map(|c| c.normal.abs()).sum();
    let j = (p.w.contacts.iter()).position(|c| -c.normal > 1e-10 * (1.0 + total))?;
    Some(StopReason::ContactChange {
        d,
        message: format!(
            "the rod does not go on quasi-statically (a snap): its equilibria fold back in the \
             contact state {} with its contact at s = {:.6} pulling (N = {:.3e}), where no \
             state of the model holds",
            set.label(),
            set.s_of(j, &p.u),
            p.w.contacts[j].normal
        ),
    })
}

/// The stop where a slip's sliding contact `j` lets go (`N = 0` at the located point `pe`) while
/// the slip still needs a tangential force there, and the state without it is no nearby
/// equilibrium (`why`: the switch's failure, or what the state found without it violates):
/// releasing the contact removes a finite force from the rod at once, so no quasi-static state
/// continues from there and the rod jumps (the slip turns dynamic). `None` where the tangential
/// force is within rounding of zero (the release is continuous there, and a failure to solve it
/// is the solver's).
fn released_pushing(pe: &Pt, j: usize, why: &dyn std::fmt::Display) -> Option<StopReason> {
    let c = pe.w.contacts.get(j)?;
    let total: f64 = pe.w.contacts.iter().map(|c| c.normal.abs()).sum();
    if c.tangential.abs() <= 1e-8 * (1.0 + total) {
        return None;
    }
    Some(StopReason::Jam {
        d: pe.lam,
        message: format!(
            "the sliding contact at s = {:.6} lets go (N = {:.1e}) while the slip still needs \
             the tangential force T = {:.3e} there: releasing it removes that force from the rod \
             at once, and no quasi-static state without it follows (from the state at the \
             release: {why}); the slip turns dynamic",
            c.s, c.normal, c.tangential
        ),
    })
}

/// Why the state `q` of `set` found where a slip's driver let go is no state of the model: the
/// free rod crosses the surface there, or its end points into it, beyond a located event's
/// rounding, or a contact that holds without slip needs more than its static friction, beyond
/// the rounding of a force (`None` where none). The others take up at once the force the driver
/// still carried; a contact that cannot hold it slips at once (the property's seed 44 at 64
/// cases: a round tip lets go with T = 0.075 on it, and the side beside it, held, needs 0.0825
/// beyond μs N; driven on from there, the slip's released energy exceeded its friction work by
/// 3.7e-7, the jump's).
fn crossing_after_release(env: &Env, set: &ContactSet, q: &Pt) -> Option<String> {
    let beyond_static = (0..set.contacts.len())
        .filter(|&k| set.contacts[k].mode.no_slip() && k < q.w.contacts.len())
        .map(|k| (Crossing::Slip(k), q.w.contacts[k].normal))
        .map(|(c, n)| (c, c.of_watch(env, &q.w), FORCE_ROUNDING * (1.0 + n)));
    [Crossing::Touchdown, Crossing::TipTangent]
        .into_iter()
        .map(|c| (c, c.of_watch(env, &q.w), JUMP))
        .chain(beyond_static)
        .find(|&(_, v, by)| v > by)
        .map(|(c, v, _)| match c {
            Crossing::Touchdown => format!(
                "without it, {} = {v:.3e} at s = {:.6}",
                c.describe(),
                q.w.clear_s
            ),
            _ => format!("without it, {} = {v:.3e}", c.describe()),
        })
}

/// Why the jump at once from the state where a slip's driver let go (elastic energy `before`) to
/// the state without it (`after`) is no quasi-static change: it releases more energy than the
/// accuracy of a slip's balance, beyond [`GAIN`] `(1 + E)`, which no contact's friction works
/// off, or it would gain energy (`None` where neither). The driver's tangential force, still
/// there at `N = 0`, is gone at once, and the rod moves to the state without it dynamically (the
/// property's seed 44 at 64 cases, μk/μs 0.557: a tip slides 9.8e-8, lets go with
/// `T = 0.035` on it, and the jump released 1.0e-7 of the slip's 1.2e-7).
fn release_jump(before: f64, after: f64) -> Option<String> {
    let jump = before - after;
    let by = GAIN * (1.0 + before.abs());
    if jump > by {
        Some(format!(
            "without it, the rod jumps to a state with {jump:.3e} less elastic energy at once, \
             which no contact's friction works off"
        ))
    } else if jump < -by {
        Some(format!(
            "without it, the rod would jump to a state with {:.3e} more elastic energy",
            -jump
        ))
    } else {
        None
    }
}

/// How far beyond its static limit a contact held without slip may need friction, relative to
/// `1 + N`, and be taken to hold: the rounding of forces of order 1 solved to the corrector's
/// tolerance (the property test's slack of the friction conditions).
const FORCE_ROUNDING: f64 = 1e-10;

/// Why the march ends where a sliding contact of `set` halts at `pe` and holds (`held`, first
/// point `q`) in a state that traps the rod in an equilibrium singular to working precision, as
/// a start in such a state does (issue 31: a side 0.0054 from the tip; the sign of the Newton
/// matrix's determinant, 1e-27, is noise there, and the next step's fold passage reported a
/// fold 1.3e-16 on). A halt at the slip rate's noise into such a state is not taken where the
/// step can be taken again ([`Flow::Quiet`]).
fn halted_trapped(set: &ContactSet, held: &ContactSet, pe: &Pt, q: &Pt) -> String {
    let j = halted(set, held);
    let at: Vec<String> = (0..held.contacts.len())
        .filter(|&k| held.contacts[k].mode.no_slip())
        .map(|k| format!("{:.6}", held.s_of(k, &q.u)))
        .collect();
    format!(
        "the sliding contact at s = {:.6} halts and holds where it is: the state {} then traps \
         the rod between contacts at s = {} that hold without slip, and its equilibrium is \
         singular to working precision: the pair of tangential forces between them is \
         indeterminate; the point-contact model does not resolve it",
        set.s_of(j, &pe.u),
        held.label(),
        at.join(" and ")
    )
}

/// The contact of `set` that halted, held in `held` (the first whose mode differs).
fn halted(set: &ContactSet, held: &ContactSet) -> usize {
    (0..set.contacts.len())
        .find(|&k| set.contacts[k].mode != held.contacts[k].mode)
        .unwrap_or(0)
}

/// The set `new_set` left where the slip's driver let go (from `set` at `pe`, the foot at `xf`),
/// with the contacts that slid along with it (passive sliders, `T = ratio·N`) held where they are
/// at `pe`; their numbers in it and their ratios. Left sliding, they would be free to move at
/// once to where their kinetic friction alone holds the rod, the force the driver still carried
/// (its tangential force need not vanish with its normal force) gone: a jump whose energy no
/// friction work accounts for (issue 31: 3.3e-4 of 1.14e-3 released, the tip moving 3.8e-4 at
/// once). Held, each takes that force up; one that then needs more than kinetic friction slides
/// on as the slip's driver (module `drag`).
fn hold_riders(
    set: &ContactSet,
    mut new_set: ContactSet,
    pe: &Pt,
    xf: f64,
) -> (ContactSet, Vec<(usize, f64)>) {
    let gone = (0..new_set.contacts.len())
        .find(|&k| set.contacts[k] != new_set.contacts[k])
        .unwrap_or(new_set.contacts.len());
    let mut riders = Vec::new();
    for k in 0..new_set.contacts.len() {
        let Mode::Sliding(r) = new_set.contacts[k].mode else {
            continue;
        };
        if !crate::events::is_slider(&new_set.contacts[k]) {
            continue;
        }
        // (its number in the old set, whose unknowns `pe` carries)
        let ko = if k < gone { k } else { k + 1 };
        new_set.contacts[k].mode = crate::events::held(set, ko, pe, xf).contacts[ko].mode;
        riders.push((k, r));
    }
    (new_set, riders)
}

/// Whether the event `c`, located at `pe`, comes before the event found `f` (in a march whose
/// smallest natural step is `h_min`). Two events within `h_min` of each other of which one is
/// the other's shadow ([`shadows`]) are the one event.
fn earlier((c, pe): (Crossing, &Pt), f: &Found, h_min: f64) -> bool {
    if (pe.lam - f.pt.lam).abs() <= h_min {
        if shadows((f.cross, &f.pt), (c, pe)) {
            return false;
        }
        if shadows((c, pe), (f.cross, &f.pt)) {
            return true;
        }
    }
    pe.lam < f.pt.lam
}

/// Whether the event `b` (at `pb`) is the shadow of the event `a` (at `pa`) next to it: a
/// function that passes zero there only because `a` happens (issue 31's texture grid).
/// * A sliding contact's halt at its own lift-off: its normal force vanishes there, and with it
///   its friction and its slip rate, whose sign near `N = 0` is the solver's noise (0.001/0.02/0
///   on the rod tapered to 0.3: a creeping side halted at a root of that noise, `N = 7.4e-7`,
///   1.7e-8 in `d` before its lift-off, and held it needed `|T|/N` of 23 at once, so no
///   natural step followed it).
/// * A touchdown of the free end beyond a side that rolls to the tip: the free part vanishes
///   there, and its height above the surface with it (0.05/0.5/4π/3 on the uniform rod: the
///   side at s = 1 − 1.5e-12 and a tip touching down beside it, 1.8e-12 in the slide before
///   the peel-back, left a set whose contacts crossed at the first step).
fn shadows((a, pa): (Crossing, &Pt), (b, pb): (Crossing, &Pt)) -> bool {
    may_shadow(a, b)
        && match (a, b) {
            (Crossing::PeelBack(j), Crossing::Touchdown) => {
                pa.w.contacts.get(j).is_some_and(|c| pb.w.clear_s >= c.s)
            }
            _ => true,
        }
}

/// Whether the event `b` can be the shadow of `a` (the pairs of [`shadows`], at any points).
fn may_shadow(a: Crossing, b: Crossing) -> bool {
    match (a, b) {
        (Crossing::Lift(j), Crossing::Halt(k)) => j == k,
        (Crossing::PeelBack(_), Crossing::Touchdown) => true,
        _ => false,
    }
}

/// A state's first point `p` as the row of an event there: a contact's normal force below zero
/// by no more than [`AT_ZERO`] is zero, as any event function that close to zero right after a
/// change of set (the march's own test of a pull is `1e-10 (1 + ΣN)`). Issue 31's property seed
/// 25: a side touching down at N = 0 beside a slider at N = 4.9e-12 (both at the rounding of
/// the stuck side's 5.6) had N = −3.5e-13 at the first point after the slider's halt, which
/// was the row of the next halt there; released there instead, it left the free rod crossing
/// the surface at once, so it stays, at zero.
fn at_zero(p: Pt) -> Pt {
    zero_within(p, AT_ZERO)
}

/// As [`at_zero`], for the row of a halt at a state's first point: a normal force below zero
/// by no more than the noise of a contact just formed ([`NOISE`] of the total) is zero. The
/// property's seed 67 at 256 cases: a side touching down sliding beside a sliding side and the
/// stuck round tip (total N 3.86) halted at once, its N −2.2e-9 on the halt's row, the noise
/// of its touchdown (the drag goes on from there to d_max).
fn at_noise(p: Pt) -> Pt {
    let total: f64 = p.w.contacts.iter().map(|c| c.normal.abs()).sum();
    zero_within(p, NOISE * (1.0 + total))
}

/// `p` with each contact's normal force below zero by no more than `bound` set to zero (and
/// the total with it).
fn zero_within(mut p: Pt, bound: f64) -> Pt {
    for c in &mut p.w.contacts {
        if c.normal < 0.0 && -c.normal <= bound {
            p.w.normal -= c.normal;
            c.normal = 0.0;
        }
    }
    p
}

/// Ends the march with `stop` at the newest point of the history.
fn end(stop: StopReason) -> Flow {
    Flow::End(stop, None)
}

/// What the record and the march were before an event's outcome (a step taken again).
struct Before {
    mark: crate::record::Mark,
    range: RangeTracker,
    slide: Option<crate::surface::Slide>,
}

/// How many times one march may take the stretch reaching the tip ([`Run::reach_tip`]): a
/// bound on a tip that joins the stretch and touches down beyond it again in turn.
const REACHES: usize = 64;

/// How far past a failure's point the stretch reaching the tip is looked for: the first joined
/// states measured lay 7e-15 to 1.24e-5 past it ([`Run::reach_tip`]).
const REACH_SPAN: f64 = 1e-2;

/// The weight of the rate at the failure's point in the works across the gap to the first
/// joined state (the rest that state's; metered, and in the gap's balance that tells one path),
/// [`Run::reach_tip`]: the trapezoid. Measured on the
/// four gaps of 6.7e-6 to 1.24e-5 whose works are 2.7e-7 to 5e-7, where the rates at the ends
/// differ by up to 0.4 %: each slip balanced to 1.5e-11 to 1.9e-11 with it, to 1.1e-10 to
/// 3.4e-10 with the weights ⅔ and ⅓ that a rate `g* + c·√(λ* − λ)` (the free rod's own law
/// near `λ*`) would give; the gap's work itself is what a balance without it misses.
const REACH_WEIGHT: f64 = 0.5;

/// How far an event function of the joined state may be past zero where the stretch reaches
/// the tip: its place is solved to the corrector's tolerance.
const REACH_AT_ZERO: f64 = 1e-9;

/// How far the elastic energy released between a failure's point and the joined state may be
/// from the work of the contacts over that gap for the two to be one path
/// ([`Run::reach_tip`]): measured 2e-14 to 1.2e-12 on the six joins of the texture grid and the
/// one of its 4π/3 rat drag to d 0.06, against gaps' works up to 5.2e-6.
const REACH_JUMP: f64 = 1e-9;

/// A joined state that is not solved (before the stretch reaches the tip, [`Run::reach_tip`]).
#[derive(Clone, Copy, Debug)]
struct NoJoin;

/// A sliding contact's slip rate (per unit of the march's parameter) below which its sign is
/// taken for the solver's noise: the rates of such contacts measured 6e-12 to 3.9e-9 (at the
/// default tol 1e-10; see [`Run::dipped`]), a sliding contact that moves at 1e-7 of the foot's
/// speed being none.
const SLIP_NOISE: f64 = 1e-7;

/// Whether `c` is the halt of a sliding contact that lifts off within the step (its normal
/// force below zero at the step's `end`) and whose slip rate is within [`SLIP_NOISE`] at the
/// step's start `prev` and at `at` (the step's end, or an event found in it): the sign of such
/// a rate is the solver's noise, and no halt is located from it. (Not for a slider that stays:
/// one that halts for real, slowing through zero at a finite slope, has rates within the noise
/// at both ends of a short step next to its halt, and a halt left unlocated there ends before
/// the next step starts: the rod tapered to 0.3 over 0.001/0.5/2π/3, whose tip halts at d
/// 0.2633, then failed to locate it, "no sign change".)
///
/// Nor for the contact `quiet` ([`Walk::quiet`]), whose halt at its rate's noise was found to
/// hold it in a state that traps the rod, singular to working precision (a tip sliding beside
/// a side 0.0066 from it, the pair of tangential forces between them indeterminate): it slides
/// on at a rate of zero, `T = dir·μk N` determining the forces, where held they are not.
fn noise_halt(
    env: &Env,
    c: Crossing,
    (prev, at, end): (&Pt, &Pt, &Pt),
    quiet: Option<usize>,
) -> bool {
    let Crossing::Halt(j) = c else {
        return false;
    };
    let lifts = ended(Crossing::Lift(j).of_watch(env, &end.w));
    (lifts || quiet == Some(j)) && slip_noise(at, j) && slip_noise(prev, j)
}

/// Whether the slip rate of the contact `j` at `p` is within [`SLIP_NOISE`].
fn slip_noise(p: &Pt, j: usize) -> bool {
    p.w.contacts
        .get(j)
        .is_some_and(|c| c.slide.slip.abs() <= SLIP_NOISE)
}

/// A located event inside a step.
struct Found {
    cross: Crossing,
    pt: Pt,
}

impl<P: Profile> Run<'_, '_, P> {
    /// The march proper; returns why it stopped and the last point.
    fn run(&mut self, p0: Pt, quiet: Option<usize>) -> (StopReason, Option<(ContactSet, Pt)>) {
        let spec = self.spec;
        let lam_end = spec.lam_end;
        let h_max = self.stepper.h_max().min(lam_end - p0.lam).max(1e-12);
        self.metered_to = self.env.ground.meter.map(|_| p0.clone());
        let pending = Crossing::all(&self.env, self.stepper.set())
            .into_iter()
            .filter(|c| !holds(c.of_watch(&self.env, &p0.w)))
            .collect();
        let mut w = Walk {
            h: self.ctl.h_init.min(h_max),
            h_max,
            h_min: self.ctl.h_min(lam_end),
            steps: 0,
            max_steps: self.ctl.max_steps(spec.grid.len()),
            stalled: 0,
            lam0: p0.lam,
            hist: vec![p0],
            pending,
            pprev: None,
            queue: VecDeque::new(),
            rate0: None,
            failed: None,
            quiet,
            chord: None,
        };
        loop {
            let flow = self.step(&mut w);
            if let Flow::End(stop, last) = self.ended(flow) {
                let newest = || (self.stepper.set().clone(), w.hist[w.hist.len() - 1].clone());
                return (stop, Some(last.map_or_else(newest, |b| *b)));
            }
        }
    }

    /// A drag's start that traps the rod between contacts whose pair of tangential forces is
    /// indeterminate (`set` at `p0`, pressed without friction, `T = 0`): the point-contact model
    /// leaves the pair's split open, and every split is the same rod (the foot's force the
    /// same). Dragged, the pair's forces change by thousands per unit `d` (a stiff pair: the
    /// uniform rod over 0.003/0.02 with a side 0.0097 before the tip, `dN/dd` −4575 at the tip),
    /// so a contact of the pair reaches its cone at once: the one with the least normal force
    /// first. It slides from the start with kinetic friction, `T = ±μk N`, the first way its
    /// slip rate's sign agrees with, and no longer traps the rod: the start, its split the one
    /// friction fixes, and the contact `Some(j)` that so slides. Its rate is zero within the
    /// noise (the pair holds it in place), so the way is the noise's: it slides on at a rate of
    /// zero, its halts at the noise not located until the contact set changes
    /// ([`Walk::quiet`]), as a slider's whose halt would trap the rod ([`noise_halt`]). (The
    /// other way at the same start halts at once and reverses, the rows after it the same.)
    /// `None` where no contact so slides, or not in a drag: the start stops by name.
    fn slides_at_start(&mut self, set: &ContactSet, p0: &Pt) -> Option<(Pt, Option<usize>)> {
        let mu_k = self.env.ground.mu_k.filter(|_| self.spec.friction)?;
        let mut held: Vec<usize> = (0..set.contacts.len())
            .filter(|&j| set.contacts[j].mode.no_slip())
            .collect();
        held.sort_by(|&a, &b| (p0.w.contacts[a].normal).total_cmp(&p0.w.contacts[b].normal));
        let untrapped = |st: &mut dyn Stepper, slid: &ContactSet, p: &Pt, _: usize| {
            !st.trapped_singular(slid, p.lam, &p.u)
        };
        for j in held {
            if let Some((_, p)) = self.slides_from_start(set, j, (p0.lam, &p0.u), mu_k, untrapped) {
                return Some((*p, Some(j)));
            }
        }
        // (the stepper back on the start's set, for its row: `None` either way)
        let _ = self.stepper.switch(set.clone(), p0.lam, p0.u.clone());
        None
    }

    /// A start whose trapped pair is indeterminate: its own grid row (frictionless, T = 0), and
    /// the end.
    fn indeterminate(&mut self, set: &ContactSet, p0: &Pt) -> StopReason {
        let at: Vec<String> = (0..set.contacts.len())
            .map(|j| format!("{:.6}", set.s_of(j, &p0.u)))
            .collect();
        let emitted = self.emit(std::slice::from_ref(p0), p0.lam);
        self.range.close(RangeEnd::Event);
        let d = p0.lam;
        let message = format!(
            "the start {} traps the rod between contacts at s = {} that hold without slip, \
             and its equilibrium is singular to working precision: the pair of tangential \
             forces between them is indeterminate; the point-contact model does not resolve \
             it",
            set.label(),
            at.join(" and ")
        );
        emitted
            .err()
            .unwrap_or(StopReason::ContactChange { d, message })
    }

    /// One step: the next point, its acceptance, the events inside it and what they change.
    fn step(&mut self, w: &mut Walk) -> Flow {
        let prev = w.hist[w.hist.len() - 1].clone();
        let lam = prev.lam;
        if lam >= self.spec.lam_end {
            self.range.close(RangeEnd::DMax);
            if let Err(fail) = self.emit(&w.hist, self.spec.lam_end) {
                return end(fail);
            }
            return end(StopReason::DMax);
        }
        if self.stepper.cancelled() {
            self.range.close(RangeEnd::SolverFailure);
            if let Err(fail) = self.emit(&w.hist, lam) {
                return end(fail);
            }
            return end(StopReason::Cancelled { d: lam });
        }
        w.steps += 1;
        if w.steps > w.max_steps {
            self.range.close(RangeEnd::SolverFailure);
            let message = format!(
                "the march needed more than {} steps ({} per output point and {} more)",
                w.max_steps, self.ctl.steps_per_point, self.ctl.extra_steps
            );
            return end(StopReason::SolverFailure { d: lam, message });
        }
        let armed: Vec<Crossing> = Crossing::all(&self.env, self.stepper.set())
            .into_iter()
            .filter(|c| !w.pending.contains(c))
            .collect();
        let (p, from_queue) = match self.advance(w, &prev, &armed) {
            Ok(next) => next,
            Err(flow) => return flow,
        };
        match self.check_pending(w, &p, lam, from_queue) {
            Some(Pending::Stop(stop)) => return end(stop),
            Some(Pending::Shorter) => return Flow::Go,
            // a sliding contact that reverses from the state's first point halts there: the
            // event at the start, as a step's (its held state then decides on)
            Some(Pending::AtStart(Crossing::Halt(j))) => {
                let prev = at_noise(prev);
                let (set, u) = (self.stepper.set().clone(), prev.u.clone());
                let next = self.reversed(&set, j, &prev);
                let flow = self.switch(w, (Event::Halt, set, prev), next, u);
                return self.ended(flow);
            }
            Some(Pending::AtStart(c)) => {
                let prev = at_zero(prev);
                let mark = self.out.mark();
                let flow = self.on_event(w, c, prev.clone());
                // a side lying along the surface from the state's first point, or two contacts
                // closed up at the change lying down as one stretch there, whose stretch does not
                // hold: the stop is the lie's, or the closing's, the solver's words added (as for
                // a stretch whose march fails after it, `Lain`), without the lie's row (its state
                // is the one that did not go on)
                let Flow::Unheld(StopReason::ContactChange { d, message }, last) = flow else {
                    return self.ended(flow);
                };
                let said = match c {
                    Crossing::Lie(j) => {
                        let why = format!("the stretch it forms is not resolved ({message})");
                        crate::events::curve_lie(&last.0, j, &prev, &why)
                    }
                    Crossing::Close(j, k) => {
                        let why = format!("{} ({message})", crate::events::MERGED_UNRESOLVED);
                        crate::events::closed_up(&last.0, (j, k), &prev, &why)
                    }
                    _ => {
                        return self
                            .ended(Flow::Unheld(StopReason::ContactChange { d, message }, last))
                    }
                };
                self.out.rewind(mark);
                self.range.close(RangeEnd::Event);
                return Flow::End(
                    StopReason::ContactChange {
                        d: lam,
                        message: said,
                    },
                    Some(last),
                );
            }
            None => {}
        }
        if let Some(stop) = self.check_stall(w, &p, lam, from_queue) {
            return end(stop);
        }
        // a point a rounding away from the newest (a step that ended a rounding short of a
        // grid value, then the grid value) replaces it: the interpolant through two such
        // points is degenerate
        if w.hist
            .last()
            .is_some_and(|q| (p.lam - q.lam).abs() <= 1e-13 * (1.0 + q.lam.abs()))
        {
            w.hist.pop();
        }
        w.hist.push(p.clone());
        if w.hist.len() > 4 {
            w.hist.remove(0);
        }
        self.after_step(w, &prev, p, &armed)
    }

    /// The next point: from the queue of a fold passage, else a natural step (`Err(Go)`: rejected,
    /// the step shortened; `Err(End)`: the march ends). With it whether it came from the queue.
    fn advance(&mut self, w: &mut Walk, prev: &Pt, armed: &[Crossing]) -> Result<(Pt, bool), Flow> {
        if let Some(q) = w.queue.pop_front() {
            return Ok((q, true));
        }
        let lam = prev.lam;
        // the first step from the start predicts a change of at most a quarter of the state's
        // size (1 + its largest component): a start near a bifurcation has a steep branch, and
        // Newton from a longer linear prediction lands on whichever branch is nearest (a higher
        // Euler mode)
        if let (true, Some(du)) = (w.hist.len() == 1 && lam == w.lam0, &prev.du) {
            let rate = du.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let size = 1.0 + prev.u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            if rate * w.h > self.ctl.first_change * size {
                w.h = (self.ctl.first_change * size / rate).max(w.h_min);
            }
        }
        if self.forecasts_touchdown(armed) && w.hist.len() == 1 {
            let p = &w.hist[0];
            if w.rate0.is_none_or(|(l, _)| l != p.lam) {
                w.rate0 = self.stepper.clear_rate(p).map(|r| (p.lam, r));
            }
        }
        let target = self.target(w, lam, armed);
        let corrected = self.stepper.correct(target, &w.hist, false);
        // a failed step where the only contact lets go ends the branch (see vanishing_normal)
        let vanish = match &corrected {
            Err(e) if e.shorter_may_help() => vanishing_normal(&w.hist),
            _ => None,
        };
        match (corrected, vanish) {
            (Ok(p), _) => {
                w.h = self.ctl.after(w.h, p.iters, w.h_max);
                Ok((p, false))
            }
            (Err(e), v) if e.shorter_may_help() && w.h > w.h_min => {
                if self.spec.pass_fold_ahead && v.is_none() && fold::ahead(&w.hist, target) {
                    // passed at once, not crawled to by shorter steps (see `fold::ahead`; where
                    // the only contact lets go the crawl ends in the lift-off as before)
                    return self.through_fold(w, (lam, target), e, armed);
                }
                w.h *= self.ctl.reject;
                Err(Flow::Go)
            }
            (Err(e), Some((ls, limit, wl))) if e.shorter_may_help() => {
                // the branch ends where a contact lets go: a lift-off, located by extrapolation
                // (no state beyond it brackets the root, and a pseudo-arclength crawl towards it
                // costs without end)
                self.range.see(&wl);
                self.range.close(RangeEnd::Event);
                let limit = Some(limit);
                Err(end(StopReason::LiftOff { d: ls, limit }))
            }
            (Err(e), _) => self.through_fold(w, (lam, target), e, armed),
        }
    }

    /// The next natural target: at most `h` ahead, never past the next grid point, and just past
    /// an event the predictor sees coming within the step (the event is then located on a short
    /// step, and the march pays no full step beyond it).
    fn target(&self, w: &Walk, lam: f64, armed: &[Crossing]) -> f64 {
        let lam_end = self.spec.lam_end;
        let mut target = (lam + w.h).min(lam_end);
        if let Some(&g) = self.spec.grid.get(self.out.gi) {
            if g > lam && g < target {
                target = g;
            }
        }
        if lam_end - target < self.ctl.snap_end * w.h {
            target = lam_end;
        }
        for &c in armed {
            let env = &self.env;
            if let Some(ds) = predicted_crossing(&*self.stepper, env, &w.hist, (lam, target), c) {
                // (not when it is as good as here: the step would not move)
                if ds - lam > w.h_min {
                    target = ds + self.ctl.past_event * (target - ds);
                }
            }
        }
        if let Some(ds) = self.touchdown_forecast(w, target, armed) {
            if ds - lam > w.h_min {
                target = ds + self.ctl.past_event * (target - ds);
            }
        }
        target
    }

    /// Whether a touchdown is forecast from the clearance's history: armed, on a curved surface
    /// (at a state's first point only on the rod's own shooter, the only stepper with a
    /// [`Stepper::clear_rate`]).
    fn forecasts_touchdown(&self, armed: &[Crossing]) -> bool {
        self.env.ground.curve.is_some() && armed.contains(&Crossing::Touchdown)
    }

    /// Where the free parts' clearance `g`, extrapolated linearly from the newest point, reaches
    /// the surface before `target` (`None` where it does not, or no rate is known). The rate is
    /// the secant through the two newest points, or at a state's first point the stepper's
    /// [`Stepper::clear_rate`].
    ///
    /// Why: the clearance is not a function of the unknowns, so the branch polynomial cannot
    /// forecast it, and over a curve a free part can reach the surface and the branch without it
    /// fold back within one step. A drag over 0.003/0.2/2π/3 (taper 0.3) lay down at
    /// d = 0.0905768 with a free part 6.3e-6 above the surface; with `--points 11` the next step,
    /// to 0.1, ended on another branch of the same contact set (its free parts 2.2e-3 clear),
    /// past a touchdown at 0.0908549 and the fold at 0.0911078 of the set without it, where the
    /// default 201 points found the touchdown. Stepping to just past the forecast meets the
    /// touchdown; a forecast that comes early costs a step.
    fn touchdown_forecast(&self, w: &Walk, target: f64, armed: &[Crossing]) -> Option<f64> {
        if !self.forecasts_touchdown(armed) {
            return None;
        }
        let q = w.hist.last()?;
        let g = q.w.clear;
        if g.is_nan() || g >= 0.0 || q.w.light {
            return None;
        }
        let rate = match w.hist.len() {
            1 => w.rate0.filter(|&(l, _)| l == q.lam)?.1,
            n => {
                let p = &w.hist[n - 2];
                if p.w.light {
                    return None;
                }
                (g - p.w.clear) / (q.lam - p.lam)
            }
        };
        if rate.is_nan() || rate <= 0.0 {
            return None;
        }
        let at = q.lam - g / rate;
        (at.is_finite() && at < target).then_some(at)
    }

    /// The fold passage after the natural step to `target` failed with `e`: its first point (the
    /// rest queued, up to the first where an `armed` event has ended), or the fold (the end), or
    /// the end with the failure.
    fn through_fold(
        &mut self,
        w: &mut Walk,
        (lam, target): (f64, f64),
        e: StepError,
        armed: &[Crossing],
    ) -> Result<(Pt, bool), Flow> {
        let lam_end = self.spec.lam_end;
        let env = &self.env;
        let done = |q: &Pt| armed.iter().any(|c| ended(c.of_watch(env, &q.w)));
        match fold::pass(&mut *self.stepper, &w.hist, (target, lam_end), &done) {
            Passed::Beyond(ps, chord) => {
                w.chord = Some(chord);
                // every point of the path, each taken as a step: a branch too steep for natural
                // steps (near a bifurcation) is not a polynomial in λ between far points, and
                // events inside it are found on it
                let mut ps = ps.into_iter();
                let Some(first) = ps.next() else {
                    self.range.close(RangeEnd::SolverFailure);
                    let message = format!(
                        "natural step to {target}: {e}; pseudo-arclength passed it without a \
                         point"
                    );
                    return Err(end(StopReason::SolverFailure { d: lam, message }));
                };
                w.queue.extend(ps);
                Ok((first, false))
            }
            Passed::Fold(lf, pt) => {
                // (where the free rod between a lying stretch and the tip beyond it vanishes:
                // the stretch reaches the tip, and the march goes on from the joined state)
                let set = self.stepper.set().clone();
                if let Some(q) = pt.as_deref().and_then(|p| self.reach_tip(&set, p)) {
                    let joined = self.stepper.set().clone();
                    self.go_on(w, &joined, q);
                    return Err(Flow::Go);
                }
                // the fold's own point belongs to the measurable range it ends
                if let Some(p) = &pt {
                    self.range.see(&p.w);
                }
                self.range.close(RangeEnd::Event);
                if let Err(fail) = self.emit(&w.hist, lf.min(lam_end)) {
                    return Err(end(fail));
                }
                let stop = StopReason::FoldInD { d: lf };
                let Some(p) = pt else {
                    return Err(end(stop));
                };
                let set = self.stepper.set().clone();
                if let Some(stop) = pulling(&set, &p, lf) {
                    return Err(end(stop));
                }
                self.out.push(&set, &p, Some(Event::FoldInD));
                Err(Flow::End(stop, Some(Box::new((set, *p)))))
            }
            Passed::Failed(msg) => {
                self.range.close(RangeEnd::SolverFailure);
                let message = format!("natural step to {target}: {e}; {msg}");
                Err(end(StopReason::SolverFailure { d: lam, message }))
            }
        }
    }

    /// A change of contact set holds only if its new event functions leave zero inwards: the end
    /// where one leaves it outwards at the new point `p`.
    fn check_pending(
        &mut self,
        w: &mut Walk,
        p: &Pt,
        lam: f64,
        from_queue: bool,
    ) -> Option<Pending> {
        if self.formed_too_long(w, p, lam) {
            w.h = self.ctl.reject * (p.lam - lam);
            w.queue.clear();
            return Some(Pending::Shorter);
        }
        let env = &self.env;
        // the free rod's height is its highest point: one that crossed the surface elsewhere
        // inside the step (a touchdown of its own, issue 31: at s = 0.946 while the side released
        // at s = 0.986 rose) hides whether the point at zero after the change left it inwards;
        // the step again, shorter, tells them apart (in the foot's march; in a slip it stays the
        // jam it was)
        let crossed = |c: &Crossing| *c == Crossing::Touchdown && c.of_watch(env, &p.w) > 0.0;
        let stick = env.ground.slide.is_none();
        if stick && !from_queue && w.h > w.h_min && w.pending.iter().any(crossed) {
            // (shorter than the last try too: a fold passage's point comes back whatever the step)
            w.h = self.ctl.reject * w.h.min(p.lam - lam);
            w.queue.clear();
            return Some(Pending::Shorter);
        }
        let mut wrong = None;
        w.pending.retain(|&c| {
            let v = c.of_watch(env, &p.w);
            if v > 0.0 {
                wrong.get_or_insert((c, v));
            }
            !holds(v)
        });
        let (c, v) = wrong?;
        if matches!(c, Crossing::Halt(_)) && w.hist.len() == 1 {
            w.pending.clear();
            return Some(Pending::AtStart(c));
        }
        // a slip's driver that kinetic friction holds from the first point of a state inside
        // the slip (another contact broke free there, taking up the load): its slide ends there,
        // and the other drives on. (At the slip's own first point, `λ = 0`, it stays a jam: the
        // driver, at μs there, held at once by μk has no quasi-static slide; ended there as
        // well, 15 of the texture grid's jams became 11 failures to follow a slide of no
        // length, 3 trapped halts and a state that does not hold.)
        let driver = env.ground.slide.map(|s| s.driver);
        let inside = lam > 0.0 && w.hist.len() == 1;
        if matches!(c, Crossing::Stick(j) if Some(j) == driver) && inside {
            w.pending.clear();
            return Some(Pending::AtStart(c));
        }
        // a side that lies along the surface from the state's first point (the tip lay down
        // where the surface curves more than the rod's end): it lies down there, where the model
        // has the stretch
        if let Crossing::Lie(j) = c {
            let set = self.stepper.set();
            if w.hist.len() == 1 && crate::events::lie_kept_out(set, j).is_none() {
                w.pending.clear();
                return Some(Pending::AtStart(c));
            }
        }
        if let Crossing::Close(j, k) = c {
            if crate::events::merges(env, self.stepper.set(), (j, k)) {
                // (closed up at the change of set: the two lie down as one stretch there)
                w.pending.clear();
                return Some(Pending::AtStart(c));
            }
        }
        self.range.close(RangeEnd::Event);
        if let (Crossing::Close(j, k), Some(q)) = (c, w.hist.last()) {
            // a change of set made with a sliding side already closed up to its neighbour: the
            // closing's stop, not a state that does not hold (a jam in a slip)
            let set = self.stepper.set();
            let why = crate::events::not_merged(set, (j, k));
            let message = crate::events::closed_up(set, (j, k), q, why);
            return Some(Pending::Stop(StopReason::ContactChange { d: lam, message }));
        }
        if env.ground.slide.is_some() {
            // in a slip (the foot held) the impasse is friction's: the slip cannot go on
            // quasi-statically
            return Some(Pending::Stop(StopReason::Jam {
                d: lam,
                message: format!(
                    "the slip cannot go on quasi-statically: the contact state {} does not hold \
                     beyond {lam:.6e} of the slip ({} = {v:.3e}), and the state before it ended \
                     there: no contact state consistent with Coulomb friction continues it (the \
                     slip turns dynamic)",
                    self.stepper.set().label(),
                    c.describe()
                ),
            }));
        }
        let set = self.stepper.set();
        if let Crossing::Lie(j) = c {
            if let (Some(q), Geom::Curve { .. }) = (w.hist.last(), &set.contacts[j].geom) {
                // a side that lies along the surface from the state's first point (the tip
                // lay down where the surface curves more than the rod's end, issue 31): the
                // stop is the lie's, with its reason
                let why = crate::events::lie_kept_out(set, j);
                let why = why.unwrap_or("a stretch lying from a contact state's first point");
                let message = crate::events::curve_lie(set, j, q, why);
                return Some(Pending::Stop(StopReason::ContactChange { d: lam, message }));
            }
        }
        Some(Pending::Stop(StopReason::ContactChange {
            d: lam,
            message: format!(
                "the contact state {} does not hold beyond d = {lam}: {} = {v:.3e} after the change, and the state before it ended there: the model has no contact state that continues",
                self.stepper.set().label(),
                c.describe()
            ),
        }))
    }

    /// Whether the first step `p` after a change of contact set is too long for a contact that has
    /// just formed: its slip limit, pending (its `|T| − μs N` at the first point is the
    /// solver's noise, 1e-10, of either sign, as its forces start at zero), lies beyond at `p`,
    /// though on the new state's tangent its tangential force grows slower than `μs` times its
    /// normal force (it holds as it forms), so it reaches its limit inside the step (issue 31:
    /// a side touching down beside the tip needs 0.497 of its normal force at first and 0.53
    /// at the step's end; the drag stopped there, "the model has no contact state").
    fn formed_too_long(&mut self, w: &Walk, p: &Pt, lam: f64) -> bool {
        let [p0] = &w.hist[..] else {
            return false;
        };
        if p.lam - lam <= w.h_min {
            return false;
        }
        let env = &self.env;
        let forming = |c: &Crossing| match *c {
            Crossing::Slip(j) => {
                let total: f64 = p0.w.contacts.iter().map(|k| k.normal.abs()).sum();
                p0.w.contacts
                    .get(j)
                    .is_some_and(|k| k.normal.abs() <= NOISE * (1.0 + total))
                    && c.of_watch(env, &p.w) > 0.0
            }
            _ => false,
        };
        let Some(Crossing::Slip(j)) = w.pending.iter().find(|c| forming(c)).copied() else {
            return false;
        };
        let set = self.stepper.set().clone();
        let Some(du) = self.stepper.tangent_in(&set, lam, &p0.u) else {
            return false;
        };
        let o = set.offset(j);
        let (dn, dt) = (du[o], du[o + 1]);
        dn > 0.0 && dt.abs() < p.w.contacts[j].mu_s * dn
    }

    /// The state after the sliding contact `j` of `set` reverses from the first point `p`: it
    /// holds where it is, unless holding it leaves the march no way on (the held state's tangent
    /// singular or beyond `HOLD_MAX`, as for a side trapped a short stretch behind a sliding
    /// tip, which must move with it): then it slides the other way.
    fn reversed(&mut self, set: &ContactSet, j: usize, p: &Pt) -> ContactSet {
        let xf = self.stepper.foot(p.lam).0;
        let hold = crate::events::held(set, j, p, xf);
        let way_on = (self.stepper.tangent_in(&hold, p.lam, &p.u))
            .is_some_and(|t| t.iter().all(|v| v.abs() < HOLD_MAX));
        if way_on {
            return hold;
        }
        let mut back = set.clone();
        if let Mode::Sliding(r) = back.contacts[j].mode {
            back.contacts[j].mode = Mode::Sliding(-r);
        }
        back
    }

    /// The end at the event point `pe` of `set` where no contact state continues (`message`
    /// why): in a slip a jam, the slip turning dynamic; else a contact change.
    fn impasse(&mut self, message: String, set: ContactSet, pe: Pt) -> Flow {
        self.range.close(RangeEnd::Event);
        let d = pe.lam;
        let stop = match self.env.ground.slide {
            Some(_) => StopReason::Jam { d, message },
            None => StopReason::ContactChange { d, message },
        };
        Flow::End(stop, Some(Box::new((set, pe))))
    }

    /// Where a halt reverses a sliding contact at once (`set` at `pe` to `new_set` at `q`, its
    /// held state no way on: [`Run::reversed`]), how the jump between the two states changes the
    /// elastic energy, beyond [`GAIN`] `(1 + E)`. Its friction flips by `2 μk N` at once, so the
    /// rod jumps between two equilibria at the same foot and slide, and no contact's friction is
    /// metered over the jump. One that would gain energy is no state the rod reaches
    /// ([`Jump::Gains`]: the property's seed 31 at 64 cases, a side reversing 2.5e-7 into a slip
    /// gained 9.66e-8, and that slip's dissipation exceeded its released energy by as much). One
    /// that loses energy ([`Jump::Loses`]) has the held route tried instead
    /// ([`Run::held_instead`]). `None` for any other change, a jump within `GAIN`, and where the
    /// stepper has no energy.
    fn reversal_jumps(
        &mut self,
        ev: Event,
        (set, pe): (&ContactSet, &Pt),
        (new_set, q): (&ContactSet, &Pt),
    ) -> Option<Jump> {
        if ev != Event::Halt {
            return None;
        }
        let j = halted(set, new_set);
        let (Mode::Sliding(a), Mode::Sliding(b)) = (set.contacts[j].mode, new_set.contacts[j].mode)
        else {
            return None;
        };
        if a * b >= 0.0 {
            return None;
        }
        let before = self.stepper.energy(&pe.u, pe.lam)?;
        let after = self.stepper.energy(&q.u, q.lam)?;
        let gain = after - before;
        let by = GAIN * (1.0 + before.abs());
        if gain > by {
            let c = &pe.w.contacts[j];
            Some(Jump::Gains(Impasse::JumpGains {
                s: c.s,
                flip: 2.0 * c.tangential.abs(),
                gain,
            }))
        } else if -gain > by {
            Some(Jump::Loses(j))
        } else {
            None
        }
    }

    /// The held state of the contact `j` of `set` that halted at `pe` and its first point, where
    /// its tangent is within [`HOLD_FAR`]: taken instead of a reversal at once whose jump loses
    /// energy that no friction works off. Held, the contact's friction turns through its cone
    /// over the short slide that state allows, and it slips where it reaches its limit, each
    /// step metered (the property's seed 62 at 256 cases: a side 0.22 behind a tip that slips,
    /// reversed at once, jumped 5.2e-5 the way it slid before, against its new friction, and
    /// released 1.8e-8 unmetered). `back`: the reversed set and the old state in its unknowns,
    /// switched to again where the held state's switch fails. `Ok(Some)`: the held set and its
    /// first point, or, where the held state's switch failed, the reversed set switched to
    /// again; `Ok(None)`: the reversal stays as it was (no `back`, or the held state's tangent
    /// beyond `HOLD_FAR`); `Err`: the held state's switch and the second one both failed.
    fn held_instead(
        &mut self,
        set: &ContactSet,
        j: usize,
        pe: &Pt,
        back: Option<(ContactSet, Vec<f64>)>,
    ) -> Result<Option<(ContactSet, Pt)>, Impasse> {
        let Some((reversed, u)) = back else {
            return Ok(None);
        };
        let xf = self.stepper.foot(pe.lam).0;
        let hold = crate::events::held(set, j, pe, xf);
        let far = (self.stepper.tangent_in(&hold, pe.lam, &pe.u))
            .is_none_or(|t| !t.iter().all(|v| v.abs() < HOLD_FAR));
        if far {
            return Ok(None);
        }
        if let Ok(q) = self.stepper.switch(hold.clone(), pe.lam, u.clone()) {
            return Ok(Some((hold, q)));
        }
        match self.stepper.switch(reversed.clone(), pe.lam, u) {
            Ok(q) => Ok(Some((reversed, q))),
            Err(why) => Err(Impasse::NeitherSolves {
                s: set.s_of(j, &pe.u),
                why,
            }),
        }
    }

    /// The end after too many steps in a row without progress in `λ`.
    fn check_stall(
        &mut self,
        w: &mut Walk,
        p: &Pt,
        lam: f64,
        from_queue: bool,
    ) -> Option<StopReason> {
        if !from_queue && p.lam - lam <= 1e-12 * (1.0 + lam.abs()) {
            w.stalled += 1;
            if w.stalled > self.ctl.max_stalled {
                self.range.close(RangeEnd::SolverFailure);
                return Some(StopReason::SolverFailure {
                    d: lam,
                    message: format!(
                        "the march stalled: {} steps without progress",
                        self.ctl.max_stalled
                    ),
                });
            }
        } else {
            w.stalled = 0;
        }
        None
    }

    /// After an accepted step from `prev` to `p`: the events inside it, the metered work, the
    /// first maximum of `|μ|`, the output points up to the step's end, and the earliest event's
    /// outcome.
    fn after_step(&mut self, w: &mut Walk, prev: &Pt, p: Pt, armed: &[Crossing]) -> Flow {
        let lam = prev.lam;
        let (mut found, mut failure) = self.events_in(w, prev, &p, armed);
        if let Some(f) = self.dipped(w, (prev, &p), armed, &mut found) {
            failure = Some(f);
        }
        if let (None, Some(f)) = (&found, failure) {
            // a sliding contact's halt whose rate is within the noise at both ends of the step,
            // where no sign change is found: the step again, as long, the contact sliding on at
            // a rate of zero (its halts at the noise not located until the set changes)
            let noise = armed.iter().find_map(|&c| match c {
                Crossing::Halt(j)
                    if w.quiet != Some(j)
                        && ended(c.of_watch(&self.env, &p.w))
                        && slip_noise(prev, j)
                        && slip_noise(&p, j) =>
                {
                    Some(j)
                }
                _ => None,
            });
            if let Some(j) = noise {
                w.quiet = Some(j);
                w.hist.pop();
                w.queue.clear();
                w.h = p.lam - lam;
                return Flow::Go;
            }
            // a step too long for the event's scale (a light touch changes fast): the step
            // again, shorter, before giving up — unless this very step failed before: a
            // shorter natural step that fails hands over to the fold passage, whose first
            // point does not depend on the step (a short rat preset's drag over 0.001/0.2/2π/3
            // took the same step from the fold passage 100 000 times, locating a slip beside
            // a fold each time, until the step budget ended it after 67 s)
            let again = w.failed == Some((lam, p.lam));
            if p.lam - lam > w.h_min && !again {
                w.failed = Some((lam, p.lam));
                w.hist.pop();
                w.queue.clear();
                w.h = self.ctl.reject * (p.lam - lam);
                return Flow::Go;
            }
            self.range.close(RangeEnd::SolverFailure);
            return end(f);
        }
        let l_stop = found.as_ref().map_or(p.lam, |f| f.pt.lam);
        let before = found.as_ref().map(|_| Before {
            mark: self.out.mark(),
            range: *self.range,
            slide: self.env.ground.slide,
        });
        let env = &self.env;
        if let Some(m) = env.ground.meter {
            let upto = found.as_ref().map_or(&p, |f| &f.pt).clone();
            let st = &mut *self.stepper;
            let done = meter_between(st, env, m, &w.hist, (prev, &upto), 0);
            self.out.metered[0] += done[0];
            self.out.metered[1] += done[1];
            self.metered_to = Some(upto);
        }
        if self.range.end.is_none() {
            let ws = (&prev.w, w.pprev.as_ref());
            if let Some(m) = first_max(&mut *self.stepper, env, &w.hist, ws, &p.w, l_stop) {
                self.range.see(&m);
                self.range.close(RangeEnd::FirstMaximum);
            }
        }
        match &found {
            Some(f) => self.range.see(&f.pt.w),
            None => self.range.see(&p.w),
        }
        if let Err(fail) = self.emit(&w.hist, l_stop) {
            return end(fail);
        }
        let Some(Found { cross, pt }) = found else {
            w.pprev = Some(prev.w.clone());
            return Flow::Go;
        };
        let lain = self.lain.take();
        let p_lam = p.lam;
        match self.on_event(w, cross, pt) {
            Flow::Unheld(stop, last) => {
                // a new contact state that does not hold at an event located at the start of
                // a long step may be a root of the noise: the step again, shorter, once
                let again = w.failed == Some((lam, p_lam));
                let long = p_lam - lam > w.h_min && !again;
                if let Some(b) = before.filter(|b| long && self.env.ground.slide == b.slide) {
                    let h = self.ctl.reject * (p_lam - lam);
                    if self.take_again(w, b, (last.0.clone(), prev), lain, h) {
                        w.failed = Some((lam, p_lam));
                        return Flow::Go;
                    }
                }
                self.ended(Flow::Unheld(stop, last))
            }
            Flow::Quiet(j, stop, last) => {
                // a halt at the rate's noise into a trapped, singular state: the step again,
                // as long, with that contact's noise halts not located (it slides on at zero)
                let noise = slip_noise(prev, j);
                if let Some(b) = before.filter(|b| noise && self.env.ground.slide == b.slide) {
                    if self.take_again(w, b, (last.0.clone(), prev), lain, p_lam - lam) {
                        w.quiet = Some(j);
                        return Flow::Go;
                    }
                }
                Flow::End(stop, Some(last))
            }
            flow => flow,
        }
    }

    /// The march's failure or fold at `p` of `set` taken as the stretch reaching the tip: the
    /// first point of the set where the tip has joined the stretch
    /// ([`crate::events::tip_into_stretch`]), its row recorded as [`Event::ReachTip`]; `None`
    /// where the tip does not press just beyond a lying stretch at `p`
    /// ([`crate::events::stretch_at_tip`]), no joined state follows within [`REACH_SPAN`] of
    /// `p`, it does not hold, it is not one path with `p` ([`REACH_JUMP`]), or the march has
    /// taken [`REACHES`] joins already.
    ///
    /// Where the free rod between the stretch's outer end and the tip vanishes (`ℓ → 0`), the
    /// state is singular (the two forces come to act at one point, only their sum determined),
    /// and the solver fails a little before (or its fold passage takes the noise there for a
    /// fold). The joined state's outer end (where the rod's moment is zero, the rest beyond
    /// unloaded) lies past the tip before the place `λ*` where the stretch reaches the tip and
    /// inside the rod after it; near the tip it is not solved either (Newton stalls at residuals
    /// of 2e-12 to 2e-11 against 1e-12). The joined state taken is the first one solved past
    /// `p`, bracketed outwards from `p` and bisected down to it; where the joined states solve
    /// on both sides of `λ*`, `λ*` itself, by Brent's method. With a meter, the works from its
    /// last metered point to `p` are metered on the old set, and across the gap taken from the
    /// rates at its ends ([`REACH_WEIGHT`]).
    ///
    /// Measured on the short rat preset's drags over 0.003/0.2 (phases 0, 2π/3, 4π/3 twice, and
    /// 4π/3 to d 0.06): the old branch's last points left `ℓ` 8.4e-5 to 8.6e-4; the first joined
    /// states solved lay 7e-15 to 1.24e-5 further on, with 0 (Brent) to 1.1e-5 of free rod.
    /// Their outer ends move at a rate of 1.0 in the slide: taken back linearly to the tip they
    /// give `λ*`, and at the four gaps the old branch's `ℓ/√(λ* − λ)` is 0.333 at each: the two
    /// branches meet there, with no jump between them. (Phase 0's failure came within 8.4e-5
    /// of the tip, and the joined state solved at its `λ` with 1.8e-7 of free rod.)
    fn reach_tip(&mut self, set: &ContactSet, p: &Pt) -> Option<Pt> {
        if self.reaches >= REACHES || crate::events::stretch_at_tip(set, p).is_none() {
            return None;
        }
        self.reaches += 1;
        // (the points' watches with the works' integrands, for the jump's balance)
        let unmetered = self.env.ground.meter.is_none();
        if unmetered {
            self.stepper.set_meter(Some(Meter::Slide));
        }
        let q = self.join_tip(set, p);
        if unmetered {
            self.stepper.set_meter(None);
        }
        if q.is_none() {
            // (the stepper back on the old set, for the stop there)
            let _ = self.stepper.switch(set.clone(), p.lam, p.u.clone());
        }
        q
    }

    /// [`Run::reach_tip`], the stepper left where the search left it where it is `None`.
    fn join_tip(&mut self, set: &ContactSet, p: &Pt) -> Option<Pt> {
        let (ns, nu) = crate::events::tip_into_stretch(&self.env, set, p)?;
        let jl = set.lain()?;
        let s2 = |q: &Pt| q.w.contacts.get(jl).map_or(f64::NAN, |c| c.lies_to);
        let free = 1.0 - s2(p);
        // (`p` again, its watch with the works' integrands)
        let p = &self.stepper.switch(set.clone(), p.lam, p.u.clone()).ok()?;
        let e_old = self.stepper.energy(&p.u, p.lam)?;
        // the works up to the failure's point, on its set
        let tail = match (self.env.ground.meter, self.metered_to.clone()) {
            (Some(m), Some(a)) if a.lam < p.lam => {
                let hist = [a.clone(), p.clone()];
                meter_between(&mut *self.stepper, &self.env, m, &hist, (&a, p), 0)
            }
            _ => [0.0, 0.0],
        };
        // `Ok(s2 − 1)` of the joined state at `λ`, `Err` where it is not solved (before `λ*`)
        let joined = |st: &mut dyn Stepper, lam: f64, u: &[f64]| {
            st.switch(ns.clone(), lam, u.to_vec())
                .ok()
                .filter(|q| s2(q).is_finite())
        };
        let st = &mut *self.stepper;
        let (mut lo, mut lo_solved, mut hi) = (p.lam, false, None);
        let mut dl = (free * free).max(1e-12);
        while dl <= REACH_SPAN {
            match joined(st, p.lam + dl, &nu) {
                Some(q) if s2(&q) < 1.0 => {
                    hi = Some(q);
                    break;
                }
                q => (lo, lo_solved) = (p.lam + dl, q.is_some()),
            }
            dl *= 2.0;
        }
        let mut hi = hi?;
        let tol = 1e-14 * (1.0 + p.lam.abs());
        while !lo_solved && hi.lam - lo > tol {
            let mid = 0.5 * (lo + hi.lam);
            let u = hi.u.clone();
            match joined(st, mid, &u) {
                Some(q) if s2(&q) < 1.0 => hi = q,
                q => (lo, lo_solved) = (mid, q.is_some()),
            }
        }
        if lo_solved {
            let u = hi.u.clone();
            let mut f = |lam: f64| joined(st, lam, &u).map(|q| s2(&q) - 1.0).ok_or(NoJoin);
            if let Ok(lam) = search::root(&mut f, lo, hi.lam, tol) {
                hi = joined(st, lam, &u)?;
            }
        }
        let q = joined(st, hi.lam, &hi.u.clone())?;
        // (every condition of the joined state holds there, its outer end at the tip within
        // rounding, and it leaves no more free rod than the failure's point: the state the
        // old one went over to, not another)
        let env = &self.env;
        let held = Crossing::all(env, &ns).into_iter().all(|c| {
            let v = c.of_watch(env, &q.w);
            holds(v) || v.abs() <= REACH_AT_ZERO
        });
        if !held || 1.0 - s2(&q) > free {
            return None;
        }
        // (and reached from `p` without a jump: the elastic energy the gap releases is the work
        // its sliding contacts absorb, less the foot's, to `REACH_JUMP`; else the old branch's
        // end is a snap)
        let h = q.lam - p.lam;
        let (fa, fb) = (st.foot(p.lam), st.foot(q.lam));
        // (the mean over the gap of the rate `i` that the meter `m` integrates)
        let mean = |m, i: usize| {
            let ra = crate::record::rates(m, env, set, p, fa.0)[i];
            let rb = crate::record::rates(m, env, &ns, &q, fb.0)[i];
            REACH_WEIGHT * ra + (1.0 - REACH_WEIGHT) * rb
        };
        let foot = mean(Meter::Foot, 0) * (fb.0 - fa.0) + mean(Meter::Turn, 0) * (fb.1 - fa.1);
        let jump = e_old - st.energy(&q.u, q.lam)? + foot - mean(Meter::Slide, 1) * h;
        if !jump.is_finite() || jump.abs() > REACH_JUMP {
            return None;
        }
        if let Some(m) = env.ground.meter {
            for (i, (done, t)) in self.out.metered.iter_mut().zip(tail).enumerate() {
                *done += t + h * mean(m, i);
            }
            self.metered_to = Some(q.clone());
        }
        self.out.push(&ns, &q, Some(Event::ReachTip));
        Some(q)
    }

    /// The step from `prev` taken again, `h` long, where an event inside it led to a state that
    /// is not taken: the stepper back on the old set `old` at the step's start, the record, the
    /// range and the fallback lie (`lain`) as they were before the event, the step's end
    /// dropped. `false` (nothing restored) where the stepper cannot go back.
    fn take_again(
        &mut self,
        w: &mut Walk,
        b: Before,
        (old, prev): (ContactSet, &Pt),
        lain: Option<Box<Lain>>,
        h: f64,
    ) -> bool {
        if self.stepper.switch(old, prev.lam, prev.u.clone()).is_err() {
            return false;
        }
        self.out.rewind(b.mark);
        *self.range = b.range;
        self.lain = lain;
        if self.env.ground.meter.is_some() {
            self.metered_to = Some(prev.clone());
        }
        w.hist.pop();
        w.queue.clear();
        w.h = h;
        true
    }

    /// `flow` with [`Flow::Unheld`] and [`Flow::Quiet`] made the end they are where they are not
    /// taken again.
    fn ended(&mut self, flow: Flow) -> Flow {
        match flow {
            Flow::Unheld(stop, last) => {
                self.range.close(RangeEnd::SolverFailure);
                Flow::End(stop, Some(last))
            }
            Flow::Quiet(_, stop, last) => Flow::End(stop, Some(last)),
            flow => flow,
        }
    }

    /// The armed events that ended between `prev` and the new point `p`, located: the earliest,
    /// and the first failure to locate one. They are located in the order of their secant
    /// estimates (the straight line through their values at the step's ends): an event that
    /// still holds at an earlier one's point is not located, so the likely first goes first
    /// (a texture drag's side and tip both reached their slip limits in nearly every step that
    /// ended in a slip, the side's listed first and later: three searches a slip instead of two).
    fn events_in(
        &mut self,
        w: &Walk,
        prev: &Pt,
        p: &Pt,
        armed: &[Crossing],
    ) -> (Option<Found>, Option<StopReason>) {
        let env = &self.env;
        let lam = prev.lam;
        let mut found: Option<Found> = None;
        let mut failure: Option<StopReason> = None;
        // (where the highest free point jumped, the step's only outcome a failure: see `born`)
        let mut jumped: Option<f64> = None;
        let mut ended_now: Vec<(f64, Crossing)> = armed
            .iter()
            .filter(|&&c| {
                ended(c.of_watch(env, &p.w)) && !noise_halt(env, c, (prev, p, p), w.quiet)
            })
            .map(|&c| {
                let (g0, g1) = (c.of_watch(env, &prev.w), c.of_watch(env, &p.w));
                let at = g0 / (g0 - g1);
                (if at.is_finite() { at } else { 0.0 }, c)
            })
            .collect();
        // (stable: ties and estimates that are not numbers keep the armed order; so does a step
        // where one of the events may be the shadow of another, whose winner is decided by
        // `earlier` only if both are searched: a halt located before its contact's lift-off
        // left the lift-off unsearched, still holding there, and two texture drags of the rod
        // tapered to 0.3 stopped in a trapped halt where they had gone on to d_max)
        let pairs = ended_now.iter().any(|&(_, a)| {
            ended_now
                .iter()
                .any(|&(_, b)| may_shadow(a, b) || may_shadow(b, a))
        });
        if !pairs {
            ended_now.sort_by(|a, b| a.0.partial_cmp(&b.0).unwrap_or(std::cmp::Ordering::Equal));
        }
        for (_, c) in ended_now {
            // an event that still holds at an earlier event's point ends after it: not the step's
            // outcome, and not located
            if found
                .as_ref()
                .is_some_and(|f| !ended(c.of_watch(env, &f.pt.w)))
            {
                continue;
            }
            // (a step from the fold passage: where the search in λ fails, on its path's step)
            let on_path = w.chord.as_deref().filter(|ch| spans(ch, prev, p));
            let located = match (
                locate(&mut *self.stepper, env, &w.hist, (lam, p.lam), c),
                on_path,
            ) {
                (Err(_), Some(chord)) => fold::locate_on_chord(&mut *self.stepper, env, chord, c),
                (r, _) => r,
            };
            match located {
                Ok(pe) => {
                    let v = c.of_watch(env, &pe.w);
                    if c == Crossing::Touchdown && env.ground.curve.is_some() && v < -JUMP {
                        jumped.get_or_insert(pe.lam);
                        // not a root but a jump of the highest free point (one the clearance
                        // did not see before): no contact to insert there
                        failure.get_or_insert(StopReason::SolverFailure {
                            d: lam,
                            message: format!(
                                "{} jumps from {v:.3e} to {:.3e} at d = {}",
                                c.describe(),
                                c.of_watch(env, &p.w),
                                pe.lam
                            ),
                        });
                        continue;
                    }
                    if found.as_ref().is_none_or(|f| earlier((c, &pe), f, w.h_min)) {
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
        if let (None, Some(from)) = (&found, jumped) {
            // a highest free point born inside the step, the step's only outcome: see `born`
            let born = born(&mut *self.stepper, env, &w.hist, (from, p));
            found = born.map(|b| match b {
                Born::Below(pt) => Found {
                    cross: Crossing::Touchdown,
                    pt,
                },
                Born::BesideTip(pt) => Found {
                    cross: Crossing::TipTangent,
                    pt,
                },
            });
            if found.is_some() {
                failure = None;
            }
        }
        (found, failure)
    }

    /// The armed events beyond zero at the earliest located event's point (other than that
    /// event): they ended before it, though some hold again at the step's end or were located
    /// later (a root past it), as a free tip that dips below a corrugation and out again within
    /// one step of a slip (issue 31: the slip ended with the tip 1.6e-5 inside the surface, or a
    /// stuck tip 1.2e-3 beyond its slip limit), or a sliding tip that turns into the surface and
    /// back within the step (issue 31's own drag, A 0.005, W 0.05: its third slip ended with
    /// `sin(φ(1) − β)` at −5.0e-3, and no contact state continued the march in `d` from
    /// there; the tip lies down 3.0e-5 into that slip, and the side it becomes slides on, its
    /// place kept by `driver_anchor`). Each is located before the event found, and the
    /// earliest replaces it (`found`); a failure to locate one leaves no event found and is
    /// returned (the step is then taken again, shorter).
    ///
    /// Neither here nor among the step's ended events ([`Run::events_in`]) is a halt located
    /// of a sliding contact that lifts off within the step and whose slip rate is within
    /// [`SLIP_NOISE`] at the step's start and at the point found (or the step's end)
    /// ([`noise_halt`]): its sign is the solver's noise, and held the contact would trap the
    /// rod. The texture grid's uniform rod over 0.05/0.5/4π/3: a tip formed sliding beside a
    /// side at a slip's end, its rate 1.3e-9 to 1.5e-10 over the step and −3.9e-9 at its
    /// lift-off, halted at that noise 5.8e-5 before the lift-off and the drag stopped in the
    /// trapped state; the same rod over 0.01/0.1/0 did so on 11 output points but not on 201,
    /// where the noise had the other sign. Sliding at a rate of zero with `T = dir·μk N` the
    /// contact is within its static cone: a state of the model.
    fn dipped(
        &mut self,
        w: &Walk,
        (prev, end): (&Pt, &Pt),
        armed: &[Crossing],
        found: &mut Option<Found>,
    ) -> Option<StopReason> {
        let lam = prev.lam;
        let env = &self.env;
        let back = |c: Crossing, f: &Found| {
            c != f.cross
                && beyond(c.of_watch(env, &f.pt.w))
                && !noise_halt(env, c, (prev, &f.pt, end), w.quiet)
        };
        // (each replacement is strictly earlier: at most one per armed event)
        for _ in 0..armed.len() {
            let f = found.as_ref()?;
            let &c = armed.iter().find(|&&c| back(c, f))?;
            let fail = |message: String| StopReason::SolverFailure { d: lam, message };
            match locate(&mut *self.stepper, env, &w.hist, (lam, f.pt.lam), c) {
                Ok(pe) if earlier((c, &pe), f, w.h_min) => {
                    let v = c.of_watch(env, &pe.w);
                    if c == Crossing::Touchdown && env.ground.curve.is_some() && v < -JUMP {
                        // (a jump of the highest free point, not a root: as in events_in; where
                        // the event found is the tip turning tangent with the highest point
                        // beside it, the jump is that point's birth there, `Born::BesideTip`)
                        if f.cross == Crossing::TipTangent
                            && 1.0 - f.pt.w.clear_s < crate::events::NEAR_TIP
                        {
                            return None;
                        }
                        *found = None;
                        let at = pe.lam;
                        return Some(fail(format!(
                            "{} jumps to {v:.3e} at d = {at}",
                            c.describe()
                        )));
                    }
                    *found = Some(Found { cross: c, pt: pe });
                }
                Ok(_) => return None,
                Err(msg) => {
                    *found = None;
                    return Some(fail(format!(
                        "locating the {c:?} event before another: {msg}"
                    )));
                }
            }
        }
        None
    }

    /// The outcome of the event `cross` at its located point `pe`: a change of contact set and
    /// the march goes on, or the end.
    fn on_event(&mut self, w: &mut Walk, cross: Crossing, mut pe: Pt) -> Flow {
        if let Crossing::Lift(_) = cross {
            // (the contact letting go has N = 0 at its root: one a rounding below it, −4.3e-18
            // on the property's seed 39 at 64 cases, is that zero on the release's row)
            pe = at_zero(pe);
        }
        let set = self.stepper.set().clone();
        let rules = Rules {
            friction: self.spec.friction,
            slide: self.spec.slide,
        };
        let xf = self.stepper.foot(pe.lam).0;
        let mut next = transition(&self.env, rules, &set, cross, &pe, xf);
        // (a failure falls back on a lie-down only while the set it formed is the march's)
        self.lain = None;
        if matches!(next, Next::Switch(Event::LieDown, ..)) {
            // (a side that lies down, or two contacts that close up lying down as one stretch:
            // the stop said as that, with why)
            let words = |why: &str| match cross {
                Crossing::Lie(j) => Some(crate::events::curve_lie(&set, j, &pe, why)),
                Crossing::Close(j, k) => Some(crate::events::closed_up(&set, (j, k), &pe, why)),
                _ => None,
            };
            if !self.stepper.lies() {
                let why = "a stretch lying on the surface is solved by the rod's own shooter \
                           (method shooting)";
                if let Some(stop) = words(why) {
                    next = Next::Limit(stop);
                }
            } else {
                // where the march after it fails in the solver, the drag ends there, said so
                let fallback = match cross {
                    Crossing::Lie(j) if crate::events::lies_sliding_with_beyond(&set, j) => words(
                        "the stretch that forms sliding along the surface, with contacts beyond \
                         it, is not resolved",
                    ),
                    Crossing::Close(..) => words(crate::events::MERGED_UNRESOLVED),
                    _ => None,
                };
                if let Some(lie) = fallback {
                    self.lain = Some(Box::new(Lain {
                        set: set.clone(),
                        pe: pe.clone(),
                        lie,
                        mark: self.out.mark(),
                        range: *self.range,
                    }));
                }
            }
        }
        match next {
            Next::Done => {
                self.range.close(RangeEnd::DMax);
                Flow::End(StopReason::DMax, Some(Box::new((set, pe))))
            }
            // (the slide's equilibria fold back where the free rod between a lying stretch
            // and the tip beyond it vanishes: the stretch reaches the tip, and the march goes
            // on from the joined state)
            Next::Stop(Event::FoldInD) => match self.reach_tip(&set, &pe) {
                Some(q) => {
                    let joined = self.stepper.set().clone();
                    self.go_on(w, &joined, q);
                    Flow::Go
                }
                None => self.stopped(Event::FoldInD, set, pe),
            },
            Next::Stop(ev) => self.stopped(ev, set, pe),
            Next::Limit(message) => {
                // (the event point is already in the range: seen where it was found)
                self.range.close(RangeEnd::Event);
                let stop = StopReason::ContactChange { d: pe.lam, message };
                Flow::End(stop, Some(Box::new((set, pe))))
            }
            Next::Switch(ev, new_set, u) => self.switch(w, (ev, set, pe), new_set, u),
        }
    }

    /// The end at the event `ev` that stops the march, at `pe` of `set`.
    fn stopped(&mut self, ev: Event, set: ContactSet, mut pe: Pt) -> Flow {
        if ev == Event::LiftOff {
            lifted(&mut pe.w);
        }
        self.range.see(&pe.w);
        self.range.close(RangeEnd::Event);
        self.out.push(&set, &pe, Some(ev));
        Flow::End(stop_reason(ev, &pe.w, &set), Some(Box::new((set, pe))))
    }

    /// The march goes on from `q`, the first point of the new contact set `set`: its history
    /// and the event functions still at (or past) zero there.
    fn go_on(&mut self, w: &mut Walk, set: &ContactSet, q: Pt) {
        let env = &self.env;
        w.quiet = None;
        // (one within rounding of zero too: its side is noise, and an armed one would cross
        // back at once, an event the grid decides)
        w.pending = Crossing::all(env, set)
            .into_iter()
            .filter(|c| {
                let v = c.of_watch(env, &q.w);
                !holds(v) || v.abs() <= AT_ZERO
            })
            .collect();
        if env.ground.meter.is_some() {
            self.metered_to = Some(q.clone());
        }
        w.hist = vec![q];
        w.queue.clear();
        w.pprev = None;
    }

    /// The contact set changes at the event point `pe` of `set` to `new_set` (the old state in
    /// its unknowns `u`); the march goes on from the new state's first point.
    fn switch(
        &mut self,
        w: &mut Walk,
        (ev, set, pe): (Event, ContactSet, Pt),
        mut new_set: ContactSet,
        u: Vec<f64>,
    ) -> Flow {
        let driver_before = self.env.ground.slide.map(|s| s.driver);
        let driver_gone = self.renumber(&set, &new_set, pe.lam);
        if driver_gone {
            let xf = self.stepper.foot(pe.lam).0;
            (new_set, self.out.riders) = hold_riders(&set, new_set, &pe, xf);
        }
        let env = &self.env;
        self.out.push(&set, &pe, Some(ev));
        // (the event's row is of the old set; the points after it of the new one)
        self.out.driver = env.ground.slide.map(|s| s.driver);
        if new_set.contacts.len() > set.contacts.len() {
            let du = self.stepper.tangent_in(&new_set, pe.lam, &u);
            if let Some(message) = forming_slip(&set, &new_set, &u, du.as_deref(), env.mu0) {
                // with kinetic friction (a drag) the new contact slides from the start; without
                // it (a scan) the scan ends there
                match env
                    .ground
                    .mu_k
                    .and_then(|mk| sliding_from_start(&set, &new_set, du, mk))
                {
                    Some(slid) => new_set = slid,
                    None => {
                        self.range.close(RangeEnd::Event);
                        let stop = StopReason::ContactChange { d: pe.lam, message };
                        return Flow::End(stop, Some(Box::new((set, pe))));
                    }
                }
            }
        }
        let rising = pe.w.dmu_abs;
        // (the energy where the driver lets go, of the old set, for the jump at its release)
        let released_from = driver_gone
            .then(|| self.stepper.energy(&pe.u, pe.lam))
            .flatten();
        let formed = (new_set.contacts.len() > set.contacts.len()).then(|| u.clone());
        let again = (ev == Event::Halt).then(|| u.clone());
        let switched = self.stepper.switch(new_set.clone(), pe.lam, u);
        let switched = match (switched, formed) {
            (Ok(q), Some(u)) => match self.formed_holds(&set, &new_set, &q, &u) {
                Trapped::No => Ok(q),
                Trapped::Slides(slid, q) => {
                    new_set = slid;
                    Ok(*q)
                }
                Trapped::Stop(message) => return self.impasse(message, set, pe),
                Trapped::Jam(message) => {
                    self.range.close(RangeEnd::Event);
                    let stop = StopReason::Jam { d: pe.lam, message };
                    return Flow::End(stop, Some(Box::new((set, pe))));
                }
            },
            (r, _) => r,
        };
        match switched {
            Ok(q) => {
                let q = match self.after_reversal(ev, (&set, &pe), (&mut new_set, q), again) {
                    Ok(q) => q,
                    Err(why) => return self.impasse(why.to_string(), set, pe),
                };
                let crossing = driver_gone
                    .then(|| crossing_after_release(&self.env, &new_set, &q))
                    .flatten()
                    .or_else(|| {
                        let before = released_from?;
                        release_jump(before, self.stepper.energy(&q.u, q.lam)?)
                    });
                let pushing = driver_before
                    .zip(crossing)
                    .and_then(|(j, why)| released_pushing(&pe, j, &why));
                if let Some(stop) = pushing {
                    return self.still_touching(stop, driver_before, set, pe);
                }
                if driver_gone {
                    // the sliding contact lifted off: the slip ends at the first point without
                    // it (the foot held, the other contacts as they were)
                    return Flow::End(StopReason::DMax, Some(Box::new((new_set, q))));
                }
                if ev == Event::Halt && self.stepper.trapped_singular(&new_set, q.lam, &q.u) {
                    self.range.close(RangeEnd::Event);
                    let message = halted_trapped(&set, &new_set, &pe, &q);
                    let stop = StopReason::ContactChange { d: pe.lam, message };
                    let j = halted(&set, &new_set);
                    if slip_noise(&pe, j) && w.quiet != Some(j) {
                        return Flow::Quiet(j, stop, Box::new((set, pe)));
                    }
                    return Flow::End(stop, Some(Box::new((set, pe))));
                }
                // a maximum of |μ| at the kink of the change
                if self.range.end.is_none()
                    && rising.is_some_and(|s| s > 0.0)
                    && q.w.dmu_abs.is_some_and(|s| s < 0.0)
                {
                    self.range.see(&q.w);
                    self.range.close(RangeEnd::FirstMaximum);
                }
                self.go_on(w, &new_set, q);
                Flow::Go
            }
            Err(e) => {
                if let Some(stop) = driver_before
                    .filter(|_| driver_gone)
                    .and_then(|j| released_pushing(&pe, j, &e))
                {
                    return self.still_touching(stop, driver_before, set, pe);
                }
                let message = format!(
                    "{} ({} to {}): the new contact state does not hold: {e}",
                    ev.name(),
                    set.label(),
                    new_set.label()
                );
                Flow::Unheld(
                    StopReason::ContactChange { d: pe.lam, message },
                    Box::new((set, pe)),
                )
            }
        }
    }

    /// The end `stop` at the event point `pe` of `set`, where the slip's driver (`driver`, its
    /// number before the change) still touches: a release that no quasi-static state follows.
    fn still_touching(
        &mut self,
        stop: StopReason,
        driver: Option<usize>,
        set: ContactSet,
        pe: Pt,
    ) -> Flow {
        self.out.driver = driver;
        self.range.close(RangeEnd::Event);
        Flow::End(stop, Some(Box::new((set, pe))))
    }

    /// The first point `q` of `new_set` after the change `ev` at `pe` of `set`, or of the held
    /// state that replaces it (`new_set` then that set) where `ev` reverses a sliding contact at
    /// once with a jump that loses energy ([`Run::reversal_jumps`], [`Run::held_instead`];
    /// `again`: the old state in the new unknowns, for a halt). `Err`: the words of the jam
    /// where the jump would gain energy, or where neither state solves.
    fn after_reversal(
        &mut self,
        ev: Event,
        (set, pe): (&ContactSet, &Pt),
        (new_set, q): (&mut ContactSet, Pt),
        again: Option<Vec<f64>>,
    ) -> Result<Pt, Impasse> {
        match self.reversal_jumps(ev, (set, pe), (new_set, &q)) {
            Some(Jump::Gains(why)) => Err(why),
            Some(Jump::Loses(j)) => {
                let back = again.map(|u| (new_set.clone(), u));
                match self.held_instead(set, j, pe, back)? {
                    Some((held, qh)) => {
                        *new_set = held;
                        Ok(qh)
                    }
                    None => Ok(q),
                }
            }
            None => Ok(q),
        }
    }

    /// How the contact that has just formed in `new_set` (from `set`; the old state in the new
    /// unknowns `u`, its first point `q`) holds where holding it without slip, as it formed, is
    /// no way on. Two such cases, one remedy (with kinetic friction, a drag): the contact slides
    /// from the start, with kinetic friction, the way the rod moves over it there (its friction
    /// opposing its slip, on the sliding state's tangent), if that state loads it
    /// ([`Run::slides_from_start`]); else no contact state continues.
    /// * Its state is singular at that point: the contact forms at the end of a straight,
    ///   unloaded stretch of the rod beyond a contact that does not slip either (the free rod
    ///   touching down on the next crest of a corrugation, issue 31). Pulled along its length, a
    ///   straight inextensible stretch does not bend, so at `N = 0` any pair of opposite
    ///   tangential forces at its ends is an equilibrium: a line of states, and the branch on
    ///   which the new contact loads leaves that line at a finite `T` (0.003/0.05/0 on the rod
    ///   tapered to 0.3: `T = −1.7e-4` at `N = 0`), beyond any friction. The same holds for the
    ///   tip touching down at the end of the free tail beyond a side that rolls (the tail is
    ///   unloaded, so straight): rolling that side along the surface moves its contact point
    ///   along the tail by as much as it shortens it, so to first order the side may roll either
    ///   way with the tip held (issue 31's own drag, A 0.005, W 0.05: the tip touching down
    ///   4.3e-3 beyond the side that drove its sixth slip, the stuck state's tangent 1e18, its
    ///   equilibria folding back at once with the tip pulling, N = −9.7e-6). Where no slide
    ///   loads it, the stop names the singular state ([`Trapped::Stop`]).
    /// * Held, it would pull at once: its normal force falls from zero on the held state's exact
    ///   tangent, though the state before crosses the surface there (the touchdown). Holding it
    ///   traps the stretch between it and a contact that does not slip, whose tangential forces
    ///   then bend the rod away from the surface (issue 31's texture grid, 0.003/0.1/4π/3 on the
    ///   rod tapered to 0.3: a side touching down at s = 0.8138, 0.071 behind a rolling side, at
    ///   d 0.29658 needs `dT/dd = 92` and `dN/dd = −14.6` held; sliding towards +x it loads,
    ///   `dN/dd = 4.3`, and slips that way, 5.9e-4 per unit d; towards −x it would slip against
    ///   its friction). The drag ended there, "the contact state side+side does not hold". The
    ///   rate problem of the new contact (hold, slide either way, or leave, which the touchdown
    ///   excludes) then has the slide as its solution; where it has none, no quasi-static state
    ///   continues: a jam ([`Trapped::Jam`]).
    fn formed_holds(
        &mut self,
        set: &ContactSet,
        new_set: &ContactSet,
        q: &Pt,
        u: &[f64],
    ) -> Trapped {
        let Some(mu_k) = self.env.ground.mu_k else {
            return Trapped::No;
        };
        let Some(j) = (new_set.contacts.iter()).position(|c| !set.contacts.contains(c)) else {
            return Trapped::No;
        };
        let ct = &new_set.contacts[j];
        if !ct.mode.no_slip() {
            return Trapped::No;
        }
        let what = if ct.tip {
            "tip contact"
        } else {
            "side contact"
        };
        if self.stepper.trapped_singular(new_set, q.lam, &q.u) {
            if let Some((slid, p)) = self.slides_from_start(new_set, j, (q.lam, u), mu_k, loads) {
                return Trapped::Slides(slid, p);
            }
            return Trapped::Stop(format!(
                "a {what} forms at s = {:.6} at the end of a straight stretch of the rod that \
                 another contact holds without slip: the state {} is singular there (the tension \
                 of the stretch is indeterminate, and holding the new contact needs a tangential \
                 force at zero normal force), and sliding with kinetic friction the way the rod \
                 moves over it does not load it: no contact state continues",
                new_set.s_of(j, &q.u),
                new_set.label()
            ));
        }
        let o = new_set.offset(j);
        let Some((dn, dt)) = (self.stepper.tangent_in(new_set, q.lam, &q.u))
            .and_then(|du| Some((*du.get(o)?, *du.get(o + 1)?)))
        else {
            return Trapped::No;
        };
        if dn >= 0.0 {
            return Trapped::No;
        }
        if let Some((slid, p)) = self.slides_from_start(new_set, j, (q.lam, u), mu_k, loads) {
            return Trapped::Slides(slid, p);
        }
        Trapped::Jam(format!(
            "a {what} forms at s = {:.6} in the state {}: held without slip it would pull at once \
             (dN = {dn:.3e}, dT = {dt:.3e} per unit of the march), and sliding with kinetic \
             friction either way does not load it or slips against its friction: no contact \
             state consistent with Coulomb friction continues",
            new_set.s_of(j, &q.u),
            new_set.label()
        ))
    }

    /// `new_set` with its contact `j` sliding with kinetic friction `mu_k` the way the rod moves
    /// over it, and its first point at `λ` from the state's unknowns `u`: the first of the two
    /// ways (`+x`, then `−x`) whose state slips it the way its friction opposes and that `takes`
    /// (for a contact just formed, [`loads`]: its normal force rises); `None` where neither does.
    fn slides_from_start(
        &mut self,
        new_set: &ContactSet,
        j: usize,
        (lam, u): (f64, &[f64]),
        mu_k: f64,
        takes: impl Fn(&mut dyn Stepper, &ContactSet, &Pt, usize) -> bool,
    ) -> Option<(ContactSet, Box<Pt>)> {
        for ratio in [mu_k, -mu_k] {
            let mut slid = new_set.clone();
            slid.contacts[j].mode = Mode::Sliding(ratio);
            let Ok(p) = self.stepper.switch(slid.clone(), lam, u.to_vec()) else {
                continue;
            };
            if ratio * p.w.contacts[j].slide.slip > 0.0 && takes(&mut *self.stepper, &slid, &p, j) {
                return Some((slid, Box::new(p)));
            }
        }
        None
    }

    /// A contact before a slip's driver that lets go (`set` to `new_set`) moves the driver one
    /// place down the set, one that touches down before it one place up: the slip's family and
    /// events follow it under its new number (before, the old number named another contact or
    /// none, and the slide moved the wrong contact or none). Whether the driver itself let go:
    /// then the march has no slide left (`env.ground.slide` none; the family's driver a number
    /// past the set, which moves no contact).
    fn renumber(&mut self, set: &ContactSet, new_set: &ContactSet, lam: f64) -> bool {
        let Some(slide) = self.env.ground.slide.as_mut() else {
            return false;
        };
        let (old, new) = (set.contacts.len(), new_set.contacts.len());
        if new.abs_diff(old) != 1 {
            return false;
        }
        // (the first place where the sets differ: the contact that came or went)
        let shared = old.min(new);
        let at = (0..shared)
            .find(|&k| set.contacts[k] != new_set.contacts[k])
            .unwrap_or(shared);
        if at > slide.driver {
            return false;
        }
        let ((xf, theta), dir) = (self.stepper.foot(lam), slide.dir);
        let lost = new < old && at == slide.driver;
        let driver = if lost {
            self.env.ground.slide = None;
            new
        } else {
            if new > old {
                slide.driver += 1;
            } else {
                slide.driver -= 1;
            }
            slide.driver
        };
        let family = crate::chain::Family::Slide {
            xf,
            theta,
            dir,
            driver,
        };
        self.stepper.phase(family, &self.env);
        lost
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
            self.out.push(&set, &p, None);
            self.out.gi += 1;
        }
        Ok(())
    }

    /// The point at `g` by natural steps from the last point of `hist` before it (where one
    /// correction from the whole history fails, e.g. after pseudo-arclength jumped past `g`).
    fn bridge(&mut self, hist: &[Pt], g: f64) -> Result<Pt, BridgeError> {
        let mut local: Vec<Pt> = hist.iter().filter(|p| p.lam < g).cloned().collect();
        let Some(last) = local.last() else {
            return Err(BridgeError::NoPointBefore);
        };
        let mut h = (g - last.lam) / 4.0;
        for _ in 0..BRIDGE_STEPS {
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
                        return Err(BridgeError::Step(e));
                    }
                }
            }
        }
        Err(BridgeError::Budget)
    }
}

/// Steps a bridge to an output point may take.
const BRIDGE_STEPS: usize = 200;

/// Why an output point could not be reached in shorter steps.
#[derive(Clone, Debug, PartialEq)]
enum BridgeError {
    /// The history has no point before it.
    NoPointBefore,
    /// A step shorter than 1e-9 still failed.
    Step(StepError),
    /// Not reached within [`BRIDGE_STEPS`] steps.
    Budget,
}

impl std::fmt::Display for BridgeError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            BridgeError::NoPointBefore => f.write_str("no point before it"),
            BridgeError::Step(e) => write!(f, "{e}"),
            BridgeError::Budget => write!(f, "no convergence in {BRIDGE_STEPS} steps"),
        }
    }
}

/// The normal force of a contact just formed, relative to the total, below which its forces are
/// the solver's noise (a located touchdown lies within 1e-13 in `λ` of the new contact's zero;
/// the corrector iterates to 1e-11).
const NOISE: f64 = 1e-8;

/// How a contact that has just formed holds where holding it as it formed is no way on
/// ([`Run::formed_holds`]).
enum Trapped {
    /// As it formed (its state is not singular, or not of that kind).
    No,
    /// It slides from the start: the set, and its first point.
    Slides(ContactSet, Box<Pt>),
    /// No contact state continues from its singular state: why.
    Stop(String),
    /// Held it would pull, and no slide loads it: no state consistent with Coulomb friction
    /// continues (a jam): why.
    Jam(String),
}

/// A new contact state's event that its first step found beyond zero.
enum Pending {
    /// The step is too long for it: taken again, shorter.
    Shorter,
    /// The state does not hold: the march ends.
    Stop(StopReason),
    /// The event happens at the state's first point.
    AtStart(Crossing),
}

/// The elastic energy a reversal at once may gain, relative to `1 + E`, and still be the same
/// state within the energy's accuracy (its quadrature agrees with the metered work to 1e-11 per
/// step; a slip's balance is asked to 1e-8).
const GAIN: f64 = 1e-9;

/// Whether the sliding state `p` loads its contact `j` (its normal force rises): the test of a
/// contact that forms sliding ([`Run::slides_from_start`]).
fn loads(_: &mut dyn Stepper, _: &ContactSet, p: &Pt, j: usize) -> bool {
    p.w.contacts[j].slide.dnormal > 0.0
}

/// The largest rate `|du/dλ|` of a held state's tangent that still lets the march go on from it.
const HOLD_MAX: f64 = 1e6;

/// The largest rate `|du/dλ|` of a held state's tangent taken instead of a reversal at once that
/// loses energy ([`Run::held_instead`]): the held state's friction then turns through its cone
/// over a slide of `2 μ N / rate`, no shorter than about 1e-9 for forces of order 1, steps the
/// march still takes.
const HOLD_FAR: f64 = 1e9;

/// What a highest free point born inside a step (between `from`, where the free rod has none
/// and its clearance is the foot's, and the step's end `p`, where it is above the surface) is,
/// its birth bracketed by bisection on the points between.
enum Born {
    /// Born below the surface: the touchdown located between the birth and `p`.
    Below(Pt),
    /// Born above the surface within [`crate::events::NEAR_TIP`] of a touching tip, at this
    /// point: the rod beside the tip, nearly straight (its moment falls to zero there) and
    /// nearly tangent to a crest that curves away under it, cuts the crest at `2δ/|h''|` from
    /// the tip, `δ` the tip's angle to the surface; as `δ → 0` that is the tip turning tangent
    /// (`Crossing::TipTangent`), which it is taken for. (A rod tapered to 0.45 over a
    /// corrugation of amplitude 1e-4: its clearance jumped from the foot's −0.75 to 2.2e-10 at
    /// s = 0.99951, the tip 4e-6 off tangent, and the drag ended in a solver failure.)
    BesideTip(Pt),
}

/// See [`Born`]; `None` where it was born above the surface elsewhere (a jump the march
/// reports) or a point between does not solve.
fn born(st: &mut dyn Stepper, env: &Env, hist: &[Pt], (from, p): (f64, &Pt)) -> Option<Born> {
    let c = Crossing::Touchdown;
    let (mut lo, mut hi) = (from, p.lam);
    let mut first = p.clone();
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if !(mid > lo && mid < hi) {
            break;
        }
        let q = st.correct(mid, hist, false).ok()?;
        if c.of_watch(env, &q.w) < -JUMP {
            lo = mid;
        } else {
            hi = mid;
            first = q;
        }
    }
    if c.of_watch(env, &first.w) < 0.0 && first.lam < p.lam {
        let q = crate::events::locate(st, env, hist, (first.lam, p.lam), c).ok()?;
        return Some(Born::Below(q));
    }
    let beside_tip = st.set().tip() && 1.0 - first.w.clear_s < crate::events::NEAR_TIP;
    beside_tip.then_some(Born::BesideTip(first))
}

/// How a reversal at once changes the elastic energy beyond [`GAIN`] (`Run::reversal_jumps`).
enum Jump {
    /// It would gain energy: the stop.
    Gains(Impasse),
    /// It would lose energy unmetered: the contact that reversed.
    Loses(usize),
}

/// Why a halt that reverses a sliding contact ends the march (its stop's words).
#[derive(Clone, Debug, thiserror::Error)]
pub(crate) enum Impasse {
    /// The jump to the reversed state would gain elastic energy ([`Run::reversal_jumps`]).
    #[error(
        "the sliding contact at s = {s:.6} halts and, held, is no way on, so it would slide \
         back at once, its friction flipping by 2 mu_k N = {flip:.3e}; the state it would jump \
         to has {gain:.3e} more elastic energy than the one it leaves, which no passive change \
         at once reaches: no contact state consistent with Coulomb friction continues (the rod \
         moves dynamically)"
    )]
    JumpGains {
        /// The contact's arc length.
        s: f64,
        /// `2 μk N`, the flip of its friction.
        flip: f64,
        /// The elastic energy the jump would gain.
        gain: f64,
    },
    /// Neither the held state nor the reversed one solves ([`Run::held_instead`]).
    #[error(
        "the sliding contact at s = {s:.6} halts; held, its state does not solve, and reversed \
         at once it no longer does either: {why}"
    )]
    NeitherSolves {
        /// The contact's arc length.
        s: f64,
        /// Why the reversed state's switch failed.
        why: StepError,
    },
}

/// Whether the path's step `chord` is the march's step from `prev` to `p`.
fn spans(chord: &Chord, prev: &Pt, p: &Pt) -> bool {
    chord.a.lam() == prev.lam && chord.b.lam() == p.lam
}
