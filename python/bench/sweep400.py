"""Times a 400-scene sweep from Python against the same sweep by the program.

    .venv/bin/python python/bench/sweep400.py [REPEATS]  (program: $VIBRISSA_BIN or
                                                          target/release/vibrissa)

Runs the two alternately REPEATS times (default 7) on the grid eta 0.6:0.95:20 x precurvature
-1:1:20 (201 points per scan, tol 1e-10, 2 threads) and prints each run and the ratio of the
minimum wall times (on a shared machine single runs vary by 2x; the minimum is the run least
disturbed). The Python time is the user's: scene construction, the sweep and its columns."""

import os
import pathlib
import subprocess
import sys
import tempfile
import time

import vibrissa

REPO = pathlib.Path(__file__).resolve().parents[2]
exe = os.environ.get("VIBRISSA_BIN", str(REPO / "target" / "release" / "vibrissa"))
repeats = int(sys.argv[1]) if len(sys.argv) > 1 else 7
args = [exe, "sweep", "--eta", "0.6:0.95:20", "--precurvature", "-1:1:20", "--jobs", "2"]
with tempfile.TemporaryDirectory() as tmp:
    out = f"{tmp}/sweep.csv"
    subprocess.run(args + ["--out", out], check=True)
    rows = [line.split(",") for line in open(out).read().splitlines()]
    head = rows[0]
    etas = sorted({float(r[head.index("eta")]) for r in rows[1:]})
    ks = sorted({float(r[head.index("precurvature")]) for r in rows[1:]})
    tp, tpy = [], []
    for _ in range(repeats):
        t0 = time.perf_counter()
        subprocess.run(args + ["--out", out], check=True)
        tp.append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        sw = vibrissa.sweep(vibrissa.grid(eta=etas, precurvature=ks), jobs=2)
        tpy.append(time.perf_counter() - t0)
        print(f"program {tp[-1]:.3f} s   python {tpy[-1]:.3f} s", flush=True)
assert len(sw) == 400
print(f"minimum: program {min(tp):.3f} s, python {min(tpy):.3f} s, ratio {min(tpy) / min(tp):.3f}")
