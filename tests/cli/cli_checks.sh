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
    # The settings table: --json records every option; its flags parse with range checks (exit 2 naming the flag).
    "$idk" render --size 16x16 --out "$tmp/s.png" --exposure 2 --shadow-size 256 --json >"$tmp/set.json" \
      || fail "render with table options failed"
    grep -q '"shadow-size": "256"' "$tmp/set.json" || fail "--json settings lack shadow-size 256: $(cat "$tmp/set.json")"
    grep -q '"exposure": 2' "$tmp/set.json" || fail "--json settings lack exposure 2"
    "$idk" render --size 8x8 --out "$tmp/s.png" --shadow-size 300 2>"$tmp/err"; [ $? -eq 2 ] \
      || fail "--shadow-size 300 should exit 2"
    grep -q -- "--shadow-size '300'" "$tmp/err" || fail "error does not name --shadow-size: $(cat "$tmp/err")"
    "$idk" render --help | grep -q -- "--env-intensity" || fail "render --help lacks the table's options"
    "$idk" render --size 16x16 --out "$tmp/g.png" --graph "$tmp/frame.dot" || fail "render with --graph failed"
    grep -q "digraph" "$tmp/frame.dot" || fail "--graph .dot is not graphviz: $(head -3 "$tmp/frame.dot")"
    ;;
  vrs)
    # Issue 14: --vrs on shades fewer pixels (shadingInvocations: lighting + sky) than off (64x48 = 3072); a fixed
    # 4x4 rate shades exactly 16 x 12; the shared-memory reduction gives the same rates as the subgroup one.
    inv() { grep -o '"shadingInvocations": [0-9]*' "$1" | grep -o '[0-9]*$'; }
    "$idk" render --size 64x48 --out "$tmp/off.png" --stats --json >"$tmp/off.json" 2>/dev/null || fail "render failed"
    [ "$(inv "$tmp/off.json")" = 3072 ] || fail "VRS off: shadingInvocations $(inv "$tmp/off.json"), expected 3072"
    "$idk" render --size 64x48 --out "$tmp/on.png" --vrs on --stats --json >"$tmp/on.json" 2>/dev/null || fail "--vrs on failed"
    on=$(inv "$tmp/on.json")
    [ -n "$on" ] && [ "$on" -lt 3072 ] || fail "--vrs on: shadingInvocations '$on', expected < 3072"
    grep -q '"vrs_classify"' "$tmp/on.json" || fail "--vrs on ran no classifier"
    grep -q '"motion_vectors"' "$tmp/on.json" && grep -q '"vrs_velocity"' "$tmp/on.json" \
      || fail "--vrs on (with --aa none) took its speed from no motion vectors"
    grep -q '"id": "vrs"' "$tmp/on.json" || fail "--vrs on does not report the vrs rung"
    "$idk" render --size 64x48 --out "$tmp/sh.png" --vrs on --rung subgroup-arithmetic=fallback --stats --json \
      >"$tmp/sh.json" 2>/dev/null || fail "--rung subgroup-arithmetic=fallback failed"
    [ "$(inv "$tmp/sh.json")" = "$on" ] || fail "shared-memory reduction: $(inv "$tmp/sh.json") invocations, subgroup: $on"
    "$idk" render --size 64x48 --out "$tmp/f.png" --vrs on --vrs-rate 4x4 --vrs-debug --json >"$tmp/f.json" 2>/dev/null \
      || fail "--vrs-rate 4x4 --vrs-debug failed"
    [ "$(inv "$tmp/f.json")" = 192 ] || fail "--vrs-rate 4x4: $(inv "$tmp/f.json") invocations, expected 192"
    grep -q '"vrs_overlay"' "$tmp/f.json" || fail "--vrs-debug drew no overlay"
    "$idk" render --size 8x8 --out "$tmp/x.png" --vrs maybe 2>"$tmp/err"; [ $? -eq 2 ] || fail "--vrs maybe should exit 2"
    grep -q -- "--vrs 'maybe'" "$tmp/err" || fail "error does not name --vrs: $(cat "$tmp/err")"
    # The hardware rungs: where the device has neither VK_KHR_fragment_shading_rate nor VK_NV_shading_rate_image
    # (lavapipe), the software rung runs with that reason, and forcing --rung vrs=native is a clear error (exit 2).
    "$idk" info --json --no-validation >"$tmp/info.json" || fail "idk info --json failed"
    if ! python3 -c "import json,sys; l=[l for l in json.load(open(sys.argv[1]))['ladders'] if l['id']=='vrs'][0]; sys.exit(0 if any(r['available'] for r in l['rungs'][:2]) else 1)" "$tmp/info.json"; then
      grep -q '"reason": "device lacks VK_KHR_fragment_shading_rate' "$tmp/on.json" || fail "no software-rung reason: $(grep -A3 '"id": "vrs"' "$tmp/on.json")"
      "$idk" render --size 16x16 --out "$tmp/n.png" --vrs on --rung vrs=native 2>"$tmp/err"; [ $? -eq 2 ] \
        || fail "--rung vrs=native without the extensions should exit 2"
      grep -q -- "--rung vrs=native: device lacks VK_KHR_fragment_shading_rate" "$tmp/err" || fail "unclear error: $(cat "$tmp/err")"
    fi
    ;;
  gi_selection)
    # --gi none (the default) allocates and runs nothing of VXGI; --gi vxgi runs its passes and holds its volumes.
    "$idk" render --size 16x16 --out "$tmp/n.png" --json >"$tmp/none.json" || fail "render --gi none failed"
    grep -q '"gi": "none"' "$tmp/none.json" || fail "--json settings lack gi none"
    [ "$(grep -c '"vxgi' "$tmp/none.json")" -eq 0 ] || fail "--gi none ran or allocated VXGI: $(grep vxgi "$tmp/none.json")"
    "$idk" render --size 16x16 --out "$tmp/v.png" --gi vxgi --voxels 64 --json >"$tmp/vxgi.json" \
      || fail "render --gi vxgi failed"
    for key in '"gi": "vxgi"' '"voxels": "64"' '"vxgi_voxelize"' '"vxgi_merge"' '"vxgi_cone_trace"' '"vxgi": ' \
               '"gi-resolution": "half"' '"vxgi_upsample"' '"vxgi_cone_trace_fixup"'; do
      grep -q "$key" "$tmp/vxgi.json" || fail "--gi vxgi --json lacks $key: $(cat "$tmp/vxgi.json")"
    done
    "$idk" render --size 8x8 --out "$tmp/x.png" --voxels 100 2>"$tmp/err"; [ $? -eq 2 ] || fail "--voxels 100 should exit 2"
    grep -q -- "--voxels" "$tmp/err" || fail "error does not name --voxels: $(cat "$tmp/err")"
    # The voxel debug view: one pass when on (--json names it and its settings), none in the frame above; it needs
    # --gi vxgi and a level the grid has (exit 2 naming the flag).
    grep -q '"vxgi_debug_voxels"' "$tmp/vxgi.json" && fail "--gi-debug off ran the debug view"
    "$idk" render --size 16x16 --out "$tmp/d.png" --gi vxgi --voxels 64 --gi-debug voxels --gi-debug-level 2 --json \
      >"$tmp/debug.json" || fail "render --gi-debug voxels failed"
    for key in '"gi-debug": "voxels"' '"gi-debug-level": 2' '"vxgi_debug_voxels"'; do
      grep -q "$key" "$tmp/debug.json" || fail "--gi-debug voxels --json lacks $key: $(cat "$tmp/debug.json")"
    done
    "$idk" render --size 8x8 --out "$tmp/x.png" --gi-debug voxels 2>"$tmp/err"; [ $? -eq 2 ] \
      || fail "--gi-debug voxels with --gi none should exit 2"
    grep -q -- "--gi-debug 'voxels'.*--gi vxgi" "$tmp/err" || fail "error does not name --gi-debug: $(cat "$tmp/err")"
    "$idk" render --size 8x8 --out "$tmp/x.png" --gi vxgi --voxels 64 --gi-debug voxels --gi-debug-level 7 \
      2>"$tmp/err"; [ $? -eq 2 ] || fail "--gi-debug-level 7 at 64^3 should exit 2"
    grep -q -- "--gi-debug-level '7'" "$tmp/err" || fail "error does not name --gi-debug-level: $(cat "$tmp/err")"
    ;;
  gi_gl_rung)
    # Issue 15/11: --rung vxgi-atomics=gl-interop --gi vxgi forces VXGI's GL-interop rung on llvmpipe: the fragments'
    # records are added by the OpenGL pass "vxgi_gl_accumulate" inside the frame's graph, --json names the rung,
    # and the frame matches the device's own (native float-atomics) rung within the GPU test's threshold.
    vx=(render --size 32x32 --gi vxgi --voxels 64 --json)
    "$idk" "${vx[@]}" --rung vxgi-atomics=gl-interop --out "$tmp/gl.exr" >"$tmp/gl.json" || fail "GL rung render failed"
    "$idk" "${vx[@]}" --out "$tmp/own.exr" >"$tmp/own.json" || fail "own rung render failed"
    python3 - "$tmp/gl.json" "$tmp/own.json" <<'PY' || fail "--json does not report the GL rung: $(cat "$tmp/gl.json")"
