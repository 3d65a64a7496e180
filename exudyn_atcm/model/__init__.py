"""The physical description below any mechanism: layer materials, the laminate, the drive, voltage
programs, controllers, strain sources, recording schedules and literature parameter sets.

May import: numpy, scipy, :mod:`exudyn_atcm.hysteresis`, :mod:`exudyn_atcm.theory`,
:mod:`exudyn_atcm.io` and the package's argument checks; never Exudyn, solving or plotting.
"""
