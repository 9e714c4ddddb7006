"""gl_vs_vk: OpenGL time against Vulkan time for the same configuration (log-log, the
±10% band around y = x).

draw(c) draws it on a plotting.Canvas (or says on stderr why it is skipped).
"""

import math

from .labels import short_ids, shorten

NAME = "gl_vs_vk"


def api_pairs(records):
    """[(gl record, vk record)] for configurations measured on both APIs."""
    by = {}
    for r in records:
        by[(r["scene"], r["kernel"], r["samples"], r["blur"], r["res"], r["size"], r["stage"], r["api"])] = r
    out = []
    for k, r in sorted(by.items(), key=lambda kv: kv[1]["id"]):
        if k[-1] == "gl" and k[:-1] + ("vk",) in by:
            out.append((r, by[k[:-1] + ("vk",)]))
    return out


def draw(c):
    pairs = api_pairs(c.records)
    if not pairs:
        return c.skip("gl_vs_vk", "no configuration measured on both OpenGL and Vulkan")
    fig, ax = c.figure(width=7.0, height=7.0)
    vals = [v for g, k in pairs for v in (g["ms"], k["ms"])]
    lo, hi = min(vals) / 1.6, max(vals) * 1.6
    xs = [lo * (hi / lo) ** (i / 100) for i in range(101)]
    ax.fill_between(xs, [x * 0.9 for x in xs], [x * 1.1 for x in xs], color="#999999", alpha=0.22,
                    label="±10% band", zorder=1)
    ax.plot(xs, xs, color="#555555", linewidth=1, label="y = x (same time)", zorder=2)
    markers = {"compute": "o", "fragment": "^"}
    seen = set()
    for g, k in pairs:
        kern, stage = g["kernel"], g["stage"]
        ax.scatter(g["ms"], k["ms"], s=46, color=c.kcolor.get(kern, "#333333"),
                   marker=markers.get(stage, "D"), edgecolor="white", linewidth=0.6, zorder=3)
        seen.add((kern, stage))
    for kern in sorted({k for k, _ in seen}):
        ax.plot([], [], linestyle="none", marker="o", color=c.kcolor.get(kern), label=kern)
    for stage in sorted({s for _, s in seen}):
        ax.plot([], [], linestyle="none", marker=markers.get(stage, "D"), color="#777777", label=f"{stage} stage")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlim(lo, hi)
    ax.set_ylim(lo, hi)
    c.plain_log(ax.xaxis)
    c.plain_log(ax.yaxis)
    ax.set_aspect("equal")
    ax.set_xlabel("OpenGL GPU time (ms, log scale)")
    ax.set_ylabel("Vulkan GPU time (ms, log scale)")
    within = sum(1 for g, k in pairs if abs(k["ms"] / g["ms"] - 1) <= 0.10)
    vk_faster = sum(1 for g, k in pairs if k["ms"] < g["ms"])
    text = (f"{len(pairs)} configurations on both APIs, {within} within ±10%\n"
            f"Vulkan faster in {vk_faster}, OpenGL in {len(pairs) - vk_faster} (below the line: Vulkan faster)")
    outside = sorted(((k["ms"] / g["ms"], g) for g, k in pairs if abs(k["ms"] / g["ms"] - 1) > 0.10),
                     key=lambda t: -abs(math.log(t[0])))
    if outside:
        ids = [g["id"] for g, _ in pairs]
        _, short = short_ids(ids) if len(ids) > 1 else ("", {ids[0]: ids[0]})
        text += "\noutside the band (Vulkan time vs OpenGL time):"
        for ratio, g in outside[:5]:
            text += f"\n  {shorten(short[g['id']].replace('/gl', ''), 40)}: {(ratio - 1) * 100:+.1f}%"
        if len(outside) > 5:
            text += f"\n  and {len(outside) - 5} more"
    ax.text(0.98, 0.03, text, transform=ax.transAxes, ha="right", va="bottom", fontsize=8, linespacing=1.35, multialignment="left",
            bbox=dict(boxstyle="round", facecolor="white", edgecolor="#cccccc"))
    c.finish("gl_vs_vk", fig, ax, "OpenGL vs Vulkan, same configuration",
             "every configuration measured on both APIs (all scenes, sizes, samples)",
             legend_kw=dict(loc="upper left"))
