// The HDF5 results file (its fields: include/etfe/io/output_fields.h; layout: docs/results.md) and
// its life: creation, steps, status, continuation after a restart. Fields live in PETSc order on
// their owning ranks; a VecScatter per layout brings them to the scene's ("natural") order in
// contiguous row blocks, which every rank writes as a hyperslab of one collective dataset.
#include <hdf5.h>
#include <petscvec.h>
#include <sys/statvfs.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>
#include <sstream>
#include <map>
#include <memory>
#include <utility>

#include "etfe/assembly/assembly.h"
#include "etfe/contact/contact.h"
#include "etfe/io/h5io.h"
#include "etfe/base/log_events.h"
#include "etfe/io/output.h"
#include "etfe/io/output_fields.h"
#include "etfe/io/writer_identity.h"
#include "xdmf.h"

namespace etfe {

struct OutputFile {
  Problem *problem = nullptr;
  std::string path;
  XdmfIndex xdmf;
  std::vector<const OutputField *> step_fields;  // the rows of every step of this run
  hid_t file = -1;
  std::vector<std::pair<PetscInt, double>> steps;  // written steps (step, time)
  std::unique_ptr<NaturalOrder> order;
  PetscInt every = 1;
  std::string run_id;  // the same in the results file and the checkpoints of one load history
  std::string steps_lost;  // what a restart could not keep (-output_allow_lost_steps); "" if nothing
};

// The file an error exit must mark as failed (see OutputAbandon).
static OutputFile *g_open_output = nullptr;

namespace {

// The rows of the field table this run writes: those of the file's creation (open) or those of
// every step (with a plastic material, wrinkling or contact also theirs).
std::vector<const OutputField *> FieldsWritten(const Problem *P, bool open) {
  std::vector<const OutputField *> rows;
  for (const OutputField &f : kOutputFields) {
    bool on = false;
    switch (f.when) {
    case FieldWhen::Open: on = open; break;
    case FieldWhen::Step: on = !open; break;
    case FieldWhen::Plastic: on = !open && P->HasPlasticStrain(); break;
    case FieldWhen::Wrinkling: on = !open && P->wrinkling; break;
    case FieldWhen::Contact: on = !open && FindTerm<ContactSet>(*P); break;
    case FieldWhen::Term: break;  // WriteTermFields
    }
    if (on) rows.push_back(&f);
  }
  return rows;
}

// The dataset's self-description, so that a reader needs no copy of the table.
PetscErrorCode DescribeField(const std::string &path, hid_t loc, const OutputField &f) {
  PetscFunctionBeginUser;
  hid_t d = H5Dopen2(loc, f.name, H5P_DEFAULT);
  PetscCheck(d >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "HDF5: cannot reopen %s in %s to describe it",
             f.name, path.c_str());
  PetscCall(H5WriteString(path, d, "vector_field_type", kFieldKindName[(int)f.kind]));
  PetscCall(H5WriteString(path, d, "units", f.units));
  PetscCall(H5WriteString(path, d, "family", f.family));
  PetscCall(H5WriteString(path, d, "description", f.description));
  H5Dclose(d);
  PetscFunctionReturn(0);
}

// Collective: the rows' values (owned rows, PETSc order) as datasets below loc, in the scene's order.
PetscErrorCode WriteFields(OutputFile *out, hid_t loc, const std::vector<const OutputField *> &rows,
                           const OutputValues &v) {
  PetscFunctionBeginUser;
  for (const OutputField *f : rows) {
    PetscCall(H5WriteNatural(out->path, *out->order, loc, f->name, f->location, f->components, f->values(v),
                             f->integer));
    PetscCall(DescribeField(out->path, loc, *f));
  }
  PetscFunctionReturn(0);
}

// The table itself as the root attribute field_table: a header line, then one tab-separated line
// per row (also the rows this run does not write).
std::string FieldTableText() {
  std::string t = "name\tlocation\tcomponents\tvector_field_type\tnumber_type\tunits\tfamily\twritten\txdmf\t"
                  "description\n";
  for (const OutputField &f : kOutputFields)
    t += std::string(f.name) + "\t" + kFieldLocationName[(int)f.location] + "\t" + std::to_string(f.components) + "\t" +
         kFieldKindName[(int)f.kind] + "\t" + (f.integer ? "int32" : "float64") + "\t" + f.units + "\t" + f.family +
         "\t" + kFieldWhenName[(int)f.when] + "\t" + (f.viewer ? f.viewer : "") + "\t" + f.description + "\n";
  return t;
}

PetscErrorCode CreateGroup(const std::string &path, hid_t loc, const char *name) {
  PetscFunctionBeginUser;
  hid_t g = H5Gcreate2(loc, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  PetscCheck(g >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "HDF5: cannot create the group %s in %s (disk full?)",
             name, path.c_str());
  H5Gclose(g);
  PetscFunctionReturn(0);
}

// The physics terms' fields of a step (a chamber's pressure and volume), each the table's row
// <term>/<field> in the term's group of the step, with that row's self-description.
PetscErrorCode WriteTermFields(OutputFile *out, const Problem *P, hid_t g) {
  PetscFunctionBeginUser;
  for (const auto &term : P->terms) {
    std::vector<TermData> fields;
    PetscCall(term->Fields(*P, &fields));
    if (fields.empty()) continue;
    PetscCall(CreateGroup(out->path, g, term->Name()));
    for (const TermData &d : fields) {
      const std::string name = std::string(term->Name()) + "/" + d.name;
      const int row = OutputFieldIndex(name);
      PetscCheck(row >= 0 && kOutputFields[row].when == FieldWhen::Term && !std::strcmp(kOutputFields[row].units, d.units),
                 P->comm, PETSC_ERR_PLIB,
                 "the field %s [%s] of the physics term %s is not a row of the field table with those units "
                 "(include/etfe/io/output_fields.h, FieldWhen::Term): add it there and to docs/results.md",
                 name.c_str(), d.units, term->Name());
      const OutputField &f = kOutputFields[row];
      if (d.replicated)
        PetscCall(H5WriteRows(out->path, g, f.name, H5T_NATIVE_DOUBLE, d.values.size(), 1, 0,
                              P->rank == 0 ? d.values.size() : 0, d.values.data()));
      else
        PetscCall(H5WriteNatural(out->path, *out->order, g, f.name, d.layout, d.components, d.values.data(), f.integer));
      PetscCall(DescribeField(out->path, g, f));
    }
  }
  PetscFunctionReturn(0);
}

// Contact pairs of a step: local force, slide (local and global X/Y), status, film node.
void ContactValues(const ContactSet &c, OutputValues *v) {
  const size_t n = c.pairs.size();
  v->force.resize(3 * n), v->slide_local.resize(2 * n), v->slide_global.resize(2 * n);
  v->status.resize(n), v->node.resize(n);
  for (size_t k = 0; k < n; ++k) {
    const ContactPair &pr = c.pairs[k];
    const ContactPairReport r = ContactReport(c, pr);
    for (int i = 0; i < 3; ++i) v->force[3 * k + i] = r.force[i];
    for (int i = 0; i < 2; ++i) v->slide_local[2 * k + i] = r.slide_local[i], v->slide_global[2 * k + i] = r.slide_global[i];
    v->status[k] = r.status;
    v->node[k] = (double)pr.natural_node;
  }
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
  PetscCall(PetscOptionsBool("-output_allow_lost_steps",
                             "-restart: continue although the results file is missing or unreadable (the steps up "
                             "to the checkpoint are then missing, and its status says so instead of complete); "
                             "without it such a restart is refused",
                             "", o->allow_lost_steps, &o->allow_lost_steps, nullptr));
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
  StepInfo info{name, -1, 0.0};
  hid_t s = H5Gopen2(g, name, H5P_DEFAULT);
  if (s < 0) {  // left half-written by a kill: listed, so that it is dropped
    v->push_back(info);
    return 0;
  }
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

// Status is a fixed 1 kB string rewritten in place, so recording a failure needs no new space in
// the file (a full disk is one of the failures it records).
const size_t kStatusSize = 1024;

PetscErrorCode WriteStatus(const std::string &path, hid_t file, std::string text) {
  PetscFunctionBeginUser;
  std::replace(text.begin(), text.end(), '\n', ' ');
  if (H5Aexists(file, "status") > 0) {
    hid_t a = H5Aopen(file, "status", H5P_DEFAULT);
    hid_t type = a >= 0 ? H5Aget_type(a) : -1;
    const size_t size = type >= 0 ? H5Tget_size(type) : 0;
    herr_t w = -1;
    if (size >= text.size() + 1) {
      std::vector<char> buf(size, 0);
      std::copy(text.begin(), text.end(), buf.begin());
      w = H5Awrite(a, type, buf.data());
    }
    if (type >= 0) H5Tclose(type);
    if (a >= 0) H5Aclose(a);
    if (size >= text.size() + 1) {
      PetscCheck(w >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "cannot write the status of %s", path.c_str());
      PetscFunctionReturn(0);
    }
  }
  std::vector<char> buf(std::max(kStatusSize, text.size() + 1), 0);
  std::copy(text.begin(), text.end(), buf.begin());
  hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, buf.size());
  PetscCall(H5WriteAttribute(path, file, "status", type, buf.data()));
  H5Tclose(type);
  PetscFunctionReturn(0);
}

hid_t ResultsAccess(MPI_Comm comm) {
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  H5Pset_fapl_mpio(fapl, comm, MPI_INFO_NULL);
  // Closing the file after an error must also close what the error left open, so the status lands.
  H5Pset_fclose_degree(fapl, H5F_CLOSE_STRONG);
  return fapl;
}

// What the XDMF index shows of this run's file.
XdmfIndex XdmfIndexOf(const OutputFile *out) {
  const Problem *P = out->problem;
  XdmfIndex ix;
  ix.path = std::filesystem::path(out->path).replace_extension(".xmf").string();
  ix.results = std::filesystem::path(out->path).filename().string();
  ix.name = P->scene.name;
  ix.rows[(int)Layout::Nodes] = P->mesh.num_nodes_global;
  ix.rows[(int)Layout::Cells] = P->mesh.num_elements_global;
  const ContactSet *contact = FindTerm<ContactSet>(*P);
  ix.rows[(int)Layout::Pairs] = contact ? (long long)contact->num_global : 0;
  ix.contact = contact != nullptr;
  ix.fields = out->step_fields;
  return ix;
}

// Rank 0 writes the index; a failure there (disk full) must stop every rank together, not leave
// the others waiting in the next collective call.
PetscErrorCode WriteXdmfEverywhere(OutputFile *out) {
  int ok;
  PetscFunctionBeginUser;
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr));
  ok = out->problem->rank != 0 || WriteXdmf(out->xdmf, out->steps) == 0;
  PetscCall(PetscPopErrorHandler());
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, out->problem->comm));
  PetscCheck(ok, out->problem->comm, PETSC_ERR_FILE_WRITE, "cannot write the XDMF index %s (disk full or not writable?)",
             out->xdmf.path.c_str());
  PetscFunctionReturn(0);
}

