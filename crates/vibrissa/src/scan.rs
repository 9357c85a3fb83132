//! The quasi-static stiction scan (paper §3) by pseudo-arclength continuation in the foot
//! displacement `d`, and its inverse.

use crate::model::{Ends, Profile, RodBvp, ScanFamily, Uniform};
use crate::solve::{check_branch, extrema, shape_from, solve_with, Engine, SolverConfig};
use crate::{BranchChoice, Method, Model, Shape, ShapePoint, Target, VibrissaError};
use bvp::continuation::Fixed;
use bvp::continuation::{Continuation, ContinuationOptions, FoldKind};
use bvp::{BvpSolver, Guess, ParamBvp, Solution};
use serde::Serialize;
use std::fmt;

/// Options of [`scan`].
#[derive(Clone, Debug, PartialEq, Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ScanOptions {
    /// Largest foot displacement. Default 0.5.
    pub d_max: f64,
    /// Output points, uniformly on `[0, d_max]` (both included). Default 201.
    pub points: usize,
    /// Slip threshold μ0: the scan stops where μ reaches it. Default none.
    pub mu0: Option<f64>,
    /// Solver settings.
    pub solver: SolverConfig,
    /// `Some(n)`: keep each output point's shape sampled at `n` points.
    pub keep_shapes: Option<usize>,
}

impl Default for ScanOptions {
    fn default() -> Self {
        ScanOptions {
            d_max: 0.5,
            points: 201,
            mu0: None,
            solver: SolverConfig::default(),
            keep_shapes: None,
        }
    }
}

impl ScanOptions {
    /// Checks: `d_max ∈ (0, 2)`, `points ∈ [2, 1e6]`, `mu0 ≥ 0` finite, `keep_shapes ≥ 2`.
    pub fn validate(&self) -> Result<(), VibrissaError> {
        if !(self.d_max > 0.0 && self.d_max < 2.0) {
            return Err(VibrissaError::range("d_max", self.d_max, "(0, 2)"));
        }
        if !(2..=1_000_000).contains(&self.points) {
            return Err(VibrissaError::range(
                "points",
                self.points as f64,
                "[2, 1000000]",
            ));
        }
        if let Some(mu0) = self.mu0 {
            if !(mu0.is_finite() && mu0 >= 0.0) {
                return Err(VibrissaError::range("mu0", mu0, "[0, inf)"));
            }
        }
        if let Some(n) = self.keep_shapes {
            if !(2..=100_000).contains(&n) {
                return Err(VibrissaError::range("keep_shapes", n as f64, "[2, 100000]"));
            }
        }
        self.solver.validate()
    }
}

/// One point of the scan.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ScanPoint {
    /// Foot displacement.
    pub d: f64,
    /// Friction ratio the contact must supply, `tan(β − α)` (β: surface angle; `tan(−α)` flat).
    pub mu: f64,
    /// Force angle.
    pub alpha: f64,
    /// Tip slope.
    pub phi1: f64,
    /// Force magnitude.
    pub f: f64,
    /// `f·sin α`.
    pub fx: f64,
    /// `−f·cos α`.
    pub fy: f64,
    /// `m(0)` (the paper's clamp moment is `−m(0)`).
    pub m_base: f64,
    /// Number of flex points.
    pub flex: usize,
    /// Arc length of the first flex point.
    pub s_flex: Option<f64>,
    /// Maximum of `y(s)`.
    pub y_max: f64,
}

/// Why a scan stopped.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "reason", rename_all = "snake_case")]
pub enum StopReason {
    /// `d_max` reached.
    DMax,
    /// μ reached μ0 at `d`: the tip slips.
    Slip {
        /// Displacement.
        d: f64,
        /// μ there (= μ0).
        mu: f64,
    },
    /// The rod crosses the surface at arc length `s` (`y(s) = η` with `s < 1`, or the tip
    /// slope turns downwards at `s = 1`).
    Penetration {
        /// Displacement.
        d: f64,
        /// Arc length of the touching point.
        s: f64,
        /// Its height.
        y: f64,
    },
    /// `d` has a maximum along the solution curve: snap-through.
    FoldInD {
        /// Displacement at the fold.
        d: f64,
    },
    /// The solver failed.
    SolverFailure {
        /// Last displacement reached.
        d: f64,
        /// Diagnostics.
        message: String,
    },
}

