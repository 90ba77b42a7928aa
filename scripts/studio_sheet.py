#!/usr/bin/env python3
"""The side-by-side renders behind the default gem studio (BENCHMARKS.md, "Default studio
for gems"): the four bare diamond cuts (rows) under soft, jeweller and bright (columns),
the same render settings as scripts/studio_choice.sh (288x216, path tracer, 256 spp, seed 2;
the PNG denoised, as a preview is).

usage: scripts/studio_sheet.py IRIS_BIN OUTDIR SHEET.png   (needs Pillow)
Renders what is missing in OUTDIR (the .glb cuts and the *_4N.png images), then writes the
labelled sheet.
"""
import os
import subprocess
import sys

from PIL import Image, ImageDraw

CUTS = ["round", "emerald", "oval", "pear"]
PRESETS = ["soft", "jeweller", "bright"]


def main():
    iris, out, sheet = sys.argv[1], sys.argv[2], sys.argv[3]
    os.makedirs(out, exist_ok=True)
    for cut in CUTS:
        glb = os.path.join(out, f"{cut}.glb")
        if not os.path.exists(glb):
            subprocess.run([iris, "gem", "--cut", cut, "--stone", "diamond", "--bare", "-o", glb],
                           check=True, stdout=subprocess.DEVNULL)
        for st in PRESETS:
            png = os.path.join(out, f"{cut}_{st}_4N.png")
            if not os.path.exists(png):
                subprocess.run([iris, "render", glb, "-o", png, "--size", "288x216", "--method",
                                "path", "--spp", "256", "--seed", "2", "--studio", st, "-q"],
                               check=True, stdout=subprocess.DEVNULL)
    w, h, top, left = 288, 216, 22, 70
    img = Image.new("RGB", (left + w * len(PRESETS), top + h * len(CUTS)), "white")
    d = ImageDraw.Draw(img)
    for j, st in enumerate(PRESETS):
        d.text((left + j * w + w // 2 - 20, 5), st, fill="black")
    for i, cut in enumerate(CUTS):
        d.text((8, top + i * h + h // 2), cut, fill="black")
        for j, st in enumerate(PRESETS):
            tile = Image.open(os.path.join(out, f"{cut}_{st}_4N.png")).convert("RGB")
            img.paste(tile.resize((w, h)), (left + j * w, top + i * h))
    img.save(sheet)


if __name__ == "__main__":
    main()
