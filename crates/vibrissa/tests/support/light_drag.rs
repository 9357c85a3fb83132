//! The dynamic-drag tests' discretization (tests/dynamic_drag.rs, tests/dynamic_surfaces.rs).

use vibrissa::dynamics::DynDragOptions;

/// The test drags' discretization: collocation tol 1e-8 on a history grid of 100 intervals
/// (the first slip of the paper's rod at v = 0.05, dt = 0.02 moves by 1.3e-9 from tol 1e-10 on
/// 200 intervals; 3.1 times faster).
pub fn light(speed: f64, dt: f64, d_max: f64) -> DynDragOptions {
    DynDragOptions {
        speed,
        dt,
        d_max,
        tol: 1e-8,
        grid: 100,
        ..DynDragOptions::default()
    }
}
