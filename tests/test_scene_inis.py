"""The scene INIs work from any checkout and any directory, as their comments say.

Each INI's comment gives the command that renders it "from the top of a checkout". The test
runs that command, word for word (plus options that make it small), in a copy of the scenes
at another path, and compares every frame on pixels with a render of the original scene.
"""
import re
import shutil
import subprocess

import pytest

from fcutil import BIN, POVRAY_FC, SCENES, files_below, read_pixels

# INIs a user renders by hand; each documents its command.
DOCUMENTED = ["demo/demo.ini", "newton/newton.ini", "newton/newton-hd.ini", "bounce/bounce.ini"]
# Appended to the documented command (later options win): small, three frames.
SMALL = ["+W64", "+H48", "+SF1", "+EF3", "-V"]


def documented_command(ini):
    """The shell command after "from the top of a checkout:" in ini's comment."""
    lines = ini.read_text().splitlines()
    start = next((i for i, line in enumerate(lines)
                  if line.startswith(";") and "top of a checkout:" in line), None)
    assert start is not None, f"{ini}: no command 'from the top of a checkout:' in its comment"
    command = []
    for line in lines[start + 1:]:
        assert line.startswith(";   "), f"{ini}: command ends without its last line"
        command.append(line[1:].strip())
        if not line.endswith("\\"):
            break
    return "\n".join(command)


@pytest.mark.parametrize("ini", sorted(p.relative_to(SCENES).as_posix()
                                       for p in SCENES.glob("*/*.ini")))
def test_ini_names_no_absolute_path(ini):
    # An absolute path (in a setting, or in the command of a comment) ties the INI to
    # one checkout. Two components at least: a bare "/tmp" is a mention, not a path.
    text = (SCENES / ini).read_text()
    found = re.findall(r"(?:^|[\s=;\"']|\+[A-Za-z]{1,2})(/[\w.-]+(?:/[\w.-]+)+)", text,
                       re.MULTILINE)
    assert not found, f"{ini}: absolute paths {found}"


@pytest.mark.parametrize("ini", DOCUMENTED)
def test_documented_command_works_in_another_checkout(ini, tmp_path):
    assert POVRAY_FC.is_file(), "build povray-fc first (make)"
    ini = SCENES / ini
    command = documented_command(ini)
    # Another checkout: the scenes copied to another path, the same binaries.
    other = tmp_path / "other checkout"
    shutil.copytree(SCENES, other / "scenes")
    (other / "build").mkdir()
    (other / "build" / "bin").symlink_to(BIN)
    copied = files_below(other / "scenes")
    done = subprocess.run(["sh", "-ec", command + " " + " ".join(SMALL)], cwd=other,
                          capture_output=True, text=True, timeout=300,
                          stdin=subprocess.DEVNULL)
    assert done.returncode == 0, f"{command}\n{done.stderr[-3000:]}"
    outdir = re.search(r"mkdir -p (\S+)", command).group(1)
    got = sorted((other / outdir).glob("*.tga"))
    assert len(got) == 3, (command, [p.name for p in (other / outdir).iterdir()])

    # The same options on the original scene, rendered from a third directory.
    scene = re.search(r"\+I\S*/scenes/(\S+\.pov)", command).group(1)
    stem = re.search(r"\+O(\S+)", command).group(1)
    extra = [w for w in command.split() if w.startswith("+") and w[1] not in "IO"]
    ref = tmp_path / "reference"
    ref.mkdir()
    r = subprocess.run([str(POVRAY_FC), str(ini), f"+I{SCENES / scene}", f"+O{stem}"] + extra +
                       SMALL, cwd=ref, capture_output=True, text=True, timeout=300,
                       stdin=subprocess.DEVNULL)
    assert r.returncode == 0, r.stderr[-3000:]
    want = sorted(ref.glob("*.tga"))
    assert [p.name for p in got] == [p.name for p in want]
    for a, b in zip(got, want):
        pa, pb = read_pixels(a), read_pixels(b)
        assert pa.shape == (48, 64, 3) and (pa == pb).all(), a.name
    # Nothing was written next to the copied scenes (compared with the copy itself, so that
    # what another test left in the original tree is not blamed on this command).
    assert files_below(other / "scenes") == copied
