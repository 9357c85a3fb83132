"""vibrissa: an elastic whisker pressed on a surface, from Python.

The model and its solvers are the Rust library ``vibrissa`` of this repository (the same code
as the ``vibrissa`` program, so the numbers are the program's to the last digit). Units are
normalized: length L (rod length), force EI/L^2, moment EI/L (EI at the foot), angles in
radians; see the repository's docs/model.md for the model and docs/reference.md for the
columns and their signs.

Example::

    import vibrissa
    rod = vibrissa.Rod(taper=0.3, precurvature=-0.5, support_compliance=0.1)
    result = vibrissa.scan(rod, vibrissa.Surface(eta=0.8), points=51)
    result.points["mu"]      # numpy array, one value per output point
    result.stop              # {'reason': 'd_max'} or {'reason': 'slip', 'd': ..., 'mu': ...}

Results are plain Python values and numpy arrays: ``scan`` returns a :class:`ScanResult` whose
``points`` is a dict of columns (numpy arrays; text columns such as ``event`` are lists of
str or None), ``sweep`` a :class:`Sweep` of one row per scene. Both have ``to_pandas()`` when
pandas is installed. Every field the library adds to its results appears here as a new key or
column by itself (the binding converts the library's structs generically).

Errors are :class:`InputError` (also a ``ValueError``) for values outside their range and
:class:`SolveError` (also a ``RuntimeError``) for failed solves, both :class:`Error`; the
message is the library's.
"""

from __future__ import annotations

import itertools
import os
from typing import Any, Dict, Iterable, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _core
from ._errors import Error, InputError, SolveError

Rod = _core.Rod
Surface = _core.Surface

# the library's defaults (vibrissa::ScanOptions, SolverConfig): one source for the signatures
_DEFAULTS = _core.defaults()
_SOLVER = _DEFAULTS["solver"]

__all__ = [
    "Rod",
    "Surface",
    "ScanResult",
    "Sweep",
    "Error",
    "InputError",
    "SolveError",
    "load_scene",
    "scene",
    "solve",
    "scan",
    "infer",
    "sweep",
    "grid",
    "columns",
    "drag",
    "DragResult",
    "whisk",
    "locate",
    "solve_peg",
    "limits",
    "fit",
    "dynamics_free",
    "dynamics_drag",
    "modes",
]

Column = Union[np.ndarray, List[Any]]


def columns(rows: Sequence[Mapping[str, Any]]) -> Dict[str, Column]:
    """Rows (dicts) to columns, keys in order of first appearance.

    A column of numbers becomes a numpy array (float64, ``None`` as NaN; int64 when every value
    is an integer); anything else (text, nested values, and a column that is ``None`` in every
    row, whose type is unknown) stays a list. Nested dicts
    are flattened with ``_`` (``stop`` → ``stop_reason``, ``stop_d``, ...).
    """
    flat = [_flatten(r) for r in rows]
    keys: Dict[str, None] = {}
    for r in flat:
        for k in r:
            keys.setdefault(k, None)
    out: Dict[str, Column] = {}
    for k in keys:
        out[k] = _column([r.get(k) for r in flat])
    return out


def _flatten(row: Mapping[str, Any], prefix: str = "") -> Dict[str, Any]:
    out: Dict[str, Any] = {}
    for k, v in row.items():
        if isinstance(v, Mapping):
            out.update(_flatten(v, f"{prefix}{k}_"))
        else:
            out[f"{prefix}{k}"] = v
    return out


def _column(values: List[Any]) -> Column:
    numbers = [v for v in values if v is not None]
    if not numbers or not all(
        isinstance(v, (int, float)) and not isinstance(v, bool) for v in numbers
    ):
        return values
    if len(numbers) == len(values) and all(isinstance(v, int) for v in numbers):
        return np.array(values, dtype=np.int64)
    return np.array([np.nan if v is None else v for v in values], dtype=np.float64)


def _to_pandas(cols: Mapping[str, Column]):
    try:
        import pandas as pd
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError("to_pandas() needs pandas: pip install pandas") from e
    return pd.DataFrame(dict(cols))


