//! The report's sheet as bytes: how the experiment's module hands a
//! [`Sheet`] to the report module, which is downloaded only when a student
//! asks for a report (issue 26 §4: optional parts load on demand).
//!
//! The format is private to one build of the lab (both modules come from
//! the same `cargo xtask dist`), so it has no version and no field names:
//! values are written in declaration order. Numbers are little-endian;
//! `f64` and `f32` as their bits, so every value crosses exactly (NaN and
//! signed zeros included); lengths, counts and `usize` as `u32`; a string
//! as its length and UTF-8 bytes; an enum as a one-byte tag. Reading checks
//! every length against what is left and every tag, so a damaged buffer
//! gives an error, never a panic.
//!
//! Writing costs the experiment's module a few kilobytes; reading lives
//! only in the report module (the linker leaves out what a build does not
//! call).

use super::{Moment, ParamRow, QuizSheet, Sheet, StudentSheet};
use crate::experiment::{Phase, Readout, Status, Tone};
use crate::plot::{Axis, Band, Marker, Plot, RefLine, Series, SeriesRole, XWindow};
use crate::quiz::{Prepared, PreparedKind, Response};
use crate::route::AnswerKey;
use crate::scene::{Item, RasterColour, Role, Scene, SegmentLayer, ViewBox};
use crate::table::Table;
use glam::DVec2;

/// Why a buffer could not be read back.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct WireError(pub &'static str);

impl std::fmt::Display for WireError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "the report data is damaged ({})", self.0)
    }
}

/// The bytes being written.
#[derive(Default)]
pub struct Writer {
    pub bytes: Vec<u8>,
}

/// The bytes being read, and where.
pub struct Reader<'a> {
    bytes: &'a [u8],
}

impl Reader<'_> {
    fn take(&mut self, n: usize) -> Result<&[u8], WireError> {
        if n > self.bytes.len() {
            return Err(WireError("ends early"));
        }
        let (head, rest) = self.bytes.split_at(n);
        self.bytes = rest;
        Ok(head)
    }

    fn array<const N: usize>(&mut self) -> Result<[u8; N], WireError> {
        let mut a = [0; N];
        a.copy_from_slice(self.take(N)?);
        Ok(a)
    }

    /// A length or count, checked to be at most what the rest of the buffer
    /// could hold (every element takes at least a byte, except `()`-like
    /// ones no type here has), so a damaged length cannot ask for gigabytes.
    fn len(&mut self) -> Result<usize, WireError> {
        let n = u32::take(self)? as usize;
        if n > self.bytes.len() {
            return Err(WireError("a length is larger than the data"));
        }
        Ok(n)
    }

    fn tag(&mut self) -> Result<u8, WireError> {
        Ok(self.take(1)?[0])
    }
}

/// A value that crosses between the modules.
pub trait Wire: Sized {
    fn put(&self, w: &mut Writer);
    fn take(r: &mut Reader<'_>) -> Result<Self, WireError>;
}

/// `value` as bytes.
#[must_use]
pub fn encode<T: Wire>(value: &T) -> Vec<u8> {
    let mut w = Writer::default();
    value.put(&mut w);
    w.bytes
}

/// The value `bytes` hold, which must be all of them.
pub fn decode<T: Wire>(bytes: &[u8]) -> Result<T, WireError> {
    let mut r = Reader { bytes };
    let value = T::take(&mut r)?;
    if r.bytes.is_empty() {
        Ok(value)
    } else {
        Err(WireError("bytes left over"))
    }
}

macro_rules! number {
    ($($t:ty),*) => {$(
        impl Wire for $t {
            fn put(&self, w: &mut Writer) {
                w.bytes.extend_from_slice(&self.to_le_bytes());
            }
            fn take(r: &mut Reader<'_>) -> Result<Self, WireError> {
                Ok(<$t>::from_le_bytes(r.array()?))
            }
        }
    )*};
}
number!(u32, u64, f32, f64);

impl Wire for usize {
    fn put(&self, w: &mut Writer) {
        (*self as u32).put(w);
    }
    fn take(r: &mut Reader<'_>) -> Result<Self, WireError> {
        Ok(u32::take(r)? as usize)
    }
}

impl Wire for u8 {
    fn put(&self, w: &mut Writer) {
        w.bytes.push(*self);
    }
    fn take(r: &mut Reader<'_>) -> Result<Self, WireError> {
        r.tag()
    }
}

impl Wire for bool {
    fn put(&self, w: &mut Writer) {
        w.bytes.push(u8::from(*self));
    }
    fn take(r: &mut Reader<'_>) -> Result<Self, WireError> {
        match r.tag()? {
            0 => Ok(false),
            1 => Ok(true),
            _ => Err(WireError("a flag is neither 0 nor 1")),
        }
    }
}

/// A string's length, then its UTF-8 bytes.
fn put_str(text: &str, w: &mut Writer) {
    text.len().put(w);
    w.bytes.extend_from_slice(text.as_bytes());
}

impl Wire for String {
    fn put(&self, w: &mut Writer) {
        put_str(self, w);
    }
    fn take(r: &mut Reader<'_>) -> Result<Self, WireError> {
        let n = r.len()?;
        String::from_utf8(r.take(n)?.to_vec()).map_err(|_| WireError("text is not UTF-8"))
    }
}

/// A label the experiment's code names (`&'static str` in labcore's types).
/// Read back it is leaked to live as long: the report module makes a handful
/// of reports in a session, each leaking a few kilobytes of labels.
impl Wire for &'static str {
    fn put(&self, w: &mut Writer) {
        put_str(self, w);
    }
    fn take(r: &mut Reader<'_>) -> Result<Self, WireError> {
        Ok(Box::leak(String::take(r)?.into_boxed_str()))
    }
}

