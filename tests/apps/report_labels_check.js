// Run inside a copy of report.html by report_browser_test.sh: measures every label of every
// chart as Chromium draws it and writes what it found into a <pre> (id label-check) at the end.
//   - a row, category or legend label is whole, or shortened (an ellipsis) with its full name in
//     a <title> whose start and end are the ones shown;
//   - a legend repeats no entry (name, colour and opacity), nor shows two names alike;
//   - no text reaches past the SVG's left or right edge;
//   - no two texts of one chart overlap (their drawn boxes, rotation included).
(function () {
  const problems = [];
  let labels = 0, shortened = 0, texts = 0;
  const say = (svg, what) => problems.push(svg.dataset.chart + ': ' + what);
  // The corners of a text's box in its SVG's coordinates (rotated labels give a rotated box).
  const corners = (svg, t) => {
    const b = t.getBBox();
    const m = svg.getScreenCTM().inverse().multiply(t.getScreenCTM());
    return [[b.x, b.y], [b.x + b.width, b.y], [b.x + b.width, b.y + b.height], [b.x, b.y + b.height]].map(([x, y]) => {
      const p = new DOMPoint(x, y).matrixTransform(m);
      return [p.x, p.y];
    });
  };
  // Two convex quadrilaterals overlap unless one of their edges' normals separates them
  // (by the separating axis theorem); touching within half a pixel is not overlapping.
  const overlap = (a, b) => {
    for (const poly of [a, b]) {
      for (let i = 0; i < 4; ++i) {
        const [x1, y1] = poly[i], [x2, y2] = poly[(i + 1) % 4];
        const len = Math.hypot(x2 - x1, y2 - y1);
        if (len === 0) continue;
        const n = [(y1 - y2) / len, (x2 - x1) / len];
        const along = (q) => q.map(([x, y]) => x * n[0] + y * n[1]);
        const pa = along(a), pb = along(b);
        if (Math.max(...pa) - 0.5 <= Math.min(...pb) || Math.max(...pb) - 0.5 <= Math.min(...pa)) return false;
      }
    }
    return true;
  };
  const shown = (t) => [...t.childNodes].filter((n) => n.nodeType === Node.TEXT_NODE).map((n) => n.data).join('');
  for (const svg of document.querySelectorAll('svg.chart')) {
    const width = svg.viewBox.baseVal.width;
    for (const t of svg.querySelectorAll('.gantt-row text, .categories text, .legend-item text')) {
      ++labels;
      const owner = t.closest('.legend-item') || t;
      const title = owner.querySelector('title') ? owner.querySelector('title').textContent : null;
      const s = shown(t);
      if (title === s) continue;
      if (title === null) { say(svg, 'label "' + s + '" has no <title>'); continue; }
      const dots = s.indexOf('\u2026');
      const head = s.slice(0, Math.max(dots, 0)), tail = s.slice(dots + 1);
      if (dots < 0 || !title.startsWith(head) || !title.endsWith(tail)) say(svg, 'label "' + s + '" is not its title "' + title + '" shortened');
      else ++shortened;
    }
    const entries = new Set(), names = new Map();
    for (const item of svg.querySelectorAll('.legend-item')) {
      const name = item.querySelector('title').textContent, swatch = item.querySelector('rect');
      const entry = [name, swatch.getAttribute('fill'), swatch.getAttribute('fill-opacity')].join('|');
      if (entries.has(entry)) say(svg, 'legend entry "' + name + '" is repeated');
      entries.add(entry);
      const s = shown(item.querySelector('text'));
      if (names.has(s) && names.get(s) !== name) say(svg, 'legend entries "' + name + '" and "' + names.get(s) + '" both read "' + s + '"');
      names.set(s, name);
    }
    const boxes = [];
    for (const t of svg.querySelectorAll('text')) {
      ++texts;
      const box = corners(svg, t);
      const xs = box.map((p) => p[0]);
      if (Math.min(...xs) < 0) say(svg, '"' + shown(t) + '" starts left of x = 0, at ' + Math.min(...xs).toFixed(1));
      if (Math.max(...xs) > width) say(svg, '"' + shown(t) + '" ends right of the SVG, at ' + Math.max(...xs).toFixed(1));
      for (const [other, otherBox] of boxes) {
        if (overlap(box, otherBox)) say(svg, '"' + shown(t) + '" overlaps "' + shown(other) + '"');
      }
      boxes.push([t, box]);
    }
  }
  const pre = document.createElement('pre');
  pre.id = 'label-check';
  pre.textContent = 'labels=' + labels + ' shortened=' + shortened + ' texts=' + texts + ' problems=' + problems.length + '\n' + problems.slice(0, 40).join('\n');
  document.body.appendChild(pre);
})();
