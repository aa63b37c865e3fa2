// Tests of the Gmsh reader and writer and of MeshCheck: the shipped square meshes (MSH 4.1 and
// 2.2), a hand-made binary 4.1 file in both byte orders, write/read round trips, damaged inputs
// that must fail with "<file>:<line>:", and MeshCheck's messages.
// Usage: test_gmsh_reader [meshes-directory]   (default "meshes")
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "check.h"
#include "etfe/mesh/gmsh_reader.h"

namespace {

using etfe::MeshData;

bool Contains(const std::string &s, const std::string &part) {
  return s.find(part) != std::string::npos;
}

std::string Slurp(const std::string &path) {
  std::string out;
  if (std::FILE *f = std::fopen(path.c_str(), "rb")) {
    char b[4096];
    size_t n;
    while ((n = std::fread(b, 1, sizeof b, f)) > 0) out.append(b, n);
    std::fclose(f);
  }
  return out;
}

// Twice the signed area in the XY plane: Gmsh orients a plane surface's triangles with it.
double SignedArea2(const MeshData &m, int e) {
  const double *a = &m.coords[3 * m.triangles[3 * e]];
  const double *b = &m.coords[3 * m.triangles[3 * e + 1]];
  const double *c = &m.coords[3 * m.triangles[3 * e + 2]];
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

bool SameMesh(const MeshData &a, const MeshData &b) {
  return a.coords == b.coords && a.triangles == b.triangles && a.node_sets == b.node_sets &&
         a.element_sets == b.element_sets;
}

// The unit square 0..1000 mm of meshes/square_groups.geo: 30 nodes, 42 triangles.
void CheckSquare(const MeshData &m, const std::string &what) {
  CHECK(m.NumNodes() == 30, "%s: %d nodes", what.c_str(), m.NumNodes());
  CHECK(m.NumElements() == 42, "%s: %d elements", what.c_str(), m.NumElements());
  double total = 0;
  bool all_positive = true;
  for (int e = 0; e < m.NumElements(); ++e) {
    const double a2 = SignedArea2(m, e);
    all_positive = all_positive && a2 > 0;
    total += 0.5 * a2;
  }
  CHECK(all_positive, "%s: a triangle has a non-positive area", what.c_str());
  CHECK_CLOSE(total, 1e6, 1e-9, 0.0);

  const struct { const char *name; size_t size; int axis; double value; } kSets[] = {
      {"left", 5, 0, 0.0},   {"right", 5, 0, 1000.0}, {"bottom", 5, 1, 0.0},
      {"top", 5, 1, 1000.0}, {"corner", 1, -1, 0.0},  {"film", 30, -1, 0.0}};
  CHECK(m.node_sets.size() == 6, "%s: %zu node sets", what.c_str(), m.node_sets.size());
  for (const auto &s : kSets) {
    const auto it = m.node_sets.find(s.name);
    CHECK(it != m.node_sets.end(), "%s: no node set %s", what.c_str(), s.name);
    if (it == m.node_sets.end()) continue;
    CHECK(it->second.size() == s.size, "%s: set %s has %zu nodes", what.c_str(), s.name,
          it->second.size());
    for (int v : it->second) {
      if (s.axis >= 0) {
        CHECK(m.coords[3 * v + s.axis] == s.value, "%s: node %d of %s is off its edge",
              what.c_str(), v, s.name);
      }
    }
  }
  // The 1-D groups' line elements (cables run along them): 4 segments per edge, both nodes on it.
  CHECK(m.line_sets.size() == 4, "%s: %zu line sets", what.c_str(), m.line_sets.size());
  for (const auto &s : kSets) {
    if (s.axis < 0) continue;
    const auto it = m.line_sets.find(s.name);
    CHECK(it != m.line_sets.end() && it->second.size() == 8, "%s: line set %s missing or not 4 segments", what.c_str(),
          s.name);
    if (it == m.line_sets.end()) continue;
    for (size_t k = 0; k + 1 < it->second.size(); k += 2) {
      const int a = it->second[k], b = it->second[k + 1];
      CHECK(a >= 0 && b >= 0 && a != b && m.coords[3 * a + s.axis] == s.value && m.coords[3 * b + s.axis] == s.value,
            "%s: segment %zu of %s is not an edge segment", what.c_str(), k / 2, s.name);
    }
  }
  const auto corner = m.node_sets.find("corner");
  if (corner != m.node_sets.end() && corner->second.size() == 1) {
    const int v = corner->second[0];
    CHECK(m.coords[3 * v] == 0 && m.coords[3 * v + 1] == 0, "%s: corner is not at the origin",
          what.c_str());
  }
  CHECK(m.element_sets.size() == 1 && m.element_sets.count("film") == 1,
        "%s: expected only the element set film", what.c_str());
  if (m.element_sets.count("film")) {
    const std::vector<int> &film = m.element_sets.at("film");
    bool all = film.size() == 42;
    for (size_t i = 0; all && i < film.size(); ++i) all = film[i] == (int)i;
    CHECK(all, "%s: film is not all 42 triangles", what.c_str());
  }
  std::string err;
  CHECK(etfe::MeshCheck(m, 1e-6, &err), "%s: %s", what.c_str(), err.c_str());
}

// A small valid MSH 4.1 file; the damaged variants below edit single lines of it.
const char *const kSmall =
    "$MeshFormat\n"                     // 1
    "4.1 0 8\n"                         // 2
    "$EndMeshFormat\n"                  // 3
    "$PhysicalNames\n"                  // 4
    "2\n"                               // 5
    "1 1 \"edge\"\n"                    // 6
    "2 2 \"film\"\n"                    // 7
    "$EndPhysicalNames\n"               // 8
    "$Entities\n"                       // 9
    "2 1 1 0\n"                         // 10
    "1 0 0 0 0\n"                       // 11
    "2 1 0 0 0\n"                       // 12
    "1 0 0 0 1 0 0 1 1 2 1 -2\n"        // 13
    "1 0 0 0 1 1 0 1 2 1 1\n"           // 14
    "$EndEntities\n"                    // 15
    "$Nodes\n"                          // 16
    "1 4 1 4\n"                         // 17
    "2 1 0 4\n"                         // 18
    "1\n"                               // 19
    "2\n"                               // 20
    "3\n"                               // 21
    "4\n"                               // 22
    "0 0 0\n"                           // 23
    "1 0 0\n"                           // 24
    "1 1 0\n"                           // 25
    "0 1 0\n"                           // 26
    "$EndNodes\n"                       // 27
    "$Elements\n"                       // 28
    "2 3 1 3\n"                         // 29
    "1 1 1 1\n"                         // 30
    "1 1 2\n"                           // 31
    "2 1 2 2\n"                         // 32
    "2 1 2 3\n"                         // 33
    "3 1 3 4\n"                         // 34
    "$EndElements\n";                   // 35

std::vector<std::string> Lines(const std::string &s) {
  std::vector<std::string> out;
  size_t start = 0;
  while (start < s.size()) {
    size_t end = s.find('\n', start);
    if (end == std::string::npos) end = s.size();
    out.push_back(s.substr(start, end - start));
    start = end + 1;
  }
  return out;
}

// kSmall with lines first..last (1-based) replaced by text.
std::string EditRange(int first, int last, const std::string &text) {
  const std::vector<std::string> lines = Lines(kSmall);
  std::string out;
  for (int i = 1; i <= (int)lines.size(); ++i) {
    if (i == first) out += text + "\n";
    if (i < first || i > last) out += lines[(size_t)i - 1] + "\n";
  }
  return out;
}
std::string Edit(int line, const std::string &text) { return EditRange(line, line, text); }

// True when err is "<name>:<digits>: <something>".
bool Located(const std::string &err, const std::string &name, long *line) {
  if (err.compare(0, name.size() + 1, name + ":") != 0) return false;
  size_t i = name.size() + 1, j = i;
  while (j < err.size() && err[j] >= '0' && err[j] <= '9') ++j;
  if (j == i || err.compare(j, 2, ": ") != 0 || j + 2 >= err.size()) return false;
  *line = std::stol(err.substr(i, j - i));
  return true;
}

void ExpectFailure(const std::string &buf, int want_line, const std::string &want_text,
                   const std::string &what) {
  MeshData m;
  m.source = "untouched";
  std::string err;
  const bool ok = etfe::ReadGmshBuffer(buf, "bad.msh", &m, &err);
  std::printf("  %-28s -> %s\n", what.c_str(), err.c_str());
  CHECK(!ok, "%s: accepted", what.c_str());
  long line = -1;
  CHECK(Located(err, "bad.msh", &line), "%s: message not located: %s", what.c_str(), err.c_str());
  const std::string tag = ":" + std::to_string(want_line) + ":";
  CHECK(Contains(err, tag), "%s: expected %s in: %s", what.c_str(), tag.c_str(), err.c_str());
  CHECK(Contains(err, want_text), "%s: expected '%s' in: %s", what.c_str(), want_text.c_str(),
        err.c_str());
  CHECK(m.source == "untouched" && m.coords.empty(), "%s: output changed on failure",
        what.c_str());
}

// Every strict prefix that ends before the last token is complete must fail, with a location.
void CheckTruncations(const std::string &full, const std::string &what) {
  size_t end = full.size();
  while (end > 0 && (full[end - 1] == '\n' || full[end - 1] == '\r')) --end;
  int bad = 0, unlocated = 0;
  for (size_t k = 0; k < end; ++k) {
    MeshData m;
    std::string err;
    if (etfe::ReadGmshBuffer(full.substr(0, k), "cut.msh", &m, &err)) {
      if (bad++ == 0) std::printf("  %s: prefix of %zu bytes accepted\n", what.c_str(), k);
      continue;
    }
    long line = -1;
    if (!Located(err, "cut.msh", &line)) {
      if (unlocated++ == 0) std::printf("  %s: unlocated message: %s\n", what.c_str(), err.c_str());
    }
  }
  CHECK(bad == 0, "%s: %d truncated prefixes were accepted", what.c_str(), bad);
  CHECK(unlocated == 0, "%s: %d messages without <file>:<line>:", what.c_str(), unlocated);
}

void TestDamagedInputs() {
  std::printf("damaged inputs:\n");
  {
    MeshData m;
    std::string err;
    CHECK(etfe::ReadGmshBuffer(kSmall, "small.msh", &m, &err), "small: %s", err.c_str());
    CHECK(m.NumNodes() == 4 && m.NumElements() == 2, "small: %d nodes %d elements", m.NumNodes(),
          m.NumElements());
    CHECK(m.node_sets.count("edge") && m.node_sets["edge"] == std::vector<int>({0, 1}),
          "small: edge set");
    CHECK(m.element_sets.count("film") && m.element_sets["film"] == std::vector<int>({0, 1}),
          "small: film set");
  }
  // Line-level truncations, then every byte.
  const std::vector<std::string> lines = Lines(kSmall);
  for (size_t n = 0; n + 1 < lines.size(); ++n) {
    std::string cut;
    for (size_t i = 0; i < n; ++i) cut += lines[i] + "\n";
    MeshData m;
    std::string err;
    long line = -1;
    const bool ok = etfe::ReadGmshBuffer(cut, "cut.msh", &m, &err);
    CHECK(!ok && Located(err, "cut.msh", &line) && line >= 1 && line <= (long)n + 1,
          "truncated after %zu lines: %s", n, err.c_str());
  }
  CheckTruncations(kSmall, "small");

  ExpectFailure(Edit(17, "1 5 1 5"), 17, "gives 5 nodes", "wrong node count");
  ExpectFailure(Edit(18, "2 1 0 5"), 18, "hold more than", "wrong block size");
  ExpectFailure(Edit(29, "2 4 1 4"), 29, "gives 4 elements", "wrong element count");
  ExpectFailure(Edit(32, "2 1 2 3"), 32, "hold more than", "block longer than its count");
  ExpectFailure(Edit(24, "1.2.3 0 0"), 24, "'1.2.3'", "bad number 1.2.3");
  ExpectFailure(Edit(25, "1 nan 0"), 25, "not a finite number", "nan coordinate");
  ExpectFailure(Edit(25, "1 1e999 0"), 25, "range of a double", "1e999 coordinate");
  ExpectFailure(Edit(21, "1099511627776"), 21, "node tag", "node tag 2^40");
  ExpectFailure(Edit(21, "-3"), 21, "negative", "negative node tag");
  ExpectFailure(Edit(21, "1"), 21, "defined twice", "duplicate node tag");
  ExpectFailure(Edit(34, "3 1 3 9"), 34, "node 9", "triangle with a missing node");
  ExpectFailure(Edit(17, "1 -4 1 4"), 17, "negative", "negative count");
  ExpectFailure(Edit(17, "1 1000000000000 1 4"), 17, "can hold", "node count 10^12");
  ExpectFailure(Edit(29, "2 1000000000000 1 3"), 29, "can hold", "element count 10^12");
  ExpectFailure(Edit(5, "1000000000000"), 5, "can hold", "name count 10^12");
  ExpectFailure(Edit(10, "2 1 1000000000000 0"), 10, "can hold", "entity count 10^12");
  ExpectFailure(Edit(18, "2 1 0 " + std::string(400, '9')), 18, "too large", "400-digit count");
  ExpectFailure(Edit(10, "2 one 1 0"), 10, "'one'", "word for a number");
  ExpectFailure(Edit(32, "2 7 2 2"), 32, "$Entities lacks", "unknown entity");
  ExpectFailure(Edit(32, "1 1 2 2"), 32, "entity dimension 1", "triangle on a curve");
  ExpectFailure(Edit(2, "4.0 0 8"), 2, "not supported", "MSH 4.0");
  ExpectFailure(Edit(2, "2.2 1 8"), 2, "binary MSH 2", "binary MSH 2.2");
  ExpectFailure(Edit(6, "1 1 \"edge"), 6, "closing double quote", "unclosed name");
  ExpectFailure(Edit(7, "1 1 \"again\""), 7, "named twice", "name given twice");
  ExpectFailure(Edit(27, "$EndNode"), 27, "$EndNodes", "misspelt end marker");
  ExpectFailure(Edit(16, "$Elements"), 16, "after $Nodes", "elements before nodes");
  ExpectFailure(Edit(1, "$MeshFormats"), 1, "not a Gmsh MSH file", "not MSH");
  ExpectFailure("", 1, "empty", "empty buffer");
  ExpectFailure(std::string(kSmall) + "$NodeData\n1\n", 36, "no $EndNodeData",
                "unterminated section");
  // Element types the membrane cannot use are refused, naming the element and its type, not
  // dropped: a tetrahedron among the triangles, a second-order triangle.
  ExpectFailure(EditRange(29, 29, "3 4 1 9\n2 1 4 1\n9 1 2 3 4"), 31, "element 9 is of type 4",
                "tetrahedron among triangles");
  ExpectFailure(EditRange(29, 34, "2 2 1 2\n1 1 1 1\n1 1 2\n2 1 9 1\n2 1 2 3 4 1 2 3"), 33,
                "type 9 (6-node second-order triangle)", "second-order triangle");
  {
    // Quadrangles are split into two triangles along the shorter diagonal, with a note; their
    // physical group gets both halves, and both carry the quad's tag.
    const std::string s = EditRange(29, 34, "2 2 1 2\n1 1 1 1\n1 1 2\n2 1 3 1\n7 1 2 3 4");
    MeshData m;
    std::string err;
    CHECK(etfe::ReadGmshBuffer(s, "quads.msh", &m, &err), "quads: %s", err.c_str());
    CHECK(m.NumElements() == 2 && m.element_tags == std::vector<long long>({7, 7}),
          "quads: %d elements", m.NumElements());
    CHECK(m.element_sets["film"] == std::vector<int>({0, 1}), "quads: film set");
    CHECK(m.notes.size() == 1 && Contains(m.notes[0], "split 1 quadrangles"), "quads: note");
    CHECK(etfe::MeshCheck(m, 1e-9, &err), "quads: %s", err.c_str());
  }
  {
    // Harmless extras: CRLF line ends, sections this reader ignores.
    std::string s;
    for (const std::string &x : Lines(kSmall)) s += x + "\r\n";
    s += "$Periodic\n0\n$EndPeriodic\n$NodeData\n1\n\"x\"\n$EndNodeData\n";
    MeshData m;
    std::string err;
    CHECK(etfe::ReadGmshBuffer(s, "extra.msh", &m, &err), "extras: %s", err.c_str());
    CHECK(m.NumElements() == 2, "extras: %d elements", m.NumElements());
    CHECK(m.node_tags == std::vector<long long>({1, 2, 3, 4}), "extras: node tags");
  }
  // A file of zeros or binary junk stops at its first token, long before its end.
  ExpectFailure("$MeshFormat\n" + std::string(5000, '\0'), 2, "longer than 1024", "zeros");
  {
    // Sparse node tags and a node no triangle uses: dropped, also from its node set.
    const std::string s = EditRange(17, 34,
                                    "1 5 2 1000000\n"
                                    "2 1 0 5\n"
                                    "10\n2\n3\n4\n1000000\n"
                                    "0 0 0\n1 0 0\n1 1 0\n0 1 0\n7 7 7\n"
                                    "$EndNodes\n$Elements\n"
                                    "2 3 1 3\n"
                                    "1 1 1 1\n1 10 1000000\n"
                                    "2 1 2 2\n2 10 2 3\n3 10 3 4");
    MeshData m;
    std::string err;
    CHECK(etfe::ReadGmshBuffer(s, "sparse.msh", &m, &err), "sparse: %s", err.c_str());
    CHECK(m.NumNodes() == 4, "sparse: %d nodes", m.NumNodes());
    CHECK(m.node_sets.count("edge") && m.node_sets["edge"] == std::vector<int>({0}),
          "sparse: edge set should keep only node 0");
    CHECK(etfe::MeshCheck(m, 1e-9, &err), "sparse: %s", err.c_str());
  }
}

// A binary MSH 4.1 version of kSmall, in native or swapped byte order.
struct BinaryWriter {
  std::string out;
  bool swap;
  void Raw(const void *p, size_t n) {
    unsigned char b[8];
    std::memcpy(b, p, n);
    if (swap) {
      for (size_t i = 0; i < n / 2; ++i) std::swap(b[i], b[n - 1 - i]);
    }
    out.append((const char *)b, n);
  }
  void I(int32_t v) { Raw(&v, 4); }
  void S(uint64_t v) { Raw(&v, 8); }
  void D(double v) { Raw(&v, 8); }
};

std::string BinarySmall(bool swap) {
  BinaryWriter w{"", swap};
  w.out = "$MeshFormat\n4.1 1 8\n";
  w.I(1);
  w.out += "\n$EndMeshFormat\n$PhysicalNames\n2\n1 1 \"edge\"\n2 2 \"film\"\n$EndPhysicalNames\n";
  w.out += "$Entities\n";
  w.S(2), w.S(1), w.S(1), w.S(0);
  w.I(1), w.D(0), w.D(0), w.D(0), w.S(0);
  w.I(2), w.D(1), w.D(0), w.D(0), w.S(0);
  w.I(1);
  for (double x : {0., 0., 0., 1., 0., 0.}) w.D(x);
  w.S(1), w.I(1), w.S(2), w.I(1), w.I(-2);
  w.I(1);
  for (double x : {0., 0., 0., 1., 1., 0.}) w.D(x);
  w.S(1), w.I(2), w.S(1), w.I(1);
  w.out += "\n$EndEntities\n$Nodes\n";
  w.S(1), w.S(4), w.S(1), w.S(4);
  w.I(2), w.I(1), w.I(0), w.S(4);
  for (int t = 1; t <= 4; ++t) w.S((uint64_t)t);
  for (double x : {0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0.}) w.D(x);
  w.out += "\n$EndNodes\n$Elements\n";
  w.S(2), w.S(3), w.S(1), w.S(3);
  w.I(1), w.I(1), w.I(1), w.S(1);
  w.S(1), w.S(1), w.S(2);
  w.I(2), w.I(1), w.I(2), w.S(2);
  w.S(2), w.S(1), w.S(2), w.S(3);
  w.S(3), w.S(1), w.S(3), w.S(4);
  w.out += "\n$EndElements\n";
  return w.out;
}

void TestBinary() {
  MeshData ascii, native, swapped;
  std::string err;
  CHECK(etfe::ReadGmshBuffer(kSmall, "small.msh", &ascii, &err), "%s", err.c_str());
  const std::string bin = BinarySmall(false);
  CHECK(etfe::ReadGmshBuffer(bin, "bin.msh", &native, &err), "binary: %s", err.c_str());
  CHECK(etfe::ReadGmshBuffer(BinarySmall(true), "swapped.msh", &swapped, &err), "swapped: %s",
        err.c_str());
  CHECK(SameMesh(ascii, native), "binary differs from ASCII");
  CHECK(SameMesh(ascii, swapped), "byte-swapped binary differs from ASCII");
  CheckTruncations(bin, "binary");
  std::string bad_marker = bin;
  bad_marker[bad_marker.find("4.1 1 8\n") + 8] = 2;
  ExpectFailure(bad_marker, 3, "endianness", "binary marker 2");
  std::string bad_size = bin;
  bad_size.replace(bad_size.find("4.1 1 8"), 7, "4.1 1 2");
  ExpectFailure(bad_size, 2, "data size 2", "binary data size 2");
}

void TestShippedMeshes(const std::string &dir) {
  MeshData v4, v2;
  std::string err;
  const std::string p4 = dir + "/square_groups.msh", p2 = dir + "/square_groups_v2.msh";
  CHECK(etfe::ReadGmshFile(p4, &v4, &err), "%s", err.c_str());
  CHECK(etfe::ReadGmshFile(p2, &v2, &err), "%s", err.c_str());
  CheckSquare(v4, "MSH 4.1");
  CheckSquare(v2, "MSH 2.2");
  CHECK(SameMesh(v4, v2), "the 4.1 and 2.2 files read differently");
  CHECK(v4.source == p4, "source is '%s'", v4.source.c_str());
  CheckTruncations(Slurp(p4), "square_groups.msh");
  CheckTruncations(Slurp(p2), "square_groups_v2.msh");
  MeshData none;
  CHECK(!etfe::ReadGmshFile(dir + "/no_such_file.msh", &none, &err) &&
            Contains(err, "no_such_file.msh"),
        "missing file: %s", err.c_str());
}

void RoundTrip(const MeshData &m, const std::string &what) {
  const std::string path = "test_gmsh_reader_" + what + ".msh";
  std::string err;
  CHECK(etfe::WriteGmshFile(path, m, &err), "%s: %s", what.c_str(), err.c_str());
  MeshData back;
  CHECK(etfe::ReadGmshFile(path, &back, &err), "%s: %s", what.c_str(), err.c_str());
  CHECK(SameMesh(m, back), "%s: the round trip changed the mesh", what.c_str());
  // Writing what was read gives the same bytes: the layout is a function of the data.
  const std::string first = Slurp(path);
  CHECK(etfe::WriteGmshFile(path, back, &err), "%s: %s", what.c_str(), err.c_str());
  CHECK(Slurp(path) == first, "%s: rewriting changed the file", what.c_str());
  std::remove(path.c_str());
}

void TestRoundTrip(const std::string &dir) {
  MeshData square;
  std::string err;
  CHECK(etfe::ReadGmshFile(dir + "/square_groups.msh", &square, &err), "%s", err.c_str());
  RoundTrip(square, "square");

  // A 3x3 grid of nodes, 8 triangles, with overlapping and interleaved element sets, a node set
  // that goes beyond its element set, a node in several sets and empty sets.
  MeshData g;
  g.source = "grid";
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) g.coords.insert(g.coords.end(), {0.1 * i, 1.0 / 3 * j, 0.0});
  }
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 2; ++i) {
      const int a = 3 * j + i;
      g.triangles.insert(g.triangles.end(), {a, a + 1, a + 4, a, a + 4, a + 3});
    }
  }
  g.element_sets["a"] = {0, 1, 2, 5};
  g.element_sets["b"] = {2, 3, 7};
  g.element_sets["none"] = {};
  g.node_sets["a"] = {0, 1, 2, 3, 4, 5, 6, 7, 8};  // the nodes of element set a, plus 8
  g.node_sets["b"] = {1, 2, 4, 5, 7, 8};           // exactly the nodes of element set b
  g.node_sets["none"] = {};
  g.node_sets["edge"] = {0, 1, 2};
  g.node_sets["corner"] = {0};
  g.node_sets["empty"] = {};
  g.node_sets["name with spaces"] = {8};
  CHECK(etfe::MeshCheck(g, 1e-9, &err), "grid: %s", err.c_str());
  RoundTrip(g, "grid");

  MeshData bad = g;
  bad.triangles[4] = 99;
  CHECK(!etfe::WriteGmshFile("test_gmsh_reader_bad.msh", bad, &err) && Contains(err, "node 99"),
        "writer accepted a bad node id: %s", err.c_str());
  bad = g;
  bad.node_sets["quote\"d"] = {0};
  CHECK(!etfe::WriteGmshFile("test_gmsh_reader_bad.msh", bad, &err) && Contains(err, "quote"),
        "writer accepted a quote in a name: %s", err.c_str());
  CHECK(!etfe::WriteGmshFile("no_such_dir/x.msh", g, &err) && Contains(err, "no_such_dir"),
        "writer into a missing directory: %s", err.c_str());
}

