"""Cases and readings in words, for titles and captions: made where tables and figures are made,
from the resolved case a run or a case file stores (which holds numbers, ids and units only)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from rodimpact.contact.laws import UnknownLaw, law_of

__all__ = ["case_in_words", "reading_words"]


def case_in_words(config: Mapping[str, Any]) -> str:
    """A case in words for a title: its ``description`` and its rod (mm), e.g. ``Table 2 row 1:
    steel ball, diameter 3.16 mm, mass 0.13 g; rod radius 1 mm, length 30.1 mm``."""
    rod = config.get("rod") or {}
    if rod.get("radius_m") is not None:
        words = f"rod radius {1000 * float(rod['radius_m']):.3g} mm, length {1000 * float(rod['length_m']):.3g} mm"
    else:
        words = (
            f"rod length {1000 * float(rod['length_m']):.3g} mm, cross-section {1e6 * float(rod['area_m2']):.3g} mm²"
        )
    description = str(config.get("description") or "").strip()
    return f"{description}; {words}" if description else words[0].upper() + words[1:]


def reading_words(config: Mapping[str, Any]) -> str:
    """How a run's case reads the experiment, in words: its rod, its film, its contact law."""
    rod = config["rod"]
    words = [
        f"rod radius {1000 * float(rod['radius_m']):g} mm"
        if "radius_m" in rod
        else f"rod cross-section {float(rod['area_m2']):g} m²",
        f"length {1000 * float(rod['length_m']):g} mm",
    ]
    contact = config.get("contact") or {}
    film = contact.get("film")
    if film:
        name = str((film.get("material") or {}).get("name", "")).upper()
        words.append(f"with the {1e6 * float(film['thickness_m']):g} µm {name} film".replace("  ", " "))
    else:
        words.append("without the film")
    try:
        words.append(law_of(contact).reading)
    except UnknownLaw as unknown:  # a stored run of a law this code does not have
        words.append(f"contact law {unknown.name}")
    return ", ".join(words)
