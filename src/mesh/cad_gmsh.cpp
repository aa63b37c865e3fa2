// The CAD meshing module (libetfe_cad.so): a STEP, IGES or BREP file meshed by Gmsh's C++ API
// into a MeshData (what comes out: etfe/mesh/cad_reader.h). Built only when CMake finds the
// Gmsh API, and loaded by ReadCadFile (cad_reader.cpp) through its one C entry point, so that
// libgmsh and OpenCASCADE are loaded only by a run that reads a CAD file.
#include <gmsh.h>

#include <algorithm>
#include <cctype>
#include <clocale>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "etfe/mesh/mesh_data.h"

namespace {

constexpr double kDefaultSizeFraction = 1.0 / 50.0;  // of the bounding-box diagonal
// A surface filling its bounding box has about (diagonal / size)^2 triangles: past 2^24 (as for
// the generated meshes) the size is taken for a mistake of unit rather than meshed for hours.
constexpr double kMaxDiagonalOverSize = 4096.0;

// Gmsh initialized for one reading and finalized after it, whatever happens in between; the
// process's locale, which gmsh::initialize changes (LC_CTYPE and others from the environment),
// is restored.
class GmshSession {
public:
  GmshSession() : locale_(std::setlocale(LC_ALL, nullptr)) {
    gmsh::initialize(0, nullptr, false);  // no gmshrc: the same options on every machine
    gmsh::option::setNumber("General.Terminal", 0);
  }
  ~GmshSession() {
    gmsh::finalize();
    std::setlocale(LC_ALL, locale_.c_str());
  }

private:
  std::string locale_;
};

// The last part of a STEP label path "Shapes/<assembly>/<n>/<name>", usable in an option value.
std::string GroupName(const std::string &label) {
  std::string name = label.substr(label.find_last_of('/') + 1);
  for (char &c : name)
    if (!(std::isalnum((unsigned char)c) || c == '_' || c == '.' || c == '-')) c = '_';
  return name;
}

std::string Format(const char *fmt, double a, double b = 0.0) {
  char buf[160];
  std::snprintf(buf, sizeof buf, fmt, a, b);
  return buf;
}

// Imports the file and fuses coincident entities; returns the surface names by their new tags.
std::map<int, std::string> ImportFused(const std::string &path, std::vector<std::string> *notes) {
  gmsh::option::setNumber("Geometry.OCCImportLabels", 1);
  // Gmsh 4.8 sets the target unit before OpenCASCADE's IGES reader has declared that setting, so
  // every IGES file then fails with "Could not set OpenCASCADE target unit"; left unset, the IGES
  // reader converts to OpenCASCADE's default unit, mm (xstep.cascade.unit), all the same.
  const size_t dot = path.find_last_of('.');
  std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
  for (char &c : ext) c = (char)std::tolower((unsigned char)c);
  gmsh::option::setString("Geometry.OCCTargetUnit", ext == "iges" || ext == "igs" ? "" : "MM");
  gmsh::vectorpair imported, fused;
  std::vector<gmsh::vectorpair> map;
  gmsh::model::occ::importShapes(path, imported, false);
  gmsh::model::occ::synchronize();
  // Names of faces, and of solids (a cushion drawn as a closed body), which their faces take.
  std::map<std::pair<int, int>, std::string> before;
  for (int dim : {3, 2}) {
    gmsh::vectorpair ents;
    gmsh::model::getEntities(ents, dim);
    for (const auto &e : ents) {
      std::string label;
      gmsh::model::getEntityName(e.first, e.second, label);
      if (label.empty()) continue;
      if (dim == 2) {
        before[e] = GroupName(label);
        continue;
      }
      gmsh::vectorpair boundary;
      gmsh::model::getBoundary({e}, boundary, false, false, false);
      for (const auto &f : boundary) before.emplace(f, GroupName(label));
    }
  }
  gmsh::vectorpair all, curves;  // getEntities replaces its output
  gmsh::model::getEntities(all, 2);
  const size_t faces = all.size();
  gmsh::model::getEntities(curves, 1);  // free curves too: on a face they become a line of its mesh
  all.insert(all.end(), curves.begin(), curves.end());
  std::map<int, std::string> names;
  if (all.empty()) return names;
  gmsh::model::occ::fragment(all, {}, fused, map);
  gmsh::model::occ::synchronize();
  for (size_t k = 0; k < all.size() && k < map.size(); ++k) {
    auto it = before.find(all[k]);
    if (it == before.end()) continue;
    for (const auto &out : map[k])
      if (out.first == 2) names[out.second] = it->second;
  }
  gmsh::vectorpair now;
  gmsh::model::getEntities(now, 2);
  if (now.size() != faces)
    notes->push_back("the " + std::to_string(faces) + " CAD faces became " + std::to_string(now.size()) +
                     " when Gmsh fused their coincident edges (a curve cut a face)");
  return names;
}

// Meshes the model and copies the triangles and the groups into *mesh.
bool MeshModel(const std::string &path, double size, const std::map<int, std::string> &names,
               etfe::MeshData *mesh, std::string *err) {
  gmsh::option::setNumber("Mesh.MeshSizeMax", size);
  gmsh::option::setNumber("Mesh.MeshSizeMin", 0.0);
  gmsh::option::setNumber("Mesh.MeshSizeFactor", 1.0);
  gmsh::option::setNumber("Mesh.ElementOrder", 1);
  gmsh::option::setNumber("Mesh.RecombineAll", 0);
  gmsh::option::setNumber("Mesh.SubdivisionAlgorithm", 0);
  gmsh::option::setNumber("General.NumThreads", 1);  // the same triangles on every run
  // Gmsh 4.8 throws from inside its OpenMP face-meshing loop on some CAD models (OpenCASCADE's
  // sample bearing.iges): no catch can reach that, the C++ runtime terminates. Say which file
  // and the way out before the process ends, instead of a bare abort and a stack trace.
  static std::string meshing;
  meshing = path;
  const std::terminate_handler previous = std::set_terminate([] {
    std::fprintf(stderr,
                 "etfe: Gmsh failed inside its face meshing of %s and ended the process (an error it cannot "
                 "report back: Gmsh 4.8, some IGES/STEP models). Way out: mesh the file with Gmsh itself "
                 "(gmsh -2 %s -o surface.msh, any Gmsh version) and give -mesh_file surface.msh\n",
                 meshing.c_str(), meshing.c_str());
    std::fflush(stderr);
    std::_Exit(2);
  });
  gmsh::model::mesh::generate(2);
  std::set_terminate(previous);

  std::vector<std::size_t> tags;
  std::vector<double> xyz, param;
  gmsh::model::mesh::getNodes(tags, xyz, param, -1, -1, true, false);
  std::map<std::size_t, int> index;  // Gmsh node tag -> position in xyz
  for (size_t k = 0; k < tags.size(); ++k) index.emplace(tags[k], (int)k);

  std::map<std::size_t, int> used;  // Gmsh node tag -> MeshData node id, in order of first use
  auto node_id = [&](std::size_t tag) {
    auto it = used.find(tag);
    if (it != used.end()) return it->second;
    const int id = (int)used.size(), at = index.at(tag);
    used.emplace(tag, id);
    mesh->coords.insert(mesh->coords.end(), &xyz[3 * at], &xyz[3 * at + 3]);
    mesh->node_tags.push_back((long long)tag);
    return id;
  };
  gmsh::vectorpair faces;
  gmsh::model::getEntities(faces, 2);
  for (const auto &f : faces) {
    std::vector<std::size_t> etags, enodes;
    gmsh::model::mesh::getElementsByType(2, etags, enodes, f.second);
    std::vector<int> set;
    for (size_t e = 0; e < etags.size(); ++e) {
      set.push_back(mesh->NumElements());
      for (int a = 0; a < 3; ++a) mesh->triangles.push_back(node_id(enodes[3 * e + a]));
      mesh->element_tags.push_back((long long)etags[e]);
    }
    // Each face in one element set, so the sets partition the film (cutting patterns take them
    // as strips): its name from the file, else its tag.
    auto named = names.find(f.second);
    std::vector<int> &s =
        mesh->element_sets[named != names.end() ? named->second : "surface_" + std::to_string(f.second)];
    s.insert(s.end(), set.begin(), set.end());
  }
  if (mesh->triangles.empty()) {
    *err = path + ": Gmsh made no triangles of it: does the file hold a surface (a face, shell or solid)?";
    return false;
  }
  // Node sets: each element set's nodes, and each curve's and point's nodes (used ones only).
  for (const auto &es : mesh->element_sets) {
    std::set<int> nodes;
    for (int e : es.second)
      for (int a = 0; a < 3; ++a) nodes.insert(mesh->triangles[3 * e + a]);
    mesh->node_sets[es.first].assign(nodes.begin(), nodes.end());
  }
  for (int dim : {1, 0}) {
    gmsh::vectorpair ents;
    gmsh::model::getEntities(ents, dim);
    for (const auto &c : ents) {
      std::vector<std::size_t> ntags;
      std::vector<double> cxyz, cparam;
      gmsh::model::mesh::getNodes(ntags, cxyz, cparam, dim, c.second, true, false);
      std::set<int> nodes;
      for (std::size_t t : ntags)
        if (used.count(t)) nodes.insert(used.at(t));
      if (!nodes.empty())
        mesh->node_sets[(dim == 1 ? "curve_" : "point_") + std::to_string(c.second)].assign(nodes.begin(),
                                                                                           nodes.end());
    }
  }
  for (auto &es : mesh->element_sets) std::sort(es.second.begin(), es.second.end());
  return true;
}

std::string GroupNote(const std::map<int, std::string> &names, const etfe::MeshData &mesh) {
  std::set<std::string> named;
  for (const auto &n : names) named.insert(n.second);
  size_t faces = 0, curves = 0, points = 0;
  for (const auto &s : mesh.node_sets) {
    faces += s.first.rfind("surface_", 0) == 0;
    curves += s.first.rfind("curve_", 0) == 0;
    points += s.first.rfind("point_", 0) == 0;
  }
  std::string note = "groups by Gmsh tag: " + std::to_string(faces) + " surface_<tag> (faces without a name), " +
                     std::to_string(curves) + " curve_<tag>, " + std::to_string(points) +
                     " point_<tag>; faces named in the file: ";
  if (named.empty()) return note + "none (Gmsh reads STEP product names only; IGES and BREP carry none)";
  std::string list;
  for (const auto &n : named) list += (list.empty() ? "" : ", ") + n;
  return note + list;
}

} // namespace

