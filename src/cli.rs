//! Command-line definitions (clap derive). Every flag says its unit, range and default.
//!
//! Numbers are parsed here only for their spelling (every form Rust's `f64` parser accepts,
//! negative ones included: `-1e-3`, `-.5`, `-0.1:0.1:3`, `-1,0,1`); their ranges are the
//! library's (`vibrissa::limits`), checked by `validate`, the same for every command. Named values
//! (methods, branches, contact models, starts) are the library's enums, parsed by their names,
//! and the defaults shown are the library's. Depends on clap, std, the library and
//! `number_text` only (the end-to-end tests include this file to list every numeric flag).

use crate::number_text::{self, Axis};
use clap::builder::TypedValueParser;
use clap::{Args, CommandFactory, Parser, Subcommand, ValueEnum};
use std::any::TypeId;
use std::path::PathBuf;
use std::sync::LazyLock;
use vibrissa::{
    limits, BranchChoice, ContactModel, Method, ScanOptions, SolverConfig, StartKind, WhiskOptions,
};

/// The library's defaults as `--help` shows them (`1e-10`, `0.5`, `201`): clap's default values
/// are text that lives as long as the program.
struct Defaults {
    tol: String,
    d_max: String,
    points: String,
    drag_d_max: String,
    drag_points: String,
    theta_max: String,
    whisk_points: String,
    shape_points: String,
    solve_shape_points: String,
    max_slips: String,
    dyn_dt: String,
    dyn_grid: String,
    dyn_tol: String,
    dyn_event_tol: String,
    dyn_max_events: String,
    dyn_refinements: String,
    free_dt: String,
    free_grid: String,
    free_tol: String,
}

static DEFAULTS: LazyLock<Defaults> = LazyLock::new(|| {
    // the shorter of the plain and the scientific spelling
    let shown = |v: f64| {
        let (plain, sci) = (format!("{v}"), format!("{v:e}"));
        if sci.len() < plain.len() {
            sci
        } else {
            plain
        }
    };
    let (scan, whisk) = (ScanOptions::default(), WhiskOptions::default());
    let drag_in_time = vibrissa::dynamics::DynDragOptions::default();
    let free = vibrissa::dynamics::DynamicsOptions::default();
    Defaults {
        tol: shown(scan.solver.tol),
        d_max: shown(scan.d_max),
        points: scan.points.to_string(),
        drag_d_max: shown(limits::DEFAULT_DRAG_D_MAX),
        drag_points: limits::DEFAULT_DRAG_POINTS.to_string(),
        theta_max: shown(whisk.theta_max),
        whisk_points: whisk.points.to_string(),
        shape_points: limits::DEFAULT_SHAPE_POINTS.to_string(),
        solve_shape_points: limits::DEFAULT_SOLVE_SHAPE_POINTS.to_string(),
        max_slips: vibrissa::DragOptions::default().max_slips.to_string(),
        dyn_dt: shown(drag_in_time.dt),
        dyn_grid: drag_in_time.grid.to_string(),
        dyn_tol: shown(drag_in_time.tol),
        dyn_event_tol: shown(drag_in_time.event_tol),
        dyn_max_events: drag_in_time.max_events.to_string(),
        dyn_refinements: drag_in_time.refinements.to_string(),
        free_dt: shown(free.dt),
        free_grid: free.grid.to_string(),
        free_tol: shown(free.tol),
    }
});

/// Parse a finite `f64` (NaN and infinities are refused).
pub fn finite_f64(s: &str) -> Result<f64, String> {
    number_text::finite_f64(s)
}

/// Parse an `f64` that may be `inf` (no limit); NaN refused.
pub fn f64_or_inf(s: &str) -> Result<f64, String> {
    number_text::number_or_inf(s)
}

/// Parse a grid axis (`a:b:n` or a comma list).
pub fn axis(s: &str) -> Result<Axis, String> {
    number_text::parse_axis(s)
}

/// Parse a grid axis whose lists may hold `inf` (`--mu0 0.5,1,inf`).
pub fn axis_or_inf(s: &str) -> Result<Axis, String> {
    number_text::parse_axis_or_inf(s)
}

/// Parse a point `X,Y` (two finite numbers).
pub fn point(s: &str) -> Result<Point, String> {
    let parts: Vec<&str> = s.split(',').collect();
    match parts.as_slice() {
        [x, y] => Ok(Point {
            x: number_text::finite_f64(x.trim())?,
            y: number_text::finite_f64(y.trim())?,
        }),
        _ => Err(format!(
            "'{s}' is not a point X,Y (two numbers separated by a comma)"
        )),
    }
}

/// A point `X,Y` of the plane (rod lengths).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point {
    /// x
    pub x: f64,
    /// y
    pub y: f64,
}

/// Parse a shard `K/N`.
pub fn shard(s: &str) -> Result<Shard, String> {
    number_text::parse_shard(s).map(|(k, n)| Shard { k, n })
}

/// Shard `k` of `n` (1-based).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// this shard, 1..=n
    pub k: u64,
    /// number of shards
    pub n: u64,
}

/// Most output points of a scan (the model's limit).
pub const MAX_POINTS: u64 = limits::POINTS.hi as u64;
/// Most points of one shape.
pub const MAX_SHAPE_POINTS: u64 = limits::SHAPE_POINTS.hi as u64;
/// Most worker threads asked for (more are capped at a multiple of the cores, with a warning).
pub const MAX_JOBS: u64 = vibrissa::limits::JOBS.hi as u64;

fn points(s: &str) -> Result<u32, String> {
    number_text::count(s, 2, MAX_POINTS)
}
fn max_slips(s: &str) -> Result<u32, String> {
    // the library's range (the limits table), as a flag's value
    let r = limits::MAX_SLIPS;
    number_text::count(s, r.lo as u64, r.hi as u64)
}
fn shape_points(s: &str) -> Result<u32, String> {
    number_text::count(s, 2, MAX_SHAPE_POINTS)
}
fn solve_shape_points(s: &str) -> Result<u32, String> {
    number_text::count(s, 2, 1_000_000)
}
/// A whole number as spelled; its range is the library's (the options' `validate`).
fn whole(s: &str) -> Result<u32, String> {
    let t = s.trim();
    if t.starts_with('-') {
        return Err(format!("{t} is negative: a count is 0 or more"));
    }
    number_text::count(t, 0, u64::from(u32::MAX))
}
/// Values named by the library (`name`, with its one-line `help` that `--help` lists), parsed
/// by the library's `FromStr`.
fn named<T>(
    values: impl IntoIterator<Item = (&'static str, &'static str)>,
) -> impl TypedValueParser<Value = T>
where
    T: std::str::FromStr + Clone + Send + Sync + 'static,
    T::Err: std::error::Error + Send + Sync + 'static,
{
    let values: Vec<clap::builder::PossibleValue> = values
        .into_iter()
        .map(|(name, help)| clap::builder::PossibleValue::new(name).help(help))
        .collect();
    clap::builder::PossibleValuesParser::new(values).try_map(|s| s.parse::<T>())
}

/// Every method of the library.
fn method() -> impl TypedValueParser<Value = Method> {
    named(Method::ALL.map(|m| (m.name(), m.help())))
}

/// The numerical methods (every method but `analytic`).
fn numerical_method() -> impl TypedValueParser<Value = Method> {
    named(
        Method::ALL
            .into_iter()
            .filter(|m| *m != Method::Analytic)
            .map(|m| (m.name(), m.help())),
    )
}

fn branch() -> impl TypedValueParser<Value = BranchChoice> {
    named(BranchChoice::NAMED.map(|b| (b.name(), b.help())))
}

fn contact() -> impl TypedValueParser<Value = ContactModel> {
    named(ContactModel::ALL.map(|c| (c.name(), c.help())))
}

fn start() -> impl TypedValueParser<Value = StartKind> {
    named(StartKind::ALL.map(|k| (k.name(), k.help())))
}

/// The long help of sweep's `--method`: the library's methods, one a line.
fn method_list() -> String {
    let mut h = String::from("Methods, a comma list of:");
    for m in Method::ALL {
        h.push_str(&format!("\n- {:<19}{}", format!("{}:", m.name()), m.help()));
    }
    h
}

fn point_index(s: &str) -> Result<usize, String> {
    s.trim()
        .parse()
        .map_err(|_| "not a point index (a whole number >= 0, the point column)".to_string())
}

fn jobs(s: &str) -> Result<u32, String> {
    number_text::count(s, 1, MAX_JOBS)
}

