#!/usr/bin/env python3
"""The turned drag's energy balance over the turn grid's 45 scenes (benches/grids/turn.py):
each drag run again with `--energy-balance`, and per drag the largest imbalance of its sticks
(the support's work `∫ m(0) dθ` against the change of the elastic energy plus what sliding
contacts took) and of its slips (the work the sliding contact absorbs against the energy
released), relative to the rod's elastic energy at the start (docs/robustness.md, "The support
turned").

Usage: python3 benches/grids/turn_energy.py [--bin target/release/vibrissa] [--jobs 2]
           [--timeout 600]
"""
import argparse, json, sys
from concurrent.futures import ThreadPoolExecutor

from timed import run_timed
import turn


def balance(binary, timeout, key, args):
    """`(key, slips, worst stick, worst slip, energy scale, cpu)` of one drag, or its error."""
    code, timed_out, stdout, stderr, cpu = run_timed(
        [binary, "drag"] + args + ["--energy-balance"], timeout)
    if timed_out or code != 0:
        return key, None, stderr.strip().splitlines()[-1:] if not timed_out else "timeout", cpu
    j = json.loads(stdout)
    stick = slip = 0.0
    scale = 0.0
    for s in j["slips"]:
        scale = max(scale, abs(s["energy_stick"]), abs(s["before"]["energy"]))
        change = s["before"]["energy"] - s["energy_stick"] + (s["friction"] or 0.0)
        stick = max(stick, abs(s["work"] - change))
        slip = max(slip, abs(s["dissipated"] - s["released"]))
    return key, (len(j["slips"]), stick, slip, scale), j["stop_reason"], cpu


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", default="target/release/vibrissa")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--timeout", type=float, default=600)
    a = ap.parse_args()
    cases = list(turn.scenes())
    worst = (0.0, None)
    slips = drags = 0
    with ThreadPoolExecutor(a.jobs) as pool:
        for key, r, stop, cpu in pool.map(lambda c: balance(a.bin, a.timeout, *c), cases):
            name = " ".join(key.values())
            if r is None:
                print(f"{name}: no drag ({stop})")
                continue
            n, stick, slip, scale = r
            rel = max(stick, slip) / scale if scale > 0 else 0.0
            print(f"{name}: {stop}, {n} slips, stick {stick:.1e}, slip {slip:.1e}, "
                  f"relative {rel:.1e}, {cpu:.1f} s")
            drags += 1
            slips += n
            if rel > worst[0]:
                worst = (rel, name)
    print(f"{drags} drags, {slips} slips; largest imbalance relative to the elastic energy "
          f"{worst[0]:.1e} ({worst[1]})")


if __name__ == "__main__":
    sys.exit(main())
