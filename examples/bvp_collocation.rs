//! A generic boundary-value problem with crate `bvp`: Bratu's problem u'' + λ eᵘ = 0,
//! u(0) = u(1) = 0 at λ = 1, written with closures, solved by 6th-order Lobatto collocation,
//! and evaluated between the mesh nodes with the solution's dense output; compared with the
//! closed form u = −2 ln(cosh((x − ½)θ/2) / cosh(θ/4)).
//!
//! `cargo run --release --example bvp_collocation`

use bvp::samples::Bratu;
use bvp::{
    from_fns, BvpError, BvpSolver, Collocation, CollocationOptions, Guess, Scheme, Solution,
};

/// Solves the problem; returns the solution and its largest error on 1001 points.
pub fn run() -> Result<(Solution, f64), Box<BvpError>> {
    let lambda = 1.0;
    // z = (u, u'): z' = (u', −λ eᵘ)
    let bratu = from_fns(
        2,
        (0.0, 1.0),
        move |_s, z, _p, dz| {
            dz[0] = z[1];
            dz[1] = -lambda * z[0].exp();
        },
        |za, zb, _p, res| {
            res[0] = za[0];
            res[1] = zb[0];
        },
    );
    let opts = CollocationOptions {
        scheme: Scheme::Lobatto6,
        tol: 1e-8,
        ..CollocationOptions::default()
    };
    let guess = Guess::constant(0.0, 1.0, 11, &[0.0, 0.0], vec![]);
    let sol = Collocation::new(opts)?.solve(&bratu, &guess)?;
    println!("{} nodes, {}", sol.len(), sol.stats);
    // dense output: anywhere in [0, 1], not only at the nodes
    let exact = Bratu { lambda };
    let mut worst: f64 = 0.0;
    let mut z = [0.0; 2];
    for i in 0..=1000 {
        let s = i as f64 / 1000.0;
        sol.eval(s, &mut z);
        worst = worst.max((z[0] - exact.exact(0, s)[0]).abs());
    }
    println!(
        "u(0.5) = {:.12} (closed form {:.12}); largest error on 1001 points {worst:.2e}",
        sol.at(0.5)[0],
        exact.exact(0, 0.5)[0]
    );
    Ok((sol, worst))
}

#[allow(dead_code)] // the tests call `run`
fn main() {
    if let Err(e) = run() {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}
