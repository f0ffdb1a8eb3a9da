"""A contact law no module of the package knows: the linear spring P = c alpha.

It implements only what the contact-law interface requires (force, stiffness, energy,
approach); the step and the rigid impact come from the interface's generic parts. The tests
run it through the solvers (tests/test_contact_laws.py) and, declared with a setting of its
own, from a case file (tests/test_contact_law_declared.py).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rodimpact.contact.law import ContactLaw


@dataclass(frozen=True)
class LinearSpring(ContactLaw):
    """P = c alpha, N, with c the spring's stiffness, N/m."""

    c: float
    name = "linear_spring"
    label = "linear spring"
    reading = "a linear spring"

    def force(self, approach_m: float) -> float:
        return self.c * approach_m if approach_m > 0.0 else 0.0

    def stiffness(self, approach_m: float) -> float:
        return self.c if approach_m > 0.0 else 0.0

    def energy(self, approach_m):
        return 0.5 * self.c * np.maximum(approach_m, 0.0) ** 2

    def approach(self, force_N: float) -> float:
        return max(force_N, 0.0) / self.c
