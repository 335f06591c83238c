//! `cargo xtask size`: raw and gzip -9 size of every file in dist/.

use crate::util::{self, files_below, human, slash_path};
use flate2::write::GzEncoder;
use flate2::Compression;
use std::io::Write;

pub fn gzip_len(bytes: &[u8]) -> u64 {
    let mut enc = GzEncoder::new(Vec::new(), Compression::best());
    enc.write_all(bytes).expect("writing to a Vec cannot fail");
    enc.finish().expect("writing to a Vec cannot fail").len() as u64
}

pub fn size() -> Result<(), String> {
    let dist = util::root().join("dist");
    if !dist.join("pkg").is_dir() {
        return Err("dist/ is not built: run `cargo xtask dist` first".into());
    }
    let mut rows = Vec::new();
    for rel in files_below(&dist)? {
        let bytes = std::fs::read(dist.join(&rel))
            .map_err(|e| format!("cannot read dist/{}: {e}", rel.display()))?;
        rows.push((slash_path(&rel), bytes.len() as u64, gzip_len(&bytes)));
    }
    let width = rows.iter().map(|r| r.0.len()).max().unwrap_or(4).max(5);
    println!("{:<width$}  {:>12}  {:>12}", "file", "raw", "gzip -9");
    println!("{:-<width$}  {:->12}  {:->12}", "", "", "");
    let (mut raw, mut gz) = (0, 0);
    for (name, r, g) in &rows {
        println!("{name:<width$}  {:>12}  {:>12}", human(*r), human(*g));
        raw += r;
        gz += g;
    }
    println!("{:-<width$}  {:->12}  {:->12}", "", "", "");
    println!(
        "{:<width$}  {:>12}  {:>12}",
        format!("total ({} files)", rows.len()),
        human(raw),
        human(gz)
    );
    println!("(exact bytes: raw {raw}, gzip {gz})");
    Ok(())
}
