//! Comparison with the independent mpmath quadrature of the paper's integrals
//! (data/elastica/reference.csv, made by data/elastica/make_reference.py at 40 digits).

use elastica::{Branch, Elastica, ElasticaError};

const CSV: &str = include_str!("../../../data/elastica/reference.csv");

struct Row {
    branch: Branch,
    alpha: f64,
    phi1: f64,
    f: f64,
    x1: f64,
    y1: f64,
    m_base: f64,
    s_b: Option<f64>,
}

fn rows() -> Vec<Row> {
    CSV.lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let c: Vec<&str> = l.split(',').collect();
            let p = |i: usize| c[i].parse::<f64>().unwrap();
            Row {
                branch: if c[0] == "convex" {
                    Branch::Convex
                } else {
                    Branch::OneFlex
                },
                alpha: p(1),
                phi1: p(2),
                f: p(3),
                x1: p(4),
                y1: p(5),
                m_base: p(6),
                s_b: if c[7] == "nan" { None } else { Some(p(7)) },
            }
        })
        .collect()
}

/// Error measure: relative, except for quantities that vanish (x1 at the straight rod, m_base at
/// the turning point), where it is relative to the natural scale of the quantity (1 for lengths,
/// sqrt(f) for the moment, whose size is 2 sqrt(f) k cos(theta_top)).
fn err(got: f64, want: f64, scale: f64) -> f64 {
    (got - want).abs() / want.abs().max(scale)
}

#[test]
fn reference_csv_all_points() -> Result<(), ElasticaError> {
    let rows = rows();
    assert!(rows.len() >= 30);
    let mut worst = [0.0f64; 2];
    let mut worst_at = [(0.0, 0.0); 2];
    for r in &rows {
        let e = Elastica::new(r.branch, r.alpha, r.phi1)?;
        let g = r.f.sqrt();
        let errs = [
            err(e.f, r.f, 0.0),
            err(e.x1, r.x1, 1.0),
            err(e.y1, r.y1, 1.0),
            err(e.m_base, r.m_base, g * 1e-3),
            match (e.s_b, r.s_b) {
                (Some(a), Some(b)) => err(a, b, 1e-3),
                (None, None) => 0.0,
                _ => 1.0,
            },
        ];
        let emax = errs.iter().cloned().fold(0.0, f64::max);
        let bi = usize::from(r.branch == Branch::OneFlex);
        if emax > worst[bi] {
            worst[bi] = emax;
            worst_at[bi] = (r.alpha, r.phi1);
        }
        // Every point of the table is well conditioned for this implementation (the distances
        // to the domain ends are formed without cancellation), so one bound holds throughout.
        assert!(
            emax <= 1e-14,
            "{:?} alpha={} phi1={}: errors {:?}",
            r.branch,
            r.alpha,
            r.phi1,
            errs
        );
    }
    eprintln!(
        "max error vs mpmath: convex {:.2e} at {:?}, one flex {:.2e} at {:?}",
        worst[0], worst_at[0], worst[1], worst_at[1]
    );
    Ok(())
}
