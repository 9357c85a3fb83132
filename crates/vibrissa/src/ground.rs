//! Where a scan or a drag starts on any surface: the straight line (module `start`) or a curved
//! profile (module `surface`), and the march's view of it.
//!
//! On a curved profile the rod is pressed onto the profile's straight trend as on a line, and
//! the profile's shape is grown from zero to its full amplitude (see [`curve_start`]). (Pressing
//! a straight rod vertically onto a corrugation folds: the frictionless tip snaps down a slope.)

use crate::chain::{Chain, Contact, ContactSet, Family, Geom, Mode};
use crate::events::{transition, Crossing, Next, Rules, AT_ZERO};
use crate::march::{march, Spec};
use crate::own::OwnStepper;
use crate::profile::Profile;
use crate::report::StopReason;
use crate::start::Pressed;
use crate::stepper::{Pt, StepError, Stepper};
use crate::surface::{Ground, Height};
use crate::watch::Env;
use crate::{Rod, Surface, VibrissaError};
use bvp::Stats;
use std::sync::Arc;

/// The march's view of a surface: the line (through `p0`, inclination β) or the curve, the
/// texture.
pub(crate) fn env_of(surface: &Surface, p0: [f64; 2], mu0: Option<f64>, compound: bool) -> Env {
    Env {
        line: match surface.profile() {
            Some(_) => None,
            None => Some((p0, surface.angle())),
        },
        mu0,
        compound,
        target: None,
        ground: Ground {
            curve: surface.profile_shared(),
            texture: surface.texture_shared(),
            ..Ground::default()
        },
    }
}

/// The start of a scan or a drag on `surface`: the pressed state and the drag's contact set
/// (tips stuck, sides rolling) with a point of the surface (the last contact).
pub(crate) fn start<P: Profile>(
    rod: &Rod,
    profile: &P,
    surface: &Surface,
    kind: crate::StartKind,
    tol: f64,
) -> Result<(Pressed<P>, ContactSet, [f64; 2]), VibrissaError> {
    surface.check_tip(rod.tip_radius())?;
    match surface.profile_shared() {
        None => {
            let start = crate::start::scan_start(rod, profile, surface, kind, tol)?;
            let (set, p0) = crate::start::stuck(&start, surface.angle());
            Ok((start, set, p0))
        }
        Some(h) => {
            if kind == crate::StartKind::Connected {
                return Err(VibrissaError::MethodUnavailable {
                    method: "start = connected".into(),
                    reason: "a curved surface profile starts from the rod pressed onto it \
                             (start = pressed)"
                        .into(),
                });
            }
            let pressed = curve_start(rod, profile, surface, &h, tol)?;
            let (set, u) = stuck(&pressed, &h, 0.0);
            let p0 = {
                let z = pressed.pt.sol.right();
                [z[0], z[1]]
            };
            let mut pressed = pressed;
            pressed.pt.u = u;
            Ok((pressed, set, p0))
        }
    }
}

