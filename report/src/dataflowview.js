// Data-flow map: the harness's Graphviz DOT text, parsed and laid out here
// (no Graphviz at view time), plus the writer -> message -> reader table and
// the DOT source itself.
import { parseDot, layoutGraph, messageTable, messageNodes } from './dot.js';
import { el } from './data.js';

const SVGNS = 'http://www.w3.org/2000/svg';
function s(tag, attrs, text) {
  const e = document.createElementNS(SVGNS, tag);
  for (const [k, v] of Object.entries(attrs || {})) e.setAttribute(k, String(v));
  if (text !== undefined) e.textContent = text;
  return e;
}

function pathD(pts, tb) {
  const f = (v) => v.toFixed(1);
  let d = `M${f(pts[0][0])},${f(pts[0][1])}`;
  for (let i = 1; i < pts.length; i++) {
    const [x0, y0] = pts[i - 1];
    const [x1, y1] = pts[i];
    if (tb) {
      const my = (y0 + y1) / 2;
      d += ` C${f(x0)},${f(my)} ${f(x1)},${f(my)} ${f(x1)},${f(y1)}`;
    } else {
      const mx = (x0 + x1) / 2;
      d += ` C${f(mx)},${f(y0)} ${f(mx)},${f(y1)} ${f(x1)},${f(y1)}`;
    }
  }
  return d;
}

function drawSvg(L, msgs, measure) {
  const tb = L.rankdir === 'TB';
  const svg = s('svg', { class: 'dataflow', width: L.width, height: L.height, viewBox: `0 0 ${L.width} ${L.height}`, role: 'img' });
  const defs = s('defs');
  for (const [id, color] of [['arr', '#4a5a78'], ['arrb', '#b3541e']]) {
    const m = s('marker', { id: `df-${id}`, viewBox: '0 0 10 10', refX: 9, refY: 5, markerWidth: 7, markerHeight: 7, orient: 'auto-start-reverse' });
    m.appendChild(s('path', { d: 'M0,0 L10,5 L0,10 z', fill: color }));
    defs.appendChild(m);
  }
  svg.appendChild(defs);
  for (const e of L.edges) {
    const attrs = { d: pathD(e.points, tb), fill: 'none', class: e.reversed ? 'edge back' : 'edge' };
    if (e.reversed) attrs['marker-start'] = 'url(#df-arrb)';
    else attrs['marker-end'] = 'url(#df-arr)';
    const p = s('path', attrs);
    p.appendChild(s('title', {}, `${e.edge.from} \u2192 ${e.edge.to}${e.edge.label ? ' : ' + e.edge.label : ''}`));
    svg.appendChild(p);
  }
  for (const e of L.edges) {
    if (!e.edge.label) continue;
    const [x, y] = e.labelAt;
    const w = measure(e.edge.label) + 8;
    svg.appendChild(s('rect', { x: x - w / 2, y: y - 9, width: w, height: 16, rx: 3, class: 'elabel-bg' }));
    svg.appendChild(s('text', { x, y: y + 3, 'text-anchor': 'middle', class: 'elabel' }, e.edge.label));
  }
  for (const n of L.nodes) {
    const isMsg = msgs.has(n.id);
    svg.appendChild(s('rect', { x: n.x, y: n.y, width: n.w, height: n.h, rx: isMsg ? Math.min(n.h / 2, 14) : 4, class: isMsg ? 'node msg' : 'node' }));
    const top = n.y + n.h / 2 - (n.lines.length * 16) / 2 + 12;
    n.lines.forEach((ln, i) => {
      svg.appendChild(s('text', { x: n.x + n.w / 2, y: top + i * 16, 'text-anchor': 'middle', class: 'nlabel' }, ln));
    });
  }
  for (const sl of L.selfLoops) {
    const n = sl.node;
    svg.appendChild(s('path', { d: `M${n.x + n.w * 0.3},${n.y} C${n.x + n.w * 0.3},${n.y - 22} ${n.x + n.w * 0.7},${n.y - 22} ${n.x + n.w * 0.7},${n.y}`, fill: 'none', class: 'edge', 'marker-end': 'url(#df-arr)' }));
  }
  return svg;
}

export function buildDataflow(root, D, status) {
  if (!D.dot.trim()) {
    root.appendChild(el('p', { class: 'absent', text: 'No data-flow graph in this run.' }));
    status.dataflow = 'absent';
    return;
  }
  let g;
  try {
    g = parseDot(D.dot);
  } catch (e) {
    root.appendChild(el('p', { class: 'absent', text: 'The data-flow graph could not be read: ' + e.message }));
    root.appendChild(el('pre', { class: 'dot', text: D.dot }));
    status.dataflow = 'unreadable';
    return;
  }
  const card = el('div', { class: 'card wide' });
  root.appendChild(card);
  const ctx = document.createElement('canvas').getContext('2d');
  ctx.font = '12px sans-serif';
  const measure = (txt) => ctx.measureText(txt).width;
  const msgs = messageNodes(g);
  const layouts = { LR: layoutGraph(g, measure, { rankdir: 'LR' }), TB: layoutGraph(g, measure, { rankdir: 'TB' }) };
  // left to right when it fits the page (or the DOT asks for it and it fits), else the narrower one
  const avail = Math.max(300, card.getBoundingClientRect().width - 28);
  const want = String(g.attrs.rankdir || '').toUpperCase() === 'TB' ? 'TB' : 'LR';
  const other = want === 'LR' ? 'TB' : 'LR';
  let dir = want;
  if (layouts[want].width > avail && layouts[other].width < layouts[want].width) dir = other;
  const scroll = el('div', { class: 'df-scroll' });
  const flip = el('button', { class: 'toggle' });
  const draw = () => {
    scroll.textContent = '';
    scroll.appendChild(drawSvg(layouts[dir], msgs, measure));
    flip.textContent = dir === 'LR' ? 'lay out top to bottom' : 'lay out left to right';
  };
  flip.addEventListener('click', () => { dir = dir === 'LR' ? 'TB' : 'LR'; draw(); });
  card.appendChild(el('div', { class: 'controls' }, flip));
  card.appendChild(scroll);
  draw();
  card.appendChild(el('p', { class: 'note', text: `${g.nodes.size} nodes, ${g.edges.length} edges. Laid out in layers by this page (no Graphviz needed); edges that close a loop ` +
    '(feedback) are drawn dashed in orange with the arrow at their reader; message nodes are amber. Hover an edge for its endpoints.' }));

  const rows = messageTable(g);
  const table = el('table', { class: 'df-table' });
  table.appendChild(el('thead', null, el('tr', null, el('th', { text: 'writer' }), el('th', { text: 'message' }), el('th', { text: 'reader(s)' }))));
  const tb = el('tbody');
  for (const r of rows) tb.appendChild(el('tr', null, el('td', { text: r.writers.join(', ') || '\u2013' }), el('td', { class: 'msgname', text: r.message }), el('td', { text: r.readers.join(', ') || '\u2013' })));
  table.appendChild(tb);
  card.appendChild(el('h3', { text: 'Writer \u2192 message \u2192 reader' }));
  card.appendChild(table);
  const det = el('details', null, el('summary', { text: 'DOT source' }), el('pre', { class: 'dot', text: D.dot }));
  card.appendChild(det);
  status.dataflow = 'ok';
  status.dataflowNodes = g.nodes.size;
}
