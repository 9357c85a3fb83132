//! Where a scan starts: the rod pressed onto the surface from its rest shape, found numerically
//! (no closed form anywhere on the path).
//!
//! The press is a march in the depth `λ` by which the surface line (inclination β) has moved
//! along its normal since it first touched the unloaded rod, the contacts frictionless (the force
//! normal to the surface, the contact points free to slide), until the last contact point is at
//! the surface height η. First touch is the rest shape's highest point: the tip, or a side where
//! the rest shape is tangent to the line. New contacts form on the way (a tapered tip lies down)
//! exactly as in the scan.
//!
//! A rod whose rest shape gives no side preference (straight, on a horizontal surface) meets the
//! surface with an axial load and stays straight until it buckles: the press starts on the
//! buckled branch, bent to the right (the paper's convention, `m(0) < 0`), from the critical load
//! of the rod (the first root of `∂m(1)/∂m(0)` on the straight rod, by Brent's method) and a
//! small deflection.

use crate::chain::{Chain, Contact, ContactSet, Family, Geom, Mode};
use crate::config::StartKind;
use crate::control::corrector_tol;
use crate::march::{march, MarchOut, Spec};
use crate::own::OwnStepper;
use crate::profile::{General, Profile};
use crate::report::{RangeEnd, StopReason};
use crate::rodsolve::{solve_damped, Converged};
use crate::search;
use crate::shooter::Shooter;
use crate::stepper::Pt;
use crate::watch::{Env, Goal};
use crate::VibrissaError;
use bvp::Stats;
use std::f64::consts::FRAC_PI_2;

/// Below this inclination (rad) a straight rod's press starts on the buckled branch.
const NEARLY_SYMMETRIC: f64 = 0.1;

/// How a press is set up.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PressSpec {
    /// Inclination of the line the contact points stay on.
    pub geom_beta: f64,
    /// Inclination of the line the contact force is normal to (the force angle; equal to
    /// `geom_beta` for a real surface).
    pub force_beta: f64,
    /// New contacts form along the rod (else the tip alone touches and nothing else is checked).
    pub sides: bool,
    /// Where the press ends.
    pub goal: Goal,
    /// The tip's disk radius (0: a point tip).
    pub tip_radius: f64,
}

/// A pressed state: its contact set (frictionless contacts on the line through `p0`), the point,
/// the work done.
pub(crate) struct Pressed<P: Profile> {
    /// The shooter, its meshes graded for the pressed rod.
    pub sh: Shooter<P>,
    pub set: ContactSet,
    pub pt: Pt,
    pub p0: [f64; 2],
    /// The line's final offset along its normal (the press geometry: `n·r = h`).
    pub h: f64,
    /// The goal as approached (its side).
    pub goal: Goal,
    pub stats: Stats,
}

/// Why a press ends without reaching its goal (the press marches in its depth, how far the line
/// has moved along its normal past first touch, not in d).
fn press_failed(what: &str, stop: &StopReason) -> VibrissaError {
    VibrissaError::NoStart {
        reason: format!("{what}: {}", stop.describe("depth")),
    }
}

/// The rest shape (unloaded) and its highest point along the normal of a line inclined by
/// `beta`: `(height, s)`, refined on the rod (a round tip of radius `r` reaches `r` above its
/// centre).
fn rest_top<P: Profile>(
    sh: &mut Shooter<P>,
    beta: f64,
    tip_only: bool,
    r: f64,
) -> (f64, f64, [f64; 4]) {
    let z0 = [0.0, 0.0, FRAC_PI_2, 0.0];
    for _ in 0..32 {
        let shot = sh.shoot(0, 0.0, 1.0, z0, &[], [0.0, 0.0], false);
        if shot.err <= 1.0 || !sh.refine(0) {
            break;
        }
    }
    let (sb, cb) = beta.sin_cos();
    let (ps, pz, _) = sh.path(0);
    let last = pz.len() - 4;
    let zt = [pz[last], pz[last + 1], pz[last + 2], pz[last + 3]];
    let h = |z: &[f64]| -sb * z[0] + cb * z[1];
    let mut best = (if r > 0.0 { h(&zt) + r } else { h(&zt) }, 1.0, zt);
    if tip_only {
        return best;
    }
    // interior maxima: the tangent points φ(s) = β (+2πk) on the rod, bracketed by the nodes
    let n = ps.len();
    for i in 0..n - 1 {
        let g = |z: &[f64]| (z[2] - beta).sin();
        let (za, zb) = (&pz[4 * i..4 * i + 4], &pz[4 * i + 4..4 * i + 8]);
        if g(za) > 0.0 && g(zb) <= 0.0 && (za[2] - beta).cos() > 0.0 {
            let mut f =
                |s: f64| -> Result<f64, std::convert::Infallible> { Ok(g(&sh.state_at(0, s))) };
            if let Ok(s) = search::root(&mut f, ps[i], ps[i + 1], 1e-15) {
                let z = sh.state_at(0, s);
                if s < 1.0 && h(&z) > best.0 {
                    best = (h(&z), s, z);
                }
            }
        }
    }
    best
}

