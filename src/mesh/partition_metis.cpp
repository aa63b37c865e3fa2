// METIS dual-graph partition of the triangles. PETSc 3.18 (Debian) has no METIS partitioner
// inside, so rank 0, which alone holds the global mesh, calls METIS directly (distribute.cpp).
#include <metis.h>

#include <string>

#include "etfe/mesh/partition.h"

namespace etfe {

bool PartitionElementsMetis(const MeshData &mesh, int nparts, std::vector<int> *part,
                            std::string *err) {
  idx_t ne = mesh.NumElements();
  part->assign(ne, 0);
  if (nparts <= 1 || ne == 0) return true;
  if (ne < nparts) {
    *err = mesh.source + ": " + std::to_string(ne) + " elements cannot be split over " +
           std::to_string(nparts) + " ranks; refine the mesh or use fewer ranks";
    return false;
  }
  idx_t nn = mesh.NumNodes(), ncommon = 2, np = nparts, objval = 0;
  std::vector<idx_t> eptr(ne + 1), eind(mesh.triangles.begin(), mesh.triangles.end());
  for (idx_t e = 0; e <= ne; ++e) eptr[e] = 3 * e;
  std::vector<idx_t> epart(ne), npart(nn);
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = 7;  // reproducible partitions, hence reproducible runs
  int rc = METIS_PartMeshDual(&ne, &nn, eptr.data(), eind.data(), nullptr, nullptr, &ncommon, &np,
                              nullptr, options, &objval, epart.data(), npart.data());
  if (rc != METIS_OK) {
    *err = mesh.source + ": METIS_PartMeshDual failed with code " + std::to_string(rc);
    return false;
  }
  for (idx_t e = 0; e < ne; ++e) (*part)[e] = (int)epart[e];
  return true;
}

} // namespace etfe
