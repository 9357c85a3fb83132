//! Interoperation with `ode_solvers` 0.6 (feature `ode_solvers`).
//!
//! - [`from_ode_system`]: a problem whose right-hand side is an [`ode_solvers::System`] (state
//!   [`ode_solvers::DVector`] or [`ode_solvers::SVector`]), with boundary conditions as a closure;
//!   it implements [`Bvp`], so every solver of this crate takes it.
//! - [`OdeShooting`]: single shooting that integrates with `ode_solvers`' `Dop853` (output
//!   [`ode_solvers::OutputType::Sparse`], i.e. the accepted steps: its `Dense` output can end
//!   short of `x_end`) and builds the Newton matrix by forward differences (`n + k` extra
//!   integrations per iteration). It is the off-the-shelf baseline against which the crate's own
//!   [`crate::Shooting`] (DOP853 with the variational equations on the same stages, no
//!   allocation) is measured: `cargo bench -p bvp --features ode_solvers --bench ode_solvers`.
//!
//! ```
//! use bvp::odes::{from_ode_system, OdeShooting, OdeShootingOptions};
//! use bvp::{BvpSolver, Guess};
//! use ode_solvers::{System, Vector2};
//!
//! /// y'' = −y as an ode_solvers system.
//! struct Oscillator;
//! impl System<f64, Vector2<f64>> for Oscillator {
//!     fn system(&self, _x: f64, y: &Vector2<f64>, dy: &mut Vector2<f64>) {
//!         dy[0] = y[1];
//!         dy[1] = -y[0];
//!     }
//! }
//!
//! // y(0) = 0, y(π/2) = 1: y = sin x.
//! let p = from_ode_system(Oscillator, 2, (0.0, std::f64::consts::FRAC_PI_2), |za, zb, r| {
//!     r[0] = za[0];
//!     r[1] = zb[0] - 1.0;
//! });
//! let guess = Guess::constant(0.0, std::f64::consts::FRAC_PI_2, 3, &[0.5, 0.5], vec![]);
//! let sol = OdeShooting::new(OdeShootingOptions::default())?.solve(&p, &guess)?;
//! assert!((sol.left()[1] - 1.0).abs() < 1e-7);
//! # Ok::<(), bvp::BvpError>(())
//! ```

use crate::linalg::DenseLu;
use crate::newton::{attach, non_finite, singular, Newton, NewtonSystem};
use crate::{Bvp, BvpError, BvpSolver, Dense, Dims, Guess, NewtonOptions, Solution, Stats, Status};
use ode_solvers::dop853::Dop853;
use ode_solvers::{DVector, OutputType, SVector, System};
use std::cell::RefCell;

/// A state vector type of `ode_solvers` usable by [`from_ode_system`].
pub trait OdeState {
    /// A zero vector of length `n`.
    fn zeros(n: usize) -> Self;
    /// The components.
    fn values(&self) -> &[f64];
    /// The components, mutable.
    fn values_mut(&mut self) -> &mut [f64];
}

impl OdeState for DVector<f64> {
    fn zeros(n: usize) -> Self {
        DVector::zeros(n)
    }
    fn values(&self) -> &[f64] {
        self.as_slice()
    }
    fn values_mut(&mut self) -> &mut [f64] {
        self.as_mut_slice()
    }
}

impl<const N: usize> OdeState for SVector<f64, N> {
    fn zeros(_n: usize) -> Self {
        SVector::zeros()
    }
    fn values(&self) -> &[f64] {
        self.as_slice()
    }
    fn values_mut(&mut self) -> &mut [f64] {
        self.as_mut_slice()
    }
}

/// A problem with an [`ode_solvers::System`] right-hand side; made by [`from_ode_system`].
pub struct OdeSystemBvp<S, G, V> {
    system: S,
    bc: G,
    n: usize,
    interval: (f64, f64),
    /// Copies of `z` and `dz` in the system's vector type (no allocation per call).
    scratch: RefCell<(V, V)>,
}

impl<S, G, V> std::fmt::Debug for OdeSystemBvp<S, G, V> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("OdeSystemBvp")
            .field("n", &self.n)
            .field("interval", &self.interval)
            .finish_non_exhaustive()
    }
}

/// The problem `y' = system(x, y)` (`n` states) on `interval` with boundary residual
/// `bc(y(a), y(b), res)` (`n` conditions, no unknown parameters; Jacobians by finite
/// differences).
pub fn from_ode_system<S, G, V>(
    system: S,
    n: usize,
    interval: (f64, f64),
    bc: G,
) -> OdeSystemBvp<S, G, V>
where
    S: System<f64, V>,
    G: Fn(&[f64], &[f64], &mut [f64]),
    V: OdeState,
{
    OdeSystemBvp {
        system,
        bc,
        n,
        interval,
        scratch: RefCell::new((V::zeros(n), V::zeros(n))),
    }
}