// The writer of this run (rank 0's process: writer_identity.h), in the root attributes every
// rank writes alike, so that a reader can tell whether the run still lives.
PetscErrorCode WriteWriterIdentity(OutputFile *out) {
  Problem *P = out->problem;
  std::string text;
  PetscFunctionBeginUser;
  WriterIdentity w = ThisProcess();
  if (P->rank == 0)
    text = w.host + "\n" + w.boot_id + "\n" + w.started + "\n" + std::to_string(w.pid) + "\n" + std::to_string(w.start_ticks);
  unsigned long long n = text.size();
  PetscCallMPI(MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, P->comm));
  text.resize(n);
  PetscCallMPI(MPI_Bcast(text.data(), (int)n, MPI_CHAR, 0, P->comm));
  std::istringstream in(text);
  std::getline(in, w.host), std::getline(in, w.boot_id), std::getline(in, w.started);
  in >> w.pid >> w.start_ticks;
  PetscMPIInt size;
  PetscCallMPI(MPI_Comm_size(P->comm, &size));
  const long long ranks = size;
  PetscCall(H5WriteString(out->path, out->file, "writer_host", w.host));
  PetscCall(H5WriteString(out->path, out->file, "writer_boot_id", w.boot_id));
  PetscCall(H5WriteString(out->path, out->file, "writer_started", w.started));
  PetscCall(H5WriteAttribute(out->path, out->file, "writer_pid", H5T_NATIVE_LLONG, &w.pid));
  PetscCall(H5WriteAttribute(out->path, out->file, "writer_start_ticks", H5T_NATIVE_ULLONG, &w.start_ticks));
  PetscCall(H5WriteAttribute(out->path, out->file, "writer_ranks", H5T_NATIVE_LLONG, &ranks));
  PetscFunctionReturn(0);
}

