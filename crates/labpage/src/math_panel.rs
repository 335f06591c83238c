//! "The math" panel of the Simulation tab: each governing equation of an
//! experiment three times over — in symbols, with the student's numbers put
//! in, and the result, which is the readout — as MathML with a plain-text
//! twin that screen readers read ([`labcore::live_math`]). One writer
//! ([`Writer`]) serves both, so the two cannot say different things.

use crate::experiment::Readout;
use labcore::layout::html::escape;
use labcore::live_math::{Equation, Expr, Form, Quantity};
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
        let mut lead = Writer::new(Target::MathMl, Form::Symbols, quantities);
        // The result's symbol points at what it names too, when a quantity
        // carries the equation's key (rrtstar's r, dls's |e|).
        if quantities.iter().any(|q| q.key == eq.key) {
            lead.expr(&Expr::Var(eq.key), 0);
        } else {
            lead.symbol(eq.symbol);
        }
        lead.put("<mo>=</mo>", "");
        let mut symbols = Writer::new(Target::MathMl, Form::Symbols, quantities);
        symbols.parts(&lead.out, &eq.expr);
        let _ = write!(
            out,
            "<div class=\"equation\" data-equation=\"{i}\" data-key=\"{key}\">\
             <p class=\"equation-caption\">{caption}</p>\
             <p class=\"equation-forms\">\
             {symbols} \
             <span class=\"equation-numbers\" aria-hidden=\"true\">{numbers}</span> \
             <span class=\"equation-result\" aria-hidden=\"true\">{result}</span></p>\
             <p class=\"sr-only equation-text\">{text}</p></div>",
            key = eq.key,
            caption = escape(eq.caption),
            symbols = symbols.out,
        );
    }
    out.push_str("</section>");
    out
}

/// The parts of an equation that change with the run: the substituted form
/// (MathML that may wrap between the terms of its top-level sum), the
/// result (`= ` and the readout's text) and the whole equation as text.
///
/// Where a number the equation reads, or its readout, has no value (no
/// goal yet, ωn with Ki ≠ 0), no numbers are put in: the substituted form
/// is the equation's words saying why ([`Equation::absent`]), the result is
/// empty, and the text is the equation in symbols and those words. A row
/// of numbers ending in `= --` told a student nothing (issue 53 §6).
#[must_use]
pub fn live_parts(
    eq: &Equation,
    quantities: &[Quantity],
    readouts: &[Readout],
) -> (String, String, String) {
    let mut text = Writer::new(Target::Text, Form::Symbols, quantities);
    text.symbol(eq.symbol);
    text.out.push_str(" = ");
    text.expr(&eq.expr, 0);
    let symbols = text.out.len();
    text.out.push_str(" = ");
    text.form = Form::Numbers;
    text.expr(&eq.expr, 0);
    let result = readouts
        .iter()
        .find(|r| r.key == eq.readout)
        .map(|r| r.value.as_str())
        .filter(|v| !text.missing && !v.starts_with("--"));
    match result {
        Some(result) => {
            text.out.push_str(" = ");
            let at = text.out.len() - 2;
            text.out.push_str(result);
            (
                wrapping_mathml(&eq.expr, quantities),
                escape(&text.out[at..]),
                escape(&text.out),
            )
        }
        None => {
            text.out.truncate(symbols);
            text.out.push_str(". ");
            text.out.push_str(eq.absent);
            let mut words = String::from("<span class=\"equation-absent\">");
            words.push_str(&escape(eq.absent));
            words.push_str("</span>");
            (words, String::new(), escape(&text.out))
        }
    }
}

/// The substituted form as MathML that may wrap between the terms of its
/// top-level sum and between the factors of each term's product:
/// `<math>= 1.00</math><wbr><math>· cos 35°</math> <math>+ 0.80</math>…`,
/// each in its own box (a `<math>` element never breaks inside itself).
#[must_use]
pub fn wrapping_mathml(expr: &Expr, quantities: &[Quantity]) -> String {
    let mut w = Writer::new(Target::MathMl, Form::Numbers, quantities);
    w.parts("<mo>=</mo>", expr);
    w.out
}

/// A symbol spec (`θ_1`, `K_p`, `x`) as MathML.
#[must_use]
pub fn symbol_mathml(symbol: &str) -> String {
    let mut w = Writer::new(Target::MathMl, Form::Symbols, &[]);
    w.symbol(symbol);
    w.out
}

/// What a [`Writer`] writes: MathML for the eye or text for the ear.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Target {
    MathMl,
    Text,
}

/// Writes an expression, with symbols or numbers, as MathML or text.
struct Writer<'a> {
    out: String,
    to: Target,
    form: Form,
    quantities: &'a [Quantity],
    /// Writing a term of [`Writer::parts`]: sums (and with numbers,
    /// products) break into boxes.
    flowing: bool,
    /// Term boxes nested in the current term and still open.
    open: usize,
    /// A number put in had no value (and was not hidden).
    missing: bool,
}

impl<'a> Writer<'a> {
    fn new(to: Target, form: Form, quantities: &'a [Quantity]) -> Self {
        Self {
            out: String::new(),
            to,
            form,
            quantities,
            flowing: false,
            open: 0,
            missing: false,
        }
    }

    /// `mathml` or `text`, whichever this writer writes.
    fn put(&mut self, mathml: &str, text: &str) {
        self.out.push_str(match self.to {
            Target::MathMl => mathml,
            Target::Text => text,
        });
    }

    /// A token: `<tag>` in MathML, the bare text otherwise.
    fn token(&mut self, tag: &str, text: &str) {
        match self.to {
            Target::MathMl => {
                let _ = write!(self.out, "<{tag}>{}</{tag}>", escape(text));
            }
            Target::Text => self.out.push_str(text),
        }
    }

