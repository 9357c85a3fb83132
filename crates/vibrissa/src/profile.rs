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
    /// `(b, κ0)` at each of `places`, into `out` (replaced): the bits of [`Profile::b`] and
    /// [`Profile::k0`] there.
    fn table(&self, places: &[f64], out: &mut Vec<[f64; 2]>) {
        out.clear();
        out.extend(places.iter().map(|&s| [self.b(s), self.k0(s)]));
    }
    /// [`Profile::slopes`] at each of `places`, into `out` (replaced).
    fn slope_table(&self, places: &[f64], out: &mut Vec<[f64; 2]>) {
        out.clear();
        out.extend(places.iter().map(|&s| {
            let (db, dk) = self.slopes(s);
            [db, dk]
        }));
    }
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
    // The shots re-tabulate a segment whose end moves at every iterate, so the common kinds
    // (taper, linear rest curvature) get loops of one expression each; the same expressions as
    // `b_at`, `k0_at` and `slopes`, so the same bits.
    fn table(&self, places: &[f64], out: &mut Vec<[f64; 2]>) {
        let t = self.t;
        out.clear();
        out.resize(places.len(), [0.0; 2]);
        match &self.stiffness {
            Stiffness::Taper { ratio } => {
                for (o, &s) in out.iter_mut().zip(places) {
                    let r = 1.0 - t * (1.0 - ratio) * s;
                    let r2 = r * r;
                    o[0] = 1.0 / (r2 * r2);
                }
            }
            _ => {
                for (o, &s) in out.iter_mut().zip(places) {
                    o[0] = self.b_at(s, t);
                }
            }
        }
        match &self.precurvature {
            Precurvature::None => {}
            Precurvature::Linear { k0, k1 } => {
                for (o, &s) in out.iter_mut().zip(places) {
                    o[1] = t * (k0 + k1 * s);
                }
            }
            Precurvature::Table { .. } => {
                for (o, &s) in out.iter_mut().zip(places) {
                    o[1] = self.k0_at(s, t);
                }
            }
        }
    }
    fn slope_table(&self, places: &[f64], out: &mut Vec<[f64; 2]>) {
        let t = self.t;
        out.clear();
        out.resize(places.len(), [0.0; 2]);
        match &self.stiffness {
            Stiffness::Uniform => {}
            Stiffness::Taper { ratio } => {
                for (o, &s) in out.iter_mut().zip(places) {
                    let r = 1.0 - t * (1.0 - ratio) * s;
                    o[0] = 4.0 * t * (1.0 - ratio) / (r * r * r * r * r);
                }
            }
            Stiffness::Table { .. } => {
                for (o, &s) in out.iter_mut().zip(places) {
                    o[0] = self.slopes(s).0;
                }
            }
        }
        match &self.precurvature {
            Precurvature::None => {}
            Precurvature::Linear { k1, .. } => {
                let dk = t * k1;
                for o in out.iter_mut() {
                    o[1] = dk;
                }
            }
            Precurvature::Table { .. } => {
                for (o, &s) in out.iter_mut().zip(places) {
                    o[1] = self.slopes(s).1;
                }
            }
        }
    }
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

#[cfg(test)]
mod tests {
    use super::{General, Profile};
    use crate::parts::{Precurvature, Stiffness};

    /// The shots read `b`, `κ0` and their slopes from the tables, the rows and shapes from the
    /// profile itself: the tables must hold the very bits of `b`, `k0` and `slopes` at their
    /// places, for every kind of profile and homotopy amplitude (a kind whose loop wrote another
    /// expression, `b·(1/r)` for the taper's slope say, would fail here).
    #[test]
    fn tables_hold_the_bits_of_the_profile() {
        let stiff = [
            Stiffness::Uniform,
            Stiffness::Taper { ratio: 0.1 },
            Stiffness::Table {
                s: vec![0.0, 0.3, 1.0],
                b: vec![1.0, 3.0, 40.0],
            },
        ];
        let curv = [
            Precurvature::None,
            Precurvature::Linear { k0: -0.72, k1: 0.3 },
            Precurvature::Table {
                s: vec![0.0, 0.6, 1.0],
                k: vec![0.5, -0.2, 0.1],
            },
        ];
        // places as a shot lays them: inside, on the tables' nodes, at and just past the ends
        let places: Vec<f64> = (0..=400)
            .map(|i| i as f64 / 400.0 * 1.05 - 0.01)
            .chain([0.3, 0.6, 1.0, 0.0])
            .collect();
        for st in &stiff {
            for cv in &curv {
                for t in [1.0, 0.37, 0.0] {
                    let p = General::new(st, cv, t);
                    let (mut tab, mut slo) = (vec![[9.0; 2]; 3], vec![[9.0; 2]; 7]);
                    p.table(&places, &mut tab);
                    p.slope_table(&places, &mut slo);
                    assert_eq!((tab.len(), slo.len()), (places.len(), places.len()));
                    for (i, &s) in places.iter().enumerate() {
                        let (db, dk) = p.slopes(s);
                        let want = [p.b(s), p.k0(s), db, dk].map(f64::to_bits);
                        let got = [tab[i][0], tab[i][1], slo[i][0], slo[i][1]].map(f64::to_bits);
                        assert_eq!(got, want, "{st:?} {cv:?} t = {t} at s = {s}");
                    }
                }
            }
        }
    }
}
