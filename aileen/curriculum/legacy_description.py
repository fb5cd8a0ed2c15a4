"""An original-format lesson's `description`: what stands on the table, the relation, the
composite word, and an action with the trace the trainer demonstrates.

Split from `legacy` (which reads a lesson's other fields and decides what the trainer says)
so that each reader is one job. Every list of valid names in an error is read from the
declarations (`aileen.domain`), never written here.
"""

from __future__ import annotations

import json
from typing import Any

from aileen.curriculum.legacy_where import Where as _Where
from aileen.curriculum.legacy_where import field as _field
from aileen.curriculum.lesson import ActionSpec, ObjectSpec, Step, auto_demonstration
from aileen.curriculum.sentences import parse_action
from aileen.domain import actions, channels, composites, relations
from aileen.errors import UserError

__all__ = ["COMPOSITE_KEYS", "IGNORED_DESCRIPTION_KEYS", "IGNORED_OBJECT_KEYS", "read_action", "read_composite",
           "read_objects", "read_relation", "read_trace", "read_visual_objects"]

COMPOSITE_KEYS: tuple[str, ...] = ("composite", "objects")
IGNORED_OBJECT_KEYS: tuple[str, ...] = ("rgb", "position", "translation")
IGNORED_DESCRIPTION_KEYS: tuple[str, ...] = ("initial_configuration", "language")
TRACE_KEYS: tuple[str, ...] = ("name", "argument", "argument1", "argument2", "relation")


def read_composite(description: dict[str, Any] | None, where: _Where) -> tuple[str, list[ObjectSpec]]:
    """`{"composite": "wall"}`, optionally with `objects` (its parts; default: the parts the
    word declares)."""
    if description is None or "composite" not in description:
        raise where.error(f"a composite-word lesson needs 'description.composite', one of: "
                          f"{', '.join(composites.COMPOSITES)}", _field("description"))
    for key in description:
        if key not in (*COMPOSITE_KEYS, *IGNORED_DESCRIPTION_KEYS) and not _is_placeholder(key):
            raise where.error(f"description: unknown field {key!r}; expected one of: {', '.join(COMPOSITE_KEYS)}",
                              _field(key))
    word = description["composite"]
    if not isinstance(word, str):
        raise where.error(f"'description.composite' must be one of: {', '.join(composites.COMPOSITES)}",
                          _field("composite"))
    try:
        comp = composites.get(word)
    except UserError as exc:
        raise where.error(exc.message, _field("composite")) from None
    if "objects" not in description:
        return comp.word, [ObjectSpec(shape) for shape in comp.parts]
    objects = read_objects(description["objects"], description, where)
    if len(objects) != len(comp.parts):
        raise where.error(f"a {comp.word} has {len(comp.parts)} parts; 'description.objects' lists "
                          f"{len(objects)}", _field("description"), _field("objects"))
    for i, (spec, shape) in enumerate(zip(objects, comp.parts)):
        if shape is not None and spec.shape not in (None, shape):
            raise where.error(f"description.objects[{i + 1}]: part {i + 1} of a {comp.word} is a {shape}, "
                              f"not a {spec.shape}", _field("objects"))
    return comp.word, [spec.with_values(shape=spec.shape or shape) for spec, shape in zip(objects, comp.parts)]


def _is_placeholder(name: str) -> bool:
    return len(name) > 2 and name.startswith("<") and name.endswith(">")


def _object(raw: Any, where: _Where, label: str, ignored: tuple[str, ...] = IGNORED_OBJECT_KEYS) -> ObjectSpec:
    """One described object; `ignored` are the Webots-only fields it may carry (a visual
    lesson's description is its object, so it may carry a description's too)."""
    if not isinstance(raw, dict):
        raise where.error(f"{label} must be an object like {{\"color\": \"red\", \"shape\": \"box\"}}",
                          _field("description"))
    names = sorted((*c.keys, c.name)[0] for c in channels.CHANNELS)  # the original's spellings: color, shape, size
    for key in raw:
        if key not in (*channels.key_names(), *ignored):
            raise where.error(f"{label}: unknown field {key!r}; expected {', '.join(names)}", _field(key))
    values: dict[str, str] = {}
    for channel in channels.CHANNELS:
        given = [k for k in (*channel.keys, channel.name) if k in raw and raw[k] is not None]
        if len({json.dumps(raw[k]) for k in given}) > 1:
            raise where.error(f"{label}: both {given[0]!r} and {given[1]!r} are given, and they differ: give one",
                              _field(given[1]))
        key = next((k for k in (*channel.keys, channel.name) if k in raw), None)  # "color" before "colour"
        if key is None or raw[key] is None:
            continue
        try:
            values[channel.name] = channel.check(raw[key])
        except UserError:
            raise where.error(f"{label}: unknown {channel.name} {raw[key]!r}; expected one of: "
                              f"{', '.join(channel.values)}", _field(key), json.dumps(raw[key])) from None
    return ObjectSpec(appearance=values)


def read_visual_objects(description: dict[str, Any] | None, where: _Where) -> list[ObjectSpec]:
    if description is None:
        return [ObjectSpec()]
    if "objects" in description:
        objects = read_objects(description["objects"], description, where)
        if not objects:
            raise where.error("'description.objects' is empty", _field("objects"))
        return objects
    return [_object(description, where, "'description'", (*IGNORED_OBJECT_KEYS, *IGNORED_DESCRIPTION_KEYS))]