impl<T: Wire> Wire for Vec<T> {
    fn put(&self, w: &mut Writer) {
        self.len().put(w);
        for v in self {
            v.put(w);
        }
    }
    fn take(r: &mut Reader<'_>) -> Result<Self, WireError> {
        let n = r.len()?;
        (0..n).map(|_| T::take(r)).collect()
    }
}

impl<T: Wire> Wire for Option<T> {
    fn put(&self, w: &mut Writer) {
        self.is_some().put(w);
        if let Some(v) = self {
            v.put(w);
        }
    }
    fn take(r: &mut Reader<'_>) -> Result<Self, WireError> {
        Ok(if bool::take(r)? {
            Some(T::take(r)?)
        } else {
            None
        })
    }
}

impl<A: Wire, B: Wire> Wire for (A, B) {
    fn put(&self, w: &mut Writer) {
        self.0.put(w);
        self.1.put(w);
    }
    fn take(r: &mut Reader<'_>) -> Result<Self, WireError> {
        Ok((A::take(r)?, B::take(r)?))
    }
}

impl Wire for DVec2 {
    fn put(&self, w: &mut Writer) {
        self.x.put(w);
        self.y.put(w);
    }
    fn take(r: &mut Reader<'_>) -> Result<Self, WireError> {
        Ok(DVec2::new(f64::take(r)?, f64::take(r)?))
    }
}

/// Fields of a struct, in order: `put` writes them, `take` reads them into
/// the struct literal.
macro_rules! record {
    ($t:ident { $($f:ident),* $(,)? }) => {
        impl Wire for $t {
            fn put(&self, w: &mut Writer) {
                $(self.$f.put(w);)*
            }
            fn take(r: &mut Reader<'_>) -> Result<Self, WireError> {
                Ok($t { $($f: Wire::take(r)?),* })
            }
        }
    };
}

/// A field-less enum as its index in a list of every variant.
macro_rules! unit_enum {
    ($t:ty, $all:expr) => {
        impl Wire for $t {
            fn put(&self, w: &mut Writer) {
                let i = $all.iter().position(|v| v == self).unwrap_or(0);
                (i as u8).put(w);
            }
            fn take(r: &mut Reader<'_>) -> Result<Self, WireError> {
                $all.get(r.tag()? as usize)
                    .copied()
                    .ok_or(WireError("unknown kind"))
            }
        }
    };
}

unit_enum!(Role, Role::ALL);
unit_enum!(SeriesRole, SeriesRole::ALL);
unit_enum!(AnswerKey, AnswerKey::ALL);
unit_enum!(Tone, [Tone::Neutral, Tone::Good, Tone::Warning, Tone::Bad]);
unit_enum!(Phase, [Phase::Live, Phase::Ended]);
unit_enum!(Axis, [Axis::X, Axis::Y]);

record!(ViewBox { min, max });
record!(RasterColour { role, alpha });
record!(Readout { key, label, value });
record!(Status { text, tone, phase });
record!(Table {
    key,
    caption,
    columns,
    rows,
    highlight
});
record!(Series {
    label,
    unit,
    role,
    x,
    y,
    comparison
});
record!(RefLine { axis, value, label });
record!(Band {
    axis,
    lo,
    hi,
    label
});
record!(Marker { x, y, label });
record!(Plot {
    key,
    title,
    x_label,
    x_unit,
    y_label,
    y_unit,
    log_y,
    window,
    series,
    ref_lines,
    bands,
    markers,
    revision,
});
record!(Prepared {
    prompt,
    kind,
    explanation,
    parameterised
});
/// A scene crosses without its quantity tags: they serve the page's
/// highlight of a symbol, which a printed report has no use for.
impl Wire for Scene {
    fn put(&self, w: &mut Writer) {
        self.items.put(w);
        self.backdrop.put(w);
        self.backdrop_key.put(w);
    }
    fn take(r: &mut Reader<'_>) -> Result<Self, WireError> {
        Ok(Scene {
            items: Wire::take(r)?,
            backdrop: Wire::take(r)?,
            backdrop_key: Wire::take(r)?,
            ..Scene::default()
        })
    }
}
record!(ParamRow {
    key,
    label,
    value,
    unit,
    group
});
record!(StudentSheet {
    name,
    group,
    observations
});
record!(QuizSheet {
    seed,
    questions,
    answers,
    submitted
});
record!(Sheet {
    id,
    number,
    title,
    aim,
    link,
    date,
    note,
    student,
    answer_key,
    params,
    extra_state,
    status,
    scene,
    view,
    readouts,
    tables,
    plots,
    quiz,
    marks,
    shown,
});
record!(Moment {
    t_s,
    status,
    scene,
    view,
    readouts,
    points
});

