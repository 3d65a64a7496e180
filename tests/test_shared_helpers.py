"""One helper for each repeated job (issue 14, part 5): atomic writes, closest-name suggestions,
durations, GIF animations.  Each is tested on its own, and a scan of the package's source checks
that no second copy of the logic has come back."""

from __future__ import annotations

import ast
import os
import pathlib
import stat

import numpy as np
import pytest
from PIL import Image

from exudyn_atcm.suggestions import close_names
from exudyn_atcm.io.atomic import WriteError, atomic_path, move_into_place, write_text
from exudyn_atcm.io.progress import format_duration
from exudyn_atcm.plots import new_figure, save_gif

PACKAGE = pathlib.Path(__file__).resolve().parents[1] / "exudyn_atcm"


# ----------------------------------------------------------------------------- atomic writes
def test_atomic_path_replaces_the_target_only_when_complete(tmp_path):
    target = tmp_path / "a.txt"
    target.write_text("old\n")
    with atomic_path(target) as tmp:
        assert tmp.parent == tmp_path and tmp.name.startswith(".tmp_") and tmp.suffix == ".txt"
        tmp.write_text("new\n")
        assert target.read_text() == "old\n"  # readers see the old file until the block ends
    assert target.read_text() == "new\n"
    assert [p.name for p in tmp_path.iterdir()] == ["a.txt"]
    mask = os.umask(0)
    os.umask(mask)
    assert stat.S_IMODE(os.stat(target).st_mode) == 0o666 & ~mask  # not mkstemp's 0600


def test_atomic_path_keeps_the_old_file_on_error(tmp_path):
    target = tmp_path / "a.txt"
    target.write_text("old\n")
    with pytest.raises(RuntimeError, match="boom"):
        with atomic_path(target) as tmp:
            tmp.write_text("half")
            raise RuntimeError("boom")
    assert target.read_text() == "old\n"
    assert [p.name for p in tmp_path.iterdir()] == ["a.txt"]


def test_atomic_path_names_the_target_not_the_temporary_file(tmp_path):
    target = tmp_path / "a.txt"
    with pytest.raises(WriteError) as info:
        with atomic_path(target):
            raise PermissionError(13, "Permission denied", "/somewhere/.tmp_x")
    assert str(info.value) == f"cannot write {str(target)!r}: permission denied (the directory is read-only or belongs to someone else)"
    with pytest.raises(ValueError, match=r"path must be in an existing directory, got '.*missing/a.txt'"):
        with atomic_path(tmp_path / "missing" / "a.txt"):
            pass
    with atomic_path(tmp_path / "made" / "a.txt", make_dirs=True) as tmp:
        tmp.write_text("x")
    assert (tmp_path / "made" / "a.txt").read_text() == "x"


def test_move_into_place_replaces_the_target_and_names_both_paths_on_error(tmp_path):
    source, target = tmp_path / "new.png", tmp_path / "plot.png"
    source.write_text("new")
    target.write_text("old")
    assert move_into_place(source, target) == target
    assert target.read_text() == "new" and not source.exists()
    with pytest.raises(WriteError, match=rf"cannot move '{source}' to '{target}': "):
        move_into_place(source, target)  # the source is gone
    assert target.read_text() == "new"


def test_write_text_goes_through_atomic_path(tmp_path):
    path = write_text(tmp_path / "t.csv", "a\r\nb\n")
    assert path.read_bytes() == b"a\r\nb\n"  # UTF-8 with newline="\n": no line end translated
    assert [p.name for p in tmp_path.iterdir()] == ["t.csv"]


# ----------------------------------------------------------------------------- closest names
@pytest.mark.parametrize("name, candidates, kwargs, expected", [
    ("stpe", ["step", "t_end"], {}, ["step"]),            # difflib ratio 0.75
    ("xx", ["x", "period"], {"cutoff": 0.5}, ["x"]),       # ratio 2*1/3 = 0.67
    ("xx", ["x", "period"], {"cutoff": 0.7}, []),
    ("PERIOD", ["period"], {}, []),                        # ratio 0: case matters to difflib
    ("PERIOD", ["period"], {"ignore_case": True}, ["period"]),
    ("tip_y", ["tip_x", "tip_y0", "z"], {"n": 2, "cutoff": 0.75}, ["tip_y0", "tip_x"]),
])
def test_close_names(name, candidates, kwargs, expected):
    assert close_names(name, candidates, **kwargs) == expected


