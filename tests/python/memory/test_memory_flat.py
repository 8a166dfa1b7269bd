"""Many create/destroy cycles of a delegate leave memory flat.

What a leak would cost is measured here, not assumed: one live delegate after a render (its Vulkan
device, pipelines and buffers on lavapipe: 77 MB measured with validation) and its Python side (the
scene, the converted arrays, the callbacks). 20 cycles must grow resident memory by less than half
of one live delegate, and the Python heap by less than one delegate's Python side: leaking any
single delegate, native or Python, fails the test.

Resident memory is read after malloc_trim(0): glibc keeps freed blocks in its arenas (about 50 MB
after a few cycles here), which is reuse, not a leak. Each cycle renders once, at 16x16:
lavapipe keeps ~1.2 MB per frame while render buffers are bound, released only when the delegate
is destroyed (TOOLCHAIN.md, "Memory over many frames").
XXX: what remains is ~0.2 MB of resident memory and ~23 KB of malloc'd blocks per cycle, below the
package (the Python heap stays flat); lavapipe's per-device JIT or the plugin, not bisected yet.
"""

from __future__ import annotations

import ctypes
import gc
import os
import tracemalloc

import obscura
from lit_plane import add_lit_plane, add_sun

CYCLES = 20
_PAGE = os.sysconf("SC_PAGE_SIZE")
_libc = ctypes.CDLL("libc.so.6")


def resident_bytes() -> int:
    gc.collect()
    _libc.malloc_trim(0)
    # A sanitized plugin runs with AddressSanitizer preloaded: drain its quarantine of freed memory
    # first, so that what is measured is what is still allocated.
    purge = getattr(ctypes.CDLL(None), "__sanitizer_purge_allocator", None)
    if purge is not None:
        purge()
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * _PAGE


def rendered_delegate(renderer: obscura.Renderer) -> obscura.Delegate:
    d = renderer.delegate()
    add_lit_plane(d, size=16)
    add_sun(d, 1.0, (0.0, 0.0, -1.0))
    d.render("/Camera", {"color": "/Buffers/color"})
    d.read("/Buffers/color")
    return d


def test_create_destroy_cycles_leave_memory_flat(renderer: obscura.Renderer) -> None:
    for _ in range(3):  # warm-up: the plugin's and the driver's one-time allocations
        rendered_delegate(renderer).close()

    before = resident_bytes()
    tracemalloc.start()
    live = rendered_delegate(renderer)
    live_python = tracemalloc.get_traced_memory()[0]
    live_native = resident_bytes() - before
    live.close()
    del live
    tracemalloc.stop()

    before = resident_bytes()
    tracemalloc.start()
    for _ in range(CYCLES):
        d = rendered_delegate(renderer)
        assert d.stats.validation_errors == 0 and not d.logged_errors, d.logged_errors
        d.close()
    del d
    gc.collect()
    python_growth = tracemalloc.get_traced_memory()[0]
    tracemalloc.stop()
    growth = resident_bytes() - before

    mb = 2.0 ** 20
    print(f"one live delegate: {live_native / mb:.1f} MB resident, {live_python / 1024:.1f} KB Python heap; "
          f"{CYCLES} cycles: {growth / mb:.1f} MB resident, {python_growth / 1024:.1f} KB Python heap")
    assert live_native > 0 and live_python > 0
    assert growth < live_native / 2
    assert python_growth < live_python
