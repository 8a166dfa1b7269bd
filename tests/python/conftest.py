"""Fixtures of the Python package's tests. ctest runs them with OBSCURA_PLUGINPATH naming the built
plugin's folder, the package on PYTHONPATH and OBSCURA_VALIDATION=1: every delegate has the Vulkan
validation layer on, and a validation error or a logged error the test did not declare fails it."""

from __future__ import annotations

import os

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
    """Substrings of the plugin's logged errors a test expects; any other logged error fails it."""
    return []


@pytest.fixture
def delegate(renderer: obscura.Renderer, declared_errors: list[str]) -> obscura.Delegate:
    assert os.environ.get("OBSCURA_VALIDATION") == "1", "the suite runs with the validation layer on"
    with renderer.delegate() as d:
        yield d
        assert_clean(d, declared_errors)


def assert_clean(d: obscura.Delegate, declared_errors: list[str] = ()) -> None:
    """No validation error and no logged error beyond the declared ones."""
    assert d.stats.validation_errors == 0, d.logged_errors
    undeclared = [e for e in d.logged_errors if not any(s in e for s in declared_errors)]
    assert not undeclared, undeclared
