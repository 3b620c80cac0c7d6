#!/usr/bin/env bash
# Path-tracer benchmarks of issue 5 (BENCHMARKS.md "Path tracer"): drives `idk render --pathtrace ... --json` and
# `idk compare` on the Cornell box (embedded default scene), DamagedHelmet and TransmissionTest at 256x256:
#   - a high-sample reference per scene (NEE+MIS, its own seed);
#   - error (RMSE, relative MSE against the reference) against wall time for increasing spp, NEE+MIS (Sobol'
#     sampler, and the independent sampler) and BSDF sampling only (IDKEngine's approach), raw and denoised;
#   - samples per second with ray sorting on and off, and with our BVH traversal against the ray-query rung.
# Then bench/pathtrace_report.py writes bench/results/pathtrace.json, the log-log error-vs-time plots
# bench/results/pathtrace_<scene>.png and the Markdown section bench/results/pathtrace_section.md that
# scripts/bench_report.py puts into BENCHMARKS.md.
#
# usage: scripts/bench_pathtrace.sh BUILD_DIR     (scripts/bench.sh calls it; IDK_BENCH_PATHTRACE=0 skips it there)
# Knobs (environment): PT_SCENES (names: cornell DamagedHelmet TransmissionTest), PT_SIZE (256x256),
# PT_SPP ("1 2 4 8 16": the curves), PT_REF_SPP (reference spp for every scene; default 256, TransmissionTest 128),
# PT_MID_SPP (8: sorting run), PT_TRAV_SPP (1: traversal runs), PT_MAX_DEPTH (6).
# Every render uses our BVH traversal (--traversal bvh) except the ray-query row: lavapipe's ray query is ~50x
# slower on TransmissionTest's 129k triangles. With the defaults the whole script takes about 12-15 minutes on
# 2 cores with lavapipe (about 40% of it the references); the images stay in BUILD_DIR/bench_pathtrace/.
set -euo pipefail

build="${1:?usage: scripts/bench_pathtrace.sh BUILD_DIR}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
idk="$build/bin/idk"
if [ ! -x "$idk" ]; then
  echo "bench_pathtrace.sh: $idk not found; build it first (ninja -C $build idk)" >&2
  exit 1
fi
lavapipe=/usr/share/vulkan/icd.d/lvp_icd.json
if [ -z "${VK_ICD_FILENAMES:-}" ] && [ -z "${VK_DRIVER_FILES:-}" ] && [ -f "$lavapipe" ]; then
  export VK_ICD_FILENAMES="$lavapipe"
fi

scenes=(${PT_SCENES:-cornell DamagedHelmet TransmissionTest})
size="${PT_SIZE:-256x256}"
spps=(${PT_SPP:-1 2 4 8 16})
mid_spp="${PT_MID_SPP:-8}"
trav_spp="${PT_TRAV_SPP:-1}"
max_depth="${PT_MAX_DEPTH:-6}"
ref_spp_of() {
  if [ -n "${PT_REF_SPP:-}" ]; then echo "$PT_REF_SPP"
  elif [ "$1" = TransmissionTest ]; then echo 128
  else echo 256; fi
}
work="$build/bench_pathtrace"
rm -rf "$work"
mkdir -p "$work" bench/results
manifest="$work/manifest.tsv"
: > "$manifest"

scene_file() {
  case "$1" in
    cornell) echo "" ;;
    DamagedHelmet) echo "../shared/scenes/DamagedHelmet/glTF-Binary/DamagedHelmet.glb" ;;
    TransmissionTest) echo "../shared/scenes/TransmissionTest/glTF-Binary/TransmissionTest.glb" ;;
    *) echo "bench_pathtrace.sh: unknown scene '$1' (cornell, DamagedHelmet, TransmissionTest)" >&2; exit 1 ;;
  esac
}

# render SCENE VARIANT SPP [idk render options...]: one render; the image, its JSON and (after the reference) its
# comparison with the reference land in $work; one manifest line records it.
render() {
  local scene="$1" variant="$2" spp="$3"
  shift 3
  local tag="${scene}_${variant}_${spp}" file
  file="$(scene_file "$scene")"
  local args=(render)
  [ -n "$file" ] && args+=("$file")
  args+=(--pathtrace --size "$size" --spp "$spp" --max-depth "$max_depth" --no-validation
         --out "$work/$tag.exr" --json "$@")
  echo "bench_pathtrace.sh: $scene $variant spp $spp" >&2
  local rc=0 attempt
  for attempt in 1 2; do
    rc=0
    "$idk" "${args[@]}" > "$work/$tag.json" 2> "$work/$tag.log" || rc=$?
    # A crash (killed by a signal) is retried once and reported; an error exit is not retried.
    [ "$rc" -ge 128 ] && [ "$attempt" = 1 ] || break
    echo "bench_pathtrace.sh: CRASHED (exit $rc), retrying once: idk ${args[*]}" >&2
    echo "$tag crashed with exit $rc" >> "$work/crashes.txt"
  done
  if [ "$rc" != 0 ]; then
    echo "bench_pathtrace.sh: FAILED (exit $rc): idk ${args[*]}" >&2
    tail -n 3 "$work/$tag.log" >&2
    return 1
  fi
  if [ "$variant" != reference ]; then
    "$idk" compare "$work/$tag.exr" "$work/${scene}_reference_${ref_spp}.exr" --json > "$work/$tag.compare.json"
  fi
  printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$scene" "$variant" "$spp" "$tag" "idk ${args[*]}" "$ref_spp" >> "$manifest"
}

start=$(date +%s)
for scene in "${scenes[@]}"; do
  ref_spp="$(ref_spp_of "$scene")"
  # The reference: NEE+MIS, seed 1000 (the measured renders use seed 1: independent noise). Required.
  render "$scene" reference "$ref_spp" --seed 1000 --traversal bvh
  for spp in "${spps[@]}"; do
    render "$scene" nee "$spp" --seed 1 --traversal bvh
    # The same estimator with independent random numbers (the default is Owen-scrambled Sobol').
    render "$scene" independent "$spp" --seed 1 --traversal bvh --sampler independent
    render "$scene" bsdf "$spp" --seed 1 --traversal bvh --light-sampling bsdf
    # Same seed as the nee row: the same raw image, then denoised. Optional (exit 1 when the denoiser did not run).
    render "$scene" denoised "$spp" --seed 1 --traversal bvh --denoise || true
  done
  render "$scene" sort-on "$mid_spp" --seed 1 --traversal bvh --sort on || true
  render "$scene" traversal-bvh "$trav_spp" --seed 1 --traversal bvh
  render "$scene" traversal-bvh2 "$trav_spp" --seed 1 --traversal bvh2
  render "$scene" traversal-rayquery "$trav_spp" --seed 1 --traversal rayquery || true
done
elapsed=$(( $(date +%s) - start ))
echo "bench_pathtrace.sh: renders took $elapsed s" >&2

# Debian's interpreter: python3-matplotlib (scripts/setup.sh) is installed for it, not for a pyenv/venv python3.
python=/usr/bin/python3
[ -x "$python" ] || python=python3
"$python" bench/pathtrace_report.py "$work" bench/results --size "$size" --max-depth "$max_depth" \
  --elapsed "$elapsed"
