// A small parser for the Graphviz DOT language (the subset a program writes:
// graph/digraph, node/edge/attribute statements, edge chains, subgraphs and
// clusters, quoted and HTML strings, comments), a layered left-to-right
// layout (cycle breaking, longest-path layers, dummy nodes for long edges,
// barycentre ordering) and the writer -> message -> reader table.
// Pure functions: no DOM, tested with node.

function tokenize(src) {
  const toks = [];
  let i = 0;
  const n = src.length;
  let lineStart = true;
  while (i < n) {
    const c = src[i];
    if (c === '\n') { i++; lineStart = true; continue; }
    if (c === ' ' || c === '\t' || c === '\r' || c === '\f' || c === '\v') { i++; continue; }
    if (lineStart && c === '#') { while (i < n && src[i] !== '\n') i++; continue; }
    lineStart = false;
    if (c === '/' && src[i + 1] === '/') { while (i < n && src[i] !== '\n') i++; continue; }
    if (c === '/' && src[i + 1] === '*') {
      const e = src.indexOf('*/', i + 2);
      i = e < 0 ? n : e + 2;
      continue;
    }
    if (c === '"') {
      let s = '';
      i++;
      while (i < n && src[i] !== '"') {
        if (src[i] === '\\' && i + 1 < n) {
          const d = src[i + 1];
          if (d === '"') s += '"';
          else if (d === '\n') { /* line continuation */ }
          else if (d === 'n' || d === 'l' || d === 'r') s += '\n';
          else s += '\\' + d;
          i += 2;
        } else s += src[i++];
      }
      i++;
      // "a" + "b" concatenation
      toks.push({ t: 'id', v: s, q: true });
      continue;
    }
    if (c === '<') {
      let depth = 0;
      let s = '';
      for (; i < n; i++) {
        if (src[i] === '<') depth++;
        else if (src[i] === '>') depth--;
        s += src[i];
        if (depth === 0) { i++; break; }
      }
      // HTML label: keep its text only
      toks.push({ t: 'id', v: s.slice(1, -1).replace(/<[^>]*>/g, ' ').replace(/\s+/g, ' ').trim(), q: true });
      continue;
    }
    if (c === '-' && (src[i + 1] === '>' || src[i + 1] === '-')) {
      toks.push({ t: 'edgeop', v: src.slice(i, i + 2) });
      i += 2;
      continue;
    }
    if ('{}[];,=:+'.includes(c)) { toks.push({ t: c }); i++; continue; }
    let m = /^-?(?:\.\d+|\d+(?:\.\d*)?)/.exec(src.slice(i, i + 64));
    if (!m) m = /^[A-Za-z_\u0080-\uffff][A-Za-z_0-9\u0080-\uffff]*/.exec(src.slice(i, i + 4096));
    if (m) { toks.push({ t: 'id', v: m[0] }); i += m[0].length; continue; }
    i++; // unknown character: skip
  }
  // join "a" + "b"
  const out = [];
  for (let k = 0; k < toks.length; k++) {
    if (toks[k].t === '+' && out.length && out[out.length - 1].t === 'id' && toks[k + 1] && toks[k + 1].t === 'id') {
      out[out.length - 1] = { t: 'id', v: out[out.length - 1].v + toks[k + 1].v, q: true };
      k++;
    } else out.push(toks[k]);
  }
  return out;
}

const KEYWORDS = new Set(['graph', 'digraph', 'subgraph', 'node', 'edge', 'strict']);

