//! Point objects touching the side of the rod — a peg, an edge: the rod at a given foot angle
//! ([`solve_peg`]), the whisk that turns the foot against the object ([`whisk`]), and the inverse
//! that reads the object's place off the base signals ([`locate`]).
//!
//! The object sits at `P = (X, Y)` in the frame of the unturned foot; the foot turns clockwise by
//! `θ` (`φ(0) = π/2 − θ + c·m(0)`). The rod touches the object at an unknown arc length
//! `s_c ∈ (0, 1]`: the force on the rod there is normal to it (frictionless), or held by
//! friction (the material point `s_c` stuck to the object while `|T| ≤ μ0 N`, then sliding
//! with `T = ±μ0 N`); the moment vanishes at `s_c` and the rod beyond it is unloaded. The
//! unknowns `(m(0), N, T, s_c)` are those of one contact of the contact chain, solved in the same
//! Newton and continuation as every other contact state: the whisk is the one march in the
//! foot angle, from first touch (where the rest shape, turned rigidly with the foot, reaches the
//! object) until the object slips off the tip or the angle asked for.

use crate::chain::{Chain, Contact, ContactSet, Family, Geom, Mode};
use crate::config::SolverConfig;
use crate::control::corrector_tol;
use crate::engine::{Begin, FirstPoint};
use crate::march::{march, Spec};
use crate::profile::{Profile, Uniform};
use crate::report::{Event, StopReason};
use crate::rodsolve::solve_damped;
use crate::search;
use crate::shape::ShapePoint;
use crate::shooter::Shooter;
use crate::watch::Env;
use crate::{Rod, VibrissaError};
use bvp::Stats;
use serde::Serialize;
use std::f64::consts::FRAC_PI_2;

/// The rod against the object at one foot angle.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PegPoint {
    /// Foot angle θ (clockwise).
    pub theta: f64,
    /// Arc length of the contact point.
    pub s_c: f64,
    /// Magnitude of the contact force on the rod.
    pub f: f64,
    /// The contact force on the rod, components in the frame of the unturned foot (the rod
    /// carries it to its base: the base signals).
    pub fx: f64,
    /// See [`PegPoint::fx`].
    pub fy: f64,
    /// The same force along the rod at its foot (`τ0 = (cos φ(0), sin φ(0))`, positive pushing
    /// out along the rod).
    pub f_axial: f64,
    /// The same force across the rod at its foot (`ν0 = (sin φ(0), −cos φ(0))`, positive to the
    /// right of the rod).
    pub f_transverse: f64,
    /// `m(0)`, the internal moment at the foot (the paper's clamp moment is `−m(0)`).
    pub m_base: f64,
    /// Normal force at the contact (≥ 0 while it pushes).
    pub normal: f64,
    /// Friction ratio `T/N` at the contact (0 frictionless).
    pub mu: f64,
    /// The event at this point (`slip`, `slip_off`, `lift_off`, `fold_in_d`), if it is one.
    pub event: Option<Event>,
}

/// Options of [`whisk`] and [`solve_peg`].
#[derive(Clone, Debug, PartialEq, Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct WhiskOptions {
    /// Largest foot angle (rad). Default 1.
    pub theta_max: f64,
    /// Output angles, uniformly from first touch to `theta_max`. Default 201.
    pub points: usize,
    /// Stiction coefficient at the object: the contact sticks while `|T| ≤ μ0 N`, then slides
    /// with `|T| = μ0 N`. Default none (frictionless).
    pub mu0: Option<f64>,
    /// Solver settings.
    pub solver: SolverConfig,
    /// Keep each output point's shape sampled at this many points.
    pub keep_shapes: Option<usize>,
}

impl Default for WhiskOptions {
    fn default() -> Self {
        WhiskOptions {
            theta_max: 1.0,
            points: 201,
            mu0: None,
            solver: SolverConfig::default(),
            keep_shapes: None,
        }
    }
}

impl WhiskOptions {
    /// Checks against [`limits`](crate::limits): `theta_max ∈ (−π/2, π/2)`,
    /// `points ∈ [2, 1e6]`, `mu0 ≥ 0` finite, `keep_shapes ∈ [2, 1e5]`, the solver.
    pub fn validate(&self) -> Result<(), VibrissaError> {
        use crate::limits;
        limits::THETA.check("theta_max", self.theta_max)?;
        limits::POINTS.check_count("points", self.points)?;
        if let Some(m) = self.mu0 {
            limits::MU0.check("mu0", m)?;
        }
        if let Some(n) = self.keep_shapes {
            limits::SHAPE_POINTS.check_count("keep_shapes", n)?;
            limits::check_shapes("keep_shapes", n, self.points)?;
        }
        self.solver.validate()
    }
}

