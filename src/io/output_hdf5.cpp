// HDF5 + XDMF results (layout in output.h). Fields live in PETSc order on their owning ranks; a
// VecScatter per (nodes|cells, components) brings them to the scene's ("natural") order in
// contiguous row blocks, which every rank writes as a hyperslab of one collective dataset.
#include <hdf5.h>
#include <petscvec.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <random>
#include <map>
#include <memory>
#include <utility>

#include "etfe/assembly.h"
#include "etfe/contact.h"
#include "etfe/h5io.h"
#include "etfe/output.h"

namespace etfe {

struct OutputFile {
  Problem *problem = nullptr;
  std::string path, xdmf_path;
  hid_t file = -1;
  std::vector<std::pair<PetscInt, double>> steps;  // written steps (step, time)
  std::unique_ptr<NaturalOrder> order;
  PetscInt every = 1;
  std::string run_id;  // the same in the results file and the checkpoints of one load history
};

// The file an error exit must mark as failed (see OutputAbandon).
static OutputFile *g_open_output = nullptr;

namespace {

PetscErrorCode WriteField(OutputFile *out, hid_t group, const char *name, Layout layout, int ncomp,
                          const double *owned, bool as_int = false) {
  return H5WriteNatural(out->path, *out->order, group, name, layout, ncomp, owned, as_int);
}

// Contact pairs of a step: local force, slide (local and global X/Y), status, film node.
PetscErrorCode WriteContact(OutputFile *out, hid_t step_group) {
  const ContactSet &c = *out->problem->contact;
  const size_t n = c.pairs.size();
  std::vector<double> force(3 * n), slide_local(2 * n), slide_global(2 * n), status(n), node(n);
  PetscFunctionBeginUser;
  for (size_t k = 0; k < n; ++k) {
    const ContactPair &pr = c.pairs[k];
    const ContactPairReport r = ContactReport(c, pr);
    for (int i = 0; i < 3; ++i) force[3 * k + i] = r.force[i];
    for (int i = 0; i < 2; ++i) slide_local[2 * k + i] = r.slide_local[i], slide_global[2 * k + i] = r.slide_global[i];
    status[k] = r.status;
    node[k] = (double)pr.natural_node;
  }
  hid_t g = H5Gcreate2(step_group, "contact", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  PetscCheck(g >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "HDF5: cannot create a contact group in %s",
             out->path.c_str());
  PetscCall(WriteField(out, g, "force", Layout::Pairs, 3, force.data()));
  PetscCall(WriteField(out, g, "slide_local", Layout::Pairs, 2, slide_local.data()));
  PetscCall(WriteField(out, g, "slide_global", Layout::Pairs, 2, slide_global.data()));
  PetscCall(WriteField(out, g, "status", Layout::Pairs, 1, status.data(), true));
  PetscCall(WriteField(out, g, "node", Layout::Pairs, 1, node.data(), true));
  H5Gclose(g);
  PetscFunctionReturn(0);
}

PetscErrorCode WriteXdmf(OutputFile *out) {
  PetscFunctionBeginUser;
  if (out->problem->rank != 0) PetscFunctionReturn(0);
  const LocalMesh &m = out->problem->mesh;
  const std::string h5 = std::filesystem::path(out->path).filename().string();
  const long long N = m.num_nodes_global, E = m.num_elements_global;
  const bool plastic = out->problem->material->HasPlasticStrain();
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
  const bool contact = out->problem->contact != nullptr;
  const long long C = contact ? (long long)out->problem->contact->num_global : 0;
  // One column of an (rows x cols) dataset, as a scalar attribute ParaView names.
  auto column = [&](const char *name, const char *path, long long rows, int cols, int c, const char *center,
                    const std::string &group) {
    std::fprintf(f, " <Attribute Name=\"%s\" AttributeType=\"Scalar\" Center=\"%s\">\n", name, center);
    std::fprintf(f, "  <DataItem ItemType=\"HyperSlab\" Dimensions=\"%lld 1\" Type=\"HyperSlab\">\n", rows);
    std::fprintf(f, "   <DataItem Dimensions=\"3 2\" Format=\"XML\">0 %d 1 1 %lld 1</DataItem>\n", c, rows);
    std::fprintf(f, "   <DataItem Dimensions=\"%lld %d\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:%s%s"
                    "</DataItem>\n  </DataItem>\n </Attribute>\n",
                 rows, cols, h5.c_str(), group.c_str(), path);
  };
  for (auto &s : out->steps) {
    char group[64];
    std::snprintf(group, sizeof group, "/steps/%06lld/", (long long)s.first);
    if (contact)
      std::fprintf(f, " <Grid Name=\"step_%06lld\" GridType=\"Collection\" CollectionType=\"Spatial\">\n"
                      "  <Time Value=\"%.12g\"/>\n", (long long)s.first, s.second);
    std::fprintf(f, " <Grid Name=\"%s\" GridType=\"Uniform\">\n", contact ? "film" : ("step_" + std::string(group + 7, 6)).c_str());
    if (!contact) std::fprintf(f, "  <Time Value=\"%.12g\"/>\n", s.second);
    std::fprintf(f, " <Topology TopologyType=\"Triangle\" NumberOfElements=\"%lld\">\n", E);
    item("/mesh/triangles", E, 3, "Int", 4, "");
    std::fprintf(f, " </Topology>\n <Geometry GeometryType=\"XYZ\">\n");
    item("/mesh/coordinates", N, 3, "Float", 8, "");
    std::fprintf(f, " </Geometry>\n");
    // The measure is in the name: PK2 stress and Green-Lagrange strain of the reference
    // configuration, components in the element's MD/TD frame (x = MD).
    struct Field { const char *name, *path; bool cell; int ncomp; };
    std::vector<Field> fields = {{"displacement", "displacement", false, 3}, {"reaction", "reaction", false, 3},
                                 {"nodal_mises_PK2", "nodal_mises", false, 1}, {"mises_PK2", "mises", true, 1},
                                 {"min_principal_stress_PK2", "min_principal_stress", true, 1},
                                 {"min_principal_strain_GL", "min_principal_strain", true, 1},
                                 {"area_ratio", "area_ratio", true, 1}, {"cauchy_mises", "cauchy_mises", true, 1},
                                 {"principal_dir1", "principal_dir1", true, 3},
                                 {"principal_dir2", "principal_dir2", true, 3}};
    if (plastic) fields.push_back({"plastic_strain_eq", "plastic_strain_eq", true, 1});
    for (const Field &fl : fields) {
      std::fprintf(f, " <Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"%s\">\n", fl.name,
                   fl.ncomp == 3 ? "Vector" : "Scalar", fl.cell ? "Cell" : "Node");
      item(fl.path, fl.cell ? E : N, fl.ncomp, "Float", 8, group);
      std::fprintf(f, " </Attribute>\n");
    }
    std::fprintf(f, " <Attribute Name=\"cauchy_stress\" AttributeType=\"Tensor6\" Center=\"Cell\">\n");
    item("cauchy_stress", E, 6, "Float", 8, group);
    std::fprintf(f, " </Attribute>\n");
    column("principal_stress_1", "principal_stress", E, 2, 0, "Cell", group);
    column("principal_stress_2", "principal_stress", E, 2, 1, "Cell", group);
    const char *stress[3] = {"PK2_Sxx", "PK2_Syy", "PK2_Sxy"}, *strain[3] = {"GL_Exx", "GL_Eyy", "GL_Exy"},
               *plast[3] = {"plastic_Exx", "plastic_Eyy", "plastic_Exy"};
    for (int c = 0; c < 3; ++c) {
      column(stress[c], "stress", E, 3, c, "Cell", group);
      column(strain[c], "strain", E, 3, c, "Cell", group);
      if (plastic) column(plast[c], "plastic_strain", E, 3, c, "Cell", group);
    }
    std::fprintf(f, " </Grid>\n");
    if (contact && C > 0) {
      // The contact pairs as their own point set: one vertex per pair at its film node.
      std::fprintf(f, " <Grid Name=\"contact\" GridType=\"Uniform\">\n");
      std::fprintf(f, " <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"%lld\" NodesPerElement=\"1\">\n", C);
      item("contact/node", C, 1, "Int", 4, group);
      std::fprintf(f, " </Topology>\n <Geometry GeometryType=\"XYZ\">\n");
      item("/mesh/coordinates", N, 3, "Float", 8, "");
      std::fprintf(f, " </Geometry>\n <Attribute Name=\"displacement\" AttributeType=\"Vector\" Center=\"Node\">\n");
      item("displacement", N, 3, "Float", 8, group);
      std::fprintf(f, " </Attribute>\n <Attribute Name=\"contact_force\" AttributeType=\"Vector\" Center=\"Cell\">\n");
      item("contact/force", C, 3, "Float", 8, group);
      std::fprintf(f, " </Attribute>\n <Attribute Name=\"contact_status\" AttributeType=\"Scalar\" Center=\"Cell\">\n");
      item("contact/status", C, 1, "Int", 4, group);
      std::fprintf(f, " </Attribute>\n");
      column("slide_X", "contact/slide_global", C, 2, 0, "Cell", group);
      column("slide_Y", "contact/slide_global", C, 2, 1, "Cell", group);
      column("slide_x0", "contact/slide_local", C, 2, 0, "Cell", group);
      column("slide_y0", "contact/slide_local", C, 2, 1, "Cell", group);
      std::fprintf(f, " </Grid>\n");
    }
    if (contact) std::fprintf(f, " </Grid>\n");
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

namespace {

struct StepInfo {
  std::string group;
  long long step;
  double time;
};

herr_t CollectStep(hid_t g, const char *name, const H5L_info_t *, void *data) {
  auto *v = (std::vector<StepInfo> *)data;
  hid_t s = H5Gopen2(g, name, H5P_DEFAULT);
  if (s < 0) return 0;
  StepInfo info{name, -1, 0.0};
  if (H5Aexists(s, "step") > 0 && H5Aexists(s, "time") > 0) {
    hid_t a = H5Aopen(s, "step", H5P_DEFAULT);
    H5Aread(a, H5T_NATIVE_LLONG, &info.step);
    H5Aclose(a);
    a = H5Aopen(s, "time", H5P_DEFAULT);
    H5Aread(a, H5T_NATIVE_DOUBLE, &info.time);
    H5Aclose(a);
  }
  H5Gclose(s);
  v->push_back(info);
  return 0;
}

// Reopens a results file to continue it after a restart. Returns false (nothing changed) when
// the file is missing; an unreadable one (cut short by a kill) is moved aside, never
// overwritten; a file of another scene or another load history (run_id) is refused untouched.
PetscErrorCode ReopenForRestart(OutputFile *out, PetscInt restart_step, bool *ok) {
  Problem *P = out->problem;
  PetscFunctionBeginUser;
  int exists = P->rank == 0 && std::filesystem::exists(out->path) ? 1 : 0;
  PetscCallMPI(MPI_Bcast(&exists, 1, MPI_INT, 0, P->comm));
  *ok = false;
  if (!exists) PetscFunctionReturn(0);
  // Probe serially first: a file cut short by a kill may not open.
  int state = 0;  // 0 unreadable, 1 this run's, 2 another scene, 3 another run
  char other[256] = "";
  if (P->rank == 0) {
    H5E_BEGIN_TRY {
      hid_t f = H5Fopen(out->path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
      if (f >= 0) {
        std::string scene, id;
        if (H5Aexists(f, "scene") > 0 && H5ReadString(out->path, f, "scene", &scene) == 0 &&
            H5Lexists(f, "steps", H5P_DEFAULT) > 0) {
          if (H5Aexists(f, "run_id") > 0) H5ReadString(out->path, f, "run_id", &id);
          state = scene != P->scene.name ? 2 : id != out->run_id ? 3 : 1;
          std::snprintf(other, sizeof other, "%s", state == 2 ? scene.c_str() : id.empty() ? "(none)" : id.c_str());
        }
        H5Fclose(f);
      }
    }
    H5E_END_TRY;
  }
  PetscCallMPI(MPI_Bcast(&state, 1, MPI_INT, 0, P->comm));
  PetscCallMPI(MPI_Bcast(other, sizeof other, MPI_CHAR, 0, P->comm));
  PetscCheck(state != 2, P->comm, PETSC_ERR_FILE_UNEXPECTED,
             "-output_file %s holds results of scene %s, not of this checkpoint's %s: nothing was changed; give "
             "the results file of the run that wrote the checkpoint, or a new -output_file",
             out->path.c_str(), other, P->scene.name.c_str());
  PetscCheck(state != 3, P->comm, PETSC_ERR_FILE_UNEXPECTED,
             "-output_file %s holds another load history (run %s, the checkpoint's is %s): continuing it would "
             "mix two runs, so nothing was changed; give the results file of the run that wrote the checkpoint, "
             "or a new -output_file",
             out->path.c_str(), other, out->run_id.c_str());
  if (state == 0) {
    int moved = 0;
    std::string aside = out->path + ".unreadable";
    if (P->rank == 0) {
      std::error_code ec;
      std::filesystem::rename(out->path, aside, ec);
      moved = ec ? 0 : 1;
    }
    PetscCallMPI(MPI_Bcast(&moved, 1, MPI_INT, 0, P->comm));
    PetscCheck(moved, P->comm, PETSC_ERR_FILE_WRITE,
               "-output_file %s is unreadable and cannot be moved aside to %s: move it yourself", out->path.c_str(),
               aside.c_str());
    PetscCall(PetscPrintf(P->comm, "  output: %s was unreadable (cut short?); kept as %s, the restarted run "
                          "starts the results anew\n", out->path.c_str(), aside.c_str()));
    PetscFunctionReturn(0);
  }
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  H5Pset_fapl_mpio(fapl, P->comm, MPI_INFO_NULL);
  out->file = H5Fopen(out->path.c_str(), H5F_ACC_RDWR, fapl);
  H5Pclose(fapl);
  if (out->file < 0) PetscFunctionReturn(0);
  std::vector<StepInfo> steps;
  hid_t g = H5Gopen2(out->file, "steps", H5P_DEFAULT);
  H5Literate(g, H5_INDEX_NAME, H5_ITER_INC, nullptr, CollectStep, &steps);
  for (const StepInfo &s : steps) {
    if (s.step >= 0 && s.step <= restart_step) out->steps.push_back({(PetscInt)s.step, s.time});
    else H5Ldelete(g, s.group.c_str(), H5P_DEFAULT);  // written after the checkpoint
  }
  H5Gclose(g);
  PetscCall(H5WriteString(out->path, out->file, "status", "running"));
  long long count = (long long)out->steps.size();
  PetscCall(H5WriteAttribute(out->path, out->file, "steps_written", H5T_NATIVE_LLONG, &count));
  *ok = true;
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode OutputOpen(Problem *P, const OutputOptions &o, OutputFile **result, PetscInt restart_step,
                          const std::string &run_id) {
  auto *out = new OutputFile();
  PetscFunctionBeginUser;
  out->problem = P;
  out->run_id = run_id;
  if (out->run_id.empty()) PetscCall(NewRunId(P->comm, &out->run_id));
  out->path = o.path;
  out->every = o.every;
  std::filesystem::path xp(out->path);
  out->xdmf_path = xp.replace_extension(".xmf").string();
  out->order = std::make_unique<NaturalOrder>(P);
  if (restart_step >= 0) {
    bool ok = false;
    PetscCall(ReopenForRestart(out, restart_step, &ok));
    if (ok) {
      PetscCall(WriteXdmf(out));
      *result = g_open_output = out;
      PetscFunctionReturn(0);
    }
    PetscCall(PetscPrintf(P->comm, "  output: %s missing or unreadable; the restarted run starts it anew\n",
                          out->path.c_str()));
  }
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
  PetscCall(H5WriteString(out->path, out->file, "format", "etfe-results-1"));
  PetscCall(H5WriteString(out->path, out->file, "scene", P->scene.name));
  PetscCall(H5WriteString(out->path, out->file, "run_id", out->run_id));
  {
    // What made this file: the options in force (options files expanded) and the solver's version,
    // so a reader (scripts/figures, a colleague) need not guess them.
    char *all = nullptr;
    PetscCall(PetscOptionsGetAll(nullptr, &all));
    PetscCall(H5WriteString(out->path, out->file, "options", all ? all : ""));
    PetscCall(PetscFree(all));
    PetscCall(H5WriteString(out->path, out->file, "version", ETFE_VERSION));
  }
  PetscCall(H5WriteString(out->path, out->file, "status", "running"));
  long long zero = 0;
  PetscCall(H5WriteAttribute(out->path, out->file, "steps_written", H5T_NATIVE_LLONG, &zero));
  hid_t mesh = H5Gcreate2(out->file, "mesh", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  hid_t steps = H5Gcreate2(out->file, "steps", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  const MeshData &gm = P->scene.mesh;
  PetscInt n = PETSC_DECIDE, N = gm.NumNodes(), lo = 0;
  PetscCall(PetscSplitOwnership(P->comm, &n, &N));
  PetscCallMPI(MPI_Exscan(&n, &lo, 1, MPIU_INT, MPI_SUM, P->comm));
  if (P->rank == 0) lo = 0;
  PetscCall(H5WriteRows(out->path, mesh, "coordinates", H5T_NATIVE_DOUBLE, N, 3, lo, n,
                      gm.coords.data() + 3 * lo));
  PetscInt ne = PETSC_DECIDE, NE = gm.NumElements(), elo = 0;
  PetscCall(PetscSplitOwnership(P->comm, &ne, &NE));
  PetscCallMPI(MPI_Exscan(&ne, &elo, 1, MPIU_INT, MPI_SUM, P->comm));
  if (P->rank == 0) elo = 0;
  PetscCall(H5WriteRows(out->path, mesh, "triangles", H5T_NATIVE_INT, NE, 3, elo, ne,
                      gm.triangles.data() + 3 * elo));
  H5Gclose(mesh);
  H5Gclose(steps);
  H5Fflush(out->file, H5F_SCOPE_GLOBAL);
  *result = g_open_output = out;
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
  PetscCheck(g >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "HDF5: cannot create %s in %s", name, out->path.c_str());
  long long st = step;
  const int stage = (int)std::min<double>(std::floor(time), P->scene.NumStages() - 1);
  const double factor = time - stage;
  PetscCall(H5WriteAttribute(out->path, g, "step", H5T_NATIVE_LLONG, &st));
  PetscCall(H5WriteAttribute(out->path, g, "time", H5T_NATIVE_DOUBLE, &time));
  PetscCall(H5WriteAttribute(out->path, g, "stage", H5T_NATIVE_INT, &stage));
  PetscCall(H5WriteAttribute(out->path, g, "load_factor", H5T_NATIVE_DOUBLE, &factor));
  PetscCall(VecGetArrayRead(U, &u));
  PetscCall(WriteField(out, g, "displacement", Layout::Nodes, 3, u));
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscCall(VecGetArrayRead(P->reaction, &r));
  PetscCall(WriteField(out, g, "reaction", Layout::Nodes, 3, r));
  PetscCall(VecRestoreArrayRead(P->reaction, &r));
  PetscCall(WriteField(out, g, "nodal_mises", Layout::Nodes, 1, c.nodal_mises.data()));
  PetscCall(WriteField(out, g, "stress", Layout::Cells, 3, c.stress.data()));
  PetscCall(WriteField(out, g, "strain", Layout::Cells, 3, c.strain.data()));
  PetscCall(WriteField(out, g, "mises", Layout::Cells, 1, c.mises.data()));
  PetscCall(WriteField(out, g, "min_principal_stress", Layout::Cells, 1, c.smin.data()));
  PetscCall(WriteField(out, g, "min_principal_strain", Layout::Cells, 1, c.emin.data()));
  PetscCall(WriteField(out, g, "area_ratio", Layout::Cells, 1, c.area_ratio.data()));
  PetscCall(WriteField(out, g, "cauchy_stress", Layout::Cells, 6, c.cauchy.data()));
  PetscCall(WriteField(out, g, "cauchy_mises", Layout::Cells, 1, c.cauchy_mises.data()));
  PetscCall(WriteField(out, g, "principal_stress", Layout::Cells, 2, c.principal.data()));
  PetscCall(WriteField(out, g, "principal_dir1", Layout::Cells, 3, c.dir1.data()));
  PetscCall(WriteField(out, g, "principal_dir2", Layout::Cells, 3, c.dir2.data()));
  if (P->material->HasPlasticStrain()) {
    PetscCall(WriteField(out, g, "plastic_strain", Layout::Cells, 3, c.ep.data()));
    PetscCall(WriteField(out, g, "plastic_strain_eq", Layout::Cells, 1, c.ep_bar.data()));
  }
  if (P->contact) PetscCall(WriteContact(out, g));
  H5Gclose(g);
  out->steps.push_back({step, time});
  long long count = (long long)out->steps.size();
  PetscCall(H5WriteAttribute(out->path, out->file, "steps_written", H5T_NATIVE_LLONG, &count));
  PetscCheck(H5Fflush(out->file, H5F_SCOPE_GLOBAL) >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "HDF5: flush of %s failed", out->path.c_str());
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

const std::string &OutputRunId(const OutputFile *out) {
  static const std::string none;
  return out ? out->run_id : none;
}

PetscErrorCode NewRunId(MPI_Comm comm, std::string *id) {
  char buf[32] = "";
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    std::random_device rd;
    const unsigned long long a = ((unsigned long long)rd() << 32) ^ rd();
    const unsigned long long b = (unsigned long long)std::chrono::steady_clock::now().time_since_epoch().count();
    std::snprintf(buf, sizeof buf, "%016llx", a ^ (b * 0x9e3779b97f4a7c15ULL));
  }
  PetscCallMPI(MPI_Bcast(buf, sizeof buf, MPI_CHAR, 0, comm));
  *id = buf;
  PetscFunctionReturn(0);
}

PetscErrorCode OutputAbandon(const std::string &why) {
  PetscFunctionBeginUser;
  if (g_open_output) PetscCall(OutputClose(&g_open_output, "failed: " + why));
  PetscFunctionReturn(0);
}

PetscInt OutputLastStep(const OutputFile *out) {
  return (!out || out->steps.empty()) ? -1 : out->steps.back().first;
}

PetscInt OutputEvery(const OutputFile *out) { return out ? out->every : 1; }

std::string OutputStem(const OutputFile *out) {
  return std::filesystem::path(out->path).replace_extension("").string();
}

std::string OutputDirectory(const OutputFile *out) {
  const std::string d = std::filesystem::path(out->path).parent_path().string();
  return d.empty() ? "." : d;
}

PetscErrorCode OutputClose(OutputFile **pout, const std::string &status) {
  OutputFile *out = *pout;
  PetscFunctionBeginUser;
  if (!out) PetscFunctionReturn(0);
  if (out == g_open_output) g_open_output = nullptr;
  PetscCall(H5WriteString(out->path, out->file, "status", status));
  H5Fclose(out->file);
  delete out;
  *pout = nullptr;
  PetscFunctionReturn(0);
}

} // namespace etfe
