"""perceive() returns, float for float, what it returned before the perception path was sped
up (issue 25): the reference was written by `tools/perceive_reference.py` from the code
before that work, on 80 evaluation scenes (half with stacks) and 3 of the agent's camera."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tools"))

import perceive_reference as ref  # noqa: E402

REFERENCE = ROOT / "tests" / "data" / "perceive_reference.json"


@pytest.fixture(scope="module")
def reference() -> dict:
    data = json.loads(REFERENCE.read_text())
    if data["model_sha256"] != ref.model_digest():
        pytest.fail(f"{REFERENCE} was written for another detector model: write it again with "
                    f"`python tools/perceive_reference.py --out {REFERENCE.relative_to(ROOT)}` "
                    "once the perception path is known to be unchanged")
    return data


def test_perceive_equals_the_reference(reference: dict) -> None:
    now = ref.snapshot(reference["n"], reference["seed"])
    assert len(now["scenes"]) == len(reference["scenes"])
    # through JSON, as the file was: tuples become lists and floats their shortest repr
    got = json.loads(json.dumps(now["scenes"]))
    for k, (a, b) in enumerate(zip(got, reference["scenes"])):
        assert a == b, f"scene {k} perceived differently from the reference"
