//! Reading the surface from the signals (issue 21): the friction coefficients `μs`, `μk` (and on
//! request the surface height η and inclination β, or a sine corrugation's amplitude,
//! wavelength and phase, issue 31) estimated from a measured drag by nonlinear least squares.
//!
//! The data are the trace's slips (the sawtooth's corners): for each slip `k` its foot
//! displacement `d_k` and any of the base signals `fx`, `fy`, `m_base` just before and just after
//! it. The model is the drag ([`crate::drag()`]) of the same scene at the parameters `θ`; its
//! slip `k` gives the same quantities. The residuals
//!
//! ```text
//!     r_i(θ) = (observed_i − model_i(θ)) / σ_kind(i)
//! ```
//!
//! are minimized by argmin's Gauss–Newton method with a backtracking (Armijo) line search, in
//! unconstrained coordinates (`μs = e^a`, `μk = μs / (1 + e^−b)`, η and β mapped onto their open
//! ranges, the wavelength's logarithm onto its range `[0.01, 100]`, the amplitude onto `±` the
//! largest the slope limit allows at that wavelength, the phase as it is); the Jacobian by
//! central differences of drags. `σ_kind` is each kind's noise level
//! (`d`, `fx`, `fy`, `m_base`): given, or estimated. Estimated: a first fit with unit weights,
//! then, until no level changes by more than 1e-3 (at most 12 rounds), each kind's variance
//! from its residuals `e_i` (in its own units) over its own degrees of freedom and the fit
//! repeated with those weights:
//!
//! ```text
//!     σ_k² = Σ_{i in k} e_i² / ν_k,   ν_k = Σ_{i in k} (1 − h_i),   h_i = j_i (JᵀJ)⁻¹ j_iᵀ
//! ```
//!
//! (`h_i` the leverage of observation `i`, `j_i` its row of the weighted Jacobian; the `ν_k` add
//! up to `n − p`, so the weighted residuals give `s² = 1` at the fixed point. Spreading the `p`
//! over the kinds by their counts instead underestimates the level of a kind that carries more
//! of the information, e.g. the slip places.)
//!
//! Standard errors: with the noise levels given `cov = (JᵀJ)⁻¹`, `J` the Jacobian of the
//! weighted residuals with respect to the natural parameters at the estimate (the levels are
//! known; `s² = Σ r² / (n − p)` then checks them). With estimated levels (the equations above
//! are those of restricted maximum likelihood, REML, for one variance per kind) the weights
//! carry the noise of a few residuals each, and `(JᵀJ)⁻¹` at them is too small on average:
//! it misses the estimate's extra variance from noisy weights (Kackar–Harville) and is itself
//! a biased estimate of its value at the true levels. Kenward and Roger's correction of both,
//! derived for this model at `adjusted_covariance` in the source,
//!
//! ```text
//!     cov = s² (M + 2Λ),   M = (JᵀJ)⁻¹,   Λ = M [Σ_k C_kk A_k − Σ_kl C_kl A_k M A_l] M,
//! ```
//!
//! with `A_k = J_kᵀ J_k` the information of kind `k` and `C_kl = Cov(σ̂_k², σ̂_l²) / (σ_k² σ_l²)`
//! from REML's information (≈ `2 / ν_k` on the diagonal); `Λ` vanishes with one kind of
//! observation and grows as the kinds with few degrees of freedom carry much of the
//! information. The standard error is itself an estimate: its degrees of freedom
//! (Satterthwaite, from the parts `v_k` of the variance that each kind carries, `ν = 2 (Σ
//! v_k)² / vᵀ C v`, i.e. `(Σ v_k)² / Σ (v_k² / ν_k)` for diagonal `C`) give the Student-t
//! interval `value ± t_ν · std_error` (with a few slips, ν is small: 3 standard errors are then
//! a t interval of less than 99.73 %). A parameter is
//! not identifiable from the given signals when the column-scaled `J` is rank deficient (singular
//! value ratio below 1e-7): the parameters carrying the null direction are named, held at their
//! starting values, and the others fitted (e.g. μk from a trace with one slip and no signals after
//! it: the slip's place depends on μs alone; a corrugation's wavelength and phase when its
//! amplitude starts at 0: they change nothing).
//!
//! Starting values: μs from the first slip — the friction ratio of the scan at `d_1` — and μk
//! from the second (the scan's ratio at `d_1 − (d_2 − d_1)`, the place the flat surface's slip
//! goes back to), else `0.6 μs`.
//!
//! Cost: every residual vector is a drag (stopped after the trace's number of slips, or at
//! twice the last slip's `d` and 0.05 more), each Jacobian `2p` of them. The model remembers
//! the drags at its last few parameter values (each Gauss–Newton iteration starts where the
//! line search ended; the global strategy compares costs at points already computed), and the
//! line search halves the step per trial.

use crate::drag::{drag, DragOptions, DragResult, MAX_MU_S};
use crate::report::{ContactModel, ScanOptions};
use crate::surface::SurfaceProfile;
use crate::{Scene, SolverConfig, VibrissaError};
use argmin::core::{CostFunction, Error as ArgminError, Executor, Jacobian, Operator, State};
use argmin::solver::gaussnewton::GaussNewtonLS;
use argmin::solver::linesearch::condition::ArmijoCondition;
use argmin::solver::linesearch::BacktrackingLineSearch;
use nalgebra::{DMatrix, DVector};
use serde::Serialize;
use std::cell::RefCell;
use std::fmt;

/// A base signal.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Signal {
    /// Force on the support, x.
    Fx,
    /// Force on the support, y.
    Fy,
    /// `m(0)`.
    MBase,
}

impl Signal {
    /// All, in column order.
    pub const ALL: [Signal; 3] = [Signal::Fx, Signal::Fy, Signal::MBase];
    /// The column name: `fx`, `fy`, `m_base`.
    pub fn name(self) -> &'static str {
        match self {
            Signal::Fx => "fx",
            Signal::Fy => "fy",
            Signal::MBase => "m_base",
        }
    }
}

/// One observed slip: where, and the signals just before and just after it (those measured).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Default)]
pub struct TraceSlip {
    /// Foot displacement at the slip.
    pub d: f64,
    /// `fx`, `fy`, `m_base` just before (in [`Signal::ALL`] order), if measured.
    pub before: [Option<f64>; 3],
    /// The same just after.
    pub after: [Option<f64>; 3],
}

/// A measured drag: its slips in order.
#[derive(Clone, Debug, PartialEq, Serialize, Default)]
pub struct Trace {
    /// The slips.
    pub slips: Vec<TraceSlip>,
    /// The tip positions `(x_tip, y_tip)` of the trace's rows, where it has them (empty: not
    /// measured). On a straight surface they lie on one line; [`fit`] says when they do not
    /// (a curved or corrugated surface fitted as a straight one).
    pub tips: Vec<[f64; 2]>,
    /// What the trace's parameter moved: the foot along x (column `d`), or the foot's support
    /// turned with the foot held (column `theta`, `drag --turn`); the model's drags move the
    /// same.
    pub motion: crate::FootMotion,
}

/// A table's error about the trace.
fn bad_trace(reason: String) -> VibrissaError {
    VibrissaError::InvalidTable {
        name: "trace".into(),
        reason,
    }
}

impl Trace {
    /// The slips of a trace CSV: a header with a column `d` (or `theta`: a turned support's
    /// trace, [`Trace::motion`]) and any of `fx`, `fy`, `m_base`
    /// (those of `use_sig`, in [`Signal::ALL`] order), `x_tip`, `y_tip`, `event`. Its slips are
    /// the rows whose `event` is `slip` (the state just before) with the next `slip_end` row
    /// (just after), as [`crate::drag()`]'s rows are written; without an `event` column, a slip
    /// is where `d` does not increase from one row to the next. Every row has the header's
    /// fields (a row cut short is refused, not read as missing values); an empty field is a
    /// value not measured.
    pub fn from_csv(text: &str, use_sig: [bool; 3]) -> Result<Trace, VibrissaError> {
        let mut lines = text
            .lines()
            .enumerate()
            .filter(|(_, l)| !l.trim().is_empty());
        let (_, head) = lines.next().ok_or_else(|| bad_trace("empty file".into()))?;
        let cols: Vec<&str> = head.split(',').map(str::trim).collect();
        let at = |c: &str| cols.iter().position(|h| *h == c);
        let (d_col, motion) = match (at("d"), at("theta")) {
            (Some(c), _) => (c, crate::FootMotion::Along),
            (None, Some(c)) => (c, crate::FootMotion::Turn),
            (None, None) => {
                return Err(bad_trace(
                    "no column d (the foot displacement) or theta (the support's turn)".into(),
                ))
            }
        };
        let ev_col = at("event");
        let tip_col = at("x_tip").zip(at("y_tip"));
        let sig_col: Vec<Option<usize>> = Signal::ALL
            .iter()
            .zip(use_sig)
            .map(|(s, u)| if u { at(s.name()) } else { None })
            .collect();
        let mut rows = Vec::new();
        let mut tips = Vec::new();
        for (i, l) in lines {
            let f: Vec<&str> = l.split(',').map(str::trim).collect();
            if f.len() != cols.len() {
                return Err(bad_trace(format!(
                    "line {} has {} fields, the header {}: a row cut short or run together is \
                     not read",
                    i + 1,
                    f.len(),
                    cols.len()
                )));
            }
            let value = |c: usize, what: &str| -> Result<Option<f64>, VibrissaError> {
                match f[c] {
                    "" => Ok(None),
                    t => match t.parse::<f64>() {
                        Ok(v) if v.is_finite() => Ok(Some(v)),
                        _ => Err(bad_trace(format!(
                            "line {}: {what} = '{t}' is not a finite number",
                            i + 1
                        ))),
                    },
                }
            };
            let d = value(d_col, "d")?.ok_or_else(|| bad_trace(format!("line {}: no d", i + 1)))?;
            let mut s = [None; 3];
            for (k, c) in sig_col.iter().enumerate() {
                if let Some(c) = *c {
                    s[k] = value(c, Signal::ALL[k].name())?;
                }
            }
            if let Some((cx, cy)) = tip_col {
                if let (Some(x), Some(y)) = (value(cx, "x_tip")?, value(cy, "y_tip")?) {
                    tips.push([x, y]);
                }
            }
            let ev = ev_col.map_or("", |c| f[c]).to_string();
            rows.push((d, s, ev));
        }
        let slips = slips_of(&rows, ev_col.is_some());
        if slips.is_empty() {
            return Err(bad_trace(
                "no slip in the trace (rows with event = slip, or, without an event column, a row \
                 whose d does not increase)"
                    .into(),
            ));
        }
        for w in slips.windows(2) {
            if w[1].d <= w[0].d {
                return Err(bad_trace(format!(
                    "the slips at d = {} and d = {} are not in increasing order",
                    w[0].d, w[1].d
                )));
            }
        }
        Ok(Trace {
            slips,
            tips,
            motion,
        })
    }
}

