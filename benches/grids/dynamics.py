#!/usr/bin/env python3
"""Issue 32's dynamic-drag grid: `vibrissa dynamics drag` over time steps, speeds, rods and
options, every drag classified by how it ends (docs/robustness.md, "The dynamic drag").

Usage: python3 benches/grids/dynamics.py [--bin target/release/vibrissa] [--jobs 2]
           [--timeout 300] [--out data/dynamics/drag_grid.csv]
       python3 benches/grids/dynamics.py --scenes NAME,NAME [--out ...]
       python3 benches/grids/dynamics.py --count FILE.csv

--scenes runs the rows of the named scenes only (e.g. rat_long).

The grid: dt {0.1, 0.05, 0.02, 0.01} x speed {0.01, 0.05, 0.2} x scenes {the paper's rod;
taper 0.3 at eta 0.9 (at 0.75 its pressed start crosses the surface); the short and the long
rat presets; the paper's rod with internal damping 0.01; the paper's rod with --flight; the
paper's rod on a surface inclined by 0.1, over a corrugation 0.003 sin(2 pi x/0.1) and over one
0.02 sin(2 pi x/0.2) (where the rod's end lies down, a side that rolls and slides on until
its contact reaches the tip, which takes it over; a side and the tip on the surface at once,
to where two stuck contacts would trap the rod, side_change trapped, or the pair's steps do not
solve, the rod lying along the surface between them, stretch); the short
rat preset over the first
corrugation; the paper's rod on friction patches and on a friction table along x
(data/dynamics/friction_*.toml); the paper's rod with a round tip of radius 0.02 and internal
damping 1e-4, on the flat surface and over a corrugation 0.005 sin(2 pi x/0.2); a rod of rest
curvature 1 pressed lightly onto eta 0.83 with --flight, which lifts off and touches down;
the paper's rod on a viscoelastic support, compliance 1 and damper 0.5} = 192 drags to d_max 0.12 (program defaults otherwise: the scene file's eta, else 0.75; mu_s 0.5,
mu_k 0.3 or the scene's [friction], ramp 2, grid 200, tol 1e-10), each with `--json`. A drag is killed after --timeout
seconds of wall time (class "slow"). cpu_s is the drag's user + system CPU time (os.wait4), the
only column that differs between runs. Checked on every row that ends: no event with a normal
force below zero (a lift-off's: below -1e-8, its N zero to the event's location) or not a
number, and no located slip beyond the friction cone (|T| > μs N, μs
the texture's at the slip's place, by
more than 1e-6 of it; a slip at the instant of a stick, the stuck tip needing more at once, is
not counted), and no `unresolved_stick` stop whose force, what the stuck tip needs at once, is
neither a pull nor beyond the friction cone of the scene's least μs (column bad_events).
"""
import argparse, collections, csv, json, sys
from concurrent.futures import ThreadPoolExecutor

from timed import run_timed

DTS = ["0.1", "0.05", "0.02", "0.01"]
SPEEDS = ["0.01", "0.05", "0.2"]
SCENES = [
    ("paper", []),
    ("taper0.3_eta0.9", ["--taper", "0.3", "--eta", "0.9"]),
    ("rat_short", ["--scene", "data/scenes/rat_mystacial_short.toml"]),
    ("rat_long", ["--scene", "data/scenes/rat_mystacial_long.toml"]),
    ("paper_damped0.01", ["--internal-damping", "0.01"]),
    ("paper_flight", ["--flight"]),
    ("inclined0.1", ["--surface-angle", "0.1"]),
    ("corrugation0.003_0.1", ["--corrugation-amplitude", "0.003",
                              "--corrugation-wavelength", "0.1"]),
    ("corrugation0.02_0.2", ["--corrugation-amplitude", "0.02", "--corrugation-wavelength", "0.2"]),
    ("rat_short_corrugation0.003_0.1", ["--scene", "data/scenes/rat_mystacial_short.toml",
                                        "--corrugation-amplitude", "0.003",
                                        "--corrugation-wavelength", "0.1"]),
    ("friction_patches", ["--scene", "data/dynamics/friction_patches.toml"]),
    ("friction_table", ["--scene", "data/dynamics/friction_table.toml"]),
    ("round_tip0.02", ["--tip-radius", "0.02", "--internal-damping", "1e-4"]),
    ("round_tip0.02_corrugation0.005_0.2", ["--tip-radius", "0.02", "--internal-damping", "1e-4",
                                            "--corrugation-amplitude", "0.005",
                                            "--corrugation-wavelength", "0.2"]),
    ("precurved1_eta0.83_flight", ["--precurvature", "1", "--eta", "0.83", "--flight"]),
    ("viscoelastic1_0.5", ["--support-compliance", "1", "--foot-damping", "0.5"]),
]