impl fmt::Display for StopReason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            StopReason::DMax => write!(f, "d_max reached"),
            StopReason::Slip { d, mu } => write!(f, "slip at d = {d} (mu = {mu})"),
            StopReason::Penetration { d, s, y } => {
                write!(f, "penetration at d = {d} (s = {s}, y = {y})")
            }
            StopReason::FoldInD { d } => write!(f, "fold in d (snap-through) at d = {d}"),
            StopReason::SolverFailure { d, message } => {
                write!(f, "solver failure after d = {d}: {message}")
            }
        }
    }
}

/// Result of [`scan`].
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ScanResult {
    /// Surface height.
    pub eta: f64,
    /// The starting rod (d = 0).
    pub start: ScanPoint,
    /// Points at the requested displacements, up to where the scan stopped.
    pub points: Vec<ScanPoint>,
    /// Largest μ over the scan (located by a 1-D search, not the grid maximum).
    pub mu_max: f64,
    /// The d where it occurs: the upper end of the measurable range.
    pub d_at_mu_max: f64,
    /// Why the scan stopped.
    pub stop: StopReason,
    /// Accumulated solver statistics.
    pub stats: bvp::Stats,
    /// Shapes of the output points (if `keep_shapes`).
    pub shapes: Vec<Vec<ShapePoint>>,
}

/// Result of [`infer`].
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Inference {
    /// The stiction coefficient μ0 = μ(d0).
    pub mu0: f64,
    /// The displacement at which the tip slipped.
    pub d0: f64,
    /// The measurable range `[0, d at μ_max]`.
    pub measurable_d: (f64, f64),
    /// μ_max.
    pub mu_max: f64,
}

/// Runs the stiction scan. Errors only for invalid input or when it cannot even start;
/// failures along the way end the scan with [`StopReason::SolverFailure`].
///
/// Output points are at `d = i·d_max/(points − 1)`, `i = 0, …, points − 1`, up to the stop.
pub fn scan(model: &Model, opts: &ScanOptions) -> Result<ScanResult, VibrissaError> {
    opts.validate()?;
    let n = opts.points;
    let grid: Vec<f64> = (0..n)
        .map(|i| {
            if i + 1 == n {
                opts.d_max
            } else {
                opts.d_max * i as f64 / (n - 1) as f64
            }
        })
        .collect();
    scan_impl(model, opts, &grid)
}

/// As [`scan`], with output points at the given displacements (sorted ascending, in
/// `[0, d_max]`) instead of the uniform grid; `opts.points` is ignored.
pub fn scan_at(model: &Model, opts: &ScanOptions, d: &[f64]) -> Result<ScanResult, VibrissaError> {
    opts.validate()?;
    for (i, &di) in d.iter().enumerate() {
        if !(di >= 0.0 && di <= opts.d_max) {
            return Err(VibrissaError::range(
                format!("d[{i}]"),
                di,
                format!("[0, d_max] = [0, {}]", opts.d_max),
            ));
        }
        if i > 0 && di < d[i - 1] {
            return Err(VibrissaError::range(
                format!("d[{i}]"),
                di,
                format!("[d[{}], d_max] (sorted ascending)", i - 1),
            ));
        }
    }
    scan_impl(model, opts, d)
}

fn scan_impl(model: &Model, opts: &ScanOptions, grid: &[f64]) -> Result<ScanResult, VibrissaError> {
    if opts.solver.method == Method::Analytic {
        return crate::analytic::scan_analytic(model, opts, grid);
    }
    let c = model.scene().support_compliance;
    if model.has_uniform_profile() && c == 0.0 {
        Scanner::run(model, Uniform, opts, grid)
    } else {
        Scanner::run(model, model.profile(1.0), opts, grid)
    }
}

/// Per-solution quantities the scan watches.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Watch {
    d: f64,
    pub(crate) mu: f64,
    /// > 0: the rod is above the surface somewhere with s < 1.
    pub(crate) pen: f64,
    pen_s: f64,
    pen_y: f64,
}

pub(crate) struct Scanner<'m, Pr: Profile> {
    model: &'m Model,
    pub(crate) family: ScanFamily<Pr>,
    pub(crate) beta: f64,
}