/// Result of [`whisk`].
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct WhiskResult {
    /// The foot angle of first touch.
    pub first_touch: f64,
    /// The arc length the rest shape first touches at.
    pub s_touch: f64,
    /// Points at the output angles, and the events, in order.
    pub points: Vec<PegPoint>,
    /// Why the whisk stopped (`d` is the foot angle there).
    pub stop: StopReason,
    /// Solver work.
    pub stats: Stats,
    /// Shapes of the output points (if asked for), in the frame of the unturned foot.
    pub shapes: Vec<Vec<ShapePoint>>,
}

fn check_peg(peg: [f64; 2]) -> Result<(), VibrissaError> {
    let r = (peg[0] * peg[0] + peg[1] * peg[1]).sqrt();
    if !(peg[0].is_finite() && peg[1].is_finite() && r > 0.0 && r < 1.0) {
        return Err(VibrissaError::range(
            "object distance from the foot",
            r,
            "(0, 1) rod lengths (a point the rod can reach)",
        ));
    }
    Ok(())
}

/// Where the rest shape, turned rigidly with the foot, first reaches the object (turning
/// clockwise from `theta0`): `(θ, s)`; `OutOfReach` if it never does.
fn first_touch<P: Profile>(
    sh: &mut Shooter<P>,
    peg: [f64; 2],
    theta0: f64,
) -> Result<(f64, f64, [f64; 4]), VibrissaError> {
    let z0 = [0.0, 0.0, FRAC_PI_2, 0.0];
    for _ in 0..32 {
        let shot = sh.shoot(0, 0.0, 1.0, z0, &[], [0.0, 0.0], false);
        if shot.err <= 1.0 || !sh.refine(0) {
            break;
        }
    }
    let rp = (peg[0] * peg[0] + peg[1] * peg[1]).sqrt();
    let ap = peg[1].atan2(peg[0]);
    let dist = |z: &[f64]| (z[0] * z[0] + z[1] * z[1]).sqrt();
    let (ps, pz, _) = sh.path(0);
    let (ps, pz) = (ps.to_vec(), pz.to_vec());
    let mut best: Option<(f64, f64, [f64; 4])> = None;
    let mut reach: f64 = 0.0;
    for i in 0..ps.len() - 1 {
        let (za, zb) = (&pz[4 * i..4 * i + 4], &pz[4 * i + 4..4 * i + 8]);
        reach = reach.max(dist(zb));
        if (dist(za) - rp) * (dist(zb) - rp) > 0.0 {
            continue;
        }
        let mut f =
            |s: f64| -> Result<f64, std::convert::Infallible> { Ok(dist(&sh.state_at(0, s)) - rp) };
        let Ok(s) = search::root(&mut f, ps[i], ps[i + 1], 1e-15) else {
            continue;
        };
        let z = sh.state_at(0, s);
        // the rest shape's point at the object's distance, turned onto it: θ = its angle − the
        // object's (clockwise positive), the first such angle from theta0 on
        let mut theta = z[1].atan2(z[0]) - ap;
        theta -= std::f64::consts::TAU * ((theta - theta0) / std::f64::consts::TAU).floor();
        if best.is_none_or(|b| theta < b.0) {
            best = Some((theta, s, z));
        }
    }
    match best {
        Some(b) if b.0 < theta0 + std::f64::consts::PI => Ok(b),
        _ => Err(VibrissaError::OutOfReach {
            what: format!(
                "the object at ({}, {}) is out of reach of the rod turning from {theta0}",
                peg[0], peg[1]
            ),
            reach,
            needed: rp,
        }),
    }
}

/// The whisk: the foot turns clockwise from first touch to `opts.theta_max` against the object
/// at `peg` (frame of the unturned foot); one point per output angle, the events in order
/// (`slip` where friction gives and the contact starts sliding, `slip_off` where the object
/// slips off the tip, which ends it).
pub fn whisk(rod: &Rod, peg: [f64; 2], opts: &WhiskOptions) -> Result<WhiskResult, VibrissaError> {
    opts.validate()?;
    check_peg(peg)?;
    if rod.has_uniform_profile() {
        whisk_with(rod, Uniform, peg, opts, None)
    } else {
        whisk_with(rod, rod.profile(1.0), peg, opts, None)
    }
}

