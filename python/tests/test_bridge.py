"""Bridges: modes, creep curves and sweeps against the CLI; the Dask sweep equal to the local
sweep."""

import tomllib

import numpy as np
import pytest

import dyncontact
from conftest import EXAMPLES, cli_json


def test_modes_equal_the_cli():
    path = EXAMPLES / "moving_load_fryba.toml"
    m = dyncontact.modes(path)
    cli = cli_json("modes", str(path))
    assert m["bridge"] == cli["bridge"] and m["modes"] == cli["modes"]
    # Simply supported: w_n(x) = √(2/(m L)) sin(nπx/L) mass-normalised (references.md §D1).
    mass, length = 2303.0, 25.0
    expected = np.sqrt(2 / (mass * length)) * np.sin(np.pi * m["x"] / length)
    np.testing.assert_allclose(m["shapes"][:, 0], expected, atol=1e-9 * expected.max())
    # f_1 = (π/L)² √(EI/m) / (2π).
    assert m["frequency"][0] == pytest.approx((np.pi / length) ** 2 * np.sqrt(8.323e9 / mass) / (2 * np.pi), rel=1e-12)
    with open(path, "rb") as f:
        from_dict = dyncontact.modes(tomllib.load(f))
    assert from_dict["modes"] == m["modes"]


def test_modes_bad_input_names_the_key():
    bridge = {"length": 20.0, "EI": 1e9, "mass_per_length": 1e4, "modes": 3}
    for key, value in [("length", -20.0), ("modes", 0), ("suports", "pinned")]:
        with pytest.raises(ValueError, match=key):
            dyncontact.modes({"bridge": {**bridge, key: value}})


def test_creep_curve_equals_the_cli():
    path = EXAMPLES / "tangential_rolling.toml"
    count, start, stop = 5, 0.0, 0.002
    values = [start + (stop - start) * k / (count - 1) for k in range(count)]  # as the CLI
    curve = dyncontact.creep_curve(path, values)
    cli = cli_json("creep-curve", str(path), "--creepage-x", f"{start}:{stop}:{count}", "--out", "/tmp/dyncontact-pytest-creep")
    for k in ("variable", "mu", "normal_force", "hertz_a", "hertz_b", "points"):
        assert curve[k] == cli[k], k
    assert curve["columns"]["exact_force_x"].shape == (count,)
    # Saturation: |F_x| ≤ μ F_n at every point.
    assert np.all(np.abs(curve["columns"]["exact_force_x"]) <= curve["mu"] * curve["normal_force"] * (1 + 1e-9))


def test_creep_curve_bad_input():
    with open(EXAMPLES / "hertz_sphere.toml", "rb") as f:
        case = tomllib.load(f)
    with pytest.raises(ValueError, match="mu"):
        dyncontact.creep_curve(case, [0.001])
    with pytest.raises(ValueError, match="variable"):
        dyncontact.creep_curve(EXAMPLES / "tangential_rolling.toml", [0.001], variable="creepage_z")


def small_sweep() -> dict:
    with open(EXAMPLES / "sweep_hslm.toml", "rb") as f:
        case = tomllib.load(f)
    case["trains"]["names"] = ["HSLM-A1", "HSLM-A4", "HSLM-A8"]
    case["speeds"]["step"] = 4 * case["speeds"]["step"]
    return case


def without_wall_time(d: dict) -> dict:
    return {k: v for k, v in d.items() if k not in ("wall_time_s", "passages")}


def columns(p) -> dict:
    if isinstance(p, dict):
        return p
    return {k: p[k].to_numpy() for k in p.columns}


def sweep_equal_to_the_cli(example: str, tmp_path) -> dict:
    """The sweep of an example from Python, checked equal to the CLI's summary.json."""
    path = EXAMPLES / example
    local = dyncontact.sweep(path)
    cli = cli_json("sweep", str(path), "--out", str(tmp_path))
    assert without_wall_time(local) == without_wall_time(cli)
    return local


def test_sweep_equals_the_cli(tmp_path):
    local = sweep_equal_to_the_cli("sweep_hslm.toml", tmp_path)
    table = columns(local["passages"])
    assert len(table["train"]) == local["runs"] * len(local["points"])
    assert np.max(table["max_acceleration_m_s2"]) == max(t["max_acceleration"] for t in local["trains"])


def test_interaction_sweep_reports_the_vehicles_as_the_cli(tmp_path):
    local = sweep_equal_to_the_cli("sweep_interaction.toml", tmp_path)
    table = columns(local["passages"])
    for t, train in enumerate(local["trains"]):
        rows = table["train"] == t
        assert np.sum(table["loss_of_contact_events"][rows]) == train["loss_of_contact_events"]
        assert np.max(table["max_unloading_ratio"][rows]) == train["max_unloading_ratio"]
        assert np.min(table["min_contact_force_n"][rows]) == train["min_contact_force"]
    # The Eurostar rake lifts wheels at 90 m/s (docs/sweep.md): unloading ratio 1, force 0.
    assert local["trains"][1]["speeds_with_loss_of_contact"] == [90.0]
    assert local["trains"][1]["min_contact_force"] == 0.0


def test_sweep_bad_input_names_the_key():
    case = small_sweep()
    case["speeds"]["step"] = -1.0
    with pytest.raises(ValueError, match="step"):
        dyncontact.sweep(case)


def test_dask_sweep_equals_the_local_sweep():
    distributed = pytest.importorskip("distributed")
    case = small_sweep()
    local = dyncontact.sweep(case)
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        remote = dyncontact.sweep(case, client=client)
        three = dyncontact.sweep(case, client=client, shards=3)
    assert without_wall_time(remote) == without_wall_time(local)
    assert without_wall_time(three) == without_wall_time(local)
    for r in (remote, three):
        a, b = columns(r["passages"]), columns(local["passages"])
        assert a.keys() == b.keys()
        for k in a:
            np.testing.assert_array_equal(a[k], b[k])


def test_merge_refuses_an_incomplete_or_mixed_set():
    from dyncontact import _native

    case = small_sweep()
    text = _native.toml_text(case)
    one_of_two = _native.sweep_shard(text, ".", 1, 2)
    with pytest.raises(ValueError, match="shard 2/2 is missing"):
        _native.sweep_merge([one_of_two])
    with pytest.raises(ValueError, match="does not fit"):
        _native.sweep_merge([one_of_two, one_of_two])
    case["speeds"]["step"] *= 2
    other = _native.sweep_shard(_native.toml_text(case), ".", 2, 2)
    with pytest.raises(ValueError, match="another scenario"):
        _native.sweep_merge([one_of_two, other])
    with pytest.raises(ValueError, match="shard 3/2"):
        _native.sweep_shard(text, ".", 3, 2)
