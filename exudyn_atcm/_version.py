"""Version of the exudyn_atcm package."""

__version__ = "0.3.0"
