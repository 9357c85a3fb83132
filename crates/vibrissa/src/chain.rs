//! The contact set and the rod under it: one abstraction for every scene (a tip stuck on a
//! surface, a side lying on it, a point object touching the side, a frictionless press), solved
//! by shooting segment by segment.
//!
//! Contacts sit at arc lengths `0 < s_1 < … < s_L ≤ 1` (the tip is `s = 1`). Between them the
//! internal force is constant, the resultant of the contact forces beyond; beyond the last one
//! the rod is unloaded (its rest shape). Each contact `j` carries a force `F_j = −N_j n_j +
//! T_j t_j` in a frame fixed when it formed (`n_j` points into the obstacle, `t_j = (−n_y, n_x)`;
//! for the surface `t` points back along it, against the drag), and adds as many unknowns as
//! conditions:
//!
//! ```text
//!     unknowns  u = (m(0); N_j, T_j [, s_j if interior] for each contact)
//!     residual  m(s_L) = 0;  for each contact:
//!       surface, tip:       on the line;                       mode
//!       surface, interior:  on the line;  φ(s_j) = β (+2πk);   mode
//!       point object:       x(s_j) = X,   y(s_j) = Y;          mode
//!     mode: stuck (the tip's place along the line, or the object's material point s_j, fixed),
//!           rolling (along-line position − s_j fixed: no slip at a moving contact point),
//!           frictionless (no tangential force), sliding (T = ratio·N)
//! ```
//!
//! The one-parameter families (module docs of `family` in [`Family`]) move the foot, turn it,
//! or shift the surface along its normal; `λ` enters the conditions and, for a turned foot, the
//! start slope. The Jacobian comes from the segment sensitivities of the shooter by the chain
//! rule; a breakpoint `s_j` moves a segment's end by `F(z(s_j))` (the continuous derivative, exact
//! to the integration tolerance).

use crate::profile::Profile;
use crate::shooter::{End, Shooter};
use crate::surface::disk_on_curve;
use bvp::Solution;
use nalgebra::{DMatrix, DVector};
use std::f64::consts::FRAC_PI_2;
use std::sync::Arc;

/// What a contact touches.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Geom {
    /// The surface line through `p0` (lab frame) inclined by `beta`, shifted along its normal by
    /// the pose's offset `h`.
    Line { p0: [f64; 2], beta: f64 },
    /// A point object at `p` (lab frame).
    Point { p: [f64; 2] },
    /// No obstacle: the tip's slope is held at `phi1` (a single solve's tip condition).
    Slope { phi1: f64 },
    /// A curved surface `y = h(x)` (lab frame), shifted up by the pose's offset `h`.
    Curve { h: Arc<crate::surface::Height> },
}

/// How a contact holds.
#[derive(Clone, Copy, Debug, PartialEq)]
#[allow(dead_code)] // sliding: the drag, next
pub(crate) enum Mode {
    /// Stuck: the tip's along-line coordinate stays at the value, or (point object) the material
    /// point `s` of the rod stays at the object.
    Stuck(f64),
    /// Rolling on the surface without slip: along-line position − `s` stays at the value.
    Rolling(f64),
    /// Frictionless: no tangential force (for a point object: the force is normal to the rod).
    Free,
    /// Sliding with `T = ratio·N`.
    Sliding(f64),
}

impl Mode {
    /// Whether it holds without slip (stuck or rolling): its tangential force is whatever the
    /// equilibrium needs, bounded only by a slip threshold.
    pub fn no_slip(self) -> bool {
        matches!(self, Mode::Stuck(_) | Mode::Rolling(_))
    }
}

/// Whether a contact slides on the surface with a given friction ratio (a passive slider).
pub(crate) fn is_slider(c: &Contact) -> bool {
    matches!(c.mode, Mode::Sliding(_)) && matches!(c.geom, Geom::Line { .. } | Geom::Curve { .. })
}

/// One contact.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Contact {
    /// At the tip (`s = 1`), else at an unknown interior arc length.
    pub tip: bool,
    pub geom: Geom,
    pub mode: Mode,
    /// Unit normal of the force frame, into the obstacle.
    pub n: [f64; 2],
    /// The rod's slope at an interior surface contact (β + kπ); at a point object, its slope
    /// where the contact formed (which side of the rod the object is on).
    pub phi_ref: f64,
}

impl Contact {
    /// The multiple of π the rod's slope keeps against a curved surface's slope angle `th`
    /// there (`|φ − θ − kπ| < π/4`): `φ = θ + kπ` while it lies on the surface, and
    /// `cos(kπ) = ±1` the way it runs along it.
    pub fn kpi(&self, th: f64) -> f64 {
        std::f64::consts::PI * ((self.phi_ref - th) / std::f64::consts::PI).round()
    }

    /// Unit tangent of the force frame, `(−n_y, n_x)`.
    pub fn t(&self) -> [f64; 2] {
        [-self.n[1], self.n[0]]
    }
    /// Unknowns it adds: `N`, `T` and, inside the rod, `s`.
    pub fn unknowns(&self) -> usize {
        if self.tip {
            2
        } else {
            3
        }
    }
    /// The Cartesian force from `(N, T)`.
    pub fn force(&self, nn: f64, tt: f64) -> [f64; 2] {
        let t = self.t();
        [-nn * self.n[0] + tt * t[0], -nn * self.n[1] + tt * t[1]]
    }
    /// The rod's own frame at a point-object contact where its slope is `phi`: the tangent `τ`
    /// (increasing s) and the normal `ν` on the side of the object (the side it was on when the
    /// contact formed, at the slope `phi_ref`).
    pub fn rod_frame(&self, phi: f64) -> ([f64; 2], [f64; 2]) {
        let (sr, cr) = self.phi_ref.sin_cos();
        let side = if self.n[0] * sr - self.n[1] * cr >= 0.0 {
            1.0
        } else {
            -1.0
        };
        let (sp, cp) = phi.sin_cos();
        ([cp, sp], [side * sp, -side * cp])
    }
    /// A surface contact on the line of `surface` (frame: normal up into it, tangent back).
    pub fn on_surface(tip: bool, p0: [f64; 2], beta: f64, mode: Mode, phi_ref: f64) -> Contact {
        Contact {
            tip,
            geom: Geom::Line { p0, beta },
            mode,
            n: [-beta.sin(), beta.cos()],
            phi_ref,
        }
    }
    /// A contact on the curved surface `h` at lab `x` (frame: the local normal and tangent
    /// there; `phi_ref` the rod's slope there if it lies tangent, `θ(x) + kπ`).
    pub fn on_curve(
        tip: bool,
        h: &Arc<crate::surface::Height>,
        x: f64,
        mode: Mode,
        phi_ref: f64,
    ) -> Contact {
        let th = h.angle(x).0;
        Contact {
            tip,
            geom: Geom::Curve { h: h.clone() },
            mode,
            n: [-th.sin(), th.cos()],
            phi_ref,
        }
    }
}

/// The contacts, ordered along the rod (the tip, if touching, last).
#[derive(Clone, Debug, PartialEq, Default)]
pub(crate) struct ContactSet {
    pub contacts: Vec<Contact>,
    /// Radius `r ≥ 0` of the rigid disk the rod's end carries (0: a point tip). A tip contact
    /// on a surface then touches it at `C = P + r·n(x_c)`, `P` the rod's end; see
    /// [`disk_on_curve`](crate::surface::disk_on_curve), [`tip_place`].
    pub tip_radius: f64,
    /// A contact is the inner end of a stretch lying along a curved surface ([`Lying`]).
    pub lying: Option<Lying>,
}

/// A stretch of the rod lying along a curved surface (issue 31), from its contact's arc length
/// `s1` out to `s2`. On the stretch the rod follows the surface without slip: its material point
/// `s` sits where `σ(x) = c + dir·s` (the contact's rolling invariant `c`, `dir` the way it runs
/// along the surface), tangent to it, with the surface's curvature, `κ0(s) + b(s)·m =
/// dir·κ_s(x)`. Where the contact is the last one, the unloaded rest beyond `s2` has `m = 0`, so
/// the outer end sits where `dir·κ_s(x2) = κ0(s2)` (for a straight rod, an inflection of the
/// surface); while the stretch holds without slip its outer end stays there. The inner end `s1`
/// is the contact's unknown arc length, where the loaded rod from the foot arrives on the surface,
/// tangent to it and with its curvature: the set's last condition is that curvature match
/// instead of `m(s1) = 0`. The contact's `(N, T)` are the stretch's resultant (its distributed
/// pressure and the point forces at its ends).
///
/// With contacts beyond the stretch (`beyond > 0`: the tip stuck on the surface, say) the rest
/// beyond is loaded: the outer end `s2` is then the set's last unknown, the segment beyond starts
/// there from the surface's state (the moment continuous), and the curvature match at `s1` is a
/// condition of its own, the fourth of the stretch's contact.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Lying {
    /// Arc length of the outer end (with contacts beyond: where it was when the stretch formed).
    pub s2: f64,
    /// Lab x of the outer end (as `s2`).
    pub x2: f64,
    /// The rolling invariant at which `s2`, `x2` hold: with the rest beyond unloaded the outer
    /// end is where `m = 0`, so a stretch that slides (its invariant moved) has its outer end
    /// found again ([`Stretch::outer_end`]).
    pub c: f64,
    /// How many contacts lie beyond the stretch (the last of the set's contacts).
    pub beyond: usize,
    /// Lab x where the stretch formed: below the full amplitude (the start's growth) the
    /// surface's arc length is taken from there ([`Chain::stretch_sigma`]).
    pub anchor: f64,
}

impl Lying {
    /// Below the full amplitude `amp` (the start's growth): the anchor and the surface's `σ`
    /// there, from which the scaled surface's arc length is integrated (`Chain::stretch_sigma`);
    /// `None` at the full amplitude, where `σ` is the profile's own.
    fn anchor_at(&self, h: &crate::surface::Height, amp: f64) -> Option<(f64, f64)> {
        (amp != 1.0).then(|| (self.anchor, h.sigma(self.anchor).0))
    }
}

/// The lying stretch of a set at a pose: the surface and the rolling invariant that place it.
#[derive(Clone, Copy)]
pub(crate) struct Stretch<'a> {
    h: &'a crate::surface::Height,
    /// The rolling invariant, with the pose's slide: `σ(x) = c + dir·s` on the stretch.
    c: f64,
    /// `+1` where the rod runs along the surface towards `+x`, `−1` towards `−x`.
    dir: f64,
    /// The multiple of π between the rod's slope and the surface's.
    kpi: f64,
    /// The surface's shape amplitude and its shift along y at the pose.
    amp: f64,
    off: f64,
    /// The foot's lab x.
    xf: f64,
    pub s2: f64,
    pub x2: f64,
    /// Below the full amplitude (the start's growth): a lab `x` and the scaled surface's `σ`
    /// there, from which [`Stretch::sigma`] integrates ([`crate::surface::Height::arc_scaled`]).
    anchor: Option<(f64, f64)>,
}

