"""Writing render buffers to OpenEXR files, with numpy alone.

Debian ships no Python binding of OpenEXR, so this writes the simplest file the format defines:
single-part scanline, uncompressed, 32-bit float channels (OpenEXR, "OpenEXR File Layout":
magic number and version, a header of attributes, a line offset table, then one chunk per
scanline holding each channel's row in channel-name order). Every OpenEXR reader opens it.
"""

from __future__ import annotations

import os
import struct
from typing import Mapping

import numpy as np

_MAGIC = 20000630
_VERSION = 2  # single-part scanline, names up to 31 bytes
_FLOAT = 2  # pixel type FLOAT
_NO_COMPRESSION = 0
_INCREASING_Y = 0


def _attribute(name: str, type_name: str, value: bytes) -> bytes:
    return name.encode() + b"\0" + type_name.encode() + b"\0" + struct.pack("<i", len(value)) + value


def write_exr(path: str | os.PathLike, channels: Mapping[str, np.ndarray]) -> None:
    """Writes ``channels`` (name -> (height, width) array, rows from the top) as float channels.

    Names follow OpenEXR's conventions: ``R``, ``G``, ``B``, ``A`` for colour, ``Z`` for depth,
    ``layer.X`` for a layer's channels (``normal.X``).
    """
    if not channels:
        raise ValueError("an EXR file needs at least one channel")
    names = sorted(channels)  # the format stores channels in name order
    planes = [np.ascontiguousarray(channels[n], dtype="<f4") for n in names]
    height, width = planes[0].shape
    for name, plane in zip(names, planes):
        if plane.shape != (height, width):
            raise ValueError(f"channel {name} is {plane.shape}, the others ({height}, {width})")
        if len(name.encode()) > 31:
            raise ValueError(f"channel name {name!r} is longer than 31 bytes")
    chlist = b"".join(n.encode() + b"\0" + struct.pack("<iB3xii", _FLOAT, 0, 1, 1) for n in names) + b"\0"
    window = struct.pack("<iiii", 0, 0, width - 1, height - 1)
    header = b"".join([
        struct.pack("<ii", _MAGIC, _VERSION),
        _attribute("channels", "chlist", chlist),
        _attribute("compression", "compression", bytes([_NO_COMPRESSION])),
        _attribute("dataWindow", "box2i", window),
        _attribute("displayWindow", "box2i", window),
        _attribute("lineOrder", "lineOrder", bytes([_INCREASING_Y])),
        _attribute("pixelAspectRatio", "float", struct.pack("<f", 1.0)),
        _attribute("screenWindowCenter", "v2f", struct.pack("<ff", 0.0, 0.0)),
        _attribute("screenWindowWidth", "float", struct.pack("<f", 1.0)),
        b"\0",
    ])
    row_bytes = len(names) * width * 4
    chunk_bytes = 8 + row_bytes  # y, data size, data
    first_chunk = len(header) + 8 * height
    offsets = np.arange(height, dtype="<u8") * chunk_bytes + first_chunk
    # One chunk per scanline: (y, size) then the channels' rows side by side.
    rows = np.stack(planes, axis=1).reshape(height, row_bytes // 4)
    chunks = np.empty((height, chunk_bytes // 4), dtype="<i4")
    chunks[:, 0] = np.arange(height)
    chunks[:, 1] = row_bytes
    chunks[:, 2:] = rows.view("<i4")
    with open(path, "wb") as f:
        f.write(header)
        f.write(offsets.tobytes())
        f.write(chunks.tobytes())


def write_color_exr(path: str | os.PathLike, rgba: np.ndarray) -> None:
    """Writes a colour AOV ((height, width, 4) linear RGBA) as the R, G, B, A channels."""
    write_exr(path, {c: rgba[..., i] for i, c in enumerate("RGBA")})
