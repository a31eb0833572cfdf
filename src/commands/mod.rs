//! One file per subcommand: arguments (clap) and the glue from library calls to files.
//!
//! Every `run` returns the exit code, or an error that `cli` prints (exit code 1).

pub mod build;
pub mod check;
pub mod fmt;
pub mod import;
pub mod render;
pub mod svg;

/// The error type of command glue: library errors already carry file and place.
pub type CommandError = Box<dyn std::error::Error>;
