"""Error messages show NumPy numbers as numbers: ``got -1.0``, not ``got np.float64(-1.0)`` (NumPy 2's repr).

Values from ``np.arange``, ``np.linspace`` or an array's element are NumPy scalars; the messages of the
package's checks quoted them with ``repr``.  Reference: the Python number the NumPy scalar holds.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

import exudyn_atcm as atcm
from exudyn_atcm._checks import shown
from exudyn_atcm.hysteresis import EverettPreisach
from exudyn_atcm.model import Triangle

PACKAGE = Path(atcm.__file__).resolve().parent


@pytest.mark.parametrize("value, text", [(np.float64(-1.0), "-1.0"), (np.int64(2), "2"), (np.float32(0.5), "0.5"),
                                         ((np.float64(5.0), np.float64(2.0)), "(5.0, 2.0)"), ("a", "'a'"),
                                         ([np.int64(1), 2], "[1, 2]"), (np.bool_(True), "True")])
def test_shown_writes_numpy_scalars_as_python_numbers(value, text):
    assert shown(value) == text


def test_the_audits_messages_show_numbers():
    cfc = atcm.Layer(0.2e-3, 70e9, 1550.0)
    with pytest.raises(ValueError, match=r"thickness must be > 0, got -0\.0002$"):
        atcm.Layer(np.float64(-2e-4), 70e9, 1550.0)
    with pytest.raises(ValueError, match=r"period must be > 0, got 0\.0$"):
        Triangle(750.0, 750.0, np.float64(0.0))
    bender = atcm.Bender("b", width=10e-3, passive=cfc, active=cfc, length=0.03, n_cells=2, cell="rigid",
                         drive=atcm.PiezoDrive(0.0))
    with pytest.raises(ValueError, match=r"t_end must be > 0, got -1\.0$"):
        atcm.simulate(atcm.Mechanism("m").add(bender).ground(bender.base), np.float64(-1.0))
    u = np.linspace(0.0, 1.0, 50)
    with pytest.raises(ValueError, match=r"got 20\.0") as caught:
        EverettPreisach.fit(u, u, np.float64(20.0))
    assert "np." not in str(caught.value)


def test_no_message_quotes_a_value_with_a_bare_repr():
    """A guard for new messages: ``got {value!r}`` writes NumPy scalars as ``np.float64(...)``; use ``shown``.
    (The case layer and the start-up modules, which do not import NumPy, have their own ``_shown`` or need none.)"""
    bare = re.compile(r"got \{[a-z_][a-z_0-9]*!r\}")
    offenders = [f"{path.relative_to(PACKAGE)}:{n}" for path in PACKAGE.rglob("*.py")
                 if path.relative_to(PACKAGE).parts[0] != "casework" and path.name not in ("cli.py", "command.py", "lazy_names.py")
                 for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1) if bare.search(line)]
    assert not offenders, offenders
