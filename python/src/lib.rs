//! `vibrissa._core`: the Python binding of the `vibrissa` library. The Python package
//! (`python/vibrissa/__init__.py`) wraps it: it turns the rows returned here into numpy columns.
//!
//! Results cross over generically: every result struct of the library is converted through its
//! `Serialize` impl (pythonize), so a field added to `ScanPoint`, `ScanResult`, `Shape`, ... shows
//! up in Python as a new key (a new column) without binding code. Errors keep the library's
//! message (its `Display`); input errors are `ValueError`s, failed solves `RuntimeError`s.

use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use pythonize::{depythonize, pythonize};
use rayon::prelude::*;
use serde::Serialize;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{channel, RecvTimeoutError};
use std::sync::Arc;
use std::time::Duration;
use vibrissa::dynamics::{DynDragOptions, DynamicsOptions};
use vibrissa::fit::{CorrugationFit, FitOptions, Signal, Trace};
use vibrissa::modes::{BaseLoad, ModeOptions, TipCondition};
use vibrissa::surface::{FrictionProfile, SurfaceProfile};
use vibrissa::{
    BranchChoice, ContactModel, DragOptions, Method, Physical, Precurvature, Rod, ScanOptions,
    ScanResult, Scene, SolverConfig, StartKind, Stiffness, Surface, Target, Units, VibrissaError,
    WhiskOptions,
};

/// An exception of class `name` of `vibrissa._errors` (pure Python: `InputError` is also a
/// `ValueError`, `SolveError` a `RuntimeError`, both `vibrissa.Error`s) with `msg`.
fn raise(name: &str, msg: String) -> PyErr {
    Python::attach(
        |py| match py.import("vibrissa._errors").and_then(|m| m.getattr(name)) {
            Ok(cls) => PyErr::from_type(cls.cast_into().expect("an exception class"), msg),
            Err(e) => e,
        },
    )
}

/// The library's error as a Python exception with the same message; the input errors are the
/// library's ([`VibrissaError::is_input`]), those the program reports as bad input (exit 2), a
/// surface the rod cannot reach among them.
fn py_err(e: VibrissaError) -> PyErr {
    let class = if e.is_input() {
        "InputError"
    } else {
        "SolveError"
    };
    raise(class, e.to_string())
}

/// A value from Python that does not fit the scene format, in the format's words.
fn input_err(what: &str, e: impl std::fmt::Display) -> PyErr {
    raise(
        "InputError",
        format!("{what}: {}", vibrissa::scene::plain_message(&e.to_string())),
    )
}

fn input(msg: impl Into<String>) -> PyErr {
    raise("InputError", msg.into())
}

fn to_py<'py, T: Serialize + ?Sized>(py: Python<'py>, v: &T) -> PyResult<Bound<'py, PyAny>> {
    pythonize(py, v).map_err(|e| PyRuntimeError::new_err(e.to_string()))
}

/// A validated rod (see `vibrissa.Rod` in Python for the arguments).
#[pyclass(frozen, from_py_object, module = "vibrissa._core", name = "Rod")]
#[derive(Clone)]
struct PyRod(Rod);

#[pymethods]
impl PyRod {
    #[new]
    #[pyo3(signature = (taper=None, precurvature=0.0, precurvature_slope=0.0, support_compliance=0.0, *, stiffness=None, precurvature_profile=None, physical=None, tip_radius=0.0))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        taper: Option<f64>,
        precurvature: f64,
        precurvature_slope: f64,
        support_compliance: f64,
        stiffness: Option<&Bound<'_, PyAny>>,
        precurvature_profile: Option<&Bound<'_, PyAny>>,
        physical: Option<&Bound<'_, PyAny>>,
        tip_radius: f64,
    ) -> PyResult<Self> {
        let stiff = match (taper, stiffness) {
            (Some(_), Some(_)) => return Err(input("give either taper or stiffness, not both")),
            (Some(ratio), None) => Stiffness::Taper { ratio },
            (None, Some(s)) => depythonize(s).map_err(|e| input_err("stiffness", e))?,
            (None, None) => Stiffness::Uniform,
        };
        let pre = match precurvature_profile {
            Some(_) if precurvature != 0.0 || precurvature_slope != 0.0 => {
                return Err(input("give either precurvature (and precurvature_slope) or precurvature_profile, not both",
                ))
            }
            Some(p) => depythonize(p).map_err(|e| input_err("precurvature_profile", e))?,
            None if precurvature == 0.0 && precurvature_slope == 0.0 => Precurvature::None,
            None => Precurvature::Linear {
                k0: precurvature,
                k1: precurvature_slope,
            },
        };
        let phys: Option<Physical> = physical
            .map(|p| depythonize(p).map_err(|e| input_err("physical", e)))
            .transpose()?;
        Rod::new(stiff, pre, support_compliance, phys)
            .and_then(|r| r.with_tip_radius(tip_radius))
            .map(PyRod)
            .map_err(py_err)
    }

    /// The rod's parts as a dict (the scene file's keys: stiffness, precurvature,
    /// support_compliance, physical, and tip_radius when the tip is round).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let r = &self.0;
        let d = PyDict::new(py);
        d.set_item("stiffness", to_py(py, r.stiffness())?)?;
        d.set_item("precurvature", to_py(py, r.precurvature())?)?;
        d.set_item("support_compliance", r.support_compliance())?;
        d.set_item("physical", to_py(py, &r.physical())?)?;
        if r.tip_radius() > 0.0 {
            // (as in a scene file, where the key is left out for the point tip)
            d.set_item("tip_radius", r.tip_radius())?;
        }
        Ok(d.into_any())
    }

    /// The physical units (`length_mm`, `force_n`, `moment_nm`) of a rod with physical
    /// dimensions, else None.
    fn units<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        units_dict(py, self.0.units())
    }

    /// True for the paper's rod: uniform, straight, clamped (where the closed forms hold).
    fn is_uniform_clamped(&self) -> bool {
        self.0.is_uniform_clamped()
    }

    fn __repr__(&self) -> String {
        let r = &self.0;
        let tip = if r.tip_radius() > 0.0 {
            format!(", tip_radius={}", r.tip_radius())
        } else {
            String::new()
        };
        format!(
            "Rod(stiffness={:?}, precurvature={:?}, support_compliance={}, physical={:?}{tip})",
            r.stiffness(),
            r.precurvature(),
            r.support_compliance(),
            r.physical()
        )
    }
}

/// The surface the tip touches, with the scene's settings that go with it (see
/// `vibrissa.Surface` in Python): its profile and friction texture as given (a scene's
/// `[surface]` and `[friction]` tables), and the scene's `contact` and `start` (None: not set,
/// the functions' defaults).
#[pyclass(frozen, from_py_object, module = "vibrissa._core", name = "Surface")]
#[derive(Clone)]
struct PySurface {
    s: Surface,
    profile: SurfaceProfile,
    friction: FrictionProfile,
    contact: Option<ContactModel>,
    start: Option<StartKind>,
}

