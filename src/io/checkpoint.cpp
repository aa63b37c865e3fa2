// Checkpoint/restart (see checkpoint.h).
#include "etfe/io/checkpoint.h"

#include <fcntl.h>
#include <hdf5.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <vector>

#include "checkpoint_branch.h"
#include "checkpoint_compare.h"
#include "etfe/assembly/assembly.h"
#include "etfe/io/h5io.h"
#include "etfe/base/log_events.h"
#include "etfe/base/rank0.h"

namespace etfe {

namespace {

constexpr const char *kFormat = "etfe-checkpoint-3";  // -3: mesh and physics fingerprints

uint64_t StringChecksum(const char *name, const std::string &s) {
  uint64_t h = 0;
  for (size_t i = 0; i < s.size(); ++i) h += ValueChecksum(name, (double)(unsigned char)s[i] + 256.0 * (double)i);
  return h;
}

// A 64-bit value as two exactly representable halves.
uint64_t FingerprintChecksum(const char *name, uint64_t v) {
  return ValueChecksum(name, (double)(v >> 32)) + 3 * ValueChecksum(name, (double)(v & 0xffffffffULL));
}


// The scene's restart state (a few values, the same on every rank).
uint64_t SceneStateChecksum(const std::vector<double> &v) {
  uint64_t h = 0;
  for (size_t i = 0; i < v.size(); ++i) h += ValueChecksum(("scene_state" + std::to_string(i)).c_str(), v[i]);
  return h;
}

const char *const kDoubles[3] = {"t", "dt", "dt_last"};
const char *const kInts[5] = {"step", "converged_states", "easy", "cutbacks", "newton"};
const char *const kShape[5] = {"nodes", "elements", "pairs", "history_size", "stages"};

// What the header contributes to data_checksum (the same sum on writing and reading).
uint64_t HeaderChecksum(const std::string &scene, const std::string &options, const std::string &run_id,
                        uint64_t mesh, uint64_t physics, const double dbl[3], const long long ints[5],
                        const long long shape[5]) {
  uint64_t sum = StringChecksum("options", options) + StringChecksum("scene", scene) +
                 StringChecksum("run_id", run_id) + FingerprintChecksum("mesh_fingerprint", mesh) +
                 FingerprintChecksum("physics_fingerprint", physics);
  for (int k = 0; k < 3; ++k) sum += ValueChecksum(kDoubles[k], dbl[k]);
  for (int k = 0; k < 5; ++k) sum += ValueChecksum(kInts[k], (double)ints[k]);
  for (int k = 0; k < 5; ++k) sum += ValueChecksum("shape", (double)shape[k]);
  return sum;
}

struct Shape {
  long long nodes, elements, pairs, history, stages;
};

// The rows of Layout::Pairs (contact pairs; 0 without a term that numbers pairs).
PetscInt PairRows(const Problem *P) {
  PetscInt n = 0, first;
  std::vector<PetscInt> ids;
  for (const auto &term : P->terms)
    if (term->PairRows(&n, &first, &ids)) break;
  return n;
}

Shape ProblemShape(const Problem *P) {
  return {(long long)P->mesh.num_nodes_global, (long long)P->mesh.num_elements_global,
          (long long)PairRows(P), (long long)P->history_size,
          (long long)P->scene.NumStages()};
}

// The datasets every checkpoint of this shape has and their columns; rows: nodes or elements.
// The terms' datasets: TermCheckpointDatasets.
struct Dataset {
  const char *name;
  int shape_index;  // into Shape: 0 nodes, 1 elements, 2 pairs
  long long cols;
};

std::vector<Dataset> Datasets(const long long shape[5]) {
  std::vector<Dataset> d = {{"u_committed", 0, 3}, {"u_previous", 0, 3}};
  if (shape[3] > 0) d.push_back({"history", 1, shape[3]});
  return d;
}

// Rank 0 alone, errors silenced: the dataset `name` of f if it is nrows x cols doubles.
bool ReadRowsChecked(hid_t f, const char *name, hsize_t nrows, hsize_t cols, std::vector<double> *v) {
  hid_t d = H5Dopen2(f, name, H5P_DEFAULT);
  if (d < 0) return false;
  hid_t sp = H5Dget_space(d);
  hsize_t dims[2] = {0, 1};
  const int nd = sp >= 0 ? H5Sget_simple_extent_ndims(sp) : -1;
  bool good = (nd == 1 || nd == 2) && H5Sget_simple_extent_dims(sp, dims, nullptr) >= 0 && dims[0] == nrows &&
              dims[1] == cols;
  if (good) {
    v->resize(nrows * cols);
    good = v->empty() || H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v->data()) >= 0;
  }
  if (sp >= 0) H5Sclose(sp);
  H5Dclose(d);
  return good;
}

// Rank 0 alone reads the whole file as stored and compares it with its checksum, before anything
// in it is trusted (and before the ranks read it together). Returns "" or why it is refused.
std::string VerifyIntegrity(const std::string &path) {
  std::string why;
  H5E_BEGIN_TRY {
    hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    auto str = [&](const char *name, std::string *v) {
      hid_t a = H5Aopen(f, name, H5P_DEFAULT);
      if (a < 0) return false;
      hid_t t = H5Aget_type(a);
      const size_t n = t >= 0 ? H5Tget_size(t) : 0;
      std::vector<char> buf(n + 1, 0);
      const bool good = t >= 0 && H5Tget_class(t) == H5T_STRING && H5Aread(a, t, buf.data()) >= 0;
      if (t >= 0) H5Tclose(t);
      H5Aclose(a);
      *v = buf.data();
      return good;
    };
    auto num = [&](const char *name, hid_t type, void *v) {
      hid_t a = H5Aopen(f, name, H5P_DEFAULT);
      const bool good = a >= 0 && H5Aread(a, type, v) >= 0;
      if (a >= 0) H5Aclose(a);
      return good;
    };
    auto rows = [&](const char *name, hsize_t nrows, hsize_t cols, std::vector<double> *v) {
      return ReadRowsChecked(f, name, nrows, cols, v);
    };
    std::string format, scene, options, run_id;
    uint64_t mesh = 0, physics = 0;
    unsigned long long stored = 0;
    double dbl[3];
    long long ints[5], shape[5];
    bool good = f >= 0;
    if (!good) why = "not a readable HDF5 file (truncated or corrupt)";
    else if (!str("format", &format)) why = "no format attribute (corrupt, or not an etfe checkpoint)";
    else if (format != kFormat)
      why = "format \"" + format + "\" is not " + kFormat +
            (format.rfind("etfe-checkpoint-", 0) == 0 ? " (written by an older etfe: start the run again)" : "");
    else {
      good = str("scene", &scene) && str("options", &options) && str("run_id", &run_id) &&
             num("mesh_fingerprint", H5T_NATIVE_UINT64, &mesh) &&
             num("physics_fingerprint", H5T_NATIVE_UINT64, &physics) &&
             num("data_checksum", H5T_NATIVE_ULLONG, &stored);
      for (int k = 0; k < 3; ++k) good = good && num(kDoubles[k], H5T_NATIVE_DOUBLE, &dbl[k]);
      for (int k = 0; k < 5; ++k) good = good && num(kInts[k], H5T_NATIVE_LLONG, &ints[k]);
      for (int k = 0; k < 5; ++k) good = good && num(kShape[k], H5T_NATIVE_LLONG, &shape[k]);
      uint64_t sum = good ? HeaderChecksum(scene, options, run_id, mesh, physics, dbl, ints, shape) : 0;
      std::vector<double> v;
      for (const Dataset &d : good ? Datasets(shape) : std::vector<Dataset>()) {
        good = good && rows(d.name, (hsize_t)shape[d.shape_index], (hsize_t)d.cols, &v);
        if (good) DataChecksum(PETSC_COMM_SELF, d.name, 0, shape[d.shape_index], (int)d.cols, v.data(), &sum);
      }
      // The terms' blocks (WriteFile writes what the problem's terms give): a term's is
      // there when the run had the term, and the pairs' whenever the checkpoint has pairs.
      std::vector<const char *> replicated = {"scene_state"};
      for (const TermDatasetInfo &t : TermCheckpointDatasets()) {
        if (t.replicated) {
          replicated.push_back(t.name);
          continue;
        }
        const int index = t.layout == Layout::Pairs ? 2 : t.layout == Layout::Cells ? 1 : 0;
        const bool always = t.layout == Layout::Pairs && shape[2] > 0;
        if (!good || (!always && H5Lexists(f, t.name, H5P_DEFAULT) <= 0)) continue;
        good = rows(t.name, (hsize_t)shape[index], (hsize_t)t.components, &v);
        if (good) DataChecksum(PETSC_COMM_SELF, t.name, 0, shape[index], t.components, v.data(), &sum);
      }
      if (good) good = LoadPathVerify(f, &sum);  // -restart_branch's fingerprints, when there
      for (const char *state : replicated) {
        if (!good || H5Lexists(f, state, H5P_DEFAULT) <= 0) continue;
        hid_t d = H5Dopen2(f, state, H5P_DEFAULT);
        hid_t sp = d >= 0 ? H5Dget_space(d) : -1;
        const hssize_t n = sp >= 0 ? H5Sget_simple_extent_npoints(sp) : -1;
        if (sp >= 0) H5Sclose(sp);
        if (d >= 0) H5Dclose(d);
        good = n >= 0 && rows(state, (hsize_t)n, 1, &v);
        if (good) sum += SceneStateChecksum(v);
      }
      if (!good) why = "an attribute or dataset is missing or cannot be read (truncated or corrupt)";
      else if (sum != (uint64_t)stored) why = "its contents do not match its checksum (changed or damaged after it was written)";
    }
    if (f >= 0) H5Fclose(f);
  }
  H5E_END_TRY;
  return why;
}

// The checkpoint's contents, written collectively to `tmp`; its checksum adds up as it goes.
PetscErrorCode WriteFile(Problem *P, const std::string &tmp, const StepperState &st, Vec Uc, Vec Up,
                         const std::string &run_id) {
  NaturalOrder order(P);
  const PetscScalar *a;
  PetscFunctionBeginUser;
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  H5Pset_fapl_mpio(fapl, P->comm, MPI_INFO_NULL);
  H5Pset_libver_bounds(fapl, H5F_LIBVER_LATEST, H5F_LIBVER_LATEST);  // HDF5's own metadata checksums
  hid_t f = H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  H5Pclose(fapl);
  PetscCheck(f >= 0, P->comm, PETSC_ERR_FILE_OPEN, "cannot create the checkpoint %s (check -checkpoint_file)",
             tmp.c_str());
  const Shape sh = ProblemShape(P);
  const long long shape[5] = {sh.nodes, sh.elements, sh.pairs, sh.history, sh.stages};
  const uint64_t mesh = P->scene_mesh_fingerprint, physics = PhysicsFingerprint(P);
  const double dbl[3] = {st.t, st.dt, st.dt_last};
  const long long ints[5] = {(long long)st.step, (long long)st.converged_states, (long long)st.easy,
                             (long long)st.cutbacks, (long long)st.newton};
  std::string options;
  PetscCall(OptionsAsLines(&options));
  uint64_t sum = HeaderChecksum(P->scene.name, options, run_id, mesh, physics, dbl, ints, shape);
  PetscCall(H5WriteString(tmp, f, "format", kFormat));
  PetscCall(H5WriteString(tmp, f, "scene", P->scene.name));
  PetscCall(H5WriteString(tmp, f, "options", options));
  PetscCall(H5WriteString(tmp, f, "run_id", run_id));
  PetscCall(H5WriteAttribute(tmp, f, "mesh_fingerprint", H5T_NATIVE_UINT64, &mesh));
  PetscCall(H5WriteAttribute(tmp, f, "physics_fingerprint", H5T_NATIVE_UINT64, &physics));
  for (int k = 0; k < 5; ++k) PetscCall(H5WriteAttribute(tmp, f, kShape[k], H5T_NATIVE_LLONG, &shape[k]));
  for (int k = 0; k < 3; ++k) PetscCall(H5WriteAttribute(tmp, f, kDoubles[k], H5T_NATIVE_DOUBLE, &dbl[k]));
  for (int k = 0; k < 5; ++k) PetscCall(H5WriteAttribute(tmp, f, kInts[k], H5T_NATIVE_LLONG, &ints[k]));
  PetscCall(VecGetArrayRead(Uc, &a));
  PetscCall(H5WriteNatural(tmp, order, f, "u_committed", Layout::Nodes, 3, a, false, &sum));
  PetscCall(VecRestoreArrayRead(Uc, &a));
  PetscCall(VecGetArrayRead(Up, &a));
  PetscCall(H5WriteNatural(tmp, order, f, "u_previous", Layout::Nodes, 3, a, false, &sum));
  PetscCall(VecRestoreArrayRead(Up, &a));
  if (sh.history > 0)
    PetscCall(H5WriteNatural(tmp, order, f, "history", Layout::Cells, (int)sh.history, P->history.data(), false, &sum));
  PetscCall(LoadPathWrite(P, tmp, f, &sum));
  if (P->observer.state_get) {
    std::vector<double> v;
    P->observer.state_get(P->observer.ctx, &v);
    PetscCall(H5WriteRows(tmp, f, "scene_state", H5T_NATIVE_DOUBLE, v.size(), 1, 0, P->rank == 0 ? v.size() : 0,
                          v.data()));
    sum += SceneStateChecksum(v);
  }
  // The physics terms' committed state (contact_state, layer_pairs, chamber_state, ...): rows in
  // the scene's order, or the same values on every rank written once.
  std::vector<TermData> blocks;
  for (const auto &term : P->terms) PetscCall(term->State(*P, &blocks));
  for (const TermData &b : blocks) {
    if (b.replicated) {
      PetscCall(H5WriteRows(tmp, f, b.name.c_str(), H5T_NATIVE_DOUBLE, b.values.size(), 1, 0,
                            P->rank == 0 ? b.values.size() : 0, b.values.data()));
      sum += SceneStateChecksum(b.values);
    } else {
      PetscCall(H5WriteNatural(tmp, order, f, b.name.c_str(), b.layout, b.components, b.values.data(), false, &sum));
    }
  }
  {
    const unsigned long long stored = sum;
    PetscCall(H5WriteAttribute(tmp, f, "data_checksum", H5T_NATIVE_ULLONG, &stored));
  }
  // Closing writes what HDF5 still holds; on a full disk that fails on some ranks only.
  int closed = H5FcloseWritten(f) >= 0, all_closed;
  PetscCallMPI(MPI_Allreduce(&closed, &all_closed, 1, MPI_INT, MPI_MIN, P->comm));
  PetscCheck(all_closed, P->comm, PETSC_ERR_FILE_WRITE, "cannot write the checkpoint %s (disk full?)", tmp.c_str());
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode CheckpointOptionsFromCommandLine(MPI_Comm comm, const std::string &results_stem, CheckpointOptions *o) {
  PetscFunctionBeginUser;
  // Beside the results and named after them, so runs with their own -output_file never share
  // (and overwrite) one checkpoint.
  std::snprintf(o->file, sizeof o->file, "%s.checkpoint.h5", results_stem.c_str());
  PetscOptionsBegin(comm, nullptr, "Checkpoint and restart", "Checkpoint");
  PetscCall(PetscOptionsInt("-checkpoint_every", "Write a checkpoint every n increments (0: only at -load_stop_after, stage ends, -checkpoint_every_s and "
                            "signals)",
                            "", o->every, &o->every, nullptr));
  PetscCall(PetscOptionsReal("-checkpoint_every_s",
                             "Also write a checkpoint when this many seconds of wall time have passed since the last "
                             "one (0: never)",
                             "", o->every_s, &o->every_s, nullptr));
  PetscCall(PetscOptionsBool("-checkpoint_stage_end",
                             "Write a checkpoint at the end of every stage of the schedule (when results are written)",
                             "", o->stage_end, &o->stage_end, nullptr));
  PetscCall(PetscOptionsString("-checkpoint_file", "Checkpoint file (HDF5; default <-output_file stem>.checkpoint.h5)",
                               "", o->file, o->file, sizeof o->file, nullptr));
  PetscCall(PetscOptionsString("-restart",
                               "Continue the load history from this checkpoint (only solver, output and monitor "
                               "options may differ from the run that wrote it)",
                               "", o->restart, o->restart, sizeof o->restart, nullptr));
  PetscOptionsEnd();
  PetscCheck(o->every >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-checkpoint_every %" PetscInt_FMT " must be >= 0",
             o->every);
  PetscCheck(o->every_s >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-checkpoint_every_s %g: use seconds >= 0 (0: never)",
             (double)o->every_s);
  PetscFunctionReturn(0);
}

PetscErrorCode CheckpointCheckWritable(MPI_Comm comm, const CheckpointOptions &o) {
  PetscMPIInt rank;
  int err = 0;
  std::string dir;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    std::error_code ec;
    const auto parent = std::filesystem::path(o.file).parent_path();
    dir = parent.empty() ? "." : parent.string();
    std::filesystem::create_directories(dir, ec);
    // A file of its own, beside where the checkpoint's .tmp will go; written, synced, removed.
    const std::string probe = std::string(o.file) + ".writetest." + std::to_string((long long)getpid());
    const int fd = open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
    if (fd < 0) err = errno;
    else {
      if (write(fd, "x", 1) != 1 || fsync(fd) != 0) err = errno ? errno : EIO;
      close(fd);
      unlink(probe.c_str());
    }
  }
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, comm));
  errno = err;  // the error exit reads it (a full disk is the system's failure, not the input's)
  PetscCheck(!err, comm, PETSC_ERR_FILE_OPEN,
             "-checkpoint_file %s: cannot write in its directory %s (%s); a checkpoint would fail only after the "
             "work before it. Give -checkpoint_file in a writable directory (or an -output_file there: the "
             "checkpoint goes beside it)",
             o.file, rank == 0 ? dir.c_str() : "(its directory)", std::strerror(err));
  PetscFunctionReturn(0);
}

