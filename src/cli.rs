//! The command line: clap definitions only; each command lives in [`crate::commands`].

use std::process::ExitCode;

use clap::{Parser, Subcommand};

use crate::commands;

/// xglyph: X-spline glyph sources to Bézier outlines, PNG proofs, SVG and OpenType fonts.
#[derive(Debug, Parser)]
#[command(name = "xglyph", version, about, long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Build everything (sheet, proof, SVG glyph set, SVG font, TTF/OTF) into OUT.
    Build(commands::build::BuildArgs),
    /// Validate the sources; every problem as file:line:col.
    Check(commands::check::CheckArgs),
    /// Rewrite the sources in the canonical layout.
    Fmt(commands::fmt::FmtArgs),
    /// Render a glyph sheet or a text proof to PNG.
    Render(commands::render::RenderArgs),
    /// Write the SVG glyph set and the SVG font.
    Svg(commands::svg::SvgArgs),
    /// Turn existing outlines (TTF/OTF fonts, SVG drawings) into X-spline sources.
    Import(commands::import::ImportArgs),
    /// Edit the font in the browser, with live preview of every saved change.
    Serve(commands::serve::ServeArgs),
}

/// Parses the command line, runs the command, prints errors; the process exit code.
pub fn run() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Build(args) => commands::build::run(args),
        Command::Check(args) => commands::check::run(args),
        Command::Fmt(args) => commands::fmt::run(args),
        Command::Render(args) => commands::render::run(args),
        Command::Svg(args) => commands::svg::run(args),
        Command::Import(args) => commands::import::run(args),
        Command::Serve(args) => commands::serve::run(args),
    };
    match result {
        Ok(code) => code,
        Err(err) => {
            crate::terminal::errln!("error: {err}");
            ExitCode::FAILURE
        }
    }
}
