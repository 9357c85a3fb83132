//! Cost of the stiction scan per scene: time, Newton iterations, integration steps.
//! `cargo run -p vibrissa --release --example scan_cost`
use std::time::Instant;
use vibrissa::{scan, Model, ScanOptions, Scene, Stiffness};

fn run(name: &str, scene: Scene, points: usize) {
    run_d(name, scene, points, 0.5)
}

fn run_d(name: &str, scene: Scene, points: usize, d_max: f64) {
    let m = Model::new(&scene).unwrap();
    let o = ScanOptions {
        points,
        d_max,
        ..ScanOptions::default()
    };
    let t = Instant::now();
    let r = scan(&m, &o);
    let el = t.elapsed().as_secs_f64();
    match r {
        Ok(r) => println!(
            "{name:28} phi1_0 {:.4} {:8.1} ms  pts {:3}  stop {}  mu_max {:.6}  newton {} steps {} rej {} rhs {}",
            r.start.phi1,
            el * 1e3,
            r.points.len(),
            r.stop,
            r.mu_max,
            r.stats.newton_iters,
            r.stats.steps,
            r.stats.rejected_steps,
            r.stats.rhs_evals
        ),
        Err(e) => println!("{name:28} {:8.1} ms  error {e}", el * 1e3),
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let which = args.get(1).map(|s| s.as_str()).unwrap_or("all");
    let eta = |e: f64, s: Stiffness| Scene {
        eta: e,
        stiffness: s,
        ..Scene::default()
    };
    if which == "all" || which == "b1" {
        run("uniform", Scene::default(), 201);
        run(
            "table b=1",
            eta(
                0.75,
                Stiffness::Table {
                    s: vec![0.0, 0.25, 0.5, 0.75, 1.0],
                    b: vec![1.0; 5],
                },
            ),
            201,
        );
    }
    if which == "all" || which == "taper" {
        run(
            "taper 0.999",
            eta(0.75, Stiffness::Taper { ratio: 0.999 }),
            201,
        );
        run("taper 0.3", eta(0.75, Stiffness::Taper { ratio: 0.3 }), 21);
        run("taper 0.1", eta(0.75, Stiffness::Taper { ratio: 0.1 }), 201);
    }
    if which == "all" || which == "pen" {
        run(
            "taper 0.5 eta 0.6",
            eta(0.6, Stiffness::Taper { ratio: 0.5 }),
            21,
        );
    }
    if which == "fold2" {
        for e in [0.6, 0.75, 0.9, 0.95] {
            run_d(
                &format!("uniform eta {e}"),
                Scene {
                    eta: e,
                    ..Scene::default()
                },
                11,
                1.9,
            );
            run_d(
                &format!("c 2 eta {e}"),
                Scene {
                    eta: e,
                    support_compliance: 2.0,
                    ..Scene::default()
                },
                11,
                1.9,
            );
            run_d(
                &format!("beta -0.3 eta {e}"),
                Scene {
                    eta: e,
                    surface_angle: -0.3,
                    ..Scene::default()
                },
                11,
                1.9,
            );
            run_d(
                &format!("beta 0.3 eta {e}"),
                Scene {
                    eta: e,
                    surface_angle: 0.3,
                    ..Scene::default()
                },
                11,
                1.9,
            );
            run_d(
                &format!("taper .7 eta {e}"),
                Scene {
                    eta: e,
                    stiffness: Stiffness::Taper { ratio: 0.7 },
                    ..Scene::default()
                },
                11,
                1.9,
            );
        }
    }
    if which == "fold" {
        use vibrissa::Precurvature;
        for e in [0.6, 0.75, 0.9] {
            for c in [0.5, 1.0, 2.0] {
                run(
                    &format!("compliance {c} eta {e}"),
                    Scene {
                        eta: e,
                        support_compliance: c,
                        ..Scene::default()
                    },
                    11,
                );
            }
            for k in [-2.0, -1.0, 1.0, 2.0] {
                run(
                    &format!("k0 {k} eta {e}"),
                    Scene {
                        eta: e,
                        precurvature: Precurvature::Linear { k0: k, k1: 0.0 },
                        ..Scene::default()
                    },
                    11,
                );
            }
            for b in [-0.3, 0.3] {
                run(
                    &format!("beta {b} eta {e}"),
                    Scene {
                        eta: e,
                        surface_angle: b,
                        ..Scene::default()
                    },
                    11,
                );
            }
        }
    }
    if which == "all" || which == "t005" {
        for e in [0.5, 0.6, 0.75, 0.9] {
            run(
                &format!("taper 0.05 eta {e}"),
                eta(e, Stiffness::Taper { ratio: 0.05 }),
                6,
            );
        }
    }
}