    /// The letters of a symbol spec's base or subscript as MathML tokens, in
    /// an `<mrow>` where there are several and `group` asks for one:
    /// - each letter its own `<mi>` (italic, as the Theory's LaTeX writes
    ///   `P_{xx}`), an upper-case Greek letter upright (`Λ`, `Δ`), and a word
    ///   of three or more Latin letters one upright `<mi>` (`max`, `att`);
    /// - a letter with a combining dot or hat (`θ̇`: θ and U+0307, `ẑ`: z
    ///   and U+0302) as the reading pages write `\dot` and `\hat` (labtex's
    ///   `accents::portable`), the one form that Chromium, Firefox and
    ///   WebKit all draw over its letter (as `<mi>θ̇</mi>` Chromium with
    ///   DejaVu Serif drew no dot at all);
    /// - digits an `<mn>`, `∫` and `|` operators, a space a thin space
    ///   (`∫e dt`).
    fn letters(&mut self, text: &str, group: bool) {
        if self.to == Target::Text {
            self.out.push_str(text);
            return;
        }
        let word = text.len() >= 3 && text.bytes().all(|b| b.is_ascii_alphabetic());
        if word || text.bytes().all(|b| b.is_ascii_digit()) {
            let tag = if word { "mi>" } else { "mn>" };
            for part in ["<", tag, text, "</", tag] {
                self.out.push_str(part);
            }
            return;
        }
        let accented = |c: char| matches!(c, '\u{307}' | '\u{302}');
        let group = group && text.chars().filter(|&c| !accented(c)).count() > 1;
        if group {
            self.out.push_str("<mrow>");
        }
        let mut rest = text;
        while let Some(c) = rest.chars().next() {
            let (letter, after) = rest.split_at(c.len_utf8());
            let accent = match after.chars().next() {
                Some('\u{307}') => "\u{2D9}",
                Some('\u{302}') => "^",
                _ => "",
            };
            rest = if accent.is_empty() {
                after
            } else {
                &after[2..]
            };
            let parts = if accent.is_empty() {
                match c {
                    ' ' => ["<mspace width=\"0.1667em\"></mspace>", "", ""],
                    '∫' | '|' => ["<mo stretchy=\"false\">", letter, "</mo>"],
                    'Γ'..='Ω' => ["<mi mathvariant=\"normal\">", letter, "</mi>"],
                    _ => ["<mi>", letter, "</mi>"],
                }
            } else {
                [
                    "<mover accent=\"true\"><mi>",
                    letter,
                    "</mi><mo stretchy=\"true\">",
                ]
            };
            for part in parts {
                self.out.push_str(part);
            }
            if !accent.is_empty() {
                self.out.push_str(accent);
                self.out.push_str("</mo></mover>");
            }
        }
        if group {
            self.out.push_str("</mrow>");
        }
    }

    /// A symbol spec: a base, an optional subscript after `_` and an
    /// optional `²` (`θ_1`, `K_p`, `σ_x²`, `ẑ_φ`), or such a spec between
    /// bars (`|F_att|`, a magnitude).
    fn symbol(&mut self, spec: &str) {
        if let Some(inner) = spec
            .strip_prefix('|')
            .and_then(|s| s.strip_suffix('|'))
            .filter(|s| !s.is_empty())
        {
            self.letters("|", false);
            self.symbol(inner);
            self.letters("|", false);
            return;
        }
        let (spec, squared) = match spec.strip_suffix('²') {
            Some(s) => (s, true),
            None => (spec, false),
        };
        let (base, sub) = match spec.split_once('_') {
            Some((base, sub)) => (base, Some(sub)),
            None => (spec, None),
        };
        let tag = match (sub, squared) {
            (Some(_), true) => "msubsup",
            (Some(_), false) => "msub",
            (None, true) => "msup",
            (None, false) => "",
        };
        let mathml = self.to == Target::MathMl && !tag.is_empty();
        if mathml {
            self.out.push('<');
            self.out.push_str(tag);
            self.out.push('>');
        }
        self.letters(base, !tag.is_empty());
        if let Some(sub) = sub {
            self.letters(sub, true);
        }
        if squared {
            self.put("<mn>2</mn>", "²");
        }
        if mathml {
            self.out.push_str("</");
            self.out.push_str(tag);
            self.out.push('>');
        }
    }

    /// A quantity's number as shown with its unit (`0.4700 m`, `35.0°`,
    /// `0.01009 rad`: the unit the number is in, whatever unit a readout
    /// beside it uses), bracketed inside an operation where it is negative
    /// or missing, raised to a power with its unit (`(0.0950 m/s)²`), or
    /// written in the magnitude form in a product (`(5.3 × 10⁻⁵ rad)`).
    /// `outer` is the binding strength around it ([`precedence`]; 5 for
    /// the base of a power).
    fn number(&mut self, q: &Quantity, outer: u8) {
        let number = q.number_text();
        // "--" (no value) is not a negative number.
        let (negative, digits) = match number.strip_prefix('-') {
            Some(rest) if rest.starts_with(|c: char| c.is_ascii_digit()) => (true, rest),
            _ => (false, number.as_str()),
        };
        self.missing |= !q.hidden && !q.value.is_finite();
        let unit = if q.hidden || !q.value.is_finite() {
            ""
        } else {
            q.unit
        };
        // The degree sign sits on the number; another unit a narrow space
        // after it (a space in the text twin).
        let spaced = !unit.is_empty() && unit != "°";
        let bracket = ((negative || !q.value.is_finite()) && outer > 0)
            || (spaced && outer > 4)
            || (number.contains('×') && outer > 1);
        let (open, close) = if bracket { ("(", ")") } else { ("", "") };
        let minus = if negative { "−" } else { "" };
        let space = match (spaced, self.to) {
            (false, _) => "",
            (true, Target::MathMl) => "\u{202F}",
            (true, Target::Text) => " ",
        };
        // Sign-stable: one `<mn>` holds the number with its sign, unit and
        // brackets, so a value that changes sign (or goes missing) is
        // rewritten in its text node (`dom::rewrite_markup`), not parsed and
        // laid out anew as other elements: 15 of 71 of ekf's equation
        // writes in 4 s were such, 24.6 ms in all. The text sits as TeX sets
        // a unary minus, with no space; the degree sign inside the number,
        // as a trailing `<mo>` Chromium may leave it out at the end of a
        // `<math>`. The numbers are hidden from screen readers (their text
        // twin reads them).
        self.token("mn", &format!("{open}{minus}{digits}{space}{unit}{close}"));
    }

