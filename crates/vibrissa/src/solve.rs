//! Single solves: the rod shape for a given force angle and tip condition.
//!
//! The numerical path never starts from a closed form: the rod is loaded from its rest shape by
//! a tip force at the given angle (a press of a line through the tip, frictionless at that
//! angle), followed by continuation until the tip condition holds; the convex branch is the
//! first time it holds, the one-flex branch a later one along the same curve. A tip-position
//! target then moves the tip along its line with the force angle free. The other methods of
//! crate `bvp` solve the same contact problem from the shooter's rod, so their answer is their
//! own.

pub use crate::config::{Method, SolverConfig, StartKind, Target};

use crate::arclength::{self, ArcPoint};
use crate::chain::{Chain, Contact, ContactSet, Family, Geom, Mode, Pose};
use crate::config::NEWTON_TOL_MAX;
use crate::engine::{Begin, FirstPoint};
use crate::profile::{Profile, Uniform};
use crate::rodsolve::solve_damped;
use crate::shape::{shape_from, shape_from_elastica, BranchChoice, Shape};
use crate::shooter::Shooter;
use crate::start::{press, PressSpec};
use crate::watch::{Env, Goal};
use crate::{Rod, VibrissaError};
use bvp::Stats;
use elastica::{Branch, Elastica};
use std::f64::consts::PI;

/// Solves for the rod with force angle `alpha` (fixed for φ1 / η targets, the start for a tip
/// target) and the tip condition `target`, on the requested branch.
///
/// The rod is loaded at `alpha` from its rest shape (a straight rod under an axial load buckles
/// to the right first) and followed until the target holds: the first time for the convex
/// branch and [`BranchChoice::Any`], the first time with one load reversal for the flex branch.
/// A converged solution on another branch is an error ([`VibrissaError::WrongBranch`]) unless
/// [`BranchChoice::Any`] is asked for. [`BranchChoice::Guess`] starts Newton from the given
/// shape instead.
///
/// ```
/// use vibrissa::{BranchChoice, Method, Rod, SolverConfig, Target};
///
/// // the paper's Fig. 3: alpha = -pi/8, phi1 = pi/8 needs f = 4.718136... (closed form)
/// let cfg = SolverConfig::default();
/// let shape = vibrissa::solve(&Rod::uniform(), -0.3927, Target::Phi1(0.3927), &BranchChoice::Convex, &cfg)?;
/// assert!((shape.f - 4.718136345368394).abs() < 1e-8);
/// let closed = SolverConfig { method: Method::Analytic, ..cfg };
/// let exact = vibrissa::solve(&Rod::uniform(), -0.3927, Target::Phi1(0.3927), &BranchChoice::Convex, &closed)?;
/// assert_eq!(exact.f, 4.718136345368394);
/// # Ok::<(), vibrissa::VibrissaError>(())
/// ```
pub fn solve(
    rod: &Rod,
    alpha: f64,
    target: Target,
    branch: &BranchChoice,
    cfg: &SolverConfig,
) -> Result<Shape, VibrissaError> {
    cfg.validate()?;
    check_alpha(alpha)?;
    check_target(&target)?;
    if rod.tip_radius() > 0.0
        && (!matches!(target, Target::Eta(_)) || cfg.method == Method::Analytic)
    {
        return Err(VibrissaError::MethodUnavailable {
            method: "a round tip (tip radius > 0)".into(),
            reason: "a solve holds a round tip on the surface at the height eta (--eta), on the \
                     rod's own shooter: a tip slope or a tip position has no contact point for \
                     the disk, and the closed forms are the point tip's"
                .into(),
        });
    }
    if cfg.method == Method::Analytic {
        return solve_analytic(rod, alpha, target, branch);
    }
    let shape = if rod.has_uniform_profile() {
        solve_with(rod, Uniform, alpha, target, branch, cfg)?
    } else {
        solve_with(rod, rod.profile(1.0), alpha, target, branch, cfg)?
    };
    check_branch(&shape, branch)?;
    Ok(shape)
}

