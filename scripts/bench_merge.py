#!/usr/bin/env python3
"""bench_merge.py: merges the rows of a partial idk_bench run into bench/results/latest.json.

usage: scripts/bench_merge.py LATEST.json PARTIAL.json FILTER_REGEX

Every benchmark of LATEST whose run name matches FILTER_REGEX is replaced by PARTIAL's benchmarks (placed where the
first replaced one was); the partial run's date, filter and load average are recorded in context["reruns"] so
BENCHMARKS.md says which rows come from which run. Then run scripts/bench_report.py --compact LATEST.json OUT.md.
Python 3 standard library only.
"""
import json
import re
import sys


def main(argv):
    if len(argv) != 4:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    latest_path, partial_path, pattern = argv[1:]
    regex = re.compile(pattern)
    with open(latest_path) as f:
        latest = json.load(f)
    with open(partial_path) as f:
        partial = json.load(f)

    def matches(b):
        return regex.search(b.get("run_name", b["name"])) is not None

    kept, insert_at = [], None
    for b in latest["benchmarks"]:
        if matches(b):
            if insert_at is None:
                insert_at = len(kept)
            continue
        kept.append(b)
    if insert_at is None:
        insert_at = len(kept)
    new = [b for b in partial["benchmarks"] if matches(b)]
    latest["benchmarks"] = kept[:insert_at] + new + kept[insert_at:]
    ctx = partial.get("context", {})
    reruns = [r for r in latest["context"].get("reruns", []) if r.get("filter") != pattern]
    reruns.append({"date": ctx.get("date", "?"), "filter": pattern, "load_avg": ctx.get("load_avg", [])})
    latest["context"]["reruns"] = reruns
    with open(latest_path, "w") as f:
        json.dump(latest, f, indent=1)  # NaN allowed here; bench_report.py --compact writes them as null
        f.write("\n")
    print(f"bench_merge.py: {len(new)} benchmarks from {partial_path} replace the matching rows of {latest_path}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
