//! The events of a march, in one place: what they are (functions of a branch point, negative
//! while a contact state holds and zero where it ends: a contact lifts, slips, a free part of the
//! rod touches the surface, the tip turns tangent to it, a lying part peels back, an object
//! slips off the tip, `|μ|` stops rising, a press reaches its goal), where they are located
//! inside a step (on the branch polynomial refined by solves, or by Brent's method on solves),
//! and what follows each (the next contact set, or the end).
//!
//! An event is an outcome of a step: the driver (module `march`) backs up to the located point,
//! applies what [`transition`] says (a new contact set: touchdown, peel-back, release, a contact
//! that slides on; or the end) and continues in the same step sequence.

use crate::chain::{Contact, ContactSet, Geom, Mode};
use crate::report::{Event, StopReason};
use crate::search::{self, RootError};
use crate::stepper::{Pt, StepError, Stepper};
use crate::watch::{lies_inside, slip_limit, Env, Goal, Watch, SIDE_FRICTION_LIMIT};
use std::sync::Arc;

/// The events of a contact state: functions negative while it holds, zero where it ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Crossing {
    /// Contact `j`'s normal force falls to 0.
    Lift(usize),
    /// Contact `j` (stuck or rolling) needs `|T| = μ0 N`.
    Slip(usize),
    /// The sliding contact `j` needs no more than `dir·T = μk N` (the end of a slip; `dir` the
    /// way it slides).
    Stick(usize),
    /// A free part of the rod reaches the surface.
    Touchdown,
    /// The tip, touching the surface, turns tangent to it.
    TipTangent,
    /// The rolling contact `j` reaches the tip (the lying part peels back).
    PeelBack(usize),
    /// The point object at contact `j` reaches the tip.
    SlipOff(usize),
    /// The side contact `j` (on a line: with another beyond it) begins to lie along the surface:
    /// the rod's curvature there, relative to the surface, falls to zero.
    Lie(usize),
    /// The contact `j`, sliding with kinetic friction, comes to rest: its slip rate falls to zero
    /// (it would reverse against its friction).
    Halt(usize),
    /// The lying stretch whose inner end is contact `j` shrinks to its outer end: the rod rises
    /// off the surface to a point contact there.
    Unlie(usize),
    /// The outer end of the lying stretch whose inner end is contact `j`, the rest beyond it
    /// unloaded, reaches the rod's end.
    Reach(usize),
    /// An end of the lying stretch whose inner end is contact `j` would pull on the surface (the
    /// smaller of its ends' point forces falls to zero).
    EndLift(usize),
    /// The side contact `j`, driving a slip, closes up to its neighbour `k` on the surface (a
    /// side, or the inner end of the lying stretch): the surface's arc between them and the rod's
    /// length between them come within [`CLOSED`] (the free rod between lies down along the
    /// surface).
    Close(usize, usize),
    /// `|μ|` stops rising (its first maximum).
    MuMax,
    /// The last contact point reaches the target height (the end of a press).
    Target(Goal),
}

impl Crossing {
    /// What the function measures, in words.
    pub fn describe(self) -> String {
        match self {
            Crossing::Lift(j) => format!("-N of contact {} (it would pull)", j + 1),
            Crossing::Slip(j) => format!("|T| - mu0 N of contact {} (it would slip)", j + 1),
            Crossing::Lie(j) => format!(
                "cos(phi - beta) kappa at contact {} (it would lie along the surface)",
                j + 1
            ),
            Crossing::Stick(j) => {
                format!("mu_k N - dir T of contact {} (it would stick again)", j + 1)
            }
            Crossing::Touchdown => {
                "the height of the free rod above the surface (it would cross it)".into()
            }
            Crossing::TipTangent => {
                "-sin(phi(1) - beta) (the tip would turn into the surface)".into()
            }
            Crossing::PeelBack(j) => format!(
                "s - 1 of contact {} (the lying part's inner end would pass the tip)",
                j + 1
            ),
            Crossing::SlipOff(j) => {
                format!("s - 1 of contact {} (the object would pass the tip)", j + 1)
            }
            Crossing::Halt(j) => format!(
                "-dir v of contact {} (its slip would reverse against its friction)",
                j + 1
            ),
            Crossing::Unlie(j) => format!(
                "s - s2 of contact {} (the lying stretch would shrink past its outer end)",
                j + 1
            ),
            Crossing::Reach(j) => format!(
                "s2 - 1 of contact {} (the lying stretch would reach past the rod's end)",
                j + 1
            ),
            Crossing::EndLift(j) => format!(
                "-min(P1, P2) of contact {} (an end of the lying stretch would pull)",
                j + 1
            ),
            Crossing::Close(j, k) => format!(
                "{CLOSED:e} less |surface's arc - rod's length| between contacts {} and {} (the \
                 side would close up to its neighbour)",
                j + 1,
                k + 1
            ),
            Crossing::MuMax => "-d|mu|/dd".into(),
            Crossing::Target(Goal::Height(h, _)) => format!("y of the last contact - {h}"),
            Crossing::Target(Goal::TipSlope(p, _)) => format!("phi(1) - {p}"),
        }
    }

    /// The event functions of a contact set.
    pub fn all(env: &Env, set: &ContactSet) -> Vec<Crossing> {
        let mut v = Vec::new();
        for (j, c) in set.contacts.iter().enumerate() {
            v.push(Crossing::Lift(j));
            if env.ground.slide.is_some_and(|s| s.driver == j) {
                v.push(Crossing::Stick(j));
                for k in closing(env, set, j) {
                    v.push(Crossing::Close(j, k));
                }
            } else if is_slider(c) {
                v.push(Crossing::Halt(j));
            } else if (slip_limit(env, set, j).is_finite() || env.ground.texture.is_some())
                && c.mode.no_slip()
            {
                v.push(Crossing::Slip(j));
            }
            if set.lain() == Some(j) {
                // the inner end of a lying stretch (module `chain`, `Lying`)
                v.push(Crossing::Unlie(j));
                v.push(Crossing::EndLift(j));
                if j + 1 == set.contacts.len() {
                    v.push(Crossing::Reach(j));
                }
                continue;
            }
            if lies_inside(set, j) || (!c.tip && matches!(c.geom, Geom::Curve { .. })) {
                v.push(Crossing::Lie(j));
            }
            match (&c.geom, c.tip) {
                // (a round tip meets the surface at any angle)
                (Geom::Line { .. } | Geom::Curve { .. }, true) if set.tip_radius > 0.0 => {}
                (Geom::Line { .. } | Geom::Curve { .. }, true) => v.push(Crossing::TipTangent),
                (Geom::Line { .. } | Geom::Curve { .. }, false) => v.push(Crossing::PeelBack(j)),
                (Geom::Point { .. }, false) => v.push(Crossing::SlipOff(j)),
                _ => {}
            }
        }
        if env.line.is_some() || env.ground.curve.is_some() {
            v.push(Crossing::Touchdown);
        }
        if let Some(h) = env.target {
            v.push(Crossing::Target(h));
        }
        v
    }

