//! Natural frequencies and mode shapes of a static state, and its stability.
//!
//! The equations of motion of the planar inextensible rod (docs/model.md, "The rod in time"),
//! linearized about a static state `z = (x, y, φ, m)` with the internal force `G` (constant: the
//! total contact force beyond), for perturbations `∝ e^{iωt}`, `λ = ω²`:
//!
//! ```text
//!     δx' = −sin φ δφ,      δy' = cos φ δφ,      δφ' = b δm,
//!     δm' = (G·e) δφ − e⊥·δG − λ j δφ,           δG' = −λ μ δr
//! ```
//!
//! (`e = (cos φ, sin φ)`, `e⊥ = (−sin φ, cos φ)`, `μ` the mass and `j` the rotary inertia per
//! length, module `inertia`). The foot: `δr(0) = 0`, `δφ(0) = c δm(0)` (the rotational spring;
//! the support's damper does not enter undamped modes). The tip: free (`δm = 0`, `δG = 0`: a
//! dead load keeps its value), pinned or stuck (`δr = 0`, `δm = 0`), or sliding without friction
//! on a line of normal `n` (`n·δr = 0`, `δm = 0`, `t·δG = 0`). With the three columns started by
//! `δm(0)`, `δGx(0)`, `δGy(0)`, the three tip conditions make a 3×3 matrix `D(λ)`; the
//! eigenvalues are the roots of `det D(λ)` (an entire function of `λ`: no poles), found by a
//! sweep in `β = sign(λ)|λ|^(1/4)` (the roots of the uniform rod are nearly equally spaced in β)
//! from below the lowest possible eigenvalue, then Brent's method (`elastica::roots`) on each bracket. The
//! mode shape is the state along the rod of `D`'s null vector.
//!
//! At `λ = 0` the problem is the linearization of the static equations with the same conditions,
//! so `ω₁² → 0` exactly where the static family folds, and a state with `ω₁² < 0` is unstable.

use crate::inertia::mass_density;
use crate::parts::Stiffness;
use crate::profile::{General, Profile};
use crate::report::ScanPoint;
use crate::sode::{integrate, SodeStats};
use crate::{Rod, Surface, VibrissaError};
use nalgebra::Matrix3;
use serde::Serialize;
use std::f64::consts::FRAC_PI_2;
use std::fmt;

/// How the tip is held in the static state and its perturbations.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case", tag = "kind")]
pub enum TipCondition {
    /// Free (a load on it, if any, is a dead load).
    Free,
    /// Pinned, or stuck on a surface by friction: the tip does not move.
    Pinned,
    /// Sliding without friction on a line of inclination `angle`.
    Sliding {
        /// Inclination β of the line (rad).
        angle: f64,
    },
}

impl TipCondition {
    /// `free`, `pinned`, `sliding`.
    pub fn name(self) -> &'static str {
        match self {
            TipCondition::Free => "free",
            TipCondition::Pinned => "pinned",
            TipCondition::Sliding { .. } => "sliding",
        }
    }
}

/// The static state whose vibrations are asked for, by its values at the foot (which fix the
/// whole rod: integrated from the foot they give the shape, as `locate` does): `m(0)` and the
/// internal force, the total contact force `(fx, fy)` on the rod.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct BaseLoad {
    /// `m(0)`.
    pub m_base: f64,
    /// Contact force on the rod, x.
    pub fx: f64,
    /// Contact force on the rod, y.
    pub fy: f64,
}

/// Options of [`modes`].
#[derive(Clone, Debug, PartialEq, Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ModeOptions {
    /// How many of the lowest modes, in `[1, 50]`. Default 3.
    pub count: usize,
    /// Tolerance of the integrations along the rod, in `[1e-14, 1e-6]`. Default 1e-12
    /// (frequencies to about 1e-10 relative).
    pub tol: f64,
    /// Radius of gyration of the foot's cross-section over the length, `g0 = r(0)/(2L)` (rotary
    /// inertia `j = g0²/b`), in `[0, 0.1]`. Default 0 (Euler–Bernoulli).
    pub rotary_inertia: f64,
    /// Points of each mode shape, uniform in `s` (0: no shapes), in `[0, 100000]`. Default 0.
    pub shape_points: usize,
}

impl Default for ModeOptions {
    fn default() -> Self {
        ModeOptions {
            count: 3,
            tol: 1e-12,
            rotary_inertia: 0.0,
            shape_points: 0,
        }
    }
}

impl ModeOptions {
    /// Checks every value against [`limits`](crate::limits).
    pub fn validate(&self) -> Result<(), VibrissaError> {
        use crate::limits;
        limits::MODE_COUNT.check_count("count", self.count)?;
        limits::MODE_TOL.check("tol", self.tol)?;
        limits::ROTARY_INERTIA.check("rotary_inertia", self.rotary_inertia)?;
        if self.shape_points > 0 {
            limits::SHAPE_POINTS.check_count("shape_points", self.shape_points)?;
        }
        Ok(())
    }
}

