"""perceive() returns what it returned before the perception path was sped up (issue 25): the
reference was written by `tools/perceive_reference.py` from the code before that work, on 80
evaluation scenes (half with stacks) and 3 of the agent's camera.

Everything discrete (ids, values, facts and their digest) must be equal; floats must agree to
float32's precision. The detector runs in float32 and OpenCV's dnn picks its SIMD kernels by
the CPU, so the last bits differ between machines (seen: up to 1.1e-5 relative on a small score between machines and OpenCV releases); a
change to the perception path moves them by far more."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import math
from typing import Any

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


REL = 1e-4  # float32 carries about 7 digits; layers of sums lose some (seen: 1.1e-5 on a 0.011 score)
ABS = 1e-6


def differences(got: Any, want: Any, path: str = "") -> list[str]:
    """Where `got` differs from `want`: anything but a float must be equal, floats close."""
    if isinstance(got, float) and isinstance(want, float):
        return [] if math.isclose(got, want, rel_tol=REL, abs_tol=ABS) else [f"{path}: {got} != {want}"]
    if isinstance(got, dict) and isinstance(want, dict):
        if got.keys() != want.keys():
            return [f"{path}: keys {sorted(got)} != {sorted(want)}"]
        return [d for k in got for d in differences(got[k], want[k], f"{path}/{k}")]
    if isinstance(got, list) and isinstance(want, list):
        if len(got) != len(want):
            return [f"{path}: {len(got)} items != {len(want)}"]
        return [d for i, (a, b) in enumerate(zip(got, want)) for d in differences(a, b, f"{path}[{i}]")]
    return [] if got == want else [f"{path}: {got!r} != {want!r}"]


def test_differences_catch_a_moved_float_and_a_changed_fact() -> None:
    want = {"objects": [{"centre_px": [79.06125736236572, 95.9]}], "facts_sha256": "ab"}
    assert differences(json.loads(json.dumps(want)), want) == []
    assert differences({"objects": [{"centre_px": [79.06125736236572 * (1 + 3e-7), 95.9]}],
                        "facts_sha256": "ab"}, want) == []
    assert differences({"objects": [{"centre_px": [79.2, 95.9]}], "facts_sha256": "ab"}, want)
    assert differences({"objects": [{"centre_px": [79.06125736236572, 95.9]}], "facts_sha256": "ac"}, want)


def test_perceive_equals_the_reference(reference: dict) -> None:
    now = ref.snapshot(reference["n"], reference["seed"])
    assert len(now["scenes"]) == len(reference["scenes"])
    # through JSON, as the file was: tuples become lists and floats their shortest repr
    got = json.loads(json.dumps(now["scenes"]))
    for k, (a, b) in enumerate(zip(got, reference["scenes"])):
        diffs = differences(a, b, f"scene {k}")
        assert not diffs, "perceived differently from the reference: " + "; ".join(diffs[:5])