impl<S, G, V> Bvp for OdeSystemBvp<S, G, V>
where
    S: System<f64, V>,
    G: Fn(&[f64], &[f64], &mut [f64]),
    V: OdeState,
{
    fn dims(&self) -> Dims {
        Dims { n: self.n, k: 0 }
    }
    fn interval(&self) -> (f64, f64) {
        self.interval
    }
    fn rhs(&self, s: f64, z: &[f64], _p: &[f64], dz: &mut [f64]) {
        let mut sc = self.scratch.borrow_mut();
        let (y, dy) = &mut *sc;
        y.values_mut().copy_from_slice(z);
        self.system.system(s, y, dy);
        dz.copy_from_slice(dy.values());
    }
    fn bc(&self, za: &[f64], zb: &[f64], _p: &[f64], res: &mut [f64]) {
        (self.bc)(za, zb, res)
    }
}

/// Options of [`OdeShooting`].
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct OdeShootingOptions {
    /// Relative tolerance of `Dop853`. Default 1e-10. Valid: `(0, 1)`.
    pub rtol: f64,
    /// Absolute tolerance of `Dop853`. Default 1e-12. Valid: finite, `>= 0`.
    pub atol: f64,
    /// Step limit of one integration (`n_max` of `Dop853`). Default 100 000. Valid: `>= 1`.
    pub max_steps: u32,
    /// Newton options. Default [`NewtonOptions::default`].
    pub newton: NewtonOptions,
}

impl Default for OdeShootingOptions {
    fn default() -> Self {
        OdeShootingOptions {
            rtol: 1e-10,
            atol: 1e-12,
            max_steps: 100_000,
            newton: NewtonOptions::default(),
        }
    }
}

impl OdeShootingOptions {
    /// Checks the ranges documented on the fields.
    pub fn validate(&self) -> Result<(), BvpError> {
        let bad = |name, value: f64, reason| BvpError::InvalidOption {
            name,
            value: value.to_string(),
            reason,
        };
        if !(self.rtol > 0.0 && self.rtol < 1.0) {
            return Err(bad("rtol", self.rtol, "must be in (0, 1)"));
        }
        if !(self.atol >= 0.0 && self.atol.is_finite()) {
            return Err(bad("atol", self.atol, "must be finite and >= 0"));
        }
        if self.max_steps == 0 {
            return Err(bad("max_steps", 0.0, "must be >= 1"));
        }
        self.newton.validate()
    }
}

/// Single shooting through `ode_solvers`' `Dop853` with a forward-difference Jacobian (see the
/// [module docs](self)). Unknowns `u = (z(a), p)`; residual `g(z(a), Z(b; u), p)`.
#[derive(Clone, Debug)]
pub struct OdeShooting {
    opts: OdeShootingOptions,
    newton: Newton,
}

impl OdeShooting {
    /// Creates a solver; validates the options.
    pub fn new(opts: OdeShootingOptions) -> Result<Self, BvpError> {
        opts.validate()?;
        Ok(OdeShooting {
            opts,
            newton: Newton::new(),
        })
    }

    /// The options.
    pub fn options(&self) -> &OdeShootingOptions {
        &self.opts
    }
}

/// A [`Bvp`]'s right-hand side at fixed `p` as an `ode_solvers` system.
struct RhsOf<'a, P: ?Sized> {
    problem: &'a P,
    p: &'a [f64],
}

impl<P: Bvp + ?Sized> System<f64, DVector<f64>> for RhsOf<'_, P> {
    fn system(&self, x: f64, y: &DVector<f64>, dy: &mut DVector<f64>) {
        self.problem.rhs(x, y.as_slice(), self.p, dy.as_mut_slice());
    }
}

/// Integrates from `za` over the problem's interval; the accepted steps `(x, y)`.
fn integrate<P: Bvp + ?Sized>(
    problem: &P,
    p: &[f64],
    za: &[f64],
    opts: &OdeShootingOptions,
    stats: &mut Stats,
) -> Result<(Vec<f64>, Vec<DVector<f64>>), BvpError> {
    let (a, b) = problem.interval();
    let mut stepper = Dop853::from_param(
        RhsOf { problem, p },
        a,
        b,
        b - a,
        DVector::from_column_slice(za),
        opts.rtol,
        opts.atol,
        0.9,
        0.0,
        0.333,
        6.0,
        b - a,
        0.0,
        opts.max_steps,
        // Stiffness detection off: a BVP's trial shots are often mildly stiff, and crate's own
        // integrator has none either.
        opts.max_steps.saturating_add(1),
        OutputType::Sparse,
    );
    match stepper.integrate() {
        Ok(s) => {
            stats.rhs_evals += s.num_eval as usize;
            stats.steps += (s.accepted_steps + s.rejected_steps) as usize;
            stats.rejected_steps += s.rejected_steps as usize;
        }
        Err(e) => {
            let x = match e {
                ode_solvers::dop_shared::IntegrationError::MaxNumStepReached { x, .. }
                | ode_solvers::dop_shared::IntegrationError::StepSizeUnderflow { x }
                | ode_solvers::dop_shared::IntegrationError::StiffnessDetected { x } => x,
            };
            return Err(BvpError::StepSizeTooSmall {
                s: x,
                h: f64::NAN,
                stats: Stats::default(),
            });
        }
    }
    let (xs, ys) = stepper.results().get();
    let (xs, ys) = (xs.clone(), ys.clone());
    match (xs.last(), ys.last()) {
        (Some(&x), Some(y)) if (x - b).abs() <= 1e-12 * (b - a) => {
            if y.iter().all(|v| v.is_finite()) {
                Ok((xs, ys))
            } else {
                Err(non_finite("rhs", f64::NAN))
            }
        }
        (x, _) => Err(BvpError::StepSizeTooSmall {
            s: x.copied().unwrap_or(a),
            h: f64::NAN,
            stats: Stats::default(),
        }),
    }
}

