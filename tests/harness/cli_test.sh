#!/usr/bin/env bash
# The harness's command-line contract (DESIGN.md): outputs, exit codes and error messages.
# usage: cli_test.sh OBSCURA_EXE SOURCE_DIR FAKE_PLUGIN_DIR
set -u
obscura=$1; src=$2; fake_plugin=$3
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
export OBSCURA_VALIDATION=1
source "$(dirname "$0")/check.sh"

"$obscura" render "$src/scenes/demo.usda" -o "$tmp/demo.exr" --width 96 --height 54 \
    --aov color,depth,normal,albedo,motion,primId >"$tmp/out" 2>&1
check "render demo to EXR" 0 $?
"$obscura" render "$src/scenes/demo.usda" -o "$tmp/demo.png" --width 96 --height 54 >"$tmp/out" 2>&1
check "render demo to PNG" 0 $?
[ -s "$tmp/demo.png" ] && [ -s "$tmp/demo.exr" ]; check "both files written" 0 $?
if command -v exrheader >/dev/null; then
    exrheader "$tmp/demo.exr" >"$tmp/header" 2>&1
    check "EXR has the AOV channels" 0 $? "$tmp/header" 'primId\.id.*' 
    grep -qE '^ +Z, ' "$tmp/header" && grep -q 'normal.X' "$tmp/header" && grep -q 'albedo.R' "$tmp/header" &&
        grep -q 'motion.X' "$tmp/header"
    check "EXR names Z, normal, albedo and motion layers" 0 $?
fi

# Every UsdGeom implicit surface renders, none reported as unsupported.
"$obscura" render "$src/scenes/gprims.usda" -o "$tmp/gprims.png" --width 96 --height 40 --set taa:frames=2 >"$tmp/out" 2>&1
check "render every implicit gprim" 0 $?
! grep -q "not supported" "$tmp/out"; check "no gprim reported unsupported" 0 $?

# Colour grading from a chart: the neutral chart over a rendered frame, read back as the grade.
"$obscura" grade-chart --write "$tmp/chart.png" --into "$tmp/demo.png" >"$tmp/out" 2>&1
check "grade-chart over a screenshot" 0 $? "$tmp/out" 'grading chart \(256x16'
"$obscura" render "$src/scenes/demo.usda" -o "$tmp/graded.png" --width 32 --height 18 --set taa:frames=2 \
    --set grading:chart="$tmp/chart.png" >"$tmp/out" 2>&1
check "render graded by the chart" 0 $?
"$obscura" render "$src/scenes/demo.usda" -o "$tmp/graded.png" --width 32 --height 18 --set taa:frames=2 \
    --set grading:chart="$tmp/demo.png" >"$tmp/out" 2>&1
check "a screenshot too small for the chart is refused" 3 $? "$tmp/out" 'smaller than the 256x16 chart'
"$obscura" grade-chart --write "$tmp/c.png" --into "$tmp/missing.png" >"$tmp/out" 2>&1
check "grade-chart names an unreadable screenshot" 3 $? "$tmp/out" 'missing.png'

"$obscura" render "$src/scenes/demo.usda" -o "$tmp/frame.####.png" --frames 1-2 --width 32 --height 18 >"$tmp/out" 2>&1
check "frame sequence" 0 $? "$tmp/out" 'frame 2 \(2/2\)'
[ -s "$tmp/frame.0001.png" ] && [ -s "$tmp/frame.0002.png" ]; check "#### becomes the frame number" 0 $?

"$obscura" compare "$tmp/demo.exr" "$tmp/demo.exr" --psnr-min 60 --ssim-min 0.999 >"$tmp/out" 2>&1
check "compare identical images" 0 $? "$tmp/out" 'psnr inf'
"$obscura" render "$src/scenes/demo.usda" -o "$tmp/dim.exr" --width 96 --height 54 --set exposure=-2 >"$tmp/out" 2>&1
check "render with --set" 0 $?
"$obscura" compare "$tmp/demo.exr" "$tmp/dim.exr" --psnr-min 60 --diff "$tmp/diff.png" >"$tmp/out" 2>&1
check "compare below threshold exits 1" 1 $? "$tmp/out" 'below threshold'
[ -s "$tmp/diff.png" ]; check "diff image written" 0 $?

