//! Short import names for a shipped wasm module and its JS glue.
//!
//! wasm-bindgen names every function the module imports from its glue after
//! the Rust binding plus a 16-hex-digit hash (`__wbg_set_textContent_0177b2a6d9293c2c`),
//! and each name is written twice: in the module's import section and as a
//! key of the glue's import object. A module of ours imports about 215 of
//! them; the hashes are nearly incompressible, and the names came to about
//! 6 KB of every page's gzip total (measured on the A* page: glue 7,268 →
//! 4,534 B gzip, the module's names 3,463 → 261 B).
//!
//! [`shorten`] renames every import of the module to `a`, `b`, … `z`, `aa`,
//! … (the module names, such as `./astar_bg.js`, stay), and
//! [`rename_in_glue`] renames the same keys in the glue. Nothing else in
//! either file changes. The wasm binary format's import section is
//! <https://webassembly.github.io/spec/core/binary/modules.html#import-section>.

/// The import section's id in the module's section list.
const IMPORT_SECTION: u8 = 2;

/// An old import name and its new one.
pub type Rename = (String, String);

/// The `i`-th short name: `a` … `z`, `aa` … `zz`, `aaa` …
#[must_use]
pub fn short_name(mut i: usize) -> String {
    let mut name = Vec::new();
    loop {
        name.push(b'a' + (i % 26) as u8);
        if i < 26 {
            break;
        }
        i = i / 26 - 1;
    }
    name.reverse();
    String::from_utf8(name).expect("ASCII letters")
}

/// Reads an unsigned LEB128 number at `*at`, moving past it.
fn read_leb(bytes: &[u8], at: &mut usize) -> Result<u64, String> {
    let mut value = 0u64;
    for shift in (0..64).step_by(7) {
        let byte = *bytes.get(*at).ok_or("wasm ends inside a number")?;
        *at += 1;
        value |= u64::from(byte & 0x7f) << shift;
        if byte & 0x80 == 0 {
            return Ok(value);
        }
    }
    Err("a LEB128 number longer than 64 bits".into())
}

/// Appends `value` as unsigned LEB128.
fn write_leb(out: &mut Vec<u8>, mut value: u64) {
    loop {
        let byte = (value & 0x7f) as u8;
        value >>= 7;
        if value == 0 {
            out.push(byte);
            return;
        }
        out.push(byte | 0x80);
    }
}

/// Reads a name (length, then UTF-8 bytes) at `*at`.
fn read_name<'a>(bytes: &'a [u8], at: &mut usize) -> Result<&'a str, String> {
    let len = usize::try_from(read_leb(bytes, at)?).map_err(|_| "name too long")?;
    let end = at.checked_add(len).filter(|e| *e <= bytes.len());
    let slice = bytes[*at..end.ok_or("wasm ends inside a name")?].as_ref();
    *at += len;
    std::str::from_utf8(slice).map_err(|_| "a name that is not UTF-8".into())
}

fn write_name(out: &mut Vec<u8>, name: &str) {
    write_leb(out, name.len() as u64);
    out.extend_from_slice(name.as_bytes());
}

/// Skips an import's description (what is imported) at `*at`.
fn skip_import_desc(bytes: &[u8], at: &mut usize) -> Result<(), String> {
    let kind = *bytes.get(*at).ok_or("wasm ends inside an import")?;
    *at += 1;
    let limits = |at: &mut usize| -> Result<(), String> {
        let flags = *bytes.get(*at).ok_or("wasm ends inside limits")?;
        *at += 1;
        read_leb(bytes, at)?;
        if flags & 1 != 0 {
            read_leb(bytes, at)?;
        }
        Ok(())
    };
    match kind {
        // A function (type index) or a tag (attribute byte, type index).
        0 => read_leb(bytes, at).map(|_| ()),
        4 => {
            *at += 1;
            read_leb(bytes, at).map(|_| ())
        }
        // A table (reference type, limits) or a memory (limits).
        1 => {
            *at += 1;
            limits(at)
        }
        2 => limits(at),
        // A global: value type and mutability.
        3 => {
            *at += 2;
            Ok(())
        }
        other => Err(format!("unknown import kind {other}")),
    }
}

/// Renames every import of the module `wasm` to a short name; returns the
/// new module and the renames in import order.
pub fn shorten(wasm: &[u8]) -> Result<(Vec<u8>, Vec<Rename>), String> {
    if wasm.len() < 8 || &wasm[..4] != b"\0asm" {
        return Err("not a wasm module".into());
    }
    let mut out = wasm[..8].to_vec();
    let mut renames = Vec::new();
    let mut at = 8;
    while at < wasm.len() {
        let id = wasm[at];
        at += 1;
        let size = usize::try_from(read_leb(wasm, &mut at)?).map_err(|_| "section too long")?;
        let end = at
            .checked_add(size)
            .filter(|e| *e <= wasm.len())
            .ok_or("wasm ends inside a section")?;
        if id != IMPORT_SECTION {
            out.push(id);
            write_leb(&mut out, size as u64);
            out.extend_from_slice(&wasm[at..end]);
            at = end;
            continue;
        }
        let body = &wasm[at..end];
        let mut p = 0;
        let count = read_leb(body, &mut p)?;
        let mut section = Vec::new();
        write_leb(&mut section, count);
        for i in 0..count {
            let module = read_name(body, &mut p)?;
            let name = read_name(body, &mut p)?;
            let desc_start = p;
            skip_import_desc(body, &mut p)?;
            let short = short_name(usize::try_from(i).map_err(|_| "too many imports")?);
            write_name(&mut section, module);
            write_name(&mut section, &short);
            section.extend_from_slice(&body[desc_start..p]);
            renames.push((name.to_owned(), short));
        }
        if p != body.len() {
            return Err("the import section has bytes after its last import".into());
        }
        out.push(id);
        write_leb(&mut out, section.len() as u64);
        out.extend_from_slice(&section);
        at = end;
    }
    Ok((out, renames))
}