PetscErrorCode CheckpointWrite(Problem *P, const std::string &path, const StepperState &st, Vec Uc, Vec Up,
                               const std::string &run_id) {
  const std::string tmp = path + ".tmp";
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(LogEvents().checkpoint, 0, 0, 0, 0));
  if (P->rank == 0) {
    std::error_code ec;
    auto dir = std::filesystem::path(path).parent_path();
    if (!dir.empty()) std::filesystem::create_directories(dir, ec);
  }
  PetscCallMPI(MPI_Barrier(P->comm));
  const PetscErrorCode ierr = WriteFile(P, tmp, st, Uc, Up, run_id);
  if (ierr) {
    // Disk full or an I/O error: the previous checkpoint stays; its partial successor goes.
    std::error_code ec;
    if (P->rank == 0) std::filesystem::remove(tmp, ec);
    PetscCall(ierr);
  }
  // On disk before it replaces the previous checkpoint: a crash leaves one or the other.
  int ok = 1;
  if (P->rank == 0) {
    int fd = open(tmp.c_str(), O_RDONLY);
    ok = fd >= 0 && fsync(fd) == 0;
    if (fd >= 0) close(fd);
    std::error_code ec;
    if (ok) std::filesystem::rename(tmp, path, ec);
    ok = ok && !ec;
    const auto dir = std::filesystem::path(path).parent_path();
    fd = open(dir.empty() ? "." : dir.c_str(), O_RDONLY);
    if (fd >= 0) fsync(fd), close(fd);
  }
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, P->comm));
  PetscCheck(ok, P->comm, PETSC_ERR_FILE_WRITE, "cannot sync and rename %s to %s (the previous checkpoint is kept)",
             tmp.c_str(), path.c_str());
  PetscCall(PetscLogEventEnd(LogEvents().checkpoint, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

namespace {

// Opens a checkpoint (collective) and refuses it unless it is intact and of this run: checksum
// first (rank 0 reads the whole file), then scene, every physics option (see
// checkpoint_compare.cpp), mesh, material history, contact pairs, stages and what the options
// resolve to. A refusal changes nothing. A branch (-restart_branch) compares the loads only up to
// the checkpoint's load time, a stage end (checkpoint_compare.cpp).
PetscErrorCode OpenChecked(Problem *P, const std::string &path, hid_t *file, bool branch) {
  PetscFunctionBeginUser;
  std::string why;
  if (P->rank == 0) {
    std::error_code ec;
    why = std::filesystem::is_regular_file(path, ec) ? VerifyIntegrity(path) : "no such checkpoint (or not a regular file)";
  }
  PetscCall(Rank0Outcome(P->comm, why.empty(),
                         "-restart " + path + ": " + why +
                             ". Nothing was changed; restart from an older checkpoint or run again from the start",
                         PETSC_ERR_FILE_READ));
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  H5Pset_fapl_mpio(fapl, P->comm, MPI_INFO_NULL);
  hid_t f = -1;
  H5E_BEGIN_TRY { f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl); }
  H5E_END_TRY;
  H5Pclose(fapl);
  PetscCheck(f >= 0, P->comm, PETSC_ERR_FILE_READ, "-restart %s: cannot be opened by every rank; nothing was changed",
             path.c_str());
  *file = f;
  std::string scene, options, now;
  PetscCall(H5ReadString(path, f, "scene", &scene));
  PetscCheck(scene == P->scene.name, P->comm, PETSC_ERR_FILE_UNEXPECTED,
             "-restart %s: the checkpoint is of scene %s, this run is %s; nothing was changed", path.c_str(),
             scene.c_str(), P->scene.name.c_str());
  const Shape sh = ProblemShape(P);
  Shape cp;
  uint64_t mesh, physics;
  PetscCall(H5ReadAttribute(path, f, "nodes", H5T_NATIVE_LLONG, &cp.nodes));
  PetscCall(H5ReadAttribute(path, f, "elements", H5T_NATIVE_LLONG, &cp.elements));
  PetscCall(H5ReadAttribute(path, f, "pairs", H5T_NATIVE_LLONG, &cp.pairs));
  PetscCall(H5ReadAttribute(path, f, "history_size", H5T_NATIVE_LLONG, &cp.history));
  PetscCall(H5ReadAttribute(path, f, "stages", H5T_NATIVE_LLONG, &cp.stages));
  PetscCall(H5ReadAttribute(path, f, "mesh_fingerprint", H5T_NATIVE_UINT64, &mesh));
  PetscCall(H5ReadAttribute(path, f, "physics_fingerprint", H5T_NATIVE_UINT64, &physics));
  PetscCall(H5ReadString(path, f, "options", &options));
  PetscCall(OptionsAsLines(&now));
  std::string table = OptionDifferences(options, now, branch);
  const bool same_shape = cp.nodes == sh.nodes && cp.elements == sh.elements && cp.pairs == sh.pairs &&
                          cp.history == sh.history && (branch || cp.stages == sh.stages);
  if (mesh != P->scene_mesh_fingerprint)
    table += "\n    mesh: checkpoint " + std::to_string(cp.nodes) + " nodes, " + std::to_string(cp.elements) +
             " triangles; this run " + std::to_string(sh.nodes) + ", " + std::to_string(sh.elements) +
             (cp.nodes == sh.nodes && cp.elements == sh.elements ? " (other coordinates or groups)" : "");
  else if (table.empty() && !same_shape)
    table += "\n    the options agree, but the checkpoint has " + std::to_string(cp.history) +
             " history values per element, " + std::to_string(cp.pairs) + " contact pairs and " +
             std::to_string(cp.stages) + " stages, this run " + std::to_string(sh.history) + ", " +
             std::to_string(sh.pairs) + " and " + std::to_string(sh.stages);
  else if (table.empty() && branch)
    PetscCall(BranchDifferences(P, path, f, &table));
  else if (table.empty() && physics != PhysicsFingerprint(P))
    table += "\n    the options agree, but what they resolve to does not (schedules, supports, contact or material "
             "constants: another etfe build, or changed defaults?)";
  PetscCheck(table.empty() || !branch, P->comm, PETSC_ERR_FILE_UNEXPECTED,
             "-restart_branch %s: this run is no branch of the checkpoint's run:%s\n  Nothing was changed. A branch "
             "starts its own loads from the base state the checkpoint holds (a stage end): the model (-scene, -mesh_*, "
             "-material_*, -membrane_*, -contact_*, -layer_*) and what the options resolve to up to the checkpoint's "
             "load time (supports and their motions, loads, chambers, film) must be those of the base run (its "
             "options: h5dump -a options %s); only the stages after it may differ",
             path.c_str(), table.c_str(), path.c_str());
  PetscCheck(table.empty(), P->comm, PETSC_ERR_FILE_UNEXPECTED,
             "-restart %s: this run's physics differs from the checkpoint's run:%s\n  Nothing was changed. A restart "
             "continues the same history: give the options of that run (stored in the checkpoint: h5dump -a options "
             "%s); only solver, output and monitor options may change (-snes_*, -ksp_*, -pc_*, -mat_*, "
             "-load_force_rtol, -load_max_cutbacks, -load_max_it, -output*, -checkpoint_*, -load_monitor, -load_stop_after, ...)",
             path.c_str(), table.c_str(), path.c_str());
  PetscFunctionReturn(0);
}

// Reads the state into the problem, U_committed and U_previous (OpenChecked has verified the
// whole file against its checksum).
PetscErrorCode ReadState(Problem *P, const std::string &path, hid_t f, StepperState *st, Vec Uc, Vec Up) {
  NaturalOrder order(P);
  PetscScalar *a;
  PetscFunctionBeginUser;
  const Shape sh = ProblemShape(P);
  double dbl[3];
  long long ints[5];
  for (int k = 0; k < 3; ++k) PetscCall(H5ReadAttribute(path, f, kDoubles[k], H5T_NATIVE_DOUBLE, &dbl[k]));
  for (int k = 0; k < 5; ++k) PetscCall(H5ReadAttribute(path, f, kInts[k], H5T_NATIVE_LLONG, &ints[k]));
  st->t = dbl[0], st->dt = dbl[1], st->dt_last = dbl[2];
  st->step = ints[0], st->converged_states = ints[1], st->easy = ints[2], st->cutbacks = ints[3];
  st->newton = ints[4];
  PetscCall(VecGetArray(Uc, &a));
  PetscCall(H5ReadNatural(path, order, f, "u_committed", Layout::Nodes, 3, a));
  PetscCall(VecRestoreArray(Uc, &a));
  PetscCall(VecGetArray(Up, &a));
  PetscCall(H5ReadNatural(path, order, f, "u_previous", Layout::Nodes, 3, a));
  PetscCall(VecRestoreArray(Up, &a));
  if (sh.history > 0)
    PetscCall(H5ReadNatural(path, order, f, "history", Layout::Cells, (int)sh.history, P->history.data()));
  if (P->observer.state_set) {
    std::vector<double> v;
    P->observer.state_get(P->observer.ctx, &v);  // its size
    PetscCall(H5ReadRows(path, f, "scene_state", H5T_NATIVE_DOUBLE, v.size(), 1, 0, v.size(), v.data()));
    P->observer.state_set(P->observer.ctx, v);
  }
  // Each term's blocks as its State gives them now (names, layouts and sizes), read over.
  for (auto &term : P->terms) {
    std::vector<TermData> blocks;
    PetscCall(term->State(*P, &blocks));
    for (TermData &b : blocks) {
      if (b.replicated)
        PetscCall(H5ReadRows(path, f, b.name.c_str(), H5T_NATIVE_DOUBLE, b.values.size(), 1, 0, b.values.size(),
                             b.values.data()));
      else
        PetscCall(H5ReadNatural(path, order, f, b.name.c_str(), b.layout, b.components, b.values.data()));
    }
    PetscCall(term->Restore(*P, blocks));
  }
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode CheckpointValidate(Problem *P, const std::string &path, PetscInt *step, std::string *run_id,
                                  std::string *results_file, bool branch) {
  hid_t f = -1;
  long long s = -1;
  std::string options;
  PetscFunctionBeginUser;
  PetscCall(OpenChecked(P, path, &f, branch));
  PetscErrorCode ierr = H5ReadString(path, f, "run_id", run_id);
  if (!ierr) ierr = H5ReadAttribute(path, f, "step", H5T_NATIVE_LLONG, &s);
  if (!ierr && results_file) ierr = H5ReadString(path, f, "options", &options);
  H5Fclose(f);
  PetscCall(ierr);
  *step = (PetscInt)s;
  if (results_file) {  // the options are one "-name value" per line (OptionsAsLines)
    *results_file = "results/" + P->scene.name + "/" + P->scene.name + ".h5";
    std::istringstream in(options);
    for (std::string line; std::getline(in, line);)
      if (line.rfind("-output_file ", 0) == 0) *results_file = line.substr(13);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode CheckpointRead(Problem *P, const std::string &path, StepperState *st, Vec Uc, Vec Up, bool branch) {
  hid_t f = -1;
  PetscFunctionBeginUser;
  PetscCall(OpenChecked(P, path, &f, branch));
  PetscErrorCode ierr = ReadState(P, path, f, st, Uc, Up);
  H5Fclose(f);
  PetscCall(ierr);
  PetscFunctionReturn(0);
}

PetscErrorCode CheckpointFingerprintScene(MPI_Comm comm, const SceneSpec &scene, Problem *P) {
  std::uint64_t v[2] = {0, 0};
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) v[0] = MeshFingerprint(scene.mesh), v[1] = ScenePhysicsState(scene, P->thickness, P->min_area_ratio);
  PetscCallMPI(MPI_Bcast(v, 2, MPI_UINT64_T, 0, comm));
  P->load_path_states.assign((size_t)scene.NumStages() + 1, 0);  // NumStages: the same on every rank
  if (rank == 0) P->load_path_states = LoadPathStates(scene, P->thickness, P->min_area_ratio, P->clock);
  PetscCallMPI(MPI_Bcast(P->load_path_states.data(), (int)P->load_path_states.size(), MPI_UINT64_T, 0, comm));
  P->scene_mesh_fingerprint = v[0];
  P->scene_physics_state = v[1];
  PetscFunctionReturn(0);
}

} // namespace etfe
