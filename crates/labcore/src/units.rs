//! Numbers with units, written and read the same way everywhere: the
//! readouts (`1.500 m`, `-35.0°`), the scene descriptions, the plots, the
//! report, the link and the quiz (`8000 m`, `5 m⁻¹`), and the numbers
//! students type into a number box or a quiz answer (`8 km`, `1.2 rad`,
//! `8,000`).
//!
//! Writing: [`format_number`] (at most N decimals, trailing zeros trimmed),
//! [`format_fixed`] (exactly N decimals), [`format_metres`] and
//! [`format_degrees`] (the readouts' units and decimals), [`format_point`],
//! [`format_magnitude`] (many orders of magnitude) and [`with_unit`].
//! Reading: [`read_number`], [`read_answer`] (with unit conversion) and their
//! `parse_*` forms that drop the details. None of them panics, and a value
//! that is not finite is written as `--`.

use glam::DVec2;

/// Decimals of every length readout, in every experiment (1 mm).
pub const METRE_DECIMALS: usize = 3;
/// Decimals of every angle readout, in every experiment (0.1°).
pub const DEGREE_DECIMALS: usize = 1;

/// `8000 m`, `45°`, `70.7%`, `5 m⁻¹`: a number followed by its unit.
pub fn with_unit(number: &str, unit: &str) -> String {
    match unit.trim() {
        "" => number.to_owned(),
        "°" | "%" => format!("{number}{}", unit.trim()),
        "1/m" => format!("{number} m⁻¹"),
        u => format!("{number} {u}"),
    }
}

/// A number as it was read, and how to show it (`8000 m`).
#[derive(Clone, Debug, PartialEq)]
pub struct Reading {
    /// The value in the question's (or field's) unit.
    pub value: f64,
    /// The value with that unit, e.g. `8000 m`, for “read as 8000 m”.
    pub read_as: String,
}

/// Why a typed number could not be read. The message says what to type instead.
#[derive(Clone, Debug, PartialEq)]
pub enum ReadError {
    Empty,
    /// Not a number at all (`one`, `1.2.3`, `NaN`, `1e999`).
    NotANumber {
        text: String,
    },
    /// A comma that is not a thousands separator (`1,5`, `0,25`, `12,34`).
    AmbiguousComma {
        text: String,
    },
    /// A unit that cannot be converted to the expected one (`3 s` for metres).
    WrongUnit {
        given: String,
        expected: String,
    },
}

impl std::fmt::Display for ReadError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ReadError::Empty => write!(f, "nothing was typed"),
            ReadError::NotANumber { text } => write!(f, "“{text}” is not a number"),
            ReadError::AmbiguousComma { text } => write!(
                f,
                "“{text}”: a comma only separates thousands, as in 8,000; write decimals with a point, as in 1.5"
            ),
            ReadError::WrongUnit { given, expected } if expected.is_empty() => {
                write!(f, "this answer has no unit, but “{given}” was typed")
            }
            ReadError::WrongUnit { given, expected } => {
                write!(f, "“{given}” cannot be converted to {expected}")
            }
        }
    }
}

impl std::error::Error for ReadError {}

