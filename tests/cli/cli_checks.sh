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
  *) fail "unknown case" ;;
esac
echo "ok ($case_name)"
