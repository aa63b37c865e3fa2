// Who writes a results file, so that a reader can tell a live run from a dead one. A run that is
// killed (SIGKILL, a lost node, a power cut) cannot write its status: the file keeps "running".
// So the file also names its writer (rank 0's host, pid, the kernel's boot id and the process's
// start time in clock ticks since boot), and a reader on the same host checks that this process
// still exists: the pid alone could have been reused, pid + start time + boot id cannot. On
// another host nothing can be checked (a pid there means nothing here): the reader says so.
// Shared file systems (NFS, Lustre) need nothing beyond consistent reads of the file's
// attributes; no lock is taken (flock/fcntl locks are unreliable on NFS and are released by a
// dead client only after the server's lease runs out).
//
// One rank failing alone cannot write the HDF5 status (a collective write), so it writes the
// status note <results>.status (run id and status, one line each, created exclusively: the first
// failing rank's message) beside the file; a reader takes it when the file says "running".
#pragma once
#include <string>

namespace etfe {

struct WriterIdentity {
  std::string host, boot_id, started;  // started: UTC, ISO 8601
  long long pid = 0;
  unsigned long long start_ticks = 0;  // /proc/<pid>/stat field 22
};

WriterIdentity ThisProcess();
// alive: that process runs on this host; gone: it does not (or the host rebooted since);
// elsewhere: another host (cannot check); unknown: the file names no writer.
enum class WriterState { alive, gone, elsewhere, unknown };
WriterState WriterStateOf(const WriterIdentity &w);
// The status a reader should believe: the stored one, except that "running" becomes the status
// note's text (a rank that failed alone), "interrupted (writer gone...)" when the writer is dead,
// "running (on host X, cannot check from here)" for another host.
std::string StatusAsSeen(const std::string &stored, const WriterIdentity &w, const std::string &note);
// The status note beside a results file: its status when it belongs to run_id, else "".
std::string StatusNoteRead(const std::string &results, const std::string &run_id);
// Creates the status note (only if none exists: the first failure wins). Plain POSIX I/O, any
// rank, no MPI. Returns false when it could not be written.
bool StatusNoteWrite(const std::string &results, const std::string &run_id, const std::string &status);
void StatusNoteRemove(const std::string &results);
// Reads a results file (serial HDF5, read-only) and returns the status as seen from here, or
// "unreadable: ..." when it cannot be opened.
std::string ResultsStatusSeen(const std::string &results);

} // namespace etfe
