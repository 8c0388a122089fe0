// Straight channel for the tests (tests/cpp/test_mesh_domain.cpp): Poiseuille flow.
//
//   x in [0, 4], y in [0, 1]; area 4
//
// Physical groups (facet tags of the generated XDMF):
//   inflow    x = 0
//   outflow   x = 4
//   wall      y = 0 and y = 1
//   domain    the surface (cells)
// Mesh size 0.25 (unstructured).

h = 0.25;
Point(1) = {0, 0, 0, h};
Point(2) = {4, 0, 0, h};
Point(3) = {4, 1, 0, h};
Point(4) = {0, 1, 0, h};
Line(1) = {1, 2};   // wall
Line(2) = {2, 3};   // outflow
Line(3) = {3, 4};   // wall
Line(4) = {4, 1};   // inflow
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Curve("inflow") = {4};
Physical Curve("outflow") = {2};
Physical Curve("wall") = {1, 3};
Physical Surface("domain") = {1};
