// Builds the run page from the data `cavity run` inlined: a chart per
// kernel, then a contact sheet of every configuration's images.
(function () {
  const data = JSON.parse(document.getElementById('run-data').textContent);
  const configs = data.configurations;
  const el = (tag, cls, text) => {
    const e = document.createElement(tag);
    if (cls) e.className = cls;
    if (text !== undefined) e.textContent = text;
    return e;
  };
  const devices = [...new Set(configs.map(c => c.api + ' ' + c.device))].join(', ');
  document.getElementById('meta').textContent =
    configs.length + ' configurations on ' + devices + ' · commit ' + data.git_commit + ' · ' + data.created_utc +
    ' · ' + data.command;

  const byKernel = new Map();
  for (const c of configs) {
    if (!byKernel.has(c.kernel)) byKernel.set(c.kernel, []);
    byKernel.get(c.kernel).push(c);
  }
  // The configuration's id without its kernel and API (those are the chart
  // and the series): every parameter the id names stays, so configurations
  // that differ only in a kernel's own parameter get a bar each.
  const parts = c => c.id.split('/').filter((part, i) => i !== 1 && part !== c.api);
  const label = c => parts(c).join(' ');
  const palette = ['#3465a4', '#cc0000', '#4e9a06', '#c4a000', '#75507b', '#ce5c00', '#06989a', '#555753'];

  // Whiskers from each bar's min to its p90 (Chart.js has no error bars).
  const whiskers = {
    id: 'whiskers',
    afterDatasetsDraw(chart) {
      const ctx = chart.ctx;
      const x = chart.scales.x;
      chart.data.datasets.forEach((ds, i) => {
        const meta = chart.getDatasetMeta(i);
        if (meta.hidden) return;
        meta.data.forEach((bar, j) => {
          const s = ds.stats[j];
          if (!s) return;
          ctx.save();
          ctx.strokeStyle = '#1d2430';
          ctx.lineWidth = 1;
          const y = bar.y, lo = x.getPixelForValue(s.min), hi = x.getPixelForValue(s.p90);
          ctx.beginPath();
          ctx.moveTo(lo, y); ctx.lineTo(hi, y);
          ctx.moveTo(lo, y - 3); ctx.lineTo(lo, y + 3);
          ctx.moveTo(hi, y - 3); ctx.lineTo(hi, y + 3);
          ctx.stroke();
          ctx.restore();
        });
      });
    }
  };

  const charts = document.getElementById('charts');
  for (const [kernel, list] of byKernel) {
    // A bar's label is what sets it apart; what every bar shares goes above.
    const shared = parts(list[0]).filter(p => list.every(c => parts(c).includes(p)));
    const barLabel = c => parts(c).filter(p => !shared.includes(p)).join(' ') || label(c);
    const labels = [...new Set(list.map(barLabel))].sort((a, b) => a.localeCompare(b, 'en', { numeric: true }));
    const series = [...new Set(list.map(c => c.api))].sort();
    const clocks = [...new Set(list.map(c => c.api + ': ' + c.clock))].sort().join(', ');
    const card = el('div', 'card chart');
    card.appendChild(el('div', 'title', kernel + (shared.length > 1 || labels.length > 1 ? ' · ' + shared.join(' ') : '')));
    card.appendChild(el('div', 'sub', 'AO pipeline, ms (G-buffer left out) · ' + clocks));
    const plot = el('div', 'plot');
    plot.style.height = (60 + labels.length * series.length * 16) + 'px';
    const canvas = el('canvas');
    plot.appendChild(canvas);
    card.appendChild(plot);
    charts.appendChild(card);
    const datasets = series.slice(0, palette.length).map((api, i) => {
      const rows = labels.map(l => list.find(c => c.api === api && barLabel(c) === l));
      return {
        label: api, backgroundColor: palette[i] + 'b0', borderColor: palette[i], borderWidth: 1,
        data: rows.map(c => (c ? c.pipeline.median : null)), stats: rows.map(c => (c ? c.pipeline : null))
      };
    });
    new Chart(canvas, {
      type: 'bar',
      data: { labels, datasets },
      options: {
        indexAxis: 'y', animation: false, maintainAspectRatio: false,
        // The axis reaches the whiskers' ends (the 90th percentiles), not
        // only the bars' medians.
        scales: { x: { beginAtZero: true, suggestedMax: Math.max(0, ...datasets.flatMap(d => d.stats.map(s => (s ? s.p90 : 0)))),
                       title: { display: true, text: 'ms' } },
                  y: { ticks: { autoSkip: false } } },
        plugins: { legend: { position: 'top' } }
      },
      plugins: [whiskers]
    });
  }

  // The contact sheet: the AO and its blur first, then the rest by name.
  const order = ['ao', 'ao_blur', 'color', 'normal'];
  const rank = n => (order.indexOf(n) < 0 ? order.length : order.indexOf(n));
  const sheet = document.getElementById('sheet');
  for (const [kernel, list] of byKernel) {
    sheet.appendChild(el('h3', null, kernel));
    const row = el('div', 'sheet');
    for (const c of [...list].sort((a, b) => (a.id < b.id ? -1 : 1))) {
      const card = el('div', 'card config');
      card.dataset.id = c.id;
      card.appendChild(el('div', 'title', label(c) + ' ' + c.api));
      card.appendChild(el('div', 'sub', 'pipeline ' + c.pipeline.median.toFixed(3) + ' ms, frame ' +
                                         c.frame.median.toFixed(3) + ' ms · ' + c.clock));
      const images = el('div', 'images');
      const names = Object.keys(c.images).sort((a, b) => rank(a) - rank(b) || (a < b ? -1 : 1));
      for (const name of names) {
        const fig = el('figure');
        const link = el('a');
        link.href = c.images[name];
        const img = el('img');
        img.src = c.images[name];
        img.alt = c.id + ' ' + name;
        link.appendChild(img);
        fig.appendChild(link);
        fig.appendChild(el('figcaption', null, name));
        images.appendChild(fig);
      }
      card.appendChild(images);
      row.appendChild(card);
    }
    sheet.appendChild(row);
  }
})();
