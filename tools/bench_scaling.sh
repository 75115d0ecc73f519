#!/usr/bin/env bash
# Scaling benchmark of issue 15 (docs/benchmarks.md, "Scaling to 2048² and 4096²"): generates
# stress-like maps of 2048 and 4096 cells a side under out/large/ (tools/generate_maps.py
# --large), then, for them and assets/maps/stress512.map, runs 50 seeded random queries per
# planner with `rts bench random --json` under /usr/bin/time (build time, graph bytes, query
# times, error against AA*, peak memory). Build first (cmake --build build).
set -euo pipefail
cd "$(dirname "$0")/.."
rts=build/tools/rts
[[ -x "$rts" ]] || { echo "bench_scaling: build first (cmake --build build)" >&2; exit 2; }
mkdir -p out/large
for size in 2048 4096; do
  [[ -f out/large/stress$size.map ]] ||
    python3 tools/generate_maps.py --large "$size" "out/large/stress$size.map"
done
for map in assets/maps/stress512.map out/large/stress2048.map out/large/stress4096.map; do
  for algo in aa jps haa-hq haa-lq hybrid; do
    echo "== $map $algo load $(cut -d' ' -f1 /proc/loadavg)"
    /usr/bin/time -f "maxrss_kb %M" "$rts" bench random "$map" --algo "$algo" --queries 50 --json 2>&1
  done
done
