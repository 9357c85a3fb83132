//! What a scan returns: options, points, events, stop reasons, the measurable range.
//!
//! # Contact and the friction ratio
//!
//! The surface line through the contact point has the unit tangent `t = −(cos β, sin β)`
//! (pointing back, against the drag of the foot) and the upward unit normal `n = (−sin β, cos β)`.
//! The tip force on the rod is `F = (f sin α, −f cos α)`. The contact is unilateral and
//! frictional:
//!
//! ```text
//!     N = −F·n = f cos(α − β) ≥ 0          (the surface pushes; N = 0 is lift-off)
//!     μ = F·t / N = tan(β − α)             (signed friction ratio; |μ| ≤ μ0 while it sticks)
//! ```
//!
//! `μ > 0`: the surface holds the tip back against the drag (the usual case); `μ < 0`: it pushes
//! the tip forward. The tip slips where `|μ|` reaches μ0 (either sign) and lifts off where `N`
//! reaches 0 (where `|μ|` grows without bound).

use crate::config::SolverConfig;
use crate::limits;
use crate::shape::ShapePoint;
use crate::VibrissaError;
use serde::Serialize;
use std::fmt;

/// Options of [`crate::scan()`].
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
    /// Where the rod may touch: anywhere (default) or the tip alone (the paper's model).
    pub contact: ContactModel,
}

/// Where the rod may touch the surface.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ContactModel {
    /// Anywhere: the rod stays on its side of the surface line everywhere (the paper's compound
    /// constraint `y(s) ≤ η`). Where a free part reaches the surface a new contact forms, a tip
    /// that turns tangent lies down, and the scan goes on in the new contact state.
    #[default]
    Anywhere,
    /// The tip alone (the paper's model): a touching side is a penetration that ends the scan.
    Tip,
}

impl ContactModel {
    /// Every model.
    pub const ALL: [ContactModel; 2] = [ContactModel::Anywhere, ContactModel::Tip];
    /// The name in scene files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            ContactModel::Anywhere => "anywhere",
            ContactModel::Tip => "tip",
        }
    }
    /// What the model is, in one line (the program's `--help` lists it).
    pub fn help(self) -> &'static str {
        match self {
            ContactModel::Anywhere => "anywhere along the rod (the paper's compound constraint)",
            ContactModel::Tip => "the tip alone (the paper's model)",
        }
    }
}

impl std::str::FromStr for ContactModel {
    type Err = VibrissaError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        ContactModel::ALL
            .into_iter()
            .find(|k| k.name() == s)
            .ok_or_else(|| VibrissaError::InvalidName {
                name: "contact",
                value: s.to_string(),
                valid: "anywhere, tip",
            })
    }
}

impl Default for ScanOptions {
    fn default() -> Self {
        ScanOptions {
            d_max: ScanOptions::DEFAULT_D_MAX,
            points: ScanOptions::DEFAULT_POINTS,
            mu0: None,
            solver: SolverConfig::default(),
            keep_shapes: None,
            contact: ContactModel::Anywhere,
        }
    }
}

impl ScanOptions {
    /// The default largest foot displacement (rod lengths).
    pub const DEFAULT_D_MAX: f64 = 0.5;
    /// The default number of output points (`d` in steps of 0.0025 to the default `d_max`).
    pub const DEFAULT_POINTS: usize = 201;

    /// Checks against [`crate::limits`]: `d_max ∈ (0, 2)`, `points ∈ [2, 1e6]`,
    /// `mu0 ≥ 0` finite, `keep_shapes ∈ [2, 1e5]`, the solver.
    pub fn validate(&self) -> Result<(), VibrissaError> {
        limits::D_MAX.check("d_max", self.d_max)?;
        limits::POINTS.check_count("points", self.points)?;
        if let Some(mu0) = self.mu0 {
            limits::MU0.check("mu0", mu0)?;
        }
        if let Some(n) = self.keep_shapes {
            limits::SHAPE_POINTS.check_count("keep_shapes", n)?;
            limits::check_shapes("keep_shapes", n, self.points)?;
        }
        self.solver.validate()
    }
}

