#!/usr/bin/env bash
# `obscura farm` on a single-node Slurm cluster started here (tests/scheduler/slurm_cluster.sh): a range in
# chunks equals a local render of the same frames bit for bit; a task killed mid-frame leaves no partial
# file and `resubmit` completes the range; a scene with an error fails its tasks with the message in
# the logs and `status` says so. usage: farm_test.sh OBSCURA SOURCE_DIR
set -uo pipefail
obscura=$1; src=$2
here=$(cd "$(dirname "$0")" && pwd)
tmp=$(mktemp -d)
export XDG_STATE_HOME=$tmp/state
cleanup() { "$here/slurm_cluster.sh" stop "$tmp/cluster"; rm -rf "$tmp"; }
trap cleanup EXIT
eval "$("$here/slurm_cluster.sh" start "$tmp/cluster")" || { echo "FAILED: no Slurm cluster"; exit 1; }

pass=0; fail=0
check() {  # check NAME CONDITION-EXIT-CODE [DETAIL FILE]
  if [ "$2" -eq 0 ]; then pass=$((pass + 1)); echo "ok: $1"
  else fail=$((fail + 1)); echo "FAILED: $1"; [ -n "${3:-}" ] && [ -f "$3" ] && sed 's/^/  | /' "$3"; fi
}
# wait_for JOB SECONDS: until `farm status` says complete (0) or nothing is running or pending (1).
wait_for() {
  local deadline=$((SECONDS + $2))
  while [ $SECONDS -lt $deadline ]; do
    "$obscura" farm status "$1" >"$tmp/status" 2>&1 && return 0
    grep -q " 0 running, 0 pending" "$tmp/status" && return 1
    sleep 1
  done
  return 1
}

scene=$src/scenes/motion_blur.usda
args=(--width 24 --height 16 --set taa:frames=2)

# 1. Twelve frames in chunks of four, against one local process rendering the same range.
job=$("$obscura" farm submit "$scene" -o "$tmp/range/f.####.exr" --frames 1-12 --chunk 4 \
      --render-args "${args[*]}" 2>"$tmp/submit")
check "submit prints the job id" "$([[ $job =~ ^[0-9]+$ ]]; echo $?)" "$tmp/submit"
wait_for "$job" 300; check "the range completes" $? "$tmp/status"
grep -q "12/12 frames done" "$tmp/status"; check "status counts 12 frames" $? "$tmp/status"
"$obscura" render "$scene" -o "$tmp/local/f.####.exr" --frames 1-12 "${args[@]}" 2>"$tmp/local.log"
same=0
for f in $(seq -f %04g 1 12); do cmp -s "$tmp/range/f.$f.exr" "$tmp/local/f.$f.exr" || same=1; done
check "every farm frame equals the local render, bit for bit" $same
LP_NUM_THREADS=1 "$obscura" render "$scene" -o "$tmp/alone.exr" --frame 5 "${args[@]}" 2>/dev/null
cmp -s "$tmp/alone.exr" "$tmp/range/f.0005.exr"; check "a frame alone, on one lavapipe thread, is the same file" $?
! cmp -s "$tmp/range/f.0001.exr" "$tmp/range/f.0012.exr"; check "the frames differ (the scene moves)" $?
grep -q "frame 5 (1/4) -> .*f.0005.exr: [0-9]* ms on " "$tmp/range/.obscura-farm/f/logs/${job}_1.log"
check "a task's log names each frame, its time and the device" $? "$tmp/range/.obscura-farm/f/logs/${job}_1.log"

# 2. A task killed mid-frame: one task of four slow frames (the reference mode at a larger size),
# cancelled once its first frame is on disk, so while it renders the second.
slow=(--width 64 --height 48 --reference 32)
job=$("$obscura" farm submit "$scene" -o "$tmp/kill/k.####.exr" --frames 1-4 --chunk 4 --render-args "${slow[*]}" \
      2>"$tmp/submit")
deadline=$((SECONDS + 180))
until [ -e "$tmp/kill/k.0001.exr" ] || [ $SECONDS -ge $deadline ]; do sleep 0.1; done
scancel "$job"
deadline=$((SECONDS + 60))
while squeue -h -j "$job" -t running,completing 2>/dev/null | grep -q . && [ $SECONDS -lt $deadline ]; do sleep 0.5; done
sleep 1
[ ! -e "$tmp/kill/k.0004.exr" ]; check "the cancelled task stopped mid-range" $?
! compgen -G "$tmp/kill/.k.partial-*" >/dev/null; check "no partial file after the kill" $?
complete=0
for f in "$tmp"/kill/k.*.exr; do [ -e "$f" ] && { exrheader "$f" >/dev/null 2>&1 || complete=1; }; done
check "every frame file left is a complete EXR" $complete
wait_for "$job" 300
"$obscura" farm status "$job" >"$tmp/status" 2>&1
grep -q "failed: task 0" "$tmp/status"; check "status reports the killed task" $? "$tmp/status"
again=$("$obscura" farm resubmit "$job" 2>"$tmp/resubmit")
check "resubmit requeues what is missing" "$([[ $again =~ ^[0-9]+$ ]]; echo $?)" "$tmp/resubmit"
grep -q "resubmitted tasks 0$" "$tmp/resubmit"; check "only the killed task is resubmitted" $? "$tmp/resubmit"
wait_for "$job" 300; check "the range completes after resubmit" $? "$tmp/status"
"$obscura" render "$scene" -o "$tmp/kill-local/k.####.exr" --frames 1-4 "${slow[@]}" 2>/dev/null
same=0
for f in 0001 0002 0003 0004; do cmp -s "$tmp/kill/k.$f.exr" "$tmp/kill-local/k.$f.exr" || same=1; done
check "the resumed range equals a local render" $same

# 3. A scene with an error: the task fails with exit 3 and the message; status says failed.
mkdir -p "$tmp/bad"
printf '#usda 1.0\ndef Xform "World" {\n    double3 xformOp:translate = (0, 0\n}\n' >"$tmp/bad/broken.usda"
job=$("$obscura" farm submit "$tmp/bad/broken.usda" -o "$tmp/bad/b.####.exr" --frames 1-2 --max-retries 0 \
      --render-args "${args[*]}" 2>"$tmp/submit")
wait_for "$job" 120
"$obscura" farm status "$job" >"$tmp/status" 2>&1
check "status exits 1 for an incomplete range" "$([ $? -eq 1 ]; echo $?)" "$tmp/status"
grep -q "failed: task 0 (frames 1-1): obscura render exit 3" "$tmp/status"; check "status names the failed task and exit 3" $? "$tmp/status"
grep -q "broken.usda:[0-9]*:[0-9]*" "$tmp/bad/.obscura-farm/b/logs/${job}_0.log"
check "the task's log names the file, line and column" $? "$tmp/bad/.obscura-farm/b/logs/${job}_0.log"
"$obscura" farm resubmit "$job" >/dev/null 2>"$tmp/resubmit"
check "a task out of retries is not resubmitted" "$([ $? -eq 3 ]; echo $?)" "$tmp/resubmit"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
