"""Python and the `vibrissa` program give identical numbers (to the last digit: the program
prints the shortest round-trip digits, so parsing them gives back the same double), and a
400-scene sweep from Python is timed against the program's."""

import math
import sys
import tempfile
import time

import pytest

import vibrissa
from conftest import SCENES, read_csv

# scenes of every class: the paper's, tapered, pre-curved, compliant, inclined, and the rat
# presets; (flags of the program, the same as vibrissa.scene() keys)
SCENE_FLAGS = [
    {},
    {"taper": 0.3, "eta": 0.9},
    {"precurvature": -0.5, "precurvature_slope": 0.2},
    {"support_compliance": 0.5},
    {"surface_angle": -0.2},
    {"taper": 0.5, "precurvature": 0.3, "support_compliance": 0.1, "eta": 0.8},
]


def flags(keys):
    out = []
    for k, v in keys.items():
        out += [f"--{k.replace('_', '-')}", repr(float(v))]
    return out


def number(text):
    """A CSV field as the program wrote it: empty means None, inf/-inf at lift-off."""
    return None if text == "" else float(text)


def same(a, b, what):
    """Equal to the last digit (None and NaN stand for the program's empty field)."""
    if a is None or (isinstance(a, float) and math.isnan(a)):
        assert b is None, f"{what}: python {a!r}, program {b!r}"
    else:
        assert a == b, f"{what}: python {a!r} != program {b!r}"


def check_points(py_points, csv_rows, what):
    assert len(csv_rows) == len(py_points["d"]), what
    for name in csv_rows[0]:
        if name.endswith(("_N", "_Nm", "_mm")):
            continue  # physical units: the program's own columns
        col = py_points[name]
        for i, row in enumerate(csv_rows):
            if name in ("event", "contact"):
                assert (col[i] or "") == row[name], f"{what} row {i}: {name}"
            else:
                same(col[i], number(row[name]), f"{what} row {i}: {name}")


@pytest.mark.parametrize("keys", SCENE_FLAGS, ids=lambda k: ",".join(k) or "paper")
def test_scan_equals_the_program(program, keys):
    rod, surface = vibrissa.scene(**keys)
    args = ["scan", "--points", "41", *flags(keys)]
    py = vibrissa.scan(rod, surface, points=41)
    check_points(py.points, read_csv(program(*args)), " ".join(args))


@pytest.mark.parametrize("file", ["paper.toml", "tapered.toml", "precurved.toml", "compliant.toml", "rat_mystacial_long.toml", "rat_mystacial_short.toml"])
def test_scene_files_scan_as_in_the_program(program, file):
    rod, surface = vibrissa.load_scene(SCENES / file)
    py = vibrissa.scan(rod, surface, points=31, mu0=0.6)
    check_points(py.points, read_csv(program("scan", "--scene", str(SCENES / file), "--points", "31", "--mu0", "0.6")), file)


def test_scan_summary_and_shapes_equal_the_program(program):
    import json

    with tempfile.TemporaryDirectory() as tmp:
        shapes = f"{tmp}/shapes.csv"
        out = json.loads(program("scan", "--taper", "0.5", "--points", "7", "--mu0", "0.7", "--json", "--shapes", shapes, "--shape-points", "9"))
        csv_shapes = read_csv(open(shapes).read())
    rod, surface = vibrissa.scene(taper=0.5)
    py = vibrissa.scan(rod, surface, points=7, mu0=0.7, shape_points=9)
    for k in ("mu_max", "mu_at_max", "d_at_mu_max", "range_end"):
        assert getattr(py, k) == out[k], k
    assert py.stop_reason == out["stop_reason"] and py.stop.get("d") == out["stop"]["d"]
    assert py.stats["newton_iters"] == out["stats"]["newton_iters"]
    assert py.stats["rhs_evals"] == out["stats"]["rhs_evals"]
    n = len(py)
    assert len(csv_shapes) == n * 9
    for row in csv_shapes:
        i, j = int(row["point"]), None
        j = [float(v) for v in py.shapes["s"][i]].index(float(row["s"]))
        for k in ("x", "y", "phi", "kappa", "m"):
            assert py.shapes[k][i, j] == float(row[k]), (i, j, k)