/// The contact set of a tip condition under a tip force at angle `alpha` (force frame normal
/// `(−sin α, cos α)`), and its fixed pose; `r` the round tip's radius (a height target: the
/// disk touching the line `y = η`, its centre at `η − r`).
fn tip_set(alpha: f64, target: &Target, r: f64) -> (ContactSet, Pose) {
    let (geom, mode, h) = match *target {
        Target::Phi1(phi1) => (Geom::Slope { phi1 }, Mode::Free, 0.0),
        Target::Eta(eta) => (
            Geom::Line {
                p0: [0.0, 0.0],
                beta: 0.0,
            },
            Mode::Free,
            eta,
        ),
        Target::Tip { x1, y1 } => (
            Geom::Line {
                p0: [0.0, 0.0],
                beta: 0.0,
            },
            Mode::Stuck(x1),
            y1,
        ),
    };
    let ct = Contact {
        tip: true,
        geom,
        mode,
        n: [-alpha.sin(), alpha.cos()],
        phi_ref: 0.0,
    };
    (
        ContactSet {
            contacts: vec![ct],
            tip_radius: if matches!(target, Target::Eta(_)) {
                r
            } else {
                0.0
            },
            lying: None,
        },
        Pose {
            h,
            ..Pose::default()
        },
    )
}

/// Core of [`solve`] for one profile type.
fn solve_with<P: Profile>(
    rod: &Rod,
    profile: P,
    alpha: f64,
    target: Target,
    branch: &BranchChoice,
    cfg: &SolverConfig,
) -> Result<Shape, VibrissaError> {
    let c = rod.support_compliance();
    let tol = cfg.own_shooter_tol().unwrap_or(cfg.tol.min(1e-10));
    let ntol = tol.min(NEWTON_TOL_MAX);
    let (set, pose) = tip_set(alpha, &target, rod.tip_radius());
    let mut chain = Chain::new(
        Shooter::new(profile.clone(), c, tol, 8),
        set.clone(),
        Family::Fixed(pose),
    );
    let context = || format!("solve at alpha = {alpha}, {target:?}");
    let cv = match branch {
        BranchChoice::Guess(g) => {
            let u0 = vec![
                g.m_base,
                g.f * (g.alpha - alpha).cos(),
                g.f * (alpha - g.alpha).sin(),
            ];
            solve_damped(&mut chain, 0.0, &u0, ntol, 40).map_err(|e| {
                VibrissaError::NoConvergence {
                    what: format!("{} from the given shape", context()),
                    reason: e.to_string(),
                }
            })?
        }
        _ => {
            let loaded = load(rod, &profile, alpha, &target, branch, tol, cfg.start)?;
            solve_damped(&mut chain, 0.0, &loaded, ntol, 40).map_err(|e| {
                VibrissaError::NoConvergence {
                    what: context(),
                    reason: e.to_string(),
                }
            })?
        }
    };
    let (residual, load) = (cv.residual, chain.sh.stats.clone());
    let generic = cfg.own_shooter_tol().is_none();
    // the method's own solution of the same problem, from the shooter's rod
    let env = Env {
        line: None,
        mu0: None,
        compound: false,
        target: None,
        ground: Default::default(),
    };
    let begun = Begin {
        chain,
        env,
        solver: cfg,
        lam: 0.0,
        u: cv.u.clone(),
        first: FirstPoint::Converged(cv),
        run: "solve",
        hand_over: false,
        what: context(),
    }
    .begin()?;
    let mut sol = begun.stepper.method_solution().unwrap_or(begun.p0.sol);
    sol.stats = if generic {
        let mut stats = load;
        stats.accumulate(&begun.stepper.stats());
        Stats {
            nodes: sol.mesh.len(),
            residual: sol.stats.residual,
            error_estimate: sol.stats.error_estimate,
            ..stats
        }
    } else {
        Stats {
            nodes: sol.mesh.len(),
            residual,
            ..begun.stepper.stats()
        }
    };
    let f = sol.params[0];
    let a = sol.params[1];
    let mut shape = shape_from(sol, a, rod.profile(1.0));
    shape.f = f;
    shape.alpha = a;
    Ok(shape)
}

