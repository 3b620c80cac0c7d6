#!/usr/bin/env bash
# accept_goldens.sh [BUILD_DIR] [GTEST_FILTER]: deliberately regenerates golden images (tests/golden/*.png) from the
# current renderer: builds the GPU test executables that have golden tests (PBR, animation, transparency) and runs
# their *MatchesGolden* tests (or only those matching GTEST_FILTER, e.g. '*MatchesGolden/cornell_box') with
# IDK_ACCEPT_GOLDENS=1, which writes the rendered frame instead of comparing it. Render goldens on lavapipe (the CI
# device); review the new images and `git diff --stat tests/golden` before committing them.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
filter=${2:-*MatchesGolden*}
targets=(idk_gpu_pbr_tests idk_gpu_animation_tests idk_gpu_blend_tests)
cmake --build "$build" --target "${targets[@]}"
export VK_ICD_FILENAMES=${VK_ICD_FILENAMES:-/usr/share/vulkan/icd.d/lvp_icd.json}
for t in "${targets[@]}"; do
  IDK_ACCEPT_GOLDENS=1 "$build/bin/$t" --gtest_filter="$filter"
done
echo "accept_goldens: $(ls "$root"/tests/golden/*.png | wc -l) golden image(s) in $root/tests/golden"