/// One point of a mode shape.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ModePoint {
    /// Arc length.
    pub s: f64,
    /// Displacement, x (the largest `|δr|` along the rod is 1).
    pub dx: f64,
    /// Displacement, y.
    pub dy: f64,
    /// Rotation.
    pub dphi: f64,
    /// Bending moment.
    pub dm: f64,
}

/// One mode.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Mode {
    /// `ω²` (negative: the state is unstable, growing like `e^{√(−ω²) t}`).
    pub omega2: f64,
    /// `ω` (NaN where `ω² < 0`), in the normalized time of docs/model.md.
    pub omega: f64,
    /// The shape, if asked for.
    pub shape: Vec<ModePoint>,
}

/// Work done.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct ModeStats {
    /// Values of the characteristic function.
    pub evaluations: usize,
    /// Integration steps (accepted) along the rod.
    pub steps: usize,
    /// Right-hand sides evaluated.
    pub rhs_evals: usize,
}

impl fmt::Display for ModeStats {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} characteristic values, {} steps, {} right-hand sides",
            self.evaluations, self.steps, self.rhs_evals
        )
    }
}

/// The modes of a static state.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ModesResult {
    /// The tip condition.
    pub tip: TipCondition,
    /// The lowest modes, in increasing `ω²`.
    pub modes: Vec<Mode>,
    /// Whether the state is stable (`ω₁² > 0`).
    pub stable: bool,
    /// Work done.
    pub stats: ModeStats,
}

impl fmt::Display for ModesResult {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} modes, tip {}, {}: omega^2 =",
            self.modes.len(),
            self.tip.name(),
            if self.stable { "stable" } else { "unstable" }
        )?;
        for m in &self.modes {
            write!(f, " {:.10e}", m.omega2)?;
        }
        write!(f, " ({})", self.stats)
    }
}

/// The linear problem of one state.
struct Linear<'a> {
    profile: General,
    stiffness: &'a Stiffness,
    compliance: f64,
    load: BaseLoad,
    tip: TipCondition,
    g0sq: f64,
    tol: f64,
    /// The static state is the straight rod along `y` (no rest curvature, `m(0) = 0`, no
    /// transverse force): its tip cannot move along the rod (inextensible, clamped foot), so a
    /// tip condition on that motion is void and the axial force is left undetermined. Its
    /// transverse problem alone is posed (2×2, the columns `δm(0)`, `δGx(0)`).
    straight: bool,
    /// `∫ (μ/b)^(1/4) ds`: the columns grow like `exp(|λ|^(1/4) ∫ (μ/b)^(1/4) ds)` along the
    /// rod (the local wave number of `δm'' ≈ ±λ μ b δm`), see [`Linear::det`].
    growth: f64,
    stats: ModeStats,
}

/// The rod (4) and three perturbation columns (6 each).
const NY: usize = 22;

/// The most the columns may grow between two orthonormalizations of [`Linear::det`], `e^8`.
const PIECE_GROWTH: f64 = 8.0;

impl<'r> Linear<'r> {
    fn new(rod: &'r Rod, load: &BaseLoad, tip: TipCondition, opts: &ModeOptions) -> Self {
        Linear {
            profile: rod.profile(1.0),
            stiffness: rod.stiffness(),
            compliance: rod.support_compliance(),
            load: *load,
            tip,
            g0sq: opts.rotary_inertia * opts.rotary_inertia,
            tol: opts.tol,
            straight: matches!(rod.precurvature(), crate::parts::Precurvature::None)
                && load.m_base == 0.0
                && load.fx == 0.0,
            growth: growth_rate(rod),
            stats: ModeStats::default(),
        }
    }

    fn start(&self) -> [f64; NY] {
        let c = self.compliance;
        let m0 = self.load.m_base;
        let mut y = [0.0; NY];
        y[2] = FRAC_PI_2 + c * m0;
        y[3] = m0;
        // columns: δm(0) (with δφ(0) = c δm(0)), δGx(0), δGy(0)
        y[4 + 2] = c;
        y[4 + 3] = 1.0;
        y[10 + 4] = 1.0;
        y[16 + 5] = 1.0;
        y
    }

    fn rhs(&self, lam: f64, s: f64, y: &[f64; NY]) -> [f64; NY] {
        let (b, k0) = (self.profile.b(s), self.profile.k0(s));
        let mu = mass_density(self.stiffness, s);
        let j = self.g0sq / b;
        let (gx, gy) = (self.load.fx, self.load.fy);
        let (sp, cp) = y[2].sin_cos();
        let mut d = [0.0; NY];
        d[0] = cp;
        d[1] = sp;
        d[2] = k0 + b * y[3];
        d[3] = gx * sp - gy * cp;
        let ge = gx * cp + gy * sp;
        for q in 0..3 {
            let o = 4 + 6 * q;
            let (dx, dy, dphi, dm, dgx, dgy) =
                (y[o], y[o + 1], y[o + 2], y[o + 3], y[o + 4], y[o + 5]);
            d[o] = -sp * dphi;
            d[o + 1] = cp * dphi;
            d[o + 2] = b * dm;
            d[o + 3] = (ge - lam * j) * dphi + sp * dgx - cp * dgy;
            d[o + 4] = -lam * mu * dx;
            d[o + 5] = -lam * mu * dy;
        }
        d
    }