/// The unknowns of the tip condition `target` at force angle `alpha` (in the contact set of
/// [`tip_set`]), reached numerically: the rod pressed at its tip straight down until the
/// condition holds (a straight rod buckles to the right first), the force then turned to `alpha`
/// with the condition held — the convex family, as in the paper. The flex branch lies further
/// along the fixed-angle curve of the condition's parameter, past the fold where the flex point
/// is born: followed by pseudo-arclength (the load rising) to where the condition holds again.
fn load<P: Profile>(
    rod: &Rod,
    profile: &P,
    alpha: f64,
    target: &Target,
    branch: &BranchChoice,
    tol: f64,
    start: StartKind,
) -> Result<Vec<f64>, VibrissaError> {
    let c = rod.support_compliance();
    let connected = start == StartKind::Connected;
    let general = rod.profile(1.0);
    let ntol = tol.min(NEWTON_TOL_MAX);
    let goal = match *target {
        Target::Phi1(p) => Goal::TipSlope(p, 1.0),
        Target::Eta(e) | Target::Tip { y1: e, .. } => Goal::Height(e, 1.0),
    };
    let spec = PressSpec {
        geom_beta: 0.0,
        force_beta: 0.0,
        sides: false,
        goal,
        tip_radius: if matches!(target, Target::Eta(_)) {
            rod.tip_radius()
        } else {
            0.0
        },
    };
    // connected: the uniform clamped rod first, its deviations grown once the force is turned
    let first_rod = if connected {
        profile.at_amplitude(0.0)
    } else {
        profile.clone()
    };
    let pressed = match press(
        Shooter::new(first_rod.clone(), if connected { 0.0 } else { c }, tol, 8),
        &general,
        &first_rod,
        &spec,
    ) {
        Ok(p) => p,
        // a rod leaning away from the goal (rest curvature against the slope asked for) never
        // reaches it by being pressed: the state connected to the uniform rod is the answer
        Err(_) if !connected => {
            return load(
                rod,
                profile,
                alpha,
                target,
                branch,
                tol,
                StartKind::Connected,
            )
        }
        Err(e) => return Err(e),
    };
    // the condition's own set (slope or height held), at force angle 0
    let r = rod.tip_radius();
    let (set0, pose) = tip_set(0.0, target, r);
    let (set0, pose) = match *target {
        // the tip x follows later: hold the height first
        Target::Tip { y1, .. } => tip_set(0.0, &Target::Eta(y1), r),
        _ => (set0, pose),
    };
    let mut chain = Chain::new(pressed.sh, set0, Family::Fixed(pose));
    let f = pressed.pt.w.force;
    let first =
        solve_damped(&mut chain, 0.0, &[pressed.pt.u[0], -f[1], f[0]], ntol, 30).map_err(|e| {
            VibrissaError::NoConvergence {
                what: format!("the pressed rod at {target:?}"),
                reason: e.to_string(),
            }
        })?;
    // At alpha = 0 the force is square to the held condition's line of symmetry: the curve
    // of the condition's parameter passes the flex solution where it meets its mirror image,
    // and the continuation in flex_of finds only the convex ones there (issue 33: solve
    // --alpha 0 --phi1 0.3 --branch flex failed for every numerical method). The flex solution
    // is found at a slightly tilted force and turned back.
    let detour = branch.load_reversals() == Some(1) && alpha <= 0.0 && alpha > -FLEX_DETOUR;
    let turned = if detour { -FLEX_DETOUR } else { alpha };
    let (chain, u) = crate::start::turn_force(chain, &first.u, 0.0, turned, ntol)?;
    let (mut chain, mut u) = (chain, u);
    if connected {
        let p1 = profile.clone();
        let (ch, cv) = crate::start::morph(
            chain,
            &u,
            move |ch: &mut Chain<P>, t: f64| ch.sh.set_profile(p1.at_amplitude(t), t * c),
            ntol,
            "homotopy from the uniform clamped rod",
            &|t| format!("t = {t} of 1"),
        )?;
        (chain, u) = (ch, cv.u);
    }
    if branch.load_reversals() == Some(1) {
        (chain, u) = flex_of(chain, &u, target, ntol)?;
        if detour {
            (chain, u) = crate::start::turn_force(chain, &u, turned, alpha, ntol)?;
        }
    }
    if let Target::Tip { x1, y1 } = *target {
        // move the tip along its line to x1, the force angle free
        chain.sh.stats = Default::default();
        let x0 = {
            let _ = chain.eval(&u, 0.0, false);
            chain.path(&u).right()[0]
        };
        let (tset, _) = tip_set(alpha, target, r);
        let mut ch = Chain::new(chain.sh, tset, Family::Drag);
        if let Some(ct) = ch.set.contacts.first_mut() {
            ct.mode = Mode::Stuck(x0);
            ct.geom = Geom::Line {
                p0: [0.0, y1],
                beta: 0.0,
            };
        }
        let first =
            solve_damped(&mut ch, 0.0, &u, ntol, 30).map_err(|e| VibrissaError::NoConvergence {
                what: format!("tip target ({x1}, {y1})"),
                reason: e.to_string(),
            })?;
        let end = arclength::follow_to(
            &mut ch,
            ArcPoint::from_converged(&first, 0.0),
            x0 - x1,
            ntol,
        )
        .map_err(|e| VibrissaError::NoConvergence {
            what: format!("continuation of the tip x towards {x1}"),
            reason: e.to_string(),
        })?;
        u = end.u();
    }
    Ok(u)
}

