// The film's stress-free state as the flat cutting patterns of its strips (pattern_reference.cpp).
#pragma once
#include <petscsys.h>

#include <string>
#include <vector>

#include "etfe/analyses/cutpattern.h"
#include "etfe/mesh/mesh_data.h"

namespace etfe {

struct PatternStrips {
  std::vector<std::string> strips;  // element sets of the mesh, each flattened on its own
  std::string option;               // what asked for it, for messages ("-saddle_reference pattern")
  std::string scene;                // the report lines' prefix ("saddle")
  std::string missing_hint;         // what to do when a strip is missing from the mesh
  // With compensation (-cutpattern_compensation uniform, or stress with -cutpattern_prestress):
  // the patterns are cut as -cutpattern cuts them, so the laid-on film reaches the prestress.
  const CutPatternOptions *cut = nullptr;
};

// Per element of m (9 each) its triangle in the flat pattern of its strip, for
// SceneSpec::element_reference. Every element must lie in exactly one strip. Collective: rank 0,
// which holds the mesh, flattens the strips; a failure is an error on every rank.
PetscErrorCode PatternReference(MPI_Comm comm, const MeshData &m, const PatternStrips &strips,
                                std::vector<double> *element_reference);

} // namespace etfe
