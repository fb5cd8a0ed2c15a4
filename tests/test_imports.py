"""The package's imports run one way: no circles of files, no arrow from a lower package back up
to a higher one (tools/imports.py; docs/architecture.md, "The house")."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def _tool():
    spec = importlib.util.spec_from_file_location("imports_tool", ROOT / "tools" / "imports.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # dataclasses look their module up
    spec.loader.exec_module(module)
    return module


imports = _tool()


def _tree(root: Path, files: dict[str, str]) -> Path:
    for name, text in files.items():
        path = root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
    return root


def test_the_package_imports_run_one_way() -> None:
    house = imports.measure(ROOT)
    assert not house.circles, imports.report(house)
    assert not house.back_up, imports.report(house)
    assert imports.main([str(ROOT)]) == 0


def test_a_circle_hidden_in_a_function_and_an_arrow_back_up_are_found(tmp_path: Path, capsys) -> None:
    root = _tree(tmp_path, {
        "aileen/__init__.py": "",
        "aileen/base.py": "X = 1\n",
        "aileen/low/__init__.py": "",
        "aileen/low/a.py": "from aileen import base\n\ndef f():\n    from aileen.high import b\n    return b\n",
        "aileen/high/__init__.py": "",
        "aileen/high/b.py": "from aileen.low.a import f\nfrom aileen.high import c\n",
        "aileen/high/c.py": "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from .d import D\n",
        "aileen/high/d.py": "from . import c\nD = 1\n",
        "aileen/high/e.py": "from aileen.low import a\n",
    })
    house = imports.measure(root)
    assert house.circles == (("aileen.high.b", "aileen.low.a"), ("aileen.high.c", "aileen.high.d"))
    # high imports low twice (b -> a, e -> a) and low imports high once (a -> b): that once runs back up
    assert house.back_up == (("aileen/low/", "aileen/high/"),)
    assert imports.main([str(root)]) == 1
    out = capsys.readouterr().out
    assert "arrows back up 1, circles 2" in out
    assert "arrow back up: aileen/low/ -> aileen/high/ (aileen.low.a -> aileen.high.b)" in out


def test_a_house_without_loops_stands_on_floors(tmp_path: Path) -> None:
    root = _tree(tmp_path, {
        "aileen/__init__.py": "from aileen.top import T\n",  # the package's face draws no arrow
        "aileen/errors.py": "",
        "aileen/mid/__init__.py": "",
        "aileen/mid/m.py": "import aileen.errors\n",
        "aileen/top.py": "from aileen.mid.m import *\nfrom aileen import errors\nT = 1\n",
        "benchmarks/run.py": "from aileen import top\n",
        "tools/apart.py": "import os\n",
    })
    house = imports.measure(root)
    assert house.ok
    assert house.floors == {"aileen/errors.py": 1, "aileen/mid/": 2, "aileen/top.py": 3, "benchmarks/": 4, "tools/": 1}
    assert len(house.arrows) == 4
    assert imports.report(house).splitlines()[0] == (
        "rooms 5, floors 4, arrows 4, arrows back up 0, circles 0 (apart: tools/)")


def test_a_folder_without_the_package_is_refused(tmp_path: Path, capsys) -> None:
    assert imports.main([str(tmp_path)]) == 2
    assert "no aileen/ folder here" in capsys.readouterr().err
