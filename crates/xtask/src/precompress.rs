//! Precompressed siblings for static hosts: `dist/x.js` gets `x.js.gz`
//! (gzip -9) and `x.js.br` (Brotli quality 11), so nginx (`gzip_static on;`,
//! `brotli_static on;`), Apache (`MultiViews` or rewrite rules) and static
//! hosts that look for them send compressed files without compressing on
//! every request. `cargo xtask serve` sends them too.

use crate::util::files_below;
use std::fs;
use std::io::Write;
use std::path::Path;

/// Whether a file is worth compressing: text and wasm (images and icons are
/// compressed already or tiny).
#[must_use]
pub fn compressible(path: &Path) -> bool {
    matches!(
        path.extension().and_then(|e| e.to_str()),
        Some(
            "html"
                | "js"
                | "mjs"
                | "css"
                | "svg"
                | "json"
                | "wasm"
                | "txt"
                | "map"
                | "csv"
                | "xml"
                | "webmanifest"
        )
    )
}

/// Whether a file is a precompressed sibling written here.
#[must_use]
pub fn is_sibling(path: &Path) -> bool {
    matches!(path.extension().and_then(|e| e.to_str()), Some("gz" | "br"))
}

/// gzip at level 9.
pub fn gzip(bytes: &[u8]) -> Vec<u8> {
    let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::best());
    enc.write_all(bytes).expect("writing to a Vec cannot fail");
    enc.finish().expect("writing to a Vec cannot fail")
}

/// Brotli at quality 11 with a 4 MiB window (what `brotli -q 11` does).
pub fn brotli(bytes: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    let params = brotli::enc::BrotliEncoderParams {
        quality: 11,
        lgwin: 22,
        ..Default::default()
    };
    brotli::BrotliCompress(&mut &bytes[..], &mut out, &params)
        .expect("compressing from and to memory cannot fail");
    out
}

/// Writes `.gz` and `.br` beside every compressible file of `dist`. Returns
/// (files, raw bytes, gzip bytes, brotli bytes).
pub fn write_siblings(dist: &Path) -> Result<(usize, u64, u64, u64), String> {
    let (mut n, mut raw, mut gz, mut br) = (0, 0, 0, 0);
    for rel in files_below(dist)? {
        let path = dist.join(&rel);
        if !compressible(&path) {
            continue;
        }
        let bytes = fs::read(&path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
        let g = gzip(&bytes);
        let b = brotli(&bytes);
        for (ext, body) in [("gz", &g), ("br", &b)] {
            let mut name = path.as_os_str().to_owned();
            name.push(".");
            name.push(ext);
            fs::write(&name, body)
                .map_err(|e| format!("cannot write {}: {e}", Path::new(&name).display()))?;
        }
        n += 1;
        raw += bytes.len() as u64;
        gz += g.len() as u64;
        br += b.len() as u64;
    }
    Ok((n, raw, gz, br))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Read;

    #[test]
    fn siblings_decompress_to_the_original_and_only_text_and_wasm_get_them() {
        let dir = std::env::temp_dir().join(format!("xtask-precompress-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(dir.join("pkg")).unwrap();
        let text = "let x = 1;\n".repeat(500);
        fs::write(dir.join("pkg/app.js"), &text).unwrap();
        fs::write(dir.join("icon.png"), [137u8, 80, 78, 71]).unwrap();
        let (n, raw, gz, br) = write_siblings(&dir).unwrap();
        assert_eq!(n, 1);
        assert_eq!(raw, text.len() as u64);
        assert!(gz < raw / 10 && br < raw / 10, "gz {gz}, br {br}");
        let mut back = String::new();
        flate2::read::GzDecoder::new(&fs::read(dir.join("pkg/app.js.gz")).unwrap()[..])
            .read_to_string(&mut back)
            .unwrap();
        assert_eq!(back, text);
        let mut back = Vec::new();
        brotli::BrotliDecompress(
            &mut &fs::read(dir.join("pkg/app.js.br")).unwrap()[..],
            &mut back,
        )
        .unwrap();
        assert_eq!(back, text.as_bytes());
        assert!(!dir.join("icon.png.gz").exists());
        assert!(is_sibling(Path::new("a/app.js.br")) && !is_sibling(Path::new("a/app.js")));
        fs::remove_dir_all(&dir).unwrap();
    }
}
