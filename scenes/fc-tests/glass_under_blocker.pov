// fc-test:
// Two opaque discs hang over the floor, a glass slab under each, and a shadow test from the
// floor passes the glass before it meets a disc. POV-Ray's shadow loop goes on from where
// the ray leaves the glass and ignores what it meets within SHADOW_TOLERANCE of there, so
// where a slab's top comes within that of its disc the light leaks through the disc. The
// left slab slides in under its disc; the right one grows until its top nearly touches its
// disc: in both, a shadow an opaque disc cast changes though the disc stays.
#version 3.7;
global_settings { assumed_gamma 1.0 }
camera { location <0, 6, -5> look_at <0, 0.5, 0> angle 50 }
light_source { <1, 12, -2> rgb 1 }
plane { y, 0 pigment { checker rgb 0.9 rgb 0.6 } }
#declare Blocker = disc { <0, 1, 0>, y, 0.9 pigment { rgb <0.8, 0.2, 0.2> } }
#declare Glass = pigment { rgbf <0.6, 0.9, 1, 0.9> }
object { Blocker translate -1.2*x }
box { <-0.8, 0.5, -0.8>, <0.8, 0.9996, 0.8> pigment { Glass } translate <-1.2 - 2.4 + 2.4*clock, 0, 0> }
object { Blocker translate 1.2*x }
box { <-0.8, 0.5, -0.8>, <0.8, 0.99 + 0.0096*clock, 0.8> pigment { Glass } translate 1.2*x }
