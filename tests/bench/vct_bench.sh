#!/usr/bin/env bash
# VCT benchmark through gi-render's per-pass GPU timestamps (run by hand, never by ctest):
#   tests/bench/vct_bench.sh [build-dir] [repeats]
# 1. The issue's configuration: cornell at 1280x720, a 64^3 grid, nine diffuse cones plus the
#    specular cone, voxelized every frame (as a peer that rebuilds the grid per frame), at trace
#    scales 1, 0.5 and 0.25, anisotropic with face sides (the defaults), without them at 0.25,
#    and isotropic at 1 and 0.25. The
#    peer's frame is an anchor quoted from issue 17, not measured here (Friduric's VCT rebuilt and
#    run side by side with the project on one idle llvmpipe machine of this kind, 2 cores,
#    2026-12-02): 1538 ms (full-resolution trace, a shadow cone, no specular cone). The 5.9 s
#    this script quoted before was 3-4x too high for this machine kind.
#    Then the steady state (grid and light kept, render.keepStaticWork) beside everything redone.
# 2. Sponza at 640x480 (seed 000's size) per mode (dense, cascaded, clipmap), 64^3 per level.
# Each run renders 3 frames and keeps the last (the first includes shader compilation). Shared
# hosts are noisy (+-20% run to run), so each configuration runs `repeats` times (default 3) and
# the run with the median frame time is reported, with the range of frame times. Beside the time:
# the trace's work (VCT::report: samples per traced pixel and per cone, texture calls per sample)
# and, for the cornell rows, the SSIM of the same settings at 320x180 against the path-traced
# reference (set GI_CACHE_DIR to keep the references between runs).
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
repeats=${2:-3}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

run() {  # run LABEL SCORE PRESET gi-render-args...: repeats runs, then the median one's passes;
         # SCORE 1: also the SSIM of the same settings at 320x180
  local label=$1 score=$2 preset=$3
  shift 3
  for i in $(seq "$repeats"); do
    "$build/app/gi-render" "$preset" --frames 3 --out "$out/run$i" "$@" >/dev/null
  done
  rm -rf "$out/score"
  if [ "$score" = 1 ]; then  # the same settings but the size
    local settings=() skip=0
    for a in "$@"; do
      if [ $skip = 1 ]; then skip=0; continue; fi
      case $a in --width|--height) skip=1 ;; *) settings+=("$a") ;; esac
    done
    "$build/app/gi-render" "$preset" "${settings[@]}" --width 320 --height 180 --score --out "$out/score" >/dev/null
  fi
  python3 - "$out" "$repeats" "$label" <<'PY'
import json, os, sys
out, n, label = sys.argv[1], int(sys.argv[2]), sys.argv[3]
runs = sorted((json.load(open('%s/run%d/stats.json' % (out, i + 1))) for i in range(n)), key=lambda s: s['gpuMsTotal'])
s = runs[len(runs) // 2]
vct = [(p['name'][4:], p['gpuMs']) for p in s['passes'] if p['name'].startswith('vct.')]
mem = sum(v['bytes'] for v in s.get('volumes', [])) / 2**20
w = s.get('vct', {})
print('%s: frame %.1f ms (range %.0f-%.0f over %d runs; %s), VCT volumes %.1f MiB' % (
    label, s['gpuMsTotal'], runs[0]['gpuMsTotal'], runs[-1]['gpuMsTotal'], n,
    ', '.join('%s %.1f' % p for p in vct), mem))
print('  work: %.0f traced pixels, %.1f samples per pixel, %.2f per cone, %.2f texture calls per sample' % (
    w.get('tracedPixels', 0), w.get('samplesPerPixel', 0), w.get('samplesPerCone', 0), w.get('textureCallsPerSample', 0)))
print('  raster work: %s' % ', '.join('%s %d draws, %d triangles' % (p['name'], p.get('draws', 0), p.get('triangles', 0))
                                     for p in s['passes'] if p['name'] in ('shadows', 'gbuffer')))
if os.path.exists(out + '/score/stats.json'):
    print('  the same settings at 320x180: SSIM %.4f against the reference' % json.load(open(out + '/score/stats.json'))['metrics']['ssim'])
PY
}

cornell=(--width 1280 --height 720 --set vct.gridResolution=64 --set vct.coneSet=nine --set vct.specularCone=true
         --set vct.bounceCount=1 --set vct.revoxelizeEveryFrame=true)
for scale in 1 0.5 0.25; do
  run "cornell 1280x720 64^3 9+1 cones, anisotropic, traceScale $scale" 1 presets/vct_cornell.json "${cornell[@]}" \
    --set vct.traceScale=$scale
done
# Face sides (on by default since issue 13's stop 45): the same atlas without them, and without
# the bounce tail that comes with them.
run "cornell 1280x720 64^3 9+1 cones, anisotropic without face sides, traceScale 0.25" 1 presets/vct_cornell.json \
  "${cornell[@]}" --set vct.traceScale=0.25 --set vct.faceSides=false --set vct.bounceTail=false
for scale in 1 0.25; do
  run "cornell 1280x720 64^3 9+1 cones, isotropic, traceScale $scale" 1 presets/vct_cornell.json "${cornell[@]}" \
    --set vct.traceScale=$scale --set vct.anisotropic=false
done
# The editor's steady state: the grid voxelized once and its light kept under static lights
# (render.keepStaticWork), against the same frame with everything redone.
run "cornell 1280x720 64^3 9+1 cones, anisotropic, traceScale 0.25, steady" 0 presets/vct_cornell.json "${cornell[@]}" \
  --set vct.traceScale=0.25 --set vct.revoxelizeEveryFrame=false
run "cornell 1280x720 64^3 9+1 cones, anisotropic, traceScale 0.25, everything dynamic" 0 presets/vct_cornell.json "${cornell[@]}" \
  --set vct.traceScale=0.25 --set render.keepStaticWork=false

if [ -d ../shared/scenes/sponza_crytek ]; then
  for mode in dense cascaded clipmap; do
    preset=presets/vct_sponza.json
    [ $mode != dense ] && preset=presets/vct_sponza_$mode.json
    run "sponza 640x480 $mode, voxelized every frame" 0 $preset --width 640 --height 480 --set vct.revoxelizeEveryFrame=true
    run "sponza 640x480 $mode, static grid" 0 $preset --width 640 --height 480
  done
fi
