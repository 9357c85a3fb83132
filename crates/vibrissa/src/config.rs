//! Solver settings: the method, its tolerance, the engine built from them, the tip condition.

use crate::limits;
use crate::VibrissaError;
use bvp::{
    Bvp, BvpError, BvpSolver, Collocation, CollocationOptions, ErrorControl, Guess, Integrator,
    NewtonOptions, Scheme, Shooting, ShootingOptions, Solution,
};
use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

/// Numerical method.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Method {
    /// Single shooting (adaptive Runge–Kutta unless `rk4_steps` is set).
    #[default]
    Shooting,
    /// Multiple shooting with `segments` segments.
    MultipleShooting,
    /// Lobatto IIIA collocation, order 4.
    #[serde(rename = "collocation")]
    Collocation4,
    /// Lobatto IIIA collocation, order 6.
    #[serde(rename = "collocation6")]
    Collocation6,
    /// Closed forms (crate `elastica`); only for the paper's scene.
    Analytic,
}

impl Method {
    /// All methods.
    pub const ALL: [Method; 5] = [
        Method::Shooting,
        Method::MultipleShooting,
        Method::Collocation4,
        Method::Collocation6,
        Method::Analytic,
    ];
    /// The command-line name.
    pub fn name(self) -> &'static str {
        match self {
            Method::Shooting => "shooting",
            Method::MultipleShooting => "multiple-shooting",
            Method::Collocation4 => "collocation",
            Method::Collocation6 => "collocation6",
            Method::Analytic => "analytic",
        }
    }
    /// What the method is, in one line (the program's `--help` lists it).
    pub fn help(self) -> &'static str {
        match self {
            Method::Shooting => {
                "single shooting (adaptive Runge-Kutta, Newton on the unknown initial values)"
            }
            Method::MultipleShooting => "multiple shooting (several segments)",
            Method::Collocation4 => "Lobatto IIIA collocation of order 4 with mesh adaptation",
            Method::Collocation6 => "Lobatto IIIA collocation of order 6 with mesh adaptation",
            Method::Analytic => {
                "closed-form elliptic-integral solution (uniform clamped straight rod only)"
            }
        }
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Method {
    type Err = VibrissaError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Method::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| VibrissaError::InvalidName {
                name: "method",
                value: s.to_string(),
                valid: "shooting, multiple-shooting, collocation, collocation6, analytic",
            })
    }
}

/// The loosest Newton tolerance of any solve: Newton iterates to `min(tol, NEWTON_TOL_MAX)`
/// whatever the discretization tolerance `tol` (see [`SolverConfig::tol`]).
pub(crate) const NEWTON_TOL_MAX: f64 = 1e-9;

/// Solver settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SolverConfig {
    /// Method. Default shooting.
    pub method: Method,
    /// Tolerance of the discretization (integrator local error, collocation residual). Newton
    /// iterates to `min(tol, 1e-9)` (the scan's chord corrector to `min(tol/10, 1e-9)`), so a loose
    /// tolerance coarsens the mesh but never leaves iterates that continuation would take for
    /// the branch. Default 1e-10.
    pub tol: f64,
    /// Segments of multiple shooting. Default 8.
    pub segments: usize,
    /// `Some(n)`: fixed-step RK4 with `n` steps instead of the adaptive integrator.
    pub rk4_steps: Option<usize>,
    /// Which equilibrium a solve or a scan starts from: the rod pressed onto the surface (or
    /// loaded at its tip) from its rest shape (default), or the state connected to the straight
    /// uniform rod pressed the same way (the homotopy in the rod's deviations).
    pub start: StartKind,
    /// A flag another thread may set to stop the run at its next step (a scan, drag or whisk
    /// then ends with [`crate::StopReason::Cancelled`], its rows so far kept). Default: none.
    #[serde(skip)]
    pub cancel: Cancel,
}

