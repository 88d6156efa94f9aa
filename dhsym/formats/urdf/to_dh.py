"""A URDF chain as a DH table: the joint axes at home through the lectures' frame assignment.

:func:`import_urdf` follows the chain from the root link (or ``base``) to ``tip``, places
each moving joint's axis at the home pose (every joint at zero) in the base link's
coordinates, folds ``fixed`` joints into those placements, and runs the lectures'
frame-assignment algorithm (:func:`~dhsym.geometry.frames.assign_frames`) on the axes,
with the tip link's frame as the tool. The DH z axes point along the URDF axes and the
variables are zero at the URDF zero, so q means the same in both: ``robot.fk(q)`` is the
URDF chain's pose of the tip link in the base link for every q. ``revolute`` and
``continuous`` joints become revolute rows, ``prismatic`` ones prismatic rows (``limit``
becomes the row's limits); ``mimic``, ``floating`` and ``planar`` joints on the chain are
refused. Each link's ``<inertial>`` becomes part of ``row.inertia`` of the DH link that
moves it (links fixed below it merged by :meth:`~dhsym.model.inertia.LinkInertia.combine`),
in DH frame k; the base's and off-chain links' inertials are left out with a warning.

Angles in ``rpy`` that are no multiple of π/12 (``-1.8``) are measurements: their cosines
are floats (as in the transform kernel), and positions that depend on them are read as
the simplest exact number within 1e-12. The frame geometry is exact; the table it gives
holds what a textbook prints (:func:`as_written`): the URDF's decimals as written, exact
forms of small numbers (``pi/2``), and each measured number the geometry makes of them (a
fraction of 20 digits, ``sqrt(134560049)/100000``) as a decimal of 12 significant digits,
so ``fk`` of the table is the URDF chain's to about 1e-12 of the arm's size.

Examples
--------
>>> imp = import_urdf('''<robot name="r"><link name="a"/><link name="b"/>
...   <joint name="j" type="prismatic"><parent link="a"/><child link="b"/>
...   <origin xyz="0 0 0.1"/><axis xyz="0 0 1"/></joint></robot>''')
>>> imp.table.rows[0], [j.name for j in imp.moving]
(DHRow(P: theta=0, d=d1 + 1/10, a=0, alpha=0), ['j'])
"""

from __future__ import annotations

import os
import textwrap
import unicodedata
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import sympy as sp

from dhsym.errors import DHError, FormatError, echoed
from dhsym.geometry.axes import Frame, JointAxis, Tool, exact_number, measured
from dhsym.geometry.frame_choices import FrameChoice, match_frames, textbook_frames, turned
from dhsym.geometry.frames import FrameAssignment, assign_frames
from dhsym.kinematics.numeric import to_float
from dhsym.kinematics.transforms import chain_word, plain_product, rigid_inverse
from dhsym.model.angles import AngleSnap, snap_note
from dhsym.model.inertia import LinkInertia
from dhsym.model.kinds import Convention
from dhsym.model.table import DHTable, Elementary
from dhsym.model.tablefile import dump_table
from dhsym.notation.escape import clean_text

from .description import MOVING_KINDS, Expr, Inertial, UrdfJoint, UrdfModel
from .read import read_urdf

if TYPE_CHECKING:
    from dhsym.kinematics.chain import KinematicChain

__all__ = [
    "MAX_CHAIN",
    "UrdfImport",
    "as_written",
    "chain_from_urdf",
    "import_urdf",
    "table_yaml",
]

#: Most joints (fixed and moving) on the chain from base to tip; arms have 6 to 20.
MAX_CHAIN = 100


