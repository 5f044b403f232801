// crand: random noise added per evaluation of the finish.
#version 3.7;
#include "common.inc"
light_source { <-3, 5, -3> color rgb 1 }
sphere { <0, 0.6, 0>, 0.6 pigment { color rgb <0.3, 0.6, 0.9> } finish { crand 0.3 } }
