#!/usr/bin/env python3
"""bench_report.py: turns idk_bench's Google Benchmark JSON into BENCHMARKS.md (DESIGN.md "Benchmarks and
reports").

usage: scripts/bench_report.py [--compact] RESULTS.json OUT.md

Each benchmark carries its row metadata in its label (bench/bench_support.hpp, setRow): group, input,
settings, rung, role (ours|peer), time (cpu|real|manual: which time the median is read from) and peer (the
names of the peer benchmarks, comma-separated). Rows are built from the "median" aggregates only; one row per
(ours, peer) pair, with the ratio ours / peer. Counters named "mismatches", "rel_error", "rel_error_indirect", "psnr_db" and "flip" fill the error
column; "pass_ms.<pass>" counters become one row per GPU pass; other counters are listed with the settings.

--compact rewrites RESULTS.json keeping only the median and cv aggregates (NaN written as null), so the
committed file stays small. Plots (PNG, bench/results/) are drawn only when matplotlib can be imported;
nothing is installed. Python 3 standard library otherwise.
"""
import datetime
import json
import math
import os
import re
import sys

GROUP_ORDER = ["compute", "render graph", "render", "scene loading", "scenes", "bvh"]
ERROR_COUNTERS = {"mismatches", "rel_error", "rel_error_indirect", "psnr_db", "flip"}
HIDDEN_COUNTERS = {"items_per_second", "bytes_per_second", "gpu_ms"}
SUFFIX = re.compile(r"/(iterations:\d+|min_time:[0-9.]+|manual_time|real_time|repeats:\d+|threads:\d+)")


def base_name(run_name):
    """The benchmark name without Google Benchmark's option suffixes: what labels use to name peers."""
    return SUFFIX.sub("", run_name)


def parse_label(label):
    info = {}
    for part in (label or "").split(";"):
        if "=" in part:
            key, value = part.split("=", 1)
            info[key] = value
    return info


def load(path):
    with open(path) as f:
        return json.load(f)


def compact(path, data):
    def clean(value):
        if isinstance(value, float) and not math.isfinite(value):
            return None
        return value

    kept = [{k: clean(v) for k, v in b.items()} for b in data["benchmarks"]
            if b.get("run_type") != "aggregate" or b.get("aggregate_name") in ("median", "cv")]
    data = dict(data, benchmarks=kept)
    with open(path, "w") as f:
        json.dump(data, f, indent=1, allow_nan=False)
        f.write("\n")


