#!/usr/bin/env bash
# Side by side with warthog (issue 15, docs/benchmarks.md "Beside warthog"): every query of each
# shared MovingAI map's .scen, solved by warthog's A*, JPS and JPS2+ and by rts bench scen's aa,
# jps, jps+, haa-hq (one level, and with level 2 of 4x4 blocks), hybrid and hybrid with the JPS+
# attempt; prints the median microseconds per query of each. warthog is never
# part of this project: fetch ShortestPathLab/warthog-core and warthog-jps, build them outside
# (cmake -DCMAKE_BUILD_TYPE=Release -B build in warthog-jps, warthog-core in its extern/), and
# point WARTHOG_JPS at the build folder. Usage: WARTHOG_JPS=DIR tools/bench_warthog.sh [MAP...]
# (MAP: a path under the data's maps/, e.g. bg512/AR0011SR; default: every shared map).
# Medians are over the queries warthog solves: it reads some terrains of the wc3maps512 maps as
# blocked, so it finds no path for most of their queries (the queries column says how many it
# solves), and those cost it almost nothing. RUNS=N: run each N times and print the median of
# the N medians (a single run of a map whose queries take a few microseconds moves by up to a
# third). JUMP_ONLY=1: only the jump point columns (warthog's JPS2+, warpath's JPS+ and the
# hybrid with the JPS+ attempt). HAA_ONLY=1: warthog's JPS2+ beside HAA*-HQ with insertion by
# search and by tables (--insertion tables), at one level and with level 2 of 4x4 blocks.
set -euo pipefail
cd "$(dirname "$0")/.."
rts=build/tools/rts
data=${WARPATH_DATA:-../shared/data}/movingai
runs=${RUNS:-1}
[[ -x "$rts" ]] || { echo "bench_warthog: build first (cmake --build build)" >&2; exit 2; }
[[ -n "${WARTHOG_JPS:-}" && -x "$WARTHOG_JPS/warthog-jps" ]] ||
  { echo "bench_warthog: set WARTHOG_JPS to warthog-jps's build folder" >&2; exit 2; }
[[ "$runs" =~ ^[1-9][0-9]*$ ]] || { echo "bench_warthog: RUNS must be a positive count" >&2; exit 2; }
maps=("$@")
if ((${#maps[@]} == 0)); then
  while IFS= read -r m; do maps+=("${m#"$data/maps/"}"); done < <(find "$data/maps" -name '*.map' | sort)
  maps=("${maps[@]%.map}")
fi
median() { sort -n | awk '{v[NR]=$1} END {if (NR) printf "%.2f\n", (NR%2 ? v[(NR+1)/2] : (v[NR/2]+v[NR/2+1])/2); else print "-"}'; }
# The median of `runs` runs' medians of a command printing one query time a line.
cell() { for ((r = 0; r < runs; ++r)); do "$@" | median; done | grep -v "^-$" | median | awk '{printf "%s", ($1 == "-" ? "-" : sprintf($1 < 10 ? "%.2f" : "%.1f", $1))}'; }
if [[ -n "${HAA_ONLY:-}" ]]; then
  printf '| map | queries (warthog solves) | warthog JPS2+ | HAA*-HQ | HAA*-HQ, tables | HAA*-HQ, level 2 | HAA*-HQ, level 2, tables |\n|---|---|---|---|---|---|---|\n'
  warthog=("$WARTHOG_JPS/warthog-jps jps2+")
  planners=("haa-hq" "haa-hq --insertion tables" "haa-hq --levels 2 --level-two-size 4"
    "haa-hq --levels 2 --level-two-size 4 --insertion tables")
elif [[ -n "${JUMP_ONLY:-}" ]]; then
  printf '| map | queries (warthog solves) | warthog JPS2+ | warpath JPS+ | warpath hybrid, JPS+ attempt |\n|---|---|---|---|---|\n'
  warthog=("$WARTHOG_JPS/warthog-jps jps2+")
  planners=("jps+" "hybrid --attempt jps+")
else
  printf '| map | queries (warthog solves) | warthog A* | warthog JPS | warthog JPS2+ | warpath AA* | warpath JPS | warpath JPS+ | warpath HAA*-HQ | warpath HAA*-HQ, level 2 | warpath HAA*-HQ, level 2, insertion tables | warpath hybrid | warpath hybrid, JPS+ attempt |\n'
  printf '|---|---|---|---|---|---|---|---|---|---|---|---|---|\n'
  warthog=("$WARTHOG_JPS/extern/warthog-core/warthog astar" "$WARTHOG_JPS/warthog-jps jps"
    "$WARTHOG_JPS/warthog-jps jps2+")
  planners=("aa" "jps" "jps+" "haa-hq" "haa-hq --levels 2 --level-two-size 4"
    "haa-hq --levels 2 --level-two-size 4 --insertion tables" "hybrid" "hybrid --attempt jps+")
fi
for m in "${maps[@]}"; do
  map="$data/maps/$m.map"
  scen="$data/scenarios/$m.map.scen"
  # warthog's columns: id, alg, expanded, generated, reopen, surplus, heapops, nanos, plen,
  # pcost (inf when it found no path), ...; the id is the query's number in the scen.
  solved=/tmp/bench_warthog_solved.txt
  "$WARTHOG_JPS/warthog-jps" --alg jps2+ --scen "$scen" --map "$map" 2> /dev/null |
    awk -F'\t' 'NR > 1 && $10 < 1e300 {print $1}' > "$solved"
  row="| $m | $(($(wc -l < "$scen") - 1)) ($(wc -l < "$solved"))"
  wh() { "$1" --alg "$2" --scen "$scen" --map "$map" 2> /dev/null | awk -F'\t' 'NR > 1 && $10 < 1e300 {print $8 / 1000}'; }
  for w in "${warthog[@]}"; do
    # shellcheck disable=SC2086
    row+=" | $(cell wh $w)"
  done
  ours() {
    # shellcheck disable=SC2068
    "$rts" bench scen "$map" "$scen" --algo $@ --rows /tmp/bench_warthog_rows.tsv > /dev/null
    # Rows: line (the query's line in the scen, 2 for query 0), ..., microseconds (12th).
    awk -F'\t' 'NR == FNR {solved[$1] = 1; next} FNR > 1 && (($1 - 2) in solved) {print $12}' \
      "$solved" /tmp/bench_warthog_rows.tsv
  }
  for planner in "${planners[@]}"; do
    # shellcheck disable=SC2086
    row+=" | $(cell ours $planner)"
  done
  echo "$row |"
done
