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
  // 1-D Gmsh physical groups as their line elements, 2 node ids per segment in file order (-1
  // where a line's node is no triangle's: the reader keeps only the film's nodes). Cables.
  std::map<std::string, std::vector<int>> line_sets;
  std::string source;            // file name or generator description, for messages
  // Gmsh tags of the nodes and triangles (empty for a generated mesh), so that messages name
  // what the user sees in the file; both halves of a split quadrangle carry the quad's tag.
  std::vector<long long> node_tags, element_tags;
  // What was changed on reading or repairing (split quadrangles, flipped triangles), one
  // sentence each, for the log: nothing is changed silently.
  std::vector<std::string> notes;
  // Edges of three or more triangles are welds of layers (a three-layer cushion's rim), not an
  // error (-mesh_welds).
  bool welds = false;

  int NumNodes() const { return (int)(coords.size() / 3); }
  int NumElements() const { return (int)(triangles.size() / 3); }
};

// Checks a mesh: finite coordinates, node ids in range, no repeated node in a triangle, no
// triangle with area below min_area (mm^2), every node used, sets in range, and the topology of
// a membrane surface: no two nodes at one place (a crack: tolerance 1e-6 of the mean edge
// length), no triangle twice, no edge shared by more than two triangles, neighbours oriented
// alike. On failure returns false and writes a message naming the source, the element/node
// (with its file tag when read from a file) and the way out.
bool MeshCheck(const MeshData &mesh, double min_area, std::string *err);

// Makes the orientation of the triangles agree across every shared edge: in each connected
// piece the triangles that disagree with the majority are flipped, and a sentence saying how
// many, in which piece and of which element groups goes into mesh->notes. Returns false with a
// message when no consistent orientation exists (a Moebius-like surface) or when a piece splits
// evenly (no majority: which way is meant cannot be told; a two-layer cushion's foils share the
// rim, so the count is over the whole closed surface, not per group). Leaves meshes with
// bad ids or non-manifold edges alone: MeshCheck refuses those with their own message.
bool MeshOrient(MeshData *mesh, std::string *err);

} // namespace etfe
