#!/usr/bin/python3
"""What the docs and the shipped options files cite exists: every tests/regression/<name>.py,
options/<...>.opts and docs/<name>.md named in docs/*.md, README.md or options/**/*.opts is a file
of the repository (a renamed test left options/structure/general_dd1511.opts citing
test_structure_saddle.py). And they point nowhere outside the repository, which a user's clone does
not have: no relative path that leaves it (../shared/SPEC.md from README.md), no absolute path
under /work/, no "SPEC §n" (the development team's specification; docs/theory.md is the user's)."""
import glob
import os
import re
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the repository
import etfe_testlib as T  # noqa: E402

CITED = re.compile(r"\b((?:tests/regression/[a-z0-9_]+\.py)|(?:options/[a-z0-9_/]+\.opts)|(?:docs/[a-z0-9_-]+\.md))")
RELATIVE = re.compile(r"(?<![\w.])((?:\.\./)+[\w./-]+)")
OUTSIDE = re.compile(r"(/work/[\w./-]*|\bSPEC(?:\.md|\s*§))")


def outside_pointers(path, text):
    """The pointers of the file at path that lead outside the repository (or to nothing in it)."""
    found = [m.group(1) for m in OUTSIDE.finditer(text)]
    for rel in RELATIVE.findall(text):
        target = os.path.realpath(os.path.join(os.path.dirname(path), rel))
        if os.path.relpath(target, os.path.realpath(T.REPO)).startswith("..") or not os.path.exists(target):
            found.append(rel)
    return found


def main_test(etfe, chk):
    files = sorted(glob.glob(os.path.join(T.REPO, "docs", "*.md")) + [os.path.join(T.REPO, "README.md")] +
                   glob.glob(os.path.join(T.REPO, "options", "**", "*.opts"), recursive=True))
    missing, cited, outside = [], 0, []
    for f in files:
        with open(f, encoding="utf-8", errors="replace") as fd:
            text = fd.read()
        outside += ["%s: %s" % (os.path.relpath(f, T.REPO), p) for p in sorted(set(outside_pointers(f, text)))]
        for path in sorted(set(CITED.findall(text))):
            cited += 1
            if not os.path.exists(os.path.join(T.REPO, path)):
                missing.append("%s cites %s" % (os.path.relpath(f, T.REPO), path))
    chk.check(cited > 0 and not missing, "%d citations of tests, options files and docs in %d files, all exist%s" % (
        cited, len(files), "" if not missing else ": " + "; ".join(missing[:8])))
    chk.check(not outside, "no pointer outside the repository in %d files%s" % (
        len(files), "" if not outside else ": " + "; ".join(outside[:8])))


if __name__ == "__main__":
    T.main(main_test)