export function parseDot(src) {
  const toks = tokenize(String(src || ''));
  let p = 0;
  const peek = (o = 0) => toks[p + o] || { t: 'eof' };
  const isKw = (tok, kw) => tok.t === 'id' && !tok.q && tok.v.toLowerCase() === kw;
  const g = { name: '', directed: true, nodes: new Map(), edges: [], clusters: [], attrs: {} };

  function attrList() {
    const a = {};
    while (peek().t === '[') {
      p++;
      while (peek().t !== ']' && peek().t !== 'eof') {
        if (peek().t === 'id') {
          const k = toks[p++].v;
          let v = 'true';
          if (peek().t === '=') { p++; if (peek().t === 'id') v = toks[p++].v; }
          a[k] = v;
        } else p++;
      }
      if (peek().t === ']') p++;
    }
    return a;
  }
  function addNode(id, attrs, scope) {
    let nd = g.nodes.get(id);
    if (!nd) {
      nd = { id, attrs: Object.assign({}, scope.node) };
      g.nodes.set(id, nd);
      for (const c of scope.clusters) c.nodes.push(id);
    }
    if (attrs) Object.assign(nd.attrs, attrs);
    return nd;
  }
  function nodeId() {
    const id = toks[p++].v;
    if (peek().t === ':') { p++; if (peek().t === 'id') p++; if (peek().t === ':') { p++; if (peek().t === 'id') p++; } }
    return id;
  }
  // returns the list of node ids the operand stands for
  function operand(scope) {
    if (peek().t === '{' || isKw(peek(), 'subgraph')) return subgraph(scope);
    if (peek().t === 'id') {
      const id = nodeId();
      addNode(id, null, scope);
      return [id];
    }
    p++;
    return [];
  }
  function subgraph(scope) {
    let name = '';
    if (isKw(peek(), 'subgraph')) { p++; if (peek().t === 'id') name = toks[p++].v; }
    const inner = { node: Object.assign({}, scope.node), edge: Object.assign({}, scope.edge), clusters: scope.clusters.slice(), members: [] };
    let cluster = null;
    if (/^cluster/i.test(name)) {
      cluster = { id: name, label: name.replace(/^cluster_?/i, ''), nodes: [] };
      g.clusters.push(cluster);
      inner.clusters.push(cluster);
    }
    if (peek().t === '{') { p++; stmtList(inner, cluster); if (peek().t === '}') p++; }
    const ids = new Set();
    for (const c of [cluster].filter(Boolean)) for (const id of c.nodes) ids.add(id);
    for (const id of inner.members) ids.add(id);
    return [...ids];
  }
  function stmtList(scope, cluster) {
    while (peek().t !== '}' && peek().t !== 'eof') {
      const tok = peek();
      if (tok.t === ';' || tok.t === ',') { p++; continue; }
      if (isKw(tok, 'graph') || isKw(tok, 'node') || isKw(tok, 'edge')) {
        p++;
        const a = attrList();
        const kw = tok.v.toLowerCase();
        if (kw === 'graph') { if (cluster) { if (a.label !== undefined) cluster.label = a.label; } else Object.assign(g.attrs, a); }
        else Object.assign(scope[kw], a);
        continue;
      }
      if (tok.t === 'id' && peek(1).t === '=' ) {
        p += 2;
        const v = peek().t === 'id' ? toks[p++].v : '';
        if (cluster) { if (tok.v === 'label') cluster.label = v; } else g.attrs[tok.v] = v;
        continue;
      }
      let left = operand(scope);
      scope.members.push(...left);
      if (peek().t !== 'edgeop') {
        const a = attrList();
        if (left.length === 1 && !(tok.t === '{' || isKw(tok, 'subgraph'))) addNode(left[0], a, scope);
        continue;
      }
      const chain = [left];
      while (peek().t === 'edgeop') {
        p++;
        const r = operand(scope);
        scope.members.push(...r);
        chain.push(r);
      }
      const a = Object.assign({}, scope.edge, attrList());
      for (let k = 0; k + 1 < chain.length; k++) {
        for (const from of chain[k]) for (const to of chain[k + 1]) {
          g.edges.push({ from, to, attrs: a, label: a.label !== undefined ? a.label : (a.xlabel || '') });
        }
      }
    }
  }

  if (isKw(peek(), 'strict')) p++;
  if (isKw(peek(), 'graph')) { g.directed = false; p++; }
  else if (isKw(peek(), 'digraph')) p++;
  else if (peek().t !== '{') throw new Error('DOT: expected "digraph" or "graph"');
  if (peek().t === 'id') g.name = toks[p++].v;
  if (peek().t !== '{') throw new Error('DOT: expected "{" after the graph header');
  p++;
  stmtList({ node: {}, edge: {}, clusters: [], members: [] }, null);
  if (peek().t !== '}') throw new Error('DOT: unbalanced braces');
  for (const nd of g.nodes.values()) {
    nd.label = nd.attrs.label !== undefined && nd.attrs.label !== '\\N' ? nd.attrs.label.replace(/\\N/g, nd.id) : nd.id;
  }
  for (const e of g.edges) if (KEYWORDS.has(e.label)) e.label = '';
  return g;
}

const MSG_SHAPES = new Set(['note', 'ellipse', 'oval', 'cds', 'parallelogram', 'cylinder', 'tab', 'component', 'folder', 'box3d', 'plain', 'plaintext', 'underline']);

