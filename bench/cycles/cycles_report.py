#!/usr/bin/env python3
"""cycles_report.py: the "Path tracer vs Cycles" section of BENCHMARKS.md from bench/results/cycles.json (written by
bench/cycles/bench_cycles.py): a log-log plot of RMSE against render time per scene for both renderers
(bench/results/cycles.png), the mean-radiance ratio ours/Cycles, the error of each at equal time, and where the two
converged images disagree. scripts/bench_report.py calls section(); run alone it prints the section:
  bench/cycles/cycles_report.py RESULTS_DIR
"""
import json
import math
import os
import sys


def _fmt(v, digits=3):
    return "-" if v is None else f"{v:.{digits}g}"


def _secs(ms):
    return "-" if ms is None else f"{ms / 1000:.2f} s"


def loglog_at(points, t):
    """Error at time t on the log-log polyline through (time, error) points, extrapolated from the nearest segment
    outside their range. Returns (error, extrapolated) or (None, False)."""
    pts = sorted((p, e) for p, e in points if p and e and p > 0 and e > 0)
    if len(pts) < 2:
        return None, False
    lt = math.log(t)
    for i in range(len(pts) - 1):
        (t0, e0), (t1, e1) = pts[i], pts[i + 1]
        if t0 <= t <= t1 or (i == 0 and t < t0) or (i == len(pts) - 2 and t > t1):
            if t1 == t0:
                return e0, False
            w = (lt - math.log(t0)) / (math.log(t1) - math.log(t0))
            return math.exp(math.log(e0) + w * (math.log(e1) - math.log(e0))), not (pts[0][0] <= t <= pts[-1][0])
    return None, False


def _curve(entry, renderer):
    rows = sorted((r for r in entry["runs"] if r["renderer"] == renderer), key=lambda r: r["spp"])
    return rows, [(r["renderMilliseconds"] / 1000.0, r["rmse"]) for r in rows]