/// A cancellation flag shared with another thread (Ctrl-C in Python): not part of a
/// configuration's value (any two compare equal; never serialized).
#[derive(Clone, Debug, Default)]
pub struct Cancel(Option<std::sync::Arc<std::sync::atomic::AtomicBool>>);

impl Cancel {
    /// A run stops at its next step once `flag` is set.
    pub fn new(flag: std::sync::Arc<std::sync::atomic::AtomicBool>) -> Self {
        Cancel(Some(flag))
    }

    /// Whether the run was asked to stop.
    pub fn is_set(&self) -> bool {
        (self.0.as_ref()).is_some_and(|f| f.load(std::sync::atomic::Ordering::Relaxed))
    }
}

impl PartialEq for Cancel {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

impl Default for SolverConfig {
    fn default() -> Self {
        SolverConfig {
            method: Method::Shooting,
            tol: SolverConfig::DEFAULT_TOL,
            segments: SolverConfig::DEFAULT_SEGMENTS,
            rk4_steps: None,
            start: StartKind::Pressed,
            cancel: Cancel::default(),
        }
    }
}

impl SolverConfig {
    /// The default tolerance.
    pub const DEFAULT_TOL: f64 = 1e-10;
    /// The default number of segments of multiple shooting.
    pub const DEFAULT_SEGMENTS: usize = 8;

    /// The tolerance of the rod's own shooter when this configuration is plain single shooting
    /// with the adaptive integrator (which the shooter replaces), else `None`.
    pub(crate) fn own_shooter_tol(&self) -> Option<f64> {
        (self.method == Method::Shooting && self.rk4_steps.is_none()).then_some(self.tol)
    }
    /// The tolerance of the start's press (the rod pressed onto the surface): the run's own on
    /// the rod's own shooter; for a generic method, which solves its first point itself from
    /// the press's rod, no looser than 1e-8, so that the guess (and the adaptive mesh the
    /// method grows from it) does not coarsen with the method's tolerance.
    pub(crate) fn start_tol(&self) -> f64 {
        self.own_shooter_tol().unwrap_or(self.tol.min(1e-8))
    }
    /// Checks the values against [`limits`](crate::limits): `tol ∈ [1e-15, 1e-2]`,
    /// `segments ∈ [1, 10000]`, `rk4_steps ∈ [1, 1e7]`.
    pub fn validate(&self) -> Result<(), VibrissaError> {
        limits::TOL.check("tol", self.tol)?;
        limits::SEGMENTS.check_count("segments", self.segments)?;
        if let Some(n) = self.rk4_steps {
            limits::RK4_STEPS.check_count("rk4_steps", n)?;
        }
        Ok(())
    }
}

/// A BVP solver built from a [`SolverConfig`]; keeps its work buffers across solves.
#[derive(Clone, Debug)]
#[allow(clippy::large_enum_variant)] // one per solve or scan, never in bulk
pub(crate) enum Engine {
    Shoot(Shooting),
    Coll(Collocation),
}

impl Engine {
    /// For the steps of a continuation, which start from good predictions: a step that needs
    /// more than `max_iter` Newton iterations is better shortened than pursued.
    pub(crate) fn with_max_iter(
        cfg: &SolverConfig,
        max_iter: usize,
    ) -> Result<Engine, VibrissaError> {
        cfg.validate()?;
        let newton = NewtonOptions {
            max_iter,
            tol: cfg.tol,
            ..NewtonOptions::default()
        };
        let wrap = |e: BvpError| VibrissaError::solver("solver options", e);
        let integrator = match cfg.rk4_steps {
            Some(steps) => Integrator::Rk4 { steps },
            None => Integrator::Adaptive {
                rtol: cfg.tol,
                atol: cfg.tol,
            },
        };
        Ok(match cfg.method {
            Method::Shooting | Method::MultipleShooting | Method::Analytic => {
                let segments = if cfg.method == Method::MultipleShooting {
                    cfg.segments
                } else {
                    1
                };
                Engine::Shoot(
                    Shooting::new(ShootingOptions {
                        integrator,
                        segments,
                        // Newton to NEWTON_TOL_MAX at most whatever the integration tolerance:
                        // scans and homotopies predict from the last points, and loose
                        // residuals are noise there (multiple shooting at tol 1e-3 stopped at
                        // d = 0.11 on the paper scan with a singular Jacobian)
                        newton: NewtonOptions {
                            tol: cfg.tol.min(NEWTON_TOL_MAX),
                            ..newton
                        },
                        // a smooth rod needs a few hundred steps at most; more means a Newton
                        // iterate far off (huge f), better rejected fast
                        max_steps: 1500,
                        ..ShootingOptions::default()
                    })
                    .map_err(wrap)?,
                )
            }
            Method::Collocation4 | Method::Collocation6 => {
                let scheme = if cfg.method == Method::Collocation4 {
                    Scheme::Lobatto4
                } else {
                    Scheme::Lobatto6
                };
                Engine::Coll(
                    Collocation::new(CollocationOptions {
                        scheme,
                        tol: cfg.tol,
                        // boundary rows and Newton to NEWTON_TOL_MAX at most, as for shooting
                        bc_tol: Some(cfg.tol.min(NEWTON_TOL_MAX)),
                        max_nodes: 20_000,
                        // Residual control, not bvp's default (`Confirmed`): on the paper's scan
                        // (default scene, 201 points) both give the same rows byte for byte at
                        // tol 1e-4, 1e-6, 1e-8 and 1e-10, orders 4 and 6 (μ within 1.4e-11 of the
                        // closed form at 1e-10), and `Confirmed` took 1.0–1.9× the time
                        control: ErrorControl::Residual,
                        newton: NewtonOptions {
                            tol: cfg.tol.min(NEWTON_TOL_MAX),
                            ..newton
                        },
                        ..CollocationOptions::default()
                    })
                    .map_err(wrap)?,
                )
            }
        })
    }
}

impl BvpSolver for Engine {
    fn solve<B: Bvp + ?Sized>(&mut self, p: &B, g: &Guess) -> Result<Solution, BvpError> {
        match self {
            Engine::Shoot(s) => s.solve(p, g),
            Engine::Coll(c) => c.solve(p, g),
        }
    }
}

/// The tip condition of a solve.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Target {
    /// Tip slope `φ(1)`; unknown `f`.
    Phi1(f64),
    /// Tip height `y(1)`; unknown `f`.
    Eta(f64),
    /// Tip position; unknowns `f` and `α` (the given `α` is only the start of the search).
    Tip {
        /// Tip x.
        x1: f64,
        /// Tip y.
        y1: f64,
    },
}

