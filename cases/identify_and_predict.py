"""Identify a hysteresis model on one part of a measured record and predict the rest.

The record (by default ``cases/data/preisach_record.csv``: the synthetic record of a known
non-uniform Preisach model with major and minor loops plus 0.4 µm noise, see its header) is
read with :func:`exudyn_atcm.io.measurements.read_record` and split by time: the part before
``split_fraction`` of the duration is fitted, the rest is held out and predicted (the model
runs over the whole record, so the held-out part starts from the memory the fitted part left).
A record whose amplitude grows (the usual identification excitation) has held-out inputs beyond
the fitted part's: ``split=cycles`` holds out interleaved whole cycles instead, ``split=auto``
chooses (:func:`exudyn_atcm.hysteresis.identify`).  A family the record cannot identify (Eq. 12
needs a whole major loop) is left out of the comparison, with the reason in the notes
(``not_fitted``); if the Preisach fit itself fails, the chosen family's model is the main result
(``main_model`` in the notes).

Fitted: a Preisach density on an ``n_levels`` grid by non-negative least squares (variable
gains; ``prior``: ``"pi"`` by default, as for the fits, 1.02 x the noise held out on the
shipped record where ``"smooth"`` gives 1.06), once with each weight spread over its grid cell (:meth:`EverettPreisach.fit`:
continuous output; the main result) and once as the bare relay grid
(:meth:`DiscretePreisach.fit`: staircase output); for comparison a Prandtl-Ishlinskii operator, the
paper's continuous power-law model fitted by least squares, and the equal-gain relays of
Eq. 12 (:meth:`DiscretePreisach.from_loop`, on the record's major-loop branches).

All five families are fitted on the same split by :func:`exudyn_atcm.hysteresis.identify`,
which ranks them by held-out RMS error (with parameter count, fit time, invertibility) and
chooses one; the table is printed, kept in the case JSON's notes (``model_choice``), its
predictions written as ``<case>_model_choice.csv`` and drawn in ``<case>_model_choice.png``.

Outputs: the time series (measured, predicted, error), the Preisach fit's
:class:`~exudyn_atcm.hysteresis.fit_report.FitReport` as ``<case>_fit_report.json`` (and all
four reports in the case JSON's notes), the fitted Preisach model itself as ``<case>_model.json``
(``model.save``; read it with :func:`exudyn_atcm.load_model`, or drive ``tip_tracking`` with it:
``--set model=out/identify_and_predict_model.json``; its output unit is the record's), plots of
the loop and the time series.  Key scalars:
the held-out RMS error of each model, of the best linear model, and for the shipped record
the Preisach fit's held-out RMS error divided by the known noise level.
"""

from __future__ import annotations

from pathlib import Path
from types import SimpleNamespace

import numpy as np

from exudyn_atcm import Result, preprocess, read_record
from exudyn_atcm.casework import Case, CaseOutput, Parameter, Parameters, RunContext
from exudyn_atcm.hysteresis import IdentifyOptions
from exudyn_atcm.hysteresis import (
    ContinuousPreisach,
    DiscretePreisach,
    EverettPreisach,
    PrandtlIshlinskii,
    identify,
    make_report,
    save_model,
)
from exudyn_atcm.model import REFERENCE
from exudyn_atcm.plots import AxisLabels, plot_fit, plot_fit_series, plot_model_choice

SHIPPED = Path(__file__).resolve().parent / "data" / "preisach_record.csv"

PARAMETERS = [
    Parameter("record", "", "-", "record file (empty: the shipped synthetic record cases/data/preisach_record.csv)"),
    Parameter("time_column", "time", "-", "column of the time [s]"),
    Parameter("input_column", "voltage", "-", "column of the input (voltage)"),
    Parameter("output_column", "displacement", "-", "column of the output (displacement)"),
    Parameter("split", "time", "-", "which samples are held out: time (the part after split_fraction of the duration), "
              "cycles (interleaved whole cycles: records whose amplitude grows or changes) or auto (time when the fitted "
              "part covers the held-out inputs, else cycles; exudyn_atcm.hysteresis.identify)",
              choices=("time", "cycles", "auto")),
    Parameter("split_fraction", 0.6, "-", "split=time: fraction of the duration fitted; the rest is held out", exclusive_minimum=0.0, maximum=1.0),
    Parameter("n_levels", 40, "-", "grid levels of the Preisach fit", minimum=1),
    Parameter("smoothing", 1e-3, "-", "smoothness regularisation of the Preisach fit", minimum=0.0),
    Parameter("prior", "pi", "-", "prior of the Preisach fits where the record says nothing: pi (cross-validated; "
              "the fits' default) or smooth", choices=("smooth", "pi")),
    Parameter("n_plays", 20, "-", "plays of the Prandtl-Ishlinskii fit", minimum=1),
    Parameter("n_relays_eq12", 20, "-", "relays of the equal-gain model (Eq. 12)", minimum=1),
    Parameter("trim_start", 0.0, "s", "settling time trimmed from the start", minimum=0.0),
    Parameter("decimate", 1, "-", "block-mean decimation factor", minimum=1),
]


