//! Solving a hard member of a family by continuation from an easy one: [`solve_by_continuation`].
//!
//! Singularly perturbed problems (`ε y'' = …` with `ε` small), stiff loads and strong
//! nonlinearities often defeat Newton from any simple guess, while the same problem at a mild
//! parameter value is easy and its solution is an excellent guess for a slightly harder one.
//! [`solve_by_continuation`] solves the family member at `from` from the user's guess, then walks
//! the parameter to `to` with [`Continuation`] (its step control: a failed corrector halves the
//! step, an easy one doubles it, bounded by `ds_min`/`ds_max`) and returns the solution at exactly
//! `to`. Every [`BvpSolver`] works (shooting, multiple shooting, collocation); collocation meshes
//! adapt along the way, so the final mesh resolves the layers of the hard member.
//!
//! # Scale
//!
//! A parameter spanning decades (`ε` from 1e-1 to 1e-4) is walked in `μ = ln λ` ([`Scale::Log`];
//! chosen by [`Scale::Auto`] when `from` and `to` have the same sign and differ by more than a
//! factor 10): equal steps in `μ` are equal ratios of `ε`, which is how layer widths change.
//! Steps (`ds`, `ds_min`, `ds_max` of [`ContinuationOptions`]) are then measured in `μ`.
//!
//! # Method
//!
//! The default is natural continuation ([`Method::Natural`]): step the parameter, correct with it
//! fixed, predictor the secant through the last two solutions. Its steps are measured in the
//! parameter alone, which suits layer problems (their boundary slopes grow like `1/ε`, so an
//! arclength in the boundary values would force tiny parameter steps). If the path folds (a limit
//! point before `to`), natural continuation stops there with [`BvpError::Continuation`] and a
//! "fold?" hint; choose [`Method::PseudoArclength`] to pass folds (the result is then the first
//! point found at `to` along the branch).
//!
//! ```
//! use bvp::testset::CashMazzia;
//! use bvp::{solve_by_continuation, Collocation, CollocationOptions, PathOptions};
//!
//! // Problem 20 of the Cash–Mazzia set, ε y'' + y'² = 1, is out of Newton's reach from a
//! // straight line at ε = 1e-3, but easy at ε = 0.1.
//! let p = CashMazzia::new(20).unwrap();
//! let mut solver = Collocation::new(CollocationOptions::default())?;
//! let guess = p.guess(0.1, 101);
//! let res = solve_by_continuation(&p, &mut solver, &guess, 0.1, 1e-3, &PathOptions::default())?;
//! let y = res.solution.at(0.745)[0];
//! let exact = p.exact(0.745, 1e-3).unwrap()[0];
//! assert!((y - exact).abs() < 1e-5);
//! # Ok::<(), bvp::BvpError>(())
//! ```

use crate::continuation::{Continuation, ContinuationOptions, Member, Method, ParamBvp};
use crate::{BvpError, BvpSolver, Dims, Guess, Solution, Stats};

/// How the parameter is walked.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize)]
pub enum Scale {
    /// `Log` when `from` and `to` have the same sign and differ by a factor of 10 or more (up to
    /// rounding: `0.1 → 0.01` is logarithmic), else `Linear`.
    #[default]
    Auto,
    /// Steps in `λ`.
    Linear,
    /// Steps in `ln |λ|` (needs `from`, `to` nonzero and of the same sign).
    Log,
}

/// Options of [`solve_by_continuation`].
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct PathOptions {
    /// Parameter scale. Default [`Scale::Auto`].
    pub scale: Scale,
    /// Continuation options. Default: those of [`ContinuationOptions::default`] with
    /// `method = Natural`, `ds = 0.2`, `ds_min = 1e-4`, `ds_max = 1.0` (in the units of `scale`)
    /// and `max_steps = 500`. `lambda_min`, `lambda_max` and `direction` are set from `from` and
    /// `to` and ignored here.
    pub continuation: ContinuationOptions,
    /// Tolerance of the members solved on the way (the solver's [`BvpSolver::set_tolerance`]);
    /// the member at `to` is then solved again at the solver's own tolerance from the last one.
    /// Default `None`: every member at the solver's tolerance. A looser one makes the walk
    /// cheaper (coarser meshes, fewer shooting steps); solvers without a tolerance ignore it.
    pub intermediate_tol: Option<f64>,
}

impl Default for PathOptions {
    fn default() -> Self {
        PathOptions {
            scale: Scale::Auto,
            continuation: ContinuationOptions {
                method: Method::Natural,
                ds: 0.2,
                ds_min: 1e-4,
                ds_max: 1.0,
                max_steps: 500,
                ..ContinuationOptions::default()
            },
            intermediate_tol: None,
        }
    }
}

