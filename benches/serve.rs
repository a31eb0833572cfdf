//! The studio's loop through the real server (`xglyph serve` as a process), on glyph `o`
//! of the bundled typeface in a temporary copy:
//!
//! - file save -> the SSE event, and -> the new outline fetched (what a page does);
//! - an API edit's answer (move one point, written and refitted);
//! - the server's CPU time while idle with a page connected (file events, no polling);
//! - references in the same run: `xglyph build` of a one-glyph font (process start, load,
//!   fit, write), and a raw `fs::write` of the same file.
//!
//! Run: `cargo bench --bench serve` (prints medians and ratios; no Criterion: each sample is
//! a round trip through a child process, and the figures are latencies, not throughput).

use std::fs;
use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::path::Path;
use std::process::{Command, Stdio};
use std::sync::mpsc::channel;
use std::time::{Duration, Instant};

use serde_json::{json, Value};

const SAMPLES: usize = 40;

fn main() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("glyphs");
    fs::create_dir(&dir).unwrap();
    for entry in fs::read_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join("glyphs")).unwrap() {
        let path = entry.unwrap().path();
        fs::copy(&path, dir.join(path.file_name().unwrap())).unwrap();
    }
    let mut child = Command::new(env!("CARGO_BIN_EXE_xglyph"))
        .args(["serve", "--port", "0"])
        .arg(&dir)
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    let mut line = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    let port: u16 = line
        .split("http://127.0.0.1:")
        .nth(1)
        .and_then(|r| r.split('/').next())
        .and_then(|p| p.parse().ok())
        .expect("the server prints its URL");

    // The event stream, read on its own thread: (arrival time, message).
    let mut sse = TcpStream::connect(("127.0.0.1", port)).unwrap();
    write!(
        sse,
        "GET /api/events HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n\r\n"
    )
    .unwrap();
    let (tx, events) = channel();
    std::thread::spawn(move || {
        for line in BufReader::new(sse).lines().map_while(Result::ok) {
            if let Some(data) = line.strip_prefix("data: ") {
                let msg: Value = serde_json::from_str(data).unwrap();
                let _ = tx.send((Instant::now(), msg));
            }
        }
    });
    std::thread::sleep(Duration::from_millis(200));

    let path = dir.join("o.toml");
    let original = fs::read_to_string(&path).unwrap();
    let mut to_event = Vec::new();
    let mut to_outline = Vec::new();
    let mut raw_write = Vec::new();
    for k in 0..SAMPLES {
        let text = original.replace(
            "[275, -12, -1]",
            &format!("[275, {}, -1]", -12 - (k as i64 % 7) - 1),
        );
        let start = Instant::now();
        fs::write(&path, &text).unwrap();
        raw_write.push(start.elapsed());
        let (at, msg) = events
            .recv_timeout(Duration::from_secs(5))
            .expect("an event");
        assert_eq!(msg["changed"][0], "o", "{msg}");
        to_event.push(at - start);
        let glyph = request(port, "GET", "/api/glyph/o", "");
        assert!(glyph.contains(&format!("[275.0,{}.0,-1.0]", -12 - (k as i64 % 7) - 1)));
        to_outline.push(start.elapsed());
        std::thread::sleep(Duration::from_millis(30));
    }
    fs::write(&path, &original).unwrap();
    let _ = events.recv_timeout(Duration::from_secs(5));

    let mut edit = Vec::new();
    for k in 0..SAMPLES {
        let glyph: Value = serde_json::from_str(&request(port, "GET", "/api/glyph/o", "")).unwrap();
        let body = json!({"version": glyph["version"], "ops": [
            {"op": "move", "contour": 0, "point": 1, "x": 477 + (k % 5) as i64 + 1, "y": 25.38}
        ]});
        let start = Instant::now();
        let answer = request(port, "POST", "/api/glyph/o/edit", &body.to_string());
        edit.push(start.elapsed());
        assert!(answer.contains("\"version\""), "{answer}");
        while events.recv_timeout(Duration::from_millis(30)).is_ok() {}
    }

    // Idle: a page connected, nothing happening.
    let cpu_before = cpu_ticks(child.id());
    std::thread::sleep(Duration::from_secs(3));
    let idle_ticks = cpu_ticks(child.id()) - cpu_before;

    // References: building a one-glyph font (a fresh process), and the raw write above.
    let one = tmp.path().join("one");
    fs::create_dir(&one).unwrap();
    fs::copy(dir.join("font.toml"), one.join("font.toml")).unwrap();
    fs::write(one.join("o.toml"), &original).unwrap();
    let mut build = Vec::new();
    for _ in 0..10 {
        let start = Instant::now();
        let out = Command::new(env!("CARGO_BIN_EXE_xglyph"))
            .arg("build")
            .arg(&one)
            .arg("-o")
            .arg(tmp.path().join("out"))
            .output()
            .unwrap();
        build.push(start.elapsed());
        assert!(out.status.success());
    }
    let _ = child.kill();
    let _ = child.wait();

    let ms = |d: Duration| d.as_secs_f64() * 1000.0;
    let (event, outline, edit, build, write) = (
        median(&mut to_event),
        median(&mut to_outline),
        median(&mut edit),
        median(&mut build),
        median(&mut raw_write),
    );
    println!("studio (glyph o, {SAMPLES} samples each, medians):");
    println!(
        "  file save -> SSE event           {:7.2} ms  ({:.2}x build of one glyph)",
        ms(event),
        ms(event) / ms(build)
    );
    println!(
        "  file save -> event + new outline {:7.2} ms  ({:.2}x build of one glyph)",
        ms(outline),
        ms(outline) / ms(build)
    );
    println!(
        "  API edit answer (move a point)   {:7.2} ms  ({:.2}x build of one glyph)",
        ms(edit),
        ms(edit) / ms(build)
    );
    println!("  reference: xglyph build, 1 glyph {:7.2} ms", ms(build));
    println!("  reference: fs::write of o.toml   {:7.3} ms", ms(write));
    println!(
        "  idle CPU over 3 s (page connected): {idle_ticks} ticks of 1/{} s",
        clock_ticks()
    );
}