/// The start on the curved profile `h`: the rod pressed onto its straight trend (the line
/// `η + x·tan β` through the contact at height η, module `start`), then the profile's shape grown
/// from zero to its full amplitude with the contacts frictionless: the one march in the
/// amplitude `t ∈ [0, 1]` (family `Grow`), the contact points sliding to where the force is
/// normal to the profile, sides touching down, lying parts peeling back, as in any march. The
/// press on the line keeps its handling of first touch and buckling. A free part of the pressed
/// rod lying on the trend (a straight tail beyond a side contact) is settled on the profile at a
/// small amplitude first ([`grow`], [`settle`]).
///
/// Where that fails (the grown profile's equilibria end short of its full amplitude: a snap, a
/// stretch that reaches the rod's end, a state the model does not follow), the profile is
/// grown at a lighter press instead, the line at `η' = η + f·(η_top − η)` for the fractions
/// [`LIGHTER`] of the way to first touch `η_top` (where the lightly bent rod rides the growing
/// profile on fewer contacts), and the rod then pressed down onto the full profile to η (the
/// march in the depth, family `Press`). The pressed state is the same kind of state — the rod
/// at rest on the full profile at η, every contact frictionless — reached along another path;
/// a start found the first way is never looked for the second. Where that fails too, the
/// profile is grown at η once more with the tail's crossing beyond the last side laid down as
/// a stretch ([`Settle::Lie`]); where that fails, the error is the first path's.
fn curve_start<P: Profile>(
    rod: &Rod,
    profile: &P,
    surface: &Surface,
    h: &Arc<Height>,
    tol: f64,
) -> Result<Pressed<P>, VibrissaError> {
    let first = grown_start(rod, profile, surface, h, tol, None, false);
    let e = match first {
        Err(e) if !e.is_input() => e,
        done => return done,
    };
    let eta = surface.eta();
    let top = crate::start::rest_reach(rod, profile, surface.angle(), tol);
    let mut last = None;
    for f in LIGHTER {
        let light = eta + f * (top - eta);
        if !(light > eta && light < top) {
            continue;
        }
        match grown_start(rod, profile, surface, h, tol, Some(light), false) {
            Ok(p) => return Ok(p),
            Err(e) => last = Some((light, e)),
        }
    }
    // (the last resort: at η, a tail crossing beyond the last side laid down as a stretch)
    if let Ok(p) = grown_start(rod, profile, surface, h, tol, None, true) {
        return Ok(p);
    }
    Err(match (e, last) {
        (VibrissaError::NoStart { reason }, Some((light, e))) => VibrissaError::NoStart {
            reason: format!(
                "{reason}; grown at lighter presses and pressed down (the last from eta' = \
                 {light:.6}): {e}"
            ),
        },
        (e, _) => e,
    })
}

/// The fractions of the way from η to the rod's first touch at which [`curve_start`] grows the
/// profile where growing it at η fails, in the order tried.
const LIGHTER: [f64; 3] = [0.5, 0.25, 0.75];

/// The start of [`curve_start`]: the rod pressed onto the straight trend at η (`light` None)
/// or at the lighter `light` (then the profile grown there and the rod pressed down onto it);
/// `lie`: the last resort of [`curve_start`] ([`grow`]).
fn grown_start<P: Profile>(
    rod: &Rod,
    profile: &P,
    surface: &Surface,
    h: &Arc<Height>,
    tol: f64,
    light: Option<f64>,
    lie: bool,
) -> Result<Pressed<P>, VibrissaError> {
    let line = Surface::new(light.unwrap_or(surface.eta()), surface.angle())?;
    let pressed = crate::start::scan_start(rod, profile, &line, crate::StartKind::Pressed, tol)?;
    // the pressed line n·r = h in the lab frame: y = h / cos β + x tan β; the profile's trend
    // y = η + x tan β lies off0 below it (at a lighter press the profile grows there: off1)
    let off0 = pressed.h / surface.angle().cos() - surface.eta();
    let off1 = if light.is_some() { off0 } else { 0.0 };
    let set = ContactSet {
        contacts: pressed
            .set
            .contacts
            .iter()
            .map(|c| Contact {
                geom: Geom::Curve { h: h.clone() },
                ..*c
            })
            .collect(),
        tip_radius: pressed.set.tip_radius,
        lying: None,
    };
    let mut st = OwnStepper {
        chain: Chain::new(pressed.sh, set, Family::Grow { off0, off1 }),
        env: Env {
            line: None,
            mu0: None,
            compound: true,
            target: None,
            ground: Ground {
                curve: Some(h.clone()),
                grow: true,
                ..Ground::default()
            },
        },
        cancel: Default::default(),
        light: false,
        polish: false,
        retangent: false,
    };
    let fail = |what: &dyn std::fmt::Display, e: &dyn std::fmt::Display| VibrissaError::NoStart {
        reason: format!("growing the surface profile from its straight trend: {what}: {e}"),
    };
    let p0 = st
        .correct_from(0.0, &pressed.pt.u, None, true)
        .map_err(|e| fail(&"the pressed rod", &e))?;
    let (set, end) = grow(&mut st, p0, rod, profile, lie).map_err(|e| match e {
        GrowError::Snap { amplitude } => VibrissaError::StartSnaps { amplitude },
        GrowError::Lies {
            amplitude,
            s,
            spacing,
        } => VibrissaError::StartLies {
            amplitude,
            s,
            spacing,
        },
        GrowError::Failed(what, e) => fail(&what, &e),
    })?;
    let (set, end) = match light {
        None => (set, end),
        Some(light) => press_down(&mut st, (set, end), rod, profile, off1)
            .map_err(|e| fail(&format!("pressed down from eta' = {light:.6}"), &e))?,
    };
    // the grown profile is the drag's at d = 0
    st.chain.family = Family::Drag;
    st.env.ground.grow = false;
    let pt = st
        .switch(set, 0.0, end.u)
        .map_err(|e| fail(&"the rod on the profile", &e))?;
    if let Some(c) =
        pt.w.contacts
            .iter()
            .find(|c| c.normal.is_nan() || c.normal <= 0.0)
    {
        return Err(VibrissaError::OutOfReach {
            what: format!(
                "on the surface profile the rod's contact at s = {:.6} (x = {:.6}) needs a pull \
                 (normal force {:.6e})",
                c.s, c.x, c.normal
            ),
            reach: c.normal,
            needed: 0.0,
        });
    }
    let mut stats = pressed.stats;
    stats.accumulate(&st.chain.sh.stats);
    Ok(Pressed {
        sh: st.chain.sh,
        set: st.chain.set,
        pt,
        p0: pressed.p0,
        h: 0.0,
        goal: pressed.goal,
        stats,
    })
}