#: The families compared, by :func:`~exudyn_atcm.hysteresis.identify`'s names: their reports' keys in the notes and
#: their held-out error's scalar.
FAMILIES = {
    "everett": ("preisach_fit", "held_out_rms_preisach"),
    "discrete": ("relay_grid_fit", "held_out_rms_relay_grid"),
    "prandtl_ishlinskii": ("prandtl_ishlinskii_fit", "held_out_rms_prandtl_ishlinskii"),
    "continuous": ("continuous_fit", "held_out_rms_continuous"),
    "equal_gain": ("equal_gain_eq12", "held_out_rms_equal_gain"),
}


def fit_families(p: Parameters, u: np.ndarray, y: np.ndarray, n_fit: int, unit: str):
    """Every family fitted to all samples (no held-out part): ``(models, reports, failures)`` by family."""
    fits = {
        "everett": lambda: EverettPreisach.fit(u, y, p.n_levels, smoothing=p.smoothing, n_fit=n_fit, output_unit=unit,
                                               prior=p.prior),
        "discrete": lambda: DiscretePreisach.fit(u, y, p.n_levels, smoothing=p.smoothing, n_fit=n_fit, output_unit=unit,
                                                 prior=p.prior),
        "prandtl_ishlinskii": lambda: PrandtlIshlinskii.fit(u, y, p.n_plays, n_fit=n_fit, output_unit=unit),
        "continuous": lambda: ContinuousPreisach.fit(u, y, n_fit=n_fit, output_unit=unit),
        "equal_gain": lambda: DiscretePreisach.from_loop(u[:n_fit], y[:n_fit], p.n_relays_eq12, reversal_tolerance=0.02,
                                                         report=True, output_unit=unit),
    }
    models, reports, failures = {}, {}, {}
    for family, fit in fits.items():
        try:
            models[family], reports[family] = fit()
        except ValueError as exc:  # a family the record cannot identify (e.g. Eq. 12 without a whole loop)
            failures[family] = str(exc)
    return models, reports, failures


def run(p: Parameters, ctx: RunContext) -> CaseOutput:
    path = Path(p.record) if p.record else SHIPPED
    record = read_record(path, time=p.time_column, input=p.input_column, output=p.output_column)
    if p.trim_start > 0.0 or p.decimate > 1:
        record = preprocess(record, trim_start=p.trim_start, decimate=p.decimate)
    t, u, y = record.time, record.input, record.output
    unit = record.units["output"]
    by_time = p.split == "time"
    n_fit = t.size if by_time and p.split_fraction == 1.0 else \
        record.split_index(t[0] + p.split_fraction * (t[-1] - t[0]))
    if not by_time and p.split_fraction != 0.6:
        raise ValueError(f"split_fraction applies to split='time' only, got split_fraction={p.split_fraction:g} with "
                         f"split={p.split!r} (which chooses the held-out samples itself)")

    choice = None
    fit_mask = None
    if not by_time or n_fit < t.size:  # every family on the same split, ranked on the held-out part
        split = {"n_fit": n_fit} if by_time else {"split": p.split}
        choice = identify(u, y, **split, output_unit=unit,
                          options=IdentifyOptions(n_levels=p.n_levels, smoothing=p.smoothing, prior=p.prior,
                                                  n_plays=p.n_plays, n_relays=p.n_relays_eq12, reversal_tolerance=0.02))
        print(choice.to_text())
        n_fit = choice.n_fit
        fit_mask = None if by_time else choice.fit_mask
        fitted = {c.family: c for c in choice.candidates if not c.failure}
        failures = {c.family: c.failure for c in choice.candidates if c.failure}
        models = {family: c.model for family, c in fitted.items()}
        reports = {family: c.report for family, c in fitted.items()}
        main = "everett" if "everett" in fitted else choice.chosen.family
        if "equal_gain" in fitted:  # compared from the main fit's first sample, as the other reports
            eq12 = fitted["equal_gain"]
            reports["equal_gain"] = make_report(eq12.model, u, y, n_fit, reports[main].fit_start,
                                                "DiscretePreisach.from_loop (Eq. 12)", notes=eq12.report.notes,
                                                output_unit=unit, fit_mask=fit_mask)
    else:
        models, reports, failures = fit_families(p, u, y, n_fit, unit)
        if "everett" not in models:
            raise ValueError(f"the Preisach fit failed on the whole record: {failures['everett']}")
        main = "everett"
        reports["equal_gain"] = make_report(models["equal_gain"], u, y, n_fit, reports[main].fit_start,
                                            "DiscretePreisach.from_loop (Eq. 12)", notes=reports["equal_gain"].notes,
                                            output_unit=unit) if "equal_gain" in models else None
        reports = {f: r for f, r in reports.items() if r is not None}
    model, report = models[main], reports[main]
    fitted_part = fit_mask if fit_mask is not None else np.arange(t.size) < n_fit
    result = Result(
        {"time": t, "voltage": u, "measured": y, "predicted": report.predicted,
         "error": report.predicted - y, "fitted": np.asarray(fitted_part, dtype=float)},
        {"time": record.units["time"], "voltage": record.units["input"] or "-", "measured": unit or "-",
         "predicted": unit or "-", "error": unit or "-", "fitted": "-"},
        parameters={"record": str(path), "processing": "; ".join(record.processing)},
    )
    scalars = {FAMILIES[family][1]: (r.model_errors["held_out"]["rms"], unit) for family, r in reports.items()}
    scalars["held_out_rms_linear"] = (report.linear_errors["held_out"]["rms"], unit)
    if main == "everett":
        scalars.update({
            "fit_rms_preisach": (report.model_errors["fit"]["rms"], unit),
            "linear_over_preisach_held_out": (report.improvement_over_linear("held_out"), "-"),
            "fit_time_preisach": (report.fit_time, "s"),
        })
    if path.resolve() == SHIPPED and main == "everett":
        scalars["held_out_rms_per_noise"] = (report.model_errors["held_out"]["rms"] / REFERENCE["noise [m]"], "-")
    reports = {FAMILIES[family][0]: r for family, r in reports.items()}
    notes = {name: r.to_dict() for name, r in reports.items()}
    notes["main_model"] = main
    if failures:  # the families the record could not identify, and why
        notes["not_fitted"] = failures
    tables = {}
    if choice is not None:
        notes["model_choice"] = choice.to_dict()
        scalars["chosen_held_out_rms_percent"] = (choice.chosen.held_out_rms_percent, "%")
        fitted = [c for c in choice.candidates if not c.failure]
        tables["model_choice"] = Result(
            {"time": t, "voltage": u, "measured": y, **{f"predicted_{c.family}": c.report.predicted for c in fitted}},
            {"time": record.units["time"], "voltage": record.units["input"] or "-", "measured": unit or "-",
             **{f"predicted_{c.family}": unit or "-" for c in fitted}},
            parameters={"record": str(path)},
        )
    if ctx.out_dir is not None:
        written = report.write_json(ctx.output_file(f"{ctx.case}_fit_report.json"))
        notes["fit_report_file"] = written.name
        if not getattr(model, "output_unit", ""):  # the record's output unit, kept in the saved model
            model.output_unit = unit
        notes["model_file"] = save_model(model, Path(ctx.out_dir) / f"{ctx.case}_model.json").name
    return CaseOutput(result, scalars, tables=tables, notes=notes)


