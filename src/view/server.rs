//! The live view's HTTP interface (axum on tokio), bound to 127.0.0.1 only.
//!
//! Every request must carry the session's token (`?token=…` or the header
//! `X-Iris-Token`) and a `Host` of 127.0.0.1 or localhost at the server's port (a page of
//! another site cannot reach it through DNS rebinding): otherwise 403. Routes:
//!
//! | route | answer |
//! |---|---|
//! | `GET /` | the page ([`super::page`]) |
//! | `GET /favicon.ico` | 204, no content, without the token (the page's icon is inline) |
//! | `GET /app.js`, `GET /style.css` | its script and style, compiled into the binary |
//! | `GET /choices` | the values each control accepts ([`super::controls::choices`]) |
//! | `GET /state` | the controls, the status, the newest frame, the subject, the live size |
//! | `GET /events` | server-sent events: `status`, `frame`, `final`, `bye` ([`super::session`]) |
//! | `GET /frame/{id}` | frame `id` as PNG, while kept (else 404) |
//! | `GET /final/{id}` | final render `id` as PNG |
//! | `POST /controls` | a JSON change (also `view`, `reset`, `pick`: [`Shared::change`]); 200 with the generation and the controls, 400 naming what is wrong |
//! | `POST /render` | `{"width", "height", "units"}`: renders, answers with the command line |
//!
//! Nothing else exists: every other path is 404, and no file is read from disk except the
//! scene (by the renderer) and the final render the server wrote itself.

use super::session::{Event, FinalRequest, Shared};
use axum::body::Body;
use axum::extract::{Path, Request, State};
use axum::http::{header, HeaderMap, StatusCode};
use axum::middleware::{self, Next};
use axum::response::sse::{self, KeepAlive, Sse};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::{Json, Router};
use serde_json::{json, Value};
use std::convert::Infallible;
use std::sync::Arc;
use tokio_stream::wrappers::BroadcastStream;
use tokio_stream::StreamExt;

/// What the handlers share.
#[derive(Clone)]
pub struct App {
    /// The session.
    pub shared: Arc<Shared>,
    /// The URL token.
    pub token: Arc<str>,
    /// The port served, for the Host check.
    pub port: u16,
}

/// The router with every route and the guard.
pub fn router(app: App) -> Router {
    Router::new()
        .route("/", get(|| async { super::page::asset("index.html") }))
        .route("/app.js", get(|| async { super::page::asset("app.js") }))
        .route(
            "/style.css",
            get(|| async { super::page::asset("style.css") }),
        )
        .route(
            "/choices",
            get(|| async { Json(super::controls::choices()) }),
        )
        .route("/state", get(state))
        .route("/events", get(events))
        .route("/frame/{id}", get(frame))
        .route("/final/{id}", get(final_image))
        .route("/controls", post(controls))
        .route("/render", post(render))
        .fallback(|| async { error(StatusCode::NOT_FOUND, "no such page") })
        .layer(middleware::from_fn_with_state(app.clone(), guard))
        .with_state(app)
}

/// A JSON error answer.
fn error(status: StatusCode, message: &str) -> Response {
    (status, Json(json!({"error": message}))).into_response()
}

/// The token and Host check of the module docs, before any route (`/favicon.ico`, which
/// browsers ask for without the token, needs only the Host).
async fn guard(State(app): State<App>, request: Request, next: Next) -> Response {
    let host_ok = request
        .headers()
        .get(header::HOST)
        .and_then(|h| h.to_str().ok())
        .is_some_and(|h| {
            [
                format!("127.0.0.1:{}", app.port),
                format!("localhost:{}", app.port),
            ]
            .iter()
            .any(|ok| ok == h)
        });
    if !host_ok {
        return error(StatusCode::FORBIDDEN, "this server answers 127.0.0.1 only");
    }
    if request.uri().path() == "/favicon.ico" {
        return StatusCode::NO_CONTENT.into_response();
    }
    let from_query = request.uri().query().and_then(|q| {
        q.split('&')
            .find_map(|kv| kv.strip_prefix("token="))
            .map(str::to_string)
    });
    let from_header = request
        .headers()
        .get("x-iris-token")
        .and_then(|h| h.to_str().ok())
        .map(str::to_string);
    let given = from_query.or(from_header).unwrap_or_default();
    if !same(given.as_bytes(), app.token.as_bytes()) {
        return error(
            StatusCode::FORBIDDEN,
            "missing or wrong token: open the URL iris view printed",
        );
    }
    next.run(request).await
}

/// Equality of two byte strings in time independent of where they differ.
fn same(a: &[u8], b: &[u8]) -> bool {
    a.len() == b.len() && a.iter().zip(b).fold(0u8, |acc, (x, y)| acc | (x ^ y)) == 0
}

async fn state(State(app): State<App>) -> Json<Value> {
    Json(app.shared.snapshot())
}

