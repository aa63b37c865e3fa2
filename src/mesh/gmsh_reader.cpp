// Gmsh MSH reader for MeshData: 4.1 (ASCII and binary) and 2.2 (ASCII), on the tokenizer of
// gmsh_tokenizer.h. The reader treats its input as hostile: counts are bounded by the file size
// before anything is allocated, and every failure becomes "<file>:<line>: <what>" rather than a
// crash, a hang or an allocation larger than the file.
#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstring>
#include <map>
#include <new>
#include <string_view>
#include <utility>
#include <vector>

#include "etfe/mesh/gmsh_reader.h"
#include "gmsh_tokenizer.h"

namespace etfe {
namespace {

using namespace gmsh;

// A mesh of at most 2^31 nodes (kMaxTag) in ASCII fits in a few GiB; past this the file is not a
// mesh for this solver, and reading it would only exhaust memory.
constexpr unsigned long long kMaxFileBytes = 1ull << 33;

// Physical groups can make the sets far larger than the file (many groups on one big entity, or
// a great many tiny groups, each of which costs a named set). Past this many set entries per
// input byte, a group counting as kGroupCost entries, the file is rejected instead of allocated.
constexpr size_t kSetEntriesPerByte = 8;
constexpr size_t kGroupCost = 64;  // about the bytes of two map entries, in ints

// Dimension of the element types that feed the mesh or its sets; -1 for the refused ones.
int KeptTypeDim(long long type) {
  switch (type) {
    case 15: return 0;  // point
    case 1: return 1;   // 2-node line
    case 2: return 2;   // 3-node triangle
    case 3: return 2;   // 4-node quadrangle, split into two triangles
    default: return -1;
  }
}

// For the message that refuses an element type: what a user would call it.
std::string TypeName(long long type) {
  switch (type) {
    case 4: return "4-node tetrahedron";
    case 5: return "8-node hexahedron";
    case 6: return "6-node prism";
    case 7: return "5-node pyramid";
    case 8: return "3-node second-order line";
    case 9: return "6-node second-order triangle";
    case 10: return "9-node second-order quadrangle";
    case 11: return "10-node second-order tetrahedron";
    case 16: return "8-node second-order quadrangle";
    default: {
      const int n = NodesPerElement(type);
      return n > 0 ? Str((long long)n) + "-node element" : "unknown element";
    }
  }
}

// The nodes and triangles of one entity (4.1) or one physical group (2.2), in file-order node
// indices and output triangle ids, kept per carrier so that a group on many elements costs one
// list rather than one entry per element and group.
struct Carrier {
  std::vector<int> nodes;
  std::vector<int> tris;
  std::vector<int> lines;  // 2 file-order node indices per line element (cables follow them)
};

using Key = std::pair<int, long long>;  // (dimension, tag)

class Reader {
 public:
  Reader(const std::string &buf, const std::string &name) : in_(buf, name), name_(name) {}

  bool Read(MeshData *mesh) {
    if (!ParseMeshFormat()) return false;
    while (!in_.AtEnd()) {
      std::string_view tok;
      if (!in_.Token(&tok, "a section")) return false;
      const size_t header = in_.at();
      if (tok.size() < 2 || tok[0] != '$') {
        return in_.Fail("expected a section header such as $Nodes, found " + Quote(tok));
      }
      const std::string_view sec = tok.substr(1);
      bool ok;
      if (sec.substr(0, 3) == "End") {
        return in_.Fail(Quote(tok) + " without its section header");
      } else if (sec == "MeshFormat") {
        return in_.Fail("a second $MeshFormat section");
      } else if (sec == "PhysicalNames") {
        ok = Once(&seen_names_, tok) && ParsePhysicalNames();
      } else if (sec == "Entities" && v41_) {
        if (seen_elements_) return in_.Fail("$Entities must come before $Elements");
        ok = Once(&seen_entities_, tok) && Binary(tok) && ParseEntities() && Ascii("Entities");
      } else if (sec == "PartitionedEntities" && v41_) {
        return in_.Fail("partitioned MSH files are not supported: save the mesh unpartitioned");
      } else if (sec == "Nodes") {
        ok = Once(&seen_nodes_, tok) && Binary(tok) && (v41_ ? ParseNodes41() : ParseNodes2()) &&
             Ascii("Nodes") && IndexNodes();
      } else if (sec == "Elements") {
        if (!seen_nodes_) return in_.Fail("$Elements must come after $Nodes");
        elements_pos_ = header;
        ok = Once(&seen_elements_, tok) && Binary(tok) &&
             (v41_ ? ParseElements41() : ParseElements2()) && Ascii("Elements");
      } else {
        ok = in_.SkipSection(sec, header);
      }
      if (!ok) return false;
    }
    if (!seen_nodes_) return in_.FailAt(in_.size(), "no $Nodes section");
    if (!seen_elements_) return in_.FailAt(in_.size(), "no $Elements section");
    if (tri_.empty()) {
      return in_.FailAt(elements_pos_, "no triangles (element type 2) or quadrangles (type 3) in "
                                       "$Elements: the membrane needs a surface mesh");
    }
    return Finish(mesh);
  }

