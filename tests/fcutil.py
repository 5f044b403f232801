"""Shared helpers for povray-fc's integration tests: run renders, read and compare pixels.

Where the programs are and how a frame's pixels are read is the scripts' shared module
(scripts/fcscript.py), so that tests and scripts read images one way."""
import subprocess
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "scripts"))
from fcscript import BIN, DEBIAN_POVRAY, POVRAY_FC, TOP, read_pixels  # noqa: E402,F401

SCENES = TOP / "scenes"
# Options for scenes/coordinator-test/moving.pov that keep fc-master busy for a while: about
# 11 s on one processor of the 2026-12-04 (17305d6) machine (24 frames, deep anti-aliasing).
# For tests that act while a render runs (a preview's first write 5 s in, a host added 1 s
# in); shorter renders ended too close to those moments on a fast machine.
LONG_COORDINATOR_RENDER = ["+FT", "+W320", "+H240", "+KFI1", "+KFF24", "+A0.1", "+AM2", "+R4"]


def render(binary, scene, out_file, *options, cwd=None, timeout=600, threads=None, env=None):
    """Render `scene` with `binary` into `out_file` (Targa); returns the CompletedProcess.

    Display and pause are off and the render runs without a terminal, as in CI.
    """
    args = [str(binary), f"+I{scene}", f"+O{out_file}", "+FT", "-D", "-P", "-V"]
    if threads is not None:
        args.append(f"+WT{threads}")
    args += list(options)
    return subprocess.run(args, cwd=cwd or Path(scene).parent, capture_output=True,
                          text=True, timeout=timeout, stdin=subprocess.DEVNULL, env=env)


def files_below(top):
    """Every file below the directory top, as paths relative to it."""
    top = Path(top)
    return {p.relative_to(top).as_posix() for p in top.rglob("*") if p.is_file()}


def pixel_difference(path_a, path_b):
    """(pixels that differ, largest channel difference) between two images of equal size."""
    a = read_pixels(path_a).astype(np.int16)
    b = read_pixels(path_b).astype(np.int16)
    if a.shape != b.shape:
        raise ValueError(f"size differs: {path_a} {a.shape} vs {path_b} {b.shape}")
    diff = np.abs(a - b)
    return int(np.count_nonzero(diff.max(axis=2))), int(diff.max())


def assert_same_pixels(path_a, path_b):
    differing, largest = pixel_difference(path_a, path_b)
    assert differing == 0, f"{path_a} vs {path_b}: {differing} pixels differ, by up to {largest}"
