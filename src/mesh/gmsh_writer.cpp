// Gmsh MSH 4.1 ASCII writer for MeshData (form finding hands its surface to the stretch scenes
// this way). Writes only what keeps the file self-consistent; quality checks are MeshCheck's.
#include <charconv>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "etfe/mesh/gmsh_reader.h"
#include "gmsh_tokenizer.h"

namespace etfe {
namespace {

using gmsh::Quote;
using gmsh::Str;

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
  for (const auto &s : mesh.line_sets) {
    if (s.first.empty() || s.first.find_first_of("\"\n\r") != std::string::npos || s.second.size() % 2 != 0)
      return WriteFail(path, mesh, "line set " + Quote(s.first) + " has a bad name or an odd number of node ids", err);
    for (int v : s.second)
      if (v < -1 || v >= (long long)nn)
        return WriteFail(path, mesh, "line set " + Quote(s.first) + " holds node " + Str((long long)v) + ", out of range",
                         err);
  }
  return true;
}

// Layout: all nodes in one block on surface entity 1. Triangles go to one surface entity per
// distinct combination of element sets (a triangle can only sit on one entity), written in runs
// so that the file keeps the triangle order. A node set is the node set of the element set with
// the same name (the reader derives it) plus, for the nodes that adds, a 0-D physical group of
// the same name carried by one point entity per node, as Gmsh itself models points.
struct GmshLayout {
  // 2-D physical tags 1..E for the element sets, then 1-D tags for the line sets (one curve
  // entity each, tag 1..C in their order), then 0-D tags for the node sets that need them.
  std::vector<std::pair<long long, const std::string *>> phys2, phys1, phys0;
  std::vector<const std::vector<int> *> curves;  // curve entity - 1 -> its segments (2 node ids each)
  std::vector<std::vector<long long>> tri_groups;      // triangle -> 2-D physical tags
  std::map<int, std::vector<long long>> point_groups;  // node -> 0-D physical tags
  // Surface entities 1..S: one per distinct group combination, in order of first use.
  std::map<std::vector<long long>, long long> surface_of;
  std::vector<const std::vector<long long> *> surface_groups;  // entity - 1 -> its groups
  std::vector<long long> tri_surface;                          // triangle -> its entity
  std::vector<double> box;                                     // entity - 1 -> min xyz, max xyz
};

void PhysicalGroups(const MeshData &mesh, GmshLayout *g) {
  const size_t nn = mesh.coords.size() / 3, ne = mesh.triangles.size() / 3;
  g->tri_groups.assign(ne, {});
  for (const auto &s : mesh.element_sets) {
    const long long tag = (long long)g->phys2.size() + 1;
    g->phys2.emplace_back(tag, &s.first);
    for (int e : s.second) {
      if (g->tri_groups[(size_t)e].empty() || g->tri_groups[(size_t)e].back() != tag) {
        g->tri_groups[(size_t)e].push_back(tag);
      }
    }
  }
  // Line sets (cables run along them): a 1-D group on one curve entity; its nodes need no points.
  for (const auto &s : mesh.line_sets) {
    g->phys1.emplace_back((long long)(g->phys2.size() + g->phys1.size()) + 1, &s.first);
    g->curves.push_back(&s.second);
  }
  for (const auto &s : mesh.node_sets) {
    std::vector<char> covered;
    const auto es = mesh.element_sets.find(s.first);
    if (es != mesh.element_sets.end()) {
      covered.assign(nn, 0);
      for (int e : es->second) {
        for (int k = 0; k < 3; ++k) covered[(size_t)mesh.triangles[3 * (size_t)e + k]] = 1;
      }
    }
    const auto ls = mesh.line_sets.find(s.first);
    if (ls != mesh.line_sets.end()) {
      if (covered.empty()) covered.assign(nn, 0);
      for (int v : ls->second)
        if (v >= 0) covered[(size_t)v] = 1;
    }
    std::vector<int> extra;
    for (int v : s.second) {
      if (covered.empty() || !covered[(size_t)v]) extra.push_back(v);
    }
    // An empty node set without an element set is kept as a named group with no entity.
    if (extra.empty() && !(s.second.empty() && es == mesh.element_sets.end())) continue;
    const long long tag = (long long)(g->phys2.size() + g->phys1.size() + g->phys0.size()) + 1;
    g->phys0.emplace_back(tag, &s.first);
    for (int v : extra) {
      std::vector<long long> &groups = g->point_groups[v];
      if (groups.empty() || groups.back() != tag) groups.push_back(tag);
    }
  }
}

// The surface entities of the triangles' group combinations and their bounding boxes.
void SurfaceEntities(const MeshData &mesh, GmshLayout *g) {
  const size_t ne = mesh.triangles.size() / 3;
  g->tri_surface.assign(ne, 0);
  for (size_t e = 0; e < ne; ++e) {
    const auto ins = g->surface_of.emplace(g->tri_groups[e], (long long)g->surface_groups.size() + 1);
    if (ins.second) g->surface_groups.push_back(&ins.first->first);
    g->tri_surface[e] = ins.first->second;
  }
  static const std::vector<long long> kNoGroups;
  if (g->surface_groups.empty()) g->surface_groups.push_back(&kNoGroups);  // to carry the nodes
  const size_t nsurf = g->surface_groups.size();
  g->box.assign(6 * nsurf, 0.0);
  std::vector<char> box_set(nsurf, 0);
  for (size_t e = 0; e < ne; ++e) {
    const size_t s = (size_t)g->tri_surface[e] - 1;
    for (int k = 0; k < 3; ++k) {
      const double *x = &mesh.coords[3 * (size_t)mesh.triangles[3 * e + k]];
      for (int c = 0; c < 3; ++c) {
        if (!box_set[s] || x[c] < g->box[6 * s + c]) g->box[6 * s + c] = x[c];
        if (!box_set[s] || x[c] > g->box[6 * s + 3 + c]) g->box[6 * s + 3 + c] = x[c];
      }
      box_set[s] = 1;
    }
  }
}

void AppendPhysicalNames(const GmshLayout &g, std::string *out) {
  *out += "$PhysicalNames\n";
  Line(out, (long long)(g.phys0.size() + g.phys1.size() + g.phys2.size()));
  for (const auto &p : g.phys0) {
    Line(out, 0LL, p.first, ("\"" + *p.second + "\"").c_str());
  }
  for (const auto &p : g.phys1) {
    Line(out, 1LL, p.first, ("\"" + *p.second + "\"").c_str());
  }
  for (const auto &p : g.phys2) {
    Line(out, 2LL, p.first, ("\"" + *p.second + "\"").c_str());
  }
  *out += "$EndPhysicalNames\n";
}

void AppendEntities(const MeshData &mesh, const GmshLayout &g, std::string *out) {
  const size_t nsurf = g.surface_groups.size();
  *out += "$Entities\n";
  Line(out, (long long)g.point_groups.size(), (long long)g.curves.size(), (long long)nsurf, 0LL);
  long long point_tag = 0;
  for (const auto &pg : g.point_groups) {
    const double *x = &mesh.coords[3 * (size_t)pg.first];
    Append(out, ++point_tag);
    for (int c = 0; c < 3; ++c) Field(out, x[c]);
    Field(out, (long long)pg.second.size());
    for (long long t : pg.second) Field(out, t);
    *out += '\n';
  }
  for (size_t c = 0; c < g.curves.size(); ++c) {
    double box[6] = {0, 0, 0, 0, 0, 0};
    bool first = true;
    for (int v : *g.curves[c]) {
      if (v < 0) continue;
      for (int k = 0; k < 3; ++k) {
        const double x = mesh.coords[3 * (size_t)v + k];
        if (first || x < box[k]) box[k] = x;
        if (first || x > box[3 + k]) box[3 + k] = x;
      }
      first = false;
    }
    Append(out, (long long)c + 1);
    for (int k = 0; k < 6; ++k) Field(out, box[k]);
    Line(out, "", 1LL, g.phys1[c].first, 0LL);  // one physical group, no bounding points
  }
  for (size_t s = 0; s < nsurf; ++s) {
    Append(out, (long long)s + 1);
    for (int c = 0; c < 6; ++c) Field(out, g.box[6 * s + c]);
    Field(out, (long long)g.surface_groups[s]->size());
    for (long long t : *g.surface_groups[s]) Field(out, t);
    *out += " 0\n";  // no bounding curves: a discrete surface
  }
  *out += "$EndEntities\n";
}

void AppendNodes(const MeshData &mesh, std::string *out) {
  const size_t nn = mesh.coords.size() / 3;
  *out += "$Nodes\n";
  Line(out, 1LL, (long long)nn, nn ? 1LL : 0LL, (long long)nn);
  Line(out, 2LL, 1LL, 0LL, (long long)nn);
  for (size_t i = 0; i < nn; ++i) Line(out, (long long)i + 1);
  for (size_t i = 0; i < nn; ++i) {
    Line(out, mesh.coords[3 * i], mesh.coords[3 * i + 1], mesh.coords[3 * i + 2]);
  }
  *out += "$EndNodes\n";
}

// The triangles in runs of one surface entity, then one point element per point entity.
void AppendElements(const MeshData &mesh, const GmshLayout &g, std::string *out) {
  const size_t ne = mesh.triangles.size() / 3;
  *out += "$Elements\n";
  size_t nruns = 0;
  for (size_t e = 0; e < ne; ++e) nruns += (e == 0 || g.tri_surface[e] != g.tri_surface[e - 1]);
  // A line segment with a node the mesh lacks (the reader's -1) cannot be written: left out.
  std::vector<size_t> nseg(g.curves.size(), 0);
  size_t nlines = 0;
  for (size_t c = 0; c < g.curves.size(); ++c) {
    for (size_t k = 0; k + 1 < g.curves[c]->size(); k += 2)
      nseg[c] += (*g.curves[c])[k] >= 0 && (*g.curves[c])[k + 1] >= 0;
    nlines += nseg[c];
  }
  size_t nblocks_1d = 0;
  for (size_t n : nseg) nblocks_1d += n > 0;
  const size_t nelem = ne + g.point_groups.size() + nlines;
  Line(out, (long long)(nruns + g.point_groups.size() + nblocks_1d), (long long)nelem, nelem ? 1LL : 0LL,
       (long long)nelem);
  for (size_t e = 0; e < ne;) {
    size_t end = e;
    while (end < ne && g.tri_surface[end] == g.tri_surface[e]) ++end;
    Line(out, 2LL, g.tri_surface[e], 2LL, (long long)(end - e));
    for (; e < end; ++e) {
      Line(out, (long long)e + 1, (long long)mesh.triangles[3 * e] + 1,
           (long long)mesh.triangles[3 * e + 1] + 1, (long long)mesh.triangles[3 * e + 2] + 1);
    }
  }
  long long elem_tag = (long long)ne, point_tag = 0;
  for (const auto &pg : g.point_groups) {
    Line(out, 0LL, ++point_tag, 15LL, 1LL);
    Line(out, ++elem_tag, (long long)pg.first + 1);
  }
  for (size_t c = 0; c < g.curves.size(); ++c) {
    if (!nseg[c]) continue;
    Line(out, 1LL, (long long)c + 1, 1LL, (long long)nseg[c]);
    const std::vector<int> &l = *g.curves[c];
    for (size_t k = 0; k + 1 < l.size(); k += 2)
      if (l[k] >= 0 && l[k + 1] >= 0) Line(out, ++elem_tag, (long long)l[k] + 1, (long long)l[k + 1] + 1);
  }
  *out += "$EndElements\n";
}

bool WriteWholeFile(const std::string &path, const std::string &out, std::string *err) {
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

} // namespace

bool WriteGmshFile(const std::string &path, const MeshData &mesh, std::string *err) {
  if (!WriterCheck(path, mesh, err)) return false;
  GmshLayout layout;
  PhysicalGroups(mesh, &layout);
  SurfaceEntities(mesh, &layout);
  std::string out;
  out.reserve(64 * (mesh.coords.size() / 3 + mesh.triangles.size() / 3) + 4096);
  out += "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
  AppendPhysicalNames(layout, &out);
  AppendEntities(mesh, layout, &out);
  AppendNodes(mesh, &out);
  AppendElements(mesh, layout, &out);
  return WriteWholeFile(path, out, err);
}

} // namespace etfe
