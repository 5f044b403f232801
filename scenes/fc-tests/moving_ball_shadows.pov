// fc-test: speedup
// Opaque balls moving a little over a floor, each casting a shadow that mostly covers the
// same floor in the next frame: those shadow tests stay dark while a ball of the new frame
// still crosses them. Around that rule's edges: a ball in an opaque union (still a
// blocker), one in a union with a glass part (the shadow test asks the union, which lets
// light through: not a blocker), a no_shadow ball, a ball seen through a glass pane on the
// light's way (the test's pieces up to the pane are moot once the ball darkens it), a
// light with projected_through, and a ball moving towards the light.
#version 3.7;
#include "common.inc"
light_source { <3, 9, -2> color rgb 0.5 projected_through { sphere { <0.5, 3, 0.5>, 2.6 } } }
#declare Matte = finish { diffuse 0.7 phong 0.3 }
sphere { <-0.9 + 0.15 * clock, 0.9, 0>, 0.4 pigment { color rgb <0.9, 0.3, 0.2> } finish { Matte } }
union {
  sphere { <0, 0, 0>, 0.35 }
  cylinder { <0, 0, 0>, <0, 0.6, 0>, 0.05 }
  pigment { color rgb <0.3, 0.8, 0.3> } finish { Matte }
  translate <0.3, 1.0 + 0.1 * clock, -0.4>
}
union {
  sphere { <0, 0, 0>, 0.3 pigment { color rgb <0.3, 0.3, 0.9> } }
  sphere { <0.45, 0, 0>, 0.2 pigment { color rgbf <0.9, 0.9, 1, 0.8> } }
  finish { Matte }
  translate <1.1 - 0.1 * clock, 0.8, 0.2>
}
sphere { <-0.2, 0.5, -1.1 + 0.1 * clock>, 0.25 pigment { color rgb 0.8 } no_shadow }
box { <-2.0, 2.2, -1.5>, <0.5, 2.25, 1.0> pigment { color rgbf <0.8, 0.9, 1, 0.9> } }
sphere { <-1.5 + 0.2 * clock, 1.2 + 0.4 * clock, -0.6>, 0.3 pigment { color rgb <0.9, 0.8, 0.2> } }