  const std::string &error() const { return in_.error(); }

 private:
  bool Once(bool *seen, std::string_view tok) {
    if (*seen) return in_.Fail("a second " + Quote(tok) + " section");
    *seen = true;
    return true;
  }
  bool Binary(std::string_view tok) {
    if (!binary_) return true;
    if (!in_.EndHeaderLine(std::string(tok))) return false;
    in_.SetBinary(true);
    return true;
  }
  bool Ascii(const char *section) {
    in_.SetBinary(false);
    return in_.ExpectEnd(section);
  }

  bool ParseMeshFormat() {
    std::string_view tok;
    in_.SkipSpace();
    if (in_.AtEnd()) return in_.FailAt(0, "empty file, expected $MeshFormat");
    if (!in_.Token(&tok, "$MeshFormat")) return false;
    if (tok != "$MeshFormat") {
      return in_.Fail("not a Gmsh MSH file: expected $MeshFormat, found " + Quote(tok) +
                      "; an OBJ or STL surface converts with scripts/surface2msh SURFACE OUT.msh");
    }
    std::string_view ver;
    if (!in_.Token(&ver, "the MSH version")) return false;
    double v = 0;
    const auto r = std::from_chars(ver.data(), ver.data() + ver.size(), v);
    if (r.ec != std::errc() || r.ptr != ver.data() + ver.size()) {
      return in_.Fail("expected the MSH version, found " + Quote(ver));
    }
    if (v == 4.1) {
      v41_ = true;
    } else if (!(v >= 2.0 && v < 3.0)) {
      return in_.Fail("MSH version " + Quote(ver) +
                      " is not supported: save as 4.1 or 2.2 (Gmsh: -format msh41)");
    }
    long long file_type, data_size;
    if (!in_.ReadInt(&file_type, "file type (0 = ASCII, 1 = binary)", 0, 1)) return false;
    if (!in_.ReadInt(&data_size, "data size", 1, 64)) return false;
    binary_ = (file_type == 1);
    if (binary_) {
      if (!v41_) {
        return in_.Fail("binary MSH 2 is not supported: save as ASCII or as binary 4.1 "
                        "(Gmsh: -format msh41, or Mesh.Binary=0)");
      }
      // size_t fields are data_size wide; the int 1 that follows tells the byte order.
      if (data_size != 4 && data_size != 8) {
        return in_.Fail("binary data size " + Str(data_size) + " is not supported (need 4 or 8)");
      }
      if (!in_.EndHeaderLine("the MSH version line")) return false;
      in_.SetBinary(true);
      in_.SetBinaryLayout(false, (int)data_size);
      long long one;
      if (!in_.ReadInt(&one, "endianness marker", INT_MIN, INT_MAX)) return false;
      if (one == 0x01000000) {
        in_.SetBinaryLayout(true, (int)data_size);
      } else if (one != 1) {
        return in_.Fail("binary endianness marker is " + Str(one) + ", not 1: the file is damaged");
      }
      in_.SetBinary(false);
    }
    return in_.ExpectEnd("MeshFormat");
  }