/// The `vibrissa` program.
#[derive(Parser, Debug)]
#[command(
    name = "vibrissa",
    version,
    about = "Elastic whisker (vibrissa) model: tip-contact solves, stiction scans, parameter sweeps, the paper's figures",
    long_about = "Elastic whisker (vibrissa) model: tip-contact solves, stiction scans, parameter sweeps, the paper's figures.\n\n\
Units are normalized: length L (the rod length), force EI/L^2, moment EI/L (EI at the base), angles in radians. \
The tip force is F = (f sin(alpha), -f cos(alpha)): alpha = 0 points straight down, alpha < 0 rotates it clockwise; \
mu = F.t/N = tan(beta - alpha) is the signed friction ratio the contact must supply (beta: surface angle; \
N = f cos(alpha - beta) >= 0 the normal force; mu > 0 holds the tip back against the drag), the tip slips where |mu| \
reaches mu0 and lifts off where N reaches 0. m_base = m(0) is the internal moment at the foot (the paper's clamp moment is m0 = -m_base).\n\n\
Exit codes: 0 success (also when the reader closes stdout early), 1 solver or I/O failure, 2 bad input. \
Output files appear only when the whole command succeeded (see docs/reference.md, \"Exit codes, errors and output files\")."
)]
pub struct Cli {
    /// The command to run.
    #[command(subcommand)]
    pub command: Command,
}

/// Sub-commands.
#[derive(Subcommand, Debug)]
#[allow(clippy::large_enum_variant)] // one value per process
pub enum Command {
    /// Solve one tip-loaded rod: given alpha and the tip slope phi1 (or the tip height eta).
    Solve(SolveArgs),
    /// Stiction scan: drag the foot by d while the tip sticks at height eta; report mu(d).
    Scan(ScanArgs),
    /// Grid of stiction scans over scene parameters, in parallel, one CSV row per scene.
    Sweep(SweepArgs),
    /// Read the stiction coefficient mu0 = mu(d0) off a scan at the slip displacement d0.
    Infer(InferArgs),
    /// Regenerate the paper's Figures 2-11 as SVG files, with the CSV data behind each.
    Figures(FiguresArgs),
    /// Draw a file of yours as SVG: a scan CSV, its --shapes, a sweep CSV, a drag CSV, a
    /// dynamics CSV or its --spectrum.
    Plot(PlotArgs),
    /// Turn the foot against a point object (a peg): the contact moves along the rod until the
    /// object slips off the tip; one row per foot angle.
    Whisk(WhiskArgs),
    /// Where a point object touches the rod, from the base signals of one instant (the inverse
    /// of solve --peg).
    Locate(LocateArgs),
    /// Drag the foot across the surface through every stick-slip cycle: one row per output d,
    /// plus a row at each slip (before) and where the tip sticks again (after).
    Drag(DragArgs),
    /// Estimate mu_s and mu_k (with standard errors) from a measured drag trace: the slips'
    /// places and the base signals around them, by nonlinear least squares.
    Fit(FitArgs),
    /// Natural frequencies of a static state given by its foot values (the free, unloaded rod by
    /// default): one row per mode, omega^2 < 0 meaning the state is unstable.
    Modes(ModesArgs),
    /// The rod in time: `dynamics drag` drags the foot at a speed with the tip on the surface
    /// (stick, slip and lift-off located in time), `dynamics free` releases it from a tip force
    /// or a foot moment; one row per time step.
    Dynamics(DynamicsArgs),
}

/// `vibrissa dynamics`.
#[derive(Args, Debug)]
pub struct DynamicsArgs {
    /// What to follow in time.
    #[command(subcommand)]
    pub command: DynamicsCommand,
}

/// The sub-commands of `vibrissa dynamics`.
#[derive(Subcommand, Debug)]
#[allow(clippy::large_enum_variant)] // one value per process
pub enum DynamicsCommand {
    /// Drag the foot along x at --speed with the tip on the surface (a line or a height
    /// profile) under Coulomb friction, from the pressed start at rest: one row per time step.
    Drag(DynamicsDragArgs),
    /// Release the rod at t = 0 from its equilibrium under a tip force (--release-fx,
    /// --release-fy) or step a moment onto its foot (--foot-moment), tip free: one row per time
    /// step.
    Free(DynamicsFreeArgs),
}

/// `vibrissa dynamics free`.
#[derive(Args, Debug)]
#[command(
    after_help = "The rod in time (docs/model.md, \"The rod in time\"): every time step a BVP in s; in time the energy-momentum step (the default with fixed steps: the step's mean force and moment, so each step keeps the energy whatever the amplitude) or Newmark's average acceleration (--time-scheme newmark, and the scheme of --time-tol), both second order with no numerical damping (periods lengthen by (omega dt)^2/12). The start is the static equilibrium under the dead tip force (--release-fx, --release-fy), at rest; the force is removed at t = 0 (Newmark's first step sees the mean of the force before and after, which loses about 1 % of the energy at 50 steps per period; the energy-momentum step loses none). --foot-moment steps a moment onto the foot's support (it turns the rod only when --support-compliance > 0). Time unit sqrt(rho A(0) L^4 / EI(0)); with physical dimensions (keratin, 1250 kg/m^3) t_s and the physical-unit columns are added."
)]
pub struct DynamicsFreeArgs {
    /// Tip force x (EI/L^2) held before t = 0 and released then (a dead load), finite.
    #[arg(long, value_name = "FX", value_parser = finite_f64, default_value = "0")]
    pub release_fx: f64,
    /// Tip force y (EI/L^2) held before t = 0 and released then, finite.
    #[arg(long, value_name = "FY", value_parser = finite_f64, default_value = "0")]
    pub release_fy: f64,
    /// A moment (EI/L) applied to the foot's support from t = 0 on (a step), finite; needs
    /// --support-compliance > 0 to turn the foot.
    #[arg(long, value_name = "M", value_parser = finite_f64, default_value = "0")]
    pub foot_moment: f64,
    /// Time step, in (0, 1].
    #[arg(long, value_name = "DT", value_parser = finite_f64, default_value = DEFAULTS.free_dt.as_str())]
    pub dt: f64,
    /// End time (normalized time units), in (0, 1e6].
    #[arg(long, value_name = "T", value_parser = finite_f64, default_value = "1")]
    pub t_end: f64,
    /// Adaptive time steps: the tolerance (rod lengths) of each step's local error estimate in
    /// the positions, in [1e-14, 0.1]; --dt is then the first step, a step over it is tried
    /// again shorter, and the rows are at the steps taken (docs/model.md, "Adaptive time
    /// steps"). [default: fixed steps of --dt]
    #[arg(long, value_name = "TOL", value_parser = finite_f64)]
    pub time_tol: Option<f64>,
    /// Intervals of the history grid in s (the positions, velocities and accelerations kept
    /// between steps), even, in [20, 100000]: with --tol, the accuracy in s bought per step
    /// (docs/performance.md, "The drag in time: accuracy against cost").
    #[arg(long, value_name = "N", value_parser = whole, default_value = DEFAULTS.free_grid.as_str())]
    pub grid: u32,
    /// Tolerance of each step's collocation in s (its residual and error estimate), in
    /// [1e-13, 1e-4].
    #[arg(long, value_name = "T", value_parser = finite_f64, default_value = DEFAULTS.free_tol.as_str())]
    pub tol: f64,
    /// Damper of the foot's support (moment per angular velocity), in [0, inf); its spring is
    /// 1/--support-compliance.
    #[arg(long, value_name = "C", value_parser = finite_f64, default_value = "0")]
    pub foot_damping: f64,
    /// The rod's internal (Kelvin-Voigt) damping gamma_i, in [0, 1e6]: every mode of the
    /// linearized rod decays at gamma_i omega^2/2 (docs/model.md). The energy it takes is in
    /// --json (`internal_damping`).
    #[arg(long, value_name = "G", value_parser = finite_f64, default_value = "0")]
    pub internal_damping: f64,
    /// External viscous damping gamma_e, in [0, 1e6]: a distributed force -gamma_e mu(s) r_t
    /// (every mode decays at gamma_e/2). The energy it takes is in --json (`external_damping`).
    #[arg(long, value_name = "G", value_parser = finite_f64, default_value = "0")]
    pub external_damping: f64,
    /// Rotary inertia: the radius of gyration of the foot's section over the length g0, in
    /// [0, 0.1] (as modes --rotary-inertia): the slopes carry the inertia g0^2/b per length and
    /// the kinetic energy its share (0: none, the Euler-Bernoulli rod).
    #[arg(long, value_name = "G", value_parser = finite_f64, default_value = "0")]
    pub rotary_inertia: f64,
    /// The time scheme: energy-momentum (each step keeps the energy whatever the amplitude,
    /// where Newmark's grows at large ones; fixed steps only; the rows' base force and moment
    /// are the steps' means: docs/model.md, "The energy of a large oscillation") or newmark
    /// (the trapezoidal rule; the scheme of --time-tol's adaptive steps). [default:
    /// energy-momentum with fixed steps, newmark with --time-tol]
    #[arg(long, value_enum)]
    pub time_scheme: Option<TimeSchemeArg>,
    /// Also write the amplitude spectrum of m_base (mean removed, Hann window) to this CSV file.
    #[arg(long, value_name = "FILE.csv")]
    pub spectrum: Option<PathBuf>,
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Print a JSON object instead of CSV.
    #[arg(long)]
    pub json: bool,
}

