"""Change detection at parse time (the parse patches, 0230-0245).

With POVRAYFC_DEBUG_SIGNATURES=1 the parser lists, for every frame, each top-level
item's class, hash, source line and world bounds, then the camera, lights and global
hashes and the inexact effects it saw. These tests render tiny animations of small
scenes and check the two properties frame coherence depends on:
- whatever changes between frames changes the hash of the item it belongs to (or the
  camera/lights/global hash), so that no change is ever missed;
- whatever does not change hashes the same in every frame, or fc gains nothing.
"""
import os
import re
import subprocess

import pytest

from fcutil import POVRAY_FC, SCENES

ITEM = re.compile(r"povrayfc-signature: item (\d+) (\w+) ([0-9a-f]{16}) line=(\d+) label=(\S+)(.*)$")
SUMMARY = re.compile(r"povrayfc-signature: (camera|lights|global) ([0-9a-f]{16})$")
INEXACT = re.compile(r"povrayfc-signature: inexact (.+)$")
OBJECTS = re.compile(r"povrayfc-signature: objects (\d+)$")
UNIT = re.compile(r"povrayfc-signature: unit (\d+) item=(\d+) ([0-9a-f]{16}) geometry=([0-9a-f]{16})(.*)$")


class Frame:
    """One frame's signature as the parser listed it."""

    def __init__(self):
        self.items = []       # dicts: cls, hash, line, label, bounds (tuple or None), infinite, lights,
                              # units (dicts: hash, geometry, bounds, infinite, opaque, translucent,
                              # cut_part)
        self.camera = self.lights = self.glob = None
        self.inexact = []
        self.object_count = None

    def objects(self):
        return [i for i in self.items if i["cls"] == "object"]

    def at(self, line, nth=0):
        """The nth item whose first token is on `line`."""
        found = [i for i in self.items if i["line"] == line]
        assert len(found) > nth, f"no item {nth} at line {line}: {self.items}"
        return found[nth]

    def hashes(self):
        return sorted(i["hash"] for i in self.objects())


def parse_listing(stderr):
    frames = []
    frame = Frame()
    for line in stderr.splitlines():
        line = line.rstrip()
        m = ITEM.search(line)
        if m:
            rest = m.group(6)
            bounds = None
            b = re.search(r"bounds=(\S+)", rest)
            if b:
                bounds = tuple(float(v) for v in b.group(1).split(","))
            frame.items.append(dict(cls=m.group(2), hash=m.group(3), line=int(m.group(4)),
                                    label=m.group(5), bounds=bounds,
                                    infinite=" infinite" in rest, lights=" lights" in rest, units=[]))
            continue
        m = UNIT.search(line)
        if m:
            rest = m.group(5)
            b = re.search(r"bounds=(\S+)", rest)
            frame.items[-1]["units"].append(dict(
                hash=m.group(3), geometry=m.group(4), bounds=tuple(float(v) for v in b.group(1).split(",")) if b else None,
                infinite=" infinite" in rest, opaque=" opaque" in rest, translucent=" translucent" in rest,
                cut_part=" cut-part" in rest))
            continue
        m = SUMMARY.search(line)
        if m:
            setattr(frame, {"camera": "camera", "lights": "lights", "global": "glob"}[m.group(1)],
                    m.group(2))
            continue
        m = INEXACT.search(line)
        if m:
            frame.inexact.append(m.group(1))
            continue
        m = OBJECTS.search(line)
        if m:
            frame.object_count = int(m.group(1))
            assert frame.object_count == len(frame.objects())
            frames.append(frame)
            frame = Frame()
    return frames


