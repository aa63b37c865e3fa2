#!/usr/bin/python3
"""Results file layout and its XDMF index: a plastic patch over three stages (load, unload,
reload) with -output_every 2 and an odd number of increments.
  * every DataItem "<file>.h5:/path" of the .xmf exists in the HDF5 file with the declared
    dimensions, number type and precision; topology/geometry/attribute sizes are consistent;
  * one temporal grid per written step, names step_<k:06d>, times strictly increasing and equal to
    the step attributes (stage, load_factor consistent with time);
  * the written steps are 0, every 2nd increment and the last one; steps_written agrees;
  * status "complete"; plastic_strain_eq present and > 0 in every element at the end.
If pvpython (ParaView) is on PATH the .xmf is also opened with ParaView's XDMF3 reader;
otherwise that part is skipped (ParaView is not installed by the test).
"""
import math
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

import numpy as np

sys.dont_write_bytecode = True  # no __pycache__ in the repository
import etfe_testlib as T  # noqa: E402

INCREMENTS = 9  # 3 per stage; odd, so the last increment is not a multiple of -output_every
EVERY = 2
DTYPES = {("Int", "4"): np.dtype("int32"), ("Float", "8"): np.dtype("float64"),
          ("Int", "8"): np.dtype("int64"), ("Float", "4"): np.dtype("float32")}


