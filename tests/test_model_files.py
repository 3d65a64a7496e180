"""Saved hysteresis models (issue 28, part 6): ``model.save(path)`` / ``load_model(path)``.

The truth of a round trip is the saved model itself: the loaded model must be the same class with
bit for bit the same parameters, metadata and outputs (compared as bytes, not to a tolerance) on
long random inputs that reverse thousands of times and leave the models' ranges.  The new-family
test checks its loaded operator against a plain play operator written in the test.
"""

from __future__ import annotations

import json
import os
import re
import textwrap
from pathlib import Path

import numpy as np
import pytest

import exudyn_atcm
from exudyn_atcm.hysteresis import (ContinuousPreisach, DiscretePreisach, EverettPreisach, HysteresisOperator,
                                    ModelFileError, PrandtlIshlinskii, load_model, register_model_kind, save_model)
from exudyn_atcm.hysteresis.bisection import BisectionInverse
from exudyn_atcm.hysteresis.creep import Creep, CreepHysteresis
from exudyn_atcm.hysteresis.dynamics import LagSum, RateLag, WithDynamics
from exudyn_atcm.hysteresis.inverse import ShiftedPIInverse
from exudyn_atcm.hysteresis.model_files import model_text
from exudyn_atcm.hysteresis.model_format import FORMAT_NAME, FORMAT_VERSION, model_from_document
from exudyn_atcm.hysteresis.model_registry import FLOAT, registered_kinds
from exudyn_atcm.hysteresis.relay_gram import relay_grid

RNG = np.random.default_rng(28)
N = 20_000


def wander(n: int = N, low: float = -600.0, high: float = 1600.0) -> np.ndarray:
    """A random input: a random walk plus random jumps, reversing thousands of times, beyond [-500, 1500]."""
    steps = RNG.normal(0.0, 40.0, n)
    jumps = np.where(RNG.random(n) < 0.01, RNG.uniform(low, high, n), np.nan)
    u = np.empty(n)
    value = 500.0
    for k in range(n):
        value = jumps[k] if np.isfinite(jumps[k]) else min(max(value + steps[k], low), high)
        u[k] = value
    return u


U = wander()
T = np.cumsum(RNG.uniform(1e-4, 3e-3, N))


def same_bits(a, b) -> None:
    a, b = np.asarray(a), np.asarray(b)
    assert a.dtype == b.dtype and a.shape == b.shape
    assert a.tobytes() == b.tobytes()


def random_everett(levels: int = 14) -> EverettPreisach:
    alpha, beta, _ = relay_grid(-500.0, 1500.0, levels)
    return EverettPreisach(np.linspace(-500.0, 1500.0, levels + 1), alpha, beta,
                           RNG.uniform(0.0, 1e-4, alpha.size) / 7.0, offset=-3.1e-4 / 3.0)


def random_pi() -> PrandtlIshlinskii:
    radii = np.sort(RNG.uniform(0.0, 900.0, 12))
    return PrandtlIshlinskii(radii, RNG.uniform(0.0, 2e-7, 12) / 3.0, 1.0e-7 / 3.0, offset=2e-5 / 7.0,
                             input_offset=-123.456789)


def scattered_relays(monotone: bool):
    n = 300
    alpha = RNG.uniform(-500.0, 1500.0, n)
    beta = alpha - RNG.uniform(0.0, 800.0, n)
    if monotone:  # sorted by alpha, beta non-decreasing: the "prefix" kernel
        alpha, beta = np.sort(alpha), np.sort(beta)
        beta = np.minimum(beta, alpha)
    return alpha, beta, RNG.uniform(0.0, 1e-5, n) / 3.0