    /// `lead` and `expr` (MathML) as boxes a line may break between: one
    /// for each term of its top-level sum, led by its sign (the first by
    /// `lead`), separated by spaces; with numbers, a term's product also
    /// breaks between its factors, each led by its cross (`<wbr>`, no space).
    /// The sums inside a term break between their terms the same way (see
    /// [`Writer::expr`]), each further term a box nested in the current one;
    /// a fraction, a root's bar, a square and, with symbols, a product
    /// never break.
    ///
    /// A term sits in an `eq-term` box (an inline block no wider than the
    /// line, `style.css`), so a line breaks between a sum's terms first and
    /// inside a term only when the term alone is wider than the line.
    fn parts(&mut self, lead: &str, expr: &Expr) {
        let term = match *expr {
            Expr::Add(a, b) | Expr::Sub(a, b) => {
                self.parts(lead, a);
                self.out.push(' ');
                b
            }
            _ => expr,
        };
        self.out.push_str(TERM_OPEN);
        self.term_lead(expr, lead);
        (self.open, self.flowing) = (0, true);
        self.expr(term, 2);
        self.flowing = false;
        self.out.push_str(PART_CLOSE);
        for _ in 0..=self.open {
            self.out.push_str("</span>");
        }
    }

    /// What leads the last term of `sum` in its box: its sign, spaced as a
    /// binary one (MathML takes an operator that starts a `<math>` for a
    /// prefix sign, set tight; the space between the boxes stands before
    /// it), or `lead` when `sum` is not a sum.
    fn term_lead(&mut self, sum: &Expr, lead: &str) {
        self.out.push_str(match sum {
            Expr::Add(..) => "<mo rspace=\"0.2222em\">+</mo>",
            Expr::Sub(..) => "<mo rspace=\"0.2222em\">−</mo>",
            _ => lead,
        });
    }

    /// A bracket, `tall` around a fraction or a root's bar: then it
    /// stretches to what it holds, the two halves and the content in one
    /// `<mrow>` (the content does not break, [`Writer::flowing`]).
    /// Otherwise it is of one size (`stretchy="false"`): a stretchy bracket
    /// grows to the tallest thing in the row it stands in (cartpole's
    /// `(M + m)` stood twice the height of M beside a ½ and a θ̇, in
    /// Chromium and WebKit), and its two halves may stand in different
    /// boxes ([`Writer::parts`]).
    fn bracket(&mut self, open: bool, tall: bool) {
        let mathml = match (open, tall) {
            (true, false) => "<mo stretchy=\"false\">(</mo>",
            (false, false) => "<mo stretchy=\"false\">)</mo>",
            (true, true) => "<mrow><mo>(</mo>",
            (false, true) => "<mo>)</mo></mrow>",
        };
        self.put(mathml, if open { "(" } else { ")" });
    }

    /// `content` between brackets ([`Writer::bracket`]), bound as `outer`.
    fn bracketed(&mut self, content: &Expr, outer: u8) {
        let tall = self.tall(content);
        let flowing = self.flowing;
        self.flowing &= !tall && !short_sum(content);
        self.bracket(true, tall);
        self.expr(content, outer);
        self.bracket(false, tall);
        self.flowing = flowing;
    }

    /// Whether `expr` is written with a fraction bar or a root's bar in it
    /// (in this writer's form), so that a bracket around it must stretch.
    fn tall(&self, expr: &Expr) -> bool {
        match *expr {
            Expr::Var(_) | Expr::Num(..) => false,
            Expr::Div(a, _) if !self.inline_division(a) => true,
            Expr::Sqrt(_) if self.form == Form::Symbols => true,
            Expr::Add(a, b)
            | Expr::Sub(a, b)
            | Expr::Mul(a, b)
            | Expr::Div(a, b)
            | Expr::Max(a, b)
            | Expr::Min(a, b)
            | Expr::Clamp(a, b) => self.tall(a) || self.tall(b),
            Expr::Neg(a)
            | Expr::Cos(a)
            | Expr::Sin(a)
            | Expr::CosRad(a)
            | Expr::Ln(a)
            | Expr::Sqrt(a)
            | Expr::Sq(a)
            | Expr::Acos(a) => self.tall(a),
        }
    }

    /// Whether a quotient with numerator `a` is written on the line,
    /// `(a) / (b)`, rather than as a fraction: with numbers, when `a` is a
    /// sum, so that it may break between its terms ([`Writer::parts`]): a
    /// fraction never breaks, and a sum of numbers over a fraction bar is
    /// wider than a phone's column (ik's law of cosines).
    fn inline_division(&self, a: &Expr) -> bool {
        self.form == Form::Numbers && matches!(a, Expr::Add(..) | Expr::Sub(..))
    }

