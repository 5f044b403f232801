// fc-test: speedup
// Parts of merges, intersections and differences that change on their own. A cylinder
// cut through a wall moves: the window of light it opens in the wall's shadow moves with
// it, though no shadow test that the wall stopped ended on the cutter. The box of an
// intersection slides over a ball, so the ball's surface counts elsewhere; a glass merge
// turns one of its parts; the cut-out parts of the wall keep their own texture.
#version 3.7;
#declare NoDefaultLight = 1;
#include "common.inc"
light_source { <1.5, 7, 5> color rgb 1 }
difference {
  box { <-1.4, 0, 0>, <1.4, 1.6, 0.1> pigment { color rgb <0.8, 0.5, 0.3> } }
  cylinder { <-0.8 + 1.6 * clock, 0.8, -1>, <-0.8 + 1.6 * clock, 0.8, 1>, 0.3 }
  object { box { <-0.2, -0.2, -1>, <0.2, 0.2, 1> } rotate z * 45 * clock translate <0.9, 1.3, 0>
           pigment { color rgb <0.2, 0.8, 0.3> } }
  pigment { color rgb <0.5, 0.5, 0.9> }
}
intersection {
  sphere { <1.9, 0.55, -1.2>, 0.55 }
  box { <1.5 + 0.5 * clock, 0, -1.8>, <2.5 + 0.5 * clock, 1.2, -0.6> }
  pigment { color rgb <0.9, 0.3, 0.3> }
}
merge {
  sphere { <-1.9, 0.5, -1.2>, 0.45 }
  cylinder { <-1.9, 0.5, -1.2>, <-1.9 + 0.7 * cos(2 * clock), 1.1, -1.2 + 0.7 * sin(2 * clock)>, 0.15 }
  pigment { color rgbf <0.7, 0.9, 1, 0.8> }
  interior { ior 1.3 }
}
