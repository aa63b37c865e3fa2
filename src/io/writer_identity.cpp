// The writer of a results file and the status a reader should believe (see writer_identity.h).
#include "etfe/io/writer_identity.h"

#include <fcntl.h>
#include <hdf5.h>
#include <unistd.h>

#include <cstdio>
#include <ctime>
#include <fstream>
#include <sstream>
#include <vector>

namespace etfe {

namespace {

std::string FirstLine(const std::string &path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return line;
}

// Field 22 of /proc/<pid>/stat (the start time in clock ticks since boot); 0 when the process
// does not exist or has ended (a zombie, state Z or X, not yet reaped). The fields after the
// command name, which may hold spaces, follow its last ')'.
unsigned long long StartTicks(long long pid) {
  const std::string stat = FirstLine("/proc/" + std::to_string(pid) + "/stat");
  const size_t close = stat.rfind(')');
  if (close == std::string::npos) return 0;
  std::istringstream rest(stat.substr(close + 1));
  std::string field;
  for (int k = 3; k <= 22 && rest >> field; ++k) {
    if (k == 3 && (field == "Z" || field == "X")) return 0;
    if (k == 22) return std::strtoull(field.c_str(), nullptr, 10);
  }
  return 0;
}

std::string HostName() {
  char host[256] = "";
  gethostname(host, sizeof host - 1);
  return host;
}

std::string NotePath(const std::string &results) { return results + ".status"; }

// A string attribute of the file's root, fixed or variable length (as tools such as h5py write
// it); "" when missing or not a string.
std::string RootString(hid_t f, const char *name) {
  if (H5Aexists(f, name) <= 0) return "";
  hid_t a = H5Aopen(f, name, H5P_DEFAULT);
  hid_t t = a >= 0 ? H5Aget_type(a) : -1;
  std::string v;
  if (t >= 0 && H5Tget_class(t) == H5T_STRING && H5Tis_variable_str(t) > 0) {
    char *p = nullptr;
    hid_t mt = H5Tcopy(H5T_C_S1);
    H5Tset_size(mt, H5T_VARIABLE);
    if (H5Aread(a, mt, &p) >= 0 && p) v = p;
    if (p) H5free_memory(p);
    H5Tclose(mt);
  } else if (t >= 0 && H5Tget_class(t) == H5T_STRING) {
    std::vector<char> buf(H5Tget_size(t) + 1, 0);
    if (H5Aread(a, t, buf.data()) >= 0) v = buf.data();
  }
  if (t >= 0) H5Tclose(t);
  if (a >= 0) H5Aclose(a);
  return v;
}

unsigned long long RootInteger(hid_t f, const char *name) {
  unsigned long long v = 0;
  if (H5Aexists(f, name) <= 0) return 0;
  hid_t a = H5Aopen(f, name, H5P_DEFAULT);
  if (a >= 0 && H5Aread(a, H5T_NATIVE_ULLONG, &v) < 0) v = 0;
  if (a >= 0) H5Aclose(a);
  return v;
}

} // namespace

WriterIdentity ThisProcess() {
  WriterIdentity w;
  w.host = HostName();
  w.pid = (long long)getpid();
  w.boot_id = FirstLine("/proc/sys/kernel/random/boot_id");
  w.start_ticks = StartTicks(w.pid);
  char when[32];
  const std::time_t now = std::time(nullptr);
  std::tm utc;
  gmtime_r(&now, &utc);
  std::strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", &utc);
  w.started = when;
  return w;
}

WriterState WriterStateOf(const WriterIdentity &w) {
  if (w.host.empty() || w.pid <= 0) return WriterState::unknown;
  if (w.host != HostName()) return WriterState::elsewhere;
  const std::string boot = FirstLine("/proc/sys/kernel/random/boot_id");
  if (!w.boot_id.empty() && !boot.empty() && w.boot_id != boot) return WriterState::gone;  // rebooted since
  const unsigned long long ticks = StartTicks(w.pid);
  return ticks != 0 && ticks == w.start_ticks ? WriterState::alive : WriterState::gone;
}

std::string StatusAsSeen(const std::string &stored, const WriterIdentity &w, const std::string &note) {
  if (stored != "running") return stored;
  if (!note.empty()) return note;
  switch (WriterStateOf(w)) {
  case WriterState::alive: return "running";
  case WriterState::gone:
    return "interrupted (writer gone: pid " + std::to_string(w.pid) + " on " + w.host + ", started " + w.started +
           ", no longer runs; killed, or its node lost)";
  case WriterState::elsewhere: return "running (on host " + w.host + ", cannot check from here)";
  case WriterState::unknown: break;
  }
  return "running (no writer recorded: cannot check)";
}

std::string StatusNoteRead(const std::string &results, const std::string &run_id) {
  std::ifstream in(NotePath(results));
  std::string id, status;
  if (!std::getline(in, id) || !std::getline(in, status) || id != run_id) return "";
  return status;
}

bool StatusNoteWrite(const std::string &results, const std::string &run_id, const std::string &status) {
  const std::string text = run_id + "\n" + status + "\n";
  const int fd = open(NotePath(results).c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
  if (fd < 0) return false;
  const bool ok = write(fd, text.data(), text.size()) == (ssize_t)text.size() && fsync(fd) == 0;
  close(fd);
  return ok;
}

void StatusNoteRemove(const std::string &results) { unlink(NotePath(results).c_str()); }

std::string ResultsStatusSeen(const std::string &results) {
  std::string stored, run_id;
  WriterIdentity w;
  bool opened = false;
  H5E_BEGIN_TRY {
    hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
    H5Pset_file_locking(fapl, false, true);  // a live writer holds it open
    hid_t f = H5Fopen(results.c_str(), H5F_ACC_RDONLY, fapl);
    H5Pclose(fapl);
    if (f >= 0) {
      opened = true;
      stored = RootString(f, "status");
      run_id = RootString(f, "run_id");
      w.host = RootString(f, "writer_host");
      w.boot_id = RootString(f, "writer_boot_id");
      w.started = RootString(f, "writer_started");
      w.pid = (long long)RootInteger(f, "writer_pid");
      w.start_ticks = RootInteger(f, "writer_start_ticks");
      H5Fclose(f);
    }
  }
  H5E_END_TRY;
  if (!opened) return "unreadable: not an HDF5 file this HDF5 can open (missing, cut short or damaged)";
  if (stored.empty()) return "unknown: no status attribute (not an etfe results file?)";
  return StatusAsSeen(stored, w, StatusNoteRead(results, run_id));
}

} // namespace etfe
