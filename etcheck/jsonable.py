"""Numbers, arrays and typed records as JSON: a missing (NaN) or unbounded (inf) entry of an array becomes None,
never NaN in a report; a record (a frozen dataclass of :mod:`etcheck.checks.results.sections`) becomes a dict of its
fields (:func:`to_json`, the one serializer of a check's results)."""

from __future__ import annotations

import math
import sys
import types
import typing
from dataclasses import MISSING, Field, field, fields, is_dataclass
from enum import Enum
from functools import cache
from typing import TypeVar

T = TypeVar("T")


def finite_or_none(a) -> list:
    """Nested lists of floats with None wherever ``a`` is not finite (same shape as ``a``)."""
    import numpy as np

    a = np.asarray(a, dtype=float)
    return np.where(np.isfinite(a), a, None).tolist()


def jsonable(x):
    """``x`` as JSON-able data: arrays as (nested) lists, complex arrays as {"real", "imag"}, numpy scalars as
    Python numbers, non-finite floats as None; tuples, lists and dicts converted item by item."""
    import numpy as np

    if isinstance(x, np.ndarray):
        if np.iscomplexobj(x):
            return {"real": jsonable(x.real), "imag": jsonable(x.imag)}
        return [jsonable(v) for v in x] if x.ndim > 1 else [None if (isinstance(v, float) and not math.isfinite(v))
                                                             else v for v in x.tolist()]
    if isinstance(x, (float, np.floating)):
        return float(x) if math.isfinite(x) else None
    if isinstance(x, (np.integer,)):
        return int(x)
    if isinstance(x, (np.bool_,)):
        return bool(x)
    if isinstance(x, (list, tuple)):
        return [jsonable(v) for v in x]
    if isinstance(x, dict):
        return {k: jsonable(v) for k, v in x.items()}
    return x


# --------------------------------------------------------------------------- typed records <-> JSON


class Omitted(Enum):
    """The type of :data:`OMITTED`: a record's key that is left out of its JSON (not null: absent)."""

    OMITTED = "omitted"


#: the value of a record's field whose key the JSON leaves out (the schema's not-required keys)
OMITTED = Omitted.OMITTED


def key(description: str = "", *, default=MISSING, init: bool = True, name: str | None = None, nullable: str = "oneOf",
        **schema):
    """A field of a results record with what docs/results.schema.json says of it beyond its type: its
    ``description`` and JSON Schema keywords (``minimum``, ``maxItems``, ...); ``name``: its JSON key where that
    is not a Python name; ``nullable``: how an ``X | None`` field that is not a plain number, string or bool
    admits null ("oneOf" or "anyOf" with a null branch, or "type" for a list of types)
    (:mod:`etcheck.checks.results.schema`); ``default``, ``init``: as :func:`dataclasses.field`'s."""
    info = ({"description": description} if description else {}) | schema
    metadata = {"schema": info, "nullable": nullable} | ({"name": name} if name else {})
    return field(default=default, init=init, metadata=metadata)


def json_name(f: Field) -> str:
    """The JSON key of a record's field."""
    return f.metadata.get("name", f.name)


def to_json(x):
    """``x`` as plain JSON data, the one serializer of typed results: a dataclass as a dict of its fields in
    their order (by their JSON keys; :data:`OMITTED` ones left out), tuples and lists as lists, enums as their
    values, numpy scalars and arrays as Python numbers and lists; floats are kept as they are (NaN too, which
    the writer of results.json refuses)."""
    if is_dataclass(x) and not isinstance(x, type):
        return {json_name(f): to_json(v) for f in fields(x) if (v := getattr(x, f.name)) is not OMITTED}
    if isinstance(x, dict):
        return {k: to_json(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [to_json(v) for v in x]
    if isinstance(x, Enum):
        return x.value
    np = sys.modules.get("numpy")  # not loaded: no numpy value to convert (the records load without numpy)
    if np is not None and isinstance(x, (np.generic, np.ndarray)):
        return x.tolist()
    return x


def fields_of(record) -> dict:
    """A record's fields by name, their values as they are (not converted, unlike :func:`dataclasses.asdict`):
    to build a record that extends it (``CriticalLoad(**fields_of(point), IB0_N_per_m=...)``)."""
    return {f.name: getattr(record, f.name) for f in fields(record) if f.init}


def from_json(cls: type[T], data: dict) -> T:
    """The record ``cls`` from its JSON form (nested records, tuples, maps built by their fields' types): a key
    ``cls`` does not have, or a required key missing, raises (a builder and its record cannot drift apart)."""
    by_key = {json_name(f): f for f in fields(cls)}
    unknown = set(data) - set(by_key)
    if unknown:
        raise KeyError(f"{cls.__name__} has no field for {sorted(unknown)}")
    hints = _hints(cls)
    return cls(**{f.name: _typed(hints[f.name], data[k]) for k, f in by_key.items() if k in data and f.init})


@cache
def _hints(cls: type) -> dict:
    return typing.get_type_hints(cls)


def _typed(annotation, x):
    """``x`` (JSON data) as a value of ``annotation``."""
    origin = typing.get_origin(annotation)
    if origin in (typing.Union, types.UnionType):
        if x is None or x is OMITTED:
            return x
        records = [a for a in typing.get_args(annotation) if is_dataclass(a)]
        if records and isinstance(x, dict):
            return _typed(records[0], x)
        sequences = [a for a in typing.get_args(annotation) if typing.get_origin(a) in (tuple, list)]
        return _typed(sequences[0], x) if sequences and isinstance(x, (list, tuple)) else x
    if origin in (tuple, list) and isinstance(x, (list, tuple)):
        item = typing.get_args(annotation)[0]
        return tuple(_typed(item, v) for v in x)
    if origin is dict and isinstance(x, dict):
        value = typing.get_args(annotation)[1]
        return {k: _typed(value, v) for k, v in x.items()}
    if is_dataclass(annotation) and isinstance(x, dict):
        return from_json(annotation, x)
    return x
