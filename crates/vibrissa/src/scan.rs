//! The quasi-static stiction scan (paper §3) and its inverse: the entry points, the start, and the
//! choice of stepper; the march itself is in module `march`.

use crate::chain::{Chain, Family};
use crate::engine::{Begin, FirstPoint};
use crate::march::Spec;
use crate::profile::{Profile, Uniform};
use crate::report::{ContactModel, Inference, RangeEnd, ScanOptions, ScanPoint, ScanResult};
use crate::solve::Method;
use crate::{Rod, Surface, VibrissaError};

/// Runs the stiction scan. Errors only for invalid input or when it cannot even start;
/// failures along the way end the scan with [`crate::StopReason::SolverFailure`].
///
/// Output points are at `d = i·d_max/(points − 1)`, `i = 0, …, points − 1`, up to the stop.
///
/// ```
/// use vibrissa::{Rod, ScanOptions, StopReason, Surface};
///
/// // the paper's rod at eta = 0.75, stopped where |mu| reaches mu0 = 0.7 (the tip slips)
/// let opts = ScanOptions { points: 21, mu0: Some(0.7), ..ScanOptions::default() };
/// let r = vibrissa::scan(&Rod::uniform(), &Surface::flat(0.75)?, &opts)?;
/// let last = r.points.last().unwrap();
/// assert_eq!(last.event, Some(vibrissa::Event::Slip));
/// assert!(matches!(r.stop, StopReason::Slip { .. }) && (last.mu - 0.7).abs() < 1e-9);
/// # Ok::<(), vibrissa::VibrissaError>(())
/// ```
pub fn scan(rod: &Rod, surface: &Surface, opts: &ScanOptions) -> Result<ScanResult, VibrissaError> {
    opts.validate()?;
    let n = opts.points;
    let grid: Vec<f64> = (0..n)
        .map(|i| {
            if i + 1 == n {
                opts.d_max
            } else {
                opts.d_max * i as f64 / (n - 1) as f64
            }
        })
        .collect();
    scan_impl(rod, surface, opts, &grid)
}

/// As [`scan`], with output points at the given displacements (sorted ascending, in
/// `[0, d_max]`) instead of the uniform grid; `opts.points` is ignored.
///
/// ```
/// use vibrissa::{Rod, ScanOptions, Surface};
///
/// let r = vibrissa::scan_at(&Rod::uniform(), &Surface::flat(0.75)?, &ScanOptions::default(), &[0.0, 0.1])?;
/// assert_eq!(r.points.len(), 2);
/// assert!((r.points[1].mu - 0.7183848759918717).abs() < 1e-9); // the README's scan at d = 0.1
/// # Ok::<(), vibrissa::VibrissaError>(())
/// ```
pub fn scan_at(
    rod: &Rod,
    surface: &Surface,
    opts: &ScanOptions,
    d: &[f64],
) -> Result<ScanResult, VibrissaError> {
    opts.validate()?;
    // (an empty list would give a μ_max over no point; the output points' own limits)
    crate::limits::OUTPUT_DISPLACEMENTS
        .check_count("the number of output displacements d", d.len())?;
    if let Some(n) = opts.keep_shapes {
        crate::limits::check_shapes("keep_shapes", n, d.len())?;
    }
    for (i, &di) in d.iter().enumerate() {
        if !(di >= 0.0 && di <= opts.d_max) {
            return Err(VibrissaError::range(
                format!("d[{i}]"),
                di,
                format!("[0, d_max] = [0, {}]", opts.d_max),
            ));
        }
        if i > 0 && di < d[i - 1] {
            return Err(VibrissaError::range(
                format!("d[{i}]"),
                di,
                format!("[d[{}], d_max] (sorted ascending)", i - 1),
            ));
        }
    }
    scan_impl(rod, surface, opts, d)
}

/// The scan to its end without output points (its start, events and measurable range).
fn scan_probe(
    rod: &Rod,
    surface: &Surface,
    opts: &ScanOptions,
) -> Result<ScanResult, VibrissaError> {
    opts.validate()?;
    scan_impl(rod, surface, opts, &[])
}

fn scan_impl(
    rod: &Rod,
    surface: &Surface,
    opts: &ScanOptions,
    grid: &[f64],
) -> Result<ScanResult, VibrissaError> {
    if opts.solver.method == Method::Analytic {
        if rod.tip_radius() > 0.0 {
            return Err(VibrissaError::MethodUnavailable {
                method: "analytic".into(),
                reason: "the closed forms are those of the point tip; a round tip (tip radius > \
                         0) is solved by the rod's own shooter (method shooting)"
                    .into(),
            });
        }
        return crate::analytic::scan_analytic(rod, surface, opts, grid);
    }
    if rod.has_uniform_profile() {
        scan_with(rod, Uniform, surface, opts, grid)
    } else {
        scan_with(rod, rod.profile(1.0), surface, opts, grid)
    }
}

