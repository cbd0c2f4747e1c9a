#!/usr/bin/python3
"""The module include graph of meshfree: which module's files include which other module's headers
(include/meshfree/<module>/ and src/<module>/), printed as one line per module, checked against
the layering of docs/architecture.md.

    scripts/include_graph.py            # prints the graph; exits 1 if it has a cycle
    scripts/include_graph.py --check    # also checks the allowed dependencies below and the
                                        # size limits (app/ under 800 lines, no file over 600,
                                        # no function over 80 lines outside data tables)

The allowed dependencies are the module map of docs/architecture.md: a module may include the
modules listed for it and, through them, nothing that lies above it.
"""
import argparse
import re
import sys
from collections import defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
INCLUDE = re.compile(r'^\s*#\s*include\s+"meshfree/(([a-z_0-9]+)/[a-z_0-9]+\.hpp)"', re.M)

# Module -> the modules it may include (docs/architecture.md, "Module map").
ALLOWED = {
    "core": set(),
    "neighbors": {"core", "particles"},
    "geometry": {"core", "neighbors"},
    "materials": {"core"},
    "kernels": {"core"},
    "loads": {"core"},
    "verification": {"core", "materials"},
    "particles": {"core"},
    "distribution": {"core", "particles", "solvers"},
    "quadrature": {"core", "geometry"},
    "solvers": {"core"},
    "fem": {"core", "geometry", "materials", "neighbors"},
    "spec": {"core", "geometry", "materials", "loads", "kernels", "verification"},
    "io": {"core", "spec", "particles", "distribution"},
    "implicit": {"core", "geometry", "materials", "kernels", "quadrature", "neighbors", "fem",
                 "solvers", "spec", "io", "verification", "loads", "distribution"},
    "pd": {"core", "geometry", "materials", "particles", "neighbors", "loads", "distribution",
           "solvers"},
    "sph": {"core", "geometry", "materials", "particles", "neighbors", "kernels", "loads",
            "distribution"},
    "explicit": {"core", "geometry", "materials", "particles", "neighbors", "kernels", "loads",
                 "pd", "sph", "spec", "io", "solvers", "distribution"},
    "stages": {"core", "geometry", "materials", "particles", "neighbors", "kernels", "loads",
               "distribution",
               "quadrature", "fem", "solvers", "spec", "io", "verification", "implicit", "pd", "sph",
               "explicit"},
    "app": None,  # may include anything
}


# Plain-data headers of a solver module (its parameter structs, including nothing but core and
# kernels) that the problem spec holds as they are instead of a copy of its own.
SOLVER_PARAMETERS = {"spec": {"sph/settings.hpp"}}

def module_of(path: Path):
    rel = path.relative_to(ROOT)
    parts = rel.parts
    if parts[0] == "include":
        return parts[2]
    return parts[1]


def graph():
    g = defaultdict(set)
    for path in list((ROOT / "include" / "meshfree").rglob("*.hpp")) + list((ROOT / "src").rglob("*.[ch]pp")):
        m = module_of(path)
        g.setdefault(m, set())
        for header, dep in INCLUDE.findall(path.read_text()):
            if dep != m and header not in SOLVER_PARAMETERS.get(m, ()):
                g[m].add(dep)
    return g


# Functions that are data tables, exempt from the length limit: (file, first line's text).
DATA_TABLES = {("src/loads/blast.cpp", "const std::vector<Segment>& segments() {")}
DECLARATION_STARTS = ("//", "#", "}", "namespace", "using", "struct", "class", "enum", "template",
                      "extern", "static_assert", "constexpr", "inline constexpr")


def function_lengths(path: Path):
    """(lines, first line number, first line) of each function defined at file scope in `path`,
    in the code's layout (clang-format: a definition starts at column 0 and ends at a lone '}')."""
    lines = path.read_text().splitlines()
    i = 0
    while i < len(lines):
        first = lines[i]
        if (first and not first[0].isspace() and not first.startswith(DECLARATION_STARTS)
                and "(" in first and not first.rstrip().endswith(";")):
            j = i
            while j < len(lines) and not lines[j].rstrip().endswith(("{", ";")):
                j += 1
            if j < len(lines) and lines[j].rstrip().endswith("{"):
                k = j + 1
                while k < len(lines) and lines[k] != "}":
                    k += 1
                yield k - i + 1, i + 1, first.strip()
                i = k
        i += 1


def long_functions(limit=80):
    for p in sorted(list((ROOT / "src").rglob("*.cpp")) + list((ROOT / "include").rglob("*.hpp"))):
        rel = str(p.relative_to(ROOT))
        for n, line, first in function_lengths(p):
            if n > limit and (rel, first) not in DATA_TABLES:
                yield f"{rel}:{line} has a function of {n} lines (at most {limit}): {first}"


def cycle(g):
    state, stack = {}, []

    def visit(n):
        state[n] = 1
        stack.append(n)
        for d in sorted(g.get(n, ())):
            if state.get(d) == 1:
                return stack[stack.index(d):] + [d]
            if d not in state:
                c = visit(d)
                if c:
                    return c
        state[n] = 2
        stack.pop()
        return None

    for n in sorted(g):
        if n not in state:
            c = visit(n)
            if c:
                return c
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--check", action="store_true")
    args = ap.parse_args()
    g = graph()
    for m in sorted(g):
        print(f"{m} -> {', '.join(sorted(g[m])) or '(nothing)'}")
    problems = []
    c = cycle(g)
    if c:
        problems.append("include cycle: " + " -> ".join(c))
    if args.check:
        for m, deps in sorted(g.items()):
            allowed = ALLOWED.get(m, set())
            if allowed is None:
                continue
            if m not in ALLOWED:
                problems.append(f"module {m} is not in the module map of docs/architecture.md")
                continue
            for d in sorted(deps - allowed):
                problems.append(f"{m} includes {d}, which the module map does not allow")
        app = sum(len(p.read_text().splitlines()) for p in (ROOT / "src" / "app").glob("*.cpp"))
        print(f"src/app: {app} lines")
        if app > 800:
            problems.append(f"src/app holds {app} lines (at most 800: drivers are recipes)")
        for p in sorted(list((ROOT / "src").rglob("*.cpp")) + list((ROOT / "include").rglob("*.hpp"))):
            n = len(p.read_text().splitlines())
            if n > 600:
                problems.append(f"{p.relative_to(ROOT)} has {n} lines (at most 600)")
        problems += list(long_functions())
        for header in set().union(*SOLVER_PARAMETERS.values()):
            for _, dep in INCLUDE.findall((ROOT / "include" / "meshfree" / header).read_text()):
                if dep not in ("core", "kernels", header.split("/")[0]):
                    problems.append(f"{header} is held by the spec and includes {dep}")
        raw_mpi = [str(p.relative_to(ROOT)) for p in (ROOT / "src" / "app").glob("*.cpp")
                   if re.search(r"\bMPI_(?!Abort)[A-Z][a-z_]+\s*\(", p.read_text())]
        if raw_mpi:
            problems.append("raw MPI calls in " + ", ".join(raw_mpi))
    for p in problems:
        print("FAIL:", p)
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
