#!/usr/bin/python3
"""Beam-theory dynamic response of the paper-000 verification cantilever.

Run from the repository root (about 1 min; needs numpy and scipy):

    /usr/bin/python3 scripts/pd_reference/cantilever_beam_theory.py

writes reference/beam_theory/cantilever_tip.csv and cantilever_stations.csv and prints
every number quoted in reference/beam_theory/README.md.  Options: --out DIR (write the
CSV files into DIR instead), --omega W (forcing frequency in rad/s, default 27),
--quick (skip the slow checks: finite-element cross-check and step-by-step Duhamel).

Problem (Majidi, Tajmir Riahi & Zandi 2022, verification example after Mossaiby et al.
2017): cantilever L = 48 m, rectangular section b = 6 m (width) x h = 12 m (height),
E = 30 MPa, nu = 0.25, rho = 1 kg/m^3, clamped at x = 0.  The free end x = L carries a
uniform shear traction q(t) = tau0 sin(Omega t), tau0 = -13.89 N/m^2, Omega = 27 rad/s,
for 0 <= t <= 0.5 s and nothing afterwards, so the end shear force is
P(t) = tau0 b h sin(Omega t) = -1000.08 sin(27 t) N.  Undamped, starting at rest.

Two beam theories, both by modal superposition with closed-form Duhamel integrals:

* Euler-Bernoulli: rho A w_tt + E I w_xxxx = 0, w = w_x = 0 at x = 0, M = V = 0 at
  x = L except for the end force.  Modes from cos(bL) cosh(bL) = -1.
* Timoshenko (rotary inertia and shear deformation):
      rho A w_tt = k G A (w_xx - psi_x),
      rho I psi_tt = E I psi_xx + k G A (w_x - psi),
  with Cowper's shear coefficient for a rectangle k = 10(1+nu)/(12+11nu).
  w = psi = 0 at x = 0; E I psi_x = 0 and k G A (w_x - psi) = P(t) at x = L.
  Modes from the 4x4 boundary determinant of the exact solution, below the cut-off
  frequency omega_c = sqrt(k G A / (rho I)) with cosh/sinh/cos/sin and above it with
  cos/sin only (the two spectra of Han, Benaroya & Wei 1999, J. Sound Vib. 225(5),
  935-988); the roots are checked against Han et al.'s closed-form clamped-free
  frequency equation and against a finite-element model.

Modal superposition: w(x,t) = sum_n W_n(x) q_n(t), q_n'' + w_n^2 q_n = P(t) W_n(L) / M_n,
M_n = int_0^L (rho A W_n^2 + rho I Psi_n^2) dx (Euler-Bernoulli: Psi-term absent).
For 0 <= t <= T: q = F0/(w^2 - W^2) (sin W t - (W/w) sin w t); afterwards free vibration
from q(T), q'(T).  The result is reported by plain modal superposition with N modes and,
as a check, by the mode-acceleration form w = P(t) w_static(x) + sum W_n (q_n - P c_n/w_n^2),
which converges faster and must agree.
"""

import argparse
import math
import os
import sys
import time

import numpy as np
from scipy.linalg import eigh
from scipy.optimize import brentq

# ----------------------------------------------------------------------------------------
# Data
L, B, H = 48.0, 6.0, 12.0
E, NU, RHO = 30.0e6, 0.25, 1.0
TAU0 = -13.89
T_LOAD = 0.5
T_END = 1.0
DT_OUT = 1.0e-3
A = B * H
I = B * H**3 / 12.0
G = E / (2.0 * (1.0 + NU))
KAPPA = 10.0 * (1.0 + NU) / (12.0 + 11.0 * NU)  # Cowper (1966), rectangle
P0 = TAU0 * B * H  # end force amplitude, N
# x = 47.5 m is the last column of particles of the peridynamic model with dx = 1 m (cell
# centres at 0.5, 1.5, ..., 47.5), where its tip deflection is read.
STATIONS = (12.0, 24.0, 36.0, 47.5, 48.0)

EI, KGA, RA, RI = E * I, KAPPA * G * A, RHO * A, RHO * I
OMEGA_C = math.sqrt(KGA / RI)  # second cut-off frequency of the Timoshenko beam


def static_tip_eb(p):
    return p * L**3 / (3.0 * EI)