impl<'m, Pr: Profile> Scanner<'m, Pr> {
    pub(crate) fn watch(&self, sol: &Solution, d: f64) -> Watch {
        let (sb, cb) = self.beta.sin_cos();
        let alpha = sol.params[1];
        let mu = (self.beta - alpha).tan();
        // height above the surface line through the contact point (x* − d, η)
        let x1 = self.family.x_star - d;
        let ex = extrema(sol, -sb, cb);
        let h0 = -sb * x1 + cb * self.family.eta;
        let interior = ex.interior - h0;
        let phi1 = sol.right()[2];
        // tip slope turned below the surface line: the points just before the tip are above it
        let tip = -(phi1 - self.beta).sin();
        let (pen, pen_s) = if interior > tip {
            (interior, ex.s_interior)
        } else {
            (tip, 1.0)
        };
        let mut z = [0.0; 4];
        sol.eval(pen_s, &mut z);
        Watch {
            d,
            mu,
            pen,
            pen_s,
            pen_y: z[1],
        }
    }

    pub(crate) fn point(&self, sol: &Solution, d: f64) -> (ScanPoint, Shape) {
        let shape = shape_from(sol.clone(), &self.family.rod, self.model.profile(1.0));
        let w = self.watch(sol, d);
        (
            ScanPoint {
                d,
                mu: w.mu,
                alpha: shape.alpha,
                phi1: shape.phi1,
                f: shape.f,
                fx: shape.fx,
                fy: shape.fy,
                m_base: shape.m_base,
                flex: shape.flex,
                s_flex: shape.s_flex,
                y_max: shape.y_max,
            },
            shape,
        )
    }

    fn run(
        model: &'m Model,
        profile: Pr,
        opts: &ScanOptions,
        grid: &[f64],
    ) -> Result<ScanResult, VibrissaError> {
        let scene = model.scene();
        let (eta, beta) = (scene.eta, scene.surface_angle);
        let mut engine = Engine::new(&opts.solver)?;
        let start = solve_with(
            model,
            profile.clone(),
            &mut engine,
            beta,
            Target::Eta(eta),
            &BranchChoice::Convex,
        )
        .map_err(|e| context(e, "scan start (alpha = surface angle, y(1) = eta, convex)"))?;
        check_branch(&start, &BranchChoice::Convex)?;
        let mut start_sol = start
            .solution()
            .cloned()
            .ok_or(VibrissaError::NotImplemented("analytic start"))?;
        start_sol.params = vec![start.f, start.alpha];
        let scanner = Scanner {
            model,
            family: ScanFamily {
                rod: RodBvp {
                    profile,
                    compliance: scene.support_compliance,
                    alpha: beta,
                    ends: Ends::Tip {
                        x1: start.x1,
                        y1: eta,
                    },
                },
                eta,
                x_star: start.x1,
            },
            beta,
        };
        // uniform clamped rod, single shooting: the specialized path (falls back to this one)
        if opts.solver.method == Method::Shooting && opts.solver.rk4_steps.is_none() {
            if let Some(r) = crate::fast::scan_uniform(&scanner, &start_sol, opts, grid) {
                return Ok(r);
            }
        }
        scanner.continue_scan(engine, start_sol, opts, grid)
    }