    /// Its value at a watched point.
    pub fn of_watch(self, env: &Env, w: &Watch) -> f64 {
        match self {
            Crossing::Lift(j) => -w.contacts[j].normal,
            Crossing::Slip(j) => {
                let c = w.contacts[j];
                c.friction().abs() - c.mu_s * c.normal
            }
            Crossing::Lie(j) => w.contacts[j].curv,
            Crossing::Halt(j) => {
                // the friction opposes the slip: T > 0 for a slip towards +x
                let c = w.contacts[j];
                -c.slide.dir * c.slide.slip
            }
            Crossing::Stick(j) => {
                // signed along the slip: it rises through zero once where μk holds the tip
                let c = w.contacts[j];
                let dir = env.ground.slide.map_or(1.0, |s| s.dir);
                if c.kinetic_balance.is_finite() {
                    // a lying stretch: its balance at μk, zero where the ratio it needs is
                    // μk (not `μk N − dir·gμ N`: that ratio falls smoothly to μk, but has no
                    // value where the normal force falls on towards a lift-off, and a search
                    // for μk over a step that reached there stopped at a jump of that value: a
                    // slip of the short rat preset over 0.001/0.05/2π/3 ended where it began,
                    // off μk, 3.0e-4 of released energy unmetered)
                    -dir * c.kinetic_balance
                } else {
                    c.mu_k * c.normal - dir * c.friction()
                }
            }
            Crossing::Touchdown => w.clear,
            Crossing::TipTangent => -w.tip_approach,
            Crossing::PeelBack(j) | Crossing::SlipOff(j) => w.contacts[j].s - 1.0,
            Crossing::Unlie(j) => w.contacts[j].s - w.contacts[j].lies_to,
            Crossing::Reach(j) => w.contacts[j].lies_to - 1.0,
            Crossing::Close(j, k) => match &env.ground.curve {
                Some(h) => {
                    let (a, b) = (&w.contacts[j.min(k)], &w.contacts[j.max(k)]);
                    // (the gap nears zero, from a bridge's side or a blister's, without crossing
                    // it: the event is its coming within `CLOSED`)
                    let gap = (h.sigma(b.x).0 - h.sigma(a.x).0).abs() - (b.s - a.s);
                    CLOSED - gap.abs()
                }
                None => f64::NAN,
            },
            Crossing::EndLift(j) => {
                let [p1, p2] = w.contacts[j].end_push;
                -p1.min(p2)
            }
            Crossing::MuMax => -w.dmu_abs.unwrap_or(f64::NAN),
            Crossing::Target(Goal::Height(h, sign)) => sign * (h - w.last_y),
            Crossing::Target(Goal::TipSlope(p, sign)) => sign * (p - w.phi1),
        }
    }

    /// Whether the value depends on the unknowns alone on a surface (so the branch polynomial
    /// predicts it).
    pub fn of_u(self, env: &Env, set: &ContactSet, u: &[f64]) -> Option<f64> {
        let line = |j: usize| matches!(set.contacts[j].geom, Geom::Line { .. });
        match self {
            Crossing::Lift(j) if line(j) => Some(-u[set.offset(j)]),
            Crossing::Slip(j)
                if line(j) && (set.contacts[j].tip || env.ground.texture.is_none()) =>
            {
                let o = set.offset(j);
                Some(u[o + 1].abs() - slip_limit(env, set, j) * u[o])
            }
            Crossing::Stick(j) if line(j) => {
                let mu_k = match (&env.ground.texture, env.ground.slide) {
                    (None, Some(sl)) => sl.mu_k,
                    (Some(t), Some(_)) => t.uniform_mu_k()?,
                    _ => return None,
                };
                let o = set.offset(j);
                let dir = env.ground.slide.map_or(1.0, |s| s.dir);
                Some(mu_k * u[o] - dir * u[o + 1])
            }
            Crossing::PeelBack(j) | Crossing::SlipOff(j) => Some(set.s_of(j, u) - 1.0),
            // (a stretch that slides, driving a slip or passively, moves its outer end)
            Crossing::Unlie(j)
                if env.ground.slide.is_none_or(|sl| sl.driver != j)
                    && !is_slider(&set.contacts[j]) =>
            {
                Some(set.s_of(j, u) - set.s2_of(u))
            }
            _ => None,
        }
    }
}

/// The set with contact `j` holding where it is at `pe` (foot at `xf`): a tip stuck at its place
/// along the surface, a side rolling from there on (its invariant, place along the surface less
/// its place along the rod, at today's value).
pub(crate) fn held(set: &ContactSet, j: usize, pe: &Pt, xf: f64) -> ContactSet {
    let ct = &set.contacts[j];
    let s = set.s_of(j, &pe.u);
    let z = if ct.tip {
        let r = pe.sol.right();
        [r[0], r[1], r[2], r[3]]
    } else {
        let mut z = [0.0; 4];
        pe.sol.eval(s, &mut z);
        z
    };
    let x = z[0] + xf;
    let (sigma, dir) = match &ct.geom {
        Geom::Line { p0, beta } => {
            let (sb, cb) = beta.sin_cos();
            let along = cb * (x - p0[0]) + sb * (z[1] - p0[1]);
            (along, (ct.phi_ref - beta).cos().round())
        }
        Geom::Curve { h } => {
            let th = h.angle(x).0;
            (h.sigma(x).0, ct.kpi(th).cos().round())
        }
        _ => return set.clone(),
    };
    let mut ns = set.clone();
    ns.contacts[j].mode = if ct.tip {
        // (a round tip's place includes its turn: it rolls)
        Mode::Stuck(if set.tip_radius > 0.0 {
            crate::chain::tip_place(set.tip_radius, &ct.geom, &z, xf).unwrap_or(f64::NAN)
        } else {
            sigma
        })
    } else {
        Mode::Rolling(sigma - dir * s)
    };
    ns
}

pub(crate) use crate::chain::is_slider;

