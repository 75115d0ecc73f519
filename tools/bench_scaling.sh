#!/usr/bin/env bash
# Scaling benchmark of issue 15 (docs/benchmarks.md, "Scaling to 2048² and 4096²" and
# "Multi-level HAA*"): generates stress-like maps of 2048 and 4096 cells a side and a 2048² maze
# under out/large/ (tools/generate_maps.py --large, --maze), then, for them and
# assets/maps/stress512.map, runs 50 seeded random queries per planner with `rts bench random
# --json` under /usr/bin/time (build time, graph bytes, query times, error against AA*, peak
# memory), and HAA*-HQ with a second level of 4x4 and 8x8 blocks. Build first (cmake --build
# build).
set -euo pipefail
cd "$(dirname "$0")/.."
rts=build/tools/rts
[[ -x "$rts" ]] || { echo "bench_scaling: build first (cmake --build build)" >&2; exit 2; }
mkdir -p out/large
for size in 2048 4096; do
  [[ -f out/large/stress$size.map ]] ||
    python3 tools/generate_maps.py --large "$size" "out/large/stress$size.map"
done
[[ -f out/large/maze2048-4.map ]] || python3 tools/generate_maps.py --maze 2048 4 out/large/maze2048-4.map
run() {  # MAP ALGO [OPTIONS...]
  echo "== $* load $(cut -d' ' -f1 /proc/loadavg)"
  /usr/bin/time -f "maxrss_kb %M" "$rts" bench random "$@" --queries 50 --json 2>&1
}
for map in assets/maps/stress512.map out/large/stress2048.map out/large/stress4096.map \
  out/large/maze2048-4.map; do
  for algo in aa jps haa-hq haa-lq hybrid; do
    run "$map" --algo "$algo"
  done
  for blocks in 4 8; do
    run "$map" --algo haa-hq --levels 2 --level-two-size "$blocks"
  done
done
