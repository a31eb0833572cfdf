//! The studio in a real browser: Debian's Chromium, headless, driven over the DevTools
//! protocol (a websocket, `tungstenite`) with real mouse and key events.
//!
//! Skipped with a printed notice when `/usr/bin/chromium` is missing, unless
//! `XGLYPH_REQUIRE_TOOLS=1` (CI), which makes it fail. The ignored test `screenshot`
//! writes `docs/studio.png` (run by `docs/regenerate.sh`).

use std::fs;
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use serde_json::{json, Value};
use tungstenite::stream::MaybeTlsStream;
use tungstenite::{Message, WebSocket};

use crate::serve::Studio;

const CHROMIUM: &str = "/usr/bin/chromium";
const WIDTH: u32 = 1400;
const HEIGHT: u32 = 860;

/// A headless Chromium with one page, attached over the DevTools protocol.
pub(crate) struct Browser {
    child: Child,
    ws: WebSocket<MaybeTlsStream<TcpStream>>,
    session: String,
    next_id: u64,
    _profile: tempfile::TempDir,
}

impl Browser {
    /// Starts Chromium, or `None` (with a notice) when it is not installed.
    pub(crate) fn start() -> Option<Browser> {
        if !Path::new(CHROMIUM).exists() {
            if std::env::var("XGLYPH_REQUIRE_TOOLS").as_deref() == Ok("1") {
                panic!("XGLYPH_REQUIRE_TOOLS=1 but {CHROMIUM} is missing; install chromium");
            }
            println!("skipped: {CHROMIUM} not installed; XGLYPH_REQUIRE_TOOLS=1 makes this fail");
            return None;
        }
        let profile = tempfile::tempdir().unwrap();
        let child = Command::new(CHROMIUM)
            .args([
                "--headless",
                "--no-sandbox",
                "--disable-gpu",
                "--no-first-run",
                "--disable-background-networking",
                "--disable-component-update",
                "--disable-sync",
                "--hide-scrollbars",
                "--remote-debugging-port=0",
                &format!("--window-size={WIDTH},{HEIGHT}"),
            ])
            .arg(format!("--user-data-dir={}", profile.path().display()))
            .arg("about:blank")
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        let port_file = profile.path().join("DevToolsActivePort");
        let started = Instant::now();
        let text = loop {
            if let Ok(text) = fs::read_to_string(&port_file) {
                if text.lines().count() >= 2 {
                    break text;
                }
            }
            assert!(
                started.elapsed() < Duration::from_secs(60),
                "Chromium did not start"
            );
            std::thread::sleep(Duration::from_millis(50));
        };
        let mut lines = text.lines();
        let (port, path) = (lines.next().unwrap(), lines.next().unwrap());
        let (ws, _) = tungstenite::connect(format!("ws://127.0.0.1:{port}{path}")).unwrap();
        let mut browser = Browser {
            child,
            ws,
            session: String::new(),
            next_id: 0,
            _profile: profile,
        };
        let target = browser.call("Target.createTarget", json!({"url": "about:blank"}));
        let attached = browser.call(
            "Target.attachToTarget",
            json!({"targetId": target["targetId"], "flatten": true}),
        );
        browser.session = attached["sessionId"].as_str().unwrap().to_string();
        browser.call(
            "Emulation.setDeviceMetricsOverride",
            json!({"width": WIDTH, "height": HEIGHT, "deviceScaleFactor": 1, "mobile": false}),
        );
        Some(browser)
    }

    /// One DevTools command (on the page once attached); its result.
    fn call(&mut self, method: &str, params: Value) -> Value {
        self.next_id += 1;
        let id = self.next_id;
        let mut msg = json!({"id": id, "method": method, "params": params});
        if !self.session.is_empty() {
            msg["sessionId"] = json!(self.session);
        }
        self.ws.send(Message::Text(msg.to_string().into())).unwrap();
        loop {
            let Message::Text(text) = self.ws.read().unwrap() else {
                continue;
            };
            let reply: Value = serde_json::from_str(&text).unwrap();
            if reply["id"] == id {
                assert!(reply["error"].is_null(), "{method}: {reply}");
                return reply["result"].clone();
            }
        }
    }

