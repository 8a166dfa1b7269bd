"""Lifetimes: a closed delegate raises on every use, never crashes; mapped buffers are numpy views
without a copy that can never outlive their memory."""

from __future__ import annotations

import gc
import weakref

import numpy as np
import pytest

import obscura
from lit_plane import add_lit_plane, add_sun

AOVS = {"color": "/Buffers/color"}


def lit(renderer: obscura.Renderer) -> obscura.Delegate:
    d = renderer.delegate()
    add_lit_plane(d, size=16)
    add_sun(d, 1.0, (0.0, 0.0, -1.0))
    d.render("/Camera", AOVS)
    return d


CALLS = {
    "insert_prim": lambda d: d.insert_prim("camera", "/Other"),
    "remove_prim": lambda d: d.remove_prim("/Camera"),
    "mark_dirty": lambda d: d.mark_dirty("/Camera"),
    "set": lambda d: d.set("/Camera", "focalLength", 35.0),
    "set_transform": lambda d: d.set_transform("/Camera", np.identity(4)),
    "set_render_settings": lambda d: d.set_render_settings(exposure=1.0),
    "render": lambda d: d.render("/Camera", AOVS),
    "render_until_converged": lambda d: d.render_until_converged("/Camera", AOVS),
    "map": lambda d: d.map("/Buffers/color"),
    "read": lambda d: d.read("/Buffers/color"),
    "prim_id": lambda d: d.prim_id("/Plane"),
    "stats": lambda d: d.stats,
    "converged": lambda d: d.converged,
    "pass_timings": lambda d: d.pass_timings,
}


@pytest.fixture(scope="module")
def closed(renderer: obscura.Renderer) -> obscura.Delegate:
    with lit(renderer) as d:
        pass
    assert not d.logged_errors, d.logged_errors
    return d


@pytest.mark.parametrize("call", CALLS)
def test_a_closed_delegate_raises(closed: obscura.Delegate, call: str) -> None:
    assert closed.closed
    with pytest.raises(obscura.InvalidStateError, match="closed") as caught:
        CALLS[call](closed)
    assert caught.value.status == obscura.Status.INVALID_STATE
    closed.close()  # closing again is harmless


def test_closing_the_renderer_closes_its_delegates(renderer: obscura.Renderer) -> None:
    r = obscura.Renderer()
    d = lit(r)
    with r:
        pass
    assert d.closed
    assert not d.logged_errors, d.logged_errors
    with pytest.raises(obscura.InvalidStateError):
        r.delegate()


def test_a_view_is_zero_copy_and_keeps_its_memory_alive(renderer: obscura.Renderer) -> None:
    d = lit(renderer)
    expected = d.read("/Buffers/color")
    mapped = d.map("/Buffers/color")
    view = mapped.array[4:12, 4:12]
    assert not view.flags.owndata and not view.flags.writeable
    assert np.shares_memory(view, mapped.array)
    copy = mapped.copy()
    assert copy.flags.owndata and not np.shares_memory(copy, mapped.array)

    mapped.unmap()
    with pytest.raises(obscura.InvalidStateError, match="unmapped"):
        mapped.array
    # The view is alive, so the buffer stays mapped: a render now would reuse its memory.
    with pytest.raises(obscura.InvalidStateError, match="/Buffers/color still mapped"):
        d.render("/Camera", AOVS)

    # Closed with the view alive: the plugin's delegate lives on until the view goes.
    native = weakref.ref(d._native)
    d.close()
    gc.collect()
    assert native() is not None
    np.testing.assert_array_equal(view, expected[4:12, 4:12])
    del view
    gc.collect()
    assert native() is None  # destroyed with the last view
    assert not d.logged_errors, d.logged_errors


def test_a_buffer_is_unmapped_once_its_last_view_is_gone(delegate: obscura.Delegate) -> None:
    add_lit_plane(delegate, size=16)
    delegate.render("/Camera", AOVS)
    with delegate.map("/Buffers/color") as mapped:
        row = mapped.array[3]
    with pytest.raises(obscura.InvalidStateError, match="still mapped"):
        delegate.render("/Camera", AOVS)
    with pytest.raises(obscura.InvalidStateError, match="still mapped"):
        delegate.remove_prim("/Buffers/color")
    del row
    delegate.render("/Camera", AOVS)  # unmapped when the view went
    assert delegate.read("/Buffers/color").shape == (16, 16, 4)


@pytest.mark.parametrize("format, shape, dtype", [
    ("float32Vec4", (16, 16, 4), np.float32), ("float32", (16, 16), np.float32), ("int32", (16, 16), np.int32),
    ("unorm8Vec4", (16, 16, 4), np.uint8),
])
def test_mapped_arrays_take_the_buffers_format(delegate: obscura.Delegate, format, shape, dtype) -> None:
    aov = {"float32Vec4": "color", "float32": "depth", "int32": "primId", "unorm8Vec4": "display"}[format]
    add_lit_plane(delegate, buffer_format=format, buffer="/Buffers/aov", size=16)
    delegate.render("/Camera", {aov: "/Buffers/aov"})
    with delegate.map("/Buffers/aov") as mapped:
        assert (mapped.width, mapped.height) == (16, 16)
        assert mapped.array.shape == shape and mapped.array.dtype == dtype