/// The slips of the rows `(d, signals, event)`: by their events, or where d does not increase.
fn slips_of(rows: &[(f64, [Option<f64>; 3], String)], events: bool) -> Vec<TraceSlip> {
    let mut slips = Vec::new();
    if events {
        for (k, r) in rows.iter().enumerate() {
            if r.2 != "slip" {
                continue;
            }
            // the state after it: its slip_end row, before any next slip
            let after = rows[k + 1..]
                .iter()
                .take_while(|q| q.2 != "slip")
                .find(|q| q.2 == "slip_end")
                .map_or([None; 3], |q| q.1);
            slips.push(TraceSlip {
                d: r.0,
                before: r.1,
                after,
            });
        }
    } else {
        for w in rows.windows(2) {
            if w[1].0 <= w[0].0 {
                slips.push(TraceSlip {
                    d: w[0].0,
                    before: w[0].1,
                    after: w[1].1,
                });
            }
        }
    }
    slips
}

/// Options of [`fit`].
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FitOptions {
    /// Also estimate the surface height η (straight surfaces). Default false.
    pub fit_eta: bool,
    /// Also estimate the surface inclination β (straight surfaces). Default false.
    pub fit_angle: bool,
    /// Which of the corrugation's amplitude, wavelength and phase to estimate as well (a scene
    /// whose surface is one sine, `[surface] kind = "sine"`; their starts are the scene's).
    /// Default: none.
    pub corrugation: CorrugationFit,
    /// Starting `(μs, μk)`; default from the first two slips (module docs).
    pub guess: Option<(f64, f64)>,
    /// Noise levels of `d`, `fx`, `fy`, `m_base` (`None`: estimated).
    pub sigma: Option<[f64; 4]>,
    /// Solver of the drags.
    pub solver: SolverConfig,
    /// Where the rod may touch.
    pub contact: ContactModel,
    /// Most Gauss–Newton iterations per fit, in `[1, 1000]`. Default 50.
    pub max_iter: u64,
}

impl Default for FitOptions {
    fn default() -> Self {
        FitOptions {
            fit_eta: false,
            fit_angle: false,
            corrugation: CorrugationFit::default(),
            guess: None,
            sigma: None,
            solver: SolverConfig::default(),
            contact: ContactModel::Anywhere,
            max_iter: 50,
        }
    }
}

/// Which parameters of a sine corrugation `A·sin(2πx/W + P)` (the scene's `[surface] kind =
/// "sine"`) [`fit`] estimates beside μs and μk; the others are held at the scene's values.
/// Default: none (the corrugation is known).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct CorrugationFit {
    /// The amplitude `A` (rod lengths), within the slope limit of the surface
    /// (`|tan β| + 2π|A|/W < 1`) and `|A| ≤ 0.2`.
    pub amplitude: bool,
    /// The wavelength `W` (rod lengths), in `[0.01, 100]`.
    pub wavelength: bool,
    /// The phase `P` (rad) at `x = 0`.
    pub phase: bool,
}

impl CorrugationFit {
    /// All three.
    pub const ALL: CorrugationFit = CorrugationFit {
        amplitude: true,
        wavelength: true,
        phase: true,
    };

    /// Whether any is estimated.
    pub fn any(self) -> bool {
        self.amplitude || self.wavelength || self.phase
    }

    /// The parts named (`amplitude`, `wavelength`, `phase`; surrounding blanks ignored); none
    /// named: all three (the program's `--fit-corrugation` without a list, Python's
    /// `fit_corrugation=True`). An unknown name is [`VibrissaError::InvalidName`].
    pub fn from_names<'a>(
        names: impl IntoIterator<Item = &'a str>,
    ) -> Result<CorrugationFit, VibrissaError> {
        let mut c = CorrugationFit::default();
        let mut named = false;
        for part in names {
            named = true;
            match part.trim() {
                "amplitude" => c.amplitude = true,
                "wavelength" => c.wavelength = true,
                "phase" => c.phase = true,
                other => {
                    return Err(VibrissaError::InvalidName {
                        name: "part of the corrugation",
                        value: other.to_string(),
                        valid: "amplitude, wavelength, phase",
                    })
                }
            }
        }
        Ok(if named { c } else { CorrugationFit::ALL })
    }
}

/// One estimated parameter.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FitParam {
    /// `mu_s`, `mu_k`, `eta`, `surface_angle`, `amplitude`, `wavelength`, `phase`.
    pub name: &'static str,
    /// The estimate (the starting value when not identifiable).
    pub value: f64,
    /// Its standard error (`None` when not identifiable, or when the observations are as many as
    /// the parameters and no noise levels are given).
    pub std_error: Option<f64>,
    /// The degrees of freedom of `std_error` when the noise levels are estimated (from the
    /// kinds' own degrees of freedom by Satterthwaite; module docs): the estimate lies within
    /// `t_dof(q) · std_error` of the truth with probability `q` (Student's t). `None` when the
    /// noise levels are given (then the standard error is not itself estimated: normal
    /// quantiles) or there is no standard error.
    pub dof: Option<f64>,
    /// Whether the signals determine it.
    pub identifiable: bool,
}

/// Result of [`fit`].
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FitResult {
    /// The parameters.
    pub params: Vec<FitParam>,
    /// Why some parameter is not identifiable, if one is.
    pub message: Option<String>,
    /// Observations used.
    pub observations: usize,
    /// The noise levels used for `d`, `fx`, `fy`, `m_base` (NaN where unused).
    pub sigma: [f64; 4],
    /// `s² = Σ r² / (n − p)` of the weighted residuals (1 to 1e-3 when the noise levels are
    /// estimated; with given levels ≈ 1 when they fit the data; NaN when `n = p` and no noise
    /// levels are given).
    pub s2: f64,
    /// Whether the residuals are consistent with the noise along the whole trace (from 4
    /// slips on); when not, the message says so and no parameter has a standard error.
    pub consistency: Option<Consistency>,
    /// Gauss–Newton iterations (both passes).
    pub iterations: u64,
    /// Drags computed.
    pub drags: usize,
}

impl FitResult {
    /// The estimate of `name`, if fitted.
    pub fn get(&self, name: &str) -> Option<&FitParam> {
        self.params.iter().find(|p| p.name == name)
    }
}

impl fmt::Display for FitResult {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for p in &self.params {
            match p.std_error {
                Some(se) => write!(f, "{} = {:.6} ± {:.2e}; ", p.name, p.value, se)?,
                None => write!(f, "{} = {:.6} (not identifiable); ", p.name, p.value)?,
            }
        }
        write!(
            f,
            "{} observations, s² = {:.3}, {} iterations, {} drags",
            self.observations, self.s2, self.iterations, self.drags
        )?;
        if let Some(m) = &self.message {
            write!(f, "; {m}")?;
        }
        Ok(())
    }
}

/// Which quantity an observation is: the slip's place, or a signal before/after it.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Obs {
    D(usize),
    Before(usize, usize),
    After(usize, usize),
}

impl Obs {
    fn kind(self) -> usize {
        match self {
            Obs::D(_) => 0,
            Obs::Before(_, s) | Obs::After(_, s) => 1 + s,
        }
    }
}

/// A parameter's natural value from its free coordinate, and back.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Par {
    MuS,
    MuK,
    Eta,
    Angle,
    Amplitude,
    Wavelength,
    Phase,
}

/// Natural values of every parameter, indexed by [`Par`].
type Values = [f64; 7];

impl Par {
    /// In [`Values`] order.
    const ALL: [Par; 7] = [
        Par::MuS,
        Par::MuK,
        Par::Eta,
        Par::Angle,
        Par::Amplitude,
        Par::Wavelength,
        Par::Phase,
    ];

