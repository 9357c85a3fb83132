//! One collocation solve across its mesh passes: Newton on a mesh, then error control,
//! the conditioning check, the check of the returned interpolant, refinement and coarsening
//! (see the module docs of [`crate::collocation`]), each step a method of [`Run`].

use super::{
    adapt_mesh, attach_stats, bisect, fill_unknowns, snapshot, with_total_stats,
    CollocationOptions, Disc, ErrorControl, Progress, Scheme, Snapshot, Tableau, MAX_COARSEN,
    MAX_ILL_REFINES, MAX_RETRIES,
};
use crate::newton::{attach, homotopy, Newton};
use crate::{Bvp, BvpError, Check, Dense, Dims, Guess, NewtonOptions, Solution, Stats, Status};

/// Limits of the Lobatto4 solve that seeds a failed Lobatto6 ([`Run::seed_from_lobatto4`]).
const SEED_MAX_NODES: usize = 500;
const SEED_MAX_PASSES: usize = 6;

/// What the solve does after a mesh pass (one value per pass: its size does not matter).
#[allow(clippy::large_enum_variant)]
pub(super) enum Next {
    /// Solve again, on `Run::mesh` from `Run::u`.
    Again,
    /// The outcome of the solve.
    Done(Result<Solution, BvpError>),
}

/// What a pass needs besides the state: options, tableau, dimensions, the guess.
pub(super) struct Ctx<'c> {
    pub opts: &'c CollocationOptions,
    /// Newton's options with the residual threshold of the module docs.
    pub nopts: NewtonOptions,
    pub tab: &'c Tableau,
    pub dims: Dims,
    pub guess: &'c Guess,
}

/// The state of one solve across its mesh passes.
pub(super) struct Run {
    /// The mesh of the next pass (empty while a pass runs on it).
    pub mesh: Vec<f64>,
    /// The unknowns (starting values of the next pass, then its solution).
    pub u: Vec<f64>,
    /// The solution the current starting values were interpolated from.
    source: Option<Snapshot>,
    /// An accepted solution while a coarser mesh is tried.
    best: Option<Solution>,
    retries: usize,
    coarsenings: usize,
    ill_refines: usize,
    homotopy_tried: bool,
    /// Lobatto6 restarted from Lobatto4's solution ([`Run::seed_from_lobatto4`]).
    seeded: bool,
    /// The starting values in place of the guess after such a restart.
    seed: Option<Guess>,
    /// The collocation polynomial's scaled RMS residual per interval.
    rms: Vec<f64>,
    /// The residual tolerance in force: `tol`, lowered by error control
    /// ([`super::ErrorControl::Error`]) until the estimated error meets `tol`.
    res_tol: f64,
    /// The error control in force: the option's, or `Error` once the guard of `Guarded` found
    /// an estimated error above `tol` ([`Run::guard`]).
    control: ErrorControl,
    /// The guard's first estimate ([`super::Collocation::guard_error`]).
    pub guard: Option<f64>,
    /// The estimate that checked the guard's alarm ([`super::ErrorControl::Confirmed`],
    /// [`super::Collocation::confirmation`]).
    pub confirmed: Option<f64>,
    /// A cap on Newton's residual threshold besides `res_tol / 20`: set when a confirmed alarm
    /// re-solves on the same mesh first ([`Run::confirm`]).
    newton_cap: f64,
    /// The error estimate that made error control refine the mesh last: the next estimate
    /// must be at most half of it ([`Run::refine_for_error`]).
    refined_from: Option<f64>,
    /// After such a refinement: the largest residual of the last pass that refined for the
    /// lowered residual tolerance ([`Run::residual_floor`]).
    refined_residual: Option<f64>,
    /// A cap on Newton's precision floor (`newton.step_residual_tol`): set to `bc_tol` when
    /// Newton stopped at its floor with the boundary conditions unmet ([`Run::floor_missed`]).
    floor_cap: f64,
    pub stats: Stats,
}

/// The factor by which error control lowers the residual tolerance when the estimated error
/// `worst` misses `tol` (the error is the residual propagated by the problem's Green's function,
/// proportional to it; halved again, between 1/1000 and 1/2).
fn lowering(tol: f64, worst: f64) -> f64 {
    (0.5 * tol / worst).clamp(1e-3, 0.5)
}

/// The largest entry; NaN counts as infinite (a residual that could not be evaluated fails).
fn max_of(v: &[f64]) -> f64 {
    v.iter().fold(
        0.0_f64,
        |m, x| if x.is_nan() { f64::INFINITY } else { m.max(*x) },
    )
}

