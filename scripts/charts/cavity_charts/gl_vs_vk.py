"""gl_vs_vk: OpenGL time against Vulkan time for the same configuration (log-log, a
band of a tenth either side of y = x), each point with both spreads; a difference within them is drawn hollow.

draw(c) draws it on a plotting.Canvas (or says on stderr why it is skipped).
"""

import math

from . import spread
from .labels import short_ids, shorten, time_label
from .plotting import MAX_SERIES, whiskers

NAME = "gl_vs_vk"


def api_pairs(records):
    """[(gl record, vk record)] for configurations measured on both APIs."""
    by = {}
    for r in records:
        by[(r["scene"], r["kernel"], r["samples"], r["blur"], r["params"], r["res"], r["size"], r["stage"], r["api"])] = r
    out = []
    for k, r in sorted(by.items(), key=lambda kv: kv[1]["id"]):
        if k[-1] == "gl" and k[:-1] + ("vk",) in by:
            out.append((r, by[k[:-1] + ("vk",)]))
    return out


def changes(pairs):
    """Per pair: Vulkan against OpenGL in percent, its range from the two
    spreads and whether the spreads overlap (spread.ratio_entry of vk / gl)."""
    out = []
    for g, k in pairs:
        e = spread.ratio_entry(k, g)
        out.append({"id": g["id"].replace("/gl/", "/*/"), "gl_ms": g["ms"], "vk_ms": k["ms"],
                    "change_pct": (e["ratio"] - 1) * 100,
                    "low_pct": (e["low"] - 1) * 100 if e["low"] is not None else None,
                    "high_pct": (e["high"] - 1) * 100 if e["high"] is not None else None,
                    "overlap": e["overlap"]})
    return out


def change_text(ch):
    if ch["overlap"]:
        return f"{ch['change_pct']:+.1f}% (spreads overlap)"
    if ch["low_pct"] is not None:
        return f"{ch['change_pct']:+.1f}% ({ch['low_pct']:+.0f} to {ch['high_pct']:+.0f}%)"
    return f"{ch['change_pct']:+.1f}% (no spread)"


def draw(c):
    pairs = api_pairs(c.records)
    if not pairs:
        return c.skip("gl_vs_vk", "no configuration measured on both OpenGL and Vulkan")
    # A colour a kernel: at most MAX_SERIES of them, the first by name.
    kernels = sorted({g["kernel"] for g, _ in pairs})
    left_out = len(kernels) - MAX_SERIES
    if left_out > 0:
        keep = set(kernels[:MAX_SERIES])
        pairs = [(g, k) for g, k in pairs if g["kernel"] in keep]
    fig, ax = c.figure(width=11.0, height=7.4)
    vals = [v for g, k in pairs for r in (g, k) for v in (r["ms"], r.get("q25"), r.get("q75")) if v]
    lo, hi = min(vals) / 1.6, max(vals) * 1.6
    xs = [lo * (hi / lo) ** (i / 100) for i in range(101)]
    ax.fill_between(xs, [x * 0.9 for x in xs], [x * 1.1 for x in xs], color="#999999", alpha=0.22,
                    label="±10% band", zorder=1)
    ax.plot(xs, xs, color="#555555", linewidth=1, label="y = x (same time)", zorder=2)
    markers = {"compute": "o", "fragment": "^"}
    seen = set()
    chs = changes(pairs)
    for (g, k), ch in zip(pairs, chs):
        kern, stage = g["kernel"], g["stage"]
        colour = c.kcolor.get(kern, "#333333")
        hollow = ch["overlap"] is True
        whiskers(ax, [g["ms"]], [k["ms"]], [g], horizontal=True, ecolor=colour, elinewidth=0.9, alpha=0.7,
                 capsize=2, zorder=2.5)
        whiskers(ax, [g["ms"]], [k["ms"]], [k], ecolor=colour, elinewidth=0.9, alpha=0.7, capsize=2, zorder=2.5)
        ax.scatter(g["ms"], k["ms"], s=46, marker=markers.get(stage, "D"), zorder=3,
                   facecolor="white" if hollow else colour, edgecolor=colour if hollow else "white",
                   linewidth=1.2 if hollow else 0.6)
        seen.add((kern, stage))
    for kern in sorted({k for k, _ in seen}):
        ax.plot([], [], linestyle="none", marker="o", color=c.kcolor.get(kern), label=kern)
    for stage in sorted({s for _, s in seen}):
        ax.plot([], [], linestyle="none", marker=markers.get(stage, "D"), color="#777777", label=f"{stage} stage")
    if any(ch["overlap"] for ch in chs):
        ax.plot([], [], linestyle="none", marker="o", markerfacecolor="white", markeredgecolor="#777777",
                label="hollow: the APIs' spreads overlap")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlim(lo, hi)
    ax.set_ylim(lo, hi)
    c.plain_log(ax.xaxis)
    c.plain_log(ax.yaxis)
    ax.set_aspect("equal")
    gls, vks = [g for g, _ in pairs], [k for _, k in pairs]
    ax.set_xlabel(time_label(gls, "OpenGL time", log=True).replace("\n", ", "))
    ax.set_ylabel(time_label(vks, "Vulkan time", log=True).replace("\n", ", "))
    within = sum(1 for ch in chs if abs(ch["change_pct"]) <= 10)
    vk_faster = sum(1 for ch in chs if ch["change_pct"] < 0)
    noise = sum(1 for ch in chs if ch["overlap"])
    text = (f"{len(pairs)} configurations on both APIs, {within} within ±10%\n"
            f"Vulkan faster in {vk_faster}, OpenGL in {len(pairs) - vk_faster} (below the line: Vulkan faster)")
    if any(ch["overlap"] is not None for ch in chs):
        text += f"\n{noise} of {len(pairs)} differ by less than their spreads (hollow)"
    outside = sorted((ch for ch in chs if abs(ch["change_pct"]) > 10),
                     key=lambda ch: (ch["overlap"] is True, -abs(math.log(1 + ch["change_pct"] / 100))))
    if outside:
        ids = [g["id"] for g, _ in pairs]
        _, short = short_ids(ids) if len(ids) > 1 else ("", {ids[0]: ids[0]})
        by_id = {g["id"].replace("/gl/", "/*/"): g["id"] for g in gls}
        text += "\noutside the band (Vulkan time vs OpenGL time):"
        for ch in outside[:5]:
            name = shorten(short[by_id[ch["id"]]].replace("/gl", ""), 40)
            text += f"\n  {name}: {change_text(ch)}"
        if len(outside) > 5:
            text += f"\n  and {len(outside) - 5} more"
    # beside the axes, not on them: a box over the plot hides the points it is about
    ax.text(1.03, 0.0, text, transform=ax.transAxes, ha="left", va="bottom", fontsize=8, linespacing=1.35,
            multialignment="left",
            bbox=dict(boxstyle="round", facecolor="white", edgecolor="#cccccc"))
    c.finish("gl_vs_vk", fig, ax, "OpenGL vs Vulkan, same configuration",
             "every configuration measured on both APIs (all scenes, sizes, samples)" +
             (f", of the first {MAX_SERIES} of {len(kernels)} kernels (--filter picks others)" if left_out > 0 else ""),
             legend_kw=dict(loc="upper left", bbox_to_anchor=(1.03, 1.0), ncol=1), drawn=gls + vks, extra={"pairs": chs})
