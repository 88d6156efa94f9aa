"""The notation room: lecture printers (C12, S23, c1), formula layout and line breaking,
the one view of a DH table, escaping of user text for LaTeX and Markdown, and the one
template renderer (:mod:`~dhsym.notation.templates`) of documents, feedback and code.

May import :mod:`dhsym.model`; never kinematics, documents or checking.
"""

from dhsym._lazy import lazy_exports

__getattr__, __dir__ = lazy_exports(
    __name__,
    {
        "angle_label": "printers",
        "as_math": "layout",
        "Equation": "layout",
        "escape_latex": "escape",
        "escape_markdown": "escape",
        "format_angle": "printers",
        "LegendEntry": "printers",
        "Math": "layout",
        "matrix_block": "layout",
        "MatrixBlock": "layout",
        "Notation": "printers",
        "Sentence": "layout",
        "sentence": "layout",
        "table_latex": "tables",
        "table_markdown": "tables",
        "TeX": "escape",
        "TrigStyle": "printers",
    },
)

__all__ = [
    "Equation",
    "LegendEntry",
    "Math",
    "MatrixBlock",
    "Notation",
    "Sentence",
    "TeX",
    "TrigStyle",
    "angle_label",
    "as_math",
    "escape_latex",
    "escape_markdown",
    "format_angle",
    "matrix_block",
    "sentence",
    "table_latex",
    "table_markdown",
]
