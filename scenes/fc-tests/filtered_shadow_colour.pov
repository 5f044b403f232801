// fc-test: speedup
// A coloured glass pane whose filter colour changes: its shape stays, but the shadow rays
// that pass it carry another colour. They end on it piece by piece, so they are found.
#version 3.7;
#include "common.inc"
box { <-1, 1.6, -1>, <1, 1.65, 1>
  pigment { color rgbf <1 - clock, 0.4, clock, 0.9> }
  translate <0.5, 0, 0>
}