  bool ParsePhysicalNames() {
    size_t n;
    if (!in_.ReadCount(&n, "physical names", 3, 0)) return false;
    for (size_t i = 0; i < n; ++i) {
      long long dim, tag;
      std::string name;
      if (!in_.ReadInt(&dim, "physical dimension", 0, 3)) return false;
      if (!in_.ReadInt(&tag, "physical tag", INT_MIN, INT_MAX)) return false;
      const size_t tag_pos = in_.at();
      if (!in_.QuotedName(&name)) return false;
      if (!names_.emplace(Key((int)dim, tag), name).second) {
        return in_.FailAt(tag_pos, "physical group (dimension " + Str(dim) + ", tag " + Str(tag) +
                                       ") is named twice");
      }
    }
    return in_.ExpectEnd("PhysicalNames");
  }

  bool ParseEntities() {
    size_t count[4];
    // A point is at least tag, x, y, z, number of physical tags; the others add a bounding box
    // and a number of bounding entities.
    if (!in_.ReadCount(&count[0], "points", 5, 4 + 24 + 8)) return false;
    for (int d = 1; d < 4; ++d) {
      if (!in_.ReadCount(&count[d], "entities of dimension " + Str((long long)d), 9, 4 + 48 + 16)) {
        return false;
      }
    }
    for (int d = 0; d < 4; ++d) {
      for (size_t i = 0; i < count[d]; ++i) {
        long long tag;
        double skip;
        if (!in_.ReadInt(&tag, "entity tag", INT_MIN, INT_MAX)) return false;
        const size_t tag_pos = in_.at();
        for (int k = 0; k < (d == 0 ? 3 : 6); ++k) {
          if (!in_.ReadDouble(&skip, "entity coordinate", false)) return false;
        }
        size_t nphys;
        if (!in_.ReadCount(&nphys, "physical tags", 1, 4)) return false;
        std::vector<long long> phys;
        for (size_t k = 0; k < nphys; ++k) {
          long long p;
          if (!in_.ReadInt(&p, "physical tag", INT_MIN, INT_MAX)) return false;
          if (p != 0) phys.push_back(p);  // 0 is Gmsh's "no physical group" (as in MSH 2)
        }
        std::sort(phys.begin(), phys.end());  // not a linear search per tag: nphys can be huge
        phys.erase(std::unique(phys.begin(), phys.end()), phys.end());
        if (!entities_.emplace(Key(d, tag), std::move(phys)).second) {
          return in_.FailAt(tag_pos, "entity (dimension " + Str((long long)d) + ", tag " +
                                         Str(tag) + ") is listed twice in $Entities");
        }
        if (d > 0) {
          size_t nb;
          if (!in_.ReadCount(&nb, "bounding entities", 1, 4)) return false;
          for (size_t k = 0; k < nb; ++k) {
            long long b;
            if (!in_.ReadInt(&b, "bounding entity tag", INT_MIN, INT_MAX)) return false;
          }
        }
      }
    }
    return true;
  }

  // Records one node; its tag position is kept until IndexNodes() has checked for duplicates.
  bool AddNodeTag(unsigned long long tag) {
    if (node_tags_.size() >= (size_t)INT_MAX) return in_.Fail("too many nodes");
    node_tags_.push_back((int)tag);
    node_tag_pos_.push_back(in_.at());
    return true;
  }

