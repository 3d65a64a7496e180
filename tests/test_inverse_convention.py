"""One inverse convention (issue 30, part 6): ``inverse()`` on every operator class returns an operator.

The independent check of each inverse is the forward operator itself: the inverse applied to the
forward output gives back the input (or, for a staircase that is flat between its steps, an input
with the same output), to the accuracy the inverse documents.
"""

from __future__ import annotations

import abc
import importlib
import pkgutil

import numpy as np
import pytest

import exudyn_atcm.hysteresis as hysteresis
from exudyn_atcm.errors import AtcmDeprecationWarning
from exudyn_atcm.hysteresis import (ContinuousPreisach, DiscretePreisach, EverettPreisach, HysteresisOperator,
                                    PrandtlIshlinskii, inverse_operator)
from exudyn_atcm.hysteresis.bisection import BisectionInverse, default_input_range
from exudyn_atcm.hysteresis.dynamics import RateLag, WithDynamics
from exudyn_atcm.hysteresis.dynamics_inverse import DynamicsInverse
from exudyn_atcm.hysteresis.identification import relay_grid
from exudyn_atcm.hysteresis.creep import Creep
from exudyn_atcm.hysteresis.inverse import ShiftedPIInverse

from test_identification import corners_path

U = corners_path([-1.0, 0.8, -0.6, 0.9, 0.1, 0.5, -0.95, 0.7], 0.01)  # inside every example's input range
T = np.arange(U.size) * 2e-4  # 50 samples per 0.01 s, for the time-dependent operators [s]


def continuous():
    return ContinuousPreisach(-1.0, 1.0, 0.0, 1.0, 1.6, 2.6)


def pi():
    return PrandtlIshlinskii([0.1, 0.3, 0.6], [0.5, 0.3, 0.2], 0.4, offset=0.2, input_offset=-0.1)


def everett():
    alpha, beta, _ = relay_grid(-1.0, 1.0, 8)
    return EverettPreisach(np.linspace(-1.0, 1.0, 9), alpha, beta, np.exp(-(alpha - beta)) / alpha.size)


def discrete():
    alpha = np.array([-0.83, -0.55, -0.31, -0.07, 0.18, 0.41, 0.66, 0.93])
    return DiscretePreisach(alpha, alpha - 0.12, np.full(8, 0.125))


def with_dynamics():
    # creep (feed-through: the output may jump) after a PI operator
    return WithDynamics(pi(), creep=Creep([0.003, 0.03], [0.05, 0.1]))


# the forward input and the accuracy the inverse documents, per class (every concrete operator class
# of the package: test_every_operator_class_has_an_example checks the list against the package)
EXAMPLES = {
    # Preisach models are flat wherever no relay switches (e.g. the paper's power law after a reversal until
    # the input has come back far enough; a staircase between its steps): the check is the output of the
    # returned input, exactly the wanted one for the staircase's reachable steps, else to the bisection's
    # 1e-9 of the input range times the slope (measured 1e-9 of the output range)
    ContinuousPreisach: (continuous, U, None),
    EverettPreisach: (everett, U, None),
    DiscretePreisach: (discrete, U, None),
    PrandtlIshlinskii: (pi, U, 1e-12),  # analytic: rounding only
    ShiftedPIInverse: (lambda: pi().inverse(), pi().apply(U), 1e-12),
    # its input is an output of the forward model; its inverse, the forward model, gives it back to the
    # bisection's accuracy (above; measured 1e-9 of the range)
    BisectionInverse: (lambda: continuous().inverse(), continuous().apply(U), 1e-8),
    # exact step inverse of the lags (rounding) then the analytic PI inverse
    WithDynamics: (with_dynamics, U, 1e-10),
    DynamicsInverse: (lambda: with_dynamics().inverse(), with_dynamics().apply(U, T), 1e-10),
}

INTERNAL = {"CellFractions"}  # the vector-valued helper of the grid fits (relay_gram), not a model


def _concrete_operator_classes():
    for info in pkgutil.iter_modules(hysteresis.__path__):
        importlib.import_module(f"exudyn_atcm.hysteresis.{info.name}")
    found, todo = set(), [HysteresisOperator]
    while todo:
        cls = todo.pop()
        todo.extend(cls.__subclasses__())
        if (cls.__module__.startswith("exudyn_atcm.") and not abc.ABC in cls.__bases__
                and not getattr(cls, "__abstractmethods__", None) and cls.__name__ not in INTERNAL):
            found.add(cls)
    return found


def test_every_operator_class_has_an_example():
    assert _concrete_operator_classes() == set(EXAMPLES)


def _run(op, x):
    return op.apply(x, T[: len(x)]) if getattr(op, "time_dependent", False) else op.apply(x)


