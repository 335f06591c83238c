//! labweb — the browser front end.
