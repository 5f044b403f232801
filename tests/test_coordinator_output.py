"""fc-master's output: nothing lost, nothing half written, nothing misreported.

A full disk is an error that says so and leaves only complete frames under final names; the
output directory is checked (writable, room for the frames) before anything renders; a resume
re-renders every frame that is not complete and correct, or whose inputs (the scene, the files
its parse read) changed; two masters never write the same frames; a resume after the options
changed is refused unless --force; frames are written in the format POV-Ray would write; a
preview shows the render while it runs.
Small file systems are tmpfs mounts (root only).
"""
import os
import signal
import subprocess
import time

import numpy as np
import pytest

from conftest import (COORDINATOR_SCENES, coordinator_renderer, coordinator_stats, frame_files,
                      load_rgb, master_with_failing_image_writer)
from fcutil import LONG_COORDINATOR_RENDER, TOP

pytestmark = pytest.mark.usefixtures("coordinator_build")

SCENE = "moving.pov"
SMALL = ["+FT", "+W160", "+H120", "+KFI1", "+KFF8"]
# 24 Targa frames of 225 KB; about 0.2 s a frame per process.
SLOW = ["+FT", "+W320", "+H240", "+KFI1", "+KFF24", "+A0.1", "+AM2", "+R3"]

root_only = pytest.mark.skipif(os.geteuid() != 0, reason="needs root to mount tmpfs")


def assert_frames_exact(outdir, reference, only=None):
    """outdir holds exactly the reference's frames (or the subset `only`), pixel for pixel,
    and nothing else but fc-master's own files (no temporary file)."""
    files = frame_files(outdir)
    assert files == (sorted(reference) if only is None else sorted(only))
    assert set(files) <= set(reference), files
    for name in files:
        got, want = load_rgb(os.path.join(outdir, name)), reference[name]
        # Invariant: a frame under its final name is complete and equals one process's.
        assert got.shape == want.shape and (got == want).all(), name


def wait_for_frames(outdir, count, proc, timeout=60):
    deadline = time.time() + timeout
    while time.time() < deadline:
        if os.path.isdir(outdir) and len([f for f in os.listdir(outdir)
                                          if f.endswith(".tga")]) >= count:
            return
        assert proc.poll() is None, "fc-master ended early:\n" + proc.communicate()[1]
        time.sleep(0.02)
    raise AssertionError("no %d frames after %d s" % (count, timeout))


@pytest.fixture
def tmpfs(tmp_path):
    """mount(name, size, readonly=False): a tmpfs below tmp_path; all unmounted at the end."""
    mounts = []

    def mount(name, size, readonly=False):
        path = tmp_path / name
        path.mkdir()
        subprocess.run(["mount", "-t", "tmpfs", "-o", "size=" + size, "tmpfs", str(path)],
                       check=True)
        mounts.append(path)
        if readonly:
            subprocess.run(["mount", "-o", "remount,ro", str(path)], check=True)
        return path

    yield mount
    for path in reversed(mounts):
        subprocess.run(["umount", "-l", str(path)])


def fill(directory, leave):
    """Fill the file system of directory until about `leave` bytes are free."""
    st = os.statvfs(directory)
    free = st.f_bavail * st.f_frsize
    filler = os.path.join(directory, "filler")
    with open(filler, "wb") as f:
        try:
            f.write(b"\0" * max(0, free - leave))
        except OSError:
            pass
    return filler


def counting_renderer(tmp_path):
    """A renderer that counts the renders fc-slave starts (in tmp_path/renders)."""
    counter = tmp_path / "renders"
    script = tmp_path / "counting-povray"
    script.write_text(f"""#!/bin/sh
case "$*" in *Frame_Control=*) echo x >> {counter};; esac
exec {coordinator_renderer()} "$@"
""")
    script.chmod(0o755)
    return script, counter


# --- a full disk ------------------------------------------------------------------------------

@root_only
def test_full_disk_is_an_error_and_resume_completes(coordinator, coordinator_references,
                                                    tmp_path, tmpfs):
    out = tmpfs("out", "12m") / "frames"
    ref = coordinator_references.frames(SCENE, SLOW)
    args = ["--no-fc", "--quiet", "--division", "sequence", "--slaves", "2", SCENE] + SLOW + \
           ["-o", str(out)]
    p = coordinator.start(args)
    wait_for_frames(out, 3, p)
    filler = fill(out.parent, 64 * 1024)       # less than one frame
    _, err = p.communicate(timeout=120)
    # Invariant: a full disk fails the run, and the message says the disk is full.
    assert p.returncode == 1, err
    assert "No space left on device" in err and "is full" in err, err
    assert coordinator.wait_no_processes() == []
    written = frame_files(out)
    assert 3 <= len(written) < len(ref), written
    # Invariant: only complete frames exist, under final names, no temporary file.
    assert_frames_exact(out, ref, only=written)

    os.unlink(filler)
    stats = tmp_path / "stats.json"
    r = coordinator.run(args + ["--stats", str(stats)])
    assert r.returncode == 0, r.stderr
    assert_frames_exact(out, ref)
    s = coordinator_stats(stats)
    # Invariant: nothing rendered before is lost or rendered again.
    assert s["frames_resumed"] == len(written)
    assert s["frames_rendered"] == len(ref) - len(written)


