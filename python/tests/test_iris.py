"""The Python module against the command line (pytest; python/README: how to run).

The `iris` binary to compare with is $IRIS_BIN, else target/release/iris of this checkout
(`cargo build --release` first; scripts/run test-python does both)."""
import os
import pathlib
import subprocess

import numpy as np
import pytest

import iris

ROOT = pathlib.Path(__file__).resolve().parents[2]
RUBY = str(ROOT / "assets" / "scenes" / "ruby.glb")
FLAGS = dict(size=(64, 40), spp=4, seed=3, method="path")


def iris_bin():
    path = os.environ.get("IRIS_BIN", str(ROOT / "target" / "release" / "iris"))
    assert os.path.isfile(path), f"no iris binary at {path}: cargo build --release, or set IRIS_BIN"
    return path


def cli_render(tmp_path, *flags):
    out = tmp_path / "cli.exr"
    subprocess.run([iris_bin(), "render", RUBY, *flags, "-o", str(out), "--quiet"], check=True, cwd=ROOT)
    return iris.read_exr(str(out))


def test_image_equals_the_command_lines_exr_bit_for_bit(tmp_path):
    image = iris.render(RUBY, **FLAGS)
    assert image.dtype == np.float32 and image.shape == (40, 64, 3)
    cli = cli_render(tmp_path, "--size", "64x40", "--spp", "4", "--seed", "3", "--method", "path")
    assert np.array_equal(image.view(np.uint32), cli.view(np.uint32))
    # Flags named like the command line's, with the same effect: another stone, another image.
    ruby_as_sapphire = iris.render(RUBY, stone="sapphire", **FLAGS)
    assert not np.array_equal(ruby_as_sapphire, image)
    cli_sapphire = cli_render(tmp_path, "--size", "64x40", "--spp", "4", "--seed", "3", "--method", "path",
                              "--stone", "sapphire")
    assert np.array_equal(ruby_as_sapphire, cli_sapphire)


def test_a_bad_flag_value_raises_value_error_naming_the_flag():
    with pytest.raises(ValueError, match="--spp"):
        iris.render(RUBY, spp=0)
    with pytest.raises(ValueError, match="--stone"):
        iris.render(RUBY, stone="unobtainium", spp=1)
    with pytest.raises(ValueError, match="--colour"):
        iris.render(RUBY, colour="red")
    with pytest.raises(ValueError, match="--camera-look-at"):
        iris.render(RUBY, camera_look_at="0,0,1:0,0,1:30", spp=1)


def test_a_bad_file_raises_iris_error_naming_it(tmp_path):
    bad = tmp_path / "broken.glb"
    bad.write_bytes(b"glTF not really")
    with pytest.raises(iris.IrisError, match="broken.glb"):
        iris.render(str(bad), spp=1)
    with pytest.raises(iris.IrisError, match="missing.glb"):
        iris.info(str(tmp_path / "missing.glb"))


def test_progress_sees_checkpoints_and_can_stop_the_render():
    seen = []

    def progress(p):
        seen.append(p)
        return p["units"] < 4

    s = iris.render_summary(RUBY, progress=progress, size=(48, 32), spp=64, seed=1, method="path")
    assert [p["units"] for p in seen] == [1, 2, 4]
    assert s["end"] == "progress" and s["units"] == 4
    assert seen[-1]["estimate"] is not None and seen[0]["seconds"] >= 0
    # An exception in the callback stops the render and reaches the caller.
    def fails(p):
        raise RuntimeError("stop here")
    with pytest.raises(RuntimeError, match="stop here"):
        iris.render(RUBY, progress=fails, size=(16, 16), spp=8)


def test_plan_and_notes_are_python_objects():
    p = iris.plan(RUBY, spectral="off", size=(32, 32))
    names = [s["name"] for s in p["stages"]]
    assert names[0] == "transport" and "photons" in names
    transport = p["stages"][0]
    assert transport["reason"].startswith("RGB") and p["spectral"] is False
    assert p["size"] == (32, 32)
    s = iris.render_summary(RUBY, size=(32, 20), spp=2, method="path")
    assert s["method"] == "path" and s["end"] == "samples" and s["units"] == 2
    assert any("own light" in n for n in s["notes"]), s["notes"]


def test_info_describes_the_file():
    d = iris.info(RUBY)
    assert sum(m["triangles"] for m in d["meshes"]) > 0
    ruby = [m for m in d["materials"] if "Ruby" in m["name"]]
    assert ruby and abs(ruby[0]["ior"] - 1.77) < 1e-3 and ruby[0]["transmission"] == 1.0
    assert d["text"].startswith(RUBY) or "meshes" in d["text"]


def test_output_writes_the_file_as_the_command_does(tmp_path):
    out = tmp_path / "x.exr"
    image = iris.render(RUBY, output=str(out), **FLAGS)
    assert np.array_equal(iris.read_exr(str(out)), image)