    /// The generic scan: natural continuation in `d` from grid point to grid point (with
    /// intermediate steps where the grid is coarse), warm-started by quadratic extrapolation of
    /// the last three points, so every output point is a continuation point and needs one or two
    /// Newton iterations. Pseudo-arclength continuation (crate `bvp`) takes over only where the
    /// natural step fails, to pass or locate a fold in `d`. Every point, the start included, is
    /// watched for penetration and slip; crossings are located by Brent's method.
    fn continue_scan(
        &self,
        mut engine: Engine,
        start_sol: Solution,
        opts: &ScanOptions,
        grid: &[f64],
    ) -> Result<ScanResult, VibrissaError> {
        let d_end = opts.d_max;
        let mut m = March {
            sc: self,
            engine: &mut engine,
            hist: Vec::with_capacity(4),
            stats: start_sol.stats.clone(),
        };
        let sol0 = m
            .solve(0.0, &Guess::from(&start_sol))
            .map_err(|e| VibrissaError::solver("scan start (correction at d = 0)", e))?;
        let (start_point, _) = self.point(&sol0, 0.0);
        let mut out = Output {
            points: Vec::with_capacity(grid.len()),
            shapes: Vec::new(),
            keep: opts.keep_shapes,
            gi: 0,
        };
        let w0 = self.watch(&sol0, 0.0);
        m.push(0.0, sol0);
        let mut best = (w0.mu, 0.0);
        // the start itself may already be through the surface
        if w0.pen > 0.0 {
            let stop = StopReason::Penetration {
                d: 0.0,
                s: w0.pen_s,
                y: w0.pen_y,
            };
            let stop = out.emit(&mut m, grid, 0.0).err().unwrap_or(stop);
            return Ok(m.finish(start_point, out, best, stop));
        }
        if let Some(mu0) = opts.mu0 {
            if w0.mu >= mu0 {
                let stop = StopReason::Slip { d: 0.0, mu: w0.mu };
                let stop = out.emit(&mut m, grid, 0.0).err().unwrap_or(stop);
                return Ok(m.finish(start_point, out, best, stop));
            }
        }
        let mut prev = w0;
        let mut pprev: Option<Watch> = None;
        let mut h: f64 = 0.01_f64.min(d_end);
        let h_max = 0.05_f64.min(d_end);
        let h_min = 1e-7;
        let mut solves = 0usize;
        let stop = loop {
            let d = prev.d;
            if d >= d_end {
                if let Err(fail) = out.emit(&mut m, grid, d_end) {
                    break fail;
                }
                break StopReason::DMax;
            }
            solves += 1;
            if solves > 100_000 {
                break StopReason::SolverFailure {
                    d,
                    message: "more than 100000 continuation steps".into(),
                };
            }
            // next target: at most h ahead, never past the next grid point
            let mut target = (d + h).min(d_end);
            if let Some(&g) = grid.get(out.gi) {
                if g > d && g < target {
                    target = g;
                }
            }
            if d_end - target < 1e-3 * h {
                target = d_end;
            }
            let step = m.step_to(target);
            let (dn, sol) = match step {
                Ok((sol, iters)) => {
                    h = if iters <= 2 {
                        (2.0 * h).min(h_max)
                    } else if iters <= 4 {
                        (1.25 * h).min(h_max)
                    } else {
                        0.5 * h
                    };
                    (target, sol)
                }
                Err(_) if h > h_min => {
                    h *= 0.25;
                    continue;
                }
                Err(e) => {
                    // the natural step failed for tiny steps: a fold, or a hard point; pass it
                    // (or locate the fold) by pseudo-arclength continuation
                    match m.arclength_past(d, target, d_end) {
                        Passed::Beyond(dn, sol) => (dn, sol),
                        Passed::Fold(df) => break StopReason::FoldInD { d: df },
                        Passed::Failed(msg) => {
                            break StopReason::SolverFailure {
                                d,
                                message: format!("natural step to d = {target}: {e}; {msg}"),
                            }
                        }
                    }
                }
            };
            let w = self.watch(&sol, dn);
            m.push(dn, sol);
            // events between d and dn, each located by Brent's method
            let mut event: Option<(f64, StopReason)> = None;
            if w.pen > 0.0 {
                event = Some(match m.locate_root(d, dn, |w| w.pen) {
                    Ok((dp, wp)) => (
                        dp,
                        StopReason::Penetration {
                            d: dp,
                            s: wp.pen_s,
                            y: wp.pen_y,
                        },
                    ),
                    Err(msg) => (
                        d,
                        StopReason::SolverFailure {
                            d,
                            message: format!("locating the penetration: {msg}"),
                        },
                    ),
                });
            }
            if let Some(mu0) = opts.mu0 {
                if w.mu >= mu0 {
                    let e = match m.locate_root(d, dn, |w| w.mu - mu0) {
                        Ok((ds, _)) => (ds, StopReason::Slip { d: ds, mu: mu0 }),
                        Err(msg) => (
                            d,
                            StopReason::SolverFailure {
                                d,
                                message: format!("locating the slip: {msg}"),
                            },
                        ),
                    };
                    if event.as_ref().is_none_or(|(de, _)| e.0 < *de) {
                        event = Some(e);
                    }
                }
            }
            let d_stop = event.as_ref().map_or(dn, |e| e.0);
            // μ at the stop point counts (it is often the largest, e.g. at penetration)
            if event.is_some() && d_stop > d {
                if let Ok(sol) = m.solve_within(d_stop) {
                    let mu = self.watch(&sol, d_stop).mu;
                    if mu > best.0 {
                        best = (mu, d_stop);
                    }
                }
            }
            // a local maximum of μ at the previous point
            if let Some(pp) = pprev {
                if prev.mu > pp.mu && prev.mu >= w.mu {
                    if let Ok((dm, mm)) = m.locate_max(pp.d, dn.min(d_stop)) {
                        if mm > best.0 {
                            best = (mm, dm);
                        }
                    }
                }
            }
            if w.mu > best.0 && dn <= d_stop {
                best = (w.mu, dn);
            }
            if let Err(fail) = out.emit(&mut m, grid, d_stop) {
                break fail;
            }
            if let Some((_, reason)) = event {
                break reason;
            }
            pprev = Some(prev);
            prev = w;
        };
        Ok(m.finish(start_point, out, best, stop))
    }
}

