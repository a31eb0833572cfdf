//! `xglyph serve`: the studio, a local web editor with live preview.

use std::net::IpAddr;
use std::path::PathBuf;
use std::process::ExitCode;

use super::build::print_diagnostic;
use super::CommandError;
use crate::serve::{Server, StartError};
use crate::terminal::{errln, outln};

#[derive(Debug, clap::Args)]
#[command(after_help = "\
Opens a local web page with every glyph, a text line set in the live font and a point
editor. Edits are written to the glyph's TOML file at once (only the numbers that change);
saving a file in any editor updates every open page. The API is in docs/serve.md.

Examples:
  xglyph serve                    # glyphs/ at http://127.0.0.1:7878/ (or the next free port)
  xglyph serve my-font --open     # and open it in the default browser
  xglyph serve --port 9000")]
pub struct ServeArgs {
    /// Font directory (font.toml and one TOML file per glyph).
    #[arg(default_value = "glyphs")]
    pub font_dir: PathBuf,
    /// Port (default: 7878 or the next free one; 0 lets the system choose).
    #[arg(long)]
    pub port: Option<u16>,
    /// Address to listen on. Anything but loopback exposes the sources to the network.
    #[arg(long, default_value = "127.0.0.1")]
    pub host: IpAddr,
    /// Open the page in the default browser.
    #[arg(long)]
    pub open: bool,
}

pub fn run(args: ServeArgs) -> Result<ExitCode, CommandError> {
    if !args.host.is_loopback() {
        errln!(
            "warning: listening on {}: anyone who can reach this machine can read and edit \
             the sources in {}",
            args.host,
            args.font_dir.display()
        );
    }
    let server = match Server::start(&args.font_dir, args.host, args.port) {
        Ok(server) => server,
        Err(StartError::Sources(diags)) => {
            diags.iter().for_each(print_diagnostic);
            return Err(format!(
                "{} has errors; fix them and start the studio again",
                args.font_dir.display()
            )
            .into());
        }
        Err(StartError::Other(e)) => return Err(e.to_string().into()),
    };
    // The handler first: once the URL is printed, Ctrl-C must stop cleanly.
    ctrlc::set_handler(server.stopper())?;
    let url = server.url();
    outln!(
        "xglyph studio: {} at {url} (Ctrl-C stops)",
        args.font_dir.display()
    );
    if args.open {
        open_browser(&url);
    }
    server.run();
    outln!("stopped");
    Ok(ExitCode::SUCCESS)
}

/// Opens `url` with the desktop's opener; a failure is a warning (the URL is printed).
fn open_browser(url: &str) {
    let opener = if cfg!(target_os = "macos") {
        "open"
    } else if cfg!(windows) {
        "explorer"
    } else {
        "xdg-open"
    };
    if let Err(e) = std::process::Command::new(opener).arg(url).spawn() {
        errln!("warning: cannot open a browser ({opener}: {e}); open {url} yourself");
    }
}
