"""Random scenes with random changes render with fc exactly as without (scripts/fc-random-scenes).

The script builds each scene from a seed (unions, declared objects, CSG, meshes, text,
mirrors, glass, coincident surfaces; objects that move, turn, grow, change colour or
transparency, appear, vanish or trade places), renders it with fc off and on and compares
every frame on pixels; it exits 1 and names the seed when a frame differs.
"""
import subprocess

import pytest

from fcutil import TOP

SCRIPT = TOP / "scripts" / "fc-random-scenes"


@pytest.mark.parametrize("first, last, frames, options",
                         [(1, 16, 4, []), (17, 24, 4, ["--threads", "2", "--aa"]),
                          # frames numbered f01.tga on; blocks whose cones grow frame after frame
                          (25, 27, 14, ["--threads", "2"])],
                         ids=["one-thread", "two-threads-aa", "fourteen-frames"])
def test_random_scenes_render_the_same_with_fc(first, last, frames, options, tmp_path):
    done = subprocess.run(["/usr/bin/python3", str(SCRIPT), "--seeds", f"{first}-{last}", "--frames", str(frames),
                           *options, "--keep", str(tmp_path)], capture_output=True, text=True, timeout=1200)
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    # Every seed was rendered and compared, every frame identical.
    zeros = ", ".join(["0"] * frames)
    for seed in range(first, last + 1):
        assert f"seed {seed}: pixels differing per frame [{zeros}]" in done.stdout, done.stdout


def test_a_differing_frame_fails_and_names_its_seed(tmp_path):
    # The comparison itself: the fc renders get another clock, so their frames differ.
    done = subprocess.run(["/usr/bin/python3", str(SCRIPT), "--seeds", "3", "--keep", str(tmp_path),
                           "--fc-options=+KF0.5"], capture_output=True, text=True, timeout=600)
    assert done.returncode == 1, done.stdout + done.stderr
    assert "seed 3" in done.stderr
