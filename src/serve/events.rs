//! Server-Sent Events: every open page gets one `data: {...}` message per reload.
//!
//! Each stream has its own thread, blocked on a channel until a message comes. Without
//! messages it writes a comment line every [`HEARTBEAT`]: a stream whose page has gone is
//! found by a failed write (at the latest at the second heartbeat after the page left), its
//! thread ends, and the hub drops its channel at the next broadcast. Without the heartbeat,
//! every reload of a page while no file changed left a thread and a socket behind.

use std::io::Write;
use std::sync::mpsc::{channel, RecvTimeoutError, Sender};
use std::sync::Mutex;
use std::time::Duration;

/// How long a stream stays silent before it writes a comment line (and so learns whether
/// its page is still there).
pub const HEARTBEAT: Duration = Duration::from_secs(15);

/// The open event streams.
pub struct Hub {
    streams: Mutex<Vec<Sender<String>>>,
    heartbeat: Duration,
}

impl Default for Hub {
    fn default() -> Hub {
        Hub::with_heartbeat(HEARTBEAT)
    }
}

impl Hub {
    /// A hub whose streams write a comment line after `heartbeat` of silence.
    pub fn with_heartbeat(heartbeat: Duration) -> Hub {
        Hub {
            streams: Mutex::default(),
            heartbeat,
        }
    }

    /// Sends `data` (one line of JSON) to every open stream.
    pub fn broadcast(&self, data: &str) {
        if let Ok(mut streams) = self.streams.lock() {
            streams.retain(|s| s.send(data.to_string()).is_ok());
        }
    }

    /// Answers an event-stream request on its raw connection: the response head, then
    /// `first` (the current errors, if any) and every later broadcast, until the page goes.
    pub fn subscribe(&self, mut writer: Box<dyn Write + Send>, first: Option<String>) {
        let (tx, rx) = channel::<String>();
        if let Ok(mut streams) = self.streams.lock() {
            streams.push(tx);
        }
        let heartbeat = self.heartbeat;
        std::thread::spawn(move || {
            let head = "HTTP/1.1 200 OK\r\nContent-Type: text/event-stream\r\n\
                        Cache-Control: no-cache\r\nConnection: close\r\n\r\n";
            // A comment line first, so that the page's EventSource opens at once.
            let mut ok = writer.write_all(head.as_bytes()).is_ok()
                && writer.write_all(b": xglyph studio\n\n").is_ok();
            if let Some(data) = first {
                ok = ok && send(&mut writer, &data);
            }
            ok = ok && writer.flush().is_ok();
            while ok {
                match rx.recv_timeout(heartbeat) {
                    Ok(data) => ok = send(&mut writer, &data),
                    Err(RecvTimeoutError::Timeout) => {
                        ok = writer
                            .write_all(b":\n\n")
                            .and_then(|()| writer.flush())
                            .is_ok();
                    }
                    Err(RecvTimeoutError::Disconnected) => break,
                }
            }
        });
    }
}

/// Writes one event and flushes it; whether the page is still there.
fn send(writer: &mut Box<dyn Write + Send>, data: &str) -> bool {
    writer
        .write_all(format!("data: {data}\n\n").as_bytes())
        .and_then(|()| writer.flush())
        .is_ok()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicBool, Ordering};
    use std::sync::Arc;
    use std::time::Instant;

    /// A connection: what was written, until the page "goes" (then every write fails).
    struct Page {
        written: Arc<Mutex<Vec<u8>>>,
        gone: Arc<AtomicBool>,
    }

    impl Write for Page {
        fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
            if self.gone.load(Ordering::SeqCst) {
                return Err(std::io::ErrorKind::BrokenPipe.into());
            }
            self.written.lock().unwrap().extend_from_slice(buf);
            Ok(buf.len())
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }

    #[test]
    fn a_silent_stream_beats_and_ends_when_its_page_has_gone() {
        let hub = Hub::with_heartbeat(Duration::from_millis(20));
        let written = Arc::new(Mutex::new(Vec::new()));
        let gone = Arc::new(AtomicBool::new(false));
        let page = Page {
            written: Arc::clone(&written),
            gone: Arc::clone(&gone),
        };
        hub.subscribe(Box::new(page), None);
        hub.broadcast("{\"changed\": []}");
        std::thread::sleep(Duration::from_millis(150));
        let text = String::from_utf8(written.lock().unwrap().clone()).unwrap();
        let body = text.split("\r\n\r\n").nth(1).unwrap();
        assert!(
            body.starts_with(": xglyph studio\n\ndata: {\"changed\": []}\n\n:\n\n:\n\n"),
            "{body:?}"
        );
        // The page goes: the next heartbeat fails, the stream's thread ends and drops the
        // connection (the only other holder of `written`).
        gone.store(true, Ordering::SeqCst);
        let start = Instant::now();
        while Arc::strong_count(&written) > 1 {
            assert!(
                start.elapsed() < Duration::from_secs(5),
                "the stream's thread lives on"
            );
            std::thread::sleep(Duration::from_millis(5));
        }
        // The hub forgets the stream at the next broadcast.
        hub.broadcast("{}");
        assert_eq!(hub.streams.lock().unwrap().len(), 0);
    }
}
