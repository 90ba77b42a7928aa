#!/usr/bin/env python3
"""Writes the small committed seed inputs of fuzz/seeds/ (all made here, no third-party
files): glTF JSON with data: URIs (triangle, indexed quad with a texture, sparse accessor,
strip/fan, camera + light + material extensions), OBJ+MTL pairs, and PNG/JPEG/HDR images.
Usage: python3 fuzz/make_seeds.py  (needs Pillow for the PNG/JPEG seeds)."""
import base64, io, json, os, struct

HERE = os.path.dirname(os.path.abspath(__file__))
SEP = b"\n#%%MTL%%\n"  # iris::load::fuzz_entry::OBJ_MTL_SEPARATOR


def out(kind, name, data):
    with open(os.path.join(HERE, "seeds", kind, name), "wb") as f:
        f.write(data)


def png_bytes(mode="RGBA", size=(4, 4)):
    from PIL import Image
    img = Image.new(mode, size)
    for y in range(size[1]):
        for x in range(size[0]):
            v = (x * 60 + y * 30) % 256
            img.putpixel((x, y), {"RGBA": (v, 255 - v, 128, 200), "RGB": (v, v, 255 - v),
                                  "L": v, "P": v % 16, "I;16": v * 200}[mode])
    buf = io.BytesIO()
    img.save(buf, "PNG")
    return buf.getvalue()


def data_uri(b, mime="application/octet-stream"):
    return "data:%s;base64,%s" % (mime, base64.b64encode(b).decode())


def gltf(name, positions, indices=None, extra=None, mode=4, image=None, sparse=False):
    buf = b"".join(struct.pack("<3f", *p) for p in positions)
    views = [{"buffer": 0, "byteOffset": 0, "byteLength": len(buf)}]
    accessors = [{"bufferView": 0, "componentType": 5126, "count": len(positions), "type": "VEC3",
                  "min": [min(p[i] for p in positions) for i in range(3)],
                  "max": [max(p[i] for p in positions) for i in range(3)]}]
    prim = {"attributes": {"POSITION": 0}, "mode": mode, "material": 0}
    if indices is not None:
        off = len(buf)
        ib = b"".join(struct.pack("<H", i) for i in indices)
        buf += ib + b"\0" * (-len(ib) % 4)
        views.append({"buffer": 0, "byteOffset": off, "byteLength": len(ib)})
        accessors.append({"bufferView": 1, "componentType": 5123, "count": len(indices), "type": "SCALAR"})
        prim["indices"] = 1
    if sparse:
        off = len(buf)
        sb = struct.pack("<B", 1) + b"\0\0\0" + struct.pack("<3f", 0.0, 2.0, 0.0)
        buf += sb
        views += [{"buffer": 0, "byteOffset": off, "byteLength": 1},
                  {"buffer": 0, "byteOffset": off + 4, "byteLength": 12}]
        accessors[0]["sparse"] = {"count": 1, "indices": {"bufferView": len(views) - 2, "componentType": 5121},
                                  "values": {"bufferView": len(views) - 1}}
    doc = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
           "nodes": [{"mesh": 0, "rotation": [0, 0.3826834, 0, 0.9238795]}],
           "meshes": [{"name": name, "primitives": [prim]}],
           "materials": [{"name": "glass", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1]},
                          "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
                                         "KHR_materials_ior": {"ior": 1.5},
                                         "KHR_materials_volume": {"thicknessFactor": 1,
                                                                  "attenuationDistance": 0.5,
                                                                  "attenuationColor": [1, 0.5, 0.5]}}}],
           "extensionsUsed": ["KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_volume"],
           "accessors": accessors, "bufferViews": views,
           "buffers": [{"byteLength": len(buf), "uri": data_uri(buf)}]}
    if image is not None:
        doc["images"] = [{"uri": data_uri(image, "image/png")}]
        doc["textures"] = [{"source": 0}]
        doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0}
    if extra:
        extra(doc)
    return json.dumps(doc, indent=1).encode()


