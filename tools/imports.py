"""Which way the imports of the package run: `python tools/imports.py [ROOT]`.

Why: a module that imports another module which (through others) imports it back cannot be
read, tested or moved on its own, and a package that imports a package above it (the domain
reading perception, say) makes the layers of docs/architecture.md untrue. Both crept in once
(issue 21); this check keeps them out. `tests/test_imports.py` runs it on every test run.

What it reads: every `import` and `from ... import` of the Python files under `aileen/`,
`benchmarks/` and `tools/` (tests are not read), wherever the statement stands: at the top,
inside a function, under `if TYPE_CHECKING:`. An import inside a function is still a
dependency, so it cannot hide a loop from this check. Names that a package's `__init__.py`
loads through `importlib` are not followed.

What it prints: the rooms (each folder of `aileen/` is one, so is each module directly under
`aileen/`, and `benchmarks/` and `tools/`), the floors (a room stands one floor above the highest
room it imports; a room that imports nothing of the package stands on floor 1), the arrows
between rooms, the arrows that run back up (from a lower floor to a higher one: where rooms
import each other in a loop, the floors are drawn so that as few arrows as can be run back up),
and the circles (files that import each other in a loop), each with its files. Exit status 1 when there is any arrow back up or any circle, else 0.
"""

from __future__ import annotations

import argparse
import ast
import itertools
import sys
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path

PACKAGE = "aileen"
READ = ("aileen", "benchmarks", "tools")


@dataclass(frozen=True)
class House:
    """The import structure of one source tree."""

    files: dict[str, Path]  # module name -> file
    imports: dict[str, frozenset[str]]  # module -> the package's modules it imports
    rooms: dict[str, str]  # module -> its room
    arrows: frozenset[tuple[str, str]]  # (room, room it imports)
    floors: dict[str, int]  # room -> floor
    back_up: tuple[tuple[str, str], ...]  # arrows from a lower floor to a higher one
    circles: tuple[tuple[str, ...], ...]  # files that import each other in a loop

    @property
    def ok(self) -> bool:
        return not self.back_up and not self.circles