def static_eb(x, p):
    return p / EI * (L * x**2 / 2.0 - x**3 / 6.0)


def static_timo(x, p):
    return static_eb(x, p) + p * x / KGA


# ----------------------------------------------------------------------------------------
# Euler-Bernoulli modes, normalised so that int_0^L phi^2 dx = L
def eb_roots(n):
    out = []
    for k in range(1, n + 1):
        c = (k - 0.5) * math.pi
        out.append(brentq(lambda z: math.cos(z) + 1.0 / math.cosh(z), c - math.pi / 4, c + math.pi / 4,
                          xtol=1e-15, rtol=1e-15))
    return np.array(out)


def eb_shape(bl, x):
    """phi(x) = cosh bx - cos bx - s (sinh bx - sin bx), evaluated without overflow."""
    b = bl / L
    e = math.exp(-bl)
    den = 1.0 - e * e + 2.0 * math.sin(bl) * e  # (2 sinh bL + 2 sin bL) e^{-bL}
    one_minus_s_half = (math.sin(bl) - math.cos(bl) - e) / den  # (1-s) e^{bL} / 2
    s = 1.0 - 2.0 * one_minus_s_half * e
    bx = b * x
    # cosh bx - s sinh bx = (1-s)/2 e^{bx} + (1+s)/2 e^{-bx}
    return (one_minus_s_half * np.exp(bx - bl) + 0.5 * (1.0 + s) * np.exp(-bx)
            - np.cos(bx) + s * np.sin(bx))


def eb_modes(n):
    bl = eb_roots(n)
    omega = bl**2 * math.sqrt(EI / (RA * L**4))
    return bl, omega


# ----------------------------------------------------------------------------------------
# Timoshenko modes
def _timo_wavenumbers(w):
    """Roots of k EI lam^4 + (rhoA EI + k rhoI) w^2 lam^2 + rhoA rhoI w^4 - rhoA k w^2 = 0
    in lam^2; returns (a2, b2) with lam^2 = a2 (> 0 below cut-off, < 0 above) and -b2."""
    a = KGA * EI
    bq = (RA * EI + KGA * RI) * w * w
    c = RA * RI * w**4 - RA * KGA * w * w
    disc = math.sqrt(bq * bq - 4.0 * a * c)
    r1 = (-bq + disc) / (2.0 * a)  # the larger root
    r2 = (-bq - disc) / (2.0 * a)  # always negative
    return r1, -r2


def timo_matrix(w):
    """Boundary matrix (rows: W(0), Psi(0), Psi'(L), W'(L)-Psi(L)) for the basis
    W = C1 f1 + C2 f2 + C3 cos bx + C4 sin bx, f = cosh/sinh (below cut-off) or cos/sin."""
    a2, b2 = _timo_wavenumbers(w)
    beta = math.sqrt(b2)
    gb = (RA * w * w - KGA * b2) / (KGA * beta)
    cb, sb = math.cos(beta * L), math.sin(beta * L)
    if a2 > 0.0:
        al = math.sqrt(a2)
        ga = (RA * w * w + KGA * a2) / (KGA * al)
        ca, sa = math.cosh(al * L), math.sinh(al * L)
        # Psi = C1 ga sinh + C2 ga cosh + C3 gb sin - C4 gb cos
        m = np.array([
            [1.0, 0.0, 1.0, 0.0],
            [0.0, ga, 0.0, -gb],
            [ga * al * ca, ga * al * sa, gb * beta * cb, gb * beta * sb],
            [al * sa - ga * sa, al * ca - ga * ca, -beta * sb - gb * sb, beta * cb + gb * cb],
        ])
    else:
        al = math.sqrt(-a2)
        ga = (RA * w * w - KGA * (-a2)) / (KGA * al)
        ca, sa = math.cos(al * L), math.sin(al * L)
        # W = C1 cos ax + C2 sin ax ..., Psi = C1 ga sin ax - C2 ga cos ax ...
        m = np.array([
            [1.0, 0.0, 1.0, 0.0],
            [0.0, -ga, 0.0, -gb],
            [ga * al * ca, ga * al * sa, gb * beta * cb, gb * beta * sb],
            [-al * sa - ga * sa, al * ca + ga * ca, -beta * sb - gb * sb, beta * cb + gb * cb],
        ])
    return m