import json, sys
gl, own = (json.load(open(p)) for p in sys.argv[1:3])
ran = {r["id"]: r for r in gl["rungs"]}
assert ran["vxgi-atomics"]["chosen"] == "gl-interop", ran["vxgi-atomics"]
assert "vxgi_gl_accumulate" in json.dumps(gl), "the GL pass did not run"
assert {r["id"]: r for r in own["rungs"]}["vxgi-atomics"]["chosen"] != "gl-interop"
assert "vxgi_gl_accumulate" not in json.dumps(own)
PY
    "$idk" compare "$tmp/gl.exr" "$tmp/own.exr" --fail-above 0.001 >/dev/null || fail "GL rung frame differs from the native one"
    ;;
  voxel_single_draw)
    # Issue 11: the single-draw voxelization's native rung (VK_NV_geometry_shader_passthrough +
    # VK_NV_viewport_swizzle). Where the device lacks them (lavapipe) `idk info` offers only the geometry-shader
    # fallback and names what is missing, --gi-voxel-draws single runs and reports the fallback, and forcing the
    # native rung is a clear error (exit 2) naming the missing extension.
    "$idk" info --json >"$tmp/info.json" || fail "idk info failed"
    native=$(python3 - "$tmp/info.json" <<'PY'
import json, sys
l = next(l for l in json.load(open(sys.argv[1]))["ladders"] if l["id"] == "voxel-single-draw")
native = l["rungs"][0]
assert native["rung"] == "native" and "VK_NV_geometry_shader_passthrough" in native["mechanism"], native
if not native["available"]:
    assert l["chosen"] == "fallback", l
    assert native["note"].startswith("device lacks ") and "VK_NV" in native["note"], native
    assert l["reason"] == native["note"], l
print("available" if native["available"] else "absent")
PY
    ) || fail "no voxel-single-draw ladder: $(grep -A12 'voxel-single-draw' "$tmp/info.json")"
    [ "$native" = absent ] || exit 0  # a device with the NV extensions: nothing to refuse
    vx=(render --size 16x16 --gi vxgi --voxels 64 --gi-voxel-draws single --gi-raster centre)
    "$idk" "${vx[@]}" --out "$tmp/s.png" --json >"$tmp/s.json" || fail "single-draw render failed"
    python3 - "$tmp/s.json" <<'PY' || fail "--json does not report the single-draw fallback: $(cat "$tmp/s.json")"
import json, sys
ran = {r["id"]: r for r in json.load(open(sys.argv[1]))["rungs"]}
assert ran["voxel-single-draw"]["chosen"] == "fallback", ran["voxel-single-draw"]
PY
    "$idk" "${vx[@]}" --out "$tmp/n.png" --rung voxel-single-draw=native 2>"$tmp/err"; [ $? -eq 2 ] \
      || fail "--rung voxel-single-draw=native without the extensions should exit 2"
    [ "$(wc -l <"$tmp/err")" -eq 1 ] || fail "expected one line on stderr, got: $(cat "$tmp/err")"
    grep -q -- "--rung voxel-single-draw=native: device lacks VK_NV_geometry_shader_passthrough" "$tmp/err" \
      || fail "unclear error: $(cat "$tmp/err")"
    [ ! -e "$tmp/n.png" ] || fail "an image was written despite the refused rung"
    ;;
  vxgi_gl_fp16)
    # Issue 11: VXGI's gl-interop rung adds the fragments' records with the RGBA16F-image program
    # (GL_NV_shader_atomic_fp16_vector) only where the GL context has it ("vxgi-gl-accumulate" = native). Without it
    # (llvmpipe) the float-buffer program runs and --json names the fallback, and forcing native exits 2 naming the
    # extension.
    "$idk" info --json >"$tmp/info.json" || fail "idk info failed"
    state=$(python3 - "$tmp/info.json" <<'PY'
import json, sys
l = next(l for l in json.load(open(sys.argv[1]))["ladders"] if l["id"] == "vxgi-gl-accumulate")
native, fallback = l["rungs"]
assert "GL_NV_shader_atomic_fp16_vector" in native["mechanism"], native
print("native" if native["available"] else ("fallback" if fallback["available"] else "none"))
PY
    ) || fail "no vxgi-gl-accumulate ladder: $(grep -A12 'vxgi-gl-accumulate' "$tmp/info.json")"
    [ "$state" = fallback ] || exit 0  # the extension present, or no GL rung at all: nothing to check here
    vx=(render --size 16x16 --gi vxgi --voxels 64 --rung vxgi-atomics=gl-interop)
    "$idk" "${vx[@]}" --out "$tmp/f.png" --json >"$tmp/f.json" || fail "GL rung render failed"
    python3 - "$tmp/f.json" <<'PY' || fail "--json does not report the float-buffer program: $(cat "$tmp/f.json")"
import json, sys
ran = {r["id"]: r for r in json.load(open(sys.argv[1]))["rungs"]}
assert ran["vxgi-gl-accumulate"]["chosen"] == "fallback", ran["vxgi-gl-accumulate"]
PY
    "$idk" "${vx[@]}" --rung vxgi-gl-accumulate=native --out "$tmp/n.png" 2>"$tmp/err"; [ $? -eq 2 ] \
      || fail "--rung vxgi-gl-accumulate=native without the extension should exit 2"
    [ "$(wc -l <"$tmp/err")" -eq 1 ] || fail "expected one line on stderr, got: $(cat "$tmp/err")"
    grep -q -- "--rung vxgi-gl-accumulate=native: the OpenGL context lacks GL_NV_shader_atomic_fp16_vector" "$tmp/err" \
      || fail "unclear error: $(cat "$tmp/err")"
    ;;
  material_variants)
    # KHR_materials_variants: scenes/material_spheres.gltf with two variants; "velvet" gives the first sphere the
    # sheen material. --variant velvet changes the image, --variant studio (no mapping) does not, an unknown
    # name is a usage error (exit 2, one line) that lists the variants.
    src="$(dirname "$0")/../../scenes/material_spheres.gltf"
    python3 - "$src" "$tmp/variants.gltf" <<'PY' || fail "could not write the variants scene"
