"""A margin is typed once, as :class:`etcheck.checks.margins.Margin`; ``MarginRecord`` (results.json, the schema)
is its JSON form, key for key: the dataclass's fields and its ``model``, made only by ``Margin.as_dict``."""

from __future__ import annotations

import json
from dataclasses import fields

from etcheck.checks.margins import Margin, incomplete_margin, ratio_margin
from etcheck.checks.sections import MarginRecord


def test_the_record_has_the_margin_s_fields_and_nothing_else():
    assert set(MarginRecord.__annotations__) == {f.name for f in fields(Margin)} | {"model"}


def test_as_dict_is_plain_json_with_the_record_s_keys():
    margins = [ratio_margin("load", "N/m", 3.0, 1.0, 2.0, 1, 1e-9, "why"),
               incomplete_margin("spin", "rpm", 0.1, 2.0, 1, "not answered")]
    for m in margins:
        record = m.as_dict()
        assert set(record) == set(MarginRecord.__annotations__)
        assert json.loads(json.dumps(record)) == record  # plain JSON types only (the verdict a str)
        assert record["model"] == m.model and record["verdict"] == m.verdict
