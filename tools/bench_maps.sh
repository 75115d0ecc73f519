#!/usr/bin/env bash
# Runs `rts bench scen` on every map of the shared MovingAI data for each planner and prints
# one Markdown table row per (map, planner): the figures in docs/benchmarks.md.
#   tools/bench_maps.sh [DATA_DIR] [ALGO ...]    (defaults: ../shared/data/movingai, aa)
# Extra `rts bench scen` options go in $BENCH_OPTIONS (e.g. "--bucket-min 100").
set -euo pipefail
cd "$(dirname "$0")/.."
data=${1:-${WARPATH_DATA:-../shared/data}}
[[ -d "$data/movingai/maps" ]] && data="$data/movingai"
shift || true
algos=("$@")
((${#algos[@]})) || algos=(aa)
rts=build/tools/rts
[[ -x "$rts" ]] || { echo "bench_maps: build first (cmake --build build)" >&2; exit 2; }

echo "| map | algo | queries | optimal | mean subopt % | max subopt % | median µs | p95 µs | mean expanded | expansions/s | preprocess ms |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for map in "$data"/maps/*/*.map; do
  family=$(basename "$(dirname "$map")")
  scen="$data/scenarios/$family/$(basename "$map").scen"
  [[ -f "$scen" ]] || continue
  for algo in "${algos[@]}"; do
    # A map whose scen has no query left (e.g. under --bucket-min) is skipped, not fatal.
    # shellcheck disable=SC2086
    if ! summary=$("$rts" bench scen "$map" "$scen" --algo "$algo" ${BENCH_OPTIONS:-} 2>/dev/null); then
      continue
    fi
    awk -v name="$family/$(basename "$map" .map)" -v algo="$algo" '
      { value[$1] = $2 }
      END {
        printf "| %s | %s | %d | %d | %.2f | %.2f | %.1f | %.1f | %.0f | %.2fM | %.1f |\n",
          name, algo, value["queries"], value["optimal_matches"],
          value["mean_suboptimality_pct"], value["max_suboptimality_pct"], value["median_us"],
          value["p95_us"], value["mean_expanded"], value["expanded_per_second"] / 1e6,
          value["preprocess_ms"]
      }' <<<"$summary"
  done
done
