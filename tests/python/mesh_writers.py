# SPDX-License-Identifier: GPL-3.0-or-later
"""Writers of every mesh format hyvox offers (docs/mesh-formats.md), written from the format
descriptions with numpy and the standard library only: the test files they make do not come
from the library that reads them (assimp) nor from hyvox. Each takes float32 vertices (N, 3)
and uint32 triangles (M, 3) and returns the file's bytes.

    FORMATS: {name: (file suffix, writer)}"""

import base64
import io
import json
import struct
import zipfile
import zlib

import numpy as np


def _arrays(vertices, triangles):
    return np.ascontiguousarray(vertices, "<f4"), np.ascontiguousarray(triangles, "<u4")


def ply_binary(vertices, triangles):
    v, t = _arrays(vertices, triangles)
    header = (
        f"ply\nformat binary_little_endian 1.0\nelement vertex {len(v)}\nproperty float x\n"
        f"property float y\nproperty float z\nelement face {len(t)}\n"
        "property list uchar int vertex_indices\nend_header\n"
    ).encode()
    faces = np.zeros(len(t), np.dtype([("n", "u1"), ("i", "<i4", 3)]))
    faces["n"] = 3
    faces["i"] = t
    return header + v.tobytes() + faces.tobytes()


def obj(vertices, triangles):
    v, t = _arrays(vertices, triangles)
    lines = [f"v {x!r} {y!r} {z!r}\n" for x, y, z in v.astype(float).tolist()]
    lines += [f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in t.tolist()]
    return "".join(lines).encode()


def stl_binary(vertices, triangles):
    v, t = _arrays(vertices, triangles)
    records = np.zeros(len(t), np.dtype([("normal", "<f4", 3), ("corners", "<f4", (3, 3)), ("attribute", "<u2")]))
    records["corners"] = v[t]
    return b"binary STL written by the hyvox tests".ljust(80, b" ") + struct.pack("<I", len(t)) + records.tobytes()


def stl_ascii(vertices, triangles):
    v, t = _arrays(vertices, triangles)
    out = ["solid hyvox\n"]
    for corners in v[t].astype(float).tolist():
        out.append("facet normal 0 0 0\n outer loop\n")
        out += [f"  vertex {x!r} {y!r} {z!r}\n" for x, y, z in corners]
        out.append(" endloop\nendfacet\n")
    out.append("endsolid hyvox\n")
    return "".join(out).encode()


def off(vertices, triangles):
    v, t = _arrays(vertices, triangles)
    out = [f"OFF\n# written by the hyvox tests\n{len(v)} {len(t)} 0\n"]
    out += [f"{x!r} {y!r} {z!r}\n" for x, y, z in v.astype(float).tolist()]
    out += [f"3 {a} {b} {c}\n" for a, b, c in t.tolist()]
    return "".join(out).encode()


def _gltf(vertices, triangles, uri):
    """The glTF JSON and its one buffer (positions, then indices)."""
    v, t = _arrays(vertices, triangles)
    data = v.tobytes() + t.tobytes()
    buffer = {"byteLength": len(data)}
    if uri is not None:
        buffer["uri"] = uri(data)
    document = {
        "asset": {"version": "2.0", "generator": "hyvox tests"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": 4}]}],
        "buffers": [buffer],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": v.nbytes, "target": 34962},
            {"buffer": 0, "byteOffset": v.nbytes, "byteLength": t.nbytes, "target": 34963},
        ],
        "accessors": [
            {
                "bufferView": 0,
                "componentType": 5126,
                "count": len(v),
                "type": "VEC3",
                "min": v.min(axis=0).tolist(),
                "max": v.max(axis=0).tolist(),
            },
            {"bufferView": 1, "componentType": 5125, "count": t.size, "type": "SCALAR"},
        ],
    }
    return document, data


def gltf(vertices, triangles):
    """glTF with its buffer embedded as a base64 data URI (one self-contained file)."""
    document, _ = _gltf(
        vertices, triangles, lambda data: "data:application/octet-stream;base64," + base64.b64encode(data).decode()
    )
    return json.dumps(document).encode()


def glb(vertices, triangles):
    document, data = _gltf(vertices, triangles, None)
    text = json.dumps(document).encode()
    text += b" " * (-len(text) % 4)
    data += b"\0" * (-len(data) % 4)
    chunks = struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(data), 0x004E4942) + data
    return struct.pack("<III", 0x46546C67, 2, 12 + len(chunks)) + chunks


