//! The scan by the closed forms of crate `elastica` (the paper's rod on a horizontal surface).
//!
//! `elastica::ClosedFormScan` parametrizes the scan as one curve in `t` across the fold in φ1
//! (phase 0 in α, phase 1 in φ1 down to its minimum, the other sheet back up). Along it `d(t)`
//! rises to a fold in `d` (snap-through) or to the end of the curve, which is a penetration when
//! the tip slope reaches 0. The curve is tabulated (64 values of `t` per unit), every event is
//! located on it by Brent's method in `t` (slip where `μ(t) = μ0`, the fold as the maximum of
//! `d(t)`), and each output displacement is found by Brent's method on `d(t) − d` in its cell.

use crate::report::{Event, RangeEnd, ScanOptions, ScanPoint, ScanResult, StopReason};
use crate::shape::ShapePoint;
use crate::{Rod, Surface, VibrissaError};
use elastica::roots::{brent_max, brent_root};
use elastica::{Branch, ClosedFormScan, Elastica, ElasticaError, Phase0End};

/// Values of the curve parameter per unit in the table.
const PER_UNIT: usize = 64;

/// The closed-form scan as a curve in `t`.
struct Curve {
    cf: ClosedFormScan,
    /// `(t, d)` with `d` increasing, up to the fold in `d` or the end of the curve.
    table: Vec<(f64, f64)>,
}

impl Curve {
    fn new(eta: f64) -> Result<Curve, ElasticaError> {
        let cf = ClosedFormScan::new(eta)?;
        let mut c = Curve { cf, table: vec![] };
        let end = c.cf.curve_end();
        let n = (end * PER_UNIT as f64) as usize;
        for i in 0..=n {
            let t = if i == n {
                end
            } else {
                i as f64 / PER_UNIT as f64
            };
            let d = c.at(t)?.1;
            if c.table.last().is_some_and(|&(_, dp)| d < dp) {
                break;
            }
            c.table.push((t, d));
        }
        Ok(c)
    }

    /// The rod at `t` and its displacement.
    fn at(&self, t: f64) -> Result<(Elastica, f64), ElasticaError> {
        let cf = &self.cf;
        let p = cf.curve_at(t)?;
        let br = if t <= 1.0 || p.flex == 0 {
            Branch::Convex
        } else {
            Branch::OneFlex
        };
        let e = if t == 1.0 && br == Branch::Convex && cf.phase0_end == Phase0End::TurningPoint {
            Elastica::turning(Branch::Convex, p.alpha)?
        } else {
            Elastica::new(br, p.alpha, p.phi1)?
        };
        Ok((e, p.d))
    }

    /// Where the tabulated curve stops: the fold in `d` (located as the maximum of `d(t)`) or
    /// the end of the curve. `(t, d, event)`.
    fn end(&self) -> Result<(f64, f64, Option<Event>), ElasticaError> {
        let n = self.table.len();
        let (t_last, d_last) = self.table[n - 1];
        if t_last < self.cf.curve_end() {
            // d fell after t_last: its maximum lies between the neighbours of t_last
            let lo = self.table[n.saturating_sub(2)].0;
            let hi = (t_last + 1.0 / PER_UNIT as f64).min(self.cf.curve_end());
            let (t, d) = brent_max(|t| Ok(self.at(t)?.1), lo, hi, 1e-15, 500)?;
            return Ok((t, d, Some(Event::FoldInD)));
        }
        // the curve ends where the tip slope reaches 0 (phase 0 or 1 down to φ1 = 0): beyond
        // it the rod crosses the surface
        let pen = self.cf.phase0_end == Phase0End::TipHorizontal || self.cf.fold.is_none();
        Ok((t_last, d_last, pen.then_some(Event::Penetration)))
    }

    /// `t` with `d(t) = d` for `d` within the table.
    fn t_of_d(&self, d: f64) -> Result<f64, ElasticaError> {
        let i = self.table.partition_point(|g| g.1 < d);
        if i == 0 {
            return Ok(self.table[0].0);
        }
        let (ta, tb) = (self.table[i - 1].0, self.table[i].0);
        if self.table[i].1 == d {
            return Ok(tb);
        }
        Ok(brent_root(|t| Ok(self.at(t)?.1 - d), ta, tb, 1e-15, 200)?)
    }

    /// The first `t ≤ t_stop` where `μ(t) = mu0`, if any.
    fn slip(&self, mu0: f64, t_stop: f64) -> Result<Option<f64>, ElasticaError> {
        let mu = |t: f64| -> Result<f64, ElasticaError> { Ok((-self.at(t)?.0.alpha).tan()) };
        if mu(0.0)? >= mu0 {
            return Ok(Some(0.0));
        }
        let mut ts: Vec<f64> = self
            .table
            .iter()
            .map(|g| g.0)
            .filter(|&t| t < t_stop)
            .collect();
        ts.push(t_stop);
        let mut prev = 0.0;
        for &t in &ts[1..] {
            if mu(t)? >= mu0 {
                return Ok(Some(brent_root(|t| Ok(mu(t)? - mu0), prev, t, 1e-15, 200)?));
            }
            prev = t;
        }
        Ok(None)
    }
}

/// The stuck tip of a closed-form point `p`, where the start put it (`at`), as the numerical
/// scan gives its contacts: the force in the surface's frame, `T = μ N`.
fn stuck_tip(p: &ScanPoint, at: [f64; 2], mu0: Option<f64>) -> crate::contacts::ContactState {
    crate::contacts::ContactState {
        s: 1.0,
        tip: true,
        x: at[0],
        y: at[1],
        normal: p.normal,
        tangential: p.mu * p.normal,
        hold: crate::contacts::Hold::Stuck,
        mu: mu0.unwrap_or(f64::INFINITY),
        lies_to: None,
        friction_ratio: None,
    }
}

