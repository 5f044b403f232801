"""povray-fc (fc off) and Debian's packaged povray agree on every pixel.

Both are POV-Ray 3.7.0.10 built from the same Debian source with the same flags;
our patches must not change a single pixel when frame coherence is off.
"""
import os

import pytest

from fcutil import DEBIAN_POVRAY, POVRAY_FC, SCENES, assert_same_pixels, render

EXAMPLES = "/usr/share/doc/povray/examples"

CASES = {
    # name: (scene, options)
    "demo-frame-7": (SCENES / "demo" / "demo.pov", ["+W320", "+H240", "+K0.25"]),
    "biscuit-aa2": (f"{EXAMPLES}/advanced/biscuit.pov", ["+W160", "+H120", "+A0.3", "+AM2"]),
    "woodbox-aa1": (f"{EXAMPLES}/advanced/woodbox.pov", ["+W160", "+H120", "+A0.3", "+AM1"]),
    "wineglass": (f"{EXAMPLES}/advanced/wineglass.pov", ["+W160", "+H120"]),
    "glasschess-aa2-jitter": (f"{EXAMPLES}/advanced/glasschess/glasschess.pov",
                              ["+W160", "+H120", "+A0.3", "+AM2", "+J"]),
    # Radiosity is order dependent across threads; with one thread it is deterministic.
    "object-pattern-radiosity-wt1": (f"{EXAMPLES}/advanced/object_pattern.pov",
                                     ["+W160", "+H120", "+WT1"]),
    # Radiosity's sample directions are made on first use (patch 0420), not before each block.
    "cornell-radiosity-wt1": (f"{EXAMPLES}/radiosity/cornell.pov", ["+W120", "+H90", "+WT1"]),
}


def render_case(binary, name, out, env=None):
    scene, options = CASES[name]
    done = render(binary, scene, out, *options, env=env)
    assert done.returncode == 0, f"{binary}: {done.stderr[-2000:]}"
    return out


@pytest.mark.parametrize("name", sorted(CASES))
def test_same_pixels_as_debian_povray_with_stock_shadow_cache(name, tmp_path):
    # Patch 0003 makes the shadow cache exact, which can move a few pixels by one level
    # (see README); with the stock cache test every other patch must change nothing.
    stock = dict(os.environ, POVRAYFC_STOCK_SHADOW_CACHE="1")
    assert_same_pixels(render_case(DEBIAN_POVRAY, name, tmp_path / "debian.tga"),
                       render_case(POVRAY_FC, name, tmp_path / "povray-fc.tga", env=stock))


@pytest.mark.parametrize("name", ["demo-frame-7", "biscuit-aa2", "woodbox-aa1"])
def test_pixels_do_not_depend_on_thread_count(name, tmp_path):
    # With the exact shadow cache a pixel no longer depends on the pixel a thread traced
    # before it, so one thread and two give the same picture.
    scene, options = CASES[name]
    outputs = []
    for threads in (1, 2):
        out = tmp_path / f"wt{threads}.tga"
        done = render(POVRAY_FC, scene, out, *options, threads=threads)
        assert done.returncode == 0, done.stderr[-2000:]
        outputs.append(out)
    assert_same_pixels(*outputs)