def signatures(tmp_path, scene_text, frames=2, final_clock=1.0, extra=()):
    """Render `frames` frames (clock 0 .. final_clock) of the scene; their signatures.

    With Frame_Coherence on: the parser hashes nothing with it off."""
    scene = tmp_path / "scene.pov"
    scene.write_text(scene_text)
    env = dict(os.environ, POVRAYFC_DEBUG_SIGNATURES="1")
    args = [str(POVRAY_FC), f"+I{scene}", f"+O{tmp_path}/frame", "+FT", "+W16", "+H12",
            "-D", "-P", "-V", "+KFI1", f"+KFF{frames}", "+KI0", f"+KF{final_clock}", "Frame_Coherence=on",
            *extra]
    done = subprocess.run(args, cwd=tmp_path, capture_output=True, text=True, timeout=300,
                          env=env, stdin=subprocess.DEVNULL)
    assert done.returncode == 0, done.stderr[-3000:]
    parsed = parse_listing(done.stderr)
    assert len(parsed) == frames, done.stderr[-3000:]
    return parsed


def line_of(text, marker):
    """1-based line of the first line containing `marker`."""
    for number, line in enumerate(text.splitlines(), 1):
        if marker in line:
            return number
    raise AssertionError(f"marker {marker!r} not in scene")


HEADER = """#version 3.7;
global_settings { assumed_gamma 1.0 }
camera { location <0, 2, -6> look_at <0, 0.5, 0> }
light_source { <-5, 8, -4> color rgb 1 }
"""


def test_demo_only_the_ball_changes(tmp_path):
    scene = (SCENES / "demo" / "demo.pov").read_text()
    f1, f2 = signatures(tmp_path, scene)
    ball = line_of(scene, "<BallX, BallY, -0.6>") - 1      # the line of `sphere {`
    plane = line_of(scene, "plane {")
    glass = line_of(scene, "<1.6, 0.9, 1.2>, 0.9") - 1
    column = line_of(scene, "cylinder {")
    for line in (plane, glass, column):
        assert f1.at(line)["hash"] == f2.at(line)["hash"], line
        assert f1.at(line)["bounds"] == f2.at(line)["bounds"]
    assert f1.at(ball)["hash"] != f2.at(ball)["hash"]
    assert f1.at(ball)["bounds"] != f2.at(ball)["bounds"]
    assert f1.at(plane)["infinite"] and not f1.at(glass)["infinite"]
    assert (f1.camera, f1.lights, f1.glob) == (f2.camera, f2.lights, f2.glob)
    assert f1.object_count == f2.object_count == 4
    assert f1.inexact == f2.inexact == []
    # the light sources are lights, not objects
    assert [i["cls"] for i in f1.items].count("light") == 2


def test_same_clock_same_signature(tmp_path):
    """Parsing the same frame twice gives the same hashes for everything (no hash is
    'unknown', which would make an object count as changed in every frame), also with
    the standard include files, macros, functions, arrays and splines."""
    scene = HEADER + """#include "colors.inc"
#include "textures.inc"
#include "functions.inc"
#include "shapes.inc"
#include "transforms.inc"
#declare Pts = array[3] { <0,0,0>, <1,1,0>, <2,0,0> }
#declare Sp = spline { linear_spline 0, <0,0,0>, 1, <1,1,1> }
#declare F = function(x, y, z) { f_sphere(x, y, z, 1) }
#macro Ring(R) torus { R, 0.1 texture { Polished_Chrome } } #end
#declare Obj = union { sphere { Pts[1], 0.3 } cylinder { Pts[0], Pts[2], 0.1 } }
object { Obj pigment { Red } }
Ring(1.5)
isosurface { function { F(x, y, z) } contained_by { box { -1.1, 1.1 } } translate Sp(0.5) pigment { Blue } }
object { Round_Box(<-1,-1,-1>, <1,1,1>, 0.1, 0) translate x*3 pigment { Green } }
sphere { 0, 1 texture { Jade } }
"""
    f1, f2 = signatures(tmp_path, scene, final_clock=0.0)
    assert f1.hashes() == f2.hashes()
    assert len(f1.objects()) == 5
    assert (f1.camera, f1.lights, f1.glob) == (f2.camera, f2.lights, f2.glob)


