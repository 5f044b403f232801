"""scripts/figure2 end to end on a small Newton animation: it renders with fc off and on,
checks its own invariants (fc frames equal full frames; every changed pixel re-traced) and
writes the pair images and the per-frame plot."""
import csv
import importlib.machinery
import importlib.util
import math
import subprocess
import sys

import numpy as np
import OpenImageIO as oiio

from fcutil import POVRAY_FC, TOP, read_pixels

FIGURE2 = TOP / "scripts" / "figure2"


def read_grey(path):
    """A one-channel 8-bit image as a (height, width) uint8 array; fails on any other kind."""
    inp = oiio.ImageInput.open(str(path))
    assert inp is not None, oiio.geterror()
    try:
        spec = inp.spec()
        assert (spec.nchannels, spec.format) == (1, oiio.TypeDesc(oiio.UINT8)), \
            f"{path}: {spec.nchannels} channel(s) of {spec.format}"
        pixels = inp.read_image(0, 0, 0, 1, oiio.UINT8)
    finally:
        inp.close()
    assert pixels is not None, oiio.geterror()
    return np.asarray(pixels).reshape(spec.height, spec.width)


def load_figure2():
    """scripts/figure2 as a module (it has no .py suffix), for its helpers."""
    loader = importlib.machinery.SourceFileLoader("figure2", str(FIGURE2))
    module = importlib.util.module_from_spec(importlib.util.spec_from_loader("figure2", loader))
    loader.exec_module(module)
    return module


def test_write_grey_round_trip(tmp_path):
    # A mask with structure in both directions and at every edge, not square, so a
    # transposed, shifted or misread buffer cannot pass.
    mask = np.zeros((37, 53), dtype=bool)
    mask[0, :] = True
    mask[:, -1] = True
    mask[5:20, 7:30] = True
    mask[np.arange(37), np.arange(37)] = True
    for n in range(10):     # the garbage came from memory beyond the buffer: try several
        path = tmp_path / f"mask{n}.png"
        load_figure2().write_grey(path, mask)
        got = read_grey(path)
        assert got.shape == mask.shape
        assert set(np.unique(got)) <= {0, 255}, np.unique(got)
        wrong = int(np.count_nonzero((got == 255) != mask))
        assert wrong == 0, f"{path.name}: {wrong} of {mask.size} pixels wrong"


def test_figure2_newton_small(tmp_path):
    assert POVRAY_FC.is_file(), "build povray-fc first (make)"
    out = tmp_path / "figure2"
    done = subprocess.run([sys.executable, str(FIGURE2), "--scene", "newton", "--frames", "4",
                           "--size", "80x60", "--pair", "3", "--out", str(out)],
                          capture_output=True, text=True, timeout=300, stdin=subprocess.DEVNULL)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "invariants hold" in done.stdout

    for name in ("pair-03.png", "frames-03.png", "changed-03.png", "retraced-03.png",
                 "fractions.png", "fractions.csv", "off/stats.csv", "on/stats.csv"):
        assert (out / name).is_file(), name
    # The frames are the first four of newton.ini's 45 (same motion per frame).
    assert sorted(p.name for p in (out / "on").glob("*.tga")) == [f"newton0{n}.tga" for n in range(1, 5)]
    assert sorted(p.name for p in (out / "on" / "mask").glob("*.png")) == \
        [f"retraced000{n}.png" for n in range(1, 5)]

    plot = oiio.ImageInput.open(str(out / "fractions.png"))
    assert plot is not None, oiio.geterror()
    assert plot.spec().width > 100 and plot.spec().height > 100
    plot.close()
    assert read_pixels(out / "frames-03.png").shape == (60, 2 * 80 + 4, 3)

    # The pair's masks are exactly what they show: changed-03.png is white where the full
    # renders of frames 2 and 3 differ, retraced-03.png is povray-fc's own +YM mask of frame 3;
    # single-channel, only 0 and 255.
    want_changed = np.any(read_pixels(out / "off" / "newton02.tga") !=
                          read_pixels(out / "off" / "newton03.tga"), axis=2)
    want_retraced = read_pixels(out / "on" / "mask" / "retraced0003.png")[:, :, 0] > 127
    masks = {}
    for name, want in (("changed-03.png", want_changed), ("retraced-03.png", want_retraced)):
        got = read_grey(out / name)
        assert got.shape == (60, 80), name
        assert set(np.unique(got)) <= {0, 255}, (name, np.unique(got))
        wrong = int(np.count_nonzero((got == 255) != want))
        assert wrong == 0, f"{name}: {wrong} of {got.size} pixels wrong"
        masks[name] = got == 255

    # The invariants, checked again from the outputs.
    changed, retraced = masks["changed-03.png"], masks["retraced-03.png"]
    assert changed.any(), "the end marble moves between frames 2 and 3"
    assert not (changed & ~retraced).any()
    with open(out / "fractions.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert [int(r["frame"]) for r in rows] == [1, 2, 3, 4]
    assert float(rows[0]["retraced"]) == 1.0 and math.isnan(float(rows[0]["changed"]))
    for r in rows:
        assert int(r["fc_differing"]) == 0
        assert int(r["pixels"]) == 80 * 60
    for r in rows[1:]:
        assert 0 < float(r["changed"]) <= float(r["retraced"]) < 1, r
    for n in range(1, 5):
        a = read_pixels(out / "off" / f"newton0{n}.tga")
        b = read_pixels(out / "on" / f"newton0{n}.tga")
        assert np.array_equal(a, b), f"frame {n}"
