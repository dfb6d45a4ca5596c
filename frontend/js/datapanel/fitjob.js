// A fit job on the server (POST /api/fit/jobs): submit, poll, cancel, fetch results.
// Requests only, through api.js; the data panel (datapanel.js) owns the state and the view.

import { ApiError, deleteResource, getJSON, getText, postForm } from "../page/api.js";

const POLL_MS = 200;
const BUSY_RETRY_MS = 400; // 429: the server's fit workers are all taken
const BUSY_RETRIES = 50;

export function sleep(ms) {
  return new Promise((resolve) => { setTimeout(resolve, ms); });
}

export function jobUrl(id) {
  return `/api/fit/jobs/${encodeURIComponent(id)}`;
}

export function isActive(job) {
  return Boolean(job) && (job.status === "queued" || job.status === "running");
}

/** Ask the server to stop a job (it stops at its next checkpoint). */
export function cancelJob(id, keepalive = false) {
  return deleteResource(jobUrl(id), keepalive);
}

/** A bundled sample as a File to upload. */
export async function sampleFile(name, signal) {
  const text = await getText(`/api/samples/${encodeURIComponent(name)}.csv`, signal);
  return new File([text], `${name}.csv`, { type: "text/csv" });
}

/**
 * Upload `file` as a fit job; while every worker is busy (429) wait and retry, telling
 * `onWaiting()`. `isCurrent()` false ends the wait (the person started another fit).
 * Resolves to the job, or null when it is no longer current.
 */
export async function submitFit(file, kind, { signal, isCurrent, onWaiting }) {
  const form = new FormData();
  form.append("file", file, file.name || "upload.csv");
  if (kind) form.append("kind", kind);
  for (let attempt = 0; ; attempt += 1) {
    try {
      return await postForm("/api/fit/jobs", form, signal);
    } catch (error) {
      if (!(error instanceof ApiError && error.status === 429 && attempt < BUSY_RETRIES)) throw error;
      if (!isCurrent()) return null;
      onWaiting();
      await sleep(BUSY_RETRY_MS);
      if (!isCurrent()) return null;
    }
  }
}

/**
 * Poll `job` every POLL_MS until it is done, failed or cancelled, calling
 * `onUpdate(job)` with each state. Resolves to the last job, or null when it is no
 * longer current.
 */
export async function pollJob(job, { signal, isCurrent, onUpdate }) {
  let current = job;
  for (;;) {
    onUpdate(current);
    if (!isActive(current)) return current;
    await sleep(POLL_MS);
    if (!isCurrent()) return null;
    current = await getJSON(jobUrl(current.id), signal);
    if (!isCurrent()) return null;
  }
}

/** Every row's residuals of a finished job, as CSV text. */
export function residualsCsv(id) {
  return getText(`${jobUrl(id)}/residuals.csv`);
}
