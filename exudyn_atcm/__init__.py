"""exudyn_atcm: multibody simulation of active textile-reinforced compliant mechanisms on Exudyn."""

from . import hysteresis, signals
from ._version import __version__

__all__ = ["__version__", "hysteresis", "signals"]
