#!/usr/bin/env bash
# Side by side with warthog (issue 15, docs/benchmarks.md "Beside warthog"): every query of each
# shared MovingAI map's .scen, solved by warthog's A*, JPS and JPS2+ and by rts bench scen's aa,
# jps, jps+, haa-hq (one level, and with level 2 of 4x4 blocks), hybrid and hybrid with the JPS+
# attempt; prints the median microseconds per query of each. warthog is never
# part of this project: fetch ShortestPathLab/warthog-core and warthog-jps, build them outside
# (cmake -DCMAKE_BUILD_TYPE=Release -B build in warthog-jps, warthog-core in its extern/), and
# point WARTHOG_JPS at the build folder. Usage: WARTHOG_JPS=DIR tools/bench_warthog.sh [MAP...]
# (MAP: a path under the data's maps/, e.g. bg512/AR0011SR; default: every shared map).
set -euo pipefail
cd "$(dirname "$0")/.."
rts=build/tools/rts
data=${WARPATH_DATA:-../shared/data}/movingai
[[ -x "$rts" ]] || { echo "bench_warthog: build first (cmake --build build)" >&2; exit 2; }
[[ -n "${WARTHOG_JPS:-}" && -x "$WARTHOG_JPS/warthog-jps" ]] ||
  { echo "bench_warthog: set WARTHOG_JPS to warthog-jps's build folder" >&2; exit 2; }
maps=("$@")
if ((${#maps[@]} == 0)); then
  while IFS= read -r m; do maps+=("${m#"$data/maps/"}"); done < <(find "$data/maps" -name '*.map' | sort)
  maps=("${maps[@]%.map}")
fi
median() { sort -n | awk '{v[NR]=$1} END {if (NR) printf "%.1f", (NR%2 ? v[(NR+1)/2] : (v[NR/2]+v[NR/2+1])/2); else printf "-"}'; }
printf '| map | queries | warthog A* | warthog JPS | warthog JPS2+ | warpath AA* | warpath JPS | warpath JPS+ | warpath HAA*-HQ | warpath HAA*-HQ, level 2 | warpath hybrid | warpath hybrid, JPS+ attempt |\n'
printf '|---|---|---|---|---|---|---|---|---|---|---|---|\n'
for m in "${maps[@]}"; do
  map="$data/maps/$m.map"
  scen="$data/scenarios/$m.map.scen"
  row="| $m | $(($(wc -l < "$scen") - 1))"
  wh() { "$1" --alg "$2" --scen "$scen" --map "$map" 2> /dev/null | awk -F'\t' 'NR > 1 {print $8 / 1000}' | median; }
  row+=" | $(wh "$WARTHOG_JPS/extern/warthog-core/warthog" astar)"
  row+=" | $(wh "$WARTHOG_JPS/warthog-jps" jps) | $(wh "$WARTHOG_JPS/warthog-jps" jps2+)"
  for planner in "aa" "jps" "jps+" "haa-hq" "haa-hq --levels 2 --level-two-size 4" "hybrid" \
    "hybrid --attempt jps+"; do
    # shellcheck disable=SC2086
    "$rts" bench scen "$map" "$scen" --algo $planner --rows /tmp/bench_warthog_rows.tsv > /dev/null
    row+=" | $(awk -F'\t' 'NR > 1 {print $12}' /tmp/bench_warthog_rows.tsv | median)"
  done
  echo "$row |"
done
