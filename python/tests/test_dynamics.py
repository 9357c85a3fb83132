"""Issue 32: the rod in time from Python. ``dynamics_free``, ``dynamics_drag`` and ``modes``
give the program's numbers (its ``--json``, the library's result) field by field, and refuse
what the program refuses."""

import csv
import inspect
import io
import json
import re

import numpy as np
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
            if isinstance(b[k], (str, dict)):
                assert a[k] == b[k], f"{what} sample {i}: {k}"
            else:
                same(a[k], b[k], f"{what} sample {i}: {k}")
        for k in b:
            if isinstance(b[k], dict):
                # (a side's place: the columns side_s, side_x, side_y)
                for kk, v in b[k].items():
                    same(py["samples"][f"{k}_{kk}"][i], v, f"{what} column {k}_{kk} row {i}")
            elif not isinstance(b[k], str):
                same(py["samples"][k][i], b[k], f"{what} column {k} row {i}")


def test_dynamics_free_equals_the_program(program):
    args = ["dynamics", "free", "--release-fx", "1e-3", "--dt", "0.05", "--t-end", "0.5"]
    want = json.loads(program(*args, "--json"))
    py = vibrissa.dynamics_free(vibrissa.Rod(), release_force=(1e-3, 0.0), dt=0.05, t_end=0.5)
    check_samples(py, want["samples"], " ".join(args))
    assert py["stats"] == want["stats"]
    assert py["units"] is None and py["time_unit_s"] is None


def test_rotary_inertia_equals_the_program(program):
    # the slopes' inertia in both dynamics commands; it changes the motion
    args = ["dynamics", "free", "--release-fx", "1e-3", "--dt", "0.05", "--t-end", "0.5",
            "--rotary-inertia", "0.05"]
    want = json.loads(program(*args, "--json"))
    py = vibrissa.dynamics_free(vibrissa.Rod(), release_force=(1e-3, 0.0), dt=0.05, t_end=0.5,
                                rotary_inertia=0.05)
    check_samples(py, want["samples"], " ".join(args))
    plain = vibrissa.dynamics_free(vibrissa.Rod(), release_force=(1e-3, 0.0), dt=0.05,
                                   t_end=0.5)
    assert py["samples"]["tip_x"][-1] != plain["samples"]["tip_x"][-1]
    args = ["dynamics", "drag", "--speed", "0.1", "--d-max", "0.003", "--dt", "0.05",
            "--rotary-inertia", "0.05"]
    want = json.loads(program(*args, "--json"))
    py = vibrissa.dynamics_drag(vibrissa.Rod(), speed=0.1, d_max=0.003, dt=0.05,
                                rotary_inertia=0.05)
    check_samples(py, want["samples"], " ".join(args))
    with pytest.raises(vibrissa.InputError, match="rotary_inertia"):
        vibrissa.dynamics_free(vibrissa.Rod(), rotary_inertia=0.2)


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


# Every option of `vibrissa dynamics free|drag` (issue 32, Python parity): the program's flags
# and Python's keywords name the same library options; time_tol, the dampers, the friction table
# give the program's numbers; the defaults are the library's and its checks refuse.

# the program's flags that are not options of the computation, or are named otherwise here
NOT_OPTIONS = {"help", "json", "spectrum", "eta", "scene"}
# the drag's texture flags set the surface (Python: ``Surface(profile=...)``), not an option
NOT_OPTIONS |= {"corrugation-amplitude", "corrugation-wavelength", "corrugation-phase",
                "grating-period", "grating-depth", "grating-flank-angle", "grating-ridge-radius",
                "grating-offset", "surface-profile", "profile-tolerance"}
RENAMED = {"release-fx": "release_force", "release-fy": "release_force"}


def flags_of(program, command):
    """The long flags of `vibrissa dynamics COMMAND --help` before its scene's flags."""
    text = program("dynamics", command, "--help")
    text = text.split("Scene:")[0]
    return {m.group(1) for m in re.finditer(r"^\s+--([a-z0-9-]+)", text, re.M)}