def operators() -> dict[str, HysteresisOperator]:
    """One of every rate-independent family (and every DiscretePreisach kernel)."""
    return {
        "continuous": ContinuousPreisach(-500.0, 1500.0, -1.9e-4 / 3.0, 1.1e-3 / 7.0, 1.0 + 1.0 / 3.0, 2.0 + 2.0 / 7.0),
        "discrete_prefix": DiscretePreisach(*scattered_relays(True), offset=1e-5 / 3.0),
        "discrete_table": DiscretePreisach(*scattered_relays(False), offset=-1e-5 / 3.0),
        "discrete_dominance": DiscretePreisach(*scattered_relays(False), max_table_entries=0),
        "everett": random_everett(),
        "prandtl_ishlinskii": random_pi(),
    }


@pytest.fixture(scope="module")
def ops():
    return operators()


@pytest.mark.parametrize("name", list(operators()))
def test_every_operator_round_trips_bit_for_bit(ops, name, tmp_path):
    model = ops[name]
    path = model.save(tmp_path / f"{name}.json")
    loaded = load_model(path)
    assert type(loaded) is type(model)
    for attr in ("alpha", "beta", "weights", "edges", "radii", "offset", "input_offset", "p0", "u_min", "u_max",
                 "y_min", "y_max", "r1", "r2", "kernel", "max_table_entries"):
        if hasattr(model, attr):
            same_bits(getattr(loaded, attr), getattr(model, attr))
    same_bits(loaded.apply(U), model.apply(U))
    if name.startswith("discrete"):  # the kernel (and so the rounding of every step) is the saved one
        assert loaded.kernel == model.kernel == name.split("_")[1]


def test_the_memory_is_not_saved_a_loaded_model_starts_reset(ops, tmp_path):
    model = ops["everett"]
    for u in (1400.0, -100.0, 900.0, 200.0):
        model.commit(u)
    assert len(model.reversal_points) == 3
    loaded = load_model(model.save(tmp_path / "m.json"))
    assert loaded.reversal_points == [] and loaded.output == model.offset  # all relays off
    same_bits(loaded.apply(U), model.apply(U))  # apply runs from the reset state for both
    model.reset()


def test_wrappers_and_lag_blocks_round_trip_bit_for_bit(ops, tmp_path):
    creep = Creep([0.05, 0.7, 5.0], [0.04 / 3.0, 0.03, 0.02 / 7.0])
    lag = RateLag(4e-3 / 3.0)
    h = ops["prandtl_ishlinskii"].apply(U)
    for i, block in enumerate([creep, lag, LagSum(0.25, [0.01, 0.3], [0.5 / 3.0, 0.25])]):
        loaded = load_model(block.save(tmp_path / f"block{i}.json"))
        assert type(loaded) is type(block)
        same_bits(loaded.response(h, T), block.response(h, T))
    for j, wrapped in enumerate([WithDynamics(ops["everett"], creep, lag), WithDynamics(ops["prandtl_ishlinskii"], creep),
                                 WithDynamics(ops["continuous"], lag=lag)]):
        loaded = load_model(wrapped.save(tmp_path / f"with_dynamics{j}.json"))
        assert type(loaded.operator) is type(wrapped.operator)
        assert (loaded.creep is None) == (wrapped.creep is None) and (loaded.lag is None) == (wrapped.lag is None)
        same_bits(loaded.apply(U, T), wrapped.apply(U, T))
    offline = CreepHysteresis(ops["discrete_table"], creep)
    loaded = load_model(offline.save(tmp_path / "creep_hysteresis.json"))
    same_bits(loaded.apply(U, T), offline.apply(U, T))


def test_inverses_are_saved_as_their_forward_model_and_settings(ops, tmp_path):
    forward = ops["everett"]
    inverse = BisectionInverse(forward, input_range=(-450.0, 1450.0), tolerance=1e-7)
    wanted = forward.apply(np.clip(U[:3000], -400.0, 1400.0))  # 50 V inside the range: nothing is clipped
    loaded = load_model(inverse.save(tmp_path / "bisection.json"))
    assert (loaded.u_lo, loaded.u_hi, loaded.tolerance) == (-450.0, 1450.0, 1e-7)
    same_bits(loaded.apply(wanted), inverse.apply(wanted))
    pi = ops["prandtl_ishlinskii"]
    shifted = ShiftedPIInverse(pi)
    y = pi.apply(U)
    loaded = load_model(shifted.save(tmp_path / "shifted.json"))
    same_bits(loaded.apply(y), shifted.apply(y))
    same_bits(loaded.model.apply(U), y)  # the forward model is in the file