/// The rod against the object at the foot angle `theta`: the whisk from first touch to `theta`.
/// `OutOfReach` when the turned rod does not touch the object (before first touch, or past the
/// angle where it slipped off the tip).
pub fn solve_peg(
    rod: &Rod,
    peg: [f64; 2],
    theta: f64,
    opts: &WhiskOptions,
) -> Result<PegPoint, VibrissaError> {
    at_theta(whisk_to(rod, peg, theta, opts, None)?, theta)
}

/// The whisk of `opts` up to `theta` alone (shapes of `keep` samples).
fn whisk_to(
    rod: &Rod,
    peg: [f64; 2],
    theta: f64,
    opts: &WhiskOptions,
    keep: Option<usize>,
) -> Result<WhiskResult, VibrissaError> {
    let o = WhiskOptions {
        theta_max: theta,
        keep_shapes: keep,
        ..opts.clone()
    };
    o.validate()?;
    check_peg(peg)?;
    if rod.has_uniform_profile() {
        whisk_with(rod, Uniform, peg, &o, Some(theta))
    } else {
        whisk_with(rod, rod.profile(1.0), peg, &o, Some(theta))
    }
}

/// [`solve_peg`] and the rod's shape there (`opts.keep_shapes` samples, default 101; frame of
/// the unturned foot).
pub fn solve_peg_shape(
    rod: &Rod,
    peg: [f64; 2],
    theta: f64,
    opts: &WhiskOptions,
) -> Result<(PegPoint, Vec<ShapePoint>), VibrissaError> {
    let r = whisk_to(rod, peg, theta, opts, Some(opts.keep_shapes.unwrap_or(101)))?;
    let shape = r.shapes.last().cloned().unwrap_or_default();
    let p = at_theta(r, theta)?;
    Ok((p, shape))
}

/// The point of a one-angle whisk at `theta`, or why there is none.
fn at_theta(r: WhiskResult, theta: f64) -> Result<PegPoint, VibrissaError> {
    match (&r.stop, r.points.last()) {
        (StopReason::DMax, Some(p)) if p.theta == theta => Ok(p.clone()),
        (StopReason::SlipOff { d }, _) => Err(VibrissaError::OutOfReach {
            what: format!("the object slipped off the tip at theta = {d}, before theta = {theta}"),
            reach: *d,
            needed: theta,
        }),
        (stop, _) => Err(VibrissaError::NoConvergence {
            what: format!("the rod against the object at theta = {theta}"),
            reason: stop.to_string(),
        }),
    }
}

