"""PyElastica as a benchmark peer (issue 32): the dynamic drag, its first slip and its 10 slips.

The scene of the bench group `dynamic_drag` (crates/vibrissa/benches/dynamics.rs, `ten_slips`)
and of `vibrissa::dynamics::drag`, in its units (EI = 1, rho*A = 1, L = 1): the uniform rod
clamped at its foot, leaving it straight up (+y); the flat surface y = eta = 0.75 above the
foot; the tip pressed up against it, with Coulomb friction mu_s = 0.5, mu_k = 0.3. The foot moves
along +x, d(t) = v*ramp*u^4 (5/2 - 3u + u^2) with u = t/ramp on the ramp (its speed rising as
v (10u^3 - 15u^4 + 6u^5)), then v*ramp/2 + v (t - ramp); v = 0.05, ramp = 2.

As a PyElastica Cosserat rod (as benches/pyelastica_free.py): a circular section of radius r
(I = pi r^4 / 4, A = pi r^2), E = 1/I, rho = 1/A, PyElastica's default shear modulus (nu = 0.5),
n elements, stepped by PositionVerlet at a fixed step (below the explicit bounds of the free
script: min(0.4 r^2, dx r / 4)). The foot: a constraint of this script that sets the first node
to (d(t), 0) with velocity (d'(t), 0) and the first element's directors to the vertical
(OneEndFixedBC's clamp, moved). The tip: its node is held on the surface (y = eta, v_y = 0: a
bilateral constraint, as vibrissa's y(1) = eta; the normal force does not fall to zero in this
drag); the surface's reaction on the tip node is R = -F (F the rod's internal force on that
node, which PyElastica computes before the external forces of each stage): N = F_y, T = F_x
(T > 0: the surface holds the tip back against +x; mu = T/N as vibrissa's).

Friction: a stick-slip switch tested at every step, not a regularized law (no regularization
velocity or stiffness). Stuck: a constraint holds the tip node at its x; it slips where |T|
reaches mu_s N, in the direction dir = sign T (its place d interpolated linearly between the two
steps around the zero of |T| - mu_s N). Sliding: the force -dir mu_k N on the tip node along x
(a forcing class); it sticks at the first step where dir v_x is zero or below (its place
interpolated linearly in v_x). Stiction is thus exact up to the step, as vibrissa's, whose
events are located inside the step instead; a regularized Coulomb law (tanh(v/v_reg)) would
make the stuck tip creep.

The start: the Euler-Bernoulli pressed equilibrium (the clamped rod with its tip at height eta
and the force on it normal to the surface, by scipy's solve_bvp: N = 2.8266222292, tip
x = 0.5847792847, as the first row of `vibrissa dynamics drag --speed 0.05`), put on the nodes
(the element directors along the chords, the first one vertical), then settled, not timed:
the foot fixed, the tip held on the surface but free along it (no friction), the velocities
scaled by 0.3 every step for 0.02 time units (the start's shear and stretch relax, the shape
stays), then by exp(-40 dt) to 1.5 time units. That is the Cosserat rod's own pressed state
at rest with the force normal to the surface (r 0.02: N = 2.948 at 25 elements, 2.886 at 50;
|T| < 1e-4); there the tip sticks and the drag starts, timed, without damping (vibrissa's rod
has none), until `--events` events (slips and sticks; default 20, the bench's 10 slips each with
the stick that ends it; 1: the first slip).

Output, CSV on stdout, one row per (r, elements, dt):

    r,elements,dt,steps,slips,seconds,cpu,slip_d,stick_d

(`seconds` the wall time of the drag's loop, `cpu` its `time.process_time()`, the figure to
compare on a shared, loaded machine; slip_d, stick_d the foot displacements d of the slip
onsets and of the sticks, space-separated.) The errors against vibrissa's converged first slip,
and why the later slips are not compared: docs/performance.md.

Run (PyElastica 1.0 from PyPI, scipy; not dependencies of the project):

    python3 -m venv /tmp/pye && /tmp/pye/bin/pip install pyelastica scipy
    /tmp/pye/bin/python benches/pyelastica_drag.py --events 1     # first slip, r 0.02, 25-400 elements (1 min)
    /tmp/pye/bin/python benches/pyelastica_drag.py --events 1 --r 0.01 --elements 25,50,100,200,400
    /tmp/pye/bin/python benches/pyelastica_drag.py --elements 25,50,100   # the 10 slips
    /tmp/pye/bin/python benches/pyelastica_drag.py --quick        # one row, 25 elements
    /tmp/pye/bin/python benches/pyelastica_drag.py --d-max 0.4 --elements 25,50,100,200,400,800
        # the drag over the foot's travel 0..0.4 (the span of vibrissa's ten slips) at each
        # resolution, whatever its events (7 min; data/dynamics/pyelastica_drag_span.csv)

The same drag of ours: `cargo run --release -p vibrissa --example drag_slips` and the criterion
bench `cargo bench -p vibrissa --bench dynamics` (group `dynamic_drag`).
"""