// Open MPI's <file>-<job>-<n>.lock files beside the results (and its checkpoints, named after
// it): its shared-file-pointer component makes one per open file, and a run that does not close
// its files leaves them. HDF5 never uses shared file pointers.
void RemoveOpenMpiLocks(const std::string &path) {
  std::error_code ec;
  const std::filesystem::path p(path);
  const std::string stem = p.stem().string();
  const auto dir = p.parent_path().empty() ? std::filesystem::path(".") : p.parent_path();
  for (const auto &e : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(stem, 0) == 0 && name.size() > 5 && name.compare(name.size() - 5, 5, ".lock") == 0 &&
        name.find(".h5") != std::string::npos)
      std::filesystem::remove(e.path(), ec);
  }
}

// Before a run writes `path` (afresh or continued): a run that is still writing it is never
// disturbed; what dead runs left beside it goes (the status note of a rank that failed alone, and
// Open MPI's lock files).
PetscErrorCode ClaimResultsFile(MPI_Comm comm, const std::string &path) {
  PetscMPIInt rank;
  char seen[1024] = "";
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0 && std::filesystem::exists(path)) {
    const std::string st = ResultsStatusSeen(path);
    if (st == "running") std::snprintf(seen, sizeof seen, "%s", st.c_str());
  }
  PetscCallMPI(MPI_Bcast(seen, sizeof seen, MPI_CHAR, 0, comm));
  PetscCheck(!seen[0], comm, PETSC_ERR_FILE_OPEN,
             "-output_file %s is being written by a run that is still alive (etfe -results_status %s names it): "
             "stop that run first, or give another -output_file",
             path.c_str(), path.c_str());
  if (rank == 0) {
    StatusNoteRemove(path);
    RemoveOpenMpiLocks(path);
  }
  PetscFunctionReturn(0);
}

