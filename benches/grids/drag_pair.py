#!/usr/bin/env python3
"""Two builds of `vibrissa` side by side on the texture drags of the drag bench
(benches/drag.rs's three drags over corrugations, as program runs): the minimum CPU time of
each over REPS runs, the builds alternating run by run (a shared machine's load then falls on
both alike).

Usage: python3 benches/grids/drag_pair.py BIN_BEFORE BIN_AFTER [--reps 7]
"""
import argparse

from timed import run_timed

FRICTION = ["--mu-s", "0.5", "--mu-k", "0.3"]
DRAGS = {
    "corrugation 0.01/0.5, 10 slips": FRICTION + [
        "--corrugation-amplitude", "0.01", "--corrugation-wavelength", "0.5",
        "--corrugation-phase", "2", "--d-max", "1", "--max-slips", "10"],
    "a side drives every slip (eta 0.46), 10 slips": FRICTION + [
        "--eta", "0.46", "--corrugation-amplitude", "0.001",
        "--corrugation-wavelength", "1", "--d-max", "0.3", "--max-slips", "10"],
    "short rat preset over 0.001/0.05/0 to d 0.0162": FRICTION + [
        "--scene", "data/scenes/rat_mystacial_short.toml", "--eta", "0.75",
        "--corrugation-amplitude", "0.001", "--corrugation-wavelength", "0.05",
        "--corrugation-phase", "0", "--d-max", "0.0162"],
}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("before")
    ap.add_argument("after")
    ap.add_argument("--reps", type=int, default=7)
    a = ap.parse_args()
    best = {}
    for _ in range(a.reps):
        for name, args in DRAGS.items():
            for b in (a.before, a.after):
                code, _, _, err, cpu = run_timed([b, "drag"] + args, 600)
                if code != 0:
                    raise SystemExit(f"{b} drag {' '.join(args)}: {err.strip()}")
                best[name, b] = min(best.get((name, b), float("inf")), cpu)
    for name in DRAGS:
        t0, t1 = best[name, a.before], best[name, a.after]
        print(f"{name}: {1e3 * t0:.1f} ms -> {1e3 * t1:.1f} ms ({t1 / t0:.3f}x)")


if __name__ == "__main__":
    main()
