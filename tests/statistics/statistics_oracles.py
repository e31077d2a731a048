#!/usr/bin/env python3
"""Independent oracle values for tests/statistics/statistics_*_test.cpp.

Written without scipy (not installed) and without the C++ code: plain Python for the
statistics, mpmath (50 significant digits) for the t and normal distributions, exact integer
enumeration for the rank distributions. Run it to reprint every expected value:
    python3 tests/statistics/statistics_oracles.py
"""
from fractions import Fraction
from itertools import combinations
import math
import mpmath as mp

mp.mp.dps = 50


def t_two_sided(t, df):
    # P(|T| >= |t|) = I_{df/(df+t^2)}(df/2, 1/2), the regularised incomplete beta.
    t = mp.mpf(t)
    df = mp.mpf(df)
    return mp.betainc(df / 2, mp.mpf(1) / 2, 0, df / (df + t * t), regularized=True)


def t_quantile(q, df):
    # Invert the cdf numerically: cdf(x) = 1 - p/2 with p the two-sided tail.
    return mp.findroot(lambda x: 1 - t_two_sided(x, df) / 2 - q, 2)


def norm_two_sided(z):
    return mp.erfc(abs(mp.mpf(z)) / mp.sqrt(2))


def mean(v):
    return mp.fsum(v) / len(v)


def var(v):
    m = mean(v)
    return mp.fsum((x - m) ** 2 for x in v) / (len(v) - 1)


def show(name, value):
    print(f"{name:40s} {mp.nstr(value, 17)}")


def quantile7(v, p):
    s = sorted(v)
    h = (len(s) - 1) * p
    lo = math.floor(h)
    hi = min(lo + 1, len(s) - 1)
    return s[lo] + (h - lo) * (s[hi] - s[lo])


def quantile6(v, p):
    s = sorted(v)
    h = min(max((len(s) + 1) * p - 1, 0), len(s) - 1)
    lo = math.floor(h)
    hi = min(lo + 1, len(s) - 1)
    return s[lo] + (h - lo) * (s[hi] - s[lo])


def avg_ranks(v):
    s = sorted(v)
    return [Fraction(2 * s.index(x) + 1 + s.count(x), 2) for x in v]  # mean of first..last position


def wilson(k, n, z=mp.sqrt(2) * mp.erfinv(mp.mpf("0.95"))):
    p = mp.mpf(k) / n
    d = 1 + z * z / n
    c = (p + z * z / (2 * n)) / d
    h = z * mp.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / d
    return p, c - h, c + h


print("== describe")
d = [2, 4, 4, 5, 7, 9, 10, 12]
show("mean", mean(d)); show("sd", mp.sqrt(var(d)))
for p in (0.25, 0.5, 0.75):
    show(f"type7 q{p}", quantile7(d, p)); show(f"type6 q{p}", quantile6(d, p))

print("== t tests")
x = [5.1, 4.9, 6.2, 5.8, 6.0, 5.5, 5.3]
y = [4.2, 4.8, 4.5, 5.0, 4.1, 4.6]
xs = [mp.mpf(str(a)) for a in x]; ys = [mp.mpf(str(a)) for a in y]
nx, ny = len(xs), len(ys)
vx, vy = var(xs), var(ys)
est = mean(xs) - mean(ys)
sp = ((nx - 1) * vx + (ny - 1) * vy) / (nx + ny - 2)
se = mp.sqrt(sp * (mp.mpf(1) / nx + mp.mpf(1) / ny)); df = nx + ny - 2
t = est / se
show("student t", t); show("student p", t_two_sided(t, df))
q = t_quantile(mp.mpf("0.975"), df)
show("student ci lower", est - q * se); show("student ci upper", est + q * se)
ax, ay = vx / nx, vy / ny
se = mp.sqrt(ax + ay); df = (ax + ay) ** 2 / (ax ** 2 / (nx - 1) + ay ** 2 / (ny - 1)); t = est / se
show("welch t", t); show("welch df", df); show("welch p", t_two_sided(t, df))
q = t_quantile(mp.mpf("0.975"), df)
show("welch ci lower", est - q * se); show("welch ci upper", est + q * se)

before = [mp.mpf(a) for a in ("12.1", "14.3", "11.8", "13.5", "12.9", "15.0", "13.2", "12.4")]
after = [mp.mpf(a) for a in ("11.4", "13.9", "11.9", "12.6", "12.1", "14.2", "12.8", "12.0")]
diff = [a - b for a, b in zip(before, after)]
se = mp.sqrt(var(diff) / len(diff)); t = mean(diff) / se
show("paired t", t); show("paired p", t_two_sided(t, len(diff) - 1))
t1 = (mean(xs) - 5) / mp.sqrt(vx / nx)
show("one-sample t vs 5", t1); show("one-sample p", t_two_sided(t1, nx - 1))

