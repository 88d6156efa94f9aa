"""Source code to take away: fk, Jacobian, closed-form IK, inverse dynamics (rne) and the
product of exponentials in C, C++, MATLAB, Rust, NumPy.

The room turns a robot's exact closed forms (:mod:`dhsym.kinematics`) into
self-contained source files with no dependency on dhsym: :mod:`.program` is the
front end (named straight-line programs), :mod:`.ik_source` the one adapter to the IK
derivation, :mod:`.languages` and the templates in ``templates/export`` the back end, one
module per language (:mod:`.c`, :mod:`.cpp`, :mod:`.matlab`, :mod:`.rust`,
:mod:`.python`), and :mod:`.shared_library` builds the C once and loads it with ``ctypes``.
May import model, notation, kinematics, ik (the derivation, read by :mod:`.ik_source`),
dynamics (the Newton–Euler recursion, read by :func:`.program.rne_program`), trajectory
(the profiles, :mod:`.motion`) and screws (the product of exponentials, :mod:`.screws`).

``dhsym.export(robot, lang, ...)`` is :func:`export` (the module is callable).

Examples
--------
>>> import dhsym
>>> files = dhsym.export(dhsym.load("planar2r"), "c", what=("fk",), prefix="arm")
>>> sorted(files)
['arm.c', 'arm.h']
>>> print(files["arm.c"].split("void arm_fk")[1].split("\\n}")[0])  # doctest: +ELLIPSIS
(const double q[ARM_NJOINTS], double T[16])
{
    const double q1 = q[0];
    const double q2 = q[1];
    double s1, c1, s12, c12;
    { /* the sines and cosines of 2 angles, two at a time */
        const double angle[2] = {q1, q1 + q2};
        double sine[2], cosine[2];
        dh_sincos_n(2, angle, sine, cosine);
        s1 = sine[0];
        c1 = cosine[0];
        s12 = sine[1];
        c12 = cosine[1];
    }
    T[0] = c12;
    T[1] = -s12;
    T[2] = 0.0;
    T[3] = c1 + 0.8*c12;
...
"""

from __future__ import annotations

import sys
import types
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from dhsym.errors import DHError

if TYPE_CHECKING:
    from dhsym.ik.choices import IKCache
    from dhsym.kinematics.chain import KinematicChain

    from .languages import Language

__all__ = ["DEFAULT_PARTS", "LANGUAGES", "PARTS", "export", "export_languages"]

#: The languages and the modules that print them.
LANGUAGES = ("c", "cpp", "matlab", "rust", "python")
#: What can be exported (``rne`` is another name for ``dynamics``; ``trajectory``: the
#: cubic and quintic profiles; ``control``: computed torque, on the exported ``rne``;
#: ``screws``: the product of exponentials' fk in space form and ``J_s``, ``J_b``).
PARTS = ("fk", "jacobian", "ik", "dynamics", "trajectory", "control", "screws")
#: What is exported unless asked otherwise (the dynamics needs numeric inertial parameters).
DEFAULT_PARTS = ("fk", "jacobian", "ik")


def _language(lang: str) -> Language:
    from importlib import import_module

    if lang not in LANGUAGES:
        raise DHError(f"unknown language {lang!r}: choose one of {', '.join(LANGUAGES)}")
    language: Language = import_module(f"{__name__}.{lang}").LANGUAGE
    return language


def _parts(what: str | Iterable[str]) -> tuple[str, ...]:
    items = what.split(",") if isinstance(what, str) else list(what)
    parts = []
    for w in (x.strip() for x in items):
        w = "dynamics" if w == "rne" else w
        if w not in PARTS:
            raise DHError(f"unknown part {w!r} in what: choose from {', '.join(PARTS)}")
        if w not in parts:
            parts.append(w)
    if not parts:
        raise DHError(
            "nothing to export: give what=fk,jacobian,ik,dynamics,trajectory,control,screws "
            "(or a part of it)"
        )
    return tuple(p for p in PARTS if p in parts)


