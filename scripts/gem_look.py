"""Gem look measures per (cut, studio): fire, brilliance, contrast, scintillation.
Inputs per case: NAME_N.exr, NAME_4N.exr (linear, same camera), NAME_mask.png (alpha = stone
coverage, --ground off --background transparent), NAME_4N.png (what the viewer sees)."""
import sys, json, numpy as np, OpenEXR
from PIL import Image

def exr(path):
    f = OpenEXR.File(path)
    ch = f.channels()
    if 'RGB' in ch:
        return np.asarray(ch['RGB'].pixels, dtype=np.float64)
    return np.stack([np.asarray(ch[c].pixels, dtype=np.float64) for c in 'RGB'], -1)

def lum(a):
    return 0.2126 * a[..., 0] + 0.7152 * a[..., 1] + 0.0722 * a[..., 2]

def chroma_median(img, m):
    Y = lum(img)[m]
    r, g, b = img[..., 0][m], img[..., 1][m], img[..., 2][m]
    c = np.sqrt(((r - g) ** 2 + (g - b) ** 2 + (b - r) ** 2) / 2)
    y0 = 0.1 * np.median(Y)
    return float(np.median(np.minimum(c / np.maximum(Y, y0), 2.0)))

def srgb_to_lin(v):
    v = v / 255.0
    return np.where(v <= 0.04045, v / 12.92, ((v + 0.055) / 1.055) ** 2.4)

name = sys.argv[1]
a = exr(f"{name}_N.exr"); b = exr(f"{name}_4N.exr")
alpha = np.asarray(Image.open(f"{name}_mask.png").convert('RGBA'))[..., 3] / 255.0
m = alpha > 0.99
bg = alpha < 0.01
mN, m4 = chroma_median(a, m), chroma_median(b, m)
fire = float(np.sqrt(max((4 * m4 ** 2 - mN ** 2) / 3, 0)))
disp = np.asarray(Image.open(f"{name}_4N.png").convert('RGB')).astype(np.float64)
dl = lum(srgb_to_lin(disp))  # displayed relative luminance, 0..1
stone, back = dl[m], dl[bg]
res = dict(case=name, stone_px=int(m.sum()), fire=fire, chroma_N=mN, chroma_4N=m4,
           brilliance=float(stone.mean()), contrast=float(stone.mean() / max(back.mean(), 1e-3)),
           scintillation=float(stone.std() / max(stone.mean(), 1e-6)),
           bright_share=float((stone > 0.5).mean()))
print(json.dumps(res))
