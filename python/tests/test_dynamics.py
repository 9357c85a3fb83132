"""Issue 32: the rod in time from Python. ``dynamics_free``, ``dynamics_drag`` and ``modes``
give the program's numbers (its ``--json``, the library's result) field by field, and refuse
what the program refuses."""

import json

import pytest

import vibrissa
from conftest import SCENES
from test_program import same


def check_samples(py, program_json, what):
    """Every sample of the program's --json equals Python's, field by field."""
    rows = py["samples_rows"]
    assert len(rows) == len(program_json), what
    for i, (a, b) in enumerate(zip(rows, program_json)):
        assert a.keys() == b.keys(), f"{what} sample {i}"
        for k in b:
            if isinstance(b[k], str):
                assert a[k] == b[k], f"{what} sample {i}: {k}"
            else:
                same(a[k], b[k], f"{what} sample {i}: {k}")
        for k in b:
            if not isinstance(b[k], str):
                same(py["samples"][k][i], b[k], f"{what} column {k} row {i}")


def test_dynamics_free_equals_the_program(program):
    args = ["dynamics", "free", "--release-fx", "1e-3", "--dt", "0.05", "--t-end", "0.5"]
    want = json.loads(program(*args, "--json"))
    py = vibrissa.dynamics_free(vibrissa.Rod(), release_force=(1e-3, 0.0), dt=0.05, t_end=0.5)
    check_samples(py, want["samples"], " ".join(args))
    assert py["stats"] == want["stats"]
    assert py["units"] is None and py["time_unit_s"] is None


def test_dynamics_free_with_a_physical_rod_and_a_foot_moment(program, tmp_path):
    # the rat's long whisker (tapered, precurved, physical units) on a compliant, damped foot
    text = (SCENES / "rat_mystacial_long.toml").read_text()
    assert "support_compliance = 0.0" in text
    sc = tmp_path / "rat.toml"
    sc.write_text(text.replace("support_compliance = 0.0", "support_compliance = 0.5"))
    args = ["dynamics", "free", "--scene", str(sc), "--foot-moment", "1e-3",
            "--foot-damping", "0.2", "--dt", "0.05", "--t-end", "0.3"]
    want = json.loads(program(*args, "--json"))
    rod, _ = vibrissa.load_scene(sc)
    py = vibrissa.dynamics_free(rod, foot_moment=1e-3, foot_damping=0.2, dt=0.05, t_end=0.3)
    check_samples(py, want["samples"], " ".join(args))
    assert py["time_unit_s"] > 0 and py["units"]["length_mm"] == 45.0
    assert py["samples"]["theta"][-1] > 0


def test_dynamics_drag_equals_the_program(program):
    args = ["dynamics", "drag", "--speed", "0.1", "--d-max", "0.003", "--dt", "0.05"]
    want = json.loads(program(*args, "--json"))
    py = vibrissa.dynamics_drag(vibrissa.Rod(), vibrissa.Surface(eta=0.75), speed=0.1,
                                d_max=0.003, dt=0.05)
    check_samples(py, want["samples"], " ".join(args))
    assert py["events"] == want["events"]
    assert py["stop"] == want["stop"]
    assert py["stats"] == want["stats"]


def test_modes_equal_the_program(program):
    for args, kw in [
        ([], {}),
        (["--tip", "pinned", "--count", "2"], {"tip": "pinned", "count": 2}),
        (["--fy", "-1", "--m-base", "0.2", "--points", "5"], {"fy": -1.0, "m_base": 0.2, "points": 5}),
        (["--tip", "sliding", "--tip-angle", "0.3", "--fx", "0.1", "--fy", "-2", "--m-base", "0.5"],
         {"tip": "sliding", "tip_angle": 0.3, "fx": 0.1, "fy": -2.0, "m_base": 0.5}),
    ]:
        want = json.loads(program("modes", *args, "--json"))
        py = vibrissa.modes(vibrissa.Rod(), **kw)
        assert py["stable"] == want["stable"], args
        assert len(py["modes"]) == len(want["modes"]), args
        for a, b in zip(py["modes"], want["modes"]):
            for k in ("omega2", "omega"):
                same(a[k], b[k], f"modes {args}: {k}")
            assert len(a.get("shape") or []) == len(b.get("shape") or []), args


def test_dynamics_refuse_what_the_program_refuses():
    with pytest.raises(vibrissa.InputError, match="dt"):
        vibrissa.dynamics_free(vibrissa.Rod(), dt=0.0)
    with pytest.raises(vibrissa.InputError, match="speed"):
        vibrissa.dynamics_drag(vibrissa.Rod(), speed=-1.0)
    with pytest.raises(vibrissa.InputError, match="mu_k"):
        vibrissa.dynamics_drag(vibrissa.Rod(), mu_s=0.3, mu_k=0.5)
    with pytest.raises(vibrissa.InputError, match="tip"):
        vibrissa.modes(vibrissa.Rod(), tip="glued")
    with pytest.raises(vibrissa.InputError, match="tip_angle"):
        vibrissa.modes(vibrissa.Rod(), tip="sliding", tip_angle=2.0)
    with pytest.raises(vibrissa.InputError, match="count"):
        vibrissa.modes(vibrissa.Rod(), count=0)
