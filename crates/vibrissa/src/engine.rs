//! One way into the engine, for every run (scan, drag, whisk, solve) and what comes next: pick
//! the stepper the solver settings ask for (the rod's own shooter, or a generic method of crate
//! `bvp` on the same chain), take the first point, and hand a trapped start over to the own
//! shooter where a generic method cannot take it.
//!
//! A rod trapped between two contacts that do not slip carries a pair of tangential forces that
//! is nearly indeterminate (the inextensible segment between the contacts only bends under
//! them): a generic method whose check finds its Newton matrix singular at its accuracy there,
//! or whose march fails in such a state, hands the run to the rod's own shooter, and the run
//! says so (`docs/robustness.md`).

use crate::chain::{Chain, ContactSet};
use crate::config::{Method, SolverConfig};
use crate::generic::GenericStepper;
use crate::march::{march, MarchOut, Spec};
use crate::own::OwnStepper;
use crate::profile::Profile;
use crate::report::StopReason;
use crate::rodsolve::Converged;

use crate::stepper::{Pt, StepError, Stepper};
use crate::watch::{traps, Env};
use crate::VibrissaError;
use bvp::Stats;

/// How the own shooter takes the first point.
#[derive(Clone, Debug)]
pub(crate) enum FirstPoint {
    /// Corrected from the unknowns (chord Newton, exact tangent there).
    Correct,
    /// Already converged on the chain (its paths hold it).
    Converged(Converged),
}

/// What a run starts from.
#[derive(Clone)]
pub(crate) struct Begin<'s, P: Profile> {
    /// The own shooter's chain: contact set, family, meshes graded for the start.
    pub chain: Chain<P>,
    /// The march's view of the scene.
    pub env: Env,
    pub solver: &'s SolverConfig,
    /// The first point's family parameter and its unknowns on the own shooter.
    pub lam: f64,
    pub u: Vec<f64>,
    pub first: FirstPoint,
    /// The run, in messages: `scan`, `drag`, `whisk`, `solve`.
    pub run: &'static str,
    /// Whether a trapped start a generic method cannot take goes to the own shooter (else its
    /// failure is the error).
    pub hand_over: bool,
    /// The first point, in the error of a start that fails.
    pub what: String,
}

/// A started run: its stepper, the first point, and why it runs on the own shooter if it was
/// handed over.
pub(crate) struct Begun<'a> {
    pub stepper: Box<dyn Stepper + 'a>,
    pub p0: Pt,
    pub handover: Option<String>,
}

impl<P: Profile + 'static> Begin<'_, P> {
    /// The own shooter's stepper and first point.
    fn own(self) -> Result<(Box<dyn Stepper>, Pt), VibrissaError> {
        let what = self.what;
        let mut st = OwnStepper {
            chain: self.chain,
            env: self.env,
            cancel: self.solver.cancel.clone(),
            light: false,
            polish: false,
            retangent: false,
        };
        let p = match self.first {
            FirstPoint::Correct => st.first(self.lam, &self.u),
            FirstPoint::Converged(cv) => st.point(self.lam, cv),
        }
        .map_err(|e| start_failed(&what, &e))?;
        Ok((Box::new(st), p))
    }

    /// Starts the run.
    pub fn begin(self) -> Result<Begun<'static>, VibrissaError> {
        if self.solver.own_shooter_tol().is_some() {
            let (stepper, p0) = self.own()?;
            return Ok(Begun {
                stepper,
                p0,
                handover: None,
            });
        }
        if self.chain.set.tip_radius > 0.0 {
            // (the generic methods' boundary conditions hold m(1) = 0 at the tip)
            return Err(VibrissaError::MethodUnavailable {
                method: self.solver.method.name().into(),
                reason: "a round tip (tip radius > 0) is solved by the rod's own shooter \
                         (method shooting)"
                    .into(),
            });
        }
        let sh = &self.chain.sh;
        let mut g = GenericStepper::new(
            sh.profile.clone(),
            sh.compliance,
            self.chain.set.clone(),
            self.chain.family,
            self.env.clone(),
            self.solver,
        )?;
        match g.first(self.lam, &self.u) {
            Ok(p0) => Ok(Begun {
                stepper: Box::new(g),
                p0,
                handover: None,
            }),
            Err(e) if self.hand_over && e.singular_method() && traps(&self.chain.set) => {
                let handover = trapped_start(self.solver.method, &self.chain.set, self.run);
                let (stepper, p0) = self.own()?;
                Ok(Begun {
                    stepper,
                    p0,
                    handover: Some(handover),
                })
            }
            Err(e) => Err(start_failed(&self.what, &e)),
        }
    }

    /// Starts the run and marches it over `spec`; a generic method's march that ends in a
    /// solver failure in a state that traps the rod (its corrections scatter along the nearly
    /// indeterminate pair) is run again on the own shooter from the same start, and says so.
    pub fn march(
        self,
        spec: &Spec<'_>,
        profile: &P,
        stats: &Stats,
    ) -> Result<(MarchOut, Option<String>), VibrissaError> {
        let generic = self.solver.own_shooter_tol().is_none();
        let (method, run) = (self.solver.method, self.run);
        let again = generic.then(|| self.clone());
        let mut begun = self.begin()?;
        let out = march(&mut *begun.stepper, spec, profile, begun.p0, stats.clone());
        let (Some(again), None) = (again, &begun.handover) else {
            return Ok((out, begun.handover));
        };
        match (&out.stop, &out.last) {
            (StopReason::SolverFailure { d, message }, Some((set, _))) if traps(set) => {
                let failure = format!("{} failed at d = {d} in the state", method.name());
                let why = handover(&failure, set, &format!("{message}; "), run);
                let (mut st, p0) = again.own()?;
                Ok((march(&mut *st, spec, profile, p0, stats.clone()), Some(why)))
            }
            _ => Ok((out, None)),
        }
    }
}

/// The error of a start whose first point failed.
fn start_failed(what: &str, e: &StepError) -> VibrissaError {
    VibrissaError::NoConvergence {
        what: what.to_string(),
        reason: e.to_string(),
    }
}

/// Why a run (scan, drag) ran on the rod's own shooter: the generic method's `failure` in the
/// contact state `set`, which traps the rod, and its own message (`detail`, "" or "…; ").
pub(crate) fn handover(failure: &str, set: &ContactSet, detail: &str, run: &str) -> String {
    format!(
        "{failure} {}, which traps the rod between two contacts that do not slip (the tangential \
         forces between them are nearly indeterminate): {detail}the {run} ran on the rod's own \
         shooter",
        set.label()
    )
}

/// [`handover`] at a start whose Newton matrix `method` finds singular at its accuracy.
fn trapped_start(method: Method, set: &ContactSet, run: &str) -> String {
    let failure = format!(
        "the Newton matrix of {} is singular at its accuracy in the start",
        method.name()
    );
    handover(&failure, set, "", run)
}
