// The datasets of a results file, one row each. Everything that names them follows this table:
// the HDF5 writer (src/io/output_hdf5.cpp) writes a row's values and its self-description (the
// dataset attributes vector_field_type, units, family, description; the root attribute
// field_table holds the whole table), the XDMF index (src/io/xdmf.cpp) shows a row under its
// viewer name(s), scripts/h5compare.py reads the families from those attributes, and
// docs/results.md is checked against the file by tests/regression/test_output_fields.py.
// A new field is one row here (and its values in CellFields or OutputValues).
#pragma once
#include <cstddef>
#include <iterator>
#include <string_view>
#include <vector>

#include "etfe/assembly/assembly.h"
#include "etfe/io/h5io.h"

namespace etfe {

// As PyLith's vector_field_type: how a reader should treat the components of a row.
enum class FieldKind { Scalar, Vector, Tensor, Other };
// When a row is written: once at the file's creation (/mesh), in every step, or in every step of a
// run with a plastic material, with -membrane_wrinkling tension_field, or with contact; Term: in
// every step of a run whose problem has the physics term that gives it (PhysicsTerm::Fields: the
// row <term name>/<field name>, its values from the term, not from OutputValues).
enum class FieldWhen { Open, Step, Plastic, Wrinkling, Contact, Term };

// The values the writer has at hand, in PETSc order on the owning rank (rows of `components`).
struct OutputValues {
  const double *coordinates = nullptr;  // owned nodes: reference X, Y, Z
  std::vector<double> triangles;        // owned elements: scene node ids, exact as doubles
  const double *displacement = nullptr, *reaction = nullptr;  // owned nodes
  CellFields cells;                                           // owned elements
  std::vector<double> force, slide_local, slide_global, status, node;  // owned contact pairs
};

struct OutputField {
  const char *name;  // dataset path below /steps/<k>/ (contact/...), or from the root for mesh/...
  Layout location;   // one row per node, element (cell) or contact pair
  int components;    // columns (1: a one-dimensional dataset)
  FieldKind kind;
  bool integer;       // int32 in the file (ids, codes), else float64
  const char *units;  // "1": dimensionless, a code or an id
  // Fields of one family share a scale: h5compare --family-scale measures each against the
  // family's largest value in the step. A field that shares with none is its own family.
  const char *family;
  FieldWhen when;
  // Its name in the XDMF index, one attribute of all its columns (src/io/xdmf.cpp: Scalar,
  // Vector, Tensor6 or Matrix); a name of several columns lists them in order (PK2_Sxx_Syy_Sxy),
  // since ParaView shows them only as components 0, 1, 2. nullptr: it is the grid's geometry or
  // topology, not an attribute.
  const char *viewer;
  const char *description;
  const double *(*values)(const OutputValues &);
};

inline constexpr OutputField kOutputFields[] = {
    {"mesh/coordinates", Layout::Nodes, 3, FieldKind::Vector, false, "mm", "coordinates", FieldWhen::Open, nullptr,
     "reference coordinates X Y Z, scene node order", [](const OutputValues &v) { return v.coordinates; }},
    {"mesh/triangles", Layout::Cells, 3, FieldKind::Other, true, "1", "triangles", FieldWhen::Open, nullptr,
     "0-based scene node ids of each triangle, scene element order",
     [](const OutputValues &v) -> const double * { return v.triangles.data(); }},
    {"displacement", Layout::Nodes, 3, FieldKind::Vector, false, "mm", "displacement", FieldWhen::Step,
     "displacement", "displacement u x y z from the scene's mesh", [](const OutputValues &v) { return v.displacement; }},
    {"reaction", Layout::Nodes, 3, FieldKind::Vector, false, "N", "reaction", FieldWhen::Step, "reaction",
     "reaction x y z: the internal force at the constrained degrees of freedom", [](const OutputValues &v) { return v.reaction; }},
    {"nodal_mises", Layout::Nodes, 1, FieldKind::Scalar, false, "MPa", "stress", FieldWhen::Step, "nodal_mises_PK2",
     "von Mises of the PK2 stress, average of the elements around the node",
     [](const OutputValues &v) { return v.cells.nodal_mises.data(); }},
    {"stress", Layout::Cells, 3, FieldKind::Tensor, false, "MPa", "stress", FieldWhen::Step,
     "PK2_Sxx_Syy_Sxy", "2nd Piola-Kirchhoff stress Sxx Syy Sxy, element MD/TD frame (x = MD)",
     [](const OutputValues &v) { return v.cells.stress.data(); }},
    {"strain", Layout::Cells, 3, FieldKind::Tensor, false, "1", "strain", FieldWhen::Step, "GL_Exx_Eyy_Exy",
     "Green-Lagrange strain Exx Eyy Exy (tensor shear), element MD/TD frame",
     [](const OutputValues &v) { return v.cells.strain.data(); }},
    {"mises", Layout::Cells, 1, FieldKind::Scalar, false, "MPa", "stress", FieldWhen::Step, "mises_PK2",
     "von Mises of the PK2 stress", [](const OutputValues &v) { return v.cells.mises.data(); }},
    {"min_principal_stress", Layout::Cells, 1, FieldKind::Scalar, false, "MPa", "stress", FieldWhen::Step,
     "min_principal_stress_PK2", "smaller in-plane principal PK2 stress", [](const OutputValues &v) { return v.cells.smin.data(); }},
    {"min_principal_strain", Layout::Cells, 1, FieldKind::Scalar, false, "1", "strain", FieldWhen::Step,
     "min_principal_strain_GL", "smaller in-plane principal Green-Lagrange strain",
     [](const OutputValues &v) { return v.cells.emin.data(); }},
    {"area_ratio", Layout::Cells, 1, FieldKind::Scalar, false, "1", "area_ratio", FieldWhen::Step, "area_ratio",
     "current over reference element area", [](const OutputValues &v) { return v.cells.area_ratio.data(); }},
    {"cauchy_stress", Layout::Cells, 6, FieldKind::Tensor, false, "MPa", "stress", FieldWhen::Step, "cauchy_stress",
     "true (Cauchy) stress xx yy zz xy yz xz, global frame", [](const OutputValues &v) { return v.cells.cauchy.data(); }},
    {"cauchy_mises", Layout::Cells, 1, FieldKind::Scalar, false, "MPa", "stress", FieldWhen::Step, "cauchy_mises",
     "von Mises of the Cauchy stress", [](const OutputValues &v) { return v.cells.cauchy_mises.data(); }},
    {"principal_stress", Layout::Cells, 2, FieldKind::Other, false, "MPa", "stress", FieldWhen::Step,
     "principal_stress_1_2", "in-plane principal Cauchy stresses, largest first",
     [](const OutputValues &v) { return v.cells.principal.data(); }},
    {"principal_dir1", Layout::Cells, 3, FieldKind::Vector, false, "1", "principal_direction", FieldWhen::Step,
     "principal_dir1", "unit direction of principal_stress_1, global, current configuration (sign free)",
     [](const OutputValues &v) { return v.cells.dir1.data(); }},
    {"principal_dir2", Layout::Cells, 3, FieldKind::Vector, false, "1", "principal_direction", FieldWhen::Step,
     "principal_dir2", "unit direction of principal_stress_2, global, current configuration (sign free)",
     [](const OutputValues &v) { return v.cells.dir2.data(); }},
    {"plastic_strain", Layout::Cells, 3, FieldKind::Tensor, false, "1", "strain", FieldWhen::Plastic,
     "plastic_Exx_Eyy_Exy", "plastic Green-Lagrange strain Exx Eyy Exy, element MD/TD frame",
     [](const OutputValues &v) { return v.cells.ep.data(); }},
    {"plastic_strain_eq", Layout::Cells, 1, FieldKind::Scalar, false, "1", "strain", FieldWhen::Plastic,
     "plastic_strain_eq", "equivalent plastic strain", [](const OutputValues &v) { return v.cells.ep_bar.data(); }},
    {"wrinkle_state", Layout::Cells, 1, FieldKind::Scalar, false, "1", "wrinkle_state", FieldWhen::Wrinkling,
     "wrinkle_state", "0 taut, 1 wrinkled, 2 slack", [](const OutputValues &v) { return v.cells.wrinkle_state.data(); }},
    {"wrinkle_dir", Layout::Cells, 3, FieldKind::Vector, false, "1", "wrinkle_dir", FieldWhen::Wrinkling,
     "wrinkle_dir", "wrinkle (tension) direction, global unit vector, current configuration; 0 when not wrinkled",
     [](const OutputValues &v) { return v.cells.wrinkle_dir.data(); }},
    {"wrinkle_strain", Layout::Cells, 1, FieldKind::Scalar, false, "1", "strain", FieldWhen::Wrinkling,
     "wrinkle_strain", "Green-Lagrange strain taken up by wrinkles",
     [](const OutputValues &v) { return v.cells.wrinkle_strain.data(); }},
    {"contact/force", Layout::Pairs, 3, FieldKind::Vector, false, "N", "contact_force", FieldWhen::Contact,
     "contact_force", "contact force in the pair's frame: x0 tangent, y0, z0 normal (f_z < 0 in compression)",
     [](const OutputValues &v) { return v.force.data(); }},
    {"contact/slide_local", Layout::Pairs, 2, FieldKind::Vector, false, "mm", "slide_local", FieldWhen::Contact,
     "slide_x0_y0", "slide since t0 along the pair's x0, y0", [](const OutputValues &v) { return v.slide_local.data(); }},
    {"contact/slide_global", Layout::Pairs, 2, FieldKind::Vector, false, "mm", "slide_global", FieldWhen::Contact,
     "slide_X_Y", "slide since t0 in plan, global X, Y", [](const OutputValues &v) { return v.slide_global.data(); }},
    {"contact/status", Layout::Pairs, 1, FieldKind::Scalar, true, "1", "contact_status", FieldWhen::Contact,
     "contact_status", "0 open, 1 stick, 2 slip", [](const OutputValues &v) { return v.status.data(); }},
    {"contact/node", Layout::Pairs, 1, FieldKind::Scalar, true, "1", "contact_node", FieldWhen::Contact, nullptr,
     "scene id of the pair's film node (the XDMF's contact point set)", [](const OutputValues &v) { return v.node.data(); }},
    {"chambers/gauge_pressure", Layout::Items, 1, FieldKind::Scalar, false, "MPa", "chamber_pressure", FieldWhen::Term,
     nullptr, "gauge pressure of each gas chamber, the scene's chamber order (not in the XDMF: no mesh entity)", nullptr},
    {"chambers/volume", Layout::Items, 1, FieldKind::Scalar, false, "mm^3", "chamber_volume", FieldWhen::Term, nullptr,
     "volume each gas chamber encloses, the scene's chamber order (not in the XDMF: no mesh entity)", nullptr},
    {"cables/force", Layout::Items, 1, FieldKind::Scalar, false, "N", "cable_force", FieldWhen::Term, nullptr,
     "axial force of each cable segment, the cables in the scene's order, each from its first end (not in the XDMF)",
     nullptr},
    {"cables/length", Layout::Items, 1, FieldKind::Scalar, false, "mm", "cable_length", FieldWhen::Term, nullptr,
     "current length of each cable segment, as cables/force", nullptr},
    {"cables/slack", Layout::Items, 1, FieldKind::Scalar, false, "1", "cable_slack", FieldWhen::Term, nullptr,
     "1 where a cable segment is slack (carries nothing), as cables/force", nullptr},
    {"cables/cable", Layout::Items, 1, FieldKind::Scalar, false, "1", "cable_index", FieldWhen::Term, nullptr,
     "the cable of each segment: its index in the scene's cable order", nullptr},
};

// The row of a dataset name, -1 when the table has none.
constexpr int OutputFieldIndex(std::string_view name) {
  for (int i = 0; i < (int)std::size(kOutputFields); ++i)
    if (name == kOutputFields[i].name) return i;
  return -1;
}

// A row's viewer name is one word: the XDMF index shows a row as one attribute. (Columns as
// scalars of their own would need hyperslabs, which ParaView's XDMF3 readers skip.)
constexpr bool ViewerIsOneName(const OutputField &f) {
  if (!f.viewer || !*f.viewer) return !f.viewer;
  for (const char *c = f.viewer; *c; ++c)
    if (*c == ' ') return false;
  return true;
}

constexpr bool ViewersAreOneName() {
  for (const OutputField &f : kOutputFields)
    if (!ViewerIsOneName(f)) return false;
  return true;
}
static_assert(ViewersAreOneName(), "an output field's viewer name is not one word (see OutputField::viewer)");

// The names the file uses, by enum value: vector_field_type, and the field table's location and
// written columns.
inline constexpr const char *kFieldKindName[] = {"scalar", "vector", "tensor", "other"};
inline constexpr const char *kFieldLocationName[] = {"node", "cell", "contact pair", "item"};  // by Layout
inline constexpr const char *kFieldWhenName[] = {"once",      "every step", "plastic material",
                                                 "wrinkling", "contact",    "with its term"};

} // namespace etfe
