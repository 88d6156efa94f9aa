"""Sphinx extension of dhsym's documentation: pages generated from the code.

- ``builder-inited``: writes the Python API pages (``api/``: one page per room, one per
  public module, found by walking the package, so a new room or module appears without
  an edit) and copies the course notebooks (``notebooks/*.ipynb``, committed executed)
  into ``tutorials/``;
- the directive ``dhsym-cli``: the command-line reference, read from the argparse parser
  that ``dhsym`` itself runs (:func:`dhsym.cli.main.build_parser`), every command and
  sub-command, every option with its default and choices;
- the directive ``dhsym-mistakes``: the mistake catalogue, read from the registry
  :mod:`dhsym.checking.mistakes.registry`;
- ``build-finished``: copies Debian's MathJax 2 (``libjs-mathjax``) into ``_static/``, so
  the site typesets mathematics without the network, and writes the 3D view of each
  tutorial robot (:data:`VIEWS`, ``dhsym view NAME``) into ``_static/views/``, where the
  guide's page on the view and the tutorials embed them.

Nothing here runs user input: the API pages only import dhsym's modules (``__main__`` is
skipped) and autodoc reads their docstrings.
"""

from __future__ import annotations

import argparse
import importlib
import inspect
import pkgutil
import shutil
from pathlib import Path

from docutils import nodes
from docutils.parsers.rst import Directive
from docutils.statemachine import StringList
from sphinx.application import Sphinx
from sphinx.util.nodes import nested_parse_with_titles

MATHJAX_SOURCE = Path("/usr/share/javascript/mathjax")
#: What MathJax 2 needs for TeX input and CommonHTML output (about 1.6 MB of the 54 MB).
MATHJAX_PARTS = (
    "MathJax.js",
    "config/TeX-AMS_CHTML-full.js",
    "extensions",
    "jax/input/TeX",
    "jax/output/CommonHTML",
    "jax/element",
    "fonts/HTML-CSS/TeX/woff",
)
MATHJAX_PATH = "mathjax/MathJax.js?config=TeX-AMS_CHTML-full"

#: The tutorial robots whose 3D views the site shows (``_static/views/NAME.html``).
VIEWS = ("planar2r", "puma560", "ur5", "panda", "stanford")

PACKAGE = "dhsym"
SKIP_MODULES = {"dhsym.__main__"}


# --------------------------------------------------------------------------- API pages


def _public(name: str) -> bool:
    return not any(part.startswith("_") for part in name.split("."))


def _walk(package: str) -> list[str]:
    """Every public module of the package (depth first, sorted), the package first."""
    mod = importlib.import_module(package)
    names = [package]
    for info in sorted(pkgutil.iter_modules(mod.__path__), key=lambda i: i.name):
        full = f"{package}.{info.name}"
        if not _public(full) or full in SKIP_MODULES:
            continue
        names.extend(_walk(full) if info.ispkg else [full])
    return names


def _exported(module: object) -> list[str]:
    names = getattr(module, "__all__", None)
    if names is None:
        names = [
            n
            for n, v in vars(module).items()
            if not n.startswith("_") and getattr(v, "__module__", None) == module.__name__
        ]
    return list(names)


def _home(modules: list[str]) -> dict[int, tuple[str, object]]:
    """Where each public class and function is documented (by ``id``: the module and the
    object): its defining module when that is public, else the first public (non-package)
    module that exports it."""
    homes: dict[int, tuple[str, object]] = {}
    loaded = {m: importlib.import_module(m) for m in modules}
    packages = {m for m, mod in loaded.items() if hasattr(mod, "__path__")}
    for m, mod in loaded.items():
        for n in _exported(mod):
            obj = getattr(mod, n, None)
            if not (inspect.isclass(obj) or inspect.isfunction(obj)):
                continue
            origin = getattr(obj, "__module__", "") or ""
            if origin in loaded and origin not in packages and _public(origin):
                homes.setdefault(id(obj), (origin, obj))
            elif m not in packages:
                homes.setdefault(id(obj), (m, obj))
            elif origin in loaded:
                homes.setdefault(id(obj), (origin, obj))
    return homes


def _directive(obj: object) -> str:
    if inspect.isclass(obj):
        return "autoclass" if not issubclass(obj, BaseException) else "autoexception"
    if inspect.isfunction(obj):
        return "autofunction"
    return "autodata"


def _first_line(obj: object) -> str:
    doc = inspect.getdoc(obj) or ""
    return doc.strip().splitlines()[0] if doc.strip() else ""


