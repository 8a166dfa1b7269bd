#!/usr/bin/env python3
"""Writes scenes/nurbs.usda: 100 rational NURBS spheres (UsdGeomNurbsPatch, 9 x 5 control points,
the quadratic circle swept along a half circle) on a 10 x 10 grid over a NURBS ground patch, and
behind them a wall patch with a row of round windows cut by trim curves: the delegate evaluates
each surface with steps per knot span chosen from its size on screen. Used for the NurbsPatch cost
in bench/RESULTS.md."""
import math
import pathlib

from usda_pieces import SUN_AND_SKY, fmt, ints, world_header

H = math.sqrt(0.5)
CIRCLE = [(1, 0, 1), (1, 1, H), (0, 1, 1), (-1, 1, H), (-1, 0, 1), (-1, -1, H), (0, -1, 1), (1, -1, H), (1, 0, 1)]
PROFILE = [(0, -1, 1), (1, -1, H), (1, 0, 1), (1, 1, H), (0, 1, 1)]  # radial, height, weight


def patch(name, u, v, points, colour, extra=""):
    """A NurbsPatch of u and v = (vertex count, order, knots) over `points` (u fastest)."""
    return f'''    def NurbsPatch "{name}"
    {{
        int uVertexCount = {u[0]}
        int vVertexCount = {v[0]}
        int uOrder = {u[1]}
        int vOrder = {v[1]}
        double[] uKnots = {u[2]}
        double[] vKnots = {v[2]}
        point3f[] points = {fmt(points)}
        color3f[] primvars:displayColor = {fmt([colour])} (interpolation = "constant")
{extra}    }}

'''


def sphere(name, radius, centre, colour):
    # The poles on Y (the scene's up axis), the circle in the XZ plane: u turns from +X towards +Z,
    # so dS/du x dS/dv points inwards and the patch is leftHanded.
    points, weights = [], []
    for radial, height, pw in PROFILE:
        for x, z, cw in CIRCLE:
            points.append((centre[0] + radius * x * radial, centre[1] + radius * height, centre[2] + radius * z * radial))
            weights.append(f"{cw * pw:.9g}")
    extra = (f"        double[] pointWeights = [{', '.join(weights)}]\n"
             '        uniform token orientation = "leftHanded"\n')
    return patch(name, (9, 3, "[0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4]"), (5, 3, "[0, 0, 0, 1, 1, 2, 2, 2]"), points,
                 colour, extra)


WALL = (-600.0, 600.0, 0.0, 400.0, -600.0)  # x from, x to, y from, y to, z
WALL_WINDOWS = [(-400 + 200 * k, 220, 60) for k in range(5)]  # centre x, centre y, radius


def wall(windows):
    """A bilinear wall patch facing +Z whose (u, v) runs over its width and height, each window a
    clockwise trim circle (a hole): the quadratic circle's points, homogeneous (u w, v w, w)."""
    x0, x1, y0, y1, z = WALL
    counts, orders, vertex_counts, knots, ranges, points = [], [], [], [], [], []
    for cx, cy, r in windows:
        counts.append(1), orders.append(3), vertex_counts.append(9), ranges.append((0, 4))
        knots += [0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4]
        for x, y, w in CIRCLE:  # CIRCLE's second coordinate negated: clockwise
            u, v = (cx + r * x - x0) / (x1 - x0), (cy - r * y - y0) / (y1 - y0)
            points.append((u * w, v * w, w))
    extra = (f"        int[] trimCurve:counts = {ints(counts)}\n"
             f"        int[] trimCurve:orders = {ints(orders)}\n"
             f"        int[] trimCurve:vertexCounts = {ints(vertex_counts)}\n"
             f"        double[] trimCurve:knots = {ints(knots)}\n"
             f"        double2[] trimCurve:ranges = [{', '.join('(%g, %g)' % r for r in ranges)}]\n"
             f"        double3[] trimCurve:points = {fmt(points)}\n")
    return patch("Wall", (2, 2, "[0, 0, 1, 1]"), (2, 2, "[0, 0, 1, 1]"),
                 [(x0, y0, z), (x1, y0, z), (x0, y1, z), (x1, y1, z)], (0.6, 0.55, 0.5), extra)


def main():
    text = world_header("100 rational NURBS spheres over a NURBS ground patch")
    text += '''    def Camera "Camera"
    {
        float focalLength = 35
        float horizontalAperture = 36
        float verticalAperture = 20.25
        float2 clippingRange = (10, 10000)
        double3 xformOp:translate = (0, 600, 1100)
        float3 xformOp:rotateXYZ = (-28, 0, 0)
        uniform token[] xformOpOrder = ["xformOp:translate", "xformOp:rotateXYZ"]
    }

''' + SUN_AND_SKY + "\n"
    text += patch("Ground", (2, 2, "[0, 0, 1, 1]"), (2, 2, "[0, 0, 1, 1]"),
                  [(-700, 0, 700), (700, 0, 700), (-700, 0, -700), (700, 0, -700)], (0.5, 0.5, 0.5))
    text += wall(WALL_WINDOWS)
    for i in range(10):
        for j in range(10):
            hue = (i * 10 + j) / 100.0
            colour = tuple(0.5 + 0.4 * math.cos(2 * math.pi * (hue + k / 3)) for k in range(3))
            text += sphere(f"Ball_{i}_{j}", 40, ((i - 4.5) * 100, 40, (j - 4.5) * 100), colour)
    pathlib.Path(__file__).with_name("nurbs.usda").write_text(text + "}\n")


if __name__ == "__main__":
    main()
