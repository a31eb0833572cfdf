//! The page's files, embedded in the binary: plain HTML, CSS and ES modules, no build step.

/// `(content type, text)` of the embedded file at URL path `path`.
pub fn asset(path: &str) -> Option<(&'static str, &'static str)> {
    const JS: &str = "text/javascript; charset=utf-8";
    Some(match path {
        "/" | "/index.html" => ("text/html; charset=utf-8", include_str!("web/index.html")),
        "/style.css" => ("text/css; charset=utf-8", include_str!("web/style.css")),
        "/studio.js" => (JS, include_str!("web/studio.js")),
        "/api.js" => (JS, include_str!("web/api.js")),
        "/overview.js" => (JS, include_str!("web/overview.js")),
        "/editor.js" => (JS, include_str!("web/editor.js")),
        "/favicon.svg" => ("image/svg+xml", include_str!("web/favicon.svg")),
        _ => return None,
    })
}
