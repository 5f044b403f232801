// fc-test: speedup
// Boxes modelled the usual way and turned: a seesaw plank tilting about its middle, a
// propeller of two crossed planks spinning, and a cube turning on a post. A turned box is
// kept by POV-Ray as its own box under a transform; its world box is far wider than the
// plank, so a change of it is tested against a capsule along the plank too.
#version 3.7;
global_settings { assumed_gamma 1.0 }
camera { location <0, 4, -7> look_at <0, 0.8, 0> angle 55 }
light_source { <-4, 9, -5> rgb 1 }
plane { y, 0 pigment { checker rgb 0.85 rgb 0.55 } }
box { <-2.2, -0.06, -0.25>, <2.2, 0.06, 0.25> pigment { rgb <0.8, 0.5, 0.2> }
      rotate z * (-15 + 30 * clock) translate <-1.2, 0.9, 0> }
cylinder { <-1.2, 0, 0>, <-1.2, 0.84, 0>, 0.08 pigment { rgb 0.4 } }
union {
  box { <-1.1, -0.05, -0.08>, <1.1, 0.05, 0.08> }
  box { <-0.08, -0.05, -1.1>, <0.08, 0.05, 1.1> }
  pigment { rgb <0.2, 0.4, 0.8> }
  rotate y * 90 * clock rotate x * 70 translate <1.8, 1.6, 1>
}
box { <-0.35, -0.35, -0.35>, <0.35, 0.35, 0.35> pigment { rgb <0.3, 0.7, 0.3> }
      rotate <20, 60 * clock, 0> translate <1.6, 0.5, -1.5> }
