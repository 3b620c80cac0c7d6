#!/usr/bin/env bash
# device_failure.sh IDK CASE: a GPU that fails mid-render (issue 17, part 4), simulated by the test hook
# IDK_TEST_FAIL_SUBMIT=KIND:N (engine/vk/fault_injection.hpp: the Nth queue submission returns the error).
# Every N from the first submission up to the last one of the run is tried: each must exit with the documented
# code (3 device lost, 4 out of device memory) and one line on stderr naming the error, and leave no output file
# (not even a temporary one); the first N past the last submission must render normally.
set -u
idk="$1"
case_name="$2"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL ($case_name): $*"; exit 1; }

# expect_failures KIND CODE PATTERN STEP -- ARGS...: runs `idk ARGS` with N = 1, 1+STEP, ... until it succeeds.
expect_failures() {
  local kind=$1 code=$2 pattern=$3 step=$4; shift 5
  local n=1 failures=0
  while [ "$n" -le 200 ]; do
    rm -rf "$tmp/out"; mkdir "$tmp/out"
    IDK_TEST_FAIL_SUBMIT="$kind:$n" "$idk" "$@" >/dev/null 2>"$tmp/err"
    local rc=$?
    if [ "$rc" -eq 0 ]; then
      [ -n "$(ls "$tmp/out")" ] || fail "$kind:$n: exit 0 but no output"
      [ "$failures" -ge 2 ] || fail "$kind: only $failures failing submissions before success at $n"
      echo "$kind: submissions 1..$((n - 1)) (every ${step}th tried) failed cleanly, $n rendered"
      return 0
    fi
    [ "$rc" -eq "$code" ] || fail "$kind:$n: exit code $rc, expected $code: $(cat "$tmp/err")"
    [ "$(wc -l <"$tmp/err")" -eq 1 ] || fail "$kind:$n: expected one line on stderr, got: $(cat "$tmp/err")"
    grep -q "$pattern" "$tmp/err" || fail "$kind:$n: message lacks '$pattern': $(cat "$tmp/err")"
    grep -q "submission $n," "$tmp/err" || fail "$kind:$n: message does not name the failed submission: $(cat "$tmp/err")"
    [ -z "$(ls -A "$tmp/out")" ] || fail "$kind:$n: files left behind: $(ls -A "$tmp/out")"
    failures=$((failures + 1))
    n=$((n + step))
  done
  fail "$kind: still failing at submission $n"
}

case "$case_name" in
  render_device_lost)
    expect_failures device-lost 3 "device lost.*VK_ERROR_DEVICE_LOST" 1 -- render --size 32x24 --out "$tmp/out/x.png"
    ;;
  render_out_of_memory)
    expect_failures out-of-device-memory 4 "out of device memory.*VK_ERROR_OUT_OF_DEVICE_MEMORY" 3 -- \
      render --size 32x24 --out "$tmp/out/x.exr"
    ;;
  replay_device_lost)
    # 10 records at 30 Hz in the documented capture layout (engine/tools/camera_capture.hpp).
    python3 - "$tmp/cap.idkcap" <<'PY' || fail "cannot write the test capture"
import struct, sys
records = b"".join(struct.pack("<d3f3fdI", i / 30, -0.278, 0.273, 0.8 - 0.03 * i, 0.0, 0.0, 0.686, i / 30, 0)
                   for i in range(10))
open(sys.argv[1], "wb").write(b"IDKCAPT\0" + struct.pack("<IIfIQ", 1, 44, 30.0, 0, 10) + records)
PY
    expect_failures device-lost 3 "device lost" 5 -- render --replay "$tmp/cap.idkcap" --video "$tmp/out/v.mp4" \
      --size 32x24
    ;;
  bad_hook)
    IDK_TEST_FAIL_SUBMIT=sometimes "$idk" render --size 8x8 --out "$tmp/x.png" 2>"$tmp/err"
    [ $? -eq 1 ] || fail "a malformed IDK_TEST_FAIL_SUBMIT should exit 1"
    grep -q "IDK_TEST_FAIL_SUBMIT='sometimes'" "$tmp/err" || fail "message does not name the variable: $(cat "$tmp/err")"
    ;;
  *) fail "unknown case" ;;
esac
echo "ok ($case_name)"
