#!/usr/bin/env bash
# conformance_checks.sh IDK CASE: `idk conformance` and the GL-interop rung end to end (issue 15): every check
# passes on this device with --json/--junit written (every kernel family listed); a planted broken kernel (the
# native splat, the 8-wide BVH walk) fails naming kernel and rung, and the intact peer passes; with EGL
# disabled the GL rung is reported absent with the reason and everything else still runs; a forced GL rung runs;
# --device N beyond the loader's list exits 2 naming the option and the devices; a planted kernel is caught on a
# rung that runs on a context of its own.
set -u
idk="$1"
case_name="$2"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

fail() { echo "FAIL ($case_name): $*"; exit 1; }

case "$case_name" in
  json_passes)
    "$idk" conformance --json "$tmp/c.json" --junit "$tmp/c.xml" >"$tmp/out" 2>"$tmp/err" ||
      fail "exit $?: $(cat "$tmp/err")"
    python3 - "$tmp/c.json" <<'PY' || fail "JSON: $(cat "$tmp/c.json")"
import json, sys
j = json.load(open(sys.argv[1]))
checks = j["checks"]
assert j["failed"] == 0 and j["passed"] + j["skipped"] == len(checks) >= 45, (j["passed"], j["failed"], j["skipped"])
# On lavapipe + llvmpipe every rung exists but two, skipped with the ladders' reasons, and the VRS hardware rung
# (lavapipe has neither VK_KHR_fragment_shading_rate nor VK_NV_shading_rate_image): nothing else may be skipped.
skipped = {(c["kernel"], c["rung"]): c["message"] for c in checks if c["result"] == "skip"}
assert set(skipped) == {("vxgi/thin wall", "native"), ("vrs/hardware rung", "-")}, skipped
assert "VK_EXT_conservative_rasterization" in skipped[("vxgi/thin wall", "native")], skipped
assert "shading" in skipped[("vrs/hardware rung", "-")], skipped
rungs = {c["rung"] for c in checks if c["kernel"] == "float-atomics/splat"}
assert rungs == {"native", "gl-interop", "fallback"}, rungs
# every kernel family is in the registry, with per-rung results where the kernel has a ladder
families = {c["kernel"].split("/")[0] for c in checks}
want = {"sum", "scan", "sort", "subgroups", "float-atomics", "gl-interop", "pathtrace", "bvh", "denoise", "textures", "vrs",
        "culling", "ssr", "atmosphere", "vxgi", "shadows"}
assert want <= families, want - families
kernels = {c["kernel"] for c in checks}
for k in ("culling/cull kernel", "ssr/closest-depth pyramid", "bvh/refit", "bvh/offset ray origin", "atmosphere/bake",
          "pathtrace/ray sorting", "vxgi/rungs agree", "shadows/point faces rungs agree"):
    assert k in kernels, k
rungs = {c["rung"] for c in checks if c["kernel"] == "pathtrace/traversal"}
assert rungs == {"native", "fallback"}, rungs  # lavapipe has VK_KHR_ray_query: both traversal rungs run
rungs = {c["rung"] for c in checks if c["kernel"] == "vrs/classify"}
assert rungs == {"native", "fallback"}, rungs  # subgroup and shared-memory reductions
for k, ladder in (("culling/hi-z pyramid", {"native", "fallback"}), ("vxgi/voxelize", {"native", "gl-interop", "fallback"}),
                  ("vxgi/thin wall", {"native", "fallback"})):  # one run per rung of the kernel's ladder
    assert {c["rung"] for c in checks if c["kernel"] == k} == ladder, k
for k in ("bvh/blas binary", "bvh/blas 8-wide", "bvh/tlas binary", "bvh/tlas 8-wide", "pathtrace/compaction"):
    assert [c["rung"] for c in checks if c["kernel"] == k] == ["-"], k
