//! `noncirc studio`: serves the design studio (`studio/`, with the WebAssembly module that
//! `bash studio/build.sh` writes into `studio/pkg/`) on 127.0.0.1 until stopped.

use std::path::{Path, PathBuf};

/// The studio's folder in this repository.
pub fn default_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../studio")
}

/// The file a request path names under `root`: none for a path that leaves it (`..`), a
/// hidden name or a query's tail; a folder's `index.html`.
fn file_for(root: &Path, url: &str) -> Option<PathBuf> {
    let path = url.split(['?', '#']).next().unwrap_or("");
    let mut file = root.to_path_buf();
    for part in path.split('/').filter(|p| !p.is_empty()) {
        if part.starts_with('.') || part.contains('\\') {
            return None;
        }
        file.push(part);
    }
    if file.is_dir() {
        file.push("index.html");
    }
    file.is_file().then_some(file)
}

/// The media type of a studio file (`application/wasm` lets the browser compile the
/// module while it downloads).
fn media_type(file: &Path) -> &'static str {
    match file.extension().and_then(|e| e.to_str()) {
        Some("html") => "text/html; charset=utf-8",
        Some("js" | "mjs") => "text/javascript; charset=utf-8",
        Some("css") => "text/css; charset=utf-8",
        Some("wasm") => "application/wasm",
        Some("json") => "application/json",
        Some("svg") => "image/svg+xml",
        Some("png") => "image/png",
        Some("woff2") => "font/woff2",
        Some("toml" | "txt" | "md") => "text/plain; charset=utf-8",
        _ => "application/octet-stream",
    }
}

/// Serves `dir` on 127.0.0.1:`port` (0: a free port), printing the address, until the
/// process is stopped.
pub fn serve(dir: &Path, port: u16) -> Result<(), Box<dyn std::error::Error>> {
    let root = dir
        .canonicalize()
        .map_err(|e| format!("studio folder {}: {e}", dir.display()))?;
    if !root.join("pkg/noncirc_wasm_bg.wasm").is_file() {
        return Err(format!(
            "the studio's WebAssembly module is not built in {}: run `bash studio/build.sh`",
            root.join("pkg").display()
        )
        .into());
    }
    let server = tiny_http::Server::http(("127.0.0.1", port))
        .map_err(|e| format!("cannot listen on 127.0.0.1:{port}: {e}"))?;
    let address = server
        .server_addr()
        .to_ip()
        .ok_or("the server has no IP address")?;
    println!("noncirc studio: http://{address}/  (Ctrl-C stops it)");
    for request in server.incoming_requests() {
        let response = match file_for(&root, request.url()).map(|f| (std::fs::read(&f), f)) {
            Some((Ok(bytes), file)) => {
                let header = |name: &str, value: &str| {
                    tiny_http::Header::from_bytes(name.as_bytes(), value.as_bytes())
                        .expect("ASCII header")
                };
                tiny_http::Response::from_data(bytes)
                    .with_header(header("Content-Type", media_type(&file)))
                    .with_header(header("Cache-Control", "no-store"))
            }
            _ => tiny_http::Response::from_string("not found").with_status_code(404),
        };
        // A browser that went away mid-response is not the server's failure.
        let _ = request.respond(response);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Requests cannot leave the studio's folder or read hidden files.
    #[test]
    fn paths_stay_inside_the_studio() {
        let root = default_dir().canonicalize().unwrap();
        assert_eq!(file_for(&root, "/"), Some(root.join("index.html")));
        assert_eq!(file_for(&root, "/app.js?v=1"), Some(root.join("app.js")));
        for bad in [
            "/../Cargo.toml",
            "/%2e%2e/Cargo.toml",
            "/.hidden",
            "/nope.js",
        ] {
            assert_eq!(file_for(&root, bad), None, "{bad}");
        }
    }
}