// base, or base.1, base.2, ...: the first name not taken (a kept file is never overwritten).
std::string FreeName(const std::string &base) {
  std::error_code ec;
  std::string name = base;
  for (int k = 1; std::filesystem::exists(name, ec) && k < 1000; ++k) name = base + "." + std::to_string(k);
  return name;
}

herr_t CopyAttribute(hid_t from, const char *name, const H5A_info_t *, void *to) {
  hid_t a = H5Aopen(from, name, H5P_DEFAULT);
  hid_t type = H5Aget_type(a), space = H5Aget_space(a);
  std::vector<char> buf(H5Tget_size(type) * std::max<hssize_t>(1, H5Sget_simple_extent_npoints(space)));
  herr_t r = H5Aread(a, type, buf.data());
  hid_t b = r >= 0 ? H5Acreate2(*(hid_t *)to, name, type, space, H5P_DEFAULT, H5P_DEFAULT) : -1;
  if (b >= 0) r = H5Awrite(b, type, buf.data()), H5Aclose(b);
  H5Sclose(space);
  H5Tclose(type);
  H5Aclose(a);
  return r < 0 || b < 0 ? -1 : 0;
}

// Rank 0: the results file without the steps after the checkpoint (and without step groups a kill
// left half-written), copied to a new file that then replaces it. HDF5 cannot always delete such
// groups in place (their headers may be incomplete), and a leftover name would stop the restarted
// run when it writes that step again. Returns the steps kept that could not be copied (they stay
// in the file kept under another name; without allow_lost nothing is changed then), counting
// lost_before steps the caller could not even find; -1 when nothing could be rebuilt.
int RebuildWithout(const std::string &path, const std::vector<std::string> &keep, bool allow_lost, int lost_before,
                   std::string *kept_aside) {
  const std::string tmp = path + ".restart.tmp";
  int lost = -1;
  H5E_BEGIN_TRY {
    hid_t src = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    hid_t dst = src >= 0 ? H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT) : -1;
    bool good = dst >= 0 && H5Aiterate2(src, H5_INDEX_NAME, H5_ITER_INC, nullptr, CopyAttribute, &dst) >= 0 &&
                H5Ocopy(src, "mesh", dst, "mesh", H5P_DEFAULT, H5P_DEFAULT) >= 0;
    hid_t steps = good ? H5Gcreate2(dst, "steps", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT) : -1;
    if (steps >= 0) {
      lost = lost_before;
      for (const std::string &name : keep)
        if (H5Ocopy(src, ("steps/" + name).c_str(), steps, name.c_str(), H5P_DEFAULT, H5P_DEFAULT) < 0) ++lost;
      H5Gclose(steps);
    }
    if (dst >= 0 && H5FcloseWritten(dst) < 0) lost = -1;
    if (src >= 0) H5Fclose(src);
  }
  H5E_END_TRY;
  std::error_code ec;
  if (lost < 0) {
    std::filesystem::remove(tmp, ec);
    return -1;
  }
  if (lost > 0 && !allow_lost) {  // refused: the file stays as it was
    std::filesystem::remove(tmp, ec);
    return lost;
  }
  if (lost > 0) {
    *kept_aside = FreeName(path + ".before-restart");
    std::filesystem::rename(path, *kept_aside, ec);
  }
  if (!ec) std::filesystem::rename(tmp, path, ec);
  return ec ? -1 : lost;
}

