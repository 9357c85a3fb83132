//! The static rod of a turned clamp with its tip pinned: the independent reference of the whisk
//! against a surface (tests/dynamic_drag.rs, tests/drag_turn.rs). The uniform rod throughout.

use vibrissa::{solve, BranchChoice, Rod, SolverConfig, Target};

/// The static rod of the clamp turned clockwise by `theta` with its tip pinned at the lab point
/// `(x, y)`: `solve` with the tip's place seen from the clamp turned back upright
/// (counter-clockwise by `theta`; the rod's internal force is in that frame too).
pub fn turned_static(x: f64, y: f64, theta: f64) -> vibrissa::Shape {
    let (sn, cs) = theta.sin_cos();
    let (x1, y1) = (x * cs - y * sn, x * sn + y * cs);
    solve(
        &Rod::uniform(),
        -theta,
        Target::Tip { x1, y1 },
        &BranchChoice::Convex,
        &SolverConfig::default(),
    )
    .unwrap()
}

/// `T/N` the tip pinned at `(x, y)` needs on the flat surface through it, the clamp turned by
/// `theta` ([`turned_static`], its internal force turned back clockwise into the lab frame:
/// `N = −G_y`, `T = −G_x`).
pub fn pinned_ratio(x: f64, y: f64, theta: f64) -> f64 {
    let q = turned_static(x, y, theta);
    let (sn, cs) = theta.sin_cos();
    let (gx, gy) = (q.fx * cs + q.fy * sn, -q.fx * sn + q.fy * cs);
    -gx / -gy
}

/// The turn in `(lo, hi)` at which the rod, its tip pinned at `(x_a, eta)`, needs `T/N = mu`
/// (the ratio rising through it): bisection to the last bit.
pub fn turn_at_ratio(x_a: f64, eta: f64, mu: f64, (mut lo, mut hi): (f64, f64)) -> f64 {
    let ratio = |theta: f64| pinned_ratio(x_a, eta, theta);
    assert!(ratio(lo) < mu && ratio(hi) > mu);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if ratio(mid) < mu {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}
