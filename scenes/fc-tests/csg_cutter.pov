// fc-test: speedup
// A moving cutter carves a static block (CSG difference).
#version 3.7;
#include "common.inc"
difference {
  box { <-1, 0, -0.5>, <1, 1.2, 0.5> }
  sphere { <-1 + 2 * clock, 1.2, -0.5>, 0.45 }
  pigment { color rgb <0.9, 0.9, 0.7> }
}
