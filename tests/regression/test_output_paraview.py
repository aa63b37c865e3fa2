#!/usr/bin/python3
"""ParaView shows every field of the results: the .xmf of a plastic patch, a wrinkling annulus and
a capstan (contact), each a few increments, opened with ParaView's three XDMF readers ("Xdmf3
Reader S", the one the README names, "Xdmf3 Reader T" and the XDMF2 "XDMF Reader"):
  * every row of the field table (the results file's root attribute field_table) that the run
    writes is an array of the last step under its viewer name, with the row's number of columns
    as its components (a Tensor6 row: 6 in the XDMF3 readers, 9 in the XDMF2 one, which expands
    the symmetric tensor), on points (node rows) or cells (element and contact pair rows), with
    one tuple per node, element or pair;
  * no reader complains: no "Skipping unrecognized array type" (the XDMF3 readers drop a
    HyperSlab column so) and no error line.
Needs ParaView's pvpython; without it the test prints that it skipped and why, and passes (CI
installs only what scripts/setup installs, and ParaView is not among them).
"""
import json
import os
import shutil
import subprocess
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the repository
import etfe_testlib as T  # noqa: E402

CASES = {  # name: options (the patch writes the plastic rows, the annulus the wrinkling ones)
    "patch": ["-options_file", T.opts("patch"), "-material_type", "plastic", "-patch_strain_x", "0.05",
              "-load_increments", 2],
    "annulus": ["-options_file", T.opts("annulus"), "-load_increments", 2],
    "capstan": ["-options_file", T.opts("capstan"), "-load_monitor", 0, "-output_every", 40],
}
READERS = ("Xdmf3ReaderS", "Xdmf3ReaderT", "XDMFReader")

# Run by pvpython: for each reader, the arrays of every leaf block at the last time step.
SCRIPT = r"""
import json, sys
from paraview import servermanager
import paraview.simple as pv
fn, out = sys.argv[1], {}
for name in %r:
    r = pv.XDMFReader(FileNames=[fn]) if name == "XDMFReader" else getattr(pv, name)(FileName=[fn])
    r.UpdatePipelineInformation()
    ts = list(r.TimestepValues)
    r.UpdatePipeline(ts[-1] if ts else 0)
    d = servermanager.Fetch(r)
    leaves = []
    def walk(b):
        if b is None:
            return
        if b.IsA("vtkMultiBlockDataSet"):
            for i in range(b.GetNumberOfBlocks()):
                walk(b.GetBlock(i))
            return
        if b.IsA("vtkMultiPieceDataSet"):  # the XDMF3 readers wrap a spatial collection's grids
            for i in range(b.GetNumberOfPieces()):
                walk(b.GetPiece(i))
            return
        arrays = {}
        for kind, data in (("node", b.GetPointData()), ("cell", b.GetCellData())):
            for i in range(data.GetNumberOfArrays()):
                a = data.GetArray(i)
                arrays[a.GetName()] = [kind, a.GetNumberOfComponents(), a.GetNumberOfTuples()]
        leaves.append({"points": b.GetNumberOfPoints(), "cells": b.GetNumberOfCells(), "arrays": arrays})
    walk(d)
    out[name] = {"steps": len(ts), "leaves": leaves}
print("PVJSON " + json.dumps(out))
""" % (READERS,)


def pvpython_command():
    """pvpython, or None; ParaView 5.11 reads without a display, xvfb-run is the fallback."""
    pv = shutil.which("pvpython")
    return [pv] if pv else None


def read_with_paraview(cmd, xmf, tmp):
    script = os.path.join(tmp, "read_arrays.py")
    with open(script, "w") as f:
        f.write(SCRIPT)
    runs = [cmd + [script, xmf]]
    if shutil.which("xvfb-run"):
        runs.append(["xvfb-run", "-a"] + cmd + [script, xmf])
    for argv in runs:
        p = subprocess.run(argv, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=300)
        text = p.stdout.decode("utf-8", "replace")
        line = [l for l in text.splitlines() if l.startswith("PVJSON ")]
        if p.returncode == 0 and line:
            return json.loads(line[0][len("PVJSON "):]), text, " ".join(argv[:-2])
    return None, text, " ".join(argv[:-2])