def write_api_pages(target: Path) -> list[str]:
    """Write ``target/index.md`` and one page per public module; returns the modules."""
    modules = _walk(PACKAGE)
    homes = _home(modules)
    shutil.rmtree(target, ignore_errors=True)
    target.mkdir(parents=True)
    rooms = [m for m in modules if m.count(".") == 1]
    top = importlib.import_module(PACKAGE)
    lines = [
        "# Python API",
        "",
        "Generated from the docstrings (numpydoc; every example is a doctest that runs "
        "with the test suite). `import dhsym` gives the names below; each is documented "
        "in the room that defines it.",
        "",
        "## The `dhsym` namespace",
        "",
        "```{eval-rst}",
        ".. autosummary::",
        "",
    ]
    for name in sorted(top.__all__, key=str.lower):
        obj = getattr(top, name)
        if inspect.ismodule(obj) or name.startswith("_"):
            continue
        home = homes.get(id(obj))
        if home:
            lines.append(f"   {home[0]}.{name}")
    lines += ["```", "", "## The rooms", "", "```{toctree}", ":maxdepth: 1", ""]
    lines += [m for m in rooms]
    lines += ["```", ""]
    (target / "index.md").write_text("\n".join(lines), encoding="utf-8")
    for m in modules[1:]:
        _module_page(target, m, modules, homes)
    return modules


def _module_page(
    target: Path, name: str, modules: list[str], homes: dict[int, tuple[str, object]]
) -> None:
    mod = importlib.import_module(name)
    children = [c for c in modules if c.rsplit(".", 1)[0] == name]
    lines = [f"# `{name}`", "", "```{eval-rst}", f".. automodule:: {name}", "   :no-members:"]
    lines += ["```", ""]
    members = []
    for n in _exported(mod):
        obj = getattr(mod, n, None)
        if obj is None or inspect.ismodule(obj):
            continue
        if inspect.isclass(obj) or inspect.isfunction(obj):
            if homes.get(id(obj), ("",))[0] != name:
                continue
        elif hasattr(mod, "__path__"):
            continue
        members.append((n, obj))
    listed = {id(obj) for _, obj in members}
    for home, obj in homes.values():  # defined here, exported only by a room's package
        n = getattr(obj, "__name__", "")
        if home == name and id(obj) not in listed and getattr(mod, n, None) is obj:
            members.append((n, obj))
            listed.add(id(obj))
    if hasattr(mod, "__path__"):
        exported = [
            f"{homes[id(o)][0]}.{n}"
            for n, o in ((n, getattr(mod, n, None)) for n in _exported(mod))
            if id(o) in homes and homes[id(o)][0] != name
        ]
        if exported:
            lines += ["Names this room exports:", "", "```{eval-rst}", ".. autosummary::", ""]
            lines += [
                # relative to this room, or the full name of another room's definition
                f"   {e[len(name) + 1 :] if e.startswith(name + '.') else e}"
                for e in sorted(exported, key=lambda s: s.rsplit(".", 1)[1])
            ]
            lines += ["```", ""]
    if children:
        lines += ["```{toctree}", ":maxdepth: 1", ""] + children + ["```", ""]
    if members:
        lines += ["```{eval-rst}"]
        for n, obj in members:
            lines.append(f".. {_directive(obj)}:: {name}.{n}")
            if inspect.isclass(obj) and not issubclass(obj, BaseException):
                lines += ["   :members:", "   :show-inheritance:"]
            lines.append("")
        lines += ["```", ""]
    (target / f"{name}.md").write_text("\n".join(lines), encoding="utf-8")


def copy_notebooks(source: Path, target: Path) -> list[Path]:
    """Copy the committed, executed notebooks (``*.ipynb``) into the site's sources."""
    target.mkdir(parents=True, exist_ok=True)
    for old in target.glob("*.ipynb"):
        old.unlink()
    copied = []
    for nb in sorted(source.glob("*.ipynb")):
        shutil.copy2(nb, target / nb.name)
        copied.append(target / nb.name)
    return copied


def _on_builder_inited(app: Sphinx) -> None:
    src = Path(app.srcdir)
    root = Path(app.config.dhsym_repo_root or src.parent)
    write_api_pages(src / "api")
    copy_notebooks(root / "notebooks", src / "tutorials" / "notebooks")


