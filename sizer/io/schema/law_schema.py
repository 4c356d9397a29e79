"""A law entry of the input files: a spec text, or a mapping for a law defined by data;
its check and its JSON schema."""

from __future__ import annotations

from typing import Annotated, Any

from pydantic import BeforeValidator, WithJsonSchema

from sizer.errors import UserError
from sizer.io.schema.inputs_base import show_value as _show
from sizer.laws.cam_interpolation import INTERPOLATIONS
from sizer.laws.data_spec import DATA_LAW_KINDS


def _data_law_schema() -> dict[str, Any]:
    return {"type": "object", "required": ["kind"],
            "properties": {"kind": {"enum": list(DATA_LAW_KINDS)},
                           "units": {"type": "object",
                                     "properties": {"time": {"type": "string"},
                                                    "position": {"type": "string"}},
                                     "additionalProperties": False},
                           "interpolation": {
                               "enum": list(INTERPOLATIONS),
                               "description": "cam_table: the controller's interpolation "
                                              "of the points (absent: a spline fitted by "
                                              "order)"},
                           "span": {
                               "type": "array", "minItems": 2, "maxItems": 2,
                               "items": {"type": "number"},
                               "description": "cam_table, cam_segments: [x0, x1], the "
                                              "rows (segment ends) of the file between "
                                              "which the law is read, in the file's "
                                              "master units; the law is normalized to "
                                              "their stroke and duration (one move of "
                                              "an exported cycle)"}},
            "description": "a law defined by data (docs/data-laws.md), e.g. {kind: "
                           "cubic_spline, points: [[0, 0], [0.4, 0.3], [1, 1]]}"}


LAW_SPEC_SCHEMA: dict[str, Any] = {"anyOf": [
    {"type": "string",
     "description": "a motion law spec like 'cycloidal', 'poly5', "
                    "'trapezoidal(alpha=1/3)' or 'double_s(alpha=auto, beta=1/4)'"},
    _data_law_schema()]}


def check_law_spec(text: Any) -> str:
    """Validate a law spec (``auto`` shape parameters allowed); ValueError if invalid.

    Beyond reading it (:func:`sizer.laws.law_choice`) it rejects unknown parameter names
    and numbers out of a parameter's range, and builds the law when it is fixed.
    """
    from sizer.laws import AUTO, law_choice
    from sizer.laws.data_spec import data_spec_text

    if isinstance(text, dict):
        # a law defined by data: the design loader has built it (its files are relative
        # to the design's folder) and passes its text; a mapping here is only made text
        try:
            return data_spec_text(text)
        except UserError as error:
            raise ValueError(error.message) from None
    if not isinstance(text, str):
        raise ValueError(f"expected a law spec like 'cycloidal' or 'trapezoidal(alpha=1/3)', "
                         f"got {_show(text)}")
    try:
        choice = law_choice(text)
        family, values = choice.family, dict(choice.values)
        names = {p.name: p for p in family.parameters}
        unknown = sorted(set(values) - set(names))
        if unknown:
            raise UserError(f"{family.law_id}: unknown parameter(s) {', '.join(unknown)}; "
                            f"parameters: {', '.join(names) or 'none'}")
        for key, value in values.items():
            if value != AUTO:
                names[key].validate(family.law_id, float(value))
            elif (refusal := names[key].auto_refusal(family.law_id)) is not None:
                raise UserError(refusal)
        if choice.is_fixed:  # an open shaped law is built by its design (sizer.io.data_laws)
            _ = choice.law
    except UserError as error:
        raise ValueError(error.message) from None
    except (ArithmeticError, ValueError, TypeError) as error:  # huge numbers and the like
        raise ValueError(f"invalid law spec {_show(text)}: {error}") from None
    return text.strip()


LawSpecText = Annotated[
    str,
    BeforeValidator(check_law_spec),
    WithJsonSchema(LAW_SPEC_SCHEMA),
]
