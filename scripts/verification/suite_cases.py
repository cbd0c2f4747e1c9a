"""Runs test cases of the unit-test executable (build/tests/meshfree_tests, Catch2) and reads back
every assertion with its values (Catch2's XML reporter with -s), so that the report shows the very
numbers and bounds the suite checks, computed by the suite's own code."""
import html
import re
import subprocess
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field

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
    """The named test cases, run in one process; a name that matches nothing is an error."""
    cmd = [tests, "-r", "xml", "-s", "-d", "yes", "--order", "decl"] + [escaped(n) for n in names]
    proc = subprocess.run(cmd, capture_output=True, text=True)
    root = ET.fromstring(proc.stdout[proc.stdout.index("<Catch"):])
    cases = [read_case(tc) for tc in root.iter("TestCase")]
    missing = set(names) - {c.name for c in cases}
    if missing:
        raise RuntimeError(f"{tests}: no test case named {sorted(missing)}")
    return cases


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
