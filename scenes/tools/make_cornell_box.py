#!/usr/bin/env python3
"""make_cornell_box.py: writes scenes/cornell_box.gltf, the Cornell box from its published measurements.

Source of the numbers: "Cornell Box Data", Cornell University Program of Computer Graphics
(https://www.graphics.cornell.edu/online/box/data.html): vertex coordinates in millimetres, camera
position/direction/focal length/film size. Python 3 standard library only; the output is deterministic.

Usage: python3 scenes/tools/make_cornell_box.py [OUTPUT.gltf]   (default: scenes/cornell_box.gltf)
"""
import base64
import json
import math
import struct
import sys
from pathlib import Path

# --- Geometry: the published quads, in millimetres, in the data's own frame ------------------------------
# The data frame is right-handed with y up: x runs from the green wall (x = 0) to the red wall (x ~ 556),
# z from the open front (z = 0) to the back wall (z = 559.2); the camera sits at z = -800 looking along +z.
# Each quad is listed exactly as published (4 corners, in order). The left (red) wall is not planar in the
# data (its corners are off by a few millimetres), which is why every triangle gets its own flat normal.
FLOOR = [(552.8, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 559.2), (549.6, 0.0, 559.2)]
CEILING = [(556.0, 548.8, 0.0), (556.0, 548.8, 559.2), (0.0, 548.8, 559.2), (0.0, 548.8, 0.0)]
BACK_WALL = [(549.6, 0.0, 559.2), (0.0, 0.0, 559.2), (0.0, 548.8, 559.2), (556.0, 548.8, 559.2)]
RIGHT_WALL = [(0.0, 0.0, 559.2), (0.0, 0.0, 0.0), (0.0, 548.8, 0.0), (0.0, 548.8, 559.2)]  # green
LEFT_WALL = [(552.8, 0.0, 0.0), (549.6, 0.0, 559.2), (556.0, 548.8, 559.2), (556.0, 548.8, 0.0)]  # red
LIGHT = [(343.0, 548.8, 227.0), (343.0, 548.8, 332.0), (213.0, 548.8, 332.0), (213.0, 548.8, 227.0)]
SHORT_BLOCK = [
    [(130.0, 165.0, 65.0), (82.0, 165.0, 225.0), (240.0, 165.0, 272.0), (290.0, 165.0, 114.0)],
    [(290.0, 0.0, 114.0), (290.0, 165.0, 114.0), (240.0, 165.0, 272.0), (240.0, 0.0, 272.0)],
    [(130.0, 0.0, 65.0), (130.0, 165.0, 65.0), (290.0, 165.0, 114.0), (290.0, 0.0, 114.0)],
    [(82.0, 0.0, 225.0), (82.0, 165.0, 225.0), (130.0, 165.0, 65.0), (130.0, 0.0, 65.0)],
    [(240.0, 0.0, 272.0), (240.0, 165.0, 272.0), (82.0, 165.0, 225.0), (82.0, 0.0, 225.0)],
]
TALL_BLOCK = [
    [(423.0, 330.0, 247.0), (265.0, 330.0, 296.0), (314.0, 330.0, 456.0), (472.0, 330.0, 406.0)],
    [(423.0, 0.0, 247.0), (423.0, 330.0, 247.0), (472.0, 330.0, 406.0), (472.0, 0.0, 406.0)],
    [(472.0, 0.0, 406.0), (472.0, 330.0, 406.0), (314.0, 330.0, 456.0), (314.0, 0.0, 456.0)],
    [(314.0, 0.0, 456.0), (314.0, 330.0, 456.0), (265.0, 330.0, 296.0), (265.0, 0.0, 296.0)],
    [(265.0, 0.0, 296.0), (265.0, 330.0, 296.0), (423.0, 330.0, 247.0), (423.0, 0.0, 247.0)],
]
# The published light quad lies in the ceiling plane (y = 548.8); we lower it by 0.5 mm so that a rasterizer
# does not z-fight it against the ceiling. It emits downwards only (one-sided, facing -y).
LIGHT_DROP_MM = 0.5
ROOM_CENTRE_MM = (278.0, 274.4, 279.6)  # only used to orient the walls' normals inwards

