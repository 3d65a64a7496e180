"""The rules of the result CSV format, shared by its writer and its reader.

:meth:`Result.to_csv <exudyn_atcm.io.result.Result.to_csv>` writes and
:func:`~exudyn_atcm.read_csv` reads the same format; this module holds what both must
agree on, so that whatever the writer accepts reads back identically:

* a header cell is ``name [unit]``; neither may contain ``,``, ``[``, ``]``, a line break or an
  invisible character (byte-order mark, zero-width space), nor begin or end with blanks;
  a name may not contain ``#``;
* a ``# key: value`` line holds a parameter (``# info.key: value``: run information); the key
  ``data_rows`` is reserved for the row count, and a parameter key may not begin with
  ``info.``;
* a value is written as its text where that text parses back (:func:`parse_value`) to the same
  value; a string whose text would parse as something else (``"1.0"``, ``"None"``) or that holds a
  line break is written quoted (``'1.0'``); numpy numbers and arrays are written as Python numbers
  and lists.  Other objects cannot be read back and are refused.

:func:`comment_line` and :func:`header_cell` apply these rules and raise a ``ValueError``
naming the offending key, name or unit.
"""

from __future__ import annotations

import ast
import re
from typing import Any

import numpy as np
from .._checks import shown

__all__ = [
    "COLUMN",
    "RESERVED_KEYS",
    "parse_value",
    "split_comment",
    "invisible_characters",
    "plain_value",
    "same_value",
    "comment_line",
    "header_cell",
]

#: A header cell ``name [unit]`` (the reader's pattern).
COLUMN = re.compile(r"^\s*([^\[\],#]+?)\s*\[([^\[\],]*)\]\s*$")

#: ``# key: value`` keys the format itself uses (a parameter of that name would be misread).
RESERVED_KEYS = ("data_rows",)

#: Characters that do not show in an editor but make two names differ: the byte-order mark,
#: zero-width spaces and joiners, the word joiner, and C0/C1 control characters (tab excepted).
_INVISIBLE = re.compile("[\ufeff\u200b\u200c\u200d\u2060\u00ad\x00-\x08\x0b-\x1f\x7f-\x9f]")


def parse_value(text: str) -> Any:
    """The value of a ``# key: value`` line: a Python literal where the text is one, else the text.

    ``nan``, ``inf`` and ``-inf`` are floats.
    """
    text = text.strip()
    if text in ("nan", "inf", "-inf"):
        return float(text)
    try:
        return ast.literal_eval(text)
    except (ValueError, SyntaxError, MemoryError, RecursionError, TypeError):
        return text


def split_comment(body: str) -> tuple[str, str] | None:
    """``(key, value text)`` of a comment line's body (after ``#``), or ``None`` for a free comment."""
    key, sep, value = body.partition(": ")
    if not sep:
        key, sep, value = body.partition(":")
    if not sep or not key.strip():
        return None
    return key.strip(), value


def invisible_characters(text: str) -> list[str]:
    """The invisible characters in ``text``, as ``U+XXXX`` (empty if none)."""
    return [f"U+{ord(c):04X}" for c in _INVISIBLE.findall(text)]


def plain_value(value: Any) -> Any:
    """``value`` with numpy scalars and arrays turned into Python numbers and lists (recursively)."""
    if isinstance(value, np.ndarray):
        return plain_value(value.tolist())
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, list):
        return [plain_value(v) for v in value]
    if isinstance(value, tuple):
        return tuple(plain_value(v) for v in value)
    if isinstance(value, dict):
        return {plain_value(k): plain_value(v) for k, v in value.items()}
    return value


def same_value(a: Any, b: Any) -> bool:
    """``a`` and ``b`` are the same value of the same kind (floats bit for bit, NaN equal to NaN)."""
    if isinstance(a, bool) or isinstance(b, bool):
        return type(a) is type(b) and a == b
    if isinstance(a, float) or isinstance(b, float):
        return type(a) is type(b) and (repr(a) == repr(b))
    if isinstance(a, (list, tuple)):
        return type(a) is type(b) and len(a) == len(b) and all(same_value(x, y) for x, y in zip(a, b))
    if isinstance(a, dict):
        return (type(b) is dict and len(a) == len(b)
                and all(any(same_value(k, k2) and same_value(v, b[k2]) for k2 in b) for k, v in a.items()))
    if a is None or b is None:
        return a is b
    if isinstance(a, (int, str, complex, bytes)):
        return type(a) is type(b) and a == b
    return False


