//! The studio: `xglyph serve`, a local web editor over the font folder.
//!
//! The TOML files stay the only source of truth. A small synchronous HTTP server
//! (`tiny_http`; a local tool needs no async runtime) serves an embedded page, a JSON API
//! and a stream of Server-Sent Events. The folder is watched (`watch.rs`); a change reloads
//! the font, refits only the glyphs it touched (`state.rs`) and tells every open page. An
//! edit from the page rewrites only the numbers it changes (`edit.rs`), is checked by the
//! normal loader and written atomically; an edit made against an older version of the file
//! is refused (409). The API is documented in `docs/serve.md`.
//!
//! Limits: one font folder (not its subfolders); the sources must load when the server
//! starts (later errors are shown while the last good font is served); requests are
//! answered one at a time, which an editor used by one person never notices.

mod assets;
mod edit;
mod events;
mod http;
mod state;
mod watch;

use std::net::{IpAddr, Ipv4Addr, SocketAddr};
use std::path::Path;
use std::sync::{Arc, Mutex};

use serde_json::json;

pub use edit::{apply as apply_edit, EditError, Op};
pub use http::MAX_BODY;
pub use state::{version, Reload, Studio};

use crate::source::Diagnostic;

/// The error type of starting a server.
pub type ServeError = Box<dyn std::error::Error + Send + Sync>;

/// The port tried first when none is given; the next free one is taken if it is busy.
pub const DEFAULT_PORT: u16 = 7878;

/// How many ports from [`DEFAULT_PORT`] on are tried.
const PORTS_TRIED: u16 = 100;

/// Why a server did not start.
#[derive(Debug)]
pub enum StartError {
    /// The sources have errors (all of them, as `check` reports them).
    Sources(Vec<Diagnostic>),
    /// The address could not be bound, or the folder not watched.
    Other(ServeError),
}

/// A running studio: bound, watching, ready to answer.
pub struct Server {
    http: Arc<tiny_http::Server>,
    ctx: http::Context,
    addr: SocketAddr,
    _watcher: notify::RecommendedWatcher,
}

impl Server {
    /// Loads `dir`, binds `host` on `port` (or the first free port from [`DEFAULT_PORT`]
    /// when `None`; 0 lets the system choose), and starts watching the folder.
    pub fn start(dir: &Path, host: IpAddr, port: Option<u16>) -> Result<Server, StartError> {
        let studio = Studio::open(dir).map_err(StartError::Sources)?;
        let http = bind(host, port).map_err(StartError::Other)?;
        let addr = http
            .server_addr()
            .to_ip()
            .ok_or_else(|| StartError::Other("the server has no IP address".into()))?;
        let studio = Arc::new(Mutex::new(studio));
        let hub = Arc::new(events::Hub::default());
        let watcher =
            watch::watch(dir, Arc::clone(&studio), Arc::clone(&hub)).map_err(StartError::Other)?;
        let mut hosts: Vec<String> = ["localhost", "127.0.0.1", "[::1]"]
            .iter()
            .map(|h| format!("{h}:{}", addr.port()))
            .collect();
        if !host.is_loopback() && !host.is_unspecified() {
            hosts.push(SocketAddr::new(host, addr.port()).to_string());
        }
        Ok(Server {
            http: Arc::new(http),
            ctx: http::Context { studio, hub, hosts },
            addr,
            _watcher: watcher,
        })
    }

    /// The address the server listens on.
    pub fn addr(&self) -> SocketAddr {
        self.addr
    }

    /// The page's URL (`http://127.0.0.1:7878/`; a wildcard address is shown as localhost).
    pub fn url(&self) -> String {
        let ip = if self.addr.ip().is_unspecified() {
            IpAddr::V4(Ipv4Addr::LOCALHOST)
        } else {
            self.addr.ip()
        };
        format!("http://{}/", SocketAddr::new(ip, self.addr.port()))
    }

    /// A function that makes [`Server::run`] return (for a Ctrl-C handler).
    pub fn stopper(&self) -> impl Fn() + Send + 'static {
        let http = Arc::clone(&self.http);
        move || http.unblock()
    }

    /// Answers requests until the stopper is called.
    pub fn run(&self) {
        while let Ok(rq) = self.http.recv() {
            http::handle(rq, &self.ctx);
        }
    }
}

/// Binds `host:port`, or the first free port from [`DEFAULT_PORT`].
fn bind(host: IpAddr, port: Option<u16>) -> Result<tiny_http::Server, ServeError> {
    if let Some(port) = port {
        return tiny_http::Server::http(SocketAddr::new(host, port))
            .map_err(|e| format!("cannot listen on {}: {e}", SocketAddr::new(host, port)).into());
    }
    let last = DEFAULT_PORT + PORTS_TRIED - 1;
    (DEFAULT_PORT..=last)
        .find_map(|p| tiny_http::Server::http(SocketAddr::new(host, p)).ok())
        .ok_or_else(|| format!("no free port on {host} from {DEFAULT_PORT} to {last}").into())
}

/// The event to broadcast after a reload: `{"changed": [...]}` when glyphs changed,
/// `{"errors": [...]}` when the sources are broken, nothing when nothing changed (nor
/// when the errors are the ones already announced).
pub(crate) fn reload_message(outcome: &Reload) -> Option<String> {
    match outcome {
        Reload::Changed { names, fixed } if names.is_empty() && !fixed => None,
        Reload::Changed { names, .. } => Some(json!({ "changed": names }).to_string()),
        Reload::Errors(errors) if errors.is_empty() => None,
        Reload::SameErrors => None,
        Reload::Errors(errors) => {
            let errors: Vec<_> = errors.iter().map(state::diagnostic_json).collect();
            Some(json!({ "errors": errors }).to_string())
        }
    }
}
