#!/usr/bin/env python3
"""Builds the seed corpus of one fuzz harness (tests/fuzz) into a folder, at run time, from the shared scenes
(../shared/scenes, used in place: nothing of it is copied into the repository), the repository's own scenes and the
small hand-made seeds committed under tests/fuzz/seeds/NAME/.

  gltf     every .gltf with its external buffers and images inlined as data: URIs (the harness loads from an empty
           folder, so an external file would only ever be "missing"), and every small .glb rewritten as such a
           .gltf, if the result is at most MAX_SEED bytes
  glb      every .glb of at most MAX_SEED bytes
  image    PNG/JPEG files of the scenes of at most 128x128 texels, plus a 16x16 copy of one converted by oiiotool
           to every format the decoder sniffs (BMP, GIF, HDR, EXR, TIFF, WebP, DDS...; those OIIO cannot write are
           skipped) in several channel layouts (grey, grey+alpha, RGBA; 8 and 16 bits, half floats)
  capture  valid captures written in the documented format (0, 1 and 5 records, paused flag, odd rates)
  script   only the committed seeds
usage: fuzz_seeds.py NAME OUT_DIR
"""
import base64
import hashlib
import json
import math
import os
import shutil
import struct
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHARED = os.path.normpath(os.path.join(ROOT, "..", "shared", "scenes"))
MAX_SEED = 256 * 1024


def scene_files(*extensions):
    found = []
    for base in (SHARED, os.path.join(ROOT, "scenes")):
        for folder, _, files in os.walk(base):
            found += [os.path.join(folder, f) for f in files if f.lower().endswith(extensions)]
    return sorted(found)


def put(out, data, stem):
    digest = hashlib.sha1(data).hexdigest()[:12]
    if any(f.endswith(digest) for f in os.listdir(out)):
        return  # the same bytes under another name
    name = stem + "_" + digest
    with open(os.path.join(out, name), "wb") as f:
        f.write(data)


def inline_gltf(path):
    with open(path, "rb") as f:
        doc = json.load(f)
    folder = os.path.dirname(path)
    for key, mime in (("buffers", "application/octet-stream"), ("images", "image/png")):
        for item in doc.get(key, []):
            uri = item.get("uri")
            if not isinstance(uri, str) or uri.startswith("data:"):
                continue
            target = os.path.join(folder, uri)
            if not os.path.isfile(target) or os.path.getsize(target) > MAX_SEED:
                return None
            with open(target, "rb") as f:
                payload = base64.b64encode(f.read()).decode()
            if key == "images" and uri.lower().endswith((".jpg", ".jpeg")):
                mime = "image/jpeg"
            item["uri"] = "data:%s;base64,%s" % (mime, payload)
    data = json.dumps(doc, separators=(",", ":")).encode()
    return data if len(data) <= MAX_SEED else None


def glb_as_gltf(path):
    """The same asset as a .gltf: the GLB's JSON with its BIN chunk as buffer 0's data: URI."""
    with open(path, "rb") as f:
        data = f.read()
    json_len, = struct.unpack_from("<I", data, 12)
    doc = json.loads(data[20:20 + json_len])
    rest = data[20 + json_len:]
    if len(rest) >= 8 and doc.get("buffers"):
        bin_len, = struct.unpack_from("<I", rest, 0)
        doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(rest[8:8 + bin_len]).decode()
    out = json.dumps(doc, separators=(",", ":")).encode()
    return out if len(out) <= MAX_SEED else None


def capture_bytes(rate, frames):
    out = b"IDKCAPT\0" + struct.pack("<IIfIQ", 1, 44, rate, 0, len(frames))
    for time, pos, yaw, pitch, yfov, scene_time, paused in frames:
        out += struct.pack("<dffffffdI", time, *pos, yaw, pitch, yfov, scene_time, paused)
    return out


def pixel_count(path):
    info = subprocess.run(["oiiotool", "--info", path], capture_output=True, text=True, check=False).stdout
    try:
        dims = info.split(" : ", 1)[1].split(",")[0].split("x")
        return int(dims[0]) * int(dims[1])
    except (IndexError, ValueError):
        return None


def image_seeds(out):
    """Decoding costs per pixel, so seeds are small images: scene files of at most 128x128 texels, and 16x16
    conversions of a scene image to every format and channel layout the decoder handles."""
    if not shutil.which("oiiotool"):
        return
    images = [p for p in scene_files(".png", ".jpg", ".jpeg") if os.path.getsize(p) <= 64 * 1024]
    for p in images:
        if (pixel_count(p) or 1 << 30) <= 128 * 128:
            with open(p, "rb") as f:
                put(out, f.read(), "scene")
    if not images:
        return
    layouts = [("", []), ("_u16", ["-d", "uint16"]), ("_half", ["-d", "half"]), ("_grey", ["--ch", "R"]),
               ("_greyalpha", ["--ch", "R,A=0.5"]), ("_rgba", ["--ch", "R,G,B,A=0.25"])]
    with tempfile.TemporaryDirectory() as tmp:
        extensions = ("png", "jpg", "bmp", "gif", "hdr", "exr", "tif", "webp", "dds", "tga")
        for suffix, args in layouts:  # one oiiotool run writes every format of a layout
            outputs = [os.path.join(tmp, "small%s.%s" % (suffix, ext)) for ext in extensions]
            command = ["oiiotool", images[0], "--resize", "16x16"] + args
            for target in outputs:
                command += ["-o", target]
            subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False)
            for target in outputs:
                if os.path.isfile(target):
                    with open(target, "rb") as f:
                        put(out, f.read(), os.path.basename(target).replace(".", "_"))


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    name, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    committed = os.path.join(ROOT, "tests", "fuzz", "seeds", name)
    if os.path.isdir(committed):
        for f in sorted(os.listdir(committed)):
            with open(os.path.join(committed, f), "rb") as fh:
                put(out, fh.read(), "committed")
    if name == "gltf":
        for p in scene_files(".gltf"):
            data = inline_gltf(p)
            if data:
                put(out, data, os.path.splitext(os.path.basename(p))[0])
        for p in scene_files(".glb"):
            data = glb_as_gltf(p) if os.path.getsize(p) <= MAX_SEED else None
            if data:
                put(out, data, os.path.splitext(os.path.basename(p))[0] + "_from_glb")
    elif name == "glb":
        for p in scene_files(".glb"):
            if os.path.getsize(p) <= MAX_SEED:
                with open(p, "rb") as f:
                    put(out, f.read(), os.path.splitext(os.path.basename(p))[0])
    elif name == "image":
        image_seeds(out)
    elif name == "capture":
        walk = [(i / 30.0, (0.1 * i, 1.0, -2.0), 0.05 * i, -0.1, 0.8, i / 30.0, 0) for i in range(5)]
        put(out, capture_bytes(30.0, []), "empty")
        put(out, capture_bytes(1000.0, walk[:1]), "one")
        put(out, capture_bytes(30.0, walk), "walk")
        put(out, capture_bytes(0.5, [w[:6] + (1,) for w in walk]), "paused")
        put(out, capture_bytes(24.0, [(0.0, (0.0, 0.0, 0.0), math.pi, 1.5, 3.14, 1e9, 1)]), "extreme")
    elif name != "script":
        sys.exit("fuzz_seeds.py: unknown harness " + name)


if __name__ == "__main__":
    main()
