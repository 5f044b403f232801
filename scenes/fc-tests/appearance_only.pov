// fc-test: speedup
// A lamp shade (a difference) and a post change only their colour and finish: every ray
// that ended on them is traced again, no other; their shape is tested nowhere.
#version 3.7;
#include "common.inc"
difference {
  cone { <0, 0.8, 0>, 0.6, <0, 1.6, 0>, 0.3 }
  cone { <0, 0.79, 0>, 0.55, <0, 1.61, 0>, 0.25 }
  pigment { color rgb <0.9, 0.8 - 0.5 * clock, 0.3 + 0.5 * clock> }
  finish { phong 0.3 * clock }
}
cylinder { <0, 0, 0>, <0, 1.2, 0>, 0.05 pigment { color rgb clock } }
