#!/usr/bin/env python3
"""Oracle for `palprig stats trials`' response-time tests (tests/store/condition_comparisons_test.cpp).

Reads a palprig trial store with Python's own sqlite3 (no palprig code), takes the response time
of every answered, scored trial (practice left out), one value per trial, per condition, and runs
scipy's two-sample t-tests on them: Student's (scipy.stats.ttest_ind, equal_var=True, paper 002)
and Welch's (equal_var=False). Prints one JSON object:
  {"conditions": [A, B], "n": [nA, nB], "mean": [...],
   "student": {"t": ..., "p": ..., "df": ...}, "welch": {"t": ..., "p": ..., "df": ...}}
with A < B (palprig compares conditions in sorted order: t is mean(A) - mean(B) over its error).
Needs Debian's python3-scipy (tools/debian-packages.txt).
"""
import json
import sqlite3
import sys

import numpy as np
from scipy import stats


def main(path):
    db = sqlite3.connect("file:" + path + "?mode=ro", uri=True)
    rows = db.execute(
        "SELECT condition, response_time_s FROM trials "
        "WHERE practice = 0 AND answered = 1 AND response_time_s IS NOT NULL ORDER BY id").fetchall()
    by = {}
    for condition, rt in rows:
        by.setdefault(condition, []).append(rt)
    a, b = sorted(by)
    x, y = np.array(by[a]), np.array(by[b])
    out = {"conditions": [a, b], "n": [len(x), len(y)], "mean": [x.mean(), y.mean()]}
    for name, equal in (("student", True), ("welch", False)):
        r = stats.ttest_ind(x, y, equal_var=equal)
        if equal:
            df = len(x) + len(y) - 2
        else:
            vx, vy = x.var(ddof=1) / len(x), y.var(ddof=1) / len(y)
            df = (vx + vy) ** 2 / (vx ** 2 / (len(x) - 1) + vy ** 2 / (len(y) - 1))
        out[name] = {"t": float(r.statistic), "p": float(r.pvalue), "df": float(df)}
    print(json.dumps(out))


if __name__ == "__main__":
    main(sys.argv[1])
