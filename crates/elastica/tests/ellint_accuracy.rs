//! Accuracy of the `ellip` crate's Legendre integrals near m -> 1, and of this crate's
//! complementary-parameter forms, against mpmath (data/elastica/ellint_reference.csv, inputs
//! m = 1 - 2^-j exact in binary, 40-digit mpmath values).

use elastica::ellint::{
    e_mc, k_mc, legendre_e, legendre_e_inc, legendre_f, legendre_f_e_mc, legendre_k,
};

const CSV: &str = include_str!("../../../data/elastica/ellint_reference.csv");

fn rel(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

#[test]
fn ellip_near_m_one() {
    let mut worst_ellip = [0.0f64; 4];
    let mut worst_mc = [0.0f64; 4];
    for l in CSV.lines().skip(1) {
        let c: Vec<&str> = l.split(',').collect();
        let j: i32 = c[0].parse().unwrap();
        let p = |i: usize| c[i].parse::<f64>().unwrap();
        let (m, phi, kk, ee, fi, ei) = (p(1), p(2), p(3), p(4), p(5), p(6));
        let mc = 2f64.powi(-j);
        assert_eq!(1.0 - mc, m);
        let e = [
            rel(legendre_k(m).unwrap(), kk),
            rel(legendre_e(m).unwrap(), ee),
            rel(legendre_f(phi, m).unwrap(), fi),
            rel(legendre_e_inc(phi, m).unwrap(), ei),
        ];
        for (w, v) in worst_ellip.iter_mut().zip(e) {
            *w = w.max(v);
        }
        worst_mc[0] = worst_mc[0].max(rel(k_mc(mc).unwrap(), kk));
        worst_mc[1] = worst_mc[1].max(rel(e_mc(mc).unwrap(), ee));
        let (f2, e2) = legendre_f_e_mc(phi, mc).unwrap();
        worst_mc[2] = worst_mc[2].max(rel(f2, fi));
        worst_mc[3] = worst_mc[3].max(rel(e2, ei));
        if j <= 2 {
            // for m <= 3/4 (this crate uses m <= 1/2) ellip's incomplete integrals are fine
            assert!(e[2] < 5e-15 && e[3] < 5e-15, "j={j} phi={phi}: {e:?}");
        }
    }
    eprintln!(
        "ellip max rel err for m = 1 - 2^-j, j <= 52: K {:.2e}, E {:.2e}, F(phi|m) {:.2e}, E(phi|m) {:.2e}; \
         mended: k_mc {:.2e}, e_mc {:.2e}, F_mc {:.2e}, E_mc {:.2e}",
        worst_ellip[0],
        worst_ellip[1],
        worst_ellip[2],
        worst_ellip[3],
        worst_mc[0],
        worst_mc[1],
        worst_mc[2],
        worst_mc[3]
    );
    // Given the exact double m, ellip's complete K, E are accurate to a few ulp even at
    // m = 1 - 2^-52. Its incomplete F, E lose up to ~1e-9 relative near m = 1 and phi = pi/2
    // (1 - m sin^2 phi cancels); legendre_f_e_mc mends that. A further loss near m -> 1 is in
    // *forming* m: see `forming_m_loses_digits`.
    assert!(
        worst_ellip[0] < 5e-15 && worst_ellip[1] < 5e-15,
        "{worst_ellip:?}"
    );
    assert!(
        worst_ellip[2] < 1e-8 && worst_ellip[3] < 1e-8,
        "{worst_ellip:?}"
    );
    for w in worst_mc {
        assert!(w < 5e-15, "{worst_mc:?}");
    }
}

/// Where the digits really go: K(m) has condition number ~ 1/(2 (1-m) ln(16/(1-m))) in m. If
/// m is computed as 1 - mc with mc not a power of two, the rounding of m (1e-16 absolute) is a
/// relative error 1e-16/mc in mc and hence in K of about 1e-16/(mc * 2 K): the complementary form
/// avoids it.
#[test]
fn forming_m_loses_digits() {
    // mc = 1e-10 (not exactly representable as 1 - m)
    // mpmath: K(m = 1 - 1e-10) = 12.899219826387599535...
    let mc = 1e-10;
    let k_exact = 12.899_219_826_387_6;
    let via_m = legendre_k(1.0 - mc).unwrap();
    let via_mc = k_mc(mc).unwrap();
    let e_m = rel(via_m, k_exact);
    let e_mc = rel(via_mc, k_exact);
    eprintln!("K(1 - 1e-10): via m rel err {e_m:.2e}, via mc rel err {e_mc:.2e}");
    assert!(e_mc < 1e-15);
    assert!(e_m > 1e-10, "expected the loss to show: {e_m:e}");
}