MeshData TwoTriangles() {
  MeshData m;
  m.source = "two.msh";
  m.coords = {0, 0, 0, 1000, 0, 0, 0, 1000, 0, 500, 0, 0};
  m.triangles = {0, 1, 2, 0, 3, 1};  // element 1 lies on the X axis: zero area
  m.node_sets["bottom"] = {0, 1, 3};
  return m;
}

void ExpectCheckFailure(const MeshData &m, double min_area, const std::vector<std::string> &parts,
                        const std::string &what) {
  std::string err;
  const bool ok = etfe::MeshCheck(m, min_area, &err);
  std::printf("  %-28s -> %s\n", what.c_str(), err.c_str());
  CHECK(!ok, "%s: passed", what.c_str());
  CHECK(err.compare(0, m.source.size() + 2, m.source + ": ") == 0, "%s: no source in: %s",
        what.c_str(), err.c_str());
  for (const std::string &p : parts) {
    CHECK(Contains(err, p), "%s: expected '%s' in: %s", what.c_str(), p.c_str(), err.c_str());
  }
}

void TestMeshCheck() {
  std::printf("MeshCheck:\n");
  MeshData m = TwoTriangles();
  ExpectCheckFailure(m, 1e-6, {"element 1 ", "nodes 0 3 1", "area 0 ", "-mesh_min_area"},
                     "zero-area triangle");
  m.coords[3 * 3 + 1] = -1;  // now element 1 has area 500 mm^2
  std::string err;
  CHECK(etfe::MeshCheck(m, 1e-6, &err), "%s", err.c_str());
  ExpectCheckFailure(m, 600, {"element 1 ", "area 500 "}, "area below min_area");
  MeshData nan = m;
  nan.coords[3 * 2 + 1] = std::nan("");
  ExpectCheckFailure(nan, 1e-6, {"node 2 ", "non-finite"}, "NaN coordinate");
  MeshData inf = m;
  inf.coords[0] = INFINITY;
  ExpectCheckFailure(inf, 1e-6, {"node 0 ", "non-finite"}, "infinite coordinate");
  MeshData range = m;
  range.triangles[5] = 4;
  ExpectCheckFailure(range, 1e-6, {"element 1 ", "node 4"}, "node id out of range");
  MeshData neg = m;
  neg.triangles[0] = -1;
  ExpectCheckFailure(neg, 1e-6, {"element 0 ", "node -1"}, "negative node id");
  MeshData rep = m;
  rep.triangles[5] = 0;
  ExpectCheckFailure(rep, 1e-6, {"element 1 ", "repeats a node"}, "repeated node");
  MeshData unused = m;
  unused.coords.insert(unused.coords.end(), {5, 5, 0, 6, 6, 0});
  ExpectCheckFailure(unused, 1e-6, {"node 4 (and 1 more)", "not used"}, "unused nodes");
  MeshData set = m;
  set.node_sets["bottom"].push_back(7);
  ExpectCheckFailure(set, 1e-6, {"node set 'bottom'", "node 7"}, "node set out of range");
  MeshData eset = m;
  eset.element_sets["film"] = {0, 2};
  ExpectCheckFailure(eset, 1e-6, {"element set 'film'", "element 2"}, "element set out of range");
  MeshData unsorted = m;
  unsorted.node_sets["bottom"] = {3, 0};
  ExpectCheckFailure(unsorted, 1e-6, {"not sorted"}, "unsorted node set");
  MeshData ragged = m;
  ragged.coords.pop_back();
  ExpectCheckFailure(ragged, 1e-6, {"not 3 per node"}, "ragged coords");
  MeshData empty;
  empty.source = "empty";
  ExpectCheckFailure(empty, 1e-6, {"no triangles"}, "no triangles");
}

