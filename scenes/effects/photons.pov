// Photons: a caustic from a glass sphere, shot before each frame renders.
#version 3.7;
global_settings { photons { count 20000 } }
#include "common.inc"
light_source { <-3, 5, -3> color rgb 1 photons { refraction on reflection on } }
sphere { <0, 0.6, 0>, 0.5 pigment { rgbf <1, 1, 1, 0.95> } interior { ior 1.5 }
  photons { target refraction on reflection on } }
