"""povray-fc's frame channel and frame control (frame-channel/), without the coordinator.

A render with Frame_Channel writes one record per frame (a header line, then the pixels of
the frame's rectangles as the Targa writer encodes them) and no image file; with
Frame_Control it renders, frame by frame, only what the control lines ask for. Pixels are
compared with a plain render of the same frames (OpenImageIO).
"""
import os
import struct
import subprocess

import numpy as np
import pytest

from fcutil import BIN, POVRAY_FC, SCENES, read_pixels

SCENE = SCENES / "coordinator-test" / "moving.pov"
ANIMATION = ["+W160", "+H120", "+KFI1", "+KFF4"]


def povray(args, tmp_path):
    argv = [str(POVRAY_FC), f"+I{SCENE}", "-D", "-P", "-V", "+FT", "-UA"] + args
    return subprocess.run(argv, cwd=tmp_path, capture_output=True, text=True, timeout=120,
                          stdin=subprocess.DEVNULL)


def records(path, with_files=False, with_reads=False):
    """[(fields, rects, payload)] of a frame channel file; with_files, (fields, rects,
    payload, file): file is the image file a whole-image record carries, or None; with_reads,
    (fields, rects, payload, reads): reads is the text of the files the frame's parse read."""
    data = path.read_bytes()
    out, pos = [], 0
    while pos < len(data):
        nl = data.index(b"\n", pos)
        words = data[pos:nl].decode().split()
        assert words[:2] == ["FCFRAME", "1"], words
        fields, rects, i = {}, [], 2
        while i < len(words):
            key, value = words[i].split("=")
            if key == "rects":
                rects = [tuple(int(v) for v in words[i + 1 + k].split(",")) for k in range(int(value))]
                i += int(value)
            else:
                fields[key] = value
            i += 1
        size, file_size = int(fields["bytes"]), int(fields.get("file", 0))
        reads_size = int(fields.get("reads", 0))
        payload = data[nl + 1:nl + 1 + size]
        file = data[nl + 1 + size:nl + 1 + size + file_size] if "file" in fields else None
        at = nl + 1 + size + file_size
        reads = data[at:at + reads_size].decode()
        if with_reads:
            out.append((fields, rects, payload, reads))
        else:
            out.append((fields, rects, payload, file) if with_files else (fields, rects, payload))
        pos = at + reads_size
    return out


def reference(tmp_path, options, ext=".tga"):
    """A plain render of the same frames: {frame: pixels}."""
    ref = tmp_path / "ref"
    ref.mkdir(exist_ok=True)
    r = povray(ANIMATION + options + [f"+O{ref}/f"], tmp_path)
    assert r.returncode == 0, r.stderr
    return {n: read_pixels(ref / f"f{n}{ext}")[:, :, :3] for n in range(1, 5)}


def assert_rectangles_equal(fields, rects, payload, ref):
    """A record's payload holds exactly its rectangles, each equal to the full render's."""
    want = ref[int(fields["frame"])]
    offset = 0
    for x0, y0, x1, y1 in rects:
        n = (x1 - x0) * (y1 - y0) * 3
        got = np.frombuffer(payload[offset:offset + n], np.uint8).reshape(y1 - y0, x1 - x0, 3)
        offset += n
        assert np.array_equal(got, want[y0:y1, x0:x1]), (fields["frame"], (x0, y0, x1, y1))
    assert offset == len(payload)


def channel_render(tmp_path, options, control):
    (tmp_path / "control").write_text(control)
    r = povray(ANIMATION + options + [f"+O{tmp_path}/x", f"Frame_Channel={tmp_path}/channel",
                                      f"Frame_Control={tmp_path}/control"], tmp_path)
    return r


@pytest.mark.parametrize("options", [["-A"], ["+A0.1", "+AM1"], ["+A0.05", "+AM1", "+J0.7"],
                                     ["+A0.1", "+AM2", "+R2", "+J"]],
                         ids=["no-aa", "am1", "am1-jitter", "am2-jitter"])
def test_rectangles_equal_a_full_render(tmp_path, options):
    # Rectangles that do not line up with the 32-pixel render blocks, frames skipped.
    control = "render 1 37,0,117,80 117,80,160,120\nrender 3 0,13,33,120\nrender 4\n"
    r = channel_render(tmp_path, options, control)
    assert r.returncode == 0, r.stderr
    recs = records(tmp_path / "channel")
    ref = reference(tmp_path, options)
    # Invariant: one record per frame asked for, in order, and no image file.
    assert [int(f["frame"]) for f, _, _ in recs] == [1, 3, 4]
    assert not list(tmp_path.glob("x*.tga"))
    assert recs[2][1] == [(0, 0, 160, 120)]     # no rectangles: the whole image
    for fields, rects, payload in recs:
        assert fields["encoding"] == "rgb8" and int(fields["rays"]) > 0
        assert float(fields["parse"]) >= 0 and float(fields["trace"]) > 0
        assert_rectangles_equal(fields, rects, payload, ref)


