#!/usr/bin/env bash
# Installs the Debian packages warpath builds and tests with (and, with --cluster, Slurm and
# munge). Idempotent: prints nothing and touches nothing when every package is already present.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config clang-format
  libgtest-dev libgmock-dev libbenchmark-dev
  libcli11-dev nlohmann-json3-dev libfmt-dev libpng-dev libgif-dev
  libxml2-utils  # xmllint: the tests check rts test's JUnit XML with it
  libbox2d-dev libsdl2-dev libosmesa6-dev libyaml-cpp-dev zlib1g-dev
  # The fuzz harnesses (docs/fuzzing.md): clang 14, and libclang-rt-14-dev, which holds
  # libFuzzer (libclang_rt.fuzzer*.a) and clang's sanitizer runtimes on Debian 12.
  clang libclang-rt-14-dev
  # The HTML report's browser test (headless Chromium), the viewer's test in an X server
  # (Xvfb) and `rts run --video` (the ffmpeg program; its test uses ffprobe from the same).
  chromium xvfb ffmpeg
)

# --cluster: a single-node Slurm for `rts test` shards (tools/cluster/, docs/cluster.md); the
# CTest label `cluster` runs on it and is skipped without it.
cluster_packages=(slurmctld slurmd slurm-client munge)
for arg in "$@"; do
  case "$arg" in
    --cluster) packages+=("${cluster_packages[@]}") ;;
    *) echo "usage: tools/setup.sh [--cluster]" >&2; exit 2 ;;
  esac
done

missing=()
for pkg in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$pkg")
done
((${#missing[@]} == 0)) && exit 0

sudo=()
if ((EUID != 0)); then
  command -v sudo >/dev/null || { echo "setup: need root (or sudo) to install: ${missing[*]}" >&2; exit 1; }
  sudo=(sudo)
fi
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -qq
"${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
