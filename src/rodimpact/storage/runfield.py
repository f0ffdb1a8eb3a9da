"""The space-time field of a run (output ``strain_field``) in its HDF5 file: the group ``field``.

:mod:`.runs` writes and reads it with the rest of the run::

    field/                     group, present when the run recorded the field
      time     float64 (m,)    s    sample times; HDF5 dimension scale "time"
      x        float64 (k,)    m    cross-sections, from the struck end; dimension scale "position"
      strain   float64 (m, k)  1    axial strain du/dx (negative in compression); its dimensions
                                    labelled "time" and "position", with those scales attached
      every dataset: @units, @description, @long_name (= the description); gzip + shuffle
      above 4096 elements

The field has its own time axis (a subsampled grid, :mod:`rodimpact.solvers.field`), so it
is kept apart from the root's histories, whose first dimension is the run's ``time``. The
run's content digest covers it under the names ``field/<name>``; the digest of a run without a
field is that of its series and summary alone.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import h5py
import numpy as np

__all__ = ["FIELD_GROUP", "check_field", "digest_entries", "read_field", "write_field"]

#: The group that holds the field.
FIELD_GROUP = "field"
#: The field's axes: name -> the label of its dimension scale.
_AXES = {"time": "time", "x": "position"}
_COMPRESS_MIN_ELEMENTS = 4096
_COMPRESSION = {"compression": "gzip", "compression_opts": 4, "shuffle": True}

Entry = tuple[str, np.ndarray, str, str]


def check_field(field: Mapping[str, tuple[np.ndarray, str, str]] | None) -> list[Entry]:
    """The field's datasets as float64 arrays, axes first (empty for no field).

    Raises
    ------
    ValueError, TypeError
        An axis is missing or not 1-D, a value dataset is not (len(time), len(x)), an entry
        is not (array, units, description) or a name is not a dataset name.
    """
    if not field:
        return []
    if not isinstance(field, Mapping):
        raise TypeError(f"field must be a mapping, got {type(field).__name__}")
    if missing := [axis for axis in _AXES if axis not in field]:
        raise ValueError(f"field must contain {list(_AXES)}; missing {missing}")
    checked: list[Entry] = []
    for name in [*_AXES, *(n for n in field if n not in _AXES)]:
        entry = field[name]
        if not isinstance(name, str) or not name or "/" in name:
            raise ValueError(f"field name {name!r} is not a valid dataset name")
        if not (isinstance(entry, tuple) and len(entry) == 3 and all(isinstance(s, str) for s in entry[1:])):
            raise TypeError(f"field[{name!r}] must be a tuple (array, units, description)")
        array = np.ascontiguousarray(entry[0], dtype=np.float64)
        shape = (len(checked[0][1]), len(checked[1][1])) if name not in _AXES else None
        if (shape is None and array.ndim != 1) or (shape is not None and array.shape != shape):
            raise ValueError(
                f"field[{name!r}] has shape {array.shape}; expected "
                + ("1-D" if shape is None else f"(len(time), len(x)) = {shape}")
            )
        checked.append((name, array, entry[1], entry[2]))
    return checked


def digest_entries(checked: list[Entry]) -> dict[str, tuple[np.ndarray, str, str]]:
    """The field's datasets as the run's content digest takes them: ``field/<name>``."""
    return {f"{FIELD_GROUP}/{name}": (array, units, description) for name, array, units, description in checked}


def write_field(h5: h5py.Group, checked: list[Entry]) -> None:
    """Write the checked field (:func:`check_field`) into ``h5``'s group ``field``."""
    if not checked:
        return
    group = h5.create_group(FIELD_GROUP, track_order=True)
    for name, array, units, description in checked:
        big = array.size > _COMPRESS_MIN_ELEMENTS
        dataset = group.create_dataset(name, data=array, **(_COMPRESSION if big else {}))
        dataset.attrs.update({"units": units, "description": description, "long_name": description})
    scales = [group[axis] for axis in _AXES]
    for scale, label in zip(scales, _AXES.values()):
        scale.make_scale(label)
    for name, dataset in group.items():
        if name not in _AXES:
            for dim, (scale, label) in enumerate(zip(scales, _AXES.values())):
                dataset.dims[dim].attach_scale(scale)
                dataset.dims[dim].label = label


def read_field(h5: h5py.Group, path: Path) -> list[Entry]:
    """The field of an open run file, checked (:func:`check_field`); empty without one.

    Raises
    ------
    ValueError
        The group is malformed (an axis missing, a shape that does not fit, no units).
    """
    group = h5.get(FIELD_GROUP)
    if group is None:
        return []
    if not isinstance(group, h5py.Group):
        raise ValueError(f"{path}: {FIELD_GROUP!r} is not a group")
    entries = {}
    for name, dataset in group.items():
        attrs = [dataset.attrs.get(key) for key in ("units", "description")]
        attrs = [value.decode("utf-8") if isinstance(value, bytes) else value for value in attrs]
        if not all(isinstance(value, str) for value in attrs):
            raise ValueError(f"{path}: field dataset {name!r} lacks a str units or description")
        entries[name] = (np.asarray(dataset[()], dtype=np.float64), *attrs)
    return check_field(entries)
