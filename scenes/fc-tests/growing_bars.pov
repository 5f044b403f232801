// fc-test: speedup
// A bar chart whose bars grow, each a box moved and scaled into place (no rotation: POV-Ray
// keeps such a box between its corners), casting long shadows on the floor. A shadow test
// a bar darkened stays dark while the grown bar still crosses it, so only the shadows'
// new ends are traced again (the bars' own faces still are wherever a ray ended on them).
// Around that rule's edges: a bar in an opaque union (still a
// blocker), a turned bar (a box with a transformation: not one), a no_shadow bar, and a
// bar that lets light through, a bar that shrinks. A ray that ended on a bar's face that stays in its plane
// meets the grown bar there again (povray-fc/README.md, "Boxes that grow"), except on a
// bar whose checks are scaled with it (its texture comes before the scaling) and on one
// whose texture is uv-mapped, whole or in its pigment (a box's uv coordinates stretch with
// it).
#version 3.7;
#declare NoDefaultLight = 1;
#include "common.inc"
light_source { <-8, 2, -1> color rgb 1 }
#macro Bar(X, H, Colour)
  box { <-0.2, 0, -0.2>, <0.2, 1, 0.2> scale <1, H, 1> translate <X, 0, 0> pigment { color Colour } }
#end
object { Bar(-1.2, 0.8 + 0.3 * clock, rgb <0.9, 0.3, 0.2>) }
union {
  object { Bar(-0.6, 1.0 + 0.2 * clock, rgb <0.3, 0.8, 0.3>) }
  sphere { <-0.6, 0, -0.5>, 0.1 pigment { color rgb 1 } }
}
object { Bar(0, 0.6 + 0.25 * clock, rgb <0.3, 0.3, 0.9>) rotate y * (10 + 5 * clock) }
object { Bar(0.6, 0.9 + 0.2 * clock, rgb 0.8) no_shadow }
object { Bar(1.2, 0.7 + 0.2 * clock, rgbf <0.9, 0.9, 1, 0.7>) }
box { <-0.2, 0, -0.2>, <0.2, 1, 0.2> pigment { checker color rgb 0.9 color rgb 0.2 scale 0.1 }
      scale <1, 0.5 + 0.3 * clock, 1> translate <1.8, 0, -0.6> }
box { <-0.2, 0, -0.2>, <0.2, 0.6 + 0.3 * clock, 0.2> uv_mapping pigment { checker color rgb 0.9 color rgb 0.1 scale 0.25 }
      translate <-1.8, 0, -0.6> }
box { <-0.2, 0, -0.2>, <0.2, 0.5 + 0.3 * clock, 0.2>
      texture { pigment { uv_mapping checker color rgb 0.9 color rgb 0.4 scale 0.25 } }
      translate <-1.3, 0, -1.0> }
box { <-0.2, 0, -0.2>, <0.2, 1, 0.2> scale <1, 1.3 - 0.4 * clock, 1> translate <-0.3, 0, 0.9>
      pigment { color rgb <0.9, 0.6, 0.2> } }