PY
    grep -q 'tests="[0-9]*" failures="0"' "$tmp/c.xml" || fail "JUnit: $(head -3 "$tmp/c.xml")"
    [ "$(grep -c '<testcase' "$tmp/c.xml")" -ge 45 ] || fail "JUnit lists too few test cases"
    ;;
  bad_device)
    # A device index the loader does not list is a usage error naming the option and the devices there are.
    "$idk" conformance --device 99 >"$tmp/out" 2>"$tmp/err"
    code=$?
    [ "$code" -eq 2 ] || fail "exit code $code, expected 2: $(cat "$tmp/err")"
    grep -q -- "--device 99" "$tmp/err" || fail "the error does not name the option: $(cat "$tmp/err")"
    "$idk" info --json >"$tmp/info.json" || fail "idk info failed"
    name=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["device"]["name"])' "$tmp/info.json") ||
      fail "no device name in idk info --json"
    grep -qF "0: $name" "$tmp/err" || fail "the error does not list the devices ('0: $name'): $(cat "$tmp/err")"
    "$idk" conformance --device 0 --filter "sum/uint reduce" >"$tmp/out" 2>"$tmp/err" ||
      fail "--device 0 failed: $(cat "$tmp/err")"
    ;;
  broken_kernel)
    "$idk" conformance --shader-dir "$here/broken_kernels" --filter float-atomics/splat >"$tmp/out" 2>"$tmp/err"
    code=$?
    [ "$code" -eq 1 ] || fail "exit code $code, expected 1 for a broken kernel"
    grep -q "float-atomics/splat \[native\]" "$tmp/err" || fail "stderr does not name the native rung: $(cat "$tmp/err")"
    grep -q "float-atomics/splat \[gl-interop\]" "$tmp/err" || fail "stderr does not name the GL rung: $(cat "$tmp/err")"
    grep -q "float-atomics/splat \[fallback\]" "$tmp/err" && fail "the fallback kernel was not broken: $(cat "$tmp/err")"
    grep -Eq "float-atomics/splat +fallback +pass" "$tmp/out" || fail "the intact rung did not pass: $(cat "$tmp/out")"
    echo 'void main() {' >"$tmp/x.comp.glsl"
    mkdir -p "$tmp/dir/nosuch" && cp "$tmp/x.comp.glsl" "$tmp/dir/nosuch/x.comp.glsl"
    "$idk" conformance --shader-dir "$tmp/dir" 2>"$tmp/err"; [ $? -eq 1 ] || fail "an unknown shader file must be an error"
    grep -q "nosuch/x.comp.glsl" "$tmp/err" || fail "error does not name the file: $(cat "$tmp/err")"
    ;;
  broken_bvh_walk)
    "$idk" conformance --shader-dir "$here/broken_kernels" --filter "bvh/blas" >"$tmp/out" 2>"$tmp/err"
    code=$?
    [ "$code" -eq 1 ] || fail "exit code $code, expected 1 for a broken 8-wide walk"
    grep -q "bvh/blas 8-wide \[-\]" "$tmp/err" || fail "stderr does not name the 8-wide walk: $(cat "$tmp/err")"
    grep -q "closest-hit mismatches" "$tmp/err" || fail "stderr does not say what differs: $(cat "$tmp/err")"
    grep -q "bvh/blas binary \[-\]" "$tmp/err" && fail "the binary walk was not broken: $(cat "$tmp/err")"
    grep -Eq "bvh/blas binary +- +pass" "$tmp/out" || fail "the intact walk did not pass: $(cat "$tmp/out")"
    ;;
  broken_forced_rung)
    # A kernel whose rung runs on a context of its own (onRung: the fallback voxelizer on lavapipe, whose shared
    # context chose the native rung) gets the planted shader too: the r32ui fragment shader with red and green
    # swapped, made from the source at test time (a copy would go stale).
    src="$here/../../shaders_glsl/vxgi/voxelize_uint.frag.glsl"
    mkdir -p "$tmp/vx/vxgi"
    sed 's/p.accum\[0\]], voxel, floatBitsToUint(radiance.r)/p.accum[0]], voxel, floatBitsToUint(radiance.g)/' "$src" \
      >"$tmp/vx/vxgi/voxelize_uint.frag.glsl"
    cmp -s "$src" "$tmp/vx/vxgi/voxelize_uint.frag.glsl" && fail "the planted change no longer applies to $src"
    "$idk" conformance --shader-dir "$tmp/vx" --filter "vxgi/voxelize" >"$tmp/out" 2>"$tmp/err"
    code=$?
    [ "$code" -eq 1 ] || fail "exit code $code, expected 1 for a broken fallback voxelizer: $(cat "$tmp/out")"
    grep -q "vxgi/voxelize \[fallback\]" "$tmp/err" || fail "stderr does not name the fallback rung: $(cat "$tmp/err")"
    grep -Eq "vxgi/voxelize +native +pass" "$tmp/out" || fail "the intact native rung did not pass: $(cat "$tmp/out")"
    ;;
  no_egl)
    IDK_GL_INTEROP=off "$idk" info >"$tmp/info" || fail "idk info failed without EGL"
    grep -A1 "^gl interop: absent" "$tmp/info" | grep -q "IDK_GL_INTEROP=off" || fail "no reason: $(grep -A1 'gl interop' "$tmp/info")"
    grep -q "not gl-interop: no OpenGL 4.5 context: disabled by IDK_GL_INTEROP=off" "$tmp/info" ||
      fail "the ladders do not give the reason"
    IDK_GL_INTEROP=off "$idk" conformance --json "$tmp/c.json" >"$tmp/out" 2>"$tmp/err" ||
      fail "exit $? without EGL: $(cat "$tmp/err")"
    python3 - "$tmp/c.json" <<'PY' || fail "JSON without EGL: $(cat "$tmp/c.json")"
