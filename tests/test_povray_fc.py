"""The povray-fc binary: it names itself, renders our scenes, and fails loudly on bad input."""
import math
import re
import subprocess
import time

import numpy as np

from fcutil import POVRAY_FC, SCENES, read_pixels, render


def test_version_names_povray_fc_and_its_pov_ray():
    done = subprocess.run([str(POVRAY_FC), "--version"], capture_output=True, text=True)
    # POV-Ray may warn about a missing user povray.conf first; the version line follows.
    lines = [line for line in done.stderr.splitlines() if not line.startswith("povray: ")]
    assert lines and lines[0].startswith("povray-fc "), done.stderr
    assert "POV-Ray 3.7.0.10" in lines[0]


def test_banner_names_povray_fc(tmp_path):
    done = render(POVRAY_FC, SCENES / "tiny" / "tiny.pov", tmp_path / "t.tga", "+W16", "+H12", "+V")
    assert done.returncode == 0, done.stderr
    banner = " ".join(done.stderr.split())  # the banner wraps at 80 columns
    assert "povray-fc 0.1.0, Persistence of Vision(tm) Ray Tracer Version 3.7.0.10" in banner


def test_renders_demo_animation_frames(tmp_path):
    ini = SCENES / "demo" / "demo.ini"
    done = subprocess.run([str(POVRAY_FC), str(ini), "+KFF3", f"+O{tmp_path}/demo", "-D", "-P", "-V"],
                          cwd=ini.parent, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    # POV-Ray numbers frames with as many digits as the final frame has.
    frames = [read_pixels(tmp_path / f"demo{n}.tga") for n in (1, 2, 3)]
    for pixels in frames:
        assert pixels.shape == (240, 320, 3)
        # A real picture: many distinct colours, not a blank or single-colour frame.
        assert len(np.unique(pixels.reshape(-1, 3), axis=0)) > 1000
    # The ball moves, so consecutive frames differ, but only in part of the picture.
    changed = np.count_nonzero(np.any(frames[0] != frames[1], axis=2))
    assert 0 < changed < 0.5 * 320 * 240


def test_missing_scene_fails_with_its_name(tmp_path):
    done = render(POVRAY_FC, tmp_path / "no-such-scene.pov", tmp_path / "x.tga", cwd=tmp_path)
    assert done.returncode != 0
    assert "no-such-scene.pov" in done.stderr
    assert not (tmp_path / "x.tga").exists()


def test_parse_error_names_file_and_line(tmp_path):
    scene = tmp_path / "broken.pov"
    scene.write_text("camera { location <0,0,-3> look_at 0 }\nsphere { 0, 1 pigment { colour rgb 1 }\n")
    done = render(POVRAY_FC, scene, tmp_path / "broken.tga", cwd=tmp_path)
    assert done.returncode != 0
    assert "broken.pov" in done.stderr and "Parse Error" in done.stderr
    assert not (tmp_path / "broken.tga").exists()


import pytest  # noqa: E402


@pytest.mark.parametrize("option, named", [
    ("Frame_Coherence=maybe", "Frame_Coherence=maybe: expected on or off"),
    ("Frame_Coherence_Grid=-1", "Frame_Coherence_Grid=-1: expected a whole number from 0 (automatic) to 256"),
    ("Frame_Coherence_Grid=2000", "Frame_Coherence_Grid=2000: expected a whole number from 0"),
    ("+YG300", "+YG300: expected a whole number from 0"),
    ("+YGmany", "+YGmany: expected a whole number from 0"),
    ("Frame_Coherence_Memory=-1", "Frame_Coherence_Memory=-1: expected a whole number from 0"),
    ("+YBlots", "+YBlots: expected a whole number from 0"),
])
def test_bad_frame_coherence_option_is_named_and_fails(tmp_path, option, named):
    done = render(POVRAY_FC, SCENES / "tiny" / "tiny.pov", tmp_path / "t.tga", "+W8", "+H8", option,
                  cwd=tmp_path)
    assert done.returncode != 0
    # One line names the option, its value and what it accepts.
    assert any(line == f"povray-fc: {named}" or line.startswith(f"povray-fc: {named}")
               for line in done.stderr.splitlines()), done.stderr
    assert not (tmp_path / "t.tga").exists()


@pytest.mark.parametrize("value, shown", [("on", "On"), ("off", "Off"), ("yes", "On"), ("0", "Off")])
def test_option_summary_says_whether_frame_coherence_is_on(tmp_path, value, shown):
    done = render(POVRAY_FC, SCENES / "tiny" / "tiny.pov", tmp_path / "t.tga", "+W8", "+H8",
                  f"Frame_Coherence={value}", "+GA", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert f"  Frame coherence......{shown}" in done.stderr.splitlines()


def test_render_progress_is_rate_limited_and_ends_complete(tmp_path):
    # Patch 0440: a progress message goes out at most every 100 ms, and always the one that
    # completes the render area. A 320x240 frame has 80 render blocks; before the patch each
    # sent one, and the console showed a status line for nearly every one of them.
    start = time.monotonic()
    done = render(POVRAY_FC, SCENES / "tiny" / "tiny.pov", tmp_path / "p.tga", "+W320", "+H240",
                  "+Y", "+V", threads=2)
    elapsed = time.monotonic() - start
    assert done.returncode == 0, done.stderr
    shown = re.findall(r"Rendered (\d+) of (\d+) pixels", done.stderr)
    assert shown and shown[-1] == ("76800", "76800"), done.stderr[-2000:]
    # The first block's, one per 100 ms of the run at most, and the last.
    assert len(shown) <= 2 + math.ceil(elapsed / 0.1), (len(shown), elapsed)