@pytest.mark.parametrize("command", ["free", "drag"])
def test_every_flag_of_the_program_is_a_keyword(program, command):
    flags = flags_of(program, command) - NOT_OPTIONS
    assert "time-tol" in flags and "internal-damping" in flags, flags
    params = inspect.signature(getattr(vibrissa, f"dynamics_{command}")).parameters
    missing = [f for f in flags if RENAMED.get(f, f.replace("-", "_")) not in params]
    assert not missing, f"dynamics {command}: flags without a keyword: {missing}"


@pytest.mark.parametrize("command", ["free", "drag"])
def test_keyword_defaults_are_the_library_s(command):
    lib = vibrissa._core.defaults()[f"dynamics_{command}"]
    params = inspect.signature(getattr(vibrissa, f"dynamics_{command}")).parameters
    checked = 0
    for name, p in params.items():
        if name in ("rod", "surface"):
            continue
        if name in ("time_tol", "whisk"):
            # the library's default is None (fixed steps, no whisk), which its dict leaves out
            assert name not in lib and p.default is None
        elif name == "foot_table":
            assert [tuple(x) for x in p.default] == [tuple(x) for x in lib["foot_table"]]
        elif name == "release_force":
            assert tuple(p.default) == tuple(lib["release_force"])
        elif name in ("mu_s", "mu_k"):
            # None: the surface's friction texture, else the library's default
            assert name in lib and p.default is None
        elif name == "mu_k_table":
            assert [tuple(x) for x in p.default] == [tuple(x) for x in lib["mu_k_table"]]
        else:
            assert p.default == lib[name], f"{command} {name}: {p.default!r} != {lib[name]!r}"
        checked += 1
    assert checked >= 10


def test_dynamics_free_with_time_tol_equals_the_program(program):
    args = ["dynamics", "free", "--release-fx", "1e-4", "--dt", "0.05", "--t-end", "2",
            "--time-tol", "1e-9"]
    want = json.loads(program(*args, "--json"))
    py = vibrissa.dynamics_free(vibrissa.Rod(), release_force=(1e-4, 0.0), dt=0.05, t_end=2.0,
                                time_tol=1e-9)
    check_samples(py, want["samples"], " ".join(args))
    assert py["stats"] == want["stats"]
    # the adaptive steps: a first step shorter than dt (the release), steps of unequal length,
    # rejected steps counted; the fixed run has t_end/dt steps and no rejected ones
    fixed = vibrissa.dynamics_free(vibrissa.Rod(), release_force=(1e-4, 0.0), dt=0.05, t_end=2.0)
    assert fixed["stats"]["steps"] == 40 and "rejected_steps" not in fixed["stats"]
    assert py["stats"]["rejected_steps"] > 0
    assert py["stats"]["steps"] != fixed["stats"]["steps"]
    steps = np.diff(py["samples"]["t"])
    assert steps[0] < 0.05 and steps.max() > 1.5 * steps.min()
    same(py["samples"]["t"][-1], 2.0, "the adaptive run's end")


def test_dynamics_free_with_dampers_equals_the_program(program):
    args = ["dynamics", "free", "--release-fx", "1e-3", "--dt", "0.05", "--t-end", "1",
            "--internal-damping", "0.01", "--external-damping", "0.2", "--foot-damping", "0.1",
            "--support-compliance", "0.5"]
    want = json.loads(program(*args, "--json"))
    rod = vibrissa.Rod(support_compliance=0.5)
    py = vibrissa.dynamics_free(rod, release_force=(1e-3, 0.0), dt=0.05, t_end=1.0,
                                internal_damping=0.01, external_damping=0.2, foot_damping=0.1)
    check_samples(py, want["samples"], " ".join(args))
    assert py["stats"] == want["stats"]