    fn name(self) -> &'static str {
        match self {
            Par::MuS => "mu_s",
            Par::MuK => "mu_k",
            Par::Eta => "eta",
            Par::Angle => "surface_angle",
            Par::Amplitude => "amplitude",
            Par::Wavelength => "wavelength",
            Par::Phase => "phase",
        }
    }
}

/// The range of a corrugation's wavelength, rod lengths (the scene's).
const WAVELENGTH_RANGE: (f64, f64) = (0.01, 100.0);

/// The largest amplitude of a corrugation of wavelength `w` on a surface inclined by `beta`: the
/// scene's 0.2, and just below the slope limit `|tan β| + 2π|A|/W < 1`.
fn max_amplitude(w: f64, beta: f64) -> f64 {
    let room = (crate::surface::MAX_PROFILE_SLOPE - beta.tan().abs()).max(0.0);
    (room * w / std::f64::consts::TAU * (1.0 - 1e-9)).min(0.2)
}

/// The least-squares problem: observations, weights, the scene and which parameters are free.
struct Model<'a> {
    scene: &'a Scene,
    trace: &'a Trace,
    obs: Vec<(Obs, f64)>,
    sigma: [f64; 4],
    free: Vec<Par>,
    /// Natural values of every parameter (the held ones stay).
    base: Values,
    opts: &'a FitOptions,
    d_max: f64,
    drags: RefCell<usize>,
    /// The model's values of the observations at the last few parameter values (module docs,
    /// "Cost").
    memo: RefCell<Vec<(Values, DVector<f64>)>>,
}

/// How many parameter values [`Model::predictions`] remembers.
const MEMO: usize = 4;

fn logistic(x: f64) -> f64 {
    1.0 / (1.0 + (-x).exp())
}

fn logit(p: f64) -> f64 {
    (p / (1.0 - p)).ln()
}

/// `p` moved by whole turns into `(start − π, start + π]`.
fn within_pi_of(p: f64, start: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    let q = start + (p - start).rem_euclid(TAU);
    if q - start > PI {
        q - TAU
    } else {
        q
    }
}

impl Model<'_> {
    /// Natural `(μs, μk, η, β, A, W, P)` from the free coordinates `x` (μk a share of μs, the
    /// amplitude a share of its largest at the wavelength and inclination).
    fn natural(&self, x: &[f64]) -> Values {
        let mut v = self.base;
        let (w_lo, w_hi) = (WAVELENGTH_RANGE.0.ln(), WAVELENGTH_RANGE.1.ln());
        for (i, p) in self.free.iter().enumerate() {
            match p {
                Par::MuS => v[0] = x[i].exp(),
                Par::MuK | Par::Amplitude => {}
                Par::Eta => {
                    let lo = elastica::lower_limit().1;
                    v[2] = lo + (1.0 - lo) * logistic(x[i]);
                }
                Par::Angle => v[3] = crate::MAX_SURFACE_ANGLE * (2.0 * logistic(x[i]) - 1.0),
                Par::Wavelength => v[5] = (w_lo + (w_hi - w_lo) * logistic(x[i])).exp(),
                Par::Phase => v[6] = x[i],
            }
        }
        if let Some(i) = self.free.iter().position(|&p| p == Par::MuK) {
            v[1] = v[0] * logistic(x[i]);
        }
        if let Some(i) = self.free.iter().position(|&p| p == Par::Amplitude) {
            v[4] = max_amplitude(v[5], v[3]) * (2.0 * logistic(x[i]) - 1.0);
        }
        v
    }

    /// `v` with a fitted phase moved by whole turns to within π of its start: the surface is
    /// 2π-periodic in the phase, so the least squares may end any number of turns away (seen:
    /// +2π and +30π from starts 0.3 off), and a user compares with the start they gave.
    fn near_start_phase(&self, mut v: Values) -> Values {
        if self.free.contains(&Par::Phase) {
            v[6] = within_pi_of(v[6], self.base[6]);
        }
        v
    }

    /// Free coordinates of natural values.
    fn coords(&self, v: Values) -> Vec<f64> {
        let (w_lo, w_hi) = (WAVELENGTH_RANGE.0.ln(), WAVELENGTH_RANGE.1.ln());
        self.free
            .iter()
            .map(|p| match p {
                Par::MuS => v[0].ln(),
                Par::MuK => logit(v[1] / v[0]),
                Par::Eta => {
                    let lo = elastica::lower_limit().1;
                    logit((v[2] - lo) / (1.0 - lo))
                }
                Par::Angle => logit(0.5 * (v[3] / crate::MAX_SURFACE_ANGLE + 1.0)),
                Par::Amplitude => logit(0.5 * (v[4] / max_amplitude(v[5], v[3]) + 1.0)),
                Par::Wavelength => logit((v[5].ln() - w_lo) / (w_hi - w_lo)),
                Par::Phase => v[6],
            })
            .collect()
    }

    /// The drag at natural values.
    fn drag_at(&self, v: Values) -> Result<DragResult, VibrissaError> {
        *self.drags.borrow_mut() += 1;
        let mut sc = self.scene.clone();
        sc.eta = v[2];
        sc.surface_angle = v[3];
        if let SurfaceProfile::Sine { .. } = sc.surface {
            // (the scene's own values unless fitted)
            sc.surface = SurfaceProfile::Sine {
                amplitude: v[4],
                wavelength: v[5],
                phase: v[6],
            };
        }
        let (rod, surface) = sc.parts()?;
        drag(
            &rod,
            &surface,
            &DragOptions {
                d_max: self.d_max,
                points: 2,
                mu_s: Some(v[0]),
                mu_k: Some(v[1]),
                solver: self.opts.solver.clone(),
                contact: self.opts.contact,
                max_slips: self.trace.slips.len(),
                motion: self.trace.motion,
                ..DragOptions::default()
            },
        )
    }

    /// Weighted residuals at natural values (a missing model slip counts as one at `d_max`, its
    /// signals as zero; a drag that fails gives large residuals, so that a line search backs
    /// off).
    fn residuals(&self, v: Values) -> DVector<f64> {
        self.residuals_of(v)
            .unwrap_or_else(|_| DVector::from_element(self.obs.len(), 1e6))
    }

    /// The weighted residuals, or why the drag at `v` fails.
    fn residuals_of(&self, v: Values) -> Result<DVector<f64>, VibrissaError> {
        let m = self.predictions(v)?;
        Ok(DVector::from_iterator(
            self.obs.len(),
            self.obs
                .iter()
                .zip(m.iter())
                .map(|(&(o, y), m)| (y - m) / self.sigma[o.kind()]),
        ))
    }

    /// The model's values of the observations at natural values `v` (unweighted): those of the
    /// drag there, or of the last few drags when `v` is one of theirs (the same numbers: a drag
    /// is a function of its parameters).
    fn predictions(&self, v: Values) -> Result<DVector<f64>, VibrissaError> {
        let same = |w: &Values| w.iter().zip(&v).all(|(a, b)| a.to_bits() == b.to_bits());
        if let Some((_, m)) = self.memo.borrow().iter().find(|(w, _)| same(w)) {
            return Ok(m.clone());
        }
        let r = self.drag_at(v)?;
        let m = DVector::from_iterator(
            self.obs.len(),
            self.obs.iter().map(|&(o, _)| {
                let sig = |k: usize, s: usize, after: bool| -> f64 {
                    r.slips.get(k).map_or(0.0, |e| {
                        let x = if after { &e.after } else { &e.before };
                        [x.fx, x.fy, x.m_base][s]
                    })
                };
                match o {
                    Obs::D(k) => r.slips.get(k).map_or(self.d_max, |e| e.d),
                    Obs::Before(k, s) => sig(k, s, false),
                    Obs::After(k, s) => sig(k, s, true),
                }
            }),
        );
        let mut memo = self.memo.borrow_mut();
        if memo.len() == MEMO {
            memo.remove(0);
        }
        memo.push((v, m.clone()));
        Ok(m)
    }

    /// `∂r/∂(natural free parameters)` by central differences.
    fn jacobian_natural(&self, v: Values) -> Result<DMatrix<f64>, VibrissaError> {
        let mut j = DMatrix::zeros(self.obs.len(), self.free.len());
        for (c, p) in self.free.iter().enumerate() {
            let i = *p as usize;
            let h = 1e-6 * v[i].abs().max(0.1);
            let (mut a, mut b) = (v, v);
            a[i] += h;
            b[i] -= h;
            // (a failed drag there is an error, not a parameter the signals do not see)
            let at = |w: Values| {
                self.residuals_of(w)
                    .map_err(|e| VibrissaError::NoConvergence {
                        what: format!(
                            "the fit's derivative in {} (the drag at {} = {})",
                            p.name(),
                            p.name(),
                            w[i]
                        ),
                        reason: e.to_string(),
                    })
            };
            let col = (at(a)? - at(b)?) / (2.0 * h);
            j.set_column(c, &col);
        }
        Ok(j)
    }
}

/// The model as argmin's problem (weighted residuals in the free coordinates).
struct Ls<'m, 'a>(&'m Model<'a>);

impl Operator for Ls<'_, '_> {
    type Param = DVector<f64>;
    type Output = DVector<f64>;
    fn apply(&self, x: &Self::Param) -> Result<Self::Output, ArgminError> {
        Ok(self.0.residuals(self.0.natural(x.as_slice())))
    }
}

impl CostFunction for Ls<'_, '_> {
    type Param = DVector<f64>;
    type Output = f64;
    fn cost(&self, x: &Self::Param) -> Result<f64, ArgminError> {
        Ok(self.apply(x)?.norm())
    }
}

