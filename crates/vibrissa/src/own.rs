//! The [`Stepper`] on the rod's own shooter, for every profile and contact set: quintic Hermite
//! predictor through the last three points and their exact tangents `u' = −J⁻¹ ∂R/∂λ`, chord
//! Newton. A sign change of `det J` between neighbours means the corrector crossed a fold:
//! rejected, and passed or located by the fold passage (module `fold`), whose corrections on a
//! hyperplane of `(u, λ)` are the bordered Newton of module `arclength` on the same chain.

use crate::arclength::{self, ArcPoint};
use crate::chain::{Chain, ContactSet, Family};
use crate::control::{corrector_tol, MAX_ITER, OWN_H_MAX};
use crate::profile::Profile;
use crate::rodsolve::{correct_chord, Converged, Flags, ShotFailure};
use crate::stepper::{interpolate, same_branch, within_span, Pt, StepError, Stepper};
use crate::watch::{fill_slip, has_slider, watch, Env, RodView};
use bvp::Stats;
use nalgebra::DVector;

/// States on the rod the watch of one point keeps (see [`OwnStepper::point`]).
const MEMO: usize = 4;

/// How far along the branch (relative to `1 + |λ|`) [`Stepper::clear_rate`] takes its
/// prediction.
const CLEAR_PROBE: f64 = 1e-5;

/// The stepper on the rod's own shooter.
pub(crate) struct OwnStepper<P: Profile> {
    pub chain: Chain<P>,
    pub env: Env,
    pub cancel: crate::config::Cancel,
    /// The points leave out the free parts' clearance ([`Stepper::set_light`]).
    pub light: bool,
    /// The corrector polishes its converged iterates ([`Stepper::set_polish`]).
    pub polish: bool,
    /// The corrector's Jacobian made exact after a second chord step
    /// ([`Stepper::set_retangent`]).
    pub retangent: bool,
}

impl<P: Profile> OwnStepper<P> {
    /// The branch point of a converged solve at `λ` (the shooter's paths hold it).
    pub(crate) fn point(&mut self, lam: f64, cv: Converged) -> Result<Pt, StepError> {
        let du = cv.tangent();
        let det = cv.det();
        self.shot_at(&cv.u, lam)?;
        let sol = self.chain.path(&cv.u);
        let w = self.watch_of(lam, &cv.u, du.as_deref(), &sol, self.light);
        Ok(Pt {
            lam,
            u: cv.u,
            du,
            det: Some(det),
            iters: cv.iterations,
            sol,
            w,
            raw: None,
        })
    }

    /// Makes the shooter's paths those of `(u, λ)`.
    fn shot_at(&mut self, u: &[f64], lam: f64) -> Result<(), StepError> {
        if !self.chain.shot_of(u, lam) {
            // (a solve converted after the shooter went on to other states: its paths are of
            // those, and the watch would read the rod of another point; the fold passage once
            // turned its whole path into points at its end, 982 such points in one texture drag)
            self.chain.eval(u, lam, false).map_err(StepError::Rod)?;
        }
        Ok(())
    }

