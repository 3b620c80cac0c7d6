#!/usr/bin/env bash
# security_checks.sh IDK CASE: the `idk` command line on untrusted scenes (issue 17): URIs that leave the
# scene's folder are refused with exit code 1 and one line naming the file and the URI, no image is written,
# and --allow-external-uris renders the same files; --max-memory refuses a scene over its budget.
set -u
idk="$1"
case_name="$2"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

fail() { echo "FAIL ($case_name): $*"; exit 1; }

# A one-triangle scene in $tmp/asset whose buffer (3 float positions + 3 uint16 indices + 2 padding bytes) has
# the URI $1; the buffer file itself lies outside, in $tmp/outside/secret.bin.
mkdir -p "$tmp/asset" "$tmp/outside"
printf '\0\0\0\0\0\0\0\0\0\0\0\0\0\0\x80\x3f\0\0\0\0\0\0\0\0\0\0\0\0\0\0\x80\x3f\0\0\0\0\0\0\x01\0\x02\0\0\0' \
  >"$tmp/outside/secret.bin"
scene_with() {  # scene_with BUFFER_URI [IMAGE_URI]
  local images=""
  [ $# -ge 2 ] && images=", \"images\": [{\"uri\": \"$2\"}]"
  cat >"$tmp/asset/scene.gltf" <<JSON
{"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
 "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0,0,0], "max": [1,1,0]},
               {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
 "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
 "buffers": [{"uri": "$1", "byteLength": 44}]$images}
JSON
}

expect_refused() {  # expect_refused URI_AS_WRITTEN [idk args...]
  local uri="$1"; shift
  rm -f "$tmp/x.png"
  "$idk" "$@" 2>"$tmp/err" >/dev/null
  local code=$?
  [ "$code" -eq 1 ] || fail "exit code $code for uri '$uri', expected 1: $(cat "$tmp/err")"
  [ "$(wc -l <"$tmp/err")" -eq 1 ] || fail "expected one line on stderr, got: $(cat "$tmp/err")"
  grep -qF "$tmp/asset/scene.gltf" "$tmp/err" || fail "error does not name the scene file: $(cat "$tmp/err")"
  grep -qF "uri '$uri'" "$tmp/err" || fail "error does not name the uri '$uri': $(cat "$tmp/err")"
  grep -qF -- "--allow-external-uris" "$tmp/err" || fail "error does not name the option: $(cat "$tmp/err")"
  [ ! -e "$tmp/x.png" ] || fail "an image was written for the refused uri '$uri'"
}

case "$case_name" in
  uri_confinement)
    ln -s "$tmp/outside/secret.bin" "$tmp/asset/link.bin"
    for uri in "../outside/secret.bin" "%2e%2e/outside/secret.bin" "$tmp/outside/secret.bin" "link.bin"; do
      scene_with "$uri"
      expect_refused "$uri" render "$tmp/asset/scene.gltf" --size 16x16 --out "$tmp/x.png"
      expect_refused "$uri" bvh "$tmp/asset/scene.gltf"
      "$idk" render "$tmp/asset/scene.gltf" --allow-external-uris --size 16x16 --out "$tmp/x.png" 2>"$tmp/err" \
        || fail "--allow-external-uris did not render uri '$uri': $(cat "$tmp/err")"
      [ -s "$tmp/x.png" ] || fail "no image written with --allow-external-uris"
    done
    # An image URI that climbs out: refused the same way (before the texture decoder could open it).
    cp "$tmp/outside/secret.bin" "$tmp/asset/tri.bin"
    scene_with "tri.bin" "../outside/secret.png"
    expect_refused "../outside/secret.png" render "$tmp/asset/scene.gltf" --size 16x16 --out "$tmp/x.png"
    # Inside the folder everything still works.
    scene_with "tri.bin"
    "$idk" render "$tmp/asset/scene.gltf" --size 16x16 --out "$tmp/x.png" 2>"$tmp/err" \
      || fail "a scene whose buffer is in its folder failed: $(cat "$tmp/err")"
    "$idk" render --help | grep -q -- "--allow-external-uris" || fail "render --help does not describe the option"
    ;;
  max_memory)
    cp "$tmp/outside/secret.bin" "$tmp/asset/tri.bin"
    scene_with "tri.bin"
    "$idk" render "$tmp/asset/scene.gltf" --max-memory 256 --size 16x16 --out "$tmp/x.png" 2>"$tmp/err"
    code=$?
    [ "$code" -eq 1 ] || fail "exit code $code under --max-memory 256, expected 1: $(cat "$tmp/err")"
    [ "$(wc -l <"$tmp/err")" -eq 1 ] || fail "expected one line on stderr, got: $(cat "$tmp/err")"
    grep -qF "$tmp/asset/scene.gltf: memory budget exceeded: " "$tmp/err" || fail "no budget error: $(cat "$tmp/err")"
    grep -qF -- "--max-memory is 256 bytes" "$tmp/err" || fail "the error does not give the budget: $(cat "$tmp/err")"
    [ ! -e "$tmp/x.png" ] || fail "an image was written over budget"
    "$idk" render "$tmp/asset/scene.gltf" --max-memory 64M --size 16x16 --out "$tmp/x.png" 2>"$tmp/err" \
      || fail "the scene did not render under --max-memory 64M: $(cat "$tmp/err")"
    "$idk" render "$tmp/asset/scene.gltf" --max-memory lots --out "$tmp/x.png" 2>/dev/null
    [ $? -eq 2 ] || fail "--max-memory lots should be a usage error (exit 2)"
    ;;
  *)
    fail "unknown case"
    ;;
esac
echo "PASS ($case_name)"
