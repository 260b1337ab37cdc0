"""dyncontact: contact in dynamical simulations, from Python.

The Rust library (elastic half-space contact, bridge modes, speed sweeps) with numpy arrays in
and out, SI units everywhere (m, N, Pa, kg, s). Scenario dicts have the structure of the TOML
files that the ``dyncontact`` command-line program reads (README.md, docs/*.md): the same keys,
the same checks and the same error messages, which name the key.

Errors: bad input raises ``ValueError`` naming the key; a solver that does not converge raises
``SolverError`` (with ``iterations``, ``residual`` and, where there is one, the last iterate as
``result``); a bug in the Rust code raises ``InternalError``, never a crash. Long computations
release the GIL, and sweeps and creep curves stop on Ctrl-C (``KeyboardInterrupt``).
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from typing import Any, Dict, Mapping, Optional, Sequence, Union

import numpy as np

from . import _native
from ._native import InternalError, SolverError

__all__ = [
    "ContactResult",
    "InternalError",
    "SolverError",
    "contact",
    "creep_curve",
    "modes",
    "run",
    "solve_normal",
    "sweep",
]
__version__ = _native.__version__

Case = Union[str, "os.PathLike[str]", Mapping[str, Any]]


@dataclass(frozen=True)
class ContactResult:
    """The solution of a normal (and tangential) contact problem.

    Arrays are float64 with shape (ny, nx), x fastest (element (ix, iy) is ``[iy, ix]``).
    """

    pressure: np.ndarray
    """Normal pressure p ≥ 0 per element [Pa], shape (ny, nx)."""
    x: np.ndarray
    """Element centres along x [m], shape (nx,)."""
    y: np.ndarray
    """Element centres along y [m], shape (ny,)."""
    normal_force: float
    """Total normal force F_n [N]."""
    approach: float
    """Approach δ of the two bodies [m] (positive when they overlap)."""
    max_pressure: float
    """Largest element pressure [Pa]."""
    contact_area: float
    """Contact area [m²]."""
    elements_in_contact: int
    """Elements with p > 0."""
    centre_of_pressure: tuple
    """Centre of pressure (x, y) [m]."""
    iterations: int
    """NormCG iterations."""
    residual: float
    """Last relative change ‖Δp‖/‖p‖ of the pressure."""
    converged: bool
    """Whether NormCG met its stopping rule (always True in a returned result)."""
    dfn_dapproach: Optional[float]
    """Contact stiffness dF_n/dδ [N/m] of the converged contact set."""
    solve_time_s: float
    """Wall time of the Rust solve [s] (solver set-up included)."""
    hertz: Optional[Dict[str, float]] = None
    """Hertz's closed form for a quadratic or sphere gap: approach [m], max_pressure [Pa],
    a, b [m], normal_force [N]; None otherwise."""
    traction_x: Optional[np.ndarray] = None
    """Tangential traction p_x on body 1 [Pa], shape (ny, nx) (exact tangential solver)."""
    traction_y: Optional[np.ndarray] = None
    """Tangential traction p_y on body 1 [Pa], shape (ny, nx)."""
    adhesion: Optional[np.ndarray] = None
    """Boolean mask of the adhesion area, shape (ny, nx)."""
    summary: Dict[str, Any] = field(default_factory=dict)
    """Every key of ``dyncontact contact --json`` (tangential forces, grid, material, ...)."""


def _result(d: Dict[str, Any], summary: Optional[Dict[str, Any]] = None) -> ContactResult:
    summary = summary or {}
    return ContactResult(
        pressure=d["pressure"],
        x=d["x"],
        y=d["y"],
        normal_force=d["normal_force"],
        approach=d["approach"],
        max_pressure=d["max_pressure"],
        contact_area=d["contact_area"],
        elements_in_contact=d["elements_in_contact"],
        centre_of_pressure=tuple(d["centre_of_pressure"]),
        iterations=d["iterations"],
        residual=d["residual"],
        converged=d["converged"],
        dfn_dapproach=d["dfn_dapproach"],
        solve_time_s=d["solve_time_s"],
        hertz=summary.get("hertz"),
        traction_x=d.get("traction_x"),
        traction_y=d.get("traction_y"),
        adhesion=d.get("adhesion"),
        summary=summary,
    )


def _not_converged(d: Dict[str, Any], result: ContactResult) -> SolverError:
    err = SolverError(
        f"NormCG did not converge in {d['iterations']} iterations "
        f"(relative change {d['residual']:.3e})"
    )
    err.iterations = d["iterations"]
    err.residual = d["residual"]
    err.result = result
    return err


def _case_text(case: Case, what: str) -> "tuple[str, str]":
    """The TOML text of a case and the directory its relative paths are resolved against."""
    if isinstance(case, Mapping):
        return _native.toml_text(dict(case)), os.getcwd()
    if isinstance(case, (str, os.PathLike)):
        path = os.fspath(case)
        with open(path, encoding="utf-8") as f:
            text = f.read()
        return text, os.path.dirname(os.path.abspath(path))
    raise TypeError(f"{what}: expected a dict or a path to a TOML file, got {type(case).__name__}")


def solve_normal(
    gap: "np.typing.ArrayLike",
    dx: float,
    dy: float,
    material: Mapping[str, Any],
    force: Optional[float] = None,
    approach: Optional[float] = None,
    tol: float = 1e-8,
    max_iter: Optional[int] = None,
) -> ContactResult:
    """Normal contact of two elastic half-spaces for a user-made gap (e.g. a rough surface).

    gap: undeformed distance h [m], shape (ny, nx), x fastest; a C-contiguous float64 array is
        read without conversion. dx, dy: element size [m]. The grid is centred on the origin.
    material: ``{"body1": {"E": Pa, "nu": -}, "body2": {...}}`` (``{"rigid": True}`` for a
        rigid body), or ``{"E": Pa, "nu": -}`` for two identical bodies.
    force: total normal force [N], or approach: approach δ [m] (exactly one).
    tol: relative change of the pressure at convergence; max_iter: NormCG iteration limit
        (default 200).

    Raises ValueError naming the key for bad input, SolverError (iterations, residual, result)
    when NormCG does not converge. The GIL is released during the solve.
    """
    h = np.asarray(gap, dtype=np.float64)
    if h.ndim != 2:
        raise ValueError(f"`gap`: expected a 2-D array (ny, nx), got {h.ndim} dimensions")
    if not h.flags.c_contiguous:
        h = np.ascontiguousarray(h)
    if not isinstance(material, Mapping):
        raise TypeError("`material`: expected a dict")
    d = _native.solve_normal(
        h, float(dx), float(dy), dict(material), force, approach, tol, max_iter
    )
    result = _result(d)
    if not d["converged"]:
        raise _not_converged(d, result)
    return result


def contact(case: Case) -> ContactResult:
    """Solve a contact case, as ``dyncontact contact CASE.toml``.

    case: a dict with the structure of the TOML case file (``body1``, ``body2``, ``gap``,
        ``grid``, ``load``, ``solver``, ``friction``, ``kinematics``; README.md), or the path
        of such a file (relative gap-table paths are resolved against its directory, for a dict
        against the working directory).

    Returns a ContactResult (pressure, x, y, forces, Hertz, and the exact tangential tractions
    and adhesion mask when the case has ``[friction]`` and ``[kinematics]``).
    """
    text, base = _case_text(case, "contact")
    d = _native.contact_text(text, base)
    summary = json.loads(d["summary_json"])
    result = _result(d, summary)
    if not d["converged"]:
        raise _not_converged(d, result)
    return result


def creep_curve(
    case: Case, creepages: "np.typing.ArrayLike", variable: str = "creepage_x"
) -> Dict[str, Any]:
    """Creep force against creepage in steady rolling, as ``dyncontact creep-curve``.

    case: a contact case (dict or path) with ``friction.mu``; its ``kinematics`` creepages (if
        any) hold the creepages that are not swept. creepages: values of ``variable``
        (``creepage_x``, ``creepage_y`` (dimensionless) or ``spin`` [1/m]).

    Returns the dict of ``creep_curve.json`` with the points also as numpy arrays under
    ``"columns"`` (``exact_force_x`` [N], ``fastsim_force_x`` [N] (NaN without a Hertzian gap),
    ...). Ctrl-C stops it between points.
    """
    text, base = _case_text(case, "creep_curve")
    values = [float(v) for v in np.asarray(creepages, dtype=np.float64).ravel()]
    curve = json.loads(_native.creep_curve_text(text, base, variable, values))
    points = curve["points"]
    columns = {}
    for key in points[0] if points else []:
        columns[key] = np.array(
            [np.nan if p[key] is None else p[key] for p in points], dtype=np.float64
        )
    curve["columns"] = columns
    return curve


def modes(bridge: Case) -> Dict[str, Any]:
    """The modal table of a bridge, as ``dyncontact modes``.

    bridge: a dict with a ``bridge`` table (the ``[bridge]`` section of a scenario file), or a
        path to a file with one.

    Returns ``{"bridge": description, "modes": [{"n", "beta_l", "omega" [rad/s],
    "frequency" [Hz]}, ...], "frequency": array [Hz], "omega": array [rad/s], "x": array [m]
    (401 points along the span), "shapes": array (401, modes) [1/√kg]}``.
    """
    text, _ = _case_text(bridge, "modes")
    d = _native.modes_text(text)
    out = json.loads(d["summary_json"])
    out["frequency"] = np.array([m["frequency"] for m in out["modes"]])
    out["omega"] = np.array([m["omega"] for m in out["modes"]])
    out["x"] = d["x"]
    out["shapes"] = d["shapes"]
    return out


def _sweep_shard(text: str, base: str, k: int, n: int) -> str:
    """One shard of a sweep (runs on a Dask worker)."""
    return _native.sweep_shard(text, base, k, n)


def _maybe_frame(columns: Dict[str, np.ndarray]) -> Any:
    try:
        import pandas as pd
    except ImportError:
        return columns
    return pd.DataFrame(columns)


def sweep(
    file_or_dict: Case, client: Any = None, shards: Optional[int] = None
) -> Dict[str, Any]:
    """Every train at every speed over a bridge, as ``dyncontact sweep`` (``kind = "sweep"``).

    file_or_dict: the sweep scenario (path or dict). client: a ``distributed.Client``; the
        (train, speed) passages are then cut into ``shards`` interleaved slices (default: one
        per worker thread of the cluster), run on the workers, and merged exactly as
        ``dyncontact sweep-merge`` merges shards: the result equals a local run (bit for bit;
        only ``wall_time_s`` differs). Works with any Dask cluster, e.g.
        ``dask_jobqueue.SLURMCluster`` on an HPC cluster.

    Returns the dict of the CLI's ``summary.json`` (per-train maxima, envelope, Eurocode
    check; SI units) with ``"passages"``: the table of ``sweep.csv`` (one row per passage and
    output point; a pandas DataFrame when pandas is installed, else a dict of arrays).
    """
    text, base = _case_text(file_or_dict, "sweep")
    if client is None:
        parts = [_native.sweep_shard(text, base, 1, 1)]
    else:
        if shards is None:
            info = client.scheduler_info()
            shards = max(1, sum(w.get("nthreads", 1) for w in info["workers"].values()))
        if shards < 1:
            raise ValueError(f"`shards` = {shards}: must be at least 1")
        futures = client.map(
            _sweep_shard,
            [text] * shards,
            [base] * shards,
            range(1, shards + 1),
            [shards] * shards,
            pure=False,
        )
        parts = client.gather(futures)
    merged = _native.sweep_merge(list(parts))
    out = json.loads(merged.pop("summary_json"))
    out["passages"] = _maybe_frame(merged)
    return out


def run(scenario: Case) -> Dict[str, Any]:
    """Run a scenario file (dispatch on its ``kind``), as ``dyncontact run``.

    ``kind = "vehicle_bridge"``: wheels or a train over a bridge, coupled at every step (GIL
    released; Ctrl-C raises ``KeyboardInterrupt``). Returns ``{"summary": dict, "timeseries":
    table}``: the summary holds the run's key numbers under the names of the CLI's
    ``summary.json`` (``max_midspan_deflection`` [m], ``max_midspan_acceleration`` [m/s²],
    ``dynamic_amplification``, ``points`` (with ``[output] points``: per point ``x`` [m],
    ``max_deflection`` [m], ``max_acceleration`` [m/s²]), ``contact`` (``max_force``, ``min_force`` [N], ``max_pressure``
    [Pa], ``loss_of_contact_events``, ``max_unloading_ratio``; BEM contact also
    ``full_solves``, ``factor_solves``, ``reused_evaluations``, ``max_reuse_error_estimate``,
    ``table_evaluations``, ``table_solves``), ``vehicle``, ``solver``,
    ``warnings``, and for trains ``vehicles`` (per bogie or articulated vehicle
    ``max_body_acceleration`` [m/s²], ``max_body_pitch_acceleration`` [rad/s²],
    ``max_bogie_acceleration`` [m/s²]), ``train`` (``name``, ``axles``, ``length`` [m],
    ``mass`` [kg]) and ``comfort`` (EN 1990 A2 level)); the time series
    has the columns of ``timeseries.csv`` (``t_s`` [s], ``deflection_midspan_m`` [m], ...,
    ``contact_force`` [N] per wheel, the response points' and, for trains, the car bodies'
    accelerations), one row per recorded step (``[output] every``), as a
    pandas DataFrame when pandas is installed, else a dict of float64 arrays.

    ``kind = "ball_drop"`` and ``kind = "moving_load"`` run the same way (GIL released, Ctrl-C
    stops them) and return ``{"summary": dict, "timeseries": table}`` with the CLI's
    ``summary.json`` (every key, as written by ``dyncontact run``, ``wall_time_s`` aside) and
    the columns of its ``timeseries.csv`` (ball drop: ``t_s``, ``z_m``, ``v_m_s``, ``a_m_s2``,
    ``approach_m``, ``force_n``, ``energy_j``; moving load: ``t_s``, ``load_position_m``,
    ``deflection_midspan_m``, ``velocity_midspan_m_s``, ``acceleration_midspan_m_s2``,
    ``moment_midspan_n_m`` and the same per further output point).

    ``kind = "contact"`` returns ``contact(scenario)``; ``kind = "sweep"`` returns
    ``sweep(scenario)``.
    """
    text, base = _case_text(scenario, "run")
    d = _native.run_text(text, base)
    kind = d["kind"]
    if kind == "contact":
        return contact(scenario)
    if kind == "sweep":
        return sweep(scenario)
    if kind in ("ball_drop", "moving_load"):
        import json

        series = d["series"]
        columns = {name: series[:, k] for k, name in enumerate(d["columns"])}
        return {"summary": json.loads(d["summary_json"]), "timeseries": _maybe_frame(columns)}
    if kind != "vehicle_bridge":
        raise ValueError(f'`kind` = "{kind}": not a scenario kind `run` knows')
    import json

    summary = d["summary"]
    extra = json.loads(d["train_json"])
    summary["contact"]["max_unloading_ratio"] = extra["max_unloading_ratio"]
    if extra.get("contact_solves") is not None:
        summary["contact"].update(extra["contact_solves"])
    for key in ("vehicles", "train", "comfort"):
        if extra[key] is not None:
            summary[key] = extra[key]
    series = d["series"]
    columns = {name: series[:, k] for k, name in enumerate(d["columns"])}
    return {"summary": summary, "timeseries": _maybe_frame(columns)}
