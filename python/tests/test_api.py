"""The Python API: rods, surfaces, scenes, results as numpy columns, errors as exceptions."""

import math

import numpy as np
import pytest

import vibrissa
from conftest import SCENES


def test_rod_and_surface_validate_like_the_library():
    # the library's own messages, as the program's error line shows them (without the flag)
    with pytest.raises(vibrissa.InputError, match=r"^taper ratio = 0 is outside the valid range \[0\.01, 1\]$"):
        vibrissa.Rod(taper=0)
    with pytest.raises(ValueError, match=r"eta = 0\.3 is outside the valid range"):
        vibrissa.Surface(eta=0.3)
    with pytest.raises(vibrissa.Error, match="support compliance"):
        vibrissa.Rod(support_compliance=-1)
    assert vibrissa.Rod().is_uniform_clamped()
    r = vibrissa.Rod(taper=0.5, precurvature=0.3, precurvature_slope=-0.1, support_compliance=0.2)
    assert not r.is_uniform_clamped()
    assert r.to_dict() == {
        "stiffness": {"kind": "taper", "ratio": 0.5},
        "precurvature": {"kind": "linear", "k0": 0.3, "k1": -0.1},
        "support_compliance": 0.2,
        "physical": None,
    }
    s = vibrissa.Surface(0.8, -0.1)
    assert (s.eta, s.angle) == (0.8, -0.1)
    # a surface the rod cannot reach is bad input, as for the program (exit 2)
    curled, high = vibrissa.scene(eta=0.6, precurvature=-2.5)
    with pytest.raises(vibrissa.InputError, match="no contact"):
        vibrissa.scan(curled, high, points=3)


def test_scene_dicts_speak_the_file_format():
    with pytest.raises(vibrissa.InputError, match="unknown key `ratio`"):
        vibrissa.Rod(stiffness={"kind": "uniform", "ratio": 0.5})
    with pytest.raises(vibrissa.InputError, match=r"expected a stiffness table: \{ kind = \"uniform\" \}"):
        vibrissa.Rod(stiffness=3)
    with pytest.raises(vibrissa.InputError, match="either taper or stiffness"):
        vibrissa.Rod(taper=0.5, stiffness={"kind": "uniform"})
    table = vibrissa.Rod(stiffness={"kind": "table", "s": [0, 1], "b": [1, 2]})
    assert table.to_dict()["stiffness"] == {"kind": "table", "s": [0.0, 1.0], "b": [1.0, 2.0]}
    rod, surface = vibrissa.load_scene(SCENES / "rat_mystacial_long.toml")
    assert surface.eta == 0.9
    assert rod.to_dict()["physical"] == {
        "length_mm": 45.0,
        "youngs_modulus_gpa": 3.3,
        "base_diameter_um": 180.0,
    }
    rod2, surface2 = vibrissa.scene(eta=0.9, taper=0.1, precurvature=-0.72, physical=rod.to_dict()["physical"])
    assert rod2.to_dict() == rod.to_dict() and surface2.eta == 0.9
    # the file's keys too: precurvature as a table
    rod3, _ = vibrissa.scene(precurvature={"kind": "table", "s": [0, 1], "k": [0.1, -0.1]})
    assert rod3.to_dict()["precurvature"] == {"kind": "table", "s": [0.0, 1.0], "k": [0.1, -0.1]}
    # and the flags override them, as on the command line
    rod4, _ = vibrissa.scene(stiffness={"kind": "taper", "ratio": 0.2}, taper=0.4)
    assert rod4.to_dict()["stiffness"] == {"kind": "taper", "ratio": 0.4}


