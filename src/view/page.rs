//! The page the live view serves: HTML, script and style compiled into the binary (no
//! CDN, no network), from `src/view/page/`.

use axum::http::header;
use axum::response::{IntoResponse, Response};

/// The asset `name` with its content type (the router only asks for the three that exist).
pub fn asset(name: &str) -> Response {
    let (body, kind) = match name {
        "app.js" => (
            include_str!("page/app.js"),
            "text/javascript; charset=utf-8",
        ),
        "style.css" => (include_str!("page/style.css"), "text/css; charset=utf-8"),
        _ => (include_str!("page/index.html"), "text/html; charset=utf-8"),
    };
    (
        [
            (header::CONTENT_TYPE, kind),
            (header::CACHE_CONTROL, "no-store"),
        ],
        body,
    )
        .into_response()
}
