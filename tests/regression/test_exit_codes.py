#!/usr/bin/python3
"""Exit statuses a batch script can act on (docs/scheduler.md, "Exit status"): 0 complete, 75
interrupted or stopped (resubmit), 1 the run did not complete, 2 input refused, 3 system (out of
memory, disk full), 4 internal; an error never exits 75 or 10 (PETSc's own error code is not an
exit status: PETSC_ERR_ARG_INCOMP is 75). Also: a results file that cannot be written (/dev/full)
ends with its message and status 3, not a crash in MPI_Finalize; a restart whose results file is
missing or cut short is refused unless -output_allow_lost_steps, and then the status never says
complete (nor for a restart into a new results file); an unwritable checkpoint directory is refused at set-up, before any increment; the
memory check costs a factorization wherever the configured solver has one (GMRES + LU, PC
redundant on every rank)."""
import os
import struct
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the repository
import etfe_testlib as T  # noqa: E402

etfe = T.etfe_path()
chk = T.Checker("exit_codes")


def status_exit(path):
    rc, out = T.run(etfe, ["-results_status", path], expect_fail=None)
    line = next((l for l in out.splitlines() if l.startswith(path + ": ")), "")
    return rc, line[len(path) + 2:]


def damaged_steps_heap(data):
    """The results file's bytes with the local heap of the steps group (the one holding the names
    000001 and 000002) given a free-list offset past its data segment."""
    b = bytearray(data)
    i = b.find(b"HEAP")
    while i >= 0:
        size, _, addr = struct.unpack_from("<QQQ", b, i + 8)
        seg = bytes(b[addr:addr + size])
        if b"000001\0" in seg and b"000002\0" in seg:
            struct.pack_into("<Q", b, i + 16, size + 64)
            return bytes(b)
        i = b.find(b"HEAP", i + 4)
    raise T.TestFailure("no local heap with the step names in the results file")


def expect(what, args, want, words=(), np=1):
    rc, out = T.run(etfe, args, np=np, expect_fail=None, timeout=180)
    msg = T.error_message(out)
    ok = rc == want and all(w in msg for w in words)
    chk.check(ok, "%s: exit %d (want %d)%s" % (what, rc, want, "" if ok else "\n" + T.tail(out)))
    return rc, out


