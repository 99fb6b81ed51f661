"""A margin is typed once, as the record :class:`etcheck.checks.results.sections.Margin` (made by
:mod:`etcheck.checks.margins.margin`); results.json holds its fields and its ``model``, written by
:func:`etcheck.jsonable.to_json` (``Margin.as_dict``)."""

from __future__ import annotations

import json
from dataclasses import fields, replace

from etcheck.checks.margins.margin import Margin, incomplete_margin, ratio_margin
from etcheck.checks.plan import route_model


def test_the_json_has_the_margin_s_fields_and_its_model():
    margins = [ratio_margin("load", "N/m", 3.0, 1.0, 2.0, 1, 1e-9, "why"),
               incomplete_margin("spin", "rpm", 0.1, 2.0, 1, "not answered")]
    for m in margins:
        record = m.as_dict()
        assert list(record) == [f.name for f in fields(Margin)]
        assert json.loads(json.dumps(record)) == record  # plain JSON types only (the verdict a str)
        assert record["model"] == m.model == route_model(m.rung, m.route) and record["verdict"] == m.verdict


def test_the_model_follows_the_rung_and_route():
    m = ratio_margin("load", "N/m", 3.0, 1.0, 2.0, 1, 1e-9, "why")
    assert replace(m, route="exact determinant").model == route_model(1, "exact determinant") != m.model