def _normalised(m):
    return m / np.linalg.norm(m, axis=0)


def timo_det(w):
    return np.linalg.det(_normalised(timo_matrix(w)))


def han_frequency_equation(w):
    """Han, Benaroya & Wei (1999), clamped-free Timoshenko beam, in their non-dimensional
    form: b^2 = rho A L^4 w^2 / EI, r^2 = I/(A L^2), s^2 = EI/(k G A L^2),
    alpha, beta = sqrt(-+(r^2+s^2) + sqrt((r^2-s^2)^2 + 4/b^2)) / sqrt(2).
    Below the cut-off (b^2 r^2 s^2 < 1):
        2 + [b^2 (r^2-s^2)^2 + 2] cosh(b alpha) cos(b beta)
          - b (r^2+s^2)/sqrt(1 - b^2 r^2 s^2) sinh(b alpha) sin(b beta) = 0;
    above it alpha = i alpha', alpha' = sqrt((r^2+s^2) - sqrt((r^2-s^2)^2 + 4/b^2)) / sqrt(2):
        2 + [b^2 (r^2-s^2)^2 + 2] cos(b alpha') cos(b beta)
          - b (r^2+s^2)/sqrt(b^2 r^2 s^2 - 1) sin(b alpha') sin(b beta) = 0.
    Vectorised over w (all on one side of the cut-off or not; each value is treated on its
    own side).  Below the cut-off the function is divided by cosh(b alpha)."""
    w = np.atleast_1d(np.asarray(w, dtype=float))
    bb = np.sqrt(RA * L**4 * w * w / EI)
    r2 = I / (A * L * L)
    s2 = EI / (KGA * L * L)
    root = np.sqrt((r2 - s2) ** 2 + 4.0 / bb**2)
    beta = np.sqrt((r2 + s2 + root) / 2.0)
    c0 = bb * bb * (r2 - s2) ** 2 + 2.0
    x = bb * bb * r2 * s2
    out = np.empty_like(w)
    lo = x < 1.0
    if np.any(lo):
        al = np.sqrt((-(r2 + s2) + root[lo]) / 2.0)
        b = bb[lo]
        out[lo] = (2.0 / np.cosh(b * al) + c0[lo] * np.cos(b * beta[lo])
                   - b * (r2 + s2) / np.sqrt(1.0 - x[lo]) * np.tanh(b * al) * np.sin(b * beta[lo]))
    hi = ~lo
    if np.any(hi):
        al = np.sqrt(((r2 + s2) - root[hi]) / 2.0)
        b = bb[hi]
        out[hi] = (2.0 + c0[hi] * np.cos(b * al) * np.cos(b * beta[hi])
                   - b * (r2 + s2) / np.sqrt(x[hi] - 1.0) * np.sin(b * al) * np.sin(b * beta[hi]))
    return out


def han_sign_changes(w_max, dw=0.01):
    """Number of sign changes of Han et al.'s frequency function on (0, w_max), scanned
    separately below and above the cut-off (independent count of the natural frequencies)."""
    eps = 1e-9 * OMEGA_C
    count = 0
    for lo, hi in ((1e-3, min(w_max, OMEGA_C - eps)), (OMEGA_C + eps, w_max)):
        if hi <= lo:
            continue
        for a in np.arange(lo, hi, 2e5 * dw):
            grid = np.append(np.arange(a, min(a + 2e5 * dw, hi), dw), min(a + 2e5 * dw, hi))
            f = han_frequency_equation(grid)
            count += int(np.sum(np.sign(f[:-1]) * np.sign(f[1:]) < 0))
    return count