def test_the_energy_momentum_step_equals_the_program(program):
    """``time_scheme="energy_momentum"`` is the program's ``--time-scheme energy-momentum`` and
    the default of fixed steps: the release from a tip force keeps the stored energy in its
    first step (Newmark's rule, ``time_scheme="newmark"``, loses about 1 % there: the mean of
    the force before and after the jump), and the scheme refuses adaptive steps by name
    (docs/model.md, "The energy of a large oscillation")."""
    args = ["dynamics", "free", "--release-fx", "1e-3", "--dt", "0.05", "--t-end", "0.5",
            "--grid", "50", "--tol", "1e-8", "--time-scheme", "energy-momentum"]
    want = json.loads(program(*args, "--json"))
    kw = dict(release_force=(1e-3, 0.0), dt=0.05, t_end=0.5, grid=50, tol=1e-8)
    py = vibrissa.dynamics_free(vibrissa.Rod(), time_scheme="energy_momentum", **kw)
    check_samples(py, want["samples"], " ".join(args))
    assert py["stats"] == want["stats"]
    # the default scheme of fixed steps is this one
    default = vibrissa.dynamics_free(vibrissa.Rod(), **kw)
    assert default["samples_rows"] == py["samples_rows"]
    newmark = vibrissa.dynamics_free(vibrissa.Rod(), time_scheme="newmark", **kw)
    for r, lo, hi in ((py, 0.0, 1e-5), (newmark, 5e-3, 5e-2)):
        e = r["samples"]["kinetic"] + r["samples"]["elastic"]
        lost = abs(e[1] / e[0] - 1.0)
        assert lo <= lost < hi, lost
    with pytest.raises(vibrissa.InputError, match="energy-momentum"):
        vibrissa.dynamics_free(vibrissa.Rod(), time_scheme="energy_momentum", time_tol=1e-8)
    with pytest.raises(vibrissa.InputError, match="time_scheme"):
        vibrissa.dynamics_free(vibrissa.Rod(), time_scheme="verlet")


def test_damping_makes_the_energy_fall():
    """External damping gamma_e = 0.2 takes energy (every mode of the linearized rod decays at
    gamma_e/2: the energy by e^(-0.4) = 0.67 over t = 2), internal damping takes some more,
    and the energy the rod loses is what the dampers take: the library's identity, its unit
    test `damping_takes_the_lost_energy` asserts the balance to 3e-8 from step 1 on for
    Newmark's rule (whose first step of a release loses about 1 % to the jump of the force);
    the default scheme of fixed steps, the energy-momentum step, balances from the start
    (measured 3.5e-9). Undamped, the rod keeps its energy from the start (measured within
    4.8e-7, alternating from step to step: the modes the release rings; the library's test
    `release_from_a_tip_load_keeps_the_stored_energy`)."""
    kw = dict(release_force=(1e-3, 0.0), dt=0.02, t_end=2.0)
    free = vibrissa.dynamics_free(vibrissa.Rod(), **kw)
    damped = vibrissa.dynamics_free(vibrissa.Rod(), internal_damping=0.01,
                                    external_damping=0.2, **kw)
    s, d = free["samples"], damped["samples"]
    e_free = s["kinetic"] + s["elastic"]
    assert np.all(np.abs(e_free / e_free[0] - 1.0) < 1e-6)
    assert not np.any(s["internal_damping"]) and not np.any(s["external_damping"])
    e = d["kinetic"] + d["elastic"]
    assert e[-1] < 0.8 * e[1], (e[1], e[-1])
    assert np.all(np.diff(d["internal_damping"]) >= 0) and d["internal_damping"][-1] > 0
    assert np.all(np.diff(d["external_damping"]) >= 0) and d["external_damping"][-1] > 0
    total = e + d["dissipated"] + d["internal_damping"] + d["external_damping"]
    assert np.all(np.abs(total / total[0] - 1.0) < 3e-8)