/// An event already true at the start.
pub(crate) fn start_event(env: &Env, set: &ContactSet, w: &Watch) -> Option<Event> {
    if set.contacts.is_empty() {
        return None;
    }
    if w.clear > 0.0 || w.tip_approach < 0.0 || (!env.compound && !set.tip_only()) {
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

pub(crate) fn stop_reason(ev: Event, w: &Watch, set: &ContactSet) -> StopReason {
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
        Event::Touchdown
        | Event::PeelBack
        | Event::Release
        | Event::Halt
        | Event::LieDown
        | Event::PeelUp
        | Event::ReachTip => StopReason::ContactChange {
            d,
            message: format!("{} in state {}", ev.name(), set.label()),
        },
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
pub(crate) fn vanishing_normal(hist: &[Pt]) -> Option<(f64, String, Watch)> {
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
pub(crate) fn lifted(w: &mut Watch) {
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
pub(crate) const JUMP: f64 = 1e-6;
/// An event function this close to zero right after a change of contact set is at zero.
pub(crate) const AT_ZERO: f64 = 1e-12;
/// A sliding side has closed up to its neighbour (a side, or the lying stretch's inner end) where
/// the surface's arc between them and the rod's length between them differ by no more than this:
/// the contacts' places are solved to the corrector's tolerance, 1e-12 at the default tol. The
/// gap nears zero without crossing it, ever faster (issue 31's property seed 11: 2.6e-11,
/// 2.3e-12, 3.0e-13, 3.8e-14 at slides of 7.1e-4, 9.0e-4, 1.01e-3, 1.09e-3), and the state is
/// singular with it: that slide's march failed further on ("not resolved by arclength steps down
/// to 1.2e-10"). 1e-11, not the corrector's 1e-12: at 1e-12 the stuck states of slips that had
/// come within 1e-11 (singular to 4e-14 of their largest singular value) still placed folds by
/// rounding or failed, differently on different output grids (the short rat preset over
/// 0.001/0.2/4π/3: a fold on 21 and 201 points, a slip more on 11 and 51; over 0.001/0.2/2π/3:
/// a failure on 11 points); at 1e-11 both end in the same slip on every grid. A change of set
/// made with the gap already within it ends the drag the same way (march.rs `check_pending`),
/// not as a state that does not hold (a jam in a slip).
pub(crate) const CLOSED: f64 = 1e-11;

/// The set with the interior contact `ct` touched down at `s` (in its place along the rod; its
/// unknowns N, T start at zero), and its unknowns. A touchdown at the free tip (`s = 1`: the
/// clearance's largest value at the rod's end, where the rod is not tangent to the surface)
/// is a tip contact, `tip` (a corner on the surface, no tangency condition).
fn touchdown(set: &ContactSet, u: &[f64], ct: Contact, s: f64, tip: Contact) -> Next {
    if s >= 1.0 && !set.tip() {
        let mut ns = set.clone();
        ns.contacts.push(tip);
        let mut nu = u.to_vec();
        nu.extend([0.0, 0.0]);
        return Next::Switch(Event::Touchdown, ns, nu);
    }
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

/// Whether a touchdown at `pe` of `set` is the point tip's, beyond a lying stretch with the rest
/// unloaded (the last contact's): the free rod between them comes down onto the surface at its
/// end.
fn tip_beyond_stretch(set: &ContactSet, pe: &Pt) -> bool {
    let jl = set.contacts.len().wrapping_sub(1);
    set.lain() == Some(jl)
        && !set.tip()
        && set.tip_radius == 0.0
        && pe.w.clear_s >= 1.0
        && pe.w.contacts.get(jl).is_some_and(|c| c.lies_to < 1.0)
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
pub(crate) fn forming_slip(
    old: &ContactSet,
    new: &ContactSet,
    u: &[f64],
    du: Option<&[f64]>,
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

/// The set `new` (a contact just formed beside those of `old`) with the new contact sliding from
/// the start with kinetic friction `mu_k`, its friction the way its tangential force grows on
/// the new state's tangent `du`; `None` where that is not known.
pub(crate) fn sliding_from_start(
    old: &ContactSet,
    new: &ContactSet,
    du: Option<Vec<f64>>,
    mu_k: f64,
) -> Option<ContactSet> {
    let j = new
        .contacts
        .iter()
        .position(|c| !old.contacts.contains(c))?;
    let dt = du?[new.offset(j) + 1];
    let mut ns = new.clone();
    ns.contacts[j].mode = Mode::Sliding(if dt < 0.0 { -mu_k } else { mu_k });
    Some(ns)
}

/// An event function's value where its contact state holds strictly (NaN: not known to).
pub(crate) fn holds(v: f64) -> bool {
    v < 0.0
}

/// Its value where the event has happened (zero included).
pub(crate) fn ended(v: f64) -> bool {
    v >= 0.0
}

/// Its value beyond the event (NaN: not known to be).
pub(crate) fn beyond(v: f64) -> bool {
    v > 0.0
}

/// What follows an event.
pub(crate) enum Next {
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
    h: &Arc<crate::surface::Height>,
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
        // (the tip itself, beyond a stretch with the rest unloaded: the stretch with the tip
        // beyond it, the join of `tip_into_stretch` undone with free rod between them)
        Crossing::Touchdown if tip_beyond_stretch(set, pe) => {
            let jl = set.contacts.len() - 1;
            let xb = pe.sol.right()[0] + xf;
            let mode = if friction {
                Mode::Stuck(h.sigma(xb).0)
            } else {
                Mode::Free
            };
            let mut ns = set.clone();
            ns.contacts.push(Contact::on_curve(true, h, xb, mode, 0.0));
            let c = &pe.w.contacts[jl];
            // (its outer end, where the unloaded rest began, is an unknown again; `x2` is the
            // set's, kept at the point evaluated)
            if let Some(ly) = ns.lying.as_mut() {
                (ly.s2, ly.beyond) = (c.lies_to, 1);
            }
            let mut nu = u.clone();
            nu.extend([0.0, 0.0, c.lies_to]);
            Next::Switch(Event::Touchdown, ns, nu)
        }
        Crossing::Touchdown
            if set
                .lain()
                .is_some_and(|j| pe.w.clear_s > set.s_of(j, &pe.u)) =>
        {
            Next::Limit(format!(
                "the rod beyond the stretch lying on the surface touches down at s = {:.6}: a \
                 new contact beyond a lying stretch is not followed",
                pe.w.clear_s
            ))
        }
        Crossing::Touchdown => {
            let s = pe.w.clear_s;
            let z = pe.w.clear_z;
            let (mode, phi_ref) = rolling(&z, s);
            let ct = Contact::on_curve(false, h, z[0] + xf, mode, phi_ref);
            let xb = pe.sol.right()[0] + xf;
            let stuck = if friction && set.tip_radius > 0.0 {
                let geom = Geom::Curve { h: h.clone() };
                let place = crate::chain::tip_place(set.tip_radius, &geom, pe.sol.right(), xf);
                Mode::Stuck(place.unwrap_or(f64::NAN))
            } else if friction {
                Mode::Stuck(h.sigma(xb).0)
            } else {
                Mode::Free
            };
            touchdown(set, u, ct, s, Contact::on_curve(true, h, xb, stuck, 0.0))
        }
        Crossing::TipTangent => {
            let j = set.contacts.len() - 1;
            let zb = pe.sol.right();
            let (mode, phi_ref) = rolling(zb, 1.0);
            let mode = kept_sliding(&set.contacts[j], mode);
            let mut ns = set.clone();
            // the force keeps its frame (the unknowns carry over)
            ns.contacts[j] = Contact {
                tip: false,
                mode,
                phi_ref,
                ..set.contacts[j].clone()
            };
            let mut nu = u.clone();
            nu.push(1.0);
            Next::Switch(Event::Touchdown, ns, nu)
        }
        Crossing::PeelBack(j) if set.tip_radius > 0.0 && !set.tip() => {
            Next::Limit(round_tip_peel(set, j, pe))
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
                let ct = &set.contacts[jt];
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
                let mode = kept_sliding(&set.contacts[j], mode);
                ns.contacts[j] = Contact {
                    tip: true,
                    mode,
                    ..set.contacts[j].clone()
                };
                nu.remove(o + 2);
            }
            Next::Switch(Event::PeelBack, ns, nu)
        }
        _ => Next::Stop(Event::Penetration),
    }
}

/// How a march treats the contacts it changes.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Rules {
    /// New contacts hold by friction (stuck, rolling) rather than slide freely (the press).
    pub friction: bool,
    /// A stuck contact that reaches `|T| = μ0 N` slides on (`T = ±μ0 N`) instead of ending the
    /// march (a whisk against an object).
    pub slide: bool,
}

/// The contact set after the event `cross` at the point `pe` (foot at `xf`), or the end.
pub(crate) fn transition(
    env: &Env,
    rules: Rules,
    set: &ContactSet,
    cross: Crossing,
    pe: &Pt,
    xf: f64,
) -> Next {
    // (a lying stretch ends some events first: module `chain`, `Lying`)
    let next = stretch_transition(set, cross, pe)
        .unwrap_or_else(|| transition_at(env, rules, set, cross, pe, xf));
    driver_anchor(env, set, pe.lam, next)
}

/// `next` with the place of a slip's driver that changed its kind (a tip that lies down, a side
/// that peels back to the tip) as the slip's family reads it. The family moves the driver's
/// place (a stuck tip's anchor, a rolling side's invariant) by `dir·λ` (module `chain`,
/// `Pose::slide`), and the new mode holds its place at `λ`: its anchor is that less `dir·λ`.
/// (Taken as it was, the new state at the event's `λ` is the driver moved on by a second `dir·λ`:
/// the rod jumps there, and the energy it releases is no work of friction.)
fn driver_anchor(env: &Env, set: &ContactSet, lam: f64, next: Next) -> Next {
    let Next::Switch(ev, mut ns, nu) = next else {
        return next;
    };
    if let Some(sl) = env.ground.slide {
        let j = sl.driver;
        let same = ns.contacts.len() == set.contacts.len() && j < set.contacts.len();
        if same && ns.contacts[j].tip != set.contacts[j].tip {
            let by = sl.dir * lam;
            ns.contacts[j].mode = match ns.contacts[j].mode {
                Mode::Stuck(a) => Mode::Stuck(a - by),
                Mode::Rolling(k) => Mode::Rolling(k - by),
                m => m,
            };
        }
    }
    Next::Switch(ev, ns, nu)
}

/// [`transition`], the places of the new contacts as they are at `pe`.
fn transition_at(
    env: &Env,
    rules: Rules,
    set: &ContactSet,
    cross: Crossing,
    pe: &Pt,
    xf: f64,
) -> Next {
    let friction = rules.friction;
    let u = &pe.u;
    let along = |z: &[f64], beta: f64, p0: [f64; 2]| {
        let (sb, cb) = beta.sin_cos();
        cb * (z[0] + xf - p0[0]) + sb * (z[1] - p0[1])
    };
    match cross {
            Crossing::Slip(j) if rules.slide => {
                let mut ns = set.clone();
                ns.contacts[j].mode = Mode::Sliding(pe.w.contacts[j].breaking_ratio());
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
            Crossing::Lie(j) if matches!(set.contacts[j].geom, Geom::Curve { .. }) => {
                lie_down(env, set, j, pe)
            }
            Crossing::Unlie(_) => peel_up(set, u),
            Crossing::EndLift(j) => end_lift(&pe.w.contacts[j]),
            Crossing::Reach(j) => reach(&pe.w.contacts[j]),
            Crossing::Close(j, k) => close_up(env, set, (j, k), pe),
            Crossing::Lie(j) => Next::Limit(format!(
                "the side contact at s = {:.6} begins to lie along the surface: the rod's curvature relative to the surface there fell to zero, so beyond it the rod would run along the line; a lying stretch pressed by a distributed force is not in the model",
                pe.w.contacts[j].s
            )),
            // the end of a slip: the march in the slip's parameter reached its goal
            Crossing::Stick(_) => Next::Done,
            Crossing::SlipOff(_) => Next::Stop(Event::SlipOff),
            Crossing::Halt(j) => Next::Switch(Event::Halt, held(set, j, pe, xf), u.clone()),
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
                match &env.ground.curve {
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
                let stuck = if friction && set.tip_radius > 0.0 {
                    let geom = Geom::Line { p0, beta };
                    let place = crate::chain::tip_place(set.tip_radius, &geom, pe.sol.right(), xf);
                    Mode::Stuck(place.unwrap_or(f64::NAN))
                } else if friction {
                    Mode::Stuck(along(pe.sol.right(), beta, p0))
                } else {
                    Mode::Free
                };
                touchdown(set, u, ct, s, Contact::on_surface(true, p0, beta, stuck, 0.0))
            }
            Crossing::TipTangent => {
                let j = set.contacts.len() - 1;
                let ct = &set.contacts[j];
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
                let mode = kept_sliding(ct, mode);
                let mut ns = set.clone();
                ns.contacts[j] = Contact::on_surface(false, p0, beta, mode, phi_ref);
                let mut nu = u.clone();
                nu.push(1.0);
                Next::Switch(Event::Touchdown, ns, nu)
            }
            Crossing::PeelBack(j) if set.tip_radius > 0.0 && !set.tip() => {
                Next::Limit(round_tip_peel(set, j, pe))
            }
            Crossing::PeelBack(j) => {
                let ct = &set.contacts[j];
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

/// The mode of the contact `ct` after it changes between tip and side (the tip lies down, a
/// side peels back to the tip): a contact that slides (a passive slider, `T = ratio N`) slides
/// on with its ratio, else `held` (how a new contact holds). Holding a sliding tip where it lay
/// down trapped the stretch between it and a slip's driver 0.027 away, whose tangential forces
/// then changed by 2e7 per unit slide (issue 31).
fn kept_sliding(ct: &Contact, held: Mode) -> Mode {
    match ct.mode {
        Mode::Sliding(r) => Mode::Sliding(r),
        _ => held,
    }
}

/// Why a side on a curved surface stops where the rod begins to curve as the surface does (its
/// relative curvature, the gap's second derivative along the rod, rises to zero): beyond it the
/// rod, tangent there, would cut the surface beside the contact. No second point contact next to
/// it holds the rod instead (between two tangent points of nearly equal curvature the gap would
/// vanish along the whole stretch): the rod would lie along the surface. Where the contact is the
/// last one and the rod's rest beyond it straight, the place is an inflection of the surface, its
/// steepest point.
///
/// The model has the stretch that forms where such a side holds without slip ([`lie_down`]);
/// `why` says what keeps this one out.
pub(crate) fn curve_lie(set: &ContactSet, j: usize, pe: &Pt, why: &str) -> String {
    let c = &pe.w.contacts[j];
    let last = j + 1 == set.contacts.len();
    let unloaded = if last {
        ", the last contact: the rod beyond it is unloaded"
    } else {
        ""
    };
    format!(
        "the side contact at s = {:.6} (x = {:.6}{unloaded}) begins to lie along the surface: \
         the rod's curvature there fell to the surface's, so beyond it the rod, tangent there, \
         would cut the surface beside the contact, and no point contact next to it holds it; \
         {why}",
        c.s, c.x
    )
}

/// What follows an event of a set with a lying stretch (module `chain`, `Lying`) that ends it: a
/// stop where the contacts at or beyond it would change (the stretch letting go beside other
/// contacts, a contact beyond it lifting, lying down or peeling back): not followed. `None` for
/// every other event (its slip is a slip, module `drag`), and without a stretch.
fn stretch_transition(set: &ContactSet, cross: Crossing, pe: &Pt) -> Option<Next> {
    let jl = set.lain()?;
    let c = &pe.w.contacts[jl];
    let beyond = set.contacts.len() - 1 - jl;
    let what = match cross {
        Crossing::Lift(k) if k == jl && set.contacts.len() > 1 => "the stretch lets go",
        Crossing::Lift(k) if k > jl => "a contact beyond it lifts off",
        Crossing::TipTangent if beyond > 0 => "the tip beyond it lies down",
        Crossing::PeelBack(k) if k > jl => "a side beyond it peels back to the tip",
        _ => return None,
    };
    Some(Next::Limit(format!(
        "with a stretch lying on the surface from s = {:.6} to {:.6}, {what}: a change of the \
         contacts at or beyond a lying stretch is not followed",
        c.s, c.lies_to
    )))
}

/// The set after the lying stretch of `set` shrinks back to its outer end (`u` its unknowns):
/// the side contact there again.
fn peel_up(set: &ContactSet, u: &[f64]) -> Next {
    let mut ns = set.clone();
    ns.lying = None;
    let mut nu = u.to_vec();
    if set.n() > ns.n() {
        // (the outer end's place, the last unknown with contacts beyond)
        nu.pop();
    }
    Next::Switch(Event::PeelUp, ns, nu)
}

/// The stop where an end of the lying stretch whose inner end is the contact `c` would pull.
fn end_lift(c: &crate::watch::ContactForce) -> Next {
    let [p1, p2] = c.end_push;
    let (end, s) = if p1 <= p2 {
        ("inner", c.s)
    } else {
        ("outer", c.lies_to)
    };
    Next::Limit(format!(
        "the stretch lying on the surface from s = {:.6} to {:.6} would pull on it at its {end} \
         end, s = {s:.6} (the point forces there: inner {p1:.3e}, outer {p2:.3e}): a stretch \
         whose end lets go while it holds is not in the model",
        c.s, c.lies_to,
    ))
}

/// The neighbours of the side `j` of `set`, driving a slip on a curved surface, that its slide
/// may close up to, laying the free rod between them down on the surface: the sides on the
/// surface next to it and the inner end of the lying stretch (not the tip: a side that reaches
/// the tip peels back, `Crossing::PeelBack`).
fn closing(env: &Env, set: &ContactSet, j: usize) -> Vec<usize> {
    let side = |k: usize| {
        let c = &set.contacts[k];
        !c.tip && matches!(c.geom, Geom::Curve { .. })
    };
    if env.ground.curve.is_none() || !side(j) {
        return Vec::new();
    }
    [j.checked_sub(1), Some(j + 1)]
        .into_iter()
        .flatten()
        .filter(|&k| k < set.contacts.len() && side(k))
        .collect()
}

/// What follows where the side `j` of `set`, sliding, closes up to its neighbour `k` (at `pe`):
/// the rod between them lies along the surface, and the two lie down as one stretch ([`merged`])
/// where the model has it; else the stop, by name ([`closed_up`]). Before the side gets there the
/// point-contact state is singular with the gap (the Newton matrix's smallest singular value over
/// its largest 0.11–0.35 times the gap, from 5.8e-8 down to 1.4e-11, in the stuck states between
/// the slips of issue 31's property seed 11, a side closing up to the stretch), so a slide that
/// nears it is not resolved either ("the branch is not resolved by arclength steps down to
/// 1.2e-10"; rounded, the slide ended at μk with the gap at 1.4e-14, and the stick after it
/// placed a fold by the output grid, its Newton matrix's smallest singular value 8.5e-14 to
/// 4.2e-12 of the largest; two sides of the short rat preset over 0.001 sin(2πx/0.2 + 2π/3)
/// close up over slips that take that ratio from 5.7e-11 down to 3.7e-14): the event is the gap
/// coming within [`CLOSED`].
fn close_up(env: &Env, set: &ContactSet, jk: (usize, usize), pe: &Pt) -> Next {
    merged(env, set, jk, pe)
        .unwrap_or_else(|| Next::Limit(closed_up(set, jk, pe, not_merged(set, jk))))
}

/// The set after the side `j`, driving a slip, closes up to its neighbour `k = j + 1` further
/// on (at `pe`): the rod between them lies along the surface (the gap within [`CLOSED`]), so the
/// two are one lying stretch from `j`'s place on, whose material moves with the slide (the rod is
/// inextensible along it): `j` becomes its inner end, keeping the driver's rolling invariant;
/// `k`, a side, becomes its outer end (with contacts beyond it an unknown, at `k`'s place), or,
/// the inner end of the stretch already lying there, passes its place to `j`. The stretch's
/// resultant starts from the two contacts' forces summed. `None` where the model has no such
/// stretch: a side closing up to the one before it, a second stretch, a driver that does not
/// roll.
fn merged(env: &Env, set: &ContactSet, (j, k): (usize, usize), pe: &Pt) -> Option<Next> {
    if !merges(env, set, (j, k)) {
        return None;
    }
    let (slide, Mode::Rolling(a)) = (env.ground.slide?, set.contacts[j].mode) else {
        return None;
    };
    let inv = a + slide.dir * pe.lam;
    let ck = &pe.w.contacts[k];
    let mut ns = set.clone();
    let outer = match set.lain() {
        Some(_) => None,
        None => {
            let beyond = set.contacts.len() - 1 - k;
            ns.lying = Some(crate::chain::Lying {
                s2: ck.s,
                x2: ck.x,
                c: inv,
                beyond,
                anchor: pe.w.contacts[j].x,
            });
            (beyond > 0).then_some(ck.s)
        }
    };
    let (oj, ok) = (set.offset(j), set.offset(k));
    let mut nu = pe.u.clone();
    nu[oj] += nu[ok];
    nu[oj + 1] += nu[ok + 1];
    nu.drain(ok..ok + set.contacts[k].unknowns());
    nu.extend(outer);
    ns.contacts.remove(k);
    Some(Next::Switch(Event::LieDown, ns, nu))
}

/// Whether the side `j` of `set`, driving a slip, and its neighbour `k` that it closes up to
/// lie down as one stretch ([`merged`]).
pub(crate) fn merges(env: &Env, set: &ContactSet, (j, k): (usize, usize)) -> bool {
    env.ground.slide.is_some_and(|sl| sl.driver == j)
        && matches!(set.contacts[j].mode, Mode::Rolling(_))
        && k == j + 1
        && !set.contacts[k].tip
        && set.lain().is_none_or(|l| l == k)
}

/// Why the side `j` of `set` and its neighbour `k` that it closes up to do not lie down as one
/// stretch ([`merges`] false).
pub(crate) fn not_merged(set: &ContactSet, (j, k): (usize, usize)) -> &'static str {
    if set.lain().is_some_and(|l| l != k) {
        "a second lying stretch is not in the model"
    } else if k < j {
        "a side that closes up to the contact before it, towards the foot, is not in the model"
    } else {
        // (the event is armed only for a side that drives the slip, towards sides: one that
        // does not roll, or a tip, is not met)
        "a stretch from a contact that does not roll is not in the model"
    }
}

/// The words of [`close_up`]'s stop, `why` the model does not follow it (also the stop where a
/// change of set is made with the side already closed up, march.rs `check_pending`, and where
/// the march after the two lay down as one stretch fails in the solver).
pub(crate) fn closed_up(set: &ContactSet, (j, k): (usize, usize), pe: &Pt, why: &str) -> String {
    let (a, b) = (&pe.w.contacts[j], &pe.w.contacts[k]);
    let to = if set.lain() == Some(k) {
        format!("the stretch lying on the surface from s = {:.6}", b.s)
    } else {
        format!("the side contact at s = {:.6}", b.s)
    };
    format!(
        "the side contact at s = {:.6}, sliding, closes up to {to}: the rod between them lies \
         along the surface, so they are one stretch; {why}",
        a.s
    )
}

/// Why the drag ends where two contacts that closed up lay down as one stretch: the march after
/// it failed in the solver (its words follow).
pub(crate) const MERGED_UNRESOLVED: &str =
    "they lie down as one stretch there, whose slide the solver does not resolve";

/// The stop where the unloaded lying stretch whose inner end is the contact `c` reaches the
/// rod's end: beyond, its outer end (where the rod's moment is zero) would lie past the tip, so
/// the rod would lie to its end with a moment there that a free end does not carry. What
/// follows is the tip pressing on the surface beyond the stretch, but that state is singular
/// where it forms (docs/model.md, "A stretch that reaches the rod's end"), and it is not
/// followed.
fn reach(c: &crate::watch::ContactForce) -> Next {
    Next::Limit(format!(
        "the stretch lying on the surface from s = {:.6} reaches the rod's end: beyond, the \
         rod would lie to its end with a moment there that a free end does not carry; the tip \
         pressing on the surface beyond a lying stretch is not followed",
        c.s,
    ))
}

/// How short the free rod between a lying stretch's outer end and the tip beyond it must be for
/// a solver failure there to be the stretch reaching the tip ([`stretch_at_tip`]). Measured: on
/// the short rat preset's drags over 0.003 sin(2πx/0.2 + φ) (φ 0, 2π/3, 4π/3) a side that broke
/// free in a slip drove the stretch beside it towards the tip, and the slide's last converged
/// points left 8.4e-5, 4.4e-4 and 8.6e-4 of free rod; beyond them every correction stalled at
/// residuals of 1e-11 to 2e-8 (tol 1e-12) or turned the tangent by more than 25° at arclength
/// steps of 1e-10.
pub(crate) const NEAR_TIP: f64 = 2e-3;

/// The stop where a march fails in the solver at `p` with the tip pressing just beyond a lying
/// stretch (the free rod between them shorter than [`NEAR_TIP`]): the stretch reaches the tip.
/// Where the free rod vanishes, the tip's force and the stretch's outer end's act at one point
/// and only their sum is determined (docs/model.md, "A stretch that reaches the rod's end" and
/// "A stretch that reaches the tip"): a singular state, which the solver resolves ever more
/// poorly as it nears. `None` elsewhere.
pub(crate) fn stretch_at_tip(set: &ContactSet, p: &Pt) -> Option<String> {
    let jl = set.lain()?;
    if !set.tip() || jl + 2 != set.contacts.len() {
        return None;
    }
    let c = p.w.contacts.get(jl)?;
    let free = 1.0 - c.lies_to;
    (free < NEAR_TIP).then(|| {
        format!(
            "the stretch lying on the surface from s = {:.6} reaches the tip: {free:.1e} of free \
             rod is left between its outer end and the tip, where the two forces come to act at \
             one point with only their sum determined; the tip pressing on the surface at a \
             lying stretch's end is not followed",
            c.s
        )
    })
}

/// The set where the stretch lying on the surface has reached the tip of `set` (at `p`): the
/// tip's contact joins the stretch, whose outer end is again where the rod's moment is zero with
/// the rest beyond unloaded (module `chain`, `Lying`), and `p`'s unknowns without the tip's
/// `(N, T)` and the outer end's. Beyond that place, where the surface's curvature meets the
/// rod's rest curvature, the tip draws back from the surface. `None` where `set` is not a
/// stretch with the tip alone beyond it, or where the tip drives a slide (its place is the
/// slide's parameter).
pub(crate) fn tip_into_stretch(
    env: &Env,
    set: &ContactSet,
    p: &Pt,
) -> Option<(ContactSet, Vec<f64>)> {
    let u = &p.u;
    let jl = set.lain()?;
    let tip = jl + 1;
    let driven = env.ground.slide.is_some_and(|s| s.driver == tip);
    if !set.tip() || tip + 1 != set.contacts.len() || driven || u.len() != set.n() {
        return None;
    }
    let ly = set.lying?;
    let mut ns = set.clone();
    let mut nu = u.to_vec();
    // (the outer end's unknown is the last; the tip's pair the last contact's)
    let s2 = nu.pop()?;
    let o = set.offset(tip);
    nu.drain(o..o + set.contacts[tip].unknowns());
    ns.contacts.pop();
    // (the outer end found again from the inner end's invariant, from the tip's place on)
    ns.lying = Some(crate::chain::Lying {
        s2,
        x2: p.w.contacts.get(tip)?.x,
        c: f64::NAN,
        beyond: 0,
        ..ly
    });
    Some((ns, nu))
}

/// What keeps the side contact `j` of `set`, on a curved surface, that begins to lie along it out
/// of the lying stretch the model has ([`lie_down`]); `None` where it may lie down.
pub(crate) fn lie_kept_out(set: &ContactSet, j: usize) -> Option<&'static str> {
    let ct = &set.contacts[j];
    Some(if set.lying.is_some() {
        "a second lying stretch is not in the model"
    } else if ct.tip
        || !matches!(
            (&ct.geom, ct.mode),
            (
                Geom::Curve { .. },
                Mode::Rolling(_) | Mode::Sliding(_) | Mode::Free
            )
        )
    {
        "a stretch from a contact other than a side on a curved surface is not in the model"
    } else {
        return None;
    })
}

/// Whether the side contact `j` of `set` that lies down slides along the surface with contacts
/// beyond it: the stretch then forms sliding, loaded by them ([`crate::march`] keeps the lie's
/// place as the stop for a failure of the state that follows).
pub(crate) fn lies_sliding_with_beyond(set: &ContactSet, j: usize) -> bool {
    !set.contacts[j].mode.no_slip() && j + 1 < set.contacts.len()
}

/// The set after the side contact `j`, on a curved surface and holding without slip, begins to
/// lie along it (module `chain`, `Lying`): a stretch from there, of no length yet. The unknowns
/// carry over: where the side's curvature reached the surface's, its moment there is the
/// stretch's curvature match (with the rest beyond unloaded, `m = 0` there; with contacts
/// beyond, the outer end is a new unknown, at the side's place). Where [`lie_kept_out`] keeps it
/// out, the stop, with the reason.
pub(crate) fn lie_down(env: &Env, set: &ContactSet, j: usize, pe: &Pt) -> Next {
    if let Some(why) = lie_kept_out(set, j) {
        return Next::Limit(curve_lie(set, j, pe, why));
    }
    let c = &pe.w.contacts[j];
    let mut ns = set.clone();
    let beyond = set.contacts.len() - 1 - j;
    // (the side's rolling invariant; a slip's driver has it moved by the slide so far; a side
    // that slides has none: the stretch's is where its inner end is)
    let inv = match set.contacts[j].mode {
        Mode::Rolling(k) => {
            k + env
                .ground
                .slide
                .filter(|sl| sl.driver == j)
                .map_or(0.0, |sl| sl.dir * pe.lam)
        }
        _ => f64::NAN,
    };
    ns.lying = Some(crate::chain::Lying {
        s2: c.s,
        x2: c.x,
        c: inv,
        beyond,
        anchor: c.x,
    });
    let mut nu = pe.u.clone();
    if beyond > 0 {
        // (its outer end, where the loaded rod beyond it leaves the surface, is an unknown)
        nu.push(c.s);
    }
    Next::Switch(Event::LieDown, ns, nu)
}

/// Why a side lying on the surface cannot peel back to a round tip: its contact point reached
/// the rod's end, where the disk (centred there) would overlap the surface.
fn round_tip_peel(set: &ContactSet, j: usize, pe: &Pt) -> String {
    format!(
        "the side contact at s = {:.6} reached the rod's end, where the round tip (radius {}) \
         would overlap the surface: a side lying under a round tip is not in the model",
        pe.w.contacts[j].s, set.tip_radius
    )
}

/// Why an event could not be located inside its step.
pub(crate) type LocateError = RootError<StepError>;

/// Where the branch polynomial, extrapolated from the last points, predicts `c` to reach 0
/// within `(a, b]` (`None` without a polynomial, or when it does not).
pub(crate) fn predicted_crossing(
    st: &dyn Stepper,
    env: &Env,
    hist: &[Pt],
    (a, b): (f64, f64),
    c: Crossing,
) -> Option<f64> {
    let set = st.set();
    let on_poly = |lam: f64| -> Result<f64, NoValue> {
        let (u, _) = st.interpolant(hist, lam).ok_or(NoValue)?;
        c.of_u(env, set, &u).ok_or(NoValue)
    };
    let (ga, gb) = (on_poly(a).ok()?, on_poly(b).ok()?);
    if !(ga < 0.0 && gb >= 0.0) {
        return None;
    }
    let mut f = on_poly;
    search::root(&mut f, a, b, 1e-15 * (1.0 + b.abs())).ok()
}

/// No polynomial through the history, or an event function that is not one of the unknowns.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct NoValue;

impl std::fmt::Display for NoValue {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("no polynomial")
    }
}

/// The first `λ` in `[a, b]` where `c` reaches 0 (`c(a) < 0 ≤ c(b)`). Where the stepper has
/// the branch as a polynomial and `c` depends on the unknowns alone: Brent's method on that
/// polynomial, refined by Newton steps with solves — one or two solves. Otherwise Brent's
/// method on solves within the step (the event function evaluated on the rod).
pub(crate) fn locate(
    st: &mut dyn Stepper,
    env: &Env,
    hist: &[Pt],
    span: (f64, f64),
    c: Crossing,
) -> Result<Pt, LocateError> {
    // the points tried on the way need only the contacts where the function is of the
    // contacts: their clearance (most of a point's watch) is made for the point found alone
    let light = !matches!(c, Crossing::Touchdown | Crossing::TipTangent);
    st.set_light(light);
    let found = search_event(st, env, hist, span, c);
    st.set_light(false);
    st.complete(found?).map_err(RootError::Caller)
}

/// [`locate`]'s search, on points as the stepper makes them.
fn search_event(
    st: &mut dyn Stepper,
    env: &Env,
    hist: &[Pt],
    (a, b): (f64, f64),
    c: Crossing,
) -> Result<Pt, LocateError> {
    // the events whose values come from the tangent (the slope of |μ|, a slider's slip rate)
    // need the Jacobian at the solution, not the chord corrector's at its prediction: one
    // chord step of ~1e-9 left the tangent off by 1.6e-8 and the slip rate by 1.2e-10, which
    // put a sliding side's halt 7.7e-8 late (issue 31)
    let fresh = matches!(c, Crossing::MuMax | Crossing::Halt(_));
    let set = st.set().clone();
    let poly_val = |st: &dyn Stepper, lam: f64| -> Option<f64> {
        let (u, du) = st.interpolant(hist, lam)?;
        match c {
            Crossing::MuMax => Some(-mu_slope(&set, &u, &du)),
            _ => c.of_u(env, &set, &u),
        }
    };
    if poly_val(&*st, a).is_some() {
        let on_poly: &dyn Stepper = &*st;
        let mut poly = |lam: f64| poly_val(on_poly, lam).ok_or(NoValue);
        if let Ok(mut lam) = search::root(&mut poly, a, b, 1e-15 * (1.0 + b.abs())) {
            let eps = 1e-6 * (b - a);
            for _ in 0..4 {
                let p = st.correct(lam, hist, fresh).map_err(RootError::Caller)?;
                let slope = match (poly_val(&*st, lam + eps), poly_val(&*st, lam - eps)) {
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
    let (p, jump) = search_on_solves(st, env, hist, (a, b), c, fresh)?;
    // a root where the function jumps between the corrector's points: search again with
    // polished points (see `jumped`)
    if jump {
        st.set_polish(true);
        let again = search_on_solves(st, env, hist, (a, b), c, fresh);
        st.set_polish(false);
        if let Ok((q, false)) = again {
            return Ok(q);
        }
    }
    Ok(p)
}

/// Whether a function jumps at the root `root` found, where it is `g`, from `(lam, g_other)`,
/// the nearest point tried on the other side: its change is more than a thousand times what
/// its mean rate over the step, `rate`, gives there and more than 1e-6 of the contacts' total
/// normal force `total` (not the scatter of a trapped pair's forces, ~1e-7 of it). A pair
/// nearly indeterminate (a tip with 0.33 % of the load, nearly tangent to the surface beside a
/// side, tests/contact.rs) had its chord corrector accept predictions at a residual of 9.9e-13
/// (tol 1e-12) that were 5.2e-6 off in the pair's forces, where points one Newton step away
/// were not: its slip was located on that jump, 1.07e-7 in d before its place; searched again
/// on polished points (`rodsolve`'s `large_correction`) it lies 9.4e-10 from its place at tol
/// 1e-12. The scan grids of docs/robustness.md (3867 scenes) and the texture grid's 450 drags
/// come out as before.
fn jumped((root, g): (f64, f64), (lam, g_other): (f64, f64), rate: f64, total: f64) -> bool {
    let change = (g - g_other).abs();
    change > 1e-6 * total && change > 1e3 * rate * (root - lam).abs()
}

/// Brent's method on solves within the step `[a, b]` (the event function evaluated on the
/// rod): the point on the side where the old state holds ([`inside`]), and whether the
/// function [`jumped`] at the root.
fn search_on_solves(
    st: &mut dyn Stepper,
    env: &Env,
    hist: &[Pt],
    (a, b): (f64, f64),
    c: Crossing,
    fresh: bool,
) -> Result<(Pt, bool), LocateError> {
    // the last solve of the search: where it is the root, it is the point (a correction at
    // the same λ from the same history and meshes gives the same point, so it is not redone)
    let mut last: Option<Pt> = None;
    let mut tried: Vec<(f64, f64)> = Vec::new();
    let mut eval = |lam: f64| -> Result<f64, StepError> {
        let p = st.correct(lam, hist, fresh)?;
        let v = c.of_watch(env, &p.w);
        last = Some(p);
        tried.push((lam, v));
        Ok(v)
    };
    let lam = match search::root(&mut eval, a, b, 1e-13 * (1.0 + b.abs())) {
        Ok(lam) => lam,
        // the function at the step's start, solved again, within rounding of zero on the ended
        // side (a threshold below the solver's noise: a drag with mu_s = 1e-300 on a flat
        // surface, whose start has |mu| of order 1e-22): the event is at the start
        Err(RootError::NoBracket { fa, .. }) if ended(fa) && fa <= AT_ZERO => {
            let p = st.correct(a, hist, fresh).map_err(RootError::Caller)?;
            return Ok((p, false));
        }
        Err(e) => return Err(e),
    };
    let p = match last {
        Some(p) if p.lam.to_bits() == lam.to_bits() => p,
        _ => st.correct(lam, hist, fresh).map_err(RootError::Caller)?,
    };
    let g = c.of_watch(env, &p.w);
    // the step's mean rate, from its ends (the first two points tried)
    let rate = match tried[..] {
        [(la, ga), (lb, gb), ..] if lb != la => ((gb - ga) / (lb - la)).abs(),
        _ => f64::INFINITY,
    };
    // the nearest point tried on the other side of the root
    let other = (tried.iter())
        .filter(|&&(_, v)| ended(v) != ended(g))
        .min_by(|x, y| (x.0 - lam).abs().total_cmp(&(y.0 - lam).abs()))
        .copied();
    let p = inside(st, env, hist, a, p, c, fresh).map_err(RootError::Caller)?;
    let total: f64 = p.w.contacts.iter().map(|c| c.normal.abs()).sum();
    let jump = other.is_some_and(|o| jumped((lam, g), o, rate, total));
    Ok((p, jump))
}

/// The located event point on the side where the old state still holds (`c ≤ 0`): a root to
/// ~1e-13 in λ may lie a rounding beyond it (a free part ~1e-12 above the surface); then λ
/// moves back by twice the secant step towards `a`, doubling until the point is inside (up to
/// 40 times, and never past `a`, where it holds). Where the rod is trapped between two contacts
/// that hold (a stuck side and a round tip, issue 31), the forces carry the shot's rounding
/// amplified to ~1e-8, which one more Newton step with the exact Jacobian does not lower: a
/// side's `|T| − μs N` read 9.2e-9, 1.3e-8, 3.4e-9, 1.1e-8, ... at points 3e-14 to 4e-12 back
/// in `d`, where its mean rate over the stick is 570. A secant step from a value of that noise
/// is ~1e-14, and the eight doublings once allowed ended 4e-12 back, still beyond, leaving the
/// point 4.7e-10 beyond `μs N`; the ninth, 8e-12 back, is inside.
fn inside(
    st: &mut dyn Stepper,
    env: &Env,
    hist: &[Pt],
    a: f64,
    p: Pt,
    c: Crossing,
    fresh: bool,
) -> Result<Pt, StepError> {
    let g = c.of_watch(env, &p.w);
    if !beyond(g) {
        return Ok(p);
    }
    let ga = hist
        .iter()
        .find(|q| q.lam == a)
        .map_or(-1.0, |q| c.of_watch(env, &q.w));
    let secant = g * (p.lam - a) / (g - ga);
    for k in 0..40 {
        let lam = (p.lam - 2.0 * secant * 2f64.powi(k)).max(a);
        let q = st.correct(lam, hist, fresh)?;
        if !beyond(c.of_watch(env, &q.w)) {
            return Ok(q);
        }
        if lam == a {
            break;
        }
    }
    Ok(p)
}

/// The first maximum of `|μ|` in `(prev.λ, l_stop]`, if there is one: the root of `d|μ|/dλ`
/// where tangents are known, else (three-point pattern) Brent's maximizer.
pub(crate) fn first_max(
    st: &mut dyn Stepper,
    env: &Env,
    hist: &[Pt],
    (prev, pprev): (&Watch, Option<&Watch>),
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
        let p = locate(st, env, hist, (prev.lam, w.lam), Crossing::MuMax).ok()?;
        return (p.lam <= l_stop).then_some(p.w);
    }
    let pp = pprev?;
    if !(prev.mu.abs() > pp.mu.abs() && prev.mu.abs() >= w.mu.abs()) {
        return None;
    }
    let mut eval =
        |lam: f64| -> Result<f64, StepError> { Ok(st.correct(lam, hist, false)?.w.mu.abs()) };
    let (lam, _) = search::maximize(&mut eval, pp.lam, w.lam.min(l_stop), 1e-12).ok()?;
    Some(st.correct(lam, hist, false).ok()?.w)
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
