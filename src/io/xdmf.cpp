// The XDMF index (see xdmf.h). Every field of a step appears under its viewer name from the field
// table, as one attribute of the whole dataset: Scalar, Vector (3 columns of a vector), Tensor6,
// or Matrix (any other columns: tensor components, principal pairs, 2-D slides; its name lists the
// columns, PK2_Sxx_Syy_Sxy). Every DataItem is a plain HDF5 dataset: ParaView's XDMF3 readers
// ("Xdmf3 Reader S/T") skip a HyperSlab item ("Skipping unrecognized array type [None]": its
// number type is not known before it is read) and the XDMF2 one cannot read XDMF3's
// "file:path|start:stride:count:space" selection, while all three read a Matrix.
#include "xdmf.h"

#include <cstdio>
#include <filesystem>

namespace etfe {

namespace {

// The rows the grids are built on.
constexpr int kCoordinates = OutputFieldIndex("mesh/coordinates"), kTriangles = OutputFieldIndex("mesh/triangles"),
              kContactNode = OutputFieldIndex("contact/node"), kDisplacement = OutputFieldIndex("displacement");
static_assert(kCoordinates >= 0 && kTriangles >= 0 && kContactNode >= 0 && kDisplacement >= 0,
              "the XDMF grids need the mesh, contact/node and displacement rows of the field table");

const char *Center(Layout l) { return l == Layout::Nodes ? "Node" : "Cell"; }

const char *AttributeType(const OutputField &fl) {
  if (fl.components == 1) return "Scalar";
  if (fl.components == 3 && fl.kind == FieldKind::Vector) return "Vector";
  if (fl.components == 6 && fl.kind == FieldKind::Tensor) return "Tensor6";
  return "Matrix";
}

class XdmfWriter {
public:
  XdmfWriter(FILE *f, const XdmfIndex &ix) : f_(f), ix_(ix) {}
  void Step(PetscInt step, double time);

private:
  long long Rows(const OutputField &fl) const { return ix_.rows[(int)fl.location]; }
  // The dataset of a row: mesh rows from the root, the others in the step's group.
  std::string Path(const OutputField &fl) const {
    return std::string(fl.when == FieldWhen::Open ? "/" : group_) + fl.name;
  }
  void Item(const OutputField &fl);
  void Shown(const OutputField &fl);
  void Mesh(const char *topology, const char *more, const OutputField &cells);
  void Film(const char *grid, const double *time);
  void Contact();

  FILE *f_;
  const XdmfIndex &ix_;
  char group_[64] = "";  // "/steps/<k>/"
};

void XdmfWriter::Item(const OutputField &fl) {
  const char *type = fl.integer ? "NumberType=\"Int\" Precision=\"4\"" : "NumberType=\"Float\" Precision=\"8\"";
  if (fl.components > 1)
    std::fprintf(f_, "  <DataItem Dimensions=\"%lld %d\" %s Format=\"HDF\">%s:%s</DataItem>\n", Rows(fl),
                 fl.components, type, ix_.results.c_str(), Path(fl).c_str());
  else
    std::fprintf(f_, "  <DataItem Dimensions=\"%lld\" %s Format=\"HDF\">%s:%s</DataItem>\n", Rows(fl), type,
                 ix_.results.c_str(), Path(fl).c_str());
}

// A field under its viewer name, all its columns as one attribute.
void XdmfWriter::Shown(const OutputField &fl) {
  std::fprintf(f_, " <Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"%s\">\n", fl.viewer, AttributeType(fl),
               Center(fl.location));
  Item(fl);
  std::fprintf(f_, " </Attribute>\n");
}

// The grid's topology (cells: its connectivity) and geometry (the reference coordinates).
void XdmfWriter::Mesh(const char *topology, const char *more, const OutputField &cells) {
  std::fprintf(f_, " <Topology TopologyType=\"%s\" NumberOfElements=\"%lld\"%s>\n", topology, Rows(cells), more);
  Item(cells);
  std::fprintf(f_, " </Topology>\n <Geometry GeometryType=\"XYZ\">\n");
  Item(kOutputFields[kCoordinates]);
  std::fprintf(f_, " </Geometry>\n");
}

void XdmfWriter::Film(const char *grid, const double *time) {
  std::fprintf(f_, " <Grid Name=\"%s\" GridType=\"Uniform\">\n", grid);
  if (time) std::fprintf(f_, "  <Time Value=\"%.12g\"/>\n", *time);
  Mesh("Triangle", "", kOutputFields[kTriangles]);
  for (const OutputField *fl : ix_.fields)
    if (fl->viewer && fl->location != Layout::Pairs) Shown(*fl);
  std::fprintf(f_, " </Grid>\n");
}

// The contact pairs as their own point set, one vertex per pair at its film node; it carries the
// film's displacement too, so Warp By Vector moves it with the film.
void XdmfWriter::Contact() {
  std::fprintf(f_, " <Grid Name=\"contact\" GridType=\"Uniform\">\n");
  Mesh("Polyvertex", " NodesPerElement=\"1\"", kOutputFields[kContactNode]);
  Shown(kOutputFields[kDisplacement]);
  for (const OutputField *fl : ix_.fields)
    if (fl->viewer && fl->location == Layout::Pairs) Shown(*fl);
  std::fprintf(f_, " </Grid>\n");
}

void XdmfWriter::Step(PetscInt step, double time) {
  char grid[32];
  std::snprintf(group_, sizeof group_, "/steps/%06lld/", (long long)step);
  std::snprintf(grid, sizeof grid, "step_%06lld", (long long)step);
  if (!ix_.contact) {
    Film(grid, &time);
    return;
  }
  std::fprintf(f_, " <Grid Name=\"%s\" GridType=\"Collection\" CollectionType=\"Spatial\">\n"
                   "  <Time Value=\"%.12g\"/>\n", grid, time);
  Film("film", nullptr);
  if (ix_.rows[(int)Layout::Pairs] > 0) Contact();
  std::fprintf(f_, " </Grid>\n");
}

} // namespace

PetscErrorCode WriteXdmf(const XdmfIndex &ix, const std::vector<std::pair<PetscInt, double>> &steps) {
  PetscFunctionBeginUser;
  const std::string tmp = ix.path + ".tmp";
  FILE *f = std::fopen(tmp.c_str(), "w");
  PetscCheck(f, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot write %s (is its directory writable?)", tmp.c_str());
  std::fprintf(f, "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n<Domain>\n"
                  "<Grid Name=\"%s\" GridType=\"Collection\" CollectionType=\"Temporal\">\n",
               ix.name.c_str());
  XdmfWriter w(f, ix);
  for (const auto &s : steps) w.Step(s.first, s.second);
  std::fprintf(f, "</Grid>\n</Domain>\n</Xdmf>\n");
  PetscCheck(std::fclose(f) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "cannot write %s (disk full?)",
             tmp.c_str());
  std::error_code ec;
  std::filesystem::rename(tmp, ix.path, ec);
  PetscCheck(!ec, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "cannot rename %s to %s: %s", tmp.c_str(),
             ix.path.c_str(), ec.message().c_str());
  PetscFunctionReturn(0);
}

} // namespace etfe
