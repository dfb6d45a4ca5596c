// The loop's runs off the page's main thread (loopmodel.js in a module worker), so that
// a drag keeps its frames while a run is made: {id, body, defaults} in, {id, result} out
// (result null when the run is the server's to make, or when it failed here: the
// server then says what is wrong).

import { loopExperiment } from "./loopmodel.js";

self.onmessage = ({ data: { id, body, defaults } }) => {
  let result;
  try {
    result = loopExperiment(body, defaults);
  } catch {
    result = null;
  }
  self.postMessage({ id, result });
};
