// Element partitioning with METIS (dual graph: elements sharing an edge are neighbours).
#pragma once
#include <string>
#include <vector>

#include "etfe/mesh/mesh_data.h"

namespace etfe {

// part[e] in [0, nparts). Returns false with a message when METIS fails.
bool PartitionElementsMetis(const MeshData &mesh, int nparts, std::vector<int> *part,
                            std::string *err);

} // namespace etfe