impl Jacobian for Ls<'_, '_> {
    type Param = DVector<f64>;
    type Jacobian = DMatrix<f64>;
    fn jacobian(&self, x: &Self::Param) -> Result<Self::Jacobian, ArgminError> {
        let n = x.len();
        let mut j = DMatrix::zeros(self.0.obs.len(), n);
        for c in 0..n {
            let h = 1e-6 * x[c].abs().max(0.1);
            let (mut a, mut b) = (x.clone(), x.clone());
            a[c] += h;
            b[c] -= h;
            let col = (self.apply(&a)? - self.apply(&b)?) / (2.0 * h);
            j.set_column(c, &col);
        }
        Ok(j)
    }
}

/// Most rounds of re-estimating the noise levels and refitting.
const MAX_REWEIGHT: usize = 12;
/// The rounds stop when no noise level changes by more than this (relative).
const REWEIGHT_TOL: f64 = 1e-3;

/// The leverages `h_i = j_i (JᵀJ)⁻¹ j_iᵀ` of the rows of `j` (they add up to its columns), and
/// `(JᵀJ)⁻¹`.
fn leverages(j: &DMatrix<f64>) -> Result<(DVector<f64>, DMatrix<f64>), VibrissaError> {
    let m = (j.transpose() * j)
        .try_inverse()
        .ok_or_else(|| VibrissaError::NoConvergence {
            what: "the fit's covariance".into(),
            reason: format!(
                "the normal matrix of the {}x{} Jacobian is singular",
                j.nrows(),
                j.ncols()
            ),
        })?;
    let h = DVector::from_iterator(
        j.nrows(),
        j.row_iter().map(|row| (row * &m * row.transpose())[(0, 0)]),
    );
    Ok((h, m))
}

/// Each kind's noise level from the residuals `e` (in the kinds' own units) and the leverages
/// `h`: `σ_k² = Σ_{i in k} e_i² / ν_k`, `ν_k = Σ_{i in k} (1 − h_i)` — the restricted
/// (REML) likelihood's equation for a variance per kind. NaN for kinds without observations.
/// Returns the levels and the `ν_k`.
fn kind_levels(kinds: &[usize], e: &DVector<f64>, h: &DVector<f64>) -> ([f64; 4], [f64; 4]) {
    let (mut sum, mut nu, mut cnt) = ([0.0; 4], [0.0; 4], [0usize; 4]);
    for ((&k, ei), hi) in kinds.iter().zip(e.iter()).zip(h.iter()) {
        sum[k] += ei * ei;
        nu[k] += 1.0 - hi;
        cnt[k] += 1;
    }
    let mut sig = [f64::NAN; 4];
    let mut dof = [f64::NAN; 4];
    for k in 0..4 {
        if cnt[k] > 0 {
            dof[k] = nu[k];
            sig[k] = (sum[k] / nu[k].max(1e-3)).sqrt().max(1e-14);
        }
    }
    (sig, dof)
}

/// The covariance of the estimate with estimated noise levels, and the degrees of freedom of
/// its diagonal (Kenward & Roger 1997, for this model's variance components).
#[derive(Debug)]
struct Adjusted {
    /// `M + 2Λ` (to be scaled by `s²`).
    cov: DMatrix<f64>,
    /// Per parameter, `2 v² / (vᵀ C v)` (Satterthwaite), `v_k = [M A_k M]_cc`.
    dof: Vec<Option<f64>>,
}

/// Kenward–Roger's small-sample covariance of the estimate when each kind's noise level is
/// estimated (REML, [`kind_levels`]) from the residuals of the same fit.
///
/// `j` is the weighted Jacobian (rows divided by their kind's σ), `kinds` each row's kind, `M =
/// (JᵀJ)⁻¹`. The model's covariance is `V = diag(σ_k(i)²)`, linear in the variance components
/// `σ_k²`; with `A_k = J_kᵀ J_k` (the rows of kind `k`), `M⁻¹ = Σ_k A_k` and
///
/// ```text
///     P_k = Xᵀ (∂V⁻¹/∂σ_k²) X = −A_k / σ_k²,   Q_kl = Xᵀ (∂V⁻¹/∂σ_k²) V (∂V⁻¹/∂σ_l²) X = δ_kl A_k / σ_k⁴.
/// ```
///
/// Plugging estimated levels into `M` misses twice the same term: the estimate's extra
/// variance from the noise of the weights (Kackar & Harville 1984) and the bias of `M(σ̂)` as
/// an estimate of `M(σ)` (second order in `σ̂ − σ`); together
///
/// ```text
///     cov = M + 2Λ,   Λ = M [Σ_kl W_kl (Q_kl − P_k M P_l)] M = M [Σ_k C_kk A_k − Σ_kl C_kl A_k M A_l] M
/// ```
///
/// with `W_kl = Cov(σ̂_k², σ̂_l²) = σ_k² σ_l² C_kl`, the inverse of REML's expected information
/// `½ tr(P V_k P V_l)`: `C = 2 G⁻¹`, `G_kl = Σ_{i in k, j in l} (δ_ij − H_ij)²`, `H = J M Jᵀ`
/// (`G_kk ≈ ν_k`, so `Var(σ̂_k²) ≈ 2 σ_k⁴ / ν_k`). There is no second-derivative term: `V` is
/// linear in the `σ_k²`. With one kind, `C = 2 / (n − p)` and `Λ = 0`: Student's t with `n − p`
/// degrees of freedom is then exact and needs no correction; the term grows with how unevenly
/// the kinds share the information and how few degrees of freedom each has. (`Λ` is positive
/// semidefinite: `A_k − A_k M A_k = (A_k⁻¹ + (Σ_{l≠k} A_l)⁻¹)⁻¹`.) The degrees of freedom of
/// `cov_cc` are Satterthwaite's with the same `C`: `M_cc = Σ_k v_k`, `∂M_cc/∂σ_k² = v_k / σ_k²`,
/// so `dof = 2 M_cc² / (vᵀ C v)` — Welch–Satterthwaite `(Σ v_k)² / Σ (v_k² / ν_k)` when `C` is
/// diagonal `2 / ν_k`. If `G` is singular (a kind fitted exactly), `C = diag(2 / ν_k)` (`ν_k` at
/// least 1e-3).
fn adjusted_covariance(
    kinds: &[usize],
    j: &DMatrix<f64>,
    m: &DMatrix<f64>,
    kind_dof: &[f64; 4],
) -> Adjusted {
    let present: Vec<usize> = (0..4).filter(|k| kinds.contains(k)).collect();
    let nk = present.len();
    let slot = |k: usize| present.iter().position(|&q| q == k).unwrap_or(0);
    let p = j.ncols();
    let mut a = vec![DMatrix::<f64>::zeros(p, p); nk];
    for (row, &k) in j.row_iter().zip(kinds) {
        a[slot(k)] += row.transpose() * row;
    }
    let hat = j * m * j.transpose();
    let mut g = DMatrix::<f64>::zeros(nk, nk);
    for (i, &ki) in kinds.iter().enumerate() {
        for (l, &kl) in kinds.iter().enumerate() {
            let d = f64::from(u8::from(i == l)) - hat[(i, l)];
            g[(slot(ki), slot(kl))] += d * d;
        }
    }
    let c = g
        .try_inverse()
        .map(|gi| gi * 2.0)
        .filter(|c| c.iter().all(|x| x.is_finite()))
        .unwrap_or_else(|| {
            DMatrix::from_fn(nk, nk, |r, s| {
                if r == s {
                    2.0 / kind_dof[present[r]].max(1e-3)
                } else {
                    0.0
                }
            })
        });
    let mut inner = DMatrix::<f64>::zeros(p, p);
    for r in 0..nk {
        inner += &a[r] * c[(r, r)];
        for s in 0..nk {
            inner -= &a[r] * m * &a[s] * c[(r, s)];
        }
    }
    let cov = m + m * inner * m * 2.0;
    let parts: Vec<DMatrix<f64>> = a.iter().map(|ak| m * ak * m).collect();
    let dof = (0..p)
        .map(|col| {
            let v = DVector::from_iterator(nk, parts.iter().map(|q| q[(col, col)]));
            let dof = 2.0 * v.sum().powi(2) / (v.transpose() * &c * &v)[(0, 0)];
            (dof.is_finite() && dof > 0.0).then_some(dof)
        })
        .collect();
    Adjusted { cov, dof }
}

/// The parameters carrying the null direction of `j` (columns scaled to unit norm), if its
/// singular values fall below 1e-7 of the largest.
fn unidentifiable(j: &DMatrix<f64>) -> Option<Vec<usize>> {
    let n = j.ncols();
    let norms: Vec<f64> = (0..n).map(|c| j.column(c).norm()).collect();
    // a zero column: that parameter does nothing
    let zero: Vec<usize> = (0..n)
        .filter(|&c| norms[c] <= 1e-9 * norms.iter().fold(1e-300f64, |a, &b| a.max(b)))
        .collect();
    if !zero.is_empty() {
        return Some(zero);
    }
    let mut js = j.clone();
    for (c, nc) in norms.iter().enumerate() {
        js.column_mut(c).scale_mut(1.0 / nc);
    }
    let svd = js.svd(false, true);
    let sv = &svd.singular_values;
    let (imin, smin) =
        sv.iter().enumerate().fold(
            (0, f64::INFINITY),
            |a, (i, &s)| if s < a.1 { (i, s) } else { a },
        );
    let smax = sv.iter().fold(0.0f64, |a, &s| a.max(s));
    if smin > 1e-7 * smax {
        return None;
    }
    let vt = svd.v_t?;
    let v = vt.row(imin);
    Some((0..n).filter(|&c| v[c].abs() > 0.3).collect())
}

