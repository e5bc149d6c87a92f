#!/usr/bin/env python3
"""Writes the five glTF scenes of presets/matrix/unseen_rooms.json into this folder (self-contained,
buffers embedded as base64; standard library only): interiors and a courtyard of the kinds the
Cornell boxes and Sponza do not cover, each with its own light and camera and no preset, so every
technique renders them with its defaults.
  sunlit_room.gltf        a 5 x 3 x 5 m room of 0.15 m box walls lit by the sun through a window
  sunlit_room_thick.gltf  the same room with 0.6 m walls
  corridor.gltf           a 14 m corridor of one-sided walls lit by a point light at its far end
  two_rooms.gltf          two rooms joined by a doorway, a spot light in one, the camera in the other
  courtyard.gltf          two buildings, a wall and a crate on open ground in the sun
Run it again after changing a scene; the files are committed so the matrix needs no Python."""
import base64
import json
import math
import os
import struct

OUT_DIR = os.path.dirname(os.path.abspath(__file__))


# ---------------------------------------------------------------- small vector maths
def sub(a, b): return (a[0] - b[0], a[1] - b[1], a[2] - b[2])
def dot(a, b): return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
def cross(a, b): return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
def neg(a): return (-a[0], -a[1], -a[2])


def normalize(a):
    l = math.sqrt(dot(a, a))
    return (a[0] / l, a[1] / l, a[2] / l)


def quat_from_basis(x, y, z):
    """Quaternion [x,y,z,w] of the rotation whose matrix has columns x, y, z."""
    m00, m01, m02 = x[0], y[0], z[0]
    m10, m11, m12 = x[1], y[1], z[1]
    m20, m21, m22 = x[2], y[2], z[2]
    tr = m00 + m11 + m22
    if tr > 0:
        s = math.sqrt(tr + 1.0) * 2
        w, qx, qy, qz = 0.25 * s, (m21 - m12) / s, (m02 - m20) / s, (m10 - m01) / s
    elif m00 > m11 and m00 > m22:
        s = math.sqrt(1.0 + m00 - m11 - m22) * 2
        w, qx, qy, qz = (m21 - m12) / s, 0.25 * s, (m01 + m10) / s, (m02 + m20) / s
    elif m11 > m22:
        s = math.sqrt(1.0 + m11 - m00 - m22) * 2
        w, qx, qy, qz = (m02 - m20) / s, (m01 + m10) / s, 0.25 * s, (m12 + m21) / s
    else:
        s = math.sqrt(1.0 + m22 - m00 - m11) * 2
        w, qx, qy, qz = (m10 - m01) / s, (m02 + m20) / s, (m12 + m21) / s, 0.25 * s
    n = math.sqrt(qx * qx + qy * qy + qz * qz + w * w)
    return [qx / n, qy / n, qz / n, w / n]


def look_rotation(direction, up=(0.0, 1.0, 0.0)):
    """Rotation that maps the node's -Z onto `direction` and keeps +Y as close to `up` as it can."""
    f = normalize(direction)
    if abs(dot(f, normalize(up))) > 0.999:
        up = (1.0, 0.0, 0.0)
    r = normalize(cross(f, up))
    u = cross(r, f)
    return quat_from_basis(r, u, neg(f))


# ---------------------------------------------------------------- geometry
def quad(p0, p1, p2, p3, normal):
    """One flat quad (4 vertices, 2 triangles) wound counter-clockwise seen from `normal`."""
    pts = [p0, p1, p2, p3]
    if dot(cross(sub(p1, p0), sub(p2, p0)), normal) < 0:
        pts = [p0, p3, p2, p1]
    return pts, [normal] * 4, [0, 1, 2, 0, 2, 3]