async fn events(State(app): State<App>) -> impl IntoResponse {
    let receiver = app.shared.subscribe();
    let hello = Event {
        kind: "state",
        data: app.shared.snapshot().to_string(),
    };
    // A page that falls behind by more than the channel holds skips to the newest events.
    // The stream sends `bye` and ends at the `end` after it (so the graceful shutdown can
    // finish).
    let stream = tokio_stream::once(hello)
        .chain(BroadcastStream::new(receiver).filter_map(Result::ok))
        .take_while(|e| e.kind != "end")
        .map(|e| Ok::<_, Infallible>(sse::Event::default().event(e.kind).data(e.data)));
    Sse::new(stream).keep_alive(KeepAlive::default())
}

fn png_answer(bytes: Option<Arc<Vec<u8>>>, what: &str) -> Response {
    match bytes {
        Some(b) => (
            [
                (header::CONTENT_TYPE, "image/png"),
                (header::CACHE_CONTROL, "no-store"),
            ],
            Body::from(b.as_ref().clone()),
        )
            .into_response(),
        None => error(StatusCode::NOT_FOUND, &format!("no {what} with this id")),
    }
}

async fn frame(State(app): State<App>, Path(id): Path<String>) -> Response {
    match id.parse::<u64>() {
        Ok(id) => png_answer(app.shared.frame(id), "frame"),
        Err(_) => error(StatusCode::NOT_FOUND, "a frame id is a number"),
    }
}

async fn final_image(State(app): State<App>, Path(id): Path<String>) -> Response {
    match id.parse::<u64>() {
        Ok(id) => png_answer(app.shared.final_png(id), "final render"),
        Err(_) => error(StatusCode::NOT_FOUND, "a final render id is a number"),
    }
}

/// The body as JSON, or a 400 saying why not.
fn json_body(headers: &HeaderMap, body: &[u8]) -> Result<Value, Response> {
    let is_json = headers
        .get(header::CONTENT_TYPE)
        .and_then(|h| h.to_str().ok())
        .is_some_and(|t| t.starts_with("application/json"));
    if !is_json {
        return Err(error(
            StatusCode::UNSUPPORTED_MEDIA_TYPE,
            "send application/json",
        ));
    }
    serde_json::from_slice(body)
        .map_err(|e| error(StatusCode::BAD_REQUEST, &format!("bad JSON: {e}")))
}

async fn controls(State(app): State<App>, headers: HeaderMap, body: axum::body::Bytes) -> Response {
    let change = match json_body(&headers, &body) {
        Ok(v) => v,
        Err(r) => return r,
    };
    let shared = app.shared.clone();
    // The change parses the command line (and may read an environment map): off the
    // async workers.
    match tokio::task::spawn_blocking(move || shared.change(&change)).await {
        Ok(Ok((generation, controls))) => {
            Json(json!({"generation": generation, "controls": controls})).into_response()
        }
        Ok(Err(e)) => error(StatusCode::BAD_REQUEST, &e),
        Err(_) => error(StatusCode::INTERNAL_SERVER_ERROR, "the change failed"),
    }
}

/// Largest final render side and unit count the page may ask for.
const MAX_FINAL_SIDE: u64 = 8192;
const MAX_FINAL_UNITS: u64 = 1_000_000;

async fn render(State(app): State<App>, headers: HeaderMap, body: axum::body::Bytes) -> Response {
    let ask = match json_body(&headers, &body) {
        Ok(v) => v,
        Err(r) => return r,
    };
    let field = |key: &str, max: u64| -> Result<u32, Response> {
        ask.get(key)
            .and_then(Value::as_u64)
            .filter(|v| (1..=max).contains(v))
            .map(|v| v as u32)
            .ok_or_else(|| {
                error(
                    StatusCode::BAD_REQUEST,
                    &format!("{key}: expected a whole number from 1 to {max}"),
                )
            })
    };
    let (w, h, units) = match (
        field("width", MAX_FINAL_SIDE),
        field("height", MAX_FINAL_SIDE),
        field("units", MAX_FINAL_UNITS),
    ) {
        (Ok(w), Ok(h), Ok(u)) => (w, h, u),
        (Err(r), _, _) | (_, Err(r), _) | (_, _, Err(r)) => return r,
    };
    let (reply, answer) = tokio::sync::oneshot::channel();
    let request = FinalRequest {
        size: (w, h),
        units,
        reply,
    };
    if app.shared.final_render(request).is_err() {
        return error(StatusCode::CONFLICT, "a final render is already running");
    }
    match answer.await {
        Ok(Ok(v)) => Json(v).into_response(),
        Ok(Err(e)) => error(StatusCode::BAD_REQUEST, &e),
        Err(_) => error(StatusCode::SERVICE_UNAVAILABLE, "the server is stopping"),
    }
}
