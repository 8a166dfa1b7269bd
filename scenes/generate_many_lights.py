#!/usr/bin/env python3
"""Writes many_lights_16.usda, many_lights_128.usda and many_lights_1024.usda: one 80 m field
with 400 props, lit by N small local lights (sphere, rect and disk, a quarter of them spots)
for the tiled light culling benchmark. The lights are dim and close to the ground, so each one's
influence range (see docs/ARCHITECTURE.md; the camera's exposure of 3 stops widens it to 15-30 m)
still leaves tiles with different lists."""
import math
import random

from generate_demo import box, fmt, ints, material, prototypes_scope, sphere


def light(i, rng):
    x, z = rng.uniform(-38, 38), rng.uniform(-38, 38)
    y = rng.uniform(0.5, 2.0)
    hue = rng.random()
    color = tuple(0.55 + 0.45 * math.cos(2 * math.pi * (hue + k / 3)) for k in range(3))
    intensity = rng.uniform(1.0, 3.0)
    kind = rng.random()
    shaping = ""
    if rng.random() < 0.25:
        shaping = f"""
        float inputs:shaping:cone:angle = {rng.uniform(25, 60):.1f}
        float inputs:shaping:cone:softness = 0.3"""
    # Local -Z (the emission axis) points down: rotate -90 degrees about X.
    xform = f"""
        double3 xformOp:translate = ({x:.3f}, {y:.3f}, {z:.3f})
        float xformOp:rotateX = -90
        uniform token[] xformOpOrder = ["xformOp:translate", "xformOp:rotateX"]"""
    if kind < 0.7:
        body = f'def SphereLight "L{i}"\n    {{\n        float inputs:radius = 0.05\n        float inputs:intensity = {intensity:.2f}'
    elif kind < 0.85:
        body = f'def RectLight "L{i}"\n    {{\n        float inputs:width = 0.3\n        float inputs:height = 0.15\n        float inputs:intensity = {intensity * 0.18:.3f}'
    else:
        body = f'def DiskLight "L{i}"\n    {{\n        float inputs:radius = 0.12\n        float inputs:intensity = {intensity * 0.18:.3f}'
    return f"""
    {body}
        color3f inputs:color = ({color[0]:.3f}, {color[1]:.3f}, {color[2]:.3f}){shaping}{xform}
    }}
"""


def scene(count):
    rng = random.Random(11)
    sp, sn, sc, si = sphere(0.5, 10, 20)
    bp, bc, bi = box(0.8)
    positions, proto = [], []
    for i in range(400):
        x, z = (i % 20 - 9.5) * 4 + rng.uniform(-1, 1), (i // 20 - 9.5) * 4 + rng.uniform(-1, 1)
        positions.append((x, 0.5, z))
        proto.append(i % 2)
    lights = "".join(light(i, rng) for i in range(count))
    return f'''#usda 1.0
(
    doc = "{count} local lights over a field of 400 props: the tiled light culling benchmark."
    defaultPrim = "World"
    metersPerUnit = 1
    upAxis = "Y"
)

def Xform "World"
{{
    def Scope "Looks"
    {{{material("Ground", (0.5, 0.5, 0.5), 0.7)}{material("Clay", (0.6, 0.55, 0.5), 0.5)}{material("Steel", (0.8, 0.8, 0.8), 0.3, 1.0)}
    }}

    def Mesh "Ground"
    {{
        int[] faceVertexCounts = [4]
        int[] faceVertexIndices = [0, 1, 2, 3]
        point3f[] points = [(-40, 0, 40), (40, 0, 40), (40, 0, -40), (-40, 0, -40)]
        uniform token subdivisionScheme = "none"
        rel material:binding = </World/Looks/Ground>
    }}

    def PointInstancer "Props"
    {{
        rel prototypes = [</World/Props/Prototypes/Ball>, </World/Props/Prototypes/Crate>]
        int[] protoIndices = {ints(proto)}
        point3f[] positions = {fmt(positions)}

{prototypes_scope((sp, sn, sc, si), (bp, bc, bi), "Clay", "Steel")}
    }}

    def DomeLight "Sky"
    {{
        float inputs:intensity = 0.03
        color3f inputs:color = (0.6, 0.7, 1.0)
    }}

    def Scope "Lights"
    {{{lights}    }}

    def Camera "Camera"
    {{
        float focalLength = 24
        float horizontalAperture = 36
        float verticalAperture = 24
        float2 clippingRange = (0.5, 500)
        float exposure = 3
        double3 xformOp:translate = (0, 18, 48)
        float xformOp:rotateX = -28
        uniform token[] xformOpOrder = ["xformOp:translate", "xformOp:rotateX"]
    }}
}}
'''


for n in (16, 128, 1024):
    with open(f"many_lights_{n}.usda", "w") as f:
        f.write(scene(n))
