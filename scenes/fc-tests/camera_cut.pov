// fc-test: speedup
// A camera cut in the middle of the animation starts a new coherent sequence.
#version 3.7;
#declare NoDefaultCamera = 1;
#include "common.inc"
#if (clock < 0.5)
  camera { location <0, 2.5, -6> look_at <0, 0.8, 0> angle 55 }
#else
  camera { location <3, 3, -5> look_at <0, 0.5, 0> angle 60 }
#end
sphere { <-1 + 2 * clock, 0.5, -1>, 0.5 pigment { color rgb <1, 0.5, 0> } }
