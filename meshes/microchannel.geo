// Chamber joined to a narrow micro-channel, for the chemotaxis demo of thesis Fig. 5.11
// (a cell on the right migrates into a tube of 10 um thickness). Dimensionless lengths,
// unit 10 um = the tube width.
//
//   tube      x in [0, 3], y in [-0.5, 0.5] (width 1, length 3)
//   chamber   x in [3, 9], y in [-2.5, 2.5] (6 x 5)
//   area 33 (polygon)
//
// Physical groups (facet tags of the generated XDMF):
//   inflow    x = 9, the right side of the chamber (the flow enters here)
//   outflow   x = 0, the open end of the tube
//   wall      every other boundary curve
//   domain    the surface (cells)
// Mesh size 0.2 in the chamber, 0.1 in the tube (10 cells across it).

H = 0.2; h = 0.1;

Point(1) = {0, -0.5, 0, h};
Point(2) = {3, -0.5, 0, h};
Point(3) = {3, -2.5, 0, H};
Point(4) = {9, -2.5, 0, H};
Point(5) = {9,  2.5, 0, H};
Point(6) = {3,  2.5, 0, H};
Point(7) = {3,  0.5, 0, h};
Point(8) = {0,  0.5, 0, h};

Line(1) = {1, 2};   // wall (tube, bottom)
Line(2) = {2, 3};   // wall (chamber, left, lower part)
Line(3) = {3, 4};   // wall (chamber, bottom)
Line(4) = {4, 5};   // inflow
Line(5) = {5, 6};   // wall (chamber, top)
Line(6) = {6, 7};   // wall (chamber, left, upper part)
Line(7) = {7, 8};   // wall (tube, top)
Line(8) = {8, 1};   // outflow

Curve Loop(1) = {1, 2, 3, 4, 5, 6, 7, 8};
Plane Surface(1) = {1};

Physical Curve("inflow") = {4};
Physical Curve("outflow") = {8};
Physical Curve("wall") = {1, 2, 3, 5, 6, 7};
Physical Surface("domain") = {1};
