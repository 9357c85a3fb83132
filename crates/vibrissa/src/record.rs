//! What a march records (module `march` drives, this module observes): the output rows on the
//! grid and at events, their shapes and tip states, the first maximum of `|μ|` and what ended the
//! measurable range, and the work integrated along the branch (the drag's energy balance).

use crate::chain::{ContactSet, Geom, Mode};
use crate::profile::{General, Profile};
use crate::report::{ContactLabel, Event, RangeEnd, ScanPoint};
use crate::sampling::flex_and_reversals;
use crate::shape::{shape_from, ShapePoint};
use crate::stepper::{Pt, Stepper};
use crate::surface::Meter;
use crate::watch::{Env, Watch};

/// The first maximum of `|μ|` and what ended the range, once known.
#[derive(Clone, Copy)]
pub(crate) struct RangeTracker {
    pub best: (f64, f64, f64),
    pub end: Option<RangeEnd>,
}

impl RangeTracker {
    /// Takes the point `w` into the range while it is open.
    pub fn see(&mut self, w: &Watch) {
        if self.end.is_none() && w.mu.abs() >= self.best.0 {
            self.best = (w.mu.abs(), w.mu, w.lam);
        }
    }
    /// Closes the range with `end` (the first close counts).
    pub fn close(&mut self, end: RangeEnd) {
        if self.end.is_none() {
            self.end = Some(end);
        }
    }
}

/// The works `m` meters from `a` to `b` on the branch (points of `hist`'s span), `[foot,
/// friction]`: the Hermite-corrected trapezoid, halved with solves at the midpoints until the
/// halves agree with the whole to 1e-11 (its error falls 16-fold per halving: the halves' sum is
/// then extrapolated).
pub(crate) fn meter_between(
    st: &mut dyn Stepper,
    env: &Env,
    m: Meter,
    hist: &[Pt],
    (a, b): (&Pt, &Pt),
    depth: u32,
) -> [f64; 2] {
    let ends = |st: &dyn Stepper, a: &Pt, b: &Pt| {
        let set = st.set();
        metered(m, env, set, (a, st.foot(a.lam).0), (b, st.foot(b.lam).0))
    };
    let whole = ends(&*st, a, b);
    if depth >= 16 || b.lam - a.lam <= 1e-13 * (1.0 + b.lam.abs()) {
        return whole;
    }
    let lam = 0.5 * (a.lam + b.lam);
    // (the walk's newest points may lie past `b`, and where they crowd at an event their
    // polynomial strays inside the span; and the branch may turn fast inside an accepted
    // step. Both refused midpoints of a lying stretch's stick before slip 1224 of the drag
    // property's seed 22, whose halves were then left unrefined: 3.4e-8 of the balance. The
    // span's own ends predict it then, and only a fold or a jump refuses it)
    let Ok(mid) = st
        .correct(lam, hist, true)
        .or_else(|_| st.correct_within(lam, a, b))
    else {
        return whole;
    };
    let (h1, h2) = (ends(&*st, a, &mid), ends(&*st, &mid, b));
    let halves = [h1[0] + h2[0], h1[1] + h2[1]];
    let agree = (0..2).all(|i| (halves[i] - whole[i]).abs() <= 1e-11 * (1.0 + whole[i].abs()));
    if agree {
        return [0, 1].map(|i| halves[i] + (halves[i] - whole[i]) / 15.0);
    }
    let l = meter_between(st, env, m, hist, (a, &mid), depth + 1);
    let r = meter_between(st, env, m, hist, (&mid, b), depth + 1);
    [l[0] + r[0], l[1] + r[1]]
}

/// The rate of the foot's work at the point `p` and its slope in `λ`: `−ΣF_x` (the foot carries
/// minus the total contact force).
fn foot_rate(set: &ContactSet, p: &Pt) -> (f64, f64) {
    let zero = vec![0.0; p.u.len()];
    let du = p.du.as_deref().unwrap_or(&zero);
    let (mut r, mut dr) = (0.0, 0.0);
    for (j, ct) in set.contacts.iter().enumerate() {
        let o = set.offset(j);
        r -= ct.force(p.u[o], p.u[o + 1])[0];
        dr -= ct.force(du[o], du[o + 1])[0];
    }
    (r, dr)
}

