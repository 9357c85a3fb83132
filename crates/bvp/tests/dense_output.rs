//! The dense output at the ends of a mesh whose end interval has shrunk to a point (a repeated
//! end node, as a path whose last segment has zero length): the value of the interval of positive
//! length before it, not 0/0.

use bvp::{Solution, Status};

fn quadratic(mesh: Vec<f64>) -> Solution {
    // z = s², z' = 2s: the cubic Hermite interpolant is exact
    let z = mesh.iter().map(|s| s * s).collect();
    let dz = mesh.iter().map(|s| 2.0 * s).collect();
    Solution {
        n: 1,
        mesh,
        z,
        dz,
        params: vec![],
        status: Status::Converged,
        stats: Default::default(),
        dense: Default::default(),
    }
}

#[test]
fn a_repeated_end_node_is_evaluated_on_its_neighbour() {
    let sol = quadratic(vec![0.0, 0.0, 0.5, 1.0, 1.0]);
    let mut out = [0.0];
    for s in [0.0, 0.25, 0.5, 0.75, 1.0] {
        sol.eval(s, &mut out);
        assert!((out[0] - s * s).abs() < 1e-15, "z({s}) = {}", out[0]);
    }
}