/// The units an answer in `unit` may be typed in, with the factor that
/// converts each to `unit`. Lower case; matched after lower-casing the text.
fn unit_aliases(unit: &str) -> Vec<(&'static str, f64)> {
    use std::f64::consts::PI;
    const METRE: [&str; 5] = ["m", "metre", "metres", "meter", "meters"];
    let deg_per_rad = 180.0 / PI;
    let with = |names: &[&'static str], factor: f64| -> Vec<(&'static str, f64)> {
        names.iter().map(|n| (*n, factor)).collect()
    };
    match unit {
        "m" => [
            with(&METRE, 1.0),
            with(
                &[
                    "cm",
                    "centimetre",
                    "centimetres",
                    "centimeter",
                    "centimeters",
                ],
                0.01,
            ),
            with(
                &[
                    "mm",
                    "millimetre",
                    "millimetres",
                    "millimeter",
                    "millimeters",
                ],
                0.001,
            ),
            with(
                &["km", "kilometre", "kilometres", "kilometer", "kilometers"],
                1000.0,
            ),
        ]
        .concat(),
        "°" => [
            with(&["°", "deg", "degs", "degree", "degrees"], 1.0),
            with(&["rad", "rads", "radian", "radians"], deg_per_rad),
        ]
        .concat(),
        "rad" => [
            with(&["rad", "rads", "radian", "radians"], 1.0),
            with(
                &["°", "deg", "degs", "degree", "degrees"],
                1.0 / deg_per_rad,
            ),
        ]
        .concat(),
        "%" => with(&["%", "percent", "per cent"], 1.0),
        "m²" => [
            with(
                &[
                    "m²",
                    "m2",
                    "m^2",
                    "sq m",
                    "square metre",
                    "square metres",
                    "square meter",
                    "square meters",
                ],
                1.0,
            ),
            with(&["cm²", "cm2", "cm^2"], 1e-4),
        ]
        .concat(),
        "1/m" => [
            with(
                &[
                    "1/m",
                    "/m",
                    "m⁻¹",
                    "m^-1",
                    "m-1",
                    "per m",
                    "per metre",
                    "per meter",
                ],
                1.0,
            ),
            with(&["1/cm", "/cm", "cm⁻¹", "cm^-1", "per cm"], 100.0),
        ]
        .concat(),
        "m/rad" => with(
            &["m/rad", "m / rad", "m per rad", "m/radian", "m per radian"],
            1.0,
        ),
        _ => Vec::new(),
    }
}

/// Splits `text` into its leading number (sign, digits, commas, one point,
/// exponent) and the rest, both trimmed. Unicode minus and en dash count as `-`.
fn split_number(text: &str) -> (String, String) {
    let text: String = text.trim().replace(['\u{2212}', '\u{2013}'], "-");
    let chars: Vec<char> = text.chars().collect();
    let mut i = 0;
    if matches!(chars.first(), Some('+' | '-')) {
        i = 1;
    }
    while i < chars.len() && (chars[i].is_ascii_digit() || chars[i] == '.' || chars[i] == ',') {
        i += 1;
    }
    // An exponent only when digits follow (`1e-3`; `5e` is 5 and a unit “e”).
    if i > 0 && matches!(chars.get(i), Some('e' | 'E')) {
        let mut j = i + 1;
        if matches!(chars.get(j), Some('+' | '-')) {
            j += 1;
        }
        if chars.get(j).is_some_and(char::is_ascii_digit) {
            while chars.get(j).is_some_and(char::is_ascii_digit) {
                j += 1;
            }
            i = j;
        }
    }
    let number: String = chars[..i].iter().collect();
    let rest: String = chars[i..].iter().collect();
    (number, rest.trim().to_owned())
}

/// Reads the number part. The comma rule, the same everywhere: a comma is a
/// thousands separator, allowed only between groups of exactly three digits
/// before the decimal point (`8,000`, `1,234,567.5`). Any other comma (`1,5`,
/// `0,25`, `12,34`) is ambiguous and refused with a message, never guessed.
fn read_plain_number(number: &str, original: &str) -> Result<f64, ReadError> {
    let (mantissa, _) = number
        .find(['e', 'E'])
        .map_or((number, ""), |k| number.split_at(k));
    let unsigned = mantissa.trim_start_matches(['+', '-']);
    let (int_part, frac_part) = unsigned.split_once('.').unwrap_or((unsigned, ""));
    if unsigned.contains(',') {
        let groups: Vec<&str> = int_part.split(',').collect();
        let thousands = !frac_part.contains(',')
            && (1..=3).contains(&groups[0].len())
            && groups[1..].iter().all(|g| g.len() == 3);
        if !thousands {
            return Err(ReadError::AmbiguousComma {
                text: truncate_chars(original.trim(), 30),
            });
        }
    }
    let cleaned = number.replace(',', "");
    match cleaned.parse::<f64>() {
        Ok(v) if v.is_finite() && cleaned.chars().any(|c| c.is_ascii_digit()) => Ok(v),
        _ => Err(ReadError::NotANumber {
            text: truncate_chars(original.trim(), 30),
        }),
    }
}