/// The rate of the turning support's work at the point `p` and its slope in `λ = θ`: the moment
/// at the foot `m(0)` (the unknowns' first, `ContactSet`), since the clamp holds the slope
/// `π/2 − θ` and `δE = m(0) δθ` for the rod and its support's spring.
fn turn_rate(p: &Pt) -> (f64, f64) {
    (p.u[0], p.du.as_deref().map_or(0.0, |du| du[0]))
}

/// The rate of the work the driving contact `j` of a slip absorbs (`dir·T`, its place moving by
/// `dir·λ` along the surface) at `p` (foot at `xf`) and its slope in `λ`.
fn driver_rate(env: &Env, set: &ContactSet, j: usize, p: &Pt, xf: f64) -> (f64, f64) {
    let zero = vec![0.0; p.u.len()];
    let du = p.du.as_deref().unwrap_or(&zero);
    let dir = env.ground.slide.map_or(1.0, |s| s.dir);
    let ct = &set.contacts[j];
    let o = set.offset(j);
    let f = ct.force(p.u[o], p.u[o + 1]);
    let df = ct.force(du[o], du[o + 1]);
    // the unit tangent along +σ at the contact and its turn per unit arc length, and the rate
    // of the contact point's arc length (a point tip's: its place's, dir; a round tip's: its
    // contact point's, which rolls)
    let disk = ct.tip && set.tip_radius > 0.0;
    let (e, de, rate) = match &ct.geom {
        Geom::Curve { h } => {
            let x = if ct.tip && !disk {
                p.sol.right()[0] + xf
            } else {
                p.w.contacts[j].x
            };
            let (_, d, dd) = h.jet(x);
            let w = (1.0 + d * d).sqrt();
            let kappa = dd / (w * w * w);
            let rate = if disk { w * p.w.contacts[j].dxc } else { dir };
            ([1.0 / w, d / w], [-d / w * kappa, kappa / w], rate)
        }
        Geom::Line { beta, .. } => ([beta.cos(), beta.sin()], [0.0, 0.0], dir),
        _ => return (0.0, 0.0),
    };
    let r = -dir * (f[0] * e[0] + f[1] * e[1]);
    let dr = -dir * (df[0] * e[0] + df[1] * e[1]) - dir * rate * (f[0] * de[0] + f[1] * de[1]);
    // a lying stretch slides as a whole: its friction's work is `T + Q(0)` along it (module
    // `chain`, `Chain::stretch_friction`)
    match p.w.contacts[j].turn {
        [q, dq] if q.is_finite() => (r + dir * q, dr + dir * dq),
        _ => (r, dr),
    }
}

/// The trapezoid with the end-slope correction of `∫ g` over a step of `h` from the values and
/// slopes at its ends (exact for cubics).
fn corrected((ga, da): (f64, f64), (gb, db): (f64, f64), h: f64) -> f64 {
    0.5 * h * (ga + gb) + h * h / 12.0 * (da - db)
}

