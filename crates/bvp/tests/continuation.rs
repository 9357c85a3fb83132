//! Continuation tests (temporary mini solver while the real ones land).
use bvp::continuation::{Continuation, ContinuationOptions, FoldKind, Method, ParamBvp};
use bvp::{Bvp, BvpError, BvpSolver, Dims, Guess, Solution, Stats, Status};

/// Test-only single shooting, RK4 with fixed steps, FD Newton.
struct Mini {
    steps: usize,
}

fn rk4<P: Bvp + ?Sized>(
    pb: &P,
    za: &[f64],
    p: &[f64],
    steps: usize,
) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let n = za.len();
    let (a, b) = pb.interval();
    let h = (b - a) / steps as f64;
    let mut mesh = vec![a];
    let mut z = za.to_vec();
    let mut y = za.to_vec();
    let (mut k1, mut k2, mut k3, mut k4, mut t) = (
        vec![0.0; n],
        vec![0.0; n],
        vec![0.0; n],
        vec![0.0; n],
        vec![0.0; n],
    );
    for i in 0..steps {
        let s = a + i as f64 * h;
        pb.rhs(s, &y, p, &mut k1);
        for j in 0..n {
            t[j] = y[j] + 0.5 * h * k1[j];
        }
        pb.rhs(s + 0.5 * h, &t, p, &mut k2);
        for j in 0..n {
            t[j] = y[j] + 0.5 * h * k2[j];
        }
        pb.rhs(s + 0.5 * h, &t, p, &mut k3);
        for j in 0..n {
            t[j] = y[j] + h * k3[j];
        }
        pb.rhs(s + h, &t, p, &mut k4);
        for j in 0..n {
            y[j] += h / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]);
        }
        mesh.push(if i + 1 == steps { b } else { s + h });
        z.extend_from_slice(&y);
    }
    let mut dz = vec![0.0; z.len()];
    for (i, &s) in mesh.iter().enumerate() {
        pb.rhs(s, &z[i * n..(i + 1) * n], p, &mut dz[i * n..(i + 1) * n]);
    }
    (mesh, z, dz)
}

fn resid<P: Bvp + ?Sized>(pb: &P, x: &[f64], n: usize, steps: usize) -> Vec<f64> {
    let (_, z, _) = rk4(pb, &x[..n], &x[n..], steps);
    let m = z.len();
    let mut r = vec![0.0; x.len()];
    pb.bc(&x[..n], &z[m - n..], &x[n..], &mut r);
    r
}

impl BvpSolver for Mini {
    fn solve<P: Bvp + ?Sized>(&mut self, pb: &P, g: &Guess) -> Result<Solution, BvpError> {
        let Dims { n, k } = pb.dims();
        let (a, _) = pb.interval();
        let mut za = vec![0.0; n];
        g.eval(a, &mut za);
        let mut x = za;
        x.extend_from_slice(&g.params);
        let m = n + k;
        let mut it = 0;
        loop {
            let r = resid(pb, &x, n, self.steps);
            let rn = r.iter().fold(0.0f64, |a, b| a.max(b.abs()));
            if !rn.is_finite() {
                return Err(BvpError::NonFinite {
                    location: "rhs",
                    s: f64::NAN,
                    stats: Stats::default(),
                });
            }
            if rn < 1e-12 {
                break;
            }
            if it == 30 {
                return Err(BvpError::MaxIterations {
                    max_iter: 30,
                    residual: rn,
                    stats: Stats {
                        newton_iters: it,
                        ..Stats::default()
                    },
                });
            }
            it += 1;
            let mut jac = vec![0.0; m * m];
            for j in 0..m {
                let mut xp = x.clone();
                let hh = 1e-7 * (1.0 + x[j].abs());
                xp[j] += hh;
                let rp = resid(pb, &xp, n, self.steps);
                for i in 0..m {
                    jac[i * m + j] = (rp[i] - r[i]) / hh;
                }
            }
            // Gaussian elimination with partial pivoting.
            let mut bvec: Vec<f64> = r.iter().map(|v| -v).collect();
            for c in 0..m {
                let piv = (c..m)
                    .max_by(|&p, &q| jac[p * m + c].abs().total_cmp(&jac[q * m + c].abs()))
                    .unwrap();
                if jac[piv * m + c].abs() < 1e-14 {
                    return Err(BvpError::SingularJacobian {
                        iteration: it,
                        stats: Stats::default(),
                    });
                }
                for j in 0..m {
                    jac.swap(c * m + j, piv * m + j);
                }
                bvec.swap(c, piv);
                for i in c + 1..m {
                    let f = jac[i * m + c] / jac[c * m + c];
                    for j in c..m {
                        jac[i * m + j] -= f * jac[c * m + j];
                    }
                    bvec[i] -= f * bvec[c];
                }
            }
            for c in (0..m).rev() {
                let mut s = bvec[c];
                for j in c + 1..m {
                    s -= jac[c * m + j] * bvec[j];
                }
                bvec[c] = s / jac[c * m + c];
            }
            for j in 0..m {
                x[j] += bvec[j];
            }
        }
        let (mesh, z, dz) = rk4(pb, &x[..n], &x[n..], self.steps);
        Ok(Solution {
            n,
            mesh,
            z,
            dz,
            params: x[n..].to_vec(),
            status: Status::Converged,
            stats: Stats {
                newton_iters: it,
                ..Stats::default()
            },
        })
    }
}

