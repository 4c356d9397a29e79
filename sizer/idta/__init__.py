"""IDTA 02021 "Sizing of Power Drive Trains" (the AAS submodel template, version 1.0.1): read
its ApplicationRequirements into a sizer design, write sizer's result as its SizingResult.

Pure data mapping: mappings and text in, mappings and text out; the command line
(:mod:`sizer.cli.idta_command`) reads and writes the files. See docs/idta-02021.md.
"""

from __future__ import annotations

from sizer.idta.read import IdtaDesign, read_motion_csv, read_submodel
from sizer.idta.write import PairResult, pair_from_record, sizing_result_submodel

__all__ = ["IdtaDesign", "PairResult", "pair_from_record", "read_motion_csv", "read_submodel",
           "sizing_result_submodel"]
