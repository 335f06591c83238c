//! Live math: an experiment's governing equations over its live quantities,
//! so the Simulation tab can show each one three times over — in symbols,
//! with the student's numbers put in, and the result, which is a readout.
//!
//! An experiment publishes its quantities ([`Quantity`]: a key, a symbol, a
//! value as shown and its unit) and its equations ([`Equation`]: a symbol,
//! an expression tree [`Expr`] over the quantities' keys, and the key of the
//! readout it produces). The tree is `const`, so an experiment's equations
//! are static data; [`Expr::eval`] evaluates it from the numbers *as shown*,
//! which is what the tests compare with the readout (within the display
//! rounding, propagated through the expression).
//!
//! Angles are shown in degrees: a quantity with unit `°` is a number of
//! degrees, and [`Expr::Cos`]/[`Expr::Sin`] take their argument in degrees,
//! as the substituted form reads (`1.00 m × cos 35°`). Every number is put
//! in with its unit ([`Quantity::unit`]: `rad` where a controller works in
//! radians beside a readout in degrees); a quantity without one is a pure
//! number (a count, a weight). Its symbol is the one the experiment's
//! Theory tab writes for it.

use crate::units::format_fixed;

/// One live quantity of an experiment, as the panel shows it.
#[derive(Clone, Debug, PartialEq)]
pub struct Quantity {
    /// Stable key; [`Expr::Var`] names it.
    pub key: &'static str,
    /// Its symbol: a base and an optional subscript after `_` (`θ_1`, `K_p`).
    pub symbol: &'static str,
    /// The value in the unit shown.
    pub value: f64,
    /// Decimals shown.
    pub decimals: usize,
    /// Unit shown after the number (`m`, `°`, `N/m`), or empty.
    pub unit: &'static str,
    /// Hidden by an instructor's link (`hide=m`): shown as "hidden", never
    /// as its number.
    pub hidden: bool,
}

impl Quantity {
    #[must_use]
    pub const fn new(
        key: &'static str,
        symbol: &'static str,
        value: f64,
        decimals: usize,
        unit: &'static str,
    ) -> Self {
        Self {
            key,
            symbol,
            value,
            decimals,
            unit,
            hidden: false,
        }
    }

    /// The number as shown (`0.80`), without its unit; `--` when there is
    /// none (no goal yet, no obstacle); `hidden` when [`Quantity::hidden`].
    /// A number that is not zero is never written as zero: where its
    /// decimals show none of it, it is written in the magnitude form
    /// (`1.1 × 10⁻²⁵⁶`), so what the equation computes from it follows
    /// from the numbers shown.
    #[must_use]
    pub fn number_text(&self) -> String {
        if self.hidden {
            "hidden".into()
        } else if self.value.is_finite() {
            let fixed = format_fixed(self.value, self.decimals);
            if self.value != 0.0 && fixed.bytes().all(|b| matches!(b, b'0' | b'.')) {
                crate::units::format_magnitude(self.value)
            } else {
                fixed
            }
        } else {
            "--".into()
        }
    }

    /// The value the shown number stands for (the rounding the student
    /// reads), the magnitude form's too.
    #[must_use]
    pub fn shown_value(&self) -> f64 {
        let text = self.number_text();
        let Some((mantissa, power)) = text.split_once(" × 10") else {
            return crate::units::parse_number(&text).unwrap_or(f64::NAN);
        };
        let exponent: String = power
            .chars()
            .map(|c| match "⁰¹²³⁴⁵⁶⁷⁸⁹".chars().position(|d| d == c) {
                Some(digit) => char::from(b'0' + digit as u8),
                None => '-',
            })
            .collect();
        format!("{mantissa}e{exponent}").parse().unwrap_or(f64::NAN)
    }
}

