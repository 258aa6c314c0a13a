// The frame shared by the report pages (main.js, mc_main.js): the embedded
// data, sections that fail on their own, and the ready flag the browser tests
// wait for (window.kestrelReport).
import { el } from './data.js';

// Runs fn(root) for the element `id`; an exception is shown in place and
// recorded in status.errors, and the other sections still render.
export function section(status, id, fn) {
  const root = document.getElementById(id);
  if (!root) return;
  const t0 = performance.now();
  try {
    fn(root);
    status.ms = status.ms || {};
    status.ms[id] = Math.round(performance.now() - t0); // shown by the browser tests
  } catch (e) {
    status.errors.push(`${id}: ${e && e.message}`);
    root.appendChild(el('p', { class: 'error', text: `This section could not be drawn: ${e && e.message}` }));
    console.error(e);
  }
}

// The JSON of <script id="kestrel-data">; {} (and an error shown in
// errorRootId) if it is not valid JSON.
export function embeddedData(status, errorRootId, what) {
  const node = document.getElementById('kestrel-data');
  try {
    return JSON.parse(node ? node.textContent : '{}');
  } catch (e) {
    status.errors.push('data: ' + e.message);
    document.getElementById(errorRootId).appendChild(el('p', { class: 'error', text: `The ${what} embedded in this page is not valid JSON: ${e.message}` }));
    console.error(e);
    return {};
  }
}

// Plots follow the window's width; the page is marked ready.
export function finishPage(status, resizePlots) {
  let timer = 0;
  window.addEventListener('resize', () => { clearTimeout(timer); timer = setTimeout(resizePlots, 150); });
  status.ready = true;
  document.body.setAttribute('data-ready', status.errors.length ? 'errors' : 'ok');
}

export function whenLoaded(main) {
  if (document.readyState === 'loading') document.addEventListener('DOMContentLoaded', main);
  else main();
}
