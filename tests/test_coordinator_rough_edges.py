"""fc-master behaves as one povray-fc process with the same options would, and says what is
wrong in one line before anything renders: the format and names of the same INI, impossible
frames, mistakes on the command line, an output directory that cannot take frames, POV-Ray's
own word on a prohibited shell-out, and TMPDIR for its private files.
"""
import os
import subprocess

import pytest

from conftest import COORDINATOR_SCENES, coordinator_renderer, frame_files, load_rgb
from test_coordinator import SCENE

pytestmark = pytest.mark.usefixtures("coordinator_build")

TINY = ["+W64", "+H48", "+KFI1", "+KFF3"]


def povray_fc_files(tmp_path, args):
    """The files one povray-fc process writes for args (a copy of the scenes as cwd)."""
    work = tmp_path / "single"
    work.mkdir()
    for f in os.listdir(COORDINATOR_SCENES):
        (work / f).write_bytes(open(os.path.join(COORDINATOR_SCENES, f), "rb").read())
    before = set(os.listdir(work))
    r = subprocess.run([coordinator_renderer(), "-D"] + args, cwd=work, capture_output=True,
                       text=True, timeout=120)
    assert r.returncode == 0, r.stderr[-2000:]
    return work, sorted(set(os.listdir(work)) - before)


def test_same_ini_same_format_and_names_as_povray_fc(coordinator, tmp_path):
    # moving.ini names no format: POV-Ray's povray.ini decides, for both.
    work, single = povray_fc_files(tmp_path, ["moving.ini"])
    out = tmp_path / "out"
    r = coordinator.run(["--no-fc", "--quiet", "moving.ini", "-o", str(out)])
    assert r.returncode == 0, r.stderr
    assert frame_files(out) == single
    for name in single:
        assert (load_rgb(out / name) == load_rgb(work / name)).all(), name


@pytest.mark.parametrize("size, words", [
    (["+W70000", "+H10", "+FT"], "a Targa frame holds at most 65535 pixels a side, not "
                                 "70000x10: use PNG (+FN) or OpenEXR (+FE)"),
    (["+W100000", "+H100000", "+FN"], "a frame of 100000x100000 pixels needs"),
])
def test_impossible_frames_are_refused_before_rendering(coordinator, tmp_path, size, words):
    out = tmp_path / "out"
    r = coordinator.run(["--no-fc", SCENE] + size + ["-o", str(out)])
    assert r.returncode == 1, r.stderr
    assert r.stderr.startswith("fc-master: " + words), r.stderr
    assert len(r.stderr.splitlines()) == 1, r.stderr
    assert not out.exists()
    assert coordinator.wait_no_processes() == []


@pytest.mark.parametrize("args, line", [
    (["nosuch.ini", SCENE], "fc-master: nosuch.ini: No such file or directory (an INI file "
                            "or scene named on the command line)"),
    ([SCENE, "+Qx9"], "fc-master: POV-Ray does not take the option +Qx9 (\"Failed to parse "
                      "command-line option\")"),
])
def test_a_bad_povray_option_is_named(coordinator, tmp_path, args, line):
    r = coordinator.run(["--no-fc"] + args + TINY + ["-o", str(tmp_path / "out")])
    assert r.returncode == 1
    assert r.stderr.splitlines() == [line], r.stderr


def test_a_repeated_output_does_not_take_the_scene(coordinator, tmp_path):
    r = coordinator.run(["-o", str(tmp_path / "a"), "-o", SCENE] + TINY)
    assert r.returncode == 2
    assert r.stderr.splitlines()[0] == "fc-master: -o given twice (%s, then %s)" % (
        tmp_path / "a", SCENE), r.stderr


def test_a_hostfile_without_hosts_is_an_error(coordinator, tmp_path):
    hosts = tmp_path / "hosts"
    hosts.write_text("# no host yet\n")
    r = coordinator.run(["--hostfile", str(hosts), SCENE] + TINY + ["-o", str(tmp_path / "o")])
    assert r.returncode == 2
    assert "--hostfile %s names no host" % hosts in r.stderr, r.stderr


@pytest.mark.skipif(os.geteuid() != 0, reason="needs root for mounts")
def test_output_directory_itself_must_take_files(coordinator, tmp_path):
    # The directory is read-only while its record folder is writable (another file system
    # mounted on it): refused before rendering, not at the first frame.
    out = tmp_path / "out"
    out.mkdir()
    subprocess.run(["mount", "-t", "tmpfs", "-o", "size=1m", "tmpfs", str(out)], check=True)
    try:
        (out / ".fc-master").mkdir()
        subprocess.run(["mount", "-t", "tmpfs", "-o", "size=1m", "tmpfs",
                        str(out / ".fc-master")], check=True)
        subprocess.run(["mount", "-o", "remount,ro", str(out)], check=True)
        r = coordinator.run(["--no-fc", SCENE, "+FT"] + TINY + ["-o", str(out)])
        assert r.returncode == 1
        assert r.stderr.splitlines() == [
            "fc-master: output directory %s is not writable: create %s/.fc-master-write-test-%s: "
            "Read-only file system" % (out, out, r.stderr.split("write-test-")[1].split(":")[0])
        ], r.stderr
    finally:
        subprocess.run(["umount", "-l", str(out / ".fc-master")])
        subprocess.run(["umount", "-l", str(out)])
    assert coordinator.wait_no_processes() == []


def test_prohibited_frame_command_says_so_once(coordinator, tmp_path):
    # Debian's povray.conf forbids shell-outs: POV-Ray says so and renders on (the command's
    # return action is to ignore its failure); fc-master says it once, not once a frame.
    ini = tmp_path / "frames.ini"
    ini.write_text("Pre_Frame_Command=touch %s\n" % (tmp_path / "ran"))
    out = tmp_path / "out"
    r = coordinator.run(["--no-fc", SCENE, str(ini), "+FT"] + TINY + ["-o", str(out)])
    assert r.returncode == 0, r.stderr
    said = [line for line in r.stderr.splitlines() if "prohibited" in line]
    assert said == ["fc-master: Execution of shellout 'touch' prohibited (povray.conf's "
                    "[Shellout Security])"], r.stderr
    assert len(frame_files(out)) == 3 and not (tmp_path / "ran").exists()


def test_private_files_go_to_tmpdir(coordinator, tmp_path):
    # With /tmp full there is a way out: TMPDIR, for fc-master's probes, its private pvmd and
    # the slaves' working directories.
    tmpdir = tmp_path / "tmpdir"
    tmpdir.mkdir()
    trace = tmp_path / "strace.log"
    out = tmp_path / "out"
    r = coordinator.run(["--no-fc", SCENE, "+FT"] + TINY + ["-o", str(out)],
                        env={"TMPDIR": str(tmpdir)},
                        prefix=["strace", "-f", "-qq", "-e", "trace=mkdir", "-o", str(trace)])
    assert r.returncode == 0, r.stderr
    made = [line for line in trace.read_text().splitlines() if "mkdir(" in line and "= 0" in line]
    mine = [line for line in made if "/fc-" in line]
    assert any('"%s/fc-master-' % tmpdir in line for line in mine), made
    assert any('"%s/fc-pvm-' % tmpdir in line for line in mine), made
    assert any('"%s/fc-slave-' % tmpdir in line for line in mine), made
    assert not any('"/tmp/fc-' in line for line in mine), mine
