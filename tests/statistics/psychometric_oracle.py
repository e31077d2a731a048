#!/usr/bin/python3
"""Independent oracle for the psychometric fit with guess = lapse = 0 (tests/statistics/
psychometric_fit_test.cpp): a probit GLM by statsmodels (IRLS, Debian's python3-statsmodels),
which shares no code with palprig's Ceres fit.

    psychometric_oracle.py FILE.csv    (columns level,n,k)
prints one JSON object: b0, b1 (probit intercept and slope), alpha = -b0/b1 (PSE),
beta = 1/b1 (sd of the cumulative Gaussian), log_likelihood, deviance.
"""
import csv
import json
import sys

import numpy as np
import statsmodels.api as sm

rows = list(csv.DictReader(open(sys.argv[1])))
level = np.array([float(r["level"]) for r in rows])
n = np.array([float(r["n"]) for r in rows])
k = np.array([float(r["k"]) for r in rows])
X = sm.add_constant(level)
model = sm.GLM(np.column_stack([k, n - k]), X, family=sm.families.Binomial(link=sm.families.links.probit()))
fit = model.fit(tol=1e-14, maxiter=200)
b0, b1 = fit.params
# statsmodels' llf includes the binomial coefficients; palprig's does not: remove them.
from math import lgamma
log_binom = sum(lgamma(a + 1) - lgamma(b + 1) - lgamma(a - b + 1) for a, b in zip(n, k))
print(json.dumps({"b0": b0, "b1": b1, "alpha": -b0 / b1, "beta": 1 / b1,
                  "log_likelihood": fit.llf - log_binom, "deviance": fit.deviance}))