impl Run {
    /// The starting mesh and values from the guess.
    pub fn start(cx: &Ctx<'_>, mesh: Vec<f64>) -> Result<Run, BvpError> {
        let stats = Stats::default();
        if mesh.len() > cx.opts.max_nodes {
            return Err(BvpError::MeshLimit {
                max_nodes: cx.opts.max_nodes,
                needed: mesh.len(),
                residual: f64::NAN,
                stats,
            });
        }
        let mut u = Vec::new();
        let guess = cx.guess;
        fill_unknowns(
            cx.tab,
            &mesh,
            cx.dims,
            &guess.params,
            |s, o| guess.eval(s, o),
            &mut u,
        );
        Ok(Run {
            mesh,
            u,
            source: None,
            best: None,
            retries: 0,
            coarsenings: 0,
            ill_refines: 0,
            homotopy_tried: false,
            seeded: false,
            seed: None,
            rms: Vec::new(),
            res_tol: cx.opts.tol,
            control: cx.opts.control,
            guard: None,
            confirmed: None,
            newton_cap: f64::INFINITY,
            refined_from: None,
            refined_residual: None,
            floor_cap: f64::INFINITY,
            stats,
        })
    }

    /// The pass limit is reached: the accepted solution if there is one, else `MeshLimit`.
    pub fn out_of_passes(self, cx: &Ctx<'_>) -> Result<Solution, BvpError> {
        if let Some(sol) = self.best {
            return Ok(with_total_stats(sol, &self.stats));
        }
        let mut stats = self.stats;
        stats.nodes = self.mesh.len();
        Err(BvpError::MeshLimit {
            max_nodes: cx.opts.max_nodes,
            needed: self.mesh.len(),
            residual: stats.error_estimate.unwrap_or(f64::NAN),
            stats,
        })
    }

    /// Moves to the mesh `fine`, interpolating the solution on `mesh` (its collocation
    /// polynomials).
    fn move_to<P: Bvp + ?Sized>(
        &mut self,
        cx: &Ctx<'_>,
        disc: &Disc<'_, P>,
        mesh: &[f64],
        fine: Vec<f64>,
    ) {
        let snap = snapshot(disc, mesh, &self.u);
        snap.fill(cx.tab, cx.dims, &fine, &mut self.u);
        self.source = Some(snap);
        self.mesh = fine;
    }

    /// The accepted solution kept while a coarser mesh was tried, if any.
    fn keep_best(&mut self) -> Option<Next> {
        let sol = self.best.take()?;
        Some(Next::Done(Ok(with_total_stats(sol, &self.stats))))
    }

    /// Damped Newton on this mesh; the first time it fails (stall, iteration limit), the Newton
    /// homotopy from the same starting values.
    pub fn newton<P: Bvp + ?Sized>(
        &mut self,
        cx: &Ctx<'_>,
        newton: &mut Newton,
        disc: &mut Disc<'_, P>,
    ) -> Result<(), BvpError> {
        let start = (!self.homotopy_tried).then(|| self.u.clone());
        let mut nopts = cx.nopts.clone();
        nopts.tol = nopts.tol.min(self.res_tol / 20.0).min(self.newton_cap);
        nopts.step_residual_tol = nopts.step_residual_tol.min(self.floor_cap);
        let mut res = newton.solve(disc, &mut self.u, &nopts, &mut self.stats);
        if let (Err(BvpError::Stalled { .. } | BvpError::MaxIterations { .. }), Some(u0)) =
            (&res, start)
        {
            if disc.non_finite.is_none() && cx.opts.homotopy {
                self.homotopy_tried = true;
                let mut uh = u0;
                let mut hstats = self.stats.clone();
                if homotopy(newton, disc, &mut uh, &nopts, &mut hstats).is_ok() {
                    self.u = uh;
                    res = Ok(());
                }
                self.stats = hstats;
            }
        }
        res
    }