class ScanResult:
    """The result of :func:`scan`.

    Attributes:
        points: dict of columns, one value per output point (``d``, ``mu``, ``normal``,
            ``alpha``, ``phi1``, ``f``, ``fx``, ``fy``, ``m_base``, ``flex``, ``s_flex``,
            ``y_max``, ``event``, and any column the library adds). The last point is the
            event's (``event`` names it) when the scan stopped at one.
        start: the starting rod (d = 0) as a dict of the same fields.
        mu_max, mu_at_max, d_at_mu_max: largest ``|mu|`` over the measurable range, its signed
            value, and where.
        range_end: what ends the measurable range (``first_maximum``, ``event``, ``d_max``,
            ``solver_failure``).
        stop: why the scan stopped: ``{'reason': 'd_max'}``, ``{'reason': 'slip', 'd': ...,
            'mu': ...}``, ``{'reason': 'penetration', 'd': ..., 's': ..., 'y': ...}``, ...
        stop_reason: ``stop['reason']``.
        stats: solver statistics (Newton iterations, right-hand-side evaluations, ...).
        handover: ``None``, or why the scan ran on the rod's own shooter instead of the
            requested method (in a state that traps the rod between two contacts that do not
            slip, the method could not start or its march failed).
        shapes: with ``shape_points``: dict of arrays of shape (points, shape_points) for
            ``s``, ``x``, ``y``, ``phi``, ``kappa``, ``m`` (foot frame), else ``None``.
        contacts: one list per point of its contacts, in order along the rod (dicts: ``s``,
            ``tip``, ``x``, ``y``, ``normal``, ``tangential``, ``hold`` (``{"state":
            "stuck"}``), ``mu`` (the slip threshold)), as a drag's rows give them: with several
            contacts, each one's own forces.
        raw: everything as the library returned it (nested dicts and lists).
    """

    def __init__(self, raw: Dict[str, Any]):
        self.raw = raw
        self.points: Dict[str, Column] = columns(raw["points"])
        self.start: Dict[str, Any] = raw["start"]
        self.eta: float = raw["eta"]
        self.mu_max: float = raw["mu_max"]
        self.mu_at_max: float = raw["mu_at_max"]
        self.d_at_mu_max: float = raw["d_at_mu_max"]
        self.range_end: str = raw["range_end"]
        self.stop: Dict[str, Any] = raw["stop"]
        self.stop_reason: str = raw["stop"]["reason"]
        self.stats: Dict[str, Any] = raw["stats"]
        self.contacts: List[List[Dict[str, Any]]] = raw["contacts"]
        self.handover: Optional[str] = raw.get("handover")
        self.units: Optional[Dict[str, float]] = raw.get("units")
        if self.units:
            # the program's physical columns (vibrissa scan with a physical scene)
            u = self.units
            p = self.points
            p["d_mm"] = np.asarray(p["d"]) * u["length_mm"]
            for k in ("f", "fx", "fy"):
                p[f"{k}_N"] = np.asarray(p[k]) * u["force_n"]
            p["m_base_Nm"] = np.asarray(p["m_base"]) * u["moment_nm"]
        self.shapes: Optional[Dict[str, np.ndarray]] = None
        if raw["shapes"]:
            per_point = [columns(sh) for sh in raw["shapes"]]
            self.shapes = {
                k: np.array([c[k] for c in per_point]) for k in per_point[0]
            }

    def __len__(self) -> int:
        return len(self.raw["points"])

    def to_pandas(self):
        """The points as a pandas DataFrame (needs pandas)."""
        return _to_pandas(self.points)

    def __repr__(self) -> str:
        return (
            f"ScanResult(eta={self.eta}, points={len(self)}, mu_max={self.mu_max}, "
            f"d_at_mu_max={self.d_at_mu_max}, stop={self.stop})"
        )


class Sweep:
    """The result of :func:`sweep`: one row per scene, in the order given.

    ``rows`` are dicts (the scene's own keys when it came from :func:`grid`, then the scan's
    summary: ``start``, ``end`` (its last point), ``mu_max``, ``d_at_mu_max``, ``range_end``,
    ``stop``, ``stats``, ``error``); ``columns`` the same flattened into numpy columns
    (``start_f``, ``end_mu``, ``stop_reason``, ``stats_newton_iters``, ...). A scene whose scan
    failed has its message in ``error`` and NaN (or None) elsewhere.
    """

    def __init__(self, rows: List[Dict[str, Any]]):
        self.rows = rows
        self.columns: Dict[str, Column] = columns(rows)
        c = self.columns
        # the program's names (vibrissa sweep's CSV) for the same values
        for prog, here in _SWEEP_NAMES.items():
            if here in c:
                c[prog] = c[here]
        if "units_length_mm" in c:
            c["f0_N"] = np.asarray(c["start_f"]) * np.asarray(c["units_force_n"], dtype=float)
            for k in ("d_at_mu_max", "d_end"):
                c[f"{k}_mm"] = np.asarray(c[k]) * np.asarray(c["units_length_mm"], dtype=float)

    def __len__(self) -> int:
        return len(self.rows)

    def __getitem__(self, key: str) -> Column:
        return self.columns[key]

    def to_pandas(self):
        """The rows as a pandas DataFrame (needs pandas)."""
        return _to_pandas(self.columns)

    def __repr__(self) -> str:
        failed = sum(r.get("error") is not None for r in self.rows)
        return f"Sweep({len(self)} scenes, {failed} with an error)"


# the program's sweep columns and where the same value is here
_SWEEP_NAMES = {
    "f0": "start_f",
    "phi1_0": "start_phi1",
    "mu_end": "end_mu",
    "d_end": "end_d",
    "newton_iters": "stats_newton_iters",
    "rhs_evals": "stats_rhs_evals",
}

SceneLike = Union[Tuple[Any, Any], Mapping[str, Any]]


def limits() -> Dict[str, Any]:
    """The valid ranges, the library's (``vibrissa::limits``, the program's too): a dict from
    the value's name (``eta``, ``taper``, ``tol``, ``points``, ``shape_points``, ``alpha``,
    ``mu_s``, ``jobs``, ...) to ``lo``, ``lo_closed``, ``hi``, ``hi_closed``, ``text`` (as the
    error messages write it), ``unit`` and ``why``; and the size limits
    ``memory_budget_bytes`` (kept shapes and scan points), ``jobs_per_core`` and
    ``max_scenes``. A value outside its range raises :class:`InputError` with that text."""
    return _core.limits()


def load_scene(path: Union[str, os.PathLike]) -> Tuple[Any, Any]:
    """``(Rod, Surface)`` of a scene file (TOML, the program's ``--scene`` format). The surface
    carries the file's ``[surface]``, ``[friction]``, ``contact`` and ``start``: the functions
    use them unless told otherwise, so the same file gives the program's answers."""
    with open(path, encoding="utf-8") as f:
        text = f.read()
    try:
        return _core.scene_from_toml(text)
    except InputError as e:
        raise InputError(f"scene file {os.fspath(path)}: {e}") from None


