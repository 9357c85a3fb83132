"""Type stubs of the compiled module `vibrissa._core` (see the `vibrissa` package)."""

from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple

class Rod:
    """A validated rod: stiffness profile, rest curvature, support compliance, physical units."""

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
    ) -> None: ...
    def to_dict(self) -> Dict[str, Any]: ...
    def is_uniform_clamped(self) -> bool: ...

class Surface:
    """The surface line the tip touches: height eta (rod lengths) and inclination angle (rad)."""

    def __init__(self, eta: float = 0.75, angle: float = 0.0) -> None: ...
    @property
    def eta(self) -> float: ...
    @property
    def angle(self) -> float: ...

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
    contact: str = "anywhere",
    start: str = "pressed",
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
    contact: str = "anywhere",
    start: str = "pressed",
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
    contact: str = "anywhere",
    start: str = "pressed",
) -> List[Dict[str, Any]]: ...
