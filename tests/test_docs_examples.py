"""Every ``.. code-block:: python`` of the runnable documentation pages executes as printed.

The blocks of a page run in order in one namespace, in a fresh working directory, as a reader
would paste them into one Python session.  The pages contain their own checks (``assert``
against closed forms of beam theory and the hysteresis model), so a block that runs but gives
a wrong answer fails here too.
"""

from __future__ import annotations

import re
import textwrap
from pathlib import Path

import pytest

DOCS = Path(__file__).resolve().parent.parent / "docs"

#: Pages whose python code blocks are complete programs (others show fragments with ``...``).
RUNNABLE_PAGES = ["tutorial.rst"]

_BLOCK = re.compile(r"^\.\. code-block:: python[^\n]*\n((?:[ \t]*\n|[ \t]+[^\n]*\n)+)", re.MULTILINE)


def python_blocks(page: Path) -> list[tuple[int, str]]:
    """(line number, dedented source) of each ``.. code-block:: python`` of ``page``."""
    text = page.read_text(encoding="utf-8")
    blocks = []
    for match in _BLOCK.finditer(text):
        body = match.group(1)
        # directive options (":linenos:") would come first; skip them
        lines = [line for line in body.splitlines() if not re.match(r"^\s+:\w[\w-]*:", line)]
        source = textwrap.dedent("\n".join(lines)).strip("\n")
        blocks.append((text.count("\n", 0, match.start()) + 1, source))
    return blocks


def test_block_extraction_finds_every_block():
    # independent count: the directive lines themselves
    for name in RUNNABLE_PAGES:
        page = DOCS / name
        expected = sum(1 for line in page.read_text(encoding="utf-8").splitlines()
                       if line.startswith(".. code-block:: python"))
        assert len(python_blocks(page)) == expected > 0


@pytest.mark.parametrize("name", RUNNABLE_PAGES)
def test_page_code_blocks_run(name, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    namespace: dict = {"__name__": "__docs__"}
    for line, source in python_blocks(DOCS / name):
        code = compile(source, f"docs/{name}:{line}", "exec")
        exec(code, namespace)  # noqa: S102 - the documentation's own examples
    if name == "tutorial.rst":
        # the files the tutorial promises
        for file in ("my_actuator.csv", "my_actuator_loop.png", "my_actuator_time_series.png",
                     "my_actuator_tip_vs_voltage.png", "my_actuator_shapes.png"):
            assert (tmp_path / "out" / file).stat().st_size > 0, file
