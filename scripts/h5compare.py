#!/usr/bin/python3
"""Compare two etfe results files (HDF5, layout in docs/results.md).

    h5compare.py A.h5 B.h5 [--step last|<k>|all] [--field name:rtol:atol ...]
                 [--default-rtol 1e-9] [--default-atol 1e-12] [--only] [--allow-incomplete]

B is the reference. A field passes when max|a - b| <= atol + rtol * max|b| (maxima over the whole
field of one step). Compared: /mesh/coordinates, /mesh/triangles and, for the selected steps,
every dataset of /steps/<k>/ plus the step attributes time, stage and load_factor. A field or step
present in only one file, a shape mismatch or a results file whose root attribute status is not
"complete" (unless --allow-incomplete) is a failure. Prints a table; exits 1 on any failure,
2 on a usage error.

--family-scale measures a field against the largest value of its family in the same step
(stresses against the stresses, strains against the strains): a field that is round-off in one
case, e.g. min_principal_stress of a uniaxial patch (~1e-12 MPa beside stresses of ~20 MPa), is
then not held to a tolerance relative to its own near-zero size. A dataset's family is its
attribute "family" (written from the field table, include/etfe/io/output_fields.h); files written
before datasets described themselves fall back to FAMILIES below. Fields of the family
principal_direction (defined up to sign) are not compared unless named with --only.

--step last compares the last written step of A with the last of B (their step numbers must
match); --step <k> compares step k of both; --step all compares every step (the sets of written
steps must match). --field sets the tolerances of one field (a dataset name such as displacement,
or mesh/coordinates); --only restricts the comparison to the fields named with --field.

Importable: compare(a, b, ...) returns the list of failures (strings; empty means equal within
tolerance); compare_rows(...) also returns the table rows.
"""
import argparse
import sys

import numpy as np

try:
    import h5py
except ImportError:  # pragma: no cover - reported clearly instead of a traceback
    sys.stderr.write("h5compare: needs h5py (Debian: apt-get install python3-h5py; run with /usr/bin/python3)\n")
    raise

from etfepy.results import text  # noqa: E402  (scripts/etfepy: an HDF5 string attribute as str)

STEP_ATTRS = ("time", "stage", "load_factor")


def file_status(path):
    """Status of a results file as a reader should believe it (etfepy.status: a "running" whose
    writer is gone says so; "" when missing)."""
    from etfepy import status
    st = status.seen(path)
    return "" if st.startswith("unknown: no status") else st


def written_steps(f):
    """Sorted step numbers present in an open results file."""
    if "steps" not in f:
        return []
    return sorted(int(k) for k in f["steps"].keys())


def _step_name(k):
    return "%06d" % k


def datasets(group, prefix=""):
    """{relative path: dataset} of every dataset below an HDF5 group (subgroups such as
    contact/ give names like "contact/force")."""
    res = {}
    for k, v in group.items():
        if isinstance(v, h5py.Group):
            res.update(datasets(v, prefix + k + "/"))
        else:
            res[prefix + k] = v
    return res


# Principal directions are defined up to sign, and not at all where the two principal stresses
# are equal (the centre of a Hencky membrane, equibiaxial patches): round-off turns them freely
# there. They are a function of cauchy_stress, which is compared, so they are not compared.
UNCOMPARED_FAMILY = "principal_direction"
DIRECTIONS = ("principal_dir1", "principal_dir2")

# Only for results files written before each dataset carried its "family" attribute (such as
# tests/regression/reference/patch_uniaxial.h5): the families of the field table that group more
# than one field. Newer files are read, not this.
FAMILIES = {
    "stress": ("stress", "mises", "min_principal_stress", "nodal_mises", "cauchy_stress",
               "cauchy_mises", "principal_stress"),
    "strain": ("strain", "min_principal_strain", "plastic_strain", "plastic_strain_eq",
               "wrinkle_strain"),
    UNCOMPARED_FAMILY: DIRECTIONS,
}


def family_of(name, *dsets):
    """Family of the dataset `name`: the "family" attribute of the first of dsets that has one,
    else (an older file) FAMILIES; None when it shares its scale with no other field."""
    for d in dsets:
        if d is not None and "family" in d.attrs:
            return text(d.attrs["family"])
    for fam, members in FAMILIES.items():
        if name.split("/")[-1] in members:
            return fam
    return None


def _parse_field_spec(spec):
    parts = spec.split(":")
    if len(parts) != 3:
        raise ValueError("--field %r: expected name:rtol:atol" % spec)
    name, rtol, atol = parts
    return name, (float(rtol), float(atol))


