//! The inputs a student makes during a run, as a link carries them (issue
//! 53: a moment after cart-pole's *Nudge pole* or a drag in RRT* had no
//! link). A link of a moment is the run's start (its parameters, `do=`
//! actions) stepped on to the moment; an input on the way is part of that
//! path, so the link names each one with the step it came at:
//! `then=1.20:a:nudge;2.05:p:kp:60;3.00:d:1.5,0.25;3.02:m:1.6,0.25`.
//!
//! Each entry is `time:kind:what`, in the order they came, separated by
//! `;`. The time is the step's, in seconds to 0.01 as `at=` and `marks=`
//! write it (every step reads back as itself: see [`crate::marks`]). The
//! kinds:
//!
//! | kind | what | input |
//! |---|---|---|
//! | `a` | an action's key | a button pressed |
//! | `p` | `key:value` | a parameter set |
//! | `h` | `id:x,y` | a handle moved to a point (keys, typed) |
//! | `d`, `m`, `u` | `x,y` | a pointer pressed, dragged, let go (metres) |
//! | `n` | `dx,dy` | a keyboard nudge of the dragged point (metres) |
//!
//! A pointer kind may carry the keys held after it: `ds` Shift, `dc` Ctrl,
//! `dsc` both. Numbers are written as Rust writes an `f64` (the shortest
//! text that reads back as the same number), so a replay is the live run
//! bit for bit.

use crate::experiment::{Input, Lab, Modifiers};
use crate::marks::time_text;
use crate::route::link_number;
use crate::Clock;
use glam::DVec2;

/// The link key of the inputs during a run.
pub const THEN_KEY: &str = "then";

/// Most inputs a link carries: a long drag is a few hundred pointer moves.
pub const MAX_INPUTS: usize = 2_000;

/// One input made during a run, as a link carries it.
#[derive(Clone, Debug, PartialEq)]
pub enum RunInput {
    /// An action's button pressed (its key).
    Action(String),
    /// A parameter set: its key and the value asked for (before clamping).
    Param(String, f64),
    /// A handle moved to a point (world, metres) by keys or typing.
    Handle(String, DVec2),
    /// A pointer or keyboard input on the canvas (not a hover).
    Pointer(Input, Modifiers),
}

impl RunInput {
    /// Gives the input to `exp` as the page gives it. The result is the
    /// action's or the parameter's (the page shows its message).
    ///
    /// # Errors
    /// What the experiment says of an action or a value it does not take.
    pub fn apply(&self, exp: &mut dyn Lab) -> Result<(), String> {
        match self {
            Self::Action(key) => exp.action(key).map_err(|e| e.to_string()),
            Self::Param(key, value) => exp
                .set_param(key, *value)
                .map(|_| ())
                .map_err(|e| e.to_string()),
            Self::Handle(id, to) => {
                exp.move_handle(id, *to);
                Ok(())
            }
            Self::Pointer(input, modifiers) => {
                exp.input_with(*input, *modifiers);
                Ok(())
            }
        }
    }

    /// Writes the entry's kind and what, as the link writes them (no time),
    /// to `out`. (Pushed piece by piece: the link is written on every
    /// pause, and each `format!` cost the shipped modules bytes.)
    fn write(&self, out: &mut String) {
        let point = |out: &mut String, p: DVec2| {
            out.push_str(&link_number(p.x));
            out.push(',');
            out.push_str(&link_number(p.y));
        };
        match self {
            Self::Action(key) => {
                out.push_str("a:");
                out.push_str(key);
            }
            Self::Param(key, value) => {
                out.push_str("p:");
                out.push_str(key);
                out.push(':');
                out.push_str(&link_number(*value));
            }
            Self::Handle(id, to) => {
                out.push_str("h:");
                out.push_str(id);
                out.push(':');
                point(out, *to);
            }
            Self::Pointer(input, m) => {
                let (kind, p) = match *input {
                    Input::PointerDown(p) => ('d', p),
                    Input::PointerMove { pos, .. } => ('m', pos),
                    Input::PointerUp(p) => ('u', p),
                    Input::Nudge(d) => ('n', d),
                };
                out.push(kind);
                if m.shift {
                    out.push('s');
                }
                if m.ctrl {
                    out.push('c');
                }
                out.push(':');
                point(out, p);
            }
        }
    }