def test_declared_texture_used_by_name(tmp_path):
    scene = HEADER + """#declare Changing = texture { pigment { color rgb <clock, 0.5, 1 - clock> } }
#declare Fixed = texture { pigment { color rgb <0.3, 0.8, 0.3> } }
sphere { <0, 0.7, 0>, 0.7 texture { Changing } } // @changing
sphere { <1, 0.4, -1>, 0.4 texture { Fixed } } // @fixed
"""
    f1, f2 = signatures(tmp_path, scene)
    changing, fixed = line_of(scene, "@changing"), line_of(scene, "@fixed")
    assert f1.at(changing)["hash"] != f2.at(changing)["hash"]
    assert f1.at(changing)["bounds"] == f2.at(changing)["bounds"]
    assert f1.at(fixed)["hash"] == f2.at(fixed)["hash"]
    assert f1.glob == f2.glob


def test_declares_between_objects_do_not_change_them(tmp_path):
    """Top-level directives between items, even ones that use clock, are not part of
    the items around them; nor is what a declared texture's lookahead reads."""
    scene = HEADER + """sphere { <-1, 0.5, 0>, 0.5 pigment { rgb 1 } } // @first
#declare Moving = clock * 3;
#declare T = texture { pigment { rgb <1, 0, 0> } }
#if (clock > 0.5)
  #declare Late = 1;
#else
  #declare Late = 0;
#end
#while (Moving > 10) #declare Moving = Moving - 1; #end
sphere { <1, 0.5, 0>, 0.5 texture { T } } // @second
#declare Unused = sphere { <clock, 0, 0>, 1 }
box { <2, 0, 0>, <3, 1, 1> pigment { rgb 0.5 } } // @third
"""
    f1, f2 = signatures(tmp_path, scene)
    for marker in ("@first", "@second", "@third"):
        line = line_of(scene, marker)
        assert f1.at(line)["hash"] == f2.at(line)["hash"], marker
    assert f1.glob == f2.glob and f1.lights == f2.lights


def test_object_that_exists_only_late(tmp_path):
    scene = HEADER + """sphere { <-1, 0.5, 0>, 0.5 pigment { rgb 1 } } // @always
#if (clock > 0.5)
sphere { <1, 0.5, 0>, 0.5 pigment { rgb <1, 0, 0> } } // @late
#end
"""
    f1, f2 = signatures(tmp_path, scene)
    always, late = line_of(scene, "@always"), line_of(scene, "@late")
    assert len(f1.objects()) == 1 and len(f2.objects()) == 2
    assert f1.at(always)["hash"] == f2.at(always)["hash"]
    assert not [i for i in f1.items if i["line"] == late]
    assert f2.at(late)["bounds"] is not None
    assert f1.glob == f2.glob


def test_objects_built_in_loops(tmp_path):
    scene = HEADER + """#declare I = 0;
#while (I < 5)
  sphere { <I, 0.3, 0>, 0.3 #if (I = 2) translate y * clock #end pigment { rgb 1 } } // @while
  #declare I = I + 1;
#end
#for (J, 0, 3)
  box { <J, 0, 2>, <J + 0.5, 0.5, 2.5> #if (J = 3) scale <1, 1 + clock, 1> #end } // @for
#end
box { <0, 0, 4>, <1, 1 + 0 * clock, 5> } // @zero
"""
    f1, f2 = signatures(tmp_path, scene)
    line = line_of(scene, "@while")
    for n in range(5):
        same = f1.at(line, n)["hash"] == f2.at(line, n)["hash"]
        assert same == (n != 2), n
    line = line_of(scene, "@for")
    for n in range(4):
        same = f1.at(line, n)["hash"] == f2.at(line, n)["hash"]
        assert same == (n != 3), n
    # loop iterations that build the same object at different places differ
    assert len(set(i["hash"] for i in f1.objects())) == 10
    # conservative: every value read counts, even one that cannot matter
    line = line_of(scene, "@zero")
    assert f1.at(line)["hash"] != f2.at(line)["hash"]


