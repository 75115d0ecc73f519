#!/usr/bin/env bash
# Installs what is missing, builds warpath and runs the main job on a bundled map: a tank
# (size 3, ground only) and an infantry unit (size 1, ground/swamp/trees) plan routes across
# a river. The tank must take the bridge; the infantry wades the ford and cuts through forest.
set -euo pipefail
cd "$(dirname "$0")/.."

bash tools/setup.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$(nproc)" --target rts >/dev/null

map=assets/maps/crossing.map
echo "== tank: size 3, capability ground"
build/tools/rts path "$map" --size 3 --capability ground --from 3,20 --to 56,22 --draw
echo
echo "== infantry: size 1, capability ground,swamp,trees"
build/tools/rts path "$map" --size 1 --capability ground,swamp,trees --from 3,20 --to 56,22 --draw
