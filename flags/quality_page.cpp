#include "quality_page.h"
#include "core/chart_library.h"
#include "core/digest.h"
#include "images/metrics.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace cavity::flags {

namespace {

unsigned char byte(double v) { return (unsigned char)std::lround(std::clamp(v, 0.0, 1.0) * 255.0); }

// The AO as grey bytes; off the surface (the truth's mask) a dark grey.
std::string greyBytes(const core::HostImage& ao, const core::HostImage& surface) {
    std::string out;
    out.reserve(size_t(ao.width) * ao.height);
    for (int y = 0; y < ao.height; ++y)
        for (int x = 0; x < ao.width; ++x) out += char(surface.at(x, y) > 0 ? byte(ao.at(x, y, 0)) : 40);
    return out;
}

// AO - truth through the gate's diverging map at kErrorMapScale: blue where
// the kernel is darker than the truth (too much occlusion), orange where it
// is lighter (too little); off the surface a dark grey.
std::string errorBytes(const core::HostImage& ao, const measure::GroundTruth& truth) {
    std::string out;
    out.reserve(size_t(ao.width) * ao.height * 3);
    for (int y = 0; y < ao.height; ++y)
        for (int x = 0; x < ao.width; ++x) {
            if (truth.surface.at(x, y) == 0) {
                out.append(3, char(40));
                continue;
            }
            const auto c = images::metrics::diffColor((double(ao.at(x, y, 0)) - truth.ao.at(x, y, 0)) / kErrorMapScale);
            for (float v : c) out += char(byte(v));
        }
    return out;
}

std::string colourScale() {
    std::string g = "linear-gradient(to right";
    for (int k = -8; k <= 8; ++k) {
        const auto c = images::metrics::diffColor(k / 8.0);
        g += ",rgb(" + std::to_string(byte(c[0])) + "," + std::to_string(byte(c[1])) + "," + std::to_string(byte(c[2])) + ")";
    }
    return g + ")";
}

constexpr const char* kPage = R"(<!doctype html>
<html><head><meta charset="utf-8"><title>Cavity quality</title>
<style>
body{background:#1e1f22;color:#ddd;font:13px sans-serif;margin:16px}
h1{font-size:18px} h2{font-size:15px;margin-top:24px} table{border-collapse:collapse;margin:8px 0}
td,th{padding:2px 8px;border-bottom:1px solid #333;text-align:right} td.l,th.l{text-align:left}
.tie{color:#f0b429} figure{display:inline-block;margin:4px 8px 8px 0;vertical-align:top}
figcaption{font-size:11px;color:#aaa;max-width:330px} canvas{image-rendering:pixelated;display:block}
.scale{height:10px;width:320px} .labels{display:flex;justify-content:space-between;width:320px;font-size:11px;color:#aaa}
.replaced{color:#f0b429}
</style></head><body>
<h1>Cavity quality: each AO kernel against the ray-traced ground truth</h1>
<div id="head"></div><div id="scenes"></div>
<script type="application/json" id="quality-data">@DATA@</script>
<script>
'use strict';
(function () {
  const data = JSON.parse(document.getElementById('quality-data').textContent);
  const doc = data.doc, maps = data.maps;
  function el(tag, attrs, ...kids) {
    const e = document.createElement(tag);
    for (const [k, v] of Object.entries(attrs || {})) e.setAttribute(k, v);
    for (const c of kids) if (c !== null && c !== undefined) e.append(c);
    return e;
  }
  function num(x) { return Number(x).toFixed(4); }
  // A canvas from base64 bytes: 1 (grey) or 3 (RGB) a pixel, drawn at 2x.
  function picture(b64, w, h, channels, id) {
    const bytes = Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
    const c = el('canvas', {width: String(w), height: String(h), id: id});
    c.style.width = 2 * w + 'px';
    const img = c.getContext('2d').createImageData(w, h);
    for (let i = 0; i < w * h; ++i) {
      for (let k = 0; k < 3; ++k) img.data[4 * i + k] = bytes[channels * i + (channels === 3 ? k : 0)];
      img.data[4 * i + 3] = 255;
    }
    c.getContext('2d').putImageData(img, 0, 0);
    return c;
  }
  const head = document.getElementById('head');
  head.append(el('p', {}, doc.width + 'x' + doc.height + ', ' + doc.resolution + ' resolution, ' + doc.backend + ' on ' +
                 doc.device + ', the truth from ' + doc.rays + ' rays a pixel, reach ' + doc.reach +
                 (doc.radius !== null ? ' (R = ' + doc.radius + ')' : '') + ', blur ' + doc.blur + '.'));
  for (const r of doc.kernel_sources)
    head.append(el('p', {class: 'replaced'}, 'kernel source replaced: kernels/' + r.name + ' by ' + r.file +
                   ' (' + r.digest + '): every row measures the edit'));
  head.append(el('p', {}, 'Error maps: kernel AO minus the truth, on surface pixels, every map on one scale:'),
              el('div', {class: 'scale', style: 'background:' + data.scale}),
              el('div', {class: 'labels'}, el('span', {}, '-' + data.range + ' darker (too much occlusion)'),
                 el('span', {}, '0'), el('span', {}, '+' + data.range + ' lighter')));
  const scenes = document.getElementById('scenes');
  for (const scene of Object.keys(maps)) {
    const m = maps[scene];
    const rows = doc.rows.filter((r) => r.scene === scene).sort((a, b) => a.mae - b.mae);
    const table = el('table', {}, el('tr', {}, el('th', {class: 'l'}, 'kernel'), el('th', {}, 'samples'),
                                     el('th', {}, 'MAE'), el('th', {}, '95% interval'), el('th', {class: 'l'}, '')));
    // tied_with: the better row whose MAE this one's cannot be told from
    // (a paired bootstrap of the difference holds 0).
    for (const r of rows)
      table.append(el('tr', {}, el('td', {class: 'l'}, r.kernel + (r.edited ? ' (edited; committed: ' + num(r.committed_mae) + ')' : '')),
                      el('td', {}, String(r.samples)), el('td', {}, num(r.mae)),
                      el('td', {}, num(r.mae_low) + ' to ' + num(r.mae_high)),
                      el('td', {class: 'l tie'}, r.tied_with ? 'cannot be told from ' + r.tied_with : '')));
    const figs = el('div', {});
    figs.append(el('figure', {}, el('figcaption', {}, 'ground truth'), picture(m.truth, m.width, m.height, 1, 'truth-' + scene)));
    for (const r of rows) {
      const key = r.kernel + '/n' + r.samples;
      const k = m.kernels[key];
      figs.append(el('figure', {class: 'kernel', 'data-kernel': key},
                     el('figcaption', {}, key + ' · MAE ' + num(r.mae) + ' (' + num(r.mae_low) + ' to ' + num(r.mae_high) + ')'),
                     picture(k.ao, m.width, m.height, 1, 'ao-' + scene + '-' + key),
                     picture(k.error, m.width, m.height, 3, 'error-' + scene + '-' + key)));
    }
    scenes.append(el('h2', {}, 'scene ' + scene), table, figs);
  }
})();
</script></body></html>
)";

}  // namespace

std::string qualityPage(const nlohmann::json& doc, const std::vector<measure::QualityRow>& rows) {
    nlohmann::json maps = nlohmann::json::object();
    for (const auto& r : rows) {
        if (!r.ao || !r.truth) continue;
        auto& m = maps[r.scene];
        if (m.is_null()) {
            m = {{"width", r.ao->width}, {"height", r.ao->height}, {"kernels", nlohmann::json::object()},
                 {"truth", core::base64(greyBytes(r.truth->ao, r.truth->surface))}};
        }
        m["kernels"][r.kernel + "/n" + std::to_string(r.samples)] = {
            {"ao", core::base64(greyBytes(*r.ao, r.truth->surface))}, {"error", core::base64(errorBytes(*r.ao, *r.truth))}};
    }
    const nlohmann::json data = {{"doc", doc}, {"maps", maps}, {"scale", colourScale()}, {"range", kErrorMapScale}};
    std::string page = kPage;
    page.replace(page.find("@DATA@"), 6,
                 core::scriptSafeJson(data.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace)));
    return page;
}

}  // namespace cavity::flags
