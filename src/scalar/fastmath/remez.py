#!/usr/bin/env python3
"""Coefficients of the polynomials in `f64.rs` and `f32.rs`: weighted minimax fits
(Remez exchange on a dense Chebyshev grid, 40 significant digits with mpmath),
with the coefficients rounded to the working precision one at a time, lowest
degree first, and the remaining ones refitted after each rounding (so the
rounded set is close to the best one in that precision).

Run `python3 remez.py` (needs mpmath); it prints the coefficients as Rust
literals with the maximum relative error of the rounded polynomial, evaluated
exactly (the rounding of the evaluation itself is left to the Rust tests).
"""
import struct

import mpmath as mp

mp.mp.dps = 40


def to_f32(v):
    return mp.mpf(struct.unpack("f", struct.pack("f", float(v)))[0])


def to_f64(v):
    return mp.mpf(float(v))


def remez(target, weight, powers, a, b, npts=800, iters=30):
    """min over c of max_x |weight(x) (sum c_k x^powers[k] - target(x))| on [a, b]."""
    grid = [(a + b) / 2 + (b - a) / 2 * mp.cos(mp.pi * (npts - 1 - i) / (npts - 1)) for i in range(npts)]
    grid = [x for x in grid if weight(x) != 0]
    tv = [target(x) for x in grid]
    wv = [weight(x) for x in grid]
    n = len(powers)
    ref = [grid[int(round(i * (len(grid) - 1) / n))] for i in range(n + 1)]
    best, best_err = None, None
    for _ in range(iters):
        m = mp.matrix(n + 1, n + 1)
        rhs = mp.matrix(n + 1, 1)
        for i, x in enumerate(ref):
            for k, p in enumerate(powers):
                m[i, k] = x**p
            m[i, n] = (-1) ** i / weight(x)
            rhs[i] = target(x)
        sol = mp.lu_solve(m, rhs)
        c = [sol[k] for k in range(n)]
        lev = abs(sol[n])
        err = [wv[i] * (sum(ck * grid[i] ** p for ck, p in zip(c, powers)) - tv[i]) for i in range(len(grid))]
        emax = max(abs(e) for e in err)
        if best_err is None or emax < best_err:
            best, best_err = c, emax
        if emax <= lev * (1 + mp.mpf("1e-6")):
            break
        # local extrema of alternating sign, keep the largest of each run
        ext = []
        i = 0
        while i < len(grid):
            j = i
            s = mp.sign(err[i])
            k = i
            while j < len(grid) and mp.sign(err[j]) == s:
                if abs(err[j]) > abs(err[k]):
                    k = j
                j += 1
            ext.append(k)
            i = j
        while len(ext) > n + 1:  # drop the smaller end, or the smallest adjacent pair
            if abs(err[ext[0]]) < abs(err[ext[-1]]):
                ext.pop(0)
            else:
                ext.pop()
        if len(ext) < n + 1:
            break
        ref = [grid[k] for k in ext]
    return best, best_err


def fit_rounded(target, weight, powers, a, b, rnd):
    fixed = {}
    remaining = list(powers)
    while remaining:
        def t2(x, fixed=dict(fixed)):
            return target(x) - sum(v * x**p for p, v in fixed.items())
        c, _ = remez(t2, weight, remaining, a, b)
        fixed[remaining[0]] = rnd(c[0])
        remaining = remaining[1:]
    grid = [a + (b - a) * i / 4000 for i in range(4001)]
    emax = max(abs(weight(x) * (sum(v * x**p for p, v in fixed.items()) - target(x))) for x in grid if weight(x) != 0)
    return [fixed[p] for p in powers], emax


def show(name, coeffs, emax, f32):
    print(f"// {name}: max relative error of the exactly evaluated polynomial {mp.nstr(emax, 3)}")
    ty = "f32" if f32 else "f64"
    for c in coeffs:
        v = float(c)
        if f32:
            print(f"    {struct.unpack('f', struct.pack('f', v))[0]!r}_f32 (0x{struct.unpack('I', struct.pack('f', v))[0]:08x}),")
        else:
            print(f"    {v!r}_{ty},")


