"""Implicit sections: the CalculiX load-displacement curves (scripts/compare.py) and the
convergence against exact solutions (scripts/convergence_study.py)."""
import compare as calculix  # scripts/compare.py
import convergence_study

from verification.page import Section, image, table

# The suite's checks: tests/cli/problems_run.sh (its compare.py call) and scripts.convergence_study.
CURVE_CHECK, FIRST_YIELD_CHECK = 0.02, 0.01
MIN_ENERGY_RATE, MIN_L2_RATE = 0.9, 1.8


def calculix_section(problem, ctx):
    methods = ["meshfree"] if ctx.quick else ["meshfree", "fem"]
    runs = {m: calculix.run(problem, m, str(ctx.out), ctx.meshfree) for m in methods}
    worst = calculix.compare(problem, runs, str(ctx.out))
    rows, passed = [], True
    for (method, label), d in worst.items():
        limit = calculix.tolerance(problem, label, CURVE_CHECK, FIRST_YIELD_CHECK)
        ok = limit is None or d <= limit
        passed &= ok
        rows.append((method, label, f"{d:.3e}", "-" if limit is None else f"<= {limit:g}",
                     "yes" if ok else "NO"))
    return Section(f"<p>Largest difference from the converged CalculiX curve, over its points, "
                   f"divided by the largest |CalculiX| value (reference/calculix_plastic/{problem}); "
                   f"the first-yield load as a fraction of CalculiX's.</p>"
                   + table(["discretisation", "quantity", "difference", "suite's bound", "within"],
                           rows) + image(ctx.out / f"{problem}.png"), passed)


def convergence_section(ctx):
    fig_rows, rows, passed = {}, [], True
    for problem, spacings in convergence_study.STUDIES.items():
        spacings = spacings[:3] if ctx.quick else spacings
        h, l2, en, rate_l2, rate_en, _ = convergence_study.run_study(ctx.meshfree, ctx.out, problem,
                                                                     spacings)
        fig_rows[problem] = (h, l2, en, rate_l2, rate_en)
        ok = rate_l2 >= MIN_L2_RATE and rate_en >= MIN_ENERGY_RATE
        passed &= ok
        rows.append((problem, len(h), f"{h[-1]:g}", f"{l2[-1]:.2e}", f"{en[-1]:.2e}",
                     f"{rate_l2:.2f}", f"{rate_en:.2f}", "yes" if ok else "NO"))
    convergence_study.plot(fig_rows, ctx.out / "convergence.png")
    return Section(f"<p>Relative L2 and energy-norm errors against the exact solutions; the suite "
                   f"asserts rates of at least {MIN_L2_RATE} (L2) and {MIN_ENERGY_RATE} (energy), "
                   f"the least-squares slopes over the spacings.</p>"
                   + table(["problem", "spacings", "finest h", "L2 error", "energy error",
                            "L2 rate", "energy rate", "rates within"], rows)
                   + image(ctx.out / "convergence.png"), passed)