  bool ParseNodes41() {
    size_t nblocks, nnodes;
    unsigned long long min_tag, max_tag;
    if (!in_.ReadCount(&nblocks, "node blocks", 4, 12 + 8)) return false;
    if (!in_.ReadCount(&nnodes, "nodes", 4, 8 + 24)) return false;
    const size_t header_pos = in_.at();
    if (!in_.ReadSize(&min_tag, "smallest node tag", 0, ULLONG_MAX)) return false;
    if (!in_.ReadSize(&max_tag, "largest node tag", 0, ULLONG_MAX)) return false;
    size_t total = 0;
    for (size_t b = 0; b < nblocks; ++b) {
      long long dim, entity, parametric;
      size_t n;
      if (!in_.ReadInt(&dim, "entity dimension", 0, 3)) return false;
      if (!in_.ReadInt(&entity, "entity tag", INT_MIN, INT_MAX)) return false;
      if (!in_.ReadInt(&parametric, "parametric flag", 0, 1)) return false;
      const size_t ncoord = 3 + (parametric ? (size_t)dim : 0);
      if (!in_.ReadCount(&n, "nodes in the block", 1 + ncoord, 8 * (1 + ncoord))) return false;
      if (n > nnodes - total) {
        return in_.Fail("node blocks hold more than the " + Str((unsigned long long)nnodes) +
                        " nodes the $Nodes header gives");
      }
      total += n;
      Grow(&node_tags_, n);
      Grow(&node_tag_pos_, n);
      Grow(&xyz_, 3 * n);
      for (size_t i = 0; i < n; ++i) {
        unsigned long long tag;
        if (!in_.ReadSize(&tag, "node tag", 1, kMaxTag)) return false;
        if (!AddNodeTag(tag)) return false;
      }
      for (size_t i = 0; i < n; ++i) {
        for (int k = 0; k < 3; ++k) {
          double x;
          if (!in_.ReadDouble(&x, "node coordinate", true)) return false;
          xyz_.push_back(x);
        }
        for (size_t k = 3; k < ncoord; ++k) {
          double u;
          if (!in_.ReadDouble(&u, "parametric node coordinate", false)) return false;
        }
      }
    }
    if (total != nnodes) {
      return in_.FailAt(header_pos, "the $Nodes header gives " + Str((unsigned long long)nnodes) +
                                        " nodes but its blocks hold " +
                                        Str((unsigned long long)total));
    }
    return true;
  }

  bool ParseNodes2() {
    size_t n;
    if (!in_.ReadCount(&n, "nodes", 4, 0)) return false;
    node_tags_.reserve(n);
    node_tag_pos_.reserve(n);
    xyz_.reserve(3 * n);
    for (size_t i = 0; i < n; ++i) {
      unsigned long long tag;
      if (!in_.ReadSize(&tag, "node number", 1, kMaxTag)) return false;
      if (!AddNodeTag(tag)) return false;
      for (int k = 0; k < 3; ++k) {
        double x;
        if (!in_.ReadDouble(&x, "node coordinate", true)) return false;
        xyz_.push_back(x);
      }
    }
    return true;
  }

  // Builds the tag -> file-order index lookup: a direct table when the tags are dense enough
  // (Gmsh's are 1..N), else a sorted list; either way duplicates are found here.
  bool IndexNodes() {
    if (node_tags_.empty()) {
      node_tag_pos_.clear();
      return true;
    }
    const auto mm = std::minmax_element(node_tags_.begin(), node_tags_.end());
    const size_t n = node_tags_.size();
    const size_t range = (size_t)*mm.second - (size_t)*mm.first + 1;
    if (range <= 2 * n + 1024) {
      tag_base_ = *mm.first;
      dense_.assign(range, -1);
      for (size_t i = 0; i < n; ++i) {
        int &slot = dense_[(size_t)(node_tags_[i] - tag_base_)];
        if (slot >= 0) return DuplicateNode(i);
        slot = (int)i;
      }
    } else {
      sorted_.resize(n);
      for (size_t i = 0; i < n; ++i) sorted_[i] = {node_tags_[i], (int)i};
      std::sort(sorted_.begin(), sorted_.end());
      for (size_t i = 1; i < n; ++i) {
        if (sorted_[i].first == sorted_[i - 1].first) return DuplicateNode(sorted_[i].second);
      }
    }
    std::vector<size_t>().swap(node_tag_pos_);  // the tags stay: MeshCheck's messages name them
    return true;
  }
  bool DuplicateNode(size_t i) {
    const size_t pos = node_tag_pos_[i];
    return in_.FailAt(pos, "node tag " + Str((long long)node_tags_[i]) + " is defined twice");
  }

