"""The repository the tests run in, and the parts of it that make the workflow."""

from __future__ import annotations

from pathlib import Path

#: The repository: config/, workflow/, src/, .test/.
ROOT = Path(__file__).resolve().parents[2]
#: What a copy of the project needs to run the workflow (the small configuration .test/ aside).
PROJECT_PARTS = ("Snakefile", "config", "workflow", "src")
