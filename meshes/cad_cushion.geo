// A closed body for the CAD reader's test (tests/unit/test_cad_reader.cpp): a box 1000 x 1000 x
// 500 mm, a cushion drawn as a solid, whose STEP product is named "cushion" (README.md): its six
// faces take the solid's name. Surface area 4e6 mm^2.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1000, 1000, 500};
