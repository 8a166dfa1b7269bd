#version 460
#extension GL_GOOGLE_include_directive : require
// Depth of field, step 2 (seed 000 "Tile min/max CoC": "also used for scatter as gather
// approximation for near field"): a near CoC spreads its blur up to its radius beyond its own
// tile, so a tile's near-field kernel is the largest near CoC of every tile within reach
// (dof.tileNeighbourhood tiles each side). The far field gathers with each texel's own CoC and
// keeps its tile's own value.
#include "common/dof_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D tileCoc;
layout(set = 0, binding = 1, rg8) uniform writeonly image2D neighbourhoodCoc;

void main() {
    ivec2 tile = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(neighbourhoodCoc);
    if (any(greaterThanEqual(tile, size))) return;
    float nearMax = 0.0;
    for (int y = -dof.tileNeighbourhood; y <= dof.tileNeighbourhood; ++y)
        for (int x = -dof.tileNeighbourhood; x <= dof.tileNeighbourhood; ++x) {
            ivec2 neighbour = tile + ivec2(x, y);
            if (all(greaterThanEqual(neighbour, ivec2(0))) && all(lessThan(neighbour, size)))
                nearMax = max(nearMax, texelFetch(tileCoc, neighbour, 0).x);
        }
    imageStore(neighbourhoodCoc, tile, vec4(nearMax, texelFetch(tileCoc, tile, 0).y, 0.0, 0.0));
}