#[pymethods]
impl PySurface {
    #[new]
    #[pyo3(signature = (eta=0.75, angle=0.0, *, profile=None, friction=None, contact=None, start=None))]
    fn new(
        eta: f64,
        angle: f64,
        profile: Option<&Bound<'_, PyAny>>,
        friction: Option<&Bound<'_, PyAny>>,
        contact: Option<&str>,
        start: Option<&str>,
    ) -> PyResult<Self> {
        let profile: SurfaceProfile = profile
            .map(|p| depythonize(p).map_err(|e| input_err("profile", e)))
            .transpose()?
            .unwrap_or_default();
        let friction: FrictionProfile = friction
            .map(|p| depythonize(p).map_err(|e| input_err("friction", e)))
            .transpose()?
            .unwrap_or_default();
        let scene = Scene {
            eta,
            surface_angle: angle,
            surface: profile,
            friction,
            ..Scene::default()
        };
        let mut out = surface_of(&scene)?;
        out.contact = contact
            .map(|c| c.parse::<ContactModel>().map_err(py_err))
            .transpose()?;
        out.start = start
            .map(|c| c.parse::<StartKind>().map_err(py_err))
            .transpose()?;
        Ok(out)
    }
    /// Height of the contact point above the foot (rod lengths).
    #[getter]
    fn eta(&self) -> f64 {
        self.s.eta()
    }
    /// Inclination of the surface line (rad).
    #[getter]
    fn angle(&self) -> f64 {
        self.s.angle()
    }
    /// The profile as a dict (the scene file's `[surface]`).
    #[getter]
    fn profile<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_py(py, &self.profile)
    }
    /// The friction texture as a dict (the scene file's `[friction]`).
    #[getter]
    fn friction<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_py(py, &self.friction)
    }
    /// The scene's contact model (`anywhere`, `tip`), or None.
    #[getter]
    fn contact(&self) -> Option<&'static str> {
        self.contact.map(ContactModel::name)
    }
    /// The scene's start (`pressed`, `connected`), or None.
    #[getter]
    fn start(&self) -> Option<&'static str> {
        self.start.map(StartKind::name)
    }
    fn __repr__(&self) -> String {
        format!(
            "Surface(eta={}, angle={}, profile={:?}, friction={:?}, contact={:?}, start={:?})",
            self.s.eta(),
            self.s.angle(),
            self.profile,
            self.friction,
            self.contact(),
            self.start()
        )
    }
}

/// The surface of a scene, its contact and start set.
fn surface_of(scene: &Scene) -> PyResult<PySurface> {
    Ok(PySurface {
        s: scene.surface().map_err(py_err)?,
        profile: scene.surface.clone(),
        friction: scene.friction.clone(),
        contact: Some(scene.contact),
        start: Some(scene.start),
    })
}

/// The scene of a rod and a surface (what `fit` varies).
fn scene_of(rod: &Rod, surface: &PySurface, contact: ContactModel, start: StartKind) -> Scene {
    Scene {
        eta: surface.s.eta(),
        stiffness: rod.stiffness().clone(),
        precurvature: rod.precurvature().clone(),
        support_compliance: rod.support_compliance(),
        surface_angle: surface.s.angle(),
        physical: rod.physical().cloned(),
        contact,
        start,
        surface: surface.profile.clone(),
        friction: surface.friction.clone(),
        tip_radius: rod.tip_radius(),
    }
}

/// A scene (the dict of a scene file's keys, or the text of a TOML file) as `(Rod, Surface)`,
/// the surface carrying the scene's contact and start.
fn scene_parts(scene: Scene) -> PyResult<(PyRod, PySurface)> {
    let rod = scene.rod().map_err(py_err)?;
    Ok((PyRod(rod), surface_of(&scene)?))
}

/// `(Rod, Surface)` of a scene given as a dict with the keys of a scene file.
#[pyfunction]
fn scene_from_dict(scene: &Bound<'_, PyAny>) -> PyResult<(PyRod, PySurface)> {
    scene_parts(depythonize(scene).map_err(|e| input_err("scene", e))?)
}

/// `(Rod, Surface)` of a scene file's text (TOML).
#[pyfunction]
fn scene_from_toml(text: &str) -> PyResult<(PyRod, PySurface)> {
    scene_parts(toml::from_str(text).map_err(|e| input_err("scene", e.message()))?)
}

/// The solver settings from their Python arguments.
fn config_named(method: &str, tol: f64, segments: usize, start: &str) -> PyResult<SolverConfig> {
    let start = start.parse::<StartKind>().map_err(py_err)?;
    let cfg = SolverConfig {
        method: method.parse::<Method>().map_err(py_err)?,
        tol,
        segments,
        rk4_steps: None,
        start,
        cancel: Default::default(),
    };
    cfg.validate().map_err(py_err)?;
    Ok(cfg)
}

fn branch(name: &str) -> PyResult<BranchChoice> {
    name.parse::<BranchChoice>().map_err(py_err)
}

/// The contact model and start: the arguments, else the surface's scene, else the library's.
fn settings(
    surface: &PySurface,
    contact: Option<&str>,
    start: Option<&str>,
) -> PyResult<(ContactModel, StartKind)> {
    let c = match contact {
        Some(c) => c.parse::<ContactModel>().map_err(py_err)?,
        None => surface.contact.unwrap_or_default(),
    };
    let s = match start {
        Some(s) => s.parse::<StartKind>().map_err(py_err)?,
        None => surface.start.unwrap_or_default(),
    };
    Ok((c, s))
}

/// How often a running computation looks for Ctrl-C.
const SIGNAL_POLL: Duration = Duration::from_millis(50);

/// Runs `work` on a thread of its own with the GIL released, looking for Ctrl-C (Python's
/// signal handlers) every [`SIGNAL_POLL`]: `KeyboardInterrupt` comes within a tenth of a second.
/// `cancel` is then set: a scan, drag, whisk or fit whose configuration holds it stops at its
/// next step (`StopReason::Cancelled`), a sweep at its next scene, and the result is dropped.
fn interruptible<T: Send + 'static>(
    py: Python<'_>,
    cancel: Arc<AtomicBool>,
    work: impl FnOnce() -> T + Send + 'static,
) -> PyResult<T> {
    let (tx, rx) = channel();
    std::thread::spawn(move || {
        let _ = tx.send(work());
    });
    let mut rx = rx;
    loop {
        // (the receiver is not Sync: it moves into the GIL-free closure and back)
        let (got, back) = py.detach(move || {
            let got = rx.recv_timeout(SIGNAL_POLL);
            (got, rx)
        });
        rx = back;
        match got {
            Ok(v) => return Ok(v),
            Err(RecvTimeoutError::Timeout) => {
                if let Err(e) = py.check_signals() {
                    cancel.store(true, Ordering::SeqCst);
                    return Err(e);
                }
            }
            Err(RecvTimeoutError::Disconnected) => {
                return Err(PyRuntimeError::new_err(
                    "the computation's thread ended without a result",
                ))
            }
        }
    }
}