/// Output points on the grid, filled as the scan passes them.
struct Output {
    points: Vec<ScanPoint>,
    shapes: Vec<Vec<ShapePoint>>,
    keep: Option<usize>,
    gi: usize,
}

impl Output {
    /// Emits the grid points up to `upto` (the exact continuation point where one is at the grid
    /// value, else a solve warm-started from the branch). A point that cannot be solved ends the
    /// scan with [`StopReason::SolverFailure`] at that `d`.
    fn emit<Pr: Profile>(
        &mut self,
        m: &mut March<'_, '_, '_, Pr>,
        grid: &[f64],
        upto: f64,
    ) -> Result<(), StopReason> {
        while let Some(&dg) = grid.get(self.gi) {
            if dg > upto {
                break;
            }
            let sol = match m.hist.iter().rev().find(|(d, _)| *d == dg) {
                Some((_, s)) => Ok(s.clone()),
                None => m.solve_within(dg),
            };
            let sol = sol.map_err(|e| StopReason::SolverFailure {
                d: dg,
                message: format!("output point at d = {dg}: {e}"),
            })?;
            let (p, sh) = m.sc.point(&sol, dg);
            self.points.push(p);
            if let Some(ns) = self.keep {
                self.shapes.push(sh.samples(ns));
            }
            self.gi += 1;
        }
        Ok(())
    }
}

/// Result of the pseudo-arclength fallback.
enum Passed {
    /// The branch continues beyond the failed step: a point on it.
    Beyond(f64, Solution),
    /// `d` has a maximum along the branch here.
    Fold(f64),
    /// Neither.
    Failed(String),
}

/// The marching state: solver, the last points of the branch.
struct March<'s, 'm, 'e, Pr: Profile> {
    sc: &'s Scanner<'m, Pr>,
    engine: &'e mut Engine,
    hist: Vec<(f64, Solution)>,
    stats: bvp::Stats,
}