def _on_build_finished(app: Sphinx, exc: BaseException | None) -> None:
    if exc is not None or app.builder.format != "html":
        return
    if not (MATHJAX_SOURCE / "MathJax.js").is_file():
        raise RuntimeError(
            f"MathJax 2 not found in {MATHJAX_SOURCE}: apt-get install libjs-mathjax "
            "(scripts/system-deps.sh installs it)"
        )
    dest = Path(app.outdir) / "_static" / "mathjax"
    for part in MATHJAX_PARTS:
        s, d = MATHJAX_SOURCE / part, dest / part
        d.parent.mkdir(parents=True, exist_ok=True)
        if s.is_dir():
            shutil.copytree(s, d, dirs_exist_ok=True)
        else:
            shutil.copy2(s, d)
    _write_views(Path(app.outdir) / "_static" / "views")


def _write_views(folder: Path) -> None:
    """The page of ``dhsym view NAME`` for each robot of :data:`VIEWS`."""
    import dhsym
    from dhsym.view import view_page

    folder.mkdir(parents=True, exist_ok=True)
    for name in VIEWS:
        page = view_page(dhsym.load(name), footer=f"dhsym view {name} -o {name}.html")
        (folder / f"{name}.html").write_text(page, encoding="utf-8")


# --------------------------------------------------------------------------- CLI


def _subcommands(parser: argparse.ArgumentParser) -> list[tuple[str, str, argparse.ArgumentParser]]:
    out = []
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            helps = {a.dest: a.help or "" for a in action._choices_actions}
            for name, sub in action.choices.items():
                out.append((name, helps.get(name, ""), sub))
    return out


def _text_nodes(text: str) -> list[nodes.Node]:
    """Help text as written: paragraphs, and indented or list-like blocks kept verbatim."""
    out: list[nodes.Node] = []
    for block in text.strip().split("\n\n"):
        if not block.strip():
            continue
        lines = block.splitlines()
        if any(ln.startswith((" ", "\t")) for ln in lines[1:]) or block.startswith(" "):
            out.append(nodes.literal_block(text=block.rstrip(), language="none"))
        else:
            out.append(nodes.paragraph(text=" ".join(block.split())))
    return out


def _option_list(parser: argparse.ArgumentParser) -> nodes.Node | None:
    formatter = parser._get_formatter()
    items = nodes.definition_list()
    for action in parser._actions:
        if isinstance(action, (argparse._HelpAction, argparse._SubParsersAction)):
            continue
        if action.help == argparse.SUPPRESS:
            continue
        if action.option_strings:
            metavar = (
                formatter._format_args(action, action.dest.upper()) if action.nargs != 0 else ""
            )
            term_text = ", ".join(f"{o} {metavar}".strip() for o in action.option_strings)
        else:
            term_text = formatter._metavar_formatter(action, action.dest)(1)[0]
        help_text = formatter._expand_help(action) if action.help else ""
        if action.choices and "{" not in help_text:
            help_text += f" Choices: {', '.join(map(str, action.choices))}."
        item = nodes.definition_list_item()
        item += nodes.term("", "", nodes.literal(text=term_text))
        definition = nodes.definition()
        definition += nodes.paragraph(text=" ".join(help_text.split()) or "")
        item += definition
        items += item
    return items if len(items) else None


class CommandLine(Directive):
    """``dhsym-cli``: every command of ``dhsym``, from its argparse parser."""

    has_content = False

    def run(self) -> list[nodes.Node]:
        from dhsym.cli.main import build_parser

        parser = build_parser()
        result: list[nodes.Node] = []
        top = nodes.section(ids=["dhsym-command"], names=["dhsym command"])
        top += nodes.title(text="dhsym")
        top += nodes.literal_block(text=parser.format_usage().strip(), language="none")
        top.extend(_text_nodes(parser.description or ""))
        options = _option_list(parser)
        if options is not None:
            top += options
        top.extend(_text_nodes(parser.epilog or ""))
        self.state.document.note_implicit_target(top, top)
        result.append(top)
        for name, summary, sub in _subcommands(parser):
            result.append(self._command(f"dhsym {name}", summary, sub))
        return result

    def _command(self, title: str, summary: str, parser: argparse.ArgumentParser) -> nodes.Node:
        ident = nodes.make_id(title)
        sec = nodes.section(ids=[ident], names=[nodes.fully_normalize_name(title)])
        sec += nodes.title(text=title)
        self.state.document.note_implicit_target(sec, sec)
        sec += nodes.literal_block(text=parser.format_usage().strip(), language="none")
        description = parser.description or summary
        sec.extend(_text_nodes(description))
        options = _option_list(parser)
        if options is not None:
            sec += options
        sec.extend(_text_nodes(parser.epilog or ""))
        for name, sub_summary, sub in _subcommands(parser):
            sec += self._command(f"{title} {name}", sub_summary, sub)
        return sec


