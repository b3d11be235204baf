// A flat rigid surface z = 0 under the unit cube of meshes/cube.geo, for -obstacle_mesh: the square [-0.25, 1.25]^2
// as triangles (x < 0.6) and quadrilaterals (x > 0.6), oriented counter-clockwise seen from above so that every
// normal (right-hand rule) is +z, into the body. Physical surface "floor".
Point(1) = {-0.25, -0.25, 0}; Point(2) = {0.6, -0.25, 0}; Point(3) = {1.25, -0.25, 0};
Point(4) = {1.25, 1.25, 0}; Point(5) = {0.6, 1.25, 0}; Point(6) = {-0.25, 1.25, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5}; Line(5) = {5, 6}; Line(6) = {6, 1};
Line(7) = {2, 5};
Curve Loop(1) = {1, 7, 5, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, 4, -7};
Plane Surface(2) = {2};
Transfinite Curve{1, 5} = 3; Transfinite Curve{2, 4} = 3; Transfinite Curve{3, 6, 7} = 4;
Transfinite Surface{1}; Transfinite Surface{2};
Recombine Surface{2};
Physical Surface("floor") = {1, 2};
