"""Validate catalog files: the schema, then the sanity checks, with every finding listed.

A loader stops at the first mistake; the validator goes on, so a CI run shows them all:

    report = validate_catalogs(["catalogs/yaskawa-sgm7j.yaml", "my-motors.yaml"])
    report.findings     -> [Finding(file, line, field, message, severity), ...]
    report.unreadable   -> [UserError, ...]  (missing file, not UTF-8, broken YAML, ...)

Duplicate motor ids are findings within a file and across the files validated together
(they would clash when loaded together). A file named twice is validated once. Each motor
that loading accepts is also checked for consistency (:mod:`sizer.catalog_tools.consistency`,
warnings), and each file's figures are counted by grade (``report.grades``).
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from pydantic import ValidationError

from sizer.catalog_tools.consistency import NOT_CHECKED, inconsistencies
from sizer.catalog_tools.findings import Finding, Severity
from sizer.catalog_tools.grade_mix import GradeMix, grade_mix, total
from sizer.errors import UserError
from sizer.io.loader import resolve_catalog
from sizer.io.motor_rules import check_motor, motor_of
from sizer.io.schema.inputs import CatalogFile, DriveCatalogFile, MotorInput
from sizer.io.schema.transmission_inputs import GearboxCatalogFile
from sizer.io.validation import all_problems
from sizer.io.yaml_source import YamlSource, format_path, read_yaml


@dataclass
class ValidationReport:
    """The findings of the readable files and the errors of the unreadable ones."""

    files: list[str] = field(default_factory=list)
    findings: list[Finding] = field(default_factory=list)
    unreadable: list[UserError] = field(default_factory=list)
    motors: int = 0
    """How many motor entries the readable files hold."""
    drives: int = 0
    """How many drive entries the readable drive catalogs hold."""
    gearboxes: int = 0
    """How many gearbox series the readable gearbox catalogs hold."""
    grades: dict[str, GradeMix] = field(default_factory=dict)
    """Each readable file's figures per grade (A, B, C, D, ungraded)."""
    not_checked: tuple[str, ...] = NOT_CHECKED
    """The consistency checks that cannot run, and why."""

    @property
    def total_grades(self) -> GradeMix:
        """The figures of every file per grade."""
        return total(self.grades.values())

    @property
    def exit_code(self) -> int:
        """0 clean, 1 with findings, 2 when a file could not be read at all."""
        if self.unreadable:
            return 2
        return 1 if self.findings else 0


@dataclass(frozen=True)
class _Seen:
    file: str
    line: int | None


def validate_catalogs(references: Iterable[str | Path], base: Path | None = None
                      ) -> ValidationReport:
    """Validate catalog files (paths relative to ``base``, default the working directory,
    or bundled catalog names)."""
    base = base if base is not None else Path.cwd()
    report = ValidationReport()
    ids: dict[str, _Seen] = {}
    done: set[Path] = set()
    for reference in references:
        try:
            path = resolve_catalog(reference, base)
        except UserError as error:
            report.unreadable.append(error.located(file=str(reference)))
            continue
        key = path.resolve()
        if key in done:
            continue
        done.add(key)
        shown = _shown(path, base)
        try:
            source = read_yaml(path)
        except UserError as error:
            report.unreadable.append(UserError(error.message, file=shown, line=error.line,
                                               field=error.field))
            continue
        source.file = shown
        report.files.append(shown)
        report.grades[shown] = grade_mix(source.data)
        report.findings += _validate_source(source, ids, report)
    report.findings.sort(key=Finding.sort_key)
    return report


def _shown(path: Path, base: Path) -> str:
    """The path relative to ``base`` when it is inside it (as a user would type it)."""
    try:
        return str(path.relative_to(base))
    except ValueError:
        return str(path)


