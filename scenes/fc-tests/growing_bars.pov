// fc-test: speedup
// A bar chart whose bars grow, each a box moved and scaled into place (no rotation: POV-Ray
// keeps such a box between its corners), casting long shadows on the floor. A shadow test
// a bar darkened stays dark while the grown bar still crosses it, so only the shadows'
// new ends are traced again (the bars' own faces still are wherever a ray ended on them).
// Around that rule's edges: a bar in an opaque union (still a
// blocker), a turned bar (a box with a transformation: not one), a no_shadow bar, and a
// bar that lets light through.
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