// A restart whose results file cannot hold the steps up to the checkpoint: refused (nothing
// changed) unless -output_allow_lost_steps, and then recorded so that the file's status never
// claims a complete history.
PetscErrorCode LostSteps(OutputFile *out, PetscInt restart_step, bool allow, const std::string &what,
                         const std::string &was) {
  PetscFunctionBeginUser;
  PetscCheck(allow, out->problem->comm, PETSC_ERR_FILE_OPEN,
             "-restart: the results file %s %s: the continued run would lack steps up to increment "
             "%" PetscInt_FMT " yet claim a complete history, so nothing was changed. Put back the results file of "
             "the run that wrote the checkpoint, run again from the start (without -restart), or continue without "
             "those steps with -output_allow_lost_steps (the status then says they are missing)",
             out->path.c_str(), what.c_str(), restart_step);
  out->steps_lost = "the steps up to increment " + std::to_string((long long)restart_step) + " (the file " + was +
                    " when the run was restarted from its checkpoint; continued with -output_allow_lost_steps)";
  PetscFunctionReturn(0);
}

// Whether path is the results file the checkpoint's run wrote (or that is unknown): then its
// absence means the steps up to the checkpoint were lost, not that a new file was asked for.
bool SameResultsFile(const std::string &path, const std::string &checkpoint_results) {
  if (checkpoint_results.empty()) return true;
  std::error_code ec;
  const auto a = std::filesystem::weakly_canonical(path, ec);
  const auto b = ec ? std::filesystem::path() : std::filesystem::weakly_canonical(checkpoint_results, ec);
  return ec || a == b;
}

