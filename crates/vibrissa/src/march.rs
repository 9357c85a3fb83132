//! The scan's one march in the foot displacement `d`, for every rod and every method.
//!
//! Natural continuation from output point to output point (intermediate steps where the grid is
//! coarse), each point predicted from the last ones and corrected by a [`Stepper`]; where a
//! natural step fails for tiny steps (near a fold in `d`) the stepper's pseudo-arclength
//! continuation passes it or locates the fold. After every step the events between the last point
//! and the new one are located by Brent's method on solves inside that step (no restart):
//! penetration, lift-off (`N = 0`), slip (`|μ| = μ0`, either sign); the earliest ends the scan and
//! is written as the last point with its [`Event`]. The first maximum of `|μ|` (the end of the
//! measurable range) is located on the way, by the root of `d|μ|/dd` from exact tangents where the
//! stepper has them, else by Brent's maximizer.

use crate::profile::Profile;
use crate::report::{Event, RangeEnd, ScanOptions, ScanPoint, ScanResult, StopReason};
use crate::sampling::{clearance, extrema, flex_and_reversals};
use crate::search;
use crate::shape::{shape_from, ShapePoint};
use bvp::{Solution, Stats};

/// A converged point of the branch.
#[derive(Clone, Debug)]
pub(crate) struct Pt {
    /// Foot displacement.
    pub d: f64,
    /// `(m(0), f, α)`.
    pub u: [f64; 3],
    /// Exact tangent `du/dd`, where the stepper has one.
    pub du: Option<[f64; 3]>,
    /// `det ∂R/∂u` (its sign changes at a fold in `d`), where the stepper has it.
    pub det: Option<f64>,
    /// Newton iterations it took.
    pub iters: usize,
    /// The rod (`params = [f, α]`).
    pub sol: Solution,
}

/// Result of the pseudo-arclength fallback.
pub(crate) enum Passed {
    /// The branch continues beyond the failed step: a point on it.
    Beyond(Pt),
    /// `d` has a maximum along the branch here (with the rod there, if it was found).
    Fold(f64, Option<Solution>),
    /// Neither.
    Failed(String),
}

/// Why a correction was refused.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum StepError {
    /// The corrector landed across a fold in `d` (`det J` changed sign): the fold is within the
    /// step, pass or locate it by pseudo-arclength rather than by shorter natural steps.
    CrossedFold,
    /// Anything else (a shorter step may succeed).
    Failed(String),
}

impl std::fmt::Display for StepError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            StepError::CrossedFold => f.write_str("the corrector crossed a fold in d"),
            StepError::Failed(m) => f.write_str(m),
        }
    }
}

impl From<String> for StepError {
    fn from(m: String) -> Self {
        StepError::Failed(m)
    }
}

impl From<StepError> for String {
    fn from(e: StepError) -> Self {
        e.to_string()
    }
}

/// Prediction and correction of branch points (the method-specific part of the scan).
pub(crate) trait Stepper {
    /// The point at `d` from the history `hist` (newest last; `d` ahead of it or inside its span).
    /// Rejects corrections that land on another branch.
    fn correct(&mut self, d: f64, hist: &[Pt]) -> Result<Pt, StepError>;
    /// Pseudo-arclength continuation from the newest point until the branch passes `target` or
    /// turns back in `d`.
    fn pass_fold(&mut self, hist: &[Pt], target: f64, d_end: f64) -> Passed;
    /// Work done so far.
    fn stats(&self) -> Stats;
    /// Largest natural step in `d`.
    fn h_max(&self) -> f64;
    /// The branch between the points of `hist` as a polynomial in `d` (from their exact tangents):
    /// `(u, du/dd)` at `d`, where the stepper has one.
    fn interpolant(&self, _hist: &[Pt], _d: f64) -> Option<([f64; 3], [f64; 3])> {
        None
    }
}