import math
import sys
import time

import numpy as np
import elastica as ea
from scipy.integrate import solve_bvp

from pyelastica_rod import option, stable_dt, unit_rod

ETA = 0.75
MU_S = 0.5
MU_K = 0.3
SPEED = 0.05
RAMP = 2.0
SLIPS = 10


def foot_at(t):
    """The foot's place d(t) and speed d'(t) (vibrissa's DynDragOptions::foot_at)."""
    if t >= RAMP:
        return SPEED * RAMP / 2.0 + SPEED * (t - RAMP), SPEED
    u = t / RAMP
    return SPEED * RAMP * u**4 * (2.5 - 3.0 * u + u * u), SPEED * (10 * u**3 - 15 * u**4 + 6 * u**5)


def pressed(n):
    """The Euler-Bernoulli pressed state: (x, y, phi) at s = i/n, the normal force N, tip x.

    x' = cos phi, y' = sin phi, phi' = m, m' = N cos phi; x(0) = y(0) = 0, phi(0) = pi/2,
    m(1) = 0, y(1) = eta (the force on the tip (0, -N): normal to the surface)."""

    def f(s, z, p):
        return np.vstack([np.cos(z[2]), np.sin(z[2]), z[3], p[0] * np.cos(z[2])])

    def bc(a, b, p):
        return np.array([a[0], a[1], a[2] - math.pi / 2, b[3], b[1] - ETA])

    s = np.linspace(0.0, 1.0, 201)
    phi = math.pi / 2 - 1.5 * s
    guess = np.vstack([np.zeros_like(s), s, phi, -1.6 * (1 - s)])
    sol = solve_bvp(f, bc, s, guess, p=[2.8], tol=1e-10, max_nodes=100000)
    if not sol.success:
        raise RuntimeError(f"the pressed start: {sol.message}")
    z = sol.sol(np.linspace(0.0, 1.0, n + 1))
    return z[0], z[1], z[2], sol.p[0], sol.y[0, -1]


class Sim(ea.BaseSystemCollection, ea.Constraints, ea.Forcing):
    pass


class Contact:
    """The tip's state shared by the foot-and-tip constraint and the friction force."""

    def __init__(self, anchor):
        self.moving = False  # the foot moves (the drag) or not (the settle: the tip slides freely)
        self.stuck = False
        self.dir = 0.0
        self.anchor = anchor
        self.g_prev = None  # |T| - mu_s N and d at the last stuck step
        self.d_prev = 0.0
        self.slips = []
        self.sticks = []
        self.v_prev = 0.0  # the sliding tip's dir * v_x and d at the last step
        self.dv_prev = 0.0


class Drive(ea.ConstraintBase):
    """The foot moved and clamped; the tip on the surface, held at its x while stuck."""

    def __init__(self, contact, director, **kwargs):
        super().__init__(**kwargs)
        self.c = contact
        self.director = director.copy()

    def constrain_values(self, system, time):
        rod = system
        d = foot_at(time)[0] if self.c.moving else 0.0
        rod.position_collection[0, 0] = d
        rod.position_collection[1, 0] = 0.0
        rod.position_collection[2, 0] = 0.0
        rod.director_collection[..., 0] = self.director
        rod.position_collection[1, -1] = ETA
        if self.c.stuck:
            rod.position_collection[0, -1] = self.c.anchor

    def constrain_rates(self, system, time):
        rod = system
        v = foot_at(time)[1] if self.c.moving else 0.0
        rod.velocity_collection[:, 0] = (v, 0.0, 0.0)
        rod.omega_collection[:, 0] = 0.0
        rod.velocity_collection[1, -1] = 0.0
        c = self.c
        if c.moving and not c.stuck:
            w, d = c.dir * rod.velocity_collection[0, -1], foot_at(time)[0]
            if w <= 0.0:
                c.stuck = True
                at = d
                if c.v_prev > 0.0:
                    at = c.dv_prev + (d - c.dv_prev) * c.v_prev / (c.v_prev - w)
                c.sticks.append(at)
                c.anchor = rod.position_collection[0, -1]
                c.g_prev = None
            else:
                c.v_prev, c.dv_prev = w, d
        if c.stuck:
            rod.velocity_collection[0, -1] = 0.0


