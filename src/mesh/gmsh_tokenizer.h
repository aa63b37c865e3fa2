// The tokenizer of the Gmsh MSH reader (src/mesh/gmsh_reader.cpp): a cursor over the whole file
// that yields ASCII tokens or raw binary values, checks every number in full and every count
// against the bytes left, and turns each failure into "<file>:<line>: <what>". Private to
// src/mesh (the fuzz target builds it too); PETSc-free.
#pragma once
#include <algorithm>
#include <charconv>
#include <climits>
#include <cstddef>
#include <string>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <vector>

namespace etfe {
namespace gmsh {

// Tags become int ids in MeshData; a membrane mesh with 2^31 nodes is not a use case, and the
// limit turns garbage such as 2^40 into a clear error instead of a silent truncation.
constexpr unsigned long long kMaxTag = INT_MAX;

// Nodes per element of the element types in the Gmsh documentation; 0 = unknown, so a binary
// record of that type cannot be skipped.
inline int NodesPerElement(long long type) {
  static const int kNodes[32] = {0, 2,  3,  4,  4,  8,  6,  5,  3,  6, 9,  10, 27, 18, 14, 1,
                                 8, 20, 15, 13, 9,  10, 12, 15, 15, 21, 4,  5,  6,  20, 35, 56};
  if (type >= 1 && type <= 31) return kNodes[type];
  if (type == 92) return 64;
  if (type == 93) return 125;
  return 0;
}

// Fuzzed or binary bytes can land in a message: keep it short and printable.
std::string Quote(std::string_view s);

// reserve() for a block whose count ReadCount has bounded; growing at least geometrically keeps
// a file of many one-element blocks linear rather than copying the array once per block.
template <typename T> void Grow(std::vector<T> *v, size_t extra) {
  const size_t need = v->size() + extra;
  if (need > v->capacity()) v->reserve(std::max(need, 2 * v->capacity()));
}

// No ASCII MSH token (a number, a section name) is anywhere near this long, nor any line
// ($Entities lines list bounding entities, a few per curve): a file of zeros or binary junk is
// refused at its first token instead of being scanned or held to the end.
constexpr size_t kMaxTokenChars = 1024;
constexpr size_t kMaxLineBytes = 1u << 20;

inline bool IsSpace(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

inline std::string Str(long long v) { return std::to_string(v); }
inline std::string Str(unsigned long long v) { return std::to_string(v); }

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
  void SetBinary(bool binary) {
    binary_ = binary;
    line_start_ = pos_;
  }
  void SetBinaryLayout(bool swap, int size_width) {
    swap_ = swap;
    size_width_ = size_width;
  }

  bool FailAt(size_t pos, const std::string &msg);
  bool Fail(const std::string &msg) { return FailAt(at_, msg); }

  void SkipSpace() {
    for (; pos_ < buf_.size() && IsSpace(buf_[pos_]); ++pos_) {
      if (buf_[pos_] == '\n') line_start_ = pos_ + 1;
    }
  }
  bool AtEnd() {
    SkipSpace();
    return pos_ >= buf_.size();
  }

  // The next ASCII token; at the end of the file, fails saying what was expected.
  bool Token(std::string_view *tok, const std::string &what);

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

  bool ReadInt(long long *v, const std::string &what, long long lo, long long hi);

  bool ReadSize(unsigned long long *v, const std::string &what, unsigned long long lo,
                unsigned long long hi);

  // finite: reject nan/inf (coordinates); entity bounding boxes are read but never used.
  bool ReadDouble(double *v, const std::string &what, bool finite);

  // A count of items that follow in the file. Each item needs at least ascii_tokens tokens (two
  // bytes each with the separator) or binary_bytes bytes, so a count the rest of the file cannot
  // hold is rejected here, before anything is allocated or looped over.
  bool ReadCount(size_t *n, const std::string &what, size_t ascii_tokens, size_t binary_bytes);

  // Binary data starts right after the newline that ends the section header line.
  bool EndHeaderLine(const std::string &header);

  bool ExpectEnd(const std::string &section);

  // Sections this reader does not need ($Periodic, $NodeData, ...) are skipped by looking for
  // their end marker at the start of a line, as Gmsh does, which also works for binary ones.
  bool SkipSection(std::string_view name, size_t header_pos);

  // A physical name: "..." on the rest of the line; Gmsh allows spaces inside.
  bool QuotedName(std::string *name);

 private:
  bool Raw(void *out, size_t n, const std::string &what);

  const std::string &buf_;
  const std::string &name_;
  size_t pos_ = 0;
  size_t at_ = 0;  // where the value being read starts: the place errors point at
  size_t line_start_ = 0;  // of the ASCII line being read, for the line-length cap
  bool binary_ = false;
  bool swap_ = false;
  int size_width_ = 8;
  std::string error_;
};

} // namespace gmsh
} // namespace etfe
