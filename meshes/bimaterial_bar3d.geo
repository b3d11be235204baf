// The bar of bimaterial_bar.geo in 3D: [0, 1.2] x [0, 0.4]^2 (soft) and [1.2, 2] x [0, 0.4]^2 (stiff), tetrahedra,
// one connected body (tests/cases, bimaterial_bar:3d).
// Physical groups: soft, stiff (volumes), left, right (surfaces), origin (0, 0, 0), corner (0, 0.4, 0).
h = 0.2;
Point(1) = {0, 0, 0, h}; Point(2) = {1.2, 0, 0, h}; Point(3) = {2, 0, 0, h};
Point(4) = {2, 0.4, 0, h}; Point(5) = {1.2, 0.4, 0, h}; Point(6) = {0, 0.4, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 5}; Line(3) = {5, 6}; Line(4) = {6, 1};
Line(5) = {2, 3}; Line(6) = {3, 4}; Line(7) = {4, 5};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, -2};
Plane Surface(2) = {2};
// Extruded without Recombine: each prism is split into tetrahedra, conforming across the interface x = 1.2.
soft[] = Extrude {0, 0, 0.4} { Surface{1}; Layers{2}; };
stiff[] = Extrude {0, 0, 0.4} { Surface{2}; Layers{2}; };
Physical Volume("soft") = {soft[1]};
Physical Volume("stiff") = {stiff[1]};
Physical Surface("left") = {soft[5]};
Physical Surface("right") = {stiff[3]};
Physical Point("origin") = {1};
Physical Point("corner") = {6};
