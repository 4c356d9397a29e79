"""Reading the input files: YAML with line numbers, validation, SI domain objects."""

from sizer.io.loader import (
    NOT_DEFAULT_CATALOGS,
    LoadedCatalog,
    bundled_catalogs,
    catalog_schema,
    default_catalogs,
    default_laws,
    design_schema,
    load_catalog,
    load_design,
    read_catalog,
    resolve_catalog,
)
from sizer.io.yaml_source import YamlSource, parse_yaml, read_yaml

__all__ = [
    "NOT_DEFAULT_CATALOGS",
    "LoadedCatalog",
    "YamlSource",
    "bundled_catalogs",
    "catalog_schema",
    "default_catalogs",
    "default_laws",
    "design_schema",
    "load_catalog",
    "load_design",
    "parse_yaml",
    "read_catalog",
    "read_yaml",
    "resolve_catalog",
]