import json, sys
d = json.load(open(sys.argv[1]))
d["extensionsUsed"].append("KHR_materials_variants")
d["extensions"]["KHR_materials_variants"] = {"variants": [{"name": "studio"}, {"name": "velvet"}]}
d["meshes"][1]["primitives"][0]["extensions"] = {"KHR_materials_variants": {"mappings": [{"material": 3, "variants": [1]}]}}
json.dump(d, open(sys.argv[2], "w"))
PY
    "$idk" render "$tmp/variants.gltf" --size 48x48 --out "$tmp/plain.png" 2>/dev/null || fail "render failed"
    "$idk" render "$tmp/variants.gltf" --variant velvet --size 48x48 --out "$tmp/velvet.png" 2>/dev/null \
      || fail "--variant velvet failed"
    "$idk" render "$tmp/variants.gltf" --variant studio --size 48x48 --out "$tmp/studio.png" 2>/dev/null \
      || fail "--variant studio failed"
    "$idk" compare "$tmp/velvet.png" "$tmp/plain.png" --fail-above 0.001 >/dev/null && fail "velvet looks like the default"
    "$idk" compare "$tmp/studio.png" "$tmp/plain.png" --fail-above 0 >/dev/null || fail "studio differs from the default"
    "$idk" render "$tmp/variants.gltf" --variant nope --size 8x8 --out "$tmp/x.png" 2>"$tmp/err"
    code=$?
    [ "$code" -eq 2 ] || fail "unknown variant: exit code $code, expected 2"
    [ "$(wc -l <"$tmp/err")" -eq 1 ] || fail "expected one line on stderr, got: $(cat "$tmp/err")"
    grep -q "'nope'" "$tmp/err" && grep -q "'studio', 'velvet'" "$tmp/err" || fail "message: $(cat "$tmp/err")"
    [ -e "$tmp/x.png" ] && fail "an output was written"
    ;;
  info_json)
    "$idk" info --json >"$tmp/info.json" || fail "idk info --json failed"
    for key in '"device"' '"ladders"' '"subgroupSize"' '"chosen"' '"apiVersion"'; do
      grep -q "$key" "$tmp/info.json" || fail "missing $key in: $(cat "$tmp/info.json")"
    done
    # No shader uses double precision: shaderFloat64 is reported as unused (issue 19).
    grep -A3 '"feature": "shaderFloat64"' "$tmp/info.json" | grep -q '"use": "unused"' ||
      fail "shaderFloat64 not reported as unused in: $(cat "$tmp/info.json")"
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
  camera_flags)
    # Issue 20: an --orbit render equals the render of the same glTF with that camera added to the file (computed
    # here from the Khronos render-fidelity convention: theta = azimuth around +Y from +Z, phi = polar angle from
    # +Y), and so does --camera with the same eye and target. The asset is copied with its .bin and texture (URIs
    # stay inside the scene's folder).
    shared="${IDK_SHARED_DIR:-$(cd "$(dirname "$0")/../../.." && pwd)/shared}"
    src="$shared/scenes/Duck/glTF-Quantized"
    cp "$src/Duck.gltf" "$src/Duck.bin" "$src/DuckCM.png" "$tmp/" || fail "missing test input $src"
    orbit="theta=30,phi=60,radius=3.5,target=0,0.7,0"
    "$idk" render "$tmp/Duck.gltf" --orbit "$orbit" --size 96x64 --out "$tmp/orbit.png" --json >"$tmp/orbit.json" \
      2>"$tmp/err" || fail "orbit render failed: $(cat "$tmp/err")"
    python3 - "$tmp/Duck.gltf" "$tmp/orbit.json" "$tmp/with_camera.gltf" "$tmp/lookat.txt" <<'PY' || fail "camera file"
import json, math, sys
src, rendered, out, lookat = sys.argv[1:5]
theta, phi, radius, target = math.radians(30), math.radians(60), 3.5, (0.0, 0.7, 0.0)
d = (math.sin(phi) * math.sin(theta), math.cos(phi), math.sin(phi) * math.cos(theta))
eye = [t + radius * c for t, c in zip(target, d)]
cam = json.load(open(rendered))["camera"]
assert all(abs(a - b) < 1e-5 for a, b in zip(cam["position"], eye)), (cam["position"], eye)
# Camera axes: +Z = d (the camera looks down -Z), +Y = world up made orthogonal, +X = Y x Z.
z = d
y = [u - z[1] * c for u, c in zip((0.0, 1.0, 0.0), z)]
n = math.sqrt(sum(c * c for c in y)); y = [c / n for c in y]
x = [y[1] * z[2] - y[2] * z[1], y[2] * z[0] - y[0] * z[2], y[0] * z[1] - y[1] * z[0]]
m = [[x[0], y[0], z[0]], [x[1], y[1], z[1]], [x[2], y[2], z[2]]]  # rows of the rotation matrix
w = math.sqrt(1.0 + m[0][0] + m[1][1] + m[2][2]) / 2.0
q = [(m[2][1] - m[1][2]) / (4 * w), (m[0][2] - m[2][0]) / (4 * w), (m[1][0] - m[0][1]) / (4 * w), w]
g = json.load(open(src))
g.setdefault("cameras", []).append({"type": "perspective", "perspective": {
    "yfov": math.radians(45), "znear": cam["znear"], "zfar": cam["zfar"]}})
g["nodes"].append({"camera": len(g["cameras"]) - 1, "translation": eye, "rotation": q})
g["scenes"][g.get("scene", 0)]["nodes"].append(len(g["nodes"]) - 1)
json.dump(g, open(out, "w"))
open(lookat, "w").write("eye=%r,%r,%r:target=%r,%r,%r" % tuple(eye + list(target)))
PY
    # The file's own camera comes first in node order (index 0); the added one is index 1.
    "$idk" render "$tmp/with_camera.gltf" --camera-index 1 --size 96x64 --out "$tmp/file.png" 2>"$tmp/err" \
      || fail "--camera-index render failed: $(cat "$tmp/err")"
    "$idk" compare "$tmp/orbit.png" "$tmp/file.png" --fail-above 0 --diff "$tmp/d1.png" >"$tmp/cmp" \
      || fail "orbit vs file camera differ: $(cat "$tmp/cmp")"
    "$idk" render "$tmp/Duck.gltf" --camera "$(cat "$tmp/lookat.txt")" --size 96x64 --out "$tmp/lookat.png" 2>/dev/null \
      || fail "--camera render failed"
    "$idk" compare "$tmp/lookat.png" "$tmp/file.png" --fail-above 0 >"$tmp/cmp" \
      || fail "--camera vs file camera differ: $(cat "$tmp/cmp")"
    # The image shows the duck (not an empty or uniform frame): it differs from the file's own camera's view.
    "$idk" render "$tmp/with_camera.gltf" --camera-index 0 --size 96x64 --out "$tmp/own.png" 2>/dev/null || fail "index 0"
    "$idk" compare "$tmp/own.png" "$tmp/file.png" --fail-above 0.01 >/dev/null && fail "camera 0 and 1 look the same"
    # Usage errors name the flag and exit 2.
    for bad in "--orbit theta=0" "--orbit theta=0,phi=200" "--camera eye=0,0,1" "--camera-index 5" \
        "--camera eye=0,0,1:target=0,0,0:up=0,0,1" "--orbit-frames 0"; do
      # shellcheck disable=SC2086
      "$idk" render "$tmp/with_camera.gltf" $bad --size 8x8 --out "$tmp/x.png" 2>"$tmp/err"
      [ $? -eq 2 ] || fail "'$bad' should exit 2"
      grep -q -- "${bad%% *}" "$tmp/err" || fail "'$bad': message does not name the flag: $(cat "$tmp/err")"
    done
    # A turntable: 4 images, the first equal to the orbit's theta; with --video one 4-frame video.
    "$idk" render "$tmp/Duck.gltf" --orbit "$orbit" --orbit-frames 4 --size 96x64 --out "$tmp/turn.png" 2>/dev/null \
      || fail "--orbit-frames failed"
    for k in 000 001 002 003; do [ -s "$tmp/turn_$k.png" ] || fail "missing turn_$k.png"; done
    [ -e "$tmp/turn_004.png" ] && fail "a fifth image"
    "$idk" compare "$tmp/turn_000.png" "$tmp/orbit.png" --fail-above 0 >/dev/null || fail "turntable frame 0 != --orbit"
    "$idk" compare "$tmp/turn_001.png" "$tmp/orbit.png" --fail-above 0.01 >/dev/null && fail "frame 1 did not turn"
    "$idk" render "$tmp/Duck.gltf" --orbit-frames 4 --video "$tmp/turn.mp4" --size 32x32 2>/dev/null || fail "turntable video"
    [ "$(ffprobe -v error -count_frames -show_entries stream=nb_read_frames -of csv=p=0 "$tmp/turn.mp4")" = "4" ] \
      || fail "turntable video frame count"
    ;;
  background_transparent)
    # --background transparent: the PNG's alpha equals the EXR's coverage alpha (to 8 bits); without it, opaque.
    shared="${IDK_SHARED_DIR:-$(cd "$(dirname "$0")/../../.." && pwd)/shared}"
    scene="$shared/scenes/Duck/glTF-Quantized/Duck.gltf"
    "$idk" render "$scene" --orbit theta=20,phi=70 --size 80x60 --background transparent --out "$tmp/t.png" 2>/dev/null \
      || fail "transparent render failed"
    "$idk" render "$scene" --orbit theta=20,phi=70 --size 80x60 --out "$tmp/t.exr" 2>/dev/null || fail "EXR render failed"
    "$idk" render "$scene" --orbit theta=20,phi=70 --size 80x60 --out "$tmp/o.png" 2>/dev/null || fail "opaque render failed"
    oiiotool "$tmp/t.png" --ch R=A,G=A,B=A -d float -o "$tmp/pa.exr" && oiiotool "$tmp/t.exr" --ch R=A,G=A,B=A -o "$tmp/ea.exr" \
      && oiiotool "$tmp/o.png" --ch R=A,G=A,B=A -d float -o "$tmp/oa.exr" && oiiotool --pattern constant:color=0,0,0 80x60 3 \
      -d float -o "$tmp/black.exr" && oiiotool --pattern constant:color=1,1,1 80x60 3 -d float -o "$tmp/white.exr" \
      || fail "oiiotool failed"
    "$idk" compare "$tmp/pa.exr" "$tmp/ea.exr" --json >"$tmp/alpha.json" || fail "compare failed"
    "$idk" compare "$tmp/ea.exr" "$tmp/black.exr" --json >"$tmp/cover.json" || fail "compare failed"
    python3 - "$tmp/alpha.json" "$tmp/cover.json" <<'PY' || fail "alpha: $(cat "$tmp/alpha.json")"