def test_solve_and_infer_equal_the_program(program):
    for method in ("shooting", "multiple-shooting", "collocation6"):
        args = ["solve", "--alpha", "-0.3", "--phi1", "0.3", "--taper", "0.5", "--precurvature", "0.3", "--method", method]
        row = read_csv(program(*args))[0]
        py = vibrissa.solve(vibrissa.Rod(taper=0.5, precurvature=0.3), -0.3, phi1=0.3, method=method)
        for k in ("alpha", "phi1", "f", "fx", "fy", "x1", "y1", "m_base", "s_flex", "y_max", "residual"):
            same(py[k], number(row[k]), f"{method}: {k}")
        assert py["flex"] == int(row["flex"]) and py["load_reversals"] == int(row["load_reversals"])
    row = read_csv(program("infer", "--d0", "0.05", "--eta", "0.8", "--support-compliance", "0.2"))[0]
    rod, surface = vibrissa.scene(eta=0.8, support_compliance=0.2)
    py = vibrissa.infer(rod, surface, 0.05)
    assert py["mu0"] == float(row["mu0"]) and py["mu_max"] == float(row["mu_max"])
    assert py["measurable_d"] == (float(row["d_min"]), float(row["d_max_measurable"]))


def test_a_400_scene_sweep_equals_the_program_and_is_timed(program, capsys):
    """The program's sweep CSV and Python's sweep of the same 400 scenes (the grid values read
    from the program's CSV, so that both run the same doubles) agree in every column; both are
    timed (wall clock, both cores, one run each, printed: speed is not asserted in tests)."""
    args = ["sweep", "--eta", "0.6:0.95:20", "--precurvature", "-1:1:20", "--jobs", "2"]
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        program(*args, "--out", f"{tmp}/sweep.csv")
        t_program = time.perf_counter() - t0
        rows = read_csv(open(f"{tmp}/sweep.csv").read())
    assert len(rows) == 400
    scenes = vibrissa.grid(
        eta=sorted({float(r["eta"]) for r in rows}),
        precurvature=sorted({float(r["precurvature"]) for r in rows}),
    )
    t0 = time.perf_counter()
    sw = vibrissa.sweep(scenes, jobs=2)
    t_python = time.perf_counter() - t0
    c = sw.columns
    pairs = {
        "eta": "eta",
        "precurvature": "precurvature",
        "f0": "start_f",
        "phi1_0": "start_phi1",
        "mu_max": "mu_max",
        "d_at_mu_max": "d_at_mu_max",
        "mu_end": "end_mu",
        "d_end": "end_d",
        "points": "points",
        "newton_iters": "stats_newton_iters",
        "rhs_evals": "stats_rhs_evals",
    }
    errors = 0
    for i, row in enumerate(rows):
        failed = row["stop_reason"] == "error"
        assert (c["error"][i] is not None) == failed, f"scene {i}: {row['error']} / {c['error'][i]}"
        if failed:
            errors += 1
            continue
        assert c["stop_reason"][i] == row["stop_reason"], f"scene {i}"
        for prog, py in pairs.items():
            same(c[py][i], number(row[prog]), f"scene {i}: {prog}")
    assert 0 < errors < 400  # the grid covers scenes that cannot start, and the sweep goes on
    build = "release" if "release" in str(program.path) else "not a release build: no comparison"
    with capsys.disabled():  # shown in the test log
        print(
            f"\n400-scene sweep, 2 threads, one run each: program ({build}) {t_program:.3f} s, "
            f"Python {t_python:.3f} s, ratio {t_python / t_program:.2f}"
        )