/// The force angle below 0 at which the flex solution of a force angle in `(-FLEX_DETOUR, 0]`
/// is found (see [`load`]); -0.01 and -0.001 are found directly.
const FLEX_DETOUR: f64 = 0.01;

/// From the convex solution `u` of `target` on `chain` (fixed force angle), the one-flex
/// solution of the same condition: the curve of the condition's parameter (tip slope, or height)
/// followed by pseudo-arclength the way the load rises, past its fold, to where the condition
/// holds again (up to three times, until the rod has one load reversal).
fn flex_of<P: Profile>(
    chain: Chain<P>,
    u: &[f64],
    target: &Target,
    tol: f64,
) -> Result<(Chain<P>, Vec<f64>), VibrissaError> {
    let fail = |e: String| VibrissaError::NoConvergence {
        what: "the one-flex solution along the fixed-angle curve".into(),
        reason: e,
    };
    let mut chain = chain;
    // the family: the held slope (λ = its offset) or the held height (λ = depth below it)
    let (family, lam0) = match *target {
        Target::Phi1(_) => (Family::Slope, 0.0),
        Target::Eta(e) | Target::Tip { y1: e, .. } => (Family::Press { h0: e }, 0.0),
    };
    chain.family = family;
    let first =
        arclength::at_lambda(&mut chain, u, lam0, tol, 30).map_err(|e| fail(e.to_string()))?;
    let t0 = first
        .tangent(None)
        .ok_or_else(|| fail("no tangent".into()))?;
    let steps = arclength::Steps {
        ds: 0.02,
        ds_min: 1e-9,
        ds_max: 0.2,
    };
    let mut crossings = 0;
    let mut last_err = String::new();
    // both ways along the curve, the load falling first (towards the fold where the flex point
    // is born, in the paper's scene), each until the load or the parameter runs away
    for sign in [-1.0, 1.0] {
        let tau = if t0[1] * sign >= 0.0 {
            t0.clone()
        } else {
            -t0.clone()
        };
        let mut arc = arclength::Arc::along(first.clone(), tau, steps, tol);
        for _ in 0..2000 {
            let (prev, _) = match arc.step(&mut chain) {
                Ok(p) => p,
                Err(e) => {
                    last_err =
                        format!("at lambda = {}, f = {}: {e}", arc.last.lam(), arc.last.v[1]);
                    break;
                }
            };
            let (l0, l1) = (prev.lam(), arc.last.lam());
            if l1.abs() > 2.0 * PI || arc.last.v[1].abs() > 1e4 {
                break;
            }
            if (l0 - lam0) * (l1 - lam0) <= 0.0 && l1 != lam0 {
                crossings += 1;
                let w = (lam0 - l0) / (l1 - l0);
                let (a, b) = (prev.u(), arc.last.u());
                let ug: Vec<f64> = a.iter().zip(&b).map(|(x, y)| x + w * (y - x)).collect();
                let p = arclength::at_lambda(&mut chain, &ug, lam0, tol, 16)
                    .map_err(|e| fail(e.to_string()))?;
                let sol = chain.path(&p.u());
                let reversals = crate::sampling::flex_and_reversals(&sol, &chain.sh.profile).2;
                if reversals == 1 {
                    let pose = match *target {
                        Target::Eta(e) | Target::Tip { y1: e, .. } => Pose {
                            h: e,
                            ..Pose::default()
                        },
                        _ => Pose::default(),
                    };
                    chain.family = Family::Fixed(pose);
                    return Ok((chain, p.u()));
                }
            }
        }
    }
    Err(fail(format!(
        "the condition did not hold with one load reversal along the curve ({crossings} other \
         crossings){}",
        if last_err.is_empty() {
            String::new()
        } else {
            format!("; {last_err}")
        }
    )))
}

