#!/usr/bin/python3
"""Haar (db1) approximations of a sampled load history, levels 1-5, as in paper 000.

Run from the repository root (about 2 s; needs numpy, matplotlib for the figure;
PyWavelets, if installed, is used for an independent check):

    /usr/bin/python3 scripts/pd_reference/haar_levels.py

reads problems/loads/random_load_1.csv and random_load_2.csv (`index,value`) and writes
into reference/loads/ (or --out DIR):
  random_load_<r>_haar_A<j>.csv   the level-j approximation for j = 3, 4, 5 (`index,value`,
                                  %.17g, so the doubles round-trip exactly)
  haar_summary.csv                every level 0-5: points, peak |value|, RMS, mean, sum,
                                  first and last value, dominant frequency
  haar_levels.png                 original and A3-A5 around the peak, and their spectra
Other files: haar_levels.py FILE.csv [FILE.csv ...] --out DIR.

Algorithm (the definition the C++ implementation must reproduce):

    a_0 = s                          (the N samples as read from the CSV, float64)
    for j = 1 .. J:
        if len(a_{j-1}) is odd: append a copy of its last value
        a_j[k] = (a_{j-1}[2k] + a_{j-1}[2k+1]) / 2,   k = 0 .. len/2 - 1

so N_j = ceil(N_{j-1} / 2).  Every a_j[k] except the last is the mean of the 2^j
original samples s[2^j k .. 2^j k + 2^j - 1]; the last value of a level can differ from
a plain block mean because the padding is applied level by level (see README).
This equals the approximation coefficients of a j-level Haar discrete wavelet transform
with half-sample symmetric extension (MATLAB wavedec 'sym' / PyWavelets mode 'symmetric')
divided by sqrt(2)^j, which keeps the amplitude of the original record.
Sample k of level j stands for the time interval [k, k+1) * 2^j * dt_0.
"""

import argparse
import math
import os
import sys

import numpy as np

PAPER_COUNTS = {
    19890: [19890, 9945, 4973, 2487, 1244, 622],
    18000: [18000, 9000, 4500, 2250, 1125, 563],
}
LEVELS = 5
FULL_LEVELS = (3, 4, 5)


def read_samples(path):
    vals = []
    with open(path) as fh:
        header = fh.readline()
        if not header.strip().startswith("index"):
            raise ValueError(f"{path}: expected a header 'index,value'")
        for line in fh:
            if line.strip():
                vals.append(float(line.split(",")[1]))
    return np.array(vals, dtype=np.float64)


def haar_step(a):
    if len(a) % 2:
        a = np.append(a, a[-1])
    return (a[0::2] + a[1::2]) / 2.0


def haar_levels(s, levels=LEVELS):
    out = [np.asarray(s, dtype=np.float64)]
    for _ in range(levels):
        out.append(haar_step(out[-1]))
    return out


def block_means(s, j):
    """Plain block means of 2^j samples with s padded once by repeating its last sample
    (for comparison only; differs from haar_levels only in the last value of a level)."""
    m = 2 ** j
    n = math.ceil(len(s) / m) * m
    p = np.concatenate([s, np.full(n - len(s), s[-1])])
    return p.reshape(-1, m).mean(axis=1)


def dominant(a):
    amp = np.abs(np.fft.rfft(a))
    sm = np.convolve(amp, np.ones(11) / 11, mode="same")
    return int(np.argmax(sm[1:]) + 1)


def write_csv(path, a):
    with open(path, "w") as fh:
        fh.write("index,value\n")
        for i, v in enumerate(a):
            fh.write(f"{i},{v:.17g}\n")


