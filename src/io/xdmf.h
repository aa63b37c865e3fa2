// The XDMF index of a results file: the light XML that ParaView (or VisIt) opens as a time series,
// pointing into the HDF5 file beside it. What it shows, and under which names, follows the field
// table (include/etfe/io/output_fields.h).
#pragma once
#include <petscsys.h>

#include <string>
#include <utility>
#include <vector>

#include "etfe/io/output_fields.h"

namespace etfe {

struct XdmfIndex {
  std::string path;     // the .xmf (written to path.tmp, then renamed: a reader never sees half)
  std::string results;  // the HDF5 file's name, beside the index
  std::string name;     // the scene: the temporal collection's name
  long long rows[4] = {0, 0, 0, 0};  // by Layout: nodes, cells, contact pairs, term items (unused)
  // With contact each step is a spatial collection of the film and the contact pairs (a point
  // set, one vertex per pair at its film node); without, the film alone.
  bool contact = false;
  std::vector<const OutputField *> fields;  // the fields of every step
};

// Rank 0 only; steps: the written steps (step, time), in order.
PetscErrorCode WriteXdmf(const XdmfIndex &index, const std::vector<std::pair<PetscInt, double>> &steps);

} // namespace etfe