def test_macro_generated_objects(tmp_path):
    scene = HEADER + """#macro Ball(P, T)
  #local R = 0.5;
  sphere { P, R texture { T } } // @body
#end
#declare Tex = texture { pigment { rgb <0.2, 0.4, 0.9> } }
Ball(<clock, 0.5, 0>, Tex)
Ball(<2, 0.5, 0>, Tex)
#macro Box(S) box { -S, S } #end // @box
object { Box(0.5 + 0 * clock) translate <-2, 0.5, 0> }  // @boxuse
"""
    f1, f2 = signatures(tmp_path, scene)
    body = line_of(scene, "@body")
    assert f1.at(body, 0)["hash"] != f2.at(body, 0)["hash"]
    assert f1.at(body, 1)["hash"] == f2.at(body, 1)["hash"]
    use = line_of(scene, "@boxuse")
    assert f1.at(use)["hash"] == f2.at(use)["hash"]


def test_moving_csg_cutter(tmp_path):
    scene = HEADER + """difference { // @diff
  box { <-1, 0, -1>, <1, 1, 1> }
  sphere { <-1 + 2 * clock, 1, -1>, 0.5 }
  pigment { rgb 1 }
}
"""
    f1, f2 = signatures(tmp_path, scene)
    line = line_of(scene, "@diff")
    assert f1.at(line)["hash"] != f2.at(line)["hash"]
    # the difference is bounded by its box, whatever the cutter does
    assert f1.at(line)["bounds"] == f2.at(line)["bounds"]
    lo = f1.at(line)["bounds"][:3]
    hi = f1.at(line)["bounds"][3:]
    for got, want in zip(lo, (-1, 0, -1)):
        assert want - 0.01 < got <= want
    for got, want in zip(hi, (1, 1, 1)):
        assert want <= got < want + 0.01


def test_parts_of_a_difference_are_units_of_their_own(tmp_path):
    scene = HEADER + """difference { // @diff
  box { <-1, 0, -1>, <1, 1, 1> }
  sphere { <-1 + 2 * clock, 1, -1>, 0.5 }
  pigment { rgb 1 }
}
intersection { // @inter
  box { <3, 0, 0>, <5, 1, 1> }
  cylinder { <4, 0.5, -5>, <4, 0.5, 5>, 0.4 + 0.2 * clock }
}
merge { // @merge
  sphere { <8, 0, 0>, 1 }
  sphere { <8, 2, 0>, 1.5 }
}
difference { // @bounded (a bounded_by: its box may be smaller than where its inside test holds)
  box { <10, 0, 0>, <12, 1, 1> }
  sphere { <11, 1, 0>, 0.5 bounded_by { box { <10.5, 0.5, -0.5>, <11.5, 1, 0.5> } } }
}
"""
    f1, f2 = signatures(tmp_path, scene)
    box, cutter = f1.at(line_of(scene, "@diff"))["units"]
    box2, cutter2 = f2.at(line_of(scene, "@diff"))["units"]
    # The box did not change; the cutter did. Both are parts, and opaque.
    assert box["hash"] == box2["hash"] and cutter["hash"] != cutter2["hash"]
    assert box["cut_part"] and cutter["cut_part"] and box["opaque"] and cutter["opaque"]
    # A change of the cutter shows only inside the box: its unit's box is clipped to it
    # (the ball reaches x -1.5 and z -1.5, y 1.5).
    lo, hi = cutter["bounds"][:3], cutter["bounds"][3:]
    assert lo[0] >= -1.01 and lo[2] >= -1.01 and hi[1] <= 1.01
    # In an intersection too; in a merge a part's own surfaces show anywhere in its box.
    slab, rod = f1.at(line_of(scene, "@inter"))["units"]
    assert rod["bounds"][2] >= -0.01 and rod["bounds"][5] <= 1.01
    assert slab["hash"] == f2.at(line_of(scene, "@inter"))["units"][0]["hash"]
    low, high = f1.at(line_of(scene, "@merge"))["units"]
    assert high["bounds"][4] >= 3.49 and low["bounds"][1] <= -0.99
    # A part with bounded_by keeps the CSG one unit.
    (whole,) = f1.at(line_of(scene, "@bounded"))["units"]
    assert not whole["cut_part"]


