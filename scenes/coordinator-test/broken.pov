// coordinator test scene that does not parse: the sphere below lacks its closing brace,
// so POV-Ray stops at line 9 with "No matching } in 'sphere'".
#version 3.7;
camera { location <0, 2, -6> look_at <0, 0.8, 0> }
light_source { <4, 8, -6> color rgb 1 }
sphere { <0, 0.8, 0>, 0.8
  pigment { color rgb <0.9, 0.3, 0.2> }

box { <-1, 0, 1>, <1, 1, 2> }
