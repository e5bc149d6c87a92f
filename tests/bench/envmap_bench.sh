#!/usr/bin/env bash
# Environment prefilter benchmark (run by hand, never by ctest):
#   tests/bench/envmap_bench.sh [build-dir]
# The prefilter of a 256^2 cube (the default) from ../shared/envmaps/studio_small_03_1k.hdr (or
# builtin:sky without ../shared) at 64 and 200 samples (the seed's recommended count; it took
# 28 s on the CPU), GGX and the seed's Beckmann cone, and a 1024^2 cube at 64 (the seed's size,
# all 11 of its mips): the load (latlong -> cube + source mips) and each mip's time, from
# stats.json (CPU clock around each finished dispatch).
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
map=studio_small_03_1k.hdr
[ -f ../shared/envmaps/$map ] || map=builtin:sky

run() {  # run LABEL --set ...
  local label=$1
  shift
  "$build/app/gi-render" presets/environment_spheres.json --width 64 --height 48 --out "$out" \
    --set environment.file=$map "$@" >/dev/null
  python3 - "$out/stats.json" "$label" <<'PY'
import json, sys
e = json.load(open(sys.argv[1]))['environment']
mips = e['mips']
total = sum(m['ms'] for m in mips)
print('%s: load %.0f ms, prefilter %.0f ms: %s' % (sys.argv[2], e['loadMs'], total,
      ', '.join('mip %d (r %.2f, %d^2) %.1f' % (i, m['roughness'], m['size'], m['ms']) for i, m in enumerate(mips))))
PY
}

for samples in 64 200; do
  for dist in ggx beckmannCone; do
    run "256^2 $dist $samples samples" --set environment.cubeSize=256 --set environment.samples=$samples \
      --set environment.distribution=$dist
  done
done
run "1024^2 ggx 64 samples" --set environment.cubeSize=1024 --set environment.samples=64