def test_a_shadow_test_may_pass_every_unit_of_an_item_that_is_not_opaque(tmp_path):
    # A shadow test goes on past a surface that lets light through: every unit of an item
    # with such a surface counts (its opaque parts too, more than needed); an opaque item's
    # surfaces clear the light for good.
    scene = HEADER + """sphere { <0, 0, 0>, 1 pigment { rgb 1 } } // @stone
sphere { <3, 0, 0>, 1 pigment { rgbf <1, 1, 1, 0.8> } } // @glass
union { // @mixed
  sphere { <6, 0, 0>, 1 pigment { rgb 1 } }
  sphere { <8, 0, 0>, 1 pigment { rgbt <1, 1, 1, 0.5> } }
}
"""
    f1, _ = signatures(tmp_path, scene)
    (stone,) = f1.at(line_of(scene, "@stone"))["units"]
    (glass,) = f1.at(line_of(scene, "@glass"))["units"]
    opaque_part, clear_part = f1.at(line_of(scene, "@mixed"))["units"]
    assert stone["opaque"] and not stone["translucent"]
    assert glass["translucent"] and not glass["opaque"]
    assert opaque_part["opaque"] and opaque_part["translucent"] and clear_part["translucent"]


def test_mesh_vertex_moving_inside_unchanged_bounds(tmp_path):
    scene = HEADER + """mesh { // @mesh
  triangle { <-1, 0, 0>, <1, 0, 0>, <0, 2, 0> }
  triangle { <-1, 0, 0>, <1, 0, 0>, <0, 0.5 + clock, 0.5> }
  pigment { rgb 1 }
}
mesh2 { // @mesh2
  vertex_vectors { 4, <-1, 0, 2>, <1, 0, 2>, <0, 2, 2>, <0, 0.2 + 0.5 * clock, 2.5> }
  face_indices { 2, <0, 1, 2>, <0, 1, 3> }
}
"""
    f1, f2 = signatures(tmp_path, scene)
    for marker in ("@mesh", "@mesh2"):
        line = line_of(scene, marker)
        assert f1.at(line)["hash"] != f2.at(line)["hash"], marker
        assert f1.at(line)["bounds"] == f2.at(line)["bounds"], marker


def test_object_pattern_referencing_a_moving_object(tmp_path):
    scene = HEADER + """#declare Mover = sphere { <-1 + 2 * clock, 0.5, 0>, 0.4 }
#declare Still = sphere { <0, 0.5, 0>, 0.4 }
box { <-2, 0, -0.1>, <2, 1, 0> pigment { object { Mover color rgb 1 color rgb <1, 0, 0> } } } // @moving
box { <-2, 0, 1>, <2, 1, 1.1> pigment { object { Still color rgb 1 color rgb <1, 0, 0> } } } // @still
"""
    f1, f2 = signatures(tmp_path, scene)
    moving, still = line_of(scene, "@moving"), line_of(scene, "@still")
    assert f1.at(moving)["hash"] != f2.at(moving)["hash"]
    assert f1.at(moving)["bounds"] == f2.at(moving)["bounds"]
    assert f1.at(still)["hash"] == f2.at(still)["hash"]
    assert len(f1.objects()) == 2    # the declared spheres are not in the scene


def test_pigment_translated_with_clock_on_static_object(tmp_path):
    scene = HEADER + """sphere { <0, 1, 0>, 1 pigment { checker rgb 1 rgb 0 translate x * clock } } // @moving
sphere { <2, 1, 0>, 1 pigment { checker rgb 1 rgb 0 translate x * 0.25 } } // @still
"""
    f1, f2 = signatures(tmp_path, scene)
    moving, still = line_of(scene, "@moving"), line_of(scene, "@still")
    assert f1.at(moving)["hash"] != f2.at(moving)["hash"]
    assert f1.at(moving)["bounds"] == f2.at(moving)["bounds"]
    assert f1.at(still)["hash"] == f2.at(still)["hash"]


