"""The methods, each declared once: what every other part of the project reads about a method.

:data:`METHODS` maps a method's name (as a case's ``methods`` lists it) to a :class:`Method`:
its options class (the settings, with their docs, units and bounds), the problem its solver
takes, its solver, its cost model, and how it is presented (label, line style, colour,
theoretical order, the paper's column it is compared with). The configuration check, the
runner, the resource estimates, the tables, the figures and the workflow all read this
table; adding a method is its own package under :mod:`rodimpact.solvers` and one entry here.

The solver and the cost model are named by their dotted paths and imported only when a run
is solved or estimated, so that reading the registry (the configuration check of every
workflow job) loads no solver and no scikit-fem, and so that a rule's source inputs
(:mod:`rodimpact.plumbing.sources`) can name exactly the modules of its method
(:attr:`Method.solver_module`): a change to one method reruns that method's runs only, and
a new calibration of a cost model reruns none.
"""

from __future__ import annotations

import functools
import importlib
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from rodimpact.model.problem import ImpactProblem
from rodimpact.solvers.cost import Cost
from rodimpact.solvers.fem1d.options import FEM1DOptions
from rodimpact.solvers.fem_axi.options import FEMAxiOptions
from rodimpact.solvers.fem_axi.problem import AxiImpact
from rodimpact.solvers.field import FIELD_OUTPUT, FieldGrid
from rodimpact.solvers.gauge_series import FAR_END_OUTPUT, GAUGE_OUTPUT, case_gauges
from rodimpact.solvers.options import Options
from rodimpact.solvers.result import ImpactResult
from rodimpact.solvers.sem.options import PaperSEMOptions, SEMOptions

__all__ = ["CONTACT_KINDS", "METHODS", "Method", "UnknownMethod", "method"]

#: How a method treats the contact (``Method.contact``) -> what that means, in words.
CONTACT_KINDS = {"law": "takes the case's contact law P(alpha)", "continuum": "resolves the contact in the continuum"}


class UnknownMethod(KeyError):
    """A method name that is not in :data:`METHODS` (``name``: the name asked for)."""

    def __init__(self, name: str) -> None:
        self.name = name
        super().__init__(name)

    def __str__(self) -> str:
        return f"unknown method {self.name!r}; known: {', '.join(METHODS)}"


@functools.lru_cache(maxsize=256)
def _options(options: type, settings: tuple[tuple[str, str, Any], ...]) -> Any:
    """``options.from_settings`` of flat ``settings`` (name, type name, value), once per distinct
    settings: a planned sweep estimates every point's cost with the same settings."""
    return options.from_settings({name: value for name, _, value in settings})


