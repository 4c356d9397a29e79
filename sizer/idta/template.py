"""The names of IDTA 02021 version 1.0.1 (admin-shell-io/submodel-templates,
published/Sizing of Power Drive Trains/1/0/1/IDTA 02021-1-0-1_Template_Sizing of Power
Drive Trains.json): the idShorts and semantic IDs sizer reads and writes."""

from __future__ import annotations

TEMPLATE = "IDTA 02021-1-0-1 Sizing of Power Drive Trains"
PREFIX = "https://admin-shell.io/idta/PowerDriveTrainSizing/"
SUBMODEL_SEMANTIC_ID = PREFIX + "1/0"
SUBMODEL_ID_SHORT = "PowerDriveTrainSizing"


def semantic_id(name: str) -> str:
    """The template's semantic ID of the concept ``name`` (``MessageText``)."""
    return f"{PREFIX}{name}/1/0"


ROTATIVE_SECTION = semantic_id("RotativeMotionPatternSection")
LINEAR_SECTION = semantic_id("LinearMotionPatternSection")

MECHANISMS = ("Fan", "Pump", "RotraryTable", "ChainConveyor", "BeltConveyor", "RollerConveyor",
              "BeltDrive", "TravelingDrive", "RackDrive", "SpindleDrive")
"""The entities of TransformationMechanism, as the template spells them (``RotraryTable``:
the template's spelling of a rotary table, its semantic ID too)."""

ALIASES = {"RotaryTable": "RotraryTable"}
"""Spellings accepted for a template name: the corrected ``RotaryTable``."""

ECLASS = {"ManufacturerName": "0173-1#02-AAO677#002",
          "ManufacturerArticleNumber": "0173-1#02-AAO676#003",
          "ManufacturerProductDesignation": "0173-1#02-AAW338#001",
          "ManufacturerOrderCode": "0173-1#02-AAO227#002"}
"""Elements whose semantic ID is an ECLASS IRDI (the template writes ``ManufacturerOrderCode``'s
with a leading space, ``" 0173-1#02-AAO227#002"``: sizer writes it without)."""

RESULT_SEMANTIC_IDS = {"InternalMomentOfIntertia": semantic_id("InternalMomentOfInertia")}
"""Result elements whose semantic ID is not ``PREFIX + idShort``: the template's idShort
``InternalMomentOfIntertia`` is misspelt, its semantic ID is not."""

PROJECT_INFORMATION_SEMANTIC_ID = PREFIX + "SizingProjectInformation1/0"
"""SizingProjectInformation's semantic ID as the template writes it (no '/' before '1/0')."""