// Nodes that stand for messages: marked with kind/class/type=message, or with
// an explicit shape from MSG_SHAPES when other nodes have a different shape.
export function messageNodes(g) {
  const out = new Set();
  const shapes = new Set([...g.nodes.values()].map((n) => (n.attrs.shape || '').toLowerCase()));
  for (const n of g.nodes.values()) {
    const a = n.attrs;
    const kind = String(a.kind || a.class || a.type || '').toLowerCase();
    if (kind === 'message' || kind === 'msg') out.add(n.id);
    else if (a.shape && MSG_SHAPES.has(a.shape.toLowerCase()) && shapes.size > 1) out.add(n.id);
  }
  return out;
}

// Rows { message, writers: [], readers: [] } sorted by message name.
export function messageTable(g) {
  const msgs = messageNodes(g);
  const rows = new Map();
  const row = (name) => {
    if (!rows.has(name)) rows.set(name, { message: name, writers: new Set(), readers: new Set() });
    return rows.get(name);
  };
  const label = (id) => (g.nodes.get(id) ? g.nodes.get(id).label : id);
  for (const m of msgs) row(label(m));
  for (const e of g.edges) {
    const fm = msgs.has(e.from);
    const tm = msgs.has(e.to);
    if (tm && !fm) row(label(e.to)).writers.add(label(e.from));
    else if (fm && !tm) row(label(e.from)).readers.add(label(e.to));
    else if (!fm && !tm) {
      const r = row(e.label || '(unnamed)');
      r.writers.add(label(e.from));
      r.readers.add(label(e.to));
    }
  }
  return [...rows.values()]
    .map((r) => ({ message: r.message, writers: [...r.writers].sort(), readers: [...r.readers].sort() }))
    .sort((a, b) => a.message.localeCompare(b.message));
}