    /// Newton failed on `mesh` with `e`: refine where the unconverged iterate's residual is large
    /// and restart from that iterate (as solve_bvp does: a coarse mesh that cannot resolve a
    /// layer often has no nearby discrete solution at all), bisect, or report.
    pub fn after_failure<P: Bvp + ?Sized>(
        &mut self,
        cx: &Ctx<'_>,
        disc: &mut Disc<'_, P>,
        mesh: &[f64],
        mut e: BvpError,
    ) -> Next {
        let failed = matches!(e, BvpError::Stalled { .. } | BvpError::MaxIterations { .. });
        if let (true, Some((location, s))) = (failed, disc.non_finite) {
            // Newton was blocked by NaN/∞ of the problem: report that, it is the cause.
            e = BvpError::NonFinite {
                location,
                s,
                stats: self.stats.clone(),
            };
        }
        if let Some(next) = self.keep_best() {
            // A coarsening attempt failed: keep the accepted solution.
            return next;
        }
        let retry = failed && disc.non_finite.is_none() && cx.opts.adapt;
        // Not from a guess with slopes: those come from solutions (continuation's predictor, a
        // warm start), close enough that a failure there is the member's, not the guess's (the
        // restart cost Cash–Mazzia 104 at ε = 1e-4 +40 % inside continuation).
        let poor_guess = cx.guess.dz.is_none();
        if retry && self.retries == 0 && cx.tab.internal && !self.seeded && poor_guess {
            self.seeded = true;
            if self.seed_from_lobatto4(cx, disc.prob) {
                return Next::Again;
            }
        }
        let retry = retry && self.retries < MAX_RETRIES;
        let max_nodes = cx.opts.max_nodes;
        if retry
            && disc
                .estimate(&self.u, &mut self.rms, &mut self.stats)
                .is_ok()
        {
            let mut fine = adapt_mesh(mesh, &self.rms, self.res_tol, true, false);
            if fine.len() == mesh.len() {
                fine = bisect(mesh);
            }
            if fine.len() <= max_nodes {
                self.retries += 1;
                self.move_to(cx, disc, mesh, fine);
                return Next::Again;
            }
        }
        if retry && 2 * mesh.len() - 1 <= max_nodes {
            self.retries += 1;
            let fine = bisect(mesh);
            match &self.source {
                Some(snap) => snap.fill(cx.tab, cx.dims, &fine, &mut self.u),
                None => {
                    let guess = self.seed.as_ref().unwrap_or(cx.guess);
                    fill_unknowns(
                        cx.tab,
                        &fine,
                        cx.dims,
                        &guess.params,
                        |s, o| guess.eval(s, o),
                        &mut self.u,
                    )
                }
            }
            self.mesh = fine;
            return Next::Again;
        }
        Next::Done(Err(attach_stats(e, &self.stats)))
    }

    /// Lobatto6's Newton failed on its first mesh (damped, then the homotopy): Lobatto4 from the
    /// same guess at `max(tol, 1e-3)` and, if it converges, Lobatto6 restarted on its mesh from
    /// its solution. Lobatto6's Newton has a smaller region of convergence from a poor guess
    /// (Falkner–Skan from the tutorial's guess `(0, 0, 1)`: Lobatto6 stalled on 8 299 nodes
    /// after 4.7 s where Lobatto4 converges in 0.7 ms); Lobatto4's solution is within its
    /// `O(h⁴)` of Lobatto6's discrete solution on that mesh. Returns whether it restarted.
    fn seed_from_lobatto4<P: Bvp + ?Sized>(&mut self, cx: &Ctx<'_>, problem: &P) -> bool {
        // A seed is worth only a cheap solve: no homotopy (Lobatto6 tried one), few passes and
        // nodes (Falkner–Skan: 5 passes, 69 nodes). Cash–Mazzia 104 at ε = 1e-4 spent 2 s in an
        // unbounded Lobatto4 seed that did not help, +20 % on the whole Lobatto6 study.
        let opts = CollocationOptions {
            scheme: Scheme::Lobatto4,
            tol: cx.opts.tol.max(1e-3),
            bc_tol: Some(cx.opts.bc_tol().max(1e-3)),
            max_nodes: cx.opts.max_nodes.min(SEED_MAX_NODES),
            max_mesh_passes: SEED_MAX_PASSES,
            homotopy: false,
            control: ErrorControl::Residual,
            ..cx.opts.clone()
        };
        let Ok(mut l4) = super::Collocation::new(opts) else {
            return false;
        };
        let result = l4.solve_plain(problem, cx.guess, &mut |_| {});
        let sol = match result {
            Ok(sol) => sol,
            Err(e) => {
                if let Some(st) = e.stats() {
                    self.stats.accumulate(st);
                }
                return false;
            }
        };
        self.stats.accumulate(&sol.stats);
        let seed = Guess::from(&sol);
        fill_unknowns(
            cx.tab,
            &sol.mesh,
            cx.dims,
            &seed.params,
            |s, o| seed.eval(s, o),
            &mut self.u,
        );
        self.mesh = sol.mesh;
        self.source = None;
        self.seed = Some(seed);
        true
    }