// Reopens a results file to continue it after a restart. Returns false when the file is missing:
// a new file asked for (not the checkpoint's run's) or, with allow_lost, the lost one (refused
// otherwise). An unreadable one (cut short by a kill) is refused untouched or, with allow_lost,
// moved aside, never overwritten; a file of another scene or another load history (run_id) is
// refused untouched.
PetscErrorCode ReopenForRestart(OutputFile *out, PetscInt restart_step, bool allow_lost,
                                const std::string &checkpoint_results, bool *ok) {
  Problem *P = out->problem;
  PetscFunctionBeginUser;
  int exists = P->rank == 0 && std::filesystem::exists(out->path) ? 1 : 0, same = 1;
  if (P->rank == 0) same = SameResultsFile(out->path, checkpoint_results) ? 1 : 0;
  PetscCallMPI(MPI_Bcast(&exists, 1, MPI_INT, 0, P->comm));
  PetscCallMPI(MPI_Bcast(&same, 1, MPI_INT, 0, P->comm));
  *ok = false;
  if (!exists && !same) {  // a new file asked for: it starts at the checkpoint, and says so
    out->steps_lost = "the steps up to increment " + std::to_string((long long)restart_step) +
                      " (a restart from a checkpoint into a new results file; the run that wrote the checkpoint "
                      "wrote them to " + checkpoint_results + ")";
    PetscFunctionReturn(0);
  }
  if (!exists) {
    PetscCall(LostSteps(out, restart_step, allow_lost, "is missing", "was missing"));
    PetscFunctionReturn(0);
  }
  // Probe serially first: a file cut short by a kill may not open.
  int state = 0;  // 0 unreadable, 1 this run's, 2 another scene, 3 another run
  int unread = 0;  // earlier steps that could not be copied (the file then left as it was)
  int not_found = 0;  // earlier steps whose names could not be looked up (salvaged)
  bool salvaged = false;  // the steps were found by name: the file must be rebuilt
  char other[256] = "", note[512] = "", lost_before[512] = "";
  std::vector<std::string> keep;
  size_t drop = 0;
  if (P->rank == 0) {
    H5E_BEGIN_TRY {
      hid_t f = H5Fopen(out->path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
      if (f >= 0) {
        std::string scene, id, lost;
        if (H5Aexists(f, "scene") > 0 && H5ReadString(out->path, f, "scene", &scene) == 0 &&
            H5Lexists(f, "steps", H5P_DEFAULT) > 0) {
          if (H5Aexists(f, "run_id") > 0) H5ReadString(out->path, f, "run_id", &id);
          if (H5Aexists(f, "steps_lost") > 0 && H5ReadString(out->path, f, "steps_lost", &lost) == 0)
            std::snprintf(lost_before, sizeof lost_before, "%s", lost.c_str());
          state = scene != P->scene.name ? 2 : id != out->run_id ? 3 : 1;
          std::snprintf(other, sizeof other, "%s", state == 2 ? scene.c_str() : id.empty() ? "(none)" : id.c_str());
          std::vector<StepInfo> steps;
          hid_t g = H5Gopen2(f, "steps", H5P_DEFAULT);
          if (g >= 0 && H5Literate(g, H5_INDEX_NAME, H5_ITER_INC, nullptr, CollectStep, &steps) < 0) {
            // The group's index is damaged (a kill while a step was being added, "bad heap free
            // list"): the steps up to the checkpoint are looked up by their names instead, and
            // the file is rebuilt from those found; a name whose lookup fails is a lost step.
            steps.clear();
            salvaged = true;
            for (long long k = 0; k <= (long long)restart_step; ++k) {
              char name[32];
              std::snprintf(name, sizeof name, "%06lld", k);
              const htri_t e = H5Lexists(g, name, H5P_DEFAULT);
              if (e > 0) CollectStep(g, name, nullptr, &steps);
              if (e < 0 || (e > 0 && steps.back().step < 0)) {
                if (e > 0) steps.pop_back();
                ++not_found;
              }
            }
          }
          if (g < 0) state = 0;
          if (g >= 0) H5Gclose(g);
          for (const StepInfo &st : steps) {
            if (st.step >= 0 && st.step <= restart_step) keep.push_back(st.group);
            else ++drop;
          }
        }
        H5Fclose(f);
      }
    }
    H5E_END_TRY;
    if (state == 1 && (drop > 0 || salvaged)) {
      // Steps written after the checkpoint (or a damaged index): a new file without them
      // replaces this one.
      std::string aside;
      const int lost = RebuildWithout(out->path, keep, allow_lost, not_found, &aside);
      if (lost < 0) state = 0;
      else if (lost == 0 && salvaged)
        std::snprintf(note, sizeof note, "its list of steps was damaged (a kill while a step was written?); the %zu "
                      "steps up to the checkpoint were found by name and copied into a new file", keep.size());
      else if (lost == 0)
        std::snprintf(note, sizeof note, "%zu step(s) written after the checkpoint dropped", drop);
      else if (!allow_lost)
        unread = lost;
      else
        std::snprintf(note, sizeof note, "%d of the %zu earlier steps could not be read; the old file is kept as %s",
                      lost, keep.size() + (size_t)not_found, aside.c_str());
    }
  }
  PetscCallMPI(MPI_Bcast(&unread, 1, MPI_INT, 0, P->comm));
  PetscCallMPI(MPI_Bcast(lost_before, sizeof lost_before, MPI_CHAR, 0, P->comm));
  out->steps_lost = lost_before;
  if (unread > 0)
    PetscCall(LostSteps(out, restart_step, false,
                        "has " + std::to_string(unread) + " step(s) up to the checkpoint that cannot be read", ""));
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
    PetscCall(LostSteps(out, restart_step, allow_lost, "cannot be read (cut short or damaged)", "could not be read"));
    int moved = 0;
    std::string aside = out->path + ".unreadable";
    if (P->rank == 0) aside = FreeName(aside);
    unsigned long long n = aside.size();
    PetscCallMPI(MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, P->comm));
    aside.resize(n);
    PetscCallMPI(MPI_Bcast(aside.data(), (int)n, MPI_CHAR, 0, P->comm));
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
    out->steps_lost += "; the unreadable file is kept as " + aside;
    PetscFunctionReturn(0);
  }
  PetscCallMPI(MPI_Bcast(note, sizeof note, MPI_CHAR, 0, P->comm));
  if (note[0]) PetscCall(PetscPrintf(P->comm, "  output: %s: %s\n", out->path.c_str(), note));
  if (note[0] && !unread && std::strstr(note, "could not be read"))
    out->steps_lost = std::string("some of the steps up to increment ") + std::to_string((long long)restart_step) +
                      " (" + note + "; continued with -output_allow_lost_steps)";
  hid_t fapl = ResultsAccess(P->comm);
  out->file = H5Fopen(out->path.c_str(), H5F_ACC_RDWR, fapl);
  H5Pclose(fapl);
  if (out->file < 0) PetscFunctionReturn(0);
  g_open_output = out;
  // Rank 0 rebuilt the file without the steps after the checkpoint: what is left is kept.
  std::vector<StepInfo> steps;
  hid_t g = H5Gopen2(out->file, "steps", H5P_DEFAULT);
  H5Literate(g, H5_INDEX_NAME, H5_ITER_INC, nullptr, CollectStep, &steps);
  H5Gclose(g);
  for (const StepInfo &s : steps)
    if (s.step >= 0 && s.step <= restart_step) out->steps.push_back({(PetscInt)s.step, s.time});
  PetscCall(WriteStatus(out->path, out->file, "running"));
  PetscCall(WriteWriterIdentity(out));
  PetscCall(H5WriteString(out->path, out->file, "field_table", FieldTableText()));
  if (!out->steps_lost.empty()) PetscCall(H5WriteString(out->path, out->file, "steps_lost", out->steps_lost));
  long long count = (long long)out->steps.size();
  PetscCall(H5WriteAttribute(out->path, out->file, "steps_written", H5T_NATIVE_LLONG, &count));
  // On disk now, as a new file's start is: a kill before the next step's flush must not leave the
  // steps kept so far behind metadata half written.
  H5Fflush(out->file, H5F_SCOPE_GLOBAL);
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
  out->order = std::make_unique<NaturalOrder>(P);
  out->step_fields = FieldsWritten(P, false);
  out->xdmf = XdmfIndexOf(out);
  PetscCall(ClaimResultsFile(P->comm, out->path));
  if (restart_step >= 0) {
    bool ok = false;
    PetscCall(ReopenForRestart(out, restart_step, o.allow_lost_steps, o.checkpoint_results, &ok));
    if (ok) {
      PetscCall(WriteXdmfEverywhere(out));
      *result = g_open_output = out;
      PetscFunctionReturn(0);
    }
    PetscCall(PetscPrintf(P->comm, "  output: %s starts anew at the checkpoint, without the steps before it (its "
                          "status will say so)\n", out->path.c_str()));
  }
  if (P->rank == 0) {
    std::error_code ec;
    auto dir = std::filesystem::path(out->path).parent_path();
    if (!dir.empty()) std::filesystem::create_directories(dir, ec);
    // A stale index must not describe the new file while it is being written.
    std::filesystem::remove(out->xdmf.path, ec);
  }
  PetscCallMPI(MPI_Barrier(P->comm));
  hid_t fapl = ResultsAccess(P->comm);
  out->file = H5Fcreate(out->path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  H5Pclose(fapl);
  PetscCheck(out->file >= 0, P->comm, PETSC_ERR_FILE_OPEN,
             "cannot create the results file %s (check -output_file and that its directory is "
             "writable)",
             out->path.c_str());
  g_open_output = out;  // an error from here on marks the file failed (and closes it)
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
  PetscCall(WriteStatus(out->path, out->file, "running"));
  PetscCall(WriteWriterIdentity(out));
  PetscCall(H5WriteString(out->path, out->file, "field_table", FieldTableText()));
  if (!out->steps_lost.empty()) PetscCall(H5WriteString(out->path, out->file, "steps_lost", out->steps_lost));
  for (const auto &[name, values] : P->scene.result_attributes)
    if (!values.empty()) PetscCall(H5WriteArrayAttribute(out->path, out->file, name.c_str(), values));
  long long zero = 0;
  PetscCall(H5WriteAttribute(out->path, out->file, "steps_written", H5T_NATIVE_LLONG, &zero));
  PetscCall(CreateGroup(out->path, out->file, "mesh"));
  PetscCall(CreateGroup(out->path, out->file, "steps"));
  // From each rank's part, in the scene's order (only rank 0 built the global mesh, and a load
  // history has dropped it).
  const LocalMesh &m = P->mesh;
  OutputValues v;
  v.coordinates = m.X.data();
  v.triangles.resize(3 * (size_t)m.num_elements);
  for (size_t k = 0; k < v.triangles.size(); ++k) v.triangles[k] = (double)m.natural_id[m.tri[k]];
  PetscCall(WriteFields(out, out->file, FieldsWritten(P, true), v));
  H5Fflush(out->file, H5F_SCOPE_GLOBAL);
  *result = g_open_output = out;
  PetscFunctionReturn(0);
}

