"""What a calibration fits: a set's measured quantities as functions of its declared constants.

:class:`SetModel` runs every case with the block's method at a vector of the constants (each
set by its path, :mod:`rodimpact.config.paths`), in memory, storing nothing, and reads each
case's quantities from the run as the comparison tables read them
(:func:`rodimpact.analysis.observations.observed`): one place says what "the computed arrival at
the gauge" is, for a table and for a fit alike. A case whose contact law a rule's curve
calibrates (``tabulated`` from the continuum's indentation) gets that curve computed again at
every vector, since a constant may change it (a layer's thickness, the rod's modulus); at the
case's own constants it reads the curve its rule computed for the case's runs instead, where it
is given (``curves``): the same curve, computed once.

:class:`GridModel` is the same model read between runs made once on a parameter's ``grid``: each
quantity is a monotone cubic (PCHIP, :class:`scipy.interpolate.PchipInterpolator`) through its
values at the grid's points, for a model too costly to run at every trial of a fit (an
indentation of the continuum per case and trial). Its derivative, and so the fit's standard
error, is the interpolant's: the grid's spacing sets how well it follows the model.
"""

from __future__ import annotations

import importlib
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rodimpact.analysis.calibration import ModelFailure
from rodimpact.analysis.measured import MeasuredHistory
from rodimpact.analysis.observations import Observed, gives, observed
from rodimpact.config.calibration import with_method
from rodimpact.config.measured import record_outputs
from rodimpact.config.paths import setting_at, with_setting
from rodimpact.contact.laws import law_of
from rodimpact.contact.tabulated import CURVE_NUMERICS
from rodimpact.jobs.batch import CURVE_BUILDERS
from rodimpact.jobs.runner import SolverFailed, run_case, with_curve

__all__ = ["GridModel", "SetModel", "predicted_values"]


def predicted_values(rows: Sequence[Observed]) -> NDArray[np.float64]:
    """The value a fit compares of each row: the computed value, or a norm's error in %."""
    return np.asarray([row.error_pct if row.is_norm else row.computed for row in rows], float)


class SetModel:
    """The fitted quantities of a set's cases at a vector of its constants (module docstring).

    Parameters
    ----------
    cases : sequence of mapping
        The cases, resolved.
    block : mapping
        The set's ``calibrate`` block.
    numerics : mapping
        The global numerics per method (a calibrated law's curve is computed with its rule's).
    records : mapping
        Case id -> its records, read, by their key in the ``measured`` block.
    curves : mapping, optional
        Case id -> the file of the curve its law's rule computed at the case's own constants
        (with ``numerics``, as here): read instead of computed when a vector is those constants.
    """

    def __init__(
        self,
        cases: Sequence[Mapping[str, Any]],
        block: Mapping[str, Any],
        numerics: Mapping[str, Any],
        records: Mapping[str, Mapping[str, MeasuredHistory]],
        curves: Mapping[str, str] | None = None,
    ) -> None:
        self.block, self.records, self.numerics = block, records, numerics
        self.curves = dict(curves or {})
        self.method = str(block["method"])
        self.paths = [str(p["path"]) for p in block["parameters"]]
        self.cases = [self._as_run(case, numerics) for case in cases]
        self.rows = [(case["id"], q) for case in self.cases for q in block["quantities"] if gives(case, q)]

    def _as_run(self, case: Mapping[str, Any], numerics: Mapping[str, Any]) -> dict[str, Any]:
        """The case as the method runs it here: its outputs only those the records need."""
        run = with_method(case, self.method, numerics)
        run["outputs"] = list(dict.fromkeys(["contact_force", *record_outputs(case)]))
        return run

    def _solve(self, case: Mapping[str, Any], own: bool = False):
        """The method's run of ``case``, with its law's curve computed first where the law needs one
        (read from :attr:`curves` when ``own``: the case is at its own constants)."""
        rule = law_of(case.get("contact")).needs.curve_rule
        if rule is not None and own and case["id"] in self.curves:
            case = with_curve(case, self.curves[case["id"]])
        elif rule is not None:
            module, function = CURVE_BUILDERS[rule]
            build = getattr(importlib.import_module(module), function)
            case = with_curve(case, build(case, self.numerics[CURVE_NUMERICS[rule]]))
        return run_case(case, self.method)

    def observe(self, theta: NDArray[np.float64]) -> list[Observed]:
        """Every fitted measurement against the runs at ``theta``, in the order of :attr:`rows`.

        Raises
        ------
        ModelFailure
            A run failed (its solver's status and message), or a signal could not be read.
        """
        found: list[Observed] = []
        for case in self.cases:
            changed, own = case, True
            for path, value in zip(self.paths, np.asarray(theta, float), strict=True):
                own = own and setting_at(case, path) == float(value)
                changed = with_setting(changed, path, float(value))
            try:
                result = self._solve(changed, own)
                series = {name: array for name, (array, _, _) in result.series(changed["outputs"]).items()}
                rows = observed(changed, series, result.summary(), self.records.get(case["id"]))
            except (SolverFailed, KeyError, ValueError, ArithmeticError) as problem:
                raise ModelFailure(
                    f"case {case['id']!r} at {dict(zip(self.paths, theta, strict=True))}: {problem}"
                ) from None
            by_quantity = {row.quantity: row for row in rows}
            found += [by_quantity[q] for cid, q in self.rows if cid == case["id"]]
        return found

    def __call__(self, theta: NDArray[np.float64]) -> NDArray[np.float64]:
        """The predicted value of every fitted measurement (a norm's value in %)."""
        return predicted_values(self.observe(theta))


class GridModel:
    """A :class:`SetModel` of one constant, run once at each value of ``grid`` and read between
    them by a monotone cubic per measurement (module docstring).

    Parameters
    ----------
    model : SetModel
        The model; it has one constant.
    grid : sequence of float, shape (g,)
        Increasing values of that constant (g >= 3), in its unit.

    Raises
    ------
    ModelFailure
        A run at a grid value failed: nothing can be read between the grid's points.
    """

    def __init__(self, model: SetModel, grid: Sequence[float]) -> None:
        from scipy.interpolate import PchipInterpolator

        if len(model.paths) != 1:
            raise ValueError(f"grid: a grid model has one constant, this model has {len(model.paths)}")
        self.model, self.rows, self.method, self.cases = model, model.rows, model.method, model.cases
        self.grid = np.asarray(grid, float)
        observed_rows = [model.observe(np.array([value])) for value in self.grid]
        #: the rows observed at the grid's first value (the measurements and their words)
        self.first_rows = observed_rows[0]
        #: each measurement's predicted value at each grid value, shape (g, n)
        self.values = np.asarray([predicted_values(rows) for rows in observed_rows])
        self._interpolant = PchipInterpolator(self.grid, self.values, axis=0, extrapolate=False)

    def observe(self, theta: NDArray[np.float64]) -> list[Observed]:
        """The rows at the grid's first value (their measurements and words do not depend on the constant)."""
        return list(self.first_rows)

    def __call__(self, theta: NDArray[np.float64]) -> NDArray[np.float64]:
        """Each measurement's interpolated value at ``theta`` (one constant, inside the grid)."""
        return np.asarray(self._interpolant(float(np.asarray(theta, float)[0])), float)