impl Stretch<'_> {
    /// The surface's arc length `σ(x)` and `dσ/dx` at the stretch's amplitude
    /// ([`crate::surface::Height::sigma_scaled_from`] from the anchor, where the shape is scaled).
    fn sigma(&self, x: f64) -> (f64, f64) {
        match self.anchor {
            None => self.h.sigma(x),
            Some((xa, sa)) => self.h.sigma_scaled_from(xa, sa, x, self.amp),
        }
    }

    /// `dσ/dx` at `x` ([`Stretch::sigma`]).
    fn speed(&self, x: f64) -> f64 {
        match self.anchor {
            None => self.h.speed(x),
            Some(_) => self.h.speed_scaled(x, self.amp),
        }
    }

    /// [`Stretch::sigma`], below the full amplitude integrated from a point `known` of it
    /// nearby, `(x0, σ(x0))` (the same function to rounding, with a shorter integral).
    fn sigma_near(&self, x: f64, known: Option<(f64, f64)>) -> (f64, f64) {
        match (self.anchor, known) {
            (Some(_), Some((x0, s0))) => self.h.sigma_scaled_from(x0, s0, x, self.amp),
            _ => self.sigma(x),
        }
    }

    /// Lab x of the material point `s` on the stretch (Newton on `σ(x) = c + dir·s`).
    pub fn x_at(&self, s: f64) -> f64 {
        let target = self.c + self.dir * s;
        let mut x = self.x2 + self.dir * (s - self.s2);
        for _ in 0..50 {
            let (sg, dsg) = self.sigma(x);
            let dx = (sg - target) / dsg;
            x -= dx;
            if dx.abs() <= 4.0 * f64::EPSILON * x.abs().max(1.0) {
                break;
            }
        }
        x
    }

    /// The rod's curvature where it lies at lab `x`: `dir·κ_s(x)`, `κ_s = h''/(1 + h'²)^{3/2}`.
    pub fn kappa(&self, x: f64) -> f64 {
        let (_, d, dd) = self.h.jet_scaled(x, self.amp);
        self.dir * dd / (1.0 + d * d).powf(1.5)
    }

    /// `d/dx` of [`Stretch::kappa`] (central differences: the surfaces give `h''` at most; with
    /// the step 1e-6 the error is below 1e-7 of it for wavelengths down to 0.02).
    pub fn dkappa(&self, x: f64) -> f64 {
        let e = 1e-6;
        (self.kappa(x + e) - self.kappa(x - e)) / (2.0 * e)
    }

    /// `d/d(amp)` of [`Stretch::kappa`] at lab `x`: the surface's shape grows with `amp` at the
    /// start (central differences, step 1e-6).
    pub fn dkappa_damp(&self, x: f64) -> f64 {
        let e = 1e-6;
        let at = |amp: f64| Stretch { amp, ..*self }.kappa(x);
        (at(self.amp + e) - at(self.amp - e)) / (2.0 * e)
    }

    /// The rod's state at `s` on the stretch (foot frame) and its derivative in `s`, for the
    /// profile `p`: `m = (dir·κ_s(x) − κ0(s))/b(s)`.
    pub fn state<P: Profile>(&self, p: &P, s: f64) -> ([f64; 4], [f64; 4]) {
        self.state_x(p, s, self.x_at(s))
    }

    /// [`Stretch::state`] with the lab `x` of `s` given.
    fn state_x<P: Profile>(&self, p: &P, s: f64, x: f64) -> ([f64; 4], [f64; 4]) {
        let (hv, d, _) = self.h.jet_scaled(x, self.amp);
        let phi = d.atan() + self.kpi;
        let (sp, cp) = phi.sin_cos();
        let k = self.kappa(x);
        let (b, k0) = (p.b(s), p.k0(s));
        let (db, dk0) = p.slopes(s);
        let m = (k - k0) / b;
        let dm = (self.dkappa(x) * cp - dk0) / b - (k - k0) * db / (b * b);
        ([x - self.xf, hv + self.off, phi, m], [cp, sp, k, dm])
    }

    /// The outer end where the rest beyond is unloaded: the material point `s2` where the
    /// surface's curvature is the rod's rest curvature, `dir·κ_s(x(s2)) = κ0(s2)` (so `m = 0`
    /// there), found by Newton from the stored place moved with the invariant (for a straight
    /// rest the same lab `x`, an inflection). `None` where Newton does not converge.
    pub fn outer_end<P: Profile>(&self, p: &P) -> Option<(f64, f64)> {
        let mut s = self.dir * (self.sigma(self.x2).0 - self.c);
        for _ in 0..30 {
            let x = self.x_at(s);
            let g = self.kappa(x) - p.k0(s);
            let dxds = self.dir / self.speed(x);
            let dg = self.dkappa(x) * dxds - p.slopes(s).1;
            let ds = g / dg;
            s -= ds;
            if !s.is_finite() {
                return None;
            }
            if ds.abs() <= 1e-15 {
                return Some((s, self.x_at(s)));
            }
        }
        None
    }

    /// The capstan term of a stretch that slides with friction ratio `gmu` (signed: `g·μ`, `g`
    /// the way its material slides along the surface, `+` towards `+σ`) from its inner end `s1`,
    /// the rest beyond unloaded: `q1 = dir·(1 + μ²)·∫ φ'·m'·exp(−gμ(φ(s) − φ(s1))) ds` over the
    /// stretch. With the kinetic friction `gμ·p` against a distributed pressure `p` and the same
    /// ratio at its ends' point forces, the stretch is in equilibrium where its resultant
    /// `(N, T)` (module docs of `chain`, the frame at `s1`) has `T = gμ·N − q1` (docs/model.md,
    /// "A stretch that slides"); on a straight stretch `q1 = 0`. Eight 10-point Gauss panels:
    /// the integrand's parts at the nodes once ([`Capstan`]), for any `gμ` and load beyond.
    pub fn capstan<P: Profile>(&self, p: &P, s1: f64) -> Capstan {
        let st1 = self.state(p, s1);
        let phi1 = st1.0[2];
        let mut nodes = Vec::new();
        if self.s2 - s1 > 0.0 {
            let w = (self.s2 - s1) / 8.0;
            // (each node's x by Newton from the last one's: the correction below 1e-9 is the
            // last, the error after it of its square)
            let (mut sp, mut x) = (s1, st1.0[0] + self.xf);
            // (the last `(x, σ(x))` evaluated: below the full amplitude the next `σ` is
            // integrated from there)
            let mut known = None;
            for i in 0..8 {
                let a = s1 + w * i as f64;
                for (s, wt) in crate::gauss::nodes10(a, a + w) {
                    let target = self.c + self.dir * s;
                    x += self.dir * (s - sp) / self.speed(x);
                    for _ in 0..50 {
                        let (sg, dsg) = self.sigma_near(x, known);
                        known = Some((x, sg));
                        let dx = (sg - target) / dsg;
                        x -= dx;
                        if dx.abs() <= 1e-9 {
                            break;
                        }
                    }
                    sp = s;
                    let (z, dz) = self.state_x(p, s, x);
                    nodes.push((wt * dz[2] * dz[3], z[2] - phi1));
                }
            }
        }
        let frame = |x: f64| {
            let (st, ct) = self.h.angle_scaled(x, self.amp).0.sin_cos();
            [ct, st, -st, ct]
        };
        let (f1, f2) = (frame(st1.0[0] + self.xf), frame(self.x2));
        let st2 = self.state(p, self.s2);
        let turn = st2.0[2] - phi1;
        Capstan {
            dir: self.dir,
            nodes,
            ends: (f1, f2, turn),
            bend: [st2.1[2], st2.1[3]],
        }
    }
}

/// The capstan term of a stretch from its inner end ([`Stretch::capstan`]): the integrand's
/// parts at the quadrature's nodes and the surface's frames at the ends.
pub(crate) struct Capstan {
    dir: f64,
    /// `(weight·φ'·m', φ(s) − φ(s1))` at each node.
    nodes: Vec<(f64, f64)>,
    /// `[e, n]` (the surface's tangent towards `+x` and its normal) at the inner and the outer
    /// end, and the stretch's turn `φ(s2) − φ(s1)`.
    ends: ([f64; 4], [f64; 4], f64),
    /// `φ'` and `m'` at the outer end.
    bend: [f64; 2],
}

/// The friction of a lying stretch at a point ([`Chain::stretch_friction`]).
pub(crate) struct StretchFriction {
    /// The friction ratio it needs, or slides with.
    pub mu: f64,
    /// Where it moves: the part `W` of its friction's work its ratio does not count, and its
    /// rate along the branch (NaN elsewhere).
    pub turn: [f64; 2],
    /// Where asked for: its balance sliding with the given ratio, and its slope in the ratio.
    pub kinetic_balance: Option<(f64, f64)>,
}

impl Capstan {
    /// The friction ratio the stretch needs to hold with its resultant `(n, t)`: the `gμ`
    /// (signed, `μ ≥ 0`) at which the stretch sliding with that ratio balances it, `t = gμ·n −
    /// q1(gμ)` ([`Stretch::capstan`]; the way `g` is that of `t + q1(0)`, the force friction
    /// must take up), by the fixed point `μ = g·(t + q1(gμ))/n` (`q1` changes with `μ` by the
    /// stretch's turn, below 0.03 rad on the texture grid's corrugations, so each iteration
    /// gains about two digits). Where the stretch has no length this is `t/n`. With a load `fb`
    /// beyond it, `q1` has its [`Capstan::q`]. With `q1(0)`, the part of the
    /// resultant that the surface's curvature (and the load beyond) takes up without friction.
    /// NaN where it does not converge in 60 iterations.
    pub fn friction_ratio(&self, (n, t): (f64, f64), fb: [f64; 2]) -> (f64, f64) {
        let q = |gmu: f64| self.q(gmu, fb);
        let q0 = q(0.0);
        let g = (t + q0).signum();
        let mut mu = g * (t + q0) / n;
        for _ in 0..60 {
            let next = g * (t + q(g * mu)) / n;
            let done = (next - mu).abs() <= 4.0 * f64::EPSILON * next.abs().max(1e-3);
            mu = next;
            if done {
                return (g * mu, q0);
            }
        }
        // the fixed point contracts by |dq1/d(gμ)|/n, which a load beyond the stretch larger
        // than its own resultant makes exceed 1 (a tip at N = 0.055 beyond a stretch at
        // N = 0.012): the balance `t − r·n + q1(r) = 0` by secant steps in `r = gμ` instead
        let balance = |r: f64| self.balance((n, t), fb, r);
        let mut r0 = g * (t + q0) / n;
        let mut r1 = r0 + 1e-6 * (1.0 + r0.abs());
        let (mut f0, mut f1) = (balance(r0), balance(r1));
        for _ in 0..60 {
            let r2 = r1 - f1 * (r1 - r0) / (f1 - f0);
            if !r2.is_finite() {
                break;
            }
            if (r2 - r1).abs() <= 4.0 * f64::EPSILON * r2.abs().max(1e-3) {
                return (r2, q0);
            }
            (r0, f0) = (r1, f1);
            (r1, f1) = (r2, balance(r2));
        }
        (f64::NAN, q0)
    }

    /// The balance `t − r·n + Q(r)` of the stretch with its resultant `(n, t)` sliding with the
    /// friction ratio `r` (`Q` = `q1` with the load `fb` beyond, [`Capstan::q`]): zero at the
    /// ratio it needs ([`Capstan::friction_ratio`]), and defined where that ratio is not (no
    /// ratio balances a stretch whose normal force falls towards zero while the surface's
    /// curvature takes up a part of its resultant).
    pub fn balance(&self, (n, t): (f64, f64), fb: [f64; 2], r: f64) -> f64 {
        t - r * n + self.q(r, fb)
    }

    /// [`Capstan::balance`] and its slope in `r` (central differences, step 1e-6).
    pub fn balance_slope(&self, nt: (f64, f64), fb: [f64; 2], r: f64) -> (f64, f64) {
        let e = 1e-6;
        let dq = (self.q(r + e, fb) - self.q(r - e, fb)) / (2.0 * e);
        (self.balance(nt, fb, r), dq - nt.0)
    }

    /// `Q(gμ)`: `q1(gμ) = dir·(1 + μ²)·∫ φ'·m'·exp(−gμ(φ(s) − φ(s1))) ds` and, with the force
    /// `fb` (lab) of contacts beyond the stretch on the rod there, its load's part
    /// `(fb·e2 − gμ fb·n2)·exp(−gμ(φ(s2) − φ(s1))) − fb·e1 + gμ fb·n1` (linear in `fb`, 0
    /// without a load; docs/model.md, "A stretch that slides"). The balance of a stretch
    /// sliding with that ratio is `T − gμ·N + Q(gμ) = 0`.
    pub fn q(&self, gmu: f64, fb: [f64; 2]) -> f64 {
        let sum: f64 = self
            .nodes
            .iter()
            .map(|&(wa, dphi)| wa * (-gmu * dphi).exp())
            .sum();
        let q1 = self.dir * (1.0 + gmu * gmu) * sum;
        if fb == [0.0, 0.0] {
            return q1;
        }
        let (f1, f2, turn) = self.ends;
        let dot = |f: &[f64; 4], k: usize| fb[0] * f[k] + fb[1] * f[k + 1];
        q1 + (dot(&f2, 0) - gmu * dot(&f2, 2)) * (-gmu * turn).exp() - dot(&f1, 0)
            + gmu * dot(&f1, 2)
    }

    /// `∂Q/∂s2` ([`Capstan::q`]) with the stretch's invariant held, where contacts beyond
    /// make the outer end an unknown: the integral's end, the turn in the exponential
    /// (`φ' = dir·κ_s` there) and the outer end's frame, which turns with the surface
    /// (`de/ds = φ'·n`, `dn/ds = −φ'·e`).
    pub fn q_s2(&self, gmu: f64, fb: [f64; 2]) -> f64 {
        let [k2, m2] = self.bend;
        let (_, f2, turn) = self.ends;
        let e2 = (-gmu * turn).exp();
        let dot = |k: usize| fb[0] * f2[k] + fb[1] * f2[k + 1];
        let b2 = (dot(0) - gmu * dot(2)) * e2;
        let c = self.dir * (1.0 + gmu * gmu);
        c * k2 * m2 * e2 + k2 * e2 * (dot(2) + gmu * dot(0)) - gmu * k2 * b2
    }
}