    /// Newton converged on `mesh`: error control, the conditioning check, and acceptance or
    /// refinement.
    pub fn after_newton<P: Bvp + ?Sized>(
        &mut self,
        cx: &Ctx<'_>,
        disc: &mut Disc<'_, P>,
        mesh: &[f64],
        observer: &mut dyn FnMut(&Progress<'_>),
    ) -> Next {
        if let Err(e) = disc.estimate(&self.u, &mut self.rms, &mut self.stats) {
            return Next::Done(Err(attach(e, self.stats.newton_iters, &self.stats)));
        }
        let bcres = disc.bc_residual(&self.u, &mut self.stats);
        let max_rms = max_of(&self.rms);
        self.stats.error_estimate = Some(max_rms);
        observer(&Progress {
            pass: self.stats.mesh_passes,
            mesh,
            newton_iters: self.stats.newton_iters,
            newton_converged: true,
            residual: self.stats.residual,
            residuals: &self.rms,
        });
        let opts = cx.opts;
        let met = max_rms <= self.res_tol && bcres <= opts.bc_tol();
        if met && opts.adapt {
            if let Some(next) = self.ill_conditioned(cx, disc, mesh, max_rms.max(bcres)) {
                return next;
            }
        }
        if !opts.adapt || met {
            return self.accept(cx, disc, mesh);
        }
        if let Some(next) = self.keep_best() {
            // The coarsened mesh missed the tolerance: keep the accepted solution.
            return next;
        }
        if max_rms > self.res_tol {
            if let Some(next) = self.residual_floor(max_rms, mesh.len()) {
                return next;
            }
        }
        let new_mesh = adapt_mesh(mesh, &self.rms, self.res_tol, true, opts.coarsen);
        if new_mesh == mesh {
            return self.floor_missed(cx, bcres);
        }
        if new_mesh.len() > opts.max_nodes {
            return Next::Done(Err(BvpError::MeshLimit {
                max_nodes: opts.max_nodes,
                needed: new_mesh.len(),
                residual: max_rms,
                stats: self.stats.clone(),
            }));
        }
        self.move_to(cx, disc, mesh, new_mesh);
        Next::Again
    }

    /// The residual is met on this mesh but the boundary conditions are not (`bcres` above
    /// `bc_tol`): Newton stopped at its precision floor, where a full step no longer decreased
    /// the merit function. That test cannot tell rounding from a Newton step that is too long
    /// for the nonlinearity (a nearly singular problem: the dynamic rod pressed into a nearly
    /// straight strut moved its interior by 2 000 times the foot's 3e-10 in one step, and the
    /// product of force and angle in `m'` undid the step): once, Newton goes on from its iterate
    /// on the same mesh with its floor capped at `bc_tol`, so that only the damped steps decide.
    /// A second time, or a cap already at `bc_tol`, is [`BvpError::Stalled`].
    fn floor_missed(&mut self, cx: &Ctx<'_>, bcres: f64) -> Next {
        let cap = cx.opts.bc_tol();
        if self.floor_cap > cap && cx.nopts.step_residual_tol > cap {
            self.floor_cap = cap;
            return Next::Again;
        }
        Next::Done(Err(BvpError::Stalled {
            iteration: self.stats.newton_iters,
            residual: bcres,
            stats: self.stats.clone(),
        }))
    }

    /// Error control lowered the residual tolerance and refined (`refined_from`), and the
    /// residual `r` (max over the intervals, of `nodes` nodes) still misses it: if a pass that
    /// refined for it did not halve `r`, the residual is at a floor (rounding in `F`) that the
    /// lowered tolerance is below: [`BvpError::Inaccurate`] at once (`r` and the tolerance), not
    /// at `max_nodes` (the rod dynamics of the `vibrissa` crate under error control: a residual
    /// of 1.9e-9 against 1.1e-12 on 6 958 nodes). `None`: refine on.
    fn residual_floor(&mut self, r: f64, nodes: usize) -> Option<Next> {
        self.refined_from?;
        let stalled = self.refined_residual.is_some_and(|last| r > 0.5 * last);
        self.refined_residual = Some(r);
        if !stalled {
            return None;
        }
        self.stats.nodes = nodes;
        self.stats.error_estimate = Some(r);
        Some(Next::Done(Err(BvpError::Inaccurate {
            check: Check::ErrorEstimate,
            value: r,
            tol: self.res_tol,
            stats: self.stats.clone(),
        })))
    }

    /// The conditioning check (module docs) of a solution whose residuals are of size `r`:
    /// `None` if it passes. Those residuals may move the solution by `amp` times their size;
    /// beyond the size of the solution itself no digit is right: the problem is numerically
    /// singular here (e.g. it has no solution and the mesh only picks one of huge amplitude),
    /// reported as a singular Jacobian. The defect, not `tol`: a well-posed layer problem has
    /// `amp ~ 1/ε` in `y'` on any mesh (Cash–Mazzia 3 at ε = 1e-4: 4.8e4), so `amp·tol` can
    /// exceed the solution's size while the error is tiny.
    fn ill_conditioned<P: Bvp + ?Sized>(
        &mut self,
        cx: &Ctx<'_>,
        disc: &mut Disc<'_, P>,
        mesh: &[f64],
        r: f64,
    ) -> Option<Next> {
        let amp = match disc.amplification(&self.u, &mut self.stats) {
            Ok(amp) => amp,
            Err(e) => return Some(Next::Done(Err(attach_stats(e, &self.stats)))),
        };
        let size = self.u.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        if amp * r <= 1.0 + size {
            return None;
        }
        if let Some(next) = self.keep_best() {
            return Some(next);
        }
        // A mesh that barely meets the tolerance can fail this by itself: bisect (from this
        // solution) a few times before reporting; the defect falls like h^order, the
        // amplification of a nearly singular problem grows.
        if self.ill_refines < MAX_ILL_REFINES && 2 * mesh.len() - 1 <= cx.opts.max_nodes {
            self.ill_refines += 1;
            self.move_to(cx, disc, mesh, bisect(mesh));
            return Some(Next::Again);
        }
        self.stats.nodes = mesh.len();
        Some(Next::Done(Err(BvpError::SingularJacobian {
            iteration: self.stats.newton_iters,
            stats: self.stats.clone(),
        })))
    }

    /// The solution on `mesh` met the error control: build the returned object and check it
    /// (the residual of the returned interpolant at interior points of every interval, as
    /// scipy does; its maximum is `stats.error_estimate`). If it misses `tol`, refine where it
    /// does (or report `Inaccurate` at the node limit), except where the miss is Newton's
    /// rounding floor ([`at_floor`]: refinement would raise it); else try a coarser mesh or
    /// return it (its `error_estimate` then the check, above `tol` by that floor).
    fn accept<P: Bvp + ?Sized>(
        &mut self,
        cx: &Ctx<'_>,
        disc: &mut Disc<'_, P>,
        mesh: &[f64],
    ) -> Next {
        let opts = cx.opts;
        let (sol, check, d2z) = returned(
            cx,
            disc,
            mesh,
            &self.u,
            (&self.rms, self.res_tol),
            &mut self.stats,
        );
        let worst = max_of(&check);
        let refinable =
            |(a, b): (&f64, &f64)| !(*b <= self.res_tol || at_floor(*a, *b, self.res_tol));
        if opts.adapt && self.rms.iter().zip(&check).any(refinable) {
            if let Some(next) = self.keep_best() {
                return next;
            }
            if let Some(next) = self.residual_floor(worst, mesh.len()) {
                return next;
            }
            let both: Vec<f64> = self
                .rms
                .iter()
                .zip(&check)
                .map(|(a, b)| {
                    if at_floor(*a, *b, self.res_tol) {
                        *a
                    } else {
                        a.max(*b)
                    }
                })
                .collect();
            let fine = adapt_mesh(mesh, &both, self.res_tol, true, false);
            if fine.len() > opts.max_nodes {
                return Next::Done(Err(BvpError::Inaccurate {
                    check: Check::ErrorEstimate,
                    value: worst,
                    tol: self.res_tol,
                    stats: sol.stats,
                }));
            }
            self.move_to(cx, disc, mesh, fine);
            return Next::Again;
        }
        if opts.adapt
            && matches!(
                self.control,
                ErrorControl::Guarded | ErrorControl::Confirmed
            )
        {
            if let Some(next) = self.guard(cx, disc, mesh, &sol, d2z.as_deref()) {
                return next;
            }
        }
        if opts.adapt && self.control == ErrorControl::Error {
            return self.control_error(cx, disc, mesh, sol);
        }
        if opts.adapt && opts.coarsen && self.coarsenings < MAX_COARSEN {
            let coarse = adapt_mesh(mesh, &self.rms, self.res_tol, false, true);
            if coarse.len() * 10 <= mesh.len() * 9 {
                self.coarsenings += 1;
                self.move_to(cx, disc, mesh, coarse);
                self.best = Some(sol);
                return Next::Again;
            }
        }
        Next::Done(Ok(sol))
    }
}

impl Run {
    /// The guard of residual control (`collocation::guard`): the true error of `sol` (which met
    /// the residual tolerance on `mesh`) estimated by deferred correction, into `self.guard`.
    /// `None` if it meets `tol` (or cannot be formed): `sol` goes on as accepted. Else the solve
    /// switches to [`ErrorControl::Error`] from here on (the first estimate is kept).
    fn guard<P: Bvp + ?Sized>(
        &mut self,
        cx: &Ctx<'_>,
        disc: &mut Disc<'_, P>,
        mesh: &[f64],
        sol: &Solution,
        d2z: Option<&[f64]>,
    ) -> Option<Next> {
        let scale = scales(cx, sol);
        let est = disc.guard(&self.u, sol, (d2z, scale.as_deref()), &mut self.stats);
        let previous = std::mem::replace(&mut self.guard, est);
        let est = est?;
        if est <= cx.opts.tol {
            return None;
        }
        if let Some(next) = self.keep_best() {
            // A coarser mesh tried after an accepted one (which met the guard): keep that one,
            // and its estimate.
            self.guard = previous;
            return Some(next);
        }
        if self.control == ErrorControl::Confirmed {
            return Some(self.confirm(cx, disc, sol.clone()));
        }
        self.control = ErrorControl::Error;
        Some(self.control_error(cx, disc, mesh, sol.clone()))
    }

