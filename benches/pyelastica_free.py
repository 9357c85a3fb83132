"""PyElastica as a benchmark peer (issue 32): the uniform clamped-free rod's free oscillation.

The same rod as `vibrissa::dynamics::free` in its units (EI = 1, rho*A = 1, L = 1, so the first
frequency is beta_1^2 = 3.51601526..., Blevins table 8-1) as a PyElastica Cosserat rod: a circular
section of radius r (I = pi r^4 / 4, A = pi r^2), E = 1/I, rho = 1/A, shear modulus E/(2(1 + nu))
with nu = 0.5 (PyElastica's default), clamped at s = 0 (OneEndFixedBC), released from the straight
rest shape with a small velocity in the first mode's shape (amplitude 1e-4 at the tip), stepped by
PyElastica's PositionVerlet at a fixed step (the sections' angular velocity from the same mode). The period is read off the tip's first upward zero
crossing after the start (linear interpolation between steps) and compared with 2 pi / beta_1^2.

A Cosserat rod is shearable, extensible and has rotary inertia, so its frequency differs from the
Euler-Bernoulli one by O((r/L)^2) (about 1e-4 at r = 0.01); its explicit time step is bounded by
the fastest wave: the section's rotation against shear, omega = sqrt(G A / (rho I)) = 2.31 / r^2
(independent of the elements), so dt < 2 / omega = 0.87 r^2 (dt = 0.4 r^2 here; 1e-4 at r = 0.01
blows up), and the axial wave, dt < dx / sqrt(E/rho) = dx r / 2. Both costs are the peer's, and both are in the
error-against-time curve this script prints: one row per (r, elements, dt), CSV on stdout:

    r,elements,dt,steps,period,error,seconds

(`seconds` the wall time of the stepping loop; its CPU time, `time.process_time()`, goes to stderr,
one line per row: on a shared, loaded machine that is the figure to compare.)

Run (PyElastica 1.0 from PyPI; not a dependency of the project):

    python3 -m venv /tmp/pye && /tmp/pye/bin/pip install pyelastica
    /tmp/pye/bin/python benches/pyelastica_free.py            # about 10 minutes on one core
    /tmp/pye/bin/python benches/pyelastica_free.py --quick    # two rows
    /tmp/pye/bin/python benches/pyelastica_free.py --r 0.02 --elements 200,400,800   # chosen rows

The same study of ours: `cargo run --release -p vibrissa --example free_oscillation` and the
criterion bench `cargo bench -p vibrissa --bench dynamics`; docs/performance.md compares them.
"""

import math
import sys
import time

import numpy as np
import elastica as ea

from pyelastica_rod import option, stable_dt, unit_rod

BETA1 = 1.87510406871196
OMEGA1 = BETA1**2
PERIOD = 2.0 * math.pi / OMEGA1


def mode1(s):
    b = BETA1
    sigma = (math.cosh(b) + math.cos(b)) / (math.sinh(b) + math.sin(b))
    w = lambda x: np.cosh(b * x) - np.cos(b * x) - sigma * (np.sinh(b * x) - np.sin(b * x))
    return w(s) / w(1.0)


class Sim(ea.BaseSystemCollection, ea.Constraints):
    pass


def run(r, n, dt, amp=1e-4):
    sim = Sim()
    rod = unit_rod(n, r, [1.0, 0.0, 0.0], [0.0, 1.0, 0.0])
    sim.append(rod)
    sim.constrain(rod).using(ea.OneEndFixedBC, constrained_position_idx=(0,), constrained_director_idx=(0,))
    sim.finalize()
    s = np.linspace(0.0, 1.0, n + 1)
    rod.velocity_collection[1, :] = amp * mode1(s)
    rod.velocity_collection[1, 0] = 0.0
    # the sections turn with the centre line: angular velocity d(v_y)/ds about the binormal
    # (directors d1 = normal y, d2 = binormal z, d3 = tangent x; omega in the material frame)
    rod.omega_collection[1, :] = amp * np.diff(mode1(s)) * n
    stepper = ea.PositionVerlet()
    steps = int(math.ceil(1.6 * PERIOD / dt))
    t = 0.0
    y_prev = 0.0
    crossings = []
    t0, c0 = time.perf_counter(), time.process_time()
    for _ in range(steps):
        t = stepper.step(sim, t, dt)
        y = rod.position_collection[1, -1]
        if y_prev < 0.0 <= y:
            crossings.append(t - dt + dt * (-y_prev) / (y - y_prev))
        y_prev = y
    seconds = time.perf_counter() - t0
    cpu = time.process_time() - c0
    period = crossings[0] if crossings else float("nan")
    return steps, period, seconds, cpu


def main():
    quick = "--quick" in sys.argv
    cases = []
    radii = option("--r", [0.01] if quick else [0.02, 0.01, 0.005])
    elements = [int(n) for n in option("--elements", [25] if quick else [25, 50, 100, 200])]
    for r in radii:
        for n in elements:
            cases.append((r, n, stable_dt(r, n)))
    if quick:
        cases = cases[:2]
    # warm numba's compilation outside the timed runs
    run(0.02, 10, 1e-3, amp=1e-4)
    print("r,elements,dt,steps,period,error,seconds")
    for r, n, dt in cases:
        steps, period, seconds, cpu = run(r, n, dt)
        err = abs(period / PERIOD - 1.0)
        print(f"{r},{n},{dt:.3e},{steps},{period:.10f},{err:.3e},{seconds:.3f}", flush=True)
        print(f"r {r}, {n} elements: {cpu:.3f} s CPU time of the process", file=sys.stderr, flush=True)
        if seconds > 300:
            break


if __name__ == "__main__":
    main()
