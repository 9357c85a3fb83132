"""Type stubs of the compiled module `vibrissa._core` (see the `vibrissa` package)."""

from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple

class Rod:
    """A validated rod: stiffness profile, rest curvature, support compliance, physical units,
    the radius of a round tip (0: the point tip)."""

    def __init__(
        self,
        taper: Optional[float] = None,
        precurvature: float = 0.0,
        precurvature_slope: float = 0.0,
        support_compliance: float = 0.0,
        *,
        stiffness: Optional[Mapping[str, Any]] = None,
        precurvature_profile: Optional[Mapping[str, Any]] = None,
        physical: Optional[Mapping[str, float]] = None,
        tip_radius: float = 0.0,
    ) -> None: ...
    def to_dict(self) -> Dict[str, Any]: ...
    def units(self) -> Optional[Dict[str, float]]: ...
    def is_uniform_clamped(self) -> bool: ...

class Surface:
    """The surface the tip touches: height eta (rod lengths), inclination angle (rad), its
    profile and friction texture (the scene file's [surface] and [friction] tables), and the
    scene's contact and start (None: the functions' defaults)."""

    def __init__(
        self,
        eta: float = 0.75,
        angle: float = 0.0,
        *,
        profile: Optional[Mapping[str, Any]] = None,
        friction: Optional[Mapping[str, Any]] = None,
        contact: Optional[str] = None,
        start: Optional[str] = None,
    ) -> None: ...
    @property
    def eta(self) -> float: ...
    @property
    def angle(self) -> float: ...
    @property
    def profile(self) -> Dict[str, Any]: ...
    @property
    def friction(self) -> Dict[str, Any]: ...
    @property
    def contact(self) -> Optional[str]: ...
    @property
    def start(self) -> Optional[str]: ...

def scene_from_dict(scene: Mapping[str, Any]) -> Tuple[Rod, Surface]: ...
def scene_from_toml(text: str) -> Tuple[Rod, Surface]: ...
def solve(
    rod: Rod,
    alpha: float,
    *,
    phi1: Optional[float] = None,
    eta: Optional[float] = None,
    tip: Optional[Tuple[float, float]] = None,
    branch: str = "convex",
    method: str = "shooting",
    tol: float = 1e-10,
    segments: int = 8,
    shape_points: int = 101,
    start: str = "pressed",
) -> Dict[str, Any]: ...
def scan(
    rod: Rod,
    surface: Surface,
    *,
    d_max: float = 0.5,
    points: int = 201,
    d: Optional[Sequence[float]] = None,
    mu0: Optional[float] = None,
    method: str = "shooting",
    tol: float = 1e-10,
    segments: int = 8,
    shape_points: Optional[int] = None,
    contact: Optional[str] = None,
    start: Optional[str] = None,
) -> Dict[str, Any]: ...
def infer(
    rod: Rod,
    surface: Surface,
    d0: float,
    *,
    d_max: float = 0.5,
    points: int = 201,
    method: str = "shooting",
    tol: float = 1e-10,
    segments: int = 8,
    contact: Optional[str] = None,
    start: Optional[str] = None,
) -> Dict[str, Any]: ...
def sweep(
    scenes: Sequence[Tuple[Rod, Surface]],
    *,
    d_max: float = 0.5,
    points: int = 201,
    mu0: Optional[float] = None,
    method: str = "shooting",
    tol: float = 1e-10,
    segments: int = 8,
    jobs: Optional[int] = None,
    contact: Optional[str] = None,
    start: Optional[str] = None,
) -> List[Dict[str, Any]]: ...
def drag(
    rod: Rod,
    surface: Surface,
    *,
    mu_s: Optional[float] = None,
    mu_k: Optional[float] = None,
    d_max: float = 1.0,
    points: int = 201,
    method: str = "shooting",
    tol: float = 1e-10,
    segments: int = 8,
    shape_points: Optional[int] = None,
    contact: Optional[str] = None,
    start: Optional[str] = None,
    energy_balance: bool = False,
    max_slips: Optional[int] = None,
    turn: bool = False,
) -> Dict[str, Any]: ...
def whisk(
    rod: Rod,
    peg: Tuple[float, float],
    *,
    theta_max: float = 1.0,
    points: int = 201,
    mu0: Optional[float] = None,
    method: str = "shooting",
    tol: float = 1e-10,
    segments: int = 8,
    shape_points: Optional[int] = None,
) -> Dict[str, Any]: ...
def limits() -> Dict[str, Any]: ...
def solve_peg(
    rod: Rod,
    peg: Tuple[float, float],
    theta: float = 0.0,
    *,
    mu0: Optional[float] = None,
    method: str = "shooting",
    tol: float = 1e-10,
    segments: int = 8,
    shape_points: int = 101,
) -> Dict[str, Any]: ...
def locate(
    rod: Rod,
    theta: float,
    m_base: float,
    fx: float,
    fy: float,
    *,
    method: str = "shooting",
    tol: float = 1e-10,
    segments: int = 8,
) -> Dict[str, float]: ...
def fit(
    csv: str,
    rod: Rod,
    surface: Surface,
    *,
    signals: Optional[Sequence[str]] = None,
    fit_eta: bool = False,
    fit_angle: bool = False,
    mu_s: Optional[float] = None,
    mu_k: Optional[float] = None,
    sigma: Optional[Sequence[float]] = None,
    method: str = "shooting",
    tol: float = 1e-10,
    segments: int = 8,
    contact: Optional[str] = None,
    start: Optional[str] = None,
) -> Dict[str, Any]: ...
def dynamics_free(
    rod: Rod,
    *,
    release_force: Tuple[float, float] = (0.0, 0.0),
    foot_moment: float = 0.0,
    dt: float = 0.01,
    t_end: float = 1.0,
    time_tol: Optional[float] = None,
    foot_damping: float = 0.0,
    internal_damping: float = 0.0,
    external_damping: float = 0.0,
    grid: int = 200,
    tol: float = 1e-10,
) -> Dict[str, Any]: ...
def dynamics_drag(
    rod: Rod,
    surface: Surface,
    *,
    speed: float = 0.01,
    ramp: float = 2.0,
    d_max: float = 0.03,
    mu_s: float = 0.5,
    mu_k: float = 0.3,
    mu_k_table: Sequence[Tuple[float, float]] = (),
    dt: float = 0.01,
    time_tol: Optional[float] = None,
    foot_damping: float = 0.0,
    internal_damping: float = 0.0,
    external_damping: float = 0.0,
    rotary_inertia: float = 0.0,
    flight: bool = False,
    grid: int = 200,
    tol: float = 1e-10,
    event_tol: float = 1e-10,
    max_events: int = 10000,
    refinements: int = 3,
    foot_table: Sequence[Sequence[float]] = (),
    whisk: Optional[Tuple[float, float]] = None,
) -> Dict[str, Any]: ...
def modes(
    rod: Rod,
    *,
    m_base: float = 0.0,
    fx: float = 0.0,
    fy: float = 0.0,
    tip: str = "free",
    tip_angle: float = 0.0,
    count: int = 3,
    rotary_inertia: float = 0.0,
    points: int = 0,
) -> Dict[str, Any]: ...
