#!/usr/bin/env bash
# VCT benchmark through gi-render's per-pass GPU timestamps (run by hand, never by ctest):
#   tests/bench/vct_bench.sh [build-dir]
# 1. The issue's configuration: cornell at 1280x720, a 64^3 grid, nine diffuse cones plus the
#    specular cone, voxelized every frame (as a peer that rebuilds the grid per frame), at trace
#    scales 1, 0.5 and 0.25; a peer implementation takes 5.9 s per frame on llvmpipe, 2 cores.
# 2. Sponza at 640x480 (seed 000's size) per mode (dense, cascaded, clipmap), 64^3 per level.
# Each run renders 3 frames and reports the last (the first includes shader compilation).
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

report() {  # report LABEL: the VCT passes and the frame total from the last stats.json
  python3 - "$out/stats.json" "$1" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
vct = [(p['name'][4:], p['gpuMs']) for p in s['passes'] if p['name'].startswith('vct.')]
mem = sum(p['memoryBytes'] for p in s['passes'] if p['name'].startswith('vct.')) / 2**20
print('%s: frame %.1f ms (%s), VCT memory %.1f MiB' % (sys.argv[2], s['gpuMsTotal'],
      ', '.join('%s %.1f' % p for p in vct), mem))
PY
}

for scale in 1 0.5 0.25; do
  "$build/app/gi-render" presets/vct_cornell.json --width 1280 --height 720 --frames 3 --out "$out" \
    --set vct.gridResolution=64 --set vct.coneSet=nine --set vct.specularCone=true --set vct.bounceCount=1 \
    --set vct.revoxelizeEveryFrame=true --set vct.traceScale=$scale >/dev/null
  report "cornell 1280x720 64^3 9+1 cones, traceScale $scale"
done

if [ -d ../shared/scenes/sponza_crytek ]; then
  for mode in dense cascaded clipmap; do
    preset=presets/vct_sponza.json
    [ $mode != dense ] && preset=presets/vct_sponza_$mode.json
    "$build/app/gi-render" $preset --width 640 --height 480 --frames 3 --out "$out" --set vct.revoxelizeEveryFrame=true >/dev/null
    report "sponza 640x480 $mode, voxelized every frame"
    "$build/app/gi-render" $preset --width 640 --height 480 --frames 3 --out "$out" >/dev/null
    report "sponza 640x480 $mode, static grid"
  done
fi
