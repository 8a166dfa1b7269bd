"""The delegate tests' lit plane (tests/delegate/render_fixture.cpp), built from Python: a grey
Lambert plane at z = 0 facing +Z, seen by a camera at (0, 0, 5) looking down -Z."""

from __future__ import annotations

import numpy as np

import obscura

WIDTH = HEIGHT = 64
CAMERA_DISTANCE = 5.0
FOCAL_LENGTH, APERTURE = 50.0, 20.955  # tenths of a scene unit (mm at the default cm stage)
TAN_HALF_FOV = (APERTURE / 2.0) / FOCAL_LENGTH


def srgb8_exact(code: int) -> float:
    """A linear value that 8-bit sRGB storage (the albedo G-buffer target) holds exactly (IEC 61966-2-1)."""
    c = code / 255.0
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


ALBEDO = float(np.float32(srgb8_exact(188)))


def translation(x: float, y: float, z: float) -> np.ndarray:
    m = np.identity(4)
    m[3, :3] = (x, y, z)  # GfMatrix4d: row vectors, translation in the last row
    return m


def light_pointing_along(direction) -> np.ndarray:
    """Rotation taking a light's local -Z axis (its emission direction) onto ``direction``; the
    rows are the images of the local axes (row vectors)."""
    d = np.asarray(direction, dtype=float)
    z = -d / np.linalg.norm(d)
    up = np.array([0.0, 1.0, 0.0]) if abs(z[1]) < 0.9 else np.array([1.0, 0.0, 0.0])
    x = np.cross(up, z)
    x /= np.linalg.norm(x)
    y = np.cross(z, x)
    m = np.identity(4)
    m[0, :3], m[1, :3], m[2, :3] = x, y, z
    return m


def add_lit_plane(d: obscura.Delegate, buffer_format: str = "float32Vec4", buffer: str = "/Buffers/color",
                  size: int = WIDTH) -> None:
    d.insert_prim("camera", "/Camera", focalLength=FOCAL_LENGTH, horizontalAperture=APERTURE,
                  verticalAperture=APERTURE, clippingRange=(0.1, 1000.0),
                  transform=translation(0, 0, CAMERA_DISTANCE))
    d.insert_prim("material", "/Looks/Grey", {
        "inputs:diffuseColor": (ALBEDO, ALBEDO, ALBEDO),
        "inputs:roughness": 1.0,
        "inputs:metallic": 0.0,
        "inputs:emissiveColor": (0.0, 0.0, 0.0),
    })
    add_quad(d, "/Plane", half=10.0)
    d.insert_prim("renderBuffer", buffer, dimensions=(size, size), format=buffer_format)


def add_quad(d: obscura.Delegate, path: str, half: float, z: float = 0.0, **attributes) -> None:
    """A quad facing +Z with the grey material; ``attributes`` override its values."""
    values = {
        "points": np.array([[-half, -half, z], [half, -half, z], [half, half, z], [-half, half, z]],
                           dtype=np.float32),
        "faceVertexCounts": [4],
        "faceVertexIndices": [0, 1, 2, 3],
        "subdivisionScheme": "none",
        "material:binding": obscura.Path("/Looks/Grey"),
    }
    values.update(attributes)
    d.insert_prim("mesh", path, values)


def add_sun(d: obscura.Delegate, irradiance: float, direction) -> None:
    """A normalized distant light: its intensity is the illuminance on a surface facing it (UsdLux)."""
    d.insert_prim("distantLight", "/Sun", {
        "inputs:intensity": irradiance,
        "inputs:normalize": True,
        "inputs:specular": 0.0,
    }, transform=light_pointing_along(direction))


def plane_point_at_pixel(x: int, y: int) -> np.ndarray:
    """The point of the z = 0 plane seen through the centre of pixel (x, y) (row 0 at the top)."""
    ndc_x = (x + 0.5) / WIDTH * 2.0 - 1.0
    ndc_y = 1.0 - (y + 0.5) / HEIGHT * 2.0
    return np.array([ndc_x * TAN_HALF_FOV * CAMERA_DISTANCE, ndc_y * TAN_HALF_FOV * CAMERA_DISTANCE, 0.0])


def small_float_step(value: float, mantissa_bits: int) -> float:
    """One step of an unsigned small float (B10G11R11: 6 mantissa bits for R and G, 5 for B) at ``value``."""
    if value <= 0.0:
        return 0.0
    _, exponent = np.frexp(value)  # value = m * 2^exponent, m in [0.5, 1)
    return float(np.ldexp(1.0, int(exponent) - 1 - mantissa_bits))


# The light buffer is B10G11R11_UFLOAT: R and G keep 6 mantissa bits, B 5.
MANTISSA_BITS = (6, 6, 5)


def radiance_tolerance(expected: float, channel: int) -> float:
    """As the delegate tests' expectRadiance: one step of the light buffer's format at the value
    (conversion may round or truncate; Vulkan allows both) plus 1% for the rest of the pipeline
    (the normal's 24-bit best-fit encoding, float arithmetic)."""
    return 0.01 * expected + small_float_step(expected, MANTISSA_BITS[channel])
