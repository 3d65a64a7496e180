"""Draw the package's layers and the imports between them, read from the source with ``ast``.

Run by the ``plot`` directive of ``architecture.rst`` at every docs build, so the picture is the
code's, not a drawing that can drift from it.
"""

import ast
import pathlib

import matplotlib.pyplot as plt

import exudyn_atcm

PACKAGE = pathlib.Path(exudyn_atcm.__file__).resolve().parent
BOTTOM = "_checks, errors, physical_bounds, suggestions"
#: rows of the picture, bottom up (a folder imports only folders below or beside it)
ROWS = [
    [BOTTOM],
    ["io", "theory"],
    ["hysteresis", "cells"],
    ["model"],
    ["mechanism"],
    ["mbs"],
    ["solve", "plots"],
    ["casework"],
    ["study"],
    ["cli"],
]
TOP_LEVEL = {"_checks": BOTTOM, "errors": BOTTOM, "physical_bounds": BOTTOM, "suggestions": BOTTOM, "cli": "cli"}


def folder_of(module: str) -> str | None:
    parts = module.split(".")
    if parts[0] != "exudyn_atcm" or len(parts) < 2:
        return None
    if parts[1] in TOP_LEVEL:
        return TOP_LEVEL[parts[1]]
    return parts[1] if (PACKAGE / parts[1]).is_dir() else None


def edges() -> set[tuple[str, str]]:
    """(importer folder, imported folder) for every import in the package, functions included."""
    out = set()
    for path in PACKAGE.rglob("*.py"):
        rel = path.relative_to(PACKAGE.parent).with_suffix("").parts
        name = ".".join(rel[:-1] if rel[-1] == "__init__" else rel)
        package = name if path.name == "__init__.py" else name.rpartition(".")[0]
        source = folder_of(name)
        for node in ast.walk(ast.parse(path.read_text())):
            targets = []
            if isinstance(node, ast.ImportFrom):
                if node.level:
                    base = package.split(".")[: len(package.split(".")) - (node.level - 1)]
                    targets.append(".".join(base + ([node.module] if node.module else [])))
                else:
                    targets.append(node.module or "")
            elif isinstance(node, ast.Import):
                targets += [a.name for a in node.names]
            for target in targets:
                folder = folder_of(target)
                if source and folder and folder != source:
                    out.add((source, folder))
    return out


def draw(ax) -> None:
    pos = {}
    for y, row in enumerate(ROWS):
        for i, name in enumerate(row):
            pos[name] = ((i + 1) / (len(row) + 1), y)
    for a, b in sorted(edges()):
        if a in pos and b in pos:
            (x0, y0), (x1, y1) = pos[a], pos[b]
            ax.annotate("", xy=(x1, y1 + 0.18), xytext=(x0, y0 - 0.18),
                        arrowprops=dict(arrowstyle="->", color="0.6", lw=0.7, shrinkA=2, shrinkB=2))
    for name, (x, y) in pos.items():
        ax.text(x, y, name, ha="center", va="center", fontsize=9,
                bbox=dict(boxstyle="round,pad=0.35", fc="#dde8f5" if name != "mbs" else "#f5e2cc", ec="0.3"))
    ax.set_xlim(0, 1)
    ax.set_ylim(-0.6, len(ROWS) - 0.4)
    ax.axis("off")
    ax.set_title("exudyn_atcm: folders (boxes) and imports between them (arrows), read from the code",
                 fontsize=9)


fig, axis = plt.subplots(figsize=(7.5, 6.5))
draw(axis)
fig.tight_layout()