def glb(json_bytes, bin_bytes):
    json_bytes += b" " * (-len(json_bytes) % 4)
    bin_bytes += b"\0" * (-len(bin_bytes) % 4)
    body = struct.pack("<I4s", len(json_bytes), b"JSON") + json_bytes
    body += struct.pack("<I4s", len(bin_bytes), b"BIN\0") + bin_bytes
    return struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body


def main():
    tri = [(0, 0, 0), (1, 0, 0), (0, 1, 0)]
    quad = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]
    out("gltf", "triangle.gltf", gltf("tri", tri))
    out("gltf", "quad_indexed_textured.gltf", gltf("quad", quad, [0, 1, 2, 0, 2, 3], image=png_bytes("RGB", (2, 2))))
    out("gltf", "sparse.gltf", gltf("sparse", tri, sparse=True))
    out("gltf", "strip.gltf", gltf("strip", quad, [0, 1, 3, 2], mode=5))
    out("gltf", "fan.gltf", gltf("fan", quad, [0, 1, 2, 3], mode=6))

    def scene_extras(doc):
        doc["nodes"].append({"camera": 0, "translation": [0, 0, 3]})
        doc["nodes"].append({"extensions": {"KHR_lights_punctual": {"light": 0}}, "translation": [0, 2, 0],
                             "children": [0]})
        doc["scenes"][0]["nodes"] = [2, 1]
        doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.01, "aspectRatio": 1.5}}]
        doc["extensions"] = {"KHR_lights_punctual": {"lights": [{"type": "spot", "intensity": 100,
                                                                 "spot": {"outerConeAngle": 0.5}}]}}
        doc["extensionsUsed"].append("KHR_lights_punctual")
        doc["scenes"][0]["extras"] = {"iris_environment": [0.1, 0.2, 0.3]}
        doc["materials"][0]["extensions"]["KHR_materials_dispersion"] = {"dispersion": 20}
        doc["extensionsUsed"].append("KHR_materials_dispersion")
    out("gltf", "camera_light.gltf", gltf("gem", tri, extra=scene_extras))

    # The same triangle as a GLB with a BIN chunk.
    doc = json.loads(gltf("glb", quad, [0, 1, 2, 0, 2, 3]))
    buf = base64.b64decode(doc["buffers"][0]["uri"].split(",", 1)[1])
    del doc["buffers"][0]["uri"]
    out("gltf", "quad.glb", glb(json.dumps(doc).encode(), buf))

    mtl = b"""newmtl glass
Ni 1.5
illum 7
Kd 1 1 1
# iris_glass BK7
newmtl light
Ke 10 10 10
Kd 0.5 0.5 0.5
illum 2
newmtl tex
Kd 0.8 0.2 0.2
Ns 100
Ks 0.5 0.5 0.5
d 0.5
map_Kd -s 2 2 1 tex.png
"""
    obj = b"""# own seed
mtllib seed.mtl
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 1
o quad
usemtl glass
f 1/1/1 2/2/1 3/3/1 4/4/1
g side
usemtl light
f -5 -4 -1
s 1
usemtl tex
f 1//1 3//1 5//1
l 1 2
"""
    out("obj", "quad_mtl.objmtl", obj + SEP + mtl)
    out("obj", "plain.objmtl", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")

    for mode in ["RGBA", "RGB", "L", "P", "I;16"]:
        out("image", "seed_%s.png" % mode.replace(";", ""), png_bytes(mode, (5, 3)))
    from PIL import Image
    img = Image.new("RGB", (16, 8), (200, 100, 50))
    for kw, name in [({}, "baseline.jpg"), ({"progressive": True}, "progressive.jpg")]:
        buf = io.BytesIO()
        img.save(buf, "JPEG", **kw)
        out("image", name, buf.getvalue())
    # Radiance RGBE, flat (uncompressed) scanlines: 4 x 2 texels.
    hdr = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 4\n" + bytes([128, 64, 32, 129] * 8)
    out("image", "flat.hdr", hdr)
    # Run-length encoded scanlines (width 8 enables the new RLE format).
    line = bytes([2, 2, 0, 8]) + b"".join(bytes([128 + 8, v]) for v in (100, 50, 25, 130))
    out("image", "rle.hdr", b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 8\n" + line * 2)


if __name__ == "__main__":
    main()