def _round_trips(key: str, text: str, value: Any) -> bool:
    """The line ``# key: text`` reads back as ``key`` and ``value``."""
    if "\n" in text or "\r" in text:
        return False
    parsed = split_comment(f"# {key}: {text}".strip()[1:].strip())
    return parsed is not None and parsed[0] == key and same_value(parse_value(parsed[1]), value)


def comment_line(key: Any, value: Any, *, prefix: str = "", what: str = "parameter") -> str:
    """The line ``# <prefix><key>: <value>`` that reads back to ``key`` and ``value``.

    Parameters
    ----------
    key : str
        Parameter or info name.
    value : object
        A number, string, bool, ``None``, or a list, tuple or dict of those (numpy values are
        written as Python numbers and lists).
    prefix : str
        ``"info."`` for run information.
    what : str
        ``"parameter"`` or ``"info"``, for the message.

    Raises
    ------
    ValueError
        Naming the key, if the key is not a non-empty string free of ``": "``, line breaks,
        invisible characters and surrounding blanks, is reserved (``data_rows``; a parameter
        beginning with ``info.``), or if the value would not read back as itself.
    """
    if not isinstance(key, str):
        raise ValueError(f"{what} names must be strings to be written to CSV, got {shown(key)}")
    full = prefix + key
    problems = []
    if not key.strip():
        problems.append("it is empty")
    elif key != key.strip():
        problems.append("it begins or ends with blanks")
    if ": " in key or key.endswith(":") or "\n" in key or "\r" in key:
        problems.append("it contains ': ', a final ':' or a line break")
    if invisible_characters(key):
        problems.append(f"it contains invisible characters {invisible_characters(key)}")
    if not prefix and (key in RESERVED_KEYS or key.startswith("info.")):
        problems.append("the name is reserved by the CSV format (data_rows; info.* is run information)")
    if key.startswith("#"):
        problems.append("it begins with '#'")
    if problems:
        raise ValueError(f"{what} {key!r} cannot be written to CSV: {'; '.join(problems)}; rename it")
    plain = plain_value(value)
    candidates = [str(plain)]
    if isinstance(plain, str):
        candidates.append(repr(plain))
    for text in candidates:
        if _round_trips(full, text, plain):
            return f"# {full}: {text}"
    raise ValueError(
        f"{what} {key!r} = {value!r} cannot be written to CSV so that read_csv reads it back: use a number, "
        "string, bool, None, or a list, tuple or dict of those (str(value) to keep its text)"
    )


def header_cell(name: Any, unit: Any) -> str:
    """The header cell ``name [unit]`` of a series.

    Raises
    ------
    ValueError
        Naming the series, if the name or unit holds ``,``, ``[``, ``]`` or a line break (the
        name also ``#``), an invisible character, begins or ends with blanks, or the name is
        empty.
    """
    problems = []
    name_text, unit_text = str(name), str(unit)
    if not name_text.strip():
        problems.append("the name is empty")
    elif name_text != name_text.strip():
        problems.append("the name begins or ends with blanks")
    if any(c in name_text for c in ",[]#\n\r"):
        problems.append("the name contains one of , [ ] # or a line break")
    if unit_text != unit_text.strip():
        problems.append(f"the unit {unit_text!r} begins or ends with blanks")
    if any(c in unit_text for c in ",[]\n\r"):
        problems.append(f"the unit {unit_text!r} contains one of , [ ] or a line break")
    for label, text in (("name", name_text), ("unit", unit_text)):
        if invisible_characters(text):
            problems.append(f"the {label} contains invisible characters {invisible_characters(text)}")
    if problems:
        raise ValueError(f"series {name_text!r} with unit {unit_text!r} cannot be written to CSV: {'; '.join(problems)}")
    cell = f"{name_text} [{unit_text}]"
    match = COLUMN.match(cell)
    if match is None or match.group(1).strip() != name_text or match.group(2).strip() != unit_text:  # pragma: no cover
        raise ValueError(f"series {name_text!r} with unit {unit_text!r} cannot be written to CSV")
    return cell

