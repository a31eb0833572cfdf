//! One file per subcommand: arguments (clap) and the glue from library calls to files.
//!
//! Every `run` returns the exit code, or an error that `cli` prints (exit code 1).

use std::path::PathBuf;

pub mod build;
pub mod check;
pub mod fmt;
pub mod import;
pub mod render;
pub mod serve;
pub mod svg;

/// The error type of command glue: library errors already carry file and place.
pub type CommandError = Box<dyn std::error::Error>;

/// What every command that fits a font takes: the font, where to write, how exactly.
#[derive(Debug, clap::Args)]
pub struct FontArgs {
    /// Font directory (font.toml and one TOML file per glyph).
    #[arg(default_value = "glyphs")]
    pub font_dir: PathBuf,
    /// Output directory (created if needed).
    #[arg(short, long, default_value = "out")]
    pub out: PathBuf,
    /// Fitting tolerance in font units; overrides `tolerance` in font.toml.
    #[arg(long, value_name = "T")]
    pub tolerance: Option<f64>,
}
