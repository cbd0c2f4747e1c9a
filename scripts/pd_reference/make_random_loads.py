#!/usr/bin/python3
"""Two band-limited random load histories that stand in for the earthquake records of paper 000.

Run from the repository root (about 3 s; needs numpy, matplotlib for the figure):

    /usr/bin/python3 scripts/pd_reference/make_random_loads.py

writes problems/loads/random_load_1.csv (19,890 samples, stand-in for the Sarpol-e Zahab
record) and problems/loads/random_load_2.csv (18,000 samples, stand-in for the Chi-Chi
record), one row `index,value` per sample (%.9e), and reference/loads/random_loads.png.
Option --out-loads DIR / --out-figure DIR write elsewhere.

Both histories are dimensionless, peak |value| = 1, and carry no time step: like the
records of paper 000 they are time-compressed to whatever duration a problem gives them,
so frequencies are stated in cycles per record (cycles over the whole history); a
frequency of F cycles per record is F / T Hz when the record lasts T seconds.

Recipe (per record):
  1. z = numpy.random.default_rng(seed).standard_normal(N)          (white Gaussian noise)
  2. Z = rfft(z); line k has frequency f_k = k cycles per record, k = 0 .. N//2
  3. X = Z * sqrt(S(f_k)), S(0) = 0; x = irfft(X, N)                  (band-limited noise)
     S(f) = HP(f) * LP(f) * sum_i w_i KT(f; f_i, z_i)
     KT(f; f_i, z_i) = (1 + 4 z_i^2 r^2) / ((1 - r^2)^2 + 4 z_i^2 r^2),  r = f / f_i
                       (Kanai-Tajimi filter, one per dominant frequency)
     HP(f) = r^4 / ((1 - r^2)^2 + 4 z_hp^2 r^2),  r = f / f_hp          (Clough-Penzien high pass)
     LP(f) = 1 / (1 + (f / f_lp)^8)                                      (4th-order Butterworth-like
                                                                          low pass in amplitude)
  4. x_n *= e(n / N)                                                   (envelope, see below)
  5. x /= max |x|                                                      (peak |value| = 1)
"""

import argparse
import math
import os
import sys

import numpy as np

RECORDS = [
    {
        "name": "random_load_1",
        "stands_in_for": "Sarpol-e Zahab record (paper 000, load type 1)",
        "n": 19890,
        "seed": 20171112,
        # dominant frequencies (cycles per record), damping ratios and weights of the KT peaks
        "peaks": [(80.0, 0.15, 1.0), (210.0, 0.12, 0.6), (480.0, 0.10, 0.3)],
        "highpass": (12.0, 0.7),
        "lowpass": 1500.0,
        # piecewise envelope (Jennings et al. 1968 / Amin & Ang 1968 type):
        # (tau/t1)^2 for tau < t1, 1 for t1 <= tau <= t2, exp(-c (tau - t2)) for tau > t2
        "envelope": ("piecewise", {"t1": 0.06, "t2": 0.22, "c": 5.0}),
    },
    {
        "name": "random_load_2",
        "stands_in_for": "Chi-Chi record (paper 000, load type 2)",
        "n": 18000,
        "seed": 19990921,
        "peaks": [(40.0, 0.20, 1.0), (125.0, 0.15, 0.6), (300.0, 0.12, 0.35)],
        "highpass": (6.0, 0.7),
        "lowpass": 1200.0,
        # Saragoni-Hart (1974) envelope a tau^b exp(-c tau), written with its peak (value 1)
        # at tau_p: (tau/tau_p)^b exp(b (1 - tau/tau_p))
        "envelope": ("saragoni_hart", {"tau_p": 0.30, "b": 2.5}),
    },
]


def spectrum(f, rec):
    f = np.asarray(f, dtype=float)
    s = np.zeros_like(f)
    for fi, zi, wi in rec["peaks"]:
        r2 = (f / fi) ** 2
        s += wi * (1.0 + 4.0 * zi * zi * r2) / ((1.0 - r2) ** 2 + 4.0 * zi * zi * r2)
    fh, zh = rec["highpass"]
    r2 = (f / fh) ** 2
    s *= r2 * r2 / ((1.0 - r2) ** 2 + 4.0 * zh * zh * r2)
    s /= 1.0 + (f / rec["lowpass"]) ** 8
    return s


def envelope(tau, rec):
    kind, p = rec["envelope"]
    tau = np.asarray(tau, dtype=float)
    if kind == "piecewise":
        return np.where(tau < p["t1"], (tau / p["t1"]) ** 2,
                        np.where(tau <= p["t2"], 1.0, np.exp(-p["c"] * (tau - p["t2"]))))
    if kind == "saragoni_hart":
        u = tau / p["tau_p"]
        return u ** p["b"] * np.exp(p["b"] * (1.0 - u))
    raise ValueError(kind)


