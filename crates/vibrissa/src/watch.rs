//! What the marches watch at each solved point: the contact forces, the friction ratio, how the
//! free parts of the rod stand off the surface (found on the rod itself, not on an interpolant),
//! and the event functions that are negative while a contact state holds and reach zero where it
//! ends (a contact lifts, slips, a new one forms, a lying part peels back, the object slips off).

use crate::chain::{ContactSet, Geom, Mode};
use crate::surface::Ground;
use bvp::Solution;

/// The scene's obstacles and thresholds, fixed along a march.
#[derive(Clone, Debug)]
pub(crate) struct Env {
    /// The surface line (lab frame: a point on it and its inclination β), if the scene has one.
    pub line: Option<([f64; 2], f64)>,
    /// Slip threshold of the stuck contacts.
    pub mu0: Option<f64>,
    /// Contact anywhere (new contacts form) or the paper's tip-only model (a touching side is a
    /// penetration that ends the march).
    pub compound: bool,
    /// March until the target is reached (the press of the start, a load to a tip condition).
    pub target: Option<Goal>,
    /// A curved surface, a friction texture, a slip in progress (module `surface`).
    pub ground: Ground,
}

/// Where a press ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Goal {
    /// The last contact point at this height, approached from above (`+1`) or below (`−1`).
    Height(f64, f64),
    /// The tip slope at this value, approached from above (`+1`) or below (`−1`).
    TipSlope(f64, f64),
}

/// One contact's forces in its own frame (surface: normal and tangent of the line; point
/// object: the rod's normal and tangent there) and its place.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct ContactForce {
    /// Normal force (≥ 0 while it pushes).
    pub normal: f64,
    /// Tangential (friction) force.
    pub tangential: f64,
    /// Arc length.
    pub s: f64,
    /// Lab x of the contact point.
    pub x: f64,
    /// Its height (a round tip: the point of its disk that touches, from the rod's end).
    pub y: f64,
    /// Its slip threshold (μ0 for the tip, else the texture's μs there; `inf`: none).
    pub mu_s: f64,
    /// μk there during a slip (`inf` otherwise).
    pub mu_k: f64,
    /// Where it is a side on the line with a contact beyond it: the height's second derivative
    /// along the rod there, `cos(φ − β) κ` (negative while the rod curves away from the line on
    /// both sides; zero where it begins to lie along it); a side on a curved surface: the same
    /// of the gap to the surface ([`curve_curv`]). NaN elsewhere.
    pub curv: f64,
    /// How a contact slides on the surface (filled where the set has a sliding contact).
    pub slide: SlideRate,
    /// A round tip's contact point on a curved surface: the rate `dx_c/dλ` of its lab x along
    /// the branch (its friction's frame turns with it; NaN elsewhere or where not known).
    pub dxc: f64,
    /// The inner end of a lying stretch (module `chain`, `Lying`): the normal point forces at
    /// the stretch's inner and outer ends, `P = dir·(m'(s−) − m'(s+))` (the jump of the internal
    /// force's normal part: `m'` on the loaded rod before it, on the stretch, and on the rod
    /// beyond it); each pushes while positive. NaN elsewhere.
    pub end_push: [f64; 2],
    /// The inner end of a lying stretch: the arc length of its outer end (NaN elsewhere).
    pub lies_to: f64,
    /// The inner end of a lying stretch: the friction ratio it needs, signed (`gμ`: a stretch
    /// sliding the way `g` with kinetic friction `μ` along it would balance its resultant,
    /// [`crate::chain::Capstan::friction_ratio`]; one that slides, its ratio). NaN elsewhere.
    pub stretch_mu: f64,
    /// The same stretch, where it slides (a slip's driver, or sliding along): the part `W` of
    /// its friction's work that its ratio does not count, and its rate along the branch
    /// ([`crate::chain::Chain::stretch_friction`]: the work per slide `dc` is `r·N + W`, `T +
    /// Q(0)` for a slip's driver). NaN elsewhere.
    pub turn: [f64; 2],
    /// The inner end of a lying stretch that drives a slip: its balance `T − r·N + Q(r)` were
    /// it sliding with kinetic friction, `r = dir·μk` ([`crate::chain::Capstan::balance`]),
    /// which times `dir` is positive along the slip while `μk` does not hold it (the balance
    /// falls with `r` where it holds). NaN elsewhere.
    pub kinetic_balance: f64,
}

impl ContactForce {
    /// The friction force the contact needs, in its frame: `T` of a point contact; for a lying
    /// stretch `gμ·N`, its friction ratio ([`ContactForce::stretch_mu`]) times its resultant's
    /// normal part (its slip threshold and its kinetic friction compare this with `μ N`).
    pub fn friction(&self) -> f64 {
        if self.stretch_mu.is_nan() {
            self.tangential
        } else {
            self.stretch_mu * self.normal
        }
    }