    /// Evaluates `expr` in the page (promises awaited); its value.
    pub(crate) fn eval(&mut self, expr: &str) -> Value {
        let r = self.call(
            "Runtime.evaluate",
            json!({"expression": expr, "returnByValue": true, "awaitPromise": true}),
        );
        assert!(r["exceptionDetails"].is_null(), "{expr}: {r}");
        r["result"]["value"].clone()
    }

    /// Waits until `expr` is true; the time it took.
    fn wait_for(&mut self, expr: &str, limit: Duration) -> Duration {
        let start = Instant::now();
        loop {
            if self.eval(expr) == json!(true) {
                return start.elapsed();
            }
            assert!(start.elapsed() < limit, "timed out waiting for {expr}");
            std::thread::sleep(Duration::from_millis(10));
        }
    }

    pub(crate) fn open(&mut self, url: &str) {
        self.open_until(url, "document.body && document.body.dataset.ready === '1'");
    }

    /// Opens `url` and waits until `ready` is true in it.
    pub(crate) fn open_until(&mut self, url: &str, ready: &str) {
        self.call("Page.navigate", json!({"url": url}));
        self.wait_for(ready, Duration::from_secs(60));
    }

    /// The centre of control point `c`.`i` on the screen, CSS pixels.
    fn point_on_screen(&mut self, c: usize, i: usize) -> (f64, f64) {
        let r = self.eval(&format!(
            "(() => {{ const r = document.querySelector('.pt[data-contour=\"{c}\"][data-index=\"{i}\"]')
                .getBoundingClientRect(); return [r.x + r.width / 2, r.y + r.height / 2]; }})()"
        ));
        (r[0].as_f64().unwrap(), r[1].as_f64().unwrap())
    }

    fn mouse(&mut self, kind: &str, (x, y): (f64, f64), buttons: u32) {
        self.call(
            "Input.dispatchMouseEvent",
            json!({"type": kind, "x": x, "y": y, "button": "left", "buttons": buttons,
                   "clickCount": 1}),
        );
    }

    /// Presses, moves in steps, releases: a real drag.
    fn drag(&mut self, from: (f64, f64), by: (f64, f64)) {
        self.mouse("mouseMoved", from, 0);
        self.mouse("mousePressed", from, 1);
        for k in 1..=8 {
            let t = f64::from(k) / 8.0;
            self.mouse("mouseMoved", (from.0 + by.0 * t, from.1 + by.1 * t), 1);
        }
        self.mouse("mouseReleased", (from.0 + by.0, from.1 + by.1), 0);
    }

    /// Presses and releases one key (no modifiers).
    fn key(&mut self, key: &str, code: &str, key_code: u32) {
        let text = if key.chars().count() == 1 { key } else { "" };
        for kind in ["keyDown", "keyUp"] {
            self.call(
                "Input.dispatchKeyEvent",
                json!({"type": kind, "key": key, "code": code, "text": text,
                       "windowsVirtualKeyCode": key_code}),
            );
        }
    }

    /// Two clicks in a row: a double-click.
    fn double_click(&mut self, (x, y): (f64, f64)) {
        self.mouse("mouseMoved", (x, y), 0);
        for count in [1, 2] {
            for kind in ["mousePressed", "mouseReleased"] {
                self.call(
                    "Input.dispatchMouseEvent",
                    json!({"type": kind, "x": x, "y": y, "button": "left",
                           "buttons": u32::from(kind == "mousePressed"), "clickCount": count}),
                );
            }
        }
    }

    /// Ctrl-Z, or Ctrl-Shift-Z with `shift`.
    fn undo_key(&mut self, shift: bool) {
        let modifiers = if shift { 2 | 8 } else { 2 };
        let key = if shift { "Z" } else { "z" };
        for kind in ["rawKeyDown", "keyUp"] {
            self.call(
                "Input.dispatchKeyEvent",
                json!({"type": kind, "modifiers": modifiers, "key": key, "code": "KeyZ",
                       "windowsVirtualKeyCode": 90}),
            );
        }
    }

    /// Waits until the page has no edit on its way.
    fn settle(&mut self) {
        self.wait_for(
            "studio.editor.pending === 0 && !studio.editor.drag",
            Duration::from_secs(30),
        );
    }

    fn screenshot(&mut self) -> Vec<u8> {
        use base64::Engine;
        let r = self.call("Page.captureScreenshot", json!({"format": "png"}));
        let data = r["data"].as_str().unwrap();
        base64::engine::general_purpose::STANDARD
            .decode(data)
            .unwrap()
    }
}

