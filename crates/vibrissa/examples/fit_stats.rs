//! The statistics of `fit` (issue 21): 100 seeded synthetic traces of the paper's scene
//! (uniform clamped rod, η = 0.75, μs = 0.5, μk = 0.3) with Gaussian noise on the slip places
//! (σ = 2e-4) and on `fx`, `m_base` before and `fx` after each slip (σ = 2e-3); the share of
//! trials whose estimate lies within 3 standard errors of the truth, and the root-mean-square
//! error for traces of 4, 8 and 16 slips (errors should shrink like 1/√n).
//!
//! ```sh
//! cargo run --release -p vibrissa --example fit_stats
//! ```

use vibrissa::fit::{fit, FitOptions};
use vibrissa::{drag, DragOptions, Scene};

#[path = "../tests/support/noisy_trace.rs"]
mod noisy_trace;
use noisy_trace::{noisy, Rng};

fn main() {
    let scene = Scene::default();
    let (rod, surface) = scene.parts().expect("scene");
    let truth = (0.5, 0.3);
    let r = drag(
        &rod,
        &surface,
        &DragOptions {
            d_max: 0.25,
            points: 2,
            mu_s: Some(truth.0),
            mu_k: Some(truth.1),
            ..DragOptions::default()
        },
    )
    .expect("drag");
    assert!(r.slips.len() >= 16, "{r}");
    println!("slips | trials | within 3 SE: mu_s, mu_k, both | rms error mu_s, mu_k | mean SE mu_s, mu_k");
    let mut rms = Vec::new();
    for n in [4, 8, 16] {
        let trials = 100;
        let (mut in_s, mut in_k, mut both) = (0, 0, 0);
        let (mut e2s, mut e2k, mut ses, mut sek) = (0.0, 0.0, 0.0, 0.0);
        for seed in 0..trials {
            let mut rng = Rng(1000 * n as u64 + seed);
            let t = noisy(&r, n, &mut rng);
            let f = fit(&scene, &t, &FitOptions::default()).expect("fit");
            let (ps, pk) = (f.get("mu_s").unwrap(), f.get("mu_k").unwrap());
            let (ss, sk) = (ps.std_error.unwrap(), pk.std_error.unwrap());
            let (es, ek) = (ps.value - truth.0, pk.value - truth.1);
            let (a, b) = (es.abs() <= 3.0 * ss, ek.abs() <= 3.0 * sk);
            in_s += usize::from(a);
            in_k += usize::from(b);
            both += usize::from(a && b);
            e2s += es * es;
            e2k += ek * ek;
            ses += ss;
            sek += sk;
        }
        let k = trials as f64;
        let (rs, rk) = ((e2s / k).sqrt(), (e2k / k).sqrt());
        println!(
            "{n} | {trials} | {in_s}, {in_k}, {both} | {rs:.3e}, {rk:.3e} | {:.3e}, {:.3e}",
            ses / k,
            sek / k
        );
        rms.push((n, rs, rk));
    }
    for w in rms.windows(2) {
        println!(
            "{} -> {} slips: rms error ratio mu_s {:.2}, mu_k {:.2} (1/sqrt(n): {:.2})",
            w[0].0,
            w[1].0,
            w[0].1 / w[1].1,
            w[0].2 / w[1].2,
            ((w[1].0 as f64) / (w[0].0 as f64)).sqrt()
        );
    }
}