def plot(data, results_dir):
    """Writes cycles.png; returns its file name, or None without matplotlib."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return None
    scenes = data["scenes"]
    fig, axes = plt.subplots(1, len(scenes), figsize=(4.6 * len(scenes), 4.0), squeeze=False)
    for ax, entry in zip(axes[0], scenes):
        for renderer, label, colour in (("ours", "ours (GPU path tracer on lavapipe)", "tab:blue"),
                                        ("cycles", "Blender Cycles (CPU)", "tab:orange")):
            rows, pts = _curve(entry, renderer)
            ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", color=colour, label=label)
            for r, (t, e) in zip(rows, pts):
                ax.annotate(str(r["spp"]), (t, e), textcoords="offset points", xytext=(3, 3), fontsize=7,
                            color=colour)
        floor = entry["converged"]["rmse"]
        ax.axhline(floor, color="grey", ls="--", lw=1,
                   label=f"ours at {data['refSpp']} spp vs reference ({floor:.3g})")
        ax.set_title(entry["scene"])
        ax.set_xlabel("render time (s)")
        ax.set_ylabel(f"RMSE vs Cycles {data['refSpp']} spp")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle(f"Path tracer vs Cycles: error against time ({data['size']}, max depth {data['maxDepth']}, "
                 f"{data['threads']} CPU threads each)", fontsize=10)
    fig.tight_layout()
    name = "cycles.png"
    fig.savefig(os.path.join(results_dir, name), dpi=90)
    plt.close(fig)
    return name


def section(data, results_dir):
    png = plot(data, results_dir)
    ref = data["refSpp"]
    lines = ["## Path tracer vs Cycles", "",
             f"Issue 16's independent peer: {data.get('blender') or 'Blender'} Cycles on the CPU renders the same glTF "
             "file (its own importer's version of it), from the camera our renderer used (its `--json` camera), "
             f"at {data['size']}, with the same longest path (our `--max-depth {data['maxDepth']}` = Cycles "
             f"`max_bounces` {data['maxDepth'] - 2}) and the same uniform environment (`--environment none`, "
             "radiance 0.5; black for the Cornell box, lit by its own point light and emissive quad). Cycles runs "
             "without denoising, adaptive sampling, clamping or glossy filter, with a 1-pixel box filter and the "
             "Standard view transform; both write linear radiance to EXR. Reference: Cycles at "
             f"{ref} spp (seed 1000); errors are `idk compare` RMSE against it; times are the render calls (ours: "
             "`wallMilliseconds`, path tracing only; Cycles: `bpy.ops.render.render`, which includes its scene "
             f"sync and BVH build). Both use {data['threads']} threads of this {data.get('cpus')}-core machine "
             "(ours through Mesa lavapipe). Produced by `bench/cycles/bench_cycles.py` "
             f"({data['date']}, {data['elapsedSeconds'] / 60:.1f} min); "
             "`IDK_BENCH_CYCLES=0 make bench` keeps these results.", ""]
    if png:
        lines += [f"![Path tracer vs Cycles: RMSE against time](bench/results/{png})", ""]
    lines += ["| scene | mean radiance ours/Cycles (luminance; R, G, B) | converged disagreement (RMSE, ours "
              f"{ref} spp vs reference) | ours at its {max(r['spp'] for r in data['scenes'][0]['runs'] if r['renderer'] == 'ours')} spp: time, RMSE "
              "| Cycles RMSE at that time | error ratio ours/Cycles at equal time |",
              "|---|---|---|---|---|---|"]
    for e in data["scenes"]:
        rows, _ = _curve(e, "ours")
        last = rows[-1]
        t = last["renderMilliseconds"] / 1000.0
        cyc, extrapolated = loglog_at(_curve(e, "cycles")[1], t)
        rgb = ", ".join(_fmt(v, 3) for v in e["meanRatioRgb"])
        lines.append(f"| {e['scene']} | {e['meanRatio']:.3f} ({rgb}) | {_fmt(e['converged']['rmse'])} "
                     f"(relMSE {_fmt(e['converged']['relMse'])}) | {t:.2f} s, {_fmt(last['rmse'])} | "
                     f"{_fmt(cyc)}{' (extrapolated)' if extrapolated else ''} | "
                     f"{_fmt(last['rmse'] / cyc if cyc else None)} |")
    lines += ["", "Every run (RMSE and relative MSE against the Cycles reference; samples per second = "
              "spp x pixels / render time):", "",
              "| scene | renderer | spp | render time | RMSE | relMSE | samples/s | mean luminance |",
              "|---|---|---|---|---|---|---|---|"]
    w, h = (int(v) for v in data["size"].split("x"))
    lum = lambda m: 0.2126 * m[0] + 0.7152 * m[1] + 0.0722 * m[2]
    for e in data["scenes"]:
        for r in sorted(e["runs"], key=lambda r: (r["renderer"] != "ours", r["spp"])) + [e["converged"]]:
            sps = r["spp"] * w * h / (r["renderMilliseconds"] / 1000.0) if r["renderMilliseconds"] else None
            lines.append(f"| {e['scene']} | {r['renderer']} | {r['spp']} | {_secs(r['renderMilliseconds'])} | "
                         f"{_fmt(r['rmse'])} | {_fmt(r['relMse'])} | {_fmt(sps)} | {_fmt(lum(r['mean']))} |")
        refrow = e["reference"]
        lines.append(f"| {e['scene']} | cycles (reference) | {refrow['spp']} | "
                     f"{_secs(refrow['renderMilliseconds'])} | - | - | "
                     f"{_fmt(refrow['spp'] * w * h / (refrow['renderMilliseconds'] / 1000.0))} | "
                     f"{_fmt(lum(refrow['mean']))} |")
    lines.append("")
    for e in data["scenes"]:
        spec, lam = e.get("specLighting"), e.get("lambertMaterials")
        if spec and lam:
            ref_lum, ours_lum = lum(e["reference"]["mean"]), lum(e["converged"]["mean"])
            lines += [f"Light units ({e['scene']}, a point light and an emissive quad): the benchmark imports with "
                      "the importer's `COMPAT` mode (W = cd x 4pi, so Cycles' point intensity W / 4pi is the glTF "
                      "value, as our renderer reads it). Blender's default `SPEC` mode (W = cd x 4pi / 683 lm/W) "
                      f"gives a mean luminance of {_fmt(lum(spec['mean']))} at {spec['spp']} spp against "
                      f"{_fmt(ref_lum)}: the point light's share drops 683-fold. With every material shaded by a "
                      f"Lambertian Diffuse BSDF of the same base colour (`render_cycles.py --lambert`, {lam['spp']} "
                      f"spp) Cycles' mean is {_fmt(lum(lam['mean']))}, ours/Cycles "
                      f"{ours_lum / lum(lam['mean']):.3f}: the units agree, and the ratio of "
                      f"{e['meanRatio']:.3f} against the Principled import comes from its material model (below). "
                      "Emission strength (`KHR_materials_emissive_strength`) imports unconverted in both modes.", ""]
    lines += WHY + [""]
    return lines


# Where the two renderers differ by construction (the measured ratios and floors above show how much).
WHY = [
    "Where and why the renderers differ:",
    "- **Importer gaps.** Blender 3.4's glTF importer maps the core metallic-roughness material, emission with "
    "`KHR_materials_emissive_strength`, transmission, IOR, clearcoat, specular, sheen, unlit, texture transforms "
    "and variants, but not `KHR_materials_anisotropy`, `_iridescence`, `_dispersion` or `_diffuse_transmission`; "
    "it ignores the punctual lights' `range` window (we apply glTF's recommended falloff) and maps spot cones to "
    "Blender's smoothstep blend rather than glTF's angular falloff. Occlusion maps shade neither image.",
    "- **Material model.** Cycles shades the import with its Principled BSDF (3.x): Disney (Burley) diffuse with "
    "a roughness-dependent retro-reflection where glTF has a Lambert base, and single-scattering GGX (the "
    "importer keeps the node's default `GGX`, not `Multiscatter GGX`), so rough metals lose energy in Cycles; "
    "our energy compensation (issue 16) makes them brighter than Cycles by design. Emissive surfaces emit from "
    "both sides in Cycles and from the front in ours.",
    "- **Light units.** glTF gives point and spot lights in candela and we use the value as radiant intensity; "
    "Blender's default import divides by 683 lm/W (measured above), so the benchmark imports with the unitless "
    "mode. Point lights get radius 0 (Blender's default is 0.25 m).",
    "- **Sky and tonemapping.** Both render under the same uniform environment (none of our HDR file or baked "
    "atmosphere) and are compared as linear radiance before any tonemapping (Cycles' Filmic is off; our AgX only "
    "applies to PNG output).",
    "- **Time.** Cycles is a CPU renderer on these cores; ours is a GPU renderer running on the same cores "
    "through a software Vulkan driver, so equal-time errors say nothing about a real GPU.",
]


def main(argv):
    if len(argv) != 2:
        print(__doc__.strip().splitlines()[-1].strip(), file=sys.stderr)
        return 2
    with open(os.path.join(argv[1], "cycles.json")) as f:
        print("\n".join(section(json.load(f), argv[1])))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