/// A fresh cancellation flag set into `solver`: Ctrl-C stops the run at its next step.
fn cancel_on(solver: &mut vibrissa::SolverConfig) -> Arc<AtomicBool> {
    let flag = Arc::new(AtomicBool::new(false));
    solver.cancel = vibrissa::Cancel::new(flag.clone());
    flag
}

/// `mu0` as the program takes it: `inf` is no threshold (never slips).
fn threshold(mu0: Option<f64>) -> Option<f64> {
    mu0.filter(|m| *m != f64::INFINITY)
}

/// The rod's physical units as a dict (`length_mm`, `force_n`, `moment_nm`), or None.
fn units_dict<'py>(py: Python<'py>, u: Option<Units>) -> PyResult<Bound<'py, PyAny>> {
    match u {
        None => Ok(py.None().into_bound(py)),
        Some(u) => {
            let d = PyDict::new(py);
            d.set_item("length_mm", u.length_mm)?;
            d.set_item("force_n", u.force_n)?;
            d.set_item("moment_nm", u.moment_nm)?;
            Ok(d.into_any())
        }
    }
}

/// One rod under a tip force at angle `alpha` with one tip condition; returns the `Shape` as a
/// dict plus `shape`, a list of `shape_points` samples (dicts of s, x, y, phi, kappa, m).
#[pyfunction]
#[pyo3(signature = (rod, alpha, *, phi1=None, eta=None, tip=None, branch="convex", method="shooting", tol=SolverConfig::DEFAULT_TOL, segments=SolverConfig::DEFAULT_SEGMENTS, shape_points=vibrissa::limits::DEFAULT_SOLVE_SHAPE_POINTS, start="pressed"))]
#[allow(clippy::too_many_arguments)]
fn solve<'py>(
    py: Python<'py>,
    rod: &PyRod,
    alpha: f64,
    phi1: Option<f64>,
    eta: Option<f64>,
    tip: Option<(f64, f64)>,
    branch: &str,
    method: &str,
    tol: f64,
    segments: usize,
    shape_points: usize,
    start: &str,
) -> PyResult<Bound<'py, PyAny>> {
    let target = match (phi1, eta, tip) {
        (Some(p), None, None) => Target::Phi1(p),
        (None, Some(h), None) => Target::Eta(h),
        (None, None, Some((x1, y1))) => Target::Tip { x1, y1 },
        _ => {
            return Err(input(
                "give exactly one tip condition: phi1, eta or tip = (x1, y1)",
            ))
        }
    };
    vibrissa::limits::SHAPE_POINTS
        .check_count("shape_points", shape_points)
        .map_err(py_err)?;
    let (b, cfg, rod) = (
        self::branch(branch)?,
        config_named(method, tol, segments, start)?,
        &rod.0,
    );
    let (shape, samples) = py
        .detach(|| {
            vibrissa::solve(rod, alpha, target, &b, &cfg).map(|s| {
                let samples = s.samples(shape_points);
                (s, samples)
            })
        })
        .map_err(py_err)?;
    let d = to_py(py, &shape)?;
    d.set_item("shape", to_py(py, &samples)?)?;
    Ok(d)
}

/// The library's defaults of a scan and its solver (`ScanOptions::default()`) and the samples
/// of a solved shape: the package's signatures read them (one source of the defaults).
#[pyfunction]
fn defaults(py: Python<'_>) -> PyResult<Bound<'_, PyAny>> {
    let d = to_py(py, &ScanOptions::default())?;
    d.set_item(
        "solve_shape_points",
        vibrissa::limits::DEFAULT_SOLVE_SHAPE_POINTS,
    )?;
    d.set_item("drag_d_max", vibrissa::limits::DEFAULT_DRAG_D_MAX)?;
    d.set_item("drag_points", vibrissa::limits::DEFAULT_DRAG_POINTS)?;
    d.set_item("drag_max_slips", DragOptions::default().max_slips)?;
    d.set_item("whisk", to_py(py, &WhiskOptions::default())?)?;
    d.set_item("dynamics_free", to_py(py, &DynamicsOptions::default())?)?;
    d.set_item("dynamics_drag", to_py(py, &DynDragOptions::default())?)?;
    d.set_item("modes", to_py(py, &ModeOptions::default())?)?;
    Ok(d)
}

/// The library's ranges (`vibrissa::limits::named()`) as a dict: name -> `lo`, `lo_closed`,
/// `hi`, `hi_closed`, `text` (as the error messages write it), `unit`, `why`; and the size
/// limits `memory_budget_bytes`, `jobs_per_core`, `max_scenes`.
#[pyfunction]
fn limits(py: Python<'_>) -> PyResult<Bound<'_, PyAny>> {
    let out = PyDict::new(py);
    for (name, r) in vibrissa::limits::named() {
        let d = PyDict::new(py);
        d.set_item("lo", r.lo)?;
        d.set_item("lo_closed", r.lo_closed)?;
        d.set_item("hi", r.hi)?;
        d.set_item("hi_closed", r.hi_closed)?;
        d.set_item("text", r.text(6))?;
        d.set_item("unit", r.unit)?;
        d.set_item("why", r.why)?;
        out.set_item(name, d)?;
    }
    out.set_item("memory_budget_bytes", vibrissa::limits::MEMORY_BUDGET)?;
    out.set_item("jobs_per_core", vibrissa::limits::JOBS_PER_CORE)?;
    out.set_item("max_scenes", vibrissa::limits::MAX_SCENES)?;
    Ok(out.into_any())
}

/// The kept shapes within the library's memory budget (`limits::check_shapes`, as the
/// options' `validate` checks them), the error naming this package's argument `shape_points`.
fn shapes_fit(shape_points: Option<usize>, outputs: usize) -> PyResult<()> {
    match shape_points {
        Some(n) => vibrissa::limits::check_shapes("shape_points", n, outputs).map_err(py_err),
        None => Ok(()),
    }
}

/// Scan options from the Python arguments.
#[allow(clippy::too_many_arguments)]
fn scan_options(
    d_max: f64,
    points: usize,
    mu0: Option<f64>,
    method: &str,
    tol: f64,
    segments: usize,
    shape_points: Option<usize>,
    (contact, start): (ContactModel, StartKind),
) -> PyResult<ScanOptions> {
    let opts = ScanOptions {
        d_max,
        points,
        mu0: threshold(mu0),
        solver: config(method, tol, segments, start)?,
        keep_shapes: shape_points,
        contact,
    };
    shapes_fit(shape_points, opts.points)?;
    opts.validate().map_err(py_err)?;
    Ok(opts)
}

/// The solver settings (`start` a name parsed already).
fn config(method: &str, tol: f64, segments: usize, start: StartKind) -> PyResult<SolverConfig> {
    config_named(method, tol, segments, start.name())
}

/// The stiction scan; returns the `ScanResult` as a dict (`points` and `shapes` as lists of
/// dicts) with `units` (the rod's physical units or None). `d`: output displacements instead of
/// the uniform grid (`scan_at`). Ctrl-C interrupts it.
#[pyfunction]
#[pyo3(signature = (rod, surface, *, d_max=ScanOptions::DEFAULT_D_MAX, points=ScanOptions::DEFAULT_POINTS, d=None, mu0=None, method="shooting", tol=SolverConfig::DEFAULT_TOL, segments=SolverConfig::DEFAULT_SEGMENTS, shape_points=None, contact=None, start=None))]
#[allow(clippy::too_many_arguments)]
fn scan<'py>(
    py: Python<'py>,
    rod: &PyRod,
    surface: &PySurface,
    d_max: f64,
    points: usize,
    d: Option<Vec<f64>>,
    mu0: Option<f64>,
    method: &str,
    tol: f64,
    segments: usize,
    shape_points: Option<usize>,
    contact: Option<&str>,
    start: Option<&str>,
) -> PyResult<Bound<'py, PyAny>> {
    let settings = settings(surface, contact, start)?;
    let mut opts = scan_options(
        d_max,
        points,
        mu0,
        method,
        tol,
        segments,
        shape_points,
        settings,
    )?;
    let (rod, surface) = (rod.0.clone(), surface.s.clone());
    let units = rod.units();
    let r = interruptible(py, cancel_on(&mut opts.solver), move || match &d {
        Some(ds) => vibrissa::scan_at(&rod, &surface, &opts, ds),
        None => vibrissa::scan(&rod, &surface, &opts),
    })?
    .map_err(py_err)?;
    let out = to_py(py, &r)?;
    out.set_item("units", units_dict(py, units)?)?;
    Ok(out)
}

