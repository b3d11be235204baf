// A flat rigid surface z = 0 under the unit cube of meshes/cube.geo, for -obstacle_mesh: the square [-0.5, 1.5]^2
// as triangles (x < 1) and quadrilaterals (x > 1), oriented counter-clockwise seen from above so that every normal
// (right-hand rule) is +z, into the body. Facet edges run along x = 0, x = 1, y = 0 and y = 1, through the nodes of the
// cube's bottom edges and corners, which therefore lie on two to six facets (parallel duplicates of one constraint).
// Physical surface "floor".
Point(1) = {-0.5, -0.5, 0}; Point(2) = {1, -0.5, 0}; Point(3) = {1.5, -0.5, 0};
Point(4) = {1.5, 1.5, 0}; Point(5) = {1, 1.5, 0}; Point(6) = {-0.5, 1.5, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5}; Line(5) = {5, 6}; Line(6) = {6, 1};
Line(7) = {2, 5};
Curve Loop(1) = {1, 7, 5, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, 4, -7};
Plane Surface(2) = {2};
Transfinite Curve{1, 5} = 4; Transfinite Curve{2, 4} = 2; Transfinite Curve{3, 6, 7} = 5;
Transfinite Surface{1}; Transfinite Surface{2};
Recombine Surface{2};
Physical Surface("floor") = {1, 2};