/// The height the unloaded rod reaches on a line inclined by `beta` (its rest shape's highest
/// point along the line's normal; a round tip's top): where a press onto it first touches, as
/// [`first_touch`] measures it.
pub(crate) fn rest_reach<P: Profile>(rod: &crate::Rod, profile: &P, beta: f64, tol: f64) -> f64 {
    let mut sh = Shooter::new(profile.clone(), rod.support_compliance(), tol, 8);
    let r = rod.tip_radius();
    let (_, s_top, z_top) = rest_top(&mut sh, beta, false, r);
    if r > 0.0 && s_top >= 1.0 {
        z_top[1] + r
    } else {
        z_top[1]
    }
}

/// `∂m(1)/∂m(0)` of the straight rod under the axial load `f` (its zero is the buckling load).
fn straight_stiffness<P: Profile>(sh: &mut Shooter<P>, f: f64) -> f64 {
    let c = sh.compliance;
    let z0 = [0.0, 0.0, FRAC_PI_2, 0.0];
    for _ in 0..32 {
        let shot = sh.shoot(0, 0.0, 1.0, z0, &[[c, 1.0]], [0.0, -f], true);
        if shot.err <= 1.0 || !sh.refine(0) {
            return shot.col[0][3];
        }
    }
    f64::NAN
}

/// Where a press first touches and how it starts.
struct Touch {
    /// The rest shape's height along the line's normal at first touch, and where.
    top: f64,
    s_top: f64,
    /// The first contact (frictionless, its force normal to the force line).
    contact: Contact,
    /// The line's inclination.
    gb: f64,
    /// A straight rod on a horizontal line: it starts on the buckled branch.
    symmetric: bool,
    /// A straight rod on a nearly horizontal line (an imperfect bifurcation).
    nearly: bool,
    /// A symmetric rod buckles to the left (a tip slope goal only the left-bent rod reaches).
    left: bool,
    /// How far the goal lies: the first point must be short of it.
    room: f64,
}

/// First touch of the press `spec` on the rest shape of `sh`, or why the rod never touches.
fn first_touch<P: Profile>(
    sh: &mut Shooter<P>,
    profile: &P,
    spec: &PressSpec,
) -> Result<Touch, VibrissaError> {
    let gb = spec.geom_beta;
    let r = spec.tip_radius;
    let (top, s_top, z_top) = rest_top(sh, gb, !spec.sides, r);
    // (the height the rest shape reaches: a round tip's top)
    let reach = if r > 0.0 && s_top >= 1.0 {
        z_top[1] + r
    } else {
        z_top[1]
    };
    let symmetric = gb == 0.0 && spec.force_beta == 0.0 && s_top == 1.0 && profile.straight();
    if let Goal::Height(eta, _) = spec.goal {
        if reach <= eta {
            return Err(VibrissaError::OutOfReach {
                what: format!(
                    "the rod's rest shape does not reach the surface at eta = {eta}: its highest \
                     point (s = {s_top:.6}) is below it, so it touches only when pulled up"
                ),
                reach,
                needed: eta,
            });
        }
    }
    let n_force = [-spec.force_beta.sin(), spec.force_beta.cos()];
    let mut contact = Contact::on_surface(s_top >= 1.0, [0.0, 0.0], gb, Mode::Free, 0.0);
    contact.n = n_force;
    if !contact.tip {
        contact.phi_ref = crate::chain::slope_on(gb, z_top[2]);
    }
    let room = match spec.goal {
        Goal::Height(eta, _) => (reach - eta).max(1e-12),
        Goal::TipSlope(..) => 1.0,
    };
    // a straight rod on a nearly horizontal line meets it almost axially: its path passes close
    // by the buckling point (an imperfect bifurcation), which a march from a small load can step
    // past onto another branch; it starts on the buckled branch too, bent the way the line's
    // inclination pushes its tip (to the left for β < 0)
    let nearly = !symmetric
        && gb == spec.force_beta
        && gb.abs() < NEARLY_SYMMETRIC
        && s_top == 1.0
        && profile.straight();
    Ok(Touch {
        top,
        s_top,
        contact,
        gb,
        symmetric,
        nearly,
        // the side a symmetric rod buckles to: the right (the paper's), unless the goal is a
        // tip slope only the left-bent rod reaches
        left: matches!(spec.goal, Goal::TipSlope(p, _) if p > FRAC_PI_2),
        room,
    })
}