impl ContactSet {
    /// The contacts `contacts` of a point tip.
    pub fn of(contacts: Vec<Contact>) -> ContactSet {
        ContactSet {
            contacts,
            tip_radius: 0.0,
            lying: None,
        }
    }
    /// Number of unknowns.
    pub fn n(&self) -> usize {
        let outer = self.lying.is_some_and(|l| l.beyond > 0);
        1 + self.contacts.iter().map(Contact::unknowns).sum::<usize>() + usize::from(outer)
    }
    /// The contact that is the inner end of the lying stretch, if the set lies.
    pub fn lain(&self) -> Option<usize> {
        let l = self.lying?;
        self.contacts.len().checked_sub(1 + l.beyond)
    }
    /// The lying stretch's outer end at `u` (NaN where the set does not lie).
    pub fn s2_of(&self, u: &[f64]) -> f64 {
        match self.lying {
            Some(l) if l.beyond > 0 => u[self.n() - 1],
            Some(l) => l.s2,
            None => f64::NAN,
        }
    }
    /// Offset of contact `j`'s unknowns `(N, T[, s])` in `u`.
    pub fn offset(&self, j: usize) -> usize {
        1 + self.contacts[..j]
            .iter()
            .map(Contact::unknowns)
            .sum::<usize>()
    }
    /// Arc length of contact `j` at `u`.
    pub fn s_of(&self, j: usize, u: &[f64]) -> f64 {
        if self.contacts[j].tip {
            1.0
        } else {
            u[self.offset(j) + 2]
        }
    }
    /// Whether the tip touches.
    pub fn tip(&self) -> bool {
        self.contacts.last().is_some_and(|c| c.tip)
    }
    /// Whether the tip alone touches a surface (the paper's tip-only contact state, label `tip`).
    pub fn tip_only(&self) -> bool {
        matches!(
            self.contacts[..],
            [Contact {
                tip: true,
                geom: Geom::Line { .. } | Geom::Slope { .. } | Geom::Curve { .. },
                ..
            }]
        )
    }
    /// The label of the state: `tip`, `side`, `tip+side`, `point`, `stretch` (a lying stretch's
    /// inner end), … in order along the rod.
    pub fn label(&self) -> String {
        if self.contacts.is_empty() {
            return "none".into();
        }
        let lain = self.lain();
        self.contacts
            .iter()
            .enumerate()
            .map(|(j, c)| match (&c.geom, c.tip) {
                _ if Some(j) == lain => "stretch",
                (Geom::Line { .. } | Geom::Slope { .. } | Geom::Curve { .. }, true) => "tip",
                (Geom::Line { .. } | Geom::Slope { .. } | Geom::Curve { .. }, false) => "side",
                (Geom::Point { .. }, _) => "point",
            })
            .collect::<Vec<_>>()
            .join("+")
    }
}

/// Where the foot is and how the surface sits at a family parameter `λ`: foot at `(xf, 0)`,
/// turned clockwise by `theta` (`φ(0) = π/2 − θ + c·m(0)`), the surface line shifted along its
/// normal by `h` (the scene's surface at `h = 0`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Pose {
    pub xf: f64,
    pub theta: f64,
    pub h: f64,
    /// Offset of a held tip slope (a single solve's slope condition `φ(1) = φ1 + phi`).
    pub phi: f64,
    /// How far a stuck surface contact's anchor has moved along the surface (a slip in progress).
    pub slide: f64,
    /// How much of a curved surface's shape is flattened away (0: the profile itself; 1: its
    /// straight trend; the start grows the shape from the pressed straight surface).
    pub flat: f64,
}

/// A one-parameter family of scenes: what `λ` moves.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Family {
    /// The foot dragged: `xf = λ` (the stiction scan; `λ = d`).
    Drag,
    /// The surface pressed down from the offset `h0`: `h = h0 − λ` (the start; loading at a
    /// fixed force angle).
    Press { h0: f64 },
    /// The foot turned: `θ = λ` (whisking against an object).
    Turn,
    /// The held tip slope moved: `φ(1) = φ1 + λ` (a single solve's family).
    Slope,
    /// Nothing moves with λ (a fixed scene; a homotopy of the rod itself sets the shooter).
    Fixed(Pose),
    /// The foot held at `xf`, its support turned by `theta`, while the contact `driver` slides
    /// along the surface by `dir·λ` (a slip: the anchor of a stuck tip, or the rolling invariant
    /// of a side, moves by that much in arc length); the other contacts keep their modes.
    Slide {
        xf: f64,
        theta: f64,
        dir: f64,
        driver: usize,
    },
    /// A curved surface's shape grown from its straight trend (`λ = 0`, lifted by `off0`) to
    /// itself lifted by `off1` (`λ = 1`): `flat = 1 − λ`, `h = off1 + (1 − λ)·(off0 − off1)`
    /// (the start grows it at the scene's height, `off1 = 0`, or at a lighter press, `off1 =
    /// off0`, and then presses the rod down onto it: module `ground`).
    Grow { off0: f64, off1: f64 },
}

impl Family {
    /// Whether the pose's slide moves contact `k` (a slip moves its driver only).
    pub fn moves(&self, k: usize) -> bool {
        match *self {
            Family::Slide { driver, .. } => driver == k,
            _ => true,
        }
    }
    /// The pose at `λ` and its derivative in `λ`.
    pub fn pose(&self, lam: f64) -> (Pose, Pose) {
        let z = Pose::default();
        match *self {
            Family::Drag => (Pose { xf: lam, ..z }, Pose { xf: 1.0, ..z }),
            Family::Press { h0 } => (Pose { h: h0 - lam, ..z }, Pose { h: -1.0, ..z }),
            Family::Turn => (Pose { theta: lam, ..z }, Pose { theta: 1.0, ..z }),
            Family::Slope => (Pose { phi: lam, ..z }, Pose { phi: 1.0, ..z }),
            Family::Fixed(p) => (p, z),
            Family::Slide { xf, theta, dir, .. } => (
                Pose {
                    xf,
                    theta,
                    slide: dir * lam,
                    ..z
                },
                Pose { slide: dir, ..z },
            ),
            Family::Grow { off0, off1 } => (
                Pose {
                    h: off1 + (1.0 - lam) * (off0 - off1),
                    flat: 1.0 - lam,
                    ..z
                },
                Pose {
                    h: -(off0 - off1),
                    flat: -1.0,
                    ..z
                },
            ),
        }
    }
}

/// Why an evaluation has no value.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum EvalError {
    /// The contacts' arc lengths are out of order or outside `(0, 1]`.
    Order,
    /// Not finite.
    NonFinite,
}

impl std::fmt::Display for EvalError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            EvalError::Order => "the contacts' arc lengths leave their order in (0, 1]",
            EvalError::NonFinite => "its values are not finite",
        })
    }
}

/// Residual, and on request its Jacobians, of one contact set at `(u, λ)`.
#[derive(Clone, Debug)]
pub(crate) struct Eval {
    pub r: DVector<f64>,
    /// `∂R/∂u` (n × n).
    pub jac: Option<DMatrix<f64>>,
    /// `∂R/∂λ`.
    pub r_lam: Option<DVector<f64>>,
    /// Largest scaled step error of the loaded segments (≤ 1: within tolerance).
    pub err: f64,
}

/// A contact set and the rod under it, for one family.
#[derive(Clone, Debug)]
pub(crate) struct Chain<P: Profile> {
    pub sh: Shooter<P>,
    pub set: ContactSet,
    pub family: Family,
    /// The breakpoints of the last evaluation.
    bps: Vec<f64>,
    /// The last evaluation with sensitivities: `∂z(s_k)/∂(u, λ)` at each breakpoint (4 × (n + 1)).
    zs: Vec<DMatrix<f64>>,
    /// The unknowns and `λ` of the last evaluation (the shooter's paths are of that state).
    shot: (Vec<f64>, f64),
    /// The unloaded rest beyond the last contact, where its segment is new, is laid out on its
    /// span ([`Shooter::ensure_segment_on`]) rather than with the first segment's count of
    /// steps: the scan. Beyond the long rat preset's side at s ≈ 0.95 that is 2 steps where
    /// the count was 22 (its rest's shots were 8 % of the scan). The drag's marches keep the
    /// count: the rest's shape decides their touchdowns, and their paths through trapped pairs
    /// turn on rounding (docs/performance.md, "The rat presets under 3×").
    pub lean_rest: bool,
}

/// How far past the tip a contact's arc length may go inside a solve (see
/// [`Chain::breakpoints`]).
pub(crate) const OVERSHOOT: f64 = 0.05;

/// The Jacobian's rows and `∂R/∂λ`, where they are asked for.
type Rows<'a> = (Option<&'a mut DMatrix<f64>>, Option<&'a mut DVector<f64>>);

/// The state at a breakpoint and its sensitivities (4 rows × n + 1 columns; the last is λ).
#[derive(Clone, Debug)]
struct Sens {
    z: [f64; 4],
    d: DMatrix<f64>,
}

impl<P: Profile> Chain<P> {
    /// A chain of `set` on the shooter `sh` in `family`.
    pub fn new(sh: Shooter<P>, set: ContactSet, family: Family) -> Self {
        Chain {
            sh,
            set,
            family,
            bps: Vec::new(),
            zs: Vec::new(),
            shot: (Vec::new(), f64::NAN),
            lean_rest: false,
        }
    }

    /// The same chain with [`Chain::lean_rest`].
    pub fn with_lean_rest(mut self) -> Self {
        self.lean_rest = true;
        self
    }

    /// The sorted breakpoints `s_1 < … < s_L` at `u`, or `Order`. A contact may pass the tip by
    /// a little ([`OVERSHOOT`]): the rod continued beyond it, so that events at the tip (a lying
    /// part peeling back, an object slipping off) are bracketed by solves.
    fn breakpoints(&self, u: &[f64]) -> Result<Vec<f64>, EvalError> {
        let mut prev = 0.0;
        let mut out = Vec::with_capacity(self.set.contacts.len());
        for j in 0..self.set.contacts.len() {
            let s = self.set.s_of(j, u);
            if !(s > prev && s <= 1.0 + OVERSHOOT) {
                return Err(EvalError::Order);
            }
            out.push(s);
            prev = s;
        }
        // a lying stretch with contacts beyond: its outer end before them (and past its inner
        // end, but for the solves beyond its peel-up that bracket it)
        if let Some(j) = self.set.lain().filter(|&j| j + 1 < out.len()) {
            let s2 = self.set.s2_of(u);
            if !(s2 > out[j].min(1.0) - OVERSHOOT && s2 < out[j + 1]) {
                return Err(EvalError::Order);
            }
        }
        Ok(out)
    }

    /// Residual and, with `var`, `∂R/∂u` and `∂R/∂λ` at `(u, λ)`.
    pub fn eval(&mut self, u: &[f64], lam: f64, var: bool) -> Result<Eval, EvalError> {
        let (pose, dpose) = self.family.pose(lam);
        let set = &self.set;
        let n = set.n();
        let nc = n + 1; // columns: u, then λ
                        // (a shot that fails part way leaves paths of no state)
        self.shot.1 = f64::NAN;
        let bps = self.breakpoints(u)?;
        let lain = set.lain();
        self.bps.clone_from(&bps);
        if var {
            self.zs.clear();
        }
        let c = self.sh.compliance;
        let m0 = u[0];
        // forces and their resultants beyond each breakpoint
        let forces: Vec<[f64; 2]> = set
            .contacts
            .iter()
            .enumerate()
            .map(|(j, ct)| {
                let o = set.offset(j);
                ct.force(u[o], u[o + 1])
            })
            .collect();
        let mut r = DVector::zeros(n);
        let mut jac = var.then(|| DMatrix::zeros(n, n));
        let mut rl = var.then(|| DVector::zeros(n));
        // the start and its sensitivities
        let z0 = [0.0, 0.0, FRAC_PI_2 - pose.theta + c * m0, m0];
        let mut cur = Sens {
            z: z0,
            d: DMatrix::zeros(4, if var { nc } else { 0 }),
        };
        if var {
            cur.d[(2, 0)] = c;
            cur.d[(3, 0)] = 1.0;
            cur.d[(2, n)] = -dpose.theta;
        }
        let mut err: f64 = 0.0;
        let mut a = 0.0;
        let mut row = 1;
        for (k, &b) in bps.iter().enumerate() {
            // the force on segment k: the contacts from k on
            let mut g = [0.0; 2];
            for f in &forces[k..] {
                g[0] += f[0];
                g[1] += f[1];
            }
            let first = k == 0 && dpose.theta == 0.0;
            let dirs: &[[f64; 2]] = if first {
                &[[c, 1.0]]
            } else {
                &[[1.0, 0.0], [0.0, 1.0]]
            };
            let ends = self.moving_ends(k);
            let shot = self.sh.shoot_ends(k, (a, b), cur.z, dirs, g, var, ends);
            err = err.max(shot.err);
            if !shot.z.iter().all(|v| v.is_finite()) {
                return Err(EvalError::NonFinite);
            }
            let next = if var {
                self.carry(k, &cur, &shot, first, u)
            } else {
                DMatrix::zeros(4, 0)
            };
            cur = Sens { z: shot.z, d: next };
            if var {
                self.zs.push(cur.d.clone());
            }
            // the contact's conditions
            let rows = (jac.as_mut(), rl.as_mut());
            row = self.conditions_of(k, u, (&pose, &dpose), &cur, (&mut r, rows), row);
            a = b;
            if Some(k) == lain && k + 1 < bps.len() {
                let rows = (jac.as_mut(), rl.as_mut());
                cur = self.across(k, u, (&pose, &dpose), &cur, (&mut r, rows), row)?;
                row += 1;
                a = set.s2_of(u);
            }
        }
        // the free end of the loaded part: m(s_L) = 0 (with no contact: m(1) = 0 on the rest shape)
        if bps.is_empty() {
            let shot = self
                .sh
                .shoot(0, 0.0, 1.0, cur.z, &[[c, 1.0]], [0.0, 0.0], var);
            err = err.max(shot.err);
            if var {
                let mut d = DMatrix::zeros(4, nc);
                for i in 0..4 {
                    d[(i, 0)] = shot.col[0][i];
                }
                cur = Sens { z: shot.z, d };
            } else {
                cur.z = shot.z;
            }
        }
        match (lain, bps.last()) {
            // a lying stretch beyond the last contact, the rest beyond it unloaded: the rod
            // arrives with the surface's curvature instead
            (Some(k), Some(&s1)) if k + 1 == bps.len() => {
                let st = self.stretch_at(&pose, u).ok_or(EvalError::NonFinite)?;
                let rows = (jac.as_mut(), rl.as_mut());
                self.match_row(&st, (s1, k), (&pose, &dpose), &cur, (&mut r, rows), 0);
            }
            _ => {
                r[0] = cur.z[3];
                if let (Some(j), Some(l)) = (jac.as_mut(), rl.as_mut()) {
                    for col in 0..n {
                        j[(0, col)] = cur.d[(3, col)];
                    }
                    l[0] = cur.d[(3, n)];
                }
            }
        }
        // a round tip carries the moment of its contact force about its centre: m(1) = r·T_loc
        if let Some(jt) = self.disk_tip() {
            let ct = &set.contacts[jt];
            let o = set.offset(jt);
            let Some((mv, dpx, down, dlam)) =
                disk_moment(ct, set.tip_radius, &cur.z, &u[o..o + 2], &pose, &dpose)
            else {
                return Err(EvalError::NonFinite);
            };
            r[0] -= mv;
            if let (Some(j), Some(l)) = (jac.as_mut(), rl.as_mut()) {
                for col in 0..n {
                    j[(0, col)] -= dpx * cur.d[(0, col)];
                }
                j[(0, o)] -= down[0];
                j[(0, o + 1)] -= down[1];
                l[0] -= dpx * cur.d[(0, n)] + dlam;
            }
        }
        if !r.iter().all(|v| v.is_finite()) {
            return Err(EvalError::NonFinite);
        }
        self.shot.0.clear();
        self.shot.0.extend_from_slice(u);
        self.shot.1 = lam;
        self.relay(&pose, u);
        Ok(Eval {
            r,
            jac,
            r_lam: rl,
            err,
        })
    }

