//! `xglyph svg` against `fig2dev -L svg` on the same 2,000 random closed X-splines
//! (issue 15, item 8), timed in one run so that the ratio holds on a loaded machine.
//!
//! The stress font: 2,000 glyphs of one contour each, 12 control points on a star-shaped
//! polygon (random radius at sorted random angles, so the control polygon does not cross
//! itself) with random shape factors `s ∈ [-1, 1]`, from a fixed seed. The same X-splines
//! go into an xfig 3.2 file as closed X-splines (sub-type 5), y flipped, with the shape
//! factor mapped: our `q = -s/2` for `s < 0` is xfig's `q = -s`, so a negative `s` is
//! written as `s/2`; `s ≥ 0` is the same in both.
//!
//! xglyph does more than fig2dev (Béziers within a guaranteed 0.5-unit bound, one SVG file
//! per glyph plus an SVG font, against one polyline file), so the target is a ratio: xglyph
//! at most 3 × fig2dev on the whole command. Run: `cargo bench --bench fig2dev`; it skips
//! with a notice when fig2dev is not installed. Reported: the median of 5 interleaved rounds,
//! each one `xglyph svg` into an empty folder, one into the same folder again (every file
//! already holds its bytes, so none is written), and one `fig2dev`.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const GLYPHS: usize = 2000;
const POINTS: usize = 12;
const RUNS: usize = 5;

// xorshift64*, so the font is the same on every machine: the corpus's generator.
#[path = "../tests/it/common/corpus.rs"]
#[allow(dead_code)]
mod corpus;
use corpus::Rng;

/// One random contour: `(x, y, s)` in font units (y up), 1000 per em.
fn contour(rng: &mut Rng) -> Vec<(f64, f64, f64)> {
    let mut angles: Vec<f64> = (0..POINTS)
        .map(|k| (k as f64 + 0.1 + 0.8 * rng.next()) / POINTS as f64 * std::f64::consts::TAU)
        .collect();
    angles.sort_by(f64::total_cmp);
    angles
        .into_iter()
        .map(|a| {
            let r = 150.0 + 250.0 * rng.next();
            let s = (2.0 * rng.next() - 1.0).clamp(-1.0, 1.0);
            // Whole units, as a designer writes them; s to two decimals.
            (
                (500.0 + r * a.cos()).round(),
                (400.0 + r * a.sin()).round(),
                (s * 100.0).round() / 100.0,
            )
        })
        .collect()
}

/// Writes the stress font (`dir/font/`) and the xfig file (`dir/stress.fig`).
fn generate(dir: &Path) -> (PathBuf, PathBuf) {
    let font = dir.join("font");
    let _ = std::fs::remove_dir_all(dir);
    std::fs::create_dir_all(&font).expect("create the stress font folder");
    std::fs::write(
        font.join("font.toml"),
        "family = \"Stress\"\nstyle = \"Regular\"\nunits_per_em = 1000\nascender = 800\n\
         descender = -200\nx_height = 500\ncap_height = 700\ntolerance = 0.5\n",
    )
    .expect("write font.toml");
    let mut fig = String::from(
        "#FIG 3.2  xglyph stress font\nLandscape\nCenter\nInches\nLetter\n100.00\nSingle\n-2\n\
         1200 2\n",
    );
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    for g in 0..GLYPHS {
        let points = contour(&mut rng);
        let list: Vec<String> = points
            .iter()
            .map(|(x, y, s)| format!("[{x}, {y}, {s}]"))
            .collect();
        let toml = format!(
            "name = \"g{g:04}\"\nadvance = 1000\n\n[[contour]]\npoints = [{}]\n",
            list.join(", ")
        );
        std::fs::write(font.join(format!("g{g:04}.toml")), toml).expect("write a glyph");
        // Glyphs side by side in a 50-wide grid, 1 font unit = 1 xfig unit, y down.
        let (ox, oy) = ((g % 50) as f64 * 1000.0, (g / 50) as f64 * 1000.0);
        let _ = writeln!(fig, "3 5 0 1 0 7 50 -1 -1 0.000 0 0 0 {POINTS}");
        fig.push('\t');
        for (x, y, _) in &points {
            let _ = write!(fig, " {} {}", (ox + x) as i64, (oy + 1000.0 - y) as i64);
        }
        fig.push_str("\n\t");
        for (_, _, s) in &points {
            let xfig_s = if *s < 0.0 { s / 2.0 } else { *s };
            let _ = write!(fig, " {xfig_s:.3}");
        }
        fig.push('\n');
    }
    let fig_path = dir.join("stress.fig");
    std::fs::write(&fig_path, fig).expect("write the xfig file");
    (font, fig_path)
}

/// Wall time of one run of `cmd` (which must succeed).
fn time(mut cmd: Command) -> Duration {
    let start = Instant::now();
    let status = cmd
        .stdout(Stdio::null())
        .status()
        .expect("the command starts");
    assert!(status.success(), "{status}");
    start.elapsed()
}

fn main() {
    let fig2dev_ok = Command::new("fig2dev")
        .arg("-V")
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok();
    if !fig2dev_ok {
        println!("fig2dev: skipped (fig2dev is not installed; apt-get install fig2dev)");
        return;
    }
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("fig2dev-bench");
    let (font, fig) = generate(&dir);
    let out = dir.join("out");
    let xglyph = env!("CARGO_BIN_EXE_xglyph");
    let threads = std::env::var("RAYON_NUM_THREADS").unwrap_or_else(|_| "all".into());
    // Interleaved: one run of each per round, so load changes hit both alike.
    let svg_out = dir.join("fig.svg");
    // xglyph twice a round: into an empty folder (2,001 new files), then again into the
    // same folder (the files hold their bytes already, so nothing is written).
    let (mut fresh, mut again, mut theirs) = (Vec::new(), Vec::new(), Vec::new());
    for _ in 0..RUNS {
        let _ = std::fs::remove_dir_all(&out);
        for times in [&mut fresh, &mut again] {
            let mut c = Command::new(xglyph);
            c.arg("svg").arg(&font).arg("-o").arg(&out);
            times.push(time(c));
        }
        let mut c = Command::new("fig2dev");
        c.args(["-L", "svg"]).arg(&fig).arg(&svg_out);
        theirs.push(time(c));
    }
    let median = |mut v: Vec<Duration>| {
        v.sort();
        v[RUNS / 2].as_secs_f64() * 1e3
    };
    let (a, r, b) = (median(fresh), median(again), median(theirs));
    println!(
        "fig2dev: {GLYPHS} random {POINTS}-point closed X-splines (threads: {threads})\n\
         \x20 xglyph svg, empty folder  {a:>8.1} ms (median of {RUNS}, interleaved)  {:>6.2} x\n\
         \x20 xglyph svg, same folder   {r:>8.1} ms                                {:>6.2} x\n\
         \x20 fig2dev -L svg            {b:>8.1} ms (target: xglyph at most 3 x)",
        a / b,
        r / b,
    );
}
