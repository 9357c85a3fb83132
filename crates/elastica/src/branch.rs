//! The two families of the closed forms (a module of its own: the errors, the elliptic
//! integrals and the solutions all name them, and none of those may import another back).

use serde::{Deserialize, Serialize};
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4};

/// Which family of elastica: without inflection (2.1.1) or with one flex point (2.1.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Branch {
    /// Right-handed rod, curvature `<= 0` all along (section 2.1.1, force from (2.8)).
    Convex,
    /// One flex point at `s_b`: curvature `> 0` before it, `< 0` after (section 2.1.2, (2.15)).
    OneFlex,
}

impl Branch {
    /// Admissible `alpha` range of the branch: `[-pi/2, 0]` (convex, non-empty `phi1` range only
    /// for `alpha >= -pi/4`) and `[-pi/4, 0]` (one flex, (2.13)).
    pub fn alpha_range(self) -> (f64, f64) {
        match self {
            Branch::Convex => (-FRAC_PI_2, 0.0),
            Branch::OneFlex => (-FRAC_PI_4, 0.0),
        }
    }
}
