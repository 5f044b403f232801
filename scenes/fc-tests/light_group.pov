// fc-test: speedup
// A light_group whose light moves: it lights only the group's sphere, so only pixels
// that see that sphere (or its shadow on itself) change; the rest of the frame is reused.
#version 3.7;
#include "common.inc"
light_group {
  light_source { <2 - 4 * clock, 3, -3> color rgb <1, 0.6, 0.3> }
  sphere { <0, 0.6, 0>, 0.5 pigment { color rgb 0.9 } finish { phong 0.8 } }
  global_lights off
}
