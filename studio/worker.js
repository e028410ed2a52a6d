// The search worker: runs the core's executor a few generations at a time, posting progress
// between slices so that the page stays live and a stop arrives between two generations.

import init, { Search } from './pkg/noncirc_wasm.js';

const ready = init();
let stopAsked = false;

/** Milliseconds of search between two progress messages. */
const SLICE_MS = 50;

self.onmessage = async ({ data }) => {
  await ready;
  if (data.type === 'stop') { stopAsked = true; return; }
  if (data.type !== 'start') return;
  stopAsked = false;
  let search;
  try {
    search = data.checkpoint
      ? Search.resume(data.checkpoint, data.budget === undefined ? undefined : BigInt(data.budget))
      : new Search(data.scene, data.algorithm, BigInt(data.budget), BigInt(data.seed));
  } catch (e) {
    self.postMessage({ type: 'error', message: e.message });
    return;
  }
  const start = performance.now();
  let searching = 0; // ms spent inside the search itself (rate = evaluations / searching)
  const slice = () => {
    const t0 = performance.now();
    let done = false;
    while (!done && !stopAsked && performance.now() - t0 < SLICE_MS) done = search.run(1);
    searching += performance.now() - t0;
    const progress = JSON.parse(search.progress());
    self.postMessage({ type: 'progress', progress, searchingMs: searching });
    if (done || stopAsked) {
      if (!done) search.stop();
      const seconds = (performance.now() - start) / 1000;
      self.postMessage({ type: 'result', result: JSON.parse(search.result(seconds)), checkpoint: search.checkpoint(), searchingMs: searching });
      search.free();
      return;
    }
    setTimeout(slice, 0);
  };
  slice();
};