@dataclass(frozen=True)
class UrdfImport:
    """A URDF chain read as a DH table: the chain, the frame assignment, the table, inertials.

    ``inertials`` are the links' ``<inertial>`` as written (in each URDF link's own
    frame), from the base link to the tip link; the table's rows carry them converted
    into the DH link frames (``row.inertia``, see :func:`import_urdf`).
    """

    model: UrdfModel
    base: str
    tip: str
    joints: tuple[UrdfJoint, ...]
    assignment: FrameAssignment
    table: DHTable
    inertials: tuple[tuple[str, Inertial], ...]
    #: the senses of the x axes chosen after the frame assignment (a textbook's, or a
    #: reference table's), with the rows a reference could not match
    choice: FrameChoice | None = None

    @property
    def moving(self) -> tuple[UrdfJoint, ...]:
        """The joints that became DH rows, in order."""
        return tuple(j for j in self.joints if j.moving)

    @property
    def steps(self) -> list[str]:
        """The frame-assignment sentences, one per choice, then the senses of x chosen."""
        extra = list(self.choice.sentences + self.choice.mismatches) if self.choice else []
        return self.assignment.step_texts + extra

    def verify(self, samples: int = 20, *, seed: int = 0) -> float:
        """The largest difference between ``fk`` of the table and the URDF chain at the
        home pose and ``samples`` random configurations.

        The table as chosen (:attr:`choice`: some frames turned by π about z) is checked
        against the joint axes directly: its frame k at q must be the assigned frame k,
        turned as chosen, moved by the screw motions of joints 1 … k (one numeric word
        product, :meth:`~dhsym.geometry.frames.FrameAssignment.verify`; no closed form is
        derived for the check).
        """
        chosen = self.choice.flipped if self.choice is not None else ()
        frames = [turned(f) if k in chosen else f for k, f in enumerate(self.assignment.frames)]
        if self.choice is not None and self.choice.last_z_reversed:
            last = frames[-1]
            frames[-1] = Frame(last.index, last.origin, last.x, -last.z)
        checked = replace(self.assignment, frames=tuple(frames), table=self.table)
        return checked.verify(samples, seed=seed)

    def chain(self, **kw: Any) -> KinematicChain:  # its keywords: compact, style
        """A :class:`~dhsym.kinematics.chain.KinematicChain` of the table (``compact``,
        ``style``)."""
        from dhsym.kinematics.chain import KinematicChain

        return KinematicChain(self.table, **kw)