// the solver's own error, passed through unboxed as crate `bvp` returns it
#[allow(clippy::result_large_err)]
impl<Pr: Profile> March<'_, '_, '_, Pr> {
    fn solve(&mut self, d: f64, guess: &Guess) -> Result<Solution, bvp::BvpError> {
        let r = self.engine.solve(&Fixed::new(&self.sc.family, d), guess);
        match &r {
            Ok(s) => self.stats.accumulate(&s.stats),
            Err(e) => {
                if let Some(st) = e.stats() {
                    self.stats.accumulate(st);
                }
            }
        }
        r
    }

    fn push(&mut self, d: f64, sol: Solution) {
        if self.hist.len() == 3 {
            self.hist.remove(0);
        }
        self.hist.push((d, sol));
    }

    /// Lagrange inter-/extrapolation in `d` of the kept points (at most the `k` nearest in `d`),
    /// on the mesh of the newest one.
    fn guess_at(&self, d: f64, k: usize) -> Guess {
        let mut idx: Vec<usize> = (0..self.hist.len()).collect();
        idx.sort_by(|&a, &b| {
            (self.hist[a].0 - d)
                .abs()
                .total_cmp(&(self.hist[b].0 - d).abs())
        });
        idx.truncate(k.max(1));
        let newest = &self.hist[self.hist.len() - 1].1;
        let w: Vec<f64> = idx
            .iter()
            .map(|&i| {
                idx.iter()
                    .filter(|&&j| j != i)
                    .map(|&j| (d - self.hist[j].0) / (self.hist[i].0 - self.hist[j].0))
                    .product()
            })
            .collect();
        let n = newest.n;
        let mesh = newest.mesh.clone();
        let mut z = vec![0.0; n * mesh.len()];
        let mut buf = vec![0.0; n];
        for (&i, &wi) in idx.iter().zip(&w) {
            let sol = &self.hist[i].1;
            for (node, &s) in mesh.iter().enumerate() {
                sol.eval(s, &mut buf);
                for j in 0..n {
                    z[node * n + j] += wi * buf[j];
                }
            }
        }
        let mut params = vec![0.0; newest.params.len()];
        for (&i, &wi) in idx.iter().zip(&w) {
            for (p, &q) in params.iter_mut().zip(&self.hist[i].1.params) {
                *p += wi * q;
            }
        }
        let mut dz = vec![0.0; z.len()];
        for (node, &s) in mesh.iter().enumerate() {
            self.sc.family.rhs(
                s,
                &z[node * n..(node + 1) * n],
                &params,
                d,
                &mut dz[node * n..(node + 1) * n],
            );
        }
        Guess {
            n,
            mesh,
            z,
            dz: Some(dz),
            params,
        }
    }

    /// A natural step to `d` from the extrapolated guess; rejected when the corrector lands far
    /// from the prediction (another branch across a fold) relative to the last step.
    fn step_to(&mut self, d: f64) -> Result<(Solution, usize), bvp::BvpError> {
        let g = self.guess_at(d, 3);
        let sol = self.solve(d, &g)?;
        let (dl, last) = {
            let (dl, s) = &self.hist[self.hist.len() - 1];
            (*dl, s)
        };
        let u = |s: &Solution| [s.left()[3], s.params[0], s.params[1]];
        let (un, ul, ug) = (u(&sol), u(last), [g.z[3], g.params[0], g.params[1]]);
        // the correction must be small against the change over the step
        let mut corr: f64 = 0.0;
        let mut change: f64 = 0.0;
        for i in 0..3 {
            corr = corr.max((un[i] - ug[i]).abs());
            change = change.max((un[i] - ul[i]).abs());
        }
        let scale = 1.0 + un.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        if !(corr <= 0.5 * change.max(1e-3 * scale * (d - dl).abs().min(1.0))
            || corr < 1e-9 * scale)
        {
            return Err(bvp::BvpError::Stalled {
                iteration: sol.stats.newton_iters,
                residual: corr,
                stats: bvp::Stats::default(),
            });
        }
        let it = sol.stats.newton_iters;
        Ok((sol, it))
    }

    /// A solve at `d` inside the span of the kept points (interpolated guess).
    fn solve_within(&mut self, d: f64) -> Result<Solution, bvp::BvpError> {
        let g = self.guess_at(d, 3);
        self.solve(d, &g)
    }

    /// First `d` in `[a, b]` where `g(watch(d))` crosses 0 (g(a) <= 0 < g(b)), by Brent's method.
    fn locate_root(
        &mut self,
        a: f64,
        b: f64,
        g: impl Fn(&Watch) -> f64,
    ) -> Result<(f64, Watch), String> {
        let mut failure = None;
        let r = elastica::roots::try_brent_root(
            |d| match self.solve_within(d) {
                Ok(sol) => Ok(g(&self.sc.watch(&sol, d))),
                Err(e) => {
                    failure = Some(format!("solve at d = {d}: {e}"));
                    Err(elastica::ElasticaError::NotFinite {
                        name: "scan solve",
                        value: d,
                    })
                }
            },
            a,
            b,
            1e-13,
            200,
        );
        match r {
            Ok(d) => {
                let sol = self.solve_within(d).map_err(|e| e.to_string())?;
                Ok((d, self.sc.watch(&sol, d)))
            }
            Err(e) => Err(failure.unwrap_or_else(|| e.to_string())),
        }
    }

    /// Maximum of μ(d) on `[a, b]` by Brent's method: `(d, μ)`.
    fn locate_max(&mut self, a: f64, b: f64) -> Result<(f64, f64), String> {
        elastica::roots::try_brent_max(
            |d| match self.solve_within(d) {
                Ok(sol) => Ok(self.sc.watch(&sol, d).mu),
                Err(_) => Err(elastica::ElasticaError::NotFinite {
                    name: "scan solve",
                    value: d,
                }),
            },
            a,
            b,
            1e-10,
            200,
        )
        .map_err(|e| e.to_string())
    }

    /// Pseudo-arclength continuation from the last point (at `d`) until the branch passes
    /// `target` (natural steps resume there) or turns back in `d` (a fold).
    fn arclength_past(&mut self, d: f64, target: f64, d_end: f64) -> Passed {
        let copts = ContinuationOptions {
            ds: 1e-3,
            ds_min: 1e-9,
            ds_max: 0.05,
            max_steps: 2000,
            lambda_min: -0.25,
            lambda_max: d_end,
            detect_folds: true,
            fold_tol: 1e-10,
            history: 4,
            ..ContinuationOptions::default()
        };
        let start = self.hist[self.hist.len() - 1].1.clone();
        let mut stats = bvp::Stats::default();
        let result = (|| {
            let mut cont =
                match Continuation::new(&self.sc.family, &mut *self.engine, start, d, copts) {
                    Ok(c) => c,
                    Err(e) => return Passed::Failed(e.to_string()),
                };
            let _ = cont.next(); // the start, already converged
            let mut last = d;
            for item in cont.by_ref() {
                let bp = match item {
                    Ok(bp) => bp,
                    Err(e) => return Passed::Failed(format!("pseudo-arclength: {e}")),
                };
                stats.accumulate(&bp.stats);
                if let Some(f) = &bp.fold {
                    if f.kind == FoldKind::Max {
                        return Passed::Fold(f.lambda);
                    }
                }
                if bp.lambda < last {
                    return Passed::Fold(last);
                }
                last = bp.lambda;
                if bp.lambda > target || bp.on_bound {
                    return Passed::Beyond(bp.lambda, bp.solution);
                }
            }
            Passed::Failed(format!(
                "pseudo-arclength continuation did not pass d = {target} (last d = {last})"
            ))
        })();
        self.stats.accumulate(&stats);
        result
    }

    fn finish(
        self,
        start: ScanPoint,
        out: Output,
        best: (f64, f64),
        stop: StopReason,
    ) -> ScanResult {
        ScanResult {
            eta: self.sc.family.eta,
            start,
            points: out.points,
            mu_max: best.0,
            d_at_mu_max: best.1,
            stop,
            stats: self.stats,
            shapes: out.shapes,
        }
    }
}