def mu_s_at(scene, x, side):
    """μs at the tip's x of the scene's friction (at a patch's boundary the side pushed to)."""
    if scene == "friction_patches":
        q = x + (1e-9 if side >= 0 else -1e-9) - 0.6
        return 0.5 if q - 0.1 * (q // 0.1) < 0.05 else 0.4
    if scene == "friction_table":
        return 0.5 + 0.1 * min(max((x - 0.55) / 0.2, 0.0), 1.0)
    return 0.5
# the least mu_s of each scene's friction (0.5 where not named)
MU_S_LEAST = {"friction_patches": 0.4}
COMMON = ["--d-max", "0.12", "--json"]
COLUMNS = ["dt", "speed", "scene", "class", "stop_reason", "slips", "events", "bad_events",
           "d_end", "cpu_s", "exit", "detail"]
CLASSES = ["d_max", "lift-off", "touchdown", "side contact", "side change (named)",
           "stretch (named)",
           "unresolved stick (named)",
           "unresolved step (named)", "max_events", "refused", "no start", "error: other",
           "panic", "slow"]


def run(binary, timeout, case):
    dt, speed, (scene, extra) = case
    cmd = [binary, "dynamics", "drag", "--dt", dt, "--speed", speed, *extra, *COMMON]
    code, timed_out, stdout, stderr, cpu = run_timed(cmd, timeout)
    if timed_out:
        code = None
    row = dict(dt=dt, speed=speed, scene=scene, cpu_s=f"{cpu:.3f}",
               exit="timeout" if code is None else code)
    lines = [l for l in stderr.strip().splitlines() if l.startswith("error")]
    if code is None:
        row.update({"class": "slow", "detail": f"killed after {timeout} s"})
        return row
    if code != 0:
        detail = lines[-1] if lines else stderr.strip().splitlines()[-1:]
        cls = ("panic" if code == 101 else "no start" if "no start" in str(detail)
               else "refused" if code == 2 else "error: other")
        row.update({"class": cls, "detail": str(detail)[:300]})
        return row
    r = json.loads(stdout)
    ev = r["events"]
    # (a located slip's |T| is μs N to the event's location; a slip at the instant of a stick is
    # the stuck tip needing more than μs N at once, by design)
    at_once = [i > 0 and e["kind"] == "slip" and e["t"] == ev[i - 1]["t"] for i, e in enumerate(ev)]
    limit = [mu_s_at(scene, e["tip_x"], e["tangential"]) for e in ev]
    floor = [-1e-8 if e["kind"] == "lift_off" else 0.0 for e in ev]
    bad = sum(1 for i, e in enumerate(ev) if not (e["normal"] >= floor[i])
              or (e["kind"] == "slip" and not at_once[i]
                  and not abs(e["tangential"]) <= limit[i] * (1 + 1e-6) * e["normal"]))
    reason = r["stop"]["reason"]
    if reason == "unresolved_stick":
        # the stop's force is what the stuck tip needs at once: a pull or beyond the friction
        # cone (of the scene's smallest mu_s: the stop names no place), else it is counted
        n, t = r["stop"]["normal"], r["stop"]["tangential"]
        if not (n < 0.0 or abs(t) > MU_S_LEAST.get(scene, 0.5) * n):
            bad += 1
    cls = {"d_max": "d_max", "lift_off": "lift-off", "touchdown": "touchdown",
           "side_contact": "side contact", "unresolved_stick": "unresolved stick (named)",
           "unresolved_step": "unresolved step (named)", "side_change": "side change (named)",
           "stretch": "stretch (named)", "max_events": "max_events"}.get(reason, "error: other")
    d_end = r["samples"][-1]["d"] if r["samples"] else 0.0
    row.update({"class": cls, "stop_reason": reason,
                "slips": sum(e["kind"] == "slip" for e in ev), "events": len(ev),
                "bad_events": bad, "d_end": f"{d_end:.6f}",
                "detail": json.dumps(r["stop"]) if reason != "d_max" else "",
                # (not columns of this grid: benches/grids/side_sweep.py's)
                "to_tip": sum(e["kind"] == "to_tip" for e in ev),
                "pairs": sum(1 for i, e in enumerate(ev) if "tip_also" in e
                             and (i == 0 or "tip_also" not in ev[i - 1]))})
    return row


def count(paths):
    for path in paths:
        rows = list(csv.DictReader(open(path)))
        c = collections.Counter(r["class"] for r in rows)
        print(f"{path}: {len(rows)} drags")
        for k in CLASSES:
            if c[k]:
                print(f"  {k}: {c[k]}")
        bad = sum(int(r["bad_events"] or 0) for r in rows)
        print(f"  events with a pull, no number or a slip beyond mu_s, and stops inside the "
              f"cone: {bad}")


def arguments(out):
    """The options every grid of drags takes (--bin, --jobs, --timeout, --out)."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", default="target/release/vibrissa")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--timeout", type=float, default=300)
    ap.add_argument("--out", default=out)
    return ap


def run_cases(a, cases, columns=COLUMNS):
    """Runs the drags `cases` ((dt, speed, (scene, flags))) `a.jobs` at a time, each row to
    stderr as it ends, the rows' `columns` to `a.out`, and counts them."""
    with ThreadPoolExecutor(a.jobs) as ex:
        rows = []
        for row in ex.map(lambda c: run(a.bin, a.timeout, c), cases):
            rows.append(row)
            print(",".join(str(row.get(k, "")) for k in columns[:10]), file=sys.stderr, flush=True)
    with open(a.out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=columns, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    count([a.out])


def main():
    ap = arguments("data/dynamics/drag_grid.csv")
    ap.add_argument("--count", nargs="+")
    ap.add_argument("--scenes", help="comma-separated scene names (default: all)")
    a = ap.parse_args()
    if a.count:
        return count(a.count)
    keep = set(a.scenes.split(",")) if a.scenes else {name for name, _ in SCENES}
    run_cases(a, [(dt, v, s) for dt in DTS for v in SPEEDS for s in SCENES if s[0] in keep])


if __name__ == "__main__":
    sys.exit(main())
