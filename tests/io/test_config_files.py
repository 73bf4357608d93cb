"""The one YAML reader (tennis_stroke.io.config_files): a key given twice is refused with
file and line, exponent numbers are numbers (as in YAML 1.2, also in claims.yaml), and a
file that is not UTF-8 is one line."""

import pytest
import yaml

from tennis_stroke.io.config_files import ConfigFileError, load_yaml


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
