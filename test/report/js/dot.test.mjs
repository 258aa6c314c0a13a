// Unit tests of the report's DOT parser, layout and message table.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { parseDot, layoutGraph, messageTable, messageNodes } from '../../../report/src/dot.js';

test('parses nodes, attributes, chains, comments, quoted ids and defaults', () => {
  const g = parseDot(`// header
  digraph "flow" {
    rankdir=LR;
# a preprocessor-style line, ignored
    node [shape=box];
    "fsw app" [label="FSW\\napp"];
    a -> b -> c [label="m1"];  /* block
    comment */
    c -> "fsw app" [label=<<b>html</b> msg>];
    subgraph cluster_plant { label="Plant"; hub; wheels; }
    wheels -> hub;
  }`);
  assert.equal(g.name, 'flow');
  assert.ok(g.directed);
  assert.deepEqual([...g.nodes.keys()].sort(), ['a', 'b', 'c', 'fsw app', 'hub', 'wheels']);
  assert.equal(g.nodes.get('fsw app').label, 'FSW\napp');
  assert.equal(g.nodes.get('a').attrs.shape, 'box');
  assert.equal(g.edges.length, 4);
  assert.equal(g.edges[0].label, 'm1');
  assert.equal(g.edges[1].label, 'm1');
  assert.equal(g.edges[2].label, 'html msg');
  assert.equal(g.clusters.length, 1);
  assert.equal(g.clusters[0].label, 'Plant');
  assert.deepEqual(g.clusters[0].nodes, ['hub', 'wheels']);
});

test('message nodes give writer -> message -> reader rows', () => {
  const g = parseDot(`digraph { node [shape=box]; fsw; plant; sensor;
    node [shape=note]; Cmd; Meas;
    fsw -> Cmd -> plant; plant -> Meas; Meas -> fsw; Meas -> sensor; }`);
  assert.deepEqual([...messageNodes(g)].sort(), ['Cmd', 'Meas']);
  assert.deepEqual(messageTable(g), [
    { message: 'Cmd', writers: ['fsw'], readers: ['plant'] },
    { message: 'Meas', writers: ['plant'], readers: ['fsw', 'sensor'] },
  ]);
});

test('labelled edges give the rows when there are no message nodes', () => {
  const g = parseDot('digraph { a -> b [label=X]; a -> c [label=X]; c -> a [label=Y]; b -> c; }');
  assert.equal(messageNodes(g).size, 0);
  assert.deepEqual(messageTable(g), [
    { message: '(unnamed)', writers: ['b'], readers: ['c'] },
    { message: 'X', writers: ['a'], readers: ['b', 'c'] },
    { message: 'Y', writers: ['c'], readers: ['a'] },
  ]);
});

test('layout: layers follow the edges, cycles are broken, nothing overlaps', () => {
  const g = parseDot('digraph { a -> b -> c -> d; a -> d; d -> a [label=fb]; e; c -> c; }');
  for (const dir of ['LR', 'TB']) {
    const L = layoutGraph(g, (s) => 7 * s.length, { rankdir: dir });
    const pos = new Map(L.nodes.map((n) => [n.id, n]));
    const along = (n) => (dir === 'LR' ? n.x : n.y);
    assert.ok(along(pos.get('a')) < along(pos.get('b')) && along(pos.get('b')) < along(pos.get('c')) && along(pos.get('c')) < along(pos.get('d')));
    assert.equal(L.edges.length, 5); // self loop apart
    assert.equal(L.selfLoops.length, 1);
    assert.equal(L.edges.filter((e) => e.reversed).length, 1);
    const ad = L.edges.find((e) => e.edge.from === 'a' && e.edge.to === 'd');
    assert.ok(ad.points.length > 2, 'long edge routed through dummy nodes');
    for (const p of L.nodes) for (const q of L.nodes) {
      if (p === q) continue;
      const overlap = p.x < q.x + q.w && q.x < p.x + p.w && p.y < q.y + q.h && q.y < p.y + p.h;
      assert.ok(!overlap, `${p.id} overlaps ${q.id}`);
    }
    for (const n of L.nodes) assert.ok(n.x >= 0 && n.y >= 0 && n.x + n.w <= L.width && n.y + n.h <= L.height);
  }
});

test('malformed DOT throws a message or degrades, never hangs', () => {
  assert.throws(() => parseDot('hello'), /DOT/);
  assert.throws(() => parseDot('digraph { a -> b'), /unbalanced/);
  const g = parseDot('digraph { a -> ; b -> "c</script>" [label="<!-- x -->"]; { d e } -> f }');
  assert.ok(g.nodes.has('c</script>'));
  assert.ok(g.edges.some((e) => e.from === 'd' && e.to === 'f') && g.edges.some((e) => e.from === 'e' && e.to === 'f'));
  assert.equal(parseDot('digraph {}').nodes.size, 0);
  assert.equal(layoutGraph(parseDot('digraph {}')).nodes.length, 0);
});
