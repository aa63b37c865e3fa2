// Reader for Gmsh MSH files: format 4.1 (ASCII and binary) and 2.2 (ASCII). PETSc-free.
// Keeps 3-node triangles (type 2) as elements and splits 4-node quadrangles (type 3) into two
// triangles along the shorter diagonal (saying so in MeshData::notes); lines (1), points (15)
// and surface elements feed the named node/element sets through their physical groups
// ($PhysicalNames gives the names; an unnamed group is called "group_<tag>"). Any other element
// type is refused by name: dropping it would leave a hole. Node tags may be non-contiguous: they
// are renumbered 0..N-1 in file order (MeshData::node_tags keeps them for messages), and unused
// nodes are dropped. Implementation: gmsh_tokenizer.cpp, gmsh_reader.cpp, gmsh_writer.cpp.
#pragma once
#include <string>

#include "etfe/mesh/mesh_data.h"

namespace etfe {

// Returns true on success. On failure returns false and writes "<file>:<line>: <what is wrong>"
// to err; never crashes or allocates unbounded memory on malformed input (counts are checked
// against the remaining file size before allocating). ReadGmshFile refuses anything but a
// regular file (a device such as /dev/zero never ends; a FIFO blocks) and files over 8 GiB
// before reading, and reads the file in one allocation of its size.
bool ReadGmshFile(const std::string &path, MeshData *mesh, std::string *err);
bool ReadGmshBuffer(const std::string &buffer, const std::string &name, MeshData *mesh,
                    std::string *err);

// Writes an ASCII MSH 4.1 file with the triangles and every node/element set as a physical
// group (used by form finding to hand its surface to the stretch scenes).
bool WriteGmshFile(const std::string &path, const MeshData &mesh, std::string *err);

} // namespace etfe
