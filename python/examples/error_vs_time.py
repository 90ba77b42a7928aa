#!/usr/bin/env python3
"""Error against time for a few methods, from Python: each method renders the scene for the
same time; the progress callback records the half-buffer relative error estimate at every
checkpoint (1, 2, 4, … samples or passes); matplotlib plots them log-log.

    python python/examples/error_vs_time.py [SCENE] [--time 10] [--out error_vs_time.png]

Needs `pip install .` (the module) and matplotlib. The same figures come from
`iris converge` on the command line; this shows the module's progress callback.
"""
import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import iris  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]


def curve(scene, method, seconds, size):
    points = []

    def progress(p):
        if p["checkpoint"] and p["estimate"] is not None:
            points.append((p["seconds"], p["estimate"]))
        return True

    s = iris.render_summary(scene, progress=progress, method=method, time=seconds, size=size,
                            spp=1_000_000, passes=1_000_000)
    return points, s


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene", nargs="?", default=str(ROOT / "assets" / "scenes" / "ruby.glb"))
    ap.add_argument("--time", type=float, default=10.0, help="seconds per method")
    ap.add_argument("--methods", default="path,hybrid,sppm")
    ap.add_argument("--size", default="320x180")
    ap.add_argument("--out", default="error_vs_time.png")
    a = ap.parse_args()
    w, h = (int(v) for v in a.size.split("x"))
    fig, ax = plt.subplots(figsize=(6, 4))
    for method in a.methods.split(","):
        points, s = curve(a.scene, method, a.time, (w, h))
        if points:
            t, e = zip(*points)
            ax.loglog(t, e, "o-", label=f"{method} ({s['units']} {'passes' if method == 'sppm' else 'spp'})")
        print(f"{method}: {len(points)} checkpoints, last estimate {points[-1][1] if points else None}")
    ax.set_xlabel("render time (s)")
    ax.set_ylabel("estimated relative error")
    ax.set_title(pathlib.Path(a.scene).name)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(a.out, dpi=120)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
