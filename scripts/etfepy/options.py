"""PETSc options files as etfe reads them (src/app/options_files.cpp).

The rule: a comment starts at #, ! or %; tokens are separated by white space, a double-quoted
token keeps its spaces; a token is an option when it starts with '-' and the next character is
neither a digit nor '.', and it takes the next token as its value when that is no option;
`-options_file G` inside F is replaced by G's options, G looked up in F's folder and then in each
folder above it (so `options/solvers/x.opts` named inside options/saddle/ resolves from the
repository root). A line `# requires: FILE from OPTIONS` names a file the case needs and the
options file that makes it (scripts/run makes missing ones first).
"""
import os
import re

COMMENT = re.compile(r"[#!%]")
REQUIRES = re.compile(r"^# requires: (.*) from (.*)$")


class OptionsFileError(Exception):
    pass


def is_key(token):
    return len(token) > 1 and token[0] == "-" and not (token[1].isdigit() or token[1] == ".")


def tokens(line):
    """White-space separated tokens of one line (comment already removed); "a b" is one token."""
    out, i = [], 0
    while i < len(line):
        while i < len(line) and line[i].isspace():
            i += 1
        if i >= len(line):
            break
        if line[i] == '"':
            end = line.find('"', i + 1)
            if end < 0:
                raise OptionsFileError("a quote is not closed")
            out.append(line[i + 1:end])
            i = end + 1
        else:
            j = i
            while j < len(line) and not line[j].isspace():
                j += 1
            out.append(line[i:j])
            i = j
    return out


def pairs(words):
    """[(option, value or None)] of a token list (a command line or the options a run recorded)."""
    out, k = [], 0
    while k < len(words):
        w = words[k]
        if not is_key(w):
            k += 1
            continue
        val = words[k + 1] if k + 1 < len(words) and not is_key(words[k + 1]) else None
        out.append((w, val))
        k += 2 if val is not None else 1
    return out


def resolve_include(including, name):
    """The file G that `-options_file G` inside `including` names: its folder, then each above."""
    if os.path.isabs(name):
        return name
    d = os.path.dirname(os.path.abspath(including))
    while True:
        if os.path.exists(os.path.join(d, name)):
            return os.path.join(d, name)
        up = os.path.dirname(d)
        if up == d:
            return os.path.join(os.path.dirname(os.path.abspath(including)), name)
        d = up


def read(path, _open=None):
    """[(option, value or None)] of an options file in order, its -options_file includes expanded."""
    _open = set() if _open is None else _open
    if not os.path.isfile(path):
        raise OptionsFileError("options file %s: no such file" % path)
    real = os.path.realpath(path)
    if real in _open or len(_open) > 16:
        raise OptionsFileError("options file %s: includes itself (an -options_file loop)" % path)
    _open.add(real)
    out = []
    with open(path) as fh:
        for lineno, line in enumerate(fh, 1):
            m = COMMENT.search(line)
            try:
                words = tokens(line[:m.start()] if m else line)
            except OptionsFileError as e:
                raise OptionsFileError("%s:%d: %s" % (path, lineno, e))
            for key, val in pairs(words):
                if key == "-options_file" and val:
                    out.extend(read(resolve_include(path, val), _open))
                else:
                    out.append((key, val))
    _open.discard(real)
    return out


def read_dict(path):
    """{option: value or None} of an options file (the last setting of an option wins)."""
    return dict(read(path))


def requires(path):
    """[(file, options file that makes it)] from the `# requires:` lines of an options file."""
    out = []
    with open(path) as fh:
        for line in fh:
            m = REQUIRES.match(line.rstrip("\n"))
            if m:
                out.append((m.group(1).strip(), m.group(2).strip()))
    return out


def floats(value):
    """A comma-separated option value as floats ([] for None or empty)."""
    return [float(x) for x in value.split(",") if x.strip()] if value else []
