#!/usr/bin/env bash
# cli_checks.sh IDK CASE: end-to-end checks of the `idk` command line (exit codes, one-line errors, outputs).
set -u
idk="$1"
case_name="$2"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

fail() { echo "FAIL ($case_name): $*"; exit 1; }

case "$case_name" in
  missing_scene)
    "$idk" render /no/such/scene.gltf --out "$tmp/x.png" 2>"$tmp/err" && fail "exit code 0 for a missing scene"
    code=$?
    [ "$code" -eq 1 ] || fail "exit code $code, expected 1"
    [ "$(wc -l <"$tmp/err")" -eq 1 ] || fail "expected one line on stderr, got: $(cat "$tmp/err")"
    grep -q "/no/such/scene.gltf" "$tmp/err" || fail "error does not name the path: $(cat "$tmp/err")"
    ;;
  malformed_scene)
    printf '{"asset":{"version":"2.0"},"meshes":[{"primitives":[{"attributes":{"POSITION":7}}]}]}' >"$tmp/bad.gltf"
    "$idk" render "$tmp/bad.gltf" --out "$tmp/x.png" 2>"$tmp/err"
    code=$?
    [ "$code" -eq 1 ] || fail "exit code $code, expected 1"
    [ "$(wc -l <"$tmp/err")" -eq 1 ] || fail "expected one line on stderr, got: $(cat "$tmp/err")"
    grep -q "bad.gltf" "$tmp/err" || fail "error does not name the file: $(cat "$tmp/err")"
    ;;
  render_default)
    "$idk" render --size 64x48 --out "$tmp/out.png" || fail "render failed"
    [ -s "$tmp/out.png" ] || fail "no image written"
    "$idk" render --size 32x32 --out "$tmp/out.exr" --json >"$tmp/stats.json" || fail "EXR render failed"
    [ -s "$tmp/out.exr" ] || fail "no EXR written"
    grep -q '"passes"' "$tmp/stats.json" || fail "--json has no passes: $(cat "$tmp/stats.json")"
    grep -q '"gbuffer"' "$tmp/stats.json" || fail "--json does not list the gbuffer pass"
    grep -q '"memoryBytes"' "$tmp/stats.json" || fail "--json has no memory by category"
    "$idk" render --size 16x16 --out "$tmp/g.png" --graph "$tmp/frame.dot" || fail "render with --graph failed"
    grep -q "digraph" "$tmp/frame.dot" || fail "--graph .dot is not graphviz: $(head -3 "$tmp/frame.dot")"
    ;;
  info_json)
    "$idk" info --json >"$tmp/info.json" || fail "idk info --json failed"
    for key in '"device"' '"ladders"' '"subgroupSize"' '"chosen"' '"apiVersion"'; do
      grep -q "$key" "$tmp/info.json" || fail "missing $key in: $(cat "$tmp/info.json")"
    done
    ;;
  no_device)
    VK_ICD_FILENAMES="$tmp/none.json" VK_DRIVER_FILES="$tmp/none.json" "$idk" info --no-validation 2>"$tmp/err"
    code=$?
    [ "$code" -eq 1 ] || fail "exit code $code, expected 1"
    grep -q "mesa-vulkan-drivers" "$tmp/err" || fail "message does not name the driver package: $(cat "$tmp/err")"
    ;;
  usage_errors)
    "$idk" render --out "$tmp/x.png" --size 12 2>/dev/null; [ $? -eq 2 ] || fail "bad --size should exit 2"
    "$idk" bogus 2>/dev/null; [ $? -eq 2 ] || fail "unknown command should exit 2"
    "$idk" render --size 8x8 2>/dev/null; [ $? -eq 2 ] || fail "missing --out should exit 2"
    "$idk" render --out "$tmp/x.bmp" --size 8x8 2>/dev/null; [ $? -eq 2 ] || fail "unsupported format should exit 2"
    "$idk" render --help | grep -q -- "--out" || fail "render --help does not describe --out"
    ;;
  bvh)
    shared="${IDK_SHARED_DIR:-$(cd "$(dirname "$0")/../../.." && pwd)/shared}"
    bunny="$shared/scenes/bunny/bunny.bin"
    [ -f "$bunny" ] || fail "missing test input $bunny"
    "$idk" bvh "$bunny" --split-factor 0.3 >"$tmp/bvh.txt" 2>"$tmp/err" || fail "idk bvh failed: $(cat "$tmp/err")"
    for key in "triangles: *69630" "fragments:" "references:" "nodes:" "leaves:" "SAH:" "EPO:" "max depth:" "stack:" "build:"; do
      grep -q "$key" "$tmp/bvh.txt" || fail "text output lacks '$key': $(cat "$tmp/bvh.txt")"
    done
    [ ! -s "$tmp/err" ] || fail "progress or noise on a non-terminal stderr: $(cat "$tmp/err")"
    "$idk" bvh "$bunny" --json >"$tmp/bvh.json" || fail "idk bvh --json failed"
    python3 - "$tmp/bvh.json" <<'PY' || fail "bad JSON: $(cat "$tmp/bvh.json")"
