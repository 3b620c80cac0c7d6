"""render_cycles.py: renders a glTF scene with Blender Cycles (CPU) the way `idk render --pathtrace` sees it, as the
independent peer of the path-tracer benchmarks (issue 16; bench/cycles/bench_cycles.py drives it). Linear radiance
goes to an OpenEXR file (32-bit float, no view transform), timings to a JSON file.

usage: blender -b --factory-startup --python bench/cycles/render_cycles.py -- --gltf SCENE.gltf|.glb --out F.exr
         --camera CAMERA.json --size WxH --spp N [--seed S] [--max-depth D] [--env L] [--lighting-mode M]
         [--threads T] [--json TIMES.json]
  --camera    a JSON file holding `idk render --json`'s "camera" object (position, forward, up, yfovDegrees; glTF
              axes, +Y up): the exact view our renderer used, so that both frame the scene alike
  --max-depth our --max-depth (path segments: 1 = what the camera sees, 2 = direct light); Cycles counts bounces
              after the first hit, so its max_bounces is D - 2
  --env       radiance of a uniform environment (our `--environment none` is a constant 0.5; 0 = black world)
  --lighting-mode  the glTF importer's light conversion: COMPAT (default: W = cd * 4 pi, so Cycles' point/spot
              intensity P / 4pi equals the glTF candela value, our convention) or SPEC (Blender's default,
              "physical": W = cd * 4 pi / 683, i.e. 683 times darker than ours for punctual lights)

Settings that make Cycles an estimator of the same integral as ours: no denoising, no adaptive sampling, no sample
clamping, no glossy filter, a 1-pixel box pixel filter (ours jitters uniformly in the pixel), point lights of zero
radius (Blender gives new lights a 0.25 m radius; glTF punctual lights are points), the Standard view transform.
No counterpart in IDKEngine.
"""
import argparse
import json
import math
import os
import sys
import time

import bpy
import numpy
from mathutils import Matrix, Vector