def main():
    ln2 = mp.log(2)

    def q_exp(r):
        return mp.expm1(r) / r if r != 0 else mp.mpf(1)

    def w_exp(r):
        return abs(r) / mp.exp(r)

    def p_log(z):
        s = mp.sqrt(z)
        return 2 * mp.atanh(s) / (s * ln2) if z != 0 else 2 / ln2

    def w_log(z):
        return 1 / p_log(z)

    # ---- f64 (tables: exp 2^(j/32), log centres of 16 intervals of [0.6875, 1.375)) ----
    # exp(r) = 1 + r Q(r) for |r| <= ln2/64.
    h64 = ln2 / 64 * (1 + mp.mpf("1e-3"))
    for deg in (4, 5):
        c, e = fit_rounded(q_exp, w_exp, list(range(deg + 1)), -h64, h64, to_f64)
        show(f"f64 exp kernel: 1 + r Q(r), |r| <= ln2/64, Q of degree {deg}", c, e, False)
    print("// f64 EXP2_TABLE: 2^(j/32)")
    for j in range(32):
        print(f"    {float(mp.power(2, mp.mpf(j) / 32))!r},")
    # log: m in [0.703125, 1.40625): 9 intervals of width 1/32 below 1 - 1/64, the
    # interval [1 - 1/64, 1 + 1/32) with centre 1 (so that log2 1 = 0 exactly), and
    # 6 intervals of width 1/16 above.
    edges = [mp.mpf("0.703125") + mp.mpf(j) / 32 for j in range(10)] + [
        mp.mpf("1.03125") + mp.mpf(j) / 16 for j in range(7)
    ]
    smax = 0
    print("// f64 LOG_TABLE: (centre c, log2 c)")
    for j in range(16):
        lo, hi = edges[j], edges[j + 1]
        c = mp.mpf(1) if j == 9 else to_f64((lo + hi) / 2)
        smax = max(smax, abs((lo - c) / (lo + c)), abs((hi - c) / (hi + c)))
        print(f"    ({float(c)!r}, {float(mp.log(c, 2))!r}),")
    print(f"// max |s| = {mp.nstr(smax, 6)}")
    zmax = (smax * (1 + mp.mpf("1e-6"))) ** 2
    for deg in (2, 3):
        c, e = fit_rounded(p_log, w_log, list(range(deg + 1)), mp.mpf(0), zmax, to_f64)
        show(f"f64 log2 kernel: s P(s^2), |s| <= {mp.nstr(smax, 4)}, P of degree {deg}", c, e, False)

    # ---- f32 (no tables) ----
    # log2(m) = s P(s^2), m in [0.75, 1.5): s in [-1/7, 1/5].
    smax32 = mp.mpf(1) / 5 * (1 + mp.mpf("1e-6"))
    c, e = fit_rounded(p_log, w_log, list(range(4)), mp.mpf(0), smax32**2, to_f32)
    show("f32 log2: s P(s^2), P of degree 3", c, e, True)

    # 2^f = 1 + f Q(f), |f| <= 1/2 (plus the rounding of the reduction).
    hf = mp.mpf("0.5") * (1 + mp.mpf("1e-5"))

    def q_exp2(f):
        return mp.expm1(f * ln2) / f if f != 0 else ln2

    def w_exp2(f):
        return abs(f) / mp.power(2, f)

    for deg in (4, 5):
        c, e = fit_rounded(q_exp2, w_exp2, list(range(deg + 1)), -hf, hf, to_f32)
        show(f"f32 exp2: 1 + f Q(f), Q of degree {deg}", c, e, True)

    # e^r = 1 + r Q(r), |r| <= ln2/2.
    h = ln2 / 2 * (1 + mp.mpf("1e-3"))
    for deg in (4, 5):
        c, e = fit_rounded(q_exp, w_exp, list(range(deg + 1)), -h, h, to_f32)
        show(f"f32 exp: 1 + r Q(r), Q of degree {deg}", c, e, True)


if __name__ == "__main__":
    main()
