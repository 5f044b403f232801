"""scripts/figure2 end to end on a small Newton animation: it renders with fc off and on,
checks its own invariants (fc frames equal full frames; every changed pixel re-traced) and
writes the pair images and the per-frame plot."""
import csv
import math
import subprocess
import sys

import numpy as np
import OpenImageIO as oiio

from fcutil import POVRAY_FC, TOP, read_pixels

FIGURE2 = TOP / "scripts" / "figure2"


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

    # The invariants, checked again from the outputs.
    changed = read_pixels(out / "changed-03.png")[:, :, 0] > 127
    retraced = read_pixels(out / "retraced-03.png")[:, :, 0] > 127
    assert changed.shape == (60, 80)
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
