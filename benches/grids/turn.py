#!/usr/bin/env python3
"""The turned drag's grid: `vibrissa drag --turn` (the support turned with the foot held, a whisk
against the surface), every drag classified by how it stops as texture.py classifies the drags
(docs/robustness.md, "The support turned").

Usage: python3 benches/grids/turn.py [--bin target/release/vibrissa] [--jobs 2]
           [--timeout 600] [--out data/drag/turn_grid.csv]
       python3 benches/grids/turn.py --count FILE.csv

The grid: rods {uniform, taper 0.3, the short rat preset data/scenes/rat_mystacial_short.toml,
rest curvature +1, rest curvature -1} x eta {0.5, 0.75, 0.9} x surfaces {flat; a corrugation
0.003 sin(2 pi x/0.1); a corrugation 0.01 sin(2 pi x/0.1) under a round tip of radius 0.005}
= 45 drags, each with mu_s 0.5, mu_k 0.3, the turn to 1.2 rad, 121 points and `--json` (the
rat preset's eta overridden). A drag is killed after --timeout seconds of wall time (class
"slow"). cpu_s is the drag's user + system CPU time, the only column that differs between runs.
"""
import argparse, collections, csv, sys
from concurrent.futures import ThreadPoolExecutor

import texture
from texture import CLASSES

RODS = [
    ("uniform", []),
    ("taper0.3", ["--taper", "0.3"]),
    ("rat_short", ["--scene", "data/scenes/rat_mystacial_short.toml"]),
    ("precurved+1", ["--precurvature", "1"]),
    ("precurved-1", ["--precurvature", "-1"]),
]
ETAS = ["0.5", "0.75", "0.9"]
SURFACES = [
    ("flat", []),
    ("corrugation0.003_0.1", ["--corrugation-amplitude", "0.003",
                              "--corrugation-wavelength", "0.1"]),
    ("corrugation0.01_0.1_r0.005", ["--corrugation-amplitude", "0.01",
                                    "--corrugation-wavelength", "0.1", "--tip-radius", "0.005"]),
]
COMMON = ["--turn", "--mu-s", "0.5", "--mu-k", "0.3", "--d-max", "1.2", "--points", "121",
          "--json"]
NO_CONTACT = "refused: the rest shape does not reach the surface"
COLUMNS = ["rod", "eta", "surface", "class", "stop_reason", "slips", "theta_end", "cpu_s", "exit",
           "detail"]


def scenes():
    for rod, rflags in RODS:
        for eta in ETAS:
            for surface, sflags in SURFACES:
                yield dict(rod=rod, eta=eta, surface=surface), rflags + ["--eta", eta] + sflags + COMMON


def run(binary, timeout, key, args):
    row = texture.run(binary, timeout, key, args, d_max=1.2, end="theta_end")
    if row["detail"].startswith("error: no contact:"):
        # (a precurved rest shape below the surface: the input is refused, exit 2)
        row["class"] = NO_CONTACT
    return row


def count(files):
    for f in files:
        rows = list(csv.DictReader(open(f)))
        c = collections.Counter(r["class"] for r in rows)
        cpu = sorted(float(r["cpu_s"]) for r in rows)
        print(f"{f}: {len(rows)} drags; CPU median {cpu[len(cpu) // 2]:.3f} s, total "
              f"{sum(cpu):.1f} s, longest {cpu[-1]:.1f} s")
        for k in CLASSES + [NO_CONTACT]:
            if c[k]:
                print(f"  {k}: {c[k]}")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", default="target/release/vibrissa")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--timeout", type=float, default=600)
    ap.add_argument("--out", default="data/drag/turn_grid.csv")
    ap.add_argument("--count", nargs="+")
    a = ap.parse_args()
    if a.count:
        return count(a.count)
    cases = list(scenes())
    with ThreadPoolExecutor(a.jobs) as ex:
        rows = list(ex.map(lambda c: run(a.bin, a.timeout, *c), cases))
    with open(a.out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLUMNS)
        w.writeheader()
        w.writerows(rows)
    count([a.out])


if __name__ == "__main__":
    sys.exit(main())
