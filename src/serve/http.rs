//! Requests to answers: routing, the safety checks, and the JSON API.
//!
//! Every request first passes the Host check (a defence against DNS rebinding: a page on
//! another site that resolves its own name to 127.0.0.1 sends its own name as Host).
//! Edits must be `application/json` (a cross-site form cannot send that without a CORS
//! preflight, which this server never grants) and, when the browser says where they come
//! from (`Origin`), come from the studio itself. No path is ever built from request text:
//! glyph names are looked up in the loaded font, which knows each glyph's file.

use std::io::Read;
use std::sync::{Arc, Mutex};

use serde::Deserialize;
use serde_json::{json, Value};
use tiny_http::{Header, Method, Request, Response};

use super::assets;
use super::edit::{apply, EditError, Op};
use super::events::Hub;
use super::reload_message;
use super::state::{diagnostic_json, version, Reload, Studio};
use crate::write::write_atomic;

/// The largest request body accepted (1 MB).
pub const MAX_BODY: usize = 1 << 20;

/// What every request handler shares.
pub struct Context {
    pub studio: Arc<Mutex<Studio>>,
    pub hub: Arc<Hub>,
    /// The Host header values accepted (`localhost:7878`, `127.0.0.1:7878`, ...).
    pub hosts: Vec<String>,
}

/// An answer: status and JSON body.
struct Answer(u16, Value);

fn error(code: u16, message: impl Into<String>) -> Answer {
    Answer(code, json!({ "error": message.into() }))
}

/// Answers one request (an event stream is handed to the hub and lives on).
pub fn handle(mut rq: Request, ctx: &Context) {
    if !host_allowed(&rq, ctx) {
        let msg = "refused: the Host header must name this studio (localhost, 127.0.0.1 or \
                   [::1] with its port)";
        return respond_json(rq, error(403, msg));
    }
    let url = rq.url().to_string();
    let path = url.split(['?', '#']).next().unwrap_or("");
    let method = rq.method().clone();
    if method == Method::Get {
        if path == "/api/events" {
            let first = lock(ctx).and_then(|s| {
                let errors = s.errors().to_vec();
                reload_message(&Reload::Errors(errors))
            });
            let writer = rq.into_writer();
            return ctx.hub.subscribe(writer, first);
        }
        if let Some((content_type, body)) = assets::asset(path) {
            return respond(rq, 200, content_type, body.to_string());
        }
        if let Some(name) = path
            .strip_prefix("/glyph/")
            .and_then(|n| n.strip_suffix(".svg"))
        {
            let svg = decode(name).and_then(|n| lock(ctx)?.glyph_svg(&n));
            return match svg {
                Some(svg) => respond(rq, 200, "image/svg+xml", svg),
                None => respond_json(rq, unknown(name)),
            };
        }
    }
    let answer = match (&method, path) {
        (Method::Get, "/api/font") => match lock(ctx) {
            Some(s) => Answer(200, s.font_json()),
            None => error(500, "the studio's state is unavailable"),
        },
        (Method::Get, p) if p.starts_with("/api/glyph/") => {
            let name = &p["/api/glyph/".len()..];
            let found = decode(name).and_then(|n| lock(ctx)?.glyph_json(&n));
            match found {
                Some(glyph) => Answer(200, glyph),
                None => unknown(name),
            }
        }
        (Method::Post, p) if p.starts_with("/api/glyph/") && p.ends_with("/edit") => {
            let name = &p["/api/glyph/".len()..p.len() - "/edit".len()];
            match decode(name) {
                Some(name) => edit(&mut rq, &name, ctx),
                None => unknown(name),
            }
        }
        (_, p) if p.starts_with("/api/") || assets::asset(p).is_some() => {
            error(405, format!("{method} is not allowed on {p}"))
        }
        (_, p) => error(404, format!("nothing at {p}")),
    };
    respond_json(rq, answer)
}

fn unknown(name: &str) -> Answer {
    error(404, format!("no glyph named `{name}` in this font"))
}

fn lock(ctx: &Context) -> Option<std::sync::MutexGuard<'_, Studio>> {
    ctx.studio.lock().ok()
}

/// The body of `POST /api/glyph/{name}/edit`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct EditRequest {
    version: String,
    ops: Vec<Op>,
}

