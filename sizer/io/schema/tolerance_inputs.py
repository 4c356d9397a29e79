"""The ``tolerances:`` section of a design (``sizer size --robust``, docs/robust.md): per
input a text (``20 %`` relative, ``0.05 kg*m^2`` absolute, uniform over +-that) or a
mapping giving the distribution.

The values stay text here: whether a value is a fraction or a quantity of the input's
kind, and its bounds, are decided by the loader (sizer.io.loader ``_tolerances``), which
knows the input and the axis.
"""

from dataclasses import dataclass
from typing import Annotated, Any, Literal, Self

from pydantic import Field, GetCoreSchemaHandler, GetJsonSchemaHandler, model_validator
from pydantic.json_schema import JsonSchemaValue
from pydantic_core import PydanticCustomError, core_schema

from sizer.io.schema.inputs_base import Strict, Text


class ToleranceInput(Strict):
    """One input's tolerance: uniform over +-``plus_minus``, or normal with ``sigma``,
    truncated (and cornered) at ``truncate`` standard deviations."""

    distribution: Literal["uniform", "normal"] = Field(
        "uniform", description="uniform over +-plus_minus (default), or normal with sigma")
    plus_minus: Text | None = Field(
        None, description="uniform: the half-width, relative ('20 %') or absolute in the "
                          "input's unit ('0.05 kg*m^2')")
    sigma: Text | None = Field(
        None, description="normal: the standard deviation, relative ('5 %') or absolute")
    truncate: float | None = Field(
        None, gt=0.0, le=10.0,
        description="normal: truncated at this many sigmas, where its corners are "
                    "(default 3)")

    @model_validator(mode="after")
    def _fields_of_the_distribution(self) -> Self:
        if self.distribution == "uniform":
            if self.plus_minus is None:
                raise PydanticCustomError("missing", "required field is missing",
                                          {"at": ("plus_minus",)})
            for name in ("sigma", "truncate"):
                if getattr(self, name) is not None:
                    raise PydanticCustomError(
                        "not_uniform", "only for 'distribution: normal' (a uniform "
                        "tolerance gives plus_minus)", {"at": (name,)})
        else:
            if self.sigma is None:
                raise PydanticCustomError("missing", "required field is missing",
                                          {"at": ("sigma",)})
            if self.plus_minus is not None:
                raise PydanticCustomError(
                    "not_normal", "not for 'distribution: normal': give sigma (and "
                    "truncate)", {"at": ("plus_minus",)})
        return self


@dataclass(frozen=True)
class _TextForm:
    """``20 %`` (or a number) is ``{plus_minus: 20 %}``; in the JSON Schema, a string or
    number beside the mapping."""

    def _as_mapping(self, value: Any) -> Any:
        if isinstance(value, str | int | float) and not isinstance(value, bool):
            return {"plus_minus": value}
        return value

    def __get_pydantic_core_schema__(self, source: Any,
                                     handler: GetCoreSchemaHandler) -> core_schema.CoreSchema:
        return core_schema.no_info_before_validator_function(self._as_mapping,
                                                             handler(source))

    def __get_pydantic_json_schema__(self, schema: core_schema.CoreSchema,
                                     handler: GetJsonSchemaHandler) -> JsonSchemaValue:
        text = {"type": ["string", "number"],
                "description": "uniform over +-this: relative ('20 %') or absolute in the "
                               "input's unit ('0.05 kg*m^2')"}
        return {"anyOf": [text, handler(schema)]}


ToleranceValue = Annotated[ToleranceInput, _TextForm()]
"""A tolerance: its text form or its mapping."""