// A 2 x 2 grid of unit-free cells (nodes 0..8, node i + 3 j at (i, j)), 8 counter-clockwise
// triangles, with file tags 1..9 and 11..18 as a reader would keep them.
MeshData Grid() {
  MeshData m;
  m.source = "grid.msh";
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) m.coords.insert(m.coords.end(), {100.0 * i, 100.0 * j, 0.0});
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const int a = i + 3 * j, b = a + 1, c = b + 3, d = a + 3;
      m.triangles.insert(m.triangles.end(), {a, b, c, a, c, d});
    }
  for (int i = 0; i < 9; ++i) m.node_tags.push_back(i + 1);
  for (int e = 0; e < 8; ++e) m.element_tags.push_back(e + 11);
  return m;
}

void TestTopology() {
  std::printf("topology:\n");
  std::string err;
  MeshData good = Grid();
  CHECK(etfe::MeshCheck(good, 1e-6, &err), "grid: %s", err.c_str());
  MeshData crack = Grid();  // node 9 on node 4, used by the right column
  crack.coords.insert(crack.coords.end(), {100.0, 100.0, 1e-9});
  for (int e = 2; e < 4; ++e)
    for (int k = 0; k < 3; ++k)
      if (crack.triangles[3 * e + k] == 4) crack.triangles[3 * e + k] = 9;
  crack.node_tags.push_back(42);
  ExpectCheckFailure(crack, 1e-6,
                     {"node 4 (tag 5 in the file) and node 9 (tag 42", "coincide", "crack"},
                     "coincident nodes");
  MeshData twice = Grid();
  twice.triangles.insert(twice.triangles.end(), {4, 5, 8});
  twice.element_tags.push_back(99);
  ExpectCheckFailure(twice, 1e-6, {"element 8 (tag 99 in the file)", "same triangle"},
                     "duplicated triangle");
  MeshData fin = Grid();
  fin.coords.insert(fin.coords.end(), {50.0, 50.0, 80.0});
  fin.triangles.insert(fin.triangles.end(), {1, 4, 9});
  ExpectCheckFailure(
      fin, 1e-6, {"edge between node 1", "node 4", "three or more triangles (3: ", "non-manifold"},
      "non-manifold edge");
  MeshData mixed = Grid();
  for (int e : {1, 4, 6}) std::swap(mixed.triangles[3 * e + 1], mixed.triangles[3 * e + 2]);
  ExpectCheckFailure(mixed, 1e-6, {"run the same way", "orientation"}, "mixed orientation");
  CHECK(etfe::MeshOrient(&mixed, &err), "orient: %s", err.c_str());
  CHECK(mixed.triangles == Grid().triangles,
        "orient: the three clockwise triangles are flipped back");
  CHECK(mixed.notes.size() == 1 && Contains(mixed.notes[0], "flipped 3 of 8"), "orient: note");
  CHECK(etfe::MeshCheck(mixed, 1e-6, &err), "oriented: %s", err.c_str());
  MeshData majority = Grid();  // five of eight clockwise: the majority wins, three are flipped
  for (int e : {0, 2, 3, 5, 7})
    std::swap(majority.triangles[3 * e + 1], majority.triangles[3 * e + 2]);
  CHECK(etfe::MeshOrient(&majority, &err) && Contains(majority.notes.at(0), "flipped 3 of 8"),
        "orient: the majority decides");
  MeshData tie = Grid();  // four of eight clockwise: no majority, refused (nothing flipped)
  for (int e : {0, 2, 5, 7}) std::swap(tie.triangles[3 * e + 1], tie.triangles[3 * e + 2]);
  const std::vector<int> tied = tie.triangles;
  CHECK(!etfe::MeshOrient(&tie, &err) && Contains(err, "4 triangles oriented like that one") &&
            Contains(err, "4 the other way") && Contains(err, "split evenly") && Contains(err, "Reverse Surface"),
        "orient: an even split is refused: %s", err.c_str());
  CHECK(tie.triangles == tied && tie.notes.empty(), "orient: an even split is left as it was");
  MeshData same = Grid();
  CHECK(etfe::MeshOrient(&same, &err) && same.notes.empty(), "orient: nothing to do, no note");
  // A Moebius strip: a band of 4 quads (8 triangles) closed with a half twist.
  MeshData moebius;
  moebius.source = "moebius.msh";
  const int n = 4;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * M_PI * i / n, w = 0.3 * std::cos(t / 2), h = 0.3 * std::sin(t / 2);
    for (int s : {-1, 1}) {
      moebius.coords.insert(moebius.coords.end(),
                            {(1 + s * w) * std::cos(t), (1 + s * w) * std::sin(t), s * h});
    }
  }
  for (int i = 0; i < n; ++i) {
    const int a = 2 * i, b = 2 * i + 1;
    int c = 2 * ((i + 1) % n), d = c + 1;
    if (i == n - 1) std::swap(c, d);  // the half twist
    moebius.triangles.insert(moebius.triangles.end(), {a, c, d, a, d, b});
  }
  MeshData mb = moebius;
  CHECK(!etfe::MeshOrient(&mb, &err) && Contains(err, "cannot be oriented"), "moebius: %s",
        err.c_str());
}

} // namespace

int main(int argc, char **argv) {
  const std::string dir = argc > 1 ? argv[1] : "meshes";
  TestShippedMeshes(dir);
  TestRoundTrip(dir);
  TestBinary();
  TestDamagedInputs();
  TestMeshCheck();
  TestTopology();
  TEST_MAIN_END();
}
