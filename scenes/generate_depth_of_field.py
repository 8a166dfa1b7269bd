#!/usr/bin/env python3
"""Writes depth_of_field.usda: chequered cards at three depths and small glowing spheres, seen
through an 85 mm lens at f/2 focused on the middle card (seed 000 "Depth of field"): the near card
and the far wall blur, the glowing spheres make bokeh. Run from this folder; the output is
committed. Units are centimetres (metersPerUnit 0.01), so focalLength and apertures read as mm."""
from usda_pieces import world_header, SUN_AND_SKY, card_prim, glow_material, glow_prim


glows = "".join(glow_prim(f"FarGlow{k}", (-150 + 75 * k, 70 + 30 * (k % 2), -600), "Warm" if k % 2 else "Cool")
                for k in range(5))
text = f'''{world_header("Depth of field: chequered cards at 1.5 m, 3 m and 9 m and glowing spheres, through an 85 mm f/2 lens focused at 3 m, 6 aperture blades.")}    def Scope "Looks"
    {{{glow_material("Warm", (40, 22, 8))}{glow_material("Cool", (8, 20, 40))}
    }}
{card_prim("FarWall", (0, 0, -600), 600, 400, 30, 20)}{card_prim("FocusCard", (20, -5, 0), 40, 60, 8, 12)}{card_prim("NearCard", (-18, -5, 150), 14, 20, 4, 6)}{glows}{glow_prim("NearGlow", (12, 14, 150), "Warm", 0.4)}
{SUN_AND_SKY}
    def Camera "Camera"
    {{
        float focalLength = 85
        float horizontalAperture = 36
        float verticalAperture = 24
        float fStop = 2
        float focusDistance = 300
        uniform int obscura:apertureBlades = 6
        float obscura:apertureRotation = 15
        float2 clippingRange = (10, 10000)
        double3 xformOp:translate = (0, 0, 300)
        uniform token[] xformOpOrder = ["xformOp:translate"]
    }}
}}
'''
with open("depth_of_field.usda", "w") as f:
    f.write(text)