/// Applies an edit: every op or none, checked by the loader, written atomically.
fn edit(rq: &mut Request, name: &str, ctx: &Context) -> Answer {
    let Some(mut studio) = lock(ctx) else {
        return error(500, "the studio's state is unavailable");
    };
    let Some(path) = studio.glyph_file(name).map(|p| p.to_path_buf()) else {
        return unknown(name);
    };
    if let Some(answer) = check_origin(rq, ctx) {
        return answer;
    }
    let body = match read_body(rq) {
        Ok(body) => body,
        Err(answer) => return answer,
    };
    let request: EditRequest = match serde_json::from_slice(&body) {
        Ok(r) => r,
        Err(e) => return error(400, format!("malformed edit: {e}")),
    };
    let bytes = match std::fs::read(&path) {
        Ok(b) => b,
        Err(e) => return error(500, format!("cannot read {}: {e}", path.display())),
    };
    let current = version(&bytes);
    if current != request.version {
        return Answer(
            409,
            json!({
                "error": format!(
                    "{} changed since version {}; load the glyph again",
                    path.display(),
                    request.version
                ),
                "version": current,
            }),
        );
    }
    let Ok(text) = String::from_utf8(bytes) else {
        return error(422, format!("{} is not valid UTF-8", path.display()));
    };
    let edited = match apply(&text, &request.ops) {
        Ok(t) => t,
        Err(EditError::OutOfRange(m)) => return error(400, m),
        Err(EditError::Unreadable(m)) => return error(422, m),
    };
    if let Err(diags) = studio.check_glyph_text(name, &edited) {
        let text: Vec<String> = diags.iter().map(ToString::to_string).collect();
        let diagnostics: Vec<Value> = diags.iter().map(diagnostic_json).collect();
        return Answer(
            422,
            json!({ "error": text.join("\n"), "diagnostics": diagnostics }),
        );
    }
    if edited != text {
        if let Err(e) = write_atomic(&path, edited.as_bytes()) {
            return error(500, format!("cannot write {}: {e}", path.display()));
        }
        // Only this file changed, and it was checked: no need to load the folder again
        // (the watcher's event for this write finds the font current).
        let names = studio.replace_glyph(name, &edited);
        let outcome = if studio.errors().is_empty() {
            Reload::Changed {
                names,
                fixed: false,
            }
        } else {
            // Another file is broken: this glyph shows its edit on the last good font.
            Reload::Errors(studio.errors().to_vec())
        };
        if let Some(message) = reload_message(&outcome) {
            ctx.hub.broadcast(&message);
        }
    }
    match studio.glyph_json(name) {
        Some(glyph) => Answer(200, glyph),
        None => unknown(name),
    }
}

/// The request body, at most [`MAX_BODY`] bytes, JSON only.
fn read_body(rq: &mut Request) -> Result<Vec<u8>, Answer> {
    let json_type = header(rq, "Content-Type").is_some_and(|t| {
        t.trim()
            .to_ascii_lowercase()
            .starts_with("application/json")
    });
    if !json_type {
        return Err(error(
            415,
            "an edit must be sent as Content-Type: application/json",
        ));
    }
    let too_large = || error(413, format!("request body over {MAX_BODY} bytes"));
    if rq.body_length().is_some_and(|n| n > MAX_BODY) {
        return Err(too_large());
    }
    let mut body = Vec::new();
    let limit = MAX_BODY as u64 + 1;
    if let Err(e) = rq.as_reader().take(limit).read_to_end(&mut body) {
        return Err(error(400, format!("cannot read the request body: {e}")));
    }
    if body.len() > MAX_BODY {
        return Err(too_large());
    }
    Ok(body)
}

/// The value of header `name`.
fn header<'r>(rq: &'r Request, name: &'static str) -> Option<&'r str> {
    rq.headers()
        .iter()
        .find(|h| h.field.equiv(name))
        .map(|h| h.value.as_str())
}

fn host_allowed(rq: &Request, ctx: &Context) -> bool {
    header(rq, "Host").is_some_and(|h| ctx.hosts.iter().any(|a| a.eq_ignore_ascii_case(h)))
}

/// A 403 when the browser says the request comes from another site.
fn check_origin(rq: &Request, ctx: &Context) -> Option<Answer> {
    let origin = header(rq, "Origin")?;
    let host = origin.strip_prefix("http://").unwrap_or("");
    if ctx.hosts.iter().any(|a| a.eq_ignore_ascii_case(host)) {
        None
    } else {
        Some(error(403, format!("refused: an edit from origin {origin}")))
    }
}

/// Percent-decodes one URL path segment; `None` when it is not UTF-8 or badly encoded.
/// Hand-written: six lines, and no crate of the dependency tree offers it.
fn decode(segment: &str) -> Option<String> {
    let bytes = segment.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = segment.get(i + 1..i + 3)?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).ok()
}

fn respond_json(rq: Request, Answer(code, body): Answer) {
    respond(rq, code, "application/json", body.to_string());
}

fn respond(rq: Request, code: u16, content_type: &str, body: String) {
    // A Content-Length rather than chunks: every answer is in memory already.
    let mut response = Response::from_string(body)
        .with_status_code(code)
        .with_chunked_threshold(usize::MAX);
    for (field, value) in [
        ("Content-Type", content_type),
        ("Cache-Control", "no-store"),
        ("X-Content-Type-Options", "nosniff"),
    ] {
        if let Ok(h) = Header::from_bytes(field.as_bytes(), value.as_bytes()) {
            response.add_header(h);
        }
    }
    // The page may have gone; nothing to do about it.
    let _ = rq.respond(response);
}

#[cfg(test)]
mod tests {
    use super::decode;

    #[test]
    fn percent_decoding() {
        assert_eq!(decode("A").as_deref(), Some("A"));
        assert_eq!(decode("..%2Fx").as_deref(), Some("../x"));
        assert_eq!(decode("%C3%A9").as_deref(), Some("é"));
        assert_eq!(decode("%zz"), None);
        assert_eq!(decode("%C3"), None);
    }
}
