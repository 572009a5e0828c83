// REST calls to the gateway, with the token (when the page was opened with ?token=...) on every request;
// the WebSocket and downloads use the session cookie the token is traded for (see `loggedIn`).

const TOKEN_KEY = "wana.token";

function readToken() {
  const params = new URLSearchParams(location.search);
  const fromUrl = params.get("token");
  if (fromUrl) {
    sessionStorage.setItem(TOKEN_KEY, fromUrl);
    params.delete("token");
    const query = params.toString();
    history.replaceState(null, "", location.pathname + (query ? `?${query}` : "") + location.hash);
  }
  return sessionStorage.getItem(TOKEN_KEY) || "";
}

export const token = readToken();

// The WebSocket and download links cannot send the header: trade the token for the gateway's
// short-lived HttpOnly session cookie once (it never goes into a URL, so never into a log).
export const loggedIn = token
  ? fetch(apiUrl("/api/session"), { method: "POST", headers: { Authorization: `Bearer ${token}` } })
  : Promise.resolve();

export function authHeaders() {
  return token ? { Authorization: `Bearer ${token}` } : {};
}

/** Absolute URL of a gateway path (the page is served by the gateway, possibly under a prefix). */
export function apiUrl(path) {
  return new URL(path.replace(/^\//, ""), new URL(".", location.href)).toString();
}

/** The WebSocket URL of a document, resuming from `version` when given. */
export function liveUrl(docId, version) {
  const url = new URL(apiUrl(`/api/documents/${encodeURIComponent(docId)}/live`));
  url.protocol = url.protocol === "https:" ? "wss:" : "ws:";
  if (version !== null && version !== undefined) url.searchParams.set("version", String(version));
  url.searchParams.set("wire", "binary"); // animation messages as binary frames, characters as patches
  return url.toString();
}

async function call(method, path, body) {
  const response = await fetch(apiUrl(path), {
    method,
    headers: { ...authHeaders(), ...(body !== undefined ? { "Content-Type": "application/json" } : {}) },
    body: body !== undefined ? JSON.stringify(body) : undefined,
  });
  if (!response.ok) {
    let message = `${response.status} ${response.statusText}`;
    try {
      const detail = (await response.json()).detail;
      message = detail?.message || (typeof detail === "string" ? detail : message);
    } catch {
      /* not JSON */
    }
    const error = new Error(message);
    error.status = response.status;
    throw error;
  }
  return response.status === 204 ? null : response.json();
}

export const listDocuments = () => call("GET", "/api/documents");
export const createDocument = (text = "", title = "") => call("POST", "/api/documents", { text, title });
export const deleteDocument = (docId) => call("DELETE", `/api/documents/${encodeURIComponent(docId)}`);
export const renameDocument = (docId, title) => call("PATCH", `/api/documents/${encodeURIComponent(docId)}`, { title });
export const getDocument = (docId) => call("GET", `/api/documents/${encodeURIComponent(docId)}`);

/** An export's bytes (ArrayBuffer), e.g. scene.glb with the director's camera; throws on failure. */
export async function fetchExport(docId, format) {
  const response = await fetch(apiUrl(`/api/documents/${encodeURIComponent(docId)}/export/${format}`), {
    headers: authHeaders(),
  });
  if (!response.ok) throw new Error(`${format.toUpperCase()} export failed (${response.status})`);
  return response.arrayBuffer();
}

/**
 * Render the MP4 as a job on the gateway (services/gateway/videojobs.py): `onProgress(status)` with the frames
 * rendered of the total as they grow; resolves to a message for the status line once the file is downloaded,
 * cancelled (`signal`: the job is deleted, and rendering stops on the server) or failed.
 */
export async function exportVideo(docId, onProgress, signal, params = {}) {
  const base = apiUrl(`/api/documents/${encodeURIComponent(docId)}/export/mp4/jobs`);
  const search = new URLSearchParams(params).toString();
  const started = await fetch(search ? `${base}?${search}` : base, { method: "POST", headers: authHeaders() });
  if (!started.ok) return `MP4 export failed (${started.status})`;
  let status = await started.json();
  const url = `${base}/${status.job_id}`;
  const cancel = () => fetch(url, { method: "DELETE", headers: authHeaders() }).catch(() => {});
  signal?.addEventListener("abort", cancel, { once: true });
  try {
    while (status.state === "running") {
      onProgress(status);
      await new Promise((resolve) => setTimeout(resolve, 250));
      const response = await fetch(url, { headers: authHeaders() });
      if (!response.ok) return `MP4 export failed (${response.status})`;
      status = await response.json();
    }
    onProgress(status);
    if (status.state !== "done") return status.state === "cancelled" ? "MP4 cancelled" : status.message || "MP4 export failed";
    return await downloadExport(docId, `mp4/jobs/${status.job_id}/file`, "", signal, {}, "MP4");
  } finally {
    signal?.removeEventListener("abort", cancel);
  }
}

/** Download an export; resolves to a message for the status line. */
export async function downloadExport(docId, format, character = "", signal = undefined, params = {}, label = format.toUpperCase()) {
  const search = new URLSearchParams({ ...(character ? { character } : {}), ...params }).toString();
  const query = search ? `?${search}` : "";
  let response;
  try {
    response = await fetch(apiUrl(`/api/documents/${encodeURIComponent(docId)}/export/${format}${query}`), {
      headers: authHeaders(),
      signal,
    });
  } catch (err) {
    if (err.name === "AbortError") return `${label} cancelled`;
    throw err;
  }
  if (!response.ok) {
    let message = `${label} export failed (${response.status})`;
    try {
      message = (await response.json()).detail?.message || message;
    } catch {
      /* not JSON */
    }
    return message;
  }
  const blob = await response.blob();
  const name = /filename="([^"]+)"/.exec(response.headers.get("Content-Disposition") || "")?.[1] || `wana.${format}`;
  const link = document.createElement("a");
  link.href = URL.createObjectURL(blob);
  link.download = name;
  link.click();
  setTimeout(() => URL.revokeObjectURL(link.href), 10000);
  return `saved ${name}`;
}

/** The document's own characters (story name -> {bytes, mapped}). */
export const listCast = (docId) => call("GET", `/api/documents/${encodeURIComponent(docId)}/cast`);
export const deleteCast = (docId, name) =>
  call("DELETE", `/api/documents/${encodeURIComponent(docId)}/cast/${encodeURIComponent(name)}`);

/** Upload a .glb/.vrm to play the story character `name`; resolves to the server's answer or throws. */
export async function putCast(docId, name, file) {
  const response = await fetch(apiUrl(`/api/documents/${encodeURIComponent(docId)}/cast/${encodeURIComponent(name)}`), {
    method: "PUT",
    headers: { ...authHeaders(), "Content-Type": "application/octet-stream" },
    body: file,
  });
  if (!response.ok) {
    let message = `upload failed (${response.status})`;
    try {
      message = (await response.json()).detail?.message || message;
    } catch {
      /* not JSON */
    }
    throw new Error(message);
  }
  return response.json();
}
