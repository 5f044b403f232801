"""povray-fc (fc off) and Debian's packaged povray agree on every pixel.

Both are POV-Ray 3.7.0.10 built from the same Debian source with the same flags;
our patches must not change a single pixel when frame coherence is off.
"""
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
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_same_pixels_as_debian_povray(name, tmp_path):
    scene, options = CASES[name]
    outputs = []
    for binary in (DEBIAN_POVRAY, POVRAY_FC):
        out = tmp_path / f"{binary.name}.tga"
        done = render(binary, scene, out, *options)
        assert done.returncode == 0, f"{binary}: {done.stderr[-2000:]}"
        outputs.append(out)
    assert_same_pixels(*outputs)