PetscErrorCode OutputWriteStep(OutputFile *out, Problem *P, Vec U, PetscInt step, double time,
                               Vec U_fields) {
  OutputValues v;
  PetscFunctionBeginUser;
  if (!out) PetscFunctionReturn(0);
  if (!out->steps.empty() && out->steps.back().first == step) PetscFunctionReturn(0);
  PetscCall(PetscLogEventBegin(LogEvents().output, 0, 0, 0, 0));
  PetscCall(ComputeCellFields(P, U_fields ? U_fields : U, &v.cells));
  if (const ContactSet *contact = FindTerm<ContactSet>(*P)) ContactValues(*contact, &v);
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
  if (FindTerm<ContactSet>(*P)) PetscCall(CreateGroup(out->path, g, "contact"));
  PetscCall(VecGetArrayRead(U, &v.displacement));
  PetscCall(VecGetArrayRead(P->reaction, &v.reaction));
  PetscCall(WriteFields(out, g, out->step_fields, v));
  PetscCall(VecRestoreArrayRead(P->reaction, &v.reaction));
  PetscCall(VecRestoreArrayRead(U, &v.displacement));
  // A term that reports what its last evaluation left (the cables) is evaluated at the state written.
  if (TermsReportLastEvaluation(*P)) PetscCall(ProblemUpdateReactions(P, U_fields ? U_fields : U));
  PetscCall(WriteTermFields(out, P, g));
  H5Gclose(g);
  out->steps.push_back({step, time});
  long long count = (long long)out->steps.size();
  PetscCall(H5WriteAttribute(out->path, out->file, "steps_written", H5T_NATIVE_LLONG, &count));
  {
    // The flush writes on some ranks only: all of them learn whether it worked.
    int flushed = H5Fflush(out->file, H5F_SCOPE_GLOBAL) >= 0, all;
    PetscCallMPI(MPI_Allreduce(&flushed, &all, 1, MPI_INT, MPI_MIN, P->comm));
    PetscCheck(all, P->comm, PETSC_ERR_FILE_WRITE, "HDF5: flush of %s failed (disk full?)", out->path.c_str());
  }
  PetscCall(WriteXdmfEverywhere(out));
  PetscCall(PetscLogEventEnd(LogEvents().output, 0, 0, 0, 0));
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
  PetscCheck(!P->scene_released, P->comm, PETSC_ERR_PLIB,
             "the shape needs the scene's topology, released after set-up (ProblemReleaseScene)");
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
  if (!g_open_output) PetscFunctionReturn(0);
  std::string cause;
  struct statvfs fs;
  const std::string dir = OutputDirectory(g_open_output);
  if (why.find("No space left") == std::string::npos && statvfs(dir.c_str(), &fs) == 0 &&
      (double)fs.f_bavail * fs.f_frsize < 65536.0)
    cause = " (the disk of " + dir + " is full)";
  PetscCall(OutputClose(&g_open_output, "failed: " + why + cause));
  PetscFunctionReturn(0);
}

