// Subsurface light transport: sampled at random points under the surface.
#version 3.7;
global_settings { subsurface { samples 30, 10 } }
#include "common.inc"
light_source { <-3, 5, -3> color rgb 1 }
sphere { <0, 0.6, 0>, 0.6 pigment { color rgb 0.9 } finish { subsurface { translucency <0.8, 0.5, 0.3> } } }
