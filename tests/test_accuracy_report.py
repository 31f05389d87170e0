"""The accuracy-versus-time report (benchmarks/accuracy_vs_time.py) keeps working.

Runs ``--quick`` in a subprocess into a temporary directory and checks that the Markdown table
and the PNG exist, that every model family appears, and that the numbers are finite. Nothing is
asserted about the timings (they depend on the machine and its load).
"""

import math
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
FAMILIES = ["2-D Hertz/Carter", "2-D corrugated rail", "3-D creep forces", "Corrugation & wear",
            "Friction (Ch. 5)", "Non-steady & one asperity", "Roughness, two patches (Ch. 6)",
            "FMU (per step)"]


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    out = tmp_path_factory.mktemp("accuracy")
    proc = subprocess.run([sys.executable, str(ROOT / "benchmarks" / "accuracy_vs_time.py"),
                           "--quick", "--out", str(out)], capture_output=True, text=True,
                          timeout=900, cwd=str(ROOT))
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    return out


def _sections(text):
    """{family heading: list of table rows (cells)} of the Markdown report."""
    out, current = {}, None
    for line in text.splitlines():
        if line.startswith("## "):
            current = line[3:].strip()
            out[current] = []
        elif current and line.startswith("| ") and not line.startswith("| method") \
                and not line.startswith("|---"):
            out[current].append([c.strip() for c in line.strip("|").split("|")])
    return out


def _number(cell):
    """Seconds or a plain float from a cell ('1.2e-03', '12.3 us', '4.5 ms', '1.2 s')."""
    m = re.fullmatch(r"([-+0-9.eE]+)( us| ms| s)?", cell)
    if not m:
        return None
    factor = {None: 1.0, " us": 1e-6, " ms": 1e-3, " s": 1.0}[m.group(2)]
    return float(m.group(1)) * factor


def test_outputs_exist(report):
    md = report / "accuracy_vs_time.md"
    png = report / "figures" / "accuracy_vs_time.png"
    assert md.is_file() and md.stat().st_size > 1000
    assert png.is_file() and png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "figures/accuracy_vs_time.png" in md.read_text()


def test_every_family_with_finite_numbers(report):
    sections = _sections((report / "accuracy_vs_time.md").read_text())
    for fam in FAMILIES:
        assert fam in sections, f"family {fam!r} missing"
        rows = sections[fam]
        assert rows, f"family {fam!r} has no rows"
        errors = [_number(r[2]) for r in rows]
        times = [_number(r[-3]) for r in rows]   # single-call column
        assert any(e is not None and math.isfinite(e) for e in errors), fam
        assert all(t is not None and math.isfinite(t) and t > 0 for t in times), fam
        assert all(e is None or e >= 0 for e in errors), fam
        for r in rows:                                   # no NaN / inf printed anywhere
            assert not any(c.lower() in ("nan", "inf") for c in r), r


def test_answers_section(report):
    text = (report / "accuracy_vs_time.md").read_text()
    for key in ("## Answers", "error budget", "How fast the tables are",
                "linearised closed forms", "Where the tables", "(4.28)", "CONTACT", "FASTSIM",
                "USETAB"):
        assert key in text, key


def test_comparison_methods_measured_and_regions_table(report):
    """FASTSIM, Polach and FaStrip are measured points of the 3-D family (finite error and
    time), and the 'within 1 %, 5 %, 10 % of mu N' table has a row per 3-D method with one
    cell per (a/b, spin class)."""
    sections = _sections((report / "accuracy_vs_time.md").read_text())
    rows = {r[0].replace(" **(P)**", ""): r for r in sections["3-D creep forces"]}
    for method in ("fastsim", "polach", "fastrip"):
        r = rows[f"comparison: {method}"]
        assert 0 < _number(r[2]) < 0.2 and _number(r[-3]) > 0 and _number(r[-2]) > 0
    table = sections["Where each 3-D method is within 1 %, 5 %, 10 % of mu N"]
    assert [r[0] for r in table] == ["linear", "she", "strip", "modified_strip", "fastsim",
                                     "polach", "fastrip"]
    for r in table:
        assert len(r) == 1 + 9
        assert all(re.fullmatch(r"(<= (1|5|10) %|> 10 %) \([0-9.]+\)", c) for c in r[1:]), r