// Layered layout, left to right.  measure(text) -> width in px.
// opt.rankdir: 'LR' (layers left to right, default) or 'TB' (top to bottom).
export function layoutGraph(g, measure = (s) => 7 * s.length, opt = {}) {
  const tb = String(opt.rankdir || 'LR').toUpperCase() === 'TB';
  const lineH = opt.lineHeight || 16;
  const padX = 12;
  const padY = 8;
  const ids = [...g.nodes.keys()];
  const idx = new Map(ids.map((id, i) => [id, i]));
  const N = ids.length;
  const edges = g.edges.filter((e) => idx.has(e.from) && idx.has(e.to));
  const out = Array.from({ length: N }, () => []);
  edges.forEach((e, k) => { if (e.from !== e.to) out[idx.get(e.from)].push(k); });
  // 1. break cycles: DFS, edges to a node on the stack are reversed
  const state = new Uint8Array(N);
  const reversed = new Set();
  for (let s = 0; s < N; s++) {
    if (state[s]) continue;
    const stack = [[s, 0]];
    state[s] = 1;
    while (stack.length) {
      const top = stack[stack.length - 1];
      const [u, j] = top;
      if (j < out[u].length) {
        top[1]++;
        const k = out[u][j];
        const v = idx.get(edges[k].to);
        if (state[v] === 1) reversed.add(k);
        else if (state[v] === 0) { state[v] = 1; stack.push([v, 0]); }
      } else { state[u] = 2; stack.pop(); }
    }
  }
  const dag = []; // [u, v, edgeIndex, reversed]
  edges.forEach((e, k) => {
    if (e.from === e.to) return;
    const u = idx.get(e.from);
    const v = idx.get(e.to);
    dag.push(reversed.has(k) ? [v, u, k, true] : [u, v, k, false]);
  });
  // 2. longest-path layers
  const layer = new Int32Array(N);
  const indeg = new Int32Array(N);
  const succ = Array.from({ length: N }, () => []);
  for (const [u, v] of dag) { succ[u].push(v); indeg[v]++; }
  const queue = [];
  for (let i = 0; i < N; i++) if (!indeg[i]) queue.push(i);
  for (let q = 0; q < queue.length; q++) {
    const u = queue[q];
    for (const v of succ[u]) {
      layer[v] = Math.max(layer[v], layer[u] + 1);
      if (--indeg[v] === 0) queue.push(v);
    }
  }
  // 3. dummy nodes for edges over several layers
  const V = ids.map((id, i) => {
    const nd = g.nodes.get(id);
    const lines = String(nd.label).split('\n');
    const w = Math.max(40, ...lines.map(measure)) + 2 * padX;
    const h = lines.length * lineH + 2 * padY;
    // layout space: w along the layer axis, h across it
    return { id, label: nd.label, lines, layer: layer[i], w: tb ? h : w, h: tb ? w : h, dummy: false };
  });
  const chains = [];
  for (const [u, v, k, rev] of dag) {
    const chain = [u];
    let prev = u;
    for (let L = V[u].layer + 1; L < V[v].layer; L++) {
      const d = V.length;
      V.push({ id: `__d${d}`, label: '', lines: [], layer: L, w: 0, h: tb ? 16 : 8, dummy: true });
      chain.push(d);
      prev = d;
    }
    chain.push(v);
    chains.push({ edge: edges[k], nodes: chain, reversed: rev });
  }
  const nLayers = V.reduce((m, v) => Math.max(m, v.layer + 1), 0);
  const layers = Array.from({ length: nLayers }, () => []);
  V.forEach((v, i) => layers[v.layer].push(i));
  const preds = V.map(() => []);
  const succs = V.map(() => []);
  for (const c of chains) for (let j = 0; j + 1 < c.nodes.length; j++) {
    succs[c.nodes[j]].push(c.nodes[j + 1]);
    preds[c.nodes[j + 1]].push(c.nodes[j]);
  }
  // 4. barycentre ordering sweeps
  const pos = new Float64Array(V.length);
  const setPos = () => layers.forEach((L) => L.forEach((v, i) => { pos[v] = i; }));
  setPos();
  for (let sweep = 0; sweep < 12; sweep++) {
    const down = sweep % 2 === 0;
    const order = down ? layers.map((_, i) => i) : layers.map((_, i) => nLayers - 1 - i);
    for (const li of order) {
      const nb = down ? preds : succs;
      const bc = new Map();
      for (const v of layers[li]) {
        const ns = nb[v];
        bc.set(v, ns.length ? ns.reduce((s, u) => s + pos[u], 0) / ns.length : pos[v]);
      }
      layers[li].sort((a, b) => bc.get(a) - bc.get(b) || pos[a] - pos[b]);
      layers[li].forEach((v, i) => { pos[v] = i; });
    }
  }
  // 5. coordinates: column widths leave room for the edge labels leaving them
  const gapY = tb ? 28 : 18;
  const labelW = new Float64Array(nLayers);
  for (const c of chains) {
    const lbl = c.edge.label || '';
    if (!lbl) continue;
    const L = V[c.nodes[0]].layer;
    labelW[L] = Math.max(labelW[L], tb ? 2 * lineH + 8 : measure(lbl) + 16);
  }
  const colW = layers.map((L) => L.reduce((m, v) => Math.max(m, V[v].w), 0));
  const colH = layers.map((L) => L.reduce((s, v) => s + V[v].h + gapY, -gapY));
  const H = Math.max(0, ...colH);
  let x = 10;
  layers.forEach((L, li) => {
    let y = 10 + (H - colH[li]) / 2;
    for (const v of L) {
      V[v].x = x + (colW[li] - V[v].w) / 2;
      V[v].y = y;
      y += V[v].h + gapY;
    }
    x += colW[li] + Math.max(tb ? 44 : 70, labelW[li]);
  });
  const width = x - Math.max(tb ? 44 : 70, labelW[nLayers - 1] || 0) + 10;
  // 6. edge polylines (in layout direction), label at the first segment
  const routed = chains.map((c) => {
    const pts = [];
    c.nodes.forEach((v, j) => {
      const n = V[v];
      const cy = n.y + n.h / 2;
      if (j === 0) pts.push([n.x + n.w, cy]);
      else if (j === c.nodes.length - 1) pts.push([n.x, cy]);
      else { pts.push([n.x, cy]); pts.push([n.x + n.w, cy]); }
    });
    const [a, b] = [pts[0], pts[1]];
    return { edge: c.edge, points: pts, reversed: c.reversed, labelAt: [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2] };
  });
  const selfLoops = edges.filter((e) => e.from === e.to).map((e) => ({ edge: e, node: V[idx.get(e.from)] }));
  let W = Math.max(width, 40);
  let Ht = H + 20;
  if (tb) {
    for (const v of V) [v.x, v.y, v.w, v.h] = [v.y, v.x, v.h, v.w];
    for (const r of routed) {
      r.points = r.points.map(([a, b]) => [b, a]);
      r.labelAt = [r.labelAt[1], r.labelAt[0]];
    }
    [W, Ht] = [Ht, W];
  }
  return { nodes: V.filter((v) => !v.dummy), edges: routed, selfLoops, width: W, height: Ht, rankdir: tb ? 'TB' : 'LR' };
}
