#!/usr/bin/env bash
# Feeds the real CLI one input of each class of bad input from issue 11 (docs/bad_input.md) and
# prints a Markdown table: exit status, wall time, peak resident memory and the first line of
# the message. Every case must exit 2 within 2 s and 200 MB; the script exits 1 when one does
# not.
#   tools/bad_input_check.sh [RTS]      (default: build/tools/rts)
# The inputs are made in a temporary folder (the 2 GiB files are sparse: no disk is used) that
# is removed afterwards.
set -euo pipefail
cd "$(dirname "$0")/.."

rts=$(realpath "${1:-build/tools/rts}")
[[ -x "$rts" ]] || { echo "bad_input_check: build first (cmake --build build)" >&2; exit 2; }
command -v /usr/bin/time >/dev/null || { echo "bad_input_check: needs GNU time (apt-get install time)" >&2; exit 2; }
command -v python3 >/dev/null || { echo "bad_input_check: needs python3" >&2; exit 2; }

max_seconds=2
max_mb=200
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
repo=$(pwd)

# --- the inputs -------------------------------------------------------------------------------
mkdir "$tmp/dir.replay"
mkfifo "$tmp/fifo.replay" "$tmp/fifo.yaml"
truncate -s 2G "$tmp/zeros.replay"
truncate -s 2G "$tmp/zeros.yaml"
truncate -s 2G "$tmp/zeros.map"
truncate -s 2G "$tmp/zeros.json"
mkfifo "$tmp/fifo.json"
python3 -c "import sys; open(sys.argv[1], 'w').write('[' * 2000000 + ']' * 2000000)" "$tmp/deep.json"

# A valid scenario to hang the others on (absolute paths: the files live in $tmp).
scenario() {  # EXTRA_KEYS -> a scenario on the bundled river map with one group
  cat <<EOF
map: $repo/assets/maps/river.map
catalogue: $repo/assets/units.yaml
duration: 10
teams: [blue]
groups:
  - {team: blue, type: infantry, count: 4, spawn: {x: 0, y: 0, w: 6, h: 6}}
$1
EOF
}
scenario "" >"$tmp/ok.yaml"
scenario "" | sed "s|^map: .*|map: /dev/zero|" >"$tmp/map_dev_zero.yaml"
scenario "" | sed "s|^map: .*|map: $tmp/dir.replay|" >"$tmp/map_dir.yaml"

# Nine levels of ten aliases: a billion nodes once expanded, in 0.4 KB.
{
  echo "l0: &l0 [a, a, a, a, a, a, a, a, a, a]"
  for i in 1 2 3 4 5 6 7 8; do
    a="*l$((i - 1))"
    echo "l$i: &l$i [$a, $a, $a, $a, $a, $a, $a, $a, $a, $a]"
  done
} >"$tmp/alias_bomb.yaml"

# One 8192-cell row repeated 8192 times through an alias: a 64 M-cell map in 41 KB.
python3 - "$tmp/alias_map.yaml" "$repo" <<'EOF'
import sys
row = "." * 8192
with open(sys.argv[1], "w") as f:
    f.write("map:\n  rows: [&r '" + row + "'" + ", *r" * 8191 + "]\n")
    f.write("catalogue: " + sys.argv[2] + "/assets/units.yaml\nduration: 1\nteams: [a]\ngroups: []\n")
EOF

# A group of a million units repeated through an alias.
scenario "" | sed '/^groups:/,$d' >"$tmp/alias_units.yaml"
python3 - "$tmp/alias_units.yaml" <<'EOF'
import sys
g = "{team: blue, type: infantry, count: 1000000, spawn: {x: 0, y: 0, w: 3, h: 3}}"
with open(sys.argv[1], "a") as f:
    f.write("groups: [&g " + g + ", *g" * 30 + "]\n")
EOF

scenario "unit_types: {infantry: {radius: 0.6}}" >"$tmp/radius.yaml"
scenario "pathing: {cluster_size: 1}" >"$tmp/cluster.yaml"
scenario "duration: 5" >"$tmp/duplicate_key.yaml"

for depth in 100 5000; do
  {
    scenario ""
    printf 'expectations: %s%s\n' "$(printf '[%.0s' $(seq $depth))" "$(printf ']%.0s' $(seq $depth))"
  } >"$tmp/nested_$depth.yaml"
done

# A replay whose end record claims tick 5,000,000,000 (checksums fixed up): before, `replay
# verify` simulated "forever".
"$rts" run "$tmp/ok.yaml" --quiet --until 30 --replay "$tmp/good.replay" >/dev/null 2>&1 || true
python3 - "$tmp/good.replay" "$tmp/far_tick.replay" <<'EOF'
import struct, sys, zlib
data = bytearray(open(sys.argv[1], "rb").read())
i, end = 12, None
while i + 9 <= len(data):
    length = struct.unpack_from("<I", data, i + 1)[0]
    if data[i] == ord("E"):
        end = i
    i += 9 + length + 4