with T.scratch_dir("exitcodes") as tmp:
    # Input refused: 2 (each of these exited 75 = PETSC_ERR_ARG_INCOMP before).
    expect("catenoid (form finding) with a hold", ["-options_file", T.opts("catenoid"), "-load_hold_after", "1",
                                                   "-load_hold_duration", "10", "-output", "0"], 2, ["-load_hold_after"])
    expect("patch with -patch_shear in uniaxial mode", ["-options_file", T.opts("patch"), "-patch_shear", "0.01",
                                                        "-output", "0"], 2, ["-patch_shear"])
    expect("tension field with the viscoelastic law", ["-options_file", T.opts("patch"), "-membrane_wrinkling",
                                                       "tension_field", "-material_type", "viscoelastic_plastic",
                                                       "-output", "0"], 2, ["tension_field"])
    expect("the same on 2 ranks (MPI_Abort's status through mpirun)",
           ["-options_file", T.opts("patch"), "-patch_shear", "0.01", "-output", "0"], 2, ["-patch_shear"], np=2)
    expect("an unknown -pc_type", ["-options_file", T.opts("patch"), "-pc_type", "nonesuch", "-output", "0"], 2)
    expect("a missing options file", ["-options_file", os.path.join(tmp, "none.opts")], 2)

    # The run did not complete: 1 (was 91, PETSC_ERR_NOT_CONVERGED).
    out = os.path.join(tmp, "diverged.h5")
    expect("Hencky with one Newton iteration and no cut-back", ["-options_file", T.opts("hencky"), "-snes_max_it", "1",
                                                               "-load_max_cutbacks", "0", "-output_file", out], 1,
           ["did not converge"])
    rc, st = status_exit(out)
    chk.check(rc == 1 and st.startswith("failed:"), "its results: status %r, -results_status exits %d (want 1)" % (st[:60], rc))

    # A results file on a full disk: the message and 3 (was a segmentation fault in MPI_Finalize, 139).
    rc, log = expect("Hencky with -output_file /dev/full", ["-options_file", T.opts("hencky"), "-output_file",
                                                            "/dev/full"], 3, ["/dev/full", "No space left on device"])
    chk.check("Segmentation" not in log and "signal number 11" not in log, "no segmentation fault after the message")

    # An unwritable checkpoint directory: refused at set-up (no results file made, no increment run).
    blocker = os.path.join(tmp, "a_file")
    open(blocker, "w").close()
    out = os.path.join(tmp, "ck_dir.h5")
    rc, log = expect("capstan with -checkpoint_file under a regular file",
                     ["-options_file", T.opts("capstan"), "-output_file", out, "-checkpoint_file",
                      os.path.join(blocker, "run.checkpoint.h5"), "-load_monitor", "1"], 2, ["-checkpoint_file"])
    chk.check(not os.path.exists(out) and not T.increments(log), "refused before the results file and any increment "
              "(results file %s, %d increments)" % ("made" if os.path.exists(out) else "none", len(T.increments(log))))

    # Results deleted or cut short before a restart.
    d = os.path.join(tmp, "restart")
    os.makedirs(d)
    out, ck = os.path.join(d, "run.h5"), os.path.join(d, "run.checkpoint.h5")
    base = ["-options_file", T.opts("capstan"), "-output_file", out, "-load_monitor", "0"]
    T.run(etfe, base + ["-checkpoint_every", "5", "-load_stop_after", "13"])
    rc, st = status_exit(out)
    chk.check(rc == 75 and st.startswith("stopped"), "stopped run: -results_status exits %d (want 75)" % rc)
    whole = open(out, "rb").read()
    os.remove(out)
    rc, log = expect("restart with the results deleted", base + ["-restart", ck], 2,
                     [out, "is missing", "-output_allow_lost_steps"])
    chk.check(not os.path.exists(out), "refused: no new results file")
    with open(out, "wb") as f:
        f.write(whole[:len(whole) // 2])
    before = open(out, "rb").read()
    expect("restart with the results cut short", base + ["-restart", ck], 2, [out, "cannot be read",
                                                                             "-output_allow_lost_steps"])
    chk.check(open(out, "rb").read() == before and sorted(os.listdir(d)) == sorted(
        n for n in os.listdir(d) if not n.endswith(".unreadable")), "refused: the cut-short file unchanged, not moved")
    # A kill while a step is added can leave the steps group's index unreadable ("bad heap free
    # list", seen in the fault campaign): here its local heap's free-list offset is pointed past
    # the heap. Refused too, the file unchanged.
    with open(out, "wb") as f:
        f.write(damaged_steps_heap(whole))
    before = open(out, "rb").read()
    expect("restart with the results' list of steps damaged", base + ["-restart", ck], 2,
           [out, "cannot be read", "-output_allow_lost_steps"])
    chk.check(open(out, "rb").read() == before, "refused: the damaged file unchanged")
    other = os.path.join(d, "other.h5")
    rc, log = T.run(etfe, base[:-4] + ["-output_file", other, "-load_monitor", "0", "-restart", ck])
    rc, st = status_exit(other)
    chk.check(rc == 1 and st.startswith("incomplete:") and "new results file" in st and out in st,
              "a restart into a new -output_file runs; its status %r names the file with the earlier steps, "
              "-results_status exits %d (want 1)" % (st[:100], rc))
    os.remove(out)
    T.run(etfe, base + ["-restart", ck, "-output_allow_lost_steps"])
    rc, st = status_exit(out)
    chk.check(rc == 1 and st.startswith("incomplete:") and "increment 13" in st,
              "continued with -output_allow_lost_steps: status %r, -results_status exits %d (want 1)" % (st[:90], rc))

    # The memory check: a factorization wherever the configured solver has one. Hencky (24 rings,
    # 5 403 DOF) needs ~13.5 MB with one factorization, ~5.9 MB as a lean Krylov method.
    small = ["-options_file", T.opts("hencky"), "-output", "0", "-load_increments", "1"]
    expect("GMRES + LU on a 0.01 GB node (costed as a Krylov method before)",
           small + ["-ksp_type", "gmres", "-pc_type", "lu", "-etfe_memory_node_gb", "0.01"], 3,
           ["memory:", "factorization"])
    expect("PC redundant + LU on 2 ranks of a 0.02 GB node (every rank factors the whole system)",
           small + ["-options_file", os.path.join(T.OPTIONS, "solvers", "redundant_lu.opts"), "-etfe_memory_node_gb",
                    "0.02"], 3, ["memory:", "redundant"], np=2)
    expect("MUMPS LU on 2 ranks of the same node (one factorization in parts: fits)",
           small + ["-options_file", os.path.join(T.OPTIONS, "solvers", "mumps_lu.opts"), "-etfe_memory_node_gb",
                    "0.02"], 0, np=2)
    expect("block Jacobi with LU blocks on a 0.01 GB node", small + ["-ksp_type", "gmres", "-pc_type", "bjacobi",
                                                                     "-sub_pc_type", "lu", "-etfe_memory_node_gb",
                                                                     "0.01"], 3, ["block Jacobi"])
chk.finish()