/// `vibrissa dynamics drag`.
#[derive(Args, Debug)]
#[command(
    after_help = "The rod in time (docs/model.md, \"The rod in time\"): Newmark's average acceleration in time, every step a BVP in s. The tip sticks while |T| < mu_s N, slides with T = mu_k N against its motion, sticks again where its velocity along the surface is zero; lift-off (N = 0) ends the drag. Events are located in time to --event-tol (default 1e-10); --dt, --grid and --tol set the accuracy in time and in s (docs/performance.md, \"The drag in time: accuracy against cost\"). The foot's speed rises smoothly to --speed over --ramp time units, or the foot follows --foot-table; --whisk turns its support. Time unit sqrt(rho A(0) L^4 / EI(0)). Any surface line (--surface-angle) or height profile (the --corrugation, --grating and --surface-profile flags, or the scene's [surface]) with the tip on it. Where the rod's end lies down on the surface (a point tip, uniform friction) the contact moves inwards: a side that rolls, slips, slides, sticks or lifts off as the tip does (states side_stuck, side_sliding_forward, side_sliding_back; columns side_s, side_x, side_y; docs/model.md, \"A side in time\"); where its contact reaches the tip the tip takes it over (event to_tip). Where a point of the rod touches beside the stuck or sliding tip (side_contact), or the tip touches down beside a side (touchdown), the two contacts go on together, each sticking, slipping and lifting off by its own law (the tip's in the columns tip_state, tip_normal, tip_tangential; docs/model.md, \"Two contacts in time\"), until one lifts off or they meet at the tip (to_tip); the drag stops by name where a third point reaches the surface (side_change). A scene's [friction] texture gives mu_s and mu_k along the surface (the stuck tip's where it sticks, the sliding tip's where it slides: a patch's boundary crossed is an event, patch). A round tip (--tip-radius, on a line or a height profile the disk fits) rolls while it sticks and carries the moment r T; it needs --internal-damping above 0 (e.g. 1e-4)."
)]
pub struct DynamicsDragArgs {
    /// Foot speed after the start ramp (rod lengths per time unit), in (0, 100].
    #[arg(long, value_name = "V", value_parser = finite_f64, default_value = "0.01")]
    pub speed: f64,
    /// Duration of the smooth start of the foot's speed, in [0, 1e6] (0: at --speed at once).
    #[arg(long, value_name = "T", value_parser = finite_f64, default_value = "2")]
    pub ramp: f64,
    /// Surface height eta (rod lengths), in (eta_, 1) (see scan --help). [default: scene file's, else 0.75]
    #[arg(long, value_name = "H", value_parser = finite_f64)]
    pub eta: Option<f64>,
    /// Foot displacement where the drag ends (rod lengths), in (0, 1000].
    #[arg(long, value_name = "D", value_parser = finite_f64, default_value = "0.03")]
    pub d_max: f64,
    /// Static friction coefficient, in [0, 100]; with --mu-k it replaces the scene's [friction]
    /// texture. [default: the scene's [friction], else 0.5]
    #[arg(long, value_name = "MU", value_parser = finite_f64)]
    pub mu_s: Option<f64>,
    /// Kinetic friction coefficient, in [0, mu_s). [default: the scene's [friction], else 0.3]
    #[arg(long, value_name = "MU", value_parser = finite_f64)]
    pub mu_k: Option<f64>,
    /// Time step, in (0, 1].
    #[arg(long, value_name = "DT", value_parser = finite_f64, default_value = DEFAULTS.dyn_dt.as_str())]
    pub dt: f64,
    /// Adaptive time steps: the tolerance (rod lengths) of each step's local error estimate in
    /// the positions, in [1e-14, 0.1]; --dt is then the first step, a step over it is tried
    /// again shorter, each step taken proposes the next, and events still shorten a step to
    /// their place (docs/model.md, "Adaptive time steps"). [default: fixed steps of --dt]
    #[arg(long, value_name = "TOL", value_parser = finite_f64)]
    pub time_tol: Option<f64>,
    /// Intervals of the history grid in s (the positions, velocities and accelerations kept
    /// between steps), even, in [20, 100000]: with --tol, the accuracy in s bought per step
    /// (docs/performance.md, "The drag in time: accuracy against cost").
    #[arg(long, value_name = "N", value_parser = whole, default_value = DEFAULTS.dyn_grid.as_str())]
    pub grid: u32,
    /// Tolerance of each step's collocation in s (its residual and error estimate), in
    /// [1e-13, 1e-4].
    #[arg(long, value_name = "T", value_parser = finite_f64, default_value = DEFAULTS.dyn_tol.as_str())]
    pub tol: f64,
    /// Tolerance in time of the events' places (slip, stick, lift-off, touchdown, patch), in
    /// [1e-14, 1e-3].
    #[arg(long, value_name = "T", value_parser = finite_f64, default_value = DEFAULTS.dyn_event_tol.as_str())]
    pub event_tol: f64,
    /// Most events before the drag stops (stop max_events), in [1, 1e6].
    #[arg(long, value_name = "N", value_parser = whole, default_value = DEFAULTS.dyn_max_events.as_str())]
    pub max_events: u32,
    /// Halvings of --dt tried where the steps do not resolve a stick or a stuck step, place a
    /// slip beyond the friction cone, or give a step Newton does not solve: the drag goes back
    /// to its state after the last event
    /// and takes the steps from there at dt/2, dt/4, ... (docs/model.md, "A stick the time
    /// step does not resolve"), in [0, 10]; 0 ends the drag there by name at once. Fixed steps
    /// only (not with --time-tol).
    #[arg(long, value_name = "K", value_parser = whole, default_value = DEFAULTS.dyn_refinements.as_str())]
    pub refinements: u32,
    /// Damper of the foot's support (moment per angular velocity), in [0, inf).
    #[arg(long, value_name = "C", value_parser = finite_f64, default_value = "0")]
    pub foot_damping: f64,
    /// The rod's internal (Kelvin-Voigt) damping gamma_i, in [0, 1e6]: every mode of the
    /// linearized rod decays at gamma_i omega^2/2 (docs/model.md). The energy it takes is in
    /// --json (`internal_damping`).
    #[arg(long, value_name = "G", value_parser = finite_f64, default_value = "0")]
    pub internal_damping: f64,
    /// External viscous damping gamma_e, in [0, 1e6]: a distributed force -gamma_e mu(s) r_t
    /// (every mode decays at gamma_e/2). The energy it takes is in --json (`external_damping`).
    #[arg(long, value_name = "G", value_parser = finite_f64, default_value = "0")]
    pub external_damping: f64,
    /// Rotary inertia: the radius of gyration of the foot's section over the length g0, in
    /// [0, 0.1] (as modes --rotary-inertia): the slopes carry the inertia g0^2/b per length and
    /// the kinetic energy its share (0: none, the Euler-Bernoulli rod).
    #[arg(long, value_name = "G", value_parser = finite_f64, default_value = "0")]
    pub rotary_inertia: f64,
    /// Kinetic friction depending on the slip speed: points V:MU,V:MU,... (speeds >= 0
    /// increasing, each MU in [0, mu_s)), piecewise linear, constant beyond the ends; replaces
    /// --mu-k.
    #[arg(long, value_name = "V:MU,...", value_parser = speed_table)]
    pub mu_k_table: Option<SpeedTable>,
    /// After a lift-off the tip flies until it touches the surface again (event touchdown, a
    /// plastic impact whose energy is in --json as `impact`), then slides or sticks on; without
    /// it a lift-off ends the drag.
    #[arg(long)]
    pub flight: bool,
    /// The foot's path by a time table instead of --speed, --ramp and --d-max: a file of rows
    /// t, d[, theta] (time, the foot's displacement along x, the turn of its support in rad,
    /// clockwise; comma, semicolon or space separated, '#' comments, an optional header), t
    /// strictly increasing from the first row 0, 0[, 0]; each column a natural cubic spline
    /// (docs/model.md, "The foot's path"). The drag ends at the table's last time; a column
    /// theta is added after d.
    #[arg(long, value_name = "FILE.csv", conflicts_with_all = ["speed", "ramp", "d_max"])]
    pub foot_table: Option<PathBuf>,
    /// Whisking: the foot's support turns by theta(t) = A (1 - cos 2 pi F t)/2 (rad, clockwise;
    /// A in (-pi/2, pi/2), F in (0, 1000] whisks per time unit), on top of the foot's path; a
    /// column theta is added after d.
    #[arg(long, value_name = "A,F", value_parser = whisk_arg)]
    pub whisk: Option<vibrissa::dynamics::Whisk>,
    /// Also write the amplitude spectrum of m_base (mean removed, Hann window) to this CSV file.
    #[arg(long, value_name = "FILE.csv")]
    pub spectrum: Option<PathBuf>,
    #[command(flatten)]
    pub texture: TextureArgs,
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Print a JSON object instead of CSV.
    #[arg(long)]
    pub json: bool,
}