import json, sys
j = json.load(open(sys.argv[1]))
assert j["triangles"] == 69630 and j["fragments"] == 69630 and j["splitFactor"] == 0
assert j["nodes"] == 2 * j["leaves"] - 1 and j["references"] == 69630
assert 1 < j["sah"] < 1000 and j["epo"] > 0 and j["maxDepth"] > 10 and 0 < j["requiredStackSize"] <= j["maxDepth"]
assert j["buildMs"] > 0
PY
    "$idk" bvh /no/such/mesh.bin 2>"$tmp/err" >/dev/null
    code=$?
    [ "$code" -eq 1 ] || fail "missing file: exit code $code, expected 1"
    [ "$(wc -l <"$tmp/err")" -eq 1 ] || fail "expected one line on stderr, got: $(cat "$tmp/err")"
    grep -q "/no/such/mesh.bin" "$tmp/err" || fail "error does not name the file: $(cat "$tmp/err")"
    "$idk" bvh /no/such/scene.glb 2>"$tmp/err" >/dev/null; [ $? -eq 1 ] || fail "missing glTF should exit 1"
    grep -q "/no/such/scene.glb" "$tmp/err" || fail "error does not name the glTF: $(cat "$tmp/err")"
    "$idk" bvh "$bunny" --split-factor -1 2>/dev/null >/dev/null; [ $? -eq 2 ] || fail "negative split factor should exit 2"
    "$idk" bvh --help | grep -q -- "--split-factor" || fail "bvh --help does not describe --split-factor"
    # Spatial splits: more references than triangles (chopped ones), within the budget, and a lower SAH than above.
    "$idk" bvh "$bunny" --spatial-splits --split-budget 1.5 --no-epo --json >"$tmp/sbvh.json" || fail "idk bvh --spatial-splits failed"
    python3 - "$tmp/bvh.json" "$tmp/sbvh.json" <<'PY' || fail "bad spatial-split JSON: $(cat "$tmp/sbvh.json")"