impl Wire for XWindow {
    fn put(&self, w: &mut Writer) {
        match *self {
            XWindow::All => 0u8.put(w),
            XWindow::Rolling(s) => (1u8, s).put(w),
            XWindow::Fixed(a, b) => (2u8, (a, b)).put(w),
        }
    }
    fn take(r: &mut Reader<'_>) -> Result<Self, WireError> {
        Ok(match r.tag()? {
            0 => XWindow::All,
            1 => XWindow::Rolling(Wire::take(r)?),
            2 => XWindow::Fixed(Wire::take(r)?, Wire::take(r)?),
            _ => return Err(WireError("unknown plot window")),
        })
    }
}

impl Wire for PreparedKind {
    fn put(&self, w: &mut Writer) {
        match self {
            PreparedKind::Choice { options, answer } => {
                0u8.put(w);
                options.put(w);
                answer.put(w);
            }
            PreparedKind::Numeric {
                answer,
                tolerance,
                unit,
                angle_degrees,
            } => {
                1u8.put(w);
                answer.put(w);
                tolerance.put(w);
                unit.put(w);
                angle_degrees.put(w);
            }
        }
    }
    fn take(r: &mut Reader<'_>) -> Result<Self, WireError> {
        Ok(match r.tag()? {
            0 => PreparedKind::Choice {
                options: Wire::take(r)?,
                answer: Wire::take(r)?,
            },
            1 => PreparedKind::Numeric {
                answer: Wire::take(r)?,
                tolerance: Wire::take(r)?,
                unit: Wire::take(r)?,
                angle_degrees: Wire::take(r)?,
            },
            _ => return Err(WireError("unknown question kind")),
        })
    }
}

impl Wire for Response {
    fn put(&self, w: &mut Writer) {
        match self {
            Response::Choice(k) => {
                0u8.put(w);
                k.put(w);
            }
            Response::Text(t) => {
                1u8.put(w);
                t.put(w);
            }
        }
    }
    fn take(r: &mut Reader<'_>) -> Result<Self, WireError> {
        Ok(match r.tag()? {
            0 => Response::Choice(Wire::take(r)?),
            1 => Response::Text(Wire::take(r)?),
            _ => return Err(WireError("unknown answer kind")),
        })
    }
}

/// Writes the tag and the listed fields of one display-list item; reads
/// them back into the same variant.
macro_rules! items {
    ($($tag:literal => $v:ident $({ $($f:ident),* })?),* $(,)?) => {
        impl Wire for Item {
            fn put(&self, w: &mut Writer) {
                match self {
                    $(Item::$v $({ $($f),* })? => {
                        ($tag as u8).put(w);
                        $($($f.put(w);)*)?
                    })*
                }
            }
            fn take(r: &mut Reader<'_>) -> Result<Self, WireError> {
                Ok(match r.tag()? {
                    $($tag => Item::$v $({ $($f: Wire::take(r)?),* })?,)*
                    _ => return Err(WireError("unknown scene item")),
                })
            }
        }
    };
}

items! {
    0 => Line { from, to, width_px, role, dashed },
    1 => Circle { center, radius_m, role, fill, dashed },
    2 => Dot { center, radius_px, role },
    3 => Points { points, radius_px, role },
    4 => Heatmap { min, cell_m, cols, rows, values, role },
    5 => Ellipse { center, semi_axis_a, semi_axis_b, role },
    6 => Label { pos, text, role, offset_px },
    7 => Polyline { points, width_px, role, dashed, closed },
    8 => Polygon { points, role },
    9 => Rect { min, max, role, fill },
    10 => Arrow { from, to, width_px, role },
    11 => Arrows { arrows, width_px, role },
    12 => Segments { segments, width_px, role },
    13 => ScaleBar,
    14 => OffView { at, label, role },
    15 => FocusRing { center, radius_px },
    16 => Raster { min, cell_m, cols, rows, cells, palette },
    17 => SegmentLayer { layer, width_px, role },
    18 => VersionedRaster { id, version, min, cell_m, cols, rows, cells, palette },
}

/// A layer crosses as its segments (its identity and journal serve only the
/// page's painter).
impl Wire for SegmentLayer {
    fn put(&self, w: &mut Writer) {
        self.len().put(w);
        for s in self.segments() {
            s.put(w);
        }
    }
    fn take(r: &mut Reader<'_>) -> Result<Self, WireError> {
        Ok(SegmentLayer::from_segments(Wire::take(r)?))
    }
}
