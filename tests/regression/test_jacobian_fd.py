#!/usr/bin/python3
"""Hand-coded Jacobian against PETSc's finite-difference Jacobian (-snes_test_jacobian) on small
scenes, at the first two Newton iterates of a single load increment:
  * hencky, 3 rings: follower pressure on a bulged membrane, i.e. including the non-symmetric
    pressure load stiffness;
  * patch, plastic material, -patch_strain_x 0.05 in one increment: at the first iterate the
    column of elements next to the displaced edge is stretched ~40% (far beyond the 13.28 MPa
    yield), so the consistent elasto-plastic tangent is tested; the rest is elastic.

Why the ratio PETSc prints is not the number to assert: the residual is R = u - u_prescribed on
constrained DOFs, and the Jacobian deliberately drops the columns of constrained DOFs (see
src/assembly/assemble.cpp: a symmetric operator stays symmetric; exact for Newton because every
iterate already carries the prescribed values, so the constrained part of every Newton step is
zero). The finite-difference Jacobian does contain dR_free/du_constrained, so PETSc's
||J - Jfd||_F/||J||_F is O(0.1) by design (measured 0.25 for hencky, 0.14-0.16 for the patch).
The test therefore reads both matrices at full precision (-snes_test_jacobian_view ::ascii_matlab)
and asserts
  * ||J - Jfd||_F/||J||_F over the free-free block < 1e-5 (every evaluation),
  * constrained rows of J and Jfd are unit rows, and J has no entries in constrained columns,
  * PETSc's printed ratio equals the one recomputed from the parsed matrices (so it is explained
    entirely by the dropped constrained columns plus the free-block difference).
The pressure load stiffness is small next to the membrane stiffness at the scene's pressure
(||L||/||J|| ~ 4e-5 on 3 rings), so it is also checked on its own: the first iterate (the
paraboloid initial guess) does not depend on the pressure, hence J(p) - J(0) is the hand-coded
pressure stiffness and Jfd(p) - Jfd(0) its finite-difference counterpart; on the free block they
must agree to 1e-3 at the scene's p = 2e-4 MPa and to 1e-5 at p = 2e-2 MPa. The element pressure
stiffness is non-symmetric, but with the whole rim clamped the assembled free block is symmetric
(conservative load on a surface with a fixed boundary); the test reports that asymmetry.
-snes_test_jacobian is read only when the Jacobian is first evaluated, so the solver's unused-
option check flags it before the solve: the runs need -options_allow_unused.

Contact: the same free-free comparison on the capstan (a strip over a pipe; the pairs
are node-local, so contact only adds 3x3 blocks on the diagonal of J) and on the saddle's arch:
  * capstan, implicit law in stick (-capstan_pull 1e-4) and in gross slip, the lagged law: every
    Newton iterate of every increment agrees to FREE_LIMIT, except where the law has no
    derivative: the first iterate (u = 0, every pair exactly at w = 0, where f_z = kn min(w, 0)
    kinks). There the test asserts what holds: the mismatch lies only in the node blocks on the
    diagonal (couplings between nodes agree to FREE_LIMIT) and is the jump kn (measured: exactly
    kn). In the stick-to-slip increment of the slip case pairs slip by small amounts, where the
    slip law f_t = mu |f_z| t/|t| is strongly curved, and PETSc's forward difference (h = 1.5e-8
    |u|) leaves a truncation error in their node blocks (measured up to 4.9e-5 of ||J||); it
    shrinks with h (3.5e-6 with -snes_test_err 1e-9), so that increment is asserted with the
    smaller step, and at the default step only for the couplings between nodes.
  * -contact_normal follow: the tangent uses the frame of the current iterate without its
    derivative (docs/design.md). For a stuck pair the omitted terms cancel (its force is a fixed global
    vector), so stick agrees to FREE_LIMIT. For a slipping or frictionless pair the omitted term
    is (f_z x0 - f_x n) x0^T / rho (x0 circumferential, rho the radial distance; see
    tests/unit/test_contact_frame.cpp for dn/dp), of norm |f| / rho. Asserted: couplings between
    nodes agree to FREE_LIMIT; in the frictionless stage the largest node-block mismatch equals
    the closed form T_node * 2 sin(dphi/2) / R of an interior node (within 5 %); everywhere
    ||D_ff||_F <= sqrt(1 + mu^2) T_max theta / R (the whole radial load over the radius); and the
    mismatch in slip does not shrink with the FD step (it is the tangent's, not the FD's).
  * saddle arch (pd10a on a 7-cell quarter, implicit law, plastic film, no tangent shift): runs
    to increment k, checkpoints, restarts and tests the first two iterates of increment k + 1
    (FD step: see contact_saddle_arch).
"""
import math
import re
import sys

