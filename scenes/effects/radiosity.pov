// Radiosity: a shared sample cache filled in the order the blocks are rendered.
#version 3.7;
global_settings { radiosity { count 30 pretrace_start 0.08 pretrace_end 0.04 } }
#include "common.inc"
light_source { <-3, 5, -3> color rgb 1 }
sphere { <0, 0.6, 0>, 0.6 pigment { color rgb <0.9, 0.3, 0.2> } }