import json, sys
a, c = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
assert a["maxError"] <= 0.5 / 255 + 1e-6, a["maxError"]  # 8-bit rounding of the same coverage
assert 0.05 < c["meanAbsError"] < 0.95, c  # the duck covers part of the frame: both 0 and 1 occur
PY
    "$idk" compare "$tmp/oa.exr" "$tmp/white.exr" --fail-above 0 >/dev/null || fail "default PNG is not opaque"
    "$idk" render "$scene" --background green --size 8x8 --out "$tmp/x.png" 2>/dev/null; [ $? -eq 2 ] || fail "bad --background"
    "$idk" render "$scene" --background transparent --pathtrace --size 8x8 --out "$tmp/x.png" 2>/dev/null
    [ $? -eq 2 ] || fail "--background transparent --pathtrace should exit 2 (not supported)"
    ;;
  compare_gates)
    # Issue 20: `idk compare` as a CI gate. The test image is the reference with a 5x3 block recoloured and one
    # pixel changed by a single 8-bit step: 16 changed pixels at known places.
    oiiotool --pattern constant:color=0.2,0.4,0.6 24x16 3 -d uint8 -o "$tmp/ref.png" \
      && oiiotool "$tmp/ref.png" --fill:color=0.8,0.1,0.3 5x3+7+4 --fill:color=0.20392157,0.4,0.6 1x1+20+12 \
        -o "$tmp/test.png" || fail "oiiotool failed"
    for metric in rmse relmse psnr flip; do
      "$idk" compare "$tmp/test.png" "$tmp/ref.png" --metric "$metric" --json >"$tmp/m.json" || fail "$metric: no gate, exit $?"
      v=$(python3 -c "import json,sys; print(repr(json.load(open(sys.argv[1]))['value']))" "$tmp/m.json")
      read -r lo hi < <(python3 -c "import sys; v=float(sys.argv[1]); print(v*0.999, v*1.001)" "$v")
      python3 -c "import sys; v=float(sys.argv[1]); assert v > 0 and v == v, v" "$v" || fail "$metric value $v"
      if [ "$metric" = psnr ]; then pass="--fail-below $lo"; failing="--fail-below $hi"; else pass="--fail-above $hi"; failing="--fail-above $lo"; fi
      # shellcheck disable=SC2086
      "$idk" compare "$tmp/test.png" "$tmp/ref.png" --metric "$metric" $pass >"$tmp/out" || fail "$metric $pass: exit $?: $(cat "$tmp/out")"
      grep -q "PASS" "$tmp/out" || fail "$metric: no PASS line: $(cat "$tmp/out")"
      # shellcheck disable=SC2086
      "$idk" compare "$tmp/test.png" "$tmp/ref.png" --metric "$metric" $failing >"$tmp/out"
      [ $? -eq 1 ] || fail "$metric $failing should exit 1: $(cat "$tmp/out")"
      grep -q "FAIL" "$tmp/out" || fail "$metric: no FAIL line: $(cat "$tmp/out")"
    done
    # FLIP of black against white is near 1 (0.967 by hand from the paper's constants).
    oiiotool --pattern constant:color=0,0,0 64x64 3 -d uint8 -o "$tmp/black.png" \
      && oiiotool --pattern constant:color=1,1,1 64x64 3 -d uint8 -o "$tmp/white.png" || fail "oiiotool failed"
    "$idk" compare "$tmp/black.png" "$tmp/white.png" --metric flip --fail-below 0.95 >/dev/null \
      || fail "FLIP black vs white: $("$idk" compare "$tmp/black.png" "$tmp/white.png" --metric flip)"
    # Identical images pass the strictest gates: rmse 0, PSNR infinite, FLIP 0.
    "$idk" compare "$tmp/ref.png" "$tmp/ref.png" --fail-above 0 >/dev/null || fail "identical: rmse gate"
    "$idk" compare "$tmp/ref.png" "$tmp/ref.png" --metric psnr --fail-below 1000 >/dev/null || fail "identical: psnr gate"
    "$idk" compare "$tmp/ref.png" "$tmp/ref.png" --metric flip --fail-above 0 >/dev/null || fail "identical: flip gate"
    # The diff image marks exactly the 16 changed pixels (magenta), and nothing else.
    "$idk" compare "$tmp/test.png" "$tmp/ref.png" --diff "$tmp/diff.png" --json >"$tmp/d.json" || fail "--diff failed"
    oiiotool --dumpdata "$tmp/diff.png" >"$tmp/diff.txt" || fail "cannot read the diff image"
    python3 - "$tmp/diff.txt" "$tmp/d.json" <<'PY' || fail "diff image is wrong"
import json, re, sys
marked = {(int(x), int(y)) for x, y, r, g, b in re.findall(r"Pixel \((\d+), (\d+)\): (\d+) (\d+) (\d+)", open(sys.argv[1]).read())
          if (r, g, b) == ("255", "0", "255")}
expected = {(x, y) for x in range(7, 12) for y in range(4, 7)} | {(20, 12)}
assert marked == expected, (sorted(marked ^ expected))
assert json.load(open(sys.argv[2]))["diff"]["changedPixels"] == 16
PY
    # EXR: differences up to 1e-6 are float noise, larger ones are marked.
    oiiotool --pattern constant:color=0.5,0.5,0.5 16x16 3 -d float -o "$tmp/ref.exr" \
      && oiiotool "$tmp/ref.exr" --fill:color=0.5000001,0.5,0.5 1x1+3+2 --fill:color=0.5001,0.5,0.5 2x2+10+10 \
        -d float -o "$tmp/test.exr" || fail "oiiotool failed"
    "$idk" compare "$tmp/test.exr" "$tmp/ref.exr" --diff "$tmp/diffe.png" --json >"$tmp/e.json" || fail "EXR diff failed"
    python3 -c "import json,sys; assert json.load(open(sys.argv[1]))['diff']['changedPixels'] == 4" "$tmp/e.json" \
      || fail "EXR diff: $(cat "$tmp/e.json")"
    # Refusals: another size (exit 1, both files and sizes named), usage errors (exit 2).
    oiiotool --pattern constant:color=0,0,0 24x15 3 -d uint8 -o "$tmp/small.png" || fail "oiiotool failed"
    "$idk" compare "$tmp/test.png" "$tmp/small.png" 2>"$tmp/err" >/dev/null
    [ $? -eq 1 ] || fail "size mismatch should exit 1"
    grep -q "test.png (24x16) vs .*small.png (24x15): image sizes differ" "$tmp/err" || fail "size message: $(cat "$tmp/err")"
    "$idk" compare "$tmp/test.png" "$tmp/ref.png" --fail-above 1 --fail-below 0 2>/dev/null; [ $? -eq 2 ] || fail "two gates"
    "$idk" compare "$tmp/test.png" "$tmp/ref.png" --metric ssim 2>/dev/null; [ $? -eq 2 ] || fail "unknown metric"
    "$idk" compare "$tmp/test.png" "$tmp/ref.png" --fail-above x 2>/dev/null; [ $? -eq 2 ] || fail "bad threshold"
    ;;
  pt_replay)
    # Issue 20: `--replay --pathtrace`: a 6-record capture over an animated scene; the video has 6 frames and each
    # frame (also written as EXR by --out) equals a still path-traced at the record's camera and scene time with the
    # same seed. The records look straight down -Z (yaw = pitch = 0) from positions that are exact binary
    # fractions, so the still's `--camera eye=P:target=P-Z` gives the very same floats.
    shared="${IDK_SHARED_DIR:-$(cd "$(dirname "$0")/../../.." && pwd)/shared}"
    scene="$shared/scenes/InterpolationTest/glTF-Binary/InterpolationTest.glb"
    [ -f "$scene" ] || fail "missing test input $scene"
    python3 - "$tmp/cap.idkcap" "$tmp/stills.txt" <<'PY' || fail "cannot write the test capture"