def test_metadata_round_trips_on_the_model_and_inside_a_wrapper(tmp_path):
    # a fitted model, with the metadata the fits record set by hand (the fits' contract)
    truth = random_everett(20)
    u = np.concatenate([np.linspace(-500.0, 1500.0, 400), np.linspace(1500.0, -500.0, 400),
                        np.linspace(-500.0, 900.0, 300), np.linspace(900.0, 100.0, 200), np.linspace(100.0, 1500.0, 300)])
    model, _ = EverettPreisach.fit(u, truth.apply(u), 10)
    model.output_quantity, model.output_unit = "displacement", "m"
    model.fitted_range = (-500.0, 1500.0)
    model.fit_info = {"method": "EverettPreisach.fit", "n_levels": np.int64(10), "smoothing": 1e-3,
                      "grid": np.array([-500.0, 1500.0]), "settings": {"prior": "smooth", "cv": None, "ok": np.bool_(True)}}
    loaded = load_model(model.save(tmp_path / "fitted.json"))
    assert loaded.output_quantity == "displacement" and loaded.output_unit == "m"
    assert loaded.fitted_range == (-500.0, 1500.0)
    assert loaded.fit_info == {"method": "EverettPreisach.fit", "n_levels": 10, "smoothing": 1e-3,
                               "grid": [-500.0, 1500.0], "settings": {"prior": "smooth", "cv": None, "ok": True}}
    inside = np.clip(U, -500.0, 1500.0)  # a fitted model warns beyond its fitted range
    same_bits(loaded.apply(inside), model.apply(inside))
    wrapped = load_model(WithDynamics(model, Creep([0.1], [0.05])).save(tmp_path / "wrapped.json"))
    assert wrapped.output_quantity == "displacement"  # the wrapper's own, taken from its operator
    assert wrapped.operator.fitted_range == (-500.0, 1500.0) and wrapped.operator.fit_info == loaded.fit_info
    # a model without metadata loads with the class defaults, not instance attributes
    plain = load_model(random_pi().save(tmp_path / "plain.json"))
    assert "output_unit" not in vars(plain) and "fit_info" not in vars(plain) and plain.output_quantity is None


def test_the_file_is_strict_json_with_its_format_and_versions(ops, tmp_path):
    model = ops["discrete_table"]
    text = model_text(model)
    assert text == model_text(model)  # the same model gives the same bytes (no time stamp)
    document = json.loads(text, parse_constant=lambda name: pytest.fail(f"non-strict JSON constant {name}"))
    assert document["format"] == FORMAT_NAME == "exudyn_atcm.hysteresis_model"
    assert document["format_version"] == FORMAT_VERSION == 1
    assert document["package_version"] == exudyn_atcm.__version__
    assert document["model"]["kind"] == "discrete_preisach"
    assert list(document["model"]["params"]) == ["alpha", "beta", "weights", "offset", "max_table_entries"]
    assert document["model"]["metadata"]["input_range"] == [float(model.beta.min()), float(model.alpha.max())]
    path = save_model(model, tmp_path / "m.json")
    assert path.read_text(encoding="utf-8") == text
    # a save replaces an existing file; both entry points load it
    random_everett().save(path)
    assert type(exudyn_atcm.load_model(path)) is EverettPreisach