pub(crate) fn check_branch(shape: &Shape, branch: &BranchChoice) -> Result<(), VibrissaError> {
    match branch.load_reversals() {
        Some(requested) if !shape.is_on(branch) => Err(VibrissaError::WrongBranch {
            requested,
            found: shape.kind(),
        }),
        _ => Ok(()),
    }
}
/// The force angle against [`limits::ALPHA`](crate::limits::ALPHA), the program's range (the
/// contact pushes the tip down); was `[-pi, pi]` here while the program refused `|alpha| >= pi/2`.
fn check_alpha(alpha: f64) -> Result<(), VibrissaError> {
    crate::limits::ALPHA.check("alpha", alpha)
}
fn check_target(target: &Target) -> Result<(), VibrissaError> {
    match *target {
        Target::Phi1(p) => {
            if !(p.is_finite() && (-PI..=PI).contains(&p)) {
                return Err(VibrissaError::range("phi1", p, "[-pi, pi]"));
            }
        }
        Target::Eta(e) => {
            if !(e.is_finite() && e > -1.0 && e < 1.0) {
                return Err(VibrissaError::range("eta", e, "(-1, 1)"));
            }
        }
        Target::Tip { x1, y1 } => {
            if !(x1.is_finite() && y1.is_finite() && x1 * x1 + y1 * y1 < 1.0) {
                return Err(VibrissaError::range(
                    "tip distance sqrt(x1² + y1²)",
                    (x1 * x1 + y1 * y1).sqrt(),
                    "[0, 1) (the rod has length 1)",
                ));
            }
        }
    }
    Ok(())
}
fn elastica_branch(branch: &BranchChoice) -> Branch {
    match branch {
        BranchChoice::Flex => Branch::OneFlex,
        _ => Branch::Convex,
    }
}
fn closed_form(alpha: f64, target: &Target, branch: Branch) -> Result<Elastica, VibrissaError> {
    let ctx = format!("closed form at alpha = {alpha}, {target:?}");
    match *target {
        Target::Phi1(p) => Elastica::new(branch, alpha, p),
        Target::Eta(e) => elastica::solve_eta(branch, alpha, e),
        Target::Tip { .. } => unreachable_tip(),
    }
    .map_err(|e| VibrissaError::elastica(ctx, e))
}
fn unreachable_tip() -> Result<Elastica, elastica::ElasticaError> {
    Err(elastica::ElasticaError::IllConditioned {
        what: "closed-form tip target",
        name: "target",
        value: f64::NAN,
        reason: "a tip-position target has no direct closed form",
    })
}
fn solve_analytic(
    rod: &Rod,
    alpha: f64,
    target: Target,
    branch: &BranchChoice,
) -> Result<Shape, VibrissaError> {
    if !rod.is_uniform_clamped() {
        return Err(VibrissaError::MethodUnavailable {
            method: "analytic".into(),
            reason: "closed forms exist only for the paper's rod (uniform, straight, clamped)"
                .into(),
        });
    }
    if matches!(target, Target::Tip { .. }) {
        return Err(VibrissaError::MethodUnavailable {
            method: "analytic".into(),
            reason: "a tip-position target needs a numerical method".into(),
        });
    }
    let e = closed_form(alpha, &target, elastica_branch(branch))?;
    // the residual of a closed form: the defect of the first integral at the clamp (φ = π/2),
    // ½m(0)² = f·[cos α − sin(φ1 − α)], relative to max(f, 1), and the miss of a height target
    let fi = 0.5 * e.m_base * e.m_base - e.f * (e.alpha.cos() - (e.phi1 - e.alpha).sin());
    let mut residual = fi.abs() / e.f.max(1.0);
    if let Target::Eta(h) = target {
        residual = residual.max((e.y1 - h).abs());
    }
    let mut shape = shape_from_elastica(e);
    shape.residual = residual;
    Ok(shape)
}