fn truncate_chars(s: &str, max: usize) -> String {
    if s.chars().count() <= max {
        s.to_owned()
    } else {
        let mut t: String = s.chars().take(max).collect();
        t.push('…');
        t
    }
}

/// Reads an answer given in `unit`: a number (the comma rule of
/// [`read_number`]), optionally followed by that unit or one convertible to
/// it — `m`: metres/meters, cm, mm, km; `°`: deg, degrees, rad, radians;
/// `rad`: radians, °, deg; `m²`: m2, m^2, cm²; `1/m`: /m, m⁻¹, per metre;
/// `%`: percent. A number with no unit is taken in `unit`. The result says
/// how the text was read (`8 km` → `8000 m`).
///
/// # Example
/// ```
/// use labcore::units::read_answer;
/// assert_eq!(read_answer("8 km", "m").unwrap().read_as, "8000 m");
/// assert_eq!(read_answer("51/m", "1/m").unwrap().value, 51.0);
/// assert!(read_answer("1,5", "m").is_err());
/// ```
pub fn read_answer(text: &str, unit: &str) -> Result<Reading, ReadError> {
    if text.trim().is_empty() {
        return Err(ReadError::Empty);
    }
    let unit = unit.trim();
    let (number, rest) = split_number(text);
    if number.is_empty() {
        return Err(ReadError::NotANumber {
            text: truncate_chars(text.trim(), 30),
        });
    }
    let value = read_plain_number(&number, text)?;
    let factor = if rest.is_empty() {
        1.0
    } else {
        let given = rest.to_ascii_lowercase();
        let given = given.split_whitespace().collect::<Vec<_>>().join(" ");
        let mut aliases = unit_aliases(unit);
        if aliases.is_empty() && !unit.is_empty() {
            aliases.push((unit, 1.0));
        }
        let found = aliases
            .iter()
            .find(|(name, _)| name.to_ascii_lowercase() == given)
            .map(|(_, f)| *f);
        match found {
            Some(f) => f,
            None => {
                return Err(ReadError::WrongUnit {
                    given: truncate_chars(&rest, 20),
                    expected: unit.to_owned(),
                })
            }
        }
    };
    let value = value * factor;
    if !value.is_finite() {
        return Err(ReadError::NotANumber {
            text: truncate_chars(text.trim(), 30),
        });
    }
    Ok(Reading {
        value,
        read_as: with_unit(&format_number(value, 6), unit),
    })
}

/// [`read_answer`] without the details: the value, or `None`.
#[must_use]
pub fn parse_answer(text: &str, unit: &str) -> Option<f64> {
    read_answer(text, unit).ok().map(|r| r.value)
}

/// Reads a number the way students type it (surrounding spaces, a Unicode
/// minus, a leading `+`, an exponent, a trailing `°`), with the one comma rule
/// of the lab: a comma separates thousands only (`8,000`); `1,5` is refused
/// as ambiguous rather than read as 15 or 1.5. The [`Reading`] says what was
/// read so a number box can show it (“read as 8000”); the error says what to
/// type instead. For a field with a unit, [`read_answer`] also converts
/// (`1.2 rad` in a degree field).
pub fn read_number(text: &str) -> Result<Reading, ReadError> {
    read_answer(text, "°").and_then(|r| {
        // Only a degree sign may follow a bare number; other units need
        // `read_answer` with the field's unit.
        let (_, rest) = split_number(text);
        if rest.is_empty() || rest == "°" {
            Ok(Reading {
                read_as: format_number(r.value, 6),
                value: r.value,
            })
        } else {
            Err(ReadError::WrongUnit {
                given: truncate_chars(&rest, 20),
                expected: String::new(),
            })
        }
    })
}

/// [`read_number`] without the details: the value, or `None` (also for `1,5`).
#[must_use]
pub fn parse_number(text: &str) -> Option<f64> {
    read_number(text).ok().map(|r| r.value)
}

