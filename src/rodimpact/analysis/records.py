"""What the analyses read of a stored run (``rodimpact.storage.runs.RunRecord`` has it)."""

from __future__ import annotations

from typing import Any, Protocol

import numpy as np

__all__ = ["StoredRun"]


class StoredRun(Protocol):
    """A stored run as the analyses read it: its case, method, config, summary and series."""

    case_id: str
    method: str
    config: dict[str, Any]
    summary: dict[str, Any]
    series: dict[str, np.ndarray]
    wall_time_s: float