# the flags of `vibrissa sweep` and `scan` (grid keys) and where they go in a scene
_SCENE_KEYS = (
    "eta",
    "taper",
    "precurvature",
    "precurvature_slope",
    "support_compliance",
    "surface_angle",
)


def scene(**keys: Any) -> Tuple[Any, Any]:
    """``(Rod, Surface)`` from the program's flag names (``eta``, ``taper``, ``precurvature``,
    ``precurvature_slope``, ``support_compliance``, ``surface_angle``; ``physical`` a dict) or
    from a scene file's keys (``stiffness``, ``precurvature`` as dicts, ...)."""
    flags: Dict[str, Any] = {}
    file_keys: Dict[str, Any] = {}
    for k, v in keys.items():
        # `precurvature` is a number as a flag (K0), a table as a file key
        if k in _SCENE_KEYS and not isinstance(v, Mapping):
            flags[k] = v
        else:
            file_keys[k] = v
    # flags override the file's keys, as on the command line
    for k in ("eta", "surface_angle", "support_compliance"):
        if k in flags:
            file_keys[k] = flags[k]
    if flags.get("taper") is not None:
        file_keys["stiffness"] = {"kind": "taper", "ratio": flags["taper"]}
    if "precurvature" in flags or "precurvature_slope" in flags:
        k0, k1 = flags.get("precurvature") or 0.0, flags.get("precurvature_slope") or 0.0
        file_keys["precurvature"] = (
            {"kind": "none"} if k0 == 0.0 and k1 == 0.0 else {"kind": "linear", "k0": k0, "k1": k1}
        )
    return _core.scene_from_dict(file_keys)


def _parts(s: SceneLike) -> Tuple[Any, Any]:
    if isinstance(s, Mapping):
        return scene(**s)
    rod, surface = s
    return rod, surface


def solve(
    rod: Any,
    alpha: float,
    *,
    phi1: Optional[float] = None,
    eta: Optional[float] = None,
    tip: Optional[Tuple[float, float]] = None,
    branch: str = "convex",
    method: str = _SOLVER["method"],
    tol: float = _SOLVER["tol"],
    segments: int = _SOLVER["segments"],
    shape_points: int = _DEFAULTS["solve_shape_points"],
    start: str = _SOLVER["start"],
) -> Dict[str, Any]:
    """One rod under a tip force at angle ``alpha`` (rad) with one tip condition: the tip slope
    ``phi1``, the tip height ``eta`` or the tip position ``tip = (x1, y1)``.

    Returns a dict: ``alpha``, ``f``, ``fx``, ``fy``, ``phi1``, ``x1``, ``y1``, ``m_base``,
    ``phi0``, ``flex``, ``load_reversals``, ``s_flex`` (None without a flex point), ``y_max``,
    ``residual``, ``stats``, and ``shape``: a dict of numpy arrays ``s``, ``x``, ``y``,
    ``phi``, ``kappa``, ``m`` at ``shape_points`` points uniform in s. ``branch``: ``convex``,
    ``flex`` or ``any``; ``method``: ``shooting``, ``multiple-shooting``, ``collocation``,
    ``collocation6``, ``analytic``; ``start``: ``pressed`` (the rod loaded from its rest shape)
    or ``connected`` (the state connected to the straight uniform rod's).
    """
    r = _core.solve(
        rod,
        alpha,
        phi1=phi1,
        eta=eta,
        tip=tip,
        branch=branch,
        method=method,
        tol=tol,
        segments=segments,
        shape_points=shape_points,
        start=start,
    )
    r["shape"] = columns(r["shape"])
    return r


def scan(
    rod: Any,
    surface: Any = None,
    *,
    d_max: float = _DEFAULTS["d_max"],
    points: int = _DEFAULTS["points"],
    d: Optional[Iterable[float]] = None,
    mu0: Optional[float] = None,
    method: str = _SOLVER["method"],
    tol: float = _SOLVER["tol"],
    segments: int = _SOLVER["segments"],
    shape_points: Optional[int] = None,
    contact: Optional[str] = None,
    start: Optional[str] = None,
) -> ScanResult:
    """The stiction scan: the foot moves right by d from 0 to ``d_max`` while the tip sticks
    on ``surface`` (default: flat at eta = 0.75); ``points`` output points uniform in d, or the
    displacements ``d`` (ascending, in [0, d_max]). It stops at the first event (slip at
    ``|mu| = mu0``, lift-off, a fold in d), located inside the step and returned as the last
    point; changes of the contact state (``touchdown``, ``peel_back``, ``release``) are points of
    their own. ``contact``: ``anywhere`` (sides touch and lie down) or ``tip`` (the paper's
    model: a touching side ends the scan with ``penetration``); ``start``: ``pressed`` or
    ``connected``. ``shape_points``: keep each point's rod shape (see :class:`ScanResult`).
    The defaults are the program's (``vibrissa scan``)."""
    if surface is None:
        surface = Surface()
    raw = _core.scan(
        rod,
        surface,
        d_max=d_max,
        points=points,
        d=None if d is None else [float(x) for x in d],
        mu0=mu0,
        method=method,
        tol=tol,
        segments=segments,
        shape_points=shape_points,
        contact=contact,
        start=start,
    )
    return ScanResult(raw)