/// Estimates μs, μk (and on request η, β, the corrugation's amplitude, wavelength, phase) of
/// `scene` from the slips of `trace` (module docs). Errors for invalid input (fewer than one
/// slip, non-finite values, a corrugation to fit on a surface that is not one sine), when the
/// start cannot be guessed, or when Gauss–Newton fails.
pub fn fit(scene: &Scene, trace: &Trace, opts: &FitOptions) -> Result<FitResult, VibrissaError> {
    let (mut model, mut message, held) = setup(scene, trace, opts)?;
    let n = model.obs.len();
    // no residual degrees of freedom: the estimate fits exactly, its spread is unknown unless
    // the noise levels are given
    let exact = model.free.len() == n;
    let mut iterations = 0;
    // pass 1 with unit weights (or the given noise levels), then with estimated levels
    if let Some(s) = opts.sigma {
        model.sigma = s;
    }
    let mut x = global_minimum(&model, &mut iterations)?;
    let mut kind_dof = [f64::NAN; 4];
    let kinds: Vec<usize> = model.obs.iter().map(|(o, _)| o.kind()).collect();
    if opts.sigma.is_none() && !exact {
        (x, kind_dof) = reweight(&mut model, x, &kinds, &mut iterations)?;
    }
    let v = model.near_start_phase(model.natural(&x));
    if v[0] > 0.99 * MAX_MU_S {
        // the drag's own limit: nothing in the trace is matched there
        return Err(VibrissaError::NoConvergence {
            what: "the least-squares fit".into(),
            reason: format!(
                "mu_s ran to {} at the limit {MAX_MU_S}: the trace does not match the scene (its \
                 eta, surface_angle or rod)",
                v[0]
            ),
        });
    }
    let used_sigma = model.sigma;
    model.sigma = model.sigma.map(|s| if s.is_nan() { 1.0 } else { s });
    let r = model.residuals(v);
    let p = model.free.len() as f64;
    let s2 = match (exact, opts.sigma) {
        (false, _) => r.norm_squared() / (n as f64 - p),
        // given noise levels: the weighted residuals have unit variance
        (true, Some(_)) => 1.0,
        (true, None) => f64::NAN,
    };
    let note = |message: &mut Option<String>, note: String| {
        *message = Some(match message.take() {
            Some(m) => format!("{m}; {note}"),
            None => note,
        });
    };
    if exact && opts.sigma.is_none() {
        note(
            &mut message,
            "as many observations as parameters: the estimate fits them exactly and its standard \
             error needs the noise levels (sigma)"
                .into(),
        );
    }
    if let Some(t) = tips_off_line(scene, trace) {
        note(&mut message, t);
    }
    let consistency = consistency(&model, &x, &mut iterations);
    let misfit = consistency.as_ref().is_some_and(|c| !c.consistent);
    if let Some(c) = consistency.as_ref().filter(|c| !c.consistent) {
        note(&mut message, c.to_string());
    }
    let mut params = estimates(&model, v, (&kinds, &kind_dof), s2, exact, &held)?;
    if misfit {
        // (a standard error describes the noise about a model that fits; this one does not)
        for p in &mut params {
            p.std_error = None;
            p.dof = None;
        }
    }
    let drags = *model.drags.borrow();
    Ok(FitResult {
        params,
        message,
        observations: n,
        sigma: used_sigma,
        s2,
        consistency,
        iterations,
        drags,
    })
}

/// The checked input of [`fit`] as its least-squares model at the starting values, the
/// parameters the signals do not determine held (with the message saying so).
fn setup<'a>(
    scene: &'a Scene,
    trace: &'a Trace,
    opts: &'a FitOptions,
) -> Result<(Model<'a>, Option<String>, Vec<Par>), VibrissaError> {
    if !(1..=1000).contains(&opts.max_iter) {
        return Err(VibrissaError::range(
            "max_iter",
            opts.max_iter as f64,
            "[1, 1000]",
        ));
    }
    opts.solver.validate()?;
    let (rod, surface) = scene.parts()?;
    if (opts.fit_eta || opts.fit_angle) && surface.profile().is_some() {
        return Err(VibrissaError::MethodUnavailable {
            method: "fit of eta or surface_angle".into(),
            reason: "only on a straight surface (a curved profile is placed by its own keys)"
                .into(),
        });
    }
    let corrugation = match scene.surface {
        SurfaceProfile::Sine {
            amplitude,
            wavelength,
            phase,
        } => Some([amplitude, wavelength, phase]),
        _ => None,
    };
    if opts.corrugation.any() && corrugation.is_none() {
        return Err(VibrissaError::MethodUnavailable {
            method: "fit of the corrugation (amplitude, wavelength, phase)".into(),
            reason:
                "the scene's surface is not one sine corrugation (scene [surface] kind = \"sine\", \
                     or one --corrugation-amplitude with its --corrugation-wavelength): its values \
                     are the fit's start"
                    .into(),
        });
    }
    let obs = observations(trace)?;
    if let Some(s) = opts.sigma {
        if let Some(i) = (0..4).find(|&i| !(s[i].is_finite() && s[i] > 0.0)) {
            return Err(VibrissaError::range(
                ["sigma.d", "sigma.fx", "sigma.fy", "sigma.m_base"][i],
                s[i],
                "(0, inf)",
            ));
        }
    }
    let (mu_s0, mu_k0) = match opts.guess {
        Some(g) => g,
        None => start_values(&rod, &surface, trace, opts)?,
    };
    if !(mu_s0 > 0.0 && mu_k0 >= 0.0 && mu_k0 < mu_s0) {
        return Err(VibrissaError::range(
            "guess mu_k",
            mu_k0,
            format!("[0, mu_s = {mu_s0}) with mu_s > 0"),
        ));
    }
    let mut free = vec![Par::MuS, Par::MuK];
    if opts.fit_eta {
        free.push(Par::Eta);
    }
    if opts.fit_angle {
        free.push(Par::Angle);
    }
    let c = opts.corrugation;
    for (on, par) in [
        (c.amplitude, Par::Amplitude),
        (c.wavelength, Par::Wavelength),
        (c.phase, Par::Phase),
    ] {
        if on {
            free.push(par);
        }
    }
    // (a surface other than a sine has no corrugation: its values are never used)
    let [amplitude, wavelength, phase] = corrugation.unwrap_or([0.0, 1.0, 0.0]);
    let mut model = Model {
        scene,
        trace,
        obs,
        sigma: [1.0; 4],
        free,
        base: [
            mu_s0,
            mu_k0.max(1e-6 * mu_s0),
            scene.eta,
            scene.surface_angle,
            amplitude,
            wavelength,
            phase,
        ],
        opts,
        d_max: reach(trace),
        drags: RefCell::new(0),
        memo: RefCell::new(Vec::new()),
    };
    let n = model.obs.len();
    let (message, held) = hold_unidentifiable(&mut model)?;
    if model.free.len() > n {
        return Err(VibrissaError::InvalidTable {
            name: "trace".into(),
            reason: format!(
                "{n} observations for {} parameters: the fit needs at least as many observations \
                 as parameters",
                model.free.len()
            ),
        });
    }
    Ok((model, message, held))
}

/// How far the model's drags go for `trace`: twice as far as its last slip, and 0.05 more
/// (a start whose first slip comes twice as late still sees it). Not further: far from the
/// estimate a drag that has not slipped as often as the trace runs on to here, and beyond the
/// trace a corrugation can trap the rod (issue 31: a drag from the start of a fit of 8 slips,
/// the last at d = 0.042, ran to 0.35 and a trapped slide, 0.6 s against 0.04 s).
fn reach(trace: &Trace) -> f64 {
    let d_last = trace.slips[trace.slips.len() - 1].d;
    let most = match trace.motion {
        crate::FootMotion::Along => crate::drag::MAX_DRAG,
        // (a turn below π/2)
        crate::FootMotion::Turn => MAX_FIT_TURN,
    };
    (2.0 * d_last + REACH_MARGIN).min(most)
}

/// The largest turn of a fit's drags on a turned trace (rad; the range of a turn is below π/2).
const MAX_FIT_TURN: f64 = 1.5;

/// What the model's drags go beyond twice the trace's last slip ([`reach`]).
const REACH_MARGIN: f64 = 0.05;

/// The first `k` slips of the model's trace, as a trace of their own.
fn prefix(trace: &Trace, k: usize) -> Trace {
    Trace {
        slips: trace.slips[..k].to_vec(),
        tips: Vec::new(),
        motion: trace.motion,
    }
}

impl<'a> Model<'a> {
    /// The same problem (parameters, weights, held values) on another trace, e.g. a prefix.
    fn on<'b>(&self, trace: &'b Trace) -> Result<Model<'b>, VibrissaError>
    where
        'a: 'b,
    {
        Ok(Model {
            scene: self.scene,
            trace,
            obs: observations(trace)?,
            sigma: self.sigma,
            free: self.free.clone(),
            base: self.base,
            opts: self.opts,
            d_max: reach(trace),
            drags: RefCell::new(0),
            memo: RefCell::new(Vec::new()),
        })
    }

    /// The weighted residual sum of squares at free coordinates `x`.
    fn cost(&self, x: &[f64]) -> f64 {
        self.residuals(self.natural(x)).norm_squared()
    }
}

