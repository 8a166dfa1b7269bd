#!/usr/bin/env python3
"""Writes curves_and_points.usda: a tuft of cubic B-spline hairs (tubes, widths tapering from root
to tip), a catmullRom ribbon loop facing up, and a spiral of particles (Points, one width each)
over a ground. `--curves N --points M -o FILE` writes a larger one (the benchmark's 10,000 curves
and 100,000 points)."""
import argparse
import math
import random

from usda_pieces import SUN_AND_SKY, fmt, ints, world_header

parser = argparse.ArgumentParser()
parser.add_argument("--curves", type=int, default=200)
parser.add_argument("--points", type=int, default=2000)
parser.add_argument("-o", "--output", default="curves_and_points.usda")
args = parser.parse_args()

random.seed(11)
hair_points, hair_widths = [], []
for i in range(args.curves):
    # Roots on a disc of radius 60, each hair four control points leaning outwards.
    r, a = 60 * math.sqrt(random.random()), random.uniform(0, 2 * math.pi)
    x, z = r * math.cos(a), r * math.sin(a)
    lean = random.uniform(5, 25)
    for k in range(4):
        t = k / 3
        hair_points.append((x + lean * t * t * math.cos(a), 45 * t, z + lean * t * t * math.sin(a)))
        hair_widths.append(1.2 * (1 - 0.8 * t))

loop = [(150 + 40 * math.cos(2 * math.pi * k / 8), 10, 40 * math.sin(2 * math.pi * k / 8)) for k in range(8)]

particles, particle_widths, particle_colours = [], [], []
for i in range(args.points):
    t = i / max(1, args.points - 1)
    a = 14 * math.pi * t
    particles.append((-150 + (20 + 40 * t) * math.cos(a), 5 + 90 * t + random.uniform(-2, 2), (20 + 40 * t) * math.sin(a)))
    particle_widths.append(random.uniform(1.0, 3.0))
    particle_colours.append((0.9, 0.5 + 0.4 * t, 0.1 + 0.8 * (1 - t)))

text = world_header(f"{args.curves} B-spline hairs, a catmullRom ribbon loop and {args.points} particles.") + f'''    def Mesh "Ground"
    {{
        int[] faceVertexCounts = [4]
        int[] faceVertexIndices = [0, 1, 2, 3]
        point3f[] points = [(-300, 0, 150), (300, 0, 150), (300, 0, -150), (-300, 0, -150)]
        uniform token subdivisionScheme = "none"
        color3f[] primvars:displayColor = [(0.4, 0.4, 0.4)]
    }}

    def BasisCurves "Hair"
    {{
        uniform token type = "cubic"
        uniform token basis = "bspline"
        uniform token wrap = "pinned"
        int[] curveVertexCounts = {ints([4] * args.curves)}
        point3f[] points = {fmt(hair_points)}
        float[] widths = {"[" + ", ".join("%g" % w for w in hair_widths) + "]"} (
            interpolation = "vertex"
        )
        color3f[] primvars:displayColor = [(0.35, 0.2, 0.08)]
    }}

    def BasisCurves "Ribbon"
    {{
        uniform token type = "cubic"
        uniform token basis = "catmullRom"
        uniform token wrap = "periodic"
        int[] curveVertexCounts = [8]
        point3f[] points = {fmt(loop)}
        normal3f[] normals = [(0, 1, 0)] (
            interpolation = "constant"
        )
        float[] widths = [12] (
            interpolation = "constant"
        )
        color3f[] primvars:displayColor = [(0.1, 0.3, 0.8)]
    }}

    def Points "Particles"
    {{
        point3f[] points = {fmt(particles)}
        float[] widths = {"[" + ", ".join("%.3g" % w for w in particle_widths)+ "]"} (
            interpolation = "vertex"
        )
        color3f[] primvars:displayColor = {fmt(particle_colours)} (
            interpolation = "vertex"
        )
    }}

{SUN_AND_SKY}
    def Camera "Camera"
    {{
        float focalLength = 24
        float horizontalAperture = 36
        float verticalAperture = 20.25
        float2 clippingRange = (1, 5000)
        double3 xformOp:translate = (0, 170, 330)
        float xformOp:rotateX = -25
        uniform token[] xformOpOrder = ["xformOp:translate", "xformOp:rotateX"]
    }}
}}
'''
with open(args.output, "w") as out:
    out.write(text)