    /// The ends of segment `k` that move with the unknowns: its end unless the tip's, its start
    /// unless the foot's or the tip's (a contact's arc length, or a lying stretch's outer end).
    fn moving_ends(&self, k: usize) -> &'static [End] {
        let set = &self.set;
        let stop = !set.contacts[k].tip;
        let start = k > 0 && !set.contacts[k - 1].tip;
        match (stop, start) {
            (true, true) => &[End::Stop, End::Start],
            (true, false) => &[End::Stop],
            (false, true) => &[End::Start],
            (false, false) => &[],
        }
    }

    /// The sensitivities of the end state of segment `k` (the shot `shot` from the start `cur`,
    /// with its moving ends' columns; `first`: the foot's segment with its compliance folded
    /// into the first column) with respect to the unknowns and `λ`.
    fn carry(
        &self,
        k: usize,
        cur: &Sens,
        shot: &crate::shooter::SegShot,
        first: bool,
        u: &[f64],
    ) -> DMatrix<f64> {
        let set = &self.set;
        let nc = set.n() + 1;
        let mut d = DMatrix::zeros(4, nc);
        // start position carried over; start (φ, m) through the columns
        for col in 0..nc {
            d[(0, col)] += cur.d[(0, col)];
            d[(1, col)] += cur.d[(1, col)];
            if first {
                let w = cur.d[(3, col)];
                for i in 0..4 {
                    d[(i, col)] += shot.col[0][i] * w;
                }
            } else {
                let (wp, wm) = (cur.d[(2, col)], cur.d[(3, col)]);
                for i in 0..4 {
                    d[(i, col)] += shot.col[0][i] * wp + shot.col[1][i] * wm;
                }
            }
        }
        // the force columns: contacts j ≥ k
        let (qx, qy) = (shot.ncol - shot.nend - 2, shot.ncol - shot.nend - 1);
        for j in k..set.contacts.len() {
            let ct = &set.contacts[j];
            let o = set.offset(j);
            let t = ct.t();
            for (col, dfx, dfy) in [(o, -ct.n[0], -ct.n[1]), (o + 1, t[0], t[1])] {
                for i in 0..4 {
                    d[(i, col)] += shot.col[qx][i] * dfx + shot.col[qy][i] * dfy;
                }
            }
        }
        // moving ends: the shot's own columns for them (`Shooter::shoot_ends`), the exact
        // derivatives of the discrete end state with the mesh laid on the moved segment
        for (e, end) in self.moving_ends(k).iter().enumerate() {
            let col = match end {
                End::Stop => set.offset(k) + 2,
                // (beyond a lying stretch the segment starts at its outer end, the last unknown)
                End::Start if set.lain() == Some(k - 1) => u.len() - 1,
                End::Start => set.offset(k - 1) + 2,
            };
            let q = shot.ncol - shot.nend + e;
            for i in 0..4 {
                d[(i, col)] += shot.col[q][i];
            }
        }
        d
    }

    /// Across the lying stretch of contact `k` with contacts beyond it: its curvature match at its
    /// inner end (the rod's state there `cur`) in row `row`, and the state where the segment
    /// beyond starts, at its outer end on the surface (`s2`, the last unknown), with its
    /// sensitivities.
    fn across(
        &self,
        k: usize,
        u: &[f64],
        (pose, dpose): (&Pose, &Pose),
        cur: &Sens,
        rows: (&mut DVector<f64>, Rows<'_>),
        row: usize,
    ) -> Result<Sens, EvalError> {
        let st = self.stretch_at(pose, u).ok_or(EvalError::NonFinite)?;
        self.match_row(&st, (self.bps[k], k), (pose, dpose), cur, rows, row);
        let p = &self.sh.profile;
        let (z2, dz2) = st.state(p, st.s2);
        let n = self.set.n();
        let mut d = DMatrix::zeros(4, if cur.d.ncols() > 0 { n + 1 } else { 0 });
        if d.ncols() > 0 {
            for i in 0..4 {
                d[(i, n - 1)] = dz2[i];
            }
            // (the foot's place, and the surface's lift as the start grows the texture)
            d[(0, n)] = -dpose.xf;
            d[(1, n)] = dpose.h;
            // a stretch that slides moves the outer end's place with its invariant `c`: a
            // slip's driver by the slide, a passive slider with its inner end
            // (`c = σ(x1) − dir·s1`); `∂z2/∂c` by central differences
            let slides =
                is_slider(&self.set.contacts[k]) || matches!(self.set.contacts[k].mode, Mode::Free);
            let moved = self.family.moves(k) && dpose.slide != 0.0;
            if slides || moved {
                let e = 1e-6;
                let at = |c: f64| {
                    let m = Stretch { c, ..st };
                    m.state(p, st.s2).0
                };
                let (a, b) = (at(st.c + e), at(st.c - e));
                let dz: [f64; 4] = std::array::from_fn(|i| (a[i] - b[i]) / (2.0 * e));
                if slides {
                    let Geom::Curve { h } = &self.set.contacts[k].geom else {
                        return Err(EvalError::NonFinite);
                    };
                    let dsg = self.stretch_sigma(h, cur.z[0] + pose.xf, st.amp).1;
                    let o = self.set.offset(k) + 2;
                    for i in 0..4 {
                        for col in 0..=n {
                            let dx = cur.d[(0, col)] + if col == n { dpose.xf } else { 0.0 };
                            d[(i, col)] += dz[i] * dsg * dx;
                        }
                        d[(i, o)] -= dz[i] * st.dir;
                    }
                } else {
                    for i in 0..4 {
                        d[(i, n)] += dz[i] * dpose.slide;
                    }
                }
            }
            if dpose.flat != 0.0 {
                // (the start grows the shape: the outer end's state moves with the amplitude,
                // `1 − flat`, at the inner end's place, the invariant with the scaled arc
                // length there; central differences)
                let Geom::Curve { h } = &self.set.contacts[k].geom else {
                    return Err(EvalError::NonFinite);
                };
                let (s1, x1) = (self.bps[k], cur.z[0] + pose.xf);
                let za = |a: f64| -> Result<[f64; 4], EvalError> {
                    let m = self.stretch_scaled(h, pose, u, (x1, s1, st.dir), a);
                    Ok(m.ok_or(EvalError::NonFinite)?.state(p, st.s2).0)
                };
                let e = 1e-6;
                let (a, b) = (za(st.amp + e)?, za(st.amp - e)?);
                for i in 0..4 {
                    d[(i, n)] -= (a[i] - b[i]) / (2.0 * e) * dpose.flat;
                }
            }
        }
        Ok(Sens { z: z2, d })
    }

    /// A stretch that slides with the friction ratio `ratio` from its inner end `s1` at lab `x1`
    /// (contact `k`): its friction row `T − ratio·N = 0` becomes the balance
    /// `T − ratio·N + Q(ratio) = 0` ([`Stretch::capstan`], with a load beyond it its
    /// [`Capstan::q`]), with the invariant `c = σ(x1) − dir·s1` where its inner end is
    /// (it slides). `Q` moves with `s1` and `c` (central differences, step 1e-6) and a loaded
    /// outer end `s2` ([`Capstan::q_s2`]), `c` with `x1` and `s1`, and `Q` linearly with the
    /// forces of the contacts beyond.
    fn capstan_row(
        &self,
        k: usize,
        (u, s1, x1, ratio): (&[f64], f64, f64, f64),
        (pose, dpose): (&Pose, &Pose),
        cur: &Sens,
        (r, (jac, rl)): (&mut DVector<f64>, Rows<'_>),
        row: usize,
    ) -> Result<(), EvalError> {
        let (Some(ly), Geom::Curve { h }) = (self.set.lying, &self.set.contacts[k].geom) else {
            return Err(EvalError::NonFinite);
        };
        let p = &self.sh.profile;
        let set = &self.set;
        let loaded = ly.beyond > 0;
        let dir = self.stretch_dir(h, ly.x2, 1.0 - pose.flat);
        let fb = self.force_from(u, k + 1);
        let cap = |s1: f64, s2: f64, c: f64| -> Result<Capstan, EvalError> {
            let st = self.stretch_from(pose, u, c).ok_or(EvalError::NonFinite)?;
            let st = if loaded {
                Stretch {
                    s2,
                    x2: st.x_at(s2),
                    ..st
                }
            } else {
                st
            };
            Ok(st.capstan(p, s1))
        };
        let q = |s1: f64, s2: f64, c: f64, fb: [f64; 2]| -> Result<f64, EvalError> {
            Ok(cap(s1, s2, c)?.q(ratio, fb))
        };
        let amp = 1.0 - pose.flat;
        let (sg, dsg) = self.stretch_sigma(h, x1, amp);
        let c = sg - dir * s1;
        let s2 = set.s2_of(u);
        let here = cap(s1, s2, c)?;
        r[row] += here.q(ratio, fb);
        if let (Some(j), Some(l)) = (jac, rl) {
            let e = 1e-6;
            // (in `s1` by differences too: where the stretch shrinks to nothing, `Q` has a
            // kink there, and the one-sided derivative stalled Newton in a slide)
            let qs = (q(s1 + e, s2, c, fb)? - q(s1 - e, s2, c, fb)?) / (2.0 * e);
            let q2 = here.q_s2(ratio, fb);
            let qc = (q(s1, s2, c + e, fb)? - q(s1, s2, c - e, fb)?) / (2.0 * e);
            let n = set.n();
            for col in 0..n {
                j[(row, col)] += qc * dsg * cur.d[(0, col)];
            }
            j[(row, set.offset(k) + 2)] += qs - dir * qc;
            l[row] += qc * dsg * (cur.d[(0, n)] + dpose.xf);
            if dpose.flat != 0.0 {
                // (the start grows the shape: `Q` moves with the amplitude at the inner end's
                // place, the invariant with the scaled arc length there; the amplitude is
                // `1 − flat`)
                let qa = |a: f64| -> Result<f64, EvalError> {
                    let st = self.stretch_scaled(h, pose, u, (x1, s1, dir), a);
                    Ok(st.ok_or(EvalError::NonFinite)?.capstan(p, s1).q(ratio, fb))
                };
                l[row] -= (qa(amp + e)? - qa(amp - e)?) / (2.0 * e) * dpose.flat;
            }
            if loaded {
                j[(row, n - 1)] += q2;
                // (linear in the forces beyond)
                let q0 = here.q(ratio, [0.0; 2]);
                for (m, ct) in set.contacts.iter().enumerate().skip(k + 1) {
                    let o = set.offset(m);
                    j[(row, o)] += here.q(ratio, ct.force(1.0, 0.0)) - q0;
                    j[(row, o + 1)] += here.q(ratio, ct.force(0.0, 1.0)) - q0;
                }
            }
        }
        Ok(())
    }

    /// The lying stretch's curvature match at its inner end `s1` (contact `k`), with the rod's
    /// state `cur` there: `m(s1) − (dir·κ_s(x1) − κ0(s1))/b(s1)`, written into row `row`.
    fn match_row(
        &self,
        st: &Stretch<'_>,
        (s1, k): (f64, usize),
        (pose, dpose): (&Pose, &Pose),
        cur: &Sens,
        (r, (jac, rl)): (&mut DVector<f64>, Rows<'_>),
        row: usize,
    ) {
        let n = self.set.n();
        let p = &self.sh.profile;
        let x1 = cur.z[0] + pose.xf;
        let (b, k0) = (p.b(s1), p.k0(s1));
        let (db, dk0) = p.slopes(s1);
        let kap = st.kappa(x1);
        r[row] = cur.z[3] - (kap - k0) / b;
        if let (Some(j), Some(l)) = (jac, rl) {
            let dx = st.dkappa(x1) / b;
            for col in 0..n {
                j[(row, col)] = cur.d[(3, col)] - dx * cur.d[(0, col)];
            }
            j[(row, self.set.offset(k) + 2)] += dk0 / b + (kap - k0) * db / (b * b);
            // (the shape's amplitude moves with `flat` as the start grows the texture)
            l[row] = cur.d[(3, n)] - dx * (cur.d[(0, n)] + dpose.xf)
                + st.dkappa_damp(x1) / b * dpose.flat;
        }
    }

    /// Contact `k`'s conditions at the end state `cur` of its segment, written into the
    /// residual (and, where they are asked for, the Jacobian's rows and `∂R/∂λ`) from `row` on;
    /// the next free row.
    fn conditions_of(
        &self,
        k: usize,
        u: &[f64],
        (pose, dpose): (&Pose, &Pose),
        cur: &Sens,
        (r, (jac, rl)): (&mut DVector<f64>, Rows<'_>),
        mut row: usize,
    ) -> usize {
        let set = &self.set;
        let (n, nc) = (set.n(), set.n() + 1);
        let ct = &set.contacts[k];
        let o = set.offset(k);
        let z = cur.z;
        // (a slip moves its driver's place only)
        let still = |p: &Pose| Pose { slide: 0.0, ..*p };
        let (pose, dpose) = if self.family.moves(k) {
            (*pose, *dpose)
        } else {
            (still(pose), still(dpose))
        };
        let radius = if ct.tip { set.tip_radius } else { 0.0 };
        let cs = conditions(ct, &z, &u[o..o + ct.unknowns()], &pose, &dpose, radius);
        let mut rows = jac.zip(rl);
        for i in 0..cs.rows {
            r[row] = cs.val[i];
            if let Some((j, l)) = rows.as_mut() {
                let dz = &cur.d;
                for col in 0..nc {
                    let mut g: f64 = (0..4).map(|q| cs.dz[i][q] * dz[(q, col)]).sum();
                    if col >= o && col < o + ct.unknowns() {
                        g += cs.down[i][col - o];
                    }
                    if col < n {
                        j[(row, col)] = g;
                    } else {
                        l[row] = g + cs.dlam[i];
                    }
                }
            }
            row += 1;
        }
        // a lying stretch that slides: its friction row, the last, is the balance of its
        // distributed friction
        let ratio = match ct.mode {
            Mode::Sliding(ratio) => Some(ratio),
            Mode::Free => Some(0.0),
            _ => None,
        };
        if let (true, Some(ratio)) = (set.lain() == Some(k), ratio) {
            let rows = rows.map_or((None, None), |(j, l)| (Some(j), Some(l)));
            let at = (u, set.s_of(k, u), z[0] + pose.xf, ratio);
            if self
                .capstan_row(k, at, (&pose, &dpose), cur, (r, rows), row - 1)
                .is_err()
            {
                r[row - 1] = f64::NAN;
            }
        }
        row
    }

    /// The rates `dz(s_k)/dλ` of the contact points' states along the branch with tangent `du`
    /// at `(u, λ)` (total derivatives: a contact point moving along the rod included), in the
    /// foot's frame, from one evaluation with sensitivities; `None` where it fails.
    pub fn contact_rates(&mut self, u: &[f64], lam: f64, du: &[f64]) -> Option<Vec<[f64; 4]>> {
        self.eval(u, lam, true).ok()?;
        let n = du.len();
        let rates = self
            .zs
            .iter()
            .map(|d| {
                let mut r = [0.0; 4];
                for (i, ri) in r.iter_mut().enumerate() {
                    *ri = d[(i, n)] + (0..n).map(|c| d[(i, c)] * du[c]).sum::<f64>();
                }
                r
            })
            .collect();
        Some(rates)
    }

    /// Whether the equilibrium at `(u, λ)` is singular to working precision: the smallest
    /// singular value of `∂R/∂u` at most `n·ε` times the largest (the usual numerical rank).
    pub fn singular_to_precision(&mut self, u: &[f64], lam: f64) -> bool {
        let Some(j) = self.eval(u, lam, true).ok().and_then(|e| e.jac) else {
            return false;
        };
        let sv = j.singular_values();
        sv.min() <= sv.len() as f64 * f64::EPSILON * sv.max()
    }

    /// The exact tangent `du/dλ = −J⁻¹ ∂R/∂λ` of the contact set `set` at `(u, λ)`, the chain's
    /// own set kept (a change of set checks the new state's first direction before solving it);
    /// `None` where the shot fails or `J` is singular.
    pub fn tangent_in(&mut self, set: ContactSet, u: &[f64], lam: f64) -> Option<Vec<f64>> {
        let own = std::mem::replace(&mut self.set, set);
        let e = self.eval(u, lam, true);
        self.set = own;
        let e = e.ok()?;
        let x = e.jac?.lu().solve(&(-e.r_lam?))?;
        x.iter()
            .all(|v| v.is_finite())
            .then(|| x.iter().copied().collect())
    }

    /// `E = ∫ ½ b m² ds + ½ c m(0)²` of the rod at `(u, λ)` on the chain's own shooter (the unloaded
    /// rest beyond the last contact has `m ≡ 0`).
    pub fn elastic_energy(&mut self, u: &[f64], lam: f64) -> Option<f64> {
        for _ in 0..32 {
            let e = self.eval(u, lam, false).ok()?;
            if e.err <= 1.0 {
                break;
            }
            if !self.refine() {
                return None;
            }
        }
        let nseg = self.set.contacts.len().max(1);
        let mut total = 0.5 * self.sh.compliance * u[0] * u[0];
        if let (Some(st), Some(jl)) = (
            self.stretch_at(&self.family.pose(lam).0, u),
            self.set.lain(),
        ) {
            // the lying stretch: b·m²/2 with the surface's curvature
            let s1 = self.set.s_of(jl, u);
            let p = &self.sh.profile;
            let w = (st.s2 - s1) / 8.0;
            for i in 0..8 {
                let a = s1 + w * i as f64;
                total += crate::gauss::gauss10(a, a + w, |s| {
                    let m = st.state(p, s).0[3];
                    0.5 * p.b(s) * m * m
                });
            }
        }
        for k in 0..nseg {
            let (ps, _, _) = self.sh.path(k);
            let ps = ps.to_vec();
            for w in ps.windows(2) {
                total += crate::gauss::gauss10_batch(w[0], w[1], |s| {
                    let z = self.sh.states_at(k, s);
                    std::array::from_fn(|l| {
                        let m = z[l][3];
                        0.5 * self.sh.profile.b(s[l]) * m * m
                    })
                });
            }
        }
        total.is_finite().then_some(total)
    }

    /// The tip contact that is a disk on a surface (a tip radius > 0), if the set has one.
    pub fn disk_tip(&self) -> Option<usize> {
        let set = &self.set;
        let j = set.contacts.len().checked_sub(1)?;
        let ct = &set.contacts[j];
        (set.tip_radius > 0.0
            && ct.tip
            && matches!(ct.geom, Geom::Line { .. } | Geom::Curve { .. }))
        .then_some(j)
    }

    /// Refines the meshes of the loaded segments whose last shot was over tolerance.
    pub fn refine(&mut self) -> bool {
        let k = self.set.contacts.len().max(1);
        self.sh.refine_all(k)
    }
}

/// A curve `R(u, λ) = 0` the solvers follow: a contact chain in its family, or a homotopy of
/// the rod itself.
pub(crate) trait Curve {
    /// Number of unknowns.
    fn n(&self) -> usize;
    /// Residual, and with `var` the Jacobians, at `(u, λ)`.
    fn eval(&mut self, u: &[f64], lam: f64, var: bool) -> Result<Eval, EvalError>;
    /// Refines the meshes after a shot over tolerance; `false` past the step limit.
    fn refine(&mut self) -> bool;
    /// Counts one Newton iteration (one factorization).
    fn count_iteration(&mut self);
}

impl<P: Profile> Curve for Chain<P> {
    fn n(&self) -> usize {
        self.set.n()
    }
    fn eval(&mut self, u: &[f64], lam: f64, var: bool) -> Result<Eval, EvalError> {
        Chain::eval(self, u, lam, var)
    }
    fn refine(&mut self) -> bool {
        Chain::refine(self)
    }
    fn count_iteration(&mut self) {
        self.sh.stats.newton_iters += 1;
        self.sh.stats.factorizations += 1;
    }
}

/// A curve in a parameter that changes the chain itself (not its family's pose): the rod's
/// profile and compliance (the homotopy from the uniform straight rod), the angle of a held tip
/// force. `set(chain, λ)` makes member `λ`; the chain is evaluated at its own family parameter
/// `at`; `∂R/∂λ` by a forward difference.
pub(crate) struct Morph<P: Profile, M: FnMut(&mut Chain<P>, f64)> {
    pub chain: Chain<P>,
    pub set: M,
    pub at: f64,
}

impl<P: Profile, M: FnMut(&mut Chain<P>, f64)> Curve for Morph<P, M> {
    fn n(&self) -> usize {
        self.chain.set.n()
    }
    fn eval(&mut self, u: &[f64], t: f64, var: bool) -> Result<Eval, EvalError> {
        if var {
            let h = 1e-7;
            (self.set)(&mut self.chain, t + h);
            let r1 = self.chain.eval(u, self.at, false)?.r;
            (self.set)(&mut self.chain, t);
            let mut e = self.chain.eval(u, self.at, true)?;
            e.r_lam = Some((r1 - &e.r) / h);
            Ok(e)
        } else {
            (self.set)(&mut self.chain, t);
            self.chain.eval(u, self.at, false)
        }
    }
    fn refine(&mut self) -> bool {
        self.chain.refine()
    }
    fn count_iteration(&mut self) {
        self.chain.count_iteration()
    }
}

impl<P: Profile> Chain<P> {
    /// Whether the shooter's paths are of the state `(u, λ)` (its last evaluation).
    pub fn shot_of(&self, u: &[f64], lam: f64) -> bool {
        self.shot.1.to_bits() == lam.to_bits()
            && self.shot.0.len() == u.len()
            && self
                .shot
                .0
                .iter()
                .zip(u)
                .all(|(a, b)| a.to_bits() == b.to_bits())
    }

    /// Keeps the set's unloaded lying stretch at the invariant of `(pose, u)`: where it slid
    /// (a slip moves it), its outer end found again, so that the set's `s2` (the watch's
    /// clearance and `peel_up`) is that of the point evaluated.
    fn relay(&mut self, pose: &Pose, u: &[f64]) {
        let Some(ly) = self.set.lying.filter(|l| l.beyond == 0) else {
            return;
        };
        let moved = self
            .stretch_at(pose, u)
            .filter(|st| st.c.to_bits() != ly.c.to_bits())
            .map(|st| (st.s2, st.x2, st.c));
        if let Some((s2, x2, c)) = moved {
            self.set.lying = Some(Lying { s2, x2, c, ..ly });
        }
    }

    /// The lying stretch of the set at the pose `pose` and the unknowns `u`, if the set lies.
    pub fn stretch_at(&self, pose: &Pose, u: &[f64]) -> Option<Stretch<'_>> {
        let j = self.set.lain()?;
        let slide = if self.family.moves(j) {
            pose.slide
        } else {
            0.0
        };
        let c = match self.set.contacts[j].mode {
            Mode::Rolling(k) => k + slide,
            // (a stretch that slides passively: its invariant where its inner end is, on the
            // shooter's path there)
            Mode::Sliding(_) | Mode::Free => {
                let s1 = self.set.s_of(j, u);
                let x1 = self.sh.state_at(j, s1)[0] + pose.xf;
                let (Geom::Curve { h }, Some(ly)) = (&self.set.contacts[j].geom, self.set.lying)
                else {
                    return None;
                };
                let amp = 1.0 - pose.flat;
                let dir = self.stretch_dir(h, ly.x2, amp);
                self.stretch_sigma(h, x1, amp).0 - dir * s1
            }
            _ => return None,
        };
        self.stretch_from(pose, u, c)
    }

    /// The surface's arc length `σ(x)` and `dσ/dx` as the lying stretch sees it at the
    /// amplitude `amp`: [`crate::surface::Height::sigma`] at the full amplitude; below it (the
    /// start's growth) the scaled surface's arc length from the stretch's anchor, where it is
    /// taken to be the full one's (any fixed origin serves: the stretch there is frictionless,
    /// its invariant found from its inner end at every evaluation; a near one keeps the
    /// integral short).
    fn stretch_sigma(&self, h: &crate::surface::Height, x: f64, amp: f64) -> (f64, f64) {
        match self.set.lying.and_then(|ly| ly.anchor_at(h, amp)) {
            Some((xa, sa)) => h.sigma_scaled_from(xa, sa, x, amp),
            None => h.sigma(x),
        }
    }

    /// The set's lying stretch at the pose `pose` with the surface's amplitude `a` instead of
    /// the pose's, its invariant where its inner end `(x1, s1)` is (running the way `dir`): the
    /// start's derivatives in the amplitude, by differences.
    fn stretch_scaled(
        &self,
        h: &crate::surface::Height,
        pose: &Pose,
        u: &[f64],
        (x1, s1, dir): (f64, f64, f64),
        a: f64,
    ) -> Option<Stretch<'_>> {
        let at = Pose {
            flat: 1.0 - a,
            ..*pose
        };
        let c = self.stretch_sigma(h, x1, a).0 - dir * s1;
        self.stretch_from(&at, u, c)
    }

    /// The way the lain contact's rod runs along the surface, `±1` (its slope against the
    /// surface's at `x`, amplitude `amp`), and that multiple of π.
    fn stretch_dir(&self, h: &crate::surface::Height, x: f64, amp: f64) -> f64 {
        self.stretch_kpi(h, x, amp).cos().round()
    }

    fn stretch_kpi(&self, h: &crate::surface::Height, x: f64, amp: f64) -> f64 {
        let th = h.angle_scaled(x, amp).0;
        self.set
            .lain()
            .map_or(f64::NAN, |j| self.set.contacts[j].kpi(th))
    }

    /// [`Chain::stretch_at`] with the rolling invariant `c`.
    fn stretch_from(&self, pose: &Pose, u: &[f64], c: f64) -> Option<Stretch<'_>> {
        let ly = self.set.lying?;
        let j = self.set.lain()?;
        let Geom::Curve { h } = &self.set.contacts[j].geom else {
            return None;
        };
        let amp = 1.0 - pose.flat;
        let kpi = self.stretch_kpi(h, ly.x2, amp);
        let st = Stretch {
            h,
            c,
            dir: kpi.cos().round(),
            kpi,
            amp,
            off: pose.h,
            xf: pose.xf,
            s2: ly.s2,
            x2: ly.x2,
            anchor: ly.anchor_at(h, amp),
        };
        if ly.beyond == 0 {
            if st.c.to_bits() == ly.c.to_bits() {
                return Some(st);
            }
            // (a stretch that slides: its outer end where the moment is zero again)
            let (s2, x2) = st.outer_end(&self.sh.profile)?;
            return Some(Stretch { s2, x2, ..st });
        }
        // (the outer end moves with the loaded rest beyond: its place from the unknowns)
        let s2 = self.set.s2_of(u);
        Some(Stretch {
            s2,
            x2: st.x_at(s2),
            ..st
        })
    }

    /// The normal point forces at the lying stretch's inner and outer ends at `u` (the last
    /// evaluation's point: [`crate::watch::ContactForce::end_push`]); `None` where the set does
    /// not lie.
    pub fn end_push(&self, u: &[f64]) -> Option<[f64; 2]> {
        let st = self.stretch_now()?;
        let j = self.set.lain()?;
        let s1 = self.set.s_of(j, u);
        // the forces on the loaded rod before the stretch and beyond it
        let (g1, g2) = (self.force_from(u, j), self.force_from(u, j + 1));
        let mprime = |g: [f64; 2], phi: f64| {
            let (sp, cp) = phi.sin_cos();
            g[0] * sp - g[1] * cp
        };
        let p = &self.sh.profile;
        let (_, d1) = st.state(p, s1);
        let (z2, d2) = st.state(p, st.s2);
        let before = mprime(g1, self.state_at(s1)[2]);
        Some([
            st.dir * (before - d1[3]),
            st.dir * (d2[3] - mprime(g2, z2[2])),
        ])
    }

    /// The friction of the lying stretch at `u` (the last evaluation's point, tangent `du`) with
    /// its resultant `(n, t)`: the ratio it needs ([`crate::watch::ContactForce::stretch_mu`]; a
    /// stretch that slides with a set ratio has that ratio) and, where it moves by `dc` per unit
    /// `λ` (`moves`; else NaN), the part `W = Q(0) − Q(r)` of its friction's work that its ratio
    /// `r` (0 unless it slides) does not count, with its rate along the branch: a slide of the
    /// stretch by `dc` absorbs `(T + Q(0))·dc = (r·N + W)·dc` (`Q = q1` with the load beyond,
    /// [`Capstan::q`]). `W` moves with `s1`, `c` and a loaded outer end `s2` (central
    /// differences, step 1e-6) and, linearly, with the load beyond. With a ratio `kinetic`, a
    /// stretch that does not slide with a set ratio (a slip's driver) also gives its balance
    /// sliding with that ratio and the balance's slope in it ([`Capstan::balance_slope`]), from
    /// the capstan its needed ratio is solved on.
    pub fn stretch_friction(
        &self,
        u: &[f64],
        du: Option<&[f64]>,
        nt: (f64, f64),
        (dc, kinetic): (Option<f64>, Option<f64>),
    ) -> Option<StretchFriction> {
        let st = self.stretch_now()?;
        let j = self.set.lain()?;
        let p = &self.sh.profile;
        let s1 = self.set.s_of(j, u);
        let fb = self.force_from(u, j + 1);
        let loaded = j + 1 < self.set.contacts.len();
        let mut kinetic_balance = None;
        let (mu, r) = match self.set.contacts[j].mode {
            Mode::Sliding(r) => (r, r),
            Mode::Free => (0.0, 0.0),
            _ => {
                let here = st.capstan(p, s1);
                kinetic_balance = kinetic.map(|k| here.balance_slope(nt, fb, k));
                (here.friction_ratio(nt, fb).0, 0.0)
            }
        };
        let (Some(dc), Some(du)) = (dc, du) else {
            return Some(StretchFriction {
                mu,
                turn: [f64::NAN; 2],
                kinetic_balance,
            });
        };
        let cap = |s1: f64, s2: f64, c: f64| -> Option<Capstan> {
            let at = Stretch { c, ..st };
            let (s2, x2) = match (c == st.c && s2 == st.s2, loaded) {
                (true, _) => (st.s2, st.x2),
                (false, true) => (s2, at.x_at(s2)),
                (false, false) => at.outer_end(p)?,
            };
            Some(Stretch { s2, x2, ..at }.capstan(p, s1))
        };
        let wq = |q: &Capstan, fb: [f64; 2]| q.q(0.0, fb) - if r == 0.0 { 0.0 } else { q.q(r, fb) };
        let w = |s1: f64, s2: f64, c: f64, fb: [f64; 2]| Some(wq(&cap(s1, s2, c)?, fb));
        let e = 1e-6;
        let diff = |a: Option<f64>, b: Option<f64>| match (a, b) {
            (Some(a), Some(b)) => (a - b) / (2.0 * e),
            _ => f64::NAN,
        };
        let (s2, c) = (st.s2, st.c);
        let ds1 = du[self.set.offset(j) + 2];
        let mut rate = diff(w(s1 + e, s2, c, fb), w(s1 - e, s2, c, fb)) * ds1;
        if dc != 0.0 {
            rate += diff(w(s1, s2, c + e, fb), w(s1, s2, c - e, fb)) * dc;
        }
        if loaded {
            let ds2 = du[self.set.n() - 1];
            rate += diff(w(s1, s2 + e, c, fb), w(s1, s2 - e, c, fb)) * ds2;
            // (linear in the load beyond: its rate from the rates of those contacts' forces)
            let dfb = self.force_from(du, j + 1);
            let here = cap(s1, s2, c)?;
            rate += wq(&here, dfb) - wq(&here, [0.0; 2]);
        }
        Some(StretchFriction {
            mu,
            turn: [w(s1, s2, c, fb)?, rate],
            kinetic_balance,
        })
    }

    /// The rate of the lain contact's rolling invariant along the branch as the family moves
    /// it (a slip's driver; 0 otherwise).
    pub fn stretch_moved(&self) -> f64 {
        match self.set.lain() {
            Some(j) if self.family.moves(j) => self.family.pose(self.shot.1).1.slide,
            _ => 0.0,
        }
    }

    /// The lying stretch at the last evaluation's point.
    fn stretch_now(&self) -> Option<Stretch<'_>> {
        self.stretch_at(&self.family.pose(self.shot.1).0, &self.shot.0)
    }

    /// The whole rod of the last evaluation as a [`Solution`] (the loaded segments' paths, then
    /// the unloaded rest beyond the last contact, integrated here to the tolerance), with
    /// `params = [f, α]` of the total contact force. A breakpoint appears twice in the mesh, with
    /// the derivatives on either side (the moment's slope jumps there).
    pub fn path(&mut self, u: &[f64]) -> Solution {
        let nseg = self.bps.len().max(1);
        let s_end = self.bps.last().copied().unwrap_or(1.0);
        // a lying stretch's samples, after its contact's segment; the unloaded rest's start
        // beyond the last contact, or beyond a stretch there
        let (jl, lain, rest) = match (self.stretch_now(), self.set.lain()) {
            (Some(st), Some(jl)) => {
                let lain = stretch_samples(&st, &self.sh.profile, self.bps[jl]);
                let rest = (jl + 1 == self.bps.len())
                    .then(|| (st.s2, st.state(&self.sh.profile, st.s2).0));
                (jl, lain, rest)
            }
            _ => (usize::MAX, Vec::new(), None),
        };
        let rest = rest.or_else(|| {
            (s_end < 1.0).then(|| {
                let (_, pz, _) = self.sh.path(nseg - 1);
                let last = pz.len() - 4;
                (s_end, [pz[last], pz[last + 1], pz[last + 2], pz[last + 3]])
            })
        });
        let rest = rest.filter(|r| r.0 < 1.0);
        if let Some((a, z0)) = rest {
            if self.lean_rest {
                let span0 = self.bps.first().copied().unwrap_or(1.0);
                self.sh.ensure_segment_on(nseg, (a, 1.0), span0);
            }
            for _ in 0..32 {
                let shot = self.sh.shoot(nseg, a, 1.0, z0, &[], [0.0, 0.0], false);
                if shot.err <= 1.0 || !self.sh.refine(nseg) {
                    break;
                }
            }
        }
        let (mut mesh, mut z, mut dz) = (Vec::new(), Vec::new(), Vec::new());
        for k in 0..nseg {
            let (ps, pz, pdz) = self.sh.path(k);
            mesh.extend_from_slice(ps);
            z.extend_from_slice(pz);
            dz.extend_from_slice(pdz);
            if k == jl {
                for (s, zs, dzs) in &lain {
                    mesh.push(*s);
                    z.extend_from_slice(zs);
                    dz.extend_from_slice(dzs);
                }
            }
        }
        if rest.is_some() {
            let (ps, pz, pdz) = self.sh.path(nseg);
            mesh.extend_from_slice(ps);
            z.extend_from_slice(pz);
            dz.extend_from_slice(pdz);
        }
        let f = self.total_force(u);
        Solution {
            n: 4,
            stats: bvp::Stats {
                nodes: mesh.len(),
                ..bvp::Stats::default()
            },
            mesh,
            z,
            dz,
            params: polar(f, self.set.contacts.first().map(|c| c.n)).to_vec(),
            status: bvp::Status::Converged,
            dense: bvp::Dense::Hermite,
        }
    }

    /// The total contact force at `u` (the force the rod's foot carries).
    pub fn total_force(&self, u: &[f64]) -> [f64; 2] {
        self.force_from(u, 0)
    }

    /// The resultant of the contact forces at `u` from contact `j` on (the force the rod carries
    /// before contact `j`).
    pub fn force_from(&self, u: &[f64], j: usize) -> [f64; 2] {
        let mut g = [0.0; 2];
        for (j, ct) in self.set.contacts.iter().enumerate().skip(j) {
            let o = self.set.offset(j);
            let f = ct.force(u[o], u[o + 1]);
            g[0] += f[0];
            g[1] += f[1];
        }
        g
    }

    /// The state on the rod at arc length `s` (last evaluation, after [`Chain::path`]): one
    /// integration step from the node before `s` in its segment.
    pub fn state_at(&self, s: f64) -> [f64; 4] {
        let k = self.bps.partition_point(|&b| b < s);
        match (self.stretch_now(), self.set.lain()) {
            (Some(st), Some(jl)) if k == jl + 1 && s <= st.s2 => st.state(&self.sh.profile, s).0,
            _ => self.sh.state_at(k, s),
        }
    }
}