    /// The watch of the point `(u, λ)` (tangent `du`, whole rod `sol`) on the shooter's paths
    /// of that point (`light`: see [`watch`]).
    fn watch_of(
        &mut self,
        lam: f64,
        u: &[f64],
        du: Option<&[f64]>,
        sol: &bvp::Solution,
        light: bool,
    ) -> crate::watch::Watch {
        let xf = self.chain.family.pose(lam).0.xf;
        let mut w = self.contacts_watch(lam, u, du, sol, light, xf);
        // a round tip on a curve: its contact point's rate (x_c + r sin θ(x_c) = P_x)
        if let (Some(j), Some(d)) = (self.chain.disk_tip(), du) {
            let set = &self.chain.set;
            if let crate::chain::Geom::Curve { h } = &set.contacts[j].geom {
                let foot = self.chain.family.pose(lam).1.xf;
                let px = sol.right()[0] + xf;
                let dk = crate::surface::disk_on_curve(h, set.tip_radius, px, 1.0);
                if let (Some(r), Some(dk)) = (self.chain.contact_rates(u, lam, d), dk) {
                    w.contacts[j].dxc = (r[j][0] + foot) / dk.jac;
                }
            }
        }
        if let (true, Some(d)) = (has_slider(&self.chain.set), du) {
            let foot = self.chain.family.pose(lam).1.xf;
            if let Some(r) = self.chain.contact_rates(u, lam, d) {
                fill_slip(&mut w, &self.chain.set, (u, d), &r, foot);
            }
        }
        // a lying stretch: its ends' point forces and its outer end, its friction
        if let (Some(j), Some(push)) = (self.chain.set.lain(), self.chain.end_push(u)) {
            let set = &self.chain.set;
            let c = &mut w.contacts[j];
            c.end_push = push;
            c.lies_to = set.s2_of(u);
            // (its invariant moves as a slip's driver, or as it slides)
            let slides = crate::chain::is_slider(&set.contacts[j]);
            let dc = if slides {
                c.slide.slip
            } else {
                self.chain.stretch_moved()
            };
            let nt = (c.normal, c.tangential);
            // (its work is asked for where the march meters the friction's work)
            let metered = self.env.ground.meter.is_some();
            let moves = (metered && (slides || dc != 0.0)).then_some(dc);
            // (a slip's driver: the balance it would have sliding with kinetic friction, whose
            // sign says whether μk holds it where the ratio it needs may not exist; where a load
            // beyond outweighs the stretch the balance rises with the ratio, and the ratio,
            // which the secant steps find there, decides)
            let kinetic = (self.env.ground.slide)
                .filter(|sl| sl.driver == j && !slides)
                .map(|sl| sl.dir * c.mu_k)
                .filter(|r| r.is_finite());
            if let Some(f) = self.chain.stretch_friction(u, du, nt, (moves, kinetic)) {
                c.stretch_mu = f.mu;
                c.turn = f.turn;
                if let Some((b, _)) = f.kinetic_balance.filter(|&(_, db)| db < 0.0) {
                    c.kinetic_balance = b;
                }
            }
        }
        w
    }

    /// [`watch`] on the shooter's paths (the foot at `xf`).
    fn contacts_watch(
        &self,
        lam: f64,
        u: &[f64],
        du: Option<&[f64]>,
        sol: &bvp::Solution,
        light: bool,
        xf: f64,
    ) -> crate::watch::Watch {
        let chain = &self.chain;
        // the watch asks for some states more than once (a located maximum, then its state; a
        // contact's place, then its height): the last few are kept (the same function of `s`)
        let mut memo = [(f64::NAN, [0.0; 4]); MEMO];
        let mut slot = 0;
        let mut exact = |s: f64| {
            if let Some((_, z)) = memo.iter().find(|m| m.0.to_bits() == s.to_bits()) {
                return *z;
            }
            let z = chain.state_at(s);
            memo[slot] = (s, z);
            slot = (slot + 1) % MEMO;
            z
        };
        watch(
            &self.env,
            &chain.set,
            lam,
            u,
            du,
            RodView {
                sol,
                xf,
                exact: &mut exact,
                kappa: &|s, m| chain.sh.profile.kappa(s, m),
                straight: chain.sh.profile.straight(),
            },
            light,
        )
    }

    /// The point at `λ` from the prediction `u`.
    pub(crate) fn correct_from(
        &mut self,
        lam: f64,
        u: &[f64],
        newest: Option<&Pt>,
        fresh: bool,
    ) -> Result<Pt, StepError> {
        let tol = corrector_tol(self.chain.sh.tol);
        let flags = Flags {
            fresh,
            polish: self.polish,
            retangent: self.retangent,
        };
        let cv = correct_chord(&mut self.chain, lam, u, tol, MAX_ITER, flags)?;
        let p = self.point(lam, cv)?;
        if p.du.is_none() {
            return Err(StepError::NoTangent);
        }
        // (a polished point may move along the direction the Jacobian nearly loses by more than
        // the step changes the branch: it is searched for within a step already taken)
        if let Some(last) = newest.filter(|_| !self.polish) {
            same_branch(last, u, &p, self.chain.sh.tol)?;
        }
        Ok(p)
    }
}

impl<P: Profile> Stepper for OwnStepper<P> {
    fn set(&self) -> &ContactSet {
        &self.chain.set
    }

    fn correct(&mut self, lam: f64, hist: &[Pt], fresh: bool) -> Result<Pt, StepError> {
        let u = interpolate(hist, lam).0;
        self.correct_from(lam, &u, hist.last(), fresh)
    }

