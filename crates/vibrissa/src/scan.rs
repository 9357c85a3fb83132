//! The quasi-static stiction scan (paper §3) and its inverse: the entry points, the start, and the
//! choice of stepper; the march itself is in module `march`.

use crate::config::Engine;
use crate::equations::{Ends, RodBvp, ScanFamily};
use crate::march::{march, Contact, Ctx};
use crate::profile::{Profile, Uniform};
use crate::report::{Inference, RangeEnd, ScanOptions, ScanResult};
use crate::shooter::Shooter;
use crate::solve::{solve, Method, Target};
use crate::stepper::{GenericStepper, OwnStepper};
use crate::{BranchChoice, Rod, Shape, ShapeKind, Surface, VibrissaError};
use bvp::Guess;

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

fn scan_impl(
    rod: &Rod,
    surface: &Surface,
    opts: &ScanOptions,
    grid: &[f64],
) -> Result<ScanResult, VibrissaError> {
    if opts.solver.method == Method::Analytic {
        return crate::analytic::scan_analytic(rod, surface, opts, grid);
    }
    let (eta, beta) = (surface.eta(), surface.angle());
    // the start: the rod continuously connected to the pressed uniform rod (whatever its load
    // reversals: a pre-curved rod may have some), pushed, not pulled
    let start = solve(
        rod,
        beta,
        Target::Eta(eta),
        &BranchChoice::Any,
        &opts.solver,
    )
    .map_err(|e| match convex_reach(beta) {
        // say why when the uniform rod's convex shape, the start of every rod's homotopy,
        // cannot have its tip at eta under this force angle
        Some((lo, hi)) if !(lo..=hi).contains(&eta) => context(
            e,
            &format!(
                "scan start (alpha = surface angle, y(1) = eta; at this surface angle the \
                 uniform clamped rod's convex shapes put the tip only at heights in \
                 [{lo:.6}, {hi:.6}], not at eta = {eta}: flatten the surface or move eta)"
            ),
        ),
        _ => context(e, "scan start (alpha = surface angle, y(1) = eta)"),
    })?;
    match start.kind() {
        ShapeKind::Regular { .. } => {}
        found => {
            return Err(VibrissaError::NoContact {
                eta,
                f: start.f,
                found,
            })
        }
    }
    let contact = Contact {
        eta,
        beta,
        x_star: start.x1,
    };
    if rod.has_uniform_profile() {
        run_with(rod, Uniform, opts, grid, contact, &start)
    } else {
        run_with(rod, rod.profile(1.0), opts, grid, contact, &start)
    }
}

/// The march for one profile type, on the rod's own shooter (single shooting) or a generic
/// method.
fn run_with<P: Profile>(
    rod: &Rod,
    profile: P,
    opts: &ScanOptions,
    grid: &[f64],
    contact: Contact,
    start: &Shape,
) -> Result<ScanResult, VibrissaError> {
    let c = rod.support_compliance();
    let family = ScanFamily {
        rod: RodBvp {
            profile: profile.clone(),
            compliance: c,
            alpha: contact.beta,
            ends: Ends::Tip {
                x1: contact.x_star,
                y1: contact.eta,
            },
        },
        eta: contact.eta,
        x_star: contact.x_star,
    };
    let general = rod.profile(1.0);
    let ctx = Ctx {
        contact,
        profile: &profile,
        general: &general,
        opts,
    };
    let start_failed = |e: String| VibrissaError::NoConvergence {
        what: "scan start (correction at d = 0)".into(),
        reason: e,
    };
    let u0 = [start.m_base, start.f, contact.beta];
    if let Some(tol) = opts.solver.own_shooter_tol() {
        let mut st = OwnStepper {
            shooter: match start.solution() {
                Some(sol) => Shooter::on_mesh(profile.clone(), c, tol, sol.mesh.clone()),
                None => Shooter::new(profile.clone(), c, tol, 8),
            },
            eta: contact.eta,
            x_star: contact.x_star,
        };
        let p0 = st
            .correct_from(0.0, u0, None)
            .map_err(|e| start_failed(e.to_string()))?;
        Ok(march(&mut st, &ctx, grid, p0, start.stats.clone()))
    } else {
        let mut st = GenericStepper {
            family,
            engine: Engine::with_max_iter(&opts.solver, 12)?,
            stats: Default::default(),
            tangents: Shooter::new(profile.clone(), c, opts.solver.tol.min(1e-8), 8),
        };
        let mut sol = start
            .solution()
            .cloned()
            .ok_or(VibrissaError::NotImplemented("analytic start"))?;
        sol.params = vec![start.f, contact.beta];
        let p0 = st.point(0.0, &Guess::from(&sol)).map_err(start_failed)?;
        Ok(march(&mut st, &ctx, grid, p0, start.stats.clone()))
    }
}

/// The tip heights `[y1(φ1 = 0), y1(φ1 = π/2 + 2α)]` of the uniform clamped rod's convex shapes
/// under the force angle `alpha` (`y1` increases with `φ1` there), where the closed forms exist.
fn convex_reach(alpha: f64) -> Option<(f64, f64)> {
    let top = std::f64::consts::FRAC_PI_2 + 2.0 * alpha;
    let y = |p: f64| elastica::Elastica::new(elastica::Branch::Convex, alpha, p).map(|e| e.y1);
    Some((y(0.0).ok()?, y(top).ok()?))
}

fn context(e: VibrissaError, what: &str) -> VibrissaError {
    match e {
        VibrissaError::Solver { context, source } => VibrissaError::Solver {
            context: format!("{what}: {context}"),
            source,
        },
        other => other,
    }
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
    let probe = scan_at(rod, surface, &o, &[])?;
    let max = probe.d_at_mu_max;
    match probe.range_end {
        RangeEnd::FirstMaximum | RangeEnd::Event => {}
        RangeEnd::DMax => {
            // what the range would be: the scan to (almost) the largest d_max, 2 rod lengths
            let wide = ScanOptions {
                d_max: 1.999,
                ..o.clone()
            };
            let full = scan_at(rod, surface, &wide, &[]).ok().and_then(|w| {
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
