// fc-test: speedup
// An object that appears in the middle frames and vanishes again.
#version 3.7;
#include "common.inc"
#if (clock > 0.3 & clock < 0.7)
  cone { <0.5, 0, 0>, 0.5, <0.5, 1.5, 0>, 0 pigment { color rgb <0.9, 0.4, 0.9> } }
#end
