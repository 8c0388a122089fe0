// Chamber joined to a narrow micro-channel, for the chemotaxis demo of thesis Fig. 5.11
// (a cell in the chamber migrates into a tube of 10 um thickness). Dimensionless lengths
// in the unit of chapter 5, L = 5 um (the radius of the round cell), so the tube is 2 wide.
//
//   tube      x in [0, 5],  y in [-1, 1]  (width 2, length 5)
//   chamber   x in [5, 11], y in [-3, 3]  (6 x 6)
//   area 46 (polygon)
//
// Physical groups (facet tags of the generated XDMF):
//   chamber_end   x = 11, the right side of the chamber (length 6)
//   tube_end      x = 0, the open end of the tube (length 2)
//   wall          every other boundary curve
//   domain        the surface (cells)
// Mesh size 0.7 everywhere, about the 0.75 base of the GTPase demos' rectangles: the
// adaptive refinement makes the cell's surroundings as fine as in those demos (a finer
// base, e.g. in the tube, would refine the band around the cell further and double the
// cost); 3 P2 cells across the empty tube carry its parabolic flow.

H = 0.7; h = 0.7;

Point(1) = {0, -1, 0, h};
Point(2) = {5, -1, 0, h};
Point(3) = {5, -3, 0, H};
Point(4) = {11, -3, 0, H};
Point(5) = {11,  3, 0, H};
Point(6) = {5,  3, 0, H};
Point(7) = {5,  1, 0, h};
Point(8) = {0,  1, 0, h};

Line(1) = {1, 2};   // wall (tube, bottom)
Line(2) = {2, 3};   // wall (chamber, left, lower part)
Line(3) = {3, 4};   // wall (chamber, bottom)
Line(4) = {4, 5};   // chamber_end
Line(5) = {5, 6};   // wall (chamber, top)
Line(6) = {6, 7};   // wall (chamber, left, upper part)
Line(7) = {7, 8};   // wall (tube, top)
Line(8) = {8, 1};   // tube_end

Curve Loop(1) = {1, 2, 3, 4, 5, 6, 7, 8};
Plane Surface(1) = {1};

Physical Curve("chamber_end") = {4};
Physical Curve("tube_end") = {8};
Physical Curve("wall") = {1, 2, 3, 5, 6, 7};
Physical Surface("domain") = {1};
