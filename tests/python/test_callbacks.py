"""A scene delegate of Python callbacks: values served from code, and a callback that raises makes
that prim's error (logged, named, skipped), never a crash; the rest of the scene renders."""

from __future__ import annotations

import numpy as np
import pytest

import obscura
from lit_plane import add_lit_plane, add_quad

AOVS = {"primId": "/Buffers/id"}


class Served(obscura.SceneDelegate):
    """Serves an in-memory scene, except where a test makes it raise."""

    def __init__(self) -> None:
        self.scene = obscura.Scene()
        self.fail_value: tuple[str, str] | None = None
        self.served_as_is: dict[tuple[str, str], object] = {}  # raw values, not converted beforehand
        self.fail_transform: str | None = None
        self.calls = 0

    def get_value(self, path, attribute, time):
        self.calls += 1
        if (path, attribute) == self.fail_value:
            raise ZeroDivisionError(f"no {attribute} today")
        if (path, attribute) in self.served_as_is:
            return self.served_as_is[path, attribute]
        return self.scene.get_value(path, attribute, time)

    def sample_transform(self, path, time0, time1, max_samples):
        if path == self.fail_transform:
            raise RuntimeError("transform server down")
        return self.scene.sample_transform(path, time0, time1, max_samples)


@pytest.fixture
def served(renderer: obscura.Renderer, declared_errors: list[str]):
    from conftest import assert_clean

    scene = Served()
    with renderer.delegate(scene) as d:
        # The same prims as the in-memory scene's helpers make, inserted into `scene` by hand.
        helper = renderer.delegate()
        add_lit_plane(helper)
        helper.insert_prim("renderBuffer", "/Buffers/id", dimensions=(64, 64), format="int32")
        add_quad(helper, "/Front", half=0.4, z=1.0)  # over the middle half of the image
        for path, prim in helper.scene.prims.items():
            scene.scene.prims[path] = prim
            d.insert_prim(prim.type, path)
        helper.close()
        yield d, scene
        assert_clean(d, declared_errors)


def test_values_come_from_the_callbacks(served) -> None:
    d, scene = served
    d.render("/Camera", AOVS)
    assert scene.calls > 0
    ids = d.read("/Buffers/id")
    assert ids[32, 32] == d.prim_id("/Front") and ids[2, 2] == d.prim_id("/Plane")
    scene.calls = 0
    d.render("/Camera", AOVS)
    assert scene.calls == 0  # nothing dirty, nothing pulled


@pytest.mark.parametrize("fail", ["value", "transform"])
def test_a_callback_that_raises_skips_its_prim(served, declared_errors: list[str], caplog, fail: str) -> None:
    d, scene = served
    if fail == "value":
        scene.fail_value, expected = ("/Front", "points"), ZeroDivisionError
    else:
        scene.fail_transform, expected = "/Front", RuntimeError
    declared_errors.append("/Front")
    with pytest.raises(obscura.BadPrimDataError) as caught:
        d.render("/Camera", AOVS)
    [(path, what, error)] = caught.value.callback_errors
    assert path == "/Front" and isinstance(error, expected) and caught.value.__cause__ is error
    assert what == ("get_value('points')" if fail == "value" else "sample_transform")
    assert expected.__name__ in caught.value.message and "/Front" in caught.value.message
    assert any("/Front" in r.getMessage() and r.exc_info for r in caplog.records if r.name == "obscura")
    assert d.callback_errors == caught.value.callback_errors
    assert d.read("/Buffers/id")[32, 32] == d.prim_id("/Plane")  # the rest rendered

    scene.fail_value = scene.fail_transform = None  # fixed: marked dirty, the prim comes back
    d.mark_dirty("/Front")
    d.render("/Camera", AOVS)
    assert d.read("/Buffers/id")[32, 32] == d.prim_id("/Front")


def test_a_camera_callback_that_raises_fails_the_render_cleanly(served, declared_errors: list[str]) -> None:
    d, scene = served
    scene.fail_value = ("/Camera", "focalLength")
    declared_errors.append("/Camera")
    with pytest.raises(obscura.BadPrimDataError, match="camera /Camera"):
        d.render("/Camera", AOVS)


def test_a_callback_cannot_call_back_into_the_rendering_delegate(served, declared_errors: list[str]) -> None:
    d, scene = served

    served_value = scene.get_value

    def reentrant(path, attribute, time):
        if path == "/Front":
            d.insert_prim("mesh", "/Sneaky")
        return served_value(path, attribute, time)

    scene.get_value = reentrant
    d.mark_dirty("/Front")
    declared_errors.append("/Front")
    with pytest.raises(obscura.BadPrimDataError) as caught:
        d.render("/Camera", AOVS)
    [(path, _, error)] = caught.value.callback_errors
    assert path == "/Front" and isinstance(error, obscura.InvalidStateError)


def test_wrong_values_from_a_callback_are_the_prims_error(served, declared_errors: list[str]) -> None:
    d, scene = served
    scene.served_as_is["/Front", "points"] = np.zeros((4, 7), np.float32)  # no ABI value has 7 components
    d.mark_dirty("/Front", obscura.Dirty.POINTS)
    declared_errors.append("/Front")
    with pytest.raises(obscura.BadPrimDataError, match=r"shape \(4, 7\)"):
        d.render("/Camera", AOVS)
