"""Effects fc cannot follow ray by ray, in frames where nothing changes.

A frame in which nothing changed may reuse every pixel only where a full render of it
is itself reproducible and equal to the previous frame. Each scene in scenes/effects/
uses one such effect and never moves; rendered as a 3-frame animation with fc off, the
frames show whether POV-Ray renders them alike. The table below is fc's policy
(povray-fc/src/effect_policy.cpp); the tests check that fc reuses exactly where the
policy says, and that wherever it reuses, the full renders really are equal frame to
frame and to fc's.
"""
import pytest

from fcutil import SCENES, assert_same_pixels, read_pixels
from test_frame_coherence import render_animation

EFFECTS = SCENES / "effects"
# Reused at one render thread (their random sequences restart each frame and follow the
# order of one thread); with several, which thread takes which block changes the noise.
REUSED_AT_ONE_THREAD = ["radiosity", "crand", "media_method1", "media_method2", "media_jitter",
                        "subsurface", "isosurface_evaluate"]
# Never reused: their random state carries from frame to frame (photons measured so; a
# jittered area light is kept out because some of Debian's scenes with one were found to
# differ from frame to frame with fc off).
NEVER_REUSED = ["jittered_area_light", "photons"]
SIZE = ["+W64", "+H48"]


def frames_equal(folder, frames):
    first = read_pixels(folder / "f1.tga")
    return all((read_pixels(folder / f"f{n}.tga") == first).all() for n in range(2, frames + 1))


@pytest.mark.parametrize("effect", REUSED_AT_ONE_THREAD + NEVER_REUSED)
def test_static_frames_reuse_only_where_full_renders_repeat(effect, tmp_path):
    scene = EFFECTS / f"{effect}.pov"
    opts = SIZE + [f"+L{EFFECTS}"]
    off = render_animation(scene, tmp_path / "off", False, 1, opts)
    on = render_animation(scene, tmp_path / "on", True, 1, opts)
    frames = len(off)
    reused = [int(r["traced"]) == 0 for r in on[1:]]
    if effect in REUSED_AT_ONE_THREAD:
        assert all(reused), on
        # Invariant: reuse happens only where POV-Ray itself renders the frames alike.
        assert frames_equal(tmp_path / "off", frames), f"{effect}: full renders differ frame to frame"
    else:
        assert not any(reused), on
        assert all(r["full_reason"] for r in on[1:])
    for n in range(1, frames + 1):
        assert_same_pixels(tmp_path / "off" / f"f{n}.tga", tmp_path / "on" / f"f{n}.tga")


@pytest.mark.parametrize("effect", REUSED_AT_ONE_THREAD)
def test_static_frames_are_not_reused_with_several_threads(effect, tmp_path):
    # With two render threads these effects are not reproducible: every frame is traced.
    on = render_animation(EFFECTS / f"{effect}.pov", tmp_path / "on", True, 2, SIZE + [f"+L{EFFECTS}"])
    for row in on:
        assert int(row["traced"]) == int(row["pixels"]), row
        assert effect.split("_")[0] in row["full_reason"].replace(" ", "_") or row["full_reason"], row
