//! The stiction scan of section 3 in closed form (Remark 3.1).
//!
//! The tip sticks at height `eta` while the foot moves right by `d`. Phase 0: convex rod, solved
//! in `phi1` for each `alpha in [alpha_end, 0]`. It ends either at the turning point
//! (`phi1 = pi/2 + 2 alpha_t`, `kappa(0) = 0`, a flex point is born at the clamp) or, for low
//! surfaces (e.g. `eta = 0.6`), with a horizontal tip `phi1 = 0` before the turning point (the
//! rod would have to cross the surface to go on). Phase 1: one-flex rod, parameterised by
//! `phi1` descending from `phi1_t`, solved in `alpha`. On that sheet `phi1` has a minimum (a
//! fold: the paper's "computing break"), beyond which the scan goes on along the other root
//! (`phase1_upper_at_phi1`), which only pseudo-arclength continuation (crate `vibrissa`) follows
//! in `d`.

use crate::branch::Branch;
use crate::elastica::{solve_eta, Elastica};
use crate::error::{finite, ElasticaError};
use crate::roots::{brent_max, brent_root};
use crate::{ellint::half_pi_plus, lower_limit};
use serde::{Deserialize, Serialize};
use std::f64::consts::FRAC_PI_4;

/// One point of the scan.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ScanPoint {
    /// foot displacement `d = x1(start) - x1(current)`
    pub d: f64,
    /// friction ratio the contact must supply, `mu = tan(-alpha) = -fx/|fy|` (signed)
    pub mu: f64,
    /// force angle
    pub alpha: f64,
    /// tip slope
    pub phi1: f64,
    /// force magnitude
    pub f: f64,
    /// `f sin(alpha)`
    pub fx: f64,
    /// `-f cos(alpha)`
    pub fy: f64,
    /// `m(0) = kappa(0)` (the paper's clamp moment is `-m_base`)
    pub m_base: f64,
    /// tip x relative to the foot
    pub x1: f64,
    /// number of flex points
    pub flex: usize,
}

/// How phase 0 (convex rod) ends.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Phase0End {
    /// at the turning point `phi1 = pi/2 + 2 alpha_t`; phase 1 (one flex) follows
    TurningPoint,
    /// with a horizontal tip `phi1 = 0` before the turning point; there is no phase 1
    TipHorizontal,
}

/// The closed-form stiction scan at surface height `eta in (eta_, 1)`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ClosedFormScan {
    /// surface height
    pub eta: f64,
    /// starting rod: `alpha = 0`, convex, `y1 = eta`
    pub start: Elastica,
    /// end of phase 0: the turning point (Remark 3.1) or, see `phase0_end`, the `phi1 = 0` rod
    pub turning: ScanPoint,
    /// how phase 0 ends
    pub phase0_end: Phase0End,
    /// `alpha` at the end of phase 0
    pub alpha_t: f64,
    /// `phi1` at the end of phase 0
    pub phi1_t: f64,
    /// minimum of `phi1` on the one-flex phase (the fold), if it is above 0; `None` if the
    /// one-flex phase reaches `phi1 = 0` or does not exist
    pub fold: Option<ScanPoint>,
}

const TOL: f64 = 1e-15;

fn y1_turning(alpha: f64) -> Result<f64, ElasticaError> {
    Ok(Elastica::turning(Branch::Convex, alpha)?.y1)
}

fn y1_flex(alpha: f64, phi1: f64) -> Result<f64, ElasticaError> {
    Ok(Elastica::new(Branch::OneFlex, alpha, phi1)?.y1)
}

/// Lowest admissible alpha of the one-flex branch at this phi1: phi1 = pi/2 + 2 alpha.
fn alpha_low(phi1: f64) -> f64 {
    (0.5 * half_pi_plus(-1.0, &[phi1])).max(-FRAC_PI_4)
}

/// Peak of y1 over alpha in [alpha_low(phi1), 0] on the one-flex branch: (alpha, y1).
fn flex_peak(phi1: f64) -> Result<(f64, f64), ElasticaError> {
    Ok(brent_max(
        |a| y1_flex(a, phi1),
        alpha_low(phi1),
        0.0,
        1e-12,
        500,
    )?)
}

