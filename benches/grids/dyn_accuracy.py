#!/usr/bin/env python3
"""Accuracy against cost of the drag in time through the program's own flags (issue 32: a user
trades speed for accuracy): `vibrissa dynamics drag` of the paper's rod (eta 0.75, mu_s 0.5,
mu_k 0.3) at --speed 0.05 to --d-max 0.045, through its first slip and first stick, for every
time step --dt and every pair of the history grid in s and the steps' tolerance (--grid, --tol).

Usage: python3 benches/grids/dyn_accuracy.py [--bin target/release/vibrissa]
           [--out data/dynamics/accuracy.csv]

The first slip's error is against its limit dt -> 0, d = 0.021003157884 (Richardson's
extrapolation of the runs at grid 200, tol 1e-12, second order in dt: `cargo run --release -p
vibrissa --example drag_slips -- --reference`); the first stick's against the finest run, dt
0.00125 with grid 200, tol 1e-12 (the last row), whose own stick moved by 7.6e-6 from dt 0.0025:
below 1e-5 the table does not resolve the stick's error. One run at a time;
cpu_s is the run's user + system CPU time (os.wait4), the only column that differs between
runs of the same build. Columns: dt, grid, tol, slip_d, stick_d, slip_error, stick_error
(against the limit and the reference), steps, newton_iterations, max_nodes, cpu_s.
"""
import argparse, csv, json, sys

from timed import run_timed

DTS = ["0.1", "0.05", "0.02", "0.01", "0.005", "0.0025"]
SPACE = [("20", "1e-6"), ("50", "1e-8"), ("100", "1e-8"), ("200", "1e-10"), ("200", "1e-12")]
REFERENCE = ("0.00125", "200", "1e-12")
SLIP_LIMIT = 0.021003157884
COMMON = ["dynamics", "drag", "--speed", "0.05", "--d-max", "0.045", "--json"]
COLUMNS = ["dt", "grid", "tol", "slip_d", "stick_d", "slip_error", "stick_error", "steps",
           "newton_iterations", "max_nodes", "cpu_s"]


def run(binary, dt, grid, tol):
    cmd = [binary, *COMMON, "--dt", dt, "--grid", grid, "--tol", tol]
    code, timed_out, stdout, stderr, cpu = run_timed(cmd, 3600)
    if code != 0 or timed_out:
        sys.exit(f"{' '.join(cmd)} failed: {stderr.strip()}")
    r = json.loads(stdout)
    place = {}
    for e in r["events"]:
        place.setdefault(e["kind"], e["d"])
    if r["stop"]["reason"] != "d_max" or "slip" not in place or "stick" not in place:
        sys.exit(f"{' '.join(cmd)}: no slip and stick before d_max: {r['stop']}")
    return dict(dt=dt, grid=grid, tol=tol, slip_d=place["slip"], stick_d=place["stick"],
                steps=r["stats"]["steps"], newton_iterations=r["stats"]["newton_iterations"],
                max_nodes=r["stats"]["max_nodes"], cpu_s=f"{cpu:.3f}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--bin", default="target/release/vibrissa")
    ap.add_argument("--out", default="data/dynamics/accuracy.csv")
    a = ap.parse_args()
    ref = run(a.bin, *REFERENCE)
    rows = [run(a.bin, dt, g, t) for dt in DTS for g, t in SPACE] + [ref]
    for r in rows:
        r["slip_error"] = f"{r['slip_d'] - SLIP_LIMIT:.2e}"
        r["stick_error"] = f"{r['stick_d'] - ref['stick_d']:.2e}"
        r["slip_d"], r["stick_d"] = f"{r['slip_d']:.10f}", f"{r['stick_d']:.10f}"
    with open(a.out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLUMNS)
        w.writeheader()
        w.writerows(rows)
    for r in rows:
        print(",".join(str(r[c]) for c in COLUMNS))


if __name__ == "__main__":
    main()