@pytest.mark.parametrize("cls", list(EXAMPLES), ids=lambda c: c.__name__)
def test_inverse_is_an_operator_that_undoes_the_operator(cls):
    make, x, accuracy = EXAMPLES[cls]
    op = make()
    assert type(op) is cls
    inverse = op.inverse()
    assert isinstance(inverse, HysteresisOperator)
    assert type(inverse_operator(op)) is type(inverse)  # the function is the method
    y = _run(op, x)
    back = _run(inverse, y)
    if accuracy is None:  # flat parts: the returned inputs give the same outputs
        np.testing.assert_allclose(_run(op, back), y, rtol=0, atol=1e-8 * np.ptp(y))
        assert np.ptp(y) > 0.5
        if cls is DiscretePreisach:  # its step values exactly
            np.testing.assert_array_equal(_run(op, back), y)
    else:
        np.testing.assert_allclose(back, x, rtol=0, atol=accuracy * np.ptp(x))
        if cls is not BisectionInverse:  # its outputs (inputs of a Preisach model) are not unique where that is flat
            np.testing.assert_allclose(_run(op, back), y, rtol=0, atol=10 * accuracy * np.ptp(y))
    # the inverse of the inverse undoes the inverse: it is the forward model again
    again = inverse.inverse()
    np.testing.assert_allclose(_run(again, x), y, rtol=0, atol=1e-12 * np.ptp(y))


def test_inverse_does_not_guess_the_range_from_attribute_names():
    # a monotone operator with the old guessed attributes (u_min, u_max) but no declared range is refused,
    # naming input_range; declared ranges are used
    class Linear(HysteresisOperator):
        u_min, u_max = -1.0, 1.0

        def __init__(self):
            self._y = 0.0

        def evaluate(self, u):
            return 2.0 * u

        def commit(self, u):
            self._y = 2.0 * u
            return self._y

        def reset(self):
            self._y = 0.0

        def checkpoint(self):
            return self._y

        def restore(self, snapshot):
            self._y = snapshot

        @property
        def output(self):
            return self._y

    with pytest.raises(ValueError, match="input_range must be given for a Linear: it declares neither"):
        inverse_operator(Linear())
    with pytest.raises(NotImplementedError, match="inverse_operator"):
        Linear().inverse()
    fitted = Linear().set_fit_metadata((-0.5, 2.0), {"method": "test"})
    assert default_input_range(fitted) == (-0.5, 2.0)
    inverse = inverse_operator(fitted)
    assert isinstance(inverse, BisectionInverse) and inverse.commit(3.0) == pytest.approx(1.5, abs=1e-8)


def test_pi_inverse_with_an_input_range_clips_with_a_warning():
    from exudyn_atcm.errors import OutOfReachWarning

    inverse = pi().inverse(input_range=(-1.0, 1.0))
    assert isinstance(inverse, BisectionInverse)
    top = pi().apply([1.0])[-1]
    with pytest.warns(OutOfReachWarning, match="clipped"):
        assert inverse.commit(top + 0.5) == 1.0


def test_with_dynamics_inverse_apply_is_a_deprecated_shim_with_the_same_inputs():
    model = with_dynamics()
    y = model.apply(U, T)
    with pytest.warns(AtcmDeprecationWarning, match=r"inverse\(\)\.apply\(y, t\)"):
        old = model.inverse_apply(y, T, inverse_operator(model.operator))
    # the same exact lag inverse, step by step instead of in one pass: rounding differences only
    np.testing.assert_allclose(model.inverse().apply(y, T), old, rtol=0, atol=1e-12 * np.ptp(U))


def test_creep_hysteresis_inverse_and_the_deprecated_inverse_apply(tmp_path):
    from exudyn_atcm.hysteresis import load_model
    from exudyn_atcm.hysteresis.creep import CreepHysteresis, CreepHysteresisInverse

    model = CreepHysteresis(pi(), Creep([0.003, 0.03], [0.05, 0.1]))
    y = model.apply(U, T)
    inverse = model.inverse()
    assert isinstance(inverse, CreepHysteresisInverse)
    # exact creep inverse, then the analytic PI inverse: rounding only
    np.testing.assert_allclose(inverse.apply(y, T), U, rtol=0, atol=1e-10 * np.ptp(U))
    np.testing.assert_allclose(inverse.inverse().apply(U, T), y, rtol=0, atol=0)
    with pytest.warns(AtcmDeprecationWarning, match=r"inverse\(\)\.apply\(y, t\)"):
        old = model.inverse_apply(y, T, inverse_operator(model.hysteresis))
    np.testing.assert_array_equal(inverse.apply(y, T), old)
    again = load_model(inverse.save(tmp_path / "inverse.json"))
    np.testing.assert_array_equal(again.apply(y, T), old)


def test_dynamics_inverse_is_saved_with_its_range(tmp_path):
    from exudyn_atcm.hysteresis import load_model

    inverse = with_dynamics().inverse(input_range=(-1.0, 1.0))
    again = load_model(inverse.save(tmp_path / "inverse.json"))
    assert type(again) is DynamicsInverse and again.requested_range == (-1.0, 1.0)
    y = with_dynamics().apply(U, T)
    np.testing.assert_array_equal(again.apply(y, T), inverse.apply(y, T))