def plot(names, all_levels, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, 2, figsize=(10, 6.4), dpi=90)
    styles = {0: ("k", 0.8, "original"), 3: ("tab:green", 1.0, "A3"), 4: ("tab:orange", 1.0, "A4"),
              5: ("tab:red", 1.2, "A5")}
    for r, (name, lv) in enumerate(zip(names, all_levels)):
        s = lv[0]
        n = len(s)
        k0 = int(np.argmax(np.abs(s)))
        lo, hi = max(0, k0 - 300), min(n, k0 + 300)
        ax = axes[r, 0]
        for j, (c, lw, lab) in styles.items():
            a = lv[j]
            m = 2 ** j
            edges = np.arange(len(a) + 1) * m
            sel = (edges[:-1] + m > lo) & (edges[:-1] < hi)
            ks = np.nonzero(sel)[0]
            ax.stairs(a[ks], edges[ks[0]:ks[-1] + 2], color=c, lw=lw, label=lab)
        ax.set_xlim(lo, hi)
        ax.set_xlabel("original sample index")
        ax.set_ylabel("value")
        ax.set_title(f"{name}: around the peak (sample {k0})", fontsize=9)
        ax.legend(fontsize=7, ncol=4)
        ax.grid(alpha=0.3)
        ax = axes[r, 1]
        for j, (c, lw, lab) in styles.items():
            a = lv[j]
            amp = np.abs(np.fft.rfft(a)) * (2 ** j)  # same scale as the original's spectrum
            sm = np.convolve(amp, np.ones(11) / 11, mode="same")
            k = np.arange(len(amp))
            ax.loglog(k[1:], sm[1:], color=c, lw=lw, label=f"{lab} ({len(a)} points)")
        ax.set_xlim(1, 1e4)
        ax.set_ylim(1e-1, None)
        ax.set_xlabel("frequency (cycles per record)")
        ax.set_ylabel("Fourier amplitude x 2^j (11-line mean)")
        ax.set_title(f"{name}: spectra", fontsize=9)
        ax.legend(fontsize=7)
        ax.grid(alpha=0.3, which="both")
    fig.tight_layout()
    fig.savefig(path)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("files", nargs="*", default=[os.path.join("problems", "loads", "random_load_1.csv"),
                                                   os.path.join("problems", "loads", "random_load_2.csv")])
    ap.add_argument("--out", default=os.path.join("reference", "loads"))
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    try:
        import pywt
    except ImportError:
        pywt = None
        print("PyWavelets not installed: the wavedec cross-check is skipped")

    ok = True
    rows = []
    names, all_levels = [], []
    for path in args.files:
        name = os.path.splitext(os.path.basename(path))[0]
        s = read_samples(path)
        lv = haar_levels(s)
        counts = [len(a) for a in lv]
        expect = PAPER_COUNTS.get(len(s))
        print(f"{name}: points per level {' -> '.join(map(str, counts))}"
              + (f"; paper 000: {' -> '.join(map(str, expect))} {'(same)' if counts == expect else '(DIFFERENT)'}"
                 if expect else ""))
        if expect and counts != expect:
            ok = False
        for j in range(1, LEVELS + 1):
            bm = block_means(s, j)
            d = np.abs(bm - lv[j])
            first_diff = np.nonzero(d > 1e-15 * np.max(np.abs(s)))[0]
            note = "identical up to round-off" if len(first_diff) == 0 else \
                f"differ only at index {list(first_diff)} (last = {len(bm) - 1})"
            msg = f"   A{j}: plain block means of 2^{j} samples (single end padding) {note}"
            if pywt is not None:
                ca = pywt.wavedec(s, "haar", mode="symmetric", level=j)[0] / math.sqrt(2.0) ** j
                err = np.max(np.abs(ca - lv[j])) if len(ca) == len(lv[j]) else float("inf")
                msg += f"; PyWavelets wavedec('haar', 'symmetric')/sqrt(2)^{j}: max |diff| {err:.1e}"
                if not err < 1e-12:
                    ok = False
            print(msg)
        for j, a in enumerate(lv):
            rows.append((name, j, len(a), 2 ** j, float(np.max(np.abs(a))), float(np.sqrt(np.mean(a * a))),
                         float(np.mean(a)), float(np.sum(a)), float(a[0]), float(a[-1]), dominant(a)))
        for j in FULL_LEVELS:
            write_csv(os.path.join(args.out, f"{name}_haar_A{j}.csv"), lv[j])
        names.append(name)
        all_levels.append(lv)

    with open(os.path.join(args.out, "haar_summary.csv"), "w") as fh:
        fh.write("record,level,points,samples_per_point,peak_abs,rms,mean,sum,first,last,dominant_cycles_per_record\n")
        for r in rows:
            fh.write(f"{r[0]},{r[1]},{r[2]},{r[3]},{r[4]:.17g},{r[5]:.17g},{r[6]:.17g},{r[7]:.17g},"
                     f"{r[8]:.17g},{r[9]:.17g},{r[10]}\n")
    print()
    print("record          level points  dt/dt0  peak|a|    RMS        mean        first        last          f_dom")
    for r in rows:
        print(f"{r[0]:15s} A{r[1]}  {r[2]:6d}  {r[3]:5d}   {r[4]:.6f}  {r[5]:.6f}  {r[6]:+.3e}  "
              f"{r[8]:+.6e}  {r[9]:+.6e}  {r[10]:5d}")
    try:
        plot(names, all_levels, os.path.join(args.out, "haar_levels.png"))
        print(f"wrote {args.out}/haar_levels.png")
    except ImportError:
        print("matplotlib missing: no figure")
    print(f"wrote {args.out}/haar_summary.csv and the A{FULL_LEVELS[0]}-A{FULL_LEVELS[-1]} CSV files")
    print("all checks passed" if ok else "CHECK FAILED")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