struct Bratu;
impl ParamBvp for Bratu {
    fn dims(&self) -> Dims {
        Dims { n: 2, k: 0 }
    }
    fn interval(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn rhs(&self, _s: f64, z: &[f64], _p: &[f64], l: f64, dz: &mut [f64]) {
        dz[0] = z[1];
        dz[1] = -l * z[0].exp();
    }
    fn bc(&self, za: &[f64], zb: &[f64], _p: &[f64], _l: f64, r: &mut [f64]) {
        r[0] = za[0];
        r[1] = zb[0];
    }
}

#[test]
fn mini_bratu() {
    let mut solver = Mini { steps: 200 };
    let g = Guess::constant(0.0, 1.0, 11, &[0.0, 0.0], vec![]);
    let start = solver
        .solve(&bvp::continuation::Fixed::new(&Bratu, 0.1), &g)
        .unwrap();
    let opts = ContinuationOptions {
        lambda_min: 0.05,
        lambda_max: 4.0,
        ds: 0.05,
        max_steps: 200,
        fold_tol: 1e-10,
        ..Default::default()
    };
    let cont = Continuation::new(&Bratu, solver, start, 0.1, opts).unwrap();
    for p in cont {
        let p = p.unwrap();
        println!(
            "{:3} λ={:.10} σ={:.4} ds={:.3e} dl={:+.3} u'(0)={:.6} it={} {:?}",
            p.step,
            p.lambda,
            p.sigma,
            p.ds,
            p.dlambda_dsigma,
            p.solution.left()[1],
            p.stats.newton_iters,
            p.fold
                .as_ref()
                .map(|f| (f.lambda, f.located, f.evaluations, f.kind == FoldKind::Max))
        );
    }
    let _ = Method::Natural;
}

#[test]
fn mini_natural() {
    let mut solver = Mini { steps: 200 };
    let g = Guess::constant(0.0, 1.0, 11, &[0.0, 0.0], vec![]);
    let start = solver
        .solve(&bvp::continuation::Fixed::new(&Bratu, 0.1), &g)
        .unwrap();
    let opts = ContinuationOptions {
        method: Method::Natural,
        ds_min: 1e-4,
        ds: 0.1,
        max_steps: 500,
        ..Default::default()
    };
    let mut cont = Continuation::new(&Bratu, solver, start, 0.1, opts).unwrap();
    let mut n = 0;
    let mut last = 0.0;
    while let Some(p) = cont.next() {
        match p {
            Ok(p) => {
                n += 1;
                last = p.lambda;
            }
            Err(e) => {
                println!(
                    "after {n} points, last λ={last}: {e}  status {:?}",
                    e.status()
                );
            }
        }
    }
    let s = cont.point_at(1.0).unwrap();
    println!("{:?}", s.left());
}