bool OutputIsOpen() { return g_open_output != nullptr; }

bool OutputLibraryClose() {
  if (H5AnyCloseFailed()) return false;
  H5E_BEGIN_TRY {
    // Files an error left open (a checkpoint half written on a full disk) are closed one by one
    // first: a close that fails inside H5close crashes this HDF5 as a second close does.
    const ssize_t n = H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_FILE);
    std::vector<hid_t> files(n > 0 ? (size_t)n : 0);
    if (n > 0) H5Fget_obj_ids(H5F_OBJ_ALL, H5F_OBJ_FILE, (size_t)n, files.data());
    for (hid_t f : files) H5FcloseWritten(f);
    if (!H5AnyCloseFailed()) H5close();
  }
  H5E_END_TRY;
  return !H5AnyCloseFailed();
}

std::string OutputNoteFailure(const std::string &why) {
  if (!g_open_output) return "";
  RemoveOpenMpiLocks(g_open_output->path);  // the job is about to be aborted: nobody closes the file
  if (!StatusNoteWrite(g_open_output->path, g_open_output->run_id, "failed: " + why)) return "";
  return g_open_output->path + ".status";
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
  // A history continued over lost results (-output_allow_lost_steps) ran to its end, but the file
  // does not hold it all.
  const std::string said = status == "complete" && !out->steps_lost.empty()
                               ? "incomplete: the load history ran to its end, but this file lacks " + out->steps_lost
                               : status;
  // Closed and freed whatever the status write gives: the caller may be on its error path.
  const PetscErrorCode ierr = WriteStatus(out->path, out->file, said);
  const herr_t closed = H5FcloseWritten(out->file);
  const std::string path = out->path;
  delete out;
  *pout = nullptr;
  PetscCall(ierr);
  PetscCheck(closed >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "cannot close the results file %s (disk full?)",
             path.c_str());
  PetscFunctionReturn(0);
}

} // namespace etfe
