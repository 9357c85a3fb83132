//! Single solves: the rod shape for a given force angle and tip condition.

pub use crate::config::{Method, SolverConfig, Target};

use crate::arclength::{self, Arc, ArcPoint, Family, Homotopy, Steps, TipLine};
use crate::config::{Engine, NEWTON_TOL_MAX};
use crate::equations::{Ends, HomotopyFamily, RodBvp};
use crate::profile::{Profile, Uniform};
use crate::rodsolve::{self, Converged, TipCond};
use crate::shape::{elastica_guess, shape_from, shape_from_elastica, BranchChoice, Shape};
use crate::shooter::Shooter;
use crate::{Rod, VibrissaError};
use bvp::continuation::{Continuation, ContinuationOptions};
use bvp::{Bvp, BvpError, BvpSolver, Guess, Solution, Stats};
use elastica::{Branch, Elastica};
use nalgebra::Vector4;
use std::f64::consts::{FRAC_PI_2, PI};

/// A circular-arc guess (used where the closed form has no solution, e.g. `α < −π/4`): the slope
/// goes linearly from π/2 to the target tip slope (or 0.5 for a height target), `m` decreases
/// linearly to 0, and `f` balances the base moment with a lever of half the rod.
fn arc_guess(alpha: f64, target: &Target) -> Option<Guess> {
    let phi1 = match *target {
        Target::Phi1(p) => p,
        Target::Eta(_) => 0.5,
        Target::Tip { .. } => return None,
    };
    let turn = phi1 - FRAC_PI_2;
    let m0 = 2.0 * turn;
    let f = (m0.abs() / 0.5).max(0.5);
    let nodes = 41;
    let mesh: Vec<f64> = (0..nodes).map(|i| i as f64 / (nodes - 1) as f64).collect();
    let mut g = Guess::from_fn(4, mesh, vec![f], |s, z| {
        // φ(s) = π/2 + turn·(2s − s²) has φ' = 2 turn (1 − s) = m(s)
        let phi = FRAC_PI_2 + turn * (2.0 * s - s * s);
        // positions by the midpoint rule on 64 sub-steps
        let (mut x, mut y) = (0.0, 0.0);
        let k = 64;
        for j in 0..k {
            let t = s * (j as f64 + 0.5) / k as f64;
            let p = FRAC_PI_2 + turn * (2.0 * t - t * t);
            x += p.cos() * s / k as f64;
            y += p.sin() * s / k as f64;
        }
        z.copy_from_slice(&[x, y, phi, m0 * (1.0 - s)]);
    });
    let _ = alpha;
    g.dz = None;
    Some(g)
}

/// Checks that a shape is on the requested branch.
pub(crate) fn check_branch(shape: &Shape, branch: &BranchChoice) -> Result<(), VibrissaError> {
    match branch.load_reversals() {
        Some(requested) if !shape.is_on(branch) => Err(VibrissaError::WrongBranch {
            requested,
            found: shape.kind(),
        }),
        _ => Ok(()),
    }
}

fn check_alpha(alpha: f64) -> Result<(), VibrissaError> {
    if !(alpha.is_finite() && (-PI..=PI).contains(&alpha)) {
        return Err(VibrissaError::range("alpha", alpha, "[-pi, pi]"));
    }
    Ok(())
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

/// The closed-form rod for `(alpha, target)` on `branch` (tip targets excluded).
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

/// Solves `rod` from `guess`, wrapping the error with `context`.
pub(crate) fn run<B: Bvp + ?Sized>(
    engine: &mut Engine,
    rod: &B,
    guess: &Guess,
    context: impl FnOnce() -> String,
) -> Result<Solution, VibrissaError> {
    engine
        .solve(rod, guess)
        .map_err(|e| VibrissaError::solver(context(), e))
}

/// Solves for the rod with force angle `alpha` (fixed for φ1 / η targets, the start for a tip
/// target) and the tip condition `target`, on the requested branch.
///
/// Start: the closed form (crate `elastica`) of the uniform clamped rod on the requested branch
/// (a circular arc where it has none); any other rod follows the homotopy from it in the
/// amplitude `t ∈ [0, 1]` of taper, pre-curvature and compliance, so the answer is the solution
/// continuously connected to the uniform rod's branch. Single shooting runs on the rod's own
/// shooter (module `rodsolve`) for every profile; the other methods through crate `bvp`. A
/// converged solution on another branch is an error ([`VibrissaError::WrongBranch`]) unless
/// [`BranchChoice::Any`] is asked for.
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
    if cfg.method == Method::Analytic {
        return solve_analytic(rod, alpha, target, branch);
    }
    let fast = cfg.own_shooter_tol().and_then(|tol| {
        if rod.has_uniform_profile() {
            let c = rod.support_compliance();
            solve_fast(rod, |t| (Uniform, t * c), alpha, target, branch, tol)
        } else {
            let (p, c) = (rod.profile(1.0), rod.support_compliance());
            solve_fast(
                rod,
                |t| (p.clone().with_t(t), t * c),
                alpha,
                target,
                branch,
                tol,
            )
        }
    });
    let shape = match fast {
        Some(s) => s,
        None => {
            let mut engine = Engine::new(cfg)?;
            if rod.is_uniform_clamped() {
                solve_with(rod, Uniform, &mut engine, alpha, target, branch)?
            } else {
                solve_with(rod, rod.profile(1.0), &mut engine, alpha, target, branch)?
            }
        }
    };
    check_branch(&shape, branch)?;
    Ok(shape)
}

