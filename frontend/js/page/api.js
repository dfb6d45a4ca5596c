// Requests to the explorer API. Errors carry the server's 422 detail so the page can
// show them at the field they name.

export class ApiError extends Error {
  constructor(status, detail) {
    const first = Array.isArray(detail) && detail.length ? detail[0] : null;
    super(first ? first.msg : `HTTP ${status}`);
    this.status = status;
    this.detail = Array.isArray(detail) ? detail : [];
  }

  /** {field: message} of the errors that name a body field. */
  fieldErrors() {
    const errors = {};
    for (const item of this.detail) {
      const loc = item.loc ?? [];
      if (loc[0] === "body" && typeof loc[1] === "string") errors[loc[1]] = item.msg;
    }
    return errors;
  }
}

async function failure(response) {
  let detail = [];
  try {
    detail = (await response.json()).detail;
  } catch {
    // not JSON: keep the status only
  }
  if (typeof detail === "string") detail = [{ msg: detail }];
  return new ApiError(response.status, detail);
}

async function request(url, options) {
  const response = await fetch(url, options);
  if (!response.ok) throw await failure(response);
  return response.json();
}

/** POST a multipart form; the JSON answer. */
export function postForm(url, form, signal) {
  return request(url, { method: "POST", body: form, signal });
}

/** GET a text resource (a CSV). */
export async function getText(url, signal) {
  const response = await fetch(url, { signal });
  if (!response.ok) throw await failure(response);
  return response.text();
}

/** DELETE, never failing (a job that is gone is as good as cancelled). */
export function deleteResource(url, keepalive = false) {
  return fetch(url, { method: "DELETE", keepalive }).catch(() => null);
}

/** POST a JSON body; the JSON answer. `priority` "low" for requests made ahead of need. */
export function postJSON(url, body, signal, priority = "auto") {
  return request(url, {
    method: "POST",
    headers: { "Content-Type": "application/json" },
    body: JSON.stringify(body),
    signal,
    priority,
  });
}

export function getJSON(url, signal) {
  return request(url, { signal });
}