/// A first point of the press: on the buckled branch with the tip lowered by about `buckled`,
/// else at first touch (a side) or under a small tip load (the tip).
fn press_point<P: Profile>(
    chain: &mut Chain<P>,
    t: &Touch,
    ntol: f64,
    buckled: Option<f64>,
) -> Result<(f64, Converged), VibrissaError> {
    let (lam0, u0) = if let Some(drop) = buckled {
        let left = if t.nearly { t.gb < 0.0 } else { t.left };
        buckled_start(chain, t.top, ntol, drop, left)?
    } else if t.contact.tip {
        // a small load: at zero load a straight tip's height is stationary under a transverse
        // force (it falls as the load squared), which no Newton iteration in the height
        // resolves
        // (a soft, curled rod moves far under it: smaller loads until the point is
        // short of the goal)
        let mut n0 = 1e-3;
        loop {
            let (l, u) = loaded_start(chain, t.top, ntol, n0)?;
            if l < 0.5 * t.room || n0 < 1e-9 {
                break (l, u);
            }
            n0 *= 0.1;
        }
    } else {
        (0.0, vec![0.0, 0.0, 0.0, t.s_top])
    };
    let cv = solve_damped(chain, lam0, &u0, ntol, 40).map_err(|e| VibrissaError::NoStart {
        reason: format!("the first point of the press did not converge: {e}"),
    })?;
    // a guess next to the buckling load that converged onto another mode (the third
    // clamped-free mode, f ≈ 25π²/4, for β ≈ 0.03) is no first point of this press
    if buckled.is_some() && (cv.u[1] - u0[1]).abs() > 0.5 * u0[1].abs() {
        return Err(VibrissaError::NoStart {
            reason: format!(
                "the first point of the press converged onto another mode (f = {} from {})",
                cv.u[1], u0[1]
            ),
        });
    }
    Ok((lam0, cv))
}

/// The press's first point (at first touch (N = 0), or on the buckled branch of a symmetric
/// rod), walked up to a depth of 1e-3 (or half the room) in steps of 4×: a first point far
/// below the march's first step (a tiny load next to the imperfect bifurcation of a straight
/// rod on a slightly inclined line) would let the march's first step land on another mode
/// (β = 0.025…0.03 went to the third clamped-free mode, f ≈ 70).
fn press_start<P: Profile>(
    chain: &mut Chain<P>,
    t: &Touch,
    ntol: f64,
) -> Result<(f64, Converged), VibrissaError> {
    let drop = (0.1 * t.room).min(1e-3);
    let (mut lam0, mut cv) = if t.symmetric {
        press_point(chain, t, ntol, Some(drop))?
    } else if t.nearly {
        // the inclined line's state next to the buckled one: closer the more it is bent (the
        // inclination's share of the bending smaller); else from a small load after all
        [drop, 1e-2, 3e-2]
            .into_iter()
            .filter(|&dr| dr <= 0.2 * t.room)
            .find_map(|dr| press_point(chain, t, ntol, Some(dr)).ok())
            .map_or_else(|| press_point(chain, t, ntol, None), Ok)?
    } else {
        press_point(chain, t, ntol, None)?
    };
    let ramp_end = 1e-3f64.min(0.5 * t.room);
    while lam0 > 0.0 && lam0 < ramp_end {
        let next = (4.0 * lam0).min(ramp_end);
        match solve_damped(chain, next, &cv.u, ntol, 40) {
            Ok(c) => (lam0, cv) = (next, c),
            Err(_) => break,
        }
    }
    Ok((lam0, cv))
}

