#!/usr/bin/python3
"""Patch test on an irregular mesh (options/patch.opts: 8x4 cells, -mesh_perturb 0.3), elastic:
uniaxial, biaxial and pure shear stretch must give the same stress in every element
(stress_spread < 1e-9) and the closed form (relative_error < 1e-9). The uniaxial run's HDF5 fields
(all steps) must also match the stored reference tests/regression/reference/patch_uniaxial.h5
(rtol 1e-8).

Regenerate the reference (only after a deliberate change of the results):
    /usr/bin/python3 tests/regression/test_regression_patch.py build/etfe --regenerate
"""
import os
import shutil
import sys

import numpy as np

sys.dont_write_bytecode = True  # no __pycache__ in the repository
import etfe_testlib as T  # noqa: E402

REFERENCE = os.path.join(T.HERE, "reference", "patch_uniaxial.h5")
CASES = {
    "uniaxial": ["-patch_mode", "uniaxial"],
    "biaxial": ["-patch_mode", "biaxial", "-patch_strain_y", "0.01"],
    "pureshear": ["-patch_mode", "pureshear"],
}
# Tolerances against the reference: rtol 1e-8 of each field's largest value, plus an absolute
# floor for fields that are pure round-off in uniaxial tension (Syy, Sxy, the minimum principal
# stress ~ 1e-12 MPa; the reactions of unloaded supports).
REF_FIELDS = {"min_principal_stress": (1e-8, 1e-9)}
REF_RTOL, REF_ATOL = 1e-8, 1e-10


def main_test(etfe, chk):
    regenerate = "--regenerate" in sys.argv
    with T.scratch_dir("patch") as tmp:
        for name, extra in CASES.items():
            h5 = os.path.join(tmp, name + ".h5")
            rc, out = T.run(etfe, ["-options_file", T.opts("patch"), "-output_file", h5,
                                   "-load_monitor", "0"] + extra)
            spread = T.scene_value(out, "patch", "stress_spread")
            err = T.scene_value(out, "patch", "closed_form", "relative_error")
            sxx = T.scene_value(out, "patch", "closed_form", "Sxx")
            print("%s: stress_spread = %.3e, closed-form relative_error = %.3e (Sxx = %.10e)"
                  % (name, spread, err, sxx))
            chk.less(spread, 1e-9, "%s stress_spread" % name)
            chk.less(err, 1e-9, "%s closed_form relative_error" % name)
            chk.check(T.status(h5) == "complete", "%s results status is 'complete'" % name)
            steps = T.read_steps(h5)
            S = steps[-1][2]["stress"]
            chk.less(float(np.abs(S[:, 0] - sxx).max() / abs(sxx)), 1e-9,
                     "%s HDF5 stress[:,0] vs closed form (relative)" % name)
            if name == "uniaxial":
                # The mesh really is irregular: interior nodes are off the 125 x 125 mm grid.
                import h5py
                with h5py.File(h5, "r") as f:
                    X = f["mesh/coordinates"][()]
                off = np.abs(X[:, :2] / 125.0 - np.round(X[:, :2] / 125.0)).max()
                chk.check(off > 0.05, "mesh is perturbed (largest off-grid shift %.3f cell)" % off)
                if regenerate:
                    os.makedirs(os.path.dirname(REFERENCE), exist_ok=True)
                    shutil.copyfile(h5, REFERENCE)
                    print("reference written: %s (%d bytes)" % (REFERENCE, os.path.getsize(REFERENCE)))
                if not os.path.exists(REFERENCE):
                    raise T.TestFailure("reference %s missing; create it with --regenerate" % REFERENCE)
                failures, rows = T.h5compare.compare_rows(h5, REFERENCE, step="all", fields=REF_FIELDS,
                                                          default_rtol=REF_RTOL, default_atol=REF_ATOL)
                print(T.h5compare.format_table(rows))
                chk.check(len(rows) > 20, "reference comparison covered %d field/step pairs" % len(rows))
                chk.check(not failures, "uniaxial fields match %s (rtol 1e-8)%s" % (
                    os.path.relpath(REFERENCE, T.REPO), "" if not failures else ":\n    " + "\n    ".join(failures)))


if __name__ == "__main__":
    T.main(main_test)
