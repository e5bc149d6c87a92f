#!/usr/bin/env bash
# LPV benchmark through gi-render's per-pass GPU timestamps (run by hand, never by ctest):
#   tests/bench/lpv_bench.sh [build-dir]
# Prints ms per propagation step at 32^3 and 64^3 (from the difference between 17 and 1 steps,
# so fixed costs cancel) and the LPV passes on Sponza at 800x600 with 3 cascades of 32^3 and 8
# steps, the configuration the issue compares with a peer implementation (5675 ms per frame).
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

pass() {  # pass NAME: the pass's GPU ms from the last stats.json
  python3 -c "import json,sys; s=json.load(open('$out/stats.json')); print(sum(p['gpuMs'] for p in s['passes'] if p['name']==sys.argv[1]))" "$1"
}

for res in 32 64; do
  declare -A ms
  for steps in 1 17; do
    "$build/app/gi-render" presets/lpv_cornell.json --set lpv.gridResolution=$res --set lpv.propagationSteps=$steps \
      --width 320 --height 240 --frames 3 --out "$out" >/dev/null
    ms[$steps]=$(pass lpv.propagate)
  done
  python3 -c "print('propagation %d^3: %.2f ms per step' % ($res, (${ms[17]} - ${ms[1]}) / 16))"
done

if [ -d ../shared/scenes/sponza_crytek ]; then
  "$build/app/gi-render" presets/sponza.json --set technique=lpv --set lpv.cascadeCount=3 --set lpv.cascadeExtent=10 \
    --set lpv.propagationSteps=8 --set lpv.gridResolution=32 --width 800 --height 600 --frames 4 --out "$out" >/dev/null
  python3 - "$out/stats.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
lpv = [(p['name'], p['gpuMs']) for p in s['passes'] if p['name'].startswith('lpv.')]
total = sum(ms for _, ms in lpv)
print('sponza 800x600, 3 cascades 32^3, 8 steps: ' + ', '.join('%s %.1f ms' % p for p in lpv))
print('LPV passes %.1f ms per frame; the peer spends 5675 ms: %.1fx faster' % (total, 5675.0 / total))
PY
fi
