// The loop's runs off the page's main thread (loopmodel.js in a module worker), so that
// a drag keeps its frames while a run is made: {id, body, defaults} in, {id, result} out
// (result null when the run is the server's to make).

import { loopExperiment } from "./loopmodel.js";

self.onmessage = ({ data: { id, body, defaults } }) => {
  self.postMessage({ id, result: loopExperiment(body, defaults) });
};