fn point(e: &Elastica, d: f64, event: Option<Event>) -> ScanPoint {
    ScanPoint {
        d,
        mu: (-e.alpha).tan(),
        normal: e.f * e.alpha.cos(),
        mu_peak: (-e.alpha).tan().abs(),
        alpha: e.alpha,
        phi1: e.phi1,
        f: e.f,
        fx: e.fx(),
        fy: e.fy(),
        m_base: e.m_base,
        flex: e.flex_count(),
        s_flex: if e.flex_count() > 0 { e.s_b } else { None },
        y_max: e.y_max(),
        contact: crate::report::ContactLabel::TIP,
        s_c: None,
        event,
        x_contact: None,
    }
}

fn shape(e: &Elastica, n: usize) -> Result<Vec<ShapePoint>, ElasticaError> {
    Ok(e.shape(n)?
        .into_iter()
        .map(|p| ShapePoint {
            s: p.s,
            x: p.x,
            y: p.y,
            phi: p.phi,
            kappa: p.kappa,
            m: p.kappa,
        })
        .collect())
}

/// The closed-form scan at the displacements `grid` (sorted, in `[0, d_max]`).
pub(crate) fn scan_analytic(
    rod: &Rod,
    surface: &Surface,
    opts: &ScanOptions,
    grid: &[f64],
) -> Result<ScanResult, VibrissaError> {
    if !(rod.is_uniform_clamped() && surface.angle() == 0.0 && surface.profile().is_none()) {
        return Err(VibrissaError::MethodUnavailable {
            method: "analytic".into(),
            reason: "closed forms exist only for the paper's rod (uniform, straight, clamped) on a horizontal straight surface".into(),
        });
    }
    let eta = surface.eta();
    let ctx =
        |e: ElasticaError| VibrissaError::elastica(format!("closed-form scan at eta = {eta}"), e);
    let c = Curve::new(eta).map_err(ctx)?;
    let (mut t_stop, mut d_stop, mut event) = c.end().map_err(ctx)?;
    if let Some(mu0) = opts.mu0 {
        if let Some(ts) = c.slip(mu0, t_stop).map_err(ctx)? {
            t_stop = ts;
            d_stop = c.at(ts).map_err(ctx)?.1;
            event = Some(Event::Slip);
        }
    }
    let (e0, _) = c.at(0.0).map_err(ctx)?;
    let start = point(&e0, 0.0, None);
    let mut points = Vec::with_capacity(grid.len() + 1);
    let mut shapes = Vec::new();
    let mut push = |e: &Elastica, p: ScanPoint| -> Result<(), ElasticaError> {
        points.push(p);
        if let Some(n) = opts.keep_shapes {
            shapes.push(shape(e, n)?);
        }
        Ok(())
    };
    for &d in grid {
        if d > d_stop || (d == d_stop && event.is_some()) {
            break;
        }
        let (e, _) = c.at(c.t_of_d(d).map_err(ctx)?).map_err(ctx)?;
        push(&e, point(&e, d, None)).map_err(ctx)?;
    }
    let reached_end = event.is_some() && d_stop <= opts.d_max;
    let mut stop = StopReason::DMax;
    let mut at_stop = None;
    if reached_end {
        let ev = event.unwrap_or(Event::Penetration);
        let (e, _) = c.at(t_stop).map_err(ctx)?;
        let p = point(&e, d_stop, Some(ev));
        stop = match ev {
            Event::Slip => StopReason::Slip {
                d: d_stop,
                mu: p.mu,
            },
            Event::FoldInD => StopReason::FoldInD { d: d_stop },
            _ => StopReason::Penetration {
                d: d_stop,
                s: 1.0,
                y: eta,
            },
        };
        at_stop = Some(p);
        push(&e, p).map_err(ctx)?;
    } else if event.is_none() && d_stop < opts.d_max {
        stop = StopReason::SolverFailure {
            d: d_stop,
            message: format!(
                "the closed-form curve ends at d = {d_stop}; beyond it use a numerical method"
            ),
        };
    }
    // the measurable range: the first maximum of μ if the scan reaches it, else its end
    let best = c.cf.mu_max().map_err(ctx)?;
    let reach = if reached_end {
        d_stop
    } else {
        opts.d_max.min(d_stop)
    };
    let phase1 = c.cf.phase0_end == Phase0End::TurningPoint;
    let (mu_max, d_at_mu_max, range_end) = if phase1 && best.d <= reach {
        (best.mu, best.d, RangeEnd::FirstMaximum)
    } else if let Some(p) = at_stop {
        (p.mu, p.d, RangeEnd::Event)
    } else {
        let t = c.t_of_d(reach).map_err(ctx)?;
        let (e, _) = c.at(t).map_err(ctx)?;
        ((-e.alpha).tan(), reach, RangeEnd::DMax)
    };
    let contacts = (points.iter())
        .map(|p| vec![stuck_tip(p, [e0.x1, e0.y1], opts.mu0)])
        .collect();
    Ok(ScanResult {
        eta,
        surface_point: [e0.x1, e0.y1],
        start,
        points,
        mu_max,
        mu_at_max: mu_max,
        d_at_mu_max,
        range_end,
        stop,
        stats: bvp::Stats::default(),
        shapes,
        contacts,
        handover: None,
    })
}
