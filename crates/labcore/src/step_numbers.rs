//! The numbers of a Procedure step are one: every number its prose writes is
//! one of the values of its machine part (what the student sets, waits for
//! or is told to read) or one it lists as `given` (a number of the theory,
//! not of this lab: "Experiment 2", "−c/(2m) = −0.5").
//!
//! Std only and free of the crate's other modules: `build.rs` compiles it in
//! too (`#[path]`), so the check stops the build of a file whose prose and
//! machine part disagree, and `Content::parse` runs the same code on files
//! being edited (`cargo xtask dist` validates every content file).

/// The numbers written in `text`, unsigned, in order: HTML tags and
/// entities are left out, and digits inside a word (`L1`, `x2`) are no
/// number; a decimal point counts only between digits (`1.30`, not `3.`).
#[must_use]
pub fn numbers_in(text: &str) -> Vec<(String, f64)> {
    let mut out = Vec::new();
    let chars: Vec<char> = strip_markup(text).chars().collect();
    let mut i = 0;
    while i < chars.len() {
        let starts = chars[i].is_ascii_digit()
            && (i == 0 || !(chars[i - 1].is_alphanumeric() || chars[i - 1] == '.'));
        if !starts {
            i += 1;
            continue;
        }
        let from = i;
        while i < chars.len() && chars[i].is_ascii_digit() {
            i += 1;
        }
        if i + 1 < chars.len() && chars[i] == '.' && chars[i + 1].is_ascii_digit() {
            i += 1;
            while i < chars.len() && chars[i].is_ascii_digit() {
                i += 1;
            }
        }
        let written: String = chars[from..i].iter().collect();
        // A number glued to a letter after it is a word's part (`2D`), but a
        // unit or symbol right after it (`3σ`, `10°`) keeps it a number.
        if let Ok(n) = written.parse::<f64>() {
            out.push((written, n));
        }
    }
    out
}

/// `text` without its HTML tags (`<em>`, `<sub>max</sub>` keeps `max`) and
/// with each entity (`&amp;`) as one space.
fn strip_markup(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut in_tag = false;
    let mut in_entity = false;
    for c in text.chars() {
        match c {
            '<' => in_tag = true,
            '>' if in_tag => in_tag = false,
            '&' if !in_tag => in_entity = true,
            ';' if in_entity => {
                in_entity = false;
                out.push(' ');
            }
            _ if in_tag || in_entity => {}
            _ => out.push(c),
        }
    }
    out
}

/// The two numbers are one value, whatever their sign or trailing zeros
/// (`−3` and `3`, `1.30` and `1.3`).
#[must_use]
pub fn same_value(a: f64, b: f64) -> bool {
    (a.abs() - b.abs()).abs() <= 1e-9 * a.abs().max(b.abs()).max(1.0)
}

/// The first number written in the prose `text` that is none of `values`,
/// as written; `None` when every one is.
#[must_use]
pub fn stray_number(text: &str, values: &[f64]) -> Option<String> {
    numbers_in(text)
        .into_iter()
        .find(|(_, n)| !values.iter().any(|v| same_value(*v, *n)))
        .map(|(written, _)| written)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_read_as_written_in_prose() {
        let found: Vec<f64> =
            numbers_in("Set <em>Kp</em> = 25, d = −3 N, L₁ 1.30 s, 3σ, x2 &amp; 2.")
                .into_iter()
                .map(|(_, n)| n)
                .collect();
        assert_eq!(found, vec![25.0, 3.0, 1.30, 3.0, 2.0]);
    }

    #[test]
    fn a_prose_number_missing_from_the_values_is_named() {
        assert_eq!(stray_number("Kp = 25 and Ki = 2", &[25.0, 2.0]), None);
        assert_eq!(stray_number("Rise 1.30 s", &[1.3]), None);
        assert_eq!(
            stray_number("Rise 1.30 s, settling 18.16 s", &[1.3]),
            Some("18.16".into())
        );
        assert_eq!(stray_number("d = −3 N", &[-3.0]), None);
    }
}
