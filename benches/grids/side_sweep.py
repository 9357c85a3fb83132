#!/usr/bin/env python3
"""Sides in time over corrugations (issue 32): `vibrissa dynamics drag` over A sin(2 pi x/W + P),
A {0.01, 0.02, 0.03}, W {0.1, 0.2, 0.3}, P {0, 1, 2}, v {0.01, 0.05}, dt 0.01, d_max 0.03, grid
100, tol 1e-8 (54 drags, the paper's rod otherwise), each classified by how it ends and checked
as the dynamic grid's rows are (benches/grids/dynamics.py: events with a pull or not a number,
located slips beyond the cone); the rows also count the drag's hand-overs to the tip (to_tip)
and its phases with two contacts at once (pairs: events whose tip_also is set as the pair
forms). docs/robustness.md, "The dynamic drag".

Usage: python3 benches/grids/side_sweep.py [--bin target/release/vibrissa] [--jobs 2]
           [--out data/dynamics/side_sweep.csv]
"""
import sys

import dynamics

dynamics.COMMON = ["--d-max", "0.03", "--grid", "100", "--tol", "1e-8", "--json"]
COLUMNS = dynamics.COLUMNS + ["to_tip", "pairs"]


def scenes():
    for a in ("0.01", "0.02", "0.03"):
        for w in ("0.1", "0.2", "0.3"):
            for p in ("0", "1", "2"):
                yield (f"corrugation{a}_{w}_{p}",
                       ["--corrugation-amplitude", a, "--corrugation-wavelength", w,
                        "--corrugation-phase", p])


def main():
    a = dynamics.arguments("data/dynamics/side_sweep.csv").parse_args()
    dynamics.run_cases(a, [("0.01", v, s) for s in scenes() for v in ("0.01", "0.05")], COLUMNS)


if __name__ == "__main__":
    sys.exit(main())
