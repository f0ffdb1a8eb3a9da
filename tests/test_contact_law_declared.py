"""A contact law declared once: a law with a setting of its own, defined in this file only,
read from a case's YAML, checked before any job, and run by the one-dimensional methods.

The law is a linear spring P = c alpha with ``stiffness_n_per_m`` = c. Registering its class
in ``rodimpact.contact.laws.LAWS`` is all it takes: the case schema's ``contact`` block, the
configuration's checks with their field paths, the defaults, the runner's problem and the
methods read its declarations. No module outside ``rodimpact/contact`` knows it.

Closed form. A mass m striking, through a spring c, the end of a long elastic rod (impedance
Z = rho a S) before any wave returns from the far end (contact time < 2 l / a): the end moves
with velocity P / Z, so the approach alpha obeys m alpha'' + (m c / Z) alpha' + c alpha = 0,
alpha(0) = 0, alpha'(0) = v0: a damped oscillator with omega^2 = c / m and 2 zeta omega = c / Z.
Then alpha = (v0 / omega_d) exp(-zeta omega t) sin(omega_d t), omega_d = omega sqrt(1 - zeta^2);
the contact lasts pi / omega_d, and the force c alpha peaks where tan(omega_d t) = omega_d /
(zeta omega).
"""

from __future__ import annotations

import math
import shutil
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest
import yaml

from rodimpact.config.load import load_global_config, load_project
from rodimpact.config.project import ConfigError
from rodimpact.contact import laws
from rodimpact.contact.law import LawSettings
from rodimpact.settings.declare import REQUIRED, setting
from rodimpact.solvers.registry import METHODS

from helpers.laws import LinearSpring

ROOT = Path(__file__).resolve().parents[1]


@dataclass(frozen=True, kw_only=True)
class SpringSettings(LawSettings):
    """The linear spring's settings."""

    stiffness_n_per_m: float = setting(REQUIRED, "Stiffness c of the spring.", unit="N/m", exclusive_minimum=0)


@dataclass(frozen=True)
class LinearSpringLaw(LinearSpring):
    """The linear spring, declared as a case file selects it: its stiffness is a setting."""

    settings = SpringSettings

    @classmethod
    def from_bodies(cls, spec: Mapping[str, Any], sphere_radius_m: float, impactor: Any, rod: Any) -> LinearSpringLaw:
        return cls(float(spec["stiffness_n_per_m"]))


MASS, VELOCITY, SPRING = 0.01, 1.0, 1.0e7  # kg, m/s, N/m
ROD_RADIUS, ROD_LENGTH = 0.005, 1.0  # m
CASE = {
    "set": "spring",
    "cases": [
        {
            "id": "spring",
            "description": "A 10 g steel mass on a linear spring striking a long steel rod",
            "impactor": {"mass_kg": MASS, "radius_m": 0.005, "velocity_m_s": VELOCITY, "material": "steel"},
            "rod": {"radius_m": ROD_RADIUS, "length_m": ROD_LENGTH, "material": "steel", "far_end": "fixed"},
            "contact": {"law": "linear_spring", "stiffness_n_per_m": SPRING},
            "methods": ["sem", "fem1d"],
        }
    ],
}


@pytest.fixture
def spring_law(monkeypatch: pytest.MonkeyPatch) -> type[LinearSpringLaw]:
    """The law registered as the project's own laws are: one entry in LAWS."""
    monkeypatch.setitem(laws.LAWS, LinearSpringLaw.name, LinearSpringLaw)
    return LinearSpringLaw


def _project(tmp_path: Path, contact: Mapping[str, Any]) -> Path:
    """A copy of the project's configuration with one more case file, ``spring.yaml``."""
    shutil.copytree(ROOT / "config", tmp_path / "config")
    shutil.copytree(ROOT / "workflow" / "schemas", tmp_path / "workflow" / "schemas")
    document = {**CASE, "cases": [{**CASE["cases"][0], "contact": dict(contact)}]}
    (tmp_path / "config" / "cases" / "spring.yaml").write_text(yaml.safe_dump(document, sort_keys=False))
    return tmp_path


def _load(root: Path):
    config = load_global_config(root / "config" / "config.yaml")
    return load_project(config, root=root)


def _error(root: Path) -> ConfigError:
    with pytest.raises(ConfigError) as info:
        _load(root)
    return info.value


def test_the_case_schema_takes_the_laws_setting_from_its_declaration(spring_law):
    schema = laws.contact_schema()
    assert "linear_spring" in schema["properties"]["law"]["enum"]
    stiffness = schema["properties"]["stiffness_n_per_m"]
    assert stiffness["type"] == "number" and stiffness["exclusiveMinimum"] == 0
    assert "Unit: N/m" in stiffness["description"] and "linear_spring" in stiffness["description"]


