"""The status of a results file as a reader should believe it (include/etfe/io/writer_identity.h:
the same rule as `etfe -results_status FILE`).

    from etfepy import status
    status.seen("results/dd1511/dd1511.h5")   # "complete", "running", "interrupted (writer gone ...)", ...

A killed run (SIGKILL, a lost node, a power cut) cannot write its status: its file keeps
"running". The file names its writer (root attributes writer_host, writer_pid, writer_boot_id,
writer_start_ticks, writer_started): on the same host a reader checks that this very process still
runs (pid + start time in clock ticks + boot id; a pid alone may have been reused); on another host
it cannot and says so. A rank that failed alone wrote its status to the note <results>.status
(run id, status), which stands for the file's "running".
"""
import os
import socket


def _first_line(path):
    try:
        with open(path) as f:
            return f.readline().rstrip("\n")
    except OSError:
        return ""


def start_ticks(pid):
    """Field 22 of /proc/<pid>/stat (start time in clock ticks since boot); 0 when no such process
    or it has ended (a zombie, state Z or X, not yet reaped)."""
    stat = _first_line("/proc/%d/stat" % pid)
    close = stat.rfind(")")
    if close < 0:
        return 0
    fields = stat[close + 1:].split()
    return int(fields[19]) if len(fields) > 19 and fields[0] not in ("Z", "X") else 0


def writer_state(attrs):
    """'alive', 'gone', 'elsewhere' (another host) or 'unknown' (no writer recorded)."""
    host, pid = _text(attrs.get("writer_host", b"")), int(attrs.get("writer_pid", 0))
    if not host or pid <= 0:
        return "unknown"
    if host != socket.gethostname():
        return "elsewhere"
    boot = _first_line("/proc/sys/kernel/random/boot_id")
    recorded = _text(attrs.get("writer_boot_id", b""))
    if recorded and boot and recorded != boot:
        return "gone"
    ticks = start_ticks(pid)
    return "alive" if ticks and ticks == int(attrs.get("writer_start_ticks", 0)) else "gone"


def note(path, run_id):
    """The status note beside a results file, when it belongs to run_id ('' otherwise)."""
    try:
        with open(path + ".status") as f:
            lines = f.read().split("\n")
    except OSError:
        return ""
    return lines[1] if len(lines) > 1 and lines[0] == run_id else ""


def seen_from_attrs(path, attrs):
    stored = _text(attrs.get("status", b""))
    if stored != "running":
        return stored
    n = note(path, _text(attrs.get("run_id", b"")))
    if n:
        return n
    state = writer_state(attrs)
    host, pid = _text(attrs.get("writer_host", b"")), int(attrs.get("writer_pid", 0))
    if state == "alive":
        return "running"
    if state == "gone":
        return ("interrupted (writer gone: pid %d on %s, started %s, no longer runs; killed, or its node lost)"
                % (pid, host, _text(attrs.get("writer_started", b""))))
    if state == "elsewhere":
        return "running (on host %s, cannot check from here)" % host
    return "running (no writer recorded: cannot check)"


def seen(path):
    """The status of the results file at path as a reader should believe it."""
    import h5py
    try:
        with h5py.File(path, "r", locking=False) as f:
            attrs = {k: f.attrs[k] for k in f.attrs if k == "status" or k == "run_id" or k.startswith("writer_")}
    except (OSError, TypeError):
        try:
            with h5py.File(path, "r") as f:
                attrs = {k: f.attrs[k] for k in f.attrs if k == "status" or k == "run_id" or k.startswith("writer_")}
        except OSError:
            return "unreadable: not an HDF5 file this HDF5 can open (missing, cut short or damaged)"
    if "status" not in attrs:
        return "unknown: no status attribute (not an etfe results file?)"
    return seen_from_attrs(path, attrs)


def _text(v):
    from .results import text
    return text(v)
