//! Where a scan or a drag starts on any surface: the straight line (module `start`) or a curved
//! profile (module `surface`), and the march's view of it.
//!
//! On a curved profile the rod is pressed onto the profile's straight trend as on a line, and
//! the profile's shape is grown from zero to its full amplitude (see [`curve_start`]). (Pressing
//! a straight rod vertically onto a corrugation folds: the frictionless tip snaps down a slope.)

use crate::chain::{Chain, Contact, ContactSet, Family, Geom, Mode};
use crate::march::{march, Spec};
use crate::own::OwnStepper;
use crate::profile::Profile;
use crate::report::StopReason;
use crate::start::Pressed;
use crate::stepper::Stepper;
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
/// press on the line keeps its handling of first touch and buckling.
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
    let out = march(&mut st, &spec, profile, p0, Stats::default());
    let (set, end) = match (&out.stop, out.last) {
        (StopReason::DMax, Some((set, pt))) if pt.lam == 1.0 => (set, pt),
        (stop, _) => return Err(fail("the march in the amplitude", stop)),
    };
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
