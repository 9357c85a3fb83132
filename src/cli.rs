//! Command-line definitions (clap derive). Every flag says its unit and default.

use clap::{Args, Parser, Subcommand, ValueEnum};
use std::path::PathBuf;

/// Parse a finite `f64` (NaN and infinities are rejected at the command line).
pub fn finite_f64(s: &str) -> Result<f64, String> {
    let v: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("'{s}' is not a number"))?;
    if v.is_finite() {
        Ok(v)
    } else {
        Err(format!("'{s}' is not a finite number"))
    }
}

/// Parse a strictly positive finite `f64`.
pub fn positive_f64(s: &str) -> Result<f64, String> {
    let v = finite_f64(s)?;
    if v > 0.0 {
        Ok(v)
    } else {
        Err(format!("{v} must be > 0"))
    }
}

/// Parse a non-negative finite `f64`.
pub fn nonneg_f64(s: &str) -> Result<f64, String> {
    let v = finite_f64(s)?;
    if v >= 0.0 {
        Ok(v)
    } else {
        Err(format!("{v} must be >= 0"))
    }
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
reaches mu0 and lifts off where N reaches 0. m_base = m(0) is the internal moment at the foot (the paper's clamp moment is m0 = -m_base).",
    allow_negative_numbers = true
)]
pub struct Cli {
    /// The command to run.
    #[command(subcommand)]
    pub command: Command,
}

/// Sub-commands.
#[derive(Subcommand, Debug)]
pub enum Command {
    /// Solve one tip-loaded rod: given alpha and the tip slope phi1 (or the tip height eta).
    #[command(allow_negative_numbers = true)]
    Solve(SolveArgs),
    /// Stiction scan: drag the foot by d while the tip sticks at height eta; report mu(d).
    #[command(allow_negative_numbers = true)]
    Scan(ScanArgs),
    /// Grid of stiction scans over scene parameters, in parallel, one CSV row per scene.
    #[command(allow_negative_numbers = true)]
    Sweep(SweepArgs),
    /// Read the stiction coefficient mu0 = mu(d0) off a scan at the slip displacement d0.
    #[command(allow_negative_numbers = true)]
    Infer(InferArgs),
    /// Regenerate the paper's Figures 2-11 as SVG files, with the CSV data behind each.
    Figures(FiguresArgs),
}

/// Numerical method.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum MethodArg {
    /// single shooting (adaptive Runge-Kutta, Newton on the unknown initial values)
    Shooting,
    /// multiple shooting (several segments)
    MultipleShooting,
    /// Lobatto IIIA collocation of order 4 with mesh adaptation
    Collocation,
    /// Lobatto IIIA collocation of order 6 with mesh adaptation
    Collocation6,
    /// closed-form elliptic-integral solution (uniform clamped straight rod only)
    Analytic,
}

impl MethodArg {
    /// The name used on the command line and in CSV files.
    pub fn name(self) -> &'static str {
        match self {
            MethodArg::Shooting => "shooting",
            MethodArg::MultipleShooting => "multiple-shooting",
            MethodArg::Collocation => "collocation",
            MethodArg::Collocation6 => "collocation6",
            MethodArg::Analytic => "analytic",
        }
    }
}

/// Branch of the solution family for `solve`.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum BranchArg {
    /// no flex point (curvature <= 0 all along)
    Convex,
    /// one flex point (curvature > 0 near the foot, < 0 near the tip)
    Flex,
}

