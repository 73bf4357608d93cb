"""The one YAML reader (tennis_stroke.io.config_files): a key given twice is refused with
file and line, exponent numbers are numbers (as in YAML 1.2, also in claims.yaml), and a
file that is not UTF-8 is one line."""

import sys
from pathlib import Path

import pytest
import yaml

from tennis_stroke.io.config_files import ConfigFileError, load_yaml

ROOT = Path(__file__).resolve().parents[2]


def test_a_duplicate_key_is_refused_naming_file_and_line(tmp_path):
    path = tmp_path / "claims.yaml"
    path.write_text("a: 1\nb:\n  x: 1\n  x: 2\n")
    with pytest.raises(
        ConfigFileError, match=r"claims.yaml, line 4, column 3: .*duplicate key 'x'"
    ):
        load_yaml(path)


@pytest.mark.parametrize(
    "text, value",
    [
        ("2e-3", 2e-3),
        ("1e6", 1e6),
        ("-3E+2", -300.0),
        ("1.5e-2", 1.5e-2),
        ("2", 2),
        ("abc", "abc"),
        ("1e", "1e"),
        ("e5", "e5"),
    ],
)
def test_exponent_numbers_are_numbers(tmp_path, text, value):
    path = tmp_path / "c.yaml"
    path.write_text(f"tolerance: {text}\n")
    got = load_yaml(path)["tolerance"]
    assert got == value and type(got) is type(value)


def test_the_shipped_files_read_as_before(tmp_path):
    """The reader changes nothing of the shipped config, claims and readings."""
    from pathlib import Path

    root = Path(__file__).resolve().parents[2] / "config"
    for name in ("config.yaml", "claims.yaml", "readings.yaml"):
        assert load_yaml(root / name) == yaml.safe_load((root / name).read_text())


def test_a_file_that_is_not_utf8_is_one_line(tmp_path):
    path = tmp_path / "config.yaml"
    path.write_bytes(b"model: {}\nname: \xff\xfe\n")
    with pytest.raises(ConfigFileError, match="config.yaml: not a UTF-8 text file"):
        load_yaml(path)


def bomb(levels: int, nested_in: str = "") -> str:
    """YAML of ``levels`` levels of nine references each (9^levels values expanded),
    below the mapping keys ``nested_in`` (dotted) if given."""
    lines = ["l0: &l0 [1, 2, 3, 4, 5, 6, 7, 8, 9]"]
    lines += [f"l{i}: &l{i} [{', '.join([f'*l{i - 1}'] * 9)}]" for i in range(1, levels)]
    indent = ""
    head = []
    for key in filter(None, nested_in.split(".")):
        head.append(f"{indent}{key}:")
        indent += "  "
    return "\n".join([*head, *(indent + line for line in lines)]) + "\n"


@pytest.mark.parametrize(
    "text",
    [
        bomb(9),  # a top-level mapping of lists
        bomb(9, "scenario.model"),  # nested inside one scenario's overrides
        "a: &a {x: 1, y: 2, z: 3}\n"  # merge keys: mappings of mappings
        + "".join(
            f"{c}: &{c} {{{', '.join(f'k{j}: *{p}' for j in range(12))}}}\n"
            for p, c in zip("abcdefg", "bcdefgh", strict=True)
        ),
    ],
    ids=["top-level", "in-a-scenario", "mappings"],
)
def test_an_alias_bomb_is_refused_in_one_line_at_once(tmp_path, text):
    """Aliases that expand to more than MAX_VALUES values: one line, before any reader
    walks the expanded data (sorted_data took minutes and gigabytes on a bomb inside one
    scenario).  The count itself never expands: it visits each value it meets, as
    written, once per reference (a few hundred here, against 9^9 = 3.9e8 expanded),
    counted by a profiler, not a clock."""
    path = tmp_path / "scenarios.yaml"
    path.write_text(text)
    visits = [0]

    def count(frame, event, arg):
        if event == "call" and frame.f_code.co_name == "size":
            visits[0] += 1

    sys.setprofile(count)
    try:
        with pytest.raises(ConfigFileError, match=r"values once its YAML aliases are") as err:
            load_yaml(path)
    finally:
        sys.setprofile(None)
    assert "\n" not in str(err.value)
    assert 0 < visits[0] < 10 * len(text), visits[0]


def test_aliases_that_expand_to_a_few_values_are_read():
    from tennis_stroke.io.config_files import MAX_VALUES, expanded_size

    shared = [1, 2, 3]
    assert expanded_size({"a": shared, "b": {"c": shared, "d": 4}}) == 1 + 4 + (1 + 4 + 1)
    recursive: list = [1]
    recursive.append(recursive)
    assert expanded_size(recursive) == 3  # a node inside itself counts once
    assert MAX_VALUES >= 100 * expanded_size(load_yaml(ROOT / "config" / "config.yaml"))
