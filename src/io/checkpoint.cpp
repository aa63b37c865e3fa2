// Checkpoint/restart (see checkpoint.h).
#include "etfe/checkpoint.h"

#include <hdf5.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <sstream>
#include <vector>

#include "etfe/contact.h"
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

constexpr const char *kFormat = "etfe-checkpoint-2";  // -2: with data_checksum

// Options that may differ between the run that wrote a checkpoint and the one that continues it:
// how the equations are solved and what is written, never what they are. Everything else
// (scene, mesh, material, membrane, contact, schedule, -load_increments, scene options) is
// physics and must match.
bool OptionMayChange(const std::string &key) {
  static const char *prefixes[] = {
      "snes_", "ksp_", "pc_", "mat_", "sub_", "mg_", "output", "checkpoint_", "restart", "options_",
      "load_monitor", "load_stop_after", "load_max_cutbacks", "load_grow_after", "load_easy_iterations",
      "load_extrapolate", "load_tangent_predictor", "load_force_rtol", "membrane_tangent_", "mesh_file",
      "contact_probe_nodes", "saddle_history", "formfind_monitor", "log", "info", "help", "etfe_traceback",
      "memory_view", "malloc", "fp_trap", "on_error", "history", "viewer_", "objects_dump", "check_pointer",
      "scene_list", "vecscatter_", "sf_", "use_gpu_aware_mpi", "no_signal_handler"};
  for (const char *p : prefixes)
    if (key.compare(0, std::strlen(p), p) == 0) return true;
  return false;
}

// "-a 1 -b -c x" (PetscOptionsGetAll) -> {a: 1, b: "", c: x}. A token starting with '-' and a
// digit or '.' is a (negative) value, not a key.
std::map<std::string, std::string> ParseOptions(const std::string &all) {
  std::map<std::string, std::string> m;
  std::istringstream in(all);
  std::string tok, key;
  bool have_key = false;
  while (in >> tok) {
    const bool is_key = tok.size() > 1 && tok[0] == '-' && !(std::isdigit((unsigned char)tok[1]) || tok[1] == '.');
    if (is_key) {
      key = tok.substr(1);
      m[key] = "";
      have_key = true;
    } else if (have_key) {
      m[key] += (m[key].empty() ? "" : " ") + tok;
    }
  }
  return m;
}

// Physics options that differ between the checkpoint's run and this one, one per line.
std::string PhysicsDifferences(const std::string &then_all, const std::string &now_all) {
  auto then = ParseOptions(then_all), now = ParseOptions(now_all);
  std::string diff;
  auto add = [&](const std::string &k, const std::string *a, const std::string *b) {
    diff += "\n    -" + k + ": checkpoint " + (a ? (a->empty() ? "(set)" : *a) : "(not set)") + ", this run " +
            (b ? (b->empty() ? "(set)" : *b) : "(not set)");
  };
  for (auto &kv : then) {
    if (OptionMayChange(kv.first)) continue;
    auto it = now.find(kv.first);
    if (it == now.end()) add(kv.first, &kv.second, nullptr);
    else if (it->second != kv.second) add(kv.first, &kv.second, &it->second);
  }
  for (auto &kv : now)
    if (!OptionMayChange(kv.first) && !then.count(kv.first)) add(kv.first, nullptr, &kv.second);
  return diff;
}