@pytest.mark.parametrize("options", [["-A"], ["+A0.1", "+AM1"]], ids=["no-aa", "am1"])
def test_frame_coherence_rectangle_left_out_then_back(tmp_path, options):
    # With fc, one process keeps rendering while its rectangles change (as a slave's tiles
    # do when fc-master moves them): the right half sits out frame 2, while the sphere
    # crosses it, and comes back in frame 3; the left half leaves in frame 4.
    left, right = "0,0,80,120", "80,0,160,120"
    control = f"render 1 {left} {right}\nrender 2 {left}\nrender 3 {left} {right}\nrender 4 {right}\n"
    r = channel_render(tmp_path, options + ["Frame_Coherence=on"], control)
    assert r.returncode == 0, r.stderr
    recs = records(tmp_path / "channel")
    ref = reference(tmp_path, options)
    assert [int(f["frame"]) for f, _, _ in recs] == [1, 2, 3, 4]
    # Invariant: fc's pixels equal a full render's, also where the last frame was not
    # rendered here.
    for fields, rects, payload in recs:
        assert_rectangles_equal(fields, rects, payload, ref)


@pytest.mark.parametrize("options,ext", [([], ".tga"), (["+FC"], ".tga"), (["+FN"], ".png"),
                                         (["Frame_Coherence=on"], ".tga"),
                                         (["+FN", "Frame_Coherence=on"], ".png")],
                         ids=["targa", "rle-targa", "png", "targa-fc", "png-fc"])
def test_whole_image_records_carry_the_file(tmp_path, options, ext):
    # A record of the whole image carries the file POV-Ray's writer makes of the frame, after
    # the pixels; a record of rectangles carries none. With fc the file's
    # encoding shares the memo of encoded pixels with the record's: both must stay exact.
    options = ["+A0.1", "+AM1"] + options
    r = channel_render(tmp_path, options, "render 1\nrender 2 0,0,32,32\nrender 3\nrender 4\n")
    assert r.returncode == 0, r.stderr
    recs = records(tmp_path / "channel", with_files=True)
    ref = reference(tmp_path, options, ext)
    assert [int(f["frame"]) for f, _, _, _ in recs] == [1, 2, 3, 4]
    assert recs[1][3] is None and "file" not in recs[1][0]
    for fields, rects, payload, file in recs:
        assert_rectangles_equal(fields, rects, payload, ref)
        if rects != [(0, 0, 160, 120)]:
            continue
        assert file, fields
        path = tmp_path / f"record{fields['frame']}{ext}"
        path.write_bytes(file)
        assert np.array_equal(read_pixels(path)[:, :, :3], ref[int(fields["frame"])]), fields


def test_fewer_rays_for_fewer_rectangles(tmp_path):
    r = channel_render(tmp_path, ["-A"], "render 1\nrender 2 0,0,32,32\n")
    assert r.returncode == 0, r.stderr
    (whole, _, _), (corner, _, _) = records(tmp_path / "channel")
    # Only the blocks meeting the rectangle are traced.
    assert 0 < int(corner["rays"]) < int(whole["rays"]) / 4


def test_stop_and_end_of_file_end_the_render(tmp_path):
    r = channel_render(tmp_path, ["-A"], "render 2\nstop\nrender 3\n")
    assert r.returncode == 0, r.stderr
    assert [int(f["frame"]) for f, _, _ in records(tmp_path / "channel")] == [2]
    r = channel_render(tmp_path, ["-A"], "render 1\n")
    assert r.returncode == 0, r.stderr
    assert len(records(tmp_path / "channel")) == 1