  int FindNode(unsigned long long tag) const {
    if (tag > kMaxTag) return -1;
    const long long t = (long long)tag;
    if (!dense_.empty()) {
      if (t < tag_base_ || t - tag_base_ >= (long long)dense_.size()) return -1;
      return dense_[(size_t)(t - tag_base_)];
    }
    const auto it = std::lower_bound(sorted_.begin(), sorted_.end(), std::make_pair((int)t, -1));
    return (it != sorted_.end() && it->first == (int)t) ? it->second : -1;
  }

  // Reads the npe node tags of one element; for kept types looks them up (idx gets file-order
  // indices), for skipped types only checks they are numbers.
  bool ReadElementNodes(int npe, bool keep, unsigned long long elem_tag, int *idx) {
    for (int k = 0; k < npe; ++k) {
      unsigned long long tag;
      if (!in_.ReadSize(&tag, "node tag", 0, ULLONG_MAX)) return false;
      if (!keep) continue;
      idx[k] = FindNode(tag);
      if (idx[k] < 0) {
        return in_.Fail("element " + Str(elem_tag) + " refers to node " + Str(tag) +
                        ", which $Nodes does not define");
      }
    }
    return true;
  }

  // Silently dropping elements would leave holes in the membrane; volume or second-order
  // elements mean the file was meshed for something else.
  bool Refuse(long long type, unsigned long long elem_tag) {
    return in_.Fail(
        "element " + Str(elem_tag) + " is of type " + Str(type) + " (" + TypeName(type) +
        "): this reader takes first-order triangles (type 2), quadrangles (type 3, split "
        "into two triangles), lines (1) and points (15); remesh the surface only, first "
        "order (Gmsh: -2 -order 1)");
  }

  bool AddTriangle(const int *idx, Carrier *c, unsigned long long elem_tag) {
    if (tri_.size() / 3 >= (size_t)INT_MAX) return in_.Fail("too many triangles");
    const int id = (int)(tri_.size() / 3);
    tri_.insert(tri_.end(), idx, idx + 3);
    tri_tags_.push_back((long long)elem_tag);
    if (c) {
      c->tris.push_back(id);
      c->nodes.insert(c->nodes.end(), idx, idx + 3);
    }
    return true;
  }

  // A quadrangle becomes two triangles along its shorter diagonal (the better-shaped pair), in
  // the quadrangle's own orientation.
  bool AddQuadrangle(const int *q, Carrier *c, unsigned long long elem_tag) {
    auto dist2 = [this](int a, int b) {
      double d = 0;
      for (int k = 0; k < 3; ++k) {
        const double x = xyz_[3 * (size_t)a + k] - xyz_[3 * (size_t)b + k];
        d += x * x;
      }
      return d;
    };
    ++quads_;
    if (dist2(q[0], q[2]) <= dist2(q[1], q[3])) {
      const int t0[3] = {q[0], q[1], q[2]}, t1[3] = {q[0], q[2], q[3]};
      return AddTriangle(t0, c, elem_tag) && AddTriangle(t1, c, elem_tag);
    }
    const int t0[3] = {q[0], q[1], q[3]}, t1[3] = {q[1], q[2], q[3]};
    return AddTriangle(t0, c, elem_tag) && AddTriangle(t1, c, elem_tag);
  }

