"""Contact through the Python package: Hertz's closed form through `solve_normal`, the dict,
TOML and CLI paths giving the same numbers, errors as exceptions naming the key."""

import math
import subprocess
import sys
import tomllib

import numpy as np
import pytest

import dyncontact
from conftest import EXAMPLES, ROOT, cli_json

E, NU = 210e9, 0.3
E_STAR = E / (2.0 * (1.0 - NU**2))  # two identical steel bodies (Johnson, Contact Mechanics §4.2)
R = 0.01
STEEL = {"E": E, "nu": NU}


def sphere_gap(n: int, half_width: float):
    dx = 2.0 * half_width / n
    x = -half_width + (np.arange(n) + 0.5) * dx
    xx, yy = np.meshgrid(x, x)  # shape (ny, nx), x fastest
    return (xx**2 + yy**2) / (2.0 * R), dx


def hertz_force(force: float):
    """Hertz's sphere: a = (3FR/4E*)^(1/3), p0 = 3F/(2πa²), δ = a²/R."""
    a = (3.0 * force * R / (4.0 * E_STAR)) ** (1.0 / 3.0)
    return a, 3.0 * force / (2.0 * math.pi * a * a), a * a / R


def test_solve_normal_hertz_sphere_force():
    force = 1000.0
    a, p0, delta = hertz_force(force)
    gap, dx = sphere_gap(128, 1.25 * a)  # about 51 elements per contact radius
    r = dyncontact.solve_normal(gap, dx, dx, STEEL, force=force)
    assert r.converged and r.pressure.shape == (128, 128) and r.pressure.dtype == np.float64
    assert r.normal_force == pytest.approx(force, rel=1e-9)
    # Discretisation errors at a/dx = 51 are ~1e-4 (second order, measured in the Rust tests
    # crates/halfspace/tests); 2e-3 leaves room without letting a wrong formula pass.
    assert r.approach == pytest.approx(delta, rel=2e-3)
    assert r.max_pressure == pytest.approx(p0, rel=2e-3)
    # The contact area is a staircase of whole elements: ~2 dx / a ≈ 4 % at most.
    assert r.contact_area == pytest.approx(math.pi * a * a, rel=0.04)
    # Pressure profile along the centre row: p0 √(1 − r²/a²) within 1 % of p0 away from the edge.
    row = r.pressure[64]
    inside = np.abs(r.x) < 0.9 * a
    expected = p0 * np.sqrt(1.0 - (r.x[inside] / a) ** 2)
    # the row at y = dx/2, not 0: compare with the closed form there
    expected = p0 * np.sqrt(np.clip(1.0 - (r.x[inside] ** 2 + r.y[64] ** 2) / a**2, 0, None))
    assert np.max(np.abs(row[inside] - expected)) < 0.01 * p0
    # dF/dδ = 3F/(2δ) (Hertz), within 3 % (the discrete contact set jumps).
    assert r.dfn_dapproach == pytest.approx(1.5 * force / delta, rel=0.03)


def test_solve_normal_hertz_approach_and_rigid_body():
    # Prescribed approach on a rigid sphere pressed into steel: F = (4/3) E* √R δ^{3/2}
    # with E* = E/(1 − ν²) for one elastic body.
    e_star = E / (1.0 - NU**2)
    delta = 5e-6
    a = math.sqrt(R * delta)
    gap, dx = sphere_gap(96, 1.3 * a)
    r = dyncontact.solve_normal(
        gap, dx, dx, {"body1": {"rigid": True}, "body2": STEEL}, approach=delta, tol=1e-10
    )
    force = 4.0 / 3.0 * e_star * math.sqrt(R) * delta**1.5
    assert r.approach == delta
    assert r.normal_force == pytest.approx(force, rel=3e-3)


def test_solve_normal_reads_non_contiguous_and_lists():
    force = 500.0
    a, _, _ = hertz_force(force)
    gap, dx = sphere_gap(64, 1.25 * a)
    base = dyncontact.solve_normal(gap, dx, dx, STEEL, force=force)
    fortran = dyncontact.solve_normal(np.asfortranarray(gap), dx, dx, STEEL, force=force)
    listed = dyncontact.solve_normal(gap.tolist(), dx, dx, STEEL, force=force)
    np.testing.assert_array_equal(base.pressure, fortran.pressure)
    np.testing.assert_array_equal(base.pressure, listed.pressure)


def hertz_case() -> dict:
    with open(EXAMPLES / "hertz_sphere.toml", "rb") as f:
        return tomllib.load(f)


def same_summary(a: dict, b: dict):
    a = {k: v for k, v in a.items() if not k.endswith("time_s")}
    b = {k: v for k, v in b.items() if not k.endswith("time_s")}
    assert a == b


@pytest.mark.parametrize("name", ["hertz_sphere.toml", "hertz_ellipse.toml", "tangential_rolling.toml", "wavy_table.toml"])
def test_contact_path_dict_and_cli_agree(name):
    path = EXAMPLES / name
    from_path = dyncontact.contact(path)
    cli = cli_json("contact", str(path))
    same_summary(from_path.summary, cli)
    assert from_path.max_pressure == cli["max_pressure"]
    assert from_path.normal_force == cli["normal_force"]
    assert from_path.iterations == cli["iterations"]
    with open(path, "rb") as f:
        case = tomllib.load(f)
    if name == "wavy_table.toml":  # relative table path: from the working directory for a dict
        case["gap"]["file"] = str(EXAMPLES / case["gap"]["file"])
    from_dict = dyncontact.contact(case)
    same_summary(from_dict.summary, from_path.summary)
    np.testing.assert_array_equal(from_dict.pressure, from_path.pressure)
    g = cli["grid"]
    assert from_path.pressure.shape == (g["ny"], g["nx"])
    assert from_path.x[0] == pytest.approx(g["x0"] + 0.5 * g["dx"], rel=1e-12)


