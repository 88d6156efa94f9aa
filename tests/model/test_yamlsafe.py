"""The one YAML loader and the capped file reader: nothing explodes, nothing blocks."""

from __future__ import annotations

import os

import pytest
import yaml
from hypothesis import given, settings
from hypothesis import strategies as st

from dhsym.model.yamlsafe import FileRefused, YAMLInputError, YAMLLimits, load_yaml, read_limited


def laughs(levels: int, width: int = 10, leaf: str = "x") -> str:
    lines = [f"l0: &l0 [{', '.join([leaf] * width)}]"]
    for k in range(1, levels):
        lines.append(f"l{k}: &l{k} [" + ", ".join([f"*l{k - 1}"] * width) + "]")
    return "\n".join(lines) + "\n"


def test_plain_yaml_loads_as_plain_data():
    assert load_yaml("a: [1, 2.5, x, true, null]\nb: {c: d}") == {
        "a": [1, 2.5, "x", True, None],
        "b": {"c": "d"},
    }
    assert load_yaml("a: &x [1, 2]\nb: *x") == {"a": [1, 2], "b": [1, 2]}


def test_aliases_count_every_time_they_are_used():
    assert load_yaml(laughs(4))["l3"][0][0][0] == ["x"] * 10  # 10**4 values: fine
    with pytest.raises(YAMLInputError, match="more than 100000 values"):
        load_yaml(laughs(6))  # 400 bytes, 10**6 values
    long = "y" * 5000
    with pytest.raises(YAMLInputError, match="expand to more than 4000000 characters"):
        load_yaml(laughs(3, leaf=long))  # few values, but 5 * 10**6 characters


def test_a_structure_that_contains_itself_is_refused():
    with pytest.raises(YAMLInputError, match=r"line 1: the alias \*a is inside its own anchor"):
        load_yaml("joints: &a [*a, *a, *a]\nname: &b [*a, *a]")


def test_depth_digits_size_and_tags():
    with pytest.raises(YAMLInputError, match="nested more than 64 levels"):
        load_yaml("a: " + "{b: " * 65 + "1" + "}" * 65)
    assert isinstance(load_yaml("[" * 64 + "]" * 64), list)  # 64 levels are fine
    with pytest.raises(YAMLInputError, match="a number with 5000 digits"):
        load_yaml("n: " + "9" * 5000)
    with pytest.raises(YAMLInputError, match="the YAML text is 11 bytes; at most 10"):
        load_yaml("a: 12345678", limits=YAMLLimits(max_bytes=10))
    with pytest.raises(YAMLInputError, match="not valid YAML"):
        load_yaml("x: !!python/object/apply:os.system ['touch /tmp/pwned']")
    with pytest.raises(YAMLInputError, match="not UTF-8"):
        load_yaml(b"a: \xff")


@settings(max_examples=300, deadline=None, derandomize=True)
@given(st.text(alphabet="[]{}&*:,- ab1\n#!|>'\"?%@`", max_size=120))
def test_any_text_is_data_or_one_clear_error(text):
    try:
        load_yaml(text, file="f.yaml")
    except YAMLInputError as err:
        assert str(err).startswith("f.yaml: ") and "\n" not in err.message


def test_read_limited_reads_regular_files_up_to_the_cap(tmp_path):
    p = tmp_path / "a.txt"
    p.write_bytes(b"x" * 100)
    assert read_limited(p, 100) == b"x" * 100
    with pytest.raises(FileRefused, match="is 100 bytes; at most 99"):
        read_limited(p, 99)
    link = tmp_path / "link.txt"
    link.symlink_to(p)
    assert read_limited(link, 100) == b"x" * 100
    with pytest.raises(FileRefused, match="symbolic link"):
        read_limited(link, 100, follow_links=False)
    hard = tmp_path / "hard.txt"
    os.link(p, hard)
    assert read_limited(hard, 100) == b"x" * 100
    with pytest.raises(FileRefused, match="2 hard links"):
        read_limited(hard, 100, hard_links=False)


def test_read_limited_never_blocks_or_trusts_the_size(tmp_path):
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    for special in (fifo, "/dev/zero", "/dev/urandom", tmp_path):
        with pytest.raises(FileRefused, match="not a regular file"):
            read_limited(special, 10)
    status = "/proc/self/status"  # a regular file whose st_size is 0
    if os.path.exists(status) and os.stat(status).st_size == 0:
        with pytest.raises(FileRefused, match="larger than 10 bytes"):
            read_limited(status, 10)
    with pytest.raises(FileRefused, match="No such file"):
        read_limited(tmp_path / "nope", 10)


def test_pyyaml_would_have_expanded_the_bomb():
    """The reason for all this: ``safe_load`` builds the shared lists, ``str`` expands them."""
    data = yaml.safe_load(laughs(4))
    assert len(str(data["l3"])) > 10**4