/// The lengths of the prefixes the continuation fits: 2, 4, 8, ... slips, below `n`.
fn prefix_lengths(n: usize) -> Vec<usize> {
    std::iter::successors(Some(2usize), |k| Some(2 * k))
        .take_while(|&k| k < n)
        .collect()
}

/// The global strategy of the fit: the least-squares minimum from the starting values, and the
/// one reached by continuation in the trace's length (the first 2, 4, 8, ... slips fitted in
/// turn, each from the last estimate, then the whole trace). The second follows the minimum
/// that a short trace determines unambiguously as slips are added; the first can end in a
/// minimum where the model's slips are shifted against the trace's by a whole period of a
/// corrugation (issue 33: a noise-free corrugated trace fitted to μs 0.5933 for 0.5). The lower
/// of the two.
fn global_minimum(model: &Model<'_>, iters: &mut u64) -> Result<Vec<f64>, VibrissaError> {
    let x0 = model.coords(model.base);
    let direct = gauss_newton(model, x0.clone(), iters);
    let mut x = x0;
    let mut prefix_drags = 0;
    for k in prefix_lengths(model.trace.slips.len()) {
        let sub = prefix(model.trace, k);
        let m = model.on(&sub)?;
        if m.obs.len() <= m.free.len() {
            continue;
        }
        let step = gauss_newton(&m, x.clone(), iters);
        prefix_drags += *m.drags.borrow();
        match step {
            Ok(y) => x = y,
            // (the longer prefixes, or the direct fit, go on from the last good estimate)
            Err(_) => break,
        }
    }
    *model.drags.borrow_mut() += prefix_drags;
    let continued = if prefix_lengths(model.trace.slips.len()).is_empty() {
        None
    } else {
        gauss_newton(model, x, iters).ok()
    };
    match (direct, continued) {
        (Ok(a), Some(b)) => Ok(if model.cost(&b) < model.cost(&a) {
            b
        } else {
            a
        }),
        (Ok(a), None) => Ok(a),
        (Err(_), Some(b)) => Ok(b),
        (Err(e), None) => Err(e),
    }
}

/// The significance level below which [`Consistency`] calls the trace not fitted.
pub const CONSISTENCY_LEVEL: f64 = 1e-3;

/// Whether the residuals are consistent with the noise levels throughout the trace: a
/// predictive (Chow) test of the fit to the first half of the slips against the fit to all of
/// them, with the same weights. With a model that fits, the weighted residuals of the later
/// observations are of the same size as those of the earlier:
///
/// ```text
///     F = ((S − S₁) / (n − n₁)) / (S₁ / (n₁ − p))  ~  F(n − n₁, n₁ − p),
/// ```
///
/// `S`, `S₁` the weighted residual sums of squares of the whole fit and of the half's own fit.
/// A model that matches the first slips but not the later ones (a local minimum, the wrong
/// surface) gives residuals far larger than the noise the first half shows. The statistic is
/// invariant to a common scale of the weights, so it holds with estimated noise levels too.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Consistency {
    /// Slips of the first part.
    pub prefix_slips: usize,
    /// `F`.
    pub f: f64,
    /// Its degrees of freedom `(n − n₁, n₁ − p)`.
    pub dof: (f64, f64),
    /// `P(F' > F)` under a fitting model.
    pub p_value: f64,
    /// `p_value ≥` [`CONSISTENCY_LEVEL`], or the residuals at the solver's own accuracy.
    pub consistent: bool,
}

impl fmt::Display for Consistency {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.consistent {
            write!(
                f,
                "the residuals are consistent along the trace (F = {:.3} on {} and {} degrees of \
                 freedom against its first {} slips, p = {:.3})",
                self.f, self.dof.0, self.dof.1, self.prefix_slips, self.p_value
            )
        } else {
            write!(
                f,
                "the model does not fit the whole trace: the residuals after its first {} slips \
                 are {} times the noise those show (F = {} on {} and {} degrees of \
                 freedom, p = {:.2e}); the estimate is a misfit (a local minimum, or a surface or \
                 rod other than the trace's) and has no standard error",
                self.prefix_slips,
                crate::limits::digits(self.f.sqrt(), 3),
                crate::limits::digits(self.f, 4),
                self.dof.0,
                self.dof.1,
                self.p_value
            )
        }
    }
}

/// Relative size below which residuals are the solver's (a noise-free trace fitted exactly).
const EXACT_RESIDUAL: f64 = 1e-7;

/// The [`Consistency`] check at the estimate `x` (weights as fitted); `None` below 4 slips or
/// when the first half has no residual degrees of freedom.
fn consistency(model: &Model<'_>, x: &[f64], iters: &mut u64) -> Option<Consistency> {
    let slips = model.trace.slips.len();
    if slips < 4 {
        return None;
    }
    let k = slips / 2;
    let sub = prefix(model.trace, k);
    let m = model.on(&sub).ok()?;
    let (n, n1, p) = (model.obs.len(), m.obs.len(), model.free.len());
    if n1 <= p {
        return None;
    }
    let x1 = gauss_newton(&m, x.to_vec(), iters).ok()?;
    *model.drags.borrow_mut() += *m.drags.borrow();
    let (s, s1) = (model.cost(x), m.cost(&x1));
    let (d1, d2) = ((n - n1) as f64, (n1 - p) as f64);
    let f = ((s - s1).max(0.0) / d1) / (s1 / d2);
    let p_value = f_tail(f, d1, d2);
    // the residuals' own size against the observations': at the solver's accuracy the trace is
    // fitted exactly and the ratio is that of rounding errors
    let scale = model
        .obs
        .iter()
        .map(|(o, y)| (y / model.sigma[o.kind()]).powi(2))
        .sum::<f64>();
    let exact = s <= EXACT_RESIDUAL * EXACT_RESIDUAL * scale;
    Some(Consistency {
        prefix_slips: k,
        f,
        dof: (d1, d2),
        p_value,
        consistent: exact || p_value.is_nan() || p_value >= CONSISTENCY_LEVEL,
    })
}

/// On a straight surface, how far the trace's tips lie off one line: a message when they
/// visibly do (rms over 1e-6 rod lengths about their least-squares line), as a corrugated or
/// curved surface's tips would.
fn tips_off_line(scene: &Scene, trace: &Trace) -> Option<String> {
    if !matches!(scene.surface, crate::surface::SurfaceProfile::Line {}) || trace.tips.len() < 3 {
        return None;
    }
    let n = trace.tips.len() as f64;
    let (mx, my) = trace
        .tips
        .iter()
        .fold((0.0, 0.0), |a, t| (a.0 + t[0] / n, a.1 + t[1] / n));
    let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
    for t in &trace.tips {
        let (dx, dy) = (t[0] - mx, t[1] - my);
        sxx += dx * dx;
        sxy += dx * dy;
        syy += dy * dy;
    }
    // the smallest eigenvalue of the scatter matrix: the squared distances to the best line
    let tr = sxx + syy;
    let det = sxx * syy - sxy * sxy;
    let off = (0.5 * tr - (0.25 * tr * tr - det).max(0.0).sqrt()).max(0.0);
    let rms = (off / n).sqrt();
    (rms > TIP_LINE_TOL).then(|| {
        format!(
            "the trace's tips lie off a straight line by {rms:.3e} rod lengths (rms), but the \
             fit's surface is straight: give the surface the trace was measured on (the scene's \
             [surface], or --corrugation-amplitude and --corrugation-wavelength)"
        )
    })
}

/// The tips' distance from one line (rms, rod lengths) above which [`fit`] says they are not on
/// a straight surface.
pub const TIP_LINE_TOL: f64 = 1e-6;

/// `ln Γ(x)`, x > 0 (Lanczos, g = 7, 9 terms: 1e-15 relative).
fn ln_gamma(x: f64) -> f64 {
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    let x = x - 1.0;
    let t = x + 7.5;
    let s = C[0] + (1..9).map(|i| C[i] / (x + i as f64)).sum::<f64>();
    0.5 * std::f64::consts::TAU.ln() + (x + 0.5) * t.ln() - t + s.ln()
}

/// The regularized incomplete beta function `I_x(a, b)`, `a, b > 0` (Lentz's continued
/// fraction; `ln Γ` by Lanczos, 1e-15 relative): the tails of Fisher's F and Student's t, as
/// `P(|T| > t) = I_{ν/(ν+t²)}(ν/2, 1/2)` for `ν` degrees of freedom.
pub fn inc_beta(x: f64, a: f64, b: f64) -> f64 {
    if x <= 0.0 || x >= 1.0 {
        return x.clamp(0.0, 1.0);
    }
    if x > (a + 1.0) / (a + b + 2.0) {
        return 1.0 - inc_beta(1.0 - x, b, a);
    }
    let front =
        (ln_gamma(a + b) - ln_gamma(a) - ln_gamma(b) + a * x.ln() + b * (1.0 - x).ln()).exp() / a;
    let tiny = 1e-300;
    let (mut c, mut d) = (1.0, 1.0 - (a + b) * x / (a + 1.0));
    d = 1.0 / if d.abs() < tiny { tiny } else { d };
    let mut f = d;
    for m in 1..300 {
        let m = m as f64;
        for num in [
            m * (b - m) * x / ((a + 2.0 * m - 1.0) * (a + 2.0 * m)),
            -(a + m) * (a + b + m) * x / ((a + 2.0 * m) * (a + 2.0 * m + 1.0)),
        ] {
            d = 1.0 + num * d;
            d = 1.0 / if d.abs() < tiny { tiny } else { d };
            c = 1.0 + num / c;
            c = if c.abs() < tiny { tiny } else { c };
            f *= c * d;
        }
        if (c * d - 1.0).abs() < 1e-15 {
            break;
        }
    }
    front * f
}