    /// Reads one entry's kind and what ([`RunInput::write`]).
    fn parse(kind: &str, what: &str) -> Option<Self> {
        // A key or an id holds no ':', so the first one ends it.
        let (head, tail) = what.split_once(':').unwrap_or(("", what));
        let key = (!head.is_empty()
            && head.bytes().all(|c| c.is_ascii_alphanumeric() || c == b'_'))
        .then(|| head.to_owned());
        let number = |s: &str| s.parse::<f64>().ok().filter(|v| v.is_finite());
        let point = tail
            .split_once(',')
            .and_then(|(x, y)| Some(DVec2::new(number(x)?, number(y)?)));
        let keys = kind.get(1..).unwrap_or("");
        let modifiers = Modifiers {
            shift: keys.starts_with('s'),
            ctrl: keys.ends_with('c'),
        };
        let keys_read = ["", "s", "c", "sc"].contains(&keys);
        Some(match kind.as_bytes() {
            // An action's key is all of `what`.
            b"a" if what.bytes().all(|c| c.is_ascii_alphanumeric() || c == b'_')
                && !what.is_empty() =>
            {
                Self::Action(what.to_owned())
            }
            b"p" => Self::Param(key?, number(tail)?),
            b"h" => Self::Handle(key?, point?),
            [pointer, ..] if head.is_empty() && keys_read => {
                let p = point?;
                Self::Pointer(
                    match pointer {
                        b'd' => Input::PointerDown(p),
                        b'm' => Input::PointerMove {
                            pos: p,
                            pressed: true,
                        },
                        b'u' => Input::PointerUp(p),
                        b'n' => Input::Nudge(p),
                        _ => return None,
                    },
                    modifiers,
                )
            }
            _ => return None,
        })
    }
}

/// Writes one input with its step (`1.20:a:nudge`) to `out`, after a `;`
/// where `out` holds others: [`link_value`] piece by piece.
pub fn push_entry(out: &mut String, step: u64, input: &RunInput) {
    if !out.is_empty() {
        out.push(';');
    }
    out.push_str(&time_text(step));
    out.push(':');
    input.write(out);
}

/// The link value of `inputs` (step, input), in order: `1.20:a:nudge;…`.
#[must_use]
pub fn link_value(inputs: &[(u64, RunInput)]) -> String {
    let mut out = String::new();
    for (step, input) in inputs {
        push_entry(&mut out, *step, input);
    }
    out
}