fn median(v: &mut [Duration]) -> Duration {
    v.sort();
    v[v.len() / 2]
}

/// User + system CPU time of a process, in clock ticks (`/proc/<pid>/stat`, Linux).
fn cpu_ticks(pid: u32) -> u64 {
    let stat = fs::read_to_string(format!("/proc/{pid}/stat")).unwrap_or_default();
    let after = stat.rsplit_once(')').map_or("", |(_, r)| r);
    let fields: Vec<&str> = after.split_whitespace().collect();
    // Fields 14 and 15 of stat (utime, stime) are 12 and 13 after the command name.
    let get = |i: usize| {
        fields
            .get(i)
            .and_then(|f| f.parse::<u64>().ok())
            .unwrap_or(0)
    };
    get(11) + get(12)
}

fn clock_ticks() -> u64 {
    Command::new("getconf")
        .arg("CLK_TCK")
        .output()
        .ok()
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .and_then(|s| s.trim().parse().ok())
        .unwrap_or(100)
}

/// One HTTP request; the body of the answer.
fn request(port: u16, method: &str, path: &str, body: &str) -> String {
    let mut s = TcpStream::connect(("127.0.0.1", port)).unwrap();
    write!(
        s,
        "{method} {path} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nContent-Type: application/json\r\n\
         Content-Length: {}\r\nConnection: close\r\n\r\n{body}",
        body.len()
    )
    .unwrap();
    let mut text = String::new();
    s.read_to_string(&mut text).unwrap();
    text.split_once("\r\n\r\n")
        .map(|(_, b)| b.to_string())
        .unwrap_or_default()
}
