#!/usr/bin/env python3
"""Writes scenarios/assets/Box/box.gltf: a 1 m cube centred on its origin (24 vertices with flat
normals, 12 triangles, counter-clockwise seen from outside), one buffer embedded as base64.
Copies on a grid with spacing 1 share their faces exactly, the test scene for ties in depth
(docs/error.md). Run from the repository root: python3 scripts/make_box_gltf.py"""
import base64
import json
import struct
from pathlib import Path

FACES = [  # normal, and two axes spanning the face so that u x v = normal (counter-clockwise)
    ((1, 0, 0), (0, 1, 0), (0, 0, 1)),
    ((-1, 0, 0), (0, 0, 1), (0, 1, 0)),
    ((0, 1, 0), (0, 0, 1), (1, 0, 0)),
    ((0, -1, 0), (1, 0, 0), (0, 0, 1)),
    ((0, 0, 1), (1, 0, 0), (0, 1, 0)),
    ((0, 0, -1), (0, 1, 0), (1, 0, 0)),
]

positions, normals, indices = [], [], []
for n, u, v in FACES:
    base = len(positions)
    for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
        positions.append(tuple(0.5 * n[i] + 0.5 * su * u[i] + 0.5 * sv * v[i] for i in range(3)))
        normals.append(n)
    indices += [base, base + 1, base + 2, base, base + 2, base + 3]

pos_bytes = b"".join(struct.pack("<3f", *p) for p in positions)
nor_bytes = b"".join(struct.pack("<3f", *n) for n in normals)
idx_bytes = b"".join(struct.pack("<H", i) for i in indices)
data = pos_bytes + nor_bytes + idx_bytes
gltf = {
    "asset": {"version": "2.0", "generator": "occsim scripts/make_box_gltf.py"},
    "scene": 0,
    "scenes": [{"nodes": [0]}],
    "nodes": [{"mesh": 0, "name": "Box"}],
    "meshes": [{"name": "Box", "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2}]}],
    "buffers": [{"byteLength": len(data),
                 "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
    "bufferViews": [
        {"buffer": 0, "byteOffset": 0, "byteLength": len(pos_bytes), "target": 34962},
        {"buffer": 0, "byteOffset": len(pos_bytes), "byteLength": len(nor_bytes), "target": 34962},
        {"buffer": 0, "byteOffset": len(pos_bytes) + len(nor_bytes), "byteLength": len(idx_bytes), "target": 34963},
    ],
    "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": len(positions), "type": "VEC3",
         "min": [-0.5, -0.5, -0.5], "max": [0.5, 0.5, 0.5]},
        {"bufferView": 1, "componentType": 5126, "count": len(normals), "type": "VEC3"},
        {"bufferView": 2, "componentType": 5123, "count": len(indices), "type": "SCALAR"},
    ],
}
out = Path("scenarios/assets/Box/box.gltf")
out.write_text(json.dumps(gltf, indent=1) + "\n")
print(f"wrote {out}: {len(positions)} vertices, {len(indices) // 3} triangles")
