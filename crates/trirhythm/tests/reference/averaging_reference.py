"""Independent reference values for tests/averaging.rs.

Written from the paper's printed formulas (Eq. 5, 18, 26, 27 with the (1+tau^2) factor on the
impact term, formulas.md), in the amplitude A itself (not x = A^2 as the library does), with
mpmath at 30 significant digits: polynomial roots by mpmath.polyroots, integrals by mpmath.quad
(tanh-sinh), the coloured-noise harmonic sum by mpmath.nsum. Run: python3 averaging_reference.py
"""
from mpmath import mp, mpf, sin, cos, pi, sqrt, polyroots, quad, exp, log, nsum, inf, findroot, diff

mp.dps = 30


def equivalents(mu0, w0, lam):
    s, c = sin(pi * lam / 2), cos(pi * lam / 2)
    return mu0 * w0 ** (1 - lam) / s, 1 - w0 ** lam * c / mu0, sqrt(w0 ** (3 - lam) / s), w0 ** (1 - lam) / s


def eq18(A, mu1, b1, w1, r, a0, b0, g0, d0):
    return (mu1 * A / 1024) * (512 * b1 - 128 * A**2 + 64 * a0 * A**4 - 40 * b0 * A**6
                               + 28 * g0 * A**8 - 21 * d0 * A**10) - (1 - r) * w1 * A / pi


def cycles(mu0, w0, lam, r, a0, b0, g0, d0):
    mu1, b1, w1, b2 = equivalents(mu0, w0, lam)
    # f(A)/A as a polynomial in A (degree 10), highest power first for polyroots
    c = [-21 * d0, 0, 28 * g0, 0, -40 * b0, 0, 64 * a0, 0, -128, 0, 512 * b1 - 1024 * (1 - r) * w1 / (pi * mu1)]
    roots = polyroots(c, maxsteps=400, extraprec=200)
    pos = sorted(z.real for z in roots if abs(z.imag) < mpf(10) ** -20 and z.real > 0)
    out = []
    for a in pos:
        slope = diff(lambda x: eq18(x, mu1, b1, w1, r, a0, b0, g0, d0), a)
        out.append((a, slope < 0))
    return out


print("equivalents at lambda = 0.998, omega0 = 1, mu0 = 0.01:")
for name, v in zip(["mu1", "beta1", "omega1", "beta2"], equivalents(mpf("0.01"), mpf(1), mpf("0.998"))):
    print(f"  {name} = {mp.nstr(v, 20)}")
print("equivalents at lambda = 0.99, omega0 = 0.9, mu0 = 0.002:")
for name, v in zip(["mu1", "beta1", "omega1", "beta2"], equivalents(mpf("0.002"), mpf("0.9"), mpf("0.99"))):
    print(f"  {name} = {mp.nstr(v, 20)}")

cp = (mpf("0.144"), mpf("0.005"), mpf("5.862e-5"), mpf("2.13e-7"))
print("roots of f, Fig. 4(c) control parameters, r = 1, lambda = 0.998, mu0 = 0.01, omega0 = 1:")
for a, st in cycles(mpf("0.01"), mpf(1), mpf("0.998"), mpf(1), *cp):
    print(f"  A = {mp.nstr(a, 20)} stable = {st}")
print("roots of f, same, r = 0.999, lambda = 0.999, mu0 = 0.05, omega0 = 0.9:")
for a, st in cycles(mpf("0.05"), mpf("0.9"), mpf("0.999"), mpf("0.999"), *cp):
    print(f"  A = {mp.nstr(a, 20)} stable = {st}")

# Stationary amplitude PDF, paper variant, Eq. 27 with (1+tau^2) on the impact term.
mu0, w0, lam, r, D, tau = mpf("0.005"), mpf(1), mpf("0.998"), mpf("0.99"), mpf("0.1"), mpf("0.5")
mu1, b1, w1, b2 = equivalents(mu0, w0, lam)
a0, b0, g0, d0 = cp


def log_unnormalised(A):
    k = w1**2 * (1 + tau**2) / (b2 * D)
    poly = 256 * b1 * A**2 - 32 * A**4 + 32 * a0 / 3 * A**6 - 5 * b0 * A**8 + 14 * g0 / 5 * A**10 - 7 * d0 / 4 * A**12
    return log(k * A) + k * (mu1 / 512 * poly - (1 - r) * w1 * A**2 / pi)


shift = max(log_unnormalised(mpf(a) / 10) for a in range(1, 160))
mass = quad(lambda A: exp(log_unnormalised(A) - shift), [0, 2, 4, 6, 8, 10, 12, 13, 14, 16, 20])
mean = quad(lambda A: A * exp(log_unnormalised(A) - shift), [0, 2, 4, 6, 8, 10, 12, 13, 14, 16, 20]) / mass
print("amplitude PDF, paper variant, mu0 = 0.005, lambda = 0.998, r = 0.99, D = 0.1, tau = 0.5, omega0 = 1:")
print(f"  ln N0 = {mp.nstr(-shift - log(mass), 20)}  (ln P(A) = ln N0 + ln_unnormalised)")
print(f"  mean amplitude = {mp.nstr(mean, 20)}")
print(f"  P(A = 8) = {mp.nstr(exp(log_unnormalised(mpf(8)) - shift) / mass, 20)}")
dlogp = lambda A: diff(log_unnormalised, A)
modes = []
for guess in [mpf(x) / 4 for x in range(2, 60)]:
    try:
        z = findroot(dlogp, guess)
        z = mp.re(z) if abs(mp.im(z)) < 1e-25 else z
    except Exception:
        continue
    if mp.im(z) == 0 and 0 < z < 15 and all(abs(z - m) > 1e-8 for m in modes):
        modes.append(z)
print("  extrema of P(A):", [mp.nstr(m, 15) for m in sorted(modes)])

s = nsum(lambda k: (8 * k / (pi * (4 * k**2 - 1)))**2 / (1 + 4 * k**2 * mpf("0.25") * mpf("0.81")), [1, inf])
print(f"consistent sigma1 factor sum_k b_k^2/(1 + 4 k^2 tau^2 omega1^2) at tau = 0.5, omega1 = 0.9: {mp.nstr(s, 20)}")