def test_values_that_depend_on_the_frame(tmp_path):
    """clock in a function, frame_number, rand() seeded by the frame, an array
    element, a spline: each object changes exactly when its input does."""
    scene = HEADER + """#declare F = function(x, y, z) { x * x + y * y + z * z - 0.25 - 0.1 * clock }
#declare G = function(x, y, z) { x * x + y * y + z * z - 0.25 }
isosurface { function { F(x, y, z) } contained_by { box { -1, 1 } } } // @fclock
isosurface { function { G(x, y, z) } contained_by { box { -1, 1 } } translate x * 3 } // @fstill
sphere { <frame_number, 0, 5>, 0.3 } // @frame
#declare S = seed(frame_number);
sphere { <rand(S), 1, 5>, 0.3 } // @rand
#declare S2 = seed(7);
sphere { <rand(S2), 2, 5>, 0.3 } // @rand7
#declare A = array[2];
#declare A[0] = sphere { <clock, 0, 8>, 0.2 };
#declare A[1] = sphere { <0, 1, 8>, 0.2 };
#declare B = A;
object { A[0] } // @a0
object { A[1] } // @a1
object { B[1] } // @b1
#declare Path = spline { linear_spline 0, <0, 0, 9>, 1, <1, 1, 9> }
sphere { Path(clock), 0.2 } // @spline
sphere { Path(0.5), 0.2 } // @splinefixed
"""
    f1, f2 = signatures(tmp_path, scene)
    changes = {"@fclock": True, "@fstill": False, "@frame": True, "@rand": True,
               "@rand7": False, "@a0": True, "@a1": False, "@b1": False, "@spline": True,
               "@splinefixed": False}
    for marker, changed in changes.items():
        line = line_of(scene, marker)
        assert (f1.at(line)["hash"] != f2.at(line)["hash"]) == changed, marker


def test_camera_lights_and_global(tmp_path):
    base = """#version 3.7;
global_settings { assumed_gamma 1.0 }
sphere { 0, 1 pigment { rgb 1 } } // @sphere
"""
    cases = {
        "camera": "camera { location <clock, 2, -6> look_at 0 }\nlight_source { <0, 5, -5> rgb 1 }\n",
        "lights": "camera { location <0, 2, -6> look_at 0 }\nlight_source { <clock, 5, -5> rgb 1 }\n",
        "csg light": "camera { location <0, 2, -6> look_at 0 }\n"
                     "union { light_source { <clock, 5, -5> rgb 1 } box { 4, 5 } }\n",
        "global": "camera { location <0, 2, -6> look_at 0 }\nlight_source { <0, 5, -5> rgb 1 }\n"
                  "fog { distance 10 + clock color rgb 0.5 }\n",
        "default": "camera { location <0, 2, -6> look_at 0 }\nlight_source { <0, 5, -5> rgb 1 }\n"
                   "#default { finish { ambient 0.1 * clock } }\n",
        "background": "camera { location <0, 2, -6> look_at 0 }\nlight_source { <0, 5, -5> rgb 1 }\n"
                      "background { rgb clock }\n",
    }
    for name, extra in cases.items():
        scene = base + extra
        f1, f2 = signatures(tmp_path, scene)
        changed = {"camera": f1.camera != f2.camera, "lights": f1.lights != f2.lights,
                   "global": f1.glob != f2.glob}
        expected = {"camera": name == "camera", "lights": name in ("lights", "csg light"),
                    "global": name in ("global", "default", "background")}
        assert changed == expected, name
        sphere = line_of(scene, "@sphere")
        # the object itself did not change (a default{} after it does not apply to it
        # anyway; global changes make fc render the whole frame)
        assert f1.at(sphere)["hash"] == f2.at(sphere)["hash"], name
        if name == "csg light":
            union = [i for i in f1.items if i["label"] == "union"][0]
            assert union["lights"] and union["cls"] == "object"


def test_unbounded_objects(tmp_path):
    scene = HEADER + """plane { y, 0 } // @plane
sphere { 0, 1 inverse } // @inverse
union { sphere { 0, 1 } sphere { 3, 1 inverse } } // @union
difference { box { -1, 1 } sphere { 0, 1.2 } translate x * 5 } // @difference
quadric { <1, 0, 1>, <0, 0, 0>, <0, 0, 0>, -1 } // @quadric (an infinite cylinder)
"""
    (f1,) = signatures(tmp_path, scene, frames=1)
    for marker, infinite in (("@plane", True), ("@inverse", True), ("@union", True),
                             ("@difference", False), ("@quadric", True)):
        item = f1.at(line_of(scene, marker))
        assert item["infinite"] == infinite, marker
        assert (item["bounds"] is None) == infinite, marker