/// Samples of the lying stretch `st` from its inner end `s1` to its outer end (none where it has
/// no length): arc length, state and its derivative, for a [`Solution`]'s cubic Hermite pieces.
fn stretch_samples<P: Profile>(st: &Stretch<'_>, p: &P, s1: f64) -> Vec<(f64, [f64; 4], [f64; 4])> {
    if st.s2 - s1 <= 1e-12 {
        return Vec::new();
    }
    const PIECES: usize = 32;
    (0..=PIECES)
        .map(|i| {
            let s = s1 + (st.s2 - s1) * i as f64 / PIECES as f64;
            let (z, dz) = st.state(p, s);
            (s, z, dz)
        })
        .collect()
}

/// `[f, α]` with `F = (f sin α, −f cos α)` for the force `F`: α within a quarter turn of the
/// angle of the frame normal `n` (`α_n = atan2(−n_x, n_y)`, the force angle of a pure normal
/// force), `f` negative where the force pulls against that normal.
pub(crate) fn polar(f: [f64; 2], n: Option<[f64; 2]>) -> [f64; 2] {
    use std::f64::consts::{FRAC_PI_2, PI, TAU};
    let a_ref = n.map_or(0.0, |n| (-n[0]).atan2(n[1]));
    let mag = (f[0] * f[0] + f[1] * f[1]).sqrt();
    if mag == 0.0 {
        return [0.0, a_ref];
    }
    let mut d = f[0].atan2(-f[1]) - a_ref;
    d -= TAU * (d / TAU).round();
    if d > FRAC_PI_2 {
        [-mag, a_ref + d - PI]
    } else if d <= -FRAC_PI_2 {
        [-mag, a_ref + d + PI]
    } else {
        [mag, a_ref + d]
    }
}