    /// The friction ratio `T/N` with which the contact, at its slip limit here, breaks free and
    /// slides along: its own ratio, `±μs` where the limit is a root. A limit located on a jump
    /// of the branch leaves the point on the side where the contact holds, short of `μs`: it
    /// slides at `μs` the way its force points there. (The property's seed 69 at 256 cases: a side
    /// beside a slipping tip, its pair with the tip nearly indeterminate, had `T/N` 0.1848 at
    /// its located limit under μs 0.551, its force beyond the limit 8.3e-10 later; it slid at
    /// 0.1848, below μk 0.335, and ended the slip so.)
    pub fn breaking_ratio(&self) -> f64 {
        let ratio = self.friction() / self.normal;
        if ratio.abs() < self.mu_s * (1.0 - BREAK_SHORT) {
            self.mu_s.copysign(ratio)
        } else {
            ratio
        }
    }
}

/// How far short of `μs`, relative, the ratio of a contact at its located slip limit may be and
/// still be its own: a root is located to ~1e-12, one on the scatter of a nearly indeterminate
/// pair to ~1e-5 (a side creeping beside a stuck tip, seed 69's drag before its jump); a jump
/// leaves it short by a finite part of `μs`.
const BREAK_SHORT: f64 = 1e-3;

/// A surface contact's slip along the branch (module `events`' halt, `record`'s friction work).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct SlideRate {
    /// The slip rate of the rod at the contact against the surface, `dσ/dλ` of the material
    /// point there (arc length along the surface, `+` towards `+x`): where the contact slides
    /// (its rate decides when it halts and what its friction dissipates). NaN where not known.
    pub slip: f64,
    /// The way a contact sliding with a set friction ratio slides (the sign of the ratio: its
    /// friction `T` has that sign, and so has its slip), 0 for the others.
    pub dir: f64,
    /// Where a contact slides: its slip coordinate, the place along the surface less its place
    /// along the rod (`σ − dir·s`, the invariant of rolling), and `dN/dλ` of its normal force
    /// (the friction work it absorbs is `ratio·∫N dq`). NaN where not known.
    pub q: f64,
    pub dnormal: f64,
}

impl SlideRate {
    /// Not known (no sliding contact in the set, or its rates not found).
    const UNKNOWN: SlideRate = SlideRate {
        slip: f64::NAN,
        dir: 0.0,
        q: f64::NAN,
        dnormal: f64::NAN,
    };
}

/// Per-point quantities of a march.
#[derive(Clone, Debug)]
pub(crate) struct Watch {
    pub lam: f64,
    /// Total friction ratio `ΣT/ΣN` (signed).
    pub mu: f64,
    /// Total normal force.
    pub normal: f64,
    /// Total contact force (the foot carries its opposite).
    pub force: [f64; 2],
    /// Each contact.
    pub contacts: Vec<ContactForce>,
    /// Largest height of a free part of the rod above the surface (`−inf` without one) and where.
    pub clear: f64,
    pub clear_s: f64,
    /// The state on the rod at `clear_s`.
    pub clear_z: [f64; 4],
    /// `sin(φ(1) − β)` where the tip touches the surface (positive: it arrives from below).
    pub tip_approach: f64,
    /// Slope of `|μ|` along λ (from the exact tangent), if known.
    pub dmu_abs: Option<f64>,
    /// Largest `y` on the rod.
    pub y_max: f64,
    /// Height `y` of the last contact point (NaN without contact).
    pub last_y: f64,
    /// Tip slope.
    pub phi1: f64,
    /// Made without the free parts' clearance and the highest point (`clear`, `clear_s`,
    /// `clear_z`, `tip_approach` and `y_max` not numbers): a point that an event's search
    /// tries on its way to the root of a function of the contacts (see [`watch`]).
    pub light: bool,
}

/// Distance from a contact inside which a maximum of the height is that contact's own.
const NEAR: f64 = 1e-4;

/// Shortest free tail beyond the last contact whose end counts as a free part that may touch
/// down. The tail is unloaded, so its gap to the surface is the relative curvature at the contact
/// times `ℓ²/2` (plus `O(ℓ³)`): on a line `κ0·ℓ²/2 ≤ 4e-13` for `ℓ < 5e-7`, `|κ0| ≤ 3`; on a
/// curve its sign is the one event `Lie` watches (the gap's second derivative), so a shorter
/// tail's height is the rounding of the gap at the contact (issue 31: 6.7e-16 with the side
/// 1.5e-13 before the tip, taken as the tip touching down there, a state of two contacts
/// 4e-13 apart whose first step's residual was NaN).
const TAIL: f64 = 5e-7;

