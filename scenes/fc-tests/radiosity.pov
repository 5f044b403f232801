// fc-test: +WT1
// Radiosity: fc cannot keep it exact, so every frame renders in full (one thread:
// radiosity is only deterministic with one).
#version 3.7;
global_settings { radiosity { count 20 pretrace_start 0.08 pretrace_end 0.04 } }
#include "common.inc"
sphere { <-1 + 2 * clock, 0.4, -1>, 0.4 pigment { color rgb <1, 0.4, 0.2> } }