/// The press of `spec` on the rod of `sh` (tolerance `tol`), from first touch to the goal.
pub(crate) fn press<P: Profile>(
    mut sh: Shooter<P>,
    general: &General,
    profile: &P,
    spec: &PressSpec,
) -> Result<Pressed<P>, VibrissaError> {
    let tol = sh.tol;
    let t = first_touch(&mut sh, profile, spec)?;
    let (p0, top) = ([0.0, 0.0], t.top);
    let set = ContactSet {
        contacts: vec![t.contact.clone()],
        tip_radius: spec.tip_radius,
        lying: None,
    };
    let mut chain = Chain::new(sh, set, Family::Press { h0: top });
    let ntol = corrector_tol(tol);
    let (lam0, cv) = press_start(&mut chain, &t, ntol)?;
    // a slope goal approached from the side the first point is on
    let goal = match spec.goal {
        Goal::TipSlope(p, _) => {
            let phi1 = chain.sh.path(0).1[chain.sh.path(0).1.len() - 2];
            Goal::TipSlope(p, if phi1 >= p { 1.0 } else { -1.0 })
        }
        g => g,
    };
    let env = Env {
        line: spec.sides.then_some((p0, t.gb)),
        mu0: None,
        compound: spec.sides,
        target: Some(goal),
        ground: Default::default(),
    };
    let mut st = OwnStepper {
        chain,
        env,
        cancel: Default::default(),
        light: false,
        polish: false,
        retangent: false,
    };
    let p = st.point(lam0, cv).map_err(|e| VibrissaError::NoStart {
        reason: format!("the first point of the press: {e}"),
    })?;
    let mspec = Spec {
        env: &st.env.clone(),
        grid: &[],
        lam_end: top + 4.0,
        keep_shapes: None,
        general,
        friction: false,
        check_start: false,
        slide: false,
        pass_fold_ahead: false,
        retangent: false,
    };
    let out: MarchOut = march(&mut st, &mspec, profile, p, Stats::default());
    match (&out.stop, out.range_end, out.last) {
        (StopReason::DMax, RangeEnd::DMax, Some((set, pt))) if goal_met(&goal, &pt) => {
            Ok(Pressed {
                sh: st.chain.sh,
                set,
                h: top - pt.lam,
                goal,
                pt,
                p0,
                stats: out.stats,
            })
        }
        (StopReason::DMax, _, _) => Err(VibrissaError::NoStart {
            reason: format!(
                "pressing the rod {} deep did not bring its contact to the goal {:?}",
                top + 4.0,
                spec.goal
            ),
        }),
        (stop, _, _) => Err(press_failed("pressing the rod onto the surface", stop)),
    }
}

fn goal_met(goal: &Goal, pt: &Pt) -> bool {
    match *goal {
        Goal::Height(h, _) => (pt.w.last_y - h).abs() <= 1e-6,
        Goal::TipSlope(p, _) => (pt.w.phi1 - p).abs() <= 1e-6,
    }
}