def import_urdf(
    source: str | os.PathLike[str] | UrdfModel,
    tip: str | None = None,
    base: str | None = None,
    convention: Convention | str = "standard",
    *,
    snap_angles: AngleSnap | bool | float | None = True,
    physical: bool = True,
    frames: str | DHTable = "textbook",
) -> UrdfImport:
    """Read a URDF and derive the DH table of the chain from ``base`` (default: the root)
    to ``tip`` (default: the one leaf link), with the frame-assignment sentences.

    ``frames`` chooses among the equivalent senses of the x axes
    (:mod:`dhsym.geometry.frame_choices`): ``"textbook"`` (default) the table a textbook
    prints (no constant offsets of θ, the fewest negative twists, then lengths; for the
    UR5 Universal Robots' own table), ``"assigned"`` the frame-assignment algorithm's as
    it chose them, or a reference :class:`~dhsym.model.table.DHTable` to match (the rows
    no choice can match are named in :attr:`UrdfImport.steps`). The joint values and
    ``fk`` are the same for every choice.

    The inertials are checked as the table reader checks inertias; ``physical=False``
    accepts inertias that break the triangle inequality (published data that does), and
    the table says so (``physical: false``).

    Without ``tip``, the tip is the one leaf below ``base``, or the one leaf that a moving
    joint moves (ROS-Industrial's fixed ``base`` frame beside ``tool0`` is no tip); else
    the choices are named:

    >>> text = '''<robot name="r"><link name="a"/><link name="b"/><link name="c"/>
    ...   <joint name="j1" type="revolute"><parent link="a"/><child link="b"/>
    ...     <axis xyz="0 0 -1"/></joint>
    ...   <joint name="j2" type="fixed"><parent link="a"/><child link="c"/></joint></robot>'''
    >>> import_urdf(text).table.source
    'URDF text, chain a -> b'
    >>> import_urdf(text.replace('"fixed"', '"continuous"'))
    Traceback (most recent call last):
    ...
    dhsym.errors.FormatError: field tip: the tree branches below link 'a': give the tip ... b ...
    """
    model = (
        source
        if isinstance(source, UrdfModel)
        else read_urdf(source, snap_angles=snap_angles, physical=physical)
    )
    if not model.links:
        raise FormatError("the robot has no links", file=model.file, field="<robot>")
    start = base or model.root
    if tip is None:
        leaves = model.leaves(start)
        below = model.below(start)
        moved = [leaf for leaf in leaves if below[leaf]]
        if len(leaves) != 1 and len(moved) == 1:  # the others hang on fixed joints only
            leaves = moved
        if len(leaves) != 1:
            counts = [below[leaf] for leaf in leaves]
            choices = ", ".join(
                f"{leaf} ({c} moving joint{'s' if c != 1 else ''})"
                for leaf, c in zip(leaves, counts, strict=True)
            )
            raise FormatError(
                f"the tree branches below link {echoed(start)}: give the tip link (tip=, --tip), "
                "one of "
                f"{choices}",
                file=model.file,
                field="tip",
            )
        tip = leaves[0]
    joints = model.chain(start, tip)
    if len(joints) > MAX_CHAIN:
        raise FormatError(
            f"the chain from {echoed(start)} to {echoed(tip)} has {len(joints)} joints: at most "
            f"{MAX_CHAIN} "
            "are read (choose base= and tip= closer together)",
            file=model.file,
            field="tip",
        )
    moving = [j for j in joints if j.moving]
    for j in joints:
        if j.kind in ("floating", "planar"):
            raise FormatError(
                f"a {j.kind} joint has {'six' if j.kind == 'floating' else 'three'} degrees of "
                "freedom and no single axis: a DH row describes one revolute or prismatic "
                "joint; choose base= below it",
                file=model.file,
                field=j.where,
            )
        if j.mimic is not None and j.moving:
            raise FormatError(
                f"the joint mimics joint {j.mimic!r} (its value follows another joint's): a DH "
                "table has one independent variable per joint; choose a tip above it",
                file=model.file,
                field=j.where,
            )
    if not moving:
        raise FormatError(
            f"no revolute, continuous or prismatic joint between {echoed(start)} and {echoed(tip)}",
            file=model.file,
            field="tip",
        )
    axes, tool = _geometry(joints, model.file)
    try:
        fa = assign_frames(axes, convention=convention, tool=tool, name=model.name)
    except DHError as err:
        raise err.located(file=model.file) from None
    rows = tuple(
        replace(row, limits=j.limits if j.kind != "continuous" else None)
        for row, j in zip(fa.table.rows, moving, strict=True)
    )
    inertias, dropped = _dh_inertias(
        model, start, moving, replace(fa.table, rows=rows), physical and model.physical
    )
    rows = tuple(
        replace(row, inertia=inertia) if inertia is not None else row
        for row, inertia in zip(rows, inertias, strict=True)
    )
    snapped = [s for j in joints for s in j.snapped]
    note = snap_note(snapped, "snap_angles=False") if snapped else ""
    notes = [note] if note else []
    if dropped:
        notes.append("inertials not in the DH table: " + "; ".join(dropped))
    unknown = [k for k, inertia in enumerate(inertias, start=1) if inertia is None]
    if unknown:
        rows_text = ", ".join(map(str, unknown))
        notes.append(
            f"no <inertial> on the links of row{'s' * (len(unknown) > 1)} {rows_text}: "
            "their dynamics are in the textbook symbols (m_k, r_k, I_k); give values= "
            "for them, or a URDF with inertials"
        )
    table = replace(
        fa.table,
        rows=rows,
        name=model.name or (Path(model.file).stem if model.file else "URDF robot"),
        source=f"URDF {Path(model.file).name if model.file else 'text'}, chain {start} -> {tip}",
        notes=(
            f"Read from {model.file or 'URDF text'}: links {start} to {tip}, joints "
            + ", ".join(j.name for j in moving)
            + "; DH z axes along the URDF axes, variables zero at the URDF zero."
        ),
        warnings=tuple(notes),
        physical=physical and model.physical,
    )
    inertials = tuple(
        (name, inertial)
        for name, inertial in model.links
        if inertial is not None and (name == start or any(j.child == name for j in joints))
    )
    choice = _choose_frames(table, frames)
    if choice is not None:
        table = choice.table
    return UrdfImport(model, start, tip, joints, fa, as_written(table), inertials, choice)


def as_written(table: DHTable) -> DHTable:
    """The table with every measured constant
    (:func:`~dhsym.geometry.axes.measured`) as a decimal: the DH
    parameters, the base and tool transforms and the inertias (the joint limits are the
    URDF's decimals already). ``fk`` moves by less than 1e-12 of the arm's size."""
    rows = []
    for row in table.rows:
        new = replace(
            row,
            theta=measured(row.theta),
            d=measured(row.d),
            a=measured(row.a),
            alpha=measured(row.alpha),
        )
        if row.inertia is not None:
            inertia = row.inertia
            new = replace(
                new,
                inertia=replace(
                    inertia,
                    m=measured(inertia.m),
                    r=(measured(inertia.r[0]), measured(inertia.r[1]), measured(inertia.r[2])),
                    I=sp.ImmutableMatrix(3, 3, [measured(v) for v in inertia.I]),
                ),
            )
        rows.append(new)
    base = tuple(Elementary(e.kind, e.axis, measured(e.value)) for e in table.base)
    tool = tuple(Elementary(e.kind, e.axis, measured(e.value)) for e in table.tool)
    return replace(table, rows=tuple(rows), base=base, tool=tool)


