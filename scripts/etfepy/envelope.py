"""Envelopes over the combinations' results and the design checks (docs/design-run.md).

Each combination's quantities are the element-wise (node-wise, segment-wise) extremes over every
step its results file holds: a branch writes only the steps of the combination's own stage (after
the base), every -output_every-th increment and the stage end, so the extremes cover the ramp as
written, not the increments between written steps. Reactions per support group and chamber
pressures come from the history CSV, one row per increment, so theirs cover every increment. A
combination that did not complete has no state and makes the envelopes incomplete. Envelope
fields are element-wise (cells) or node-wise extremes over the completed combinations, each with
the index of the governing combination (the first in the design's order on a tie).
"""
import csv
import math
import os

import numpy as np

from .design import DEFAULT_CABLE_FACTOR
from .results import h5py, text

# name: (where, how, unit, description); how: max or min over the combinations.
ENVELOPES = {
    "max_principal_stress": ("cell", "max", "MPa", "largest principal Cauchy stress"),
    "lowest_major_stress": ("cell", "min", "MPa", "smallest major principal Cauchy stress (the prestress left)"),
    "cauchy_mises": ("cell", "max", "MPa", "von Mises of the Cauchy stress"),
    "max_principal_strain": ("cell", "max", "1", "largest principal Green-Lagrange strain"),
    "plastic_strain_eq": ("cell", "max", "1", "equivalent plastic strain"),
    "wrinkle_state": ("cell", "max", "1", "0 taut, 1 wrinkled, 2 slack"),
    "utilisation": ("cell", "max", "1", "design stress / design resistance"),
    "displacement_magnitude": ("node", "max", "mm", "|u| from the mesh"),
    "deflection": ("node", "max", "mm", "|u - u_base|: the motion from the base state"),
}


def combination_steps(path):
    """[{field: array}] of every step of a results file (cable datasets under "cables/...") and its
    status, or (None, status)."""
    with h5py().File(path, "r") as f:
        status = text(f.attrs.get("status", b""))
        steps = sorted(f["steps"].keys()) if "steps" in f else []
        if not status.startswith("complete") or not steps:
            return None, status
        out = []
        for s in steps:
            g = f["steps"][s]
            st = {k: g[k][()] for k in g.keys() if not isinstance(g[k], h5py().Group)}
            if "cables" in g:
                for k in g["cables"].keys():
                    st["cables/" + k] = g["cables"][k][()]
            st["_time"] = float(g.attrs["time"])
            out.append(st)
        return out, status


def combination_state(path):
    """{field: array} of a results file's last step and its status, or (None, status)."""
    with h5py().File(path, "r") as f:
        status = text(f.attrs.get("status", b""))
        steps = sorted(f["steps"].keys()) if "steps" in f else []
        if not status.startswith("complete") or not steps:
            return None, status
        g = f["steps"][steps[-1]]
        st = {k: g[k][()] for k in g.keys() if not isinstance(g[k], h5py().Group)}
        st["_time"] = float(g.attrs["time"])
        return st, status


def mesh(path):
    with h5py().File(path, "r") as f:
        return f["mesh/coordinates"][()], f["mesh/triangles"][()]


def history_rows(stem, base_stages):
    """The history CSV's rows of the combination's own stage (load time above the base's stages), one
    per increment, as [{column: float}], or []. Reactions and chamber pressures are enveloped over these,
    not over the written steps only."""
    path = stem + "_history.csv"
    if not os.path.exists(path):
        return []
    with open(path) as f:
        rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
    return [r for r in rows if r["time"] > base_stages + 1e-12]


GROUP_SUFFIXES = ("_RX", "_RY", "_RZ", "_p_kPa")


def history_extremes(rows):
    """{column: (max, its increment, min, its increment)} of the reaction and chamber-pressure columns
    over a combination's increments (rows: history_rows)."""
    res = {}
    for col in (rows[0] if rows else {}):
        if not col.endswith(GROUP_SUFFIXES):
            continue
        vals = [r[col] for r in rows]
        hi, lo = int(np.argmax(vals)), int(np.argmin(vals))
        inc = [int(r.get("step", k)) for k, r in enumerate(rows)]
        res[col] = (vals[hi], inc[hi], vals[lo], inc[lo])
    return res