import math, struct, sys
yfov = struct.unpack("<f", struct.pack("<f", math.radians(45)))[0]
rows, stills = [], []
for i in range(6):
    p = (-0.5 + 0.25 * i, 3.0, 17.5 - 0.5 * i)
    rows.append(struct.pack("<d3f3fdI", i / 30, *p, 0.0, 0.0, yfov, 0.25 * i, 0))
    stills.append("%r eye=%r,%r,%r:target=%r,%r,%r:yfov=45" % (0.25 * i, *p, p[0], p[1], p[2] - 1))
open(sys.argv[1], "wb").write(b"IDKCAPT\0" + struct.pack("<IIfIQ", 1, 44, 30.0, 0, 6) + b"".join(rows))
open(sys.argv[2], "w").write("\n".join(stills) + "\n")
PY
    pt=(--pathtrace --spp 2 --max-depth 3 --seed 7 --size 40x24 --no-validation)
    "$idk" render "$scene" --replay "$tmp/cap.idkcap" "${pt[@]}" --video "$tmp/pt.mp4" --out "$tmp/frames/f.exr" \
      2>"$tmp/err" || fail "path-traced replay failed: $(cat "$tmp/err")"
    grep -q $'\r' "$tmp/err" && fail "progress bar on a non-terminal stderr"
    [ "$(ffprobe -v error -select_streams v:0 -count_frames -show_entries stream=nb_read_frames -of csv=p=0 "$tmp/pt.mp4")" = 6 ] \
      || fail "ffprobe does not count 6 frames"
    i=0
    while read -r time camera; do
      "$idk" render "$scene" "${pt[@]}" --time "$time" --camera "$camera" --out "$tmp/still_$i.exr" 2>/dev/null \
        || fail "still $i failed"
      "$idk" compare "$tmp/frames/f_000$i.exr" "$tmp/still_$i.exr" --fail-above 0 >"$tmp/cmp" \
        || fail "frame $i differs from its still: $(cat "$tmp/cmp")"
      i=$((i + 1))
    done <"$tmp/stills.txt"
    [ "$i" -eq 6 ] || fail "only $i stills"
    # Not trivially equal: the frames differ among themselves (camera and animation moved).
    "$idk" compare "$tmp/frames/f_0000.exr" "$tmp/frames/f_0005.exr" --fail-above 0 >/dev/null && fail "frames 0 and 5 equal"
    # --frames 2:4 renders just those two, the same as in the whole run.
    "$idk" render "$scene" --replay "$tmp/cap.idkcap" "${pt[@]}" --frames 2:4 --out "$tmp/part/f.exr" 2>/dev/null \
      || fail "--frames 2:4 failed"
    [ "$(ls "$tmp/part")" = "$(printf 'f_0002.exr\nf_0003.exr')" ] || fail "--frames 2:4 wrote: $(ls "$tmp/part")"
    "$idk" compare "$tmp/part/f_0003.exr" "$tmp/frames/f_0003.exr" --fail-above 0 >/dev/null || fail "split run differs"
    # A path-traced turntable: view 1 of 2 is the still at theta + 180 degrees; --video makes a 2-frame video.
    "$idk" render "${pt[@]}" --orbit theta=10,phi=80 --orbit-frames 2 --out "$tmp/turn.exr" 2>/dev/null || fail "PT turntable"
    "$idk" render "${pt[@]}" --orbit theta=190,phi=80 --out "$tmp/turn_still.exr" 2>/dev/null || fail "PT orbit still"
    "$idk" compare "$tmp/turn_001.exr" "$tmp/turn_still.exr" --fail-above 0 >/dev/null || fail "PT turntable view 1 != still"
    "$idk" render "${pt[@]}" --orbit-frames 2 --video "$tmp/turn.mp4" 2>/dev/null || fail "PT turntable video"
    [ "$(ffprobe -v error -count_frames -show_entries stream=nb_read_frames -of csv=p=0 "$tmp/turn.mp4")" = 2 ] \
      || fail "PT turntable video frame count"
    ;;
  rungs_agree)
    # Issue 20: `idk info --json` and `idk render --json` name the same rung, mechanism and reason for every ladder
    # the render consulted (the rungs that ran), with and without --rung forcing; the path tracer's traversal is the
    # ray-traversal ladder's rung.
    check() {  # INFO.json RENDER.json [EXPECTED_TRAVERSAL]
      python3 - "$@" <<'PY'
import json, sys
info = {l["id"]: l for l in json.load(open(sys.argv[1]))["ladders"]}
render = json.load(open(sys.argv[2]))
assert render["rungs"], "no rung reported"
for rung in render["rungs"]:
    assert rung == info[rung["id"]], (rung, info[rung["id"]])
if "pathtrace" in render:
    rt = next(r for r in render["rungs"] if r["id"] == "ray-traversal")
    ran = render["pathtrace"]["traversal"]
    assert ran == ("rayquery" if rt["chosen"] == "native" else "bvh"), (ran, rt)
    if len(sys.argv) > 3: assert ran == sys.argv[3], ran
PY
    }
    "$idk" info --json --no-validation >"$tmp/info.json" || fail "idk info failed"
    "$idk" render --json --size 32x32 --out "$tmp/r.png" >"$tmp/r.json" 2>/dev/null || fail "raster render failed"
    check "$tmp/info.json" "$tmp/r.json" || fail "raster rungs disagree: $(cat "$tmp/r.json")"
    pt=(--pathtrace --spp 1 --max-depth 2 --size 16x16 --json)
    "$idk" render "${pt[@]}" --out "$tmp/p.exr" >"$tmp/p.json" 2>/dev/null || fail "path tracer failed"
    check "$tmp/info.json" "$tmp/p.json" || fail "path-tracer rungs disagree: $(cat "$tmp/p.json")"
    "$idk" render "${pt[@]}" --traversal bvh --out "$tmp/p.exr" >"$tmp/pb.json" 2>/dev/null || fail "--traversal bvh"
    "$idk" info --json --no-validation --rung ray-traversal=fallback >"$tmp/info_b.json" || fail "info --rung"
    check "$tmp/info_b.json" "$tmp/pb.json" bvh || fail "--traversal bvh disagrees: $(cat "$tmp/pb.json")"
    if python3 -c "import json,sys; l=[l for l in json.load(open(sys.argv[1]))['ladders'] if l['id']=='ray-traversal'][0]; sys.exit(0 if l['rungs'][0]['available'] else 1)" "$tmp/info.json"; then
      "$idk" info --json --no-validation --rung ray-traversal=native >"$tmp/info_n.json" || fail "info --rung native"
      "$idk" render "${pt[@]}" --rung ray-traversal=native --out "$tmp/p.exr" >"$tmp/pn.json" 2>/dev/null || fail "--rung native"
      check "$tmp/info_n.json" "$tmp/pn.json" rayquery || fail "forced native disagrees: $(cat "$tmp/pn.json")"
    else
      "$idk" render "${pt[@]}" --rung ray-traversal=native --out "$tmp/p.exr" >/dev/null 2>&1
      [ $? -eq 2 ] || fail "forcing ray query on a device without it should exit 2"
    fi
    # Usage errors: exit 2 with the valid names.
    "$idk" info --rung warp=native 2>"$tmp/err"; [ $? -eq 2 ] || fail "unknown ladder should exit 2"
    grep -q "ray-traversal: native|fallback" "$tmp/err" || fail "no ladder list: $(cat "$tmp/err")"
    "$idk" render --rung ray-traversal=fast --size 8x8 --out "$tmp/x.png" 2>"$tmp/err"; [ $? -eq 2 ] || fail "unknown rung"
    grep -q "vxgi-atomics: native|gl-interop|fallback" "$tmp/err" || fail "no rung list: $(cat "$tmp/err")"
    IDK_GL_INTEROP=off "$idk" info --rung vxgi-atomics=gl-interop 2>"$tmp/err"; [ $? -eq 2 ] || fail "an unavailable rung should exit 2"
    grep -q "IDK_GL_INTEROP=off" "$tmp/err" || fail "the refusal should name why GL is absent: $(cat "$tmp/err")"
    grep -q "rungs this device can run: vxgi-atomics=" "$tmp/err" || fail "no runnable list: $(cat "$tmp/err")"
    "$idk" info | grep -q "ray-traversal: native|fallback" || fail "idk info does not list the rung names"
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
  culling)
    # --culling off|frustum|hiz gives the same PNG; --json reports the GPU counters per view only when culling.
    scene="$(dirname "$0")/../../../shared/scenes/SimpleInstancing/glTF-Binary/SimpleInstancing.glb"
    for mode in off frustum hiz; do
      "$idk" render "$scene" --size 48x32 --out "$tmp/$mode.png" --culling $mode --camera eye=3,2,6:target=-2,0,0 \
        --json >"$tmp/$mode.json" || fail "--culling $mode failed"
      grep -q "\"culling\": \"$mode\"" "$tmp/$mode.json" || fail "--json settings lack culling $mode"
    done
    cmp -s "$tmp/off.png" "$tmp/frustum.png" || fail "frustum culling changed the image"
    cmp -s "$tmp/off.png" "$tmp/hiz.png" || fail "hiz culling changed the image"
    grep -q '"instancesDrawn"' "$tmp/off.json" && fail "--culling off reports culling counters"
    # 125 cubes; the view looks past most of them (the exact counts are checked against the CPU oracle by
    # tests/gpu/culling).
    grep -q '"instancesTested": 125' "$tmp/frustum.json" || fail "frustum --json lacks instancesTested 125"
    drawn=$(sed -n 's/.*"instancesDrawn": \([0-9]*\).*/\1/p' "$tmp/frustum.json")
    [ -n "$drawn" ] && [ "$drawn" -gt 0 ] && [ "$drawn" -lt 125 ] || fail "frustum drew '$drawn' of 125"
    grep -q '"trianglesDrawn"' "$tmp/hiz.json" || fail "hiz --json lacks trianglesDrawn"
    # The Hi-Z pyramid's ladder: hiz consults "hiz-reduction"; forcing its compute rung gives the same image.
    "$idk" render "$scene" --size 48x32 --out "$tmp/hizc.png" --culling hiz --camera eye=3,2,6:target=-2,0,0 \
      --rung hiz-reduction=fallback --json >"$tmp/hizc.json" || fail "--rung hiz-reduction=fallback failed"
    python3 - "$tmp/hiz.json" "$tmp/hizc.json" <<'PY' || fail "hiz-reduction rungs not as expected"