/// The works of `m` between two points of one branch, `[foot, friction]`: the foot's in a stick,
/// the driving contact's in a slip, and every contact sliding passively in either
/// (`ratio·∫N dq` over its slip coordinate `q`, `dN/dq` from the rates).
fn metered(m: Meter, env: &Env, set: &ContactSet, a: (&Pt, f64), b: (&Pt, f64)) -> [f64; 2] {
    let h = b.0.lam - a.0.lam;
    if h == 0.0 {
        return [0.0, 0.0];
    }
    let mut out = [0.0, 0.0];
    match m {
        Meter::Foot => out[0] = corrected(foot_rate(set, a.0), foot_rate(set, b.0), h),
        Meter::Turn => out[0] = corrected(turn_rate(a.0), turn_rate(b.0), h),
        Meter::Slide => {
            // (a driver numbered past the set, after a lift-off before it: nothing metered)
            let driver = env.ground.slide.map(|s| s.driver);
            if let Some(j) = driver.filter(|&j| j < set.contacts.len()) {
                let (ra, rb) = (
                    driver_rate(env, set, j, a.0, a.1),
                    driver_rate(env, set, j, b.0, b.1),
                );
                out[1] = corrected(ra, rb, h);
            }
        }
    }
    for (k, ct) in set.contacts.iter().enumerate() {
        let Mode::Sliding(ratio) = ct.mode else {
            continue;
        };
        if env.ground.slide.is_some_and(|s| s.driver == k) || !is_surface(ct) {
            continue;
        }
        let (ca, cb) = (&a.0.w.contacts[k], &b.0.w.contacts[k]);
        let hq = cb.slide.q - ca.slide.q;
        // a lying stretch that slides: the part of its friction's work its ratio does not
        // count (module `chain`, `Stretch::capstan`), `∫ W dq`
        let ([wa, ra], [wb, rb]) = (ca.turn, cb.turn);
        if wa.is_finite() && wb.is_finite() {
            let (da, db) = (ra / ca.slide.slip, rb / cb.slide.slip);
            out[1] += if da.is_finite() && db.is_finite() {
                corrected((wa, da), (wb, db), hq)
            } else {
                // (a slip rate of zero at an end: the trapezoid alone)
                0.5 * hq * (wa + wb)
            };
        }
        let end = |c: &crate::watch::ContactForce| (c.normal, c.slide.dnormal / c.slide.slip);
        let (ea, eb) = (end(ca), end(cb));
        out[1] += ratio
            * if ea.1.is_finite() && eb.1.is_finite() {
                corrected(ea, eb, hq)
            } else {
                // a slip rate of zero at an end (the slider halts there, a located `Halt`):
                // `dN/dq` is unbounded, and its `±inf` made the meter infinite (issue 31:
                // the stick work `inf` before slip 1 of 0.001/0.5/2π/3). `∫ N q' dλ` instead,
                // with `q''` constant over the step
                let qq = (cb.slide.slip - ca.slide.slip) / h;
                let g = |c: &crate::watch::ContactForce| {
                    let (n, v) = (c.normal, c.slide.slip);
                    (n * v, c.slide.dnormal * v + n * qq)
                };
                corrected(g(ca), g(cb), h)
            };
    }
    out
}

/// The rates in `λ` of the works `m` meters ([`metered`]) at the point `p` of `set` (foot at
/// `xf`), `[foot, friction]`: the integrands `metered` takes over a step, for a stretch of the
/// branch no solve reaches (a stretch reaching the tip, module `march`).
pub(crate) fn rates(m: Meter, env: &Env, set: &ContactSet, p: &Pt, xf: f64) -> [f64; 2] {
    let mut out = [0.0, 0.0];
    let driver = env.ground.slide.map(|s| s.driver);
    match m {
        Meter::Foot => out[0] = foot_rate(set, p).0,
        Meter::Turn => out[0] = turn_rate(p).0,
        Meter::Slide => {
            if let Some(j) = driver.filter(|&j| j < set.contacts.len()) {
                out[1] = driver_rate(env, set, j, p, xf).0;
            }
        }
    }
    for (k, ct) in set.contacts.iter().enumerate() {
        let Mode::Sliding(ratio) = ct.mode else {
            continue;
        };
        if driver == Some(k) || !is_surface(ct) {
            continue;
        }
        let c = &p.w.contacts[k];
        let v = c.slide.slip;
        if c.turn[0].is_finite() {
            out[1] += c.turn[0] * v;
        }
        out[1] += ratio * c.normal * v;
    }
    out
}

/// Whether a contact touches the surface (a line or a curve).
fn is_surface(ct: &crate::chain::Contact) -> bool {
    matches!(ct.geom, Geom::Line { .. } | Geom::Curve { .. })
}

/// The output point of a branch point.
pub(crate) fn scan_point<P: Profile>(
    p: &Pt,
    set: &ContactSet,
    profile: &P,
    event: Option<Event>,
) -> ScanPoint {
    let w = &p.w;
    let (fx, fy) = (w.force[0], w.force[1]);
    let f = (fx * fx + fy * fy).sqrt();
    let alpha = fx.atan2(-fy);
    let (flex, s_flex, _) = flex_and_reversals(&p.sol, profile);
    let s_c = set
        .contacts
        .iter()
        .position(|c| !c.tip)
        .map(|j| set.s_of(j, &p.u));
    let mu_peak = w
        .contacts
        .iter()
        .map(|c| match c.normal {
            // lift-off: unbounded unless no tangential force is needed
            0.0 if c.tangential == 0.0 => 0.0,
            n => (c.tangential / n).abs(),
        })
        .fold(0.0, f64::max);
    ScanPoint {
        d: p.lam,
        mu: w.mu,
        normal: w.normal,
        mu_peak,
        alpha,
        phi1: p.sol.right()[2],
        f,
        fx,
        fy,
        m_base: p.sol.left()[3],
        flex,
        s_flex,
        y_max: w.y_max,
        contact: ContactLabel::of(set),
        s_c,
        event,
        x_contact: match w.contacts.last() {
            Some(c) if set.tip_radius > 0.0 && set.tip() => Some(c.x),
            _ => None,
        },
    }
}