/// Physical dimensions: with all three (or a scene file's `[physical]`), physical-unit columns.
#[derive(Args, Debug, Clone, Default)]
pub struct PhysicalArgs {
    /// Physical rod length (mm), in (0, inf); with --youngs-modulus-gpa and --base-diameter-um adds physical-unit columns.
    #[arg(long, value_name = "MM", value_parser = finite_f64, help_heading = "Physical units")]
    pub length_mm: Option<f64>,
    /// Young's modulus (GPa), in (0, inf).
    #[arg(long, value_name = "GPA", value_parser = finite_f64, help_heading = "Physical units")]
    pub youngs_modulus_gpa: Option<f64>,
    /// Base diameter (µm), in (0, inf); I = pi d^4 / 64.
    #[arg(long, value_name = "UM", value_parser = finite_f64, help_heading = "Physical units")]
    pub base_diameter_um: Option<f64>,
}

/// Scene flags of solve, scan and infer; they override the values of `--scene`.
#[derive(Args, Debug, Clone, Default)]
pub struct SceneArgs {
    /// Scene file (TOML, the fields of vibrissa::Scene; see docs/reference.md, "Scene files"; "-": stdin; read once, so a pipe or FIFO works). Flags override its values.
    #[arg(long, value_name = "FILE.toml", help_heading = "Scene")]
    pub scene: Option<PathBuf>,
    /// Conical taper: tip/base radius ratio RHO in [0.01, 1]; b(s) = (1 - (1 - RHO) s)^-4. [default: 1, uniform]
    #[arg(long, value_name = "RHO", value_parser = finite_f64, help_heading = "Scene")]
    pub taper: Option<f64>,
    /// Pre-curvature at the foot K0 (1/L; > 0 bends the rest shape counter-clockwise), in [-3, 3]. [default: 0]
    #[arg(long, value_name = "K0", value_parser = finite_f64, help_heading = "Scene")]
    pub precurvature: Option<f64>,
    /// Pre-curvature slope K1 (1/L^2): kappa0(s) = K0 + K1 s, in [-6, 6] with |K0 + K1| <= 3. [default: 0]
    #[arg(long, value_name = "K1", value_parser = finite_f64, help_heading = "Scene")]
    pub precurvature_slope: Option<f64>,
    /// Compliance C in [0, 1000] of the rotational spring at the foot (1/(EI/L)): phi(0) = pi/2 + C m(0); 0 = clamp. [default: 0]
    #[arg(long, value_name = "C", value_parser = finite_f64, help_heading = "Scene")]
    pub support_compliance: Option<f64>,
    /// Inclination B of the surface line through the contact point (rad), in (-pi/4, pi/4); 0 = horizontal. [default: 0]
    #[arg(long, value_name = "B", value_parser = finite_f64, help_heading = "Scene")]
    pub surface_angle: Option<f64>,
    /// Where the rod may touch the surface: anywhere (the rod stays below the surface line
    /// everywhere; sides touch and lie down) or the tip alone (the paper's model: a touching side
    /// ends the scan with penetration). [default: scene file's, else anywhere]
    #[arg(long, value_parser = contact(), value_name = "MODEL", help_heading = "Scene")]
    pub contact: Option<ContactModel>,
    /// The state a scan starts from: pressed (the rod pressed onto the surface from its rest
    /// shape) or connected (the tip-loaded state connected to the pressed straight uniform rod).
    /// [default: scene file's, else pressed]
    #[arg(long, value_parser = start(), value_name = "START", help_heading = "Scene")]
    pub start: Option<StartKind>,
    /// Radius R of the round tip (rod lengths), in [0, 0.05]: the rod's end carries a rigid disk
    /// of radius R centred at its end point, which rolls while it sticks and takes surface slopes
    /// up to 80 degrees; 0 is the point tip. [default: scene file's, else 0]
    #[arg(long, value_name = "R", value_parser = finite_f64, help_heading = "Scene")]
    pub tip_radius: Option<f64>,
    #[command(flatten)]
    pub physical: PhysicalArgs,
}

/// Solver flags shared by solve, scan and infer.
#[derive(Args, Debug, Clone)]
pub struct SolverArgs {
    /// Numerical method ("analytic" only for the uniform clamped straight rod).
    #[arg(long, value_parser = method(), default_value = Method::default().name())]
    pub method: Method,
    /// Tolerance of the numerical solver (local error / collocation residual), in [1e-15, 1e-2];
    /// Newton always iterates to min(tol, 1e-9).
    #[arg(long, value_name = "T", value_parser = finite_f64, default_value = DEFAULTS.tol.as_str())]
    pub tol: f64,
}

impl SolverArgs {
    /// The library's settings of these flags, starting from `start`.
    pub fn config(&self, start: StartKind) -> SolverConfig {
        SolverConfig {
            method: self.method,
            tol: self.tol,
            start,
            ..SolverConfig::default()
        }
    }
}

/// `vibrissa solve`.
#[derive(Args, Debug)]
#[command(
    after_help = "One of --phi1 and --eta is required (or --peg X,Y for a point object).",
    group(clap::ArgGroup::new("tip").args(["phi1", "eta"]).multiple(false))
)]
pub struct SolveArgs {
    /// Force angle alpha (rad), in (-pi/2, pi/2): 0 = straight down, < 0 = rotated clockwise (friction to -x); the closed forms (analytic) need [-pi/4, 0]. Required unless --peg.
    #[arg(long, value_name = "A", value_parser = finite_f64, required_unless_present = "peg")]
    pub alpha: Option<f64>,
    /// A point object at X,Y (rod lengths, frame of the unturned foot: y up the unloaded rod)
    /// touching the rod's side instead of a tip load: the rod turned by --theta against it.
    #[arg(long, value_name = "X,Y", value_parser = point, conflicts_with_all = ["alpha", "phi1", "eta", "branch"])]
    pub peg: Option<Point>,
    /// Foot angle for --peg (rad, clockwise, towards +x), in (-pi/2, pi/2): phi(0) = pi/2 - theta
    /// (+ the compliance term). [default: 0]
    #[arg(long, value_name = "A", value_parser = finite_f64, requires = "peg")]
    pub theta: Option<f64>,
    /// Stiction coefficient at the object for --peg, in [0, inf): the contact sticks while
    /// |T| <= mu0 N, then slides. [default: frictionless]
    #[arg(long, value_name = "MU", value_parser = f64_or_inf, requires = "peg")]
    pub mu0: Option<f64>,
    /// Tip slope phi1 = phi(1) (rad), in [-pi, pi]; the closed forms need [0, pi/2 + 2 alpha]. One of --phi1 and --eta is required.
    #[arg(long, value_name = "P", value_parser = finite_f64)]
    pub phi1: Option<f64>,
    /// Tip height eta (rod lengths), in (-1, 1): solve for the tip slope that puts the tip at y(1) = eta. One of --phi1 and --eta is required.
    #[arg(long, value_name = "H", value_parser = finite_f64)]
    pub eta: Option<f64>,
    /// Solution family.
    #[arg(long, value_parser = branch(), default_value = BranchChoice::default().name())]
    pub branch: BranchChoice,
    #[command(flatten)]
    pub solver: SolverArgs,
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Print a JSON object instead of CSV.
    #[arg(long)]
    pub json: bool,
    /// Also write the rod shape (s, x, y, phi, kappa, m) to this CSV file.
    #[arg(long, value_name = "FILE.csv")]
    pub shape_out: Option<PathBuf>,
    /// Number of points of --shape-out, uniform in s, in [2, 1000000] (needs --shape-out).
    #[arg(long, value_name = "N", default_value = DEFAULTS.solve_shape_points.as_str(), value_parser = solve_shape_points, requires = "shape_out")]
    pub shape_points: u32,
    /// Make it an error when the rod crosses the surface line through its tip (inclined by
    /// --surface-angle): some point with s < 1 above it, or the tip arriving from above. Without
    /// it such a rod is reported with penetration = 1 and a warning on stderr.
    #[arg(long)]
    pub require_contact: bool,
}