def box_faces(lo, hi, inward=False):
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    faces = [
        ([(x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1)], (1, 0, 0)),
        ([(x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0)], (-1, 0, 0)),
        ([(x0, y1, z0), (x0, y1, z1), (x1, y1, z1), (x1, y1, z0)], (0, 1, 0)),
        ([(x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1)], (0, -1, 0)),
        ([(x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)], (0, 0, 1)),
        ([(x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (x1, y0, z0)], (0, 0, -1)),
    ]
    out = []
    for pts, n in faces:
        n = tuple(float(c) for c in n)
        if inward:
            n = neg(n)
        out.append(quad(*pts, n))
    return out


def merge(faces):
    pos, nrm, idx = [], [], []
    for p, n, i in faces:
        base = len(pos)
        pos += p
        nrm += n
        idx += [base + k for k in i]
    return pos, nrm, idx


def box(lo, hi):
    return merge(box_faces(lo, hi))


def inward_box(lo, hi):
    return merge(box_faces(lo, hi, inward=True))


# ---------------------------------------------------------------- glTF writer
class Gltf:
    def __init__(self):
        self.bin = bytearray()
        self.doc = {
            "asset": {"version": "2.0", "generator": "gen.py"},
            "extensionsUsed": ["KHR_lights_punctual"],
            "scene": 0,
            "scenes": [{"nodes": []}],
            "nodes": [], "meshes": [], "materials": [], "accessors": [], "bufferViews": [],
            "buffers": [], "cameras": [],
            "extensions": {"KHR_lights_punctual": {"lights": []}},
        }
        self.mat_ids = {}

    def _view(self, data, target):
        while len(self.bin) % 4:
            self.bin.append(0)
        off = len(self.bin)
        self.bin += data
        self.doc["bufferViews"].append({"buffer": 0, "byteOffset": off, "byteLength": len(data), "target": target})
        return len(self.doc["bufferViews"]) - 1

    def _accessor(self, view, ctype, count, typ, mn=None, mx=None):
        a = {"bufferView": view, "componentType": ctype, "count": count, "type": typ}
        if mn is not None:
            a["min"], a["max"] = mn, mx
        self.doc["accessors"].append(a)
        return len(self.doc["accessors"]) - 1

    def material(self, name, albedo):
        key = (name, tuple(albedo))
        if key not in self.mat_ids:
            self.doc["materials"].append({
                "name": name,
                "pbrMetallicRoughness": {"baseColorFactor": [albedo[0], albedo[1], albedo[2], 1.0],
                                         "metallicFactor": 0.0, "roughnessFactor": 1.0}})
            self.mat_ids[key] = len(self.doc["materials"]) - 1
        return self.mat_ids[key]

    def mesh(self, name, geom, mat_name, albedo):
        pos, nrm, idx = geom
        pv = self._view(b"".join(struct.pack("<3f", *p) for p in pos), 34962)
        nv = self._view(b"".join(struct.pack("<3f", *n) for n in nrm), 34962)
        iv = self._view(struct.pack("<%dI" % len(idx), *idx), 34963)
        mn = [min(p[k] for p in pos) for k in range(3)]
        mx = [max(p[k] for p in pos) for k in range(3)]
        pa = self._accessor(pv, 5126, len(pos), "VEC3", mn, mx)
        na = self._accessor(nv, 5126, len(nrm), "VEC3")
        ia = self._accessor(iv, 5125, len(idx), "SCALAR")
        self.doc["meshes"].append({"name": name, "primitives": [{
            "attributes": {"POSITION": pa, "NORMAL": na}, "indices": ia,
            "material": self.material(mat_name, albedo), "mode": 4}]})
        self._node({"name": name, "mesh": len(self.doc["meshes"]) - 1})

    def _node(self, node):
        self.doc["nodes"].append(node)
        self.doc["scenes"][0]["nodes"].append(len(self.doc["nodes"]) - 1)

    def _light(self, name, light, node):
        lights = self.doc["extensions"]["KHR_lights_punctual"]["lights"]
        light["name"] = name
        lights.append(light)
        node["name"] = name
        node["extensions"] = {"KHR_lights_punctual": {"light": len(lights) - 1}}
        self._node(node)

    def sun(self, direction, intensity, color=(1.0, 1.0, 1.0)):
        self._light("sun", {"type": "directional", "color": list(color), "intensity": intensity},
                    {"rotation": look_rotation(direction)})

    def point(self, position, intensity, color=(1.0, 1.0, 1.0)):
        self._light("point", {"type": "point", "color": list(color), "intensity": intensity},
                    {"translation": list(position)})

    def spot(self, position, direction, intensity, inner, outer, color=(1.0, 1.0, 1.0)):
        self._light("spot", {"type": "spot", "color": list(color), "intensity": intensity,
                             "spot": {"innerConeAngle": inner, "outerConeAngle": outer}},
                    {"translation": list(position), "rotation": look_rotation(direction)})

    def camera(self, eye, target):
        self.doc["cameras"].append({"name": "camera", "type": "perspective",
                                    "perspective": {"yfov": 1.0, "znear": 0.05, "zfar": 100.0}})
        self._node({"name": "camera", "camera": len(self.doc["cameras"]) - 1,
                    "translation": list(eye), "rotation": look_rotation(sub(target, eye))})

    def write(self, filename):
        while len(self.bin) % 4:
            self.bin.append(0)
        self.doc["buffers"] = [{"byteLength": len(self.bin),
                                "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(self.bin)).decode("ascii")}]
        path = os.path.join(OUT_DIR, filename)
        with open(path, "w") as f:
            json.dump(self.doc, f, indent=1)
        print("wrote", path)


GREY = (0.75, 0.75, 0.75)


# ---------------------------------------------------------------- scenes
def w_sun(filename, t):
    """Room x,z in [-2.5,2.5], y in [0,3]; shell boxes of thickness t lie outside the interior."""
    g = Gltf()
    X, Y = 2.5, 3.0
    # floor and ceiling cover the walls' footprint too, so the shell is closed at the edges
    g.mesh("floor", box((-X - t, -t, -X - t), (X + t, 0, X + t)), "grey", GREY)
    g.mesh("ceiling", box((-X - t, Y, -X - t), (X + t, Y + t, X + t)), "grey", GREY)
    g.mesh("wall_-x", box((-X - t, 0, -X - t), (-X, Y, X + t)), "blue", (0.2, 0.3, 0.7))
    g.mesh("wall_+x", box((X, 0, -X - t), (X + t, Y, X + t)), "grey", GREY)
    g.mesh("wall_+z", box((-X, 0, X), (X, Y, X + t)), "grey", GREY)
    # -z wall with a window opening x in [-0.8,0.8], y in [1,2.2]
    z0, z1 = -X - t, -X
    g.mesh("wall_-z_left", box((-X, 0, z0), (-0.8, Y, z1)), "grey", GREY)
    g.mesh("wall_-z_right", box((0.8, 0, z0), (X, Y, z1)), "grey", GREY)
    g.mesh("wall_-z_below", box((-0.8, 0, z0), (0.8, 1.0, z1)), "grey", GREY)
    g.mesh("wall_-z_above", box((-0.8, 2.2, z0), (0.8, Y, z1)), "grey", GREY)
    g.mesh("orange_box", box((0.8, 0, 0.6), (1.8, 0.8, 1.6)), "orange", (0.8, 0.4, 0.1))
    g.sun(normalize((0.25, -0.6, 0.75)), 8.0)
    g.camera((1.8, 1.6, -2.2), (-1.0, 0.8, 1.5))
    g.write(filename)


def corr():
    g = Gltf()
    g.mesh("corridor", inward_box((-1, 0, -7), (1, 3, 7)), "wall", (0.7, 0.7, 0.7))
    g.mesh("red_block", box((-1, 0, 2), (-0.6, 1.2, 3)), "red", (0.8, 0.1, 0.1))
    g.point((0, 2.5, -6), 40.0)
    g.camera((0.5, 1.6, 6.5), (0, 1.2, -7))
    g.write("corridor.gltf")


def l_flat():
    g = Gltf()
    g.mesh("shell", inward_box((-4, 0, -2), (4.1, 2.8, 2)), "grey", GREY)
    g.mesh("divider_a", box((0, 0, -2), (0.1, 2.8, -0.6)), "grey", GREY)
    g.mesh("divider_b", box((0, 0, 0.6), (0.1, 2.8, 2)), "grey", GREY)
    g.mesh("divider_lintel", box((0, 2.1, -0.6), (0.1, 2.8, 0.6)), "grey", GREY)
    g.spot((-2, 2.6, 0.5), normalize((0.2, -1, -0.1)), 60.0, 0.4, 0.8)
    g.camera((3.6, 1.5, -1.6), (0, 1, 0.4))
    g.write("two_rooms.gltf")


def court():
    g = Gltf()
    ground = merge([quad((-8, 0, -8), (-8, 0, 8), (8, 0, 8), (8, 0, -8), (0.0, 1.0, 0.0))])
    g.mesh("ground", ground, "ground", (0.5, 0.5, 0.45))
    g.mesh("building_n", box((-6, 0, -6), (6, 5, -3)), "building", (0.8, 0.78, 0.7))
    g.mesh("building_w", box((-6, 0, -3), (-3, 4, 6)), "building", (0.8, 0.78, 0.7))
    g.mesh("red_wall", box((2, 0, 1), (6, 2.5, 1.4)), "red", (0.7, 0.15, 0.1))
    g.mesh("crate", box((-1, 0, -1), (0.2, 1.2, 0.2)), "yellow", (0.8, 0.7, 0.1))
    g.sun(normalize((0.5, -0.55, -0.65)), 6.0)
    g.camera((6, 2.2, 6), (-3, 1.5, -3))
    g.write("courtyard.gltf")


if __name__ == "__main__":
    w_sun("sunlit_room.gltf", 0.15)
    w_sun("sunlit_room_thick.gltf", 0.6)
    corr()
    l_flat()
    court()