def test_records_list_the_files_each_parse_read(tmp_path):
    # A scene that includes late.inc from frame 3 on and looks for extra.txt, which is not
    # there, along a library path. Every record lists this frame's lookups only: the scene
    # and the include it opened (F), and each place it looked in vain (A: the current
    # directory, then the library path; for the include too, before the library path).
    lib = tmp_path / "lib"
    lib.mkdir()
    (lib / "late.inc").write_text("sphere { <1, 2, 0>, 0.3 pigment { color rgb 1 } }\n")
    scene = tmp_path / "scene.pov"
    scene.write_text(SCENE.read_text() + '#if (file_exists("extra.txt")) #end\n'
                     '#if (frame_number >= 3) #include "late.inc" #end\n')
    (tmp_path / "control").write_text("render 2\nrender 3\n")
    argv = [str(POVRAY_FC), f"+I{scene}", "-D", "-P", "-V", "+FT", "-UA", "+L" + str(lib),
            "Frame_Channel=channel", "Frame_Control=control"] + ANIMATION
    r = subprocess.run(argv, cwd=tmp_path, capture_output=True, text=True, timeout=120,
                       stdin=subprocess.DEVNULL)
    assert r.returncode == 0, r.stderr
    recs = records(tmp_path / "channel", with_reads=True)
    assert [int(f["frame"]) for f, _, _, _ in recs] == [2, 3]
    for fields, _, _, reads in recs:
        assert int(fields["reads"]) == len(reads.encode())
        lines = reads.splitlines()
        # Invariant: each line once, the scene first (its parse opened it first).
        assert len(lines) == len(set(lines)) and lines[0] == f"F\t{scene}", lines
        assert "A\textra.txt" in lines and f"A\t{lib}/extra.txt" in lines, lines
        assert not any(line.startswith("F\t") and "extra.txt" in line for line in lines)
    frame2, frame3 = (reads.splitlines() for _, _, _, reads in recs)
    assert set(frame2) <= set(frame3)
    # The include: the places tried before lib (the current directory, then povray.ini's
    # library paths) absent, then the file found in lib; nothing tried after it.
    late = [line for line in frame3 if line not in frame2]
    assert late[0] == "A\tlate.inc" and late[-1] == f"F\t{lib}/late.inc", late
    assert all(line.startswith("A\t/") and line.endswith("/late.inc") for line in late[1:-1])


@pytest.mark.parametrize("control,message", [
    ("render 2\nrender 1\n", "Frame control asked for frame 1, but frame 3 is next"),
    ("rendr 1\n", "Frame control: cannot understand 'rendr 1'"),
    ("render 1 10,10,5,20\n", "Frame control: bad rectangle '10,10,5,20'"),
], ids=["passed", "verb", "rectangle"])
def test_bad_control_lines_fail_with_a_message(tmp_path, control, message):
    r = channel_render(tmp_path, ["-A"], control)
    assert r.returncode != 0
    assert message in r.stdout + r.stderr


def test_unusable_channel_is_an_error(tmp_path):
    r = povray(ANIMATION + [f"+O{tmp_path}/x", f"Frame_Channel={tmp_path}/no/such/dir"], tmp_path)
    assert r.returncode != 0
    assert f"Cannot open frame channel '{tmp_path}/no/such/dir'" in r.stdout + r.stderr


def image_writer_dither(width, height, values, diffusion):
    """The frame of values (3 floats a pixel) dithered by fc-image-writer, as fc-master has it
    dither a frame assembled from tiles: width x height x 3 bytes."""
    request = struct.pack("<Iiiiif", 0x32574346, 2, width, height, 0, 0.0) + diffusion
    req_r, req_w = os.pipe()
    rep_r, rep_w = os.pipe()
    writer = subprocess.Popen([str(BIN / "fc-image-writer")], pass_fds=(3, 4),
                              preexec_fn=lambda: (os.dup2(req_r, 3), os.dup2(rep_w, 4)))
    os.close(req_r)
    os.close(rep_w)
    with os.fdopen(req_w, "wb") as requests:
        requests.write(request + values)
    with os.fdopen(rep_r, "rb") as replies:
        magic, ok, size = struct.unpack("<IiQ", replies.read(16))
        answer = replies.read(size)
    assert writer.wait(timeout=30) == 0
    assert magic == 0x31524346 and ok == 1, answer
    return np.frombuffer(answer, np.uint8).reshape(height, width, 3)


def test_diffusion_dithering_sends_values_for_povrays_own_dither(tmp_path):
    # Error diffusion crosses tiles: the record carries the values the Targa writer would
    # quantise and how to dither them (method, working and file gamma); POV-Ray's own dither
    # handler over them (fc-image-writer's) gives the file one POV-Ray process writes.
    r = channel_render(tmp_path, ["-A", "Dither=on"], "render 1\nrender 2 0,0,50,40\n")
    assert r.returncode == 0, r.stderr
    (whole, whole_rects, values), (part, part_rects, part_values) = records(tmp_path / "channel")
    assert whole["encoding"] == part["encoding"] == "rgbf"
    assert whole_rects == [(0, 0, 160, 120)] and part_rects == [(0, 0, 50, 40)]
    assert len(part_values) == 50 * 40 * 12 + 20
    pixels = 160 * 120 * 12
    assert len(values) == pixels + 20
    # Floyd-Steinberg (3, the default), a neutral working gamma (1) and sRGB files (3, 2.2).
    method, working_type, _, file_type, file_gamma = struct.unpack("<iifif", values[pixels:])
    assert (method, working_type, file_type) == (3, 1, 3) and abs(file_gamma - 2.2) < 1e-6
    ref = reference(tmp_path, ["-A", "Dither=on"])
    dithered = image_writer_dither(160, 120, values[:pixels], values[pixels:])
    assert np.array_equal(dithered, ref[1])
