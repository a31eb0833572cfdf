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
//! with a notice when fig2dev is not installed; `XGLYPH_BIN=<path>` times another build of
//! xglyph instead of this one. Reported: the median of 5 interleaved rounds
//! of wall time, and the CPU time (user + system) of each command summed over the rounds;
//! each round runs `xglyph svg` into a new folder (2,001 files written, every contour
//! fitted: no fit cache there yet), `xglyph svg` into that folder again (every file already
//! holds its bytes, so none is written, and the fits come from the fit cache the first run
//! left there), and `fig2dev`.
//!
//! Each round writes into a folder no earlier round used (`out-<round>`), and the folders
//! are deleted only once every round is timed. Deleting the last round's 2,001 files just
//! before the next round's made the new folder's files slow to create on this machine's
//! ext4 (no journal): its inode allocator checks whether each free inode it meets was
//! freed in the last seconds (`recently_deleted`, from the kernel's perf profile) and
//! skips those, so the first run paid 1.0 to 1.4 s of system time instead of 0.14 s. The
//! stress font is written over in place (same names, so no file is deleted); only the
//! folders of an interrupted earlier run are deleted before the rounds.

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
    // Written over in place (see the module docs: no file deleted before the rounds).
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

/// CPU time (user + system) of the waited-for children of this process so far, from
/// `/proc/self/stat` (`cutime`, `cstime`, in clock ticks of 1/100 s); zero elsewhere.
fn children_cpu() -> Duration {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    // The fields after the command name (which is in parentheses and may hold spaces):
    // state is field 3, cutime and cstime fields 16 and 17.
    let rest = stat.rsplit_once(')').map_or("", |(_, rest)| rest);
    let ticks: u64 = rest
        .split_whitespace()
        .skip(13)
        .take(2)
        .filter_map(|t| t.parse::<u64>().ok())
        .sum();
    Duration::from_millis(ticks * 10)
}

/// Wall time and CPU time (user + system) of one run of `cmd` (which must succeed).
fn time(mut cmd: Command) -> (Duration, Duration) {
    let cpu = children_cpu();
    let start = Instant::now();
    let status = cmd
        .stdout(Stdio::null())
        .status()
        .expect("the command starts");
    let wall = start.elapsed();
    assert!(status.success(), "{status}");
    (wall, children_cpu() - cpu)
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
    let out = |round: usize| dir.join(format!("out-{round}"));
    // Only after an interrupted run: see the module docs.
    let _ = std::fs::remove_dir_all(dir.join("out"));
    for round in 0..RUNS {
        let _ = std::fs::remove_dir_all(out(round));
    }
    let (font, fig) = generate(&dir);
    // Another build to compare (as `benches/cjk.sh` takes it), or this one.
    let xglyph = std::env::var_os("XGLYPH_BIN")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_BIN_EXE_xglyph")));
    let threads = std::env::var("RAYON_NUM_THREADS").unwrap_or_else(|_| "all".into());
    // Interleaved: one run of each per round, so load changes hit both alike.
    let svg_out = dir.join("fig.svg");
    let (mut fresh, mut again, mut theirs) = (Vec::new(), Vec::new(), Vec::new());
    for round in 0..RUNS {
        for times in [&mut fresh, &mut again] {
            let mut c = Command::new(&xglyph);
            c.arg("svg").arg(&font).arg("-o").arg(out(round));
            times.push(time(c));
        }
        let mut c = Command::new("fig2dev");
        c.args(["-L", "svg"]).arg(&fig).arg(&svg_out);
        theirs.push(time(c));
    }
    for round in 0..RUNS {
        let _ = std::fs::remove_dir_all(out(round));
    }
    // Median wall time (ms) and summed CPU time (s).
    let stats = |v: Vec<(Duration, Duration)>| {
        let cpu: Duration = v.iter().map(|t| t.1).sum();
        let mut wall: Vec<Duration> = v.iter().map(|t| t.0).collect();
        wall.sort();
        (wall[RUNS / 2].as_secs_f64() * 1e3, cpu.as_secs_f64())
    };
    let ((a, a_cpu), (r, r_cpu), (b, b_cpu)) = (stats(fresh), stats(again), stats(theirs));
    // A ratio of CPU times only when fig2dev's is measurable (1/100 s ticks).
    let cpu_ratio = |x: f64| {
        if b_cpu > 0.0 {
            format!("{:>6.2} x", x / b_cpu)
        } else {
            "     - ".into()
        }
    };
    println!(
        "fig2dev: {GLYPHS} random {POINTS}-point closed X-splines (threads: {threads}; {})\n\
         \x20                            wall, median of {RUNS}       CPU, sum of {RUNS}\n\
         \x20 xglyph svg, new folder    {a:>8.1} ms {:>6.2} x    {a_cpu:>6.2} s {}\n\
         \x20 xglyph svg, same again   {r:>8.1} ms {:>6.2} x    {r_cpu:>6.2} s {}\n\
         \x20 fig2dev -L svg           {b:>8.1} ms             {b_cpu:>6.2} s\n\
         \x20 (target: xglyph at most 3 x fig2dev; rounds interleaved, each into a new folder)",
        xglyph.display(),
        a / b,
        cpu_ratio(a_cpu),
        r / b,
        cpu_ratio(r_cpu),
    );
}
