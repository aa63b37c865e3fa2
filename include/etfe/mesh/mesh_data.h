// The global (undistributed) triangle mesh as read from a file or made by a generator.
// PETSc-free: the distributed mesh is built from it in src/mesh/distribute.cpp.
#pragma once
#include <map>
#include <string>
#include <vector>

namespace etfe {

struct MeshData {
  std::vector<double> coords;    // 3 per node, mm
  std::vector<int> triangles;    // 3 per element, 0-based node ids
  // Named groups. Gmsh physical groups: 0-D and 1-D groups become node sets (all nodes of their
  // points/lines), 2-D groups become element sets and also node sets. Generators fill them too.
  std::map<std::string, std::vector<int>> node_sets;     // sorted, unique node ids
  std::map<std::string, std::vector<int>> element_sets;  // sorted, unique element ids
  std::string source;            // file name or generator description, for messages

  int NumNodes() const { return (int)(coords.size() / 3); }
  int NumElements() const { return (int)(triangles.size() / 3); }
};

// Checks a mesh: finite coordinates, node ids in range, no repeated node in a triangle, no
// triangle with area below min_area (mm^2), every node used, sets in range. On failure returns
// false and writes a message naming the source, the element/node and the way out.
bool MeshCheck(const MeshData &mesh, double min_area, std::string *err);

} // namespace etfe