def infer(
    rod: Any,
    surface: Any,
    d0: float,
    *,
    d_max: float = _DEFAULTS["d_max"],
    points: int = _DEFAULTS["points"],
    method: str = _SOLVER["method"],
    tol: float = _SOLVER["tol"],
    segments: int = _SOLVER["segments"],
    contact: Optional[str] = None,
    start: Optional[str] = None,
) -> Dict[str, Any]:
    """The stiction coefficient mu0 = |mu(d0)| from the slip displacement ``d0`` (as
    ``vibrissa infer``): a dict with ``mu0``, ``d0``, ``measurable_d`` (the range of d where
    the answer is unique), ``mu_max``, ``range_end``. A d0 outside the measurable range is an
    :class:`InputError` that names the range."""
    r = _core.infer(
        rod,
        surface,
        d0,
        d_max=d_max,
        points=points,
        method=method,
        tol=tol,
        segments=segments,
        contact=contact,
        start=start,
    )
    r["measurable_d"] = tuple(r["measurable_d"])
    return r


def grid(**axes: Union[float, Sequence[float]]) -> List[Dict[str, float]]:
    """The scenes of a grid, as ``vibrissa sweep`` orders them: row-major with ``eta`` slowest
    (then ``taper``, ``precurvature``, ``precurvature_slope``, ``support_compliance``,
    ``surface_angle``). Each axis is a number or a sequence; e.g.
    ``grid(eta=np.linspace(0.6, 0.9, 4), taper=[1.0, 0.5])``."""
    unknown = set(axes) - set(_SCENE_KEYS)
    if unknown:
        raise InputError(
            f"unknown grid axis {sorted(unknown)}: the axes are {', '.join(_SCENE_KEYS)}"
        )
    names = [k for k in _SCENE_KEYS if k in axes]
    values = [
        [float(v) for v in np.atleast_1d(np.asarray(axes[k], dtype=float))] for k in names
    ]
    return [dict(zip(names, combo)) for combo in itertools.product(*values)]


def sweep(
    scenes: Iterable[SceneLike],
    *,
    d_max: float = _DEFAULTS["d_max"],
    points: int = _DEFAULTS["points"],
    mu0: Optional[float] = None,
    method: str = _SOLVER["method"],
    tol: float = _SOLVER["tol"],
    segments: int = _SOLVER["segments"],
    jobs: Optional[int] = None,
    contact: Optional[str] = None,
    start: Optional[str] = None,
) -> Sweep:
    """Scans of many scenes in parallel (``jobs`` threads, default all cores; the GIL is
    released while they run), one summary row per scene in the order given. ``scenes``:
    ``(Rod, Surface)`` pairs or dicts of scene keys (e.g. from :func:`grid`). A scene whose
    values are invalid raises before any work; a scan that fails has its message in the
    ``error`` column and the others go on."""
    given = list(scenes)
    parts = [_parts(s) for s in given]
    rows = _core.sweep(
        parts,
        d_max=d_max,
        points=points,
        mu0=mu0,
        method=method,
        tol=tol,
        segments=segments,
        jobs=jobs,
        contact=contact,
        start=start,
    )
    out = []
    for s, r in zip(given, rows):
        row: Dict[str, Any] = dict(s) if isinstance(s, Mapping) else {}
        row.update(r)
        out.append(row)
    return Sweep(out)


class DragResult:
    """The result of :func:`drag`.

    Attributes:
        rows: dict of columns with the program's names (``vibrissa drag``'s CSV): ``d``
            (``theta`` with ``turn``),
            ``phase``, ``x_tip``, ``y_tip``, (with a round tip ``x_contact``), ``mu``, ``mu_s``,
            ``normal``, ``fx``, ``fy``,
            ``m_base``, ``contact``, (with a physical rod ``d_mm``, ``x_tip_mm``, ``y_tip_mm``,
            ``normal_N``, ``fx_N``, ``fy_N``, ``m_base_Nm``), ``event``, ``jump``,
            ``energy_released``.
        slips: one dict per slip (``d``, ``jump``, ``released``, ``before``, ``after``, ...).
        summary: means and spreads over the slips (``cycles``, ``jump_mean``, ...).
        stop, stop_reason: why the drag stopped.
        stats, handover, units: as for :class:`ScanResult`.
        raw: everything as the library returned it.
    """

    def __init__(self, raw: Dict[str, Any]):
        self.raw = raw
        self.rows: Dict[str, Column] = columns(raw["rows"])
        self.slips: List[Dict[str, Any]] = raw["slips"]
        self.summary: Dict[str, Any] = raw["summary"]
        self.stop: Any = raw["stop"]
        self.stop_reason: str = raw["stop_reason"]
        self.stats: Dict[str, Any] = raw["stats"]
        self.handover: Optional[str] = raw["handover"]
        self.units: Optional[Dict[str, float]] = raw["units"]

    def __len__(self) -> int:
        return len(self.raw["rows"])

    def to_csv(self) -> str:
        """The rows as the program's CSV text (what :func:`fit` reads)."""
        keys = list(self.rows)
        lines = [",".join(keys)]
        for r in self.raw["rows"]:
            lines.append(",".join("" if r[k] is None else _text(r[k]) for k in keys))
        return "\n".join(lines) + "\n"

    def to_pandas(self):
        """The rows as a pandas DataFrame (needs pandas)."""
        return _to_pandas(self.rows)

    def __repr__(self) -> str:
        return (
            f"DragResult(rows={len(self)}, slips={len(self.slips)}, "
            f"stop_reason={self.stop_reason!r})"
        )