def _timo_matrices(w):
    """Column-normalised boundary matrices for an array of frequencies, all on one side
    of the cut-off (vectorised version of timo_matrix)."""
    w = np.asarray(w, dtype=float)
    a = KGA * EI
    bq = (RA * EI + KGA * RI) * w * w
    c = RA * RI * w**4 - RA * KGA * w * w
    disc = np.sqrt(bq * bq - 4.0 * a * c)
    r1 = (-bq + disc) / (2.0 * a)
    b2 = (bq + disc) / (2.0 * a)
    beta = np.sqrt(b2)
    gb = (RA * w * w - KGA * b2) / (KGA * beta)
    cb, sb = np.cos(beta * L), np.sin(beta * L)
    m = np.zeros(w.shape + (4, 4))
    m[..., 0, 0] = 1.0
    m[..., 0, 2] = 1.0
    m[..., 1, 3] = -gb
    m[..., 2, 2] = gb * beta * cb
    m[..., 2, 3] = gb * beta * sb
    m[..., 3, 2] = -beta * sb - gb * sb
    m[..., 3, 3] = beta * cb + gb * cb
    if np.all(r1 > 0.0):
        al = np.sqrt(r1)
        ga = (RA * w * w + KGA * r1) / (KGA * al)
        ca, sa = np.cosh(al * L), np.sinh(al * L)
        m[..., 1, 1] = ga
        m[..., 2, 0] = ga * al * ca
        m[..., 2, 1] = ga * al * sa
        m[..., 3, 0] = al * sa - ga * sa
        m[..., 3, 1] = al * ca - ga * ca
    elif np.all(r1 < 0.0):
        al = np.sqrt(-r1)
        ga = (RA * w * w + KGA * r1) / (KGA * al)
        ca, sa = np.cos(al * L), np.sin(al * L)
        m[..., 1, 1] = -ga
        m[..., 2, 0] = ga * al * ca
        m[..., 2, 1] = ga * al * sa
        m[..., 3, 0] = -al * sa - ga * sa
        m[..., 3, 1] = al * ca + ga * ca
    else:
        raise ValueError("frequencies on both sides of the cut-off")
    return m / np.linalg.norm(m, axis=-2)[..., None, :]


def timo_roots(nmodes, dw=0.01, chunk=200000):
    """First nmodes natural frequencies: scan the sign of the (column-normalised) boundary
    determinant in steps of dw rad/s separately below and above the cut-off frequency,
    refine each sign change with brentq and keep it only if the matrix is singular there."""
    eps = 1e-9 * OMEGA_C
    roots = []
    lo = 1e-3
    while len(roots) < nmodes:
        if lo < OMEGA_C:
            hi = min(lo + chunk * dw, OMEGA_C - eps)
        else:
            hi = lo + chunk * dw
        grid = np.append(np.arange(lo, hi, dw), hi)
        d = np.linalg.det(_timo_matrices(grid))
        idx = np.nonzero(np.sign(d[:-1]) * np.sign(d[1:]) < 0)[0]
        for i in idx:
            r = brentq(timo_det, grid[i], grid[i + 1], xtol=1e-13, rtol=1e-15)
            sv = np.linalg.svd(_normalised(timo_matrix(r)), compute_uv=False)
            if sv[-1] / sv[0] < 1e-7:
                roots.append(r)
        lo = OMEGA_C + eps if hi == OMEGA_C - eps else hi
    return np.array(sorted(roots)[:nmodes])


def timo_shape(w, x):
    """(W(x), Psi(x)) of the mode at frequency w (null vector of the boundary matrix)."""
    m = timo_matrix(w)
    scale = np.linalg.norm(m, axis=0)
    _, _, vt = np.linalg.svd(m / scale)
    c = vt[-1] / scale
    a2, b2 = _timo_wavenumbers(w)
    beta = math.sqrt(b2)
    gb = (RA * w * w - KGA * b2) / (KGA * beta)
    if a2 > 0.0:
        al = math.sqrt(a2)
        ga = (RA * w * w + KGA * a2) / (KGA * al)
        W = c[0] * np.cosh(al * x) + c[1] * np.sinh(al * x) + c[2] * np.cos(beta * x) + c[3] * np.sin(beta * x)
        P = ga * (c[0] * np.sinh(al * x) + c[1] * np.cosh(al * x)) + gb * (c[2] * np.sin(beta * x) - c[3] * np.cos(beta * x))
    else:
        al = math.sqrt(-a2)
        ga = (RA * w * w + KGA * a2) / (KGA * al)
        W = c[0] * np.cos(al * x) + c[1] * np.sin(al * x) + c[2] * np.cos(beta * x) + c[3] * np.sin(beta * x)
        P = ga * (c[0] * np.sin(al * x) - c[1] * np.cos(al * x)) + gb * (c[2] * np.sin(beta * x) - c[3] * np.cos(beta * x))
    return W, P


