#!/usr/bin/python3
"""The results file describes itself, and everything that names its fields follows one table
(include/etfe/io/output_fields.h, written into each file as the root attribute field_table).
For a plastic patch, a capstan (contact) and an annulus (wrinkling), each a few increments:
  * every dataset of the file is a row of the field table, with that row's attributes
    (vector_field_type, units, family, description), columns, number type and row count;
  * every row the run's options call for is written in every step (and none other);
  * the XDMF index points at every dataset of every step and shows each row under its viewer
    name(s) from the table;
  * docs/results.md holds the field table as generated from the file's field_table (on a
    mismatch the expected table is printed, ready to paste).
"""
import os
import sys
import xml.etree.ElementTree as ET

sys.dont_write_bytecode = True  # no __pycache__ in the repository
import etfe_testlib as T  # noqa: E402

DOC = os.path.join(T.REPO, "docs", "results.md")
ATTRS = ("vector_field_type", "units", "family", "description")
ROWS = {"node": "N", "cell": "E", "contact pair": "C"}
CASES = {  # name: (options, which conditional rows it writes)
    "patch": (["-options_file", T.opts("patch"), "-material_type", "plastic", "-patch_strain_x", "0.05",
               "-load_increments", 3], {"plastic material"}),
    "capstan": (["-options_file", T.opts("capstan"), "-load_monitor", 0, "-output_every", 40], {"contact"}),
    "annulus": (["-options_file", T.opts("annulus"), "-load_increments", 2],
                {"wrinkling"}),
}


def field_table(f):
    """The root attribute field_table as a list of dicts (its first line names the columns)."""
    lines = T.h5compare.text(f.attrs["field_table"]).strip("\n").split("\n")
    keys = lines[0].split("\t")
    return [dict(zip(keys, line.split("\t"))) for line in lines[1:]]


def markdown(table):
    """The field table as docs/results.md shows it."""
    out = ["| dataset | rows | columns | type | vector_field_type | units | family | written | in ParaView | "
           "description |", "|---|---|---|---|---|---|---|---|---|---|"]
    for r in table:
        # no viewer name: the grid's geometry or topology, or a term's item (a chamber: no mesh entity)
        viewer = ", ".join("`%s`" % w for w in r["xdmf"].split()) or ("(none)" if r["location"] == "item" else "(grid)")
        out.append("| `%s` | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            r["name"], r["location"], r["components"], r["number_type"], r["vector_field_type"], r["units"],
            r["family"], r["written"], viewer, r["description"]))
    return out


def check_datasets(chk, case, f, table, wanted):
    import h5py
    rows = {r["name"]: r for r in table}
    n = {"N": f["mesh/coordinates"].shape[0], "E": f["mesh/triangles"].shape[0]}
    bad = []
    expected_step = {r["name"] for r in table if r["written"] == "every step" or r["written"] in wanted}
    for k in T.h5compare.written_steps(f):
        names = set(T.h5compare.datasets(f["steps/%06d" % k]))
        if names != expected_step:
            bad.append("step %d: missing %s, not in the table or not called for %s" % (
                k, sorted(expected_step - names), sorted(names - expected_step)))
    found = []
    f.visititems(lambda name, obj: found.append((name, obj)) if isinstance(obj, h5py.Dataset) else None)
    for path, d in found:
        name = path if path.startswith("mesh/") else path.split("/", 2)[2]
        r = rows.get(name)
        if r is None:
            bad.append("%s is not a row of the field table" % path)
            continue
        for a in ATTRS:
            if a not in d.attrs or (a != "description" and T.h5compare.text(d.attrs[a]) != r[a]):
                bad.append("%s: attribute %s %r, the table says %r" % (
                    path, a, T.h5compare.text(d.attrs[a]) if a in d.attrs else None, r[a]))
        if not T.h5compare.text(d.attrs.get("description", b"")):
            bad.append("%s: empty description" % path)
        cols = int(r["components"])
        if r["location"] == "contact pair":
            n["C"] = d.shape[0]
        shape = (n[ROWS[r["location"]]],) + ((cols,) if cols > 1 else ())
        if d.shape != shape or str(d.dtype) != r["number_type"]:
            bad.append("%s: %s %s, the table says %s %s" % (path, d.shape, d.dtype, shape, r["number_type"]))
    chk.check(not bad, "%s: %d datasets, each a row of the field table with its attributes, shape and type%s" % (
        case, len(found), "" if not bad else ": " + "; ".join(bad[:5])))


def check_xdmf(chk, case, h5, f, table):
    root = ET.parse(os.path.splitext(h5)[0] + ".xmf").getroot()
    grids = root.find("Domain/Grid").findall("Grid")
    viewers = {r["name"]: r["xdmf"].split() for r in table}
    bad = []
    for g, k in zip(grids, T.h5compare.written_steps(f)):
        group = "steps/%06d" % k
        items = {it.text.strip().split(":", 1)[1].lstrip("/") for it in g.iter("DataItem") if it.get("Format") == "HDF"}
        shown = {a.get("Name") for a in g.iter("Attribute")}
        for name in sorted(T.h5compare.datasets(f[group])):
            if group + "/" + name not in items:
                bad.append("step %d: %s not in the XDMF" % (k, name))
            missing = [w for w in viewers[name] if w not in shown]
            if missing:
                bad.append("step %d: %s not shown as %s" % (k, name, missing))
        bad += ["step %d: %s not in the XDMF" % (k, m) for m in ("mesh/coordinates", "mesh/triangles") if m not in items]
    chk.check(len(grids) == len(T.h5compare.written_steps(f)) and not bad,
              "%s: the XDMF names every dataset of its %d steps under the table's viewer names%s" % (
                  case, len(grids), "" if not bad else ": " + "; ".join(bad[:5])))


def main_test(etfe, chk):
    import h5py
    tables = []
    with T.scratch_dir("fields") as tmp:
        for case, (args, wanted) in CASES.items():
            h5 = os.path.join(tmp, case + ".h5")
            T.run(etfe, args + ["-output_file", h5])
            with h5py.File(h5, "r") as f:
                table = field_table(f)
                tables.append(table)
                chk.check(T.h5compare.file_status(h5) == "complete" and len(table) > 20,
                          "%s: complete, root attribute field_table with %d rows" % (case, len(table)))
                check_datasets(chk, case, f, table, wanted)
                check_xdmf(chk, case, h5, f, table)
    chk.check(all(t == tables[0] for t in tables), "every scene writes the same field table")
    with open(DOC) as fd:
        doc = fd.read().splitlines()
    expected = markdown(tables[0])
    at = doc.index(expected[0]) if expected[0] in doc else -1
    ok = at >= 0 and doc[at:at + len(expected)] == expected and (at + len(expected) == len(doc) or
                                                                   not doc[at + len(expected)].startswith("|"))
    if not ok:
        print("docs/results.md should hold this field table (from the results file's field_table):\n")
        print("\n".join(expected) + "\n")
    chk.check(ok, "docs/results.md holds the field table as the results file writes it (%d rows)" % len(tables[0]))


if __name__ == "__main__":
    T.main(main_test)
