#!/usr/bin/env python3
"""Issue 31's texture grid: `vibrissa drag` over sine corrugations, every drag classified by
how it stops (docs/robustness.md, "Textures").

Usage: python3 benches/grids/texture.py [--bin target/release/vibrissa] [--jobs 2]
           [--timeout 1200] [--out data/drag/texture_grid.csv]
       python3 benches/grids/texture.py --redo CLASS --from FILE.csv [--out ...]
       python3 benches/grids/texture.py --count FILE.csv [FILE.csv ...]

The grid: amplitudes {0.001, 0.003, 0.01, 0.02, 0.05} x wavelengths {0.02, 0.05, 0.1, 0.2, 0.5}
x phases {0, 2 pi/3, 4 pi/3} x rods {uniform, taper 0.3, the short rat preset
data/scenes/rat_mystacial_short.toml} x tip radius {0, 0.005} = 450 drags, each with the paper's
settings (eta 0.75, mu_s 0.5, mu_k 0.3, d_max 0.3; the rat preset's eta overridden to 0.75) and
`--json`. A drag is killed after --timeout seconds of wall time (class "slow"). cpu_s is the
drag's user + system CPU time (os.wait4), the only column that differs between runs.

--redo runs again only the rows of FILE.csv in the class CLASS (e.g. "slow": drags killed by the
wall-time limit when the machine was loaded) and writes FILE.csv's rows with those replaced.

--count prints the class counts of committed CSVs (the tables of docs/robustness.md).
"""
import argparse, collections, csv, json, math, sys
from concurrent.futures import ThreadPoolExecutor

from timed import run_timed

AMPLITUDES = [0.001, 0.003, 0.01, 0.02, 0.05]
WAVELENGTHS = [0.02, 0.05, 0.1, 0.2, 0.5]
PHASES = [("0", 0.0), ("2pi/3", 2 * math.pi / 3), ("4pi/3", 4 * math.pi / 3)]
RODS = [
    ("uniform", []),
    ("taper0.3", ["--taper", "0.3"]),
    ("rat_short", ["--scene", "data/scenes/rat_mystacial_short.toml"]),
]
RADII = ["0", "0.005"]
COMMON = ["--eta", "0.75", "--mu-s", "0.5", "--mu-k", "0.3", "--d-max", "0.3", "--json"]
COLUMNS = ["amplitude", "wavelength", "phase", "rod", "tip_radius", "class", "stop_reason",
           "slips", "d_end", "cpu_s", "exit", "detail"]

# Class order of the tables: physical stops first, then refusals, then the rest.
CLASSES = ["d_max", "lift-off", "jam", "fold/snap", "start snaps as the texture grows",
           "refused: steep for a point tip", "refused: other", "no start", "trapped start",
           "start lies along the texture (not modelled)",
           "start's stretch reaches the rod's end (not followed)",
           "slider halts into a trapped state (named)", "trapped slide (not followed)",
           "nested slips 8 deep (named)", "side begins to lie along the surface",
           "sliding side closes up to its neighbour (named)",
           "closed-up stretch not resolved (named)",
           "lying stretch would slip (not modelled)",
           "change at a lying stretch (not followed)", "lying stretch's end would pull",
           "lying stretch reaches the rod's end (not followed)",
           "lying stretch reaches the tip (not followed)",
           "slide of 4 rod lengths", "side behind the sliding "
           "contact (not followed)", "not modelled / no contact state", "too many slips",
           "named stop: other", "stale slip driver", "Newton failure / NaN",
           "solver failure: event", "error: other", "panic", "slow"]


def classify(reason, detail, code):
    """The stop class of one drag from its JSON stop (or its exit code and stderr line)."""
    if code == "timeout":
        return "slow"
    if code not in (0, "0"):
        if code in (101, "101") or "panicked" in detail:
            return "panic"
        if "reach 1 (45 degrees" in detail:
            return "refused: steep for a point tip"
        if "80 degrees, the steepest" in detail or "a groove narrower than the tip" in detail:
            return "refused: other"
        # the pressed rod has no start on the texture: it snaps as the texture grows from
        # its straight trend (a fold), or lies down along a stretch of it (not in the
        # point-contact model)
        if "snaps as the surface's shape grows" in detail:
            return "start snaps as the texture grows"
        if "lies down along the surface" in detail:
            return "start lies along the texture (not modelled)"
        if "reaches the rod's end" in detail:
            return "start's stretch reaches the rod's end (not followed)"
        if "no start" in detail:
            return "no start"
        if "Newton" in detail or "NaN" in detail or "not finite" in detail:
            return "Newton failure / NaN"
        if "locating the" in detail or "jumps from" in detail:
            return "solver failure: event"
        return "error: other"
    named = {"d_max": "d_max", "lift_off": "lift-off", "jam": "jam", "fold_in_d": "fold/snap"}
    if reason in named:
        return named[reason]
    if reason == "solver_failure":
        if "locating the" in detail or "jumps from" in detail:
            return "solver failure: event"
        return "Newton failure / NaN"
    if "s = NaN" in detail or "is gone" in detail:
        return "stale slip driver"
    # (two contacts that closed up and lay down as one stretch, whose slide the solver then did
    # not resolve, end at the closing: named as that, the solver's message added)
    if "lie down as one stretch there, whose slide the solver does not resolve" in detail:
        return "closed-up stretch not resolved (named)"
    # (a solver failure with the tip just beyond a lying stretch: the stretch reaches the tip,
    # a singular state, named, the solver's message added)
    if "stretch lying on the surface" in detail and "reaches the tip" in detail:
        return "lying stretch reaches the tip (not followed)"
    # (a side that lay down in a slip with contacts beyond it, whose state the solver then did
    # not resolve, ends at its lie-down: named as that, the solver's message added)
    if (("Newton did not converge" in detail or "has no rod" in detail)
            and "trapped" not in detail
            and "begins to lie along the surface" not in detail):
        return "Newton failure / NaN"
    if "equilibria fold back" in detail and "(a snap)" in detail:
        return "fold/snap"
    if "closes up to the" in detail:
        return "sliding side closes up to its neighbour (named)"
    if "halts and holds where it is" in detail:
        return "slider halts into a trapped state (named)"
    if "the start" in detail and "trap" in detail:
        return "trapped start"
    if "trapped" in detail:
        return "trapped slide (not followed)"
    if "reach their slip limits in turn" in detail:
        return "nested slips 8 deep (named)"
    if "begins to lie along the surface" in detail:
        return "side begins to lie along the surface"
    if "stretch lying on the surface" in detail and "would slip" in detail:
        return "lying stretch would slip (not modelled)"
    if "at or beyond a lying stretch is not followed" in detail:
        return "change at a lying stretch (not followed)"
    if "stretch lying on the surface" in detail and "would pull" in detail:
        return "lying stretch's end would pull"
    if "stretch lying on the surface" in detail and "reaches the rod's end" in detail:
        return "lying stretch reaches the rod's end (not followed)"
    if "rod lengths along the surface without reaching" in detail:
        return "slide of 4 rod lengths"
    if "joins behind the sliding one" in detail:
        return "side behind the sliding contact (not followed)"
    if "not modelled" in detail or "no contact state" in detail:
        return "not modelled / no contact state"
    if "max_slips" in detail:
        return "too many slips"
    return "named stop: other"


