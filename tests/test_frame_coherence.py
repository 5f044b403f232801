"""Frame coherence re-renders only what changed and changes no pixel.

Every scene in scenes/fc-tests/ is a case that could fool fc. Each is rendered as a
short animation with fc off, and with fc on at one and two render threads; every
frame must have exactly the same pixels. A scene whose first line says `speedup`
must also trace fewer rays with fc on. The first line may also carry POV-Ray
options for that scene (`// fc-test: speedup +A0.1 +AM2`).
"""
import csv
import subprocess
from pathlib import Path

import numpy as np
import pytest

from fcutil import POVRAY_FC, SCENES, assert_same_pixels, read_pixels

FC_SCENES = SCENES / "fc-tests"
FRAMES = 4
SIZE = ["+W96", "+H72"]


def scene_header(scene):
    first = scene.read_text().splitlines()[0]
    assert first.startswith("// fc-test:"), f"{scene}: first line must be '// fc-test: ...'"
    words = first[len("// fc-test:"):].split()
    return "speedup" in words, [w for w in words if w.startswith(("+", "-"))]


def render_animation(scene, outdir, fc, threads, options):
    """Renders FRAMES frames; returns the per-frame statistics rows (fc's CSV)."""
    outdir.mkdir(parents=True, exist_ok=True)
    stats = outdir / "stats.csv"
    args = [str(POVRAY_FC), f"+I{scene}", f"+O{outdir}/f", "+FT", "-D", "-P", "-V",
            f"+KFI1", f"+KFF{FRAMES}", "+KI0", "+KF1", f"+WT{threads}", *SIZE,
            f"+L{scene.parent}", f"Frame_Coherence={'on' if fc else 'off'}", f"+YS{stats}", *options]
    done = subprocess.run(args, cwd=outdir, capture_output=True, text=True, timeout=600,
                          stdin=subprocess.DEVNULL)
    assert done.returncode == 0, f"{' '.join(args)}\n{done.stderr[-3000:]}"
    with open(stats, newline="") as f:
        rows = list(csv.DictReader(f))
    assert [int(r["frame"]) for r in rows] == list(range(1, FRAMES + 1))
    return rows


SCENE_FILES = sorted(FC_SCENES.glob("*.pov"))


@pytest.mark.parametrize("scene", SCENE_FILES, ids=[s.stem for s in SCENE_FILES])
def test_fc_frames_equal_full_renders(scene, tmp_path):
    speedup, options = scene_header(scene)
    full = render_animation(scene, tmp_path / "off", False, 1, options)
    # One thread with the default budget: a store this small writes its segments in full.
    # Two threads with an 8 MiB budget: the store packs them past its first 128 KiB
    # (SampleStore::PackTightly), so both forms, and records mixing them, are checked.
    for threads, budget in ((1, []), (2, ["Frame_Coherence_Memory=8"])):
        coherent = render_animation(scene, tmp_path / f"on-wt{threads}", True, threads, [*options, *budget])
        for n in range(1, FRAMES + 1):
            assert_same_pixels(tmp_path / "off" / f"f{n}.tga", tmp_path / f"on-wt{threads}" / f"f{n}.tga")
    if speedup:
        # Frames after the first reuse pixels, so fc traces fewer rays than full renders.
        rays_full = sum(int(r["rays"]) for r in full[1:])
        rays_fc = sum(int(r["rays"]) for r in coherent[1:])
        assert rays_fc < rays_full, f"fc traced {rays_fc} rays, full renders {rays_full}"
        assert sum(int(r["reused"]) for r in coherent) > 0


def test_radiosity_frames_render_in_full_and_say_why(tmp_path):
    rows = render_animation(FC_SCENES / "radiosity.pov", tmp_path, True, 1, ["+WT1"])
    for row in rows:
        assert row["coherent"] == "0" and "radiosity" in row["full_reason"]
        assert int(row["traced"]) == int(row["pixels"])


def test_moving_light_renders_full_frames(tmp_path):
    rows = render_animation(FC_SCENES / "moving_light.pov", tmp_path, True, 1, [])
    for row in rows[1:]:
        assert "light" in row["full_reason"] and row["reused"] == "0"


def test_camera_cut_starts_a_new_sequence(tmp_path):
    rows = render_animation(FC_SCENES / "camera_cut.pov", tmp_path, True, 1, [])
    reasons = [row["full_reason"] for row in rows]
    # Clock 0, 1/3 share a camera; 2/3 cuts; 1 shares the new one.
    assert reasons[0] and not reasons[1] and "camera" in reasons[2] and not reasons[3]


