// fc-test: speedup
// A texture declared once with clock and used by name on a static object.
#version 3.7;
#include "common.inc"
#declare Changing = texture { pigment { color rgb <clock, 0.5, 1 - clock> } finish { phong 0.3 } }
#declare Fixed = texture { pigment { color rgb <0.3, 0.8, 0.3> } }
sphere { <0, 0.7, 0>, 0.7 texture { Changing } }
sphere { <1, 0.4, -1>, 0.4 texture { Fixed } }