def _text(v: Any) -> str:
    if isinstance(v, float):
        return repr(v) if v == v and abs(v) != float("inf") else ("inf" if v > 0 else "-inf")
    return str(v)


def drag(
    rod: Any,
    surface: Any = None,
    *,
    mu_s: Optional[float] = None,
    mu_k: Optional[float] = None,
    d_max: float = _DEFAULTS["drag_d_max"],
    points: int = _DEFAULTS["drag_points"],
    method: str = _SOLVER["method"],
    tol: float = _SOLVER["tol"],
    segments: int = _SOLVER["segments"],
    shape_points: Optional[int] = None,
    contact: Optional[str] = None,
    start: Optional[str] = None,
    energy_balance: bool = False,
    max_slips: int = _DEFAULTS["drag_max_slips"],
    turn: bool = False,
) -> DragResult:
    """The drag (as ``vibrissa drag``): the foot moves from 0 to ``d_max`` across ``surface``;
    the tip sticks until ``|mu|`` reaches ``mu_s``, slips to where ``mu_k`` holds it, and sticks
    again. ``mu_s`` with ``mu_k`` (``mu_k < mu_s``), or neither: the surface's ``friction``
    texture. ``max_slips``: the most slips before the drag stops (a guard, as the program's
    ``--max-slips``). ``turn``: the foot held and its support turned clockwise by
    ``theta = 0 ... d_max`` rad instead (a whisk against the surface, the program's ``--turn``;
    the rows' first column is ``theta``). The defaults are the program's; the values are checked as the program
    checks them (the library's limits). Ctrl-C interrupts it."""
    if surface is None:
        surface = Surface()
    return DragResult(
        _core.drag(
            rod,
            surface,
            mu_s=mu_s,
            mu_k=mu_k,
            d_max=d_max,
            points=points,
            method=method,
            tol=tol,
            segments=segments,
            shape_points=shape_points,
            contact=contact,
            start=start,
            energy_balance=energy_balance,
            max_slips=max_slips,
            turn=turn,
        )
    )


def whisk(
    rod: Any,
    peg: Tuple[float, float],
    *,
    theta_max: float = _DEFAULTS["whisk"]["theta_max"],
    points: int = _DEFAULTS["whisk"]["points"],
    mu0: Optional[float] = None,
    method: str = _SOLVER["method"],
    tol: float = _SOLVER["tol"],
    segments: int = _SOLVER["segments"],
    shape_points: Optional[int] = None,
) -> Dict[str, Any]:
    """The whisk (as ``vibrissa whisk``): the foot turns clockwise from first touch to
    ``theta_max`` against a point object at ``peg = (x, y)`` (frame of the unturned foot).
    A dict: ``first_touch``, ``s_touch``, ``points`` (columns ``theta``, ``s_c``, ``f``, ``fx``,
    ``fy``, ``f_axial``, ``f_transverse``, ``m_base``, ``normal``, ``mu``, ``event``; with a
    physical rod ``f_N``, ``fx_N``, ``fy_N``, ``m_base_Nm``), ``stop``, ``stop_reason``,
    ``stats``, ``units``. ``mu0``: stiction at the object (None or inf: frictionless)."""
    r = _core.whisk(
        rod,
        (float(peg[0]), float(peg[1])),
        theta_max=theta_max,
        points=points,
        mu0=mu0,
        method=method,
        tol=tol,
        segments=segments,
        shape_points=shape_points,
    )
    r["points"] = columns(r["points"])
    return r


def solve_peg(
    rod: Any,
    peg: Tuple[float, float],
    theta: float = 0.0,
    *,
    mu0: Optional[float] = None,
    method: str = _SOLVER["method"],
    tol: float = _SOLVER["tol"],
    segments: int = _SOLVER["segments"],
    shape_points: int = _DEFAULTS["solve_shape_points"],
) -> Dict[str, Any]:
    """The rod against a point object at ``peg = (x, y)`` with the foot turned to ``theta``
    (as ``vibrissa solve --peg X,Y --theta A``): a dict with the whisk's columns at ``theta``
    (``theta``, ``s_c``, ``f``, ``fx``, ``fy``, ``f_axial``, ``f_transverse``, ``m_base``,
    ``normal``, ``mu``, ``event``; with a physical rod ``f_N``, ``fx_N``, ``fy_N``,
    ``m_base_Nm``) and ``shape``: a dict of numpy arrays ``s``, ``x``, ``y``, ``phi``,
    ``kappa``, ``m`` (frame of the unturned foot). An object the turned rod does not touch is
    an :class:`InputError` that says so."""
    r = _core.solve_peg(
        rod,
        (float(peg[0]), float(peg[1])),
        theta,
        mu0=mu0,
        method=method,
        tol=tol,
        segments=segments,
        shape_points=shape_points,
    )
    r["shape"] = columns(r["shape"])
    return r


def locate(
    rod: Any,
    theta: float,
    m_base: float,
    fx: float,
    fy: float,
    *,
    method: str = _SOLVER["method"],
    tol: float = _SOLVER["tol"],
    segments: int = _SOLVER["segments"],
) -> Dict[str, float]:
    """Where a point object is from the base signals of one instant (as ``vibrissa locate``):
    a dict with ``theta``, ``m_base``, ``fx``, ``fy``, ``x``, ``y``, ``s_c`` (and ``x_mm``,
    ``y_mm`` with a physical rod)."""
    return _core.locate(
        rod, theta, m_base, fx, fy, method=method, tol=tol, segments=segments
    )