def quantities(state, base_u, design, fd):
    """The per-element and per-node quantities the envelopes and checks take; fd: the design strength
    per element (its group's material at the combination's duration and temperature) or None (no
    duration class: no utilisation, NaN)."""
    q = {}
    ps = state["principal_stress"]
    q["max_principal_stress"] = ps[:, 0]
    q["lowest_major_stress"] = ps[:, 0]
    q["cauchy_mises"] = state["cauchy_mises"]
    e = state["strain"]
    q["max_principal_strain"] = 0.5 * (e[:, 0] + e[:, 1]) + np.sqrt(0.25 * (e[:, 0] - e[:, 1]) ** 2 + e[:, 2] ** 2)
    n_el = ps.shape[0]
    q["plastic_strain_eq"] = state.get("plastic_strain_eq", np.zeros(n_el))
    q["wrinkle_state"] = state.get("wrinkle_state", np.zeros(n_el))
    measure = design.resistance.stress
    sigma = q["max_principal_stress"] if measure == "max_principal_stress" else q["cauchy_mises"]
    q["utilisation"] = sigma / fd if fd is not None else np.full(n_el, np.nan)
    u = state["displacement"]
    q["displacement_magnitude"] = np.linalg.norm(u, axis=1)
    q["deflection"] = np.linalg.norm(u - base_u, axis=1)
    q["area_ratio"] = state["area_ratio"]
    return q


def over_steps(states, base_u, design, fd):
    """The quantities of every step, each element's (node's) extreme over the steps (max or min as its
    envelope); the wrinkled area is the largest over the steps; cable segment forces their largest."""
    qs = [quantities(st, base_u, design, fd) for st in states]
    q = {}
    for name, (_, how, _, _) in ENVELOPES.items():
        stack = np.stack([x[name] for x in qs])
        q[name] = stack.max(axis=0) if how == "max" else stack.min(axis=0)
    q["area_ratio"] = qs[-1]["area_ratio"]
    q["steps"] = len(qs)
    q["wrinkled_area_steps"] = [(x["wrinkle_state"] >= 1, x["area_ratio"]) for x in qs]
    if "cables/force" in states[-1]:
        q["cable_force"] = np.stack([st["cables/force"] for st in states]).max(axis=0)
        q["cable_index"] = states[-1]["cables/cable"].astype(int)
    return q


def cable_maxima(q, cable_names):
    """{cable name: (largest segment force N, segment index within the cable)} of a combination."""
    res = {}
    if q is None or "cable_force" not in q:
        return res
    for k in np.unique(q["cable_index"]):
        seg = np.nonzero(q["cable_index"] == k)[0]
        i = int(np.argmax(q["cable_force"][seg]))
        name = cable_names[k] if k < len(cable_names) else "cable %d" % k
        res[name] = (float(q["cable_force"][seg][i]), i)
    return res


def cable_envelopes(names, per_comb, cable_names):
    """Per cable: the largest segment force over the completed combinations (every written step) and
    the combination and segment giving it. [dict(cable, max_force, combination, segment)]."""
    best = {}
    for k, q in enumerate(per_comb):
        for cab, (f, seg) in cable_maxima(q, cable_names).items():
            if cab not in best or f > best[cab]["max_force"]:
                best[cab] = dict(cable=cab, max_force=f, combination=names[k], segment=seg)
    return list(best.values())


def envelopes(per_comb):
    """per_comb: [quantities or None] in the design's order. {name: (values, governing index)}."""
    done = [k for k, q in enumerate(per_comb) if q is not None]
    res = {}
    if not done:
        return res
    for name, (_, how, _, _) in ENVELOPES.items():
        stack = np.stack([per_comb[k][name] for k in done])
        # NaN (a utilisation without a duration class) takes no part
        filled = np.where(np.isnan(stack), -np.inf if how == "max" else np.inf, stack)
        idx = np.argmax(filled, axis=0) if how == "max" else np.argmin(filled, axis=0)
        vals = np.take_along_axis(stack, idx[None, :], axis=0)[0]
        res[name] = (vals, np.array(done)[idx])
    return res