uint64_t StringChecksum(const char *name, const std::string &s) {
  uint64_t h = 0;
  for (size_t i = 0; i < s.size(); ++i) h += ValueChecksum(name, (double)(unsigned char)s[i] + 256.0 * (double)i);
  return h;
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

PetscErrorCode CheckpointWrite(Problem *P, const std::string &path, const StepperState &st, Vec Uc, Vec Up,
                               const std::string &run_id) {
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
  uint64_t sum = 0;
  PetscCall(H5WriteString(tmp, f, "format", kFormat));
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
    sum += StringChecksum("options", opts ? opts : "");
    PetscCall(PetscFree(opts));
  }
  PetscCall(H5WriteString(tmp, f, "run_id", run_id));
  sum += StringChecksum("scene", P->scene.name) + ValueChecksum("mesh_checksum", cs) + StringChecksum("run_id", run_id);
  const double dbl[3] = {st.t, st.dt, st.dt_last};
  const long long ints[6] = {(long long)st.step, (long long)st.converged_states, (long long)st.easy,
                             (long long)st.cutbacks, (long long)st.newton, 0};
  const char *dnames[3] = {"t", "dt", "dt_last"};
  const char *inames[5] = {"step", "converged_states", "easy", "cutbacks", "newton"};
  for (int k = 0; k < 3; ++k) {
    PetscCall(H5WriteAttribute(tmp, f, dnames[k], H5T_NATIVE_DOUBLE, &dbl[k]));
    sum += ValueChecksum(dnames[k], dbl[k]);
  }
  for (int k = 0; k < 5; ++k) {
    PetscCall(H5WriteAttribute(tmp, f, inames[k], H5T_NATIVE_LLONG, &ints[k]));
    sum += ValueChecksum(inames[k], (double)ints[k]);
  }
  const long long shape_values[5] = {sh.nodes, sh.elements, sh.pairs, sh.history, sh.stages};
  for (long long v : shape_values) sum += ValueChecksum("shape", (double)v);
  PetscCall(VecGetArrayRead(Uc, &a));
  PetscCall(H5WriteNatural(tmp, order, f, "u_committed", Layout::Nodes, 3, a, false, &sum));
  PetscCall(VecRestoreArrayRead(Uc, &a));
  PetscCall(VecGetArrayRead(Up, &a));
  PetscCall(H5WriteNatural(tmp, order, f, "u_previous", Layout::Nodes, 3, a, false, &sum));
  PetscCall(VecRestoreArrayRead(Up, &a));
  if (sh.history > 0)
    PetscCall(H5WriteNatural(tmp, order, f, "history", Layout::Cells, (int)sh.history, P->history.data(), false, &sum));
  if (P->contact) {
    std::vector<double> cst(7 * P->contact->pairs.size());
    for (size_t k = 0; k < P->contact->pairs.size(); ++k) {
      const ContactState &c = P->contact->pairs[k].committed;
      for (int i = 0; i < 3; ++i) cst[7 * k + i] = c.g[i], cst[7 * k + 3 + i] = c.f[i];
      cst[7 * k + 6] = c.status;
    }
    PetscCall(H5WriteNatural(tmp, order, f, "contact_state", Layout::Pairs, 7, cst.data(), false, &sum));
  }
  if (P->observer.state_get) {
    std::vector<double> v;
    P->observer.state_get(P->observer.ctx, &v);
    PetscCall(H5WriteRows(tmp, f, "scene_state", H5T_NATIVE_DOUBLE, v.size(), 1, 0, P->rank == 0 ? v.size() : 0,
                          v.data()));
    for (size_t i = 0; i < v.size(); ++i) sum += ValueChecksum(("scene_state" + std::to_string(i)).c_str(), v[i]);
  }
  {
    const unsigned long long stored = sum;
    PetscCall(H5WriteAttribute(tmp, f, "data_checksum", H5T_NATIVE_ULLONG, &stored));
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

namespace {

// Opens a checkpoint (collective) and refuses it unless it is of this run: format, scene, mesh,
// material history, contact pairs, stages and every physics option (see OptionMayChange).
PetscErrorCode OpenChecked(Problem *P, const std::string &path, hid_t *file) {
  PetscFunctionBeginUser;
  int exists = 0;
  if (P->rank == 0) exists = std::filesystem::is_regular_file(path) ? 1 : 0;
  PetscCallMPI(MPI_Bcast(&exists, 1, MPI_INT, 0, P->comm));
  PetscCheck(exists, P->comm, PETSC_ERR_FILE_OPEN,
             "-restart %s: no such checkpoint (or not a regular file); nothing was changed", path.c_str());
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  H5Pset_fapl_mpio(fapl, P->comm, MPI_INFO_NULL);
  hid_t f = -1;
  H5E_BEGIN_TRY { f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl); }
  H5E_END_TRY;
  H5Pclose(fapl);
  PetscCheck(f >= 0, P->comm, PETSC_ERR_FILE_READ,
             "-restart %s: not a readable HDF5 file (truncated or corrupt checkpoint: use an older one or start "
             "again); nothing was changed", path.c_str());
  *file = f;
  std::string format, scene, options;
  PetscCall(H5ReadString(path, f, "format", &format));
  PetscCheck(format == kFormat, P->comm, PETSC_ERR_FILE_UNEXPECTED,
             "-restart %s: format \"%s\" is not a checkpoint this version reads (%s; one without a data "
             "checksum was written by an older etfe): start the run again", path.c_str(), format.c_str(), kFormat);
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
  PetscCall(H5ReadString(path, f, "options", &options));
  {
    char *now = nullptr;
    PetscCall(PetscOptionsGetAll(nullptr, &now));
    const std::string diff = PhysicsDifferences(options, now ? now : "");
    PetscCall(PetscFree(now));
    PetscCheck(diff.empty(), P->comm, PETSC_ERR_FILE_UNEXPECTED,
               "-restart %s: this run's physics differs from the checkpoint's run:%s\n  A restart continues the same "
               "history: give the original options (only solver, output and checkpoint options -snes_* -ksp_* "
               "-pc_* -mat_* -output_* -checkpoint_* -load_monitor/stop_after/max_cutbacks/force_rtol/... may "
               "change), or start a new run", path.c_str(), diff.c_str());
  }
  PetscFunctionReturn(0);
}

// Reads the state into the problem, U_committed and U_previous, and refuses the file when the
// checksum of what was read differs from the stored one.
PetscErrorCode ReadState(Problem *P, const std::string &path, hid_t f, StepperState *st, Vec Uc, Vec Up) {
  NaturalOrder order(P);
  PetscScalar *a;
  uint64_t sum = 0;
  unsigned long long stored = 0;
  PetscFunctionBeginUser;
  const Shape sh = ProblemShape(P);
  std::string scene, options, run_id;
  double cs;
  PetscCall(H5ReadString(path, f, "scene", &scene));
  PetscCall(H5ReadString(path, f, "options", &options));
  PetscCall(H5ReadString(path, f, "run_id", &run_id));
  PetscCall(H5ReadAttribute(path, f, "mesh_checksum", H5T_NATIVE_DOUBLE, &cs));
  sum += StringChecksum("options", options) + StringChecksum("scene", scene) + ValueChecksum("mesh_checksum", cs) +
         StringChecksum("run_id", run_id);
  double dbl[3];
  long long ints[5];
  const char *dnames[3] = {"t", "dt", "dt_last"};
  const char *inames[5] = {"step", "converged_states", "easy", "cutbacks", "newton"};
  for (int k = 0; k < 3; ++k) {
    PetscCall(H5ReadAttribute(path, f, dnames[k], H5T_NATIVE_DOUBLE, &dbl[k]));
    sum += ValueChecksum(dnames[k], dbl[k]);
  }
  for (int k = 0; k < 5; ++k) {
    PetscCall(H5ReadAttribute(path, f, inames[k], H5T_NATIVE_LLONG, &ints[k]));
    sum += ValueChecksum(inames[k], (double)ints[k]);
  }
  const long long shape_values[5] = {sh.nodes, sh.elements, sh.pairs, sh.history, sh.stages};
  for (long long v : shape_values) sum += ValueChecksum("shape", (double)v);
  st->t = dbl[0], st->dt = dbl[1], st->dt_last = dbl[2];
  st->step = ints[0], st->converged_states = ints[1], st->easy = ints[2], st->cutbacks = ints[3];
  st->newton = ints[4];
  PetscCall(VecGetArray(Uc, &a));
  PetscCall(H5ReadNatural(path, order, f, "u_committed", Layout::Nodes, 3, a, &sum));
  PetscCall(VecRestoreArray(Uc, &a));
  PetscCall(VecGetArray(Up, &a));
  PetscCall(H5ReadNatural(path, order, f, "u_previous", Layout::Nodes, 3, a, &sum));
  PetscCall(VecRestoreArray(Up, &a));
  if (sh.history > 0)
    PetscCall(H5ReadNatural(path, order, f, "history", Layout::Cells, (int)sh.history, P->history.data(), &sum));
  if (P->contact) {
    std::vector<double> cst(7 * P->contact->pairs.size());
    PetscCall(H5ReadNatural(path, order, f, "contact_state", Layout::Pairs, 7, cst.data(), &sum));
    for (size_t k = 0; k < P->contact->pairs.size(); ++k) {
      ContactState &c = P->contact->pairs[k].committed;
      for (int i = 0; i < 3; ++i) c.g[i] = cst[7 * k + i], c.f[i] = cst[7 * k + 3 + i];
      c.status = (int)cst[7 * k + 6];
      P->contact->pairs[k].trial = c;
    }
  }
  if (P->observer.state_set) {
    std::vector<double> v;
    P->observer.state_get(P->observer.ctx, &v);  // its size
    PetscCall(H5ReadRows(path, f, "scene_state", H5T_NATIVE_DOUBLE, v.size(), 1, 0, v.size(), v.data()));
    for (size_t i = 0; i < v.size(); ++i) sum += ValueChecksum(("scene_state" + std::to_string(i)).c_str(), v[i]);
    P->observer.state_set(P->observer.ctx, v);
  }
  PetscCall(H5ReadAttribute(path, f, "data_checksum", H5T_NATIVE_ULLONG, &stored));
  PetscCheck((uint64_t)stored == sum, P->comm, PETSC_ERR_FILE_UNEXPECTED,
             "-restart %s: the checkpoint's data do not match its checksum (the file was changed or damaged "
             "after it was written): use an older checkpoint or start again", path.c_str());
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode CheckpointValidate(Problem *P, const std::string &path, PetscInt *step, std::string *run_id) {
  hid_t f = -1;
  Vec Uc, Up;
  StepperState st;
  PetscFunctionBeginUser;
  PetscCall(OpenChecked(P, path, &f));
  // Read everything (the checksum needs it) into scratch, then put the problem's state back.
  const std::vector<double> history = P->history;
  std::vector<ContactPair> pairs;
  if (P->contact) pairs = P->contact->pairs;
  std::vector<double> scene_state;
  if (P->observer.state_get) P->observer.state_get(P->observer.ctx, &scene_state);
  PetscCall(VecDuplicate(P->U, &Uc));
  PetscCall(VecDuplicate(P->U, &Up));
  PetscErrorCode ierr = ReadState(P, path, f, &st, Uc, Up);
  P->history = history;
  if (P->contact) P->contact->pairs = pairs;
  if (P->observer.state_set) P->observer.state_set(P->observer.ctx, scene_state);
  H5Fclose(f);
  PetscCall(VecDestroy(&Uc));
  PetscCall(VecDestroy(&Up));
  PetscCall(ierr);
  *step = st.step;
  {
    hid_t g = -1;
    PetscCall(OpenChecked(P, path, &g));
    PetscErrorCode e2 = H5ReadString(path, g, "run_id", run_id);
    H5Fclose(g);
    PetscCall(e2);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode CheckpointRead(Problem *P, const std::string &path, StepperState *st, Vec Uc, Vec Up) {
  hid_t f = -1;
  PetscFunctionBeginUser;
  PetscCall(OpenChecked(P, path, &f));
  PetscErrorCode ierr = ReadState(P, path, f, st, Uc, Up);
  H5Fclose(f);
  PetscCall(ierr);
  PetscFunctionReturn(0);
}

} // namespace etfe