impl PathOptions {
    /// Checks the continuation options (bounds and direction excepted) and `intermediate_tol`
    /// (`0 < tol < 1`).
    pub fn validate(&self) -> Result<(), BvpError> {
        if let Some(t) = self.intermediate_tol {
            if !(t > 0.0 && t < 1.0) {
                return Err(invalid("intermediate_tol", t, "must be in (0, 1)"));
            }
        }
        ContinuationOptions {
            lambda_min: f64::NEG_INFINITY,
            lambda_max: f64::INFINITY,
            direction: 1.0,
            ..self.continuation.clone()
        }
        .validate()
    }
}

/// The solution at `to` and how it was reached.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct PathSolution {
    /// The solution of the member at `to` (its `stats` are those of the last solve).
    pub solution: Solution,
    /// Parameter values of the accepted points, `from` first and `to` last.
    pub path: Vec<f64>,
    /// Work of the whole walk: every solve, rejected steps included.
    pub stats: Stats,
}

/// The family in `μ = ln(λ/sign)`: `λ = sign·e^μ`.
struct LogFamily<'a, P: ?Sized> {
    family: &'a P,
    sign: f64,
}

impl<P: ParamBvp + ?Sized> ParamBvp for LogFamily<'_, P> {
    fn dims(&self) -> Dims {
        self.family.dims()
    }
    fn interval(&self) -> (f64, f64) {
        self.family.interval()
    }
    fn rhs(&self, s: f64, z: &[f64], p: &[f64], mu: f64, dz: &mut [f64]) {
        self.family.rhs(s, z, p, self.sign * mu.exp(), dz)
    }
    fn bc(&self, za: &[f64], zb: &[f64], p: &[f64], mu: f64, res: &mut [f64]) {
        self.family.bc(za, zb, p, self.sign * mu.exp(), res)
    }
    fn rhs_jacobian(
        &self,
        s: f64,
        z: &[f64],
        p: &[f64],
        mu: f64,
        dfdz: &mut [f64],
        dfdp: &mut [f64],
        dfdl: &mut [f64],
    ) -> bool {
        let lambda = self.sign * mu.exp();
        let ok = self.family.rhs_jacobian(s, z, p, lambda, dfdz, dfdp, dfdl);
        dfdl.iter_mut().for_each(|d| *d *= lambda);
        ok
    }
    fn bc_jacobian(
        &self,
        za: &[f64],
        zb: &[f64],
        p: &[f64],
        mu: f64,
        dga: &mut [f64],
        dgb: &mut [f64],
        dgp: &mut [f64],
        dgl: &mut [f64],
    ) -> bool {
        let lambda = self.sign * mu.exp();
        let ok = self
            .family
            .bc_jacobian(za, zb, p, lambda, dga, dgb, dgp, dgl);
        dgl.iter_mut().for_each(|d| *d *= lambda);
        ok
    }
}

/// The identity reparametrization (so both scales share one code path).
struct Same<'a, P: ?Sized>(&'a P);

impl<P: ParamBvp + ?Sized> ParamBvp for Same<'_, P> {
    fn dims(&self) -> Dims {
        self.0.dims()
    }
    fn interval(&self) -> (f64, f64) {
        self.0.interval()
    }
    fn rhs(&self, s: f64, z: &[f64], p: &[f64], l: f64, dz: &mut [f64]) {
        self.0.rhs(s, z, p, l, dz)
    }
    fn bc(&self, za: &[f64], zb: &[f64], p: &[f64], l: f64, res: &mut [f64]) {
        self.0.bc(za, zb, p, l, res)
    }
    fn rhs_jacobian(
        &self,
        s: f64,
        z: &[f64],
        p: &[f64],
        l: f64,
        dfdz: &mut [f64],
        dfdp: &mut [f64],
        dfdl: &mut [f64],
    ) -> bool {
        self.0.rhs_jacobian(s, z, p, l, dfdz, dfdp, dfdl)
    }
    fn bc_jacobian(
        &self,
        za: &[f64],
        zb: &[f64],
        p: &[f64],
        l: f64,
        dga: &mut [f64],
        dgb: &mut [f64],
        dgp: &mut [f64],
        dgl: &mut [f64],
    ) -> bool {
        self.0.bc_jacobian(za, zb, p, l, dga, dgb, dgp, dgl)
    }
}

