// Symmetric bifurcated vessel (thesis Fig. 7.4, section 7.3.2): one inlet channel that
// splits into two symmetric branches. Dimensionless lengths (unit = the inlet width).
//
//   inlet channel  x in [0, 3], y in [-0.5, 0.5] (width 1)
//   branches       width 0.7, at +-30 degrees to the x axis, outer walls 3.5 long from
//                  (3, +-0.5); they meet at the apex (3.5339, 0) on the symmetry line
//   outlets        perpendicular to each branch, width 0.7
//   mirror symmetric about y = 0; area 8.01828 (polygon), wall length 19.5751
//
// Physical groups (facet tags of the generated XDMF):
//   inflow          x = 0, -0.5 < y < 0.5
//   outflow_upper   end of the upper branch
//   outflow_lower   end of the lower branch
//   wall            every other boundary curve
//   domain          the surface (cells)
// Mesh size h = 0.125 (about 8 cells across the inlet).

h = 0.125;
c = Cos(Pi/6); s = Sin(Pi/6);   // branch direction (c, +-s)
L = 3.5;                        // outer wall length of a branch
w = 0.7;                        // branch width
xo = 3 + L*c; yo = 0.5 + L*s;   // outer end of the upper branch
xi = xo + w*s; yi = yo - w*c;   // inner end (outer end minus w times the normal (-s, c))
xa = xi - yi*c/s;               // apex: the inner wall line meets y = 0

Point(1) = {0, -0.5, 0, h};
Point(2) = {0,  0.5, 0, h};
Point(3) = {3,  0.5, 0, h};
Point(4) = {xo,  yo, 0, h};
Point(5) = {xi,  yi, 0, h};
Point(6) = {xa,   0, 0, h};
Point(7) = {xi, -yi, 0, h};
Point(8) = {xo, -yo, 0, h};
Point(9) = {3, -0.5, 0, h};

Line(1) = {1, 2};   // inflow
Line(2) = {2, 3};   // wall
Line(3) = {3, 4};   // wall (outer, upper branch)
Line(4) = {4, 5};   // outflow_upper
Line(5) = {5, 6};   // wall (inner, upper branch)
Line(6) = {6, 7};   // wall (inner, lower branch)
Line(7) = {7, 8};   // outflow_lower
Line(8) = {8, 9};   // wall (outer, lower branch)
Line(9) = {9, 1};   // wall

Curve Loop(1) = {1, 2, 3, 4, 5, 6, 7, 8, 9};
Plane Surface(1) = {1};

Physical Curve("inflow") = {1};
Physical Curve("outflow_upper") = {4};
Physical Curve("outflow_lower") = {7};
Physical Curve("wall") = {2, 3, 5, 6, 8, 9};
Physical Surface("domain") = {1};