def _choose_frames(table: DHTable, frames: str | DHTable) -> FrameChoice | None:
    """The senses of x of ``frames`` (``"textbook"``, ``"assigned"`` or a reference table)."""
    if isinstance(frames, DHTable):
        return match_frames(table, frames)
    if frames == "textbook":
        return textbook_frames(table)
    if frames == "assigned":
        return None
    raise DHError(f"frames: 'textbook', 'assigned' or a reference table, not {frames!r}")


def chain_from_urdf(
    source: str | os.PathLike[str],
    tip: str | None = None,
    base: str | None = None,
    convention: Convention | str = "standard",
    *,
    snap_angles: AngleSnap | bool | float | None = True,
    physical: bool = True,
    **kw: object,
) -> KinematicChain:
    """A :class:`~dhsym.kinematics.chain.KinematicChain` from a URDF file or text (see
    :func:`import_urdf`).

    >>> r = chain_from_urdf('''<robot name="slide"><link name="a"/><link name="b"/>
    ...   <joint name="s" type="prismatic"><parent link="a"/><child link="b"/>
    ...     <axis xyz="1 0 0"/><limit lower="0" upper="0.5" effort="1" velocity="1"/></joint>
    ... </robot>''', convention="modified")
    >>> r.table.rows[0], r.fk([0.2])[0, 3]
    (DHRow(P: theta=0, d=d1, a=0, alpha=0), np.float64(0.2))
    """
    imp = import_urdf(source, tip, base, convention, snap_angles=snap_angles, physical=physical)
    return imp.chain(**kw)


def _dh_inertias(
    model: UrdfModel, start: str, moving: Sequence[UrdfJoint], table: DHTable, physical: bool
) -> tuple[list[LinkInertia | None], list[str]]:
    """Each DH link's inertia (link k moves with row k) in DH frame k, and what was dropped.
    With ``physical``, each such body keeps the triangle inequality: the rigid body the
    dynamics see, not each ``<inertial>`` alone (a frame link with a placeholder inertia,
    such as the Sawyer's ``right_hand`` with every entry 1e-8, merges into its link).

    Every link below ``start`` joins the body of its nearest moving ancestor on the chain:
    links hung on by ``fixed`` joints (a hand, a flange, a tool-centre link) merge into the
    link they hang on (:meth:`~dhsym.model.inertia.LinkInertia.combine`: masses add, centres
    of mass combine, the parallel-axis theorem moves each inertia to the common centre; the
    sums are then expanded, and read as exact numbers within 1e-12 where measured angles put
    floats in them). Links before the first moving joint form the base,
    which has no row; links behind a moving joint off the chain (fingers) are not on the
    chain. Both are named in the returned notes. An ``<inertial>`` given as all zeros is a
    massless part (a row of only such parts is massless), not an unknown one. Rotations
    stay exact where the ``rpy`` angles are (snapped or rational multiples of π); measured
    angles use :attr:`Origin.rational_matrix`.
    """
    rows = {j.name: k for k, j in enumerate(moving, start=1)}
    children: dict[str, list[UrdfJoint]] = {}
    for j in model.joints:
        children.setdefault(j.parent, []).append(j)
    inertial = dict(model.links)
    bodies: list[list[tuple[sp.Matrix, Inertial]]] = [[] for _ in range(len(moving) + 1)]
    names: list[list[str]] = [[] for _ in range(len(moving) + 1)]
    base: list[str] = []
    off: list[str] = []
    stack: list[tuple[str, sp.Matrix, int]] = [(start, sp.eye(4), 0)]
    while stack:
        link, T, body = stack.pop()
        found = inertial.get(link)
        if found is not None:  # given, even all zero: a massless link, not unknown symbols
            bodies[body].append((T * found.origin.rational_matrix, found))
            names[body].append(link)
            if body == 0 and (found.mass != 0 or any(v != 0 for v in found.inertia)):
                base.append(link)
        for j in children.get(link, []):
            if j.moving and j.name not in rows or j.kind in ("floating", "planar"):
                off.extend(_subtree(children, j.child, inertial))
                continue
            stack.append((j.child, T * j.origin.rational_matrix, rows.get(j.name, body)))
    zero = {v: 0 for v in table.variables}
    out: list[LinkInertia | None] = []
    for k in range(1, len(moving) + 1):
        if not bodies[k]:
            out.append(None)
            continue
        to_frame = rigid_inverse(plain_product(chain_word(table, -1, k)).subs(zero))
        parts = []
        for T, found in bodies[k]:
            M = to_frame * T
            xx, xy, xz, yy, yz, zz = found.inertia
            Ic = sp.Matrix([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]])
            R = M[:3, :3]
            parts.append(LinkInertia(found.mass, (M[0, 3], M[1, 3], M[2, 3]), R * Ic * R.T))
        whole = LinkInertia.combine(parts)
        try:
            whole.check(physical=physical)
        except DHError as err:
            hint = " (or read with physical=False)" if "physical: false" in err.message else ""
            links = " ".join(f"<link name={echoed(n)}>" for n in names[k])
            raise FormatError(
                err.message + hint, file=model.file, field=f"{links} <inertial>"
            ) from None
        out.append(
            LinkInertia(
                _tidy(whole.m),
                (_tidy(whole.r[0]), _tidy(whole.r[1]), _tidy(whole.r[2])),
                sp.ImmutableMatrix(3, 3, [_tidy(v) for v in whole.I]),
            )
        )
    dropped = []
    if base:
        dropped.append(", ".join(sorted(base)) + " (the base: it does not move and has no row)")
    if off:
        dropped.append(", ".join(off) + " (behind a moving joint that is not on the chain)")
    return out, dropped


