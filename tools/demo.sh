#!/usr/bin/env bash
# Installs what is missing, builds warpath and runs the main job: the bundled demo battle
# (scenarios/demo.yaml: 64 infantry, jeeps, tanks and amphibious units of two teams crossing a
# river map), headless, with its report, PNG frames, an animated GIF and a replay (verified);
# then plans one tank and one infantry route on a small map to show what the planner does with
# size and terrain.
set -euo pipefail
cd "$(dirname "$0")/.."

bash tools/setup.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$(nproc)" --target rts >/dev/null

out=out/demo
rm -rf "$out/frames"
echo "== scenarios/demo.yaml"
status=0
build/tools/rts run scenarios/demo.yaml --report "$out/report.json" --replay "$out/demo.replay" \
  --frames "$out/frames" --frame-every 15 --gif "$out/demo.gif" || status=$?
build/tools/rts replay verify "$out/demo.replay"
echo "report: $out/report.json   frames: $out/frames/   animation: $out/demo.gif"
echo "replay: $out/demo.replay (watch it: build/tools/rts view $out/demo.replay)"
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