    /// `expr`, bracketed when it binds less tightly than `outer` asks.
    ///
    /// While [`Writer::flowing`], a sum closes the open part after each
    /// term but the last and opens a box for the next (nested in the box
    /// open where the sum starts), and with numbers a product opens a part
    /// for each factor, led by its cross.
    fn expr(&mut self, expr: &Expr, outer: u8) {
        let start = self.open;
        let flowing = self.flowing;
        // What MathML nests (a fraction, a root, a square) never breaks; nor
        // does a product of symbols (juxtaposition).
        let symbols = self.form == Form::Symbols;
        self.flowing &= match *expr {
            Expr::Sq(_) => false,
            Expr::Sqrt(_) | Expr::Mul(..) => !symbols,
            Expr::Div(a, _) => self.inline_division(a),
            _ => true,
        };
        let paren = precedence(expr) < outer.min(4);
        let tall = paren && self.tall(expr);
        if tall || (paren && short_sum(expr)) {
            self.flowing = false;
        }
        if paren {
            self.bracket(true, tall);
        }
        match *expr {
            Expr::Var(key) => match self.quantities.iter().find(|q| q.key == key) {
                Some(q) if self.form == Form::Symbols => {
                    // A quantity's symbol points at what it names (issue 27 §3).
                    let live = format!("<mrow data-live=\"{key}\" tabindex=\"0\">");
                    self.put(&live, "");
                    self.symbol(q.symbol);
                    self.put("</mrow>", "");
                }
                Some(q) => self.number(q, outer),
                None => self.token("mi", key),
            },
            Expr::Num(_, text) => self.token("mn", text),
            Expr::Add(a, b) | Expr::Sub(a, b) => {
                self.expr(a, 1);
                if self.flowing {
                    // Closes the previous term's box (and what it nested).
                    self.out.push_str(PART_CLOSE);
                    for _ in start..self.open {
                        self.out.push_str("</span>");
                    }
                    self.out.push(' ');
                    self.out.push_str(TERM_OPEN);
                    self.term_lead(expr, "");
                    self.open = start + 1;
                } else if matches!(expr, Expr::Add(..)) {
                    self.put("<mo>+</mo>", " + ");
                } else {
                    self.put("<mo>−</mo>", " − ");
                }
                self.expr(b, 2);
            }
            Expr::Mul(a, b) => {
                // Symbols multiply by juxtaposition (L₁ cos θ₁), with a thin
                // space before a function's name as TeX sets `l\cos\theta`
                // (MathML puts none: "mlẋθ̇cos θ"). Numbers, which carry
                // their units (`N·s/m`), are multiplied by a cross, as the
                // SI writes a product of numbers.
                self.expr(a, 2);
                if symbols {
                    if matches!(
                        b,
                        Expr::Cos(_) | Expr::Sin(_) | Expr::CosRad(_) | Expr::Ln(_)
                    ) {
                        self.put("<mo>\u{2062}</mo><mspace width=\"0.1667em\"></mspace>", " ");
                    } else {
                        self.put("<mo>\u{2062}</mo>", " ");
                    }
                } else if self.flowing {
                    // A cross that leads its box is a prefix operator to
                    // MathML: the spacing it has between two factors is set
                    // by hand.
                    self.out.push_str(
                        "</math></span><wbr><span class=\"eq-part\"><math>\
                         <mo lspace=\"0.2222em\" rspace=\"0.2222em\">×</mo>",
                    );
                } else {
                    self.put("<mo>×</mo>", " × ");
                }
                self.expr(b, 3);
            }
            Expr::Div(a, b) if self.inline_division(a) => {
                self.bracketed(a, 0);
                self.put("<mo>/</mo>", " / ");
                self.bracketed(b, 0);
            }
            Expr::Div(a, b) => {
                self.put("<mfrac><mrow>", "(");
                self.expr(a, 0);
                self.put("</mrow><mrow>", ") / (");
                self.expr(b, 0);
                self.put("</mrow></mfrac>", ")");
            }
            Expr::Neg(a) => {
                self.put(UNARY_MINUS, "−");
                self.expr(a, 3);
            }
            Expr::Cos(a) | Expr::Sin(a) | Expr::CosRad(a) | Expr::Ln(a) => {
                let name = match expr {
                    Expr::Sin(_) => "sin",
                    Expr::Ln(_) => "ln",
                    _ => "cos",
                };
                self.token("mi", name);
                // A thin space after the name, as TeX sets `\cos\theta`
                // (browsers add none for the function-application operator).
                if precedence(a) >= 4 {
                    self.put("<mo>\u{2061}</mo><mspace width=\"0.1667em\"></mspace>", " ");
                } else {
                    self.put("<mo>\u{2061}</mo>", " ");
                }
                self.expr(a, 4);
            }
            Expr::Sqrt(a) if self.form == Form::Numbers => {
                self.put("<mo>√</mo>", "√");
                self.bracketed(a, 0);
            }
            Expr::Sqrt(a) => {
                self.put("<msqrt>", "√(");
                self.expr(a, 0);
                self.put("</msqrt>", ")");
            }
            Expr::Sq(a) => {
                self.put("<msup><mrow>", "");
                self.expr(a, 5);
                self.put("</mrow><mn>2</mn></msup>", "²");
            }
            Expr::Acos(a) => {
                self.token("mi", "arccos");
                self.put("<mo>\u{2061}</mo>", "");
                self.bracketed(a, 0);
            }
            Expr::Clamp(a, b) | Expr::Max(a, b) | Expr::Min(a, b) => {
                let clamp = matches!(expr, Expr::Clamp(..));
                self.token("mi", function_name(expr));
                let tall = self.tall(expr);
                if tall {
                    self.flowing = false;
                }
                self.bracket(true, tall);
                self.expr(a, 0);
                self.put("<mo separator=\"true\">,</mo>", ", ");
                if clamp {
                    self.put("<mo>±</mo>", "±");
                }
                self.expr(b, if clamp { 4 } else { 0 });
                self.bracket(false, tall);
            }
        }
        if paren {
            self.bracket(false, tall);
        }
        self.flowing = flowing;
    }
}

/// Opens a term's box and its first part (see [`Writer::parts`]).
const TERM_OPEN: &str = "<span class=\"eq-term\"><span class=\"eq-part\"><math>";
/// Closes a part.
const PART_CLOSE: &str = "</math></span>";
/// A sign that makes a number or a factor negative: no space either side,
/// as TeX sets a unary minus. A plain `<mo>` after another token is an
/// infix operator to MathML, spaced as in a − b: "( − 0.16)".
const UNARY_MINUS: &str = "<mo lspace=\"0\" rspace=\"0\">−</mo>";
/// The name of a `clamp`, `max` or `min` (`min` for anything else).
fn function_name(expr: &Expr) -> &'static str {
    match expr {
        Expr::Clamp(..) => "clamp",
        Expr::Max(..) => "max",
        _ => "min",
    }
}