assert end is not None, "no end record"
length = struct.unpack_from("<I", data, end + 1)[0]
struct.pack_into("<q", data, end + 9 + 1, 5_000_000_000)  # after the reason byte
struct.pack_into("<I", data, end + 9 + length, zlib.crc32(bytes(data[end + 9:end + 9 + length])))
open(sys.argv[2], "wb").write(data)
EOF

# --- the cases --------------------------------------------------------------------------------
cases=(
  "a directory as a replay (verify)|replay verify $tmp/dir.replay"
  "a directory as a replay (info)|replay info $tmp/dir.replay"
  "a FIFO as a replay|replay verify $tmp/fifo.replay"
  "a FIFO as a scenario|run $tmp/fifo.yaml --quiet"
  "/dev/zero as a map|path /dev/zero --from 0,0 --to 1,1"
  "/dev/zero as a scenario|run /dev/zero --quiet"
  "2 GiB of zeros as a replay (verify)|replay verify $tmp/zeros.replay"
  "2 GiB of zeros as a replay (info)|replay info $tmp/zeros.replay"
  "2 GiB of zeros as a scenario|run $tmp/zeros.yaml --quiet"
  "2 GiB of zeros as a map|path $tmp/zeros.map --from 0,0 --to 1,1"
  "map: /dev/zero in a scenario|run $tmp/map_dev_zero.yaml --quiet"
  "map: a directory in a scenario|run $tmp/map_dir.yaml --quiet"
  "replay claiming tick 5e9 (verify)|replay verify $tmp/far_tick.replay"
  "replay claiming tick 5e9 (info)|replay info $tmp/far_tick.replay"
  "replay claiming tick 5e9 (render)|replay render $tmp/far_tick.replay --frames $tmp/frames"
  "YAML alias bomb (10^9 nodes)|run $tmp/alias_bomb.yaml --quiet"
  "aliased inline map 8192x8192|run $tmp/alias_map.yaml --quiet"
  "aliased groups, 31 M units|run $tmp/alias_units.yaml --quiet"
  "nesting 100 levels|run $tmp/nested_100.yaml --quiet"
  "nesting 5000 levels|run $tmp/nested_5000.yaml --quiet"
  "a unit type past its limits (radius)|run $tmp/radius.yaml --quiet"
  "a setting past its limits (cluster_size)|run $tmp/cluster.yaml --quiet"
  "a key given twice (duration)|run $tmp/duplicate_key.yaml --quiet"
  "--until -1|run $tmp/ok.yaml --quiet --until -1"
  "--until 99999999999999999999|run $tmp/ok.yaml --quiet --until 99999999999999999999"
  "--replay-every 0|run $tmp/ok.yaml --quiet --replay $tmp/out.replay --replay-every 0"
  "bench paper --cluster-sizes 0|bench paper $repo/assets/maps/river.map --cluster-sizes 0"
  "a directory as a report (plot)|report plot $tmp/dir.replay --png $tmp/plot.png"
  "a FIFO as a report (plot)|report plot $tmp/fifo.json --png $tmp/plot.png"
  "/dev/zero as a report (plot)|report plot /dev/zero --png $tmp/plot.png"
  "2 GiB of zeros as a report (plot)|report plot $tmp/zeros.json --png $tmp/plot.png"
  "a report nested 2,000,000 deep (plot)|report plot $tmp/deep.json --png $tmp/plot.png"
)

failed=0
echo "| input | command | exit | wall s | peak MB | first line of the message |"
echo "|---|---|---|---|---|---|"
for entry in "${cases[@]}"; do
  name=${entry%%|*}
  args=${entry#*|}
  # shellcheck disable=SC2086 # the arguments hold no spaces
  /usr/bin/time -v -o "$tmp/time" timeout 60 "$rts" $args >"$tmp/out" 2>&1 && status=0 || status=$?
  wall=$(awk -F': ' '/Elapsed \(wall clock\)/ {n = split($2, p, ":"); s = 0;
          for (i = 1; i <= n; ++i) s = s * 60 + p[i]; printf "%.2f", s}' "$tmp/time")
  kb=$(awk -F': ' '/Maximum resident set size/ {print $2}' "$tmp/time")
  mb=$(awk -v kb="$kb" 'BEGIN {printf "%.0f", kb / 1024}')
  first=$(grep -m1 -v '^$' "$tmp/out" | sed "s|$tmp|TMP|g; s|$repo/||g; s/|/\\\\|/g" || true)
  shown=$(sed "s|$tmp|TMP|g; s|$repo/||g" <<<"$args")
  verdict=""
  if ((status != 2)) || awk -v w="$wall" -v m="$max_seconds" 'BEGIN {exit !(w > m)}' ||
    ((mb > max_mb)); then
    verdict=" **MISSES**"
    failed=1
  fi
  echo "| $name | \`rts $shown\` | $status$verdict | $wall | $mb | \`${first:0:150}\` |"
done
rm -rf "$tmp/frames"
if ((failed)); then
  echo "bad_input_check: a case missed exit 2 within ${max_seconds} s and ${max_mb} MB" >&2
  exit 1
fi
