// A CAD surface for the CAD reader's test (tests/unit/test_cad_reader.cpp): a cylindrical vault
// (radius 1000 mm, 60 degrees of arc about the Z axis, 1500 mm long in Z) and a flat apron
// (500 x 1500 mm in the plane Y = 0) meeting it along its edge X = 1000, Y = 0.
// Areas: vault 1000 * pi/3 * 1500 = 1.5708e6 mm^2, apron 7.5e5 mm^2.
// Written as STEP with `gmsh cad_vault.geo -0 -o cad_vault.step`, then named (README.md).
SetFactory("OpenCASCADE");
Circle(1) = {0, 0, 0, 1000, 0, Pi/3};
Extrude {0, 0, 1500} { Curve{1}; }
Point(10) = {1000, 0, 0};
Point(11) = {1500, 0, 0};
Line(10) = {10, 11};
Extrude {0, 0, 1500} { Curve{10}; }
