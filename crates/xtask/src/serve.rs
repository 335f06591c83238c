//! `cargo xtask serve`: builds dist/ and serves it with a small std-only,
//! thread-per-connection static file server (GET and HEAD only). The
//! end-to-end tests serve the built site with this same server
//! (`--dir dist --port 0`, see tests/e2e/helpers.mjs), so its media types,
//! cache headers and compression are what they test.

use crate::dist;
use std::io::{BufRead, BufReader, Read, Write};
use std::net::{TcpListener, TcpStream};
use std::path::{Component, Path, PathBuf};
use std::time::Duration;

#[derive(Debug, PartialEq)]
pub struct Options {
    pub host: String,
    pub port: u16,
    /// Always starts and ends with `/`.
    pub base: String,
    /// Serve this folder as it is instead of building dist/ first.
    pub dir: Option<PathBuf>,
    /// Send every file as it is, as a host that does not compress does
    /// (no `.br`/`.gz` sibling, no gzip on the fly).
    pub compress: bool,
}

pub fn parse_args(args: &[String]) -> Result<Options, String> {
    let mut opts = Options {
        host: "127.0.0.1".into(),
        port: 8000,
        base: "/".into(),
        dir: None,
        compress: true,
    };
    let mut it = args.iter();
    while let Some(a) = it.next() {
        let (key, inline) = match a.split_once('=') {
            Some((k, v)) => (k, Some(v.to_string())),
            None => (a.as_str(), None),
        };
        let mut value = || {
            inline
                .clone()
                .or_else(|| it.next().cloned())
                .ok_or_else(|| format!("`{key}` needs a value"))
        };
        match key {
            "--port" | "-p" => {
                let v = value()?;
                opts.port = v
                    .parse()
                    .map_err(|_| format!("`--port {v}`: not a port number"))?;
            }
            "--host" => opts.host = value()?,
            "--base" => opts.base = normalise_base(&value()?)?,
            "--dir" => opts.dir = Some(PathBuf::from(value()?)),
            "--no-compression" if inline.is_none() => opts.compress = false,
            other => {
                return Err(format!(
                    "unknown option `{other}` (serve takes --port N, --host H, --base /prefix/, \
                     --dir PATH, --no-compression)"
                ))
            }
        }
    }
    Ok(opts)
}

fn normalise_base(b: &str) -> Result<String, String> {
    let trimmed = b.trim_matches('/');
    if trimmed
        .split('/')
        .any(|s| s == "." || s == ".." || s.contains(['?', '#', '\\']))
    {
        return Err(format!("`--base {b}`: not a plain path prefix"));
    }
    Ok(if trimmed.is_empty() {
        "/".into()
    } else {
        format!("/{trimmed}/")
    })
}

pub fn serve(opts: Options) -> Result<(), String> {
    let dist = match opts.dir {
        Some(dir) => dir,
        None => dist::dist()?,
    };
    let root = dist
        .canonicalize()
        .map_err(|e| format!("cannot open {}: {e}", dist.display()))?;
    let listener = TcpListener::bind((opts.host.as_str(), opts.port))
        .map_err(|e| format!("cannot listen on {}:{}: {e}", opts.host, opts.port))?;
    let addr = listener.local_addr().map_err(|e| e.to_string())?;
    let shown_host = if addr.ip().is_ipv6() {
        format!("[{}]", addr.ip())
    } else {
        addr.ip().to_string()
    };
    println!(
        "serving {} at http://{shown_host}:{}{} (Ctrl-C stops)",
        dist.display(),
        addr.port(),
        opts.base
    );
    let base: &'static str = Box::leak(opts.base.into_boxed_str());
    let root: &'static Path = Box::leak(root.into_boxed_path());
    let compress = opts.compress;
    for stream in listener.incoming() {
        match stream {
            Ok(stream) => {
                std::thread::spawn(move || {
                    let _ = handle(stream, root, base, compress);
                });
            }
            Err(e) => eprintln!("accept failed: {e}"),
        }
    }
    Ok(())
}