# Debian's Blender 3.4.1 runs on the system NumPy (1.24), which removed the np.bool/np.int/... aliases that the
# bundled glTF importer (3.4) still uses (AttributeError in set_poly_smoothing): restore them for the importer.
for _alias, _builtin in (("bool", bool), ("int", int), ("float", float), ("object", object), ("str", str)):
    if _alias not in numpy.__dict__:
        setattr(numpy, _alias, _builtin)


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    ap = argparse.ArgumentParser(prog="render_cycles.py")
    ap.add_argument("--gltf", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--camera", required=True)
    ap.add_argument("--size", default="256x256")
    ap.add_argument("--spp", type=int, required=True)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--max-depth", type=int, default=6)
    ap.add_argument("--env", type=float, default=0.5)
    ap.add_argument("--lighting-mode", choices=["COMPAT", "SPEC"], default="COMPAT")
    ap.add_argument("--threads", type=int, default=0, help="0: Blender's automatic choice")
    ap.add_argument("--lambert", action="store_true",
                    help="diagnostic: shade every imported material with a Lambertian Diffuse BSDF of its base "
                         "colour instead of the Principled BSDF (separates light units from the material model)")
    ap.add_argument("--json")
    a = ap.parse_args(argv)
    try:
        w, h = (int(v) for v in a.size.lower().split("x"))
    except ValueError:
        ap.error(f"--size '{a.size}': give WxH")
    if w < 1 or h < 1 or a.spp < 1 or a.max_depth < 2:
        ap.error("--size, --spp must be positive and --max-depth at least 2 (direct light)")
    a.width, a.height = w, h
    return a


def gltf_to_blender(v):
    """glTF (+Y up, -Z forward) to Blender (+Z up) axes, as the importer converts the scene: (x, y, z) -> (x, -z, y)."""
    return Vector((v[0], -v[2], v[1]))


def place_camera(scene, spec, width, height):
    fwd = gltf_to_blender(spec["forward"]).normalized()
    up = gltf_to_blender(spec["up"])
    up = (up - up.dot(fwd) * fwd).normalized()
    right = fwd.cross(up).normalized()
    # A Blender camera looks down its local -Z with +Y up: the columns of its rotation are right, up, -forward.
    rot = Matrix((right, up, -fwd)).transposed()
    cam_data = bpy.data.cameras.new("idk_camera")
    cam_data.sensor_fit = "VERTICAL"
    cam_data.angle_y = math.radians(spec["yfovDegrees"])
    cam_data.clip_start = min(float(spec.get("znear", 1e-3)), 1e-3)
    cam_data.clip_end = max(float(spec.get("zfar", 1e4)), 1e4)
    cam = bpy.data.objects.new("idk_camera", cam_data)
    cam.matrix_world = Matrix.Translation(gltf_to_blender(spec["position"])) @ rot.to_4x4()
    scene.collection.objects.link(cam)
    scene.camera = cam
    scene.render.resolution_x = width
    scene.render.resolution_y = height
    scene.render.resolution_percentage = 100
    scene.render.pixel_aspect_x = scene.render.pixel_aspect_y = 1.0


def set_world(scene, radiance):
    world = bpy.data.worlds.new("idk_uniform")
    world.use_nodes = True
    bg = world.node_tree.nodes["Background"]
    bg.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    bg.inputs["Strength"].default_value = radiance
    scene.world = world


def lambert_materials():
    """Replaces each Principled BSDF by a Diffuse BSDF (roughness 0: Lambert) fed the same base colour, keeping
    emission (a separate Emission shader added on top)."""
    for mat in bpy.data.materials:
        if not mat.use_nodes:
            continue
        nodes, links = mat.node_tree.nodes, mat.node_tree.links
        for p in [n for n in nodes if n.type == "BSDF_PRINCIPLED"]:
            diffuse = nodes.new("ShaderNodeBsdfDiffuse")
            diffuse.inputs["Roughness"].default_value = 0.0
            base = p.inputs["Base Color"]
            if base.is_linked:
                links.new(base.links[0].from_socket, diffuse.inputs["Color"])
            else:
                diffuse.inputs["Color"].default_value = base.default_value
            emission = nodes.new("ShaderNodeEmission")
            for name, target in (("Emission", "Color"), ("Emission Strength", "Strength")):
                src = p.inputs[name]
                if src.is_linked:
                    links.new(src.links[0].from_socket, emission.inputs[target])
                else:
                    emission.inputs[target].default_value = src.default_value
            add = nodes.new("ShaderNodeAddShader")
            links.new(diffuse.outputs[0], add.inputs[0])
            links.new(emission.outputs[0], add.inputs[1])
            for link in list(p.outputs[0].links):
                links.new(add.outputs[0], link.to_socket)


def set_cycles(scene, a):
    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    c.samples = a.spp
    c.use_adaptive_sampling = False
    c.seed = a.seed
    c.use_animated_seed = False
    c.use_denoising = False
    c.sample_clamp_direct = 0.0    # the defaults clamp indirect light at 10: biased, unlike ours
    c.sample_clamp_indirect = 0.0
    c.blur_glossy = 0.0
    c.light_sampling_threshold = 0.0
    c.caustics_reflective = True
    c.caustics_refractive = True
    bounces = a.max_depth - 2
    c.max_bounces = bounces
    c.diffuse_bounces = c.glossy_bounces = c.transmission_bounces = bounces
    c.volume_bounces = 0
    c.transparent_max_bounces = 8  # alpha-blended layers; Cycles counts them apart from bounces
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    scene.render.film_transparent = False
    if a.threads > 0:
        scene.render.threads_mode = "FIXED"
        scene.render.threads = a.threads
    vs = scene.view_settings
    vs.view_transform = "Standard"  # not Filmic (the EXR is written linear anyway; this keeps previews honest)
    vs.look = "None"
    vs.exposure = 0.0
    vs.gamma = 1.0
    img = scene.render.image_settings
    img.file_format = "OPEN_EXR"
    img.color_mode = "RGB"
    img.color_depth = "32"
    img.exr_codec = "ZIP"


def main():
    a = parse_args()
    with open(a.camera) as f:
        spec = json.load(f)
    spec = spec.get("camera", spec)
    for key in ("position", "forward", "up", "yfovDegrees"):
        if key not in spec:
            raise SystemExit(f"render_cycles.py: {a.camera}: the camera has no '{key}'")
    bpy.ops.wm.read_factory_settings(use_empty=True)
    t0 = time.perf_counter()
    result = bpy.ops.import_scene.gltf(filepath=a.gltf, convert_lighting_mode=a.lighting_mode)
    if "FINISHED" not in result:
        raise SystemExit(f"render_cycles.py: {a.gltf}: the glTF importer failed ({result})")
    import_s = time.perf_counter() - t0
    scene = bpy.context.scene
    lights = 0
    for light in bpy.data.lights:
        light.shadow_soft_size = 0.0  # glTF punctual lights are points (Blender's default radius is 0.25 m)
        if light.type == "SUN":
            light.angle = 0.0
        lights += 1
    if a.lambert:
        lambert_materials()
    place_camera(scene, spec, a.width, a.height)
    set_world(scene, a.env)
    set_cycles(scene, a)
    scene.render.filepath = a.out
    scene.render.use_file_extension = False
    t1 = time.perf_counter()
    bpy.ops.render.render(write_still=True)
    render_s = time.perf_counter() - t1
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"renderer": "cycles", "blender": bpy.app.version_string, "spp": a.spp, "seed": a.seed,
                       "maxBounces": a.max_depth - 2, "width": a.width, "height": a.height,
                       "lightingMode": a.lighting_mode, "lights": lights, "env": a.env,
                       "threads": scene.render.threads, "importSeconds": import_s,
                       "renderMilliseconds": render_s * 1000.0}, f, indent=1)


if __name__ == "__main__":
    try:
        main()
    except SystemExit as e:
        # Blender keeps running after a Python error unless told otherwise: exit non-zero so drivers see it.
        print(e, file=sys.stderr)
        sys.stderr.flush()
        os._exit(e.code if isinstance(e.code, int) else 1)
    except Exception:  # noqa: BLE001 - any failure must end the process with an error code
        import traceback
        traceback.print_exc()
        sys.stderr.flush()
        os._exit(1)
