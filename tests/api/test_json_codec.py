"""The app's JSON text (api/protocol/json_codec.py): what any JSON parser accepts, non-finite numbers
as null wherever they sit, and the same text for a value with none as json.dumps gives."""

from __future__ import annotations

import json
import math

from api.protocol.json_codec import dumps


def test_dumps_writes_a_finite_value_as_json_dumps_does_compactly() -> None:
    value = {
        "topic": "/uav/sensors/gps",
        "msg": {"x": 1.5, "n": -2, "ok": True, "names": ["ä", "b"], "t": (1, 2)},
    }
    text = dumps(value)
    assert text == json.dumps(value, ensure_ascii=False, separators=(",", ":"))
    assert json.loads(text) == {**value, "msg": {**value["msg"], "t": [1, 2]}}


def test_dumps_writes_every_non_finite_number_as_null_and_leaves_the_value_alone() -> None:
    value = {"a": [math.nan, (1.0, math.inf)], "b": -math.inf, "c": {"d": [[math.nan]], "e": 0.5}}
    text = dumps(value)
    assert json.loads(text, parse_constant=_not_json) == {
        "a": [None, [1.0, None]],
        "b": None,
        "c": {"d": [[None]], "e": 0.5},
    }
    assert math.isnan(value["a"][0]) and value["b"] == -math.inf  # the caller's value is not changed


def _not_json(name: str) -> None:
    raise AssertionError(f"{name} in the text: not JSON")