/// Serves requests on one connection (keep-alive) until the client closes it.
/// `compress: false` sends every file as it is.
fn handle(stream: TcpStream, root: &Path, base: &str, compress: bool) -> std::io::Result<()> {
    stream.set_read_timeout(Some(Duration::from_secs(30)))?;
    let mut reader = BufReader::new(stream.try_clone()?);
    let mut out = stream;
    loop {
        let mut line = String::new();
        if reader.read_line(&mut line)? == 0 {
            return Ok(());
        }
        let mut parts = line.split_whitespace();
        let (method, target, version) = (parts.next(), parts.next(), parts.next());
        // Headers: only Connection and Content-Length matter here.
        let mut keep_alive = version == Some("HTTP/1.1");
        let mut body_len = 0u64;
        let mut encodings = Encodings::default();
        let mut if_none_match = None;
        loop {
            let mut h = String::new();
            if reader.read_line(&mut h)? == 0 {
                return Ok(());
            }
            let h = h.trim_end();
            if h.is_empty() {
                break;
            }
            if let Some((name, value)) = h.split_once(':') {
                let value = value.trim().to_ascii_lowercase();
                match name.trim().to_ascii_lowercase().as_str() {
                    "connection" if value == "close" => keep_alive = false,
                    "connection" if value == "keep-alive" => keep_alive = true,
                    "content-length" => body_len = value.parse().unwrap_or(0),
                    "if-none-match" => if_none_match = Some(value),
                    "accept-encoding" if compress => {
                        encodings = Encodings {
                            gzip: accepts(&value, "gzip"),
                            br: accepts(&value, "br"),
                        }
                    }
                    _ => {}
                }
            }
        }
        std::io::copy(&mut (&mut reader).take(body_len), &mut std::io::sink())?;

        let (Some(method), Some(target)) = (method, target) else {
            respond_text(&mut out, 400, "Bad Request", "bad request\n", false, true)?;
            return Ok(());
        };
        let head = method == "HEAD";
        // Logged before the answer: whoever reads the log (the end-to-end
        // tests count requests) sees a request before its response arrives.
        eprintln!("{method} {target}");
        if method != "GET" && !head {
            respond_text(
                &mut out,
                405,
                "Method Not Allowed",
                "GET or HEAD only\n",
                head,
                keep_alive,
            )?;
        } else {
            match resolve(root, base, target) {
                Resolved::File(path) => {
                    let request = Request {
                        head,
                        keep_alive,
                        accepted: encodings,
                        if_none_match: if_none_match.as_deref(),
                    };
                    if send_file(&mut out, &path, request)? == Sent::NotModified {
                        // Said after the answer: the tests that weigh a
                        // page count what was downloaded, not revalidated.
                        eprintln!("not modified {target}");
                    }
                }
                Resolved::Redirect(to) => {
                    let msg = format!("moved to {to}\n");
                    write!(
                        out,
                        "HTTP/1.1 301 Moved Permanently\r\nLocation: {to}\r\n\
                         Content-Type: text/plain; charset=utf-8\r\nContent-Length: {}\r\n\
                         Connection: {}\r\n\r\n",
                        msg.len(),
                        if keep_alive { "keep-alive" } else { "close" }
                    )?;
                    if !head {
                        out.write_all(msg.as_bytes())?;
                    }
                }
                Resolved::Forbidden => {
                    respond_text(&mut out, 403, "Forbidden", "forbidden\n", head, keep_alive)?
                }
                Resolved::NotFound => {
                    respond_text(&mut out, 404, "Not Found", "not found\n", head, keep_alive)?
                }
            }
        }
        out.flush()?;
        if !keep_alive {
            return Ok(());
        }
    }
}

#[derive(Debug, PartialEq)]
enum Resolved {
    File(PathBuf),
    Redirect(String),
    Forbidden,
    NotFound,
}