/// A place in an [`Output`] ([`Output::mark`]).
pub(crate) struct Mark {
    rows: usize,
    shapes: usize,
    gi: usize,
    driver: Option<usize>,
    metered: [f64; 2],
    riders: Vec<(usize, f64)>,
}

/// What a march records: the output points on the grid, filled as the march passes them, and
/// the event points, with their shapes and tip states, and the metered work.
pub(crate) struct Output<'a, P: Profile> {
    pub points: Vec<ScanPoint>,
    pub shapes: Vec<Vec<ShapePoint>>,
    /// The next grid point to emit.
    pub gi: usize,
    pub tips: Vec<[f64; 4]>,
    /// Each output point's contacts (their holds from the modes of its set).
    pub contacts: Vec<Vec<crate::contacts::ContactState>>,
    /// In a slip: the sliding contact's number in the set of the points recorded now (the march
    /// renumbers it where a contact before it lets go), and of each output point.
    pub driver: Option<usize>,
    pub drivers: Vec<Option<usize>>,
    pub metered: [f64; 2],
    /// Where a slip's driver let go: the passive sliders then, held (module `march`).
    pub riders: Vec<(usize, f64)>,
    /// Each row's shape sampled at this many points, if kept.
    pub keep_shapes: Option<usize>,
    /// The rod's profile (flex points of the rows, shapes).
    pub profile: &'a P,
    pub general: &'a General,
}

impl<'a, P: Profile> Output<'a, P> {
    /// An empty record for `rows` rows, starting at grid point `gi`.
    pub fn new(
        rows: usize,
        gi: usize,
        keep_shapes: Option<usize>,
        profile: &'a P,
        general: &'a General,
    ) -> Self {
        Output {
            points: Vec::with_capacity(rows),
            shapes: Vec::new(),
            gi,
            tips: Vec::with_capacity(rows),
            contacts: Vec::with_capacity(rows),
            driver: None,
            drivers: Vec::with_capacity(rows),
            metered: [0.0, 0.0],
            riders: Vec::new(),
            keep_shapes,
            profile,
            general,
        }
    }

    /// What the record holds now, to go back to with [`Output::rewind`].
    pub fn mark(&self) -> Mark {
        Mark {
            rows: self.points.len(),
            shapes: self.shapes.len(),
            gi: self.gi,
            driver: self.driver,
            metered: self.metered,
            riders: self.riders.clone(),
        }
    }

    /// Drops what was recorded after `mark`.
    pub fn rewind(&mut self, mark: Mark) {
        self.points.truncate(mark.rows);
        self.tips.truncate(mark.rows);
        self.contacts.truncate(mark.rows);
        self.drivers.truncate(mark.rows);
        self.shapes.truncate(mark.shapes);
        self.gi = mark.gi;
        self.driver = mark.driver;
        self.metered = mark.metered;
        self.riders = mark.riders;
    }

    /// Records the point `p` of the contact set `set` (with its event, if it is one).
    pub fn push(&mut self, set: &ContactSet, p: &Pt, event: Option<Event>) {
        self.points.push(scan_point(p, set, self.profile, event));
        let zb = p.sol.right();
        self.tips.push([zb[0], zb[1], zb[2], zb[3]]);
        (self.contacts).push(crate::contacts::states(set, &p.w.contacts));
        self.drivers.push(self.driver);
        if let Some(ns) = self.keep_shapes {
            let shape = shape_from(p.sol.clone(), 0.0, self.general.clone());
            self.shapes.push(shape.samples(ns));
        }
    }
}
