#!/usr/bin/env bash
# Runs the benchmarks (bench/, DESIGN.md "Benchmarks and reports") and regenerates BENCHMARKS.md.
# usage: scripts/bench.sh BUILD_DIR      (`make bench` builds first and passes $(BUILD))
# Writes bench/results/latest.json (medians and spread of 5 repetitions per benchmark) and BENCHMARKS.md.
# Extra arguments after BUILD_DIR go to idk_bench (e.g. --benchmark_filter=Gpu). Takes about a minute on
# 2 cores with lavapipe, plus about 15 minutes for the path tracer (scripts/bench_pathtrace.sh) and about 10 for the
# Cycles comparison (bench/cycles/bench_cycles.py; IDK_BENCH_CYCLES=0 skips it).
set -euo pipefail

build="${1:?usage: scripts/bench.sh BUILD_DIR [idk_bench options]}"
shift
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
bench="$build/bin/idk_bench"
if [ ! -x "$bench" ]; then
  echo "bench.sh: $bench not found; build it first (make bench, or ninja -C $build idk_bench)" >&2
  exit 1
fi

# Software Vulkan (Mesa lavapipe) unless the caller picked a driver.
lavapipe=/usr/share/vulkan/icd.d/lvp_icd.json
if [ -z "${VK_ICD_FILENAMES:-}" ] && [ -z "${VK_DRIVER_FILES:-}" ] && [ -f "$lavapipe" ]; then
  export VK_ICD_FILENAMES="$lavapipe"
fi

# Debian's interpreter: python3-matplotlib (scripts/setup.sh) is installed for it, not for a pyenv/venv python3,
# and the reports draw their plots with it.
python=/usr/bin/python3
[ -x "$python" ] || python=python3

mkdir -p bench/results
start=$(date +%s)
"$bench" --benchmark_out=bench/results/latest.json --benchmark_out_format=json \
  --benchmark_repetitions=5 --benchmark_report_aggregates_only=true "$@"
echo "bench.sh: benchmarks took $(( $(date +%s) - start )) s"
# The path tracer's error-vs-time runs (about 15 minutes; IDK_BENCH_PATHTRACE=0 skips them and keeps the last
# bench/results/pathtrace_section.md, which bench_report.py includes as its own section).
if [ "${IDK_BENCH_PATHTRACE:-1}" != 0 ]; then
  bash scripts/bench_pathtrace.sh "$build"
fi
# Issue 16's independent peer: Blender Cycles against our path tracer on the Cornell box and two shared scenes at
# 128x128 (about 10 minutes on 2 cores). Blender is a benchmark-only package: `scripts/setup.sh --bench` installs it
# here, never for `make test`. IDK_BENCH_CYCLES=0 skips it and keeps the last bench/results/cycles.json, which
# bench_report.py turns into the "Path tracer vs Cycles" section.
if [ "${IDK_BENCH_CYCLES:-1}" != 0 ]; then
  bash scripts/setup.sh --bench || echo "bench.sh: scripts/setup.sh --bench could not install Blender" >&2
  if command -v blender >/dev/null; then
    "$python" bench/cycles/bench_cycles.py "$build" bench/results
  else
    echo "bench.sh: skipping the Cycles comparison (no blender; scripts/setup.sh --bench installs it)" >&2
  fi
fi
# The soak runs (issue 17: 10,000 viewer frames and a 2,000-frame replay with memory sampled; a few minutes;
# IDK_BENCH_SOAK=0 skips them and keeps the last bench/results/soak.json).
if [ "${IDK_BENCH_SOAK:-1}" != 0 ]; then
  bash scripts/soak.sh "$build"
fi
# Issue 18's render farm: a 300-frame replay on 1, 2, 4 Slurm tasks of a throwaway single-node cluster (about 3
# minutes). It needs root, slurm-wlm and munge; IDK_BENCH_FARM=0 skips it and keeps the last farm_section.md.
if [ "${IDK_BENCH_FARM:-1}" != 0 ]; then
  if [ "$(id -u)" = 0 ] && command -v slurmctld >/dev/null; then
    bash scripts/bench_farm.sh "$build"
  else
    echo "bench.sh: skipping the render-farm benchmark (needs root and slurm-wlm; scripts/setup.sh installs it)" >&2
  fi
fi
# Issue 14's VRS sweep: 2 scenes x 13 settings x 4 frames of a camera path at 1280x720 (the committed results'
# settings; about 25 minutes on a loaded 2-core lavapipe machine; IDK_BENCH_VRS=0 skips it and keeps the last
# bench/results/vrs_section.md).
if [ "${IDK_BENCH_VRS:-1}" != 0 ]; then
  "$build/bin/idk_vrs_bench" bench/results/vrs.json --size 1280x720 --frames 4
  "$python" bench/vrs_report.py bench/results
fi
"$python" scripts/bench_report.py --compact bench/results/latest.json BENCHMARKS.md
