//! `iris view`: over HTTP without a browser, and in headless Chromium.

#[path = "../common/mod.rs"]
mod common;

mod view;
mod view_browser;
