"""The plain data of a derivation: frozen dataclasses read by the templates.

:func:`dhsym.explain.derivation.derive` fills these; :mod:`dhsym.explain.rendering`
arranges them. Every formula is a :class:`~dhsym.notation.layout.Math`, printed twice
(LaTeX and plain text). The public names are re-exported by :mod:`dhsym.explain.derivation`.

Examples
--------
>>> from dhsym.notation.escape import TeX
>>> from dhsym.notation.layout import Math, Term
>>> c12 = Math(TeX("C_{12}"), "C12")
>>> Identity((Term("+", Math(TeX("C_1 C_2"), "C1*C2")),), c12).result.text
'C12'
"""

from __future__ import annotations

from dataclasses import dataclass, field

from dhsym.model.table import Convention
from dhsym.notation.layout import (
    LATEX_WIDTH,
    Equation,
    LegendLine,
    Math,
    MatrixBlock,
    Run,
    Term,
    math_width,
)
from dhsym.notation.tables import TableCell

__all__ = [
    "Block",
    "BranchData",
    "Derivation",
    "Document",
    "DynamicsDerivation",
    "EnergyData",
    "Factor",
    "FactorData",
    "GeneralLink",
    "IKCheck",
    "IKDerivation",
    "IKPart",
    "IKStepData",
    "Identity",
    "JacobianColumnData",
    "JacobianDerivation",
    "LinkData",
    "NEStepData",
    "NumericCheck",
    "SingularityDerivation",
    "Step",
    "TableCell",
    "TableData",
]


class Document:
    """What every derivation shares: it renders itself through the templates of its ``kind``.

    ``kind`` names the templates (``derivation`` for forward kinematics, ``jacobian``,
    ``singularities``, ``ik``): ``<kind>.txt.j2``, ``<kind>.md.j2`` and ``<kind>.tex.j2``.
    """

    kind = "derivation"
    convention: str
    legend: tuple[LegendLine, ...]
    width: float

    @property
    def modified(self) -> bool:
        """True for the modified (Craig) convention."""
        return self.convention == Convention.MODIFIED.value

    @property
    def legend_columns(self) -> int:
        """How many ``abbreviation = meaning`` pairs fit side by side on a page (1 to 3)."""
        w = max(
            (math_width(e.abbrev.latex) + math_width(e.meaning.latex) + 3 for e in self.legend),
            default=0.0,
        )
        return 3 if 3 * w + 4 <= self.width else (2 if 2 * w + 2 <= self.width else 1)

    def to_text(self) -> str:
        """The derivation as terminal text."""
        from .rendering import render

        return render(self, "text")

    def to_markdown(self) -> str:
        """The derivation as Markdown with ``$…$``/``$$…$$`` math."""
        from .rendering import render

        return render(self, "markdown")

    def to_latex(self) -> str:
        """The derivation as a LaTeX fragment (needs ``amsmath``)."""
        from .rendering import render

        return render(self, "latex")

    def _repr_markdown_(self) -> str:
        return self.to_markdown()

    def _repr_latex_(self) -> str:
        return self.to_latex()

    def _latex(self, printer: object) -> str:
        """``sympy.latex(derivation)``: the LaTeX fragment."""
        return self.to_latex()

    def __str__(self) -> str:
        return self.to_text()


@dataclass(frozen=True)
class Identity:
    """A sum-angle identity used in a product: ``terms`` sum to ``result``."""

    terms: tuple[Term, ...]
    result: Math
    wide: bool = False  # too long for running text: display it
    split: bool = False  # too long for one display line: result on the next line


@dataclass(frozen=True)
class Factor:
    """One elementary transform of the general link matrix (Mohan, Lecture 9,
    Transformations 1–4)."""

    kind: str
    axis: str
    value: Math
    block: MatrixBlock


@dataclass(frozen=True)
class GeneralLink:
    """The convention's link matrix with general parameters, factor by factor."""

    parameters: tuple[Math, ...]
    word: Math
    factors: tuple[Factor, ...]
    result: MatrixBlock
    legend: tuple[LegendLine, ...]


@dataclass(frozen=True)
class Step:
    """``^iT_k = ^iT_{k-1} ^{k-1}T_k`` and the identities that combine angles in it."""

    block: MatrixBlock
    identities: tuple[Identity, ...]
    final: bool


@dataclass(frozen=True)
class TableData:
    """The DH table with the convention's headers (same cells as ``table_latex``)."""

    heads: tuple[Math, ...]
    rows: tuple[tuple[TableCell, ...], ...]
    degrees: bool
    values: tuple[tuple[Math, Math], ...]
    variables: tuple[Math, ...]