def test_tangential_results():
    r = dyncontact.contact(EXAMPLES / "tangential_rolling.toml")
    assert r.traction_x is not None and r.traction_x.shape == r.pressure.shape
    assert r.adhesion.dtype == np.bool_
    assert int(r.adhesion.sum()) == r.summary["adhesion_elements"]
    area = (r.x[1] - r.x[0]) * (r.y[1] - r.y[0])
    assert r.traction_x.sum() * area == pytest.approx(r.summary["tangential_force_x"], rel=1e-9, abs=1e-9)
    # Coulomb: |p_t| ≤ μ p_n everywhere (to rounding).
    mu = r.summary["mu"]
    pt = np.hypot(r.traction_x, r.traction_y)
    assert np.all(pt <= mu * r.pressure * (1 + 1e-9) + 1e-6 * mu * r.max_pressure)


def test_readme_one_liner_prints_the_cli_number():
    out = subprocess.run(
        [sys.executable, "-c", "import dyncontact; print(dyncontact.contact('examples/hertz_sphere.toml').max_pressure)"],
        cwd=ROOT, capture_output=True, text=True, check=True,
    )
    assert float(out.stdout) == cli_json("contact", "examples/hertz_sphere.toml")["max_pressure"]
    # README.md quotes the printed number.
    assert f"prints {out.stdout.strip()}," in (ROOT / "README.md").read_text(encoding="utf-8")


@pytest.mark.parametrize(
    "edit, key",
    [
        (lambda c: c["load"].update(force=-1.0), "force"),
        (lambda c: c["body1"].update(nu=0.7), "nu"),
        (lambda c: c["body1"].update(youngs=1.0), "youngs"),
        (lambda c: c.update(grid={"nx": 0, "ny": 8, "dx": 1e-5, "dy": 1e-5}), "nx"),
        (lambda c: c["gap"].update(kind="banana"), "banana"),
        (lambda c: c["load"].update(approach=1e-6), "approach"),
        (lambda c: c.update(solver={"tol": 2.0}), "tol"),
    ],
)
def test_contact_bad_input_names_the_key(edit, key):
    case = hertz_case()
    edit(case)
    with pytest.raises(ValueError, match=key):
        dyncontact.contact(case)


def test_solve_normal_bad_input_names_the_key():
    gap, dx = sphere_gap(16, 1e-3)
    with pytest.raises(ValueError, match="force"):
        dyncontact.solve_normal(gap, dx, dx, STEEL, force=-5.0)
    with pytest.raises(ValueError, match="force.*approach|approach.*force"):
        dyncontact.solve_normal(gap, dx, dx, STEEL)
    with pytest.raises(ValueError, match="nu"):
        dyncontact.solve_normal(gap, dx, dx, {"E": E}, force=1.0)
    with pytest.raises(ValueError, match="youngs"):
        dyncontact.solve_normal(gap, dx, dx, {"youngs": E, "nu": NU}, force=1.0)
    with pytest.raises(ValueError, match="dx"):
        dyncontact.solve_normal(gap, -1.0, dx, STEEL, force=1.0)
    with pytest.raises(ValueError, match="tol"):
        dyncontact.solve_normal(gap, dx, dx, STEEL, force=1.0, tol=0.0)
    with pytest.raises(ValueError, match="`max_iter` = -1: must be at least 1"):
        dyncontact.solve_normal(gap, dx, dx, STEEL, force=1.0, max_iter=-1)
    with pytest.raises(ValueError, match=r"`force` = 1e300: must lie in"):
        dyncontact.solve_normal(gap, dx, dx, STEEL, force=1e300)
    bad = gap.copy()
    bad[3, 5] = np.nan
    with pytest.raises(ValueError, match=r"gap.*\(5, 3\)"):
        dyncontact.solve_normal(bad, dx, dx, STEEL, force=1.0)
    with pytest.raises(ValueError, match="gap"):
        dyncontact.solve_normal(np.zeros(10), dx, dx, STEEL, force=1.0)


def test_non_convergence_is_a_solver_error_with_its_numbers():
    a, _, _ = hertz_force(1000.0)
    gap, dx = sphere_gap(64, 1.25 * a)
    with pytest.raises(dyncontact.SolverError) as info:
        dyncontact.solve_normal(gap, dx, dx, STEEL, force=1000.0, max_iter=1)
    err = info.value
    assert isinstance(err, RuntimeError)
    assert err.iterations == 1 and err.residual > 1e-8
    assert err.result.pressure.shape == (64, 64) and not err.result.converged
    case = hertz_case()
    case["solver"] = {"max_iter": 1}
    with pytest.raises(dyncontact.SolverError, match="did not converge in 1 iterations"):
        dyncontact.contact(case)


def test_wrong_types_are_type_errors():
    with pytest.raises(TypeError):
        dyncontact.contact(42)
    case = hertz_case()
    case["load"]["force"] = object()
    with pytest.raises(TypeError, match="load.force"):
        dyncontact.contact(case)