def make_record(rec):
    n = rec["n"]
    rng = np.random.default_rng(rec["seed"])
    z = rng.standard_normal(n)
    f = np.arange(n // 2 + 1, dtype=float)
    x = np.fft.irfft(np.fft.rfft(z) * np.sqrt(spectrum(f, rec)), n)
    x *= envelope(np.arange(n) / n, rec)
    return x / np.max(np.abs(x)) + 0.0  # + 0.0 turns a -0.0 into 0.0


def husid_duration(x, lo=0.05, hi=0.95):
    """Significant duration (fraction of the record) between lo and hi of sum x^2."""
    c = np.cumsum(x * x)
    c /= c[-1]
    return (np.searchsorted(c, hi) - np.searchsorted(c, lo)) / len(x), np.searchsorted(c, lo) / len(x)


def describe(x):
    n = len(x)
    amp = np.abs(np.fft.rfft(x))
    k = np.arange(len(amp))
    # smoothed amplitude spectrum (running mean over 11 lines) for the dominant frequency
    sm = np.convolve(amp, np.ones(11) / 11, mode="same")
    kdom = int(k[1:][np.argmax(sm[1:])])
    centroid = float(np.sum(k * amp**2) / np.sum(amp**2))
    d, start = husid_duration(x)
    return {
        "n": n, "peak": float(np.max(np.abs(x))), "rms": float(np.sqrt(np.mean(x * x))),
        "mean": float(np.mean(x)), "kdom": kdom, "centroid": centroid,
        "husid": d, "husid_start": start, "argmax": int(np.argmax(np.abs(x))),
    }


def write_csv(path, x):
    with open(path, "w") as fh:
        fh.write("index,value\n")
        for i, v in enumerate(x):
            fh.write(f"{i},{v:.9e}\n")


def plot(records, xs, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(3, 1, figsize=(8.0, 8.2), dpi=80)
    colors = ("tab:blue", "tab:red")
    for ax, rec, x, c in zip(axes[:2], records, xs, colors):
        tau = np.arange(len(x)) / len(x)
        ax.plot(tau, x, color=c, lw=0.3)
        ax.set_xlim(0, 1)
        ax.set_ylim(-1.05, 1.05)
        ax.set_ylabel("value")
        ax.set_title(f"{rec['name']}: N = {rec['n']}, seed {rec['seed']} "
                     f"(stand-in for the {rec['stands_in_for'].split(' (')[0]})", fontsize=9)
        ax.grid(alpha=0.3)
    axes[1].set_xlabel("fraction of the record, k / N")
    ax = axes[2]
    for rec, x, c in zip(records, xs, colors):
        amp = np.abs(np.fft.rfft(x))
        k = np.arange(len(amp))
        sm = np.convolve(amp, np.ones(11) / 11, mode="same")
        ax.loglog(k[1:], amp[1:], color=c, lw=0.2, alpha=0.35)
        ax.loglog(k[1:], sm[1:], color=c, lw=1.2, label=f"{rec['name']} (11-line running mean)")
        target = np.sqrt(spectrum(k[1:].astype(float), rec))
        ax.loglog(k[1:], target / np.max(target) * np.max(sm[1:]), color=c, lw=0.8, ls="--",
                  label=f"{rec['name']}: sqrt(S(f)), scaled")
    for j, ls in ((3, ":"), (4, "-."), (5, "--")):
        ax.axvline(19890 / 2 ** (j + 1), color="0.5", lw=0.7, ls=ls)
        ax.text(19890 / 2 ** (j + 1) * 1.03, 2e-2, f"Nyquist A{j}\n(load 1)", fontsize=6, color="0.4")
    ax.set_xlim(1, 1e4)
    ax.set_ylim(1e-2, None)
    ax.set_xlabel("frequency (cycles per record)")
    ax.set_ylabel("Fourier amplitude |X_k|")
    ax.legend(fontsize=7, loc="lower left")
    ax.grid(alpha=0.3, which="both")
    fig.tight_layout()
    fig.savefig(path)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out-loads", default=os.path.join("problems", "loads"))
    ap.add_argument("--out-figure", default=os.path.join("reference", "loads"))
    args = ap.parse_args()
    os.makedirs(args.out_loads, exist_ok=True)
    os.makedirs(args.out_figure, exist_ok=True)
    xs = []
    for rec in RECORDS:
        x = make_record(rec)
        path = os.path.join(args.out_loads, rec["name"] + ".csv")
        write_csv(path, x)
        # what is on disk (rounded to 10 digits) is the record
        xr = np.loadtxt(path, delimiter=",", skiprows=1)[:, 1]
        xs.append(xr)
        d = describe(xr)
        print(f"{rec['name']} ({rec['stands_in_for']}): N = {d['n']}, seed = {rec['seed']}")
        print(f"   peaks (f cycles/record, damping, weight): {rec['peaks']}; high pass {rec['highpass']}; "
              f"low pass {rec['lowpass']}")
        print(f"   envelope {rec['envelope'][0]} {rec['envelope'][1]}")
        print(f"   peak |value| = {d['peak']:.9f} at index {d['argmax']} (k/N = {d['argmax'] / d['n']:.4f}), "
              f"RMS = {d['rms']:.6f}, mean = {d['mean']:+.3e}")
        print(f"   dominant frequency (smoothed Fourier amplitude) = {d['kdom']} cycles/record, "
              f"spectral centroid = {d['centroid']:.1f} cycles/record")
        print(f"   5-95% Husid duration = {d['husid']:.3f} of the record, starting at {d['husid_start']:.3f}")
        print(f"   wrote {path}")
    try:
        plot(RECORDS, xs, os.path.join(args.out_figure, "random_loads.png"))
        print(f"wrote {os.path.join(args.out_figure, 'random_loads.png')}")
    except ImportError:
        print("matplotlib missing: no figure")
    return 0


if __name__ == "__main__":
    sys.exit(main())