import numpy as np

sys.dont_write_bytecode = True  # no __pycache__ in the repository
import etfe_testlib as T  # noqa: E402

COMMON = ["-snes_test_jacobian", "-snes_test_jacobian_view", "::ascii_matlab", "-load_increments", "1",
          "-snes_max_it", "2", "-load_max_cutbacks", "0", "-options_allow_unused", "-output", "0"]
CASES = {  # name: (options file, extra options)
    "hencky_rings3_pressure": ("hencky", ["-mesh_rings", "3"]),
    "patch_plastic_0.05": ("patch", ["-material_type", "plastic", "-patch_strain_x", "0.05"]),
    # Tension field: the shear panel (3 x 2 cells, so every element touches a displaced
    # edge node: no element sits at E = 0, where the relaxed law has a kink) wrinkles; the relaxed
    # law's tangent includes the wrinkle direction's dependence on the strain.
    "patch_shear_tension_field": ("patch", ["-patch_mode", "shear", "-patch_strain_x", "1e-3", "-patch_shear", "0.01",
                                            "-membrane_wrinkling", "tension_field", "-mesh_nx", "3", "-mesh_ny", "2"]),
    # Viscous stabilization on every increment: the residual's k (u - u_n) and the tangent's
    # diagonal k on the free DOFs (constrained rows stay unit rows).
    "hencky_stabilized": ("hencky", ["-mesh_rings", "3", "-load_stabilize_when", "always", "-load_stabilize", "0.1"]),
}
FREE_LIMIT = 1e-5


def parse_tests(out):
    """[(petsc_ratio, J, Jfd)] for every Jacobian test in the output (dense numpy matrices)."""
    tests, cur, which, mat, rows = [], None, None, None, None
    for line in out.splitlines():
        m = re.search(r"\|\|J - Jfd\|\|_F/\|\|J\|\|_F = (%s)" % T.NUMBER, line)
        if m:
            cur = {"ratio": float(m.group(1))}
            tests.append(cur)
            continue
        if "Hand-coded Jacobian ----------" in line:
            which = "J"
        elif "Finite difference Jacobian ----------" in line:
            which = "Jfd"
        elif "Hand-coded minus finite-difference" in line:
            which = "diff"
        m = re.match(r"% Size = (\d+) (\d+)", line)
        if m:
            mat = np.zeros((int(m.group(1)), int(m.group(2))))
            continue
        if line.startswith("zzz = ["):
            rows = []
            continue
        if rows is not None:
            if line.startswith("];"):
                for i, j, v in rows:
                    mat[i - 1, j - 1] = v
                if cur is not None and which in ("J", "Jfd"):
                    cur[which] = mat
                rows = None
                continue
            p = line.split()
            if len(p) == 3:
                rows.append((int(p[0]), int(p[1]), float(p[2])))
    return [(t["ratio"], t.get("J"), t.get("Jfd")) for t in tests]


def analyse(J, Jfd):
    n = J.shape[0]
    unit = np.array([J[i, i] == 1.0 and np.count_nonzero(J[i]) == 1 for i in range(n)])
    fd_unit = np.array([abs(Jfd[i, i] - 1.0) < 1e-6 and np.count_nonzero(np.abs(Jfd[i]) > 1e-6) == 1
                        for i in range(n)])
    con = unit & fd_unit
    free = ~con
    D = J - Jfd
    Jff = J[np.ix_(free, free)]
    free_ratio = np.linalg.norm(D[np.ix_(free, free)]) / np.linalg.norm(Jff)
    recomputed = np.linalg.norm(D) / np.linalg.norm(J)
    return dict(n=n, ncon=int(con.sum()), free_ratio=free_ratio, recomputed=recomputed,
                con_cols_zero=bool(np.all(J[np.ix_(free, con)] == 0.0)),
                fd_coupling=np.linalg.norm(Jfd[np.ix_(free, con)]) / np.linalg.norm(J),
                unit_mismatch=int((unit != fd_unit).sum()),
                asym=np.linalg.norm(Jff - Jff.T) / np.linalg.norm(Jff))


