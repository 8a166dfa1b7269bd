#!/usr/bin/env python3
"""Writes motion_blur.usda: a chequered card racing across a still wall, a card spinning about the
view axis, glowing spheres moving diagonally, and a camera panning slowly, through a 180-degree
shutter (shutter:open -0.25, shutter:close 0.25) at frame 1 (seed 000 "Motion blur"). At 1920x1080
the racing card moves about 120 pixels a frame, so its blur reaches the filter's 32-pixel
half-length. Run from this folder; the output is committed. Units are centimetres."""
from usda_pieces import world_header, SUN_AND_SKY, card_prim, glow_material, glow_prim


def moving(start, velocity):
    """Translate samples at frames 0, 1, 2 for a constant velocity through `start` at frame 1."""
    return {t: tuple(s + v * (t - 1) for s, v in zip(start, velocity)) for t in (0, 1, 2)}


glows = "".join(glow_prim(f"Glow{k}", moving((-120 + 60 * k, 80 - 20 * k, -100), (12, -8, 0)),
                          "Warm" if k % 2 else "Cool", radius=6.0) for k in range(5))
text = f'''{world_header("Motion blur: a card racing across a still wall, a spinning card and moving glows, a panning camera, 180-degree shutter.")}    def Scope "Looks"
    {{{glow_material("Warm", (40, 22, 8))}{glow_material("Cool", (8, 20, 40))}
    }}
{card_prim("Wall", (0, 0, -600), 900, 600, 30, 20)}{card_prim("Racer", moving((0, -40, 0), (20, 0, 0)), 60, 40, 6, 4)}{card_prim("Spinner", (90, 60, -50), 80, 20, 8, 2, rotate_z={0: 0, 1: 90, 2: 180})}{glows}
{SUN_AND_SKY}
    def Camera "Camera"
    {{
        float focalLength = 35
        float horizontalAperture = 36
        float verticalAperture = 20.25
        double shutter:open = -0.25
        double shutter:close = 0.25
        float2 clippingRange = (10, 10000)
        double3 xformOp:translate.timeSamples = {{ 0: (-3, 0, 300), 1: (0, 0, 300), 2: (3, 0, 300) }}
        uniform token[] xformOpOrder = ["xformOp:translate"]
    }}
}}
'''
with open("motion_blur.usda", "w") as f:
    f.write(text)
