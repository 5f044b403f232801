"""Lexeme replay (patches 0452-0460, speedups/) replays the tokens of loop and macro bodies: a
parse must come out as a plain one.

Each scene below reads every kind of token inside #while, #for and macro bodies (numbers
of every form, symbols, array elements, vector components, directives, comments, strings,
skipped #if branches, a macro from another file, a file included on some passes, bodies
longer than the stream's buffer, CRLF line ends) and prints what it computed with #debug. povray-fc must render the same
pixels and print the same debug text as Debian's povray, which reads every pass afresh;
an error on a later pass must be reported at the same line and column.
"""
import re

import pytest

from fcutil import DEBIAN_POVRAY, POVRAY_FC, assert_same_pixels, render

INCLUDE = """// a macro in another file: each call opens the file anew
#macro Ring(N, R)
  #local U = union {
    #local K = 0;
    #while (K < N)
      sphere { <R * cos(2 * pi * K / N), 0.2 * mod(K, 3), R * sin(2 * pi * K / N)>, 0.15 }
      #local K = K + 1;
    #end
  }
  U
#end
"""

SCENE = """#version 3.7;
global_settings { assumed_gamma 1.0 }
#include "ring.inc"
camera { location <0, 6, -9> look_at <0, 0.5, 0> angle 50 }
light_source { <-10, 20, -15> color rgb 1 }
plane { y, -0.5 pigment { checker rgb 0.8 rgb 0.3 } }

#declare Total = 0;
#declare Values = array[40];
#declare I = 0;
#while (I < 40)
  /* a block comment
     over two lines */
  #declare Values[I] = mod(I * 7, 11) + .5 + 1e-3 * I - 2.5E-2 + 3.e1 / 30; // numbers of every form
  #if (mod(I, 3) = 0)
    #declare Total = Total + Values[I];
  #elseif (mod(I, 3) = 1)
    #declare Total = Total - 0.5 * Values[I];
  #else
    #switch (mod(I, 4))
      #case (0) #declare Total = Total * 1.0001; #break
      #case (1) #declare Total = Total + 1; #break
      #else #declare Total = Total - 1;
    #end
  #end
  #declare P = <I / 10, Values[I] / 20, -I / 13>;
  #if (P.x >= 1 & P.y <= 0.4 | P.z < -2)
    #declare Total = Total + P.x + P.y;
  #end
  #if (mod(I, 10) = 0)
    #include "step.inc"  // a file included on some passes: a new stream each time
  #end
  #debug concat("I ", str(I, 0, 0), " value ", str(Values[I], 0, 6), " total ", str(Total, 0, 6), "\\n")
  #declare I = I + 1;
#end

#macro Post(X, Z)
  cylinder { <X, -0.5, Z>, <X, 0.4 + 0.01 * abs(X * Z), Z>, 0.08
    pigment { color rgb <mod(abs(X), 1), 0.5, mod(abs(Z), 1)> } }
#end
#for (J, -4, 4, 0.5)
  Post(J, -2)
  Post(-J, 2.5)
#end

object { Ring(12, 1.5) pigment { rgb <0.9, 0.6, 0.2> } }
object { Ring(7, 0.7) translate y pigment { rgb <0.2, 0.5, 0.9> } }

#declare Long = 0;
#declare I = 0;
#while (I < 6)
PADDING
  #declare Long = Long + I * Total / 1000;
  #declare I = I + 1;
#end
#debug concat("Long ", str(Long, 0, 9), " Total ", str(Total, 0, 9), "\\n")
sphere { <0, 1.5, 0>, 0.5 + mod(abs(Long), 0.3) pigment { rgb <0.9, 0.9, 0.9> } finish { reflection 0.3 } }
"""

# A loop body longer than the 4 KiB stream buffer: replaying must seek the file.
PADDING = "\n".join(f"  // padding line {n} to make this loop body longer than one buffer of the stream"
                    for n in range(80))


def write_scene(directory, crlf=False):
    text = SCENE.replace("PADDING", PADDING)
    include = INCLUDE
    if crlf:
        text = text.replace("\n", "\r\n")
        include = include.replace("\n", "\r\n")
    (directory / "ring.inc").write_bytes(include.encode())
    step = "#declare Total = Total + sqrt(I + 0.25) / 3;\n#declare K = 0;\n#while (K < 3) #declare Total = Total + K * 1e-2; #declare K = K + 1; #end\n"
    (directory / "step.inc").write_bytes((step.replace("\n", "\r\n") if crlf else step).encode())
    scene = directory / "loops.pov"
    scene.write_bytes(text.encode())
    return scene


def render_with_debug(binary, scene, name):
    debug = scene.parent / f"{name}.debug"
    out = scene.parent / f"{name}.tga"
    done = render(binary, scene, out, "+W160", "+H120", f"+GD{debug.name}")
    assert done.returncode == 0, f"{binary}: {done.stderr[-2000:]}"
    return out, debug.read_text()


@pytest.mark.parametrize("crlf", [False, True], ids=["lf", "crlf"])
def test_loops_and_macros_parse_as_in_debian_povray(crlf, tmp_path):
    scene = write_scene(tmp_path, crlf)
    debian, debian_debug = render_with_debug(DEBIAN_POVRAY, scene, "debian")
    ours, our_debug = render_with_debug(POVRAY_FC, scene, "povray-fc")
    assert "I 39 value" in debian_debug and "Long " in debian_debug, debian_debug[-500:]
    assert our_debug == debian_debug
    assert_same_pixels(debian, ours)


def error_report(stderr):
    """The lines of POV-Ray's parse error report that say where and what."""
    return [line.strip() for line in stderr.splitlines()
            if re.search(r"line \d+|Parse Error|File:|Line:", line)]


def test_an_error_on_a_later_pass_is_reported_at_the_same_place(tmp_path):
    scene = tmp_path / "late_error.pov"
    scene.write_text("""#version 3.7;
#declare I = 0;
#while (I < 10)
  #declare A = I * 2;
  #if (I = 7)
    #declare B = A +   NoSuchIdentifier;
  #end
  #declare I = I + 1;
#end
sphere { 0, 1 pigment { rgb 1 } }
""")
    reports = []
    for binary in (DEBIAN_POVRAY, POVRAY_FC):
        done = render(binary, scene, tmp_path / "out.tga", "+W16", "+H16")
        assert done.returncode != 0
        reports.append(error_report(done.stderr))
    assert any("line 6" in line for line in reports[0]), reports[0]
    assert reports[1] == reports[0]