/// The press's point where the tip force (normal to its frame, no friction) is `n0`: `m(0)` from
/// `m(1) = 0` by Newton, the depth from the tip's height: `(λ, u)`.
fn loaded_start<P: Profile>(
    chain: &mut Chain<P>,
    top: f64,
    tol: f64,
    n0: f64,
) -> Result<(f64, Vec<f64>), VibrissaError> {
    let ct = chain.set.contacts[0].clone();
    let g = ct.force(n0, 0.0);
    let c = chain.sh.compliance;
    let mut m0 = 0.0;
    for _ in 0..60 {
        let z0 = [0.0, 0.0, FRAC_PI_2 + c * m0, m0];
        let shot = chain.sh.shoot(0, 0.0, 1.0, z0, &[[c, 1.0]], g, true);
        if shot.err > 1.0 {
            if !chain.sh.refine(0) {
                break;
            }
            continue;
        }
        let step = shot.z[3] / shot.col[0][3];
        if !step.is_finite() {
            break;
        }
        m0 -= step;
        if step.abs() <= tol {
            let Geom::Line { beta, .. } = ct.geom else {
                break;
            };
            let z1 = chain
                .sh
                .shoot(
                    0,
                    0.0,
                    1.0,
                    [0.0, 0.0, FRAC_PI_2 + c * m0, m0],
                    &[],
                    g,
                    false,
                )
                .z;
            let h = -beta.sin() * z1[0] + beta.cos() * z1[1];
            // (a round tip's centre stays its radius below the line)
            let r = chain.set.tip_radius;
            let h = if r > 0.0 { h + r } else { h };
            return Ok((top - h, vec![m0, n0, 0.0]));
        }
    }
    Err(VibrissaError::NoStart {
        reason: format!("the rod under a tip load of {n0} did not converge"),
    })
}

/// The first sign change of `∂m(1)/∂m(0)` below `f_cr` (by steps of ×1.2 up to `f_cr`, from a
/// lower bound of the first buckling load), refined by Brent's method; `None` where there is
/// none (`f_cr` is then the first buckling load; the uniform clamped rod's bound is its load
/// itself, so it takes no shot more).
///
/// Why: [`buckled_start`] brackets the load by checks at f = 0.5, 0.75, 1.125, …, which step over
/// two buckling loads that fall between two checks. A tip far more flexible than the foot has
/// them low and close: the rod tapered to 0.1 started on its third mode (two flex points,
/// f = 0.796 at η 0.97, unstable: ω₁² = −3620), the one tapered to 0.05 on its fifth (four), where
/// 0.15 starts on its first (none, f = 0.176, ω₁² = 278). The lower bound: the rod is at least
/// as stiff as the uniform one of its least stiffness, whose clamped–free load is
/// `π²/4 · min EI`, and the support's spring lowers it at most as Dunkerley's sum says,
/// `1/f₁ ≤ 4/(π² min EI) + c`.
fn first_buckling_below<P: Profile>(
    sh: &mut Shooter<P>,
    k0: f64,
    f_cr: f64,
) -> Result<Option<f64>, VibrissaError> {
    let ei_min = (0..=100)
        .map(|i| 1.0 / sh.profile.b(i as f64 / 100.0))
        .fold(f64::INFINITY, f64::min);
    let top = f_cr * (1.0 - 1e-6);
    let mut a = 1.0 / (4.0 / (std::f64::consts::PI.powi(2) * ei_min) + sh.compliance);
    while a < top {
        let b = (1.2 * a).min(top);
        let kb = straight_stiffness(sh, b);
        if kb.is_nan() {
            // (a shot the shooter cannot resolve: the load found stays)
            return Ok(None);
        }
        if kb.signum() != k0.signum() {
            let mut g =
                |f: f64| -> Result<f64, std::convert::Infallible> { Ok(straight_stiffness(sh, f)) };
            let f1 = search::root(&mut g, a, b, 1e-14 * b).map_err(|e| VibrissaError::NoStart {
                reason: format!("the first buckling load: {e}"),
            })?;
            return Ok(Some(f1));
        }
        a = b;
    }
    Ok(None)
}

