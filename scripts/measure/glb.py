"""Small edits of binary glTF (.glb) files for the peer comparison, standard library only.

A .glb is a 12-byte header, a JSON chunk and an optional BIN chunk (glTF 2.0 §4.4); the edits
here touch the JSON only, so the BIN chunk is copied byte for byte. Units follow the peers
harness (../shared/peers/README.md): metres, Y up, a camera looks down its local −Z, a
KHR_lights_punctual point light's intensity is read as W/sr by the peers and as candela by
Iris (factor 1.000 between them, measured there)."""
import json
import math
import struct

GLB_MAGIC = 0x46546C67
JSON_CHUNK = 0x4E4F534A


def read(path):
    """(json dict, bytes after the JSON chunk) of a .glb file."""
    data = open(path, "rb").read()
    magic, _version, _total = struct.unpack_from("<III", data, 0)
    if magic != GLB_MAGIC:
        raise SystemExit(f"{path}: not a binary glTF (.glb) file")
    jlen, jtype = struct.unpack_from("<II", data, 12)
    if jtype != JSON_CHUNK:
        raise SystemExit(f"{path}: first chunk is not JSON")
    return json.loads(data[20:20 + jlen]), data[20 + jlen:]


def encode(doc, rest):
    """The bytes of a .glb holding `doc` and the chunks `rest` (as returned by read)."""
    js = json.dumps(doc, separators=(",", ":"), sort_keys=True).encode()
    js += b" " * ((4 - len(js) % 4) % 4)
    header = struct.pack("<III", GLB_MAGIC, 2, 20 + len(js) + len(rest))
    return header + struct.pack("<II", len(js), JSON_CHUNK) + js + rest


def write_if_changed(path, data):
    """Write `data` to `path` unless it already holds it; returns True when written."""
    try:
        if open(path, "rb").read() == data:
            return False
    except OSError:
        pass
    with open(path, "wb") as f:
        f.write(data)
    return True


def look_at_quaternion(eye, target, up=(0.0, 1.0, 0.0)):
    """Rotation (x, y, z, w) turning a glTF camera (looking down −Z, +Y up) towards target."""
    f = _normalise([t - e for t, e in zip(target, eye)])
    r = _normalise(_cross(f, up))
    u = _cross(r, f)
    # columns of the rotation matrix: r, u, −f
    m = [[r[0], u[0], -f[0]], [r[1], u[1], -f[1]], [r[2], u[2], -f[2]]]
    tr = m[0][0] + m[1][1] + m[2][2]
    if tr > 0:  # Shepperd's method, the branch for a positive trace
        s = math.sqrt(tr + 1.0) * 2
        return [(m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, 0.25 * s]
    i = max(range(3), key=lambda k: m[k][k])
    j, k = (i + 1) % 3, (i + 2) % 3
    s = math.sqrt(1.0 + m[i][i] - m[j][j] - m[k][k]) * 2
    q = [0.0, 0.0, 0.0, 0.0]
    q[i] = 0.25 * s
    q[j] = (m[j][i] + m[i][j]) / s
    q[k] = (m[k][i] + m[i][k]) / s
    q[3] = (m[k][j] - m[j][k]) / s
    return q


def add_camera(doc, eye, target, yfov_deg, name="Camera"):
    """Append a perspective camera node at `eye` looking at `target` to the default scene."""
    doc.setdefault("cameras", []).append(
        {"name": name, "type": "perspective",
         "perspective": {"aspectRatio": 1.0, "yfov": math.radians(yfov_deg), "znear": 0.01, "zfar": 100.0}})
    _add_node(doc, {"name": name, "camera": len(doc["cameras"]) - 1, "translation": list(eye),
                    "rotation": look_at_quaternion(eye, target)})


def add_point_light(doc, position, intensity, name="Light"):
    """Append a KHR_lights_punctual point light (white, radius 0) at `position`."""
    lights = doc.setdefault("extensions", {}).setdefault("KHR_lights_punctual", {}).setdefault("lights", [])
    lights.append({"name": name, "type": "point", "color": [1.0, 1.0, 1.0], "intensity": float(intensity)})
    _use_extension(doc, "KHR_lights_punctual")
    _add_node(doc, {"name": name, "translation": list(position),
                    "extensions": {"KHR_lights_punctual": {"light": len(lights) - 1}}})


def lambertian_opaque(doc):
    """make_variant.py --spec0: opaque materials get KHR_materials_specular specularFactor 0 (a
    pure Lambertian base in Iris, as the peers render it). Returns the names changed."""
    changed = []
    for m in doc.get("materials", []):
        ext = m.setdefault("extensions", {})
        if "KHR_materials_transmission" in ext:
            continue
        ext["KHR_materials_specular"] = {"specularFactor": 0.0}
        changed.append(m.get("name", "?"))
    _use_extension(doc, "KHR_materials_specular")
    return changed


def drop_textures(doc, base_color=(0.8, 0.8, 0.8)):
    """Remove every texture reference from the materials (the peers' reader ignores textures);
    a material that had a base-colour texture gets `base_color`. Returns the names changed."""
    changed = []
    for m in doc.get("materials", []):
        pbr = m.get("pbrMetallicRoughness", {})
        had = False
        if pbr.pop("baseColorTexture", None) is not None:
            pbr["baseColorFactor"] = list(base_color) + [1.0]
            had = True
        for key in ("metallicRoughnessTexture",):
            had |= pbr.pop(key, None) is not None
        for key in ("normalTexture", "occlusionTexture", "emissiveTexture"):
            had |= m.pop(key, None) is not None
        for ext in m.get("extensions", {}).values():
            for key in [k for k in ext if k.endswith("Texture")]:
                ext.pop(key)
                had = True
        if had:
            changed.append(m.get("name", "?"))
    return changed


def smooth_transmissive(doc):
    """Roughness 0 on every transmissive material (the peers' dispersive BSDFs are smooth).
    Returns the names changed."""
    changed = []
    for m in doc.get("materials", []):
        if "KHR_materials_transmission" in m.get("extensions", {}):
            m.setdefault("pbrMetallicRoughness", {})["roughnessFactor"] = 0.0
            changed.append(m.get("name", "?"))
    return changed


def _add_node(doc, node):
    doc.setdefault("nodes", []).append(node)
    scene = doc.get("scene", 0)
    doc["scenes"][scene].setdefault("nodes", []).append(len(doc["nodes"]) - 1)


def _use_extension(doc, name):
    used = doc.setdefault("extensionsUsed", [])
    if name not in used:
        used.append(name)


def _cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def _normalise(v):
    n = math.sqrt(sum(c * c for c in v))
    return [c / n for c in v]
