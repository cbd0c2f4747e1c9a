#!/usr/bin/python3
"""Tabulates the Kingery-Bulmash blast parameters of 1 kg of TNT at scaled distances 0.2-40
m/kg^(1/3) from reference/blast/kingery_bulmash_coefficients.csv, beside Swisdak's (1994)
independent fits of the hemispherical surface burst (swisdak1994_hemispherical_coefficients.csv)
and the ideal-gas Rankine-Hugoniot reflected pressure and shock speed from the incident
pressure (p0 = 101.325 kPa, c0 = 340.3 m/s, gamma = 1.4; UFC 3-340-02 eqs. 2-3, 2-4).
Writes reference/blast/kingery_bulmash_check_values.csv.

    scripts/blast_reference/kingery_bulmash_table.py [--out FILE]
"""
import argparse
import csv
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))
REF = os.path.join(HERE, "..", "..", "reference", "blast")
ZS = [0.2, 0.3, 0.5, 0.7, 1, 1.5, 2, 3, 4, 5, 7, 10, 15, 20, 30, 40]
QUANTITIES = [("incident_overpressure", "Pso_kPa"), ("normal_reflected_overpressure", "Pr_kPa"),
              ("incident_impulse", "Iso_kPa_ms_per_kg13"),
              ("normal_reflected_impulse", "Ir_kPa_ms_per_kg13"),
              ("arrival_time", "ta_ms_per_kg13"), ("positive_phase_duration", "td_ms_per_kg13"),
              ("shock_front_velocity", "U_km_s")]


def kb(rows, burst, quantity, z):
    segs = [r for r in rows if r["burst"] == burst and r["quantity"] == quantity]
    best, z_eval = None, z
    for s in segs:
        lo, hi = float(s["z_min"]), float(s["z_max"])
        if lo <= z <= hi:
            best, z_eval = s, z
            break
        end = lo if z < lo else hi
        if best is None or abs(end - z) < abs(z_eval - z):
            best, z_eval = s, end
    u = float(best["K0"]) + float(best["K1"]) * math.log10(z_eval)
    cs = [float(best[f"C{i}"]) for i in range(15) if best[f"C{i}"] != ""]
    return 10 ** sum(c * u ** i for i, c in enumerate(cs))


def swisdak(rows, quantity, z):
    for r in rows:
        if r["quantity"] == quantity and float(r["z_min"]) <= z <= float(r["z_max"]):
            x = math.log(z)
            cs = [float(r[k]) for k in "ABCDEFG"]
            return math.exp(sum(c * x ** i for i, c in enumerate(cs)))
    return None


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", default=os.path.join(REF, "kingery_bulmash_check_values.csv"))
    args = ap.parse_args()
    kb_rows = list(csv.DictReader(open(os.path.join(REF, "kingery_bulmash_coefficients.csv"))))
    sw_rows = list(csv.DictReader(open(os.path.join(REF,
                                                    "swisdak1994_hemispherical_coefficients.csv"))))
    p0, c0 = 101.325, 0.3403
    header = ["burst", "Z_m_per_kg13"] + [c for _, c in QUANTITIES]
    header += ["swisdak_" + s for s in ["Pso_kPa", "Pr_kPa", "Iso", "Ir", "ta", "td", "U"]]
    header += ["RH_Pr_from_Pso_kPa", "RH_U_from_Pso_km_s"]
    with open(args.out, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        for burst in ["spherical_free_air", "hemispherical_surface"]:
            for z in ZS:
                vals = [kb(kb_rows, burst, q, z) for q, _ in QUANTITIES]
                sw = [swisdak(sw_rows, q, z) if burst == "hemispherical_surface" else None
                      for q, _ in QUANTITIES]
                pso = vals[0]
                rh_pr = 2 * pso * (7 * p0 + 4 * pso) / (7 * p0 + pso)
                rh_u = c0 * math.sqrt(1 + 6 * pso / (7 * p0))
                fmt = lambda v: "" if v is None else f"{v:.5g}"
                w.writerow([burst, f"{z:g}"] + [fmt(v) for v in vals] + [fmt(v) for v in sw]
                           + [fmt(rh_pr), fmt(rh_u)])
    print("wrote", args.out)


if __name__ == "__main__":
    main()