impl ClosedFormScan {
    /// Set up the scan at height `eta in (eta_, 1)`: the start (`alpha = 0`) and the end of
    /// phase 0 (the turning point `alpha_t` with `y1 = eta` at `phi1 = pi/2 + 2 alpha_t`, or the
    /// horizontal-tip rod), and the fold of phase 1.
    pub fn new(eta: f64) -> Result<Self, ElasticaError> {
        finite("eta", eta)?;
        let (_, eta_low) = lower_limit();
        if !(eta > eta_low && eta < 1.0) {
            return Err(ElasticaError::EtaOutOfRange {
                eta,
                min: eta_low,
                max: 1.0,
            });
        }
        let start = solve_eta(Branch::Convex, 0.0, eta)?;
        let x1s = start.x1;
        let y_low = y1_turning(-FRAC_PI_4)?;
        let (end, phase0_end) = if eta > y_low {
            // y1 along the turning-point locus rises from 0.6015 (alpha = -pi/4) to 1 (alpha = 0)
            let at = brent_root(|a| Ok(y1_turning(a)? - eta), -FRAC_PI_4, 0.0, TOL, 200)?;
            (
                Elastica::turning(Branch::Convex, at)?,
                Phase0End::TurningPoint,
            )
        } else {
            // convex rod with a horizontal tip: y1(alpha, 0) rises from eta_ to 0.6015
            let a0 = brent_root(
                |a| Ok(Elastica::new(Branch::Convex, a, 0.0)?.y1 - eta),
                -FRAC_PI_4,
                0.0,
                TOL,
                200,
            )?;
            (
                Elastica::new(Branch::Convex, a0, 0.0)?,
                Phase0End::TipHorizontal,
            )
        };
        let mut scan = ClosedFormScan {
            eta,
            start,
            turning: point(&end, x1s),
            phase0_end,
            alpha_t: end.alpha,
            phi1_t: end.phi1,
            fold: None,
        };
        if phase0_end == Phase0End::TurningPoint {
            // fold: the phi1 where max_alpha y1 = eta (the two alpha roots merge)
            let gap = |p: f64| -> Result<f64, ElasticaError> { Ok(flex_peak(p)?.1 - eta) };
            if gap(0.0)? < 0.0 {
                let pf = brent_root(gap, 0.0, scan.phi1_t, 1e-13, 200)?;
                let (af, _) = flex_peak(pf)?;
                let e = Elastica::new(Branch::OneFlex, af, pf)?;
                scan.fold = Some(point(&e, x1s));
            }
        }
        Ok(scan)
    }

    /// Smallest `phi1` of the one-flex phase (the fold, or 0).
    pub fn phi1_min(&self) -> f64 {
        self.fold.map_or(0.0, |p| p.phi1)
    }

    /// Phase 0: the convex rod with `y1 = eta` at `alpha in [alpha_t, 0]`.
    pub fn phase0_at_alpha(&self, alpha: f64) -> Result<ScanPoint, ElasticaError> {
        finite("alpha", alpha)?;
        if !(self.alpha_t..=0.0).contains(&alpha) {
            return Err(ElasticaError::AlphaOutOfRange {
                alpha,
                min: self.alpha_t,
                max: 0.0,
            });
        }
        if alpha == self.alpha_t {
            return Ok(self.turning);
        }
        let e = match solve_eta(Branch::Convex, alpha, self.eta) {
            Ok(e) => e,
            // within rounding of the end of phase 0 the root sits on the end of the phi1 range
            Err(ElasticaError::NoRoot { .. }) if (alpha - self.alpha_t).abs() < 1e-9 => {
                return Ok(self.turning)
            }
            Err(e) => return Err(e),
        };
        Ok(point(&e, self.start.x1))
    }

    fn flex_phase_check(&self, phi1: f64) -> Result<(), ElasticaError> {
        finite("phi1", phi1)?;
        if self.phase0_end == Phase0End::TipHorizontal {
            return Err(ElasticaError::NoFlexPhase {
                eta: self.eta,
                alpha_end: self.alpha_t,
            });
        }
        let lo = self.phi1_min();
        if !(lo..=self.phi1_t).contains(&phi1) {
            return Err(ElasticaError::Phi1OutOfRange {
                phi1,
                min: lo,
                max: self.phi1_t,
                branch: Branch::OneFlex,
            });
        }
        Ok(())
    }

    /// Phase 1: the one-flex rod with tip slope `phi1 in [phi1_min, phi1_t]` and `y1 = eta`,
    /// solved for `alpha` on the sheet that starts at the turning point (the root between
    /// `alpha_low = (phi1 - pi/2)/2` and the peak of `y1` over `alpha`).
    pub fn phase1_at_phi1(&self, phi1: f64) -> Result<ScanPoint, ElasticaError> {
        self.flex_phase_check(phi1)?;
        if phi1 == self.phi1_t {
            return Ok(self.turning);
        }
        let (apk, ypk) = flex_peak(phi1)?;
        let lo = alpha_low(phi1);
        let a = if ypk - self.eta <= 1e-14 {
            apk // at the fold
        } else {
            brent_root(|a| Ok(y1_flex(a, phi1)? - self.eta), lo, apk, TOL, 200)?
        };
        Ok(point(
            &Elastica::new(Branch::OneFlex, a, phi1)?,
            self.start.x1,
        ))
    }

