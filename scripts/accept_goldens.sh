#!/usr/bin/env bash
# accept_goldens.sh [BUILD_DIR]: deliberately regenerates the golden images (tests/golden/*.png) from the current
# renderer: builds the PBR GPU tests and runs every *MatchesGolden* test with IDK_ACCEPT_GOLDENS=1, which writes
# the rendered frame instead of comparing it. Render goldens on lavapipe (the CI device); review the new images
# and `git diff --stat tests/golden` before committing them.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
cmake --build "$build" --target idk_gpu_pbr_tests
export VK_ICD_FILENAMES=${VK_ICD_FILENAMES:-/usr/share/vulkan/icd.d/lvp_icd.json}
IDK_ACCEPT_GOLDENS=1 "$build/bin/idk_gpu_pbr_tests" --gtest_filter='*MatchesGolden*'
echo "accept_goldens: wrote $(ls "$root"/tests/golden/*.png | wc -l) golden image(s) to $root/tests/golden"