/// The contact seen from the rod's foot: tip fixed at `(x* − d, η)`, surface angle β.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Contact {
    pub eta: f64,
    pub beta: f64,
    pub x_star: f64,
}

/// Per-point quantities the scan watches.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Watch {
    pub d: f64,
    /// Signed friction ratio `tan(β − α)`.
    pub mu: f64,
    /// Normal force `f cos(α − β)`.
    pub normal: f64,
    /// > 0: the rod is above the surface somewhere with s < 1 (or its tip turns into it).
    pub pen: f64,
    pub pen_s: f64,
    pub pen_y: f64,
    /// Sign-carrying slope of `|μ|` in `d` (from the exact tangent), if known.
    pub dmu_abs: Option<f64>,
}

impl Contact {
    /// `(μ, N, d|μ|/dd)` of the unknowns `u = (m(0), f, α)` and their tangent `du/dd`.
    fn of_u(&self, u: &[f64; 3], du: Option<&[f64; 3]>) -> (f64, f64, Option<f64>) {
        let (f, alpha) = (u[1], u[2]);
        let mu = (self.beta - alpha).tan();
        let normal = f * (alpha - self.beta).cos();
        // d|μ|/dd = sign(μ)·dμ/dd, dμ/dd = −sec²(β − α)·α'; at μ = 0 it is |dμ/dd|
        let dmu_abs = du.map(|du| {
            let dmu = -du[2] / (self.beta - alpha).cos().powi(2);
            if mu == 0.0 {
                dmu.abs()
            } else {
                mu.signum() * dmu
            }
        });
        (mu, normal, dmu_abs)
    }

    pub fn watch(&self, p: &Pt) -> Watch {
        let (mu, normal, dmu_abs) = self.of_u(&p.u, p.du.as_ref());
        let (pen, pen_s) = clearance(&p.sol, self.beta).excess();
        let mut z = [0.0; 4];
        p.sol.eval(pen_s, &mut z);
        Watch {
            d: p.d,
            mu,
            normal,
            pen,
            pen_s,
            pen_y: z[1],
            dmu_abs,
        }
    }
}

/// A function along the branch that is negative before an event and reaches 0 at it.
#[derive(Clone, Copy, Debug)]
enum Crossing {
    /// The rod rises above the surface line.
    Penetration,
    /// The normal force falls to 0.
    LiftOff,
    /// `|μ|` reaches μ0.
    Slip(f64),
    /// `|μ|` stops rising (its first maximum).
    MuMax,
}

impl Crossing {
    fn of_watch(self, w: &Watch) -> f64 {
        match self {
            Crossing::Penetration => w.pen,
            Crossing::LiftOff => -w.normal,
            Crossing::Slip(mu0) => w.mu.abs() - mu0,
            Crossing::MuMax => -w.dmu_abs.unwrap_or(f64::NAN),
        }
    }
    /// The value from the unknowns alone (`None` for penetration, which needs the shape).
    fn of_u(self, c: &Contact, u: &[f64; 3], du: &[f64; 3]) -> Option<f64> {
        let (mu, normal, dmu_abs) = c.of_u(u, Some(du));
        match self {
            Crossing::Penetration => None,
            Crossing::LiftOff => Some(-normal),
            Crossing::Slip(mu0) => Some(mu.abs() - mu0),
            Crossing::MuMax => dmu_abs.map(|v| -v),
        }
    }
}

/// The first maximum of `|μ|`: `(|μ|, μ, d)` and what ended the range, once known.
struct RangeTracker {
    best: (f64, f64, f64),
    end: Option<RangeEnd>,
}

impl RangeTracker {
    fn see(&mut self, w: &Watch) {
        if self.end.is_none() && w.mu.abs() >= self.best.0 {
            self.best = (w.mu.abs(), w.mu, w.d);
        }
    }
    fn close(&mut self, end: RangeEnd) {
        if self.end.is_none() {
            self.end = Some(end);
        }
    }
}