import json, sys
rung = lambda f: next(r for r in json.load(open(f))["rungs"] if r["id"] == "hiz-reduction")["chosen"]
assert rung(sys.argv[2]) == "fallback", rung(sys.argv[2])
assert rung(sys.argv[1]) in ("native", "fallback"), rung(sys.argv[1])
PY
    cmp -s "$tmp/off.png" "$tmp/hizc.png" || fail "hiz culling on the compute pyramid rung changed the image"
    "$idk" render --size 8x8 --out "$tmp/x.png" --culling sometimes 2>"$tmp/err"; [ $? -eq 2 ] \
      || fail "--culling sometimes should exit 2"
    grep -q -- "off|frustum|hiz" "$tmp/err" || fail "error does not list the modes: $(cat "$tmp/err")"
    # --stats (text) lists the counters per view.
    "$idk" render "$scene" --size 48x32 --out "$tmp/st.png" --culling frustum --camera eye=3,2,6:target=-2,0,0 \
      --stats >"$tmp/stats.txt" || fail "--stats failed"
    grep -q "^culling (GPU counters per view, frustum" "$tmp/stats.txt" || fail "--stats lacks the culling block"
    grep -q "camera .* of 125 instances drawn" "$tmp/stats.txt" || fail "--stats lacks the camera's counters: $(cat "$tmp/stats.txt")"
    # A still with hiz renders two warm-ups up to the G-buffer first, so its early phase draws the visible set and
    # occlusion culls: a wall filling the view with 36 cubes behind it (a glTF written here), hiz draws the wall
    # only, the frustum all 37; the image equals --culling off.
    python3 - "$tmp/wall.gltf" <<'PY' || fail "could not write the wall scene"
import base64, json, struct, sys
# A unit cube (24 vertices with face normals, 36 indices); a wall node (scaled cube) at z = 0 and a 6 x 6 grid of
# cubes behind it (z < 0), all hidden from a camera at +z looking at the wall.
pos, nrm, idx = [], [], []
for axis in range(3):
    for sign in (-1.0, 1.0):
        n = [0.0, 0.0, 0.0]; n[axis] = sign
        u, v = [(axis + 1) % 3, (axis + 2) % 3]
        base = len(pos)
        for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            p = [0.0, 0.0, 0.0]; p[axis] = 0.5 * sign; p[u] = 0.5 * a; p[v] = 0.5 * b
            pos.append(p); nrm.append(n)
        quad = [0, 1, 2, 0, 2, 3] if sign > 0 else [0, 2, 1, 0, 3, 2]
        idx += [base + q for q in quad]
blob = b"".join(struct.pack("<3f", *p) for p in pos) + b"".join(struct.pack("<3f", *n) for n in nrm) + \
       b"".join(struct.pack("<H", i) for i in idx)
nodes = [{"mesh": 0, "translation": [0, 0, 0], "scale": [12, 12, 0.2]}]
nodes += [{"mesh": 0, "translation": [-4 + 1.6 * i, -4 + 1.6 * k, -3.0 - 0.5 * (i + k)]} for i in range(6) for k in range(6)]
g = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": list(range(len(nodes)))}], "nodes": nodes,
     "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2}]}],
     "buffers": [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
     "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 288}, {"buffer": 0, "byteOffset": 288, "byteLength": 288},
                     {"buffer": 0, "byteOffset": 576, "byteLength": 72}],
     "accessors": [{"bufferView": 0, "componentType": 5126, "count": 24, "type": "VEC3", "min": [-0.5] * 3, "max": [0.5] * 3},
                   {"bufferView": 1, "componentType": 5126, "count": 24, "type": "VEC3"},
                   {"bufferView": 2, "componentType": 5123, "count": 36, "type": "SCALAR"}]}
json.dump(g, open(sys.argv[1], "w"))
PY
    for mode in off frustum hiz; do
      "$idk" render "$tmp/wall.gltf" --size 64x64 --out "$tmp/wall_$mode.png" --culling $mode \
        --camera eye=0,0,10:target=0,0,0 --json >"$tmp/wall_$mode.json" || fail "wall render $mode failed"
    done
    cmp -s "$tmp/wall_off.png" "$tmp/wall_hiz.png" || fail "hiz culling changed the image of the wall"
    python3 - "$tmp/wall_frustum.json" "$tmp/wall_hiz.json" <<'PY' || fail "hiz did not cull the cubes behind the wall"
