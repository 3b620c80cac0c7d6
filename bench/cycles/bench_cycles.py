#!/usr/bin/env python3
"""bench_cycles.py: our GPU path tracer against an independent peer, Blender Cycles (issue 16's benchmark; BENCHMARKS.md
"Path tracer vs Cycles"). Per scene, on the same glTF file, camera, environment, size and path length:
  - a high-spp Cycles reference (seed 1000), rendered by bench/cycles/render_cycles.py in `blender -b`;
  - our path tracer (`idk render --pathtrace`, NEE+MIS, Sobol', seed 1) and Cycles (seed 1) at increasing spp,
    each timed and compared with the reference by `idk compare` (RMSE, relative MSE);
  - our path tracer at the reference's spp (seed 1000): its mean radiance over the Cycles reference's is the
    mean-radiance ratio, and its RMSE against the reference is where the two converged images disagree.
Writes RESULTS_DIR/cycles.json; scripts/bench_report.py turns it into the section and its plot (cycles_report.py).

usage: bench/cycles/bench_cycles.py BUILD_DIR RESULTS_DIR [--scenes A,B,..] [--size WxH] [--ref-spp N]
         [--ours-spp 1,2,..] [--cycles-spp 1,4,..] [--max-depth D] [--threads T] [--blender PATH] [--work DIR]
scripts/bench.sh runs it when `blender` is installed (scripts/setup.sh --bench); IDK_BENCH_CYCLES=0 skips it there.
Both renderers run on the CPU cores of this machine (ours on Mesa lavapipe), so their times compare directly.
"""
import argparse
import datetime
import json
import os
import re
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))

# name -> (glTF file, uniform environment radiance). The Cornell box is the embedded default scene's source file and
# is lit by its own lights only (black world); the others sit in our `--environment none` constant 0.5.
SCENES = {
    "cornell": ("scenes/cornell_box.gltf", 0.0),
    "DamagedHelmet": ("../shared/scenes/DamagedHelmet/glTF-Binary/DamagedHelmet.glb", 0.5),
    "MetalRoughSpheresNoTextures": (
        "../shared/scenes/MetalRoughSpheresNoTextures/glTF-Binary/MetalRoughSpheresNoTextures.glb", 0.5),
    "ToyCar": ("../shared/scenes/ToyCar/glTF/ToyCar.gltf", 0.5),
}


def spp_list(text):
    try:
        values = [int(v) for v in text.replace(",", " ").split()]
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}': give whole numbers, e.g. 1,4,16")
    if not values or min(values) < 1:
        raise argparse.ArgumentTypeError(f"'{text}': sample counts must be >= 1")
    return values


def run(cmd, log_path):
    """Runs cmd (stdout+stderr to log_path) and returns its wall seconds; raises naming the command and log."""
    t0 = time.perf_counter()
    with open(log_path, "w") as log:
        rc = subprocess.run(cmd, stdout=log, stderr=subprocess.STDOUT).returncode
    seconds = time.perf_counter() - t0
    if rc != 0:
        with open(log_path) as log:
            tail = log.read()[-1500:]
        raise RuntimeError(f"exit {rc}: {' '.join(cmd)}\n(log {log_path})\n{tail}")
    return seconds


def mean_rgb(path):
    """Per-channel mean of an image, from `oiiotool --printstats` (openimageio-tools, scripts/setup.sh)."""
    out = subprocess.run(["oiiotool", path, "--printstats"], capture_output=True, text=True)
    m = re.search(r"Stats Avg:\s*([-\d.eE+naif]+)\s+([-\d.eE+naif]+)\s+([-\d.eE+naif]+)", out.stdout)
    if out.returncode != 0 or not m:
        raise RuntimeError(f"oiiotool could not read the statistics of {path}: {out.stderr.strip()}")
    return [float(v) for v in m.groups()]


def compare(idk, image, reference, work, tag):
    out = subprocess.run([idk, "compare", image, reference, "--json"], capture_output=True, text=True)
    if out.returncode != 0:
        raise RuntimeError(f"idk compare {image} {reference} failed: {out.stderr.strip()}")
    with open(os.path.join(work, tag + ".compare.json"), "w") as f:
        f.write(out.stdout)
    j = json.loads(out.stdout)
    return {"rmse": j.get("rmse"), "relMse": j.get("relMse"), "nonFinite": j.get("nanCount")}


