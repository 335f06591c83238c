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
//! as the substituted form reads (`1.00·cos 35°`).

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
        }
    }

    /// The number as shown (`0.80`), without its unit.
    #[must_use]
    pub fn number_text(&self) -> String {
        format_fixed(self.value, self.decimals)
    }

    /// The value the shown number stands for (the rounding the student reads).
    #[must_use]
    pub fn shown_value(&self) -> f64 {
        crate::units::parse_number(&self.number_text()).unwrap_or(f64::NAN)
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
    /// A product, written with a middle dot between factors.
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
            | Expr::Clamp(a, b) => {
                a.collect_keys(out);
                b.collect_keys(out);
            }
            Expr::Neg(a)
            | Expr::Cos(a)
            | Expr::Sin(a)
            | Expr::Sqrt(a)
            | Expr::Sq(a)
            | Expr::Acos(a) => {
                a.collect_keys(out);
            }
        }
    }
}

/// One governing equation of an experiment: `symbol = expr`, whose value is
/// the readout `readout`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Equation {
    /// What it computes (`x`, `ω_n`).
    pub symbol: &'static str,
    pub expr: Expr,
    /// The readout that shows its value.
    pub readout: &'static str,
    /// What the equation says, for the panel's caption and screen readers.
    pub caption: &'static str,
}

/// The value of `key` among `quantities` as shown.
#[must_use]
pub fn shown(quantities: &[Quantity], key: &str) -> Option<f64> {
    quantities
        .iter()
        .find(|q| q.key == key)
        .map(Quantity::shown_value)
}

/// A symbol spec (`θ_1`) as plain text (`θ1`), for screen readers and the
/// text forms.
#[must_use]
pub fn symbol_text(symbol: &str) -> String {
    symbol.replace('_', "")
}

/// How an expression is written: with symbols, or with the shown numbers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Form {
    Symbols,
    Numbers,
}

/// The expression as plain text (`L1·cos θ1 + L2·cos(θ1 + θ2)` or
/// `1.00·cos 35° + 0.80·cos 95°`): the panel's text for screen readers.
#[must_use]
pub fn expr_text(expr: &Expr, form: Form, quantities: &[Quantity]) -> String {
    let mut out = String::new();
    write_text(expr, form, quantities, 0, &mut out);
    out
}

/// Binding strength: sums 1, products 2, unary minus 3, atoms 4.
fn precedence(expr: &Expr) -> u8 {
    match expr {
        Expr::Add(..) | Expr::Sub(..) => 1,
        Expr::Mul(..) | Expr::Div(..) => 2,
        Expr::Neg(..) => 3,
        _ => 4,
    }
}

fn write_text(expr: &Expr, form: Form, quantities: &[Quantity], outer: u8, out: &mut String) {
    let paren = precedence(expr) < outer;
    if paren {
        out.push('(');
    }
    match *expr {
        Expr::Var(key) => {
            let q = quantities.iter().find(|q| q.key == key);
            match (form, q) {
                (Form::Symbols, Some(q)) => out.push_str(&symbol_text(q.symbol)),
                (Form::Numbers, Some(q)) => {
                    let number = q.number_text();
                    let negative = number.starts_with('-');
                    if negative && outer > 0 {
                        out.push('(');
                    }
                    out.push_str(&number);
                    if q.unit == "°" {
                        out.push('°');
                    }
                    if negative && outer > 0 {
                        out.push(')');
                    }
                }
                (_, None) => out.push_str(key),
            }
        }
        Expr::Num(_, text) => out.push_str(text),
        Expr::Add(a, b) => {
            write_text(a, form, quantities, 1, out);
            out.push_str(" + ");
            write_text(b, form, quantities, 2, out);
        }
        Expr::Sub(a, b) => {
            write_text(a, form, quantities, 1, out);
            out.push_str(" − ");
            write_text(b, form, quantities, 2, out);
        }
        Expr::Mul(a, b) => {
            write_text(a, form, quantities, 2, out);
            // Symbols multiply by juxtaposition (`L1 cos θ1`); numbers need a dot.
            out.push_str(if form == Form::Symbols { " " } else { "·" });
            write_text(b, form, quantities, 3, out);
        }
        Expr::Div(a, b) => {
            write_text(a, form, quantities, 3, out);
            out.push_str(" / ");
            write_text(b, form, quantities, 3, out);
        }
        Expr::Neg(a) => {
            out.push('−');
            write_text(a, form, quantities, 3, out);
        }
        Expr::Cos(a) | Expr::Sin(a) => {
            out.push_str(if matches!(expr, Expr::Cos(_)) {
                "cos "
            } else {
                "sin "
            });
            write_text(a, form, quantities, 4, out);
        }
        Expr::Sqrt(a) => {
            out.push('√');
            write_text(a, form, quantities, 4, out);
        }
        Expr::Sq(a) => {
            write_text(a, form, quantities, 4, out);
            out.push('²');
        }
        Expr::Acos(a) => {
            out.push_str("acos(");
            write_text(a, form, quantities, 0, out);
            out.push(')');
        }
        Expr::Clamp(a, b) => {
            out.push_str("clamp(");
            write_text(a, form, quantities, 0, out);
            out.push_str(", ±");
            write_text(b, form, quantities, 4, out);
            out.push(')');
        }
        Expr::Max(a, b) => {
            out.push_str("max(");
            write_text(a, form, quantities, 0, out);
            out.push_str(", ");
            write_text(b, form, quantities, 0, out);
            out.push(')');
        }
    }
    if paren {
        out.push(')');
    }
}