/// 10^`k`, correctly rounded (`10f64.powf(k)` may be an ulp off), read from its
/// decimal text: the page's float parser is in every wasm module already,
/// where `powf` would add libm's `pow` (about 1 KB gzip) to it.
#[must_use]
pub fn power_of_ten(k: i32) -> f64 {
    format!("1e{k}").parse().unwrap_or(f64::NAN)
}

/// Formats with at most `decimals` places, trailing zeros trimmed, `-0` as `0`.
#[must_use]
pub fn format_number(value: f64, decimals: usize) -> String {
    if !value.is_finite() {
        return "--".into();
    }
    let s = format!("{value:.decimals$}");
    let s = if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        s
    };
    if s == "-0" {
        "0".into()
    } else {
        s
    }
}

/// A length as every readout shows it: `1.500 m`.
#[must_use]
pub fn format_metres(value_m: f64) -> String {
    if value_m.is_finite() {
        format!("{} m", format_fixed(value_m, METRE_DECIMALS))
    } else {
        "--".into()
    }
}

/// A length of any size: [`format_metres`] (`1.500 m`) below a kilometre,
/// a power of ten beyond (`6.9 × 10³³ m`), never dozens of digits; `--`
/// when it is not finite.
#[must_use]
pub fn format_length(value_m: f64) -> String {
    if value_m.abs() < 1e3 || !value_m.is_finite() {
        format_metres(value_m)
    } else {
        format!("{} m", format_magnitude(value_m))
    }
}

/// An angle as every readout shows it: `-35.0°`.
#[must_use]
pub fn format_degrees(value_deg: f64) -> String {
    if value_deg.is_finite() {
        format!("{}°", format_fixed(value_deg, DEGREE_DECIMALS))
    } else {
        "--".into()
    }
}

/// Exactly `decimals` places, and no `-0.000` (a tiny negative shows as zero).
#[must_use]
pub fn format_fixed(value: f64, decimals: usize) -> String {
    let s = format!("{value:.decimals$}");
    match s.strip_prefix('-') {
        Some(rest) if rest.chars().all(|c| c == '0' || c == '.') => rest.to_owned(),
        _ => s,
    }
}

/// A positive quantity that spans many orders of magnitude (a condition
/// number, a tiny error), readable at a glance: `12.3` below 1000, else one
/// decimal times a power of ten, `2.4 × 10⁵` or `3.1 × 10⁻⁷`; infinity as
/// `∞ (singular)`.
#[must_use]
pub fn format_magnitude(value: f64) -> String {
    if value.is_nan() {
        return "--".into();
    }
    if value.is_infinite() {
        return "∞ (singular)".into();
    }
    let magnitude = value.abs();
    if magnitude == 0.0 || (1e-3..1e3).contains(&magnitude) {
        return format_fixed(value, if magnitude < 1.0 { 3 } else { 1 });
    }
    // The standard library's scientific form rounds the decimal digits
    // exactly over the whole range, subnormals included (`4.9e-324`); a
    // division by `10^exponent` does not (it is 0 below 10⁻³⁰⁸).
    let scientific = format!("{value:.1e}");
    let (mantissa, exponent) = scientific.split_once('e').unwrap_or((&scientific, "0"));
    let exponent: i32 = exponent.parse().unwrap_or(0);
    format!("{mantissa} × 10{}", superscript(exponent))
}

/// `-7` → `⁻⁷`.
#[must_use]
pub fn superscript(n: i32) -> String {
    const DIGITS: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let mut s = String::new();
    if n < 0 {
        s.push('⁻');
    }
    for c in n.unsigned_abs().to_string().chars() {
        s.push(DIGITS[c.to_digit(10).unwrap_or(0) as usize]);
    }
    s
}
/// `(2.10, 3.40) m`: a point as the scene descriptions say it.
#[must_use]
pub fn format_point(p: DVec2) -> String {
    format!("({}, {}) m", format_fixed(p.x, 2), format_fixed(p.y, 2))
}

