// UsdPreviewSurface inputs read through UsdUVTexture (frame_data.glsl MaterialTexture), shared by
// the passes that rasterise materials: the G-buffer and the shadow maps' opacity cut-outs.
#ifndef OBSCURA_MATERIAL_INPUTS_GLSL
#define OBSCURA_MATERIAL_INPUTS_GLSL

// What the draw's materials use (passes/frame_data.h MaterialFeature), a specialization constant:
// the G-buffer and the transparent pass build a pipeline per set, leaving out the code of the
// features their draws lack (a CPU device runs every branch for every lane, taken or not); the
// shadow maps' cut-outs keep all of them.
layout(constant_id = 1) const uint MATERIAL_FEATURES = 0xffffffffu;
const uint MATERIAL_TEXTURED = 1u;
const uint MATERIAL_UDIM = 2u;
const uint MATERIAL_TRANSFORMED_TEXTURE = 4u;
const uint MATERIAL_NORMAL_MAP = 8u;
const uint MATERIAL_ANISOTROPIC = 16u;
const uint MATERIAL_TEXTURED_EMISSION = 32u;

bool drawUses(uint feature) { return (MATERIAL_FEATURES & feature) != 0u; }

// Added to every lookup's LOD. An includer whose views may be samples of a still's mean defines it
// before including this file (CameraData::textureLodBias); a shadow map's cut-outs take none.
#ifndef MATERIAL_LOD_BIAS
#define MATERIAL_LOD_BIAS 0.0
#endif

// The texture's own coordinates: the affine map of st (UsdTransform2d, MaterialX uvtiling and
// uvoffset) applied in st; uv is the image's (s, 1 - t) (common/gbuffer_vertex.glsl).
vec2 textureCoordinates(MaterialTexture t, vec2 uv) {
    vec3 st = vec3(uv.x, 1.0 - uv.y, 1.0);
    return vec2(dot(t.transformS.xyz, st), 1.0 - dot(t.transformT.xyz, st));
}

// A UDIM set's atlas (delegate/udim_tiles.h) holds tile 1001 + u + 10 v's square where st has it,
// so the atlas coordinate is an affine map of st, continuous across tiles. The mip comes from those
// continuous derivatives (textureGrad), so a seam does not jump to a coarse mip, kept fine enough
// that a square still spans a 4x4 block; the lookup is clamped within its square by half a texel
// of the coarser mip trilinear filtering reads (the atlas's sampler is not anisotropic:
// delegate/material_texture.cpp), so no neighbouring tile bleeds in. Squares with no tile read transparent black, Storm's fallback.
vec4 sampleUdim(MaterialTexture t, sampler2D tex, vec2 uv) {
    vec2 grid = t.udimGrid.zw;
    vec2 st = vec2(uv.x, 1.0 - uv.y) - t.udimGrid.xy;  // from the grid's lower-left corner
    vec2 squareTexels = vec2(textureSize(tex, 0)) / grid;
    vec2 dx = dFdx(st) * exp2(MATERIAL_LOD_BIAS), dy = dFdy(st) * exp2(MATERIAL_LOD_BIAS);
    float lod = log2(max(max(length(dx * squareTexels), length(dy * squareTexels)), 1e-20));
    float coarsest = max(log2(min(squareTexels.x, squareTexels.y)) - 2.0, 0.0);
    if (!(lod <= coarsest)) {  // also where the derivatives are not finite
        float shrink = isinf(lod) || isnan(lod) ? 0.0 : exp2(coarsest - lod);
        dx *= shrink;
        dy *= shrink;
        lod = coarsest;
    }
    vec2 square = floor(st);
    vec2 margin = min(0.5 * exp2(max(ceil(lod), 0.0)) / squareTexels, vec2(0.5));
    vec2 inSquare = clamp(st, square + margin, square + 1.0 - margin);
    vec2 toAtlas = vec2(1.0, -1.0) / grid;  // image rows run down from the top row of squares
    vec4 texel = textureGrad(tex, vec2(0.0, 1.0) + inSquare * toAtlas, dx * toAtlas, dy * toAtlas);
    bool outside = any(lessThan(square, vec2(0.0))) || any(greaterThanEqual(square, grid));
    return outside ? vec4(0.0) : texel;
}

// The sRGB transfer function's inverse (IEC 61966-2-1).
vec3 srgbDecoded(vec3 encoded) {
    return mix(encoded / 12.92, pow((encoded + 0.055) / 1.055, vec3(2.4)), greaterThan(encoded, vec3(0.04045)));
}