def _module_name(root: Path, path: Path) -> str:
    parts = list(path.relative_to(root).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def _room(name: str, files: dict[str, Path]) -> str:
    """`aileen/<folder>/` for a module in a folder of the package, `aileen/<module>.py` for one
    directly under it, `<top folder>/` for everything else."""
    parts = name.split(".")
    if parts[0] != PACKAGE:
        return parts[0] + "/"
    if len(parts) == 1:
        return "aileen/__init__.py"
    if len(parts) == 2 and files[name].name != "__init__.py":
        return f"aileen/{parts[1]}.py"
    return f"aileen/{parts[1]}/"


def _resolve(name: str, files: dict[str, Path]) -> str | None:
    """The package's module that an import of `name` loads: itself, else its nearest parent."""
    while name and name not in files:
        name = name.rpartition(".")[0]
    return name or None


def _imports_of(name: str, path: Path, files: dict[str, Path]) -> frozenset[str]:
    try:
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    except SyntaxError as exc:
        raise SystemExit(f"{path}:{exc.lineno}: cannot read the file as Python: {exc.msg}") from None
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            targets: Iterable[str] = (a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                up = package.split(".")[: len(package.split(".")) - (node.level - 1)]
                base = ".".join(up + ([node.module] if node.module else []))
            # `from aileen.curriculum import trainer` imports the module; `from x import name`, x
            targets = (f"{base}.{a.name}" if f"{base}.{a.name}" in files else base for a in node.names)
        else:
            continue
        for target in targets:
            module = _resolve(target, files)
            if module is not None and module != name:
                found.add(module)
    return frozenset(found)


def _loops(nodes: Iterable[str], edges: dict[str, frozenset[str]]) -> list[list[str]]:
    """The strongly connected parts of more than one node (Tarjan), each sorted."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    out: list[list[str]] = []
    counter = 0
    for start in nodes:
        if start in index:
            continue
        work = [(start, iter(sorted(edges.get(start, ()))))]
        index[start] = low[start] = counter
        counter += 1
        stack.append(start)
        on_stack.add(start)
        while work:
            node, successors = work[-1]
            for nxt in successors:
                if nxt not in index:
                    index[nxt] = low[nxt] = counter
                    counter += 1
                    stack.append(nxt)
                    on_stack.add(nxt)
                    work.append((nxt, iter(sorted(edges.get(nxt, ())))))
                    break
                if nxt in on_stack:
                    low[node] = min(low[node], index[nxt])
            else:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[node])
                if low[node] == index[node]:
                    part = []
                    while True:
                        member = stack.pop()
                        on_stack.discard(member)
                        part.append(member)
                        if member == node:
                            break
                    if len(part) > 1:
                        out.append(sorted(part))
    return sorted(out)


def _fewest_back_up(part: list[str], arrows: frozenset[tuple[str, str]],
                    weight: dict[tuple[str, str], int]) -> list[tuple[str, str]]:
    """Rooms that import each other in a loop cannot all stand above what they import: of every
    order of them from the ground up, take the one with the fewest arrows back up (then the fewest
    imports behind those arrows), and return those arrows. Every order is tried for up to 8 rooms;
    beyond that, rooms are laid from the ground up, the one that imports least of the rest first."""
    inside = [(a, b) for a, b in arrows if a in part and b in part]

    def cost(order: tuple[str, ...]) -> tuple[int, int]:
        at = {r: i for i, r in enumerate(order)}
        up = [(a, b) for a, b in inside if at[a] < at[b]]
        return len(up), sum(weight[p] for p in up)

    if len(part) <= 8:
        best = min(itertools.permutations(part), key=cost)
    else:
        rest, laid = set(part), []
        while rest:
            low = min(sorted(rest), key=lambda r: sum(weight[a, b] for a, b in inside if a == r and b in rest))
            laid.append(low)
            rest.discard(low)
        best = tuple(laid)
    at = {r: i for i, r in enumerate(best)}
    return [(a, b) for a, b in inside if at[a] < at[b]]


def measure(root: Path) -> House:
    """Read the tree under `root` and measure its import structure."""
    files: dict[str, Path] = {}
    for top in READ:
        for path in sorted((root / top).rglob("*.py")):
            files[_module_name(root, path)] = path
    imports = {name: _imports_of(name, path, files) for name, path in files.items()}
    rooms = {name: _room(name, files) for name in files}
    # The package's own __init__.py only hands names on: it is no room and draws no arrow.
    arrows = frozenset(
        (rooms[a], rooms[b])
        for a, targets in imports.items()
        for b in targets
        if rooms[a] != rooms[b] and "aileen/__init__.py" not in (rooms[a], rooms[b])
    )
    room_edges: dict[str, frozenset[str]] = {}
    for a, b in arrows:
        room_edges[a] = room_edges.get(a, frozenset()) | {b}
    weight = {pair: 0 for pair in arrows}  # how many imports make each arrow
    for a, targets in imports.items():
        for b in targets:
            if (rooms[a], rooms[b]) in weight:
                weight[rooms[a], rooms[b]] += 1
    all_rooms = sorted(set(rooms.values()) - {"aileen/__init__.py"})
    back_up: list[tuple[str, str]] = []
    for part in _loops(all_rooms, room_edges):
        back_up += _fewest_back_up(part, arrows, weight)
    kept = {a: frozenset(b for b in room_edges.get(a, ()) if (a, b) not in back_up) for a in all_rooms}
    floors: dict[str, int] = {}

    def floor(r: str) -> int:
        if r not in floors:
            floors[r] = 1 + max((floor(b) for b in kept[r]), default=0)
        return floors[r]

    for r in all_rooms:
        floor(r)
    circles = tuple(tuple(part) for part in _loops(sorted(files), imports))
    return House(files, imports, rooms, arrows, floors, tuple(sorted(back_up)), circles)


def report(house: House) -> str:
    """The figures, then each arrow back up and each circle with its files."""
    rooms = sorted(set(house.rooms.values()) - {"aileen/__init__.py"})
    tied = {r for pair in house.arrows for r in pair}
    apart = [r for r in rooms if r not in tied]
    lines = [
        f"rooms {len(rooms)}, floors {max(house.floors.values(), default=0)}, arrows {len(house.arrows)}, "
        f"arrows back up {len(house.back_up)}, circles {len(house.circles)}"
        + (f" (apart: {', '.join(apart)})" if apart else "")
    ]
    for a, b in house.back_up:
        why = sorted(f"{m} -> {t}" for m, ts in house.imports.items() if house.rooms[m] == a
                     for t in ts if house.rooms[t] == b)
        lines.append(f"arrow back up: {a} -> {b} ({'; '.join(why)})")
    for part in house.circles:
        lines.append("circle: " + ", ".join(str(house.files[m]) for m in part))
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description="Check that the package's imports run one way.")
    parser.add_argument("root", nargs="?", default=Path(__file__).resolve().parent.parent, type=Path,
                        help="the project's folder (default: the one this tool stands in)")
    args = parser.parse_args(argv)
    if not (args.root / PACKAGE).is_dir():
        print(f"{args.root}: no {PACKAGE}/ folder here; expected the project's folder", file=sys.stderr)
        return 2
    house = measure(args.root)
    print(report(house))
    return 0 if house.ok else 1


if __name__ == "__main__":
    sys.exit(main())
