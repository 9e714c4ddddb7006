// The history page: one Chart.js chart per series (Debian's libjs-chart.js,
// inlined by the build). Median line, the 95% interval of each commit's
// median as a band, change points as a dashed line at the step with its
// change; hover for the commit; wheel to zoom about the pointer, drag to
// zoom to a range, double-click or the button to reset.
(function () {
  'use strict';
  const data = JSON.parse(document.getElementById('history-data').textContent);
  const meta = document.getElementById('meta');
  meta.textContent = data.series.length + ' series from ' + data.db + ', ' + data.generated +
    '; change points: E-divisive, alpha ' + data.alpha + ', min change ' + data.min_change_pct +
    '%. Wheel: zoom about the pointer; drag: zoom to a range; double-click: reset.';
  const grid = document.getElementById('charts');
  if (!data.series.length) {
    grid.innerHTML = '<p class="empty">No series matches the filters.</p>';
    return;
  }
  const fmt = (v) => (v >= 10 ? v.toFixed(2) : v >= 1 ? v.toFixed(3) : v.toPrecision(3));
  const short = (c) => c.slice(0, 8);

  // The step of each change point: a dashed line between the last commit
  // before it and the first after, its change written beside the line's top
  // (labels of close steps alternate between two rows).
  const stepLines = {
    id: 'stepLines',
    afterDatasetsDraw(chart) {
      const steps = chart.options.plugins.stepLines.steps || [];
      const { ctx, chartArea, scales } = chart;
      ctx.save();
      steps.forEach((s, i) => {
        const x = scales.x.getPixelForValue(s.index - 0.5);
        if (x < chartArea.left || x > chartArea.right) return;
        const colour = s.slower ? '#c0392b' : '#1e8449';
        ctx.strokeStyle = colour;
        ctx.setLineDash([5, 4]);
        ctx.lineWidth = 1.5;
        ctx.beginPath();
        ctx.moveTo(x, chartArea.top);
        ctx.lineTo(x, chartArea.bottom);
        ctx.stroke();
        ctx.setLineDash([]);
        ctx.fillStyle = colour;
        ctx.font = '600 11px system-ui, sans-serif';
        const text = (s.change_pct > 0 ? '+' : '') + s.change_pct.toFixed(1) + '%';
        const w = ctx.measureText(text).width;
        const left = x + 4 + w > chartArea.right ? x - 4 - w : x + 4;
        ctx.fillText(text, left, chartArea.top + 12 + (i % 2) * 14);
      });
      ctx.restore();
    },
  };

  function zoomTo(chart, lo, hi) {
    const n = chart.data.datasets[2].data.length;
    lo = Math.max(-0.5, lo);
    hi = Math.min(n - 0.5, hi);
    if (hi - lo < 1) return;
    chart.options.scales.x.min = lo;
    chart.options.scales.x.max = hi;
    chart.update('none');
  }

  function resetZoom(chart) {
    const n = chart.data.datasets[2].data.length;
    chart.options.scales.x.min = -0.5;
    chart.options.scales.x.max = n - 0.5;
    chart.update('none');
  }

  function addZoom(chart, canvas, sel) {
    canvas.addEventListener('wheel', (e) => {
      e.preventDefault();
      const x = chart.scales.x;
      const at = x.getValueForPixel(e.offsetX);
      const f = e.deltaY < 0 ? 0.8 : 1.25;
      zoomTo(chart, at - (at - x.min) * f, at + (x.max - at) * f);
    }, { passive: false });
    let from = null;
    canvas.addEventListener('mousedown', (e) => { from = e.offsetX; });
    canvas.addEventListener('mousemove', (e) => {
      if (from === null) return;
      sel.style.display = 'block';
      sel.style.left = Math.min(from, e.offsetX) + 'px';
      sel.style.width = Math.abs(e.offsetX - from) + 'px';
    });
    window.addEventListener('mouseup', (e) => {
      if (from === null) return;
      const rect = canvas.getBoundingClientRect();
      const to = e.clientX - rect.left;
      sel.style.display = 'none';
      if (Math.abs(to - from) > 5) {
        const x = chart.scales.x;
        zoomTo(chart, x.getValueForPixel(Math.min(from, to)), x.getValueForPixel(Math.max(from, to)));
      }
      from = null;
    });
    canvas.addEventListener('dblclick', () => resetZoom(chart));
  }

  function card(s) {
    const div = document.createElement('div');
    div.className = 'card';
    const steps = s.change_points.map((c) =>
      '<span class="' + (c.slower ? 'slower' : 'faster') + '">' + short(c.commit) + ' ' +
      (c.change_pct > 0 ? '+' : '') + c.change_pct.toFixed(1) + '%</span>').join(', ');
    div.innerHTML = '<h2></h2><div class="sub"></div><div class="plot"><canvas></canvas><div class="sel"></div></div>';
    div.querySelector('h2').textContent = s.id + '  ' + s.pass;
    div.querySelector('.sub').innerHTML = '';
    div.querySelector('.sub').append(s.device + ' \u00b7 ' + s.points.length + ' commits \u00b7 ');
    const cp = document.createElement('span');
    cp.innerHTML = s.change_points.length ? 'change points: ' + steps : 'no change point';
    div.querySelector('.sub').append(cp);
    const reset = document.createElement('button');
    reset.textContent = 'reset zoom';
    div.querySelector('.sub').append(reset);
    grid.append(div);
    return { div, reset };
  }

  function draw(s) {
    const { div, reset } = card(s);
    const canvas = div.querySelector('canvas');
    const xy = (key) => s.points.map((p, i) => ({ x: i, y: p[key] }));
    const chart = new Chart(canvas, {
      type: 'line',
      data: {
        datasets: [
          { label: '_lo', data: xy('lo'), borderWidth: 0, pointRadius: 0, fill: false },
          { label: '95% interval of the median', data: xy('hi'), borderWidth: 0, pointRadius: 0, fill: '-1',
            backgroundColor: 'rgba(52, 101, 164, 0.22)' },
          { label: 'median', data: xy('median'), borderColor: '#3465a4', backgroundColor: '#3465a4', borderWidth: 2,
            pointRadius: 3, pointHoverRadius: 6, tension: 0 },
          { label: 'change point', type: 'scatter', data: s.change_points.map((c) => ({ x: c.index, y: s.points[c.index].median })),
            pointStyle: 'triangle', pointRadius: 8, pointHoverRadius: 9, borderColor: '#7a1f14',
            backgroundColor: s.change_points.map((c) => (c.slower ? '#e74c3c' : '#27ae60')) },
        ],
      },
      options: {
        animation: false,
        maintainAspectRatio: false,
        parsing: true,
        interaction: { mode: 'nearest', axis: 'x', intersect: false },
        scales: {
          x: { type: 'linear', min: -0.5, max: s.points.length - 0.5,
               title: { display: true, text: 'commit (oldest left)' },
               ticks: { stepSize: 1, autoSkip: true, autoSkipPadding: 8, maxRotation: 40, minRotation: 0, precision: 0,
                        callback: (v) => (Number.isInteger(v) && s.points[v] ? short(s.points[v].commit) : '') } },
          y: { grace: '8%', title: { display: true, text: s.y_label }, ticks: { callback: (v) => fmt(v) } },
        },
        plugins: {
          legend: { labels: { boxWidth: 14, filter: (item, d) => !item.text.startsWith('_') &&
                                                    d.datasets[item.datasetIndex].data.length > 0 } },
          stepLines: { steps: s.change_points },
          tooltip: {
            filter: (item) => item.datasetIndex === 2,
            callbacks: {
              title: (items) => { const p = s.points[items[0].parsed.x]; return p.commit + '  ' + p.date; },
              label: (item) => {
                const p = s.points[item.parsed.x];
                return ['median ' + fmt(p.median) + ' ms', '95% interval ' + fmt(p.lo) + ' .. ' + fmt(p.hi) + ' ms' +
                        (p.covers_less ? ' (min..max: too few repetitions for 95%)' : ''),
                        'n ' + p.n + ' in ' + p.runs + (p.runs === 1 ? ' run' : ' runs') + ', min ' + fmt(p.min) + ', max ' + fmt(p.max)];
              },
            },
          },
        },
      },
      plugins: [stepLines],
    });
    addZoom(chart, canvas, div.querySelector('.sel'));
    reset.addEventListener('click', () => resetZoom(chart));
  }

  data.series.forEach(draw);
  document.body.setAttribute('data-charts-drawn', String(data.series.length));
})();
