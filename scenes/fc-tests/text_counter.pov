// fc-test: speedup
// A label whose last digits change every frame ("frame 0.33" ...), casting a shadow on
// the floor and seen in a mirror: only the changed glyphs, their shadows and their
// reflection change; the glyphs a string keeps are not traced again.
#version 3.7;
#include "common.inc"
text {
  ttf "timrom.ttf" concat("frame ", str(clock, 0, 2)), 0.2, 0
  pigment { color rgb <0.9, 0.2, 0.2> }
  scale 0.8
  translate <-1.6, 0.6, 0>
}
box { <-3, 0, 3>, <3, 2.4, 3.1> pigment { color rgb 0.1 } finish { reflection 0.7 } }
