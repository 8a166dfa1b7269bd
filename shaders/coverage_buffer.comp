#version 460
// Occlusion culling's coverage buffer (seed 004 "Occlusion culling": "downscale previous frame's z
// buffer", "use conservative occlusion to avoid false culling"): the frame's opaque depth reduced
// to one texel per tile of kCoverageTilePixels^2 pixels, holding the nearest and the farthest
// depth of the tile. The farthest is what the tile occludes behind; the nearest bounds where the
// occluder lies, so that the CPU can reproject the tile conservatively into the next frame's view
// (renderer/coverage_buffer.h). A tile with any background pixel has the far depth 1: no occluder.
layout(local_size_x = 8, local_size_y = 8) in;

// The G-buffer's depth (one sample), or with MSAA the farthest of each pixel's samples.
layout(set = 0, binding = 0) uniform sampler2D depthTexture;
layout(set = 0, binding = 1, std430) writeonly buffer Tiles { vec2 nearestFarthest[]; };

layout(push_constant) uniform Push {
    uvec2 tiles;      // the grid's size in tiles
    uint tilePixels;  // a tile's side in pixels
} push;

void main() {
    uvec2 tile = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(tile, push.tiles))) return;
    ivec2 size = textureSize(depthTexture, 0);
    ivec2 first = ivec2(tile * push.tilePixels);
    ivec2 end = min(first + ivec2(push.tilePixels), size);
    vec2 range = vec2(1.0, 0.0);
    for (int y = first.y; y < end.y; ++y)
        for (int x = first.x; x < end.x; ++x) {
            float depth = texelFetch(depthTexture, ivec2(x, y), 0).r;
            range = vec2(min(range.x, depth), max(range.y, depth));
        }
    nearestFarthest[tile.y * push.tiles.x + tile.x] = range;
}
