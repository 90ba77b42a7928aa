#!/usr/bin/env python3
"""Error of directly seen floor caustics against a reference, by region.

  $V scripts/caustic-peak.py SCENE.glb REF.exr [--ref-shift 1] IMG.exr... [--peak 20]

SCENE is the peers' caustic sphere (or a variant): one transmissive mesh (the sphere) on
a floor mesh, one point light, a glTF camera. Pixels (Iris's raster convention: (0,0) top
left, ray through the pixel centre, `Camera::generate_ray`) are classed geometrically:
- floor: the centre ray hits the floor's top plane inside its bounds and passes the
  glass sphere's bounding sphere by more than 1.5 pixel footprints (outside the
  silhouette, so only light seen directly on the floor counts);
- caustic: floor pixels whose reference exceeds 1.2 x the unshadowed direct light
  I cos(theta) / r^2 * albedo / pi (analytic, the point light and the floor's albedo);
- peak: the PEAK brightest caustic pixels of the reference.
Printed per image: RMSE/mean on the floor and on the caustic, the share of the floor's
squared error in its 100 worst pixels, and sum(img)/sum(ref) over the peak pixels with the
spread of the per-pixel ratios. `--ref-shift 1` moves the reference up one row (LuxCore's
images sit one pixel lower, peers README); images named lx* are moved up `--lx-shift` rows
(default 1). Luminance-free: all three channels averaged.
Needs the peers' venv (numpy, OpenEXR via gltf_scene).
"""
import argparse
import math
import os
import sys

import numpy as np

PEERS = os.environ.get("PEERS_DIR", "/work/shared/peers")
sys.path.insert(0, PEERS)
import gltf_scene  # noqa: E402


def classify(sc, w, h):
    glass = [m for m in sc.meshes if sc.materials[m.material].is_glass]
    floor = [m for m in sc.meshes if not sc.materials[m.material].is_glass]
    g = np.concatenate([m.positions for m in glass]).astype(np.float64)
    lo, hi = g.min(0), g.max(0)
    c = 0.5 * (lo + hi)
    R = np.linalg.norm(g - c, axis=1).max()
    f = np.concatenate([m.positions for m in floor]).astype(np.float64)
    flo, fhi = f.min(0), f.max(0)
    fy = fhi[1]
    cam = sc.camera
    fw = np.asarray(cam.forward, np.float64)
    fw /= np.linalg.norm(fw)
    right = np.cross(fw, np.asarray(cam.up, np.float64))
    right /= np.linalg.norm(right)
    up = np.cross(right, fw)
    hh = math.tan(cam.yfov / 2)
    hw = hh * w / h
    px, py = np.meshgrid(np.arange(w) + 0.5, np.arange(h) + 0.5)
    nx = (2 * px / w - 1) * hw
    ny = (1 - 2 * py / h) * hh
    d = nx[..., None] * right + ny[..., None] * up + fw
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    o = np.asarray(cam.position, np.float64)
    # distance of the ray to the sphere centre, and the footprint there
    t_c = np.maximum((c - o) @ np.moveaxis(d, -1, 0).reshape(3, -1), 0).reshape(h, w)
    closest = o + d * t_c[..., None]
    dist = np.linalg.norm(closest - c, axis=-1)
    foot = 2 * hh / h * np.linalg.norm(c - o)
    outside = dist > R + 1.5 * foot
    t = (fy - o[1]) / d[..., 1]
    p = o + d * t[..., None]
    on_floor = (t > 0) & (p[..., 0] >= flo[0]) & (p[..., 0] <= fhi[0]) & (p[..., 2] >= flo[2]) & (p[..., 2] <= fhi[2])
    floor_mask = on_floor & outside
    L = sc.lights[0]
    albedo = np.mean(sc.materials[floor[0].material].base_color[:3])
    v = np.asarray(L.position, np.float64) - p
    r2 = np.sum(v * v, axis=-1)
    cos = np.clip(v[..., 1] / np.sqrt(r2), 0, None)
    direct = L.intensity * np.mean(L.color) * cos / r2 * albedo / math.pi
    return floor_mask, direct


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene")
    ap.add_argument("ref")
    ap.add_argument("imgs", nargs="+")
    ap.add_argument("--ref-shift", type=int, default=0, help="rows to move the reference up")
    ap.add_argument("--lx-shift", type=int, default=1,
                    help="rows to move images named lx* (LuxCore's) up")
    ap.add_argument("--peak", type=int, default=20)
    a = ap.parse_args()
    r = gltf_scene.read_exr(a.ref)[..., :3].mean(-1).astype(np.float64)
    if a.ref_shift:
        r = np.concatenate([r[a.ref_shift:], np.repeat(r[-1:], a.ref_shift, 0)])
    h, w = r.shape
    sc = gltf_scene.load(a.scene)
    floor, direct = classify(sc, w, h)
    caustic = floor & (r > 1.2 * direct)
    order = np.argsort(np.where(caustic, r, -np.inf).ravel())[::-1][: a.peak]
    peak = np.zeros(h * w, bool)
    peak[order] = True
    peak = peak.reshape(h, w) & caustic
    print(f"floor {floor.sum()} px, caustic {caustic.sum()} px (ref mean {r[caustic].mean():.4g}), "
          f"peak {peak.sum()} px (ref mean {r[peak].mean():.4g}, max {r.max():.4g})")
    for path in a.imgs:
        x = gltf_scene.read_exr(path)[..., :3].mean(-1).astype(np.float64)
        if os.path.basename(path).startswith("lx") and a.lx_shift:
            x = np.concatenate([x[a.lx_shift:], np.repeat(x[-1:], a.lx_shift, 0)])
        e2 = (x - r) ** 2
        fl = np.sqrt(e2[floor].mean()) / r[floor].mean()
        ca = np.sqrt(e2[caustic].mean()) / r[caustic].mean()
        worst = np.sort(e2[floor])[::-1]
        share = worst[:100].sum() / max(worst.sum(), 1e-300)
        ratio = x[peak] / r[peak]
        print(f"{os.path.basename(path):44s} floor {fl:.4f} caustic {ca:.4f} worst100 {share:.2f} "
              f"floor-mean {x[floor].mean() / r[floor].mean():.4f} "
              f"peak sum {x[peak].sum() / r[peak].sum():.4f} ratio sd {ratio.std():.4f} "
              f"[{ratio.min():.3f}, {ratio.max():.3f}]")


if __name__ == "__main__":
    main()
