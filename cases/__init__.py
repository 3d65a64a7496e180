"""The example cases of exudyn_atcm, installed as the package ``exudyn_atcm.example_cases``.

Each file is a case script (see :mod:`exudyn_atcm.casework.case`); run one with
``python cases/<name>.py`` from the source tree or ``exudyn-atcm run <name>`` anywhere.
"""
