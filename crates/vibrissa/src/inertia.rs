//! The rod's inertia, consistent with its stiffness: the mass per length `μ(s) = ρA(s)/ρA(0)` and
//! the rotary inertia `j(s) = ρI(s)/(ρA(0) L²)`, for a solid circular cross-section of one
//! material (`I ∝ r⁴`, `A ∝ r²`, so `μ = b^(−1/2)` and `j = g0²/b` with `b = I(0)/I(s)` and
//! `g0 = r(0)/(2L)` the radius of gyration of the foot's section over the length).
//!
//! A conical taper of ratio ρ: `μ(s) = (1 − (1 − ρ)s)²`; a table of `b`: `μ = b^(−1/2)`; the
//! uniform rod: `μ ≡ 1`. Time is normalized at the foot, `t̂ = t·sqrt(EI(0)/(ρA(0) L⁴))`, so
//! the uniform clamped rod's frequencies are `ω_n = β_n²` in these units.

use crate::parts::{Physical, Stiffness};

/// Mass per unit length relative to the foot's, `μ(s) = ρA(s)/ρA(0)`.
pub fn mass_density(stiffness: &Stiffness, s: f64) -> f64 {
    match stiffness {
        Stiffness::Uniform => 1.0,
        Stiffness::Taper { ratio } => {
            let r = 1.0 - (1.0 - ratio) * s;
            r * r
        }
        Stiffness::Table { .. } => {
            let b = crate::profile::General::new(stiffness, &crate::parts::Precurvature::None, 1.0)
                .b_at(s, 1.0);
            1.0 / b.sqrt()
        }
    }
}

/// Density of keratin, kg/m³: whisker shafts are keratin with a density of about 1.2–1.3 g/cm³;
/// this is the value the rat presets use when their scene gives none.
pub const KERATIN_DENSITY: f64 = 1250.0;

/// The time unit `sqrt(ρA(0) L⁴ / EI(0))` in seconds of a rod with physical dimensions and the
/// density `rho` (kg/m³): one normalized time unit lasts this long (`I = π d⁴/64`,
/// `A = π d²/4`, so `ρA L⁴/EI = 16 ρ L⁴/(E d²)`).
pub fn time_unit_s(p: &Physical, rho: f64) -> f64 {
    let l = p.length_mm * 1e-3;
    let d = p.base_diameter_um * 1e-6;
    let e = p.youngs_modulus_gpa * 1e9;
    (16.0 * rho * l.powi(4) / (e * d * d)).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A table of the taper's own `b` gives the taper's mass density (the two conventions agree).
    #[test]
    fn table_agrees_with_taper() {
        let rho: f64 = 0.3;
        let s: Vec<f64> = (0..=200).map(|i| i as f64 / 200.0).collect();
        let b: Vec<f64> = s.iter().map(|s| (1.0 - (1.0 - rho) * s).powi(-4)).collect();
        let table = Stiffness::Table { s: s.clone(), b };
        for &si in &s {
            let (a, t) = (
                mass_density(&Stiffness::Taper { ratio: rho }, si),
                mass_density(&table, si),
            );
            assert!((a - t).abs() < 1e-12, "{si}: {a} {t}");
        }
    }

    /// The long rat preset (45 mm, 180 µm, 3.3 GPa, 1250 kg/m³): the time unit by hand.
    #[test]
    fn time_unit_of_a_rat_whisker() {
        let p = Physical {
            length_mm: 45.0,
            youngs_modulus_gpa: 3.3,
            base_diameter_um: 180.0,
        };
        let hand = (16.0 * 1250.0 * 0.045f64.powi(4) / (3.3e9 * 180e-6 * 180e-6)).sqrt();
        assert!((time_unit_s(&p, 1250.0) / hand - 1.0).abs() < 1e-15);
        // ω1 = 3.516 in these units is the first frequency of the clamped uniform rod
        assert!(hand > 1e-3 && hand < 1e-1);
    }
}