/// Runs the march from the start point `p0` (d = 0) over `grid` (sorted, in `[0, d_max]`).
pub(crate) fn march<P: Profile>(
    stepper: &mut dyn Stepper,
    ctx: &Ctx<'_, P>,
    grid: &[f64],
    p0: Pt,
    mut stats: Stats,
) -> ScanResult {
    let (contact, profile, opts) = (ctx.contact, ctx.profile, ctx.opts);
    let d_end = opts.d_max;
    let mut out = Output {
        points: Vec::with_capacity(grid.len() + 1),
        shapes: Vec::new(),
        keep: opts.keep_shapes,
        gi: 0,
    };
    let w0 = contact.watch(&p0);
    let start = scan_point(&p0, &w0, profile, None);
    let mut range = RangeTracker {
        best: (w0.mu.abs(), w0.mu, 0.0),
        end: None,
    };
    let mut hist: Vec<Pt> = vec![p0];
    // events at the start itself
    let start_event = if w0.pen > 0.0 {
        Some(Event::Penetration)
    } else if w0.normal <= 0.0 {
        Some(Event::LiftOff)
    } else if opts.mu0.is_some_and(|m| w0.mu.abs() >= m) {
        Some(Event::Slip)
    } else {
        None
    };
    let stop = if let Some(ev) = start_event {
        // the start itself is not a valid state (the rod crosses the surface, is pulled, or
        // slips): it is reported as the event, never as a grid row
        range.close(RangeEnd::Event);
        out.event(ctx, &hist[0], &w0, ev);
        stop_reason(ev, &w0)
    } else {
        run(stepper, ctx, &mut hist, &mut out, &mut range, grid, d_end)
    };
    stats.accumulate(&stepper.stats());
    if let Some(last) = hist.last() {
        stats.residual = last.sol.stats.residual;
        stats.nodes = last.sol.mesh.len();
    }
    let (mu_max, mu_at_max, d_at_mu_max) = range.best;
    ScanResult {
        eta: contact.eta,
        start,
        points: out.points,
        mu_max,
        mu_at_max,
        d_at_mu_max,
        range_end: range.end.unwrap_or(RangeEnd::SolverFailure),
        stop,
        stats,
        shapes: out.shapes,
    }
}

/// What the march needs besides the stepper: the contact, the rod's profile (as the stepper's
/// type, and as the general one kept in shapes), the options.
pub(crate) struct Ctx<'a, P: Profile> {
    pub contact: Contact,
    pub profile: &'a P,
    pub general: &'a crate::profile::General,
    pub opts: &'a ScanOptions,
}

fn stop_reason(ev: Event, w: &Watch) -> StopReason {
    match ev {
        Event::Slip => StopReason::Slip { d: w.d, mu: w.mu },
        Event::LiftOff => StopReason::LiftOff { d: w.d },
        Event::Penetration => StopReason::Penetration {
            d: w.d,
            s: w.pen_s,
            y: w.pen_y,
        },
        Event::FoldInD => StopReason::FoldInD { d: w.d },
    }
}