    /// The other sheet of phase 1 (beyond the fold): the root in `alpha` between the peak of `y1`
    /// and `alpha = 0`, for cross-checks of continuation codes.
    pub fn phase1_upper_at_phi1(&self, phi1: f64) -> Result<ScanPoint, ElasticaError> {
        self.flex_phase_check(phi1)?;
        let (apk, ypk) = flex_peak(phi1)?;
        let a = if ypk - self.eta <= 1e-14 {
            apk
        } else {
            brent_root(|a| Ok(y1_flex(a, phi1)? - self.eta), apk, 0.0, TOL, 200)?
        };
        Ok(point(
            &Elastica::new(Branch::OneFlex, a, phi1)?,
            self.start.x1,
        ))
    }

    /// End of the curve parameter of [`ClosedFormScan::curve_at`]: 1 when phase 0 ends with a
    /// horizontal tip, 2 when phase 1 has no fold, 3 when it has one.
    pub fn curve_end(&self) -> f64 {
        match (self.phase0_end, self.fold) {
            (Phase0End::TipHorizontal, _) => 1.0,
            (Phase0End::TurningPoint, None) => 2.0,
            (Phase0End::TurningPoint, Some(_)) => 3.0,
        }
    }

    /// The whole scan as one curve in `t ∈ [0, curve_end()]`, so that callers can pass the fold
    /// in `phi1`: `t ∈ [0, 1]` phase 0 (`alpha = alpha_t·t`), `t ∈ [1, 2]` phase 1 (`phi1` from
    /// `phi1_t` down to `phi1_min`), `t ∈ [2, 3]` the other sheet beyond the fold (`phi1` back up).
    /// `d` increases along it up to a fold in `d`, if any.
    pub fn curve_at(&self, t: f64) -> Result<ScanPoint, ElasticaError> {
        finite("t", t)?;
        let end = self.curve_end();
        if !(0.0..=end).contains(&t) {
            return Err(ElasticaError::OutOfRange {
                name: "t",
                value: t,
                min: 0.0,
                max: end,
            });
        }
        let lo = self.phi1_min();
        if t <= 1.0 {
            self.phase0_at_alpha(self.alpha_t * t)
        } else if t <= 2.0 {
            let p = self.phi1_t + (lo - self.phi1_t) * (t - 1.0);
            self.phase1_at_phi1(p.clamp(lo, self.phi1_t))
        } else {
            let p = lo + (self.phi1_t - lo) * (t - 2.0);
            self.phase1_upper_at_phi1(p.clamp(lo, self.phi1_t))
        }
    }

    /// Both phases in scan order: `n0 >= 2` points of phase 0 uniformly in `alpha` from 0 to
    /// `alpha_t` (both included), then `n1` points of phase 1 uniformly in `phi1` from `phi1_t`
    /// (excluded: it is the last phase-0 point) down to `phi1_min` (included). Phase 1 is empty
    /// when the scan has none.
    pub fn points(&self, n0: usize, n1: usize) -> Result<Vec<ScanPoint>, ElasticaError> {
        if n0 < 2 {
            return Err(ElasticaError::OutOfRange {
                name: "n0",
                value: n0 as f64,
                min: 2.0,
                max: f64::INFINITY,
            });
        }
        let mut out = Vec::with_capacity(n0 + n1);
        for i in 0..n0 {
            let a = if i + 1 == n0 {
                self.alpha_t
            } else {
                self.alpha_t * i as f64 / (n0 - 1) as f64
            };
            out.push(self.phase0_at_alpha(a)?);
        }
        if self.phase0_end == Phase0End::TurningPoint {
            let lo = self.phi1_min();
            for j in 1..=n1 {
                let p = if j == n1 {
                    lo
                } else {
                    self.phi1_t + (lo - self.phi1_t) * j as f64 / n1 as f64
                };
                out.push(self.phase1_at_phi1(p)?);
            }
        }
        Ok(out)
    }

    /// Maximum of `mu = tan(-alpha)` over the scan (on the phase-1 sheet before the fold, or at
    /// the end of phase 0 when there is no phase 1), the measurable range of `mu0`.
    pub fn mu_max(&self) -> Result<ScanPoint, ElasticaError> {
        if self.phase0_end == Phase0End::TipHorizontal {
            return Ok(self.turning);
        }
        let (p, _) = brent_max(
            |p| Ok(self.phase1_at_phi1(p)?.mu),
            self.phi1_min(),
            self.phi1_t,
            1e-10,
            500,
        )?;
        self.phase1_at_phi1(p)
    }
}

fn point(e: &Elastica, x1_start: f64) -> ScanPoint {
    ScanPoint {
        d: x1_start - e.x1,
        mu: (-e.alpha).tan(),
        alpha: e.alpha,
        phi1: e.phi1,
        f: e.f,
        fx: e.fx(),
        fy: e.fy(),
        m_base: e.m_base,
        x1: e.x1,
        flex: e.flex_count(),
    }
}