/// Scene flags shared by all commands; they override the values of `--scene`.
#[derive(Args, Debug, Clone, Default)]
pub struct SceneArgs {
    /// Scene file (TOML, the fields of vibrissa::Scene; see README "Scene files"). Flags override its values.
    #[arg(long, value_name = "FILE.toml", help_heading = "Scene")]
    pub scene: Option<PathBuf>,
    /// Conical taper: tip/base radius ratio RHO in (0, 1]; b(s) = (1 - (1 - RHO) s)^-4. [default: 1, uniform]
    #[arg(long, value_name = "RHO", value_parser = finite_f64, help_heading = "Scene")]
    pub taper: Option<f64>,
    /// Pre-curvature at the foot K0 (1/L; > 0 bends the rest shape counter-clockwise). [default: 0]
    #[arg(long, value_name = "K0", value_parser = finite_f64, help_heading = "Scene")]
    pub precurvature: Option<f64>,
    /// Pre-curvature slope K1 (1/L^2): kappa0(s) = K0 + K1 s. [default: 0]
    #[arg(long, value_name = "K1", value_parser = finite_f64, help_heading = "Scene")]
    pub precurvature_slope: Option<f64>,
    /// Compliance C >= 0 of the rotational spring at the foot (1/(EI/L)): phi(0) = pi/2 + C m(0); 0 = clamp. [default: 0]
    #[arg(long, value_name = "C", value_parser = finite_f64, help_heading = "Scene")]
    pub support_compliance: Option<f64>,
    /// Inclination B of the surface line through the contact point (rad; 0 = horizontal). [default: 0]
    #[arg(long, value_name = "B", value_parser = finite_f64, help_heading = "Scene")]
    pub surface_angle: Option<f64>,
    /// Physical rod length (mm); with --youngs-modulus-gpa and --base-diameter-um adds physical-unit columns.
    #[arg(long, value_name = "MM", value_parser = positive_f64, help_heading = "Physical units")]
    pub length_mm: Option<f64>,
    /// Young's modulus (GPa).
    #[arg(long, value_name = "GPA", value_parser = positive_f64, help_heading = "Physical units")]
    pub youngs_modulus_gpa: Option<f64>,
    /// Base diameter (µm); I = pi d^4 / 64.
    #[arg(long, value_name = "UM", value_parser = positive_f64, help_heading = "Physical units")]
    pub base_diameter_um: Option<f64>,
}

/// Solver flags shared by solve, scan and infer.
#[derive(Args, Debug, Clone)]
pub struct SolverArgs {
    /// Numerical method ("analytic" only for the uniform clamped straight rod).
    #[arg(long, value_enum, default_value = "shooting")]
    pub method: MethodArg,
    /// Tolerance of the numerical solver (residual / local error), dimensionless.
    #[arg(long, value_name = "T", value_parser = positive_f64, default_value = "1e-10")]
    pub tol: f64,
}

/// `vibrissa solve`.
#[derive(Args, Debug)]
pub struct SolveArgs {
    /// Force angle alpha (rad): 0 = straight down, < 0 = rotated clockwise (friction to -x).
    #[arg(long, value_name = "A", value_parser = finite_f64)]
    pub alpha: f64,
    /// Tip slope phi1 = phi(1) (rad).
    #[arg(long, value_name = "P", value_parser = finite_f64, required_unless_present = "eta", conflicts_with = "eta")]
    pub phi1: Option<f64>,
    /// Tip height eta (rod lengths): solve for the tip slope that puts the tip at y(1) = eta.
    #[arg(long, value_name = "H", value_parser = finite_f64)]
    pub eta: Option<f64>,
    /// Solution family.
    #[arg(long, value_enum, default_value = "convex")]
    pub branch: BranchArg,
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
    /// Number of points of --shape-out, uniform in s (>= 2).
    #[arg(long, value_name = "N", default_value_t = 101, value_parser = clap::value_parser!(u32).range(2..=1_000_000))]
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
    /// Surface height eta (rod lengths), in (0.45695, 1) for the uniform rod. [default: scene file's, else 0.75]
    #[arg(long, value_name = "H", value_parser = finite_f64)]
    pub eta: Option<f64>,
    /// Largest foot displacement d (rod lengths).
    #[arg(long, value_name = "D", value_parser = positive_f64, default_value = "0.5")]
    pub d_max: f64,
    /// Number of output points, uniform in d from 0 to --d-max (>= 2).
    #[arg(long, value_name = "N", default_value_t = 201, value_parser = clap::value_parser!(u32).range(2..=10_000_000))]
    pub points: u32,
    /// Stiction coefficient: stop where |mu| reaches it (the tip slips, backwards for mu = mu0,
    /// forwards for mu = -mu0). mu = F.t/N is the signed friction ratio, tan(beta - alpha). [default: none]
    #[arg(long, value_name = "MU", value_parser = nonneg_f64)]
    pub mu0: Option<f64>,
    #[command(flatten)]
    pub solver: SolverArgs,
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Write the scan points to this CSV file (written to a temporary file, renamed when complete).
    /// Without it the CSV goes to stdout (unless --json).
    #[arg(long, value_name = "FILE.csv")]
    pub out: Option<PathBuf>,
    /// Write the rod shapes of all scan points to this CSV file (columns point, d, s, x, y, phi, kappa).
    #[arg(long, value_name = "FILE.csv")]
    pub shapes: Option<PathBuf>,
    /// Points per shape in --shapes (>= 2).
    #[arg(long, value_name = "N", default_value_t = 41, value_parser = clap::value_parser!(u32).range(2..=100_000))]
    pub shape_points: u32,
    /// Print the summary as a JSON object on stdout.
    #[arg(long)]
    pub json: bool,
}

