//! A sum of sines (issue 31): `s(x) = Σ A_i sin(k_i x + φ_i)`, `k_i = 2π/λ_i`, on the trend
//! `t = tan β`.
//!
//! The steepest slope: `|h'| ≤ |t| + Σ |A_i| k_i`, and for wavelengths without a common period
//! the slope comes arbitrarily close to it somewhere along the surface (the phases `k_i x + φ_i`
//! fill the torus); the bound must stay below the profiles' limit. A sum with a common period
//! may be refused although its true steepest slope is lower.
//!
//! Arc length `σ(x) = ∫₀ˣ √(1 + h'²) dx` by 10-point Gauss–Legendre on panels of a 64th of the
//! shortest wavelength (as one sine's), exact to rounding (the integrand is analytic in every
//! panel). A sum has no period in general, so the cumulative values at every eighth panel are
//! tabulated lazily as far out as the contacts go, up to `|x| ≤` [`REACH`] (beyond, σ continues
//! along the tangent of its last value: no drag goes that far, only a solver's stray iterate).

use crate::limits;
use crate::VibrissaError;
use serde::Serialize;
use std::sync::Mutex;

/// How far from `x = 0` the arc length is tabulated (rod lengths): a drag's foot moves at most
/// 1000 rod lengths.
pub(crate) const REACH: f64 = 2048.0;

/// Panels per shortest wavelength.
const PANELS: f64 = 64.0;
/// Panels per tabulated value.
const CHUNK: usize = 8;

/// The lazily grown table of `σ` at every `CHUNK` panels: `[σ(i w) for i ≥ 0]` and
/// `[σ(−i w) for i ≥ 0]`, `w = CHUNK` panel widths.
#[derive(Debug, Default)]
struct Table(Mutex<(Vec<f64>, Vec<f64>)>);

impl Table {
    fn lock(&self) -> std::sync::MutexGuard<'_, (Vec<f64>, Vec<f64>)> {
        // a panic elsewhere while holding the lock leaves the table as it was: usable
        self.0.lock().unwrap_or_else(|p| p.into_inner())
    }
}

impl Clone for Table {
    fn clone(&self) -> Self {
        Table(Mutex::new(self.lock().clone()))
    }
}

impl PartialEq for Table {
    /// A cache: equal sums are equal whatever each has tabulated.
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

/// A resolved sum of sines (see the module docs).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub(crate) struct Sines {
    a: Vec<f64>,
    k: Vec<f64>,
    phase: Vec<f64>,
    trend: f64,
    /// Panel width.
    panel: f64,
    #[serde(skip)]
    table: Table,
}

impl Sines {
    /// The sum of `amplitude[i]·sin(2π x / wavelength[i] + phase[i])` (`phase` empty: all 0) on
    /// the trend `tan β = trend`, validated (its steepest slope below `max_slope`); errors name
    /// the scene key.
    pub fn new(
        amplitude: &[f64],
        wavelength: &[f64],
        phase: &[f64],
        trend: f64,
        max_slope: f64,
    ) -> Result<Sines, VibrissaError> {
        let n = amplitude.len();
        if n != wavelength.len() || !(phase.is_empty() || phase.len() == n) {
            return Err(VibrissaError::InvalidTable {
                name: "surface".into(),
                reason: format!(
                    "a sum of sines needs as many wavelengths as amplitudes, and as many phases \
                     or none (they have {n}, {} and {})",
                    wavelength.len(),
                    phase.len()
                ),
            });
        }
        limits::SINES_TERMS.check_count("surface.amplitude (terms of the sum)", n)?;
        let mut steepest = trend.abs();
        let mut k = Vec::with_capacity(n);
        for i in 0..n {
            limits::CORRUGATION_AMPLITUDE
                .check(&format!("surface.amplitude[{i}]"), amplitude[i])?;
            limits::CORRUGATION_WAVELENGTH
                .check(&format!("surface.wavelength[{i}]"), wavelength[i])?;
            if let Some(&p) = phase.get(i) {
                limits::CORRUGATION_PHASE.check(&format!("surface.phase[{i}]"), p)?;
            }
            k.push(std::f64::consts::TAU / wavelength[i]);
            steepest += amplitude[i].abs() * k[i];
        }
        if steepest.is_nan() || steepest >= max_slope {
            return Err(VibrissaError::InvalidTable {
                name: "surface".into(),
                reason: format!(
                    "the sum of sines' steepest slope |tan(surface_angle)| + sum of 2 pi \
                     |amplitude| / wavelength = {steepest:.6} must stay below {max_slope} \
                     ({:.0} degrees); lower the amplitudes",
                    max_slope.atan().to_degrees()
                ),
            });
        }
        let shortest = wavelength.iter().copied().fold(f64::INFINITY, f64::min);
        Ok(Sines {
            a: amplitude.to_vec(),
            k,
            phase: if phase.is_empty() {
                vec![0.0; n]
            } else {
                phase.to_vec()
            },
            trend,
            panel: shortest / PANELS,
            table: Table::default(),
        })
    }

    /// `(s, s', s'')` of the shape at `x`.
    pub fn jet(&self, x: f64) -> (f64, f64, f64) {
        let mut j = (0.0, 0.0, 0.0);
        for i in 0..self.a.len() {
            let (a, k) = (self.a[i], self.k[i]);
            let (s, c) = (k * x + self.phase[i]).sin_cos();
            j.0 += a * s;
            j.1 += a * k * c;
            j.2 -= a * k * k * s;
        }
        j
    }

    fn speed(&self, x: f64) -> f64 {
        let d = self.trend + self.jet(x).1;
        (1.0 + d * d).sqrt()
    }

    /// `∫ speed` over panels from `a` to `b` (`|b − a|` at most a few panels).
    fn panels(&self, a: f64, b: f64) -> f64 {
        let n = ((b - a).abs() / self.panel).ceil().max(1.0) as usize;
        (0..n)
            .map(|j| {
                let lo = a + (b - a) * j as f64 / n as f64;
                let hi = a + (b - a) * (j + 1) as f64 / n as f64;
                crate::gauss::gauss10(lo, hi, |x| self.speed(x))
            })
            .sum()
    }

    /// The arc length `σ(x)` from `x = 0` (signed).
    pub fn arc(&self, x: f64) -> f64 {
        if x.abs() > REACH {
            let e = REACH.copysign(x);
            return self.arc(e) + (x - e) * self.speed(e);
        }
        let w = self.panel * CHUNK as f64;
        let i = (x / w).floor();
        let base = {
            let t = self.lock_grow(i);
            if i >= 0.0 {
                t.0[i as usize]
            } else {
                t.1[(-i) as usize]
            }
        };
        base + self.panels(i * w, x)
    }

    /// The table, grown to hold `σ(i w)`.
    fn lock_grow(&self, i: f64) -> std::sync::MutexGuard<'_, (Vec<f64>, Vec<f64>)> {
        let w = self.panel * CHUNK as f64;
        let mut t = self.table.lock();
        if t.0.is_empty() {
            t.0.push(0.0);
            t.1.push(0.0);
        }
        if i >= 0.0 {
            let want = i as usize;
            while t.0.len() <= want {
                let j = t.0.len() as f64;
                let next = t.0[t.0.len() - 1] + self.panels((j - 1.0) * w, j * w);
                t.0.push(next);
            }
        } else {
            let want = (-i) as usize;
            while t.1.len() <= want {
                let j = t.1.len() as f64;
                let next = t.1[t.1.len() - 1] - self.panels(-j * w, -(j - 1.0) * w);
                t.1.push(next);
            }
        }
        t
    }
}
