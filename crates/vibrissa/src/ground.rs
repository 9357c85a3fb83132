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
fn curve_start<P: Profile>(
    rod: &Rod,
    profile: &P,
    surface: &Surface,
    h: &Arc<Height>,
    tol: f64,
) -> Result<Pressed<P>, VibrissaError> {
    let line = Surface::new(surface.eta(), surface.angle())?;
    let pressed = crate::start::scan_start(rod, profile, &line, crate::StartKind::Pressed, tol)?;
    // the pressed line n·r = h in the lab frame: y = h / cos β + x tan β; the profile's trend
    // y = η + x tan β lies off0 below it
    let off0 = pressed.h / surface.angle().cos() - surface.eta();
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
    };
    let mut st = OwnStepper {
        chain: Chain::new(pressed.sh, set, Family::Grow { off0 }),
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
    };
    let fail = |what: &str, e: &dyn std::fmt::Display| VibrissaError::NoStart {
        reason: format!("growing the surface profile from its straight trend: {what}: {e}"),
    };
    let p0 = st
        .correct_from(0.0, &pressed.pt.u, None, true)
        .map_err(|e| fail("the pressed rod", &e))?;
    let (set, end) = grow(&mut st, p0, rod, profile).map_err(|(what, e)| fail(what, &e))?;
    // the grown profile is the drag's at d = 0
    st.chain.family = Family::Drag;
    st.env.ground.grow = false;
    let pt = st
        .switch(set, 0.0, end.u)
        .map_err(|e| fail("the rod on the profile", &e))?;
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
    let contacts = p
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
    (
        ContactSet {
            contacts,
            tip_radius: p.set.tip_radius,
        },
        u,
    )
}

/// The amplitudes at which [`settle`] finds the contacts of a rod whose free part lies on the
/// straight trend, in the order tried where the march from amplitude 0 ends short of the full
/// profile: the first that settles and grows to the full profile is the start.
const SETTLE_AT: [f64; 3] = [1e-3, 1e-2, 3e-2];

/// The march in the amplitude from the rod pressed on the straight trend, `p0` (amplitude 0),
/// to the full profile: its contact set and last point there, or what failed (and why). Where a
/// free part lies on the trend at `p0` and that march ends short, the rod is settled on the
/// profile at a small amplitude ([`settle`]) and the march goes on from there.
fn grow<P: Profile>(
    st: &mut OwnStepper<P>,
    p0: Pt,
    rod: &Rod,
    profile: &P,
) -> Result<(ContactSet, Pt), (&'static str, String)> {
    let spec = Spec {
        env: &st.env.clone(),
        grid: &[],
        lam_end: 1.0,
        keep_shapes: None,
        general: &rod.profile(1.0),
        friction: false,
        check_start: false,
        slide: false,
    };
    // (the march from amplitude 0 first, as for any start: where it grows the profile, the
    // start is what it was before settling existed)
    let n = if lying(&p0) { SETTLE_AT.len() + 1 } else { 1 };
    let set0 = st.chain.set.clone();
    let mut first_failure: Option<(&'static str, String)> = None;
    for &t in [0.0].iter().chain(&SETTLE_AT).take(n) {
        st.chain.set = set0.clone();
        let from = if t > 0.0 {
            match settle(st, &p0, t) {
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
            (stop, _) if t == 0.0 => {
                first_failure = Some(("the march in the amplitude", stop.describe("d")));
            }
            (stop, _) => note(
                &mut first_failure,
                t,
                format!("then {}", stop.describe("d")),
            ),
        }
    }
    Err(first_failure.unwrap_or(("the march in the amplitude", "no start".into())))
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

/// The rod at amplitude `t` from the state `p` at amplitude 0 whose free part lies on the
/// straight trend. Every point of that part touches at 0, so the contacts the grown profile
/// makes begin there at once (a touchdown at the march's start, with no place singled out
/// along the lying part); they are found at the small amplitude `t` itself, as an active set:
/// the state solved with the contacts so far, then a contact that pulls released, a touching
/// tip that turns into the profile laid down, or a contact added where the rod crosses the
/// profile most (beside the others, else in place of its neighbour before or after it, which
/// passes it its load), until the state holds (no pull, no crossing beyond [`AT_ZERO`]). The
/// contacts are frictionless, as in the march in the amplitude.
fn settle<P: Profile>(st: &mut OwnStepper<P>, p: &Pt, t: f64) -> Result<Pt, SettleError> {
    let rules = Rules {
        friction: false,
        slide: false,
    };
    let env = st.env.clone();
    let mut set = st.chain.set.clone();
    let mut q = st
        .switch(set.clone(), t, p.u.clone())
        .map_err(SettleError::Start)?;
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
        let mut failed = None;
        let mut next = None;
        for (ts, tu) in tries {
            match st.switch(ts.clone(), t, tu) {
                Ok(r) => {
                    next = Some((ts, r));
                    break;
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
        let Some(n) = next else {
            return Err(failed.unwrap_or(SettleError::NoState {
                cross,
                set: set.label(),
            }));
        };
        (set, q) = n;
    }
    Err(SettleError::Unsettled { set: set.label() })
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
