"""Checkpoints by stage and by the clock, and the status a reader believes.

capstan (40 increments, 2 stages):
* by default one checkpoint at the stage end (increment 20), none after the last increment;
* -checkpoint_stage_end 0: none at all; -checkpoint_every_s 1e-9 (always due): one after every
  increment but the last, so the file holds increment 39;
* etfe -results_status and etfepy.status agree: complete (exit 0); a copy marked running whose
  writer is a process that has ended: "interrupted (writer gone ...)" (exit 75); a writer on
  another host: "running (on host ..., cannot check from here)" (exit 10); a status note beside
  the file (a rank that failed alone): its text.
"""
import os
import shutil
import subprocess
import sys

import h5py
from etfe_testlib import REPO, main, opts, run, scratch_dir

sys.path.insert(0, os.path.join(REPO, "scripts"))
from etfepy import status  # noqa: E402


def checkpoint_step(path):
    if not os.path.exists(path):
        return None
    with h5py.File(path, "r") as f:
        return int(f.attrs["step"])


def test(etfe, chk):
    with scratch_dir() as tmp:
        def case(name, extra):
            out = os.path.join(tmp, name + ".h5")
            run(etfe, ["-options_file", opts("capstan"), "-output_file", out, "-load_monitor", "0"] + extra)
            return out, checkpoint_step(out[:-3] + ".checkpoint.h5")

        out, step = case("default", [])
        chk.check(step == 20, "default: a checkpoint at the stage end, increment 20 (got %s)" % step)
        _, step = case("nostage", ["-checkpoint_stage_end", 0])
        chk.check(step is None, "-checkpoint_stage_end 0: no checkpoint (got %s)" % step)
        _, step = case("clock", ["-checkpoint_stage_end", 0, "-checkpoint_every_s", 1e-9])
        chk.check(step == 39, "-checkpoint_every_s always due: the last checkpoint is increment 39 (got %s)" % step)

        def both(path):
            rc, text = run(etfe, ["-results_status", path], expect_fail=None)
            line = next((l for l in text.splitlines() if l.startswith(path + ": ")), "")
            return rc, line[len(path) + 2:], status.seen(path)

        rc, mine, py = both(out)
        chk.check(rc == 0 and mine == "complete" == py, "complete: exit %d, %r / %r" % (rc, mine, py))
        dead = os.path.join(tmp, "dead.h5")
        shutil.copy(out, dead)
        ended = subprocess.Popen(["true"])
        ended.wait()
        with h5py.File(dead, "r+") as f:
            f.attrs["status"] = b"running"
            f.attrs["writer_pid"] = ended.pid
        rc, mine, py = both(dead)
        chk.check(rc == 75 and mine.startswith("interrupted (writer gone") and mine == py,
                  "writer ended: exit %d, %r / %r" % (rc, mine[:60], py[:60]))
        with h5py.File(dead, "r+") as f:
            f.attrs["writer_host"] = b"some-other-node"
        rc, mine, py = both(dead)
        chk.check(rc == 10 and mine == "running (on host some-other-node, cannot check from here)" == py,
                  "another host: exit %d, %r / %r" % (rc, mine, py))
        with h5py.File(dead, "r") as f:
            run_id = f.attrs["run_id"].decode()
        with open(dead + ".status", "w") as f:
            f.write("%s\nfailed: a message (rank 1)\n" % run_id)
        rc, mine, py = both(dead)
        chk.check(rc == 1 and mine == "failed: a message (rank 1)" == py,
                  "status note: exit %d, %r / %r" % (rc, mine, py))


main(test)
