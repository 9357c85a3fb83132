//! The statistics of `fit` (issue 21): 100 seeded synthetic traces of the paper's scene
//! (uniform clamped rod, η = 0.75, μs = 0.5, μk = 0.3) with Gaussian noise on the slip places
//! (σ = 2e-4) and on `fx`, `m_base` before and `fx` after each slip (σ = 2e-3), fitted twice: with
//! the noise levels estimated from the residuals (the default) and with them given. For traces of
//! 4, 8, 16 and 32 slips: the share of trials whose estimate lies within 3 standard errors of the
//! truth, and (noise levels estimated) within Student's t interval of the same confidence
//! (99.73 %) with the fit's degrees of freedom; the root-mean-square error, the mean standard
//! error and the standard error the noise levels give (the errors should shrink like the latter),
//! and the estimated standard errors against that and against the rms error (their bias);
//! and that standard error from the signals alone and from the slip places alone (why it falls
//! faster than 1/√n: docs/model.md, "The drag").
//!
//! ```sh
//! cargo run --release -p vibrissa --example fit_stats [-- [corrugated] TRIALS [SLIPS...]]
//! ```
//!
//! `corrugated`: the same on a corrugated surface (A = 0.005, W = 0.1, the scene of issue 33).
//! A fit whose consistency check calls it a misfit has no standard error and counts as not
//! covered (`misfits` in the first table).
//!
//! `texture [TRIALS [SLIPS]]` (issue 31): the corrugation read back. The noise-free trace of
//! SLIPS slips (default 6) over A = 0.005, W = 0.1, P = 0.7 fitted with μs, μk, A, W, P free from
//! eight perturbed starts (A ±20 %, W ±5 %, P ±0.3, with unit weights given: the errors against
//! `√n · tol · std_error`, observations exact to the drags' tolerance); then TRIALS (default 10)
//! noisy traces (the noise below, the levels given; trial `i` draws from seed `31000 + i`) from
//! the start A = 0.0055, W = 0.097, P = 0.6: each parameter within 3 standard errors (and A and
//! W both, and all five), the rms error and the mean standard error, the trials not covered,
//! and the CPU time and the drags per fit.
//!
//! (default 100 trials of 4, 8, 16 and 32 slips; trial `i` of `n` slips draws from seed
//! `1000 n + i`)

use vibrissa::fit::{fit, inc_beta, CorrugationFit, FitOptions, FitResult, Trace};
use vibrissa::{drag, DragOptions, Scene};

#[path = "../benches/support/clock.rs"]
mod clock;
#[path = "../tests/support/noisy_trace.rs"]
mod noisy_trace;
use noisy_trace::{
    corrugated, exact, noisy, places_only, texture_trace, Rng, SIGMA, TEXTURE_TRUTH,
};

/// `P(|T| > t)` for Student's t with `dof` degrees of freedom.
fn t_tail(t: f64, dof: f64) -> f64 {
    inc_beta(dof / (dof + t * t), 0.5 * dof, 0.5)
}

/// One length's tallies: within 3 SE (μs, μk, both), within the t interval (both), Σ error²,
/// Σ SE, Σ SE², Σ dof (μs, μk each).
#[derive(Default)]
struct Tally {
    in3: [usize; 3],
    in_t: usize,
    e2: [f64; 2],
    se: [f64; 2],
    se2: [f64; 2],
    dof: [f64; 2],
    misfits: usize,
}

impl Tally {
    fn add(&mut self, f: &FitResult, truth: [f64; 2]) {
        let mut inside = [false; 2];
        let mut inside_t = [true; 2];
        for (i, name) in ["mu_s", "mu_k"].into_iter().enumerate() {
            let p = f.get(name).expect("fitted");
            // (a fit its consistency check calls a misfit has no standard error: not covered)
            let Some(se) = p.std_error else {
                self.misfits += usize::from(i == 0);
                inside_t[i] = false;
                continue;
            };
            let e = p.value - truth[i];
            inside[i] = e.abs() <= 3.0 * se;
            if let Some(dof) = p.dof {
                // within the interval of the normal 3-sigma confidence
                inside_t[i] = t_tail(e.abs() / se, dof) >= 2.699_796e-3;
                self.dof[i] += dof;
            }
            self.e2[i] += e * e;
            self.se[i] += se;
            self.se2[i] += se * se;
        }
        self.in3[0] += usize::from(inside[0]);
        self.in3[1] += usize::from(inside[1]);
        self.in3[2] += usize::from(inside[0] && inside[1]);
        self.in_t += usize::from(inside_t[0] && inside_t[1]);
    }
}

