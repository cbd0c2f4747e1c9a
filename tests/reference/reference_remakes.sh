#!/usr/bin/env bash
# The CalculiX reference in reference/calculix is remade by its recipe: rerunning the script
# gives the committed sampled displacements (CalculiX single-threaded is bit-reproducible; the
# comparison allows 1e-6 of the largest value on a line for other CalculiX builds).
set -eu
ROOT="$1"
WORK="$(mktemp -d)"; trap 'rm -rf "$WORK"' EXIT
CALCULIX_REFERENCE_OUT="$WORK" /usr/bin/python3 "$ROOT/scripts/fe_reference/make_calculix_reference.py" > "$WORK/log.txt" ||
  { tail -30 "$WORK/log.txt"; exit 1; }
/usr/bin/python3 - "$ROOT/reference/calculix" "$WORK" <<'PY'
import csv, sys
committed, remade = sys.argv[1], sys.argv[2]
worst = 0.0
for problem in ("plate_tension", "plate_asymmetric"):
    for line in ("y07", "top"):
        rows = [list(csv.reader(open(f"{d}/{problem}/line_{line}.csv")))[1:] for d in (committed, remade)]
        a = [[float(v) for v in r] for r in rows[0]]
        b = [[float(v) for v in r] for r in rows[1]]
        assert len(a) == len(b), (problem, line)
        for c in (2, 3):
            scale = max(abs(r[c]) for r in a)
            worst = max(worst, max(abs(p[c] - q[c]) for p, q in zip(a, b)) / scale)
print(f"remade reference differs from the committed one by {worst:.2e} of the largest value")
sys.exit(0 if worst <= 1e-6 else 1)
PY