def plot(output: CaseOutput, p: Parameters, out_dir: Path) -> list[Path]:
    r = output.result
    n_fit = int(np.sum(r["fitted"]))
    main = output.notes.get("main_model", "everett")
    report = SimpleNamespace(**{k: v for k, v in output.notes[FAMILIES[main][0]].items()})
    report.predicted = r["predicted"]
    report.n_fit = n_fit
    files = [out_dir / f"{output.case}_loop.png", out_dir / f"{output.case}_time.png"]
    title = f"Preisach fit, {p.n_levels} levels" if main == "everett" else f"{main} fit (the Preisach fit failed)"
    labels = {"labels": AxisLabels(output_unit=r.unit("measured")), "title": title}
    plot_fit(report, r["voltage"], r["measured"], path=files[0], **labels)
    plot_fit_series(report, r["voltage"], r["measured"], time=r["time"], path=files[1], **labels)
    if "model_choice" in output.notes:  # the ranked table of hysteresis.identify as a figure
        data = output.notes["model_choice"]
        table = output.tables["model_choice"]
        candidates = [SimpleNamespace(label=c["label"], family=c["family"], failure=c["failure"],
                                      held_out_rms_percent=c["held_out_rms [% of range]"], parameters=c["parameters"],
                                      report=SimpleNamespace(predicted=table[f"predicted_{c['family']}"]))
                      for c in data["candidates"] if not c["failure"]]
        chosen = next(c for c in candidates if c.family == data["chosen"])
        choice = SimpleNamespace(candidates=candidates, chosen=chosen, input=table["voltage"], output=table["measured"],
                                 n_fit=data["n_fit"], output_unit=data["output_unit"])
        files.append(out_dir / f"{output.case}_model_choice.png")
        plot_model_choice(choice, path=files[-1], title="hysteresis.identify: families on the same held-out part")
    return files


#: The case's regression benchmarks (``exudyn-atcm bench``; stored references in
#: benchmarks/regression/references/<id>.*; schema in exudyn_atcm.casework.regression).
BENCHMARKS = [
    {
        "id": "identify_and_predict",
        "quick": True,
        "scalars": [
            {"name": "held_out_rms_per_noise (<= 1.5)", "scalar": "held_out_rms_per_noise", "analytic": 1.0, "abs": 0.5, "source": "a perfect model's held-out RMS error equals the record's noise level (ratio 1); accepted up to 1.5 (and down to 0.5)"},
            {"scalar": "held_out_rms_preisach", "rel": 1e-6},
            {"scalar": "held_out_rms_linear", "rel": 1e-6}
        ]
    },
]

CASE = Case("identify_and_predict", __doc__, PARAMETERS, run, plot, benchmarks=BENCHMARKS, table_order=10,
            summary="fit on part of a record, predict the rest (the known density of the shipped record)")

if __name__ == "__main__":
    raise SystemExit(CASE.main())