# Gauss-Legendre rule on [0, L] in panels (exact enough for every mode used)
def _gauss(npanel=400, order=12):
    g, wg = np.polynomial.legendre.leggauss(order)
    edges = np.linspace(0.0, L, npanel + 1)
    xs = ((edges[:-1, None] + edges[1:, None]) / 2 + (edges[1:, None] - edges[:-1, None]) / 2 * g).ravel()
    ws = ((edges[1:, None] - edges[:-1, None]) / 2 * wg).ravel()
    return xs, ws


XQ, WQ = _gauss()


# ----------------------------------------------------------------------------------------
# Modal data: for each mode (omega_n, c_n = W_n(L)/M_n, W_n at the stations)
def eb_modal_data(n):
    bl, omega = eb_modes(n)
    xs = np.array(STATIONS)
    shapes = np.array([eb_shape(b, xs) for b in bl])
    tip = shapes[:, -1]
    mass = np.array([RA * np.dot(WQ, eb_shape(b, XQ) ** 2) for b in bl])
    return omega, tip / mass, shapes


def timo_modal_data(n, dw=0.01):
    omega = timo_roots(n, dw)
    xs = np.array(STATIONS)
    shapes, coef, mass_err = [], [], 0.0
    for w in omega:
        Wq, Pq = timo_shape(w, XQ)
        mass = np.dot(WQ, RA * Wq**2 + RI * Pq**2)
        Ws, _ = timo_shape(w, xs)
        shapes.append(Ws)
        coef.append(Ws[-1] / mass)
    return omega, np.array(coef), np.array(shapes)


# ----------------------------------------------------------------------------------------
# Closed-form modal response to F(t) = sin(Om t) on [0, T], 0 afterwards (unit amplitude)
def modal_response(omega, om, t):
    """q_n(t) for q'' + w^2 q = sin(om t) H(T - t); returns array (nmodes, nt)."""
    w = omega[:, None]
    tt = t[None, :]
    denom = w * w - om * om
    q_on = (np.sin(om * tt) - om / w * np.sin(w * tt)) / denom
    qT = (math.sin(om * T_LOAD) - om / w * np.sin(w * T_LOAD)) / denom
    vT = om * (math.cos(om * T_LOAD) - np.cos(w * T_LOAD)) / denom
    tau = tt - T_LOAD
    q_off = qT * np.cos(w * tau) + vT / w * np.sin(w * tau)
    return np.where(tt <= T_LOAD, q_on, q_off)


def load_shape(om, t):
    return np.where(t <= T_LOAD, np.sin(om * t), 0.0)


def response(omega, coef, shapes, om, t, mode_acceleration=False, static=None):
    """w at the stations (nstations, nt) for end force P(t) = P0 sin(om t) H(T-t)."""
    q = modal_response(omega, om, t)  # per unit force amplitude
    if not mode_acceleration:
        return P0 * (shapes.T * coef) @ q
    qs = q - load_shape(om, t)[None, :] / (omega[:, None] ** 2)
    xs = np.array(STATIONS)
    return P0 * ((shapes.T * coef) @ qs + static(xs, 1.0)[:, None] * load_shape(om, t)[None, :])


def duhamel_stepwise(omega, om, dt, stride):
    """Independent check: exact integration of q'' + w^2 q = f with f linear between samples
    (Nigam-Jennings recurrence) on a uniform grid of step dt; the load switch-off at T is
    resolved by taking the T-value from the left and restarting from there with f = 0."""
    t_all, q_all = [], []
    n1 = int(round(T_LOAD / dt))
    n2 = int(round((T_END - T_LOAD) / dt))
    w = omega[:, None]
    q = np.zeros((len(omega), 1))
    v = np.zeros((len(omega), 1))
    c, s = np.cos(w * dt), np.sin(w * dt)
    qs = [q.copy()]
    step = 0
    for k in range(n1):
        f0, f1 = math.sin(om * k * dt), math.sin(om * (k + 1) * dt)
        slope = (f1 - f0) / dt
        # particular solution of q'' + w^2 q = f0 + slope*tau: qp = (f0 + slope tau)/w^2
        qp0, vp0 = f0 / w**2, slope / w**2
        qh0, vh0 = q - qp0, v - vp0
        q = qh0 * c + vh0 / w * s + (f0 + slope * dt) / w**2
        v = -qh0 * w * s + vh0 * c + slope / w**2
        step += 1
        if step % stride == 0:
            qs.append(q.copy())
    for k in range(n2):
        q, v = q * c + v / w * s, -q * w * s + v * c
        step += 1
        if step % stride == 0:
            qs.append(q.copy())
    return np.hstack(qs)


