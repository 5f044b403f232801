"""povray-fc loads SDL (its display) only when a display opens (speedups/sdl_on_demand.c).

Debian's libSDL-1.2 loads SDL2 and its libraries from a constructor, most of a short
process's start; povray-fc without a display must not pay it, with a display it must still
show one.
"""
import os
import subprocess

from fcutil import POVRAY_FC, SCENES, assert_same_pixels, render

TINY = SCENES / "tiny" / "tiny.pov"


def loaded_libraries(stderr):
    """Libraries the dynamic loader opened, from LD_DEBUG=files output."""
    return [line.split("file=", 1)[1].split()[0] for line in stderr.splitlines()
            if "file=" in line and "generating link map" in line]


def test_binary_needs_no_libsdl_and_defines_every_sdl_function_it_calls():
    dynamic = subprocess.run(["readelf", "-d", str(POVRAY_FC)], capture_output=True, text=True,
                             check=True).stdout
    assert "libSDL" not in dynamic
    # A new SDL call in a patch would pull libSDL back in, or leave the symbol undefined.
    undefined = subprocess.run(["nm", "-D", "--undefined-only", str(POVRAY_FC)],
                               capture_output=True, text=True, check=True).stdout
    assert "SDL_" not in undefined
    defined = subprocess.run(["nm", str(POVRAY_FC)], capture_output=True, text=True,
                             check=True).stdout
    assert " T SDL_Init" in defined and " T SDL_SetVideoMode" in defined


def test_render_without_display_loads_no_sdl(tmp_path):
    env = dict(os.environ, LD_DEBUG="files")
    done = render(POVRAY_FC, TINY, tmp_path / "t.tga", "+W16", "+H12", "-D", env=env)
    assert done.returncode == 0, done.stderr[-2000:]
    libraries = loaded_libraries(done.stderr)
    assert libraries, "LD_DEBUG=files printed no library: the check would see nothing"
    assert not [lib for lib in libraries if "SDL" in lib], libraries


def test_display_loads_sdl_and_renders_the_same_pixels(tmp_path):
    # SDL's dummy video driver: a display that needs no X server.
    env = dict(os.environ, LD_DEBUG="files", SDL_VIDEODRIVER="dummy")
    env.pop("DISPLAY", None)
    shown = render(POVRAY_FC, TINY, tmp_path / "shown.tga", "+W16", "+H12", "+D", env=env)
    assert shown.returncode == 0, shown.stderr[-2000:]
    libraries = loaded_libraries(shown.stderr)
    assert "libSDL-1.2.so.0" in libraries and "libSDL2-2.0.so.0" in libraries, libraries
    assert "Couldn't" not in shown.stderr     # SDL_Init and the video mode succeeded
    hidden = render(POVRAY_FC, TINY, tmp_path / "hidden.tga", "+W16", "+H12", "-D")
    assert hidden.returncode == 0, hidden.stderr[-2000:]
    assert_same_pixels(tmp_path / "shown.tga", tmp_path / "hidden.tga")