/// The start `u = (m(0), f, α)` on the uniform clamped rod: the closed form where it exists,
/// else a circular arc (slope from π/2 to the target slope, `m` linear, `f` balancing `m(0)` with
/// half the rod as lever).
fn uniform_start(alpha: f64, target: &Target, branch: &BranchChoice) -> [f64; 3] {
    let closed = match *target {
        Target::Phi1(p) => Elastica::new(elastica_branch(branch), alpha, p).ok(),
        Target::Eta(e) | Target::Tip { y1: e, .. } => {
            elastica::solve_eta(elastica_branch(branch), alpha, e).ok()
        }
    };
    match closed {
        Some(e) => [e.m_base, e.f, alpha],
        None => {
            let phi1 = match *target {
                Target::Phi1(p) => p,
                _ => 0.5,
            };
            let m0 = 2.0 * (phi1 - FRAC_PI_2);
            [m0, (m0.abs() / 0.5).max(0.5), alpha]
        }
    }
}

/// [`solve`] on the rod's own shooter: `member(t)` is the rod at homotopy amplitude `t`. `None`
/// when it does not converge (the caller then runs the generic solver).
///
/// The homotopy from the uniform clamped rod (`t = 0`, started from its closed form) to the rod
/// (`t = 1`) follows the curve by pseudo-arclength ([`crate::arclength`]), so it passes folds in
/// `t` and never jumps to another branch (e.g. the mirror image bending the other way); a tip
/// target then moves the tip along its line the same way.
fn solve_fast<P: Profile>(
    rod: &Rod,
    member: impl Fn(f64) -> (P, f64),
    alpha: f64,
    target: Target,
    branch: &BranchChoice,
    tol: f64,
) -> Option<Shape> {
    let (p1, c1) = member(1.0);
    let mut sh = Shooter::new(p1.clone(), c1, tol, 8);
    // Newton to at most 1e-9 whatever the integration tolerance: the homotopy and tip moves are
    // continuations, and iterates left with loose residuals stray (the rat whiskers' starts
    // failed at tol 1e-2)
    let ntol = tol.min(NEWTON_TOL_MAX);
    let height = |t: &Target| match *t {
        Target::Phi1(phi1) => TipCond::Phi1 { phi1, alpha },
        Target::Eta(eta) | Target::Tip { y1: eta, .. } => TipCond::Eta { eta, alpha },
    };
    let cv = if let BranchChoice::Guess(g) = branch {
        let cond = match target {
            Target::Tip { x1, y1 } => TipCond::Pos { x1, y1 },
            t => height(&t),
        };
        let a = if matches!(target, Target::Tip { .. }) {
            g.alpha
        } else {
            alpha
        };
        rodsolve::solve_damped(&mut sh, &cond, [g.m_base, g.f, a], ntol, 40).ok()?
    } else {
        let u0 = uniform_start(alpha, &target, branch);
        let cv = if rod.is_uniform_clamped() {
            // the start is the rod's own closed form: no homotopy
            rodsolve::solve_damped(&mut sh, &height(&target), u0, ntol, 30).ok()?
        } else {
            let fam = Homotopy {
                member: &member,
                cond: height(&target),
            };
            follow_to(&mut sh, &fam, u0, 0.0, 1.0, ntol)?
        };
        match target {
            Target::Tip { x1, y1 } => {
                // move the tip from where the height solve put it to x1, α free
                let x0 = sh.shoot::<false>(&cv.u).y1[0];
                let line = TipLine { x0, slope: 1.0, y1 };
                follow_to(&mut sh, &line, cv.u, 0.0, x1 - x0, ntol)?
            }
            _ => cv,
        }
    };
    // near a turning point the residual says little about the unknowns (square-root
    // dependence): leave such rods to the generic solver
    // (a NaN condition number is ill-conditioned too)
    if cv.cond().partial_cmp(&1e6) != Some(std::cmp::Ordering::Less) {
        return None;
    }
    let params = match target {
        Target::Tip { .. } => vec![cv.u[1], cv.u[2]],
        _ => vec![cv.u[1]],
    };
    let mut sol = sh.solution(params, cv.residual);
    sol.stats = Stats {
        nodes: sol.stats.nodes,
        residual: cv.residual,
        ..sh.stats.clone()
    };
    Some(shape_from(sol, alpha, rod.profile(1.0)))
}