/// A point on the buckled branch of the straight rod under an axial tip load, bent to the right,
/// its tip lowered by about `drop`: `(λ, u)` of the press.
fn buckled_start<P: Profile>(
    chain: &mut Chain<P>,
    top: f64,
    tol: f64,
    drop: f64,
    left: bool,
) -> Result<(f64, Vec<f64>), VibrissaError> {
    let side = if left { -1.0 } else { 1.0 };
    // (a round tip's centre stays its radius below the line)
    let r = chain.set.tip_radius;
    let top = if r > 0.0 { top - r } else { top };
    let sh = &mut chain.sh;
    // the first sign change of ∂m(1)/∂m(0) in f: bracket by doubling, then Brent
    let k0 = straight_stiffness(sh, 0.0);
    let (mut lo, mut hi) = (0.0, 0.5);
    let mut found = false;
    for _ in 0..60 {
        let k = straight_stiffness(sh, hi);
        if k.signum() != k0.signum() {
            found = true;
            break;
        }
        lo = hi;
        hi *= 1.5;
        if hi > 1e9 {
            break;
        }
    }
    if !found {
        return Err(VibrissaError::NoStart {
            reason: "the straight rod does not buckle under an axial tip load".into(),
        });
    }
    let mut g = |f: f64| -> Result<f64, std::convert::Infallible> { Ok(straight_stiffness(sh, f)) };
    // (a bracket whose ends, shot again on a refined mesh, no longer differ in sign is searched
    // from below as well: the rod tapered to 0.02 had its signs at f = 0.5 and 0.75 change
    // between the check and the search)
    let f_cr = match search::root(&mut g, lo, hi, 1e-14 * hi) {
        Ok(f) => first_buckling_below(sh, k0, f)?.unwrap_or(f),
        Err(e) => first_buckling_below(sh, k0, hi)?.ok_or_else(|| VibrissaError::NoStart {
            reason: format!("the buckling load: {e}"),
        })?,
    };
    // a small deflection on the right-bent branch: m(0) = −ε, f from m(1) = 0 (Newton in f)
    let solve_f = |chain: &mut Chain<P>, eps: f64| -> Option<(f64, f64)> {
        let mut f = f_cr;
        let c = chain.sh.compliance;
        let z0 = [0.0, 0.0, FRAC_PI_2 - c * eps, -eps];
        for _ in 0..60 {
            let shot = chain
                .sh
                .shoot(0, 0.0, 1.0, z0, &[[c, 1.0]], [0.0, -f], true);
            if shot.err > 1.0 {
                if !chain.sh.refine(0) {
                    return None;
                }
                continue;
            }
            let r = shot.z[3];
            // ∂m(1)/∂f = −∂m(1)/∂Gy
            let dr = -shot.col[2][3];
            let step = r / dr;
            if !step.is_finite() {
                return None;
            }
            if r.abs() <= tol || step.abs() <= 1e-15 * f.abs() {
                return Some((f, shot.z[1]));
            }
            f -= step;
        }
        None
    };
    // (a rod whose tip is far more flexible than its foot, e.g. taper 0.01, turns its tip through
    // a large angle already at m(0) = 1e-2, beyond where this Newton in f converges: smaller
    // deflections first, issue 33)
    let (eps0, y0) = [1e-2, 1e-3, 1e-4, 1e-5]
        .into_iter()
        .find_map(|e| solve_f(chain, e).map(|(_, y)| (e, y)))
        .ok_or_else(|| VibrissaError::NoStart {
            reason: format!(
                "no buckled state next to the critical load f = {f_cr:.6e} (Newton in f from \
                 m(0) = 1e-2 down to 1e-5 did not converge)"
            ),
        })?;
    // the amplitude for the tip drop asked for (the drop grows as ε²)
    let drop0 = top - y0;
    let eps = if drop0 > 0.0 {
        (eps0 * (drop / drop0).sqrt()).min(0.3)
    } else {
        eps0
    };
    let (f, y) = solve_f(chain, side * eps).ok_or_else(|| VibrissaError::NoStart {
        reason: "no buckled state next to the critical load".into(),
    })?;
    Ok((top - y, vec![-side * eps, f, 0.0]))
}

