"""The documents room: derivations as plain data in the lecture's order, rendered through
the Jinja2 templates (text, Markdown, LaTeX), handouts compiled to PDF, notebooks run/exported.

May import model, notation, kinematics and plot (figures in handouts).
"""

from dhsym._lazy import lazy_exports

__getattr__, __dir__ = lazy_exports(
    __name__,
    {
        "build_notebook": "notebooks",
        "builtin_dir": "dhsym.notation.templates",
        "check_log": "latex",
        "compile_pdf": "latex",
        "Derivation": "derivation",
        "derive": "derivation",
        "derive_dynamics": "equations_of_motion",
        "derive_inverse": "inverse_kinematics",
        "derive_jacobian": "velocity_kinematics",
        "derive_singularities": "velocity_kinematics",
        "document": "documents",
        "execute_notebook": "notebooks",
        "export_notebook": "notebooks",
        "general_link": "derivation",
        "loader": "dhsym.notation.templates",
        "render": "rendering",
        "render_derivation": "documents",
        "render_handout": "documents",
        "run_latex": "latex",
        "LatexRun": "latex",
        "tex_available": "latex",
        "write_handout": "documents",
    },
)

__all__ = [
    "Derivation",
    "LatexRun",
    "build_notebook",
    "builtin_dir",
    "check_log",
    "compile_pdf",
    "derive",
    "derive_dynamics",
    "derive_inverse",
    "derive_jacobian",
    "derive_singularities",
    "document",
    "execute_notebook",
    "export_notebook",
    "general_link",
    "loader",
    "render",
    "render_derivation",
    "render_handout",
    "run_latex",
    "tex_available",
    "write_handout",
]