// UsdUVTexture (UsdPreviewSurface spec): texel * scale + bias. An sRGB texture is filtered in its
// encoded values and decoded here, as Cycles interpolates 8-bit textures
// (delegate/texture_cache.cpp makeFromImage). Untransformed textures look up uv
// itself. XXX: on lavapipe, a one-pixel line along the edge two triangles share misreads the
// transform (the texture there is untransformed or at its coarsest mip); not yet understood.
vec4 sampleTexture(MaterialTexture t, sampler2D tex, vec2 uv) {
    vec2 at = drawUses(MATERIAL_TRANSFORMED_TEXTURE) && t.transformed != 0u ? textureCoordinates(t, uv) : uv;
    vec4 texel = drawUses(MATERIAL_UDIM) && t.udimGrid.z > 0.0 ? sampleUdim(t, tex, at) : texture(tex, at, MATERIAL_LOD_BIAS);
    if (t.encoding == TEXEL_SRGB) texel.rgb = srgbDecoded(texel.rgb);
    return texel * t.scale + t.bias;
}

vec3 colorInput(vec3 constant, MaterialTexture t, sampler2D tex, vec2 uv) {
    if (!drawUses(MATERIAL_TEXTURED) || t.sampled == 0u) return constant;
    vec4 v = sampleTexture(t, tex, uv);
    return t.channel == TEXTURE_CHANNEL_RGB ? v.rgb : vec3(v[t.channel]);
}

// Float inputs fed from the rgb output read its first component.
float scalarInput(float constant, MaterialTexture t, sampler2D tex, vec2 uv) {
    if (!drawUses(MATERIAL_TEXTURED) || t.sampled == 0u) return constant;
    return clamp(sampleTexture(t, tex, uv)[t.channel == TEXTURE_CHANNEL_RGB ? 0u : t.channel], 0.0, 1.0);
}

// UsdPreviewSurface `normal`: a tangent-space normal (the texture's scale and bias map texels to
// [-1, 1], e.g. scale 2, bias -1), in the frame of the interpolated tangent (direction of
// increasing u), the bitangent cross(N, T) * handedness and the normal. Two-channel normal maps
// (16-bit RG, BC5) hold x and y; z is the unit vector's (Kaplanyan 2010, "3Dc encoder
// improvements": the renormalised normal is what the encoder minimised the error of).
// The map's x and y run along the texture's own coordinates: through a transformed lookup
// (st' = A st + b) those are the columns of A^-1 in the mesh's (tangent, bitangent) frame, so a
// rotated or mirrored texture turns its normals with it. Only their directions are used: a
// non-uniform scale would also tilt the map's slopes, which is left out.
vec3 perturbedNormal(vec3 n, vec4 tangent, MaterialTexture t, sampler2D tex, vec2 uv) {
    if (!drawUses(MATERIAL_NORMAL_MAP) || t.sampled == 0u) return n;
    vec3 local = sampleTexture(t, tex, uv).xyz;
    if (t.encoding == TEXEL_TWO_CHANNEL_NORMAL) local.z = sqrt(max(0.0, 1.0 - dot(local.xy, local.xy)));
    vec3 T = tangent.xyz - n * dot(n, tangent.xyz);  // re-orthogonalised after interpolation
    if (dot(T, T) < 1e-12 || dot(local, local) < 1e-12) return n;
    T = normalize(T);
    vec3 B = cross(n, T) * (tangent.w < 0.0 ? -1.0 : 1.0);
    mat2 mapAxes = mat2(1.0);
    mat2 linear = mat2(t.transformS.x, t.transformT.x, t.transformS.y, t.transformT.y);  // A, by columns
    if (t.transformed != 0u && abs(determinant(linear)) > 1e-12) {
        mat2 inverseLinear = inverse(linear);
        mapAxes = mat2(normalize(inverseLinear[0]), normalize(inverseLinear[1]));
    }
    vec2 inFrame = mapAxes * local.xy;  // x and y in the (T, B) frame
    return normalize(T * inFrame.x + B * inFrame.y + n * local.z);
}

// UsdPreviewSurface opacityThreshold: above 0, opacity is a cut-out mask and the surface is absent
// where opacity falls below the threshold. Callers discard last, so that every implicit-LOD
// sample runs in uniform control flow.
float opacityAt(MaterialData mat, sampler2D opacityTexture, vec2 uv) {
    return scalarInput(mat.opacity.x, mat.textures[TEXTURE_OPACITY], opacityTexture, uv);
}

bool cutOut(MaterialData mat, sampler2D opacityTexture, vec2 uv) {
    float threshold = mat.opacity.y;
    if (threshold <= 0.0) return false;
    return opacityAt(mat, opacityTexture, uv) < threshold;
}

#endif
