"""Build script.  The metadata is in setup.cfg; this file only adds the example cases.

The example cases live in ``cases/`` of the source tree (run them as
``python cases/<name>.py``); they are installed as the package ``exudyn_atcm.example_cases``
so that ``exudyn-atcm list`` and ``exudyn-atcm run <name>`` find them in any installation.
"""

from setuptools import find_packages, setup

setup(
    packages=find_packages(include=["exudyn_atcm", "exudyn_atcm.*"]) + ["exudyn_atcm.example_cases"],
    package_dir={"exudyn_atcm.example_cases": "cases"},
    # the cases' data files (e.g. the synthetic hysteresis record of identify_and_predict)
    package_data={"exudyn_atcm.example_cases": ["data/*.csv", "data/*.py"]},
)
