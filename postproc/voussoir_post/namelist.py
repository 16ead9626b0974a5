"""Fortran namelists in both directions: :func:`format_namelist` writes a mapping
``{group: {variable: value}}`` as namelist text (what :mod:`voussoir_post.runner` gives
the executables), :func:`parse_namelist` reads namelist text back into such a mapping
(the ``config_nml`` attribute of every result file). ``parse_namelist(format_namelist(g))
== g`` for the values the runner writes (int, float, bool, str and lists of them).
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping, Sequence

__all__ = ["format_value", "format_namelist", "parse_namelist"]


def format_value(value) -> str:
    """One namelist value in Fortran syntax (lists comma-separated)."""
    if isinstance(value, bool):
        return ".true." if value else ".false."
    if isinstance(value, (int,)) and not isinstance(value, bool):
        return str(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            raise ValueError(f"a namelist value must be finite, got {value!r}")
        return repr(value)
    if isinstance(value, str):
        return "'" + value.replace("'", "''") + "'"
    if isinstance(value, Sequence):
        if len(value) == 0:
            raise ValueError("a namelist list must not be empty")
        return ", ".join(format_value(v) for v in value)
    if hasattr(value, "item"):  # numpy scalars
        return format_value(value.item())
    raise TypeError(f"no namelist form for {type(value).__name__} {value!r}")


def format_namelist(groups: Mapping[str, Mapping[str, object]]) -> str:
    """The text of a namelist file: one ``&group`` per mapping entry, in order."""
    out = []
    for group, variables in groups.items():
        body = ",\n".join(f"  {name} = {format_value(v)}" for name, v in variables.items())
        out.append(f"&{group}\n{body}\n/\n" if body else f"&{group}\n/\n")
    return "".join(out)


def _nml_value(text: str):
    """One namelist value: int, float, bool, string or a list of them."""
    text = text.strip().rstrip(",").strip()
    if not text:
        return None
    items = []
    for token in re.findall(r"'(?:[^']|'')*'|\"(?:[^\"]|\"\")*\"|[^,\s]+", text):
        repeat = 1
        m = re.fullmatch(r"(\d+)\*(.+)", token)
        if m and not token.startswith(("'", '"')):
            repeat, token = int(m.group(1)), m.group(2)
        if token[0] in "'\"":
            value = token[1:-1].replace(token[0] * 2, token[0]).rstrip()
        elif re.fullmatch(r"\.?(t|true|f|false)\.?", token, re.I):
            value = token.strip(".").lower().startswith("t")
        else:
            try:
                value = int(token)
            except ValueError:
                try:
                    value = float(token.replace("d", "e").replace("D", "e"))
                except ValueError:
                    value = token
        items.extend([value] * repeat)
    return items[0] if len(items) == 1 else items


def parse_namelist(text: str) -> dict[str, dict[str, object]]:
    """Parse Fortran namelist text into ``{group: {variable: value}}`` (lower case names).

    Tolerant of the formats compilers write (upper-case names, trailing commas,
    ``n*value`` repeats, quoted strings, ``T``/``F`` logicals); values are int, float,
    bool, str or lists of them. Used on the ``config_nml`` root attribute.
    """
    groups: dict[str, dict[str, object]] = {}
    # Split on group starts; each chunk runs to its terminating '/'.
    for chunk in re.split(r"(?m)^\s*&", "\n" + text)[1:]:
        m = re.match(r"(\w+)", chunk)
        if not m:
            continue
        name = m.group(1).lower()
        body = chunk[m.end():]
        # Drop the terminating '/' (outside quotes) and anything after it.
        end = _namelist_end(body)
        body = body[:end]
        variables: dict[str, object] = {}
        # Assignments: name = values up to the next 'name ='; name(i) = value sets the
        # i-th element (from 1) of the list `name` (the form voussoir's config_nml gives
        # &bridge span_m(1) and &load point_load_n(1)).
        assigns = list(re.finditer(r"(?:^|[\s,])([A-Za-z]\w*(?:%\w+)*)\s*(?:\(\s*(\d+)\s*\))?\s*=", body))
        for k, am in enumerate(assigns):
            stop = assigns[k + 1].start() if k + 1 < len(assigns) else len(body)
            value = _nml_value(body[am.end():stop])
            var = am.group(1).lower()
            if am.group(2) is None:
                variables[var] = value
                continue
            items = variables.get(var)
            items = list(items) if isinstance(items, list) else ([] if items is None else [items])
            start = int(am.group(2)) - 1
            values = value if isinstance(value, list) else [value]
            items.extend([None] * max(0, start + len(values) - len(items)))
            items[start:start + len(values)] = values
            variables[var] = items
        groups[name] = variables
    return groups


def _namelist_end(body: str) -> int:
    """Index of the '/' ending a namelist group body (outside quotes)."""
    quote = None
    for i, ch in enumerate(body):
        if quote:
            if ch == quote:
                quote = None
        elif ch in "'\"":
            quote = ch
        elif ch == "/":
            return i
        elif body.startswith("&end", i) or body.startswith("&END", i):
            return i
    return len(body)


# ------------------------------------------------------------------------ run files
