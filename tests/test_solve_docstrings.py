"""The solve functions document exactly the parameters they take (a pasted ``method`` entry once sat in
``eigenfrequencies``' docstring, which has no such parameter)."""

from __future__ import annotations

import inspect
import re

import pytest

import exudyn_atcm as atcm


def documented(function) -> set[str]:
    doc = inspect.getdoc(function)
    section = doc.split("Parameters\n----------\n", 1)[1]
    section = re.split(r"\n\n[A-Z][a-z]+\n-+\n", section, maxsplit=1)[0]
    names = set()
    for line in section.splitlines():
        match = re.match(r"^([A-Za-z_][\w, ]*) :", line)
        if match:
            names.update(n.strip() for n in match.group(1).split(","))
    return names


@pytest.mark.parametrize("function", [atcm.simulate, atcm.solve_static, atcm.static_sweep, atcm.eigenfrequencies],
                         ids=lambda f: f.__name__)
def test_the_docstring_lists_the_signature(function):
    taken = {n for n, p in inspect.signature(function).parameters.items() if p.kind is not p.VAR_POSITIONAL}
    assert documented(function) == taken
