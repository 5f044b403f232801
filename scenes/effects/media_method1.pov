// Media method 1: sample positions drawn at random along each ray.
#version 3.7;
#include "common.inc"
light_source { <-3, 5, -3> color rgb 1 }
box { <-0.8, 0, -0.8>, <0.8, 1.4, 0.8> pigment { rgbt 1 } hollow
  interior { media { method 1 intervals 4 samples 3, 3 scattering { 1, rgb 0.6 } } } }
