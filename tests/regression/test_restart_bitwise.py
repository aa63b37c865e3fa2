"""Checkpoint/restart: a run stopped after increment k (-load_stop_after, which writes a
checkpoint) and continued with -restart gives the same results as the uninterrupted run, bit for
bit, on 1 and 2 ranks (on 2 ranks with options/solvers/redundant_lu.opts: parallel MUMPS
schedules its factorisation dynamically, so on a busy machine its round-off can differ from run
to run; with it the 2-rank restart is checked to 1e-8 instead): a plastic patch over load/unload/reload stages (history variables), the
capstan (contact state, the scene's own slip-onset monitor) and, on 1 rank, PD15a with the arch
fixed, stopped at a stage end (the next increment starts with the tangent predictor, whose tangent
must not depend on the last Newton solve, which the restarted run has not made; the adaptive
tangent shift; stabilized increments). A checkpoint of another scene, mesh
or material, and a truncated file, are refused with a message."""
import hashlib
import os
import shutil

import h5py

from etfe_testlib import Checker, etfe_path, opts, run, scratch_dir
import h5compare

etfe = etfe_path()
chk = Checker("restart_bitwise")
cases = {  # name: (options, increment to stop after, rank variants)
    "patch": (["-options_file", opts("patch"), "-material_type", "plastic", "-patch_strain_x", 0.2,
               "-patch_schedule", "1,0.8,1.5", "-load_increments", 30], 13, None),
    "capstan": (["-options_file", opts("capstan")], 13, None),
    "saddle": (["-options_file", opts("saddle/pd15a"), "-contact_friction", "fixed", "-load_increments", 60], 20,
               ((1, []),)),
}
with scratch_dir() as tmp:
    for name, (base, stop, variants) in cases.items():
        for np, solver in variants or ((1, []), (2, ["-options_file", "options/solvers/redundant_lu.opts"]), (2, None)):
            exact = solver is not None
            tag = "%s%d%s" % (name, np, "" if exact else "mumps")
            full, part, ck = (os.path.join(tmp, "%s_%s.h5" % (tag, k)) for k in ("full", "part", "ck"))
            common = base + ["-load_monitor", 0] + (solver or [])
            rc, out_full = run(etfe, common + ["-output_file", full], np=np)
            rc, out1 = run(etfe, common + ["-output_file", part, "-load_stop_after", stop, "-checkpoint_file", ck], np=np)
            chk.check(os.path.exists(ck) and "stopped as asked" in out1,
                      "%s np=%d: stopped at %d with a checkpoint" % (name, np, stop))
            rc, out2 = run(etfe, common + ["-output_file", part, "-restart", ck], np=np)
            # Parallel MUMPS: each run converges Newton to its tolerance from other round-off, so the
            # runs agree to about that tolerance (1e-10 relative seen on a busy machine), not bit for bit.
            tol = 0.0 if exact else 1e-8
            # Parallel MUMPS round-off differs between runs: fields are measured against their
            # family (min_principal_stress of the uniaxial patch is ~1e-12 MPa beside ~20 MPa).
            fails = h5compare.compare(full, part, step="all", default_rtol=tol, default_atol=tol * 1e-3,
                                      family_scale=not exact)
            chk.check(not fails, "%s np=%d%s: restarted results equal the uninterrupted run %s (all steps)%s"
                      % (name, np, "" if exact else " (parallel MUMPS)", "bit for bit" if exact else "to 1e-8",
                         "" if not fails else ": " + "; ".join(map(str, fails[:3]))))
            lines_full = [l for l in out_full.splitlines() if l.startswith(("mu_eff", "patch:", "capstan:", "saddle:"))]
            lines_part = [l for l in out2.splitlines() if l.startswith(("mu_eff", "patch:", "capstan:", "saddle:"))]
            if exact:
                chk.check(lines_full == lines_part and lines_full, "%s np=%d: the scene's report is identical" % (name, np))
    # refusals
    ck_patch = os.path.join(tmp, "patch1_ck.h5")
    ck_cap = os.path.join(tmp, "capstan1_ck.h5")
    bad = os.path.join(tmp, "truncated.h5")
    with open(ck_cap, "rb") as f:
        data = f.read()
    with open(bad, "wb") as f:
        f.write(data[:len(data) // 3])
    flipped = os.path.join(tmp, "flipped.h5")
    shutil.copy(ck_cap, flipped)
    with h5py.File(ck_cap, "r") as f:
        offset = f["u_committed"].id.get_offset()
    with open(flipped, "r+b") as f:  # one bit of one displacement value
        f.seek(offset + 8 * 7 + 2)
        byte = f.read(1)
        f.seek(offset + 8 * 7 + 2)
        f.write(bytes([byte[0] ^ 0x04]))
    # A refused restart leaves the results file it would continue exactly as it was (here a
    # complete run's file, which a restart would first cut back to the checkpoint's step).
    results = os.path.join(tmp, "capstan1_full.h5")
    digest = hashlib.sha256(open(results, "rb").read()).hexdigest()
    capstan = cases["capstan"][0] + ["-load_monitor", 0, "-output_file", results]
    for args, words in ((["-restart", ck_patch], "scene patch"),
                        (["-contact_mu", 0.5, "-restart", ck_cap], "-contact_mu checkpoint: 0.3 this run: 0.5"),
                        (["-membrane_thickness", 0.3, "-restart", ck_cap], "-membrane_thickness"),
                        (["-load_increments", 80, "-restart", ck_cap], "-load_increments"),
                        (["-restart", flipped], "checksum"),
                        (["-mesh_nx", 32, "-restart", ck_cap], "mesh"),
                        (["-material_type", "plastic", "-restart", ck_cap], "-material_type checkpoint: elastic this run: plastic"),
                        (["-restart", bad], "corrupt"),
                        (["-restart", os.path.join(tmp, "none.h5")], "checkpoint")):
        rc, out = run(etfe, capstan + args, expect_fail=True)
        chk.check(words in " ".join(out.split()),
                  "refused %s with a message naming the %s" % (" ".join(map(str, args)), words))
        chk.check(hashlib.sha256(open(results, "rb").read()).hexdigest() == digest,
                  "the refused restart (%s) left the results file unchanged" % " ".join(map(str, args)))
    # Solver and output options may change on a restart.
    rc, out = run(etfe, capstan[:-1] + [os.path.join(tmp, "solver_change.h5"), "-restart", ck_cap,
                                        "-snes_rtol", "1e-10", "-load_max_cutbacks", 8, "-load_max_it", 40])
    chk.check(rc == 0 and "restart: from" in out,
              "a restart with other solver options (-snes_rtol, -load_max_cutbacks, -load_max_it) runs")
chk.finish()
