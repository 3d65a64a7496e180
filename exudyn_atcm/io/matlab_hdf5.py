"""MATLAB v7.3 files (HDF5) read with ``h5py`` where it is installed, into the form :func:`scipy.io.loadmat` gives.

``h5py`` is optional (not a dependency of the package): without it :func:`load_hdf5` refuses
the file and says what to do.  The layout is MATLAB's v7.3 format: every variable is an HDF5
dataset or group at the root with a ``MATLAB_class`` attribute; arrays are stored with their
dimensions reversed (MATLAB is column-major); text is ``char`` (UTF-16 code units); a struct is
a group whose members are its fields; in a struct array every field is a dataset of object
references (one per element, into ``#refs#``); a cell array is a dataset of references with
``MATLAB_class = "cell"``; an empty array has ``MATLAB_empty`` set.  The result uses the types
of ``scipy.io.loadmat(..., simplify_cells=True)``: dicts for structs, lists for struct arrays
and cells, squeezed arrays for numbers and ``str`` for text.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

try:  # optional: only for MATLAB v7.3 (HDF5) files
    import h5py
except ImportError:  # pragma: no cover - depends on the environment
    h5py = None

__all__ = ["load_hdf5"]


def _class(node: Any) -> str:
    value = node.attrs.get("MATLAB_class", b"")
    return value.decode() if isinstance(value, bytes) else str(value)


def _is_reference(dataset: Any) -> bool:
    return dataset.dtype == h5py.ref_dtype


def _dataset(dataset: Any, root: Any) -> Any:
    kind = _class(dataset)
    if dataset.attrs.get("MATLAB_empty", 0):
        return "" if kind == "char" else np.zeros(0)
    if _is_reference(dataset):
        items = [_value(root[ref], root) for ref in np.asarray(dataset[()]).T.ravel()]
        return items[0] if len(items) == 1 and kind != "cell" else items
    data = np.asarray(dataset[()]).T
    if kind == "char":
        return "".join(chr(int(c)) for c in data.ravel()).strip("\x00")
    if kind == "logical":
        data = data.astype(bool)
    return data.squeeze() if data.ndim > 1 or data.size > 1 else (data.ravel()[0] if data.size else data)


def _group(group: Any, root: Any) -> Any:
    members = {k: group[k] for k in group.keys()}
    fields = group.attrs.get("MATLAB_fields")
    if fields is not None:  # MATLAB's own field order
        order = ["".join(c.decode() if isinstance(c, bytes) else str(c) for c in np.ravel(f)) for f in fields]
        members = {k: members[k] for k in order if k in members} | members
    struct_array = bool(members) and all(
        isinstance(m, h5py.Dataset) and _is_reference(m) and not _class(m) for m in members.values())
    if not struct_array:
        return {k: _value(m, root) for k, m in members.items()}
    refs = {k: np.asarray(m[()]).T.ravel() for k, m in members.items()}
    n = min(r.size for r in refs.values())
    elements = [{k: _value(root[r[i]], root) for k, r in refs.items()} for i in range(n)]
    return elements[0] if n == 1 else elements


def _value(node: Any, root: Any) -> Any:
    return _group(node, root) if isinstance(node, h5py.Group) else _dataset(node, root)


def load_hdf5(path: Path) -> dict:
    """The variables of a MATLAB v7.3 file, as :func:`scipy.io.loadmat` with ``simplify_cells=True`` gives them.

    Raises
    ------
    ValueError
        If ``h5py`` is not installed (with what to do), or the file cannot be read as HDF5.
    """
    if h5py is None:
        raise ValueError(
            f"{path} is a MATLAB v7.3 file (HDF5), which scipy.io cannot read; save it in MATLAB as "
            "save(file, ..., '-v7'), or install h5py (pip install h5py), with which read_record reads v7.3 files"
        )
    try:
        with h5py.File(str(path), "r") as root:
            return {k: _value(root[k], root) for k in root.keys() if not k.startswith("#")}
    except OSError as exc:
        raise ValueError(f"{path}: the MATLAB v7.3 (HDF5) file cannot be read ({exc})") from None