def test_a_failed_save_leaves_the_existing_file_whole(ops, tmp_path):
    path = ops["continuous"].save(tmp_path / "m.json")
    before = path.read_bytes()
    bad = random_pi()
    bad.fit_info = {"settings": {"rms": float("nan")}}
    with pytest.raises(ValueError, match=r"model\.metadata\.fit_info\.settings\.rms: nan is not finite"):
        bad.save(path)
    bad.fit_info = {1: "x"}
    with pytest.raises(ValueError, match=r"fit_info: its keys must be strings, got 1"):
        bad.save(path)
    bad.fit_info = {"when": object()}
    with pytest.raises(ValueError, match=r"fit_info\.when: 'object' values are not JSON data"):
        bad.save(path)
    assert path.read_bytes() == before
    assert sorted(os.listdir(tmp_path)) == ["m.json"]  # no temporary file left behind
    with pytest.raises(ValueError, match="path must be in an existing directory"):
        ops["continuous"].save(tmp_path / "missing" / "m.json")


def test_an_unregistered_class_is_refused_by_name(tmp_path):
    class MyPI(PrandtlIshlinskii):
        pass

    with pytest.raises(TypeError, match=r"cannot save a MyPI \(model\): no saved-model kind is registered for "
                                        r".*MyPI; registered: bisection_inverse, continuous_preisach"):
        MyPI([0.1], [0.2], 0.5).save(tmp_path / "x.json")
    assert not (tmp_path / "x.json").exists()


class Backlash(HysteresisOperator):
    """A new family for the registry test: one play of half width ``radius`` times ``gain``."""

    def __init__(self, radius: float, gain: float) -> None:
        self.radius, self.gain = float(radius), float(gain)
        self.reset()

    def evaluate(self, u):
        return self.gain * max(u - self.radius, min(u + self.radius, self._z))

    def commit(self, u):
        self._z = max(u - self.radius, min(u + self.radius, self._z))
        return self.gain * self._z

    def reset(self):
        self._z = 0.0

    def checkpoint(self):
        return self._z

    def restore(self, snapshot):
        self._z = snapshot

    @property
    def output(self):
        return self.gain * self._z


def test_a_new_family_registers_with_one_call(tmp_path):
    register_model_kind("test_backlash", Backlash, {"radius": FLOAT, "gain": FLOAT})
    assert registered_kinds()["test_backlash"] is Backlash
    model = Backlash(100.0 / 3.0, 2e-6 / 7.0)
    loaded = load_model(model.save(tmp_path / "b.json"))
    # independent reference: the play recursion written out here
    z, expected = 0.0, []
    for u in U[:2000]:
        z = min(max(z, u - 100.0 / 3.0), u + 100.0 / 3.0)
        expected.append(2e-6 / 7.0 * z)
    np.testing.assert_allclose(loaded.apply(U[:2000]), expected, rtol=1e-15, atol=0)
    # inside a wrapper too: the nested operator may be of any registered kind
    wrapped = load_model(WithDynamics(model, lag=RateLag(0.01)).save(tmp_path / "w.json"))
    assert type(wrapped.operator) is Backlash
    with pytest.raises(ValueError, match="name 'everett_preisach' is registered already"):
        register_model_kind("everett_preisach", Backlash, {})
    with pytest.raises(ValueError, match="must be lower case letters"):
        register_model_kind("Test-Backlash", Backlash, {})
    with pytest.raises(ValueError, match=r"parameters\['radius'\] must be a ParameterType"):
        register_model_kind("test_backlash", Backlash, {"radius": float})


# ----------------------------------------------------------------------------- refusals on load
def document(model=None) -> dict:
    return json.loads(model_text(model if model is not None else PrandtlIshlinskii([0.1, 0.3], [0.2, 0.4], 0.5)))


INF = "__overflowing_number__"  # written as 1e999, which JSON parsers read as infinity


def write(tmp_path, content) -> str:
    path = tmp_path / "model.json"
    text = content if isinstance(content, str) else json.dumps(content).replace(f'"{INF}"', "1e999")
    path.write_text(text, encoding="utf-8")
    return str(path)


def edited(change, model=None) -> dict:
    doc = document(model)
    change(doc)
    return doc