/// One point of the scan.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ScanPoint {
    /// Foot displacement.
    pub d: f64,
    /// Signed friction ratio the contact must supply, `μ = F·t/N = tan(β − α)` (β: surface
    /// angle; `tan(−α)` on the flat surface); see the module docs.
    pub mu: f64,
    /// Normal force `N = −F·n = f cos(α − β)` (≥ 0 while the tip touches); with several
    /// contacts their sum.
    pub normal: f64,
    /// The largest friction ratio `|T_j|/N_j` any single contact needs (equal to `|mu|` with one
    /// contact); a stuck contact slips where it reaches μ0.
    pub mu_peak: f64,
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
    /// Which parts of the rod touch (`tip`, `side`, `side+tip`, …, along the rod from the foot).
    pub contact: ContactLabel,
    /// Arc length of the first contact inside the rod (a side touching or lying on the surface,
    /// or a point object), if there is one.
    pub s_c: Option<f64>,
    /// The event at this point, if it is one (a change of the contact state, or where the scan
    /// stopped), not a grid point.
    pub event: Option<Event>,
    /// Lab x of the contact point of a round tip (tip radius > 0) touching the surface (the
    /// disk's centre is the rod's end); `None` for a point tip.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub x_contact: Option<f64>,
}

impl ScanPoint {
    /// A point with every number NaN (a placeholder where a scan has no point).
    pub fn nan() -> ScanPoint {
        ScanPoint {
            d: f64::NAN,
            mu: f64::NAN,
            normal: f64::NAN,
            mu_peak: f64::NAN,
            alpha: f64::NAN,
            phi1: f64::NAN,
            f: f64::NAN,
            fx: f64::NAN,
            fy: f64::NAN,
            m_base: f64::NAN,
            flex: 0,
            s_flex: None,
            y_max: f64::NAN,
            contact: ContactLabel("none"),
            s_c: None,
            event: None,
            x_contact: None,
        }
    }
}

/// The contact state of a point: which parts of the rod touch, in order from the foot.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct ContactLabel(&'static str);

impl ContactLabel {
    /// The states the model has names for; longer sets are `multiple`.
    const NAMES: [&'static str; 18] = [
        "none",
        "tip",
        "side",
        "side+tip",
        "side+side",
        "side+side+tip",
        "point",
        "point+tip",
        "side+point",
        "point+side",
        "point+point",
        "stretch",
        "side+stretch",
        "point+stretch",
        "side+side+stretch",
        "stretch+tip",
        "side+stretch+tip",
        "multiple",
    ];
    pub(crate) fn of(set: &crate::chain::ContactSet) -> ContactLabel {
        let l = set.label();
        ContactLabel(
            Self::NAMES
                .iter()
                .find(|n| **n == l)
                .copied()
                .unwrap_or("multiple"),
        )
    }
    /// The tip alone (the paper's model).
    pub const TIP: ContactLabel = ContactLabel("tip");
    /// The name (`tip`, `side+tip`, …).
    pub fn name(self) -> &'static str {
        self.0
    }
}

impl fmt::Display for ContactLabel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.0)
    }
}

/// An event of a scan, located to the solver's tolerance on the rod itself: a change of the
/// contact state, or the end of the scan.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Event {
    /// `|μ|` reached μ0 at a stuck contact: it slips (either direction). Ends the scan.
    Slip,
    /// The normal force of the last contact reached zero: the rod leaves the surface. Ends the
    /// scan.
    LiftOff,
    /// Tip-only model (`ContactModel::Tip`): the rod touches the surface elsewhere, or its tip
    /// turns into it. Ends the scan.
    Penetration,
    /// `d` has a maximum along the branch: snap-through. Ends the scan.
    FoldInD,
    /// A new contact forms: a free part of the rod reaches the surface, or the tip lies down on
    /// it (turns tangent). The scan goes on in the new state.
    Touchdown,
    /// The part lying on the surface peels back to the tip: the tip alone touches again.
    PeelBack,
    /// One of several contacts lifts off (its normal force reached zero); the others hold.
    Release,
    /// The point object slips off the tip. Ends a whisk.
    SlipOff,
    /// A contact sliding with kinetic friction comes to rest (its slip rate reached zero) and
    /// holds again. The march goes on.
    Halt,
    /// A side contact on a curved surface that holds without slip begins to lie along it: a
    /// stretch of the rod lies on the surface from there (docs/model.md, "A stretch lying on the surface").
    /// The march goes on.
    LieDown,
    /// The lying stretch shrinks back to a point contact at its outer end. The march goes on.
    PeelUp,
    /// The lying stretch reaches the tip pressing beyond it: the tip's force goes over to the
    /// stretch's outer end, which then draws back from the tip, the rest beyond unloaded
    /// (docs/model.md, "A stretch that reaches the tip"). The march goes on.
    ReachTip,
}