/// The solved rod as the watch sees it.
pub(crate) struct RodView<'a> {
    /// The whole rod (its interpolant locates the highest points).
    pub sol: &'a Solution,
    /// The foot's x in the lab frame.
    pub xf: f64,
    /// The state on the rod at `s` (refines what the interpolant found).
    pub exact: &'a mut dyn FnMut(f64) -> [f64; 4],
    /// The curvature `κ(s, m)`.
    pub kappa: &'a dyn Fn(f64, f64) -> f64,
    /// The rest shape is straight (an unloaded part beyond a tangent contact lies on the line).
    pub straight: bool,
}

/// The friction ratio `|T|/N` that no dry surface provides (real dry friction coefficients lie
/// below ~2; rubber on glass reaches 1–4): without μ0 it is the slip limit of the contacts of a
/// set that traps the rod between two contacts that do not slip (docs/model.md).
pub(crate) const SIDE_FRICTION_LIMIT: f64 = 10.0;

/// Whether a contact holds without slip on the surface (a line or a curve).
fn holds_on_surface(c: &crate::chain::Contact) -> bool {
    c.mode.no_slip() && matches!(c.geom, Geom::Line { .. } | Geom::Curve { .. })
}

/// Whether the set traps the rod between two surface contacts that do not slip (the segment
/// between them carries a pair of tangential forces that nothing in the model bounds).
pub(crate) fn traps(set: &ContactSet) -> bool {
    set.contacts.iter().filter(|c| holds_on_surface(c)).count() >= 2
}

/// Whether contact `j` is one of the contacts that trap the rod.
fn trapping(set: &ContactSet, j: usize) -> bool {
    holds_on_surface(&set.contacts[j]) && traps(set)
}

/// Whether contact `j` is a side on a surface line with another contact beyond it (the last
/// contact's curvature is its rest curvature, `m = 0` there, and a straight rest beyond it lies
/// on the line by design).
pub(crate) fn lies_inside(set: &ContactSet, j: usize) -> bool {
    let c = &set.contacts[j];
    !c.tip && matches!(c.geom, Geom::Line { .. }) && j + 1 < set.contacts.len()
}

/// Whether contact `j` is the inner end of the set's lying stretch (module `chain`, `Lying`).
fn lain_end(set: &ContactSet, j: usize) -> bool {
    set.lain() == Some(j)
}

/// [`ContactForce::curv`] of contact `j` of `set` at `s` (the rod's state there `zs`, if known;
/// foot at `xf`, the surface at amplitude `amp`).
fn side_curv(
    set: &ContactSet,
    j: usize,
    (s, zs): (f64, Option<[f64; 4]>),
    (xf, amp): (f64, f64),
    exact: &mut dyn FnMut(f64) -> [f64; 4],
    kappa: &dyn Fn(f64, f64) -> f64,
) -> f64 {
    let ct = &set.contacts[j];
    match &ct.geom {
        Geom::Line { beta, .. } if lies_inside(set, j) => {
            let z = zs.unwrap_or_else(|| exact(s));
            (z[2] - beta).cos() * kappa(s, z[3])
        }
        // (a lying stretch's inner end: its own events, module `events`)
        Geom::Curve { h } if !ct.tip && !lain_end(set, j) => {
            let z = zs.unwrap_or_else(|| exact(s));
            let inside = j + 1 < set.contacts.len();
            curve_curv(h, amp, z, xf, kappa(s, z[3]), inside)
        }
        _ => f64::NAN,
    }
}

/// The height's second derivative along the rod at a side contact on the curved surface `h`
/// (at amplitude `amp`; the rod's state `z` there in the foot frame, foot at `xf`, its curvature
/// `kappa`), `cos θ·(κ (cos φ + h' sin φ) − h'' cos² φ)` of the vertical gap `y − h(x)`: negative
/// while the rod curves away from the surface on both sides of the contact, zero where it curves
/// as the surface does (beyond it the rod cuts the surface beside the contact). As on a line
/// ([`lies_inside`]), NaN for the last contact where the surface is straight (`h'' = 0`, a
/// grating's flank or land): a straight rest beyond it lies on the surface by design.
fn curve_curv(
    h: &crate::surface::Height,
    amp: f64,
    z: [f64; 4],
    xf: f64,
    kappa: f64,
    inside: bool,
) -> f64 {
    let (_, d, dd) = h.jet_scaled(z[0] + xf, amp);
    if dd == 0.0 && !inside {
        return f64::NAN;
    }
    let (sp, cp) = z[2].sin_cos();
    (kappa * (cp + d * sp) - dd * cp * cp) / d.hypot(1.0)
}

/// The slip threshold `|T|/N` of contact `j` off a friction texture: μ0, or without it unbounded
/// (a lone contact's ratio is what a scan measures), except in a set that traps the rod between
/// two contacts that do not slip: [`SIDE_FRICTION_LIMIT`].
pub(crate) fn slip_limit(env: &Env, set: &ContactSet, j: usize) -> f64 {
    match env.mu0 {
        Some(m) => m,
        None if trapping(set, j) => SIDE_FRICTION_LIMIT,
        None => f64::INFINITY,
    }
}