def main_test(etfe, chk):
    import h5py
    with T.scratch_dir("xdmf") as tmp:
        h5 = os.path.join(tmp, "out", "plastic_patch.h5")  # a directory the solver must create
        xmf = os.path.splitext(h5)[0] + ".xmf"
        rc, out = T.run(etfe, ["-options_file", T.opts("patch"), "-material_type", "plastic",
                               "-patch_strain_x", "0.05", "-patch_schedule", "1,0.5,1.5",
                               "-load_increments", INCREMENTS, "-output_every", EVERY, "-output_file", h5])
        incs = T.increments(out)
        chk.check(len(incs) == INCREMENTS, "%d increments converged (expected %d)" % (len(incs), INCREMENTS))
        chk.check(os.path.exists(xmf), "XDMF index %s written beside the results" % os.path.basename(xmf))
        chk.check(not os.path.exists(xmf + ".tmp"), "no temporary .xmf.tmp left behind")

        root = ET.parse(xmf).getroot()
        with h5py.File(h5, "r") as f:
            chk.check(T.h5compare.text(f.attrs["status"]) == "complete", "status 'complete'")
            chk.check(T.h5compare.text(f.attrs["format"]) == "etfe-results-1", "format etfe-results-1")
            chk.check(T.h5compare.text(f.attrs["scene"]) == "patch", "scene attribute 'patch'")
            h5steps = sorted(int(k) for k in f["steps"])
            last = incs[-1]["step"] if incs else INCREMENTS
            expected = sorted({0} | {k for k in range(1, last + 1) if k % EVERY == 0} | {last})
            chk.check(h5steps == expected, "written steps %s == 0, every %dnd and the last %s" % (h5steps, EVERY, expected))
            chk.check(int(f.attrs["steps_written"]) == len(h5steps), "steps_written = %d" % int(f.attrs["steps_written"]))
            N, E = f["mesh/coordinates"].shape[0], f["mesh/triangles"].shape[0]

            # Every DataItem points at an existing dataset with the declared shape and type.
            items = root.iter("DataItem")
            nitems = bad = 0
            for it in items:
                if it.get("Format") == "XML":  # a hyperslab's (start, stride, count)
                    sel = [int(x) for x in it.text.split()]
                    chk.check(len(sel) == 6 and sel[2:4] == [1, 1], "hyperslab selection %s" % sel)
                    continue
                if it.get("ItemType") == "HyperSlab":  # one column of the HDF item inside it
                    inner = [c for c in it if c.get("Format") == "HDF"][0]
                    rows, cols = (int(x) for x in inner.get("Dimensions").split())
                    sel = [int(x) for x in [c for c in it if c.get("Format") == "XML"][0].text.split()]
                    ok = it.get("Dimensions") == "%d 1" % rows and 0 <= sel[1] < cols and sel[4:] == [rows, 1]
                    chk.check(ok, "hyperslab %s selects one column of %s" % (sel, inner.text.strip()))
                    continue
                nitems += 1
                ref = it.text.strip()
                fname, path = ref.split(":", 1)
                dims = tuple(int(d) for d in it.get("Dimensions").split())
                ok = fname == os.path.basename(h5) and it.get("Format") == "HDF" and path in f
                if ok:
                    d = f[path]
                    want = DTYPES.get((it.get("NumberType"), it.get("Precision")))
                    ok = d.shape == dims and want is not None and d.dtype == want
                if not ok:
                    bad += 1
                    chk.check(False, "DataItem %s (Dimensions %s, %s %s) does not match the HDF5 file" % (
                        ref, dims, it.get("NumberType"), it.get("Precision")))
            chk.check(nitems > 0 and bad == 0, "%d DataItems, all resolve to datasets of the declared shape and type" % nitems)

            coll = root.find("Domain/Grid")
            chk.check(coll is not None and coll.get("GridType") == "Collection" and coll.get("CollectionType") == "Temporal",
                      "a temporal collection grid")
            grids = coll.findall("Grid") if coll is not None else []
            names = [g.get("Name") for g in grids]
            chk.check(names == ["step_%06d" % k for k in h5steps], "one grid per written step, in order (%d grids)" % len(grids))
            times = [float(g.find("Time").get("Value")) for g in grids]
            chk.check(all(b > a for a, b in zip(times, times[1:])), "times strictly increase: %s" % times)
            kinds = {}  # viewer name -> the AttributeType its row needs
            for line in T.h5compare.text(f.attrs["field_table"]).strip("\n").split("\n")[1:]:
                r = dict(zip(T.h5compare.text(f.attrs["field_table"]).split("\n")[0].split("\t"), line.split("\t")))
                cols = int(r["components"])
                kinds[r["xdmf"]] = "Scalar" if cols == 1 else "Vector" if cols == 3 and r["vector_field_type"] == "vector" \
                    else "Tensor6" if cols == 6 and r["vector_field_type"] == "tensor" else "Matrix"
            attrs_ok = True
            for g, k, t in zip(grids, h5steps, times):
                at = f["steps/%06d" % k].attrs
                st, lf, ht = int(at["stage"]), float(at["load_factor"]), float(at["time"])
                attrs_ok &= abs(ht - t) < 1e-9 and int(at["step"]) == k and st == min(math.floor(ht), 2) \
                    and abs(lf - (ht - st)) < 1e-12
                topo = g.find("Topology")
                attrs_ok &= topo.get("TopologyType") == "Triangle" and int(topo.get("NumberOfElements")) == E
                for a in g.findall("Attribute"):
                    d = a.find("DataItem")
                    dims = [int(x) for x in d.get("Dimensions").split()]
                    attrs_ok &= dims[0] == (E if a.get("Center") == "Cell" else N)
                    attrs_ok &= a.get("AttributeType") == kinds.get(a.get("Name"))
                    attrs_ok &= len(dims) <= 2
            chk.check(attrs_ok, "grid times equal the step attributes (step, stage, load_factor) and "
                      "attribute sizes and types (Scalar, Vector, Tensor6, Matrix) match their rows")
            fields = {a.get("Name") for g in grids for a in g.findall("Attribute")}
            named = {"displacement", "PK2_Sxx_Syy_Sxy", "GL_Exx_Eyy_Exy", "plastic_Exx_Eyy_Exy", "principal_stress_1_2",
                     "plastic_strain_eq", "mises_PK2", "min_principal_stress_PK2"}
            chk.check(named <= fields, "XDMF attributes are named by stress measure and components: %s" % sorted(fields))
            chk.check(not fields & {"stress", "strain", "plastic_strain"},
                      "no tensor components under a name without their measure and order in the XDMF")
            slabs = [it for it in root.iter("DataItem") if it.get("ItemType") == "HyperSlab"]
            chk.check(not slabs, "no HyperSlab DataItem (ParaView's XDMF3 readers skip them): %d" % len(slabs))
            chk.check("etfe" in T.h5compare.text(f.attrs["version"]) and "-patch_schedule 1,0.5,1.5" in
                      T.h5compare.text(f.attrs["options"]), "the results file records the version and the options")
            eq = f["steps/%06d/plastic_strain_eq" % h5steps[-1]][()]
            chk.check(eq.shape == (E,) and bool((eq > 0).all()),
                      "plastic_strain_eq > 0 in every element at the end (min %.4e, max %.4e)" % (eq.min(), eq.max()))
            eq0 = f["steps/000000/plastic_strain_eq"][()]
            chk.check(bool((eq0 == 0).all()), "plastic_strain_eq = 0 in the initial state")
        paraview(chk, xmf, len(h5steps))
        contact_grid(etfe, chk, tmp)


