#!/usr/bin/env python3
"""Render one of Iris's scattering-media scenes with Mitsuba 3's `volpath`, for a wall-time
budget (run under the peers' Python, $PEERS_VENV/bin/python; see scripts/media-peers).

    python scripts/measure/mitsuba_media.py SCENE.glb --out X.exr --width W --height H \
        --time SECONDS [--seed S] [--threads 2] [--max-depth 64] [--variant llvm_ad_spectral]

The scene is built by the peers harness (../shared/peers/mitsuba_render.build: meshes, camera,
punctual lights, opaque and dielectric materials; or $IRIS_PEERS), then the media Iris reads
are added (docs/media.md), in Mitsuba's spectral units (nm, inverse scene units):

  material `extras.iris_medium: {"rayleigh": S}`  -> the shape's interior: a homogeneous
        medium, sigma_t(lambda) = S (550/lambda)^4 as an irregular spectrum (360-830 nm, 5-nm
        steps), albedo 1, Mitsuba's `rayleigh` phase function. A boundary of IOR 1 becomes a
        `null` BSDF (Iris's index-matched boundary: no bounce, shadow rays pass).
  scene `extras.iris_fog: "density=D[,g=G]"` or `"rayleigh=S"` -> a box of the scene's
        bounds (every mesh's vertices, 0.1 mm larger on each side so the floor does not
        coincide with its face) with a `null` BSDF and the fog inside; every other shape gets
        the fog as its exterior medium, the sensor too when the camera is inside the box.
  scene `extras.iris_environment: L` (a number) -> a `constant` emitter of radiance L.

Anything else a medium could say (an absorbing attenuation with scattering, a fog colour,
KHR_materials_volume_scatter) is refused with a message: this script covers the comparison's
scenes, not glTF media in general. Wall-time loop as the harness's mitsuba_time.py: the JIT
warm-up excluded, chunks of samples with successive seeds averaged. Prints one JSON line
{"peer": "mitsuba", "integrator": "volpath", "spp", "render_s", ...}.
"""
import argparse
import json
import math
import os
import shutil
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
PEERS = os.environ.get("IRIS_PEERS", os.path.join(HERE, "..", "..", "..", "shared", "peers"))
sys.path.insert(0, os.path.abspath(PEERS))
sys.path.insert(0, HERE)
import gltf_scene  # noqa: E402  (the peers harness)
import mitsuba_render  # noqa: E402
import glb  # noqa: E402

FOG_MARGIN = 1e-4  # metres added to each side of the fog's box


def rayleigh_spectrum(at_550):
    """sigma_s(lambda) = at_550 (550/lambda)^4 as a Mitsuba irregular spectrum."""
    nm = list(range(360, 831, 5))
    vals = [at_550 * (550.0 / x) ** 4 for x in nm]
    return {"type": "irregular", "wavelengths": ", ".join(map(str, nm)),
            "values": ", ".join(f"{v:.6g}" for v in vals)}


def material_medium(m, where):
    """The Mitsuba medium of a glTF material dict, or None when it holds no medium."""
    medium = ((m.get("extras") or {}).get("iris_medium"))
    ext = m.get("extensions", {})
    if "KHR_materials_volume_scatter" in ext or "KHR_materials_scatter" in ext:
        raise SystemExit(f"{where}: KHR_materials_volume_scatter is not carried to Mitsuba by this script")
    if medium is None:
        return None
    if set(medium) != {"rayleigh"}:
        raise SystemExit(f"{where}: iris_medium {medium}: only {{\"rayleigh\": S}} is carried to Mitsuba")
    if math.isfinite(ext.get("KHR_materials_volume", {}).get("attenuationDistance", math.inf)):
        raise SystemExit(f"{where}: absorption on top of Rayleigh scattering is not carried to Mitsuba")
    return {"type": "homogeneous", "sigma_t": rayleigh_spectrum(float(medium["rayleigh"])),
            "albedo": 1.0, "phase": {"type": "rayleigh"}}


def fog_medium(spec, where):
    """The Mitsuba medium of an iris_fog text (the subset this script carries)."""
    kv = {}
    for part in [p.strip() for p in spec.split(",") if p.strip()]:
        key, _, value = part.partition("=") if "=" in part else ("density", "", part)
        kv[key.strip()] = float(value)
    if set(kv) - {"density", "rayleigh", "g"}:
        raise SystemExit(f"{where}: iris_fog {spec!r}: only density, rayleigh and g are carried to Mitsuba")
    if "rayleigh" in kv:
        return {"type": "homogeneous", "sigma_t": rayleigh_spectrum(kv["rayleigh"]), "albedo": 1.0,
                "phase": {"type": "rayleigh"}}
    g = kv.get("g", 0.0)
    phase = {"type": "hg", "g": g} if g != 0.0 else {"type": "isotropic"}
    return {"type": "homogeneous", "sigma_t": kv["density"], "albedo": 1.0, "phase": phase}