/// `vibrissa scan`.
#[derive(Args, Debug)]
pub struct ScanArgs {
    /// Surface height eta (rod lengths), in (eta_, 1) with eta_ = 0.456946581044463625 (the tip height of the uniform rod pushed straight down with a horizontal tip). [default: scene file's, else 0.75]
    #[arg(long, value_name = "H", value_parser = finite_f64)]
    pub eta: Option<f64>,
    /// Largest foot displacement d (rod lengths), in (0, 2).
    #[arg(long, value_name = "D", value_parser = finite_f64, default_value = DEFAULTS.d_max.as_str())]
    pub d_max: f64,
    /// Number of output points, uniform in d from 0 to --d-max, in [2, 1000000].
    #[arg(long, value_name = "N", default_value = DEFAULTS.points.as_str(), value_parser = points)]
    pub points: u32,
    /// Stiction coefficient, in [0, inf]: stop where |mu| reaches it (the tip slips, backwards for
    /// mu = mu0, forwards for mu = -mu0; mu = F.t/N = tan(beta - alpha) is the signed friction
    /// ratio). [default: none]
    #[arg(long, value_name = "MU", value_parser = f64_or_inf)]
    pub mu0: Option<f64>,
    #[command(flatten)]
    pub solver: SolverArgs,
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Write the scan points to this CSV file ("-": stdout, not with --json). Without it the CSV
    /// goes to stdout (unless --json).
    #[arg(long, value_name = "FILE.csv")]
    pub out: Option<PathBuf>,
    /// Write the rod shapes of all scan points to this CSV file (columns point, d, s, x, y, x_lab,
    /// phi, kappa, m, event; event names the event on the rows of the point where the scan
    /// stopped, as in the scan CSV).
    #[arg(long, value_name = "FILE.csv")]
    pub shapes: Option<PathBuf>,
    /// Points per shape in --shapes, in [2, 100000]; --points × --shape-points × 100 bytes must fit in 1 GB (needs --shapes).
    #[arg(long, value_name = "N", default_value = DEFAULTS.shape_points.as_str(), value_parser = shape_points, requires = "shapes")]
    pub shape_points: u32,
    /// Print the summary as a JSON object on stdout.
    #[arg(long)]
    pub json: bool,
    /// Add the column omega1_sq: the lowest omega^2 of each row's state with the tip stuck
    /// (vibrissa modes); < 0 is an unstable state (a warning says where), 0 at a fold in d;
    /// empty where a side touches.
    #[arg(long)]
    pub modes: bool,
}

/// `vibrissa infer`.
#[derive(Args, Debug)]
pub struct InferArgs {
    /// Surface height eta (rod lengths), in (eta_, 1) (see scan --help). [default: scene file's, else 0.75]
    #[arg(long, value_name = "H", value_parser = finite_f64)]
    pub eta: Option<f64>,
    /// Measured foot displacement at which the tip slipped (rod lengths), in [0, --d-max).
    #[arg(long, value_name = "D", value_parser = finite_f64)]
    pub d0: f64,
    /// Largest foot displacement the underlying scan explores (rod lengths), in (0, 2).
    #[arg(long, value_name = "D", value_parser = finite_f64, default_value = DEFAULTS.d_max.as_str())]
    pub d_max: f64,
    /// Points of the underlying scan, in [2, 1000000].
    #[arg(long, value_name = "N", default_value = DEFAULTS.points.as_str(), value_parser = points)]
    pub points: u32,
    #[command(flatten)]
    pub solver: SolverArgs,
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Print a JSON object instead of CSV.
    #[arg(long)]
    pub json: bool,
}

/// `vibrissa whisk`.
#[derive(Args, Debug)]
pub struct WhiskArgs {
    /// The point object X,Y (rod lengths, frame of the unturned foot: y up the unloaded rod).
    #[arg(long, value_name = "X,Y", value_parser = point)]
    pub peg: Point,
    /// Largest foot angle (rad, clockwise), in (-pi/2, pi/2); the rows run from first touch.
    #[arg(long, value_name = "A", value_parser = finite_f64, default_value = DEFAULTS.theta_max.as_str())]
    pub theta_max: f64,
    /// Number of output angles, uniform from first touch to --theta-max, in [2, 1000000].
    #[arg(long, value_name = "N", default_value = DEFAULTS.whisk_points.as_str(), value_parser = points)]
    pub points: u32,
    /// Stiction coefficient at the object, in [0, inf): the contact sticks while |T| <= mu0 N,
    /// then slides with |T| = mu0 N. [default: frictionless]
    #[arg(long, value_name = "MU", value_parser = f64_or_inf)]
    pub mu0: Option<f64>,
    #[command(flatten)]
    pub solver: SolverArgs,
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Write the rows to this CSV file ("-": stdout). Without it the CSV goes to stdout (unless
    /// --json).
    #[arg(long, value_name = "FILE.csv")]
    pub out: Option<PathBuf>,
    /// Write the rod shapes of all rows to this CSV file (columns point, theta, s, x, y, phi,
    /// kappa, m, event; frame of the unturned foot).
    #[arg(long, value_name = "FILE.csv")]
    pub shapes: Option<PathBuf>,
    /// Points per shape in --shapes, in [2, 100000] (needs --shapes).
    #[arg(long, value_name = "N", default_value = DEFAULTS.shape_points.as_str(), value_parser = shape_points, requires = "shapes")]
    pub shape_points: u32,
    /// Print the summary as a JSON object on stdout.
    #[arg(long)]
    pub json: bool,
}

/// `vibrissa locate`.
#[derive(Args, Debug)]
pub struct LocateArgs {
    /// Foot angle (rad, clockwise) at the instant, in (-pi/2, pi/2).
    #[arg(long, value_name = "A", value_parser = finite_f64, default_value = "0")]
    pub theta: f64,
    /// Base moment m_base = m(0) (EI/L).
    #[arg(long, value_name = "M", value_parser = finite_f64)]
    pub m_base: f64,
    /// Contact force on the rod, x component (EI/L^2, frame of the unturned foot).
    #[arg(long, value_name = "FX", value_parser = finite_f64)]
    pub fx: f64,
    /// Contact force on the rod, y component (EI/L^2).
    #[arg(long, value_name = "FY", value_parser = finite_f64)]
    pub fy: f64,
    #[command(flatten)]
    pub solver: SolverArgs,
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Print a JSON object instead of CSV.
    #[arg(long)]
    pub json: bool,
}

/// The surface textures of a drag from flags (each replaces the scene's `[surface]`; one kind at
/// a time): a corrugation or a sum of sines, a grating, a measured profile.
#[derive(Args, Debug, Default)]
pub struct TextureArgs {
    /// A sinusoidal corrugation A sin(2 pi x / W + P) on the surface: its amplitude A (rod
    /// lengths), |A| <= 0.2 (with --corrugation-wavelength; replaces the scene's [surface]). A
    /// comma list A1,A2,... with as many wavelengths (and phases, or none) is a sum of sines.
    #[arg(long, value_name = "A", value_parser = finite_f64, value_delimiter = ',')]
    pub corrugation_amplitude: Vec<f64>,
    /// The corrugation's wavelength W (rod lengths), in [0.01, 100] (a list: one per amplitude).
    #[arg(long, value_name = "W", value_parser = finite_f64, value_delimiter = ',')]
    pub corrugation_wavelength: Vec<f64>,
    /// The corrugation's phase P at x = 0 (rad), in [-1000, 1000] (a list: one per amplitude).
    /// [default: 0]
    #[arg(long, value_name = "P", value_parser = finite_f64, value_delimiter = ',')]
    pub corrugation_phase: Vec<f64>,
    /// A grating on the surface (straight flanks, round ridges and grooves; replaces the
    /// scene's [surface]): its period (rod lengths), in [0.01, 100], with --grating-ridge-radius
    /// and --grating-depth, --grating-flank-angle or both (then with flat lands).
    #[arg(long, value_name = "P", value_parser = finite_f64)]
    pub grating_period: Option<f64>,
    /// The grating's peak-to-valley depth (rod lengths), in (0, 0.4]; alone, the rounded
    /// triangle of this depth.
    #[arg(long, value_name = "D", value_parser = finite_f64)]
    pub grating_depth: Option<f64>,
    /// The grating's flank angle against its mean line (rad), in (0, pi/2), and with the
    /// surface angle below 45 degrees; alone, the rounded triangle of this angle.
    #[arg(long, value_name = "ANGLE", value_parser = finite_f64)]
    pub grating_flank_angle: Option<f64>,
    /// The radius of the grating's ridges and grooves (rod lengths), in (0, 100] (a sharp
    /// corner has no tangent).
    #[arg(long, value_name = "R", value_parser = finite_f64)]
    pub grating_ridge_radius: Option<f64>,
    /// Lab x of the middle of a ridge (rod lengths), in [-1000, 1000]. [default: 0]
    #[arg(long, value_name = "X", value_parser = finite_f64)]
    pub grating_offset: Option<f64>,
    /// A measured height profile on the surface: a file of two columns x, h (rod lengths; any
    /// spacing and order; replaces the scene's [surface]), smoothed to --profile-tolerance.
    #[arg(long, value_name = "FILE")]
    pub surface_profile: Option<PathBuf>,
    /// The measured profile's smoothing: the smoothest cubic spline within this of every
    /// sample (rod lengths), in [0, 0.1]; 0 interpolates.
    #[arg(long, value_name = "T", value_parser = finite_f64)]
    pub profile_tolerance: Option<f64>,
}

/// `dynamics free --time-scheme`.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum TimeSchemeArg {
    /// Newmark's average-acceleration rule.
    Newmark,
    /// The energy-momentum step.
    EnergyMomentum,
}

