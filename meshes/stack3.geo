// Three blocks 2 x 1 stacked (2D), non-matching meshes on both interfaces (y = 1 and y = 2), each block with its own
// points: three bodies. The middle one touches only the other two, so only both interfaces together hold it.
// -setnumber gap G opens both interfaces by G at the start (stack3_gap.msh: G = 0.01).
// Physical groups: low, mid, high (surfaces); bottom, low_top, mid_bottom, mid_top, high_bottom, high_top, left
// (the three blocks' left sides) (curves).
DefineConstant[gap = 0];
W = 2;
For k In {0:2}
  p = newp; l = newl;
  y = k * (1 + gap);
  Point(p) = {0, y, 0}; Point(p + 1) = {W, y, 0}; Point(p + 2) = {W, y + 1, 0}; Point(p + 3) = {0, y + 1, 0};
  Line(l) = {p, p + 1}; Line(l + 1) = {p + 1, p + 2}; Line(l + 2) = {p + 2, p + 3}; Line(l + 3) = {p + 3, p};
  Curve Loop(k + 1) = {l, l + 1, l + 2, l + 3}; Plane Surface(k + 1) = {k + 1};
  Transfinite Curve{l, l + 2} = 4 + 3 * k;
  Transfinite Curve{l + 1, l + 3} = 4;
  Transfinite Surface{k + 1};
  bottoms[k] = l; tops[k] = l + 2; lefts[k] = l + 3;
EndFor
Recombine Surface{2};
Physical Surface("low") = {1};
Physical Surface("mid") = {2};
Physical Surface("high") = {3};
Physical Curve("bottom") = {bottoms[0]};
Physical Curve("low_top") = {tops[0]};
Physical Curve("mid_bottom") = {bottoms[1]};
Physical Curve("mid_top") = {tops[1]};
Physical Curve("high_bottom") = {bottoms[2]};
Physical Curve("high_top") = {tops[2]};
Physical Curve("left") = {lefts[0], lefts[1], lefts[2]};