/// Whether `expr` is a sum of two numbers or symbols, which a bracket
/// keeps on one line: `(1.00 kg + 0.10 kg)` broke after its first term.
fn short_sum(expr: &Expr) -> bool {
    let atom = |e: &Expr| matches!(e, Expr::Var(_) | Expr::Num(..));
    matches!(*expr, Expr::Add(a, b) | Expr::Sub(a, b) if atom(a) && atom(b))
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

#[cfg(test)]
mod tests {
    use super::*;

    const L: Expr = Expr::Var("l");
    const T: Expr = Expr::Var("t");
    const X: Expr = Expr::Mul(&L, &Expr::Cos(&T));
    const EQ: Equation = Equation {
        key: "x",
        symbol: "x",
        expr: X,
        readout: "x",
        caption: "Tip x",
        absent: "No arm.",
    };

    /// The `<mover>` of the first accent in `markup`.
    fn first_mover(markup: &str) -> &str {
        let start = markup.find("<mover").expect("an accent");
        let end = start + markup[start..].find("</mover>").expect("closed") + "</mover>".len();
        &markup[start..end]
    }

    #[test]
    fn no_live_symbol_has_a_combining_accent_but_the_dot_and_the_hat() {
        // The panel writes only U+0307 and U+0302 as accents over their
        // letter (`Writer::letters`); another would show as the browser
        // pleases.
        for entry in labcore::registry() {
            let exp = (entry.make)();
            for q in exp.quantities() {
                for c in q.symbol.chars() {
                    assert!(
                        !('\u{300}'..='\u{36F}').contains(&c) || c == '\u{307}' || c == '\u{302}',
                        "{}: {} has the combining mark U+{:04X}",
                        entry.id,
                        q.symbol,
                        u32::from(c)
                    );
                }
            }
        }
    }

    #[test]
    fn a_symbol_with_a_combining_dot_is_its_letter_under_the_reading_pages_dot() {
        // The same MathML the reading pages carry for the LaTeX, built by
        // the converter and made portable (labtex).
        for (symbol, latex) in [("θ̇", r"$\dot{\theta}$"), ("ω̇", r"$\dot{\omega}$")] {
            let page = labtex::render(latex).unwrap();
            let panel = symbol_mathml(symbol);
            assert_eq!(panel, first_mover(&page), "{symbol} against {latex}");
        }
        // With a subscript, the accented letter is the base.
        let subscripted = symbol_mathml("θ̇_k");
        assert!(subscripted.starts_with("<msub><mover accent=\"true\"><mi>θ</mi>"));
        assert!(subscripted.ends_with("</mover><mi>k</mi></msub>"));
        // Precomposed letters, plain letters and the text twin stay as written.
        assert_eq!(symbol_mathml("ẋ"), "<mi>ẋ</mi>");
        assert_eq!(symbol_mathml("θ"), "<mi>θ</mi>");
        let mut text = Writer::new(Target::Text, Form::Symbols, &[]);
        text.symbol("θ̇_k");
        assert_eq!(text.out, "θ̇k");
    }

    fn quantities(t_deg: f64) -> Vec<Quantity> {
        vec![
            Quantity::new("l", "L_1", 1.0, 2, "m"),
            Quantity::new("t", "θ_1", t_deg, 0, "°"),
        ]
    }

    /// Issue 27 §3: each quantity's symbol in the symbolic form is a
    /// focusable `data-live` element naming its key (the numbers are not),
    /// outside anything hidden from assistive technology.
    #[test]
    fn live_the_panel_marks_each_quantity_symbol_with_its_key() {
        let html = panel_html(&[EQ], &quantities(35.0), &[]);
        assert_eq!(
            html.matches("<mrow data-live=\"l\" tabindex=\"0\">")
                .count()
                + html
                    .matches("<mrow data-live=\"t\" tabindex=\"0\">")
                    .count(),
            2,
            "{html}"
        );
        let symbols_at = html.find("data-live").unwrap();
        assert!(!html[..symbols_at].contains("aria-hidden"), "{html}");
        let (numbers, _, text) = live_parts(&EQ, &quantities(35.0), &[]);
        assert!(!numbers.contains("data-live") && !text.contains("data-live"));
    }

    /// Issue 53 §6: each symbol as the Theory's LaTeX writes it — an
    /// italic letter each in `∫e dt` and `Λ_xθ` (a one-token `<mi>∫e</mi>`
    /// set its e upright), a word subscript upright, an upper-case Greek
    /// letter upright, a hat and bars, a square.
    #[test]
    fn a_symbol_is_written_letter_by_letter_as_the_theory_writes_it() {
        assert_eq!(
            symbol_mathml("∫e dt"),
            "<mo stretchy=\"false\">∫</mo><mi>e</mi><mspace width=\"0.1667em\"></mspace><mi>d</mi><mi>t</mi>"
        );
        assert_eq!(
            symbol_mathml("Λ_xθ"),
            "<msub><mi mathvariant=\"normal\">Λ</mi><mrow><mi>x</mi><mi>θ</mi></mrow></msub>"
        );
        assert_eq!(
            symbol_mathml("L_max"),
            "<msub><mi>L</mi><mi>max</mi></msub>"
        );
        assert_eq!(
            symbol_mathml("σ_x²"),
            "<msubsup><mi>σ</mi><mi>x</mi><mn>2</mn></msubsup>"
        );
        assert_eq!(symbol_mathml("σ²"), "<msup><mi>σ</mi><mn>2</mn></msup>");
        assert_eq!(
            symbol_mathml("|F_att|"),
            "<mo stretchy=\"false\">|</mo><msub><mi>F</mi><mi>att</mi></msub><mo stretchy=\"false\">|</mo>"
        );
        assert_eq!(
            symbol_mathml("z\u{302}_φ"),
            "<msub><mover accent=\"true\"><mi>z</mi><mo stretchy=\"true\">^</mo></mover><mi>φ</mi></msub>"
        );
        assert_eq!(
            symbol_mathml("|Δx|"),
            "<mo stretchy=\"false\">|</mo><mi mathvariant=\"normal\">Δ</mi><mi>x</mi><mo stretchy=\"false\">|</mo>"
        );
        // The text twin reads them plainly.
        let mut text = Writer::new(Target::Text, Form::Symbols, &[]);
        text.symbol("σ_x²");
        text.out.push(' ');
        text.symbol("|F_att|");
        assert_eq!(text.out, "σx² |Fatt|");
    }

    /// Issue 53 §6: brackets stretch only around a fraction or a root's
    /// bar, in one `<mrow>` with what they hold; elsewhere they are of one
    /// size, or they grew to the tallest thing in their row (cartpole's
    /// `(M + m)` beside ½ and θ̇, twice M's height).
    #[test]
    fn brackets_stretch_around_a_fraction_only() {
        const SUM: Expr = Expr::Mul(&Expr::Num(0.5, "½"), &Expr::Add(&L, &T));
        let q = quantities(35.0);
        let mut w = Writer::new(Target::MathMl, Form::Symbols, &q);
        w.expr(&SUM, 0);
        assert!(
            w.out.contains("<mo stretchy=\"false\">(</mo>") && !w.out.contains("<mo>(</mo>"),
            "{}",
            w.out
        );
        const ARC: Expr = Expr::Acos(&Expr::Div(&L, &T));
        let mut w = Writer::new(Target::MathMl, Form::Symbols, &q);
        w.expr(&ARC, 0);
        assert!(
            w.out.contains("<mrow><mo>(</mo><mfrac>")
                && w.out.ends_with("</mfrac><mo>)</mo></mrow>"),
            "{}",
            w.out
        );
    }

    /// Issue 53 §6: a thin space stands between a factor and a function's
    /// name, as TeX sets `l\cos\theta` ("mlẋθ̇cos θ" had none).
    #[test]
    fn a_function_after_a_factor_has_a_thin_space_before_its_name() {
        let q = quantities(35.0);
        let mut w = Writer::new(Target::MathMl, Form::Symbols, &q);
        w.expr(&X, 0);
        assert!(
            w.out
                .contains("<mo>\u{2062}</mo><mspace width=\"0.1667em\"></mspace><mi>cos</mi>"),
            "{}",
            w.out
        );
    }

    /// Issue 53 §6: a number raised to a power takes its unit into the
    /// bracket, and one in the magnitude form is bracketed in a product.
    #[test]
    fn a_power_takes_the_unit_with_its_number_and_a_magnitude_is_bracketed() {
        const SQ: Expr = Expr::Sq(&L);
        let speed = [Quantity::new("l", "v", 0.095, 4, "m/s")];
        assert_eq!(text(&SQ, Form::Numbers, &speed), "(0.0950 m/s)²");
        const P: Expr = Expr::Mul(&L, &T);
        let tiny = [
            Quantity::new("l", "K", 3.5, 2, "s⁻¹"),
            Quantity::new("t", "e", 5.3e-5, 3, "rad"),
        ];
        assert_eq!(
            text(&P, Form::Numbers, &tiny),
            "3.50 s⁻¹ × (5.3 × 10⁻⁵ rad)"
        );
    }

    /// Issue 53 §6: where a number the equation reads has no value, or its
    /// readout none, the panel puts no numbers in and no `= --`: the
    /// symbols and the equation's words why.
    #[test]
    fn without_a_value_the_equation_says_why_in_words() {
        let mut q = quantities(35.0);
        q[1].value = f64::NAN;
        let readouts = [Readout::new("x", "Tip X", "0.819 m")];
        let (numbers, result, text) = live_parts(&EQ, &q, &readouts);
        assert_eq!(numbers, "<span class=\"equation-absent\">No arm.</span>");
        assert_eq!(result, "");
        assert_eq!(text, "x = L1 cos θ1. No arm.");
        let none = [Readout::new("x", "Tip X", "--")];
        let (_, result, text) = live_parts(&EQ, &quantities(35.0), &none);
        assert_eq!(
            (result.as_str(), text.as_str()),
            ("", "x = L1 cos θ1. No arm.")
        );
        let html = panel_html(&[EQ], &q, &readouts);
        assert!(!html.contains("--") && html.contains("No arm."), "{html}");
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
            "<mi>x</mi><mo>=</mo><mrow data-live=\"l\" tabindex=\"0\"><msub><mi>L</mi><mn>1</mn></msub></mrow><mo>\u{2062}</mo><mspace width=\"0.1667em\"></mspace><mi>cos</mi>"
        ));
        assert!(html.contains(
            "<span class=\"eq-part\"><math><mo>=</mo><mn>1.00\u{202F}m</mn></math></span><wbr>\
             <span class=\"eq-part\"><math><mo lspace=\"0.2222em\" rspace=\"0.2222em\">×</mo>\
             <mi>cos</mi><mo>\u{2061}</mo><mspace width=\"0.1667em\"></mspace><mn>35°</mn></math></span>"
        ));
        assert!(html.contains("= 0.819 m"));
        assert!(html.contains("x = L1 cos θ1 = 1.00 m × cos 35° = 0.819 m"));
    }

    /// Issue 51 §4: a quantity hidden by an instructor's link (`hide=t`)
    /// reads "hidden" in the substituted form and its text twin, never its
    /// number (nor the number's degree sign).
    #[test]
    fn hidden_means_hidden_in_the_math_panel() {
        let mut q = quantities(35.0);
        q[1].hidden = true;
        let readouts = [Readout::new("x", "Tip X", "0.819 m")];
        let (numbers, _, text) = live_parts(&EQ, &q, &readouts);
        assert_eq!(text, "x = L1 cos θ1 = 1.00 m × cos hidden = 0.819 m");
        assert!(
            numbers.contains("<mn>hidden</mn>") && !numbers.contains("35"),
            "{numbers}"
        );
        assert!(!panel_html(&[EQ], &q, &readouts).contains("35"));
    }

    #[test]
    fn a_product_of_numbers_may_wrap_between_its_factors_and_symbols_between_terms() {
        // 2.0·(−0.25)·2.0 − 2.0: the dots lead their boxes, joined by <wbr>,
        // inside their term's box.
        const P: Expr = Expr::Sub(&Expr::Mul(&Expr::Mul(&L, &T), &L), &L);
        let q = [
            Quantity::new("l", "L", 2.0, 1, ""),
            Quantity::new("t", "e", -0.25, 2, ""),
        ];
        let dot = "<mo lspace=\"0.2222em\" rspace=\"0.2222em\">×</mo>";
        assert_eq!(
            wrapping_mathml(&P, &q),
            format!(
                "<span class=\"eq-term\">\
                 <span class=\"eq-part\"><math><mo>=</mo><mn>2.0</mn></math></span><wbr>\
                 <span class=\"eq-part\"><math>{dot}<mn>(−0.25)</mn></math></span><wbr>\
                 <span class=\"eq-part\"><math>{dot}<mn>2.0</mn></math></span></span> \
                 <span class=\"eq-term\"><span class=\"eq-part\"><math><mo rspace=\"0.2222em\">−</mo><mn>2.0</mn></math></span></span>"
            )
        );
        // Symbols: a box a term, products by juxtaposition inside it.
        let html = panel_html(&[Equation { expr: P, ..EQ }], &q, &[]);
        let symbols =
            &html[html.find("equation-forms").unwrap()..html.find("equation-numbers").unwrap()];
        assert_eq!(symbols.matches("<math>").count(), 2, "{symbols}");
        assert!(
            symbols.contains("<mo>\u{2062}</mo>") && !symbols.contains('·'),
            "{symbols}"
        );
        assert!(
            symbols.contains(
                "</math></span></span> <span class=\"eq-term\"><span class=\"eq-part\"><math><mo rspace=\"0.2222em\">−</mo>"
            ),
            "{symbols}"
        );
    }

    #[test]
    fn the_sums_inside_a_bracket_and_a_max_break_in_boxes_nested_in_their_term() {
        // max(0, 2·L − (L + L + L)) with L = 2.0.
        const R: Expr = Expr::Max(
            &Expr::Num(0.0, "0"),
            &Expr::Sub(
                &Expr::Mul(&Expr::Num(2.0, "2"), &L),
                &Expr::Add(&Expr::Add(&L, &L), &L),
            ),
        );
        let q = [Quantity::new("l", "L", 2.0, 1, "")];
        let dot = "<mo lspace=\"0.2222em\" rspace=\"0.2222em\">×</mo>";
        let (open, close) = (
            "<mo stretchy=\"false\">(</mo>",
            "<mo stretchy=\"false\">)</mo>",
        );
        let part = |m: &str| format!("<span class=\"eq-part\"><math>{m}</math></span>");
        let term = "<span class=\"eq-term\">";
        assert_eq!(
            wrapping_mathml(&R, &q),
            [
                term,
                &part(&format!(
                    "<mo>=</mo><mi>max</mi>{open}<mn>0</mn><mo separator=\"true\">,</mo><mn>2</mn>"
                )),
                "<wbr>",
                &part(&format!("{dot}<mn>2.0</mn>")),
                " ",
                term,
                &part(&format!("<mo rspace=\"0.2222em\">−</mo>{open}<mn>2.0</mn>")),
                " ",
                term,
                &part("<mo rspace=\"0.2222em\">+</mo><mn>2.0</mn>"),
                "</span> ",
                term,
                &part(&format!(
                    "<mo rspace=\"0.2222em\">+</mo><mn>2.0</mn>{close}{close}"
                )),
                "</span></span></span>",
            ]
            .concat()
        );
        // A sum of two numbers in brackets stays on one line.
        const SHORT: Expr = Expr::Mul(&L, &Expr::Add(&L, &L));
        assert_eq!(
            wrapping_mathml(&SHORT, &q),
            [
                term,
                &part("<mo>=</mo><mn>2.0</mn>"),
                "<wbr>",
                &part(&format!(
                    "{dot}{open}<mn>2.0</mn><mo>+</mo><mn>2.0</mn>{close}"
                )),
                "</span>",
            ]
            .concat()
        );
    }

    #[test]
    fn with_numbers_a_root_and_a_sum_over_a_number_are_written_on_the_line_and_break() {
        // √(L² + L²) and (L − L) / (2·L): with symbols a radical and a fraction.
        const ROOT: Expr = Expr::Sqrt(&Expr::Add(&Expr::Sq(&L), &Expr::Sq(&L)));
        const QUOTIENT: Expr = Expr::Div(&Expr::Sub(&L, &L), &Expr::Mul(&Expr::Num(2.0, "2"), &L));
        const RATIO: Expr = Expr::Div(&L, &L);
        let q = [Quantity::new("l", "L", 2.0, 1, "")];
        let root = wrapping_mathml(&ROOT, &q);
        assert!(root.starts_with("<span class=\"eq-term\"><span class=\"eq-part\"><math><mo>=</mo><mo>√</mo><mo stretchy=\"false\">(</mo>"), "{root}");
        assert_eq!(
            root.matches("<span class=\"eq-term\">").count(),
            2,
            "a box a term: {root}"
        );
        assert!(!root.contains("msqrt"), "{root}");
        let quotient = wrapping_mathml(&QUOTIENT, &q);
        assert!(
            quotient.contains(
                "<mo stretchy=\"false\">)</mo><mo>/</mo><mo stretchy=\"false\">(</mo><mn>2</mn>"
            ),
            "{quotient}"
        );
        assert!(!quotient.contains("mfrac"), "{quotient}");
        // A quotient of single numbers stays a fraction, and symbols keep theirs.
        assert!(wrapping_mathml(&RATIO, &q).contains("<mfrac>"));
        let mut symbols = Writer::new(Target::MathMl, Form::Symbols, &q);
        symbols.parts("<mo>=</mo>", &ROOT);
        symbols.parts("<mo>=</mo>", &QUOTIENT);
        assert!(
            symbols.out.contains("<msqrt>") && symbols.out.contains("<mfrac>"),
            "{}",
            symbols.out
        );
    }

    /// Tags out, the text left (`<mo>(</mo><mn>2</mn>` gives `(2`).
    fn tokens(markup: &str) -> String {
        let mut out = String::new();
        let mut in_tag = false;
        for c in markup.chars() {
            match c {
                '<' => in_tag = true,
                '>' => in_tag = false,
                ' ' => {}
                c if !in_tag => out.push(c),
                _ => {}
            }
        }
        out
    }

    /// Every equation of every experiment, split into boxes, is well formed
    /// (spans and `<math>` elements balanced, no span inside a `<math>`) and
    /// says what the equation written whole says.
    #[test]
    fn every_equation_split_into_boxes_is_well_formed_and_says_the_same() {
        for entry in crate::registry() {
            let mut exp = (entry.make)();
            exp.preview();
            let quantities = exp.quantities();
            for (eq, form) in exp
                .equations()
                .iter()
                .flat_map(|eq| [(eq, Form::Numbers), (eq, Form::Symbols)])
            {
                let mut parts = Writer::new(Target::MathMl, form, &quantities);
                parts.parts("<mo>=</mo>", &eq.expr);
                let split = parts.out;
                let mut whole = Writer::new(Target::MathMl, form, &quantities);
                whole.put("<mo>=</mo>", "");
                whole.expr(&eq.expr, 0);
                assert_eq!(
                    tokens(&split),
                    tokens(&whole.out),
                    "{}: {}",
                    entry.id,
                    eq.key
                );
                let (mut spans, mut in_math) = (0i32, false);
                let mut rest = split.as_str();
                while let Some(at) = rest.find('<') {
                    rest = &rest[at..];
                    let tag = &rest[..rest.find('>').unwrap() + 1];
                    match tag {
                        t if t.starts_with("<span") => {
                            assert!(!in_math, "{}: a span inside <math>: {split}", eq.key);
                            spans += 1;
                        }
                        "</span>" => spans -= 1,
                        "<math>" => in_math = true,
                        "</math>" => in_math = false,
                        _ => {}
                    }
                    assert!(spans >= 0, "{}: {split}", eq.key);
                    rest = &rest[tag.len()..];
                }
                assert_eq!((spans, in_math), (0, false), "{}: {split}", eq.key);
            }
        }
    }

    #[test]
    fn a_long_sum_is_written_a_term_to_a_math_element_so_it_can_wrap() {
        const SUM: Expr = Expr::Sub(&Expr::Add(&L, &T), &L);
        assert_eq!(
            wrapping_mathml(&SUM, &quantities(35.0)),
            "<span class=\"eq-term\"><span class=\"eq-part\"><math><mo>=</mo><mn>1.00\u{202F}m</mn></math></span></span> \
             <span class=\"eq-term\"><span class=\"eq-part\"><math><mo rspace=\"0.2222em\">+</mo><mn>35°</mn></math></span></span> \
             <span class=\"eq-term\"><span class=\"eq-part\"><math><mo rspace=\"0.2222em\">−</mo><mn>1.00\u{202F}m</mn></math></span></span>"
        );
    }

    fn text(expr: &Expr, form: Form, q: &[Quantity]) -> String {
        let mut w = Writer::new(Target::Text, form, q);
        w.expr(expr, 0);
        w.out
    }

    #[test]
    fn the_text_twin_writes_symbols_by_juxtaposition_and_numbers_with_crosses_and_units() {
        let q = quantities(35.0);
        assert_eq!(text(&X, Form::Symbols, &q), "L1 cos θ1");
        assert_eq!(text(&X, Form::Numbers, &q), "1.00 m × cos 35°");
        const SUM: Expr = Expr::Cos(&Expr::Add(&T, &T));
        assert_eq!(text(&SUM, Form::Symbols, &q), "cos (θ1 + θ1)");
        const HOLE: Expr = Expr::Max(&Expr::Num(0.0, "0"), &Expr::Sub(&L, &Expr::Num(2.0, "2")));
        assert_eq!(text(&HOLE, Form::Numbers, &q), "max(0, 1.00 m − 2)");
        const HELD: Expr = Expr::Clamp(&X, &L);
        assert_eq!(text(&HELD, Form::Symbols, &q), "clamp(L1 cos θ1, ±L1)");
        let negative = [
            Quantity::new("l", "L", 2.0, 1, ""),
            Quantity::new("t", "e", -0.25, 2, ""),
        ];
        const P: Expr = Expr::Mul(&L, &T);
        assert_eq!(text(&P, Form::Numbers, &negative), "2.0 × (−0.25)");
    }

    #[test]
    fn a_negative_number_takes_a_unary_minus_and_a_missing_one_reads_dashes_in_brackets() {
        const SQ: Expr = Expr::Sq(&T);
        let missing = [Quantity::new("t", "x", f64::NAN, 2, "m")];
        assert_eq!(text(&SQ, Form::Numbers, &missing), "(--)²");
        let mut w = Writer::new(Target::MathMl, Form::Numbers, &missing);
        w.expr(&SQ, 0);
        assert!(!w.out.contains('−'), "{}", w.out);
        assert!(w.out.contains("<mn>(--)</mn>"), "{}", w.out);
        let negative = [Quantity::new("t", "x", -0.5, 2, "m")];
        let mut w = Writer::new(Target::MathMl, Form::Numbers, &negative);
        w.expr(&SQ, 0);
        assert!(w.out.contains("<mn>(−0.50\u{202F}m)</mn>"), "{}", w.out);
        // At the top level, no brackets: the minus leads the number.
        let mut w = Writer::new(Target::MathMl, Form::Numbers, &negative);
        w.expr(&T, 0);
        assert_eq!(w.out, "<mn>−0.50\u{202F}m</mn>");
    }

    /// The tags of an equation's numbers do not depend on the values: a
    /// value that changes sign or goes missing changes texts only, which
    /// the page rewrites in their nodes (`dom::rewrite_markup`).
    #[test]
    fn the_numbers_markup_keeps_its_tags_whatever_the_values_sign() {
        let tags = |html: &str| {
            let mut out = String::new();
            let mut in_tag = false;
            for c in html.chars() {
                if c == '<' {
                    in_tag = true;
                }
                if in_tag {
                    out.push(c);
                }
                if c == '>' {
                    in_tag = false;
                }
            }
            out
        };
        let exprs: [Expr; 4] = [
            Expr::Mul(&L, &T),
            Expr::Sub(&Expr::Mul(&Expr::Mul(&L, &T), &L), &T),
            Expr::Sq(&T),
            Expr::Add(&T, &Expr::Cos(&T)),
        ];
        for expr in &exprs {
            let shapes: Vec<String> = [0.25, -0.25, 0.0, f64::NAN]
                .iter()
                .map(|&t| {
                    let q = [
                        Quantity::new("l", "L", -2.0, 1, ""),
                        Quantity::new("t", "e", t, 2, ""),
                    ];
                    tags(&wrapping_mathml(expr, &q))
                })
                .collect();
            assert!(
                shapes.windows(2).all(|w| w[0] == w[1]),
                "{expr:?}: {shapes:#?}"
            );
        }
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
        let mut w = Writer::new(Target::MathMl, Form::Numbers, &q);
        w.expr(&P, 0);
        assert_eq!(w.out, "<mn>2.0</mn><mo>×</mo><mn>(−0.5)</mn>");
    }

    #[test]
    fn min_ln_and_a_radian_cosine_are_written_like_their_kin() {
        const R: Expr = Expr::Min(
            &Expr::Mul(
                &Expr::Var("g"),
                &Expr::Sqrt(&Expr::Div(&Expr::Ln(&Expr::Var("n")), &Expr::Var("n"))),
            ),
            &Expr::CosRad(&Expr::Var("e")),
        );
        const EQ: Equation = Equation {
            key: "r",
            symbol: "r",
            expr: R,
            readout: "r",
            caption: "",
            absent: "",
        };
        let q = [
            Quantity::new("g", "γ", 11.775, 3, "m"),
            Quantity::new("n", "n", 300.0, 0, ""),
            Quantity::new("e", "e_θ", 0.5, 3, "rad"),
        ];
        let readouts = [Readout::new("r", "r", "0.878 m")];
        let (numbers, _, text) = live_parts(&EQ, &q, &readouts);
        assert_eq!(
            text,
            "r = min(γ √((ln n) / (n)), cos eθ) = min(11.775 m × √((ln 300) / (300)), cos 0.500 rad) = 0.878 m"
        );
        assert!(
            numbers.contains("<mi>min</mi>") && numbers.contains("<mi>ln</mi>"),
            "{numbers}"
        );
        assert!(!numbers.contains('°'), "{numbers}");
    }
}