@pytest.mark.parametrize("content, message", [
    ("{not json", r"is not a saved model: not JSON \(line 1 column 2"),
    ('{"format": NaN}', "holds NaN, which strict JSON and a saved model do not allow"),
    ('{"a": 1, "a": 2}', "the field 'a' appears twice"),
    ("[1, 2]", "must be a JSON object with the fields format, format_version, package_version, model, got a list"),
    ('{"kind": "everett_preisach"}', "is not a saved exudyn_atcm hysteresis model: it has no 'format' field"),
    ({"format": "exudyn_atcm.result"}, r"format must be 'exudyn_atcm.hysteresis_model' \(a saved exudyn_atcm "
                                       r"hysteresis model\), got 'exudyn_atcm.result'"),
])
def test_what_is_not_a_saved_model_is_refused(tmp_path, content, message):
    path = write(tmp_path, content)
    with pytest.raises(ModelFileError, match=f"^{path}: .*{message}"):
        load_model(path)


def _set(doc, dotted, value):
    *parents, last = dotted.split(".")
    for key in parents:
        doc = doc[key]
    if value is KeyError:
        del doc[last]
    else:
        doc[last] = value


@pytest.mark.parametrize("field, value, message", [
    ("format_version", 2, r"format_version is 2, written by exudyn_atcm '" + re.escape(exudyn_atcm.__version__) + r"'; this exudyn_atcm \(.*\) reads "
                          r"format versions up to 1: upgrade exudyn_atcm"),
    ("format_version", "1", r"format_version must be an integer >= 1, got '1'"),
    ("package_version", KeyError, r"package_version is missing \(required: format, format_version, package_version, "
                                  r"model\)"),
    ("saved_at", "today", r"saved_at is not a field of a saved model here"),
    ("model.kind", "exudyn_atcm.hysteresis.PrandtlIshlinskii", r"model\.kind is an unknown model kind "
                                                               r"'exudyn_atcm\.hysteresis\.PrandtlIshlinskii'"),
    ("model.kind", "prandtl_ishlinski", r"model\.kind is an unknown model kind 'prandtl_ishlinski'; this exudyn_atcm \(.*\) knows "
                                            r"bisection_inverse, .* \(did you mean 'prandtl_ishlinskii'"),
    ("model.params.p0", KeyError, r"model\.params\.p0 is missing \(required: radii, weights, p0, offset, input_offset\)"),
    ("model.params.gain", 1.0, r"model\.params\.gain is not a field of a saved model here"),
    ("model.params.p0", "0.5", r"model\.params\.p0 must be a finite number, got '0\.5'"),
    ("model.params.p0", True, r"model\.params\.p0 must be a finite number, got true"),
    ("model.params.p0", INF, r"model\.params\.p0 must be a finite number, got inf"),
    ("model.params.radii", [0.1, None], r"model\.params\.radii\[1\] must be a finite number, got null"),
    ("model.params.radii", 0.1, r"model\.params\.radii must be a list of finite numbers, got 0\.1"),
    ("model.params.radii", [0.3, 0.1], r"model\.params do not make a PrandtlIshlinskii \(kind 'prandtl_ishlinskii'\): "
                                       r"radii must be strictly increasing"),
    ("model.metadata", KeyError, r"model\.metadata is missing"),
    ("model.metadata.output_unit", None, r"model\.metadata\.output_unit must be a string"),
    ("model.metadata.fitted_range", [2.0, 1.0], r"model\.metadata\.fitted_range must have high >= low"),
    ("model.metadata.fitted_range", [1.0], r"model\.metadata\.fitted_range must be a list of two finite numbers"),
    ("model.metadata.fit_info", {"rms": INF}, r"model\.metadata\.fit_info\.rms must be finite, got inf"),
])
def test_a_bad_field_is_refused_naming_it(tmp_path, field, value, message):
    path = write(tmp_path, edited(lambda doc: _set(doc, field, value)))
    with pytest.raises(ModelFileError, match=f"^{path}: {message}"):
        load_model(path)


