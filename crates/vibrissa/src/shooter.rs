//! The rod's own integrator: the rod equations over one segment `[a, b]` of the arc length under a
//! constant internal force `G = (Gx, Gy)` (the resultant of every contact force beyond the
//! segment), with the sensitivities of the end state carried on the same stages.
//!
//! ```text
//!     x' = cos φ,   y' = sin φ,   φ' = κ0(s) + b(s)·m,   m' = Gx sin φ − Gy cos φ
//! ```
//!
//! - 8th-order DOP853 weights on a fixed mesh per segment (nodes in `σ ∈ [0, 1]`,
//!   `s = a + (b − a)σ`). Fixed steps make the sensitivities the exact derivatives of the discrete
//!   end state with respect to the start `(φ, m)` and the force, so Newton converges
//!   quadratically. The embedded error estimate of each step is checked against `tol`
//!   (`rtol = atol = tol`, Hairer's norm); steps over it are split by equidistributing the step
//!   sizes the errors ask for, and the solve redone, so each segment's mesh grades itself (fine
//!   near the thin tip of a tapered rod).
//! - Columns of the sensitivities: `nd` start directions in `(φ, m)` (one, `(c, 1)`, for the
//!   first segment of a rod whose foot slope is `π/2 + c·m(0)`; two, `e_φ` and `e_m`, elsewhere)
//!   and the two force components. Monomorphized per width: 4 (no sensitivities), 16 (one start
//!   direction) or 20 (two), so the paper's rod costs what it always did.
//! - Generic over the [`Profile`]: the uniform rod folds `b ≡ 1`, `κ0 ≡ 0` away; any other
//!   profile is tabulated once per mesh and interval at the stage abscissae.
//! - Allocation-free per shot (buffers kept), an inline `sin_cos`, and an AVX2 build chosen at run
//!   time.

use crate::profile::Profile;
use bvp::tableau::dop853 as tab;
use bvp::Stats;

/// Largest number of steps of one segment's mesh (a far-off Newton iterate refines forever).
pub(crate) const MAX_STEPS: usize = 100_000;

/// Result of one segment: the end state, its sensitivities to the columns, the largest scaled
/// step error (≤ 1: within tolerance).
#[derive(Clone, Copy, Debug)]
pub(crate) struct SegShot {
    /// `z(b)`.
    pub z: [f64; 4],
    /// `∂z(b)/∂(column q)`: the start directions first, then `Gx`, `Gy`, then the moving ends
    /// asked for (in the order of [`End`]s given).
    pub col: [[f64; 4]; 6],
    /// Number of columns filled.
    pub ncol: usize,
    /// Of them, the moving ends' (last).
    pub nend: usize,
    /// Max over the steps of the scaled error estimate.
    pub err: f64,
}

/// An end of a segment that moves with the unknowns (a side contact's arc length): a shot asked
/// for it carries the derivative of its end state with respect to that end's place, the mesh
/// moving with the segment (`s = a + (b − a)σ` at fixed `σ`). Integrated as one more column of
/// the variational equations,
///
/// ```text
///     w' = J w + (±f + ς(σ)·∂f/∂s) / (b − a),   w(a) = 0,
/// ```
///
/// (`+`, `ς = σ(b − a)` for the end `b`; `−`, `ς = (1 − σ)(b − a)` for the start `a`;
/// `∂f/∂s = (0, 0, κ0'(s) + b'(s)·m, 0)`), on the same stages, it is the exact derivative of
/// the discrete end state (a Runge–Kutta step commutes with differentiation), to rounding.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum End {
    /// The segment's start `a` (the start state held where it is).
    Start,
    /// The segment's end `b`.
    Stop,
}

/// The mesh of one segment and what depends on it.
#[derive(Clone, Debug)]
struct SegMesh {
    /// Nodes `0 = σ_0 < … < σ_N = 1`.
    nodes: Vec<f64>,
    /// The interval `(a, b)` the profile table was made for.
    ab: (f64, f64),
    /// The places of `coef` and `slope` ([`table_places`]).
    places: Vec<f64>,
    /// `(b, κ0)` at the 12 stage abscissae of each step, then at the end (non-uniform profiles).
    coef: Vec<[f64; 2]>,
    /// `(b', κ0')` at the same places, for shots with moving ends (empty until one asks).
    slope: Vec<[f64; 2]>,
    /// Scaled error estimate of each step of the last shot.
    step_err: Vec<f64>,
    /// The last shot's nodes in `s`, `z` and `F(z)` (node-major, 4 each), and its force.
    path_s: Vec<f64>,
    path_z: Vec<f64>,
    path_dz: Vec<f64>,
    force: [f64; 2],
}

impl SegMesh {
    fn uniform(steps: usize) -> SegMesh {
        SegMesh {
            nodes: (0..=steps).map(|i| i as f64 / steps as f64).collect(),
            ab: (f64::NAN, f64::NAN),
            places: Vec::new(),
            coef: Vec::new(),
            slope: Vec::new(),
            step_err: Vec::new(),
            path_s: Vec::new(),
            path_z: Vec::new(),
            path_dz: Vec::new(),
            force: [0.0; 2],
        }
    }
}

/// The tolerance the shooters' starting meshes are laid out for (the default of
/// [`crate::SolverConfig::tol`]).
const MESH_TOL: f64 = 1e-10;

/// The first mesh's steps for `steps` at [`MESH_TOL`] and the tolerance `tol`: DOP853's local
/// error falls as `h⁸`, so a mesh that meets `MESH_TOL` with `n` steps meets a looser `tol` with
/// `n·(MESH_TOL/tol)^(1/8)` (at least 2); a tighter one starts from `n` and refines. Either way
/// every shot whose error estimate exceeds `tol` is refined before a point is accepted, so this
/// only saves the work a loose tolerance does not need (at 1e-4 a quarter of the steps).
pub(crate) fn initial_steps(steps: usize, tol: f64) -> usize {
    let n = steps.max(1);
    if tol <= MESH_TOL {
        return n;
    }
    let scaled = (n as f64 * (MESH_TOL / tol).powf(0.125)).ceil() as usize;
    scaled.clamp(2.min(n), n)
}