// The module's entry point (looked up by name in cad_reader.cpp): 1 on success, else 0 with *err.
extern "C" int etfe_cad_mesh(const char *path, double size, etfe::MeshData *mesh, std::string *err) {
  const std::string file(path);
  etfe::MeshData out;
  std::vector<std::string> notes;
  try {
    GmshSession session;
    try {
      const std::map<int, std::string> names = ImportFused(file, &notes);
      double box[6];
      gmsh::model::getBoundingBox(-1, -1, box[0], box[1], box[2], box[3], box[4], box[5]);
      const double diagonal =
          std::sqrt((box[3] - box[0]) * (box[3] - box[0]) + (box[4] - box[1]) * (box[4] - box[1]) +
                    (box[5] - box[2]) * (box[5] - box[2]));
      if (!(diagonal > 0 && std::isfinite(diagonal))) {
        *err = file + ": no surface in it (Gmsh found no entity with an extent)";
        return 0;
      }
      const bool by_default = !(size > 0);
      if (by_default) size = kDefaultSizeFraction * diagonal;
      if (diagonal / size > kMaxDiagonalOverSize) {
        *err = file + Format(": -mesh_cad_size %g mm on a model whose bounding-box diagonal is %g mm", size,
                             diagonal) +
               Format(" would make up to %.3g triangles: give a larger size (or check the model's unit: STEP and "
                      "IGES are converted to mm, BREP is taken as mm)",
                      (diagonal / size) * (diagonal / size));
        return 0;
      }
      notes.insert(notes.begin(), Format("meshed by Gmsh at the target element size %.4g mm", size) +
                                      (by_default ? Format(" (1/50 of the model's bounding-box diagonal %.4g mm; "
                                                           "-mesh_cad_size sets it)", diagonal)
                                                  : std::string(" (-mesh_cad_size)")));
      if (!MeshModel(file, size, names, &out, err)) return 0;
      notes.push_back(GroupNote(names, out));
    } catch (...) {
      std::string last;
      gmsh::logger::getLastError(last);
      // OpenCASCADE's words for a file it found nothing in ("Could not set OpenCASCADE target
      // unit", "Empty bounding box", "Could not read file") say nothing about the file itself.
      const bool unreadable = last.find("target unit") != std::string::npos ||
                              last.find("Empty bounding box") != std::string::npos ||
                              last.find("Could not read file") != std::string::npos;
      *err = file + (unreadable ? ": Gmsh (OpenCASCADE) found no readable geometry in it (Gmsh said: "
                                : ": Gmsh could not read or mesh it (Gmsh said: ") +
             (last.empty() ? std::string("no reason given") : last) +
             (unreadable ? "): check that it is a complete STEP, IGES or BREP file as its name says (re-export it "
                           "from the CAD program), or mesh it yourself (gmsh -2 file -o file.msh) and give the .msh"
                         : "): mesh it yourself (gmsh -2 file -o file.msh) and give the .msh, or try another "
                           "-mesh_cad_size");
      return 0;
    }
  } catch (...) {
    *err = file + ": the Gmsh API failed to start";
    return 0;
  }
  out.source = file;
  out.notes = std::move(notes);
  *mesh = std::move(out);
  return 1;
}
