"""Case scripts (declared parameters, one run function, standard outputs), the regression suite
and the command line's error reports.

May import everything below it; :mod:`exudyn_atcm.study` and the command line build on it.
"""