/// A contact's normal and tangential force in its own frame, and their rates along the branch
/// with tangent `du` (NaN where not known): a surface line's unknowns themselves; on a curve, the
/// local normal and tangent at lab `x` (rates only for a stuck contact off a slip: the frame
/// turns with a moving contact point); at a point object, the rod's own frame there (its state
/// from `at_rod`). `f` is the contact's Cartesian force, `o` its offset in `u`.
fn own_frame(
    env: &Env,
    ct: &crate::chain::Contact,
    f: [f64; 2],
    (u, du, o): (&[f64], Option<&[f64]>, usize),
    x: f64,
    at_rod: impl FnOnce() -> [f64; 4],
) -> [f64; 4] {
    match ct.geom {
        Geom::Curve { .. } => {
            let (nl, tl) = crate::chain::local_forces(ct, u[o], u[o + 1], x);
            let (dn, dt) = match du {
                Some(d) if matches!(ct.mode, Mode::Stuck(_)) && env.ground.slide.is_none() => {
                    crate::chain::local_forces(ct, d[o], d[o + 1], x)
                }
                _ => (f64::NAN, f64::NAN),
            };
            [nl, tl, dn, dt]
        }
        Geom::Line { .. } | Geom::Slope { .. } => [
            u[o],
            u[o + 1],
            du.map_or(0.0, |d| d[o]),
            du.map_or(0.0, |d| d[o + 1]),
        ],
        Geom::Point { .. } => {
            let z = at_rod();
            let (tl, nl) = ct.rod_frame(z[2]);
            let dfx = du.map_or(0.0, |d| -d[o] * ct.n[0] + d[o + 1] * ct.t()[0]);
            let dfy = du.map_or(0.0, |d| -d[o] * ct.n[1] + d[o + 1] * ct.t()[1]);
            [
                -(f[0] * nl[0] + f[1] * nl[1]),
                f[0] * tl[0] + f[1] * tl[1],
                -(dfx * nl[0] + dfy * nl[1]),
                dfx * tl[0] + dfy * tl[1],
            ]
        }
    }
}

/// The watch of the point `(λ, u)` with tangent `du` on the rod `rod`.
///
/// `light`: the contacts alone. The clearance of the free parts is most of a point's watch
/// (over a texture it is searched on the rod against the profile), and the searches for an
/// event of the contacts (slip, stick, lift-off, ...) try several points of which only the root
/// is kept: a texture drag of the short rat preset spent 32 % of its time there.
pub(crate) fn watch(
    env: &Env,
    set: &ContactSet,
    lam: f64,
    u: &[f64],
    du: Option<&[f64]>,
    rod: RodView<'_>,
    light: bool,
) -> Watch {
    let RodView {
        sol,
        xf,
        exact,
        kappa,
        straight,
    } = rod;
    let amp = if env.ground.grow { lam } else { 1.0 };
    let mut contacts = Vec::with_capacity(set.contacts.len());
    let (mut nsum, mut tsum) = (0.0, 0.0);
    let (mut dnsum, mut dtsum) = (0.0, 0.0);
    let mut force = [0.0; 2];
    for (j, ct) in set.contacts.iter().enumerate() {
        let o = set.offset(j);
        let s = set.s_of(j, u);
        let f = ct.force(u[o], u[o + 1]);
        force[0] += f[0];
        force[1] += f[1];
        // (the rod's state at a contact along it, once)
        let zs = (s < 1.0).then(|| exact(s));
        let (x, y) = match zs {
            None => {
                let zb = sol.right();
                disk_point(set, j, zb, xf, amp).map_or((zb[0] + xf, zb[1]), |c| (c[0], c[1]))
            }
            Some(z) => (z[0] + xf, z[1]),
        };
        let [nrm, tng, dn, dt] = own_frame(env, ct, f, (u, du, o), x, || exact(s));
        nsum += nrm;
        tsum += tng;
        dnsum += dn;
        dtsum += dt;
        let side = env.ground.slide.map_or(1.0, |sl| sl.dir);
        let tex = env.ground.friction_at(x, side);
        let mu_s = match (ct.tip, tex) {
            (false, Some((ms, _))) => ms,
            _ => slip_limit(env, set, j),
        };
        contacts.push(ContactForce {
            normal: nrm,
            tangential: tng,
            s,
            x,
            y,
            mu_s,
            mu_k: env.ground.mu_k_at(x).unwrap_or(f64::INFINITY),
            slide: SlideRate::UNKNOWN,
            dxc: f64::NAN,
            // (a lying stretch's: module `own`)
            end_push: [f64::NAN; 2],
            lies_to: f64::NAN,
            stretch_mu: f64::NAN,
            turn: [f64::NAN; 2],
            kinetic_balance: f64::NAN,
            curv: side_curv(set, j, (s, zs), (xf, amp), &mut *exact, kappa),
        });
    }
    let mu = if nsum != 0.0 { tsum / nsum } else { 0.0 };
    let dmu_abs = du
        .filter(|_| dnsum.is_finite() && dtsum.is_finite())
        .map(|_| {
            let dmu = (dtsum * nsum - tsum * dnsum) / (nsum * nsum);
            if mu == 0.0 {
                dmu.abs()
            } else {
                mu.signum() * dmu
            }
        });
    let (clear, clear_s, tip_approach) = match (env.line, &env.ground.curve) {
        _ if light => (f64::NAN, f64::NAN, f64::NAN),
        (_, Some(h)) => curve_clearance(set, u, (h, amp), sol, xf, exact, kappa),
        (line, None) => match line {
            Some((p0, beta)) => clearance(
                set,
                u,
                (p0, beta),
                RodView {
                    sol,
                    xf,
                    exact: &mut *exact,
                    kappa,
                    straight,
                },
            ),
            None => (f64::NEG_INFINITY, f64::NAN, f64::NAN),
        },
    };
    let clear_z = if clear_s.is_finite() {
        exact(clear_s)
    } else {
        [f64::NAN; 4]
    };
    let y_max = if light {
        f64::NAN
    } else {
        crate::sampling::extrema(sol, 0.0, 1.0).max
    };
    let last_y = contacts.last().map_or(f64::NAN, |c| c.y);
    Watch {
        lam,
        mu,
        normal: nsum,
        force,
        contacts,
        clear,
        clear_s,
        clear_z,
        tip_approach,
        dmu_abs,
        y_max,
        last_y,
        phi1: sol.right()[2],
        light,
    }
}