class Friction(ea.NoForces):
    """Coulomb friction on the tip node: the slip test while stuck, -dir mu_k N while sliding."""

    def __init__(self, contact):
        super().__init__()
        self.c = contact

    def apply_forces(self, system, time=0.0):
        rod = system
        c = self.c
        t_force = rod.internal_forces[0, -1]
        n_force = rod.internal_forces[1, -1]
        if not c.moving:
            return
        if c.stuck:
            g = abs(t_force) - MU_S * n_force
            d = foot_at(time)[0]
            if g >= 0.0:
                c.stuck = False
                c.dir = 1.0 if t_force >= 0.0 else -1.0
                at = d
                if c.g_prev is not None and c.g_prev < 0.0:
                    at = c.d_prev + (d - c.d_prev) * (-c.g_prev) / (g - c.g_prev)
                c.slips.append(at)
                c.v_prev, c.dv_prev = 0.0, at
            else:
                c.g_prev, c.d_prev = g, d
                return
        rod.external_forces[0, -1] += -c.dir * MU_K * n_force

    def apply_torques(self, system, time=0.0):
        pass


def t_of(d):
    """The time at which the foot has moved by `d` (past the ramp: d = v ramp/2 + v (t - ramp))."""
    return RAMP + (d - SPEED * RAMP / 2.0) / SPEED


def run(r, n, dt, events=2 * SLIPS, settle=1.5, damping=40.0, d_max=0.45):
    x, y, phi, normal, tip_x = pressed(n)
    sim = Sim()
    rod = unit_rod(n, r, [0.0, 1.0, 0.0], [1.0, 0.0, 0.0])
    foot_director = rod.director_collection[..., 0].copy()
    rod.position_collection[0, :] = x
    rod.position_collection[1, :] = y
    # element directors along the chords: d3 the tangent, d1 its normal, d2 = -z
    th = np.arctan2(np.diff(y), np.diff(x))
    rod.director_collection[0, 0, :] = np.sin(th)
    rod.director_collection[0, 1, :] = -np.cos(th)
    rod.director_collection[2, 0, :] = np.cos(th)
    rod.director_collection[2, 1, :] = np.sin(th)
    rod.director_collection[..., 0] = foot_director
    sim.append(rod)
    contact = Contact(tip_x)
    sim.constrain(rod).using(Drive, contact=contact, director=foot_director)
    sim.add_forcing_to(rod).using(Friction, contact=contact)
    sim.finalize()
    stepper = ea.PositionVerlet()
    t = 0.0
    # first overdamped (velocities times 0.3 every step, 0.02 time units: the start's mismatch
    # of shear and stretch relaxes while the shape stays), then the damping c
    for k in range(int(math.ceil(settle / dt))):
        t = stepper.step(sim, t, dt)
        decay = 0.3 if k * dt < 0.02 else math.exp(-damping * dt)
        rod.velocity_collection *= decay
        rod.omega_collection *= decay
    rod.velocity_collection[:] = 0.0
    rod.omega_collection[:] = 0.0
    contact.moving = True
    contact.stuck = True
    contact.anchor = rod.position_collection[0, -1]
    t = 0.0
    steps = 0
    t_end = t_of(d_max)
    t0, c0 = time.perf_counter(), time.process_time()
    while t < t_end and len(contact.slips) + len(contact.sticks) < events:
        t = stepper.step(sim, t, dt)
        steps += 1
    seconds = time.perf_counter() - t0
    cpu = time.process_time() - c0
    return steps, contact, seconds, cpu


def main():
    quick = "--quick" in sys.argv
    radii = option("--r", [0.02])
    elements = [int(n) for n in option("--elements", [25] if quick else [25, 50, 100, 200, 400])]
    scale = option("--dt-scale", [1.0])[0]
    events = int(option("--events", [2 * SLIPS])[0])
    # `--d-max D`: the drag over the foot's travel 0..D whatever its events (the span the ten
    # slips of vibrissa's drag take), not to its 20th event
    d_max = option("--d-max", [0.0])[0]
    if d_max > 0.0:
        events = 10**9
    cases = []
    for r in radii:
        for n in elements:
            cases.append((r, n, scale * stable_dt(r, n)))
    # warm numba's compilation outside the timed runs
    run(0.02, 10, 1e-4, events=1, settle=0.01)
    print("r,elements,dt,steps,slips,seconds,cpu,slip_d,stick_d")
    for r, n, dt in cases:
        steps, c, seconds, cpu = run(r, n, dt, events=events, d_max=d_max or 0.45)
        # over a span (`--d-max`) the switch chatters (hundreds to thousands of slips): the
        # first ten places of each are written, `slips` counts them all
        keep = 10 if d_max > 0.0 else None
        ds = " ".join(f"{d:.10f}" for d in c.slips[:keep])
        ks = " ".join(f"{d:.10f}" for d in c.sticks[:keep])
        print(f"{r},{n},{dt:.3e},{steps},{len(c.slips)},{seconds:.3f},{cpu:.3f},{ds},{ks}", flush=True)
        if seconds > 600:
            break


if __name__ == "__main__":
    main()