def _corrugation_parts(parts: Union[bool, str, Sequence[str]]) -> Optional[List[str]]:
    """``fit``'s ``fit_corrugation`` as the names the library reads (None: none, []: all)."""
    if parts is False or parts is None:
        return None
    if parts is True:
        return []
    if isinstance(parts, str):
        return parts.split(",")
    return [str(p) for p in parts]


def fit(
    trace: Any,
    rod: Any = None,
    surface: Any = None,
    *,
    signals: Optional[Sequence[str]] = None,
    fit_eta: bool = False,
    fit_angle: bool = False,
    fit_corrugation: Union[bool, str, Sequence[str]] = False,
    mu_s: Optional[float] = None,
    mu_k: Optional[float] = None,
    sigma: Optional[Sequence[float]] = None,
    method: str = _SOLVER["method"],
    tol: float = _SOLVER["tol"],
    segments: int = _SOLVER["segments"],
    contact: Optional[str] = None,
    start: Optional[str] = None,
) -> Dict[str, Any]:
    """μs and μk (and with ``fit_eta``/``fit_angle`` the surface's height and inclination)
    from a drag trace (as ``vibrissa fit``). ``trace``: a :class:`DragResult`, a path to a
    CSV file, or the CSV text (``vibrissa drag``'s columns: ``d`` and any of ``fx``, ``fy``,
    ``m_base``, ``x_tip``, ``y_tip``, ``event``). ``rod``, ``surface``: the scene the trace
    was measured in (default: the paper's rod on a flat surface at 0.75; fit a corrugated
    trace with its corrugated surface). ``fit_corrugation``: also estimate the surface's
    corrugation (a sine ``surface``, its values the start): ``True`` its amplitude, wavelength
    and phase, or the parts named (a list, or a comma list as the program's
    ``--fit-corrugation=PARTS``); a part the trace cannot determine is named in ``message`` and
    has no standard error. ``mu_s``, ``mu_k``: the start (default: read off the
    first slips); ``sigma``: the noise levels of ``d``, ``fx``, ``fy``, ``m_base`` (default
    estimated). A dict: ``params`` (``name``, ``value``, ``std_error``, ``dof``,
    ``identifiable``), ``message`` (None, or what limits the answer: a misfit has no standard
    error), ``consistency``, ``sigma``, ``s2``, ``observations``, ``slips``, ``signals``, ...
    """
    if isinstance(trace, DragResult):
        text = trace.to_csv()
    elif isinstance(trace, os.PathLike) or (isinstance(trace, str) and "\n" not in trace):
        with open(trace, encoding="utf-8") as f:
            text = f.read()
    else:
        text = str(trace)
    return _core.fit(
        text,
        Rod() if rod is None else rod,
        Surface() if surface is None else surface,
        signals=None if signals is None else list(signals),
        fit_eta=fit_eta,
        fit_angle=fit_angle,
        corrugation=_corrugation_parts(fit_corrugation),
        mu_s=mu_s,
        mu_k=mu_k,
        sigma=None if sigma is None else [float(x) for x in sigma],
        method=method,
        tol=tol,
        segments=segments,
        contact=contact,
        start=start,
    )


def _in_columns(r: Dict[str, Any], key: str) -> Dict[str, Any]:
    """``r[key]`` (a list of dicts) as columns, the rows kept as ``r[key + "_rows"]``."""
    r[key + "_rows"] = r[key]
    r[key] = columns(r[key])
    return r


_FREE = _DEFAULTS["dynamics_free"]
_DRAG = _DEFAULTS["dynamics_drag"]


def dynamics_free(
    rod: Any,
    *,
    release_force: Tuple[float, float] = tuple(_FREE["release_force"]),
    foot_moment: float = _FREE["foot_moment"],
    dt: float = _FREE["dt"],
    t_end: float = _FREE["t_end"],
    time_tol: Optional[float] = _FREE.get("time_tol"),
    foot_damping: float = _FREE["foot_damping"],
    internal_damping: float = _FREE["internal_damping"],
    external_damping: float = _FREE["external_damping"],
    rotary_inertia: float = _FREE["rotary_inertia"],
    grid: int = _FREE["grid"],
    tol: float = _FREE["tol"],
    time_scheme: Optional[str] = _FREE.get("time_scheme"),
) -> Dict[str, Any]:
    """The rod released at t = 0 (as ``vibrissa dynamics free``): from its equilibrium under
    the dead tip force ``release_force = (fx, fy)`` (removed at t = 0), and/or with the moment
    ``foot_moment`` stepped onto its support (it turns the foot through the rod's
    ``support_compliance``), time step ``dt`` to ``t_end`` (normalized time).

    ``time_tol`` (the program's ``--time-tol``): adaptive time steps, the tolerance (rod
    lengths) of each step's local error estimate in the positions, in [1e-14, 0.1]; ``dt`` is
    then the first step, a step over the tolerance is tried again shorter, and the samples are
    at the steps taken (``stats["rejected_steps"]`` counts the steps tried again). ``None``:
    fixed steps of ``dt``. The dampers (each >= 0, default 0): ``foot_damping`` the support's
    damper, ``internal_damping`` the rod's Kelvin-Voigt damping gamma_i (every mode of the
    linearized rod decays at gamma_i omega^2/2), ``external_damping`` a viscous force
    -gamma_e mu(s) r_t (every mode decays at gamma_e/2). ``rotary_inertia``: the radius of
    gyration g0 of the foot's section over the length, in [0, 0.1] (as :func:`modes`'s; the
    slopes carry the inertia g0^2/b per length, the kinetic energy its share; default 0).
    ``grid`` (even, intervals of the history grid in s) and ``tol`` (each step's collocation
    tolerance). ``time_scheme``: ``"energy_momentum"`` (each step keeps the energy whatever
    the amplitude; fixed steps only) or ``"newmark"`` (Newmark's rule, the scheme of adaptive
    steps); ``None`` (the default) takes the first with fixed steps and the second with
    ``time_tol`` (the program's ``--time-scheme``). The defaults and valid
    ranges are the library's (a value out of range raises ``InputError`` naming it).

    A dict: ``samples`` (columns ``t``, ``tip_x``, ``tip_y``, ``tip_vx``, ``tip_vy``,
    ``theta``, ``m_base``, ``gx_base``, ``gy_base`` (the program's ``fx``, ``fy``),
    ``kinetic``, ``elastic``, ``dissipated`` (the program's ``damper``), ``internal_damping``
    and ``external_damping`` (the energy each damper took)), ``samples_rows`` (the same as
    dicts: the program's ``--json``), ``stats`` (steps, rejected steps, Newton iterations,
    ...), ``units`` and ``time_unit_s`` (seconds per time unit for a rod with physical
    dimensions, keratin's density; else None)."""
    r = _core.dynamics_free(
        rod,
        release_force=(float(release_force[0]), float(release_force[1])),
        foot_moment=foot_moment,
        dt=dt,
        t_end=t_end,
        time_tol=time_tol,
        foot_damping=foot_damping,
        internal_damping=internal_damping,
        external_damping=external_damping,
        rotary_inertia=rotary_inertia,
        grid=grid,
        tol=tol,
        time_scheme=time_scheme,
    )
    return _in_columns(r, "samples")


