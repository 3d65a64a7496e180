"""Results and files: :class:`Result`, the package's CSV format, measured records (text and MATLAB files, units),
atomic writes and the terminal progress display.

May import: numpy, scipy.io (MATLAB files), h5py where installed (MATLAB v7.3 files; optional), matplotlib only
inside :meth:`Result.plot`, through :mod:`exudyn_atcm.plots`.
"""

from typing import TYPE_CHECKING

from ..lazy_names import lazy_face

# The names load on first use (PEP 562, exudyn_atcm.lazy_names): name -> (module, attribute), read as
# `from module import attribute`.  To add a public name: one line here, the name in __all__ and the same
# import under TYPE_CHECKING (tests/test_lazy_names.py checks that the three agree).
_LAZY = {
    "CsvHeader": (".csv_files", "CsvHeader"),
    "read_csv_header": (".csv_files", "read_csv_header"),
    "Record": (".measurements", "Record"),
    "preprocess": (".measurements", "preprocess"),
    "read_record": (".measurements", "read_record"),
    "Result": (".result", "Result"),
    "read_csv": (".result", "read_csv"),
}

if TYPE_CHECKING:  # for type checkers and IDEs: the same names, eagerly
    from .csv_files import CsvHeader, read_csv_header
    from .measurements import Record, preprocess, read_record
    from .result import Result, read_csv

__all__ = ["Result", "read_csv", "read_csv_header", "CsvHeader", "Record", "read_record", "preprocess"]

__getattr__, __dir__ = lazy_face(__name__, _LAZY, submodules=True)