# --- Camera: published as position (278, 273, -800) mm, direction (0, 0, 1), up (0, 1, 0), focal length
# 0.035 m, film 0.025 x 0.025 m. Vertical FOV = 2 * atan((0.025 / 2) / 0.035) = 2 * atan(0.357142857)
# = 0.686048 rad = 39.3076 degrees; aspect ratio 1 (square film).
CAMERA_POSITION_MM = (278.0, 273.0, -800.0)
FOCAL_LENGTH_M = 0.035
FILM_HEIGHT_M = 0.025
CAMERA_YFOV = 2.0 * math.atan((FILM_HEIGHT_M / 2.0) / FOCAL_LENGTH_M)
CAMERA_ZNEAR = 0.05  # metres
CAMERA_ZFAR = 10.0

# --- Materials: the data give reflectance spectra (400-700 nm) and an emission spectrum. We use the RGB values
# commonly derived from them (e.g. the pbrt/Mitsuba Cornell box scenes), as LINEAR base colours.
WHITE = (0.73, 0.73, 0.73)
RED = (0.65, 0.05, 0.05)
GREEN = (0.12, 0.45, 0.15)
LIGHT_ALBEDO = (0.78, 0.78, 0.78)  # the data list the light's reflectance as ~0.78
# Emitted radiance of the light quad (W / (m^2 sr), linear RGB): the customary (17, 12, 4). glTF clamps
# emissiveFactor to [0, 1], so it is written as factor * KHR_materials_emissive_strength.
LIGHT_RADIANCE = (17.0, 12.0, 4.0)

# --- Conversion to glTF: rotate 180 degrees about +y, (x, y, z) -> (-x, y, -z), and scale mm -> m. This is a
# proper rotation (no mirroring, winding and handedness are kept): the camera then looks down -z (glTF's camera
# convention) into the open side, the green wall stays on the right and the red wall on the left.
MM_TO_M = 0.001


def to_gltf(p):
    return (-p[0] * MM_TO_M, p[1] * MM_TO_M, -p[2] * MM_TO_M)


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def normalize(a):
    length = math.sqrt(dot(a, a))
    return (a[0] / length, a[1] / length, a[2] / length)


def quad_centre(quad):
    return tuple(sum(p[i] for p in quad) / 4.0 for i in range(3))


def orient(quad, towards):
    """Returns the quad with a counter-clockwise winding seen from the side `towards` points to."""
    n = cross(sub(quad[1], quad[0]), sub(quad[2], quad[0]))
    return list(quad) if dot(n, towards) > 0.0 else list(reversed(quad))


def quad_triangles(quad):
    """Two triangles (0,1,2) and (0,2,3); each gets its own 3 vertices and flat normal."""
    return [(quad[0], quad[1], quad[2]), (quad[0], quad[2], quad[3])]


class MeshBuilder:
    def __init__(self, name, material):
        self.name = name
        self.material = material
        self.positions = []
        self.normals = []

    def add_quad(self, quad_mm, towards):
        quad = orient([to_gltf(p) for p in quad_mm], towards)
        for tri in quad_triangles(quad):
            n = normalize(cross(sub(tri[1], tri[0]), sub(tri[2], tri[0])))
            for p in tri:
                self.positions.append(p)
                self.normals.append(n)


def build_meshes():
    room_centre = to_gltf(ROOM_CENTRE_MM)
    meshes = []

    def wall(name, quad, material):
        m = MeshBuilder(name, material)
        m.add_quad(quad, sub(room_centre, to_gltf(quad_centre(quad))))  # walls face the inside of the room
        meshes.append(m)

    wall("floor", FLOOR, 0)
    wall("ceiling", CEILING, 0)
    wall("back_wall", BACK_WALL, 0)
    wall("left_wall_red", LEFT_WALL, 1)
    wall("right_wall_green", RIGHT_WALL, 2)
    for name, faces in (("short_block", SHORT_BLOCK), ("tall_block", TALL_BLOCK)):
        m = MeshBuilder(name, 0)
        block_centre = to_gltf(tuple(sum(quad_centre(q)[i] for q in faces) / len(faces) for i in range(3)))
        for quad in faces:
            m.add_quad(quad, sub(to_gltf(quad_centre(quad)), block_centre))  # block faces point outwards
        meshes.append(m)
    light = MeshBuilder("light", 3)
    light.add_quad([(x, y - LIGHT_DROP_MM, z) for (x, y, z) in LIGHT], (0.0, -1.0, 0.0))
    meshes.append(light)
    return meshes


def pad4(data):
    return data + b"\0" * ((4 - len(data) % 4) % 4)