def dynamics_drag(
    rod: Any,
    surface: Any = None,
    *,
    speed: float = _DRAG["speed"],
    ramp: float = _DRAG["ramp"],
    d_max: float = _DRAG["d_max"],
    mu_s: Optional[float] = None,
    mu_k: Optional[float] = None,
    mu_k_table: Sequence[Tuple[float, float]] = tuple(tuple(p) for p in _DRAG["mu_k_table"]),
    dt: float = _DRAG["dt"],
    time_tol: Optional[float] = _DRAG.get("time_tol"),
    foot_damping: float = _DRAG["foot_damping"],
    internal_damping: float = _DRAG["internal_damping"],
    external_damping: float = _DRAG["external_damping"],
    rotary_inertia: float = _DRAG["rotary_inertia"],
    flight: bool = _DRAG["flight"],
    grid: int = _DRAG["grid"],
    tol: float = _DRAG["tol"],
    event_tol: float = _DRAG["event_tol"],
    max_events: int = _DRAG["max_events"],
    refinements: int = _DRAG["refinements"],
    foot_table: Sequence[Sequence[float]] = tuple(tuple(r) for r in _DRAG["foot_table"]),
    whisk: Optional[Tuple[float, float]] = None,
) -> Dict[str, Any]:
    """The drag in time (as ``vibrissa dynamics drag``): the foot moves along x at ``speed``
    (rising smoothly over ``ramp``) with the tip on the ``surface`` (a line, inclined or not, or
    a height profile such as ``profile={"kind": "sine", ...}``) under Coulomb friction ``mu_s``,
    ``mu_k`` (default the surface's ``friction`` texture, else the library's 0.5, 0.3; given,
    they replace the texture, as the program's flags do: a texture's patches and tables give
    the stuck tip's μs where it sticks and the sliding tip's μk where it slides, a patch's
    boundary crossed is an event ``patch``), from the pressed start at rest to ``d_max``. A
    ``rod`` with a ``tip_radius`` (on a line) rolls while it sticks and carries the moment
    ``r T``; it needs ``internal_damping`` above 0 (e.g. 1e-4). The start has the tip alone
    on the surface (a start with a side on it raises :class:`Error` naming the contact: no
    start). Beside a point tip on a surface of uniform friction a side that reaches the surface
    is followed: where the rod's end lies down, a side that rolls and slides (states
    ``side_stuck``, ``side_sliding_forward``, ``side_sliding_back``; its place in the columns
    ``side_s``, ``side_x``, ``side_y``) until its contact returns to the tip (event
    ``to_tip``); elsewhere, or where the free tip touches down beside a side, two contacts at
    once (the tip's state and forces in the columns ``tip_also_state``, ``tip_also_normal``,
    ``tip_also_tangential``; ``normal``, ``tangential`` the side's) until one lifts off or they
    meet; else (a round tip, a texture, a table of μk) it ends the drag (stop
    ``side_contact``).

    ``foot_table``: the foot's path instead of ``speed``, ``ramp`` and ``d_max`` (any of them
    given with it raises :class:`InputError`, as the program's flags conflict), rows
    ``(t, d)`` or ``(t, d, theta)`` (time, displacement along x, the turn of the foot's support
    in rad, clockwise), ``t`` strictly increasing from the first row ``(0, 0[, 0])``; each
    column a natural cubic spline; the drag ends at the last time (stop ``table_end``; the
    program's ``--foot-table FILE``). ``whisk``: ``(amplitude, frequency)``, the support turns
    by ``amplitude (1 - cos 2 pi frequency t)/2`` on top of the path (``--whisk A,F``); the
    samples' ``theta`` is the turn.

    ``mu_k_table``: kinetic friction depending on the slip speed, ``(speed, mu_k)`` pairs
    (speeds >= 0 increasing, each mu_k in [0, mu_s)), piecewise linear, constant beyond the
    ends; replaces ``mu_k`` (the program's ``--mu-k-table V:MU,...``). ``time_tol``: adaptive
    time steps as in :func:`dynamics_free` (``dt`` the first step; events still shorten a step
    to their place). The dampers ``foot_damping``, ``internal_damping``, ``external_damping``
    and ``rotary_inertia`` as in :func:`dynamics_free`. ``flight``: after a lift-off the tip flies until it touches
    the surface again (event ``touchdown``, a plastic impact), then slides or sticks on;
    without it a lift-off ends the drag. ``grid``, ``tol`` as in :func:`dynamics_free`; ``event_tol``
    the tolerance in time of the events' places, ``max_events`` the most events before the
    drag stops, ``refinements`` the halvings of ``dt`` tried where the steps do not resolve a
    stick or a stuck step, place a slip beyond the friction cone or give a step Newton does not
    solve (the drag goes back to its
    state after the last event and takes the steps again at dt/2, dt/4, ...; 0 stops there at
    once; fixed steps only; the program's ``--refinements``). The defaults and valid ranges
    are the library's.

    A dict: ``samples`` (columns as the program's CSV: ``t``, ``d``, ``theta`` (the support's
    turn), ``tip_x``, ..., ``state``, ``normal``, ``tangential``, ``fx``, ``fy`` (after the
    first event without the time rule's alternating mode), ``m_base``, energies),
    ``samples_rows`` (the same as dicts: the program's ``--json``), ``events`` (``slip``,
    ``stick``, ``lift_off``, ``touchdown``, ``side_contact``, ``patch`` with their time and
    place), ``stop`` (its
    ``reason``: ``d_max``, ``table_end``, ``lift_off``, ``max_events``, or
    ``unresolved_stick``, a stick the time step does not resolve, with ``t``, ``d`` and the
    force the stuck tip would need, ``unresolved_step``, a stuck rod the time step does not
    resolve (its force would jump within the shortest step, or the event's search within
    the step is not solved: ``t``, ``d``, ``before`` and the forces after), or
    ``side_contact`` with ``t``, ``d`` and the rod's point ``s``, ``x`` that reached the
    surface, ``s`` 1 where the rod's end lies down, ``side_change`` with its ``change``
    (``second_contact``, ``third_contact``, ``trapped``: a side and the tip that would both
    stick, ...), or ``stretch``, two contacts whose steps do not solve with the rod between
    them within ``gap`` of the surface), ``stats``,
    ``units``, ``time_unit_s``."""
    if surface is None:
        surface = Surface()
    if (mu_s is not None or mu_k is not None) and surface.friction.get("kind", "none") != "none":
        surface = Surface(
            eta=surface.eta,
            angle=surface.angle,
            profile=surface.profile,
            contact=surface.contact,
            start=surface.start,
        )
    if len(foot_table) > 0:
        # as the program's --foot-table, which conflicts with --speed, --ramp and --d-max
        given = [k for k, v in (("speed", speed), ("ramp", ramp), ("d_max", d_max)) if v != _DRAG[k]]
        if given:
            raise InputError(
                f"foot_table replaces speed, ramp and d_max (the drag ends at its last time): "
                f"{', '.join(given)} given with it"
            )
    r = _core.dynamics_drag(
        rod,
        surface,
        speed=speed,
        ramp=ramp,
        d_max=d_max,
        mu_s=_DRAG["mu_s"] if mu_s is None else mu_s,
        mu_k=_DRAG["mu_k"] if mu_k is None else mu_k,
        mu_k_table=[(float(v), float(m)) for v, m in mu_k_table],
        dt=dt,
        time_tol=time_tol,
        foot_damping=foot_damping,
        internal_damping=internal_damping,
        external_damping=external_damping,
        rotary_inertia=rotary_inertia,
        flight=flight,
        grid=grid,
        tol=tol,
        event_tol=event_tol,
        max_events=max_events,
        refinements=refinements,
        foot_table=[[float(v) for v in row] for row in foot_table],
        whisk=None if whisk is None else (float(whisk[0]), float(whisk[1])),
    )
    return _in_columns(r, "samples")