# Depth of field and its ground truth: the reference mode converges towards the post-process image.
"$obscura" render "$src/scenes/depth_of_field.usda" -o "$tmp/dof.exr" --width 96 --height 64 >"$tmp/out" 2>&1
check "render with depth of field" 0 $?
"$obscura" render "$src/scenes/depth_of_field.usda" -o "$tmp/ref.exr" --width 96 --height 64 --reference 32 >"$tmp/out" 2>&1
check "render --reference N" 0 $?
"$obscura" render "$src/scenes/depth_of_field.usda" -o "$tmp/sharp.exr" --width 96 --height 64 --set dof=off >"$tmp/out" 2>&1
check "render with --set dof=off" 0 $?
"$obscura" compare "$tmp/dof.exr" "$tmp/sharp.exr" --ssim-min 0.999 >"$tmp/out" 2>&1
check "depth of field changes the image" 1 $? "$tmp/out" 'below threshold'
"$obscura" render "$src/scenes/depth_of_field.usda" -o "$tmp/x.exr" --reference -1 >"$tmp/out" 2>&1
check "negative --reference is a usage error" 2 $?
"$obscura" render "$src/scenes/depth_of_field.usda" -o "$tmp/x.exr" --set dof:taps=99 >"$tmp/out" 2>&1
check "dof:taps out of range is a usage error" 2 $? "$tmp/out" 'dof:taps: 99 is outside 3\.\.15'

# Deferred MSAA: --msaa N is --set msaa=N; -v prints the share of pixels lit per sample.
"$obscura" render "$src/scenes/demo.usda" -o "$tmp/msaa.png" --width 96 --height 54 --msaa 4 --set taa=off -v >"$tmp/out" 2>&1
check "render --msaa 4 -v" 0 $? "$tmp/out" 'msaa 4x: [0-9.]+% of pixels tagged'
"$obscura" render "$src/scenes/demo.usda" -o "$tmp/x.png" --width 32 --height 18 --msaa 3 >"$tmp/out" 2>&1
check "--msaa 3 is a usage error" 2 $? "$tmp/out" 'msaa: 3 samples per pixel is not a sample count'

