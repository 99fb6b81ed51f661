"""docs/results.schema.json made from the records of a check's results (:mod:`etcheck.checks.results.sections`).

A record's JSON Schema follows from its fields' types (float a number, int an integer, str a string, bool a
boolean, ``X | None`` admits null, a tuple an array, a ``dict[str, X]`` a map, a ``Literal`` an enum, a record an
object with its keys all listed, every key required unless its field may be :data:`etcheck.jsonable.OMITTED`),
with what :func:`etcheck.jsonable.key` says beyond the type (descriptions, bounds) and a record's own
``JSON_SCHEMA`` (its description). tests/checks/test_results_schema.py fails when the committed schema is not
this one; ``python -m etcheck.checks.results.schema`` writes it.
"""

from __future__ import annotations

import json
import sys
import types
import typing
from dataclasses import fields, is_dataclass
from pathlib import Path
from typing import Literal

from etcheck.checks.results.sections import CheckResults
from etcheck.jsonable import OMITTED, Omitted, json_name

SCHEMA_PATH = Path(__file__).resolve().parents[3] / "docs" / "results.schema.json"
_LEAF = {float: "number", int: "integer", str: "string", bool: "boolean", type(None): "null"}


def results_schema() -> dict:
    """The JSON Schema (draft 2020-12) of results.json."""
    return object_schema(CheckResults)


def schema_text() -> str:
    """The text of docs/results.schema.json."""
    return json.dumps(results_schema(), indent=2, ensure_ascii=False) + "\n"


def object_schema(record: type) -> dict:
    """The schema of a record: its keys, each typed, which are required, no others."""
    hints = typing.get_type_hints(record)
    own = dict(getattr(record, "JSON_SCHEMA", {}))
    head = {k: own.pop(k) for k in ("$schema", "title") if k in own}
    properties = {json_name(f): type_schema(hints[f.name], f.metadata.get("nullable", "oneOf"))
                  | f.metadata.get("schema", {}) for f in fields(record)}
    required = [json_name(f) for f in fields(record) if f.default is not OMITTED]
    return head | {"type": "object"} | own | {"properties": properties, "required": required,
                                               "additionalProperties": False}


def type_schema(annotation, nullable: str = "oneOf") -> dict:
    """The schema of a value of ``annotation`` (``nullable``: how ``X | None`` admits null, see
    :func:`etcheck.jsonable.key`)."""
    origin = typing.get_origin(annotation)
    if origin in (typing.Union, types.UnionType):
        return _union_schema([a for a in typing.get_args(annotation) if a is not Omitted], nullable)
    if origin is Literal:
        values = list(typing.get_args(annotation))
        return {"const": values[0]} if len(values) == 1 else {"enum": values}
    if origin in (tuple, list):
        return {"type": "array", "items": type_schema(typing.get_args(annotation)[0])}
    if origin is dict:
        return {"type": "object", "additionalProperties": type_schema(typing.get_args(annotation)[1])}
    if is_dataclass(annotation):
        return object_schema(annotation)
    return {"type": _LEAF[annotation]}


def _union_schema(args: list, nullable: str) -> dict:
    """``X | None`` (the one union of the results)."""
    (inner,) = [a for a in args if a is not type(None)]
    schema = type_schema(inner)
    if len(args) == 1:
        return schema
    if nullable == "type" or set(schema) == {"type"}:
        return schema | {"type": [schema["type"], "null"]}
    return {nullable: [{"type": "null"}, schema]}


if __name__ == "__main__":  # python -m etcheck.checks.results.schema [PATH]: write the schema
    Path(sys.argv[1] if len(sys.argv) > 1 else SCHEMA_PATH).write_text(schema_text(), encoding="utf-8")