/// μ0 from the slip displacement `d0`; returns the `Inference` as a dict.
#[pyfunction]
#[pyo3(signature = (rod, surface, d0, *, d_max=ScanOptions::DEFAULT_D_MAX, points=ScanOptions::DEFAULT_POINTS, method="shooting", tol=SolverConfig::DEFAULT_TOL, segments=SolverConfig::DEFAULT_SEGMENTS, contact=None, start=None))]
#[allow(clippy::too_many_arguments)]
fn infer<'py>(
    py: Python<'py>,
    rod: &PyRod,
    surface: &PySurface,
    d0: f64,
    d_max: f64,
    points: usize,
    method: &str,
    tol: f64,
    segments: usize,
    contact: Option<&str>,
    start: Option<&str>,
) -> PyResult<Bound<'py, PyAny>> {
    let settings = settings(surface, contact, start)?;
    let mut opts = scan_options(d_max, points, None, method, tol, segments, None, settings)?;
    let (rod, surface) = (rod.0.clone(), surface.s.clone());
    let r = interruptible(py, cancel_on(&mut opts.solver), move || {
        vibrissa::infer(&rod, &surface, d0, &opts)
    })?
    .map_err(py_err)?;
    to_py(py, &r)
}

/// A scan reduced to its summary: the `ScanResult` without its points and shapes, and its
/// last point (the start when it has none).
fn summary(mut r: ScanResult) -> (ScanResult, usize, vibrissa::ScanPoint) {
    let end = r.points.last().copied().unwrap_or(r.start);
    let n = r.points.len();
    r.points = Vec::new();
    r.shapes = Vec::new();
    r.contacts = Vec::new();
    (r, n, end)
}

/// Worker threads for `n` scenes: `jobs` in [`limits::JOBS`](vibrissa::limits::JOBS) (default:
/// the cores), capped at `JOBS_PER_CORE` per core and at the scenes, as the program does.
fn workers(jobs: Option<usize>, n: usize) -> PyResult<usize> {
    let cores = std::thread::available_parallelism().map_or(1, |c| c.get());
    if let Some(j) = jobs {
        vibrissa::limits::JOBS
            .check_count("jobs", j)
            .map_err(py_err)?;
    }
    let cap = vibrissa::limits::JOBS_PER_CORE * cores;
    Ok(jobs.unwrap_or(cores).min(cap).min(n.max(1)).max(1))
}

/// Scans of many scenes in parallel (rayon, `jobs` threads, the GIL released); one summary dict
/// per scene in order: the `ScanResult`'s keys with `points` the number of points, `end` its
/// last point (the start when it has none), `units` and `error` (None, or the message). A
/// failing scene does not stop the others; Ctrl-C stops the sweep between scenes.
#[pyfunction]
#[pyo3(signature = (scenes, *, d_max=ScanOptions::DEFAULT_D_MAX, points=ScanOptions::DEFAULT_POINTS, mu0=None, method="shooting", tol=SolverConfig::DEFAULT_TOL, segments=SolverConfig::DEFAULT_SEGMENTS, jobs=None, contact=None, start=None))]
#[allow(clippy::too_many_arguments)]
fn sweep<'py>(
    py: Python<'py>,
    scenes: Vec<(PyRod, PySurface)>,
    d_max: f64,
    points: usize,
    mu0: Option<f64>,
    method: &str,
    tol: f64,
    segments: usize,
    jobs: Option<usize>,
    contact: Option<&str>,
    start: Option<&str>,
) -> PyResult<Bound<'py, PyList>> {
    let cancel = Arc::new(AtomicBool::new(false));
    let mut runs = Vec::with_capacity(scenes.len());
    for (rod, surface) in scenes {
        let settings = settings(&surface, contact, start)?;
        let mut opts = scan_options(d_max, points, mu0, method, tol, segments, None, settings)?;
        // (a scene in flight stops at its next step too)
        opts.solver.cancel = vibrissa::Cancel::new(cancel.clone());
        runs.push((rod.0, surface.s, opts));
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(workers(jobs, runs.len())?)
        .build()
        .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    let stop = cancel.clone();
    let results: Vec<(Option<Units>, Result<_, String>)> = interruptible(py, cancel, move || {
        pool.install(|| {
            runs.par_iter()
                .map(|(rod, surface, opts)| {
                    if stop.load(Ordering::SeqCst) {
                        return (None, Err("cancelled (Ctrl-C)".to_string()));
                    }
                    let r = vibrissa::scan(rod, surface, opts)
                        .map(summary)
                        .map_err(|e| e.to_string());
                    (rod.units(), r)
                })
                .collect()
        })
    })?;
    let out = PyList::empty(py);
    for (units, r) in results {
        let row = match r {
            Ok((r, n, end)) => {
                // the summary keys of `ScanResult` (whatever they are), `points` as a count
                let d = to_py(py, &r)?.cast_into::<PyDict>()?;
                d.del_item("shapes")?;
                d.set_item("points", n)?;
                d.set_item("end", to_py(py, &end)?)?;
                d.set_item("units", units_dict(py, units)?)?;
                d.set_item("error", py.None())?;
                d.into_any()
            }
            Err(msg) => {
                let d = PyDict::new(py);
                d.set_item("error", msg)?;
                d.into_any()
            }
        };
        out.append(row)?;
    }
    Ok(out)
}

