//! A sweep over many distinct corrugated surfaces in constant memory (issue 35): 10⁵ surfaces
//! `A·sin(2π x/λ + φ)` with amplitude, wavelength and phase varied (no two alike), each a short
//! scan of the paper's rod (η = 0.75, the pressed start on the corrugation and 3 points on
//! d ∈ [0, 0.02]); the resident set size of the process (`/proc/self/statm`, pages of 4 KiB) is
//! printed at the start and after every tenth of the surfaces, with the peak (`VmHWM` of
//! `/proc/self/status`).
//!
//! A surface's curved profile is shared (`Arc`) by the surface and whatever refers to it during
//! a solve; nothing keeps it after the caller drops the surface, so the RSS stays flat.
//!
//! ```sh
//! cargo run --release --example many_surfaces            # 100 000 surfaces
//! cargo run --release --example many_surfaces -- 20000   # fewer
//! ```
//!
//! It ends with an error if the RSS after the last surface exceeds that after the first tenth by
//! more than 8 MiB (10⁵ surfaces kept alive at even 100 bytes each would add 9.5 MiB).

use anyhow::{bail, Context, Result};
use std::time::Instant;
use vibrissa::surface::SurfaceProfile;
use vibrissa::{scan, ScanOptions, Scene, StopReason};

/// Resident set size in bytes (`/proc/self/statm`, second field, 4 KiB pages).
fn rss() -> Result<u64> {
    let s = std::fs::read_to_string("/proc/self/statm").context("reading /proc/self/statm")?;
    let pages: u64 = s
        .split_whitespace()
        .nth(1)
        .context("statm: no resident field")?
        .parse()?;
    Ok(pages * 4096)
}

/// Peak resident set size in bytes (`VmHWM` of `/proc/self/status`).
#[allow(dead_code)] // main's
fn peak() -> Result<u64> {
    let s = std::fs::read_to_string("/proc/self/status").context("reading /proc/self/status")?;
    let kb: u64 = s
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .context("status: no VmHWM")?
        .trim()
        .trim_end_matches("kB")
        .trim()
        .parse()?;
    Ok(kb * 1024)
}

/// The fractional part of `i·g` (a low-discrepancy sequence: distinct for distinct `i`).
fn frac(i: usize, g: f64) -> f64 {
    (i as f64 * g).fract()
}

/// Surface `i`: amplitude in [0.002, 0.02], wavelength in [0.3, 1], phase in [0, 2π) (steepest
/// slope 2πA/λ ≤ 0.42, within the profiles' limit 1).
fn corrugation(i: usize) -> SurfaceProfile {
    SurfaceProfile::Sine {
        amplitude: 0.002 + 0.018 * frac(i, 0.618_033_988_749_894_9),
        wavelength: 0.3 + 0.7 * frac(i, 0.414_213_562_373_095_1),
        phase: std::f64::consts::TAU * frac(i, 0.732_050_807_568_877_2),
    }
}

/// What a sweep measured.
pub struct Sweep {
    /// `(surfaces done, RSS in bytes)`: at the start and after every `every` surfaces.
    pub rss: Vec<(usize, u64)>,
    /// Wall-clock time of the sweep (s).
    pub seconds: f64,
    /// Right-hand-side evaluations, all surfaces.
    pub rhs_evals: usize,
    /// The largest `μ` at the last output point of any surface's scan.
    pub mu_max: f64,
}

/// Scans `n` surfaces (`corrugation(0..n)`), reads the RSS after every `every` of them and calls
/// `report(surfaces done, RSS, seconds)` there.
pub fn run(n: usize, every: usize, mut report: impl FnMut(usize, u64, f64)) -> Result<Sweep> {
    let opts = ScanOptions {
        d_max: 0.02,
        points: 3,
        ..ScanOptions::default()
    };
    let t0 = Instant::now();
    let start = rss()?;
    report(0, start, 0.0);
    let mut sweep = Sweep {
        rss: vec![(0, start)],
        seconds: 0.0,
        rhs_evals: 0,
        mu_max: 0.0,
    };
    for i in 0..n {
        let scene = Scene {
            surface: corrugation(i),
            ..Scene::default()
        };
        let (rod, surface) = scene.parts()?;
        let r = scan(&rod, &surface, &opts).with_context(|| format!("surface {i}"))?;
        if r.stop != StopReason::DMax || r.points.len() < 3 {
            bail!("surface {i} ({:?}): stopped at {}", corrugation(i), r.stop);
        }
        sweep.rhs_evals += r.stats.rhs_evals;
        sweep.mu_max = sweep.mu_max.max(r.points[r.points.len() - 1].mu.abs());
        if (i + 1) % every == 0 {
            let now = rss()?;
            sweep.rss.push((i + 1, now));
            report(i + 1, now, t0.elapsed().as_secs_f64());
        }
    }
    sweep.seconds = t0.elapsed().as_secs_f64();
    Ok(sweep)
}

#[allow(dead_code)] // the tests call `run`
fn main() -> Result<()> {
    let n: usize = match std::env::args().nth(1) {
        Some(a) => a.parse().context("the number of surfaces")?,
        None => 100_000,
    };
    let mib = |b: u64| b as f64 / 1048576.0;
    println!("surfaces  rss_MiB  time_s");
    let sweep = run(n, (n / 10).max(1), |i, rss, t| {
        println!("{i:8}  {:7.2}  {t:6.1}", mib(rss));
    })?;
    println!(
        "{n} surfaces in {:.1} s ({:.0} µs each, {:.0} rhs evaluations each); peak RSS {:.2} MiB",
        sweep.seconds,
        1e6 * sweep.seconds / n as f64,
        sweep.rhs_evals as f64 / n as f64,
        mib(peak()?)
    );
    if let (Some(&(_, first)), Some(&(_, last))) = (sweep.rss.get(1), sweep.rss.last()) {
        let grown = last as f64 - first as f64;
        println!(
            "RSS from the first tenth to the end: {:+.2} MiB",
            grown / 1048576.0
        );
        if grown > 8.0 * 1048576.0 {
            bail!(
                "the RSS grew by {:.2} MiB over the sweep",
                grown / 1048576.0
            );
        }
    }
    Ok(())
}