def export(
    robot: KinematicChain,
    lang: str,
    what: str | Iterable[str] = DEFAULT_PARTS,
    prefix: str | None = None,
    symbolic_lengths: bool = False,
    *,
    command: str | None = None,
    cache: IKCache | None = None,
) -> dict[str, str]:
    """Self-contained source files for ``robot`` in ``lang``: file name → text.

    Parameters
    ----------
    robot
        A :class:`~dhsym.kinematics.chain.KinematicChain`.
    lang
        ``"c"``, ``"cpp"``, ``"matlab"``, ``"rust"`` or ``"python"`` (NumPy).
    what
        Parts: ``"fk"``, ``"jacobian"``, ``"ik"``, ``"dynamics"`` (or ``"rne"``: the
        inverse dynamics ``rne(q, qd, qdd)`` of ``robot.rne``, for numeric inertial
        parameters only), ``"trajectory"`` (``<prefix>_cubic``, ``<prefix>_quintic`` and
        ``<prefix>_lspb``: q, q̇, q̈ of each joint at a time ``t`` from its boundary
        conditions; ``<prefix>_spline``: the cubic spline through via points),
        ``"control"`` (``<prefix>_computed_torque``, numeric inertial parameters only) and
        ``"screws"`` (the product of exponentials of Lynch and Park: ``<prefix>_fk_space``,
        the pose of ``fk`` as ``e^[S1]q1 … e^[Sn]qn M``, and ``<prefix>_jacobian_space``,
        ``<prefix>_jacobian_body``, rows ``[ω; v]``; the header lists the screw axes and
        ``M``) as a sequence or ``"fk,ik"``. The IK checks its solutions with the fk and
        refines a branch near a pose that is not exact with the fk and the Jacobian, so
        ``ik`` brings ``fk`` and ``jacobian`` along, and ``control`` brings ``dynamics``
        (its ``rne``).
    prefix
        The name in front of every function and file (``<prefix>_fk``, ``<prefix>.h``):
        an ASCII letter, then letters, digits and ``_``, never a path (anything else is a
        :class:`~dhsym.errors.DHError`); by default the robot's name, made an identifier.
        It is written in lower case, and a keyword or a standard name of ``lang`` (``log``
        in C++, ``os`` in Python) gets a ``_`` at the end
        (:func:`dhsym.export.identifiers.prefix`).
    symbolic_lengths
        Keep the table's lengths and offsets as run-time parameters ``p`` instead of
        baking in its values.
    command
        The command line to name in the header (the CLI passes its own).
    cache
        Where the closed-form IK is derived and kept (:class:`dhsym.ik.choices.IKCache`;
        ``Robot.compiled`` passes the robot's own); by default a fresh one.

    The same input gives the same bytes.

    >>> import dhsym
    >>> sorted(export(dhsym.load("puma560"), "matlab", prefix="puma"))  # doctest: +ELLIPSIS
    ['puma_fk.m', 'puma_ik.m', 'puma_jacobian.m', 'puma_max_ik_solutions.m', 'puma_njoints.m']
    >>> sorted(export(dhsym.load("planar2r"), "python", prefix="os"))
    ['os_.py']
    >>> export(dhsym.load("planar2r"), "c", prefix="/tmp/arm")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    dhsym.errors.DHError: prefix '/tmp/arm' is not a name: it is a path. ...
    >>> export(dhsym.load("planar2r"), "c", what="dynamics")
    Traceback (most recent call last):
    ...
    dhsym.errors.DHError: Planar 2R: the dynamics export needs numeric inertial parameters; ...
    """
    return export_languages(
        robot, (lang,), what, prefix, symbolic_lengths, command=command, cache=cache
    )[lang]


