// An isosurface with evaluate: its gradient estimate changes while it renders.
#version 3.7;
#include "common.inc"
light_source { <-3, 5, -3> color rgb 1 }
isosurface {
  function { x * x + y * y + z * z - 0.36 + 0.05 * sin(12 * x) * sin(12 * z) }
  contained_by { box { -0.8, 0.8 } } evaluate 5, 1.2, 0.95
  translate <0, 0.7, 0> pigment { color rgb <0.4, 0.8, 0.4> }
}