print("== paper 002: Student t on 4.6 +/- 2.3 s vs 8.3 +/- 2.9 s, 168 each (rounded summaries)")
def student_summary(m1, s1, m2, s2, n=168):
    se = mp.sqrt(((n - 1) * s1 ** 2 + (n - 1) * s2 ** 2) / (2 * n - 2) * (mp.mpf(2) / n))
    return t_two_sided((m1 - m2) / se, 2 * n - 2)
show("p at the rounded figures", student_summary(mp.mpf("4.6"), mp.mpf("2.3"), mp.mpf("8.3"), mp.mpf("2.9")))
show("p smallest (|diff| 3.8, sd low)", student_summary(mp.mpf("4.55"), mp.mpf("2.25"), mp.mpf("8.35"), mp.mpf("2.85")))
show("p largest (|diff| 3.6, sd high)", student_summary(mp.mpf("4.65"), mp.mpf("2.35"), mp.mpf("8.25"), mp.mpf("2.95")))

print("== paper 000 table 3: two-sided p of reported t")
for tt, dd in ((-2.615, 22), (-2.955, 22), (-1.779, 22), (-1.351, 22), (-3.7, 16), (-3.816, 16), (-0.347, 16), (-1.247, 16)):
    show(f"t({dd}) = {tt}", t_two_sided(mp.mpf(str(tt)), dd))

print("== Mann-Whitney, exact by enumeration")
a = [1.1, 2.2, 3.3, 4.4]
b = [5.5, 6.6, 2.5, 7.7, 0.5]
def u_of(ga, gb):
    return sum((1 if p > q else Fraction(1, 2) if p == q else 0) for p in ga for q in gb)
pool = a + b
us = [u_of([pool[i] for i in c], [pool[i] for i in range(len(pool)) if i not in c]) for c in combinations(range(len(pool)), len(a))]
u1 = u_of(a, b)
lower = Fraction(sum(1 for u in us if u <= u1), len(us)); upper = Fraction(sum(1 for u in us if u >= u1), len(us))
print("U1", u1, "exact two-sided p", min(1, 2 * (upper if u1 > len(a) * len(b) / 2 else lower)), float(min(1, 2 * (upper if u1 > len(a) * len(b) / 2 else lower))))

print("== Mann-Whitney, paper 000 shape: groups of 17 and 23, U = 106, untied")
ranks_a = list(range(1, 13)) + [27, 37, 38, 39, 40]
ranks_b = [r for r in range(1, 41) if r not in ranks_a]
u1 = sum(ranks_a) - 17 * 18 // 2
print("U1", u1, "n", len(ranks_a), len(ranks_b))
# Exact distribution of U from the Gaussian binomial coefficient [40 choose 17]_q, built by
# exact polynomial products and divisions (a different route from the C++ recurrence).
def poly_mul(p, q):
    r = [0] * (len(p) + len(q) - 1)
    for i, x in enumerate(p):
        if x:
            for j, y in enumerate(q):
                r[i + j] += x * y
    return r
def poly_div_exact(p, q):  # q has constant term 1
    p = p[:]; out = [0] * (len(p) - len(q) + 1)
    for i in range(len(out)):
        c = p[i]; out[i] = c
        for j, y in enumerate(q):
            p[i + j] -= c * y
    return out
m, n = 17, 23
num = [1]
for i in range(1, m + 1):
    num = poly_mul(num, [1] + [0] * (n + i - 1) + [-1])  # (1 - q^(n+i))
for i in range(1, m + 1):
    num = poly_div_exact(num, [1] + [0] * (i - 1) + [-1])  # / (1 - q^i)
total = sum(num)
assert total == math.comb(40, 17)
p_exact = Fraction(2 * sum(num[: u1 + 1]), total)
print("exact two-sided p", float(p_exact))
sigma = mp.sqrt(mp.mpf(m * n) / 12 * (m + n + 1))
zc = (u1 - mp.mpf(m * n) / 2 + mp.mpf("0.5")) / sigma
z0 = (u1 - mp.mpf(m * n) / 2) / sigma
show("z corrected", zc); show("r corrected", zc / mp.sqrt(40))
show("z uncorrected", z0); show("r uncorrected", z0 / mp.sqrt(40))

print("== Mann-Whitney with ties, normal approximation")
a = [1, 2, 2, 3, 4]
b = [3, 3, 4, 5, 5, 5]
r = avg_ranks(a + b)
u1 = sum(r[: len(a)]) - Fraction(len(a) * (len(a) + 1), 2)
groups = {}
for v in a + b:
    groups[v] = groups.get(v, 0) + 1
tie = sum(t ** 3 - t for t in groups.values())
N = len(a) + len(b)
sigma = mp.sqrt(mp.mpf(len(a) * len(b)) / 12 * ((N + 1) - mp.mpf(tie) / (N * (N - 1))))
z = (mp.mpf(u1.numerator) / u1.denominator - mp.mpf(len(a) * len(b)) / 2 + mp.mpf("0.5")) / sigma
print("U1", u1, "tie term", tie); show("z", z); show("p", norm_two_sided(z)); show("r", z / mp.sqrt(N))

