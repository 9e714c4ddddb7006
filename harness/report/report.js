// Builds the gate report (index.html) from the data cavity inlined in
// #gate-data: `gate`, the gate.json written beside the page, and `view`, what
// only the page needs: the order (what fails the gate first), each result's
// label and verdict note as summary.md words them, the images it shows as
// data: URIs by the path gate.json names them, the heat-map's colour scale
// and the benchmark charts. Text goes in through textContent, never as HTML.
'use strict';
(function () {
  const data = JSON.parse(document.getElementById('gate-data').textContent);
  const gate = data.gate, view = data.view;

  // el('td', {class: 'l'}, 'text', child...): an element, its attributes in
  // the order given, then its children (strings become text).
  function el(tag, attrs, ...children) {
    const e = document.createElement(tag);
    for (const [k, v] of Object.entries(attrs || {})) e.setAttribute(k, v);
    for (const c of children) if (c !== null && c !== undefined) e.append(c);
    return e;
  }

  // As the C++ reports print numbers (%.4g); gate.json writes a non-finite
  // metric as 1e300.
  function num(x, digits = 4) {
    if (!Number.isFinite(x) || x >= 1e299) return 'inf';
    return String(Number(x.toPrecision(digits)));
  }

  function image(path, cls) {
    const src = view.images[path];
    return src ? el('img', {class: cls, src: src}) : el('p', {class: 'bad'}, 'missing');
  }

  function controls(failed) {
    const zoom = el('input', {id: 'zoom', type: 'range', min: '1', max: '24', value: '2'});
    zoom.addEventListener('input', () => setZoom(zoom.value));
    const shard = gate.shard[1] > 1 ? ' · shard ' + gate.shard[0] + '/' + gate.shard[1] : '';
    document.getElementById('controls').append(
      el('b', {}, 'Cavity gate'), ' matrix ', el('code', {}, gate.matrix), shard,
      ' · ' + gate.results.length + ' configurations · ',
      // The counts by verdict ("6 failed", "4 passed, 1 changed"), red when
      // any failed: the failures once, not twice.
      el('span', {class: failed ? 'bad' : ''}, view.counts || failed + ' failed'),
      ' · ' + (gate.render_seconds > 0
        ? 'rendered in ' + num(gate.render_seconds, 3) + ' s, judged in ' + num(gate.seconds - gate.render_seconds, 3) + ' s'
        : num(gate.seconds, 3) + ' s') + ' · zoom ', zoom, ' ', el('span', {id: 'zv'}, '2x'));
    // What was judged instead of the committed kernels (--kernel-source).
    for (const r of gate.kernel_sources || [])
      document.getElementById('controls').append(el('div', {class: 'replaced'},
        'kernel source replaced: ', el('code', {}, r.path || 'kernels/' + r.name), ' by ', el('code', {}, r.file), ' (' + r.digest + ')'));
  }

  // Thumbnails of what a passing configuration rendered and its worst
  // numbers: the page stays small enough to open, and the eye goes to the
  // failures.
  function thumbnails(r) {
    const row = el('div', {class: 'row'});
    for (const i of r.images) {
      const caption = i.image + (i.route === 'digest' ? ' · approved digest'
                                 : i.metrics ? ' · max ' + num(i.metrics.max_abs, 2) + ' · SSIM ' + num(i.metrics.ssim, 5) : '');
      row.append(el('figure', {}, el('figcaption', {}, caption), image(i.new_png, 'thumb')));
    }
    return row;
  }

  function metricsTable(i) {
    const table = el('table', {}, el('tr', {}, el('th', {class: 'l'}, 'metric'), el('th', {}, 'value'), el('th', {}, 'tolerance')));
    const m = i.metrics, t = i.tolerance;
    if (!m) return null;   // no image judged by metrics (a baseline missing, an approved digest)
    // upper: the value must stay at or under the tolerance; else at or over it.
    const row = (name, v, tol, upper, unit = '') => {
      const bad = upper ? v > tol : v < tol;
      table.append(el('tr', {}, el('td', {class: 'l'}, name), el('td', {class: bad ? 'bad' : ''}, num(v) + unit),
                      el('td', {}, (upper ? '≤ ' : '≥ ') + num(tol) + unit)));
    };
    row('max abs', m.max_abs, t.max_abs, true);
    row('mean abs', m.mean_abs, t.mean_abs, true);
    row('RMSE', m.rmse, t.rmse, true);
    row('PSNR', m.psnr, t.psnr_min, false, ' dB');
    row('pixels over threshold', 100 * m.over_threshold_share, 100 * t.over_threshold_share, true, '%');
    row('SSIM', m.ssim, t.ssim_min, false);
    if (m.flip_mean >= 0) {
      row('FLIP mean', m.flip_mean, t.flip_mean_max, true);
      row('pixels differing by > ' + num(t.differing_delta) + ' steps', 100 * m.differing_share,
          100 * t.differing_share_max, true, '%');
    }
    if (m.non_finite) table.append(el('tr', {}, el('td', {class: 'l'}, 'non-finite'), el('td', {class: 'bad'}, String(m.non_finite)), el('td', {}, '0')));
    return table;
  }

  // Baseline, new, the heat-map of new - baseline with its scale, a slider
  // between baseline and new, and the metrics against their tolerances.
  function comparison(i) {
    const row = el('div', {class: 'row'});
    const baseline = view.images[i.baseline_png];
    // The reference judged against: the default class's baseline, or the
    // nearest image approved for this device class (from the image store).
    const ref = i.reference && i.reference !== 'default' ? ' (approved ' + i.reference + ')' : '';
    row.append(el('figure', {class: 'zoomable'}, el('figcaption', {}, i.image + ' baseline' + ref), image(i.baseline_png, 'z')));
    row.append(el('figure', {class: 'zoomable'}, el('figcaption', {}, 'new'), image(i.new_png, 'z')));
    const threshold = i.tolerance.pixel_threshold;
    // Signed, saturating at the per-pixel threshold: full colour is a
    // pixel counted over it; blue went darker, orange lighter.
    // The scale only under a heat-map (a missing baseline has none).
    if (view.images[i.diff_png])
      row.append(el('figure', {class: 'zoomable'}, el('figcaption', {}, 'new - baseline'), image(i.diff_png, 'z'),
                    el('div', {class: 'scale', style: 'background:' + view.heat_scale}),
                    el('div', {class: 'scalelabels'}, el('span', {}, '≤ -' + num(threshold) + ' darker'), el('span', {}, '0'),
                       el('span', {}, '≥ +' + num(threshold) + ' lighter'))));
    if (baseline) {
      const top = el('div', {class: 'top'}, image(i.baseline_png, 'z'));
      const slider = el('input', {type: 'range', min: '0', max: '100', value: '50'});
      slider.addEventListener('input', () => { top.style.width = slider.value + '%'; });
      row.append(el('figure', {class: 'zoomable'}, el('figcaption', {}, 'baseline ◀ slider ▶ new'),
                    el('div', {class: 'cmp'}, image(i.new_png, 'z'), top), slider));
    }
    const table = metricsTable(i);
    if (table) row.append(table);
    const out = [row];
    for (const f of i.failures) out.push(el('div', {class: 'bad'}, i.image + ': ' + f));
    return out;
  }

  function timings(r) {
    const table = el('table', {}, el('tr', {}, el('th', {class: 'l'}, 'pass'), el('th', {}, 'median ms'),
                                    el('th', {}, '95% interval of the median'), el('th', {}, 'budget ms'),
                                    el('th', {}, 'clock')));
    const interval = (t) => t.ci_low_ms === undefined || t.ci_low_ms === null ? 'too few frames'
                                                                               : num(t.ci_low_ms) + ' to ' + num(t.ci_high_ms);
    // A software renderer's timestamps are the host's clock (advisory: its
    // budgets are reported, not enforced).
    const clock = (t) => t.clock === 'wall' ? 'wall clock' + (t.advisory ? ', CPU renderer' : '')
                                            : t.advisory ? 'host timestamps, CPU renderer' : 'GPU timestamps';
    for (const t of r.timings)
      table.append(el('tr', {}, el('td', {class: 'l'}, t.pass), el('td', {class: t.passed ? '' : 'bad'}, num(t.median_ms)),
                      el('td', {}, interval(t)),
                      el('td', {}, t.budget_ms === null ? 'none for this device' : num(t.budget_ms)), el('td', {}, clock(t))));
    return table;
  }

  function kindOf(r) { return r.fatal ? 'fail' : r.verdict === 'pass' ? 'pass' : 'noted'; }

  // One cell a configuration, in matrix order, coloured by verdict; a
  // cell's title is its id and verdict, and a click goes to its card.
  function overview() {
    const grid = el('div', {class: 'grid'});
    gate.results.forEach((r, k) => {
      const kind = r.error ? 'error' : kindOf(r);
      grid.append(el('a', {class: 'cell ' + kind, href: '#cfg' + view.results[k].card, title: view.results[k].label + ': ' + r.verdict}));
    });
    const legend = el('div', {class: 'legend'}, 'Overview, one cell a configuration:');
    for (const [kind, text] of [['pass', 'pass'], ['fail', 'fail'], ['noted', 'reported'], ['error', 'error']])
      legend.append(el('span', {class: 'cell ' + kind}), text);
    document.getElementById('overview').append(legend, grid);
  }

  function configuration(r, v, k) {
    const kind = kindOf(r);
    const div = el('div', {id: 'cfg' + k, class: 'cfg ' + kind, 'data-id': r.id, 'data-repetition': String(r.repetition), 'data-verdict': r.verdict},
                   el('h2', {}, v.label, el('span', {class: 'badge'}, r.verdict === 'fail' ? 'FAIL' : r.verdict)));
    if (r.error) div.append(el('p', {class: 'bad'}, r.error));
    // The other API failed with the same numbers: one card for both.
    for (const same of v.same) div.append(el('p', {class: 'same'}, 'the same failure, every metric within 1%, on ', el('code', {}, same)));
    // A note of a verdict that did not fail (changed, flaky, expected) is
    // drawn in the reported colour, not the failures'.
    if (v.note) div.append(el('p', {class: r.fatal ? 'bad' : 'note'}, v.note));
    if (!r.deterministic) div.append(el('p', {class: 'bad'}, 'not bit-identical across two frames on this device'));
    // A configuration that changed within tolerance shows what changed, as a failure does.
    if (r.passed && r.verdict !== 'changed') div.append(thumbnails(r));
    else for (const i of r.images) {
      // A known-bad digest: nothing was compared, the approval says why.
      if (i.route === 'negative') div.append(el('div', {class: 'row'}, el('figure', {}, el('figcaption', {}, i.image + ' · known bad digest'),
                                                                        image(i.new_png, 'thumb'))),
                                           el('div', {class: 'bad'}, i.image + ': ' + i.failures.join('; ')));
      else if (i.route === 'digest') div.append(el('div', {}, i.image + ': approved digest (' + i.approval + ')'));
      // Within its tolerances in a configuration that failed on another
      // image: its numbers, and the new image where its file travelled.
      else if (i.passed && !view.images[i.diff_png]) div.append(el('div', {class: 'row'},
                                       el('figure', {}, el('figcaption', {}, i.image + ' · passed' +
                                                           (i.approval.endsWith('judged where it was rendered')
                                                            ? ' where it was rendered' : '')),
                                          view.images[i.new_png] ? image(i.new_png, 'thumb') : null),
                                       metricsTable(i)));
      else div.append(...comparison(i));
    }
    if (r.timings.length) div.append(timings(r));
    return div;
  }

  function charts() {
    if (!view.charts.length) return;
    const row = el('div', {class: 'row'});
    for (const c of view.charts) row.append(el('figure', {}, el('figcaption', {}, c.name), el('img', {width: '640', src: c.src})));
    document.getElementById('charts').append(el('h1', {}, 'Benchmark charts'), row);
  }

  function setZoom(z) {
    document.getElementById('zv').textContent = z + 'x';
    // z times a width of at most 320 px: a 160x90 image at 2x is 320 px,
    // a 1920x1080 one 640 px (and its pixels at 12x and up).
    for (const img of document.querySelectorAll('img.z'))
      if (img.naturalWidth) img.style.width = Math.min(img.naturalWidth, 320) * z + 'px';
  }

  const failed = gate.results.filter((r) => r.fatal).length;
  const changed = gate.results.filter((r) => r.verdict === 'changed').length;
  document.title = 'Cavity gate ' + gate.matrix + ': ' + (failed ? failed + ' failed' : 'passed') +
                   (changed ? ', ' + changed + ' changed' : '');
  controls(failed);
  const results = document.getElementById('results');
  for (const e of gate.backend_errors) results.append(el('p', {class: 'bad'}, 'backend could not start: ' + e));
  overview();
  for (const k of view.order) results.append(configuration(gate.results[k], view.results[k], k));
  charts();
  window.addEventListener('load', () => setZoom(document.getElementById('zoom').value));
})();