def _diff(a, b):
    """(max abs difference, max |b|) of two equally shaped arrays; NaN anywhere counts as inf."""
    a = np.asarray(a, dtype=np.float64)
    b = np.asarray(b, dtype=np.float64)
    if a.size == 0:
        return 0.0, 0.0
    d = np.abs(a - b)
    same_nan = np.isnan(a) & np.isnan(b)
    d[same_nan] = 0.0
    if np.isnan(d).any():
        return float("inf"), float(np.nanmax(np.abs(b))) if np.isfinite(b).any() else 0.0
    return float(d.max()), float(np.abs(b).max())


def compare_rows(a_path, b_path, step="last", fields=None, default_rtol=1e-9, default_atol=1e-12,
                 only=False, allow_incomplete=False, family_scale=False):
    """Compare results file a_path against the reference b_path.

    step: "last", "all" or an int. fields: {name: (rtol, atol)} overriding the defaults (name is a
    dataset name such as "displacement" or "mesh/coordinates"). only: compare just those fields.
    family_scale: a field's rtol applies to the largest |b| of its family in that step (see
    family_of) instead of its own largest |b|.
    Returns (failures, rows); rows are dicts with keys field, step, shape, max_abs, max_rel, tol, ok.
    """
    fields = dict(fields or {})
    failures, rows = [], []

    def tol_of(name):
        return fields.get(name, (default_rtol, default_atol))

    def wanted(name):
        return (not only) or name in fields

    def check(label, stepname, name, da, db, scale=None):
        if da.shape != db.shape:
            failures.append("%s%s: shape %s in %s but %s in %s" % (
                name, " (step %s)" % stepname if stepname else "", da.shape, a_path, db.shape, b_path))
            rows.append(dict(field=name, step=stepname, shape="%s/%s" % (da.shape, db.shape),
                             max_abs=float("nan"), max_rel=float("nan"), tol=float("nan"), ok=False))
            return
        rtol, atol = tol_of(name)
        max_abs, max_b = _diff(da, db)
        if scale is not None:
            max_b = max(max_b, scale)
        tol = atol + rtol * max_b
        max_rel = max_abs / max_b if max_b > 0 else (0.0 if max_abs == 0 else float("inf"))
        ok = max_abs <= tol
        rows.append(dict(field=name, step=stepname, shape=str(da.shape), max_abs=max_abs,
                         max_rel=max_rel, tol=tol, ok=ok))
        if not ok:
            failures.append("%s%s: max |a-b| = %.3e exceeds atol + rtol*max|b| = %.3e "
                            "(rtol %.1e, atol %.1e, max|b| %.3e, relative %.3e)" % (
                                label, " (step %s)" % stepname if stepname else "", max_abs, tol,
                                rtol, atol, max_b, max_rel))

    with h5py.File(a_path, "r") as fa, h5py.File(b_path, "r") as fb:
        if not allow_incomplete:
            for path, f in ((a_path, fa), (b_path, fb)):
                st = text(f.attrs.get("status", b"<missing>"))
                if st != "complete":
                    failures.append("%s: status is %r, not 'complete'" % (path, file_status(path)))
        for name in ("mesh/coordinates", "mesh/triangles"):
            if not wanted(name):
                continue
            if name not in fa or name not in fb:
                failures.append("%s missing in %s" % (name, a_path if name not in fa else b_path))
                continue
            check(name, "", name, fa[name][()], fb[name][()])

        sa, sb = written_steps(fa), written_steps(fb)
        pairs = []
        if step == "last":
            if not sa or not sb:
                failures.append("no steps written in %s" % (a_path if not sa else b_path))
            else:
                if sa[-1] != sb[-1]:
                    failures.append("last step differs: %d in %s, %d in %s" % (sa[-1], a_path, sb[-1], b_path))
                pairs.append((sa[-1], sb[-1]))
        elif step == "all":
            if sa != sb:
                only_a = sorted(set(sa) - set(sb))
                only_b = sorted(set(sb) - set(sa))
                failures.append("written steps differ: only in %s: %s; only in %s: %s" % (
                    a_path, only_a, b_path, only_b))
            pairs = [(k, k) for k in sa if k in sb]
        else:
            k = int(step)
            for path, s in ((a_path, sa), (b_path, sb)):
                if k not in s:
                    failures.append("step %d missing in %s (written: %s)" % (k, path, s))
            if k in sa and k in sb:
                pairs.append((k, k))

        for ka, kb in pairs:
            ga, gb = fa["steps"][_step_name(ka)], fb["steps"][_step_name(kb)]
            da, db = datasets(ga), datasets(gb)
            stepname = _step_name(ka) if ka == kb else "%s/%s" % (_step_name(ka), _step_name(kb))
            names = sorted(set(da) | set(db))
            family = {n: family_of(n, db.get(n), da.get(n)) for n in names}
            fam_scale = {}
            if family_scale:
                for n in names:
                    fam = family[n]
                    if fam and n in db:
                        b = np.asarray(db[n][()], dtype=np.float64)
                        m = float(np.nanmax(np.abs(b))) if b.size and np.isfinite(b).any() else 0.0
                        fam_scale[fam] = max(fam_scale.get(fam, 0.0), m)
            if only:
                for n in fields:
                    if not n.startswith("mesh/") and n not in names:
                        failures.append("field %s missing in both files (step %s)" % (n, stepname))
            for n in names:
                if not wanted(n):
                    continue
                if n not in da or n not in db:
                    failures.append("field %s (step %s) missing in %s" % (
                        n, stepname, a_path if n not in da else b_path))
                    rows.append(dict(field=n, step=stepname, shape="missing", max_abs=float("nan"),
                                     max_rel=float("nan"), tol=float("nan"), ok=False))
                    continue
                if family[n] == UNCOMPARED_FAMILY and not only:
                    continue
                check(n, stepname, n, da[n][()], db[n][()], fam_scale.get(family[n]))
            if not only:
                for at in STEP_ATTRS:
                    if at in ga.attrs and at in gb.attrs:
                        va, vb = float(ga.attrs[at]), float(gb.attrs[at])
                        if abs(va - vb) > 1e-12 * max(1.0, abs(vb)):
                            failures.append("step %s attribute %s: %r vs %r" % (stepname, at, va, vb))
                    elif at in ga.attrs or at in gb.attrs:
                        failures.append("step %s attribute %s missing in one file" % (stepname, at))
    return failures, rows