    fn correct_within(&mut self, lam: f64, a: &Pt, b: &Pt) -> Result<Pt, StepError> {
        let u = interpolate(&[a.clone(), b.clone()], lam).0;
        let p = self.correct_from(lam, &u, None, true)?;
        within_span(a, b, &u, &p, self.chain.sh.tol)?;
        Ok(p)
    }

    fn set_light(&mut self, light: bool) {
        self.light = light;
    }

    fn set_retangent(&mut self, retangent: bool) {
        self.retangent = retangent;
    }

    fn set_polish(&mut self, polish: bool) {
        self.polish = polish;
    }

    fn complete(&mut self, p: Pt) -> Result<Pt, StepError> {
        if !p.w.light {
            return Ok(p);
        }
        self.shot_at(&p.u, p.lam)?;
        let xf = self.chain.family.pose(p.lam).0.xf;
        let mut w = self.contacts_watch(p.lam, &p.u, p.du.as_deref(), &p.sol, false, xf);
        // the contacts' slip rates and a round tip's contact rate are the light watch's (the
        // same computation; not shot again with sensitivities)
        w.contacts = p.w.contacts;
        Ok(Pt { w, ..p })
    }

    fn clear_rate(&mut self, p: &Pt) -> Option<f64> {
        let du = p.du.as_deref()?;
        // (the prediction's own error, O(ε²), is far below the clearance's change over ε for
        // any rate that matters; the shot keeps the meshes as they are)
        let eps = CLEAR_PROBE * (1.0 + p.lam.abs());
        let u: Vec<f64> = p.u.iter().zip(du).map(|(u, d)| u + eps * d).collect();
        let lam = p.lam + eps;
        self.chain.eval(&u, lam, false).ok()?;
        let sol = self.chain.path(&u);
        let xf = self.chain.family.pose(lam).0.xf;
        let g = self.contacts_watch(lam, &u, None, &sol, false, xf).clear;
        let rate = (g - p.w.clear) / eps;
        rate.is_finite().then_some(rate)
    }

    fn first(&mut self, lam: f64, u: &[f64]) -> Result<Pt, StepError> {
        self.correct_from(lam, u, None, true)
    }

    fn switch(&mut self, set: ContactSet, lam: f64, u: Vec<f64>) -> Result<Pt, StepError> {
        self.chain.set = set;
        self.correct_from(lam, &u, None, true)
    }

    fn phase(&mut self, family: Family, env: &Env) {
        self.chain.family = family;
        self.env = env.clone();
    }

    fn set_meter(&mut self, meter: Option<crate::surface::Meter>) {
        self.env.ground.meter = meter;
    }

    fn tangent_in(&mut self, set: &ContactSet, lam: f64, u: &[f64]) -> Option<Vec<f64>> {
        self.chain.tangent_in(set.clone(), u, lam)
    }

    fn singular_at(&mut self, lam: f64, u: &[f64]) -> bool {
        self.chain.singular_to_precision(u, lam)
    }

    fn energy(&mut self, u: &[f64], lam: f64) -> Option<f64> {
        self.chain.elastic_energy(u, lam)
    }

    fn stats(&self) -> Stats {
        self.chain.sh.stats.clone()
    }

    fn h_max(&self) -> f64 {
        OWN_H_MAX
    }

    fn lies(&self) -> bool {
        true
    }

    fn foot(&self, lam: f64) -> (f64, f64) {
        let p = self.chain.family.pose(lam).0;
        (p.xf, p.theta)
    }

    fn cancelled(&self) -> bool {
        self.cancel.is_set()
    }

    fn corrector_tol(&self) -> f64 {
        corrector_tol(self.chain.sh.tol)
    }

    fn arc_start(&mut self, last: &Pt, tol: f64) -> Result<ArcPoint, ShotFailure> {
        arclength::at_lambda(&mut self.chain, &last.u, last.lam, tol, 16)
    }

    fn on_plane(
        &mut self,
        _near: &ArcPoint,
        pred: &DVector<f64>,
        normal: &DVector<f64>,
        tol: f64,
        max_iter: usize,
    ) -> Result<ArcPoint, ShotFailure> {
        arclength::correct(&mut self.chain, pred, normal, tol, max_iter)
    }

    fn arc_point(&mut self, a: &ArcPoint) -> Result<Pt, StepError> {
        self.point(a.lam(), a.converged())
    }
}