/// Follows `fam` by pseudo-arclength from its member at `from` (Newton from `u0`) until `λ`
/// passes `to`, and returns the member at `to`; `None` on failure.
fn follow_to<P: Profile, F: Family<P>>(
    sh: &mut Shooter<P>,
    fam: &F,
    u0: [f64; 3],
    from: f64,
    to: f64,
    tol: f64,
) -> Option<Converged> {
    let cond = fam.set(sh, from);
    let first = rodsolve::solve_damped(sh, &cond, u0, tol, 30).ok()?;
    if to == from {
        return Some(first);
    }
    let r_lam = fam.r_lam(sh, &first.u, from);
    let start = ArcPoint {
        v: Vector4::new(first.u[0], first.u[1], first.u[2], from),
        jac: first.jac,
        r_lam,
        residual: first.residual,
        iterations: first.iterations,
    };
    let span = (to - from).abs();
    let steps = Steps {
        ds: 0.1 * span,
        ds_min: 1e-7 * span,
        ds_max: 0.25 * span,
    };
    let dir = (to - from).signum();
    let mut arc = Arc::new(start, dir, steps, tol).ok()?;
    for _ in 0..2000 {
        let (prev, _) = arc.step(sh, fam).ok()?;
        let (l0, l1) = (prev.lam(), arc.last.lam());
        if (l1 - to) * dir >= 0.0 {
            // the member at `to`, from the chord between the points on either side
            let w = (to - l0) / (l1 - l0);
            let (a, b) = (prev.u(), arc.last.u());
            let u = [
                a[0] + w * (b[0] - a[0]),
                a[1] + w * (b[1] - a[1]),
                a[2] + w * (b[2] - a[2]),
            ];
            return arclength::at_lambda(sh, fam, u, to, tol, 16)
                .ok()
                .map(|p| p.converged());
        }
        // the curve turned back past its start: no member at `to` connected to it
        if (l1 - from) * dir < -span {
            return None;
        }
    }
    None
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

fn ends_of(target: Target) -> Ends {
    match target {
        Target::Phi1(phi1) => Ends::Phi1 { phi1 },
        Target::Eta(eta) => Ends::Eta { eta },
        Target::Tip { x1, y1 } => Ends::Tip { x1, y1 },
    }
}

/// Core of [`solve`] for one profile type.
pub(crate) fn solve_with<Pr: Profile>(
    rod: &Rod,
    profile: Pr,
    engine: &mut Engine,
    alpha: f64,
    target: Target,
    branch: &BranchChoice,
) -> Result<Shape, VibrissaError> {
    let c = rod.support_compliance();
    if let Target::Tip { x1, y1 } = target {
        return solve_tip(rod, profile, engine, alpha, x1, y1, branch);
    }
    let problem = RodBvp {
        profile: profile.clone(),
        compliance: c,
        alpha,
        ends: ends_of(target),
    };
    if let BranchChoice::Guess(g) = branch {
        let guess = g.guess(vec![g.f]);
        let sol = run(engine, &problem, &guess, || {
            format!("solve at alpha = {alpha}, {target:?} from the given shape")
        })?;
        return Ok(shape_from(sol, alpha, rod.profile(1.0)));
    }
    // the closed form of the uniform clamped rod where it exists, else a circular arc
    let guess = match closed_form(alpha, &target, elastica_branch(branch)) {
        Ok(e) => elastica_guess(&e, vec![e.f]),
        Err(err) => match arc_guess(alpha, &target) {
            Some(g) => g,
            None => return Err(err),
        },
    };
    if Pr::UNIFORM && c == 0.0 {
        let sol = run(engine, &problem, &guess, || {
            format!("solve at alpha = {alpha}, {target:?}")
        })?;
        return Ok(shape_from(sol, alpha, rod.profile(1.0)));
    }
    let family = HomotopyFamily {
        profile: rod.profile(1.0),
        compliance: c,
        alpha,
        ends: ends_of(target),
    };
    let sol = homotopy(engine, &family, &guess)?;
    Ok(shape_from(sol, alpha, rod.profile(1.0)))
}

/// A rough "solution" made of a guess (for continuation starts, which correct it first).
pub(crate) fn guess_as_solution(g: &Guess) -> Solution {
    let dz = g.dz.clone().unwrap_or_else(|| vec![0.0; g.z.len()]);
    Solution {
        n: g.n,
        mesh: g.mesh.clone(),
        z: g.z.clone(),
        dz,
        params: g.params.clone(),
        status: bvp::Status::Converged,
        stats: Stats::default(),
        dense: bvp::Dense::Hermite,
    }
}

/// Pseudo-arclength continuation (crate `bvp`) in the homotopy amplitude `t` from 0 (uniform
/// clamped rod, started from the closed form) to 1 (the scene).
pub(crate) fn homotopy(
    engine: &mut Engine,
    family: &HomotopyFamily,
    guess: &Guess,
) -> Result<Solution, VibrissaError> {
    let opts = ContinuationOptions {
        ds: 0.25,
        ds_min: 1e-6,
        ds_max: 2.0,
        max_steps: 400,
        lambda_min: -0.5,
        lambda_max: 1.0,
        detect_folds: false,
        ..ContinuationOptions::default()
    };
    let wrap = |e: BvpError, t: f64| {
        VibrissaError::solver(
            format!("homotopy from the uniform clamped rod (t = {t:.6} of 1)"),
            e,
        )
    };
    let mut cont = Continuation::new(family, engine, guess_as_solution(guess), 0.0, opts)
        .map_err(|e| wrap(e, 0.0))?;
    let mut stats = Stats::default();
    let mut t = 0.0;
    for item in cont.by_ref() {
        let bp = item.map_err(|e| wrap(e, t))?;
        stats.accumulate(&bp.stats);
        t = bp.lambda;
        if bp.on_bound && bp.lambda >= 1.0 {
            let mut sol = bp.solution;
            sol.stats = Stats {
                residual: sol.stats.residual,
                nodes: sol.stats.nodes,
                error_estimate: sol.stats.error_estimate,
                ..stats
            };
            return Ok(sol);
        }
        if bp.lambda < -0.25 {
            break;
        }
    }
    Err(VibrissaError::NoConvergence {
        what: "homotopy from the uniform clamped rod".into(),
        reason: format!("the branch did not reach t = 1 (last t = {t})"),
    })
}

/// Tip target: solve for `y(1) = y1` at the given `alpha`, then continue the tip x to `x1` with
/// `(f, α)` unknown.
fn solve_tip<Pr: Profile>(
    rod: &Rod,
    profile: Pr,
    engine: &mut Engine,
    alpha: f64,
    x1: f64,
    y1: f64,
    branch: &BranchChoice,
) -> Result<Shape, VibrissaError> {
    let c = rod.support_compliance();
    let problem = RodBvp {
        profile: profile.clone(),
        compliance: c,
        alpha,
        ends: Ends::Tip { x1, y1 },
    };
    let start = match branch {
        BranchChoice::Guess(g) => {
            let sol = run(engine, &problem, &g.guess(vec![g.f, g.alpha]), || {
                format!("tip ({x1}, {y1}) from the given shape")
            })?;
            return Ok(shape_from(sol, alpha, rod.profile(1.0)));
        }
        _ => solve_with(rod, profile.clone(), engine, alpha, Target::Eta(y1), branch)?,
    };
    let mut sol = start
        .solution()
        .cloned()
        .ok_or(VibrissaError::NotImplemented("analytic tip"))?;
    sol.params = vec![start.f, start.alpha];
    let mut x = start.x1;
    let mut dx = (x1 - x).clamp(-0.05, 0.05);
    let mut stats = start.stats.clone();
    while (x1 - x).abs() > 0.0 {
        let xn = if (x1 - x).abs() <= dx.abs() {
            x1
        } else {
            x + dx
        };
        let r = RodBvp {
            ends: Ends::Tip { x1: xn, y1 },
            ..problem.clone()
        };
        match engine.solve(&r, &Guess::from(&sol)) {
            Ok(s) => {
                stats.accumulate(&s.stats);
                sol = s;
                x = xn;
                if sol.stats.newton_iters <= 4 {
                    dx *= 1.5;
                }
            }
            Err(e) => {
                dx *= 0.5;
                if dx.abs() < 1e-6 {
                    return Err(VibrissaError::solver(
                        format!("continuation of the tip x towards {x1} stalled at x = {x}"),
                        e,
                    ));
                }
            }
        }
    }
    let residual = sol.stats.residual;
    sol.stats = Stats { residual, ..stats };
    Ok(shape_from(sol, alpha, rod.profile(1.0)))
}