def export_languages(
    robot: KinematicChain,
    langs: Iterable[str],
    what: str | Iterable[str] = DEFAULT_PARTS,
    prefix: str | None = None,
    symbolic_lengths: bool = False,
    *,
    command: str | None = None,
    cache: IKCache | None = None,
) -> dict[str, dict[str, str]]:
    """The files of :func:`export` for several languages at once: language → (file name →
    text), each the bytes :func:`export` gives, the programs (fk, Jacobian, IK, rne) built
    once for all of them.

    >>> import dhsym
    >>> files = export_languages(dhsym.load("planar2r"), ("cpp", "python"), "fk", "log")
    >>> {lang: sorted(f) for lang, f in files.items()}
    {'cpp': ['log_.hpp'], 'python': ['log.py']}
    """
    from .identifiers import comment_lines
    from .identifiers import prefix as prefix_for
    from .languages import Context, header_lines, render_files
    from .motion import computed_torque_program, lspb_program, profile_program, spline_program
    from .program import fk_program, ik_program, jacobian_program, rne_program
    from .screws import description_lines, screw_programs

    parts = _parts(what)
    if "control" in parts and "dynamics" not in parts:  # computed torque calls rne
        parts = _parts((*parts, "dynamics"))
    languages = [(lang, _language(lang)) for lang in langs]
    names = {
        lang: prefix_for(prefix, lang, default=robot.name or "robot") for lang in dict(languages)
    }
    rne = rne_program(robot, symbolic_lengths=symbolic_lengths) if "dynamics" in parts else None
    ik = (
        ik_program(robot, symbolic_lengths=symbolic_lengths, cache=cache) if "ik" in parts else None
    )
    fk = fk_program(robot, symbolic_lengths=symbolic_lengths)
    # the IK refines a branch near a pose that is not exact with the fk and the Jacobian
    brought = {"fk", "jacobian"} if "ik" in parts else {"fk"}
    jac = (
        jacobian_program(robot, symbolic_lengths=symbolic_lengths)
        if "jacobian" in parts or "ik" in parts
        else None
    )
    profiles = (
        (*(profile_program(k) for k in ("cubic", "quintic")), lspb_program())
        if "trajectory" in parts
        else ()
    )
    spline = spline_program() if "trajectory" in parts else None
    control = computed_torque_program() if "control" in parts else None
    screws = screw_programs(robot, symbolic_lengths=symbolic_lengths) if "screws" in parts else None
    effective = tuple(sorted(set(parts) | brought))
    out: dict[str, dict[str, str]] = {}
    for lang, language in languages:
        name = names[lang]
        said = command
        if said is None:
            said = f"dhsym.export(robot, {lang!r}, what={','.join(parts)!r}, prefix={name!r}" + (
                ", symbolic_lengths=True)" if symbolic_lengths else ")"
            )
        header = header_lines(robot, said)
        if ik is not None:
            header += comment_lines(f"Inverse kinematics: {ik.source.structure}")
        if screws is not None:
            header += [c for line in description_lines(screws.poe) for c in comment_lines(line)]
        ctx = Context(
            prefix=name,
            header=tuple(header),
            njoints=len(robot.variables),
            fk=fk,
            jacobian=jac,
            ik=ik,
            rne=rne,
            profiles=profiles,
            control=control,
            spline=spline,
            screws=screws,
            parameters=fk.parameters,
            revolute=tuple(
                r.joint.value == "R" for r in robot.table.rows if r.variable is not None
            ),
        )
        out[lang] = render_files(language, ctx, effective)
    return out


class _CallableModule(types.ModuleType):
    """``dhsym.export(robot, "c")`` calls :func:`export` (the room is also a module)."""

    def __call__(self, *args: Any, **kw: Any) -> dict[str, str]:  # export's, passed on
        return export(*args, **kw)


def __dir__() -> list[str]:
    """What ``dir(dhsym.export)`` shows: the room's ``__all__``, not its imports."""
    from dhsym._lazy import public_dir

    return public_dir(__name__)


sys.modules[__name__].__class__ = _CallableModule