/// The lab contact point of contact `j` if it is a round tip on a surface (the rod's end state
/// `zb`, foot at `xf`, a curve at amplitude `amp`); `None` for a point tip or any other contact.
fn disk_point(set: &ContactSet, j: usize, zb: &[f64], xf: f64, amp: f64) -> Option<[f64; 2]> {
    let ct = &set.contacts[j];
    if !(ct.tip && set.tip_radius > 0.0) {
        return None;
    }
    match ct.geom {
        Geom::Line { .. } | Geom::Curve { .. } => {
            crate::chain::tip_point(set.tip_radius, &ct.geom, zb, xf, amp)
        }
        _ => None,
    }
}

/// Largest height above the surface line (shifted to where the contacts hold it: the line through
/// `p0` in the lab frame, the foot at `xf`) of the rod's free parts — outside the contacts' own
/// neighbourhoods, and not over an unloaded rest that lies on the line — refined on the rod, and
/// the tip's approach `sin(φ(1) − β)` (NaN unless the tip touches the surface).
fn clearance(
    set: &ContactSet,
    u: &[f64],
    (p0, beta): ([f64; 2], f64),
    rod: RodView<'_>,
) -> (f64, f64, f64) {
    let RodView {
        sol,
        xf,
        exact,
        kappa,
        straight,
    } = rod;
    let (sb, cb) = beta.sin_cos();
    let h = |x: f64, y: f64| -sb * (x + xf - p0[0]) + cb * (y - p0[1]);
    let surf: Vec<f64> = set
        .contacts
        .iter()
        .enumerate()
        .filter(|(_, c)| matches!(c.geom, Geom::Line { .. }))
        .map(|(j, _)| set.s_of(j, u))
        .collect();
    // the line the contacts hold the rod on: its height offset (0 when the scene's own surface,
    // else the pressed one's)
    // (a round tip's centre, its radius below the line)
    let r = set.tip_radius;
    let off = surf
        .last()
        .map(|&s| {
            let z = exact(s);
            if s >= 1.0 && r > 0.0 {
                h(z[0], z[1]) + r
            } else {
                h(z[0], z[1])
            }
        })
        .unwrap_or(0.0);
    let s_last = set
        .contacts
        .iter()
        .enumerate()
        .map(|(j, _)| set.s_of(j, u))
        .fold(0.0, f64::max);
    // an unloaded rest lying on the line (a straight rest shape beyond a tangent contact)
    let lying_from = match set.contacts.last() {
        Some(c) if !c.tip && matches!(c.geom, Geom::Line { .. }) && straight => s_last,
        _ => 2.0,
    };
    let near = |s: f64| surf.iter().any(|&c| (s - c).abs() < NEAR) || s >= lying_from - NEAR;
    // candidates: local maxima of the height on the interpolant, refined on the rod where they
    // come near the surface (far below it the interpolant's error, ~1e-8, does not matter)
    let mut best = (f64::NEG_INFINITY, f64::NAN);
    // maxima the interpolant hides: where the rod turns nearly parallel to the line within a
    // step (a dip of φ below β and back inside one long step of the integrator, as before a tip
    // that turns tangent), sin(φ − β) is sampled on the rod itself
    let sides: Vec<f64> = set
        .contacts
        .iter()
        .enumerate()
        .filter(|(_, c)| !c.tip)
        .map(|(j, _)| set.s_of(j, u))
        .collect();
    for (s, v) in hidden_maxima(sol, exact, beta, &h, &sides) {
        if s > 0.0 && s < 1.0 && !near(s) && v - off > best.0 {
            best = (v - off, s);
        }
    }
    for (s0, v0) in crate::sampling::local_maxima(sol, -sb, cb) {
        if s0 <= 0.0 || near(s0) || s0 >= 1.0 {
            continue;
        }
        // the interpolant measures −sin β·x + cos β·y in the foot frame
        let v0 = v0 + h(0.0, 0.0);
        let (s, v) = if v0 - off > -1e-4 {
            match refine_max(exact, kappa, s0, beta, &h) {
                Some(m) => m,
                // the interpolant's maximum is none of the rod's
                None => continue,
            }
        } else {
            (s0, v0)
        };
        if near(s) {
            continue;
        }
        if v - off > best.0 {
            best = (v - off, s);
        }
    }
    if best.0 == f64::NEG_INFINITY {
        // no free maximum: the foot's height (always below), so that the function stays finite
        best = (h(0.0, 0.0) - off, 0.0);
    }
    // the tip, when it is free (its height is a maximum of the free part's end) and not within
    // the last contact's neighbourhood (a tail of length ℓ → 0 before a peel-back sits
    // κ0·ℓ²/2 ≤ 4e-13 from the line for ℓ < 5e-7, |κ0| ≤ 3: rounding, no touchdown)
    let tip_contact = set.tip();
    if !tip_contact && lying_from > 1.0 && 1.0 - s_last >= TAIL {
        let zb = sol.right();
        // (a round tip touches down where its centre comes within its radius)
        let v = if r > 0.0 {
            h(zb[0], zb[1]) + r - off
        } else {
            h(zb[0], zb[1]) - off
        };
        if v > best.0 {
            best = (v, 1.0);
        }
    }
    let approach = if tip_contact
        && r <= 0.0
        && matches!(
            set.contacts.last().map(|c| &c.geom),
            Some(Geom::Line { .. })
        ) {
        (sol.right()[2] - beta).sin()
    } else {
        f64::NAN
    };
    (best.0, best.1, approach)
}

