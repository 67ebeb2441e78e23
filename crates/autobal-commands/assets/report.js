// autobal report: draws each figure from the JSON embedded beside it, with the Plotly.js
// shipped in this folder (no network). Figures are drawn as they come near the screen;
// autobalReport.renderAll() draws every one (used before printing and by the browser test).
(function () {
  'use strict';
  var state = { total: 0, rendered: 0, errors: [], points: {} };
  window.autobalReport = state;
  var divs = Array.prototype.slice.call(document.querySelectorAll('div.plot[data-fig]'));
  state.total = divs.length;
  function fail(msg) {
    state.errors.push(msg);
    console.error(msg);
  }
  if (typeof Plotly === 'undefined') {
    fail('autobal report: plotly-cartesian.min.js did not load; the static SVG figures are shown');
    state.renderAll = function () { return Promise.resolve(state); };
    return;
  }
  // finite data points of a trace (what the page holds of a figure's data)
  function count(t) {
    var n = 0, i, j;
    if (t.type === 'heatmap') {
      for (i = 0; i < (t.z || []).length; i++) {
        for (j = 0; j < t.z[i].length; j++) { if (t.z[i][j] !== null && isFinite(t.z[i][j])) { n++; } }
      }
      return n;
    }
    if (t.xaxis === 'x2') { return 0; }
    for (i = 0; i < (t.x || []).length; i++) {
      if (t.x[i] !== null && t.y[i] !== null && isFinite(t.x[i]) && isFinite(t.y[i])) { n++; }
    }
    return n;
  }
  function draw(div) {
    if (div._drawn) { return div._drawn; }
    var id = div.getAttribute('data-fig');
    var fig;
    try {
      fig = JSON.parse(document.getElementById('data-' + id).textContent);
    } catch (e) {
      fail('autobal report: figure ' + id + ': its data cannot be read: ' + e);
      div._drawn = Promise.resolve();
      return div._drawn;
    }
    fig.layout.height = 500;
    fig.layout.autosize = true;
    var config = {
      responsive: true,
      displaylogo: false,
      toImageButtonOptions: { format: 'svg', filename: id },
      modeBarButtonsToAdd: [{
        name: 'Download plot as PNG',
        icon: Plotly.Icons.camera,
        click: function (gd) { Plotly.downloadImage(gd, { format: 'png', filename: id, scale: 2 }); }
      }]
    };
    div._drawn = Plotly.newPlot(div, fig.data, fig.layout, config).then(function (gd) {
      var img = div.querySelector('img.fallback');
      if (img) { img.parentNode.removeChild(img); }
      var n = 0;
      gd.data.forEach(function (t) { n += count(t); });
      state.points[id] = n;
      div.setAttribute('data-drawn-points', String(n));
      state.rendered++;
      var f = fig.layout.meta && fig.layout.meta.x2factor;
      if (f) {
        // the second speed axis (rpm) follows the first through zoom and pan
        gd.on('plotly_relayout', function (ev) {
          var keys = Object.keys(ev || {});
          if (!keys.some(function (k) { return k.indexOf('xaxis.') === 0; })) { return; }
          var r = gd._fullLayout.xaxis.range;
          Plotly.relayout(gd, { 'xaxis2.range': [r[0] * f, r[1] * f] });
        });
      }
    }, function (e) {
      fail('autobal report: figure ' + id + ' could not be drawn: ' + e);
    });
    return div._drawn;
  }
  state.renderAll = function () {
    return Promise.all(divs.map(draw)).then(function () { return state; });
  };
  if ('IntersectionObserver' in window) {
    var io = new IntersectionObserver(function (entries) {
      entries.forEach(function (e) {
        if (e.isIntersecting) { io.unobserve(e.target); draw(e.target); }
      });
    }, { rootMargin: '800px 0px' });
    divs.forEach(function (d) { io.observe(d); });
  } else {
    state.renderAll();
  }
  window.addEventListener('beforeprint', function () { state.renderAll(); });
})();