#[cfg(test)]
mod tests {
    #[test]
    fn power_of_ten_is_powf_of_ten_for_every_finite_decade() {
        // Exact where 10^k is a double (k ≤ 22), and within an ulp of powf
        // everywhere (powf itself may be an ulp off).
        for k in 0..=22u32 {
            assert_eq!(power_of_ten(k as i32), 10u128.pow(k) as f64, "10^{k}");
        }
        for k in -307..=308 {
            let (p, q) = (power_of_ten(k), 10f64.powf(f64::from(k)));
            assert!(
                (p - q).abs() <= p * f64::EPSILON,
                "10^{k}: {p:e} against {q:e}"
            );
        }
        assert_eq!(power_of_ten(400), f64::INFINITY);
        assert_eq!(power_of_ten(-400), 0.0);
    }

    use super::*;

    /// Hand-computed: the binary value nearest 9.995 is 9.99499999999999921840…,
    /// so it rounds down at two decimals; 0.125 is exact and a tie, which the
    /// standard library rounds to even (0.12); 1e21 keeps every digit.
    #[test]
    fn rounding_boundaries_follow_the_binary_value() {
        assert_eq!(format_number(9.995, 2), "9.99");
        assert_eq!(format_fixed(9.995, 2), "9.99");
        assert_eq!(format_number(9.9951, 2), "10");
        assert_eq!(format_fixed(9.9951, 2), "10.00");
        assert_eq!(format_number(0.125, 2), "0.12");
        assert_eq!(format_number(0.375, 2), "0.38");
        assert_eq!(format_number(2.5, 0), "2");
        assert_eq!(format_number(1e21, 0), "1000000000000000000000");
        assert_eq!(format_metres(0.0005), "0.001 m");
        assert_eq!(format_metres(0.000_499), "0.000 m");
        assert_eq!(format_degrees(0.05), "0.1°");
        assert_eq!(format_degrees(0.049), "0.0°");
        assert_eq!(format_magnitude(999.94), "999.9");
        assert_eq!(format_magnitude(999.96), "1000.0");
        assert_eq!(format_magnitude(1000.0), "1.0 × 10³");
        assert_eq!(format_magnitude(0.001), "0.001");
        assert_eq!(format_magnitude(0.000_999), "1.0 × 10⁻³");
    }