class Bench:
    def __init__(self, a):
        self.a = a
        self.idk = os.path.join(a.build, "bin", "idk")
        self.work = a.work or os.path.join(a.build, "bench_cycles")
        self.script = os.path.join(HERE, "render_cycles.py")

    def ours(self, scene, tag, spp, seed):
        file, env = SCENES[scene]
        out = os.path.join(self.work, tag + ".exr")
        cmd = [self.idk, "render", file, "--pathtrace", "--size", self.a.size, "--spp", str(spp),
               "--max-depth", str(self.a.max_depth), "--seed", str(seed), "--traversal", "bvh", "--no-validation",
               "--environment", "none", "--out", out, "--json"]
        if env == 0.0:
            cmd += ["--env-intensity", "0"]
        else:  # `--environment none` is a constant 0.5 times --env-intensity
            cmd += ["--env-intensity", repr(env / 0.5)]
        log = os.path.join(self.work, tag + ".log")
        t0 = time.perf_counter()
        with open(log, "w") as err:
            res = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=err, text=True)
        process_s = time.perf_counter() - t0
        if res.returncode != 0:
            with open(log) as f:
                raise RuntimeError(f"exit {res.returncode}: {' '.join(cmd)}\n{f.read()[-1500:]}")
        j = json.loads(res.stdout)
        with open(os.path.join(self.work, tag + ".json"), "w") as f:
            json.dump(j, f, indent=1)
        pt = j.get("pathtrace", {})
        return out, {"renderer": "ours", "spp": spp, "seed": seed, "command": " ".join(cmd),
                     "renderMilliseconds": pt.get("wallMilliseconds"), "processSeconds": process_s,
                     "device": j.get("device")}, j.get("camera")

    def cycles(self, scene, tag, spp, seed, camera_json, lighting_mode="COMPAT", lambert=False):
        file, env = SCENES[scene]
        out = os.path.join(self.work, tag + ".exr")
        times = os.path.join(self.work, tag + ".json")
        cmd = [self.a.blender, "-b", "--factory-startup", "--python", self.script, "--", "--gltf", file,
               "--out", out, "--camera", camera_json, "--size", self.a.size, "--spp", str(spp), "--seed", str(seed),
               "--max-depth", str(self.a.max_depth), "--env", repr(env), "--threads", str(self.a.threads),
               "--lighting-mode", lighting_mode, "--json", times] + (["--lambert"] if lambert else [])
        process_s = run(cmd, os.path.join(self.work, tag + ".log"))
        with open(times) as f:
            t = json.load(f)
        return out, {"renderer": "cycles", "spp": spp, "seed": seed, "command": " ".join(cmd),
                     "renderMilliseconds": t["renderMilliseconds"], "processSeconds": process_s,
                     "importSeconds": t["importSeconds"], "lightingMode": lighting_mode, "lambert": lambert,
                     "blender": t["blender"]}

    def scene(self, name):
        a = self.a
        print(f"bench_cycles.py: {name}", file=sys.stderr, flush=True)
        runs = []
        ours_images = []
        camera = None
        ours_seconds = cycles_seconds = 0.0
        for spp in a.ours_spp:
            tag = f"{name}_ours_{spp}"
            image, row, camera = self.ours(name, tag, spp, 1)
            ours_seconds += row["processSeconds"]
            ours_images.append((tag, image, row))
        camera_json = os.path.join(self.work, f"{name}_camera.json")
        with open(camera_json, "w") as f:
            json.dump(camera, f, indent=1)
        ref_image, ref_row = self.cycles(name, f"{name}_cycles_reference_{a.ref_spp}", a.ref_spp, 1000, camera_json)
        cycles_seconds += ref_row["processSeconds"]
        ref_row["mean"] = mean_rgb(ref_image)
        for tag, image, row in ours_images:
            row.update(compare(self.idk, image, ref_image, self.work, tag))
            row["mean"] = mean_rgb(image)
            runs.append(row)
        for spp in a.cycles_spp:
            tag = f"{name}_cycles_{spp}"
            image, row = self.cycles(name, tag, spp, 1, camera_json)
            cycles_seconds += row["processSeconds"]
            row.update(compare(self.idk, image, ref_image, self.work, tag))
            row["mean"] = mean_rgb(image)
            runs.append(row)
        # Our converged image: the mean-radiance ratio and the floor where the two models disagree.
        conv_image, conv_row, _ = self.ours(name, f"{name}_ours_converged_{a.ref_spp}", a.ref_spp, 1000)
        ours_seconds += conv_row["processSeconds"]
        conv_row.update(compare(self.idk, conv_image, ref_image, self.work, f"{name}_ours_converged_{a.ref_spp}"))
        conv_row["mean"] = mean_rgb(conv_image)
        ratio = [o / c if c > 0 else None for o, c in zip(conv_row["mean"], ref_row["mean"])]
        lum = lambda m: 0.2126 * m[0] + 0.7152 * m[1] + 0.0722 * m[2]
        entry = {"scene": name, "file": SCENES[name][0], "environment": SCENES[name][1], "camera": camera,
                 "reference": ref_row, "converged": conv_row, "runs": runs,
                 "meanRatioRgb": ratio, "meanRatio": lum(conv_row["mean"]) / lum(ref_row["mean"]),
                 "oursSeconds": ours_seconds, "cyclesSeconds": cycles_seconds}
        # Light units on the Cornell box (a point light and an emissive quad): Blender's default conversion
        # (glTF candela -> W through 683 lm/W) in one render, and in another every material shaded by a Lambertian
        # Diffuse BSDF, which takes the Principled BSDF's Burley diffuse and added specular out of the ratio.
        if name == "cornell" and a.units_check_spp > 0:
            n = a.units_check_spp
            for key, mode, lambert in (("specLighting", "SPEC", False), ("lambertMaterials", "COMPAT", True)):
                image, row = self.cycles(name, f"{name}_cycles_{key}_{n}", n, 1000, camera_json, mode, lambert)
                cycles_seconds += row["processSeconds"]
                row["mean"] = mean_rgb(image)
                entry[key] = row
            entry["cyclesSeconds"] = cycles_seconds
        print(f"bench_cycles.py: {name}: mean radiance ours/Cycles {entry['meanRatio']:.4f}, converged RMSE "
              f"{conv_row['rmse']:.4g}; ours {ours_seconds:.0f} s, Cycles {cycles_seconds:.0f} s",
              file=sys.stderr, flush=True)
        return entry


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.strip().splitlines()[0])
    ap.add_argument("build")
    ap.add_argument("results")
    ap.add_argument("--scenes", default="cornell,DamagedHelmet,MetalRoughSpheresNoTextures")
    ap.add_argument("--size", default="128x128")
    ap.add_argument("--ref-spp", type=int, default=1024)
    ap.add_argument("--ours-spp", type=spp_list, default=spp_list("1,4,16,64,256"))
    ap.add_argument("--cycles-spp", type=spp_list, default=spp_list("1,4,16,64,256"))
    ap.add_argument("--units-check-spp", type=int, default=64,
                    help="spp of the Cornell box's light-unit checks (SPEC import; Lambert materials); 0 skips them")
    ap.add_argument("--max-depth", type=int, default=6)
    ap.add_argument("--threads", type=int, default=os.cpu_count() or 2)
    ap.add_argument("--blender", default="blender")
    ap.add_argument("--work")
    a = ap.parse_args(argv[1:])
    scenes = [s for s in a.scenes.split(",") if s]
    unknown = [s for s in scenes if s not in SCENES]
    if unknown:
        ap.error(f"unknown scene(s) {', '.join(unknown)} (known: {', '.join(SCENES)})")
    if not shutil.which(a.blender):
        print(f"bench_cycles.py: '{a.blender}' not found; skipping the Cycles comparison "
              "(scripts/setup.sh --bench installs Blender)", file=sys.stderr)
        return 0
    os.chdir(ROOT)
    a.build = os.path.abspath(a.build) if not os.path.isabs(a.build) else a.build
    bench = Bench(a)
    if not os.access(bench.idk, os.X_OK):
        print(f"bench_cycles.py: {bench.idk} not found; build it first (ninja -C {a.build} idk)", file=sys.stderr)
        return 1
    if a.ref_spp < max(a.cycles_spp + a.ours_spp):
        ap.error("--ref-spp must be at least the largest measured spp")
    for scene in scenes:
        path = SCENES[scene][0]
        if not os.path.exists(path):
            print(f"bench_cycles.py: {path}: no such scene file (scene {scene})", file=sys.stderr)
            return 1
    shutil.rmtree(bench.work, ignore_errors=True)
    os.makedirs(bench.work)
    os.makedirs(a.results, exist_ok=True)
    blender_version = subprocess.run([a.blender, "-b", "--factory-startup", "--version"], capture_output=True,
                                     text=True).stdout.splitlines()
    start = time.perf_counter()
    entries = [bench.scene(s) for s in scenes]
    data = {"date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
            "blender": blender_version[0] if blender_version else None, "size": a.size, "refSpp": a.ref_spp,
            "maxDepth": a.max_depth, "threads": a.threads, "cpus": os.cpu_count(),
            "elapsedSeconds": time.perf_counter() - start, "scenes": entries}
    out = os.path.join(a.results, "cycles.json")
    with open(out, "w") as f:
        json.dump(data, f, indent=1)
    print(f"bench_cycles.py: wrote {out} ({data['elapsedSeconds']:.0f} s)", file=sys.stderr)
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv))
    except RuntimeError as e:
        print(f"bench_cycles.py: {e}", file=sys.stderr)
        sys.exit(1)