def test_inexact_effects(tmp_path):
    cases = {
        "crand": "sphere { 0, 1 pigment { rgb 1 } finish { crand 0.2 } }",
        "media method 1": "sphere { 0, 1 hollow pigment { rgbt 1 } interior { media { method 1 emission 0.1 } } }",
        "media jitter": "sphere { 0, 1 hollow pigment { rgbt 1 } interior { media { jitter 0.5 emission 0.1 } } }",
        "isosurface evaluate": "isosurface { function { x*x + y*y + z*z - 1 } evaluate 5, 1.2, 0.95 }",
        "jittered area light": "light_source { <0, 5, 0> rgb 1 area_light x, z, 3, 3 jitter }",
        "radiosity": "global_settings { radiosity { } } sphere { 0, 1 }",
        "photons": "global_settings { photons { count 1000 } } sphere { 0, 1 }",
        "subsurface": "global_settings { mm_per_unit 10 subsurface { samples 10, 10 } } "
                      "sphere { 0, 1 pigment { rgb 1 } finish { subsurface { translucency <1, 0.5, 0.2> } } }",
    }
    for name, body in cases.items():
        (f1,) = signatures(tmp_path, HEADER + body + "\n", frames=1)
        assert name in f1.inexact, (name, f1.inexact)
    # and nothing for ordinary scenes: media method 3 without jitter, area light
    # without jitter, crand 0, and effects only declared, not used (textures.inc
    # declares a finish with crand)
    plain = HEADER + """#include "textures.inc"
#declare Grainy = finish { crand 0.3 }
#declare Old = media { method 1 emission 0.1 }
#declare Iso = isosurface { function { x*x + y*y + z*z - 1 } evaluate 5, 1.2, 0.95 }
sphere { 0, 1 hollow pigment { rgbt 1 } interior { media { emission 0.1 } } }
light_source { <0, 5, 0> rgb 1 area_light x, z, 3, 3 adaptive 1 }
sphere { 2, 1 finish { crand 0 } }
sphere { -2, 1 texture { Jade } }
"""
    (f1,) = signatures(tmp_path, plain, frames=1)
    assert f1.inexact == []
    # used through identifiers, arrays, macros and defaults, they count
    used = {
        "crand": "#declare Grainy = finish { crand 0.3 }\n"
                 "#declare T = texture { pigment { rgb 1 } finish { Grainy } }\n"
                 "#macro Ball(Tex) sphere { 0, 1 texture { Tex } } #end\nBall(T)",
        "media method 1": "#declare A = array[1] { media { method 1 emission 0.1 } }\n"
                          "box { -1, 1 hollow pigment { rgbt 1 } interior { media { A[0] } } }",
        "isosurface evaluate": "#declare Iso = isosurface { function { x*x + y*y + z*z - 1 } "
                               "evaluate 5, 1.2, 0.95 }\nunion { object { Iso } sphere { 3, 1 } }",
        "media jitter": "media { jitter 0.1 scattering { 1, 0.01 } }",
    }
    for name, body in used.items():
        (f1,) = signatures(tmp_path, HEADER + body + "\n", frames=1)
        assert f1.inexact == [name], (name, f1.inexact)
    (f1,) = signatures(tmp_path, HEADER + "#default { finish { crand 0.1 } }\nsphere { 0, 1 }\n", frames=1)
    assert f1.inexact == ["crand"]