def _validate_source(source: YamlSource, ids: dict[str, _Seen],
                     report: ValidationReport) -> list[Finding]:
    file = source.file or "?"
    findings: list[Finding] = []

    def finding(path: tuple[Any, ...], message: str, severity: Severity = "error") -> None:
        findings.append(Finding(file, source.line_of(path), format_path(path) or None,
                                message, severity))

    data = source.data
    if isinstance(data, dict) and "drives" in data and "motors" not in data:
        return _validate_drives(source, finding, report, findings)
    if isinstance(data, dict) and "gearboxes" in data and "motors" not in data:
        return _validate_gearboxes(source, report, findings)
    try:
        CatalogFile.model_validate(source.data)
    except ValidationError as error:
        for problem in all_problems(error, CatalogFile, source):
            findings.append(Finding(file, problem.line, problem.field, problem.message))
    except RecursionError:
        finding((), "the data is nested too deeply")
        return findings
    motors = data.get("motors")
    if not isinstance(motors, list):
        return findings  # the schema said so
    if not motors:
        finding(("motors",), "the catalog has no motors")
    report.motors += len(motors)
    manufacturer = _text(data.get("manufacturer"))
    default_source = _text(data.get("source")) or _default_citation(data)
    for index, raw in enumerate(motors):
        at = ("motors", index)
        if isinstance(raw, dict):
            _check_id(raw.get("id"), (*at, "id"), source, ids, finding)
        try:
            item = MotorInput.model_validate(raw)
        except (ValidationError, RecursionError):
            continue  # reported by the schema pass above
        motor = motor_of(item)
        problems = check_motor(motor, manufacturer=manufacturer, source=default_source,
                               given=raw)
        for rule_problem in problems:
            finding((*at, *rule_problem.path), rule_problem.message, rule_problem.severity)
        if not any(problem.at_load for problem in problems):  # refused motors: no more
            for path, message in inconsistencies(motor):
                finding((*at, *path), message, "warning")
    return findings


def _schema_findings(model: Any, source: YamlSource, findings: list[Finding]) -> None:
    """Every problem of the file against its schema ``model``, as findings."""
    try:
        model.model_validate(source.data)
    except ValidationError as error:
        for problem in all_problems(error, model, source):
            findings.append(Finding(source.file or "?", problem.line, problem.field,
                                    problem.message))


def _validate_gearboxes(source: YamlSource, report: ValidationReport,
                        findings: list[Finding]) -> list[Finding]:
    """A gearbox catalog (``gearboxes:`` without ``motors:``): its schema, provenance
    included."""
    _schema_findings(GearboxCatalogFile, source, findings)
    series = source.data.get("gearboxes")
    report.gearboxes += len(series) if isinstance(series, list) else 0
    return findings


def _validate_drives(source: YamlSource, finding: Any, report: ValidationReport,
                     findings: list[Finding]) -> list[Finding]:
    """A drive catalog (``drives:`` without ``motors:``): its schema (currents, voltage
    levels) and unique drive ids. Which motors a drive suits is checked when a design
    pairs them (it needs the motors)."""
    file = source.file or "?"
    _schema_findings(DriveCatalogFile, source, findings)
    drives = source.data.get("drives")
    if isinstance(drives, list):
        report.drives += len(drives)
        seen: dict[str, _Seen] = {}
        for index, raw in enumerate(drives):
            value = raw.get("id") if isinstance(raw, dict) else None
            if isinstance(value, str) and value.strip():
                at = ("drives", index, "id")
                earlier = seen.get(value.strip())
                if earlier is not None:
                    finding(at, f"duplicate drive id {value.strip()!r} (first defined at "
                                f"line {earlier.line})")
                else:
                    seen[value.strip()] = _Seen(file, source.line_of(at))
    return findings


def _check_id(value: Any, path: tuple[Any, ...], source: YamlSource, ids: dict[str, _Seen],
              finding: Any) -> None:
    if isinstance(value, bool) or not isinstance(value, str | int | float):
        return  # the schema reports it
    motor_id = str(value).strip()
    if not motor_id:
        return
    line = source.line_of(path)
    earlier = ids.get(motor_id)
    if earlier is None:
        ids[motor_id] = _Seen(source.file or "?", line)
        return
    where = earlier.file + (f":{earlier.line}" if earlier.line is not None else "")
    finding(path, f"duplicate motor id {motor_id!r} (first defined at {where})")


def _text(value: Any) -> str | None:
    if isinstance(value, str):
        return value
    if isinstance(value, int | float) and not isinstance(value, bool):
        return str(value)
    return None


def _default_citation(data: dict[str, Any]) -> str | None:
    """The text of the catalog's default source (``sources:`` and ``default_source:``)."""
    sources, key = data.get("sources"), data.get("default_source")
    if not isinstance(sources, dict) or not isinstance(key, str):
        return None
    entry = sources.get(key.strip())
    return _text(entry.get("text")) if isinstance(entry, dict) else None
