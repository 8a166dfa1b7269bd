#version 460
#extension GL_GOOGLE_include_directive : require
// Depth of field, step 2 (seed 000 "Tile min/max CoC"): the field CoC downscaled to one
// value pair per DOF_TILE_SIZE^2 texels. With the signed CoC (near positive, far negative) the far
// field takes the tile's min fragment and the near field its max; stored as magnitudes: x the
// largest near CoC, y the largest far CoC, as fractions of the largest radius (R8G8).
#include "common/dof_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D fieldCoc;
layout(set = 0, binding = 1, rg8) uniform writeonly image2D tileCoc;

void main() {
    ivec2 tile = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(tile, imageSize(tileCoc)))) return;
    ivec2 first = tile * DOF_TILE_SIZE;
    ivec2 last = min(first + DOF_TILE_SIZE, textureSize(fieldCoc, 0)) - 1;
    vec2 extreme = vec2(0.0);
    for (int y = first.y; y <= last.y; ++y)
        for (int x = first.x; x <= last.x; ++x) extreme = max(extreme, texelFetch(fieldCoc, ivec2(x, y), 0).xy);
    imageStore(tileCoc, tile, vec4(extreme, 0.0, 0.0));
}
