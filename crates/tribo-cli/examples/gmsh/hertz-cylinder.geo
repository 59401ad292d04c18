// A half cylinder (R = 10 mm) pressed on a block (20 x 10 mm): 2D Hertz contact from a
// gmsh mesh, for `tribo run hertz-cylinder.toml` (the case file beside this one).
// Mesh it with:  gmsh hertz-cylinder.geo -2 -order 2 -format msh41 -o hertz-cylinder.msh
// (or run make_mesh.py beside it, which does the same through gmsh's Python API).
//
// The two bodies are separate surfaces whose curves are NOT fused: they only touch at
// (0, 0), so the contact between them is found by the solver (coincident points are kept
// apart: Geometry.AutoCoherence = 0). Physical curves name the segments the case refers
// to; physical surfaces name the regions (one material each). The boundary elements are
// graded geometrically toward the contact point, the cylinder's (the slave) finer than
// the block's (the master).

Geometry.AutoCoherence = 0;
R = 10e-3;       // cylinder radius, m
W = 10e-3;       // half width of the block, m
H = 10e-3;       // block depth, m

// Block, its top split at the contact point.
Point(1) = {-W, -H, 0};
Point(2) = { W, -H, 0};
Point(3) = { W,  0, 0};
Point(4) = { 0,  0, 0};
Point(5) = {-W,  0, 0};
Line(1) = {1, 2};   // bottom
Line(2) = {2, 3};   // right side
Line(3) = {3, 4};   // top, right half (toward the contact)
Line(4) = {4, 5};   // top, left half (away from the contact)
Line(5) = {5, 1};   // left side
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};

// Half cylinder above, touching the block at the origin.
Point(10) = { 0, R, 0};   // centre
Point(11) = { R, R, 0};
Point(12) = { 0, 0, 0};
Point(13) = {-R, R, 0};
Circle(10) = {13, 10, 12};   // left quarter, down to the contact point
Circle(11) = {12, 10, 11};   // right quarter, up
Line(12) = {11, 13};         // the flat face through the centre (loaded)
Curve Loop(2) = {10, 11, 12};
Plane Surface(2) = {2};

// Grading: element k from the contact is h0 q^k (q = 1.1): 60 on each quarter arc from
// h0 = 5.2 um, 52 on each half of the block's top from 7.1 um (b = 105 um: about 40 slave
// elements across the contact).
Transfinite Curve{10} = 61 Using Progression 1/1.1;
Transfinite Curve{11} = 61 Using Progression 1.1;
Transfinite Curve{3} = 53 Using Progression 1/1.1;
Transfinite Curve{4} = 53 Using Progression 1.1;
Transfinite Curve{12} = 9;
Transfinite Curve{1} = 9;
Transfinite Curve{2, 5} = 5;

Physical Curve("block_bottom") = {1};
Physical Curve("block_sides") = {2, 5};
Physical Curve("block_top") = {3, 4};
Physical Curve("cyl_arc") = {10, 11};
Physical Curve("cyl_face") = {12};
Physical Surface("block") = {1};
Physical Surface("cylinder") = {2};