/// The friction pair the traces are drawn with.
const TRUTH: [f64; 2] = [0.5, 0.3];

fn main() {
    // (the tail function against known values: t_1 is Cauchy, P(|T_1| > 1) = 1/2; the normal
    // limit P(|Z| > 3) = 2.6998e-3)
    assert!((t_tail(1.0, 1.0) - 0.5).abs() < 1e-12);
    assert!((t_tail(3.0, 1e7) - 2.699_796e-3).abs() < 1e-8);
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().is_some_and(|a| a == "texture") {
        let num = |i: usize, default: usize| {
            args.get(i).map_or(default, |a| {
                a.parse()
                    .expect("usage: fit_stats texture [TRIALS [SLIPS]]")
            })
        };
        texture(num(1, 10), num(2, 6));
        return;
    }
    // `corrugated`: the scene's surface corrugated (A = 0.005, W = 0.1; issue 33)
    let corrugated = args.first().is_some_and(|a| a == "corrugated");
    if corrugated {
        args.remove(0);
    }
    let scene = if corrugated {
        Scene {
            surface: vibrissa::surface::SurfaceProfile::Sine {
                amplitude: 0.005,
                wavelength: 0.1,
                phase: 0.0,
            },
            ..Scene::default()
        }
    } else {
        Scene::default()
    };
    let (rod, surface) = scene.parts().expect("scene");
    let r = drag(
        &rod,
        &surface,
        &DragOptions {
            d_max: if corrugated { 1.0 } else { 0.5 },
            points: 2,
            mu_s: Some(TRUTH[0]),
            mu_k: Some(TRUTH[1]),
            max_slips: 32,
            ..DragOptions::default()
        },
    )
    .expect("drag");
    // (the corrugated drag ends at d = 0.44, a side touching down, after 15 slips)
    assert!(r.slips.len() >= if corrugated { 15 } else { 32 }, "{r}");
    let given = FitOptions {
        sigma: Some(SIGMA),
        ..FitOptions::default()
    };
    println!(
        "slips | trials | sigma estimated: within 3 SE mu_s, mu_k, both; within t(dof) both | \
         mean dof mu_s, mu_k | sigma given: within 3 SE both | rms error mu_s, mu_k | mean SE \
         mu_s, mu_k | SE with sigma given mu_s, mu_k"
    );
    let args: Vec<u64> = args
        .iter()
        .map(|a| {
            a.parse()
                .expect("usage: fit_stats [corrugated] [TRIALS [SLIPS...]]")
        })
        .collect();
    let trials = args.first().copied().unwrap_or(100);
    let lengths: Vec<usize> = if args.len() > 1 {
        args[1..].iter().map(|&n| n as usize).collect()
    } else {
        vec![4, 8, 16, 32]
    };
    assert!(lengths.iter().all(|&n| (1..=r.slips.len()).contains(&n)));
    let (rows, ratios) = trials_table(&scene, &r, (trials, lengths), &given);
    // the estimated standard errors against the spread they estimate: the standard error with
    // the noise levels given (the spread to first order) and the trials' rms error
    println!(
        "slips | mean SE / SE with sigma given mu_s, mu_k | rms SE / rms error mu_s, mu_k | mean \
         SE / rms error mu_s, mu_k (sigma estimated)"
    );
    for (n, q) in &ratios {
        println!(
            "{n} | {:.3}, {:.3} | {:.3}, {:.3} | {:.3}, {:.3}",
            q[0][0], q[1][0], q[0][1], q[1][1], q[0][2], q[1][2]
        );
    }
    information(&scene, &r, &rows, &given);
    for w in rows.windows(2) {
        let ((n0, r0, s0), (n1, r1, s1)) = (w[0], w[1]);
        println!(
            "{n0} -> {n1} slips: rms error ratio mu_s {:.2}, mu_k {:.2}; standard error ratio (sigma \
             given) mu_s {:.2}, mu_k {:.2}; 1/sqrt(n): {:.2}",
            r0[0] / r1[0],
            r0[1] / r1[1],
            s0[0] / s1[0],
            s0[1] / s1[1],
            ((n1 as f64) / (n0 as f64)).sqrt()
        );
    }
}