/// The rod on the full profile lifted by `off` (the march in the amplitude's end, `(set, end)`)
/// pressed down onto the profile itself: the march in the depth `λ ∈ [0, off]` (family
/// `Press`, the surface's height `off − λ`), its contacts frictionless as in the growth. Its
/// contact set and last point, or how it ended short.
fn press_down<P: Profile>(
    st: &mut OwnStepper<P>,
    (set, end): (ContactSet, Pt),
    rod: &Rod,
    profile: &P,
    off: f64,
) -> Result<(ContactSet, Pt), PressDownError> {
    st.chain.family = Family::Press { h0: off };
    st.env.ground.grow = false;
    let q = st.switch(set, 0.0, end.u).map_err(PressDownError::Lifted)?;
    let spec = Spec {
        env: &st.env.clone(),
        grid: &[],
        lam_end: off,
        keep_shapes: None,
        general: &rod.profile(1.0),
        friction: false,
        check_start: false,
        slide: false,
        pass_fold_ahead: false,
        retangent: false,
    };
    let out = march(st, &spec, profile, q, Stats::default());
    match (&out.stop, out.last) {
        (StopReason::DMax, Some((set, pt))) if pt.lam == off => Ok((set, pt)),
        (stop, _) => Err(PressDownError::Short(stop.clone())),
    }
}

/// Why [`press_down`] did not reach the profile itself.
#[derive(Debug, thiserror::Error)]
enum PressDownError {
    /// The grown state is not solved again in the family of the press.
    #[error("the rod on the lifted profile: {0}")]
    Lifted(StepError),
    /// The march in the depth ended short of the profile (its stop).
    #[error("the march in the depth: {}", .0.describe("depth"))]
    Short(StopReason),
}

