"""The rules the layout keeps (docs/architecture.md), checked on the source tree.

    check_tree.py ROOT

- every Fortran file of src/ and drivers/ holds one module, submodule or program named
  after the file (voussoir_<file stem>);
- no file of src/ or drivers/ over 600 lines, no Fortran procedure over 100 lines;
- no string comparison of a sweep mode outside the sweep mode factory
  (src/sweep/sweep_mode_factory.f90): no `== 'ida'`, `case ('grid')` or `%mode ==`;
- every source file is named in docs/architecture.md by its path below src/, drivers/
  or postproc/voussoir_post/ (`rigid2d/nlgs.f90`, `plots/envelope.py`), so the map
  stays the tree.

Prints one line per breach and exits 1 when there is any.
"""
from __future__ import annotations

import pathlib
import re
import sys

MAX_FILE_LINES = 600
MAX_PROCEDURE_LINES = 100
MODE_FACTORY = "src/sweep/sweep_mode_factory.f90"
MODE_NAMES = ("threshold", "grid", "ida")

UNIT = re.compile(r"^\s*(module|submodule\s*\([^)]*\)|program)\s+(\w+)\s*$", re.I)
PROC_START = re.compile(
    r"^\s*(?:(?:pure|elemental|recursive|impure|module|integer|logical|real\s*\([^)]*\)|"
    r"type\s*\([^)]*\)|character\s*\([^)]*\)|complex\s*\([^)]*\))\s+)*(subroutine|function)\s+(\w+)", re.I)
PROC_END = re.compile(r"^\s*end\s*(subroutine|function)\b", re.I)
_NAME = r"""['"](?:%s)['"]""" % "|".join(MODE_NAMES)
# A mode name compared with a text (== 'ida', 'grid' /= ..., case ('threshold')), or a
# mode component (plan%mode) compared or selected on; a mode name in a message is no comparison.
MODE_COMPARISON = re.compile(
    rf"(==|/=|\.eq\.|\.ne\.)\s*{_NAME}|{_NAME}\s*(==|/=|\.eq\.|\.ne\.)|case\s*\([^)]*{_NAME}"
    r"|%mode\w*\s*(==|/=|\.eq\.|\.ne\.)|select\s+case\s*\(\s*[\w%]*%mode\w*\s*\)", re.I)


def code_lines(path: pathlib.Path) -> list[str]:
    """The lines of a Fortran file without their comments (a '!' outside quotes)."""
    out = []
    for line in path.read_text(encoding="utf-8", errors="replace").splitlines():
        quote = None
        for i, ch in enumerate(line):
            if quote:
                if ch == quote:
                    quote = None
            elif ch in "'\"":
                quote = ch
            elif ch == "!":
                line = line[:i]
                break
        out.append(line)
    return out


def procedures(lines: list[str]) -> list[tuple[str, int, int]]:
    """(name, first line, length) of every subroutine and function, nested ones too."""
    stack, found = [], []
    for number, line in enumerate(lines, 1):
        if PROC_END.match(line):
            if stack:
                name, start = stack.pop()
                found.append((name, start, number - start + 1))
        elif not re.match(r"^\s*module\s+procedure", line, re.I):
            m = PROC_START.match(line)
            if m and not re.match(r"^\s*end", line, re.I):
                stack.append((m.group(2), number))
    return found


def main(root: pathlib.Path) -> int:
    breaches = []
    sources = sorted(p for d in ("src", "drivers") for p in (root / d).rglob("*")
                     if p.suffix in (".f90", ".c"))
    for path in sources:
        rel = path.relative_to(root).as_posix()
        text = path.read_text(encoding="utf-8", errors="replace")
        n_lines = text.count("\n")
        if n_lines > MAX_FILE_LINES:
            breaches.append(f"{rel}: {n_lines} lines (at most {MAX_FILE_LINES})")
        if path.suffix != ".f90":
            continue
        lines = code_lines(path)
        units = [m.group(2).lower() for m in map(UNIT.match, lines) if m]
        expected = path.stem if path.stem.startswith("voussoir_") else f"voussoir_{path.stem}"
        if units != [expected]:
            breaches.append(f"{rel}: holds {units or 'no unit'}, not {expected} alone")
        for name, start, length in procedures(lines):
            if length > MAX_PROCEDURE_LINES:
                breaches.append(f"{rel}:{start}: procedure {name} is {length} lines (at most {MAX_PROCEDURE_LINES})")
        if rel != MODE_FACTORY:
            for number, line in enumerate(lines, 1):
                if MODE_COMPARISON.search(line):
                    breaches.append(f"{rel}:{number}: a sweep mode by name outside {MODE_FACTORY}: {line.strip()}")

    architecture = (root / "docs" / "architecture.md").read_text(encoding="utf-8")
    listed = sources + sorted(p for p in (root / "postproc" / "voussoir_post").rglob("*.py")
                              if p.name != "__init__.py")
    tops = [root / "src", root / "drivers", root / "postproc" / "voussoir_post"]
    for path in listed:
        rel = path.relative_to(root).as_posix()
        short = next(path.relative_to(t).as_posix() for t in tops if t in path.parents)
        if not re.search(rf"(^|[\s`/(]){re.escape(short)}($|[\s`),.;:])", architecture, re.M):
            breaches.append(f"{rel}: not named in docs/architecture.md")

    for line in breaches:
        print(line)
    print(f"{len(sources)} source files of src/ and drivers/ checked, {len(listed)} named in the map: "
          f"{len(breaches)} breaches")
    return 1 if breaches else 0


if __name__ == "__main__":
    sys.exit(main(pathlib.Path(sys.argv[1])))