def test_three_frames_hash_consistently(tmp_path):
    """An object that changes between frames 1 and 2 but not 2 and 3 keeps its hash.
    What counts is every value the object's parse read: a declared value that stops
    changing stops changing the object, but clock read inline always counts, even
    where the result is the same (min(clock, 0.5) at clock 0.5 and 1)."""
    scene = HEADER + """#declare P = min(clock, 0.5);
sphere { <P, 0.5, 0>, 0.5 } // @stops
sphere { <min(clock, 0.5), 0.5, 2>, 0.5 } // @inline
sphere { <2, 0.5, 0>, 0.5 } // @still
"""
    f1, f2, f3 = signatures(tmp_path, scene, frames=3)   # clock 0, 0.5, 1
    stops, inline, still = (line_of(scene, m) for m in ("@stops", "@inline", "@still"))
    assert f1.at(stops)["hash"] != f2.at(stops)["hash"]
    assert f2.at(stops)["hash"] == f3.at(stops)["hash"]
    assert f1.at(inline)["hash"] != f2.at(inline)["hash"] != f3.at(inline)["hash"]
    assert f1.at(still)["hash"] == f2.at(still)["hash"] == f3.at(still)["hash"]


@pytest.mark.parametrize("scene", ["declared_texture", "csg_cutter", "mesh_vertices",
                                   "pattern_translate", "appear_vanish"])
def test_fc_test_scenes_change(tmp_path, scene):
    """The fc test scenes animate something: some object hash (or the object count)
    changes, and the camera and global hashes do not."""
    path = SCENES / "fc-tests" / f"{scene}.pov"
    if not path.exists():
        pytest.skip(f"{path} not present")
    text = path.read_text()
    frames = signatures(tmp_path, text.replace('#include "common.inc"',
                                               f'#include "{SCENES / "fc-tests" / "common.inc"}"'),
                        frames=3)
    assert any(a.hashes() != b.hashes() for a, b in zip(frames, frames[1:]))
    for a, b in zip(frames, frames[1:]):
        assert a.camera == b.camera and a.glob == b.glob


def test_data_files_count_by_content(tmp_path):
    """An image rewritten between frames under the same name changes the object that
    uses it; a font goes into the global hash (fonts are opened once per scene)."""
    def write_image(last):
        (tmp_path / "tex.ppm").write_bytes(b"P6\n2 2\n255\n" + bytes([255, 0, 0, 0, 255, 0, 0, 0, 255,
                                                                        255, 255, last]))
    scene = HEADER + """box { -1, 1 pigment { image_map { ppm "tex.ppm" } } } // @image
#declare P = pigment { image_map { ppm "tex.ppm" } }
sphere { <2, 0, 0>, 1 pigment { P } } // @declared
sphere { <-2, 0, 0>, 1 pigment { rgb 1 } } // @still
text { ttf "timrom.ttf" "fc" 0.1, 0 translate <0, 2, 0> } // @text
"""
    write_image(255)
    f1, f2 = signatures(tmp_path, scene)          # same files in both frames: all stable
    assert f1.hashes() == f2.hashes() and f1.glob == f2.glob
    write_image(254)
    (f3,) = signatures(tmp_path, scene, frames=1)
    for marker, changed in (("@image", True), ("@declared", True), ("@still", False), ("@text", False)):
        line = line_of(scene, marker)
        assert (f1.at(line)["hash"] != f3.at(line)["hash"]) == changed, marker
    assert f1.glob == f3.glob
    (f4,) = signatures(tmp_path, scene.replace("timrom.ttf", "cyrvetic.ttf"), frames=1)
    assert f4.glob != f1.glob


def test_no_signature_with_frame_coherence_off(tmp_path):
    # The parser hashes nothing (and reads no data file again) when fc is off.
    scene = tmp_path / "scene.pov"
    scene.write_text("camera { location <0, 1, -4> look_at 0 }\nsphere { 0, 1 pigment { rgb 1 } }\n")
    env = dict(os.environ, POVRAYFC_DEBUG_SIGNATURES="1")
    done = subprocess.run([str(POVRAY_FC), f"+I{scene}", f"+O{tmp_path}/f", "+FT", "+W16", "+H12", "-D", "-P",
                           "-V", "Frame_Coherence=off"], cwd=tmp_path, capture_output=True, text=True,
                          timeout=120, env=env, stdin=subprocess.DEVNULL)
    assert done.returncode == 0, done.stderr[-2000:]
    assert "povrayfc-signature" not in done.stderr