import json, sys
plain, spatial = (json.load(open(p)) for p in sys.argv[1:3])
assert spatial["spatialSplits"] is True and spatial["splitBudget"] == 1.5 and spatial["spatialSplitNodes"] > 0
assert 69630 < spatial["references"] <= 1.5 * 69630 and spatial["epo"] is None
assert spatial["sah"] < plain["sah"]
PY
    "$idk" bvh "$bunny" --split-budget 2 2>/dev/null >/dev/null; [ $? -eq 2 ] || fail "--split-budget without --spatial-splits should exit 2"
    "$idk" bvh "$bunny" --spatial-splits --split-budget 0.5 2>/dev/null >/dev/null; [ $? -eq 2 ] || fail "budget below 1 should exit 2"
    "$idk" bvh --help | grep -q -- "--spatial-splits" || fail "bvh --help does not describe --spatial-splits"
    ;;
  all_shared_scenes)
    # Issue 3's bar: every shared asset renders (or fails with one line naming the file and the cause).
    shared="${IDK_SHARED_DIR:-$(cd "$(dirname "$0")/../../.." && pwd)/shared}"
    count=0
    while IFS= read -r scene; do
      count=$((count + 1))
      if ! "$idk" render "$scene" --size 32x32 --out "$tmp/scene.png" 2>"$tmp/err" >/dev/null; then
        fail "$scene did not render: $(tail -2 "$tmp/err")"
      fi
      [ -s "$tmp/scene.png" ] || fail "$scene wrote no image"
      grep -qiE "validation|assert|sanitizer" "$tmp/err" && fail "$scene: $(cat "$tmp/err")"
    done < <(find "$shared/scenes" -type f \( -name '*.gltf' -o -name '*.glb' \) | sort)
    [ "$count" -ge 20 ] || fail "found only $count shared scenes"
    echo "rendered $count shared scenes"
    ;;
  replay_video | replay_frames | replay_corrupt)
    # Issue 6: camera capture -> `idk render --replay --video`. The capture is written here from the documented
    # layout (engine/tools/camera_capture.hpp), independently of the engine: 10 records at 30 Hz walking into the
    # Cornell box while turning right.
    python3 - "$tmp/cap.idkcap" 10 <<'PY' || fail "cannot write the test capture"
import struct, sys
out, n = sys.argv[1], int(sys.argv[2])
records = b"".join(struct.pack("<d3f3fdI", i / 30, -0.278 + 0.005 * i, 0.273, 0.8 - 0.03 * i, 0.01 * i, 0.0, 0.686,
                               i / 30, 0) for i in range(n))