/// A trace length: its slips, the trials' rms errors of μs and μk, and their mean standard errors
/// with the noise levels given.
type Length = (usize, [f64; 2], [f64; 2]);

/// A trace length's slips and, for μs and μk, the mean estimated standard error over the one with
/// the noise levels given, the rms standard error over the rms error, and the mean standard error
/// over the rms error.
type SeRatios = (usize, [[f64; 3]; 2]);

/// Per trace length: a row of the trials' tallies printed (σ estimated and given), and the
/// length's rms errors with the standard errors given σ, and the ratios of the estimated standard
/// errors to the spread they estimate.
fn trials_table(
    scene: &Scene,
    r: &vibrissa::DragResult,
    (trials, lengths): (u64, Vec<usize>),
    given: &FitOptions,
) -> (Vec<Length>, Vec<SeRatios>) {
    let mut rows = Vec::new();
    let mut ratios = Vec::new();
    for n in lengths {
        let (mut est, mut giv) = (Tally::default(), Tally::default());
        for seed in 0..trials {
            let mut rng = Rng(1000 * n as u64 + seed);
            let t = noisy(r, n, &mut rng);
            est.add(&fit(scene, &t, &FitOptions::default()).expect("fit"), TRUTH);
            giv.add(&fit(scene, &t, given).expect("fit"), TRUTH);
        }
        let k = trials as f64;
        let rms = est.e2.map(|e| (e / k).sqrt());
        let se = est.se.map(|s| s / k);
        let se_given = giv.se.map(|s| s / k);
        println!(
            "{n} | {trials} | {}, {}, {}; {} | {:.1}, {:.1} | {} | {:.3e}, {:.3e} | {:.3e}, {:.3e} \
             | {:.3e}, {:.3e} | misfits {}, {}",
            est.in3[0],
            est.in3[1],
            est.in3[2],
            est.in_t,
            est.dof[0] / k,
            est.dof[1] / k,
            giv.in3[2],
            rms[0],
            rms[1],
            se[0],
            se[1],
            se_given[0],
            se_given[1],
            est.misfits,
            giv.misfits
        );
        rows.push((n, rms, se_given));
        let rms_se = est.se2.map(|s| (s / k).sqrt());
        ratios.push((
            n,
            [0, 1].map(|i| [se[i] / se_given[i], rms_se[i] / rms[i], se[i] / rms[i]]),
        ));
    }
    (rows, ratios)
}

/// Where the information comes from: the standard errors of the noiseless trace of each length
/// of `rows` with the noise levels given, from every observation, from the signals alone (the
/// places weighted out by σ_d = 1e3) and from the places alone, and their ratios between lengths.
fn information(scene: &Scene, r: &vibrissa::DragResult, rows: &[Length], given: &FitOptions) {
    println!(
        "slips | SE mu_s, mu_k from all observations | signals only | places only (noiseless \
         trace, noise levels given)"
    );
    let mut info = Vec::new();
    for &(n, _, _) in rows {
        let all = exact(r, n);
        let places = places_only(&all);
        let no_places = FitOptions {
            sigma: Some([1e3, SIGMA[1], SIGMA[2], SIGMA[3]]),
            ..FitOptions::default()
        };
        let se = |t: &Trace, o: &FitOptions| -> [f64; 2] {
            let f = fit(scene, t, o).expect("fit");
            ["mu_s", "mu_k"].map(|p| f.get(p).and_then(|q| q.std_error).unwrap_or(f64::NAN))
        };
        let (a, b, c) = (se(&all, given), se(&all, &no_places), se(&places, given));
        println!(
            "{n} | {:.3e}, {:.3e} | {:.3e}, {:.3e} | {:.3e}, {:.3e}",
            a[0], a[1], b[0], b[1], c[0], c[1]
        );
        info.push((n, b, c));
    }
    for w in info.windows(2) {
        let ((n0, b0, c0), (n1, b1, c1)) = (w[0], w[1]);
        println!(
            "{n0} -> {n1} slips: standard error ratio, signals only: mu_s {:.3}, mu_k {:.3}; \
             places only: mu_s {:.3}, mu_k {:.3}",
            b0[0] / b1[0],
            b0[1] / b1[1],
            c0[0] / c1[0],
            c0[1] / c1[1]
        );
    }
}