def test_dynamics_drag_with_every_option_equals_the_program(program):
    # adaptive steps, the three dampers and a friction table, through the first slip
    args = ["dynamics", "drag", "--speed", "0.05", "--d-max", "0.025", "--dt", "0.02",
            "--time-tol", "1e-6", "--internal-damping", "0.001", "--external-damping", "0.01",
            "--foot-damping", "0.05", "--support-compliance", "0.1",
            "--mu-k-table", "0:0.3,0.1:0.25", "--flight"]
    want = json.loads(program(*args, "--json"))
    rod = vibrissa.Rod(support_compliance=0.1)
    py = vibrissa.dynamics_drag(rod, vibrissa.Surface(eta=0.75), speed=0.05, d_max=0.025,
                                dt=0.02, time_tol=1e-6, internal_damping=0.001,
                                external_damping=0.01, foot_damping=0.05,
                                mu_k_table=[(0.0, 0.3), (0.1, 0.25)], flight=True)
    check_samples(py, want["samples"], " ".join(args))
    assert py["events"] == want["events"]
    assert py["stop"] == want["stop"]
    assert py["stats"] == want["stats"]
    assert any(e["kind"] == "slip" for e in py["events"]), py["events"]
    assert py["stats"]["rejected_steps"] > 0


def test_a_flying_tip_touches_down_and_the_drag_goes_on():
    # the library's scene of tests/dynamic_drag.rs (a_flying_tip_touches_down_and_goes_on):
    # since the impact's steps, a touchdown is an event, not the drag's end
    rod = vibrissa.Rod(precurvature=1.0)
    r = vibrissa.dynamics_drag(rod, vibrissa.Surface(eta=0.83), speed=0.3, ramp=0.2, d_max=0.3,
                               dt=0.005, grid=100, tol=1e-8, flight=True)
    kinds = [e["kind"] for e in r["events"]]
    assert r["stop"]["reason"] == "d_max", r["stop"]
    assert kinds[:3] == ["slip", "lift_off", "touchdown"], kinds
    down = kinds.index("touchdown")
    assert "lift_off" in kinds[down + 1:], kinds
    for e in r["events"]:
        if e["kind"] == "lift_off":
            assert abs(e["normal"]) < 1e-8, e
    assert r["samples"]["impact"][-1] > 0.0
    assert "touchdown" not in str(r["stop"])


def test_dynamics_drag_grid_and_tol_reach_the_library():
    kw = dict(speed=0.1, d_max=0.003, dt=0.05)
    base = vibrissa.dynamics_drag(vibrissa.Rod(), **kw)
    coarse = vibrissa.dynamics_drag(vibrissa.Rod(), grid=100, tol=1e-8, **kw)
    assert coarse["stats"]["max_nodes"] < base["stats"]["max_nodes"]
    assert coarse["samples"]["m_base"][-1] != base["samples"]["m_base"][-1]


def test_options_out_of_range_raise_the_library_s_error():
    rod = vibrissa.Rod()
    for kw, name in [
        (dict(time_tol=1.0), "time_tol"),
        (dict(time_tol=0.0), "time_tol"),
        (dict(internal_damping=-1.0), "internal_damping"),
        (dict(external_damping=2e6), "external_damping"),
        (dict(foot_damping=-0.1), "foot_damping"),
        (dict(grid=101), "grid"),
        (dict(tol=1.0), "tol"),
    ]:
        with pytest.raises(vibrissa.InputError, match=name):
            vibrissa.dynamics_free(rod, **kw)
        with pytest.raises(vibrissa.InputError, match=name):
            vibrissa.dynamics_drag(rod, **kw)
    with pytest.raises(vibrissa.InputError, match=r"time_tol.*\[1e-14, 1e-1\]"):
        vibrissa.dynamics_free(rod, time_tol=1e-15)
    for kw, name in [
        (dict(mu_k_table=[(0.0, 0.6)]), "mu_k_table"),
        (dict(mu_k_table=[(0.1, 0.2), (0.0, 0.2)]), "mu_k_table"),
        (dict(event_tol=1.0), "event_tol"),
        (dict(max_events=0), "max_events"),
        (dict(refinements=11), "refinements"),
    ]:
        with pytest.raises(vibrissa.InputError, match=name):
            vibrissa.dynamics_drag(rod, **kw)


