"""One way to launch etfe: build/etfe alone, or under mpirun with N ranks.

    res = run(["-options_file", "options/patch.opts"], np=2, timeout=300, log="x.log")
    res.returncode (None after a timeout), res.output (stdout + stderr), res.wall (s)

The environment lets Open MPI run as root in a container (OMPI_ALLOW_RUN_AS_ROOT*) and turns off
its single-copy transport, which fails inside containers without ptrace rights; mpirun gets
--oversubscribe when more ranks than cores are asked for. Runs start in the repository root, in
their own process group, so that a timeout ends mpirun and every rank.
"""
import os
import signal
import subprocess
import time

from . import ETFE, REPO

MPI_ENV = {
    "OMPI_ALLOW_RUN_AS_ROOT": "1",
    "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
    "OMPI_MCA_btl_vader_single_copy_mechanism": "none",
}


class Result:
    def __init__(self, returncode, output, wall, command):
        self.returncode, self.output, self.wall, self.command = returncode, output, wall, command

    @property
    def timed_out(self):
        return self.returncode is None


def environment(**extra):
    """os.environ with the MPI settings above (and extra, e.g. OMP_NUM_THREADS="1")."""
    env = dict(os.environ)
    env.update(MPI_ENV)
    env.update(extra)
    return env


def command(args, np=1, etfe=None, oversubscribe=None, prefix=()):
    """The argv that runs etfe with args: [*prefix, mpirun -n np [--oversubscribe], etfe, *args]."""
    cmd = [etfe or ETFE] + [str(a) for a in args]
    if np > 1:
        if oversubscribe is None:
            oversubscribe = np > (os.cpu_count() or 1)
        cmd = ["mpirun", "-n", str(np)] + (["--oversubscribe"] if oversubscribe else []) + cmd
    return list(prefix) + cmd


def start(args, np=1, etfe=None, stdout=subprocess.PIPE, env=None, **popen):
    """etfe started (subprocess.Popen, stderr into stdout, own process group), for a caller that
    watches or kills it while it runs."""
    return subprocess.Popen(command(args, np, etfe), cwd=REPO, env=env or environment(), stdout=stdout,
                            stderr=subprocess.STDOUT, start_new_session=True, **popen)


def stop(p):
    """Ends a started run and all its ranks: SIGTERM to its process group, SIGKILL 3 s later."""
    try:
        os.killpg(p.pid, signal.SIGTERM)
        try:
            p.wait(timeout=3)
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, signal.SIGKILL)
    except ProcessLookupError:
        pass
    p.wait()


def run(args, np=1, etfe=None, timeout=None, log=None, env=None, prefix=(), oversubscribe=None, progress=None,
        every=30.0, cwd=None, **popen):
    """Runs etfe to the end (or timeout seconds) and returns a Result.

    log: a file that gets the command line (`# ...`) and then the output as it is printed (read
    back into Result.output). progress(elapsed_s, log): called every `every` seconds of a logged
    run. prefix: a wrapper in front of the command (e.g. /usr/bin/time -v)."""
    cmd = command(args, np, etfe, oversubscribe, prefix)
    env = env or environment()
    t0 = time.time()
    sink = open(log, "w") if log else subprocess.PIPE
    try:
        if log:
            sink.write("# " + " ".join(cmd) + "\n")
            sink.flush()
        try:
            p = subprocess.Popen(cmd, cwd=cwd or REPO, env=env, stdout=sink, stderr=subprocess.STDOUT,
                                 start_new_session=True, **popen)
        except OSError as e:
            return Result(127, "cannot run %s: %s" % (" ".join(cmd), e), 0.0, cmd)
        out, rc, next_report = b"", None, every
        while True:
            try:
                out, _ = p.communicate(timeout=2.0 if log else timeout)
                rc = p.returncode
                break
            except subprocess.TimeoutExpired as e:
                out = e.stdout or out
            elapsed = time.time() - t0
            if timeout is not None and elapsed > timeout:
                stop(p)
                if not log:
                    out = p.communicate()[0]  # what was printed before the timeout
                break
            if progress and elapsed >= next_report:
                next_report += every
                progress(elapsed, log)
    finally:
        if log:
            sink.close()
    if log:
        with open(log, errors="replace") as f:
            out = f.read()
    return Result(rc, decode(out), time.time() - t0, cmd)


def decode(b):
    return b.decode("utf-8", "replace") if isinstance(b, bytes) else (b or "")


def make_required(options_file, np=1, etfe=None, timeout=None):
    """Makes the files an options file's `# requires: FILE from OPTIONS` lines name and that are
    missing (as scripts/run does): [(file, Result)] of the runs made."""
    from . import options
    made = []
    for need, source in options.requires(options_file):
        if not os.path.isfile(os.path.join(REPO, need)):
            made.append((need, run(["-options_file", source, "-formfind_monitor", 0], np=np, etfe=etfe,
                                   timeout=timeout)))
    return made


def load_average():
    """The 1-minute load average of the machine (nan where /proc/loadavg is missing)."""
    try:
        with open("/proc/loadavg") as f:
            return float(f.read().split()[0])
    except OSError:
        return float("nan")


def progress_reporter(label, say=print):
    """A progress(elapsed, log) for run(): says how long `label` has run and its last step line."""
    def report(elapsed, log):
        last = ""
        try:
            with open(log, errors="replace") as g:
                found = [l.strip() for l in g if l.startswith(("step", "formfind:", "etfe:"))]
            last = found[-1] if found else ""
        except OSError:
            pass
        say(f"    ... {label}: {elapsed:.0f} s{', last: ' + last[:110] if last else ''}")
    return report


def run_measured(args, np, etfe, log, timeout, label, say=print):
    """A benchmark run: under /usr/bin/time -v (peak memory, CPU time; when installed), one OpenMP
    thread per rank, into the file log, saying how it goes every 30 s. Returns a Result."""
    timev = ["/usr/bin/time", "-v"] if os.path.exists("/usr/bin/time") else []
    return run(args, np=np, etfe=etfe, timeout=timeout, log=log, env=environment(OMP_NUM_THREADS="1"), prefix=timev,
               progress=progress_reporter(label, say))
