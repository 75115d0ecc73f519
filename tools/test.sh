#!/usr/bin/env bash
# Installs what is missing, builds warpath and runs the whole test suite:
#   1. Release build, every test; the MovingAI data suite (CTest label `data`) runs too when
#      $WARPATH_DATA or ../shared/data holds the benchmark maps, and the Slurm test (label
#      `cluster`) when Slurm is installed (tools/setup.sh --cluster; skipped otherwise).
#   2. AddressSanitizer + UndefinedBehaviorSanitizer build (-O1 -g1), every test but the data
#      suite and the Slurm test.
#   3. When clang is installed: the libFuzzer harnesses (tests/fuzz, docs/fuzzing.md) built in
#      build-fuzz/ and each run for 10 s from the bundled seeds; a crash, hang or OOM fails.
# Pass --no-sanitizers to skip step 2 and --no-fuzz to skip step 3 while iterating.
set -euo pipefail
cd "$(dirname "$0")/.."

sanitizers=1
fuzz=1
for arg in "$@"; do
  case "$arg" in
    --no-sanitizers) sanitizers=0 ;;
    --no-fuzz) fuzz=0 ;;
    *) echo "usage: tools/test.sh [--no-sanitizers] [--no-fuzz]" >&2; exit 2 ;;
  esac
done

bash tools/setup.sh
jobs=$(nproc)

cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$jobs"
ctest --test-dir build -j "$jobs" --output-on-failure

if ((sanitizers)); then
  # -O1 -g1 (line tables: traces still name file and line) for the libraries, half the
  # compile time of the default -O2 -g; the CLI and test sources compile at -O0 there
  # (WARPATH_FRONT_END_OPTIONS, CMakeLists.txt). The suite's 20-minute budget needs both.
  cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DWARPATH_SANITIZE=ON \
    -DWARPATH_BUILD_BENCHMARKS=OFF -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG"
  cmake --build build-asan -j "$jobs"
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
    ctest --test-dir build-asan -j "$jobs" --output-on-failure --label-exclude 'data|cluster'
fi

if ((fuzz)); then
  if command -v clang++ >/dev/null; then
    bash tools/fuzz.sh --seconds 10
  else
    echo "test: clang++ not found, fuzz harnesses skipped (tools/setup.sh installs clang)"
  fi
fi