/// The march proper; returns why it stopped.
fn run<P: Profile>(
    stepper: &mut dyn Stepper,
    ctx: &Ctx<'_, P>,
    hist: &mut Vec<Pt>,
    out: &mut Output,
    range: &mut RangeTracker,
    grid: &[f64],
    d_end: f64,
) -> StopReason {
    let h_max = stepper.h_max().min(d_end);
    let mut h: f64 = 0.01_f64.min(h_max);
    let h_min = 1e-7;
    let mut steps = 0usize;
    let mut prev = ctx.contact.watch(&hist[0]);
    let mut pprev: Option<Watch> = None;
    loop {
        let d = prev.d;
        if d >= d_end {
            range.close(RangeEnd::DMax);
            if let Err(fail) = out.emit(stepper, ctx, hist, grid, d_end) {
                return fail;
            }
            return StopReason::DMax;
        }
        steps += 1;
        if steps > 100_000 {
            range.close(RangeEnd::SolverFailure);
            return StopReason::SolverFailure {
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
        // a slip the predictor sees coming within the step: step to just past it (the event
        // is then located on a short step, and the scan pays no full step beyond it)
        if let Some(mu0) = ctx.opts.mu0 {
            if let Some(ds) = predicted_crossing(stepper, ctx, hist, d, target, Crossing::Slip(mu0))
            {
                target = ds + 1e-6 * (target - ds);
            }
        }
        let p = match stepper.correct(target, hist) {
            Ok(p) => {
                h = if p.iters <= 2 {
                    (2.0 * h).min(h_max)
                } else if p.iters <= 4 {
                    (1.25 * h).min(h_max)
                } else {
                    0.5 * h
                };
                p
            }
            Err(StepError::Failed(_)) if h > h_min => {
                h *= 0.25;
                continue;
            }
            Err(e) => match stepper.pass_fold(hist, target, d_end) {
                Passed::Beyond(p) => p,
                Passed::Fold(df, sol) => {
                    range.close(RangeEnd::Event);
                    if let Err(fail) = out.emit(stepper, ctx, hist, grid, df.min(d_end)) {
                        return fail;
                    }
                    if let Some(sol) = sol {
                        let p = Pt {
                            d: df,
                            u: [sol.left()[3], sol.params[0], sol.params[1]],
                            du: None,
                            det: None,
                            iters: 0,
                            sol,
                        };
                        let w = ctx.contact.watch(&p);
                        range.see(&w);
                        out.event(ctx, &p, &w, Event::FoldInD);
                    }
                    return StopReason::FoldInD { d: df };
                }
                Passed::Failed(msg) => {
                    range.close(RangeEnd::SolverFailure);
                    return StopReason::SolverFailure {
                        d,
                        message: format!("natural step to d = {target}: {e}; {msg}"),
                    };
                }
            },
        };
        let w = ctx.contact.watch(&p);
        hist.push(p);
        if hist.len() > 4 {
            hist.remove(0);
        }
        // events between d and the new point, the earliest first
        let mut event: Option<(Event, Pt, Watch)> = None;
        let mut failure: Option<StopReason> = None;
        let mut consider = |ev: Event, g: Crossing, hist: &[Pt], stepper: &mut dyn Stepper| {
            if g.of_watch(&w) < 0.0 {
                return;
            }
            match locate(stepper, ctx, hist, d, w.d, g) {
                Ok((pe, we)) => {
                    if event.as_ref().is_none_or(|(_, q, _)| pe.d < q.d) {
                        event = Some((ev, pe, we));
                    }
                }
                Err(msg) => {
                    failure.get_or_insert(StopReason::SolverFailure {
                        d,
                        message: format!("locating the {}: {msg}", ev.name()),
                    });
                }
            }
        };
        consider(Event::Penetration, Crossing::Penetration, hist, stepper);
        consider(Event::LiftOff, Crossing::LiftOff, hist, stepper);
        if let Some(mu0) = ctx.opts.mu0 {
            consider(Event::Slip, Crossing::Slip(mu0), hist, stepper);
        }
        if event.is_none() {
            if let Some(f) = failure {
                range.close(RangeEnd::SolverFailure);
                return f;
            }
        }
        let d_stop = event.as_ref().map_or(w.d, |e| e.1.d);
        // the first maximum of |μ| between the last point and d_stop
        if range.end.is_none() {
            if let Some(m) = first_max(stepper, ctx, hist, &prev, pprev.as_ref(), &w, d_stop) {
                range.see(&m);
                range.close(RangeEnd::FirstMaximum);
            }
        }
        if let Some((ev, _, we)) = &mut event {
            if *ev == Event::LiftOff {
                // N = 0 exactly there: the friction ratio is unbounded, any μ0 slips before
                we.normal = 0.0;
                we.mu = f64::INFINITY.copysign(we.mu);
            }
            range.see(we);
        } else {
            range.see(&w);
        }
        if let Err(fail) = out.emit(stepper, ctx, hist, grid, d_stop) {
            return fail;
        }
        if let Some((ev, pe, we)) = event {
            range.close(RangeEnd::Event);
            out.event(ctx, &pe, &we, ev);
            return stop_reason(ev, &we);
        }
        pprev = Some(prev);
        prev = w;
    }
}

/// Where the branch polynomial, extrapolated from the last points, predicts `g` to reach 0
/// within `(a, b]` (`None` without a polynomial, or when it does not).
fn predicted_crossing<P: Profile>(
    stepper: &dyn Stepper,
    ctx: &Ctx<'_, P>,
    hist: &[Pt],
    a: f64,
    b: f64,
    g: Crossing,
) -> Option<f64> {
    let on_poly = |d: f64| -> Result<f64, String> {
        let (u, du) = stepper
            .interpolant(hist, d)
            .ok_or_else(|| "no polynomial".to_string())?;
        g.of_u(&ctx.contact, &u, &du)
            .ok_or_else(|| "not a function of the unknowns".to_string())
    };
    let (ga, gb) = (on_poly(a).ok()?, on_poly(b).ok()?);
    if !(ga < 0.0 && gb >= 0.0) {
        return None;
    }
    let mut f = on_poly;
    search::root(&mut f, a, b, 1e-15 * (1.0 + b.abs())).ok()
}

/// The first `d` in `[a, b]` where `g` reaches 0 (`g(a) < 0 ≤ g(b)`). Where the stepper has the
/// branch as a polynomial (exact tangents) and `g` depends on the unknowns alone: Brent's method on
/// that polynomial, refined by Newton steps with solves (derivative from the polynomial) — one or
/// two solves. Otherwise Brent's method on solves within the step.
fn locate<P: Profile>(
    stepper: &mut dyn Stepper,
    ctx: &Ctx<'_, P>,
    hist: &[Pt],
    a: f64,
    b: f64,
    g: Crossing,
) -> Result<(Pt, Watch), String> {
    let c = &ctx.contact;
    let on_poly = |stepper: &dyn Stepper, d: f64| -> Option<f64> {
        let (u, du) = stepper.interpolant(hist, d)?;
        g.of_u(c, &u, &du)
    };
    if on_poly(stepper, a).is_some() {
        let mut poly = |d: f64| on_poly(stepper, d).ok_or_else(|| "no polynomial".to_string());
        if let Ok(mut d) = search::root(&mut poly, a, b, 1e-15 * (1.0 + b.abs())) {
            let eps = 1e-6 * (b - a);
            for _ in 0..4 {
                let p = stepper.correct(d, hist)?;
                let w = c.watch(&p);
                let slope = match (on_poly(stepper, d + eps), on_poly(stepper, d - eps)) {
                    (Some(gp), Some(gm)) => (gp - gm) / (2.0 * eps),
                    _ => break,
                };
                let step = g.of_watch(&w) / slope;
                if !step.is_finite() || !(a..=b).contains(&(d - step)) {
                    break;
                }
                if step.abs() <= 1e-13 * (1.0 + d.abs()) {
                    return Ok((p, w));
                }
                d -= step;
            }
        }
    }
    let mut eval = |d: f64| -> Result<f64, String> {
        let p = stepper.correct(d, hist)?;
        Ok(g.of_watch(&c.watch(&p)))
    };
    let d = search::root(&mut eval, a, b, 1e-13)?;
    let p = stepper.correct(d, hist)?;
    let w = c.watch(&p);
    Ok((p, w))
}

/// The first maximum of `|μ|` in `(prev.d, d_stop]`, if there is one: the root of `d|μ|/dd`
/// where tangents are known, else (three-point pattern) Brent's maximizer.
fn first_max<P: Profile>(
    stepper: &mut dyn Stepper,
    ctx: &Ctx<'_, P>,
    hist: &[Pt],
    prev: &Watch,
    pprev: Option<&Watch>,
    w: &Watch,
    d_stop: f64,
) -> Option<Watch> {
    if let (Some(s0), Some(s1)) = (prev.dmu_abs, w.dmu_abs) {
        if !(s0 > 0.0 && s1 <= 0.0) {
            return None;
        }
        let (p, wm) = locate(stepper, ctx, hist, prev.d, w.d, Crossing::MuMax).ok()?;
        return (p.d <= d_stop).then_some(wm);
    }
    let pp = pprev?;
    if !(prev.mu.abs() > pp.mu.abs() && prev.mu.abs() >= w.mu.abs()) {
        return None;
    }
    let mut eval = |d: f64| -> Result<f64, String> {
        let p = stepper.correct(d, hist)?;
        Ok(ctx.contact.watch(&p).mu.abs())
    };
    let (d, _) = search::maximize(&mut eval, pp.d, w.d.min(d_stop), 1e-10).ok()?;
    let p = stepper.correct(d, hist).ok()?;
    Some(ctx.contact.watch(&p))
}

/// The output point of a branch point.
fn scan_point<P: Profile>(p: &Pt, w: &Watch, profile: &P, event: Option<Event>) -> ScanPoint {
    let (f, alpha) = (p.u[1], p.u[2]);
    let (flex, s_flex, _) = flex_and_reversals(&p.sol, profile);
    ScanPoint {
        d: p.d,
        mu: w.mu,
        normal: w.normal,
        alpha,
        phi1: p.sol.right()[2],
        f,
        fx: f * alpha.sin(),
        fy: -f * alpha.cos(),
        m_base: p.sol.left()[3],
        flex,
        s_flex,
        y_max: extrema(&p.sol, 0.0, 1.0).max,
        event,
    }
}

/// Output points on the grid, filled as the march passes them, and the event point.
struct Output {
    points: Vec<ScanPoint>,
    shapes: Vec<Vec<ShapePoint>>,
    keep: Option<usize>,
    gi: usize,
}

impl Output {
    fn push<P: Profile>(&mut self, ctx: &Ctx<'_, P>, p: &Pt, w: &Watch, event: Option<Event>) {
        self.points.push(scan_point(p, w, ctx.profile, event));
        if let Some(ns) = self.keep {
            let shape = shape_from(p.sol.clone(), p.u[2], ctx.general.clone());
            self.shapes.push(shape.samples(ns));
        }
    }

    fn event<P: Profile>(&mut self, ctx: &Ctx<'_, P>, p: &Pt, w: &Watch, ev: Event) {
        self.push(ctx, p, w, Some(ev));
    }

    /// Emits the grid points up to `upto` (the branch point itself where one is at the grid value,
    /// else a solve from the history). A point that cannot be solved ends the scan.
    fn emit<P: Profile>(
        &mut self,
        stepper: &mut dyn Stepper,
        ctx: &Ctx<'_, P>,
        hist: &[Pt],
        grid: &[f64],
        upto: f64,
    ) -> Result<(), StopReason> {
        while let Some(&dg) = grid.get(self.gi) {
            if dg > upto {
                break;
            }
            let p = match hist.iter().rev().find(|p| p.d == dg) {
                Some(p) => p.clone(),
                None => stepper
                    .correct(dg, hist)
                    .map_err(|e| StopReason::SolverFailure {
                        d: dg,
                        message: format!("output point at d = {dg}: {e}"),
                    })?,
            };
            let w = ctx.contact.watch(&p);
            self.push(ctx, &p, &w, None);
            self.gi += 1;
        }
        Ok(())
    }
}