fn context(e: VibrissaError, what: &str) -> VibrissaError {
    match e {
        VibrissaError::Solver { context, source } => VibrissaError::Solver {
            context: format!("{what}: {context}"),
            source,
        },
        other => other,
    }
}

/// Infers μ0 from the displacement `d0` at which the tip slipped: μ0 = μ(d0) for `d0` in the
/// measurable range `[0, d at μ_max]` (beyond it μ decreases, so a slip there is ambiguous).
pub fn infer(model: &Model, d0: f64, opts: &ScanOptions) -> Result<Inference, VibrissaError> {
    opts.validate()?;
    if !d0.is_finite() || d0 < 0.0 {
        return Err(VibrissaError::NotMeasurable {
            d0,
            min: 0.0,
            max: f64::NAN,
        });
    }
    let o = ScanOptions {
        mu0: None,
        keep_shapes: None,
        ..opts.clone()
    };
    let probe = scan_at(model, &o, &[])?;
    let max = probe.d_at_mu_max;
    if d0 > max {
        return Err(VibrissaError::NotMeasurable { d0, min: 0.0, max });
    }
    let at = scan_at(model, &o, &[d0])?;
    let p = at
        .points
        .first()
        .ok_or_else(|| VibrissaError::NoConvergence {
            what: format!("scan to d0 = {d0}"),
            reason: at.stop.to_string(),
        })?;
    Ok(Inference {
        mu0: p.mu,
        d0,
        measurable_d: (0.0, max),
        mu_max: probe.mu_max,
    })
}