/// The pressed state as the start of a drag: the surface line through the pressed contacts
/// (foot at the origin), the tip stuck where it is, the sides rolling without slip.
pub(crate) fn stuck<P: Profile>(p: &Pressed<P>, beta: f64) -> (ContactSet, [f64; 2]) {
    let (sb, cb) = beta.sin_cos();
    // a point of the pressed line: the last contact point
    let z_last = if p.set.tip() {
        let z = p.pt.sol.right();
        [z[0], z[1]]
    } else {
        let s = p.pt.w.contacts.last().map_or(1.0, |c| c.s);
        let mut z = [0.0; 4];
        p.pt.sol.eval(s, &mut z);
        [z[0], z[1]]
    };
    // (a round tip touches the line its radius beyond its centre, along the normal)
    let r = p.set.tip_radius;
    let p0 = if p.set.tip() && r > 0.0 {
        [z_last[0] - r * sb, z_last[1] + r * cb]
    } else {
        z_last
    };
    let along = |z: &[f64]| cb * (z[0] - p0[0]) + sb * (z[1] - p0[1]);
    let line = Geom::Line { p0, beta };
    let contacts = p
        .set
        .contacts
        .iter()
        .enumerate()
        .map(|(j, c)| {
            let s = p.set.s_of(j, &p.pt.u);
            let mut z = [0.0; 4];
            p.pt.sol.eval(s, &mut z);
            let mode = if c.tip {
                Mode::Stuck(crate::chain::tip_place(r, &line, &z, 0.0).unwrap_or(f64::NAN))
            } else {
                Mode::Rolling(along(&z) - (c.phi_ref - beta).cos().round() * s)
            };
            Contact {
                geom: Geom::Line { p0, beta },
                mode,
                ..*c
            }
        })
        .collect();
    (
        ContactSet {
            contacts,
            tip_radius: p.set.tip_radius,
            lying: None,
        },
        p0,
    )
}

/// The tolerance of a second press when the first, at a looser tolerance, fails.
const PRESS_TOL: f64 = 1e-8;

/// The start of a scan: the pressed (or connected) state at `d = 0`.
pub(crate) fn scan_start<P: Profile>(
    rod: &crate::Rod,
    profile: &P,
    surface: &crate::Surface,
    kind: StartKind,
    tol: f64,
) -> Result<Pressed<P>, VibrissaError> {
    let (eta, beta) = (surface.eta(), surface.angle());
    let c = rod.support_compliance();
    let general = rod.profile(1.0);
    let ntol = corrector_tol(tol);
    match kind {
        StartKind::Pressed => {
            let at = |tol: f64| {
                press(
                    Shooter::new(profile.clone(), c, tol, 8),
                    &general,
                    profile,
                    // pressed as it is, sides touching where they do (the tip-only model then
                    // has no valid start: the scan reports the penetration at d = 0)
                    &PressSpec {
                        geom_beta: beta,
                        force_beta: beta,
                        sides: true,
                        goal: Goal::Height(eta, 1.0),
                        tip_radius: rod.tip_radius(),
                    },
                )
            };
            // a loose tolerance can lose the press at a change of its contacts (issue 33: tol
            // 1e-2, taper 0.1, eta 0.6 ended in a residual NaN at a touchdown): the press again
            // at PRESS_TOL, then what to do
            at(tol)
                .or_else(|e| {
                    if tol > PRESS_TOL {
                        at(PRESS_TOL)
                    } else {
                        Err(e)
                    }
                })
                .map_err(|e| {
                    // the caller's to fix (a surface the rod does not reach): as it is
                    if e.is_input() {
                        return e;
                    }
                    let reason = match e {
                        VibrissaError::NoStart { reason } => reason,
                        e => e.to_string(),
                    };
                    VibrissaError::NoStart {
                        reason: format!(
                            "{reason}; the connected start (--start connected, start = \
                             \"connected\") follows the state connected to the pressed straight \
                             uniform rod instead and may have one"
                        ),
                    }
                })
        }
        StartKind::Connected if rod.tip_radius() > 0.0 => Err(VibrissaError::MethodUnavailable {
            method: "start = connected".into(),
            reason: "a round tip (tip radius > 0) starts from the rod pressed onto the surface \
                     (start = pressed)"
                .into(),
        }),
        StartKind::Connected => {
            // the uniform clamped rod pressed down at its tip to height eta, the force turned to
            // the surface's normal, then the rod's deviations grown to the scene's rod
            let spec = PressSpec {
                geom_beta: 0.0,
                force_beta: 0.0,
                sides: false,
                goal: Goal::Height(eta, 1.0),
                tip_radius: 0.0,
            };
            let uniform = profile.at_amplitude(0.0);
            let pu = press(
                Shooter::new(uniform, 0.0, tol, 8),
                &rod.profile(0.0),
                &profile.at_amplitude(0.0),
                &spec,
            )?;
            let h = pu.h;
            let chain = Chain::new(
                pu.sh,
                pu.set.clone(),
                Family::Fixed(crate::chain::Pose {
                    h,
                    ..Default::default()
                }),
            );
            let (chain, u) = turn_force(chain, &pu.pt.u, 0.0, beta, ntol)?;
            let p1 = profile.clone();
            let (chain, end) = morph(
                chain,
                &u,
                move |ch: &mut Chain<P>, t: f64| ch.sh.set_profile(p1.at_amplitude(t), t * c),
                ntol,
                "homotopy from the uniform clamped rod",
                &|t| format!("t = {t} of 1"),
            )?;
            let mut st = OwnStepper {
                chain,
                env: Env {
                    line: None,
                    mu0: None,
                    compound: false,
                    target: None,
                    ground: Default::default(),
                },
                cancel: Default::default(),
                light: false,
                polish: false,
                retangent: false,
            };
            // the shooter's paths hold the point at t = 1 (the last correction)
            let pt = st.point(0.0, end).map_err(|e| VibrissaError::NoStart {
                reason: format!("the connected start: {e}"),
            })?;
            if pt.w.normal < 0.0 {
                return Err(VibrissaError::OutOfReach {
                    what: format!(
                        "the state connected to the pressed uniform rod needs the tip pulled up to \
                         height eta = {eta} (normal force {:.6e})",
                        pt.w.normal
                    ),
                    reach: pt.w.normal,
                    needed: 0.0,
                });
            }
            let mut stats = pu.stats;
            stats.accumulate(&st.chain.sh.stats);
            Ok(Pressed {
                sh: st.chain.sh,
                set: st.chain.set,
                pt,
                p0: pu.p0,
                h,
                goal: pu.goal,
                stats,
            })
        }
    }
}