@dataclass(frozen=True)
class NumericCheck:
    """The result evaluated at one configuration, with the table's values."""

    q: tuple[tuple[Math, Math], ...]
    rows: tuple[tuple[Math, ...], ...]


@dataclass(frozen=True)
class Derivation(Document):
    """A whole derivation as plain data; render it with :mod:`dhsym.explain.rendering`.

    Strings are trusted LaTeX (:class:`~dhsym.notation.escape.TeX`) or plain text;
    ``name``, ``source`` and ``notes`` are user text, escaped by the templates.
    """

    name: str
    key: str
    source: str
    notes: str
    convention: str
    n: int
    compact: bool
    numeric: bool
    table: TableData
    general: GeneralLink | None
    links: tuple[MatrixBlock, ...]
    products: tuple[Step, ...]
    result: MatrixBlock
    inverse: bool
    legend: tuple[LegendLine, ...]
    check: NumericCheck | None = field(default=None)
    width: float = LATEX_WIDTH
    warnings: tuple[str, ...] = ()  # how the reader read the input (decimal angles snapped)


# --- the Jacobian -----------------------------------------------------------------------------


@dataclass(frozen=True)
class JacobianColumnData:
    """Column ``J_i`` built as the lecture builds it.

    ``axis`` is ``z_a`` (the joint's axis, ``a`` = ``i − 1`` in the standard convention,
    ``i`` in the modified one), ``lever`` is ``o_e − o_a`` (revolute joints only), ``column``
    is ``J_i`` (``z_a × (o_e − o_a)`` over ``z_a``, or ``z_a`` over 0); ``rate`` is the
    factor of a table entry that is a multiple of its variable (else None);
    ``side_by_side`` is True when ``axis`` and ``lever`` fit on one line.
    """

    index: int
    revolute: bool
    variable: Math
    axis_label: Math
    origin_label: Math
    point_label: Math
    axis: MatrixBlock
    lever: MatrixBlock | None
    column: MatrixBlock
    rate: Math | None
    side_by_side: bool


@dataclass(frozen=True)
class JacobianDerivation(Document):
    """The geometric Jacobian of a robot, column by column, then the whole matrix.

    ``frame`` is the frame the vectors are written in, ``point`` the frame whose origin's
    velocity the linear part gives; ``result`` is ``J`` (its ``wide`` form refers to the
    columns above).
    """

    kind = "jacobian"

    name: str
    key: str
    convention: str
    n: int
    frame: Math
    point: Math
    columns: tuple[JacobianColumnData, ...]
    result: MatrixBlock
    legend: tuple[LegendLine, ...]
    width: float = LATEX_WIDTH


# --- singularities -----------------------------------------------------------------------------


@dataclass(frozen=True)
class Block:
    """A block whose determinant is a factor (``J_{11}``, ``J_{22}``), in frame ``frame``.

    ``matrix`` is None when the block is too wide to print on a line.
    """

    label: Math
    frame: Math
    matrix: MatrixBlock | None
    determinant: Equation


@dataclass(frozen=True)
class FactorData:
    """One named factor of the determinant and the configurations where it vanishes.

    ``kind`` is ``wrist``, ``elbow``, ``shoulder``, ``boundary`` or ``constant``; ``title`` and
    ``description`` are plain words; ``zeros`` are equations ``θ_5 = 0``.
    """

    kind: str
    title: str
    description: str
    factor: Math
    power: int
    zeros: tuple[Math, ...]


@dataclass(frozen=True)
class SingularityDerivation(Document):
    """The Jacobian determinant (or ``det(J Jᵀ)``) factored, and its singular factors named.

    ``method`` is ``blocks`` (``J`` at the wrist centre is block triangular), ``wrist``
    (a wrist alone), ``position`` (the position rows of ``J``), ``rows`` (the non-zero rows),
    ``whole`` (the whole 6×6 ``J`` of an arm without a spherical wrist, at the wrist point
    in a middle frame) or ``manipulability`` (the Cauchy–Binet sum); ``point`` names the
    reference point.
    """

    kind = "singularities"

    name: str
    key: str
    convention: str
    n: int
    method: str
    point: str
    measure: Math
    blocks: tuple[Block, ...]
    determinant: Equation
    factors: tuple[FactorData, ...]
    legend: tuple[LegendLine, ...]
    width: float = LATEX_WIDTH


# --- inverse kinematics --------------------------------------------------------------------------


@dataclass(frozen=True)
class BranchData:
    """A sign ``σ_j = ±1`` of the derivation, what it decides (``role``) and what it means."""

    symbol: Math
    role: str
    joint: int
    sentence: tuple[Run, ...]