    /// Not finite and negative zero: `--` for NaN and infinities (a magnitude
    /// says `∞ (singular)`), and never a `-0`.
    #[test]
    fn nan_infinities_and_negative_zero() {
        for v in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert_eq!(format_number(v, 3), "--", "{v}");
            assert_eq!(format_metres(v), "--", "{v}");
            assert_eq!(format_degrees(v), "--", "{v}");
        }
        assert_eq!(format_magnitude(f64::NAN), "--");
        assert_eq!(format_magnitude(f64::NEG_INFINITY), "∞ (singular)");
        assert_eq!(format_number(-0.0, 3), "0");
        assert_eq!(format_number(-0.0004, 3), "0");
        assert_eq!(format_number(-0.0005, 3), "-0.001");
        assert_eq!(format_fixed(-0.0, 2), "0.00");
        assert_eq!(format_fixed(-0.004, 2), "0.00");
        assert_eq!(format_fixed(-0.005, 2), "-0.01");
        assert_eq!(format_metres(-0.0), "0.000 m");
        assert_eq!(format_degrees(-0.01), "0.0°");
        assert_eq!(format_magnitude(-0.0), "0.000");
        assert_eq!(format_magnitude(0.0), "0.000");
        assert_eq!(format_point(DVec2::new(-0.001, 2.1)), "(0.00, 2.10) m");
    }

    /// A number and its unit, as the quiz shows an expected answer.
    #[test]
    fn with_unit_places_each_unit() {
        assert_eq!(with_unit("8000", "m"), "8000 m");
        assert_eq!(with_unit("45", "°"), "45°");
        assert_eq!(with_unit("70.7", " % "), "70.7%");
        assert_eq!(with_unit("5", "1/m"), "5 m⁻¹");
        assert_eq!(with_unit("1.5", ""), "1.5");
        assert_eq!(with_unit("1.5", "m/rad"), "1.5 m/rad");
    }

    /// What a number box says it read: the value written back with up to six
    /// decimals and the field's unit.
    #[test]
    fn a_reading_writes_back_what_was_read() {
        let r = read_answer("8 km", "m").unwrap();
        assert_eq!((r.value, r.read_as.as_str()), (8000.0, "8000 m"));
        let r = read_answer("−1,234.5", "°").unwrap();
        assert_eq!((r.value, r.read_as.as_str()), (-1234.5, "-1234.5°"));
        let r = read_number("1e-7").unwrap();
        assert_eq!((r.value, r.read_as.as_str()), (1e-7, "0"));
        assert_eq!(read_number("   "), Err(ReadError::Empty));
        assert!(matches!(
            read_answer("3 s", "m"),
            Err(ReadError::WrongUnit { .. })
        ));
        assert_eq!(parse_number("1e308"), Some(1e308));
        assert_eq!(parse_answer("1e308 km", "m"), None);
    }

    #[test]
    fn parses_what_students_type() {
        assert_eq!(parse_number(" 1.5 "), Some(1.5));
        assert_eq!(parse_number("−0.25"), Some(-0.25));
        assert_eq!(parse_number("+3"), Some(3.0));
        assert_eq!(parse_number("45°"), Some(45.0));
        assert_eq!(parse_number("1.2 m"), None);
        assert_eq!(parse_answer("1.2 m", "m"), Some(1.2));
        assert_eq!(parse_answer("1.2M", "m"), Some(1.2));
        assert_eq!(parse_answer("0.5 m²", "m²"), Some(0.5));
        assert_eq!(parse_answer("45 deg", "°"), Some(45.0));
        assert_eq!(parse_answer("45°", "°"), Some(45.0));
        assert_eq!(parse_answer("1.2 s", "°"), None);
        assert_eq!(parse_number("1e-3"), Some(0.001));
        assert_eq!(parse_number(""), None);
        assert_eq!(parse_number("abc"), None);
        assert_eq!(parse_number("1.2.3"), None);
        assert_eq!(parse_number("NaN"), None);
        assert_eq!(parse_number("inf"), None);
        assert_eq!(parse_number("1e999"), None);
        assert_eq!(parse_number("-"), None);
        assert_eq!(parse_number("."), None);
    }

    /// Regression: “0.5 m2” was not recognised for m².
    #[test]
    fn a_length_of_any_size_reads_in_metres_or_as_a_power_of_ten() {
        assert_eq!(format_length(0.7495), "0.750 m");
        assert_eq!(format_length(-999.0), "-999.000 m");
        assert_eq!(format_length(6.9e33), "6.9 × 10³³ m");
        assert_eq!(format_length(-2.5e4), "-2.5 × 10⁴ m");
        assert_eq!(format_length(f64::NAN), "--");
        assert_eq!(format_length(f64::INFINITY), "--");
    }

    #[test]
    fn square_metres_accept_m2_and_m_caret_2() {
        for text in [
            "0.5 m2",
            "0.5m2",
            "0.5 m^2",
            "0.5 M²",
            "0.5 square metres",
            "5000 cm²",
        ] {
            assert_eq!(parse_answer(text, "m²"), Some(0.5), "{text}");
        }
        assert_eq!(parse_answer("0.5 m", "m²"), None);
    }

    #[test]
    fn formats_trimmed() {
        assert_eq!(format_number(1.5, 3), "1.5");
        assert_eq!(format_number(2.0, 3), "2");
        assert_eq!(format_number(-0.0001, 3), "0");
        assert_eq!(format_number(1.23456, 3), "1.235");
        assert_eq!(format_number(f64::NAN, 3), "--");
    }

    #[test]
    fn readout_formats() {
        assert_eq!(format_metres(1.5), "1.500 m");
        assert_eq!(format_metres(-0.0001), "0.000 m");
        assert_eq!(format_degrees(-35.0), "-35.0°");
        assert_eq!(format_magnitude(f64::INFINITY), "∞ (singular)");
        assert_eq!(format_magnitude(2.4e5), "2.4 × 10⁵");
        assert_eq!(format_magnitude(99_960.0), "1.0 × 10⁵");
        assert_eq!(format_magnitude(3.14e-7), "3.1 × 10⁻⁷");
        assert_eq!(format_magnitude(12.34), "12.3");
        assert_eq!(format_magnitude(0.0123), "0.012");
    }

    /// Reads `format_magnitude`'s text back against `v`: the shown mantissa
    /// (or fixed number) and `v` in the same power of ten, with the half unit
    /// of the last shown digit. `2.4 × 10⁻⁷` → `(2.4, v·10⁷, 0.05)`; scaling
    /// by the decimal exponent in text keeps 1.8 × 10³⁰⁸ from overflowing.
    fn read_magnitude(text: &str, v: f64) -> (f64, f64, f64) {
        match text.split_once(" × 10") {
            Some((mantissa, power)) => {
                let exponent: i32 = power
                    .chars()
                    .map(|c| match c {
                        '⁻' => '-',
                        c => char::from_digit(
                            "⁰¹²³⁴⁵⁶⁷⁸⁹".chars().position(|d| d == c).unwrap() as u32,
                            10,
                        )
                        .unwrap(),
                    })
                    .collect::<String>()
                    .parse()
                    .unwrap();
                let exact = format!("{v:.20e}");
                let (digits, own) = exact.split_once('e').unwrap();
                let own: i32 = own.parse().unwrap();
                let scaled: f64 = format!("{digits}e{}", own - exponent).parse().unwrap();
                (mantissa.parse().unwrap(), scaled, 0.05)
            }
            None => {
                let decimals = text.split_once('.').map_or(0, |(_, d)| d.len());
                let half_unit = 0.5 * 10f64.powi(-(decimals as i32));
                (text.parse().unwrap(), v, half_unit)
            }
        }
    }

    /// Issue 23 §5: below about 10⁻³⁰⁸ the old division by `10^exponent`
    /// gave "inf × 10⁻³⁰⁹". Every finite value, subnormals and the extremes
    /// included, prints a finite number that reads back within its rounding.
    #[test]
    fn format_magnitude_reads_back_over_the_whole_f64_range() {
        let mut rng = crate::rng::Lcg64::new(23);
        let mut values = vec![
            2.225_073_858_507_201_4e-308,
            2.225_073_858_507_201e-308,
            5e-324,
            -5e-324,
            f64::MIN_POSITIVE,
            f64::MAX,
            f64::MIN,
            9.96e-309,
            9.95e-324,
            1e-3,
            999.96,
        ];
        for _ in 0..20_000 {
            // Any bit pattern (most of them are huge or tiny), and values
            // spread evenly over the decimal exponents.
            values.push(f64::from_bits(rng.next_u64()));
            let v = 10f64.powf(rng.range(-330.0, 309.0)) * rng.range(-10.0, 10.0);
            values.push(v);
        }
        for v in values.into_iter().filter(|v| v.is_finite()) {
            let text = format_magnitude(v);
            assert!(
                !text.contains("inf") && !text.contains("NaN") && !text.contains('∞'),
                "{v:e} → {text}"
            );
            let (shown, exact, half_unit) = read_magnitude(&text, v);
            assert!(
                (shown - exact).abs() <= half_unit * (1.0 + 1e-9),
                "{v:e} → {text}: {shown} against {exact}"
            );
            assert!(shown.abs() < 10.0 || !text.contains('×'), "{v:e} → {text}");
        }
        // The three links of the issue.
        assert_eq!(
            format_magnitude(2.225_073_858_507_201_4e-308),
            "2.2 × 10⁻³⁰⁸"
        );
        assert_eq!(
            format_magnitude(-2.225_073_858_507_201e-308),
            "-2.2 × 10⁻³⁰⁸"
        );
        assert_eq!(format_magnitude(5e-324), "4.9 × 10⁻³²⁴");
    }
}