  bool ParseElements41() {
    size_t nblocks, nelems;
    unsigned long long min_tag, max_tag;
    if (!in_.ReadCount(&nblocks, "element blocks", 4, 12 + 8)) return false;
    if (!in_.ReadCount(&nelems, "elements", 2, 16)) return false;
    const size_t header_pos = in_.at();
    if (!in_.ReadSize(&min_tag, "smallest element tag", 0, ULLONG_MAX)) return false;
    if (!in_.ReadSize(&max_tag, "largest element tag", 0, ULLONG_MAX)) return false;
    size_t total = 0;
    for (size_t b = 0; b < nblocks; ++b) {
      long long dim, entity, type;
      if (!in_.ReadInt(&dim, "entity dimension", 0, 3)) return false;
      if (!in_.ReadInt(&entity, "entity tag", INT_MIN, INT_MAX)) return false;
      const size_t entity_pos = in_.at();
      if (!in_.ReadInt(&type, "element type", 1, INT_MAX)) return false;
      const int npe = NodesPerElement(type);
      size_t n;
      if (!in_.ReadCount(&n, "elements in the block", 1 + (size_t)npe, 8 * (1 + (size_t)npe))) {
        return false;
      }
      if (n > nelems - total) {
        return in_.Fail("element blocks hold more than the " + Str((unsigned long long)nelems) +
                        " elements the $Elements header gives");
      }
      total += n;
      const int kept_dim = KeptTypeDim(type);
      if (kept_dim < 0) {
        if (n == 0) continue;
        unsigned long long tag;
        if (!in_.ReadSize(&tag, "element tag", 1, kMaxTag)) return false;
        return Refuse(type, tag);
      }
      Carrier *carrier = nullptr;
      {
        if (kept_dim != dim) {
          return in_.Fail("element type " + Str(type) + " in a block of entity dimension " +
                          Str(dim) + " (expected " + Str((long long)kept_dim) + ")");
        }
        if (seen_entities_ && entities_.count(Key((int)dim, entity)) == 0) {
          return in_.FailAt(entity_pos, "element block refers to entity (dimension " + Str(dim) +
                                            ", tag " + Str(entity) + "), which $Entities lacks");
        }
        carrier = &carriers_[Key((int)dim, entity)];
        if (type == 2 || type == 3) Grow(&tri_, 3 * n * (size_t)(type - 1));
      }
      for (size_t i = 0; i < n; ++i) {
        unsigned long long tag;
        if (!in_.ReadSize(&tag, "element tag", 1, kMaxTag)) return false;
        int idx[4] = {-1, -1, -1, -1};
        if (!ReadElementNodes(npe, true, tag, idx)) return false;
        if (type == 2) {
          if (!AddTriangle(idx, carrier, tag)) return false;
        } else if (type == 3) {
          if (!AddQuadrangle(idx, carrier, tag)) return false;
        } else if (carrier) {
          carrier->nodes.insert(carrier->nodes.end(), idx, idx + npe);
          if (type == 1) carrier->lines.insert(carrier->lines.end(), idx, idx + 2);
        }
      }
    }
    if (total != nelems) {
      return in_.FailAt(header_pos, "the $Elements header gives " +
                                        Str((unsigned long long)nelems) +
                                        " elements but its blocks hold " +
                                        Str((unsigned long long)total));
    }
    return true;
  }

  bool ParseElements2() {
    size_t n;
    if (!in_.ReadCount(&n, "elements", 3, 0)) return false;
    // Gmsh 2 writes an element once per physical group it belongs to, as consecutive records
    // with the same elementary tag and nodes: those are one surface element in several groups.
    int prev_tris = 0;  // triangles the previous record made (quadrangles make two)
    long long prev_elementary = 0, prev_phys = 0;
    int prev_idx[4] = {-1, -1, -1, -1};
    for (size_t i = 0; i < n; ++i) {
      unsigned long long tag;
      long long type;
      size_t ntags;
      if (!in_.ReadSize(&tag, "element number", 1, kMaxTag)) return false;
      if (!in_.ReadInt(&type, "element type", 1, INT_MAX)) return false;
      if (!in_.ReadCount(&ntags, "element tags", 1, 0)) return false;
      long long phys = 0, elementary = 0;
      for (size_t k = 0; k < ntags; ++k) {
        long long t;
        if (!in_.ReadInt(&t, "element tag", INT_MIN, INT_MAX)) return false;
        if (k == 0) phys = t;
        if (k == 1) elementary = t;
      }
      const int npe = NodesPerElement(type);
      const int dim = KeptTypeDim(type);
      if (dim < 0) return Refuse(type, tag);
      int idx[4] = {-1, -1, -1, -1};
      if (!ReadElementNodes(npe, true, tag, idx)) return false;
      Carrier *carrier = (phys != 0) ? &carriers_[Key(dim, phys)] : nullptr;
      if (type == 2 || type == 3) {
        const int ntri = type == 2 ? 1 : 2;
        const bool repeat = prev_tris == ntri && elementary == prev_elementary &&
                            phys != prev_phys && std::equal(idx, idx + npe, prev_idx);
        if (repeat) {
          if (carrier) {
            for (int k = ntri; k >= 1; --k) carrier->tris.push_back((int)(tri_.size() / 3) - k);
            carrier->nodes.insert(carrier->nodes.end(), idx, idx + npe);
          }
        } else if (!(type == 2 ? AddTriangle(idx, carrier, tag)
                               : AddQuadrangle(idx, carrier, tag))) {
          return false;
        }
        prev_tris = ntri;
        prev_elementary = elementary;
        prev_phys = phys;
        std::copy(idx, idx + npe, prev_idx);
      } else {
        prev_tris = 0;
        if (carrier) carrier->nodes.insert(carrier->nodes.end(), idx, idx + npe);
        if (carrier && type == 1) carrier->lines.insert(carrier->lines.end(), idx, idx + 2);
      }
    }
    return true;
  }