import json, sys
f, h = (json.load(open(p))["culling"]["camera"] for p in sys.argv[1:3])
assert f["instancesTested"] == h["instancesTested"] == 37 and f["instancesDrawn"] == 37, f
assert h["instancesDrawn"] == 1 and h["trianglesDrawn"] < f["trianglesDrawn"], (h, f)
PY
    # --geometry mesh|mdi: the task/mesh-shader path and vkCmdDrawIndexedIndirectCount give the same image; --json
    # records the path that ran (auto: the ladder's rung; culling off: one indirect draw of every instance).
    "$idk" render "$scene" --size 48x32 --out "$tmp/mdi.png" --culling hiz --geometry mdi \
      --camera eye=3,2,6:target=-2,0,0 --json >"$tmp/mdi.json" || fail "--geometry mdi failed"
    grep -q '"geometryPath": "mdi"' "$tmp/mdi.json" || fail "--geometry mdi: --json lacks geometryPath mdi"
    grep -q '"geometry": "mdi"' "$tmp/mdi.json" || fail "--geometry mdi: settings lack geometry mdi"
    grep -q '"meshletsDrawn"' "$tmp/mdi.json" && fail "--geometry mdi reports meshlet counters"
    cmp -s "$tmp/off.png" "$tmp/mdi.png" || fail "--geometry mdi changed the image"
    grep -q '"geometryPath": "indirect"' "$tmp/off.json" || fail "--culling off: geometryPath is not indirect"
    if "$idk" render "$scene" --size 48x32 --out "$tmp/mesh.png" --culling hiz --geometry mesh \
        --camera eye=3,2,6:target=-2,0,0 --json >"$tmp/mesh.json" 2>"$tmp/err"; then
      grep -q '"geometryPath": "mesh"' "$tmp/mesh.json" || fail "--geometry mesh: --json lacks geometryPath mesh"
      grep -q '"meshletsDrawn"' "$tmp/mesh.json" || fail "--geometry mesh: no meshlet counters"
      cmp -s "$tmp/mdi.png" "$tmp/mesh.png" || fail "--geometry mesh and mdi give different images"
      # --fallback takes the MDI rung for auto; an explicit --geometry mesh still runs the mesh path.
      "$idk" render "$scene" --size 48x32 --out "$tmp/meshfb.png" --fallback --geometry mesh \
        --camera eye=3,2,6:target=-2,0,0 --json >"$tmp/meshfb.json" || fail "--fallback --geometry mesh failed"
      grep -q '"geometryPath": "mesh"' "$tmp/meshfb.json" || fail "--fallback --geometry mesh did not run the mesh path"
    else
      [ $? -eq 2 ] && grep -q -- "--geometry mesh.*VK_EXT_mesh_shader" "$tmp/err" \
        || fail "--geometry mesh failed without naming the missing extension: $(cat "$tmp/err")"
    fi
    "$idk" render "$scene" --size 48x32 --out "$tmp/auto.png" --fallback --camera eye=3,2,6:target=-2,0,0 --json \
      >"$tmp/auto.json" || fail "--fallback render failed"
    grep -q '"geometryPath": "mdi"' "$tmp/auto.json" || fail "--fallback with --geometry auto did not take MDI"
    "$idk" render --size 8x8 --out "$tmp/x.png" --culling off --geometry mesh 2>"$tmp/err"; [ $? -eq 2 ] \
      || fail "--geometry mesh with --culling off should exit 2"
    grep -q -- "--geometry mesh" "$tmp/err" || fail "error does not name --geometry: $(cat "$tmp/err")"
    "$idk" render --size 8x8 --out "$tmp/x.png" --geometry triangles 2>"$tmp/err"; [ $? -eq 2 ] \
      || fail "--geometry triangles should exit 2"
    grep -q -- "auto|mesh|mdi" "$tmp/err" || fail "error does not list the geometry paths: $(cat "$tmp/err")"
    ;;
  temporal_flags)
    # Issue 12: --aa taa runs --temporal-frames jittered frames for a still (TAA passes listed), --bloom adds the
    # bloom chain; both are recorded in --json's settings; a bad choice exits 2 naming the flag.
    "$idk" render --size 16x16 --out "$tmp/t.png" --aa taa --temporal-frames 3 --bloom --ssao --json >"$tmp/t.json" \
      || fail "render with --aa taa --bloom failed"
    for key in '"aa": "taa"' '"temporal-frames": 3' '"bloom": true' '"ssao": true' '"taa_resolve"' '"motion_vectors"' '"bloom_composite"'; do
      grep -q "$key" "$tmp/t.json" || fail "--json lacks $key: $(cat "$tmp/t.json")"
    done
    "$idk" render --size 16x16 --out "$tmp/n.png" --json >"$tmp/n.json" || fail "plain render failed"
    ! grep -q '"taa_resolve"\|"bloom_composite"' "$tmp/n.json" || fail "TAA or bloom ran while off"
    "$idk" render --size 8x8 --out "$tmp/x.png" --aa fxaa 2>"$tmp/err"; [ $? -eq 2 ] || fail "--aa fxaa should exit 2"
    grep -q -- "--aa 'fxaa'" "$tmp/err" || fail "error does not name --aa: $(cat "$tmp/err")"
    ;;
  upscale_flags)
    # Issue 12: `--aa taa --upscale S` with S < 1 runs the temporal upscaler: lighting shades S^2 of the output's
    # pixels (16x16 at S = 0.5: 8x8 = 64), the upscaler's resolve runs instead of TAA's, the settings record aa and
    # the scale; `--aa upscale` is its alias; `--aa taa` alone (S = 1) runs TAA at full size; --upscale with --aa
    # none would run no temporal pass and exits 2 naming both flags; a scale outside [0.5, 1] exits 2 naming it.
    "$idk" render --size 16x16 --out "$tmp/u.png" --aa taa --upscale 0.5 --temporal-frames 2 --stats --json \
      >"$tmp/u.json" \
      || fail "render with --aa taa --upscale 0.5 failed"
    for key in '"aa": "taa"' '"upscale": 0.5' '"upscale_resolve"' '"shadingInvocations": 64'; do
      grep -q "$key" "$tmp/u.json" || fail "--json lacks $key: $(cat "$tmp/u.json")"
    done
    ! grep -q '"taa_resolve"' "$tmp/u.json" || fail "TAA's resolve ran with the upscaler"
    "$idk" render --size 16x16 --out "$tmp/a.png" --aa upscale --upscale 0.5 --temporal-frames 2 --stats --json \
      >"$tmp/a.json" || fail "render with --aa upscale --upscale 0.5 failed"
    for key in '"aa": "upscale"' '"upscale_resolve"' '"shadingInvocations": 64'; do
      grep -q "$key" "$tmp/a.json" || fail "--aa upscale: --json lacks $key: $(cat "$tmp/a.json")"
    done
    "$idk" render --size 16x16 --out "$tmp/t.png" --aa taa --temporal-frames 2 --stats --json >"$tmp/t.json" \
      || fail "render with --aa taa failed"
    for key in '"upscale": 1' '"taa_resolve"' '"shadingInvocations": 256'; do
      grep -q "$key" "$tmp/t.json" || fail "--aa taa: --json lacks $key: $(cat "$tmp/t.json")"
    done
    ! grep -q '"upscale_resolve"' "$tmp/t.json" || fail "the upscaler ran with --aa taa at S = 1"
    "$idk" render --size 16x16 --out "$tmp/v.png" --upscale 0.5 2>"$tmp/err"; [ $? -eq 2 ] \
      || fail "--upscale without --aa taa should exit 2"
    grep -q -- "--upscale '0.5'.*--aa taa" "$tmp/err" || fail "error does not name --upscale and --aa: $(cat "$tmp/err")"
    [ ! -e "$tmp/v.png" ] || fail "the refused render wrote an image"
    "$idk" render --size 8x8 --out "$tmp/x.png" --aa taa --upscale 0.3 2>"$tmp/err"; [ $? -eq 2 ] \
      || fail "--upscale 0.3 should exit 2"
    grep -q -- "--upscale '0.3'" "$tmp/err" || fail "error does not name --upscale: $(cat "$tmp/err")"
    ;;
  ssr_flags)
    # Issue 12: --ssr adds the closest-depth pyramid, the Hi-Z march and the lit-image copy (a still renders two
    # frames: hits read the previous frame's lit image); its options are recorded in --json's settings; off: none
    # of its passes runs; an out-of-range step count exits 2 naming the flag.
    "$idk" render --size 16x16 --out "$tmp/s.png" --ssr --ssr-steps 32 --ssr-thickness 0.25 --json >"$tmp/s.json" \
      || fail "render with --ssr failed"
    for key in '"ssr": true' '"ssr-steps": 32' '"ssr-thickness": 0.25' '"ssr_hiz"' '"ssr_trace"' '"ssr_keep"'; do
      grep -q "$key" "$tmp/s.json" || fail "--json lacks $key: $(cat "$tmp/s.json")"
    done
    "$idk" render --size 16x16 --out "$tmp/n.png" --json >"$tmp/n.json" || fail "plain render failed"
    ! grep -q '"ssr_hiz"\|"ssr_trace"\|"ssr_keep"' "$tmp/n.json" || fail "SSR ran while off"
    "$idk" render --size 8x8 --out "$tmp/x.png" --ssr-steps 0 2>"$tmp/err"; [ $? -eq 2 ] || fail "--ssr-steps 0 should exit 2"
    grep -q -- "--ssr-steps" "$tmp/err" || fail "error does not name --ssr-steps: $(cat "$tmp/err")"
    ;;
  light_flags)
    # Issue 13: --oit layers runs the fixed-layer rung's four passes on a scene with BLEND surfaces (and none of the
    # weighted rung's); --shadows raytraced with a light radius runs the soft-shadow denoiser, which hard shadows do
    # not; both are recorded in --json's settings; values outside the rows' ranges exit 2 naming the flag.
    shared="${IDK_SHARED_DIR:-$(cd "$(dirname "$0")/../../.." && pwd)/shared}"
    scene="$shared/scenes/AlphaBlendModeTest/glTF-Binary/AlphaBlendModeTest.glb"
    "$idk" render "$scene" --size 24x24 --out "$tmp/o.png" --oit layers --json >"$tmp/o.json" \
      || fail "render with --oit layers failed"
    for key in '"oit": "layers"' '"oit_layers_clear"' '"oit_layers_depth"' '"oit_layers_shade"' '"oit_layers_resolve"'; do
      grep -q "$key" "$tmp/o.json" || fail "--json lacks $key: $(cat "$tmp/o.json")"
    done
    ! grep -q '"oit_composite"' "$tmp/o.json" || fail "the weighted rung ran with --oit layers"
    "$idk" render --size 16x16 --out "$tmp/s.png" --shadows raytraced --light-radius 0.05 --soft-shadow-rays 4 \
      --json >"$tmp/s.json" || fail "render with soft shadows failed"
    for key in '"soft-shadow-rays": 4' '"rt_shadows"' '"rt_shadow_denoise"'; do
      grep -q "$key" "$tmp/s.json" || fail "--json lacks $key: $(cat "$tmp/s.json")"
    done
    "$idk" render --size 16x16 --out "$tmp/h.png" --shadows raytraced --json >"$tmp/h.json" \
      || fail "render with hard ray-traced shadows failed"
    ! grep -q '"rt_shadow_denoise"' "$tmp/h.json" || fail "hard shadows ran the soft-shadow denoiser"
    "$idk" render --size 8x8 --out "$tmp/x.png" --oit stacked 2>"$tmp/err"; [ $? -eq 2 ] || fail "--oit stacked should exit 2"
    grep -q -- "--oit" "$tmp/err" || fail "error does not name --oit: $(cat "$tmp/err")"
    "$idk" render --size 8x8 --out "$tmp/x.png" --soft-shadow-rays 0 2>"$tmp/err"; [ $? -eq 2 ] \
      || fail "--soft-shadow-rays 0 should exit 2"
    grep -q -- "--soft-shadow-rays" "$tmp/err" || fail "error does not name --soft-shadow-rays: $(cat "$tmp/err")"
    ;;
  temporal_replay)
    # Issue 12: capture replay with the temporal and screen-space passes keeps per-frame history: a 6-record capture
    # walking into the Cornell box with --aa taa --bloom --ssao --ssr renders a 6-frame video whose frames differ
    # among themselves (the camera moved) and, every one, from the plain replay's (the passes ran on each frame).
    # (--stats is refused with --replay; the pass lists are checked on stills by temporal_flags and ssr_flags.)
    python3 - "$tmp/cap.idkcap" 6 <<'PY' || fail "cannot write the test capture"
