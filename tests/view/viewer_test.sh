#!/usr/bin/env bash
# obscura view under Xvfb on lavapipe, driven by a script of input events:
#  - the window's converged image equals `obscura render` of the same camera: the same renderer,
#    camera, settings and size accumulate the same frames, so the presented 8-bit values may differ
#    only by rounding, at most one code value (PSNR >= 20 log10(255/1) = 48.1 dB); a swapped
#    channel, a flipped row order or another camera falls far below;
#  - a click on the left and on the right half picks the quad drawn there (by the scene's
#    construction: tests/view/data/two_quads.usda), also while the primId AOV itself is shown;
#  - orbiting, the HUD, the AOV views and a lens change run; closing the window leaves no Vulkan
#    object alive (validation on: any error fails) and exits 0;
#  - both display paths: the exported memory (shared) and readback;
#  - reading the scene again when its file changes on disk: a script waits for the reload while the
#    test recolours one quad of a copy of the scene; one prim changed, the render after the reload
#    syncs that prim alone (the delegate's count), and the window shows the scene before the edit,
#    then the edited one, each equal to `obscura render` of that file (the same 48 dB) and the two
#    different (below that bound).
#   viewer_test.sh OBSCURA SOURCE_DIR WORK_DIR
set -uo pipefail
obscura=$1 root=$2 work=$3
. "$root/tests/harness/check.sh"
if ! command -v xvfb-run >/dev/null; then echo "xvfb-run not found: install xvfb and xauth" >&2; exit 1; fi
rm -rf "$work" && mkdir -p "$work"
export OBSCURA_VALIDATION=1
scene=$root/tests/view/data/two_quads.usda

"$obscura" render "$scene" --camera /World/Camera --width 64 --height 48 -o "$work/render.png" 2>"$work/render.log"
check "obscura render of the scene camera" 0 $?

for display in shared readback; do
    cat >"$work/$display.script" <<SCRIPT
key H                          # the HUD off: the window shows the image alone
wait-converged
screenshot $work/$display.png
click 16 24                    # the left quad
click 48 24                    # the right quad
key H
aov normal
frames 2
aov primId
click 40 24                    # the right quad again, while the primId AOV itself is shown
aov display
press left 32 24               # orbit, then back to the scene camera
move 40 24
release left 40 24
lens fStop 2.8
frames 2
key 1
wait-converged
close
SCRIPT
    xvfb-run -a -s "-screen 0 320x240x24" "$obscura" view "$scene" --width 64 --height 48 --display "$display" \
        --script "$work/$display.script" >"$work/$display.out" 2>"$work/$display.err"
    code=$?
    check "view ($display) runs the script and closes cleanly" 0 $code
    check "view ($display): no Vulkan validation error, nothing left alive" 0 "$(grep -c 'error:' "$work/$display.err")"
    [ $code -eq 0 ] || sed 's/^/    /' "$work/$display.err"
    check "view ($display): a click on the left picks /World/Left" 0 0 "$work/$display.out" '^pick 16 24: /World/Left$'
    check "view ($display): a click on the right picks /World/Right" 0 0 "$work/$display.out" '^pick 48 24: /World/Right$'
    check "view ($display): a click in the primId view picks /World/Right" 0 0 "$work/$display.out" \
        '^pick 40 24: /World/Right$'
    "$obscura" compare "$work/$display.png" "$work/render.png" --psnr-min 48 >"$work/$display.compare" 2>&1
    check "view ($display): the window equals obscura render of the same camera" 0 $? "$work/$display.compare" '.*'
done

# Reloading: the viewer watches a copy of the scene; the edit recolours the left quad.
watched=$work/watched.usda
cp "$scene" "$watched"
recolour() { sed 's/displayColor = \[(0.8, 0.2, 0.1)\]/displayColor = [(0.1, 0.8, 0.2)]/' "$scene"; }
recolour >"$work/edited.usda"
check "the edit changes one line of the scene" 1 "$(diff "$scene" "$work/edited.usda" | grep -c '^>')"
"$obscura" render "$work/edited.usda" --camera /World/Camera --width 64 --height 48 -o "$work/edited.png" \
    2>"$work/edited.log"
check "obscura render of the edited scene" 0 $?
cat >"$work/reload.script" <<SCRIPT
key H
wait-converged
screenshot $work/before.png
wait-reload
wait-converged
screenshot $work/after.png
close
SCRIPT
# Bounded: a viewer that never noticed the edit would wait for ever.
timeout 300 xvfb-run -a -s "-screen 0 320x240x24" "$obscura" view "$watched" --width 64 --height 48 \
    --script "$work/reload.script" >"$work/reload.out" 2>"$work/reload.err" &
viewer=$!
# The edit once the first screenshot is written, saved as editors save: a whole file renamed into place.
for _ in $(seq 1200); do
    [ -s "$work/before.png" ] || ! kill -0 $viewer 2>/dev/null && break
    sleep 0.1
done
recolour >"$watched.saving" && mv "$watched.saving" "$watched"
wait $viewer
code=$?
check "view (reload) runs the script and closes cleanly" 0 $code
[ $code -eq 0 ] || sed 's/^/    /' "$work/reload.err"
check "view (reload): no Vulkan validation error, nothing left alive" 0 "$(grep -c 'error:' "$work/reload.err")"
check "view (reload): one prim changed" 0 0 "$work/reload.out" "^reloaded $watched: 1 prim changed$"
check "view (reload): the render after it synced that prim alone" 0 0 "$work/reload.out" \
    '^synced 1 prim after the reload$'
"$obscura" compare "$work/before.png" "$work/render.png" --psnr-min 48 >"$work/before.compare" 2>&1
check "view (reload): before the edit the window equals obscura render of the scene" 0 $? "$work/before.compare" '.*'
"$obscura" compare "$work/after.png" "$work/edited.png" --psnr-min 48 >"$work/after.compare" 2>&1
check "view (reload): after it the window equals obscura render of the edited scene" 0 $? "$work/after.compare" '.*'
"$obscura" compare "$work/after.png" "$work/before.png" --psnr-min 48 >"$work/changed.compare" 2>&1
check "view (reload): the window changed with the edit" 1 $? "$work/changed.compare" '.*'
finish