# --------------------------------------------------------------------------- mistakes


class MistakeCatalogue(Directive):
    """``dhsym-mistakes``: every kind of mistake the checker recognises, from the registry."""

    has_content = False

    def run(self) -> list[nodes.Node]:
        from dhsym.checking.mistakes import registry as mistakes

        lists = {
            "MATRIX_MISTAKES": "matrices",
            "TABLE_MISTAKES": "tables",
            "JACOBIAN_MISTAKES": "Jacobians",
            "DET_MISTAKES": "det J",
            "IK_MISTAKES": "inverse kinematics",
        }
        used: dict[str, list[str]] = {}
        for attr, label in lists.items():
            for m in getattr(mistakes, attr):
                used.setdefault(type(m).__name__, []).append(label)
        kinds = []
        for name in mistakes.__all__:
            cls = getattr(mistakes, name)
            if inspect.isclass(cls) and isinstance(getattr(cls, "kind", None), str) and cls.kind:
                kinds.append(cls)
        rows = []
        for cls in kinds:
            where = ", ".join(used.get(cls.__name__, [])) or "matrix entries"
            doc = " ".join((inspect.getdoc(cls) or "").split("\n\n")[0].split())
            title = getattr(cls, "title", "") or getattr(cls(), "title", "")
            home = cls.__module__ if _public(cls.__module__) else "dhsym.checking.mistakes.registry"
            rows.append((cls.kind, title, where, doc, f"{home}.{cls.__name__}"))
        per_instance = [(m, "dynamics") for m in mistakes.dynamics_mistakes()]
        per_instance += [(m, "product of exponentials") for m in mistakes.SCREW_MISTAKES]
        for m, where in per_instance:  # one class, one instance per kind
            cls = type(m)
            doc = " ".join((inspect.getdoc(cls) or "").split("\n\n")[0].split())
            rows.append(
                (
                    m.kind,
                    m.title,
                    where,
                    doc,
                    f"dhsym.checking.mistakes.registry.{cls.__name__}",
                )
            )
        for t in mistakes.TRAJECTORY_MISTAKES:  # one frozen value per kind
            rows.append(
                (
                    t.kind,
                    t.title,
                    "trajectories and gains",
                    t.detail,
                    "dhsym.checking.mistakes.trajectory_mistakes.TrajectoryMistake",
                )
            )
        rows.sort(key=lambda r: r[0])
        if type(self.state).__module__.startswith("myst_parser"):
            text = ["| kind | title | checked in | what the student did |", "|---|---|---|---|"]
            for kind, title, where, doc, target in rows:
                cells = (f"`{kind}`", title, where, f"{doc} ({{py:class}}`~{target}`)")
                text.append("| " + " | ".join(c.replace("|", "\\|") for c in cells) + " |")
        else:
            text = [".. list-table::", "   :header-rows: 1", ""]
            text += ["   * - kind", "     - title", "     - checked in"]
            text += ["     - what the student did"]
            for kind, title, where, doc, target in rows:
                text += [f"   * - ``{kind}``", f"     - {title}", f"     - {where}"]
                text += [f"     - {doc} (:class:`~{target}`)"]
        container = nodes.container()
        nested_parse_with_titles(self.state, StringList(text, source="dhsym-mistakes"), container)
        return container.children


def _module_sections(
    app: Sphinx, what: str, name: str, obj: object, options: object, lines: list[str]
) -> None:
    """numpydoc formats the docstrings of functions and classes, not of modules: turn a
    module docstring's numpy section headings (``Examples`` over dashes) into rubrics."""
    if what != "module":
        return
    k = 0
    while k + 1 < len(lines):
        title, rule = lines[k].strip(), lines[k + 1].strip()
        if title and rule and set(rule) == {"-"} and len(rule) >= len(title) - 1:
            lines[k : k + 2] = [f".. rubric:: {title}", ""]
        k += 1


def setup(app: Sphinx) -> dict[str, object]:
    app.add_config_value("dhsym_repo_root", "", "env")
    app.connect("builder-inited", _on_builder_inited)
    app.connect("build-finished", _on_build_finished)
    app.connect("autodoc-process-docstring", _module_sections)
    app.add_directive("dhsym-cli", CommandLine)
    app.add_directive("dhsym-mistakes", MistakeCatalogue)
    return {"parallel_read_safe": True, "parallel_write_safe": True, "version": "1"}
