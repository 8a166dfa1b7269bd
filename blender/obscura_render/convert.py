"""Blender's units and conventions to UsdLux / UsdGeom's, as Obscura's schemas read them.

Pure arithmetic on plain numbers (no bpy), so that the tests can check each formula by itself.
Blender's scene unit is the metre (times ``unit_settings.scale_length``); the add-on sets the
render setting ``metersPerUnit`` to that, so lengths pass through unchanged and only the camera's
film-back quantities (USD's "tenths of a scene unit") and the lights' intensities are converted.
"""

from __future__ import annotations

import math
from typing import Sequence

#: The camera prim the add-on renders through.
CAMERA_PATH = "/Camera"


def usd_matrix(matrix) -> list[float]:
    """A Blender ``Matrix`` (column vectors: v' = M v) as GfMatrix4d's 16 numbers (row vectors:
    v' = v M, translation in the last row): the transpose."""
    return [float(matrix[col][row]) for row in range(4) for col in range(4)]


# --- cameras ------------------------------------------------------------------------------------

def tenth_unit_in_mm(meters_per_unit: float) -> float:
    """Millimetres in a tenth of a scene unit: USD gives focal length and apertures in tenths of a
    scene unit (UsdGeomCamera, "Linear Algebra and Units"). Blender's USD exporter writes
    ``lens / tenth_unit_to_mm`` with ``tenth_unit_to_mm = 100 * meters_per_unit * scale_length``
    (source/blender/io/usd/intern/usd_writer_camera.cc); here meters_per_unit already holds the scale."""
    return 100.0 * meters_per_unit


def film_apertures(sensor_fit: str, sensor_width: float, sensor_height: float,
                   width: int, height: int) -> tuple[float, float, float]:
    """(horizontal, vertical, fitted) film size in mm for an image of width x height pixels, as
    Blender fits its sensor (BKE_camera_sensor_size / BKE_camera_sensor_fit): AUTO applies
    sensor_width to the larger image side, HORIZONTAL to the width, VERTICAL sensor_height to the
    height. ``fitted`` is the side the sensor size applies to: Blender's shift is in units of it."""
    aspect = width / height
    if sensor_fit == "VERTICAL":
        return sensor_height * aspect, sensor_height, sensor_height
    if sensor_fit == "HORIZONTAL" or width >= height:
        return sensor_width, sensor_width / aspect, sensor_width
    return sensor_width * aspect, sensor_width, sensor_width


def camera_values(*, kind: str, lens: float, ortho_scale: float, sensor_fit: str, sensor_width: float,
                  sensor_height: float, shift_x: float, shift_y: float, clip_start: float, clip_end: float,
                  width: int, height: int, meters_per_unit: float, fstop: float | None = None,
                  focus_distance: float = 0.0, blades: int = 0, rotation: float = 0.0) -> dict:
    """A camera prim's values (docs/schemas.md#camera). ``kind`` is Camera.type; ``fstop`` None
    means depth of field off; ``rotation`` in radians (Camera.dof.aperture_rotation)."""
    tenth = tenth_unit_in_mm(meters_per_unit)
    if kind == "ORTHO":
        # ortho_scale is the fitted side's extent in scene units; an orthographic camera's apertures
        # are read as tenths of a scene unit (docs/schemas.md#camera, projection).
        h, v, fitted = film_apertures(sensor_fit, ortho_scale, ortho_scale, width, height)
        h_ap, v_ap, fit_ap = h * 10.0, v * 10.0, fitted * 10.0
    else:
        h, v, fitted = film_apertures(sensor_fit, sensor_width, sensor_height, width, height)
        h_ap, v_ap, fit_ap = h / tenth, v / tenth, fitted / tenth
    values = {
        "projection": "orthographic" if kind == "ORTHO" else "perspective",
        "focalLength": lens / tenth,
        "horizontalAperture": h_ap,
        "verticalAperture": v_ap,
        # Blender shifts in units of the fitted side (both axes), USD offsets in aperture units.
        "horizontalApertureOffset": shift_x * fit_ap,
        "verticalApertureOffset": shift_y * fit_ap,
        "clippingRange": (clip_start, clip_end),
    }
    if fstop is not None and kind != "ORTHO":
        values.update({"fStop": fstop, "focusDistance": focus_distance, "obscura:apertureBlades": int(blades),
                       "obscura:apertureRotation": math.degrees(rotation)})
    return values


def focus_distance_to(camera_matrix, point: Sequence[float]) -> float:
    """Distance from the camera to the plane through ``point`` facing it, along the view axis
    (-Z of the camera), as Blender measures a focus object (BKE_camera_object_dof_distance)."""
    eye = [camera_matrix[i][3] for i in range(3)]
    forward = [-camera_matrix[i][2] for i in range(3)]
    norm = math.sqrt(sum(f * f for f in forward))
    return max(sum((p - e) * f for p, e, f in zip(point, eye, forward)) / norm, 0.0)


