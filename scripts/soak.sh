#!/usr/bin/env bash
# Soak runs (issue 17, part 6), run by `make bench` (scripts/bench.sh; IDK_BENCH_SOAK=0 skips them):
#   * idk-viewer under a private Xvfb display for SOAK_VIEWER_FRAMES (10000) frames of the Cornell box at 96x96,
#     --fixed-dt, a script that flies the camera around (FPS mode, W/A/S/D, mouse look), --memory-log (every 100);
#   * `idk render --replay` of a SOAK_REPLAY_FRAMES (2000) record capture (written here in the documented layout:
#     the camera circles the box) to an H.264 video at 96x96, IDK_MEMORY_LOG every 100 frames.
# Both without the validation layer (its own bookkeeping would dominate the figures). Writes the raw logs and
# bench/results/soak.json (scripts/soak_summary.py: host RSS and device memory by category at start, middle and end,
# least-squares slope per 1000 frames after a 10% warm-up); bench_report.py puts them in BENCHMARKS.md ("Soak").
# usage: scripts/soak.sh BUILD_DIR
set -euo pipefail
build="${1:?usage: scripts/soak.sh BUILD_DIR}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
viewer_frames="${SOAK_VIEWER_FRAMES:-10000}"
replay_frames="${SOAK_REPLAY_FRAMES:-2000}"
out=bench/results/soak
mkdir -p "$out"
tmp=$(mktemp -d)
xvfb_pid=""
cleanup() { [ -n "$xvfb_pid" ] && kill "$xvfb_pid" 2>/dev/null; rm -rf "$tmp"; }
trap cleanup EXIT
lavapipe=/usr/share/vulkan/icd.d/lvp_icd.json
if [ -z "${VK_ICD_FILENAMES:-}" ] && [ -z "${VK_DRIVER_FILES:-}" ] && [ -f "$lavapipe" ]; then
  export VK_ICD_FILENAMES="$lavapipe"
fi

# The viewer's input: FPS mode, then per 400 frames forward / strafe / back with a mouse turn (collision keeps the
# camera in the box).
python3 - "$tmp/script.txt" "$viewer_frames" <<'PY'
import sys
path, frames = sys.argv[1], int(sys.argv[2])
lines = ["0 press E"]
keys = ["W", "D", "S", "A"]
for k, start in enumerate(range(10, frames - 10, 400)):
    key = keys[k % 4]
    lines += [f"{start} down {key}", f"{start + 150} up {key}", f"{start + 200} mouse 40 {-5 if k % 2 else 5}"]
open(path, "w").write("\n".join(lines) + "\n")
PY
# The replay's capture: the camera circles the Cornell box's centre, looking in (30 Hz).
python3 - "$tmp/soak.idkcap" "$replay_frames" <<'PY'
import math, struct, sys
path, n = sys.argv[1], int(sys.argv[2])
records = b""
for i in range(n):
    a = 2 * math.pi * i / 600
    x, z = -0.278 + 0.3 * math.sin(a), 0.273 + 0.3 * math.cos(a)
    records += struct.pack("<d3f3fdI", i / 30, x, 0.273, z, a, 0.0, 0.686, i / 30, 0)
open(path, "wb").write(b"IDKCAPT\0" + struct.pack("<IIfIQ", 1, 44, 30.0, 0, n) + records)
PY

exec 3>"$tmp/display"
Xvfb -displayfd 3 -screen 0 320x240x24 -nolisten tcp >/dev/null 2>&1 &
xvfb_pid=$!
for _ in $(seq 50); do [ -s "$tmp/display" ] && break; sleep 0.1; done
display=":$(head -1 "$tmp/display")"

start=$(date +%s)
DISPLAY="$display" "$build/bin/idk-viewer" --size 96x96 --fixed-dt 0.016 --frames "$viewer_frames" --no-vsync \
  --no-validation --script "$tmp/script.txt" --memory-log "$out/viewer_memory.jsonl" >"$out/viewer.log" 2>&1
viewer_s=$(( $(date +%s) - start ))
start=$(date +%s)
IDK_MEMORY_LOG="$out/replay_memory.jsonl:100" "$build/bin/idk" render --replay "$tmp/soak.idkcap" \
  --video "$tmp/soak.mp4" --size 96x96 --no-validation >"$out/replay.log" 2>&1
replay_s=$(( $(date +%s) - start ))
python3 scripts/soak_summary.py "$out" "$viewer_frames" "$viewer_s" "$replay_frames" "$replay_s" bench/results/soak.json
