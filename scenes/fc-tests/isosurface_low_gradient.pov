// fc-test: speedup
// An isosurface whose max_gradient is set far too low: POV-Ray's root finder then keeps
// a per-thread memory of the last ray's root-free stretch that can answer the next ray
// wrongly, so a pixel could depend on the pixel traced before it. A ball moves in front.
#version 3.7;
#include "common.inc"
#include "functions.inc"
isosurface {
  function { y - 0.6 - 0.35 * f_noise3d(x * 4, 0, z * 4) + 0.2 * sin(8 * x) * cos(8 * z) }
  contained_by { box { <-2.5, 0, -1>, <2.5, 1.4, 2> } }
  max_gradient 0.3
  accuracy 0.001
  pigment { color rgb <0.9, 0.6, 0.3> }
  finish { phong 0.4 }
}
sphere { <-1.5 + 3 * clock, 1.6, -1.5>, 0.3 pigment { color rgb <0.3, 0.9, 0.4> } }
