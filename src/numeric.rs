//! The library side of the program: scene parts, solver settings, one solve.

use crate::cli::{BranchArg, MethodArg, SolveArgs};
use crate::error::{Fail, Res};
use crate::solve::{branch_name, ShapeRow, SolveOut};
use vibrissa::{BranchChoice, Method, Rod, Scene, SolverConfig, Surface, Target, VibrissaError};

impl From<VibrissaError> for Fail {
    fn from(e: VibrissaError) -> Fail {
        let msg = e.to_string();
        match e {
            VibrissaError::OutOfRange { .. }
            | VibrissaError::InvalidTable { .. }
            | VibrissaError::MethodUnavailable { .. }
            | VibrissaError::NotMeasurable { .. }
            | VibrissaError::RangeCutShort { .. }
            | VibrissaError::NoContact { .. }
            | VibrissaError::OutOfReach { .. }
            | VibrissaError::InvalidName { .. } => Fail::Usage(msg),
            VibrissaError::Elastica { source, .. } => match Fail::from(source) {
                Fail::Usage(_) => Fail::Usage(msg),
                Fail::Solve(_) | Fail::Closed => Fail::Solve(msg),
            },
            _ => Fail::Solve(msg),
        }
    }
}

/// The library's method for a CLI method.
pub fn method(m: MethodArg) -> Method {
    match m {
        MethodArg::Shooting => Method::Shooting,
        MethodArg::MultipleShooting => Method::MultipleShooting,
        MethodArg::Collocation => Method::Collocation4,
        MethodArg::Collocation6 => Method::Collocation6,
        MethodArg::Analytic => Method::Analytic,
    }
}

/// Solver configuration from the CLI flags.
pub fn config(m: MethodArg, tol: f64) -> SolverConfig {
    SolverConfig {
        method: method(m),
        tol,
        ..SolverConfig::default()
    }
}

/// The validated parts of a scene: the rod and the surface.
pub fn parts(scene: &Scene) -> Res<(Rod, Surface)> {
    Ok(scene.parts()?)
}

/// Solve of one rod, by any method.
pub fn solve(scene: &Scene, a: &SolveArgs, npts: usize) -> Res<SolveOut> {
    let rod = scene.rod()?;
    let target = match (a.phi1, a.eta) {
        (Some(p), _) => Target::Phi1(p),
        (None, Some(h)) => Target::Eta(h),
        (None, None) => return Err(crate::error::usage("give --phi1 or --eta")),
    };
    let branch = match a.branch {
        BranchArg::Convex => BranchChoice::Convex,
        BranchArg::Flex => BranchChoice::Flex,
        BranchArg::Any => BranchChoice::Any,
    };
    let cfg = SolverConfig {
        start: scene.start,
        ..config(a.solver.method, a.solver.tol)
    };
    let alpha = a.alpha.unwrap_or(0.0);
    let sh = vibrissa::solve(&rod, alpha, target, &branch, &cfg)?;
    let clearance = sh.clearance(scene.surface_angle);
    let shape = if npts >= 2 {
        sh.samples(npts)
            .into_iter()
            .map(|p| ShapeRow {
                s: p.s,
                x: p.x,
                y: p.y,
                phi: p.phi,
                kappa: p.kappa,
                m: p.m,
            })
            .collect()
    } else {
        Vec::new()
    };
    Ok(SolveOut {
        method: a.solver.method.name(),
        branch: branch_name(a.branch),
        alpha: sh.alpha,
        phi1: sh.phi1,
        f: sh.f,
        fx: sh.fx,
        fy: sh.fy,
        x1: sh.x1,
        y1: sh.y1,
        m_base: sh.m_base,
        flex: sh.flex,
        load_reversals: sh.load_reversals,
        s_flex: sh.s_flex,
        y_max: sh.y_max,
        residual: sh.residual,
        penetration: clearance.penetrates(),
        clearance,
        physical: None,
        shape,
    })
}