fn invalid(name: &'static str, value: impl std::fmt::Display, reason: &'static str) -> BvpError {
    BvpError::InvalidOption {
        name,
        value: value.to_string(),
        reason,
    }
}

/// Solves the member of `family` at `to` by continuation from the member at `from`, which is
/// solved first from `guess` (see the [module docs](self)). `solver` is used for every solve.
///
/// Errors: the solver's error at `from` (as is); [`BvpError::Continuation`] when the walk
/// cannot proceed even at `ds_min` (with the parameter reached and the solver's last error);
/// [`BvpError::PathEnded`] when `max_steps` run out or the branch turns back before `to`. Both
/// report the parameter itself (not its logarithm on a log scale).
///
/// ```
/// use bvp::{samples::BratuFamily, solve_by_continuation, Guess, PathOptions, Shooting, ShootingOptions};
///
/// // Bratu u'' + λeᵘ = 0 from λ = 0.1 to λ = 3 (lower branch, below the fold at 3.5138)
/// let mut solver = Shooting::new(ShootingOptions::default())?;
/// let guess = Guess::constant(0.0, 1.0, 11, &[0.0, 0.0], vec![]);
/// let res = solve_by_continuation(&BratuFamily, &mut solver, &guess, 0.1, 3.0, &PathOptions::default())?;
/// let exact = bvp::samples::Bratu { lambda: 3.0 }.exact(0, 0.5)[0];
/// assert!((res.solution.at(0.5)[0] - exact).abs() < 1e-7);
/// # Ok::<(), bvp::BvpError>(())
/// ```
pub fn solve_by_continuation<P: ParamBvp + ?Sized, S: BvpSolver>(
    family: &P,
    solver: &mut S,
    guess: &Guess,
    from: f64,
    to: f64,
    opts: &PathOptions,
) -> Result<PathSolution, BvpError> {
    opts.validate()?;
    if !(from.is_finite() && to.is_finite()) {
        return Err(invalid(
            "from/to",
            format!("{from} -> {to}"),
            "must be finite",
        ));
    }
    let log = match opts.scale {
        Scale::Linear => false,
        Scale::Log => {
            if from * to <= 0.0 || (from * to).is_nan() {
                return Err(invalid(
                    "scale",
                    format!("Log with {from} -> {to}"),
                    "Log needs from and to nonzero and of the same sign",
                ));
            }
            true
        }
        // A factor of 10 or more, up to rounding (0.01 / 0.1 = 0.09999999999999999).
        Scale::Auto => {
            from * to > 0.0 && (to / from).ln().abs() >= std::f64::consts::LN_10 * (1.0 - 1e-12)
        }
    };
    let own_tol = solver.tolerance();
    if let (Some(t), Some(_)) = (opts.intermediate_tol, own_tol) {
        solver.set_tolerance(t);
    }
    let recheck = solver.set_walking(true);
    let walked = walk_family(family, solver, guess, from, to, opts, log);
    solver.set_walking(false);
    let loosened = own_tol.filter(|_| opts.intermediate_tol.is_some());
    if let Some(tol) = loosened {
        solver.set_tolerance(tol);
    }
    if loosened.is_none() && !recheck {
        return walked;
    }
    let mut res = walked?;
    // The member at `to` at the solver's own tolerance and checks, from the last one on the way.
    let sol = solver.solve(&Member::new(family, to), &Guess::from(&res.solution))?;
    res.stats.accumulate(&sol.stats);
    res.stats.nodes = sol.stats.nodes;
    res.stats.residual = sol.stats.residual;
    res.stats.error_estimate = sol.stats.error_estimate;
    res.solution = sol;
    Ok(res)
}

