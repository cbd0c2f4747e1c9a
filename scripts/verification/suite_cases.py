"""Runs test cases of the unit-test executable (build/tests/meshfree_tests, Catch2) and reads back
every assertion with its values (Catch2's XML reporter with -s), so that the report shows the very
numbers and bounds the suite checks, computed by the suite's own code."""
import html
import re
import subprocess
import tempfile
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path

from verification.page import Section, table


@dataclass
class Case:
    name: str
    passed: bool
    seconds: float
    assertions: list = field(default_factory=list)  # (expression, with values, passed)
    printed: str = ""


def escaped(name):
    """A test name as a Catch2 test spec: its special characters taken literally."""
    return re.sub(r'([\\,\[\]"~*])', r"\\\1", name)


def run(tests, names):
    """The named test cases, each in its own process; a name that matches nothing is an error."""
    return [run_one(tests, name) for name in names]


def run_one(tests, name):
    # The report goes to a file: what the test prints with printf reaches stdout unescaped.
    with tempfile.TemporaryDirectory() as tmp:
        report = Path(tmp) / "case.xml"
        proc = subprocess.run([tests, "-r", "xml", "-s", "-d", "yes", "-o", str(report),
                               escaped(name)], capture_output=True, text=True)
        cases = [read_case(tc) for tc in ET.parse(report).getroot().iter("TestCase")]
    if [c.name for c in cases] != [name]:
        raise RuntimeError(f"{tests}: no test case named {name!r} (exit {proc.returncode})")
    cases[0].printed = "\n".join(t for t in (proc.stdout.strip(), cases[0].printed) if t)
    return cases[0]


def read_case(tc):
    result = tc.find("OverallResult")
    assertions = []
    for e in tc.iter("Expression"):
        original = " ".join((e.findtext("Original") or "").split())
        expanded = " ".join((e.findtext("Expanded") or "").split())
        assertions.append((original, expanded, e.get("success") == "true"))
    return Case(name=tc.get("name"), passed=result.get("success") == "true",
                seconds=float(result.get("durationInSeconds", "nan")),
                assertions=assertions, printed=(result.findtext("StdOut") or "").strip())


def grouped(assertions, listed=4):
    """Table rows; an assertion made more than `listed` times (in a loop over particles, say) is
    one row with its count and its first failure, or its last values where none failed."""
    groups = {}
    for a in assertions:
        groups.setdefault(a[0], []).append(a)
    rows = []
    for original, members in groups.items():
        if len(members) <= listed:
            rows += [(o, v, "yes" if ok else "NO") for o, v, ok in members]
            continue
        failed = [m for m in members if not m[2]]
        shown = failed[0] if failed else members[-1]
        rows.append((f"{original} ({len(members)} times)", shown[1],
                     f"NO ({len(failed)} failed)" if failed else "yes, every time"))
    return rows


def section(tests, names, intro):
    """A section of the named test cases: their printed measurements and every assertion."""
    cases = run(tests, names)
    parts = [f"<p>{intro}</p>"]
    for c in cases:
        state = "passed" if c.passed else "FAILED"
        parts.append(f"<h3>{html.escape(c.name)}</h3><p>{state} in {c.seconds:.1f} s; "
                     f"{sum(a[2] for a in c.assertions)} of {len(c.assertions)} assertions hold.</p>")
        if c.printed:
            parts.append(f'<pre class="log">{html.escape(c.printed)}</pre>')
        parts.append(table(["assertion (tests/*.cpp)", "with the values of this run", "holds"],
                           grouped(c.assertions)))
    return Section("".join(parts), all(c.passed for c in cases))