/// The conditions of one contact at the rod's state `z` there (foot frame), with its own unknowns
/// `own = (N, T[, s])`: values and derivatives with respect to `z`, `own` and `λ` (explicit).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Conds {
    pub rows: usize,
    pub val: [f64; 3],
    pub dz: [[f64; 4]; 3],
    pub down: [[f64; 3]; 3],
    pub dlam: [f64; 3],
}

impl Conds {
    fn push(&mut self, val: f64, dz: [f64; 4], down: [f64; 3], dlam: f64) {
        let i = self.rows;
        self.val[i] = val;
        self.dz[i] = dz;
        self.down[i] = down;
        self.dlam[i] = dlam;
        self.rows += 1;
    }
}

/// See [`Conds`]: on the surface (its place along the line per the mode, tangent inside the rod),
/// at a point object (its position, and the mode), or a held tip slope.
///
/// `radius`: the disk radius of a tip contact (0: a point tip, and for every other contact).
/// The disk's centre, the rod's end, stays on the surface offset by `radius` along its normal,
/// and a stuck tip rolls: its place is [`tip_place`]'s.
pub(crate) fn conditions(
    ct: &Contact,
    z: &[f64; 4],
    own: &[f64],
    pose: &Pose,
    dpose: &Pose,
    radius: f64,
) -> Conds {
    let mut cs = Conds::default();
    let (rx, ry) = (z[0] + pose.xf, z[1]);
    let (nn, tt) = (own[0], own[1]);
    let friction =
        |cs: &mut Conds, ratio: f64| cs.push(tt - ratio * nn, [0.0; 4], [-ratio, 1.0, 0.0], 0.0);
    match &ct.geom {
        Geom::Line { p0, beta } => {
            let (sb, cb) = beta.sin_cos();
            let nv = [-sb, cb];
            let e = [cb, sb];
            // (a disk's centre runs on the line lowered by its radius)
            let lowered = if radius > 0.0 { radius } else { 0.0 };
            let gap = nv[0] * (rx - p0[0]) + nv[1] * (ry - p0[1]) - pose.h;
            cs.push(
                if lowered > 0.0 { gap + lowered } else { gap },
                [nv[0], nv[1], 0.0, 0.0],
                [0.0; 3],
                nv[0] * dpose.xf - dpose.h,
            );
            if !ct.tip {
                cs.push(z[2] - ct.phi_ref, [0.0, 0.0, 1.0, 0.0], [0.0; 3], 0.0);
            }
            let along = e[0] * (rx - p0[0]) + e[1] * (ry - p0[1]);
            let da = [e[0], e[1], 0.0, 0.0];
            match ct.mode {
                Mode::Stuck(anchor) if lowered > 0.0 => cs.push(
                    // rolling: along the line, less r·(φ(1) − β)
                    along - lowered * (z[2] - beta) - anchor - pose.slide,
                    [e[0], e[1], -lowered, 0.0],
                    [0.0; 3],
                    e[0] * dpose.xf - dpose.slide,
                ),
                Mode::Stuck(anchor) => cs.push(
                    along - anchor - pose.slide,
                    da,
                    [0.0; 3],
                    e[0] * dpose.xf - dpose.slide,
                ),
                Mode::Rolling(k) => {
                    // the rod runs along the line forwards or backwards (its slope β or β + π)
                    let dir = (ct.phi_ref - beta).cos().round();
                    cs.push(
                        along - dir * own[2] - k - pose.slide,
                        da,
                        [0.0, 0.0, -dir],
                        e[0] * dpose.xf - dpose.slide,
                    )
                }
                Mode::Free => friction(&mut cs, 0.0),
                Mode::Sliding(ratio) => friction(&mut cs, ratio),
            }
        }
        Geom::Curve { h } if ct.tip && radius > 0.0 => {
            disk_conditions(&mut cs, ct, (h, radius), z, own, pose, dpose)
        }
        Geom::Curve { h } => curve_conditions(&mut cs, ct, h, z, own, pose, dpose),
        Geom::Slope { phi1 } => {
            cs.push(
                z[2] - phi1 - pose.phi,
                [0.0, 0.0, 1.0, 0.0],
                [0.0; 3],
                -dpose.phi,
            );
            match ct.mode {
                Mode::Sliding(ratio) => friction(&mut cs, ratio),
                _ => friction(&mut cs, 0.0),
            }
        }
        Geom::Point { p } => {
            cs.push(rx - p[0], [1.0, 0.0, 0.0, 0.0], [0.0; 3], dpose.xf);
            cs.push(ry - p[1], [0.0, 1.0, 0.0, 0.0], [0.0; 3], 0.0);
            match ct.mode {
                Mode::Stuck(sa) if !ct.tip => cs.push(own[2] - sa, [0.0; 4], [0.0, 0.0, 1.0], 0.0),
                mode => {
                    // frictionless or sliding, in the rod's own frame at the contact (tangent τ,
                    // normal ν towards the object): T = F·τ = ratio·N = −ratio F·ν
                    let ratio = match mode {
                        Mode::Sliding(r) => r,
                        _ => 0.0,
                    };
                    let (tau, nu) = ct.rod_frame(z[2]);
                    let dtau = [-tau[1], tau[0]];
                    let dnu = [-nu[1], nu[0]];
                    let t = ct.t();
                    let f = ct.force(nn, tt);
                    let dot = |a: [f64; 2], b: [f64; 2]| a[0] * b[0] + a[1] * b[1];
                    let w = [tau[0] + ratio * nu[0], tau[1] + ratio * nu[1]];
                    let dw = [dtau[0] + ratio * dnu[0], dtau[1] + ratio * dnu[1]];
                    cs.push(
                        dot(f, w),
                        [0.0, 0.0, dot(f, dw), 0.0],
                        [-dot(ct.n, w), dot(t, w), 0.0],
                        0.0,
                    )
                }
            }
        }
    }
    cs
}