impl StartKind {
    /// Every start.
    pub const ALL: [StartKind; 2] = [StartKind::Pressed, StartKind::Connected];
    /// The name in scene files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            StartKind::Pressed => "pressed",
            StartKind::Connected => "connected",
        }
    }
    /// What the start is, in one line (the program's `--help` lists it).
    pub fn help(self) -> &'static str {
        match self {
            StartKind::Pressed => "pressed onto the surface from the rest shape",
            StartKind::Connected => "connected to the pressed straight uniform rod",
        }
    }
}

impl FromStr for StartKind {
    type Err = VibrissaError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        StartKind::ALL
            .into_iter()
            .find(|k| k.name() == s)
            .ok_or_else(|| VibrissaError::InvalidName {
                name: "start",
                value: s.to_string(),
                valid: "pressed, connected",
            })
    }
}

/// Which equilibrium a scan or a solve starts from.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StartKind {
    /// The rod pressed onto the surface from its rest shape (frictionless, normal to the
    /// surface), by continuation in the load from first touch; a rod with no preferred side
    /// (straight, horizontal surface) bends to the right.
    #[default]
    Pressed,
    /// The tip-loaded state connected to the straight uniform rod pressed the same way, by the
    /// homotopy in the rod's deviations (taper, rest curvature, compliance): the force normal to
    /// the surface, the tip at height η. A rod bent against its own rest curvature can be such a
    /// state.
    Connected,
}
