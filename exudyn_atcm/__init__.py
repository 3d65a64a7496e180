"""exudyn_atcm: multibody simulation of active textile-reinforced compliant mechanisms on Exudyn."""

from . import hysteresis, signals
from ._version import __version__
from .csv_io import read_csv

__all__ = ["__version__", "hysteresis", "signals", "read_csv"]