def test_the_case_is_read_and_resolved(spring_law, tmp_path):
    project = _load(_project(tmp_path, CASE["cases"][0]["contact"]))
    assert project.cases["spring"]["contact"] == {"law": "linear_spring", "stiffness_n_per_m": SPRING}
    assert laws.law_of(project.cases["spring"]["contact"]) is LinearSpringLaw


@pytest.mark.parametrize("value", [-1.0e7, 0])
def test_a_bad_value_is_refused_before_any_job_naming_the_field(spring_law, tmp_path, value):
    error = _error(_project(tmp_path, {"law": "linear_spring", "stiffness_n_per_m": value}))
    assert (error.case, error.field) == ("spring", "contact.stiffness_n_per_m")
    assert error.reason == f"must be > 0, got {value!r}"
    assert str(error).startswith("config/cases/spring.yaml: case 'spring': field 'contact.stiffness_n_per_m': ")


def test_a_typo_in_the_key_is_refused_naming_the_key(spring_law, tmp_path):
    error = _error(_project(tmp_path, {"law": "linear_spring", "stifness_n_per_m": SPRING}))
    assert (error.case, error.field) == ("spring", "contact.stifness_n_per_m")
    assert "did you mean 'stiffness_n_per_m'?" in error.reason


def test_a_missing_setting_is_refused_naming_it(spring_law, tmp_path):
    error = _error(_project(tmp_path, {"law": "linear_spring"}))
    assert (error.case, error.field) == ("spring", "contact.stiffness_n_per_m")
    assert error.reason == "missing; the linear_spring law needs it"


def test_another_laws_setting_is_refused_naming_the_laws_that_take_it(spring_law, tmp_path):
    film = {"thickness_m": 2.8e-5, "material": "pvdf"}
    error = _error(_project(tmp_path, {"law": "linear_spring", "stiffness_n_per_m": SPRING, "film": film}))
    assert (error.case, error.field) == ("spring", "contact.film")
    assert error.reason == "the linear_spring law takes no 'film'; laws that take it: hertz_film, tabulated"


def test_without_the_law_registered_the_case_is_refused(tmp_path):
    error = _error(_project(tmp_path, CASE["cases"][0]["contact"]))
    assert error.field.endswith("law") and "unknown contact law 'linear_spring'" in error.reason


def _closed_form() -> tuple[float, float]:
    """Contact time (s) and peak force (N) of the damped oscillator (module docstring)."""
    area = math.pi * ROD_RADIUS**2
    density, modulus = 7800.0, 2.1e11  # config/materials.yaml: steel
    impedance = area * math.sqrt(modulus * density)
    omega = math.sqrt(SPRING / MASS)
    zeta = SPRING / impedance / (2.0 * omega)
    omega_d = omega * math.sqrt(1.0 - zeta**2)
    t_peak = math.atan2(omega_d, zeta * omega) / omega_d
    peak = SPRING * VELOCITY / omega_d * math.exp(-zeta * omega * t_peak) * math.sin(omega_d * t_peak)
    assert math.pi / omega_d < 2.0 * ROD_LENGTH / math.sqrt(modulus / density)  # no wave returns in contact
    return math.pi / omega_d, peak


#: Against the closed form: the implicit SEM at the shipped tolerance, 1e-6 on the contact time
#: and the maxima (measured: 4.0e-7 on the time, 5.1e-7 on the peak), and fem1d at its shipped
#: 2000 steps per contact, whose Newmark period error is (pi / 2000)^2 / 12 = 2.1e-7, and its
#: mesh of the rod (measured: 2.4e-7 and 2.8e-7). The rod's elasticity (zeta = 0.050) moves the
#: contact time 0.12 % and the peak 7.3 % from the rigid rod's pi sqrt(m / c) and v0 sqrt(m c).
RTOL = {"sem": 1e-6, "fem1d": 1e-6}


@pytest.mark.parametrize("method", ["sem", "fem1d"])
def test_the_methods_run_the_law_from_the_case_and_match_its_closed_form(spring_law, tmp_path, method):
    case = _load(_project(tmp_path, CASE["cases"][0]["contact"])).cases["spring"]
    result = METHODS[method].solve(case, case["numerics"][method])
    assert result.success, result.message
    contact_time, peak = _closed_form()
    assert result.n_contacts == 1
    assert result.contact_time_s == pytest.approx(contact_time, rel=RTOL[method])
    assert result.peak_force_N.max() == pytest.approx(peak, rel=RTOL[method])
    assert result.extra["contact_law"] == "linear_spring"