def read_objects(raw: Any, description: dict[str, Any], where: _Where) -> list[ObjectSpec]:
    """`[{...}, {...}]` or `["<obj1>", "<obj2>"]` with the placeholders defined in the description."""
    if not isinstance(raw, list):
        raise where.error("'description.objects' must be a list of objects", _field("description"))
    out = []
    for i, item in enumerate(raw):
        label = f"description.objects[{i + 1}]"
        if isinstance(item, str):
            if item in description:
                out.append(_object(description[item], where, f"description.{item}"))
            elif _is_placeholder(item):
                out.append(ObjectSpec())  # not described: the trainer draws a random object, as the original did
            else:
                raise where.error(f"{label}: {item!r} is neither an object nor a placeholder like \"<obj1>\"",
                                  json.dumps(item))
        else:
            out.append(_object(item, where, label))
    for key in description:
        if _is_placeholder(key) and key not in raw:  # a definition no object names was dropped unseen
            raise where.error(f"description: {key!r} is defined but 'objects' does not name it "
                              f"({', '.join(map(str, raw))})", _field("description"), _field(key))
    return out


def read_relation(raw: Any, where: _Where, label: str = "description.relation", *needles: str) -> str:
    """A relation the domain declares, by any of its spellings; `label` and `needles` say
    where it stands (an entry of `relations`, a trace step's `relation`)."""
    key = label.rsplit(".", 1)[-1]
    if not isinstance(raw, str):
        raise where.error(f"'{label}' must be one of: {', '.join(relations.known())} "
                          f"(spelt with spaces, hyphens or underscores), found {json.dumps(raw)[:40]}",
                          _field(key), *needles)
    found = relations.find(raw)
    if found is None:
        raise where.error(f"unknown relation {raw!r}; expected one of: {', '.join(relations.known())}",
                          _field(key), *(needles or (json.dumps(raw),)))
    return found


def read_action(description: dict[str, Any], where: _Where) -> ActionSpec:
    for key in description:
        if _is_placeholder(key) or key in ("objects", "relation", "relations", "action", "trace-actions",
                                           *IGNORED_DESCRIPTION_KEYS):
            continue
        raise where.error(f"description: unknown field {key!r}; expected objects, relations, action, "
                          "trace-actions", _field(key))
    rel = description.get("relation")
    rels = description.get("relations")
    if rels is not None and not isinstance(rels, list):
        raise where.error("'description.relations' must be a list like [\"right-of\"] (or [] for push)",
                          _field("relations"))
    if rels:
        for entry in rels:  # each read, so that a misspelt or stray entry is an error, not dropped
            read_relation(entry, where, "description.relations", json.dumps(entry))
        if len(rels) > 1:
            raise where.error(f"'description.relations' names {len(rels)} relations; an action has one goal: "
                              f"give one, like [{json.dumps(rels[0])}]", _field("relations"))
    if rel is None and rels:
        rel = rels[0]
    verb = description.get("action", "move")
    if not isinstance(verb, str) or not verb.strip():
        raise where.error(f"'description.action' must be one of: {', '.join(actions.VERBS)}", _field("action"))
    words = verb.replace("-", " ").replace("_", " ").split()
    declared = actions.find_verb(words[0])
    if declared is None:
        raise where.error(f"unknown action {verb!r}; expected one of: {', '.join(actions.VERBS)} "
                          "(\"move\" with 'relations', or \"move-right-of\")", _field("action"), json.dumps(verb))
    try:
        if rel is None or not declared.takes_relation:
            # "move-right-of" carries its relation; "push" takes none
            return parse_action(verb)
        return parse_action(f"{declared.name} {read_relation(rel, where)}")
    except UserError as exc:
        raise where.error(exc.message, _field("action")) from None


def read_trace(description: dict[str, Any], action: ActionSpec, where: _Where) -> list[Step]:
    """`trace-actions` -> steps (0-based object indices); the trainer's own demo if absent."""
    trace = description.get("trace-actions")
    if trace is None:
        return auto_demonstration(action)
    names = description.get("objects", [])
    if not isinstance(trace, list):
        raise where.error("'trace-actions' must be a list of actions", _field("trace-actions"))

    def index(arg: Any, label: str) -> int:
        if isinstance(arg, str) and arg in names:
            return names.index(arg)
        raise where.error(f"trace-actions: {label} {arg!r} is not one of the description's objects "
                          f"({', '.join(map(str, names))})", _field("trace-actions"))

    steps = []
    for item in trace:
        if not isinstance(item, dict) or not isinstance(item.get("name"), str):
            raise where.error(f"trace-actions: each action needs a \"name\", one of: {', '.join(actions.ACTIONS)}",
                              _field("trace-actions"))
        for key in item:
            if key not in TRACE_KEYS:  # "argumnet2" was dropped, and the step read without it
                raise where.error(f"trace-actions: unknown field {key!r}; expected {', '.join(TRACE_KEYS)}",
                                  _field("trace-actions"), _field(key))
        try:
            act = actions.action(item["name"])
        except UserError as exc:
            raise where.error(f"trace-actions: {exc.message}", _field("trace-actions"),
                              json.dumps(item["name"])) from None
        if act.touches:
            steps.append(Step(act.name, index(item.get("argument", item.get("argument1")), "argument")))
        else:
            obj = index(item.get("argument1", item.get("argument")), "argument1")
            ref = index(item.get("argument2"), "argument2")
            if ref == obj:
                raise where.error("trace-actions: place puts an object relative to itself", _field("trace-actions"))
            rel = item.get("relation", action.relation)
            if rel is None:
                raise where.error("trace-actions: place needs a \"relation\"", _field("trace-actions"))
            steps.append(Step(act.name, obj, relation=read_relation(rel, where, "trace-actions.relation"), ref=ref))
    return steps
