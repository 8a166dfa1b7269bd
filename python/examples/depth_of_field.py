#!/usr/bin/env python3
"""A scene built from numpy arrays, rendered with depth of field, written to an OpenEXR file.

Five spheres stand in a row receding from the camera on a ground plane; the lens (50 mm at f/1.4)
focuses on the middle one, so the near and far spheres blur. Units are USD's defaults:
centimetres, focal length and apertures in millimetres.

    OBSCURA_PLUGINPATH=build/lib/obscura/plugin python3 python/examples/depth_of_field.py dof.exr
"""

from __future__ import annotations

import argparse

import numpy as np

import obscura
from obscura.exr import write_color_exr


def sphere(radius: float, rings: int = 24, segments: int = 48) -> dict[str, np.ndarray]:
    """A UV sphere: points (N, 3) float32, quads as faceVertexCounts / faceVertexIndices."""
    theta = np.linspace(0.0, np.pi, rings + 1)[:, None]  # from the north pole down
    phi = np.linspace(0.0, 2.0 * np.pi, segments, endpoint=False)[None, :]
    points = np.stack([np.sin(theta) * np.cos(phi), np.cos(theta) * np.ones_like(phi),
                       -np.sin(theta) * np.sin(phi)], axis=-1).reshape(-1, 3) * radius
    ring, segment = np.meshgrid(np.arange(rings), np.arange(segments), indexing="ij")
    nxt = (segment + 1) % segments
    quads = np.stack([ring * segments + segment, (ring + 1) * segments + segment,
                      (ring + 1) * segments + nxt, ring * segments + nxt], axis=-1).reshape(-1, 4)
    return {"points": points.astype(np.float32), "faceVertexCounts": np.full(len(quads), 4, np.int32),
            "faceVertexIndices": quads.astype(np.int32).reshape(-1)}


def translation(x: float, y: float, z: float) -> np.ndarray:
    m = np.identity(4)
    m[3, :3] = (x, y, z)  # GfMatrix4d: row vectors, translation in the last row
    return m


def look_from(eye, target) -> np.ndarray:
    """A camera transform at ``eye`` looking at ``target`` (the camera looks down its local -Z)."""
    eye, target = np.asarray(eye, float), np.asarray(target, float)
    back = eye - target
    back /= np.linalg.norm(back)
    right = np.cross([0.0, 1.0, 0.0], back)
    right /= np.linalg.norm(right)
    up = np.cross(back, right)
    m = np.identity(4)
    m[0, :3], m[1, :3], m[2, :3], m[3, :3] = right, up, back, eye
    return m


def build_scene(d: obscura.Delegate, width: int, height: int) -> float:
    """Inserts the prims; returns the focus distance."""
    eye, target = (0.0, 25.0, 100.0), (0.0, 8.0, -10.0)
    focus = float(np.linalg.norm(np.subtract(eye, target)))
    d.insert_prim("camera", "/Camera", {
        "focalLength": 50.0, "horizontalAperture": 36.0, "verticalAperture": 36.0 * height / width,
        "fStop": 1.4, "focusDistance": focus, "clippingRange": (1.0, 10000.0),
        "obscura:apertureBlades": 6,
    }, transform=look_from(eye, target))

    colours = np.array([[0.8, 0.2, 0.1], [0.9, 0.6, 0.1], [0.2, 0.7, 0.3], [0.1, 0.4, 0.8], [0.6, 0.2, 0.8]])
    ball = sphere(8.0)
    for i, colour in enumerate(colours):
        d.insert_prim("material", f"/Looks/Ball{i}", {"inputs:diffuseColor": tuple(colour), "inputs:roughness": 0.4})
        d.insert_prim("mesh", f"/World/Ball{i}", ball, transform=translation(-16.0 + 8.0 * i, 8.0, 40.0 - 25.0 * i))
        d.set(f"/World/Ball{i}", "material:binding", obscura.Path(f"/Looks/Ball{i}"))
    d.insert_prim("material", "/Looks/Ground", {"inputs:diffuseColor": (0.5, 0.5, 0.5), "inputs:roughness": 0.9})
    half = 400.0
    d.insert_prim("mesh", "/World/Ground", {
        "points": np.array([[-half, 0, half], [half, 0, half], [half, 0, -half], [-half, 0, -half]], np.float32),
        "faceVertexCounts": [4], "faceVertexIndices": [0, 1, 2, 3],
        "material:binding": obscura.Path("/Looks/Ground"),
    })
    sun = look_from((1.0, 2.0, 1.5), (0.0, 0.0, 0.0))  # the light emits down its local -Z too
    d.insert_prim("distantLight", "/Lights/Sun", {"inputs:intensity": 3.0, "inputs:normalize": True}, transform=sun)
    d.insert_prim("domeLight", "/Lights/Sky", {"inputs:intensity": 0.3, "inputs:color": (0.6, 0.75, 1.0)})
    d.insert_prim("renderBuffer", "/Buffers/color", dimensions=(width, height), format="float32Vec4")
    return focus


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("output", help="the OpenEXR file to write")
    parser.add_argument("--width", type=int, default=320)
    parser.add_argument("--height", type=int, default=180)
    parser.add_argument("--taa-frames", type=int, default=8, help="frames temporal AA accumulates")
    args = parser.parse_args()

    with obscura.Renderer() as renderer, renderer.delegate() as d:
        focus = build_scene(d, args.width, args.height)
        d.set_render_settings(dof=True, taa_frames=args.taa_frames)
        renders = d.render_until_converged("/Camera", {"color": "/Buffers/color"})
        with d.map("/Buffers/color") as color:
            write_color_exr(args.output, color.array)
        print(f"{args.output}: {args.width}x{args.height}, focused at {focus:.1f} cm, {renders} renders, "
              f"{d.stats.triangles_drawn} triangles on {d.stats.device_name}")


if __name__ == "__main__":
    main()
