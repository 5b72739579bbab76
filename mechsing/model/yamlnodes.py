"""The old home of the located YAML values: :mod:`mechsing.yamlnodes` (a leaf, below the
model and the formats) holds them; their names stay importable from here."""

from mechsing.errors import YAMLReadError
from mechsing.yamlnodes import (
    MAX_FILE_BYTES,
    MAX_ITEMS,
    YMap,
    YScalar,
    YSeq,
    YValue,
    read_yaml_text,
)

__all__ = [
    "MAX_FILE_BYTES",
    "MAX_ITEMS",
    "YAMLReadError",
    "YMap",
    "YScalar",
    "YSeq",
    "YValue",
    "read_yaml_text",
]
