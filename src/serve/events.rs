//! Server-Sent Events: every open page gets one `data: {...}` message per reload.
//!
//! Each stream has its own thread, blocked on a channel until a message comes (no timer,
//! no polling). A stream whose page has gone is found at the next message: its write fails,
//! its thread ends, and the hub drops its channel.

use std::io::Write;
use std::sync::mpsc::{channel, Sender};
use std::sync::Mutex;

/// The open event streams.
#[derive(Default)]
pub struct Hub {
    streams: Mutex<Vec<Sender<String>>>,
}

impl Hub {
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
                match rx.recv() {
                    Ok(data) => ok = send(&mut writer, &data),
                    Err(_) => break,
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