/// One drag row with the program's column names (`vibrissa drag`'s CSV), the physical columns
/// with units, and `x_contact` for a round tip (`round`); a turning support's (`turn`) first
/// column is `theta`, and it has no `d_mm`.
fn drag_row<'py>(
    py: Python<'py>,
    r: &vibrissa::drag::DragRow,
    u: Option<Units>,
    (round, turn): (bool, bool),
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item(if turn { "theta" } else { "d" }, r.d)?;
    d.set_item("phase", r.phase.name())?;
    d.set_item("x_tip", r.x_tip)?;
    d.set_item("y_tip", r.y_tip)?;
    if round {
        d.set_item("x_contact", r.x_contact)?;
    }
    d.set_item("mu", r.mu)?;
    d.set_item("mu_s", r.mu_s)?;
    d.set_item("normal", r.normal)?;
    d.set_item("fx", r.fx)?;
    d.set_item("fy", r.fy)?;
    d.set_item("m_base", r.m_base)?;
    d.set_item("contact", r.contact.name())?;
    if let Some(u) = u {
        let l = u.length_mm;
        if !turn {
            d.set_item("d_mm", r.d * l)?;
        }
        d.set_item("x_tip_mm", r.x_tip * l)?;
        d.set_item("y_tip_mm", r.y_tip * l)?;
        d.set_item("normal_N", r.normal * u.force_n)?;
        d.set_item("fx_N", r.fx * u.force_n)?;
        d.set_item("fy_N", r.fy * u.force_n)?;
        d.set_item("m_base_Nm", r.m_base * u.moment_nm)?;
    }
    d.set_item("event", r.event.map(|e| e.name()))?;
    d.set_item("jump", r.jump)?;
    d.set_item("energy_released", r.released)?;
    Ok(d)
}

/// The drag: the foot from 0 to `d_max` across the surface, the tip sticking and slipping
/// (`vibrissa drag`; with `turn` the foot held and its support turned by up to `d_max` rad,
/// `--turn`); a dict: `rows` (the program's columns), `slips`, `summary`, `stop`, `stats`,
/// `handover`, `units`, `shapes`. Ctrl-C interrupts it.
#[pyfunction]
#[pyo3(signature = (rod, surface, *, mu_s=None, mu_k=None, d_max=vibrissa::limits::DEFAULT_DRAG_D_MAX, points=vibrissa::limits::DEFAULT_DRAG_POINTS, method="shooting", tol=SolverConfig::DEFAULT_TOL, segments=SolverConfig::DEFAULT_SEGMENTS, shape_points=None, contact=None, start=None, energy_balance=false, max_slips=None, turn=false))]
#[allow(clippy::too_many_arguments)]
fn drag<'py>(
    py: Python<'py>,
    rod: &PyRod,
    surface: &PySurface,
    mu_s: Option<f64>,
    mu_k: Option<f64>,
    d_max: f64,
    points: usize,
    method: &str,
    tol: f64,
    segments: usize,
    shape_points: Option<usize>,
    contact: Option<&str>,
    start: Option<&str>,
    energy_balance: bool,
    max_slips: Option<usize>,
    turn: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let (contact, start) = settings(surface, contact, start)?;
    let mut opts = DragOptions {
        d_max,
        points,
        mu_s,
        mu_k,
        solver: config(method, tol, segments, start)?,
        keep_shapes: shape_points,
        contact,
        energy_balance,
        motion: if turn {
            vibrissa::FootMotion::Turn
        } else {
            vibrissa::FootMotion::Along
        },
        ..DragOptions::default()
    };
    if let Some(n) = max_slips {
        opts.max_slips = n;
    }
    shapes_fit(shape_points, opts.points)?;
    opts.validate().map_err(py_err)?;
    let (rod, surface) = (rod.0.clone(), surface.s.clone());
    let (units, round) = (rod.units(), rod.tip_radius() > 0.0);
    let r = interruptible(py, cancel_on(&mut opts.solver), move || {
        vibrissa::drag(&rod, &surface, &opts)
    })?
    .map_err(py_err)?;
    let out = PyDict::new(py);
    let rows = PyList::empty(py);
    for row in &r.rows {
        rows.append(drag_row(py, row, units, (round, turn))?)?;
    }
    out.set_item("rows", rows)?;
    out.set_item("slips", to_py(py, &r.slips)?)?;
    out.set_item("summary", to_py(py, &r.summary)?)?;
    out.set_item("stop", to_py(py, &r.stop)?)?;
    out.set_item("stop_reason", r.stop.name())?;
    out.set_item("stats", to_py(py, &r.stats)?)?;
    out.set_item("handover", r.handover.clone())?;
    out.set_item("units", units_dict(py, units)?)?;
    out.set_item("shapes", to_py(py, &r.shapes)?)?;
    Ok(out.into_any())
}

