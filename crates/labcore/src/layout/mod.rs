//! Layout and text that every painter of the lab shares: the canvas
//! (`labweb`), the report's SVG (`labpage`) and the thumbnails (`xtask`).
//!
//! Pure functions, one concern per file, so a scale bar, a tick label or an
//! arrow head reads the same wherever a student sees it (issue 54 §1).

pub mod arrow;
pub mod html;
pub mod map;
pub mod page_colours;
pub mod scale_bar;
pub mod ticks;
