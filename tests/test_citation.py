"""The citation file: valid Citation File Format 1.2.0 (what `make lint` checks), citing
the paper it replicates; its check names what is wrong."""

import sys
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tools"))

from citation_check import problems  # noqa: E402


def test_the_citation_file_is_valid_and_cites_the_paper():
    assert problems(ROOT / "CITATION.cff") == []
    cff = yaml.safe_load((ROOT / "CITATION.cff").read_text())
    (paper,) = cff["references"]
    assert paper["url"] == "https://arxiv.org/abs/1505.01916"
    assert cff["license"] == "MIT" and "version" not in cff  # one version: _version.py


def test_a_broken_citation_file_is_named_key_by_key(tmp_path):
    cff = yaml.safe_load((ROOT / "CITATION.cff").read_text())
    del cff["authors"]
    cff["license"] = "not-a-licence"
    cff["date-released"] = "7 December"
    path = tmp_path / "CITATION.cff"
    path.write_text(yaml.safe_dump(cff))
    found = problems(path)
    assert len(found) == 3, found
    assert any("'authors' is a required property" in line for line in found)
    assert any(line.startswith(f"{path}: license:") for line in found)
    assert any(line.startswith(f"{path}: date-released:") for line in found)
    path.write_text("title: [unclosed\n")
    (line,) = problems(path)
    assert line.startswith(f"{path}: cannot be read")