/// The corrugation read back (module docs, `texture`).
fn texture(trials: usize, slips: usize) {
    let r = texture_trace(slips);
    from_perturbed_starts(&r, slips);
    let fits = noisy_trials(&r, trials, slips);
    report_trials(&fits, trials, slips);
}

/// The noise-free trace of `r` fitted from eight perturbed starts, a row each.
fn from_perturbed_starts(r: &vibrissa::DragResult, slips: usize) {
    let tol = vibrissa::SolverConfig::DEFAULT_TOL;
    println!(
        "noise-free trace of {slips} slips, unit weights: start A, W, P | error / (sqrt(n) tol SE) \
         mu_s, mu_k, A, W, P | largest error | drags | seconds ({})",
        clock::name()
    );
    let exact_trace = full(r);
    let opts = FitOptions {
        corrugation: CorrugationFit::ALL,
        sigma: Some([1.0; 4]),
        ..FitOptions::default()
    };
    for (a0, w0, p0) in [
        (0.004, 0.095, 0.4),
        (0.006, 0.095, 0.4),
        (0.004, 0.105, 0.4),
        (0.006, 0.105, 0.4),
        (0.004, 0.095, 1.0),
        (0.006, 0.095, 1.0),
        (0.004, 0.105, 1.0),
        (0.006, 0.105, 1.0),
    ] {
        let (f, secs) = clock::timed(|| fit(&corrugated(a0, w0, p0), &exact_trace, &opts));
        let secs = secs.as_secs_f64();
        match f {
            Ok(f) => {
                let n = (f.observations as f64).sqrt();
                let mut worst = 0.0f64;
                let ratios: Vec<String> = TEXTURE_TRUTH
                    .iter()
                    .map(|&(name, want)| {
                        let p = f.get(name).expect("fitted");
                        let e = (p.value - want).abs();
                        worst = worst.max(e);
                        let se = p.std_error.unwrap_or(f64::NAN);
                        format!("{:.2e}", e / (n * tol * se))
                    })
                    .collect();
                println!(
                    "{a0}, {w0}, {p0} | {} | {worst:.2e} | {} | {secs:.1}{}",
                    ratios.join(", "),
                    f.drags,
                    f.message.map_or(String::new(), |m| format!(" | {m}"))
                );
            }
            Err(e) => println!("{a0}, {w0}, {p0} | error: {e} | {secs:.1}"),
        }
    }
}