# ----------------------------------------------------------------------------------------
# Finite-element cross-check of the Timoshenko beam (quadratic elements, 3-point Gauss)
def timo_fe(nel):
    nn = 2 * nel + 1
    ndof = 2 * nn
    K = np.zeros((ndof, ndof))
    M = np.zeros((ndof, ndof))
    he = L / nel
    g, wg = np.polynomial.legendre.leggauss(3)
    for e in range(nel):
        nodes = [2 * e, 2 * e + 1, 2 * e + 2]
        dofs_w = [2 * n for n in nodes]
        dofs_p = [2 * n + 1 for n in nodes]
        for xi, wi in zip(g, wg):
            N = np.array([xi * (xi - 1) / 2, 1 - xi * xi, xi * (xi + 1) / 2])
            dN = np.array([xi - 0.5, -2 * xi, xi + 0.5]) * 2.0 / he
            jw = wi * he / 2.0
            # bending: EI psi' psi'
            K[np.ix_(dofs_p, dofs_p)] += EI * np.outer(dN, dN) * jw
            # shear: kGA (w' - psi)^2
            bs = np.zeros(ndof)
            bs[dofs_w] = dN
            bs[dofs_p] = -N
            idx = dofs_w + dofs_p
            K[np.ix_(idx, idx)] += KGA * np.outer(bs[idx], bs[idx]) * jw
            M[np.ix_(dofs_w, dofs_w)] += RA * np.outer(N, N) * jw
            M[np.ix_(dofs_p, dofs_p)] += RI * np.outer(N, N) * jw
    free = np.arange(2, ndof)  # clamp node 0 (w and psi)
    K, M = K[np.ix_(free, free)], M[np.ix_(free, free)]
    lam, vec = eigh(K, M)
    tip = ndof - 2 - 2  # w at the last node, after removing 2 dofs
    return np.sqrt(lam), vec, tip, K, (he, free)


