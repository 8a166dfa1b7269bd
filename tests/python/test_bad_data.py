"""Bad data from Python: what numpy cannot turn into an ABI value raises at once, naming the prim
and the attribute; what the delegate's schema check refuses (NaN, indices out of range, a wrong
type or shape) skips that prim with a message naming it, and the rest of the scene renders."""

from __future__ import annotations

import math

import numpy as np
import pytest

import obscura
from lit_plane import ALBEDO, add_lit_plane, add_quad, add_sun, radiance_tolerance

# Small quads in front of the plane, over the image centre: drawn, they would hide the plane there.
SKIPPED = {
    "/Bad/NaNPoints": {"points": np.array([[-1, -1, 1], [1, -1, 1], [1, 1, 1], [np.nan, 1, 1]], np.float32)},
    "/Bad/IndexOutOfRange": {"faceVertexIndices": [0, 1, 2, 7]},
    "/Bad/FloatIndices": {"faceVertexIndices": np.array([0.0, 1.0, 2.0, 3.0])},  # wrong dtype
    "/Bad/Points2D": {"points": np.zeros((4, 2), np.float32)},  # wrong shape: float2[] for float3[]
}


def test_bad_values_skip_their_prim_and_the_rest_renders(delegate: obscura.Delegate,
                                                          declared_errors: list[str]) -> None:
    add_lit_plane(delegate)
    delegate.insert_prim("renderBuffer", "/Buffers/id", dimensions=(64, 64), format="int32")
    add_sun(delegate, 3.0, (0.0, 0.0, -1.0))
    for path, bad in SKIPPED.items():
        add_quad(delegate, path, half=1.0, z=1.0, **bad)
        declared_errors.append(path)
    aovs = {"color": "/Buffers/color", "primId": "/Buffers/id"}

    with pytest.raises(obscura.BadPrimDataError) as caught:
        delegate.render("/Camera", aovs)
    assert caught.value.status == obscura.Status.BAD_PRIM_DATA
    assert "/Bad/" in caught.value.message  # lastError names the first skipped prim
    assert delegate.stats.prims_skipped == len(SKIPPED)
    for path in SKIPPED:
        assert any(path in e for e in delegate.logged_errors), (path, delegate.logged_errors)
    messages = " ".join(delegate.logged_errors)
    assert "NaN" in messages and "expected float3[], got float2[]" in messages and "expected int[]" in messages

    ids = delegate.read("/Buffers/id")
    assert ids[32, 32] == delegate.prim_id("/Plane")  # the centre shows the plane, not a skipped quad
    color = delegate.read("/Buffers/color")
    expected = ALBEDO / math.pi * 3.0
    assert color[32, 32, 0] == pytest.approx(expected, abs=radiance_tolerance(expected, 0))

    # Without check the same render reports the status instead of raising; fixed data brings a prim back.
    assert delegate.render("/Camera", aovs, check=False) == obscura.Status.BAD_PRIM_DATA
    delegate.set("/Bad/IndexOutOfRange", "faceVertexIndices", [0, 1, 2, 3])
    delegate.render("/Camera", aovs, check=False)
    assert delegate.stats.prims_skipped == len(SKIPPED) - 1
    assert delegate.read("/Buffers/id")[32, 32] == delegate.prim_id("/Bad/IndexOutOfRange")


@pytest.mark.parametrize("attribute, value, message", [
    ("points", np.zeros((4, 5), np.float32), r"shape \(4, 5\) is not"),
    ("points", np.zeros((2, 2, 3), np.float32), r"shape \(2, 2, 3\) is not"),
    ("points", np.zeros((4, 3), np.complex64), "dtype complex64 is not a number type"),
    ("points", [[0, 0, 0], [1, 0]], "not an array of numbers"),
    ("faceVertexIndices", np.array([0, 1, 2, 2**40]), "outside the int32 range"),
    ("normals", object(), "cannot pass a value of type object"),
    ("doubleSided", (1, "yes"), "holds numbers only"),
])
def test_values_numpy_cannot_convert_raise_naming_prim_and_attribute(delegate: obscura.Delegate, attribute: str,
                                                                      value: object, message: str) -> None:
    with pytest.raises(obscura.InvalidArgumentError, match=f"/Bad: {attribute}: .*{message}") as caught:
        add_quad(delegate, "/Bad", half=1.0, **{attribute: value})
    assert caught.value.status == obscura.Status.INVALID_ARGUMENT
    add_quad(delegate, "/Bad", half=1.0)  # nothing was inserted: the path is still free


def test_plugin_refusals_raise_with_status_and_message(delegate: obscura.Delegate) -> None:
    with pytest.raises(obscura.UnknownTypeError) as caught:
        delegate.insert_prim("teapot", "/Teapot")
    assert caught.value.status == obscura.Status.UNKNOWN_TYPE and "teapot" in caught.value.message
    delegate.insert_prim("camera", "/Camera", focalLength=35.0)
    with pytest.raises(obscura.AlreadyExistsError, match="/Camera"):
        delegate.insert_prim("camera", "/Camera", focalLength=85.0)
    assert delegate.scene.get_value("/Camera", "focalLength", 0.0).array == 35.0  # the first one's, kept
    with pytest.raises(obscura.NotFoundError, match="/Nowhere"):
        delegate.render("/Nowhere", {})
    with pytest.raises(obscura.InvalidStateError, match="has not been rendered"):
        delegate.insert_prim("renderBuffer", "/B", dimensions=(8, 8), format="float32")
        delegate.map("/B")