/// As [`clearance`], above the curved surface `h` (the gap `y − h(x)` measured vertically, from
/// the offset the contacts hold the rod at); the tip's approach `sin(φ(1) − θ(x(1)))`.
fn curve_clearance(
    set: &ContactSet,
    u: &[f64],
    (h, amp): (&crate::surface::Height, f64),
    sol: &Solution,
    xf: f64,
    exact: &mut dyn FnMut(f64) -> [f64; 4],
    kappa: &dyn Fn(f64, f64) -> f64,
) -> (f64, f64, f64) {
    let hh = |x: f64| h.jet_scaled(x, amp).0;
    let mut ss: Vec<f64> = (0..set.contacts.len()).map(|j| set.s_of(j, u)).collect();
    // a lying stretch: on the surface from its contact out to its outer end
    let lain = set
        .lain()
        .map_or((f64::NAN, f64::NAN), |j| (ss[j], set.s2_of(u)));
    if let Some(j) = set.lain() {
        ss.insert(j + 1, lain.1);
    }
    // (a round tip's centre on the surface offset by its radius: its gap to that offset curve)
    let r = set.tip_radius;
    let disk_gap = |z: &[f64]| -> Option<f64> {
        let dk = crate::surface::disk_on_curve(h, r, z[0] + xf, amp)?;
        Some(z[1] - (hh(dk.xc) - r * dk.th.cos()))
    };
    let off = ss
        .last()
        .map(|&s| {
            let z = if s >= 1.0 {
                sol.right().to_vec()
            } else {
                exact(s).to_vec()
            };
            match (s >= 1.0 && r > 0.0).then(|| disk_gap(&z)) {
                Some(g) => g.unwrap_or(f64::NAN),
                None => z[1] - hh(z[0] + xf),
            }
        })
        .unwrap_or(0.0);
    let near = |s: f64| {
        ss.iter().any(|&c| (s - c).abs() < NEAR) || (s > lain.0 - NEAR && s < lain.1 + NEAR)
    };
    let lab = |s: f64, z: [f64; 4]| [z[0] + xf, z[1], z[2], kappa(s, z[3])];
    let mut sample = |s: f64| {
        let mut z = [0.0; 4];
        sol.eval(s, &mut z);
        lab(s, z)
    };
    let mut on_rod = |s: f64| lab(s, exact(s));
    // samples fine enough for the surface's own waves over the rod's reach
    let n = 256;
    let (mut best, mut at) =
        crate::surface::curve_clearance(h, amp, off, n, &ss, &mut sample, &mut on_rod, &near);
    let zb = sol.right();
    // (a tail shorter than `TAIL` beyond the last contact: its height is rounding, see there)
    let s_last = ss.iter().copied().fold(0.0, f64::max);
    if !set.tip() && h.covers(zb[0] + xf) && 1.0 - s_last >= TAIL {
        let v = if r > 0.0 {
            disk_gap(zb).unwrap_or(f64::NEG_INFINITY) - off
        } else {
            zb[1] - hh(zb[0] + xf) - off
        };
        if v > best {
            (best, at) = (v, 1.0);
        }
    }
    if best == f64::NEG_INFINITY {
        // nothing free over the surface: the foot's gap (always below), to stay finite
        best = -hh(xf) - off;
        at = 0.0;
    }
    let approach = if set.tip() && r <= 0.0 {
        (zb[2] - h.angle_scaled(zb[0] + xf, amp).0).sin()
    } else {
        f64::NAN
    };
    (best, at, approach)
}

