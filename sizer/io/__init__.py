"""Reading the input files in one pass: YAML with line numbers (yaml_source), validation
against the file schema (sizer.io.schema, pydantic), then the SI domain objects of
sizer.model, which knows nothing of the schema."""

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