def expected_rows(f, table):
    """The rows this file writes with a viewer name: (name, viewer, location, components)."""
    last = "steps/%06d" % T.h5compare.written_steps(f)[-1]
    rows = []
    for r in table:
        if not r["xdmf"]:
            continue
        if r["name"] in f or r["name"] in f[last]:
            rows.append((r["name"], r["xdmf"], r["location"], int(r["components"]), r["vector_field_type"]))
    return rows


def check_case(chk, case, h5, seen, log):
    import h5py
    with h5py.File(h5, "r") as f:
        lines = T.h5compare.text(f.attrs["field_table"]).strip("\n").split("\n")
        keys = lines[0].split("\t")
        table = [dict(zip(keys, l.split("\t"))) for l in lines[1:]]
        rows = expected_rows(f, table)
        last = f["steps/%06d" % T.h5compare.written_steps(f)[-1]]
        count = {"node": f["mesh/coordinates"].shape[0], "cell": f["mesh/triangles"].shape[0],
                 "contact pair": last["contact/force"].shape[0] if "contact/force" in last else 0}
        nsteps = len(T.h5compare.written_steps(f))
    noise = [l for l in log.splitlines() if "Skipping unrecognized" in l or "ERR|" in l or "XDMF Error" in l]
    chk.check(not noise, "%s: ParaView's readers print no skipped array and no error%s" % (
        case, "" if not noise else ": %d lines, first %r" % (len(noise), noise[0])))
    for reader in READERS:
        got = seen.get(reader)
        if not got or not got["leaves"]:
            chk.check(False, "%s: %s read nothing" % (case, reader))
            continue
        film = got["leaves"][0]
        contact = got["leaves"][1] if len(got["leaves"]) > 1 else None
        bad = []
        for name, viewer, location, cols, kind in rows:
            block = contact if location == "contact pair" else film
            want_kind = "node" if location == "node" else "cell"
            want_cols = 9 if cols == 6 and reader == "XDMFReader" else cols
            # One name: the whole row; several (a table that names the columns): one scalar each.
            names = viewer.split()
            for shown in names:
                want = [want_kind, want_cols if len(names) == 1 else 1, count[location]]
                a = (block or {"arrays": {}})["arrays"].get(shown)
                if a is None:
                    bad.append("%s (%s) missing" % (shown, name))
                elif a != want:
                    bad.append("%s (%s): %s, %d components, %d tuples; want %s, %d, %d" % (
                        (shown, name) + tuple(a) + tuple(want)))
        chk.check(got["steps"] == nsteps and not bad,
                  "%s: %s shows all %d fields of the table this run writes, each with its columns as "
                  "components (%d steps)%s" % (case, reader, len(rows), got["steps"],
                                               "" if not bad else ": " + "; ".join(bad[:6])))


def main_test(etfe, chk):
    cmd = pvpython_command()
    if not cmd:
        print("  SKIP  test_output_paraview: pvpython (ParaView) is not installed, so the .xmf cannot be "
              "opened with ParaView's readers (apt-get install paraview to run it); nothing checked")
        return
    with T.scratch_dir("paraview") as tmp:
        for case, args in CASES.items():
            h5 = os.path.join(tmp, case + ".h5")
            T.run(etfe, args + ["-output_file", h5])
            seen, log, how = read_with_paraview(cmd, os.path.splitext(h5)[0] + ".xmf", tmp)
            if seen is None:
                chk.check(False, "%s: %s could not read the .xmf: %s" % (case, how, T.tail(log, 8)))
                continue
            check_case(chk, case, h5, seen, log)


if __name__ == "__main__":
    T.main(main_test)