@dataclass(frozen=True)
class IKStepData:
    """One step: the sentence, the equation it solves (if any) and what it defines.

    ``results`` are ``lhs = rhs`` equations split into lines (several when consecutive
    steps share one sentence, as ``c_x``, ``c_y``, ``c_z``); ``singular`` the values used
    instead at a wrist singularity.
    """

    sentence: tuple[Run, ...]
    equation: Equation | None
    results: tuple[Equation, ...]
    branch: BranchData | None
    singular: tuple[Equation, ...]


@dataclass(frozen=True)
class IKPart:
    """A part of the derivation: the wrist centre, the position or the orientation."""

    part: str
    title: str
    steps: tuple[IKStepData, ...]


@dataclass(frozen=True)
class IKCheck:
    """Every solution of one pose: the configuration it came from and the solutions found.

    Each solution is its branch name (runs of words and math) and its joint values
    (revolute joints in degrees when ``degrees``); ``position`` is True when only the
    position of the pose is solved (a positioning arm).
    """

    q: tuple[tuple[Math, Math], ...]
    variables: tuple[Math, ...]
    solutions: tuple[tuple[tuple[Run, ...], tuple[Math, ...]], ...]
    degrees: bool
    position: bool


@dataclass(frozen=True)
class IKDerivation(Document):
    """The closed-form inverse kinematics of a robot, step by step.

    ``structure`` says how the arm is decoupled (plain words); ``pose`` is the symbolic
    pose ``[n s a p; 0 0 0 1]``; ``count`` the number of branch combinations;
    ``singular_when`` the wrist singularity (``S_5 = 0``) where steps change (``singular``).
    """

    kind = "ik"

    name: str
    key: str
    convention: str
    n: int
    structure: str
    pose: MatrixBlock
    parts: tuple[IKPart, ...]
    branches: tuple[BranchData, ...]
    count: int
    singular_when: Math | None
    legend: tuple[LegendLine, ...]
    check: IKCheck | None = None
    width: float = LATEX_WIDTH


# --- dynamics ----------------------------------------------------------------------------------


@dataclass(frozen=True)
class EnergyData:
    """Link ``index``'s kinetic energy ``K_i`` and potential energy ``P_i``."""

    index: int
    kinetic: Equation
    potential: Equation


@dataclass(frozen=True)
class LinkData:
    """Link ``index``'s mass ``m_i``, centre of mass ``r_ci`` (in frame *i*) and inertia
    ``I_i`` about its centre of mass (axes of frame *i*)."""

    index: int
    mass: Equation
    centre: MatrixBlock
    inertia: MatrixBlock


@dataclass(frozen=True)
class NEStepData:
    """One line of the Newton–Euler table: vector ``name`` of link ``link`` in its frame.

    ``sweep`` is ``outward`` (velocities, accelerations, ``F``, ``N``) or ``inward``
    (``f``, ``n``, ``τ``); ``rule`` is the recursion it applies, in plain text.
    """

    sweep: str
    name: str
    link: int
    rule: str
    value: MatrixBlock


@dataclass(frozen=True)
class DynamicsDerivation(Document):
    """The equations of motion of a robot as the lecture derives them.

    The energies of each link, the entries ``M_ij`` (``i ≤ j``; M is symmetric), the
    nonzero Christoffel symbols ``c_ijk`` (``i ≤ j``; ``c_jik = c_ijk``), the matrix
    ``C(q, q̇)``, ``g_k`` and ``τ_k``; then the Newton–Euler table, outward then inward.
    ``links`` holds each link's mass, centre of mass and inertia, printed first.
    """

    kind = "dynamics"

    name: str
    key: str
    convention: str
    n: int
    gravity: tuple[Math, ...]
    energies: tuple[EnergyData, ...]
    inertia: tuple[Equation, ...]
    christoffel: tuple[Equation, ...]
    gravity_vector: tuple[Equation, ...]
    tau: tuple[Equation, ...]
    outward: tuple[NEStepData, ...]
    inward: tuple[NEStepData, ...]
    legend: tuple[LegendLine, ...]
    width: float = LATEX_WIDTH
    links: tuple[LinkData, ...] = ()
    coriolis: MatrixBlock | None = None  # C(q, q̇), after the Christoffel symbols
    #: the grouped inertial constants (``K1 = …``, ``gamma1 = …``) of the compact form
    constants: tuple[Equation, ...] = ()
    #: the numbers of the inertial symbols the compact form introduced (``m2 = 87/5``)
    parameter_values: tuple[Equation, ...] = ()
