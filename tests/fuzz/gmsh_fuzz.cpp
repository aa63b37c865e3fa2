// gmsh_fuzz: a deterministic mutation fuzzer for the Gmsh MSH reader, meant to be built with
// -fsanitize=address,undefined so that any crash, overflow or leak on damaged input shows up.
// It mutates the seed files (plus a built-in binary MSH 4.1 seed, so the binary paths are
// exercised without shipping a binary file), runs ReadGmshBuffer and, on success, MeshCheck, and
// checks what the reader promises: a rejected input gets "<name>:<line>: ...", an accepted one
// gives a mesh whose ids and sets are in range.
//
// Usage: gmsh_fuzz <seed-file>... [--iterations N] [--seed S] [--write I FILE]
//   --write I FILE  writes the input of iteration I to FILE and exits (to reproduce a report).
// Each iteration draws its own generator state from (S, iteration), so iteration I is the same
// input whatever N is.
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "etfe/mesh/gmsh_reader.h"

namespace {

// SplitMix64: tiny, fast and the same on every platform, which std:: distributions are not.
struct Rng {
  uint64_t s;
  uint64_t Next() {
    uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  size_t Below(size_t n) { return n == 0 ? 0 : (size_t)(Next() % n); }
  bool OneIn(size_t n) { return Below(n) == 0; }
};

// Values that sit on the limits a parser has to get right.
const char *const kExtremes[] = {
    "0", "-1", "1", "2147483647", "2147483648", "-2147483649", "4294967296", "1099511627776",
    "9223372036854775807", "9223372036854775808", "18446744073709551615",
    "18446744073709551616", "1000000000000", "1e308", "-1e308", "1e999", "1e-400", "nan", "inf",
    "-inf", "-0", "1.2.3", "0x10", "+", "-", "", "\"", "$EndNodes", "$Elements",
    "99999999999999999999999999999999999999999999999999999999999999999999999999999999"};

std::string HugeString(Rng *rng) {
  const char fill[] = {'9', '1', 'a', ' ', '\n', '$', '"'};
  return std::string(1 + rng->Below(4096), fill[rng->Below(sizeof fill)]);
}

bool IsSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

// Whitespace-separated token around a random position that looks like a number.
bool PickNumber(const std::string &s, Rng *rng, size_t *b, size_t *e) {
  for (int attempt = 0; attempt < 16 && !s.empty(); ++attempt) {
    size_t p = rng->Below(s.size());
    if (IsSpace(s[p])) continue;
    *b = p;
    *e = p;
    while (*b > 0 && !IsSpace(s[*b - 1])) --*b;
    while (*e < s.size() && !IsSpace(s[*e])) ++*e;
    const char c = s[*b];
    if ((c >= '0' && c <= '9') || c == '-' || c == '.') return true;
  }
  return false;
}

// [start, end) of each line, newline included.
std::vector<std::pair<size_t, size_t>> LineSpans(const std::string &s) {
  std::vector<std::pair<size_t, size_t>> out;
  size_t start = 0;
  while (start < s.size()) {
    size_t nl = s.find('\n', start);
    const size_t end = nl == std::string::npos ? s.size() : nl + 1;
    out.emplace_back(start, end);
    start = end;
  }
  return out;
}

// [start, end) of each "$Name ... $EndName\n" section.
std::vector<std::pair<size_t, size_t>> SectionSpans(const std::string &s) {
  std::vector<std::pair<size_t, size_t>> out;
  size_t p = 0;
  while ((p = s.find('$', p)) != std::string::npos) {
    if (s.compare(p, 4, "$End") == 0) {
      ++p;
      continue;
    }
    size_t name_end = p + 1;
    while (name_end < s.size() && !IsSpace(s[name_end])) ++name_end;
    const std::string end_tag = "$End" + s.substr(p + 1, name_end - p - 1);
    size_t q = s.find(end_tag, name_end);
    if (q == std::string::npos) break;
    q += end_tag.size();
    if (q < s.size() && s[q] == '\n') ++q;
    out.emplace_back(p, q);
    p = q;
  }
  return out;
}

void Mutate(std::string *s, const std::vector<std::string> &seeds, Rng *rng) {
  const size_t n = s->size();
  switch (rng->Below(12)) {
    case 0:  // flip a bit
      if (n) (*s)[rng->Below(n)] ^= (char)(1u << rng->Below(8));
      break;
    case 1:  // overwrite a byte, often with one that means something to the parser
      if (n) {
        const char interesting[] = {'\n', ' ', '$', '-', '9', '0', '"', '.', 'e', '\0', '\r'};
        (*s)[rng->Below(n)] =
            rng->OneIn(2) ? interesting[rng->Below(sizeof interesting)] : (char)rng->Next();
      }
      break;
    case 2: {  // insert bytes
      std::string ins(1 + rng->Below(8), '\0');
      for (char &c : ins) {
        c = rng->OneIn(2) ? "0123456789 \n-.$"[rng->Below(15)] : (char)rng->Next();
      }
      s->insert(rng->Below(n + 1), ins);
      break;
    }
    case 3:  // delete bytes
      if (n) {
        const size_t p = rng->Below(n);
        s->erase(p, 1 + rng->Below(16));
      }
      break;
    case 4:  // truncate
      s->resize(rng->Below(n + 1));
      break;
    case 5:
    case 6: {  // replace a number with an extreme value or a huge string
      size_t b, e;
      if (!PickNumber(*s, rng, &b, &e)) break;
      const size_t k = sizeof kExtremes / sizeof kExtremes[0];
      const std::string v = rng->OneIn(8) ? HugeString(rng) : kExtremes[rng->Below(k)];
      s->replace(b, e - b, v);
      break;
    }
    case 7: {  // change a number by a little: off-by-one counts and tags
      size_t b, e;
      if (!PickNumber(*s, rng, &b, &e)) break;
      const long long v = std::strtoll(s->substr(b, e - b).c_str(), nullptr, 10);
      const long long d = rng->OneIn(2) ? 1 : -1;
      s->replace(b, e - b, std::to_string(v > LLONG_MIN + 1 && v < LLONG_MAX - 1 ? v + d : 0));
      break;
    }
    case 8: {  // duplicate a line
      const auto lines = LineSpans(*s);
      if (lines.empty()) break;
      const auto l = lines[rng->Below(lines.size())];
      s->insert(l.first, s->substr(l.first, l.second - l.first));
      break;
    }
    case 9: {  // delete a line
      const auto lines = LineSpans(*s);
      if (lines.empty()) break;
      const auto l = lines[rng->Below(lines.size())];
      s->erase(l.first, l.second - l.first);
      break;
    }
    case 10: {  // swap two sections, or drop one
      const auto secs = SectionSpans(*s);
      if (secs.size() < 2) break;
      size_t i = rng->Below(secs.size()), j = rng->Below(secs.size());
      if (i > j) std::swap(i, j);
      const auto a = secs[i], b = secs[j];
      if (i == j) {
        s->erase(a.first, a.second - a.first);
        break;
      }
      const std::string sa = s->substr(a.first, a.second - a.first);
      const std::string sb = s->substr(b.first, b.second - b.first);
      s->replace(b.first, b.second - b.first, sa);  // the later one first keeps a's offsets
      s->replace(a.first, a.second - a.first, sb);
      break;
    }
    default: {  // splice in a piece of another seed
      const std::string &o = seeds[rng->Below(seeds.size())];
      if (o.empty()) break;
      const size_t b = rng->Below(o.size());
      const std::string piece = o.substr(b, 1 + rng->Below(256));
      s->insert(rng->Below(n + 1), piece);
      break;
    }
  }
}

// A binary MSH 4.1 file: two triangles, a named line group and a named surface group.
std::string BinarySeed() {
  std::string out = "$MeshFormat\n4.1 1 8\n";
  auto raw = [&out](const void *p, size_t n) { out.append((const char *)p, n); };
  auto i32 = [&](int32_t v) { raw(&v, 4); };
  auto u64 = [&](uint64_t v) { raw(&v, 8); };
  auto f64 = [&](double v) { raw(&v, 8); };
  i32(1);
  out += "\n$EndMeshFormat\n$PhysicalNames\n2\n1 1 \"edge\"\n2 2 \"film\"\n$EndPhysicalNames\n";
  out += "$Entities\n";
  u64(2), u64(1), u64(1), u64(0);
  i32(1), f64(0), f64(0), f64(0), u64(0);
  i32(2), f64(1), f64(0), f64(0), u64(0);
  i32(1);
  for (double x : {0., 0., 0., 1., 0., 0.}) f64(x);
  u64(1), i32(1), u64(2), i32(1), i32(-2);
  i32(1);
  for (double x : {0., 0., 0., 1., 1., 0.}) f64(x);
  u64(1), i32(2), u64(1), i32(1);
  out += "\n$EndEntities\n$Nodes\n";
  u64(1), u64(4), u64(1), u64(4);
  i32(2), i32(1), i32(0), u64(4);
  for (int t = 1; t <= 4; ++t) u64((uint64_t)t);
  for (double x : {0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0.}) f64(x);
  out += "\n$EndNodes\n$Elements\n";
  u64(2), u64(3), u64(1), u64(3);
  i32(1), i32(1), i32(1), u64(1);
  u64(1), u64(1), u64(2);
  i32(2), i32(1), i32(2), u64(2);
  u64(2), u64(1), u64(2), u64(3);
  u64(3), u64(1), u64(3), u64(4);
  out += "\n$EndElements\n";
  return out;
}

// Quadrangles beside triangles, one clockwise triangle and an MSH 2.2 repeat record, so that the
// quad split, the orientation repair and the group bookkeeping of split elements are mutated too.
std::string QuadSeed() {
  return "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n1 1 \"edge\"\n2 2 \"film\"\n"
         "$EndPhysicalNames\n$Nodes\n6\n1 0 0 0\n2 1 0 0\n3 2 0 0\n4 0 1 0\n5 1 1 0\n6 2 1 0\n"
         "$EndNodes\n$Elements\n5\n1 1 2 1 1 1 2\n2 3 2 2 1 1 2 5 4\n3 3 2 3 1 1 2 5 4\n"
         "4 2 2 2 1 2 6 5\n5 2 2 2 1 2 6 3\n$EndElements\n";
}

bool ReadFile(const char *path, std::string *out) {
  std::FILE *f = std::fopen(path, "rb");
  if (!f) return false;
  char b[1 << 16];
  size_t n;
  while ((n = std::fread(b, 1, sizeof b, f)) > 0) out->append(b, n);
  const bool ok = !std::ferror(f);
  std::fclose(f);
  return ok;
}

// What the reader promises; false (with a message) is a bug in the reader.
bool Invariants(bool ok, const std::string &err, const etfe::MeshData &m, std::string *why) {
  if (!ok) {
    const std::string prefix = "fuzz.msh:";
    size_t i = prefix.size();
    while (i < err.size() && err[i] >= '0' && err[i] <= '9') ++i;
    if (err.compare(0, prefix.size(), prefix) != 0 || i == prefix.size() ||
        err.compare(i, 2, ": ") != 0) {
      *why = "rejection without <file>:<line>: " + err.substr(0, 200);
      return false;
    }
    return true;
  }
  const size_t nn = m.coords.size() / 3, ne = m.triangles.size() / 3;
  if (m.coords.size() % 3 || m.triangles.size() % 3 || ne == 0) {
    *why = "accepted mesh with ragged arrays or no triangles";
    return false;
  }
  if (m.node_tags.size() != nn || m.element_tags.size() != ne) {
    *why = "accepted mesh whose file tags do not match its nodes and triangles";
    return false;
  }
  for (double x : m.coords) {
    if (!std::isfinite(x)) {
      *why = "accepted a non-finite coordinate";
      return false;
    }
  }
  std::vector<char> used(nn, 0);
  for (int v : m.triangles) {
    if (v < 0 || (size_t)v >= nn) {
      *why = "accepted a triangle with node " + std::to_string(v);
      return false;
    }
    used[(size_t)v] = 1;
  }
  for (char u : used) {
    if (!u) {
      *why = "kept a node that no triangle uses";
      return false;
    }
  }
  for (int k = 0; k < 2; ++k) {
    const auto &sets = k == 0 ? m.node_sets : m.element_sets;
    const size_t n = k == 0 ? nn : ne;
    for (const auto &s : sets) {
      for (size_t i = 0; i < s.second.size(); ++i) {
        const int v = s.second[i];
        if (v < 0 || (size_t)v >= n || (i > 0 && v <= s.second[i - 1])) {
          *why = "set '" + s.first + "' out of range or not sorted and unique";
          return false;
        }
      }
    }
  }
  return true;
}

} // namespace

int main(int argc, char **argv) {
  std::vector<std::string> seeds;
  long long iterations = 1000;
  unsigned long long seed = 1;
  long long write_iteration = -1;
  const char *write_path = nullptr;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--iterations" && i + 1 < argc) {
      iterations = std::atoll(argv[++i]);
    } else if (a == "--seed" && i + 1 < argc) {
      seed = std::strtoull(argv[++i], nullptr, 10);
    } else if (a == "--write" && i + 2 < argc) {
      write_iteration = std::atoll(argv[++i]);
      write_path = argv[++i];
    } else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr,
                   "usage: gmsh_fuzz <seed-file>... [--iterations N] [--seed S] "
                   "[--write I FILE]\n");
      return 2;
    } else {
      std::string s;
      if (!ReadFile(argv[i], &s)) {
        std::fprintf(stderr, "gmsh_fuzz: cannot read %s\n", argv[i]);
        return 2;
      }
      seeds.push_back(std::move(s));
    }
  }
  seeds.push_back(BinarySeed());
  seeds.push_back(QuadSeed());

  const auto start = std::chrono::steady_clock::now();
  long long accepted = 0, rejected = 0, violations = 0;
  for (long long it = 0; it < iterations || it == write_iteration; ++it) {
    Rng rng{seed * 0x2545F4914F6CDD1Dull ^ (uint64_t)it * 0x9E3779B97F4A7C15ull};
    std::string input = seeds[rng.Below(seeds.size())];
    const size_t mutations = 1 + rng.Below(rng.OneIn(4) ? 16 : 4);
    for (size_t k = 0; k < mutations; ++k) Mutate(&input, seeds, &rng);
    if (it == write_iteration) {
      std::FILE *f = std::fopen(write_path, "wb");
      const bool ok = f && std::fwrite(input.data(), 1, input.size(), f) == input.size();
      if (f) std::fclose(f);
      std::printf("iteration %lld: %zu bytes written to %s\n", it, input.size(), write_path);
      return ok ? 0 : 1;
    }
    etfe::MeshData mesh;
    std::string err, why;
    const bool ok = etfe::ReadGmshBuffer(input, "fuzz.msh", &mesh, &err);
    if (ok) {
      ++accepted;
      std::string check_err;
      // Orientation repair and the topology checks run on whatever the reader accepted; they
      // may refuse (a flattened triangle, a fin): fine, but they must not crash or corrupt.
      etfe::MeshData oriented = mesh;
      if (etfe::MeshOrient(&oriented, &check_err)) etfe::MeshCheck(oriented, 1e-9, &check_err);
      if (oriented.triangles.size() != mesh.triangles.size()) {
        if (violations++ < 10)
          std::printf("iteration %lld: MeshOrient changed the triangle count\n", it);
      }
    } else {
      ++rejected;
    }
    if (!Invariants(ok, err, mesh, &why)) {
      if (violations++ < 10) {
        std::printf("iteration %lld (--seed %llu --write %lld FILE): %s\n", it, seed, it,
                    why.c_str());
      }
    }
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("%lld inputs, %lld accepted, %lld rejected (%.2f s)\n", accepted + rejected,
              accepted, rejected, seconds);
  if (violations) {
    std::printf("%lld inputs broke the reader's promises\n", violations);
    return 1;
  }
  return 0;
}
