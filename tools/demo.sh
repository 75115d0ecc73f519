#!/usr/bin/env bash
# Installs what is missing, builds warpath and runs the main job: a bundled battle
# (scenarios/river_ambush.yaml: a blue convoy of tanks, jeeps and riflemen ambushed at a river
# crossing), headless, with its report (JSON and an HTML page), PNG frames, an animated GIF and
# a replay (verified);
# then the travel demo (scenarios/demo.yaml: 64 units of two armies crossing a river map) with
# its report; then plans one tank and one infantry route on a small map to show what the
# planner does with size and terrain.
set -euo pipefail
cd "$(dirname "$0")/.."

bash tools/setup.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$(nproc)" --target rts >/dev/null

out=out/demo
rm -rf "$out/frames"
echo "== scenarios/river_ambush.yaml"
status=0
build/tools/rts run scenarios/river_ambush.yaml --report "$out/report.json" \
  --html "$out/report.html" --replay "$out/battle.replay" --frames "$out/frames" \
  --frame-every 15 --gif "$out/battle.gif" ||
  status=$?
build/tools/rts replay verify "$out/battle.replay"
echo "report: $out/report.json   frames: $out/frames/   animation: $out/battle.gif"
echo "page: $out/report.html (charts and the animation; opens without network)"
echo "replay: $out/battle.replay (watch it: build/tools/rts view $out/battle.replay)"
echo
echo "== scenarios/demo.yaml (travel only: combat off)"
build/tools/rts run scenarios/demo.yaml --quiet --report "$out/demo_report.json" \
  --html "$out/demo_report.html" || status=$?
echo "report: $out/demo_report.json   page: $out/demo_report.html"
echo
echo "== tank (size 3, ground) on assets/maps/crossing.map: must take the bridge"
build/tools/rts path assets/maps/crossing.map --size 3 --capability ground \
  --from 3,20 --to 56,22 --algo haa-hq --png "$out/tank_path.png" --draw
echo
echo "== infantry (size 1, ground/swamp/trees): wades the ford, cuts through the forest"
build/tools/rts path assets/maps/crossing.map --size 1 --capability ground,swamp,trees \
  --from 3,20 --to 56,22 --algo haa-hq --png "$out/infantry_path.png"
echo "routes drawn: $out/tank_path.png $out/infantry_path.png"
exit "$status"
