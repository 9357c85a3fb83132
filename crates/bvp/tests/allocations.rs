//! Heap allocations of whole solves, counted by a global allocator per thread: the Newton and
//! integration loops must not allocate, for slice-based ([`Bvp`]) and array-based ([`FixedBvp`])
//! problems.
//!
//! A warm solver (buffers sized by an earlier solve) allocates only the returned [`Solution`]:
//! with RK4 that is a fixed handful of vectors however many steps and Newton iterations the solve
//! takes; with the adaptive pair the output vectors grow with the (unknown) step count, so
//! `O(log steps)` reallocations. One allocation per step or per iteration would show up as
//! hundreds.
//!
//! The counter is thread-local, so allocations of other threads (the test harness, other tests,
//! anything else in the process) are not counted: only the solving thread's own.

use bvp::fixed::{Fixed, SimpleBvp};
use bvp::samples::{Bratu, Cantilever};
use bvp::{Bvp, BvpSolver, Guess, Integrator, Shooting, ShootingOptions, Solution};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

struct Counting;

thread_local! {
    // Const-initialized and without destructor: accessing it never allocates.
    static ALLOCS: Cell<usize> = const { Cell::new(0) };
}

/// Counts one allocation of the calling thread (ignored while the thread is torn down).
fn count() {
    let _ = ALLOCS.try_with(|c| c.set(c.get() + 1));
}

/// Allocations made so far by the calling thread.
fn allocs() -> usize {
    ALLOCS.with(Cell::get)
}

// SAFETY: forwards to the system allocator; only counts calls.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count();
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count();
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Bratu's problem written with arrays (a parameter-free [`SimpleBvp`], through the blanket
/// [`FixedBvp`] implementation); the same arithmetic as [`Bratu`].
struct FixedBratu(f64);

impl SimpleBvp<2> for FixedBratu {
    fn interval(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn rhs(&self, _s: f64, z: &[f64; 2]) -> [f64; 2] {
        [z[1], -self.0 * z[0].exp()]
    }
    fn bc(&self, za: &[f64; 2], zb: &[f64; 2]) -> [f64; 2] {
        [za[0], zb[0]]
    }
    fn rhs_jacobian(&self, _s: f64, z: &[f64; 2], dfdz: &mut [[f64; 2]; 2]) -> bool {
        *dfdz = [[0.0, 1.0], [-self.0 * z[0].exp(), 0.0]];
        true
    }
    fn bc_jacobian(
        &self,
        _za: &[f64; 2],
        _zb: &[f64; 2],
        dga: &mut [[f64; 2]; 2],
        dgb: &mut [[f64; 2]; 2],
    ) -> bool {
        *dga = [[1.0, 0.0], [0.0, 0.0]];
        *dgb = [[0.0, 0.0], [1.0, 0.0]];
        true
    }
}

/// Allocations made by one solve, and the solution.
fn counted<P: Bvp>(solver: &mut Shooting, p: &P, g: &Guess) -> (usize, Solution) {
    let before = allocs();
    let sol = solver.solve(p, g).expect("solve");
    (allocs() - before, sol)
}

fn rk4(steps: usize, segments: usize) -> Shooting {
    Shooting::new(ShootingOptions {
        integrator: Integrator::Rk4 { steps },
        segments,
        ..Default::default()
    })
    .unwrap()
}

#[test]
fn solves_do_not_allocate_in_their_loops() {
    let bratu = Bratu { lambda: 1.0 };
    let fixed = Fixed(FixedBratu(1.0));

    // The array form is the same problem, bit for bit.
    for steps in [50, 400] {
        let a = rk4(steps, 1).solve(&bratu, &bratu.guess()).unwrap();
        let b = rk4(steps, 1).solve(&fixed, &bratu.guess()).unwrap();
        assert_eq!(a.z, b.z);
        assert_eq!(a.stats.newton_iters, b.stats.newton_iters);
    }

    // RK4: the count does not depend on steps, segments or Newton iterations.
    let mut counts = Vec::new();
    for segments in [1, 4] {
        for steps in [40, 4000] {
            let mut s = rk4(steps, segments);
            let _ = counted(&mut s, &bratu, &bratu.guess()); // sizes the buffers
            for guess in [bratu.guess(), Bratu::guess_upper(&bratu)] {
                let (slice, sl) = counted(&mut s, &bratu, &guess);
                let (array, sa) = counted(&mut s, &fixed, &guess);
                eprintln!(
                    "rk4 {steps} steps, {segments} segments: {slice} / {array} allocations, \
                     {} Newton iterations, {} rhs evaluations",
                    sl.stats.newton_iters, sl.stats.rhs_evals
                );
                assert!(sl.stats.newton_iters >= 2 && sa.stats.newton_iters >= 2);
                counts.push(slice);
                counts.push(array);
            }
        }
    }
    assert!(
        counts.iter().all(|&c| c == counts[0]) && counts[0] <= 8,
        "RK4 solve allocations vary or are many: {counts:?}"
    );

    // Adaptive DOP853, four states and a stiff-ish load: only output growth.
    let cant = Cantilever { load: 3.0 };
    for tol in [1e-6, 1e-12] {
        let mut s = Shooting::new(ShootingOptions {
            integrator: Integrator::Adaptive {
                rtol: tol,
                atol: tol,
            },
            segments: 4,
            ..Default::default()
        })
        .unwrap();
        let _ = counted(&mut s, &cant, &cant.guess());
        let (allocs, sol) = counted(&mut s, &cant, &cant.guess());
        let steps = sol.mesh.len() as f64;
        let bound = 8 + 3 * (steps.log2().ceil() as usize + 1);
        eprintln!(
            "dop853 tol {tol:e}: {allocs} allocations for {} nodes, {} Newton iterations \
             (bound {bound})",
            sol.mesh.len(),
            sol.stats.newton_iters
        );
        assert!(sol.stats.newton_iters >= 2);
        assert!(allocs <= bound, "{allocs} allocations > {bound}");
    }
}
