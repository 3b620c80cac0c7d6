#!/usr/bin/env bash
# Builds and runs the libFuzzer harnesses of tests/fuzz (issue 17, part 3).
#   scripts/fuzz.sh build                 configure (once) and build build-fuzz/ with Debian's clang
#   scripts/fuzz.sh run NAME SECONDS      run fuzz_NAME for SECONDS on its seed corpus (ctest: fuzz.NAME)
#   scripts/fuzz.sh all SECONDS           build, then run every harness for SECONDS each (`make fuzz`)
# The seed corpus is built at run time (scripts/fuzz_seeds.py: the shared scenes, the repository's scenes and the
# committed seeds under tests/fuzz/seeds/); new inputs go to a temporary folder (`run`) or, for `all`, to
# build-fuzz/corpus/NAME so longer runs build on each other. A crash leaves its input in build-fuzz/artifacts/NAME/
# and fails the run: fix the code, then keep the input under tests/fuzz/regressions/NAME/ (tests/unit/fuzz replays it).
# FUZZ_BUILD overrides the build folder (default: build-fuzz/ in the repository root, shared by `make test` and
# `make test-asan` so the second pass builds nothing).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${FUZZ_BUILD:-$root/build-fuzz}"
harnesses=(gltf glb image capture script)

# Input size caps: a seed above the cap is truncated by libFuzzer, so they sit above the largest seed we keep.
max_len() { case "$1" in gltf|glb) echo 262144 ;; image) echo 131072 ;; *) echo 8192 ;; esac; }

build_harnesses() {
  command -v clang++ >/dev/null || { echo "fuzz.sh: clang++ not found (scripts/setup.sh installs clang)" >&2; exit 1; }
  if [ ! -f "$build/build.ninja" ]; then
    local launcher=()
    command -v ccache >/dev/null && launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
    CC=clang CXX=clang++ cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DIDK_FUZZ=ON \
      -DIDK_BUILD_TESTS=OFF "${launcher[@]}" >/dev/null
  fi
  cmake --build "$build" -j "$(nproc)"
}

# run NAME SECONDS CORPUS_DIR
run_harness() {
  local name=$1 seconds=$2 corpus=$3
  local exe="$build/bin/fuzz_$name"
  [ -x "$exe" ] || { echo "fuzz.sh: $exe is not built (scripts/fuzz.sh build)" >&2; exit 1; }
  local seeds; seeds="$(mktemp -d "${TMPDIR:-/tmp}/idk_fuzz_seeds_${name}_XXXXXX")"
  trap 'rm -rf "$seeds"' RETURN
  python3 "$root/scripts/fuzz_seeds.py" "$name" "$seeds"
  mkdir -p "$corpus" "$build/artifacts/$name"
  local dict=()
  [ -f "$root/tests/fuzz/$name.dict" ] && dict=(-dict="$root/tests/fuzz/$name.dict")
  [ "$name" = glb ] && [ -f "$root/tests/fuzz/gltf.dict" ] && dict=(-dict="$root/tests/fuzz/gltf.dict")
  echo "fuzz_$name: $(ls "$seeds" | wc -l) seeds, ${seconds}s" >&2
  # -rss_limit_mb: the loader may legitimately allocate what a file declares (within its checks); 2.5 GiB marks
  # anything beyond as a finding. -timeout: one input taking longer than 20 s is a hang.
  "$exe" -max_total_time="$seconds" -max_len="$(max_len "$name")" -timeout=20 -rss_limit_mb=2560 \
    -print_final_stats=1 -artifact_prefix="$build/artifacts/$name/" "${dict[@]}" "$corpus" "$seeds"
}

case "${1:-}" in
  build) build_harnesses ;;
  run)
    [ $# -eq 3 ] || { echo "usage: fuzz.sh run NAME SECONDS" >&2; exit 2; }
    corpus="$(mktemp -d "${TMPDIR:-/tmp}/idk_fuzz_corpus_$2_XXXXXX")"
    trap 'rm -rf "$corpus"' EXIT
    run_harness "$2" "$3" "$corpus"
    ;;
  all)
    seconds="${2:-120}"
    build_harnesses
    for name in "${harnesses[@]}"; do run_harness "$name" "$seconds" "$build/corpus/$name"; done
    ;;
  *) echo "usage: fuzz.sh build | run NAME SECONDS | all [SECONDS]" >&2; exit 2 ;;
esac