# ----------------------------------------------------------------------------------------
def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default=os.path.join("reference", "beam_theory"))
    ap.add_argument("--omega", type=float, default=27.0)
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    om = args.omega
    t0 = time.time()
    t = np.round(np.arange(0, int(round(T_END / DT_OUT)) + 1) * DT_OUT, 12)

    print(f"L={L} b={B} h={H} E={E:g} nu={NU} rho={RHO}  A={A} I={I} G={G:g}")
    print(f"Cowper kappa = 10(1+nu)/(12+11nu) = {KAPPA:.6f}; kGA = {KGA:.6e} N; EI = {EI:.6e} N m^2")
    print(f"end force amplitude P0 = tau0*b*h = {P0:.4f} N, Omega = {om} rad/s, load on for t <= {T_LOAD} s")
    print(f"Timoshenko cut-off frequency omega_c = sqrt(kGA/(rho I)) = {OMEGA_C:.4f} rad/s")
    print()
    print("static tip deflection under an end force of 1 kN (magnitude):")
    print(f"  Euler-Bernoulli  P L^3/(3EI)               = {static_tip_eb(1000.0):.6e} m")
    print(f"  Timoshenko       P L^3/(3EI) + P L/(kGA)   = {static_timo(L, 1000.0):.6e} m")
    print(f"  (under |P0| = {abs(P0):.2f} N: {static_tip_eb(abs(P0)):.6e} m and {static_timo(L, abs(P0)):.6e} m)")
    print()

    # ------------------------------------------------------------------ modes
    n_eb, n_ti = 40, 160
    eb = eb_modal_data(2 * n_eb)
    ti = timo_modal_data(2 * n_ti)
    print("first natural frequencies (rad/s and Hz):")
    print("  n   EB omega     EB f       Timo omega   Timo f     Timo/EB")
    for k in range(8):
        print(f"  {k + 1}  {eb[0][k]:10.4f}  {eb[0][k] / 2 / math.pi:8.4f}   {ti[0][k]:10.4f}  "
              f"{ti[0][k] / 2 / math.pi:8.4f}   {ti[0][k] / eb[0][k]:.4f}")
    # Han et al. equation at the roots
    wr = ti[0]
    han_ok = bool(np.all(han_frequency_equation(wr * (1 - 1e-9)) * han_frequency_equation(wr * (1 + 1e-9)) <= 0))
    print(f"Han-Benaroya-Wei clamped-free frequency equation changes sign across each of the {len(wr)} "
          f"Timoshenko roots (+-1e-9 relative): {han_ok}")
    w_mid = 0.5 * (wr[-1] + wr[-2])
    print(f"sign changes of Han et al.'s function on (0, {w_mid:.1f}) rad/s in steps of 0.01 rad/s: "
          f"{han_sign_changes(w_mid)} (boundary-determinant roots there: {len(wr) - 1})")
    # modal sums of the static flexibility
    for name, data, stat in (("Euler-Bernoulli", eb, static_eb), ("Timoshenko", ti, static_timo)):
        om_, c_, sh_ = data
        s = np.cumsum(c_ * sh_[:, -1] / om_**2)
        print(f"  {name}: sum_n W_n(L) c_n / w_n^2 with N = {len(om_) // 2}, {len(om_)} modes: "
              f"{s[len(om_) // 2 - 1]:.9e}, {s[-1]:.9e}; exact static tip flexibility {stat(L, 1.0):.9e} m/N")
    print()

    # ------------------------------------------------------------------ responses
    res = {}
    for name, data, n, stat in (("Euler-Bernoulli", eb, n_eb, static_eb), ("Timoshenko", ti, n_ti, static_timo)):
        om_, c_, sh_ = data
        wN = response(om_[:n], c_[:n], sh_[:n], om, t)
        w2N = response(om_, c_, sh_, om, t)
        maN = response(om_[:n], c_[:n], sh_[:n], om, t, True, stat)
        ma2N = response(om_, c_, sh_, om, t, True, stat)
        peak = np.max(np.abs(w2N[-1]))
        print(f"{name}: N = {n} vs 2N = {2 * n} modes, max |difference| of the tip response / max |w_tip|:")
        print(f"   plain modal superposition  {np.max(np.abs(wN[-1] - w2N[-1])) / peak:.2e}")
        print(f"   mode-acceleration form     {np.max(np.abs(maN[-1] - ma2N[-1])) / peak:.2e}")
        print(f"   plain (2N) vs mode-acceleration (2N): {np.max(np.abs(w2N - ma2N)) / peak:.2e} "
              f"(all stations)")
        k = int(np.argmax(np.abs(w2N[-1])))
        print(f"   max |w_tip| = {peak:.6e} m at t = {t[k]:.3f} s (w_tip = {w2N[-1][k]:+.6e} m); "
              f"w_tip(0.5 s) = {w2N[-1][500]:+.6e} m; max |w_tip| for t > 0.5 s = "
              f"{np.max(np.abs(w2N[-1][t > T_LOAD])):.6e} m")
        for j, xs in enumerate(STATIONS):
            kk = int(np.argmax(np.abs(w2N[j])))
            print(f"   station x = {xs:4.0f} m: max |w| = {abs(w2N[j][kk]):.6e} m at t = {t[kk]:.3f} s")
        print("   convergence of the tip response, max |w_N - w_2N| / max |w_tip| (plain modal sum):")
        for nn in ((5, 10, 20, 40) if name == "Euler-Bernoulli" else (10, 20, 40, 80, 160)):
            a = response(om_[:nn], c_[:nn], sh_[:nn], om, t)[-1]
            b = response(om_[:2 * nn], c_[:2 * nn], sh_[:2 * nn], om, t)[-1]
            print(f"      N = {nn:4d}: {np.max(np.abs(a - b)) / peak:.2e}")
        for f in (0.99, 1.01):
            wf = response(om_ * f, c_, sh_, om, t)[-1]
            print(f"   sensitivity: all frequencies x {f} (E and G x {f * f:.4f}): max |w_tip| = "
                  f"{np.max(np.abs(wf)):.6e} m")
        res[name] = w2N
        print()

    # ------------------------------------------------------------------ independent checks
    if not args.quick:
        print("Duhamel integral by steps (exact for a piecewise-linear load) against the closed form,")
        print("max |difference| of the tip response / max |w_tip| (all 2N modes):")
        for name, data in (("Euler-Bernoulli", eb), ("Timoshenko", ti)):
            om_, c_, sh_ = data
            ref = res[name][-1]
            peak = np.max(np.abs(ref))
            for dt in (1e-3, 1e-4, 1e-5):
                qs = duhamel_stepwise(om_, om, dt, int(round(DT_OUT / dt)))
                wt = P0 * (sh_[:, -1] * c_) @ qs
                print(f"   {name:16s} step {dt:.0e} s: {np.max(np.abs(wt - ref)) / peak:.2e}")
        print()
        print("finite-element Timoshenko beam (quadratic w and psi, 3-point Gauss), frequencies:")
        nel_list = (96, 192, 384, 768)
        fe_res = {}
        for nel in nel_list:
            wfe, vec, tip, K, _ = timo_fe(nel)
            fe_res[nel] = (wfe, vec, tip, K)
            rel = np.abs(wfe[:20] - ti[0][:20]) / ti[0][:20]
            ncount = int(np.sum(wfe < ti[0][2 * n_ti - 1] * (1 - 1e-6)))
            print(f"   {nel:4d} elements: max rel. difference, first 20 modes {rel.max():.2e}; "
                  f"FE modes below the analytic mode {2 * n_ti}: {ncount} (analytic: {2 * n_ti - 1})")
        nel = nel_list[-1]
        wfe, vec, tip, K = fe_res[nel]
        f = np.zeros(K.shape[0])
        f[tip] = 1.0
        ust = np.linalg.solve(K, f)
        print(f"   {nel} elements: static tip flexibility {ust[tip]:.9e} m/N (exact {static_timo(L, 1.0):.9e})")
        # FE modal superposition with all modes (mass-normalised eigenvectors)
        q = modal_response(wfe, om, t)
        wtip_fe = P0 * (vec[tip, :] * vec[tip, :]) @ q
        peak = np.max(np.abs(res["Timoshenko"][-1]))
        print(f"   {nel} elements, all {len(wfe)} FE modes: tip response differs from the analytic "
              f"modal solution by {np.max(np.abs(wtip_fe - res['Timoshenko'][-1])) / peak:.2e} of its maximum")
        print()

    # ------------------------------------------------------------------ output
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "cantilever_tip.csv"), "w") as fh:
        fh.write("t,w_tip_euler_bernoulli,w_tip_timoshenko\n")
        for k in range(len(t)):
            fh.write(f"{t[k]:.3f},{res['Euler-Bernoulli'][-1][k]:.9e},{res['Timoshenko'][-1][k]:.9e}\n")
    with open(os.path.join(args.out, "cantilever_stations.csv"), "w") as fh:
        cols = []
        for name, tag in (("Euler-Bernoulli", "eb"), ("Timoshenko", "timoshenko")):
            for xs in STATIONS:
                cols.append(f"w_{tag}_x{xs:g}")
        fh.write("t," + ",".join(cols) + "\n")
        for k in range(len(t)):
            vals = [res[n][j][k] for n in ("Euler-Bernoulli", "Timoshenko") for j in range(len(STATIONS))]
            fh.write(f"{t[k]:.3f}," + ",".join(f"{v:.9e}" for v in vals) + "\n")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(7.5, 3.6), dpi=110)
        ax.plot(t, 1e3 * res["Euler-Bernoulli"][-1], label="Euler-Bernoulli")
        ax.plot(t, 1e3 * res["Timoshenko"][-1], label="Timoshenko (Cowper k)")
        ax.plot(t, 1e3 * static_timo(L, P0) * load_shape(om, t), "k:", lw=0.8,
                label="quasi-static Timoshenko, P(t) L^3/3EI + P(t) L/kGA")
        ax.axvline(T_LOAD, color="0.6", lw=0.6)
        ax.set_xlabel("t (s)")
        ax.set_ylabel("tip deflection w(L, t) (mm)")
        ax.set_title(f"cantilever 48 x 6 x 12 m, P(t) = {P0:.1f} sin({om:g} t) N for t <= 0.5 s", fontsize=9)
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(os.path.join(args.out, "cantilever_tip.png"))
    except ImportError:
        print("matplotlib missing: no plot")
    print(f"wrote {args.out}/cantilever_tip.csv, cantilever_stations.csv and cantilever_tip.png "
          f"({time.time() - t0:.0f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
