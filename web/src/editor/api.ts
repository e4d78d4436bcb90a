// The workspace's REST routes and the run routes, as the page calls them (same origin: the
// token, when there is one, travels in its cookie). Every answer that is not a success becomes an
// ApiError carrying the status and the server's own words.

import type {
  Deleted, FileText, LaunchGroupOut, LaunchRequest, PackageCreated, PackageRequest, Renamed, RenameRequest,
  RunRequest, Saved, SaveRequest, Template, WorkspaceTree, Written,
} from "../protocol.gen";

/** A refused or failed request: its HTTP status (0: no answer at all) and what the server said. */
export class ApiError extends Error {
  constructor(readonly status: number, readonly detail: string, readonly body: unknown = null) {
    super(status ? `${status}: ${detail}` : detail);
  }
}

const detailOf = (body: unknown, fallback: string): string => {
  if (body && typeof body === "object" && "detail" in body) {
    const detail = body.detail;
    if (typeof detail === "string") return detail;
    if (Array.isArray(detail)) {
      return detail.map((d) => (d && typeof d === "object" && "msg" in d ? String((d as { msg: unknown }).msg) : JSON.stringify(d))).join("; ");
    }
    return JSON.stringify(detail);
  }
  return fallback;
};

async function call<T>(method: string, url: string, init: RequestInit = {}): Promise<T> {
  let response: Response;
  try {
    response = await fetch(url, { ...init, method, credentials: "same-origin", cache: "no-store" });
  } catch (exc) {
    throw new ApiError(0, `no answer from the server (${String(exc)})`);
  }
  const text = await response.text();
  let body: unknown;
  try { body = text ? JSON.parse(text) : null; } catch { body = text; }
  if (!response.ok) throw new ApiError(response.status, detailOf(body, text || response.statusText), body);
  return body as T;
}

const json = <T>(body: T, headers: Record<string, string> = {}): RequestInit => ({
  body: JSON.stringify(body), headers: { "content-type": "application/json", ...headers },
});

/** A workspace path in a URL: each segment escaped, the slashes kept. */
export const fileUrl = (path: string): string =>
  "/api/workspace/files/" + path.split("/").map(encodeURIComponent).join("/");

export const workspace = {
  tree: (): Promise<WorkspaceTree> => call("GET", "/api/workspace/files"),
  read: (path: string): Promise<FileText> => call("GET", fileUrl(path)),
  /** Save over ``etag`` (the version this page last saw); null: create, refused if it exists. */
  write: (path: string, text: string, etag: string | null): Promise<Saved> =>
    call("PUT", fileUrl(path), json<SaveRequest>({ text }, etag === null ? { "If-None-Match": "*" } : { "If-Match": etag })),
  remove: (path: string): Promise<Deleted> => call("DELETE", fileUrl(path)),
  rename: (source: string, target: string): Promise<Renamed> =>
    call("POST", "/api/workspace/rename", json<RenameRequest>({ source, target })),
  createPackage: (request: PackageRequest): Promise<PackageCreated> =>
    call("POST", "/api/workspace/packages", json(request)),
  templates: (): Promise<Template[]> => call("GET", "/api/workspace/templates"),
  archiveUrl: "/api/workspace/archive",
  upload: (zip: Blob): Promise<Written> =>
    call("POST", "/api/workspace/archive", { body: zip, headers: { "content-type": "application/zip" } }),
};

export const runs = {
  run: (pkg: string, executable: string): Promise<LaunchGroupOut> =>
    call("POST", "/api/run", json<RunRequest>({ package: pkg, executable })),
  launch: (pkg: string, file: string): Promise<LaunchGroupOut> =>
    call("POST", "/api/launch", json<LaunchRequest>({ package: pkg, file, args: {} })),
  stop: (id: string): Promise<LaunchGroupOut> => call("DELETE", `/api/launches/${encodeURIComponent(id)}`),
  outputSocket: (id: string): WebSocket =>
    new WebSocket(`${location.protocol === "https:" ? "wss" : "ws"}://${location.host}/ws/launches/${encodeURIComponent(id)}/output`),
};
