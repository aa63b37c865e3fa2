// CAD files by name, and the loading of the Gmsh meshing module (etfe/mesh/cad_reader.h).
#include "etfe/mesh/cad_reader.h"

#include <dlfcn.h>
#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>

#include "etfe/mesh/gmsh_reader.h"

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

} // namespace

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
  return IsCadFile(path) ? ReadCadFile(path, cad_size, mesh, err) : ReadGmshFile(path, mesh, err);
}

} // namespace etfe