def group_envelopes(names, extremes):
    """Reactions per support group (<group>_RX/RY/RZ, N) and chamber pressures (<c>_p_kPa) over every
    increment of each completed combination (extremes: [history_extremes]): per column the largest and
    smallest value and the combination and increment giving each. [dict(quantity, unit, max,
    max_combination, max_increment, min, min_combination, min_increment)]."""
    cols = []
    for h in extremes:
        for k in h:
            if k not in cols:
                cols.append(k)
    rows = []
    for col in cols:
        vals = [(h[col], names[k]) for k, h in enumerate(extremes) if col in h]
        if not vals:
            continue
        hi = max(vals, key=lambda v: v[0][0])
        lo = min(vals, key=lambda v: v[0][2])
        rows.append(dict(quantity=col, unit="kPa" if col.endswith("_p_kPa") else "N", max=hi[0][0],
                         max_combination=hi[1], max_increment=hi[0][1], min=lo[0][2], min_combination=lo[1],
                         min_increment=lo[0][3]))
    return rows


def triangle_areas(X, tri):
    a, b, c = X[tri[:, 0]], X[tri[:, 1]], X[tri[:, 2]]
    return 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)


def write_envelopes(path, X, tri, env, names, missing, groups=(), cables=()):
    """Envelope HDF5 (mesh + fields + governing combination index) and its XDMF beside it."""
    with h5py().File(path, "w") as f:
        f.attrs["format"] = "etfe-envelope-1"
        f.attrs["combinations"] = "\n".join(names)
        f.attrs["complete"] = 0 if missing else 1
        f.attrs["missing"] = "\n".join(missing)
        f["mesh/coordinates"] = X
        f["mesh/triangles"] = tri.astype(np.int32)
        for name, (vals, idx) in env.items():
            where, how, unit, desc = ENVELOPES[name]
            d = f.create_dataset("envelope/" + name, data=vals)
            d.attrs.update(units=unit, description="%s of %s over the combinations" % (how, desc))
            d = f.create_dataset("envelope/" + name + "_governing", data=idx.astype(np.int32))
            d.attrs.update(units="1", description="index of the governing combination (root attribute combinations)")
        for g in groups:  # per support group and chamber: [max, min] and their combinations
            d = f.create_dataset("groups/" + g["quantity"], data=np.array([g["max"], g["min"]]))
            d.attrs.update(units=g["unit"], description="largest and smallest over every increment of the combinations",
                           governing="%s\n%s" % (g["max_combination"], g["min_combination"]),
                           increment=np.array([g["max_increment"], g["min_increment"]], dtype=np.int64))
        for c in cables:  # per cable: its largest segment force over the combinations' steps
            d = f.create_dataset("cables/" + c["cable"] + "_force_max", data=np.array([c["max_force"]]))
            d.attrs.update(units="N", description="largest segment force over the combinations (every written step)",
                           governing=c["combination"], segment=int(c["segment"]))
    h5 = os.path.basename(path)
    nn, ne = X.shape[0], tri.shape[0]
    attrs = []
    for name in env:
        where = ENVELOPES[name][0]
        n, centre = (ne, "Cell") if where == "cell" else (nn, "Node")
        for ds in (name, name + "_governing"):
            attrs.append('<Attribute Name="%s" AttributeType="Scalar" Center="%s"><DataItem Dimensions="%d" '
                         'NumberType="%s" Precision="%d" Format="HDF">%s:/envelope/%s</DataItem></Attribute>'
                         % (ds, centre, n, "Int" if ds.endswith("governing") else "Float",
                            4 if ds.endswith("governing") else 8, h5, ds))
    xmf = ('<?xml version="1.0" ?>\n<Xdmf Version="3.0"><Domain><Grid Name="envelope" GridType="Uniform">'
           '<Topology TopologyType="Triangle" NumberOfElements="%d"><DataItem Dimensions="%d 3" NumberType="Int" '
           'Precision="4" Format="HDF">%s:/mesh/triangles</DataItem></Topology><Geometry GeometryType="XYZ">'
           '<DataItem Dimensions="%d 3" NumberType="Float" Precision="8" Format="HDF">%s:/mesh/coordinates</DataItem>'
           '</Geometry>\n%s\n</Grid></Domain></Xdmf>\n' % (ne, ne, h5, nn, h5, "\n".join(attrs)))
    with open(os.path.splitext(path)[0] + ".xmf", "w") as f:
        f.write(xmf)


def place_of_cell(X, tri, e):
    c = X[tri[e]].mean(axis=0)
    return "element %d at (%.0f, %.0f, %.0f) mm" % (e, c[0], c[1], c[2])


def place_of_node(X, n):
    return "node %d at (%.0f, %.0f, %.0f) mm" % (n, X[n, 0], X[n, 1], X[n, 2])