/// The pressed state on a curve as the start of a drag (foot at `xf`): the tip stuck at its arc
/// length along the profile, its force frame turned to the local normal there (so that the
/// unknowns are the local normal and friction forces while it sticks), the sides rolling. The
/// contact set and the unknowns in it.
pub(crate) fn stuck<P: Profile>(
    p: &Pressed<P>,
    h: &Arc<Height>,
    xf: f64,
) -> (ContactSet, Vec<f64>) {
    let mut u = p.pt.u.clone();
    let contacts: Vec<Contact> = p
        .set
        .contacts
        .iter()
        .enumerate()
        .map(|(j, c)| {
            let s = p.set.s_of(j, &p.pt.u);
            // (the watch found the contact's place on the rod itself)
            let x = p.pt.w.contacts[j].x + xf;
            if c.tip {
                let o = p.set.offset(j);
                let (nl, tl) = crate::chain::local_forces(c, u[o], u[o + 1], x);
                u[o] = nl;
                u[o + 1] = tl;
                // (a round tip's place includes its turn: it rolls; its x is the contact point's)
                let r = p.set.tip_radius;
                let place = if r > 0.0 {
                    let geom = Geom::Curve { h: h.clone() };
                    crate::chain::tip_place(r, &geom, p.pt.sol.right(), xf).unwrap_or(f64::NAN)
                } else {
                    h.sigma(x).0
                };
                Contact::on_curve(true, h, x, Mode::Stuck(place), 0.0)
            } else {
                let th = h.angle(x).0;
                let dir = (c.phi_ref - th).cos().round();
                Contact {
                    mode: Mode::Rolling(h.sigma(x).0 - dir * s),
                    ..c.clone()
                }
            }
        })
        .collect();
    // (a stretch lying from the start rolls with its inner end's invariant)
    let lying = p.set.lying.map(|ly| {
        let c = match p.set.lain().map(|j| &contacts[j].mode) {
            Some(&Mode::Rolling(c)) => c,
            _ => f64::NAN,
        };
        crate::chain::Lying { c, ..ly }
    });
    (
        ContactSet {
            contacts,
            tip_radius: p.set.tip_radius,
            lying,
        },
        u,
    )
}

/// The amplitudes at which [`settle`] finds the contacts of a rod whose free part lies on the
/// straight trend, in the order tried where the march from amplitude 0 ends short of the full
/// profile: the first that settles and grows to the full profile is the start.
const SETTLE_AT: [f64; 3] = [1e-3, 1e-2, 3e-2];

/// Where those fail too: larger amplitudes, at which the settled contacts lie apart (at small
/// amplitudes a lying tail settles into contacts 1e-4 of the rod apart with the rod between
/// them within rounding of the profile, which the march cannot follow), each settled with
/// [`Settle::Careful`].
const SETTLE_LATER: [f64; 3] = [0.1, 0.3, 1.0];

/// How far in the amplitude [`resume`] settles the rod beyond the point where a march in the
/// amplitude found no contact state to continue with, in the order tried.
const RESUME_STEP: [f64; 2] = [1e-4, 1e-3];

/// How many times the march in the amplitude is resumed ([`resume`]) before the start fails.
const RESUMES: usize = 8;

/// Two contacts closer than this along the rod (of length 1) are a stretch of the rod lying
/// along the profile: the point-contact model does not resolve it (the segment between them,
/// of stiffness EI/ℓ³, is at least 1e9 times stiffer than the rod, and its Newton iterations
/// stall or its branch seems to turn back at every step).
const LYING_SPACING: f64 = 1e-3;

/// How a march in the amplitude that does not reach the full profile ends.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Short {
    /// In a fold (a snap) at this amplitude.
    Snap(f64),
    /// Where the rod begins to lie along the profile (amplitude, s, spacing): see [`lies`].
    Lies(f64, f64, f64),
    /// Otherwise.
    Other,
}

/// Where the rod lies along the profile between two neighbouring contacts of `set` at `q`:
/// they are closer than [`LYING_SPACING`] along the rod, or the free rod between them touches
/// the profile to [`AT_ZERO`] (a third point where no contact holds). The first one's place
/// and their spacing. (On the scenes of issue 31 with contacts that close, the rod's curvature
/// at both equals the profile's there to 1e-3: the rod between them follows the profile.)
fn lies(set: &ContactSet, q: &Pt) -> Option<(f64, f64)> {
    let at: Vec<f64> = (0..set.contacts.len()).map(|j| set.s_of(j, &q.u)).collect();
    let touches =
        |w: &[f64]| q.w.clear.abs() <= AT_ZERO && w[0] < q.w.clear_s && q.w.clear_s < w[1];
    at.windows(2)
        .find(|w| w[1] - w[0] < LYING_SPACING || touches(w))
        .map(|w| (w[0], w[1] - w[0]))
}