/// The places of a segment's profile table for the mesh `nodes` laid on `[a, b]`: the 12 stage
/// abscissae of each step, then `b` (the shot reads the table in this order), into `out`.
fn table_places(nodes: &[f64], (a, b): (f64, f64), out: &mut Vec<f64>) {
    let len = b - a;
    out.clear();
    out.reserve(12 * nodes.len().saturating_sub(1) + 1);
    for w in nodes.windows(2) {
        let h = w[1] - w[0];
        out.extend(tab::C.iter().map(|c| a + len * (w[0] + c * h)));
    }
    out.push(b);
}

/// The fixed-mesh integrator of one rod, segment by segment, with its recorded path.
#[derive(Clone, Debug)]
pub(crate) struct Shooter<P: Profile> {
    /// Stiffness and rest curvature.
    pub profile: P,
    /// Support compliance `c`: `φ(0) = π/2 − θ + c·m(0)`.
    pub compliance: f64,
    /// Tolerance of the step error estimates.
    pub tol: f64,
    segs: Vec<SegMesh>,
    /// Work counters.
    pub stats: Stats,
}

impl<P: Profile> Shooter<P> {
    /// A shooter whose segments start with `steps` equal steps at the default tolerance (fewer
    /// at a looser `tol`, see [`initial_steps`]).
    pub fn new(profile: P, compliance: f64, tol: f64, steps: usize) -> Self {
        Shooter {
            profile,
            compliance,
            tol,
            segs: vec![SegMesh::uniform(initial_steps(steps, tol))],
            stats: Stats::default(),
        }
    }

    /// A shooter whose segments start with exactly `steps` equal steps whatever the tolerance
    /// (the generic methods' reference for tangents and the fold test, which must not coarsen
    /// with the method's own tolerance).
    pub fn with_steps(profile: P, compliance: f64, tol: f64, steps: usize) -> Self {
        Shooter {
            profile,
            compliance,
            tol,
            segs: vec![SegMesh::uniform(steps.max(1))],
            stats: Stats::default(),
        }
    }

    /// Replaces the profile (homotopy), keeping the meshes.
    pub fn set_profile(&mut self, profile: P, compliance: f64) {
        self.profile = profile;
        self.compliance = compliance;
        for m in &mut self.segs {
            m.ab = (f64::NAN, f64::NAN);
        }
    }

    /// Makes room for `n` segments (new ones copy the density of the first).
    pub fn ensure_segments(&mut self, n: usize) {
        while self.segs.len() < n {
            let steps = (self.segs[0].nodes.len() - 1).clamp(4, 64);
            self.segs.push(SegMesh::uniform(steps));
        }
    }

    /// Makes room for segment `k` over `[a, b]`, a new one laid with the first segment's steps
    /// per unit length there (at least 2), the first spanning `span0` (the segments before it
    /// as [`Shooter::ensure_segments`]). Refinement grades it as any other.
    pub fn ensure_segment_on(&mut self, k: usize, (a, b): (f64, f64), span0: f64) {
        self.ensure_segments(k);
        if self.segs.len() == k {
            let n0 = (self.segs[0].nodes.len() - 1) as f64;
            let steps = (n0 * (b - a) / span0).ceil();
            let steps = if steps.is_finite() { steps as usize } else { 4 };
            self.segs.push(SegMesh::uniform(steps.clamp(2, 64)));
        }
    }

    /// Recomputes segment `k`'s profile table when its interval changed (with the slopes where
    /// `slopes`, for moving ends).
    fn tabulate(&mut self, k: usize, a: f64, b: f64, slopes: bool) {
        if P::UNIFORM {
            return;
        }
        let m = &mut self.segs[k];
        if m.ab == (a, b) && !m.coef.is_empty() {
            if slopes && m.slope.len() != m.coef.len() {
                self.profile.slope_table(&m.places, &mut m.slope);
            }
            return;
        }
        m.ab = (a, b);
        table_places(&m.nodes, (a, b), &mut m.places);
        self.profile.table(&m.places, &mut m.coef);
        if slopes {
            self.profile.slope_table(&m.places, &mut m.slope);
        } else {
            m.slope.clear();
        }
    }

    /// A new mesh for segment `k` after a shot with steps over tolerance: each such step should
    /// shrink by `0.9·e^(−1/8)` (the order-8 rule with a margin; a quarter where `e` is not
    /// finite), the others keep their size, and the nodes equidistribute that step-size function.
    /// `false` when it would exceed [`MAX_STEPS`].
    pub fn refine(&mut self, k: usize) -> bool {
        let m = &mut self.segs[k];
        let n_old = m.nodes.len() - 1;
        let shrink: Vec<f64> = (0..n_old)
            .map(|i| {
                let e = m.step_err.get(i).copied().unwrap_or(0.0);
                if !e.is_finite() {
                    4.0
                } else if e > 1.0 {
                    1.0 / (0.9 * e.powf(-1.0 / 8.0))
                } else {
                    1.0
                }
            })
            .collect();
        let total: f64 = shrink.iter().sum();
        let n_new = total.ceil() as usize;
        if n_new > MAX_STEPS || n_new <= n_old {
            return false;
        }
        let stretch = n_new as f64 / total;
        let mut nodes = Vec::with_capacity(n_new + 1);
        nodes.push(0.0);
        let mut count = 0.0;
        for (w, q) in m.nodes.windows(2).zip(&shrink) {
            let per = q * stretch;
            let next = count + per;
            while (nodes.len() as f64) < next - 1e-9 && nodes.len() < n_new {
                let t = (nodes.len() as f64 - count) / per;
                nodes.push(w[0] + (w[1] - w[0]) * t);
            }
            count = next;
        }
        nodes.push(1.0);
        m.nodes = nodes;
        m.ab = (f64::NAN, f64::NAN);
        true
    }