/// The conditions on a curved surface `y = h(x) + pose.h`: on it; tangent to it inside the rod
/// (`φ = θ(x) + kπ`, `θ = atan h'`); the mode, with the tip's place as arc length `σ(x)` along
/// the surface and the friction ratio in the local frame (`N`, `T` of the force resolved on the
/// normal and tangent at the contact point: the unknowns are the force in the frame fixed when
/// the contact formed, so that the shooter's forces stay constant along a segment).
fn curve_conditions(
    cs: &mut Conds,
    ct: &Contact,
    h: &crate::surface::Height,
    z: &[f64; 4],
    own: &[f64],
    pose: &Pose,
    dpose: &Pose,
) {
    let rx = z[0] + pose.xf;
    let amp = 1.0 - pose.flat;
    let (hv, d, _) = h.jet_scaled(rx, amp);
    // the shape's part (its amplitude moves with `flat`)
    let (sv, sd) = if dpose.flat != 0.0 {
        h.shape(rx)
    } else {
        (0.0, 0.0)
    };
    cs.push(
        z[1] - hv - pose.h,
        [-d, 1.0, 0.0, 0.0],
        [0.0; 3],
        -d * dpose.xf - dpose.h + sv * dpose.flat,
    );
    let (th, dth) = h.angle_scaled(rx, amp);
    // dθ/dλ at a fixed point: through x (the foot) and the amplitude
    let dth_lam = dth * dpose.xf - sd / (1.0 + d * d) * dpose.flat;
    // the multiple of π the rod's slope keeps against the surface's (|θ| < π/4)
    let kpi = ct.kpi(th);
    if !ct.tip {
        cs.push(z[2] - th - kpi, [-dth, 0.0, 1.0, 0.0], [0.0; 3], -dth_lam);
    }
    let (sg, dsg) = h.sigma(rx);
    match ct.mode {
        Mode::Stuck(anchor) => cs.push(
            sg - anchor - pose.slide,
            [dsg, 0.0, 0.0, 0.0],
            [0.0; 3],
            dsg * dpose.xf - dpose.slide,
        ),
        Mode::Rolling(k) => {
            let dir = kpi.cos().round();
            cs.push(
                sg - dir * own[2] - k - pose.slide,
                [dsg, 0.0, 0.0, 0.0],
                [0.0, 0.0, -dir],
                dsg * dpose.xf - dpose.slide,
            )
        }
        Mode::Free | Mode::Sliding(_) => {
            let ratio = if let Mode::Sliding(r) = ct.mode {
                r
            } else {
                0.0
            };
            // N_loc = Fx sin θ − Fy cos θ, T_loc = −Fx cos θ − Fy sin θ; F = −N n + T t
            let f = ct.force(own[0], own[1]);
            let (st, c) = th.sin_cos();
            let nl = f[0] * st - f[1] * c;
            let tl = -f[0] * c - f[1] * st;
            let t = ct.t();
            let dn = [-ct.n[0] * st + ct.n[1] * c, t[0] * st - t[1] * c];
            let dt = [ct.n[0] * c + ct.n[1] * st, -t[0] * c - t[1] * st];
            // ∂/∂θ: N_loc' = −T_loc... (Fx cos θ + Fy sin θ = −T_loc), T_loc' = N_loc
            let dth_row = (nl + ratio * tl) * dth;
            cs.push(
                tl - ratio * nl,
                [dth_row, 0.0, 0.0, 0.0],
                [dt[0] - ratio * dn[0], dt[1] - ratio * dn[1], 0.0],
                (nl + ratio * tl) * dth_lam,
            )
        }
    }
}

/// The force `(N, T)` of a contact resolved on the local normal and tangent of a curved surface at
/// lab `x` (for a line: the unknowns themselves).
pub(crate) fn local_forces(ct: &Contact, nn: f64, tt: f64, x: f64) -> (f64, f64) {
    match &ct.geom {
        Geom::Curve { h } => {
            let f = ct.force(nn, tt);
            let (st, c) = h.angle(x).0.sin_cos();
            (f[0] * st - f[1] * c, -f[0] * c - f[1] * st)
        }
        _ => (nn, tt),
    }
}

/// The rod's slope where it lies tangent to a line of inclination `beta` with slope near `phi`:
/// `β + kπ` (forwards or backwards along the line), the multiple nearest `phi`.
pub(crate) fn slope_on(beta: f64, phi: f64) -> f64 {
    beta + std::f64::consts::PI * ((phi - beta) / std::f64::consts::PI).round()
}

