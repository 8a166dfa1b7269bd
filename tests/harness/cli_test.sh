#!/usr/bin/env bash
# The harness's command-line contract (DESIGN.md): outputs, exit codes and error messages.
# usage: cli_test.sh OBSCURA_EXE SOURCE_DIR FAKE_PLUGIN_DIR
set -u
obscura=$1; src=$2; fake_plugin=$3
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
export OBSCURA_VALIDATION=1
pass=0; fail=0
check() {  # check NAME EXPECTED_CODE ACTUAL_CODE [OUTPUT_FILE PATTERN]
    local name=$1 want=$2 got=$3
    if [ "$got" != "$want" ]; then
        echo "FAIL $name: exit $got, expected $want"; [ -n "${4:-}" ] && sed 's/^/    /' "$4"; fail=$((fail + 1)); return
    fi
    if [ -n "${4:-}" ] && ! grep -qE "$5" "$4"; then
        echo "FAIL $name: output lacks /$5/:"; sed 's/^/    /' "$4"; fail=$((fail + 1)); return
    fi
    echo "ok   $name"; pass=$((pass + 1))
}

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
grep -q "prim type 'Cube' is not supported" "$tmp/out"; check "unsupported prim types warned once" 0 $?
[ -s "$tmp/bad.png" ]; check "the rest still renders" 0 $?
"$obscura" render "$src/tests/harness/data/no_camera.usda" -o "$tmp/x.exr" --aov color,depth >"$tmp/out" 2>&1
check "scene without camera is framed" 0 $? "$tmp/out" 'no camera; framing'

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
# A plugin that only speaks ABI 2: refused by version negotiation, exit 4.
OBSCURA_PLUGINPATH="$fake_plugin" "$tmp/lonely/bin/obscura" render "$src/scenes/demo.usda" -o "$tmp/x.png" >"$tmp/out" 2>&1
check "ABI mismatch" 4 $? "$tmp/out" 'does not provide ABI 1\.1'
OBSCURA_PLUGINPATH="$(dirname "$obscura")/../plugin" "$tmp/lonely/bin/obscura" info >"$tmp/out" 2>&1
check "OBSCURA_PLUGINPATH finds the plugin" 0 $? "$tmp/out" 'loaded: Obscura, ABI 1\.1'

# A UsdUVTexture network (Material -> UsdPreviewSurface <- UsdUVTexture <- UsdPrimvarReader_float2);
# delegate_tests (TexturedUsda) checks its pixels.
"$obscura" render "$src/tests/harness/data/textured.usda" -o "$tmp/textured.exr" --width 32 --height 32 \
    --aov albedo >"$tmp/out" 2>&1
check "textured scene renders to EXR" 0 $?

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