    /// Refines every segment whose last shot had a step over tolerance; `false` if one could
    /// not be refined.
    pub fn refine_all(&mut self, upto: usize) -> bool {
        for k in 0..upto.min(self.segs.len()) {
            if self.segs[k].step_err.iter().any(|e| e.is_nan() || *e > 1.0) && !self.refine(k) {
                return false;
            }
        }
        true
    }

    /// Integrates segment `k` over `[a, b]` from `z0` under the force `g`; with sensitivities to
    /// the start directions `dirs` (each `(∂φ, ∂m)` at `a`, one or two of them) and to `g`.
    #[allow(clippy::too_many_arguments)]
    pub fn shoot(
        &mut self,
        k: usize,
        a: f64,
        b: f64,
        z0: [f64; 4],
        dirs: &[[f64; 2]],
        g: [f64; 2],
        var: bool,
    ) -> SegShot {
        self.shoot_ends(k, (a, b), z0, dirs, g, var, &[])
    }

    /// [`Shooter::shoot`] with, where `var`, the sensitivities to the moving `ends` too (at most
    /// two, each [`End`] once): the state's bits are those of the shot without them.
    #[allow(clippy::too_many_arguments)]
    pub fn shoot_ends(
        &mut self,
        k: usize,
        (a, b): (f64, f64),
        z0: [f64; 4],
        dirs: &[[f64; 2]],
        g: [f64; 2],
        var: bool,
        ends: &[End],
    ) -> SegShot {
        let ends = if var { ends } else { &[] };
        self.ensure_segments(k + 1);
        self.tabulate(k, a, b, !ends.is_empty());
        #[cfg(target_arch = "x86_64")]
        {
            if std::is_x86_feature_detected!("avx2") {
                // SAFETY: the CPU has AVX2 (checked just above), the only requirement.
                return unsafe { self.shoot_avx2(k, a, b, z0, dirs, g, var, ends) };
            }
        }
        self.shoot_width(k, a, b, z0, dirs, g, var, ends)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    #[allow(clippy::too_many_arguments)]
    unsafe fn shoot_avx2(
        &mut self,
        k: usize,
        a: f64,
        b: f64,
        z0: [f64; 4],
        dirs: &[[f64; 2]],
        g: [f64; 2],
        var: bool,
        ends: &[End],
    ) -> SegShot {
        self.shoot_width(k, a, b, z0, dirs, g, var, ends)
    }

    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn shoot_width(
        &mut self,
        k: usize,
        a: f64,
        b: f64,
        z0: [f64; 4],
        dirs: &[[f64; 2]],
        g: [f64; 2],
        var: bool,
        ends: &[End],
    ) -> SegShot {
        let e = ends;
        match (var, dirs.len(), ends.len()) {
            (false, _, _) => self.shoot_impl::<4, 0>(k, a, b, z0, dirs, g, e),
            (true, 1, 0) => self.shoot_impl::<16, 0>(k, a, b, z0, dirs, g, e),
            (true, 1, 1) => self.shoot_impl::<20, 1>(k, a, b, z0, dirs, g, e),
            (true, 1, _) => self.shoot_impl::<24, 2>(k, a, b, z0, dirs, g, e),
            (true, _, 0) => self.shoot_impl::<20, 0>(k, a, b, z0, dirs, g, e),
            (true, _, 1) => self.shoot_impl::<24, 1>(k, a, b, z0, dirs, g, e),
            (true, _, _) => self.shoot_impl::<28, 2>(k, a, b, z0, dirs, g, e),
        }
    }

    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn shoot_impl<const N: usize, const E: usize>(
        &mut self,
        k: usize,
        a: f64,
        b: f64,
        z0: [f64; 4],
        dirs: &[[f64; 2]],
        g: [f64; 2],
        ends: &[End],
    ) -> SegShot {
        let ncol = (N - 4) / 4;
        let mut y = [0.0; N];
        y[..4].copy_from_slice(&z0);
        for (q, d) in dirs.iter().enumerate().take(ncol.saturating_sub(2 + E)) {
            y[4 + 4 * q + 2] = d[0];
            y[4 + 4 * q + 3] = d[1];
        }
        let tol = self.tol;
        let len = b - a;
        let m = &mut self.segs[k];
        m.path_s.clear();
        m.path_z.clear();
        m.path_dz.clear();
        m.step_err.clear();
        m.force = g;
        let n = m.nodes.len() - 1;
        let coef = &m.coef;
        let slope = &m.slope;
        // the moving ends' terms: `±f/(b − a)` and `ς(σ) = c0 + c1·σ` times `∂f/∂s`
        let ends: [EndTerm; E] = std::array::from_fn(|e| match ends[e] {
            End::Stop => EndTerm {
                f: 1.0 / len,
                c0: 0.0,
                c1: 1.0,
            },
            End::Start => EndTerm {
                f: -1.0 / len,
                c0: 1.0,
                c1: -1.0,
            },
        });
        // the profile's slopes at the table's place `i` (12 per step, then the end)
        let sl = |i: usize| -> [f64; 2] {
            if P::UNIFORM || E == 0 {
                [0.0; 2]
            } else {
                slope[i]
            }
        };
        // the profile at the stages of one step and at its end (one bounds check per step)
        let at = |cs: &[[f64; 2]], i: usize| -> (f64, f64) {
            if P::UNIFORM {
                (1.0, 0.0)
            } else {
                let e = cs[i];
                (e[0], e[1])
            }
        };
        let step_coef = |step: usize| -> &[[f64; 2]] {
            if P::UNIFORM {
                &[]
            } else {
                &coef[12 * step..12 * step + 13]
            }
        };
        let (gx, gy) = (g[0], g[1]);
        let mut kk = [[0.0; N]; 12];
        let (b0, q0) = at(step_coef(0), 0);
        kk[0] = rhs_ends::<N, E>(&y, gx, gy, (b0, q0), (sl(0), 0.0), &ends);
        let mut err_max: f64 = 0.0;
        for step in 0..n {
            let h = len * (m.nodes[step + 1] - m.nodes[step]);
            let (sg0, dsg) = (m.nodes[step], m.nodes[step + 1] - m.nodes[step]);
            let cs = step_coef(step);
            m.path_s.push(a + len * m.nodes[step]);
            m.path_z.extend_from_slice(&y[..4]);
            m.path_dz.extend_from_slice(&kk[0][..4]);
            // stage sums over the nonzero coefficients only, unrolled
            macro_rules! stage {
                ($i:literal, [$($j:literal),*]) => {{
                    let mut t = y;
                    $(
                        let ha = h * tab::A[$i * tab::STAGES + $j];
                        for cc in 0..N {
                            t[cc] += ha * kk[$j][cc];
                        }
                    )*
                    let (bb, qq) = at(cs, $i);
                    let ps = (sl(12 * step + $i), sg0 + tab::C[$i] * dsg);
                    kk[$i] = rhs_ends::<N, E>(&t, gx, gy, (bb, qq), ps, &ends);
                }};
            }
            stage!(1, [0]);
            stage!(2, [0, 1]);
            stage!(3, [0, 2]);
            stage!(4, [0, 2, 3]);
            stage!(5, [0, 3, 4]);
            stage!(6, [0, 3, 4, 5]);
            stage!(7, [0, 3, 4, 5, 6]);
            stage!(8, [0, 3, 4, 5, 6, 7]);
            stage!(9, [0, 3, 4, 5, 6, 7, 8]);
            stage!(10, [0, 3, 4, 5, 6, 7, 8, 9]);
            stage!(11, [0, 3, 4, 5, 6, 7, 8, 9, 10]);
            const NZB: [usize; 8] = [0, 5, 6, 7, 8, 9, 10, 11];
            let mut ynew = y;
            for j in NZB {
                let hb = h * tab::B[j];
                for cc in 0..N {
                    ynew[cc] += hb * kk[j][cc];
                }
            }
            let err = step_error(tol, &y, &ynew, &kk, h);
            m.step_err.push(err);
            err_max = err_max.max(err);
            y = ynew;
            let (bb, qq) = at(cs, 12);
            let ps = (sl(12 * step + 12), m.nodes[step + 1]);
            kk[0] = rhs_ends::<N, E>(&y, gx, gy, (bb, qq), ps, &ends);
        }
        m.path_s.push(b);
        m.path_z.extend_from_slice(&y[..4]);
        m.path_dz.extend_from_slice(&kk[0][..4]);
        self.stats.steps += n;
        self.stats.rhs_evals += 12 * n + 1;
        if N > 4 {
            self.stats.jac_evals += 12 * n + 1;
        }
        let mut col = [[0.0; 4]; 6];
        for (q, c) in col.iter_mut().enumerate().take(ncol) {
            c.copy_from_slice(&y[4 + 4 * q..8 + 4 * q]);
        }
        SegShot {
            z: [y[0], y[1], y[2], y[3]],
            col,
            ncol,
            nend: E,
            err: err_max,
        }
    }

    /// The state at arc length `s` inside segment `k` of the last shot, on the rod itself: one
    /// DOP853 step from the recorded node before `s` (its local error is within the mesh's,
    /// unlike an interpolant's between nodes).
    pub fn state_at(&self, k: usize, s: f64) -> [f64; 4] {
        let (s0, z0) = self.node_before(k, s);
        self.step(z0, s0, s - s0, self.segs[k].force)
    }

    /// The recorded node of segment `k`'s last shot at or before `s` (the first node before
    /// the segment): its place and state, where [`Shooter::state_at`] steps from.
    fn node_before(&self, k: usize, s: f64) -> (f64, [f64; 4]) {
        let m = &self.segs[k];
        let i = m.path_s.partition_point(|&t| t <= s).saturating_sub(1);
        let i = i.min(m.path_s.len().saturating_sub(1));
        let z = &m.path_z[4 * i..4 * i + 4];
        (m.path_s[i], [z[0], z[1], z[2], z[3]])
    }

    /// [`Shooter::state_at`] at each of the `L` places `s` of segment `k`, in lockstep lanes
    /// (each lane `state_at`'s one step, bit for bit: [`Shooter::steps_impl`]); the energy's
    /// quadrature asks for ten at a time.
    pub fn states_at<const L: usize>(&self, k: usize, s: [f64; L]) -> [[f64; 4]; L] {
        let nodes = s.map(|s| self.node_before(k, s));
        let (s0, z0) = (nodes.map(|n| n.0), nodes.map(|n| n.1));
        let h: [f64; L] = std::array::from_fn(|l| s[l] - s0[l]);
        let g = self.segs[k].force;
        #[cfg(target_arch = "x86_64")]
        {
            if std::is_x86_feature_detected!("avx2") {
                // SAFETY: the CPU has AVX2 (checked just above), the only requirement.
                return unsafe { self.steps_avx2(z0, s0, h, g) };
            }
        }
        self.steps_impl(z0, s0, h, g)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn steps_avx2<const L: usize>(
        &self,
        z0: [[f64; 4]; L],
        s0: [f64; L],
        h: [f64; L],
        g: [f64; 2],
    ) -> [[f64; 4]; L] {
        self.steps_impl(z0, s0, h, g)
    }

    /// [`Shooter::step_impl`] on `L` lanes at once, stage by stage (the same operations per lane,
    /// in its order). The stage sums run over the tableau's nonzero `a_ij` only, unrolled as in
    /// the shots: `step_impl` skips a term whose `h·a_ij` is zero, which for a finite step is
    /// exactly the zero `a_ij`; the final sum keeps all twelve terms, as `step_impl` does.
    #[inline(always)]
    fn steps_impl<const L: usize>(
        &self,
        z0: [[f64; 4]; L],
        s0: [f64; L],
        h: [f64; L],
        g: [f64; 2],
    ) -> [[f64; 4]; L] {
        let pb = |s: f64| -> (f64, f64) {
            if P::UNIFORM {
                (1.0, 0.0)
            } else {
                (self.profile.b(s), self.profile.k0(s))
            }
        };
        let mut kk = [[[0.0; 4]; 12]; L];
        macro_rules! stage {
            ($i:literal, [$($j:literal),*]) => {{
                for l in 0..L {
                    if h[l] == 0.0 {
                        continue;
                    }
                    #[allow(unused_mut)]
                    let mut t = z0[l];
                    $(
                        let ha = h[l] * tab::A[$i * tab::STAGES + $j];
                        for c in 0..4 {
                            t[c] += ha * kk[l][$j][c];
                        }
                    )*
                    let (bb, qq) = pb(s0[l] + tab::C[$i] * h[l]);
                    kk[l][$i] = rhs::<4>(&t, g[0], g[1], bb, qq);
                }
            }};
        }
        stage!(0, []);
        stage!(1, [0]);
        stage!(2, [0, 1]);
        stage!(3, [0, 2]);
        stage!(4, [0, 2, 3]);
        stage!(5, [0, 3, 4]);
        stage!(6, [0, 3, 4, 5]);
        stage!(7, [0, 3, 4, 5, 6]);
        stage!(8, [0, 3, 4, 5, 6, 7]);
        stage!(9, [0, 3, 4, 5, 6, 7, 8]);
        stage!(10, [0, 3, 4, 5, 6, 7, 8, 9]);
        stage!(11, [0, 3, 4, 5, 6, 7, 8, 9, 10]);
        let mut z = z0;
        for l in 0..L {
            if h[l] == 0.0 {
                continue;
            }
            for (j, kj) in kk[l].iter().enumerate() {
                let hb = h[l] * tab::B[j];
                for c in 0..4 {
                    z[l][c] += hb * kj[c];
                }
            }
        }
        z
    }

    /// One DOP853 step of size `h` from `z0` at `s0` (no sensitivities, the profile read
    /// directly). On AVX2 machines it runs in the AVX2 build of the same code, as the shots do:
    /// the same operations in the same order (no reassociation, no contraction), so the same bits,
    /// with `round` of the slope reduction a single instruction instead of a call.
    fn step(&self, z0: [f64; 4], s0: f64, h: f64, g: [f64; 2]) -> [f64; 4] {
        #[cfg(target_arch = "x86_64")]
        {
            if std::is_x86_feature_detected!("avx2") {
                // SAFETY: the CPU has AVX2 (checked just above), the only requirement.
                return unsafe { self.step_avx2(z0, s0, h, g) };
            }
        }
        self.step_impl(z0, s0, h, g)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn step_avx2(&self, z0: [f64; 4], s0: f64, h: f64, g: [f64; 2]) -> [f64; 4] {
        self.step_impl(z0, s0, h, g)
    }

    #[inline(always)]
    fn step_impl(&self, z0: [f64; 4], s0: f64, h: f64, g: [f64; 2]) -> [f64; 4] {
        if h == 0.0 {
            return z0;
        }
        let pb = |s: f64| -> (f64, f64) {
            if P::UNIFORM {
                (1.0, 0.0)
            } else {
                (self.profile.b(s), self.profile.k0(s))
            }
        };
        let mut kk = [[0.0; 4]; 12];
        for st in 0..12 {
            let mut t = z0;
            for (j, kj) in kk.iter().enumerate().take(st) {
                let ha = h * tab::A[st * tab::STAGES + j];
                if ha != 0.0 {
                    for c in 0..4 {
                        t[c] += ha * kj[c];
                    }
                }
            }
            let (bb, qq) = pb(s0 + tab::C[st] * h);
            kk[st] = rhs::<4>(&t, g[0], g[1], bb, qq);
        }
        let mut z = z0;
        for (j, kj) in kk.iter().enumerate() {
            let hb = h * tab::B[j];
            for c in 0..4 {
                z[c] += hb * kj[c];
            }
        }
        z
    }

    /// The recorded path of segment `k`'s last shot: nodes in `s`, `z`, `F(z)` (node-major).
    pub fn path(&self, k: usize) -> (&[f64], &[f64], &[f64]) {
        let m = &self.segs[k];
        (&m.path_s, &m.path_z, &m.path_dz)
    }
}

/// `(sin x, cos x)` for moderate `|x|` (here slopes within a few turns): Cody–Waite reduction by
/// π/2 and fdlibm's kernel polynomials on `[−π/4, π/4]` (error ≲ 1 ulp there). About a third of
/// the instructions of libm's general `sincos`, which is the largest single cost of a shot.
#[inline(always)]
#[allow(clippy::excessive_precision)]
pub(crate) fn sin_cos(x: f64) -> (f64, f64) {
    const PIO2_HI: f64 = 1.570_796_326_734_125_614_17; // first 33 bits of π/2
    const PIO2_LO: f64 = 6.077_100_506_506_192_249_99e-11; // π/2 − PIO2_HI
    const S: [f64; 6] = [
        -1.666_666_666_666_663_243_48e-01,
        8.333_333_333_322_489_461_24e-03,
        -1.984_126_982_985_794_931_34e-04,
        2.755_731_370_707_006_767_89e-06,
        -2.505_076_025_340_686_341_95e-08,
        1.589_690_995_211_550_102_21e-10,
    ];
    const C: [f64; 6] = [
        4.166_666_666_666_660_190_37e-02,
        -1.388_888_888_887_410_957_49e-03,
        2.480_158_728_947_672_941_78e-05,
        -2.755_731_435_139_066_330_35e-07,
        2.087_572_321_298_174_827_90e-09,
        -1.135_964_755_778_819_482_65e-11,
    ];
    if x.is_nan() || x.abs() >= 1e5 {
        return x.sin_cos();
    }
    let k = (x * std::f64::consts::FRAC_2_PI).round();
    let r = (x - k * PIO2_HI) - k * PIO2_LO;
    let z = r * r;
    let sp = S[1] + z * (S[2] + z * (S[3] + z * (S[4] + z * S[5])));
    let sr = r + r * z * (S[0] + z * sp);
    let cp = C[0] + z * (C[1] + z * (C[2] + z * (C[3] + z * (C[4] + z * C[5]))));
    let hz = 0.5 * z;
    let w = 1.0 - hz;
    // fdlibm's split keeps 1 − z/2 exact to the last bit
    let cr = w + (((1.0 - w) - hz) + z * z * cp);
    // quadrant by selects rather than a jump table
    // SAFETY: `k` is a whole number with |k| < 1e5·2/π (the test above), so it converts
    // exactly and in range: one truncating instruction instead of the saturating `as`
    let q = unsafe { k.to_int_unchecked::<i64>() };
    let (s1, c1) = if q & 1 == 0 { (sr, cr) } else { (cr, -sr) };
    if q & 2 == 0 {
        (s1, c1)
    } else {
        (-s1, -c1)
    }
}

/// Hairer's DOP853 error norm over `z` of one step from `y` to `ynew`.
#[inline(always)]
fn step_error<const N: usize>(
    tol: f64,
    y: &[f64; N],
    ynew: &[f64; N],
    kk: &[[f64; N]; 12],
    h: f64,
) -> f64 {
    const NZB: [usize; 8] = [0, 5, 6, 7, 8, 9, 10, 11];
    let (mut e5, mut e3) = (0.0, 0.0);
    for cc in 0..4 {
        let sk = tol * (1.0 + y[cc].abs().max(ynew[cc].abs()));
        let (mut a5, mut a3) = (0.0, 0.0);
        for j in NZB {
            a5 += tab::E5[j] * kk[j][cc];
            a3 += tab::E3[j] * kk[j][cc];
        }
        e5 += (a5 / sk) * (a5 / sk);
        e3 += (a3 / sk) * (a3 / sk);
    }
    let deno = e5 + 0.01 * e3;
    let err = if deno > 0.0 {
        h.abs() * e5 / (4.0 * deno).sqrt()
    } else {
        0.0
    };
    if err.is_nan() {
        f64::INFINITY
    } else {
        err
    }
}

/// The rod's right-hand side where `b(s) = b`, `κ0(s) = k0`, under the force `(gx, gy)`, on a
/// state of `N` components: `z` and, for `N > 4`, `(N − 4)/4` sensitivity columns whose last two
/// are the force components (components `4 + 4q + i` hold `∂z_i/∂(column q)`).
#[inline(always)]
pub(crate) fn rhs<const N: usize>(y: &[f64; N], gx: f64, gy: f64, b: f64, k0: f64) -> [f64; N] {
    rhs_ends::<N, 0>(y, gx, gy, (b, k0), ([0.0; 2], 0.0), &[])
}

/// A moving end's inhomogeneous term in its column ([`End`]): `f·f_rod + (c0 + c1·σ)·∂f/∂s`.
#[derive(Clone, Copy, Debug)]
struct EndTerm {
    f: f64,
    c0: f64,
    c1: f64,
}

/// [`rhs`] with `E` moving-end columns last ([`End`]): the profile `(b, κ0)` and, at the
/// stage, its slopes `(b', κ0')` and the mesh coordinate `σ`.
#[inline(always)]
fn rhs_ends<const N: usize, const E: usize>(
    y: &[f64; N],
    gx: f64,
    gy: f64,
    (b, k0): (f64, f64),
    (slope, sigma): ([f64; 2], f64),
    ends: &[EndTerm; E],
) -> [f64; N] {
    let (sp, cp) = sin_cos(y[2]);
    let mut d = [0.0; N];
    d[0] = cp;
    d[1] = sp;
    d[2] = k0 + b * y[3];
    d[3] = gx * sp - gy * cp;
    if N == 4 {
        return d;
    }
    let dm_dphi = gx * cp + gy * sp;
    let ncol = (N - 4) / 4;
    for q in 0..ncol {
        let (dphi, dm) = (y[4 + 4 * q + 2], y[4 + 4 * q + 3]);
        d[4 + 4 * q] = -sp * dphi;
        d[4 + 4 * q + 1] = cp * dphi;
        d[4 + 4 * q + 2] = b * dm;
        d[4 + 4 * q + 3] = dm_dphi * dphi;
    }
    let qx = ncol - 2 - E;
    d[4 + 4 * qx + 3] += sp;
    d[4 + 4 * (qx + 1) + 3] -= cp;
    if E > 0 {
        let ds = slope[1] + slope[0] * y[3];
        for (e, t) in ends.iter().enumerate() {
            let o = 4 + 4 * (ncol - E + e);
            for c in 0..4 {
                d[o + c] += t.f * d[c];
            }
            d[o + 2] += (t.c0 + t.c1 * sigma) * ds;
        }
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::profile::{General, Uniform};
    use crate::{Precurvature, Scene, Stiffness};

    /// A general profile with b ≡ 1, κ0 ≡ 0 gives the uniform rod's shot bit for bit (the table
    /// path and the folded path are the same arithmetic).
    #[test]
    fn general_uniform_profile_matches_uniform() {
        let scene = Scene {
            stiffness: Stiffness::Taper { ratio: 1.0 },
            precurvature: Precurvature::Linear { k0: 0.0, k1: 0.0 },
            ..Scene::default()
        };
        let mut a = Shooter::new(Uniform, 0.0, 1e-10, 16);
        let mut b = Shooter::new(
            General::new(&scene.stiffness, &scene.precurvature, 1.0),
            0.0,
            1e-10,
            16,
        );
        let z0 = [0.0, 0.0, 1.5, -1.2];
        let (sa, sb) = (
            a.shoot(0, 0.0, 1.0, z0, &[[0.0, 1.0]], [0.6, -3.0], true),
            b.shoot(0, 0.0, 1.0, z0, &[[0.0, 1.0]], [0.6, -3.0], true),
        );
        assert_eq!(sa.z, sb.z);
        assert_eq!(sa.col, sb.col);
    }

    /// Sensitivities against central differences of the shot, for a tapered, pre-curved rod on
    /// an inner segment with two start directions (the shot is smooth; the difference error is
    /// ~h² ≈ 1e-10).
    #[test]
    fn sensitivities_match_differences() {
        let scene = Scene {
            stiffness: Stiffness::Taper { ratio: 0.5 },
            precurvature: Precurvature::Linear { k0: 0.4, k1: -0.3 },
            ..Scene::default()
        };
        let mut sh = Shooter::new(
            General::new(&scene.stiffness, &scene.precurvature, 1.0),
            0.7,
            1e-10,
            40,
        );
        let (a, b) = (0.2, 0.9);
        let z0 = [0.1, 0.3, 1.2, -0.8];
        let g = [1.5, -2.5];
        let dirs = [[1.0, 0.0], [0.0, 1.0]];
        let y = sh.shoot(0, a, b, z0, &dirs, g, true);
        let e = 1e-5;
        let fd = |sh: &mut Shooter<General>, q: usize| -> [f64; 4] {
            let (mut zp, mut zm, mut gp, mut gm) = (z0, z0, g, g);
            match q {
                0 => {
                    zp[2] += e;
                    zm[2] -= e
                }
                1 => {
                    zp[3] += e;
                    zm[3] -= e
                }
                2 => {
                    gp[0] += e;
                    gm[0] -= e
                }
                _ => {
                    gp[1] += e;
                    gm[1] -= e
                }
            }
            let p = sh.shoot(0, a, b, zp, &[], gp, false).z;
            let m = sh.shoot(0, a, b, zm, &[], gm, false).z;
            std::array::from_fn::<f64, 4, _>(|i| (p[i] - m[i]) / (2.0 * e))
        };
        for q in 0..4 {
            let d = fd(&mut sh, q);
            for (i, (di, an)) in d.iter().zip(y.col[q]).enumerate() {
                assert!(
                    (di - an).abs() <= 1e-7 * (1.0 + an.abs()),
                    "∂z{i}/∂col{q}: fd {di} analytic {an}"
                );
            }
        }
    }

    /// Refinement splits only the steps over tolerance: a strongly tapered rod gets a mesh graded
    /// towards its thin tip.
    #[test]
    fn refinement_grades_the_mesh() {
        let scene = Scene {
            stiffness: Stiffness::Taper { ratio: 0.1 },
            ..Scene::default()
        };
        let mut sh = Shooter::new(
            General::new(&scene.stiffness, &scene.precurvature, 1.0),
            0.0,
            1e-10,
            8,
        );
        let z0 = [0.0, 0.0, std::f64::consts::FRAC_PI_2, -0.05];
        let mut passes = 0;
        while sh.shoot(0, 0.0, 1.0, z0, &[], [0.0, -0.3], false).err > 1.0 {
            assert!(sh.refine(0));
            passes += 1;
            assert!(passes < 20);
        }
        let nodes = &sh.segs[0].nodes;
        let n = nodes.len() - 1;
        let first = nodes[1] - nodes[0];
        let last = nodes[n] - nodes[n - 1];
        assert!(last < 0.5 * first, "first step {first}, last {last}");
    }

    /// A shooter on the rod tapered to 0.1 with rest curvature `k0 + k1 s`, its mesh refined
    /// until the shot over `span` from `z0` under the force `g` meets the tolerance 1e-10: a
    /// mesh graded towards the thin tip.
    fn graded(
        (k0, k1): (f64, f64),
        (a, b): (f64, f64),
        z0: [f64; 4],
        g: [f64; 2],
    ) -> Shooter<General> {
        let scene = Scene {
            stiffness: Stiffness::Taper { ratio: 0.1 },
            precurvature: Precurvature::Linear { k0, k1 },
            ..Scene::default()
        };
        let mut sh = Shooter::new(
            General::new(&scene.stiffness, &scene.precurvature, 1.0),
            0.0,
            1e-10,
            8,
        );
        while sh.shoot(0, a, b, z0, &[], g, false).err > 1.0 {
            assert!(sh.refine(0));
        }
        assert!(sh.segs[0].nodes.len() > 9, "the mesh was graded");
        sh
    }

    /// A shot with sensitivities has the bits of the shot without them: the same end state,
    /// largest step error and recorded path, for one and two start directions, on a mesh graded
    /// towards a thin tip (the chord corrector asks for the sensitivities of an iterate it
    /// expects to converge with the shot that tests it, and keeps its residual).
    #[test]
    fn sensitivities_leave_the_shot_bit_for_bit() {
        let (z0, g) = ([0.0, 0.0, 1.4, -0.05], [0.02, -0.3]);
        let mut sh = graded((-0.72, 0.0), (0.1, 0.95), z0, g);
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        let plain = sh.shoot(0, 0.1, 0.95, z0, &[], g, false);
        let (ps, pz, pdz) = sh.path(0);
        let path = (bits(ps), bits(pz), bits(pdz));
        for dirs in [&[[0.0, 1.0]][..], &[[1.0, 0.0], [0.0, 1.0]][..]] {
            let var = sh.shoot(0, 0.1, 0.95, z0, dirs, g, true);
            assert_eq!(var.ncol, dirs.len() + 2);
            assert_eq!(
                bits(&var.z),
                bits(&plain.z),
                "end state, {} directions",
                dirs.len()
            );
            assert_eq!(var.err.to_bits(), plain.err.to_bits());
            let (vs, vz, vdz) = sh.path(0);
            assert_eq!((bits(vs), bits(vz), bits(vdz)), path, "recorded path");
        }
    }

    /// The moving ends' columns are the derivatives of the discrete end state with the mesh laid
    /// on the moved segment: against central differences of shots over `(a, b ± e)` and
    /// `(a ± e, b)` (Richardson-extrapolated), for one and two start directions and either end alone,
    /// on a mesh graded towards the thin tip of a tapered, pre-curved rod, so that the profile's
    /// slopes enter (the `ς·∂f/∂s` term). The state's bits are those of the shot without the
    /// columns, and the other columns are those of a shot without the ends.
    #[test]
    fn moving_end_columns_are_derivatives_of_the_discrete_end_state() {
        let (z0, g) = ([0.1, 0.2, 1.3, -0.4], [0.3, -1.1]);
        let (a, b) = (0.15, 0.93);
        let mut sh = graded((-0.7, 0.9), (a, b), z0, g);
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        let plain = sh.shoot(0, a, b, z0, &[], g, false);
        // central differences at steps e and 2e, extrapolated (Richardson: error ~e⁴·z⁽⁵⁾; near
        // the thin tip `b(s)` ~ 1e3 and its slopes ~ 3e4, so one difference alone is off by
        // ~1e-7)
        let diff = |sh: &mut Shooter<General>, end: End| -> [f64; 4] {
            let at = |sh: &mut Shooter<General>, e: f64| -> [f64; 4] {
                let (lo, hi) = match end {
                    End::Stop => ((a, b - e), (a, b + e)),
                    End::Start => ((a - e, b), (a + e, b)),
                };
                let p = sh.shoot(0, hi.0, hi.1, z0, &[], g, false).z;
                let m = sh.shoot(0, lo.0, lo.1, z0, &[], g, false).z;
                std::array::from_fn(|i| (p[i] - m[i]) / (2.0 * e))
            };
            let (d1, d2) = (at(sh, 1e-4), at(sh, 2e-4));
            std::array::from_fn(|i| (4.0 * d1[i] - d2[i]) / 3.0)
        };
        let d_stop = diff(&mut sh, End::Stop);
        let d_start = diff(&mut sh, End::Start);
        let dirs2: &[[f64; 2]] = &[[1.0, 0.0], [0.0, 1.0]];
        let dirs1: &[[f64; 2]] = &[[0.3, 1.0]];
        for dirs in [dirs1, dirs2] {
            for ends in [&[End::Stop][..], &[End::Start], &[End::Stop, End::Start]] {
                let y = sh.shoot_ends(0, (a, b), z0, dirs, g, true, ends);
                assert_eq!(bits(&y.z), bits(&plain.z), "{ends:?}");
                assert_eq!((y.ncol, y.nend), (dirs.len() + 2 + ends.len(), ends.len()));
                for (q, end) in ends.iter().enumerate() {
                    let fd = if *end == End::Stop { d_stop } else { d_start };
                    let col = y.col[y.ncol - y.nend + q];
                    for i in 0..4 {
                        assert!(
                            (fd[i] - col[i]).abs() <= 1e-8 * (1.0 + fd[i].abs()),
                            "{end:?} of {ends:?}, {} directions, z{i}: fd {} column {}",
                            dirs.len(),
                            fd[i],
                            col[i]
                        );
                    }
                }
                let y0 = sh.shoot(0, a, b, z0, dirs, g, true);
                assert_eq!(y.col[..y0.ncol], y0.col[..y0.ncol]);
            }
        }
    }

    /// The lanes of `states_at` are `state_at`, bit for bit (ten places on a graded mesh of a
    /// tapered pre-curved rod, one of them a node, the quadrature's batch).
    #[test]
    fn states_at_lanes_are_state_at() {
        let (z0, g) = ([0.0, 0.0, std::f64::consts::FRAC_PI_2, -0.05], [0.02, -0.3]);
        let sh = graded((-0.7, 0.2), (0.0, 0.9), z0, g);
        let nodes = sh.path(0).0.to_vec();
        let mut s = [0.0; 10];
        for (l, x) in s.iter_mut().enumerate() {
            *x = 0.9 * (l as f64 + 0.37) / 10.0;
        }
        s[3] = nodes[nodes.len() / 2];
        let lanes = sh.states_at(0, s);
        for (l, &x) in s.iter().enumerate() {
            assert_eq!(
                lanes[l].map(f64::to_bits),
                sh.state_at(0, x).map(f64::to_bits),
                "lane {l} at s = {x}"
            );
        }
    }

    /// The state on the rod between nodes (one step from the node before) agrees with a shot on
    /// a mesh through that point.
    #[test]
    fn state_between_nodes_is_on_the_rod() {
        let mut sh = Shooter::new(Uniform, 0.0, 1e-12, 12);
        let z0 = [0.0, 0.0, std::f64::consts::FRAC_PI_2, -1.6];
        while sh.shoot(0, 0.0, 1.0, z0, &[], [0.0, -2.8], false).err > 1.0 {
            assert!(sh.refine(0));
        }
        let s = 0.4321;
        let z = sh.state_at(0, s);
        let mut fine = Shooter::new(Uniform, 0.0, 1e-13, 64);
        let zf = fine.shoot(0, 0.0, s, z0, &[], [0.0, -2.8], false).z;
        for i in 0..4 {
            assert!((z[i] - zf[i]).abs() < 1e-11, "{i}: {} vs {}", z[i], zf[i]);
        }
    }
}