@dataclass(frozen=True)
class Method:
    """One computation method.

    Attributes
    ----------
    name : str
        The name a case uses (``methods: [...]``), a file name part and a table column prefix.
    options : type[Options]
        Its settings (``numerics.<name>``): a frozen dataclass of :func:`~rodimpact.solvers.options.setting` fields.
    problem : callable
        ``problem(case) -> problem``: what the solver solves, built from a resolved case.
    solver : str
        ``"module:function"`` of the driver, ``function(problem, options, stations=...) -> ImpactResult``
        (and ``field=`` a :class:`~rodimpact.solvers.field.FieldGrid` when it records the field;
        ``gauges=`` a tuple of :class:`~rodimpact.model.gauges.Gauge` when the case lists the
        output ``gauge_strain``; ``far_end_velocity=True`` when it lists ``far_end_velocity``).
    cost : str
        ``"module:function"`` of its closed-form cost model, ``function(case, options) -> Cost``
        (:mod:`rodimpact.solvers.cost`).
    label : str
        Its name in words, for legends and captions.
    header : str
        Its name in a table's column header: short, at most two lines of eight characters.
    order : float
        Theoretical order of convergence in the step (and mesh) size.
    family : {"sem", "fem"}
        The paper's column (its SEM or its FEM) it is compared with.
    style : str
        Matplotlib line style of its curves.
    color : str
        Matplotlib colour of its curves.
    contact : {"law", "continuum"}
        How the method treats the contact (:data:`CONTACT_KINDS`): ``law``, it takes the case's
        contact law P(alpha); ``continuum``, it resolves the contact between the meshed bodies
        itself. A law declares the kinds that can run it
        (:attr:`~rodimpact.contact.law.ContactLaw.method_contact`).
    memory : bool
        Its solver carries a contact law's memory from step to step (the largest approach, the
        residual approach below which the bodies are apart, the energy dissipated;
        :class:`~rodimpact.contact.law.MemoryLaw`): only such a method can run a law with
        memory (``ContactLaw.memory``), the configuration check refuses the others.
    records_field : bool
        Its solver records the strain over the whole rod (output ``strain_field``, on the
        case's :class:`~rodimpact.solvers.field.FieldGrid`; the solver's ``field`` argument).
        A method that does not skips that output: its run stores no field, and a case that
        lists the output must run at least one method that records it (the configuration
        check refuses it otherwise).
    """

    name: str
    options: type[Options]
    problem: Callable[[Mapping[str, Any]], Any]
    solver: str
    cost: str
    label: str
    header: str
    order: float
    family: str
    style: str
    color: str
    contact: str = "law"
    memory: bool = False
    records_field: bool = False

    def options_of(self, settings: Mapping[str, Any]) -> Options:
        """This method's options from a resolved ``numerics.<name>`` mapping.

        Raises
        ------
        rodimpact.solvers.options.OptionError
            A setting is out of bounds (its name in ``field``).
        """
        try:  # flat settings of hashable values (every method's): built once, shared (frozen);
            # the key holds each value's type, so that 1 and true, equal in Python, stay apart
            key = tuple(sorted((name, type(value).__name__, value) for name, value in settings.items()))
            hash(key)
        except TypeError:
            return self.options.from_settings(settings)
        return _options(self.options, key)

    @property
    def solver_module(self) -> str:
        """The dotted name of the module its solver lives in."""
        return self.solver.partition(":")[0]

    def estimate_problem(self, case: Mapping[str, Any]) -> Any:
        """The problem for checks and estimates made before any job: a law whose data a job
        computes (the tabulated law's curve) is replaced by the law it calibrates."""
        return self.problem(case, estimate=True)

    def solve(self, case: Mapping[str, Any], settings: Mapping[str, Any]) -> ImpactResult:
        """Solve ``case`` with the resolved settings ``settings``.

        A method that takes the contact law adds the law's parameters, its run summary
        (:meth:`~rodimpact.contact.law.ContactLaw.run_summary`, at the run's largest
        approach) and its state there (:meth:`~rodimpact.contact.law.ContactLaw.state`: the
        dissipated energy and the residual approach, 0 for an elastic law) to the result's
        summary; a continuum method reports its own. The driver gets ``gauges`` and
        ``far_end_velocity`` only when the case's outputs list ``gauge_strain`` and
        ``far_end_velocity`` (:mod:`~rodimpact.solvers.gauge_series`): a run pays only for
        what it is asked.

        Raises
        ------
        rodimpact.model.gauges.GaugeError
            A gauge is malformed or off the rod (its setting in ``field``).
        """
        driver = _load(self.solver)
        problem = self.problem(case)
        grid = self.field_grid(case)
        more: dict[str, Any] = {} if grid is None else {"field": grid}
        outputs = case.get("outputs", ())
        if GAUGE_OUTPUT in outputs:
            more["gauges"] = case_gauges(case)
        if FAR_END_OUTPUT in outputs:
            more["far_end_velocity"] = True
        result = driver(problem, self.options_of(settings), stations=case.get("stations", ()), **more)
        if self.contact == "law":
            law = problem.law
            result.extra.update({key: value for key, value in law.summary().items() if key not in result.extra})
            if result.approach.size:
                largest = float(np.max(result.approach))
                result.extra.update(law.run_summary(largest))
                state = law.state(largest)
                result.extra.update(
                    dissipated_energy_J=state.dissipated_energy_J, residual_approach_m=state.residual_approach_m
                )
        return result

    def field_grid(self, case: Mapping[str, Any]) -> FieldGrid | None:
        """The grid of the strain field this method records for ``case``: None when the case
        does not list ``strain_field`` or the method does not record it (:attr:`records_field`)."""
        if not (self.records_field and FIELD_OUTPUT in case.get("outputs", ())):
            return None
        return FieldGrid.from_settings(case.get("field_grid", {}))

    def estimate(self, case: Mapping[str, Any], settings: Mapping[str, Any]) -> Cost:
        """The cost model of solving ``case`` with the resolved settings ``settings``."""
        return _load(self.cost)(case, self.options_of(settings))


def _load(path: str) -> Callable[..., Any]:
    module, _, function = path.partition(":")
    return getattr(importlib.import_module(module), function)


#: Every method, in the order tables and legends list them.
METHODS: dict[str, Method] = {
    m.name: m
    for m in (
        Method(
            name="sem",
            options=SEMOptions,
            problem=ImpactProblem.from_case,
            solver="rodimpact.solvers.sem.solver:solve_sem",
            cost="rodimpact.solvers.sem.cost:sem_cost",
            label="SEM, implicit scheme",
            header="SEM",
            order=2.0,
            family="sem",
            style="-",
            color="C0",
            memory=True,
            records_field=True,
        ),
        Method(
            name="sem_paper",
            options=PaperSEMOptions,
            problem=ImpactProblem.from_case,
            solver="rodimpact.solvers.sem.solver:solve_sem",
            cost="rodimpact.solvers.sem.cost:sem_cost",
            label="SEM, the paper's explicit scheme",
            header="SEM, explicit",
            order=1.0,
            family="sem",
            style="--",
            color="C1",
            memory=True,
        ),
        Method(
            name="fem1d",
            options=FEM1DOptions,
            problem=ImpactProblem.from_case,
            solver="rodimpact.solvers.fem1d.solver:solve_fem1d",
            cost="rodimpact.solvers.fem1d.cost:fem1d_cost",
            label="FEM, 1D bar",
            header="FEM 1-D",
            order=2.0,
            family="fem",
            style="-.",
            color="C2",
            memory=True,
            records_field=True,
        ),
        Method(
            name="fem_axi",
            options=FEMAxiOptions,
            problem=AxiImpact.from_case,
            solver="rodimpact.solvers.fem_axi.solver:solve_fem_axi",
            cost="rodimpact.solvers.fem_axi.cost:fem_axi_cost",
            label="FEM, axisymmetric continuum",
            header="FEM axisym.",
            order=2.0,
            family="fem",
            style=":",
            color="C3",
            contact="continuum",
        ),
    )
}


def method(name: str) -> Method:
    """The method called ``name``.

    Raises
    ------
    UnknownMethod
        No such method (the message lists the known ones).
    """
    try:
        return METHODS[name]
    except (KeyError, TypeError):
        raise UnknownMethod(name) from None