/// Maps a request target to a file below `root`, refusing anything that
/// would leave it.
fn resolve(root: &Path, base: &str, target: &str) -> Resolved {
    let path = target.split(['?', '#']).next().unwrap_or("");
    let Some(decoded) = percent_decode(path) else {
        return Resolved::Forbidden;
    };
    if decoded.contains(['\0', '\\']) {
        return Resolved::Forbidden;
    }
    // `/sub/path` without its slash: send the browser to `/sub/path/` so relative URLs work.
    if base != "/" && decoded == base.trim_end_matches('/') {
        return Resolved::Redirect(base.to_string());
    }
    let Some(rest) = decoded.strip_prefix(base) else {
        return Resolved::NotFound;
    };
    let mut rel = PathBuf::new();
    for part in rest.split('/') {
        match part {
            "" | "." => {}
            ".." => return Resolved::Forbidden,
            p => rel.push(p),
        }
    }
    if rel.components().any(|c| !matches!(c, Component::Normal(_))) {
        return Resolved::Forbidden;
    }
    let mut full = root.join(&rel);
    if full.is_dir() {
        if !decoded.ends_with('/') {
            let q = target.find('?').map_or("", |i| &target[i..]);
            return Resolved::Redirect(format!("{path}/{q}"));
        }
        full.push("index.html");
    }
    // Symlinks must not lead out of the served tree either.
    match full.canonicalize() {
        Ok(real) if real.starts_with(root) && real.is_file() => Resolved::File(real),
        Ok(real) if !real.starts_with(root) => Resolved::Forbidden,
        _ => Resolved::NotFound,
    }
}

fn percent_decode(s: &str) -> Option<String> {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = s.get(i + 1..i + 3)?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).ok()
}

/// MIME type by file extension.
pub fn mime(path: &Path) -> &'static str {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    match ext.as_str() {
        "html" | "htm" => "text/html; charset=utf-8",
        "js" | "mjs" => "text/javascript; charset=utf-8",
        "css" => "text/css; charset=utf-8",
        "json" | "map" => "application/json; charset=utf-8",
        "wasm" => "application/wasm",
        "svg" => "image/svg+xml; charset=utf-8",
        "png" => "image/png",
        "jpg" | "jpeg" => "image/jpeg",
        "webp" => "image/webp",
        "ico" => "image/x-icon",
        "txt" | "md" => "text/plain; charset=utf-8",
        "xml" => "application/xml; charset=utf-8",
        "woff2" => "font/woff2",
        "webmanifest" => "application/manifest+json; charset=utf-8",
        _ => "application/octet-stream",
    }
}

/// The content codings a client accepts.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Encodings {
    gzip: bool,
    br: bool,
}

/// Whether an `Accept-Encoding` value (lower-cased) allows `coding`: listed
/// (or `*`) and not refused with `q=0`.
fn accepts(value: &str, coding: &str) -> bool {
    value.split(',').any(|item| {
        let mut parts = item.split(';').map(str::trim);
        let listed = parts.next().unwrap_or("");
        let refused = parts.any(|p| {
            p.strip_prefix("q=")
                .and_then(|q| q.parse::<f64>().ok())
                .is_some_and(|q| q == 0.0)
        });
        (listed == coding || listed == "*") && !refused
    })
}

/// Sends a file: its precompressed `.br` or `.gz` sibling (written by
/// `cargo xtask dist`) when the client accepts that coding, as nginx's
/// `brotli_static`/`gzip_static` would; text compressed on the fly when there
/// is no sibling; the file as it is otherwise. Every file goes with the
/// site's Content-Security-Policy header (the same policy as the `<meta>` in
/// `index.html`; a header can also be set by hosts, and covers every file).
/// A content-hashed name never changes its content (see
/// [`crate::modules::is_content_hashed`]): cache it for a year; everything
/// else is revalidated on each load, so a rebuild shows at once.
fn cache_control(path: &Path) -> &'static str {
    if crate::modules::is_content_hashed(path) {
        "public, max-age=31536000, immutable"
    } else {
        "no-cache"
    }
}

/// What a file request asked for, beyond its path.
struct Request<'a> {
    head: bool,
    keep_alive: bool,
    accepted: Encodings,
    /// The `If-None-Match` header (lower-cased): the entity tags the
    /// browser holds for this path.
    if_none_match: Option<&'a str>,
}

/// The entity tag of a file as sent with `coding` (`""`, `"gzip"`, `"br"`):
/// its length and modification time, as nginx and Apache derive theirs, so a
/// redeployed file has a new tag. Lower-case hex (request headers are read
/// lower-cased).
fn entity_tag(path: &Path, coding: &str) -> Option<String> {
    let meta = std::fs::metadata(path).ok()?;
    let modified = meta
        .modified()
        .ok()?
        .duration_since(std::time::UNIX_EPOCH)
        .ok()?;
    let suffix = if coding.is_empty() {
        String::new()
    } else {
        format!("-{coding}")
    };
    Some(format!(
        "\"{:x}-{:x}{suffix}\"",
        modified.as_nanos(),
        meta.len()
    ))
}

