"""Rendering the document templates: the environments of each format, and one derivation."""

from __future__ import annotations

import dataclasses

import pytest

import dhsym
from dhsym.errors import DHError
from dhsym.explain.derivation import derive
from dhsym.explain.rendering import (
    _text_columns,
    _text_grid,
    environment,
    render,
    render_template,
)
from dhsym.notation.escape import TeX

HOSTILE_NAME = "Arm \\input{/etc/passwd} 50% *x* <b>\x1b[31m"


@pytest.fixture(scope="module")
def planar():
    return derive("planar2r")


def test_each_format_renders_its_own_template(planar):
    text = render(planar, "text")
    md = render(planar, "markdown")
    tex = render(planar, "latex")
    assert text.splitlines()[:2] == [
        "Planar 2R: forward kinematics (standard DH convention)",
        "=" * len("Planar 2R: forward kinematics (standard DH convention)"),
    ]
    assert "$$" in md or "$" in md
    assert r"C_{12} & -S_{12} & 0 & a_{1} C_{1} + a_{2} C_{12}" in tex
    assert r"\documentclass" not in tex  # a fragment, not a document
    assert len({text, md, tex}) == 3


def test_format_suffixes_name_the_same_formats(planar):
    assert render(planar, "md") == render(planar, "markdown")
    assert render(planar, "tex") == render(planar, "latex")
    assert render(planar, "txt") == render(planar, "text")


def test_an_unknown_format_is_one_clear_error(planar):
    with pytest.raises(DHError, match="unknown format 'docx'"):
        render(planar, "docx")
    with pytest.raises(DHError, match="unknown format 'html': expected one of latex, markdown"):
        environment("html")


def test_the_kind_of_a_document_picks_its_templates():
    jac = dhsym.explain.derive_jacobian(dhsym.load("planar2r"))
    assert jac.kind == "jacobian"
    assert "J2 = [z_1 x (o_2 - o_1); z_1]" in render(jac, "text")


def test_a_hostile_robot_name_prints_as_text_in_every_format(planar):
    hostile = dataclasses.replace(planar, name=HOSTILE_NAME)
    tex = render(hostile, "latex")
    assert r"\input" not in tex and r"\textbackslash{}input\{/etc/passwd\} 50\%" in tex
    md = render(hostile, "markdown")
    assert "<b>" not in md and r"\*x\* &lt;b&gt;" in md
    text = render(hostile, "text")
    assert "\x1b" not in text and "Arm \\input{/etc/passwd} 50% *x* <b>[31m" in text


def test_latex_escapes_strings_but_prints_trusted_tex_verbatim():
    env = environment("latex")
    src = "((( a ))) ((( b ))) ((( c|tex )))((= a comment =))"
    out = env.from_string(src).render(a="x_1 & y", b=TeX(r"\theta_{1}"), c=r"\alpha")
    assert out == r"x{\ttfamily\char95}1 \& y \theta_{1} \alpha"
    assert environment("latex").from_string("{{ a }}").render(a=1) == "{{ a }}"  # TeX braces


def test_markdown_escapes_and_text_drops_control_characters():
    md = environment("markdown").from_string("{{ a }} {{ b }}")
    assert md.render(a="*a* [l](u)", b=TeX("C_{1}")) == r"\*a\* \[l\](u) C_{1}"
    txt = environment("text").from_string("{{ a }}")
    assert txt.render(a="x\u202ey\x07\n*z*") == "xy\n*z*"


def test_template_mistakes_are_errors_that_name_the_template(tmp_path):
    (tmp_path / "undefined.txt.j2").write_text("{{ nothing }}")
    (tmp_path / "broken.txt.j2").write_text("line\n{% if %}")
    env = environment("text", tmp_path)
    with pytest.raises(DHError, match="template undefined.txt.j2: 'nothing' is undefined"):
        render_template(env, "undefined.txt.j2")
    with pytest.raises(DHError, match=r"template broken.txt.j2: .*broken.txt.j2:2: "):
        render_template(env, "broken.txt.j2")


def test_a_user_template_folder_comes_first_and_base_reaches_the_builtin(tmp_path, planar):
    (tmp_path / "derivation.txt.j2").write_text(
        '{% extends "base/derivation.txt.j2" %}{% block heading %}MINE {{ d.name }}\n{% endblock %}'
    )
    out = render(planar, "text", template_dir=tmp_path)
    assert out.startswith("MINE Planar 2R\n")
    assert "1. The DH table" in out  # the rest is the built-in template's
    assert environment("text", tmp_path) is environment("text", str(tmp_path))
    assert environment("text", tmp_path) is not environment("text")


def test_a_missing_template_folder_is_refused(tmp_path, planar):
    with pytest.raises(DHError, match="does not exist"):
        render(planar, "text", template_dir=tmp_path / "missing")


def test_text_grid_brackets_and_aligns_the_columns():
    assert _text_grid([["C12", "-S12"], ["S12", "C12"]]) == [
        "[ C12  -S12 ]",
        "[ S12   C12 ]",
    ]
    cell = type("Cell", (), {"text": "a1*C1"})()
    assert _text_grid([[cell, 0]]) == ["[ a1*C1  0 ]"]


def test_text_columns_fill_the_width():
    items = [f"item{k}" for k in range(10)]
    lines = _text_columns(items, width=30)
    assert lines == [
        "item0   item1   item2   item3",  # 4 columns of 5 + 3 characters fit in 30 + 3
        "item4   item5   item6   item7",
        "item8   item9",
    ]
    assert all(len(line) <= 30 for line in lines)
    assert _text_columns([]) == []
    assert _text_columns(["a-very-long-item"], width=5) == ["a-very-long-item"]