/// The rod's own maximum of the height near the interpolant's maximum `s0`: Newton on
/// `φ(s) = β` (the tangent point) where the rod is concave at `s0`; else (the interpolant's
/// error, ~1e-8 in the height, puts its maximum where the rod curves the other way, as near a
/// tip that turns tangent) the root of `sin(φ − β)` falling through zero nearest `s0` within
/// `MAX_WINDOW` on either side, on the rod. `None` when the rod has no maximum there.
fn refine_max(
    exact: &mut dyn FnMut(f64) -> [f64; 4],
    kappa: &dyn Fn(f64, f64) -> f64,
    s0: f64,
    beta: f64,
    h: &dyn Fn(f64, f64) -> f64,
) -> Option<(f64, f64)> {
    let mut s = s0;
    let mut z = exact(s);
    let concave = |s: f64, z: &[f64; 4]| (z[2] - beta).cos() * kappa(s, z[3]);
    if concave(s, &z).partial_cmp(&0.0) != Some(std::cmp::Ordering::Less) {
        let (a, b) = ((s0 - MAX_WINDOW).max(0.0), (s0 + MAX_WINDOW).min(1.0));
        let n = 32;
        let mut g =
            |s: f64| -> Result<f64, std::convert::Infallible> { Ok((exact(s)[2] - beta).sin()) };
        let pts: Vec<(f64, f64)> = (0..=n)
            .map(|i| {
                let t = a + (b - a) * i as f64 / n as f64;
                (t, g(t).unwrap_or(f64::NAN))
            })
            .collect();
        let (lo, hi) = pts
            .windows(2)
            .filter(|w| w[0].1 > 0.0 && w[1].1 <= 0.0)
            .map(|w| (w[0].0, w[1].0))
            .min_by(|p, q| {
                let d = |r: &(f64, f64)| (0.5 * (r.0 + r.1) - s0).abs();
                d(p).total_cmp(&d(q))
            })?;
        s = crate::search::root(&mut g, lo, hi, 1e-15).ok()?;
        z = exact(s);
        return Some((s, h(z[0], z[1])));
    }
    for _ in 0..8 {
        // height' = sin(φ − β), height'' = cos(φ − β)·κ
        let g = (z[2] - beta).sin();
        let dg = concave(s, &z);
        if dg >= 0.0 || !dg.is_finite() {
            break;
        }
        let next = (s - g / dg).clamp(0.0, 1.0);
        if next == s {
            break;
        }
        let step = (next - s).abs();
        s = next;
        z = exact(s);
        if step < 1e-14 {
            break;
        }
    }
    Some((s, h(z[0], z[1])))
}

/// The rod's maxima of the height inside the integrator's steps whose ends are nearly parallel
/// to the line (`|sin(φ − β)| < HIDDEN_SLOPE` at either end), rising at the start and holding
/// none of the side contacts `sides`: the lowest `sin(φ − β)` of the step on the rod (Brent's
/// minimizer), and where it is not positive its fall through zero before it (Brent's root).
fn hidden_maxima(
    sol: &Solution,
    exact: &mut dyn FnMut(f64) -> [f64; 4],
    beta: f64,
    h: &dyn Fn(f64, f64) -> f64,
    sides: &[f64],
) -> Vec<(f64, f64)> {
    let n = sol.n;
    let g_at = |i: usize| (sol.z[i * n + 2] - beta).sin();
    let mut out = Vec::new();
    for i in 0..sol.mesh.len().saturating_sub(1) {
        let (a, b) = (sol.mesh[i], sol.mesh[i + 1]);
        if b <= a
            || (g_at(i).abs() >= HIDDEN_SLOPE && g_at(i + 1).abs() >= HIDDEN_SLOPE)
            || sides.iter().any(|&c| c > a - NEAR && c < b + NEAR)
        {
            // (a step that ends at a side contact has the contact's own maximum there, which
            // a loose tolerance shifts out of its neighbourhood)
            continue;
        }
        // rising clearly (not the step that starts at a side contact's own tangent point)
        let ga = g_at(i);
        if ga.partial_cmp(&HIDDEN_START) != Some(std::cmp::Ordering::Greater) {
            continue;
        }
        // the lowest slope inside (a dip of φ below β and back) or at the end
        let mut g =
            |s: f64| -> Result<f64, std::convert::Infallible> { Ok((exact(s)[2] - beta).sin()) };
        let (lo, glo) = match crate::search::maximize(&mut |s| g(s).map(|v| -v), a, b, 1e-12) {
            Ok((x, v)) if -v < g_at(i + 1) => (x, -v),
            _ => (b, g_at(i + 1)),
        };
        if glo <= 0.0 {
            if let Ok(r) = crate::search::root(&mut g, a, lo, 1e-15) {
                out.push(r);
            }
        }
    }
    out.into_iter()
        .map(|r| {
            let z = exact(r);
            (r, h(z[0], z[1]))
        })
        .collect()
}