fn whisk_with<P: Profile>(
    rod: &Rod,
    profile: P,
    peg: [f64; 2],
    opts: &WhiskOptions,
    only: Option<f64>,
) -> Result<WhiskResult, VibrissaError> {
    let tol = opts.solver.tol;
    let c = rod.support_compliance();
    let general = rod.profile(1.0);
    let mut sh = Shooter::new(profile.clone(), c, tol, 8);
    let (theta_t, s_t, z_t) = first_touch(&mut sh, peg, 0.0)?;
    if theta_t > opts.theta_max {
        return Err(VibrissaError::OutOfReach {
            what: format!(
                "the object at ({}, {}) is first touched at theta = {theta_t}, beyond {} = {}",
                peg[0],
                peg[1],
                // (solve --peg asks for one angle, theta; a whisk turns to theta_max)
                if only.is_some() { "theta" } else { "theta_max" },
                opts.theta_max
            ),
            reach: opts.theta_max,
            needed: theta_t,
        });
    }
    // the force frame: the rod's normal towards the side the turning rod moves (its right)
    let phi_t = z_t[2] - theta_t;
    let (sp, cp) = phi_t.sin_cos();
    let ct = Contact {
        tip: s_t >= 1.0,
        geom: Geom::Point { p: peg },
        mode: match opts.mu0 {
            Some(_) => Mode::Stuck(s_t),
            None => Mode::Free,
        },
        n: [sp, -cp],
        phi_ref: phi_t,
    };
    let set = ContactSet::of(vec![ct]);
    let env = Env {
        ground: Default::default(),
        line: None,
        mu0: opts.mu0,
        compound: false,
        target: None,
    };
    let grid: Vec<f64> = match only {
        Some(t) => vec![t],
        None => {
            let n = opts.points;
            (0..n)
                .map(|i| {
                    if i + 1 == n {
                        opts.theta_max
                    } else {
                        theta_t + (opts.theta_max - theta_t) * i as f64 / (n - 1) as f64
                    }
                })
                .collect()
        }
    };
    let spec = Spec {
        env: &env,
        grid: &grid,
        lam_end: opts.theta_max,
        keep_shapes: opts.keep_shapes,
        general: &general,
        friction: true,
        check_start: false,
        slide: true,
        pass_fold_ahead: false,
        retangent: false,
    };
    let u0 = vec![0.0, 0.0, 0.0, s_t];
    let ntol = corrector_tol(tol);
    let mut chain = Chain::new(sh, set.clone(), Family::Turn);
    if let Some(mu0) = opts.mu0 {
        // stuck from first touch if the friction it needs at once is within μ0 (dT/dN of the
        // stuck state's tangent), else sliding from the start, friction against the way the
        // contact point moves along the rod
        chain.set.contacts[0].mode = stick_or_slide(&mut chain, theta_t, &u0, s_t, mu0);
    }
    // (friction that cannot hold the contact from first touch on: it slides at once, the whisk's
    // stick-to-slide event at its first point, issue 33)
    let slides_at_once = matches!(chain.set.contacts[0].mode, Mode::Sliding(_));
    let cv = solve_damped(&mut chain, theta_t, &u0, ntol, 30).map_err(|e| {
        VibrissaError::NoConvergence {
            what: format!("the rod at first touch (theta = {theta_t})"),
            reason: e.to_string(),
        }
    })?;
    let mut begun = Begin {
        chain,
        env: env.clone(),
        solver: &opts.solver,
        lam: theta_t,
        u: cv.u.clone(),
        first: FirstPoint::Converged(cv),
        run: "whisk",
        hand_over: false,
        what: "the rod at first touch".into(),
    }
    .begin()?;
    let out = march(
        &mut *begun.stepper,
        &spec,
        &profile,
        begun.p0,
        Stats::default(),
    );
    let points: Vec<PegPoint> = out
        .points
        .iter()
        .map(|p| {
            let phi0 = FRAC_PI_2 - p.d + c * p.m_base;
            let (s0, c0) = phi0.sin_cos();
            PegPoint {
                theta: p.d,
                s_c: p.s_c.unwrap_or(1.0),
                f: p.f,
                fx: p.fx,
                fy: p.fy,
                f_axial: p.fx * c0 + p.fy * s0,
                f_transverse: p.fx * s0 - p.fy * c0,
                m_base: p.m_base,
                normal: p.normal,
                mu: p.mu,
                event: p.event,
            }
        })
        .collect();
    let mut points = points;
    if let Some(first) = points
        .first_mut()
        .filter(|p| only.is_none() && p.theta == theta_t)
    {
        if slides_at_once && first.event.is_none() {
            first.event = Some(Event::Slip);
        }
    }
    Ok(WhiskResult {
        first_touch: theta_t,
        s_touch: s_t,
        points,
        stop: out.stop,
        stats: out.stats,
        shapes: out.shapes,
    })
}

/// The mode of a frictional contact at first touch (`N = T = 0` at `theta`): stuck at `s_t` if
/// the stuck state's tangent needs `|dT/dN| ≤ μ0` there (a rod pinned at a material point it
/// reaches fully stretched cannot turn at all: the tangent does not exist), else sliding with
/// `T = ±μ0 N`, the sign against the contact point's motion along the rod (from the
/// frictionless state's tangent).
fn stick_or_slide<P: Profile>(
    chain: &mut Chain<P>,
    theta: f64,
    u0: &[f64],
    s_t: f64,
    mu0: f64,
) -> Mode {
    let tangent = |chain: &mut Chain<P>| -> Option<Vec<f64>> {
        let e = chain.eval(u0, theta, true).ok()?;
        let (j, l) = (e.jac?, e.r_lam?);
        let cv = crate::rodsolve::Converged {
            u: u0.to_vec(),
            jac: j,
            r_lam: l,
            residual: 0.0,
            iterations: 0,
        };
        cv.tangent()
    };
    // stuck a little further on (a taut rod pinned at a material point cannot turn at all)
    chain.set.contacts[0].mode = Mode::Stuck(s_t);
    let dt = 1e-5;
    if let Some(du) = tangent(chain) {
        let guess: Vec<f64> = u0.iter().zip(&du).map(|(u, d)| u + dt * d).collect();
        if let Ok(cv) = solve_damped(chain, theta + dt, &guess, corrector_tol(chain.sh.tol), 12) {
            let z = chain.state_at(cv.u[3]);
            let (tau, nu) = chain.set.contacts[0].rod_frame(z[2]);
            let f = chain.total_force(&cv.u);
            let nn = -(f[0] * nu[0] + f[1] * nu[1]);
            let tt = f[0] * tau[0] + f[1] * tau[1];
            if nn > 0.0 && tt.abs() <= mu0 * nn {
                return Mode::Stuck(s_t);
            }
        }
    }
    // the way the contact point moves along the rod, frictionless: first order from the
    // tangent; where that vanishes (a straight rod turned against the object: the contact point
    // moves only to second order), from a solve a little further on
    chain.set.contacts[0].mode = Mode::Free;
    let ds = match tangent(chain) {
        Some(du) if du[3].abs() > 1e-6 => du[3],
        _ => {
            let dt = 1e-4;
            match solve_damped(chain, theta + dt, u0, corrector_tol(chain.sh.tol), 30) {
                Ok(cv) => cv.u[3] - s_t,
                Err(_) => 1.0,
            }
        }
    };
    // the contact point moving tipwards is the rod sliding footwards under the object: friction
    // on the rod points tipwards, T = +μ0 N
    let sign = if ds < 0.0 { -1.0 } else { 1.0 };
    Mode::Sliding(sign * mu0)
}