    /// [`ErrorControl::Confirmed`]: the guard's alarm on `sol` is checked against a reference
    /// ([`error_estimate`], as error control does). Not confirmed (the estimated error meets
    /// `tol`): `sol` is returned as residual control accepted it (its `error_estimate` the
    /// residual; no coarsening, which would only meet the guard's alarm again). Confirmed: the
    /// solve continues under [`ErrorControl::Error`], first on the same mesh with Newton's
    /// threshold lowered (part of the error can be Newton's: in the rod dynamics of the
    /// `vibrissa` crate at tol 1e-10, Newton stops at a scaled residual of 5e-12, the position
    /// is then 3e-12 off and the step equations amplify that by `μ·4/Δt² = 3100` into an error
    /// of 6.4e-9 in the internal force; every such alarm in its tests was cleared by this
    /// re-solve), then refining.
    fn confirm<P: Bvp + ?Sized>(
        &mut self,
        cx: &Ctx<'_>,
        disc: &mut Disc<'_, P>,
        sol: Solution,
    ) -> Next {
        let est = error_estimate(cx, disc.prob, &sol, (self.res_tol, self.newton_cap));
        if let Some(st) = &est.1 {
            self.stats.accumulate(st);
        }
        let worst = est.0.as_ref().map_or(f64::INFINITY, |e| max_of(e));
        self.confirmed = Some(worst);
        if worst <= cx.opts.tol {
            return Next::Done(Ok(with_total_stats(sol, &self.stats)));
        }
        self.control = ErrorControl::Error;
        // Newton's error is proportional to its residual: the one it stopped at, lowered by the
        // factor the error missed by and ten more (one or two more iterations; at Newton's
        // rounding floor it stops there).
        let reached = self.stats.residual.min(self.res_tol / 20.0);
        self.newton_cap = 0.1 * reached * lowering(cx.opts.tol, worst);
        // Next::Again without a new mesh: the same mesh, from this solution.
        Next::Again
    }

