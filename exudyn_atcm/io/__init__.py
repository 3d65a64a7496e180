"""Results and files: :class:`Result`, the package's CSV format, measured records (text and MATLAB files, units),
atomic writes and the terminal progress display.

May import: numpy, scipy.io (MATLAB files), h5py where installed (MATLAB v7.3 files; optional), matplotlib only
inside :meth:`Result.plot`, through :mod:`exudyn_atcm.plots`.
"""

from .csv_files import CsvHeader, read_csv_header
from .measurements import Record, preprocess, read_record
from .result import Result, read_csv

__all__ = ["Result", "read_csv", "read_csv_header", "CsvHeader", "Record", "read_record", "preprocess"]
