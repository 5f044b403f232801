// fc-test: speedup
// A pendulum built as one union (rod and bob) rotated about its pivot: only what the
// rod and bob cover before and after changes, not the box from pivot to bob.
#version 3.7;
#include "common.inc"
union {
  cylinder { <0, 0, 0>, <0, -1.6, 0>, 0.03 }
  sphere { <0, -1.6, 0>, 0.22 }
  pigment { color rgb <0.8, 0.75, 0.3> }
  finish { phong 0.6 reflection 0.2 }
  rotate <0, 0, -35 + 70 * clock>
  translate <0, 2.2, 0.3>
}
box { <-0.8, 2.15, 0.2>, <0.8, 2.25, 0.4> pigment { color rgb 0.4 } }
