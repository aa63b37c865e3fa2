#!/usr/bin/python3
"""What the docs and the shipped options files cite exists: every tests/regression/<name>.py,
options/<...>.opts and docs/<name>.md named in docs/*.md, README.md or options/**/*.opts is a file
of the repository (a renamed test left options/structure/general_dd1511.opts citing
test_structure_saddle.py)."""
import glob
import os
import re
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the repository
import etfe_testlib as T  # noqa: E402

CITED = re.compile(r"\b((?:tests/regression/[a-z0-9_]+\.py)|(?:options/[a-z0-9_/]+\.opts)|(?:docs/[a-z0-9_-]+\.md))")


def main_test(etfe, chk):
    files = sorted(glob.glob(os.path.join(T.REPO, "docs", "*.md")) + [os.path.join(T.REPO, "README.md")] +
                   glob.glob(os.path.join(T.REPO, "options", "**", "*.opts"), recursive=True))
    missing, cited = [], 0
    for f in files:
        with open(f, encoding="utf-8", errors="replace") as fd:
            text = fd.read()
        for path in sorted(set(CITED.findall(text))):
            cited += 1
            if not os.path.exists(os.path.join(T.REPO, path)):
                missing.append("%s cites %s" % (os.path.relpath(f, T.REPO), path))
    chk.check(cited > 0 and not missing, "%d citations of tests, options files and docs in %d files, all exist%s" % (
        cited, len(files), "" if not missing else ": " + "; ".join(missing[:8])))


if __name__ == "__main__":
    T.main(main_test)
