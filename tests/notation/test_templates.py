"""The one template renderer: the loader, one vocabulary of formats, the families."""

from __future__ import annotations

import jinja2
import pytest

from dhsym.errors import DHError
from dhsym.notation.escape import TeX
from dhsym.notation.templates import (
    CODE,
    DOCUMENT,
    FEEDBACK,
    FORMATS,
    builtin_dir,
    environment,
    format_name,
    format_suffix,
    loader,
    render_template,
)


def test_one_vocabulary_of_formats_with_the_suffixes_as_aliases():
    assert FORMATS == {"latex": "tex", "markdown": "md", "html": "html", "text": "txt"}
    for name, suffix in FORMATS.items():
        assert format_name(name) == format_name(suffix) == name
        assert format_suffix(name) == format_suffix(suffix) == suffix
    with pytest.raises(DHError, match="unknown format 'pdf': expected one of latex, markdown"):
        format_name("pdf")


def test_every_template_is_named_with_a_known_suffix():
    names = [p.relative_to(builtin_dir()) for p in builtin_dir().rglob("*.j2")]
    assert len(names) > 30
    for name in names:
        if name.parts[0] == "export":  # generated code: the language's own suffix
            continue
        pictures = ("svg",)  # the grading summary's chart, drawn from its numbers
        assert name.suffixes[-2].lstrip(".") in (*FORMATS.values(), *pictures), name


def test_the_user_folder_comes_first_and_base_reaches_the_builtin(tmp_path):
    (tmp_path / "feedback.md.j2").write_text("mine")
    source = loader(tmp_path)
    env = jinja2.Environment(loader=source)
    assert env.get_template("feedback.md.j2").render() == "mine"
    assert "{{" in source.get_source(env, "base/feedback.md.j2")[0]
    with pytest.raises(DHError, match="does not exist"):
        loader(tmp_path / "missing")


def test_the_code_family_loads_the_export_templates():
    env = environment("text", CODE)
    assert env.get_template("c_header.h.j2").filename.endswith("export/c_header.h.j2")
    with pytest.raises(jinja2.TemplateNotFound):
        env.get_template("handout.tex.j2")


def test_documents_escape_every_value_feedback_only_html():
    value = "<b>_x_ & 50%</b>"
    doc_md = environment("markdown", DOCUMENT).from_string("{{ v }}").render(v=value)
    fb_md = environment("markdown", FEEDBACK).from_string("{{ v }}").render(v=value)
    fb_html = environment("html", FEEDBACK).from_string("{{ v }}").render(v=value)
    assert doc_md == r"&lt;b&gt;\_x\_ &amp; 50%&lt;/b&gt;"
    assert fb_md == value  # feedback templates escape with their filters (| md)
    assert fb_html == "&lt;b&gt;_x_ &amp; 50%&lt;/b&gt;"
    tex = environment("latex", DOCUMENT).from_string("((( v ))) ((( t )))")
    assert tex.render(v="50%", t=TeX(r"\pi")) == r"50\% \pi"
    assert environment("text", CODE).from_string("{{ v }}").render(v=value) == value


def test_documents_trim_blocks_and_feedback_keeps_them():
    src = "{% if true %}\n  a\n{% endif %}\n"
    assert environment("text", DOCUMENT).from_string(src).render() == "  a\n"
    assert environment("text", FEEDBACK).from_string(src).render() == "\n  a\n\n"


def test_documents_have_no_html_format():
    with pytest.raises(DHError, match="the document templates have no html format"):
        environment("html", DOCUMENT)


def test_filters_are_added_and_environments_built_once():
    filters = (("shout", str.upper),)
    env = environment("md", FEEDBACK, filters=filters)
    assert env.from_string("{{ 'a' | shout }}").render() == "A"
    assert env is environment("markdown", FEEDBACK, filters=filters)
    assert env is not environment("markdown", FEEDBACK)
    assert "shout" not in environment("markdown", FEEDBACK).filters


def test_render_template_turns_template_mistakes_into_one_error(tmp_path):
    (tmp_path / "bad.txt.j2").write_text("{{ 1 + }}")
    with pytest.raises(DHError, match=r"template bad.txt.j2: .*bad.txt.j2:1: "):
        render_template(environment("text", DOCUMENT, tmp_path), "bad.txt.j2")
    with pytest.raises(DHError, match="template missing.txt.j2: missing.txt.j2"):
        render_template(environment("text", DOCUMENT, tmp_path), "missing.txt.j2")