def add_media(mi, d, sc, doc, path):
    """Put the scene's media into the Mitsuba scene dictionary `d` built by the harness."""
    shapes = {i: mesh for i, mesh in enumerate(sc.meshes)}
    for i, m in enumerate(doc.get("materials", [])):
        where = f"{path}: material {i} ({m.get('name', '?')})"
        med = material_medium(m, where)
        if med is None:
            continue
        d[f"medium{i}"] = med | {"id": f"medium{i}"}
        if sc.materials[i].ior == 1.0:
            d[f"mat{i}"] = {"type": "null", "id": f"mat{i}"}
        for k, mesh in shapes.items():
            if mesh.material == i:
                d[f"shape{k}"]["interior"] = {"type": "ref", "id": f"medium{i}"}
    extras = ((doc.get("scenes") or [{}])[doc.get("scene", 0)].get("extras") or {})
    env = extras.get("iris_environment")
    if isinstance(env, (int, float)):
        d["environment"] = {"type": "constant", "radiance": {"type": "rgb", "value": [float(env)] * 3}}
    elif env is not None:
        raise SystemExit(f"{path}: scene extras iris_environment {env!r}: only a number is carried to Mitsuba")
    if "iris_fog" not in extras:
        return
    d["fog"] = fog_medium(extras["iris_fog"], f"{path}: scene extras") | {"id": "fog"}
    pts = np.concatenate([mesh.positions for mesh in sc.meshes])
    lo, hi = pts.min(0) - FOG_MARGIN, pts.max(0) + FOG_MARGIN
    for k in shapes:
        d[f"shape{k}"]["exterior"] = {"type": "ref", "id": "fog"}
    T = mi.ScalarTransform4f
    d["fog_box"] = {"type": "cube", "bsdf": {"type": "null"}, "interior": {"type": "ref", "id": "fog"},
                    "to_world": T().translate(((lo + hi) / 2).tolist()).scale(((hi - lo) / 2).tolist())}
    eye = sc.camera.position
    if np.all(eye > lo) and np.all(eye < hi):
        d["sensor"]["medium"] = {"type": "ref", "id": "fog"}


def render_for(mi, dr, scene, budget, seed):
    """(mean image, spp, seconds): chunks with successive seeds until the budget is spent."""
    acc, done, k, chunk = None, 0, 0, 1
    t0 = time.time()
    while True:
        tc = time.time()
        img = np.array(mi.render(scene, spp=chunk, seed=seed + k), dtype=np.float64)[..., :3]
        dt = time.time() - tc
        acc = img * chunk if acc is None else acc + img * chunk
        done, k = done + chunk, k + 1
        left = budget - (time.time() - t0)
        rate = chunk / max(dt, 1e-6)
        if left <= 0 or left < 0.5 / rate:
            break
        chunk = max(1, int(min(rate * budget / 10, 256, rate * left)))
    return acc / done, done, time.time() - t0


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene")
    ap.add_argument("--out", required=True)
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--height", type=int, default=180)
    ap.add_argument("--time", type=float, required=True)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--max-depth", type=int, default=64)
    ap.add_argument("--variant", default="llvm_ad_spectral")
    a = ap.parse_args(argv)
    # what mitsuba_render.build reads from its arguments
    a.integrator, a.spp, a.point_lights = "volpath", 1, True
    mitsuba_render.ensure_llvm()
    import drjit as dr
    import mitsuba as mi
    mi.set_variant(a.variant)
    mitsuba_render.mi, mitsuba_render.dr = mi, dr
    dr.set_thread_count(a.threads)
    sc = gltf_scene.load(a.scene)
    doc, _ = glb.read(a.scene)
    tmp = tempfile.mkdtemp(prefix="mitsuba_media_")
    try:
        d = mitsuba_render.build(mi, sc, a, tmp, use_disp=False)
        add_media(mi, d, sc, doc, a.scene)
        scene = mi.load_dict(d)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    tw = time.time()
    dr.eval(mi.render(scene, spp=1, seed=a.seed + 99991))
    t_jit = time.time() - tw
    rgb, spp, secs = render_for(mi, dr, scene, a.time, a.seed)
    rgb = rgb.astype(np.float32)
    gltf_scene.write_outputs(rgb, os.path.abspath(a.out))
    print(f"[mitsuba] volpath {a.variant} {a.width}x{a.height}: {spp} spp, render {secs:.2f} s "
          f"(JIT {t_jit:.2f} s excluded), mean {rgb.reshape(-1, 3).mean(0).round(5).tolist()}")
    print(json.dumps({"peer": "mitsuba", "version": mi.__version__, "variant": a.variant, "integrator": "volpath",
                      "scene": a.scene, "spp": spp, "render_s": round(secs, 3), "out": a.out}))


if __name__ == "__main__":
    main(sys.argv[1:])