    /// The tip conditions of one column at the tip state `y` (offset `o`).
    fn tip_rows(&self, y: &[f64; NY], o: usize) -> [f64; 3] {
        if self.straight {
            // transverse (x) conditions only; the third entry is unused
            let pinned = match self.tip {
                TipCondition::Free => false,
                TipCondition::Pinned => true,
                // a line across the rod (sin β = 0) holds only the axial motion
                TipCondition::Sliding { angle } => angle.sin() != 0.0,
            };
            return if pinned {
                [y[o], y[o + 3], 0.0]
            } else {
                [y[o + 3], y[o + 4], 0.0]
            };
        }
        match self.tip {
            TipCondition::Free => [y[o + 3], y[o + 4], y[o + 5]],
            TipCondition::Pinned => [y[o], y[o + 1], y[o + 3]],
            TipCondition::Sliding { angle } => {
                let (sb, cb) = angle.sin_cos();
                // normal (−sin β, cos β), tangent −(cos β, sin β)
                [
                    -sb * y[o] + cb * y[o + 1],
                    y[o + 3],
                    -cb * y[o + 4] - sb * y[o + 5],
                ]
            }
        }
    }

    /// The rod and its columns `y` at `s0` carried to `s1` at `λ` (steps and right-hand sides
    /// counted; `what` names the solve in an error).
    fn carry(
        &mut self,
        lam: f64,
        (s0, s1): (f64, f64),
        y: [f64; NY],
        what: impl FnOnce() -> String,
    ) -> Result<[f64; NY], VibrissaError> {
        let mut st = SodeStats::default();
        let yb = integrate::<NY>(
            &mut |s, y| self.rhs(lam, s, y),
            s0,
            s1,
            y,
            self.tol,
            &mut st,
            &mut |_, _| {},
        );
        self.stats.steps += st.steps;
        self.stats.rhs_evals += st.rhs;
        yb.map_err(|e| VibrissaError::NoConvergence {
            what: what(),
            reason: e.to_string(),
        })
    }

    /// `D(λ)` with its columns scaled to unit length, and the unscaled matrix.
    fn matrix(&mut self, lam: f64) -> Result<(Matrix3<f64>, [f64; 3]), VibrissaError> {
        self.stats.evaluations += 1;
        let yb = self.carry(lam, (0.0, 1.0), self.start(), || {
            format!("the linearized rod at omega^2 = {lam:e}")
        })?;
        Ok(self.tip_matrix(&yb))
    }

