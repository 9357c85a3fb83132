"""Times a 400-scene sweep from Python against the same sweep by the program.

    .venv/bin/python python/bench/sweep400.py [REPEATS] [JOBS]
        (program: $VIBRISSA_BIN or target/release/vibrissa; defaults 7 repeats, 2 threads)

Runs the two alternately REPEATS times on the grid eta 0.6:0.95:20 x precurvature -1:1:20 (201
points per scan, tol 1e-10) and prints each run's wall and CPU time (user + system) and the
ratios of the minima: on a shared machine single runs vary by 2x, the minimum is the least
disturbed run, and CPU time is what other processes disturb least. The Python time is the
user's: scene construction, the sweep and its columns (`vibrissa.sweep`)."""

import os
import pathlib
import resource
import subprocess
import sys
import tempfile
import time

import vibrissa

REPO = pathlib.Path(__file__).resolve().parents[2]
exe = os.environ.get("VIBRISSA_BIN", str(REPO / "target" / "release" / "vibrissa"))
repeats = int(sys.argv[1]) if len(sys.argv) > 1 else 7
jobs = int(sys.argv[2]) if len(sys.argv) > 2 else 2
args = [exe, "sweep", "--eta", "0.6:0.95:20", "--precurvature", "-1:1:20", "--jobs", str(jobs)]


def cpu(who):
    r = resource.getrusage(who)
    return r.ru_utime + r.ru_stime


with tempfile.TemporaryDirectory() as tmp:
    out = f"{tmp}/sweep.csv"
    subprocess.run(args + ["--out", out], check=True)
    rows = [line.split(",") for line in open(out).read().splitlines()]
    head = rows[0]
    etas = sorted({float(r[head.index("eta")]) for r in rows[1:]})
    ks = sorted({float(r[head.index("precurvature")]) for r in rows[1:]})
    tp, tpy, cp, cpy = [], [], [], []
    for _ in range(repeats):
        c0, t0 = cpu(resource.RUSAGE_CHILDREN), time.perf_counter()
        subprocess.run(args + ["--out", out], check=True)
        tp.append(time.perf_counter() - t0)
        cp.append(cpu(resource.RUSAGE_CHILDREN) - c0)
        c0, t0 = cpu(resource.RUSAGE_SELF), time.perf_counter()
        sw = vibrissa.sweep(vibrissa.grid(eta=etas, precurvature=ks), jobs=jobs)
        tpy.append(time.perf_counter() - t0)
        cpy.append(cpu(resource.RUSAGE_SELF) - c0)
        print(
            f"program {tp[-1]:.3f} s (cpu {cp[-1]:.3f})   python {tpy[-1]:.3f} s (cpu {cpy[-1]:.3f})",
            flush=True,
        )
assert len(sw) == 400
print(
    f"minimum wall: program {min(tp):.3f} s, python {min(tpy):.3f} s, ratio {min(tpy) / min(tp):.3f}; "
    f"minimum cpu: program {min(cp):.3f} s, python {min(cpy):.3f} s, ratio {min(cpy) / min(cp):.3f} "
    f"({jobs} threads, {repeats} runs each, load average {os.getloadavg()[0]:.1f})"
)
