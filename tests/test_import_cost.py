"""Start-up cost, checked by structure (issue 31, part 4), never by a clock.

``import exudyn_atcm`` and ``exudyn-atcm --help`` must not load the slow optional layers: scipy (its
``signal``/``stats`` alone took ~1 s), matplotlib (~0.4 s), which are imported where a fit, a MATLAB
file or a figure needs them.  Each check runs a fresh interpreter, since this test process has long
imported them all.  The timings themselves are in ``benchmarks/bench_import.py``.
"""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

#: Modules that a plain ``import exudyn_atcm`` must not load (all of scipy, matplotlib).
HEAVY = ("scipy", "scipy.linalg", "scipy.optimize", "scipy.signal", "scipy.stats", "scipy.io", "scipy.sparse",
         "scipy.integrate", "matplotlib", "matplotlib.figure", "matplotlib.pyplot")


def _loaded_after(code: str) -> set[str]:
    """Names of ``HEAVY`` in ``sys.modules`` of a fresh interpreter after running ``code``."""
    probe = f"{code}\nimport json, sys\nprint(json.dumps([m for m in {HEAVY!r} if m in sys.modules]))"
    out = subprocess.run([sys.executable, "-c", probe], check=True, capture_output=True, text=True)
    return set(json.loads(out.stdout.strip().splitlines()[-1]))


def test_import_package_loads_no_scipy_nor_matplotlib():
    assert _loaded_after("import exudyn_atcm") == set()


def test_cli_help_loads_no_scipy_nor_matplotlib():
    code = ("import contextlib, io, sys\nsys.argv = ['exudyn-atcm', '--help']\n"
            "from exudyn_atcm.cli import main\n"
            "with contextlib.redirect_stdout(io.StringIO()):\n"
            "    try:\n        main()\n    except SystemExit as exc:\n        assert exc.code in (0, None), exc.code")
    assert _loaded_after(code) == set()


def test_solving_an_actuator_loads_no_scipy_signal_nor_stats():
    # a static sweep and a run, at a fixed step or one chosen for an accuracy, need scipy.linalg only:
    # scipy.signal (with scipy.stats, about a second) was loaded for the step choice's one filter
    code = ("import warnings; warnings.simplefilter('ignore')\nimport exudyn_atcm as atcm\n"
            "from exudyn_atcm.mechanism.actuator import BendingActuator\n"
            "from exudyn_atcm.model.drive import PiezoDrive\nfrom exudyn_atcm.model.materials import Layer\n"
            "from exudyn_atcm.model.signals import Triangle\n"
            "act = BendingActuator(3, 29e-3, 28e-3, Layer(0.2e-3, 70e9, 1550.0), Layer(0.3e-3, 30.336e9, 5440.0), "
            "PiezoDrive(Triangle(750.0, 750.0, 0.02)), cell='rod')\n"
            "atcm.static_sweep(act, [0.0, 500.0, 1000.0])\natcm.simulate(act, 0.02, step=1e-3)\n"
            "assert 'step_choice' in atcm.simulate(act, 0.02, accuracy=1e-2).info")
    loaded = _loaded_after(code)
    assert "scipy.linalg" in loaded  # the probe sees what the solve does load
    assert not loaded & {"scipy.signal", "scipy.stats", "matplotlib"}


def test_loading_every_case_and_plot_module_loads_no_matplotlib_nor_scipy_signal():
    # a case run without plots (--no-plot, a study's runs) must not pay for matplotlib (~0.5 s): the case
    # files import their plot functions at the top, and the plot modules import matplotlib where a figure is made
    from pathlib import Path

    cases = sorted(str(p) for p in (Path(__file__).resolve().parents[1] / "cases").glob("*.py") if p.name != "__init__.py")
    code = ("import importlib, importlib.util\nimport exudyn_atcm.plots as plots\n"
            "for name in plots.__all__: getattr(plots, name)\n"
            f"for i, path in enumerate({cases!r}):\n"
            "    spec = importlib.util.spec_from_file_location(f'case_{i}', path)\n"
            "    spec.loader.exec_module(importlib.util.module_from_spec(spec))")
    loaded = _loaded_after(code)
    assert not loaded & {"matplotlib", "matplotlib.figure", "matplotlib.pyplot", "scipy.signal", "scipy.stats"}


def test_probe_sees_heavy_modules_when_they_are_loaded():
    # the probe itself can fail: a fit module that needs scipy.optimize, and a figure, load them
    code = ("import numpy as np\nfrom exudyn_atcm.hysteresis.loop_identification import isotonic\n"
            "isotonic(np.array([1.0, 0.0]))\nfrom exudyn_atcm.plots import new_figure\nnew_figure()")
    loaded = _loaded_after(code)
    assert {"scipy.optimize", "matplotlib.figure"} <= loaded


@pytest.mark.parametrize("module", ["exudyn_atcm", "exudyn_atcm.plots", "exudyn_atcm.hysteresis", "exudyn_atcm.io"])
def test_public_names_still_resolve(module):
    # every name in __all__ still resolves from the package face, lazily loaded ones included
    code = (f"import importlib\nm = importlib.import_module({module!r})\n"
            "missing = [n for n in m.__all__ if not hasattr(m, n)]\nassert not missing, missing\n"
            f"exec('from {module} import ' + ', '.join(m.__all__))")
    subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True)


def test_lazy_plots_name_is_the_submodules_object():
    import exudyn_atcm.plots as plots
    from exudyn_atcm.plots import result, style

    assert plots.new_figure is style.new_figure
    assert plots.plot_actuator_time_series is result.plot_time_series
    with pytest.raises(AttributeError, match="no attribute 'not_a_plot'"):
        _ = plots.not_a_plot
