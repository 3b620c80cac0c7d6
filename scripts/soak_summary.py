#!/usr/bin/env python3
"""Summarises the soak logs (scripts/soak.sh) into bench/results/soak.json and renders its BENCHMARKS.md section.
usage: soak_summary.py LOG_DIR VIEWER_FRAMES VIEWER_SECONDS REPLAY_FRAMES REPLAY_SECONDS OUT.json
Per run: host RSS and device memory (total and by category) at the first, middle and last sample, and the
least-squares slope per 1000 frames over the samples after the first 10% of the run (start-up and texture streaming
settle there); flat memory means slopes near zero against the totals."""
import json
import sys


def slope_per_1000(points):
    n = len(points)
    if n < 2:
        return 0.0
    mx = sum(x for x, _ in points) / n
    my = sum(y for _, y in points) / n
    sxx = sum((x - mx) ** 2 for x, _ in points)
    return 1000.0 * sum((x - mx) * (y - my) for x, y in points) / sxx if sxx else 0.0


def summarise(path, frames, seconds):
    samples = [json.loads(line) for line in open(path) if line.strip()]
    if not samples:
        raise SystemExit(f"soak_summary.py: {path} has no samples")
    for s in samples:
        s["deviceTotal"] = sum(s["deviceBytes"].values())
    last = samples[-1]["frame"]
    steady = [s for s in samples if s["frame"] >= 0.1 * last] or samples
    pick = {"start": samples[0], "middle": samples[len(samples) // 2], "end": samples[-1]}
    categories = sorted({c for s in samples for c in s["deviceBytes"]})
    return {
        "frames": frames,
        "seconds": seconds,
        "samples": len(samples),
        "rssKiB": {k: v["rssKiB"] for k, v in pick.items()},
        "rssKiBPer1000Frames": slope_per_1000([(s["frame"], s["rssKiB"]) for s in steady]),
        "deviceBytes": {k: v["deviceTotal"] for k, v in pick.items()},
        "deviceBytesPer1000Frames": slope_per_1000([(s["frame"], s["deviceTotal"]) for s in steady]),
        "deviceBytesByCategory": {c: {k: v["deviceBytes"].get(c, 0) for k, v in pick.items()} for c in categories},
        "deviceMemoryObjects": {k: v["deviceMemoryObjects"] for k, v in pick.items()},
    }


def section(data):
    """BENCHMARKS.md lines for soak.json's contents."""
    mib = lambda b: f"{b / 1048576:.2f}"
    lines = ["## Soak", "",
             "Memory over long runs (`scripts/soak.sh`, part of `make bench`): the viewer for 10,000 frames at 96x96 "
             "under Xvfb with a script that flies the camera, and `idk render --replay` of a 2,000-record capture to "
             "H.264, both on lavapipe without validation. Host RSS from /proc (VmRSS), device memory from the "
             "engine's allocator by category; slope = least squares per 1000 frames after the first 10% of the run.",
             ""]
    for name in ("viewer", "replay"):
        r = data.get(name)
        if not r:
            continue
        lines += [f"### {name} ({r['frames']} frames, {r['samples']} samples, {r['seconds']} s)", "",
                  "| quantity | start | middle | end | slope per 1000 frames |", "|---|---|---|---|---|",
                  f"| host RSS (MiB) | {r['rssKiB']['start'] / 1024:.1f} | {r['rssKiB']['middle'] / 1024:.1f} | "
                  f"{r['rssKiB']['end'] / 1024:.1f} | {r['rssKiBPer1000Frames'] / 1024:+.3f} MiB |",
                  f"| device memory, total (MiB) | {mib(r['deviceBytes']['start'])} | {mib(r['deviceBytes']['middle'])} | "
                  f"{mib(r['deviceBytes']['end'])} | {r['deviceBytesPer1000Frames'] / 1048576:+.3f} MiB |"]
        for c, v in r["deviceBytesByCategory"].items():
            lines.append(f"| device: {c} (MiB) | {mib(v['start'])} | {mib(v['middle'])} | {mib(v['end'])} | |")
        lines.append("")
    return lines


def main(argv):
    if len(argv) != 7:
        raise SystemExit(__doc__)
    log_dir, out = argv[1], argv[6]
    data = {"viewer": summarise(f"{log_dir}/viewer_memory.jsonl", int(argv[2]), int(argv[3])),
            "replay": summarise(f"{log_dir}/replay_memory.jsonl", int(argv[4]), int(argv[5]))}
    with open(out, "w") as f:
        json.dump(data, f, indent=1)
    print("\n".join(section(data)))


if __name__ == "__main__":
    main(sys.argv)