def test_refinements_equal_the_program(program):
    # the coarse drag of tests/dynamic_drag.rs (a_stick_the_step_does_not_resolve_is_taken_
    # again_with_shorter_steps): at dt 0.05 its stick at d 0.1297 is not resolved; taken again
    # at dt/2 it is, and the drag reaches d_max; without refinements it stops there by name
    flags = ["--speed", "0.05", "--dt", "0.05", "--d-max", "0.15", "--tol", "1e-8", "--grid",
             "20", "--max-events", "200"]
    kw = dict(speed=0.05, dt=0.05, d_max=0.15, tol=1e-8, grid=20, max_events=200)
    for k, reason in ((0, "unresolved_stick"), (3, "d_max")):
        args = ["dynamics", "drag", *flags, "--refinements", str(k)]
        want = json.loads(program(*args, "--json"))
        py = vibrissa.dynamics_drag(vibrissa.Rod(), vibrissa.Surface(eta=0.75), refinements=k,
                                    **kw)
        check_samples(py, want["samples"], " ".join(args))
        assert py["events"] == want["events"]
        assert py["stop"] == want["stop"]
        assert py["stats"] == want["stats"]
        assert py["stop"]["reason"] == reason, py["stop"]
        assert py["stats"].get("refinements", 0) == (0 if k == 0 else 1), py["stats"]


def test_a_whisk_over_a_foot_table_equals_the_program(program, tmp_path):
    # the foot drawn forward and back by a table while its support whisks (issue 32)
    table = tmp_path / "foot.csv"
    table.write_text("t,d,theta\n0,0,0\n0.4,0.004,0.01\n0.8,0.002,0.0\n")
    args = ["dynamics", "drag", "--foot-table", str(table), "--whisk", "0.05,0.5",
            "--dt", "0.05"]
    want = json.loads(program(*args, "--json"))
    rows = [(0, 0, 0), (0.4, 0.004, 0.01), (0.8, 0.002, 0.0)]
    py = vibrissa.dynamics_drag(vibrissa.Rod(), vibrissa.Surface(eta=0.75), foot_table=rows,
                                whisk=(0.05, 0.5), dt=0.05)
    check_samples(py, want["samples"], " ".join(args))
    assert py["stop"] == want["stop"] == {"reason": "table_end"}
    assert py["samples"]["theta"][-1] == pytest.approx(0.05 * (1 - np.cos(2 * np.pi * 0.5 * 0.8)) / 2)
    assert [e["kind"] for e in py["events"]] == ["slip", "stick"]
    csv = program(*args).splitlines()
    assert csv[0].startswith("t,d,theta,tip_x")
    with pytest.raises(vibrissa.InputError, match="foot"):
        vibrissa.dynamics_drag(vibrissa.Rod(), foot_table=[(0.1, 0, 0), (1, 0.1, 0)])
    with pytest.raises(ValueError, match="row 1"):
        vibrissa.dynamics_drag(vibrissa.Rod(), foot_table=[(0, 0), (1, 0.1, 0, 4)])
    with pytest.raises(vibrissa.InputError, match="d_max given with it"):
        vibrissa.dynamics_drag(vibrissa.Rod(), foot_table=rows, d_max=0.1)


