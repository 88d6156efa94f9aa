"""The model room: a robot as data — joint kinds, exact entries, DH rows and tables, table
files (YAML), the whitelist parser for typed text, and the built-in robots.

May import :mod:`dhsym.errors` only (and sympy, PyYAML); every other room builds on it.
"""

from dhsym._lazy import lazy_exports

__getattr__, __dir__ = lazy_exports(
    __name__,
    {
        "AngleSnap": "angles",
        "AngleUnit": "kinds",
        "as_expr": "entries",
        "builtin_names": "library",
        "builtin_table": "library",
        "Convention": "kinds",
        "DHRow": "table",
        "DHTable": "table",
        "dump_table": "tablefile",
        "Elementary": "table",
        "exact_decimal": "entries",
        "JointType": "kinds",
        "load_table": "library",
        "normalize_name": "parsing",
        "parse_expression": "parsing",
        "parse_number_list": "parsing",
        "ParseLimits": "parsing",
        "planar_chain": "library",
        "read_table": "tablefile",
        "read_table_text": "tablefile",
        "symbol": "parsing",
        "to_radians": "entries",
    },
)

__all__ = [
    "AngleSnap",
    "AngleUnit",
    "Convention",
    "DHRow",
    "DHTable",
    "Elementary",
    "JointType",
    "ParseLimits",
    "as_expr",
    "builtin_names",
    "builtin_table",
    "dump_table",
    "exact_decimal",
    "load_table",
    "normalize_name",
    "parse_expression",
    "parse_number_list",
    "planar_chain",
    "read_table",
    "read_table_text",
    "symbol",
    "to_radians",
]