/// Whether an `If-None-Match` value names `tag` (or is `*`).
fn names_tag(if_none_match: &str, tag: &str) -> bool {
    if_none_match
        .split(',')
        .map(|t| t.trim().trim_start_matches("w/"))
        .any(|t| t == tag || t == "*")
}

/// How a file request was answered.
#[derive(Debug, PartialEq)]
enum Sent {
    /// With its bytes (200) or a 404.
    Body,
    /// 304: the browser's copy is current.
    NotModified,
}

fn send_file(out: &mut TcpStream, path: &Path, request: Request) -> std::io::Result<Sent> {
    let Request {
        head,
        keep_alive,
        accepted,
        if_none_match,
    } = request;
    let sibling = |ext: &str| {
        let mut name = path.as_os_str().to_owned();
        name.push(ext);
        std::fs::read(name).ok()
    };
    let compressible = crate::precompress::compressible(path);
    let precompressed = if !compressible {
        None
    } else if let Some(b) = accepted.br.then(|| sibling(".br")).flatten() {
        Some((b, "Content-Encoding: br\r\n"))
    } else {
        accepted
            .gzip
            .then(|| sibling(".gz"))
            .flatten()
            .map(|b| (b, "Content-Encoding: gzip\r\n"))
    };
    let (body, encoding) = match precompressed {
        Some(found) => found,
        None => {
            let body = match std::fs::read(path) {
                Ok(b) => b,
                Err(_) => {
                    respond_text(out, 404, "Not Found", "not found\n", head, keep_alive)?;
                    return Ok(Sent::Body);
                }
            };
            if accepted.gzip && compressible {
                (
                    crate::precompress::gzip(&body),
                    "Content-Encoding: gzip\r\n",
                )
            } else {
                (body, "")
            }
        }
    };
    // A file the browser already holds (it revalidates: `no-cache`) is
    // answered 304 with no body, as nginx and Apache answer: a page that
    // uses one file twice (the icon) downloads it once.
    let coding = match encoding {
        "" => "",
        e if e.contains("br") => "br",
        _ => "gzip",
    };
    let tag = entity_tag(path, coding);
    if let (Some(tag), Some(held)) = (&tag, if_none_match) {
        if names_tag(held, tag) {
            write!(
                out,
                "HTTP/1.1 304 Not Modified\r\nETag: {tag}\r\nVary: Accept-Encoding\r\n\
                 Cache-Control: {}\r\nConnection: {}\r\n\r\n",
                cache_control(path),
                if keep_alive { "keep-alive" } else { "close" }
            )?;
            return Ok(Sent::NotModified);
        }
    }
    let etag = tag.map(|t| format!("ETag: {t}\r\n")).unwrap_or_default();
    write!(
        out,
        "HTTP/1.1 200 OK\r\nContent-Type: {}\r\nContent-Length: {}\r\n{encoding}{etag}Vary: Accept-Encoding\r\n\
         Cache-Control: {}\r\nX-Content-Type-Options: nosniff\r\n\
         Content-Security-Policy: {}\r\nConnection: {}\r\n\r\n",
        mime(path),
        body.len(),
        cache_control(path),
        crate::pages::CONTENT_SECURITY_POLICY,
        if keep_alive { "keep-alive" } else { "close" }
    )?;
    if !head {
        out.write_all(&body)?;
    }
    Ok(Sent::Body)
}