/// The whisk against a point object at `peg = (x, y)` (`vibrissa whisk`): a dict with the
/// `WhiskResult`'s keys, `points` rows with the program's columns (`event` by name), `units`.
#[pyfunction]
#[pyo3(signature = (rod, peg, *, theta_max=WhiskOptions::default().theta_max, points=WhiskOptions::default().points, mu0=None, method="shooting", tol=SolverConfig::DEFAULT_TOL, segments=SolverConfig::DEFAULT_SEGMENTS, shape_points=None))]
#[allow(clippy::too_many_arguments)]
fn whisk<'py>(
    py: Python<'py>,
    rod: &PyRod,
    peg: (f64, f64),
    theta_max: f64,
    points: usize,
    mu0: Option<f64>,
    method: &str,
    tol: f64,
    segments: usize,
    shape_points: Option<usize>,
) -> PyResult<Bound<'py, PyAny>> {
    let mut opts = WhiskOptions {
        theta_max,
        points,
        mu0: threshold(mu0),
        solver: config(method, tol, segments, StartKind::default())?,
        keep_shapes: shape_points,
    };
    shapes_fit(shape_points, opts.points)?;
    opts.validate().map_err(py_err)?;
    let rod = rod.0.clone();
    let units = rod.units();
    let r = interruptible(py, cancel_on(&mut opts.solver), move || {
        vibrissa::whisk(&rod, [peg.0, peg.1], &opts)
    })?
    .map_err(py_err)?;
    let out = to_py(py, &r)?;
    let rows = PyList::empty(py);
    for p in &r.points {
        let d = to_py(py, p)?.cast_into::<PyDict>()?;
        // (a whisk marches in theta: its fold is `fold`, as the program names it)
        d.set_item(
            "event",
            p.event.map(|e| match e {
                vibrissa::Event::FoldInD => "fold",
                e => e.name(),
            }),
        )?;
        if let Some(u) = units {
            d.set_item("f_N", p.f * u.force_n)?;
            d.set_item("fx_N", p.fx * u.force_n)?;
            d.set_item("fy_N", p.fy * u.force_n)?;
            d.set_item("m_base_Nm", p.m_base * u.moment_nm)?;
        }
        rows.append(d)?;
    }
    out.set_item("points", rows)?;
    // the program's names: a whisk marches in theta
    let reason = match &r.stop {
        vibrissa::StopReason::DMax => "theta_max",
        vibrissa::StopReason::FoldInD { .. } => "fold",
        other => other.name(),
    };
    out.set_item("stop_reason", reason)?;
    out.set_item("units", units_dict(py, units)?)?;
    Ok(out)
}

/// The rod against a point object at `peg = (x, y)` with the foot turned to `theta`
/// (`vibrissa solve --peg`): the whisk's point there as a dict (`event` by name), with `shape`
/// (a list of `shape_points` samples, frame of the unturned foot) and the physical columns of a
/// rod with physical dimensions.
#[pyfunction]
#[pyo3(signature = (rod, peg, theta=0.0, *, mu0=None, method="shooting", tol=SolverConfig::DEFAULT_TOL, segments=SolverConfig::DEFAULT_SEGMENTS, shape_points=vibrissa::limits::DEFAULT_SOLVE_SHAPE_POINTS))]
#[allow(clippy::too_many_arguments)]
fn solve_peg<'py>(
    py: Python<'py>,
    rod: &PyRod,
    peg: (f64, f64),
    theta: f64,
    mu0: Option<f64>,
    method: &str,
    tol: f64,
    segments: usize,
    shape_points: usize,
) -> PyResult<Bound<'py, PyAny>> {
    vibrissa::limits::THETA
        .check("theta", theta)
        .map_err(py_err)?;
    let mut opts = WhiskOptions {
        mu0: threshold(mu0),
        solver: config(method, tol, segments, StartKind::default())?,
        keep_shapes: Some(shape_points),
        ..WhiskOptions::default()
    };
    shapes_fit(Some(shape_points), 1)?;
    opts.validate().map_err(py_err)?;
    let rod = rod.0.clone();
    let units = rod.units();
    let (p, shape) = interruptible(py, cancel_on(&mut opts.solver), move || {
        vibrissa::peg::solve_peg_shape(&rod, [peg.0, peg.1], theta, &opts)
    })?
    .map_err(py_err)?;
    let d = to_py(py, &p)?.cast_into::<PyDict>()?;
    d.set_item("event", p.event.map(|e| e.name()))?;
    if let Some(u) = units {
        d.set_item("f_N", p.f * u.force_n)?;
        d.set_item("fx_N", p.fx * u.force_n)?;
        d.set_item("fy_N", p.fy * u.force_n)?;
        d.set_item("m_base_Nm", p.m_base * u.moment_nm)?;
    }
    d.set_item("shape", to_py(py, &shape)?)?;
    Ok(d.into_any())
}

/// Where the object is from the base signals of one instant (`vibrissa locate`): a dict with
/// `theta`, `m_base`, `fx`, `fy`, `x`, `y`, `s_c` (and `x_mm`, `y_mm` with physical units).
#[pyfunction]
#[pyo3(signature = (rod, theta, m_base, fx, fy, *, method="shooting", tol=SolverConfig::DEFAULT_TOL, segments=SolverConfig::DEFAULT_SEGMENTS))]
#[allow(clippy::too_many_arguments)]
fn locate<'py>(
    py: Python<'py>,
    rod: &PyRod,
    theta: f64,
    m_base: f64,
    fx: f64,
    fy: f64,
    method: &str,
    tol: f64,
    segments: usize,
) -> PyResult<Bound<'py, PyAny>> {
    vibrissa::limits::THETA
        .check("theta", theta)
        .map_err(py_err)?;
    let cfg = config(method, tol, segments, StartKind::default())?;
    let (x, y, s_c) = py
        .detach(|| vibrissa::locate(&rod.0, theta, m_base, [fx, fy], &cfg))
        .map_err(py_err)?;
    let d = PyDict::new(py);
    for (k, v) in [
        ("theta", theta),
        ("m_base", m_base),
        ("fx", fx),
        ("fy", fy),
        ("x", x),
        ("y", y),
        ("s_c", s_c),
    ] {
        d.set_item(k, v)?;
    }
    if let Some(u) = rod.0.units() {
        d.set_item("x_mm", x * u.length_mm)?;
        d.set_item("y_mm", y * u.length_mm)?;
    }
    Ok(d.into_any())
}

