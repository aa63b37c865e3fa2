// Checkpoint/restart (see checkpoint.h).
#include "etfe/checkpoint.h"

#include <hdf5.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "etfe/h5io.h"

namespace etfe {

namespace {

// A fingerprint of the scene's mesh: equal meshes give equal numbers on every rank.
double MeshChecksum(const MeshData &m) {
  double s = 0.0;
  for (int n = 0; n < m.NumNodes(); ++n)
    s += (m.coords[3 * n] + 2.0 * m.coords[3 * n + 1] + 3.0 * m.coords[3 * n + 2]) * (1 + n % 7);
  for (int e = 0; e < m.NumElements(); ++e)
    s += (m.triangles[3 * e] + 2.0 * m.triangles[3 * e + 1] + 3.0 * m.triangles[3 * e + 2]) * (1 + e % 5);
  return s;
}

struct Shape {
  long long nodes, elements, pairs, history, stages;
};

Shape ProblemShape(const Problem *P) {
  return {(long long)P->mesh.num_nodes_global, (long long)P->mesh.num_elements_global,
          (long long)(P->contact ? P->contact->num_global : 0), (long long)P->material->HistorySize(),
          (long long)P->scene.NumStages()};
}

} // namespace

PetscErrorCode CheckpointOptionsFromCommandLine(MPI_Comm comm, const char *scene, CheckpointOptions *o) {
  PetscFunctionBeginUser;
  std::snprintf(o->file, sizeof o->file, "results/%s/%s.checkpoint.h5", scene, scene);
  PetscOptionsBegin(comm, nullptr, "Checkpoint and restart", "Checkpoint");
  PetscCall(PetscOptionsInt("-checkpoint_every", "Write a checkpoint every n increments (0: only at -load_stop_after)",
                            "", o->every, &o->every, nullptr));
  PetscCall(PetscOptionsString("-checkpoint_file", "Checkpoint file (HDF5)", "", o->file, o->file, sizeof o->file,
                               nullptr));
  PetscCall(PetscOptionsString("-restart", "Continue the load history from this checkpoint", "", o->restart,
                               o->restart, sizeof o->restart, nullptr));
  PetscOptionsEnd();
  PetscCheck(o->every >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-checkpoint_every %" PetscInt_FMT " must be >= 0",
             o->every);
  PetscFunctionReturn(0);
}

PetscErrorCode CheckpointWrite(Problem *P, const std::string &path, const StepperState &st, Vec Uc, Vec Up) {
  const std::string tmp = path + ".tmp";
  NaturalOrder order(P);
  const PetscScalar *a;
  PetscFunctionBeginUser;
  if (P->rank == 0) {
    std::error_code ec;
    auto dir = std::filesystem::path(path).parent_path();
    if (!dir.empty()) std::filesystem::create_directories(dir, ec);
  }
  PetscCallMPI(MPI_Barrier(P->comm));
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  H5Pset_fapl_mpio(fapl, P->comm, MPI_INFO_NULL);
  hid_t f = H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  H5Pclose(fapl);
  PetscCheck(f >= 0, P->comm, PETSC_ERR_FILE_OPEN, "cannot create the checkpoint %s (check -checkpoint_file)",
             tmp.c_str());
  const Shape sh = ProblemShape(P);
  const double cs = MeshChecksum(P->scene.mesh);
  PetscCall(H5WriteString(tmp, f, "format", "etfe-checkpoint-1"));
  PetscCall(H5WriteString(tmp, f, "scene", P->scene.name));
  PetscCall(H5WriteAttribute(tmp, f, "nodes", H5T_NATIVE_LLONG, &sh.nodes));
  PetscCall(H5WriteAttribute(tmp, f, "elements", H5T_NATIVE_LLONG, &sh.elements));
  PetscCall(H5WriteAttribute(tmp, f, "pairs", H5T_NATIVE_LLONG, &sh.pairs));
  PetscCall(H5WriteAttribute(tmp, f, "history_size", H5T_NATIVE_LLONG, &sh.history));
  PetscCall(H5WriteAttribute(tmp, f, "stages", H5T_NATIVE_LLONG, &sh.stages));
  PetscCall(H5WriteAttribute(tmp, f, "mesh_checksum", H5T_NATIVE_DOUBLE, &cs));
  {
    char *opts = nullptr;
    PetscCall(PetscOptionsGetAll(nullptr, &opts));
    PetscCall(H5WriteString(tmp, f, "options", opts ? opts : ""));
    PetscCall(PetscFree(opts));
  }
  const double dbl[3] = {st.t, st.dt, st.dt_last};
  const long long ints[6] = {(long long)st.step, (long long)st.converged_states, (long long)st.easy,
                             (long long)st.cutbacks, (long long)st.newton, 0};
  const char *dnames[3] = {"t", "dt", "dt_last"};
  const char *inames[5] = {"step", "converged_states", "easy", "cutbacks", "newton"};
  for (int k = 0; k < 3; ++k) PetscCall(H5WriteAttribute(tmp, f, dnames[k], H5T_NATIVE_DOUBLE, &dbl[k]));
  for (int k = 0; k < 5; ++k) PetscCall(H5WriteAttribute(tmp, f, inames[k], H5T_NATIVE_LLONG, &ints[k]));
  PetscCall(VecGetArrayRead(Uc, &a));
  PetscCall(H5WriteNatural(tmp, order, f, "u_committed", Layout::Nodes, 3, a));
  PetscCall(VecRestoreArrayRead(Uc, &a));
  PetscCall(VecGetArrayRead(Up, &a));
  PetscCall(H5WriteNatural(tmp, order, f, "u_previous", Layout::Nodes, 3, a));
  PetscCall(VecRestoreArrayRead(Up, &a));
  if (sh.history > 0) PetscCall(H5WriteNatural(tmp, order, f, "history", Layout::Cells, (int)sh.history, P->history.data()));
  if (P->contact) {
    std::vector<double> cst(7 * P->contact->pairs.size());
    for (size_t k = 0; k < P->contact->pairs.size(); ++k) {
      const ContactState &c = P->contact->pairs[k].committed;
      for (int i = 0; i < 3; ++i) cst[7 * k + i] = c.g[i], cst[7 * k + 3 + i] = c.f[i];
      cst[7 * k + 6] = c.status;
    }
    PetscCall(H5WriteNatural(tmp, order, f, "contact_state", Layout::Pairs, 7, cst.data()));
  }
  if (P->scene.state_get) {
    std::vector<double> v;
    P->scene.state_get(P->scene.report_ctx, &v);
    PetscCall(H5WriteRows(tmp, f, "scene_state", H5T_NATIVE_DOUBLE, v.size(), 1, 0, P->rank == 0 ? v.size() : 0,
                          v.data()));
  }
  PetscCheck(H5Fclose(f) >= 0, P->comm, PETSC_ERR_FILE_WRITE, "cannot close the checkpoint %s", tmp.c_str());
  PetscCallMPI(MPI_Barrier(P->comm));
  int ok = 1;
  if (P->rank == 0) {
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    ok = ec ? 0 : 1;
  }
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, P->comm));
  PetscCheck(ok, P->comm, PETSC_ERR_FILE_WRITE, "cannot rename %s to %s", tmp.c_str(), path.c_str());
  PetscFunctionReturn(0);
}