def to_ms(value, unit):
    return value * {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[unit]


def fmt_ms(ms):
    if ms is None:
        return "-"
    if ms >= 1000:
        return f"{ms / 1000:.2f} s"
    if ms >= 1:
        return f"{ms:.2f} ms"
    if ms >= 0.001:
        return f"{ms * 1000:.1f} µs"
    return f"{ms * 1e6:.0f} ns"


def fmt_number(value):
    if value is None:
        return "-"
    if value == int(value) and abs(value) < 1e9:
        return str(int(value))
    return f"{value:.3g}"


class Result:
    def __init__(self, median, cv):
        self.run_name = median["run_name"]
        self.name = base_name(self.run_name)
        self.info = parse_label(median.get("label"))
        which = "cpu_time" if self.info.get("time") == "cpu" else "real_time"
        self.ms = to_ms(median[which], median["time_unit"])
        self.cv = cv.get(which) if cv else None
        self.counters = {k: v for k, v in median.items()
                         if isinstance(v, (int, float)) and not isinstance(v, bool) and k not in (
                             "family_index", "per_family_instance_index", "repetitions", "repetition_index",
                             "threads", "iterations", "real_time", "cpu_time")}
        self.skipped = median.get("error_occurred", False)

    def error_text(self):
        parts = []
        if "mismatches" in self.counters:
            parts.append(f"{fmt_number(self.counters['mismatches'])} mismatches")
        if "rel_error" in self.counters:
            parts.append(f"{self.counters['rel_error']:.2g} relative")
        if "rel_error_indirect" in self.counters:  # the indirect term alone (e.g. VXGI vs a depth-matched reference)
            parts.append(f"{self.counters['rel_error_indirect']:.2g} indirect")
        if "psnr_db" in self.counters:  # image error against an exact reference (e.g. 16x supersampling)
            parts.append(f"PSNR {self.counters['psnr_db']:.2f} dB")
        if "flip" in self.counters:
            parts.append(f"FLIP {self.counters['flip']:.4f}")
        return ", ".join(parts) or "-"

    def facts(self):
        return [f"{k}={fmt_number(v)}" for k, v in sorted(self.counters.items())
                if k not in ERROR_COUNTERS and k not in HIDDEN_COUNTERS and not k.startswith("pass_ms.")
                and v is not None]


def collect(data):
    medians, cvs, errors = {}, {}, []
    for b in data["benchmarks"]:
        if b.get("error_occurred"):
            entry = (base_name(b.get("run_name", b["name"])), b.get("error_message", ""))
            if entry not in errors:
                errors.append(entry)
            continue
        if b.get("run_type") != "aggregate":
            continue
        if b.get("aggregate_name") == "median":
            medians[b["run_name"]] = b
        elif b.get("aggregate_name") == "cv":
            cvs[b["run_name"]] = b
    results = [Result(m, cvs.get(name)) for name, m in medians.items()]
    return results, errors


def md_escape(text):
    return text.replace("|", "\\|")


def command(exe, names):
    pattern = names[0] if len(names) == 1 else "(" + "|".join(names) + ")"
    return (f"`{exe} --benchmark_filter='^{pattern}(/|$)' --benchmark_repetitions=5 "
            f"--benchmark_report_aggregates_only=true`")


def build_rows(results, exe):
    by_name = {r.name: r for r in results}
    groups = {}
    for r in results:
        if r.info.get("role") == "peer":
            continue
        group = r.info.get("group", "other")
        peers = [p for p in r.info.get("peer", "").split(",") if p]
        settings = r.info.get("settings", "-")
        facts = r.facts()
        if facts:
            settings += " (" + ", ".join(facts) + ")"
        base = [r.name, r.info.get("input", "-"), settings, r.info.get("rung", "-")]
        rows = groups.setdefault(group, [])
        for peer_name in peers or [None]:
            peer = by_name.get(peer_name) if peer_name else None
            if peer_name and not peer:
                peer_text, peer_ms, ratio = f"{peer_name} (not run)", "-", "-"
            elif peer:
                peer_text = peer.info.get("settings", peer.name)
                peer_ms = fmt_ms(peer.ms)
                ratio = f"{r.ms / peer.ms:.2f}" if peer.ms > 0 else "-"
            else:
                peer_text, peer_ms, ratio = "-", "-", "-"
            names = [r.name] + ([peer.name] if peer else [])
            rows.append(base + [fmt_ms(r.ms), r.error_text(), peer_text, peer_ms, ratio, command(exe, names)])
        for key in sorted(k for k in r.counters if k.startswith("pass_ms.")):
            rows.append([f"`{r.name}` GPU pass `{key[len('pass_ms.'):]}`", r.info.get("input", "-"),
                         "GPU time of the pass from FrameResult::passTimes (timestamp queries), mean per frame",
                         r.info.get("rung", "-"), fmt_ms(r.counters[key]), "-", "-", "-", "-", command(exe, [r.name])])
    return groups


def header(data, results, errors, plots_note):
    ctx = data["context"]
    lines = ["# Benchmarks", "",
             "Generated by `scripts/bench_report.py` from `bench/results/latest.json` (written by `make bench`, "
             "which runs `scripts/bench.sh`). Do not edit by hand.", "",
             "Every time below is the **median of 5 repetitions** (the machines are noisy; means, minima and "
             "single runs are not reported). GPU times are timestamp-query intervals around the dispatches only "
             "(no upload or readback); CPU peers are timed around the algorithm only (no input copy). "
             "Ratio = ours / peer: below 1 means ours is faster. Timings are never test assertions.", "",
             "| | |", "|---|---|"]
    date = ctx.get("date", "")
    try:
        date = datetime.datetime.fromisoformat(date).strftime("%Y-%m-%d %H:%M %Z").strip()
    except ValueError:
        pass
    rows = [("date", date),
            ("device", ctx.get("device", "?")),
            ("driver", ctx.get("driver", "?")),
            ("Vulkan API", ctx.get("vulkan_api", "?")),
            ("subgroup size", ctx.get("subgroup_size", "?")),
            ("uploads", ctx.get("uploads", "?")),
            ("validation layer", ctx.get("validation", "?")),
            ("machine", f"{ctx.get('num_cpus', '?')} cores at {ctx.get('mhz_per_cpu', '?')} MHz, host "
                        f"`{ctx.get('host_name', '?')}`, load average at start "
                        + " / ".join(f"{x:.2f}" for x in ctx.get("load_avg", []))),
            ("build", f"idk {ctx.get('idk_build_type', '?')}; Google Benchmark library reports itself as "
                      f"{ctx.get('library_build_type', '?')} (affects only the harness)")]
    # Rows re-measured in a later run and merged in (scripts/bench_merge.py): when, which rows, load at its start.
    for rerun in ctx.get("reruns", []):
        rows.append(("re-run", f"{rerun.get('date', '?')}: {rerun.get('filter', '?')}, load average at start "
                               + " / ".join(f"{x:.2f}" for x in rerun.get("load_avg", []))))
    for key, value in rows:
        lines.append(f"| {key} | {md_escape(str(value))} |")
    spreads = [(r.cv, r.name) for r in results if r.cv is not None]
    if spreads:
        cv, name = max(spreads)
        lines.append(f"| noise | largest coefficient of variation over the repetitions: {cv * 100:.1f} % "
                     f"(`{name}`) |")
    lines += ["", "## Capability ladder rungs on this device", ""]
    if ctx.get("ladders_json"):
        # The ladder table with its reasons, as `idk info` prints it; each row's "capability rung" column lists the
        # ladders that row's code consulted (what ran), e.g. the path tracer's traversal.
        lines += ["| ladder | feature | rung (mechanism) | why |", "|---|---|---|---|"]
        for l in json.loads(ctx["ladders_json"]):
            lines.append(f"| `{l['id']}` | {md_escape(l['feature'])} | {md_escape(l['chosen'])} "
                         f"({md_escape(l['mechanism'])}) | {md_escape(l['reason'])} |")
    else:  # results recorded before the ladders carried their reasons
        lines += ["| feature | rung (mechanism) |", "|---|---|"]
        for part in ctx.get("ladders", "").split("; "):
            if ": " in part:
                feature, rung = part.split(": ", 1)
                lines.append(f"| {md_escape(feature)} | {md_escape(rung)} |")
    lines += ["", f"Reproduce everything: `make bench`. Each row's last column reproduces that row and its peer "
              "(in the Markdown source a `|` inside it is written `\\|`). "
              "Set `VK_ICD_FILENAMES=/usr/share/vulkan/icd.d/lvp_icd.json` for lavapipe, as `scripts/bench.sh` "
              f"does. {plots_note}", ""]
    if errors:
        lines += ["Benchmarks that did not run:", ""]
        lines += [f"- `{name}`: {md_escape(message)}" for name, message in errors]
        lines.append("")
    return lines


COLUMNS = ["benchmark", "scene / input", "settings", "capability rung", "median time", "error", "peer",
           "peer median", "ratio (ours / peer)", "reproduce"]


def table(rows):
    lines = ["| " + " | ".join(COLUMNS) + " |", "|" + "---|" * len(COLUMNS)]
    for row in rows:
        cells = [md_escape(c) for c in row]
        cells[0] = f"`{cells[0]}`" if "`" not in cells[0] else cells[0]
        lines.append("| " + " | ".join(cells) + " |")
    return lines


def plot(results, out_dir):
    """Bar charts ours vs peer per group, and speed vs error for rows with an error. Returns a note."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except Exception:  # noqa: BLE001 - any import failure means no plots
        return "Plots skipped: matplotlib is not importable on this machine (nothing is installed for them)."
    by_name = {r.name: r for r in results}
    written = []
    groups = {}
    for r in results:
        if r.info.get("role") != "peer":
            groups.setdefault(r.info.get("group", "other"), []).append(r)
    for group, ours in groups.items():
        labels, values, colors = [], [], []
        for r in ours:
            labels.append(r.name)
            values.append(r.ms)
            colors.append("tab:blue")
            for p in filter(None, r.info.get("peer", "").split(",")):
                if p in by_name:
                    labels.append(p)
                    values.append(by_name[p].ms)
                    colors.append("tab:gray")
        fig, ax = plt.subplots(figsize=(8, 0.45 * len(labels) + 1.2))
        ax.barh(labels[::-1], values[::-1], color=colors[::-1])
        ax.set_xscale("log")
        ax.set_xlabel("median time (ms, log scale); blue: ours, grey: peer")
        ax.set_title(group)
        fig.tight_layout()
        path = os.path.join(out_dir, group.replace(" ", "_") + ".png")
        fig.savefig(path, dpi=100)
        plt.close(fig)
        written.append(path)
    points = [r for r in results if "rel_error" in r.counters and r.counters["rel_error"]]
    if points:
        fig, ax = plt.subplots(figsize=(6, 4))
        for r in points:
            ax.scatter(r.ms, r.counters["rel_error"])
            ax.annotate(r.name, (r.ms, r.counters["rel_error"]), fontsize=8)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("median time (ms)")
        ax.set_ylabel("relative error")
        ax.set_title("speed vs error")
        fig.tight_layout()
        path = os.path.join(out_dir, "speed_vs_error.png")
        fig.savefig(path, dpi=100)
        plt.close(fig)
        written.append(path)
    written += upscale_plot(results, out_dir, plt)
    written += pass_error_plot(results, out_dir, plt)
    return "Plots: " + ", ".join(f"`{os.path.relpath(p)}`" for p in written) + "." if written else ""


def upscale_plot(results, out_dir, plt):
    """Issue 12: the upscaler's PSNR and FLIP against the render scale S (BM_Upscale/s<S>), with TAA at full
    resolution (BM_Upscale/taa), the no-AA frame (BM_Upscale/full) and bilinear upscaling of the same S x frames
    (the rows' bilinear_* counters) as references."""
    rows = sorted(((float(r.name.rsplit("/s", 1)[1]), r) for r in results
                   if r.name.startswith("BM_Upscale/s") and "psnr_db" in r.counters), key=lambda p: p[0])
    if not rows:
        return []
    by_name = {r.name: r for r in results}
    scales = [s for s, _ in rows]
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for ax, key, label in ((axes[0], "psnr_db", "PSNR (dB, higher is better)"),
                           (axes[1], "flip", "mean FLIP (lower is better)")):
        ours = [(s, r.counters[key]) for s, r in rows if r.counters.get(key) is not None]
        if ours:
            ax.plot([s for s, _ in ours], [v for _, v in ours], "o-", color="tab:blue", label="temporal upscaler")
        bilinear = [(s, r.counters["bilinear_" + key]) for s, r in rows
                    if r.counters.get("bilinear_" + key) is not None]
        if bilinear:
            ax.plot([s for s, _ in bilinear], [v for _, v in bilinear], "s--", color="tab:gray",
                    label="bilinear upscaling (no AA)")
        for name, style, text in (("BM_Upscale/taa", "tab:green", "TAA at full resolution"),
                                  ("BM_Upscale/full", "tab:red", "no AA at full resolution")):
            r = by_name.get(name)
            if r and r.counters.get(key) is not None:
                ax.axhline(r.counters[key], color=style, linestyle=":", label=text)
        ax.set_xlabel("render scale S (each axis)")
        ax.set_ylabel(label)
        ax.set_xticks(scales)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle("temporal upscaler vs 16x supersampled truth (replayed camera path)")
    fig.tight_layout()
    path = os.path.join(out_dir, "upscale_error_vs_scale.png")
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return [path]


ISSUE_12_13_GROUPS = ("temporal", "upscale", "screen-space reflections", "lights")


def pass_error_plot(results, out_dir, plt):
    """Issues 12 and 13: time against error for each pass's rows, PSNR (dB) where a row has it, else its relative
    error, one panel each."""
    rows = [r for r in results if r.info.get("group") in ISSUE_12_13_GROUPS]
    psnr = [r for r in rows if r.counters.get("psnr_db") is not None]
    rel = [r for r in rows if r.counters.get("psnr_db") is None and r.counters.get("rel_error")]
    if not psnr and not rel:
        return []
    fig, axes = plt.subplots(1, 2, figsize=(12, 5))
    colors = {g: c for g, c in zip(ISSUE_12_13_GROUPS, ("tab:blue", "tab:orange", "tab:green", "tab:purple"))}
    for ax, points, key in ((axes[0], psnr, "psnr_db"), (axes[1], rel, "rel_error")):
        for r in points:
            ax.scatter(r.ms, r.counters[key], color=colors[r.info["group"]])
            ax.annotate(r.name[3:] if r.name.startswith("BM_") else r.name, (r.ms, r.counters[key]), fontsize=7)
        ax.set_xscale("log")
        ax.set_xlabel("median time (ms, log scale)")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("PSNR vs exact reference (dB, higher is better)")
    axes[1].set_ylabel("relative error vs exact reference (log, lower is better)")
    axes[1].set_yscale("log")
    for group, color in colors.items():
        axes[0].scatter([], [], color=color, label=group)
    axes[0].legend(fontsize=8)
    fig.suptitle("issue 12/13 passes: time vs error")
    fig.tight_layout()
    path = os.path.join(out_dir, "passes_time_vs_error.png")
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return [path]


# ---- BVH section (bench/bvh_bench.cpp) ------------------------------------------------------------------------

BVH_COLUMNS = ["scene", "builder / traversal", "build", "SAH", "EPO", "Mrays/s", "peer", "ratio", "reproduce"]


def bvh_section(results, exe):
    """The BVH table: builds (ours at three split factors, Embree rtcBuildBVH at three qualities) with SAH and EPO by
    our formulas, CPU single-ray traversal against Embree rtcIntersect1, GPU traversal; then the issue's targets."""
    rows = [r for r in results if r.info.get("group") == "bvh"]
    by_name = {r.name: r for r in rows}
    scenes = []
    for r in rows:
        scene = r.name.split("/")[1]
        if scene not in scenes:
            scenes.append(scene)

    def get(name):
        return by_name.get(name)

    def mrays(r):
        rate = r.counters.get("items_per_second") if r else None
        return rate / 1e6 if rate else None

    def num(value, digits=2):
        return "-" if value is None else f"{value:.{digits}f}"

    def builder(r):
        kind = r.name.split("/")[2]
        if r.name.startswith("BM_BvhBuild/"):
            if kind == "spatial":
                return "ours, spatial splits (SBVH, budget 2x)"
            return "ours, split factor " + kind.replace("split_", "")
        if r.name.startswith("BM_EmbreeBuild/"):
            if kind == "high_exact":
                return "Embree high (spatial splits, exact triangle clipping)"
            return "Embree " + kind + (" (spatial splits)" if kind == "high" else "")
        if r.name.startswith("BM_BvhTraceCpu/"):
            return f"ours CPU, {kind} rays"
        if r.name.startswith("BM_EmbreeTraceCpu/"):
            return f"Embree rtcIntersect1, {kind} rays"
        errors = r.counters.get("mismatches")
        suffix = f" ({fmt_number(errors)} mismatches vs CPU)" if errors is not None else ""
        device = r.info.get("rung", "?").replace(", ray query", "")
        if r.name.startswith("BM_BvhTraceGpuRayQuery/"):  # bench/bvh_wide_bench.cpp: the driver's traversal
            differ = f" ({fmt_number(errors)} hits differ from our CPU's)" if errors is not None else ""
            return f"VK_KHR_ray_query on {device}, {kind} rays{differ}"
        if r.name.startswith("BM_BvhTraceGpuWide/"):
            return f"ours GLSL 8-wide compressed on {device}, {kind} rays{suffix}"
        return f"ours GLSL on {device}, {kind} rays{suffix}"

    table_lines = ["| " + " | ".join(BVH_COLUMNS) + " |", "|" + "---|" * len(BVH_COLUMNS)]
    summary = {"build": [], "cpu": [], "gpu": []}
    issue19 = []  # one row per scene: the spatial builder and the best of ours against Embree medium / high
    for scene in scenes:
        input_text = next((r.info.get("input", scene) for r in rows if r.name.split("/")[1] == scene), scene)
        medium = get(f"BM_EmbreeBuild/{scene}/medium")
        high = get(f"BM_EmbreeBuild/{scene}/high")
        ordered = [r for r in rows if r.name.split("/")[1] == scene]
        order = ["BM_BvhBuild", "BM_EmbreeBuild", "BM_BvhTraceCpu", "BM_EmbreeTraceCpu", "BM_BvhTraceGpu",
                 "BM_BvhTraceGpuWide", "BM_BvhTraceGpuRayQuery"]
        ordered.sort(key=lambda r: (order.index(r.name.split("/")[0]) if r.name.split("/")[0] in order else 9,
                                    "diffuse" in r.name))
        first = True
        for r in ordered:
            kind = r.info.get("bvh")
            build = sah = epo = rate = peer = ratio = "-"
            names = [r.name]
            if kind == "build":
                build = fmt_ms(r.ms)
                sah = num(r.counters.get("sah"))
                epo = num(r.counters.get("epo"))
                if r.info.get("role") != "peer":
                    parts, ratios = [], []
                    if medium:
                        parts.append(f"Embree medium {fmt_ms(medium.ms)}")
                        ratios.append(f"build {r.ms / medium.ms:.2f}x")
                        names.append(medium.name)
                    if high and high.counters.get("sah"):
                        parts.append(f"Embree high SAH {high.counters['sah']:.2f}")
                        ratios.append(f"SAH {r.counters.get('sah', 0) / high.counters['sah']:.3f}x")
                        names.append(high.name)
                    peer, ratio = "; ".join(parts) or "-", ", ".join(ratios) or "-"
            else:
                rate = num(mrays(r))
                peer_name = r.info.get("peer", "")
                peer_result = get(peer_name) if peer_name else None
                if peer_result and mrays(peer_result) and mrays(r):
                    what = ("ray query" if peer_name.startswith("BM_BvhTraceGpuRayQuery/")
                            else "ours CPU" if peer_name.startswith("BM_BvhTraceCpu/") else "Embree")
                    peer = f"{what} {mrays(peer_result):.2f} Mrays/s"
                    ratio = f"{mrays(r) / mrays(peer_result):.2f}x throughput"
                    names.append(peer_result.name)
            cells = [md_escape(input_text) if first else "", md_escape(builder(r)), build, sah, epo, rate,
                     md_escape(peer), ratio, command(exe, names)]
            first = False
            table_lines.append("| " + " | ".join(cells) + " |")

        ours_builds = [get(f"BM_BvhBuild/{scene}/{k}") for k in ("split_0", "split_0.3", "split_1", "spatial")]
        ours_builds = [b for b in ours_builds if b and b.counters.get("sah")]
        spatial = get(f"BM_BvhBuild/{scene}/spatial")
        if ours_builds and high and high.counters.get("sah"):
            best = min(ours_builds, key=lambda b: b.counters["sah"])
            issue19.append((scene, spatial, best, medium, high, get(f"BM_EmbreeBuild/{scene}/high_exact")))
        split0 = get(f"BM_BvhBuild/{scene}/split_0")
        if split0 and medium:
            ratio = split0.ms / medium.ms
            summary["build"].append((scene, ratio <= 1.5, f"{scene}: split 0 {fmt_ms(split0.ms)} vs Embree medium "
                                     f"{fmt_ms(medium.ms)} = {ratio:.3f}x"))
        for rays in ("primary", "diffuse"):
            ours, theirs = get(f"BM_BvhTraceCpu/{scene}/{rays}"), get(f"BM_EmbreeTraceCpu/{scene}/{rays}")
            if ours and theirs and mrays(ours) and mrays(theirs):
                ratio = mrays(ours) / mrays(theirs)
                summary["cpu"].append((scene, ratio >= 0.5, f"{scene} {rays}: {mrays(ours):.2f} vs "
                                       f"{mrays(theirs):.2f} Mrays/s = {ratio:.3f}x"))
            binary, wide = get(f"BM_BvhTraceGpu/{scene}/{rays}"), get(f"BM_BvhTraceGpuWide/{scene}/{rays}")
            query = get(f"BM_BvhTraceGpuRayQuery/{scene}/{rays}")
            if query and mrays(query) and (mrays(binary) or mrays(wide)):
                best = max(mrays(b) or 0.0 for b in (binary, wide))
                parts = [f"{label} {mrays(b):.2f}" for label, b in (("binary", binary), ("wide", wide)) if mrays(b)]
                summary["gpu"].append((scene, best >= mrays(query), f"{scene} {rays}: " + ", ".join(parts) +
                                       f" vs ray query {mrays(query):.2f} Mrays/s = {best / mrays(query):.2f}x"))

    lines = ["## BVH", "",
             "`bench/bvh_bench.cpp`: our SweepSAH builder (`engine/bvh`, leaves of at most 8 triangles, every hardware "
             "thread) at split factors 0, 0.3 and 1.0 and our spatial-split builder (`engine/bvh/sbvh.hpp`, SBVH with "
             "at most 2 references per triangle) against Embree 3's `rtcBuildBVH` (low, medium, and high with "
             "spatial splits and room for 2 references per triangle, its split callback chopping with our padded "
             "`splitTriangle`, and once more with the exact clipping our spatial splits use; same leaf size and SAH costs, its nodes converted into our tree shape through the "
             "create-node / set-bounds callbacks, so SAH and EPO are computed by our `computeSah` / `computeEpo` on "
             "both). Build time is wall time around the build only. CPU traversal: closest hit, one ray at a time on "
             "one thread (ours over the split-0.3 BLAS, Embree `rtcIntersect1` on an `RTC_SCENE_FLAG_ROBUST` "
             "high-quality scene), 256x256 primary camera rays and 65536 cosine-weighted diffuse bounce rays from the "
             "primary hits; its throughput is measured in thread CPU time (robust to other load on the machine). GPU "
             "traversal: the GLSL include `shaders_glsl/include/bvh_traverse.glsl` in one dispatch, timestamp queries, "
             "on the device named in its row (on lavapipe it runs on the same CPU cores); its mismatches are against "
             "our CPU traversal (same triangle and t). `bench/bvh_wide_bench.cpp` adds, on the same rays, the 8-wide "
             "compressed BVH walk (`include/bvh_traverse_wide.glsl`, issue 19) and the device's `VK_KHR_ray_query` over "
             "the driver's acceleration structure (peer of the wide row). The ~1M-triangle MetalRoughSpheres runs 3 repetitions instead "
             "of 5. Ratios: build ours / Embree-medium time, SAH ours / Embree-high SAH, throughput ours / peer.", ""]
    lines += table_lines + [""]
    lines += issue19_lines(issue19, builder)
    lines += ["### Issue 4 targets on this run", ""]
    titles = {"build": "build time within 1.5x of Embree-medium's (split factor 0)",
              "cpu": "CPU traversal at least 0.5x Embree's single-ray rate",
              "gpu": "GLSL traversal (the faster of binary and 8-wide) at least 1.0x the device's ray query (issue 19)"}
    for key, title in titles.items():
        items = summary[key]
        if not items:
            continue
        met = sum(1 for _, ok, _ in items if ok)
        verdict = "met" if met == len(items) else f"missed on {len(items) - met} of {len(items)}"
        lines.append(f"- **{title}: {verdict}.** " + "; ".join(
            text + (" (met)" if ok else " (**missed**)") for _, ok, text in items) + ".")
    lines += ["", "Reading the targets: build times are wall-clock medians on a 2-core machine that other processes "
              "share (see the load average above, and the re-run row for the build rows); both builders use both "
              "cores, and the ratios move by +-0.3 between runs. Throughputs are thread CPU time, steadier. SAH: the "
              "spatial-split builder (per node the full object sweep against a binned spatial split, 16 bins, searched "
              "where the object split's children overlap by more than 1e-5 of the root area, at most 2 references per "
              "triangle: the room Embree-high gets) is below Embree-high's SAH on every scene when Embree chops "
              "through our padded `splitTriangle`. Given the same exact clipping, Embree-high's SAH moves by 0.1% or "
              "less except on the rotated atrium (28.09 -> 26.58), where ours stays 3.1% above (27.41): exact "
              "clipping in our bins does not close it (tried: 27.54), a larger budget does (3x, 32 bins: 26.20), so "
              "Embree spends the same room better there. On the axis-aligned atrium spatial splits raise the SAH "
              "over the plain sweep (30.15 vs 28.55: the split choice is greedy, and chopped references cost again "
              "in every later level), still below Embree-high's 31.23. The CPU traversal walks a 4-wide SSE copy of "
              "the binary BLAS (`engine/bvh/wide.hpp`), single ray; Embree dispatches at run time to wider nodes and "
              "the widest SIMD kernels the CPU has.", ""]
    return lines


def issue19_lines(rows, builder):
    """Issue 19's tree-quality target: SAH at or below Embree-high's on every scene, with the spatial builder's build
    time against Embree-medium's and Embree-high's (wall-clock medians of the same run)."""
    if not rows:
        return []
    lines = ["### Issue 19 targets on this run", "",
             "| scene | ours spatial SAH | Embree high SAH (splitTriangle / exact clipping) | spatial / high SAH | "
             "at or below? | best of ours | spatial build | / Embree medium | / Embree high |", "|" + "---|" * 9]
    met = 0
    for scene, spatial, best, medium, high, exact in rows:
        # The stricter of Embree-high's two SAHs (its split callback with our padded splitTriangle or exact clipping).
        sahs = [high.counters["sah"]] + ([exact.counters["sah"]] if exact and exact.counters.get("sah") else [])
        high_sah = min(sahs)
        sah = spatial.counters.get("sah") if spatial else None
        ok = sah is not None and sah <= high_sah
        met += 1 if ok else 0
        cells = [scene, "-" if sah is None else f"{sah:.2f}", " / ".join(f"{v:.2f}" for v in sahs),
                 "-" if sah is None else f"{sah / high_sah:.3f}x", "yes" if ok else "**no**",
                 f"{best.counters['sah']:.2f} ({builder(best)})",
                 fmt_ms(spatial.ms) if spatial else "-",
                 f"{spatial.ms / medium.ms:.2f}x" if spatial and medium and medium.ms > 0 else "-",
                 f"{spatial.ms / high.ms:.2f}x" if spatial and high.ms > 0 else "-"]
        lines.append("| " + " | ".join(md_escape(c) for c in cells) + " |")
    verdict = "met" if met == len(rows) else f"missed on {len(rows) - met} of {len(rows)}"
    lines += ["", f"SAH of the spatial-split builder at or below Embree-high's (the lower of its two) on every scene: "
              f"**{verdict}**. Build ratios: ours spatial / Embree's wall-clock median of the same run (Embree high "
              "with the splitTriangle callback, its faster variant).", ""]
    return lines


# ---- Scenes section (bench/scene_bench.cpp) ------------------------------------------------------------------------

PASS_ORDER = ["scene_update", "pose_upload", "skinning", "shadow_table", "point_shadows", "light_shadow_maps", "gbuffer",
              "deferred_lighting", "sky", "transparency", "tonemap"]


def scene_section(results, exe):
    """One row per scene: synchronous load and first frame, asynchronous time to first frame, warm 1280x720 frame
    with its GPU time per pass."""
    rows = {r.name: r for r in results if r.info.get("group") == "scenes"}
    scenes = []
    for name in rows:
        scene = name.split("/")[1]
        if scene not in scenes:
            scenes.append(scene)
    columns = ["scene", "sync load (glTF + upload + textures)", "first frame, sync", "first frame, async",
               "ratio async / sync", "warm frame (wall)", "GPU total", "GPU per pass", "reproduce"]
    lines = ["## Scenes", "",
             "`bench/scene_bench.cpp` on the shared glTF assets, 1280x720, deferred PBR, default HDR environment. "
             "**sync load** = `loadGltf` + GPU scene upload (`Renderer::setScene`) + every texture decoded, "
             "mipmapped and uploaded (`SceneTextureStream::finishSynchronously`), the three parts in brackets. "
             "**first frame** = that load (sync) or the load with textures only started (async: "
             "`render/texture_streamer.hpp` decodes on worker threads, placeholders until each arrives) plus the "
             "first `renderOffscreen` of a fresh renderer, which also loads and prefilters the HDR environment; "
             "pipelines are already built (process-wide cache). **warm frame** = one `renderOffscreen` of a warm "
             "renderer: graph build and compile, record, submit, wait, 1280x720 readback; animated scenes (Fox, "
             "BrainStem) advance animation 0 by 1/60 s per frame, so it includes `evaluateAnimations`, the pose upload "
             "and the skinning pass. GPU per pass: timestamp queries (`FrameResult::passTimes`), mean per frame. "
             "Medians of 5 repetitions (warm frame: 4 frames each), except MetalRoughSpheresNoTextures (~1 M "
             "triangles): 3 repetitions of 2 frames. On lavapipe the \"GPU\" is the same 2 CPU cores.", "",
             "| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
    for scene in scenes:
        sync, asyn, frame = (rows.get(f"BM_Scene{kind}/{scene}") for kind in ("FirstFrameSync", "FirstFrameAsync",
                                                                              "Frame"))
        any_row = sync or asyn or frame
        load = "-"
        if sync:
            c = sync.counters
            parts = [c.get("gltf_ms"), c.get("upload_ms"), c.get("textures_ms")]
            if all(p is not None for p in parts):
                load = f"{fmt_ms(sum(parts))} ({' + '.join(fmt_ms(p) for p in parts)})"
        ratio = f"{asyn.ms / sync.ms:.2f}" if sync and asyn and sync.ms > 0 else "-"
        passes = "-"
        if frame:
            timed = {k[len("pass_ms."):]: v for k, v in frame.counters.items() if k.startswith("pass_ms.")}
            order = [p for p in PASS_ORDER if p in timed] + sorted(p for p in timed if p not in PASS_ORDER)
            passes = ", ".join(f"{p} {fmt_ms(timed[p])}" for p in order)
        names = [r.name for r in (asyn, sync, frame) if r]
        cells = [md_escape(any_row.info.get("input", scene)), load, fmt_ms(sync.ms) if sync else "-",
                 fmt_ms(asyn.ms) if asyn else "-", ratio, fmt_ms(frame.ms) if frame else "-",
                 fmt_ms(frame.counters.get("gpu_ms")) if frame else "-", passes, command(exe, names)]
        lines.append("| " + " | ".join(cells) + " |")
    return lines + [""]


# ---- Path tracer section (scripts/bench_pathtrace.sh -> bench/pathtrace_report.py) ------------------------------

def pathtrace_section(results_dir):
    """The Markdown that bench/pathtrace_report.py wrote next to the results (its own section), if any."""
    path = os.path.join(results_dir, "pathtrace_section.md")
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return f.read().rstrip().splitlines() + [""]


# ---- Path tracer vs Cycles (bench/cycles/bench_cycles.py -> bench/results/cycles.json) ----------------------------

def cycles_section(results_dir):
    """Our path tracer against Blender Cycles (issue 16), with its plot, if bench_cycles.py has written cycles.json."""
    path = os.path.join(results_dir, "cycles.json")
    if not os.path.exists(path):
        return []
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "bench", "cycles"))
    sys.dont_write_bytecode = True  # no __pycache__ left in the source tree
    import cycles_report  # bench/cycles/cycles_report.py
    with open(path) as f:
        return cycles_report.section(json.load(f), results_dir)


# ---- Soak section (scripts/soak.sh -> bench/results/soak.json) ---------------------------------------------------

def soak_section(results_dir):
    """Memory over the soak runs, if scripts/soak.sh has written bench/results/soak.json."""
    path = os.path.join(results_dir, "soak.json")
    if not os.path.exists(path):
        return []
    import soak_summary  # scripts/soak_summary.py, next to this file
    with open(path) as f:
        return soak_summary.section(json.load(f))


def farm_section(results_dir):
    """The render-farm section scripts/bench_farm.sh wrote (bench/results/farm_section.md), if any."""
    path = os.path.join(results_dir, "farm_section.md")
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return f.read().rstrip().splitlines() + [""]


def vrs_section(results_dir):
    """The VRS section bench/vrs_report.py wrote (bench/results/vrs_section.md), if any."""
    path = os.path.join(results_dir, "vrs_section.md")
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return f.read().rstrip().splitlines() + [""]


def main(argv):
    args = [a for a in argv[1:] if not a.startswith("--")]
    if len(args) != 2:
        print(__doc__.strip().splitlines()[3], file=sys.stderr)
        return 2
    results_path, out_path = args
    data = load(results_path)
    if "--compact" in argv:
        compact(results_path, data)
        data = load(results_path)
    results, errors = collect(data)
    exe = data["context"].get("executable", "build/bin/idk_bench")
    plots_note = plot(results, os.path.dirname(os.path.abspath(results_path)))
    groups = build_rows(results, exe)
    lines = header(data, results, errors, plots_note)
    for group in GROUP_ORDER + sorted(g for g in groups if g not in GROUP_ORDER):
        if group == "bvh" and any(r.info.get("group") == "bvh" for r in results):
            lines += bvh_section(results, exe)
        elif group == "scenes" and any(r.info.get("group") == "scenes" for r in results):
            lines += scene_section(results, exe)
        elif group in groups:
            lines += [f"## {group[0].upper() + group[1:]}", ""] + table(groups[group]) + [""]
    lines += pathtrace_section(os.path.dirname(os.path.abspath(results_path)))
    lines += cycles_section(os.path.dirname(os.path.abspath(results_path)))
    lines += soak_section(os.path.dirname(os.path.abspath(results_path)))
    lines += farm_section(os.path.dirname(os.path.abspath(results_path)))
    lines += vrs_section(os.path.dirname(os.path.abspath(results_path)))
    with open(out_path, "w") as f:
        f.write("\n".join(lines).rstrip() + "\n")
    print(f"bench_report.py: wrote {out_path} ({sum(len(r) for r in groups.values())} rows)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