/// `P(F > f)` for Fisher's F with `(d1, d2)` degrees of freedom (1 for f NaN or below 0).
fn f_tail(f: f64, d1: f64, d2: f64) -> f64 {
    if f.is_nan() || f <= 0.0 {
        return if f.is_infinite() { 0.0 } else { 1.0 };
    }
    if f.is_infinite() {
        return 0.0;
    }
    inc_beta(d2 / (d2 + d1 * f), 0.5 * d2, 0.5 * d1)
}

/// The observations of `trace`: each slip's place and the signals given around it, checked.
fn observations(trace: &Trace) -> Result<Vec<(Obs, f64)>, VibrissaError> {
    if trace.slips.is_empty() {
        return Err(VibrissaError::InvalidTable {
            name: "trace".into(),
            reason: "no slip: the fit reads the slips (their places and the signals around them)"
                .into(),
        });
    }
    let mut obs = Vec::new();
    for (k, s) in trace.slips.iter().enumerate() {
        if !(s.d.is_finite() && s.d >= 0.0) || (k > 0 && s.d <= trace.slips[k - 1].d) {
            return Err(VibrissaError::InvalidTable {
                name: "trace".into(),
                reason: format!(
                    "slip {k} at d = {}: slips must be finite, at d >= 0, in increasing order",
                    s.d
                ),
            });
        }
        obs.push((Obs::D(k), s.d));
        for i in 0..3 {
            for (x, o) in [
                (s.before[i], Obs::Before(k, i)),
                (s.after[i], Obs::After(k, i)),
            ] {
                if let Some(v) = x {
                    if !v.is_finite() {
                        return Err(VibrissaError::InvalidTable {
                            name: "trace".into(),
                            reason: format!("slip {k}: {} = {v}", Signal::ALL[i].name()),
                        });
                    }
                    obs.push((o, v));
                }
            }
        }
    }
    Ok(obs)
}

/// The start: μs (and μk) read off the scan at the first slips.
fn start_values(
    rod: &crate::Rod,
    surface: &crate::Surface,
    trace: &Trace,
    opts: &FitOptions,
) -> Result<(f64, f64), VibrissaError> {
    let d1 = trace.slips[0].d;
    let d2 = trace.slips.get(1).map(|s| s.d);
    let back = d2.map(|d2| d1 - (d2 - d1)).filter(|&b| b > 0.0);
    if trace.motion == crate::FootMotion::Turn {
        return turned_start(rod, surface, opts, d1, back);
    }
    let mut at = vec![d1];
    if let Some(b) = back {
        at.insert(0, b);
    }
    let o = ScanOptions {
        d_max: (1.05 * d1).clamp(1e-3, 1.999),
        points: 2,
        solver: opts.solver.clone(),
        contact: opts.contact,
        ..ScanOptions::default()
    };
    let r = crate::scan_at(rod, surface, &o, &at)?;
    let grid: Vec<f64> = r
        .points
        .iter()
        .filter(|p| p.event.is_none())
        .map(|p| p.mu.abs())
        .collect();
    match (grid.len(), back) {
        (2, Some(_)) => Ok((grid[1], grid[0].min(0.95 * grid[1]))),
        (n, _) if n >= 1 => Ok((grid[n - 1], 0.6 * grid[n - 1])),
        _ => Err(VibrissaError::NoConvergence {
            what: "the fit's starting values (the scan to the first slip)".into(),
            reason: r.stop.to_string(),
        }),
    }
}

/// The start on a turned trace: the ratio the stuck tip needs at the first slip's turn `d1`
/// (μs) and at `back` (μk; as [`start_values`] reads the scan), each the last row of a turned
/// drag to there whose tip does not slip (μs 100).
fn turned_start(
    rod: &crate::Rod,
    surface: &crate::Surface,
    opts: &FitOptions,
    d1: f64,
    back: Option<f64>,
) -> Result<(f64, f64), VibrissaError> {
    let ratio = |theta: f64| -> Result<f64, VibrissaError> {
        let o = DragOptions {
            d_max: theta,
            points: 2,
            mu_s: Some(crate::limits::MU_S.hi),
            mu_k: Some(0.5 * crate::limits::MU_S.hi),
            solver: opts.solver.clone(),
            contact: opts.contact,
            motion: crate::FootMotion::Turn,
            ..DragOptions::default()
        };
        let r = drag(rod, surface, &o)?;
        match (r.rows.last(), &r.stop) {
            (Some(p), crate::StopReason::DMax) if p.d == theta => Ok(p.mu.abs()),
            _ => Err(VibrissaError::NoConvergence {
                what: "the fit's starting values (the turned drag to the first slip)".into(),
                reason: r.stop.to_string(),
            }),
        }
    };
    let mu_s = ratio(d1)?;
    Ok(match back {
        Some(b) => (mu_s, ratio(b)?.min(0.95 * mu_s)),
        None => (mu_s, 0.6 * mu_s),
    })
}

/// Identifiability at the start: the parameters the signals do not determine are held at their
/// starting values (the last of them, μk before μs); the message saying so, and the held ones.
fn hold_unidentifiable(model: &mut Model<'_>) -> Result<(Option<String>, Vec<Par>), VibrissaError> {
    let j0 = model.jacobian_natural(model.base)?;
    let mut held = Vec::new();
    let Some(bad) = unidentifiable(&j0) else {
        return Ok((None, held));
    };
    let trace = model.trace;
    let names: Vec<&str> = bad.iter().map(|&c| model.free[c].name()).collect();
    let slips = trace.slips.len();
    let after = trace
        .slips
        .iter()
        .any(|s| s.after.iter().any(Option::is_some));
    let flat = model.base[Par::Amplitude as usize] == 0.0
        && bad
            .iter()
            .all(|&c| matches!(model.free[c], Par::Wavelength | Par::Phase));
    let why = if slips == 1 && !after {
        "the trace has one slip and no signals after it, so nothing in it depends on where the \
         slip ends"
            .to_string()
    } else if flat {
        "the corrugation's amplitude is 0 at the start, so its wavelength and phase change \
         nothing in the drag; start from a nonzero amplitude"
            .to_string()
    } else {
        "the given signals do not change along that direction of the parameters".to_string()
    };
    let message = format!(
        "{} cannot be determined from this trace ({why}); held at the starting value",
        names.join(" and ")
    );
    // hold the last of them (μk before μs)
    let mut drop: Vec<usize> = bad.clone();
    drop.sort_unstable();
    if drop.len() == model.free.len() {
        drop.remove(0);
    }
    for &c in drop.iter().rev() {
        held.push(model.free.remove(c));
    }
    Ok((Some(message), held))
}

/// The line search's contraction of the step per trial.
const LINE_SEARCH_RHO: f64 = 0.5;

/// Gauss–Newton with an Armijo line search (argmin) from `x0`; its iterations added to `iters`.
fn gauss_newton(
    model: &Model<'_>,
    x0: Vec<f64>,
    iters: &mut u64,
) -> Result<Vec<f64>, VibrissaError> {
    let setup = |e: ArgminError| VibrissaError::NoConvergence {
        what: "fit".into(),
        reason: e.to_string(),
    };
    // (halving: a step of Gauss–Newton far from the minimum can be a hundred times too long,
    // and every trial is a drag; argmin's default 0.9 took 40–60 trials there)
    let ls = BacktrackingLineSearch::new(ArmijoCondition::new(1e-6).map_err(setup)?)
        .rho(LINE_SEARCH_RHO)
        .map_err(setup)?;
    let solver = GaussNewtonLS::new(ls)
        .with_tolerance(1e-10)
        .map_err(setup)?;
    let res = Executor::new(Ls(model), solver)
        .configure(|s| {
            s.param(DVector::from_vec(x0))
                .max_iters(model.opts.max_iter)
        })
        .run()
        .map_err(|e| VibrissaError::NoConvergence {
            what: "the least-squares fit (Gauss-Newton)".into(),
            reason: e.to_string(),
        })?;
    *iters += res.state.get_iter();
    let best = res
        .state
        .get_best_param()
        .cloned()
        .ok_or_else(|| VibrissaError::NoConvergence {
            what: "the least-squares fit (Gauss-Newton)".into(),
            reason: "no estimate".into(),
        })?;
    Ok(best.iter().copied().collect())
}