def build_gltf():
    meshes = build_meshes()
    positions_blob, normals_blob, indices_blob = b"", b"", b""
    accessors, gltf_meshes, nodes = [], [], []
    for mesh in meshes:
        count = len(mesh.positions)
        lo = [min(p[i] for p in mesh.positions) for i in range(3)]
        hi = [max(p[i] for p in mesh.positions) for i in range(3)]
        # Round the float32 min/max exactly as the validator recomputes them from the stored floats.
        lo = [struct.unpack("<f", struct.pack("<f", v))[0] for v in lo]
        hi = [struct.unpack("<f", struct.pack("<f", v))[0] for v in hi]
        accessors.append({"bufferView": 0, "byteOffset": len(positions_blob), "componentType": 5126,
                          "count": count, "type": "VEC3", "min": lo, "max": hi})
        accessors.append({"bufferView": 1, "byteOffset": len(normals_blob), "componentType": 5126,
                          "count": count, "type": "VEC3"})
        accessors.append({"bufferView": 2, "byteOffset": len(indices_blob), "componentType": 5123,
                          "count": count, "type": "SCALAR", "min": [0], "max": [count - 1]})
        positions_blob += b"".join(struct.pack("<3f", *p) for p in mesh.positions)
        normals_blob += b"".join(struct.pack("<3f", *n) for n in mesh.normals)
        indices_blob = pad4(indices_blob + struct.pack(f"<{count}H", *range(count)))
        base = len(accessors) - 3
        gltf_meshes.append({"name": mesh.name, "primitives": [{
            "attributes": {"POSITION": base, "NORMAL": base + 1}, "indices": base + 2,
            "material": mesh.material, "mode": 4}]})
        nodes.append({"name": mesh.name, "mesh": len(gltf_meshes) - 1})

    camera_node = len(nodes)
    nodes.append({"name": "camera", "camera": 0, "translation": list(to_gltf(CAMERA_POSITION_MM))})
    # Point light for rasterizers without area lights: centred under the light quad, 1 cm below the ceiling.
    # Its intensity (candela) is the on-axis radiant intensity of the Lambertian light quad, I = L * A, with
    # A = 0.130 m x 0.105 m, so the floor right below receives the same irradiance from either light.
    light_area = 0.130 * 0.105
    light_centre = to_gltf((278.0, 548.8 - 10.0, 279.5))
    light_node = len(nodes)
    nodes.append({"name": "point_light", "translation": list(light_centre),
                  "extensions": {"KHR_lights_punctual": {"light": 0}}})

    max_radiance = max(LIGHT_RADIANCE)
    emissive_factor = [c / max_radiance for c in LIGHT_RADIANCE]

    def lambert(name, rgb):
        return {"name": name, "pbrMetallicRoughness": {"baseColorFactor": list(rgb) + [1.0],
                                                       "metallicFactor": 0.0, "roughnessFactor": 1.0}}

    light_material = lambert("light", LIGHT_ALBEDO)
    light_material["emissiveFactor"] = emissive_factor
    light_material["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": max_radiance}}

    blob = pad4(positions_blob) + pad4(normals_blob) + indices_blob
    normals_offset = len(pad4(positions_blob))
    indices_offset = normals_offset + len(pad4(normals_blob))
    gltf = {
        "asset": {"version": "2.0", "generator": "idk-vk scenes/tools/make_cornell_box.py",
                  "copyright": "Geometry and camera: Cornell Box Data, Cornell University Program of Computer Graphics"},
        "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_emissive_strength"],
        "scene": 0,
        "scenes": [{"name": "cornell_box", "nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "cameras": [{"name": "cornell_camera", "type": "perspective",
                     "perspective": {"yfov": CAMERA_YFOV, "aspectRatio": 1.0,
                                     "znear": CAMERA_ZNEAR, "zfar": CAMERA_ZFAR}}],
        "extensions": {"KHR_lights_punctual": {"lights": [{
            "name": "ceiling_point", "type": "point",
            "color": emissive_factor, "intensity": max_radiance * light_area}]}},
        "materials": [lambert("white", WHITE), lambert("red", RED), lambert("green", GREEN), light_material],
        "meshes": gltf_meshes,
        "accessors": accessors,
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": len(positions_blob), "byteStride": 12, "target": 34962},
            {"buffer": 0, "byteOffset": normals_offset, "byteLength": len(normals_blob), "byteStride": 12,
             "target": 34962},
            {"buffer": 0, "byteOffset": indices_offset, "byteLength": len(indices_blob), "target": 34963},
        ],
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode("ascii")}],
    }
    assert camera_node == 8 and light_node == 9
    return gltf


def main():
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "cornell_box.gltf"
    text = json.dumps(build_gltf(), indent=1) + "\n"
    out.write_text(text)
    print(f"wrote {out} ({len(text)} bytes)")


if __name__ == "__main__":
    main()
