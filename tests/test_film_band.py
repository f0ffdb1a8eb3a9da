"""The film's prediction band (``rodimpact.jobs.band``): its corners bound the contact time.

The default build computes each case's nominal and the 8 corners of the box of the film's
ranges; ``make film-axes`` adds each constant along its range with the others nominal, the
evidence that the time is monotone in each, so that its extremes over the box lie at corners.
Checked here on the lightest and the heaviest ball of the text's rod with the film.
"""

from __future__ import annotations

import numpy as np
import pytest

from rodimpact.jobs.band import AXIS_POINTS, case_band
from rodimpact.storage.bands import BAND_PARAMETERS


@pytest.mark.parametrize("row", ["ball_3.16mm", "ball_12.73mm"])
def test_the_film_bands_corners_bound_its_axes(shipped_project, row: str) -> None:
    case = shipped_project.cases[f"{row}-r10_l30_film"]
    band = case_band(case)
    axes = case_band(case, axes=True)
    # the axes add runs, and change none of the band's
    assert band.monotone is None and axes.monotone is True
    np.testing.assert_array_equal(band.corner_us, axes.corner_us)
    assert band.nominal_us == axes.nominal_us
    for name in BAND_PARAMETERS:
        times = axes.axis_us[name]
        assert len(times) == AXIS_POINTS
        # every point of every axis lies inside the corners' band, the nominal too
        assert band.band_min_us <= times.min() and times.max() <= band.band_max_us
    assert band.band_min_us <= band.nominal_us <= band.band_max_us
    # each constant moves the time: the band is not an artefact of one range
    assert all(np.ptp(axes.axis_us[name]) > 1e-3 * band.nominal_us for name in BAND_PARAMETERS)
