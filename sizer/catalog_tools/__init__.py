"""Catalog tooling: sanity checks, validation with every finding, CSV import, listings.

Pure functions returning plain data (no printing, no typer or rich); ``sizer catalog ...``
in :mod:`sizer.cli.catalog_command` is a thin layer over them.

    validate_catalogs(["motors.yaml"])        -> ValidationReport (findings, unreadable files)
    import_csv("vendor.csv", maps, ...)       -> ImportedCatalog; .yaml() is the catalog text
    catalog_summaries(), catalog_entries(..)  -> what ``sizer catalog list`` shows
    find_motor("SGM7J-02A")                   -> MotorEntry (fields as written, SI motor)
"""

from sizer.catalog_tools.csv_import import (
    CatalogImportError,
    ColumnMap,
    ImportedCatalog,
    import_csv,
    parse_column_map,
)
from sizer.catalog_tools.findings import Finding
from sizer.catalog_tools.listing import (
    CatalogSummary,
    MotorEntry,
    catalog_entries,
    catalog_summaries,
    find_motor,
    summarize_catalog,
)
from sizer.catalog_tools.validate import ValidationReport, validate_catalogs
from sizer.io.motor_rules import MotorProblem, check_motor

__all__ = [
    "CatalogImportError",
    "CatalogSummary",
    "ColumnMap",
    "Finding",
    "ImportedCatalog",
    "MotorEntry",
    "MotorProblem",
    "ValidationReport",
    "catalog_entries",
    "catalog_summaries",
    "check_motor",
    "find_motor",
    "import_csv",
    "parse_column_map",
    "summarize_catalog",
    "validate_catalogs",
]