def test_stats_file_names_the_option_when_unwritable(tmp_path):
    scene = FC_SCENES / "fog.pov"
    args = [str(POVRAY_FC), f"+I{scene}", f"+O{tmp_path}/f", "+FT", "-D", "-P", "-V", *SIZE,
            f"+L{FC_SCENES}", "Frame_Coherence=on", "+YS/nonexistent-dir/stats.csv"]
    done = subprocess.run(args, cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert "Frame_Coherence_Stats" in done.stderr and "/nonexistent-dir/stats.csv" in done.stderr


@pytest.mark.parametrize("scene", ["mirror_only", "shadow_only", "aa_method2_jitter", "aa_method1"])
def test_retraced_mask_covers_every_changed_pixel(scene, tmp_path):
    _, options = scene_header(FC_SCENES / f"{scene}.pov")
    full = render_animation(FC_SCENES / f"{scene}.pov", tmp_path / "off", False, 1, options)
    rows = render_animation(FC_SCENES / f"{scene}.pov", tmp_path / "on", True, 2,
                            options + [f"+YM{tmp_path / 'on'}"])
    del full
    for n in range(1, FRAMES + 1):
        mask = read_pixels(tmp_path / "on" / f"retraced{n:04d}.png")[:, :, 0] > 0
        # The mask is what the statistics count.
        assert int(mask.sum()) == int(rows[n - 1]["traced"])
        if n > 1:
            before = read_pixels(tmp_path / "off" / f"f{n - 1}.tga")
            after = read_pixels(tmp_path / "off" / f"f{n}.tga")
            changed = np.any(before != after, axis=2)
            # Invariant: fc re-traced every pixel that truly changed between full renders.
            assert not np.any(changed & ~mask), f"frame {n}: changed pixels fc did not re-trace"


NEWTON = SCENES / "newton" / "newton.pov"


@pytest.mark.parametrize("motion", [["+W320", "+H240"], ["+W160", "+H120", "+KF0.1"]],
                         ids=["large-moves", "small-moves"])
@pytest.mark.parametrize("options", [[], ["+A0.3"], ["+A0.3", "+J1"], ["+A0.1", "+AM2", "+R2"],
                                     ["+A0.1", "+AM2", "+R2", "+J1"]],
                         ids=["no-aa", "aa1", "aa1-jitter", "aa2", "aa2-jitter"])
def test_newton_fc_frames_equal_full_renders(options, motion, tmp_path):
    # Chrome marbles, a brass frame and a reflective floor: reflections, shadows and rays
    # that hit nothing, with every anti-aliasing method. Large moves (a third of a period
    # between frames) once let a reflection that hit nothing miss a marble moving into it.
    opts = motion + options + [f"+L{NEWTON.parent}"]
    rows_off = render_animation(NEWTON, tmp_path / "off", False, 2, opts)
    rows_on = render_animation(NEWTON, tmp_path / "on", True, 2, opts)
    for n in range(1, FRAMES + 1):
        assert_same_pixels(tmp_path / "off" / f"f{n}.tga", tmp_path / "on" / f"f{n}.tga")
    assert sum(int(r["rays"]) for r in rows_on[1:]) < sum(int(r["rays"]) for r in rows_off[1:])


def test_light_group_change_is_local(tmp_path):
    # A light_group's light lights only the group's objects: not a full frame.
    rows = render_animation(FC_SCENES / "light_group.pov", tmp_path, True, 1, [])
    for row in rows[1:]:
        assert row["full_reason"] == "", row
        assert 0 < int(row["traced"]) < int(row["pixels"]) // 4, row


def test_moving_child_of_a_union_dirties_only_its_places(tmp_path):
    # The union spans the frame (a wall behind everything); only the small sphere moves.
    rows = render_animation(FC_SCENES / "union_child.pov", tmp_path, True, 1, [])
    for row in rows[1:]:
        assert row["full_reason"] == "", row
        assert 0 < int(row["traced"]) < int(row["pixels"]) // 5, row


def changed_pixels(folder, n):
    """Pixels that differ between frames n - 1 and n of a render (the oracle, from fc off)."""
    return int(np.count_nonzero(np.any(read_pixels(folder / f"f{n - 1}.tga") != read_pixels(folder / f"f{n}.tga"),
                                       axis=2)))


def later_frames_against_the_oracle(scene, tmp_path, options=()):
    """Renders `scene` with fc off and on (one thread); for each frame after the first, which
    must be followed (no full frame) and equal to fc off's, fc's row and the pixels that
    truly changed into it."""
    render_animation(scene, tmp_path / "off", False, 1, list(options))
    rows = render_animation(scene, tmp_path / "on", True, 1, list(options))
    later = []
    for n in range(2, FRAMES + 1):
        row = rows[n - 1]
        assert row["full_reason"] == "", row
        assert_same_pixels(tmp_path / "off" / f"f{n}.tga", tmp_path / "on" / f"f{n}.tga")
        later.append((row, changed_pixels(tmp_path / "off", n)))
    return later


def test_moved_cutter_dirties_only_where_its_cut_was_or_is(tmp_path):
    # A ball cut out of a box moves along the box's top edge: each part of the difference is a
    # unit, so the rays that ended on the box away from the ball's old and new places, and
    # those that pass those places outside the box, stay clean. Taking the difference as one
    # unit re-traced the whole box (about 5 times the pixels that change).
    for row, changed in later_frames_against_the_oracle(FC_SCENES / "csg_cutter.pov", tmp_path):
        assert int(row["traced"]) <= 2 * changed, row


def test_shadow_tests_a_grown_box_still_crosses_stay_dark(tmp_path):
    # A box out of view grows and slides, casting a large shadow: a shadow test it darkened
    # holds while the new box still crosses it, so only the shadow's rim is traced again.
    # Taking only balls as blockers re-traced the whole shadow, about 30 times as much.
    for row, changed in later_frames_against_the_oracle(FC_SCENES / "growing_box_shadow.pov", tmp_path):
        assert int(row["traced"]) <= 2 * changed, row


def test_rays_that_ended_on_a_grown_boxs_kept_faces_are_kept(tmp_path):
    # A bar chart whose bars grow: a ray that ended on a face that stays in its plane meets
    # the grown bar there again, so only the bars' new tops (and a turned bar, which is not
    # kept between its corners) are traced again. Tracing every ray that ended on a bar was
    # about 4 times what truly changes.
    later = later_frames_against_the_oracle(FC_SCENES / "growing_bars.pov", tmp_path)
    traced = sum(int(row["traced"]) for row, _ in later)
    changed = sum(changed for _, changed in later)
    assert traced <= 2.5 * changed, (traced, changed)


@pytest.mark.parametrize("scene", ["mesh_strip", "mesh_turning"])
def test_a_mesh_that_changes_is_traced_again_where_its_triangles_changed(scene, tmp_path):
    # A mesh one corner of which rises, with a small triangle of it far to the side; a
    # transformed mesh that turns, gaps between its blades: only the triangles that changed
    # are hulls (and the rims of those kept), so the rays that pass between them to the
    # floor stay clean. Their whole boxes as the hulls re-traced 5 to 8 times what truly
    # changes.
    later = later_frames_against_the_oracle(FC_SCENES / f"{scene}.pov", tmp_path)
    traced = sum(int(row["traced"]) for row, _ in later)
    changed = sum(changed for _, changed in later)
    assert traced <= 3 * changed, (traced, changed)


@pytest.mark.parametrize("scene", ["tie_far_change", "tie_csg"])
def test_tied_samples_whose_searches_find_the_same_are_kept(scene, tmp_path):
    # A small sphere moving far from coincident objects reshapes POV-Ray's bounding tree
    # every frame. The tied searches, run again, mostly find the same surfaces, so fc
    # re-traces about what truly changes; tracing every tied sample again was about 25 times
    # as much.
    _, options = scene_header(FC_SCENES / f"{scene}.pov")
    for row, changed in later_frames_against_the_oracle(FC_SCENES / f"{scene}.pov", tmp_path, options):
        assert int(row["tied_samples_kept"]) > 0, row
        assert int(row["tied_samples_kept"]) <= int(row["tied_samples_replayed"]), row
        assert int(row["traced"]) <= 2 * changed, row


@pytest.mark.parametrize("scene", ["glass_before_mesh_edge", "glass_under_blocker"])
def test_shadow_tests_through_moved_glass_are_run_again(scene, tmp_path):
    # A filtering object changes shape: every shadow test that passed it met the change, but
    # light through a uniform tint keeps its colour, so most of those tests, run again, give
    # the same colour and their samples are kept. Tracing every such sample again was 5.6
    # (glass_before_mesh_edge) and 1.9 times what truly changes.
    _, options = scene_header(FC_SCENES / f"{scene}.pov")
    later = later_frames_against_the_oracle(FC_SCENES / f"{scene}.pov", tmp_path, options)
    for row, _ in later:
        assert int(row["shadow_samples_kept"]) > 0, row
        assert int(row["shadow_samples_kept"]) <= int(row["replay_samples_tried"]), row
    traced = sum(int(row["traced"]) for row, _ in later)
    changed = sum(changed for _, changed in later)
    assert traced <= 2.5 * changed, (traced, changed)


def test_shadow_tests_are_not_run_again_in_fog(tmp_path):
    # A shadow test may read state a kept test does not hold (media, fog, photons and the
    # like): in such a scene none is kept, and the frames stay exact.
    scene = tmp_path / "glass_in_fog.pov"
    text = (FC_SCENES / "glass_before_mesh_edge.pov").read_text()
    scene.write_text(text + "\nfog { distance 40 color rgb 0.8 }\n")
    for row, _ in later_frames_against_the_oracle(scene, tmp_path, scene_header(FC_SCENES / "glass_before_mesh_edge.pov")[1]):
        assert int(row["replay_samples_tried"]) == 0, row


@pytest.mark.parametrize("bounding", [["+BM2"], ["-MB"], ["+MB100"]], ids=["bsp", "no-bounding", "threshold-100"])
@pytest.mark.parametrize("scene", ["tie_swap", "tie_far_change", "tie_shadow"])
def test_ties_stay_exact_with_every_bounding_method(scene, bounding, tmp_path):
    # Coincident surfaces: which one POV-Ray shows depends on how it bounds the scene (a
    # BSP tree, bounding slabs, or the objects in scene order); fc follows each.
    _, options = scene_header(FC_SCENES / f"{scene}.pov")
    render_animation(FC_SCENES / f"{scene}.pov", tmp_path / "off", False, 1, options + bounding)
    render_animation(FC_SCENES / f"{scene}.pov", tmp_path / "on", True, 1, options + bounding)
    for n in range(1, FRAMES + 1):
        assert_same_pixels(tmp_path / "off" / f"f{n}.tga", tmp_path / "on" / f"f{n}.tga")


def test_isosurface_with_too_low_max_gradient_does_not_depend_on_the_pixel_traced_before(tmp_path):
    # The root finder's cache of the last root-free stretch lives within one sample, so a
    # pixel does not depend on the pixel its thread traced before: render blocks of 8 and
    # of 32 pixels (which change that order) give the same frames without anti-aliasing.
    scene = FC_SCENES / "isosurface_low_gradient.pov"
    render_animation(scene, tmp_path / "bs32", False, 1, ["+BS32"])
    render_animation(scene, tmp_path / "bs8", False, 1, ["+BS8"])
    for n in range(1, FRAMES + 1):
        assert_same_pixels(tmp_path / "bs32" / f"f{n}.tga", tmp_path / "bs8" / f"f{n}.tga")


def test_a_store_past_a_64th_of_its_budget_packs_what_it_records(tmp_path):
    # Segments are written in full while the store is small against its budget, and packed
    # past a 64th of it: the same frames, in fewer bytes, with the same pixels re-traced
    # but for the few a packed segment's other rounding moves across a hull's edge.
    scene = FC_SCENES / "glass_under_blocker.pov"
    size = ["+W160", "+H120"]
    render_animation(scene, tmp_path / "off", False, 1, size)
    roomy = render_animation(scene, tmp_path / "roomy", True, 1, size)
    tight = render_animation(scene, tmp_path / "tight", True, 1, [*size, "Frame_Coherence_Memory=8"])
    for n in range(1, FRAMES + 1):
        assert_same_pixels(tmp_path / "off" / f"f{n}.tga", tmp_path / "roomy" / f"f{n}.tga")
        assert_same_pixels(tmp_path / "off" / f"f{n}.tga", tmp_path / "tight" / f"f{n}.tga")
    assert all(r["over_budget_blocks"] == "0" for r in roomy + tight)
    assert int(tight[0]["store_bytes"]) < 0.9 * int(roomy[0]["store_bytes"])
    assert int(tight[0]["store_bytes"]) > (8 << 20) // 64
    roomy_traced = sum(int(r["traced"]) for r in roomy[1:])
    tight_traced = sum(int(r["traced"]) for r in tight[1:])
    assert abs(roomy_traced - tight_traced) <= 0.02 * roomy_traced


def test_store_past_its_memory_budget_traces_those_blocks_in_full(tmp_path):
    # A 1 MiB budget holds some of a 320x240 render's blocks, not all: the others are
    # traced in full every frame, the frames stay exact, and the store keeps to the budget.
    scene = FC_SCENES / "pendulum.pov"
    budget = 1 << 20
    size = ["+W320", "+H240"]
    full = render_animation(scene, tmp_path / "off", False, 2, size)
    free = render_animation(scene, tmp_path / "free", True, 2, size)
    bounded = render_animation(scene, tmp_path / "bounded", True, 2, [*size, "Frame_Coherence_Memory=1"])
    for n in range(1, FRAMES + 1):
        assert_same_pixels(tmp_path / "off" / f"f{n}.tga", tmp_path / "bounded" / f"f{n}.tga")
    assert all(r["over_budget_blocks"] == "0" for r in free)
    assert int(free[0]["store_bytes"]) > 2 * budget
    for row in bounded:
        assert int(row["over_budget_blocks"]) > 0
        assert int(row["store_bytes"]) <= budget
    # The blocks within the budget are still reused; the others cost re-traced pixels.
    assert sum(int(r["reused"]) for r in bounded[1:]) > 0
    assert sum(int(r["traced"]) for r in bounded[1:]) > sum(int(r["traced"]) for r in free[1:])
    assert int(full[1]["traced"]) > int(bounded[1]["traced"])