impl Event {
    /// The name used in CSV and JSON (`slip`, `lift_off`, `penetration`, `fold_in_d`,
    /// `touchdown`, `peel_back`, `release`, `slip_off`, `halt`, `lie_down`, `peel_up`,
    /// `reach_tip`).
    pub fn name(self) -> &'static str {
        match self {
            Event::Slip => "slip",
            Event::LiftOff => "lift_off",
            Event::Penetration => "penetration",
            Event::FoldInD => "fold_in_d",
            Event::Touchdown => "touchdown",
            Event::PeelBack => "peel_back",
            Event::Release => "release",
            Event::SlipOff => "slip_off",
            Event::Halt => "halt",
            Event::LieDown => "lie_down",
            Event::PeelUp => "peel_up",
            Event::ReachTip => "reach_tip",
        }
    }
    /// Whether the event ends the march.
    pub fn ends(self) -> bool {
        !matches!(
            self,
            Event::Touchdown
                | Event::PeelBack
                | Event::Release
                | Event::Halt
                | Event::LieDown
                | Event::PeelUp
                | Event::ReachTip
        )
    }
}

/// Why a scan stopped.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "reason", rename_all = "snake_case")]
pub enum StopReason {
    /// `d_max` reached.
    DMax,
    /// `|μ|` reached μ0 at `d`: the tip slips (backwards for μ = μ0, forwards for μ = −μ0).
    Slip {
        /// Displacement.
        d: f64,
        /// Signed μ there (±μ0).
        mu: f64,
    },
    /// The normal force reached zero at `d`: the tip lifts off the surface.
    LiftOff {
        /// Displacement.
        d: f64,
        /// Set where the branch ends at a singular point as the normal force vanishes (no state
        /// beyond it to bracket the root), so that `d` is extrapolated from the last solved
        /// states: the evidence, with the distance extrapolated over.
        #[serde(skip_serializing_if = "Option::is_none")]
        limit: Option<String>,
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
    /// The point object slipped off the tip.
    SlipOff {
        /// Where (the family parameter: the foot angle of a whisk).
        d: f64,
    },
    /// The contact changes to a state the model cannot continue in (the evidence in the
    /// message): a physical limit of the model, not a solver failure.
    ContactChange {
        /// Where.
        d: f64,
        /// What changed, and why the new state does not hold.
        message: String,
    },
    /// A slip has no quasi-static continuation: no contact state consistent with Coulomb
    /// friction goes on from where it stands (the slip turns dynamic; the evidence in the
    /// message): a physical stop.
    Jam {
        /// Where (the foot's place).
        d: f64,
        /// Which contacts, and which condition fails.
        message: String,
    },
    /// The run was cancelled (its configuration's [`crate::Cancel`] set) at `d`.
    Cancelled {
        /// Last value of the parameter reached.
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

impl StopReason {
    /// The reason's name in CSV and JSON (`d_max`, `slip`, `lift_off`, `penetration`,
    /// `fold_in_d`, `slip_off`, `contact_change`, `jam`, `cancelled`, `solver_failure`).
    pub fn name(&self) -> &'static str {
        match self {
            StopReason::DMax => "d_max",
            StopReason::Slip { .. } => "slip",
            StopReason::LiftOff { .. } => "lift_off",
            StopReason::Penetration { .. } => "penetration",
            StopReason::FoldInD { .. } => "fold_in_d",
            StopReason::SlipOff { .. } => "slip_off",
            StopReason::ContactChange { .. } => "contact_change",
            StopReason::Jam { .. } => "jam",
            StopReason::Cancelled { .. } => "cancelled",
            StopReason::SolverFailure { .. } => "solver_failure",
        }
    }
    /// Where the march stopped (its parameter: `d`, or the foot angle of a whisk); `None` at
    /// the end of the range.
    pub fn at(&self) -> Option<f64> {
        match self {
            StopReason::DMax => None,
            StopReason::Slip { d, .. }
            | StopReason::LiftOff { d, .. }
            | StopReason::Penetration { d, .. }
            | StopReason::FoldInD { d }
            | StopReason::SlipOff { d }
            | StopReason::ContactChange { d, .. }
            | StopReason::Jam { d, .. }
            | StopReason::Cancelled { d }
            | StopReason::SolverFailure { d, .. } => Some(*d),
        }
    }
    /// In words, with `param` the name of the marched parameter (`d` for a scan, `theta` for a
    /// whisk); `Display` is `describe("d")`.
    pub fn describe(&self, param: &str) -> String {
        let p = param;
        match self {
            StopReason::DMax => format!("{p}_max reached"),
            StopReason::Slip { d, mu } => format!("slip at {p} = {d} (mu = {mu})"),
            StopReason::LiftOff { d, limit: None } => {
                format!("lift-off at {p} = {d} (normal force 0)")
            }
            StopReason::LiftOff { d, limit: Some(l) } => format!("lift-off at {p} = {d} ({l})"),
            StopReason::Penetration { d, s, y } => {
                format!("penetration at {p} = {d} (s = {s}, y = {y})")
            }
            StopReason::FoldInD { d } => format!("fold in {p} (snap-through) at {p} = {d}"),
            StopReason::SlipOff { d } => format!("the object slipped off the tip at {d}"),
            StopReason::ContactChange { d, message } => {
                format!("contact change at {p} = {d}: {message}")
            }
            StopReason::Jam { d, message } => format!("jam at {p} = {d}: {message}"),
            StopReason::Cancelled { d } => format!("cancelled at {p} = {d}"),
            StopReason::SolverFailure { d, message } => {
                format!("solver failure after {p} = {d}: {message}")
            }
        }
    }
}

impl fmt::Display for StopReason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.describe("d"))
    }
}