import struct, sys
out, n = sys.argv[1], int(sys.argv[2])
records = b"".join(struct.pack("<d3f3fdI", i / 30, -0.278 + 0.01 * i, 0.273, 0.8 - 0.06 * i, 0.02 * i, 0.0, 0.686,
                               i / 30, 0) for i in range(n))
open(out, "wb").write(b"IDKCAPT\0" + struct.pack("<IIfIQ", 1, 44, 30.0, 0, n) + records)
PY
    fx=(--aa taa --bloom --ssao --ssr --size 48x32)
    "$idk" render --replay "$tmp/cap.idkcap" "${fx[@]}" --video "$tmp/fx.mp4" 2>"$tmp/err" \
      || fail "replay with TAA, bloom, SSAO, SSR failed: $(cat "$tmp/err")"
    [ "$(ffprobe -v error -select_streams v:0 -count_frames -show_entries stream=nb_read_frames -of csv=p=0 "$tmp/fx.mp4")" = 6 ] \
      || fail "ffprobe does not count 6 frames"
    "$idk" render --replay "$tmp/cap.idkcap" --size 48x32 --video "$tmp/plain.mp4" 2>/dev/null || fail "plain replay failed"
    md5s() { ffmpeg -v error -i "$1" -f framemd5 - | grep -v '^#' | awk -F, '{print $NF}'; }
    # Distinct decoded frames: the camera's motion reaches every frame (no frame repeats a stale history).
    distinct=$(md5s "$tmp/fx.mp4" | sort -u | wc -l)
    [ "$distinct" -eq 6 ] || fail "only $distinct distinct frames of 6"
    # The passes ran on every frame: each frame differs from the plain replay's frame at the same record.
    same=$(paste -d' ' <(md5s "$tmp/fx.mp4") <(md5s "$tmp/plain.mp4") | awk '$1 == $2' | wc -l)
    [ "$same" -eq 0 ] || fail "$same frames equal to the plain replay's"
    ;;
  media_passes)
    # Issue 13: --volumetrics, --sky atmosphere and --oit weighted each add their work to the frame when on and
    # none of it when off (volumetrics on the Cornell box, the others on AlphaBlendModeTest): the passes that ran (--stats --json) for volumetrics and weighted OIT; for the sky, whose
    # bake is one submission outside the graph, the skyBakes count (1 for a still: the sun never moved) and the
    # settings record.
    shared="${IDK_SHARED_DIR:-$(cd "$(dirname "$0")/../../.." && pwd)/shared}"
    scene="$shared/scenes/AlphaBlendModeTest/glTF-Binary/AlphaBlendModeTest.glb"
    [ -f "$scene" ] || fail "missing test input $scene"
    "$idk" render "$scene" --size 24x24 --out "$tmp/off.png" --stats --json >"$tmp/off.json" || fail "plain render failed"
    ! grep -q '"volumetrics_march"\|"volumetrics_upsample"\|"oit_accumulate"\|"oit_composite"\|"skyBakes"' "$tmp/off.json" \
      || fail "volumetrics, weighted OIT or the sky bake ran while off: $(cat "$tmp/off.json")"
    passes() { python3 -c "import json,sys; print('\n'.join(json.load(open(sys.argv[1]))['passes']))" "$1"; }
    passes "$tmp/off.json" | grep -qx transparency || fail "the sorted transparency pass (the default) did not run"
    # Volumetrics scatter the scene's lights: the embedded Cornell box (AlphaBlendModeTest has none: no passes).
    "$idk" render --size 24x24 --out "$tmp/cb.png" --stats --json >"$tmp/cb.json" || fail "plain Cornell box failed"
    ! grep -q '"volumetrics_march"\|"volumetrics_upsample"' "$tmp/cb.json" || fail "volumetrics ran while off"
    "$idk" render --size 24x24 --out "$tmp/v.png" --volumetrics --stats --json >"$tmp/v.json" \
      || fail "--volumetrics failed"
    for key in '"volumetrics": true' '"volumetrics_march"' '"volumetrics_upsample"'; do
      grep -q "$key" "$tmp/v.json" || fail "--volumetrics: --json lacks $key: $(cat "$tmp/v.json")"
    done
    "$idk" render "$scene" --size 24x24 --out "$tmp/w.png" --oit weighted --stats --json >"$tmp/w.json" \
      || fail "--oit weighted failed"
    for key in '"oit": "weighted"' '"oit_accumulate"' '"oit_composite"'; do
      grep -q "$key" "$tmp/w.json" || fail "--oit weighted: --json lacks $key: $(cat "$tmp/w.json")"
    done
    ! passes "$tmp/w.json" | grep -qx transparency || fail "the sorted pass ran with --oit weighted"
    "$idk" render "$scene" --size 24x24 --out "$tmp/s.png" --sky atmosphere --sun-elevation 10 --stats --json \
      >"$tmp/s.json" || fail "--sky atmosphere failed"
    for key in '"sky": "atmosphere"' '"sun-elevation": 10' '"skyBakes": 1' '"sky"'; do
      grep -q "$key" "$tmp/s.json" || fail "--sky atmosphere: --json lacks $key: $(cat "$tmp/s.json")"
    done
    ! "$idk" compare "$tmp/s.png" "$tmp/off.png" --fail-above 0 >/dev/null || fail "the atmosphere sky left the image unchanged"
    # The path tracer under the same baked sky (issue 13: the sky as the path tracer's environment).
    "$idk" render "$scene" --pathtrace --spp 2 --max-depth 2 --size 24x24 --out "$tmp/p.exr" --no-validation \
      2>/dev/null || fail "path trace under the HDR file failed"
    "$idk" render "$scene" --pathtrace --sky atmosphere --sun-elevation 10 --spp 2 --max-depth 2 --size 24x24 \
      --out "$tmp/pa.exr" --no-validation 2>"$tmp/err" || fail "--pathtrace --sky atmosphere failed: $(cat "$tmp/err")"
    ! "$idk" compare "$tmp/pa.exr" "$tmp/p.exr" --fail-above 0 >/dev/null || fail "--pathtrace ignored --sky atmosphere"
    ;;
  *) fail "unknown case" ;;
esac
echo "ok ($case_name)"
