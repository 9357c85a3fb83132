//! The quasi-static stiction scan (paper §3) by pseudo-arclength continuation in the foot
//! displacement `d`, and its inverse.

use crate::model::{Ends, Profile, RodBvp, ScanFamily, Uniform};
use crate::solve::{check_branch, extrema, shape_from, solve_with, Engine, SolverConfig};
use crate::{BranchChoice, Method, Model, Shape, ShapePoint, Target, VibrissaError};
use bvp::continuation::{Continuation, ContinuationOptions, FoldKind};
use bvp::Solution;
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

    fn continue_scan(
        &self,
        mut engine: Engine,
        start_sol: Solution,
        opts: &ScanOptions,
        grid: &[f64],
    ) -> Result<ScanResult, VibrissaError> {
        let d_end = opts.d_max;
        let copts = ContinuationOptions {
            ds: 0.05,
            ds_min: 1e-7,
            ds_max: 0.5,
            max_steps: 5000,
            lambda_min: -0.25,
            lambda_max: d_end,
            detect_folds: true,
            fold_tol: 1e-10,
            history: 8,
            ..ContinuationOptions::default()
        };
        let (start_point, start_shape) = self.point(&start_sol, 0.0);
        let mut stats = start_sol.stats.clone();
        let mut points = Vec::with_capacity(grid.len());
        let mut shapes = Vec::new();
        let keep = |shapes: &mut Vec<Vec<ShapePoint>>, sh: &Shape| {
            if let Some(ns) = opts.keep_shapes {
                shapes.push(sh.samples(ns));
            }
        };
        let mut gi = 0;
        while gi < grid.len() && grid[gi] <= 0.0 {
            points.push(start_point);
            keep(&mut shapes, &start_shape);
            gi += 1;
        }
        let w0 = self.watch(&start_sol, 0.0);
        let mut best = (w0.mu, 0.0);
        let mut hist: Vec<Watch> = vec![w0];
        let mut stop = StopReason::DMax;
        let mut cont = Continuation::new(&self.family, &mut engine, start_sol, 0.0, copts)
            .map_err(|e| VibrissaError::solver("scan continuation set-up", e))?;
        let _ = cont.next(); // the corrected start (already converged)
        let mut last_d = 0.0;
        let mut finished = false;
        while !finished {
            let bp = match cont.next() {
                None => break,
                Some(Err(e)) => {
                    stop = StopReason::SolverFailure {
                        d: last_d,
                        message: e.to_string(),
                    };
                    break;
                }
                Some(Ok(bp)) => bp,
            };
            stats.accumulate(&bp.stats);
            let d = bp.lambda;
            if let Some(fold) = &bp.fold {
                if fold.kind == FoldKind::Max {
                    stop = StopReason::FoldInD { d: fold.lambda };
                    break;
                }
            }
            if d <= last_d {
                stop = StopReason::FoldInD { d: last_d };
                break;
            }
            let w = self.watch(&bp.solution, d);
            let prev = *hist.last().unwrap_or(&w0);
            let mut d_stop = d;
            // penetration
            if w.pen > 0.0 && prev.pen <= 0.0 {
                match locate_root(&mut cont, self, prev.d, d, |w| w.pen) {
                    Ok((dp, wp)) => {
                        d_stop = dp;
                        if wp.mu > best.0 {
                            best = (wp.mu, dp);
                        }
                        stop = StopReason::Penetration {
                            d: dp,
                            s: wp.pen_s,
                            y: wp.pen_y,
                        };
                        finished = true;
                    }
                    Err(msg) => {
                        stop = StopReason::SolverFailure {
                            d: last_d,
                            message: msg,
                        };
                        break;
                    }
                }
            }
            // slip
            if let Some(mu0) = opts.mu0 {
                if w.mu >= mu0 && prev.mu < mu0 {
                    match locate_root(&mut cont, self, prev.d, d, |w| w.mu - mu0) {
                        Ok((ds, _)) => {
                            if ds <= d_stop {
                                d_stop = ds;
                                stop = StopReason::Slip { d: ds, mu: mu0 };
                                best = if mu0 > best.0 { (mu0, ds) } else { best };
                                finished = true;
                            }
                        }
                        Err(msg) => {
                            stop = StopReason::SolverFailure {
                                d: last_d,
                                message: msg,
                            };
                            break;
                        }
                    }
                }
            }
            // local maximum of μ at the previous point
            if hist.len() >= 2 {
                let pp = hist[hist.len() - 2];
                if prev.mu > pp.mu && prev.mu >= w.mu {
                    let hi = d.min(d_stop);
                    if let Ok((dm, mm)) = locate_max(&mut cont, self, pp.d, hi) {
                        if mm > best.0 {
                            best = (mm, dm);
                        }
                    }
                }
            }
            // output on the grid
            while gi < grid.len() && grid[gi] <= d_stop {
                let dg = grid[gi];
                let sol = if dg == d {
                    Ok(bp.solution.clone())
                } else {
                    cont.point_at(dg)
                };
                match sol {
                    Ok(sol) => {
                        stats.accumulate(&sol.stats);
                        let (p, sh) = self.point(&sol, dg);
                        points.push(p);
                        keep(&mut shapes, &sh);
                    }
                    Err(e) => {
                        stop = StopReason::SolverFailure {
                            d: dg,
                            message: format!("output point at d = {dg}: {e}"),
                        };
                        finished = true;
                        break;
                    }
                }
                gi += 1;
            }
            if finished {
                break;
            }
            let wl = Watch { d, ..w };
            if wl.mu > best.0 {
                best = (wl.mu, d);
            }
            hist.push(wl);
            if hist.len() > 3 {
                hist.remove(0);
            }
            last_d = d;
            if bp.on_bound {
                stop = StopReason::DMax;
                break;
            }
        }
        Ok(ScanResult {
            eta: self.family.eta,
            start: start_point,
            points,
            mu_max: best.0,
            d_at_mu_max: best.1,
            stop,
            stats,
            shapes,
        })
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

type Cont<'a, Pr> = Continuation<'a, ScanFamily<Pr>, &'a mut Engine>;

/// First `d` in `[a, b]` where `g(watch(d))` crosses 0 (g(a) <= 0 < g(b)), by Brent's method.
fn locate_root<Pr: Profile>(
    cont: &mut Cont<'_, Pr>,
    sc: &Scanner<'_, Pr>,
    a: f64,
    b: f64,
    g: impl Fn(&Watch) -> f64,
) -> Result<(f64, Watch), String> {
    let mut failure = None;
    let mut eval = |d: f64| -> Result<f64, elastica::ElasticaError> {
        match cont.point_at(d) {
            Ok(sol) => Ok(g(&sc.watch(&sol, d))),
            Err(e) => {
                failure = Some(format!("solve at d = {d}: {e}"));
                Err(elastica::ElasticaError::NotFinite {
                    name: "scan solve",
                    value: d,
                })
            }
        }
    };
    let r = elastica::roots::try_brent_root(&mut eval, a, b, 1e-13, 200);
    match r {
        Ok(d) => {
            let sol = cont.point_at(d).map_err(|e| e.to_string())?;
            Ok((d, sc.watch(&sol, d)))
        }
        Err(e) => Err(failure.unwrap_or_else(|| e.to_string())),
    }
}

/// Maximum of μ(d) on `[a, b]` by Brent's method: `(d, μ)`.
fn locate_max<Pr: Profile>(
    cont: &mut Cont<'_, Pr>,
    sc: &Scanner<'_, Pr>,
    a: f64,
    b: f64,
) -> Result<(f64, f64), String> {
    let mut eval = |d: f64| -> Result<f64, elastica::ElasticaError> {
        match cont.point_at(d) {
            Ok(sol) => Ok(sc.watch(&sol, d).mu),
            Err(_) => Err(elastica::ElasticaError::NotFinite {
                name: "scan solve",
                value: d,
            }),
        }
    };
    elastica::roots::try_brent_max(&mut eval, a, b, 1e-10, 200).map_err(|e| e.to_string())
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
