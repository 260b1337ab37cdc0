"""A Rust panic never crosses into Python: the boundary catches it (with the GIL released,
and on the worker thread of an interruptible run) and raises dyncontact.InternalError."""

import pytest

import dyncontact
from dyncontact import _native


@pytest.mark.parametrize("interruptible", [False, True])
def test_a_panic_is_an_internal_error(interruptible):
    with pytest.raises(dyncontact.InternalError, match="deliberate panic"):
        _native._panic_for_tests(interruptible)
    # The interpreter and the module still work afterwards.
    from conftest import EXAMPLES

    assert dyncontact.contact(EXAMPLES / "hertz_sphere.toml").converged


def test_error_classes():
    assert issubclass(dyncontact.SolverError, RuntimeError)
    assert issubclass(dyncontact.InternalError, RuntimeError)
    assert dyncontact.SolverError.__module__ == "dyncontact"
