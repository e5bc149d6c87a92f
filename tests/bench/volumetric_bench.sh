#!/usr/bin/env bash
# Volumetric lighting benchmark through gi-render's per-pass GPU timestamps (run by hand, never
# by ctest):  tests/bench/volumetric_bench.sh [build-dir] [size]
# The volumetric passes (march, blur, composite) on the Cornell spot-in-haze preset at
# 100, 200 and 500 samples and resolution scales 0.25, 0.5 and 1 (seed 004 Figs. 3.13 and 3.14:
# 0.9 to 7.94 ms at 1024x1024 on a Radeon R9 290), image size x size (default 512).
# Each run renders 3 frames and keeps the last; each configuration runs 3 times and the run
# with the median march time is reported, with the range.
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
size=${2:-512}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

for samples in 100 200 500; do
  for scale in 0.25 0.5 1; do
    for i in 1 2 3; do
      "$build/app/gi-render" presets/volumetric_cornell.json --width "$size" --height "$size" --frames 3 \
        --out "$out/run$i" --set technique=none --set volumetric.samples=$samples \
        --set volumetric.resolutionScale=$scale >/dev/null
    done
    python3 - "$out" "$samples" "$scale" "$size" <<'PY'
import json, sys
out, samples, scale, size = sys.argv[1:5]
def passes(i):
    s = json.load(open('%s/run%d/stats.json' % (out, i)))
    return {p['name']: p['gpuMs'] for p in s['passes'] if p['name'].startswith('volumetric.')}
runs = sorted((passes(i) for i in (1, 2, 3)), key=lambda p: p['volumetric.march'])
m = runs[1]
total = sum(m.values())
print('%sx%s, %s samples, scale %s: volumetric %.1f ms (march %.1f [%.1f-%.1f], blur %.2f, composite %.1f)' % (
    size, size, samples, scale, total, m['volumetric.march'], runs[0]['volumetric.march'], runs[2]['volumetric.march'],
    m.get('volumetric.blur', 0.0), m['volumetric.composite']))
PY
  done
done