fn respond_text(
    out: &mut TcpStream,
    code: u16,
    reason: &str,
    body: &str,
    head: bool,
    keep_alive: bool,
) -> std::io::Result<()> {
    write!(
        out,
        "HTTP/1.1 {code} {reason}\r\nContent-Type: text/plain; charset=utf-8\r\n\
         Content-Length: {}\r\nConnection: {}\r\n\r\n",
        body.len(),
        if keep_alive { "keep-alive" } else { "close" }
    )?;
    if !head {
        out.write_all(body.as_bytes())?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(a: &[&str]) -> Vec<String> {
        a.iter().map(|s| s.to_string()).collect()
    }

    #[test]
    fn parses_options() {
        let o = parse_args(&args(&[
            "--port",
            "9000",
            "--host=0.0.0.0",
            "--base",
            "lab/x",
        ]))
        .unwrap();
        assert_eq!(
            o,
            Options {
                host: "0.0.0.0".into(),
                port: 9000,
                base: "/lab/x/".into(),
                dir: None,
                compress: true,
            }
        );
        assert_eq!(parse_args(&[]).unwrap().port, 8000);
        assert_eq!(parse_args(&[]).unwrap().dir, None);
        assert!(parse_args(&[]).unwrap().compress);
        assert!(parse_args(&args(&["--port", "x"])).is_err());
        assert!(parse_args(&args(&["--base", "/a/../b"])).is_err());
        assert!(parse_args(&args(&["--bogus"])).is_err());
    }

    /// The end-to-end tests serve dist/ as it is (no build) on a free port,
    /// and compare a host that compresses with one that does not.
    #[test]
    fn serves_a_folder_as_it_is_on_any_port_with_or_without_compression() {
        let o = parse_args(&args(&["--dir", "dist", "--port", "0", "--no-compression"])).unwrap();
        assert_eq!(o.dir, Some(PathBuf::from("dist")));
        assert_eq!(o.port, 0);
        assert!(!o.compress);
        assert!(parse_args(&args(&["--no-compression=1"])).is_err());
        assert!(parse_args(&args(&["--dir"])).is_err());
    }

    #[test]
    fn resolves_paths_and_refuses_traversal() {
        let tmp = std::env::temp_dir().join(format!("xtask-serve-test-{}", std::process::id()));
        std::fs::create_dir_all(tmp.join("pkg")).unwrap();
        std::fs::write(tmp.join("index.html"), "<!doctype html>").unwrap();
        std::fs::write(tmp.join("pkg/a.wasm"), b"\0asm").unwrap();
        let root = tmp.canonicalize().unwrap();

        assert_eq!(
            resolve(&root, "/", "/"),
            Resolved::File(root.join("index.html"))
        );
        assert_eq!(
            resolve(&root, "/", "/pkg/a.wasm?x=1"),
            Resolved::File(root.join("pkg/a.wasm"))
        );
        assert_eq!(
            resolve(&root, "/", "/pkg"),
            Resolved::Redirect("/pkg/".into())
        );
        assert_eq!(resolve(&root, "/", "/nope.js"), Resolved::NotFound);
        assert_eq!(resolve(&root, "/", "/../etc/passwd"), Resolved::Forbidden);
        assert_eq!(
            resolve(&root, "/", "/%2e%2e/etc/passwd"),
            Resolved::Forbidden
        );
        assert_eq!(resolve(&root, "/", "/pkg/..%5c..%5cx"), Resolved::Forbidden);
        assert_eq!(resolve(&root, "/", "/%zz"), Resolved::Forbidden);

        assert_eq!(
            resolve(&root, "/sub/path/", "/sub/path/"),
            Resolved::File(root.join("index.html"))
        );
        assert_eq!(
            resolve(&root, "/sub/path/", "/sub/path"),
            Resolved::Redirect("/sub/path/".into())
        );
        assert_eq!(
            resolve(&root, "/sub/path/", "/index.html"),
            Resolved::NotFound
        );
        std::fs::remove_dir_all(&tmp).unwrap();
    }

    #[test]
    fn gzip_negotiation() {
        let accepts_gzip = |v: &str| accepts(v, "gzip");
        assert!(accepts_gzip("gzip, deflate, br"));
        assert!(accepts_gzip("br;q=1.0, gzip;q=0.8"));
        assert!(accepts_gzip("*"));
        assert!(!accepts_gzip("gzip;q=0"));
        assert!(!accepts_gzip("br, identity"));
        assert!(accepts("gzip, deflate, br", "br"));
        assert!(!accepts("gzip, deflate", "br"));
        assert!(!accepts("br;q=0, gzip", "br"));
        assert!(crate::precompress::compressible(Path::new(
            "a/labweb_bg.wasm"
        )));
        assert!(!crate::precompress::compressible(Path::new("a/b.png")));
    }

    #[test]
    fn hashed_modules_are_cached_for_good_and_the_rest_revalidated() {
        assert_eq!(
            cache_control(Path::new("dist/pkg/control.0a1b2c3d.wasm")),
            "public, max-age=31536000, immutable"
        );
        assert_eq!(cache_control(Path::new("dist/index.html")), "no-cache");
        assert_eq!(cache_control(Path::new("dist/main.js")), "no-cache");
    }

    #[test]
    fn mime_types() {
        assert_eq!(mime(Path::new("a.wasm")), "application/wasm");
        assert_eq!(mime(Path::new("a.js")), "text/javascript; charset=utf-8");
        assert_eq!(mime(Path::new("a.svg")), "image/svg+xml; charset=utf-8");
        assert_eq!(mime(Path::new("a.HTML")), "text/html; charset=utf-8");
    }

    #[test]
    fn serves_files_with_the_content_security_policy_header() {
        let tmp = std::env::temp_dir().join(format!("xtask-serve-csp-{}", std::process::id()));
        std::fs::create_dir_all(&tmp).unwrap();
        std::fs::write(tmp.join("index.html"), "<!doctype html><title>x</title>").unwrap();
        let root = tmp.canonicalize().unwrap();
        let (head, body) = exchange(
            &root,
            "/sub/",
            "GET /sub/ HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n",
        );
        std::fs::remove_dir_all(&tmp).unwrap();

        assert!(head.starts_with("HTTP/1.1 200 OK\r\n"), "{head}");
        let csp: Vec<&str> = head
            .lines()
            .filter_map(|l| l.strip_prefix("Content-Security-Policy: "))
            .collect();
        assert_eq!(csp, [crate::pages::CONTENT_SECURITY_POLICY], "{head}");
        assert!(csp[0].contains("script-src 'self' 'wasm-unsafe-eval'"));
        assert_eq!(body, "<!doctype html><title>x</title>");
    }

    /// Sends `request` (its lines, CRLF-joined) to a server on `root` under
    /// `base` and returns the answer's head and body.
    fn exchange(root: &Path, base: &'static str, request: &str) -> (String, String) {
        let root = root.to_path_buf();
        let listener = TcpListener::bind("127.0.0.1:0").unwrap();
        let addr = listener.local_addr().unwrap();
        let server = std::thread::spawn(move || {
            let (stream, _) = listener.accept().unwrap();
            handle(stream, &root, base, true).unwrap();
        });
        let mut client = TcpStream::connect(addr).unwrap();
        client.write_all(request.as_bytes()).unwrap();
        let mut response = String::new();
        client.read_to_string(&mut response).unwrap();
        server.join().unwrap();
        let (head, body) = response.split_once("\r\n\r\n").expect("headers end");
        (head.to_owned(), body.to_owned())
    }

    #[test]
    fn a_file_the_browser_holds_is_answered_not_modified_until_it_changes() {
        let tmp = std::env::temp_dir().join(format!("xtask-serve-etag-{}", std::process::id()));
        std::fs::create_dir_all(&tmp).unwrap();
        std::fs::write(tmp.join("favicon.svg"), "<svg/>").unwrap();
        let root = tmp.canonicalize().unwrap();
        let get = |extra: &str| {
            exchange(
                &root,
                "/",
                &format!(
                    "GET /favicon.svg HTTP/1.1\r\nHost: x\r\n{extra}Connection: close\r\n\r\n"
                ),
            )
        };
        let (head, body) = get("");
        assert!(head.starts_with("HTTP/1.1 200 OK\r\n"), "{head}");
        assert_eq!(body, "<svg/>");
        let tag = head
            .lines()
            .find_map(|l| l.strip_prefix("ETag: "))
            .expect("an ETag")
            .to_owned();
        assert!(tag.starts_with('"') && tag.ends_with('"'), "{tag}");

        let (head, body) = get(&format!("If-None-Match: {tag}\r\n"));
        assert!(head.starts_with("HTTP/1.1 304 Not Modified\r\n"), "{head}");
        assert!(head.contains("Cache-Control: no-cache"), "{head}");
        assert_eq!(body, "", "a 304 has no body");
        let (head, _) = get(&format!("If-None-Match: W/{tag}, \"other\"\r\n"));
        assert!(
            head.starts_with("HTTP/1.1 304"),
            "a weak or listed tag: {head}"
        );

        // A redeployed file (other length) has another tag: sent in full.
        std::fs::write(tmp.join("favicon.svg"), "<svg></svg>").unwrap();
        let (head, body) = get(&format!("If-None-Match: {tag}\r\n"));
        std::fs::remove_dir_all(&tmp).unwrap();
        assert!(head.starts_with("HTTP/1.1 200 OK\r\n"), "{head}");
        assert_eq!(body, "<svg></svg>");
    }
}
