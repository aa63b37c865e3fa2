// CAD surfaces through Gmsh's API (etfe/mesh/cad_reader.h): meshes/cad_vault.step (a 60-degree
// cylindrical vault of radius 1000 mm and a flat apron, both 1500 mm long, named "vault" and
// "apron" in the file) meshed at 50 mm gives positive triangles, a conforming oriented mesh, the
// named groups and the analytic areas; the same as BREP (cad_vault.brep) gives faces by tag; a
// named solid (cad_cushion.step) names its faces.
// Without the Gmsh API in the build, the refusal names the file and the way out. File names are
// recognized by their extension.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "check.h"
#include "etfe/mesh/cad_reader.h"

using etfe::MeshData;

namespace {

bool Contains(const std::string &s, const std::string &part) { return s.find(part) != std::string::npos; }

double TriangleArea(const MeshData &m, int e) {
  const double *a = &m.coords[3 * m.triangles[3 * e]], *b = &m.coords[3 * m.triangles[3 * e + 1]],
               *c = &m.coords[3 * m.triangles[3 * e + 2]];
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  return 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

double SetArea(const MeshData &m, const std::string &name) {
  double area = 0.0;
  for (int e : m.element_sets.at(name)) area += TriangleArea(m, e);
  return area;
}

void TestNames() {
  for (const char *p : {"a.step", "dir/A.STP", "x.iges", "x.IGS", "roof.brep"})
    CHECK(etfe::IsCadFile(p), "%s is a CAD file", p);
  for (const char *p : {"a.msh", "step", "a.step.msh", "dir.step/a", "a.obj", ""})
    CHECK(!etfe::IsCadFile(p), "%s is not a CAD file", p);
  const std::string msg = etfe::CadUnavailableMessage("roof.step");
  CHECK(Contains(msg, "roof.step") && Contains(msg, "no Gmsh API") && Contains(msg, "libgmsh-dev") &&
            Contains(msg, "re-run cmake"),
        "refusal: %s", msg.c_str());
}

void TestWithoutApi(const std::string &dir) {
  MeshData m;
  std::string err;
  CHECK(!etfe::ReadMeshFile(dir + "/cad_vault.step", 50.0, &m, &err) && Contains(err, "no Gmsh API") &&
            Contains(err, "cad_vault.step"),
        "a build without the Gmsh API refuses the CAD file: %s", err.c_str());
}

void TestVault(const std::string &dir) {
  const std::string path = dir + "/cad_vault.step";
  const double pi = std::acos(-1.0), vault = 1000.0 * pi / 3.0 * 1500.0, apron = 500.0 * 1500.0;
  MeshData m;
  std::string err;
  CHECK(etfe::ReadMeshFile(path, 50.0, &m, &err), "%s", err.c_str());
  CHECK(m.NumElements() > 100, "%d triangles", m.NumElements());
  double smallest = 1e300;
  for (int e = 0; e < m.NumElements(); ++e) smallest = std::fmin(smallest, TriangleArea(m, e));
  CHECK(smallest > 1.0, "smallest triangle %g mm^2", smallest);  // 50 mm elements: ~1000 mm^2
  CHECK(m.element_sets.count("vault") && m.element_sets.count("apron") && m.element_sets.size() == 2,
        "element sets named from the STEP products (%zu sets)", m.element_sets.size());
  // Node sets of the two faces, their 7 edges (4 + 4, one shared) and 6 corners, by Gmsh tag.
  int curves = 0, points = 0;
  for (const auto &s : m.node_sets) {
    curves += s.first.rfind("curve_", 0) == 0;
    points += s.first.rfind("point_", 0) == 0;
  }
  CHECK(m.node_sets.count("vault") && m.node_sets.count("apron") && curves == 7 && points == 6,
        "node sets: %d curve_<tag>, %d point_<tag>", curves, points);
  // Faceting a radius of 1000 mm with 50 mm chords loses (50/1000)^2/12 ~ 2e-4 of the area.
  CHECK_CLOSE(SetArea(m, "vault"), vault, 1e-3, 0.0);
  CHECK_CLOSE(SetArea(m, "apron"), apron, 1e-9, 0.0);
  CHECK((int)(m.element_sets.at("vault").size() + m.element_sets.at("apron").size()) == m.NumElements(),
        "the sets partition the triangles");
  // The faces meet along X = 1000, Y = 0: fused into one conforming, orientable mesh.
  CHECK(etfe::MeshOrient(&m, &err) && etfe::MeshCheck(m, 1e-6, &err), "%s", err.c_str());
  CHECK((int)m.node_tags.size() == m.NumNodes() && (int)m.element_tags.size() == m.NumElements(),
        "Gmsh tags kept for messages");
  CHECK(!m.notes.empty() && Contains(m.notes[0], "target element size 50 mm"), "note: %s",
        m.notes.empty() ? "" : m.notes[0].c_str());

  // Gmsh is finalized after each reading: a second one (default size) starts it again.
  MeshData d;
  CHECK(etfe::ReadCadFile(path, 0.0, &d, &err), "%s", err.c_str());
  CHECK(!d.notes.empty() && Contains(d.notes[0], "1/50 of the model's bounding-box diagonal"), "note: %s",
        d.notes.empty() ? "" : d.notes[0].c_str());
  CHECK_CLOSE(SetArea(d, "vault") + SetArea(d, "apron"), vault + apron, 1e-3, 0.0);
  MeshData again;
  CHECK(etfe::ReadCadFile(path, 0.0, &again, &err) && again.coords == d.coords && again.triangles == d.triangles,
        "the same file and size give the same mesh");

  CHECK(!etfe::ReadCadFile(dir + "/no_such_file.step", 0.0, &d, &err) && Contains(err, "no_such_file.step"),
        "missing file: %s", err.c_str());
  CHECK(!etfe::ReadCadFile(path, 0.1, &d, &err) && Contains(err, "would make up to"),
        "a size 20000 times below the extent (a unit mistake) is refused: %s", err.c_str());
  const std::string junk = "test_cad_reader_junk.step";
  std::ofstream(junk) << "ISO-10303-21;\nthis is no STEP data\n";
  CHECK(!etfe::ReadCadFile(junk, 0.0, &d, &err) && Contains(err, junk), "junk file: %s", err.c_str());
  std::remove(junk.c_str());
}

// The same geometry as BREP (no names, no unit): the faces are surface_<tag>, in mm.
void TestBrep(const std::string &dir) {
  const double pi = std::acos(-1.0);
  MeshData m;
  std::string err;
  CHECK(etfe::ReadMeshFile(dir + "/cad_vault.brep", 50.0, &m, &err), "%s", err.c_str());
  CHECK(m.element_sets.size() == 2 && m.element_sets.count("surface_1") && m.element_sets.count("surface_2"),
        "unnamed faces by tag (%zu sets)", m.element_sets.size());
  if (m.element_sets.count("surface_1") && m.element_sets.count("surface_2")) {
    CHECK_CLOSE(SetArea(m, "surface_1"), 1000.0 * pi / 3.0 * 1500.0, 1e-3, 0.0);
    CHECK_CLOSE(SetArea(m, "surface_2"), 500.0 * 1500.0, 1e-9, 0.0);
  }
  CHECK(m.notes.size() == 2 && Contains(m.notes[1], "faces named in the file: none"), "note: %s",
        m.notes.size() > 1 ? m.notes[1].c_str() : "");
}

// A solid named in the STEP file (meshes/cad_cushion.step, a 1000 x 1000 x 500 mm box): its six
// faces take its name, and their mesh is one closed, consistently oriented surface.
void TestSolid(const std::string &dir) {
  MeshData m;
  std::string err;
  CHECK(etfe::ReadMeshFile(dir + "/cad_cushion.step", 100.0, &m, &err), "%s", err.c_str());
  CHECK(m.element_sets.size() == 1 && m.element_sets.count("cushion"), "the faces take the solid's name");
  if (m.element_sets.count("cushion")) CHECK_CLOSE(SetArea(m, "cushion"), 4e6, 1e-9, 0.0);
  CHECK(etfe::MeshOrient(&m, &err) && etfe::MeshCheck(m, 1e-6, &err), "%s", err.c_str());
}

} // namespace

int main(int argc, char **argv) {
  const std::string dir = argc > 1 ? argv[1] : "meshes";
  TestNames();
  if (etfe::CadMeshingBuiltIn()) {
    TestVault(dir);
    TestBrep(dir);
    TestSolid(dir);
  } else
    TestWithoutApi(dir);
  TEST_MAIN_END();
}
