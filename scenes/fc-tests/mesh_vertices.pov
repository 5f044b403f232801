// fc-test: speedup
// Mesh vertices move inside an unchanged bounding box (the corners stay put).
#version 3.7;
#include "common.inc"
#declare H = 0.2 + 0.8 * clock;
mesh {
  triangle { <-1, 0, 0>, <1, 0, 0>, <0, H, 0> }
  triangle { <-1, 1, 0.1>, <1, 1, 0.1>, <0, 1, 0.1> }
  pigment { color rgb <0.3, 0.9, 0.6> }
}
