"""Ensemble statistics over repeated runs: mean, sample standard deviation and a Student t 95 %
confidence half-width per group (docs/analysis.md, Ensemble statistics). No scipy: the t
quantile inverts the t distribution's CDF, written with the regularised incomplete beta function."""
import math

import numpy as np
import pandas as pd


def _beta_continued_fraction(a, b, x):
    """The continued fraction of the regularised incomplete beta function (modified Lentz)."""
    tiny, c, d = 1e-300, 1.0, 1.0 - (a + b) * x / (a + 1)
    d = 1.0 / (d if abs(d) > tiny else tiny)
    result = d
    for m in range(1, 300):
        for numerator in (m * (b - m) * x / ((a + 2 * m - 1) * (a + 2 * m)),
                          -(a + m) * (a + b + m) * x / ((a + 2 * m) * (a + 2 * m + 1))):
            d = 1.0 + numerator * d
            d = 1.0 / (d if abs(d) > tiny else tiny)
            c = 1.0 + numerator / c
            c = c if abs(c) > tiny else tiny
            result *= c * d
        if abs(c * d - 1.0) < 1e-15:
            break
    return result


def incomplete_beta(a, b, x):
    """The regularised incomplete beta function I_x(a, b), 0 <= x <= 1."""
    if x <= 0.0 or x >= 1.0:
        return 0.0 if x <= 0.0 else 1.0
    log_front = (math.lgamma(a + b) - math.lgamma(a) - math.lgamma(b)
                 + a * math.log(x) + b * math.log1p(-x))
    if x < (a + 1) / (a + b + 2):
        return math.exp(log_front) * _beta_continued_fraction(a, b, x) / a
    return 1.0 - math.exp(log_front) * _beta_continued_fraction(b, a, 1.0 - x) / b


def t_cdf(t, dof):
    """P(T <= t) for Student's t with `dof` degrees of freedom."""
    tail = 0.5 * incomplete_beta(dof / 2, 0.5, dof / (dof + t * t))
    return 1.0 - tail if t >= 0 else tail


def t_quantile(p, dof):
    """The p quantile of Student's t with `dof` > 0 degrees of freedom (bisection on t_cdf,
    to 1e-12 relative), e.g. t_quantile(0.975, 4) = 2.776."""
    if not 0 < p < 1 or dof <= 0:
        raise ValueError(f"t_quantile: need 0 < p < 1 and dof > 0, got p={p}, dof={dof}")
    if p < 0.5:
        return -t_quantile(1 - p, dof)
    lo, hi = 0.0, 1.0
    while t_cdf(hi, dof) < p:
        lo, hi = hi, 2 * hi
    while hi - lo > 1e-12 * hi:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if t_cdf(mid, dof) < p else (lo, mid)
    return 0.5 * (lo + hi)


def summarise(df, group_cols, metric_cols, level=0.95):
    """One row per group of `group_cols`: n (rows in the group) and, for each metric over its
    finite values, <metric>_n, <metric>_mean, <metric>_std (sample, ddof=1) and <metric>_ci95,
    the half-width t_{(1+level)/2, n-1} std / sqrt(n) of the confidence interval of the mean
    (nan for fewer than 2 values)."""
    group_cols, metric_cols = list(group_cols), list(metric_cols)
    rows = []
    keys = group_cols if len(group_cols) > 1 else group_cols[0]  # a 1-list groups with a warning
    for key, group in df.groupby(keys, sort=True, dropna=False):
        key = key if isinstance(key, tuple) else (key,)
        row = dict(zip(group_cols, key), n=len(group))
        for metric in metric_cols:
            values = pd.to_numeric(group[metric], errors="coerce").to_numpy(dtype=float)
            count, mean, std, half = interval(values, level)
            row.update({f"{metric}_n": count, f"{metric}_mean": mean, f"{metric}_std": std,
                        f"{metric}_ci95": half})
        rows.append(row)
    return pd.DataFrame(rows)


def interval(values, level=0.95):
    """(n, mean, std, half-width) over the finite values: the sample std (ddof=1) and the
    half-width t_{(1+level)/2, n-1} std / sqrt(n) are nan for fewer than 2 values."""
    values = np.asarray(values, dtype=float)
    values = values[np.isfinite(values)]
    count = len(values)
    mean = float(np.mean(values)) if count else math.nan
    if count < 2:
        return count, mean, math.nan, math.nan
    std = float(np.std(values, ddof=1))
    return count, mean, std, t_quantile((1 + level) / 2, count - 1) * std / math.sqrt(count)
