// Unit square 0..1000 mm in X and Y with named physical groups, for the mesh reader tests.
// Regenerate (see README.md):
//   gmsh -2 square_groups.geo -format msh41 -o square_groups.msh
//   gmsh -2 square_groups.geo -format msh22 -o square_groups_v2.msh
lc = 250;  // 4 divisions per side: 30 nodes, 42 triangles
Point(1) = {0, 0, 0, lc};
Point(2) = {1000, 0, 0, lc};
Point(3) = {1000, 1000, 0, lc};
Point(4) = {0, 1000, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Point("corner") = {1};
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Surface("film") = {1};