/// How the tip is held in `vibrissa modes`.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModesTip {
    /// free (a load on it is a dead load)
    Free,
    /// pinned, or stuck on a surface by friction
    Pinned,
    /// sliding without friction on a line inclined by --tip-angle
    Sliding,
}

fn mode_count(s: &str) -> Result<u32, String> {
    number_text::count(
        s,
        limits::MODE_COUNT.lo as u64,
        limits::MODE_COUNT.hi as u64,
    )
}

fn mode_shape_points(s: &str) -> Result<u32, String> {
    number_text::count(s, 0, MAX_SHAPE_POINTS)
}

/// `vibrissa modes`.
#[derive(Args, Debug)]
#[command(
    after_help = "The state is fixed by its foot values (as in locate, with the foot unturned): the rod integrated from the foot with m(0) = --m-base under the contact force (--fx, --fy) at the tip. Time unit sqrt(rho A(0) L^4 / EI(0)): the uniform clamped rod has omega_n = beta_n^2 (3.5160, 22.034, 61.697). docs/model.md, \"The rod in time\"."
)]
pub struct ModesArgs {
    /// Base moment m_base = m(0) (EI/L) of the static state.
    #[arg(long, value_name = "M", value_parser = finite_f64, default_value = "0")]
    pub m_base: f64,
    /// Contact force on the rod at the tip, x component (EI/L^2).
    #[arg(long, value_name = "FX", value_parser = finite_f64, default_value = "0")]
    pub fx: f64,
    /// Contact force on the rod at the tip, y component (EI/L^2).
    #[arg(long, value_name = "FY", value_parser = finite_f64, default_value = "0")]
    pub fy: f64,
    /// How the tip is held in the state and its vibrations.
    #[arg(long, value_enum, default_value = "free")]
    pub tip: ModesTip,
    /// Inclination of the line a sliding tip moves on (rad), in [-pi/2, pi/2].
    #[arg(long, value_name = "A", value_parser = finite_f64, default_value = "0")]
    pub tip_angle: f64,
    /// Number of modes, lowest first, in [1, 50].
    #[arg(long, value_name = "N", default_value = "3", value_parser = mode_count)]
    pub count: u32,
    /// Radius of gyration of the foot's section over the length (rotary inertia), in [0, 0.1] (0: none, the Euler-Bernoulli rod).
    #[arg(long, value_name = "G", value_parser = finite_f64, default_value = "0")]
    pub rotary_inertia: f64,
    /// Points of each mode shape in the --json output, uniform in s (0: none), in [0, 1000000].
    #[arg(long, value_name = "N", default_value = "0", value_parser = mode_shape_points)]
    pub points: u32,
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Print a JSON object instead of CSV.
    #[arg(long)]
    pub json: bool,
}

/// `vibrissa drag`.
#[derive(Args, Debug)]
#[command(
    after_help = "The slip is quasi-static (docs/model.md, \"The drag\"): at |mu| = mu_s the tip slides, the foot held, to the nearest equilibrium where kinetic friction mu_k holds it, then sticks there. Surfaces other than a line and friction textures come from the scene file's [surface] and [friction] tables (docs/reference.md, \"Scene files\"); the --corrugation flags set a sinusoidal [surface] (or a sum of sines), the --grating flags a grating, --surface-profile a measured profile."
)]
pub struct DragArgs {
    /// Surface height eta (rod lengths), in (eta_, 1) (see scan --help). [default: scene file's, else 0.75]
    #[arg(long, value_name = "H", value_parser = finite_f64)]
    pub eta: Option<f64>,
    /// Largest foot displacement d (rod lengths), in (0, 1000]; with --turn the largest turn
    /// (rad), in (0, pi/2).
    // (the library's `limits::DEFAULT_DRAG_D_MAX`, shorter than `DragOptions::default()`'s 2)
    #[arg(long, value_name = "D", value_parser = finite_f64, default_value = DEFAULTS.drag_d_max.as_str())]
    pub d_max: f64,
    /// Number of output points, uniform in d from 0 to --d-max, in [2, 1000000] (the slip rows
    /// come on top).
    #[arg(long, value_name = "N", default_value = DEFAULTS.drag_points.as_str(), value_parser = points)]
    pub points: u32,
    /// Whisk against the surface instead: the foot held where it stands, its support turned
    /// clockwise (towards +x) from upright by theta = 0 ... --d-max (rad); the rows' first
    /// column is theta.
    #[arg(long, conflicts_with_all = ["speed", "speed_mm_s"])]
    pub turn: bool,
    /// Static friction coefficient, in [0, 100]: the stuck tip slips where |mu| reaches it (with
    /// --mu-k). [default: the scene file's [friction]]
    #[arg(long, value_name = "MU", value_parser = finite_f64)]
    pub mu_s: Option<f64>,
    /// Kinetic friction coefficient, in [0, --mu-s): the slipping tip stops where the ratio it
    /// needs falls to it (with --mu-s).
    #[arg(long, value_name = "MU", value_parser = finite_f64)]
    pub mu_k: Option<f64>,
    #[command(flatten)]
    pub texture: TextureArgs,
    /// Also integrate the foot's work over each stick (a turned support's: its moment's) and the
    /// work the sliding tip absorbs over each slip (the energy balance, in --json's slips; extra
    /// solves).
    #[arg(long)]
    pub energy_balance: bool,
    /// Most slips before the drag stops, in [1, 1000000]: a guard against slips that come too
    /// close together to reach --d-max (the stop names their spacing and the slips still needed).
    #[arg(long, value_name = "N", default_value = DEFAULTS.max_slips.as_str(), value_parser = max_slips)]
    pub max_slips: u32,
    /// Your foot speed (rod lengths per time unit sqrt(rho A L^4/EI)), in (0, inf): a warning on
    /// stderr when it is above the speed below which this quasi-static drag's first slip holds
    /// in time to 1e-3 (vibrissa::quasistatic; the rows are the same either way).
    #[arg(long, value_name = "V", value_parser = finite_f64, conflicts_with = "speed_mm_s")]
    pub speed: Option<f64>,
    /// Your foot speed in mm/s (needs physical dimensions; keratin's density), as --speed.
    #[arg(long, value_name = "V", value_parser = finite_f64)]
    pub speed_mm_s: Option<f64>,
    #[command(flatten)]
    pub solver: SolverArgs,
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Write the rows to this CSV file ("-": stdout, not with --json). Without it the CSV goes to
    /// stdout (unless --json).
    #[arg(long, value_name = "FILE.csv")]
    pub out: Option<PathBuf>,
    /// Write the rod shapes of all rows to this CSV file (columns point, d, s, x, y, x_lab, phi,
    /// kappa, m, event, as scan's: point is the row's index in the drag's CSV).
    #[arg(long, value_name = "FILE.csv")]
    pub shapes: Option<PathBuf>,
    /// Points per shape in --shapes, in [2, 100000] (needs --shapes).
    #[arg(long, value_name = "N", default_value = DEFAULTS.shape_points.as_str(), value_parser = shape_points, requires = "shapes")]
    pub shape_points: u32,
    /// Print the summary as a JSON object on stdout (cycles, mean and spread of the slip lengths,
    /// force drops and released energies, and every slip).
    #[arg(long)]
    pub json: bool,
}