def main_test(etfe, chk):
    report, tangents = [], {}
    for case, (scene, extra) in CASES.items():
        args = ["-options_file", T.opts(scene)] + extra
        rc, out = T.run(etfe, args + COMMON, expect_fail=None)
        tests = parse_tests(out)
        chk.check(len(tests) >= 2, "%s: %d Jacobian tests found in the output (expected 2: Newton iterates 0 and 1)"
                  % (case, len(tests)))
        for k, (ratio, J, Jfd) in enumerate(tests):
            if J is None or Jfd is None:
                chk.check(False, "%s test %d: matrices not found in the -snes_test_jacobian_view output" % (case, k))
                continue
            a = analyse(J, Jfd)
            report.append((case, k, ratio, a))
            tangents.setdefault(case, J)
            print("%s, Newton iterate %d: %d DOF (%d constrained); PETSc ||J - Jfd||_F/||J||_F = %.6g; "
                  "free-free block ratio = %.3e; FD coupling to constrained columns / ||J|| = %.4g; "
                  "free-block asymmetry ||K - K^T||/||K|| = %.3e"
                  % (case, k, a["n"], a["ncon"], ratio, a["free_ratio"], a["fd_coupling"], a["asym"]))
            chk.less(a["free_ratio"], FREE_LIMIT, "%s iterate %d: free-free ||J - Jfd||_F/||J||_F" % (case, k))
            chk.check(a["ncon"] > 0 and a["unit_mismatch"] == 0,
                      "%s iterate %d: constrained rows are unit rows in both J and Jfd (%d rows, %d mismatches)"
                      % (case, k, a["ncon"], a["unit_mismatch"]))
            chk.check(a["con_cols_zero"], "%s iterate %d: J has no entries in constrained columns" % (case, k))
            chk.check(math.isclose(a["recomputed"], ratio, rel_tol=1e-4),
                      "%s iterate %d: PETSc's ratio %.6g reproduced from the parsed matrices (%.6g)"
                      % (case, k, ratio, a["recomputed"]))
    pressure_stiffness(etfe, chk, report)
    plastic_tangent_active(etfe, chk, tangents)
    contact_capstan(etfe, chk, report)
    contact_saddle_arch(etfe, chk, report)
    sealed_cushion(etfe, chk, report)
    print("\nJacobian check summary (free-free block ratio; PETSc's whole-matrix ratio in brackets):")
    for case, k, ratio, a in report:
        name = case if "iterate" in case else "%s iterate %d" % (case, k)
        print("  %-52s %.3e  [%.4g]" % (name + ":", a["free_ratio"], ratio))