/// An expression over quantities; `const`-constructible, so equations are
/// static data.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Expr {
    /// A quantity, by key.
    Var(&'static str),
    /// A constant, written as given (`2`, `½`).
    Num(f64, &'static str),
    Add(&'static Expr, &'static Expr),
    Sub(&'static Expr, &'static Expr),
    /// A product: symbols side by side, numbers (with their units) with a
    /// cross between factors.
    Mul(&'static Expr, &'static Expr),
    /// A quotient, written as a fraction.
    Div(&'static Expr, &'static Expr),
    Neg(&'static Expr),
    /// Cosine of an angle in degrees.
    Cos(&'static Expr),
    /// Sine of an angle in degrees.
    Sin(&'static Expr),
    Sqrt(&'static Expr),
    /// Square.
    Sq(&'static Expr),
    /// The larger of two, written `max(a, b)`.
    Max(&'static Expr, &'static Expr),
    /// Arc cosine in degrees, of an argument clamped to `[-1, 1]` (as the
    /// solvers snap a target on a boundary onto it).
    Acos(&'static Expr),
    /// `a` held within `±b`, written `clamp(a, ±b)` (an actuator limit).
    Clamp(&'static Expr, &'static Expr),
    /// The smaller of two, written `min(a, b)`.
    Min(&'static Expr, &'static Expr),
    /// Natural logarithm, written `ln a`.
    Ln(&'static Expr),
    /// Cosine of an angle in radians (a controller's error in rad), written
    /// `cos` like [`Expr::Cos`]; the number shown carries no degree sign.
    CosRad(&'static Expr),
}

impl Expr {
    /// The value of the expression with each quantity at `value(key)`;
    /// NaN when a key has no value.
    #[must_use]
    pub fn eval(&self, value: &dyn Fn(&str) -> Option<f64>) -> f64 {
        match *self {
            Expr::Var(key) => value(key).unwrap_or(f64::NAN),
            Expr::Num(v, _) => v,
            Expr::Add(a, b) => a.eval(value) + b.eval(value),
            Expr::Sub(a, b) => a.eval(value) - b.eval(value),
            Expr::Mul(a, b) => a.eval(value) * b.eval(value),
            Expr::Div(a, b) => a.eval(value) / b.eval(value),
            Expr::Neg(a) => -a.eval(value),
            Expr::Cos(a) => libm::cos(a.eval(value).to_radians()),
            Expr::Sin(a) => libm::sin(a.eval(value).to_radians()),
            Expr::Sqrt(a) => libm::sqrt(a.eval(value)),
            Expr::Sq(a) => {
                let v = a.eval(value);
                v * v
            }
            Expr::Max(a, b) => a.eval(value).max(b.eval(value)),
            Expr::Acos(a) => libm::acos(a.eval(value).clamp(-1.0, 1.0)).to_degrees(),
            Expr::Clamp(a, b) => {
                let limit = b.eval(value).abs();
                a.eval(value).clamp(-limit, limit)
            }
            Expr::Min(a, b) => a.eval(value).min(b.eval(value)),
            Expr::Ln(a) => libm::log(a.eval(value)),
            Expr::CosRad(a) => libm::cos(a.eval(value)),
        }
    }

    /// Every quantity key the expression reads, in order of appearance.
    #[must_use]
    pub fn keys(&self) -> Vec<&'static str> {
        let mut out = Vec::new();
        self.collect_keys(&mut out);
        out
    }

    fn collect_keys(&self, out: &mut Vec<&'static str>) {
        match *self {
            Expr::Var(key) => {
                if !out.contains(&key) {
                    out.push(key);
                }
            }
            Expr::Num(..) => {}
            Expr::Add(a, b)
            | Expr::Sub(a, b)
            | Expr::Mul(a, b)
            | Expr::Div(a, b)
            | Expr::Max(a, b)
            | Expr::Min(a, b)
            | Expr::Clamp(a, b) => {
                a.collect_keys(out);
                b.collect_keys(out);
            }
            Expr::Neg(a)
            | Expr::Cos(a)
            | Expr::Sin(a)
            | Expr::Sqrt(a)
            | Expr::Sq(a)
            | Expr::Acos(a)
            | Expr::Ln(a)
            | Expr::CosRad(a) => {
                a.collect_keys(out);
            }
        }
    }
}

/// One governing equation of an experiment: `symbol = expr`, whose value is
/// the readout `readout`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Equation {
    /// Stable key naming the equation within its experiment (`x`, `omega_n`):
    /// the same in every variant of the equation set (a clamped and an
    /// unclamped `u` are both `u`), so content and links can refer to it.
    pub key: &'static str,
    /// What it computes (`x`, `ω_n`).
    pub symbol: &'static str,
    pub expr: Expr,
    /// The readout that shows its value.
    pub readout: &'static str,
    /// What the equation says, for the panel's caption and screen readers.
    pub caption: &'static str,
    /// Why there are no numbers to put in, said in words where a number the
    /// equation reads, or its readout, has no value (no goal yet, no
    /// landmark seen, a formula that holds only with Ki = 0): the panel
    /// then shows the symbols and these words, never a row of `--`.
    pub absent: &'static str,
}

/// The equations of `all` that `keys` name (the content's `math` list), in
/// the order of `keys`; a key without an equation is left out (the content
/// check refuses it).
#[must_use]
pub fn named(all: &[Equation], keys: &[String]) -> Vec<Equation> {
    keys.iter()
        .filter_map(|k| all.iter().find(|e| e.key == k))
        .copied()
        .collect()
}

/// Decimals that show `v` to four significant digits (3 for 1.234, 6 for
/// 0.001234, 0 for 2500), at most 12; 3 for zero or a non-finite value.
#[must_use]
pub fn four_significant(v: f64) -> usize {
    if v != 0.0 && v.is_finite() {
        (3 - libm::floor(libm::log10(v.abs())) as i32).clamp(0, 12) as usize
    } else {
        3
    }
}

/// The value of `key` among `quantities` as shown.
#[must_use]
pub fn shown(quantities: &[Quantity], key: &str) -> Option<f64> {
    quantities
        .iter()
        .find(|q| q.key == key)
        .map(Quantity::shown_value)
}

/// How an expression is written: with symbols, or with the shown numbers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Form {
    Symbols,
    Numbers,
}

/// The largest amount by which `expr` can move when each quantity it reads
/// moves by up to half a unit of its last shown digit: how far the
/// substituted form may honestly sit from a value computed from unrounded
/// numbers. Every corner of that box is tried (up to 10 quantities), so
/// roundings that add up across a kink such as `max(0, …)` count; beyond
/// that, each quantity's larger one-sided change is summed.
#[must_use]
pub fn rounding_bound(expr: &Expr, quantities: &[Quantity]) -> f64 {
    let keys = expr.keys();
    let centre = expr.eval(&|k| shown(quantities, k));
    let half = |key: &str| {
        quantities
            .iter()
            .find(|q| q.key == key)
            .map_or(0.0, |q| 0.5 * 10f64.powi(-(q.decimals as i32)))
    };
    // The value with each key `i` moved by `sign(i)` half digits.
    let moved = |sign: &dyn Fn(usize) -> f64| {
        expr.eval(&|k: &str| {
            let i = keys.iter().position(|key| *key == k)?;
            shown(quantities, k).map(|v| v + sign(i) * half(k))
        })
    };
    if keys.len() <= 10 {
        (0..1u32 << keys.len())
            .map(|corner| {
                let sign = |i: usize| if corner >> i & 1 == 1 { 1.0 } else { -1.0 };
                (moved(&sign) - centre).abs()
            })
            .fold(0.0, f64::max)
    } else {
        (0..keys.len())
            .map(|i| {
                let up = moved(&|j| if j == i { 1.0 } else { 0.0 });
                let down = moved(&|j| if j == i { -1.0 } else { 0.0 });
                (up - centre).abs().max((down - centre).abs())
            })
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const L1: Expr = Expr::Var("l1");
    const T1: Expr = Expr::Var("t1");
    const TIP_X: Expr = Expr::Mul(&L1, &Expr::Cos(&T1));

    fn arm(t1_deg: f64) -> Vec<Quantity> {
        vec![
            Quantity::new("l1", "L_1", 1.0, 2, "m"),
            Quantity::new("t1", "θ_1", t1_deg, 0, "°"),
        ]
    }

    #[test]
    fn an_expression_evaluates_from_the_numbers_as_shown() {
        let q = arm(60.0);
        let x = TIP_X.eval(&|k| shown(&q, k));
        assert!((x - 0.5).abs() < 1e-15, "{x}");
        // A value shown as 60 counts as 60, whatever digits lie behind it.
        let q = arm(60.4);
        assert!((TIP_X.eval(&|k| shown(&q, k)) - 0.5).abs() < 1e-15);
    }

    #[test]
    fn the_rounding_bound_is_the_spread_of_half_a_digit() {
        // x = L1·cos θ1 at 1.00 m, 0°: the farthest corner is L1 − 0.005 at
        // θ1 ± 0.5°, 1 − 0.995·cos 0.5°.
        let q = arm(0.0);
        let bound = rounding_bound(&TIP_X, &q);
        let expected = 1.0 - 0.995 * 0.5f64.to_radians().cos();
        assert!((bound - expected).abs() < 1e-9, "{bound}");
    }

    #[test]
    fn the_rounding_bound_counts_a_kink_at_its_corner() {
        // max(0, 2·L1 − 2) at L1 = 1.00: one side moves by 0.01, the other not.
        const HOLE: Expr = Expr::Max(
            &Expr::Num(0.0, "0"),
            &Expr::Sub(&Expr::Mul(&Expr::Num(2.0, "2"), &L1), &Expr::Num(2.0, "2")),
        );
        let bound = rounding_bound(&HOLE, &arm(0.0));
        assert!((bound - 0.01).abs() < 1e-9, "{bound}");
    }

    #[test]
    fn max_takes_the_larger_and_acos_clamps_its_argument() {
        const HOLE: Expr = Expr::Max(&Expr::Num(0.0, "0"), &Expr::Sub(&L1, &Expr::Num(2.0, "2")));
        let q = arm(0.0);
        assert_eq!(HOLE.eval(&|k| shown(&q, k)), 0.0);
        const EDGE: Expr = Expr::Acos(&Expr::Num(1.0000001, "1"));
        assert_eq!(EDGE.eval(&|_| None), 0.0);
        const HELD: Expr = Expr::Clamp(&Expr::Num(-7.0, "-7"), &Expr::Num(5.0, "5"));
        assert_eq!(HELD.eval(&|_| None), -5.0);
    }

    #[test]
    fn min_takes_the_smaller_ln_is_natural_and_cos_rad_reads_radians() {
        const CAP: Expr = Expr::Min(&L1, &Expr::Num(0.5, "0.5"));
        assert_eq!(CAP.eval(&|k| shown(&arm(0.0), k)), 0.5);
        const LOG: Expr = Expr::Ln(&Expr::Num(std::f64::consts::E, "e"));
        assert!((LOG.eval(&|_| None) - 1.0).abs() < 1e-15);
        const HALF_TURN: Expr = Expr::CosRad(&Expr::Num(std::f64::consts::PI, "π"));
        assert_eq!(HALF_TURN.eval(&|_| None), -1.0);
        // The keys of the new nodes are collected too.
        const ALL: Expr = Expr::Min(&Expr::Ln(&L1), &Expr::CosRad(&T1));
        assert_eq!(ALL.keys(), vec!["l1", "t1"]);
    }

    #[test]
    fn four_significant_digits_whatever_the_size() {
        assert_eq!(four_significant(1.234), 3);
        assert_eq!(four_significant(-0.001_234), 6);
        assert_eq!(four_significant(2500.0), 0);
        assert_eq!(four_significant(820.7), 1);
        assert_eq!(four_significant(1e-20), 12);
        assert_eq!(four_significant(0.0), 3);
        assert_eq!(four_significant(f64::NAN), 3);
    }

    /// Issue 27 §2: the panel shows the equations the content names, in the
    /// content's order.
    #[test]
    fn live_math_named_keeps_the_contents_order_and_only_those() {
        const fn eq(key: &'static str) -> Equation {
            Equation {
                key,
                symbol: "x",
                expr: Expr::Num(0.0, "0"),
                readout: "x",
                caption: "",
                absent: "",
            }
        }
        const ALL: [Equation; 3] = [eq("a"), eq("b"), eq("c")];
        let keys = |ks: &[&str]| ks.iter().map(|k| (*k).to_owned()).collect::<Vec<_>>();
        let picked: Vec<_> = named(&ALL, &keys(&["c", "a"]))
            .iter()
            .map(|e| e.key)
            .collect();
        assert_eq!(picked, ["c", "a"]);
        assert!(named(&ALL, &[]).is_empty());
    }

    #[test]
    fn keys_are_listed_once_in_order() {
        const E: Expr = Expr::Add(&TIP_X, &Expr::Mul(&L1, &Expr::Sin(&T1)));
        assert_eq!(E.keys(), vec!["l1", "t1"]);
    }
}