# kind: (quantity, max or min, unit, what); chamber_pressure and wrinkled_area are computed apart.
CHECKS = {
    "utilisation": ("utilisation", "max", "1", "design stress / design resistance"),
    "plastic_strain": ("plastic_strain_eq", "max", "1", "equivalent plastic strain"),
    "principal_strain": ("max_principal_strain", "max", "1", "largest principal strain"),
    "deflection": ("deflection", "max", "mm", "deflection from the base state"),
    "min_prestress": ("lowest_major_stress", "min", "MPa", "smallest major principal stress"),
}


def run_checks(design, combs, per_comb, extras, X, tri, cable_names=()):
    """One row per check and combination it applies to: dict(check, combination, situation, value,
    limit, unit, verdict, place). A combination that did not complete fails every check it has."""
    rows = []
    areas = triangle_areas(X, tri)
    for chk in design.checks:
        kind, name = chk["kind"], chk.get("name", chk["kind"])
        situations = chk.get("situations", ["ULS", "SLS"])
        for k, comb in enumerate(combs):
            if comb["situation"] not in situations:
                continue
            row = dict(check=name, kind=kind, combination=comb["name"], situation=comb["situation"])
            q = per_comb[k]
            if q is None:
                row.update(value=float("nan"), limit=chk.get("limit", float("nan")), unit="",
                           verdict="not converged", place="the combination did not complete")
                rows.append(row)
                continue
            if kind in CHECKS:
                qty, how, unit, _ = CHECKS[kind]
                v = q[qty]
                i = int(np.argmax(v) if how == "max" else np.argmin(v))
                value, limit = float(v[i]), float(chk["limit"] if kind != "utilisation" else chk.get("limit", 1.0))
                ok = value <= limit if how == "max" else value >= limit
                place = place_of_node(X, i) if qty in ("deflection",) else place_of_cell(X, tri, i)
                row.update(value=value, limit=limit, unit=unit, verdict="pass" if ok else "FAIL", place=place)
            elif kind == "wrinkled_area":
                # the largest over the written steps of the combination's stage
                value, wr = max(((float(np.sum(areas[w] * ar[w])) * 1e-6, w) for w, ar in q["wrinkled_area_steps"]),
                                key=lambda t: t[0])
                limit = float(chk["limit"])
                row.update(value=value, limit=limit, unit="m^2", verdict="pass" if value <= limit else "FAIL",
                           place="%d of %d elements wrinkled or slack" % (int(np.sum(wr)), len(wr)))
            elif kind == "cable_force":
                factor = float(chk.get("factor", DEFAULT_CABLE_FACTOR))
                got = cable_maxima(q, cable_names)
                for cab, breaking in chk["breaking_load"].items():
                    r = dict(row)
                    limit = float(breaking) / factor
                    if cab not in got:
                        r.update(value=float("nan"), limit=limit, unit="N", verdict="FAIL",
                                 place="cable %s: no such cable in the results (cables: %s)" % (cab, ", ".join(got)))
                    else:
                        value, seg = got[cab]
                        r.update(value=value, limit=limit, unit="N", verdict="pass" if value <= limit else "FAIL",
                                 place="cable %s segment %d (breaking load %g N / %g)" % (cab, seg, breaking, factor))
                    rows.append(r)
                continue
            elif kind == "chamber_pressure":
                # every increment of the combination: the one furthest outside (or least inside) the range
                col = chk["chamber"] + "_p_kPa"
                lo, hi = chk["range"]
                ext = extras[k].get(col)
                if ext is None:
                    value, inc = float("nan"), None
                else:
                    value, inc = (ext[0], ext[1]) if ext[0] - hi >= lo - ext[2] else (ext[2], ext[3])
                ok = inc is not None and lo <= ext[2] and ext[0] <= hi
                row.update(value=value, limit="%g to %g" % (lo, hi), unit="kPa", verdict="pass" if ok else "FAIL",
                           place="chamber %s, increment %s (range over its increments %s to %s kPa)"
                           % (chk["chamber"], inc, *(("%.4g" % ext[2], "%.4g" % ext[0]) if ext else ("-", "-"))))
            else:
                raise ValueError("check %s: unknown kind %s (utilisation, plastic_strain, principal_strain, "
                                 "deflection, min_prestress, wrinkled_area, chamber_pressure, cable_force)"
                                 % (name, kind))
            rows.append(row)
    return rows


def finite(x):
    return isinstance(x, (int, float)) and math.isfinite(x)