def test_scan_returns_columns_events_and_stop_reasons():
    r = vibrissa.scan(vibrissa.Rod(), vibrissa.Surface(0.75), points=11, mu0=0.5, shape_points=5)
    assert isinstance(r.points["mu"], np.ndarray) and r.points["mu"].dtype == np.float64
    assert r.points["flex"].dtype == np.int64
    # the slip is located inside the step and is the last point, with its name
    assert r.points["event"] == [None, "slip"]
    assert r.stop_reason == "slip" and r.stop["reason"] == "slip"
    assert r.stop["mu"] == pytest.approx(0.5, abs=1e-12)
    assert r.points["mu"][-1] == pytest.approx(0.5, abs=1e-12)
    assert r.range_end == "event"
    # s_flex: None in the library (no flex point); a column with no value at all stays a list
    assert r.points["s_flex"] == [None, None] and r.start["s_flex"] is None
    full = vibrissa.scan(vibrissa.Rod(), points=6)
    assert math.isnan(full.points["s_flex"][0]) and full.points["s_flex"][1] > 0
    assert r.shapes["x"].shape == (2, 5) and r.shapes["s"][0, -1] == 1.0
    # the rod touches the surface at its tip: y(1) = eta for every shape
    np.testing.assert_allclose(r.shapes["y"][:, -1], 0.75, atol=1e-9)
    assert len(r) == 2 and "slip" in repr(r)
    assert r.handover is None


def test_a_handover_to_the_own_shooter_is_said():
    # a start that traps the rod between a side and the tip (docs/robustness.md, third grid)
    rod, surface = vibrissa.scene(
        eta=0.55, precurvature=0.3, precurvature_slope=-0.2, surface_angle=0.2
    )
    r = vibrissa.scan(rod, surface, points=11, method="multiple-shooting")
    assert r.stop_reason == "contact_change"
    assert "the scan ran on the rod's own shooter" in r.handover


def test_scan_points_carry_each_contacts_forces():
    # a side and the tip from the start (the scene of test_a_handover_to_the_own_shooter_is_said)
    rod, surface = vibrissa.scene(
        eta=0.55, precurvature=0.3, precurvature_slope=-0.2, surface_angle=0.2
    )
    r = vibrissa.scan(rod, surface, points=11)
    assert len(r.contacts) == len(r)
    first = r.contacts[0]
    assert [c["tip"] for c in first] == [False, True] and first[0]["s"] < 1.0
    for cs, n, peak in zip(r.contacts, r.points["normal"], r.points["mu_peak"]):
        # the row's total and its peak ratio are its contacts'
        assert sum(c["normal"] for c in cs) == pytest.approx(n, rel=1e-12)
        assert max(abs(c["tangential"]) / c["normal"] for c in cs) == pytest.approx(peak, rel=1e-12)
        assert all(c["hold"]["state"] == "stuck" for c in cs)
    # the closed forms give the tip alone, T = mu N
    a = vibrissa.scan(vibrissa.Rod(), points=3, method="analytic")
    (tip,) = a.contacts[1]
    assert tip["tip"] and tip["tangential"] == pytest.approx(a.points["mu"][1] * tip["normal"])


def test_scan_at_given_displacements():
    d = [0.0, 0.05, 0.13, 0.2]
    r = vibrissa.scan(vibrissa.Rod(), d=d, d_max=0.2)
    assert list(r.points["d"]) == d
    full = vibrissa.scan(vibrissa.Rod(), points=5, d_max=0.2)
    # d = 0.05 lies on both grids
    assert r.points["mu"][1] == pytest.approx(full.points["mu"][1], abs=1e-9)


def test_solve_matches_the_closed_form():
    # the paper's Fig. 3 rod: f = 4.718136... (closed form, README)
    s = vibrissa.solve(vibrissa.Rod(), -0.3927, phi1=0.3927)
    a = vibrissa.solve(vibrissa.Rod(), -0.3927, phi1=0.3927, method="analytic")
    assert a["f"] == 4.718136345368394
    assert s["f"] == pytest.approx(a["f"], rel=1e-9)
    assert s["s_flex"] is None and s["load_reversals"] == 0
    sh = s["shape"]
    assert set(sh) == {"s", "x", "y", "phi", "kappa", "m"} and len(sh["x"]) == 101
    assert sh["x"][-1] == pytest.approx(s["x1"], abs=1e-12)
    with pytest.raises(vibrissa.InputError, match="exactly one tip condition"):
        vibrissa.solve(vibrissa.Rod(), 0.0, phi1=0.3, eta=0.5)
    with pytest.raises(vibrissa.InputError, match="invalid branch 'sideways'"):
        vibrissa.solve(vibrissa.Rod(), 0.0, phi1=0.3, branch="sideways")
    with pytest.raises(vibrissa.InputError, match="method analytic is not available"):
        vibrissa.solve(vibrissa.Rod(taper=0.5), 0.0, phi1=0.3, method="analytic")