    /// `D` of the columns at the tip `yb` and the norms of its columns.
    fn tip_matrix(&self, yb: &[f64; NY]) -> (Matrix3<f64>, [f64; 3]) {
        let mut m = Matrix3::zeros();
        let mut norms = [0.0; 3];
        let dim = if self.straight { 2 } else { 3 };
        for q in 0..dim {
            let r = self.tip_rows(yb, 4 + 6 * q);
            norms[q] = (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt().max(1e-300);
            for i in 0..3 {
                m[(i, q)] = r[i];
            }
        }
        if self.straight {
            // block diag(D₂, 1): the same determinant, a null vector without the third column
            m[(2, 2)] = 1.0;
            norms[2] = 1.0;
        }
        (m, norms)
    }

    /// `det D(λ)` with unit columns (the sign is what the sweep and Brent need), of columns
    /// orthonormalized along the rod where they grow by more than `e^8`: the rod is integrated
    /// in `k = ⌈|λ|^(1/4) ∫(μ/b)^(1/4) ds / 8⌉` equal pieces and after each the perturbation
    /// columns `Y` are replaced by `Q` of `Y = Q R` (modified Gram–Schmidt, `R` upper
    /// triangular with a positive diagonal). `D = T Y = T Q R` for the tip's conditions `T`, so
    /// `det D = det(T Q) det R` with `det R > 0`: the same sign and the same roots, continuous in
    /// `λ`. With `k = 1` nothing is orthonormalized (the shot of [`Linear::matrix`] itself).
    ///
    /// Why: a single shot's columns all turn towards the fastest-growing solution, and their
    /// determinant is rounding once the growth passes about `e^16`: for the rod tapered to
    /// ρ = 0.1 under its scan's contact force (`∫(μ/b)^(1/4) ≈ 0.45`, the sweep starting at
    /// λ = −8e6, growth `e^24`) the sweep found sign changes at λ = −7.95e6, −7.92e6,
    /// −7.86e6, and `scan --modes --taper 0.1 --eta 0.97` called every row unstable.
    fn det(&mut self, lam: f64) -> Result<f64, VibrissaError> {
        let pieces = (lam.abs().powf(0.25) * self.growth / PIECE_GROWTH).ceil();
        if pieces.is_nan() || pieces <= 1.0 {
            let (m, n) = self.matrix(lam)?;
            return Ok(m.determinant() / (n[0] * n[1] * n[2]));
        }
        let pieces = pieces.min(1e4) as usize;
        let dim = if self.straight { 2 } else { 3 };
        let mut y = self.start();
        let mut s0 = 0.0;
        for k in 1..=pieces {
            let s1 = k as f64 / pieces as f64;
            y = self.carry(lam, (s0, s1), y, || {
                format!("the linearized rod at omega^2 = {lam:e}")
            })?;
            orthonormalize(&mut y, dim).map_err(|reason| VibrissaError::NoConvergence {
                what: format!("the linearized rod at omega^2 = {lam:e}"),
                reason: format!("{reason} at s = {s1}"),
            })?;
            s0 = s1;
        }
        self.stats.evaluations += 1;
        let (m, n) = self.tip_matrix(&y);
        Ok(m.determinant() / (n[0] * n[1] * n[2]))
    }
}

/// `∫ (μ/b)^(1/4) ds` of `rod` (the trapezoidal rule on 100 intervals; [`Linear::det`]).
fn growth_rate(rod: &Rod) -> f64 {
    let (profile, stiffness) = (rod.profile(1.0), rod.stiffness());
    let f = |i: usize| {
        let s = i as f64 / 100.0;
        (mass_density(stiffness, s) / profile.b(s)).powf(0.25)
    };
    (0..100).map(|i| 0.5 * (f(i) + f(i + 1))).sum::<f64>() / 100.0
}

/// The first `dim` perturbation columns of `y` made orthonormal (modified Gram–Schmidt, in
/// order: each column less its parts along the ones before, then scaled to unit length).
/// Errors: a column that vanishes or is not a number (the columns no longer independent).
fn orthonormalize(y: &mut [f64; NY], dim: usize) -> Result<(), &'static str> {
    for q in 0..dim {
        let oq = 4 + 6 * q;
        for p in 0..q {
            let op = 4 + 6 * p;
            let dot: f64 = (0..6).map(|i| y[op + i] * y[oq + i]).sum();
            for i in 0..6 {
                y[oq + i] -= dot * y[op + i];
            }
        }
        let norm = (0..6).map(|i| y[oq + i] * y[oq + i]).sum::<f64>().sqrt();
        if !(norm > 0.0 && norm.is_finite()) {
            return Err("the perturbation columns are no longer independent");
        }
        for i in 0..6 {
            y[oq + i] /= norm;
        }
    }
    Ok(())
}

/// The lowest `opts.count` modes of the static state with foot values `load` and tip `tip` of
/// the rod `rod` (its stiffness, rest curvature and support spring; inertia from module
/// `inertia`).
///
/// ```
/// use vibrissa::modes::{modes, BaseLoad, ModeOptions, TipCondition};
/// let r = modes(&vibrissa::Rod::uniform(), &BaseLoad::default(), TipCondition::Free,
///               &ModeOptions::default())?;
/// // the clamped–free rod: ω₁ = β₁², β₁ = 1.87510406871196
/// assert!((r.modes[0].omega / 1.87510406871196f64.powi(2) - 1.0).abs() < 1e-9);
/// # Ok::<(), vibrissa::VibrissaError>(())
/// ```
pub fn modes(
    rod: &Rod,
    load: &BaseLoad,
    tip: TipCondition,
    opts: &ModeOptions,
) -> Result<ModesResult, VibrissaError> {
    opts.validate()?;
    for (name, v) in [("m_base", load.m_base), ("fx", load.fx), ("fy", load.fy)] {
        if !v.is_finite() {
            return Err(VibrissaError::range(name, v, "finite"));
        }
    }
    let mut lin = Linear::new(rod, load, tip, opts);
    let roots = lowest_roots(&mut lin, opts.count)?;
    let mut out = Vec::with_capacity(roots.len());
    for lam in roots {
        let shape = if opts.shape_points > 0 {
            shape(&mut lin, lam, opts.shape_points)?
        } else {
            Vec::new()
        };
        out.push(Mode {
            omega2: lam,
            omega: if lam >= 0.0 { lam.sqrt() } else { f64::NAN },
            shape,
        });
    }
    Ok(ModesResult {
        tip,
        stable: out[0].omega2 > 0.0,
        modes: out,
        stats: lin.stats,
    })
}

/// The modes of a scan's point: the tip stuck where it touches (only the tip may touch; a
/// state with a side contact is refused).
pub fn modes_of_point(
    rod: &Rod,
    _surface: &Surface,
    p: &ScanPoint,
    opts: &ModeOptions,
) -> Result<ModesResult, VibrissaError> {
    if p.contact.name() != "tip" {
        return Err(VibrissaError::MethodUnavailable {
            method: "modes".into(),
            reason: format!(
                "the state at d = {} has the contacts '{}'; the modes know a free, pinned or \
                 stuck tip, not side contacts",
                p.d,
                p.contact.name()
            ),
        });
    }
    let load = BaseLoad {
        m_base: p.m_base,
        fx: p.fx,
        fy: p.fy,
    };
    modes(rod, &load, TipCondition::Pinned, opts)
}

