// fc-test:
// Pairs of coincident glass plates, one filtering red and one blue, hang above the view
// and cast coloured shadows on the floor: a shadow ray meets one plate first and passes
// the other at the same depth. From frame 2 on each pair is written the other way round
// and the ball moves: the shadows take the other plate's colour.
#version 3.7;
global_settings { assumed_gamma 1.0 }
camera { location <0,2,-5> look_at <0,0,0> angle 50 }
light_source { <0,20,0> rgb 1 }
plane { y, 0 pigment { rgb 0.9 } }
#for (I, 0, 2)
  #declare Red = box { <-2.2 + I*1.2,6,-1>, <-1.4 + I*1.2,6.1,0.5> pigment { rgbf <1,0.2,0.2,0.9> } }
  #declare Blue = box { <-2.2 + I*1.2,6,-1>, <-1.4 + I*1.2,6.1,0.5> pigment { rgbf <0.2,0.2,1,0.9> } }
  #if (frame_number = 1) object { Red } object { Blue } #else object { Blue } object { Red } #end
#end
sphere { <-1 + 2*clock, 0.3, -1.5>, 0.3 pigment { rgb <0.5,1,0.5> } }
