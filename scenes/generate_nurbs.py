#!/usr/bin/env python3
"""Writes scenes/nurbs.usda: 100 rational NURBS spheres (UsdGeomNurbsPatch, 9 x 5 control points,
the quadratic circle swept along a half circle) on a 10 x 10 grid over a NURBS ground patch, under
a sun and a dome: the delegate evaluates each surface with steps per knot span chosen from its size
on screen. Used for the NurbsPatch cost in bench/RESULTS.md."""
import math
import pathlib

H = math.sqrt(0.5)
CIRCLE = [(1, 0, 1), (1, 1, H), (0, 1, 1), (-1, 1, H), (-1, 0, 1), (-1, -1, H), (0, -1, 1), (1, -1, H), (1, 0, 1)]
PROFILE = [(0, -1, 1), (1, -1, H), (1, 0, 1), (1, 1, H), (0, 1, 1)]  # radial, height, weight


def sphere(name, radius, position, colour):
    points, weights = [], []
    for radial, height, pw in PROFILE:
        for x, z, cw in CIRCLE:
            # The sphere's poles on Y (the scene's up axis): the circle in the XZ plane.
            points.append(f"({radius * x * radial:.6g}, {radius * height:.6g}, {radius * z * radial:.6g})")
            weights.append(f"{cw * pw:.9g}")
    return f'''    def NurbsPatch "{name}"
    {{
        int uVertexCount = 9
        int vVertexCount = 5
        int uOrder = 3
        int vOrder = 3
        double[] uKnots = [0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4]
        double[] vKnots = [0, 0, 0, 1, 1, 2, 2, 2]
        point3f[] points = [{", ".join(points)}]
        double[] pointWeights = [{", ".join(weights)}]
        uniform token orientation = "leftHanded"
        color3f[] primvars:displayColor = [({colour[0]:.3g}, {colour[1]:.3g}, {colour[2]:.3g})] (interpolation = "constant")
        double3 xformOp:translate = ({position[0]:.6g}, {position[1]:.6g}, {position[2]:.6g})
        uniform token[] xformOpOrder = ["xformOp:translate"]
    }}
'''


def main():
    body = []
    for i in range(10):
        for j in range(10):
            hue = (i * 10 + j) / 100.0
            colour = (0.5 + 0.4 * math.cos(6.283 * hue), 0.5 + 0.4 * math.cos(6.283 * (hue + 0.33)),
                      0.5 + 0.4 * math.cos(6.283 * (hue + 0.67)))
            body.append(sphere(f"Ball_{i}_{j}", 0.4, (i - 4.5, 0.4, j - 4.5), colour))
    text = f'''#usda 1.0
(
    defaultPrim = "World"
    metersPerUnit = 1
    upAxis = "Y"
)

def Xform "World"
{{
    def Camera "Camera"
    {{
        float focalLength = 35
        float horizontalAperture = 36
        float verticalAperture = 20.25
        float2 clippingRange = (0.1, 100)
        double3 xformOp:translate = (0, 6, 11)
        float3 xformOp:rotateXYZ = (-28, 0, 0)
        uniform token[] xformOpOrder = ["xformOp:translate", "xformOp:rotateXYZ"]
    }}

    def DistantLight "Sun"
    {{
        float inputs:intensity = 3
        float inputs:angle = 0.53
        float3 xformOp:rotateXYZ = (-50, 30, 0)
        uniform token[] xformOpOrder = ["xformOp:rotateXYZ"]
    }}

    def DomeLight "Sky"
    {{
        float inputs:intensity = 0.4
    }}

    def NurbsPatch "Ground"
    {{
        int uVertexCount = 2
        int vVertexCount = 2
        int uOrder = 2
        int vOrder = 2
        double[] uKnots = [0, 0, 1, 1]
        double[] vKnots = [0, 0, 1, 1]
        point3f[] points = [(-7, 0, 7), (7, 0, 7), (-7, 0, -7), (7, 0, -7)]
        color3f[] primvars:displayColor = [(0.5, 0.5, 0.5)] (interpolation = "constant")
    }}

{"".join(body)}}}
'''
    out = pathlib.Path(__file__).with_name("nurbs.usda")
    out.write_text(text)


if __name__ == "__main__":
    main()