/// μs, μk (and on request η, β, the corrugation's parts) from a drag trace given as CSV text
/// (`vibrissa fit`; the library's `Trace::from_csv`): the `FitResult` as a dict with `slips`
/// and `signals`. `corrugation`: the parts named (`CorrugationFit::from_names`; an empty list
/// all three), or none.
#[pyfunction]
#[pyo3(signature = (csv, rod, surface, *, signals=None, fit_eta=false, fit_angle=false, corrugation=None, mu_s=None, mu_k=None, sigma=None, method="shooting", tol=SolverConfig::DEFAULT_TOL, segments=SolverConfig::DEFAULT_SEGMENTS, contact=None, start=None))]
#[allow(clippy::too_many_arguments)]
fn fit<'py>(
    py: Python<'py>,
    csv: &str,
    rod: &PyRod,
    surface: &PySurface,
    signals: Option<Vec<String>>,
    fit_eta: bool,
    fit_angle: bool,
    corrugation: Option<Vec<String>>,
    mu_s: Option<f64>,
    mu_k: Option<f64>,
    sigma: Option<[f64; 4]>,
    method: &str,
    tol: f64,
    segments: usize,
    contact: Option<&str>,
    start: Option<&str>,
) -> PyResult<Bound<'py, PyAny>> {
    let mut use_sig = [true; 3];
    if let Some(list) = &signals {
        use_sig = [false; 3];
        for s in list {
            match Signal::ALL.iter().position(|g| g.name() == s.trim()) {
                Some(k) => use_sig[k] = true,
                None => {
                    return Err(input(format!(
                        "signals: '{s}' is not a base signal (fx, fy, m_base)"
                    )))
                }
            }
        }
    }
    let guess = match (mu_s, mu_k) {
        (Some(s), Some(k)) => {
            vibrissa::limits::MU_S.check("mu_s", s).map_err(py_err)?;
            vibrissa::limits::kinetic_friction(s)
                .check("mu_k", k)
                .map_err(py_err)?;
            Some((s, k))
        }
        (None, None) => None,
        _ => {
            return Err(input(
                "give both mu_s and mu_k (the fit's start), or neither",
            ))
        }
    };
    let trace = Trace::from_csv(csv, use_sig).map_err(py_err)?;
    let (contact, start) = settings(surface, contact, start)?;
    let scene = scene_of(&rod.0, surface, contact, start);
    let corrugation = match &corrugation {
        Some(names) => {
            CorrugationFit::from_names(names.iter().map(String::as_str)).map_err(py_err)?
        }
        None => CorrugationFit::default(),
    };
    let mut opts = FitOptions {
        fit_eta,
        fit_angle,
        corrugation,
        guess,
        sigma,
        solver: config(method, tol, segments, start)?,
        contact,
        ..FitOptions::default()
    };
    let slips = trace.slips.len();
    let found: Vec<&str> = Signal::ALL
        .iter()
        .enumerate()
        .filter(|(k, _)| {
            trace
                .slips
                .iter()
                .any(|s| s.before[*k].is_some() || s.after[*k].is_some())
        })
        .map(|(_, s)| s.name())
        .collect();
    let f = interruptible(py, cancel_on(&mut opts.solver), move || {
        vibrissa::fit(&scene, &trace, &opts)
    })?
    .map_err(py_err)?;
    let out = to_py(py, &f)?;
    out.set_item("slips", slips)?;
    out.set_item("signals", found)?;
    Ok(out)
}

/// The rod's time unit in seconds (keratin's density, as the program's `t_s`), or None.
fn time_unit(rod: &Rod) -> Option<f64> {
    rod.physical()
        .map(|p| vibrissa::inertia::time_unit_s(p, vibrissa::inertia::KERATIN_DENSITY))
}

/// The rod released at t = 0 (`vibrissa dynamics free`): from its equilibrium under the tip
/// force `release_force`, and/or with `foot_moment` stepped onto its support; every option of
/// the library's `DynamicsOptions` the program's flags set (`time_tol`: adaptive steps, `None`
/// fixed ones; the dampers; `time_scheme` "newmark" or "energy_momentum", `None` the
/// library's default: the energy–momentum step with fixed steps, Newmark's with adaptive
/// ones), and its `grid` and `tol`, the defaults and checks the library's. A
/// dict with the library's `DynamicsResult` (`samples`, `stats`; what the program's `--json`
/// prints) plus `units` and `time_unit_s`. Ctrl-C stops waiting for it.
#[pyfunction]
#[pyo3(signature = (rod, *, release_force=(DynamicsOptions::default().release_force[0], DynamicsOptions::default().release_force[1]), foot_moment=DynamicsOptions::default().foot_moment, dt=DynamicsOptions::default().dt, t_end=DynamicsOptions::default().t_end, time_tol=DynamicsOptions::default().time_tol, foot_damping=DynamicsOptions::default().foot_damping, internal_damping=DynamicsOptions::default().internal_damping, external_damping=DynamicsOptions::default().external_damping, rotary_inertia=DynamicsOptions::default().rotary_inertia, grid=DynamicsOptions::default().grid, tol=DynamicsOptions::default().tol, time_scheme=None))]
#[allow(clippy::too_many_arguments)]
fn dynamics_free<'py>(
    py: Python<'py>,
    rod: &PyRod,
    release_force: (f64, f64),
    foot_moment: f64,
    dt: f64,
    t_end: f64,
    time_tol: Option<f64>,
    foot_damping: f64,
    internal_damping: f64,
    external_damping: f64,
    rotary_inertia: f64,
    grid: usize,
    tol: f64,
    time_scheme: Option<&str>,
) -> PyResult<Bound<'py, PyAny>> {
    let time_scheme = match time_scheme {
        None => None,
        Some("newmark") => Some(vibrissa::dynamics::TimeScheme::Newmark),
        Some("energy_momentum") => Some(vibrissa::dynamics::TimeScheme::EnergyMomentum),
        Some(other) => {
            return Err(input(format!(
                "time_scheme must be 'newmark' or 'energy_momentum', not '{other}'"
            )))
        }
    };
    let opts = DynamicsOptions {
        dt,
        t_end,
        time_tol,
        time_scheme,
        foot_damping,
        internal_damping,
        external_damping,
        rotary_inertia,
        foot_moment,
        release_force: [release_force.0, release_force.1],
        grid,
        tol,
        ..DynamicsOptions::default()
    };
    opts.validate().map_err(py_err)?;
    let rod = rod.0.clone();
    let (units, unit_s) = (rod.units(), time_unit(&rod));
    let r = interruptible(py, Arc::new(AtomicBool::new(false)), move || {
        vibrissa::dynamics::free(&rod, &|_| [0.0, 0.0], &opts)
    })?
    .map_err(py_err)?;
    let out = to_py(py, &r)?;
    out.set_item("units", units_dict(py, units)?)?;
    out.set_item("time_unit_s", unit_s)?;
    Ok(out)
}

