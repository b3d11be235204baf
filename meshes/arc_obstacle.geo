// The rigid arc of options/plate_on_arc.yml as a meshed obstacle (-obstacle_mesh) for a 2D body: the circle of
// radius 4 centred at (4.5, -4.1) from 150 to 30 degrees in 30 lines of equal angle (the points of -obstacle_arcs
// 4.5,-4.1,4,150,30,30), each line going clockwise so that its left normal points away from the centre, into the
// plate above. Explicit points: a meshed Circle would place its nodes at angles 1e-7 degrees off. Physical curve "arc".
R = 4; cx = 4.5; cy = -4.1; n = 30;
For k In {0 : n}
  t = (150 + (30 - 150) * k / n) * Pi / 180;
  Point(k + 1) = {cx + R * Cos(t), cy + R * Sin(t), 0};
EndFor
For k In {1 : n}
  Line(k) = {k, k + 1};
EndFor
Physical Curve("arc") = {1 : n};