def test_two_contacts_in_time_equal_the_program(program):
    # over the corrugation 0.02 sin(2 pi x/0.2) at v 0.01 the free tip beyond a sliding side
    # touches down beside it: two contacts (the tip's in the tip_also columns), then the side
    # lifts off (docs/model.md, "Two contacts in time")
    args = ["dynamics", "drag", "--speed", "0.01", "--d-max", "0.0135", "--dt", "0.01",
            "--grid", "100", "--tol", "1e-8", "--corrugation-amplitude", "0.02",
            "--corrugation-wavelength", "0.2"]
    want = json.loads(program(*args, "--json"))
    surface = vibrissa.Surface(eta=0.75, profile={"kind": "sine", "amplitude": 0.02,
                                                 "wavelength": 0.2})
    py = vibrissa.dynamics_drag(vibrissa.Rod(), surface, speed=0.01, d_max=0.0135, dt=0.01,
                                grid=100, tol=1e-8)
    check_samples(py, want["samples"], " ".join(args))
    assert py["events"] == want["events"]
    assert py["stop"] == want["stop"]
    kinds = [e["kind"] for e in py["events"]]
    assert kinds[-2:] == ["touchdown", "lift_off"], kinds
    assert py["events"][-2]["tip_also"] == "sliding_forward"
    assert "tip_also" not in py["events"][-1]
    pair = [i for i, st in enumerate(py["samples"]["tip_also_state"]) if st is not None]
    assert pair, py["samples"]["tip_also_state"]
    for i in pair:
        assert py["samples"]["tip_also_state"][i] == "sliding_forward"
        n, t = py["samples"]["tip_also_normal"][i], py["samples"]["tip_also_tangential"][i]
        assert n > 0 and abs(t - 0.3 * n) < 1e-8 * n
    assert np.isnan(py["samples"]["tip_also_normal"][0])
    # the program's CSV has the same in its columns tip_state, tip_normal, tip_tangential
    rows = list(csv.DictReader(io.StringIO(program(*args))))
    assert [r["tip_state"] for r in rows] == [st or "" for st in py["samples"]["tip_also_state"]]


def test_dynamics_drag_on_a_corrugation_equals_the_program(program):
    # the tip over a sine corrugation through its first slip, and the rod's end lying down:
    # a side rolling on the surface from there (its place in the columns side_s, side_x, side_y)
    for amp, wl, d_max in (("0.003", "0.1", "0.013"), ("0.02", "0.2", "0.002")):
        args = ["dynamics", "drag", "--speed", "0.05", "--d-max", d_max, "--dt", "0.02",
                "--corrugation-amplitude", amp, "--corrugation-wavelength", wl]
        want = json.loads(program(*args, "--json"))
        surface = vibrissa.Surface(eta=0.75, profile={"kind": "sine", "amplitude": float(amp),
                                                     "wavelength": float(wl)})
        py = vibrissa.dynamics_drag(vibrissa.Rod(), surface, speed=0.05, d_max=float(d_max),
                                    dt=0.02)
        check_samples(py, want["samples"], " ".join(args))
        assert py["events"] == want["events"]
        assert py["stop"] == want["stop"]
        assert py["stats"] == want["stats"]
    assert py["stop"]["reason"] == "d_max", py["stop"]
    assert py["events"][-1]["kind"] == "side_contact", py["events"]
    rolling = [i for i, st in enumerate(py["samples"]["state"]) if st == "side_stuck"]
    assert len(rolling) > 3
    assert all(0.99 < py["samples"]["side_s"][i] < 1.0 for i in rolling)
    assert np.isnan(py["samples"]["side_s"][0])
    tapered = vibrissa.Rod(taper=0.3)
    fine = vibrissa.Surface(eta=0.75, profile={"kind": "sine", "amplitude": 0.001,
                                               "wavelength": 0.02})
    with pytest.raises(vibrissa.Error, match="side"):
        vibrissa.dynamics_drag(tapered, fine, d_max=0.001)