/// Steps whose ends are within this slope of the line are searched on the rod.
const HIDDEN_SLOPE: f64 = 1e-2;
/// ... when the slope at their start is above this.
const HIDDEN_START: f64 = 1e-6;

/// How far from the interpolant's maximum the rod's is looked for when they disagree.
const MAX_WINDOW: f64 = 0.02;

/// Whether the set has a contact sliding on the surface (its slip rate is watched).
pub(crate) fn has_slider(set: &ContactSet) -> bool {
    set.contacts.iter().any(crate::chain::is_slider)
}

/// The slip rates of the surface contacts (`ContactForce::slip`) from the rates of the contact
/// points' states `rates` (`dz(s_k)/dλ` in the foot's frame, a moving contact point's motion
/// along the rod included), the tangent `du` and the foot's rate `foot` (`dx_f/dλ`): the rate of
/// the contact point along the surface less its motion along the rod (`dir·ds/dλ`, `dir` the
/// way the rod runs along the surface there), so the material point's slip.
pub(crate) fn fill_slip(
    w: &mut Watch,
    set: &ContactSet,
    (u, du): (&[f64], &[f64]),
    rates: &[[f64; 4]],
    foot: f64,
) {
    for (j, ct) in set.contacts.iter().enumerate() {
        let Some(r) = rates.get(j) else {
            continue;
        };
        let vx = r[0] + foot;
        let x = w.contacts[j].x;
        let o = set.offset(j);
        // a round tip rolls: its contact point moves by the disk's turn as well, so its slip is
        // the rate of its place less the turn's (the anchor of a stuck disk, `tip_place`)
        let disk = (ct.tip && set.tip_radius > 0.0).then_some(set.tip_radius);
        // the place along the surface and its rate, the way the rod runs along it, the normal
        // force's rate in the surface's local frame
        let (place, along, dir, dn) = match &ct.geom {
            Geom::Line { p0, beta } => {
                let (sb, cb) = beta.sin_cos();
                // (on the line through p0: its height follows from x)
                let place = (x - p0[0]) / cb;
                let turn = disk.map_or((0.0, 0.0), |rr| (rr * (w.phi1 - beta), rr * r[2]));
                (
                    place - turn.0,
                    cb * vx + sb * r[1] - turn.1,
                    (ct.phi_ref - beta).cos().round(),
                    du[o],
                )
            }
            Geom::Curve { h } => {
                let (th, dth) = h.angle(x);
                let kpi = ct.kpi(th);
                let (sg, dsg) = h.sigma(x);
                // (a disk's contact point's x rate, else the rod end's)
                let vc = if disk.is_some() {
                    w.contacts[j].dxc
                } else {
                    vx
                };
                let turn = disk.map_or((0.0, 0.0), |rr| {
                    (rr * (w.phi1 - th), rr * (r[2] - dth * vc))
                });
                // N_loc = Fx sin θ − Fy cos θ: through the unknowns and through θ(x)
                let f = ct.force(du[o], du[o + 1]);
                let f0 = ct.force(u[o], u[o + 1]);
                let (st, c) = th.sin_cos();
                let dn = f[0] * st - f[1] * c + (f0[0] * c + f0[1] * st) * dth * vc;
                (sg - turn.0, dsg * vc - turn.1, kpi.cos().round(), dn)
            }
            _ => continue,
        };
        let s = w.contacts[j].s;
        let moving = if ct.tip { 0.0 } else { dir * du[o + 2] };
        let c = &mut w.contacts[j];
        c.slide = SlideRate {
            slip: along - moving,
            dir: match ct.mode {
                Mode::Sliding(r) => r.signum(),
                _ => 0.0,
            },
            q: place - if ct.tip { 0.0 } else { dir * s },
            dnormal: dn,
        };
    }
}
