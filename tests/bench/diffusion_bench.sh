#!/usr/bin/env bash
# Diffusion benchmark through gi-render's per-pass GPU timestamps (run by hand, never by ctest):
#   tests/bench/diffusion_bench.sh [build-dir] [runs]
# For 32^3 and 64^3 grids on the built-in Cornell box: ms per propagation step and per
# voxel-step of seed 001's diffusion (diffusion.propagate with 65 steps minus 1 step, over 64),
# beside LPV's propagation step on a grid of the same size (lpv.propagate, 17 minus 1 steps, over
# 16), each the median and range of `runs` runs (default 3), the bytes a cell-step moves, and the
# SSIM of both techniques' Cornell presets against the path-traced reference, beside their frame time. Seed 001's own figure, 2.8e-5 ms
# per voxel-step on a GeForce GTX 285 (32^3, 64 steps), is quoted from the paper, not measured.
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
runs=${2:-3}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

pass() {  # pass NAME: the pass's GPU ms in the last frame of the last stats.json
  python3 -c "import json,sys; s=json.load(open('$out/stats.json')); print(sum(p['gpuMs'] for p in s['passes'] if p['name']==sys.argv[1]))" "$1"
}

# step PRESET PASS KEY_RES KEY_STEPS RES FEW MANY [KEY=VALUE...]: ms per step, one line per run
step() {
  local preset=$1 name=$2 kres=$3 ksteps=$4 res=$5 few=$6 many=$7
  shift 7
  local extra=()
  for kv in "$@"; do extra+=(--set "$kv"); done
  for ((r = 0; r < runs; ++r)); do
    "$build/app/gi-render" "$preset" --set "$kres=$res" --set "$ksteps=$few" "${extra[@]}" --width 128 --height 96 --frames 3 --out "$out" >/dev/null
    a=$(pass "$name")
    "$build/app/gi-render" "$preset" --set "$kres=$res" --set "$ksteps=$many" "${extra[@]}" --width 128 --height 96 --frames 3 --out "$out" >/dev/null
    b=$(pass "$name")
    python3 -c "print(($b - $a) / ($many - $few))"
  done
}

summary() {  # summary LABEL RES < ms per step lines
  python3 -c "
import statistics, sys
ms = sorted(float(l) for l in sys.stdin if l.strip())
cells = $2 ** 3
med = statistics.median(ms)
print('%-28s %3d^3: %8.3f ms per step (range %.3f-%.3f, %d runs), %.2e ms per voxel-step' % ('$1', $2, med, ms[0], ms[-1], len(ms), med / cells))
"
}

# Bytes one empty cell moves per step (shaders/diffusion/emit.comp and gather.comp): emit reads
# its light (3 vec4) and occupancy, its bounce order, and writes six face fluxes (6 vec4);
# gather reads six face fluxes (6 vec4), occupancy and normal, writes the light (3 vec4) and the
# order. Occupied cells also read and write the accumulation (3 vec4 each way) and emit reads six
# neighbours' occupancy.
python3 -c "
emit = 48 + 4 + 4 + 96
gather = 96 + 4 + 4 + 48 + 4
print('bytes per cell-step: %d (empty cell), %d (occupied); seed 001: 104 floats = 416 bytes' % (emit + gather, emit + gather + 24 + 96))
"
for res in 32 64; do
  # keepStaticWork off: with it the last frame would hold the first frame's solve and propagate nothing.
  step presets/diffusion_cornell.json diffusion.propagate diffusion.gridResolution diffusion.iterations $res 1 65 \
    render.keepStaticWork=false | summary "diffusion (seed 001)" $res
  # One bounce, so a step is one propagation of the grid (LPV's default 2 bounces propagate twice).
  step presets/lpv_cornell.json lpv.propagate lpv.gridResolution lpv.propagationSteps $res 1 17 lpv.bounces=1 lpv.fitGrid=false | summary "LPV (1 bounce)" $res
done
echo "seed 001 (GTX 285, quoted):    32^3: 2.8e-5 ms per voxel-step"
# The quality each technique's Cornell preset buys (its defaults, so a frame rather than a step;
# the steady frame: static lights, so diffusion holds its solve and LPV its injection).
for preset in diffusion_cornell lpv_cornell; do
  if "$build/app/gi-render" presets/$preset.json --width 128 --height 96 --frames 2 --score --out "$out" >/dev/null 2>&1; then
    python3 -c "
import json; s = json.load(open('$out/stats.json')); m = s.get('metrics', s)
print('$preset at 128x96: SSIM %.4f against the reference, %.1f ms a frame' % (m['ssim'], s['gpuMsMedian']))
"
  fi
done