/// The largest amount by which `expr` can move when each quantity it reads
/// moves by half a unit of its last shown digit (first order, by central
/// differences): how far the substituted form may honestly sit from a
/// value computed from unrounded numbers.
#[must_use]
pub fn rounding_bound(expr: &Expr, quantities: &[Quantity]) -> f64 {
    let base = |key: &str| shown(quantities, key);
    expr.keys()
        .iter()
        .map(|key| {
            let Some(q) = quantities.iter().find(|q| q.key == *key) else {
                return 0.0;
            };
            let half = 0.5 * 10f64.powi(-(q.decimals as i32));
            let at = |delta: f64| {
                expr.eval(&|k: &str| {
                    if k == *key {
                        base(k).map(|v| v + delta)
                    } else {
                        base(k)
                    }
                })
            };
            let h = half.max(1e-9);
            ((at(h) - at(-h)) / (2.0 * h)).abs() * half
        })
        .sum()
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
    fn the_text_forms_write_symbols_and_numbers_with_their_degrees() {
        let q = arm(35.0);
        assert_eq!(expr_text(&TIP_X, Form::Symbols, &q), "L1 cos θ1");
        assert_eq!(expr_text(&TIP_X, Form::Numbers, &q), "1.00·cos 35°");
        const SUM: Expr = Expr::Cos(&Expr::Add(&T1, &T1));
        assert_eq!(expr_text(&SUM, Form::Symbols, &q), "cos (θ1 + θ1)");
    }

    #[test]
    fn a_negative_number_inside_a_product_is_bracketed() {
        let q = vec![
            Quantity::new("k", "K", 2.0, 1, ""),
            Quantity::new("e", "e", -0.25, 2, "m"),
        ];
        const P: Expr = Expr::Mul(&Expr::Var("k"), &Expr::Var("e"));
        assert_eq!(expr_text(&P, Form::Numbers, &q), "2.0·(-0.25)");
    }

    #[test]
    fn the_rounding_bound_is_the_first_order_spread_of_half_a_digit() {
        // x = L1·cos θ1 at 1.00 m, 0°: ∂x/∂L1 = 1 (half digit 0.005), ∂x/∂θ1 = 0.
        let q = arm(0.0);
        let bound = rounding_bound(&TIP_X, &q);
        assert!((bound - 0.005).abs() < 1e-6, "{bound}");
    }

    #[test]
    fn max_takes_the_larger_and_is_written_as_a_function() {
        const HOLE: Expr = Expr::Max(&Expr::Num(0.0, "0"), &Expr::Sub(&L1, &Expr::Num(2.0, "2")));
        let q = arm(0.0);
        assert_eq!(HOLE.eval(&|k| shown(&q, k)), 0.0);
        assert_eq!(expr_text(&HOLE, Form::Symbols, &q), "max(0, L1 − 2)");
        assert_eq!(expr_text(&HOLE, Form::Numbers, &q), "max(0, 1.00 − 2)");
    }

    #[test]
    fn keys_are_listed_once_in_order() {
        const E: Expr = Expr::Add(&TIP_X, &Expr::Mul(&L1, &Expr::Sin(&T1)));
        assert_eq!(E.keys(), vec!["l1", "t1"]);
    }
}