/// `trials` noisy traces of the first `slips` slips of `r` (trial `i` from seed `31000 + i`),
/// each fitted with the noise levels given from the start A = 0.0055, W = 0.097, P = 0.6, on
/// every core: the fits and their times, in the order of the trials.
fn noisy_trials(r: &vibrissa::DragResult, trials: usize, slips: usize) -> Vec<(FitResult, f64)> {
    let given = FitOptions {
        corrugation: CorrugationFit::ALL,
        sigma: Some(SIGMA),
        ..FitOptions::default()
    };
    // (each fit is independent; trial `seed` draws from its own seed)
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    std::thread::scope(|sc| {
        let jobs: Vec<_> = (0..threads)
            .map(|k| {
                let given = &given;
                sc.spawn(move || {
                    (k..trials)
                        .step_by(threads)
                        .map(|seed| {
                            let t = noisy(r, slips, &mut Rng(31_000 + seed as u64));
                            let (f, secs) =
                                clock::timed(|| fit(&corrugated(0.0055, 0.097, 0.6), &t, given));
                            (seed, (f.expect("fit"), secs.as_secs_f64()))
                        })
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        let mut all: Vec<(usize, (FitResult, f64))> = jobs
            .into_iter()
            .flat_map(|j| j.join().expect("a trial"))
            .collect();
        all.sort_by_key(|(seed, _)| *seed);
        all.into_iter().map(|(_, f)| f).collect()
    })
}

/// The table of the noisy trials' fits: each parameter within 3 standard errors, A and W both,
/// all five, the rms errors, the mean standard errors, the misfits, the times and the drags;
/// before it the trials not covered and the three slowest.
fn report_trials(fits: &[(FitResult, f64)], trials: usize, slips: usize) {
    println!(
        "{trials} noisy traces of {slips} slips, levels given: within 3 SE (mu_s, mu_k, A, W, P) \
         | A and W both | all five | rms error | mean SE (mu_s, mu_k, A, W, P) | misfits | {} per \
         fit: mean, median, largest | drags per fit: mean, largest",
        clock::name()
    );
    let (mut inside, mut e2, mut se) = ([0usize; 5], [0.0f64; 5], [0.0f64; 5]);
    let (mut both, mut five, mut misfits) = (0, 0, 0);
    for (seed, (f, secs)) in fits.iter().enumerate() {
        let mut covered = [false; 5];
        for (i, &(name, want)) in TEXTURE_TRUTH.iter().enumerate() {
            let p = f.get(name).expect("fitted");
            let e = p.value - want;
            e2[i] += e * e;
            match p.std_error {
                Some(s) => {
                    se[i] += s;
                    covered[i] = e.abs() <= 3.0 * s;
                    inside[i] += usize::from(covered[i]);
                }
                None => misfits += usize::from(i == 0),
            }
        }
        both += usize::from(covered[2] && covered[3]);
        five += usize::from(covered.iter().all(|&c| c));
        if !covered.iter().all(|&c| c) {
            println!(
                "  not covered: seed {seed} ({secs:.1} s, {} drags): {f}",
                f.drags
            );
        }
    }
    let k = trials as f64;
    let list = |v: [f64; 5]| {
        v.iter()
            .map(|x| format!("{x:.3e}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let mut slowest: Vec<(usize, f64, usize)> = (fits.iter().enumerate())
        .map(|(seed, (f, s))| (seed, *s, f.drags))
        .collect();
    slowest.sort_by(|a, b| b.1.total_cmp(&a.1));
    for (seed, s, drags) in slowest.iter().take(3) {
        println!("  slow: seed {seed}: {s:.1} s, {drags} drags");
    }
    let mut secs: Vec<f64> = fits.iter().map(|(_, s)| *s).collect();
    secs.sort_by(f64::total_cmp);
    let drags: Vec<usize> = fits.iter().map(|(f, _)| f.drags).collect();
    println!(
        "{inside:?} of {trials} | {both} | {five} | {} | {} | {misfits} | {:.1}, {:.1}, {:.1} s \
         | {:.0}, {}",
        list(e2.map(|e| (e / k).sqrt())),
        list(se.map(|s| s / k)),
        secs.iter().sum::<f64>() / k,
        secs[secs.len() / 2],
        secs[secs.len() - 1],
        drags.iter().sum::<usize>() as f64 / k,
        drags.iter().max().copied().unwrap_or(0)
    );
}

/// Every signal before and after each slip of `r`, without noise.
fn full(r: &vibrissa::DragResult) -> Trace {
    let sig = |s: &vibrissa::drag::Signals| [Some(s.fx), Some(s.fy), Some(s.m_base)];
    Trace {
        slips: r
            .slips
            .iter()
            .map(|e| vibrissa::fit::TraceSlip {
                d: e.d,
                before: sig(&e.before),
                after: sig(&e.after),
            })
            .collect(),
        tips: Vec::new(),
        motion: Default::default(),
    }
}
