//! The rod's stiffness and rest-curvature profiles `b(s)`, `κ0(s)`.
//!
//! Everything numerical is generic over a [`Profile`]; the uniform straight rod uses the
//! zero-sized [`Uniform`] (b ≡ 1, κ0 ≡ 0, folded away by monomorphization), every other rod the
//! table-driven [`General`]. The choice is made once per solve, never per right-hand-side call.

use crate::parts::{Precurvature, Stiffness};

/// Reciprocal bending stiffness `b(s)` and pre-curvature `κ0(s)` of a rod.
pub trait Profile: Clone + Send + Sync + 'static {
    /// True when `b ≡ 1` and `κ0 ≡ 0` (lets the compiler drop the profile entirely).
    const UNIFORM: bool;
    /// `b(s)`.
    fn b(&self, s: f64) -> f64;
    /// `κ0(s)`.
    fn k0(&self, s: f64) -> f64;
    /// The profile at homotopy amplitude `t` (0: the uniform straight rod, 1: itself).
    fn at_amplitude(&self, t: f64) -> Self;
    /// Whether the rest shape is straight (`κ0 ≡ 0`).
    fn straight(&self) -> bool;
    /// `(db/ds, dκ0/ds)` at `s` (the slope of a table's interval there).
    fn slopes(&self, s: f64) -> (f64, f64);
    /// Curvature `κ = κ0(s) + b(s)·m`.
    #[inline(always)]
    fn kappa(&self, s: f64, m: f64) -> f64 {
        if Self::UNIFORM {
            m
        } else {
            self.k0(s) + self.b(s) * m
        }
    }
}

/// The uniform straight rod: `b ≡ 1`, `κ0 ≡ 0`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Uniform;

impl Profile for Uniform {
    const UNIFORM: bool = true;
    fn at_amplitude(&self, _t: f64) -> Self {
        Uniform
    }
    fn straight(&self) -> bool {
        true
    }
    fn slopes(&self, _s: f64) -> (f64, f64) {
        (0.0, 0.0)
    }
    #[inline(always)]
    fn b(&self, _s: f64) -> f64 {
        1.0
    }
    #[inline(always)]
    fn k0(&self, _s: f64) -> f64 {
        0.0
    }
}

/// Piecewise-linear interpolation in a table with strictly increasing `s` (clamped at the ends).
#[inline]
fn interp(s_tab: &[f64], v: &[f64], s: f64) -> f64 {
    let n = s_tab.len();
    if s <= s_tab[0] {
        return v[0];
    }
    if s >= s_tab[n - 1] {
        return v[n - 1];
    }
    let i = s_tab.partition_point(|&t| t <= s).clamp(1, n - 1) - 1;
    let t = (s - s_tab[i]) / (s_tab[i + 1] - s_tab[i]);
    v[i] + t * (v[i + 1] - v[i])
}

/// Any scene's profile, scaled by a homotopy amplitude `t ∈ [0, 1]` (t = 1: the scene itself,
/// t = 0: the uniform straight rod). Taper: ratio `1 − t(1 − ρ)`; table `b`: `b^t`; `κ0`: `t·κ0`.
#[derive(Clone, Debug, PartialEq)]
pub struct General {
    stiffness: Stiffness,
    precurvature: Precurvature,
    t: f64,
}

impl General {
    /// The profile of `stiffness` and `precurvature` at homotopy amplitude `t`.
    pub fn new(stiffness: &Stiffness, precurvature: &Precurvature, t: f64) -> Self {
        General {
            stiffness: stiffness.clone(),
            precurvature: precurvature.clone(),
            t,
        }
    }
    /// The same profile at amplitude `t`.
    pub fn with_t(mut self, t: f64) -> Self {
        self.t = t;
        self
    }
    /// `b(s)` at amplitude `t`.
    #[inline]
    pub fn b_at(&self, s: f64, t: f64) -> f64 {
        match &self.stiffness {
            Stiffness::Uniform => 1.0,
            Stiffness::Taper { ratio } => {
                let r = 1.0 - t * (1.0 - ratio) * s;
                let r2 = r * r;
                1.0 / (r2 * r2)
            }
            Stiffness::Table { s: st, b } => {
                let v = interp(st, b, s);
                if t == 1.0 {
                    v
                } else {
                    v.powf(t)
                }
            }
        }
    }
    /// `κ0(s)` at amplitude `t`.
    #[inline]
    pub fn k0_at(&self, s: f64, t: f64) -> f64 {
        match &self.precurvature {
            Precurvature::None => 0.0,
            Precurvature::Linear { k0, k1 } => t * (k0 + k1 * s),
            Precurvature::Table { s: st, k } => t * interp(st, k, s),
        }
    }
}

/// The slope of the piecewise-linear table at `s` (0 outside it).
fn table_slope(s_tab: &[f64], v: &[f64], s: f64) -> f64 {
    let n = s_tab.len();
    if s < s_tab[0] || s >= s_tab[n - 1] {
        return 0.0;
    }
    let i = s_tab.partition_point(|&t| t <= s).clamp(1, n - 1) - 1;
    (v[i + 1] - v[i]) / (s_tab[i + 1] - s_tab[i])
}

impl Profile for General {
    const UNIFORM: bool = false;
    fn slopes(&self, s: f64) -> (f64, f64) {
        let t = self.t;
        let db = match &self.stiffness {
            Stiffness::Uniform => 0.0,
            Stiffness::Taper { ratio } => {
                let r = 1.0 - t * (1.0 - ratio) * s;
                4.0 * t * (1.0 - ratio) / (r * r * r * r * r)
            }
            Stiffness::Table { s: st, b } => {
                let v = interp(st, b, s);
                t * v.powf(t - 1.0) * table_slope(st, b, s)
            }
        };
        let dk = match &self.precurvature {
            Precurvature::None => 0.0,
            Precurvature::Linear { k1, .. } => t * k1,
            Precurvature::Table { s: st, k } => t * table_slope(st, k, s),
        };
        (db, dk)
    }
    fn at_amplitude(&self, t: f64) -> Self {
        self.clone().with_t(t)
    }
    fn straight(&self) -> bool {
        self.t == 0.0
            || match &self.precurvature {
                Precurvature::None => true,
                Precurvature::Linear { k0, k1 } => *k0 == 0.0 && *k1 == 0.0,
                Precurvature::Table { k, .. } => k.iter().all(|v| *v == 0.0),
            }
    }
    #[inline]
    fn b(&self, s: f64) -> f64 {
        self.b_at(s, self.t)
    }
    #[inline]
    fn k0(&self, s: f64) -> f64 {
        self.k0_at(s, self.t)
    }
}

impl General {
    /// True when `b ≡ 1` and `κ0 ≡ 0` at `t = 1` (the one test of "uniform straight rod").
    pub fn is_uniform(&self) -> bool {
        is_uniform(&self.stiffness, &self.precurvature)
    }
}

/// True when the stiffness is uniform (`b ≡ 1`) and the rod straight (`κ0 ≡ 0`).
pub(crate) fn is_uniform(stiffness: &Stiffness, precurvature: &Precurvature) -> bool {
    let b1 = match stiffness {
        Stiffness::Uniform => true,
        Stiffness::Taper { ratio } => *ratio == 1.0,
        Stiffness::Table { .. } => false,
    };
    let k0 = match precurvature {
        Precurvature::None => true,
        Precurvature::Linear { k0, k1 } => *k0 == 0.0 && *k1 == 0.0,
        Precurvature::Table { .. } => false,
    };
    b1 && k0
}
