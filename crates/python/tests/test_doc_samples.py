"""The Python sessions shown in README.md and docs/*.md print what they show.

A fenced block preceded by `<!-- sample: python -->` is a session: statements after `>>> `
(continued by `... `), each followed by what it displays. The test runs every session in one
namespace from the repository's root (as a reader would, paths like assets/drives/cj_wall.toml
are relative to it) and compares what each statement displays with the block: the text exactly
(runs of spaces as one, pandas aligns its columns to the widest value), the numbers at their
printed precision (one unit in the last printed digit; whole numbers exactly). The command
samples (`<!-- sample -->`) are checked by crates/cli/tests/doc_samples.rs, which also fails on
a session without its marker.

FLEXRIG_BLESS=1 rewrites the sessions' displayed lines with what they display now
(scripts/bless-docs.sh).
"""

import contextlib
import io
import os
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]
MARKER = "<!-- sample: python -->"
NUMBER = re.compile(r"(?<![\w.])-?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?")


def documents():
    return [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]


def sessions():
    """(path, index of the first line inside the fence, index of the closing fence) of every
    marked block."""
    out = []
    for path in documents():
        lines = path.read_text(encoding="utf-8").split("\n")
        fence = None
        for i, line in enumerate(lines):
            if not line.lstrip().startswith("```"):
                continue
            if fence is None:
                fence = i
                continue
            above = [x for x in lines[:fence] if x.strip()]
            if above and above[-1].strip() == MARKER:
                out.append((path, fence + 1, i))
            fence = None
    return out


def examples(lines):
    """The statements of a session: (source, first and end index of their displayed lines)."""
    out = []
    i = 0
    while i < len(lines):
        assert lines[i].startswith(">>> "), f"a session line outside a statement: {lines[i]!r}"
        source = [lines[i][4:]]
        i += 1
        while i < len(lines) and lines[i].startswith("... "):
            source.append(lines[i][4:])
            i += 1
        start = i
        while i < len(lines) and not lines[i].startswith(">>> "):
            i += 1
        out.append(("\n".join(source), start, i))
    return out


def shape(number):
    mantissa, _, exponent = number.lower().partition("e")
    decimals = len(mantissa.partition(".")[2])
    return decimals, int(exponent or 0), bool(exponent)


def numbers_agree(doc, now):
    if doc == now:
        return True
    if "." not in doc and "e" not in doc.lower():
        return False
    decimals, exponent, has_exponent = shape(doc)
    if shape(now)[0] != decimals or shape(now)[2] != has_exponent:
        return False
    return abs(float(doc) - float(now)) <= 10.0 ** (exponent - decimals) * (1 + 1e-9)


def lines_agree(doc, now):
    doc_text, now_text = NUMBER.split(doc.strip()), NUMBER.split(now.strip())
    if [" ".join(t.split()) for t in doc_text] != [" ".join(t.split()) for t in now_text]:
        return False
    doc_numbers, now_numbers = NUMBER.findall(doc), NUMBER.findall(now)
    return len(doc_numbers) == len(now_numbers) and all(
        numbers_agree(a, b) for a, b in zip(doc_numbers, now_numbers)
    )


def run(source, namespace):
    """What `source` displays at the prompt, as lines."""
    buffer = io.StringIO()
    with contextlib.redirect_stdout(buffer):
        exec(compile(source, "<docs>", "single"), namespace)
    return buffer.getvalue().rstrip("\n").split("\n") if buffer.getvalue().strip() else []


def test_the_comparison_reads_numbers_at_their_printed_precision():
    assert lines_agree("0  0.0  0.000000", "0  0.0   0.000001")
    assert not lines_agree("0.001804221687669039", "0.001804221687669041")
    assert not lines_agree("3 rows", "4 rows")
    assert not lines_agree("HIC15 1.5", "HIC16 1.5")
    assert NUMBER.findall("x_1 v0 2.5e-3 -4 cl_wall") == ["2.5e-3", "-4"]


def test_the_documents_hold_sessions():
    assert sessions(), "no <!-- sample: python --> block in README.md or docs/*.md"


@pytest.mark.parametrize(
    "path,start,end",
    sessions(),
    ids=lambda v: v.name if isinstance(v, Path) else str(v),
)
def test_a_documented_session_displays_what_it_shows(path, start, end, monkeypatch):
    monkeypatch.chdir(ROOT)
    lines = path.read_text(encoding="utf-8").split("\n")
    namespace = {"__name__": "__docs__"}
    bless = os.environ.get("FLEXRIG_BLESS") == "1"
    replacements = []
    failures = []
    for source, first, last in examples(lines[start:end]):
        now = run(source, namespace)
        doc = lines[start + first : start + last]
        if len(doc) == len(now) and all(lines_agree(d, n) for d, n in zip(doc, now)):
            continue
        if bless:
            replacements.append((start + first, start + last, now))
        else:
            failures.append(
                f"{path.name}:{start + first}: >>> {source}\n  documented:\n"
                + "\n".join(f"    {d}" for d in doc)
                + "\n  displayed:\n"
                + "\n".join(f"    {n}" for n in now)
            )
    if replacements:
        for first, last, now in reversed(replacements):
            lines[first:last] = now
        path.write_text("\n".join(lines), encoding="utf-8")
    assert not failures, (
        "documented Python output differs (rewrite it with FLEXRIG_BLESS=1, "
        "scripts/bless-docs.sh):\n" + "\n".join(failures)
    )
