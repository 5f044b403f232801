// fc-test: speedup
// A slab above the camera's view grows and slides, casting a large shadow on the floor: the
// shadow tests it darkened stay dark while the new slab still crosses them, so only the
// shadow's rim is traced again, not the whole shadow.
#version 3.7;
#declare NoDefaultCamera = 1;
#declare NoDefaultLight = 1;
#include "common.inc"
camera { location <0, 3, -4> look_at <0, 0, 0> angle 60 }
light_source { <0, 20, 0> color rgb 1 }
box { <-1, 0, -1>, <1, 0.2, 1> scale <1 + 0.1 * clock, 1, 1> translate <0.1 * clock, 6, 0> pigment { color rgb 0.5 } }