def compare(a_path, b_path, step="last", fields=None, default_rtol=1e-9, default_atol=1e-12,
            only=False, allow_incomplete=False, family_scale=False):
    """List of failures (empty: the files agree within tolerance). See compare_rows."""
    return compare_rows(a_path, b_path, step, fields, default_rtol, default_atol, only,
                        allow_incomplete, family_scale)[0]


def format_table(rows):
    out = ["%-24s %-8s %-10s %12s %12s %12s  %s" % ("field", "step", "shape", "max|a-b|",
                                                    "relative", "tolerance", "ok")]
    for r in rows:
        out.append("%-24s %-8s %-10s %12.3e %12.3e %12.3e  %s" % (
            r["field"], r["step"] or "-", r["shape"], r["max_abs"], r["max_rel"], r["tol"],
            "ok" if r["ok"] else "FAIL"))
    return "\n".join(out)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("a", help="results file to check")
    ap.add_argument("b", help="reference results file")
    ap.add_argument("--step", default="last", help="last (default), all, or a step number")
    ap.add_argument("--field", action="append", default=[], metavar="NAME:RTOL:ATOL",
                    help="tolerances of one field (repeatable)")
    ap.add_argument("--default-rtol", type=float, default=1e-9)
    ap.add_argument("--default-atol", type=float, default=1e-12)
    ap.add_argument("--family-scale", action="store_true",
                    help="measure each field against the largest value of its family (stresses, strains)")
    ap.add_argument("--only", action="store_true", help="compare only the fields given with --field")
    ap.add_argument("--allow-incomplete", action="store_true",
                    help="accept files whose status is not 'complete'")
    args = ap.parse_args(argv)
    if args.step not in ("last", "all"):
        try:
            int(args.step)
        except ValueError:
            ap.error("--step must be last, all or an integer, not %r" % args.step)
    try:
        fields = dict(_parse_field_spec(s) for s in args.field)
    except ValueError as e:
        ap.error(str(e))
    for p in (args.a, args.b):
        try:
            h5py.File(p, "r").close()
        except OSError as e:
            print("h5compare: cannot open %s: %s" % (p, e))
            return 1
    failures, rows = compare_rows(args.a, args.b, args.step, fields, args.default_rtol,
                                  args.default_atol, args.only, args.allow_incomplete,
                                  args.family_scale)
    print(format_table(rows))
    if failures:
        print("\nh5compare: %d failure(s):" % len(failures))
        for f in failures:
            print("  " + f)
        return 1
    print("\nh5compare: %s matches %s (%d field comparisons)" % (args.a, args.b, len(rows)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
