"""The animations Debian's povray-examples ships render the same with fc on as off.

Each runs from its own .ini (so its options apply: anti-aliasing, cyclic clocks,
declares) at a small size, with 5 frames spread over its clock range.
"""
import subprocess
from pathlib import Path

import pytest

from fcutil import POVRAY_FC, assert_same_pixels

ANIMATIONS = Path("/usr/share/doc/povray/examples/animations")
FRAMES = 5


def animations():
    cases = []
    for ini in sorted(ANIMATIONS.glob("*/*.ini")):
        scenes = sorted(ini.parent.glob("*.pov"))
        assert len(scenes) == 1, f"{ini.parent}: expected one scene"
        cases.append((ini, scenes[0]))
    return cases


CASES = animations()


@pytest.mark.parametrize("ini,scene", CASES, ids=[c[0].parent.name for c in CASES])
def test_example_animation_fc_on_equals_off(ini, scene, tmp_path):
    # Radiosity is deterministic only with one render thread.
    threads = "+WT1" if "radiosity" in scene.read_text(errors="replace") else "+WT2"
    outputs = {}
    for mode in ("off", "on"):
        out = tmp_path / mode
        out.mkdir()
        args = [str(POVRAY_FC), str(ini), f"+I{scene}", f"+L{scene.parent}", f"+O{out}/f",
                "+FT", "-D", "-P", "-V", "+W80", "+H60", f"+KFF{FRAMES}", "+KFI1", threads,
                f"Frame_Coherence={mode}"]
        done = subprocess.run(args, cwd=out, capture_output=True, text=True, timeout=600,
                              stdin=subprocess.DEVNULL)
        assert done.returncode == 0, f"{' '.join(args)}\n{done.stderr[-3000:]}"
        outputs[mode] = out
    for n in range(1, FRAMES + 1):
        assert_same_pixels(outputs["off"] / f"f{n}.tga", outputs["on"] / f"f{n}.tga")