def test_nested_fields_are_named_with_their_path(tmp_path):
    model = WithDynamics(random_everett(), Creep([0.1], [0.05]), RateLag(0.01))
    doc = edited(lambda d: _set(d, "model.params.operator.params.weights", [-1.0] * 105), model)
    with pytest.raises(ModelFileError, match=r"model\.params\.operator\.params do not make a EverettPreisach .*"
                                             r"weights must be >= 0"):
        load_model(write(tmp_path, doc))
    doc = edited(lambda d: _set(d, "model.params.creep", d["model"]["params"]["lag"]), model)
    with pytest.raises(ModelFileError, match=r"model\.params\.creep\.kind must be 'creep' here, got 'rate_lag'"):
        load_model(write(tmp_path, doc))
    doc = edited(lambda d: _set(d, "model.params.operator", d["model"]["params"]["creep"]), model)
    with pytest.raises(ModelFileError, match=r"model\.params do not make a WithDynamics .*operator must be a "
                                             r"rate-independent hysteresis operator, got Creep"):
        load_model(write(tmp_path, doc))
    doc = edited(lambda d: _set(d, "model.params.lag", None), model)  # optional: a creep alone
    assert load_model(write(tmp_path, doc)).lag is None
    with pytest.raises(ModelFileError, match=r"model\.params\.max_table_entries must be an integer, got 1\.0"):
        model_from_document(edited(lambda d: _set(d, "model.params.max_table_entries", 1.0),
                                   DiscretePreisach([1.0], [0.0], [1.0])))


def test_missing_files_and_non_text_are_refused(tmp_path):
    with pytest.raises(FileNotFoundError, match="no saved model at .*nowhere.json"):
        load_model(tmp_path / "nowhere.json")
    (tmp_path / "model.json").write_bytes(b"\xff\xfe{}")
    with pytest.raises(ModelFileError, match="not UTF-8 text"):
        load_model(tmp_path / "model.json")
    with pytest.raises(ModelFileError, match="is a directory"):
        load_model(tmp_path)


# ----------------------------------------------------------------------------- the documentation
DOCS = Path(__file__).resolve().parents[1] / "docs" / "identification.rst"


def saved_model_section() -> str:
    text = DOCS.read_text(encoding="utf-8")
    start = text.index("Saving and loading a model\n---")
    end = text.index("\n---", start + 60)  # the next section's underline
    return text[start:end]


def test_the_documented_example_file_is_what_save_writes(tmp_path):
    section = saved_model_section()
    example = json.loads(python_or_json_blocks(section, "json")[0])
    model = ContinuousPreisach(-500.0, 1500.0, -2e-06, 4.4e-05, 1.6, 2.2)
    model.output_quantity, model.output_unit, model.fitted_range = "displacement", "m", (-500.0, 1500.0)
    model.fit_info = {"method": "ContinuousPreisach.fit", "samples": 3751, "fitted_samples": 3751}
    written = json.loads(model_text(model))
    assert written.pop("package_version") == exudyn_atcm.__version__
    assert example.pop("package_version") == "0.3.0"
    assert example == written
    loaded = model_from_document({**example, "package_version": "0.3.0"}, "docs")
    inside = np.clip(U, -500.0, 1500.0)  # a fitted model warns beyond its fitted range
    same_bits(loaded.apply(inside), model.apply(inside))


def test_the_documented_save_and_load_runs(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    first = python_or_json_blocks(saved_model_section(), "python")[0]
    exec(compile(first, "docs/identification.rst", "exec"), {"__name__": "__docs__"})  # noqa: S102
    assert (tmp_path / "my_actuator_model.json").is_file()


def python_or_json_blocks(section: str, language: str) -> list[str]:
    blocks = re.findall(rf"^\.\. code-block:: {language}\n\n((?:    [^\n]*\n|\n)+)", section, re.MULTILINE)
    return [textwrap.dedent(block) for block in blocks]