@root_only
def test_slave_with_full_tmp_renders(coordinator, coordinator_references, tmp_path):
    # The renderer of every slave sees its working directory (/tmp/fc-slave-*) on a full
    # file system: the frame channel needs no disk, so the frames still arrive.
    script = tmp_path / "full-tmp-povray"
    script.write_text(f"""#!/bin/sh
dir=
for a; do case $a in +O/tmp/fc-slave-*) dir=$(dirname "${{a#+O}}");; esac; done
[ -n "$dir" ] || exec {coordinator_renderer()} "$@"
exec unshare -m sh -c 'mount -t tmpfs -o size=64k tmpfs "$0" &&
    head -c 1000000 /dev/zero > "$0/fill" 2>/dev/null; exec "$@"' "$dir" \\
    {coordinator_renderer()} "$@"
""")
    script.chmod(0o755)
    out = tmp_path / "out"
    r = coordinator.run(["--no-fc", "--quiet", "--povray", str(script), "--division", "frame",
                         "--slaves", "2", SCENE] + SMALL + ["-o", str(out)], renderer=False)
    assert r.returncode == 0, r.stderr
    assert_frames_exact(out, coordinator_references.frames(SCENE, SMALL))


@root_only
def test_slave_without_room_in_tmp_says_so(coordinator, tmp_path):
    # A slave whose /tmp has no room left for its working directory (no inode, no block):
    # the reason reaches the user, and the render stops once the host is left out.
    # PVM's directory and the checkout (binaries, scenes: a clone may live in /tmp) stay
    # visible through the new /tmp.
    from conftest import FC_SLAVE, TOP
    script = tmp_path / "full-tmp-slave"
    script.write_text(f"""#!/bin/sh
exec unshare -m sh -c '
  keep=/run/fc-test-keep-$$; mkdir -p $keep/pvm $keep/top &&
  mount --bind "$PVM_TMP" $keep/pvm && mount --bind "{TOP}" $keep/top &&
  mount -t tmpfs -o size=64k,nr_inodes=64 tmpfs /tmp && mkdir -p "$PVM_TMP" "{TOP}" &&
  mount --bind $keep/pvm "$PVM_TMP" && mount --bind $keep/top "{TOP}" &&
  umount -l $keep/pvm $keep/top && rm -rf $keep
  i=0; while touch /tmp/f$i 2>/dev/null; do i=$((i+1)); done
  head -c 100000 /dev/zero > /tmp/fill 2>/dev/null
  exec {FC_SLAVE}'
""")
    script.chmod(0o755)
    out = tmp_path / "out"
    r = coordinator.run(["--no-fc", "--slave", str(script), "--slaves", "1", SCENE] + SMALL +
                        ["-o", str(out)])
    # Invariant: the slave's own failure is shown with the system's reason, not just "exited".
    assert r.returncode == 1, r.stderr
    assert "mkdtemp /tmp/fc-slave-" in r.stderr and "No space left on device" in r.stderr, r.stderr
    assert frame_files(out) == []
    assert coordinator.wait_no_processes() == []


# --- the output directory, checked before rendering ------------------------------------------

@root_only
def test_unwritable_output_directory_fails_before_rendering(coordinator, tmp_path, tmpfs):
    out = tmpfs("readonly", "1m", readonly=True)
    script, renders = counting_renderer(tmp_path)
    r = coordinator.run(["--no-fc", "--povray", str(script), SCENE] + SMALL + ["-o", str(out)],
                        renderer=False)
    # Invariant: the error names the directory and the system's reason, before any render.
    assert r.returncode == 1
    assert str(out) in r.stderr and "Read-only file system" in r.stderr, r.stderr
    assert "not writable" in r.stderr
    assert not renders.exists()
    assert coordinator.wait_no_processes() == []


@root_only
def test_too_little_space_fails_before_rendering(coordinator, tmp_path, tmpfs):
    out = tmpfs("small", "2m")
    script, renders = counting_renderer(tmp_path)
    r = coordinator.run(["--no-fc", "--povray", str(script), SCENE] + SLOW + ["-o", str(out)],
                        renderer=False)
    # 24 frames of 225 KB do not fit in 2 MB: said at once, with the numbers.
    assert r.returncode == 1
    assert "not enough space" in r.stderr and "24 frame(s)" in r.stderr, r.stderr
    assert "free" in r.stderr
    assert not renders.exists()
    assert frame_files(out) == []
    assert coordinator.wait_no_processes() == []


# --- resume trusts only complete and correct frames -------------------------------------------

