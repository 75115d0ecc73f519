#!/usr/bin/env bash
# Builds the libFuzzer harnesses (tests/fuzz, docs/fuzzing.md) with clang in build-fuzz/,
# prepares their seed corpora from the bundled files and runs each for a while:
#   tools/fuzz.sh [--seconds N] [--build-only] [TARGET...] [-- LIBFUZZER_FLAGS...]
# TARGET: fuzz_map fuzz_scen fuzz_scenario fuzz_replay (default: all four, as many at once as
# there are cores).
# Seeds go to out/fuzz/seeds/TARGET (rebuilt every time), inputs the fuzzer finds to
# out/fuzz/corpus/TARGET (kept between runs), crash/timeout/OOM inputs to
# out/fuzz/artifacts/TARGET/, the fuzzer's output to out/fuzz/logs/TARGET.log. Exits 1 when a
# fuzzer found a crash, a timeout or an OOM; prints each fuzzer's final stats.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=30
build_only=0
targets=()
extra=()
all=(fuzz_map fuzz_scen fuzz_scenario fuzz_replay)
usage() {
  echo "usage: tools/fuzz.sh [--seconds N] [--build-only] [TARGET...] [-- LIBFUZZER_FLAGS...]" >&2
  echo "targets: ${all[*]}" >&2
  exit 2
}
while (($#)); do
  case "$1" in
    --seconds) (($# >= 2)) || usage; seconds=$2; shift 2 ;;
    --seconds=*) seconds=${1#*=}; shift ;;
    --build-only) build_only=1; shift ;;
    --) shift; extra=("$@"); break ;;
    fuzz_map|fuzz_scen|fuzz_scenario|fuzz_replay) targets+=("$1"); shift ;;
    map|scen|scenario|replay) targets+=("fuzz_$1"); shift ;;
    *) usage ;;
  esac
done
[[ "$seconds" =~ ^[0-9]+$ ]] && ((seconds >= 1)) || usage
((${#targets[@]})) || targets=("${all[@]}")

command -v clang++ >/dev/null || { echo "fuzz: clang++ not found (tools/setup.sh installs it)" >&2; exit 2; }

# A lean build: only the harnesses and what they link, no tests or benchmarks.
build=build-fuzz
# -O1 with line tables only (traces keep file and line): 5 % less compile than
# RelWithDebInfo's -O2 -g, which the test suite's 20-minute budget needs.
CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" \
  -DWARPATH_FUZZ=ON -DWARPATH_BUILD_TESTS=OFF -DWARPATH_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build "$build" -j "$(nproc)" --target "${targets[@]}" make_replay_seed
((build_only)) && exit 0

out=out/fuzz
bin=$build/tests/fuzz

# Seed corpora from the bundled files.
seeds() {  # TARGET -> fills $out/seeds/TARGET
  local target=$1 dir=$out/seeds/$1
  rm -rf "$dir"
  mkdir -p "$dir"
  case "$target" in
    fuzz_map)
      # stress512.map (256 KB) only slows the mutator down; the others cover every glyph.
      for f in assets/maps/*.map tests/fixtures/*.map; do
        [[ "$(basename "$f")" == stress512.map ]] || cp "$f" "$dir/"
      done ;;
    fuzz_scen)
      cp tests/fixtures/*.scen "$dir/" ;;
    fuzz_scenario)
      # The scenario, then each file it names under a "==> NAME" line (fuzz_scenario.cpp).
      local s map
      for s in scenarios/*.yaml tests/fuzz/seeds/*.yaml; do
        [[ "$(basename "$s")" == stress_2000.yaml ]] && continue
        {
          cat "$s"
          map=$(sed -n 's/^map: *\([^{ ][^ #]*\).*/\1/p' "$s")
          if [[ -n "$map" ]]; then
            printf '==> %s\n' "$(basename "$map")"
            cat "$(dirname "$s")/$map"
          fi
          printf '==> units.yaml\n'
          cat assets/units.yaml
        } >"$dir/$(basename "$s" .yaml)"
      done ;;
    fuzz_replay)
      # A travel scenario, hashed every tick; a battle, hashed every 10 ticks, with its orders.
      "$bin/make_replay_seed" scenarios/narrow_pass.yaml "$dir/narrow_pass.replay" 20
      "$bin/make_replay_seed" scenarios/river_ambush.yaml "$dir/river_ambush.replay" 60 10
      "$bin/make_replay_seed" scenarios/forest_battle.yaml "$dir/forest_battle.replay" 5
      # A small inline map, every order kind and a reinforcement: cheap to play back.
      "$bin/make_replay_seed" tests/fuzz/seeds/skirmish.yaml "$dir/skirmish.replay" 200 5 ;;
  esac
  # Inputs that once crashed a harness are seeds too.
  if [[ -d tests/fuzz/regressions/$target ]]; then
    find "tests/fuzz/regressions/$target" -type f ! -name 'README*' -exec cp {} "$dir/" \;
  fi
}

# Each fuzzer runs for $seconds, as many at once as there are cores (seeds are prepared first:
# make_replay_seed runs the simulation).
run() {  # TARGET -> the fuzzer's exit status; its output goes to its log
  local target=$1
  local flags=(-max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1
               -artifact_prefix="$out/artifacts/$target/")
  [[ -f tests/fuzz/$target.dict ]] && flags+=(-dict="tests/fuzz/$target.dict")
  UBSAN_OPTIONS=print_stacktrace=1 \
    "$bin/$target" "${flags[@]}" "${extra[@]}" "$out/corpus/$target" "$out/seeds/$target" \
    >"$out/logs/$target.log" 2>&1
}
for target in "${targets[@]}"; do
  seeds "$target"
  mkdir -p "$out/corpus/$target" "$out/artifacts/$target" "$out/logs"
done
declare -A pid_of
running=0
for target in "${targets[@]}"; do
  if ((running >= $(nproc))); then
    wait -n || true
    running=$((running - 1))
  fi
  echo "fuzz: $target for ${seconds}s (log $out/logs/$target.log)"
  run "$target" &
  pid_of[$target]=$!
  running=$((running + 1))
done

failed=()
for target in "${targets[@]}"; do
  status=0
  wait "${pid_of[$target]}" || status=$?
  log=$out/logs/$target.log
  # The last coverage line, then libFuzzer's final stats.
  echo "fuzz: $target:"
  grep -E '^#[0-9]+' "$log" | tail -n 1 || true
  grep -E '^stat::' "$log" | tr '\n' ' ' && echo
  if ((status != 0)); then
    echo "fuzz: $target FAILED (exit $status); artifacts in $out/artifacts/$target/:" >&2
    grep -E 'ERROR: |SUMMARY: |runtime error|Test unit written' "$log" | head -n 10 >&2 || true
    failed+=("$target")
  fi
done
if ((${#failed[@]})); then
  echo "fuzz: failed: ${failed[*]}" >&2
  exit 1
fi