open(out, "wb").write(b"IDKCAPT\0" + struct.pack("<IIfIQ", 1, 44, 30.0, 0, n) + records)
PY
    probe() {
      ffprobe -v error -select_streams v:0 -count_frames \
        -show_entries stream=codec_name,width,height,pix_fmt,nb_read_frames -of csv=p=0 "$1"
    }
    leftovers() { find "$tmp" -name '*.mp4' -o -name '*partial*' | sort | tr '\n' ' '; }
    case "$case_name" in
      replay_video)
        "$idk" render --replay "$tmp/cap.idkcap" --video "$tmp/out.mp4" --size 64x48 2>"$tmp/err" \
          || fail "replay failed: $(cat "$tmp/err")"
        [ "$(probe "$tmp/out.mp4")" = "h264,64,48,yuv420p,10" ] || fail "ffprobe: $(probe "$tmp/out.mp4")"
        [ "$(ffprobe -v error -show_entries stream=r_frame_rate -of csv=p=0 "$tmp/out.mp4")" = "30/1" ] \
          || fail "not the capture's 30 Hz"
        grep -q $'\r' "$tmp/err" && fail "progress bar on a non-terminal stderr: $(cat -A "$tmp/err")"
        [ "$(leftovers)" = "$tmp/out.mp4 " ] || fail "unexpected files: $(leftovers)"
        # Odd sizes are padded to the next even size (yuv420p).
        "$idk" render --replay "$tmp/cap.idkcap" --video "$tmp/odd.mp4" --size 33x17 --frames 0:2 2>/dev/null \
          || fail "odd-size replay failed"
        [ "$(probe "$tmp/odd.mp4")" = "h264,34,18,yuv420p,2" ] || fail "odd size: $(probe "$tmp/odd.mp4")"
        ;;
      replay_frames)
        # Two halves of a split render add up to the whole capture.
        "$idk" render --replay "$tmp/cap.idkcap" --video "$tmp/a.mp4" --size 32x32 --frames 0:4 2>/dev/null \
          || fail "--frames 0:4 failed"
        "$idk" render --replay "$tmp/cap.idkcap" --video "$tmp/b.mp4" --size 32x32 --frames 4: 2>/dev/null \
          || fail "--frames 4: failed"
        [ "$(probe "$tmp/a.mp4")" = "h264,32,32,yuv420p,4" ] || fail "0:4 gave $(probe "$tmp/a.mp4")"
        [ "$(probe "$tmp/b.mp4")" = "h264,32,32,yuv420p,6" ] || fail "4: gave $(probe "$tmp/b.mp4")"
        # Deterministic replay: the same range again decodes to the same pixels, frame for frame.
        "$idk" render --replay "$tmp/cap.idkcap" --video "$tmp/a2.mp4" --size 32x32 --frames 0:4 2>/dev/null \
          || fail "second --frames 0:4 failed"
        [ "$(ffmpeg -v error -i "$tmp/a.mp4" -f framemd5 - | grep -v '^#')" = \
          "$(ffmpeg -v error -i "$tmp/a2.mp4" -f framemd5 - | grep -v '^#')" ] || fail "two replays of 0:4 differ"
        "$idk" render --replay "$tmp/cap.idkcap" --video "$tmp/c.mp4" --frames 3:11 2>"$tmp/err"
        [ $? -eq 2 ] || fail "--frames past the end should exit 2"
        grep -q "10 frames" "$tmp/err" || fail "range error does not give the frame count: $(cat "$tmp/err")"
        "$idk" render --replay "$tmp/cap.idkcap" --size 8x8 2>/dev/null; [ $? -eq 2 ] || fail "--replay without --video should exit 2"
        [ ! -e "$tmp/c.mp4" ] || fail "a failed range wrote a video"
        ;;
      replay_corrupt)
        check_bad() {  # FILE OFFSET: exit 1, one line naming the file and the byte offset, no video
          "$idk" render --replay "$1" --video "$tmp/bad.mp4" --size 16x16 2>"$tmp/err"
          code=$?
          [ "$code" -eq 1 ] || fail "$1: exit code $code, expected 1"
          [ "$(wc -l <"$tmp/err")" -eq 1 ] || fail "$1: expected one line on stderr, got: $(cat "$tmp/err")"
          grep -q "$1: byte offset $2:" "$tmp/err" || fail "$1: message lacks the file and offset $2: $(cat "$tmp/err")"
          [ -z "$(leftovers)" ] || fail "$1: files left behind: $(leftovers)"
        }
        head -c 100 "$tmp/cap.idkcap" >"$tmp/truncated.idkcap"
        check_bad "$tmp/truncated.idkcap" 76
        head -c 20 "$tmp/cap.idkcap" >"$tmp/short.idkcap"
        check_bad "$tmp/short.idkcap" 20
        { printf 'NOTACAPT'; tail -c +9 "$tmp/cap.idkcap"; } >"$tmp/magic.idkcap"
        check_bad "$tmp/magic.idkcap" 0
        { head -c 8 "$tmp/cap.idkcap"; printf '\x02\x00\x00\x00'; tail -c +13 "$tmp/cap.idkcap"; } >"$tmp/newer.idkcap"
        check_bad "$tmp/newer.idkcap" 8
        grep -q "version 2 is newer" "$tmp/err" || fail "newer version not named: $(cat "$tmp/err")"
        "$idk" render --replay "$tmp/missing.idkcap" --video "$tmp/bad.mp4" 2>"$tmp/err"
        [ $? -eq 1 ] || fail "a missing capture should exit 1"
        grep -q "missing.idkcap" "$tmp/err" || fail "missing capture not named: $(cat "$tmp/err")"
        [ -z "$(leftovers)" ] || fail "missing capture: files left behind: $(leftovers)"
        ;;
    esac
    ;;
  *) fail "unknown case" ;;
esac
echo "ok ($case_name)"