"$obscura" render "$src/tests/harness/data/malformed.usda" -o "$tmp/x.png" >"$tmp/out" 2>&1
check "malformed scene names file:line:column" 3 $? "$tmp/out" 'malformed\.usda:7:[0-9]+'
"$obscura" render "$src/tests/harness/data/bad_prims.usda" -o "$tmp/bad.png" --width 64 --height 64 >"$tmp/out" 2>&1
check "bad prims exit 3" 3 $? "$tmp/out" 'NaNPoints.*NaN'
grep -q 'IndexOutOfRange' "$tmp/out"; check "every bad prim is reported" 0 $?
grep -q "prim type 'Volume' is not supported" "$tmp/out"; check "unsupported prim types warned once" 0 $?
grep -q 'NegativeRadius: radius is -1' "$tmp/out"; check "a sphere of negative radius is reported" 0 $?
[ -s "$tmp/bad.png" ]; check "the rest still renders" 0 $?
# Bad data the delegate finds is located in the file as a compiler would: file:line:column of the
# attribute, and the value's index (bad_data.usda holds one kind of bad data per prim).
"$obscura" render "$src/tests/harness/data/bad_data.usda" -o "$tmp/bad_data.png" --width 32 --height 32 >"$tmp/out" 2>&1
check "bad data exits 3" 3 $?
located() {  # located NAME PATTERN: one line of the last output
    grep -qE "bad_data\.usda:$2" "$tmp/out"; check "$1" 0 $? "$tmp/out" "bad_data\.usda:$2"
}
located "face index out of range" '18:15: error: skipped prim /World/IndexOutOfRange: faceVertexIndices\[2\] = 7'
located "negative face count" '24:15: error: skipped prim /World/NegativeCount: faceVertexCounts\[0\] is -3'
located "huge face count" '31:15: error: skipped prim /World/HugeCount: faceVertexCounts sum to 2000000000'
located "count beyond int32" '38:15: error: /World/BeyondInt32: faceVertexCounts: element 1 = 99999999999 does not fit'
located "counts that do not sum" '45:15: error: skipped prim /World/CountsDoNotSum: faceVertexCounts sum to 6'
located "NaN points" '54:19: error: skipped prim /World/NaNPoints: points: element 1 is NaN'
located "primvar index out of range" '65:15: error: /World/PrimvarIndexOutOfRange: primvars:st:indices\[2\] = 2 is outside'
located "faceVarying count mismatch" '73:19: warning: /World/FaceVaryingCount: primvars:displayColor has 2 values but faceVarying'
located "instancer protoIndices out of range" '81:15: error: skipped prim /World/ProtoIndexOutOfRange: protoIndices\[1\] = 1'
located "instancer positions mismatch" '95:19: error: skipped prim /World/PositionsMismatch: positions has 1 entries for 2'
located "curve widths count" '109:17: error: skipped prim /World/WidthsCount: widths has 2 elements but its interpolation needs 3'
located "curve vertex counts that do not sum" '117:15: error: skipped prim /World/CurveCountsDoNotSum: curveVertexCounts sum to 4 but there are 3 points'
located "negative point width" '124:17: error: skipped prim /World/NegativeWidth: widths\[1\] is -0\.2'
[ -s "$tmp/bad_data.png" ]; check "the good prims of bad_data.usda still render" 0 $?
printf '#usda 1.0\ndef Xform "Caf\xc3\xa9"\n{\n}\ndef Xform "Bad\xffName"\n{\n}\n' >"$tmp/utf8.usda"
"$obscura" render "$tmp/utf8.usda" -o "$tmp/x.png" >"$tmp/out" 2>&1
check "an invalid UTF-8 byte in a prim name" 3 $? "$tmp/out" 'utf8\.usda:5:11: prim name has an invalid UTF-8 byte 0xFF at offset 3'
"$obscura" render "$src/tests/import/data/bad_base64.gltf" -o "$tmp/x.png" >"$tmp/out" 2>&1
check "a glTF buffer with corrupt base64" 3 $? "$tmp/out" "bad_base64\.gltf:11:25: buffers\[0\]\.uri: base64 data has '!' at offset 20"

# Arcs to layers that are missing or do not parse are each reported where they are authored and
# add nothing: the scene renders, exit 0, as it does with those arcs taken out.
scene="$src/tests/harness/data/missing_arcs.usda"
"$obscura" render "$scene" -o "$tmp/arcs.png" --width 32 --height 32 >"$tmp/out" 2>&1
check "arcs to missing layers are warnings" 0 $?
arc() {  # arc NAME PATTERN: one warning of the last output
    check "$1" 0 0 "$tmp/out" "warning: .*missing_arcs\.usda:$2"
}
arc "a missing sublayer" '5:9: sublayer @gone_sublayer\.usda@ ignored: .*/gone_sublayer\.usda: no such file'
arc "a missing reference" '13:22: reference of </World/Local> to @gone\.usda@ ignored: .*/gone\.usda: no such file'
arc "a reference to a layer that does not parse" \
    "24:13: reference of </World/Referenced> to @malformed\.usda@ ignored: .*/malformed\.usda:7:[0-9]+: "
arc "a missing payload" '27:19: payload of </World/Referenced> to @gone_payload\.usda@ ignored'
sed -e '/@gone\|@malformed/d' -e "s|@bad_prims|@$(cd "$src" && pwd)/tests/harness/data/bad_prims|" "$scene" \
    >"$tmp/without_arcs.usda"
"$obscura" render "$tmp/without_arcs.usda" -o "$tmp/without_arcs.png" --width 32 --height 32 >"$tmp/out" 2>&1
check "render without the broken arcs" 0 $?
! grep -q "ignored" "$tmp/out"; check "no broken arc is left" 0 $?
"$obscura" compare "$tmp/arcs.png" "$tmp/without_arcs.png" --psnr-min 60 >"$tmp/out" 2>&1
check "the rest renders as if the broken arcs were not written" 0 $?