/// Where the object is, read off the base signals of one instant: the foot angle `theta`, the
/// moment `m_base = m(0)` and the contact force `force` on the rod (frame of the unturned foot;
/// the rod carries it to its base). The rod is integrated from its foot under that force until
/// the moment vanishes — there the object touches (beyond it the rod is unloaded). Returns
/// `(X, Y, s_c)`; where the moment vanishes more than once, the point where the force is most
/// nearly normal to the rod (frictionless contact).
pub fn locate(
    rod: &Rod,
    theta: f64,
    m_base: f64,
    force: [f64; 2],
    cfg: &SolverConfig,
) -> Result<(f64, f64, f64), VibrissaError> {
    cfg.validate()?;
    for (name, v) in [
        ("theta", theta),
        ("m_base", m_base),
        ("fx", force[0]),
        ("fy", force[1]),
    ] {
        if !v.is_finite() {
            return Err(VibrissaError::range(name, v, "a finite number"));
        }
    }
    if rod.has_uniform_profile() {
        locate_with(rod, Uniform, theta, m_base, force, cfg)
    } else {
        locate_with(rod, rod.profile(1.0), theta, m_base, force, cfg)
    }
}

fn locate_with<P: Profile>(
    rod: &Rod,
    profile: P,
    theta: f64,
    m_base: f64,
    force: [f64; 2],
    cfg: &SolverConfig,
) -> Result<(f64, f64, f64), VibrissaError> {
    let c = rod.support_compliance();
    let mut sh = Shooter::new(profile, c, cfg.tol, 8);
    let z0 = [0.0, 0.0, FRAC_PI_2 - theta + c * m_base, m_base];
    for _ in 0..32 {
        let shot = sh.shoot(0, 0.0, 1.0, z0, &[], force, false);
        if shot.err <= 1.0 || !sh.refine(0) {
            break;
        }
    }
    let (ps, pz, _) = sh.path(0);
    let (ps, pz) = (ps.to_vec(), pz.to_vec());
    let fmag = (force[0] * force[0] + force[1] * force[1]).sqrt();
    let mut best: Option<(f64, f64, [f64; 4])> = None;
    for i in 0..ps.len() - 1 {
        let (ma, mb) = (pz[4 * i + 3], pz[4 * i + 7]);
        if ma * mb > 0.0 || ma == 0.0 && i > 0 {
            continue;
        }
        let mut f = |s: f64| -> Result<f64, std::convert::Infallible> { Ok(sh.state_at(0, s)[3]) };
        let Ok(s) = search::root(&mut f, ps[i], ps[i + 1], 1e-15) else {
            continue;
        };
        if s <= 0.0 {
            continue;
        }
        let z = sh.state_at(0, s);
        // how far the force is from normal to the rod there
        let along = (force[0] * z[2].cos() + force[1] * z[2].sin()).abs() / fmag.max(1e-300);
        if best.is_none_or(|b| along < b.0) {
            best = Some((along, s, z));
        }
    }
    match best {
        Some((_, s, z)) => Ok((z[0], z[1], s)),
        None => Err(VibrissaError::OutOfReach {
            what: format!(
                "the base signals (m_base = {m_base}, fx = {}, fy = {}) fit no contact on the rod: \
                 the moment does not vanish along it (the reach is its smallest |m|)",
                force[0], force[1]
            ),
            reach: (0..ps.len())
                .map(|i| pz[4 * i + 3].abs())
                .fold(f64::INFINITY, f64::min),
            needed: 0.0,
        }),
    }
}