def camera_from_projection(window_matrix, meters_per_unit: float) -> dict:
    """A camera prim's film values from a viewport's projection matrix (RegionView3D.window_matrix,
    OpenGL clip space): the film is fitted so that the same frustum results."""
    p = [[float(window_matrix[r][c]) for c in range(4)] for r in range(4)]
    if p[3][3] == 1.0:  # orthographic: x_ndc = p00 x + p03
        width, height = 2.0 / p[0][0], 2.0 / p[1][1]
        near = (p[2][3] + 1.0) / p[2][2]
        far = (p[2][3] - 1.0) / p[2][2]
        return {"projection": "orthographic", "horizontalAperture": width * 10.0, "verticalAperture": height * 10.0,
                "horizontalApertureOffset": -p[0][3] / p[0][0] * 10.0,
                "verticalApertureOffset": -p[1][3] / p[1][1] * 10.0, "clippingRange": (near, far)}
    # x_ndc = (p00 x + p02 z) / -z: the film of focal length f has width 2 f / p00, offset p02 w / 2.
    focal = 50.0 / tenth_unit_in_mm(meters_per_unit)
    h, v = 2.0 * focal / p[0][0], 2.0 * focal / p[1][1]
    near = p[2][3] / (p[2][2] - 1.0)
    far = p[2][3] / (p[2][2] + 1.0)
    return {"projection": "perspective", "focalLength": focal, "horizontalAperture": h, "verticalAperture": v,
            "horizontalApertureOffset": p[0][2] * h / 2.0, "verticalApertureOffset": p[1][2] * v / 2.0,
            "clippingRange": (near, far)}


def linear_depth(clip_depth, near: float, far: float, orthographic: bool = False):
    """Distance along the view axis from the depth AOV's clip-space depth in [0, 1] (works on numpy
    arrays); the inverse of the projection's z row, as the harness writes the EXR's Z
    (harness/aov_output.cpp). 1 (nothing drawn) becomes +inf, Blender's empty Depth."""
    import numpy as np

    d = np.asarray(clip_depth, dtype=np.float64)
    if orthographic:
        z = near + d * (far - near)
    else:
        a, b = far / (near - far), near * far / (near - far)
        with np.errstate(divide="ignore"):
            z = b / (d + a)
    return np.where(d >= 1.0, np.inf, z).astype(np.float32)


# --- lights -------------------------------------------------------------------------------------
# Blender's USD exporter (source/blender/io/usd/intern/usd_writer_light.cc, Blender 3.x and 4.x
# without "convert to nits"), writing every light with inputs:normalize = true:
#     sun:         intensity = energy / 4      ("Unclear why, but approximately matches Karma.")
#     other types: intensity = energy / pi     ("Convert from radiant flux to intensity.")
# With normalize, a UsdLux distant light's intensity is the illuminance it delivers, so a sun of
# Strength S lights a surface facing it with S / 4 (Cycles: S). For point, spot and area lights
# the normalised luminance is intensity / area: a sphere of radius r then emits
# pi * (intensity / (4 pi r^2)) * 4 pi r^2 = pi * intensity = energy watts, and an area light
# pi * intensity from its front face: Blender's power, whatever the size.

def light_intensity(light_type: str, energy: float) -> float:
    """inputs:intensity for a Blender light of ``energy`` (Light.energy: W, or W/m^2 for a sun)."""
    return energy / 4.0 if light_type == "SUN" else energy / math.pi


def light_values(*, light_type: str, energy: float, color: Sequence[float], specular: float, diffuse: float = 1.0,
                 use_shadow: bool = True, angle: float = 0.0, radius: float = 0.0, spot_size: float = 0.0,
                 spot_blend: float = 0.0, shape: str = "SQUARE", size: float = 0.0,
                 size_y: float = 0.0) -> tuple[str, dict]:
    """(prim type, values) of the light (docs/schemas.md): the exporter's mapping of types and
    sizes. Angles are Blender's radians; sizes in scene units."""
    values = {"inputs:intensity": light_intensity(light_type, energy), "inputs:normalize": True,
              "inputs:color": tuple(float(c) for c in color[:3]), "inputs:specular": float(specular),
              "inputs:diffuse": float(diffuse), "inputs:shadow:enable": bool(use_shadow)}
    if light_type == "SUN":
        # UsdLux's angle is the disc's angular diameter (0.53 is the sun), as Light.angle.
        values["inputs:angle"] = math.degrees(angle)
        return "distantLight", values
    if light_type in ("POINT", "SPOT"):
        values["inputs:radius"] = float(radius)
        values["treatAsPoint"] = radius == 0.0
        if light_type == "SPOT":
            # spot_size is the cone's full angle; the cone angle is measured off the axis.
            values["inputs:shaping:cone:angle"] = math.degrees(spot_size) / 2.0
            values["inputs:shaping:cone:softness"] = float(spot_blend)
        return "sphereLight", values
    if shape in ("DISK", "ELLIPSE"):
        # An ellipse becomes a disk of the mean diameter (the exporter: "An ellipse light will
        # deteriorate into a disk light"); Blender's size is the diameter.
        diameter = size if shape == "DISK" else (size + size_y) / 2.0
        values["inputs:radius"] = diameter / 2.0
        return "diskLight", values
    values["inputs:width"] = float(size)
    values["inputs:height"] = float(size_y if shape == "RECTANGLE" else size)
    return "rectLight", values
