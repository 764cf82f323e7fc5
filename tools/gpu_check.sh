#!/usr/bin/env bash
# tools/gpu_check.sh BUILD OUT: gridrt on another OpenCL device (a GPU), on a machine that
# has gridrt's binaries but no OpenImageIO, no Embree and no PoCL. On the first OpenCL
# device it runs the test suites that drive the device (conformance, stability,
# watertight, uneven scenes, the pair bounds, phase 2's ties, the renderer's passes), the
# Whitted frames (tools/bench.py whitted) and the paper's experiment (tools/bench.py
# paper), and writes into OUT:
#   log.txt            everything, in the order it ran, with UTC times
#   whitted.csv/.png   tools/bench.py whitted (the Embree rows left out: no Embree there)
#   paper.csv/.png     tools/bench.py paper
#   images.tgz         the default scene's Whitted frame (640x480, depth 5) by gridrt on the
#                      device and by the exact host reference, as PNG, to compare elsewhere
#   layouts.csv        both PE kernel layouts (--pe-layout packets, lanes) and both batch
#                      transfers (--transfer map, copy) in turns, 3 rounds: the default Whitted
#                      frame and the bunny's 1280x960 camera rays, each the median of 10 frames
#                      after a first (frame, kernel phase, the kernels' and the transfers'
#                      own device time, host passes)
# GPU_CHECK_BENCH=0 leaves the two bench.py runs out (a shorter check).
# BUILD is a build folder, or what tools/pack_build.sh packed of one; the tests find the
# source tree and BUILD at the paths they were built with (docs/performance.md, "On other
# devices"). PYTHON: the interpreter for bench.py, with matplotlib (default python3).
set -u
# The suites that drive the device, the conformance suite first (tools/pack_build.sh packs
# the same: tools/gpu_check.sh --suites prints them).
suites="conformance stability watertight uneven_scenes pair_bounds phase2_ties
  interrupt_batches segment_culling light_culling whitted_shading render_passes cl_runtime"
[ "${1:-}" = --suites ] && { echo $suites; exit 0; }
[ $# -eq 2 ] || { echo "usage: tools/gpu_check.sh BUILD OUT | --suites" >&2; exit 2; }
build=$(realpath "$1")
out=$(realpath "$2")
root=$(cd "$(dirname "$0")/.." && pwd)
export GRIDRT_CACHE_DIR=${GRIDRT_CACHE_DIR:-$(mktemp -d)}
export PYTHONUNBUFFERED=1
log=$out/log.txt
step() { echo "== $(date -u +%H:%M:%S) $*" >>"$log"; }

step "machine"
{
  grep -m1 "model name" /proc/cpuinfo
  nproc
  command -v nvidia-smi >/dev/null && nvidia-smi --query-gpu=name,driver_version,memory.total \
    --format=csv,noheader
  "$build/gridrt" --list-devices
} >>"$log" 2>&1 || { step "no OpenCL device: stopped"; exit 1; }

# The suites one at a time, all of them within GPU_CHECK_TEST_SECONDS (default 240), so
# the benchmarks still run after a suite that hangs.
deadline=$((SECONDS + ${GPU_CHECK_TEST_SECONDS:-240}))
for suite in $suites; do
  left=$((deadline - SECONDS))
  [ $left -gt 0 ] || { step "test $suite: no time left"; continue; }
  step "test $suite"
  timeout $left "$build/tests/${suite}_test" --gtest_brief=1 >>"$log" 2>&1
  step "test $suite: exit $?"
done

step "images"
images=$(mktemp -d)
whitted=(--width 640 --height 480 --max-depth 5 -q)
timeout 120 "$build/gridrt" "${whitted[@]}" --stats-json "$images/gridrt.json" -o "$images/gridrt.png" >>"$log" 2>&1
timeout 120 "$build/gridrt" "${whitted[@]}" --accel reference -o "$images/reference.png" >>"$log" 2>&1
tar czf "$out/images.tgz" -C "$images" .
step "images: done"

benches="whitted paper"
[ "${GPU_CHECK_BENCH:-1}" = 0 ] && benches=
for set in $benches; do
  step "bench $set"
  GRIDRT_BINARY="$build/gridrt" timeout 400 "${PYTHON:-python3}" "$root/tools/bench.py" "$set" --frames 7 \
    --out "$out" >>"$log" 2>&1
  step "bench $set: exit $?"
done

# Both PE kernel layouts and both batch transfers in turns on the same frames.
step "layouts"
layouts=$out/layouts.csv
echo "scene,pe_layout,transfer,round,frame_ms,kernel_ms,kernel_device_ms,transfer_device_ms,lists_ms,reduce_ms,shade_ms" >"$layouts"
stats=$(mktemp)
for round in 1 2 3; do
  for run in packets,map packets,copy lanes,map lanes,copy; do
    layout=${run%,*} transfer=${run#*,}
    for scene in whitted bunny; do
      if [ $scene = whitted ]; then
        frame=(--width 640 --height 480 --max-depth 5)
      else
        frame=("$root/scenes/models/bunny.glb" --width 1280 --height 960 --primary-only)
      fi
      timeout 120 "$build/gridrt" "${frame[@]}" -q --repeat 10 --pe-layout $layout \
        --transfer $transfer --stats-json "$stats" -o "$images/layout.png" >>"$log" 2>&1 || continue
      "${PYTHON:-python3}" -c 'import json, sys
s = json.load(open(sys.argv[1]))
print(",".join(sys.argv[2:] + ["%.3f" % s[k] for k in ("frame_ms", "kernel_ms",
      "kernel_device_ms", "transfer_device_ms", "lists_ms", "reduce_ms", "shade_ms")]))' \
        "$stats" $scene $layout $transfer $round >>"$layouts"
    done
  done
done
step "layouts: done"