/// The place along the surface that a stuck tip keeps (the anchor of [`Mode::Stuck`]) at the
/// rod's end state `z` (foot frame, the foot at lab `xf`): for a point tip (`r = 0`) the arc
/// length of the tip (along a line: from its point `p0`); for a disk of radius `r` rolling
/// without slip, `σ(x_c) − r·(φ(1) − θ(x_c))` (the contact point's arc length less the disk's
/// turn against the surface's normal). `None` off a surface, or where a disk has no contact
/// point.
pub(crate) fn tip_place(r: f64, geom: &Geom, z: &[f64], xf: f64) -> Option<f64> {
    let x = z[0] + xf;
    match geom {
        Geom::Line { p0, beta } => {
            let (sb, cb) = beta.sin_cos();
            let along = cb * (x - p0[0]) + sb * (z[1] - p0[1]);
            Some(if r > 0.0 {
                along - r * (z[2] - beta)
            } else {
                along
            })
        }
        Geom::Curve { h } if r > 0.0 => {
            let dk = disk_on_curve(h, r, x, 1.0)?;
            Some(h.sigma(dk.xc).0 - r * (z[2] - dk.th))
        }
        Geom::Curve { h } => Some(h.sigma(x).0),
        _ => None,
    }
}

/// The lab position of a tip's contact point with a surface: the rod's end (lab `(z[0] + xf,
/// z[1])`) for a point tip, `P + r·n` for a disk (on a curve at amplitude `amp`). `None` where a
/// disk has no contact point.
pub(crate) fn tip_point(r: f64, geom: &Geom, z: &[f64], xf: f64, amp: f64) -> Option<[f64; 2]> {
    let (x, y) = (z[0] + xf, z[1]);
    if r <= 0.0 {
        return Some([x, y]);
    }
    let th = match geom {
        Geom::Line { beta, .. } => *beta,
        Geom::Curve { h } => disk_on_curve(h, r, x, amp)?.th,
        _ => return Some([x, y]),
    };
    Some([x - r * th.sin(), y + r * th.cos()])
}

/// The moment about the disk's centre of a round tip's contact force, `r·T_loc` (`T_loc` the
/// force's component on the surface's tangent `t = −(cos θ, sin θ)` at the contact point), and
/// its derivatives: `(value, ∂/∂P_x, ∂/∂(N, T), ∂/∂λ explicit)`. `None` where the disk has no
/// contact point.
fn disk_moment(
    ct: &Contact,
    r: f64,
    z: &[f64; 4],
    own: &[f64],
    pose: &Pose,
    dpose: &Pose,
) -> Option<(f64, f64, [f64; 2], f64)> {
    let px = z[0] + pose.xf;
    // θ at the contact point, its rate with P_x and with λ at a fixed P
    let (th, dth_px, dth_lam) = match &ct.geom {
        Geom::Line { beta, .. } => (*beta, 0.0, 0.0),
        Geom::Curve { h } => {
            let amp = 1.0 - pose.flat;
            let dk = disk_on_curve(h, r, px, amp)?;
            let th_amp = if dpose.flat != 0.0 {
                let d = h.jet_scaled(dk.xc, amp).1;
                h.shape(dk.xc).1 / (1.0 + d * d)
            } else {
                0.0
            };
            let lam = (dk.dth * dpose.xf - th_amp * dpose.flat) / dk.jac;
            (dk.th, dk.dth / dk.jac, lam)
        }
        _ => return Some((0.0, 0.0, [0.0; 2], 0.0)),
    };
    let f = ct.force(own[0], own[1]);
    let (st, c) = th.sin_cos();
    let tl = -f[0] * c - f[1] * st;
    let nl = f[0] * st - f[1] * c;
    let t = ct.t();
    let down = [
        r * (ct.n[0] * c + ct.n[1] * st),
        r * (-t[0] * c - t[1] * st),
    ];
    Some((r * tl, r * nl * dth_px, down, r * nl * dth_lam))
}

/// The conditions of a round tip (radius `r`) on the curved surface `h`: its centre on the
/// offset curve, `P_y = h(x_c) − r cos θ(x_c)` (`x_c` from `P_x`, [`disk_on_curve`](crate::surface::disk_on_curve)); the mode
/// at the contact point (stuck: rolling, [`tip_place`] fixed; free or sliding: the friction
/// ratio in the local frame there). The derivatives by `P_x` go through `x_c`: the offset curve's
/// slope is `tan θ(x_c)`, the place's rate `1/cos θ(x_c)`, θ's rate `θ'/J`.
fn disk_conditions(
    cs: &mut Conds,
    ct: &Contact,
    (h, r): (&crate::surface::Height, f64),
    z: &[f64; 4],
    own: &[f64],
    pose: &Pose,
    dpose: &Pose,
) {
    let px = z[0] + pose.xf;
    let amp = 1.0 - pose.flat;
    let Some(dk) = disk_on_curve(h, r, px, amp) else {
        // no contact point: no value (the solve backs off)
        cs.push(f64::NAN, [0.0; 4], [0.0; 3], 0.0);
        cs.push(f64::NAN, [0.0; 4], [0.0; 3], 0.0);
        return;
    };
    let (hv, d, _) = h.jet_scaled(dk.xc, amp);
    let (sv, sd) = if dpose.flat != 0.0 {
        h.shape(dk.xc)
    } else {
        (0.0, 0.0)
    };
    let (st, c) = dk.th.sin_cos();
    cs.push(
        z[1] - (hv - r * c) - pose.h,
        [-d, 1.0, 0.0, 0.0],
        [0.0; 3],
        -d * dpose.xf - dpose.h + sv * dpose.flat,
    );
    let dth = dk.dth / dk.jac;
    let dth_lam = (dk.dth * dpose.xf - sd / (1.0 + d * d) * dpose.flat) / dk.jac;
    match ct.mode {
        Mode::Stuck(anchor) => {
            let place = h.sigma(dk.xc).0 - r * (z[2] - dk.th);
            cs.push(
                place - anchor - pose.slide,
                [1.0 / c, 0.0, -r, 0.0],
                [0.0; 3],
                dpose.xf / c - dpose.slide,
            )
        }
        _ => {
            let ratio = if let Mode::Sliding(q) = ct.mode {
                q
            } else {
                0.0
            };
            let f = ct.force(own[0], own[1]);
            let nl = f[0] * st - f[1] * c;
            let tl = -f[0] * c - f[1] * st;
            let t = ct.t();
            let dn = [-ct.n[0] * st + ct.n[1] * c, t[0] * st - t[1] * c];
            let dt = [ct.n[0] * c + ct.n[1] * st, -t[0] * c - t[1] * st];
            cs.push(
                tl - ratio * nl,
                [(nl + ratio * tl) * dth, 0.0, 0.0, 0.0],
                [dt[0] - ratio * dn[0], dt[1] - ratio * dn[1], 0.0],
                (nl + ratio * tl) * dth_lam,
            )
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parts::{Precurvature, Stiffness};
    use crate::profile::General;
    use crate::surface::{Height, SurfaceProfile};

    /// The lying stretch's conditions and their derivatives: the Jacobian (by the chain rule
    /// over the shots' sensitivities and the moving ends' columns, with the surface's
    /// curvature slope by central differences) against central differences of the residual, to
    /// 1e-6 of each row's size (and 1e-9, the differences' rounding), at states near the drags
    /// of tests/stretch.rs (a pre-curved rod: `κ0` and `b` both vary along it), in the drag's
    /// family (the first case also in the start's, which grows the texture's amplitude with
    /// `λ`): the stretch with the rod beyond it unloaded (its curvature match is the set's last
    /// condition) and with the tip stuck beyond it (the match is a condition of its own, the
    /// outer end an unknown, the segment beyond starting there); each also driving a slip (the
    /// slide's family moves its invariant, and with it the outer end's place) and sliding along
    /// with a set ratio (its capstan row; its invariant moves with its inner end). It fails
    /// without the capstan row's `s1` column, the segment beyond's moves with the invariant
    /// (either way), or the slide's `λ` term.
    #[test]
    fn lying_jacobian_matches_differences() {
        let h = Arc::new(
            Height::new(
                &SurfaceProfile::Sine {
                    amplitude: 0.001,
                    wavelength: 0.5,
                    phase: 4.0 * std::f64::consts::PI / 3.0,
                },
                0.75,
                0.0,
            )
            .unwrap()
            .unwrap(),
        );
        let profile = General::new(
            &Stiffness::Taper { ratio: 0.3 },
            &Precurvature::Linear { k0: 0.1, k1: 0.2 },
            1.0,
        );
        let (x2, s2) = (5.0 / 12.0, 0.9658524852769022);
        let th = h.angle(x2).0;
        // (the side's rolling invariant, where the stretch lay down)
        let c = h.sigma(x2).0 - s2;
        let side = Contact::on_curve(false, &h, x2, Mode::Rolling(c), th);
        let tip = Contact::on_curve(true, &h, 0.45, Mode::Stuck(h.sigma(0.45).0), 0.0);
        let lying = |beyond| {
            Some(Lying {
                s2,
                x2,
                c,
                beyond,
                anchor: x2,
            })
        };
        let unloaded = ContactSet {
            lying: lying(0),
            ..ContactSet::of(vec![side.clone()])
        };
        let loaded = ContactSet {
            lying: lying(1),
            ..ContactSet::of(vec![side, tip])
        };
        // (the start grows the texture with frictionless contacts: a stretch there is free,
        // its invariant where its inner end is on the scaled surface's arc length)
        let grow = (
            Family::Grow {
                off0: 0.001,
                off1: 0.0,
            },
            0.7,
        );
        let free = |set: &ContactSet| {
            let mut set = set.clone();
            for c in &mut set.contacts {
                c.mode = Mode::Free;
            }
            set
        };
        let (unloaded_free, loaded_free) = (free(&unloaded), free(&loaded));
        // a stretch that slides (module docs, "A stretch that slides"): along, with its
        // capstan row and an invariant that moves with its inner end, or driving a slip
        let sliding = |set: &ContactSet| {
            let mut set = set.clone();
            set.contacts[0].mode = Mode::Sliding(0.3);
            set
        };
        let (unloaded_sliding, loaded_sliding) = (sliding(&unloaded), sliding(&loaded));
        let slide = Family::Slide {
            xf: 0.05,
            theta: 0.0,
            dir: 1.0,
            driver: 0,
        };
        // (an unloaded stretch that slides needs its outer end where `m = 0` again: a rest
        // curvature the surface's reaches)
        let gentle = General::new(
            &Stiffness::Taper { ratio: 0.3 },
            &Precurvature::Linear { k0: 0.01, k1: 0.02 },
            1.0,
        );
        type Case<'a> = (&'a General, &'a ContactSet, &'a [f64], &'a [(Family, f64)]);
        let (u1, u2): (&[f64], &[f64]) = (
            &[-0.026, 1.43, 0.59, 0.93],
            &[-0.026, 1.43, 0.59, 0.93, 0.05, 0.01, 0.955],
        );
        let cases: [Case; 8] = [
            (&profile, &unloaded, u1, &[(Family::Drag, 0.05), grow]),
            (&gentle, &unloaded_free, u1, &[grow, (Family::Drag, 0.05)]),
            (&profile, &loaded_free, u2, &[grow]),
            (
                &profile,
                &loaded,
                u2,
                &[(Family::Drag, 0.05), (slide, 0.002)],
            ),
            (&gentle, &unloaded, u1, &[(slide, 0.002)]),
            (&gentle, &unloaded_sliding, u1, &[(Family::Drag, 0.05)]),
            (&profile, &loaded_sliding, u2, &[(Family::Drag, 0.05)]),
            (&gentle, &loaded_sliding, u2, &[(Family::Drag, 0.05)]),
        ];
        for (profile, set, u, families) in cases {
            for &(family, lam) in families {
                let sh = Shooter::new(profile.clone(), 0.0, 1e-10, 16);
                check_jacobian(Chain::new(sh, set.clone(), family), u, lam);
            }
        }
    }

    fn check_jacobian(mut chain: Chain<General>, u: &[f64], lam: f64) {
        let e = chain.eval(u, lam, true).unwrap();
        let (jac, rl) = (e.jac.unwrap(), e.r_lam.unwrap());
        let n = u.len();
        for col in 0..=n {
            let dl = 1e-6;
            let (mut up, mut dn) = (u.to_vec(), u.to_vec());
            let (mut lp, mut ld) = (lam, lam);
            if col < n {
                up[col] += dl;
                dn[col] -= dl;
            } else {
                lp += dl;
                ld -= dl;
            }
            let rp = chain.eval(&up, lp, false).unwrap().r;
            let rd = chain.eval(&dn, ld, false).unwrap().r;
            for row in 0..n {
                let scale = jac.row(row).amax().max(rl[row].abs());
                let fd = (rp[row] - rd[row]) / (2.0 * dl);
                let an = if col < n { jac[(row, col)] } else { rl[row] };
                // (plus the differences' rounding, ~1e-16/1e-6 of the row's values ~1)
                assert!(
                    (fd - an).abs() < 1e-6 * scale + 1e-9,
                    "{:?}, {}: row {row}, column {col}: {an} against differences {fd} (row {})",
                    chain.family,
                    chain.set.label(),
                    jac.row(row)
                );
            }
        }
    }
}