struct OdeSystem<'a, P: ?Sized> {
    problem: &'a P,
    opts: &'a OdeShootingOptions,
    lu: DenseLu,
    r1: Vec<f64>,
    u1: Vec<f64>,
}

impl<P: Bvp + ?Sized> OdeSystem<'_, P> {
    fn eval(&self, u: &[f64], r: &mut [f64], stats: &mut Stats) -> Result<(), BvpError> {
        let n = self.problem.dims().n;
        let (za, p) = u.split_at(n);
        let (_, ys) = integrate(self.problem, p, za, self.opts, stats)?;
        let zb = ys.last().map(|y| y.as_slice()).unwrap_or(za);
        self.problem.bc(za, zb, p, r);
        stats.bc_evals += 1;
        Ok(())
    }
}

impl<P: Bvp + ?Sized> NewtonSystem for OdeSystem<'_, P> {
    fn residual(&mut self, u: &[f64], r: &mut [f64], stats: &mut Stats) -> Result<(), BvpError> {
        self.eval(u, r, stats)
    }

    fn solve_linearized(
        &mut self,
        u: &[f64],
        r: &[f64],
        du: &mut [f64],
        stats: &mut Stats,
    ) -> Result<(), BvpError> {
        let m = u.len();
        self.u1.clear();
        self.u1.extend_from_slice(u);
        self.r1.resize(m, 0.0);
        // Forward differences: one integration per unknown.
        let mut r1 = std::mem::take(&mut self.r1);
        let mut u1 = std::mem::take(&mut self.u1);
        for j in 0..m {
            let h = crate::fd::FdScheme::Forward.step(u[j]);
            u1[j] = u[j] + h;
            let res = self.eval(&u1, &mut r1, stats);
            u1[j] = u[j];
            if let Err(e) = res {
                (self.r1, self.u1) = (r1, u1);
                return Err(e);
            }
            stats.jac_evals += 1;
            let a = self.lu.matrix_mut();
            for i in 0..m {
                a[i * m + j] = (r1[i] - r[i]) / h;
            }
        }
        (self.r1, self.u1) = (r1, u1);
        stats.factorizations += 1;
        self.lu.factor().map_err(|_| singular())?;
        for (d, v) in du.iter_mut().zip(r) {
            *d = -v;
        }
        self.lu.solve(du);
        Ok(())
    }
}

impl BvpSolver for OdeShooting {
    fn solve<P: Bvp + ?Sized>(&mut self, problem: &P, guess: &Guess) -> Result<Solution, BvpError> {
        let Dims { n, k } = problem.dims();
        if guess.n != n || guess.params.len() != k || guess.z.len() != n * guess.mesh.len() {
            return Err(BvpError::Dimension {
                what: "guess (states, parameters or values)",
                got: guess.z.len(),
                expected: n * guess.mesh.len(),
            });
        }
        let (a, b) = problem.interval();
        if !(a < b && a.is_finite() && b.is_finite()) {
            return Err(BvpError::InvalidOption {
                name: "interval",
                value: format!("[{a}, {b}]"),
                reason: "need finite a < b",
            });
        }
        let mut u = vec![0.0; n + k];
        guess.eval(a, &mut u[..n]);
        u[n..].copy_from_slice(&guess.params);
        let mut stats = Stats {
            nodes: 2,
            ..Stats::default()
        };
        let mut sys = OdeSystem {
            problem,
            opts: &self.opts,
            lu: DenseLu::new(n + k),
            r1: Vec::new(),
            u1: Vec::new(),
        };
        self.newton
            .solve(&mut sys, &mut u, &self.opts.newton, &mut stats)?;
        let (za, p) = u.split_at(n);
        let (xs, ys) = integrate(problem, p, za, &self.opts, &mut stats)
            .map_err(|e| attach(e, stats.newton_iters, &stats))?;
        let mut z = Vec::with_capacity(xs.len() * n);
        let mut dz = vec![0.0; xs.len() * n];
        for (i, (x, y)) in xs.iter().zip(&ys).enumerate() {
            z.extend_from_slice(y.as_slice());
            problem.rhs(*x, y.as_slice(), p, &mut dz[i * n..(i + 1) * n]);
        }
        stats.rhs_evals += xs.len();
        Ok(Solution {
            n,
            mesh: xs,
            z,
            dz,
            params: p.to_vec(),
            status: Status::Converged,
            stats,
            dense: Dense::Hermite,
        })
    }
}