    /// Error control ([`ErrorControl::Error`]) of `sol`, which met the residual tolerance in
    /// force on `mesh`: its error is estimated against a reference ([`error_estimate`]); if it
    /// meets `tol`, `sol` is returned with that estimate. Otherwise the residual tolerance is
    /// lowered by the factor the error missed by (halved again, between 1/1000 and 1/2: the error
    /// is the residual propagated by the problem's Green's function, proportional to it) and the
    /// mesh refined where the residual exceeds it or the estimated error exceeds `tol`.
    fn control_error<P: Bvp + ?Sized>(
        &mut self,
        cx: &Ctx<'_>,
        disc: &mut Disc<'_, P>,
        mesh: &[f64],
        sol: Solution,
    ) -> Next {
        let est = error_estimate(cx, disc.prob, &sol, (self.res_tol, self.newton_cap));
        if let Some(st) = &est.1 {
            self.stats.accumulate(st);
        }
        self.refine_for_error(cx, disc, mesh, sol, est.0)
    }

    /// [`Run::control_error`] with the estimate `errs` of `sol` (per interval; `None` if the
    /// reference failed). An estimate above `tol` that is more than half the one the last
    /// refinement was made for is a floor refinement does not lower (rounding, or an error
    /// the estimate does not see falling): [`BvpError::Inaccurate`] with it at once, instead
    /// of refining to `max_nodes`.
    fn refine_for_error<P: Bvp + ?Sized>(
        &mut self,
        cx: &Ctx<'_>,
        disc: &mut Disc<'_, P>,
        mesh: &[f64],
        mut sol: Solution,
        errs: Option<Vec<f64>>,
    ) -> Next {
        let tol = cx.opts.tol;
        let worst = errs.as_ref().map_or(f64::INFINITY, |e| max_of(e));
        if worst <= tol {
            self.stats.error_estimate = Some(worst);
            sol.stats = self.stats.clone();
            return Next::Done(Ok(sol));
        }
        if self.refined_from.is_some_and(|last| worst > 0.5 * last) {
            self.stats.error_estimate = Some(worst);
            self.stats.nodes = mesh.len();
            return Next::Done(Err(BvpError::Inaccurate {
                check: Check::ErrorEstimate,
                value: worst,
                tol,
                stats: self.stats.clone(),
            }));
        }
        self.refined_from = Some(worst);
        self.refined_residual = None;
        self.res_tol *= lowering(tol, worst);
        let marks: Vec<f64> = match &errs {
            Some(e) => self
                .rms
                .iter()
                .zip(e)
                .map(|(r, e)| r.max(self.res_tol * e / tol))
                .collect(),
            None => self.rms.clone(),
        };
        let fine = adapt_mesh(mesh, &marks, self.res_tol, true, false);
        if fine.len() > cx.opts.max_nodes {
            return Next::Done(Err(BvpError::MeshLimit {
                max_nodes: cx.opts.max_nodes,
                needed: fine.len(),
                residual: worst,
                stats: self.stats.clone(),
            }));
        }
        self.move_to(cx, disc, mesh, fine);
        Next::Again
    }
}

/// With [`ErrorControl::Confirmed`] (the option): the size of every component, `max |z_c|` over
/// the nodes of `sol`, to which its errors are relative (`|S_c − R_c| / (1 + max |z_c|)`, the
/// error relative to the solution's scale, as the Cash–Mazzia study measures it). `None` in the
/// other modes: pointwise, relative to `1 + |R_c|`.
pub(super) fn scales(cx: &Ctx<'_>, sol: &Solution) -> Option<Vec<f64>> {
    if cx.opts.control != ErrorControl::Confirmed {
        return None;
    }
    let n = sol.n;
    let mut size = vec![0.0_f64; n];
    for z in sol.z.chunks_exact(n) {
        for (m, v) in size.iter_mut().zip(z) {
            *m = m.max(v.abs());
        }
    }
    Some(size)
}

/// The estimated error of `sol` per interval (max over its ends and the interior points
/// `EST_T` of `|S_c − R_c| / (1 + |R_c|)`, every component `c`; with [`ErrorControl::Confirmed`]
/// relative to `1 + max |R_c|` over the reference's nodes, [`scales`]) against a reference `R` of
/// higher accuracy on the same problem, and the reference solve's statistics. Lobatto4: `R` is
/// Lobatto6 on the same mesh (order 6 against 4 at the nodes, 5 against 4 between them);
/// Lobatto6: `R` is Lobatto6 on the halved mesh (64× more accurate). So `|S − R|` is the error
/// of `S` to a relative `O(h)` resp. `1/64`: an asymptotically correct estimate, not a bound.
/// `None` if the reference solve fails.
fn error_estimate<P: Bvp + ?Sized>(
    cx: &Ctx<'_>,
    problem: &P,
    sol: &Solution,
    (res_tol, newton_cap): (f64, f64),
) -> (Option<Vec<f64>>, Option<Stats>) {
    let mesh = if cx.tab.internal {
        bisect(&sol.mesh)
    } else {
        sol.mesh.clone()
    };
    let opts = CollocationOptions {
        scheme: Scheme::Lobatto6,
        adapt: false,
        coarsen: false,
        control: ErrorControl::Residual,
        tol: res_tol,
        max_nodes: mesh.len().max(cx.opts.max_nodes),
        newton: NewtonOptions {
            tol: cx.opts.newton.tol.min(newton_cap),
            ..cx.opts.newton.clone()
        },
        ..cx.opts.clone()
    };
    let Ok(mut solver) = super::Collocation::new(opts) else {
        return (None, None);
    };
    let mut guess = Guess::from(sol);
    if mesh.len() != sol.mesh.len() {
        guess = Guess::from_fn(sol.n, mesh, sol.params.clone(), |s, z| sol.eval(s, z));
    }
    let reference = match solver.solve_plain(problem, &guess, &mut |_| {}) {
        Ok(r) => r,
        Err(e) => return (None, e.stats().cloned()),
    };
    let n = sol.n;
    let scale = scales(cx, &reference);
    let (mut a, mut b) = (vec![0.0; n], vec![0.0; n]);
    let mut errs = Vec::with_capacity(sol.mesh.len() - 1);
    for w in sol.mesh.windows(2) {
        let mut e = 0.0_f64;
        for t in [0.0, super::EST_T[0], super::EST_T[1], super::EST_T[2], 1.0] {
            let s = w[0] + t * (w[1] - w[0]);
            sol.eval(s, &mut a);
            reference.eval(s, &mut b);
            for c in 0..n {
                let size = scale.as_ref().map_or(b[c].abs(), |s| s[c]);
                e = e.max((a[c] - b[c]).abs() / (1.0 + size));
            }
        }
        errs.push(e);
    }
    (Some(errs), Some(reference.stats))
}

/// The returned object of the solution `u` on `mesh` and the scaled RMS residual of its dense
/// output per interval. Lobatto4 returns its collocation cubic (`Dense::Hermite`), whose residual
/// is `rms` itself; Lobatto6 the quintic of [`Dense::QuinticIntervals`], whose residual is
/// measured here ([`Solution::residuals`]'s formula, three evaluations of `F` per interval).
/// `stats.error_estimate` becomes the largest residual of the returned object.
fn returned<P: Bvp + ?Sized>(
    cx: &Ctx<'_>,
    disc: &mut Disc<'_, P>,
    mesh: &[f64],
    u: &[f64],
    (rms, res_tol): (&[f64], f64),
    stats: &mut Stats,
) -> (Solution, Vec<f64>, Option<Vec<f64>>) {
    let (z, dz) = disc.nodal();
    let params = u[disc.lay.pcol()..].to_vec();
    let one_sided = cx
        .tab
        .internal
        .then(|| disc.second_derivatives(&params, &z, &dz, stats));
    let dense = match &one_sided {
        Some(d2z) => Dense::QuinticIntervals { d2z: d2z.clone() },
        None => Dense::Hermite,
    };
    let mut sol = Solution {
        n: cx.dims.n,
        mesh: mesh.to_vec(),
        z,
        dz,
        params,
        status: Status::Converged,
        stats: Stats::default(),
        dense,
    };
    let check = if cx.tab.internal {
        stats.rhs_evals += 3 * (mesh.len() - 1);
        let mut check = sol.residuals_of(disc.prob);
        if fall_back_to_the_quartic(cx, disc, &mut sol, &check, res_tol) {
            stats.rhs_evals += 3 * (mesh.len() - 1);
            check = sol.residuals_of(disc.prob);
        }
        check
    } else {
        rms.to_vec()
    };
    stats.error_estimate = Some(max_of(&check));
    sol.stats = stats.clone();
    (sol, check, one_sided)
}

/// Whether the check `check` of an interval whose collocation polynomial's residual is `rms`
/// (at most `tol`: the check runs on solutions that met it) misses `tol` by Newton's rounding
/// floor rather than by the interpolant: the part of the check the collocation polynomial does
/// not explain, `check − rms`, exceeds `tol / 2`. Such an interval returns the collocation
/// quartic itself ([`fall_back_to_the_quartic`]); what separates its check from `rms` is the
/// nodal values' own collocation residual (Newton stops at its precision floor, ∝ ε/h in the
/// rows' units of `z'`), which refinement raises instead of lowering: refining for it ran the
/// paper's whisker scan of the `vibrissa` crate at tol 1e-12, Lobatto6, into meshes of 13 770
/// nodes with intervals of 5e-8 and a Newton stall (its check grew 1.3e-12 → 1.6e-8 as the
/// intervals were halved, their `rms` 2e-15). NaN is never at the floor.
fn at_floor(rms: f64, check: f64, tol: f64) -> bool {
    check - rms > 0.5 * tol
}

/// Lobatto6: on every interval where the quintic's residual `check` exceeds `tol`, the returned
/// object becomes the collocation quartic itself (the quintic with the quartic's second
/// derivatives at the interval's ends), whose residual the error control met. The quintic is of
/// order 6 between nodes, the quartic of order 5, but in layers at tight tolerances the quintic's
/// residual can exceed the quartic's (Cash–Mazzia 3, 5, 6, 7, 11–14 at ε = 1e-4, tol 1e-8).
/// Returns whether any interval changed.
fn fall_back_to_the_quartic<P: Bvp + ?Sized>(
    cx: &Ctx<'_>,
    disc: &Disc<'_, P>,
    sol: &mut Solution,
    check: &[f64],
    tol: f64,
) -> bool {
    let n = cx.dims.n;
    let Dense::QuinticIntervals { d2z } = &mut sol.dense else {
        return false;
    };
    let mut changed = false;
    for (i, &r) in check.iter().enumerate() {
        if r > tol || r.is_nan() {
            disc.collocation_second_derivatives(i, &mut d2z[2 * i * n..2 * (i + 1) * n]);
            changed = true;
        }
    }
    changed
}