def sealed_cushion(etfe, chk, report):
    """A three-layer cushion with both chambers sealed from the start (a coarse hexagon, its foils
    a 100 mm lens): Newton's matrix is the sparse tangent plus the gas's rank-one stiffness
    (a MATLRC), against finite differences of the residual, whose pressures follow the volumes.
    PETSc tests the Jacobian and the preconditioning matrix in turn: the first must agree, the
    second (the sparse tangent alone) must not, by the size of the rank-one term."""
    args = ["-options_file", T.opts("cushion/hexagon_3layer"), "-mesh_file",
            "meshes/cushion_hexagon_3layer_coarse.msh", "-chamber_upper_sealed_from_stage", "1",
            "-chamber_lower_sealed_from_stage", "1", "-structure_reference", "mesh", "-membrane_tangent_shift", "0",
            "-membrane_wrinkling", "none"]
    rc, out = T.run(etfe, args + COMMON, expect_fail=None)
    tests = [t for t in parse_tests(out) if t[1] is not None]
    chk.check(len(tests) >= 4, "sealed cushion: %d Jacobian tests found (Jacobian and preconditioner, two iterates)"
              % len(tests))
    for k in range(0, len(tests) - 1, 2):
        lrc, sparse = analyse(tests[k][1], tests[k][2]), analyse(tests[k + 1][1], tests[k + 1][2])
        report.append(("sealed cushion (J + gas rank-one) iterate %d" % (k // 2), k, tests[k][0], lrc))
        chk.less(lrc["free_ratio"], FREE_LIMIT, "sealed cushion iterate %d: free-free ||J - Jfd||_F/||J||_F with the "
                                                "rank-one term" % (k // 2))
        chk.check(sparse["free_ratio"] > 1e-3, "sealed cushion iterate %d: without it (the sparse tangent alone) "
                                               "the mismatch is the gas's stiffness: %.3e" % (k // 2, sparse["free_ratio"]))


def plastic_tangent_active(etfe, chk, tangents):
    """The plastic patch case tests the elasto-plastic tangent only if elements are plastic at the
    first iterate: its J must differ from the elastic J (same E, nu) at the same state."""
    rc, out = T.run(etfe, ["-options_file", T.opts("patch"), "-patch_strain_x", "0.05"] + COMMON, expect_fail=None)
    tests = parse_tests(out)
    Jp = tangents.get("patch_plastic_0.05")
    if not tests or tests[0][1] is None or Jp is None:
        raise T.TestFailure("elastic patch Jacobian test missing:\n" + T.tail(out))
    d = np.linalg.norm(Jp - tests[0][1]) / np.linalg.norm(tests[0][1])
    print("plastic vs elastic Jacobian at the first iterate of the patch: ||Jp - Je||/||Je|| = %.3e" % d)
    chk.check(d > 1e-2, "patch iterate 0 is plastic: the elasto-plastic J differs from the elastic J by %.3e" % d)


def pressure_stiffness(etfe, chk, report):
    mats = {}
    for p in ("0", "2e-4", "2e-2"):
        rc, out = T.run(etfe, ["-options_file", T.opts("hencky"), "-mesh_rings", "3", "-hencky_pressure", p]
                        + COMMON, expect_fail=None)
        tests = parse_tests(out)
        if not tests or tests[0][1] is None:
            raise T.TestFailure("hencky -hencky_pressure %s: no Jacobian test in the output:\n%s" % (p, T.tail(out)))
        mats[p] = tests[0][1:]
    J0, F0 = mats["0"]
    n = J0.shape[0]
    free = ~np.array([J0[i, i] == 1.0 and np.count_nonzero(J0[i]) == 1 for i in range(n)])
    ff = np.ix_(free, free)
    for p, limit in (("2e-4", 1e-3), ("2e-2", 1e-5)):
        J, F = mats[p]
        dJ, dF = (J - J0)[ff], (F - F0)[ff]
        size = np.linalg.norm(dJ) / np.linalg.norm(J[ff])
        err = np.linalg.norm(dJ - dF) / np.linalg.norm(dJ)
        asym = np.linalg.norm(dJ - dJ.T) / np.linalg.norm(dJ)
        print("pressure stiffness at p = %s MPa: ||L||/||J|| = %.3e, ||L - L_fd||/||L|| = %.3e, "
              "assembled free-block asymmetry ||L - L^T||/||L|| = %.3e" % (p, size, err, asym))
        chk.check(size > 0, "pressure %s: the hand-coded Jacobian changes with the pressure" % p)
        chk.less(err, limit, "pressure %s MPa: free-block pressure stiffness vs finite differences" % p)
        report.append(("hencky_pressure_stiffness_p%s" % p, 0, float("nan"), dict(free_ratio=err)))


VIEW = ["-snes_test_jacobian", "-snes_test_jacobian_view", "::ascii_matlab", "-options_allow_unused", "-output", "0"]
CAPSTAN = ["-mesh_nx", "8", "-mesh_ny", "1", "-load_increments", "4"]  # steps 1-2 tension, 3-4 pull


def option_value(path, name):
    value = T.optionsfile.read_dict(path).get(name)
    if value is None:
        raise T.TestFailure("%s not set in %s" % (name, path))
    return float(value)


def by_step(out):
    """[(step, open, stick, slip, [(ratio, J, Jfd)])]: the tests printed before each progress line."""
    res, start = [], 0
    for i in T.increments(out):
        if i["open"] is None:
            continue
        res.append((i["step"], i["open"], i["stick"], i["slip"], parse_tests(out[start:i["span"][0]])))
        start = i["span"][1]
    return res


def blocks(J, Jfd):
    """Free-free mismatch split into the 3x3 node blocks on the diagonal (where node-to-support
    contact acts) and the couplings between nodes, relative to ||J_ff||."""
    n = J.shape[0]
    con = np.array([J[i, i] == 1.0 and np.count_nonzero(J[i]) == 1 for i in range(n)])
    D = J - Jfd
    D[con, :] = 0.0
    D[:, con] = 0.0
    node = np.arange(n) // 3
    diag = node[:, None] == node[None, :]
    jn = np.linalg.norm(J[np.ix_(~con, ~con)])
    per_node = [np.linalg.norm(D[3 * b:3 * b + 3, 3 * b:3 * b + 3]) for b in range(n // 3)]
    return dict(free=np.linalg.norm(D) / jn, between=np.linalg.norm(D[~diag]) / jn, jn=jn,
                d=np.linalg.norm(D), max_block=max(per_node))


def capstan_run(etfe, chk, case, extra):
    rc, out = T.run(etfe, ["-options_file", T.opts("capstan")] + CAPSTAN + extra + VIEW, expect_fail=None)
    steps = by_step(out)
    chk.check(len(steps) == 4 and all(s[4] for s in steps),
              "%s: 4 increments, each with its Jacobian tests (%d found)" % (case, len(steps)))
    return steps, T.scene_values(out, "capstan").get("theta", {}).get("end", float("nan"))


def contact_capstan(etfe, chk, report):
    path = T.opts("capstan")
    kn, kt, mu = (option_value(path, o) for o in ("-contact_kn", "-contact_kt", "-contact_mu"))
    t1, radius = option_value(path, "-capstan_t1"), option_value(path, "-capstan_radius")
    theta = option_value(path, "-capstan_angle") * math.pi / 180.0
    jump = max(kn, kt)
    # (case, options, steps checked, steps crossing a kink of the law, steps expected in stick).
    # Steps 1-2 of the follow case are its frictionless stage, checked in capstan_follow_slip below.
    cases = (("capstan_implicit_stick", ["-capstan_pull", "1e-4"], (1, 2, 3, 4), (), (3, 4)),
             ("capstan_implicit_slip", [], (1, 2, 3, 4), (3,), ()),
             ("capstan_implicit_slip_h1e-9", ["-snes_test_err", "1e-9"], (1, 2, 3, 4), (), ()),
             ("capstan_lagged", ["-contact_friction", "lagged"], (1, 2, 3, 4), (), ()),
             ("capstan_follow_stick", ["-contact_normal", "follow", "-capstan_pull", "1e-4"], (3, 4), (), (3, 4)))
    for case, extra, checked, curved, stick_steps in cases:
        steps, _ = capstan_run(etfe, chk, case, extra)
        for step, nopen, nstick, nslip, tests in steps:
            if step not in checked:
                continue
            if step in stick_steps:  # the pairs on end B, held by the grip, carry no force
                chk.check(nstick > nopen + nslip, "%s step %d: pairs stick (open %d stick %d slip %d)"
                          % (case, step, nopen, nstick, nslip))
            if case.startswith("capstan_implicit_slip") and step >= 3:
                chk.check(nstick == 0, "%s step %d: gross slip (stick %d slip %d)" % (case, step, nstick, nslip))
            for k, (ratio, J, Jfd) in enumerate(tests):
                b = blocks(J, Jfd)
                label = "%s step %d iterate %d" % (case, step, k)
                report.append((label, k, ratio, dict(free_ratio=b["free"])))
                chk.less(b["between"], FREE_LIMIT, "%s: couplings between nodes, ||D||/||J_ff||" % label)
                if step == 1 and k == 0:
                    chk.check(0.5 * kn <= b["max_block"] <= kn * (1 + 1e-6),
                              "%s: u = 0, every pair at w = 0 (the normal law's kink): largest node-block "
                              "mismatch %.6g is the jump kn = %g" % (label, b["max_block"], kn))
                elif step in curved:
                    print("  %s: %.3e free-free, largest node block %.4g (small slides on the curved slip "
                          "law: FD truncation; asserted with -snes_test_err 1e-9)" % (label, b["free"], b["max_block"]))
                    chk.check(b["max_block"] <= jump * (1 + 1e-6), "%s: node-block mismatch %.4g within the "
                              "law's largest jump %g" % (label, b["max_block"], jump))
                else:
                    chk.less(b["free"], FREE_LIMIT, "%s (open %d stick %d slip %d): free-free ||J - Jfd||/||J||"
                             % (label, nopen, nstick, nslip))

    # Follow frame in slip: the tangent omits the frame derivative; assert its closed form and bound.
    steps, t2 = capstan_run(etfe, chk, "capstan_follow_slip", ["-contact_normal", "follow"])
    small, _ = capstan_run(etfe, chk, "capstan_follow_slip_h1e-9", ["-contact_normal", "follow", "-snes_test_err", "1e-9"])
    for (step, _, _, _, tests), (_, _, _, _, tests_small) in zip(steps, small):
        if step == 4:
            for k, ((_, J, Jfd), (_, Js, Jfds)) in enumerate(zip(tests, tests_small)):
                d, ds = blocks(J, Jfd)["d"], blocks(Js, Jfds)["d"]
                chk.check(abs(ds / d - 1) < 0.1, "capstan_follow_slip step 4 iterate %d: the mismatch %.4g stays "
                          "%.4g with a 15x smaller FD step (the tangent omits it, not a FD error)" % (k, d, ds))
    ny, nx = int(CAPSTAN[3]), int(CAPSTAN[1])
    dphi = theta / nx
    bound = math.sqrt(1 + mu * mu) * max(t1, t2) * theta / radius
    for step, nopen, nstick, nslip, tests in steps:
        for k, (ratio, J, Jfd) in enumerate(tests):
            b = blocks(J, Jfd)
            label = "capstan_follow_slip step %d iterate %d" % (step, k)
            report.append((label, k, ratio, dict(free_ratio=b["free"])))
            chk.less(b["between"], FREE_LIMIT, "%s: couplings between nodes, ||D||/||J_ff||" % label)
            if step == 1 and k == 0:
                continue  # u = 0: the touch-down kink, as above
            chk.check(b["d"] <= bound, "%s: ||D_ff||_F = %.4g (%.2e of ||J||) within the omitted frame "
                      "derivative's bound sqrt(1 + mu^2) T_max theta / R = %.4g"
                      % (label, b["d"], b["free"], bound))
            if step <= 2:  # frictionless tension stage: T = T1 * load time on the whole wrap
                share = 0.5 if ny == 1 else 1.0 / ny  # the largest share of the width a node carries
                t_node = t1 * (step / 2.0) * share
                closed = t_node * 2 * math.sin(dphi / 2) / radius
                chk.check(abs(b["max_block"] / closed - 1) < 0.05,
                          "%s: largest node-block mismatch %.5g = f_z / R of an interior node %.5g "
                          "(the omitted frame derivative; %+.1f %%)"
                          % (label, b["max_block"], closed, 100 * (b["max_block"] / closed - 1)))


def contact_saddle_arch(etfe, chk, report):
    """At the predictor iterate the arch pairs slip by a small amount, where the slip law
    f_t = mu |f_z| t/|t| is strongly curved: PETSc's forward difference (h = 1.5e-8 |u|) then
    leaves a truncation error in those pairs' node blocks (measured 6.7e-6 and 1.5e-5 of ||J||).
    It shrinks with h (15x smaller h: 5e-7 and 1e-6), so the agreement is asserted with
    -snes_test_err 1e-9 and, at PETSc's default h, only for the couplings between nodes."""
    base = ["-options_file", T.opts("saddle/pd10a"), "-mesh_n", "7", "-load_increments", "8", "-output", "0",
            "-membrane_tangent_shift", "0", "-membrane_tangent_shift_adaptive", "false", "-load_monitor", "1",
            "-load_stabilize_when", "never"]  # the plain Newton iterates of the failing increment
    with T.scratch_dir("etfe-jacobian") as d:
        for k in (2, 4):
            cp = "%s/saddle_%d.h5" % (d, k)
            T.run(etfe, base + ["-load_stop_after", k, "-checkpoint_file", cp])
            found = {}
            for h in ("default", "1e-9"):
                rc, out = T.run(etfe, base + ["-restart", cp, "-load_stop_after", k + 1, "-snes_max_it", "2",
                                              "-load_max_cutbacks", "0"] + VIEW
                                + ([] if h == "default" else ["-snes_test_err", h]), expect_fail=None)
                found[h] = parse_tests(out)
                chk.check(len(found[h]) >= 2, "saddle arch increment %d, FD step %s: %d Jacobian tests"
                          % (k + 1, h, len(found[h])))
            for i, ((r0, J0, F0), (ratio, J, Jfd)) in enumerate(zip(found["default"], found["1e-9"])):
                b0, b = blocks(J0, F0), blocks(J, Jfd)
                label = "saddle_arch increment %d iterate %d" % (k + 1, i)
                report.append((label + " (FD err 1e-9)", i, ratio, dict(free_ratio=b["free"])))
                chk.less(b0["between"], FREE_LIMIT, "%s, default FD step (free-free %.2e): couplings between "
                         "nodes, ||D||/||J_ff||" % (label, b0["free"]))
                chk.less(b["free"], FREE_LIMIT, "%s, -snes_test_err 1e-9: free-free ||J - Jfd||/||J||" % label)

if __name__ == "__main__":
    T.main(main_test)
