//! The drag's cost (issue 21: a 10-cycle drag at most 10× one uniform 201-point scan, same run):
//! the paper's uniform rod at η = 0.75 with μs = 0.5, μk = 0.3, on the flat surface (10 slips,
//! `d_max` half a cycle past the tenth, 201 output points) and on a corrugation (amplitude 0.01,
//! wavelength 0.5, phase 2: stopped after its tenth slip), against `scan` with its defaults
//! (d ∈ [0, 0.5], 201 points). Issue 31 asks the same of a drag over a corrugation whose slips
//! are those of a SIDE contact sliding on the surface: the paper's rod at η = 0.46 over amplitude
//! 0.001, wavelength 1 (a side touches down near s = 0.94 and drives every slip; stopped after its
//! tenth slip). The last case is a texture drag of the kind the texture grid's longest drags
//! are made of (docs/robustness.md): the short rat preset at η 0.75 over amplitude 0.001,
//! wavelength 0.05, phase 0 to d 0.0162 (61 slips, most of them the tip's 3e-10 slips beside a
//! side that holds).
//!
//! The table printed first is measured in one interleaved run (round-robin, minimum of 40
//! repetitions) so that the ratios see the same machine load; criterion then times each.
//!
//! ```sh
//! cargo bench -p vibrissa --bench drag
//! ```

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use std::time::{Duration, Instant};
use vibrissa::surface::SurfaceProfile;
use vibrissa::{drag, scan, DragOptions, Rod, ScanOptions, Scene, StopReason, Surface};

enum Job {
    Scan(ScanOptions),
    Drag(DragOptions),
}

struct Case {
    name: &'static str,
    rod: Rod,
    surface: Surface,
    job: Job,
}

impl Case {
    /// Runs it; the number of slips.
    fn run(&self) -> usize {
        match &self.job {
            Job::Scan(o) => {
                black_box(scan(&self.rod, &self.surface, o).expect("scan"));
                0
            }
            Job::Drag(o) => black_box(drag(&self.rod, &self.surface, o).expect("drag"))
                .slips
                .len(),
        }
    }
}

/// The scan's slip displacement at `mu0` on the default scene.
fn slip_at(rod: &Rod, surface: &Surface, mu0: f64) -> f64 {
    let o = ScanOptions {
        mu0: Some(mu0),
        ..ScanOptions::default()
    };
    match scan(rod, surface, &o).expect("scan").stop {
        StopReason::Slip { d, .. } => d,
        s => panic!("no slip: {s}"),
    }
}

fn cases() -> Vec<Case> {
    let (rod, flat) = Scene::default().parts().expect("scene");
    let (ds, dk) = (slip_at(&rod, &flat, 0.5), slip_at(&rod, &flat, 0.3));
    let cycles = DragOptions {
        points: 201,
        mu_s: Some(0.5),
        mu_k: Some(0.3),
        ..DragOptions::default()
    };
    let sine = Scene {
        surface: SurfaceProfile::Sine {
            amplitude: 0.01,
            wavelength: 0.5,
            phase: 2.0,
        },
        ..Scene::default()
    };
    let corrugated = sine.surface().expect("corrugation");
    let low = Scene {
        eta: 0.46,
        surface: SurfaceProfile::Sine {
            amplitude: 0.001,
            wavelength: 1.0,
            phase: 0.0,
        },
        ..Scene::default()
    };
    let (low_rod, low_sine) = low.parts().expect("low corrugation");
    let path = format!(
        "{}/../../data/scenes/rat_mystacial_short.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let mut rat: Scene =
        toml::from_str(&std::fs::read_to_string(path).expect("preset")).expect("preset parses");
    rat.eta = 0.75;
    rat.surface = SurfaceProfile::Sine {
        amplitude: 0.001,
        wavelength: 0.05,
        phase: 0.0,
    };
    let (rat_rod, rat_sine) = rat.parts().expect("rat preset over a texture");
    vec![
        Case {
            name: "scan, 201 points",
            rod: rod.clone(),
            surface: flat.clone(),
            job: Job::Scan(ScanOptions::default()),
        },
        Case {
            name: "drag, flat, 10 cycles",
            rod: rod.clone(),
            surface: flat,
            job: Job::Drag(DragOptions {
                d_max: ds + 9.5 * (ds - dk),
                ..cycles.clone()
            }),
        },
        Case {
            name: "drag, corrugated, 10 cycles",
            rod,
            surface: corrugated,
            job: Job::Drag(DragOptions {
                d_max: 1.0,
                max_slips: 10,
                ..cycles.clone()
            }),
        },
        Case {
            name: "drag, sliding side, 10 cycles",
            rod: low_rod,
            surface: low_sine,
            job: Job::Drag(DragOptions {
                d_max: 0.3,
                max_slips: 10,
                ..cycles.clone()
            }),
        },
        Case {
            name: "drag, rat preset, texture",
            rod: rat_rod,
            surface: rat_sine,
            job: Job::Drag(DragOptions {
                d_max: 0.0162,
                ..cycles
            }),
        },
    ]
}

/// Minimum time per run over `reps` round-robin repetitions of all cases.
fn interleaved(cases: &[Case], reps: usize) -> Vec<Duration> {
    let mut best = vec![Duration::MAX; cases.len()];
    for _ in 0..reps {
        for (c, b) in cases.iter().zip(best.iter_mut()) {
            let t = Instant::now();
            c.run();
            *b = (*b).min(t.elapsed());
        }
    }
    best
}

fn bench(c: &mut Criterion) {
    let cases = cases();
    let times = interleaved(&cases, 40);
    println!(
        "\n{:<30} {:>6} {:>10} {:>8}",
        "case", "slips", "ms", "× scan"
    );
    // (the corrugated drag stops at its eleventh slip: max_slips)
    for (i, case) in cases.iter().enumerate() {
        println!(
            "{:<30} {:>6} {:>10.3} {:>8.2}",
            case.name,
            case.run(),
            times[i].as_secs_f64() * 1e3,
            times[i].as_secs_f64() / times[0].as_secs_f64()
        );
    }
    // which contact drove each slip of the last case (s < 1: a side)
    if let Job::Drag(o) = &cases[3].job {
        let r = drag(&cases[3].rod, &cases[3].surface, o).expect("drag");
        let s: Vec<f64> = r.slips.iter().map(|e| e.s_slip).collect();
        let (lo, hi) = s
            .iter()
            .fold((1.0f64, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)));
        println!("{}: slips driven at s in [{lo:.4}, {hi:.4}]", cases[3].name);
    }
    let mut g = c.benchmark_group("drag");
    g.sample_size(10);
    g.warm_up_time(Duration::from_millis(300));
    g.measurement_time(Duration::from_secs(2));
    for case in &cases {
        g.bench_function(case.name, |b| b.iter(|| case.run()));
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
