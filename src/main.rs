use std::process::ExitCode;

fn main() -> ExitCode {
    xglyph::cli::run()
}