# GeomSubsets of the materialBind family bind materials per face: the same image as the faces drawn
# as meshes of their own (ignored subsets would leave every tile blue); a bad index is located on
# its subset and ignored.
"$obscura" render "$src/tests/harness/data/geom_subsets.usda" -o "$tmp/subsets.png" --width 64 --height 64 >"$tmp/out" 2>&1
check "render per-face materials from GeomSubsets" 0 $? "$tmp/out" \
    'geom_subsets\.usda:81:[0-9]+: warning: /Tiles/RedTiles: indices\[2\] = 9 is outside the mesh.s 4 faces; ignored'
"$obscura" render "$src/tests/harness/data/geom_subsets_separate.usda" -o "$tmp/separate.png" --width 64 --height 64 >"$tmp/out" 2>&1
check "render the tiles as separate meshes" 0 $?
"$obscura" compare "$tmp/subsets.png" "$tmp/separate.png" --psnr-min 40 >"$tmp/out" 2>&1
check "GeomSubsets draw what separate meshes draw" 0 $?
sed 's/"materialBind"/"unrelated"/' "$src/tests/harness/data/geom_subsets.usda" >"$tmp/other_family.usda"
"$obscura" render "$tmp/other_family.usda" -o "$tmp/other_family.png" --width 64 --height 64 >"$tmp/out" 2>&1
check "render subsets of another family" 0 $?
"$obscura" compare "$tmp/other_family.png" "$tmp/separate.png" --psnr-min 40 >"$tmp/out" 2>&1
check "subsets of another family bind nothing" 1 $? "$tmp/out" 'below threshold'

"$obscura" render "$src/tests/harness/data/no_camera.usda" -o "$tmp/x.exr" --aov color,depth >"$tmp/out" 2>&1
check "scene without camera is framed" 0 $? "$tmp/out" 'no camera; framing'

# Composition has a budget: a file whose arcs fan out stops with its location, and the limits are options.
"$obscura" render "$src/tests/usda/data/limits/laughs.usda" -o "$tmp/x.png" --max-prims 5000 >"$tmp/out" 2>&1
check "--max-prims stops a fan-out of references" 3 $? "$tmp/out" 'laughs\.usda:[0-9]+:[0-9]+: composition stopped: .* the limit is 5000 prims'
"$obscura" render "$src/tests/usda/data/limits/laughs.usda" -o "$tmp/x.png" --max-stage-mib 32 >"$tmp/out" 2>&1
check "--max-stage-mib bounds the stage's memory" 3 $? "$tmp/out" 'laughs\.usda:[0-9]+:[0-9]+: .*more than 32 MiB'
"$obscura" render "$src/tests/usda/data/limits/repeated_reference.usda" -o "$tmp/x.png" >"$tmp/out" 2>&1
check "one prim named 1000 times stops at its arc" 3 $? "$tmp/out" 'repeated_reference\.usda:7:[0-9]+: .*more than 10000 composition arcs contribute to </T>'
"$obscura" render "$src/tests/usda/data/limits/repeated_reference.usda" -o "$tmp/x.png" --max-index-nodes 20000 >"$tmp/out" 2>&1
check "--max-index-nodes is settable" 3 $? "$tmp/out" 'more than 20000 composition arcs'

# Variant fallbacks: a set without an authored selection takes the first listed variant it has.
scene="$src/tests/harness/data/variant_fallback.usda"
"$obscura" render "$scene" -o "$tmp/none.png" --width 32 --height 32 >"$tmp/out" 2>&1
check "a variant set without a selection is ignored, with a warning" 0 $? "$tmp/out" \
    'variant_fallback\.usda:10:[0-9]+: variantSet "shape" of </Model> has no selection'
