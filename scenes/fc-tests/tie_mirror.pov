// fc-test:
// Pairs of coincident boxes seen only in a mirror (they stand behind the camera): every
// reflected ray meets a tie. From frame 2 on each pair is written the other way round
// and the ball in front moves: POV-Ray meets the other box of a pair first.
#version 3.7;
global_settings { assumed_gamma 1.0 }
camera { location <0,1.5,-3> look_at <0,0.8,0> angle 50 }
light_source { <3,8,-5> rgb 1 }
plane { y, 0 pigment { rgb 0.7 } }
box { <-3,0,1>, <3,2.5,1.05> pigment { rgb 0.1 } finish { reflection 0.9 } }
#for (I, 0, 2)
  #declare Red = box { <-2.2 + I*1.2,0,-5>, <-1.4 + I*1.2,1.2,-4.6> pigment { rgb <1,0.2,0.2> } }
  #declare Blue = box { <-2.2 + I*1.2,0,-5>, <-1.4 + I*1.2,1.2,-4.6> pigment { rgb <0.2,0.2,1> } }
  #if (frame_number = 1) object { Red } object { Blue } #else object { Blue } object { Red } #end
#end
sphere { <-1 + 2*clock, 0.3, -1>, 0.3 pigment { rgb <0.5,1,0.5> } }
