// millpath report viewer: pan/zoom, level selector, playback along the planned timing.
// Inlined into the report by html.rs; no network, no libraries.
(function () {
  'use strict';
  // Position at time t by linear interpolation between the samples around t.
  function positionAt(traj, t) {
    var n = traj.length;
    if (n === 0) { return null; }
    if (t <= traj[0][0]) { return traj[0]; }
    if (t >= traj[n - 1][0]) { return traj[n - 1]; }
    var lo = 0, hi = n - 1;
    while (hi - lo > 1) {
      var mid = (lo + hi) >> 1;
      if (traj[mid][0] <= t) { lo = mid; } else { hi = mid; }
    }
    var a = traj[lo], b = traj[hi];
    var u = b[0] > a[0] ? (t - a[0]) / (b[0] - a[0]) : 0;
    return [t, a[1] + u * (b[1] - a[1]), a[2] + u * (b[2] - a[2]), a[3] + u * (b[3] - a[3])];
  }

  function setup(root) {
    var svg = root.querySelector('.mp-canvas svg');
    var data = root.querySelector('.mp-trajectory');
    var traj = data ? JSON.parse(data.textContent) : [];
    var slider = root.querySelector('.mp-time');
    var readout = root.querySelector('.mp-readout');
    var tool = svg ? svg.querySelector('.mp-tool') : null;
    var select = root.querySelector('.mp-level-select');
    var api = { traj: traj, slider: slider, tool: tool, readout: readout };
    if (!svg) { return api; }

    // Pan and zoom by rewriting the viewBox.
    var vb0 = svg.getAttribute('viewBox').split(/[\s,]+/).map(Number);
    var vb = vb0.slice();
    function applyVb() { svg.setAttribute('viewBox', vb.join(' ')); }
    function zoom(f, cx, cy) {
      if (cx === undefined) { cx = vb[0] + vb[2] / 2; cy = vb[1] + vb[3] / 2; }
      vb = [cx - (cx - vb[0]) * f, cy - (cy - vb[1]) * f, vb[2] * f, vb[3] * f];
      applyVb();
    }
    function toSvg(ev) {
      var r = svg.getBoundingClientRect();
      return [vb[0] + (ev.clientX - r.left) / r.width * vb[2],
              vb[1] + (ev.clientY - r.top) / r.height * vb[3]];
    }
    svg.addEventListener('wheel', function (ev) {
      ev.preventDefault();
      var p = toSvg(ev);
      zoom(ev.deltaY > 0 ? 1.2 : 1 / 1.2, p[0], p[1]);
    }, { passive: false });
    var drag = null;
    svg.addEventListener('mousedown', function (ev) { drag = toSvg(ev); });
    window.addEventListener('mouseup', function () { drag = null; });
    svg.addEventListener('mousemove', function (ev) {
      if (!drag) { return; }
      var p = toSvg(ev);
      vb[0] -= p[0] - drag[0];
      vb[1] -= p[1] - drag[1];
      applyVb();
    });
    root.querySelector('.mp-zoom-in').addEventListener('click', function () { zoom(1 / 1.5); });
    root.querySelector('.mp-zoom-out').addEventListener('click', function () { zoom(1.5); });
    root.querySelector('.mp-reset').addEventListener('click', function () { vb = vb0.slice(); applyVb(); });
    api.zoom = zoom;
    api.reset = function () { vb = vb0.slice(); applyVb(); };
    api.viewBox = function () { return vb.slice(); };

    // Level selector: one level, or all (links between levels only with all).
    function showLevel(v) {
      var groups = svg.querySelectorAll('g.mp-level');
      for (var i = 0; i < groups.length; i++) {
        var l = groups[i].getAttribute('data-level');
        groups[i].style.display = (v === 'all' || v === l) ? '' : 'none';
      }
    }
    if (select) { select.addEventListener('change', function () { showLevel(select.value); }); }
    api.showLevel = showLevel;

    // Playback.
    function place(t) {
      var p = positionAt(traj, t);
      if (!p || !tool) { return null; }
      tool.setAttribute('cx', p[1].toFixed(4));
      tool.setAttribute('cy', p[2].toFixed(4));
      tool.setAttribute('visibility', 'visible');
      if (readout) {
        readout.textContent = 't = ' + t.toFixed(3) + ' s   X ' + p[1].toFixed(3) +
          '  Y ' + p[2].toFixed(3) + '  Z ' + p[3].toFixed(3);
      }
      return p;
    }
    if (slider) { slider.addEventListener('input', function () { place(Number(slider.value)); }); }
    var playing = false, last = 0;
    var play = root.querySelector('.mp-play');
    function frame(now) {
      if (!playing) { return; }
      var dt = last ? (now - last) / 1000 : 0;
      last = now;
      var t = Number(slider.value) + dt;
      if (t >= Number(slider.max)) { t = Number(slider.max); playing = false; play.textContent = 'play'; }
      slider.value = String(t);
      place(t);
      if (playing) { window.requestAnimationFrame(frame); }
    }
    if (play && slider) {
      play.addEventListener('click', function () {
        playing = !playing;
        play.textContent = playing ? 'pause' : 'play';
        if (playing) {
          if (Number(slider.value) >= Number(slider.max)) { slider.value = '0'; }
          last = 0;
          window.requestAnimationFrame(frame);
        }
      });
    }
    api.place = place;
    return api;
  }

  var viewers = [];
  var roots = document.querySelectorAll('.mp-viewer');
  for (var i = 0; i < roots.length; i++) { viewers.push(setup(roots[i])); }
  window.mpViewers = viewers;

  // Self-test for the headless-browser test: move the first slider to mid-cycle through a
  // real input event, then read the tool marker back from the DOM.
  function selfTest() {
    var v = viewers[0];
    if (!v || !v.slider || !v.tool || v.traj.length === 0) { return 'MP-SELFTEST-FAIL no viewer'; }
    var t = Number(v.slider.max) / 2;
    v.slider.value = String(t);
    v.slider.dispatchEvent(new Event('input'));
    var x = Number(v.tool.getAttribute('cx')), y = Number(v.tool.getAttribute('cy'));
    if (v.tool.getAttribute('visibility') !== 'visible') { return 'MP-SELFTEST-FAIL marker hidden'; }
    if (v.readout.textContent.indexOf('t = ') !== 0) { return 'MP-SELFTEST-FAIL readout'; }
    var p = positionAt(v.traj, Number(v.slider.value));
    if (Math.abs(p[1] - x) > 1e-3 || Math.abs(p[2] - y) > 1e-3) { return 'MP-SELFTEST-FAIL marker off'; }
    var before = v.viewBox();
    v.zoom(0.5);
    var after = v.viewBox();
    if (!(after[2] < before[2])) { return 'MP-SELFTEST-FAIL zoom'; }
    v.reset();
    var select = document.querySelector('.mp-level-select');
    if (select && select.options.length > 1) {
      select.value = select.options[1].value;
      select.dispatchEvent(new Event('change'));
      var hidden = document.querySelectorAll('.mp-viewer g.mp-level[style*="none"]').length;
      var shown = document.querySelectorAll('.mp-viewer g.mp-level[data-level="' + select.value + '"]');
      if (hidden === 0 || shown.length === 0 || shown[0].style.display === 'none') {
        return 'MP-SELFTEST-FAIL level selector';
      }
      select.value = 'all';
      select.dispatchEvent(new Event('change'));
    }
    return 'MP-SELFTEST-OK t=' + Number(v.slider.value).toFixed(6) + ' x=' + x.toFixed(4) +
      ' y=' + y.toFixed(4) + ' z=' + p[3].toFixed(4) + ' errors=' + window.mpErrors.length;
  }
  if (window.location.hash === '#selftest') {
    var r;
    try { r = selfTest(); } catch (e) { r = 'MP-SELFTEST-FAIL ' + e; }
    if (window.mpErrors.length === 0) { document.title = r; }
  }
}());