/// How a march ended short at `(stop, last)`: a fold is a snap unless its state has the rod
/// lying along the profile ([`lies`]; then its branch is not resolved).
fn short(stop: &StopReason, last: Option<&(ContactSet, Pt)>) -> Short {
    match (stop, last) {
        (StopReason::FoldInD { d }, l) if l.is_none_or(|(set, q)| lies(set, q).is_none()) => {
            Short::Snap(*d)
        }
        (_, Some((set, q))) => match lies(set, q) {
            Some((s, gap)) => Short::Lies(q.lam, s, gap),
            None => Short::Other,
        },
        _ => Short::Other,
    }
}

/// Why the profile could not be grown to its full amplitude.
enum GrowError {
    /// The pressed rod snaps as the profile grows: its equilibria fold back at the amplitude
    /// `amplitude` (of 1) and no march found a way past.
    Snap { amplitude: f64 },
    /// The rod begins to lie along the profile at the amplitude `amplitude`: between two of
    /// its contacts, at `s` and `spacing` beyond ([`lies`]).
    Lies {
        amplitude: f64,
        s: f64,
        spacing: f64,
    },
    /// What failed (and why).
    Failed(&'static str, String),
}

/// The march in the amplitude from the rod pressed on the straight trend, `p0` (amplitude 0),
/// to the full profile: its contact set and last point there, or what failed (and why). Where a
/// free part lies on the trend at `p0` and that march ends short, the rod is settled on the
/// profile at a small amplitude ([`settle`]) and the march goes on from there. Where every
/// such march ends at a change of contacts that it does not resolve (a touchdown whose new
/// state Newton does not solve, a jump of the highest free point that no event locates), the
/// march is resumed from where it ended ([`resume`]); where a free part lies on the trend, the
/// rod is settled at the larger amplitudes [`SETTLE_LATER`] as well. A march that ends in a
/// fold is a snap; one whose last state has the rod lying along the profile between two
/// contacts ([`lies`]), a rod lying down ([`short`]). With `lie`, only the settled marches
/// are tried, each settled with [`Settle::Lie`] at the small amplitudes [`SETTLE_AT`].
fn grow<P: Profile>(
    st: &mut OwnStepper<P>,
    p0: Pt,
    rod: &Rod,
    profile: &P,
    lie: bool,
) -> Result<(ContactSet, Pt), GrowError> {
    let spec = Spec {
        env: &st.env.clone(),
        grid: &[],
        lam_end: 1.0,
        keep_shapes: None,
        general: &rod.profile(1.0),
        friction: false,
        check_start: false,
        slide: false,
        pass_fold_ahead: false,
        retangent: false,
    };
    // (the march from amplitude 0 first, as for any start: where it grows the profile, the
    // start is what it was before settling existed)
    let lying_tail = lying(&p0);
    let n = if lying_tail { SETTLE_AT.len() + 1 } else { 1 };
    let set0 = st.chain.set.clone();
    let mut first_failure: Option<(&'static str, String)> = None;
    let mut ended: Vec<(StopReason, Option<(ContactSet, Pt)>)> = Vec::new();
    let how = if lie { Settle::Lie } else { Settle::First };
    for &t in [0.0]
        .iter()
        .chain(&SETTLE_AT)
        .take(n)
        .skip(usize::from(lie))
    {
        st.chain.set = set0.clone();
        let from = if t > 0.0 {
            match settle(st, &p0, t, how) {
                Ok(q) => q,
                Err(e) => {
                    note(&mut first_failure, t, e.to_string());
                    continue;
                }
            }
        } else {
            p0.clone()
        };
        let out = march(st, &spec, profile, from, Stats::default());
        match (&out.stop, out.last) {
            (StopReason::DMax, Some((set, pt))) if pt.lam == 1.0 => return Ok((set, pt)),
            (stop, last) => {
                if t == 0.0 {
                    first_failure = Some(("the march in the amplitude", stop.describe("d")));
                } else {
                    note(
                        &mut first_failure,
                        t,
                        format!("then {}", stop.describe("d")),
                    );
                }
                ended.push((stop.clone(), last));
            }
        }
    }
    // (what follows runs only where every march above ended short: a start that grew before
    // is what it was)
    let later = if lying_tail && !lie {
        &SETTLE_LATER[..]
    } else {
        &[]
    };
    for &t in later {
        st.chain.set = set0.clone();
        if let Ok(q) = settle(st, &p0, t, Settle::Careful) {
            let out = march(st, &spec, profile, q, Stats::default());
            match (&out.stop, out.last) {
                (StopReason::DMax, Some((set, pt))) if pt.lam == 1.0 => return Ok((set, pt)),
                (stop, last) => ended.push((stop.clone(), last)),
            }
        }
    }
    let mut ends = Vec::new();
    for (stop, last) in ended {
        let resumable = matches!(
            stop,
            StopReason::ContactChange { .. } | StopReason::SolverFailure { .. }
        );
        match (short(&stop, last.as_ref()), last) {
            (Short::Other, Some(l)) if resumable => match resume(st, &spec, profile, l) {
                Ok(done) => return Ok(done),
                Err(e) => ends.push(e),
            },
            (e, _) => ends.push(e),
        }
    }
    // (the earliest amplitude at which the rod snaps, else lies down)
    let first = |f: fn(&Short) -> Option<[f64; 3]>| {
        ends.iter()
            .filter_map(f)
            .min_by(|a, b| a[0].total_cmp(&b[0]))
    };
    if let Some([amplitude, ..]) = first(|e| match *e {
        Short::Snap(d) => Some([d, 0.0, 0.0]),
        _ => None,
    }) {
        return Err(GrowError::Snap { amplitude });
    }
    if let Some([amplitude, s, spacing]) = first(|e| match *e {
        Short::Lies(d, s, gap) => Some([d, s, gap]),
        _ => None,
    }) {
        return Err(GrowError::Lies {
            amplitude,
            s,
            spacing,
        });
    }
    let (what, why) = first_failure.unwrap_or(("the march in the amplitude", "no start".into()));
    Err(GrowError::Failed(what, why))
}

/// The march in the amplitude resumed from its last point `(set, p)`, where it found no contact
/// state to continue with: the rod settled ([`settle`], [`Settle::Careful`]) a little further
/// on ([`RESUME_STEP`]) and marched from there, at most [`RESUMES`] times. The full profile's
/// contact set and point, else how the last march ended short ([`short`]: one that ends with
/// the rod lying along the profile, [`lies`], is not resumed).
fn resume<P: Profile>(
    st: &mut OwnStepper<P>,
    spec: &Spec<'_>,
    profile: &P,
    (mut set, mut p): (ContactSet, Pt),
) -> Result<(ContactSet, Pt), Short> {
    for _ in 0..RESUMES {
        let settled = RESUME_STEP.iter().find_map(|&dt| {
            st.chain.set = set.clone();
            settle(st, &p, (p.lam + dt).min(1.0), Settle::Careful).ok()
        });
        let q = settled.ok_or(Short::Other)?;
        let out = march(st, spec, profile, q, Stats::default());
        match (out.stop, out.last) {
            (StopReason::DMax, Some((s, pt))) if pt.lam == 1.0 => return Ok((s, pt)),
            (
                stop @ (StopReason::ContactChange { .. } | StopReason::SolverFailure { .. }),
                Some(l),
            ) if short(&stop, Some(&l)) == Short::Other => {
                (set, p) = l;
            }
            (stop, last) => return Err(short(&stop, last.as_ref())),
        }
    }
    Err(Short::Other)
}

/// Adds to the failure of the march from amplitude 0 the first failure of a start settled at
/// amplitude `t`.
fn note(failure: &mut Option<(&'static str, String)>, t: f64, e: String) {
    if let Some((_, msg)) = failure {
        if !msg.contains("; settled at amplitude") {
            msg.push_str(&format!(
                "; settled at amplitude {t} instead (the rod lying on the straight trend): {e}"
            ));
        }
    }
}

/// Whether a free part of the rod lies on the straight trend at `p` (amplitude 0): its largest
/// height above it is zero to rounding, away from the foot (a straight unloaded tail beyond a
/// side contact, as on a tapered rod pressed deep).
fn lying(p: &Pt) -> bool {
    p.w.clear.abs() <= LYING && p.w.clear_s > 0.0
}

/// How close to the straight trend a free part lies at amplitude 0 (rounding of the rod's
/// heights is ~1e-14; a free part this close that does not lie would have to be tangent to the
/// trend without a contact).
const LYING: f64 = 1e-10;

/// How [`settle`] chooses among the contact states it tries after a touchdown.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Settle {
    /// The first that is solved.
    First,
    /// As `First`, but never a state it reached before (a contact added where Newton does not
    /// solve it, and its neighbour released instead, can give back the state it left), and
    /// where the crossing is beyond the last side, that side laid down as a stretch
    /// ([`lie_tail`]) is tried too. The last resort of [`grow`]: a start found before these
    /// existed is found as it was.
    Lie,
    /// The first solved that holds, else the first solved; never one it reached before (the
    /// same contacts at the same places), which would cycle (a tip that touches down and
    /// pulls, released, touching down again).
    Careful,
}

/// The rod at amplitude `t` from the state `p` at a smaller amplitude (0, where its free part
/// lies on the straight trend; or where a march in the amplitude ended, see [`resume`]). Every
/// point of a lying part touches at 0, so the contacts the grown profile
/// makes begin there at once (a touchdown at the march's start, with no place singled out
/// along the lying part); they are found at the amplitude `t` itself, as an active set:
/// the state solved with the contacts so far, then a contact that pulls released, a touching
/// tip that turns into the profile laid down, or a contact added where the rod crosses the
/// profile most (beside the others, else in place of its neighbour before or after it, which
/// passes it its load; with [`Settle::Lie`], where the crossing is beyond the last side, that
/// side laid down as a stretch), until the state holds (no pull, no crossing beyond
/// [`AT_ZERO`]). The contacts are frictionless, as in the march in the amplitude. (On taper 0.3
/// over 0.001 sin(2πx/0.2 + 2π/3), tests/start_texture.rs, the stretch laid down so pushes at
/// both ends at the start, 0.43 and 0.29.)
fn settle<P: Profile>(
    st: &mut OwnStepper<P>,
    p: &Pt,
    t: f64,
    how: Settle,
) -> Result<Pt, SettleError> {
    let rules = Rules {
        friction: false,
        slide: false,
    };
    let env = st.env.clone();
    let mut set = st.chain.set.clone();
    let mut q = st
        .switch(set.clone(), t, p.u.clone())
        .map_err(SettleError::Start)?;
    let mut seen = vec![place(&set, &q)];
    for _ in 0..SETTLE_CHANGES {
        let pull = (0..set.contacts.len())
            .filter(|&j| q.w.contacts[j].normal < 0.0)
            .min_by(|&a, &b| q.w.contacts[a].normal.total_cmp(&q.w.contacts[b].normal));
        let cross = if let Some(j) = pull {
            Crossing::Lift(j)
        } else if q.w.tip_approach < 0.0 {
            Crossing::TipTangent
        } else if q.w.clear > AT_ZERO {
            Crossing::Touchdown
        } else {
            return Ok(q);
        };
        let Next::Switch(_, ns, nu) = transition(&env, rules, &set, cross, &q, 0.0) else {
            return Err(SettleError::NoState {
                cross,
                set: set.label(),
            });
        };
        let mut tries = vec![(ns.clone(), nu.clone())];
        let added = ns.contacts.iter().position(|c| !set.contacts.contains(c));
        if let (Crossing::Touchdown, Some(k)) = (cross, added) {
            for j in [k.checked_sub(1), Some(k + 1)].into_iter().flatten() {
                if j < ns.contacts.len() {
                    let mut mu = nu.clone();
                    mu[ns.offset(k)] = nu[ns.offset(j)];
                    tries.push(without(&ns, &mu, j));
                }
            }
        }
        if how == Settle::Lie {
            tries.extend(lie_tail(&env, &set, cross, &q));
        }
        let mut failed = None;
        let mut next = None;
        let mut solved: Option<(ContactSet, Pt)> = None;
        for (ts, tu) in tries {
            match st.switch(ts.clone(), t, tu) {
                Ok(r)
                    if how == Settle::First
                        || !seen.contains(&place(&ts, &r))
                            && (how == Settle::Lie || settled(&r)) =>
                {
                    next = Some((ts, r));
                    break;
                }
                Ok(r) => {
                    if solved.is_none() && !seen.contains(&place(&ts, &r)) {
                        solved = Some((ts, r));
                    }
                }
                Err(error) => {
                    failed = Some(SettleError::Switch {
                        set: ts.label(),
                        cross,
                        error,
                    })
                }
            }
        }
        if next.is_none() {
            // (the stepper holds the last state tried: the one chosen, solved again)
            if let Some((ts, r)) = solved {
                next = Some((
                    ts.clone(),
                    st.switch(ts, t, r.u).map_err(SettleError::Start)?,
                ));
            }
        }
        let Some(n) = next else {
            return Err(failed.unwrap_or(SettleError::NoState {
                cross,
                set: set.label(),
            }));
        };
        (set, q) = n;
        seen.push(place(&set, &q));
    }
    Err(SettleError::Unsettled { set: set.label() })
}

/// Where a touchdown `cross` of `set` at `q` crosses the profile beyond its last contact, a
/// side with the rod beyond it unloaded: that side laid down as a stretch
/// ([`crate::events::lie_down`]), its outer end where the moment vanishes. (A straight tail
/// that lay on the trend at amplitude 0 over a hollow of the grown profile follows the hollow
/// out to where its curvature falls to the rod's, not from one point contact to the next.)
fn lie_tail(
    env: &Env,
    set: &ContactSet,
    cross: Crossing,
    q: &Pt,
) -> Option<(ContactSet, Vec<f64>)> {
    let j = set.contacts.len().checked_sub(1)?;
    let beyond = q.w.clear_s > set.s_of(j, &q.u);
    if cross != Crossing::Touchdown || !beyond || crate::events::lie_kept_out(set, j).is_some() {
        return None;
    }
    match crate::events::lie_down(env, set, j, q) {
        Next::Switch(_, ns, nu) => Some((ns, nu)),
        _ => None,
    }
}

/// Whether the state `q` holds as [`settle`] asks: no contact pulls, a touching tip does not
/// turn into the profile, no free part crosses it beyond [`AT_ZERO`].
fn settled(q: &Pt) -> bool {
    // (as the active set of [`settle`] reads them: NaN neither pulls, turns nor crosses)
    let turns = q.w.tip_approach < 0.0;
    let crosses = q.w.clear > AT_ZERO;
    let pulls = q.w.contacts.iter().any(|c| c.normal < 0.0);
    !pulls && !turns && !crosses
}

/// A state's contacts and their places along the rod (to 1e-9), which [`Settle::Careful`]
/// does not return to.
fn place(set: &ContactSet, q: &Pt) -> (String, Vec<i64>) {
    let at = (0..set.contacts.len())
        .map(|j| (set.s_of(j, &q.u) * 1e9).round() as i64)
        .collect();
    (set.label(), at)
}

/// Why [`settle`] found no state at its amplitude.
#[derive(Debug, thiserror::Error)]
enum SettleError {
    /// The state with the contacts at amplitude 0 is not solved at the small amplitude.
    #[error("{0}")]
    Start(StepError),
    /// The change `cross` of the set `set` leaves no contact state.
    #[error("{cross:?} in {set} leaves no contact state")]
    NoState { cross: Crossing, set: String },
    /// No state tried after the change `cross` is solved (the last one's error).
    #[error("{set} ({cross:?}): {error}")]
    Switch {
        set: String,
        cross: Crossing,
        error: StepError,
    },
    /// No state holds after [`SETTLE_CHANGES`] changes.
    #[error("no contact state holds after {SETTLE_CHANGES} changes ({set})")]
    Unsettled { set: String },
}

/// Changes of the contact set [`settle`] tries.
const SETTLE_CHANGES: usize = 32;

/// The set `set` (unknowns `u`) without its contact `j`.
fn without(set: &ContactSet, u: &[f64], j: usize) -> (ContactSet, Vec<f64>) {
    let mut ns = set.clone();
    ns.contacts.remove(j);
    let o = set.offset(j);
    let mut nu = u.to_vec();
    nu.drain(o..o + set.contacts[j].unknowns());
    (ns, nu)
}
