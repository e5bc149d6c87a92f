#!/usr/bin/env python3
"""Builds the fuzzers' glTF seed corpus (tests/fuzz/corpus/*.glb) from ../shared/scenes.

Each seed is one self-contained GLB: the scene's JSON, its buffer as the BIN chunk and its
images (shrunk to 32x32 PNGs with oiiotool) in buffer views, so the fuzzers mutate every part
of a file (JSON fields, accessor and view numbers, buffer bytes, image headers) in one blob.
Run once by hand; the corpus is committed and the tests need no ../shared.
"""
import json, os, struct, subprocess, sys, tempfile

here = os.path.dirname(os.path.abspath(__file__))
shared = os.path.join(here, "..", "..", "..", "shared", "scenes")
out_dir = os.path.join(here, "corpus")


def pad4(b, fill=b"\0"):
    return b + fill * ((4 - len(b) % 4) % 4)


def make_glb(gltf_path, out_name):
    folder = os.path.dirname(gltf_path)
    doc = json.load(open(gltf_path))
    bins = [open(os.path.join(folder, b["uri"]), "rb").read() for b in doc["buffers"]]
    assert len(bins) == 1, "one buffer expected"
    data = pad4(bins[0])
    for img in doc.get("images", []):
        uri = img.pop("uri")
        with tempfile.TemporaryDirectory() as t:
            small = os.path.join(t, "small.png")
            subprocess.run(["oiiotool", os.path.join(folder, uri), "--resize", "32x32", "-d", "uint8", "-o", small], check=True)
            png = open(small, "rb").read()
        doc["bufferViews"].append({"buffer": 0, "byteOffset": len(data), "byteLength": len(png)})
        img["bufferView"] = len(doc["bufferViews"]) - 1
        img["mimeType"] = "image/png"
        data = pad4(data + png)
    doc["buffers"] = [{"byteLength": len(data)}]
    js = pad4(json.dumps(doc, separators=(",", ":")).encode(), b" ")
    total = 12 + 8 + len(js) + 8 + len(data)
    glb = b"glTF" + struct.pack("<II", 2, total) + struct.pack("<I", len(js)) + b"JSON" + js + struct.pack("<I", len(data)) + b"BIN\0" + data
    open(os.path.join(out_dir, out_name), "wb").write(glb)
    print(out_name, len(glb), "bytes")


seeds = {
    "cornell_original.glb": "cornell_box/CornellBox-Original.gltf",
    "cornell_sphere.glb": "cornell_box/CornellBox-Sphere.gltf",
    "cornell_empty_rg.glb": "cornell_box/CornellBox-Empty-RG.gltf",
    "avocado.glb": "avocado/Avocado.gltf",
    "water_bottle.glb": "water_bottle/WaterBottle.gltf",
}
for name, rel in seeds.items():
    make_glb(os.path.join(shared, rel), name)