def test_dynamics_drag_on_friction_patches_equals_the_program(program, tmp_path):
    # the scene's [friction] patches: the first slip where the patch under the tip lets go, a
    # boundary crossed in the slide (event ``patch``); given mu_s, mu_k replace the texture
    scene = tmp_path / "patches.toml"
    scene.write_text(
        "eta = 0.75\n[friction]\nkind = \"patches\"\nperiod = 0.1\nx = [0.0, 0.05]\n"
        "mu_s = [0.5, 0.4]\nmu_k = [0.3, 0.2]\noffset = 0.6\n"
    )
    friction = {"kind": "patches", "period": 0.1, "x": [0.0, 0.05], "mu_s": [0.5, 0.4],
                "mu_k": [0.3, 0.2], "offset": 0.6}
    surface = vibrissa.Surface(eta=0.75, friction=friction)
    args = ["dynamics", "drag", "--scene", str(scene), "--speed", "0.05", "--d-max", "0.03",
            "--dt", "0.02"]
    want = json.loads(program(*args, "--json"))
    py = vibrissa.dynamics_drag(vibrissa.Rod(), surface, speed=0.05, d_max=0.03, dt=0.02)
    check_samples(py, want["samples"], " ".join(args))
    assert py["events"] == want["events"]
    assert [e["kind"] for e in py["events"]][:3] == ["slip", "patch", "stick"]
    slip = py["events"][0]
    assert abs(slip["tangential"] - 0.4 * slip["normal"]) < 1e-9 * slip["normal"]
    plain = vibrissa.dynamics_drag(vibrissa.Rod(), speed=0.05, d_max=0.03, dt=0.02)
    given = vibrissa.dynamics_drag(vibrissa.Rod(), surface, speed=0.05, d_max=0.03, dt=0.02,
                                   mu_s=0.5, mu_k=0.3)
    assert given["events"] == plain["events"]
    flags = json.loads(program(*args, "--mu-s", "0.5", "--mu-k", "0.3", "--json"))
    assert flags["events"] == plain["events"]


def test_dynamics_drag_with_a_round_tip_equals_the_program(program):
    # a round tip on the flat surface (it needs internal damping: without, the library's
    # error names it), its centre 0.02 below the surface
    args = ["dynamics", "drag", "--tip-radius", "0.02", "--internal-damping", "1e-4",
            "--speed", "0.05", "--dt", "0.05", "--d-max", "0.025"]
    want = json.loads(program(*args, "--json"))
    rod = vibrissa.Rod(tip_radius=0.02)
    py = vibrissa.dynamics_drag(rod, speed=0.05, dt=0.05, d_max=0.025, internal_damping=1e-4)
    check_samples(py, want["samples"], " ".join(args))
    assert py["events"] == want["events"]
    assert [e["kind"] for e in py["events"]][:1] == ["slip"]
    assert all(abs(y - 0.73) < 1e-9 for y in py["samples"]["tip_y"])
    with pytest.raises(vibrissa.InputError, match="internal damping"):
        vibrissa.dynamics_drag(rod, d_max=0.01)
    # on a corrugation the disk's centre runs r from the profile (the program's, field by field)
    args = ["dynamics", "drag", "--tip-radius", "0.02", "--internal-damping", "1e-4",
            "--corrugation-amplitude", "0.005", "--corrugation-wavelength", "0.2",
            "--speed", "0.05", "--dt", "0.05", "--d-max", "0.012"]
    want = json.loads(program(*args, "--json"))
    surface = vibrissa.Surface(eta=0.75, profile={"kind": "sine", "amplitude": 0.005,
                                                 "wavelength": 0.2})
    py = vibrissa.dynamics_drag(rod, surface, speed=0.05, dt=0.05, d_max=0.012,
                                internal_damping=1e-4)
    check_samples(py, want["samples"], " ".join(args))
    assert py["events"] == want["events"]
    assert [e["kind"] for e in py["events"]][:1] == ["slip"]
