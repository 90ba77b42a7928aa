//! `iris view SCENE`: the scene rendered live in a browser (a local web server and its
//! page), as a library call.
//!
//! - The scene is prepared once before the server starts, so a bad file fails here with
//!   the renderer's own error and nothing listens.
//! - The server ([`server`]) listens on 127.0.0.1 only and answers only requests carrying
//!   the random token of the URL it prints (128 bits from the operating system).
//! - The page ([`page`]) orbits, zooms and pans the camera about a pivot, the scene's
//!   subject (the stones, [`aim`]), and sends each change as controls ([`controls`]); the
//!   render thread ([`session`]) cancels the running render and starts the new one, showing
//!   frames as they refine.
//! - Every render the view makes is an `iris render` command line parsed by the command
//!   line's own parser ([`crate::cli::parse_render`]): the camera is
//!   `--camera-look-at EYE:TARGET:FOV` (exact `f32` text), the model's turn `--turn F/360`,
//!   so the final render's printed command reproduces its image bit for bit.
//! - Ctrl-C (the process-wide stop request, [`crate::render::guard`]) stops the server: the
//!   render stops after its tile in flight, every open event stream gets a last `bye`
//!   event, the thread is joined.
//!
//! Units: the camera in scene units and degrees; image sizes in pixels.

pub mod aim;
pub mod controls;
mod encode;
pub mod page;
pub mod server;
pub mod session;
mod status;

use crate::error::{Error, Result};
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Duration;

/// `iris view`'s flags.
#[derive(Debug, Clone)]
pub struct ViewOptions {
    /// The scene file, as given (the printed commands repeat it).
    pub scene: PathBuf,
    /// Port on 127.0.0.1; 0 lets the system choose a free one.
    pub port: u16,
    /// Open a browser on the URL (`$BROWSER`, else `xdg-open`) when one is there.
    pub open: bool,
    /// Width of the live image, pixels (the height from the camera's aspect).
    pub width: u32,
    /// Worker threads (0: all cores).
    pub threads: usize,
    /// Directory of the final renders.
    pub out_dir: PathBuf,
}

/// Runs the view until Ctrl-C: prepares the scene, listens, prints the URL, serves.
pub fn view_command(opts: &ViewOptions) -> Result<()> {
    let scene = opts.scene.display().to_string();
    let (home, preview_size, subject) = aim::home(&scene, 0, opts.width)?;
    if !opts.out_dir.is_dir() {
        return Err(Error::Usage(format!(
            "--out-dir {}: not a directory",
            opts.out_dir.display()
        )));
    }
    crate::fileio::output::check_dir(&opts.out_dir)?;
    let setup = session::Setup {
        scene,
        preview_size,
        threads: opts.threads,
        out_dir: opts.out_dir.clone(),
        subject,
    };
    let shared = session::Shared::new(setup, controls::Controls::new(home.camera, home.pivot));
    // While serving, a signal shuts the server down gracefully (`serve`).
    let _honour = crate::interrupt::Honour::begin();
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .map_err(|e| Error::Usage(format!("cannot start the web server's runtime: {e}")))?;
    runtime.block_on(serve(shared, opts))
}

async fn serve(shared: Arc<session::Shared>, opts: &ViewOptions) -> Result<()> {
    let address = std::net::SocketAddr::from(([127, 0, 0, 1], opts.port));
    let listener = tokio::net::TcpListener::bind(address)
        .await
        .map_err(|e| Error::Usage(format!("cannot listen on {address}: {e}")))?;
    let port = listener
        .local_addr()
        .map_err(|e| Error::Usage(format!("cannot read the listening port: {e}")))?
        .port();
    let token: Arc<str> = token()?.into();
    let url = format!("http://127.0.0.1:{port}/?token={token}");
    println!("iris view: {url}");
    println!("iris view: Ctrl-C stops the server");
    use std::io::Write;
    let _ = std::io::stdout().flush();
    if opts.open {
        open_browser(&url);
    }
    let thread = {
        let shared = shared.clone();
        std::thread::Builder::new()
            .name("iris-view-render".into())
            .spawn(move || shared.run())
            .map_err(|e| Error::Usage(format!("cannot start the render thread: {e}")))?
    };
    let app = server::App {
        shared: shared.clone(),
        token,
        port,
    };
    let stopping = {
        let shared = shared.clone();
        async move {
            while !crate::render::guard::stop_requested() {
                tokio::time::sleep(Duration::from_millis(100)).await;
            }
            // The event streams end with `bye`, so the graceful shutdown can finish.
            shared.shut_down();
        }
    };
    let served = axum::serve(listener, server::router(app))
        .with_graceful_shutdown(stopping)
        .await;
    shared.shut_down();
    let _ = thread.join();
    served.map_err(|e| Error::Usage(format!("the web server failed: {e}")))?;
    println!("iris view: stopped");
    Ok(())
}

/// 128 random bits from the operating system, as 32 hex digits.
fn token() -> Result<String> {
    use std::io::Read;
    let mut bytes = [0u8; 16];
    std::fs::File::open("/dev/urandom")
        .and_then(|mut f| f.read_exact(&mut bytes))
        .map_err(|e| Error::Usage(format!("cannot read /dev/urandom for the token: {e}")))?;
    Ok(bytes.iter().map(|b| format!("{b:02x}")).collect())
}

/// Starts `$BROWSER URL` or `xdg-open URL` in the background; says so when neither runs.
fn open_browser(url: &str) {
    let browser = std::env::var("BROWSER").unwrap_or_else(|_| "xdg-open".into());
    let started = std::process::Command::new(&browser)
        .arg(url)
        .stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn();
    if started.is_err() {
        println!("iris view: no browser started ({browser}); open the URL above");
    }
}