/// The scan for one profile type: the start, then the march in `d` on the rod's own shooter or
/// a generic method.
fn scan_with<P: Profile>(
    rod: &Rod,
    profile: P,
    surface: &Surface,
    opts: &ScanOptions,
    grid: &[f64],
) -> Result<ScanResult, VibrissaError> {
    let eta = surface.eta();
    let general = rod.profile(1.0);
    let compound = opts.contact == ContactModel::Anywhere;
    let (start, set, p0) = crate::ground::start(
        rod,
        &profile,
        surface,
        opts.solver.start,
        opts.solver.start_tol(),
    )?;
    surface.check_on(p0[0])?;
    // a friction profile without a given μ0: the static coefficient where the tip sticks
    let mu0 = opts.mu0.or_else(|| {
        surface
            .texture()
            .map(|t| t.at(start.pt.sol.right()[0], 1.0).0)
    });
    let env = crate::ground::env_of(surface, p0, mu0, compound);
    let spec = Spec {
        env: &env,
        grid,
        lam_end: opts.d_max,
        keep_shapes: opts.keep_shapes,
        general: &general,
        friction: true,
        check_start: true,
        slide: false,
        pass_fold_ahead: true,
        retangent: true,
    };
    let mut sh = start.sh.clone();
    sh.stats = Default::default();
    let begin = Begin {
        chain: Chain::new(sh, set, Family::Drag).with_lean_rest(),
        env: env.clone(),
        solver: &opts.solver,
        lam: 0.0,
        u: start.pt.u.clone(),
        first: FirstPoint::Correct,
        run: "scan",
        hand_over: true,
        what: "scan start (correction at d = 0)".into(),
    };
    let (out, handover) = begin.march(&spec, &profile, &start.stats)?;
    let start_point = out
        .points
        .first()
        .copied()
        .filter(|p| p.d == 0.0)
        .unwrap_or_else(|| {
            let mut sp = out.points.first().copied().unwrap_or(ScanPoint::nan());
            sp.d = 0.0;
            sp
        });
    let (mu_max, mu_at_max, d_at_mu_max) = out.best;
    Ok(ScanResult {
        eta,
        surface_point: p0,
        start: start_point,
        points: out.points,
        mu_max,
        mu_at_max,
        d_at_mu_max,
        range_end: out.range_end,
        stop: out.stop,
        stats: out.stats,
        shapes: out.shapes,
        contacts: out.contacts,
        handover,
    })
}

/// Infers μ0 from the displacement `d0` at which the tip slipped: `μ0 = |μ(d0)|` for `d0` in
/// the measurable range, the first monotone stretch of `|μ(d)|` from `d = 0` up to the first of:
/// its first maximum, lift-off, penetration, a fold in `d` (beyond it a slip would be ambiguous
/// or impossible). A `d_max` that ends the scan while `|μ|` still rises is an error too: the range
/// is not known then.
///
/// ```
/// use vibrissa::{Rod, ScanOptions, Surface};
///
/// let (rod, surface) = (Rod::uniform(), Surface::flat(0.75)?);
/// let r = vibrissa::infer(&rod, &surface, 0.1, &ScanOptions::default())?;
/// assert!((r.mu0 - 0.7183848759918717).abs() < 1e-9);
/// // beyond the first maximum of |mu| a slip displacement has two answers: refused
/// assert!(vibrissa::infer(&rod, &surface, 0.2, &ScanOptions::default()).is_err());
/// # Ok::<(), vibrissa::VibrissaError>(())
/// ```
pub fn infer(
    rod: &Rod,
    surface: &Surface,
    d0: f64,
    opts: &ScanOptions,
) -> Result<Inference, VibrissaError> {
    opts.validate()?;
    if !(d0.is_finite() && d0 >= 0.0) {
        return Err(VibrissaError::range(
            "d0",
            d0,
            "[0, d at the end of the measurable range]",
        ));
    }
    let o = ScanOptions {
        mu0: None,
        keep_shapes: None,
        ..opts.clone()
    };
    let probe = scan_probe(rod, surface, &o)?;
    let max = probe.d_at_mu_max;
    match probe.range_end {
        RangeEnd::FirstMaximum | RangeEnd::Event => {}
        RangeEnd::DMax => {
            // what the range would be: the scan to (almost) the largest d_max, 2 rod lengths
            let wide = ScanOptions {
                d_max: 1.999,
                ..o.clone()
            };
            let full = scan_probe(rod, surface, &wide).ok().and_then(|w| {
                matches!(w.range_end, RangeEnd::FirstMaximum | RangeEnd::Event)
                    .then(|| (w.d_at_mu_max, range_end_text(&w)))
            });
            return Err(VibrissaError::RangeCutShort {
                d_max: opts.d_max,
                mu: probe.mu_max,
                full,
            });
        }
        RangeEnd::SolverFailure => {
            return Err(VibrissaError::NoConvergence {
                what: "the scan that finds the measurable range".into(),
                reason: probe.stop.to_string(),
            })
        }
    }
    if d0 > max {
        return Err(VibrissaError::NotMeasurable {
            d0,
            max,
            end: range_end_text(&probe),
        });
    }
    let at = scan_at(rod, surface, &o, &[d0])?;
    let p = at
        .points
        .iter()
        .find(|p| p.event.is_none())
        .ok_or_else(|| VibrissaError::NoConvergence {
            what: format!("scan to d0 = {d0}"),
            reason: at.stop.to_string(),
        })?;
    Ok(Inference {
        mu0: p.mu.abs(),
        d0,
        measurable_d: (0.0, max),
        mu_max: probe.mu_max,
        range_end: probe.range_end,
    })
}

/// What ends a scan's measurable range, with the event when it is one.
fn range_end_text(r: &ScanResult) -> String {
    match r.range_end {
        RangeEnd::Event => format!("{} ({})", r.range_end, r.stop),
        other => other.to_string(),
    }
}