def test_infer_and_its_range_error():
    r = vibrissa.infer(vibrissa.Rod(), vibrissa.Surface(), 0.1)
    # the closed forms (`vibrissa infer --d0 0.1 --method analytic`): mu(0.1) = 0.71838487597678,
    # the maximum at d = 0.1300976131 (located on function values there, ~1e-8)
    assert r["mu0"] == pytest.approx(0.7183848759767809, abs=1e-10)
    lo, hi = r["measurable_d"]
    assert lo == 0.0 and hi == pytest.approx(0.13009761314200385, abs=1e-8)
    with pytest.raises(vibrissa.InputError, match=r"d0 = 0\.2 is outside the measurable range"):
        vibrissa.infer(vibrissa.Rod(), vibrissa.Surface(), 0.2)


def test_sweep_rows_keep_going_past_failures():
    scenes = vibrissa.grid(eta=[0.6, 0.75], precurvature=[-3.0, 0.0])
    assert scenes == [
        {"eta": 0.6, "precurvature": -3.0},
        {"eta": 0.6, "precurvature": 0.0},
        {"eta": 0.75, "precurvature": -3.0},
        {"eta": 0.75, "precurvature": 0.0},
    ]
    sw = vibrissa.sweep(scenes, points=21, jobs=2)
    assert len(sw) == 4
    err = sw["error"]
    assert err[1] is None and err[3] is None
    # a scene that cannot start is an error row, not an exception
    assert any(e is not None for e in (err[0], err[2]))
    failed = [i for i, e in enumerate(err) if e is not None]
    assert all(math.isnan(sw["mu_max"][i]) for i in failed)
    single = vibrissa.scan(vibrissa.Rod(), vibrissa.Surface(0.75), points=21)
    assert sw["mu_max"][3] == single.mu_max
    assert sw["end_d"][3] == single.points["d"][-1]
    assert sw["points"][3] == len(single)
    with pytest.raises(vibrissa.InputError, match="unknown grid axis"):
        vibrissa.grid(height=[0.5])
    # invalid values are refused before any work
    with pytest.raises(vibrissa.InputError, match="taper ratio = 2"):
        vibrissa.sweep(vibrissa.grid(taper=[0.5, 2.0]))


def test_columns_are_generic():
    # new keys of the library's rows become columns by themselves
    cols = vibrissa.columns([{"a": 1, "b": None, "c": {"x": 0.5}}, {"a": 2, "b": 1.5, "c": {"x": None}, "new": "t"}])
    assert list(cols) == ["a", "b", "c_x", "new"]
    assert cols["a"].dtype == np.int64
    assert np.isnan(cols["b"][0]) and cols["b"][1] == 1.5
    assert cols["new"] == [None, "t"]


def test_to_pandas_when_pandas_is_installed():
    pd = pytest.importorskip("pandas")
    df = vibrissa.scan(vibrissa.Rod(), points=3).to_pandas()
    assert isinstance(df, pd.DataFrame) and list(df["d"]) == [0.0, 0.25, 0.5]


def test_sweep_releases_the_gil():
    # while the compiled sweep runs on another thread, this thread runs Python (which needs the
    # GIL): it finishes a short piece of work early in the sweep; with the GIL held for the
    # sweep it could only start at the sweep's end (checked on a build without `detach`)
    import threading
    import time

    parts = [vibrissa.scene(**s) for s in vibrissa.grid(eta=np.linspace(0.7, 0.9, 400))]
    started = threading.Event()
    span = []

    def work():
        started.set()
        t0 = time.perf_counter()
        vibrissa._core.sweep(parts, jobs=1)  # ~1 s: 400 scans on one thread
        span.extend([t0, time.perf_counter()])

    t = threading.Thread(target=work)
    t.start()
    started.wait()
    total = sum(i * i for i in range(1000))  # Python bytecode: ~0.1 ms with the GIL
    finished = time.perf_counter()
    t.join()
    t0, t1 = span
    assert total == 332833500
    assert finished - t0 < 0.5 * (t1 - t0), (finished - t0, t1 - t0)