/// `vibrissa fit`.
#[derive(Args, Debug)]
#[command(
    after_help = "The trace: a CSV file with a column d (or theta: a drag --turn trace, fitted with turned drags) and any of fx, fy, m_base. Its slips are the rows whose event column says slip (the state just before) and slip_end (just after), as vibrissa drag writes them; without an event column, a slip is where d does not increase from one row to the next (the foot held while the tip slides): the row before is the state before, the row after the state after."
)]
pub struct FitArgs {
    /// The measured trace (CSV; "-": stdin).
    #[arg(long, value_name = "FILE.csv")]
    pub trace: PathBuf,
    /// Which base signals to fit, a comma list of fx, fy, m_base. [default: every one the trace has]
    #[arg(long, value_name = "NAMES", value_delimiter = ',')]
    pub signals: Option<Vec<String>>,
    /// Use only the slips' places d (no base signals).
    #[arg(long, conflicts_with = "signals")]
    pub places_only: bool,
    /// Also estimate the surface height eta (straight surfaces).
    #[arg(long)]
    pub fit_eta: bool,
    /// Also estimate the surface inclination (straight surfaces).
    #[arg(long)]
    pub fit_angle: bool,
    /// Also estimate the corrugation's amplitude, wavelength and phase (a comma list of those
    /// names: only these), starting from --corrugation-amplitude, --corrugation-wavelength,
    /// --corrugation-phase (or the scene's [surface] kind = "sine").
    #[arg(long, value_name = "PARTS", num_args = 0..=1, require_equals = true, default_missing_value = "amplitude,wavelength,phase")]
    pub fit_corrugation: Option<String>,
    /// Surface height eta of the model (rod lengths), in (eta_, 1); the start with --fit-eta. [default: scene file's, else 0.75]
    #[arg(long, value_name = "H", value_parser = finite_f64)]
    pub eta: Option<f64>,
    /// Starting static friction coefficient of the fit, in [0, 100] (with --mu-k). [default:
    /// read off the first slips]
    #[arg(long, value_name = "MU", value_parser = finite_f64)]
    pub mu_s: Option<f64>,
    /// Starting kinetic friction coefficient, in [0, --mu-s) (with --mu-s).
    #[arg(long, value_name = "MU", value_parser = finite_f64)]
    pub mu_k: Option<f64>,
    #[command(flatten)]
    pub texture: TextureArgs,
    #[command(flatten)]
    pub solver: SolverArgs,
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Print a JSON object instead of CSV.
    #[arg(long)]
    pub json: bool,
}

/// `vibrissa sweep`.
#[derive(Args, Debug)]
#[command(
    after_help = "LIST: a range a:b:n (n points, both ends included, computed from the decimal digits typed: 0.6:0.95:8 gives 0.6, 0.65, ..., 0.95) or a comma list v1,v2,... Negative values need no '=': --precurvature -1,0,1."
)]
pub struct SweepArgs {
    /// Base scene file (TOML; "-": stdin; read once, so a pipe or FIFO works); the grid flags override its values.
    #[arg(long, value_name = "FILE.toml", help_heading = "Scene")]
    pub scene: Option<PathBuf>,
    /// Surface heights, in (eta_, 1) (see scan --help). [default: scene's, else 0.75]
    #[arg(long, value_name = "LIST", value_parser = axis, help_heading = "Scene")]
    pub eta: Option<Axis>,
    /// Taper ratios RHO in [0.01, 1]. [default: scene's]
    #[arg(long, value_name = "LIST", value_parser = axis, help_heading = "Scene")]
    pub taper: Option<Axis>,
    /// Pre-curvatures K0 (1/L), in [-3, 3]. [default: scene's]
    #[arg(long, value_name = "LIST", value_parser = axis, help_heading = "Scene")]
    pub precurvature: Option<Axis>,
    /// Pre-curvature slopes K1 (1/L^2), in [-6, 6] with |K0 + K1| <= 3. [default: scene's]
    #[arg(long, value_name = "LIST", value_parser = axis, help_heading = "Scene")]
    pub precurvature_slope: Option<Axis>,
    /// Support compliances C in [0, 1000]. [default: scene's]
    #[arg(long, value_name = "LIST", value_parser = axis, help_heading = "Scene")]
    pub support_compliance: Option<Axis>,
    /// Surface angles B (rad), in (-pi/4, pi/4). [default: scene's]
    #[arg(long, value_name = "LIST", value_parser = axis, help_heading = "Scene")]
    pub surface_angle: Option<Axis>,
    /// Radius R of the round tip (rod lengths), in [0, 0.05], for every scene of the grid (see
    /// scan --help). [default: scene's, else 0]
    #[arg(long, value_name = "R", value_parser = finite_f64, help_heading = "Scene")]
    pub tip_radius: Option<f64>,
    #[command(flatten)]
    pub physical: PhysicalArgs,
    /// Methods, a comma list (shooting, multiple-shooting, collocation, collocation6, analytic).
    #[arg(
        long,
        value_name = "LIST",
        default_value = Method::default().name(),
        long_help = method_list()
    )]
    pub method: String,
    /// Solver tolerances (LIST), each in [1e-15, 1e-2].
    #[arg(long, value_name = "LIST", value_parser = axis, default_value = DEFAULTS.tol.as_str())]
    pub tol: Axis,
    /// Stiction coefficients at which the scans stop (slip) (LIST), each in [0, inf]; inf (in a
    /// comma list) never slips. [default: none]
    #[arg(long, value_name = "LIST", value_parser = axis_or_inf)]
    pub mu0: Option<Axis>,
    /// Largest foot displacements of the scans (LIST, rod lengths), each in (0, 2).
    #[arg(long, value_name = "LIST", value_parser = axis, default_value = DEFAULTS.d_max.as_str())]
    pub d_max: Axis,
    /// Points per scan (LIST), whole numbers in [2, 1000000] (as scan).
    #[arg(long, value_name = "LIST", value_parser = axis, default_value = DEFAULTS.points.as_str())]
    pub points: Axis,
    /// Worker threads; more than 4 per core are capped, with a warning. [default: all cores]
    #[arg(long, value_name = "N", value_parser = jobs)]
    pub jobs: Option<u32>,
    /// Run only shard K of N (1-based), e.g. --shard $SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT.
    /// Shard K gets the K-th contiguous block of the grid; shard 1 alone writes the header, so
    /// concatenating shards 1..N gives exactly the unsharded output.
    #[arg(long, value_name = "K/N", value_parser = shard)]
    pub shard: Option<Shard>,
    /// Never write the header line (also not in shard 1).
    #[arg(long)]
    pub no_header: bool,
    /// Add a time_ms column (wall time per scene; makes the output non-reproducible).
    #[arg(long)]
    pub timing: bool,
    /// Output CSV file ("-": stdout). A file gets a journal, FILE.journal, with the finished rows:
    /// after a kill the same command resumes the sweep (see docs/reference.md, "A sweep's journal").
    /// [default: stdout]
    #[arg(long, value_name = "FILE.csv")]
    pub out: Option<PathBuf>,
    /// Check every value, print the grid size, this shard's range and the rows a journal holds on stderr, and exit without solving.
    #[arg(long)]
    pub dry_run: bool,
}

/// `vibrissa figures`.
#[derive(Args, Debug)]
pub struct FiguresArgs {
    /// Output directory (created if missing): figNN.svg and figNN*.csv.
    #[arg(long, value_name = "DIR", default_value = "figures")]
    pub out_dir: PathBuf,
    /// Only these figures (comma list of numbers 2-11). [default: all]
    #[arg(long, value_name = "LIST")]
    pub only: Option<String>,
    /// Numerical method for the numerical curves (the closed forms are always overlaid, so
    /// "analytic" is not offered).
    #[arg(long, default_value = Method::default().name(), value_parser = numerical_method())]
    pub method: Method,
    /// Solver tolerance for the numerical curves, in [1e-15, 1e-2].
    #[arg(long, value_name = "T", value_parser = finite_f64, default_value = DEFAULTS.tol.as_str())]
    pub tol: f64,
}

/// What `vibrissa plot` draws.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum PlotKind {
    /// from the file's columns
    Auto,
    /// mu, the tip force (fx, fy, normal) and m_base against d, events marked (scan --out)
    Scan,
    /// the rod at chosen points in the lab frame with the surface line (scan --shapes)
    Shapes,
    /// a heat map of one column over two grid axes, failed scenes crossed (sweep --out)
    Sweep,
    /// as scan, plus the tip position x_tip, every slip marked (columns d, phase, x_tip, mu,
    /// normal, fx, fy, m_base, event)
    Drag,
    /// mu, the contact force and m_base against the foot angle theta, events marked (whisk --out)
    Whisk,
    /// the rod at chosen angles in the frame of the unturned foot (whisk --shapes)
    WhiskShapes,
    /// m_base, the force at the foot (fx, fy) and the tip's position against time t, events
    /// marked (dynamics drag, dynamics free)
    Dynamics,
    /// the amplitude of m_base against frequency (dynamics --spectrum)
    Spectrum,
}

impl PlotKind {
    /// What kind of file it is, in words (`scan`, `drag`, `whisk shapes`, ...).
    pub fn kind_name(self) -> &'static str {
        match self {
            PlotKind::Auto => "detected",
            PlotKind::Scan => "scan",
            PlotKind::Shapes => "scan shapes",
            PlotKind::Sweep => "sweep",
            PlotKind::Drag => "drag",
            PlotKind::Whisk => "whisk",
            PlotKind::WhiskShapes => "whisk shapes",
            PlotKind::Dynamics => "dynamics",
            PlotKind::Spectrum => "spectrum",
        }
    }
}