/// [`solve_by_continuation`] at the solver's current tolerance.
fn walk_family<P: ParamBvp + ?Sized, S: BvpSolver>(
    family: &P,
    solver: &mut S,
    guess: &Guess,
    from: f64,
    to: f64,
    opts: &PathOptions,
    log: bool,
) -> Result<PathSolution, BvpError> {
    let start = solver.solve(&Member::new(family, from), guess)?;
    let mut stats = start.stats.clone();
    if from == to {
        return Ok(PathSolution {
            solution: start,
            path: vec![from],
            stats,
        });
    }
    let sign = from.signum();
    let walk = |solver: &mut S, stats: &mut Stats, fam: &dyn ParamBvp, m0: f64, m1: f64| {
        let copts = ContinuationOptions {
            lambda_min: m0.min(m1),
            lambda_max: m0.max(m1),
            direction: (m1 - m0).signum(),
            ..opts.continuation.clone()
        };
        let mut path = Vec::new();
        let cont = Continuation::new(fam, &mut *solver, start.clone(), m0, copts)?;
        let mut last_lambda = m0;
        let mut turned_back = false;
        for point in cont {
            let point = match point {
                Ok(p) => p,
                Err(e) => {
                    if let Some(s) = e.stats() {
                        stats.accumulate(s);
                    }
                    return Err(e);
                }
            };
            if point.step > 0 {
                stats.accumulate(&point.stats);
            }
            path.push(point.lambda);
            last_lambda = point.lambda;
            if point.step > 0 && point.on_bound {
                if point.lambda == m1 {
                    return Ok((point.solution, path));
                }
                turned_back = true;
                break;
            }
        }
        Err(BvpError::PathEnded {
            lambda: last_lambda,
            steps: path.len().saturating_sub(1),
            turned_back,
            stats: stats.clone(),
        })
    };
    // Errors carry the parameter itself, not its logarithm.
    let unlog = |e: BvpError| match e {
        BvpError::Continuation {
            step,
            lambda,
            ds,
            hint,
            source,
        } if log => BvpError::Continuation {
            step,
            lambda: sign * lambda.exp(),
            ds,
            hint,
            source,
        },
        BvpError::Fold {
            step,
            lambda,
            fold,
            source,
        } if log => BvpError::Fold {
            step,
            lambda: sign * lambda.exp(),
            fold: sign * fold.exp(),
            source,
        },
        BvpError::PathEnded {
            lambda,
            steps,
            turned_back,
            stats,
        } if log => BvpError::PathEnded {
            lambda: sign * lambda.exp(),
            steps,
            turned_back,
            stats,
        },
        e => e,
    };
    let (solution, path) = if log {
        let fam = LogFamily { family, sign };
        let (sol, path) = walk(
            solver,
            &mut stats,
            &fam,
            (from / sign).ln(),
            (to / sign).ln(),
        )
        .map_err(unlog)?;
        (sol, path.into_iter().map(|m| sign * m.exp()).collect())
    } else {
        walk(solver, &mut stats, &Same(family), from, to)?
    };
    let mut path: Vec<f64> = path;
    if let Some(last) = path.last_mut() {
        *last = to;
    }
    if let Some(first) = path.first_mut() {
        *first = from;
    }
    stats.nodes = solution.stats.nodes;
    stats.residual = solution.stats.residual;
    stats.error_estimate = solution.stats.error_estimate;
    Ok(PathSolution {
        solution,
        path,
        stats,
    })
}

/// Solves the member of `family` at `lambda`: directly from `guess` first and, if that fails,
/// by [`solve_by_continuation`] from the easy member at `easy` (solved from the same `guess`)
/// with `opts` — the automatic fallback for a plain solve whose hard parameter the user names.
/// The returned `path` is `[lambda]` for a direct solve; `stats` count both attempts.
///
/// Errors: the continuation's (see [`solve_by_continuation`]) when both fail.
///
/// ```
/// use bvp::testset::CashMazzia;
/// use bvp::{solve_member, Collocation, CollocationOptions, PathOptions, Scheme};
///
/// // ε y'' = 1 − y'² at ε = 1e-4 defeats Newton (and its homotopy) from a straight line;
/// // ε = 0.1 does not.
/// let p = CashMazzia::new(20).unwrap();
/// let mut solver = Collocation::new(CollocationOptions {
///     scheme: Scheme::Lobatto6,
///     ..CollocationOptions::default()
/// })?;
/// let res = solve_member(&p, &mut solver, &p.guess(1e-4, 101), 1e-4, 0.1, &PathOptions::default())?;
/// assert!(res.path.len() > 2);
/// # Ok::<(), bvp::BvpError>(())
/// ```
pub fn solve_member<P: ParamBvp + ?Sized, S: BvpSolver>(
    family: &P,
    solver: &mut S,
    guess: &Guess,
    lambda: f64,
    easy: f64,
    opts: &PathOptions,
) -> Result<PathSolution, BvpError> {
    opts.validate()?;
    let direct = match solver.solve(&Member::new(family, lambda), guess) {
        Ok(sol) => {
            return Ok(PathSolution {
                stats: sol.stats.clone(),
                solution: sol,
                path: vec![lambda],
            })
        }
        Err(e) => e,
    };
    let spent = direct.stats().cloned().unwrap_or_default();
    let mut res = solve_by_continuation(family, solver, guess, easy, lambda, opts)?;
    res.stats.accumulate(&spent);
    Ok(res)
}