def modes(
    rod: Any,
    *,
    m_base: float = 0.0,
    fx: float = 0.0,
    fy: float = 0.0,
    tip: str = "free",
    tip_angle: float = 0.0,
    count: int = _DEFAULTS["modes"]["count"],
    rotary_inertia: float = _DEFAULTS["modes"]["rotary_inertia"],
    points: int = _DEFAULTS["modes"]["shape_points"],
) -> Dict[str, Any]:
    """Natural frequencies of a static state (as ``vibrissa modes``) given by its foot values
    ``m_base``, ``fx``, ``fy`` (default: the free, unloaded rod), the tip ``"free"``,
    ``"pinned"`` (also a tip stuck by friction) or ``"sliding"`` on the line of inclination
    ``tip_angle``. A dict: the library's result (``modes``: one dict per mode with ``omega2``,
    ``omega``, and ``points`` samples of its shape; ``stable``; what the program's ``--json``
    prints) plus ``time_unit_s`` (so ``omega / (2 pi time_unit_s)`` is the frequency in Hz)."""
    return _core.modes(
        rod,
        m_base=m_base,
        fx=fx,
        fy=fy,
        tip=tip,
        tip_angle=tip_angle,
        count=count,
        rotary_inertia=rotary_inertia,
        points=points,
    )
