// coordinator test scene that parses for the first half of the animation only: from
// clock 0.5 on, #error stops POV-Ray, as a scene bug in one frame would.
#version 3.7;
#if (clock >= 0.5)
  #error "fails-late.pov: deliberate failure in the second half"
#end
camera { location <0, 2, -6> look_at <0, 0.8, 0> angle 50 }
light_source { <4, 8, -6> color rgb 1 }
plane { y, 0 pigment { checker color rgb 0.9 color rgb <0.2, 0.3, 0.5> } }
sphere { <-2.5 + 5*clock, 0.8, 0>, 0.8 pigment { color rgb <0.9, 0.3, 0.2> } }