/// Result of [`crate::scan()`].
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ScanResult {
    /// Surface height.
    pub eta: f64,
    /// A point of the surface line (foot frame at `d = 0`): where the start's last contact
    /// touches it. The line has the surface's inclination β through it; at `d` it lies `d`
    /// further back (−x) relative to the foot.
    pub surface_point: [f64; 2],
    /// The starting rod (d = 0).
    pub start: ScanPoint,
    /// Points at the requested displacements, up to where the scan stopped.
    pub points: Vec<ScanPoint>,
    /// Largest `|μ|` over the measurable range (located by a 1-D search, not the grid maximum).
    pub mu_max: f64,
    /// The signed μ there.
    pub mu_at_max: f64,
    /// The d where it occurs: the upper end of the measurable range.
    pub d_at_mu_max: f64,
    /// What ends the measurable range (the first monotone stretch of `|μ(d)|` from d = 0).
    pub range_end: RangeEnd,
    /// Why the scan stopped.
    pub stop: StopReason,
    /// Accumulated solver statistics.
    pub stats: bvp::Stats,
    /// Shapes of the output points (if `keep_shapes`).
    pub shapes: Vec<Vec<ShapePoint>>,
    /// Each output point's contacts, one list per point of `points` (in order along the rod):
    /// where each touches and its own normal and tangential force, as a drag's rows give them
    /// ([`crate::drag::ContactState`]; all stuck, `mu` their slip threshold: μ0, without one
    /// infinite, or 10 for a contact that traps the rod with another, the most friction a dry
    /// surface provides). With several contacts a row's `mu_peak` is the largest of their ratios;
    /// their forces say how well it is determined: a contact that carries a small share of
    /// the load has its ratio known to that share of the forces' accuracy.
    pub contacts: Vec<Vec<crate::contacts::ContactState>>,
    /// Set when the scan ran on the rod's own shooter instead of the requested generic method:
    /// why. In a state that traps the rod between two contacts that do not slip, the method's
    /// Newton matrix was singular at its accuracy at the start, or its march ended in a solver
    /// failure (docs/robustness.md). `None`: the requested method computed every point.
    pub handover: Option<String>,
}

/// What ends the measurable range `[0, d_at_mu_max]`: the first monotone stretch of `|μ(d)|`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum RangeEnd {
    /// The first maximum of `|μ|`.
    FirstMaximum,
    /// The scan stopped at an event (slip, lift-off, penetration, fold) while `|μ|` still rose.
    Event,
    /// `d_max` was reached while `|μ|` still rose: the range is cut short.
    DMax,
    /// The solver failed while `|μ|` still rose.
    SolverFailure,
}

impl fmt::Display for RangeEnd {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            RangeEnd::FirstMaximum => "the first maximum of |mu|",
            RangeEnd::Event => "the event that stopped the scan",
            RangeEnd::DMax => "d_max (|mu| still rising: the range is cut short)",
            RangeEnd::SolverFailure => "a solver failure (|mu| still rising)",
        })
    }
}

/// Result of [`crate::infer`].
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Inference {
    /// The stiction coefficient μ0 = |μ(d0)|.
    pub mu0: f64,
    /// The displacement at which the tip slipped.
    pub d0: f64,
    /// The measurable range `[0, d at μ_max]`.
    pub measurable_d: (f64, f64),
    /// μ_max (of `|μ|`).
    pub mu_max: f64,
    /// What ends the measurable range.
    pub range_end: RangeEnd,
}