/// Follows `chain` through the change `set(chain, λ)` for `λ` from 0 to 1, from its converged
/// unknowns `u` at `λ = 0`: the chain at `λ = 1` and its converged point there (the shooter's
/// paths hold it).
pub(crate) fn morph<P: Profile>(
    chain: Chain<P>,
    u: &[f64],
    set: impl FnMut(&mut Chain<P>, f64),
    tol: f64,
    what: &str,
    param: &dyn Fn(f64) -> String,
) -> Result<(Chain<P>, crate::rodsolve::Converged), VibrissaError> {
    let mut m = crate::chain::Morph {
        chain,
        set,
        at: 0.0,
    };
    let fail = |e: String| VibrissaError::NoConvergence {
        what: what.to_string(),
        reason: e,
    };
    let first =
        crate::arclength::at_lambda(&mut m, u, 0.0, tol, 30).map_err(|e| fail(e.to_string()))?;
    let end = crate::arclength::follow_to(&mut m, first, 1.0, tol).map_err(|e| {
        fail(match e {
            crate::arclength::FollowError::TurnedBack { reached } => format!(
                "no such state: the curve turns back (a fold) at {}",
                param(reached)
            ),
            crate::arclength::FollowError::Step { at, reason } => {
                format!("at {}: {reason}", param(at))
            }
        })
    })?;
    // the member at 1 once more, so that the shooter's paths hold it
    let cv = crate::rodsolve::solve_damped(&mut m, 1.0, &end.u(), tol, 30)
        .map_err(|e| fail(e.to_string()))?;
    Ok((m.chain, cv))
}

/// Turns the held tip force of a one-contact chain from the angle `from` to `to` (its frame
/// rotated; the tip condition held): the chain and its unknowns at `to`.
pub(crate) fn turn_force<P: Profile>(
    chain: Chain<P>,
    u: &[f64],
    from: f64,
    to: f64,
    tol: f64,
) -> Result<(Chain<P>, Vec<f64>), VibrissaError> {
    if from == to {
        return Ok((chain, u.to_vec()));
    }
    let (chain, cv) = morph(
        chain,
        u,
        move |ch: &mut Chain<P>, t: f64| {
            let a = from + t * (to - from);
            ch.set.contacts[0].n = [-a.sin(), a.cos()];
        },
        tol,
        &format!("turning the tip force from alpha = {from} to alpha = {to}"),
        &|t| format!("alpha = {}", from + t * (to - from)),
    )?;
    Ok((chain, cv.u))
}
