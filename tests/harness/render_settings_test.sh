#!/usr/bin/env bash
# `obscura render` honours a stage's UsdRender prims as usdrecord and husk do, under its flags:
# tests/harness/data/render_settings.usda names its RenderSettings in renderSettingsPrimPath.
# usage: render_settings_test.sh OBSCURA_EXE SOURCE_DIR
set -u
obscura=$1; src=$2
data="$src/tests/harness/data"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
export OBSCURA_VALIDATION=1
source "$(dirname "$0")/check.sh"
fast="--set taa:frames=2"

# No -o: the product's productName (relative to the working folder), its vars as the AOVs, the
# settings' resolution.
(cd "$tmp" && "$obscura" render "$data/render_settings.usda" $fast >"$tmp/out" 2>&1)
check "the stage's render settings render" 0 $?
[ -s "$tmp/render_settings.exr" ]; check "the product's file is written" 0 $?
if command -v exrheader >/dev/null; then
    exrheader "$tmp/render_settings.exr" >"$tmp/header" 2>&1
    check "the settings' resolution" 0 $? "$tmp/header" 'dataWindow.*\(0 0\) - \(39 29\)'
    grep -qE '^ +Z, ' "$tmp/header" && grep -q 'primId' "$tmp/header" && grep -qE '^ +R, ' "$tmp/header"
    check "the product's vars are the EXR's channels" 0 $?
fi

# The same render with every choice given as flags is the same image: camera, resolution, pixel
# aspect, purposes and AOVs all came from the prims.
"$obscura" render "$data/render_settings.usda" --render-settings /Render/NoSuch -o "$tmp/x.exr" >"$tmp/out" 2>&1
check "--render-settings naming no prim is bad input" 3 $? "$tmp/out" 'render settings </Render/NoSuch> do not exist'
"$obscura" render "$data/render_settings.usda" --render-settings /Render/NotSettings -o "$tmp/x.exr" >"$tmp/out" 2>&1
check "--render-settings naming another type is bad input" 3 $? "$tmp/out" '</Render/NotSettings> is a Xform, not a RenderSettings prim'
printf '#usda 1.0\n(\n    renderSettingsPrimPath = "/Nothing"\n)\n' >"$tmp/empty.usda"
cp "$data/render_settings.usda" "$tmp/plain.usda"
sed -i '/renderSettingsPrimPath/d' "$tmp/plain.usda"
"$obscura" render "$tmp/plain.usda" -o "$tmp/flags.exr" --camera /Near --width 40 --height 30 \
    --aov color,depth,primId --set pixelAspectRatio=1.5 --set includedPurposes=default,render,guide $fast >"$tmp/out" 2>&1
check "the same choices as flags" 0 $?
"$obscura" compare "$tmp/render_settings.exr" "$tmp/flags.exr" --psnr-min 60 >"$tmp/out" 2>&1
check "the prims' choices equal the flags'" 0 $? "$tmp/out" 'psnr inf'
"$obscura" render "$tmp/plain.usda" -o "$tmp/front.exr" --width 40 --height 30 --aov color,depth,primId $fast >"$tmp/out" 2>&1
"$obscura" compare "$tmp/render_settings.exr" "$tmp/front.exr" --psnr-min 60 >"$tmp/out" 2>&1
check "and differ from the defaults (first camera, no guides)" 1 $?

# disableMotionBlur is the render setting motionBlur off: a stage that sublayers the motion-blur
# scene and turns it off renders as the scene does with --set motionBlur=off.
printf '#usda 1.0\n(\n    renderSettingsPrimPath = "/Settings"\n    startTimeCode = 1\n    subLayers = [@%s@]\n)\ndef RenderSettings "Settings"\n{\n    uniform bool disableMotionBlur = 1\n    uniform int2 resolution = (48, 27)\n}\n' \
    "$src/scenes/motion_blur.usda" >"$tmp/still.usda"
"$obscura" render "$tmp/still.usda" -o "$tmp/still.exr" $fast >"$tmp/out" 2>&1
check "a stage with disableMotionBlur renders" 0 $?
"$obscura" render "$src/scenes/motion_blur.usda" -o "$tmp/unblurred.exr" --width 48 --height 27 --set motionBlur=off $fast >"$tmp/out" 2>&1
"$obscura" compare "$tmp/still.exr" "$tmp/unblurred.exr" --psnr-min 60 >"$tmp/out" 2>&1
check "disableMotionBlur is motionBlur off" 0 $? "$tmp/out" 'psnr inf'
"$obscura" render "$src/scenes/motion_blur.usda" -o "$tmp/blurred.exr" --width 48 --height 27 $fast >"$tmp/out" 2>&1
"$obscura" compare "$tmp/still.exr" "$tmp/blurred.exr" --psnr-min 60 >"$tmp/out" 2>&1
check "which differs from the blurred scene" 1 $?