print("== Wilcoxon signed rank, R's wilcox.test example (Hollander & Wolfe, depression scale)")
x = [1.83, 0.50, 1.62, 2.48, 1.68, 1.88, 1.55, 3.06, 1.30]
y = [0.878, 0.647, 0.598, 2.05, 1.06, 1.29, 1.06, 3.14, 1.29]
dd = [Fraction(str(p)) - Fraction(str(q)) for p, q in zip(x, y)]
r = avg_ranks([abs(v) for v in dd])
v = sum(rk for rk, dv in zip(r, dd) if dv > 0)
n = len(dd)
sums = [sum(k for k, bit in zip(range(1, n + 1), format(mask, f"0{n}b")) if bit == "1") for mask in range(2 ** n)]
upper = Fraction(sum(1 for s in sums if s >= v), 2 ** n)
print("V", v, "exact two-sided p", float(min(1, 2 * upper)))

print("== Wilcoxon signed rank, Likert item against the neutral point 3 (paper 003 item 6 shape)")
x = [3, 4, 4, 4, 4, 4, 4, 4, 4, 4]
dd = [a - 3 for a in x if a != 3]
n = len(dd)
vf = sum(avg_ranks([abs(a) for a in dd])); v = mp.mpf(vf.numerator) / vf.denominator
var_v = mp.mpf(n * (n + 1) * (2 * n + 1)) / 24 - mp.mpf(n ** 3 - n) / 48
zc = (v - mp.mpf(n * (n + 1)) / 4 - mp.mpf("0.5")) / mp.sqrt(var_v)
z0 = (v - mp.mpf(n * (n + 1)) / 4) / mp.sqrt(var_v)
print("V", v); show("z corrected", zc); show("p corrected", norm_two_sided(zc))
show("z uncorrected", z0); show("p uncorrected", norm_two_sided(z0))
print("median, type6 quartiles", quantile6(x, .5), quantile6(x, .25), quantile6(x, .75))

print("== Pearson")
x = [1, 2, 3, 4, 5, 6]
y = [mp.mpf(s) for s in ("2.1", "3.9", "6.2", "7.8", "10.1", "12.2")]
y2 = [mp.mpf(s) for s in ("3.0", "1.0", "4.0", "1.5", "5.0", "2.0")]
for name, yy in (("linear", y), ("noisy", y2)):
    mx, my = mean(x), mean(yy)
    r_ = mp.fsum((a - mx) * (b - my) for a, b in zip(x, yy)) / mp.sqrt(
        mp.fsum((a - mx) ** 2 for a in x) * mp.fsum((b - my) ** 2 for b in yy))
    tt = r_ * mp.sqrt(4 / (1 - r_ ** 2))
    zc = mp.sqrt(2) * mp.erfinv(mp.mpf("0.95"))
    show(f"{name} r", r_); show(f"{name} t", tt); show(f"{name} p", t_two_sided(tt, 4))
    show(f"{name} ci lower", mp.tanh(mp.atanh(r_) - zc / mp.sqrt(3)))
    show(f"{name} ci upper", mp.tanh(mp.atanh(r_) + zc / mp.sqrt(3)))

print("== paper 000 table 4: p of published r (rounded to 2 decimals) at r +/- 0.005")
for rr, nn, pp in ((-0.32, 40, .044), (0.32, 38, .048), (-0.37, 38, .021), (0.32, 38, .047), (0.48, 38, .002),
                   (0.34, 38, .037), (0.37, 38, .023), (0.45, 49, .001), (0.36, 38, .026)):
    def p_of(r_):
        r_ = mp.mpf(r_)
        return t_two_sided(r_ * mp.sqrt((nn - 2) / (1 - r_ ** 2)), nn - 2)
    print(f"r {rr} n {nn} reported {pp}: p range", mp.nstr(p_of(abs(rr) + 0.005), 6), mp.nstr(p_of(abs(rr) - 0.005), 6))

print("== Wilson and paper 002 eq. 10")
for k, n in ((488, 504), (470, 504), (6, 9), (9, 9), (8, 9), (0, 10), (1, 3)):
    p, lo, hi = wilson(k, n)
    print(f"{k}/{n}", mp.nstr(p, 12), mp.nstr(lo, 12), mp.nstr(hi, 12))
p1, l1, u1 = wilson(488, 504); p2, l2, u2 = wilson(470, 504)
show("ACC combined interval", mp.sqrt((l1 - p1) ** 2 + (u2 - p2) ** 2))
show("ACC newcombe lower", (p1 - p2) - mp.sqrt((p1 - l1) ** 2 + (u2 - p2) ** 2))
show("ACC newcombe upper", (p1 - p2) + mp.sqrt((u1 - p1) ** 2 + (p2 - l2) ** 2))
p1, l1, u1 = wilson(331, 336); p2, l2, u2 = wilson(322, 336)
show("Sp difference (331 vs 322 of 336)", p1 - p2)
show("Sp combined interval", mp.sqrt((l1 - p1) ** 2 + (u2 - p2) ** 2))
