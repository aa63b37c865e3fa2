// CAD files by name, and the loading of the Gmsh meshing module (etfe/mesh/cad_reader.h).
#include "etfe/mesh/cad_reader.h"

#include <dlfcn.h>
#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>

#include "etfe/mesh/gmsh_reader.h"
#include "etfe/mesh/self_intersection.h"

namespace etfe {

namespace {

std::string Lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return (char)std::tolower(c); });
  return s;
}

#ifdef ETFE_CAD_MODULE
typedef int (*CadMeshFunction)(const char *, double, MeshData *, std::string *);

// The module's entry point, loaded once (and kept: OpenCASCADE is not made to be unloaded).
CadMeshFunction LoadModule(std::string *err) {
  static CadMeshFunction entry = nullptr;
  if (entry) return entry;
  void *handle = dlopen(ETFE_CAD_MODULE, RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char *why = dlerror();
    *err = std::string("the CAD meshing module ") + ETFE_CAD_MODULE + " of this build cannot be loaded (" +
           (why ? why : "no reason given") + "): rebuild (cmake --build build) or reinstall libgmsh-dev";
    return nullptr;
  }
  entry = (CadMeshFunction)dlsym(handle, "etfe_cad_mesh");
  if (!entry) *err = std::string("the CAD meshing module ") + ETFE_CAD_MODULE + " has no etfe_cad_mesh: rebuild it";
  return entry;
}
#endif

// What the first bytes look like, for a refusal: binary, empty, or the first line quoted.
std::string Describe(const std::string &head) {
  if (head.empty()) return "an empty file";
  size_t bad = 0;
  for (unsigned char c : head) bad += (c < 32 && c != '\n' && c != '\r' && c != '\t') || c == 127 ? 1 : 0;
  if (bad * 20 > head.size()) return "binary data (" + std::to_string(bad) + " control bytes in the first " +
                                     std::to_string(head.size()) + ")";
  size_t end = head.find_first_of("\r\n");
  std::string line = head.substr(0, end == std::string::npos ? head.size() : end);
  const size_t len = line.size();
  if (line.size() > 60) line = line.substr(0, 60) + "...";
  for (char &c : line)
    if ((unsigned char)c < 32 || (unsigned char)c > 126) c = '?';
  return "a first line of " + std::to_string(len) + " characters: \"" + line + "\"";
}

} // namespace

std::string CadContentProblem(const std::string &path, const std::string &head) {
  const size_t dot = path.find_last_of('.');
  const std::string ext = dot == std::string::npos ? "" : Lower(path.substr(dot + 1));
  size_t start = 0;  // a UTF-8 byte-order mark and leading blank lines are harmless
  if (head.compare(0, 3, "\xEF\xBB\xBF") == 0) start = 3;
  while (start < head.size() && std::isspace((unsigned char)head[start])) ++start;
  const std::string body = head.substr(start);
  std::string expected;
  if (ext == "step" || ext == "stp") {
    if (body.compare(0, 13, "ISO-10303-21;") == 0) return "";
    expected = "a STEP file, which starts with \"ISO-10303-21;\"";
  } else if (ext == "brep") {
    const std::string first = body.substr(0, 256);
    if (first.find("DBRep_DrawableShape") != std::string::npos || first.find("CASCADE Topology") != std::string::npos)
      return "";
    expected = "an OpenCASCADE BREP file, which starts with \"DBRep_DrawableShape\" or \"CASCADE Topology\"";
  } else if (ext == "iges" || ext == "igs") {
    // Fixed 80-column records with the section letter in column 73; the first is Start (S) or
    // Global (G). Checked on the first three lines.
    bool ok = true;
    size_t pos = head.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0, lines = 0;  // a line may start blank
    while (ok && lines < 3 && pos < head.size()) {
      size_t end = head.find('\n', pos);
      if (end == std::string::npos) end = head.size();
      std::string line = head.substr(pos, end - pos);
      if (!line.empty() && line.back() == '\r') line.pop_back();
      ok = line.size() >= 73 && std::strchr(lines == 0 ? "SG" : "SGDPT", line[72]) != nullptr;
      pos = end + 1;
      ++lines;
    }
    if (ok && lines > 0) return "";
    expected = "an IGES file, whose lines are 80-column records with the section letter S, G, D, P or T in column 73";
  } else {
    return "";
  }
  return path + ": expected " + expected + ", but found " + Describe(body) +
         ": give the CAD file itself (re-export it from the CAD program), or a Gmsh .msh";
}

bool IsCadFile(const std::string &path) {
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || path.find('/', dot) != std::string::npos) return false;
  const std::string ext = Lower(path.substr(dot + 1));
  return ext == "step" || ext == "stp" || ext == "iges" || ext == "igs" || ext == "brep";
}

bool CadMeshingBuiltIn() {
#ifdef ETFE_CAD_MODULE
  return true;
#else
  return false;
#endif
}

std::string CadUnavailableMessage(const std::string &path) {
  return path +
         ": a CAD file (STEP, IGES, BREP), but this build has no Gmsh API to mesh it: install libgmsh-dev "
         "(apt-get install libgmsh-dev) and re-run cmake, or mesh it yourself (gmsh -2 file -o file.msh) and give "
         "the .msh";
}

bool ReadCadFile(const std::string &path, double size, MeshData *mesh, std::string *err) {
#ifdef ETFE_CAD_MODULE
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) {
    *err = path + ": cannot open: " + std::strerror(errno);
    return false;
  }
  if (!S_ISREG(st.st_mode)) {
    *err = path + ": not a regular file: give a STEP, IGES or BREP file";
    return false;
  }
  // OpenCASCADE answers a file that is not what its name says with messages about units or
  // bounding boxes; the first bytes tell it plainly.
  std::string head(4096, '\0');
  {
    std::ifstream in(path, std::ios::binary);
    in.read(&head[0], (std::streamsize)head.size());
    head.resize((size_t)in.gcount());
  }
  *err = CadContentProblem(path, head);
  if (!err->empty()) return false;
  std::string why;
  CadMeshFunction mesh_cad = LoadModule(&why);
  if (!mesh_cad) {
    *err = path + ": " + why;
    return false;
  }
  return mesh_cad(path.c_str(), size, mesh, err) == 1;
#else
  (void)size;
  (void)mesh;
  *err = CadUnavailableMessage(path);
  return false;
#endif
}

bool ReadMeshFile(const std::string &path, double cad_size, MeshData *mesh, std::string *err) {
  const bool ok = IsCadFile(path) ? ReadCadFile(path, cad_size, mesh, err) : ReadGmshFile(path, mesh, err);
  return ok && (!MeshIntersectionCheck() || MeshCheckIntersections(*mesh, err));
}

} // namespace etfe