import json, sys
j = json.load(open(sys.argv[1]))
assert j["failed"] == 0 and not j["glInterop"]["available"]
# The VRS hardware rung is skipped wherever the device lacks both shading-rate extensions (lavapipe), EGL or not.
checks = [c for c in j["checks"] if not (c["kernel"] == "vrs/hardware rung" and c["result"] == "skip")]
skipped = {(c["kernel"], c["rung"]) for c in checks if c["result"] == "skip"}
gl = {("float-atomics/splat", "gl-interop"), ("gl-interop/round trip", "-"), ("vxgi/voxelize", "gl-interop")}
assert skipped == gl | {("vxgi/thin wall", "native")}, skipped  # the last: lavapipe lacks conservative raster
assert all("IDK_GL_INTEROP=off" in c["message"] for c in checks if (c["kernel"], c["rung"]) in gl)
assert sum(c["result"] == "pass" for c in checks) == len(checks) - 4
PY
    IDK_GL_INTEROP=off "$idk" info --rung float-atomics=gl-interop 2>"$tmp/err"
    [ $? -eq 2 ] || fail "forcing the absent GL rung should exit 2"
    grep -q "IDK_GL_INTEROP=off" "$tmp/err" || fail "the refusal does not say why: $(cat "$tmp/err")"
    ;;
  forced_gl_rung)
    "$idk" info --json --rung float-atomics=gl-interop >"$tmp/info.json" || fail "forcing the GL rung failed"
    python3 - "$tmp/info.json" <<'PY' || fail "info: $(cat "$tmp/info.json")"
import json, sys
j = json.load(open(sys.argv[1]))
assert j["glInterop"]["available"], j["glInterop"]
l = next(l for l in j["ladders"] if l["id"] == "float-atomics")
assert l["chosen"] == "gl-interop" and "forced" in l["reason"], l
assert "GL_EXT_semaphore_fd" in j["glInterop"]["note"], j["glInterop"]  # the sync mode is stated
s = j["glInterop"]["sync"]
assert s["mode"] in ("semaphores", "cpu-wait") and s["why"] in j["glInterop"]["note"], s
if "llvmpipe" in j["glInterop"]["note"]:  # neither GL_EXT_semaphore_fd nor VK_KHR_external_semaphore_fd there
    assert s["mode"] == "cpu-wait" and "GL lacks GL_EXT_semaphore_fd" in s["why"], s
PY
    IDK_GL_SYNC=cpu "$idk" info --json >"$tmp/cpu.json" || fail "IDK_GL_SYNC=cpu info failed"
    IDK_GL_SYNC=gpu "$idk" info --json >"$tmp/bad.json" || fail "IDK_GL_SYNC=gpu info failed"
    python3 - "$tmp/cpu.json" "$tmp/bad.json" <<'PY' || fail "IDK_GL_SYNC: $(cat "$tmp/cpu.json" "$tmp/bad.json")"
import json, sys
cpu, bad = (json.load(open(f))["glInterop"] for f in sys.argv[1:3])
assert cpu["sync"] == {"mode": "cpu-wait", "why": "forced by IDK_GL_SYNC=cpu"}, cpu
assert "sync: CPU-side waits (forced by IDK_GL_SYNC=cpu)" in cpu["note"], cpu
assert bad["sync"]["mode"] == "cpu-wait" and "IDK_GL_SYNC=gpu" in bad["sync"]["why"], bad
PY
    "$idk" conformance --rung float-atomics=gl-interop --filter "float-atomics/splat [gl-interop]" >"$tmp/out" ||
      fail "the forced GL rung's check failed: $(cat "$tmp/out")"
    ;;
  *) fail "unknown case" ;;
esac
exit 0