def _subtree(
    children: dict[str, list[UrdfJoint]], link: str, inertial: dict[str, Inertial | None]
) -> list[str]:
    """The links with mass in the subtree of ``link`` (``link`` included)."""
    out, stack = [], [link]
    while stack:
        name = stack.pop()
        found = inertial.get(name)
        if found is not None and found.mass != 0:
            out.append(name)
        stack.extend(j.child for j in children.get(name, []))
    return out


def _tidy(value: Expr) -> Expr:
    """An exact entry, expanded; sums with float cosines read as exact within 1e-12."""
    value = sp.expand(value)
    return exact_number(to_float(value)) if value.has(sp.Float) else value


def _geometry(joints: Iterable[UrdfJoint], file: str | None) -> tuple[list[JointAxis], Tool]:
    """The moving joints' axes at home and the tip frame as a tool, in the base link's frame."""
    T = sp.eye(4)
    axes = []
    for j in joints:
        T = T * j.origin.rational_matrix
        if j.moving:
            direction = T[:3, :3] * sp.Matrix(j.axis)
            try:
                axes.append(
                    JointAxis(_exact(T[:3, 3]), _exact(direction), MOVING_KINDS[j.kind], j.name)
                )
            except DHError as err:
                raise FormatError(err.message, file=file, field=j.where) from None
    return axes, Tool(_exact(T[:3, 3]), _exact(T[:3, 2]), _exact(T[:3, 1]))


def _exact(column: sp.MatrixBase) -> list[Expr]:
    """Entries as exact numbers; sums with float cosines (measured angles) read within 1e-12."""
    return [_tidy(v) for v in column]


def table_yaml(imp: UrdfImport) -> str:
    """The table as a YAML table file, headed by comments on where it came from and the
    frame-assignment sentences.

    >>> imp = import_urdf('''<robot name="r"><link name="a"/><link name="b"/>
    ...   <joint name="j" type="continuous"><parent link="a"/><child link="b"/>
    ...   <axis xyz="0 0 1"/></joint></robot>''')
    >>> print(table_yaml(imp).splitlines()[0])
    # DH table (standard convention) of the URDF chain a -> b in URDF text, joints: j. Derived
    """
    where = imp.model.file or "URDF text"
    head = (
        f"DH table ({imp.table.convention.value} convention) of the URDF chain {imp.base} -> "
        f"{imp.tip} in {where}, joints: {', '.join(j.name for j in imp.moving)}. Derived by "
        "dhsym from the joint axes at the URDF zero pose with the frame-assignment algorithm; "
        "the variables keep the URDF's zero and direction, so fk(q) is the URDF pose of the "
        "tip link in the base link for every q."
    )
    lines = textwrap.wrap(head, 88)
    lines.append("Frame assignment:")
    for k, text in enumerate(imp.steps, start=1):
        lines += textwrap.wrap(f"{k}. {text}", 88, subsequent_indent="   ")
    lines += [w for note in imp.table.warnings for w in textwrap.wrap(f"Note: {note}", 88)]
    return "".join(f"# {_comment(line)}\n" for line in lines) + dump_table(imp.table)


def _comment(text: str) -> str:
    """One comment line: names from the file lose control characters, and the line breaks
    YAML knows beyond newline (U+0085, U+2028, U+2029) become spaces, so no name ends the
    comment and writes a key.

    >>> _comment("link b\u2028physical: false")
    'link b physical: false'
    """
    return "".join(
        " " if unicodedata.category(ch) in ("Zl", "Zp") else ch for ch in clean_text(text)
    )