def damage(out):
    """Cut moving2.tga in half and change one pixel of moving5.tga (same size)."""
    cut = out / "moving2.tga"
    data = cut.read_bytes()
    cut.write_bytes(data[:len(data) // 2])
    changed = out / "moving5.tga"
    data = bytearray(changed.read_bytes())
    data[len(data) // 2] ^= 0xff       # among the pixels, whatever the header and footer
    changed.write_bytes(bytes(data))


def small_render_args(out):
    return ["--no-fc", "--quiet", "--slaves", "2", SCENE] + SMALL + ["-o", str(out)]


def assert_resume_renders_damaged_frames_again(coordinator, coordinator_references, tmp_path,
                                               out):
    """Damage two frames of the small render in out, resume it, check what it did."""
    damage(out)
    stats = tmp_path / "stats.json"
    r = coordinator.run(small_render_args(out)[1:] + ["--stats", str(stats)])
    assert r.returncode == 0, r.stderr
    # Invariant: a frame that is cut short or whose pixels are not those written (by this
    # version or an earlier one) is rendered again, with a warning that names it; the
    # others are kept.
    assert "moving2.tga" in r.stderr and "moving5.tga" in r.stderr, r.stderr
    s = coordinator_stats(stats)
    assert s["frames_resumed"] == 6 and s["frames_rendered"] == 2
    assert_frames_exact(out, coordinator_references.frames(SCENE, SMALL))


def test_resume_renders_damaged_frames_again(coordinator, coordinator_references, tmp_path):
    out = tmp_path / "out"
    assert coordinator.run(small_render_args(out)).returncode == 0
    assert_resume_renders_damaged_frames_again(coordinator, coordinator_references, tmp_path,
                                               out)


def test_records_of_frames_reach_the_disk_before_the_end(coordinator, tmp_path):
    # Resume trusts a frame by its record: the record of the last frame must be on disk when
    # fc-master ends, not only in the page cache (each frame file is synced as it is written).
    out = tmp_path / "out"
    trace = tmp_path / "strace.log"
    r = coordinator.run(small_render_args(out), prefix=[
        "strace", "-f", "-qq", "-y", "-e", "trace=write,fsync,fdatasync", "-o", str(trace)])
    assert r.returncode == 0, r.stderr
    [journal] = (out / ".fc-master").glob("*.frames")
    assert len(journal.read_text().splitlines()) == 8
    # strace -y names each descriptor's file: "PID write(5</path/x.frames>, ...) = 30".
    target = "<%s>" % os.path.realpath(journal)
    calls = [line.split(None, 1)[1].split("(", 1)[0] for line in trace.read_text().splitlines()
             if "(" in line and target in line.split(",", 1)[0]]
    assert calls.count("write") == 8, calls
    last_write = len(calls) - 1 - calls[::-1].index("write")
    assert set(calls[last_write + 1:]) & {"fsync", "fdatasync"}, calls


def fnv1a64(data):
    """64-bit FNV-1a: how fc-master hashed a frame's pixels before 2026-12-04 (342cbf3)."""
    h = 14695981039346656037
    for byte in data:
        h = ((h ^ byte) * 1099511628211) & 0xFFFFFFFFFFFFFFFF
    return h


def test_resume_trusts_the_record_of_an_earlier_version(coordinator, coordinator_references,
                                                        tmp_path):
    out = tmp_path / "out"
    assert coordinator.run(small_render_args(out)).returncode == 0
    # The record as an earlier fc-master wrote it: "name hash", FNV-1a of the stored pixels
    # (8-bit RGB, rows top first), instead of "name w2 hash inputs", and the scene's contents
    # in the manifest instead of every frame's inputs.
    [journal] = (out / ".fc-master").glob("*.frames")
    lines = journal.read_text().splitlines()
    assert lines and all(len(line.split(" ")) == 4 and line.split(" ")[1] == "w2"
                         for line in lines), lines
    journal.write_text("".join("%s %016x\n" % (name, fnv1a64(load_rgb(out / name).tobytes()))
                               for name in (line.split(" ")[0] for line in lines)))
    [manifest] = (out / ".fc-master").glob("*.manifest")
    with open(os.path.join(COORDINATOR_SCENES, SCENE), "rb") as f:
        scene_hash = fnv1a64(f.read())
    manifest.write_text(manifest.read_text() + "scene contents\t%016x\n" % scene_hash)
    assert_resume_renders_damaged_frames_again(coordinator, coordinator_references, tmp_path,
                                               out)


def test_resume_without_record_checks_each_frame(coordinator, coordinator_references,
                                                 tmp_path):
    # Frames that fc-master has no record of (one POV-Ray process wrote them, say) are kept
    # when they decode completely; a short one is rendered again.
    out = tmp_path / "out"
    out.mkdir()
    single = subprocess.run([coordinator_renderer(), SCENE, "-D", "+FT", "-UA",
                             "+O%s/moving" % out] + SMALL, cwd=COORDINATOR_SCENES,
                            capture_output=True, text=True, timeout=120)
    assert single.returncode == 0, single.stderr
    cut = out / "moving3.tga"
    cut.write_bytes(cut.read_bytes()[:1000])
    stats = tmp_path / "stats.json"
    r = coordinator.run(["--no-fc", "--slaves", "2", "--stats", str(stats), SCENE] + SMALL +
                        ["-o", str(out)])
    assert r.returncode == 0, r.stderr
    assert "moving3.tga" in r.stderr and "keeping 7 frame(s)" in r.stderr, r.stderr
    s = coordinator_stats(stats)
    assert s["frames_resumed"] == 7 and s["frames_rendered"] == 1
    assert_frames_exact(out, coordinator_references.frames(SCENE, SMALL))


# --- one master per output directory, one render per manifest --------------------------------

def test_second_master_on_same_directory_is_refused(coordinator, coordinator_references,
                                                    tmp_path):
    out = tmp_path / "out"
    first = coordinator.start(["--no-fc", "--quiet", "--division", "sequence", "--slaves", "2",
                               SCENE] + SLOW + ["-o", str(out)])
    wait_for_frames(out, 1, first)
    r = coordinator.run(["--no-fc", "--quiet", SCENE] + SLOW + ["-o", str(out)])
    # Invariant: two masters never write the same frames; the second says who holds them.
    assert r.returncode == 1
    assert "another fc-master (pid %d)" % first.pid in r.stderr, r.stderr
    _, err = first.communicate(timeout=120)
    assert first.returncode == 0, err
    assert_frames_exact(out, coordinator_references.frames(SCENE, SLOW))
    assert coordinator.wait_no_processes() == []


def test_changed_options_are_refused_unless_forced(coordinator, coordinator_references,
                                                   tmp_path):
    out = tmp_path / "out"
    assert coordinator.run(["--no-fc", "--quiet", SCENE] + SMALL + ["-o", str(out)]).returncode == 0
    mtimes = {f: os.stat(out / f).st_mtime_ns for f in frame_files(out)}
    changed = SMALL + ["+A0.1", "+AM2"]
    r = coordinator.run(["--no-fc", "--quiet", SCENE] + changed + ["-o", str(out)])
    # Invariant: frames of other settings are never mixed with new ones.
    assert r.returncode == 1
    assert "Antialias" in r.stderr and "--force" in r.stderr, r.stderr
    assert {f: os.stat(out / f).st_mtime_ns for f in frame_files(out)} == mtimes
    r = coordinator.run(["--no-fc", "--quiet", "--force", SCENE] + changed + ["-o", str(out)])
    assert r.returncode == 0, r.stderr
    assert_frames_exact(out, coordinator_references.frames(SCENE, changed))
    # A subset of the same animation is the same render: it resumes.
    r = coordinator.run(["--no-fc", SCENE] + changed + ["+SF2", "+EF4", "-o", str(out)])
    assert r.returncode == 0 and "nothing to render" in r.stderr, r.stderr


def test_changed_scene_renders_its_frames_again(coordinator, coordinator_references, tmp_path):
    scene = tmp_path / "scene.pov"
    with open(os.path.join(COORDINATOR_SCENES, "moving.pov")) as f:
        scene.write_text(f.read())
    out = tmp_path / "out"
    args = ["--no-fc", str(scene)] + SMALL + ["-o", str(out)]
    assert coordinator.run(args).returncode == 0
    # Unchanged inputs: nothing is rendered again.
    r = coordinator.run(args)
    assert r.returncode == 0 and "nothing to render" in r.stderr, r.stderr
    # The scene every frame read changed: every frame is rendered again, no --force needed
    # (an earlier version refused until --force).
    scene.write_text(scene.read_text().replace("color rgb <0.9, 0.3, 0.2>",
                                               "color rgb <0.2, 0.3, 0.9>"))
    r = coordinator.run(args)
    assert r.returncode == 0, r.stderr
    assert "rendering 8 frame(s) again: its inputs changed: %s" % scene in r.stderr, r.stderr
    assert_frames_exact(out, coordinator_references.frames(str(scene), SMALL))


def test_changed_include_renders_exactly_the_frames_that_read_it(coordinator, tmp_path):
    # Frames 5-8 include late.inc, frames 1-4 do not: an edit of late.inc renders 5-8 again.
    scene = tmp_path / "scene.pov"
    with open(os.path.join(COORDINATOR_SCENES, "moving.pov")) as f:
        scene.write_text(f.read() + '#if (frame_number >= 5) #include "late.inc" #end\n')
    late = tmp_path / "late.inc"
    late.write_text("sphere { <1, 2, 0>, 0.3 pigment { color rgb <1, 1, 0> } }\n")
    out = tmp_path / "out"
    stats = tmp_path / "stats.json"
    args = ["--no-fc", "--stats", str(stats), str(scene)] + SMALL + ["-o", str(out)]
    assert coordinator.run(args, cwd=tmp_path).returncode == 0
    [inputs] = (out / ".fc-master").glob("*.inputs")
    # The renderers reported what each frame's parse read (the frame record's reads section).
    assert str(late) in inputs.read_text(), inputs.read_text()
    late.write_text("sphere { <1, 2, 0>, 0.3 pigment { color rgb <0, 1, 1> } }\n")
    r = coordinator.run(args, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert "rendering 4 frame(s) again: its inputs changed: %s" % late in r.stderr, r.stderr
    s = coordinator_stats(stats)
    assert s["frames_resumed"] == 4 and s["frames_rendered"] == 4, s
    assert [f["frame"] for f in s["frames"] if not f["resumed"]] == [5, 6, 7, 8]


def test_include_with_a_line_break_in_its_name_is_never_trusted(coordinator, tmp_path):
    # Frames 5-8 include a file named "col<LF>F<TAB>x.inc": its name must not pass for the
    # files "col" and "x.inc" (an edit of the real file would then be missed on resume).
    scene = tmp_path / "scene.pov"
    with open(os.path.join(COORDINATOR_SCENES, "moving.pov")) as f:
        scene.write_text(f.read() + '#if (frame_number >= 5) '
                         '#include concat("col", chr(10), "F", chr(9), "x.inc") #end\n')
    (tmp_path / "col\nF\tx.inc").write_text("sphere { <1, 2, 0>, 0.3 pigment { rgb 1 } }\n")
    for decoy in ("col", "x.inc"):      # what a split name would hash, and trust
        (tmp_path / decoy).write_text("// not read by the scene\n")
    out = tmp_path / "out"
    stats = tmp_path / "stats.json"
    args = ["--no-fc", "--stats", str(stats), str(scene)] + SMALL + ["-o", str(out)]
    first = coordinator.run(args, cwd=tmp_path)
    assert first.returncode == 0, first.stderr
    assert "frame 5 from host" in first.stderr and "has a line break" in first.stderr, \
        first.stderr
    # Unknown inputs are never trusted: the same command renders those frames again, and
    # says why.
    r = coordinator.run(args, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert "rendering 4 frame(s) again: what it read could not be recorded when it was rendered" \
        in r.stderr, r.stderr
    s = coordinator_stats(stats)
    assert [f["frame"] for f in s["frames"] if not f["resumed"]] == [5, 6, 7, 8], s


def fresh_frames(scene, options, cwd, out):
    """One POV-Ray process's frames of scene, rendered in cwd (where its relative files are):
    {file name: pixels}."""
    out.mkdir()
    argv = [coordinator_renderer(), str(scene), "-D", "+FT", "-UA",
            "+O%s/%s" % (out, scene.stem)] + list(options)
    r = subprocess.run(argv, cwd=cwd, capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, "reference render failed:\n" + r.stderr[-3000:]
    return {f: load_rgb(out / f) for f in sorted(os.listdir(out))}


def rendered_again_after_edit(coordinator, tmp_path, late_sdl, edit, fc=False):
    """Render moving.pov with late_sdl added for frames 5-8 (scene.pov in tmp_path, which is
    the master's directory), run the same command again (nothing may render), edit(), and run
    it once more. Returns the last run's stderr and statistics, after checking that every
    frame equals a fresh render of the edited scene and that the edit shows in frames 5-8
    only."""
    scene = tmp_path / "scene.pov"
    with open(os.path.join(COORDINATOR_SCENES, "moving.pov")) as f:
        scene.write_text(f.read() + "#if (frame_number >= 5)\n" + late_sdl + "\n#end\n")
    out = tmp_path / "out"
    stats = tmp_path / "stats.json"
    args = ([] if fc else ["--no-fc"]) + ["--stats", str(stats), str(scene)] + SMALL + \
        ["-o", str(out)]
    r = coordinator.run(args, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    # Invariant: unchanged inputs render nothing again.
    r = coordinator.run(args, cwd=tmp_path)
    assert r.returncode == 0 and "nothing to render" in r.stderr, r.stderr
    before = {f: load_rgb(out / f) for f in frame_files(out)}
    edit()
    r = coordinator.run(args, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    # Invariant: after the edit every frame is the edited scene's, kept or rendered again.
    after = fresh_frames(scene, SMALL, tmp_path, tmp_path / "fresh")
    assert_frames_exact(out, after)
    assert [f for f in sorted(after) if not (after[f] == before[f]).all()] == \
        ["scene%d.tga" % n for n in (5, 6, 7, 8)]
    return r.stderr, coordinator_stats(stats)


def assert_rendered_again_exactly(stderr, stats, frames, path):
    assert "rendering %d frame(s) again: its inputs changed: %s" % (len(frames), path) \
        in stderr, stderr
    assert stats["frames_rendered"] == len(frames), stats
    assert [f["frame"] for f in stats["frames"] if not f["resumed"]] == frames


def write_png(path, pixels):
    import OpenImageIO as oiio
    png = oiio.ImageOutput.create("png")
    height, width = pixels.shape[:2]
    assert png.open(str(path), oiio.ImageSpec(width, height, 3, "uint8"))
    assert png.write_image(pixels) and png.close()


def test_edited_image_map_renders_exactly_the_frames_that_use_it(coordinator, tmp_path):
    # Frames 5-8 map tex.png onto a box (with frame coherence, fc-master's default): a new
    # picture in it renders 5-8 again, and 1-4, which never read it, stay.
    tex = tmp_path / "tex.png"
    ramp = np.zeros((16, 16, 3), np.uint8)
    ramp[:, :, 0] = np.arange(16, dtype=np.uint8)[None, :] * 16
    write_png(tex, ramp)
    late = ('box { <0, 0, 0>, <1, 1, 0.2> scale 1.4 translate <0.6, 0.2, -1> '
            'pigment { image_map { png "tex.png" } } }')
    stderr, stats = rendered_again_after_edit(
        coordinator, tmp_path, late, lambda: write_png(tex, 255 - ramp), fc=True)
    assert_rendered_again_exactly(stderr, stats, [5, 6, 7, 8], tex)


def test_edited_font_renders_exactly_the_frames_that_use_it(coordinator, tmp_path):
    # Frames 5-8 write text in font.ttf: another typeface under that name renders 5-8 again.
    font = tmp_path / "font.ttf"
    font.write_bytes(open("/usr/share/povray-3.7/include/timrom.ttf", "rb").read())
    late = ('text { ttf "font.ttf" "fc" 0.2, 0 scale 0.9 translate <0.4, 0.3, -1.5> '
            'pigment { color rgb <1, 1, 0.2> } }')
    stderr, stats = rendered_again_after_edit(
        coordinator, tmp_path, late,
        lambda: font.write_bytes(open("/usr/share/povray-3.7/include/cyrvetic.ttf",
                                      "rb").read()))
    assert_rendered_again_exactly(stderr, stats, [5, 6, 7, 8], font)


def test_file_created_where_file_exists_looked_renders_those_frames(coordinator, tmp_path):
    # Frames 5-8 include extra.inc when it exists; it does not at first. Created, it makes
    # exactly those frames render again (1-4 never looked for it).
    extra = tmp_path / "extra.inc"
    late = '#if (file_exists("extra.inc")) #include "extra.inc" #end'
    stderr, stats = rendered_again_after_edit(
        coordinator, tmp_path, late,
        lambda: extra.write_text("sphere { <1, 2, 0>, 0.3 pigment { color rgb <0, 1, 1> } }\n"))
    assert_rendered_again_exactly(stderr, stats, [5, 6, 7, 8], extra)


def file_kind(path):
    """What OpenImageIO says a file is: format, channels, bits per sample, compression."""
    import OpenImageIO as oiio
    inp = oiio.ImageInput.open(str(path))
    assert inp, oiio.geterror()
    spec = inp.spec()
    kind = (inp.format_name(), spec.nchannels, str(spec.format),
            spec.get_string_attribute("compression"),
            spec.get_int_attribute("oiio:BitsPerSample"))
    inp.close()
    return kind


# --- output formats ---------------------------------------------------------------------------

FORMATS = {
    "png": (["+FN"], ".png", "uint8"),
    "png16": (["+FN16"], ".png", "uint16"),
    "png12": (["+FN12"], ".png", "uint16"),
    "png5": (["+FN5"], ".png", "uint8"),
    "exr": (["+FE"], ".exr", "half"),
    "rle-targa": (["+FC"], ".tga", "uint8"),
}


# Frame division assembles tiles and encodes them with OpenImageIO; sequence division gets
# whole frames, stored as the file POV-Ray's writer made of each (OpenEXR's are
# encoded as tiles are).
@pytest.mark.parametrize("division", ["frame", "sequence"])
@pytest.mark.parametrize("name", sorted(FORMATS))
def test_output_format_as_povray_writes_it(coordinator, coordinator_references, tmp_path,
                                           name, division):
    fmt, ext, pixel_type = FORMATS[name]
    opts = SMALL + ["+A0.1", "+AM1"] + fmt
    out = tmp_path / "out"
    r = coordinator.run(["--quiet", "--division", division, "--tile", "48", "--slaves", "2",
                         SCENE] + opts + ["-o", str(out)])
    assert r.returncode == 0, r.stderr
    ref = coordinator_references.frames(SCENE, opts, pixel_type)
    assert frame_files(out) == sorted(ref) and all(f.endswith(ext) for f in ref), ref
    for f, want in ref.items():
        got = load_rgb(out / f, pixel_type)
        # Invariant: the same file type, bit depth and pixels as one POV-Ray process's.
        assert got.dtype == want.dtype and (got == want).all(), f
        assert file_kind(out / f) == file_kind(coordinator_references.path(SCENE, opts, f)), f


def file_metadata(path):
    """What OpenImageIO reads from a file's header and footer, but the time it was written:
    for Targa POV-Ray's software line, platform, gamma and Targa version."""
    import OpenImageIO as oiio
    inp = oiio.ImageInput.open(str(path))
    assert inp, oiio.geterror()
    spec = inp.spec()
    meta = {a.name: spec.getattribute(a.name) for a in spec.extra_attribs if a.name != "DateTime"}
    inp.close()
    return meta


# An assembled Targa frame is encoded by POV-Ray's own writer (fc-image-writer), with the
# gamma the renderer's file records, so it is the file one POV-Ray process writes
# but for the time in its footer; and the master never loads OpenImageIO for it.
@pytest.mark.parametrize("fmt", [["+FT"], ["+FC", "File_Gamma=1.8"]], ids=["targa", "rle-gamma-1.8"])
def test_assembled_targa_is_povrays_own_file(coordinator, coordinator_references, tmp_path, fmt):
    opts = SMALL + fmt
    out = tmp_path / "out"
    r = coordinator.run(["--quiet", "--division", "frame", "--tile", "48", "--slaves", "2",
                         SCENE] + opts + ["-o", str(out)])
    assert r.returncode == 0, r.stderr
    assert "warning" not in r.stderr, r.stderr
    ref = coordinator_references.frames(SCENE, opts)
    assert_frames_exact(out, ref)
    trace = coordinator.debug_log.read_text()
    assert "fc-image-writer" in trace and "loading OpenImageIO" not in trace, trace[-3000:]
    for f in ref:
        mine, povrays = out / f, coordinator_references.path(SCENE, opts, f)
        assert file_metadata(mine) == file_metadata(povrays), f
        assert os.path.getsize(mine) == os.path.getsize(povrays), f


# Should fc-image-writer fail, OpenImageIO encodes the frames: same pixels, one warning.
def test_failing_image_writer_falls_back_to_openimageio(coordinator, coordinator_references,
                                                        tmp_path):
    out = tmp_path / "out"
    argv = [str(master_with_failing_image_writer(tmp_path)), "--quiet", "--division", "frame",
            "--tile", "48", "--slaves", "2", "--povray", coordinator_renderer(), SCENE] + SMALL + \
        ["-o", str(out)]
    r = subprocess.run(argv, cwd=COORDINATOR_SCENES, env=coordinator.env(), capture_output=True,
                       text=True, timeout=90)
    assert r.returncode == 0, r.stderr
    assert r.stderr.count("encoding Targa frames with OpenImageIO") == 1, r.stderr
    assert "cannot encode today" in r.stderr, r.stderr
    assert_frames_exact(out, coordinator_references.frames(SCENE, SMALL))


# Diffusion dithering has one implementation, POV-Ray's own in fc-image-writer: without it a
# frame assembled from tiles cannot be dithered, and the run stops saying why, with no frame
# file written.
def test_failing_image_writer_stops_diffusion_dithering(coordinator, tmp_path):
    out = tmp_path / "out"
    argv = [str(master_with_failing_image_writer(tmp_path)), "--quiet", "--division", "frame",
            "--tile", "48", "--slaves", "2", "--povray", coordinator_renderer(), SCENE] + SMALL + \
        ["Dither=on", "-o", str(out)]
    r = subprocess.run(argv, cwd=COORDINATOR_SCENES, env=coordinator.env(), capture_output=True,
                       text=True, timeout=90)
    assert r.returncode == 1, r.stderr
    assert "cannot write frame 1: diffusion dithering: " in r.stderr, r.stderr
    assert "cannot encode today" in r.stderr, r.stderr
    assert not list(out.glob("*.tga"))


def test_image_writer_refuses_malformed_requests(tmp_path):
    writer = os.path.join(os.path.dirname(coordinator_renderer()), "fc-image-writer")
    r = subprocess.run([writer, "extra"], capture_output=True, text=True)
    assert r.returncode == 2 and "fc-master runs it" in r.stderr
    # Without its descriptors it says so.
    r = subprocess.run([writer], capture_output=True, text=True, timeout=10)
    assert r.returncode == 1 and "descriptor 3" in r.stderr, r.stderr
    req_r, req_w = os.pipe()
    rep_r, rep_w = os.pipe()
    os.write(req_w, b"not a request at all, no" * 4)    # longer than a request
    os.close(req_w)

    def fds():
        os.dup2(req_r, 3)
        os.dup2(rep_w, 4)
    r = subprocess.run([writer], capture_output=True, text=True, preexec_fn=fds, close_fds=False,
                       timeout=10)
    os.close(req_r)
    os.close(rep_w)
    assert r.returncode == 1 and "malformed request" in r.stderr, r.stderr
    assert os.read(rep_r, 100) == b""
    os.close(rep_r)


OUTPUT_NAMES = {
    # The names and format one povray-fc process gives the frames: +Orenders/clk.png names PNG
    # frames clk1.png ...; with no format named, POV-Ray's povray.ini chooses it (Debian's:
    # PNG), not the name; Targa named keeps a foreign extension and adds its own.
    "png-named": ["+FN", "+Orenders/clk.png"],
    "format-from-povray-ini": ["+Orenders/clk.png"],
    "exr-named": ["+FE", "+Orenders/clk.exr"],
    "foreign-extension": ["+Orenders/clk.exr"],
    "targa-named": ["+FT", "+Orenders/clk.png"],
}


@pytest.mark.parametrize("name", sorted(OUTPUT_NAMES))
def test_output_names_and_format_as_povray_fc(coordinator, tmp_path, name):
    opts = SMALL[1:] + OUTPUT_NAMES[name]   # no +FT: the options alone name the format
    scene = os.path.join(COORDINATOR_SCENES, SCENE)
    single, master = tmp_path / "single", tmp_path / "master"
    (single / "renders").mkdir(parents=True)      # POV-Ray does not create it
    master.mkdir()
    r = subprocess.run([coordinator_renderer(), scene, "-D"] + opts, cwd=single,
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr[-2000:]
    want = sorted(os.listdir(single / "renders"))
    assert len(want) == 8, want
    # From another directory, without -o: the frames go where POV-Ray would write them.
    r = coordinator.run(["--no-fc", "--quiet", scene] + opts, cwd=master)
    assert r.returncode == 0, r.stderr
    assert frame_files(master / "renders") == want
    for f in want:
        pixel_type = "half" if f.endswith(".exr") else "uint8"
        got = load_rgb(master / "renders" / f, pixel_type)
        assert (got == load_rgb(single / "renders" / f, pixel_type)).all(), f


@pytest.mark.parametrize("opt,words", [
    ("+FJ", ["JPEG", "+FN"]),
    ("+FB", ["BMP", "+FE"]),
    ("+UA", ["Output_Alpha"]),
], ids=["jpeg", "bmp", "alpha"])
def test_unsupported_output_is_refused(coordinator, tmp_path, opt, words):
    out = tmp_path / "out"
    r = coordinator.run(["--no-fc", SCENE] + SMALL + [opt, "-o", str(out)])
    # Invariant: what fc-master cannot write is refused, in one line saying what works.
    assert r.returncode == 1
    for w in words:
        assert w in r.stderr, r.stderr
    assert not out.exists() or frame_files(out) == []
    assert coordinator.wait_no_processes() == []


# --- the live preview -------------------------------------------------------------------------

# Sequence division has not loaded OpenImageIO when the preview is first due: it loads then,
# in the background, and the preview follows.
@pytest.mark.parametrize("division", ["frame", "sequence"])
def test_preview_while_rendering(coordinator, coordinator_references, tmp_path, division):
    out = tmp_path / "out"
    ref = coordinator_references.frames(SCENE, LONG_COORDINATOR_RENDER)
    # On one processor the render lasts well beyond the preview's first write (5 s in).
    p = coordinator.start(["--no-fc", "--quiet", "--division", division, "--slaves", "2", SCENE] +
                          LONG_COORDINATOR_RENDER + ["-o", str(out)], prefix=["taskset", "-c", "0"])
    latest = out / "preview" / "latest.png"
    deadline = time.time() + 60
    while not latest.exists():
        assert time.time() < deadline and p.poll() is None, "no preview while rendering"
        time.sleep(0.05)
    during = load_rgb(latest)
    still_running = p.poll() is None
    _, err = p.communicate(timeout=120)
    assert p.returncode == 0, err
    # Invariant: the preview appears while the render runs and shows a finished frame.
    assert still_running
    assert any((during == want).all() for want in ref.values())
    sheet = load_rgb(out / "preview" / "contact-sheet.png")
    # 24 frames of 320x240, halved: 160x120 thumbnails in rows of 6 (about 16:9).
    assert sheet.shape == (4 * 120, 6 * 160, 3), sheet.shape
    for k, name in enumerate(sorted(ref)):
        want = ref[name].astype(float).reshape(120, 2, 160, 2, 3).mean(axis=(1, 3))
        cell = sheet[(k // 6) * 120:(k // 6 + 1) * 120, (k % 6) * 160:(k % 6 + 1) * 160]
        # Invariant: the sheet holds every frame, in order, reduced.
        assert np.abs(cell - want).max() <= 1, name
    assert_frames_exact(out, ref)


def test_short_render_writes_no_preview(coordinator, coordinator_references, tmp_path):
    out = tmp_path / "out"
    r = coordinator.run(["--quiet", "--slaves", "2", SCENE] + SMALL + ["-o", str(out)])
    assert r.returncode == 0, r.stderr
    # Invariant: a render over before the preview's first write is due encodes no preview.
    assert not (out / "preview").exists()
    assert_frames_exact(out, coordinator_references.frames(SCENE, SMALL))


def test_preview_left_by_earlier_run_is_brought_up_to_date(coordinator, coordinator_references,
                                                           tmp_path):
    out = tmp_path / "out"
    ref = coordinator_references.frames(SCENE, SMALL)
    stale = np.zeros((120, 160, 3), np.uint8)
    (out / "preview").mkdir(parents=True)
    import OpenImageIO as oiio
    png = oiio.ImageOutput.create("png")
    assert png.open(str(out / "preview" / "latest.png"), oiio.ImageSpec(160, 120, 3, "uint8"))
    assert png.write_image(stale) and png.close()
    r = coordinator.run(["--quiet", "--division", "sequence", "--slaves", "1", SCENE] + SMALL
                        + ["-o", str(out)])
    assert r.returncode == 0, r.stderr
    # Invariant: preview files that exist show this render at its end, however short it was.
    assert (load_rgb(out / "preview" / "latest.png") == ref[sorted(ref)[-1]]).all()
    assert load_rgb(out / "preview" / "contact-sheet.png").shape[2] == 3
    assert_frames_exact(out, ref)
