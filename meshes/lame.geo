// Lame thick-walled cylinder (inner radius 1, outer radius 2), quarter model in the first quadrant, triangles.
// Physical groups: body (surface), inner (arc r = 1, pressurised), outer (arc r = 2, free), symmetry_x (edge on
// x = 0, u_x = 0), symmetry_y (edge on y = 0, u_y = 0). Refine with -mesh_size_factor (or gmsh -clscale).
a = 1; b = 2; h = 0.2;
Point(1) = {0, 0, 0, h};
Point(2) = {a, 0, 0, h}; Point(3) = {b, 0, 0, h};
Point(4) = {0, b, 0, h}; Point(5) = {0, a, 0, h};
Line(1) = {2, 3};
Circle(2) = {3, 1, 4};
Line(3) = {4, 5};
Circle(4) = {5, 1, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface("body") = {1};
Physical Curve("symmetry_y") = {1};
Physical Curve("outer") = {2};
Physical Curve("symmetry_x") = {3};
Physical Curve("inner") = {4};