# Every product is written, each to its own file with its own resolution and vars; -o names one file,
# so only the first product is then written.
cat >"$tmp/products.usda" <<EOF
#usda 1.0
(
    renderSettingsPrimPath = "/Two"
    subLayers = [@$data/render_settings.usda@]
)
def RenderSettings "Two"
{
    rel camera = </Near>
    uniform int2 resolution = (40, 30)
    rel products = [</Wide>, </Small>]
}
def RenderProduct "Wide"
{
    uniform token productName = "wide.exr"
    rel orderedVars = </Render/Vars/Color>
}
def RenderProduct "Small"
{
    uniform token productName = "small.exr"
    uniform int2 resolution = (20, 10)
    rel orderedVars = [</Render/Vars/Color>, </Render/Vars/Ids>]
}
EOF
(cd "$tmp" && "$obscura" render "$tmp/products.usda" $fast >"$tmp/out" 2>&1)
check "a stage with two products renders" 0 $?
[ -s "$tmp/wide.exr" ] && [ -s "$tmp/small.exr" ]; check "each product's file is written" 0 $?
if command -v exrheader >/dev/null; then
    exrheader "$tmp/wide.exr" >"$tmp/header" 2>&1
    check "the first product: the settings' resolution" 0 $? "$tmp/header" 'dataWindow.*\(0 0\) - \(39 29\)'
    ! grep -q 'primId' "$tmp/header"; check "the first product: its own vars" 0 $?
    exrheader "$tmp/small.exr" >"$tmp/header" 2>&1
    check "the second product: its own resolution" 0 $? "$tmp/header" 'dataWindow.*\(0 0\) - \(19 9\)'
    grep -q 'primId' "$tmp/header"; check "the second product: its own vars" 0 $?
fi
rm -f "$tmp/wide.exr" "$tmp/small.exr"
(cd "$tmp" && "$obscura" render "$tmp/products.usda" -o "$tmp/one.exr" $fast >"$tmp/out" 2>&1)
check "-o writes the first product only" 0 $? "$tmp/out" "names one file: /Two's first product is written, 1 more are not"
[ -s "$tmp/one.exr" ] && [ ! -e "$tmp/small.exr" ]; check "to the file -o names" 0 $?

# Flags override the prims.
"$obscura" render "$data/render_settings.usda" -o "$tmp/small.exr" --width 20 --aov color $fast >"$tmp/out" 2>&1
check "--width overrides the resolution" 0 $?
if command -v exrheader >/dev/null; then
    exrheader "$tmp/small.exr" >"$tmp/header" 2>&1
    check "the flag's width, the settings' height" 0 $? "$tmp/header" 'dataWindow.*\(0 0\) - \(19 29\)'
    ! grep -q 'primId' "$tmp/header"; check "--aov overrides the vars" 0 $?
fi

# Bad data on the prims: each reported with the prim and where it is authored; the rest renders.
"$obscura" render "$data/render_settings.usda" --render-settings /Render/Broken -o "$tmp/broken.exr" --width 32 --height 24 $fast >"$tmp/out" 2>&1
check "broken render settings still render" 0 $?
check "a missing camera" 0 0 "$tmp/out" 'render_settings\.usda:[0-9]+:[0-9]+: warning: /Render/Broken: camera target </Missing> does not exist'
check "a resolution of the wrong type" 0 0 "$tmp/out" 'render_settings\.usda:[0-9]+:[0-9]+: warning: /Render/Broken: resolution is a uniform float2, not a int2'
check "a negative pixel aspect" 0 0 "$tmp/out" '/Render/Broken: pixelAspectRatio must be positive'
check "a conform policy Obscura lacks" 0 0 "$tmp/out" '/Render/Broken: aspectRatioConformPolicy cropAperture is not supported; expandAperture is used'
check "a partial data window" 0 0 "$tmp/out" '/Render/Broken: dataWindowNDC other than \(0, 0, 1, 1\) is not supported'
check "a product that is a var" 0 0 "$tmp/out" '/Render/Broken: products target </Render/Vars/Color> is a RenderVar, not a RenderProduct'
check "a var no AOV answers is reported where it is authored" 0 0 "$tmp/out" \
    'render_settings\.usda:[0-9]+:[0-9]+: warning: /Render/Vars/Diffuse: no AOV answers sourceName "C<RD>\.\*" of sourceType lpe'
check "a var that is a mesh" 0 0 "$tmp/out" '/Render/BrokenProduct: orderedVars target </Quad> is a Mesh, not a RenderVar'
"$obscura" render "$tmp/empty.usda" -o "$tmp/x.exr" --width 16 --height 16 >"$tmp/out" 2>&1
check "a stage naming missing settings renders without them" 0 $? "$tmp/out" 'empty\.usda: warning: renderSettingsPrimPath: render settings </Nothing> do not exist'

finish