"$obscura" render "$scene" -o "$tmp/box.png" --width 32 --height 32 --variant-fallback shape=cone,box >"$tmp/out" 2>&1
check "--variant-fallback takes the first variant the set has" 0 $?
! grep -q "has no selection" "$tmp/out"; check "a set with a fallback is not reported" 0 $?
"$obscura" render "$scene" -o "$tmp/ball.png" --width 32 --height 32 --variant-fallback shape=ball >"$tmp/out" 2>&1
check "--variant-fallback of another variant" 0 $?
"$obscura" compare "$tmp/box.png" "$tmp/ball.png" --psnr-min 60 >"$tmp/out" 2>&1
check "the fallback chooses what is drawn" 1 $?
"$obscura" compare "$tmp/none.png" "$tmp/box.png" --psnr-min 60 >"$tmp/out" 2>&1
check "without a fallback the variant is not drawn" 1 $?
"$obscura" render "$scene" -o "$tmp/x.png" --variant-fallback shape >"$tmp/out" 2>&1
check "a fallback without variants is a usage error" 2 $? "$tmp/out" "'shape' is not SET=VARIANT"
# Plugins' UsdVariantFallbacks on PXR_PLUGINPATH_NAME, as UsdStage reads them; --variant-fallback wins.
mkdir -p "$tmp/looks" "$tmp/broken"
printf '{"Plugins": [{"Name": "looks", "Info": {"UsdVariantFallbacks": {"shape": ["cone", "box"]}}}]}\n' >"$tmp/looks/plugInfo.json"
printf '{\n  "Plugins": [,]\n}\n' >"$tmp/broken/plugInfo.json"
PXR_PLUGINPATH_NAME="$tmp/broken:$tmp/looks" "$obscura" render "$scene" -o "$tmp/plug.png" --width 32 --height 32 >"$tmp/out" 2>&1
check "a malformed plugInfo.json is named at its line and column" 0 $? "$tmp/out" 'broken/plugInfo\.json:2:15: malformed plugInfo\.json'
"$obscura" compare "$tmp/box.png" "$tmp/plug.png" --psnr-min 60 >"$tmp/out" 2>&1
check "a plugin's fallback chooses what is drawn" 0 $?
PXR_PLUGINPATH_NAME="$tmp/looks" "$obscura" render "$scene" -o "$tmp/plug.png" --width 32 --height 32 \
    --variant-fallback shape=ball >"$tmp/out" 2>&1
check "--variant-fallback over a plugin's" 0 $?
"$obscura" compare "$tmp/ball.png" "$tmp/plug.png" --psnr-min 60 >"$tmp/out" 2>&1
check "the command line's fallback wins" 0 $?

"$obscura" render "$tmp/does-not-exist.usda" -o "$tmp/x.png" >"$tmp/out" 2>&1
check "missing scene file" 3 $? "$tmp/out" 'does-not-exist'
"$obscura" render "$src/scenes/demo.usda" -o "$tmp/x.tiff" >"$tmp/out" 2>&1
check "unknown output type is a usage error" 2 $?
"$obscura" render "$src/scenes/demo.usda" -o "$tmp/x.png" --set noSuchSetting=1 >"$tmp/out" 2>&1
check "unknown setting is a usage error" 2 $? "$tmp/out" 'noSuchSetting'
"$obscura" render "$src/scenes/demo.usda" -o "$tmp/x.png" --width 32 --height 18 --set taa:mode=3tx >"$tmp/out" 2>&1
check "a bad setting value names the accepted ones" 2 $? "$tmp/out" "taa:mode: '3tx' is not one of 1tx.2tx"
"$obscura" render "$src/scenes/demo.usda" -o "$tmp/aa2.exr" --width 32 --height 18 --set taa:mode=2tx >"$tmp/out" 2>&1
check "render with SMAA 2TX" 0 $?
"$obscura" frobnicate >"$tmp/out" 2>&1
check "unknown command is a usage error" 2 $?

OBSCURA_DEVICE=llvmpipe "$obscura" render "$src/scenes/demo.usda" -o "$tmp/x.png" --width 16 --height 16 >"$tmp/out" 2>&1
check "OBSCURA_DEVICE picks a device by name" 0 $?
OBSCURA_DEVICE=0 "$obscura" render "$src/scenes/demo.usda" -o "$tmp/x.png" --width 16 --height 16 >"$tmp/out" 2>&1
check "OBSCURA_DEVICE picks a device by index" 0 $?
OBSCURA_DEVICE=no-such-gpu "$obscura" render "$src/scenes/demo.usda" -o "$tmp/x.png" >"$tmp/out" 2>&1
check "an unknown OBSCURA_DEVICE is a device failure" 4 $? "$tmp/out" "no Vulkan device matches 'no-such-gpu'"

