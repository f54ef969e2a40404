// JSON requests to the app's API, and the one reading of a refusal: a 422's first detail (its message and where it
// points, `loc`), or the detail text. Errors carry the status, the field named last in `loc`, and every detail.
export class ApiError extends Error {
  constructor(status, data, statusText) {
    const details = Array.isArray(data.detail) ? data.detail : [{ msg: data.detail || statusText, loc: [] }];
    super(details[0].msg);
    this.status = status;
    this.details = details;
    this.loc = details[0].loc || [];
    this.field = this.loc.length ? this.loc[this.loc.length - 1] : null;
  }
}

export async function api(method, url, body, headers = {}) {
  const response = await fetch(url, {
    method,
    headers: { "Content-Type": "application/json", ...headers },
    body: body === undefined ? undefined : JSON.stringify(body),
  });
  const data = await response.json().catch(() => ({}));
  if (!response.ok) throw new ApiError(response.status, data, response.statusText);
  return data;
}

// A random 128-bit id in hex: a page session's id, or the key that claims it.
export const randomId = () => Array.from(crypto.getRandomValues(new Uint8Array(16)), (b) => b.toString(16).padStart(2, "0")).join("");
