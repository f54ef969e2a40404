// JSON requests to the app's API, and the one reading of a refusal: a 422's first detail (its message and where it
// points, `loc`), or the detail text. Errors carry the status, the field named last in `loc`, and every detail.
export class ApiError extends Error {
  constructor(status, data, statusText, retryAfterS = null) {
    const details = Array.isArray(data.detail) ? data.detail : [{ msg: data.detail || statusText, loc: [] }];
    super(details[0].msg);
    this.status = status;
    this.details = details;
    this.loc = details[0].loc || [];
    this.field = this.loc.length ? this.loc[this.loc.length - 1] : null;
    // A busy server (429, 503) says when to ask again (Retry-After, s); null when it did not.
    this.retryAfterS = retryAfterS;
  }
}

export async function api(method, url, body, headers = {}) {
  const response = await fetch(url, {
    method,
    headers: { "Content-Type": "application/json", ...headers },
    body: body === undefined ? undefined : JSON.stringify(body),
  });
  const data = await response.json().catch(() => ({}));
  if (!response.ok) {
    const retryAfter = Number(response.headers.get("Retry-After"));
    throw new ApiError(response.status, data, response.statusText, Number.isFinite(retryAfter) && retryAfter > 0 ? retryAfter : null);
  }
  return data;
}

// A request that may be sent again unchanged (setting a scene's parameters, solving an example): when the server is
// busy (429 or 503 with Retry-After) it waits as the server says (1 to 10 s) and asks again, up to `attempts` times,
// telling `onWait(seconds)` each time; any other refusal, or the last busy one, is thrown as it came.
export async function apiPatient(method, url, body, headers = {}, { attempts = 5, onWait = () => {} } = {}) {
  for (let attempt = 1; ; attempt++) {
    try {
      return await api(method, url, body, headers);
    } catch (err) {
      const busy = err instanceof ApiError && (err.status === 429 || err.status === 503) && err.retryAfterS !== null;
      if (!busy || attempt >= attempts) throw err;
      const waitS = Math.min(10, Math.max(1, err.retryAfterS));
      onWait(waitS);
      await new Promise((resolve) => setTimeout(resolve, 1000 * waitS));
    }
  }
}

// A random 128-bit id in hex: a page session's id, or the key that claims it.
export const randomId = () => Array.from(crypto.getRandomValues(new Uint8Array(16)), (b) => b.toString(16).padStart(2, "0")).join("");
