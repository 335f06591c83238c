//! "The math" panel of the Simulation tab: each governing equation of an
//! experiment three times over — in symbols, with the student's numbers put
//! in, and the result, which is the readout — as MathML with a plain-text
//! twin that screen readers read ([`labcore::live_math`]).

use crate::experiment::Readout;
use labcore::live_math::{expr_text, symbol_text, Equation, Expr, Form, Quantity};
use std::fmt::Write as _;

/// The panel for `equations`, or an empty string when there are none.
#[must_use]
pub fn panel_html(equations: &[Equation], quantities: &[Quantity], readouts: &[Readout]) -> String {
    if equations.is_empty() {
        return String::new();
    }
    let mut out = String::from(
        "<section class=\"live-math\" aria-labelledby=\"live-math-title\">\
         <h3 id=\"live-math-title\">The math</h3>",
    );
    for (i, eq) in equations.iter().enumerate() {
        let (numbers, result, text) = live_parts(eq, quantities, readouts);
        let _ = write!(
            out,
            "<div class=\"equation\" data-equation=\"{i}\">\
             <p class=\"equation-caption\">{caption}</p>\
             <p class=\"equation-forms\" aria-hidden=\"true\">\
             <span class=\"eq-part\"><math>{lhs}<mo>=</mo>{symbols}</math></span> \
             <span class=\"equation-numbers\">{numbers}</span> \
             <span class=\"equation-result\">= {result}</span></p>\
             <p class=\"sr-only equation-text\">{text}</p></div>",
            caption = escape(eq.caption),
            lhs = symbol_mathml(eq.symbol),
            symbols = expr_mathml(&eq.expr, Form::Symbols, quantities),
        );
    }
    out.push_str("</section>");
    out
}

/// The parts of an equation that change with the run: the substituted form
/// (MathML), the result (the readout's text) and the whole equation as text.
#[must_use]
pub fn live_parts(
    eq: &Equation,
    quantities: &[Quantity],
    readouts: &[Readout],
) -> (String, String, String) {
    let numbers = wrapping_mathml(&eq.expr, quantities);
    let result = readouts
        .iter()
        .find(|r| r.key == eq.readout)
        .map_or_else(|| "--".to_owned(), |r| r.value.clone());
    let text = format!(
        "{} = {} = {} = {}",
        symbol_text(eq.symbol),
        expr_text(&eq.expr, Form::Symbols, quantities),
        expr_text(&eq.expr, Form::Numbers, quantities),
        result
    );
    (numbers, escape(&result), escape(&text))
}

