"""Unit tier: the documents rendered from results files say what those files
hold: BENCHMARKS.md from bench/results.json, bench/tutorials.json and
bench/coupling.json (rendered by bench/report.py)."""
import json
import sys
from pathlib import Path

import pytest

PROJECT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(PROJECT / "bench"))
import report  # noqa: E402  (bench/ is not a package)

pytestmark = pytest.mark.unit


def test_benchmarks_md_is_rendered_from_the_results(tmp_path):
    results = json.loads((PROJECT / "bench" / "results.json").read_text())
    rendered = tmp_path / "BENCHMARKS.md"
    report.write(results, rendered)
    assert rendered.read_text() == (PROJECT / "BENCHMARKS.md").read_text(), \
        "BENCHMARKS.md differs from its results: run bench/report.py"

