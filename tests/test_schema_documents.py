"""The JSON Schemas (``sizer schema``) accept what the loader accepts, and only that.

Every example file, every bundled catalog and every YAML block of README.md validates
against the schema of its kind (jsonschema, draft 2020-12), and the loader's models accept
them too; the shorthands are in the schema, and forms the loader rejects are rejected by
the schema as well. The schema follows the models: every field of every input model is a
property of the schema.
"""

from __future__ import annotations

import re
import typing
from pathlib import Path
from typing import Any

import pytest
import yaml
from jsonschema import Draft202012Validator
from pydantic import BaseModel, ValidationError

from sizer.io.loader import catalog_schema, design_schema, gearbox_catalog_schema
from sizer.io.machine_loader import machine_schema
from sizer.io.schema.inputs import CatalogFile, DesignFile
from sizer.io.schema.machine_inputs import MachineFile
from sizer.io.schema.transmission_inputs import GearboxCatalogFile

ROOT = Path(__file__).resolve().parent.parent
SCHEMAS = {"design": (design_schema, DesignFile), "catalog": (catalog_schema, CatalogFile),
           "gearboxes": (gearbox_catalog_schema, GearboxCatalogFile),
           "machine": (machine_schema, MachineFile)}
NOT_SIZER_FILES = {"examples/ci"}  # CI and pre-commit configurations, not sizer inputs


def kind_of(data: Any) -> str:
    if isinstance(data, dict) and "axes" in data:
        return "machine"
    if isinstance(data, dict) and ("task" in data or "cycle" in data):
        return "design"
    if isinstance(data, dict) and "gearboxes" in data:
        return "gearboxes"
    return "catalog"


def validator(kind: str) -> Draft202012Validator:
    return Draft202012Validator(SCHEMAS[kind][0]())


def schema_errors(kind: str, data: Any) -> list[str]:
    return [f"{list(e.absolute_path)}: {e.message[:200]}"
            for e in validator(kind).iter_errors(data)]


def model_accepts(kind: str, data: Any) -> bool:
    try:
        SCHEMAS[kind][1].model_validate(data)
    except ValidationError:
        return False
    return True


def input_files() -> list[Path]:
    files = sorted((ROOT / "examples").rglob("*.yaml")) + sorted(
        (ROOT / "sizer" / "catalogs").glob("*.yaml")) + sorted((ROOT / "catalogs").glob("*.yaml"))
    return [f for f in files
            if not any(f.relative_to(ROOT).as_posix().startswith(p) for p in NOT_SIZER_FILES)]


def readme_yaml_blocks() -> list[str]:
    text = "\n".join((ROOT / name).read_text(encoding="utf-8") for name in (
        "README.md", "docs/design-files.md", "docs/machine-cycles.md", "docs/machines.md"))
    return re.findall(r"^```yaml\n(.*?)^```$", text, flags=re.DOTALL | re.MULTILINE)


@pytest.mark.parametrize("kind", sorted(SCHEMAS))
def test_schema_is_draft_2020_12_with_an_id(kind: str) -> None:
    schema = SCHEMAS[kind][0]()
    assert schema["$schema"] == "https://json-schema.org/draft/2020-12/schema"
    assert schema["$id"] == f"urn:sizer-motion:schema:{kind}:1"
    assert list(schema)[:2] == ["$schema", "$id"]
    Draft202012Validator.check_schema(schema)


def test_there_are_examples_of_every_kind() -> None:
    kinds = [kind_of(yaml.safe_load(f.read_text(encoding="utf-8"))) for f in input_files()]
    assert kinds.count("design") >= 9 and kinds.count("gearboxes") >= 1
    assert kinds.count("catalog") >= 12 and kinds.count("machine") >= 1


@pytest.mark.parametrize("path", input_files(), ids=lambda p: p.relative_to(ROOT).as_posix())
def test_every_example_and_catalog_validates(path: Path) -> None:
    data = yaml.safe_load(path.read_text(encoding="utf-8"))
    kind = kind_of(data)
    assert schema_errors(kind, data) == []
    assert model_accepts(kind, data)


def test_readme_has_yaml_blocks_with_the_shorthands() -> None:
    blocks = readme_yaml_blocks()
    assert len(blocks) >= 3
    text = "\n".join(blocks)
    assert "yaml-language-server: $schema=" in text
    assert "laws: cycloidal" in text and "transmission: {type:" in text


@pytest.mark.parametrize("block", readme_yaml_blocks(), ids=lambda b: b.splitlines()[0][:40])
def test_every_readme_yaml_block_validates(block: str) -> None:
    """Every ```yaml block of README.md is a whole file that the schema and the loader's
    models accept (fragments belong in prose or ``` blocks without a language)."""
    data = yaml.safe_load(block)
    kind = kind_of(data)
    assert schema_errors(kind, data) == []
    assert model_accepts(kind, data)


DESIGN = {"task": {"displacement": "90 deg", "duration": "0.25 s"},
          "load": {"inertia": "0.034 kg*m^2"}}


