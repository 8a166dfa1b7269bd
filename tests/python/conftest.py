"""Fixtures of the Python package's tests. ctest runs them with OBSCURA_PLUGINPATH naming the built
plugin's folder, the package on PYTHONPATH and OBSCURA_VALIDATION=1: every delegate has the Vulkan
validation layer on, and a validation error or a logged error the test did not declare fails it."""

from __future__ import annotations

import gc
import os
import weakref

import pytest

import obscura


def environment(name: str) -> str:
    """A folder or tool the build passes to the tests (see tests/CMakeLists.txt)."""
    value = os.environ.get(name)
    if not value:
        pytest.fail(f"{name} is not set: run the tests through ctest (the python_package test)")
    return value


@pytest.fixture(scope="session")
def renderer() -> obscura.Renderer:
    with obscura.Renderer() as r:
        yield r


@pytest.fixture
def declared_errors() -> list[str]:
    """Substrings of the plugin's logged errors a test provokes; any other logged error fails it, and
    so does a declared one that never came."""
    return []


@pytest.fixture
def delegate(renderer: obscura.Renderer, declared_errors: list[str]) -> obscura.Delegate:
    assert os.environ.get("OBSCURA_VALIDATION") == "1", "the suite runs with the validation layer on"
    d = renderer.delegate()
    yield d
    assert_clean(d, declared_errors)


def assert_clean(d: obscura.Delegate, declared_errors: list[str] = ()) -> None:
    """Closes `d` and checks its log once the plugin destroyed it (what destruction logs counts too):
    no logged error beyond the declared ones (validation errors are logged errors), and each declared
    one came."""
    native = weakref.ref(d._native) if d._native else None
    if native:
        assert d.stats.validation_errors == 0, d.logged_errors
    d.close()
    gc.collect()  # a numpy view of a buffer still alive would defer the destruction
    assert native is None or native() is None, "a view of one of its buffers outlived the test"
    undeclared = [e for e in d.logged_errors if not any(s in e for s in declared_errors)]
    assert not undeclared, undeclared
    never_came = [s for s in declared_errors if not any(s in e for e in d.logged_errors)]
    assert not never_came, (never_came, d.logged_errors)