/// Renames the import keys of wasm-bindgen's glue `js`: each old name must
/// occur exactly once (as its key in the import object), else the glue is
/// not what this expects and nothing is renamed.
pub fn rename_in_glue(js: &str, renames: &[Rename]) -> Result<String, String> {
    let mut out = js.to_owned();
    for (old, new) in renames {
        let found = out.matches(old.as_str()).count();
        if found != 1 {
            return Err(format!(
                "the glue names the import `{old}` {found} times (expected once as a key)"
            ));
        }
        out = out.replacen(old.as_str(), new, 1);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A module with one type, the function imports `(module, name)` of
    /// type 0, a memory import named `memory`, then a custom section.
    fn module(imports: &[(&str, &str)], memory: &str) -> Vec<u8> {
        let mut m = b"\0asm\x01\0\0\0".to_vec();
        // Type section: one type, () -> ().
        m.extend_from_slice(&[1, 4, 1, 0x60, 0, 0]);
        let mut body = Vec::new();
        write_leb(&mut body, imports.len() as u64 + 1);
        for (module, name) in imports {
            write_name(&mut body, module);
            write_name(&mut body, name);
            body.extend_from_slice(&[0, 0]);
        }
        write_name(&mut body, "env");
        write_name(&mut body, memory);
        // A memory with a minimum and a maximum.
        body.extend_from_slice(&[2, 1, 1, 16]);
        m.push(IMPORT_SECTION);
        write_leb(&mut m, body.len() as u64);
        m.extend_from_slice(&body);
        // A custom section, copied as it is.
        m.extend_from_slice(&[0, 4, 1, b'x', 7, 7]);
        m
    }

    #[test]
    fn short_names_count_like_spreadsheet_columns() {
        let names: Vec<String> = [0, 1, 25, 26, 27, 51, 52, 701, 702]
            .iter()
            .map(|i| short_name(*i))
            .collect();
        assert_eq!(names, ["a", "b", "z", "aa", "ab", "az", "ba", "zz", "aaa"]);
        let all: std::collections::HashSet<String> = (0..2000).map(short_name).collect();
        assert_eq!(all.len(), 2000, "names repeat");
    }

    #[test]
    fn leb128_round_trips() {
        for v in [
            0u64,
            1,
            127,
            128,
            300,
            16_384,
            u64::from(u32::MAX),
            u64::MAX,
        ] {
            let mut out = Vec::new();
            write_leb(&mut out, v);
            let mut at = 0;
            assert_eq!(read_leb(&out, &mut at).unwrap(), v);
            assert_eq!(at, out.len());
        }
    }

    #[test]
    fn imports_get_short_names_and_nothing_else_changes() {
        let long = "__wbg_set_textContent_0177b2a6d9293c2c";
        let push = "__wbg_push_c9f4893fc209f768";
        let input = module(
            &[("./astar_bg.js", long), ("./astar_bg.js", push)],
            "memory_with_a_long_name",
        );
        let (output, renames) = shorten(&input).unwrap();
        assert_eq!(
            renames,
            [
                (long.to_owned(), "a".to_owned()),
                (push.to_owned(), "b".to_owned()),
                ("memory_with_a_long_name".to_owned(), "c".to_owned()),
            ]
        );
        // The same module written with the short names, byte for byte.
        let expected = module(&[("./astar_bg.js", "a"), ("./astar_bg.js", "b")], "c");
        assert_eq!(output, expected);
        let (again, _) = shorten(&output).unwrap();
        assert_eq!(again, output, "shortening twice changes nothing more");
    }

    #[test]
    fn a_module_without_imports_is_unchanged_and_garbage_is_refused() {
        let bare = b"\0asm\x01\0\0\0\x01\x04\x01\x60\0\0".to_vec();
        assert_eq!(shorten(&bare).unwrap(), (bare.clone(), Vec::new()));
        assert!(shorten(b"not wasm").is_err());
        let mut cut = module(&[("m", "f")], "memory");
        cut.truncate(cut.len() - 10);
        assert!(shorten(&cut).is_err());
    }

    #[test]
    fn the_glue_keys_are_renamed_once_each() {
        let js = r#"return {"./m.js": {__wbg_a_0123456789abcdef: function(e) {}, __wbg_b_fedcba9876543210: function() {}}}"#;
        let renames = vec![
            ("__wbg_a_0123456789abcdef".to_owned(), "a".to_owned()),
            ("__wbg_b_fedcba9876543210".to_owned(), "b".to_owned()),
        ];
        assert_eq!(
            rename_in_glue(js, &renames).unwrap(),
            r#"return {"./m.js": {a: function(e) {}, b: function() {}}}"#
        );
        let twice = format!("{js} __wbg_a_0123456789abcdef");
        assert!(rename_in_glue(&twice, &renames).is_err());
        assert!(rename_in_glue("{}", &renames).is_err());
    }
}