/// Reads a link's `then=` value ([`link_value`]): the inputs with their
/// steps, in the order given (the steps never decrease). A value that is
/// not that gives the message to show, and no inputs.
///
/// # Errors
/// The message naming the first entry that cannot be read.
pub fn parse(value: &str) -> Result<Vec<(u64, RunInput)>, String> {
    let value = value.trim();
    let mut inputs: Vec<(u64, RunInput)> = Vec::new();
    if value.is_empty() {
        return Ok(inputs);
    }
    for entry in value.split(';') {
        let last = inputs.last().map_or(0, |(s, _)| *s);
        let read = entry.split_once(':').and_then(|(t, rest)| {
            let t_s = t.parse::<f64>().ok().filter(|t| *t >= 0.0 && *t <= 1e6)?;
            let step = (t_s / Clock::DT_S).round() as u64;
            let (kind, what) = rest.split_once(':')?;
            let input = RunInput::parse(kind, what).filter(|_| step >= last)?;
            Some((step, input))
        });
        match read {
            Some(read) if inputs.len() < MAX_INPUTS => inputs.push(read),
            _ => {
                let shown: String = entry.trim().chars().take(24).collect();
                return Err(format!(
                    "The link's inputs during the run: “{shown}” is not one of at most {MAX_INPUTS} (e.g. then=1.20:a:nudge); the run was opened without them."
                ));
            }
        }
    }
    Ok(inputs)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> Vec<(u64, RunInput)> {
        vec![
            (72, RunInput::Action("nudge".into())),
            (123, RunInput::Param("kp".into(), 60.0)),
            (123, RunInput::Param("kd".into(), -0.1 + 0.2)),
            (
                180,
                RunInput::Pointer(
                    Input::PointerDown(DVec2::new(1.5, 0.25)),
                    Modifiers::default(),
                ),
            ),
            (
                181,
                RunInput::Pointer(
                    Input::PointerMove {
                        pos: DVec2::new(1.0 / 3.0, -2.0e-7),
                        pressed: true,
                    },
                    Modifiers {
                        shift: true,
                        ctrl: false,
                    },
                ),
            ),
            (
                182,
                RunInput::Pointer(
                    Input::PointerUp(DVec2::new(1.6, 0.25)),
                    Modifiers {
                        shift: true,
                        ctrl: true,
                    },
                ),
            ),
            (
                200,
                RunInput::Pointer(
                    Input::Nudge(DVec2::new(0.02, 0.0)),
                    Modifiers {
                        shift: false,
                        ctrl: true,
                    },
                ),
            ),
            (240, RunInput::Handle("w2".into(), DVec2::new(-3.25, 1e-12))),
        ]
    }

    /// Written by hand: the first entries of [`sample`].
    #[test]
    fn a_link_writes_each_input_with_its_time_kind_and_numbers() {
        let text = link_value(&sample()[..4]);
        assert_eq!(
            text,
            "1.20:a:nudge;2.05:p:kp:60;2.05:p:kd:0.1;3.00:d:1.5,0.25"
        );
        let shifted = link_value(&sample()[4..5]);
        assert_eq!(shifted, "3.02:ms:0.3333333333333333,-2e-7");
    }

    #[test]
    fn every_input_reads_back_as_itself_bit_for_bit() {
        let inputs = sample();
        let back = parse(&link_value(&inputs)).unwrap();
        assert_eq!(back, inputs);
        for ((_, a), (_, b)) in back.iter().zip(&inputs) {
            if let (RunInput::Param(_, x), RunInput::Param(_, y)) = (a, b) {
                assert_eq!(x.to_bits(), y.to_bits());
            }
        }
    }

    /// Property: any step up to ten minutes and any finite coordinates
    /// round-trip, seeded.
    #[test]
    fn random_inputs_round_trip() {
        let mut rng = crate::Lcg64::new(53);
        let mut below = |n: u64| rng.next_u64() % n;
        for _ in 0..500 {
            let mut step = 0u64;
            let mut inputs = Vec::new();
            for _ in 0..(below(6) + 1) {
                step += below(200);
                let (x, y) = (
                    below(1 << 40) as f64 / 7.0 - 1e10,
                    (below(1 << 30) as f64 - 5e8) * 1e-15,
                );
                let p = DVec2::new(x, y);
                let m = Modifiers {
                    shift: below(2) == 1,
                    ctrl: below(2) == 1,
                };
                let input = match below(5) {
                    0 => RunInput::Param("w1x".into(), p.x),
                    1 => RunInput::Handle("o3".into(), p),
                    2 => RunInput::Pointer(Input::PointerDown(p), m),
                    3 => RunInput::Pointer(
                        Input::PointerMove {
                            pos: p,
                            pressed: true,
                        },
                        m,
                    ),
                    _ => RunInput::Pointer(Input::PointerUp(p), m),
                };
                inputs.push((step, input));
            }
            assert_eq!(parse(&link_value(&inputs)).unwrap(), inputs);
        }
    }

    #[test]
    fn a_malformed_entry_says_which_and_gives_no_inputs() {
        for bad in [
            "1.20",
            "1.20:a",
            "1.20:a:",
            "x:a:nudge",
            "-1:a:nudge",
            "NaN:a:nudge",
            "1.20:q:1,2",
            "1.20:d:1",
            "1.20:d:1,NaN",
            "1.20:dx:1,2",
            "1.20:p:kp",
            "1.20:p:kp:inf",
            "1.20:h:w1:1",
            "1.20:a:<script>",
            "2.00:a:nudge;1.00:a:nudge",
        ] {
            let err = parse(bad).unwrap_err();
            assert!(
                err.starts_with("The link's inputs during the run: “"),
                "{bad}: {err}"
            );
            assert!(
                err.ends_with("the run was opened without them."),
                "{bad}: {err}"
            );
        }
        let many = vec!["1.00:a:nudge"; MAX_INPUTS + 1].join(";");
        assert!(parse(&many)
            .unwrap_err()
            .contains("“1.00:a:nudge” is not one of at most 2000"));
        assert_eq!(parse(&many[13..]).unwrap().len(), MAX_INPUTS);
        assert_eq!(parse("  ").unwrap(), Vec::new());
    }

    /// The inputs act on the experiment as the page's own do: cart-pole's
    /// Nudge, a parameter, an unknown key's message.
    #[test]
    fn an_input_acts_on_the_experiment() {
        let mut lab = (crate::find("pid").expect("pid").make)();
        RunInput::Param("kp".into(), 42.0)
            .apply(lab.as_mut())
            .unwrap();
        assert_eq!(lab.param("kp"), Some(42.0));
        assert!(RunInput::Action("no_such".into())
            .apply(lab.as_mut())
            .is_err());
        assert!(RunInput::Param("no_such".into(), 1.0)
            .apply(lab.as_mut())
            .is_err());
    }
}
