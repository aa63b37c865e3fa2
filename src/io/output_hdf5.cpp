// HDF5 + XDMF results (layout in output.h). Fields live in PETSc order on their owning ranks; a
// VecScatter per (nodes|cells, components) brings them to the scene's ("natural") order in
// contiguous row blocks, which every rank writes as a hyperslab of one collective dataset.
#include <hdf5.h>
#include <petscvec.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <utility>

#include "etfe/output.h"

namespace etfe {

struct OutputFile {
  Problem *problem = nullptr;
  std::string path, xdmf_path;
  hid_t file = -1;
  std::vector<std::pair<PetscInt, double>> steps;  // written steps (step, time)
  std::map<std::pair<int, int>, std::pair<VecScatter, std::pair<Vec, Vec>>> scatters;
  PetscInt every = 1;
};

namespace {

#define ETFE_H5CHECK(call, what)                                                                        \
  do {                                                                                             \
    if ((call) < 0)                                                                                \
      SETERRQ(PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "HDF5: %s failed (%s)", what,                 \
              out->path.c_str());                                                                  \
  } while (0)

PetscErrorCode WriteAttribute(OutputFile *out, hid_t obj, const char *name, hid_t type,
                              const void *value, size_t strlen_ = 0) {
  PetscFunctionBeginUser;
  if (H5Aexists(obj, name) > 0) ETFE_H5CHECK(H5Adelete(obj, name), name);
  hid_t space = H5Screate(H5S_SCALAR), t = type;
  if (strlen_) {
    t = H5Tcopy(H5T_C_S1);
    H5Tset_size(t, strlen_ + 1);
  }
  hid_t a = H5Acreate2(obj, name, t, space, H5P_DEFAULT, H5P_DEFAULT);
  ETFE_H5CHECK(a, name);
  ETFE_H5CHECK(H5Awrite(a, t, value), name);
  H5Aclose(a);
  if (strlen_) H5Tclose(t);
  H5Sclose(space);
  PetscFunctionReturn(0);
}

PetscErrorCode WriteString(OutputFile *out, hid_t obj, const char *name, const std::string &v) {
  return WriteAttribute(out, obj, name, H5T_C_S1, v.c_str(), v.size());
}

// Collective: rows [row0, row0 + nrows) of a (total_rows, cols) dataset from this rank.
PetscErrorCode WriteRows(OutputFile *out, hid_t group, const char *name, hid_t type,
                         hsize_t total_rows, hsize_t cols, hsize_t row0, hsize_t nrows,
                         const void *data) {
  PetscFunctionBeginUser;
  hsize_t dims[2] = {total_rows, cols}, start[2] = {row0, 0}, count[2] = {nrows, cols};
  const int rank = cols > 1 ? 2 : 1;
  hid_t fspace = H5Screate_simple(rank, dims, nullptr);
  hid_t dset = H5Dcreate2(group, name, type, fspace, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  ETFE_H5CHECK(dset, name);
  hid_t mspace = H5Screate_simple(rank, count, nullptr);
  if (nrows > 0)
    ETFE_H5CHECK(H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, nullptr, count, nullptr), name);
  else {
    H5Sselect_none(fspace);
    H5Sselect_none(mspace);
  }
  hid_t dxpl = H5Pcreate(H5P_DATASET_XFER);
  H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE);
  ETFE_H5CHECK(H5Dwrite(dset, type, mspace, fspace, dxpl, data), name);
  H5Pclose(dxpl);
  H5Sclose(mspace);
  H5Sclose(fspace);
  H5Dclose(dset);
  PetscFunctionReturn(0);
}

// Scatter owned values (PETSc order, ncomp per item) to natural order; returns the natural
// vector whose local rows start at *row0.
enum Layout { kNodes = 0, kCells = 1, kPairs = 2 };

PetscInt LayoutGlobalSize(const Problem *P, int layout) {
  return layout == kCells ? P->mesh.num_elements_global
                          : layout == kNodes ? P->mesh.num_nodes_global : P->contact->num_global;
}

PetscErrorCode ToNatural(OutputFile *out, int layout, int ncomp, const double *owned,
                         Vec *natural, PetscInt *row0, PetscInt *nrows) {
  Problem *P = out->problem;
  const LocalMesh &m = P->mesh;
  auto key = std::make_pair(layout, ncomp);
  PetscFunctionBeginUser;
  if (!out->scatters.count(key)) {
    const PetscInt nloc = layout == kCells   ? m.num_elements
                          : layout == kNodes ? m.num_owned
                                             : (PetscInt)P->contact->pairs.size();
    const PetscInt nglob = LayoutGlobalSize(P, layout);
    const PetscInt first = layout == kCells   ? m.element_start
                           : layout == kNodes ? m.owned_start
                                              : P->contact->pair_start;
    std::vector<PetscInt> from(nloc), to(nloc);
    for (PetscInt i = 0; i < nloc; ++i) {
      from[i] = first + i;
      to[i] = layout == kCells   ? m.element_natural[i]
              : layout == kNodes ? m.natural_id[i]
                                 : P->contact->pairs[i].id;
    }
    Vec src, dst;
    IS isf, ist;
    VecScatter sc;
    PetscCall(VecCreateMPI(P->comm, ncomp * nloc, ncomp * nglob, &src));
    // rows stay whole on a rank: local sizes in multiples of ncomp
    PetscInt n = PETSC_DECIDE, N = nglob;
    PetscCall(PetscSplitOwnership(P->comm, &n, &N));
    PetscCall(VecCreateMPI(P->comm, ncomp * n, ncomp * nglob, &dst));
    PetscCall(ISCreateBlock(P->comm, ncomp, nloc, from.data(), PETSC_COPY_VALUES, &isf));
    PetscCall(ISCreateBlock(P->comm, ncomp, nloc, to.data(), PETSC_COPY_VALUES, &ist));
    PetscCall(VecScatterCreate(src, isf, dst, ist, &sc));
    PetscCall(ISDestroy(&isf));
    PetscCall(ISDestroy(&ist));
    out->scatters[key] = {sc, {src, dst}};
  }
  auto &entry = out->scatters[key];
  Vec src = entry.second.first, dst = entry.second.second;
  PetscScalar *a;
  PetscInt n, lo;
  PetscCall(VecGetLocalSize(src, &n));
  PetscCall(VecGetArray(src, &a));
  for (PetscInt i = 0; i < n; ++i) a[i] = owned[i];
  PetscCall(VecRestoreArray(src, &a));
  PetscCall(VecScatterBegin(entry.first, src, dst, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(entry.first, src, dst, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetOwnershipRange(dst, &lo, nullptr));
  PetscCall(VecGetLocalSize(dst, &n));
  *natural = dst;
  *row0 = lo / ncomp;
  *nrows = n / ncomp;
  PetscFunctionReturn(0);
}

PetscErrorCode WriteField(OutputFile *out, hid_t group, const char *name, int layout, int ncomp,
                          const double *owned, bool as_int = false) {
  Vec nat = nullptr;
  PetscInt row0 = 0, nrows = 0;
  const PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(ToNatural(out, layout, ncomp, owned, &nat, &row0, &nrows));
  const hsize_t total = LayoutGlobalSize(out->problem, layout);
  PetscCall(VecGetArrayRead(nat, &a));
  if (as_int) {
    std::vector<int> v(a, a + nrows * ncomp);
    PetscCall(WriteRows(out, group, name, H5T_NATIVE_INT, total, ncomp, row0, nrows, v.data()));
  } else {
    PetscCall(WriteRows(out, group, name, H5T_NATIVE_DOUBLE, total, ncomp, row0, nrows, a));
  }
  PetscCall(VecRestoreArrayRead(nat, &a));
  PetscFunctionReturn(0);
}

// Contact pairs of a step: local force, slide (local and global X/Y), status, film node.
PetscErrorCode WriteContact(OutputFile *out, hid_t step_group) {
  const ContactSet &c = *out->problem->contact;
  const size_t n = c.pairs.size();
  std::vector<double> force(3 * n), slide_local(2 * n), slide_global(2 * n), status(n), node(n);
  PetscFunctionBeginUser;
  for (size_t k = 0; k < n; ++k) {
    const ContactPair &pr = c.pairs[k];
    const double s0 = pr.committed.g[0] - pr.g0[0], s1 = pr.committed.g[1] - pr.g0[1];
    for (int i = 0; i < 3; ++i) force[3 * k + i] = pr.committed.f[i];
    slide_local[2 * k] = s0;
    slide_local[2 * k + 1] = s1;
    slide_global[2 * k] = pr.R[0] * s0 + pr.R[3] * s1;
    slide_global[2 * k + 1] = pr.R[1] * s0 + pr.R[4] * s1;
    status[k] = pr.committed.status;
    node[k] = (double)pr.natural_node;
  }
  hid_t g = H5Gcreate2(step_group, "contact", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  ETFE_H5CHECK(g, "contact group");
  PetscCall(WriteField(out, g, "force", kPairs, 3, force.data()));
  PetscCall(WriteField(out, g, "slide_local", kPairs, 2, slide_local.data()));
  PetscCall(WriteField(out, g, "slide_global", kPairs, 2, slide_global.data()));
  PetscCall(WriteField(out, g, "status", kPairs, 1, status.data(), true));
  PetscCall(WriteField(out, g, "node", kPairs, 1, node.data(), true));
  H5Gclose(g);
  PetscFunctionReturn(0);
}

PetscErrorCode WriteXdmf(OutputFile *out) {
  PetscFunctionBeginUser;
  if (out->problem->rank != 0) PetscFunctionReturn(0);
  const LocalMesh &m = out->problem->mesh;
  const std::string h5 = std::filesystem::path(out->path).filename().string();
  const long long N = m.num_nodes_global, E = m.num_elements_global;
  const bool plastic = !out->problem->history.empty();
  const std::string tmp = out->xdmf_path + ".tmp";
  FILE *f = std::fopen(tmp.c_str(), "w");
  PetscCheck(f, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot write %s", tmp.c_str());
  std::fprintf(f, "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n<Domain>\n"
                  "<Grid Name=\"%s\" GridType=\"Collection\" CollectionType=\"Temporal\">\n",
               out->problem->scene.name.c_str());
  auto item = [&](const char *path, long long rows, int cols, const char *type, int prec,
                  const std::string &group) {
    if (cols > 1)
      std::fprintf(f, "  <DataItem Dimensions=\"%lld %d\" NumberType=\"%s\" Precision=\"%d\" "
                      "Format=\"HDF\">%s:%s%s</DataItem>\n",
                   rows, cols, type, prec, h5.c_str(), group.c_str(), path);
    else
      std::fprintf(f, "  <DataItem Dimensions=\"%lld\" NumberType=\"%s\" Precision=\"%d\" "
                      "Format=\"HDF\">%s:%s%s</DataItem>\n",
                   rows, type, prec, h5.c_str(), group.c_str(), path);
  };
  for (auto &s : out->steps) {
    char group[64];
    std::snprintf(group, sizeof group, "/steps/%06lld/", (long long)s.first);
    std::fprintf(f, " <Grid Name=\"step_%06lld\" GridType=\"Uniform\">\n  <Time Value=\"%.12g\"/>\n",
                 (long long)s.first, s.second);
    std::fprintf(f, " <Topology TopologyType=\"Triangle\" NumberOfElements=\"%lld\">\n", E);
    item("/mesh/triangles", E, 3, "Int", 4, "");
    std::fprintf(f, " </Topology>\n <Geometry GeometryType=\"XYZ\">\n");
    item("/mesh/coordinates", N, 3, "Float", 8, "");
    std::fprintf(f, " </Geometry>\n");
    struct Field { const char *name; bool cell; int ncomp; };
    std::vector<Field> fields = {{"displacement", false, 3}, {"reaction", false, 3},
                                 {"nodal_mises", false, 1}, {"stress", true, 3},
                                 {"strain", true, 3}, {"mises", true, 1},
                                 {"min_principal_stress", true, 1},
                                 {"min_principal_strain", true, 1}, {"area_ratio", true, 1}};
    if (plastic) {
      fields.push_back({"plastic_strain", true, 3});
      fields.push_back({"plastic_strain_eq", true, 1});
    }
    for (const Field &fl : fields) {
      std::fprintf(f, " <Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"%s\">\n", fl.name,
                   fl.ncomp == 3 ? "Vector" : "Scalar", fl.cell ? "Cell" : "Node");
      item(fl.name, fl.cell ? E : N, fl.ncomp, "Float", 8, group);
      std::fprintf(f, " </Attribute>\n");
    }
    std::fprintf(f, " </Grid>\n");
  }
  std::fprintf(f, "</Grid>\n</Domain>\n</Xdmf>\n");
  PetscCheck(std::fclose(f) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "cannot write %s",
             tmp.c_str());
  std::error_code ec;
  std::filesystem::rename(tmp, out->xdmf_path, ec);
  PetscCheck(!ec, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "cannot rename %s to %s: %s",
             tmp.c_str(), out->xdmf_path.c_str(), ec.message().c_str());
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode OutputOptionsFromCommandLine(MPI_Comm comm, const char *scene, OutputOptions *o) {
  PetscFunctionBeginUser;
  std::snprintf(o->path, sizeof o->path, "results/%s/%s.h5", scene, scene);
  PetscOptionsBegin(comm, nullptr, "Output (HDF5 + XDMF)", "Output");
  PetscCall(PetscOptionsString("-output_file", "Results file (HDF5; the XDMF index goes beside it)",
                               "", o->path, o->path, sizeof o->path, nullptr));
  PetscCall(PetscOptionsInt("-output_every", "Write every n-th increment (the last always)", "",
                            o->every, &o->every, nullptr));
  PetscCall(PetscOptionsBool("-output", "Write results at all", "", o->enabled, &o->enabled,
                             nullptr));
  PetscOptionsEnd();
  PetscCheck(o->every >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-output_every %" PetscInt_FMT ": must be at least 1", o->every);
  PetscFunctionReturn(0);
}

PetscErrorCode OutputOpen(Problem *P, const OutputOptions &o, OutputFile **result) {
  auto *out = new OutputFile();
  PetscFunctionBeginUser;
  out->problem = P;
  out->path = o.path;
  out->every = o.every;
  std::filesystem::path xp(out->path);
  out->xdmf_path = xp.replace_extension(".xmf").string();
  if (P->rank == 0) {
    std::error_code ec;
    auto dir = std::filesystem::path(out->path).parent_path();
    if (!dir.empty()) std::filesystem::create_directories(dir, ec);
    // A stale index must not describe the new file while it is being written.
    std::filesystem::remove(out->xdmf_path, ec);
  }
  PetscCallMPI(MPI_Barrier(P->comm));
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  H5Pset_fapl_mpio(fapl, P->comm, MPI_INFO_NULL);
  out->file = H5Fcreate(out->path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  H5Pclose(fapl);
  PetscCheck(out->file >= 0, P->comm, PETSC_ERR_FILE_OPEN,
             "cannot create the results file %s (check -output_file and that its directory is "
             "writable)",
             out->path.c_str());
  PetscCall(WriteString(out, out->file, "format", "etfe-results-1"));
  PetscCall(WriteString(out, out->file, "scene", P->scene.name));
  PetscCall(WriteString(out, out->file, "status", "running"));
  long long zero = 0;
  PetscCall(WriteAttribute(out, out->file, "steps_written", H5T_NATIVE_LLONG, &zero));
  hid_t mesh = H5Gcreate2(out->file, "mesh", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  hid_t steps = H5Gcreate2(out->file, "steps", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  const MeshData &gm = P->scene.mesh;
  PetscInt n = PETSC_DECIDE, N = gm.NumNodes(), lo = 0;
  PetscCall(PetscSplitOwnership(P->comm, &n, &N));
  PetscCallMPI(MPI_Exscan(&n, &lo, 1, MPIU_INT, MPI_SUM, P->comm));
  if (P->rank == 0) lo = 0;
  PetscCall(WriteRows(out, mesh, "coordinates", H5T_NATIVE_DOUBLE, N, 3, lo, n,
                      gm.coords.data() + 3 * lo));
  PetscInt ne = PETSC_DECIDE, NE = gm.NumElements(), elo = 0;
  PetscCall(PetscSplitOwnership(P->comm, &ne, &NE));
  PetscCallMPI(MPI_Exscan(&ne, &elo, 1, MPIU_INT, MPI_SUM, P->comm));
  if (P->rank == 0) elo = 0;
  PetscCall(WriteRows(out, mesh, "triangles", H5T_NATIVE_INT, NE, 3, elo, ne,
                      gm.triangles.data() + 3 * elo));
  H5Gclose(mesh);
  H5Gclose(steps);
  H5Fflush(out->file, H5F_SCOPE_GLOBAL);
  *result = out;
  PetscFunctionReturn(0);
}

PetscErrorCode OutputWriteStep(OutputFile *out, Problem *P, Vec U, PetscInt step, double time,
                               Vec U_fields) {
  CellFields c;
  const PetscScalar *u, *r;
  PetscFunctionBeginUser;
  if (!out) PetscFunctionReturn(0);
  if (!out->steps.empty() && out->steps.back().first == step) PetscFunctionReturn(0);
  PetscCall(ComputeCellFields(P, U_fields ? U_fields : U, &c));
  char name[64];
  std::snprintf(name, sizeof name, "steps/%06lld", (long long)step);
  hid_t g = H5Gcreate2(out->file, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  ETFE_H5CHECK(g, name);
  long long st = step;
  const int stage = (int)std::min<double>(std::floor(time), P->scene.NumStages() - 1);
  const double factor = time - stage;
  PetscCall(WriteAttribute(out, g, "step", H5T_NATIVE_LLONG, &st));
  PetscCall(WriteAttribute(out, g, "time", H5T_NATIVE_DOUBLE, &time));
  PetscCall(WriteAttribute(out, g, "stage", H5T_NATIVE_INT, &stage));
  PetscCall(WriteAttribute(out, g, "load_factor", H5T_NATIVE_DOUBLE, &factor));
  PetscCall(VecGetArrayRead(U, &u));
  PetscCall(WriteField(out, g, "displacement", kNodes, 3, u));
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscCall(VecGetArrayRead(P->reaction, &r));
  PetscCall(WriteField(out, g, "reaction", kNodes, 3, r));
  PetscCall(VecRestoreArrayRead(P->reaction, &r));
  PetscCall(WriteField(out, g, "nodal_mises", kNodes, 1, c.nodal_mises.data()));
  PetscCall(WriteField(out, g, "stress", kCells, 3, c.stress.data()));
  PetscCall(WriteField(out, g, "strain", kCells, 3, c.strain.data()));
  PetscCall(WriteField(out, g, "mises", kCells, 1, c.mises.data()));
  PetscCall(WriteField(out, g, "min_principal_stress", kCells, 1, c.smin.data()));
  PetscCall(WriteField(out, g, "min_principal_strain", kCells, 1, c.emin.data()));
  PetscCall(WriteField(out, g, "area_ratio", kCells, 1, c.area_ratio.data()));
  if (!c.ep_bar.empty() || !P->history.empty()) {
    c.ep.resize(3 * P->mesh.num_elements);
    c.ep_bar.resize(P->mesh.num_elements);
    PetscCall(WriteField(out, g, "plastic_strain", kCells, 3, c.ep.data()));
    PetscCall(WriteField(out, g, "plastic_strain_eq", kCells, 1, c.ep_bar.data()));
  }
  if (P->contact) PetscCall(WriteContact(out, g));
  H5Gclose(g);
  out->steps.push_back({step, time});
  long long count = (long long)out->steps.size();
  PetscCall(WriteAttribute(out, out->file, "steps_written", H5T_NATIVE_LLONG, &count));
  ETFE_H5CHECK(H5Fflush(out->file, H5F_SCOPE_GLOBAL), "flush");
  PetscCall(WriteXdmf(out));
  PetscFunctionReturn(0);
}

PetscErrorCode OutputGatherShape(Problem *P, Vec U, MeshData *shape) {
  const LocalMesh &m = P->mesh;
  Vec src, dst;
  IS is;
  VecScatter sc;
  const PetscScalar *u;
  PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(VecCreateMPI(P->comm, 3 * m.num_owned, 3 * m.num_nodes_global, &src));
  PetscCall(VecGetArrayRead(U, &u));
  PetscCall(VecGetArray(src, &a));
  for (PetscInt i = 0; i < 3 * m.num_owned; ++i) a[i] = m.X[i] + u[i];
  PetscCall(VecRestoreArray(src, &a));
  PetscCall(VecRestoreArrayRead(U, &u));
  // Natural order on rank 0: scatter owned rows to their scene ids.
  std::vector<PetscInt> from(m.num_owned), to(m.num_owned);
  for (PetscInt l = 0; l < m.num_owned; ++l) from[l] = m.owned_start + l, to[l] = m.natural_id[l];
  PetscCall(VecCreateMPI(P->comm, P->rank == 0 ? 3 * m.num_nodes_global : 0, 3 * m.num_nodes_global, &dst));
  IS isf;
  PetscCall(ISCreateBlock(P->comm, 3, m.num_owned, from.data(), PETSC_COPY_VALUES, &isf));
  PetscCall(ISCreateBlock(P->comm, 3, m.num_owned, to.data(), PETSC_COPY_VALUES, &is));
  PetscCall(VecScatterCreate(src, isf, dst, is, &sc));
  PetscCall(VecScatterBegin(sc, src, dst, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(sc, src, dst, INSERT_VALUES, SCATTER_FORWARD));
  *shape = P->scene.mesh;
  if (P->rank == 0) {
    const PetscScalar *d;
    PetscCall(VecGetArrayRead(dst, &d));
    for (PetscInt i = 0; i < 3 * m.num_nodes_global; ++i) shape->coords[i] = d[i];
    PetscCall(VecRestoreArrayRead(dst, &d));
  }
  PetscCall(VecScatterDestroy(&sc));
  PetscCall(ISDestroy(&isf));
  PetscCall(ISDestroy(&is));
  PetscCall(VecDestroy(&src));
  PetscCall(VecDestroy(&dst));
  PetscFunctionReturn(0);
}

PetscInt OutputLastStep(const OutputFile *out) {
  return (!out || out->steps.empty()) ? -1 : out->steps.back().first;
}

PetscInt OutputEvery(const OutputFile *out) { return out ? out->every : 1; }

std::string OutputDirectory(const OutputFile *out) {
  const std::string d = std::filesystem::path(out->path).parent_path().string();
  return d.empty() ? "." : d;
}

PetscErrorCode OutputClose(OutputFile **pout, const std::string &status) {
  OutputFile *out = *pout;
  PetscFunctionBeginUser;
  if (!out) PetscFunctionReturn(0);
  PetscCall(WriteString(out, out->file, "status", status));
  H5Fclose(out->file);
  for (auto &kv : out->scatters) {
    PetscCall(VecScatterDestroy(&kv.second.first));
    PetscCall(VecDestroy(&kv.second.second.first));
    PetscCall(VecDestroy(&kv.second.second.second));
  }
  delete out;
  *pout = nullptr;
  PetscFunctionReturn(0);
}

} // namespace etfe