def contact_grid(etfe, chk, tmp):
    """A contact scene: each step is a spatial collection of the film and the contact pairs, the
    latter a point set (one vertex per pair at its film node) with force, status and slides."""
    import h5py
    h5 = os.path.join(tmp, "capstan.h5")
    T.run(etfe, ["-options_file", T.opts("capstan"), "-load_monitor", 0, "-output_every", 20, "-output_file", h5])
    root = ET.parse(os.path.splitext(h5)[0] + ".xmf").getroot()
    steps = root.find("Domain/Grid").findall("Grid")
    with h5py.File(h5, "r") as f:
        C = f["steps/%06d/contact/force" % 20].shape[0]
    ok = bool(steps)
    for g in steps:
        sub = {x.get("Name"): x for x in g.findall("Grid")}
        ok &= g.get("CollectionType") == "Spatial" and set(sub) == {"film", "contact"} and g.find("Time") is not None
        if ok:
            topo = sub["contact"].find("Topology")
            names = {a.get("Name") for a in sub["contact"].findall("Attribute")}
            ok &= topo.get("TopologyType") == "Polyvertex" and int(topo.get("NumberOfElements")) == C
            ok &= {"contact_force", "contact_status", "slide_X_Y", "slide_x0_y0", "displacement"} <= names
    chk.check(ok, "capstan: every step holds the film and the %d contact pairs as a point set with force, "
              "status and slides" % C)
    pv = shutil.which("pvpython")
    if not pv:
        print("  SKIP  ParaView check of the contact point set: pvpython not found on PATH")
        return
    script = ("from paraview.simple import *\n"
              "r = XDMFReader(FileNames=[%r])\n"
              "r.UpdatePipelineInformation()\n"
              "r.UpdatePipeline(list(r.TimestepValues)[-1])\n"
              "d = servermanager.Fetch(r)\n"
              "c = d.GetBlock(1)\n"
              "print('PV', d.GetNumberOfBlocks(), c.GetNumberOfCells(), c.GetCellData().HasArray('contact_force'))\n"
              % (os.path.splitext(h5)[0] + ".xmf"))
    p = subprocess.run([pv, "-c", script], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=300)
    line = [l for l in p.stdout.decode("utf-8", "replace").splitlines() if l.startswith("PV ")]
    ok = p.returncode == 0 and line and line[0].split()[1:] in (["2", str(C), "1"], ["2", str(C), "True"])
    chk.check(bool(ok), "ParaView reads the film and the %d contact pairs as two blocks: %s" % (C, line[:1]))


def paraview(chk, xmf, nsteps):
    pv = shutil.which("pvpython")
    if not pv:
        print("  SKIP  ParaView check: pvpython not found on PATH")
        return
    script = (
        "from paraview.simple import *\n"
        "r = XDMFReader(FileNames=[%r])\n"
        "r.UpdatePipelineInformation()\n"
        "ts = list(r.TimestepValues)\n"
        "r.UpdatePipeline(ts[-1])\n"
        "d = servermanager.Fetch(r)\n"
        "b = d.GetBlock(0) if d.IsA('vtkMultiBlockDataSet') else d\n"
        "cd = b.GetCellData()\n"
        "print('PV', len(ts), b.GetNumberOfCells(), cd.HasArray('plastic_strain_eq') and cd.HasArray('PK2_Sxx_Syy_Sxy'))\n"
        % xmf)
    p = subprocess.run([pv, "-c", script], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=300)
    out = p.stdout.decode("utf-8", "replace")
    line = [l for l in out.splitlines() if l.startswith("PV ")]
    ok = p.returncode == 0 and line and int(line[0].split()[1]) == nsteps and line[0].split()[3] in ("1", "True")
    chk.check(bool(ok), "ParaView reads %d time steps with plastic_strain_eq and PK2_Sxx_Syy_Sxy: %s" % (nsteps, line[0] if line else T.tail(out, 5)))


if __name__ == "__main__":
    T.main(main_test)