  std::string GroupName(const Key &g) const {
    const auto it = names_.find(g);
    if (it != names_.end() && !it->second.empty()) return it->second;
    return "group_" + Str(g.second);
  }

  bool Finish(MeshData *out) {
    MeshData mesh;
    mesh.source = name_;
    // Renumber the nodes that triangles use, in file order.
    const size_t nall = xyz_.size() / 3;
    std::vector<int> new_id(nall, -1);
    for (int v : tri_) new_id[(size_t)v] = 0;
    int next = 0;
    for (size_t i = 0; i < nall; ++i) {
      if (new_id[i] < 0) continue;
      new_id[i] = next++;
      mesh.coords.insert(mesh.coords.end(), &xyz_[3 * i], &xyz_[3 * i] + 3);
    }
    mesh.triangles.resize(tri_.size());
    for (size_t i = 0; i < tri_.size(); ++i) mesh.triangles[i] = new_id[(size_t)tri_[i]];
    mesh.node_tags.reserve((size_t)next);
    for (size_t i = 0; i < nall; ++i) {
      if (new_id[i] >= 0) mesh.node_tags.push_back(node_tags_[i]);
    }
    mesh.element_tags = tri_tags_;
    if (quads_ > 0) {
      mesh.notes.push_back("split " + Str((unsigned long long)quads_) +
                           " quadrangles (element type 3) into two triangles each, along their "
                           "shorter diagonal");
    }

    // Physical group -> the carriers it covers; named groups exist even when empty.
    std::map<Key, std::vector<const Carrier *>> groups;
    for (const auto &nc : names_) {
      if (nc.first.first <= 2) groups[nc.first];
    }
    for (const auto &kc : carriers_) {
      if (!v41_) {
        groups[kc.first].push_back(&kc.second);
        continue;
      }
      const auto e = entities_.find(kc.first);
      if (e == entities_.end()) continue;
      for (long long p : e->second) groups[Key(kc.first.first, p)].push_back(&kc.second);
    }
    size_t entries = 0;
    const size_t limit = kSetEntriesPerByte * in_.size() + (1u << 20);
    for (const auto &g : groups) {
      entries += kGroupCost;
      for (const Carrier *c : g.second) entries += c->nodes.size() + c->tris.size() + c->lines.size();
      if (entries > limit) {
        return in_.FailAt(elements_pos_, "the physical groups would need more than " +
                                             Str((unsigned long long)limit) +
                                             " set entries, too many for a file of this size");
      }
    }
    for (const auto &g : groups) {
      const std::string name = GroupName(g.first);
      std::vector<int> &ns = mesh.node_sets[name];
      for (const Carrier *c : g.second) {
        for (int v : c->nodes) {
          if (new_id[(size_t)v] >= 0) ns.push_back(new_id[(size_t)v]);
        }
      }
      if (g.first.first == 1) {
        // Line elements in file order; a node no triangle uses maps to -1 (the cable set-up
        // refuses it by its group's name).
        std::vector<int> &ls = mesh.line_sets[name];
        for (const Carrier *c : g.second)
          for (int v : c->lines) ls.push_back(new_id[(size_t)v]);
      }
      if (g.first.first == 2) {
        std::vector<int> &es = mesh.element_sets[name];
        for (const Carrier *c : g.second) es.insert(es.end(), c->tris.begin(), c->tris.end());
      }
    }
    for (auto *sets : {&mesh.node_sets, &mesh.element_sets}) {
      for (auto &s : *sets) {
        std::sort(s.second.begin(), s.second.end());
        s.second.erase(std::unique(s.second.begin(), s.second.end()), s.second.end());
      }
    }
    *out = std::move(mesh);
    return true;
  }

