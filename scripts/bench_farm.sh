#!/usr/bin/env bash
# bench_farm.sh BUILD_DIR: issue 18's benchmark. Wall time of a 300-frame replay (Cornell box, 256x256 raster,
# lossless x264 as the farm tests use) rendered by `idk farm submit` as 1, 2 and 4 Slurm array tasks on a
# throwaway single-node cluster (tests/farm/slurm_cluster.sh, CPUs=2), against one `idk render --replay --video`
# in the same run. Median of IDK_BENCH_FARM_REPS (default 3) runs each. Per-task overhead = (1-task farm time -
# single render) : what one task costs beyond the render itself (sbatch, scheduling, the task wrapper's ffprobe
# checks, a second idk start-up for the finish job, concatenation). Writes bench/results/farm.json and
# bench/results/farm_section.md (bench_report.py includes it in BENCHMARKS.md). Needs root, slurm-wlm and munge.
set -euo pipefail
build="${1:?usage: scripts/bench_farm.sh BUILD_DIR}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
idk="$(cd "$build" && pwd)/bin/idk"
[ -x "$idk" ] || { echo "bench_farm.sh: $idk not found" >&2; exit 1; }
lavapipe=/usr/share/vulkan/icd.d/lvp_icd.json
if [ -z "${VK_ICD_FILENAMES:-}" ] && [ -f "$lavapipe" ]; then export VK_ICD_FILENAMES="$lavapipe"; fi
reps="${IDK_BENCH_FARM_REPS:-3}"
size=256x256
frames=300
tmp=$(mktemp -d)
trap '"$root/tests/farm/slurm_cluster.sh" stop "$tmp/cluster"; rm -rf "$tmp"' EXIT

python3 - "$tmp/cap.idkcap" "$frames" <<'PY'
import struct, sys
out, n = sys.argv[1], int(sys.argv[2])
records = b"".join(struct.pack("<d3f3fdI", i / 30, -0.278 + 0.0002 * i, 0.273, 0.8 - 0.001 * i, 0.0004 * i, 0.0, 0.686,
                               i / 30, 0) for i in range(n))
open(out, "wb").write(b"IDKCAPT\0" + struct.pack("<IIfIQ", 1, 44, 30.0, 0, n) + records)
PY
"$root/tests/farm/slurm_cluster.sh" start "$tmp/cluster"
. "$tmp/cluster/env"

now() { date +%s.%N; }
elapsed() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.3f", b - a }'; }
results="$tmp/times.txt"
for rep in $(seq "$reps"); do
  t0=$(now)
  "$idk" render --replay "$tmp/cap.idkcap" --video "$tmp/single.mp4" --size $size --crf 0 --no-validation 2>/dev/null
  echo "single $(elapsed "$t0")" >>"$results"
  for tasks in 1 2 4; do
    job="$tmp/job_${tasks}_$rep"
    t0=$(now)
    "$idk" farm submit "$job" --replay "$tmp/cap.idkcap" --video "$job.mp4" --chunks $tasks --size $size \
      -- --crf 0 --no-validation >/dev/null
    for _ in $(seq 1200); do [ -z "$(squeue -h -o %i)" ] && break; sleep 0.1; done
    t=$(elapsed "$t0")
    n=$(ffprobe -v error -select_streams v:0 -count_frames -show_entries stream=nb_read_frames -of csv=p=0 "$job.mp4")
    [ "$n" = "$frames" ] || { echo "bench_farm.sh: $tasks tasks: $n frames" >&2; cat "$job"/logs/* >&2; exit 1; }
    echo "tasks$tasks $t" >>"$results"
  done
done

mkdir -p "$root/bench/results"
python3 - "$results" "$root/bench/results" "$reps" "$size" "$frames" "$(uptime)" <<'PY'
import json, statistics, sys
path, out, reps, size, frames, load = sys.argv[1:7]
times = {}
for line in open(path):
    name, t = line.split()
    times.setdefault(name, []).append(float(t))
med = {k: statistics.median(v) for k, v in times.items()}
single = med["single"]
rows = []
for k in (1, 2, 4):
    t = med[f"tasks{k}"]
    rows.append({"tasks": k, "medianSeconds": t, "runs": times[f"tasks{k}"], "speedupVsSingle": single / t})
overhead = med["tasks1"] - single
json.dump({"frames": int(frames), "size": size, "repetitions": int(reps), "singleMedianSeconds": single,
           "singleRuns": times["single"], "farm": rows, "overheadPerTaskSeconds": overhead, "load": load},
          open(f"{out}/farm.json", "w"), indent=1)
lines = ["## Render farm (issue 18)", "",
         f"`scripts/bench_farm.sh build` (run by `make bench` as root; needs slurm-wlm and munge): a {frames}-frame "
         f"replay of the Cornell box at {size} (raster, lossless x264 `--crf 0`) as a Slurm job array on a "
         "single-node cluster started for the run (CPUs=2, so at most 2 tasks run at once), against one "
         f"`idk render --replay --video` in the same run. Medians of {reps} runs; wall time from `idk farm submit` to "
         "the concatenated, frame-checked video. Per-task overhead = 1-task farm - single render (sbatch, "
         "scheduling, the task's ffprobe checks, the finish job's idk start-up and concatenation). "
         f"Machine shared with other jobs: `{load.strip()}` at the end: with the 2 cores already busy, the tasks "
         "compete with each other and the split cannot speed anything up here; on idle nodes each task renders "
         "1/K of the frames.", "",
         "| run | median wall time | runs | vs single render |", "|---|---|---|---|",
         f"| single `idk render` | {single:.2f} s | {', '.join(f'{t:.2f}' for t in times['single'])} | 1.00x |"]
for r in rows:
    lines.append(f"| farm, {r['tasks']} task(s) | {r['medianSeconds']:.2f} s | "
                 f"{', '.join(f'{t:.2f}' for t in r['runs'])} | {r['speedupVsSingle']:.2f}x |")
lines += ["", f"Overhead per task: {overhead:.2f} s.", ""]
open(f"{out}/farm_section.md", "w").write("\n".join(lines))
print("\n".join(lines))
PY