/// The tolerance of [`lowest_roots`]'s sweep, where only the signs of `det D(λ)` at steps of
/// 0.05 in `β` are read (the options' `tol`, 1e-12 by default, where it is looser).
const SWEEP_TOL: f64 = 1e-6;

/// The lowest `count` roots of `det D(λ)`: a sweep in `β` (`λ = sign(β)β⁴`) with steps of 0.05
/// from below the lowest possible eigenvalue, each sign change refined by Brent.
///
/// The sweep reads signs only, so it integrates to [`SWEEP_TOL`]; each bracket it finds is
/// refined from its two ends at the options' `tol`. A bracket whose ends do not differ in sign
/// at `tol` (a root within the sweep's error of a step's end) sends the whole search to the
/// sweep at `tol`, so the roots are those of that sweep whenever the two sweeps bracket alike,
/// bit for bit (the refinement starts from the same ends with the same values).
fn lowest_roots(lin: &mut Linear<'_>, count: usize) -> Result<Vec<f64>, VibrissaError> {
    lowest_roots_swept_at(lin, count, SWEEP_TOL)
}

/// [`lowest_roots`] with the sweep at `sweep_tol` (where it is looser than `lin.tol`).
fn lowest_roots_swept_at(
    lin: &mut Linear<'_>,
    count: usize,
    sweep_tol: f64,
) -> Result<Vec<f64>, VibrissaError> {
    let tight = lin.tol;
    let loose = tight.max(sweep_tol);
    if loose > tight {
        lin.tol = loose;
        let found = sweep(lin, count, tight);
        lin.tol = tight;
        match found {
            Ok(Some(roots)) => return Ok(roots),
            Ok(None) => {}
            Err(e) => return Err(e),
        }
    }
    sweep(lin, count, tight)?.ok_or_else(|| VibrissaError::NoConvergence {
        what: "the modes".into(),
        reason: "a bracket of the sweep lost its sign change".into(),
    })
}

/// The sweep of [`lowest_roots`] at `lin.tol`, each bracket refined at `tight` (`None`: a
/// bracket's ends have one sign at `tight`).
fn sweep(
    lin: &mut Linear<'_>,
    count: usize,
    tight: f64,
) -> Result<Option<Vec<f64>>, VibrissaError> {
    let lam_of = |beta: f64| beta.signum() * beta.powi(4);
    // below the lowest eigenvalue: a compressive load lowers ω² by at most ~|G|·b/μ (the
    // geometric stiffness against the mass); a generous margin
    let g = lin.load.fx.hypot(lin.load.fy);
    let (mut bmax, mut mumin) = (1.0f64, 1.0f64);
    for i in 0..=100 {
        let s = i as f64 / 100.0;
        bmax = bmax.max(lin.profile.b(s));
        mumin = mumin.min(mass_density(lin.stiffness, s));
    }
    let lam_lo = -10.0 * (1.0 + g * bmax / mumin);
    let step = 0.05;
    let mut beta = -lam_lo.abs().powf(0.25);
    let mut prev = (beta, lin.det(lam_of(beta))?);
    let mut roots = Vec::new();
    while roots.len() < count {
        beta += step;
        if beta > 200.0 {
            return Err(VibrissaError::NoConvergence {
                what: "the modes".into(),
                reason: format!(
                    "found {} of {count} eigenvalues below omega^2 = {:e}",
                    roots.len(),
                    lam_of(beta)
                ),
            });
        }
        let cur = (beta, lin.det(lam_of(beta))?);
        if cur.1 == 0.0 && lin.tol == tight {
            roots.push(lam_of(cur.0));
        } else if cur.1 == 0.0 {
            // an exact zero of the sweep's determinant: the step at `tight` decides
            return Ok(None);
        } else if prev.1 != 0.0 && prev.1.signum() != cur.1.signum() {
            let (a, b) = (lam_of(prev.0), lam_of(cur.0));
            let tol = 1e-15 * a.abs().max(b.abs()).max(1e-3);
            let sweep_tol = std::mem::replace(&mut lin.tol, tight);
            let r = crate::search::root(&mut |lam| lin.det(lam), a, b, tol);
            lin.tol = sweep_tol;
            match r {
                Ok(x) => roots.push(x),
                Err(crate::search::RootError::Caller(e)) => return Err(e),
                Err(crate::search::RootError::NoBracket { .. }) if sweep_tol != tight => {
                    return Ok(None)
                }
                Err(e) => {
                    return Err(VibrissaError::NoConvergence {
                        what: format!("the eigenvalue in [{a:e}, {b:e}]"),
                        reason: format!("{e:?}"),
                    })
                }
            }
        }
        prev = cur;
    }
    Ok(Some(roots))
}