PetscErrorCode CheckpointPeekStep(MPI_Comm comm, const std::string &path, PetscInt *step) {
  long long s = -1;
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    hid_t f = -1;
    H5E_BEGIN_TRY { f = std::filesystem::exists(path) ? H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT) : -1; }
    H5E_END_TRY;
    if (f >= 0) {
      if (H5Aexists(f, "step") > 0) {
        hid_t a = H5Aopen(f, "step", H5P_DEFAULT);
        if (H5Aread(a, H5T_NATIVE_LLONG, &s) < 0) s = -1;
        H5Aclose(a);
      }
      H5Fclose(f);
    }
  }
  PetscCallMPI(MPI_Bcast(&s, 1, MPI_LONG_LONG, 0, comm));
  PetscCheck(s >= 0, comm, PETSC_ERR_FILE_READ,
             "-restart %s: missing, unreadable or not an etfe checkpoint (truncated or corrupt: use an older "
             "checkpoint or start again)", path.c_str());
  *step = (PetscInt)s;
  PetscFunctionReturn(0);
}

PetscErrorCode CheckpointRead(Problem *P, const std::string &path, StepperState *st, Vec Uc, Vec Up) {
  NaturalOrder order(P);
  PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCheck(std::filesystem::exists(path), P->comm, PETSC_ERR_FILE_OPEN, "-restart %s: no such checkpoint",
             path.c_str());
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  H5Pset_fapl_mpio(fapl, P->comm, MPI_INFO_NULL);
  hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl);
  H5Pclose(fapl);
  PetscCheck(f >= 0, P->comm, PETSC_ERR_FILE_READ,
             "-restart %s: not a readable HDF5 file (truncated or corrupt: use an older checkpoint)", path.c_str());
  std::string format, scene;
  PetscCall(H5ReadString(path, f, "format", &format));
  PetscCheck(format == "etfe-checkpoint-1", P->comm, PETSC_ERR_FILE_UNEXPECTED,
             "-restart %s: format \"%s\" is not an etfe checkpoint", path.c_str(), format.c_str());
  PetscCall(H5ReadString(path, f, "scene", &scene));
  PetscCheck(scene == P->scene.name, P->comm, PETSC_ERR_FILE_UNEXPECTED,
             "-restart %s: the checkpoint is of scene %s, this run is %s", path.c_str(), scene.c_str(),
             P->scene.name.c_str());
  const Shape sh = ProblemShape(P);
  Shape cp;
  double cs;
  PetscCall(H5ReadAttribute(path, f, "nodes", H5T_NATIVE_LLONG, &cp.nodes));
  PetscCall(H5ReadAttribute(path, f, "elements", H5T_NATIVE_LLONG, &cp.elements));
  PetscCall(H5ReadAttribute(path, f, "pairs", H5T_NATIVE_LLONG, &cp.pairs));
  PetscCall(H5ReadAttribute(path, f, "history_size", H5T_NATIVE_LLONG, &cp.history));
  PetscCall(H5ReadAttribute(path, f, "stages", H5T_NATIVE_LLONG, &cp.stages));
  PetscCall(H5ReadAttribute(path, f, "mesh_checksum", H5T_NATIVE_DOUBLE, &cs));
  PetscCheck(cp.nodes == sh.nodes && cp.elements == sh.elements && cs == MeshChecksum(P->scene.mesh), P->comm,
             PETSC_ERR_FILE_UNEXPECTED,
             "-restart %s: the checkpoint's mesh (%lld nodes, %lld elements) is not this run's (%lld nodes, %lld "
             "elements%s); restart with the options of the original run",
             path.c_str(), cp.nodes, cp.elements, sh.nodes, sh.elements,
             cp.nodes == sh.nodes && cp.elements == sh.elements ? ", different coordinates" : "");
  PetscCheck(cp.history == sh.history, P->comm, PETSC_ERR_FILE_UNEXPECTED,
             "-restart %s: the checkpoint's material keeps %lld history values per element, this one %lld "
             "(another -material_type?)", path.c_str(), cp.history, sh.history);
  PetscCheck(cp.pairs == sh.pairs && cp.stages == sh.stages, P->comm, PETSC_ERR_FILE_UNEXPECTED,
             "-restart %s: the checkpoint has %lld contact pairs and %lld stages, this run %lld and %lld",
             path.c_str(), cp.pairs, cp.stages, sh.pairs, sh.stages);
  double dbl[3];
  long long ints[5];
  const char *dnames[3] = {"t", "dt", "dt_last"};
  const char *inames[5] = {"step", "converged_states", "easy", "cutbacks", "newton"};
  for (int k = 0; k < 3; ++k) PetscCall(H5ReadAttribute(path, f, dnames[k], H5T_NATIVE_DOUBLE, &dbl[k]));
  for (int k = 0; k < 5; ++k) PetscCall(H5ReadAttribute(path, f, inames[k], H5T_NATIVE_LLONG, &ints[k]));
  st->t = dbl[0], st->dt = dbl[1], st->dt_last = dbl[2];
  st->step = ints[0], st->converged_states = ints[1], st->easy = ints[2], st->cutbacks = ints[3];
  st->newton = ints[4];
  PetscCall(VecGetArray(Uc, &a));
  PetscCall(H5ReadNatural(path, order, f, "u_committed", Layout::Nodes, 3, a));
  PetscCall(VecRestoreArray(Uc, &a));
  PetscCall(VecGetArray(Up, &a));
  PetscCall(H5ReadNatural(path, order, f, "u_previous", Layout::Nodes, 3, a));
  PetscCall(VecRestoreArray(Up, &a));
  if (sh.history > 0) PetscCall(H5ReadNatural(path, order, f, "history", Layout::Cells, (int)sh.history, P->history.data()));
  if (P->contact) {
    std::vector<double> cst(7 * P->contact->pairs.size());
    PetscCall(H5ReadNatural(path, order, f, "contact_state", Layout::Pairs, 7, cst.data()));
    for (size_t k = 0; k < P->contact->pairs.size(); ++k) {
      ContactState &c = P->contact->pairs[k].committed;
      for (int i = 0; i < 3; ++i) c.g[i] = cst[7 * k + i], c.f[i] = cst[7 * k + 3 + i];
      c.status = (int)cst[7 * k + 6];
      P->contact->pairs[k].trial = c;
    }
  }
  if (P->scene.state_set) {
    std::vector<double> v;
    P->scene.state_get(P->scene.report_ctx, &v);  // its size
    PetscCall(H5ReadRows(path, f, "scene_state", H5T_NATIVE_DOUBLE, v.size(), 1, 0, v.size(), v.data()));
    P->scene.state_set(P->scene.report_ctx, v);
  }
  H5Fclose(f);
  PetscFunctionReturn(0);
}

} // namespace etfe