/// `vibrissa plot`.
#[derive(Args, Debug)]
#[command(
    after_help = "Columns are read by name: extra columns are ignored, and every value of an event column is marked (one marker and legend entry per event name). Units are the files' (normalized: L, EI/L^2, EI/L)."
)]
pub struct PlotArgs {
    /// The CSV file to draw (written by scan --out, scan --shapes, sweep --out, drag, whisk,
    /// dynamics or dynamics --spectrum).
    #[arg(value_name = "FILE.csv")]
    pub file: PathBuf,
    /// What the file is.
    #[arg(long, value_enum, default_value = "auto")]
    pub kind: PlotKind,
    /// Output SVG file. [default: FILE with the extension .svg]
    #[arg(long, value_name = "FILE.svg")]
    pub out: Option<PathBuf>,
    /// Figure title. [default: the kind and the file name]
    #[arg(long, value_name = "TEXT")]
    pub title: Option<String>,
    /// Shapes: the point indices to draw (the `point` column), a comma list. [default: six
    /// points spread over the file and every point with an event; a drag's --shapes: its first
    /// three slips and their ends]
    #[arg(
        long,
        value_name = "LIST",
        value_delimiter = ',',
        value_parser = point_index,
        help_heading = "Shapes"
    )]
    pub select: Option<Vec<usize>>,
    /// Drag: also draw the rod just before and after the first three slips from this file,
    /// the drag's --shapes (--select chooses other points).
    #[arg(long, value_name = "SHAPES.csv", help_heading = "Drag")]
    pub shapes: Option<PathBuf>,
    /// Drag with --shapes: one picture of the drag over its surface instead, aligned in d: above,
    /// the surface, the rod just before and after every slip and the tip's contacts (lab frame,
    /// the foot at x = d); below, the moment at the foot m_base(d) with the slips marked. The
    /// --corrugation, --grating or --surface-profile flags of the drag draw its surface exactly
    /// (its height read off the tips); without them it is drawn through the tips.
    #[arg(long, requires = "shapes", help_heading = "Drag")]
    pub aligned: bool,
    #[command(flatten, next_help_heading = "Drag: its surface (with --aligned)")]
    pub texture: TextureArgs,
    /// Shapes: inclination of the surface line drawn through the tip (rad), as the scan's --surface-angle.
    #[arg(long, value_name = "B", value_parser = finite_f64, default_value = "0", help_heading = "Shapes")]
    pub surface_angle: f64,
    /// Sweep: column on the horizontal axis. [default: the first grid column that varies]
    #[arg(long, value_name = "COL", help_heading = "Sweep")]
    pub x: Option<String>,
    /// Sweep: column on the vertical axis. [default: the next grid column that varies]
    #[arg(long, value_name = "COL", help_heading = "Sweep")]
    pub y: Option<String>,
    /// Sweep: the column drawn as colour (numbers in eight bins, text one colour per value).
    #[arg(
        long,
        value_name = "COL",
        default_value = "mu_max",
        help_heading = "Sweep"
    )]
    pub z: String,
    /// Sweep: keep only the rows with COL = VALUE (repeatable), to fix the grid axes not drawn.
    #[arg(long = "where", value_name = "COL=VALUE", help_heading = "Sweep")]
    pub r#where: Vec<String>,
}

/// True for flags whose values are numbers, counts, number lists or ranges: they take values
/// starting with '-' (`--alpha -1e-3`, `--precurvature -1,0,1`, `--whisk -0.3,0.05`).
pub fn is_numeric(a: &clap::Arg) -> bool {
    if !a.get_action().takes_values() || a.is_positional() {
        return false;
    }
    let t = a.get_value_parser().type_id();
    t == TypeId::of::<f64>()
        || t == TypeId::of::<u32>()
        || t == TypeId::of::<Axis>()
        || t == TypeId::of::<Shard>()
        || t == TypeId::of::<Point>()
        || t == TypeId::of::<vibrissa::dynamics::Whisk>()
        || a.get_value_names()
            .is_some_and(|n| n.iter().any(|n| n.as_str() == "LIST"))
}

/// The command with every numeric flag taking values that start with '-'. clap's own
/// `allow_negative_numbers` knows only `-1` and `-1.5`, not `-1e-3`, `-.5`, `-inf` or lists.
pub fn command() -> clap::Command {
    hyphen_values(Cli::command())
}

/// `allow_hyphen_values` on the numeric flags of every sub-command (and theirs: `dynamics drag`).
fn hyphen_values(mut cmd: clap::Command) -> clap::Command {
    let names: Vec<String> = cmd
        .get_subcommands()
        .map(|s| s.get_name().to_string())
        .collect();
    for name in names {
        cmd = cmd.mut_subcommand(name, |sub| {
            hyphen_values(sub.mut_args(|a| {
                if is_numeric(&a) {
                    a.allow_hyphen_values(true)
                } else {
                    a
                }
            }))
        });
    }
    cmd
}

/// The values of sub-command `sub`'s flags on this process's command line, as typed (a flag not
/// given: its default, or empty), in the order of `--help`, leaving out the flags in `skip`:
/// (`--flag`, value). A flag added later is included without a change here.
pub fn typed_values(sub: &str, skip: &[&str]) -> Vec<(String, String)> {
    let cmd = command();
    let Ok(m) = cmd.clone().try_get_matches_from(std::env::args_os()) else {
        return Vec::new();
    };
    let (Some(sm), Some(sc)) = (m.subcommand_matches(sub), cmd.find_subcommand(sub)) else {
        return Vec::new();
    };
    sc.get_arguments()
        .filter_map(|a| {
            let long = a.get_long()?;
            if long == "help" || skip.contains(&long) {
                return None;
            }
            let v = sm
                .get_raw(a.get_id().as_str())
                .map(|vs| {
                    vs.map(|v| v.to_string_lossy().into_owned())
                        .collect::<Vec<_>>()
                        .join(" ")
                })
                .unwrap_or_default();
            Some((format!("--{long}"), v))
        })
        .collect()
}

/// A numeric flag directly followed by another flag of the same command (`--alpha --phi1 0.3`):
/// numeric flags take values starting with '-', so clap would take the flag for the value and
/// report the word after it instead. Returns the message.
pub fn missing_value(args: &[std::ffi::OsString]) -> Option<String> {
    let cmd = command();
    let words: Vec<String> = args
        .iter()
        .skip(1)
        .map(|a| a.to_string_lossy().into_owned())
        .collect();
    let pos = words.iter().position(|w| !w.starts_with('-'))?;
    let sub = cmd.find_subcommand(&words[pos])?;
    let long = |w: &str| -> Option<clap::Arg> {
        let name = w.strip_prefix("--")?;
        sub.get_arguments()
            .find(|a| a.get_long() == Some(name))
            .cloned()
    };
    for pair in words[pos + 1..].windows(2) {
        if pair[0] == "--" {
            break;
        }
        if let Some(a) = long(&pair[0]) {
            let next = pair[1].split('=').next().unwrap_or("");
            if is_numeric(&a) && (long(next).is_some() || next == "--help") {
                return Some(format!(
                    "{} needs a value; the next word is the flag {next}",
                    pair[0]
                ));
            }
        }
    }
    None
}

/// `--mu-k-table`'s points `(|v|, mu_k)` (the library checks their order and range).
#[derive(Clone, Debug)]
pub struct SpeedTable(pub Vec<[f64; 2]>);

/// `A,F` of `dynamics drag --whisk` (the ranges are the library's, checked with the options).
fn whisk_arg(text: &str) -> Result<vibrissa::dynamics::Whisk, String> {
    let (a, f) = text
        .split_once(',')
        .ok_or_else(|| format!("'{text}' is not A,F (amplitude in rad, whisks per time unit)"))?;
    Ok(vibrissa::dynamics::Whisk {
        amplitude: finite_f64(a)?,
        frequency: finite_f64(f)?,
    })
}

/// Parses `V:MU,V:MU,...`.
fn speed_table(text: &str) -> Result<SpeedTable, String> {
    text.split(',')
        .map(|pair| {
            let (v, mu) = pair
                .split_once(':')
                .ok_or_else(|| format!("'{pair}' is not V:MU"))?;
            let num = |t: &str| {
                t.trim()
                    .parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite())
                    .ok_or_else(|| format!("'{t}' is not a finite number"))
            };
            Ok([num(v)?, num(mu)?])
        })
        .collect::<Result<Vec<_>, String>>()
        .map(SpeedTable)
}