def scenes():
    for a in AMPLITUDES:
        for w in WAVELENGTHS:
            for pname, p in PHASES:
                for rod, rflags in RODS:
                    for r in RADII:
                        args = rflags + COMMON + [
                            "--corrugation-amplitude", str(a), "--corrugation-wavelength", str(w),
                            "--corrugation-phase", repr(p), "--tip-radius", r]
                        yield dict(amplitude=a, wavelength=w, phase=pname, rod=rod,
                                   tip_radius=r), args


def run(binary, timeout, key, args, d_max=0.3, end="d_end"):
    """One drag's row: its stop, slips, where it ended (column `end`; `d_max` where the stop
    has no place) and CPU time, classified."""
    code, timed_out, stdout, stderr, cpu = run_timed([binary, "drag"] + args, timeout)
    row = dict(key, cpu_s=f"{cpu:.3f}", exit=code)
    if timed_out:
        row.update({"exit": "timeout", "stop_reason": "", "slips": "", end: "", "detail": ""})
    elif code == 0:
        j = json.loads(stdout)
        at = j["stop"]["d"] if j["stop"]["d"] is not None else d_max
        row.update({"stop_reason": j["stop_reason"], "slips": j["cycles"], end: repr(at),
                    "detail": j["stop"]["detail"]})
    else:
        lines = [l for l in stderr.splitlines() if l.strip()]
        row.update({"stop_reason": "error", "slips": "", end: "",
                    "detail": (lines[-1] if lines else f"exit {code}")[:2000]})
    row["class"] = classify(row["stop_reason"], row["detail"], row["exit"])
    return row


def count(files):
    tables = []
    for f in files:
        rows = list(csv.DictReader(open(f)))
        for r in rows:
            r["class"] = classify(r["stop_reason"], r["detail"], r["exit"])
        tables.append((f, len(rows), collections.Counter(r["class"] for r in rows)))
    print("| class | " + " | ".join(f"{f} ({n})" for f, n, _ in tables) + " |")
    print("|---|" + "---|" * len(tables))
    for c in CLASSES:
        if any(t[c] for _, _, t in tables):
            print(f"| {c} | " + " | ".join(str(t[c]) for _, _, t in tables) + " |")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", default="target/release/vibrissa")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--timeout", type=float, default=1200.0)
    ap.add_argument("--out", default="data/drag/texture_grid.csv")
    ap.add_argument("--count", nargs="+")
    ap.add_argument("--redo", metavar="CLASS")
    ap.add_argument("--from", dest="source", metavar="FILE.csv")
    a = ap.parse_args()
    if a.count:
        return count(a.count)
    grid = list(scenes())
    old = None
    if a.redo:
        if not a.source:
            ap.error("--redo needs --from FILE.csv")
        old = list(csv.DictReader(open(a.source)))
        if len(old) != len(grid):
            ap.error(f"{a.source} has {len(old)} rows, the grid {len(grid)}")
        for r in old:
            r["class"] = classify(r["stop_reason"], r["detail"], r["exit"])
        grid = [g for g, r in zip(grid, old) if r["class"] == a.redo]
    with ThreadPoolExecutor(a.jobs) as ex:
        rows = list(ex.map(lambda ka: run(a.bin, a.timeout, *ka), grid))
    if old is not None:
        it = iter(rows)
        rows = [next(it) if r["class"] == a.redo else {c: r[c] for c in COLUMNS} for r in old]
    with open(a.out, "w", newline="") as f:
        w = csv.DictWriter(f, COLUMNS, lineterminator="\n")
        w.writeheader()
        w.writerows(rows)
    count([a.out])


if __name__ == "__main__":
    sys.exit(main())
