"""Type stub of the extension module ``dyncontact._native`` (Rust, pyo3).

Use the functions of ``dyncontact`` (``dyncontact/__init__.py``); these are their building
blocks. SI units: m, N, Pa, kg, s. Every function raises ``ValueError`` naming the key for bad
input and ``InternalError`` for a caught Rust panic; long ones release the GIL.
"""

from typing import Any, Dict, List, Optional

import numpy as np
import numpy.typing as npt

__version__: str

class SolverError(RuntimeError):
    """A solver did not converge or failed. Raised by ``dyncontact`` with ``iterations``
    (int), ``residual`` (last relative change of the pressure) and ``result`` (the last
    iterate, a ``ContactResult``) when NormCG stops at its iteration limit."""

    iterations: int
    residual: float
    result: Any

class InternalError(RuntimeError):
    """A bug in dyncontact: a Rust panic caught at the boundary (never a crash)."""

def toml_text(case: Dict[str, Any]) -> str:
    """The TOML text of a scenario dict (keys as in the file; None values left out)."""

def solve_normal(
    gap: npt.NDArray[np.float64],
    dx: float,
    dy: float,
    material: Dict[str, Any],
    force: Optional[float] = None,
    approach: Optional[float] = None,
    tol: Optional[float] = None,
    max_iter: Optional[int] = None,
) -> Dict[str, Any]:
    """NormCG on a user-made gap h [m] of shape (ny, nx) (C-contiguous float64 is read without
    conversion), elements dx × dy [m], grid centred on the origin; exactly one of ``force``
    [N] and ``approach`` [m]. Returns ``pressure`` [Pa] (ny, nx), ``x`` [m] (nx,), ``y`` [m]
    (ny,), ``normal_force`` [N], ``approach`` [m], ``max_pressure`` [Pa], ``contact_area``
    [m²], ``elements_in_contact``, ``centre_of_pressure`` [m], ``iterations``, ``residual``,
    ``converged``, ``dfn_dapproach`` [N/m], ``solve_time_s`` [s] (the Rust set-up and solve)."""

def contact_text(text: str, base: str) -> Dict[str, Any]:
    """A contact case (TOML text; ``base`` resolves a gap table's path) solved as ``dyncontact
    contact``: the keys of ``solve_normal`` plus ``summary_json`` (the CLI's ``--json``) and,
    with the exact tangential solver, ``traction_x``, ``traction_y`` [Pa] and ``adhesion``
    (bool), each (ny, nx)."""

def creep_curve_text(text: str, base: str, variable: str, values: List[float]) -> str:
    """The creep curve of a contact case with ``[friction]`` over ``values`` of ``variable``
    (``creepage_x``, ``creepage_y``, ``spin`` [1/m]), as the JSON of ``dyncontact
    creep-curve``. Ctrl-C stops it between points."""

def modes_text(text: str) -> Dict[str, Any]:
    """The modal table of a file's ``[bridge]`` (``summary_json``) and the mass-normalised
    mode shapes [1/√kg]: ``x`` [m] (401,), ``shapes`` (401, modes)."""

def sweep_shard(text: str, base: str, k: int, n: int) -> str:
    """Shard ``k`` of ``n`` of a sweep (``kind = "sweep"``) as the JSON of ``shard.json``
    (floats exact). Ctrl-C stops it between passages (``KeyboardInterrupt``)."""

def sweep_merge(shards: List[str]) -> Dict[str, Any]:
    """A complete set of shards merged as ``dyncontact sweep-merge``: ``summary_json`` (the
    CLI's ``summary.json``) and the columns of ``sweep.csv`` as float64 arrays: ``train``,
    ``speed_m_s``, ``point_m``, ``max_deflection_m``, ``max_acceleration_m_s2``,
    ``max_static_deflection_m``, ``dynamic_factor``."""

def run_text(text: str, base: str) -> Dict[str, Any]:
    """A scenario file's text: ``kind = "vehicle_bridge"`` is run (GIL released, Ctrl-C
    polled) and returns ``kind``, ``summary`` (dict), ``columns`` (the names of
    ``timeseries.csv``) and ``series`` (float64, rows × columns); ``ball_drop`` and
    ``moving_load`` are run the same way and return ``summary_json`` (the CLI's summary.json
    as JSON text) instead of ``summary``; other kinds return only ``kind``."""

def _panic_for_tests(interruptible_run: bool) -> None:
    """Panics inside the boundary (tests that it raises InternalError). Not public API."""