/// The drag in time (`vibrissa dynamics drag`): every option of the library's `DynDragOptions`
/// the program's flags set (`time_tol`: adaptive steps, `None` fixed ones; the dampers;
/// `mu_k_table` as `(speed, mu_k)` pairs, empty: `mu_k`; `flight`; `foot_table` as rows
/// `(t, d)` or `(t, d, theta)`, empty: `speed` and `ramp`; `whisk` as `(amplitude,
/// frequency)`), and its `grid`, `tol`, `event_tol`, `max_events` and `refinements`, the
/// defaults and checks the library's. A dict with the library's `DynDragResult` (`samples`,
/// `events`, `stop`, `stats`; what the program's `--json` prints) plus `units` and
/// `time_unit_s`. Ctrl-C stops waiting for it.
#[pyfunction]
#[pyo3(signature = (rod, surface, *, speed=DynDragOptions::default().speed, ramp=DynDragOptions::default().ramp, d_max=DynDragOptions::default().d_max, mu_s=DynDragOptions::default().mu_s, mu_k=DynDragOptions::default().mu_k, mu_k_table=table_pairs(&DynDragOptions::default().mu_k_table), dt=DynDragOptions::default().dt, time_tol=DynDragOptions::default().time_tol, foot_damping=DynDragOptions::default().foot_damping, internal_damping=DynDragOptions::default().internal_damping, external_damping=DynDragOptions::default().external_damping, rotary_inertia=DynDragOptions::default().rotary_inertia, flight=DynDragOptions::default().flight, grid=DynDragOptions::default().grid, tol=DynDragOptions::default().tol, event_tol=DynDragOptions::default().event_tol, max_events=DynDragOptions::default().max_events, refinements=DynDragOptions::default().refinements, foot_table=vec![], whisk=None))]
#[allow(clippy::too_many_arguments)]
fn dynamics_drag<'py>(
    py: Python<'py>,
    rod: &PyRod,
    surface: &PySurface,
    speed: f64,
    ramp: f64,
    d_max: f64,
    mu_s: f64,
    mu_k: f64,
    mu_k_table: Vec<(f64, f64)>,
    dt: f64,
    time_tol: Option<f64>,
    foot_damping: f64,
    internal_damping: f64,
    external_damping: f64,
    rotary_inertia: f64,
    flight: bool,
    grid: usize,
    tol: f64,
    event_tol: f64,
    max_events: usize,
    refinements: u32,
    foot_table: Vec<Vec<f64>>,
    whisk: Option<(f64, f64)>,
) -> PyResult<Bound<'py, PyAny>> {
    let foot_table = foot_table
        .iter()
        .enumerate()
        .map(|(i, r)| match r[..] {
            [t, d] => Ok([t, d, 0.0]),
            [t, d, theta] => Ok([t, d, theta]),
            _ => Err(py_err(vibrissa::VibrissaError::InvalidTable {
                name: "foot".into(),
                reason: format!(
                    "foot_table row {i} has {} entries: rows are (t, d) or (t, d, theta)",
                    r.len()
                ),
            })),
        })
        .collect::<PyResult<Vec<_>>>()?;
    let opts = DynDragOptions {
        speed,
        ramp,
        d_max,
        mu_s,
        mu_k,
        mu_k_table: mu_k_table.into_iter().map(|(v, m)| [v, m]).collect(),
        dt,
        time_tol,
        foot_damping,
        internal_damping,
        external_damping,
        rotary_inertia,
        flight,
        grid,
        tol,
        event_tol,
        max_events,
        refinements,
        foot_table,
        whisk: whisk.map(|(amplitude, frequency)| vibrissa::dynamics::Whisk {
            amplitude,
            frequency,
        }),
        ..DynDragOptions::default()
    };
    opts.validate().map_err(py_err)?;
    let (rod, surface) = (rod.0.clone(), surface.s.clone());
    let (units, unit_s) = (rod.units(), time_unit(&rod));
    let r = interruptible(py, Arc::new(AtomicBool::new(false)), move || {
        vibrissa::dynamics::drag(&rod, &surface, &opts)
    })?
    .map_err(py_err)?;
    let out = to_py(py, &r)?;
    out.set_item("units", units_dict(py, units)?)?;
    out.set_item("time_unit_s", unit_s)?;
    Ok(out)
}

/// A friction table's points as `(speed, mu_k)` pairs.
fn table_pairs(t: &[[f64; 2]]) -> Vec<(f64, f64)> {
    t.iter().map(|p| (p[0], p[1])).collect()
}

/// Natural frequencies of a static state given by its foot values (`vibrissa modes`): a dict
/// with the library's `ModesResult` (what the program's `--json` prints) plus `time_unit_s`.
/// `tip`: "free", "pinned" or "sliding" (on the line of inclination `tip_angle`).
#[pyfunction]
#[pyo3(signature = (rod, *, m_base=0.0, fx=0.0, fy=0.0, tip="free", tip_angle=0.0, count=ModeOptions::default().count, rotary_inertia=ModeOptions::default().rotary_inertia, points=ModeOptions::default().shape_points))]
#[allow(clippy::too_many_arguments)]
fn modes<'py>(
    py: Python<'py>,
    rod: &PyRod,
    m_base: f64,
    fx: f64,
    fy: f64,
    tip: &str,
    tip_angle: f64,
    count: usize,
    rotary_inertia: f64,
    points: usize,
) -> PyResult<Bound<'py, PyAny>> {
    let tip = match tip {
        "free" => TipCondition::Free,
        "pinned" => TipCondition::Pinned,
        "sliding" => {
            vibrissa::limits::TIP_ANGLE
                .check("tip_angle", tip_angle)
                .map_err(py_err)?;
            TipCondition::Sliding { angle: tip_angle }
        }
        other => {
            return Err(input(format!(
                "invalid tip '{other}': valid values are free, pinned, sliding"
            )))
        }
    };
    let opts = ModeOptions {
        count,
        rotary_inertia,
        shape_points: points,
        ..ModeOptions::default()
    };
    let load = BaseLoad { m_base, fx, fy };
    let rod = rod.0.clone();
    let unit_s = time_unit(&rod);
    let r = interruptible(py, Arc::new(AtomicBool::new(false)), move || {
        vibrissa::modes::modes(&rod, &load, tip, &opts)
    })?
    .map_err(py_err)?;
    let out = to_py(py, &r)?;
    out.set_item("time_unit_s", unit_s)?;
    Ok(out)
}

/// `vibrissa._core`: see the `vibrissa` package.
#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyRod>()?;
    m.add_class::<PySurface>()?;
    m.add_function(wrap_pyfunction!(scene_from_dict, m)?)?;
    m.add_function(wrap_pyfunction!(scene_from_toml, m)?)?;
    m.add_function(wrap_pyfunction!(defaults, m)?)?;
    m.add_function(wrap_pyfunction!(limits, m)?)?;
    m.add_function(wrap_pyfunction!(solve, m)?)?;
    m.add_function(wrap_pyfunction!(scan, m)?)?;
    m.add_function(wrap_pyfunction!(infer, m)?)?;
    m.add_function(wrap_pyfunction!(sweep, m)?)?;
    m.add_function(wrap_pyfunction!(drag, m)?)?;
    m.add_function(wrap_pyfunction!(whisk, m)?)?;
    m.add_function(wrap_pyfunction!(locate, m)?)?;
    m.add_function(wrap_pyfunction!(solve_peg, m)?)?;
    m.add_function(wrap_pyfunction!(fit, m)?)?;
    m.add_function(wrap_pyfunction!(dynamics_free, m)?)?;
    m.add_function(wrap_pyfunction!(dynamics_drag, m)?)?;
    m.add_function(wrap_pyfunction!(modes, m)?)?;
    Ok(())
}
