#!/usr/bin/env python3
"""vrs_report.py: turns idk_vrs_bench's JSON (bench/results/vrs.json) into the plot bench/results/vrs.png (per
scene: shading invocations saved and lighting + sky time saved, each against PSNR and against FLIP of the displayed
frame relative to VRS off; one point per factor pair)
and the Markdown section bench/results/vrs_section.md that scripts/bench_report.py puts into BENCHMARKS.md
(issue 14's benchmarks).

usage: bench/vrs_report.py RESULTS_DIR
"""
import json
import os
import sys


def section(data, plotted):
    off = {name: next(r for r in rows if not r["vrs"]) for name, rows in data["scenes"].items()}
    lines = ["## Variable-rate shading (issue 14)", "",
             f"Software rung (the only rung the frame runs; lavapipe has no hardware VRS), {data['size']}, "
             f"{data['frames']} frames of a generated camera path (an orbit accelerating to 1.2 rad/s at 60 Hz), "
             f"device: {data['device']}. Each row is one renderer following the whole path; medians over the frames "
             "after the first (which has no rates yet). Invocations: pixels shaded by deferred lighting + sky; saved "
             "and lighting time are relative to VRS off in the same run. Error: the displayed 8-bit frame against "
             "VRS off of the same frame (PSNR over sRGB values; LDR-FLIP mean). On lavapipe the classifier and the "
             "reconstruction cost more than the lighting they save; their times are listed apart, not hidden in the "
             "lighting column (classify: the motion-vector pass, which VRS runs alone with --aa none, the velocity "
             "field, the classifier and the rates' readback; on a GPU these are small per-pixel dispatches, not "
             "measured here). Lavapipe timings on "
             "a busy 2-core machine vary by tens of percent between runs; the invocation counts and errors are exact.",
             f"Reproduce: `{data['command']}` then `python3 bench/vrs_report.py bench/results`.", ""]
    if plotted:
        lines += ["![invocations and lighting time saved vs PSNR and FLIP](bench/results/vrs.png)", ""]
    lines += ["| scene | SpeedFactor | LumVarianceFactor | invocations | saved | lighting+sky ms (off) | saved | "
              "reconstruct ms | classify ms | PSNR dB (min) | FLIP |",
              "|---|---|---|---|---|---|---|---|---|---|---|"]
    best = {}
    for name, rows in data["scenes"].items():
        o = off[name]
        for r in rows:
            if not r["vrs"]:
                continue
            saved = 1.0 - r["invocationsMean"] / o["invocationsMean"]
            tsaved = 1.0 - r["lightingMsMedian"] / o["lightingMsMedian"] if o["lightingMsMedian"] else 0.0
            lines.append(f"| {name} | {r['speedFactor']:g} | {r['lumVarianceFactor']:g} | {r['invocationsMean']:.0f} "
                         f"| {saved:.0%} | {r['lightingMsMedian']:.2f} ({o['lightingMsMedian']:.2f}) | {tsaved:.0%} "
                         f"| {r['reconstructMsMedian']:.2f} | {r['classifyMsMedian']:.2f} "
                         f"| {r['psnrMedian']:.1f} ({r['psnrMin']:.1f}) | {r['flipMedian']:.4f} |")
            if r["psnrMedian"] >= 40.0 and saved > best.get(name, (-1.0, None))[0]:
                best[name] = (saved, r)
    lines.append("")
    aim = []
    for name in data["scenes"]:
        if name in best:
            s, r = best[name]
            aim.append(f"{name}: {s:.0%} saved at {r['psnrMedian']:.1f} dB (factors {r['speedFactor']:g} / "
                       f"{r['lumVarianceFactor']:g})")
        else:
            aim.append(f"{name}: no setting reaches 40 dB")
    lines += ["Aim (50% of invocations saved at 40 dB or better), best setting at >= 40 dB: " + "; ".join(aim) + ".",
              ""]
    return lines


def plot(data, path):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return False
    names = list(data["scenes"])
    # Columns: per scene, invocations saved then lighting + sky time saved; rows: PSNR (higher is better), FLIP
    # (lower is better).
    fig, axes = plt.subplots(2, 2 * len(names), figsize=(5 * 2 * len(names), 8), squeeze=False)
    for s, name in enumerate(names):
        rows = data["scenes"][name]
        off = next(r for r in rows if not r["vrs"])
        saved = {
            "shading invocations saved (%)": lambda r: 100.0 * (1.0 - r["invocationsMean"] / off["invocationsMean"]),
            "lighting + sky time saved (%)": lambda r: (100.0 * (1.0 - r["lightingMsMedian"] / off["lightingMsMedian"])
                                                        if off["lightingMsMedian"] else 0.0),
        }
        for c, (xlabel, xof) in enumerate(saved.items()):
            for row, (ylabel, key, aim) in enumerate((("PSNR vs VRS off (dB)", "psnrMedian", 40.0),
                                                      ("FLIP vs VRS off (mean)", "flipMedian", None))):
                ax = axes[row][2 * s + c]
                for sf, color in ((0.0, "tab:blue"), (0.2, "tab:orange"), (0.8, "tab:green")):
                    pts = [r for r in rows if r["vrs"] and abs(r["speedFactor"] - sf) < 1e-6]
                    xs = [xof(r) for r in pts]
                    ys = [r[key] for r in pts]
                    # Invocation counts are exact and move with the factors; timings are noisy on lavapipe: points.
                    ax.plot(xs, ys, "o-" if c == 0 else "o", color=color, label=f"SpeedFactor {sf:g}")
                    for x, y, r in zip(xs, ys, pts):
                        ax.annotate(f"{r['lumVarianceFactor']:g}", (x, y), fontsize=7, xytext=(3, 3),
                                    textcoords="offset points")
                if aim is not None:
                    ax.axhline(aim, color="grey", linestyle=":")
                ax.axvline(50.0 if c == 0 else 0.0, color="grey", linestyle=":")
                ax.set_title(f"{name}, {data['size']} (labels: LumVarianceFactor)", fontsize=9)
                ax.set_xlabel(xlabel)
                ax.set_ylabel(ylabel)
                ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    return True


def main(argv):
    if len(argv) != 2:
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 2
    results = argv[1]
    with open(os.path.join(results, "vrs.json")) as f:
        data = json.load(f)
    plotted = plot(data, os.path.join(results, "vrs.png"))
    with open(os.path.join(results, "vrs_section.md"), "w") as f:
        f.write("\n".join(section(data, plotted)) + "\n")
    print(f"vrs_report.py: wrote {results}/vrs_section.md" + (" and vrs.png" if plotted else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