/// The shape of the mode at `λ`: the null vector of `D(λ)` carried along the rod, sampled at
/// `n` points, scaled so that the largest `|δr|` is 1 and its largest component positive.
fn shape(lin: &mut Linear<'_>, lam: f64, n: usize) -> Result<Vec<ModePoint>, VibrissaError> {
    let (m, norms) = lin.matrix(lam)?;
    let mut unit = m;
    for q in 0..3 {
        for i in 0..3 {
            unit[(i, q)] /= norms[q];
        }
    }
    let svd = unit.svd(false, true);
    let vt = svd.v_t.ok_or_else(|| VibrissaError::NoConvergence {
        what: "the mode shape".into(),
        reason: "no singular vectors".into(),
    })?;
    let k = (0..3)
        .min_by(|&a, &b| svd.singular_values[a].total_cmp(&svd.singular_values[b]))
        .unwrap_or(2);
    let v: Vec<f64> = (0..3).map(|q| vt[(k, q)] / norms[q]).collect();
    let mut pts = Vec::with_capacity(n);
    let mut y = lin.start();
    let combine = |y: &[f64; NY]| -> [f64; 4] {
        let mut d = [0.0; 4];
        for (q, w) in v.iter().enumerate() {
            for (i, di) in d.iter_mut().enumerate() {
                *di += w * y[4 + 6 * q + i];
            }
        }
        d
    };
    let mut s0 = 0.0;
    for i in 0..n {
        let s1 = if n == 1 {
            1.0
        } else {
            i as f64 / (n - 1) as f64
        };
        y = lin.carry(lam, (s0, s1), y, || "the mode shape".into())?;
        let d = combine(&y);
        pts.push(ModePoint {
            s: s1,
            dx: d[0],
            dy: d[1],
            dphi: d[2],
            dm: d[3],
        });
        s0 = s1;
    }
    let (mut big, mut sign) = (0.0f64, 1.0);
    for p in &pts {
        let r = p.dx.hypot(p.dy);
        if r > big {
            big = r;
            let c = if p.dx.abs() > p.dy.abs() { p.dx } else { p.dy };
            sign = c.signum();
        }
    }
    let scale = if big > 0.0 { sign / big } else { 1.0 };
    for p in &mut pts {
        p.dx *= scale;
        p.dy *= scale;
        p.dphi *= scale;
        p.dm *= scale;
    }
    Ok(pts)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sweep at [`SWEEP_TOL`] brackets the roots as the sweep at the options' `tol` does,
    /// so the roots are the same to the bit, without a fallback: the paper's rod free, pinned
    /// and loaded; a rod tapered to 0.1 pressed at η 0.97 (its stuck tip under the contact force
    /// of its scan's start, whose sweep starts near λ = −1e6); a pre-curved compliant one; the
    /// long rat preset.
    #[test]
    fn the_loose_sweep_brackets_as_the_tight_one() {
        let load = |m_base, fx, fy| BaseLoad { m_base, fx, fy };
        let taper = |ratio| Rod::builder().taper(ratio).build().unwrap();
        let curled = Rod::builder()
            .precurvature(1.0, 0.0)
            .support_compliance(0.5)
            .build()
            .unwrap();
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../data/scenes/rat_mystacial_long.toml"
        );
        let scene: crate::Scene = toml::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
        let rat = scene.parts().unwrap().0;
        let cases: Vec<(Rod, BaseLoad, TipCondition)> = vec![
            (Rod::uniform(), load(0.0, 0.0, 0.0), TipCondition::Free),
            (Rod::uniform(), load(0.0, 0.0, 0.0), TipCondition::Pinned),
            (Rod::uniform(), load(-0.5, -1.0, -3.0), TipCondition::Pinned),
            (taper(0.1), load(0.0, 0.0, -0.0898), TipCondition::Pinned),
            (taper(0.1), load(0.02, -0.3, -2.0), TipCondition::Pinned),
            (curled, load(0.3, -1.0, -2.0), TipCondition::Free),
            (rat, load(0.05, -0.5, -1.5), TipCondition::Pinned),
        ];
        for (rod, load, tip) in &cases {
            let opts = ModeOptions::default();
            let mut lin = Linear::new(rod, load, *tip, &opts);
            let tight = sweep(&mut lin, 3, opts.tol).unwrap().unwrap();
            lin.tol = SWEEP_TOL;
            let loose = sweep(&mut lin, 3, opts.tol).unwrap();
            assert_eq!(loose.as_deref(), Some(tight.as_slice()), "{load:?} {tip:?}");
        }
    }

    /// A sweep far too loose to bracket alike (1e-1: the rod tapered to 0.1 under its start's
    /// contact force brackets a root whose ends have one sign at `tol`) falls back to the sweep
    /// at `tol`: the same roots, bit for bit.
    #[test]
    fn a_sweep_that_brackets_wrongly_falls_back() {
        let rod = Rod::builder().taper(0.1).build().unwrap();
        let load = BaseLoad {
            m_base: 0.0,
            fx: 0.0,
            fy: -0.0898,
        };
        let opts = ModeOptions::default();
        let mut lin = Linear::new(&rod, &load, TipCondition::Pinned, &opts);
        let tight = sweep(&mut lin, 3, opts.tol).unwrap().unwrap();
        lin.tol = 1e-1;
        assert_eq!(sweep(&mut lin, 3, opts.tol).unwrap(), None);
        lin.tol = opts.tol;
        let roots = lowest_roots_swept_at(&mut lin, 3, 1e-1).unwrap();
        assert_eq!(roots, tight);
        assert_eq!(lin.tol, opts.tol);
    }

    /// A root of `g` in `[a, b]` by bisection to the last bit (the closed forms' characteristic
    /// equations, solved here independently of the code under test).
    fn bisect(g: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
        let ga = g(a);
        for _ in 0..200 {
            let m = 0.5 * (a + b);
            if m == a || m == b {
                break;
            }
            if (g(m) > 0.0) == (ga > 0.0) {
                a = m;
            } else {
                b = m;
            }
        }
        0.5 * (a + b)
    }

    fn omegas(rod: &Rod, load: BaseLoad, tip: TipCondition, count: usize) -> Vec<f64> {
        let o = ModeOptions {
            count,
            ..ModeOptions::default()
        };
        modes(rod, &load, tip, &o)
            .unwrap()
            .modes
            .iter()
            .map(|m| m.omega)
            .collect()
    }

    fn assert_rel(got: f64, want: f64, tol: f64, what: &str) {
        let e = (got / want - 1.0).abs();
        assert!(
            e <= tol,
            "{what}: {got} against {want}: relative error {e:e}"
        );
    }

    /// The uniform clamped–free rod: `ω_n = β_n²` with `cos β cosh β = −1` (Blevins, *Formulas
    /// for natural frequency and mode shape*, 1979, table 8-1: β₁ = 1.87510406871196,
    /// β₂ = 4.69409113297418, β₃ = 7.85475743823761). Measured: 7e-13 relative at most.
    #[test]
    fn clamped_free_uniform_rod() {
        let stated = [1.87510406871196, 4.69409113297418, 7.85475743823761];
        let w = omegas(&Rod::uniform(), BaseLoad::default(), TipCondition::Free, 3);
        for (n, (&b, &got)) in stated.iter().zip(&w).enumerate() {
            let root = bisect(|x| x.cos() * x.cosh() + 1.0, b - 0.1, b + 0.1);
            assert!((root - b).abs() < 1e-13, "beta_{} = {root}", n + 1);
            assert_rel(got, root * root, 1e-11, &format!("omega_{}", n + 1));
        }
    }

    /// The uniform rod clamped at the foot and pinned at the tip: `tan β = tanh β` (Blevins,
    /// table 8-1: β₁ = 3.92660231204792, β₂ = 7.06858274562873; β₃ = 10.2101761228130 is the
    /// equation's root to 15 digits, where the value 10.2101761241668 sometimes quoted is the
    /// asymptote 13π/4, 1.3e-10 off). Measured: 3e-13 relative at most. A tip
    /// sliding on a line that is not across the rod holds it the same way, one across the rod
    /// (inclination 0: the rod stands along y) leaves it free.
    #[test]
    fn clamped_pinned_and_sliding_uniform_rod() {
        let stated = [3.92660231204792, 7.06858274562873, 10.2101761228130];
        let rod = Rod::uniform();
        for tip in [
            TipCondition::Pinned,
            TipCondition::Sliding { angle: FRAC_PI_2 },
            TipCondition::Sliding { angle: 0.3 },
        ] {
            let w = omegas(&rod, BaseLoad::default(), tip, 3);
            for (n, (&b, &got)) in stated.iter().zip(&w).enumerate() {
                let root = bisect(|x| x.tan() - x.tanh(), b - 0.1, b + 0.1);
                assert!((root - b).abs() < 1e-13, "beta_{} = {root}", n + 1);
                assert_rel(got, root * root, 1e-11, &format!("{tip:?} omega_{}", n + 1));
            }
        }
        let w = omegas(
            &rod,
            BaseLoad::default(),
            TipCondition::Sliding { angle: 0.0 },
            1,
        );
        assert_rel(w[0], 1.87510406871196f64.powi(2), 1e-11, "sliding across");
    }

    /// The first mode shape of the clamped–free rod: `cosh βs − cos βs − σ(sinh βs − sin βs)`,
    /// `σ = (cosh β + cos β)/(sinh β + sin β)` (Blevins, table 8-1), scaled to 1 at the tip.
    #[test]
    fn clamped_free_mode_shape() {
        let o = ModeOptions {
            count: 1,
            shape_points: 21,
            ..ModeOptions::default()
        };
        let r = modes(
            &Rod::uniform(),
            &BaseLoad::default(),
            TipCondition::Free,
            &o,
        )
        .unwrap();
        let b = r.modes[0].omega.sqrt();
        let sigma = (b.cosh() + b.cos()) / (b.sinh() + b.sin());
        let w = |s: f64| (b * s).cosh() - (b * s).cos() - sigma * ((b * s).sinh() - (b * s).sin());
        let shape = &r.modes[0].shape;
        assert_eq!(shape.len(), 21);
        for p in shape {
            let want = w(p.s) / w(1.0);
            // the rod stands along y: the mode moves it along x
            assert!(
                (p.dx.abs() - want.abs()).abs() < 1e-9,
                "{p:?} against {want}"
            );
            assert!(p.dy.abs() < 1e-12, "{p:?}");
        }
    }

    /// A compressive dead load at the free tip lowers `ω₁²` through zero at Euler's load
    /// `π²/4`; pinned, through zero at `β²` with `tan β = β` (β = 4.49340945790906,
    /// Timoshenko & Gere, *Theory of elastic stability*, §2.5). Beyond it the state is unstable.
    #[test]
    fn buckling_loads_zero_the_first_frequency() {
        let rod = Rod::uniform();
        let o = ModeOptions {
            count: 1,
            ..ModeOptions::default()
        };
        let beta = bisect(|x| x.tan() - x, 4.4, 4.6);
        for (tip, p_cr) in [
            (TipCondition::Free, std::f64::consts::PI.powi(2) / 4.0),
            (TipCondition::Pinned, beta * beta),
        ] {
            let at = |p: f64| {
                let load = BaseLoad {
                    m_base: 0.0,
                    fx: 0.0,
                    fy: -p,
                };
                modes(&rod, &load, tip, &o).unwrap()
            };
            let r = at(p_cr);
            assert!(r.modes[0].omega2.abs() < 1e-9, "{tip:?}: {r}");
            let below = at(0.9 * p_cr);
            assert!(below.stable && below.modes[0].omega2 > 0.1, "{below}");
            let above = at(1.1 * p_cr);
            assert!(!above.stable && above.modes[0].omega2 < -0.1, "{above}");
            assert!(above.modes[0].omega.is_nan());
        }
    }

    /// Rotary inertia (Rayleigh's beam): the uniform clamped–free rod with radius of gyration
    /// g has `w'''' + ω²g² w'' = ω² w` (constant coefficients), `w = A cosh αs + B sinh αs +
    /// C cos βs + D sin βs` with `α², −β² = (−ω²g² ± √(ω⁴g⁴ + 4ω²))/2`, `w(0) = w'(0) = 0`,
    /// `w''(1) = 0`, `w'''(1) + ω²g² w'(1) = 0` (no force at the tip: the shear includes the
    /// rotary inertia's moment). Its 4×4 determinant is solved here by bisection. g = 0.05:
    /// ω₁ = 3.4957481593, ω₂ = 21.190689736 (0.6 % and 3.8 % below β_n²); measured 7e-13.
    #[test]
    fn rotary_inertia_against_the_rayleigh_beam() {
        let g: f64 = 0.05;
        let det = |w: f64| -> f64 {
            let l = w * w;
            let root = (l * l * g.powi(4) + 4.0 * l).sqrt();
            let (a, b) = (
                (0.5 * (-l * g * g + root)).sqrt(),
                (0.5 * (l * g * g + root)).sqrt(),
            );
            let (ch, sh, c, sn) = (a.cosh(), a.sinh(), b.cos(), b.sin());
            let k = l * g * g;
            // columns: cosh αs, sinh αs, cos βs, sin βs; rows: w(0), w'(0), w''(1), V(1)
            let m = nalgebra::Matrix4::new(
                1.0,
                0.0,
                1.0,
                0.0,
                0.0,
                a,
                0.0,
                b,
                a * a * ch,
                a * a * sh,
                -b * b * c,
                -b * b * sn,
                a * a * a * sh + k * a * sh,
                a * a * a * ch + k * a * ch,
                b * b * b * sn - k * b * sn,
                -b * b * b * c + k * b * c,
            );
            m.determinant()
        };
        let o = ModeOptions {
            count: 2,
            rotary_inertia: g,
            ..ModeOptions::default()
        };
        let r = modes(
            &Rod::uniform(),
            &BaseLoad::default(),
            TipCondition::Free,
            &o,
        )
        .unwrap();
        for (n, guess) in [(0usize, 3.516f64), (1, 22.03)] {
            let want = bisect(det, guess * 0.9, guess * 1.001);
            let got = r.modes[n].omega;
            eprintln!("omega_{} = {got}, Rayleigh beam {want}", n + 1);
            assert!(want < guess, "rotary inertia lowers the frequency: {want}");
            assert_rel(got, want, 1e-10, &format!("omega_{}", n + 1));
        }
    }

    /// Bad options are refused before any work.
    #[test]
    fn options_are_checked() {
        let bad = ModeOptions {
            count: 0,
            ..ModeOptions::default()
        };
        let e = modes(
            &Rod::uniform(),
            &BaseLoad::default(),
            TipCondition::Free,
            &bad,
        );
        assert!(matches!(e, Err(VibrissaError::OutOfRange { .. })), "{e:?}");
        let load = BaseLoad {
            m_base: f64::NAN,
            ..BaseLoad::default()
        };
        let e = modes(
            &Rod::uniform(),
            &load,
            TipCondition::Free,
            &ModeOptions::default(),
        );
        assert!(e.is_err());
    }
}
