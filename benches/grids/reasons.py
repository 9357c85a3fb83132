#!/usr/bin/env python3
"""The stop reasons of `vibrissa sweep --timing` outputs, counted (docs/robustness.md).

Usage: python3 benches/grids/reasons.py FILE.csv [FILE.csv ...]
Errors are grouped by the first two parts of their message; an event at d = 0 is its own class.
Prints the median, p99 and maximum wall time per scene (the sweep's time_ms column).
"""
import csv, sys, statistics, collections
for f in sys.argv[1:]:
    rows = list(csv.DictReader(open(f)))
    c = collections.Counter()
    for r in rows:
        k = r["stop_reason"]
        if k == "error":
            e = r["error"]
            k = "error: " + e.split(":")[0] + (": " + e.split(":")[1].strip()[:40] if ":" in e else "")
        if k in ("penetration","lift_off","slip","fold_in_d") and float(r["d_end"] or 0) == 0:
            k += " at d = 0"
        c[k] += 1
    t = sorted(float(r["time_ms"]) for r in rows if r.get("time_ms"))
    med = statistics.median(t); p99 = t[int(0.99 * (len(t) - 1))]
    print(f"## {f}: {len(rows)} scenes, median {med:.2f} ms, p99 {p99:.2f} ms ({p99/med:.1f}x), max {t[-1]:.1f} ms")
    for k, n in c.most_common():
        print(f"| {k} | {n} | {100*n/len(rows):.1f} % |")