# ----------------------------------------------------------------------------- durations
@pytest.mark.parametrize("seconds, rough, text", [
    (42.4, False, "42 s"), (185.0, False, "3 min 05 s"), (7620.0, False, "2 h 07 min"), (-3.0, False, "0 s"),
    (42.4, True, "42 s"), (119.0, True, "119 s"), (840.0, True, "14 min"), (7199.0, True, "120 min"),
    (9000.0, True, "2.5 h"),
])
def test_format_duration(seconds, rough, text):
    assert format_duration(seconds, rough=rough) == text


# ----------------------------------------------------------------------------- GIF
def test_save_gif_writes_every_frame_with_the_frame_time(tmp_path):
    fig, (ax,) = new_figure(1, 1, width=2.0, height=1.5)
    (line,) = ax.plot([], [])
    ax.set_xlim(0, 4)
    ax.set_ylim(0, 4)
    seen = []
    path = save_gif(fig, lambda k: line.set_data([0, k], [0, k]), 4, tmp_path / "g.gif", fps=15,
                    progress=lambda done, total: seen.append((done, total)))
    assert seen == [(1, 4), (2, 4), (3, 4), (4, 4)]
    with Image.open(path) as image:
        assert image.n_frames == 4
        # round(1000 / 15) = 67 ms, stored in the GIF's units of 1/100 s (Pillow truncates): 60 ms
        assert image.info["duration"] == 60
        first = np.asarray(image.convert("RGB"))
        image.seek(3)
        last = np.asarray(image.convert("RGB"))
    assert first.shape == last.shape and not np.array_equal(first, last)
    assert [p.name for p in tmp_path.iterdir()] == ["g.gif"]


@pytest.mark.parametrize("kwargs, message", [
    ({"n_frames": 0}, "n_frames must be an integer >= 1, got 0"),
    ({"fps": 0}, "fps must be an integer >= 1, got 0"),
    ({"colors": 1}, r"colors must be an integer in \[2, 256\], got 1"),
])
def test_save_gif_refuses_bad_arguments(tmp_path, kwargs, message):
    fig, _ = new_figure(1, 1, width=2.0, height=1.5)
    arguments = {"n_frames": 2, "fps": 5, **kwargs}
    with pytest.raises(ValueError, match=message):
        save_gif(fig, lambda k: None, arguments.pop("n_frames"), tmp_path / "g.gif", **arguments)


# ----------------------------------------------------------------------------- no second copy
def _calls(path: pathlib.Path) -> set[str]:
    names = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Attribute):
            names.add(node.attr)
        elif isinstance(node, ast.Name):
            names.add(node.id)
        elif isinstance(node, (ast.Import, ast.ImportFrom)):
            names.update(a.name for a in node.names)
            names.add(node.module or "") if isinstance(node, ast.ImportFrom) else None
    return names


@pytest.mark.parametrize("marker, home", [
    ("mkstemp", "io/atomic.py"), ("replace", "io/atomic.py"),           # temp file, then os.replace
    ("difflib", "suggestions.py"), ("get_close_matches", "suggestions.py"),          # closest-name suggestion
    ("PillowWriter", None), ("FuncAnimation", None),                     # GIFs: plots/gif.py only
])
def test_each_job_has_one_home(marker, home):
    found = sorted(str(p.relative_to(PACKAGE)) for p in PACKAGE.rglob("*.py") if marker in _calls(p))
    if marker == "replace":  # str.replace is everywhere: look for os.replace itself
        found = sorted(str(p.relative_to(PACKAGE)) for p in PACKAGE.rglob("*.py")
                       if "os.replace(" in p.read_text(encoding="utf-8").replace('``os.replace``', ""))
    assert found == ([home] if home else [])


def test_gif_images_are_saved_in_one_place():
    """Only plots/gif.py calls ``save(..., format="GIF")``."""
    savers = set()
    for path in PACKAGE.rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Call) and any(k.arg == "format" and getattr(k.value, "value", None) == "GIF"
                                                  for k in node.keywords):
                savers.add(str(path.relative_to(PACKAGE)))
    assert sorted(savers) == ["plots/gif.py"]