@pytest.mark.parametrize(("extra", "accepted"), [
    ({"laws": "cycloidal"}, True),
    ({"laws": ["cycloidal", "poly5"]}, True),
    ({"laws": 5}, False),
    ({"laws": []}, False),
    ({"motors": "book-examples"}, True),
    ({"motors": ["book-examples", {"id": "m", "inertia": 0, "continuous_torque": 1,
                                   "peak_torque": 2, "rated_speed": "3000 rpm"}]}, True),
    ({"motors": {"id": "m", "inertia": 0, "continuous_torque": 1, "peak_torque": 2,
                 "rated_speed": 300}}, False),  # one inline motor must be in a list
    ({"transmission": {"type": "direct"}}, True),
    ({"transmission": {"type": "gearbox", "ratio": 10}}, True),
    ({"transmission": [{"type": "belt", "ratio": 2}, {"type": "gearbox", "ratio": [5, 7]}]},
     True),
    ({"transmission": {"type": "gearbox", "ratio": "optimize"}}, True),
    ({"transmission": {"type": "gearbox", "ratio": {"optimize": [3, 50]}}}, True),
    ({"transmission": {"type": "gearbox", "ratio": {"optimize": [3, 50, 70]}}}, False),
    ({"transmission": {"type": "gearbox", "ratio": {"optimize": [3, 50], "step": 1}}}, False),
    ({"transmission": {"type": "gearbox", "ratio": []}}, False),
    ({"transmission": {"type": "gearbox", "catalog": "gearboxes.yaml"}}, True),
    ({"transmission": "gearbox"}, False),
    ({"transmission": {"type": "chain"}}, False),
    ({"limits": {"thermal_speed": "rms", "torque_margin": "10 %"}}, True),
    ({"limits": {"thermal_speed": "median"}}, False),
    ({"colour": "red"}, False),
])
def test_schema_and_loader_agree_on_the_forms(extra: dict, accepted: bool) -> None:
    data = {**DESIGN, **extra}
    assert model_accepts("design", data) is accepted
    assert (schema_errors("design", data) == []) is accepted


@pytest.mark.parametrize(("task", "accepted"), [
    ({"displacement": "90 deg", "duration": "minimize", "return": True}, True),
    ({"displacement": "200 mm", "duration": 0.3, "dwell": "0.1 s"}, True),
    ({"displacement": "90 deg", "duration": "0.2 s", "return": "yes"}, False),
    ({"displacement": "90 deg", "duration": "0.2 s", "return_move": True}, False),
    ({"displacement": "90 deg"}, False),
])
def test_task_forms(task: dict, accepted: bool) -> None:
    data = {**DESIGN, "task": task}
    assert model_accepts("design", data) is accepted
    assert (schema_errors("design", data) == []) is accepted


MOTOR = {"id": "m", "inertia": "0.1 kg*cm^2", "continuous_torque": "0.32 N*m",
         "peak_torque": "0.95 N*m", "rated_speed": "3000 rpm"}


@pytest.mark.parametrize(("curve", "accepted"), [
    ([["0 rpm", "0.95 N*m"], ["3000 rpm", "0.95 N*m"]], True),
    ([[0, 0.95], {"speed": 314.159, "torque": 0.9}], True),
    ([{"speed": 0, "torque": 0.95}, {"speed": 300, "torque": 0.9}], True),
    ([[0, 0.95, 1.0], [300, 0.9]], False),
    ([{"speed": 0}], False),
    ([{"speed": 0, "torque": 1, "power": 3}], False),
])
def test_curve_points_as_pairs_or_mappings(curve: list, accepted: bool) -> None:
    data = {"catalog": "c", "motors": [{**MOTOR, "intermittent_curve": curve}]}
    assert model_accepts("catalog", data) is accepted
    assert (schema_errors("catalog", data) == []) is accepted


def _models(model: type[BaseModel], seen: set[type[BaseModel]]) -> None:
    """Every pydantic model reachable from ``model``'s fields."""
    if model in seen:
        return
    seen.add(model)
    for info in model.model_fields.values():
        stack = [info.annotation]
        while stack:
            tp = stack.pop()
            if isinstance(tp, type) and issubclass(tp, BaseModel):
                _models(tp, seen)
            stack.extend(typing.get_args(tp))


@pytest.mark.parametrize("kind", sorted(SCHEMAS))
def test_every_model_field_is_in_the_schema(kind: str) -> None:
    """Derived, not copied: a field added to a model appears in the schema by itself."""
    build, root = SCHEMAS[kind]
    schema = build()
    definitions = {name: d for name, d in schema.get("$defs", {}).items()}
    definitions[root.__name__] = schema
    models: set[type[BaseModel]] = set()
    _models(root, models)
    assert root in models and len(models) >= 2
    for model in models:
        properties = definitions[model.__name__]["properties"]
        names = {info.alias or name for name, info in model.model_fields.items()}
        assert names == set(properties), model.__name__
