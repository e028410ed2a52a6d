// The worker: runs a search, a fit or a repair a few generations at a time, posting
// progress between slices so that the page stays live and a stop arrives between two
// generations. A fit's refinement and a repair's end of box (its refinement, its teeth) are
// one call each, after their search.

import init, { Fit, Repair, Search } from './pkg/noncirc_wasm.js';

const ready = init();
let stopAsked = false;

/** Milliseconds of search between two progress messages. */
const SLICE_MS = 50;

/** The job the page asked for. */
function open(data) {
  if (data.checkpoint) return Search.resume(data.checkpoint, data.budget === undefined ? undefined : BigInt(data.budget));
  const args = [data.scene, data.algorithm, BigInt(data.budget), BigInt(data.seed)];
  return data.job === 'fit' ? new Fit(...args) : data.job === 'repair' ? new Repair(...args) : new Search(...args);
}

self.onmessage = async ({ data }) => {
  await ready;
  if (data.type === 'stop') { stopAsked = true; return; }
  if (data.type !== 'start') return;
  stopAsked = false;
  const job = data.job ?? 'search';
  let task;
  try {
    task = open(data);
  } catch (e) {
    self.postMessage({ type: 'error', message: e.message });
    return;
  }
  const start = performance.now();
  let searching = 0; // ms spent inside the search itself (rate = evaluations / searching)
  let stopped = false;
  const finish = (result) => {
    self.postMessage({ type: 'result', ...result, searchingMs: searching });
    task.free();
  };
  const slice = () => {
    try {
      const t0 = performance.now();
      let done = false;
      if (stopAsked && !stopped) { task.stop(); stopped = true; }
      // A stopped search ends at once; a stopped repair ends its box, then says it is done.
      while (!done && (job === 'repair' || !stopAsked) && performance.now() - t0 < SLICE_MS) done = task.run(1);
      if (job === 'search' && stopAsked && !done) done = true;
      if (job === 'fit' && stopAsked) done = true;
      searching += performance.now() - t0;
      self.postMessage({ type: 'progress', progress: JSON.parse(task.progress()), searchingMs: searching });
      if (!done) { setTimeout(slice, 0); return; }
      const seconds = (performance.now() - start) / 1000;
      if (job === 'search') {
        finish({ result: JSON.parse(task.result(seconds)), checkpoint: task.checkpoint() });
      } else if (job === 'fit') {
        self.postMessage({ type: 'progress', phase: 'refining', progress: JSON.parse(task.progress()), searchingMs: searching });
        task.refine(seconds);
        finish({ result: JSON.parse(task.result()) });
      } else {
        finish({ result: JSON.parse(task.result()) });
      }
    } catch (e) {
      self.postMessage({ type: 'error', message: e.message });
      task.free();
    }
  };
  slice();
};