def three_mf(vertices, triangles):
    v, t = _arrays(vertices, triangles)
    vertex_xml = "".join(f'<vertex x="{x!r}" y="{y!r}" z="{z!r}"/>' for x, y, z in v.astype(float).tolist())
    triangle_xml = "".join(f'<triangle v1="{a}" v2="{b}" v3="{c}"/>' for a, b, c in t.tolist())
    model = (
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        '<model unit="millimeter" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">'
        f'<resources><object id="1" type="model"><mesh><vertices>{vertex_xml}</vertices>'
        f"<triangles>{triangle_xml}</triangles></mesh></object></resources>"
        '<build><item objectid="1"/></build></model>'
    )
    types = (
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        '<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">'
        '<Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/>'
        '<Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/>'
        "</Types>"
    )
    rels = (
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        '<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">'
        '<Relationship Target="/3D/3dmodel.model" Id="rel0" '
        'Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/></Relationships>'
    )
    out = io.BytesIO()
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("[Content_Types].xml", types)
        z.writestr("_rels/.rels", rels)
        z.writestr("3D/3dmodel.model", model)
    return out.getvalue()


class _Id(int):
    """An FBX object id: a 64-bit property (plain ints are 32-bit)."""


def _fbx_property(value, compress):
    if isinstance(value, str):
        data = value.encode()
        return b"S" + struct.pack("<I", len(data)) + data
    if isinstance(value, _Id):
        return b"L" + struct.pack("<q", value)
    if isinstance(value, int):
        return b"I" + struct.pack("<i", value)
    if isinstance(value, float):
        return b"D" + struct.pack("<d", value)
    array = np.asarray(value)
    code, dtype = {"f": (b"d", "<f8"), "i": (b"i", "<i4")}[array.dtype.kind]
    data = np.ascontiguousarray(array, dtype).tobytes()
    encoding = 0
    if compress:
        data, encoding = zlib.compress(data), 1
    return code + struct.pack("<III", array.size, encoding, len(data)) + data


def _fbx_node(name, properties, children, offset, wide, compress):
    """A binary FBX node record starting at file offset `offset` (64-bit fields from 7.5 on)."""
    props = b"".join(_fbx_property(p, compress) for p in properties)
    field = "<Q" if wide else "<I"
    head = 3 * struct.calcsize(field) + 1 + len(name)
    body = b""
    for child in children:
        body += child(offset + head + len(props) + len(body), wide, compress)
    if children:
        body += b"\0" * (3 * struct.calcsize(field) + 1)
    end = offset + head + len(props) + len(body)
    return (
        struct.pack(field, end)
        + struct.pack(field, len(properties))
        + struct.pack(field, len(props))
        + struct.pack("<B", len(name))
        + name.encode()
        + props
        + body
    )


def _node(name, properties=(), children=()):
    return lambda offset, wide, compress: _fbx_node(name, properties, children, offset, wide, compress)


def fbx(vertices, triangles, version=7400, compress=False):
    """Binary FBX (7.4 by default; 7.5 and later have 64-bit record fields), one Geometry and one
    Model connected to the root; `compress`: the arrays zlib-compressed, as exporters write
    large ones."""
    v, t = _arrays(vertices, triangles)
    polygon = t.astype(np.int64).copy()
    polygon[:, 2] = -polygon[:, 2] - 1  # the last corner of a polygon is written as -(index + 1)
    geometry = _node(
        "Geometry",
        (_Id(1000), "mesh\0\1Geometry", "Mesh"),
        [
            _node("Vertices", (v.reshape(-1).astype(np.float64),)),
            _node("PolygonVertexIndex", (polygon.reshape(-1).astype(np.int32),)),
            _node("GeometryVersion", (124,)),
        ],
    )
    model = _node("Model", (_Id(2000), "mesh\0\1Model", "Mesh"), [_node("Version", (232,))])
    nodes = [
        _node("FBXHeaderExtension", (), [_node("FBXHeaderVersion", (1003,)), _node("FBXVersion", (version,))]),
        _node("GlobalSettings", (), [_node("Version", (1000,))]),
        _node("Objects", (), [geometry, model]),
        _node("Connections", (), [_node("C", ("OO", _Id(1000), _Id(2000))), _node("C", ("OO", _Id(2000), _Id(0)))]),
    ]
    wide = version >= 7500
    out = b"Kaydara FBX Binary  \0\x1a\0" + struct.pack("<I", version)
    for n in nodes:
        out += n(len(out), wide, compress)
    return out + b"\0" * (25 if wide else 13)


# name: (file suffix, writer); the names are what bench and tests call the formats.
FORMATS = {
    "ply": (".ply", ply_binary),
    "obj": (".obj", obj),
    "stl_binary": (".stl", stl_binary),
    "stl_ascii": (".stl", stl_ascii),
    "off": (".off", off),
    "gltf": (".gltf", gltf),
    "glb": (".glb", glb),
    "3mf": (".3mf", three_mf),
    "fbx": (".fbx", fbx),
}