/// The substituted form as MathML that may wrap between the terms of its
/// top-level sum: `<math>= 1.00·cos 35°</math> <math>+ 0.80·cos 95°</math>`
/// (a `<math>` element never breaks inside a narrow column).
#[must_use]
pub fn wrapping_mathml(expr: &Expr, quantities: &[Quantity]) -> String {
    let mut terms: Vec<(&str, &Expr)> = Vec::new();
    let mut rest = expr;
    loop {
        match *rest {
            Expr::Add(a, b) => {
                terms.push(("+", b));
                rest = a;
            }
            Expr::Sub(a, b) => {
                terms.push(("−", b));
                rest = a;
            }
            _ => {
                terms.push(("=", rest));
                break;
            }
        }
    }
    terms
        .iter()
        .rev()
        .map(|(op, term)| {
            let mut m = String::new();
            write_mathml(term, Form::Numbers, quantities, 2, &mut m);
            format!("<span class=\"eq-part\"><math><mo>{op}</mo>{m}</math></span>")
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// A symbol spec (`θ_1`, `K_p`, `x`) as MathML.
#[must_use]
pub fn symbol_mathml(symbol: &str) -> String {
    let token = |t: &str| {
        if !t.is_empty() && t.chars().all(|c| c.is_ascii_digit()) {
            format!("<mn>{t}</mn>")
        } else {
            format!("<mi>{}</mi>", escape(t))
        }
    };
    match symbol.split_once('_') {
        Some((base, sub)) => format!("<msub>{}{}</msub>", token(base), token(sub)),
        None => token(symbol),
    }
}

/// Binding strength, as in [`labcore::live_math`]'s text form.
fn precedence(expr: &Expr) -> u8 {
    match expr {
        Expr::Add(..) | Expr::Sub(..) => 1,
        Expr::Mul(..) | Expr::Div(..) => 2,
        Expr::Neg(..) => 3,
        _ => 4,
    }
}

/// `expr` as MathML, with symbols or with the shown numbers.
#[must_use]
pub fn expr_mathml(expr: &Expr, form: Form, quantities: &[Quantity]) -> String {
    let mut out = String::new();
    write_mathml(expr, form, quantities, 0, &mut out);
    out
}

fn write_mathml(expr: &Expr, form: Form, quantities: &[Quantity], outer: u8, out: &mut String) {
    let paren = precedence(expr) < outer;
    if paren {
        out.push_str("<mo>(</mo>");
    }
    match *expr {
        Expr::Var(key) => match quantities.iter().find(|q| q.key == key) {
            Some(q) if form == Form::Symbols => out.push_str(&symbol_mathml(q.symbol)),
            Some(q) => {
                let number = q.number_text();
                let (negative, digits) = match number.strip_prefix('-') {
                    Some(rest) => (true, rest.to_owned()),
                    None => (false, number),
                };
                let bracket = negative && outer > 0;
                if bracket {
                    out.push_str("<mo>(</mo>");
                }
                if negative {
                    out.push_str("<mo>−</mo>");
                }
                // The degree sign inside the number: as a trailing `<mo>`
                // Chromium may leave it out at the end of a `<math>`.
                let degrees = if q.unit == "°" { "°" } else { "" };
                let _ = write!(out, "<mn>{digits}{degrees}</mn>");
                if bracket {
                    out.push_str("<mo>)</mo>");
                }
            }
            None => {
                let _ = write!(out, "<mi>{}</mi>", escape(key));
            }
        },
        Expr::Num(_, text) => {
            let _ = write!(out, "<mn>{}</mn>", escape(text));
        }
        Expr::Add(a, b) | Expr::Sub(a, b) => {
            write_mathml(a, form, quantities, 1, out);
            out.push_str(if matches!(expr, Expr::Add(..)) {
                "<mo>+</mo>"
            } else {
                "<mo>−</mo>"
            });
            write_mathml(b, form, quantities, 2, out);
        }
        Expr::Mul(a, b) => {
            write_mathml(a, form, quantities, 2, out);
            // Symbols multiply by juxtaposition (L₁ cos θ₁); numbers need a dot.
            out.push_str(if form == Form::Symbols {
                "<mo>&#x2062;</mo>"
            } else {
                "<mo>·</mo>"
            });
            write_mathml(b, form, quantities, 3, out);
        }
        Expr::Div(a, b) => {
            out.push_str("<mfrac><mrow>");
            write_mathml(a, form, quantities, 0, out);
            out.push_str("</mrow><mrow>");
            write_mathml(b, form, quantities, 0, out);
            out.push_str("</mrow></mfrac>");
        }
        Expr::Neg(a) => {
            out.push_str("<mo>−</mo>");
            write_mathml(a, form, quantities, 3, out);
        }
        Expr::Cos(a) | Expr::Sin(a) => {
            let name = if matches!(expr, Expr::Cos(_)) {
                "cos"
            } else {
                "sin"
            };
            // A thin space after the name, as TeX sets `\cos\theta` (browsers
            // add none for the function-application operator).
            let _ = write!(out, "<mi>{name}</mi><mo>&#x2061;</mo>");
            if precedence(a) >= 4 {
                out.push_str("<mspace width=\"0.1667em\"></mspace>");
            }
            write_mathml(a, form, quantities, 4, out);
        }
        Expr::Sqrt(a) => {
            out.push_str("<msqrt>");
            write_mathml(a, form, quantities, 0, out);
            out.push_str("</msqrt>");
        }
        Expr::Sq(a) => {
            out.push_str("<msup><mrow>");
            write_mathml(a, form, quantities, 4, out);
            out.push_str("</mrow><mn>2</mn></msup>");
        }
        Expr::Acos(a) => {
            out.push_str("<mi>arccos</mi><mo>&#x2061;</mo><mo>(</mo>");
            write_mathml(a, form, quantities, 0, out);
            out.push_str("<mo>)</mo>");
        }
        Expr::Clamp(a, b) => {
            out.push_str("<mi>clamp</mi><mo>(</mo>");
            write_mathml(a, form, quantities, 0, out);
            out.push_str("<mo separator=\"true\">,</mo><mo>±</mo>");
            write_mathml(b, form, quantities, 4, out);
            out.push_str("<mo>)</mo>");
        }
        Expr::Max(a, b) => {
            out.push_str("<mi>max</mi><mo>(</mo>");
            write_mathml(a, form, quantities, 0, out);
            out.push_str("<mo separator=\"true\">,</mo>");
            write_mathml(b, form, quantities, 0, out);
            out.push_str("<mo>)</mo>");
        }
    }
    if paren {
        out.push_str("<mo>)</mo>");
    }
}

fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

#[cfg(test)]
mod tests {
    use super::*;

    const L: Expr = Expr::Var("l");
    const T: Expr = Expr::Var("t");
    const X: Expr = Expr::Mul(&L, &Expr::Cos(&T));
    const EQ: Equation = Equation {
        symbol: "x",
        expr: X,
        readout: "x",
        caption: "Tip x",
    };

    fn quantities(t_deg: f64) -> Vec<Quantity> {
        vec![
            Quantity::new("l", "L_1", 1.0, 2, "m"),
            Quantity::new("t", "θ_1", t_deg, 0, "°"),
        ]
    }

    #[test]
    fn a_symbol_with_a_subscript_is_an_msub() {
        assert_eq!(symbol_mathml("θ_1"), "<msub><mi>θ</mi><mn>1</mn></msub>");
        assert_eq!(symbol_mathml("K_p"), "<msub><mi>K</mi><mi>p</mi></msub>");
        assert_eq!(symbol_mathml("x"), "<mi>x</mi>");
    }

    #[test]
    fn the_panel_shows_symbols_numbers_and_the_readout() {
        let readouts = [Readout::new("x", "Tip X", "0.819 m")];
        let html = panel_html(&[EQ], &quantities(35.0), &readouts);
        assert!(html.contains("<h3 id=\"live-math-title\">The math</h3>"));
        assert!(html.contains(
            "<mi>x</mi><mo>=</mo><msub><mi>L</mi><mn>1</mn></msub><mo>&#x2062;</mo><mi>cos</mi>"
        ));
        assert!(html
            .contains("<span class=\"eq-part\"><math><mo>=</mo><mn>1.00</mn><mo>·</mo><mi>cos</mi><mo>&#x2061;</mo><mspace width=\"0.1667em\"></mspace><mn>35°</mn></math>"));
        assert!(html.contains("= 0.819 m"));
        assert!(html.contains("x = L1 cos θ1 = 1.00·cos 35° = 0.819 m"));
    }

    #[test]
    fn a_long_sum_is_written_a_term_to_a_math_element_so_it_can_wrap() {
        const SUM: Expr = Expr::Sub(&Expr::Add(&L, &T), &L);
        assert_eq!(
            wrapping_mathml(&SUM, &quantities(35.0)),
            "<span class=\"eq-part\"><math><mo>=</mo><mn>1.00</mn></math></span> \
             <span class=\"eq-part\"><math><mo>+</mo><mn>35°</mn></math></span> \
             <span class=\"eq-part\"><math><mo>−</mo><mn>1.00</mn></math></span>"
        );
    }

    #[test]
    fn no_equations_no_panel() {
        assert_eq!(panel_html(&[], &quantities(0.0), &[]), "");
    }

    #[test]
    fn a_negative_factor_is_bracketed_with_a_minus_sign() {
        let q = [
            Quantity::new("l", "L", 2.0, 1, ""),
            Quantity::new("t", "e", -0.5, 1, ""),
        ];
        const P: Expr = Expr::Mul(&L, &T);
        assert_eq!(
            expr_mathml(&P, Form::Numbers, &q),
            "<mn>2.0</mn><mo>·</mo><mo>(</mo><mo>−</mo><mn>0.5</mn><mo>)</mo>"
        );
    }
}
