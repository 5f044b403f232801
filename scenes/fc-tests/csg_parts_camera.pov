// fc-test:
// The camera inside a glass difference whose cutter moves away from it: its rays start in
// the cutter's cavity, then in the glass, though the camera is inside neither part's
// surface alone. A part near the camera changed: the frame renders in full.
#version 3.7;
#declare NoDefaultCamera = 1;
#include "common.inc"
camera { location <0, 1, -1> look_at <0, 1, 2> angle 60 }
difference {
  box { <-3, 0.01, -3>, <3, 2.5, 3> }
  sphere { <0, 1, -1 + 2 * clock>, 0.8 }
  pigment { color rgbf <0.9, 1, 0.9, 0.7> }
  interior { ior 1.2 }
}
