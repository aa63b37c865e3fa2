// Gmsh MSH input and output for MeshData: reads 4.1 (ASCII and binary) and 2.2 (ASCII), writes
// 4.1 ASCII. The reader treats its input as hostile: every number is parsed in full, every count
// is checked against the bytes left before anything is sized by it, and every failure becomes
// "<file>:<line>: <what>" rather than a crash, a hang or an allocation larger than the file.
#include "etfe/mesh/gmsh_reader.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <utility>
#include <vector>

namespace etfe {
namespace {

// Tags become int ids in MeshData; a membrane mesh with 2^31 nodes is not a use case, and the
// limit turns garbage such as 2^40 into a clear error instead of a silent truncation.
constexpr unsigned long long kMaxTag = INT_MAX;

// Physical groups can make the sets far larger than the file (many groups on one big entity, or
// a great many tiny groups, each of which costs a named set). Past this many set entries per
// input byte, a group counting as kGroupCost entries, the file is rejected instead of allocated.
constexpr size_t kSetEntriesPerByte = 8;
constexpr size_t kGroupCost = 64;  // about the bytes of two map entries, in ints

// Nodes per element of the element types in the Gmsh documentation; 0 = unknown, so a binary
// record of that type cannot be skipped.
int NodesPerElement(long long type) {
  static const int kNodes[32] = {0, 2,  3,  4,  4,  8,  6,  5,  3,  6, 9,  10, 27, 18, 14, 1,
                                 8, 20, 15, 13, 9,  10, 12, 15, 15, 21, 4,  5,  6,  20, 35, 56};
  if (type >= 1 && type <= 31) return kNodes[type];
  if (type == 92) return 64;
  if (type == 93) return 125;
  return 0;
}

// Dimension of the element types that feed the mesh or its sets; -1 for the skipped ones.
int KeptTypeDim(long long type) {
  switch (type) {
    case 15: return 0;  // point
    case 1: return 1;   // 2-node line
    case 2: return 2;   // 3-node triangle
    default: return -1;
  }
}

// Fuzzed or binary bytes can land in a message: keep it short and printable.
std::string Quote(std::string_view s) {
  std::string out = "'";
  const size_t n = std::min<size_t>(s.size(), 40);
  for (size_t i = 0; i < n; ++i) {
    const unsigned char c = (unsigned char)s[i];
    if (c >= 32 && c < 127) {
      out += (char)c;
    } else {
      char b[8];
      std::snprintf(b, sizeof b, "\\x%02x", c);
      out += b;
    }
  }
  if (s.size() > n) out += "...";
  return out + "'";
}

// reserve() for a block whose count ReadCount has bounded; growing at least geometrically keeps
// a file of many one-element blocks linear rather than copying the array once per block.
template <typename T> void Grow(std::vector<T> *v, size_t extra) {
  const size_t need = v->size() + extra;
  if (need > v->capacity()) v->reserve(std::max(need, 2 * v->capacity()));
}

bool IsSpace(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

std::string Str(long long v) { return std::to_string(v); }
std::string Str(unsigned long long v) { return std::to_string(v); }

// A cursor over the whole file. Values come either as whitespace-separated ASCII tokens or, inside
// the binary sections of a binary 4.1 file, as raw ints, size_ts and doubles; the section parsers
// read the same sequence of values in both cases and do not care which.
class Input {
 public:
  Input(const std::string &buf, const std::string &name) : buf_(buf), name_(name) {}

  const std::string &error() const { return error_; }
  size_t pos() const { return pos_; }
  size_t at() const { return at_; }  // start of the last value read
  size_t size() const { return buf_.size(); }
  size_t Remaining() const { return buf_.size() - pos_; }
  void SetBinary(bool binary) { binary_ = binary; }
  void SetBinaryLayout(bool swap, int size_width) {
    swap_ = swap;
    size_width_ = size_width;
  }

  bool FailAt(size_t pos, const std::string &msg) {
    if (!error_.empty()) return false;
    pos = std::min(pos, buf_.size());
    // Line numbers are counted only here: a parse that succeeds never pays for them.
    long long line = 1 + (long long)std::count(buf_.begin(), buf_.begin() + (long)pos, '\n');
    if (pos == buf_.size() && pos > 0 && buf_[pos - 1] == '\n') --line;  // EOF: the last line
    error_ = name_ + ":" + Str(line) + ": " + msg;
    if (binary_) error_ += " (binary data at byte offset " + Str((unsigned long long)pos) + ")";
    return false;
  }
  bool Fail(const std::string &msg) { return FailAt(at_, msg); }

  void SkipSpace() {
    while (pos_ < buf_.size() && IsSpace(buf_[pos_])) ++pos_;
  }
  bool AtEnd() {
    SkipSpace();
    return pos_ >= buf_.size();
  }

  // The next ASCII token; at the end of the file, fails saying what was expected.
  bool Token(std::string_view *tok, const std::string &what) {
    SkipSpace();
    at_ = pos_;
    if (pos_ >= buf_.size()) return Fail("unexpected end of file, expected " + what);
    const size_t start = pos_;
    while (pos_ < buf_.size() && !IsSpace(buf_[pos_])) ++pos_;
    *tok = std::string_view(buf_).substr(start, pos_ - start);
    return true;
  }

  // An ASCII integer token, in full: "12abc", "1.5" and "" are errors, not 12, 1 and 0.
  template <typename T> bool IntToken(T *v, const std::string &what) {
    std::string_view t;
    if (!Token(&t, what)) return false;
    const char *b = t.data(), *e = t.data() + t.size();
    if (std::is_unsigned<T>::value && *b == '-') {
      return Fail(what + " " + Quote(t) + " is negative");
    }
    if (e - b > 1 && *b == '+' && b[1] >= '0' && b[1] <= '9') ++b;
    const auto r = std::from_chars(b, e, *v);
    if (r.ec == std::errc::result_out_of_range) {
      return Fail(what + " " + Quote(t) + " is too large");
    }
    if (r.ec != std::errc() || r.ptr != e) return Fail("expected " + what + ", found " + Quote(t));
    return true;
  }

  bool ReadInt(long long *v, const std::string &what, long long lo, long long hi) {
    if (binary_) {
      int32_t x = 0;
      if (!Raw(&x, sizeof x, what)) return false;
      *v = x;
    } else if (!IntToken(v, what)) {
      return false;
    }
    if (*v < lo || *v > hi) {
      return Fail(what + " " + Str(*v) + " is out of range (" + Str(lo) + ".." + Str(hi) + ")");
    }
    return true;
  }

  bool ReadSize(unsigned long long *v, const std::string &what, unsigned long long lo,
                unsigned long long hi) {
    if (binary_) {
      if (size_width_ == 4) {
        uint32_t x = 0;
        if (!Raw(&x, sizeof x, what)) return false;
        *v = x;
      } else {
        uint64_t x = 0;
        if (!Raw(&x, sizeof x, what)) return false;
        *v = x;
      }
    } else if (!IntToken(v, what)) {
      return false;
    }
    if (*v < lo || *v > hi) {
      return Fail(what + " " + Str(*v) + " is out of range (" + Str(lo) + ".." + Str(hi) + ")");
    }
    return true;
  }

  // finite: reject nan/inf (coordinates); entity bounding boxes are read but never used.
  bool ReadDouble(double *v, const std::string &what, bool finite) {
    if (binary_) {
      if (!Raw(v, sizeof *v, what)) return false;
    } else {
      std::string_view t;
      if (!Token(&t, what)) return false;
      const char *b = t.data(), *e = t.data() + t.size();
      if (e - b > 1 && *b == '+' && (b[1] == '.' || (b[1] >= '0' && b[1] <= '9'))) ++b;
      const auto r = std::from_chars(b, e, *v);
      if (r.ec == std::errc::result_out_of_range && r.ptr == e) {
        // Below the smallest denormal reads as zero (as strtod would); above the largest double
        // it is garbage.
        const size_t x = t.find_first_of("eE");
        if (x == std::string_view::npos || x + 1 >= t.size() || t[x + 1] != '-') {
          return Fail(what + " " + Quote(t) + " is out of the range of a double");
        }
        *v = (*b == '-') ? -0.0 : 0.0;
      } else if (r.ec != std::errc() || r.ptr != e) {
        return Fail("expected " + what + ", found " + Quote(t));
      }
    }
    if (finite && !std::isfinite(*v)) return Fail(what + " is not a finite number");
    return true;
  }

  // A count of items that follow in the file. Each item needs at least ascii_tokens tokens (two
  // bytes each with the separator) or binary_bytes bytes, so a count the rest of the file cannot
  // hold is rejected here, before anything is allocated or looped over.
  bool ReadCount(size_t *n, const std::string &what, size_t ascii_tokens, size_t binary_bytes) {
    unsigned long long v;
    if (!ReadSize(&v, "number of " + what, 0, ULLONG_MAX)) return false;
    const size_t per_item = binary_ ? binary_bytes : 2 * ascii_tokens;
    if (per_item > 0 && v > Remaining() / per_item) {
      return Fail("number of " + what + " " + Str(v) + " is more than the remaining " +
                  Str((unsigned long long)Remaining()) + " bytes of the file can hold");
    }
    *n = (size_t)v;
    return true;
  }

  // Binary data starts right after the newline that ends the section header line.
  bool EndHeaderLine(const std::string &header) {
    while (pos_ < buf_.size() && (buf_[pos_] == ' ' || buf_[pos_] == '\t' || buf_[pos_] == '\r')) {
      ++pos_;
    }
    at_ = pos_;
    if (pos_ >= buf_.size() || buf_[pos_] != '\n') {
      return Fail("expected the end of the line after " + header);
    }
    ++pos_;
    return true;
  }

  // The rest of a record whose length is unknown (an element of an unknown type in ASCII).
  void SkipLine() {
    while (pos_ < buf_.size() && buf_[pos_] != '\n') ++pos_;
  }

  bool ExpectEnd(const std::string &section) {
    const std::string want = "$End" + section;
    std::string_view t;
    if (!Token(&t, want)) return false;
    if (t != want) {
      return Fail("expected " + want + ", found " + Quote(t) +
                  " (do the counts in the section match its contents?)");
    }
    return true;
  }

  // Sections this reader does not need ($Periodic, $NodeData, ...) are skipped by looking for
  // their end marker at the start of a line, as Gmsh does, which also works for binary ones.
  bool SkipSection(std::string_view name, size_t header_pos) {
    const std::string needle = "\n$End" + std::string(name);
    size_t from = pos_;
    for (;;) {
      const size_t p = buf_.find(needle, from);
      if (p == std::string::npos) {
        return FailAt(header_pos, "section $" + std::string(name) + " has no $End" +
                                      std::string(name));
      }
      const size_t q = p + needle.size();
      if (q == buf_.size() || IsSpace(buf_[q])) {
        pos_ = q;
        return true;
      }
      from = p + 1;
    }
  }

  // A physical name: "..." on the rest of the line; Gmsh allows spaces inside.
  bool QuotedName(std::string *name) {
    while (pos_ < buf_.size() && (buf_[pos_] == ' ' || buf_[pos_] == '\t')) ++pos_;
    at_ = pos_;
    if (pos_ >= buf_.size() || buf_[pos_] != '"') {
      return Fail("expected a physical name in double quotes");
    }
    const size_t start = ++pos_;
    while (pos_ < buf_.size() && buf_[pos_] != '"' && buf_[pos_] != '\n') ++pos_;
    if (pos_ >= buf_.size() || buf_[pos_] != '"') {
      return Fail("physical name has no closing double quote on its line");
    }
    *name = buf_.substr(start, pos_ - start);
    ++pos_;
    return true;
  }

 private:
  bool Raw(void *out, size_t n, const std::string &what) {
    at_ = pos_;
    if (Remaining() < n) return Fail("unexpected end of file, expected " + what);
    unsigned char tmp[8];
    std::memcpy(tmp, buf_.data() + pos_, n);
    if (swap_) std::reverse(tmp, tmp + n);
    std::memcpy(out, tmp, n);
    pos_ += n;
    return true;
  }

  const std::string &buf_;
  const std::string &name_;
  size_t pos_ = 0;
  size_t at_ = 0;  // where the value being read starts: the place errors point at
  bool binary_ = false;
  bool swap_ = false;
  int size_width_ = 8;
  std::string error_;
};

// The nodes and triangles of one entity (4.1) or one physical group (2.2), in file-order node
// indices and output triangle ids, kept per carrier so that a group on many elements costs one
// list rather than one entry per element and group.
struct Carrier {
  std::vector<int> nodes;
  std::vector<int> tris;
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
      std::string msg = "no 3-node triangles (element type 2) in $Elements";
      if (skipped_ > 0) {
        msg += "; skipped " + Str(skipped_) + " elements of other types (the first of type " +
               Str(first_skipped_type_) + "): this reader needs a first-order triangle mesh";
      }
      return in_.FailAt(elements_pos_, msg);
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
      return in_.Fail("not a Gmsh MSH file: expected $MeshFormat, found " + Quote(tok));
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
    std::vector<int>().swap(node_tags_);
    std::vector<size_t>().swap(node_tag_pos_);
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

  void Skipped(long long type, size_t count) {
    if (skipped_ == 0) first_skipped_type_ = type;
    skipped_ += (long long)count;
  }

  bool AddTriangle(const int *idx, Carrier *c) {
    if (tri_.size() / 3 >= (size_t)INT_MAX) return in_.Fail("too many triangles");
    const int id = (int)(tri_.size() / 3);
    tri_.insert(tri_.end(), idx, idx + 3);
    if (c) {
      c->tris.push_back(id);
      c->nodes.insert(c->nodes.end(), idx, idx + 3);
    }
    return true;
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
      if (npe == 0 && binary_) {
        return in_.Fail("element type " + Str(type) +
                        " is unknown, so its binary records cannot be skipped");
      }
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
      Carrier *carrier = nullptr;
      if (kept_dim >= 0) {
        if (kept_dim != dim) {
          return in_.Fail("element type " + Str(type) + " in a block of entity dimension " +
                          Str(dim) + " (expected " + Str((long long)kept_dim) + ")");
        }
        if (seen_entities_ && entities_.count(Key((int)dim, entity)) == 0) {
          return in_.FailAt(entity_pos, "element block refers to entity (dimension " + Str(dim) +
                                            ", tag " + Str(entity) + "), which $Entities lacks");
        }
        carrier = &carriers_[Key((int)dim, entity)];
        if (type == 2) Grow(&tri_, 3 * n);
      } else {
        Skipped(type, n);
      }
      for (size_t i = 0; i < n; ++i) {
        unsigned long long tag;
        if (!in_.ReadSize(&tag, "element tag", 1, kMaxTag)) return false;
        if (npe == 0) {
          in_.SkipLine();
          continue;
        }
        int idx[3] = {-1, -1, -1};
        if (!ReadElementNodes(npe, kept_dim >= 0, tag, idx)) return false;
        if (type == 2) {
          if (!AddTriangle(idx, carrier)) return false;
        } else if (carrier) {
          carrier->nodes.insert(carrier->nodes.end(), idx, idx + npe);
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
    // with the same elementary tag and nodes: those are one triangle in several groups.
    bool prev_tri = false;
    long long prev_elementary = 0, prev_phys = 0;
    int prev_idx[3] = {-1, -1, -1};
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
      if (dim < 0) {
        prev_tri = false;
        Skipped(type, 1);
        if (npe == 0) {
          in_.SkipLine();
        } else if (!ReadElementNodes(npe, false, tag, nullptr)) {
          return false;
        }
        continue;
      }
      int idx[3] = {-1, -1, -1};
      if (!ReadElementNodes(npe, true, tag, idx)) return false;
      Carrier *carrier = (phys != 0) ? &carriers_[Key(dim, phys)] : nullptr;
      if (type == 2) {
        const bool repeat = prev_tri && elementary == prev_elementary && phys != prev_phys &&
                            std::equal(idx, idx + 3, prev_idx);
        if (repeat) {
          if (carrier) {
            carrier->tris.push_back((int)(tri_.size() / 3) - 1);
            carrier->nodes.insert(carrier->nodes.end(), idx, idx + 3);
          }
        } else if (!AddTriangle(idx, carrier)) {
          return false;
        }
        prev_tri = true;
        prev_elementary = elementary;
        prev_phys = phys;
        std::copy(idx, idx + 3, prev_idx);
      } else {
        prev_tri = false;
        if (carrier) carrier->nodes.insert(carrier->nodes.end(), idx, idx + npe);
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
      for (const Carrier *c : g.second) entries += c->nodes.size() + c->tris.size();
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
  std::map<Key, std::vector<long long>> entities_;  // (dim, entity tag) -> physical tags
  std::map<Key, Carrier> carriers_;  // (dim, entity tag) in 4.1, (dim, physical tag) in 2.2
  std::map<Key, std::string> names_;
  long long skipped_ = 0, first_skipped_type_ = 0;
};

// ---- writer ----

void Append(std::string *out, double v) {
  char b[32];
  const auto r = std::to_chars(b, b + sizeof b, v);  // shortest form that reads back exactly
  out->append(b, r.ptr);
}
void Append(std::string *out, long long v) {
  char b[24];
  const auto r = std::to_chars(b, b + sizeof b, v);
  out->append(b, r.ptr);
}
void Append(std::string *out, const char *s) { out->append(s); }
template <typename T> void Field(std::string *out, T v) {
  out->push_back(' ');
  Append(out, v);
}
template <typename T, typename... Rest> void Line(std::string *out, T first, Rest... rest) {
  Append(out, first);
  (Field(out, rest), ...);
  out->push_back('\n');
}

bool WriteFail(const std::string &path, const MeshData &mesh, const std::string &msg,
               std::string *err) {
  if (err) *err = path + ": cannot write mesh " + Quote(mesh.source) + ": " + msg;
  return false;
}

// The writer needs only what keeps the file self-consistent; quality checks are MeshCheck's.
bool WriterCheck(const std::string &path, const MeshData &mesh, std::string *err) {
  if (mesh.coords.size() % 3 != 0 || mesh.triangles.size() % 3 != 0) {
    return WriteFail(path, mesh, "coords or triangles is not a multiple of 3 long", err);
  }
  const size_t nn = mesh.coords.size() / 3, ne = mesh.triangles.size() / 3;
  if (nn + ne >= (size_t)INT_MAX) {  // element tags run over triangles and then points
    return WriteFail(path, mesh, "too many nodes or elements", err);
  }
  for (size_t i = 0; i < mesh.coords.size(); ++i) {
    if (!std::isfinite(mesh.coords[i])) {
      return WriteFail(path, mesh,
                       "node " + Str((long long)(i / 3)) + " has a non-finite coordinate", err);
    }
  }
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    if (mesh.triangles[i] < 0 || (size_t)mesh.triangles[i] >= nn) {
      return WriteFail(path, mesh, "element " + Str((long long)(i / 3)) + " refers to node " +
                                       Str((long long)mesh.triangles[i]) + ", out of range", err);
    }
  }
  for (int dim = 0; dim < 2; ++dim) {
    const auto &sets = dim == 0 ? mesh.node_sets : mesh.element_sets;
    const size_t n = dim == 0 ? nn : ne;
    for (const auto &s : sets) {
      if (s.first.empty() || s.first.find_first_of("\"\n\r") != std::string::npos) {
        return WriteFail(path, mesh, "set name " + Quote(s.first) +
                                         " is empty or has a double quote or line break", err);
      }
      for (int v : s.second) {
        if (v < 0 || (size_t)v >= n) {
          return WriteFail(path, mesh, std::string(dim == 0 ? "node" : "element") + " set " +
                                           Quote(s.first) + " holds id " + Str((long long)v) +
                                           ", out of range", err);
        }
      }
    }
  }
  return true;
}

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
  std::FILE *f = std::fopen(path.c_str(), "rb");
  if (!f) {
    if (err) *err = path + ": cannot open: " + std::strerror(errno);
    return false;
  }
  std::string buf;
  char chunk[1 << 16];
  size_t got;
  while ((got = std::fread(chunk, 1, sizeof chunk, f)) > 0) buf.append(chunk, got);
  const bool bad = std::ferror(f) != 0;
  const int read_errno = errno;
  std::fclose(f);
  if (bad) {
    if (err) *err = path + ": cannot read: " + std::strerror(read_errno);
    return false;
  }
  return ReadGmshBuffer(buf, path, mesh, err);
}

// Layout: all nodes in one block on surface entity 1. Triangles go to one surface entity per
// distinct combination of element sets (a triangle can only sit on one entity), written in runs
// so that the file keeps the triangle order. A node set is the node set of the element set with
// the same name (the reader derives it) plus, for the nodes that adds, a 0-D physical group of
// the same name carried by one point entity per node, as Gmsh itself models points.
bool WriteGmshFile(const std::string &path, const MeshData &mesh, std::string *err) {
  if (!WriterCheck(path, mesh, err)) return false;
  const size_t nn = mesh.coords.size() / 3, ne = mesh.triangles.size() / 3;

  // 2-D physical tags 1..E for the element sets, then 0-D tags for the node sets that need them.
  std::vector<std::pair<long long, const std::string *>> phys2, phys0;
  std::vector<std::vector<long long>> tri_groups(ne);
  for (const auto &s : mesh.element_sets) {
    const long long tag = (long long)phys2.size() + 1;
    phys2.emplace_back(tag, &s.first);
    for (int e : s.second) {
      if (tri_groups[(size_t)e].empty() || tri_groups[(size_t)e].back() != tag) {
        tri_groups[(size_t)e].push_back(tag);
      }
    }
  }
  std::map<int, std::vector<long long>> point_groups;  // node -> 0-D physical tags
  for (const auto &s : mesh.node_sets) {
    std::vector<char> covered;
    const auto es = mesh.element_sets.find(s.first);
    if (es != mesh.element_sets.end()) {
      covered.assign(nn, 0);
      for (int e : es->second) {
        for (int k = 0; k < 3; ++k) covered[(size_t)mesh.triangles[3 * (size_t)e + k]] = 1;
      }
    }
    std::vector<int> extra;
    for (int v : s.second) {
      if (covered.empty() || !covered[(size_t)v]) extra.push_back(v);
    }
    // An empty node set without an element set is kept as a named group with no entity.
    if (extra.empty() && !(s.second.empty() && es == mesh.element_sets.end())) continue;
    const long long tag = (long long)(phys2.size() + phys0.size()) + 1;
    phys0.emplace_back(tag, &s.first);
    for (int v : extra) {
      std::vector<long long> &g = point_groups[v];
      if (g.empty() || g.back() != tag) g.push_back(tag);
    }
  }

  // Surface entities: one per distinct group combination, in order of first use.
  std::map<std::vector<long long>, long long> surface_of;
  std::vector<const std::vector<long long> *> surface_groups;
  std::vector<long long> tri_surface(ne);
  for (size_t e = 0; e < ne; ++e) {
    const auto ins = surface_of.emplace(tri_groups[e], (long long)surface_groups.size() + 1);
    if (ins.second) surface_groups.push_back(&ins.first->first);
    tri_surface[e] = ins.first->second;
  }
  static const std::vector<long long> kNoGroups;
  if (surface_groups.empty()) surface_groups.push_back(&kNoGroups);  // to carry the nodes
  const size_t nsurf = surface_groups.size();
  std::vector<double> box(6 * nsurf, 0.0);
  std::vector<char> box_set(nsurf, 0);
  for (size_t e = 0; e < ne; ++e) {
    const size_t s = (size_t)tri_surface[e] - 1;
    for (int k = 0; k < 3; ++k) {
      const double *x = &mesh.coords[3 * (size_t)mesh.triangles[3 * e + k]];
      for (int c = 0; c < 3; ++c) {
        if (!box_set[s] || x[c] < box[6 * s + c]) box[6 * s + c] = x[c];
        if (!box_set[s] || x[c] > box[6 * s + 3 + c]) box[6 * s + 3 + c] = x[c];
      }
      box_set[s] = 1;
    }
  }

  std::string out;
  out.reserve(64 * (nn + ne) + 4096);
  out += "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
  out += "$PhysicalNames\n";
  Line(&out, (long long)(phys0.size() + phys2.size()));
  for (const auto &p : phys0) {
    Line(&out, 0LL, p.first, ("\"" + *p.second + "\"").c_str());
  }
  for (const auto &p : phys2) {
    Line(&out, 2LL, p.first, ("\"" + *p.second + "\"").c_str());
  }
  out += "$EndPhysicalNames\n$Entities\n";
  Line(&out, (long long)point_groups.size(), 0LL, (long long)nsurf, 0LL);
  long long point_tag = 0;
  for (const auto &pg : point_groups) {
    const double *x = &mesh.coords[3 * (size_t)pg.first];
    Append(&out, ++point_tag);
    for (int c = 0; c < 3; ++c) Field(&out, x[c]);
    Field(&out, (long long)pg.second.size());
    for (long long t : pg.second) Field(&out, t);
    out += '\n';
  }
  for (size_t s = 0; s < nsurf; ++s) {
    Append(&out, (long long)s + 1);
    for (int c = 0; c < 6; ++c) Field(&out, box[6 * s + c]);
    Field(&out, (long long)surface_groups[s]->size());
    for (long long t : *surface_groups[s]) Field(&out, t);
    out += " 0\n";  // no bounding curves: a discrete surface
  }
  out += "$EndEntities\n$Nodes\n";
  Line(&out, 1LL, (long long)nn, nn ? 1LL : 0LL, (long long)nn);
  Line(&out, 2LL, 1LL, 0LL, (long long)nn);
  for (size_t i = 0; i < nn; ++i) Line(&out, (long long)i + 1);
  for (size_t i = 0; i < nn; ++i) {
    Line(&out, mesh.coords[3 * i], mesh.coords[3 * i + 1], mesh.coords[3 * i + 2]);
  }
  out += "$EndNodes\n$Elements\n";
  size_t nruns = 0;
  for (size_t e = 0; e < ne; ++e) nruns += (e == 0 || tri_surface[e] != tri_surface[e - 1]);
  const size_t nelem = ne + point_groups.size();
  Line(&out, (long long)(nruns + point_groups.size()), (long long)nelem, nelem ? 1LL : 0LL,
       (long long)nelem);
  for (size_t e = 0; e < ne;) {
    size_t end = e;
    while (end < ne && tri_surface[end] == tri_surface[e]) ++end;
    Line(&out, 2LL, tri_surface[e], 2LL, (long long)(end - e));
    for (; e < end; ++e) {
      Line(&out, (long long)e + 1, (long long)mesh.triangles[3 * e] + 1,
           (long long)mesh.triangles[3 * e + 1] + 1, (long long)mesh.triangles[3 * e + 2] + 1);
    }
  }
  long long elem_tag = (long long)ne;
  point_tag = 0;
  for (const auto &pg : point_groups) {
    Line(&out, 0LL, ++point_tag, 15LL, 1LL);
    Line(&out, ++elem_tag, (long long)pg.first + 1);
  }
  out += "$EndElements\n";

  std::FILE *f = std::fopen(path.c_str(), "wb");
  if (!f) {
    if (err) *err = path + ": cannot open for writing: " + std::strerror(errno);
    return false;
  }
  const bool wrote = std::fwrite(out.data(), 1, out.size(), f) == out.size();
  const int write_errno = errno;
  if (std::fclose(f) != 0 || !wrote) {
    if (err) *err = path + ": cannot write: " + std::strerror(wrote ? errno : write_errno);
    return false;
  }
  return true;
}

} // namespace etfe