/// The fit with estimated noise levels: each kind's variance from its residuals over its own
/// degrees of freedom, the observations less their leverages (so that the kinds' degrees of
/// freedom add up to n − p); the weights and the fit repeated until the levels settle. The
/// estimate and the kinds' degrees of freedom (NaN levels for kinds without observations).
fn reweight(
    model: &mut Model<'_>,
    mut x: Vec<f64>,
    kinds: &[usize],
    iterations: &mut u64,
) -> Result<(Vec<f64>, [f64; 4]), VibrissaError> {
    let n = model.obs.len();
    let mut kind_dof = [f64::NAN; 4];
    for _ in 0..MAX_REWEIGHT {
        let v = model.natural(&x);
        let r = model.residuals(v);
        let (h, _) = leverages(&model.jacobian_natural(v)?)?;
        // (back to the kinds' own units)
        let e = DVector::from_iterator(n, r.iter().zip(kinds).map(|(ri, &k)| ri * model.sigma[k]));
        let (sig, dof) = kind_levels(kinds, &e, &h);
        kind_dof = dof;
        let new = sig.map(|s| if s.is_nan() { 1.0 } else { s });
        let change = (0..4)
            .map(|k| (new[k] / model.sigma[k]).ln().abs())
            .fold(0.0f64, f64::max);
        model.sigma = new;
        x = gauss_newton(model, x, iterations)?;
        if change < REWEIGHT_TOL {
            break;
        }
    }
    // report NaN for kinds without observations
    for (s, dof) in model.sigma.iter_mut().zip(kind_dof) {
        if dof.is_nan() {
            *s = f64::NAN;
        }
    }
    Ok((x, kind_dof))
}

/// The estimates at `v` with their standard errors: given noise levels are known, and the
/// covariance is (JᵀJ)⁻¹ with s² only a check of them; estimated ones carry s² (1 at the
/// reweighting's fixed point) and Kenward–Roger's correction for having been estimated, with
/// its degrees of freedom. Held parameters are reported as not identifiable.
fn estimates(
    model: &Model<'_>,
    v: Values,
    (kinds, kind_dof): (&[usize], &[f64; 4]),
    s2: f64,
    exact: bool,
    held: &[Par],
) -> Result<Vec<FitParam>, VibrissaError> {
    let j = model.jacobian_natural(v)?;
    let m = leverages(&j).ok().map(|(_, m)| m);
    let (cov, dofs) = match (m, model.opts.sigma, exact) {
        (Some(m), None, false) => {
            let a = adjusted_covariance(kinds, &j, &m, kind_dof);
            (Some(a.cov * s2), a.dof)
        }
        // (no residual degrees of freedom: no noise level, no standard error)
        (_, None, true) => (None, vec![None; model.free.len()]),
        (m, _, _) => (m, vec![None; model.free.len()]),
    };
    let mut params = Vec::new();
    for par in Par::ALL {
        let value = v[par as usize];
        if let Some(c) = model.free.iter().position(|&q| q == par) {
            let se = cov
                .as_ref()
                .map(|m| m[(c, c)].sqrt())
                .filter(|s| s.is_finite());
            params.push(FitParam {
                name: par.name(),
                value,
                std_error: se,
                dof: dofs[c],
                identifiable: true,
            });
        } else if held.contains(&par) {
            params.push(FitParam {
                name: par.name(),
                value,
                std_error: None,
                dof: None,
                identifiable: false,
            });
        }
    }
    Ok(params)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::Rng;
    use proptest::test_runner::{RngAlgorithm, TestRng};

    #[test]
    fn a_fitted_phase_is_reported_within_half_a_turn_of_its_start() {
        use std::f64::consts::{PI, TAU};
        // the turns seen in fits of issue 31 (+1 and +15 turns from a start 0.1 below the truth)
        for (p, start, want) in [
            (0.7 + TAU, 0.6, 0.7),
            (0.7 + 15.0 * TAU, 0.6, 0.7),
            (0.7 - 3.0 * TAU, 0.6, 0.7),
            (-0.2, 6.0, TAU - 0.2),
            (0.6 + PI, 0.6, 0.6 + PI),
            (0.6 - PI, 0.6, 0.6 + PI),
        ] {
            let q = within_pi_of(p, start);
            assert!(
                (q - want).abs() < 1e-13,
                "{p} from {start}: {q}, want {want}"
            );
        }
    }

    /// A linear model with the trace's structure at 4 slips: kinds `d` (4 rows), `fx` (8),
    /// `m_base` (4), two parameters, each kind fixing a different direction.
    fn design() -> (DMatrix<f64>, Vec<usize>, [f64; 4]) {
        let mut rows = Vec::new();
        let mut kinds = Vec::new();
        for k in 0..4 {
            let k = k as f64;
            for (kind, row) in [
                (0, [1.0, 0.5 * k]),
                (1, [1.0, 0.2]),
                (1, [0.3, 1.0]),
                (3, [1.0, -0.5]),
            ] {
                rows.extend(row);
                kinds.push(kind);
            }
        }
        let x = DMatrix::from_row_slice(kinds.len(), 2, &rows);
        (x, kinds, [0.5, 1.0, f64::NAN, 0.7])
    }

    /// The estimate, `M` and the adjusted covariance of one noisy sample of the linear model,
    /// the noise levels estimated by the fit's fixed point ([`kind_levels`]).
    fn egls(
        x: &DMatrix<f64>,
        kinds: &[usize],
        y: &DVector<f64>,
    ) -> (DVector<f64>, DMatrix<f64>, Adjusted) {
        let mut sigma = [1.0; 4];
        let weigh = |sigma: &[f64; 4]| {
            let mut j = x.clone();
            for (mut row, &k) in j.row_iter_mut().zip(kinds) {
                row /= sigma[k];
            }
            let yw =
                DVector::from_iterator(y.len(), y.iter().zip(kinds).map(|(yi, &k)| yi / sigma[k]));
            (j, yw)
        };
        for _ in 0..200 {
            let (j, yw) = weigh(&sigma);
            let (h, m) = leverages(&j).unwrap();
            let beta = &m * j.transpose() * yw;
            let e = y - x * &beta;
            let (sig, _) = kind_levels(kinds, &e, &h);
            let new = sig.map(|s| if s.is_nan() { 1.0 } else { s });
            let change = (0..4)
                .map(|k| (new[k] / sigma[k]).ln().abs())
                .fold(0.0f64, f64::max);
            sigma = new;
            if change < 1e-10 {
                break;
            }
        }
        let (j, yw) = weigh(&sigma);
        let (h, m) = leverages(&j).unwrap();
        let beta = &m * j.transpose() * yw;
        let e = y - x * &beta;
        let (_, dof) = kind_levels(kinds, &e, &h);
        let a = adjusted_covariance(kinds, &j, &m, &dof);
        (beta, m, a)
    }

    /// Kenward–Roger against Monte Carlo: over 20000 samples of the linear model with the
    /// trace's structure (4, 8, 4 observations per kind), the mean of `M(σ̂)` falls short of the
    /// estimates' true variance (by more than 4 of the Monte Carlo's relative standard errors,
    /// √(2/N) = 1 %: the test can see the bias), and the mean of `M + 2Λ` removes at least half
    /// of that shortfall (the correction is first order in `1/ν`, what it leaves second order:
    /// with ν ≈ 3–7 per kind, well under half).
    #[test]
    fn kenward_roger_removes_the_bias_of_the_covariance() {
        let (x, kinds, sigma) = design();
        let mut rng = TestRng::from_seed(RngAlgorithm::ChaCha, &[7; 32]);
        let mut uniform = || ((rng.next_u64() >> 11) as f64 + 0.5) / (1u64 << 53) as f64;
        let trials = 20000;
        let (mut var, mut plain, mut adjusted) = ([0.0; 2], [0.0; 2], [0.0; 2]);
        for _ in 0..trials {
            let y = DVector::from_iterator(
                kinds.len(),
                kinds.iter().map(|&k| {
                    let (a, b): (f64, f64) = (uniform(), uniform());
                    sigma[k] * (-2.0 * a.ln()).sqrt() * (std::f64::consts::TAU * b).cos()
                }),
            );
            let (beta, m, a) = egls(&x, &kinds, &y);
            for c in 0..2 {
                // (the truth is 0)
                var[c] += beta[c] * beta[c] / trials as f64;
                plain[c] += m[(c, c)] / trials as f64;
                adjusted[c] += a.cov[(c, c)] / trials as f64;
            }
        }
        let mc = (2.0 / trials as f64).sqrt();
        for c in 0..2 {
            let (ru, ra) = (plain[c] / var[c], adjusted[c] / var[c]);
            assert!(
                ru < 1.0 - 4.0 * mc,
                "parameter {c}: M/var {ru}, (M + 2Λ)/var {ra}"
            );
            assert!(
                (ra - 1.0).abs() < 0.5 * (ru - 1.0).abs(),
                "parameter {c}: M/var {ru}, (M + 2Λ)/var {ra}"
            );
        }
    }

    /// One kind of observation: no correction (Student's t with n − p degrees of freedom is
    /// exact), and those are the degrees of freedom.
    #[test]
    fn one_kind_needs_no_correction() {
        let (x, _, _) = design();
        let kinds = vec![0; x.nrows()];
        let (h, m) = leverages(&x).unwrap();
        let e = DVector::from_fn(x.nrows(), |i, _| (i as f64).sin());
        let (_, dof) = kind_levels(&kinds, &e, &h);
        assert!((dof[0] - 14.0).abs() < 1e-12, "{dof:?}");
        let a = adjusted_covariance(&kinds, &x, &m, &dof);
        assert!((&a.cov - &m).norm() < 1e-12 * m.norm(), "{a:?} vs {m}");
        for d in a.dof {
            assert!((d.unwrap() - 14.0).abs() < 1e-9);
        }
    }
}
