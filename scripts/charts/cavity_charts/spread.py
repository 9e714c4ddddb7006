"""The spread every timing chart draws: the interquartile range of a
configuration's repetitions (cavity_bench JSON) or frames (results.json),
and what it means for a ratio of two such times.

Why the interquartile range: cavity_bench runs 3 to 10 repetitions and
`cavity run` 50 frames or more. Min-max would let one frame that hit a
preemption or a CPU renderer's scheduler stretch the whiskers of every
point; the middle half of the samples shows how far a median can be trusted
and is the same rule for both. With one sample there is no spread, and the
charts say so rather than draw a zero-width bar.
"""

import math

INTERVAL = "interquartile range"
INTERVAL_SHORT = "IQR"


def quantile(values, q):
    """The q-quantile of values, linearly interpolated between order
    statistics (numpy's default, R's type 7)."""
    v = sorted(values)
    if not v:
        return float("nan")
    pos = (len(v) - 1) * q
    lo = math.floor(pos)
    hi = min(lo + 1, len(v) - 1)
    return v[lo] + (v[hi] - v[lo]) * (pos - lo)


def median(values):
    return quantile(values, 0.5)


def summary(samples, centre=None):
    """{"ms", "q25", "q75", "n"} of samples; centre replaces the median as "ms"
    where the file has its own (a "median" aggregate). q25 and q75 are None
    with fewer than two samples."""
    n = len(samples)
    ms = centre if centre is not None else median(samples)
    if n < 2:
        return {"ms": ms, "q25": None, "q75": None, "n": n}
    return {"ms": ms, "q25": quantile(samples, 0.25), "q75": quantile(samples, 0.75), "n": n}


def has_spread(rec):
    return rec.get("q25") is not None and rec.get("q75") is not None


def errors(recs):
    """Matplotlib's asymmetric yerr/xerr for records: [[below ...], [above ...]];
    zero where a record has no spread (the caller says so in the subtitle)."""
    below = [max(r["ms"] - r["q25"], 0.0) if has_spread(r) else 0.0 for r in recs]
    above = [max(r["q75"] - r["ms"], 0.0) if has_spread(r) else 0.0 for r in recs]
    return [below, above]


def whisker_values(recs):
    """Every value a chart with whiskers must fit: medians and quartiles."""
    return [v for r in recs for v in (r["ms"], r.get("q25"), r.get("q75")) if v is not None]


def overlap(a, b):
    """True where the two records' interquartile ranges overlap: the
    difference between their medians is within the repetitions' noise. None
    where either has no spread (unknown)."""
    if not (has_spread(a) and has_spread(b)):
        return None
    return a["q25"] <= b["q75"] and b["q25"] <= a["q75"]


def ratio_range(a, b):
    """(low, high) of a/b when each varies within its interquartile range:
    q25(a)/q75(b) .. q75(a)/q25(b); None without spread on both."""
    if not (has_spread(a) and has_spread(b)) or b["q25"] <= 0 or b["q75"] <= 0:
        return None
    return a["q25"] / b["q75"], a["q75"] / b["q25"]


def ratio_entry(a, b):
    """What a chart writes about a/b: the ratio, its range and whether the
    two spreads overlap (then the ratio is not evidence of a difference)."""
    rr = ratio_range(a, b)
    return {"ratio": a["ms"] / b["ms"], "low": rr[0] if rr else None, "high": rr[1] if rr else None,
            "overlap": overlap(a, b)}


def spread_line(recs):
    """The subtitle's sentence about the whiskers of these records (each
    record's "per" says what its samples are: repetitions or frames)."""
    ns = sorted({r.get("n", 1) for r in recs})
    what = " or ".join(sorted({r.get("per", "repetitions") for r in recs})) or "repetitions"
    if not ns or ns[-1] < 2:
        return (f"one sample per configuration: no spread to draw (cavity_bench --benchmark_repetitions=N, "
                f"or a results.json, gives one)")
    count = f"{ns[0]}" if len(ns) == 1 else f"{ns[0]}-{ns[-1]}"
    line = f"whiskers: {INTERVAL} of each configuration's {count} {what}"
    if ns[0] < 2:
        line += " (none where there was one)"
    return line
