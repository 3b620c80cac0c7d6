#!/usr/bin/env bash
# vxgi_memory.sh IDK: the VXGI grid's memory check (frame/vxgi_memory.hpp, issue 11) with a forced small budget
# (IDK_TEST_MEMORY_BUDGET_MIB, vk/memory_budget.hpp). 90 MiB free: --voxels 128 (167.9 MiB in one slab with the
# packed directional volumes of lavapipe's "vxgi-volume-format" rung, the merge's 1 MiB cell mask and the 16 MiB of
# depth keys included; 97.9 MiB in 8 z-slabs, the least) is refused with exit 1 and one line naming the size, the
# bytes, the slabs, the budget and the largest size that fits (64), writing nothing; --voxels 64 (21.5 MiB) renders.
# The bytes the check computes equal what --json reports: the "vxgi" category exactly at 64^3 and 128^3 in 1 slab and
# 64^3 in 2 slabs (--gi-slabs), and the graph's transient heap holds at least the accumulators. 512^3 needs under
# 8 GiB (in 8 slabs; 10628.9 MiB in one).
set -u
idk="$1"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL (vxgi_memory): $*"; exit 1; }
render() { "$idk" render --gi vxgi --size 32x32 "$@"; }

IDK_TEST_MEMORY_BUDGET_MIB=90 render --voxels 128 --out "$tmp/refused.png" >/dev/null 2>"$tmp/err"
rc=$?
[ "$rc" -eq 1 ] || fail "--voxels 128 over the budget: exit $rc, expected 1: $(cat "$tmp/err")"
[ "$(wc -l <"$tmp/err")" -eq 1 ] || fail "expected one line on stderr, got: $(cat "$tmp/err")"
for pattern in "--voxels 128: the 128^3 VXGI grid needs 97.9 MiB" "bytes (in 8 slabs)" \
    "budget has 90.0 MiB (94371840 bytes) free" "IDK_TEST_MEMORY_BUDGET_MIB" "the largest --voxels that fits is 64"; do
  grep -qF -- "$pattern" "$tmp/err" || fail "message lacks '$pattern': $(cat "$tmp/err")"
done
grep -q "fits is 64$" "$tmp/err" || fail "message should end naming 64: $(cat "$tmp/err")"
[ ! -e "$tmp/refused.png" ] || fail "a refused render wrote its output"

IDK_TEST_MEMORY_BUDGET_MIB=90 render --voxels 64 --out "$tmp/ok.png" >/dev/null 2>"$tmp/err" ||
  fail "--voxels 64 within the budget failed: $(cat "$tmp/err")"
[ -s "$tmp/ok.png" ] || fail "--voxels 64 wrote no image"

# The computed bytes (from a 1 MiB budget's refusal) against the allocator's --json at each size and slab count.
for case in 64:1 128:1 64:2; do
  n=${case%:*} slabs=${case#*:}
  IDK_TEST_MEMORY_BUDGET_MIB=1 render --voxels "$n" --gi-slabs "$slabs" --out "$tmp/x.png" >/dev/null 2>"$tmp/err"
  [ $? -eq 1 ] || fail "--voxels $n with 1 MiB should be refused"
  grep -q "no --voxels fits: use --gi none" "$tmp/err" || fail "1 MiB: message should say nothing fits: $(cat "$tmp/err")"
  volumes=$(sed -n 's/.*volumes \([0-9]*\) + accumulators \([0-9]*\) bytes.*/\1/p' "$tmp/err")
  accumulators=$(sed -n 's/.*volumes \([0-9]*\) + accumulators \([0-9]*\) bytes.*/\2/p' "$tmp/err")
  [ -n "$volumes" ] && [ -n "$accumulators" ] || fail "no byte counts in: $(cat "$tmp/err")"
  render --voxels "$n" --gi-slabs "$slabs" --out "$tmp/s$n.png" --json >"$tmp/s.json" 2>"$tmp/err" ||
    fail "--voxels $n --gi-slabs $slabs: $(cat "$tmp/err")"
  python3 - "$tmp/s.json" "$n" "$volumes" "$accumulators" "$slabs" <<'PY' || exit 1
import json, sys
record = json.load(open(sys.argv[1]))
memory = record["memoryBytes"]
n, volumes, accumulators, slabs = sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), int(sys.argv[5])
if slabs > 1 and f"vxgi_merge slab {slabs - 1}" not in json.dumps(record):
    sys.exit(f"FAIL (vxgi_memory): {n}^3 in {slabs} slabs: no pass 'vxgi_merge slab {slabs - 1}' in --json")
if memory.get("vxgi") != volumes:
    sys.exit(f"FAIL (vxgi_memory): {n}^3: computed volumes {volumes} bytes, --json vxgi {memory.get('vxgi')}")
transients = memory.get("render graph transients", 0)
if transients < accumulators:
    sys.exit(f"FAIL (vxgi_memory): {n}^3: accumulators {accumulators} bytes exceed the transient heaps {transients}")
print(f"{n}^3: volumes {volumes} bytes = --json vxgi; accumulators {accumulators} <= transients {transients}")
PY
done

# 512^3: the least any slab count needs (8 slabs) is under 8 GiB, one slab's is not (the check only: nothing allocated).
IDK_TEST_MEMORY_BUDGET_MIB=1 render --voxels 512 --out "$tmp/z.png" >/dev/null 2>"$tmp/err"
total=$(sed -n 's/.*grid needs [0-9.]* MiB (\([0-9]*\) bytes).*(in 8 slabs).*/\1/p' "$tmp/err")
[ -n "$total" ] && [ "$total" -lt $((8192 << 20)) ] || fail "512^3 in 8 slabs should need < 8 GiB: $(cat "$tmp/err")"
IDK_TEST_MEMORY_BUDGET_MIB=1 render --voxels 512 --gi-slabs 1 --out "$tmp/z.png" >/dev/null 2>"$tmp/err"
grep -qF "needs 10628.9 MiB" "$tmp/err" || fail "512^3 in 1 slab: $(cat "$tmp/err")"

IDK_TEST_MEMORY_BUDGET_MIB=lots render --voxels 64 --out "$tmp/y.png" >/dev/null 2>"$tmp/err"
[ $? -eq 1 ] || fail "a malformed IDK_TEST_MEMORY_BUDGET_MIB should exit 1"
grep -q "IDK_TEST_MEMORY_BUDGET_MIB='lots'" "$tmp/err" || fail "message does not name the variable: $(cat "$tmp/err")"
echo "vxgi_memory: 128^3 refused at 90 MiB naming 64, 64^3 rendered, 512^3 needs $total bytes in 8 slabs"