impl Drop for Browser {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// Lines of `a` and `b` that differ, by line number (0-based).
fn changed_lines(a: &str, b: &str) -> Vec<(usize, String, String)> {
    assert_eq!(a.lines().count(), b.lines().count());
    a.lines()
        .zip(b.lines())
        .enumerate()
        .filter(|(_, (x, y))| x != y)
        .map(|(n, (x, y))| (n, x.to_string(), y.to_string()))
        .collect()
}

#[test]
fn drag_watch_errors_and_undo() {
    let studio = Studio::start(|_| {});
    let Some(mut browser) = Browser::start() else {
        return;
    };
    let path: PathBuf = studio.file("o.toml");
    let original = fs::read_to_string(&path).unwrap();
    browser.open(&format!("http://{}/#/glyph/o", studio.host()));
    browser.wait_for(
        "document.querySelectorAll('.pt').length === 16",
        Duration::from_secs(30),
    );

    // 1. Drag control point 0.1 ([477.1, 25.38, 1]) by (+40, -30) pixels.
    let scale = browser.eval("studio.editor.view.s").as_f64().unwrap();
    let from = browser.point_on_screen(0, 1);
    browser.drag(from, (40.0, -30.0));
    browser.settle();
    let dragged = fs::read_to_string(&path).unwrap();
    let x = (477.1 + 40.0 / scale).round();
    let y = (25.38 + 30.0 / scale).round();
    assert_eq!(
        changed_lines(&original, &dragged),
        vec![(
            7,
            "  [477.1, 25.38, 1],".to_string(),
            format!("  [{x}, {y}, 1],")
        )]
    );

    // 2. A save on disk shows in the drawing within 1 s.
    let saved = dragged.replace("[275, -12, -1]", "[275, -40, -1]");
    fs::write(&path, &saved).unwrap();
    let took = browser.wait_for(
        "document.querySelector('.pt[data-contour=\"0\"][data-index=\"0\"]')?.dataset.y === '-40'",
        Duration::from_secs(1),
    );
    println!("disk save to redrawn point: {} ms", took.as_millis());
    let (_, y0) = browser.point_on_screen(0, 0);
    let (_, y2) = browser.point_on_screen(0, 4);
    // Screen y = -y * scale + ty, from the canvas's top edge.
    let view = browser.eval(
        "[studio.editor.view.s, studio.editor.view.ty + \
          document.getElementById('canvas').getBoundingClientRect().top]",
    );
    let (s, ty) = (view[0].as_f64().unwrap(), view[1].as_f64().unwrap());
    assert!((y0 - (40.0 * s + ty)).abs() < 1.0, "point drawn at y {y0}");
    assert!(
        (y2 - (-522.0 * s + ty)).abs() < 1.0,
        "point drawn at y {y2}"
    );

    // 3. A broken file: the error text appears; fixing it clears it.
    let broken = saved.replace("advance = 550", "advance = \"wide\"");
    fs::write(&path, &broken).unwrap();
    let message = format!(
        "{}:3:11: error: `advance` must be a number, found string",
        path.display()
    );
    browser.wait_for(
        &format!(
            "document.getElementById('errors').textContent.includes({})",
            json!(message)
        ),
        Duration::from_secs(5),
    );
    assert_eq!(browser.eval("document.querySelectorAll('.pt').length"), 16);
    fs::write(&path, &saved).unwrap();
    browser.wait_for(
        "document.getElementById('errors').hidden",
        Duration::from_secs(5),
    );

    // 4. Drag another point, undo with Ctrl-Z: the file is back byte for byte; redo.
    browser.wait_for(
        &format!(
            "studio.editor.glyph.version === {}",
            json!(xglyph::serve::version(saved.as_bytes()))
        ),
        Duration::from_secs(5),
    );
    let from = browser.point_on_screen(1, 2);
    browser.drag(from, (-25.0, 15.0));
    browser.settle();
    let redone = fs::read_to_string(&path).unwrap();
    assert_eq!(changed_lines(&saved, &redone).len(), 1);
    assert_eq!(changed_lines(&saved, &redone)[0].0, 20);
    browser.undo_key(false);
    browser.settle();
    assert_eq!(fs::read(&path).unwrap(), saved.as_bytes());
    browser.undo_key(true);
    browser.settle();
    assert_eq!(fs::read_to_string(&path).unwrap(), redone);

    // 5. Keys: select a point, `0` makes it a corner, Delete removes it; a double-click on
    // an edge inserts a point there; three undos give the file back byte for byte.
    let p = browser.point_on_screen(1, 0);
    browser.mouse("mouseMoved", p, 0);
    browser.mouse("mousePressed", p, 1);
    browser.mouse("mouseReleased", p, 0);
    browser.key("0", "Digit0", 48);
    browser.settle();
    let corner = fs::read_to_string(&path).unwrap();
    assert_eq!(
        changed_lines(&redone, &corner),
        vec![(18, "  [275, 60, -1],".into(), "  [275, 60, 0],".into())]
    );
    browser.key("Delete", "Delete", 46);
    browser.settle();
    let deleted = fs::read_to_string(&path).unwrap();
    assert_eq!(deleted, corner.replace("  [275, 60, 0],\n", ""));
    let (a, b) = (browser.point_on_screen(0, 2), browser.point_on_screen(0, 3));
    let mid = ((a.0 + b.0) / 2.0, (a.1 + b.1) / 2.0);
    browser.double_click(mid);
    browser.settle();
    let inserted = fs::read_to_string(&path).unwrap();
    let new_line = inserted.lines().nth(9).unwrap().to_string();
    assert_eq!(inserted.lines().count(), deleted.lines().count() + 1);
    assert!(new_line.ends_with(", 1],"), "{new_line}");
    assert_eq!(inserted.replace(&format!("{new_line}\n"), ""), deleted);
    for _ in 0..3 {
        browser.undo_key(false);
        browser.settle();
    }
    assert_eq!(fs::read_to_string(&path).unwrap(), redone);
}

/// Writes `docs/studio.png`: the editor on `g` with a point selected, the text line above.
#[test]
#[ignore = "writes docs/studio.png; run by docs/regenerate.sh"]
fn screenshot() {
    let studio = Studio::start(|_| {});
    let Some(mut browser) = Browser::start() else {
        return;
    };
    browser.open(&format!("http://{}/#/glyph/g", studio.host()));
    browser.eval("document.getElementById('sample').value = 'Hamburgefonstiv AVATAR ragged'; studio.drawLine(); true");
    let from = browser.point_on_screen(0, 3);
    browser.mouse("mouseMoved", from, 0);
    browser.mouse("mousePressed", from, 1);
    browser.mouse("mouseReleased", from, 0);
    browser.settle();
    browser.mouse("mouseMoved", (from.0 + 60.0, from.1 + 40.0), 0);
    let png = browser.screenshot();
    let out = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/studio.png");
    fs::write(&out, png).unwrap();
    println!("wrote {}", out.display());
}
