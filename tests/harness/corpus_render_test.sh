#!/usr/bin/env bash
# Renders real scenes written by others (shared/corpus): a production assembly whose geometry is in
# binary crate files and whose materials are MaterialX documents, and USDZ packages. Each must render
# with nothing said against reading it.
# usage: corpus_render_test.sh OBSCURA_EXE CORPUS_DIR   (exit 77, skipped, without the corpus)
set -u
obscura=$1; corpus=$2
if [ ! -d "$corpus" ]; then echo "skipped: no corpus at $corpus"; exit 77; fi
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
export OBSCURA_VALIDATION=1
pass=0; fail=0
for scene in full_assets/OpenChessSet/assets/Rook/Rook.usd full_assets/OpenChessSet/assets/Rook/Rook_geom.usd \
             test_assets/USDZ/RiggedSimple/RiggedSimple.usdz \
             test_assets/NormalsTextureBiasAndScale/NormalsTextureBiasAndScale.usdz; do
    "$obscura" render "$corpus/$scene" -o "$tmp/out.png" --width 48 --height 48 >"$tmp/log" 2>&1
    code=$?
    # Words about reading the scene (its format, a layer, a value, a package) or drawing it.
    if [ $code -ne 0 ] || grep -qiE 'not supported|unsupported|error|cannot (open|read)|corrupt|byte [0-9]+:' "$tmp/log"; then
        echo "FAIL $scene: exit $code"; sed 's/^/    /' "$tmp/log"; fail=$((fail + 1))
    elif [ ! -s "$tmp/out.png" ]; then
        echo "FAIL $scene: no image written"; fail=$((fail + 1))
    else
        echo "ok   $scene"; pass=$((pass + 1))
    fi
done
# The skinned figure is posed by its animation: straight at its first frame, bent mid-way.
rigged="$corpus/test_assets/USDZ/RiggedSimple/RiggedSimple.usdz"
"$obscura" render "$rigged" -o "$tmp/frame1.png" --frame 1 --width 48 --height 48 >"$tmp/log" 2>&1 &&
    "$obscura" render "$rigged" -o "$tmp/frame25.png" --frame 25 --width 48 --height 48 >>"$tmp/log" 2>&1
code=$?
"$obscura" compare "$tmp/frame1.png" "$tmp/frame25.png" --psnr-min 40 >>"$tmp/log" 2>&1
compared=$?
if [ $code -eq 0 ] && [ $compared -eq 1 ]; then
    echo "ok   RiggedSimple.usdz differs between frames 1 and 25"; pass=$((pass + 1))
else
    echo "FAIL RiggedSimple.usdz at frames 1 and 25: exit $code"; sed 's/^/    /' "$tmp/log"; fail=$((fail + 1))
fi
# The same scene as text and packaged (its textures inside the archive) renders the same pixels.
normals="$corpus/test_assets/NormalsTextureBiasAndScale/NormalsTextureBiasAndScale"
"$obscura" render "$normals.usda" -o "$tmp/text.png" --width 48 --height 48 >"$tmp/log" 2>&1 &&
    "$obscura" render "$normals.usdz" -o "$tmp/packaged.png" --width 48 --height 48 >>"$tmp/log" 2>&1
code=$?
if [ $code -eq 0 ] && cmp -s "$tmp/text.png" "$tmp/packaged.png"; then
    echo "ok   NormalsTextureBiasAndScale .usda and .usdz render identically"; pass=$((pass + 1))
else
    echo "FAIL NormalsTextureBiasAndScale .usda and .usdz differ: exit $code"; sed 's/^/    /' "$tmp/log"; fail=$((fail + 1))
fi
# A truncated crate file: exit 3 (bad input) with the byte and what is wrong.
head -c 5000 "$corpus/full_assets/OpenChessSet/assets/Rook/Rook_geom.usd" >"$tmp/truncated.usd"
"$obscura" render "$tmp/truncated.usd" -o "$tmp/out.png" --width 16 --height 16 >"$tmp/log" 2>&1
code=$?
if [ $code -eq 3 ] && grep -q "truncated.usd: byte 16: table of contents at byte .* lies outside the file of 5000 bytes" "$tmp/log"; then
    echo "ok   truncated crate file"; pass=$((pass + 1))
else
    echo "FAIL truncated crate file: exit $code"; sed 's/^/    /' "$tmp/log"; fail=$((fail + 1))
fi
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