  Input in_;
  const std::string &name_;
  bool v41_ = false;
  bool binary_ = false;
  bool seen_names_ = false, seen_entities_ = false, seen_nodes_ = false, seen_elements_ = false;
  size_t elements_pos_ = 0;

  std::vector<double> xyz_;           // 3 per node, file order
  std::vector<int> node_tags_;        // while reading $Nodes only
  std::vector<size_t> node_tag_pos_;  // where each tag is, for the duplicate message
  std::vector<int> dense_;            // tag - tag_base_ -> index, or empty
  long long tag_base_ = 0;
  std::vector<std::pair<int, int>> sorted_;  // (tag, index) when the tags are sparse

  std::vector<int> tri_;  // 3 file-order node indices per triangle
  std::vector<long long> tri_tags_;  // the element tag each triangle came from
  size_t quads_ = 0;                 // quadrangles split into two triangles
  std::map<Key, std::vector<long long>> entities_;  // (dim, entity tag) -> physical tags
  std::map<Key, Carrier> carriers_;  // (dim, entity tag) in 4.1, (dim, physical tag) in 2.2
  std::map<Key, std::string> names_;
};

} // namespace

bool ReadGmshBuffer(const std::string &buffer, const std::string &name, MeshData *mesh,
                    std::string *err) {
  Reader reader(buffer, name);
  MeshData tmp;
  if (reader.Read(&tmp)) {
    if (mesh) *mesh = std::move(tmp);
    return true;
  }
  if (err) *err = reader.error().empty() ? name + ":1: cannot read the mesh" : reader.error();
  return false;
}

bool ReadGmshFile(const std::string &path, MeshData *mesh, std::string *err) {
  // Only a regular file has a size to bound the reading by: /dev/zero never ends, and opening a
  // FIFO blocks until someone writes to it. Refuse them before opening.
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) {
    if (err) *err = path + ": cannot open: " + std::strerror(errno);
    return false;
  }
  if (!S_ISREG(st.st_mode)) {
    if (err) {
      *err = path + ": not a regular file (" +
             (S_ISDIR(st.st_mode)    ? "a directory"
              : S_ISFIFO(st.st_mode) ? "a FIFO"
                                     : "a device or socket") +
             "): give a Gmsh .msh file";
    }
    return false;
  }
  if ((unsigned long long)st.st_size > kMaxFileBytes) {
    if (err) {
      *err = path + ": " + Str((unsigned long long)st.st_size) + " bytes, more than the " +
             Str(kMaxFileBytes) + " a mesh of at most 2^31 nodes needs: is it the right file?";
    }
    return false;
  }
  std::FILE *f = std::fopen(path.c_str(), "rb");
  if (!f) {
    if (err) *err = path + ": cannot open: " + std::strerror(errno);
    return false;
  }
  // Read exactly the size stat gave (a file that grows meanwhile is read as it was), into one
  // allocation: the peak memory is the file size, not twice it.
  std::string buf;
  try {
    buf.resize((size_t)st.st_size);
  } catch (const std::bad_alloc &) {
    std::fclose(f);
    if (err)
      *err = path + ": not enough memory to read its " + Str((unsigned long long)st.st_size) +
             " bytes";
    return false;
  }
  const size_t got = buf.empty() ? 0 : std::fread(&buf[0], 1, buf.size(), f);
  const bool bad = std::ferror(f) != 0;
  const int read_errno = errno;
  std::fclose(f);
  if (bad) {
    if (err) *err = path + ": cannot read: " + std::strerror(read_errno);
    return false;
  }
  buf.resize(got);  // a file that shrank meanwhile: the reader reports where it ends
  return ReadGmshBuffer(buf, path, mesh, err);
}

} // namespace etfe
