// Whether the chosen linear solver fits the nodes' memory (memory_check.h).
#include "memory_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

namespace etfe {

namespace {

// kB from /proc/meminfo's line `key`, or 0.
double MeminfoKb(const char *key) {
  double kb = 0.0;
  if (FILE *f = std::fopen("/proc/meminfo", "r")) {
    char line[256];
    const size_t n = std::strlen(key);
    while (std::fgets(line, sizeof line, f))
      if (!std::strncmp(line, key, n) && line[n] == ':') {
        std::sscanf(line + n + 1, "%lf", &kb);
        break;
      }
    std::fclose(f);
  }
  return kb;
}

// A batch job's memory limit (control group v2, then v1), in GB, or 0 where none is set.
double CgroupLimitGb() {
  const char *files[] = {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"};
  for (const char *path : files)
    if (FILE *f = std::fopen(path, "r")) {
      double bytes = 0.0;
      const int got = std::fscanf(f, "%lf", &bytes);
      std::fclose(f);
      if (got == 1 && bytes > 0.0) return bytes / 1e9;
    }
  return 0.0;
}

// What a node offers: its physical memory or the batch job's limit (control group), and what is
// free now; node_gb > 0 replaces both. have_gb 0: no /proc/meminfo (no check).
struct NodeMemory {
  double have_gb = 0.0, avail_gb = 0.0;
  bool job_limit = false;
};

NodeMemory ReadNodeMemory(double node_gb) {
  NodeMemory m;
  if (node_gb > 0) {
    m.have_gb = m.avail_gb = node_gb;
    return m;
  }
  m.have_gb = MeminfoKb("MemTotal") * 1024.0 / 1e9;
  const double cgroup_gb = CgroupLimitGb();
  m.job_limit = cgroup_gb > 0 && cgroup_gb < m.have_gb;
  if (m.job_limit) m.have_gb = cgroup_gb;
  m.avail_gb = std::min(m.have_gb, MeminfoKb("MemAvailable") * 1024.0 / 1e9);
  return m;
}

} // namespace

PetscErrorCode CheckMemoryFits(MPI_Comm comm, const LinearPath &path) {
  PetscBool check = PETSC_TRUE;
  PetscReal node_gb = 0.0;
  MPI_Comm node;
  PetscMPIInt size, here, node_rank, rank;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Memory check", "Sys");
  PetscCall(PetscOptionsBool("-etfe_memory_check",
                             "Refuse a run whose linear solver needs more memory than a node has (estimated per DOF "
                             "from this code's measured runs)",
                             "", check, &check, nullptr));
  PetscCall(PetscOptionsReal("-etfe_memory_node_gb",
                             "A node's memory [GB] for the check (0: the node's physical memory, or the batch job's "
                             "limit where its control group sets one)",
                             "", node_gb, &node_gb, nullptr));
  PetscOptionsEnd();
  // A NaN or a negative size would silently switch the check off (every comparison false).
  PetscCheck(std::isfinite(node_gb) && node_gb >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-etfe_memory_node_gb %g: give a node's memory in GB (> 0), or 0 for the node's own", (double)node_gb);
  PetscBool help = PETSC_FALSE;  // -help runs nothing (and would list the solver's options twice)
  PetscCall(PetscOptionsHasName(nullptr, nullptr, "-help", &help));
  if (!check || help) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node));
  PetscCallMPI(MPI_Comm_size(node, &here));
  PetscCallMPI(MPI_Comm_rank(node, &node_rank));
  PetscCallMPI(MPI_Comm_free(&node));
  const PetscInt dof = path.dof;
  const double need_gb = path.kb_per_dof * 1e3 * (double)dof * path.copies * here / size / 1e9;
  const NodeMemory mem = ReadNodeMemory(node_gb);
  // The tightest node decides; its first rank speaks for it.
  struct {
    double ratio;
    int rank;
  } mine = {node_rank == 0 && mem.have_gb > 0 ? need_gb / mem.have_gb : 0.0, rank}, worst;
  PetscCallMPI(MPI_Allreduce(&mine, &worst, 1, MPI_DOUBLE_INT, MPI_MAXLOC, comm));
  if (worst.ratio <= 0.0) PetscFunctionReturn(0);
  double v[5] = {need_gb, mem.have_gb, mem.avail_gb, (double)here, mem.job_limit ? 1.0 : 0.0};
  PetscCallMPI(MPI_Bcast(v, 5, MPI_DOUBLE, worst.rank, comm));
  char where[512];
  std::snprintf(where, sizeof where, "%.3g GB on the node of rank %d (%d of the run's %d rank(s); %s: ~%.1f kB per DOF "
                "as measured with this code, %" PetscInt_FMT " DOF)", v[0], worst.rank, (int)v[3], size, path.memory_name,
                path.kb_per_dof, dof);
  const char *ways = "Ways out: more nodes (the estimate is per node: spread the ranks over machines with mpirun's "
                     "host list or the batch scheduler), a leaner linear solver (-options_file "
                     "options/solvers/gmres_hypre_lean.opts: ~1.1 kB per DOF), a coarser mesh; -etfe_memory_check 0 "
                     "runs it anyway";
  PetscCheck(v[0] <= v[1], comm, PETSC_ERR_MEM,
             "memory: this run needs about %s, more than the node's %.3g GB%s: the system would end it part way "
             "without a message. %s",
             where, v[1], v[4] > 0 ? " (the batch job's limit)" : "", ways);
  if (v[2] > 0 && v[0] > v[2])
    PetscCall(PetscPrintf(comm,
                          "  warning: memory: this run needs about %s, more than the %.3g GB the node has free now "
                          "(of %.3g GB): other work on it may have to end first. %s\n",
                          where, v[2], v[1], ways));
  PetscFunctionReturn(0);
}

} // namespace etfe