# A harness copied away from its plugin, with no search path: a clear failure, exit 4.
mkdir -p "$tmp/lonely/bin" && cp "$obscura" "$tmp/lonely/bin/"
OBSCURA_PLUGINPATH= "$tmp/lonely/bin/obscura" render "$src/scenes/demo.usda" -o "$tmp/x.png" >"$tmp/out" 2>&1
check "missing plugin" 4 $? "$tmp/out" 'no renderer plugin found'
# The ABI version the harness speaks: the header's (one owner).
abi=$(sed -n 's/^#define OBSCURA_ABI_VERSION_MAJOR \([0-9]*\).*/\1/p' "$src/include/obscura/obscura.h")\\.$(
    sed -n 's/^#define OBSCURA_ABI_VERSION_MINOR \([0-9]*\).*/\1/p' "$src/include/obscura/obscura.h")
# A plugin that only speaks ABI 2: refused by version negotiation, exit 4.
OBSCURA_PLUGINPATH="$fake_plugin" "$tmp/lonely/bin/obscura" render "$src/scenes/demo.usda" -o "$tmp/x.png" >"$tmp/out" 2>&1
check "ABI mismatch" 4 $? "$tmp/out" "does not provide ABI $abi"
OBSCURA_PLUGINPATH="$(dirname "$obscura")/../lib/obscura/plugin" "$tmp/lonely/bin/obscura" info >"$tmp/out" 2>&1
check "OBSCURA_PLUGINPATH finds the plugin" 0 $? "$tmp/out" "loaded: Obscura, ABI $abi"
# OpenUSD's plugInfo.json may begin with '#' comments (usdGenSchema writes them): still found.
cp -r "$(dirname "$obscura")/../lib/obscura/plugin/obscura" "$tmp/commented"
sed -i '1i # Portions of this file auto-generated by usdGenSchema.' "$tmp/commented/plugInfo.json"
OBSCURA_PLUGINPATH="$tmp/commented" "$tmp/lonely/bin/obscura" info >"$tmp/out" 2>&1
check "a plugInfo.json with # comments" 0 $? "$tmp/out" "loaded: Obscura, ABI $abi"

# A UsdUVTexture network (Material -> UsdPreviewSurface <- UsdUVTexture <- UsdPrimvarReader_float2);
# delegate_tests (TexturedUsda) checks its pixels.
"$obscura" render "$src/tests/harness/data/textured.usda" -o "$tmp/textured.exr" --width 32 --height 32 \
    --aov albedo >"$tmp/out" 2>&1
check "textured scene renders to EXR" 0 $?

# A UsdTransform2d between the primvar reader and the texture (its scale on the material's
# interface) draws what st scaled in the mesh draws (30 dB: lavapipe misreads the transform on the
# one-pixel line where the plane's two triangles meet, material_inputs.glsl); without it the
# image is another (11 dB).
"$obscura" render "$src/tests/harness/data/texture_transform.usda" -o "$tmp/transform.png" --width 32 --height 32 \
    --set textures:compression=off >"$tmp/out" 2>&1
check "render a texture behind a UsdTransform2d" 0 $?
! grep -qE "not supported|ignored" "$tmp/out"; check "the UsdTransform2d is followed, not reported" 0 $?
"$obscura" render "$src/tests/harness/data/texture_tiled_uv.usda" -o "$tmp/tiled_uv.png" --width 32 --height 32 \
    --set textures:compression=off >"$tmp/out" 2>&1
check "render the same tiling from the mesh's st" 0 $?
"$obscura" compare "$tmp/transform.png" "$tmp/tiled_uv.png" --psnr-min 25 >"$tmp/out" 2>&1
check "UsdTransform2d scale (2, 2) matches st scaled by 2" 0 $?
"$obscura" render "$src/tests/harness/data/textured.usda" -o "$tmp/untiled.png" --width 32 --height 32 \
    --set textures:compression=off >"$tmp/out" 2>&1
"$obscura" compare "$tmp/transform.png" "$tmp/untiled.png" --psnr-min 25 >"$tmp/out" 2>&1
check "the untransformed texture is another image" 1 $?

finish