/// `vibrissa infer`.
#[derive(Args, Debug)]
pub struct InferArgs {
    /// Surface height eta (rod lengths). [default: scene file's, else 0.75]
    #[arg(long, value_name = "H", value_parser = finite_f64)]
    pub eta: Option<f64>,
    /// Measured foot displacement at which the tip slipped (rod lengths).
    #[arg(long, value_name = "D", value_parser = finite_f64)]
    pub d0: f64,
    /// Largest foot displacement the underlying scan explores (rod lengths).
    #[arg(long, value_name = "D", value_parser = positive_f64, default_value = "0.5")]
    pub d_max: f64,
    /// Points of the underlying scan (>= 2).
    #[arg(long, value_name = "N", default_value_t = 201, value_parser = clap::value_parser!(u32).range(2..=10_000_000))]
    pub points: u32,
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
pub struct SweepArgs {
    /// Surface heights: a range a:b:n (n points, both ends included) or a comma list. [default: scene's, else 0.75]
    #[arg(long, value_name = "LIST")]
    pub eta: Option<String>,
    /// Taper ratios RHO in (0, 1] (range a:b:n or list). [default: scene's]
    #[arg(long, value_name = "LIST")]
    pub taper: Option<String>,
    /// Pre-curvatures K0 (1/L) (range or list). [default: scene's]
    #[arg(long, value_name = "LIST")]
    pub precurvature: Option<String>,
    /// Pre-curvature slopes K1 (1/L^2) (range or list). [default: scene's]
    #[arg(long, value_name = "LIST")]
    pub precurvature_slope: Option<String>,
    /// Support compliances C >= 0 (range or list). [default: scene's]
    #[arg(long, value_name = "LIST")]
    pub support_compliance: Option<String>,
    /// Surface angles B (rad) (range or list). [default: scene's]
    #[arg(long, value_name = "LIST")]
    pub surface_angle: Option<String>,
    /// Methods, a comma list (shooting, multiple-shooting, collocation, collocation6, analytic).
    #[arg(long, value_name = "LIST", default_value = "shooting")]
    pub method: String,
    /// Solver tolerances (range or list).
    #[arg(long, value_name = "LIST", default_value = "1e-10")]
    pub tol: String,
    /// Base scene file (TOML); the grid flags override its values.
    #[arg(long, value_name = "FILE.toml")]
    pub scene: Option<PathBuf>,
    /// Largest foot displacement of each scan (rod lengths).
    #[arg(long, value_name = "D", value_parser = positive_f64, default_value = "0.5")]
    pub d_max: f64,
    /// Points per scan (>= 2).
    #[arg(long, value_name = "N", default_value_t = 101, value_parser = clap::value_parser!(u32).range(2..=10_000_000))]
    pub points: u32,
    /// Stiction coefficient at which each scan stops (slip). [default: none]
    #[arg(long, value_name = "MU", value_parser = nonneg_f64)]
    pub mu0: Option<f64>,
    /// Worker threads. [default: all cores]
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=4096))]
    pub jobs: Option<u32>,
    /// Run only shard K of N (1-based), e.g. --shard $SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT.
    /// Shard K gets the K-th contiguous block of the grid; shard 1 alone writes the header, so
    /// concatenating shards 1..N gives exactly the unsharded output.
    #[arg(long, value_name = "K/N")]
    pub shard: Option<String>,
    /// Never write the header line (also not in shard 1).
    #[arg(long)]
    pub no_header: bool,
    /// Add a time_ms column (wall time per scene; makes the output non-reproducible).
    #[arg(long)]
    pub timing: bool,
    /// Output CSV file (temporary file renamed when complete). [default: stdout]
    #[arg(long, value_name = "FILE.csv")]
    pub out: Option<PathBuf>,
    /// Print the grid size and this shard's range on stderr and exit without solving.
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
    /// Numerical method for the numerical curves.
    #[arg(long, value_enum, default_value = "shooting")]
    pub method: MethodArg,
    /// Solver tolerance for the numerical curves.
    #[arg(long, value_name = "T", value_parser = positive_f64, default_value = "1e-10")]
    pub tol: f64,
}
