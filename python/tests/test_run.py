"""Vehicle–bridge runs through `run`: the summary numbers and the time series equal the CLI's
(`dyncontact run FILE --json` and its timeseries.csv)."""

import csv
import tomllib

import numpy as np
import pytest

import dyncontact
from conftest import EXAMPLES, cli_json


def columns(t) -> dict:
    if isinstance(t, dict):
        return t
    return {k: t[k].to_numpy() for k in t.columns}


@pytest.mark.parametrize(
    "name",
    [
        "vehicle_bridge_biggs.toml",
        "vehicle_bridge_default.toml",
        "train_bridge.toml",
        "vehicle_bridge_two_span_flat.toml",
    ],
)
def test_vehicle_bridge_run_equals_the_cli(name, tmp_path):
    path = EXAMPLES / name
    r = dyncontact.run(path)
    cli = cli_json("run", str(path), "--out", str(tmp_path))
    s = r["summary"]
    assert s["completed"] and cli["completed"]
    for key in ("time_reached", "max_midspan_deflection", "max_midspan_acceleration",
                "max_quasi_static_deflection", "dynamic_amplification"):
        assert s[key] == cli[key], key
    for key in ("max_force", "min_force", "loss_of_contact_events", "max_unloading_ratio"):
        assert s["contact"][key] == cli["contact"][key], key
    # BEM contact only: the solve counts of the reuse ([contact] reuse_tol).
    for key in ("full_solves", "factor_solves", "reused_evaluations", "max_reuse_error_estimate",
                "table_evaluations", "table_solves"):
        assert (key in s["contact"]) == (key in cli["contact"]), key
        if key in cli["contact"]:
            assert s["contact"][key] == cli["contact"][key], key
    # The train's part (trains only): per-vehicle peaks, the train, the comfort level; the
    # response points of `[output] points` (the two-span example).
    for key in ("vehicles", "train", "comfort", "points"):
        assert (key in s) == (key in cli), key
        if key in cli:
            assert s[key] == cli[key], key
    assert s["vehicle"]["static_wheel_loads"] == cli["vehicle"]["static_wheel_loads"]
    for key in ("steps", "max_iterations_per_step", "failed_steps"):
        assert s["solver"][key] == cli["solver"][key], key
    # The time series: same columns and rows as timeseries.csv (the CLI writes each value in
    # its shortest round-trip form, so the numbers are bit-identical).
    with open(tmp_path / "timeseries.csv") as f:
        rows = list(csv.reader(line for line in f if not line.startswith("#")))
    header, values = rows[0], np.array(rows[1:], dtype=float)
    table = columns(r["timeseries"])
    assert list(table) == header
    for k, name in enumerate(header):
        np.testing.assert_array_equal(table[name], values[:, k], err_msg=name)


def test_run_dispatches_and_refuses():
    assert dyncontact.run(EXAMPLES / "hertz_sphere.toml").max_pressure == dyncontact.contact(
        EXAMPLES / "hertz_sphere.toml"
    ).max_pressure
    with open(EXAMPLES / "vehicle_bridge_biggs.toml", "rb") as f:
        case = tomllib.load(f)
    case.setdefault("output", {})["every"] = 0
    with pytest.raises(ValueError, match="every"):
        dyncontact.run(case)


@pytest.mark.parametrize("name", ["ball_drop_steel.toml", "moving_load_fryba.toml"])
def test_ball_drop_and_moving_load_runs_equal_the_cli(name, tmp_path):
    # The summary is the CLI's summary.json key by key (the wall time and the input echo
    # aside), and the time series is its timeseries.csv bit for bit.
    path = EXAMPLES / name
    r = dyncontact.run(path)
    cli = cli_json("run", str(path), "--out", str(tmp_path))
    s = r["summary"]
    for key in set(cli) - {"wall_time_s", "input"}:
        if key == "integrator" and isinstance(cli[key], dict):
            for k in set(cli[key]) - {"wall_time_s"}:
                assert s[key][k] == cli[key][k], (key, k)
        else:
            assert s[key] == cli[key], key
    with open(tmp_path / "timeseries.csv") as f:
        rows = list(csv.reader(line for line in f if not line.startswith("#")))
    header, values = rows[0], np.array(rows[1:], dtype=float)
    table = columns(r["timeseries"])
    assert list(table) == header
    for k, col in enumerate(header):
        np.testing.assert_array_equal(table[col], values[:, k], err_msg=col)
