#!/usr/bin/env python3
"""make_material_spheres.py: writes scenes/material_spheres.gltf, four spheres on a floor, one per BSDF material
extension the renderers implement: KHR_materials_specular (a red plastic with a weak, orange-tinted specular),
KHR_materials_clearcoat (a rough red base under a smooth coat), KHR_materials_sheen (a dark velvet with a pink
sheen) and a rough gold metal (the GGX multiple-scattering compensation). A point light and a camera. Python 3
standard library only; the output is deterministic.

Usage: python3 scenes/tools/make_material_spheres.py [OUTPUT.gltf]   (default: scenes/material_spheres.gltf)
"""
import base64
import json
import math
import struct
import sys
from pathlib import Path

RINGS, SEGMENTS = 12, 24  # per sphere: 12 * 24 * 2 triangles minus the poles' degenerate halves


def sphere(radius):
    """UV sphere: positions, normals, indices (counter-clockwise seen from outside)."""
    pos, nrm, idx = [], [], []
    for r in range(RINGS + 1):
        theta = math.pi * r / RINGS
        for s in range(SEGMENTS + 1):
            phi = 2.0 * math.pi * s / SEGMENTS
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi))
            nrm.append(n)
            pos.append(tuple(radius * c for c in n))
    for r in range(RINGS):
        for s in range(SEGMENTS):
            a = r * (SEGMENTS + 1) + s
            b = a + SEGMENTS + 1
            if r != 0:
                idx += [a, b, a + 1]
            if r != RINGS - 1:
                idx += [a + 1, b, b + 1]
    return pos, nrm, idx


def floor(half):
    pos = [(-half, 0.0, half), (half, 0.0, half), (half, 0.0, -half), (-half, 0.0, -half)]
    return pos, [(0.0, 1.0, 0.0)] * 4, [0, 1, 2, 0, 2, 3]


MATERIALS = [
    {"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1.0], "metallicFactor": 0.0,
                                               "roughnessFactor": 0.8}},
    {"name": "specular_plastic",
     "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.15, 0.1, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.35},
     "extensions": {"KHR_materials_specular": {"specularFactor": 0.3, "specularColorFactor": [1.0, 0.6, 0.3]}}},
    {"name": "clearcoat_paint",
     "pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.05, 0.05, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.7},
     "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1.0, "clearcoatRoughnessFactor": 0.1}}},
    {"name": "sheen_velvet",
     "pbrMetallicRoughness": {"baseColorFactor": [0.1, 0.02, 0.1, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.9},
     "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [0.9, 0.5, 0.9], "sheenRoughnessFactor": 0.4}}},
    {"name": "rough_gold", "pbrMetallicRoughness": {"baseColorFactor": [1.0, 0.77, 0.34, 1.0], "metallicFactor": 1.0,
                                                    "roughnessFactor": 0.8}},
]
RADIUS = 0.45
CENTRES = [(-1.5, RADIUS, 0.0), (-0.5, RADIUS, 0.0), (0.5, RADIUS, 0.0), (1.5, RADIUS, 0.0)]


def main():
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "material_spheres.gltf"
    blob = bytearray()
    views, accessors, meshes = [], [], []

    def add_view(data, target):
        while len(blob) % 4:
            blob.append(0)
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data), "target": target})
        blob.extend(data)
        return len(views) - 1

    def add_mesh(name, geometry, material):
        pos, nrm, idx = geometry
        lo = [min(p[i] for p in pos) for i in range(3)]
        hi = [max(p[i] for p in pos) for i in range(3)]
        pv = add_view(b"".join(struct.pack("<3f", *p) for p in pos), 34962)
        nv = add_view(b"".join(struct.pack("<3f", *n) for n in nrm), 34962)
        iv = add_view(b"".join(struct.pack("<H", i) for i in idx), 34963)
        accessors.append({"bufferView": pv, "componentType": 5126, "count": len(pos), "type": "VEC3", "min": lo,
                          "max": hi})
        accessors.append({"bufferView": nv, "componentType": 5126, "count": len(nrm), "type": "VEC3"})
        accessors.append({"bufferView": iv, "componentType": 5123, "count": len(idx), "type": "SCALAR"})
        n = len(accessors)
        meshes.append({"name": name, "primitives": [{"attributes": {"POSITION": n - 3, "NORMAL": n - 2},
                                                     "indices": n - 1, "material": material}]})
        return len(meshes) - 1

    nodes = [{"name": "floor", "mesh": add_mesh("floor", floor(3.0), 0)}]
    ball = sphere(RADIUS)
    for i, centre in enumerate(CENTRES):
        nodes.append({"name": MATERIALS[i + 1]["name"], "mesh": add_mesh(MATERIALS[i + 1]["name"], ball, i + 1),
                      "translation": list(centre)})
    # Camera at (0, 1.6, 4.2) looking at (0, 0.4, 0): a rotation about x by atan2(1.2, 4.2).
    pitch = -math.atan2(1.2, 4.2)
    nodes.append({"name": "camera", "camera": 0, "translation": [0.0, 1.6, 4.2],
                  "rotation": [math.sin(pitch / 2.0), 0.0, 0.0, math.cos(pitch / 2.0)]})
    nodes.append({"name": "light", "translation": [1.5, 3.0, 2.0],
                  "extensions": {"KHR_lights_punctual": {"light": 0}}})
    gltf = {
        "asset": {"version": "2.0", "generator": "idk-vk scenes/tools/make_material_spheres.py"},
        "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_specular", "KHR_materials_clearcoat",
                           "KHR_materials_sheen"],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "color": [1.0, 0.95, 0.9],
                                                            "intensity": 40.0}]}},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.6, "aspectRatio": 1.0, "znear": 0.05,
                                                            "zfar": 50.0}}],
        "meshes": meshes,
        "materials": MATERIALS,
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()}],
    }
    out.write_text(json.dumps(gltf, indent=1) + "\n")


if __name__ == "__main__":
    main()
